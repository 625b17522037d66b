"""The report section on the dynamics (paper §3, §5, §8): the Table 1 scenes in both readings of the
amplitudes, the harmonic benchmark, the energy balance per equation variant and contact model, and the
validity monitors. Reads the *-summary.json files `gomboc run` wrote and the check rows; recomputes
nothing."""
import glob
import os

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from common import load_json, save_figure  # noqa: E402

SCENE_ORDER = ["table1-gomboc-I", "table1-gomboc-II", "table1-gomboc-I-g-units", "table1-gomboc-II-g-units",
               "harmonic-gomboc-I", "harmonic-gomboc-II", "table1-gomboc-I-rolling", "table1-gomboc-II-rolling",
               "table1-gomboc-I-g-units-unilateral", "table1-gomboc-II-g-units-unilateral",
               "table1-gomboc-I-g-units-bouncing", "table1-gomboc-II-g-units-bouncing"]


def work_precision(out):
    """Final-state error against wall time, per integrator and contact model (verify/s5_dynamics.c)."""
    path = os.path.join(out, "work-precision.json")
    if not os.path.exists(path):
        return ["(work-precision data missing: the test did not write it)", ""]
    data = load_json(path)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5), sharey=True)
    for ax, contact in zip(axes, ("continuous", "grid")):
        for integrator in ("rk4", "rk8pd", "rkf45", "rk4imp"):
            points = [r for r in data if r["contact"] == contact and r["integrator"] == integrator]
            done = [r for r in points if r["finished"]]
            ax.loglog([r["seconds"] for r in done], [max(r["error"], 1e-17) for r in done], marker="o", label=integrator)
            stalled = [r for r in points if not r["finished"]]
            if stalled:
                ax.loglog([r["seconds"] for r in stalled], [r["error"] for r in stalled], marker="x", ls="none", color="red")
        ax.set_title(f"{contact} contact (red x: adaptive step collapsed, run stopped)", fontsize=9)
        ax.set_xlabel("wall time for one period [s]")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("max state error after one period")
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, os.path.join(out, "work-precision.png"))
    plt.close(fig)
    lines = ["### Work–precision: error against run time", "",
             "One period of the Table 1 forcing (Gömböc I, rolling equation, R0 = I, ω0 = 0), against a tight",
             "reference of the same model (continuous: RK4 at 10240 steps per period, which matches scipy's DOP853 to",
             "1e-15; grid: RK4 at 20480). RK4 at 40–2560 steps per period; adaptive steppers at rtol 1e-4 to 1e-10.", "",
             "| contact | integrator | steps/period or rtol | error | seconds | right-hand sides | finished |",
             "|---|---|---|---|---|---|---|"]
    for r in data:
        lines.append(f"| {r['contact']} | {r['integrator']} | {r['setting']:g} | {r['error']:.2e} | {r['seconds']:.4f} | "
                     f"{r['rhs_evaluations']:.0f} | {'yes' if r['finished'] else '**no: step limit**'} |")
    lines += ["", "![work-precision](work-precision.png)", ""]
    return lines


def switching_work_precision(out, records):
    """Error against run time over 20 periods through branch switches, gomboc against scipy (make bench)."""
    chosen = [r for r in records if "wp_law" in r]
    if not chosen:
        return []
    laws = [law for law in ("held", "unilateral") if any(r["wp_law"] == law for r in chosen)]
    fig, axes = plt.subplots(1, len(laws), figsize=(6 * len(laws), 4.5), squeeze=False)
    for ax, law in zip(axes[0], laws):
        for tool in ("gomboc", "scipy"):
            steppers = sorted({r["wp_stepper"] for r in chosen if r["wp_law"] == law and r["wp_tool"] == tool})
            for stepper in steppers:
                pts = [r for r in chosen if r["wp_law"] == law and r["wp_tool"] == tool and r["wp_stepper"] == stepper
                       and not r.get("wp_failed")]
                ax.loglog([r["wp_seconds"] for r in pts], [max(r["wp_error"], 1e-17) for r in pts],
                          marker="o" if tool == "gomboc" else "s", ls="-" if tool == "gomboc" else "--",
                          label=f"{tool} {stepper}")
        ax.set_title(f"Gömböc I, 20 periods, {law} contact law, switches located", fontsize=9)
        ax.set_xlabel("integration time [s]")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    axes[0][0].set_ylabel("max |final state − reference|")
    fig.tight_layout()
    save_figure(fig, os.path.join(out, "work-precision-switching.png"))
    plt.close(fig)
    stored = [r["wp_reference_against_stored"] for r in records if "wp_reference_against_stored" in r]
    lines = ["", "Work–precision through branch switches: 20 Table 1 periods of the rolling model (Gömböc I, R0 = I, "
             "ω0 = 0, continuous contact certified per vertical, every switch located), the integration alone timed on "
             "both sides (the set-up, and scipy's sympy derivation, not counted). gomboc's RK4 at 80–1280 steps a period "
             "and its adaptive steppers at rtol 1e-4 to 1e-12 (atol = rtol/100); scipy's `solve_ivp` DOP853 and Radau "
             "through `references/switching.py`'s own switch handling (a grid scan for a lower minimum after every "
             "nominal step, brentq on the dense output). Errors against gomboc's rk8pd at rtol 1e-13"
             + (f", which lies {stored[0]:.2g} from the stored scipy trajectory (DOP853, rtol 1e-12)" if stored else "")
             + ". The ratio: scipy's time over the least time any gomboc stepper needs for the same error "
             "(interpolated on its curve). Target (issue 30): ≥ 50×. The unilateral law (impacts, two-point rolling) "
             "has no scipy counterpart here; its curves are gomboc's alone, against its own rk8pd at 1e-13.", "",
             "| scipy stepper | rtol | error | scipy [s] | gomboc's best at that error | gomboc [s] | ratio |",
             "|---|---|---|---|---|---|---|"]
    for r in chosen:
        if r["wp_tool"] == "scipy":
            lines.append(f"| {r['wp_stepper']} | {r['wp_setting']:g} | {r['wp_error']:.2g} | {r['wp_seconds']:.2f} | "
                         f"{r['wp_gomboc_best']} | {r['wp_gomboc_seconds']:.4f} | "
                         f"{format(r['wp_ratio'], '.0f') + '×' if r['wp_ratio'] > 0 else '—'} |")
    failed = [r for r in chosen if r.get("wp_failed")]
    if failed:
        lines += ["", "Runs that failed (the computation stopped with an error; not drawn): " +
                  ", ".join(f"{r['wp_tool']} {r['wp_stepper']} at {r['wp_setting']:g} under the {r['wp_law']} law"
                            for r in failed) + "."]
    lines += ["", "![work-precision through switches](work-precision-switching.png)"]
    return lines


def bench_table(records, key, intro, header, row):
    """The lines of one table of `make bench`'s records that hold `key`: intro, header, a row each."""
    chosen = [r for r in records if key in r]
    if not chosen:
        return []
    lines = ["", intro, "", "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    return lines + ["| " + " | ".join(row(r)) + " |" for r in chosen]


def dynamics_section(out, rows):
    names = [n for n in SCENE_ORDER if os.path.exists(os.path.join(out, f"{n}-summary.json"))]
    extra = sorted(os.path.basename(p)[:-len("-summary.json")] for p in glob.glob(os.path.join(out, "*-summary.json")))
    names += [n for n in extra if n not in names]
    lines = ["## Dynamics: the Table 1 scenes (paper §3, §5, §8)", "",
             "Every scene is a file in `cases/`; the values it used are printed with it (and in its summary JSON).",
             "The paper leaves open the initial attitude — we start from R0 = I, which is not an equilibrium —",
             "and whether Table 1's A1 = 2.0, A2 = 1.0 are in m/s² or in units of g (eq 61): both readings run.", ""]
    fractions = [r for r in rows if r["quantity"].startswith("fraction of each period with g_eff <= 0")]
    for r in fractions:
        reading = r["quantity"].split("read in ")[-1]
        lines.append(f"- Table 1 read in {reading}: g_eff ≤ 0 for {100 * r['measured']:.2f} % of every period "
                     f"(checked against 10⁶ samples: {'pass' if r['passed'] else '**FAIL**'}).")
    lines += ["", "| scene | equation | contact | grid-index changes | branch switches | certified global (checks, undecided) | "
              "energy residual (max) [J] | g_eff ≤ 0 | lift-off (N ≤ 0) | max friction needed |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for n in names:
        s = load_json(os.path.join(out, f"{n}-summary.json"))
        m = s.get("monitors", {})
        continuous = s["scene"]["contact"] == "continuous"
        branches = f"{s['branch_switches']:.0f}" if continuous else "not tracked (grid)"
        cert = s.get("certificate")
        certified = (f"{cert['global']:.0f} of {cert['checks']:.0f} ({cert['undecided']:.0f} undecided)" if cert
                     else "— (grid)")
        lines.append(f"| `{n}` | {s['scene']['equation']} | {s['scene']['contact']} | {s['grid_switches']:.0f} | "
                     f"{branches} | {certified} | {s['energy_residual_max']:.3g} | "
                     f"{100 * m.get('geff_nonpositive_fraction', float('nan')):.1f} % | "
                     f"{100 * m.get('lift_off_fraction', float('nan')):.1f} % | {m.get('friction_needed_max', float('nan')):.3f} |")
    lines += ["", "**Determinism fingerprints.** Each run's summary carries an FNV-1a hash of its final state and one "
              "of its switch sequence (`gomboc run` prints both on its last line). The same binary and libm give "
              "the same two hashes on any machine; a different compiler or libm may change the last bits of a "
              "chaotic run, and with them both hashes. Across such builds the statistics are what must agree: "
              "two runs' exponents are the same when the 'equivalent' rule holds for them (difference + 2.26 "
              "combined errors within 10 %), and the checks' tolerances, not the bits, are the criterion.", "",
              "| scene | final state | switch sequence |", "|---|---|---|"]
    for n in names:
        fp = load_json(os.path.join(out, f"{n}-summary.json")).get("fingerprint")
        if fp:
            lines.append(f"| `{n}` | `{fp['final_state']}` | `{fp['switches']}` |")
    for r in fractions:
        if r["measured"] > 0:
            reading = r["quantity"].split("read in ")[-1]
            lines += ["", f"Read in {reading}, g_eff ≤ 0 for {100 * r['measured']:.1f} % of every period: the support then "
                      "accelerates downward faster than gravity, the body must leave the plane, and the paper's "
                      "single-contact model has no meaning there. The runs still integrate it, and the monitors say so."]
    lines += ["",
              "### Energy balance per equation variant and contact model", "",
              "The balance E(t) − E(0) = ∫(P_d + m ġ_eff ζ) dt (eqs 46–51) is derived in `docs/rolling.md` for a body",
              "rolling without slip. The checks (numbers from this run):", ""]
    wanted = ("energy of eq 44", "max |E(t) - E(0)|", "observed order of the energy error", "energy of the paper's grid model",
              "energy-balance residual", "observed order of the balance residual", "observed order of the state")
    lines += ["| check | measured | result |", "|---|---|---|"]
    for r in rows:
        if r["quantity"].startswith(wanted):
            measured = r.get("detail") if r["kind"] != "compare" else f"{r['measured']:.3g}"
            verdict = "pass" if r["passed"] else "**FAIL**"
            if r["kind"] == "finding":
                verdict = {"holds": "paper holds", "fails": "**paper refuted**"}.get(r["verdict"], "*undecided*") + \
                          ("" if r["passed"] else ", evidence not computed")
            quantity = r["quantity"].replace("|", "\\|")
            lines.append(f"| {quantity} | {str(measured).replace('|', '/')} | {verdict} |")
    bench = os.path.join(out, "bench.json")
    stamp = os.path.join(out, "gates", "bench.json")
    lines += ["### Speed (from the last `make bench` on this machine)", ""]
    if os.path.exists(bench):
        if os.path.exists(stamp):
            s = load_json(stamp)
            dirty = " with uncommitted changes" if s.get("uncommitted_changes") else ""
            lines += [f"Measured by `make bench` on {s['date']} at commit {s['commit']}{dirty}, not by this run of "
                      "`make verify`: compare the commit with this report's before quoting a ratio.", ""]
        else:
            lines += ["These ratios carry no record of when or at which commit they were measured: rerun `make bench`.", ""]
        lines += ["Whole Table 1 runs (300 periods, RK4, 160 steps per period = 192 000 contact queries), measured side by "
                  "side in one `make bench` run (best of 2). The baseline is the best plain loop a user would write for the "
                  "paper's contact: every node's height in its own translation unit (`verify/bench/plain.c`: the nodes as "
                  "three aligned arrays, a vectorised min-reduction, then the first node at the minimum), with the "
                  "library's equations around it, all built with -O3 -march=native (the best flags of this compiler); it "
                  "must return brute force's node on 10⁴ seeded verticals and reach the same final state. Beside it: the "
                  "library's own loop over every node in that build and in the shipped build (`CFLAGS`, -O3 by default). Targets (issue 20): fast "
                  "grid and continuous contact certified global at every step, each ≥ 20× the baseline; the continuous "
                  "column here is certified per vertical, and the table after the set-up's gives it with the atlas of "
                  "verticals. Nodes per query: "
                  "the heights the fast grid's tracker computes per contact query. The certificate columns count its checks "
                  "in the continuous run: global (proved), lower minimum found (a branch switch), undecided (a box it could "
                  "neither settle nor split further; the step keeps the continued branch).", "",
                  "| body | plain loop [s] | same node and state | library loop, native [s] | library loop, shipped flags [s] | fast grid [s] | "
                  "nodes per query | speed-up | fast run identical | continuous rolling, certified [s] | speed-up | checks | "
                  "global | lower found | undecided | boxes tested per check |",
                  "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
        records = load_json(bench)
        for r in records:
            if "plain_seconds" in r:
                cert = (f"{r['certificate_checks']} | {r['certificate_global']} | {r['certificate_lower_found']} | "
                        f"{r['certificate_undecided']} | {r['certificate_boxes_per_check']:.1f}"
                        if "certificate_checks" in r else "— | — | — | — | —")
                base = r.get("baseline_seconds") or r["plain_seconds"]
                native = (f"{r['baseline_seconds']:.3f} | {'yes' if r.get('baseline_same_state') else '**no**'}"
                          if r.get("baseline_seconds") else "not run (ratios against the shipped library loop) | —")
                library = f"{r['library_native_seconds']:.3f}" if r.get("library_native_seconds") else "—"
                nodes = f"{r['fast_nodes_per_query']:.1f}" if "fast_nodes_per_query" in r else "—"
                lines.append(f"| {r['body']} | {native} | {library} | {r['plain_seconds']:.3f} | {r['fast_seconds']:.3f} | "
                             f"{nodes} | {base / r['fast_seconds']:.1f}× | {'yes' if r['fast_identical'] else '**no**'} | "
                             f"{r['continuous_seconds']:.3f} | {base / r['continuous_seconds']:.1f}× | {cert} |")
        lines += bench_table(records, "fast_setup_seconds",
                             "Set-up of the same runs (the body's mass properties and the grid for all; the plain loop's copy "
                             "of the nodes; the fast grid's hull, built by Qhull; the continuous contact's first certified "
                             "minimum), and the speed-ups with it counted on both sides:",
                             ["body", "plain loop [s]", "fast grid [s]", "continuous [s]", "fast grid, with set-up",
                              "continuous, with set-up"],
                             lambda r: [r["body"], f"{r['baseline_setup_seconds']:.3f}", f"{r['fast_setup_seconds']:.3f}",
                                        f"{r['continuous_setup_seconds']:.3f}",
                                        f"{(r['baseline_seconds'] + r['baseline_setup_seconds']) / (r['fast_seconds'] + r['fast_setup_seconds']):.1f}×",
                                        f"{(r['baseline_seconds'] + r['baseline_setup_seconds']) / (r['continuous_seconds'] + r['continuous_setup_seconds']):.1f}×"])
        lines += bench_table(records, "whole_process_body",
                             "What a user waits for: the whole `gomboc run` process of Table 1 with the paper's model and the "
                             "fast grid (the trajectory and its summary; no history or diagnostics) against the plain loop's "
                             "whole process (its own program, built with -O3 -march=native), both timed from outside in the "
                             "same `make bench` run, best of 3: a body's first run, whose hull Qhull builds, and the runs after "
                             "it, which read the hull from the file the first one wrote (`--hull FILE`); the command's "
                             "start-up is the whole process of a one-period run with the hull read. Target (issue 30): ≥ 30×.",
                             ["body", "plain loop, whole process [s]", "gomboc run, hull by Qhull [s]", "ratio",
                              "gomboc run --hull, hull read [s]", "ratio", "start-up (1 period) [s]",
                              "the 300 periods after it [s]"],
                             lambda r: [r["whole_process_body"], f"{r['plain_process_seconds']:.3f}",
                                        f"{r['gomboc_cold_process_seconds']:.3f}" if "gomboc_cold_process_seconds" in r else "—",
                                        f"{r['cold_process_ratio']:.1f}×" if "cold_process_ratio" in r else "—",
                                        f"{r['gomboc_process_seconds']:.3f}", f"{r['process_ratio']:.1f}×",
                                        f"{r['startup_process_seconds']:.3f}",
                                        f"{r['gomboc_process_seconds'] - r['startup_process_seconds']:.3f}"])
        lines += bench_table(records, "startup_body",
                             "Where the start-up goes: the stages of a fast-grid run's set-up, each timed alone in the bench's "
                             "process (best of 5, ms), and the first period's integration. A process that only prints its "
                             "version costs the first column.",
                             ["body", "process start [ms]", "scene read [ms]", "mass properties [ms]",
                              "grid nodes, patch tree [ms]", "hull (Qhull) and its graph [ms]", "hull from its file [ms]",
                              "first period [ms]"],
                             lambda r: [r["startup_body"], f"{r['process_ms']:.1f}", f"{r['scene_ms']:.2f}",
                                        f"{r['massprops_ms']:.2f}", f"{r['grid_ms']:.2f}", f"{r['hull_ms']:.2f}",
                                        f"{r['hull_file_ms']:.2f}" if "hull_file_ms" in r else "—",
                                        f"{r['first_period_ms']:.2f}"])
        lines += bench_table(records, "scan_model",
                             "Scans through `gomboc scan` (4 × 4 points of 50 periods around Table 1, λ included; the Melnikov "
                             "margins apart, a scan of them alone over the same points: one reduced model, the integrals "
                             "at 4 frequencies; best of 2 for each thread count), and the paper model's whole Fig 12 map "
                             "(625 points of 100 periods, once each), the same `make bench` run. Each thread keeps its "
                             "body's set-up (mass properties, grid, hull) from point to point, so a point of the paper's "
                             "model costs its integration alone, and in the 4 × 4 scan the threads' own set-up and the "
                             "process's start weigh against 16 points of ~14 ms: the full map shows the threads' scaling. "
                             "Target (issue 19): parallel efficiency ≥ 90 % on 2 threads.",
                             ["model", "points/s, 1 thread", "points/s, 2 threads", "efficiency"],
                             lambda r: [r["scan_model"], f"{r['points_per_second_1']:.2f}", f"{r['points_per_second_2']:.2f}",
                                        f"{r['parallel_efficiency']:.0%}"])
        lines += switching_work_precision(out, records)
        lines += bench_table(records, "melnikov_body",
                             "A scan's Melnikov plan: one body's reduced model, then its integrals at the 25 frequencies of the "
                             "(ω, A1) maps (12 to 24 rad/s) from the separatrix tables (what `gomboc scan` and `gomboc "
                             "melnikov` do; best of 2) and, side by side in the same run, by adaptive quadrature at every "
                             "frequency; the largest difference of the integrals relative to the largest. Target (issue 30): "
                             "the reduced model and the 25 frequencies ≤ 1 s.",
                             ["body", "reduced model [s]", "tables, 25 ω [s]", "plan [s]", "adaptive, 25 ω [s]", "speed-up",
                              "max difference"],
                             lambda r: [r["melnikov_body"], f"{r['reduced_model_seconds']:.3f}", f"{r['tables_seconds']:.4f}",
                                        f"{r['reduced_model_seconds'] + r['tables_seconds']:.3f}",
                                        f"{r['adaptive_seconds']:.2f}",
                                        f"{r['adaptive_seconds'] / r['tables_seconds']:.0f}×",
                                        f"{r['max_relative_difference']:.2g}"])
        baseline = {r["body"]: r.get("baseline_seconds") or r["plain_seconds"] for r in records if "plain_seconds" in r}
        lines += bench_table(records, "atlas_cached_seconds",
                             "Certified continuous contact three ways on the same Table 1 rolling runs (the same `make bench` "
                             "run, best of 2): per vertical (`gb_certify` at every step), with the atlas of verticals built "
                             "during the run, and with the atlas loaded from the file an earlier run wrote (its load counted "
                             "in the set-up column, not the run). The three must end in the same state bits. Cells: certified "
                             "cells of verticals (two-site: a cell naming two minima); fallbacks: checks of the cached run "
                             "left to the per-vertical certificate (docs/certificate.md). Speed-ups against the plain loop; "
                             "target (issue 20): ≥ 20×.",
                             ["body", "per vertical [s]", "speed-up", "atlas built in the run [s]", "speed-up", "of it, building [s]",
                              "atlas from its file [s]", "speed-up", "set-up with the load [s]", "cells", "two-site cells",
                              "memory [MiB]", "fallbacks", "same bits"],
                             lambda r: [r["body"], f"{r['atlas_per_vertical_seconds']:.3f}",
                                        f"{baseline[r['body']] / r['atlas_per_vertical_seconds']:.1f}×",
                                        f"{r['atlas_built_seconds']:.3f}", f"{baseline[r['body']] / r['atlas_built_seconds']:.1f}×",
                                        f"{r['atlas_build_seconds']:.3f}", f"{r['atlas_cached_seconds']:.3f}",
                                        f"{baseline[r['body']] / r['atlas_cached_seconds']:.1f}×", f"{r['atlas_load_seconds']:.3f}",
                                        str(r["atlas_cells"]), str(r["atlas_two_site_cells"]),
                                        f"{r['atlas_bytes'] / 1048576:.1f}", str(r["atlas_cached_fallbacks"]),
                                        "yes" if r["atlas_identical"] else "**no**"])
        lines += bench_table(records, "law_certificate",
                             "The unilateral contact law against the held one on the same Table 1 runs (300 periods, the same "
                             "`make bench` run, best of 2): continuous rolling with every change of contact located, with each "
                             "certificate (the atlas built in the run); and the paper's grid model (90 × 180, fast grid), held "
                             "as its scenes run it (node changes at step ends, none located) against the unilateral law (the "
                             "grid body as a polyhedron, every change of node a located impact); "
                             "target (issue 28): a unilateral run ≤ 1.3× the held run of the same scene.",
                             ["body", "certificate or model", "held [s]", "unilateral [s]", "ratio"],
                             lambda r: [r["body"], r["law_certificate"], f"{r['held_seconds']:.3f}",
                                        f"{r['unilateral_seconds']:.3f}", f"{r['unilateral_over_held']:.2f}×"])
        lines += bench_table(records, "flight_held_seconds",
                             "Table 1 read in units of g (continuous rolling, 300 periods, the same `make bench` run, best of "
                             "2): the held law, whose one contact is kept where the normal force is negative (no physical "
                             "motion), against the unilateral law, where every lift-off and landing is a located event and "
                             "the body flies between them, plastic (e = 0) and bouncing (e = 0.5).",
                             ["body", "held [s]", "unilateral e = 0 [s]", "ratio", "unilateral e = 0.5 [s]", "ratio"],
                             lambda r: [r["body"], f"{r['flight_held_seconds']:.3f}", f"{r['flight_plastic_seconds']:.3f}",
                                        f"{r['flight_plastic_seconds'] / r['flight_held_seconds']:.2f}×",
                                        f"{r['flight_bouncing_seconds']:.3f}",
                                        f"{r['flight_bouncing_seconds'] / r['flight_held_seconds']:.2f}×"])
        headroom = [r for r in records if "headroom_total_seconds" in r]
        if headroom:
            lines += ["", "Why the certified run is far from 50× (the same `make bench` run): the run's time inside the "
                      "certificate's checks and outside them (the dynamics with its Newton solves and RK4), and the ratio "
                      "the outside time alone allows; then the basin half-width (widest centred box on which the range of "
                      "h's chart Hessian passes the definiteness test) at states sampled along the run, with the range "
                      "from one interval enclosure, as the certificate computes it, and sampled on a 25 × 25 grid of "
                      "points (an inner estimate of the exact range). The budget for 50× is the plain loop's time / 50.",
                      "", "| body | certified run [s] | inside checks [s] | outside [s] | free-certificate ceiling | "
                      "budget for 50× [s] | basin, one enclosure [rad] | basin, sampled ranges [rad] | basins built, "
                      "geometric mean [rad] |", "|---|---|---|---|---|---|---|---|---|"]
            plain = {r["body"]: r["plain_seconds"] for r in records if "plain_seconds" in r}
            for r in headroom:
                budget = f"{plain[r['body']] / 50:.3f}" if r["body"] in plain else "—"
                lines.append(f"| {r['body']} | {r['headroom_total_seconds']:.3f} | {r['check_seconds']:.3f} | "
                             f"{r['outside_seconds']:.3f} | {r['free_certificate_ratio']:.1f}× | {budget} | "
                             f"{r['basin_enclosed_width']:.4f} | {r['basin_sampled_width']:.4f} "
                             f"(×{r['basin_sampled_width'] / r['basin_enclosed_width']:.1f}) | "
                             f"{r['basins_built']}, {r['basin_built_width']:.4f} |")
        lines += bench_table(records, "lambda_seconds",
                             "λ_max over the same 300 periods (pair estimator, eq 77) against one run of the same scene, "
                             "timed beside it in the same `make bench` run; target (issue 5): ≤ 2.2×.",
                             ["body", "model", "one run [s]", "λ run [s]", "ratio", "reference = the run"],
                             lambda r: [r["body"], r["lambda_model"], f"{r['run_seconds']:.3f}", f"{r['lambda_seconds']:.3f}",
                                        f"{r['lambda_seconds'] / r['run_seconds']:.2f}×",
                                        "yes" if r["reference_identical"] else "**no**"])
        lines.append("")
    else:
        lines += ["`make bench` has not been run in this output folder; run it to see the ratios here.", ""]
    lines += [""] + work_precision(out)
    extreme = os.path.join(out, "extreme-scenes.json")
    if os.path.exists(extreme):
        lines += ["### Stiff and extreme scenes", "",
                  "Each `cases/extreme-*.ini` (continuous contact, rolling equation, two periods) with every integrator. The "
                  "balance residual is E − E(0) − ∫(P_d + m ġ ζ) dt; a branch switch makes it jump (I_P changes at fixed ω).",
                  "", "| scene | integrator | finished | steps | right-hand sides | seconds | branch switches | max residual [J] |",
                  "|---|---|---|---|---|---|---|---|"]
        for r in load_json(extreme):
            lines.append(f"| {r['description']} | {r['integrator']} | {'yes' if r['finished'] else '**no**'} | {r['steps']:.0f} | "
                         f"{r['rhs_evaluations']:.0f} | {r['seconds']:.3f} | {r['branch_switches']:.0f} | {r['residual_max']:.3g} |")
        lines.append("")
    lines += ["", "Figures 3–6 of the paper for each scene (ω, h*, E with contact-switch markers, switching rate; contact "
              "index and r_c):", ""]
    for n in names:
        if os.path.exists(os.path.join(out, f"fig-timeseries-{n}.png")):
            lines += [f"#### `{n}`", "", f"![{n}](fig-timeseries-{n}.png)", "", f"![{n} contact](fig-contact-{n}.png)", ""]
    return lines
