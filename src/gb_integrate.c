#include "gb_integrate_internal.h"

#include "gb_dynamics_protocol_internal.h"
#include "gb_error.h"

#include <dlfcn.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const names[] = {"rk4", "rk8pd", "rkf45", "rk4imp", "bsimp", "msbdf"};
enum { METHODS = sizeof names / sizeof names[0] };

const char *gb_integrate_name(gb_integrator m) { return (unsigned)m < METHODS ? names[m] : NULL; }

int gb_integrate_parse(const char *name, gb_integrator *method)
{
    int k = 0;
    const int status = gb_error_parse_name(name, names, METHODS, "integrator", &k);
    if (!status) *method = (gb_integrator)k;
    return status;
}

int gb_integrate_blas_single_thread(void)
{
    void *symbol = dlsym(RTLD_DEFAULT, "openblas_set_num_threads");
    if (!symbol) return 0;
    void (*set_threads)(int);
    memcpy(&set_threads, &symbol, sizeof set_threads); /* POSIX: a function's address through dlsym's object pointer */
    set_threads(1);
    return 1;
}

static const char *const strategy_names[] = {"event-driven", "time-stepping"};
enum { STRATEGIES = sizeof strategy_names / sizeof strategy_names[0] };

const char *gb_integrate_strategy_name(gb_strategy s) { return (unsigned)s < STRATEGIES ? strategy_names[s] : NULL; }

int gb_integrate_strategy_parse(const char *name, gb_strategy *strategy)
{
    int k = 0;
    const int status = gb_error_parse_name(name, strategy_names, STRATEGIES, "strategy", &k);
    if (!status) *strategy = (gb_strategy)k;
    return status;
}

gb_integrate_def gb_integrate_default_def(void)
{
    return (gb_integrate_def){.method = GB_INTEGRATOR_RK4, .steps_per_period = 160, .periods = 300.0,
                              .rtol = 1e-10, .atol = 1e-12, .sample_every = 1,
                              .strategy = GB_STRATEGY_EVENT_DRIVEN, .theta = 0.5, .solver_tolerance = 1e-12,
                              .solver_iterations = 20000, .stepping_first = 64};
}

static int validate(const gb_integrate_def *def)
{
    if (!gb_integrate_name(def->method)) return gb_error_set(GB_EINVAL, "integrator %d is unknown", (int)def->method);
    if (def->steps_per_period < 1 || def->steps_per_period > 100000000)
        return gb_error_set(GB_EDOM, "steps_per_period = %zu is out of range (allowed: 1 to 1e8)", def->steps_per_period);
    if (!(isfinite(def->periods) && def->periods > 0.0))
        return gb_error_set(GB_EDOM, "periods = %g is out of range (allowed: finite, > 0)", def->periods);
    if (!(def->rtol > 0.0 && def->rtol < 1.0 && def->atol > 0.0 && def->atol < 1.0))
        return gb_error_set(GB_EDOM, "tolerances rtol = %g, atol = %g are out of range (allowed: 0 < tol < 1)",
                            def->rtol, def->atol);
    if (def->sample_every < 1) return gb_error_set(GB_EDOM, "sample_every must be >= 1");
    if (!gb_integrate_strategy_name(def->strategy)) return gb_error_set(GB_EINVAL, "strategy %d is unknown", (int)def->strategy);
    if (def->strategy == GB_STRATEGY_TIME_STEPPING && def->method != GB_INTEGRATOR_RK4)
        return gb_error_set(GB_EINVAL, "integrator %s with the time-stepping strategy, which steps by its own θ-method "
                            "(allowed: rk4, the default, which it ignores)", names[def->method]);
    if (def->hand_over && (def->strategy != GB_STRATEGY_EVENT_DRIVEN || def->method != GB_INTEGRATOR_RK4))
        return gb_error_set(GB_EINVAL, "hand_over with the %s strategy and integrator %s (allowed: the event-driven "
                            "strategy with rk4, whose steps time-stepping can take again)",
                            strategy_names[def->strategy], names[def->method]);
    return GB_OK;
}

static void note_drift(gb_integrate_stats *stats, double drift)
{
    if (fabs(drift) > stats->max_norm_drift) stats->max_norm_drift = fabs(drift);
}

/* The angle |ω| h the body turned through in an accepted step of length h, at its end (`fixed`: a step of
 * the fixed-step RK4, which is counted when it exceeds GB_INTEGRATE_ROTATION_MAX). */
static void note_rotation(gb_integrate_stats *stats, const double y[GB_STATE_SIZE], double h, int fixed)
{
    const double *w = y + GB_STATE_OMEGA, angle = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]) * h;
    if (angle > stats->max_step_rotation) stats->max_step_rotation = angle;
    stats->coarse_steps += fixed && angle > GB_INTEGRATE_ROTATION_MAX;
}

int gb_integrate_rk4_step(gb_dynamics *d, double t, double h, const double y[GB_STATE_SIZE], double out[GB_STATE_SIZE],
                          size_t k, double *Y, gb_integrate_tangent tangent, void *context, gb_integrate_stats *stats)
{
    enum { S = GB_STATE_SIZE };
    static const double c[4] = {0.0, 0.5, 0.5, 1.0};
    double K[4][S], stage[S], KY[4][GB_INTEGRATE_TANGENT_MAX][S], Ystage[S];
    if (k > GB_INTEGRATE_TANGENT_MAX) return gb_error_set(GB_EDOM, "%zu tangent vectors (allowed: at most %d)", k, GB_INTEGRATE_TANGENT_MAX);
    int status = GB_OK;
    for (int st = 0; st < 4 && !status; st++) {
        /* Stage 0 at y itself; stage st at y + c_st h K_{st-1}. */
        const double *ys = y, *Ys;
        if (st) {
            for (int i = 0; i < S; i++) stage[i] = y[i] + c[st] * h * K[st - 1][i];
            ys = stage;
        }
        status = gb_dynamics_rhs(d, t + c[st] * h, ys, K[st]);
        for (size_t j = 0; j < k && !status; j++) {
            Ys = Y + j * S;
            if (st) {
                for (int i = 0; i < S; i++) Ystage[i] = Y[j * S + i] + c[st] * h * KY[st - 1][j][i];
                Ys = Ystage;
            }
            status = tangent(context, d, t + c[st] * h, ys, Ys, KY[st][j]);
        }
    }
    if (status) return status;
    for (int i = 0; i < S; i++) out[i] = y[i] + h / 6.0 * (K[0][i] + 2.0 * K[1][i] + 2.0 * K[2][i] + K[3][i]);
    status = gb_dynamics_state_finite(t + h, out);
    if (status) return status;
    for (size_t j = 0; j < k; j++)
        for (int i = 0; i < S; i++)
            Y[j * S + i] += h / 6.0 * (KY[0][j][i] + 2.0 * KY[1][j][i] + 2.0 * KY[2][j][i] + KY[3][j][i]);
    if (stats) stats->rhs_evaluations += 4;
    return GB_OK;
}

static int rk4_step(gb_dynamics *d, double t, double h, const double y[], double out[], gb_integrate_stats *stats)
{
    return gb_integrate_rk4_step(d, t, h, y, out, 0, NULL, NULL, NULL, stats);
}

/* One step of size h from (t, y) into out on the current branch, by the stepper that took the step. */
typedef int (*substep_fn)(void *context, gb_dynamics *d, double t, double h, const double y[], double out[],
                          gb_integrate_stats *stats);

static int rk4_substep(void *context, gb_dynamics *d, double t, double h, const double y[], double out[],
                       gb_integrate_stats *stats)
{
    (void)context;
    return rk4_step(d, t, h, y, out, stats);
}

/* The fraction of a step just after an event at its start where the gap is looked at again (see locate). */
#define AFTER_EVENT 1e-6

/* The locator on the step fraction, for any one-step method. after_event: the step starts at a change of
 * contact, where the point just left ties with the new one (Δh = 0 to rounding); a gap ≥ 0 there is
 * that tie, so the gap is taken at AFTER_EVENT of the step instead, and a crossing after it is located. */
static int locate(gb_dynamics *d, double t, double h, const double y[GB_STATE_SIZE], const gb_contact_point *other,
                  substep_fn substep, void *context, int after_event, gb_integrate_switch *out, gb_integrate_stats *stats)
{
    double a = 0.0, b = 1.0, ga, gb, yb[GB_STATE_SIZE], ymid[GB_STATE_SIZE];
    gb_contact_point other_a, other_b, other_mid;
    int status = gb_dynamics_branch_gap(d, t, y, other, &ga, &other_a);
    if (!status) status = substep(context, d, t, h, y, yb, stats);
    if (!status) status = gb_dynamics_branch_gap(d, t + h, yb, other, &gb, &other_b);
    if (status) return status;
    double ystart[GB_STATE_SIZE];
    memcpy(ystart, y, sizeof ystart);
    if (after_event && ga >= 0.0) {
        double g0;
        status = substep(context, d, t, AFTER_EVENT * h, y, ymid, stats);
        if (!status) status = gb_dynamics_branch_gap(d, t + AFTER_EVENT * h, ymid, other, &g0, &other_mid);
        if (status) return status;
        if (g0 < 0.0) a = AFTER_EVENT, ga = g0, memcpy(ystart, ymid, sizeof ystart);
    }
    out->crossed = ga < 0.0 && gb > 0.0;
    if (!out->crossed) {
        /* Already lower at the start, or lower only at the end (a branch born or lost in a fold). */
        out->fraction = ga >= 0.0 ? 0.0 : 1.0;
        memcpy(out->y, ga >= 0.0 ? y : yb, sizeof out->y);
        out->other = ga >= 0.0 ? other_a : other_b;
        return GB_OK;
    }
    memcpy(out->y, ystart, sizeof out->y);
    int side = 0;
    for (int it = 0; it < 60 && b - a > 1e-13; it++) {
        const double m = (a * gb - b * ga) / (gb - ga); /* regula falsi, Illinois-modified */
        double gm;
        status = substep(context, d, t, m * h, y, ymid, stats);
        if (!status) status = gb_dynamics_branch_gap(d, t + m * h, ymid, other, &gm, &other_mid);
        if (status) return status;
        if (gm == 0.0) {
            a = b = m;
            memcpy(out->y, ymid, sizeof out->y);
            break;
        }
        if (gm < 0.0) {
            a = m, ga = gm;
            memcpy(out->y, ymid, sizeof out->y);
            if (side == -1) gb *= 0.5;
            side = -1;
        } else {
            b = m, gb = gm;
            if (side == 1) ga *= 0.5;
            side = 1;
        }
    }
    /* θ = a: the current branch is still the lower there; `other` continued to that state. */
    double gap;
    out->fraction = a;
    return gb_dynamics_branch_gap(d, t + a * h, out->y, other, &gap, &out->other);
}

int gb_integrate_locate_switch(gb_dynamics *d, double t, double h, const double y[GB_STATE_SIZE],
                               const gb_contact_point *other, gb_integrate_switch *out, gb_integrate_stats *stats)
{
    return locate(d, t, h, y, other, rk4_substep, NULL, 0, out, stats);
}

int gb_integrate_locate_next(gb_dynamics *d, double t, double h, const double y[GB_STATE_SIZE],
                             const gb_contact_point *other, gb_integrate_switch *out, gb_integrate_stats *stats)
{
    return locate(d, t, h, y, other, rk4_substep, NULL, 1, out, stats);
}


/* A switch was found at the end of the step (t, y) → t + h: locate it, switch there, and finish the
 * step on the new branch into out. Under the unilateral law the rest of the step is checked again and
 * each further change located in turn (impacts can follow each other within a step, as a chatter
 * ends); the held law takes one, as it always has, and leaves a second to gb_dynamics_accept. */
static int located_step(gb_dynamics *d, double t, double h, const double y[], const gb_contact_point *other,
                        substep_fn substep, void *context, double out[], gb_integrate_stats *stats)
{
    const int again = gb_dynamics_get_law(d)->several_events_per_step;
    double tc = t, hc = h, yc[GB_STATE_SIZE];
    gb_contact_point next = *other;
    memcpy(yc, y, sizeof yc);
    for (int events = 0;; events++) {
        if (events == GB_INTEGRATE_EVENTS_PER_STEP_MAX)
            return gb_error_set(GB_ENUMERIC, "more than %d changes of contact inside the step from t = %.9g", GB_INTEGRATE_EVENTS_PER_STEP_MAX, t);
        gb_integrate_switch at;
        int status = locate(d, tc, hc, yc, &next, substep, context, events > 0, &at, stats);
        if (status) return status;
        const double t_event = tc + at.fraction * hc, rest = (1.0 - at.fraction) * hc;
        status = gb_dynamics_switch_to(d, t_event, at.y, &at.other); /* an impact may change ω */
        if (status) return status;
        if (at.fraction == 1.0) return memcpy(out, at.y, sizeof at.y), GB_OK;
        status = substep(context, d, t_event, rest, at.y, out, stats);
        if (status || !again) return status;
        int found = 0;
        status = gb_dynamics_switch_pending(d, t + h, out, &next, &found);
        if (status || !found) return status;
        tc = t_event, hc = rest;
        memcpy(yc, at.y, sizeof yc);
    }
}

/* A run that can be continued: the nominal time grid t_n = t0 + n·h is global (n counts steps from
 * t0), so a run advanced in pieces visits exactly the times, and takes exactly the steps, of one
 * uninterrupted run; an adaptive run keeps its GSL state (step size included) between pieces. */
struct gb_integrate_session {
    gb_dynamics *dynamics;
    gb_integrate_def def;
    double t0, h, t;         /* t: the current time (the adaptive stepper's own, else t0 + n·h) */
    size_t n;                /* nominal steps done */
    gb_integrate_stats stats;
    int stopped;             /* a sample callback asked to stop */
    /* adaptive steppers */
    struct gsl_context *gsl;
    gsl_odeiv2_system system;
    gsl_odeiv2_driver *driver;
    double dt;
    /* def.hand_over: the dynamics before the step being taken (put back when the step is taken again stepped); the
     * steps at which the run was handed over and back, alternately (the first a hand-over); the session whose hand-overs
     * this one follows (gb_integrate_lead) */
    void *snapshot;
    size_t *switches, switch_count, switch_capacity;
    const gb_integrate_session *leader;
};

/* The strategy changes at step n (a hand-over or a return), in the session's log. */
static int log_switch(gb_integrate_session *s, size_t n)
{
    if (s->switch_count == s->switch_capacity) {
        const size_t capacity = s->switch_capacity ? 2 * s->switch_capacity : 16;
        size_t *switches = realloc(s->switches, capacity * sizeof *switches);
        if (!switches) return gb_error_set(GB_ENOMEM, "out of memory for %zu hand-overs", capacity);
        s->switches = switches, s->switch_capacity = capacity;
    }
    s->switches[s->switch_count++] = n;
    return GB_OK;
}

/* Did the session take step n stepped? (Its log: an odd number of changes at or before n.) */
static int stepped_at(const gb_integrate_session *s, size_t n)
{
    size_t changes = 0;
    while (changes < s->switch_count && s->switches[changes] <= n) changes++;
    return (int)(changes & 1u);
}

static const gb_contact_problem_def *solver_of(const gb_integrate_def *def, gb_contact_problem_def *out)
{
    *out = (gb_contact_problem_def){def->solver_tolerance, def->solver_iterations, def->stepping_first, def->stepping_siconos};
    return out;
}

/* Hand the run over to time-stepping before step n (reason: the limit's message, or NULL when following a leader). */
static int hand_over(gb_integrate_session *s, double t, const char *reason)
{
    gb_contact_problem_def solver;
    int status = gb_dynamics_hand_over(s->dynamics, s->h, s->def.theta, solver_of(&s->def, &solver));
    if (!status) status = log_switch(s, s->n);
    if (status) return status;
    if (!s->stats.hand_overs++) {
        s->stats.hand_over_first = t;
        snprintf(s->stats.hand_over_reason, sizeof s->stats.hand_over_reason, "%s",
                 reason ? reason : "the reference trajectory was handed over at this step");
    }
    return GB_OK;
}

/* One time-stepping step of a handed-over run from (t, y), and its return to the events where the body flies (a
 * session that follows a leader returns where the leader did, gb_integrate_advance). */
static int stepped_step(gb_integrate_session *s, double t, double y[])
{
    int status = gb_dynamics_stepping_step(s->dynamics, t, s->h, y);
    if (status) return status;
    s->stats.stepped_steps++;
    note_rotation(&s->stats, y, s->h, 0);
    int back = 0;
    if (!s->leader) status = gb_dynamics_hand_back(s->dynamics, t + s->h, y, &back);
    if (!status && back) {
        s->stats.hand_backs++;
        status = log_switch(s, s->n + 1);
    }
    return status;
}

/* A follower takes step n as its leader did: handed over where the leader was, back where the leader came back (in
 * flight; else it goes on stepped, a step unmatched). */
static int follow_leader(gb_integrate_session *s, double t, double y[])
{
    const int want = stepped_at(s->leader, s->n), have = gb_dynamics_stepped(s->dynamics);
    if (want == have) return GB_OK;
    if (want) return hand_over(s, t, NULL);
    int back = 0;
    const int status = gb_dynamics_hand_back(s->dynamics, t, y, &back);
    if (status) return status;
    if (back) {
        s->stats.hand_backs++;
        return log_switch(s, s->n);
    }
    s->stats.unmatched++;
    return GB_OK;
}

/* One event-driven RK4 step from (t, y) into y: the switch located inside it, accepted at t_next (the grid's next time,
 * t0 + (n + 1) h, not t + h: the bits of a run in pieces are those of one run). */
static int event_step(gb_integrate_session *s, double t, double t_next, double y[])
{
    gb_dynamics *d = s->dynamics;
    const double h = s->h;
    double next[GB_STATE_SIZE];
    int status = rk4_step(d, t, h, y, next, &s->stats);
    if (status) return status;
    if (s->def.locate_switches) {
        gb_contact_point other;
        int found = 0;
        status = gb_dynamics_switch_pending(d, t + h, next, &other, &found);
        if (!status && found) status = located_step(d, t, h, y, &other, rk4_substep, NULL, next, &s->stats);
        if (status) return status;
    }
    memcpy(y, next, sizeof next);
    double drift;
    status = gb_dynamics_accept(d, t_next, y, &drift);
    if (status) return status;
    note_drift(&s->stats, drift);
    note_rotation(&s->stats, y, h, 1);
    return GB_OK;
}

/* The same step where the run may be handed over: the dynamics kept before it and its impacts held back; where the
 * law meets a configuration it does not follow (gb_error_at_limit), all of it is put back and the step taken stepped. */
static int event_step_or_hand_over(gb_integrate_session *s, double t, double t_next, double y[])
{
    gb_dynamics *d = s->dynamics;
    double y0[GB_STATE_SIZE];
    memcpy(y0, y, sizeof y0);
    gb_dynamics_snapshot(d, s->snapshot);
    gb_dynamics_hold_impacts(d, 1);
    int status = event_step(s, t, t_next, y);
    gb_dynamics_hold_impacts(d, 0);
    if (!status) return gb_dynamics_release_impacts(d, 1);
    if (!gb_error_at_limit()) return status;
    char reason[sizeof s->stats.hand_over_reason];
    snprintf(reason, sizeof reason, "%s", gb_error_message());
    gb_error_clear();
    gb_dynamics_release_impacts(d, 0);
    gb_dynamics_restore(d, s->snapshot);
    memcpy(y, y0, sizeof y0);
    s->stats.unmatched += s->leader != NULL; /* a follower handed over where its leader was not */
    status = hand_over(s, t, reason);
    return status ? status : stepped_step(s, t, y);
}

static int advance_rk4(gb_integrate_session *s, size_t steps, double y[], gb_integrate_sample sample, void *context)
{
    gb_dynamics *d = s->dynamics;
    const double h = s->h;
    for (size_t end = s->n + steps; s->n < end; s->n++) {
        const double t = s->t0 + (double)s->n * h, t_next = s->t0 + (double)(s->n + 1) * h;
        int status = s->leader ? follow_leader(s, t, y) : GB_OK;
        if (status) return status;
        if (gb_dynamics_stepped(d)) status = stepped_step(s, t, y);
        else status = s->def.hand_over ? event_step_or_hand_over(s, t, t_next, y) : event_step(s, t, t_next, y);
        if (status) return status;
        s->stats.steps++;
        s->t = t_next;
        if ((s->n + 1) % s->def.sample_every == 0 && sample && sample(context, t_next, y)) {
            s->n++;
            s->stopped = 1;
            break;
        }
    }
    return GB_OK;
}

struct gsl_context {
    gb_dynamics *dynamics;
    gb_integrate_stats *stats;
    int status; /* the first gb_ status a right-hand side returned */
};
typedef struct gsl_context gsl_context;

/* One step of the session's GSL stepper of size h (no error control: the accepted step it divides
 * already met the tolerance), from a fresh derivative. */
static int gsl_substep(void *context, gb_dynamics *d, double t, double h, const double y[], double out[],
                       gb_integrate_stats *stats)
{
    (void)d, (void)stats;
    gb_integrate_session *s = context;
    double err[GB_STATE_SIZE];
    memcpy(out, y, GB_STATE_SIZE * sizeof *out);
    gsl_odeiv2_step_reset(s->driver->s);
    if (h == 0.0) return GB_OK;
    int gsl_status;
    if (s->def.method == GB_INTEGRATOR_MSBDF) {
        /* a multistep method has no one step from a fresh start: the driver takes [t, t + h] under its control */
        double tt = t;
        gsl_odeiv2_driver_reset(s->driver);
        gsl_odeiv2_driver_reset_hstart(s->driver, fmin(h, s->dt));
        gsl_status = gsl_odeiv2_driver_apply(s->driver, &tt, t + h, out);
    } else {
        gsl_status = gsl_odeiv2_step_apply(s->driver->s, t, h, out, err, NULL, NULL, &s->system);
    }
    if (gsl_status != GSL_SUCCESS)
        return s->gsl->status ? s->gsl->status
                              : gb_error_set(GB_ENUMERIC, "GSL odeiv2 (%s) failed locating a switch at t = %.17g: %s",
                                             names[s->def.method], t, gsl_strerror(gsl_status));
    return GB_OK;
}

static int gsl_rhs(double t, const double y[], double dydt[], void *params)
{
    gsl_context *c = params;
    c->stats->rhs_evaluations++;
    const int status = gb_dynamics_rhs(c->dynamics, t, y, dydt);
    if (status && !c->status) c->status = status;
    return status ? GSL_EBADFUNC : GSL_SUCCESS;
}

/* Central-difference Jacobian for the implicit stepper; ∂f/∂t likewise. */
static int gsl_jacobian(double t, const double y[], double *dfdy, double dfdt[], void *params)
{
    double yp[GB_STATE_SIZE], fp[GB_STATE_SIZE], fm[GB_STATE_SIZE];
    memcpy(yp, y, sizeof yp);
    for (int j = 0; j < GB_STATE_SIZE; j++) {
        const double h = 1e-7 * fmax(1.0, fabs(y[j]));
        yp[j] = y[j] + h;
        if (gsl_rhs(t, yp, fp, params)) return GSL_EBADFUNC;
        yp[j] = y[j] - h;
        if (gsl_rhs(t, yp, fm, params)) return GSL_EBADFUNC;
        yp[j] = y[j];
        for (int i = 0; i < GB_STATE_SIZE; i++) dfdy[i * GB_STATE_SIZE + j] = (fp[i] - fm[i]) / (2.0 * h);
    }
    const double ht = 1e-7 * fmax(1.0, fabs(t));
    if (gsl_rhs(t + ht, y, fp, params) || gsl_rhs(t - ht, y, fm, params)) return GSL_EBADFUNC;
    for (int i = 0; i < GB_STATE_SIZE; i++) dfdt[i] = (fp[i] - fm[i]) / (2.0 * ht);
    return GSL_SUCCESS;
}

static const gsl_odeiv2_step_type *stepper_type(gb_integrator method)
{
    switch (method) {
    case GB_INTEGRATOR_RK8PD: return gsl_odeiv2_step_rk8pd;
    case GB_INTEGRATOR_RKF45: return gsl_odeiv2_step_rkf45;
    case GB_INTEGRATOR_RK4IMP: return gsl_odeiv2_step_rk4imp;
    case GB_INTEGRATOR_BSIMP: return gsl_odeiv2_step_bsimp;
    case GB_INTEGRATOR_MSBDF: return gsl_odeiv2_step_msbdf;
    default: return NULL;
    }
}

static int advance_adaptive(gb_integrate_session *s, size_t steps, double y[], gb_integrate_sample sample, void *context)
{
    gb_dynamics *d = s->dynamics;
    gsl_odeiv2_driver *driver = s->driver;
    gsl_odeiv2_step *step = driver->s;
    gsl_odeiv2_control *control = driver->c;
    gsl_odeiv2_evolve *evolve = driver->e;
    const char *name = names[s->def.method];
    int status = GB_OK;
    for (size_t end = s->n + steps; !status && s->n < end; s->n++) {
        const double target = s->t0 + (double)(s->n + 1) * s->h;
        while (!status && s->t < target) {
            const double before = s->t;
            double y_before[GB_STATE_SIZE];
            memcpy(y_before, y, sizeof y_before);
            int located = 0;
            const int gsl_status = gsl_odeiv2_evolve_apply(evolve, control, step, &s->system, &s->t, target, &s->dt, y);
            if (gsl_status != GSL_SUCCESS) {
                status = s->gsl->status ? s->gsl->status
                                        : gb_error_set(GB_ENUMERIC, "GSL odeiv2 (%s) failed at t = %.17g: %s (step %.3g)",
                                                       name, s->t, gsl_strerror(gsl_status), s->dt);
                break;
            }
            if (s->t == before) {
                status = gb_error_set(GB_ENUMERIC, "GSL odeiv2 (%s) made no progress at t = %.17g (step %.3g)", name,
                                      s->t, s->dt);
                break;
            }
            s->stats.steps++;
            if (s->def.max_steps && s->stats.steps >= s->def.max_steps) {
                status = gb_error_set(GB_ENOCONV, "%s took %zu steps by t = %.9g (the step limit): the step size "
                                      "collapsed, as it does at the jumps of a grid contact",
                                      name, s->stats.steps, s->t);
                break;
            }
            if (s->def.locate_switches) {
                /* As for RK4: a switch found at the end of the accepted step is located inside it, and the
                 * step is redone to there on the old branch and finished on the new one. */
                gb_contact_point other;
                int found = 0;
                status = gb_dynamics_switch_pending(d, s->t, y, &other, &found);
                if (!status && found) status = located_step(d, before, s->t - before, y_before, &other, gsl_substep, s, y, &s->stats);
                if (status) break;
                located = found;
            }
            double drift;
            status = gb_dynamics_accept(d, s->t, y, &drift);
            note_drift(&s->stats, drift);
            note_rotation(&s->stats, y, s->t - before, 0);
            /* y was renormalised and the contact may have changed: the stepper must not reuse derivatives; the
             * multistep BDF keeps its history (a renormalisation is rounding's size to it, and the vector field
             * reads q/|q|) unless an event was located in the step. */
            if (s->def.method != GB_INTEGRATOR_MSBDF || located) {
                gsl_odeiv2_evolve_reset(evolve);
                gsl_odeiv2_step_reset(step);
            }
        }
        s->stats.failed_steps = evolve->failed_steps;
        if (!status && (s->n + 1) % s->def.sample_every == 0 && sample && sample(context, s->t, y)) {
            s->n++;
            s->stopped = 1;
            break;
        }
    }
    return status;
}

/* Time-stepping: one Moreau–Jean step on each step of the nominal grid. */
static int advance_stepping(gb_integrate_session *s, size_t steps, double y[], gb_integrate_sample sample, void *context)
{
    const double h = s->h;
    for (size_t end = s->n + steps; s->n < end; s->n++) {
        const double t = s->t0 + (double)s->n * h, t_next = s->t0 + (double)(s->n + 1) * h;
        const int status = gb_dynamics_stepping_step(s->dynamics, t, h, y);
        if (status) return status;
        s->stats.steps++;
        s->t = t_next;
        note_rotation(&s->stats, y, h, 0);
        if ((s->n + 1) % s->def.sample_every == 0 && sample && sample(context, t_next, y)) {
            s->n++;
            s->stopped = 1;
            break;
        }
    }
    return GB_OK;
}

/* The strategies and the event-driven steppers as rows: how a session advances. */
typedef int (*advance_fn)(gb_integrate_session *s, size_t steps, double y[], gb_integrate_sample sample, void *context);

static advance_fn advance_of(const gb_integrate_def *def)
{
    if (def->strategy == GB_STRATEGY_TIME_STEPPING) return advance_stepping;
    return def->method == GB_INTEGRATOR_RK4 ? advance_rk4 : advance_adaptive;
}

int gb_integrate_begin(gb_dynamics *d, const gb_integrate_def *def, double t0, gb_integrate_session **out)
{
    *out = NULL;
    int status = validate(def);
    if (status) return status;
    if (!isfinite(t0)) return gb_error_set(GB_EDOM, "t0 = %g is out of range (allowed: finite)", t0);
    gb_integrate_session *s = calloc(1, sizeof *s);
    if (!s) return gb_error_set(GB_ENOMEM, "out of memory for an integration");
    s->dynamics = d;
    s->def = *def;
    s->t0 = s->t = t0;
    s->h = gb_forcing_step(&gb_dynamics_get_def(d)->forcing, def->steps_per_period);
    s->dt = s->h;
    gb_dynamics_use_step(d, s->h); /* the end to chatter, where the definition leaves it to the step */
    if (def->hand_over) {
        const gb_dynamics_law *law = gb_dynamics_get_law(d);
        s->snapshot = law->time_steps ? malloc(gb_dynamics_snapshot_size()) : NULL;
        if (!s->snapshot) {
            gb_integrate_end(s);
            return law->time_steps ? gb_error_set(GB_ENOMEM, "out of memory for a hand-over")
                                   : gb_error_set(GB_EINVAL, "hand_over under the %s law, which poses no one-step "
                                                  "problem (allowed: the unilateral law on a plane of finite friction)",
                                                  law->name);
        }
    }
    if (def->hand_over && gb_dynamics_stepped(d)) { /* handed over at its start (gb_dynamics_init_or_hand_over) */
        status = hand_over(s, t0, gb_dynamics_start_limit(d));
        if (status) {
            gb_integrate_end(s);
            return status;
        }
    }
    if (def->strategy == GB_STRATEGY_TIME_STEPPING) {
        gb_contact_problem_def solver;
        status = gb_dynamics_stepping_begin(d, t0, s->h, def->theta, solver_of(def, &solver));
        if (status) {
            gb_integrate_end(s);
            return status;
        }
    } else if (def->method != GB_INTEGRATOR_RK4) {
        s->gsl = malloc(sizeof *s->gsl);
        if (s->gsl) {
            *s->gsl = (struct gsl_context){d, &s->stats, GB_OK};
            s->system = (gsl_odeiv2_system){gsl_rhs, gsl_jacobian, GB_STATE_SIZE, s->gsl};
            /* A driver owns the stepper, control and evolve; implicit steppers need it to be attached. */
            s->driver = gsl_odeiv2_driver_alloc_y_new(&s->system, stepper_type(def->method), s->h, def->atol, def->rtol);
        }
        if (!s->driver) {
            gb_integrate_end(s);
            return gb_error_set(GB_ENOMEM, "out of memory for the GSL stepper");
        }
    }
    *out = s;
    return GB_OK;
}

int gb_integrate_advance(gb_integrate_session *s, size_t steps, double y[GB_STATE_SIZE], gb_integrate_sample sample,
                         void *context)
{
    if (s->stopped) return GB_OK;
    return advance_of(&s->def)(s, steps, y, sample, context);
}

size_t gb_integrate_steps_for(const gb_integrate_session *s, double periods)
{
    return (size_t)llround(periods * (double)s->def.steps_per_period);
}

double gb_integrate_time(const gb_integrate_session *s) { return s->t; }
int gb_integrate_stopped(const gb_integrate_session *s) { return s->stopped; }
const gb_integrate_stats *gb_integrate_session_stats(const gb_integrate_session *s) { return &s->stats; }

int gb_integrate_follow(gb_integrate_session *to, const gb_integrate_session *from)
{
    /* the strategy the other trajectory is in at this step (a hand-over of one is a hand-over of both) */
    const int stepped = gb_dynamics_stepped(from->dynamics);
    if (to->def.hand_over && stepped != gb_dynamics_stepped(to->dynamics)) {
        if (stepped) {
            gb_contact_problem_def solver;
            const int status = gb_dynamics_hand_over(to->dynamics, to->h, to->def.theta, solver_of(&to->def, &solver));
            if (status) return status;
        } else {
            gb_dynamics_hand_back_now(to->dynamics);
        }
    }
    to->n = from->n;
    to->t = from->t;
    to->dt = from->dt;
    to->stopped = from->stopped;
    if (to->driver) {
        gsl_odeiv2_evolve_reset(to->driver->e);
        gsl_odeiv2_step_reset(to->driver->s);
    }
    return GB_OK;
}

void gb_integrate_lead(gb_integrate_session *follower, const gb_integrate_session *leader)
{
    follower->leader = leader;
}

void gb_integrate_end(gb_integrate_session *s)
{
    if (!s) return;
    if (s->driver) gsl_odeiv2_driver_free(s->driver);
    free(s->gsl);
    free(s->snapshot);
    free(s->switches);
    free(s);
}

int gb_integrate_run(gb_dynamics *d, const gb_integrate_def *def, double t0, double y[GB_STATE_SIZE],
                     gb_integrate_sample sample, void *context, gb_integrate_stats *stats)
{
    memset(stats, 0, sizeof *stats);
    gb_integrate_session *s = NULL;
    int status = gb_integrate_begin(d, def, t0, &s);
    if (status) return status;
    if (!(sample && sample(context, t0, y)))
        status = gb_integrate_advance(s, gb_integrate_steps_for(s, def->periods), y, sample, context);
    *stats = s->stats;
    gb_integrate_end(s);
    return status;
}
