#!/usr/bin/python3
"""make bench: gomboc against Siconos, the engine a user would pick instead, on the same polyhedron scene.

The scene: cases/siconos/still-gomboc-I.ini (Gomboc I's grid polyhedron released tilted on a still plane,
plastic, rough), its first 6 periods (2.09 s). The error of a run: the largest |t_i - t_i*| over its first
K events (a vertex starting to carry the body), t* from gomboc at 1280 steps a period (its own change
from 640 is printed: it must be far below every error compared); a run whose first K vertices are not
the reference's has no error (its sequence differs). The cost: gomboc's whole process (`gomboc run`, the
hull read from its file as a user's later runs do, best of 3), Siconos's time-stepping loop alone (CPU,
the body and the Python start-up not counted). The ratio at equal error: for each Siconos run, its time
over the time of gomboc's cheapest run whose error is no larger.

Usage: siconos.py GOMBOC OUT.json   (run by `make bench` where Siconos is installed)
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "references", "siconos"))
import engine  # noqa: E402
import polyhedron  # noqa: E402

CASE = os.path.join(ROOT, "cases", "siconos", "still-gomboc-I.ini")
PERIODS, K = 6, 20
GOMBOC_STEPS = (10, 20, 40, 80, 160)
SICONOS_STEPS = (1e-3, 5e-4, 2.5e-4, 1.25e-4)


def gomboc_case(text, steps, directory):
    lines = []
    for line in text.splitlines():
        key = line.split("=")[0].strip()
        if key == "steps_per_period":
            line = "steps_per_period = %d" % steps
        elif key == "periods":
            line = "periods = %d" % PERIODS
        elif key == "history":
            line = "history = no"
        lines.append(line)
    path = os.path.join(directory, "still-%d.ini" % steps)
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    return path


def gomboc_run(gomboc, text, steps, directory, nodes):
    path = gomboc_case(text, steps, directory)
    best = math.inf
    for _ in range(3):
        start = time.perf_counter()
        subprocess.run([gomboc, "run", path, "--out", directory, "--hull", os.path.join(directory, "I.hull")], check=True,
                       capture_output=True)
        best = min(best, time.perf_counter() - start)
    events = []
    with open(path[:-4] + "-impacts.csv", encoding="utf-8") as f:
        for row in csv.DictReader(f):
            if row["kind"] in ("lift", "lift-off", "crease-end"):
                continue
            point = numpy.array([float(row["new_x"]), float(row["new_y"]), float(row["new_z"])])
            events.append((float(row["t"]), int(numpy.argmin(numpy.linalg.norm(nodes - point, axis=1)))))
    return events, best


def error(events, reference):
    if len(events) < K or [v for _, v in events[:K]] != [v for _, v in reference[:K]]:
        return math.nan
    return max(abs(a[0] - b[0]) for a, b in zip(events[:K], reference[:K]))


def main():
    gomboc, out_path = sys.argv[1], sys.argv[2]
    with open(CASE, encoding="utf-8") as f:
        text = f.read()
    scene = engine.read_scene(CASE)
    body = engine.read_body(gomboc, scene)
    nodes = body["nodes"]
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        reference, _ = gomboc_run(gomboc, text, 1280, scratch, nodes)
        previous, _ = gomboc_run(gomboc, text, 640, scratch, nodes)
        self_change = error(previous, reference)
        for steps in GOMBOC_STEPS:
            events, seconds = gomboc_run(gomboc, text, steps, scratch, nodes)
            rows.append({"engine": "gomboc", "setting": "%d steps/T" % steps, "error": error(events, reference),
                         "seconds": seconds})
    t_end = PERIODS * 2.0 * math.pi / scene["omega"]
    for h in SICONOS_STEPS:
        record = engine.simulate(scene, body, h, t_end, stop_at_rest=False)
        events = [(e["t"], e["vertex"]) for e in polyhedron.events(record, polyhedron.chatter_time(scene))]
        rows.append({"engine": "siconos", "setting": "h = %g s" % h, "error": error(events, reference),
                     "seconds": record["wall"]})
    print("\nbench: gomboc against Siconos on Gomboc I's grid polyhedron released on a still plane (%d periods; error: the "
          "first %d event times against gomboc at 1280 steps/T, whose change from 640 is %.2g s)\n" % (PERIODS, K, self_change))
    print("%-8s %-16s %12s %10s" % ("engine", "setting", "error [s]", "seconds"))
    for r in rows:
        print("%-8s %-16s %12s %10.4f" % (r["engine"], r["setting"], "differs" if math.isnan(r["error"]) else "%.3g" % r["error"],
                                          r["seconds"]))
    ratios = []
    ours = [r for r in rows if r["engine"] == "gomboc" and not math.isnan(r["error"])]
    for r in rows:
        if r["engine"] != "siconos" or math.isnan(r["error"]):
            continue
        good = [g for g in ours if g["error"] <= r["error"]]
        if good:
            cheapest = min(good, key=lambda g: g["seconds"])
            ratios.append({"siconos": r["setting"], "siconos_error": r["error"], "gomboc": cheapest["setting"],
                           "gomboc_error": cheapest["error"], "ratio": r["seconds"] / cheapest["seconds"]})
    print()
    for q in ratios:
        print("at Siconos's %s (error %.3g s): gomboc %s (error %.3g s) is %.0fx faster" % (
            q["siconos"], q["siconos_error"], q["gomboc"], q["gomboc_error"], q["ratio"]))
    worst = min((q["ratio"] for q in ratios), default=math.nan)
    print("worst ratio at equal error: %.0fx (goal: >= 100x)" % worst)
    document = {"rows": rows, "ratios": ratios, "worst_ratio": worst, "reference_self_change": self_change, "k": K,
                "periods": PERIODS, "siconos": str(__import__("siconos").version)}
    with open(out_path + ".tmp", "w", encoding="utf-8") as f:
        json.dump(document, f, indent=1, allow_nan=True)
    os.replace(out_path + ".tmp", out_path)
    return 0 if worst >= 100.0 else 1


if __name__ == "__main__":
    sys.exit(main())
