"""Helpers shared by the report generators: atomic writes and reading gomboc's outputs.

A writer removes only what its own previous manifest lists (previous_files), writes every file atomically, and
answers a malformed input with one line naming the file, the row and the column (InputError, exit 2; input_errors
turns it into that line), never a traceback."""
import csv
import json
import math
import os
import sys

import numpy


class InputError(Exception):
    """A malformed input file: the message names the file, the row and the column."""


def help_requested(doc, argv=None):
    """-h or --help among the arguments (argv, else the command line's): the script's own text (its usage first) on
    standard output, exit 0."""
    if any(a in ("-h", "--help") for a in (sys.argv[1:] if argv is None else argv)):
        sys.stdout.write(doc.strip() + "\n")
        sys.exit(0)


def input_errors(main):
    """Run main(); an InputError (or a JSON file that is not JSON) is one line on stderr and exit 2."""
    try:
        return main()
    except InputError as e:
        sys.stderr.write(f"{os.path.basename(sys.argv[0])}: {e}\n")
        sys.exit(2)


def is_number(value):
    try:
        float(value)
        return True
    except ValueError:
        return False


def load_table(path, required=(), text=()):
    """A CSV gomboc wrote, as a numpy structured array (a row a record, named columns): every row as long as the
    header, every value a number but those of the `text` columns, the `required` columns present and at least
    one row; else InputError naming the file, row (the file's line) and column."""
    try:
        with open(path, encoding="utf-8", newline="") as handle:
            rows = list(csv.reader(handle))
    except OSError as e:
        raise InputError(f"{path}: {e.strerror}") from None
    except (UnicodeDecodeError, csv.Error) as e:
        raise InputError(f"{path}: not a CSV file ({e})") from None
    if not rows or not rows[0]:
        raise InputError(f"{path}:1: no header (allowed: a CSV gomboc wrote, its header first)")
    header = rows[0]
    for column in required:
        if column not in header:
            raise InputError(f"{path}:1: no column '{column}' (allowed: a file this gomboc wrote, whose header has it)")
    if len(rows) < 2:
        raise InputError(f"{path}:2: no rows after the header (allowed: at least one row)")
    body = rows[1:]
    dtype = [(name, "U64" if name in text else "f8") for name in header]
    table = numpy.zeros(len(body), dtype=dtype)
    try:
        if any(len(row) != len(header) for row in body):
            raise ValueError
        for name, values in zip(header, zip(*body)):
            table[name] = values if name in text else numpy.fromiter(map(float, values), float, len(body))
    except ValueError:  # the first row that is too short or long, or the first value not a number, named
        for line, row in enumerate(body, start=2):
            if len(row) != len(header):
                raise InputError(f"{path}:{line}: {len(row)} values where the header names {len(header)} columns") from None
            for name, value in zip(header, row):
                if name not in text and not is_number(value):
                    raise InputError(f"{path}:{line}: column '{name}': '{value}' is not a number") from None
        raise
    return table


def finite_column(table, path, name):
    """The column, every value finite: else InputError naming the first row (the file's line) that is not."""
    for k, value in enumerate(table[name]):
        if not math.isfinite(value):
            raise InputError(f"{path}:{k + 2}: column '{name}': {value} is not a finite number")
    return table[name]


def previous_files(out, manifest, key="figures"):
    """The files a writer's previous manifest OUT/MANIFEST lists (its own outputs of an earlier run): plain names in
    OUT, never a path outside it. Nothing when there is no manifest or it is not one."""
    try:
        data = load_json(os.path.join(out, manifest))
    except (OSError, ValueError):
        return set()
    entries = data.get(key, []) if isinstance(data, dict) else []
    if isinstance(entries, dict) or isinstance(entries, str):
        entries = [entries]
    names = {e.get("file") if isinstance(e, dict) else e for e in entries}
    return {n for n in names if isinstance(n, str) and n and os.path.basename(n) == n and n not in (".", "..")}


def write_atomically(path, text):
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w", encoding="utf-8") as handle:
        handle.write(text)
    os.replace(tmp, path)


def _display_points(ax, artist):
    """The data points of a line or a scatter of ax in display pixels (finite ones only)."""
    if hasattr(artist, "get_xydata"):
        xy = numpy.asarray(artist.get_xydata(), dtype=float)
        transform = artist.get_transform()
    else:
        xy = numpy.asarray(artist.get_offsets(), dtype=float)
        transform = artist.get_offset_transform()
    if xy.ndim != 2 or not xy.size:
        return numpy.empty((0, 2))
    xy = xy[numpy.all(numpy.isfinite(xy), axis=1)]
    return transform.transform(xy) if xy.size else numpy.empty((0, 2))


def _boxes_overlap(a, b, gap=3.0):
    """Do two display boxes come closer than `gap` pixels (touching text reads as one)?"""
    width = min(a.x1, b.x1) - max(a.x0, b.x0) + gap
    height = min(a.y1, b.y1) - max(a.y0, b.y0) + gap
    return width > 0 and height > 0


def layout_facts(fig, index_axes=()):
    """What a reader sees of a drawn figure, measured on its renderer (the suite "Reports" checks it):
    legend_points_covered: data points of an axes, or of its twin, under that axes' legend;
    markers_outside_axes: marker points drawn within half a marker of an axes' edge or beyond it (clipped);
    overlapping: pairs among the axes (with their labels and ticks), colour bars and legends that overlap or come
    within 3 pixels of each other, twins apart; fractional_index_ticks: tick labels that are not integers on an axis of indices (index_axes);
    unlabelled_axes: 2-D axes without a y label, and 3-D axes without a z label."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    facts = {"legend_points_covered": 0, "markers_outside_axes": 0, "overlapping": 0, "fractional_index_ticks": 0,
             "unlabelled_axes": 0, "where": []}
    axes = list(fig.axes)
    def twins(a, b):
        return a is b or numpy.allclose(a.get_position().bounds, b.get_position().bounds)
    boxes = []
    for ax in axes:
        box = ax.get_tightbbox(renderer)
        if hasattr(ax, "zaxis"):  # a 3-D axes' tight box leaves out its axes' labels: add them
            from matplotlib.transforms import Bbox
            box = Bbox.union([box] + [a.get_tightbbox(renderer) for a in (ax.xaxis, ax.yaxis, ax.zaxis)
                                      if a.get_tightbbox(renderer) is not None])
        boxes.append((ax, box, "axes"))
        legend = ax.get_legend()
        if legend is not None and legend.get_visible():
            box = legend.get_window_extent(renderer)
            boxes.append((ax, box, "legend"))
            for other in axes:
                if not twins(ax, other):
                    continue
                for artist in list(other.get_lines()) + list(other.collections):
                    points = _display_points(other, artist)
                    inside = ((points[:, 0] > box.x0) & (points[:, 0] < box.x1) & (points[:, 1] > box.y0) &
                              (points[:, 1] < box.y1)).sum() if points.size else 0
                    if inside:
                        facts["legend_points_covered"] += int(inside)
                        facts["where"].append(f"{inside} points of {artist.get_label()!r} under the legend of "
                                              f"{ax.get_ylabel()!r}")
        frame = ax.bbox
        for line in ax.get_lines():
            marker = line.get_marker()
            if marker in (None, "None", "", " ") or line.get_linestyle() not in ("None", "", " ", "none"):
                continue
            half = 0.5 * line.get_markersize() * fig.dpi / 72.0
            points = _display_points(ax, line)
            outside = ((points[:, 0] < frame.x0 + half) | (points[:, 0] > frame.x1 - half) | (points[:, 1] < frame.y0 + half) |
                       (points[:, 1] > frame.y1 - half)).sum() if points.size else 0
            if outside:
                facts["markers_outside_axes"] += int(outside)
                facts["where"].append(f"{outside} markers of {line.get_label()!r} at the edge of {ax.get_ylabel()!r}")
        if ax in index_axes:
            low, high = ax.get_ylim()
            ticks = [v for v in ax.get_yticks() if min(low, high) <= v <= max(low, high)]
            fractional = sum(1 for v in ticks if abs(v - round(v)) > 1e-9)
            if fractional:
                facts["fractional_index_ticks"] += fractional
                facts["where"].append(f"{fractional} fractional ticks on {ax.get_ylabel()!r}")
        label = ax.get_zlabel() if hasattr(ax, "get_zlabel") else ax.get_ylabel()
        if not label:
            facts["unlabelled_axes"] += 1
            facts["where"].append(f"an axes without a label ({ax.get_title()!r})")
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            (a, box_a, kind_a), (b, box_b, kind_b) = boxes[i], boxes[j]
            if twins(a, b) and "legend" not in (kind_a, kind_b):
                continue
            if a is b or (twins(a, b) and kind_a != kind_b and "axes" in (kind_a, kind_b)):
                continue  # an axes' own legend lies inside it (its points are counted above)
            if _boxes_overlap(box_a, box_b):
                facts["overlapping"] += 1
                facts["where"].append(f"the {kind_a} of {a.get_ylabel() or a.get_title()!r} over the {kind_b} of "
                                      f"{b.get_ylabel() or b.get_title()!r}")
    return facts


def save_figure(fig, path, bbox="tight", index_axes=()):
    """Saves fig atomically; returns its layout_facts, measured as drawn."""
    facts = layout_facts(fig, index_axes)
    tmp = f"{path}.tmp{os.getpid()}.png"
    fig.savefig(tmp, dpi=110, bbox_inches=bbox)
    os.replace(tmp, path)
    return facts


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
