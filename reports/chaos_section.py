"""Report section "Is the chaos real?" (paper sections 6 and 8.2), from the data verify/s6_chaos.c
writes: chaos.json (lambda_max of both bodies under every variation, and the baseline records for
Fig 9) and lyapunov-estimator.json (the estimator's own study on Lorenz). Recomputes no physics."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from common import load_json, save_figure  # noqa: E402


def figure_9(out, records):
    fig, axes = plt.subplots(len(records), 1, figsize=(10, 2.6 * len(records)), sharex=True)
    for ax, rec in zip(axes, records):
        n = range(1, len(rec["running"]) + 1)
        ax.plot(n, rec["instantaneous"], lw=0.6, color="0.6", label="lambda_inst (per period)")
        ax.plot(n, rec["running"], lw=1.5, label="running lambda_max")
        ax.axhline(0.0, color="k", lw=0.5)
        ax.set_title(f"Gömböc {rec['body']}: {rec['variation']}", fontsize=9)
        ax.set_ylabel("1/s")
    axes[0].legend(fontsize=8)
    axes[-1].set_xlabel("forcing period")
    fig.tight_layout()
    save_figure(fig, os.path.join(out, "fig9-lyapunov.png"))
    plt.close(fig)


def chaos_section(out, rows):
    lines = ["## Is the chaos real? (sections 6, 8.2)", ""]
    path = os.path.join(out, "chaos.json")
    if not os.path.exists(path):
        return lines + ["(chaos data missing: the test did not write it)", ""]
    data = load_json(path)
    periods, batches = data["periods"], data["batches"]
    lines += ["The maximal Lyapunov exponent by the pair estimator of eq 77: two trajectories, the second put back at",
              f"delta0 along the current separation once per forcing period; {periods:g} periods from R0 = I, omega0 = 0;",
              f"error bar = batch-means standard error ({batches:g} batches). The separation is a 6-vector: the body-frame rotation",
              "vector between the two attitudes [rad] and the angular-velocity difference divided by the forcing frequency.",
              "The estimator itself is checked first on the logistic, Hénon, Lorenz and Ueda systems (the checks of",
              "`verify/s6_chaos.c` in the table of every check).", "",
              "| body | variation | lambda_max [1/s] | error bar | late drift | converged |", "|---|---|---|---|---|---|"]
    for r in data["variations"]:
        if "error" in r:
            lines.append(f"| {r['body']} | {r['variation']} | failed: {r['error']} | | | |")
            continue
        lines.append(f"| {r['body']} | {r['variation']} | {r['lambda_max']:.3f} | {r['error_bar']:.3f} | "
                     f"{r['late_drift']:.3f} | {'yes' if r['converged'] else 'no'} |")
    lines.append("")
    if data.get("baseline_records"):
        figure_9(out, data["baseline_records"])
        lines += ["![Fig 9: instantaneous and running lambda_max](fig9-lyapunov.png)", ""]
    verdicts = [r for r in rows if r.get("section") == "8.2" and r.get("claim")]
    if verdicts:
        lines += ["### Verdicts on the claims of section 8.2", "", "| claim | measured | quantity | the paper's claim |",
                  "|---|---|---|---|"]
        for r in verdicts:
            holds = "holds" if r.get("paper_holds") else "**does not hold**"
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
