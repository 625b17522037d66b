#!/usr/bin/python3
"""Draw one metric of any scan: python3 reports/plot_scan.py NAME-scan.csv [METRIC ...] [--out FILE.png]

Each metric is a panel over the scan's two axes, named by their keys (the CSV's second and third columns)
with their units, on the computed grid without interpolation; NaN points (failed, or not computed) are left
blank, and a metric with no number at all says so on its panel. The units come from the one table of each
(docs/outputs.md for the metrics, cases/README.md for the scene keys; installed beside the plotters as
outputs.md and scene-keys.md). The title is the scan's description (NAME-scan.json beside the CSV). An
exponent (lambda_*) is drawn on a diverging map centred on 0, so that chaos and order read apart; on the
lambda_max panel a dot marks each point whose |λ| is within twice its lambda_error of 0 (its sign not known); an
error bar (lambda_error) is drawn on a sequential map from 0. The default
metric is lambda_max where the scan computed it, else omega_rms. Without --out the figure goes to
NAME-scan-METRIC.png beside the CSV."""
import csv
import json
import math
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import help_requested, InputError, finite_column, input_errors, load_table, save_figure  # noqa: E402


def edges(centres):
    """Cell edges around the grid's points: midway between neighbours, as far out at the ends."""
    c = numpy.array(centres, dtype=float)
    if len(c) == 1:
        return numpy.array([c[0] - 0.5, c[0] + 0.5])
    mid = 0.5 * (c[1:] + c[:-1])
    return numpy.concatenate(([2 * c[0] - mid[0]], mid, [2 * c[-1] - mid[-1]]))


HERE = os.path.dirname(os.path.abspath(__file__))


def table_file(*candidates):
    for parts in candidates:
        path = os.path.join(HERE, *parts)
        if os.path.exists(path):
            return path
    return None


def metric_units():
    """{column: unit} of NAME-scan.csv, from docs/outputs.md's table for it."""
    path = table_file(("..", "docs", "outputs.md"), ("..", "outputs.md"))
    units, inside = {}, False
    for line in open(path, encoding="utf-8") if path else ():
        if line.startswith("### "):
            inside = line.strip() == "### NAME-scan.csv"
        m = re.match(r"\| `([^`]+)` \| ([^|]*) \|", line)
        if inside and m and m.group(2).strip() not in ("—", "", "the key's"):
            units[m.group(1)] = m.group(2).strip()
    return units


def key_units():
    """{section.key: unit} of the scene keys, from the brackets of cases/README.md's allowed values."""
    path = table_file(("..", "cases", "README.md"), ("..", "scene-keys.md"))
    units = {}
    for line in open(path, encoding="utf-8") if path else ():
        m = re.match(r"\| `\[(\w+)\]` \| `(\w+)` \| ([^|]*) \|", line)
        if m:
            unit = re.search(r"\[([^\]]+)\]\s*(\(|$)", m.group(3).strip())
            if unit:
                units[f"{m.group(1)}.{m.group(2)}"] = unit.group(1)
    return units


def label(key, units):
    return f"{key} [{units[key]}]" if key in units else key


def main(argv):
    help_requested(__doc__, argv)
    args, out = [], None
    it = iter(argv)
    for a in it:
        if a == "--out":
            out = next(it, None)
        elif a.startswith("--out="):
            out = a[6:]
        else:
            args.append(a)
    if not args or out == "":
        sys.stderr.write(__doc__ + "\n")
        return 2
    path, metrics = args[0], args[1:]
    try:
        with open(path) as f:
            names = next(csv.reader(f), [])
    except OSError as e:
        sys.stderr.write(f"plot_scan: {path}: {e.strerror}\n")
        return 2
    if len(names) < 4 or names[0] != "index":
        sys.stderr.write(f"plot_scan: {path}: not a gomboc scan CSV (allowed: NAME-scan.csv of gomboc scan)\n")
        return 2
    table = load_table(path, text=tuple(n for n in names if n.endswith("_fingerprint")))
    x_key, y_key = names[1], names[2]
    for key in (x_key, y_key):  # an axis is finite, and so are the cells' edges drawn between its values
        values = sorted(set(finite_column(table, path, key).tolist()))
        with numpy.errstate(over="ignore"):
            spread = edges(values)
        if not numpy.isfinite(spread).all():
            raise InputError(f"{path}: column '{key}': the axis's values {values[0]:g} .. {values[-1]:g} put its cells' edges "
                             "beyond the range of a double (allowed: an axis whose spacing a double holds)")
    rows = [{n: table[n][k] for n in names} for k in range(len(table))]
    if not metrics:
        has_lambda = "lambda_max" in names and any(not math.isnan(float(r["lambda_max"])) for r in rows)
        metrics = ["lambda_max" if has_lambda else "omega_rms"]
    plottable = [n for n in names[3:] if not n.endswith("_fingerprint")]
    unknown = [m for m in metrics if m not in plottable]
    if unknown:
        sys.stderr.write(f"plot_scan: unknown metric {', '.join(unknown)} (allowed: {', '.join(plottable)})\n")
        return 2
    xs = sorted({float(r[x_key]) for r in rows})
    ys = sorted({float(r[y_key]) for r in rows})
    units = {**key_units(), **metric_units()}
    description = os.path.basename(path)
    try:
        with open(path[:-len(".csv")] + ".json", encoding="utf-8") as f:
            scan = json.load(f)
        description = scan.get("description") or description
        # A1, A2 are in the base scene's amplitude_units (m/s2 unless it says g)
        with open(scan.get("base", ""), encoding="utf-8") as f:
            said = re.search(r"^amplitude_units\s*=\s*(\S+)", f.read(), re.M)
        units.update({k: said.group(1) if said else "m/s2" for k, u in units.items() if u == "amplitude_units"})
    except (OSError, ValueError):
        pass
    fig, axes = plt.subplots(1, len(metrics), figsize=(5.6 * len(metrics), 4.6), squeeze=False)
    notes = []
    for ax, metric in zip(axes[0], metrics):
        grid = numpy.full((len(ys), len(xs)), numpy.nan)
        for r in rows:
            grid[ys.index(float(r[y_key])), xs.index(float(r[x_key]))] = float(r[metric])
        finite = numpy.isfinite(grid)
        exponent = metric.startswith("lambda") and not metric.endswith("_error")
        title = metric
        if exponent and finite.any():
            reach = float(numpy.nanmax(numpy.abs(grid))) or 1.0
            image = ax.pcolormesh(edges(xs), edges(ys), grid, shading="flat", cmap="RdBu_r", vmin=-reach, vmax=reach)
            fig.colorbar(image, ax=ax, label=label(metric, units) + " (0 white)")
            if metric == "lambda_max" and "lambda_error" in names:  # where the sign is not known: a dot
                error = numpy.full_like(grid, numpy.nan)
                for r in rows:
                    error[ys.index(float(r[y_key])), xs.index(float(r[x_key]))] = float(r["lambda_error"])
                unsure = finite & ~(numpy.abs(grid) > 2.0 * error)
                if unsure.any():
                    row, column = numpy.nonzero(unsure)
                    ax.plot(numpy.array(xs)[column], numpy.array(ys)[row], "o", ms=3, color="0.25", ls="none")
                title = (f"{metric}; dots: |λ| within 2 error bars of 0 ({int(unsure.sum())} of {int(finite.sum())} "
                         "points: sign not known)")
                notes.append(f"plot_scan: {metric}: {int(unsure.sum())} of {int(finite.sum())} points within 2 error bars of "
                             "0, dotted")
        elif metric.endswith("_error") and finite.any():  # an error bar: sequential, from 0
            image = ax.pcolormesh(edges(xs), edges(ys), grid, shading="flat", cmap="Greys", vmin=0.0)
            fig.colorbar(image, ax=ax, label=label(metric, units) + " (0 white)")
        else:
            image = ax.pcolormesh(edges(xs), edges(ys), grid, shading="flat")
            if finite.any():
                fig.colorbar(image, ax=ax, label=label(metric, units))
        if not finite.any():
            ax.text(0.5, 0.5, f"{metric}: no number at any of the {grid.size} points\n(not computed by this scan, or every "
                    "point failed)", ha="center", va="center", transform=ax.transAxes, fontsize=9)
        ax.set_xlabel(label(x_key, units))
        ax.set_ylabel(label(y_key, units))
        ax.set_title(title, fontsize=9)
    fig.suptitle(description, fontsize=10)
    fig.tight_layout()
    target = out or os.path.splitext(path)[0] + "-" + "-".join(metrics) + ".png"
    save_figure(fig, target, bbox=None)  # atomically: a link or a file at the name is replaced, never written through
    print(target)  # the one line of standard output: the figure's path (gomboc.plot.scan returns it)
    for note in notes:
        sys.stderr.write(note + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(input_errors(lambda: main(sys.argv[1:])))
