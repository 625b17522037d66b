#!/usr/bin/python3
"""Figures 3–6 of the paper from the time histories `gomboc run` wrote, and a summary page.

usage: run_report.py OUT NAME [NAME ...]
Reads OUT/NAME-history.csv and OUT/NAME-summary.json for every scene NAME; writes
OUT/fig-timeseries-NAME.png (ω, h*, E with switch markers, switching rate: Figs 3 and 5),
OUT/fig-contact-NAME.png (contact index and r_c: Figs 4 and 6) and OUT/runs.md. Recomputes no physics.
"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import load_json, save_figure, write_atomically  # noqa: E402


def load_history(path):
    data = numpy.genfromtxt(path, delimiter=",", names=True)
    return data


def time_series_figure(out, name, h, summary):
    fig, axes = plt.subplots(4, 1, figsize=(11, 10), sharex=True)
    for key, label in (("omega_x", "ω_x"), ("omega_y", "ω_y"), ("omega_z", "ω_z")):
        axes[0].plot(h["t"], h[key], lw=0.6, label=label)
    axes[0].set_ylabel("ω [rad/s]")
    axes[0].legend(fontsize=8, loc="upper right")
    axes[1].plot(h["t"], h["h"], lw=0.6, color="black")
    axes[1].set_ylabel("h* [m]")
    axes[2].plot(h["t"], h["E"], lw=0.6, color="tab:purple")
    switches = (h["grid_switch"] > 0) | (h["branch_switch"] > 0)
    axes[2].plot(h["t"][switches], h["E"][switches], ".", ms=2, color="tab:red", label="contact switch")
    axes[2].set_ylabel("E [J]")
    axes[2].legend(fontsize=8, loc="upper right")
    axes[3].plot(h["t"], h["switch_rate"], lw=0.6, color="tab:green")
    axes[3].set_ylabel("switches / s\n(trailing period)")
    axes[3].set_xlabel("t [s]")
    scene = summary["scene"]
    fig.suptitle(f"{scene['description']}: {summary['grid_switches']:.0f} grid-index changes, "
                 f"{summary['branch_switches']:.0f} branch switches", fontsize=10)
    fig.tight_layout()
    save_figure(fig, os.path.join(out, f"fig-timeseries-{name}.png"))
    plt.close(fig)


def contact_figure(out, name, h, summary):
    fig, axes = plt.subplots(2, 1, figsize=(11, 6), sharex=True)
    axes[0].plot(h["t"], h["index"], lw=0.5)
    axes[0].set_ylabel("contact index (grid node)")
    for key in ("rc_x", "rc_y", "rc_z"):
        axes[1].plot(h["t"], h[key], lw=0.6, label=key.replace("rc_", "r_c,"))
    axes[1].set_ylabel("r_c [m]")
    axes[1].set_xlabel("t [s]")
    axes[1].legend(fontsize=8, loc="upper right")
    fig.suptitle(summary["scene"]["description"], fontsize=10)
    fig.tight_layout()
    save_figure(fig, os.path.join(out, f"fig-contact-{name}.png"))
    plt.close(fig)


def summary_lines(name, summary):
    scene, lines = summary["scene"], []
    lines.append(f"### {scene['description']} (`cases/{name}.ini`)")
    lines.append("")
    lines.append("Scene as read: " + ", ".join(f"{k} = {v}" for k, v in scene.items() if k != "description") + ".")
    lines.append("")
    lines.append(f"- {summary['steps']:.0f} steps to t = {summary['t_end']:.4f} s; final ω = "
                 f"({summary['omega'][0]:.6f}, {summary['omega'][1]:.6f}, {summary['omega'][2]:.6f}) rad/s")
    lines.append(f"- contact: {summary['grid_switches']:.0f} changes of the grid index, "
                 f"{summary['branch_switches']:.0f} branch switches")
    lines.append(f"- energy-balance residual E − E(0) − ∫(P_d + m ġ ζ) dt: final {summary['energy_residual_final']:.3g} J, "
                 f"largest {summary['energy_residual_max']:.3g} J")
    lines.append(f"- attitude: max |RᵀR − I| = {summary['orthonormality_max']:.2g}; largest quaternion-norm "
                 f"correction {summary['quaternion_drift_max']:.2g}")
    monitors = summary.get("monitors")
    if monitors:
        lines.append(f"- validity: g_eff ≤ 0 in {100 * monitors['geff_nonpositive_fraction']:.2f} % of samples "
                     f"(min {monitors['geff_min']:.3f} m/s²); normal force ≤ 0 (lift-off) in "
                     f"{100 * monitors['lift_off_fraction']:.2f} % (min {monitors['normal_force_min']:.3f} N); "
                     f"friction needed up to μ = {monitors['friction_needed_max']:.3f}")
    lines.append("")
    lines.append(f"![time histories](fig-timeseries-{name}.png)")
    lines.append("")
    lines.append(f"![contact](fig-contact-{name}.png)")
    lines.append("")
    return lines


def main():
    out, names = sys.argv[1], sys.argv[2:]
    lines = ["# gomboc — scene runs", ""]
    for name in names:
        summary = load_json(os.path.join(out, f"{name}-summary.json"))
        history_path = os.path.join(out, f"{name}-history.csv")
        if os.path.exists(history_path):
            h = load_history(history_path)
            time_series_figure(out, name, h, summary)
            contact_figure(out, name, h, summary)
        lines += summary_lines(name, summary)
    write_atomically(os.path.join(out, "runs.md"), "\n".join(lines))


if __name__ == "__main__":
    main()
