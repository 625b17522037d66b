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

static const char *binary(void) { return getenv("GOMBOC_BIN") ? getenv("GOMBOC_BIN") : "build/gomboc"; }

static int run(const char *args, char *out, size_t cap) { return gb_check_command(binary(), args, out, cap); }

static int spill(const char *path, const char *text)
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
static void scene_text(char *out, size_t size, double omega, double a2, double periods, int transient, int history)
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
enum { SCAN_POINTS = 9 };

typedef struct scan_dir {
    char path[64], scan[128], csv[160], journal[160];
} scan_dir;

/* A fresh directory with the base scene and the scan file; on failure `check` fails and 1 returns. */
static int make_scan_dir(scan_dir *d, const gb_check *check)
{
    snprintf(d->path, sizeof d->path, "/tmp/gomboc-scan-XXXXXX");
    if (!mkdtemp(d->path)) return !gb_check_true(check, 0, "cannot make a directory: %s", strerror(errno));
    char base[8192], path[160];
    scene_text(base, sizeof base, 18.0, 1.0, 300.0, 50, 0);
    snprintf(path, sizeof path, "%s/base.ini", d->path);
    snprintf(d->scan, sizeof d->scan, "%s/map.ini", d->path);
    snprintf(d->csv, sizeof d->csv, "%s/map-scan.csv", d->path);
    snprintf(d->journal, sizeof d->journal, "%s/map-scan.journal", d->path);
    if (spill(path, base) || spill(d->scan, scan_text)) return !gb_check_true(check, 0, "cannot write the scan files");
    return 0;
}

/* `gomboc scan` of the directory's scan file into it, with `extra` options; the exit status. */
static int scan_run(const scan_dir *d, const char *extra, char *out, size_t cap)
{
    char args[1024];
    snprintf(args, sizeof args, "scan '%s' --out '%s' %s", d->scan, d->path, extra);
    return run(args, out, cap);
}

static void remove_scan_dir(const scan_dir *d)
{
    char command[256];
    snprintf(command, sizeof command, "rm -rf '%s'", d->path);
    if (system(command) != 0) fprintf(stderr, "verify: cannot remove %s\n", d->path);
}

/* ---- the unilateral law's mechanism, per point ------------------------------------------------------ */

/* A scan of the shipped scene `base` (cases/, by absolute path), one point at (omega, A1) = (18, 2), 40
 * periods, no transient, the mechanism's columns; and the same scene run alone by gb_run. */
static void mechanism_point(const char *base, const char *what)
{
    scan_dir d;
    gb_check c = {"8.3", "-", what, "the run's own summary: impacts and landings (exact), the energy impacts and friction took "
                  "(1e-9 relative: sums in another order), the time in flight and on two points (the sampled fraction within "
                  "a step of each change, over the run)", "as stated per column"};
    if (make_scan_dir(&d, &c)) return;
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
    int status = spill(d.scan, text) ? GB_EIO : gb_scan_load(d.scan, &scan);
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
    remove_scan_dir(&d);
}

static void test_mechanism(void)
{
    mechanism_point("cases/table1-gomboc-II-unilateral.ini",
                    "a scan point's mechanism columns, Table 1 Gomboc II, unilateral contact, 40 periods (A in m/s^2: on the crease from period 21)");
    mechanism_point("cases/table1-gomboc-I-g-units-bouncing.ini",
                    "a scan point's mechanism columns, Table 1 Gomboc I in units of g, flight, e = 0.5");
    /* under the held law the columns are NaN, and the scan's JSON says why */
    scan_dir d;
    gb_check c = {"8.3", "-", "the mechanism's columns of a scan under the held law", "NaN, and the JSON's not_applicable names why",
                  "exact"};
    if (make_scan_dir(&d, &c)) return;
    static const char text[] = "[scan]\ndescription = held\nbase = base.ini\nperiods = 2\ntransient_periods = 0\n"
                               "metrics = omega_rms, contacts\n[x]\nkey = forcing.omega\nfrom = 18\nto = 18\ncount = 1\n"
                               "[y]\nkey = forcing.A2\nfrom = 1\nto = 1\ncount = 1\n";
    char out[4096], json_path[200];
    const int status = spill(d.scan, text) ? -1 : scan_run(&d, "", out, sizeof out);
    snprintf(json_path, sizeof json_path, "%s/map-scan.json", d.path);
    char *json = gb_check_read_file(json_path), *csv = gb_check_read_file(d.csv);
    cJSON *root = json ? cJSON_Parse(json) : NULL;
    const cJSON *why = cJSON_GetObjectItem(cJSON_GetObjectItem(root, "not_applicable"), "contacts");
    gb_check_true(&c, status == 0 && cJSON_IsString(why) && csv && strstr(csv, ",nan,nan,nan,nan,nan,nan,nan,nan,nan,"),
                  "exit %d; %s", status, cJSON_IsString(why) ? why->valuestring : "no reason in the JSON");
    cJSON_Delete(root);
    free(json), free(csv);
    remove_scan_dir(&d);
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

static double number_at(const cJSON *o, const char *a, const char *b)
{
    const cJSON *x = cJSON_GetObjectItem(o, a);
    if (b) x = cJSON_GetObjectItem(x, b);
    return cJSON_IsNumber(x) ? x->valuedouble : NAN;
}

static void test_point_is_the_run(void)
{
    scan_dir d;
    char out[1 << 14], args[1024];
    gb_check cs = {"8.3", "-", "gomboc scan of 3 x 3 points (omega, A2), 12 periods, fast grid, every metric", "-", "exact: exit 0"};
    if (make_scan_dir(&d, &cs)) return;
    const int code = scan_run(&d, "", out, sizeof out);
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
        scene_text(text, sizeof text, m.x, m.y, 12.0, transient, 1);
        snprintf(scene, sizeof scene, "%s/point.ini", d.path);
        snprintf(summary, sizeof summary, "%s/point-summary.json", d.path);
        snprintf(history, sizeof history, "%s/point-history.csv", d.path);
        if (spill(scene, text)) break;
        snprintf(args, sizeof args, "run '%s' --out '%s'", scene, d.path);
        if (run(args, out, sizeof out) != 0) break;
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
        same_diagnostics += number_at(root, "lyapunov", "lambda_max") == m.lambda &&
                            number_at(root, "lyapunov", "error_bar") == m.lambda_error &&
                            cJSON_GetArrayItem(sd, 0) && cJSON_GetArrayItem(sd, 0)->valuedouble == m.strobe_sd &&
                            number_at(root, "monitors", "geff_nonpositive_fraction") == m.geff_nonpositive &&
                            number_at(root, "monitors", "lift_off_fraction") == m.lift_off;
        cJSON_Delete(root);
        /* The margins against `gomboc melnikov` of the same scene file: its largest oscillatory part and
         * its ν₁A₁* + ν₂A₂* over its μD, and its exact threshold A1 times the margin is the point's A1. */
        snprintf(args, sizeof args, "melnikov '%s' --json", scene);
        char *reduced = run(args, out, sizeof out) == 0 ? out : NULL;
        cJSON *mj = reduced ? cJSON_Parse(reduced) : NULL;
        const double muD = number_at(mj, "mu_D", NULL), osc = number_at(mj, "oscillatory_max", NULL),
                     bound = number_at(mj, "nu1_A1_plus_nu2_A2", NULL), threshold = number_at(mj, "threshold_A1", "exact");
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
    remove_scan_dir(&d);
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
    scan_dir d;
    char out[1 << 14];
    gb_check ct = {"8.3", "91-93", "margins-only scan of 2 x 2 points (A1, A2) on 1 and on 2 threads",
                   "byte for byte, and no dynamics run (fingerprints 0, run metrics NaN)", "exact"};
    if (make_scan_dir(&d, &ct)) return;
    if (spill(d.scan, margin_scan_text)) {
        gb_check_true(&ct, 0, "cannot write the scan file");
        remove_scan_dir(&d);
        return;
    }
    const int c1 = scan_run(&d, "--threads 1", out, sizeof out);
    char *one = gb_check_read_file(d.csv);
    const int c2 = scan_run(&d, "--threads 2", out, sizeof out);
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
        remove_scan_dir(&d);
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
    remove_scan_dir(&d);
}

/* ---- the library's runner ------------------------------------------------------------------------ */

enum { RUNNER_POINTS = 6 };

/* What a runner's callbacks saw: each point's row and how often it came, the progress reports. */
typedef struct runner_seen {
    char row[RUNNER_POINTS][1024];
    int calls[RUNNER_POINTS];
    size_t finished, progress_calls, progress_bad, last_done, stop_after;
    int points_started, points_ended;
} runner_seen;

static int seen_finished(void *user, size_t index, const gb_scan_metrics *metrics, const char *row)
{
    (void)metrics;
    runner_seen *seen = user;
    if (index < RUNNER_POINTS) snprintf(seen->row[index], sizeof seen->row[index], "%s", row), seen->calls[index]++;
    if (++seen->finished == seen->stop_after) return gb_error_set(GB_EIO, "the caller stops the scan here");
    return GB_OK;
}

static void seen_progress(void *user, const gb_scan_progress *p)
{
    runner_seen *seen = user;
    seen->progress_calls++;
    if (p->phase != GB_SCAN_PHASE_POINTS || p->done > p->total || (p->done && p->done < seen->last_done)) seen->progress_bad++;
    if (!p->done) seen->points_started++;
    if (p->done == p->total) seen->points_ended++;
    seen->last_done = p->done;
}

static int runner_run(const gb_scan *scan, unsigned threads, size_t rank, size_t ranks, const unsigned char *done,
                      runner_seen *seen, size_t *points_run)
{
    const gb_scan_runner runner = {.threads = threads, .rank = rank, .ranks = ranks, .done = done,
                                   .finished = seen_finished, .progress = seen_progress, .user = seen};
    return gb_scan_run(scan, &runner, points_run);
}

/* gb_scan_run, the library's runner, against each point run alone (gb_scan_point_run, then its CSV row): on
 * 1 and 2 threads, as rank 0 and rank 1 of 2 (which share the points, each once), with points already
 * done left out, stopped by its caller, and refusing a runner out of range. */
static void test_library_runner(void)
{
    scan_dir d;
    gb_check c = {"8.3", "-", "gb_scan_run on 1 and 2 threads: 3 x 2 points (omega, A2), 4 periods, every row",
                  "each point run alone (gb_scan_point_run), its CSV row", "exact (byte for byte), each point once"};
    if (make_scan_dir(&d, &c)) return;
    static const char text[] = "[scan]\ndescription = the runner's scan\nbase = base.ini\nperiods = 4\n"
                               "transient_periods = 1\nmetrics = omega_rms, switch_rate, strobe_sd\n"
                               "[x]\nkey = forcing.omega\nfrom = 16\nto = 20\ncount = 3\n"
                               "[y]\nkey = forcing.A2\nfrom = 0.5\nto = 1.5\ncount = 2\n";
    gb_scan scan;
    if (spill(d.scan, text) || gb_scan_load(d.scan, &scan)) {
        gb_check_true(&c, 0, "cannot load the scan: %s", gb_error_message());
        remove_scan_dir(&d);
        return;
    }
    char alone[RUNNER_POINTS][1024];
    int status = gb_scan_points(&scan) == RUNNER_POINTS ? GB_OK : GB_EINVAL;
    for (size_t k = 0; k < RUNNER_POINTS && !status; k++) {
        gb_scan_metrics m;
        status = gb_scan_point_run(&scan, k, &m);
        if (!status) status = gb_scan_csv_row(&m, k, alone[k], sizeof alone[k]);
    }
    static runner_seen one, two, rank0, rank1, partial, stopped;
    size_t run_one = 0, run_two = 0, run0 = 0, run1 = 0, run_partial = 0, run_stopped = 0;
    const int s1 = status ? status : runner_run(&scan, 1, 0, 1, NULL, &one, &run_one);
    const int s2 = status ? status : runner_run(&scan, 2, 0, 1, NULL, &two, &run_two);
    int same = 0, once = 0;
    for (int k = 0; k < RUNNER_POINTS; k++) {
        same += !strcmp(one.row[k], alone[k]) && !strcmp(two.row[k], alone[k]);
        once += one.calls[k] == 1 && two.calls[k] == 1;
    }
    gb_check_true(&c, !status && !s1 && !s2 && same == RUNNER_POINTS && once == RUNNER_POINTS && run_one == RUNNER_POINTS &&
                  run_two == RUNNER_POINTS, "%s; statuses %d, %d; %d of %d rows the same, %d each once; %zu and %zu run",
                  status ? gb_error_message() : "alone ran", s1, s2, same, RUNNER_POINTS, once, run_one, run_two);
    gb_check cp = {"8.3", "-", "gb_scan_run's progress reports (points phase)",
                   "one at the start (done 0), one at the end (done = total), done never decreasing", "exact"};
    gb_check_true(&cp, one.progress_bad == 0 && one.points_started == 1 && one.points_ended == 1 && one.last_done == RUNNER_POINTS &&
                  two.progress_bad == 0 && two.points_started == 1 && two.points_ended == 1,
                  "%zu and %zu reports, %zu and %zu out of order, starts %d, %d, ends %d, %d", one.progress_calls,
                  two.progress_calls, one.progress_bad, two.progress_bad, one.points_started, two.points_started,
                  one.points_ended, two.points_ended);

    const int r0 = status ? status : runner_run(&scan, 2, 0, 2, NULL, &rank0, &run0);
    const int r1 = status ? status : runner_run(&scan, 2, 1, 2, NULL, &rank1, &run1);
    int shared = 0;
    for (int k = 0; k < RUNNER_POINTS; k++)
        shared += rank0.calls[k] + rank1.calls[k] == 1 && !strcmp(rank0.calls[k] ? rank0.row[k] : rank1.row[k], alone[k]);
    gb_check cr = {"8.3", "-", "gb_scan_run as rank 0 and as rank 1 of 2 (2 threads each)",
                   "every point once, on one rank, its row the point's own", "exact"};
    gb_check_true(&cr, !r0 && !r1 && shared == RUNNER_POINTS && run0 + run1 == RUNNER_POINTS && run0 == RUNNER_POINTS / 2,
                  "statuses %d, %d; %d of %d points once and the same; %zu + %zu run", r0, r1, shared, RUNNER_POINTS, run0, run1);

    const unsigned char done[RUNNER_POINTS] = {1, 0, 1, 0, 0, 1};
    const int sp = status ? status : runner_run(&scan, 2, 0, 1, done, &partial, &run_partial);
    int left_out = 0;
    for (int k = 0; k < RUNNER_POINTS; k++)
        left_out += done[k] ? partial.calls[k] == 0 : partial.calls[k] == 1 && !strcmp(partial.row[k], alone[k]);
    gb_check cd = {"8.3", "-", "gb_scan_run with points 0, 2 and 5 done already (a journal's)",
                   "those never run, the others once with their own rows", "exact"};
    gb_check_true(&cd, !sp && left_out == RUNNER_POINTS && run_partial == 3, "status %d; %d of %d as they should; %zu run", sp,
                  left_out, RUNNER_POINTS, run_partial);

    stopped.stop_after = 2;
    const int ss = status ? status : runner_run(&scan, 1, 0, 1, NULL, &stopped, &run_stopped);
    const unsigned char none[RUNNER_POINTS] = {0};
    const gb_scan_runner wide = {.threads = 257, .done = none}, beyond = {.rank = 2, .ranks = 2};
    const int sw = gb_scan_run(&scan, &wide, NULL), sb = gb_scan_run(&scan, &beyond, NULL);
    gb_check cs = {"8.3", "-", "gb_scan_run stopped by its caller's second finished point; 257 threads; rank 2 of 2",
                   "the caller's status and message, no point after; GB_EINVAL twice", "exact"};
    gb_check_true(&cs, ss == GB_EIO && stopped.finished == 2 && run_stopped == 1 && sw == GB_EINVAL && sb == GB_EINVAL,
                  "status %d (%s), %zu finished, %zu counted; %d, %d", ss, ss ? gb_error_message() : "", stopped.finished,
                  run_stopped, sw, sb);
    gb_error_clear();
    gb_scan_free(&scan);
    remove_scan_dir(&d);
}

/* ---- threads, interruption and resume ----------------------------------------------------------- */

static size_t lines_of(const char *path)
{
    FILE *f = fopen(path, "r");
    size_t n = 0;
    for (int ch; f && (ch = fgetc(f)) != EOF;) n += ch == '\n';
    if (f) fclose(f);
    return n;
}

/* Start `gomboc scan` on one thread, its standard error into `err` (a file of the test's directory), with SIGINT
 * at `sigint` (SIG_DFL, or SIG_IGN as a background job's) whatever this harness inherited, and the program's own
 * test hook (GOMBOC_TEST_PAUSE_AFTER_POINTS) stopping it once its journal holds `lines` lines (the header and
 * lines − 1 points); then send it `sig` and let it continue. The wait status. No polling and no timing: the
 * same under any load and any parent. */
static int signalled_scan_with(const scan_dir *d, size_t lines, int sig, const char *err, void (*sigint)(int))
{
    char points[32];
    snprintf(points, sizeof points, "%zu", lines - 1);
    const pid_t pid = fork();
    if (pid == 0) {
        signal(SIGINT, sigint);
        signal(SIGTERM, SIG_DFL);
        sigset_t none;
        sigemptyset(&none);
        sigprocmask(SIG_SETMASK, &none, NULL);
        setenv("GOMBOC_TEST_PAUSE_AFTER_POINTS", points, 1);
        if (!freopen(err, "w", stderr)) _exit(127);
        execl(binary(), binary(), "scan", d->scan, "--out", d->path, "--threads", "1", (char *)NULL);
        _exit(127);
    }
    int wstatus = 0;
    waitpid(pid, &wstatus, WUNTRACED); /* stopped by the hook, or ended before it (a failure the caller sees) */
    if (WIFSTOPPED(wstatus)) {
        kill(pid, sig);
        kill(pid, SIGCONT);
        waitpid(pid, &wstatus, 0);
    }
    return wstatus;
}

static int signalled_scan(const scan_dir *d, size_t lines, int sig, const char *err)
{
    return signalled_scan_with(d, lines, sig, err, SIG_DFL);
}

/* kill -9 once the journal holds `lines` lines. */
static int killed_scan(const scan_dir *d, size_t lines)
{
    char err[96];
    snprintf(err, sizeof err, "%s/killed.txt", d->path);
    const int wstatus = signalled_scan(d, lines, SIGKILL, err);
    remove(err);
    return wstatus;
}

static void test_threads_and_resume(void)
{
    scan_dir d;
    char out[1 << 14];
    gb_check ct = {"8.3", "-", "scan CSV on 1 and on 2 threads", "byte for byte", "exact"};
    if (make_scan_dir(&d, &ct)) return;
    const int c1 = scan_run(&d, "--threads 1", out, sizeof out);
    char *one = gb_check_read_file(d.csv);
    const int c2 = scan_run(&d, "--threads 2", out, sizeof out);
    char *two = gb_check_read_file(d.csv);
    gb_check_true(&ct, c1 == 0 && c2 == 0 && one && two && !strcmp(one, two), "exits %d, %d; %s", c1, c2,
                  one && two && !strcmp(one, two) ? "identical" : "different");
    free(two);

    /* Kill the scan once its journal holds two points, leave half a line behind, resume. */
    remove(d.csv);
    const int wstatus = killed_scan(&d, 3);
    const size_t kept = lines_of(d.journal);
    FILE *j = fopen(d.journal, "a");
    if (j) fputs("7,18.5,0.7", j), fclose(j); /* a line cut off by the kill */
    const int cr = scan_run(&d, "--resume", out, sizeof out);
    char *resumed = gb_check_read_file(d.csv);
    gb_check ck = {"8.3", "-", "scan CSV after a kill -9 with 2 or more points in the journal, a half-written line, and --resume",
                   "the uninterrupted run's CSV, byte for byte", "exact"};
    gb_check_true(&ck, WIFSIGNALED(wstatus) && kept >= 3 && kept < 1 + SCAN_POINTS && cr == 0 && resumed && one &&
                  !strcmp(one, resumed) && access(d.journal, F_OK) != 0,
                  "killed with %zu journal lines; resume exit %d; %s; journal %s", kept, cr,
                  resumed && one && !strcmp(one, resumed) ? "identical" : "different",
                  access(d.journal, F_OK) ? "removed" : "left");
    free(resumed);

    /* Ctrl-C: the scan says how to continue, and --resume does. */
    remove(d.csv);
    char err[96];
    snprintf(err, sizeof err, "%s/interrupted.txt", d.path);
    const int istatus = signalled_scan(&d, 3, SIGINT, err);
    char *said = gb_check_read_file(err);
    const int ci = scan_run(&d, "--resume", out, sizeof out);
    char *continued = gb_check_read_file(d.csv);
    gb_check cint = {"8.3", "-", "scan interrupted by SIGINT (Ctrl-C) with 2 or more points in the journal",
                     "says how to resume (the scan file, --out and --resume on standard error), and --resume gives the "
                     "uninterrupted run's CSV", "exact"};
    gb_check_true(&cint, WIFSIGNALED(istatus) && WTERMSIG(istatus) == SIGINT && said && strstr(said, "--resume") &&
                  strstr(said, d.scan) && ci == 0 && continued && one && !strcmp(one, continued),
                  "signal %d; said: %.200s; resume exit %d; %s", WIFSIGNALED(istatus) ? WTERMSIG(istatus) : 0,
                  said ? said : "(nothing)", ci, continued && one && !strcmp(one, continued) ? "identical" : "different");
    free(said);
    free(continued);
    remove(err);

    /* SIGINT ignored by the scan's parent (a background job, nohup): it stays ignored, the scan runs to its end. */
    remove(d.csv);
    const int gstatus = signalled_scan_with(&d, 3, SIGINT, err, SIG_IGN);
    char *whole = gb_check_read_file(d.csv);
    gb_check cg = {"8.3", "-", "scan started with SIGINT ignored (as by a background job), sent SIGINT with 2 points in the journal",
                   "the signal stays ignored: exit 0 with the uninterrupted run's CSV", "exact"};
    gb_check_true(&cg, WIFEXITED(gstatus) && WEXITSTATUS(gstatus) == 0 && whole && one && !strcmp(one, whole),
                  "wait status %d; %s", gstatus, whole && one && !strcmp(one, whole) ? "identical" : "different");
    free(whole);
    remove(err);

    /* A journal of another scan (another header), and a malformed line: refused, the journal kept. */
    spill(d.journal, "gomboc scan journal 1: scan 0000000000000000, binary 0000000000000000, 9 points\n");
    const int cm = scan_run(&d, "--resume", out, sizeof out);
    gb_check cj = {"8.3", "-", "--resume with the journal of another scan", "refused (exit 2), the journal kept", "exact"};
    gb_check_true(&cj, cm == 2 && strstr(out, "not this scan's journal") && access(d.journal, F_OK) == 0, "exit %d: %.200s", cm, out);
    remove(d.journal);
    const int first = scan_run(&d, "--threads 1", out, sizeof out); /* a complete run: no journal left */
    /* The header this binary writes, from a run killed at once (the header is written first). */
    char header[256] = "";
    killed_scan(&d, 1);
    FILE *h = fopen(d.journal, "r");
    if (h && !fgets(header, sizeof header, h)) header[0] = '\0';
    if (h) fclose(h);
    char bad[512];
    snprintf(bad, sizeof bad, "%s0,not a number\n", header);
    spill(d.journal, bad);
    const int cb = scan_run(&d, "--resume", out, sizeof out);
    gb_check cb2 = {"8.3", "-", "--resume with a malformed journal line", "refused (exit 2) naming the line, the journal kept", "exact"};
    gb_check_true(&cb2, first == 0 && header[0] && cb == 2 && strstr(out, "map-scan.journal:2: no seal at its end") &&
                       access(d.journal, F_OK) == 0,
                  "exit %d: %.200s", cb, out);
    /* An empty journal (a kill before the header of an older build's journal was written) holds no points: it
     * neither blocks --resume nor a fresh start, and both give the uninterrupted CSV. */
    int empty_codes[2];
    char *empty_csv[2];
    for (int k = 0; k < 2; k++) {
        remove(d.csv);
        spill(d.journal, "");
        empty_codes[k] = scan_run(&d, k ? "--threads 1" : "--resume --threads 1", out, sizeof out);
        empty_csv[k] = gb_check_read_file(d.csv);
    }
    gb_check ce = {"8.3", "-", "an empty journal, then --resume, and then a fresh start", "both exit 0 with the uninterrupted "
                   "run's CSV, byte for byte; no journal left", "exact"};
    gb_check_true(&ce, empty_codes[0] == 0 && empty_codes[1] == 0 && one && empty_csv[0] && empty_csv[1] &&
                       !strcmp(one, empty_csv[0]) && !strcmp(one, empty_csv[1]) && access(d.journal, F_OK) != 0,
                  "exits %d, %d: %.200s", empty_codes[0], empty_codes[1], out);
    free(empty_csv[0]), free(empty_csv[1]);
    /* The scan is complete now (its manifest beside the CSV, no journal): --resume has nothing to resume, says
     * so and runs no point, leaving the CSV as it was; a CSV whose point it ran again would be rewritten. */
    struct stat before, after;
    const int had = stat(d.csv, &before);
    const int cr2 = scan_run(&d, "--resume", out, sizeof out);
    char *csv_after = gb_check_read_file(d.csv);
    const int same = had == 0 && stat(d.csv, &after) == 0 && before.st_mtim.tv_sec == after.st_mtim.tv_sec &&
                     before.st_mtim.tv_nsec == after.st_mtim.tv_nsec && csv_after && one && !strcmp(csv_after, one);
    gb_check cn = {"8.3", "-", "--resume on a complete scan", "exit 0, 'nothing to resume' on standard error, no point run, "
                   "the CSV untouched (same bytes and modification time)", "exact"};
    gb_check_true(&cn, cr2 == 0 && strstr(out, "nothing to resume") && !strstr(out, "points (") && same, "exit %d: %.200s", cr2, out);
    free(csv_after);
    /* the same outputs, the scan file changed (a comment appended): they are another scan's, and it starts anew */
    FILE *edit = fopen(d.scan, "a");
    if (edit) fputs("; changed\n", edit), fclose(edit);
    const int cr3 = scan_run(&d, "--resume", out, sizeof out);
    gb_check cs = {"8.3", "-", "--resume beside the outputs of another scan file (the same one with a comment added)",
                   "exit 0, the scan run anew", "exact"};
    gb_check_true(&cs, cr3 == 0 && strstr(out, "starts anew") && strstr(out, "points ("), "exit %d: %.200s", cr3, out);
    free(one);
    remove_scan_dir(&d);
}

/* ---- a journal is verified, never trusted ----------------------------------------------------------- */

/* The journal's lines (the header first) as a NULL-terminated array of malloc'd strings, each with its
 * '\n'; NULL when there is none. */
static char **journal_lines(const char *path, size_t *count)
{
    char *text = gb_check_read_file(path);
    *count = 0;
    if (!text) return NULL;
    char **lines = calloc(strlen(text) + 2, sizeof *lines);
    for (char *p = text; lines && *p;) {
        char *end = strchr(p, '\n');
        const size_t n = end ? (size_t)(end - p) + 1 : strlen(p);
        lines[(*count)++] = strndup(p, n);
        p += n;
    }
    free(text);
    return lines;
}

static void free_lines(char **lines)
{
    for (size_t k = 0; lines && lines[k]; k++) free(lines[k]);
    free(lines);
}

/* A journal made of `lines` with line `which` replaced by `replacement` (or the lines as they are). */
static int spill_lines(const char *path, char *const *lines, size_t count, size_t which, const char *replacement,
                       size_t replacement_size)
{
    FILE *f = fopen(path, "wb");
    if (!f) return 1;
    for (size_t k = 0; k < count; k++) {
        if (k == which) fwrite(replacement, 1, replacement_size, f);
        else fputs(lines[k], f);
    }
    return fclose(f) != 0;
}

/* Line `line` (a point's) with its `field`-th comma-separated field replaced by `value`, and its seal:
 * SEAL_KEPT, the old one; SEAL_KEYED, recomputed with this user's key (a row this program would write,
 * for the checks behind the seal); SEAL_FORGED, recomputed as a forger without the key can (an unkeyed
 * BLAKE2b-256 of the same bytes, as a checksum would be recomputed). */
enum { SEAL_KEPT = 0, SEAL_KEYED = 1, SEAL_FORGED = 2 };
static void edited_line(const char *header, const char *line, int field, const char *value, int sign, char *out, size_t cap)
{
    char row[2048];
    size_t n = 0;
    int at = 0;
    const char *p = line;
    const size_t body = strlen(line) - (2 * GB_SEAL_BYTES + 2); /* without ",<64 hex>\n" */
    while ((size_t)(p - line) < body) {
        const char *comma = memchr(p, ',', body - (size_t)(p - line));
        const size_t len = comma ? (size_t)(comma - p) : body - (size_t)(p - line);
        n += (size_t)snprintf(row + n, sizeof row - n, "%s%.*s", at ? "," : "", (int)(at == field ? strlen(value) : len),
                              at == field ? value : p);
        at++;
        p += len + (comma != NULL);
        if (!comma) break;
    }
    snprintf(row + n, sizeof row - n, "\n");
    if (sign == SEAL_KEYED) {
        gb_scan_journal_line(header, row, out, cap);
    } else if (sign == SEAL_FORGED) {
        unsigned char digest[GB_SEAL_BYTES];
        char hex[GB_SEAL_HEX];
        const gb_seal_piece pieces[2] = {{header, strlen(header)}, {row, strlen(row) - 1}};
        gb_seal_digest(pieces, 2, digest);
        gb_seal_hex(digest, hex);
        snprintf(out, cap, "%.*s,%s\n", (int)(strlen(row) - 1), row, hex);
    } else {
        snprintf(out, cap, "%.*s%s", (int)(strlen(row) - 1), row, line + body);
    }
}

static void test_journal_verified(void)
{
    scan_dir d;
    char out[1 << 14];
    gb_check c = {"8.3", "-", "--resume with a journal edited or damaged in its middle, one way a row",
                  "refused with exit 2 naming the line and the fault, the journal byte for byte as it was", "exact"};
    if (make_scan_dir(&d, &c)) return;
    const int wstatus = killed_scan(&d, 5); /* the header and at least 4 points */
    size_t count = 0;
    char **lines = journal_lines(d.journal, &count);
    if (!WIFSIGNALED(wstatus) || !lines || count < 5 || count >= 1 + SCAN_POINTS) {
        gb_check_true(&c, 0, "the killed scan left %zu journal lines", count);
        free_lines(lines);
        remove_scan_dir(&d);
        return;
    }
    const char *header = lines[0];
    char nan_line[2048], metric[2048], forged[2048], fingerprint[2048], coordinate[2048], duplicate[2048], too_long[2048],
        negative[2048];
    edited_line(header, lines[2], 0, "-1", SEAL_KEYED, negative, sizeof negative); /* a point index of -1, re-sealed */
    edited_line(header, lines[2], 1, "17", SEAL_KEYED, coordinate, sizeof coordinate); /* x of another point, re-sealed */
    edited_line(header, lines[2], 3, "0.25", SEAL_KEPT, metric, sizeof metric);       /* omega_rms edited */
    edited_line(header, lines[2], 3, "0.5", SEAL_FORGED, forged, sizeof forged);      /* ... and its digest recomputed */
    edited_line(header, lines[2], 17, "0123456789abcdef", SEAL_KEPT, fingerprint, sizeof fingerprint);
    const char *nan_at = strstr(lines[2], ",nan,");
    snprintf(nan_line, sizeof nan_line, "%s", lines[2]);
    if (nan_at) memcpy(nan_line + (nan_at - lines[2]) + 1, "0.5", 3); /* a NaN made a number (none: the row stays, and fails) */
    edited_line(header, lines[2], 3, "0.25", SEAL_KEYED, duplicate, sizeof duplicate); /* line 2's point again, re-sealed */
    memset(too_long, '7', 1500);
    snprintf(too_long + 1500, sizeof too_long - 1500, "\n");
    char with_nul[2048];
    const size_t nul_size = strlen(lines[2]);
    memcpy(with_nul, lines[2], nul_size);
    with_nul[5] = '\0';
    char garbage[256];
    snprintf(garbage, sizeof garbage, "gomboc scan journal 3: \x1b[31mred\x07 %0180d\n", 7);
    const struct {
        const char *what;
        size_t line;
        const char *text;
        size_t size;
        const char *must;
    } faults[] = {
        {"a coordinate edited (x = 17), re-sealed with the key", 2, coordinate, strlen(coordinate), "do not read back to the same row"},
        {"a metric edited", 2, metric, strlen(metric), "seal does not verify"},
        {"a metric edited (0.5), its digest recomputed without the key", 2, forged, strlen(forged), "seal does not verify"},
        {"a NaN made a number", 2, nan_line, strlen(nan_line), "seal does not verify"},
        {"a fingerprint edited", 2, fingerprint, strlen(fingerprint), "seal does not verify"},
        {"line 2's point again with another value, re-sealed", 3, duplicate, strlen(duplicate), "a second time, with other values"},
        {"a NUL byte", 2, with_nul, nul_size, "a NUL byte"},
        {"a point index of -1, re-sealed", 2, negative, strlen(negative), "not a row of this command"},
        {"a line of 1500 bytes", 2, too_long, strlen(too_long), "1500 bytes long"},
        {"a header with escape and bell characters", 0, garbage, strlen(garbage), "its header: 'gomboc scan journal 3: ?[31mred? 000"},
    };
    size_t refused = 0;
    const size_t total = sizeof faults / sizeof faults[0];
    char report[4096] = "";
    for (size_t k = 0; k < total; k++) {
        spill_lines(d.journal, lines, count, faults[k].line, faults[k].text, faults[k].size);
        char *before = gb_check_read_file(d.journal);
        const int code = scan_run(&d, "--resume --threads 1", out, sizeof out);
        char *after = gb_check_read_file(d.journal);
        char where[64];
        snprintf(where, sizeof where, "map-scan.journal:%zu: ", faults[k].line + 1);
        const int ok = code == 2 && strstr(out, faults[k].must) && (faults[k].line == 0 || strstr(out, where)) &&
                       strstr(out, "remove it to start again") && before && after && !memcmp(before, after, strlen(before)) &&
                       access(d.csv, F_OK) != 0 && !strchr(out, '\x1b');
        refused += ok;
        if (!ok && strlen(report) < 3000)
            snprintf(report + strlen(report), sizeof report - strlen(report), "[%s: exit %d: %.300s] ", faults[k].what, code, out);
        free(before), free(after);
    }
    gb_check_true(&c, refused == total, "%zu of %zu faults refused as stated%s%s", refused, total, report[0] ? ": " : "", report);

    /* The same point twice with the same values is no fault; a half-written last line is dropped. */
    FILE *f = fopen(d.journal, "wb");
    for (size_t k = 0; f && k < count; k++) fputs(lines[k], f);
    if (f) fputs(lines[2], f), fputs("5,18,", f), fclose(f);
    const int resumed = scan_run(&d, "--resume --threads 1", out, sizeof out);
    char *csv = gb_check_read_file(d.csv);
    const int whole = scan_run(&d, "--threads 1", out, sizeof out); /* the uninterrupted CSV */
    char *reference = gb_check_read_file(d.csv);
    gb_check ci = {"8.3", "-", "--resume with a point twice, identical, and a half-written last line",
                   "accepted; the CSV of an uninterrupted run, byte for byte", "exact"};
    gb_check_true(&ci, resumed == 0 && whole == 0 && csv && reference && !strcmp(csv, reference), "resume exit %d, run exit %d, %s",
                  resumed, whole, csv && reference && !strcmp(csv, reference) ? "identical" : "different");
    free(csv), free(reference);

    /* The scan's JSON is the set's manifest and records what the scan was: gomboc check finds it whole. */
    char json_path[200], args[512];
    snprintf(json_path, sizeof json_path, "%s/map-scan.json", d.path);
    snprintf(args, sizeof args, "check '%s'", json_path);
    const int checked = run(args, out, sizeof out);
    char *json_text = gb_check_read_file(json_path);
    cJSON *root = json_text ? cJSON_Parse(json_text) : NULL;
    const cJSON *metrics = cJSON_GetObjectItem(root, "metrics");
    gb_check cm = {"8.3", "-", "a scan's JSON lists its CSV with size and checksum, and the metrics it computed",
                   "gomboc check exit 0; 8 metrics, omega_rms first, contacts last", "exact"};
    gb_check_true(&cm, checked == 0 && cJSON_GetArraySize(metrics) == 8 &&
                       !strcmp(cJSON_GetArrayItem(metrics, 0)->valuestring, "omega_rms") &&
                       !strcmp(cJSON_GetArrayItem(metrics, 7)->valuestring, "contacts"),
                  "check exit %d: %.200s", checked, out);
    cJSON_Delete(root);
    free(json_text);
    free_lines(lines);

    /* A scan that fails before any point is finished leaves no journal to stand in the way of the next
     * run (RK4 at one step a period diverges under a damping rate c/I of ~1e9 /s: "the state is no longer
     * finite", a computation that failed). */
    char path[200];
    snprintf(path, sizeof path, "%s/base.ini", d.path);
    spill(path, "[body]\nbeta = 0.12\nmass = 1e-6\n[model]\nequation = rolling\ncontact = continuous\ndamping = 1000\n"
                "[integrator]\nperiods = 1\nsteps_per_period = 1\n[initial]\nomega = 1,0,0\n");
    spill(d.scan, "[scan]\nbase = base.ini\nperiods = 2\ntransient_periods = 1\n[x]\nkey = body.mass\nfrom = 1\nto = 2\n"
                  "count = 2\n[y]\nkey = forcing.A1\nfrom = 1\nto = 1\ncount = 1\n");
    const int failed = scan_run(&d, "--threads 1", out, sizeof out);
    const int again = scan_run(&d, "--threads 1", out, sizeof out);
    gb_check cf = {"8.3", "-", "a scan whose every point fails, run twice", "exit 1 both times (never 2 for a journal left behind), "
                   "no journal", "exact"};
    gb_check_true(&cf, failed == 1 && again == 1 && access(d.journal, F_OK) != 0, "exits %d, %d; journal %s: %.200s", failed, again,
                  access(d.journal, F_OK) ? "none" : "LEFT", out);

    /* The same scan with failed_points = record: it finishes, each failed point a row of NaN metrics. */
    spill(d.scan, "[scan]\nbase = base.ini\nperiods = 2\ntransient_periods = 1\nfailed_points = record\n[x]\nkey = body.mass\n"
                  "from = 1\nto = 2\ncount = 2\n[y]\nkey = forcing.A1\nfrom = 1\nto = 1\ncount = 1\n");
    const int recorded = scan_run(&d, "--threads 1", out, sizeof out);
    char *csv_text = gb_check_read_file(d.csv);
    json_text = gb_check_read_file(json_path);
    root = json_text ? cJSON_Parse(json_text) : NULL;
    const cJSON *mode = cJSON_GetObjectItem(root, "failed_points");
    size_t nan_rows = 0;
    /* the rows after the header: each must hold ",nan," and end in two zero fingerprints */
    for (char *line = csv_text ? strchr(csv_text, '\n') : NULL; line && line[1]; line = strchr(line + 1, '\n')) {
        char *end = strchr(line + 1, '\n');
        if (end) *end = '\0';
        const size_t n = strlen(line + 1);
        nan_rows += strstr(line + 1, ",nan,") && n > 34 && !strcmp(line + 1 + n - 34, ",0000000000000000,0000000000000000");
        if (end) *end = '\n';
    }
    gb_check cg = {"8.3", "-", "that scan with failed_points = record", "exit 0; 2 rows of NaN metrics with zero fingerprints; "
                   "the JSON says record; the message names each failed point", "exact"};
    gb_check_true(&cg, recorded == 0 && nan_rows == 2 && cJSON_IsString(mode) && !strcmp(mode->valuestring, "record") &&
                       strstr(out, "recorded with NaN metrics"),
                  "exit %d, %zu NaN rows: %.300s", recorded, nan_rows, csv_text ? csv_text : out);
    cJSON_Delete(root);
    free(json_text);
    free(csv_text);

    /* A random axis is recorded as such: its seed and count, no range. */
    spill(path, "[integrator]\nperiods = 2\n[model]\ncontact = fast-grid\n");
    spill(d.scan, "[scan]\nbase = base.ini\nperiods = 2\ntransient_periods = 1\nmetrics = omega_rms\n[x]\nkey = initial.attitude\n"
                  "scale = random\ncount = 2\nseed = 5\n[y]\nkey = forcing.A1\nfrom = 1\nto = 1\ncount = 1\n");
    const int random_run = scan_run(&d, "--threads 1", out, sizeof out);
    json_text = gb_check_read_file(json_path);
    root = json_text ? cJSON_Parse(json_text) : NULL;
    const cJSON *x = cJSON_GetObjectItem(root, "x");
    const cJSON *scale = cJSON_GetObjectItem(x, "scale"), *seed = cJSON_GetObjectItem(x, "seed");
    gb_check cr = {"8.3", "-", "the JSON of a scan over random attitudes (seed 5, 2 points)",
                   "x.scale = random, x.seed = 5, x.count = 2, no from or to; metrics = [omega_rms]", "exact"};
    gb_check_true(&cr, random_run == 0 && cJSON_IsString(scale) && !strcmp(scale->valuestring, "random") && cJSON_IsNumber(seed) &&
                       seed->valuedouble == 5 && number_at(x, "count", NULL) == 2 && !cJSON_GetObjectItem(x, "from") &&
                       !cJSON_GetObjectItem(x, "to") && cJSON_GetArraySize(cJSON_GetObjectItem(root, "metrics")) == 1,
                  "exit %d: %.300s", random_run, json_text ? json_text : out);
    cJSON_Delete(root);
    free(json_text);
    remove_scan_dir(&d);
}

/* ---- MPI ranks (where an MPI build exists: $GOMBOC_MPI_BIN, launched by $GOMBOC_MPIRUN) ----------- */

static const char *mpi_binary(void) { return getenv("GOMBOC_MPI_BIN"); }

/* `LAUNCHER -n RANKS MPI-BINARY scan ...` into the scan directory; the exit status. */
static int mpi_scan_run(const scan_dir *d, int ranks, const char *extra, char *out, size_t cap)
{
    char command[1024], args[1024];
    snprintf(command, sizeof command, "%s -n %d '%s'", getenv("GOMBOC_MPIRUN"), ranks, mpi_binary());
    snprintf(args, sizeof args, "scan '%s' --out '%s' %s", d->scan, d->path, extra);
    return gb_check_command(command, args, out, cap);
}

/* The ranks the scan's JSON says it ran on. */
static int ranks_of(const scan_dir *d)
{
    char path[200];
    snprintf(path, sizeof path, "%s/map-scan.json", d->path);
    char *text = gb_check_read_file(path);
    cJSON *root = text ? cJSON_Parse(text) : NULL;
    free(text);
    const double ranks = number_at(root, "environment", "ranks");
    cJSON_Delete(root);
    return isfinite(ranks) ? (int)ranks : -1;
}

/* SIGKILL to every process of session `sid` (mpirun and its ranks, which OpenMPI puts in process groups
 * of their own) until none is left; the number killed. */
static int kill_session(pid_t sid)
{
    int killed = 0;
    for (int round = 0; round < 100; round++) {
        int found = 0;
        DIR *proc = opendir("/proc");
        for (struct dirent *e; proc && (e = readdir(proc));) {
            const long pid = strtol(e->d_name, NULL, 10);
            if (pid <= 0) continue;
            char path[64], stat[512];
            snprintf(path, sizeof path, "/proc/%ld/stat", pid);
            FILE *f = fopen(path, "r");
            if (!f) continue;
            const size_t n = fread(stat, 1, sizeof stat - 1, f);
            fclose(f);
            stat[n] = '\0';
            const char *after = strrchr(stat, ')'); /* after the command's name: state, ppid, pgrp, session */
            char state;
            long ppid, pgrp, session;
            if (!after || sscanf(after + 1, " %c %ld %ld %ld", &state, &ppid, &pgrp, &session) != 4) continue;
            if (session != (long)sid || state == 'Z') continue;
            found++;
            if (kill((pid_t)pid, SIGKILL) == 0) killed++;
        }
        if (proc) closedir(proc);
        if (!found) break;
        const struct timespec pause = {0, 10000000};
        nanosleep(&pause, NULL);
    }
    return killed;
}

static void test_mpi_ranks(void)
{
    scan_dir d;
    char out[1 << 14];
    gb_check c1 = {"8.3", "-", "scan CSV of the MPI build on 1 rank against the plain build on 1 thread", "byte for byte", "exact"};
    if (make_scan_dir(&d, &c1)) return;
    const int plain = scan_run(&d, "--threads 1", out, sizeof out);
    char *reference = gb_check_read_file(d.csv);
    remove(d.csv);
    const int one = mpi_scan_run(&d, 1, "--threads 1", out, sizeof out);
    char *csv = gb_check_read_file(d.csv);
    const int same1 = plain == 0 && one == 0 && reference && csv && !strcmp(reference, csv) && ranks_of(&d) == 1;
    gb_check_true(&c1, same1, "exits %d, %d; %d rank(s); %s%s%.200s", plain, one, ranks_of(&d),
                  reference && csv && !strcmp(reference, csv) ? "identical" : "different", same1 ? "" : ": ", same1 ? "" : out);
    free(csv);

    static const struct {
        int ranks;
        const char *threads;
    } runs[] = {{2, "--threads 1"}, {2, "--threads 2"}, {3, "--threads 1"}};
    for (size_t k = 0; k < sizeof runs / sizeof runs[0]; k++) {
        remove(d.csv);
        const int code = mpi_scan_run(&d, runs[k].ranks, runs[k].threads, out, sizeof out);
        csv = gb_check_read_file(d.csv);
        char quantity[160];
        snprintf(quantity, sizeof quantity, "scan CSV on %d MPI ranks (%s) against the plain build on 1 thread",
                 runs[k].ranks, runs[k].threads);
        gb_check c = {"8.3", "-", quantity, "byte for byte; the JSON names the ranks", "exact"};
        const int same = code == 0 && csv && reference && !strcmp(reference, csv) && ranks_of(&d) == runs[k].ranks;
        gb_check_true(&c, same, "exit %d; %d rank(s); %s%s%.200s", code, ranks_of(&d),
                      reference && csv && !strcmp(reference, csv) ? "identical" : "different", same ? "" : ": ", same ? "" : out);
        free(csv);
    }

    /* The whole launch (mpirun and its ranks, one session) killed once the journal holds two points; a
     * half-written line left behind; resumed on 2 ranks. Rank 0 stops itself there (the program's test hook,
     * GOMBOC_TEST_PAUSE_AFTER_POINTS, forwarded by mpirun -x), so the journal holds exactly 3 lines when it is
     * killed, whatever the load. */
    remove(d.csv);
    const pid_t pid = fork();
    if (pid == 0) {
        setsid();
        signal(SIGINT, SIG_DFL), signal(SIGTERM, SIG_DFL);
        char log[600];
        snprintf(log, sizeof log, "%s/mpi-killed.log", d.path);
        if (!freopen(log, "w", stdout) || !freopen(log, "a", stderr)) _exit(127);
        setenv("GOMBOC_TEST_PAUSE_AFTER_POINTS", "2", 1);
        char command[1024];
        snprintf(command, sizeof command, "exec %s -x GOMBOC_TEST_PAUSE_AFTER_POINTS -n 2 '%s' scan '%s' --out '%s' --threads 1",
                 getenv("GOMBOC_MPIRUN"), mpi_binary(), d.scan, d.path);
        execl("/bin/sh", "sh", "-c", command, (char *)NULL);
        _exit(127);
    }
    const struct timespec ms = {0, 1000000};
    for (int k = 0; k < 60000 && lines_of(d.journal) < 3; k++) nanosleep(&ms, NULL);
    const int killed = kill_session(pid);
    int wstatus = 0;
    waitpid(pid, &wstatus, 0);
    const size_t kept = lines_of(d.journal);
    FILE *j = fopen(d.journal, "a");
    if (j) fputs("5,18,1.", j), fclose(j);
    const int resumed = mpi_scan_run(&d, 2, "--resume --threads 1", out, sizeof out);
    csv = gb_check_read_file(d.csv);
    gb_check ck = {"8.3", "-", "scan CSV after a kill -9 of every rank with 2 or more points journaled, a half-written line, "
                   "and --resume on 2 ranks", "the plain build's uninterrupted CSV, byte for byte", "exact"};
    size_t journaled = SCAN_POINTS; /* what the resumed run found in the journal */
    const char *said = strstr(out, "resuming, ");
    if (!said || sscanf(said, "resuming, %zu of", &journaled) != 1) journaled = SCAN_POINTS;
    const int resumed_same = WIFSIGNALED(wstatus) && killed >= 3 && kept == 3 && journaled == kept - 1 &&
                             journaled < SCAN_POINTS && resumed == 0 && csv && reference && !strcmp(reference, csv) &&
                             access(d.journal, F_OK) != 0;
    gb_check_true(&ck, resumed_same,
                  "%d processes killed with %zu journal lines (%zu points found on resuming); resume exit %d; %s%s%.200s",
                  killed, kept, journaled, resumed, reference && csv && !strcmp(reference, csv) ? "identical" : "different",
                  resumed_same ? "" : ": ", resumed_same ? "" : out);
    free(csv);
    free(reference);
    remove_scan_dir(&d);
}

/* A disk that fills: the scan's files limited to 700 bytes (RLIMIT_FSIZE: every write past it fails with
 * EFBIG, as on a full disk with ENOSPC). The scan must stop with exit 1 naming the journal, leave no
 * CSV, keep the points it journaled, and finish them with --resume once there is room, byte for byte. */
static void test_disk_full(void)
{
    scan_dir d;
    char out[1 << 14];
    gb_check c = {"8.3", "-", "a scan whose journal cannot grow (file size limit of 700 bytes: a full disk)",
                  "exit 1 naming the journal, no CSV; --resume with room gives the uninterrupted CSV byte for byte",
                  "exact"};
    if (make_scan_dir(&d, &c)) return;
    const int plain = scan_run(&d, "--threads 1", out, sizeof out);
    char *reference = gb_check_read_file(d.csv);
    remove(d.csv);
    char log[200];
    snprintf(log, sizeof log, "%s/full.log", d.path);
    const pid_t pid = fork();
    if (pid == 0) {
        const struct rlimit limit = {700, 700};
        signal(SIGXFSZ, SIG_IGN);
        if (setrlimit(RLIMIT_FSIZE, &limit) || !freopen(log, "w", stderr)) _exit(127);
        execl(binary(), binary(), "scan", d.scan, "--out", d.path, "--threads", "1", (char *)NULL);
        _exit(127);
    }
    int wstatus = 0;
    waitpid(pid, &wstatus, 0);
    char *message = gb_check_read_file(log);
    const size_t kept = lines_of(d.journal);
    const int no_csv = access(d.csv, F_OK) != 0;
    const int resumed = scan_run(&d, "--resume --threads 1", out, sizeof out);
    char *csv = gb_check_read_file(d.csv);
    const int ok = plain == 0 && WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 1 && message &&
                   strstr(message, "cannot append to the journal") && no_csv && kept >= 2 && kept < 1 + SCAN_POINTS &&
                   resumed == 0 && csv && reference && !strcmp(csv, reference);
    gb_check_true(&c, ok, "exit %d, %zu journal lines kept, %s; resume exit %d, %s; message: %.160s",
                  WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : -1, kept, no_csv ? "no CSV" : "a CSV left", resumed,
                  csv && reference && !strcmp(csv, reference) ? "identical" : "different", message ? message : "(none)");
    free(message), free(csv), free(reference);
    remove_scan_dir(&d);
}

/* A point whose coordinate is outside its key's range is refused before any run, naming the scan
 * file's line, the point and the range; nothing is written. */
static void test_point_out_of_range(void)
{
    scan_dir d;
    char out[1 << 14];
    gb_check c = {"8.3", "-", "a scan whose last point has beta = 0.3", "refused (exit 2) before any run, naming line, point, range",
                  "exact"};
    if (make_scan_dir(&d, &c)) return;
    spill(d.scan, "[scan]\nbase = base.ini\nperiods = 12\ntransient_periods = 4\n"
                  "[x]\nkey = body.beta\nfrom = 0.1\nto = 0.3\ncount = 3\n[y]\nkey = forcing.A2\nfrom = 0.5\nto = 1.5\ncount = 2\n");
    const int code = scan_run(&d, "", out, sizeof out);
    gb_check_true(&c, code == 2 && strstr(out, "map.ini:6 (point 2): [body] beta = 0.2999") && strstr(out, "beta < 0.25") &&
                  access(d.csv, F_OK) != 0 && access(d.journal, F_OK) != 0,
                  "exit %d: %.300s", code, out);
    remove_scan_dir(&d);
}

/* The random axis: the k-th attitude depends only on (seed, k), and the draws are uniform on the
 * rotations: the rotation angle θ of a uniform rotation has the density (1 − cos θ)/π on [0, π], so its
 * mean is π/2 + 2/π. */
static void test_random_attitudes(void)
{
    enum { DRAWS = 4096 };
    double sum = 0.0, sum2 = 0.0;
    int same = 1;
    for (size_t k = 0; k < DRAWS; k++) {
        char a[160], b[160];
        gb_scan_random_attitude(20261123ul, k, a, sizeof a);
        gb_scan_random_attitude(20261123ul, k, b, sizeof b);
        same = same && !strcmp(a, b);
        double x, y, z, angle;
        if (sscanf(a, "axis-angle %lf,%lf,%lf,%lf", &x, &y, &z, &angle) != 4) angle = NAN;
        sum += angle, sum2 += angle * angle;
    }
    const double mean = sum / DRAWS, sd = sqrt(fmax(0.0, sum2 / DRAWS - mean * mean));
    gb_check cd = {"8.3", "-", "random attitudes: the same (seed, k), the same text", "determinism", "exact"};
    gb_check_true(&cd, same, "%s", same ? "4096 draws repeated identically" : "a draw differs");
    gb_check cm = {"8.3", "-", "random attitudes: mean rotation angle of 4096 draws", "pi/2 + 2/pi (uniform on SO(3))",
                   "4 standard errors of the mean (sd / sqrt 4096)"};
    gb_check_close(&cm, mean, M_PI / 2 + 2 / M_PI, 0.0, 4.0 * sd / sqrt((double)DRAWS));
}

/* The lifetime of the chaos on records whose answer is known: 12 windows of 25 intervals. */
static void test_chaos_lifetime(void)
{
    enum { N = 300 };
    double record[N];
    gb_check c = {"8.2", "77", "chaos lifetime of synthetic records (12 windows of 25 intervals, 2 periods an interval)",
                  "chaotic for 5 windows: 250 periods; for all 12: +inf; never: 0; a record of 200: too short (NaN)", "exact"};
    for (int k = 0; k < N; k++) record[k] = k < 5 * 25 ? 0.4 + 0.3 * sin(k) : 0.01 * sin(k); /* 5 chaotic windows */
    const double five = gb_scan_chaos_lifetime(record, N, 2.0);
    for (int k = 0; k < N; k++) record[k] = 0.2;
    const double all = gb_scan_chaos_lifetime(record, N, 2.0);
    for (int k = 0; k < N; k++) record[k] = k % 2 ? 0.04 : -0.04;
    const double none = gb_scan_chaos_lifetime(record, N, 2.0);
    const double short_record = gb_scan_chaos_lifetime(record, 200, 2.0);
    /* chaos that pauses and returns counts to its last window */
    for (int k = 0; k < N; k++) record[k] = (k < 50 || (k >= 200 && k < 225)) ? 0.3 : 0.0;
    const double returning = gb_scan_chaos_lifetime(record, N, 2.0);
    gb_check_true(&c, five == 250.0 && isinf(all) && all > 0 && none == 0.0 && isnan(short_record) && returning == 450.0,
                  "%g, %g, %g, %g, %g (returning chaos to window 9: 450)", five, all, none, short_record, returning);
}

/* Windowed exponents: a record whose window means are known (each window a constant plus a zero-sum
 * oscillation), and `gomboc run`'s windows file against the means of its own λ record (lyapunov.csv,
 * 12 significant digits), recomputed here. */
static void test_windowed_exponents(void)
{
    enum { N = 230, PER = 40 };
    double record[N], mean[N];
    for (int k = 0; k < N; k++) record[k] = 0.1 * (k / PER) + (k % 2 ? 0.25 : -0.25);
    const size_t count = gb_lyapunov_windows(record, N, PER, mean);
    double worst = 0.0;
    for (size_t w = 0; w < count; w++) worst = fmax(worst, fabs(mean[w] - 0.1 * (double)w));
    gb_check ck = {"8.2", "77", "windowed exponents of a record of 230 intervals in windows of 40: count and worst error",
                   "5 windows (the incomplete sixth left out), means 0, 0.1, ..., 0.4 (closed form)",
                   "4e-16: a sum of 40 terms of size 0.4 in double precision"};
    gb_check_true(&ck, count == 5 && gb_lyapunov_windows(record, N, 0, mean) == 0 &&
                  gb_lyapunov_windows(record, 10, PER, mean) == 0, "%zu windows", count);
    gb_check_close(&ck, worst, 0.0, 0.0, 4e-16);

    scan_dir d;
    char out[1 << 14], text[8192], scene[200], args[600], path[200];
    gb_check cr = {"8.2", "77", "gomboc run's windowed exponents (40 periods, 5 windows of 8) against its own lambda record",
                   "the means of lambda_inst in NAME-lyapunov.csv, recomputed",
                   "1e-11 of the largest |lambda_inst|: the record is printed with 12 significant digits"};
    if (make_scan_dir(&d, &cr)) return;
    scene_text(text, sizeof text, 18.0, 1.0, 40.0, 0, 0);
    strncat(text, "window_periods = 8\n", sizeof text - strlen(text) - 1);
    snprintf(scene, sizeof scene, "%s/windows.ini", d.path);
    snprintf(args, sizeof args, "run '%s' --out '%s'", scene, d.path);
    const int code = spill(scene, text) ? -1 : run(args, out, sizeof out);
    double inst[40], largest = 0.0, windows[5], error = NAN;
    size_t got = 0, rows = 0;
    snprintf(path, sizeof path, "%s/windows-lyapunov.csv", d.path);
    FILE *f = fopen(path, "r");
    char line[512];
    if (f && fgets(line, sizeof line, f))
        while (rows < 40 && fgets(line, sizeof line, f) && sscanf(line, "%*d,%*d,%lf", &inst[rows]) == 1)
            largest = fmax(largest, fabs(inst[rows++]));
    if (f) fclose(f);
    snprintf(path, sizeof path, "%s/windows-lyapunov-windows.csv", d.path);
    f = fopen(path, "r");
    if (f && fgets(line, sizeof line, f))
        while (got < 5 && fgets(line, sizeof line, f) && sscanf(line, "%*d,%*d,%*d,%lf", &windows[got]) == 1) got++;
    if (f) fclose(f);
    if (code == 0 && rows == 40 && got == 5) {
        error = 0.0;
        for (size_t w = 0; w < 5; w++) {
            double sum = 0.0;
            for (size_t k = 8 * w; k < 8 * (w + 1); k++) sum += inst[k];
            error = fmax(error, fabs(windows[w] - sum / 8.0));
        }
    }
    gb_check_close(&cr, error, 0.0, 0.0, 1e-11 * largest);
    remove_scan_dir(&d);
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

/* ---- one atlas of verticals for a whole scan ------------------------------------------------------- */

/* A rolling-model scan of 2 x 2 points with the per-vertical certificate, and the same with the atlas shared
 * through --atlas FILE (made by the first points, then loaded): the same CSV bytes, and the file written. */
/* Write the scan file DIR/NAME.ini with `text` and run `gomboc scan` on it into DIR with `options`: its exit. */
static int scan_file_run(const char *dir, const char *name, const char *text, const char *options, char *out, size_t size)
{
    char path[300], args[700];
    snprintf(path, sizeof path, "%s/%s.ini", dir, name);
    spill(path, text);
    snprintf(args, sizeof args, "scan '%s' --out '%s'%s", path, dir, options);
    return run(args, out, size);
}

static void test_scan_atlas(void)
{
    scan_dir d;
    gb_check cs = {"4, 8.3", "29", "gomboc scan --atlas FILE: a rolling-model scan (2 x 2 points, 4 periods, continuous "
                   "contact) with one atlas of verticals for every point, made by the first points, then loaded",
                   "the CSV of the per-vertical certificate, byte for byte; the atlas file written", "exact"};
    snprintf(d.path, sizeof d.path, "/tmp/gomboc-scan-XXXXXX");
    if (!mkdtemp(d.path)) {
        gb_check_true(&cs, 0, "cannot make a directory: %s", strerror(errno));
        return;
    }
    static const char base[] = "[body]\nmorphology = I\nbeta = 0.12\n[forcing]\nA1 = 2.0\nA2 = 1.0\nomega = 18\npsi = pi/3\n"
                               "[model]\nequation = rolling\ncontact = continuous\ncertificate = %s\ndamping = 0.02\n"
                               "[integrator]\nmethod = rk4\nsteps_per_period = 160\nlocate_switches = yes\n";
    static const char scan[] = "[scan]\nbase = %s.ini\nperiods = 4\ntransient_periods = 1\nmetrics = omega_rms, switch_rate\n"
                               "[x]\nkey = forcing.omega\nfrom = 17\nto = 19\ncount = 2\n[y]\nkey = forcing.A1\nfrom = 1.5\nto = 2\n"
                               "count = 2\n";
    char text[1024], path[200], atlas[200], args[1024], out[1 << 14], *csv[3] = {NULL, NULL, NULL};
    int codes[3] = {-1, -1, -1};
    static const char *const names[2] = {"per-vertical", "atlas"};
    for (int k = 0; k < 2; k++) {
        snprintf(text, sizeof text, base, names[k]);
        snprintf(path, sizeof path, "%s/%s.ini", d.path, names[k]);
        spill(path, text);
        snprintf(text, sizeof text, scan, names[k]);
        snprintf(path, sizeof path, "%s/scan-%s.ini", d.path, names[k]);
        spill(path, text);
    }
    snprintf(atlas, sizeof atlas, "%s/shared.atlas", d.path);
    for (int k = 0; k < 3; k++) {
        const int shared = k > 0;
        snprintf(args, sizeof args, "scan '%s/scan-%s.ini' --out '%s' --threads 2%s%s%s", d.path, names[shared], d.path,
                 shared ? " --atlas '" : "", shared ? atlas : "", shared ? "'" : "");
        codes[k] = run(args, out, sizeof out);
        snprintf(path, sizeof path, "%s/scan-%s-scan.csv", d.path, names[shared]);
        csv[k] = gb_check_read_file(path);
    }
    struct stat st;
    const int written = stat(atlas, &st) == 0 && st.st_size > 0;
    /* the CSVs differ only in nothing: the same axes, metrics and fingerprints */
    const int same = csv[0] && csv[1] && csv[2] && !strcmp(csv[0], csv[1]) && !strcmp(csv[0], csv[2]);
    gb_check_true(&cs, codes[0] == 0 && codes[1] == 0 && codes[2] == 0 && same && written,
                  "exits %d, %d, %d; CSVs %s; atlas file %s: %.200s", codes[0], codes[1], codes[2], same ? "equal" : "DIFFER",
                  written ? "written" : "MISSING", out);
    for (int k = 0; k < 3; k++) free(csv[k]);
    /* --atlas with a base scene that certifies per vertical: refused before any run, as gomboc run's */
    snprintf(args, sizeof args, "scan '%s/scan-per-vertical.ini' --out '%s' --atlas '%s/other.atlas'", d.path, d.path, d.path);
    const int refused = run(args, out, sizeof out);
    snprintf(path, sizeof path, "%s/other.atlas", d.path);
    gb_check cr = {"8.3", "-", "gomboc scan --atlas FILE with a base scene whose certificate is per vertical",
                   "exit 2 naming --atlas, the base scene and the allowed value; no atlas written", "exact"};
    gb_check_true(&cr, refused == 2 && strstr(out, "--atlas") && strstr(out, "has no atlas") &&
                       strstr(out, "certificate = atlas") && stat(path, &st) != 0,
                  "exit %d: %.300s", refused, out);
    /* [scan] atlas = shared over the per-vertical base: the atlas beside the outputs, the same CSV */
    snprintf(text, sizeof text, "[scan]\nbase = per-vertical.ini\natlas = shared\nperiods = 4\ntransient_periods = 1\n"
             "metrics = omega_rms, switch_rate\n[x]\nkey = forcing.omega\nfrom = 17\nto = 19\ncount = 2\n[y]\n"
             "key = forcing.A1\nfrom = 1.5\nto = 2\ncount = 2\n");
    const int code = scan_file_run(d.path, "scan-shared", text, " --threads 2", out, sizeof out);
    snprintf(path, sizeof path, "%s/scan-per-vertical-scan.csv", d.path);
    char *reference = gb_check_read_file(path);
    snprintf(path, sizeof path, "%s/scan-shared-scan.csv", d.path);
    char *shared_csv = gb_check_read_file(path);
    snprintf(path, sizeof path, "%s/scan-shared-scan.atlas", d.path);
    const int own = stat(path, &st) == 0 && st.st_size > 0;
    gb_check ck = {"4, 8.3", "29", "[scan] atlas = shared over a base scene that certifies per vertical (2 x 2 points, 2 threads)",
                   "the per-vertical scan's CSV, byte for byte; NAME-scan.atlas written beside it", "exact"};
    const int equal = reference && shared_csv && !strcmp(reference, shared_csv);
    gb_check_true(&ck, code == 0 && equal && own, "exit %d; CSV %s; atlas %s: %.200s", code, equal ? "equal" : "DIFFERS",
                  own ? "written" : "MISSING", out);
    /* [scan] atlas_file: two scans name one atlas in the output directory (as the ensembles of one body do);
     * the second takes every cell from it (none proved: the file is not written again) */
    char named_path[2][512];
    struct stat named_st[2];
    int named_code[2], named_equal = 1;
    for (int k = 0; k < 2; k++) {
        snprintf(text, sizeof text, "[scan]\nbase = per-vertical.ini\natlas = shared\natlas_file = body.atlas\nperiods = 4\n"
                 "transient_periods = 1\nmetrics = omega_rms, switch_rate\n[x]\nkey = forcing.omega\nfrom = 17\nto = 19\n"
                 "count = 2\n[y]\nkey = forcing.A1\nfrom = 1.5\nto = 2\ncount = 2\n");
        named_code[k] = scan_file_run(d.path, k ? "named-again" : "named", text, k ? " --threads 1" : " --threads 2", out, sizeof out);
        snprintf(path, sizeof path, "%s/%s-scan.csv", d.path, k ? "named-again" : "named");
        char *csv = gb_check_read_file(path);
        named_equal &= reference && csv && !strcmp(reference, csv);
        free(csv);
        snprintf(named_path[k], sizeof named_path[k], "%s/body.atlas", d.path);
        if (stat(named_path[k], &named_st[k])) named_st[k].st_ino = 0, named_st[k].st_size = 0;
    }
    snprintf(path, sizeof path, "%s/named-scan.atlas", d.path);
    const int no_own = stat(path, &st) != 0;
    gb_check ca = {"4, 8.3", "29", "[scan] atlas_file = body.atlas in two scans (2 x 2 points each)",
                   "the per-vertical scan's CSV, byte for byte, twice; one atlas file, not written again by the second scan",
                   "exact"};
    const int kept = named_st[0].st_size > 0 && named_st[0].st_ino == named_st[1].st_ino &&
                     named_st[0].st_mtim.tv_sec == named_st[1].st_mtim.tv_sec &&
                     named_st[0].st_mtim.tv_nsec == named_st[1].st_mtim.tv_nsec;
    gb_check_true(&ca, named_code[0] == 0 && named_code[1] == 0 && named_equal && kept && no_own,
                  "exits %d, %d; CSVs %s; body.atlas %s (%lld bytes); NAME-scan.atlas %s", named_code[0], named_code[1],
                  named_equal ? "equal" : "DIFFER", kept ? "read, not rewritten" : "REWRITTEN OR MISSING",
                  (long long)named_st[0].st_size, no_own ? "not written" : "WRITTEN");
    /* ... a name with a directory, or without atlas = shared: refused before any run */
    snprintf(text, sizeof text, "[scan]\nbase = per-vertical.ini\natlas = shared\natlas_file = ../body.atlas\nperiods = 4\n"
             "transient_periods = 1\n[x]\nkey = forcing.omega\nfrom = 17\nto = 19\ncount = 2\n[y]\nkey = forcing.A1\nfrom = 1.5\n"
             "to = 2\ncount = 2\n");
    const int slash_code = scan_file_run(d.path, "named-slash", text, "", out, sizeof out);
    const int slash_named = strstr(out, "named-slash.ini:4: [scan] atlas_file = ../body.atlas: not a file name") != NULL;
    snprintf(text, sizeof text, "[scan]\nbase = per-vertical.ini\natlas_file = body.atlas\nperiods = 4\n"
             "transient_periods = 1\n[x]\nkey = forcing.omega\nfrom = 17\nto = 19\ncount = 2\n[y]\nkey = forcing.A1\nfrom = 1.5\n"
             "to = 2\ncount = 2\n");
    const int alone_code = scan_file_run(d.path, "named-alone", text, "", out, sizeof out);
    const int alone_named = strstr(out, "named-alone.ini:3: [scan] atlas_file = body.atlas without atlas = shared") != NULL;
    gb_check cb = {"8.3", "-", "[scan] atlas_file = ../body.atlas, and atlas_file without atlas = shared",
                   "exit 2 naming the file, line, key and what is allowed", "exact"};
    gb_check_true(&cb, slash_code == 2 && slash_named && alone_code == 2 && alone_named, "exits %d, %d: %.300s", slash_code,
                  alone_code, out);
    free(reference);
    free(shared_csv);
    /* 3 x 3 points on one thread: the thread's atlas is merged with the file and written back after its
     * 8th point and at its end (gomboc_scan.c), and the CSV is still the per-vertical one */
    static const char nine[] = "[scan]\nbase = per-vertical.ini\n%speriods = 4\ntransient_periods = 1\n"
                               "metrics = omega_rms, switch_rate\n[x]\nkey = forcing.omega\nfrom = 17\nto = 19\n"
                               "count = 3\n[y]\nkey = forcing.A1\nfrom = 1.5\nto = 2\ncount = 3\n";
    int nine_code[2];
    char *nine_csv[2];
    for (int k = 0; k < 2; k++) {
        snprintf(text, sizeof text, nine, k ? "atlas = shared\n" : "");
        nine_code[k] = scan_file_run(d.path, k ? "nine-shared" : "nine-per-vertical", text, " --threads 1", out, sizeof out);
        snprintf(path, sizeof path, "%s/%s-scan.csv", d.path, k ? "nine-shared" : "nine-per-vertical");
        nine_csv[k] = gb_check_read_file(path);
    }
    snprintf(path, sizeof path, "%s/nine-shared-scan.atlas", d.path);
    const int nine_atlas = stat(path, &st) == 0 && st.st_size > 0;
    gb_check cn = {"4, 8.3", "29", "[scan] atlas = shared, 3 x 3 points on one thread (its atlas kept in memory, merged with "
                   "the file after 8 points and at the end)", "the per-vertical scan's CSV, byte for byte; the atlas written",
                   "exact"};
    const int nine_equal = nine_csv[0] && nine_csv[1] && !strcmp(nine_csv[0], nine_csv[1]);
    gb_check_true(&cn, nine_code[0] == 0 && nine_code[1] == 0 && nine_equal && nine_atlas, "exits %d, %d; CSV %s; atlas %s",
                  nine_code[0], nine_code[1], nine_equal ? "equal" : "DIFFERS", nine_atlas ? "written" : "MISSING");
    free(nine_csv[0]);
    free(nine_csv[1]);
    /* ... and over a base without continuous contact: refused, naming the scan file's line */
    snprintf(path, sizeof path, "%s/grid.ini", d.path);
    spill(path, "[body]\nmorphology = I\nbeta = 0.12\n[model]\ncontact = fast-grid\n");
    snprintf(text, sizeof text, "[scan]\nbase = grid.ini\nperiods = 4\ntransient_periods = 1\natlas = shared\n[x]\n"
             "key = forcing.omega\nfrom = 17\nto = 19\ncount = 2\n[y]\nkey = forcing.A1\nfrom = 1.5\nto = 2\ncount = 2\n");
    const int grid_code = scan_file_run(d.path, "scan-grid", text, "", out, sizeof out);
    snprintf(path, sizeof path, "%s/scan-grid-scan.csv", d.path);
    gb_check cg = {"8.3", "-", "[scan] atlas = shared with a base scene of fast-grid contact",
                   "exit 2 naming the scan file's line 5, the key and the allowed values; no output", "exact"};
    gb_check_true(&cg, grid_code == 2 && strstr(out, "scan-grid.ini:5: [scan] atlas = shared") && strstr(out, "allowed") &&
                       stat(path, &st) != 0,
                  "exit %d: %.300s", grid_code, out);
    /* Two scans of one atlas_file at once, 2 threads each, 3 times: then both again, one after the other,
     * prove nothing (the file is byte for byte what the two left): the merge kept every cell either proved,
     * where the two decomposed a cell differently too (a cell's fate depends on the verticals that first
     * needed it). */
    static const char racing[] = "[scan]\nbase = race-base.ini\natlas = shared\natlas_file = race.atlas\nperiods = 12\n"
                                 "transient_periods = 1\nmetrics = omega_rms\n[x]\nkey = forcing.omega\nfrom = %s\nto = %s\n"
                                 "count = 4\n[y]\nkey = forcing.A1\nfrom = 1.5\nto = 2.5\ncount = 2\n";
    snprintf(path, sizeof path, "%s/race-base.ini", d.path);
    spill(path, "[model]\nequation = rolling\ncontact = continuous\n[integrator]\nperiods = 12\nlocate_switches = yes\n");
    for (int k = 0; k < 2; k++) {
        snprintf(text, sizeof text, racing, k ? "16" : "15", k ? "19" : "17");
        snprintf(path, sizeof path, "%s/race-%c.ini", d.path, 'a' + k);
        spill(path, text);
    }
    int race_kept = 0, race_codes = 0;
    for (int trial = 0; trial < 3; trial++) {
        snprintf(path, sizeof path, "%s/race.atlas", d.path);
        remove(path);
        snprintf(args, sizeof args, "scan '%s/race-a.ini' --out '%s' --threads 2 2>/dev/null & %s scan '%s/race-b.ini' --out '%s' "
                 "--threads 2 2>/dev/null; wait $!", d.path, d.path, binary(), d.path, d.path);
        race_codes += run(args, out, sizeof out) != 0;
        char *left = gb_check_read_file(path);
        struct stat before_st;
        const int had = stat(path, &before_st) == 0;
        for (int k = 0; k < 2; k++) {
            snprintf(args, sizeof args, "scan '%s/race-%c.ini' --out '%s' --threads 1", d.path, 'a' + k, d.path);
            race_codes += run(args, out, sizeof out) != 0;
        }
        char *again = gb_check_read_file(path);
        race_kept += had && left && again && before_st.st_size > 0 && !memcmp(left, again, (size_t)before_st.st_size) &&
                     strlen(left) == strlen(again);
        free(left), free(again);
    }
    gb_check cc = {"4, 8.3", "29", "two scans sharing [scan] atlas_file at once (4 x 2 points, 2 threads each), then each again "
                   "alone, 3 trials", "every run exit 0; the reruns prove no cell (the atlas file unchanged)", "exact"};
    gb_check_true(&cc, race_codes == 0 && race_kept == 3, "%d runs failed; the file unchanged by the reruns in %d of 3 trials",
                  race_codes, race_kept);
    remove_scan_dir(&d);
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
        {"section 8.3: the library's runner: threads, ranks and points done give each point's own row", test_library_runner,
         "gb_scan_run, the library's parallel runner, gives each point's own run on any threads and ranks"},
        {"section 8.3: threads, kill -9 and --resume give the same bytes", test_threads_and_resume,
         "a scan's CSV does not depend on the thread count or on an interruption"},
        {"section 8.3: a journal is verified line by line, never trusted", test_journal_verified,
         "a resumed scan takes from its journal only rows it can verify"},
        {"section 8.3: a point out of its key's range is refused before any run", test_point_out_of_range, NULL},
        {"sections 4, 8.3: one atlas of verticals for a whole scan", test_scan_atlas,
         "the points of a scan can share one atlas of verticals through its file, with the per-vertical certificate's results"},
        {"section 8.3: a disk that fills stops the scan, and --resume finishes it", test_disk_full,
         "a scan that cannot write its journal stops, names it, and loses none of the points it wrote"},
        {"Figs 10-13: the shipped maps read, and hold Table 1's point", test_shipped_scans, NULL},
        {"ensembles: random initial attitudes, seeded and uniform on the rotations", test_random_attitudes, NULL},
        {"ensembles: the lifetime of the chaos in a record", test_chaos_lifetime, NULL},
        {"windowed exponents: known records, and gomboc run's windows file", test_windowed_exponents, NULL},
        {NULL, NULL, NULL},
    };
    static const verify_test mpi_tests[] = {
        {"section 8.3: 1, 2 and 3 MPI ranks, kill -9 and --resume give the same bytes", test_mpi_ranks,
         "a scan's CSV does not depend on the number of MPI ranks or on an interruption of all of them"},
        {NULL, NULL, NULL},
    };
    /* The ranks' checks need an MPI build (make mpi; make verify builds one where mpicc is). */
    return verify_register_suite("Section 8.3: parameter scans", tests) ||
           (mpi_binary() && getenv("GOMBOC_MPIRUN") && verify_register_suite("Section 8.3: scans on MPI ranks", mpi_tests));
}
