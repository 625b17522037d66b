"""Report section "The Melnikov criterion (section 7)", from melnikov.json (verify/s7_melnikov.c) and the
section-7 rows of checks.json: the oracles, the direct-splitting convergence, the Gömböc's reduced model
(U, M, S over one turn, its contact ties), eq 93 against the exact condition over ψ, the threshold
curves, the period map's manifolds (tangle.json, verify/s7_tangle.c), and the verdicts. Recomputes no physics."""
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

from common import finish_figure, load_json, section_start  # noqa: E402


def splitting_figure(out, rows):
    models = []
    for r in rows:
        if r["model"] not in models:
            models.append(r["model"])
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for name in models:
        pts = [r for r in rows if r["model"] == name]
        eps = [r["epsilon_mu"] for r in pts]
        ax.loglog(eps, [abs(r["measured"] - r["predicted_exact"]) for r in pts], "o-", label=f"{name}: q̇ G (exact)")
        paper = [abs(r["measured"] - r["predicted_paper"]) for r in pts]
        if max(paper) > 10 * max(abs(r["measured"] - r["predicted_exact"]) for r in pts):
            ax.loglog(eps, paper, "x--", label=f"{name}: p G (eq 86)")
    e = [4e-3, 5e-4]
    ax.loglog(e, [1e-4 * (x / 4e-3) ** 2 for x in e], "k:", label="slope 2")
    ax.set_xlabel("ε μ")
    ax.set_ylabel("|d measured − ε M / |f||")
    ax.legend(fontsize=7)
    ax.set_title("Direct splitting under damping alone", fontsize=9)
    finish_figure(fig, os.path.join(out, "melnikov-splitting.png"))


def body_figure(out, bodies):
    fig, axes = plt.subplots(4, 1, figsize=(9, 10), sharex=True)
    for b in bodies:
        f = b["functions"]
        q = [p[0] for p in f]
        for ax, k, label in zip(axes, (1, 2, 3), ("U [J]", "M [kg m²]", "S [kg]")):
            ax.plot(q, [p[k] for p in f], lw=1, label=f"Gömböc {b['body']}")
            ax.set_ylabel(label)
        # the separatrix (eq 83) with M frozen at the top: p_h = sqrt(2 M(q_u) (E_s - U)), E_s = 0
        axes[3].plot(q, [math.sqrt(2 * b["M_top"] * max(0.0, -p[1])) for p in f], lw=1, label=f"Gömböc {b['body']}")
        axes[3].set_ylabel("p_h [kg m²/s]")
        for t in b.get("tie_q", []):
            for ax in axes:
                ax.axvline(t, color="0.7", lw=0.5)
    axes[0].legend(fontsize=8)
    axes[-1].set_xlabel("q [rad] (rolling over the top at q = 0)")
    fig.suptitle("The reduced model over one turn and its separatrix (grey: contact ties)", fontsize=9)
    finish_figure(fig, os.path.join(out, "melnikov-model.png"))


def threshold_figure(out, bodies):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4))
    for b in bodies:
        c = b["threshold_curve"]
        axes[0].semilogy([p[0] for p in c], [p[2] for p in c], "o-", ms=3, label=f"Gömböc {b['body']}: exact")
        axes[0].semilogy([p[0] for p in c], [p[1] for p in c], "--", lw=0.8, label=f"Gömböc {b['body']}: eq 93")
        s = b["psi_scan"]
        axes[1].plot([r["psi"] for r in s], [r["threshold_A1_exact"] / r["threshold_A1_eq93"] for r in s], label=f"Gömböc {b['body']}")
    curve_path = os.path.join(out, "tangle-curve.json")  # make verify-full's: where the manifolds start to cross
    if os.path.exists(curve_path):
        rows = [r for r in load_json(curve_path) if not r.get("status")]
        for body in sorted({r["body"] for r in rows}):
            mine = [r for r in rows if r["body"] == body]
            lo = [r["threshold_A1_manifolds_lo"] for r in mine]
            hi = [r["threshold_A1_manifolds_hi"] for r in mine]
            axes[0].errorbar([r["omega"] for r in mine], [0.5 * (a + b) for a, b in zip(lo, hi)],
                             yerr=[[0.5 * (b - a) for a, b in zip(lo, hi)]] * 2, fmt="s", ms=4, capsize=2,
                             label=f"Gömböc {body}: the manifolds start to cross")
    axes[0].axhline(2.0, color="k", lw=0.5)
    axes[0].set_xlabel("ω [rad/s]")
    axes[0].set_ylabel("threshold A1 [m/s²]")
    axes[0].legend(fontsize=7)
    axes[0].set_title("Threshold A1 at Table 1's A2/A1 and ψ (line: Table 1's A1)", fontsize=9)
    axes[1].set_xlabel("ψ [rad]")
    axes[1].set_ylabel("exact / eq 93")
    axes[1].legend(fontsize=7)
    axes[1].set_title("Eq 93 against the exact condition at Table 1's ω", fontsize=9)
    finish_figure(fig, os.path.join(out, "melnikov-thresholds.png"))


def tangle_figure(out, pictures):
    fig, axes = plt.subplots(len(pictures), 1, figsize=(10, 4.2 * len(pictures)), squeeze=False)
    for ax, pic in zip(axes[:, 0], pictures):
        ax.plot(pic["unstable"]["q"], pic["unstable"]["p"], ",", color="tab:red", ms=1, label="unstable branch of q = 0")
        ax.plot(pic["stable"]["q"], pic["stable"]["p"], ",", color="tab:blue", ms=1, label="stable branch of q = 2π")
        ax.plot(pic["homoclinic"]["q"], pic["homoclinic"]["p"], "ko", ms=3, mfc="none", label="homoclinic points (one domain)")
        ax.set_xlim(0, 2 * math.pi)
        ax.set_ylabel("p [kg m²/s]")
        ax.set_title(f"Gömböc {pic['model']}: the period map's manifolds at Table 1's forcing (phase 0)", fontsize=9)
        ax.legend(handles=[Line2D([], [], color="tab:red", lw=1.5, label="unstable branch of q = 0"),
                           Line2D([], [], color="tab:blue", lw=1.5, label="stable branch of q = 2π"),
                           Line2D([], [], color="k", marker="o", ms=4, mfc="none", ls="",
                                  label="homoclinic points (one fundamental domain)")], fontsize=7, loc="upper right")
    axes[-1, 0].set_xlabel("q [rad]")
    finish_figure(fig, os.path.join(out, "melnikov-tangle.png"))


def tangle_lines(out):
    """The period map's manifolds (tangle.json, verify/s7_tangle.c): small-ε oracles and Table 1's forcing."""
    path = os.path.join(out, "tangle.json")
    if not os.path.exists(path):
        return ["(The period map's manifolds: tangle.json missing, the suite did not write it.)", ""]
    doc = load_json(path)
    rows = doc.get("tangles", [])
    lines = ["### The manifolds themselves", "",
             "The period map's unstable and stable manifolds grown from fundamental domains and intersected, each "
             "crossing confirmed on finer pieces of both curves (`docs/melnikov.md`, \"The manifolds at the scene's "
             "forcing\"). At small ε the homoclinic orbits a fundamental domain crosses must be the simple zeros of "
             "M(t₀); at ε = 1 (Table 1's forcing for the bodies) they are what the first order leaves open.", "",
             "| model | ε | spacing | multipliers | passage [periods] | chord crossings | homoclinic orbits | "
             "smallest angle [°] |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r.get("status"):
            lines.append(f"| {r['model']} | {r['epsilon']:g} | {r['spacing']:g} | failed (status {r['status']:.0f}) "
                         "| | | | |")
            continue
        angle = f"{r['smallest_angle_deg']:.2f}" if r["homoclinic_orbits"] else "–"
        lines.append(f"| {r['model']} | {r['epsilon']:g} | {r['spacing']:g} | {r['multiplier_unstable']:.4f}, "
                     f"{r['multiplier_stable']:.4f} | {r['passage_periods']:.2f} | {r['chord_crossings']:.0f} | "
                     f"{r['homoclinic_orbits']:.0f} | {angle} |")
    thresholds = doc.get("thresholds", [])
    if thresholds:
        lines += ["", "Where the manifolds start to cross as A₁ grows (A₂/A₁, ω and ψ of Table 1, the damping kept; the "
                  "bracket after five bisections at spacing 0.02), against the first order's exact threshold:", "",
                  "| body | A₁ without crossing [m/s²] | A₁ with crossing [m/s²] | first-order threshold [m/s²] | "
                  "difference |", "|---|---|---|---|---|"]
        for t in thresholds:
            lo, hi, x = t["threshold_A1_manifolds_lo"], t["threshold_A1_manifolds_hi"], t["threshold_A1_first_order"]
            lines.append(f"| {t['model']} | {lo:.3f} | {hi:.3f} | {x:.3f} | {100 * (0.5 * (lo + hi) / x - 1):+.0f} % |")
    curve_path = os.path.join(out, "tangle-curve.json")
    if os.path.exists(curve_path):
        lines += ["", "Over the (ω, A₁) maps' range of ω (`make verify-full`; also the squares of the threshold figure above):",
                  "", "| body | ω [rad/s] | A₁ without crossing | A₁ with crossing | first-order threshold | difference |",
                  "|---|---|---|---|---|---|"]
        for r in load_json(curve_path):
            if r.get("status"):
                lines.append(f"| {r['body']} | {r['omega']:g} | failed | | | |")
                continue
            lo, hi, x = r["threshold_A1_manifolds_lo"], r["threshold_A1_manifolds_hi"], r["threshold_A1_first_order"]
            lines.append(f"| {r['body']} | {r['omega']:g} | {lo:.3f} | {hi:.3f} | {x:.3f} | "
                         f"{100 * (0.5 * (lo + hi) / x - 1):+.0f} % |")
    pictures = doc.get("pictures", [])
    if pictures:
        tangle_figure(out, pictures)
        lines += ["", "![the manifolds at Table 1's forcing](melnikov-tangle.png)"]
    return lines + [""]


def melnikov_section(out, rows):
    lines, data = section_start(out, "The Melnikov criterion (section 7)", "melnikov.json",
                                "Melnikov data missing: the suite did not write it")
    if data is None:
        return lines
    lines += ["The reduced model rolls the body once over its top, the maximum of r, about the horizontal axis across "
              "the steepest descent of the centroid height there; U, M and S come from the certified support function "
              "(`docs/melnikov.md`). The integrals are GSL quadratures along the separatrix; the criterion is judged "
              "as eq 93 states it and exactly (the largest oscillatory part of M(t₀) against μD).", "",
              "### Oracles", "", "| system | ω | D | C₁ | C₁ closed form | threshold ν/μ | closed form |",
              "|---|---|---|---|---|---|---|"]
    for r in data.get("closed_forms", []):
        lines.append(f"| {r['system']} | {r['omega']:g} | {r['D']:.12g} | {r['C1']:.12g} | {r['C1_exact']:.12g} | "
                     f"{r['threshold']:.12g} | {r['threshold_exact']:.12g} |")
    lines += ["", "The Duffing loop, the parity of odd integrands, the two computations of the orbit (quadrature in q "
              "and the flow of eq 78) and eq 91 against eq 86 are rows of the table of every check.", ""]
    if data.get("splitting"):
        splitting_figure(out, data["splitting"])
        lines += ["### Direct splitting", "",
                  "The perturbed manifolds of the damped saddle integrated to a section; their distance less the first-"
                  "order prediction ε M/|f| falls as ε² with the weight q̇ G. With a varying M, eq 86's weight p G leaves "
                  "an error that does not fall.", "", "![direct splitting](melnikov-splitting.png)", ""]
    forced = data.get("forced_splitting", [])
    if forced:
        lines += ["Under the whole perturbation (damping and both harmonics) the saddle's periodic orbit and its manifolds, "
                  "at three phases t₀; the smallest ε of each:", "", "| model | t₀ | ε | d measured | ε M(t₀)/|f| |",
                  "|---|---|---|---|---|"]
        last = {}
        for r in forced:
            last[(r["model"], r["t0"])] = r
        for (model, t0), r in last.items():
            lines.append(f"| {model} | {t0:.4g} | {r['epsilon']:g} | {r['measured']:.6g} | {r['predicted']:.6g} |")
        lines.append("")
    table = data.get("table", [])
    if table:
        lines += ["### The separatrix tabulated once per body", "",
                  "A scan and `gomboc melnikov` take the integrals at many ω from one table per body and octave of ω: "
                  "the path of the adaptive quadrature cut into panels in u that end at the model's knots and span at "
                  "most 1.5 rad of the highest harmonic's phase, with t, q, |p| and U, M, S at the panels' 12 "
                  "Gauss–Legendre nodes; an ω is then a sum over the nodes. Against the adaptive path at ω = 12, 18 "
                  "and 24 rad/s (ω_max = 24):", "",
                  "| body | nodes | max difference / max integral | table [s] | one ω from the table [s] | "
                  "one ω adaptive [s] | ratio |", "|---|---|---|---|---|---|---|"]
        for r in table:
            ratio = r["adaptive_seconds_per_omega"] / r["sums_seconds_per_omega"] if r["sums_seconds_per_omega"] > 0 else float("nan")
            lines.append(f"| {r['body']} | {r['nodes']:.0f} | {r['relative_difference']:.2g} | {r['table_seconds']:.3f} | "
                         f"{r['sums_seconds_per_omega']:.4f} | {r['adaptive_seconds_per_omega']:.3f} | {ratio:.0f}× |")
        lines.append("")
    bodies = data.get("bodies", [])
    if bodies:
        body_figure(out, bodies)
        threshold_figure(out, bodies)
        lines += ["### The Gömböc's reduced model", "",
                  "| body | r_max | curvatures of H at the top (rocking, across) | contact ties | M(q_u) | saddle rate [1/s] | "
                  "D | A₁* | A₂* | μ = c/M(q_u) | threshold A1, eq 93 | threshold A1, exact |",
                  "|---|---|---|---|---|---|---|---|---|---|---|---|"]
        for b in bodies:
            lines.append(f"| {b['body']} | {b['r_max']:.6f} | {b['curvature_rocking']:.4f}, {b['curvature_across']:.4f} | "
                         f"{b['ties']:.0f} at q = {', '.join(f'{t:.3f}' for t in b.get('tie_q', []))} | {b['M_top']:.4f} | "
                         f"{b['saddle_rate']:.4f} | {b['D']:.5g} | {b['A1_star']:.4g} | {b['A2_star']:.4g} | {b['mu']:.4g} | "
                         f"{b['threshold_A1_eq93']:.4g} | {b['threshold_A1_exact']:.4g} |")
        lines += ["", "![the reduced model](melnikov-model.png)", "", "![thresholds](melnikov-thresholds.png)", "",
                  "The forcing modulates the potential by (A1 + A2)/g of itself (the Table 1 verdict rows give it): the "
                  "first-order criterion is applied there outside the small-ε regime it is derived for, as the paper "
                  "applies it.", ""]
    lines += tangle_lines(out)
    verdicts = [r for r in rows if r.get("section") == "7" and r.get("claim")]
    if verdicts:
        # the verdicts themselves are rows of the findings table at the top (§7): one table, not two
        tally = {v: sum(1 for r in verdicts if r.get("verdict") == v) for v in ("holds", "fails", "undecided")}
        lines += [f"The claims of section 7 are judged in the findings table above (its §7 rows): {tally['holds']} hold, "
                  f"{tally['fails']} fail, {tally['undecided']} undecided.", ""]
    return lines
