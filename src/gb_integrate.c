#include "gb_integrate.h"

#include "gb_error.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <string.h>

static const char *const names[] = {"rk4", "rk8pd", "rkf45", "rk4imp"};

const char *gb_integrate_name(gb_integrator m) { return (unsigned)m < 4 ? names[m] : NULL; }

int gb_integrate_parse(const char *name, gb_integrator *method)
{
    int k = 0;
    const int status = gb_error_parse_name(name, names, 4, "integrator", &k);
    if (!status) *method = (gb_integrator)k;
    return status;
}

gb_integrate_def gb_integrate_default_def(void)
{
    return (gb_integrate_def){.method = GB_INTEGRATOR_RK4, .steps_per_period = 160, .periods = 300.0,
                              .rtol = 1e-10, .atol = 1e-12, .sample_every = 1};
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
    return GB_OK;
}

static void note_drift(gb_integrate_stats *stats, double drift)
{
    if (fabs(drift) > stats->max_norm_drift) stats->max_norm_drift = fabs(drift);
}

/* One classical RK4 step of size h from (t, y) into out. */
static int rk4_step(gb_dynamics *d, double t, double h, const double y[], double out[], gb_integrate_stats *stats)
{
    double k1[GB_STATE_SIZE], k2[GB_STATE_SIZE], k3[GB_STATE_SIZE], k4[GB_STATE_SIZE], tmp[GB_STATE_SIZE];
    int status = gb_dynamics_rhs(d, t, y, k1);
    for (int i = 0; !status && i < GB_STATE_SIZE; i++) tmp[i] = y[i] + 0.5 * h * k1[i];
    if (!status) status = gb_dynamics_rhs(d, t + 0.5 * h, tmp, k2);
    for (int i = 0; !status && i < GB_STATE_SIZE; i++) tmp[i] = y[i] + 0.5 * h * k2[i];
    if (!status) status = gb_dynamics_rhs(d, t + 0.5 * h, tmp, k3);
    for (int i = 0; !status && i < GB_STATE_SIZE; i++) tmp[i] = y[i] + h * k3[i];
    if (!status) status = gb_dynamics_rhs(d, t + h, tmp, k4);
    if (status) return status;
    for (int i = 0; i < GB_STATE_SIZE; i++) out[i] = y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    stats->rhs_evaluations += 4;
    return GB_OK;
}

/* A switch was found at the end of the step (t, y) → t + h: locate the fraction θ where Δh = 0 by the
 * Illinois method on gap(θ) = Δh at the RK4 step of size θh (on the old branch), switch there, and
 * finish the step on the new branch into out. */
static int located_step(gb_dynamics *d, double t, double h, const double y[], const gb_contact_point *other,
                        double out[], gb_integrate_stats *stats)
{
    double a = 0.0, b = 1.0, ga, gb, ya[GB_STATE_SIZE], yb[GB_STATE_SIZE], ymid[GB_STATE_SIZE];
    gb_contact_point other_a, other_b, other_mid;
    int status = gb_dynamics_branch_gap(d, y, other, &ga, &other_a);
    if (!status) status = rk4_step(d, t, h, y, yb, stats);
    if (!status) status = gb_dynamics_branch_gap(d, yb, other, &gb, &other_b);
    if (status) return status;
    memcpy(ya, y, sizeof ya);
    if (!(ga < 0.0 && gb > 0.0)) {
        /* Already lower at the start (or no sign change): switch at the start of the step. */
        gb_dynamics_switch_to(d, ga >= 0.0 ? &other_a : &other_b);
        return ga >= 0.0 ? rk4_step(d, t, h, y, out, stats) : (memcpy(out, yb, sizeof yb), GB_OK);
    }
    int side = 0;
    for (int it = 0; it < 60 && b - a > 1e-13; it++) {
        const double m = (a * gb - b * ga) / (gb - ga); /* regula falsi, Illinois-modified */
        double gm;
        status = rk4_step(d, t, m * h, y, ymid, stats);
        if (!status) status = gb_dynamics_branch_gap(d, ymid, other, &gm, &other_mid);
        if (status) return status;
        if (gm == 0.0) {
            a = b = m;
            memcpy(ya, ymid, sizeof ya);
            other_a = other_mid;
            break;
        }
        if (gm < 0.0) {
            a = m, ga = gm;
            memcpy(ya, ymid, sizeof ya);
            if (side == -1) gb *= 0.5;
            side = -1;
        } else {
            b = m, gb = gm;
            other_b = other_mid;
            if (side == 1) ga *= 0.5;
            side = 1;
        }
    }
    /* Switch at θ = a (the old branch still lowest there), to the other branch continued to ya. */
    double gap;
    status = gb_dynamics_branch_gap(d, ya, other, &gap, &other_a);
    if (status) return status;
    gb_dynamics_switch_to(d, &other_a);
    return rk4_step(d, t + a * h, (1.0 - a) * h, ya, out, stats);
}

static int run_rk4(gb_dynamics *d, const gb_integrate_def *def, double t0, double h, size_t steps, double y[],
                   gb_integrate_sample sample, void *context, gb_integrate_stats *stats)
{
    double next[GB_STATE_SIZE];
    for (size_t n = 0; n < steps; n++) {
        const double t = t0 + (double)n * h;
        int status = rk4_step(d, t, h, y, next, stats);
        if (status) return status;
        if (def->locate_switches) {
            gb_contact_point other;
            int found = 0;
            status = gb_dynamics_switch_pending(d, t + h, next, &other, &found);
            if (!status && found) status = located_step(d, t, h, y, &other, next, stats);
            if (status) return status;
        }
        memcpy(y, next, sizeof next);
        stats->steps++;
        double drift;
        status = gb_dynamics_accept(d, t0 + (double)(n + 1) * h, y, &drift);
        if (status) return status;
        note_drift(stats, drift);
        if ((n + 1) % def->sample_every == 0 && sample && sample(context, t0 + (double)(n + 1) * h, y)) break;
    }
    return GB_OK;
}

typedef struct gsl_context {
    gb_dynamics *dynamics;
    gb_integrate_stats *stats;
    int status; /* the first gb_ status a right-hand side returned */
} gsl_context;

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

static int run_adaptive(gb_dynamics *d, const gb_integrate_def *def, double t0, double h, size_t steps, double y[],
                        gb_integrate_sample sample, void *context, gb_integrate_stats *stats)
{
    const gsl_odeiv2_step_type *types[] = {NULL, gsl_odeiv2_step_rk8pd, gsl_odeiv2_step_rkf45, gsl_odeiv2_step_rk4imp};
    gsl_context c = {d, stats, GB_OK};
    gsl_odeiv2_system system = {gsl_rhs, gsl_jacobian, GB_STATE_SIZE, &c};
    /* A driver owns the stepper, control and evolve; implicit steppers need it to be attached. */
    gsl_odeiv2_driver *driver = gsl_odeiv2_driver_alloc_y_new(&system, types[def->method], h, def->atol, def->rtol);
    gsl_odeiv2_step *step = driver ? driver->s : NULL;
    gsl_odeiv2_control *control = driver ? driver->c : NULL;
    gsl_odeiv2_evolve *evolve = driver ? driver->e : NULL;
    int status = driver ? GB_OK : gb_error_set(GB_ENOMEM, "out of memory for the GSL stepper");
    double t = t0, dt = h;
    for (size_t n = 0; !status && n < steps; n++) {
        const double target = t0 + (double)(n + 1) * h;
        while (!status && t < target) {
            const double before = t;
            const int gsl_status = gsl_odeiv2_evolve_apply(evolve, control, step, &system, &t, target, &dt, y);
            if (gsl_status != GSL_SUCCESS) {
                status = c.status ? c.status
                                  : gb_error_set(GB_ENUMERIC, "GSL odeiv2 (%s) failed at t = %.17g: %s (step %.3g)",
                                                 def->method < 4 ? names[def->method] : "?", t, gsl_strerror(gsl_status), dt);
                break;
            }
            if (t == before) {
                status = gb_error_set(GB_ENUMERIC, "GSL odeiv2 (%s) made no progress at t = %.17g (step %.3g)",
                                      names[def->method], t, dt);
                break;
            }
            stats->steps++;
            if (def->max_steps && stats->steps >= def->max_steps) {
                status = gb_error_set(GB_ENOCONV, "%s took %zu steps by t = %.9g of %.9g (the step limit): the step size "
                                      "collapsed, as it does at the jumps of a grid contact",
                                      names[def->method], stats->steps, t, t0 + (double)steps * h);
                break;
            }
            double drift;
            status = gb_dynamics_accept(d, t, y, &drift);
            note_drift(stats, drift);
            /* y was renormalised and the contact may have changed: the stepper must not reuse derivatives. */
            gsl_odeiv2_evolve_reset(evolve);
            gsl_odeiv2_step_reset(step);
        }
        if (!status && (n + 1) % def->sample_every == 0 && sample && sample(context, t, y)) break;
    }
    if (evolve) stats->failed_steps = evolve->failed_steps;
    if (driver) gsl_odeiv2_driver_free(driver);
    return status;
}

int gb_integrate_run(gb_dynamics *d, const gb_integrate_def *def, double t0, double y[GB_STATE_SIZE],
                     gb_integrate_sample sample, void *context, gb_integrate_stats *stats)
{
    memset(stats, 0, sizeof *stats);
    int status = validate(def);
    if (status) return status;
    const double period = gb_forcing_period(&gb_dynamics_get_def(d)->forcing);
    const double h = period / (double)def->steps_per_period;
    const size_t steps = (size_t)llround(def->periods * (double)def->steps_per_period);
    if (sample && sample(context, t0, y)) return GB_OK;
    if (def->method == GB_INTEGRATOR_RK4) return run_rk4(d, def, t0, h, steps, y, sample, context, stats);
    return run_adaptive(d, def, t0, h, steps, y, sample, context, stats);
}
