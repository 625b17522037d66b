#!/usr/bin/python3
"""The body in motion: a short animation of a run, drawn from what `gomboc run` wrote.

usage: animate.py OUT NAME [--surface FILE] [--seconds S] [--fps F]

Reads OUT/NAME-summary.json and OUT/NAME-history.csv (the attitude quaternion q, the centroid's height
ζ, the contact point r_c and the second point Q, the points on the plane) and the body's surface: the
radial map `gomboc shape --radial-map` wrote (x, y, z on a 90 x 180 grid; default OUT/radial-map-NAME.csv).
Each frame draws the surface in its attitude R(q) with its centroid at height ζ above the plane z = 0
(the view follows the centroid: the history holds no horizontal position), the contact point R r_c, the
crease P-Q on two points, and the gap while in flight. The first S seconds of the run (default 4) at F
frames a second of simulated time (default 25). Writes OUT/NAME-animation.mp4 through ffmpeg where
Debian's ffmpeg is installed, else OUT/NAME-animation.gif through Pillow; and OUT/NAME-animation.json: the
file, the history's checksum it was drawn from, and for every frame the history row, R, the contact point
drawn and the lowest point of the drawn surface (verify/figures.c checks them against the history).
Recomputes no physics.
"""
import json
import os
import shutil
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import animation  # noqa: E402
import numpy  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import help_requested, input_errors, load_json, load_radial_map, load_table, previous_files, write_atomically  # noqa: E402


def rotation(q):
    """R(q) for a unit quaternion (w, x, y, z), body axes to inertial axes (gb_dynamics_rotation)."""
    w, x, y, z = q
    return numpy.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def options(argv):
    args, opts = [], {"--surface": None, "--seconds": "4", "--fps": "25"}
    k = 0
    while k < len(argv):
        if argv[k] in opts:
            if k + 1 >= len(argv):
                sys.exit(f"animate.py: {argv[k]} needs a value")
            opts[argv[k]] = argv[k + 1]
            k += 2
        else:
            args.append(argv[k])
            k += 1
    if len(args) != 2:
        sys.exit(__doc__.split("\n\n")[1])
    return args[0], args[1], opts


def main(argv=None):
    """The command line's work on argv (else sys.argv[1:]); gomboc.plot.animate calls it in-process."""
    argv = list(sys.argv[1:] if argv is None else argv)
    help_requested(__doc__, argv)
    out, name, opts = options(argv)
    summary = load_json(os.path.join(out, f"{name}-summary.json"))
    files = {f["name"]: f for f in summary.get("files", [])}
    if f"{name}-history.csv" not in files:
        sys.exit(f"animate.py: the run {name} wrote no history (allowed: a scene with [output] history = yes)")
    h = load_table(os.path.join(out, f"{name}-history.csv"), required=("t",))
    if "q_w" not in h.dtype.names:
        sys.exit(f"animate.py: {name}-history.csv has no attitude columns (rerun the scene with this gomboc)")
    surface_path = opts["--surface"] or os.path.join(out, f"radial-map-{name}.csv")
    if not os.path.exists(surface_path):
        sys.exit(f"animate.py: no surface {surface_path} (allowed: --surface FILE, a radial map of "
                 "`gomboc shape --scene SCENE --radial-map FILE`)")
    surface = load_radial_map(surface_path)
    body = numpy.array([surface["x"], surface["y"], surface["z"]]).T  # body axes about the centroid
    seconds, fps = float(opts["--seconds"]), float(opts["--fps"])
    t = h["t"]
    stop = numpy.searchsorted(t, min(seconds, t[-1]), side="right")
    rows = numpy.unique(numpy.searchsorted(t[:stop], numpy.arange(0.0, t[stop - 1] + 1e-12, 1.0 / fps)))
    rows = rows[rows < stop]
    reach = 1.15 * numpy.max(numpy.linalg.norm(body, axis=1))
    top = reach + float(numpy.max(h["zeta"][:stop]))

    fig = plt.figure(figsize=(6, 6))
    ax = fig.add_subplot(projection="3d")
    frames = []

    def draw(k):
        row = int(rows[k])
        R = rotation((h["q_w"][row], h["q_x"][row], h["q_y"][row], h["q_z"][row]))
        zeta = h["zeta"][row]
        world = body @ R.T + numpy.array([0.0, 0.0, zeta])
        rc = numpy.array([h["rc_x"][row], h["rc_y"][row], h["rc_z"][row]])
        p = R @ rc + numpy.array([0.0, 0.0, zeta])
        ax.cla()
        grid = numpy.linspace(-reach, reach, 2)
        gx, gy = numpy.meshgrid(grid, grid)
        ax.plot_surface(gx, gy, numpy.zeros_like(gx), color="0.85", alpha=0.5, linewidth=0)
        shape = (90, 180)
        ax.plot_surface(world[:, 0].reshape(shape), world[:, 1].reshape(shape), world[:, 2].reshape(shape),
                        rstride=3, cstride=3, color="tab:olive", linewidth=0, alpha=0.9, shade=True)
        contacts = int(h["contacts"][row])
        if contacts > 0:
            ax.scatter([p[0]], [p[1]], [p[2]], color="tab:red", s=30, depthshade=False)
        if contacts == 2:
            q = R @ numpy.array([h["rq_x"][row], h["rq_y"][row], h["rq_z"][row]]) + numpy.array([0.0, 0.0, zeta])
            ax.plot([p[0], q[0]], [p[1], q[1]], [p[2], q[2]], color="tab:red", lw=2)
        ax.set_xlim(-reach, reach)
        ax.set_ylim(-reach, reach)
        ax.set_zlim(0.0, max(top, 2 * reach))
        ax.set_box_aspect((1, 1, max(top, 2 * reach) / (2 * reach)))
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_zlabel("z [m]")
        state = {0: f"in flight, gap {h['clearance'][row]:.3g} m", 1: "on one point", 2: "on two points (the crease)",
                 3: "at rest on three points"}.get(contacts, f"{contacts} points")
        ax.set_title(f"{name}\nt = {t[row]:.3f} s: {state}", fontsize=9)
        low = int(numpy.argmin(world[:, 2]))
        frames.append({"frame": k, "row": row, "t": float(t[row]), "R": R.tolist(), "zeta": float(zeta),
                       "contact_drawn": p.tolist() if contacts > 0 else None, "contacts": contacts,
                       "lowest_drawn": world[low].tolist()})
        return []

    movie = animation.FuncAnimation(fig, draw, frames=len(rows), blit=False)
    if shutil.which("ffmpeg"):
        path, writer = f"{name}-animation.mp4", animation.FFMpegWriter(fps=fps)
    else:
        path, writer = f"{name}-animation.gif", animation.PillowWriter(fps=fps)
    temporary = os.path.join(out, f".{path}.tmp{os.path.splitext(path)[1]}")
    movie.save(temporary, writer=writer)
    plt.close(fig)
    earlier = previous_files(out, f"{name}-animation.json", key="file")
    os.replace(temporary, os.path.join(out, path))
    for other in earlier - {path}:  # an earlier run's other format, as this script's own manifest names it
        if os.path.exists(os.path.join(out, other)):
            os.remove(os.path.join(out, other))
    frames = frames[-len(rows):]  # matplotlib may draw the first frame twice (its initial draw)
    write_atomically(os.path.join(out, f"{name}-animation.json"), json.dumps(
        {"scene": name, "file": path, "history_fnv1a64": files[f"{name}-history.csv"]["fnv1a64"],
         "surface": os.path.basename(surface_path), "seconds": float(t[rows[-1]]), "fps": fps, "frames": frames}))
    print(f"animate: {os.path.join(out, path)} ({len(rows)} frames of {t[rows[-1]]:.2f} s)")


if __name__ == "__main__":
    input_errors(main)
