#!/usr/bin/python3
"""Draw one metric of any scan: python3 reports/plot_scan.py NAME-scan.csv [METRIC ...] [--out FILE.png]

Each metric is a panel over the scan's two axes, named by their keys (the CSV's second and third columns),
on the computed grid without interpolation; NaN points (failed, or not computed) are left blank. The
default metric is lambda_max where the scan computed it, else omega_rms. Without --out the figure goes to
NAME-scan-METRIC.png beside the CSV."""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy  # noqa: E402


def edges(centres):
    """Cell edges around the grid's points: midway between neighbours, as far out at the ends."""
    c = numpy.array(centres, dtype=float)
    if len(c) == 1:
        return numpy.array([c[0] - 0.5, c[0] + 0.5])
    mid = 0.5 * (c[1:] + c[:-1])
    return numpy.concatenate(([2 * c[0] - mid[0]], mid, [2 * c[-1] - mid[-1]]))


def main(argv):
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
            reader = csv.DictReader(f)
            names = reader.fieldnames or []
            rows = list(reader)
    except OSError as e:
        sys.stderr.write(f"plot_scan: {path}: {e.strerror}\n")
        return 2
    if len(names) < 4 or names[0] != "index" or not rows:
        sys.stderr.write(f"plot_scan: {path}: not a gomboc scan CSV (allowed: NAME-scan.csv of gomboc scan)\n")
        return 2
    x_key, y_key = names[1], names[2]
    if not metrics:
        has_lambda = any(not math.isnan(float(r["lambda_max"])) for r in rows)
        metrics = ["lambda_max" if has_lambda else "omega_rms"]
    plottable = [n for n in names[3:] if not n.endswith("_fingerprint")]
    unknown = [m for m in metrics if m not in plottable]
    if unknown:
        sys.stderr.write(f"plot_scan: unknown metric {', '.join(unknown)} (allowed: {', '.join(plottable)})\n")
        return 2
    xs = sorted({float(r[x_key]) for r in rows})
    ys = sorted({float(r[y_key]) for r in rows})
    fig, axes = plt.subplots(1, len(metrics), figsize=(5.2 * len(metrics), 4.2), squeeze=False)
    for ax, metric in zip(axes[0], metrics):
        grid = numpy.full((len(ys), len(xs)), numpy.nan)
        for r in rows:
            grid[ys.index(float(r[y_key])), xs.index(float(r[x_key]))] = float(r[metric])
        image = ax.pcolormesh(edges(xs), edges(ys), grid, shading="flat")
        fig.colorbar(image, ax=ax, label=metric)
        ax.set_xlabel(x_key)
        ax.set_ylabel(y_key)
        ax.set_title(f"{os.path.basename(path)}: {metric}")
    fig.tight_layout()
    target = out or os.path.splitext(path)[0] + "-" + "-".join(metrics) + ".png"
    fig.savefig(target, dpi=110)
    print(target)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
