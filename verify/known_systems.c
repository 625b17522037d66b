/* Systems whose Lyapunov exponents are known, written for both estimators of gb_lyapunov. */
#include "known_systems.h"

#include "gb_error.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <string.h>

/* ------------------------------------------------------------ the pair's separation (maps and flows) */

/* Both system structs start with their two trajectories, so one pair of functions serves both. */
static int pair_separation(void *context, double *e)
{
    const known_pair *p = context;
    for (size_t i = 0; i < p->dimension; i++) e[i] = p->x[1][i] - p->x[0][i];
    return GB_OK;
}

static int pair_place(void *context, const double *e)
{
    known_pair *p = context;
    for (size_t i = 0; i < p->dimension; i++) p->x[1][i] = p->x[0][i] + e[i];
    return GB_OK;
}

/* ------------------------------------------------------------ maps */

static void map_step(const known_map *m, const double *x, double *out)
{
    if (m->kind == KNOWN_LOGISTIC) {
        out[0] = m->a * x[0] * (1.0 - x[0]);
    } else { /* Hénon: (x, y) → (1 − a x² + y, b x) */
        out[0] = 1.0 - m->a * x[0] * x[0] + x[1];
        out[1] = m->b * x[0];
    }
}

/* Jacobian-vector product J(x) v. */
static void map_tangent(const known_map *m, const double *x, const double *v, double *out)
{
    if (m->kind == KNOWN_LOGISTIC) {
        out[0] = m->a * (1.0 - 2.0 * x[0]) * v[0];
    } else {
        out[0] = -2.0 * m->a * x[0] * v[0] + v[1];
        out[1] = m->b * v[0];
    }
}

size_t known_map_dimension(const known_map *m) { return m->pair.dimension; }

static int map_advance_pair(void *context, int which, double t, double interval)
{
    (void)t;
    known_map *m = context;
    const size_t n = known_map_dimension(m);
    for (long k = 0; k < lround(interval); k++) {
        double next[2];
        map_step(m, m->pair.x[which], next);
        memcpy(m->pair.x[which], next, n * sizeof *next);
    }
    return GB_OK;
}

static int map_advance(void *context, double t, double interval) { return map_advance_pair(context, 0, t, interval); }

static int map_advance_tangent(void *context, double t, double interval, size_t k, double *vectors)
{
    (void)t;
    known_map *m = context;
    const size_t n = known_map_dimension(m);
    for (long s = 0; s < lround(interval); s++) {
        for (size_t j = 0; j < k; j++) {
            double w[2];
            map_tangent(m, m->pair.x[0], vectors + j * n, w);
            memcpy(vectors + j * n, w, n * sizeof *w);
        }
        double next[2];
        map_step(m, m->pair.x[0], next);
        memcpy(m->pair.x[0], next, n * sizeof *next);
    }
    return GB_OK;
}

gb_lyapunov_pair_system known_map_pair(const known_map *m)
{
    return (gb_lyapunov_pair_system){known_map_dimension(m), map_advance_pair, pair_separation, pair_place};
}

gb_lyapunov_tangent_system known_map_tangent(const known_map *m)
{
    return (gb_lyapunov_tangent_system){known_map_dimension(m), map_advance, map_advance_tangent};
}

/* ------------------------------------------------------------ flows */

size_t known_flow_dimension(const known_flow *f) { return f->pair.dimension; }

/* The vector field at (t, x) and, for each of the k tangent vectors stored after x, J(t, x) v. */
static int flow_rhs(double t, const double y[], double dydt[], void *params)
{
    const known_flow *f = params;
    const size_t n = known_flow_dimension(f);
    const double *x = y;
    if (f->kind == KNOWN_LORENZ) { /* σ(y − x), x(ρ − z) − y, x y − β z */
        dydt[0] = f->sigma * (x[1] - x[0]);
        dydt[1] = x[0] * (f->rho - x[2]) - x[1];
        dydt[2] = x[0] * x[1] - f->beta * x[2];
    } else { /* Ueda: ẍ + k ẋ + x³ = B cos t */
        dydt[0] = x[1];
        dydt[1] = -f->damping * x[1] - x[0] * x[0] * x[0] + f->forcing * cos(t);
    }
    for (size_t j = 0; j < f->vectors; j++) {
        const double *v = y + n * (1 + j);
        double *w = dydt + n * (1 + j);
        if (f->kind == KNOWN_LORENZ) {
            w[0] = f->sigma * (v[1] - v[0]);
            w[1] = (f->rho - x[2]) * v[0] - v[1] - x[0] * v[2];
            w[2] = x[1] * v[0] + x[0] * v[1] - f->beta * v[2];
        } else {
            w[0] = v[1];
            w[1] = -3.0 * x[0] * x[0] * v[0] - f->damping * v[1];
        }
    }
    return GSL_SUCCESS;
}

/* Integrate the state and f->vectors tangent vectors from t over `interval` in fixed rk8pd steps of
 * about f->step: both trajectories of a pair then see the same numerical flow map, so their
 * separation measures the dynamics and not a difference between two adaptive step sequences. */
static int flow_integrate(known_flow *f, double *y, double t, double interval)
{
    const size_t n = known_flow_dimension(f);
    const unsigned long steps = (unsigned long)ceil(interval / f->step - 1e-9);
    gsl_odeiv2_system sys = {flow_rhs, NULL, n * (1 + f->vectors), f};
    gsl_odeiv2_driver *driver = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, interval / (double)steps, 1e-6, 0.0);
    if (!driver) return gb_error_set(GB_ENOMEM, "out of memory for a GSL driver");
    double time = t;
    const int status = gsl_odeiv2_driver_apply_fixed_step(driver, &time, interval / (double)steps, steps, y);
    gsl_odeiv2_driver_free(driver);
    if (status != GSL_SUCCESS)
        return gb_error_set(GB_ENUMERIC, "GSL rk8pd failed on a known flow at t = %g: %s", time, gsl_strerror(status));
    return GB_OK;
}

static int flow_advance_pair(void *context, int which, double t, double interval)
{
    known_flow *f = context;
    const size_t saved = f->vectors;
    f->vectors = 0;
    const int status = flow_integrate(f, f->pair.x[which], t, interval);
    f->vectors = saved;
    return status;
}

static int flow_advance(void *context, double t, double interval) { return flow_advance_pair(context, 0, t, interval); }

static int flow_advance_tangent(void *context, double t, double interval, size_t k, double *vectors)
{
    known_flow *f = context;
    const size_t n = known_flow_dimension(f);
    double y[3 * (1 + 3)];
    memcpy(y, f->pair.x[0], n * sizeof *y);
    memcpy(y + n, vectors, k * n * sizeof *y);
    f->vectors = k;
    const int status = flow_integrate(f, y, t, interval);
    f->vectors = 0;
    if (status) return status;
    memcpy(f->pair.x[0], y, n * sizeof *y);
    memcpy(vectors, y + n, k * n * sizeof *y);
    return GB_OK;
}

gb_lyapunov_pair_system known_flow_pair(const known_flow *f)
{
    return (gb_lyapunov_pair_system){known_flow_dimension(f), flow_advance_pair, pair_separation, pair_place};
}

gb_lyapunov_tangent_system known_flow_tangent(const known_flow *f)
{
    return (gb_lyapunov_tangent_system){known_flow_dimension(f), flow_advance, flow_advance_tangent};
}

/* ------------------------------------------------------------ constructors */

known_map known_logistic(double r, double x0)
{
    return (known_map){.pair = {1, {{x0}}}, .kind = KNOWN_LOGISTIC, .a = r};
}

known_map known_henon(double a, double b, double x0, double y0)
{
    return (known_map){.pair = {2, {{x0, y0}}}, .kind = KNOWN_HENON, .a = a, .b = b};
}

known_flow known_lorenz(double sigma, double rho, double beta, const double x0[3])
{
    return (known_flow){.pair = {3, {{x0[0], x0[1], x0[2]}}}, .kind = KNOWN_LORENZ, .sigma = sigma, .rho = rho,
                        .beta = beta, .step = 0.005};
}

known_flow known_ueda(double damping, double forcing, double x0, double v0)
{
    return (known_flow){.pair = {2, {{x0, v0}}}, .kind = KNOWN_UEDA, .damping = damping, .forcing = forcing,
                        .step = 2.0 * M_PI / 400.0};
}
