#!/usr/bin/python3
"""Figures 3–9 of the paper from what `gomboc run` wrote, and a summary page.

usage: run_report.py OUT NAME [NAME ...] [--page FILE.md]
Reads OUT/NAME-summary.json for every scene NAME, and the outputs that run wrote (the summary's `files`);
writes OUT/fig-timeseries-NAME.png (ω; h* or, under the unilateral law, the centroid's height and the
lowest point's gap with the phases shaded and the impacts, landings and lift-offs marked; the energy's
mean over each period with the ledger's residual; the switching rate under the held law: Figs 3 and 5) and
OUT/fig-contact-NAME.png (the grid node and r_c: Figs 4 and 6) from NAME-history.csv (and NAME-impacts.csv);
OUT/fig7-strobe-NAME.png (Poincaré cloud of ω and the return map of ω_x) from NAME-strobe.csv;
OUT/fig8-spectrum-NAME.png (power spectrum of ω_x in Hz, and the (ω_x, ω_z) phase portrait when the
history is there) from NAME-spectrum.csv; OUT/fig9-lyapunov-NAME.png (λ_inst and the running λ_max)
from NAME-lyapunov.csv (the running mean after the warm-up, ending at the quoted λ_max, with its error
bar as a band); OUT/NAME-figures.json (each figure's file, title and the numbers the title quotes); and the
page OUT/NAME-run.md for one scene, OUT/runs.md for several (or --page FILE.md). A figure of the scene
that this run did not draw (an earlier run's) is removed, never linked. Recomputes no physics.
"""
import hashlib
import json
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import help_requested, input_errors, load_json, load_table, previous_files, save_figure, write_atomically  # noqa: E402


def load_history(path):
    return load_table(path, required=("t", "contacts"))


# Shading of the phases of a unilateral run (the history's `contacts`), and the marks of its events.
PHASES = ((0, "flight", "tab:cyan"), (2, "on two points", "tab:orange"), (3, "at rest", "0.6"))
EVENT_MARKS = {"landing": ("v", "tab:blue", "landing"), "lift-off": ("^", "tab:red", "lift-off")}


def shade_phases(ax, h):
    """Shade the phases over the whole height of the panel; the data's limits stay the data's (a span given in
    axes coordinates would otherwise stretch them to 0..1)."""
    limits = ax.get_ylim()
    for contacts, label, colour in PHASES:
        mask = h["contacts"] == contacts
        if mask.any():
            ax.fill_between(h["t"], 0, 1, where=mask, transform=ax.get_xaxis_transform(), color=colour, alpha=0.18,
                            lw=0, label=label)
    ax.set_ylim(limits)


def period_means(t, values, period):
    """The mean of `values` over each whole forcing period: (period centres, means)."""
    index = numpy.floor(t / period).astype(int)
    whole = index < int(numpy.floor(t[-1] / period + 1e-9))
    counts = numpy.bincount(index[whole])
    sums = numpy.bincount(index[whole], weights=values[whole])
    keep = counts > 0
    return (numpy.arange(len(counts))[keep] + 0.5) * period, sums[keep] / counts[keep]


def load_impacts(out, name, written):
    path = os.path.join(out, f"{name}-impacts.csv")
    if f"{name}-impacts.csv" not in written or not os.path.exists(path):
        return None
    return load_table(path, text=("kind",))


def time_series_title(summary):
    """The title's numbers are the summary's, as the text states them."""
    scene, impacts, flight = summary["scene"], summary.get("impacts"), summary.get("flight")
    if scene.get("contact_law") == "unilateral" and impacts:
        text = f"{impacts['count']:.0f} impact{'' if impacts['count'] == 1 else 's'}"
        if flight and (flight["landings"] or flight["lift_offs"]):
            on = flight.get("landings_flying_on", 0)
            text += (f", {flight['lift_offs']:.0f} lift-offs, {flight['landings']:.0f} landings"
                     + (f" ({on:.0f} flying on)" if on else "") + f", {100 * flight['flight_time_fraction']:.1f} % of the time in flight")
        return text
    if scene.get("contact") in ("grid", "fast-grid"):
        return f"{summary['grid_switches']:.0f} grid-node changes"
    return f"{summary['branch_switches']:.0f} branch switches"


def outside(ax, **options):
    """The axes' legend beside it, to the right, where it covers no data (the suite "Reports" measures that)."""
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, **options)


def paper_number(scene, kind):
    """The paper's number for a scene's time series or contact figure: Figs 3 and 4 under the biharmonic forcing
    (A2 != 0), Figs 5 and 6 under the harmonic benchmark (A1 != 0, A2 = 0); none on a still plane."""
    a1, a2 = scene.get("a1", 0.0), scene.get("a2", 0.0)
    if a2:
        return "Fig 3" if kind == "timeseries" else "Fig 4"
    if a1:
        return "Fig 5" if kind == "timeseries" else "Fig 6"
    return None


def time_series_figure(out, name, h, summary, impacts):
    scene = summary["scene"]
    hybrid = scene.get("contact_law") == "unilateral"
    period = 2 * numpy.pi / scene["omega"]
    panels = ["omega", "height", "energy", "residual"] + ([] if hybrid else ["rate"])
    fig, axes = plt.subplots(len(panels), 1, figsize=(11, 2.6 * len(panels)), sharex=True)
    for key, label in (("omega_x", "ω_x"), ("omega_y", "ω_y"), ("omega_z", "ω_z")):
        axes[0].plot(h["t"], h[key], lw=0.6, label=label)
    axes[0].set_ylabel("ω [rad/s]")
    ax = axes[1]
    if hybrid:
        # the centroid's height above the plane and the lowest point's gap, with the run's phases and events
        ax.plot(h["t"], h["zeta"], lw=0.7, color="black", label="ζ, centroid above the plane")
        ax.plot(h["t"], h["clearance"], lw=0.7, color="tab:blue", label="gap of the lowest point")
        ax.set_ylabel("height [m]")
        for a in (axes[0], ax):
            shade_phases(a, h)
        if impacts is not None and impacts.size:
            kinds = numpy.atleast_1d(impacts["kind"])
            times = numpy.atleast_1d(impacts["t"])
            bottom, top = ax.get_ylim()
            ax.set_ylim(bottom, top + 0.12 * (top - bottom))  # the event markers drawn at `top`, wholly inside the axes
            for kind, (marker, colour, label) in EVENT_MARKS.items():
                at = times[kinds == kind]
                if at.size:
                    ax.plot(at, numpy.full(at.size, top), marker, color=colour, ms=4, ls="none", label=f"{label} ({at.size})")
            other = times[(kinds != "landing") & (kinds != "lift-off") & (kinds != "lift")]
            if other.size:
                ax.plot(other, numpy.zeros(other.size), "|", color="tab:red", ms=6, ls="none",
                        label=f"impact on the plane ({other.size})")
    else:
        ax.plot(h["t"], h["h"], lw=0.6, color="black")
        ax.set_ylabel("h* [m]")
        switches = (h["grid_switch"] > 0) | (h["branch_switch"] > 0)
        ax.plot(h["t"][switches], h["h"][switches], ".", ms=2, color="tab:red", label="contact switch")
    outside(ax)
    outside(axes[0])
    # the energy: its mean over each forcing period (the forcing's own swing of m g_eff ζ would hide it), and
    # the ledger's residual E − E0 − W (+ L) beside it
    ax = axes[2]
    forced = scene.get("a1", 1.0) != 0 or scene.get("a2", 1.0) != 0
    centres, means = period_means(h["t"], h["E"], period) if forced else (numpy.array([]), None)
    if centres.size:
        ax.plot(centres, means, ".-", lw=0.8, ms=3, color="tab:purple", label="E, mean over each period")
    else:
        ax.plot(h["t"], h["E"], lw=0.6, color="tab:purple", label="E" if not forced else "E (shorter than one period)")
    ax.set_ylabel("E [J]")
    outside(ax)
    axes[3].plot(h["t"], h["residual"], lw=0.6, color="tab:gray", label="ledger residual E − E0 − W (+ L)")
    axes[3].set_ylabel("residual [J]")
    outside(axes[3])
    if not hybrid:
        axes[4].plot(h["t"], h["switch_rate"], lw=0.6, color="tab:green")
        axes[4].set_ylabel("switches / s\n(trailing period)")
    axes[-1].set_xlabel("t [s]")
    number = paper_number(scene, "timeseries")
    title = f"{number + ': ' if number else ''}{scene['description']}: {time_series_title(summary)}"
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    path = f"fig-timeseries-{name}.png"
    facts = save_figure(fig, os.path.join(out, path))
    plt.close(fig)
    return path, title, facts


def contact_figure(out, name, h, summary):
    scene = summary["scene"]
    grid = scene.get("contact") in ("grid", "fast-grid")
    fig, axes = plt.subplots(2 if grid else 1, 1, figsize=(11, 6 if grid else 3.5), sharex=True, squeeze=False)
    axes = axes[:, 0]
    if grid:  # the grid node carries the contact; continuous contact has no node to draw
        axes[0].plot(h["t"], h["index"], lw=0.5)
        axes[0].set_ylabel("contact node (grid index)")
        axes[0].yaxis.set_major_locator(matplotlib.ticker.MaxNLocator(integer=True))  # an index: whole ticks only
    ax = axes[-1]
    for key in ("rc_x", "rc_y", "rc_z"):
        ax.plot(h["t"], h[key], lw=0.6, label=key.replace("rc_", "r_c,"))
    two = h["contacts"] == 2
    if two.any():
        for key in ("rq_x", "rq_y", "rq_z"):
            ax.plot(h["t"][two], h[key][two], ".", ms=1, label=key.replace("rq_", "r_Q,") + " (on two points)")
    ax.set_ylabel("contact point, body axes [m]")
    ax.set_xlabel("t [s]")
    outside(ax, markerscale=6)  # the r_Q dots (1 point) told apart in the legend
    number = paper_number(scene, "contact")
    title = f"{number + ': ' if number else ''}{scene['description']}"
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    path = f"fig-contact-{name}.png"
    facts = save_figure(fig, os.path.join(out, path), index_axes=axes[:1] if grid else ())
    plt.close(fig)
    return path, title, facts


def strobe_figure(out, name, summary):
    data = load_table(os.path.join(out, f"{name}-strobe.csv"))
    fig = plt.figure(figsize=(11, 4.8))
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    points = ax.scatter(data["omega_x"], data["omega_y"], data["omega_z"], s=4, c=data["n"], cmap="viridis")
    ax.set_xlabel("ω_x [rad/s]", fontsize=8, labelpad=6)
    ax.set_ylabel("ω_y [rad/s]", fontsize=8, labelpad=6)
    ax.set_zlabel("ω_z [rad/s]", fontsize=8, labelpad=6)
    ax.tick_params(labelsize=7)
    ax.set_title("ω at t = t0 + (n + phase) T", fontsize=9)
    fig.colorbar(points, ax=ax, shrink=0.7, pad=0.12, label="period n")
    ax2 = fig.add_subplot(1, 2, 2)
    ax2.plot(data["omega_x"][:-1], data["omega_x"][1:], ".", ms=3)
    ax2.set_xlabel("ω_x(n) [rad/s]")
    ax2.set_ylabel("ω_x(n+1) [rad/s]")
    ax2.set_title("one-step return map", fontsize=9)
    strobe = summary["strobe"]
    title = (f"Fig 7: {summary['scene']['description']} ({strobe['samples']:.0f} samples after "
             f"{summary['scene']['strobe_transient_periods']:.0f} periods)")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    path = f"fig7-strobe-{name}.png"
    facts = save_figure(fig, os.path.join(out, path))
    plt.close(fig)
    return path, title, facts


def spectrum_figure(out, name, summary, history):
    data = load_table(os.path.join(out, f"{name}-spectrum.csv"))
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
    title = f"Fig 8: {summary['scene']['description']}"
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    path = f"fig8-spectrum-{name}.png"
    facts = save_figure(fig, os.path.join(out, path))
    plt.close(fig)
    return path, title, facts


def lyapunov_figure(out, name, summary):
    """Fig 9 as the text quotes it: the running mean after the chosen warm-up, ending at λ_max, with λ_max ±
    its error bar as a band; the whole record's running mean and λ_inst faded behind."""
    data = load_table(os.path.join(out, f"{name}-lyapunov.csv"))
    lyap = summary["lyapunov"]
    warmup = int(lyap["warmup_intervals"])
    inst, ends = data["lambda_inst"], data["period_end"]
    after = numpy.cumsum(inst[warmup:]) / numpy.arange(1, inst.size - warmup + 1)
    fig, ax = plt.subplots(figsize=(9, 4.2))
    ax.plot(ends, inst, lw=0.5, color="0.75", label="λ_inst (per interval)")
    ax.plot(ends, data["lambda_running"], lw=1.0, color="tab:blue", alpha=0.35,
            label="running mean of the whole record (warm-up included)")
    ax.plot(ends[warmup:], after, lw=1.6, color="tab:blue", label=f"running mean after the warm-up ({warmup} intervals)")
    lam, err = lyap["lambda_max"], lyap["error_bar"]
    ax.axhspan(lam - err, lam + err, xmin=0, xmax=1, color="tab:orange", alpha=0.35,
               label=f"λ_max ± error bar ({lyap['batches']:.0f} batch means)")
    ax.axhline(lam, color="tab:orange", lw=0.8)
    if warmup:
        ax.axvline(ends[warmup - 1], color="black", lw=0.6, ls="--")
    windows = lyap.get("windows")
    if windows:
        w = load_table(os.path.join(out, f"{name}-lyapunov-windows.csv"))
        ax.hlines(w["lambda_window"], w["period_start"], w["period_end"], colors="tab:red", lw=2.0,
                  label=f"windowed λ (per {windows['window_periods']:.0f} periods)")
        ax.axhline(windows["chaotic_threshold"], color="tab:red", lw=0.5, ls=":")
    ax.axhline(0.0, color="black", lw=0.5)
    ax.set_xlabel("forcing period")
    ax.set_ylabel("λ [1/s]")
    ax.set_ylim(min(-0.5, numpy.percentile(inst, 1), lam - 2 * err), max(1.0, numpy.percentile(inst, 99), lam + 2 * err) * 1.2)
    outside(ax)
    title = f"Fig 9: {summary['scene']['description']}: λ_max = {lam:.3f} ± {err:.3f} 1/s"
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    path = f"fig9-lyapunov-{name}.png"
    facts = save_figure(fig, os.path.join(out, path))
    plt.close(fig)
    return path, title, float(after[-1]) if after.size else float("nan"), facts


def as_read(value):
    """A scene's value with the digits it carries: a number to 10 significant digits (psi = pi/3 is 1.047197551,
    not its 17 binary digits), lists element by element."""
    if isinstance(value, float):
        return f"{value:.10g}"
    if isinstance(value, list):
        return "[" + ", ".join(str(as_read(v)) for v in value) + "]"
    return value


def summary_lines(name, summary, figures):
    scene, lines = summary["scene"], []
    lines.append(f"### {scene['description']} (`{scene.get('file', f'cases/{name}.ini')}`)")
    lines.append("")
    lines.append("Scene as read: " + ", ".join(f"{k} = {as_read(v)}" for k, v in scene.items() if k != "description") + ".")
    lines.append("")
    lines.append(f"- {summary['steps']:.0f} steps to t = {summary['t_end']:.4f} s; final ω = "
                 f"({summary['omega'][0]:.6f}, {summary['omega'][1]:.6f}, {summary['omega'][2]:.6f}) rad/s")
    lines.append(f"- contact: {summary['grid_switches']:.0f} changes of the grid index, "
                 f"{summary['branch_switches']:.0f} branch switches")
    impacts, two_point = summary.get("impacts"), summary.get("two_point")
    ledger = " + L (the energy the impacts took)" if impacts else ""
    lines.append(f"- energy-balance residual E − E(0) − ∫(P_d + m ġ ζ) dt{ledger}: final {summary['energy_residual_final']:.3g} J, "
                 f"largest {summary['energy_residual_max']:.3g} J"
                 + (f"; its largest change between two samples {summary['energy_residual_largest_jump']:.3g} J, at "
                    f"t = {summary['energy_residual_largest_jump_t']:.6g} s" if summary.get("energy_residual_largest_jump_t") is not None else "")
                 + (" — **the ledger drifted beyond 1 % of the run's energy: the step is too coarse here**"
                    if summary.get("ledger_too_coarse") else ""))
    grid_model = summary.get("grid_model_of_smooth_body")
    if grid_model:
        second = grid_model.get("second_grid")
        lam = (summary.get("lyapunov") or {}).get("lambda_max")
        lines.append(f"- **a smooth body run as its {grid_model['grid'][0]:.0f} × {grid_model['grid'][1]:.0f} grid polyhedron**: "
                     "its contact, switches and λ are the polyhedron's and depend on the grid (docs/bodies.md)"
                     + (f"; λ_max = {lam:.4f} 1/s here, {grid_model['lambda_max_second_grid']:.4f} ± "
                        f"{grid_model['lambda_error_second_grid']:.2g} on the {second[0]:.0f} × {second[1]:.0f} grid"
                        if second and lam is not None else ""))
    stepping = summary.get("stepping")
    if stepping:
        # time-stepping: impulses at every step, no impact events; its "impacts" are the points that arrived
        lines.append(f"- time-stepping (Moreau–Jean, θ = {stepping['theta']:g}, docs/stepping.md): {stepping['problems']:.0f} "
                     f"contact problems of up to {stepping['contacts_max']:.0f} points"
                     + (f" (of up to {stepping['candidates_max']:.0f} candidates, the most urgent first; "
                        f"{stepping['grown']:.0f} posed again with a point that went through)"
                        if stepping.get('candidates_max', 0) > stepping['contacts_max'] else "") + ", "
                     f"{stepping['sweeps'] / max(stepping['problems'], 1):.1f} sweeps each (Siconos's fc3d), residual "
                     f"≤ {stepping['residual_max']:.2g}; the impulses took {impacts['energy_lost']:.4g} J at the "
                     f"{impacts['count']:.0f} points that arrived and after, and gave {stepping['energy_given']:.3g} J "
                     f"in {stepping['steps_giving_energy']:.0f} step{'' if stepping['steps_giving_energy'] == 1 else 's'} "
                     f"(a body turning about a held point: O(h))"
                     + (f"; against the free motion the contact problems took ≥ {stepping['contact_dissipation_min']:.3g} J "
                        f"a step, giving in {stepping['steps_contacts_giving_energy']:.0f} step"
                        f"{'' if stepping['steps_contacts_giving_energy'] == 1 else 's'}"
                        if 'contact_dissipation_min' in stepping else ""))
    if impacts and two_point and not stepping:
        rest = two_point.get("rest_since")
        needed = impacts["friction_needed_max"]
        lines.append(f"- unilateral contact: {impacts['count']:.0f} impact{'' if impacts['count'] == 1 else 's'} took {impacts['energy_lost']:.4g} J (the largest "
                     f"tangential over normal impulse of an impact, the μ it would stick at: "
                     f"{format(needed, '.4g') if needed is not None else 'unbounded'}); "
                     f"on two points for {100 * two_point['time_fraction']:.1f} % of the run ({two_point['entries']:.0f} {'entry' if two_point['entries'] == 1 else 'entries'}; "
                     f"{impacts['settled']:.0f} impacts ended by the settle rule; {two_point['lifts']:.0f} lifts, "
                     f"{two_point['third_points']:.0f} third points"
                     + (f"; at rest on three points from t = {rest:.4f} s" if rest is not None else "") + ")")
    sliding = summary.get("sliding")
    if sliding:
        # a plane of finite friction: the summary's sliding section (the time sliding, the slips and sticks, friction's
        # work); under time-stepping a step "slides" where a point that carries the body slips after it
        loss = sliding["friction_loss"]
        lines.append(f"- friction μ = {sliding['friction']:g}: sliding {100 * sliding['time_fraction']:.1f} % of the run, "
                     f"{sliding['slips']:.0f} slip{'' if sliding['slips'] == 1 else 's'} and {sliding['sticks']:.0f} "
                     f"stick{'' if sliding['sticks'] == 1 else 's'}, "
                     + ("still sliding at the end, " if sliding.get("sliding_at_end") else "")
                     + f"friction took {loss:.4g} J"
                     + (" (negative: friction gave energy here rather than taking it; its cause is not yet explained)"
                        if loss < 0 else ""))
    flight = summary.get("flight")
    if flight and (flight["lift_offs"] or flight["landings"]):
        lines.append(f"- flight (restitution e = {flight['restitution']:g}): {100 * flight['flight_time_fraction']:.1f} % of the "
                     f"run in flight; {flight['lift_offs']:.0f} lift-offs, {flight['landings']:.0f} landings "
                     f"({flight['bounces']:.0f} bounced"
                     + (f"; {flight['landings_flying_on']:.0f} flew on, a point struck and the body turned off the plane"
                        if flight.get("landings_flying_on") else "")
                     + f"); highest gap between the lowest point and the plane "
                     f"{flight['max_hop_height']:.4g} m")
    lines.append(f"- attitude: max |RᵀR − I| = {summary['orthonormality_max']:.2g}; largest quaternion-norm "
                 f"correction {summary['quaternion_drift_max']:.2g}")
    monitors = summary.get("monitors")
    if monitors:
        lines.append(f"- validity: g_eff ≤ 0 in {100 * monitors['geff_nonpositive_fraction']:.2f} % of samples "
                     f"(min {monitors['geff_min']:.3f} m/s²); normal force ≤ 0 (lift-off) in "
                     f"{100 * monitors['lift_off_fraction']:.2f} % (min {monitors['normal_force_min']:.3f} N); "
                     f"the contact forces' |F_t|/N in the samples (between impacts) up to {monitors['friction_needed_max']:.3f}")
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
        # why a record is not converged, in the rule's own terms (gb_lyapunov.h): a warm-up found, batches independent,
        # the last quarter's drift within twice the error bar
        why = [reason for failed, reason in (
            (not lyap.get("warmup_found", True), "no warm-up found"),
            (not lyap.get("batches_independent", True), "its batch means are not independent (lag-1 correlation "
                                                        f"{lyap.get('batch_correlation', float('nan')):.2g})"),
            (lyap["late_drift"] > 2.0 * lyap["error_bar"], f"it moved {lyap['late_drift']:.3g} over the last quarter, "
                                                           f"more than twice its error bar {lyap['error_bar']:.3g}")) if failed]
        lines.append(f"- λ_max (Fig 9) = {lyap['lambda_max']:.4f} ± {lyap['error_bar']:.4f} 1/s over "
                     f"{lyap['periods']:.0f} periods (δ0 = {lyap['delta0']:g}, {lyap['batches']:.0f} batches); running "
                     f"value moved {lyap['late_drift']:.3g} over the last quarter: "
                     + ("converged" if lyap["converged"] else "not converged (" + "; ".join(why or ["the rule's"]) + ")"))
        windows = lyap.get("windows")
        if windows:
            life = windows["chaos_lifetime_periods"]
            life = ("no window chaotic: no chaos in the record" if not windows["chaotic_windows"]
                    else f"the chaos lasts to period {life:.0f} of the record" if not isinstance(life, str)
                    else "chaotic to the end of the record")
            lines.append(f"- windowed λ per {windows['window_periods']:.0f} periods: "
                         + ", ".join(f"{v:.3f}" for v in windows["lambda_window"])
                         + f" 1/s; {windows['chaotic_windows']:.0f} of {windows['windows']:.0f} windows above "
                         f"{windows['chaotic_threshold']:g} 1/s: {life}")
    lines.append("")
    for label, figure in figures:
        lines.append(f"![{label}]({figure})")
        lines.append("")
    movie = animation_of(name, summary)
    if movie:
        lines += [f"![the body in motion]({movie})" if movie.endswith(".gif") else f"[the body in motion]({movie})",
                  "", "The body in motion (reports/animate.py): the surface in its attitude over the first seconds of "
                  "this run, its centroid at its height above the plane, the contact point and the crease marked.", ""]
    return lines


def animation_of(name, summary):
    """The scene's animation when it was drawn from this run's history (its checksum), else None."""
    path = os.path.join(OUT_DIR[0], f"{name}-animation.json")
    if not os.path.exists(path):
        return None
    drawn = load_json(path)
    history = {f["name"]: f for f in summary.get("files", [])}.get(f"{name}-history.csv")
    if not history or drawn.get("history_fnv1a64") != history["fnv1a64"]:
        return None
    return drawn["file"] if os.path.exists(os.path.join(OUT_DIR[0], drawn["file"])) else None


OUT_DIR = ["."]


# A figure this script drew for a scene in an earlier run (its NAME-figures.json lists it) that this run does not
# draw is removed, never linked; a file it did not write, whatever its name, is left alone.


def scene_figures(out, name, summary):
    """Draw the figures of the outputs this run of the scene wrote (the summary's `files`), remove the
    scene's figures it did not draw, and write OUT/NAME-figures.json: each figure's file, title and the
    numbers its title quotes. Returns [(label, file)]."""
    written = {f["name"] for f in summary.get("files", [])}
    earlier = previous_files(out, f"{name}-figures.json")
    inputs = drawn_from(summary)
    reused = reusable(out, name, inputs)
    if reused is not None:  # drawn already from these very files by this very plotter (make verify's second page)
        return reused
    drawn, manifest = [], []
    h = None
    if f"{name}-history.csv" in written:
        h = load_history(os.path.join(out, f"{name}-history.csv"))
        impacts = load_impacts(out, name, written)
        path, title, facts = time_series_figure(out, name, h, summary, impacts)
        drawn.append((paper_number(summary["scene"], "timeseries") or "time histories", path))
        quoted = {"grid_switches": summary["grid_switches"], "branch_switches": summary["branch_switches"]}
        if summary.get("impacts"):
            quoted["impacts"] = summary["impacts"]["count"]
        manifest.append({"kind": "fig-timeseries", "file": path, "title": title, "quotes": quoted, "layout": facts})
        path, title, facts = contact_figure(out, name, h, summary)
        drawn.append((paper_number(summary["scene"], "contact") or "contact", path))
        manifest.append({"kind": "fig-contact", "file": path, "title": title, "quotes": {}, "layout": facts})
    if f"{name}-strobe.csv" in written:
        path, title, facts = strobe_figure(out, name, summary)
        drawn.append(("Fig 7", path))
        manifest.append({"kind": "fig7-strobe", "file": path, "title": title, "quotes": {"samples": summary["strobe"]["samples"]},
                         "layout": facts})
    if f"{name}-spectrum.csv" in written:
        path, title, facts = spectrum_figure(out, name, summary, h)
        drawn.append(("Fig 8", path))
        manifest.append({"kind": "fig8-spectrum", "file": path, "title": title, "quotes": {}, "layout": facts})
    if f"{name}-lyapunov.csv" in written:
        path, title, end, facts = lyapunov_figure(out, name, summary)
        drawn.append(("Fig 9", path))
        manifest.append({"kind": "fig9-lyapunov", "file": path, "title": title,
                         "quotes": {"lambda_max": summary["lyapunov"]["lambda_max"], "error_bar": summary["lyapunov"]["error_bar"]},
                         "curve_end": end, "layout": facts})
    files = {path for _, path in drawn}
    for stale in earlier - files:  # only what this script drew before, as its own manifest says
        if os.path.exists(os.path.join(out, stale)):
            os.remove(os.path.join(out, stale))
    write_atomically(os.path.join(out, f"{name}-figures.json"), json.dumps(
        {"scene": name, "drawn_from": inputs, "figures": manifest, "labels": [label for label, _ in drawn]}, indent=1))
    return drawn


def drawn_from(summary):
    """What a scene's figures depend on: the checksums of the run's files and of this plotter's own source."""
    here = os.path.dirname(os.path.abspath(__file__))
    plotter = hashlib.sha256()
    for source in ("run_report.py", "common.py"):
        with open(os.path.join(here, source), "rb") as handle:
            plotter.update(handle.read())
    files = sorted((f["name"], f.get("fnv1a64", "")) for f in summary.get("files", []))
    return {"plotter_sha256": plotter.hexdigest(), "files": [list(f) for f in files], "scene": summary.get("scene", {})}


def reusable(out, name, inputs):
    """The [(label, file)] of a manifest of this scene drawn from the same inputs whose files are all there, else None."""
    try:
        data = load_json(os.path.join(out, f"{name}-figures.json"))
    except (OSError, ValueError):
        return None
    if not isinstance(data, dict) or data.get("drawn_from") != inputs or "labels" not in data:
        return None
    files = [f.get("file") for f in data.get("figures", [])]
    if len(files) != len(data["labels"]) or not all(isinstance(f, str) and os.path.exists(os.path.join(out, f)) for f in files):
        return None
    return list(zip(data["labels"], files))


def main(argv=None):
    """The command line's work on argv (else sys.argv[1:]); gomboc.plot.run calls it in-process."""
    args = list(sys.argv[1:] if argv is None else argv)
    help_requested(__doc__, args)
    page = None
    if "--page" in args:
        k = args.index("--page")
        page = args[k + 1] if k + 1 < len(args) else None
        del args[k:k + 2]
        if not page or "/" in page:
            sys.exit("run_report.py: --page takes a file name in OUT (allowed: --page NAME.md)")
    if len(args) < 2:
        sys.exit("usage: run_report.py OUT NAME [NAME ...] [--page FILE.md]")
    out, names = args[0], args[1:]
    OUT_DIR[0] = out
    # one scene's page is named after it, so that scenes run into one directory keep their pages
    page = page or (f"{names[0]}-run.md" if len(names) == 1 else "runs.md")
    lines = ["# gomboc — scene runs", ""]
    for name in names:
        summary = load_json(os.path.join(out, f"{name}-summary.json"))
        lines += summary_lines(name, summary, scene_figures(out, name, summary))
    write_atomically(os.path.join(out, page), "\n".join(lines))


if __name__ == "__main__":
    input_errors(main)
