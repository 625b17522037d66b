"""A grid polyhedron of the project rigid on a plane that can only push, run by Siconos's kernel.

The body is built from the project's own outputs: `gomboc shape --json` gives the mass, centroid and
inertia tensor about the centroid, `gomboc shape --grid-nodes` the 90 x 180 nodes of the scenes' contact
grid to the last bit. Only the vertices of the nodes' convex hull (scipy's Qhull) can touch a plane.

Siconos (Debian's python3-siconos, its kernel): one NewtonEulerDS (the centroid's position and the
attitude quaternion; the velocity of the centroid and the angular velocity in body axes) and, for each
hull vertex near the plane, one interaction whose relation is an exact vertex-plane relation: a
NewtonEuler3DR whose h is the vertex's height above the plane, its contact point the vertex and its
normal the plane's (Bullet, Siconos's usual contact detector, is not used: Debian links its single-
precision build, whose plane contact quantises the gap in 1.2e-4 m steps and whose polyhedron contact
sits 2.4e-3 m off the vertex). Newton's impact law with Coulomb friction (NewtonImpactFrictionNSL,
e = 0: plastic), Moreau-Jean (theta = 1/2) and a three-dimensional friction-contact problem solved by
NSGS to 1e-12 at each step.

The plane's frame: the plane at rest, gravity g_eff(t) = g + a1 cos(wt) + a2 cos(2wt + psi) (the
forcing of src/gb_forcing.c) set at each step's midpoint; the damping torque -c omega (eq 42) set at each
step's start (explicit: the scheme's order is one anyway).

The interactions follow the body: before each step every hull vertex below ACTIVE_ON (1 mm) gets one
and a vertex above ACTIVE_OFF (2 mm) loses it; a step that would carry a vertex without an interaction
below the plane is an error (the run says so and stops), so the active set never hides a contact.
"""
import configparser
import json
import math
import os
import subprocess
import tempfile
import time

import numpy
from scipy.spatial import ConvexHull

import siconos.kernel as sk
import siconos.numerics as sn

ACTIVE_ON, ACTIVE_OFF = 1e-3, 2e-3   # [m] a hull vertex gets an interaction below ACTIVE_ON, loses it above ACTIVE_OFF
SOLVER_TOL = 1e-12                    # NSGS's relative residual


def read_scene(path):
    """The keys of a case file that the mechanics needs (the same file gomboc runs)."""
    ini = configparser.ConfigParser(inline_comment_prefixes=(";",), comment_prefixes=(";", "#"))
    ini.read(path, encoding="utf-8")
    g = ini.getfloat("forcing", "g")
    units = ini.get("forcing", "amplitude_units", fallback="m/s2")
    scale = g if units == "g" else 1.0
    psi_text = ini.get("forcing", "psi", fallback="0").replace("pi", str(math.pi))
    friction = ini.get("model", "friction", fallback="rough")
    attitude = ini.get("initial", "attitude", fallback="identity")
    axis, angle = numpy.array([1.0, 0.0, 0.0]), 0.0
    if attitude.startswith("axis-angle"):
        values = [float(v) for v in attitude.split(None, 1)[1].split(",")]
        axis, angle = numpy.array(values[:3]), values[3]
    return {
        "path": path,
        "morphology": ini.get("body", "morphology"), "beta": ini.getfloat("body", "beta"),
        "mass": ini.getfloat("body", "mass", fallback=1.0),
        "g": g, "a1": ini.getfloat("forcing", "A1") * scale, "a2": ini.getfloat("forcing", "A2") * scale,
        "omega": ini.getfloat("forcing", "omega"), "psi": float(eval(psi_text, {"__builtins__": {}})),
        "damping": ini.getfloat("model", "damping", fallback=0.02),
        "restitution": ini.getfloat("model", "restitution", fallback=0.0),
        "friction": friction, "steps_per_period": ini.getint("integrator", "steps_per_period"),
        "periods": ini.getfloat("integrator", "periods"),
        "axis": axis / numpy.linalg.norm(axis), "angle": angle,
    }


def read_body(gomboc, scene):
    """Mass properties and hull vertices (about the centroid, body axes) from the gomboc command."""
    args = ["--morphology", scene["morphology"], "--beta", repr(scene["beta"]), "--mass", repr(scene["mass"])]
    with tempfile.TemporaryDirectory() as scratch:
        nodes_path = os.path.join(scratch, "nodes.csv")
        out = subprocess.run([gomboc, "shape", *args, "--json", "--grid-nodes", nodes_path], check=True,
                             capture_output=True, text=True).stdout
        nodes = numpy.loadtxt(nodes_path, delimiter=",", comments="#", skiprows=2, usecols=(3, 4, 5))
    shape = json.loads(out)
    centroid = numpy.array(shape["centroid"])
    hull = ConvexHull(nodes)
    vertices = numpy.array(sorted(hull.vertices))
    return {"mass": shape["mass"], "inertia": numpy.array(shape["inertia"]), "centroid": centroid,
            "nodes": nodes, "hull": vertices, "points": nodes[vertices] - centroid}


def rotation(axis, angle):
    """Rodrigues's rotation, body to inertial (as src/gb_case.c reads [initial] attitude)."""
    k = numpy.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    return numpy.eye(3) + math.sin(angle) * k + (1.0 - math.cos(angle)) * (k @ k)


def quaternion_matrix(q):
    w, x, y, z = q
    return numpy.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


class VertexPlane(sk.NewtonEuler3DR):
    """An exact vertex-plane relation: h is the height of one body point; contact point and normal follow."""

    def __init__(self, point):
        sk.NewtonEuler3DR.__init__(self)
        self.point = numpy.array(point, dtype=float)

    def computeh(self, time, q0, y):  # noqa: N802 (Siconos's name)
        q = numpy.asarray(q0, dtype=float).ravel()[:7]
        position = q[:3] + quaternion_matrix(q[3:7]) @ self.point
        self.pc1()[:] = position
        self.pc2()[:] = (position[0], position[1], 0.0)
        self.nc()[:] = (0.0, 0.0, 1.0)
        y[0] = position[2]


def moreau_jean(ds, t_end, h, tolerance, iterations):
    """The body ds alone in a system up to t_end, stepped by Moreau-Jean (theta = 1/2) at h with a three-dimensional
    friction-contact problem solved by NSGS to `tolerance` in at most `iterations`: (system, problem, simulation)."""
    nsds = sk.NonSmoothDynamicalSystem(0.0, t_end)
    nsds.insertDynamicalSystem(ds)
    problem = sk.FrictionContact(3, sn.SICONOS_FRICTION_3D_NSGS)
    problem.numericsSolverOptions().dparam[sn.SICONOS_DPARAM_TOL] = tolerance
    problem.numericsSolverOptions().iparam[sn.SICONOS_IPARAM_MAX_ITER] = iterations
    return nsds, problem, sk.TimeStepping(nsds, sk.TimeDiscretisation(0.0, h), sk.MoreauJeanOSI(0.5), problem)


def geff(scene, t):
    return scene["g"] + scene["a1"] * math.cos(scene["omega"] * t) + scene["a2"] * math.cos(2.0 * scene["omega"] * t + scene["psi"])


def simulate(scene, body, h, t_end, attitude=None, stop_at_rest=True, ledger=False):
    """One Moreau-Jean run. Returns the record: per step the number of vertices carrying the body (a positive
    normal impulse) and the kinetic energy, the events where a vertex starts to carry it, and with `ledger`
    the energy impacts and friction took (the mechanical energy's fall less the damping's and the changing
    weight's work, midpoint sums)."""
    mass, inertia, points = body["mass"], body["inertia"], body["points"]
    R0 = rotation(scene["axis"], scene["angle"]) if attitude is None else attitude
    heights0 = (points @ R0.T)[:, 2]
    q_att = _quaternion_from_matrix(R0)
    q0 = numpy.concatenate([[0.0, 0.0, -heights0.min()], q_att])
    ds = sk.NewtonEulerDS(q0, numpy.zeros(6), mass, inertia)
    ds.setFExtPtr(numpy.array([0.0, 0.0, -mass * geff(scene, 0.5 * h)]))
    ds.setMExtPtr(numpy.zeros(3))
    mu = 10.0 if scene["friction"] == "rough" else float(scene["friction"])
    nsds, problem, sim = moreau_jean(ds, t_end + 2.0 * h, h, SOLVER_TOL, 10000)
    law = sk.NewtonImpactFrictionNSL(scene["restitution"], 0.0, mu, 3)
    active = {}

    def refresh(q):
        z = q[2] + (points @ quaternion_matrix(q[3:7]).T)[:, 2]
        for k in numpy.nonzero(z < ACTIVE_ON)[0]:
            if k not in active:
                relation = VertexPlane(points[k])   # kept: Siconos calls back into this Python object
                inter = sk.Interaction(law, relation)
                nsds.link(inter, ds)
                active[int(k)] = (inter, relation)
        for k in [k for k in active if z[k] > ACTIVE_OFF]:
            nsds.removeInteraction(active.pop(k)[0])
        outside = [k for k in range(len(z)) if k not in active and z[k] < 0.0]
        return z, outside

    record = {"h": h, "steps": 0, "carry": [], "kinetic": [], "events": [], "rest_time": None, "rest_face": None,
              "error": None, "residual_max": 0.0, "residual_over": 0, "rest_residual": None,
              "initial": [int(body["hull"][k]) for k in numpy.nonzero(heights0 - heights0.min() <= 1e-12)[0]]}
    carrying_before = set()
    lost = 0.0
    step = 0
    start, wall = time.process_time(), time.perf_counter()
    while step * h < t_end - 0.5 * h:
        q = numpy.array(ds.q(), dtype=float)
        _, outside = refresh(q)
        if outside:
            record["error"] = "a vertex without an interaction is below the plane at t = %.6f" % (step * h)
            break
        twist = numpy.array(ds.twist(), dtype=float)
        energy_before = 0.5 * mass * twist[:3] @ twist[:3] + 0.5 * twist[3:] @ inertia @ twist[3:] \
            + mass * geff(scene, step * h) * q[2]
        damping_work = -scene["damping"] * (twist[3:] @ twist[3:]) * h
        ds.setFExtPtr(numpy.array([0.0, 0.0, -mass * geff(scene, (step + 0.5) * h)]))
        ds.setMExtPtr(-scene["damping"] * twist[3:])
        approach = {k: float(inter.y(1)[0]) for k, (inter, _) in active.items()}
        sim.computeOneStep()
        residual = float(problem.numericsSolverOptions().dparam[sn.SICONOS_DPARAM_RESIDU])
        step += 1
        carrying = {k for k, (inter, _) in active.items() if float(inter.lambda_(1)[0]) > 0.0}
        twist = numpy.array(ds.twist(), dtype=float)
        kinetic = 0.5 * mass * twist[:3] @ twist[:3] + 0.5 * twist[3:] @ inertia @ twist[3:]
        if ledger:
            z_after = float(ds.q()[2])
            weight_work = mass * (geff(scene, step * h) - geff(scene, (step - 1) * h)) * 0.5 * (q[2] + z_after)
            lost += energy_before - (kinetic + mass * geff(scene, step * h) * z_after) + weight_work + damping_work
        for k in sorted(carrying - carrying_before, key=lambda k: approach.get(k, 0.0)):
            record["events"].append({"t": step * h, "vertex": int(body["hull"][k]), "approach": approach.get(k, 0.0),
                                     "kinetic_after": kinetic})
        record["carry"].append(len(carrying))
        record["kinetic"].append(kinetic)
        if len(carrying) >= 3 and kinetic < 1e-12 and record["rest_time"] is None:
            record["rest_time"] = step * h
            record["rest_face"] = sorted(int(body["hull"][k]) for k in carrying)
            # the step that brings the body to rest on three or more coplanar vertices (a singular Delassus
            # operator, where NSGS may stall short of its tolerance) is booked apart
            record["rest_residual"] = residual
            if stop_at_rest:
                sim.nextStep()
                break
        else:
            if kinetic >= 1e-12:
                record["rest_time"], record["rest_face"] = None, None
            record["residual_max"] = max(record["residual_max"], residual) if math.isfinite(residual) else math.inf
            record["residual_over"] += not residual <= SOLVER_TOL
        carrying_before = carrying
        sim.nextStep()
    record["steps"] = step
    if ledger:
        record["lost"] = lost
    record["seconds"] = time.process_time() - start   # CPU of every thread (Siconos's BLAS may use several)
    record["wall"] = time.perf_counter() - wall
    q = numpy.array(ds.q(), dtype=float)
    record["final_quaternion"] = q[3:7].tolist()
    record["final_position"] = q[:3].tolist()
    return record


def _quaternion_from_matrix(R):
    """Unit quaternion (w, x, y, z) of a rotation matrix (Shepperd's branch on the largest component)."""
    t = numpy.trace(R)
    if t > 0.0:
        s = 2.0 * math.sqrt(t + 1.0)
        return numpy.array([0.25 * s, (R[2, 1] - R[1, 2]) / s, (R[0, 2] - R[2, 0]) / s, (R[1, 0] - R[0, 1]) / s])
    i = int(numpy.argmax(numpy.diag(R)))
    j, k = (i + 1) % 3, (i + 2) % 3
    s = 2.0 * math.sqrt(1.0 + R[i, i] - R[j, j] - R[k, k])
    q = numpy.zeros(4)
    q[0] = (R[k, j] - R[j, k]) / s
    q[1 + i] = 0.25 * s
    q[1 + j] = (R[j, i] + R[i, j]) / s
    q[1 + k] = (R[k, i] + R[i, k]) / s
    return q
