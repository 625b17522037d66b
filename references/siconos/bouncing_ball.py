#!/usr/bin/python3
"""A ball dropped on Table 1's vibrated plane, read in units of g, with Newton's restitution 0.5: its landing
times from Siconos's Moreau-Jean time stepping at five steps, and in closed form.

In the plane's frame the ball's lowest point moves under g_eff(t) = g + a1 cos(wt) + a2 cos(2wt + psi)
(src/gb_forcing.c): between impacts its height is z(t) = z0 + v0 s - g s^2/2 - a1 (cos(w t0) - cos(w t))/w^2
+ a1 sin(w t0) s / w - a2 (cos(2w t0 + psi) - cos(2w t + psi))/(4 w^2) + a2 sin(2w t0 + psi) s / (2w),
s = t - t0. The closed form finds each landing as the first root of z after the last one (scipy's brentq on
a bracket found by stepping 1/400 of a period, then tightened to 1e-14 s) and rebounds at -e times the
approach speed. The ball's spin plays no part (a sphere's lowest point is below its centre).

Siconos (Debian's python3-siconos, its kernel): a LagrangianLinearTIDS of one coordinate (the height),
mass 1, a LagrangianLinearTIR y = q, Newton's impact law with e = 0.5, Moreau-Jean (theta = 1/2) with an
LCP at each step; the external force -g_eff is set at each step's midpoint (the scheme's own order is
one). A landing is a step whose impulse is positive after a step without; its time is the step's end.
Steps T/160 ... T/2560 (T = 2 pi / 18): the landing times converge at first order to the closed form's.

Run by `make references` where Siconos is installed; the output (JSON, on stdout) is committed as
references/siconos/bouncing_ball.json and read by verify/s5_flight.c.
"""
import math
import os
import sys
import time

import numpy
from scipy.optimize import brentq

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from provenance import emit, versions  # noqa: E402

import siconos  # noqa: E402
import siconos.kernel as sk  # noqa: E402

G, OMEGA, PSI = 9.81, 18.0, math.pi / 3.0
A1, A2 = 2.0 * G, 1.0 * G             # Table 1's amplitudes in units of g
H, E, LANDINGS = 0.2, 0.5, 8           # drop height of the lowest point [m], restitution, landings compared
T = 2.0 * math.pi / OMEGA


def geff(t):
    return G + A1 * math.cos(OMEGA * t) + A2 * math.cos(2.0 * OMEGA * t + PSI)


def height(t, t0, z0, v0):
    s = t - t0
    w, w2 = OMEGA, 2.0 * OMEGA
    return (z0 + v0 * s - 0.5 * G * s * s
            - A1 * (math.cos(w * t0) - math.cos(w * t)) / (w * w) + A1 * math.sin(w * t0) * s / w
            - A2 * (math.cos(w2 * t0 + PSI) - math.cos(w2 * t + PSI)) / (w2 * w2) + A2 * math.sin(w2 * t0 + PSI) * s / w2)


def velocity(t, t0, v0):
    s = t - t0
    w, w2 = OMEGA, 2.0 * OMEGA
    return (v0 - G * s - A1 * (math.sin(w * t) - math.sin(w * t0)) / w
            - A2 * (math.sin(w2 * t + PSI) - math.sin(w2 * t0 + PSI)) / w2)


def closed_form():
    """The first LANDINGS landing times and approach speeds (relative to the plane)."""
    t0, z0, v0, out = 0.0, H, 0.0, []
    while len(out) < LANDINGS:
        step = T / 400.0
        lo = t0 + (0.0 if z0 > 0.0 else 1e-12)  # after a landing the rebound starts at z = 0 going up
        hi = lo + step
        while height(hi, t0, z0, v0) >= 0.0:
            lo, hi = hi, hi + step
        landing = brentq(lambda x: height(x, t0, z0, v0), lo, hi, xtol=1e-14, rtol=1e-15)
        approach = velocity(landing, t0, v0)
        out.append({"t": landing, "approach": approach})
        t0, z0, v0 = landing, 0.0, -E * approach
    return out


def siconos_run(steps_per_period):
    h = T / steps_per_period
    ball = sk.LagrangianLinearTIDS(numpy.array([H]), numpy.array([0.0]), numpy.array([[1.0]]))
    ball.setFExtPtr(numpy.array([-geff(0.5 * h)]))
    relation = sk.LagrangianLinearTIR(numpy.array([[1.0]]))
    interaction = sk.Interaction(sk.NewtonImpactNSL(E), relation)
    t_end = 1.2 * T * 20
    nsds = sk.NonSmoothDynamicalSystem(0.0, t_end)
    nsds.insertDynamicalSystem(ball)
    nsds.link(interaction, ball)
    osi = sk.MoreauJeanOSI(0.5)
    simulation = sk.TimeStepping(nsds, sk.TimeDiscretisation(0.0, h), osi, sk.LCP())
    landings, touching, k = [], False, 0
    start = time.process_time()
    while simulation.hasNextEvent() and len(landings) < LANDINGS:
        ball.setFExtPtr(numpy.array([-geff((k + 0.5) * h)]))
        simulation.computeOneStep()
        k += 1
        impulse = float(ball.p(1)[0]) if ball.p(1) is not None else 0.0
        if impulse > 0.0 and not touching:
            landings.append(k * h)
        touching = impulse > 0.0
        simulation.nextStep()
    return landings, time.process_time() - start


def main():
    exact = closed_form()
    runs = []
    for n in (160, 320, 640, 1280, 2560):
        landings, seconds = siconos_run(n)
        runs.append({"steps_per_period": n, "landings": landings, "seconds": seconds})
    emit({"what": "a ball dropped on Table 1's plane read in units of g, e = 0.5: landing times in closed form and "
                  "from Siconos's Moreau-Jean time stepping",
          "versions": dict(versions(), siconos=str(siconos.version)),
          "cases": [{"forcing": {"g": G, "a1": A1, "a2": A2, "omega": OMEGA, "psi": PSI}, "height": H, "restitution": E,
                     "closed_form": exact, "siconos": runs}]})


if __name__ == "__main__":
    main()
