#!/usr/bin/python3
"""An independent implementation of the paper's own model (section 8): eq 44 as written, with the
contact the lowest node of a fixed 90 x 180 grid found by brute force at every RK4 stage, integrated by
the classical fixed-step RK4 at 160 steps per forcing period, for both Table 1 bodies (A1, A2 in m/s^2).

Written from the paper, not from the C code: the surface (eqs 1-9), z_b = R^T e_z (eq 21), the contact
as the global minimiser of h over the nodes (eqs 28-30), I_P by the parallel-axis theorem (eq 40),
tau = m g_eff r_c x z_b - c omega (eqs 41-43) and eq 44, where r_c is constant between node changes
(the grid's contact moves only by jumps), so its I_P-dot term is zero. The choices the paper leaves open
are the documented ones of this project: centred nodes (phi_i = (i + 1/2) pi / N_phi, theta_j =
2 pi j / N_theta, ties to the lower index i N_theta + j), R0 = I, omega0 = 0, the attitude as a unit
quaternion renormalised after every step. The inertia tensor is the independent scipy quadrature of
references/massprops.json. Output: the state (quaternion, omega) at the end of each of the first
PERIODS forcing periods, with provenance.
"""
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from provenance import emit, versions  # noqa: E402

PERIODS = 5
STEPS = 160
N_PHI, N_THETA = 90, 180
BETA, MASS, G, A1, A2, OMEGA, PSI, DAMPING = 0.12, 1.0, 9.81, 2.0, 1.0, 18.0, math.pi / 3, 0.02


def phase(morphology, phi, theta):
    """chi of eqs 8 and 9."""
    if morphology == "I":
        return theta - 5.0 * phi
    c = np.cos(phi)
    return theta - 1.5 * math.pi * (c - c ** 3 / 3.0)


def nodes(morphology):
    """x(phi, theta) = r u at every grid node, in index order i N_theta + j (eqs 1, 2, 7)."""
    phi = (np.arange(N_PHI) + 0.5) * math.pi / N_PHI
    theta = np.arange(N_THETA) * 2.0 * math.pi / N_THETA
    P, T = np.meshgrid(phi, theta, indexing="ij")
    r = (1.0 + 4.0 * BETA * np.sin(P) * np.cos(phase(morphology, P, T))) ** 0.25
    u = np.stack([np.sin(P) * np.cos(T), np.sin(P) * np.sin(T), np.cos(P)], axis=-1)
    return (r[..., None] * u).reshape(-1, 3)


def rotation(q):
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def rhs(t, y, X, inertia):
    q, w = y[:4], y[4:7]
    zb = rotation(q).T @ np.array([0.0, 0.0, 1.0])        # eq 21
    rc = X[int(np.argmin(X @ zb))]                          # eqs 28-30 on the grid; argmin takes the first
    IP = inertia + MASS * (rc @ rc * np.eye(3) - np.outer(rc, rc))  # eq 40
    geff = G + A1 * math.cos(OMEGA * t) + A2 * math.cos(2 * OMEGA * t + PSI)  # eq 25
    tau = MASS * geff * np.cross(rc, zb) - DAMPING * w      # eqs 41-43
    wdot = np.linalg.solve(IP, tau - np.cross(w, IP @ w))   # eq 44 with r_c constant between jumps
    qw = np.array([0.0, *w])
    qdot = 0.5 * np.array([q[0] * qw[0] - q[1:] @ qw[1:], *(q[0] * qw[1:] + qw[0] * q[1:] + np.cross(q[1:], qw[1:]))])
    return np.concatenate([qdot, wdot])


def run(morphology, inertia):
    X = nodes(morphology)
    h = 2.0 * math.pi / OMEGA / STEPS
    y = np.array([1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
    states = []
    for n in range(PERIODS * STEPS):
        t = n * h
        k1 = rhs(t, y, X, inertia)
        k2 = rhs(t + h / 2, y + h / 2 * k1, X, inertia)
        k3 = rhs(t + h / 2, y + h / 2 * k2, X, inertia)
        k4 = rhs(t + h, y + h * k3, X, inertia)
        y = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        y[:4] /= np.linalg.norm(y[:4])
        if (n + 1) % STEPS == 0:
            states.append({"period": (n + 1) // STEPS, "state": y[:7].tolist()})
    return states


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "massprops.json")) as f:
        props = {(c["morphology"], c["beta"], c["mass"]): c for c in json.load(f)["cases"]}
    cases = []
    for morphology in ("I", "II"):
        inertia = np.array(props[(morphology, BETA, MASS)]["inertia"])
        cases.append({"morphology": morphology, "beta": BETA, "periods": run(morphology, inertia)})
    emit({"provenance": {"script": "references/grid_model.py",
                         "method": "numpy: eq 44 with brute-force grid contact 90x180 (centred nodes), RK4 160 steps "
                                   "per period, quaternion renormalised each step; inertia from references/massprops.json",
                         "state": "quaternion (w, x, y, z), then body angular velocity",
                         "scene": {"g": G, "A1": A1, "A2": A2, "omega": OMEGA, "psi": PSI, "damping": DAMPING,
                                   "mass": MASS, "R0": "identity", "omega0": [0, 0, 0]},
                         **versions()},
          "cases": cases})


if __name__ == "__main__":
    main()
