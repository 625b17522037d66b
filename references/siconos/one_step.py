#!/usr/bin/python3
"""One Moreau-Jean step of the scenes' grid polyhedra in Siconos's kernel, from given states.

The same body as references/siconos/engine.py builds it (`gomboc shape`'s mass properties and the hull of its
90 x 180 grid nodes, an exact vertex-plane relation per hull vertex within 1 mm of the plane), on a still plane
(g = 9.81, no forcing, no damping), one step of TimeStepping with MoreauJeanOSI(theta = 1/2) and a
three-dimensional friction-contact problem solved by NSGS to a relative residual of 1e-14, from states drawn
to cover what a step meets: the body's lowest vertex 1e-6 m or 1e-9 m above the plane, moving down and
sideways, turning or not, on planes of friction 0.1 ... 2, restitution 0 or 0.5. Stored with each case: the
state (attitude as an axis and angle, the lowest vertex's gap, the centroid's velocity, omega in body axes),
mu, e, h, and Siconos's twist after the step (the centroid's velocity, omega in body axes), the interactions
it carried and its solver's residual.

Where omega is 0 at the step's start, Siconos's step and gomboc's default one pose the same problem; where it
is not, Siconos evaluates the relations at the attitude its step predicts and linearises the gyroscopic term
implicitly, as gomboc's `stepping_siconos` variant does (docs/stepping.md). verify/siconos.c reads it.

Run by `make references` where Siconos is installed; the output (JSON, on stdout) is committed as
references/siconos/one_step.json.
"""
import math
import os
import sys

import numpy

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from provenance import emit, versions  # noqa: E402

import engine  # noqa: E402
import siconos  # noqa: E402
import siconos.kernel as sk  # noqa: E402
import siconos.numerics as sn  # noqa: E402

SEED, PER_BODY, TOL, G, H = 20261128, 12, 1e-14, 9.81, 1e-4
LINEARISED = True


def siconos_step(body, R0, gap, v0, w0, h, mu, e):
    """One step of Siconos from the lowest hull vertex `gap` above the plane: its twist after, the interactions
    that carried the body (a positive normal impulse), their count and the solver's residual."""
    mass, inertia, points = body["mass"], body["inertia"], body["points"]
    heights = (points @ R0.T)[:, 2]
    q0 = numpy.concatenate([[0.0, 0.0, gap - heights.min()], engine._quaternion_from_matrix(R0)])
    ds = sk.NewtonEulerDS(q0, numpy.concatenate([v0, w0]), mass, inertia)
    ds.setFExtPtr(numpy.array([0.0, 0.0, -mass * G]))
    ds.setMExtPtr(numpy.zeros(3))
    nsds, problem, sim = engine.moreau_jean(ds, 10.0 * h, h, TOL, 100000)
    if LINEARISED:  # one linearisation, at the predicted state: Moreau-Jean's step proper (no Newton iteration after it)
        sim.setNewtonTolerance(math.inf)
    law = sk.NewtonImpactFrictionNSL(e, 0.0, mu, 3)
    kept = []
    z = q0[2] + heights
    for k in numpy.nonzero(z < engine.ACTIVE_ON)[0]:
        relation = engine.VertexPlane(points[k])  # kept: Siconos calls back into it
        interaction = sk.Interaction(law, relation)
        nsds.link(interaction, ds)
        kept.append((int(body["hull"][k]), interaction, relation))
    sim.computeOneStep()
    twist = numpy.array(ds.twist(), dtype=float)
    carried = [node for node, interaction, _ in kept if float(interaction.lambda_(1)[0]) > 0.0]
    return twist, carried, len(kept), float(problem.numericsSolverOptions().dparam[sn.SICONOS_DPARAM_RESIDU])


def main():
    gomboc = os.environ.get("GOMBOC", "build/gomboc")
    rng = numpy.random.default_rng(SEED)
    cases = []
    for morphology in ("I", "II"):
        body = engine.read_body(gomboc, {"morphology": morphology, "beta": 0.12, "mass": 1.0})
        for k in range(PER_BODY):
            axis = rng.normal(size=3)
            axis /= numpy.linalg.norm(axis)
            angle = float(rng.uniform(0.0, math.pi))
            gap = 1e-9 if k % 4 == 3 else 1e-6
            v0 = numpy.array([rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), -rng.uniform(0.05, 0.8)])
            w0 = numpy.zeros(3) if k % 2 == 0 else rng.uniform(-3.0, 3.0, size=3)
            mu = float(rng.choice([0.1, 0.3, 0.6, 2.0]))
            e = 0.5 if k % 3 == 2 else 0.0
            twist, carried, interactions, residual = siconos_step(body, engine.rotation(axis, angle), gap, v0, w0, H, mu, e)
            cases.append({"body": morphology, "axis": axis.tolist(), "angle": angle, "gap": gap, "velocity": v0.tolist(),
                          "omega": w0.tolist(), "mu": mu, "restitution": e, "h": H,
                          "velocity_after": twist[:3].tolist(), "omega_after": twist[3:].tolist(),
                          "carried": carried, "interactions": interactions,
                          "residual": residual if math.isfinite(residual) else None})  # None: no problem to solve
    emit({"what": "one Moreau-Jean step of the grid polyhedra of Gomboc I and II on a still plane in Siconos's kernel "
                  "(TimeStepping, MoreauJeanOSI(1/2), NSGS to 1e-14), from seeded states",
          "generator": f"numpy default_rng({SEED}), {PER_BODY} states a body; omega 0 at every other",
          "tolerance": TOL, "g": G, "versions": dict(versions(), siconos=str(siconos.version)), "cases": cases})


if __name__ == "__main__":
    main()
