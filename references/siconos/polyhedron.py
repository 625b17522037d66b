#!/usr/bin/python3
"""The grid polyhedra of both Table 1 bodies run by Siconos on the scenes gomboc runs (docs/siconos.md).

Three comparisons, each at three Moreau-Jean steps so that Siconos's own convergence gives the tolerance:
  still    cases/siconos/still-gomboc-{I,II}.ini: released tilted from rest on a still plane, plastic,
           rough (mu = 10, more than any friction the gomboc run needs), damping c = 3: every change of
           carrying vertex, the kinetic energy after it, the time on one and two points, the rest face and
           when it is reached. Steps 2e-4, 1e-4, 5e-5 s, until rest or the scene's end.
  coulomb  the same scenes on a plane of Coulomb friction mu = 0.6, the first 3 s, the same steps.
  table1   cases/siconos/table1-gomboc-{I,II}.ini (Table 1's plane, amplitudes in m/s2, c = 0.02, tilted
           0.3 rad) for 6 periods: the sequence of carrying vertices until the runs part. Steps T/800 ... T/3200.
  ensemble the same Table 1 scenes from 8 attitudes each (axis-angle, drawn from SEED), 6 periods at
           T/1600: impacts per period, energy lost per period, time fractions on 0, 1, 2 and 3 points.

An event is a hull vertex starting to carry the body (a positive normal impulse in a step after a step
without one), unless it carried it (or stood on the plane at the start) within one step of gomboc's
integrator before (T/160 = 2.2 ms): Moreau-Jean lets a held vertex leave and return within a few steps
(chatter), where gomboc's settle rule holds a point whose return is shorter than its step.
The energy the impacts and friction take in a step is the mechanical energy's fall minus the work of
the damping torque and of the changing weight: E = KE + m g_eff(t) z_c in the plane's frame, dE/dt =
m g_eff'(t) z_c - c |omega|^2 away from impacts (midpoint sums, first order like the scheme).

Run by `make references` where Siconos is installed (two processes); the output (JSON, on stdout) is
committed as references/siconos/polyhedron.json and read by verify/siconos.c and the report.
"""
import math
import multiprocessing
import os
import sys
import tempfile

import numpy

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from provenance import emit, versions  # noqa: E402

import siconos  # noqa: E402
import engine  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GOMBOC = os.environ.get("GOMBOC", os.path.join(ROOT, "build", "gomboc"))
SEED, MEMBERS = 20261127, 8
STILL_STEPS = (2e-4, 1e-4, 5e-5)
COULOMB_STEPS, COULOMB_SECONDS, COULOMB_MU = (2e-4, 1e-4, 5e-5), 3.0, 0.6
TABLE1_DIVISIONS, TABLE1_PERIODS, ENSEMBLE_DIVISION = (800, 1600, 3200), 6, 1600


def events(record, chatter_time):
    """The record's carrying events with chatter re-entries dropped (see the module's text)."""
    out, last_carried = [], {v: 0.0 for v in record["initial"]}
    for e in record["events"]:
        before = last_carried.get(e["vertex"])
        if before is None or e["t"] - before > chatter_time:
            out.append(e)
        last_carried[e["vertex"]] = e["t"]
    return out


def chatter_time(scene):
    """One step of gomboc's integrator in the scene (the time within which its settle rule holds a return)."""
    return 2.0 * math.pi / scene["omega"] / scene["steps_per_period"]


def finite(x):
    """x, or None (JSON null) where a solve failed (no NaN or infinity in the reference)."""
    return x if x is not None and math.isfinite(x) else None


def summarise(record, scene, body):
    """What the comparisons read, from a run's step record."""
    h = record["h"]
    carry = numpy.array(record["carry"])
    moving = carry if record["rest_time"] is None else carry[: round(record["rest_time"] / h)]
    fractions = {str(n): float(numpy.mean(moving == n)) if len(moving) else 0.0 for n in (0, 1, 2)}
    fractions["3"] = float(numpy.mean(moving >= 3)) if len(moving) else 0.0
    kept = events(record, chatter_time(scene))
    out = {"h": h, "steps": record["steps"], "seconds": record["seconds"], "error": record["error"],
           "events": [{"t": e["t"], "vertex": e["vertex"], "kinetic_after": e["kinetic_after"]} for e in kept],
           "raw_events": len(record["events"]), "carry_fractions_until_rest": fractions,
           "rest_time": record["rest_time"], "rest_face": record["rest_face"],
           "final_quaternion": record["final_quaternion"], "residual_max": finite(record["residual_max"]),
           "residual_over": record["residual_over"], "rest_residual": finite(record["rest_residual"]),
           "solver_warnings": record["solver_warnings"]}
    if "lost" in record:
        span = record["steps"] * h / (2.0 * math.pi / scene["omega"])
        out["impacts_per_period"] = len(kept) / span
        out["energy_lost_per_period"] = record["lost"] / span
    return out


def run(job):
    kind, case, h, t_end, attitude, friction = job
    scene = engine.read_scene(os.path.join(ROOT, case))
    if friction is not None:
        scene["friction"] = friction
    body = engine.read_body(GOMBOC, scene)
    R = None if attitude is None else engine.rotation(numpy.array(attitude[:3]) / numpy.linalg.norm(attitude[:3]), attitude[3])
    # Siconos prints a line on standard output for each step whose friction-contact problem missed its
    # tolerance: kept away from the JSON and counted.
    sys.stdout.flush()
    saved = os.dup(1)
    with tempfile.TemporaryFile(mode="w+") as printed:
        os.dup2(printed.fileno(), 1)
        try:
            record = engine.simulate(scene, body, h, t_end, attitude=R, stop_at_rest=kind in ("still", "coulomb"),
                                     ledger=kind == "ensemble")
        finally:
            sys.stdout.flush()
            os.dup2(saved, 1)
            os.close(saved)
        printed.seek(0)
        warnings = sum("solver warning" in line for line in printed)
    record["solver_warnings"] = warnings
    return {"kind": kind, "case": case, "friction": scene["friction"], "attitude": attitude,
            "t_end": t_end, **summarise(record, scene, body)}


def jobs():
    out = []
    for b in ("I", "II"):
        still = "cases/siconos/still-gomboc-%s.ini" % b
        scene = engine.read_scene(os.path.join(ROOT, still))
        t_still = scene["periods"] * 2.0 * math.pi / scene["omega"]
        out += [("still", still, h, t_still, None, None) for h in STILL_STEPS]
        out += [("coulomb", still, h, COULOMB_SECONDS, None, repr(COULOMB_MU)) for h in COULOMB_STEPS]
        table1 = "cases/siconos/table1-gomboc-%s.ini" % b
        scene = engine.read_scene(os.path.join(ROOT, table1))
        T = 2.0 * math.pi / scene["omega"]
        out += [("table1", table1, T / n, TABLE1_PERIODS * T, None, None) for n in TABLE1_DIVISIONS]
        rng = numpy.random.default_rng(SEED + (b == "II"))
        for _ in range(MEMBERS):
            axis = rng.normal(size=3)
            attitude = [*(axis / numpy.linalg.norm(axis)).tolist(), float(rng.uniform(0.0, math.pi))]
            out.append(("ensemble", table1, T / ENSEMBLE_DIVISION, TABLE1_PERIODS * T, attitude, None))
    return sorted(out, key=lambda j: -j[3] / j[2])   # longest first: two processes finish together


def main():
    with multiprocessing.Pool(int(os.environ.get("SICONOS_PROCESSES", "2"))) as pool:
        runs = pool.map(run, jobs(), chunksize=1)
    order = {"still": 0, "coulomb": 1, "table1": 2, "ensemble": 3}
    runs.sort(key=lambda r: (order[r["kind"]], r["case"], -r["h"], str(r["attitude"])))
    emit({"what": "the grid polyhedra of Table 1's bodies in Siconos (exact vertex-plane relations, Moreau-Jean, "
                  "NSGS friction contact): carrying events, rest, time on one and two points, ensemble statistics",
          "versions": dict(versions(), siconos=str(siconos.version)),
          "chatter": "a return within one step of gomboc's integrator (T/steps_per_period) is not an event", "seed": SEED, "active_on": engine.ACTIVE_ON, "active_off": engine.ACTIVE_OFF,
          "solver_tolerance": engine.SOLVER_TOL, "cases": runs})


if __name__ == "__main__":
    main()
