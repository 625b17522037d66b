#!/usr/bin/python3
"""Reference contact points of the two analytical Gömböcs (paper §4, eqs 27–35).

Independent of gomboc's C code: the surface is written again from the paper (eqs 1, 2, 4, 6, 8, 9),
its height h = ẑ_b·x(φ, θ) (eq 28) is differentiated symbolically by sympy (no hand-derived
derivative is shared with the C code), and every local minimum is found by scipy.optimize:
  1. h on a 200 × 400 grid (φ at cell centres, θ from 0 in steps of 2π/400; deliberately not
     gomboc's 180 × 360), and every grid node no higher than its 8 neighbours (θ periodic, across
     the poles on the opposite meridian) as a start;
  2. scipy.optimize.minimize(method="trust-exact") with the symbolic gradient and Hessian, gtol 1e-13,
     then scipy.optimize.root (MINPACK hybrj) on the gradient, xtol 1e-15, to polish;
  3. starts that reach the same point (within 1e-7) merge; a point counts as a minimum when both
     eigenvalues of its Hessian are positive (eq 35).
The verticals are seeded: numpy.random.default_rng(SEED), normal triples, normalised (uniform on the
sphere, which is the distribution of z_b = Rᵀe_z for a uniformly random attitude R).
Run by `make references`; the output (JSON, on stdout) is committed as references/contact.json.
"""
import math
import os
import sys

import numpy
import sympy
from scipy import optimize

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from provenance import emit, versions  # noqa: E402

SEED = 20261122
ATTITUDES = 200
GRID = (200, 400)
CASES = [("I", 0.12), ("II", 0.12), ("I", 0.02), ("II", 0.02)]


def height_functions(morphology):
    phi, theta, beta, d0, d1, d2 = sympy.symbols("phi theta beta d0 d1 d2", real=True)
    if morphology == "I":
        chi = theta - 5 * phi                                                          # eq 8
    else:
        chi = theta - sympy.Rational(3, 2) * sympy.pi * (sympy.cos(phi) - sympy.cos(phi) ** 3 / 3)  # eq 9
    r = (1 + 4 * beta * sympy.sin(phi) * sympy.cos(chi)) ** sympy.Rational(1, 4)     # eqs 4, 6
    u = (sympy.sin(phi) * sympy.cos(theta), sympy.sin(phi) * sympy.sin(theta), sympy.cos(phi))
    h = r * (d0 * u[0] + d1 * u[1] + d2 * u[2])                                      # eq 28
    q = (phi, theta)
    grad = [sympy.diff(h, v) for v in q]
    hess = [[sympy.diff(g, v) for v in q] for g in grad]
    args = (phi, theta, beta, d0, d1, d2)
    return (sympy.lambdify(args, h, "numpy"), sympy.lambdify(args, grad, "numpy"),
            sympy.lambdify(args, hess, "numpy"))


def discrete_minima(values):
    """Indices (i, j) of nodes no higher than any of their 8 neighbours."""
    n_phi, n_theta = values.shape
    padded = numpy.empty((n_phi + 2, n_theta))
    padded[1:-1] = values
    padded[0] = numpy.roll(values[0], n_theta // 2)      # across the north pole
    padded[-1] = numpy.roll(values[-1], n_theta // 2)    # across the south pole
    centre = padded[1:-1]
    ok = numpy.ones_like(values, dtype=bool)
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            if di == 0 and dj == 0:
                continue
            neighbour = numpy.roll(padded[1 + di:n_phi + 1 + di], -dj, axis=1)
            ok &= centre <= neighbour
    return numpy.argwhere(ok)


def minima_for(functions, beta, zb):
    h, grad, hess = functions
    n_phi, n_theta = GRID
    phi = (numpy.arange(n_phi) + 0.5) * math.pi / n_phi
    theta = numpy.arange(n_theta) * 2.0 * math.pi / n_theta
    P, T = numpy.meshgrid(phi, theta, indexing="ij")
    values = h(P, T, beta, *zb)
    found = []
    for i, j in discrete_minima(values):
        result = optimize.minimize(
            lambda q: h(q[0], q[1], beta, *zb), numpy.array([phi[i], theta[j]]),
            jac=lambda q: numpy.array(grad(q[0], q[1], beta, *zb), dtype=float),
            hess=lambda q: numpy.array(hess(q[0], q[1], beta, *zb), dtype=float),
            method="trust-exact", options={"gtol": 1e-13, "maxiter": 200})
        # Polish: Newton–Powell (MINPACK hybrj) on the stationarity conditions (eq 32).
        polished = optimize.root(lambda q: numpy.array(grad(q[0], q[1], beta, *zb), dtype=float),
                                 result.x, jac=lambda q: numpy.array(hess(q[0], q[1], beta, *zb), dtype=float),
                                 method="hybr", options={"xtol": 1e-15})
        # hybrj reports "not making good progress" once the residual reaches rounding: keep
        # whichever point has the smaller gradient.
        def gradient_norm(q):
            return float(numpy.linalg.norm(grad(q[0], q[1], beta, *zb)))
        best = polished.x if gradient_norm(polished.x) < gradient_norm(result.x) else result.x
        p, t = float(best[0]), float(best[1])
        if p < 0.0:
            p, t = -p, t + math.pi
        if p > math.pi:
            p, t = 2.0 * math.pi - p, t + math.pi
        t = math.fmod(t, 2.0 * math.pi)
        if t < 0.0:
            t += 2.0 * math.pi
        if numpy.any(numpy.linalg.eigvalsh(numpy.array(hess(p, t, beta, *zb), dtype=float)) <= 0.0):
            continue
        x = position(p, t, h, beta)
        if any(math.dist(x, position(m["phi"], m["theta"], h, beta)) < 1e-7 for m in found):
            continue
        found.append({"phi": p, "theta": t, "height": float(h(p, t, beta, *zb)),
                      "gradient_norm": float(numpy.linalg.norm(grad(p, t, beta, *zb)))})
    found.sort(key=lambda m: m["height"])
    return found


def position(p, t, h, beta):
    """x(φ, θ) from h with the three unit verticals: x_k = h(φ, θ; e_k)."""
    return tuple(float(h(p, t, beta, *e)) for e in ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)))


def main():
    rng = numpy.random.default_rng(SEED)
    verticals = rng.normal(size=(ATTITUDES, 3))
    verticals /= numpy.linalg.norm(verticals, axis=1)[:, None]
    cases = []
    for morphology, beta in CASES:
        functions = height_functions(morphology)
        attitudes = [{"zb": [float(c) for c in zb], "minima": minima_for(functions, beta, zb)}
                     for zb in verticals]
        cases.append({"morphology": morphology, "beta": beta, "attitudes": attitudes})
    document = {
        "provenance": {
            "script": "references/contact.py",
            "method": "sympy gradient and Hessian of h = zb . x (eq 28); scipy.optimize.minimize "
                      "trust-exact, gtol 1e-13, polished by optimize.root hybr, from every discrete local minimum of a 200 x 400 grid",
            "seed": SEED,
            "attitudes": ATTITUDES,
            **versions(sympy=sympy),
        },
        "cases": cases,
    }
    emit(document)


if __name__ == "__main__":
    main()
