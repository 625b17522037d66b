#!/usr/bin/python3
"""Figures 3–9 of the paper from what `gomboc run` wrote, and a summary page.

usage: run_report.py OUT NAME [NAME ...]
Reads OUT/NAME-summary.json for every scene NAME, and the outputs the scene asked for; writes
OUT/fig-timeseries-NAME.png (ω, h*, E with switch markers, switching rate: Figs 3 and 5) and
OUT/fig-contact-NAME.png (contact index and r_c: Figs 4 and 6) from NAME-history.csv;
OUT/fig7-strobe-NAME.png (Poincaré cloud of ω and the return map of ω_x) from NAME-strobe.csv;
OUT/fig8-spectrum-NAME.png (power spectrum of ω_x in Hz, and the (ω_x, ω_z) phase portrait when the
history is there) from NAME-spectrum.csv; OUT/fig9-lyapunov-NAME.png (λ_inst and the running λ_max)
from NAME-lyapunov.csv; and OUT/runs.md. Recomputes no physics.
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
    # the changes of contact the scene's contact model makes: grid-node changes, or continuous branch switches
    if scene.get("contact") in ("grid", "fast-grid"):
        changes = f"{summary['grid_switches']:.0f} grid-node changes"
    else:
        changes = f"{summary['branch_switches']:.0f} branch switches"
    fig.suptitle(f"{scene['description']}: {changes}", fontsize=10)
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


def strobe_figure(out, name, summary):
    data = numpy.genfromtxt(os.path.join(out, f"{name}-strobe.csv"), delimiter=",", names=True)
    fig = plt.figure(figsize=(11, 4.8))
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    ax.scatter(data["omega_x"], data["omega_y"], data["omega_z"], s=4, c=data["n"], cmap="viridis")
    ax.set_xlabel("ω_x")
    ax.set_ylabel("ω_y")
    ax.set_zlabel("ω_z")
    ax.set_title("Poincaré cloud of ω at t = t0 + (n + phase) T")
    ax2 = fig.add_subplot(1, 2, 2)
    ax2.plot(data["omega_x"][:-1], data["omega_x"][1:], ".", ms=3)
    ax2.set_xlabel("ω_x(n) [rad/s]")
    ax2.set_ylabel("ω_x(n+1) [rad/s]")
    ax2.set_title("one-step return map")
    fig.suptitle(f"Fig 7: {summary['scene']['description']} ({len(data)} samples after "
                 f"{summary['scene']['strobe_transient_periods']:.0f} periods)", fontsize=10)
    fig.tight_layout()
    save_figure(fig, os.path.join(out, f"fig7-strobe-{name}.png"))
    plt.close(fig)


def spectrum_figure(out, name, summary, history):
    data = numpy.genfromtxt(os.path.join(out, f"{name}-spectrum.csv"), delimiter=",", names=True)
    panels = 2 if history is not None else 1
    fig, axes = plt.subplots(1, panels, figsize=(5.5 * panels, 4.5), squeeze=False)
    ax = axes[0][0]
    ax.semilogy(data["frequency_hz"][1:], data["power"][1:], lw=0.6)
    forcing = summary["spectrum"]["forcing_hz"]
    for k in (1, 2):
        ax.axvline(k * forcing, color="tab:red", lw=0.5, ls="--")
    ax.set_xlim(0, 4 * forcing)
    # the axis spans the shown band's spectrum, from its 0.1 % quantile up: one isolated near-zero bin (a
    # window's null) would otherwise stretch it over many decades
    band = data["power"][1:][(data["frequency_hz"][1:] <= 4 * forcing) & (data["power"][1:] > 0)]
    if band.size:
        ax.set_ylim(max(numpy.quantile(band, 0.001), band.max() * 1e-12) / 2, band.max() * 2)
    ax.set_xlabel("frequency [Hz] (dashed: ω/2π and 2ω/2π)")
    ax.set_ylabel("PSD of ω_x [(rad/s)²/Hz]")
    ax.set_title(f"power spectrum ({summary['spectrum']['window']} window)")
    if history is not None:
        start = summary["scene"]["spectrum_transient_periods"] * 2 * numpy.pi / summary["scene"]["omega"]
        keep = history["t"] >= start
        axes[0][1].plot(history["omega_x"][keep], history["omega_z"][keep], lw=0.3)
        axes[0][1].set_xlabel("ω_x [rad/s]")
        axes[0][1].set_ylabel("ω_z [rad/s]")
        axes[0][1].set_title("phase portrait after the transient")
    fig.suptitle(f"Fig 8: {summary['scene']['description']}", fontsize=10)
    fig.tight_layout()
    save_figure(fig, os.path.join(out, f"fig8-spectrum-{name}.png"))
    plt.close(fig)


def lyapunov_figure(out, name, summary):
    data = numpy.genfromtxt(os.path.join(out, f"{name}-lyapunov.csv"), delimiter=",", names=True)
    lyap = summary["lyapunov"]
    fig, ax = plt.subplots(figsize=(9, 4.2))
    ax.plot(data["period_end"], data["lambda_inst"], lw=0.5, color="0.6", label="λ_inst (per interval)")
    ax.plot(data["period_end"], data["lambda_running"], lw=1.4, color="tab:blue", label="running λ_max")
    windows = lyap.get("windows")
    if windows:
        w = numpy.genfromtxt(os.path.join(out, f"{name}-lyapunov-windows.csv"), delimiter=",", names=True, ndmin=1)
        ax.hlines(w["lambda_window"], w["period_start"], w["period_end"], colors="tab:red", lw=2.0,
                  label=f"windowed λ (per {windows['window_periods']:.0f} periods)")
        ax.axhline(windows["chaotic_threshold"], color="tab:red", lw=0.5, ls=":")
    ax.axhline(0.0, color="black", lw=0.5)
    ax.set_xlabel("forcing period")
    ax.set_ylabel("λ [1/s]")
    ax.set_ylim(min(-0.5, numpy.percentile(data["lambda_inst"], 1)), max(1.0, numpy.percentile(data["lambda_inst"], 99)) * 1.2)
    ax.legend(fontsize=8)
    ax.set_title(f"Fig 9: {summary['scene']['description']}: λ_max = {lyap['lambda_max']:.3f} ± {lyap['error_bar']:.3f} 1/s",
                 fontsize=10)
    fig.tight_layout()
    save_figure(fig, os.path.join(out, f"fig9-lyapunov-{name}.png"))
    plt.close(fig)


def summary_lines(name, summary):
    scene, lines = summary["scene"], []
    lines.append(f"### {scene['description']} (`{scene.get('file', f'cases/{name}.ini')}`)")
    lines.append("")
    lines.append("Scene as read: " + ", ".join(f"{k} = {v}" for k, v in scene.items() if k != "description") + ".")
    lines.append("")
    lines.append(f"- {summary['steps']:.0f} steps to t = {summary['t_end']:.4f} s; final ω = "
                 f"({summary['omega'][0]:.6f}, {summary['omega'][1]:.6f}, {summary['omega'][2]:.6f}) rad/s")
    lines.append(f"- contact: {summary['grid_switches']:.0f} changes of the grid index, "
                 f"{summary['branch_switches']:.0f} branch switches")
    impacts, two_point = summary.get("impacts"), summary.get("two_point")
    ledger = " + L (the energy the impacts took)" if impacts else ""
    lines.append(f"- energy-balance residual E − E(0) − ∫(P_d + m ġ ζ) dt{ledger}: final {summary['energy_residual_final']:.3g} J, "
                 f"largest {summary['energy_residual_max']:.3g} J")
    if impacts and two_point:
        rest = two_point.get("rest_since")
        lines.append(f"- unilateral contact: {impacts['count']:.0f} impacts took {impacts['energy_lost']:.4g} J (the largest "
                     f"friction one needed: {impacts['friction_needed_max'] if impacts['friction_needed_max'] is not None else 'unbounded'}); "
                     f"on two points for {100 * two_point['time_fraction']:.1f} % of the run ({two_point['entries']:.0f} entries; "
                     f"{impacts['settled']:.0f} impacts ended by the settle rule; {two_point['lifts']:.0f} lifts, "
                     f"{two_point['third_points']:.0f} third points"
                     + (f"; at rest on three points from t = {rest:.4f} s" if rest is not None else "") + ")")
    flight = summary.get("flight")
    if flight and (flight["lift_offs"] or flight["landings"]):
        lines.append(f"- flight (restitution e = {flight['restitution']:g}): {100 * flight['flight_time_fraction']:.1f} % of the "
                     f"run in flight; {flight['lift_offs']:.0f} lift-offs, {flight['landings']:.0f} landings "
                     f"({flight['bounces']:.0f} bounced); highest gap between the lowest point and the plane "
                     f"{flight['max_hop_height']:.4g} m")
    lines.append(f"- attitude: max |RᵀR − I| = {summary['orthonormality_max']:.2g}; largest quaternion-norm "
                 f"correction {summary['quaternion_drift_max']:.2g}")
    monitors = summary.get("monitors")
    if monitors:
        lines.append(f"- validity: g_eff ≤ 0 in {100 * monitors['geff_nonpositive_fraction']:.2f} % of samples "
                     f"(min {monitors['geff_min']:.3f} m/s²); normal force ≤ 0 (lift-off) in "
                     f"{100 * monitors['lift_off_fraction']:.2f} % (min {monitors['normal_force_min']:.3f} N); "
                     f"friction needed up to μ = {monitors['friction_needed_max']:.3f}")
    strobe, spectrum, lyap = summary.get("strobe"), summary.get("spectrum"), summary.get("lyapunov")
    if strobe:
        period = (f"period {strobe['period_detected']:.0f}" if strobe["period_detected"]
                  else "no period up to 16 (tolerance 1e-6 rad/s over the last 64 samples)")
        lines.append(f"- strobe (Fig 7): {strobe['samples']:.0f} samples; sd of ω = ({strobe['sd'][0]:.4f}, "
                     f"{strobe['sd'][1]:.4f}, {strobe['sd'][2]:.4f}) rad/s; {period}")
    if spectrum:
        lines.append(f"- spectrum of ω_x (Fig 8): {spectrum['samples']:.0f} samples, {spectrum['window']} window, "
                     f"Δf = {spectrum['df_hz']:.4f} Hz; highest peak at {spectrum['peak_hz']:.4f} Hz "
                     f"(forcing {spectrum['forcing_hz']:.4f} Hz)")
    if lyap:
        lines.append(f"- λ_max (Fig 9) = {lyap['lambda_max']:.4f} ± {lyap['error_bar']:.4f} 1/s over "
                     f"{lyap['periods']:.0f} periods (δ0 = {lyap['delta0']:g}, {lyap['batches']:.0f} batches); running "
                     f"value moved {lyap['late_drift']:.3g} over the last quarter: "
                     f"{'converged' if lyap['converged'] else 'not converged'}")
        windows = lyap.get("windows")
        if windows:
            life = windows["chaos_lifetime_periods"]
            life = (f"the chaos lasts to period {life:.0f} of the record" if not isinstance(life, str)
                    else "chaotic to the end of the record")
            lines.append(f"- windowed λ per {windows['window_periods']:.0f} periods: "
                         + ", ".join(f"{v:.3f}" for v in windows["lambda_window"])
                         + f" 1/s; {windows['chaotic_windows']:.0f} of {windows['windows']:.0f} windows above "
                         f"{windows['chaotic_threshold']:g} 1/s: {life}")
    lines.append("")
    for figure, label in ((f"fig-timeseries-{name}.png", "time histories"), (f"fig-contact-{name}.png", "contact"),
                          (f"fig7-strobe-{name}.png", "Fig 7"), (f"fig8-spectrum-{name}.png", "Fig 8"),
                          (f"fig9-lyapunov-{name}.png", "Fig 9")):
        if os.path.exists(os.path.join(OUT_DIR[0], figure)):
            lines.append(f"![{label}]({figure})")
            lines.append("")
    return lines


OUT_DIR = ["."]


def main():
    out, names = sys.argv[1], sys.argv[2:]
    lines = ["# gomboc — scene runs", ""]
    OUT_DIR[0] = out
    for name in names:
        summary = load_json(os.path.join(out, f"{name}-summary.json"))
        history_path = os.path.join(out, f"{name}-history.csv")
        h = None
        if os.path.exists(history_path):
            h = load_history(history_path)
            time_series_figure(out, name, h, summary)
            contact_figure(out, name, h, summary)
        scene = summary["scene"]
        if scene.get("strobe"):
            strobe_figure(out, name, summary)
        if scene.get("spectrum"):
            spectrum_figure(out, name, summary, h)
        if scene.get("lyapunov"):
            lyapunov_figure(out, name, summary)
        lines += summary_lines(name, summary)
    write_atomically(os.path.join(out, "runs.md"), "\n".join(lines))


if __name__ == "__main__":
    main()
