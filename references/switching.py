#!/usr/bin/python3
"""Reference trajectories of the continuous-contact rolling model across branch switches (eqs 38-39),
over the first PERIODS forcing periods of both Table 1 bodies.

The model is references/dynamics.py's (sympy derivatives of h, Newton continuation of the contact, eq 72
for the contact's rate, the rolling equation of docs/rolling.md, I_C from references/massprops.json);
what this script adds is an independent treatment of switching, unlike gomboc's in every part:
- the solution advances by scipy DOP853 (rtol 1e-12, atol 1e-14, dense output) over one nominal step
  (T/160) at a time;
- after each step the global minimum is searched afresh: h on a 180 x 360 grid, every discrete local
  minimum polished by Newton (gomboc proves its contact global with an interval certificate instead);
- when a minimum lower than the continued branch (by more than 1e-12) exists at the step's end, the time
  inside the step where the two branches are equally low is found by scipy's brentq on the dense output
  (gomboc uses the Illinois method on RK4 sub-steps), the solution is cut there and continued on the other
  branch.
Output: the state at every period end and the switch times, with provenance.

For make bench's work-precision diagram the stepper and its tolerance can be chosen
(SWITCHING_METHOD = DOP853 or Radau, SWITCHING_RTOL, atol = rtol / 100), and SWITCHING_FINAL=1 prints
only the state at the last period's end, the switches and the seconds the integration took (the
model's set-up, sympy's derivation and lambdify, not counted).
"""
import json
import math
import os
import sys
import time

import numpy
import sympy
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from dynamics import BETA, OMEGA, Body, initial_contact, rotation  # noqa: E402
from provenance import emit, versions  # noqa: E402

PERIODS, STEPS = int(os.environ.get("SWITCHING_PERIODS", 20)), 160
METHOD = os.environ.get("SWITCHING_METHOD", "DOP853")
RTOL = float(os.environ.get("SWITCHING_RTOL", 1e-12))
ATOL = RTOL / 100
SWITCH_MARGIN = 1e-12  # a minimum counts as lower when it is lower by more than this (gomboc's eta)
PHIS = (numpy.arange(180) + 0.5) * math.pi / 180
THETAS = numpy.arange(360) * 2 * math.pi / 360
P, T = numpy.meshgrid(PHIS, THETAS, indexing="ij")


def vertical(y):
    return rotation(y[:4])[2, :]


def newton_from(body, start, zb):
    """The local minimum of h reached by Newton from `start` (phi, theta), or None."""
    saved = body.contact
    body.contact = start
    try:
        q, _ = body.find_contact(zb)
        return (float(q[0]), float(q[1])), float(body.h(q[0], q[1], BETA, *zb))
    except (RuntimeError, numpy.linalg.LinAlgError):
        return None
    finally:
        body.contact = saved


def lowest_other(body, zb, current):
    """The lowest local minimum other than `current` (by the grid scan and Newton), or None."""
    values = body.h(P, T, BETA, *zb)
    mask = numpy.ones(values.shape, dtype=bool)
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            if di == dj == 0:
                continue
            shifted = numpy.roll(numpy.roll(values, -di, axis=0), -dj, axis=1)  # theta wraps, phi does not
            if di == -1:
                shifted[0, :] = numpy.inf
            if di == 1:
                shifted[-1, :] = numpy.inf
            mask &= values <= shifted
    xc = numpy.array(body.position_derivatives(*current)[0])
    best = None
    for i, j in zip(*numpy.nonzero(mask)):
        found = newton_from(body, (float(PHIS[i]), float(THETAS[j])), zb)
        if found is None:
            continue
        point, height = found
        if numpy.linalg.norm(numpy.array(body.position_derivatives(*point)[0]) - xc) < 1e-6:
            continue
        if best is None or height < best[1]:
            best = (point, height)
    return best


def run(body, y0):
    period = 2 * math.pi / OMEGA
    h = period / STEPS
    y, t = y0.copy(), 0.0
    states, switches = [], []
    for n in range(PERIODS * STEPS):
        t_end = (n + 1) * h
        while True:
            start_contact = body.contact
            sol = solve_ivp(body.rhs, (t, t_end), y, method=METHOD, rtol=RTOL, atol=ATOL, dense_output=True,
                            first_step=(t_end - t) / 4, max_step=period / 100)
            if not sol.success:
                raise RuntimeError(sol.message)
            y_end = sol.y[:, -1]
            current, h_current = newton_from(body, body.contact, vertical(y_end))
            other = lowest_other(body, vertical(y_end), current)
            if other is None or other[1] >= h_current - SWITCH_MARGIN:
                y, t = y_end, t_end
                body.contact = current
                break
            # A lower branch at the step's end: where inside the step are the two equally low?
            def gap(s):
                zb = vertical(sol.sol(s))
                a = newton_from(body, start_contact, zb)
                b = newton_from(body, other[0], zb)
                return b[1] - a[1]
            g_start = gap(t)
            if g_start <= 0.0:
                t_switch = t  # already lower at the start of the step
            else:
                t_switch = brentq(gap, t, t_end, xtol=1e-15, rtol=1e-15, maxiter=200)
            y_switch = sol.sol(t_switch)
            switched = newton_from(body, other[0], vertical(y_switch))
            switches.append(t_switch)
            body.contact = switched[0]
            y, t = y_switch, t_switch
            if t_switch == t_end:
                break
        if (n + 1) % STEPS == 0:
            y[:4] /= numpy.linalg.norm(y[:4])
            states.append({"period": (n + 1) // STEPS, "state": [float(v) for v in y]})
    return states, switches


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "massprops.json"), encoding="utf-8") as handle:
        massprops = json.load(handle)
    cases = []
    for morphology in (sys.argv[1:] or ["I", "II"]):
        entry = next(c for c in massprops["cases"] if c["morphology"] == morphology and c["beta"] == BETA)
        body = Body(morphology, entry["inertia"])
        initial_contact(body, numpy.array([0.0, 0.0, 1.0]))
        start = time.perf_counter()
        states, switches = run(body, numpy.array([1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]))
        seconds = time.perf_counter() - start
        if os.environ.get("SWITCHING_FINAL") == "1":
            print(json.dumps({"morphology": morphology, "method": METHOD, "rtol": RTOL, "periods": PERIODS,
                              "state": states[-1]["state"], "switches": len(switches), "seconds": seconds}))
            continue
        cases.append({"morphology": morphology, "beta": BETA, "periods": states, "switch_times": switches})
    if os.environ.get("SWITCHING_FINAL") == "1":
        return
    emit({"provenance": {"script": "references/switching.py",
                         "method": "dynamics.py's rolling model; DOP853 rtol 1e-12 per nominal step T/160; global "
                                   "minimum by a 180x360 grid scan and Newton after each step; switch time by brentq "
                                   "on the dense output where the two branches are equally low",
                         "periods": PERIODS, "state": "quaternion (w, x, y, z), then body angular velocity",
                         **versions(sympy=sympy)},
          "cases": cases})


if __name__ == "__main__":
    main()
