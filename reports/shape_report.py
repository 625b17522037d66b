#!/usr/bin/python3
"""The shape study of both Table 1 bodies (`make run`): Figure 1 and a summary, from the JSON and
CSV that `gomboc shape` wrote into OUT. Recomputes no physics."""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import load_json, load_radial_map, save_figure, shape_summary_lines, write_atomically  # noqa: E402


def figure_one(out, maps):
    fig = plt.figure(figsize=(11, 8))
    for row, (name, data) in enumerate(maps):
        shape = (90, 180)
        x, y, z, r = (np.array(data[k]).reshape(shape) for k in ("x", "y", "z", "r"))
        ax = fig.add_subplot(2, 2, 2 * row + 1, projection="3d")
        colours = plt.cm.viridis((r - r.min()) / (r.max() - r.min()))
        ax.plot_surface(x, y, z, facecolors=colours, rstride=2, cstride=2, linewidth=0, antialiased=False)
        ax.set_box_aspect((1, 1, 1))
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_zlabel("z [m]")
        ax.set_title(f"Gömböc {name}: surface coloured by r")
        scale = plt.cm.ScalarMappable(cmap="viridis", norm=plt.Normalize(r.min(), r.max()))
        fig.colorbar(scale, ax=ax, shrink=0.7, pad=0.1, label="r [m]")
        ax2 = fig.add_subplot(2, 2, 2 * row + 2)
        phi, theta = np.array(data["phi"]).reshape(shape), np.array(data["theta"]).reshape(shape)
        mesh = ax2.pcolormesh(theta, phi, r, shading="auto", cmap="viridis")
        ax2.invert_yaxis()
        ax2.set_xlabel("θ [rad]")
        ax2.set_ylabel("φ [rad]")
        ax2.set_title(f"Gömböc {name}: radial map r(φ, θ)")
        fig.colorbar(mesh, ax=ax2, label="r [m]")
    fig.subplots_adjust(hspace=0.35)
    save_figure(fig, os.path.join(out, "fig1-morphologies.png"))
    plt.close(fig)


def main():
    out = sys.argv[1]
    shapes = [(name, load_json(os.path.join(out, f"shape-{name}.json"))) for name in ("I", "II")]
    maps = [(name, load_radial_map(os.path.join(out, f"radial-map-{name}.csv"))) for name in ("I", "II")]
    figure_one(out, maps)
    lines = ["# Shape study of the two Table 1 bodies (β = {:g})".format(shapes[0][1]["beta"]), "",
             "Written by `make run` from `gomboc shape --json` (reports/out/shape-I.json, shape-II.json).", "",
             "![Figure 1](fig1-morphologies.png)", ""]
    for name, shape in shapes:
        lines += [f"## Gömböc {name}", ""] + shape_summary_lines(shape) + [""]
    write_atomically(os.path.join(out, "shape.md"), "\n".join(lines))


if __name__ == "__main__":
    main()
