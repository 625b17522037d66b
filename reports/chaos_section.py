"""Report section "Is the chaos real?" (paper sections 6 and 8.2), from the data verify/s6_chaos.c
writes: chaos.json (lambda_max of both bodies under every variation, and the baseline records for
Fig 9), lyapunov-estimator.json (the estimator's own study on Lorenz) and pivot-rate.json (the
inverted-pendulum rate of a frozen contact against each run's exponent). Recomputes no physics."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from common import finish_figure, layout, load_json, section_start  # noqa: E402


def figure_9(out, records):
    fig, axes = plt.subplots(len(records), 1, figsize=(10, 2.6 * len(records)), sharex=True)
    for ax, rec in zip(axes, records):
        n = range(1, len(rec["running"]) + 1)
        ax.plot(n, rec["instantaneous"], lw=0.6, color="0.6", label="λ_inst (per period)")
        ax.plot(n, rec["running"], lw=1.5, label="running λ_max")
        ax.axhline(0.0, color="k", lw=0.5)
        ax.set_title(f"Gömböc {rec['body']}: {rec['variation']}", fontsize=9)
        ax.set_ylabel("λ [1/s]")
    axes[0].legend(fontsize=8)
    axes[-1].set_xlabel("forcing period")
    finish_figure(fig, os.path.join(out, "fig9-lyapunov.png"))


def chaos_section(out, rows):
    lines, data = section_start(out, "Is the chaos real? (sections 6, 8.2)", "chaos.json",
                                "chaos data missing: the test did not write it")
    if data is None:
        return lines
    periods = data["periods"]
    lines += ["The maximal Lyapunov exponent by the pair estimator of eq 77: two trajectories, the second put back at",
              f"delta0 along the current separation once per forcing period; {periods:g} periods from R0 = I, omega0 = 0;",
              "each record's warm-up (left out of its mean) by MSER-5 and its error bar by batch means, the batch length",
              "the shortest whose means are uncorrelated at lag 1 (at least 10 batches), both chosen from the record itself",
              "(`src/gb_lyapunov.h`; a record whose warm-up reaches the bound of half its length did not settle).",
              "The separation is a 6-vector: the body-frame rotation",
              "vector between the two attitudes [rad] and the angular-velocity difference divided by the forcing frequency.",
              "The estimator itself is checked first on the logistic, Hénon, Lorenz and Ueda systems (the checks of",
              "`verify/s6_chaos.c` in the table of every check).", "",
              "| body | variation | lambda_max [1/s] | error bar | warm-up, batches | whole record | late drift | converged |",
              "|---|---|---|---|---|---|---|---|"]
    for r in data["variations"]:
        if "error" in r:
            lines.append(f"| {r['body']} | {r['variation']} | failed: {r['error']} | | | | | |")
            continue
        lines.append(f"| {r['body']} | {r['variation']} | {r['lambda_max']:.3f} | {r['error_bar']:.3f} | "
                     f"{layout(r, '')} | {r.get('whole_record_mean', float('nan')):.3f} | "
                     f"{r['late_drift']:.3f} | {'yes' if r['converged'] else 'no'} |")
    lines.append("")
    if data.get("baseline_records"):
        figure_9(out, data["baseline_records"])
        lines += ["![Fig 9: instantaneous and running lambda_max](fig9-lyapunov.png)", ""]
    pivot = os.path.join(out, "pivot-rate.json")
    if os.path.exists(pivot):
        lines += ["### Where the paper model's exponent comes from: an inverted pendulum about a frozen contact", "",
                  "Between grid switches the paper's model keeps the contact node fixed in the body (ṙ_c = 0 in eq 45),",
                  "so the body rotates about a fixed point of its surface below the centroid: an inverted pendulum, whose",
                  "tilt grows as e^{σt} with σ = sqrt(m g |d| / I_P,min) (d from the centroid to the pivot, I_P,min the",
                  "smallest moment of inertia about a horizontal axis through it). The table gives σ over every surface point",
                  "and λ_max / mid-range σ for each run; the finding is conclusive when every paper-model run is within 15 %.",
                  "", "| body | σ range, β = 0.12 [1/s] | σ range, β = 0.02 | run | λ_max / σ |", "|---|---|---|---|---|"]
        for row in load_json(pivot):
            lo, hi = row["sigma_range_beta_0.12"]
            lo2, hi2 = row["sigma_range_beta_0.02"]
            for name, ratio in row["ratios"].items():
                lines.append(f"| {row['body']} | {lo:.3f} – {hi:.3f} | {lo2:.3f} – {hi2:.3f} | {name} | {ratio:.3f} |")
        lines.append("")
    estimators = os.path.join(out, "lyapunov-gomboc-estimators.json")
    if os.path.exists(estimators):
        lines += ["### The two estimators on the Gömböc (switches located, 300 periods)", "",
                  "The tangent estimator carries the variational equation (eq 75) through every located branch switch with",
                  "the saltation matrix; under the unilateral contact law every change of contact is also a jump of ω",
                  "(an impact), and the saltation carries the jump map's derivative. The pair estimator (eq 77) needs no",
                  "derivative. Agreement is checked within 4 combined errors. Fold switches are those with no Δh = 0",
                  "crossing inside their step (a branch lost or born).", "",
                  "| body | β | model | contact law | λ, pair (eq 77) | λ, tangent (eq 75) | saltations | fold switches |",
                  "|---|---|---|---|---|---|---|---|"]
        for r in load_json(estimators):
            model = ("rolling equation, certified continuous contact" if r.get("contact") == "continuous"
                     else f"the paper's grid (90 × 180, {r.get('contact', 'grid')}) as a polyhedron")
            lines.append(f"| {r['body']} | {r['beta']:g} | {model} | {r.get('contact_law', 'held')} | {r['pair']:.3f} ± {r['pair_error']:.3f} | "
                         f"{r['tangent']:.3f} ± {r['tangent_error']:.3f} | {r['saltations']:.0f} | {r.get('fold_switches', 0):.0f} |")
        lines.append("")
    long_path = os.path.join(out, "chaos-long.json")
    if os.path.exists(long_path):
        lines += ["### Long runs (`make verify-full`)", "",
                  "Rows neither clearly positive nor clearly removed at this length are listed as UNDECIDED among the checks.",
                  "The last two columns count the reference trajectory's switches per period in the first and the last tenth",
                  "of the record: a rate that grows while the body comes to rest is chattering between two tied contact",
                  "branches (a two-point support the single-contact model cannot represent), and λ then measures the",
                  "kinetic-energy jumps at the switches, not chaos.", "",
                  "| body | variation | periods | transient | warm-up, batches | λ_max [1/s] | error bar | λ − 4σ > 0 | "
                  "switches/period, first tenth | last tenth |",
                  "|---|---|---|---|---|---|---|---|---|---|"]
        for r in load_json(long_path):
            clear = "yes" if r["lambda_max"] - 4 * r["error_bar"] > 0 else "no"
            if r.get("chattering"):
                clear += " (chattering: not judged)"
            early, late = r.get("switches_per_period_first_tenth"), r.get("switches_per_period_last_tenth")
            rates = f"{early:.2f} | {late:.2f}" if early is not None and late is not None else "— | —"
            lines.append(f"| {r['body']} | {r['variation']} | {r['periods']:.0f} | {r['transient_periods']:.0f} | "
                         f"{layout(r, '') or '—'} | {r['lambda_max']:.3f} | {r['error_bar']:.3f} | {clear} | {rates} |")
        lines.append("")
    else:
        lines += ["Continuous rolling needs longer records than 300 periods to decide whether its exponent needs the forcing",
                  "or a non-convex body: `make verify-full` runs 10000 periods and writes them here.", ""]
    verdicts = [r for r in rows if r.get("section") == "8.2" and r.get("claim")]
    if verdicts:
        lines += ["### Verdicts on the claims of section 8.2", "", "| claim | measured | quantity | the paper's claim |",
                  "|---|---|---|---|"]
        for r in verdicts:
            holds = {"holds": "holds", "fails": "**fails**"}.get(r.get("verdict"), "*undecided*")
            lines.append(f"| {r['claim'].replace('|', '/')} | {r.get('detail', '').replace('|', '/')} | "
                         f"{r['quantity'].replace('|', '/')} | {holds} |")
        lines.append("")
    est = os.path.join(out, "lyapunov-estimator.json")
    if os.path.exists(est):
        e = load_json(est)
        lines += ["### The estimator's own parameters (Lorenz 10, 28, 8/3; literature 0.9056)", "",
                  "| study | setting | lambda_1 | error bar |", "|---|---|---|---|"]
        for key, label in (("observation_time", "t"), ("delta0", "delta0"), ("interval", "interval")):
            for r in e.get(key, []):
                lines.append(f"| {key.replace('_', ' ')} | {r[label]:g} | {r['lambda']:.4f} | {r['error_bar']:.4f} |")
        lines.append("")
    return lines
