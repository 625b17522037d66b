#!/usr/bin/python3
"""Reference mass properties of the two analytical Gömböcs (paper §2, eq 53).

Independent of gomboc's C code: the body is written again from the paper (eqs 4, 6) and every
integral is a nested scipy.integrate.quad (QUADPACK QAGS) over phi inside theta:
  V = ∫ r³/3 dΩ,  ∫x dV = ∫ r⁴/4 u dΩ,  ∫x xᵀ dV = ∫ r⁵/5 u uᵀ dΩ,  L = (1/4π) ∫ r dΩ,
with dΩ = sin φ dφ dθ, a homogeneous body of mass 1, inertia about the centroid.
Run by `make references`; the output (JSON, on stdout) is committed as references/massprops.json.
"""
import math
import os
import sys

from scipy import integrate

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from provenance import emit, versions  # noqa: E402

EPSABS = 1e-13
EPSREL = 1e-12
LIMIT = 200
CASES = [("I", 0.12), ("II", 0.12), ("I", 0.02), ("II", 0.02)]


def chi(morphology, phi, theta):
    if morphology == "I":
        return theta - 5.0 * phi                                              # eq 8
    c = math.cos(phi)
    return theta - 1.5 * math.pi * (c - c ** 3 / 3.0)                         # eq 9


def radius(morphology, beta, phi, theta):
    return (1.0 + 4.0 * beta * math.sin(phi) * math.cos(chi(morphology, phi, theta))) ** 0.25


def surface_integral(morphology, beta, power, weight):
    def inner(phi, theta):
        s = math.sin(phi)
        u = (s * math.cos(theta), s * math.sin(theta), math.cos(phi))
        return radius(morphology, beta, phi, theta) ** power / power * weight(u) * s

    def outer(theta):
        return integrate.quad(inner, 0.0, math.pi, args=(theta,), epsabs=EPSABS, epsrel=EPSREL,
                              limit=LIMIT)[0]

    return integrate.quad(outer, 0.0, 2.0 * math.pi, epsabs=EPSABS, epsrel=EPSREL, limit=LIMIT)[0]


def mass_properties(morphology, beta):
    volume = surface_integral(morphology, beta, 3, lambda u: 1.0)
    first = [surface_integral(morphology, beta, 4, lambda u, i=i: u[i]) for i in range(3)]
    second = [[0.0] * 3 for _ in range(3)]
    for i in range(3):
        for j in range(i, 3):
            second[i][j] = second[j][i] = surface_integral(morphology, beta, 5,
                                                           lambda u, i=i, j=j: u[i] * u[j])
    length = surface_integral(morphology, beta, 1, lambda u: 1.0) / (4.0 * math.pi)
    density = 1.0 / volume
    centroid = [f / volume for f in first]
    c2 = sum(c * c for c in centroid)
    trace = second[0][0] + second[1][1] + second[2][2]
    inertia = [[density * (trace * (i == j) - second[i][j]) - (c2 * (i == j) - centroid[i] * centroid[j])
                for j in range(3)] for i in range(3)]
    return {"morphology": morphology, "beta": beta, "mass": 1.0, "volume": volume,
            "centroid": centroid, "inertia": inertia, "L": length}


def main():
    out = {
        "provenance": {
            "script": "references/massprops.py",
            "method": "nested scipy.integrate.quad (QUADPACK QAGS), phi inner, theta outer",
            "epsabs": EPSABS, "epsrel": EPSREL, "limit": LIMIT,
            **versions(),
        },
        "cases": [mass_properties(m, b) for m, b in CASES],
    }
    emit(out, indent=2)


if __name__ == "__main__":
    main()
