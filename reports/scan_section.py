"""Report section "Parameter space (section 8.3)": the maps of Figs 10-13 that `make scans` last made
(OUT/scans/*-scan.csv, one row a point), drawn on their computed grid without interpolation, and the
paper's claims about them judged by rules fixed here before the data. Recomputes no physics."""
import csv
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy  # noqa: E402

from common import load_json, save_figure  # noqa: E402

FIGURES = (("fig10-gomboc-I-omega-A1", "Fig 10", "I", "ω [rad/s]", "A1 [m/s²]"),
           ("fig11-gomboc-I-A2-psi", "Fig 11", "I", "ψ [rad]", "A2 [m/s²]"),
           ("fig12-gomboc-II-omega-A1", "Fig 12", "II", "ω [rad/s]", "A1 [m/s²]"),
           ("fig13-gomboc-II-A2-psi", "Fig 13", "II", "ψ [rad]", "A2 [m/s²]"))
MODELS = (("paper", "paper model (eq 44, 90 x 180 grid)"), ("rolling", "rolling model, certified continuous contact"))
PANELS = (("omega_rms", "ω_RMS [rad/s]"), ("switch_rate", "switching rate [1/s]"), ("strobe_sd", "std(ω_x) strobe [rad/s]"),
          ("mean_height", "mean(h*)"), ("lambda_max", "λ_max [1/s]"), ("geff_nonpositive_fraction", "g_eff ≤ 0 fraction"))

# The rules, fixed before the data.
# Agreement of two maps: Spearman's rank correlation of the switching rate over the points of both, with a
# 95 % interval from Fisher's z on an effective sample of a quarter of the points (neighbouring points
# are correlated; our choice). Holds when the interval lies above 0.5 (the maps share a quarter of their
# rank variance or more), fails when it lies below 0.5, undecided otherwise.
AGREE = 0.5
# "I ridge-structured, II broad domains": the roughness of a map is the mean absolute difference between
# neighbouring points divided by the spread of the map (90th less 10th percentile). Holds when I's
# roughness exceeds II's by 25 % or more (our margin), fails when it does not exceed II's at all,
# undecided between.
ROUGHER = 1.25
# λ > 0 at a point: λ − 4σ above the no-chaos margin 0.01 1/s (the rule of section 8.2).
NO_CHAOS = 0.01
# "Where λ > 0 the forcing is above the Melnikov threshold": a point is above when its exact margin
# (melnikov_margin, the point's own forcing over the reduced model's threshold) exceeds 1. Holds when
# 90 % or more of the chaotic points are above and that share exceeds the other points' by 0.5 or more
# (the threshold separates them); fails when fewer than half of the chaotic points are above.
ABOVE_HOLDS, ABOVE_SEPARATES, ABOVE_FAILS = 0.9, 0.5, 0.5
MARGINS = ("melnikov_margin", "melnikov_margin_eq93")
# Stability of a map (cases/scans/stability). Longer runs: Spearman's ρ between the 100- and the
# 200-period map of one metric, with the interval above; stable when the interval lies above 0.8 (the
# two runs share two thirds of their rank variance), unstable when it lies below, undecided across.
STABLE = 0.8
# A finer grid: the roughness of the refined sub-window over the roughness of the base map on the same
# window. A map whose features span several points is smoother at half the spacing (the ratio falls
# towards 0.5); variation from point to point at every spacing (noise, or structure finer than the
# grid) keeps it near 1. Resolved at or below 0.75, not resolved at or above 0.9, undecided between.
RESOLVED, UNRESOLVED = 0.75, 0.9
STABILITY_METRICS = (("switch_rate", "switching rate"), ("omega_rms", "ω_RMS"))


def load_rows(path):
    """The rows of a scan's CSV, its axis columns (the second and third, named after their keys) also as x and y."""
    with open(path) as f:
        reader = csv.DictReader(f)
        x_name, y_name = reader.fieldnames[1], reader.fieldnames[2]
        rows = list(reader)
    for r in rows:
        r["x"], r["y"] = r[x_name], r[y_name]
    return rows


def load_map(path):
    rows = load_rows(path)
    xs = sorted({float(r["x"]) for r in rows})
    ys = sorted({float(r["y"]) for r in rows})
    grid = {}
    for key in [k for k, _ in PANELS] + ["lambda_error", *MARGINS]:
        a = numpy.full((len(ys), len(xs)), numpy.nan)
        for r in rows:
            if key in r:  # maps made before a column existed lack it: NaN
                a[ys.index(float(r["y"])), xs.index(float(r["x"]))] = float(r[key])
        grid[key] = a
    return numpy.array(xs), numpy.array(ys), grid


def crosses_one(a):
    """Whether a margin map has points on both sides of 1 (a contour at 1 exists)."""
    finite = a[numpy.isfinite(a)]
    return finite.size > 0 and finite.min() < 1.0 < finite.max()


def cell_extent(xs, ys):
    """imshow's extent for one cell a point of a regular grid."""
    dx = (xs[1] - xs[0]) / 2 if len(xs) > 1 else 0.5
    dy = (ys[1] - ys[0]) / 2 if len(ys) > 1 else 0.5
    return (xs[0] - dx, xs[-1] + dx, ys[0] - dy, ys[-1] + dy)


def draw(out, name, title, xlabel, ylabel, xs, ys, grid):
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5))
    extent = cell_extent(xs, ys)
    for ax, (key, label) in zip(axes.flat, PANELS):
        a = grid[key]
        im = ax.imshow(a, origin="lower", extent=extent, aspect="auto", interpolation="nearest")
        fig.colorbar(im, ax=ax)
        if key == "lambda_max":
            chaotic = grid["lambda_max"] - 4 * grid["lambda_error"] > NO_CHAOS
            yy, xx = numpy.nonzero(chaotic)
            ax.plot(xs[xx], ys[yy], ".", color="w", ms=2, label="λ − 4σ > 0.01")
        for margin, style in zip(MARGINS, ("-", "--")):
            if len(xs) > 1 and len(ys) > 1 and crosses_one(grid[margin]):
                ax.contour(xs, ys, grid[margin], levels=[1.0], colors="r", linestyles=style, linewidths=1.2)
        label_panel(ax, label, xlabel, ylabel)
    finish_map_figure(fig, out, name, title)


def label_panel(ax, label, xlabel, ylabel):
    ax.set_title(label, fontsize=9)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)


def finish_map_figure(fig, out, name, title):
    """A map's figure of panels, titled, written as OUT/NAME.png."""
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    save_figure(fig, os.path.join(out, f"{name}.png"))
    plt.close(fig)


def ranks(a):
    order = numpy.argsort(a, kind="stable")
    r = numpy.empty(len(a))
    r[order] = numpy.arange(len(a))
    return r


def spearman(a, b):
    keep = numpy.isfinite(a) & numpy.isfinite(b)
    if keep.sum() < 8:
        return math.nan, math.nan, math.nan
    rho = float(numpy.corrcoef(ranks(a[keep]), ranks(b[keep]))[0, 1])
    n_eff = keep.sum() / 4.0
    z, half = math.atanh(max(min(rho, 0.999999), -0.999999)), 1.96 / math.sqrt(max(n_eff - 3.0, 1.0))
    return rho, math.tanh(z - half), math.tanh(z + half)


def roughness(a):
    diffs = numpy.concatenate([numpy.abs(numpy.diff(a, axis=0)).ravel(), numpy.abs(numpy.diff(a, axis=1)).ravel()])
    spread = numpy.nanpercentile(a, 90) - numpy.nanpercentile(a, 10)
    return float(numpy.nanmean(diffs) / spread) if spread > 0 else math.nan


def noise_floor(xs, grid):
    """On a (ψ, A2) map the columns ψ = 0 and ψ = 2π are the same forcing up to the rounding of 2π: the median
    difference of a metric between them, over the map's spread (p90 − p10), is what the map cannot resolve."""
    if len(xs) < 2 or abs(xs[-1] - xs[0] - 2 * math.pi) > 1e-9:
        return {}
    out = {}
    for key, _ in PANELS[:5]:
        a = grid[key]
        spread = numpy.nanpercentile(a, 90) - numpy.nanpercentile(a, 10)
        out[key] = float(numpy.nanmedian(numpy.abs(a[:, 0] - a[:, -1])) / spread) if spread > 0 else math.nan
    return out


def margin_text(grid):
    """The range of a map's exact Melnikov margins, and how many points lie above 1."""
    a = grid["melnikov_margin"]
    finite = a[numpy.isfinite(a)]
    if finite.size == 0:
        return ""
    text = (f" Melnikov margin {finite.min():.2f} … {finite.max():.2f} (eq 93: {numpy.nanmin(grid[MARGINS[1]]):.2f} … "
            f"{numpy.nanmax(grid[MARGINS[1]]):.2f}); above 1 at {int((finite > 1.0).sum())} of {a.size} points.")
    # How fast the margin changes between neighbouring columns (x): where it jumps by large factors, the
    # margin-1 line is not resolved by the map's spacing.
    left, right = a[:, :-1], a[:, 1:]
    keep = numpy.isfinite(left) & numpy.isfinite(right) & (left > 0) & (right > 0)
    if keep.any():
        ratio = numpy.maximum(left[keep], right[keep]) / numpy.minimum(left[keep], right[keep])
        text += (f" Between neighbouring columns the margin changes by a factor {numpy.median(ratio):.2f} (median), up to "
                 f"{ratio.max():.1f}.")
    return text


def verdict(value, holds, fails):
    return "*undecided*" if not math.isfinite(value) else "holds" if holds else "**fails**" if fails else "*undecided*"


def scan_section(out):
    lines = ["## Parameter space (section 8.3, Figs 10–13)", ""]
    folder = os.path.join(out, "scans")
    stamp = os.path.join(out, "gates", "scans.json")
    maps = {}
    for name, fig, body, xl, yl in FIGURES:
        for model, _ in MODELS:
            path = os.path.join(folder, f"{name}-{model}-scan.csv")
            if os.path.exists(path):
                maps[(name, model)] = load_map(path)
    if not maps:
        return lines + ["No maps in this checkout: `make scans` computes the eight maps of `cases/scans` (25 × 25 points "
                        "of 100 periods each, λ included) and writes them here.", ""]
    when = ""
    if os.path.exists(stamp):
        s = load_json(stamp)
        when = f" They were made by `make scans` on {s['date']} at commit {s['commit']} ({s['result']})."
    lines += ["Each map is the scan file of `cases/scans` of the same name: the base scene (Table 1, A1 and A2 read in m/s²)",
              "with two keys set at every point, 100 periods a point, the metrics from period 20 on. Panels are drawn on the",
              "computed grid, one cell a point, without interpolation (the paper interpolates for display). White dots: λ − 4σ",
              "above the no-chaos margin 0.01 1/s. Red: the reduced model's threshold (section 7), the line where the",
              "point's Melnikov margin is 1 (solid: the exact condition, dashed: eq 93), drawn where the margins cross 1;",
              f"it is the threshold of each point's own forcing (on an (ω, A1) map A2 stays fixed).{when}", ""]
    for name, fig, body, xl, yl in FIGURES:
        for model, label in MODELS:
            if (name, model) not in maps:
                lines.append(f"- {fig}, {label}: not made in this checkout.")
                continue
            xs, ys, grid = maps[(name, model)]
            png = f"scan-{name}-{model}"
            draw(out, png, f"{fig}: Gömböc {body}, {label}", xl, yl, xs, ys, grid)
            chaotic = grid["lambda_max"] - 4 * grid["lambda_error"] > NO_CHAOS
            invalid = grid["geff_nonpositive_fraction"] > 0
            lines += [f"### {fig}, {label}", "", f"![{fig} {model}]({png}.png)", "",
                      f"λ − 4σ > 0.01 1/s at {int(chaotic.sum())} of {chaotic.size} points; g_eff ≤ 0 somewhere in the run "
                      f"at {int(invalid.sum())} (there the single-contact model does not apply).{margin_text(grid)}", ""]
            floor = noise_floor(xs, grid)
            if floor:
                text = ", ".join(f"{label} {floor[key]:.2f}" for key, label in PANELS[:5] if key in floor)
                lines += ["Noise floor (the columns ψ = 0 and ψ = 2π are one forcing up to the rounding of 2π; median "
                          f"difference between them over the map's spread p90 − p10): {text}. A feature of the map smaller "
                          "than this is not resolved by 100 periods a point.", ""]
    lines += ["### The paper's claims about the maps", "",
              f"Agreement: Spearman's ρ of the two models' switching-rate maps, a 95 % interval from Fisher's z on a quarter "
              f"of the points; holds above {AGREE}, fails below, undecided across. Ridges: roughness = mean neighbour "
              f"difference / (p90 − p10) of the ω_RMS map; \"I ridge-structured, II broad domains\" holds when I's exceeds "
              f"II's by {ROUGHER:.2f}×, fails when it does not exceed it. Rules fixed in `reports/scan_section.py`.", "",
              "| claim | evidence | verdict |", "|---|---|---|"]
    for name, fig, body, _, _ in FIGURES:
        if (name, "paper") in maps and (name, "rolling") in maps:
            rho, lo, hi = spearman(maps[(name, "paper")][2]["switch_rate"].ravel(),
                                   maps[(name, "rolling")][2]["switch_rate"].ravel())
            lines.append(f"| {fig}: the paper model's and the rolling model's maps agree in where switching is high | "
                         f"ρ = {rho:.2f} (95 %: {lo:.2f} … {hi:.2f}) | {verdict(rho, lo > AGREE, hi < AGREE)} |")
    for (a, b, plane) in (("fig10-gomboc-I-omega-A1", "fig12-gomboc-II-omega-A1", "(ω, A1)"),
                          ("fig11-gomboc-I-A2-psi", "fig13-gomboc-II-A2-psi", "(A2, ψ)")):
        for model, label in MODELS:
            if (a, model) in maps and (b, model) in maps:
                ra, rb = roughness(maps[(a, model)][2]["omega_rms"]), roughness(maps[(b, model)][2]["omega_rms"])
                ratio = ra / rb if rb > 0 else math.nan
                lines.append(f"| {plane}, {label}: Gömböc I ridge-structured, II broad domains (section 8.3) | roughness I "
                             f"{ra:.3f}, II {rb:.3f} (ratio {ratio:.2f}) | {verdict(ratio, ratio >= ROUGHER, ratio <= 1.0)} |")
    for name, fig, body, _, _ in FIGURES:
        for model, label in MODELS:
            if (name, model) not in maps:
                continue
            grid = maps[(name, model)][2]
            chaotic = grid["lambda_max"] - 4 * grid["lambda_error"] > NO_CHAOS
            n_c, n_r = int(chaotic.sum()), int((~chaotic).sum())
            if not numpy.isfinite(grid["melnikov_margin"]).any():
                lines.append(f"| {fig}, {label}: where λ > 0 the forcing is above the reduced Melnikov threshold (sections 7, "
                             f"8.3) | no margins in this map (made before the margins were a metric: `make scans` again) | "
                             f"*undecided* |")
                continue
            share = {}
            for margin in MARGINS:
                above = grid[margin] > 1.0
                share[margin] = (float((above & chaotic).sum()) / n_c if n_c else math.nan,
                                 float((above & ~chaotic).sum()) / n_r if n_r else math.nan)
            frac_c, frac_r = share["melnikov_margin"]
            pct = lambda f: f"{f:.0%}" if math.isfinite(f) else "—"  # noqa: E731
            lines.append(f"| {fig}, {label}: where λ > 0 the forcing is above the reduced Melnikov threshold (sections 7, 8.3) | "
                         f"{pct(frac_c)} of {n_c} points with λ − 4σ > 0.01 have a margin above 1, {pct(frac_r)} of the {n_r} "
                         f"others (by eq 93: {pct(share[MARGINS[1]][0])} and {pct(share[MARGINS[1]][1])}) | "
                         f"{verdict(frac_c, frac_c >= ABOVE_HOLDS and frac_c - frac_r >= ABOVE_SEPARATES, frac_c < ABOVE_FAILS)} |")
    lines += ["", f"λ above the threshold: holds when {ABOVE_HOLDS:.0%} or more of the points with λ − 4σ > 0.01 have an exact "
              f"Melnikov margin above 1 (the point's own forcing above the reduced model's threshold: the `melnikov_margin` "
              f"column) and that share exceeds the other points' by {ABOVE_SEPARATES} or more (the threshold separates them); "
              f"fails when fewer than {ABOVE_FAILS:.0%} of them are above; undecided otherwise (and where no point is chaotic)."]
    return lines + [""] + stability_lines(out, maps)


def sub_window(xs, ys, grid, fxs, fys):
    """The base map's nodes inside the refined map's window."""
    kx = (xs >= fxs[0] - 1e-9) & (xs <= fxs[-1] + 1e-9)
    ky = (ys >= fys[0] - 1e-9) & (ys <= fys[-1] + 1e-9)
    return {key: a[numpy.ix_(ky, kx)] for key, a in grid.items()}


def shared_nodes(base_path, fine_path):
    """Nodes of the refined map that are nodes of the base map (the same coordinates to the last bit):
    how many, and at how many every metric is the same text (the same scene gives the same bytes)."""
    metrics = [k for k, _ in PANELS]
    base = {(r["x"], r["y"]): r for r in load_rows(base_path)}
    shared = same = 0
    for r in load_rows(fine_path):
        b = base.get((r["x"], r["y"]))
        if b is None:
            continue
        shared += 1
        same += all(r[k] == b[k] for k in metrics if k != "lambda_max")
    return shared, same


def stability_lines(out, maps):
    folder = os.path.join(out, "scans")
    lines = ["### Stability of the maps", "",
             "Each map again with twice the run per point (200 periods; `cases/scans/stability/*-200.ini`) and on a "
             "sub-window at half the spacing (25 points a side, as a 50 × 50 grid of the whole map would have; "
             "`*-fine.ini`), λ left out. Rules fixed in `reports/scan_section.py` before the data: the 100- and "
             f"200-period maps agree when Spearman's ρ has its 95 % interval above {STABLE} (disagree below, undecided "
             f"across); a map is resolved by its grid when the refined window's roughness is at most {RESOLVED} of the "
             f"base map's on that window (not resolved at {UNRESOLVED} or more, undecided between).", "",
             "| map | metric | ρ(100, 200 periods) | longer run | roughness refined / base | grid | shared nodes equal |",
             "|---|---|---|---|---|---|---|"]
    long_maps, any_made = {}, False
    for name, fig, body, _, _ in FIGURES:
        for model, label in MODELS:
            if (name, model) not in maps:
                continue
            xs, ys, grid = maps[(name, model)]
            doubled = os.path.join(folder, f"{name}-{model}-200-scan.csv")
            fine = os.path.join(folder, f"{name}-{model}-fine-scan.csv")
            d = load_map(doubled) if os.path.exists(doubled) else None
            f = load_map(fine) if os.path.exists(fine) else None
            if d is None and f is None:
                continue
            any_made = True
            if d is not None:
                long_maps[(name, model)] = d
            nodes = ""
            if f is not None:
                shared, same = shared_nodes(os.path.join(folder, f"{name}-{model}-scan.csv"), fine)
                nodes = f"{same} of {shared}"
            for key, metric in STABILITY_METRICS:
                row = f"| {fig}, {label} | {metric} | "
                if d is not None:
                    rho, lo, hi = spearman(grid[key].ravel(), d[2][key].ravel())
                    row += f"{rho:.2f} ({lo:.2f} … {hi:.2f}) | {verdict(rho, lo > STABLE, hi < STABLE)} | "
                else:
                    row += "not made | — | "
                if f is not None:
                    window = sub_window(xs, ys, grid, f[0], f[1])
                    rough_base, rough_fine = roughness(window[key]), roughness(f[2][key])
                    ratio = rough_fine / rough_base if rough_base > 0 else math.nan
                    grid_verdict = verdict(ratio, ratio <= RESOLVED, ratio >= UNRESOLVED)
                    row += f"{rough_fine:.3f} / {rough_base:.3f} = {ratio:.2f} | {grid_verdict} | {nodes} |"
                else:
                    row += "not made | — | — |"
                lines.append(row)
    if not any_made:
        return ["### Stability of the maps", "", "Not made in this checkout: `make scans` makes the stability maps of "
                "`cases/scans/stability` after the eight maps.", ""]
    lines += ["", "\"longer run\": holds = the map is the same with 100 and 200 periods a point; \"grid\": holds = its "
              "features are resolved by the 25-point grid. \"Shared nodes equal\": the refined window's nodes that are "
              "nodes of the base map to the last bit of their coordinates, and how many of them give the same metrics "
              "(they run the same scene: any difference would be a fault of the scan).", ""]
    claims = []
    for (a, b, plane) in (("fig10-gomboc-I-omega-A1", "fig12-gomboc-II-omega-A1", "(ω, A1)"),
                          ("fig11-gomboc-I-A2-psi", "fig13-gomboc-II-A2-psi", "(A2, ψ)")):
        for model, label in MODELS:
            if all(k in maps and k in long_maps for k in ((a, model), (b, model))):
                r100 = roughness(maps[(a, model)][2]["omega_rms"]) / roughness(maps[(b, model)][2]["omega_rms"])
                r200 = roughness(long_maps[(a, model)][2]["omega_rms"]) / roughness(long_maps[(b, model)][2]["omega_rms"])
                claims.append(f"| {plane}, {label}: I ridge-structured, II broad domains | ratio {r100:.2f}: "
                              f"{verdict(r100, r100 >= ROUGHER, r100 <= 1.0)} | ratio {r200:.2f}: "
                              f"{verdict(r200, r200 >= ROUGHER, r200 <= 1.0)} |")
    for name, fig, _, _, _ in FIGURES:
        if all(k in long_maps for k in ((name, "paper"), (name, "rolling"))):
            rho, lo, hi = spearman(maps[(name, "paper")][2]["switch_rate"].ravel(),
                                   maps[(name, "rolling")][2]["switch_rate"].ravel())
            rho2, lo2, hi2 = spearman(long_maps[(name, "paper")][2]["switch_rate"].ravel(),
                                      long_maps[(name, "rolling")][2]["switch_rate"].ravel())
            claims.append(f"| {fig}: the two models agree where switching is high | ρ = {rho:.2f}: "
                          f"{verdict(rho, lo > AGREE, hi < AGREE)} | ρ = {rho2:.2f}: {verdict(rho2, lo2 > AGREE, hi2 < AGREE)} |")
    if claims:
        lines += ["The paper's claims about the maps, judged by the same rules on the 100- and on the 200-period maps:", "",
                  "| claim | 100 periods | 200 periods |", "|---|---|---|"] + claims + [""]
    return lines
