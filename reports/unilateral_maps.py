"""Report section "Where physical chaos lives (Figs 10-13 under a plane that can only push)": the maps of
cases/scans that `make scans` last made under the unilateral contact law (OUT/scans/NAME-unilateral-scan.csv,
NAME-g-units-bouncing-scan.csv, NAME-grid-unilateral-scan.csv) beside the held law's rolling map of the same
nodes (NAME-rolling-scan.csv), the mechanism drawn from the points' own columns, and four findings judged by
rules fixed here before the data. Recomputes no physics."""
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy  # noqa: E402

from common import save_figure  # noqa: E402
from scan_section import (FIGURES, STABLE, STABILITY_METRICS, cell_extent, finish_map_figure, label_panel, load_rows,  # noqa: E402
                          spearman)

LAWS = (("unilateral", "unilateral contact, A in m/s² (e = 0)"),
        ("g-units-bouncing", "unilateral contact with flight, A in units of g (e = 0.5)"),
        ("grid-unilateral", "the paper's grid as a polyhedron, unilateral contact, A in m/s² (e = 0)"))
MECHANISM = (("lambda_max", "λ_max [1/s]"), ("flight_fraction", "time in flight"), ("two_point_fraction", "time on two points"),
             ("impacts_per_period", "impacts per period"), ("energy_lost_per_period", "energy lost per period [J]"),
             ("geff_nonpositive_fraction", "g_eff ≤ 0 fraction"))

# The rules, fixed before the data.
# A point is chaotic when λ − 4σ > 0.01 1/s and regular when λ + 4σ < 0.05 1/s (no exponent left at the resolution
# 0.05 1/s: R6, the rule of section 8.2's single runs); otherwise, or where the point failed, it is undecided.
NO_CHAOS, RESOLUTION = 0.01, 0.05
# (i) "Chaos occupies a region of the forcing plane" (section 8.3): holds when 10 % or more of a map's points are
# chaotic; fails when fewer than 1 % are and half or more are regular (the map is decided, and regular); undecided
# otherwise (our margins).
REGION_HOLDS, REGION_FAILS, REGION_DECIDED = 0.10, 0.01, 0.5
# (ii) "Under the unilateral law chaos lives where the body can fly" (a point can fly when g_eff ≤ 0 for part of
# its period: geff_nonpositive_fraction > 0): holds when 90 % or more of the chaotic points can fly and at most
# 10 % of the decided points that cannot fly are chaotic; fails when 25 % or more of the chaotic points cannot
# fly; undecided otherwise, and where no point is chaotic.
FLIGHT_HOLDS, FLIGHT_LEAK, FLIGHT_FAILS = 0.9, 0.1, 0.25
# (iii) "Where λ > 0 the forcing is above the reduced Melnikov threshold" (sections 7, 8.3) under the unilateral
# law: the rule of the held maps (scan_section.ABOVE_*): holds when 90 % or more of the chaotic points have a
# margin above 1 and that share exceeds the other points' by 0.5; fails when fewer than half are above.
ABOVE_HOLDS, ABOVE_SEPARATES, ABOVE_FAILS = 0.9, 0.5, 0.5
# (iv) "The held law's map is the physical one": at the points where the held rolling map is decided (chaotic or
# regular) and the unilateral map (m/s²) too, the share where they agree; holds at 90 % or more, fails below
# 50 %, undecided between (and with fewer than 20 such points).
SURVIVES_HOLDS, SURVIVES_FAILS, SURVIVES_MIN = 0.9, 0.5, 20


def load(path, keys):
    rows = load_rows(path)
    xs = sorted({float(r["x"]) for r in rows})
    ys = sorted({float(r["y"]) for r in rows})
    grid = {}
    for key in keys:
        a = numpy.full((len(ys), len(xs)), numpy.nan)
        for r in rows:
            if key in r:
                a[ys.index(float(r["y"])), xs.index(float(r["x"]))] = float(r[key])
        grid[key] = a
    return numpy.array(xs), numpy.array(ys), grid


def states(grid):
    """+1 chaotic, -1 regular, 0 undecided, per point."""
    lam, err = grid["lambda_max"], grid["lambda_error"]
    s = numpy.zeros(lam.shape, dtype=int)
    s[lam - 4 * err > NO_CHAOS] = 1
    s[(lam + 4 * err < RESOLUTION) & (s == 0)] = -1
    return s


def verdict(value, holds, fails):
    return "*undecided*" if not math.isfinite(value) else "holds" if holds else "**fails**" if fails else "*undecided*"


def pct(f):
    return f"{f:.0%}" if math.isfinite(f) else "—"


def maps_of(out):
    folder = os.path.join(out, "scans")
    keys = [k for k, _ in MECHANISM] + ["lambda_error", "melnikov_margin"] + [k for k, _ in STABILITY_METRICS]
    found = {}
    for name, fig, body, xl, yl in FIGURES:
        for law in ("rolling",) + tuple(law for law, _ in LAWS):
            path = os.path.join(folder, f"{name}-{law}-scan.csv")
            if os.path.exists(path):
                found[(name, law)] = load(path, keys)
    return found


def draw_mechanism(out, png, title, xlabel, ylabel, xs, ys, grid):
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5))
    extent = cell_extent(xs, ys)
    for ax, (key, label) in zip(axes.flat, MECHANISM):
        a = grid[key]
        if key == "lambda_max":
            bound = float(numpy.nanmax(numpy.abs(a))) if numpy.isfinite(a).any() else 1.0
            im = ax.imshow(a, origin="lower", extent=extent, aspect="auto", interpolation="nearest", cmap="RdBu_r",
                           vmin=-bound, vmax=bound)
            unsure = numpy.isfinite(a) & ~(numpy.abs(a) > 2.0 * grid["lambda_error"])  # its sign not known: a dot
            if unsure.any():
                row, column = numpy.nonzero(unsure)
                ax.plot(numpy.asarray(xs)[column], numpy.asarray(ys)[row], "o", ms=2.5, color="0.25", ls="none")
                label = f"{label} (dots: within 2 error bars of 0)"
        else:
            im = ax.imshow(a, origin="lower", extent=extent, aspect="auto", interpolation="nearest")
        fig.colorbar(im, ax=ax)
        flight_boundary(ax, xs, ys, grid)
        label_panel(ax, label, xlabel, ylabel)
    finish_map_figure(fig, out, png, title)


def flight_boundary(ax, xs, ys, grid):
    """The line between the points whose g_eff stays positive and those where it reaches 0 within the period."""
    g = grid["geff_nonpositive_fraction"]
    can_fly = numpy.where(numpy.isfinite(g), (g > 0).astype(float), numpy.nan)  # a failed point: neither side
    if len(xs) > 1 and len(ys) > 1 and 0 < numpy.nansum(can_fly) < numpy.isfinite(can_fly).sum():
        ax.contour(xs, ys, can_fly, levels=[0.5], colors="k", linestyles=":", linewidths=1.2)


def draw_side_by_side(out, maps):
    """λ_max held (rolling) against unilateral (m/s²) and unilateral with flight (units of g), each figure a row."""
    rows = [f for f in FIGURES if any((f[0], law) in maps for law in ("rolling", "unilateral", "g-units-bouncing"))]
    if not rows:
        return None
    fig, axes = plt.subplots(len(rows), 3, figsize=(14, 3.6 * len(rows)), squeeze=False, layout="constrained")
    for r, (name, fig_name, body, xl, yl) in enumerate(rows):
        for c, (law, label) in enumerate((("rolling", "held contact, m/s²"), ("unilateral", "unilateral, m/s²"),
                                          ("g-units-bouncing", "unilateral with flight, units of g"))):
            ax = axes[r][c]
            ax.set_title(f"{fig_name} (Gömböc {body}): {label}", fontsize=9)
            if (name, law) not in maps:
                ax.text(0.5, 0.5, "not made in this checkout", ha="center", va="center", transform=ax.transAxes)
                ax.set_axis_off()
                continue
            xs, ys, grid = maps[(name, law)]
            s = states(grid).astype(float)
            s[~numpy.isfinite(grid["lambda_max"])] = numpy.nan
            cmap = plt.get_cmap("RdBu_r").copy()
            cmap.set_bad("0.25")  # a point whose run failed
            im = ax.imshow(s, origin="lower", extent=cell_extent(xs, ys), aspect="auto",
                           interpolation="nearest", cmap=cmap, vmin=-1, vmax=1)
            flight_boundary(ax, xs, ys, grid)
            ax.set_xlabel(xl)
            ax.set_ylabel(yl if law != "g-units-bouncing" else yl.replace("m/s²", "g"))
        fig.colorbar(im, ax=list(axes[r]), ticks=[-1, 0, 1], label="regular / undecided / chaotic (grey: failed)")
    save_figure(fig, os.path.join(out, "where-chaos-lives.png"))
    plt.close(fig)
    return "where-chaos-lives.png"


def share_line(fig, body, label, grid):
    s = states(grid)
    n = s.size
    return (f"| {fig} (Gömböc {body}), {label} | {int((s == 1).sum())} ({(s == 1).sum() / n:.0%}) | {int((s == -1).sum())} "
            f"({(s == -1).sum() / n:.0%}) | {int((s == 0).sum())} | {int(numpy.isnan(grid['lambda_max']).sum())} |")


def decisive(out):
    """The long passes (cases/scans/stability/NAME-unilateral-3000.ini: every fourth node, 3000 periods) by figure."""
    found = {}
    for name, *_ in FIGURES:
        path = os.path.join(out, "scans", f"{name}-unilateral-3000-scan.csv")
        if os.path.exists(path):
            found[name] = load(path, [k for k, _ in MECHANISM] + ["lambda_error", "melnikov_margin"])
    return found


def held_on(held, long_map):
    """The held map's states at the long pass's nodes (which are nodes of the held map), or None."""
    hx, hy, hgrid = held
    lx, ly, _ = long_map
    ix = [int(numpy.argmin(numpy.abs(hx - x))) for x in lx]
    iy = [int(numpy.argmin(numpy.abs(hy - y))) for y in ly]
    if not (numpy.allclose(hx[ix], lx) and numpy.allclose(hy[iy], ly)):
        return None
    return states(hgrid)[numpy.ix_(iy, ix)]


def findings(maps, long_maps=None):
    """The rows of the findings table (i)-(iv)."""
    long_maps = long_maps or {}
    out = []
    for name, fig, body, _, _ in FIGURES:
        for law, label in LAWS:
            if (name, law) not in maps:
                continue
            grid = maps[(name, law)][2]
            s = states(grid)
            out.append(region_row(f"{fig}, {label}", s))
            fly = grid["geff_nonpositive_fraction"] > 0
            n_c = int((s == 1).sum())
            if n_c:
                fly_share = float((fly & (s == 1)).sum()) / n_c
                grounded = (~fly) & (s != 0)
                leak = float(((s == 1) & grounded).sum()) / grounded.sum() if grounded.sum() else 0.0
                text = (f"{pct(fly_share)} of the {n_c} chaotic points can fly (g_eff ≤ 0 in part of the period); of the "
                        f"{int(grounded.sum())} decided points that cannot, {pct(leak)} are chaotic")
                v = verdict(fly_share, fly_share >= FLIGHT_HOLDS and leak <= FLIGHT_LEAK, fly_share <= 1 - FLIGHT_FAILS)
            else:
                text, v = "no chaotic point", "*undecided*"
            out.append(f"| (ii) {fig}, {label}: chaos lives where the body can fly | {text} | {v} |")
            margin = grid["melnikov_margin"]
            if n_c and numpy.isfinite(margin).any():
                above = margin > 1.0
                n_r = int((s != 1).sum())
                frac_c = float((above & (s == 1)).sum()) / n_c
                frac_r = float((above & (s != 1)).sum()) / n_r if n_r else math.nan
                out.append(f"| (iii) {fig}, {label}: where λ > 0 the forcing is above the reduced Melnikov threshold | "
                           f"{pct(frac_c)} of {n_c} chaotic points above, {pct(frac_r)} of the {n_r} others | "
                           f"{verdict(frac_c, frac_c >= ABOVE_HOLDS and frac_c - frac_r >= ABOVE_SEPARATES, frac_c < ABOVE_FAILS)} |")
            else:
                out.append(f"| (iii) {fig}, {label}: where λ > 0 the forcing is above the reduced Melnikov threshold | "
                           f"{'no chaotic point' if not n_c else 'no margins in this map'} | *undecided* |")
        if name in long_maps:
            s = states(long_maps[name][2])
            out.append(region_row(f"{fig}, unilateral contact, A in m/s², 3000 periods on every fourth node", s))
            if (name, "rolling") in maps:
                held = held_on(maps[(name, "rolling")], long_maps[name])
                if held is not None:
                    out.append(survival_row(f"{fig}: the held law's verdict (100 periods) survives under the unilateral law "
                                            "(3000 periods), on the long pass's nodes", held, s))
        if (name, "rolling") in maps and (name, "unilateral") in maps:
            out.append(survival_row(f"{fig}: the held law's verdict survives under the unilateral law (m/s²), point by point",
                                    states(maps[(name, "rolling")][2]), states(maps[(name, "unilateral")][2])))
    return out


def region_row(what, s):
    """Finding (i) on the states s of a map's points."""
    n = s.size
    chaotic, regular = (s == 1).sum() / n, (s == -1).sum() / n
    return (f"| (i) {what}: chaos occupies a region of the forcing plane (section 8.3) | {pct(chaotic)} of {n} points chaotic, "
            f"{pct(regular)} regular | {verdict(chaotic, chaotic >= REGION_HOLDS, chaotic < REGION_FAILS and regular >= REGION_DECIDED)} |")


def survival_row(what, held, unilateral):
    """Finding (iv): the held law's states against the unilateral law's at the same points."""
    both = (held != 0) & (unilateral != 0)
    n_b = int(both.sum())
    same = float((held == unilateral)[both].sum()) / n_b if n_b else math.nan
    flips = int(((held == 1) & (unilateral == -1)).sum())
    return (f"| (iv) {what} | {pct(same)} of the {n_b} points decided under both; {flips} chaotic under the held law are "
            f"regular under the unilateral one | "
            f"{verdict(same if n_b >= SURVIVES_MIN else math.nan, same >= SURVIVES_HOLDS, same < SURVIVES_FAILS)} |")


def summary_sentence(out):
    """One sentence for the report's summary: where chaos lives under the unilateral law, from the maps made."""
    maps = maps_of(out)
    parts, fly, chaotic_total = [], 0, 0
    for name, fig, body, _, _ in FIGURES:
        for law, label in (("unilateral", "m/s²"), ("g-units-bouncing", "units of g")):
            if (name, law) in maps:
                grid = maps[(name, law)][2]
                s = states(grid)
                parts.append(f"{fig} ({label}) {(s == 1).sum() / s.size:.0%}")
                chaotic_total += int((s == 1).sum())
                fly += int(((grid["geff_nonpositive_fraction"] > 0) & (s == 1)).sum())
    for name, (xs, ys, grid) in decisive(out).items():
        fig = next(f for n, f, *_ in FIGURES if n == name)
        s = states(grid)
        parts.append(f"{fig} (m/s², 3000 periods on {s.size} nodes: {(s == 1).sum() / s.size:.0%} chaotic, "
                     f"{(s == -1).sum() / s.size:.0%} regular)")
    if not parts:
        return []
    text = ("**Where physical chaos lives** (the maps of `make scans` under a plane that can only push; section "
            "'Where physical chaos lives'): the share of each map's points with λ − 4σ > 0.01 1/s is " + ", ".join(parts) + "; ")
    text += (f"{fly} of the {chaotic_total} chaotic points ({fly / chaotic_total:.1%}) have g_eff ≤ 0 in part of the period "
             "(the body can fly there)." if chaotic_total else "no point is chaotic.")
    figure = draw_side_by_side(out, maps)
    return [text, ""] + ([f"![where chaos lives: held against unilateral, the dotted line where the body can fly]({figure})", ""]
                         if figure else [])


def stability(out, maps):
    """The unilateral maps (m/s²) against their 200-period passes on a sub-grid of their own nodes
    (cases/scans/stability/*-unilateral-200.ini): Spearman's ρ on the shared nodes, the held maps' rule."""
    rows = []
    for name, fig, body, _, _ in FIGURES:
        path = os.path.join(out, "scans", f"{name}-unilateral-200-scan.csv")
        if (name, "unilateral") not in maps or not os.path.exists(path):
            continue
        xs, ys, grid = maps[(name, "unilateral")]
        lx, ly, long_grid = load(path, [k for k, _ in STABILITY_METRICS])
        ix = [int(numpy.argmin(numpy.abs(xs - x))) for x in lx]
        iy = [int(numpy.argmin(numpy.abs(ys - y))) for y in ly]
        shared = all(abs(xs[i] - x) <= 1e-9 * max(1.0, abs(x)) for i, x in zip(ix, lx)) and \
            all(abs(ys[j] - y) <= 1e-9 * max(1.0, abs(y)) for j, y in zip(iy, ly))
        for key, metric in STABILITY_METRICS:
            if not shared:
                rows.append(f"| {fig}, unilateral (m/s²) | {metric} | the sub-grid's nodes are not the map's | *undecided* |")
                continue
            base = grid[key][numpy.ix_(iy, ix)]
            rho, lo, hi = spearman(base.ravel(), long_grid[key].ravel())
            rows.append(f"| {fig}, unilateral (m/s²) | {metric} | {rho:.2f} ({lo:.2f} … {hi:.2f}) on {base.size} nodes | "
                        f"{verdict(rho, lo > STABLE, hi < STABLE)} |")
    if not rows:
        return []
    return ["### Stability of the unilateral maps", "",
            f"Each unilateral map (m/s²) again with 200 periods a point on the middle half of each axis (its own nodes): the "
            f"two agree when Spearman's ρ has its 95 % interval above {STABLE}, disagree below, undecided across (the held "
            "maps' rule).", "", "| map | metric | ρ(100, 200 periods) | longer run |", "|---|---|---|---|"] + rows + [""]


def unilateral_section(out):
    lines = ["## Where physical chaos lives (Figs 10–13 under a plane that can only push)", ""]
    maps = maps_of(out)
    if not any((name, law) in maps for name, *_ in FIGURES for law, _ in LAWS):
        return lines + ["No maps under the unilateral law in this checkout: `make scans` computes them (cases/scans/*-unilateral.ini, "
                        "*-g-units-bouncing.ini, *-grid-unilateral.ini, 25 × 25 points of 100 periods) and writes them here.", ""]
    lines += ["The maps of `cases/scans` under the unilateral contact law, on the nodes of the held law's rolling maps (the same "
              "axes and ranges, 100 periods a point, metrics from period 20). A point is chaotic when λ − 4σ > 0.01 1/s, regular "
              "when λ + 4σ < 0.05 1/s (no exponent left at that resolution), undecided otherwise (R6); the dotted line separates the points where g_eff stays positive "
              "from those where it reaches 0 within the period (where the body can fly). The mechanism's panels are the points' "
              "own columns (the time in flight and on two points, the impacts and the energy they and friction took per "
              "period). At 100 periods a point a regular motion's exponent keeps 4 errors above 0.05 1/s, so no point of the "
              "m/s² maps can be called regular; `cases/scans/stability/*-unilateral-3000.ini` runs every fourth node of Figs "
              "10 and 12 for 3000 periods, where it can, and the findings use that pass where it was made.", ""]
    side = draw_side_by_side(out, maps)
    if side:
        lines += [f"![where chaos lives]({side})", ""]
    lines += ["| map | chaotic | regular | undecided | failed (NaN) |", "|---|---|---|---|---|"]
    for name, fig, body, xl, yl in FIGURES:
        for law, label in (("rolling", "held contact, m/s² (for comparison)"),) + LAWS:
            if (name, law) in maps:
                lines.append(share_line(fig, body, label, maps[(name, law)][2]))
    lines.append("")
    for name, fig, body, xl, yl in FIGURES:
        for law, label in LAWS:
            if (name, law) not in maps:
                continue
            xs, ys, grid = maps[(name, law)]
            png = f"scan-{name}-{law}"
            draw_mechanism(out, png, f"{fig}: Gömböc {body}, {label}", xl, yl if "m/s²" in label else yl.replace("m/s²", "g"),
                           xs, ys, grid)
            lines += [f"### {fig}, {label}", "", f"![{fig} {law}]({png}.png)", ""]
    lines += ["### Findings on the maps", "",
              f"Rules fixed in `reports/unilateral_maps.py` before the data: (i) holds when {REGION_HOLDS:.0%} or more of a map's "
              f"points are chaotic, fails below {REGION_FAILS:.0%} with {REGION_DECIDED:.0%} or more regular; (ii) holds when "
              f"{FLIGHT_HOLDS:.0%} or more of the chaotic points can fly and at most {FLIGHT_LEAK:.0%} of the decided points "
              f"that cannot are chaotic, fails when {FLIGHT_FAILS:.0%} or more of the chaotic points cannot fly; (iii) the held "
              f"maps' rule; (iv) holds when {SURVIVES_HOLDS:.0%} or more of the points decided under both laws agree, fails "
              f"below {SURVIVES_FAILS:.0%} (at least {SURVIVES_MIN} such points).", "",
              "| finding | evidence | verdict |", "|---|---|---|"]
    return lines + findings(maps, decisive(out)) + [""] + stability(out, maps)
