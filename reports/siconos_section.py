"""Report section "Against Siconos", from siconos.json (verify/siconos.c), the suite's rows of checks.json,
references/siconos/polyhedron.json (Siconos's runs, their steps and costs) and, when `make bench` ran,
bench-siconos.json (the work-precision ratio). Recomputes no physics."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from common import finish_figure, load_json, section_start  # noqa: E402

SUITE = "Against Siconos: the same scenes in another engine"


def event_figure(out, scenes):
    fig, axes = plt.subplots(len(scenes), 1, figsize=(8, 2.2 * len(scenes)), sharex=False)
    axes = axes if len(scenes) > 1 else [axes]
    for ax, s in zip(axes, scenes):
        ax.semilogy(s["t"], [abs(d) for d in s["dt"]], "o", ms=3, label="|gomboc − Siconos|")
        ax.semilogy(s["t"], s["tolerance"], "-", lw=0.8, color="0.4", label="tolerance 3|t(h) − t(2h)| + 2h")
        ax.set_title(s["scene"], fontsize=8)
        ax.set_ylabel("event time [s]", fontsize=7)
        ax.tick_params(labelsize=7)
    axes[0].legend(fontsize=7)
    axes[-1].set_xlabel("t [s]")
    fig.suptitle("Each event (a vertex starting to carry the body) that both engines and Siconos's two finest steps "
                 "agree on", fontsize=8)
    finish_figure(fig, os.path.join(out, "siconos-events.png"))


def work_precision_figure(out, bench):
    fig, ax = plt.subplots(figsize=(6, 4))
    for engine, marker in (("gomboc", "o-"), ("siconos", "s-")):
        pts = [r for r in bench["rows"] if r["engine"] == engine and isinstance(r["error"], float) and r["error"] == r["error"]]
        ax.loglog([r["seconds"] for r in pts], [r["error"] for r in pts], marker, label=engine)
        for r in pts:
            ax.annotate(r["setting"], (r["seconds"], r["error"]), fontsize=6, xytext=(3, 3), textcoords="offset points")
    ax.set_xlabel("wall time [s] (gomboc: whole process; Siconos: its time-stepping loop)")
    ax.set_ylabel(f"largest error in the first {bench['k']} event times [s]")
    ax.set_title(f"Gömböc I's grid polyhedron on a still plane, {bench['periods']} periods", fontsize=9)
    ax.legend(fontsize=8)
    finish_figure(fig, os.path.join(out, "siconos-work-precision.png"))


def siconos_section(out, rows):
    lines, data = section_start(out, "Against Siconos", "siconos.json",
                                "siconos.json missing: the suite 'Against Siconos' did not run")
    if data is None:
        return lines
    reference = load_json(os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "references", "siconos",
                                       "polyhedron.json"))
    versions = reference.get("versions", {}) if reference else {}
    lines += ["The grid polyhedron of each Table 1 body, built from gomboc's own outputs (`gomboc shape --json`, "
              "`gomboc shape --grid-nodes`), run in Siconos "
              f"{versions.get('siconos', '?')} (Debian's `python3-siconos`): a Newton–Euler body, an exact vertex–plane "
              "relation per hull vertex near the plane (not Bullet, whose Debian build is single precision), Newton's "
              "plastic impact with Coulomb friction (μ = 10 for the rough plane), Moreau–Jean time stepping and NSGS to "
              f"{reference.get('solver_tolerance', '?') if reference else '?'}. "
              "`references/siconos/polyhedron.py` ran them (`make references`); `verify/siconos.c` runs gomboc on the "
              "same case files (`cases/siconos/`) in every `make verify` and compares. Siconos's error at its finest step h "
              "is e = max(|t(h) − t(2h)|, |t(2h) − t(4h)|/2) (first order), so an event's time must agree to 3e + 2h. "
              "The sequence of vertices must agree at least as far as Siconos has settled its own: the same vertex at h "
              "and 2h, each event's time known better than its distance to its neighbours. The time to rest, the time "
              "on two points and the ensemble's statistics compare two models and are decided by rules written before "
              "the data. These comparisons are not claims of the paper and are not counted among its findings. See "
              "`docs/siconos.md`.", ""]
    suite_rows = [r for r in rows if r.get("suite") == SUITE]
    failed = [r for r in suite_rows if not r["passed"]]
    lines += [f"{len(suite_rows)} rows in this run, {len(failed)} failed.", ""]
    scenes = [s for s in data["rows"] if s.get("kind") != "ensemble"]
    if scenes:
        lines += ["| scene | events gomboc / Siconos | agree on | Siconos settled | worst time ratio | worst energy "
                  "ratio | two points: gomboc / Siconos (2h) | rest: gomboc / Siconos [s] | CPU gomboc / Siconos at h, all threads [s] |",
                  "|---|---|---|---|---|---|---|---|---|"]
        for s in scenes:
            rest = (f"{s['rest_gomboc']:.4f} / {s['rest_siconos']:.4f}" if "rest_gomboc" in s and "rest_siconos" in s
                    else "—")
            lines.append(f"| {s['scene']} (h = {s['h_fine']:.3g} s) | {s['events_gomboc']:.0f} / {s['events_siconos']:.0f} | "
                         f"{s['agree']:.0f} | {s['siconos_self']:.0f} | {s['time_ratio_worst']:.2f} | "
                         f"{s['kinetic_ratio_worst']:.2f} | {s['two_point_gomboc']:.3f} / {s['two_point_siconos']:.3f} "
                         f"({s['two_point_siconos_coarse']:.3f}) | {rest} | {s['seconds_gomboc']:.3g} / "
                         f"{s['seconds_siconos']:.3g} |")
        lines += [""]
        parted = [s for s in scenes if "part_gomboc_t" in s]
        for s in parted:
            lines.append(f"- {s['scene']}: the runs part at event {s['agree']:.0f}: gomboc's vertex "
                         f"{s['part_gomboc_vertex']:.0f} at t = {s['part_gomboc_t']:.5f} s, Siconos's "
                         f"{s['part_siconos_vertex']:.0f} at {s['part_siconos_t']:.5f} s"
                         + (f" (gomboc's next event {s['part_gomboc_next_t'] - s['part_gomboc_t']:.2g} s later)"
                            if "part_gomboc_next_t" in s else "")
                         + (f"; λ = {s['lambda']:.3g} ± {s['lambda_error']:.2g} /s (gomboc, 60 periods)"
                            if isinstance(s.get("lambda"), float) else "")
                         + (f", which predicts the parting at t ≈ {s['t_part_predicted']:.3g} s" if "t_part_predicted" in s
                            else ", not positive beyond its error: no exponential separation predicts the parting")
                         + ".")
        if parted:
            lines += [""]
        timed = [s for s in scenes if s.get("t")]
        if timed:
            event_figure(out, timed)
            lines += ["![event times against Siconos](siconos-events.png)", ""]
    ensemble = [s for s in data["rows"] if s.get("kind") == "ensemble"]
    if ensemble:
        lines += [f"Ensemble on Table 1's plane ({ensemble[0]['members']:.0f} members compared, "
                  f"{ensemble[0].get('left_out', 0):.0f} left out for a failed solve in Siconos; random attitudes of both "
                  "bodies, paired):", "", "| statistic | gomboc | Siconos | paired difference ± standard error |", "|---|---|---|---|"]
        for s in ensemble:
            lines.append(f"| {s['statistic'].replace('_', ' ')} | {s['gomboc']:.4g} | {s['siconos']:.4g} | "
                         f"{s['difference']:.3g} ± {s['standard_error']:.2g} |")
        lines += [""]
    verdicts = [r for r in suite_rows if r["kind"] == "finding"]
    if verdicts:
        lines += ["Comparisons of the two models, each decided by the rule in its row:", ""]
        lines += [f"- {r['quantity']}: **{r['verdict']}** ({r['detail']})" for r in verdicts]
        lines += [""]
    bench = load_json(os.path.join(out, "bench-siconos.json")) if os.path.exists(os.path.join(out, "bench-siconos.json")) else None
    if bench:
        lines += [f"Speed at equal error (`make bench`, {bench['periods']} periods of the still scene of Gömböc I, the "
                  f"error over the first {bench['k']} event times): worst ratio **{bench['worst_ratio']:.0f}×** (goal ≥ 100×).",
                  ""]
        lines += ["| Siconos step | its error [s] | gomboc setting | its error [s] | ratio |", "|---|---|---|---|---|"]
        lines += [f"| {q['siconos']} | {q['siconos_error']:.3g} | {q['gomboc']} | {q['gomboc_error']:.3g} | {q['ratio']:.0f}× |"
                  for q in bench["ratios"]]
        work_precision_figure(out, bench)
        lines += ["", "![work-precision against Siconos](siconos-work-precision.png)", ""]
    else:
        lines += ["(`make bench` has not run here: the work-precision ratio against Siconos is in its output.)", ""]
    return lines
