#!/usr/bin/python3
"""The body in motion: a short animation of a run, drawn from what `gomboc run` wrote.

usage: animate.py OUT NAME [--surface FILE] [--seconds S] [--fps F]

Reads OUT/NAME-summary.json and OUT/NAME-history.csv (the attitude quaternion q, the centroid's height
ζ, the contact point r_c and the second point Q, the points on the plane) and the body's surface: a smooth
body's radial map (`gomboc shape --radial-map`: x, y, z on a 90 x 180 grid; default OUT/radial-map-NAME.csv)
or a mesh body's hull triangles (`gomboc shape --faces`: default OUT/faces-NAME.csv). Each frame draws the
plane, then the body in its attitude R(q) with its centroid at height ζ above the plane z = 0 (the view
follows the centroid: the history holds no horizontal position), then on top of both the contact point
R r_c, the crease P-Q on two points, and the gap while in flight. The first S seconds of the run (default 4)
at F frames a second of simulated time (default 25). Writes OUT/NAME-animation.mp4 through ffmpeg where
Debian's ffmpeg is installed, else OUT/NAME-animation.gif through Pillow (a GIF counts time in hundredths
of a second: each frame's delay is rounded so that the frames' times stay within 10 ms of k/F); and
OUT/NAME-animation.json: the file, the history's checksum it was drawn from, the frame delays read back
from the file, and for every frame the history row, R, the contact point drawn, where it lands on the image
and the colour there, and the lowest point of the drawn surface (verify/figures.c checks them). Recomputes
no physics.
"""
import json
import os
import shutil
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import animation  # noqa: E402
from mpl_toolkits.mplot3d import proj3d  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402
import numpy  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import help_requested, input_errors, load_json, load_radial_map, load_table, previous_files, write_atomically  # noqa: E402


def rotation(q):
    """R(q) for a unit quaternion (w, x, y, z), body axes to inertial axes (gb_dynamics_rotation)."""
    w, x, y, z = q
    return numpy.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def exact_delays(path, fps):
    """Rewrites the GIF at path with each frame's delay rounded so that frame k starts within 10 ms of k/fps (a GIF
    counts hundredths of a second; one delay for all would drift: 1/15 s stored as 60 ms is 10 % fast); returns the
    delays read back from the file [ms]."""
    from PIL import Image, ImageSequence
    with Image.open(path) as movie:
        images = [frame.copy() for frame in ImageSequence.Iterator(movie)]
    starts = [int(round(100.0 * k / fps)) * 10 for k in range(len(images) + 1)]
    delays = [b - a for a, b in zip(starts, starts[1:])]
    images[0].save(path, save_all=True, append_images=images[1:], duration=delays, loop=0, disposal=2)
    with Image.open(path) as movie:
        return [frame.info.get("duration", 0) for frame in ImageSequence.Iterator(movie)]


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
    surface_path = opts["--surface"] or next((path for path in (os.path.join(out, f"faces-{name}.csv"),
                                                                os.path.join(out, f"radial-map-{name}.csv"))
                                              if os.path.exists(path)), None)
    if not surface_path or not os.path.exists(surface_path):
        sys.exit(f"animate.py: no surface {surface_path or f'{out}/radial-map-{name}.csv or {out}/faces-{name}.csv'} "
                 "(allowed: --surface FILE, a radial map of `gomboc shape --scene SCENE --radial-map FILE` or a mesh's "
                 "faces of `gomboc shape --scene SCENE --faces FILE`)")
    surface = load_radial_map(surface_path)
    if "x0" in surface:  # a mesh's hull triangles, body axes about the centroid
        triangles = numpy.array([[surface[f"{c}{k}"] for c in "xyz"] for k in range(3)]).transpose(2, 0, 1)
        body = triangles.reshape(-1, 3)
    else:
        triangles = None
        body = numpy.array([surface["x"], surface["y"], surface["z"]]).T
    seconds, fps = float(opts["--seconds"]), float(opts["--fps"])
    t = h["t"]
    stop = numpy.searchsorted(t, min(seconds, t[-1]), side="right")
    rows = numpy.unique(numpy.searchsorted(t[:stop], numpy.arange(0.0, t[stop - 1] + 1e-12, 1.0 / fps)))
    rows = rows[rows < stop]
    reach = 1.15 * numpy.max(numpy.linalg.norm(body, axis=1))
    top = reach + float(numpy.max(h["zeta"][:stop]))

    fig = plt.figure(figsize=(6, 6))
    ax = fig.add_subplot(projection="3d", computed_zorder=False)  # drawn in the order given: plane, body, contact
    frames = []
    marker = numpy.array(matplotlib.colors.to_rgb("tab:red")) * 255

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
        ax.plot_surface(gx, gy, numpy.zeros_like(gx), color="0.85", alpha=0.5, linewidth=0, zorder=0)
        if triangles is None:
            shape = (90, 180)
            ax.plot_surface(world[:, 0].reshape(shape), world[:, 1].reshape(shape), world[:, 2].reshape(shape),
                            rstride=3, cstride=3, color="tab:olive", linewidth=0, alpha=0.8, shade=True, zorder=1)
        else:
            ax.add_collection3d(Poly3DCollection(world.reshape(-1, 3, 3), facecolor="tab:olive", edgecolor="0.25",
                                                 linewidth=0.5, alpha=0.8, zorder=1))
        contacts = int(h["contacts"][row])
        if contacts > 0:
            ax.scatter([p[0]], [p[1]], [p[2]], color="tab:red", s=40, depthshade=False, zorder=10)
        if contacts == 2:
            q = R @ numpy.array([h["rq_x"][row], h["rq_y"][row], h["rq_z"][row]]) + numpy.array([0.0, 0.0, zeta])
            ax.plot([p[0], q[0]], [p[1], q[1]], [p[2], q[2]], color="tab:red", lw=2, zorder=10)
        ax.set_xlim(-reach, reach)
        ax.set_ylim(-reach, reach)
        ax.set_zlim(0.0, max(top, 2 * reach))
        ax.set_box_aspect((1, 1, max(top, 2 * reach) / (2 * reach)))
        ax.locator_params(nbins=4)  # ticks that do not run into each other
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
        return p if contacts > 0 else None

    def where_drawn(p, image):
        """The image pixel (column, row from the top) of the point p and the colour of the 5 x 5 pixels around it
        nearest the marker's."""
        x2, y2, _ = proj3d.proj_transform(p[0], p[1], p[2], ax.get_proj())
        column, height = ax.transData.transform((x2, y2)), image.shape[0]
        c, r = int(round(column[0])), int(round(height - column[1]))
        patch = image[max(r - 2, 0):r + 3, max(c - 2, 0):c + 3, :3].reshape(-1, 3).astype(float)
        nearest = patch[numpy.argmin(numpy.linalg.norm(patch - marker, axis=1))] if len(patch) else numpy.full(3, numpy.nan)
        return [c, r], nearest.tolist()

    gif = not shutil.which("ffmpeg")
    path = f"{name}-animation.gif" if gif else f"{name}-animation.mp4"
    writer = animation.PillowWriter(fps=fps) if gif else animation.FFMpegWriter(fps=fps)
    temporary = os.path.join(out, f".{path}.tmp{os.path.splitext(path)[1]}")
    with writer.saving(fig, temporary, dpi=fig.dpi):
        for k in range(len(rows)):
            p = draw(k)
            writer.grab_frame()
            if p is not None:
                image = numpy.asarray(fig.canvas.buffer_rgba())
                frames[-1]["contact_pixel"], frames[-1]["contact_colour"] = where_drawn(p, image)
    plt.close(fig)
    delays = exact_delays(temporary, fps) if gif else None
    earlier = previous_files(out, f"{name}-animation.json", key="file")
    os.replace(temporary, os.path.join(out, path))
    for other in earlier - {path}:  # an earlier run's other format, as this script's own manifest names it
        if os.path.exists(os.path.join(out, other)):
            os.remove(os.path.join(out, other))
    write_atomically(os.path.join(out, f"{name}-animation.json"), json.dumps(
        {"scene": name, "file": path, "history_fnv1a64": files[f"{name}-history.csv"]["fnv1a64"],
         "surface": os.path.basename(surface_path), "surface_kind": "faces" if triangles is not None else "radial map",
         "seconds": float(t[rows[-1]]), "fps": fps, "marker_colour": marker.tolist(), "delays_ms": delays,
         "frames": frames}))
    print(f"animate: {os.path.join(out, path)} ({len(rows)} frames of {t[rows[-1]]:.2f} s)")


if __name__ == "__main__":
    input_errors(main)
