#!/usr/bin/python3
"""The shape study of the body of every scene `make run` runs: Figure 1 for the smooth bodies and a
summary of each, from the JSON and CSV that `gomboc shape --scene` wrote into OUT (shape-SCENE.json,
radial-map-SCENE.csv). Usage: shape_report.py OUT SCENE... Recomputes no physics."""
import json
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import load_json, load_radial_map, save_figure, shape_summary_lines, write_atomically  # noqa: E402


def body_name(shape):
    """The paper's bodies by their morphology (Gömböc I), one's own by what defines them."""
    if "mesh" in shape:
        return f"the polyhedron of {os.path.basename(shape['mesh'])}"
    m = shape["morphology"]
    return f"Gömböc {m}" if m in ("I", "II") else m


def figure_one(out, maps):
    fig = plt.figure(figsize=(11, 4 * len(maps)))
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
        ax.set_title(f"{name}: surface coloured by r", fontsize=9)
        scale = plt.cm.ScalarMappable(cmap="viridis", norm=plt.Normalize(r.min(), r.max()))
        fig.colorbar(scale, ax=ax, shrink=0.7, pad=0.2, label="r [m]")  # clear of the z axis's label
        ax2 = fig.add_subplot(2, 2, 2 * row + 2)
        phi, theta = np.array(data["phi"]).reshape(shape), np.array(data["theta"]).reshape(shape)
        mesh = ax2.pcolormesh(theta, phi, r, shading="auto", cmap="viridis")
        ax2.invert_yaxis()
        ax2.set_xlabel("θ [rad]")
        ax2.set_ylabel("φ [rad]")
        ax2.set_title(f"{name}: radial map r(φ, θ)", fontsize=9)
        fig.colorbar(mesh, ax=ax2, label="r [m]")
    fig.subplots_adjust(hspace=0.35)
    facts = save_figure(fig, os.path.join(out, "fig1-morphologies.png"))
    plt.close(fig)
    return facts


def mesh_summary_lines(shape):
    """Markdown lines for a polyhedron's study (`gomboc shape --mesh` / `--scene` with a mesh)."""
    return [
        f"- {shape['format']} mesh of {shape['mesh_vertices']:.0f} vertices; convex hull of "
        f"{shape['hull_vertices']:.0f} vertices and {shape['hull_triangles']:.0f} triangles",
        f"- mass {shape['mass']:g} kg, volume {shape['volume']:.6g} m³ (divergence theorem, closed form)",
        "- inertia about the centroid: " + "; ".join(
            "[" + ", ".join(f"{v:.6g}" for v in row) + "]" for row in shape["inertia"]),
        f"- rests stably on {shape['rest_face_count']:.0f} faces (the centroid over the face, clear of its edges)",
    ]


def main():
    out, scenes = sys.argv[1], sys.argv[2:]
    bodies = {}  # one entry a body: the scenes that use it, and its study
    for scene in scenes:
        shape = load_json(os.path.join(out, f"shape-{scene}.json"))
        key = shape.get("mesh") or (shape["morphology"], shape["beta"])
        bodies.setdefault(key, ([], shape, scene))[0].append(scene)
    maps = [(body_name(shape), load_radial_map(os.path.join(out, f"radial-map-{first}.csv")))
            for _, shape, first in bodies.values() if "mesh" not in shape]
    if maps:  # Fig 1 and what a reader sees of it (verify/figures.c checks the layout)
        facts = figure_one(out, maps)
        write_atomically(os.path.join(out, "shape-figures.json"), json.dumps(
            {"figures": [{"kind": "fig1-morphologies", "file": "fig1-morphologies.png", "layout": facts}]}, indent=1))
    lines = ["# Shape study of the bodies of the scenes `make run` runs", "",
             "Written by `make run` from `gomboc shape --scene SCENE --json` (reports/out/shape-SCENE.json), one "
             "body a section, with the scenes that use it.", ""]
    if maps:
        lines += ["![Figure 1](fig1-morphologies.png)", ""]
    for users, shape, _ in bodies.values():
        beta = "" if "mesh" in shape else f", β = {shape['beta']:g}"
        lines += [f"## {body_name(shape)}{beta}", "", "Scenes: " + ", ".join(f"`{u}`" for u in users), ""]
        lines += (mesh_summary_lines(shape) if "mesh" in shape else shape_summary_lines(shape)) + [""]
    write_atomically(os.path.join(out, "shape.md"), "\n".join(lines))


if __name__ == "__main__":
    main()
