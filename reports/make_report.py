#!/usr/bin/python3
"""The reproducibility report written by `make verify`: environment, the paper's claims against what
we measured, every check with its oracle, error, tolerance and origin, and error against run time.
Reads only what the C code wrote into OUT (checks.json, shape-*.json, the §4 files read by
contact_section.py); recomputes no physics.

usage: make_report.py OUT CC CFLAGS
"""
import datetime
import os
import platform
import re
import shutil
import subprocess
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy  # noqa: E402
import scipy  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from common import layout, load_json, save_figure, shape_summary_lines, write_atomically  # noqa: E402
from contact_section import contact_section  # noqa: E402
from dynamics_section import dynamics_section  # noqa: E402
from chaos_section import chaos_section  # noqa: E402
from melnikov_section import melnikov_section  # noqa: E402
from proofs_section import proofs_section  # noqa: E402
from scan_section import scan_section  # noqa: E402
from unilateral_maps import summary_sentence, unilateral_section  # noqa: E402
from siconos_section import SUITE as SICONOS_SUITE, siconos_section  # noqa: E402
from study_section import ensemble_readings, study_section  # noqa: E402

CHECKS_SCHEMA = 5  # verify/gb_check.h GB_CHECK_SCHEMA: {"schema": 5, "tests": [...], "rows": [...]}; rows carry file and line; findings carry verdict and rule


def load_checks(path):
    """The rows the harness recorded; refuses a file of another schema rather than misreading it."""
    document = load_json(path)
    if not isinstance(document, dict) or document.get("schema") != CHECKS_SCHEMA:
        found = document.get("schema") if isinstance(document, dict) else "none (a bare list)"
        sys.exit(f"make_report: {path} has schema {found}, this report reads schema {CHECKS_SCHEMA}")
    return document["rows"], document["tests"]


GATES = (("fuzz", "make fuzz", "the scene reader, the option parser and the atlas, scan file and scan journal readers "
          "under libFuzzer with ASan and UBSan"),
         ("sanitize", "make sanitize", "every check of the harness built with ASan and UBSan"),
         ("valgrind", "make valgrind", "one short scene of each model, shape and contact under memcheck"),
         ("verify-full", "make verify-full", "every check, the long studies (10000-period records) and the ensembles"),
         ("bench", "make bench", "speed ratios measured side by side in one run"),
         ("scans", "make scans", "the maps of Figs 10-13 (cases/scans: held and unilateral), 25 x 25 points each, and their stability maps; "
          "a 5 x 5 preview of Fig 10 in units of g stepped in time on a plane of friction 0.5"),
         ("study", "make study", "the ensembles of section 8.2 (cases/studies), 32 initial attitudes each (64 for Gömböc I; 16 in units of g and on planes of finite friction)"),
         ("mpi", "make mpi", "OpenMPI installed; gomboc-mpi's scans on 1, 2 and 3 ranks and after a kill -9, "
          "against one thread"))


def convergence(out):
    """The 300-period exponents (chaos.json) against the long records of `make verify-full`
    (chaos-long.json, no transient), per body and variation: {(body, variation): text} and the lines of
    the report's convergence paragraph. A 300-period value more than 4 combined errors from the long
    record is preliminary, and the long record is the verdict."""
    short_path, long_path = os.path.join(out, "chaos.json"), os.path.join(out, "chaos-long.json")
    stamp_path = os.path.join(out, "gates", "verify-full.json")
    notes, lines = {}, ["### Convergence of the 300-period exponents", ""]
    if not (os.path.exists(short_path) and os.path.exists(long_path)):
        lines += ["No long records in this checkout (`make verify-full` writes them): the 300-period exponents of the "
                  "continuous rolling model are not known to have converged, and their verdicts are preliminary.", ""]
        return notes, lines
    when = ""
    if os.path.exists(stamp_path):
        s = load_json(stamp_path)
        when = f" (`make verify-full` on {s['date']} at commit {s['commit']}, {s['result']})"
    lines += [f"Each 300-period λ against the long record of the same body and variation{when}. Each record's "
              "warm-up (left out of its mean, MSER-5) and batches (the error bar's) are chosen from the record itself "
              "(src/gb_lyapunov.h):", "",
              "| body | variation | 300 periods | long record | difference [combined errors] | reading | windowed λ "
              "(per 500 periods) |", "|---|---|---|---|---|---|---|"]
    short = {(r["body"], r["variation"]): r for r in load_json(short_path).get("variations", []) if "lambda_max" in r}
    for r in load_json(long_path):
        s = short.get((r["body"], r["variation"]))
        if not s or r.get("transient_periods", 0) != 0:
            continue
        combined = (s["error_bar"] ** 2 + r["error_bar"] ** 2) ** 0.5
        sigmas = abs(s["lambda_max"] - r["lambda_max"]) / combined if combined > 0 else float("inf")
        reading = ("**preliminary: the long record is the verdict**" if sigmas > 4 else "consistent")
        notes[(r["body"], r["variation"])] = reading
        lines.append(f"| {r['body']} | {r['variation']} | {s['lambda_max']:.3f} ± {s['error_bar']:.3f}{layout(s)} | "
                     f"{r['lambda_max']:.3f} ± {r['error_bar']:.3f} ({r['periods']:.0f} periods{layout(r, ', ')}) | "
                     f"{sigmas:.1f} | {reading} | {windows_text(r)} |")
    return notes, lines + [""]


def windows_text(record):
    """A long record's windowed exponents: how many windows are chaotic (above 0.05 1/s) and when the
    last one ends."""
    means = record.get("lambda_window")
    if not means:
        return "not recorded"
    life = record.get("chaos_lifetime_periods")
    life = ("to the end" if isinstance(life, str) else "no chaotic window" if life == 0
            else f"chaos ends by period {life:.0f}")
    return (f"{sum(1 for v in means if v > 0.05)} of {len(means)} above 0.05 1/s ({life}); range "
            f"{min(means):.3f} to {max(means):.3f}")


def verdict_text(verdict):
    """A finding's verdict as the report prints it: the paper's claim holds, fails, or is undecided."""
    return {"holds": "holds", "fails": "**fails**", "undecided": "*undecided*"}.get(verdict, verdict)


def gate_lines(out):
    """When each quality gate last ran in this checkout and what it gave (OUT/gates/GATE.json, written by
    scripts/gate-stamp.sh); a gate never run here says so."""
    lines = ["## Quality gates on bad input and memory", "",
             "`make verify` runs the table of bad inputs and the rule for every file written (suite 'Bad input, "
             "never misread': no output is an input, a device or another output; sets are whole or detectably "
             "mixed; concurrent writers of one atlas; journals verified line by line). The gates below run "
             "apart, by their own targets; this table reads what they last recorded in this checkout.", "",
             "| gate | what it runs | last run (UTC) | commit | result | detail |", "|---|---|---|---|---|---|"]
    for name, target, what in GATES:
        path = os.path.join(out, "gates", f"{name}.json")
        if not os.path.exists(path):
            lines.append(f"| `{target}` | {what} | not run in this checkout | — | — | — |")
            continue
        g = load_json(path)
        commit = g["commit"] + (" (with uncommitted changes)" if g.get("uncommitted_changes") else "")
        result = g["result"] if g["result"] == "passed" else f"**{g['result']}**"
        lines.append(f"| `{target}` | {what} | {g['date']} | {commit} | {result} | {g['detail'].replace('|', '/')} |")
    return lines + [""]


def command_output(args):
    try:
        return subprocess.run(args, capture_output=True, text=True, check=False).stdout.strip()
    except OSError:
        return "unavailable"


def environment(cc, cflags, rows):
    def pkg(name):
        return command_output(["pkg-config", "--modversion", name]) or "unknown"
    qhull = command_output(["dpkg-query", "-W", "-f=${Version}", "libqhull-dev"]) or "unknown"
    return [
        ("date (UTC)", datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M")),
        ("gomboc", open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "VERSION")).read().strip()
         + " (VERSION; CHANGELOG.md)"),
        ("git commit", command_output(["git", "rev-parse", "HEAD"]) or "not a git checkout"),
        ("working tree", "clean" if not command_output(["git", "status", "--porcelain"]) else "modified"),
        ("machine", f"{platform.machine()}, {os.cpu_count()} cores, {platform.platform()}"),
        ("compiler", command_output([cc, "--version"]).splitlines()[0] if command_output([cc, "--version"]) else cc),
        ("flags", cflags),
        ("GSL", pkg("gsl")), ("CUnit", pkg("cunit")), ("inih", pkg("inih")), ("cJSON", pkg("libcjson")),
        ("Qhull (Debian)", qhull),
        ("MPI", (command_output(["mpirun", "--version"]).splitlines() or ["unknown"])[0] +
         (": the checks on MPI ranks ran (suite 'Section 8.3: scans on MPI ranks')"
          if any("MPI ranks" in r.get("suite", "") for r in rows) else ": the checks on MPI ranks did not run")
         if shutil.which("mpicc") else "absent (mpicc not found): the checks on MPI ranks did not run; `make mpi` "
         "installs OpenMPI and runs them"),
        ("Python / numpy / scipy / matplotlib",
         f"{platform.python_version()} / {numpy.__version__} / {scipy.__version__} / {matplotlib.__version__}"),
    ]


def fmt(value):
    if isinstance(value, str):
        return value
    return f"{value:.3g}"


def error_vs_time(out, rows):
    compare = [r for r in rows if r["kind"] == "compare" and isinstance(r.get("relative_error"), float)]
    fig, ax = plt.subplots(figsize=(8, 5))
    groups = {}
    for r in compare:  # one colour and marker a suite (16), so that the legend fits and names each whole
        groups.setdefault(r["suite"], []).append(r)
    colours, markers = plt.get_cmap("tab20").colors, "osD^v<>p"
    for k, (suite, members) in enumerate(sorted(groups.items())):
        seconds = [max(m["seconds"], 1e-7) for m in members]
        errors = [max(m["relative_error"], 1e-18) for m in members]
        ax.scatter(seconds, errors, s=12, color=colours[k % len(colours)], marker=markers[k % len(markers)],
                   label=f"{suite} ({len(members)})")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("run time of the check [s]")
    ax.set_ylabel("relative error against the oracle (floored at 1e-18)")
    ax.set_title("Every numeric check: error against run time, by suite")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), title="suite (checks)", title_fontsize=7)
    fig.set_size_inches(12, 5.5)
    save_figure(fig, os.path.join(out, "error-vs-time.png"))
    plt.close(fig)


def spell(text):
    """One spelling in the report: the harness records ASCII names; the report writes the paper's (names in
    backticks, such as a CSV column `lambda_max`, stay as they are)."""
    text = text.replace("Gomboc", "Gömböc").replace("m/s^2", "m/s²")
    return re.sub(r"(?<![`\w])lambda_max(?![`\w])", "λ_max", text)


CENTRAL = "lambda_max > 0 after convergence at baseline"


FRICTION_PAIRS = (("continuous contact, rolling equation, unilateral contact", "m/s²"),
                  ("continuous rolling, unilateral contact with flight (e = 0), A in units of g", "units of g"))


def friction_lines(central, ensembles):
    """Whether a real plane (finite Coulomb friction) changes any verdict of the central claim against the
    perfectly rough plane of the same law, reading and body: the 300-period runs' findings, and the ensembles of
    `make study` where they were made."""
    changed, same, missing = [], 0, 0
    for rough, reading in FRICTION_PAIRS:
        for mu in ("0.3", "0.6"):
            real = central.get(f"{rough}, friction mu = {mu}", {})
            for body in ("I", "II"):
                a, b = central.get(rough, {}).get(body), real.get(body)
                if a is None or b is None:
                    missing += 1
                elif a == b:
                    same += 1
                else:
                    changed.append(f"Gömböc {body}, {reading}, μ = {mu}: {a} on the rough plane, {b} on the real one")
    if not same and not changed:
        return []
    text = (f"**A real plane** (Coulomb friction μ = 0.3 and 0.6, `docs/friction.md`): of {same + len(changed)} verdicts "
            f"of the central claim under the unilateral law, ")
    text += ("none changes from the perfectly rough plane's." if not changed else
             f"{len(changed)} change{'s' if len(changed) == 1 else ''} from the perfectly rough plane's: "
             + "; ".join(changed) + ".")
    if missing:
        text += f" ({missing} not computed in this run.)"
    moved, kept = [], 0
    for law, reading in (("unilateral", "m/s²"), ("flight", "units of g")):
        for mu in ("0.3", "0.6"):
            for body in ("I", "II"):
                a, b = ensembles.get((body, law)), ensembles.get((body, f"{law}, mu = {mu}"))
                if a is None or b is None:
                    continue
                if a == b:
                    kept += 1
                else:
                    moved.append(f"Gömböc {body}, {reading}, μ = {mu}: {a} on the rough plane, {b} on the real one")
    if kept or moved:
        text += (f" The ensembles of `make study` (16 attitudes × 1000 periods at each μ): of {kept + len(moved)} readings, "
                 + ("none changes." if not moved else f"{len(moved)} change: " + "; ".join(moved) + "."))
    return [text, ""]


def ensemble_note(where, verdict, ensembles):
    """The one-trajectory, 300-period chaos verdict of the rolling model (a finding measured `where`) against the
    ensemble of `make study`: (note, preliminary) or None. One wording, for the summary and the findings table."""
    for (body, law), reading in ensembles.items():
        base, _, mu = law.partition(", mu = ")
        model = {"unilateral": "continuous contact, rolling equation, unilateral contact",
                 "flight": "continuous rolling, unilateral contact with flight (e = 0), A in units of g",
                 "bouncing": "continuous rolling, unilateral contact with flight (e = 0.5), A in units of g"}.get(
                     base, "continuous contact, rolling equation")
        if mu:
            model += f", friction mu = {mu}"
        if where.startswith(f"Gomboc {body}, {model}: lambda_max - 4 sigma"):
            agrees = (reading == "sustained") == (verdict == "holds")
            size = ("16 initial attitudes, 1000 periods" if base in ("flight", "bouncing") or mu
                    else "32 initial attitudes, 64 for Gömböc I; 3000 periods")
            if not agrees or reading == "undecided":
                return f"**preliminary: the ensemble of `make study` ({size}) reads {reading}**", True
            return f"the ensemble of `make study` ({size}) reads {reading}", False
    return None


def readme_state(out):
    """Does the README quote this run's findings (its block between the markers, scripts/readme_findings.py)?"""
    here = os.path.dirname(os.path.abspath(__file__))
    try:
        result = subprocess.run([sys.executable, os.path.join(here, "..", "scripts", "readme_findings.py"), "--check",
                                 os.path.join(out, "findings.md")], capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return None
    return ("The README's findings quote this run's words (`scripts/readme_findings.py --check`)." if result.returncode == 0
            else "**The README's findings are not this run's words**: `scripts/readme_findings.py` copies "
                 "`reports/out/findings.md` into it.")


def undecided_reason(detail):
    """Why a central-claim cell is undecided, and which evidence decides it, in the row's own words."""
    if "model not valid here" in detail:
        return "no verdict: g_eff <= 0 for part of every period, where the model loses its contact; the rows with flight decide it"
    if "make verify-full runs 3000" in detail:
        return "300 periods leave lambda +- 4 sigma across 0.01 .. 0.05 1/s; make verify-full's 3000-period record decides it"
    if "even over 3000 periods" in detail:
        return "even 3000 periods leave lambda +- 4 sigma across 0.01 .. 0.05 1/s"
    return "its evidence did not decide it"


def findings_block(findings, ensembles):
    """The findings in the report's own words: the central claim under each model (with the ensembles' word where
    they read otherwise) and every claim with how its rows came out. The summary prints it, and make_report
    writes it to OUT/findings.md, the text the README's findings quote (scripts/readme_findings.py)."""
    lines = ["| measured on (R0 = I; 300 periods unless the row says) | Gömböc I | Gömböc II |", "|---|---|---|"]
    central, lengths = {}, {}
    for r in findings:
        if not r["claim"].startswith(CENTRAL):
            continue
        where = r["quantity"]
        body, _, model = where.partition(", ")
        model = model.replace(": lambda_max - 4 sigma", "")
        note = ensemble_note(where, r["verdict"], ensembles)
        cell = r["verdict"] + (" (" + note[0].replace("**", "") + ")" if note and note[1] else "")
        if r["verdict"] == "undecided" and not (note and note[1]):
            cell += " (" + undecided_reason(r.get("detail", "")) + ")"
        periods = re.search(r"over (\d+) periods", r.get("detail", ""))
        if periods and periods.group(1) != "300":
            lengths[model] = periods.group(1)
        central.setdefault(model, {})[body.replace("Gomboc ", "")] = cell
    for model, by_body in central.items():
        length = f" ({lengths[model]} periods)" if model in lengths else ""
        lines.append(f"| {spell(model)}{length} | {by_body.get('I', '—')} | {by_body.get('II', '—')} |")
    lines += ["", "Every claim of the paper the suite tests, with how its rows came out:", ""]
    claims = {}
    for r in findings:
        tally = claims.setdefault(r["claim"], {"holds": 0, "fails": 0, "undecided": 0})
        tally[r["verdict"]] = tally.get(r["verdict"], 0) + 1
    for claim, tally in claims.items():
        plural = {"holds": "hold", "fails": "fail", "undecided": "undecided"}
        parts = [f"{n} {v if n == 1 else plural[v]}" for v, n in tally.items() if n]
        lines.append(f"- {spell(claim)}: {', '.join(parts)}.")
    return lines, central


def summary_lines(findings, counts, rows, failed, ensembles, out):
    """The report's answer first: the verdict counts, the central claim under each model and contact law,
    and every claim of the paper with how its rows came out; all from this run's findings."""
    lines = ["## Summary", "",
             f"{len(rows)} checks recorded, **{len(rows) - len(failed)} passed, {len(failed)} failed**. "
             f"Of {len(findings)} findings about the paper, **{counts['holds']} hold, {counts['fails']} fail, "
             f"{counts['undecided']} undecided**, each decided by a rule written before the data "
             "(`verify/gb_verdict.h`); a finding's check passes when its evidence was computed, whatever its verdict.", "",
             "The paper's central claim is chaos generated by contact selection under forcing (λ_max > 0 at "
             "Table 1's baseline). It is tested under the paper's model (eq 44 on its 90 × 180 grid) and under "
             "the rolling equation with certified continuous contact, each with the paper's **held** contact "
             "(one contact, ω kept at a switch) and with the **unilateral** law (a plane that can only push: "
             "every change of contact an impact, lift-off, flight and landing) on a perfectly rough plane and on "
             "planes of Coulomb friction μ = 0.3 and 0.6, and under both readings of Table 1's amplitudes (m/s² "
             "and units of g):", "",
             ]
    block, central = findings_block(findings, ensembles)
    # the friction comparison reads the bare verdicts
    bare = {m: {b: v.split(" (")[0] for b, v in by.items()} for m, by in central.items()}
    lines += block + [""] + friction_lines(bare, ensembles) + summary_sentence(out)
    write_atomically(os.path.join(out, "findings.md"), "\n".join(block) + "\n")
    readme = readme_state(out)
    if readme:
        lines += ["", readme]
    undecided = [r for r in findings if r["verdict"] == "undecided"]
    if undecided:
        lines += ["", f"Why each of the {len(undecided)} undecided findings is undecided (its evidence, as the table below "
                  "gives it):", ""]
        lines += [spell(f"- {r['quantity']}: {r['detail']}") for r in undecided]
    return lines + [""]


def equation_keys(text):
    """The paper's equations and figures a row names: "46-51" is 46 … 51, "4, 6" is 4 and 6, "13 (2nd order)" is 13,
    "Figs 10-13" is Figs 10 … 13; "-" is none."""
    keys = []
    for part in re.split(r",|;", text):
        part = re.sub(r"\(.*?\)", "", part).strip()
        figure = re.match(r"Figs?\s+(\d+)(?:\s*-\s*(\d+))?$", part)
        numbers = re.match(r"(\d+)(?:\s*-\s*(\d+))?$", part)
        match, label = (figure, "Fig") if figure else (numbers, "eq") if numbers else (None, None)
        if not match:
            continue
        first = int(match.group(1))
        last = int(match.group(2)) if match.group(2) else first
        keys += [(label, k) for k in range(first, min(last, first + 60) + 1)]
    return keys


def equation_index(rows):
    """The report's index: each equation and figure of the paper, the checks that name it and where each is written
    (file:line, as the harness recorded it); then the records that name none, by suite."""
    index = {}
    for r in rows:
        for key in equation_keys(r["equation"]):
            index.setdefault(key, []).append(r)
    lines = ["## Checks by equation", "",
             "Each equation and figure of the paper that a check names, the number of its records, and where the checks "
             "are written (file:line; a line that records several rows is listed once).", "",
             "| equation | records | checks (file:line) |", "|---|---|---|"]
    for (label, number) in sorted(index, key=lambda k: (k[0] != "eq", k[1])):
        found = index[(label, number)]
        places = []
        for r in found:
            place = f"`{r['file']}:{r.get('line', '?')}`"
            if place not in places:
                places.append(place)
        shown = ", ".join(places[:8]) + (f", and {len(places) - 8} more" if len(places) > 8 else "")
        lines.append(f"| {label} {number} | {len(found)} | {shown} |")
    unnamed = [r for r in rows if not equation_keys(r["equation"])]
    by_suite = {}
    for r in unnamed:
        by_suite[r["suite"]] = by_suite.get(r["suite"], 0) + 1
    lines += ["", f"{len(unnamed)} of {len(rows)} records ({100 * len(unnamed) / max(len(rows), 1):.0f} %) name no equation "
              "or figure of the paper; by suite:", ""]
    lines += [f"- {suite}: {count}" for suite, count in sorted(by_suite.items(), key=lambda kv: -kv[1])] + [""]
    return lines


def main():
    out, cc, cflags = sys.argv[1], sys.argv[2], sys.argv[3]
    if not os.path.exists(os.path.join(out, "checks.json")):
        # `make scans` or `make study` before any `make verify`: their sections alone, and what is missing.
        lines = ["# gomboc — verification report", "",
                 "**No checks in this checkout: `make verify` has not run here.** This report holds only what the "
                 "gates below made; `make verify` writes the whole report.", ""]
        lines += gate_lines(out) + [""] + study_section(out) + scan_section(out) + unilateral_section(out)
        write_atomically(os.path.join(out, "verification.md"), spell("\n".join(lines)))
        return
    rows, tests = load_checks(os.path.join(out, "checks.json"))
    # the paper's two bodies: those of its Table 1 scenes (make run's shape study, one file a scene)
    shapes = [(n, load_json(os.path.join(out, f"shape-table1-gomboc-{n}.json"))) for n in ("I", "II")]
    failed = [r for r in rows if not r["passed"]]
    # the paper's claims; the comparisons of two models against Siconos are reported in their own section
    findings = [r for r in rows if r["kind"] == "finding" and r.get("suite") != SICONOS_SUITE]
    counts = {v: sum(1 for r in findings if r["verdict"] == v) for v in ("holds", "fails", "undecided")}
    error_vs_time(out, rows)

    lines = ["# gomboc — verification report", ""] + summary_lines(findings, counts, rows, failed, ensemble_readings(out), out)
    lines += ["## Environment", "", "| item | value |", "|---|---|"]
    lines += [f"| {k} | {v} |" for k, v in environment(cc, cflags, rows)]
    lines += [""] + gate_lines(out)
    lines += ["", "## What the paper claims and what we measured", "",
              "Each row names what it was measured on (body, model, reading, record length).", "",
              "Every verdict is one of holds, fails or undecided, decided by the rule in its row (written in",
              "`verify/gb_verdict.h` before the data, symmetric for the paper and against it).", "",
              f"**{counts['holds']} hold, {counts['fails']} fail, {counts['undecided']} undecided** "
              f"(of {len(findings)} findings, recomputed in this run).", "",
              "| section | paper claims | measured on | we measured | verdict | rule |", "|---|---|---|---|---|---|"]
    rule_names = {}  # each rule's text once, in the legend below the table; the table names it
    notes, convergence_lines = convergence(out)
    ensembles = ensemble_readings(out)
    for r in findings:
        claim, where, detail = (text.replace("|", "\\|") for text in (r["claim"], r["quantity"], r["detail"]))
        for (body, variation), reading in notes.items():
            if where.startswith(f"Gomboc {body}, {variation}:") and reading != "consistent":
                detail += f" — {reading} (see 'Convergence')"
        note = ensemble_note(where, r["verdict"], ensembles)
        if note:
            detail += f" — {note[0]}" + (" (see 'Chaotic for good, for a while, or not at all?')" if note[1] else "")
        rule = r["rule"].replace("|", "/")
        if rule not in rule_names:
            rule_names[rule] = f"R{len(rule_names) + 1} ({rule.split(':', 1)[0].strip()})"
        lines.append(spell(f"| §{r['section']} | {claim} | {where} | {detail} | {verdict_text(r['verdict'])} | "
                           f"{rule_names[rule]} |"))
    lines += ["", "**The rules** (each decides holds, fails or undecided from the row's evidence; written before the data "
              "in `verify/gb_verdict.h`):", ""]
    lines += [spell(f"- {name}: {rule}") for rule, name in rule_names.items()]
    # Results that are not findings, stated only as far as their checks passed in this run.
    lines += [""] + convergence_lines
    # What each test establishes when all its rows pass (recorded by the harness beside the test).
    lines += ["", "### What each test establishes", ""]
    for t in tests:
        if not t.get("establishes"):
            continue
        members = [r for r in rows if r["test"] == t["test"]]
        verdict = ("holds in this run" if members and all(r["passed"] for r in members)
                   else "**not established in this run: see the failures below**")
        lines.append(f"- {t['establishes']}: {verdict} (test '{t['test']}').")
    lines += ["",
              "## Section 2: the two Table 1 bodies", "",
              "The paper never gives the inertia tensor; we take a homogeneous body of mass m = 1 (Table 1).", ""]
    for name, shape in shapes:
        lines += [f"### Gömböc {name} (β = {shape['beta']:g})", ""] + shape_summary_lines(shape) + [""]
    lines += ["![Figure 1](fig1-morphologies.png)", ""]
    lines += contact_section(out, rows)
    lines += dynamics_section(out, rows)
    lines += chaos_section(out, rows)
    lines += melnikov_section(out, rows)
    lines += proofs_section(out)
    lines += study_section(out)
    lines += scan_section(out)
    lines += unilateral_section(out)
    lines += siconos_section(out, rows)
    lines += ["## Error against run time", "",
              "Each numeric check's relative error against its oracle, against the wall time since the",
              "previous check in the same test (the time of computing that row).", "",
              "![error against run time](error-vs-time.png)", "",
              "## Every check", "",
              "Columns: the paper's section and equation, the quantity, the oracle, measured value, error, tolerance",
              "and where the tolerance comes from, run time, result. Reproduce any row with `make verify`; the",
              "test named in its group is in the file listed with the group.", ""]
    current = None
    for r in rows:
        if r["test"] != current:
            current = r["test"]
            lines += ["", f"#### {current}", "",
                      "| § | eq | quantity | oracle | measured | error | tolerance | tolerance origin | s | result |",
                      "|---|---|---|---|---|---|---|---|---|---|"]
        if r["kind"] == "compare":
            measured, error, tol = fmt(r["measured"]), fmt(r["error"]), fmt(r["tolerance"])
        else:
            # one table cell: a command's output may run over several lines
            measured, error, tol = " ".join(r.get("detail", "").split())[:160].replace("|", "/"), "—", "—"
        result = "pass" if r["passed"] else "**FAIL**"
        if r["kind"] == "finding":
            result = ("evidence computed" if r["passed"] else "**evidence not computed**") + f", {verdict_text(r['verdict'])}"
        quantity, oracle, origin = (text.replace("|", "\\|") for text in (r["quantity"], r["oracle"], r["origin"]))
        lines.append(f"| {r['section']} | {r['equation']} | {quantity} | {oracle} | {measured} | {error} | "
                     f"{tol} | {origin} | {r['seconds']:.2g} | {result} |")
    # Each suite and the files its checks are written in, as the harness recorded them.
    where = {}
    for r in rows:
        where.setdefault(r["suite"], [])
        if r["file"] not in where[r["suite"]]:
            where[r["suite"]].append(r["file"])
    lines += ["", "## Where the checks live", ""] + \
             [f"- {suite}: " + ", ".join(f"`{f}`" for f in files) for suite, files in where.items()] + [""]
    lines += equation_index(rows)
    write_atomically(os.path.join(out, "verification.md"), spell("\n".join(lines)))


if __name__ == "__main__":
    main()
