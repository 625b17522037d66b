/* make bench: the certified run's headroom, work against precision through branch switches (against scipy),
 * and the Melnikov analysis. */
#include "gb_case.h"
#include "gb_contact.h"
#include "gb_error.h"
#include "gb_integrate.h"
#include "gb_lyapunov_body.h"
#include "gb_massprops.h"
#include "gb_melnikov_body.h"
#include "gb_surface_internal.h"
#include "bench.h"
#include "plain.h"
#include <cjson/cJSON.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdint.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* ---------------------------------------------------------------- headroom of the certified run
 *
 * Why the certified continuous run is far from 50x, measured: (1) its time inside the certificate's
 * checks and outside them (the dynamics with its Newton solves and RK4), the latter bounding the ratio
 * any certificate could reach with this dynamics; (2) at states sampled along the run, the widest
 * basin (centred box on which the range of h's chart Hessian d.x'' passes the certificate's
 * definiteness test) with the range from one interval enclosure, as the certificate computes it, and
 * with the range sampled on a 25 x 25 grid of points (an inner estimate of the exact range, so the
 * width it allows is if anything too generous). Both widths are found by growing from 1e-3 in steps of
 * 10 % up to the certificate's cap of 0.25 rad. */
enum { HEADROOM_SAMPLES = 40, HESSIAN_GRID = 24 };

typedef struct sampled_state {
    double d[3];
    gb_surface_chart chart;
    double a, b; /* the contact's chart coordinates */
} sampled_state;

typedef struct sampler {
    gb_dynamics *dynamics;
    size_t calls, count;
    sampled_state s[HEADROOM_SAMPLES];
} sampler;

static int take_sample(void *context, double t, const double y[GB_STATE_SIZE])
{
    sampler *sp = context;
    if (sp->calls++ == 0 || sp->count == HEADROOM_SAMPLES) return 0; /* not the initial state */
    gb_dynamics_observables o;
    if (gb_dynamics_observe(sp->dynamics, t, y, &o)) return 1;
    sampled_state *q = &sp->s[sp->count++];
    const double zn = sqrt(o.zb[0] * o.zb[0] + o.zb[1] * o.zb[1] + o.zb[2] * o.zb[2]);
    const double rn = sqrt(o.rc[0] * o.rc[0] + o.rc[1] * o.rc[1] + o.rc[2] * o.rc[2]);
    for (int k = 0; k < 3; k++) q->d[k] = o.zb[k] / zn;
    double theta = atan2(o.rc[1], o.rc[0]);
    if (theta < 0.0) theta += 2.0 * M_PI;
    const double phi = acos(o.rc[2] / rn);
    /* the certificate's regions: (phi, theta) on 0.8 <= phi <= pi - 0.8, the polar-x caps elsewhere */
    q->chart = phi >= 0.8 && phi <= M_PI - 0.8 ? GB_SURFACE_CHART_POLAR_Z : GB_SURFACE_CHART_POLAR_X;
    gb_surface_chart_coordinates(q->chart, phi, theta, &q->a, &q->b);
    return 0;
}

/* The certificate's definiteness test on the ranges of (h_aa, h_ab, h_bb), with its allowance 1e-12
 * (HESSIAN_ROUNDING in gb_certify.c). */
static int ranges_definite(const double lo[3], const double hi[3])
{
    const double m = fmax(fabs(lo[1]), fabs(hi[1]));
    return lo[0] > 1e-12 && lo[2] > 1e-12 && lo[0] * lo[2] - m * m > 1e-12;
}

/* Does the range of d.x'' over the box of half-width w about the state pass the definiteness test?
 * sampled = 0: from one enclosure of the box; 1: from a grid of point values. */
static int basin_passes(const gb_surface *s, const sampled_state *q, double w, int sampled)
{
    const double a_lo = fmax(q->a - w, 0.05), a_hi = fmin(q->a + w, M_PI - 0.05);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    const int n = sampled ? HESSIAN_GRID : 0;
    for (int i = 0; i <= n; i++)
        for (int j = 0; j <= n; j++) {
            gb_surface_enclosure e;
            if (sampled) {
                const double a = a_lo + (a_hi - a_lo) * i / n, b = q->b - w + 2.0 * w * j / n;
                gb_surface_enclose(s, q->chart, a, a, b, b, &e);
            } else {
                gb_surface_enclose(s, q->chart, a_lo, a_hi, q->b - w, q->b + w, &e);
            }
            const gb_interval *second[3] = {e.x_aa, e.x_ab, e.x_bb};
            for (int r = 0; r < 3; r++) {
                double l = 0.0, h = 0.0;
                for (int k = 0; k < 3; k++) {
                    const double p0 = q->d[k] * second[r][k].lo, p1 = q->d[k] * second[r][k].hi;
                    l += sampled ? 0.5 * (p0 + p1) : fmin(p0, p1);
                    h += sampled ? 0.5 * (p0 + p1) : fmax(p0, p1);
                }
                lo[r] = fmin(lo[r], l), hi[r] = fmax(hi[r], h);
            }
        }
    return ranges_definite(lo, hi);
}

/* The widest half-width from `start` in steps of 10 % (up to 0.25) whose test passes; `start` if none. */
static double widest_basin(const gb_surface *s, const sampled_state *q, double start, int sampled)
{
    double w = start;
    while (w * 1.1 <= 0.25 && basin_passes(s, q, w * 1.1, sampled)) w *= 1.1;
    return w;
}

void bench_headroom(void)
{
    printf("\nbench: what the certified continuous run spends, and how wide its basins could be\n"
           "(one Table 1 run with the certificate's checks timed, best of 2; basins at %d states sampled along the "
           "run)\n\n", HEADROOM_SAMPLES);
    for (int m = 0; m < 2; m++) {
        const char *name = m ? "II" : "I";
        gb_certify_def timed = gb_certify_default_def();
        timed.time_checks = 1;
        double y[GB_STATE_SIZE];
        size_t switches;
        const double total = time_run_with(name, GB_CONTACT_MODEL_CONTINUOUS, GB_VARIANT_ROLLING, 2, &timed, y, &switches);
        const gb_certify_stats cs = last_certificate;
        const double outside = total - cs.check_seconds;
        /* the sampled states: a second run of the same scene */
        gb_dynamics_def def = gb_dynamics_default_def();
        def.contact = GB_CONTACT_MODEL_CONTINUOUS, def.variant = GB_VARIANT_ROLLING;
        const double R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, w0[3] = {0, 0, 0};
        sampler sp = {0};
        gb_integrate_def idef = gb_integrate_default_def();
        gb_integrate_stats stats;
        idef.sample_every = (size_t)(idef.periods * idef.steps_per_period) / HEADROOM_SAMPLES;
        if (gb_dynamics_start(bench_body(name, 0.12), &def, R0, w0, &sp.dynamics, y) ||
            gb_integrate_run(sp.dynamics, &idef, 0.0, y, take_sample, &sp, &stats)) {
            fprintf(stderr, "bench: %s\n", gb_error_message());
            exit(1);
        }
        gb_dynamics_free(sp.dynamics);
        gb_surface surface;
        gb_surface_init(&surface, name, 0.12);
        double log_enclosed = 0.0, log_sampled = 0.0, least_ratio = INFINITY, most_ratio = 0.0;
        for (size_t k = 0; k < sp.count; k++) {
            const double we = widest_basin(&surface, &sp.s[k], 1e-3, 0);
            const double ws = widest_basin(&surface, &sp.s[k], we, 1);
            log_enclosed += log(we), log_sampled += log(ws);
            least_ratio = fmin(least_ratio, ws / we), most_ratio = fmax(most_ratio, ws / we);
        }
        const double enclosed = exp(log_enclosed / (double)sp.count), sampled = exp(log_sampled / (double)sp.count);
        /* against the honest baseline (the best plain loop) where it ran, else the shipped library loop */
        const double baseline = native_seconds[m] > 0.0 ? native_seconds[m] : plain_seconds[m];
        const double built = cs.minimum_basins ? exp(cs.basin_log_width_sum / (double)cs.minimum_basins) : NAN;
        printf("%-3s continuous run %.3f s: %.3f s inside %zu certificate checks, %.3f s outside them (the dynamics, "
               "its Newton solves, RK4)\n    -> with a certificate that cost nothing: at most %.1fx the plain loop (%.3f s)\n",
               name, total, cs.check_seconds, cs.checks, outside, baseline / outside, baseline);
        printf("    basin half-width, geometric mean over %zu sampled states: %.4f rad from one enclosure, %.4f rad "
               "from sampled ranges (x%.1f; x%.1f to x%.1f); basins built in the run: %zu, %.4f rad\n",
               sp.count, enclosed, sampled, sampled / enclosed, least_ratio, most_ratio, cs.minimum_basins, built);
        if (record)
            fprintf(record, ",\n  {\"body\": \"%s\", \"headroom_total_seconds\": %.6f, \"check_seconds\": %.6f, "
                            "\"outside_seconds\": %.6f, \"free_certificate_ratio\": %.3f, \"basin_samples\": %zu, "
                            "\"basin_enclosed_width\": %.6f, \"basin_sampled_width\": %.6f, \"basin_ratio_min\": %.3f, "
                            "\"basin_ratio_max\": %.3f, \"basins_built\": %zu, \"basin_built_width\": %.6f}",
                    name, total, cs.check_seconds, outside, baseline / outside, sp.count, enclosed, sampled,
                    least_ratio, most_ratio, cs.minimum_basins, built);
    }
    printf("\n(target, issue 4: >= 50x; the budget is the plain loop's time / 50 for the whole run)\n");
}

/* ---- work–precision through branch switches ------------------------------------------------------ */

enum { WP_PERIODS = 20 };

/* One 20-period Table 1 rolling run of body `m` (R0 = I, ω0 = 0, continuous contact certified per
 * vertical, every switch located) under `law` with `method` at `setting` (RK4: steps a period; the
 * adaptive steppers: rtol, atol = rtol/100, steps up to T/16; the reference, rtol 1e-13, up to T/160): the integration's seconds (best of `repeats`; set-up not
 * counted, as on scipy's side) and the final state. Returns NAN when the run fails. */
static double wp_run(const char *m, gb_contact_law law, gb_integrator method, double setting, int repeats,
                     double y[GB_STATE_SIZE], size_t *switches)
{
    double best = INFINITY;
    for (int r = 0; r < repeats; r++) {
        gb_surface s;
        gb_surface_init(&s, m, 0.12);
        gb_dynamics_def def = gb_dynamics_default_def();
        def.contact = GB_CONTACT_MODEL_CONTINUOUS, def.variant = GB_VARIANT_ROLLING, def.contact_law = law;
        if (law == GB_CONTACT_LAW_UNILATERAL)
            def.settle_time = gb_forcing_period(&def.forcing) / (double)gb_integrate_default_def().steps_per_period;
        gb_dynamics *d = NULL;
        const double R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, w0[3] = {0, 0, 0};
        if (gb_dynamics_create(&s, &def, &d) || gb_dynamics_init_state(d, 0.0, R0, w0, y)) {
            gb_dynamics_free(d);
            return NAN;
        }
        gb_integrate_def idef = gb_integrate_default_def();
        idef.method = method, idef.periods = WP_PERIODS, idef.locate_switches = 1;
        /* the adaptive steppers choose their steps up to T/16 (at T/160 one step a nominal step is already
         * tighter than every tolerance tried, and the tolerance would not show) */
        if (method == GB_INTEGRATOR_RK4) idef.steps_per_period = (size_t)setting;
        else idef.rtol = setting, idef.atol = setting / 100, idef.steps_per_period = setting < 1e-12 ? 160 : 16;
        idef.sample_every = idef.steps_per_period;
        gb_integrate_stats stats;
        const double start = now();
        const int status = gb_integrate_run(d, &idef, 0.0, y, NULL, NULL, &stats);
        const double t = now() - start;
        gb_dynamics_observables o = {0};
        if (!status) gb_dynamics_observe(d, WP_PERIODS * gb_forcing_period(&def.forcing), y, &o);
        *switches = o.branch_switches;
        gb_dynamics_free(d);
        if (status) return NAN;
        best = fmin(best, t);
    }
    return best;
}

/* max |y - reference| over the quaternion (up to its sign) and ω */
static double wp_error(const double y[7], const double ref[7])
{
    double plus = 0.0, minus = 0.0;
    for (int i = 0; i < 7; i++) {
        plus = fmax(plus, fabs(y[i] - ref[i]));
        minus = fmax(minus, fabs((i < 4 ? -y[i] : y[i]) - ref[i]));
    }
    return fmin(plus, minus);
}

typedef struct wp_point {
    double error, seconds;
} wp_point;

/* The seconds the curve (points of one stepper, any order) needs for `error`: log-log interpolation
 * between the two points that bracket it; NAN when no point of the curve is that accurate. */
static double wp_seconds_at(const wp_point *p, size_t n, double error)
{
    double best = NAN;
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++) {
            if (!(p[i].error >= error && p[j].error <= error && p[i].error > p[j].error)) continue;
            const double u = (log(error) - log(p[i].error)) / (log(p[j].error) - log(p[i].error));
            const double t = exp(log(p[i].seconds) + u * (log(p[j].seconds) - log(p[i].seconds)));
            if (!(t >= best)) best = t;
        }
    for (size_t i = 0; i < n; i++) /* a point at least as accurate costs at most its own time */
        if (p[i].error <= error && !(p[i].seconds >= best)) best = p[i].seconds;
    return best;
}

/* Error against run time over 20 Table 1 periods of the rolling model with its branch switches located:
 * gomboc's RK4 and adaptive steppers, and scipy's DOP853 and Radau through references/switching.py's own
 * switch handling (a grid scan for a lower minimum after every nominal step, brentq on the dense output),
 * in the same run; errors against gomboc's rk8pd at rtol 1e-13, itself compared with switching.json.
 * Then the same diagram under the unilateral law (impacts, two-point rolling) for gomboc alone. */
int bench_work_precision(const char *python)
{
    printf("\nbench: work-precision over %d Table 1 periods of the rolling model, Gomboc I, every branch switch located\n"
           "(integration time only, set-up not counted on either side; errors: max |final state - reference|)\n\n",
           WP_PERIODS);
    static const struct {
        gb_integrator method;
        double settings[5];
    } steppers[] = {{GB_INTEGRATOR_RK4, {80, 160, 320, 640, 1280}},
                    {GB_INTEGRATOR_RK8PD, {1e-5, 1e-7, 1e-9, 1e-11, 1e-12}},
                    {GB_INTEGRATOR_RKF45, {1e-4, 1e-6, 1e-8, 1e-10, 0}},
                    {GB_INTEGRATOR_RK4IMP, {1e-4, 1e-6, 1e-8, 0, 0}}};
    int failures = 0;
    for (int law = 0; law < 2; law++) {
        const gb_contact_law L = law ? GB_CONTACT_LAW_UNILATERAL : GB_CONTACT_LAW_HELD;
        const char *law_name = law ? "unilateral" : "held";
        double ref[GB_STATE_SIZE];
        size_t ref_switches;
        const double ref_seconds = wp_run("I", L, GB_INTEGRATOR_RK8PD, 1e-13, 1, ref, &ref_switches);
        if (!isfinite(ref_seconds)) {
            fprintf(stderr, "bench: the %s reference run failed: %s\n", law_name, gb_error_message());
            failures++;
            continue;
        }
        printf("contact law %s: reference rk8pd rtol 1e-13, %zu branch switches, %.3f s\n", law_name, ref_switches, ref_seconds);
        if (!law) { /* the reference against the stored scipy trajectory (DOP853, rtol 1e-12) at the last period's end */
            FILE *f = fopen("references/switching.json", "r");
            char *text = f ? malloc(1 << 22) : NULL;
            const size_t size = text ? fread(text, 1, (1 << 22) - 1, f) : 0;
            if (f) fclose(f);
            if (text) text[size] = 0;
            cJSON *root = text ? cJSON_Parse(text) : NULL, *c;
            double stored = NAN;
            cJSON_ArrayForEach(c, cJSON_GetObjectItem(root, "cases")) {
                const cJSON *periods = cJSON_GetObjectItem(c, "periods");
                const cJSON *last = cJSON_GetArrayItem(periods, cJSON_GetArraySize(periods) - 1);
                const cJSON *st = cJSON_GetObjectItem(last, "state");
                if (strcmp(cJSON_GetStringValue(cJSON_GetObjectItem(c, "morphology")), "I") || cJSON_GetArraySize(periods) != WP_PERIODS ||
                    cJSON_GetArraySize(st) != 7)
                    continue;
                double y[7];
                for (int i = 0; i < 7; i++) y[i] = cJSON_GetArrayItem(st, i)->valuedouble;
                stored = wp_error(y, ref);
            }
            cJSON_Delete(root);
            free(text);
            printf("the reference against references/switching.json (scipy DOP853 rtol 1e-12) at period %d: %.3g\n", WP_PERIODS,
                   stored);
            if (record && isfinite(stored)) fprintf(record, ",\n  {\"wp_reference_against_stored\": %.6g}", stored);
        }
        printf("%-8s %-10s %12s %12s %10s\n", "tool", "stepper", "setting", "error", "seconds");
        wp_point best_curve[4][5];
        size_t best_n[4] = {0, 0, 0, 0};
        for (size_t k = 0; k < sizeof steppers / sizeof steppers[0]; k++)
            for (int j = 0; j < 5 && steppers[k].settings[j] > 0; j++) {
                double y[GB_STATE_SIZE];
                size_t sw;
                const double t = wp_run("I", L, steppers[k].method, steppers[k].settings[j], 2, y, &sw);
                const double e = isfinite(t) ? wp_error(y, ref) : NAN;
                printf("%-8s %-10s %12.3g %12.3g %10.4f%s\n", "gomboc", gb_integrate_name(steppers[k].method),
                       steppers[k].settings[j], e, t, isfinite(t) ? "" : "  (failed)");
                if (isfinite(t)) best_curve[k][best_n[k]++] = (wp_point){e, t};
                if (record && isfinite(t))
                    fprintf(record, ",\n  {\"wp_law\": \"%s\", \"wp_tool\": \"gomboc\", \"wp_stepper\": \"%s\", \"wp_setting\": %.6g, "
                                    "\"wp_error\": %.6g, \"wp_seconds\": %.6g, \"wp_switches\": %zu}",
                            law_name, gb_integrate_name(steppers[k].method), steppers[k].settings[j], e, t, sw);
                else if (record) /* a run that failed: JSON has no NaN */
                    fprintf(record, ",\n  {\"wp_law\": \"%s\", \"wp_tool\": \"gomboc\", \"wp_stepper\": \"%s\", \"wp_setting\": %.6g, "
                                    "\"wp_failed\": true}",
                            law_name, gb_integrate_name(steppers[k].method), steppers[k].settings[j]);
            }
        if (law) continue; /* scipy's reference model has no impacts */
        /* the reference against the stored scipy trajectory (DOP853 rtol 1e-12) */
        {
            static const struct {
                const char *method;
                double rtol;
            } scipy[] = {{"DOP853", 1e-6}, {"DOP853", 1e-10}, {"Radau", 1e-6}, {"Radau", 1e-9}};
            enum { SCIPY_RUNS = sizeof scipy / sizeof scipy[0] };
            char lines[SCIPY_RUNS][4096];
            int closed[SCIPY_RUNS];
            /* two at a time, one on each core (each single-threaded: OPENBLAS_NUM_THREADS=1), each timing itself */
            for (size_t k = 0; k < SCIPY_RUNS; k += 2) {
                FILE *p[2] = {NULL, NULL};
                for (size_t i = 0; i < 2 && k + i < SCIPY_RUNS; i++) {
                    char command[1024];
                    snprintf(command, sizeof command,
                             "OPENBLAS_NUM_THREADS=1 SWITCHING_FINAL=1 SWITCHING_PERIODS=%d SWITCHING_METHOD=%s SWITCHING_RTOL=%g "
                             "%s references/switching.py I",
                             WP_PERIODS, scipy[k + i].method, scipy[k + i].rtol, python);
                    p[i] = popen(command, "r");
                }
                for (size_t i = 0; i < 2 && k + i < SCIPY_RUNS; i++) {
                    lines[k + i][0] = 0;
                    if (!p[i] || !fgets(lines[k + i], sizeof lines[k + i], p[i])) lines[k + i][0] = 0;
                    closed[k + i] = p[i] ? pclose(p[i]) : -1;
                }
            }
            double worst_ratio = INFINITY;
            for (size_t k = 0; k < SCIPY_RUNS; k++) {
                const char *line = lines[k];
                double y[7] = {0}, seconds = NAN;
                int switches = -1, parsed = 0;
                const char *state = strstr(line, "\"state\": ["), *sec = strstr(line, "\"seconds\": "),
                           *swp = strstr(line, "\"switches\": ");
                if (state && sec && swp) {
                    const char *c = state + 10;
                    char *end;
                    for (parsed = 0; parsed < 7; parsed++) {
                        y[parsed] = strtod(c, &end);
                        if (end == c) break;
                        c = end + (*end == ',' ? 1 : 0);
                    }
                    seconds = strtod(sec + 11, NULL), switches = atoi(swp + 12);
                }
                if (closed[k] != 0 || parsed != 7 || !isfinite(seconds)) {
                    fprintf(stderr, "bench: scipy %s rtol %g: no result (%s)\n", scipy[k].method, scipy[k].rtol, line);
                    failures++;
                    continue;
                }
                const double e = wp_error(y, ref);
                /* gomboc's best stepper at this error: the least time any of its curves needs */
                double fastest = NAN;
                const char *which = "-";
                for (size_t c2 = 0; c2 < 4; c2++) {
                    const double t = wp_seconds_at(best_curve[c2], best_n[c2], e);
                    if (isfinite(t) && !(t >= fastest)) fastest = t, which = gb_integrate_name(steppers[c2].method);
                }
                double ratio = seconds / fastest;
                if (ratio < worst_ratio) worst_ratio = ratio;
                printf("%-8s %-10s %12.3g %12.3g %10.4f   %d switches; gomboc's best at this error: %s, %.4f s = %.0fx\n",
                       "scipy", scipy[k].method, scipy[k].rtol, e, seconds, switches, which, fastest, ratio);
                if (!isfinite(ratio)) { /* no gomboc curve reaches this error: nothing to compare */
                    fastest = ratio = 0.0;
                    which = "none as accurate";
                }
                if (record)
                    fprintf(record, ",\n  {\"wp_law\": \"held\", \"wp_tool\": \"scipy\", \"wp_stepper\": \"%s\", \"wp_setting\": %.6g, "
                                    "\"wp_error\": %.6g, \"wp_seconds\": %.6g, \"wp_switches\": %d, \"wp_gomboc_best\": \"%s\", "
                                    "\"wp_gomboc_seconds\": %.6g, \"wp_ratio\": %.6g}",
                            scipy[k].method, scipy[k].rtol, e, seconds, switches, which, fastest, ratio);
            }
            printf("\n(target, issue 30: gomboc's best stepper >= 50x scipy's at equal error; least ratio measured: %.0fx)\n\n",
                   worst_ratio);
        }
    }
    return failures;
}

/* A scan's Melnikov plan (section 7): one body's reduced model and its integrals at the 25 frequencies of
 * the (omega, A1) maps (12 to 24 rad/s), from the separatrix tables (what gomboc scan and gomboc melnikov
 * do) and, side by side, by the adaptive quadrature at every frequency; the largest difference of the
 * integrals between the two, relative to the largest integral. Best of 2 for the tables, one adaptive run. */
int bench_melnikov(void)
{
    printf("\nbench: a scan's Melnikov plan, 25 frequencies 12 ... 24 rad/s, Table 1's g and mass\n\n");
    printf("%-4s %16s %16s %18s %10s %16s\n", "body", "reduced model [s]", "tables, 25 w [s]", "adaptive, 25 w [s]", "speed-up",
           "max difference");
    const gb_forcing F = gb_dynamics_default_def().forcing;
    int failures = 0;
    for (int k = 0; k < 2; k++) {
        const char *name = k ? "II" : "I";
        double body_seconds = INFINITY, tables_seconds = INFINITY, adaptive_seconds = NAN, worst = 0.0, scale = 0.0;
        gb_melnikov_integrals tabulated[25];
        int status = 0;
        for (int repeat = 0; repeat < 2 && !status; repeat++) {
            gb_melnikov_body *b = NULL;
            gb_melnikov_tables *tables = NULL;
            gb_melnikov_orbit o;
            double start = now();
            status = gb_melnikov_body_create(bench_body(name, 0.12), gb_dynamics_default_def().mass, F.g, GB_MELNIKOV_BODY_NODES, &b);
            gb_melnikov_model m = {0};
            if (!status) m = gb_melnikov_body_model(b, GB_MELNIKOV_MASS_AT_TOP), status = gb_melnikov_orbit_find(&m, &o);
            body_seconds = fmin(body_seconds, now() - start);
            start = now();
            if (!status) status = gb_melnikov_tables_create(&m, &o, GB_MELNIKOV_EXACT, &tables);
            for (int j = 0; j < 25 && !status; j++) {
                const double omega = 12.0 + 0.5 * j;
                status = gb_melnikov_tables_prepare(tables, omega);
                if (!status) status = gb_melnikov_tables_integrals(tables, omega, &tabulated[j]);
            }
            tables_seconds = fmin(tables_seconds, now() - start);
            if (repeat == 1 && !status) {
                start = now();
                for (int j = 0; j < 25 && !status; j++) {
                    gb_melnikov_integrals a;
                    status = gb_melnikov_integrals_compute(&m, &o, 12.0 + 0.5 * j, GB_MELNIKOV_EXACT, &a);
                    const double x[] = {a.D, a.C1, a.S1, a.C2, a.S2, a.D_mass}, y[] = {tabulated[j].D, tabulated[j].C1,
                        tabulated[j].S1, tabulated[j].C2, tabulated[j].S2, tabulated[j].D_mass};
                    for (int i = 0; i < 6; i++) worst = fmax(worst, fabs(x[i] - y[i])), scale = fmax(scale, fabs(x[i]));
                }
                adaptive_seconds = now() - start;
            }
            gb_melnikov_tables_free(tables);
            gb_melnikov_body_free(b);
        }
        if (status) {
            fprintf(stderr, "bench: the Melnikov plan of Gomboc %s: %s\n", name, gb_error_message());
            failures++;
            continue;
        }
        printf("%-4s %16.3f %16.4f %18.2f %9.0fx %16.2g\n", name, body_seconds, tables_seconds, adaptive_seconds,
               adaptive_seconds / tables_seconds, worst / scale);
        if (record)
            fprintf(record, ",\n  {\"melnikov_body\": \"%s\", \"reduced_model_seconds\": %.6f, \"tables_seconds\": %.6f, "
                            "\"adaptive_seconds\": %.6f, \"max_relative_difference\": %.3g}",
                    name, body_seconds, tables_seconds, adaptive_seconds, worst / scale);
    }
    printf("\n(target, issue 30: the reduced model and 25 frequencies <= 1 s)\n");
    return failures;
}
