#!/usr/bin/python3
"""Reference impacts at two and three points on a plane of Coulomb friction, solved by Siconos.

Each case is a random rigid body (a box of random half-sides turned about a random axis: a full inertia
tensor) whose two or three points lie on the plane z = depth below its centroid, moving with random
velocities, one point approaching; the plane's friction mu is random in [0.05, 2.05] and the impact
plastic (e = 0, where Moreau's velocity-level law and Siconos's formulation are the same law: with e > 0
Siconos also asks a point that leaves to leave at e times its approach, gomboc only that it leaves).

Siconos (Debian's python3-siconos, its numerics library) states the impact as a three-dimensional
friction-contact problem in the contacts' local frames (normal first): u = W r + q, with W = J M^-1 J^T
the Delassus operator and q = J (v, omega) the velocities before, and Coulomb's law with De Saxce's
modified velocity between u and the impulses r. It is solved by non-smooth Gauss-Seidel (NSGS, whose
local solver handles the singular W of three coplanar points; the non-smooth Newton methods factorise W
and fail there) to a relative residual of 1e-12; the velocities after are (v, omega) + M^-1 J^T r. Stored
with each case: the inputs, the answer, its residual and iterations, and the CPU seconds of the solve
alone (best of 3, through Python's binding).

Run by `make references` where Siconos is installed (scripts/install-deps.sh siconos); the output (JSON,
on stdout) is committed as references/siconos/impacts.json and read by verify/s5_friction.c.
"""
import math
import os
import sys
import time

import numpy

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from provenance import emit, versions  # noqa: E402

import siconos  # noqa: E402
import siconos.numerics as sn  # noqa: E402

CASES, SEED, TOL = 500, 20261127, 1e-12


def random_impact(rng, count):
    a, c, h = 0.4 + 0.5 * rng.random(3)
    m = 0.5 + 3.0 * rng.random()
    d = numpy.array([m * (c * c + h * h) / 3.0, m * (a * a + h * h) / 3.0, m * (a * a + c * c) / 3.0])
    axis = rng.normal(size=3)
    axis /= numpy.linalg.norm(axis)
    t = 3.0 * rng.uniform(-1.0, 1.0)
    ax = numpy.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    R = math.cos(t) * numpy.eye(3) + (1.0 - math.cos(t)) * numpy.outer(axis, axis) + math.sin(t) * ax
    inertia = R @ numpy.diag(d) @ R.T
    depth = -0.3 - 0.7 * rng.random()
    points = numpy.column_stack([rng.uniform(-1.0, 1.0, count), rng.uniform(-1.0, 1.0, count), numpy.full(count, depth)])
    v = rng.uniform(-1.0, 1.0, 3)
    w = 2.0 * rng.uniform(-1.0, 1.0, 3)
    v[2] = -rng.random() - 0.1 - numpy.cross(w, points[0])[2]  # point 0 approaches
    mu = 0.05 + 2.0 * rng.random()
    return m, inertia, points, v, w, mu


def jacobian(points):
    """Rows (normal, x, y) per contact: the local velocity d . (v + omega x p) = [d, p x d] . (v, omega)."""
    rows = []
    for p in points:
        for d in (numpy.array([0.0, 0.0, 1.0]), numpy.array([1.0, 0.0, 0.0]), numpy.array([0.0, 1.0, 0.0])):
            rows.append(numpy.concatenate([d, numpy.cross(p, d)]))
    return numpy.array(rows)


def solve(solver, W, q, mu, count):
    problem = sn.FrictionContactProblem(3, count, W, q, numpy.full(count, mu))
    best, r, u, options = math.inf, None, None, None
    for _ in range(3):
        r, u = numpy.zeros(3 * count), numpy.zeros(3 * count)
        options = sn.SolverOptions(solver)
        options.iparam[sn.SICONOS_IPARAM_MAX_ITER] = 100000
        options.dparam[sn.SICONOS_DPARAM_TOL] = TOL
        start = time.process_time()
        info = sn.fc3d_driver(problem, r, u, options)
        best = min(best, time.process_time() - start)
    return {"info": int(info), "residual": float(options.dparam[sn.SICONOS_DPARAM_RESIDU]),
            "iterations": int(options.iparam[sn.SICONOS_IPARAM_ITER_DONE]), "seconds": best}, r


def after(m, inertia, J, v, w, r):
    Minv = numpy.zeros((6, 6))
    Minv[:3, :3] = numpy.eye(3) / m
    Minv[3:, 3:] = numpy.linalg.inv(inertia)
    x = numpy.concatenate([v, w]) + Minv @ J.T @ r
    return x[:3], x[3:]


def main():
    rng = numpy.random.default_rng(SEED)
    cases = []
    for k in range(CASES):
        count = 2 + k % 2
        m, inertia, points, v, w, mu = random_impact(rng, count)
        J = jacobian(points)
        Minv = numpy.zeros((6, 6))
        Minv[:3, :3] = numpy.eye(3) / m
        Minv[3:, 3:] = numpy.linalg.inv(inertia)
        W = J @ Minv @ J.T
        q = J @ numpy.concatenate([v, w])
        case = {"mass": m, "inertia": inertia.tolist(), "points": points.tolist(), "v": v.tolist(), "omega": w.tolist(),
                "restitution": 0.0, "mu": mu}
        report, r = solve(sn.SICONOS_FRICTION_3D_NSGS, W, q, mu, count)
        v1, w1 = after(m, inertia, J, v, w, r)
        # the impulses in the body's axes: (P_x, P_y, P_n) per contact
        impulses = [[float(r[3 * i + 1]), float(r[3 * i + 2]), float(r[3 * i])] for i in range(count)]
        report.update({"v": v1.tolist(), "omega": w1.tolist(), "impulses": impulses})
        case["nsgs"] = report
        cases.append(case)
    emit({"what": "impacts at 2 and 3 points on a plane of Coulomb friction (e = 0), solved by Siconos's "
                  "three-dimensional friction-contact solver (NSGS)",
          "generator": f"numpy default_rng({SEED}), {CASES} cases, 2 and 3 points alternately",
          "tolerance": TOL, "versions": dict(versions(), siconos=str(siconos.version)), "cases": cases})


if __name__ == "__main__":
    main()
