#!/usr/bin/python3
"""Reference trajectory of the continuous-contact rolling model (docs/rolling.md) over a short horizon.

Independent of gomboc's C code except for the model it implements:
- the height h = ẑ_b·x and its derivatives come from sympy (references/contact.py: height_functions);
- the contact is Newton's method on ∇h = 0, started from the previous contact;
- ṙ_c comes from eq 72, d(φ, θ)/dt = −H⁻¹ [∂φx; ∂θx] ż_b with ż_b = −ω × z_b, in numpy;
- I_C comes from references/massprops.json (nested scipy quad);
- steps at most T/100 (the Newton start must stay in the contact's basin), first step T/1000;
- the rolling equation I_P ω̇ + ω × I_P ω − m r_c × (ṙ_c × ω) = m g_eff r_c × z_b − c ω and
  q̇ = ½ q ⊗ (0, ω) are integrated by scipy.integrate.solve_ivp (DOP853, rtol 1e-12, atol 1e-14).

Scene: Table 1 forcing read in m/s² (g 9.81, a1 2, a2 1, ω 18, ψ π/3), c 0.02, m 1, β 0.12, R0 = I,
ω0 = 0 (Table 1), one forcing period (no branch switch happens in it: solve_ivp would stop at the
jump), states every eighth of a period.
Run by `make references`; the output (JSON, on stdout) is committed as references/dynamics.json.
"""
import json
import math
import os
import sys

import numpy
import sympy
from scipy.integrate import solve_ivp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from contact import height_functions  # noqa: E402
from provenance import emit, versions  # noqa: E402

G, A1, A2, OMEGA, PSI, DAMPING, MASS, BETA = 9.81, 2.0, 1.0, 18.0, math.pi / 3, 0.02, 1.0, 0.12
OMEGA0 = (0.0, 0.0, 0.0)
PERIODS, SAMPLES_PER_PERIOD = 1, 8
CASES = ["I", "II"]


def rotation(q):
    w, x, y, z = q / numpy.linalg.norm(q)
    return numpy.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


class Body:
    def __init__(self, morphology, inertia):
        self.h, self.grad, self.hess = height_functions(morphology)
        self.inertia = numpy.array(inertia)
        self.contact = None  # (φ, θ) of the last contact, the next Newton start

    def position_derivatives(self, phi, theta):
        """x, ∂φx, ∂θx from the gradient of h with the three unit verticals."""
        axes = numpy.eye(3)
        x = numpy.array([self.h(phi, theta, BETA, *e) for e in axes])
        d = numpy.array([self.grad(phi, theta, BETA, *e) for e in axes], dtype=float)
        return x, d[:, 0], d[:, 1]

    def find_contact(self, zb):
        q = numpy.array(self.contact, dtype=float)
        for _ in range(50):
            g = numpy.array(self.grad(q[0], q[1], BETA, *zb), dtype=float)
            H = numpy.array(self.hess(q[0], q[1], BETA, *zb), dtype=float)
            step = numpy.linalg.solve(H, -g)
            q = q + step
            if numpy.linalg.norm(step) < 1e-15:
                break
        H = numpy.array(self.hess(q[0], q[1], BETA, *zb), dtype=float)
        if numpy.any(numpy.linalg.eigvalsh(H) <= 0):
            raise RuntimeError("contact is not a minimum")
        self.contact = (float(q[0]), float(q[1]))
        return q, H

    def rhs(self, t, y):
        quaternion, omega = y[:4], y[4:7]
        R = rotation(quaternion)
        zb = R[2, :]
        (phi, theta), H = self.find_contact(zb)
        x, x_phi, x_theta = self.position_derivatives(phi, theta)
        zb_dot = -numpy.cross(omega, zb)                                         # eq 24
        q_dot = -numpy.linalg.solve(H, numpy.array([x_phi @ zb_dot, x_theta @ zb_dot]))  # eq 72
        rc, rc_dot = x, x_phi * q_dot[0] + x_theta * q_dot[1]
        IP = self.inertia + MASS * (rc @ rc * numpy.eye(3) - numpy.outer(rc, rc))  # eq 40
        geff = G + A1 * math.cos(OMEGA * t) + A2 * math.cos(2 * OMEGA * t + PSI)   # eq 25
        torque = MASS * geff * numpy.cross(rc, zb) - DAMPING * omega                # eqs 41-43
        rhs = torque - numpy.cross(omega, IP @ omega) + MASS * numpy.cross(rc, numpy.cross(rc_dot, omega))
        omega_dot = numpy.linalg.solve(IP, rhs)
        w, a, b, c = quaternion
        quaternion_dot = 0.5 * numpy.array([-(a * omega[0] + b * omega[1] + c * omega[2]),
                                            w * omega[0] + b * omega[2] - c * omega[1],
                                            w * omega[1] + c * omega[0] - a * omega[2],
                                            w * omega[2] + a * omega[1] - b * omega[0]])
        return numpy.concatenate([quaternion_dot, omega_dot])


def initial_contact(body, zb):
    """Global minimum at the start: the lowest of a 180 × 360 grid, then Newton."""
    phis = (numpy.arange(180) + 0.5) * math.pi / 180
    thetas = numpy.arange(360) * 2 * math.pi / 360
    P, T = numpy.meshgrid(phis, thetas, indexing="ij")
    values = body.h(P, T, BETA, *zb)
    i, j = numpy.unravel_index(numpy.argmin(values), values.shape)
    body.contact = (float(phis[i]), float(thetas[j]))
    body.find_contact(zb)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "massprops.json"), encoding="utf-8") as handle:
        massprops = json.load(handle)
    period = 2 * math.pi / OMEGA
    times = [k * period / SAMPLES_PER_PERIOD for k in range(PERIODS * SAMPLES_PER_PERIOD + 1)]
    cases = []
    for morphology in CASES:
        entry = next(c for c in massprops["cases"] if c["morphology"] == morphology and c["beta"] == BETA)
        body = Body(morphology, entry["inertia"])
        y0 = numpy.array([1.0, 0.0, 0.0, 0.0, *OMEGA0])
        initial_contact(body, numpy.array([0.0, 0.0, 1.0]))
        solution = solve_ivp(body.rhs, (0.0, times[-1]), y0, method="DOP853", t_eval=times, rtol=1e-12, atol=1e-14,
                             first_step=period / 1000, max_step=period / 100)
        if not solution.success:
            raise RuntimeError(solution.message)
        cases.append({"morphology": morphology, "times": times,
                      "states": [[float(v) for v in solution.y[:, k]] for k in range(len(times))],
                      "rhs_evaluations": int(solution.nfev)})
    document = {
        "provenance": {
            "script": "references/dynamics.py",
            "method": "solve_ivp DOP853 rtol 1e-12 atol 1e-14; contact by Newton on sympy derivatives; "
                      "r_c rate by eq 72; rolling equation of docs/rolling.md; I_C from references/massprops.json",
            "scene": {"g": G, "a1": A1, "a2": A2, "omega": OMEGA, "psi": PSI, "damping": DAMPING, "mass": MASS,
                      "beta": BETA, "R0": "identity", "omega0": OMEGA0, "periods": PERIODS},
            "state": "quaternion (w, x, y, z) body to inertial, then body angular velocity",
            **versions(sympy=sympy),
        },
        "cases": cases,
    }
    emit(document)


if __name__ == "__main__":
    main()
