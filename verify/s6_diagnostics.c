/* Paper §6 (eqs 73–74) and §8.2 (Figs 7–8): stroboscopic sampling and power spectra.
 *
 * The strobe is checked where the stroboscopic map is known in closed form — the steady state of a
 * damped, harmonically forced linear oscillator, and the period-2 orbit of the logistic map — and on
 * the Gömböc, where a strobe sample must be the very state of a run stopped at that instant. The
 * spectrum is checked against closed forms (a sinusoid on a bin: where its peak is and, by Parseval,
 * how much power it carries) and against scipy.signal.periodogram on stored signals. The reference
 * trajectory of the Lyapunov pair is checked to be the scene's plain run, bit for bit, so that
 * Figs 7–9 of one scene describe one trajectory. */
#include "gb_check.h"
#include "gb_error.h"
#include "gb_integrate.h"
#include "gb_lyapunov_body.h"
#include "gb_run.h"
#include "gb_spectrum.h"
#include "gb_strobe.h"
#include "verify_sections.h"

#include <cjson/cJSON.h>
#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- strobe: closed forms */

/* x'' + 2ζx' + x = F cos Ωt. Steady state x = Re[F e^{iΩt} / (1 − Ω² + 2iζΩ)]. */
typedef struct oscillator {
    double zeta, force, Omega;
} oscillator;

static int oscillator_rhs(double t, const double y[], double dydt[], void *params)
{
    const oscillator *o = params;
    dydt[0] = y[1];
    dydt[1] = o->force * cos(o->Omega * t) - 2.0 * o->zeta * y[1] - y[0];
    return GSL_SUCCESS;
}

static void oscillator_steady(const oscillator *o, double t, double out[2])
{
    const double re = 1.0 - o->Omega * o->Omega, im = 2.0 * o->zeta * o->Omega, d = re * re + im * im;
    const double ar = o->force * re / d, ai = -o->force * im / d; /* F / (re + i im) */
    const double c = cos(o->Omega * t), s = sin(o->Omega * t);
    out[0] = ar * c - ai * s;
    out[1] = o->Omega * (-ar * s - ai * c);
}

/* The strobe of an rk8pd run with `spp` fixed steps per period over `periods` periods; returns the
 * largest deviation from the steady state over the kept samples. */
static double oscillator_strobe(const oscillator *o, size_t spp, size_t periods, const gb_strobe_def *def,
                                size_t *kept, double *time_error, size_t *period)
{
    const double T = 2.0 * M_PI / o->Omega, h = T / (double)spp;
    gsl_odeiv2_system sys = {oscillator_rhs, NULL, 2, (void *)o};
    gsl_odeiv2_step *step = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, 2);
    gb_strobe strobe;
    double y[2] = {1.0, 0.0}, err[2], worst = 0.0;
    *time_error = 0.0;
    if (!step || gb_strobe_init(&strobe, 2, 0.0, T, spp, def)) return NAN;
    gb_strobe_offer(&strobe, 0.0, y, NULL);
    for (size_t k = 1; k <= periods * spp; k++) {
        const double t = (double)(k - 1) * h;
        if (gsl_odeiv2_step_apply(step, t, h, y, err, NULL, NULL, &sys) != GSL_SUCCESS) worst = NAN;
        gb_strobe_offer(&strobe, (double)k * h, y, NULL);
    }
    for (size_t n = 0; n < strobe.count; n++) {
        double exact[2];
        const double t_n = ((double)(def->transient + n) + def->phase) * T;
        oscillator_steady(o, t_n, exact);
        worst = fmax(worst, fmax(fabs(strobe.x[2 * n] - exact[0]), fabs(strobe.x[2 * n + 1] - exact[1])));
        *time_error = fmax(*time_error, fabs(strobe.t[n] - t_n));
    }
    *kept = strobe.count;
    if (period) *period = gb_strobe_period(strobe.x, strobe.count, 2, 32, 8, 1e-9);
    gb_strobe_free(&strobe);
    gsl_odeiv2_step_free(step);
    return worst;
}

static void test_strobe_closed_forms(void)
{
    /* ζ = 0.1, Ω = 1.3: after 60 periods the free transient is below e^{−ζ·60T} ≈ 2.5e-13 of its start. */
    const oscillator o = {0.1, 0.8, 1.3};
    const gb_strobe_def def = {.transient = 60, .phase = 0.25};
    size_t kept = 0, kept2 = 0, p = 0;
    double terr, terr2;
    const double e200 = oscillator_strobe(&o, 200, 100, &def, &kept, &terr, &p);
    const double e400 = oscillator_strobe(&o, 400, 100, &def, &kept2, &terr2, NULL);
    const double T = 2.0 * M_PI / o.Omega, transient = exp(-o.zeta * 60.0 * T) * 2.0;
    gb_check cn = {"6", "74", "strobe samples kept: t_n = (n + 1/4) T, n = 60 ... 99", "40 by construction", "exact"};
    gb_check_true(&cn, kept == 40 && kept2 == 40, "kept %zu and %zu samples", kept, kept2);
    gb_check ct = {"6", "74", "strobe times t_n against (n + phase) T", "eq 74", "rounding of n h (1e3 steps of T/200: 1e-12 s)"};
    gb_check_close(&ct, fmax(terr, terr2), 0.0, 0.0, 1e-12);
    gb_check cx = {"6", "73", "damped forced oscillator: strobe samples against the steady state (x, x')",
                   "closed form F/(1 - Omega^2 + 2i zeta Omega)",
                   "free transient e^(-zeta 60 T) x 2 plus rk8pd error, bounded by the run at T/400 (step halving)"};
    gb_check_close(&cx, e200, 0.0, 0.0, transient + 2.0 * fmax(e400, 1e-14) + 1e-13);
    gb_check cp = {"6", "73", "damped forced oscillator: detected period of the strobe", "1 (a fixed point of P)", "exact"};
    gb_check_true(&cp, p == 1, "detected period %zu", p);

    /* The logistic map as a "flow" sampled once per step: its strobe is the orbit itself. */
    static const struct { double r; size_t period; } maps[] = {{3.2, 2}, {3.5, 4}, {3.835, 3}, {4.0, 0}};
    for (size_t m = 0; m < 4; m++) {
        gb_strobe orbit;
        const gb_strobe_def every = {.transient = 2000, .phase = 0.0};
        gb_strobe_init(&orbit, 1, 0.0, 1.0, 1, &every);
        double x = 0.2345;
        for (size_t k = 0; k <= 2256; k++) {
            gb_strobe_offer(&orbit, (double)k, &x, NULL);
            x = maps[m].r * x * (1.0 - x);
        }
        const size_t found = gb_strobe_period(orbit.x, orbit.count, 1, 128, 16, 1e-12);
        char q[120];
        snprintf(q, sizeof q, "logistic map r = %g: detected period of the orbit", maps[m].r);
        gb_check c = {"6", "73", q, maps[m].period ? "the attracting cycle's period" : "none up to 16 (chaotic, r = 4)", "exact"};
        gb_check_true(&c, found == maps[m].period, "detected %zu, expected %zu", found, maps[m].period);
        if (maps[m].r == 3.2) {
            /* x± = ((r + 1) ± sqrt((r − 3)(r + 1))) / (2r); the cycle multiplier 4 + 2r − r² = 0.16. */
            const double r = 3.2, root = sqrt((r - 3.0) * (r + 1.0));
            const double hi = (r + 1.0 + root) / (2.0 * r), last = orbit.x[orbit.count - 1], prev = orbit.x[orbit.count - 2];
            gb_check cv = {"6", "73", "logistic map r = 3.2: the larger point of the 2-cycle", "((r+1) + sqrt((r-3)(r+1)))/(2r)",
                           "4 ulp (after 2000 iterations the multiplier 0.16^1000 has removed the start)"};
            gb_check_close(&cv, fmax(last, prev), hi, 4.0 * DBL_EPSILON, 0.0);
        }
        gb_strobe_free(&orbit);
    }
    gb_check ce = {"6", "74", "strobe phase off the step grid (0.3 of a period with 4 steps)", "GB_EDOM", "exact"};
    gb_strobe bad;
    const gb_strobe_def off = {.transient = 0, .phase = 0.3};
    gb_check_true(&ce, gb_strobe_init(&bad, 1, 0.0, 1.0, 4, &off) == GB_EDOM, "%s", gb_error_message());
}

/* ---------------------------------------------------------------- strobe and λ on the Gömböc */

typedef struct strobe_sampler {
    gb_dynamics *dynamics;
    gb_strobe strobe;
} strobe_sampler;

static int strobe_sample(void *context, double t, const double y[GB_STATE_SIZE])
{
    strobe_sampler *s = context;
    return gb_strobe_offer(&s->strobe, t, y, NULL) != GB_OK;
}

static void test_strobe_gomboc(void)
{
    static const gb_contact_model models[2] = {GB_CONTACT_MODEL_FAST_GRID, GB_CONTACT_MODEL_CONTINUOUS};
    const double R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, w0[3] = {0, 0, 0};
    for (int m = 0; m < 2; m++) {
        gb_dynamics_def def = gb_dynamics_default_def();
        def.contact = models[m];
        def.variant = m ? GB_VARIANT_ROLLING : GB_VARIANT_PAPER;
        gb_integrate_def idef = gb_integrate_default_def();
        idef.periods = 8.0;
        const double T = 2.0 * M_PI / def.forcing.omega;
        const gb_strobe_def sdef = {.transient = 3, .phase = 0.25};
        strobe_sampler s = {0};
        double y[GB_STATE_SIZE];
        int status = gb_dynamics_start(gb_check_body("I", 0.12), &def, R0, w0, &s.dynamics, y);
        if (!status) status = gb_strobe_init(&s.strobe, GB_STATE_SIZE, 0.0, T, idef.steps_per_period, &sdef);
        gb_integrate_stats stats;
        if (!status) status = gb_integrate_run(s.dynamics, &idef, 0.0, y, strobe_sample, &s, &stats);
        gb_dynamics_free(s.dynamics);
        /* Each strobe sample against a fresh run stopped at t_n = (n + 1/4) T. */
        size_t mismatches = 0;
        for (size_t n = 0; !status && n < s.strobe.count; n++) {
            gb_dynamics *d = NULL;
            double z[GB_STATE_SIZE];
            gb_integrate_def stop = idef;
            stop.periods = (double)(sdef.transient + n) + sdef.phase;
            status = gb_dynamics_start(gb_check_body("I", 0.12), &def, R0, w0, &d, z);
            if (!status) status = gb_integrate_run(d, &stop, 0.0, z, NULL, NULL, &stats);
            mismatches += !status && memcmp(z, s.strobe.x + n * GB_STATE_SIZE, sizeof z) != 0;
            gb_dynamics_free(d);
        }
        char q[160];
        snprintf(q, sizeof q, "Gomboc I, %s: strobe samples (n + 1/4) T, n = 3 ... 7, against runs stopped there",
                 gb_contact_model_name(models[m]));
        gb_check c = {"6", "73, 74", q, "the state of a run of (n + 1/4) periods", "bit-identical (the same steps)"};
        gb_check_true(&c, !status && s.strobe.count == 5 && mismatches == 0, "%zu samples, %zu differ; %s", s.strobe.count,
                      mismatches, status ? gb_error_message() : "");
        gb_strobe_free(&s.strobe);
    }
}

static void test_pair_reference_is_the_run(void)
{
    static const gb_contact_model models[2] = {GB_CONTACT_MODEL_FAST_GRID, GB_CONTACT_MODEL_CONTINUOUS};
    static const gb_integrator methods[2] = {GB_INTEGRATOR_RK4, GB_INTEGRATOR_RK8PD};
    const double R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, w0[3] = {0, 0, 0};
    for (int m = 0; m < 2; m++)
        for (int k = 0; k < 2; k++) {
            if (methods[k] == GB_INTEGRATOR_RK8PD && models[m] != GB_CONTACT_MODEL_CONTINUOUS) continue;
            gb_dynamics_def def = gb_dynamics_default_def();
            def.contact = models[m];
            def.variant = m ? GB_VARIANT_ROLLING : GB_VARIANT_PAPER;
            gb_integrate_def idef = gb_integrate_default_def();
            idef.method = methods[k];
            idef.rtol = 1e-8, idef.atol = 1e-10;
            idef.periods = 12.0;
            gb_lyapunov_body *body = NULL;
            gb_lyapunov_result r = {0};
            gb_lyapunov_def ldef = gb_lyapunov_default_def();
            ldef.interval = 2.0 * M_PI / def.forcing.omega, ldef.intervals = 10, ldef.transient = 2, ldef.batches = 5;
            int status = gb_lyapunov_body_create(gb_check_body("II", 0.12), &def, &idef, R0, w0, def.forcing.omega, &body);
            const gb_lyapunov_pair_system ps = gb_lyapunov_body_pair(body);
            if (!status) status = gb_lyapunov_pair(&ps, body, &ldef, 0.0, NULL, &r);
            gb_dynamics *d = NULL;
            double y[GB_STATE_SIZE];
            gb_integrate_stats stats;
            if (!status) status = gb_dynamics_start(gb_check_body("II", 0.12), &def, R0, w0, &d, y);
            if (!status) status = gb_integrate_run(d, &idef, 0.0, y, NULL, NULL, &stats);
            const int same = !status && memcmp(y, gb_lyapunov_body_state(body), sizeof y) == 0 &&
                             stats.steps == gb_lyapunov_body_stats(body, 0)->steps;
            char q[200];
            snprintf(q, sizeof q, "Gomboc II, %s, %s: the pair's reference after 2 + 10 periods against the plain run",
                     gb_contact_model_name(models[m]), gb_integrate_name(methods[k]));
            gb_check c = {"6", "77", q, "the scene's plain run of 12 periods", "bit-identical state and step count"};
            gb_check_true(&c, same, "%s", status ? gb_error_message() : "states or step counts differ");
            gb_dynamics_free(d);
            gb_lyapunov_result_free(&r);
            gb_lyapunov_body_free(body);
        }
}

/* gb_run takes one path: with λ asked for, the trajectory is the pair's reference; without, a plain run.
 * Everything observed along it (state, switches, monitors, strobe, spectrum) must be the same bits. */
static int same_run(const gb_run_result *a, const gb_run_result *b)
{
    return a->state_fingerprint == b->state_fingerprint && a->switch_fingerprint == b->switch_fingerprint &&
           a->samples == b->samples && memcmp(&a->monitors, &b->monitors, sizeof a->monitors) == 0 &&
           a->residual_max == b->residual_max && a->strobe.count == b->strobe.count &&
           memcmp(a->strobe.x, b->strobe.x, 3 * a->strobe.count * sizeof *a->strobe.x) == 0 &&
           a->spectrum.count == b->spectrum.count &&
           memcmp(a->spectrum.power, b->spectrum.power, a->spectrum.count * sizeof *a->spectrum.power) == 0;
}

static void test_run_one_path(void)
{
    static const gb_contact_model models[2] = {GB_CONTACT_MODEL_FAST_GRID, GB_CONTACT_MODEL_CONTINUOUS};
    for (int m = 0; m < 2; m++) {
        gb_case scene = gb_case_default();
        scene.dynamics.contact = models[m];
        scene.dynamics.variant = m ? GB_VARIANT_ROLLING : GB_VARIANT_PAPER;
        scene.integrate.locate_switches = m;
        scene.integrate.periods = 20.0;
        scene.strobe = scene.spectrum = scene.monitors = 1;
        scene.strobe_def.transient = 5, scene.spectrum_transient = 5;
        gb_run_result plain, with;
        int status = gb_run(&scene, NULL, &plain);
        scene.lyapunov = 1;
        if (!status) status = gb_case_lyapunov_check("(the check's scene)", &scene);
        if (!status) {
            status = gb_run(&scene, NULL, &with);
            if (status) gb_run_result_free(&plain);
        }
        char q[200];
        snprintf(q, sizeof q, "Gomboc I, %s, 20 periods: gb_run with lambda against gb_run without",
                 gb_contact_model_name(models[m]));
        gb_check c = {"6", "77", q, "the same scene without lambda",
                      "bit-identical state, switches, monitors, strobe and spectrum"};
        gb_check_true(&c, !status && same_run(&plain, &with) && with.has_lyapunov && !plain.has_lyapunov, "%s",
                      status ? gb_error_message() : same_run(&plain, &with) ? "the same bits; lambda only in the second"
                                                                            : "the runs differ");
        if (!status) gb_run_result_free(&plain), gb_run_result_free(&with);
    }
}

/* ---------------------------------------------------------------- spectrum */

static void test_spectrum_closed_forms(void)
{
    static const gb_spectrum_window windows[2] = {GB_SPECTRUM_WINDOW_RECTANGULAR, GB_SPECTRUM_WINDOW_HANN};
    static const size_t lengths[3] = {512, 1000, 625};
    for (int w = 0; w < 2; w++)
        for (int l = 0; l < 3; l++) {
            const size_t n = lengths[l], k0 = 37;
            const double dt = 0.01, A = 1.7, f0 = (double)k0 / ((double)n * dt);
            double *x = malloc(n * sizeof *x);
            for (size_t i = 0; i < n; i++) x[i] = 0.3 + A * sin(2.0 * M_PI * f0 * (double)i * dt + 0.4);
            gb_spectrum s;
            const int status = gb_spectrum_compute(x, n, dt, windows[w], &s);
            free(x);
            char q[160];
            snprintf(q, sizeof q, "sinusoid on bin 37, n = %zu, %s window: peak frequency [Hz]", n, gb_spectrum_window_name(windows[w]));
            gb_check cp = {"8.2", "Fig 8", q, "f0 = 37/(n dt)", "2 ulp of f0"};
            if (status) {
                gb_check_true(&cp, 0, "%s", gb_error_message());
                continue;
            }
            gb_check_close(&cp, s.frequency[gb_spectrum_peak(&s)], f0, 2.0 * DBL_EPSILON, 0.0);
            double total = 0.0;
            for (size_t k = 0; k < s.count; k++) total += s.power[k] * s.df;
            snprintf(q, sizeof q, "sinusoid on bin 37, n = %zu, %s window: integrated power sum(P) df", n, gb_spectrum_window_name(windows[w]));
            gb_check ci = {"8.2", "Fig 8", q, "A^2/2 (Parseval; the window's cross terms vanish on bin 37)",
                           "FFT rounding: 64 eps log2(n) relative"};
            gb_check_close(&ci, total, 0.5 * A * A, 64.0 * DBL_EPSILON * log2((double)n), 0.0);
            gb_spectrum_free(&s);
        }
}

static void test_spectrum_scipy(void)
{
    cJSON *root = NULL;
    const cJSON *cases = gb_check_reference_cases("spectrum.json", "8.2", &root), *jc;
    if (!cases) return;
    cJSON_ArrayForEach(jc, cases) {
        const char *name = cJSON_GetStringValue(cJSON_GetObjectItem(jc, "name"));
        const char *wname = cJSON_GetStringValue(cJSON_GetObjectItem(jc, "window"));
        const double dt = cJSON_GetNumberValue(cJSON_GetObjectItem(jc, "dt"));
        const cJSON *sig = cJSON_GetObjectItem(jc, "signal"), *freq = cJSON_GetObjectItem(jc, "frequency"),
                    *pow_ref = cJSON_GetObjectItem(jc, "power");
        const size_t n = (size_t)cJSON_GetArraySize(sig);
        double *x = malloc(n * sizeof *x);
        for (size_t i = 0; i < n; i++) x[i] = cJSON_GetNumberValue(cJSON_GetArrayItem(sig, (int)i));
        gb_spectrum_window window;
        gb_spectrum s = {0};
        int status = gb_spectrum_window_parse(wname, &window);
        if (!status) status = gb_spectrum_compute(x, n, dt, window, &s);
        free(x);
        char q[200];
        snprintf(q, sizeof q, "%s, %s window: max |P - P_scipy| / max P", name, wname);
        gb_check c = {"8.2", "Fig 8", q, "scipy.signal.periodogram (references/spectrum.json)",
                      "FFT rounding: 64 eps log2(n) of the largest bin"};
        if (status || s.count != (size_t)cJSON_GetArraySize(pow_ref)) {
            gb_check_true(&c, 0, "%s (bins %zu vs %d)", status ? gb_error_message() : "bin count differs", s.count,
                          cJSON_GetArraySize(pow_ref));
            gb_spectrum_free(&s);
            continue;
        }
        double worst = 0.0, peak = 0.0, fworst = 0.0;
        for (size_t k = 0; k < s.count; k++) {
            const double p = cJSON_GetNumberValue(cJSON_GetArrayItem(pow_ref, (int)k));
            const double f = cJSON_GetNumberValue(cJSON_GetArrayItem(freq, (int)k));
            worst = fmax(worst, fabs(s.power[k] - p));
            peak = fmax(peak, p);
            fworst = fmax(fworst, fabs(s.frequency[k] - f) / fmax(f, s.df));
        }
        gb_check_close(&c, worst / peak, 0.0, 0.0, 64.0 * DBL_EPSILON * log2((double)n));
        snprintf(q, sizeof q, "%s, %s window: frequencies [Hz], max relative difference", name, wname);
        gb_check cf = {"8.2", "Fig 8", q, "scipy.signal.periodogram", "4 ulp"};
        gb_check_close(&cf, fworst, 0.0, 0.0, 4.0 * DBL_EPSILON);
        gb_spectrum_free(&s);
    }
    cJSON_Delete(root);
}

int verify_register_s6_diagnostics(void)
{
    static const verify_test tests[] = {
        {"eq 73-74: the strobe against closed forms (forced oscillator, logistic cycles)", test_strobe_closed_forms, NULL},
        {"eq 73-74: Gomboc strobe samples are the states of runs stopped there", test_strobe_gomboc, NULL},
        {"eq 77: the pair's reference trajectory is the plain run", test_pair_reference_is_the_run, NULL},
        {"gb_run: one path, with or without lambda", test_run_one_path,
         "a scene's run is the same trajectory, monitors and diagnostics whether or not it computes lambda"},
        {"Fig 8: spectrum against closed forms (peak, Parseval)", test_spectrum_closed_forms, NULL},
        {"Fig 8: spectrum against scipy.signal.periodogram", test_spectrum_scipy, NULL},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Sections 6, 8.2: stroboscopic maps and spectra", tests);
}
