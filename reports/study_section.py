"""Report section "Chaotic for good, for a while, or not at all? (section 8.2, ensembles)": the ensembles of
cases/studies that `make study` last ran (OUT/studies/*-scan.csv): the distribution of λ over random
initial attitudes, the two halves of each record, and a verdict by a rule fixed here before the data.
Recomputes no physics."""
import csv
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy  # noqa: E402

from common import finish_figure, load_json  # noqa: E402

# The rule, fixed before the data. A member is chaotic over its record when λ − 2σ > 0.01 1/s (the no-chaos
# margin of section 8.2 at 2 batch-means errors: one member is a weak piece of evidence, the ensemble decides).
# Its late half is chaotic when the second half's mean rate exceeds LATE = 0.05 1/s: a separation growing by
# e^(0.05 t) over half a 3000-period record (about 520 s) grows by e^26, far above the noise of a half-record
# mean. The ensemble is
#   sustained  when 75 % or more of the members are chaotic in their late half,
#   regular    when 25 % or fewer are chaotic over their whole record,
#   transient  when neither, and the median late half is below the median early half by LATE or more while
#              fewer than half the members are chaotic late (chaos that dies out, with state-dependent lifetimes),
#   undecided  otherwise.
# The claim "the forced motion is chaotic" (section 8.2) holds when sustained, fails when transient or regular.
# A member whose run failed (an ensemble with failed_points = record: every metric NaN, for example an impact
# a rough plane cannot absorb) is left out and counted; when more than FAILED = 25 % of the members failed, the
# ensemble is undecided whatever the rest says (the model does not follow enough of them).
MARGIN, LATE, FAILED = 0.01, 0.05, 0.25


def failed_members(rows):
    return sum(1 for r in rows if math.isnan(float(r["lambda_max"])))


def handed_over(rows):
    """Members whose run was handed to time-stepping somewhere (hand_over: the event-driven law could not follow)."""
    return sum(1 for r in rows if float(r.get("stepped_fraction", "0") or "0") > 0.0)


def classify(rows):
    all_rows = rows
    rows = [r for r in rows if not math.isnan(float(r["lambda_max"]))]
    if not rows:
        nan = float("nan")
        return numpy.array([nan]), numpy.array([nan]), numpy.array([nan]), numpy.array([nan]), nan, nan, "undecided"
    lam = numpy.array([float(r["lambda_max"]) for r in rows])
    err = numpy.array([float(r["lambda_error"]) for r in rows])
    early = numpy.array([float(r["lambda_first_half"]) for r in rows])
    late = numpy.array([float(r["lambda_second_half"]) for r in rows])
    chaotic = float(numpy.mean(lam - 2 * err > MARGIN))
    chaotic_late = float(numpy.mean(late > LATE))
    if chaotic_late >= 0.75:
        kind = "sustained"
    elif chaotic <= 0.25:
        kind = "regular"
    elif numpy.median(early) - numpy.median(late) >= LATE and chaotic_late < 0.5:
        kind = "transient"
    else:
        kind = "undecided"
    if failed_members(all_rows) > FAILED * len(all_rows):
        kind = "undecided"
    return lam, err, early, late, chaotic, chaotic_late, kind


def ensembles_of(folder, name):
    """[(label, rows)] of one study's CSV: one ensemble, or, for a study whose second axis is the plane's Coulomb
    coefficient (model.friction), one ensemble per value, labelled with it."""
    rows = list(csv.DictReader(open(os.path.join(folder, name))))
    label = name.replace("-scan.csv", "")
    if not rows or "model.friction" not in rows[0]:
        return [(label, rows, None)]
    values = sorted({float(r["model.friction"]) for r in rows})
    return [(f"{label} (μ = {mu:g})", [r for r in rows if float(r["model.friction"]) == mu], f"{mu:g}") for mu in values]


def ensemble_readings(out):
    """{(body, law): reading} of the ensembles `make study` last ran (sustained, transient, regular, undecided);
    law is "held" (ensemble-gomboc-BODY-rolling), "unilateral" (ensemble-gomboc-BODY-unilateral), or, for Table 1
    read in units of g under the unilateral law with flight, "flight" (e = 0, ensemble-gomboc-BODY-g-units-flight)
    and "bouncing" (e = 0.5, ensemble-gomboc-BODY-g-units-bouncing); on a plane of Coulomb friction μ,
    "unilateral, mu = μ" (ensemble-gomboc-BODY-friction) and "flight, mu = μ" (ensemble-gomboc-BODY-g-units-friction)."""
    folder = os.path.join(out, "study")
    readings = {}
    if not os.path.isdir(folder):
        return readings
    for name in sorted(os.listdir(folder)):
        for suffix, law in (("-g-units-flight-scan.csv", "flight"), ("-g-units-bouncing-scan.csv", "bouncing"),
                            ("-g-units-friction-scan.csv", "flight"), ("-friction-scan.csv", "unilateral"),
                            ("-rolling-scan.csv", "held"), ("-unilateral-scan.csv", "unilateral")):
            if name.startswith("ensemble-gomboc-") and name.endswith(suffix):
                body = name[len("ensemble-gomboc-"):-len(suffix)]
                for _, rows, mu in ensembles_of(folder, name):
                    readings[(body, law if mu is None else f"{law}, mu = {mu}")] = classify(rows)[-1]
                break
    return readings


def study_section(out):
    lines = ["## Chaotic for good, for a while, or not at all? (section 8.2, ensembles)", ""]
    folder = os.path.join(out, "study")
    files = sorted(f for f in os.listdir(folder) if f.endswith("-scan.csv")) if os.path.isdir(folder) else []
    if not files:
        return lines + ["No ensembles in this checkout: `make study` runs those of `cases/studies` (32 random initial "
                        "attitudes per body and contact law, 64 for Gömböc I, 3000 periods each; Table 1 in units of g with "
                        "flight, and on planes of Coulomb friction μ = 0.3 and 0.6, 16 attitudes x 1000 periods) and writes them here.", ""]
    stamp = os.path.join(out, "gates", "study.json")
    when = ""
    if os.path.exists(stamp):
        s = load_json(stamp)
        when = f" Made by `make study` on {s['date']} at commit {s['commit']} ({s['result']})."
    lines += ["Each ensemble runs one scene from initial attitudes drawn uniformly on the rotations (seeded), and "
              f"records λ over the whole record and over its two halves.{when} The rule (fixed in "
              "`reports/study_section.py` before the data): *sustained* when 75 % or more of the members still have a "
              f"rate above {LATE} 1/s in their second half; *regular* when 25 % or fewer have λ − 2σ > {MARGIN} 1/s over "
              "their record; *transient* when the median second half falls below the median first half by "
              f"{LATE} 1/s or more and fewer than half the members stay chaotic; *undecided* otherwise. The claim that "
              "the forced motion is chaotic holds when sustained and fails when transient or regular. A member's chaos "
              "has ended when the last of 12 windows of its record with a mean exponent above 0.05 1/s is not the last "
              "window; its lifetime is that window's end (members still chaotic at the end are not counted: censored). "
              "A member whose run failed (failed_points = record: the model could not follow it) is left out and "
              f"counted; with more than {FAILED:.0%} of the members failed the ensemble is undecided. The friction "
              "ensembles hand a member over to time-stepping where the event-driven law cannot follow it (Painlevé's "
              "paradox; `hand_over`, docs/stepping.md) and back where it flies: such members count, and are counted.", "",
              "| ensemble | members (failed; handed over) | λ median [quartiles] | λ − 2σ > 0.01 | first half, median | second half, median | "
              "chaotic in the second half | chaos ended (lifetime, periods: median [range]) | reading | the paper's claim |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    ensembles = [e for name in files for e in ensembles_of(folder, name)]
    # one row an ensemble, its name written out beside it (tilted names on one axis overlapped)
    fig, ax = plt.subplots(figsize=(9.5, max(3.0, 0.5 * len(ensembles) + 1.2)))
    for k, (label, rows, _) in enumerate(ensembles):
        lam, err, early, late, chaotic, chaotic_late, kind = classify(rows)
        q1, med, q3 = numpy.percentile(lam, [25, 50, 75])
        verdict = {"sustained": "holds", "transient": "**fails** (transient)", "regular": "**fails** (regular)"}.get(kind, "*undecided*")
        lifetimes = numpy.array([float(r.get("chaos_lifetime_periods", "nan")) for r in rows])
        ended = lifetimes[numpy.isfinite(lifetimes)]
        ended_text = (f"{len(ended)} of {len(rows)}: {numpy.median(ended):.0f} [{ended.min():.0f}, {ended.max():.0f}]"
                      if len(ended) else f"0 of {len(rows)}")
        if not numpy.any(~numpy.isnan(lifetimes)):
            ended_text = "—"
        lines.append(f"| {label} | {len(rows)} ({failed_members(rows)}; {handed_over(rows)}) | {med:.3f} [{q1:.3f}, {q3:.3f}] | {chaotic:.0%} | {numpy.median(early):.3f} | "
                     f"{numpy.median(late):.3f} | {chaotic_late:.0%} | {ended_text} | {kind} | {verdict} |")
        ax.plot(early, [k + 0.12] * len(early), "o", ms=3, color="C0", label="first half" if k == 0 else None)
        ax.plot(late, [k - 0.12] * len(late), "o", ms=3, color="C3", label="second half" if k == 0 else None)
        for e, l in zip(early, late):
            ax.plot([e, l], [k + 0.12, k - 0.12], color="0.8", lw=0.5)
    ax.axvline(LATE, color="k", lw=0.5, ls="--")
    ax.set_yticks(range(len(ensembles)))
    ax.set_yticklabels([label.replace("ensemble-", "") for label, _, _ in ensembles], fontsize=8)
    ax.invert_yaxis()
    ax.set_xlabel(f"λ over the half record [1/s] (dashed: {LATE:g} 1/s, the chaotic threshold)")
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title("Each member's exponent over the first and the second half of its record", fontsize=9)
    finish_figure(fig, os.path.join(out, "ensembles.png"))
    lines += ["", "![ensembles](ensembles.png)", ""]
    if not all(math.isfinite(x) for x in (chaotic, chaotic_late)):
        lines.append("(an ensemble without λ: its scan file must list the lambda metric)")
    return lines
