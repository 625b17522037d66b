"""make bench: the compliant law's work against precision as its stiffness grows, stepper by stepper.

Two scenes of docs/compliant.md, each at k = 1e3, 1e5, 1e7 and 1e9:
- bounce: the unit sphere dropped from 0.1 m (n = 1.5, Hunt and Crossley's x = 0.5, frictionless in effect:
  it falls straight), 0.3 s; the error is that of the energy left after the bounce [J];
- rocking: Housner's block (cases/bodies/housner-block.off) released tilted 0.1 rad (n = 1, alpha = 2 s/m,
  mu = 1, slip speed 1e-4 m/s, its four vertices pushed), 0.2 s (rocking on its edge, before its face lands); the error is the largest of the final
  centroid height's [m] and the final tilt's times the block's half height.
Each run's error is against rk8pd at rtol 1e-12 for the same k (the model's own solution); its cost is the
whole process (best of 2 wall times) and its right-hand-side evaluations. The steppers: rk4 at three step
sizes, rkf45, rk8pd, and the implicit rk4imp, bsimp and msbdf (central-difference Jacobian) at rtol 1e-5, 1e-7,
1e-9. Prints a table and, for each scene and k, the cheapest run of each stepper within 1e-6 of the reference;
writes a JSON of every run. Nothing is asserted: a run that fails (a step too large for the stiffness) is
recorded as failed.

    python3 verify/bench/compliant.py GOMBOC OUT.json
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
STIFFNESSES = (1e3, 1e5, 1e7, 1e9)
TOLERANCES = (1e-5, 1e-7, 1e-9)
ADAPTIVE = ("rkf45", "rk8pd", "rk4imp", "bsimp", "msbdf")
RK4_STEPS = (2000, 20000, 200000)  # a period is 1 s
TARGET = 1e-6

SCENES = {
    "bounce": {
        "body": "[body]\nmorphology = I\nbeta = 0\n",
        "model": "contact = continuous\nfriction = 0.5\nexponent = 1.5\ndissipation = {alpha}\n",
        "initial": "[initial]\nheight = 0.1\n",
        "periods": 0.3,
    },
    "rocking": {
        "body": "[body]\nmesh = {mesh}\nmass = 1\n",
        "model": "contact = fast-grid\nfriction = 1\nexponent = 1\ndissipation = 2\nslip_speed = 1e-4\n",
        "initial": "[initial]\nattitude = axis-angle 0,1,0,0.1\n",
        "periods": 0.2,
    },
}


def scene_text(name, k, method, rtol=None, steps=None):
    s = SCENES[name]
    alpha = 0.5 / (1.5 * math.sqrt(2 * 9.81 * 0.1))
    mesh = os.path.join(ROOT, "cases", "bodies", "housner-block.off")
    integrator = f"method = {method}\n"
    if method == "rk4":
        integrator += f"steps_per_period = {steps}\n"
    else:
        integrator += f"steps_per_period = 200\nrtol = {rtol:g}\natol = {rtol * 1e-3:g}\n"
    return (s["body"].format(mesh=mesh)
            + "[forcing]\ng = 9.81\nA1 = 0\nA2 = 0\nomega = 6.283185307179586\n"
            + "[model]\ndamping = 0\ncontact_law = compliant\n" + f"stiffness = {k:g}\n"
            + s["model"].format(alpha=repr(alpha))
            + "[integrator]\n" + integrator + f"periods = {s['periods']}\nlocate_switches = yes\n"
            + s["initial"] + "[output]\nhistory = yes\nsample_every = 1\n")


def run(gomboc, directory, name, text):
    path = os.path.join(directory, "s.ini")
    with open(path, "w", encoding="ascii") as f:
        f.write(text)
    best, document = math.inf, None
    for _ in range(2):
        start = time.perf_counter()
        done = subprocess.run([gomboc, "run", path, "--out", directory, "--json"], capture_output=True, text=True)
        best = min(best, time.perf_counter() - start)
        if done.returncode:
            return {"failed": done.stderr.strip().splitlines()[-1] if done.stderr.strip() else f"exit {done.returncode}"}
        document = json.loads(done.stdout)
    with open(os.path.join(directory, "s-history.csv"), encoding="ascii") as f:
        last = list(csv.DictReader(f))[-1]
    w, x, y, z = (float(last[c]) for c in ("q_w", "q_x", "q_y", "q_z"))
    tilt = math.asin(min(1.0, math.hypot(2 * (x * z - w * y), 2 * (y * z + w * x))))
    return {"seconds": best, "rhs_evaluations": document["rhs_evaluations"], "steps": document["steps"],
            "energy": float(last["E"]), "zeta": float(last["zeta"]), "tilt": tilt,
            "ledger": document["energy_residual_max"]}


def error_of(name, r, ref):
    if name == "bounce":
        return abs(r["energy"] - ref["energy"])
    return max(abs(r["zeta"] - ref["zeta"]), 0.4 * abs(r["tilt"] - ref["tilt"]))


def main(gomboc, out):
    rows = []
    with tempfile.TemporaryDirectory() as d:
        for name in SCENES:
            for k in STIFFNESSES:
                ref = run(gomboc, d, name, scene_text(name, k, "rk8pd", rtol=1e-12))
                if "failed" in ref:
                    print(f"bench: compliant {name} k = {k:g}: the reference failed: {ref['failed']}")
                    continue
                runs = [("rk4", None, s) for s in RK4_STEPS] + [(m, t, None) for m in ADAPTIVE for t in TOLERANCES]
                for method, rtol, steps in runs:
                    r = run(gomboc, d, name, scene_text(name, k, method, rtol=rtol, steps=steps))
                    r.update({"scene": name, "stiffness": k, "method": method, "rtol": rtol, "steps_per_period": steps})
                    if "failed" not in r:
                        r["error"] = error_of(name, r, ref)
                    rows.append(r)
                    setting = f"rtol {rtol:g}" if rtol else f"{steps} steps/s"
                    if "failed" in r:
                        print(f"bench: compliant {name:7s} k = {k:7.0e} {method:6s} {setting:16s} failed: {r['failed'][:90]}")
                    else:
                        print(f"bench: compliant {name:7s} k = {k:7.0e} {method:6s} {setting:16s} error {r['error']:9.2e} "
                              f"{r['rhs_evaluations']:9d} evaluations {r['seconds']:7.3f} s")
    print(f"bench: compliant, the cheapest run of each stepper within {TARGET:g} of the reference (whole process):")
    summary = []
    for name in SCENES:
        for k in STIFFNESSES:
            line = []
            for method in ("rk4",) + ADAPTIVE:
                good = [r for r in rows if r["scene"] == name and r["stiffness"] == k and r["method"] == method
                        and "error" in r and r["error"] <= TARGET]
                best = min(good, key=lambda r: r["seconds"]) if good else None
                summary.append({"scene": name, "stiffness": k, "method": method,
                                "seconds": best["seconds"] if best else None,
                                "rhs_evaluations": best["rhs_evaluations"] if best else None})
                line.append(f"{method} {best['seconds']:.3f} s" if best else f"{method} -")
            print(f"bench:   {name:7s} k = {k:7.0e}: " + ", ".join(line))
    with open(out + ".tmp", "w", encoding="utf-8") as f:
        json.dump({"target": TARGET, "runs": rows, "cheapest": summary}, f, indent=1)
    os.replace(out + ".tmp", out)
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-1].strip())
    sys.exit(main(sys.argv[1], sys.argv[2]))
