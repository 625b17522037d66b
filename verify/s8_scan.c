/* Section 8.3: parameter scans (gomboc scan, gb_scan). A scan point must be, bit for bit, the run of the
 * same scene: here that scene is written out as its own file, independently of how the scan sets its
 * keys, run by `gomboc run`, and its summary and history compared with the scan's row. The per-sample
 * metrics are checked against closed forms; the CSV must not depend on the thread count or on an
 * interruption (a kill -9 mid-scan, a half-written journal line) followed by --resume; a journal of
 * another scan is refused. The binary comes from $GOMBOC_BIN. */
#include "gb_check.h"
#include "gb_error.h"
#include "gb_run.h"
#include "gb_scan_internal.h"
#include "gb_seal.h"
#include "s8_scan.h"
#include "verify_sections.h"

#include <cjson/cJSON.h>
#include <dirent.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

const char *s8_binary(void) { return getenv("GOMBOC_BIN") ? getenv("GOMBOC_BIN") : "build/gomboc"; }

int s8_run(const char *args, char *out, size_t cap) { return gb_check_command(s8_binary(), args, out, cap); }

int s8_spill(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f) return 1;
    const int bad = fputs(text, f) < 0;
    return fclose(f) != 0 || bad;
}

/* ---- the per-sample metrics against closed forms ------------------------------------------------ */

static void test_accumulators(void)
{
    /* ω = (A sin t, B, 0) sampled at 160 points a period over 10 periods after a transient of 2:
     * √(mean |ω|²) = √(A²/2 + B²) exactly for whole periods of uniform samples (the discrete mean of
     * sin² over a whole period is 1/2). */
    const double A = 1.3, B = 0.4, T = 2 * M_PI, h = T / 160;
    gb_scan_accumulator a = {.first_t = 2 * T - 0.5 * h};
    size_t switches = 0;
    for (int n = 0; n <= 12 * 160; n++) {
        const double t = n * h, w[3] = {A * sin(t), B, 0.0};
        if (n % 40 == 0 && n > 0) switches++; /* four contact changes a period */
        if (n < 12 * 160) gb_scan_accumulate(&a, t, w, -0.97 + 0.01 * sin(t), switches);
    }
    double rms, height, rate;
    gb_scan_accumulated(&a, &rms, &height, &rate);
    gb_check cr = {"8.3", "-", "omega_rms of omega = (A sin t, B, 0) over 10 whole periods", "sqrt(A^2/2 + B^2)",
                   "1600 eps relative: the worst-case rounding of a sum of 1600 terms"};
    gb_check_close(&cr, rms, sqrt(A * A / 2 + B * B), 1600 * DBL_EPSILON, 0.0);
    gb_check ch = {"8.3", "36", "mean h* of -0.97 + 0.01 sin t over 10 whole periods", "-0.97",
                   "1600 eps relative: the worst-case rounding of a sum of 1600 terms"};
    gb_check_close(&ch, height, -0.97, 1600 * DBL_EPSILON, 0.0);
    /* From the first counted sample (t = 2T) to the last (t = 12T − h): 4 changes a period, the first
     * at 2T + 40h; 40 counted in all but the one at 12T, which is not sampled. */
    gb_check cs = {"8.3", "-", "switch rate of a counted sequence (4 changes a period, 10 periods)", "39 / (10 T - h)",
                   "1e-14: rounding of the time span"};
    gb_check_close(&cs, rate, 39.0 / (10 * T - h), 1e-14, 0.0);
    gb_scan_accumulator empty = {.first_t = 1.0};
    gb_scan_accumulated(&empty, &rms, &height, &rate);
    gb_check ce = {"8.3", "-", "metrics of a run shorter than its transient", "NaN (no sample counted)", "exact"};
    gb_check_true(&ce, isnan(rms) && isnan(height) && isnan(rate), "%g, %g, %g", rms, height, rate);
}

/* ---- a scan against the single runs of its points ----------------------------------------------- */

/* A scene file with every key the comparison needs: both the scan's base (history off, 300 periods)
 * and, written the way a user would, each point's own scene. */
void s8_scene_text(char *out, size_t size, double omega, double a2, double periods, int transient, int history)
{
    snprintf(out, size,
             "[body]\nmorphology = I\nbeta = 0.12\n"
             "[forcing]\nomega = %.17g\nA1 = 2.0\nA2 = %.17g\npsi = pi/3\n"
             "[model]\nequation = paper\ncontact = fast-grid\n"
             "[integrator]\nperiods = %.17g\n"
             "[output]\nhistory = %s\nsummary = yes\n"
             "[diagnostics]\nmonitors = yes\nstrobe = yes\nspectrum = no\nlyapunov = yes\n"
             "[strobe]\ntransient_periods = %d\n"
             "[lyapunov]\ntransient_periods = %d\ninterval_periods = 1\n",
             omega, a2, periods, history ? "yes" : "no", transient, transient);
}

static const char scan_text[] = "[scan]\ndescription = the harness's scan\nbase = base.ini\nperiods = 12\n"
                                "transient_periods = 4\nmetrics = all\n"
                                "[x]\nkey = forcing.omega\nfrom = 16\nto = 20\ncount = 3\n"
                                "[y]\nkey = forcing.A2\nfrom = 0.5\nto = 1.5\ncount = 3\n";


/* A fresh directory with the base scene and the scan file; on failure `check` fails and 1 returns. */
int s8_make_scan_dir(s8_scan_dir *d, const gb_check *check)
{
    if (gb_check_tempdir("scan", d->path, sizeof d->path)) return 1;
    char base[8192], path[320];
    s8_scene_text(base, sizeof base, 18.0, 1.0, 300.0, 50, 0);
    snprintf(path, sizeof path, "%s/base.ini", d->path);
    snprintf(d->scan, sizeof d->scan, "%s/map.ini", d->path);
    snprintf(d->csv, sizeof d->csv, "%s/map-scan.csv", d->path);
    snprintf(d->journal, sizeof d->journal, "%s/map-scan.journal", d->path);
    if (s8_spill(path, base) || s8_spill(d->scan, scan_text)) return !gb_check_true(check, 0, "cannot write the scan files");
    return 0;
}

/* `gomboc scan` of the directory's scan file into it, with `extra` options; the exit status. */
int s8_scan_run(const s8_scan_dir *d, const char *extra, char *out, size_t cap)
{
    char args[1024];
    snprintf(args, sizeof args, "scan '%s' --out '%s' %s", d->scan, d->path, extra);
    return s8_run(args, out, cap);
}

void s8_remove_scan_dir(const s8_scan_dir *d) { gb_check_tempdir_remove(d->path); }

/* ---- the unilateral law's mechanism, per point ------------------------------------------------------ */

/* A scan of the shipped scene `base` (cases/, by absolute path), one point at (omega, A1) = (18, 2), 40
 * periods, no transient, the mechanism's columns; and the same scene run alone by gb_run. */
static void mechanism_point(const char *base, const char *what)
{
    s8_scan_dir d;
    gb_check c = {"8.3", "-", what, "the run's own summary: impacts and landings (exact), the energy impacts and friction took "
                  "(1e-9 relative: sums in another order), the time in flight and on two points (the sampled fraction within "
                  "a step of each change, over the run)", "as stated per column"};
    if (s8_make_scan_dir(&d, &c)) return;
    char cwd[512], text[1400];
    if (!getcwd(cwd, sizeof cwd)) cwd[0] = '\0';
    snprintf(text, sizeof text, "[scan]\ndescription = the mechanism's columns\nbase = %s/%s\nperiods = 40\ntransient_periods = 0\n"
             "metrics = contacts\n[x]\nkey = forcing.omega\nfrom = 18\nto = 18\ncount = 1\n[y]\nkey = forcing.A1\nfrom = 2\nto = 2\ncount = 1\n",
             cwd, base);
    gb_scan scan;
    gb_scan_metrics m;
    gb_case scene;
    gb_run_result r;
    memset(&r, 0, sizeof r);
    int status = s8_spill(d.scan, text) ? GB_EIO : gb_scan_load(d.scan, &scan);
    if (!status) status = gb_scan_point_run(&scan, 0, &m);
    if (!status) status = gb_scan_point_case(&scan, 0, &scene);
    if (!status) status = gb_run(&scene, NULL, &r);
    if (status) {
        gb_check_true(&c, 0, "%s", gb_error_message());
    } else {
        const double periods = 40.0, h = gb_forcing_step(&scene.dynamics.forcing, scene.integrate.steps_per_period);
        const double flight_changes = (double)(r.flight.lift_offs + r.flight.landings) + 1.0;
        const double crease_changes = (double)(2 * r.two_point.entries + r.two_point.lifts + r.two_point.third_points) + 1.0;
        const double lost = r.impact_energy_lost + (r.has_sliding ? r.sliding.friction_loss : 0.0);
        const double e_lost = fabs(m.energy_lost_per_period * periods - lost) / fmax(lost, 1e-300);
        const double e_flight = fabs(m.in_flight - r.flight.time / r.t_end), e_crease = fabs(m.two_point - r.two_point.time / r.t_end);
        const int ok = (size_t)llround(m.impacts_per_period * periods) == r.impacts &&
                       (size_t)llround(m.landings_per_period * periods) == r.flight.landings && e_lost <= 1e-9 &&
                       e_flight <= flight_changes * h / r.t_end && e_crease <= crease_changes * h / r.t_end &&
                       fabs(m.one_point + m.two_point + m.at_rest + m.in_flight - 1.0) <= 1e-12 && m.end_contacts == r.final.contacts;
        gb_check_true(&c, ok, "impacts %.0f / %zu, landings %.0f / %zu, energy lost %.6g J / %.6g J, in flight %.4f / %.4f, on two "
                      "points %.4f / %.4f, at the end %g / %d points", m.impacts_per_period * periods, r.impacts,
                      m.landings_per_period * periods, r.flight.landings, m.energy_lost_per_period * periods, lost, m.in_flight,
                      r.flight.time / r.t_end, m.two_point, r.two_point.time / r.t_end, m.end_contacts, r.final.contacts);
    }
    if (!status || scan.base_text) gb_scan_free(&scan);
    gb_run_result_free(&r);
    gb_error_clear();
    s8_remove_scan_dir(&d);
}

static void test_mechanism(void)
{
    mechanism_point("cases/table1-gomboc-II-unilateral.ini",
                    "a scan point's mechanism columns, Table 1 Gomboc II, unilateral contact, 40 periods (A in m/s^2: on the crease from period 21)");
    mechanism_point("cases/table1-gomboc-I-g-units-bouncing.ini",
                    "a scan point's mechanism columns, Table 1 Gomboc I in units of g, flight, e = 0.5");
    /* under the held law the columns are NaN, and the scan's JSON says why */
    s8_scan_dir d;
    gb_check c = {"8.3", "-", "the mechanism's columns of a scan under the held law", "NaN, and the JSON's not_applicable names why",
                  "exact"};
    if (s8_make_scan_dir(&d, &c)) return;
    static const char text[] = "[scan]\ndescription = held\nbase = base.ini\nperiods = 2\ntransient_periods = 0\n"
                               "metrics = omega_rms, contacts\n[x]\nkey = forcing.omega\nfrom = 18\nto = 18\ncount = 1\n"
                               "[y]\nkey = forcing.A2\nfrom = 1\nto = 1\ncount = 1\n";
    char out[4096], json_path[200];
    const int status = s8_spill(d.scan, text) ? -1 : s8_scan_run(&d, "", out, sizeof out);
    snprintf(json_path, sizeof json_path, "%s/map-scan.json", d.path);
    char *json = gb_check_read_file(json_path), *csv = gb_check_read_file(d.csv);
    cJSON *root = json ? cJSON_Parse(json) : NULL;
    const cJSON *why = cJSON_GetObjectItem(cJSON_GetObjectItem(root, "not_applicable"), "contacts");
    gb_check_true(&c, status == 0 && cJSON_IsString(why) && csv && strstr(csv, ",nan,nan,nan,nan,nan,nan,nan,nan,nan,"),
                  "exit %d; %s", status, cJSON_IsString(why) ? why->valuestring : "no reason in the JSON");
    cJSON_Delete(root);
    free(json), free(csv);
    s8_remove_scan_dir(&d);
}


/* The metrics of a history CSV (gomboc run) after the transient, recomputed here. */
static int history_metrics(const char *path, double first_t, double *rms, double *height, double *rate)
{
    FILE *f = fopen(path, "r");
    if (!f) return 1;
    char line[2048];
    double sum2 = 0, hsum = 0, t0 = NAN, t1 = NAN;
    size_t n = 0, switches = 0;
    if (!fgets(line, sizeof line, f)) return fclose(f), 1;
    while (fgets(line, sizeof line, f)) {
        double v[17];
        char *p = line, *end;
        int k = 0;
        for (; k < 17; k++, p = end + 1) {
            v[k] = strtod(p, &end);
            if (end == p || (*end != ',' && *end != '\n')) break;
        }
        if (k != 17) return fclose(f), 1;
        if (v[0] < first_t) continue;
        if (n) switches += (size_t)(v[9] + v[10]); /* grid_switch, branch_switch */
        if (!n) t0 = v[0];
        t1 = v[0];
        n++;
        sum2 += v[1] * v[1] + v[2] * v[2] + v[3] * v[3];
        hsum += v[4];
    }
    fclose(f);
    *rms = sqrt(sum2 / (double)n), *height = hsum / (double)n, *rate = (double)switches / (t1 - t0);
    return n == 0;
}

double s8_number_at(const cJSON *o, const char *a, const char *b)
{
    const cJSON *x = cJSON_GetObjectItem(o, a);
    if (b) x = cJSON_GetObjectItem(x, b);
    return cJSON_IsNumber(x) ? x->valuedouble : NAN;
}

static void test_point_is_the_run(void)
{
    s8_scan_dir d;
    char out[1 << 14], args[1024];
    gb_check cs = {"8.3", "-", "gomboc scan of 3 x 3 points (omega, A2), 12 periods, fast grid, every metric", "-", "exact: exit 0"};
    if (s8_make_scan_dir(&d, &cs)) return;
    const int code = s8_scan_run(&d, "", out, sizeof out);
    char *csv = gb_check_read_file(d.csv);
    gb_check_true(&cs, code == 0 && csv != NULL, "exit %d: %.300s", code, out);
    gb_check ch = {"8.3", "-", "that scan's CSV header", "index, the axes by their keys, then the metrics", "exact"};
    const char *header_start = "index,forcing.omega,forcing.A2,omega_rms,";
    gb_check_true(&ch, csv && !strncmp(csv, header_start, strlen(header_start)), "%.80s", csv ? csv : "(no CSV)");
    /* the scan plotter of the README, on that CSV */
    char plot_args[600], png[200], plot_out[4096];
    snprintf(png, sizeof png, "%s/map-lambda.png", d.path);
    snprintf(plot_args, sizeof plot_args, "reports/plot_scan.py '%s' lambda_max omega_rms --out '%s'", d.csv, png);
    const int plotted = gb_check_command("/usr/bin/python3", plot_args, plot_out, sizeof plot_out);
    struct stat png_stat;
    gb_check cp = {"8.3", "-", "reports/plot_scan.py on that scan (two metrics over the axes named by their keys)",
                   "exit 0 and a PNG written", "exact"};
    gb_check_true(&cp, plotted == 0 && stat(png, &png_stat) == 0 && png_stat.st_size > 1000, "exit %d: %.200s", plotted, plot_out);
    int rows = 0, same_fingerprint = 0, same_diagnostics = 0, same_margin = 0;
    double worst = 0.0, worst_threshold = 0.0;
    for (const char *line = csv ? strchr(csv, '\n') : NULL; line && line[1]; line = strchr(line + 1, '\n')) {
        size_t index;
        gb_scan_metrics m;
        if (gb_scan_csv_parse(line + 1, &index, &m)) break;
        rows++;
        /* The point's scene as a user would write it, run alone with its history. */
        char text[8192], scene[200], summary[220], history[220];
        const int transient = 4;
        s8_scene_text(text, sizeof text, m.x, m.y, 12.0, transient, 1);
        snprintf(scene, sizeof scene, "%s/point.ini", d.path);
        snprintf(summary, sizeof summary, "%s/point-summary.json", d.path);
        snprintf(history, sizeof history, "%s/point-history.csv", d.path);
        if (s8_spill(scene, text)) break;
        snprintf(args, sizeof args, "run '%s' --out '%s'", scene, d.path);
        if (s8_run(args, out, sizeof out) != 0) break;
        char *json = gb_check_read_file(summary);
        cJSON *root = json ? cJSON_Parse(json) : NULL;
        free(json);
        char fp[40], sw[40];
        snprintf(fp, sizeof fp, "%016llx", (unsigned long long)m.state_fingerprint);
        snprintf(sw, sizeof sw, "%016llx", (unsigned long long)m.switch_fingerprint);
        const cJSON *f = cJSON_GetObjectItem(root, "fingerprint");
        same_fingerprint += f && !strcmp(cJSON_GetStringValue(cJSON_GetObjectItem(f, "final_state")), fp) &&
                            !strcmp(cJSON_GetStringValue(cJSON_GetObjectItem(f, "switches")), sw);
        const cJSON *sd = cJSON_GetObjectItem(cJSON_GetObjectItem(root, "strobe"), "sd");
        same_diagnostics += s8_number_at(root, "lyapunov", "lambda_max") == m.lambda &&
                            s8_number_at(root, "lyapunov", "error_bar") == m.lambda_error &&
                            cJSON_GetArrayItem(sd, 0) && cJSON_GetArrayItem(sd, 0)->valuedouble == m.strobe_sd &&
                            s8_number_at(root, "monitors", "geff_nonpositive_fraction") == m.geff_nonpositive &&
                            s8_number_at(root, "monitors", "lift_off_fraction") == m.lift_off;
        cJSON_Delete(root);
        /* The margins against `gomboc melnikov` of the same scene file: its largest oscillatory part and
         * its ν₁A₁* + ν₂A₂* over its μD, and its exact threshold A1 times the margin is the point's A1. */
        snprintf(args, sizeof args, "melnikov '%s' --json", scene);
        char *reduced = s8_run(args, out, sizeof out) == 0 ? out : NULL;
        cJSON *mj = reduced ? cJSON_Parse(reduced) : NULL;
        const double muD = s8_number_at(mj, "mu_D", NULL), osc = s8_number_at(mj, "oscillatory_max", NULL),
                     bound = s8_number_at(mj, "nu1_A1_plus_nu2_A2", NULL), threshold = s8_number_at(mj, "threshold_A1", "exact");
        same_margin += osc / muD == m.melnikov_margin && bound / muD == m.melnikov_margin_eq93;
        worst_threshold = fmax(worst_threshold, fabs(m.melnikov_margin * threshold / 2.0 - 1.0)); /* A1 = 2 */
        cJSON_Delete(mj);
        const double T = 2 * M_PI / m.x, h = T / 160;
        double rms, height, rate;
        if (history_metrics(history, transient * T - 0.5 * h, &rms, &height, &rate)) break;
        worst = fmax(worst, fmax(fabs(rms - m.omega_rms) / fabs(m.omega_rms),
                                 fmax(fabs(height - m.mean_height) / fabs(m.mean_height),
                                      fabs(rate - m.switch_rate) / fmax(fabs(m.switch_rate), 1e-300))));
    }
    free(csv);
    gb_check cf = {"8.3", "-", "scan points whose fingerprints equal the single run of the point's scene (gomboc run)",
                   "9 of 9: the point's scene written out by hand and run alone", "exact"};
    gb_check_true(&cf, rows == SCAN_POINTS && same_fingerprint == SCAN_POINTS, "%d rows, %d equal fingerprints", rows, same_fingerprint);
    gb_check cl = {"8.3", "77", "scan points whose lambda, error bar, strobe spread and monitors equal the single run's",
                   "the single runs' summaries", "exact (bit for bit)"};
    gb_check_true(&cl, rows == SCAN_POINTS && same_diagnostics == SCAN_POINTS, "%d rows, %d equal", rows, same_diagnostics);
    gb_check cm = {"8.3", "-", "omega_rms, mean h* and switch rate of each point against the single run's history, recomputed",
                   "the history CSV of gomboc run, after the transient",
                   "1e-9 relative: the history prints t with 10 significant digits (t <= 4.8 s over spans >= 2.8 s), "
                   "omega with 12"};
    gb_check_close(&cm, rows == SCAN_POINTS ? worst : NAN, 0.0, 0.0, 1e-9);
    gb_check cg = {"8.3", "91-93", "scan points whose Melnikov margins equal gomboc melnikov's for the point's scene",
                   "oscillatory_max / mu_D and (nu1 A1* + nu2 A2*) / mu_D of gomboc melnikov --json", "exact (bit for bit)"};
    gb_check_true(&cg, rows == SCAN_POINTS && same_margin == SCAN_POINTS, "%d rows, %d equal", rows, same_margin);
    gb_check ct = {"8.3", "93", "margin x gomboc melnikov's exact threshold A1 (A2/A1 held), over the point's A1 = 2, minus 1",
                   "0: the margin is the forcing over its threshold",
                   "1e-15: three roundings (the threshold's quotient, the margin's, their product)"};
    gb_check_close(&ct, rows == SCAN_POINTS ? worst_threshold : NAN, 0.0, 0.0, 1e-15);
    s8_remove_scan_dir(&d);
}

/* ---- the Melnikov margin ------------------------------------------------------------------------ */

static const char margin_scan_text[] = "[scan]\ndescription = margins alone\nbase = base.ini\nperiods = 12\n"
                                       "transient_periods = 4\nmetrics = melnikov\n"
                                       "[x]\nkey = forcing.A1\nfrom = 1\nto = 2\ncount = 2\n"
                                       "[y]\nkey = forcing.A2\nfrom = 0.5\nto = 1\ncount = 2\n";

/* The margins of a scan of (A1, A2) with the margins alone: 1 and 2 threads give the same bytes and run
 * no dynamics; the margin is linear in the forcing's scale and inverse in the damping, exactly (a factor
 * of 2 is exact in binary, and the maximisation over t0 sees the same comparisons); eq 93 bounds the
 * exact condition from above; a point computed alone equals the scan's planned one; the sphere, with no
 * top to rock over, has no margin. */
static void test_melnikov_margins(void)
{
    s8_scan_dir d;
    char out[1 << 14];
    gb_check ct = {"8.3", "91-93", "margins-only scan of 2 x 2 points (A1, A2) on 1 and on 2 threads",
                   "byte for byte, and no dynamics run (fingerprints 0, run metrics NaN)", "exact"};
    if (s8_make_scan_dir(&d, &ct)) return;
    if (s8_spill(d.scan, margin_scan_text)) {
        gb_check_true(&ct, 0, "cannot write the scan file");
        s8_remove_scan_dir(&d);
        return;
    }
    const int c1 = s8_scan_run(&d, "--threads 1", out, sizeof out);
    char *one = gb_check_read_file(d.csv);
    const int c2 = s8_scan_run(&d, "--threads 2", out, sizeof out);
    char *two = gb_check_read_file(d.csv);
    gb_scan_metrics m[4];
    int rows = 0, idle = 0;
    for (const char *line = one ? strchr(one, '\n') : NULL; line && line[1] && rows < 4; line = strchr(line + 1, '\n')) {
        size_t index;
        if (gb_scan_csv_parse(line + 1, &index, &m[rows]) || index != (size_t)rows) break;
        idle += m[rows].state_fingerprint == 0 && isnan(m[rows].omega_rms) && isnan(m[rows].lambda);
        rows++;
    }
    gb_check_true(&ct, c1 == 0 && c2 == 0 && one && two && !strcmp(one, two) && rows == 4 && idle == 4,
                  "exits %d, %d; %s; %d rows, %d without dynamics", c1, c2, one && two && !strcmp(one, two) ? "identical" : "different",
                  rows, idle);
    free(one);
    free(two);
    if (rows != 4) {
        s8_remove_scan_dir(&d);
        return;
    }
    /* Points 0 = (1, 0.5) and 3 = (2, 1). The eq 93 margin is a sum of the two amplitudes' terms over μD:
     * doubling both is exact in binary. The exact margin's maximum over t0 is of M(t0) + μD (eq 91 with
     * its damping term added back): one rounding of μD, μD / osc = 1 / margin relative to the result. */
    const double round_trip = 4 * DBL_EPSILON * (1.0 + 1.0 / m[0].melnikov_margin);
    gb_check cl = {"8.3", "93", "eq 93 margin at (A1, A2) = (2, 1) over that at (1, 0.5)", "2",
                   "exact: doubling is exact in binary"};
    gb_check_true(&cl, m[3].melnikov_margin_eq93 == 2.0 * m[0].melnikov_margin_eq93, "%.17g / %.17g", m[3].melnikov_margin_eq93,
                  m[0].melnikov_margin_eq93);
    gb_check cx = {"8.3", "91", "exact margin at (A1, A2) = (2, 1) over that at (1, 0.5)", "2",
                   "4 eps (1 + 1/margin) relative: the maximum is of M(t0) + mu D, a rounding of mu D"};
    gb_check_close(&cx, m[3].melnikov_margin / m[0].melnikov_margin, 2.0, round_trip, 0.0);
    int bounded = 0;
    for (int k = 0; k < 4; k++) bounded += m[k].melnikov_margin <= m[k].melnikov_margin_eq93 && m[k].melnikov_margin > 0.0;
    gb_check cb = {"8.3", "93", "points whose exact margin is positive and at most the eq 93 margin",
                   "4 of 4: eq 93 bounds the oscillatory maximum from above", "exact"};
    gb_check_true(&cb, bounded == 4, "%d of 4", bounded);

    gb_scan scan;
    gb_case scene;
    gb_scan_metrics alone;
    double halved[2] = {NAN, NAN}, sphere[2] = {0.0, 0.0}, negative[2] = {NAN, NAN};
    int status = gb_scan_load(d.scan, &scan), status_sphere = -1, status_flipped = -1;
    if (!status) {
        status = gb_scan_point_run(&scan, 3, &alone);
        if (!status) status = gb_scan_point_case(&scan, 3, &scene);
        gb_scan_free(&scan);
    }
    gb_check ca = {"8.3", "91-93", "point (2, 1) computed alone (no plan) against the scan's planned point", "the scan's CSV row",
                   "exact (bit for bit)"};
    gb_check_true(&ca, !status && alone.melnikov_margin == m[3].melnikov_margin &&
                  alone.melnikov_margin_eq93 == m[3].melnikov_margin_eq93,
                  "%s: %.17g, %.17g", status ? gb_error_message() : "ran", alone.melnikov_margin, alone.melnikov_margin_eq93);
    if (!status) {
        scene.dynamics.damping *= 2.0;
        status = gb_scan_melnikov_margins(&scene, &halved[0], &halved[1]);
        gb_case flipped = scene;
        flipped.dynamics.damping = scene.dynamics.damping / 2.0;
        flipped.dynamics.forcing.a1 = -scene.dynamics.forcing.a1, flipped.dynamics.forcing.a2 = -scene.dynamics.forcing.a2;
        status_flipped = gb_scan_melnikov_margins(&flipped, &negative[0], &negative[1]);
        gb_surface_init(&scene.body, scene.body.morphology->name, 0.0);
        status_sphere = gb_scan_melnikov_margins(&scene, &sphere[0], &sphere[1]);
    }
    gb_check ch = {"8.3", "93", "eq 93 margin of point (2, 1) with the damping c doubled", "half the scan's",
                   "exact: mu = c / M(q_u) and mu D double exactly"};
    gb_check_true(&ch, !status && 2.0 * halved[1] == m[3].melnikov_margin_eq93, "%.17g", halved[1]);
    gb_check cd = {"8.3", "91", "exact margin of point (2, 1) with the damping c doubled, times 2, over the scan's", "1",
                   "4 eps (1 + 1/margin) relative: the maximum is of M(t0) + mu D, a rounding of mu D"};
    gb_check_close(&cd, status ? NAN : 2.0 * halved[0] / m[3].melnikov_margin, 1.0, round_trip, 0.0);
    gb_check cn = {"8.3", "93", "margins of point (2, 1) with both amplitudes negated (-2, -1)",
                   "eq 93's the scan's (|nu| bounds a harmonic of either sign), the exact one positive and at most it",
                   "exact"};
    gb_check_true(&cn, status_flipped == 0 && negative[1] == m[3].melnikov_margin_eq93 && negative[0] > 0.0 &&
                  negative[0] <= negative[1], "%.17g, %.17g", negative[0], negative[1]);
    gb_check cs = {"8.3", "7", "margins of the sphere (beta = 0): no top to rock over", "NaN, and no failure", "exact"};
    gb_check_true(&cs, status_sphere == 0 && isnan(sphere[0]) && isnan(sphere[1]), "status %d: %g, %g", status_sphere, sphere[0],
                  sphere[1]);
    s8_remove_scan_dir(&d);
}

/* The maps of Figs 10–13 (cases/scans): each reads, every point's scene is valid, and Table 1's point
 * (ω = 18, A1 = 2, A2 = 1, ψ = π/3, the base scene's values) is a node of the grid. */
static void test_shipped_scans(void)
{
    static const char *const names[] = {"fig10-gomboc-I-omega-A1", "fig11-gomboc-I-A2-psi", "fig12-gomboc-II-omega-A1",
                                        "fig13-gomboc-II-A2-psi"};
    /* the held maps (paper, rolling), and under a plane that can only push: the rolling model in m/s2 and in
     * units of g with flight, the grid polyhedron for the (omega, A1) maps; these on the held rolling map's
     * nodes (checked below), so that the maps compare point by point */
    static const char *const models[] = {"paper", "rolling", "unilateral", "g-units-bouncing", "grid-unilateral"};
    for (int f = 0; f < 4; f++)
        for (int m = 0; m < 5; m++) {
            if (m == 4 && (f == 1 || f == 3)) continue; /* the grid polyhedron: Figs 10 and 12 */
            char path[256], q[320];
            snprintf(path, sizeof path, "cases/scans/%s-%s.ini", names[f], models[m]);
            snprintf(q, sizeof q, "%s: every point's scene reads, and Table 1's point is a node", path);
            gb_check c = {"8.3", "Figs 10-13", q, "Table 1: omega 18, A1 2, A2 1, psi pi/3", "exact: a node within 1e-12"};
            gb_scan scan;
            if (gb_scan_load(path, &scan)) {
                gb_check_true(&c, 0, "%s", gb_error_message());
                continue;
            }
            gb_case base;
            int found = -1;
            const int status = gb_case_load(scan.base, &base);
            const double table1[4] = {base.dynamics.forcing.omega, base.A1, base.A2, base.dynamics.forcing.psi};
            for (size_t k = 0; !status && k < gb_scan_points(&scan) && found < 0; k++) {
                gb_case point;
                if (gb_scan_point_case(&scan, k, &point)) break;
                const double here[4] = {point.dynamics.forcing.omega, point.A1, point.A2, point.dynamics.forcing.psi};
                int same = 1;
                for (int i = 0; i < 4; i++) same = same && fabs(here[i] - table1[i]) <= 1e-12 * fmax(1.0, fabs(table1[i]));
                if (same) found = (int)k;
            }
            gb_check_true(&c, !status && found >= 0 && base.dynamics.forcing.omega == 18.0 && base.A1 == 2.0 && base.A2 == 1.0,
                          "%zu points; Table 1's point %s%d", gb_scan_points(&scan), found >= 0 ? "is node " : "is missing ",
                          found);
            if (m >= 2) {
                char held_path[256];
                snprintf(held_path, sizeof held_path, "cases/scans/%s-rolling.ini", names[f]);
                gb_scan held;
                size_t same = 0;
                const int loaded = gb_scan_load(held_path, &held);
                for (size_t k = 0; !loaded && k < gb_scan_points(&scan) && gb_scan_points(&held) == gb_scan_points(&scan); k++) {
                    double x, y, hx, hy;
                    gb_scan_coordinates(&scan, k, &x, &y), gb_scan_coordinates(&held, k, &hx, &hy);
                    same += x == hx && y == hy && !strcmp(scan.axis[0].key, held.axis[0].key) && !strcmp(scan.axis[1].key, held.axis[1].key);
                }
                snprintf(q, sizeof q, "%s: its nodes are the held rolling map's", path);
                gb_check cn = {"8.3", "Figs 10-13", q, held_path, "exact: every point, the same keys and coordinates"};
                gb_check_true(&cn, !loaded && same == gb_scan_points(&scan), "%zu of %zu nodes", same, gb_scan_points(&scan));
                if (!loaded) gb_scan_free(&held);
            }
            gb_scan_free(&scan);
        }
}

int verify_register_s8_scan(void)
{
    static const verify_test tests[] = {
        {"section 8.3: scan metrics against closed forms", test_accumulators, NULL},
        {"section 8.3: the unilateral law's mechanism per point (time on one and two points, flight, impacts, energy lost)",
         test_mechanism, NULL},
        {"section 8.3: a scan point is the single run of its scene", test_point_is_the_run,
         "every scan point is, bit for bit, the run of the scene it stands for"},
        {"sections 7, 8.3: the Melnikov margin of a scan point", test_melnikov_margins,
         "a point's Melnikov margins are those of gomboc melnikov, exact under scaling, with or without a plan"},
        {"Figs 10-13: the shipped maps read, and hold Table 1's point", test_shipped_scans, NULL},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Section 8.3: parameter scans", tests);
}
