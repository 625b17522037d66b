/* Paper §5 and §8: the equations of motion against implementations written apart from the paper, not from this
 * code: the paper's grid model (eq 44, brute-force contact, RK4) against numpy (references/grid_model.json), the
 * rolling model against a scipy DOP853 trajectory (references/dynamics.json), and across branch switches against a
 * scipy solution with its own switch detection and location (references/switching.json). Body: Table 1 (β = 0.12,
 * m = 1), R0 = I, ω0 = 0. */
#include "gb_check.h"
#include "gb_dynamics.h"
#include "gb_dynamics_protocol_internal.h"
#include "gb_error.h"
#include "gb_integrate.h"
#include "verify_sections.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static const double IDENTITY[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

/* The scipy reference trajectory (references/dynamics.json): continuous rolling model, Table 1 forcing
 * in m/s², R0 = I, ω0 = 0, one period, states every eighth of a period. */
typedef struct collected {
    double states[64][GB_STATE_SIZE];
    int count;
} collected;

static int collect(void *context, double t, const double y[GB_STATE_SIZE])
{
    (void)t;
    collected *c = context;
    if (c->count < 64) memcpy(c->states[c->count++], y, sizeof c->states[0]);
    return 0;
}

/* Run `d` from y one period at a time under `idef` and compare (q, omega) at each period end with the
 * "state" of every entry of `periods` (a reference's array); samples (may be NULL) go to `sample`. *worst
 * gets the largest difference, *compared the periods compared; returns the integration status. */
static int compare_period_ends(gb_dynamics *d, const gb_integrate_def *idef, double y[GB_STATE_SIZE], const cJSON *periods,
                               gb_integrate_sample sample, void *context, double *worst, int *compared, double *t_end)
{
    gb_integrate_session *session = NULL;
    int status = gb_integrate_begin(d, idef, 0.0, &session);
    *worst = 0.0, *compared = 0;
    const cJSON *jp;
    cJSON_ArrayForEach(jp, periods) {
        if (!status) status = gb_integrate_advance(session, idef->steps_per_period, y, sample, context);
        if (status) break;
        const cJSON *state = cJSON_GetObjectItem(jp, "state");
        for (int k = 0; k < 7; k++) *worst = fmax(*worst, fabs(y[k] - cJSON_GetNumberValue(cJSON_GetArrayItem(state, k))));
        ++*compared;
    }
    if (t_end) *t_end = session ? gb_integrate_time(session) : 0.0;
    if (session) gb_integrate_end(session);
    return status;
}

/* The paper's own model (eq 44, the lowest node of the 90 x 180 grid by brute force, RK4 at 160 steps a
 * period, Table 1 in m/s^2) against references/grid_model.py, an independent numpy implementation
 * written from the paper's equations, state by state at the end of each of the first five periods (the
 * model's exponent, about 2.6 1/s, separates any two implementations within a few tens of periods). */
static void numpy_grid_case(const cJSON *jc)
{
    const char *name = cJSON_GetStringValue(cJSON_GetObjectItem(jc, "morphology"));
    const double beta = cJSON_GetNumberValue(cJSON_GetObjectItem(jc, "beta"));
    gb_dynamics_def def = gb_dynamics_default_def(); /* Table 1: eq 44, grid 90 x 180, A in m/s^2 */
    gb_dynamics *d = NULL;
    double y[GB_STATE_SIZE];
    static const double zero[3] = {0, 0, 0};
    int status = gb_dynamics_start(gb_check_body(name, beta), &def, IDENTITY, zero, &d, y);
    const gb_integrate_def idef = gb_integrate_default_def(); /* RK4, 160 steps a period */
    double worst = NAN;
    int compared = 0;
    if (!status) status = compare_period_ends(d, &idef, y, cJSON_GetObjectItem(jc, "periods"), NULL, NULL, &worst, &compared, NULL);
    char q[200];
    snprintf(q, sizeof q, "Gomboc %s, the paper's grid model: max |state - numpy| at the ends of periods 1 to %d", name, compared);
    gb_check c = {"8", "40-44", q, "references/grid_model.py (numpy, written from the paper; inertia from scipy)",
                  "1e-11: the inertia tensors agree to a few ulps (section 2); rounding of ~1e-16 a step over 800 steps "
                  "(8e-14), grown at most 100x (lambda 2.6 1/s over 1.75 s)"};
    gb_check_close(&c, status || compared < 5 ? NAN : worst, 0.0, 0.0, 1e-11);
    gb_dynamics_free(d);
}

static void test_numpy_grid_model(void) { gb_check_each_reference_case("grid_model.json", "8", numpy_grid_case); }

/* The Table 1 rolling scene (continuous contact, forced, damped, R0 = I, omega0 = 0) of a reference case,
 * started, with RK4 at 2560 steps a period: what both scipy references are compared with. */
static int rolling_reference_start(const cJSON *jc, const char **name, gb_dynamics **d, double y[GB_STATE_SIZE],
                                   gb_integrate_def *idef)
{
    *name = cJSON_GetStringValue(cJSON_GetObjectItem(jc, "morphology"));
    gb_dynamics_def def = gb_dynamics_default_def();
    def.variant = GB_VARIANT_ROLLING;
    def.contact = GB_CONTACT_MODEL_CONTINUOUS;
    *idef = gb_integrate_default_def();
    idef->steps_per_period = 2560;
    const double rest[3] = {0, 0, 0};
    return gb_dynamics_start(gb_check_body(*name, 0.12), &def, IDENTITY, rest, d, y);
}

static void scipy_trajectory_case(const cJSON *jc)
{
    const char *name;
    gb_dynamics *d = NULL;
    double y[GB_STATE_SIZE];
    gb_integrate_def idef;
    int status = rolling_reference_start(jc, &name, &d, y, &idef);
    idef.periods = 1.0;
    idef.sample_every = 320; /* an eighth of a period */
    collected got = {.count = 0};
    gb_integrate_stats stats;
    if (!status) status = gb_integrate_run(d, &idef, 0.0, y, collect, &got, &stats);
    const cJSON *states = cJSON_GetObjectItem(jc, "states");
    double worst = status || got.count != cJSON_GetArraySize(states) ? NAN : 0.0;
    for (int k = 0; isfinite(worst) && k < got.count; k++)
        for (int i = 0; i < 7; i++)
            worst = fmax(worst, fabs(got.states[k][i] - cJSON_GetNumberValue(cJSON_GetArrayItem(cJSON_GetArrayItem(states, k), i))));
    char q[200];
    snprintf(q, sizeof q, "state (q, omega) at 9 times over one period, Gomboc %s, RK4 2560 steps/period", name);
    gb_check c = {"5", "23, 44 (rolling)", q, "scipy solve_ivp DOP853 rtol 1e-12 (references/dynamics.json)",
                  "1e-9: the reference's rtol 1e-12 over ~150 steps plus RK4's 1e-13 at this step, with margin"};
    gb_check_close(&c, worst, 0.0, 0.0, 1e-9);
    gb_dynamics_free(d);
}

/* The switch times of a run, read after every sample from the dynamics' switch counter and the time of
 * its latest switch (the located time). More than one switch between two samples is counted apart. */
typedef struct switch_log {
    gb_dynamics *dynamics;
    size_t seen, missed, count;
    double times[256];
} switch_log;

static int log_switches(void *context, double t, const double y[GB_STATE_SIZE])
{
    (void)t, (void)y;
    switch_log *log = context;
    const size_t now = gb_dynamics_switch_count(log->dynamics);
    if (now == log->seen) return 0;
    if (now > log->seen + 1) log->missed += now - log->seen - 1;
    if (log->count < sizeof log->times / sizeof log->times[0])
        log->times[log->count++] = gb_dynamics_last_switch_time(log->dynamics);
    log->seen = now;
    return 0;
}

/* The largest |t − t_ref| over the switches of a run against the reference's switch_times, NAN when the
 * counts differ or a switch was missed between samples. */
static double switch_time_error(const switch_log *log, const cJSON *times)
{
    if (log->missed || (int)log->count != cJSON_GetArraySize(times)) return NAN;
    double worst = 0.0;
    for (size_t k = 0; k < log->count; k++)
        worst = fmax(worst, fabs(log->times[k] - cJSON_GetNumberValue(cJSON_GetArrayItem(times, (int)k))));
    return worst;
}

/* The rolling model with continuous contact across branch switches, against references/switching.py:
 * scipy DOP853 with its own switch handling (a grid scan for a lower minimum after every step, the switch
 * time by brentq on the dense output), over 20 periods of each body. gomboc, twice: RK4 at 2560 steps a
 * period and GSL's rk8pd at the reference's tolerances (rtol 1e-12, atol 1e-14), both with located switches
 * (Illinois on the step fraction), the certificate proving each contact global. States at every period
 * end, the number of switches and every switch time are compared. */
static void switching_run(const cJSON *jc, gb_integrator method)
{
    const char *name;
    gb_dynamics *d = NULL;
    double y[GB_STATE_SIZE];
    gb_integrate_def idef;
    int status = rolling_reference_start(jc, &name, &d, y, &idef);
    idef.locate_switches = 1;
    const int adaptive = method != GB_INTEGRATOR_RK4;
    if (adaptive) idef.method = method, idef.rtol = 1e-12, idef.atol = 1e-14, idef.steps_per_period = 160;
    double worst = NAN, t_end = 0.0;
    int compared = 0;
    switch_log log = {.dynamics = d};
    if (!status) status = compare_period_ends(d, &idef, y, cJSON_GetObjectItem(jc, "periods"), log_switches, &log, &worst,
                                              &compared, &t_end);
    gb_dynamics_observables o = {0};
    if (!status) status = gb_dynamics_observe(d, t_end, y, &o);
    const cJSON *times = cJSON_GetObjectItem(jc, "switch_times");
    const int reference_switches = cJSON_GetArraySize(times);
    char q[220], stepper[60];
    snprintf(stepper, sizeof stepper, adaptive ? "rk8pd rtol 1e-12" : "RK4 2560 steps/period");
    snprintf(q, sizeof q, "Gomboc %s, rolling model across branch switches (%s): max |state - scipy| at the ends of periods 1 to %d",
             name, stepper, compared);
    gb_check c = {"5, 4", "38-39, 44 (rolling)", q, "references/switching.py (DOP853, grid-scan global minimum, brentq switch times)",
                  adaptive ? "1e-9: both steppers at rtol 1e-12 (|y| <= 1, so ~1e-12 a period); a switch time off by ~1e-13 s "
                             "moves the state ~1e-12 (|dy/dt| <= 10); e^(lambda t) <= 30 over 20 periods; margin 30"
                           : "1e-9: RK4 at 2560 steps meets DOP853 to 1e-15 a period without a switch; a switch time off by "
                             "~1e-13 s moves the state ~1e-12 (|dy/dt| <= 10); e^(lambda t) <= 30 over 20 periods; margin 30"};
    gb_check_close(&c, status || compared < 20 ? NAN : worst, 0.0, 0.0, 1e-9);
    snprintf(q, sizeof q, "Gomboc %s, rolling model (%s): branch switches in 20 periods, gomboc against the scipy reference",
             name, stepper);
    gb_check cs = {"4", "38-39", q, "references/switching.py", "exact: the same switches"};
    gb_check_true(&cs, !status && (int)o.branch_switches == reference_switches, "gomboc %zu, reference %d", o.branch_switches,
                  reference_switches);
    snprintf(q, sizeof q, "Gomboc %s, rolling model (%s): max |switch time - scipy| over the %d switches", name, stepper,
             reference_switches);
    gb_check ct = {"4", "38-39", q, "references/switching.py (brentq on DOP853's dense output, xtol 1e-15)",
                   "1e-9 s: a state error of 1e-9 (the row above) moves the zero of the height gap by 1e-9 / |d(gap)/dt| "
                   "with |d(gap)/dt| >~ 1 at a transversal crossing"};
    gb_check_close(&ct, status ? NAN : switch_time_error(&log, times), 0.0, 0.0, 1e-9);
    gb_dynamics_free(d);
}

static void switching_case(const cJSON *jc)
{
    switching_run(jc, GB_INTEGRATOR_RK4);
    switching_run(jc, GB_INTEGRATOR_RK8PD);
}

static void test_switching_trajectory(void) { gb_check_each_reference_case("switching.json", "5", switching_case); }

static void test_scipy_trajectory(void) { gb_check_each_reference_case("dynamics.json", "5", scipy_trajectory_case); }

int verify_register_s5_references(void)
{
    static const verify_test tests[] = {
        {"eq 40-44: the paper's grid model against an independent numpy implementation", test_numpy_grid_model,
         "the paper's grid model (eq 44, brute-force contact, RK4) agrees with an independent numpy implementation "
         "written from the paper, over the first five periods of both bodies"},
        {"eq 38-39, 44: the rolling model across branch switches against scipy", test_switching_trajectory,
         "the rolling model with certified continuous contact and located switches agrees with an independent scipy "
         "solution with its own switch detection and location, switch for switch, over 20 periods of both bodies"},
        {"eq 23, 44: the rolling model against a scipy reference trajectory", test_scipy_trajectory,
         "the rolling model with continuous contact agrees with an independent scipy DOP853 trajectory"},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Sections 5, 8: the equations of motion against numpy and scipy", tests);
}
