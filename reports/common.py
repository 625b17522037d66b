"""Helpers shared by the report generators: atomic writes and reading gomboc's outputs."""
import csv
import json
import os


def write_atomically(path, text):
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w", encoding="utf-8") as handle:
        handle.write(text)
    os.replace(tmp, path)


def save_figure(fig, path):
    tmp = f"{path}.tmp{os.getpid()}.png"
    fig.savefig(tmp, dpi=110, bbox_inches="tight")
    os.replace(tmp, path)


def load_json(path):
    with open(path, encoding="utf-8") as handle:
        return json.load(handle)


def load_radial_map(path):
    """Columns phi, theta, r, x, y, z as written by `gomboc shape --radial-map` (90 x 180 grid)."""
    with open(path, encoding="utf-8") as handle:
        rows = [row for row in csv.reader(line for line in handle if not line.startswith("#"))]
    header, body = rows[0], rows[1:]
    columns = {name: [float(row[i]) for row in body] for i, name in enumerate(header)}
    return columns


def digits(value, places):
    """value with `places` decimals, a value that rounds to zero printed as 0 (no "-0.0000000000")."""
    return f"{0.0 if abs(value) < 0.5 * 10.0 ** -places else value:.{places}f}"


def shape_summary_lines(shape):
    """Markdown lines stating what `gomboc shape --json` measured for one body."""
    hull = shape["hull_equilibria"]
    eqs = ", ".join(f"{e['type']} at (φ, θ) = ({e['phi']:.6f}, {e['theta']:.6f}), r = {e['r']:.9f}"
                    for e in shape["equilibria"])
    rests = "; ".join(f"normal ({r['normal'][0]:.4f}, {r['normal'][1]:.4f}, {r['normal'][2]:.4f}), "
                      f"centroid height {r['height']:.6f}" for r in hull["rests"])
    return [
        f"- volume {shape['volume']:.13f} (± {shape['volume_error']:.1e}); L (eq 53) {shape['L']:.13f}",
        f"- centroid ({shape['centroid'][0]:.1e}, {shape['centroid'][1]:.1e}, {shape['centroid'][2]:.1e})"
        f" (± {max(shape['centroid_error']):.1e}): " + (
            "at the origin to quadrature accuracy" if all(
                abs(c) <= e for c, e in zip(shape["centroid"], shape["centroid_error"]))
            else "**off the origin by more than the quadrature error**"),
        "- inertia about the centroid, m = {:g}: ".format(shape["mass"]) + "; ".join(
            "[" + ", ".join(digits(v, 10) for v in row) + "]" for row in shape["inertia"]),
        f"- minimum Gaussian curvature {shape['curvature_min']:.6f} at (φ, θ) = "
        f"({shape['curvature_min_at'][0]:.6f}, {shape['curvature_min_at'][1]:.6f}); "
        f"K < 0 on {100 * shape['negative_curvature_fraction']:.2f} % of the area",
        (f"- strictly convex only for β < {shape['convexity_beta_limit']:.10f}; convex at this β: "
         if shape["convexity_beta_limit"] is not None else
         f"- convexity limit in β not computed ({shape.get('convexity_beta_limit_note', '')}); convex at this β: ")
        + f"**{'yes' if shape['convex'] else 'no'}**",
        f"- critical points of r: {eqs}",
        f"- convex hull ({hull['sample'][0]:.0f} × {hull['sample'][1]:.0f} sample, "
        f"{100 * hull['sampled_fraction_on_hull']:.1f} % of the sample on the hull): "
        f"{hull['stable']:.0f} stable and {hull['unstable']:.0f} unstable robust equilibria "
        f"(raw polyhedral: {hull['raw_stable']:.0f}, {hull['raw_unstable']:.0f}); rests: {rests}",
        f"- mono-monostatic: **{'yes' if shape['mono_monostatic'] else 'no'}**",
    ]


def layout(row, lead=" ("):
    """How an exponent's record was laid out (src/gb_lyapunov.h: warm-up by MSER-5, batches chosen from the
    record), as the report prints it beside the exponent; empty for a record written without it."""
    if "warmup_intervals" not in row:
        return ""
    text = f"warm-up {row['warmup_intervals']:.0f}, {row['batches']:.0f} batches"
    if not row.get("warmup_found", True):
        text += ", warm-up not found"
    return f"{lead}{text}{')' if lead == ' (' else ''}"


def finish_figure(fig, path):
    """Lay out, save (atomically, as save_figure does) and close a figure."""
    import matplotlib.pyplot as plt
    fig.tight_layout()
    save_figure(fig, path)
    plt.close(fig)


def section_start(out, title, name, missing):
    """A report section's heading and its data file OUT/name: (lines, data), data None (and the lines saying
    `missing`) when the harness did not write it."""
    lines = [f"## {title}", ""]
    path = os.path.join(out, name)
    if not os.path.exists(path):
        return lines + [f"({missing})", ""], None
    return lines, load_json(path)
