#!/usr/bin/python3
"""Reference crossings of the classical Henon map's unstable and stable manifolds (docs/proofs.md, item 12).

Two crossings of f(U) with a stable arc far out (t about -3.4e8), 4.3e-14 apart along it, which a trellis must
order. mpmath at 80 digits, independently of the library's balls: the fixed point in closed form; the
parametrisations P(lambda s) = f(P(s)) of the unstable manifold of f(x, y) = (1 - a x^2 + y, b x) and R of the
unstable manifold of its inverse g(x, y) = (y / b, x - 1 + (a / b^2) y^2), with P'(0) and R'(0) the unit
eigenvectors the library chooses ((J01, lambda - J00) or (lambda - J11, J10), the longer, normalised); their Taylor
coefficients to order 60 by the same recursion, summed where |s| <= 1/100, and larger s reached by iterating the
map; then Newton on P(s) = R(origin + tau) from a start near each crossing. origin is the middle of the stable arc
as the harness computes it in doubles. Run by `make references`; the output (JSON, on stdout) is committed as
references/henon_crossings.json.
"""
import os
import sys

import mpmath
from mpmath import mp, mpf

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from provenance import emit, versions  # noqa: E402

mp.dps = 80
A, B = mpf(7) / 5, mpf(3) / 10
ORDER, NEAR = 60, mpf(1) / 100


def forward(z):
    return (1 - A * z[0] ** 2 + z[1], B * z[0])


def backward(z):
    return (z[1] / B, z[0] - 1 + A / B ** 2 * z[1] ** 2)


def eigen(J):
    """The eigenvalue of larger modulus of J and its unit eigenvector, as the library chooses it."""
    tr, det = J[0][0] + J[1][1], J[0][0] * J[1][1] - J[0][1] * J[1][0]
    root = mpmath.sqrt(tr ** 2 - 4 * det)
    lam = (tr + root) / 2 if tr >= 0 else (tr - root) / 2
    a, b = (J[0][1], lam - J[0][0]), (lam - J[1][1], J[1][0])
    w = a if mpmath.hypot(*a) >= mpmath.hypot(*b) else b
    n = mpmath.hypot(*w)
    return lam, (w[0] / n, w[1] / n)


def coefficients(z, J, lam, v, kind):
    """p_0 ... p_ORDER: (lambda^k I - J) p_k = sum_j Q(p_j, p_(k-j)), Q the map's quadratic part."""
    p = [z, v]
    for k in range(2, ORDER + 1):
        if kind == "f":  # Q(u, w) = (-a u_x w_x, 0)
            rhs = (-A * sum(p[j][0] * p[k - j][0] for j in range(1, k)), mpf(0))
        else:  # Q(u, w) = (0, a/b^2 u_y w_y)
            rhs = (mpf(0), A / B ** 2 * sum(p[j][1] * p[k - j][1] for j in range(1, k)))
        M = mpmath.matrix([[lam ** k - J[0][0], -J[0][1]], [-J[1][0], lam ** k - J[1][1]]])
        x = mpmath.lu_solve(M, mpmath.matrix(rhs))
        p.append((x[0], x[1]))
    return p


def evaluate(p, lam, step, s):
    """The parametrisation at s: its series at s / lam^k within NEAR of 0, then k steps of the map."""
    k = 0
    while abs(s) > NEAR:
        s, k = s / lam, k + 1
    z = (sum(c[0] * s ** i for i, c in enumerate(p)), sum(c[1] * s ** i for i, c in enumerate(p)))
    for _ in range(k):
        z = step(z)
    return z


def main():
    x = (-(1 - B) + mpmath.sqrt((1 - B) ** 2 + 4 * A)) / (2 * A)
    z = (x, B * x)
    Jf = [[-2 * A * z[0], mpf(1)], [B, mpf(0)]]
    Jg = [[mpf(0), 1 / B], [mpf(1), 2 * A / B ** 2 * z[1]]]
    lf, vf = eigen(Jf)
    lg, vg = eigen(Jg)
    P, R = coefficients(z, Jf, lf, vf, "f"), coefficients(z, Jg, lg, vg, "g")
    piece = (-335744736.32183778, -335744725.12147218)
    origin = mpf(0.5 * piece[0] + 0.5 * piece[1])  # in doubles, as the harness
    cases = []
    for s0, tau0 in ((-42167.476, 4.900356471684892), (-44588.037, 4.900356471684935)):
        def gap(s, tau):
            p, r = evaluate(P, lf, forward, s), evaluate(R, lg, backward, origin + tau)
            return [p[0] - r[0], p[1] - r[1]]
        s, tau = mpmath.findroot(gap, (mpf(s0), mpf(tau0)))
        cases.append({"s": mpmath.nstr(s, 25), "tau": mpmath.nstr(tau, 25),
                      "residual": float(max(abs(g) for g in gap(s, tau)))})
    emit({"source": "mpmath " + mpmath.__version__ + " at 80 digits (references/henon_crossings.py)",
          "versions": versions(mpmath=mpmath),
          "map": "Henon a = 7/5, b = 3/10; P'(0), R'(0) unit eigenvectors; order " + str(ORDER),
          "stable_arc": list(piece), "origin": float(origin),
          "lambda_unstable": float(lf), "lambda_stable_inverse": float(lg), "cases": cases})


if __name__ == "__main__":
    main()
