/* gb_melnikov — §7 for any one-degree-of-freedom model (gb_melnikov.h): the saddle and its separatrix, the
 * path along it in q (|p| and t(q), the saddle ends in u = −ln|q − s|), the Melnikov integrals (eqs 88–90)
 * by adaptive quadrature or tabulated once for many frequencies, and the direct integral of a
 * perturbation. The criterion the integrals decide is gb_melnikov_criterion.c; the splitting measured by
 * integrating the perturbed system, gb_melnikov_split.c. */
#include "gb_melnikov.h"
#include "gb_melnikov_internal.h"

#include "gb_error.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_min.h>
#include <gsl/gsl_roots.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { WORK = 2000 };
/* The saddle ends of the path are mapped to u = −ln|q − s| and integrated by quadrature while |q − s| is
 * at least CUT_RELATIVE·max(1, |s|) (where q − s is still known to 1e-7 of itself); beyond, the orbit is
 * the saddle's linearisation (|q − s| ∝ e^{−λ|t|}, |p| ∝ |q − s|) and the rest is one QAGIU integral. */
#define CUT_RELATIVE 1e-9
#define CHECKPOINT 0.25
enum { CHECKPOINTS = 512 };
#define NEAR_SADDLE 0.1

int gb_melnikov_model_at(const gb_melnikov_model *m, double q, gb_melnikov_values *v)
{
    const int status = m->eval(m->context, q, v);
    if (status) return status;
    if (!(v->M > 0.0) || !isfinite(v->M) || !isfinite(v->U) || !isfinite(v->dU) || !isfinite(v->S))
        return gb_error_set(GB_EDOM, "the reduced model at q = %.17g: M = %g, U = %g, U' = %g, S = %g (allowed: M > 0 and "
                            "finite values, eq 80)", q, v->M, v->U, v->dU, v->S);
    return GB_OK;
}

/* ---- the saddle and the separatrix -------------------------------------------------------------- */

typedef struct call {
    const gb_melnikov_model *model;
    const gb_melnikov_orbit *orbit;
    int status;
} call;

/* The model at q for a GSL callback: the first failure is kept in the call. */
static gb_melnikov_values values_at(double q, call *c)
{
    gb_melnikov_values v = {NAN, NAN, NAN, NAN, NAN};
    const int s = gb_melnikov_model_at(c->model, q, &v);
    if (s && !c->status) c->status = s;
    return v;
}

static double dU_at(double q, void *p) { return values_at(q, p).dU; }
static double U_at(double q, void *p) { return values_at(q, p).U; }

static int brent(double (*f)(double, void *), call *c, double lo, double hi, double *root)
{
    gsl_function F = {f, c};
    gsl_root_fsolver *s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    if (!s) return gb_error_set(GB_ENOMEM, "out of memory for a root finder");
    int status = gsl_root_fsolver_set(s, &F, lo, hi) == GSL_SUCCESS ? GB_OK : GB_EDOM;
    for (int it = 0; !status && it < 200; it++) {
        if (gsl_root_fsolver_iterate(s) != GSL_SUCCESS) status = GB_ENUMERIC;
        const double a = gsl_root_fsolver_x_lower(s), b = gsl_root_fsolver_x_upper(s);
        if (gsl_root_test_interval(a, b, 0.0, 4 * DBL_EPSILON) == GSL_SUCCESS) break;
    }
    *root = gsl_root_fsolver_root(s);
    gsl_root_fsolver_free(s);
    if (c->status) return c->status;
    return status ? gb_error_set(status, "root finding failed in [%.17g, %.17g]", lo, hi) : GB_OK;
}

/* E_s − U(q) without cancellation near a point a where U(a) = E_s (the saddle, its periodic copy, or a
 * loop's turning point): −∫_a^q U′ by 5-point Gauss–Legendre on U′ within NEAR_SADDLE of a (exact for
 * U′ of degree 9; at the switch both forms agree to rounding), E_s − U(q) beyond. */
static double gap(const gb_melnikov_model *m, const gb_melnikov_orbit *o, double q, const gb_melnikov_values *v, int *status)
{
    double a = o->q_u;
    if (fabs(q - o->q_end) < fabs(q - a)) a = o->q_end;
    if (fabs(q - a) >= NEAR_SADDLE) return o->E_s - v->U;
    /* a periodic model's far saddle has the values of q_u */
    const double shift = m->period > 0.0 && a == o->q_end ? o->q_u - o->q_end : 0.0;
    static const double node[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
    static const double weight[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                                     0.2369268850561891};
    const double half = 0.5 * (q - a), centre = a + shift + half;
    double sum = 0.0;
    for (int k = 0; k < 5 && !*status; k++) {
        gb_melnikov_values w;
        *status = gb_melnikov_model_at(m, centre + half * node[k], &w);
        sum += weight[k] * w.dU;
    }
    return *status ? NAN : -half * sum;
}

int gb_melnikov_orbit_find(const gb_melnikov_model *m, gb_melnikov_orbit *o)
{
    memset(o, 0, sizeof *o);
    if (m->direction != 1 && m->direction != -1)
        return gb_error_set(GB_EDOM, "direction = %d (allowed: +1 or -1)", m->direction);
    call c = {m, o, GB_OK};
    const double a = dU_at(m->saddle_lo, &c), b = dU_at(m->saddle_hi, &c);
    if (c.status) return c.status;
    if (!(a * b < 0.0))
        return gb_error_set(GB_EDOM, "no saddle: U' = %g and %g at the ends of [%g, %g] (allowed: a bracket where U' changes "
                            "sign, eq 81)", a, b, m->saddle_lo, m->saddle_hi);
    int status = brent(dU_at, &c, m->saddle_lo, m->saddle_hi, &o->q_u);
    if (status) return status;
    gb_melnikov_values v, vp, vm;
    const double h = 1e-5 * fmax(1.0, fabs(o->q_u));
    status = gb_melnikov_model_at(m, o->q_u, &v);
    if (!status) status = gb_melnikov_model_at(m, o->q_u + h, &vp);
    if (!status) status = gb_melnikov_model_at(m, o->q_u - h, &vm);
    if (status) return status;
    o->E_s = v.U;
    o->curvature = (vp.dU - vm.dU) / (2.0 * h);
    if (!(o->curvature < 0.0))
        return gb_error_set(GB_EDOM, "U' vanishes at q = %.17g but U'' = %g there is not negative: a minimum, not a saddle "
                            "(allowed: U'' < 0, eq 81)", o->q_u, o->curvature);
    o->rate = sqrt(-o->curvature / v.M);
    if (m->period > 0.0) {
        o->q_end = o->q_u + m->direction * m->period;
        if (isfinite(m->origin)) {
            if (!((m->origin - o->q_u) * m->direction > 0.0 && (o->q_end - m->origin) * m->direction > 0.0))
                return gb_error_set(GB_EDOM, "origin = %g is not between the saddle %g and its copy %g", m->origin, o->q_u, o->q_end);
            o->q0 = m->origin;
            return GB_OK;
        }
        /* t = 0 at the lowest U between the two copies of the saddle. */
        double best = o->q_u, lowest = INFINITY;
        for (int k = 1; k < 400; k++) {
            const double q = o->q_u + m->direction * m->period * k / 400.0, u = U_at(q, &c);
            if (c.status) return c.status;
            if (!(u < o->E_s)) return gb_error_set(GB_EDOM, "U(%.6g) = %.6g is not below the saddle's %.6g: no rotation orbit over one period (allowed: a potential whose saddle is its only maximum on the period)", q, u, o->E_s);
            if (u < lowest) lowest = u, best = q;
        }
        gsl_function F = {U_at, &c};
        const double step = m->period / 400.0;
        gsl_min_fminimizer *s = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
        if (s && gsl_min_fminimizer_set(s, &F, best, best - step, best + step) == GSL_SUCCESS) {
            for (int it = 0; it < 100; it++) {
                if (gsl_min_fminimizer_iterate(s) != GSL_SUCCESS) break;
                if (gsl_min_test_interval(gsl_min_fminimizer_x_lower(s), gsl_min_fminimizer_x_upper(s), 1e-12, 0.0) == GSL_SUCCESS) break;
            }
            best = gsl_min_fminimizer_x_minimum(s);
        }
        if (s) gsl_min_fminimizer_free(s);
        o->q0 = best;
        return c.status;
    }
    /* A loop: march away from the saddle until U rises back to E_s, then Brent. */
    if (!(m->reach > 0.0)) return gb_error_set(GB_EDOM, "reach = %g (allowed: > 0 for a loop)", m->reach);
    const int n = 2000;
    double prev = o->q_u + m->direction * 1e-6 * m->reach;
    for (int k = 1; k <= n; k++) {
        const double q = o->q_u + m->direction * m->reach * k / n, g = U_at(q, &c) - o->E_s;
        if (c.status) return c.status;
        if (g >= 0.0) {
            /* Bisection on U − E_s between the last point below and the first at or above. */
            double lo = prev, hi = q;
            for (int it = 0; it < 200 && fabs(hi - lo) > 4 * DBL_EPSILON * fmax(1.0, fabs(q)); it++) {
                const double mid = 0.5 * (lo + hi), gm = U_at(mid, &c) - o->E_s;
                if (c.status) return c.status;
                if (gm >= 0.0) hi = mid;
                else lo = mid;
            }
            o->q_end = o->q0 = 0.5 * (lo + hi);
            return GB_OK;
        }
        prev = q;
    }
    return gb_error_set(GB_EDOM, "no turning point within %g of the saddle q_u = %.6g: U stays below E_s (allowed: a loop "
                        "that returns, or a periodic potential with period > 0)", m->reach, o->q_u);
}

/* ---- the separatrix in q: |p|, t(q) -------------------------------------------------------------- */

typedef struct path {
    const gb_melnikov_model *m;
    const gb_melnikov_orbit *o;
    gsl_integration_workspace *outer, *inner;
    gsl_integration_qaws_table *table;
    gsl_integration_workspace *qaws_work;
    int status;
    /* the integrand F(q, p, t) and the weight */
    double (*F)(void *context, double q, double p, double t, const gb_melnikov_values *v);
    void *context;
    gb_melnikov_weight weight;
    /* the current saddle segment: q(u) = s + σ e^{−u}, t(u) = t_r + sign_t ∫_{u_r}^{u} (M/|p|) e^{−u} du */
    double s, sigma, u_r, t_r;
    int sign_t;
    double base; /* where the model is evaluated for s: s itself, or for the far copy of a periodic
                    model's saddle, q_u (the same values, and offsets from it keep their digits) */
    /* t at checkpoints u_r + k·CHECKPOINT (k < known), so that t(u) is a short quadrature from the last */
    double checkpoint[CHECKPOINTS];
    size_t known;
    double frequency; /* the highest angular frequency of F in t (0: not oscillating) */
    int pieces;       /* integrate_oscillating goes to pieces at once (gb_melnikov_internal.h) */
} path;

static void fail(path *P, int status)
{
    if (status && !P->status) P->status = status;
}

/* |p| on the separatrix at q. */
static double momentum(path *P, double q, gb_melnikov_values *v)
{
    int status = gb_melnikov_model_at(P->m, q, v);
    const double g = status ? NAN : gap(P->m, P->o, q, v, &status);
    fail(P, status);
    return status ? NAN : sqrt(2.0 * v->M * fmax(g, 0.0));
}

/* QAG (61-point rule); where the integrand has kinks or jumps (contact ties) QAG may stall, and QAGS (with
 * extrapolation) takes over. A result whose error estimate meets the tolerance tenfold relaxed is kept. */
static int quadrature(path *P, gsl_integration_workspace *w, double (*f)(double, void *), double a, double b, double epsabs,
                      double epsrel, double *result)
{
    gsl_function F = {f, P};
    double error = 0.0;
    *result = 0.0;
    int s = gsl_integration_qag(&F, a, b, epsabs, epsrel, WORK, GSL_INTEG_GAUSS61, w, result, &error);
    if (s != GSL_SUCCESS && s != GSL_EROUND) s = gsl_integration_qags(&F, a, b, epsabs, epsrel, WORK, w, result, &error);
    if (s != GSL_SUCCESS && s != GSL_EROUND && !(error <= fmax(10.0 * epsabs, 10.0 * epsrel * fabs(*result))))
        return gb_error_set(GB_ENUMERIC, "quadrature on [%.6g, %.6g] failed: %s (error estimate %.3g of %.6g)", a, b,
                            gsl_strerror(s), error, *result);
    return GB_OK;
}

static double integrate(path *P, gsl_integration_workspace *w, double (*f)(double, void *), double a, double b, double epsabs,
                        double epsrel)
{
    double result;
    fail(P, quadrature(P, w, f, a, b, epsabs, epsrel, &result));
    return result;
}

/* An integrand that oscillates as cos(ω t) over more periods than one adaptive quadrature resolves (ω of
 * thousands of rad/s): the same integral in pieces of at most OSCILLATIONS periods each, `time(x)` the
 * time at x, each to the whole's tolerances. Tried only where the integral in one
 * piece failed, so that lower frequencies keep their values bit for bit. */
enum { OSCILLATIONS = 4 };
static double integrate_oscillating(path *P, double (*f)(double, void *), double a, double b, double epsabs, double epsrel,
                                    double (*time)(path *, double))
{
    if (!(P->frequency > 0.0) || !P->pieces) {
        double whole;
        const int status = quadrature(P, P->outer, f, a, b, epsabs, epsrel, &whole);
        if (!status || !(P->frequency > 0.0)) {
            fail(P, status);
            return whole;
        }
        gb_error_clear();
    }
    double total = 0.0;
    const double step = fmin(CHECKPOINT, b - a); /* pieces of t known at the checkpoints */
    for (double x = a; x < b && !P->status;) {
        const double y = fmin(x + step, b), span = fabs(time(P, y) - time(P, x));
        const double pieces = ceil(P->frequency * span / (2.0 * M_PI * OSCILLATIONS));
        const size_t n = pieces > 1.0 ? (size_t)fmin(pieces, 1e6) : 1;
        for (size_t k = 0; k < n && !P->status; k++) {
            const double lo = x + (y - x) * (double)k / (double)n, hi = k + 1 == n ? y : x + (y - x) * (double)(k + 1) / (double)n;
            total += integrate(P, P->outer, f, lo, hi, epsabs, epsrel);
        }
        x = y;
    }
    return total;
}

/* dt/du on a saddle segment: (M/|p|)(q(u)) e^{−u}. */
static double dtdu(double u, void *p)
{
    path *P = p;
    gb_melnikov_values v;
    const double e = exp(-u), mom = momentum(P, P->base + P->sigma * e, &v);
    return mom > 0.0 ? v.M / mom * e : 0.0;
}

static double segment_time(path *P, double u)
{
    if (!(u > P->u_r)) return P->t_r;
    size_t k = (size_t)((u - P->u_r) / CHECKPOINT);
    if (k >= CHECKPOINTS) k = CHECKPOINTS - 1;
    if (P->known == 0) P->checkpoint[0] = 0.0, P->known = 1;
    while (P->known <= k) {
        const double a = P->u_r + CHECKPOINT * (double)(P->known - 1);
        P->checkpoint[P->known] = P->checkpoint[P->known - 1] + integrate(P, P->inner, dtdu, a, a + CHECKPOINT, 1e-14, 1e-12);
        P->known++;
    }
    const double a = P->u_r + CHECKPOINT * (double)k;
    return P->t_r + P->sign_t * (P->checkpoint[k] + (u > a ? integrate(P, P->inner, dtdu, a, u, 1e-14, 1e-12) : 0.0));
}

/* M/|p| × √|x − q_t|, the smooth factor of a loop's time near its turning point: near q_t it is
 * √(M / (2 s)) with s = (E_s − U)/|x − q_t| the mean slope of U between them (Simpson on U′), finite at
 * q_t itself, where quadrature rules may evaluate it. */
static double turning_factor(double x, void *p)
{
    path *P = p;
    const double qt = P->o->q_end;
    gb_melnikov_values v, mid, end;
    if (fabs(x - qt) < NEAR_SADDLE) {
        int status = gb_melnikov_model_at(P->m, x, &v);
        if (!status) status = gb_melnikov_model_at(P->m, 0.5 * (x + qt), &mid);
        if (!status) status = gb_melnikov_model_at(P->m, qt, &end);
        fail(P, status);
        const double slope = fabs(end.dU + 4.0 * mid.dU + v.dU) / 6.0;
        return status || !(slope > 0.0) ? 0.0 : sqrt(v.M / (2.0 * slope));
    }
    const double mom = momentum(P, x, &v);
    return mom > 0.0 ? v.M / mom * sqrt(fabs(x - qt)) : 0.0;
}

/* A loop's time on its returning half at q (0 at the turning point). */
static double return_time(path *P, double q)
{
    const double qt = P->o->q_end;
    if (q == qt) return 0.0;
    gsl_function F = {turning_factor, P};
    double result = 0.0, error = 0.0;
    const int up = qt > q;
    gsl_integration_qaws_table_set(P->table, up ? 0.0 : -0.5, up ? -0.5 : 0.0, 0, 0);
    const int s = gsl_integration_qaws(&F, up ? q : qt, up ? qt : q, P->table, 0.0, 1e-12, WORK, P->qaws_work, &result, &error);
    if (s != GSL_SUCCESS && s != GSL_EROUND) fail(P, gb_error_set(GB_ENUMERIC, "the time to the turning point failed: %s", gsl_strerror(s)));
    return result;
}

/* The integrand of the path at q, p = ±|p|, at time t (see the header: weight × F, signed per dq). */
static double along(path *P, double q, double t, double mom, const gb_melnikov_values *v)
{
    const int dir = P->m->direction;
    const double w = P->weight == GB_MELNIKOV_PAPER ? v->M : 1.0;
    if (P->m->period > 0.0) return dir * w * P->F(P->context, q, dir * mom, t, v);
    /* A loop: the outgoing half at −t (p has the sign of dir), the returning half at +t. */
    return dir * w * (P->F(P->context, q, dir * mom, -t, v) - P->F(P->context, q, -dir * mom, t, v));
}

static double saddle_integrand(double u, void *p)
{
    path *P = p;
    gb_melnikov_values v;
    const double e = exp(-u), q = P->s + P->sigma * e, mom = momentum(P, P->base + P->sigma * e, &v);
    if (P->status) return 0.0;
    return along(P, q, segment_time(P, u), mom, &v) * e;
}

static double regular_integrand(double q, void *p)
{
    path *P = p;
    gb_melnikov_values v;
    const double mom = momentum(P, q, &v);
    if (P->status) return 0.0;
    return along(P, q, return_time(P, q), mom, &v);
}

/* The tail beyond the cut: q frozen at the cut, |p| decaying as e^{−(u − u_c)}, t advancing as (u − u_c)/λ. */
typedef struct tail {
    path *P;
    double q, u, t, mom;
    gb_melnikov_values v;
} tail;

static double tail_integrand(double u, void *p)
{
    tail *T = p;
    const double d = u - T->u;
    return along(T->P, T->q, T->t + T->P->sign_t * d / T->P->o->rate, T->mom * exp(-d), &T->v) * exp(-u);
}

static void enter_segment(path *P, double s, double r, double t_r, int sign_t)
{
    P->s = s, P->sigma = r > s ? 1.0 : -1.0, P->u_r = -log(fabs(r - s)), P->t_r = t_r, P->sign_t = sign_t;
    P->base = P->m->period > 0.0 && s == P->o->q_end ? P->o->q_u : s;
    P->known = 0;
}

static double saddle_segment(path *P, double s, double r, double t_r, int sign_t)
{
    enter_segment(P, s, r, t_r, sign_t);
    const double u_cut = fmax(P->u_r, -log(CUT_RELATIVE * fmax(1.0, fabs(P->base))));
    const double body = integrate_oscillating(P, saddle_integrand, P->u_r, u_cut, 1e-13, 1e-10, segment_time);
    tail T = {.P = P, .q = s + P->sigma * exp(-u_cut), .u = u_cut, .t = segment_time(P, u_cut)};
    T.mom = momentum(P, P->base + P->sigma * exp(-u_cut), &T.v);
    if (P->status) return NAN;
    gsl_function F = {tail_integrand, &T};
    double rest = 0.0, error = 0.0;
    const int st = gsl_integration_qagiu(&F, u_cut, 1e-13, 1e-10, WORK, P->outer, &rest, &error);
    if (st != GSL_SUCCESS && st != GSL_EROUND) fail(P, gb_error_set(GB_ENUMERIC, "the saddle tail's quadrature failed: %s", gsl_strerror(st)));
    return body + rest;
}

static int path_open(path *P, const gb_melnikov_model *m, const gb_melnikov_orbit *o)
{
    memset(P, 0, sizeof *P);
    P->m = m, P->o = o;
    P->outer = gsl_integration_workspace_alloc(WORK);
    P->inner = gsl_integration_workspace_alloc(WORK);
    P->qaws_work = gsl_integration_workspace_alloc(WORK);
    P->table = gsl_integration_qaws_table_alloc(0.0, -0.5, 0, 0);
    if (!P->outer || !P->inner || !P->qaws_work || !P->table) return gb_error_set(GB_ENOMEM, "out of memory for quadrature");
    return GB_OK;
}

static void path_close(path *P)
{
    if (P->outer) gsl_integration_workspace_free(P->outer);
    if (P->inner) gsl_integration_workspace_free(P->inner);
    if (P->qaws_work) gsl_integration_workspace_free(P->qaws_work);
    if (P->table) gsl_integration_qaws_table_free(P->table);
}

/* ∫ over the whole separatrix (t from −∞ to ∞) of w·F dt, w = q̇ or p, as an integral in q; F oscillates
 * in t with angular frequencies up to `frequency` (0: it does not). */
static int path_integral(const gb_melnikov_model *m, const gb_melnikov_orbit *o, gb_melnikov_weight weight,
                         double (*F)(void *, double, double, double, const gb_melnikov_values *), void *context,
                         double frequency, int pieces, double *out)
{
    path P;
    int status = path_open(&P, m, o);
    P.frequency = frequency, P.pieces = pieces;
    P.F = F, P.context = context, P.weight = weight;
    double total = 0.0;
    if (!status && m->period > 0.0) {
        /* From the saddle to q0 (t < 0), and from the far copy of the saddle back to q0 (t > 0). */
        total = saddle_segment(&P, o->q_u, o->q0, 0.0, -1);
        total += saddle_segment(&P, o->q_end, o->q0, 0.0, +1);
    } else if (!status) {
        const double mid = 0.5 * (o->q_u + o->q_end), t_mid = return_time(&P, mid);
        total = saddle_segment(&P, o->q_u, mid, t_mid, +1);
        total += integrate_oscillating(&P, regular_integrand, fmin(mid, o->q_end), fmax(mid, o->q_end), 1e-13, 1e-10, return_time);
    }
    status = status ? status : P.status;
    path_close(&P);
    *out = total;
    return status;
}

int gb_melnikov_time(const gb_melnikov_model *m, const gb_melnikov_orbit *o, double q, double *t)
{
    path P;
    int status = path_open(&P, m, o);
    *t = NAN;
    if (!status && m->period > 0.0) {
        /* Signed time from q0 along the motion. */
        const int after = (q - o->q0) * m->direction > 0.0;
        const double s = after ? o->q_end : o->q_u;
        enter_segment(&P, s, o->q0, 0.0, after ? 1 : -1);
        *t = segment_time(&P, -log(fabs(q - s)));
    } else if (!status) {
        *t = return_time(&P, q);
    }
    status = status ? status : P.status;
    path_close(&P);
    return status;
}

/* ---- the integrals and the function ------------------------------------------------------------- */

typedef struct harmonic {
    double omega;
    int kind; /* 0: p (for D), 1: S cos ωt, 2: S sin ωt, 3: p/M (for D_mass) */
} harmonic;

static double harmonic_F(void *context, double q, double p, double t, const gb_melnikov_values *v)
{
    (void)q;
    const harmonic *h = context;
    switch (h->kind) {
    case 0: return p;
    case 1: return v->S * cos(h->omega * t);
    case 2: return v->S * sin(h->omega * t);
    default: return p / v->M;
    }
}

static int integrals(const gb_melnikov_model *m, const gb_melnikov_orbit *o, double omega, gb_melnikov_weight weight,
                     int pieces, gb_melnikov_integrals *out)
{
    memset(out, 0, sizeof *out);
    out->omega = omega;
    if (!(isfinite(omega) && omega > 0.0)) return gb_error_set(GB_EDOM, "omega = %g (allowed: > 0)", omega);
    harmonic h[6] = {{omega, 0}, {omega, 1}, {omega, 2}, {2 * omega, 1}, {2 * omega, 2}, {omega, 3}};
    double *slot[6] = {&out->D, &out->C1, &out->S1, &out->C2, &out->S2, &out->D_mass};
    for (int k = 0; k < 6; k++) {
        /* A loop's cosine integrals vanish by its time symmetry (q_h even, q̇_h odd in t). */
        if (m->period == 0.0 && h[k].kind == 1) continue;
        const int oscillates = h[k].kind == 1 || h[k].kind == 2;
        const int status = path_integral(m, o, weight, harmonic_F, &h[k], oscillates ? h[k].omega : 0.0, pieces, slot[k]);
        if (status) return status;
    }
    out->A1 = hypot(out->C1, out->S1);
    out->A2 = hypot(out->C2, out->S2);
    return GB_OK;
}

int gb_melnikov_integrals_compute(const gb_melnikov_model *m, const gb_melnikov_orbit *o, double omega,
                                  gb_melnikov_weight weight, gb_melnikov_integrals *out)
{
    return integrals(m, o, omega, weight, 0, out);
}

int gb_melnikov_integrals_in_pieces(const gb_melnikov_model *m, const gb_melnikov_orbit *o, double omega,
                                    gb_melnikov_weight weight, gb_melnikov_integrals *out)
{
    return integrals(m, o, omega, weight, 1, out);
}

/* ---- the separatrix tabulated once for many frequencies ------------------------------------------ */

enum { TABLE_ORDER = 12, TABLE_DEPTH = 40 };
#define TABLE_WIDTH 0.5    /* the widest panel in u: where dt/du → 1/λ the phase is then bounded too */
#define TABLE_PHASE 1.5    /* the largest phase 2 ω_max |Δt| over one panel: the 12-point rule's error on
                              cos of it is below (Φ/2)^24/24! ≈ 1e-27 of the panel's weight */
#define TABLE_OMEGA_MAX 1e4

typedef struct table_node {
    double weight; /* the Gauss–Legendre weight × e^{−u} (|dq| = e^{−u} du) */
    double q, t, mom;
    gb_melnikov_values v;
} table_node;

/* A saddle segment's tail beyond u_cut, as saddle_segment leaves it. */
typedef struct table_tail {
    double q, u, t, mom;
    int sign_t;
    gb_melnikov_values v;
} table_tail;

struct gb_melnikov_table {
    gb_melnikov_model model;
    gb_melnikov_orbit orbit;
    gb_melnikov_weight weight;
    double omega_max;
    table_node *node;
    size_t n, capacity;
    table_tail tail[2];
};

static int table_push(gb_melnikov_table *T, const table_node *n)
{
    if (T->n == T->capacity) {
        const size_t cap = T->capacity ? 2 * T->capacity : 4096;
        table_node *grown = realloc(T->node, cap * sizeof *grown);
        if (!grown) return gb_error_set(GB_ENOMEM, "out of memory for the separatrix table");
        T->node = grown, T->capacity = cap;
    }
    T->node[T->n++] = *n;
    return GB_OK;
}

/* ∫_a^b dt/du du by the fixed rule (smooth within a panel). */
static double panel_time(path *P, const gsl_integration_glfixed_table *gl, double a, double b)
{
    gsl_function F = {dtdu, P};
    return gsl_integration_glfixed(&F, a, b, gl);
}

/* The panel [a, b] of the current segment, τ_a = ∫_{u_r}^{a} dt/du: halved until it is narrow enough
 * in u and in phase, then its nodes added. Returns ∫_a^b dt/du. */
static double table_panel(gb_melnikov_table *T, path *P, const gsl_integration_glfixed_table *gl, double a, double b,
                          double tau_a, int depth)
{
    const double span = panel_time(P, gl, a, b);
    if (P->status) return 0.0;
    if (depth < TABLE_DEPTH && (b - a > TABLE_WIDTH || 2.0 * T->omega_max * span > TABLE_PHASE)) {
        const double mid = 0.5 * (a + b), left = table_panel(T, P, gl, a, mid, tau_a, depth + 1);
        return left + table_panel(T, P, gl, mid, b, tau_a + left, depth + 1);
    }
    for (size_t i = 0; i < TABLE_ORDER && !P->status; i++) {
        double x, w;
        gsl_integration_glfixed_point(a, b, i, &x, &w, gl);
        const double e = exp(-x);
        table_node n = {.weight = w * e, .q = P->s + P->sigma * e};
        n.t = P->t_r + P->sign_t * (tau_a + panel_time(P, gl, a, x));
        n.mom = momentum(P, P->base + P->sigma * e, &n.v);
        if (!P->status) fail(P, table_push(T, &n));
    }
    return span;
}

static int ascending(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* One saddle segment, as saddle_segment integrates it: panels between u_r, the knots and u_cut. */
static void table_segment(gb_melnikov_table *T, path *P, const gsl_integration_glfixed_table *gl, double s, double r,
                          int sign_t, table_tail *tail)
{
    enter_segment(P, s, r, 0.0, sign_t);
    const double u_cut = fmax(P->u_r, -log(CUT_RELATIVE * fmax(1.0, fabs(P->base)))), reach = fabs(r - s);
    const double period = P->m->period;
    double *cuts = malloc((P->m->n_knots + 2) * sizeof *cuts);
    if (!cuts) {
        fail(P, gb_error_set(GB_ENOMEM, "out of memory for the separatrix table"));
        return;
    }
    size_t n = 0;
    cuts[n++] = P->u_r;
    for (size_t k = 0; k < P->m->n_knots; k++) {
        /* the knot's distance from the saddle on this segment's side, through the period */
        double d = fmod(P->sigma * (P->m->knots[k] - P->base), period);
        if (d < 0.0) d += period;
        const double u = d > 0.0 && d < reach ? -log(d) : NAN;
        if (u > P->u_r && u < u_cut) cuts[n++] = u;
    }
    qsort(cuts + 1, n - 1, sizeof *cuts, ascending);
    cuts[n++] = u_cut;
    double tau = 0.0;
    for (size_t k = 0; k + 1 < n && !P->status; k++)
        if (cuts[k + 1] > cuts[k]) tau += table_panel(T, P, gl, cuts[k], cuts[k + 1], tau, 0);
    free(cuts);
    *tail = (table_tail){.q = s + P->sigma * exp(-u_cut), .u = u_cut, .t = P->t_r + sign_t * tau, .sign_t = sign_t};
    tail->mom = momentum(P, P->base + P->sigma * exp(-u_cut), &tail->v);
}

int gb_melnikov_table_create(const gb_melnikov_model *m, const gb_melnikov_orbit *o, gb_melnikov_weight weight,
                             double omega_max, gb_melnikov_table **out)
{
    *out = NULL;
    if (!(m->period > 0.0))
        return gb_error_set(GB_EDOM, "a separatrix table needs a rotation (period > 0; a loop is integrated adaptively)");
    if (!(omega_max > 0.0 && omega_max <= TABLE_OMEGA_MAX))
        return gb_error_set(GB_EDOM, "omega_max = %g (allowed: 0 < omega_max <= %g rad/s)", omega_max, TABLE_OMEGA_MAX);
    gb_melnikov_table *T = calloc(1, sizeof *T);
    gsl_integration_glfixed_table *gl = gsl_integration_glfixed_table_alloc(TABLE_ORDER);
    path P;
    int status = path_open(&P, m, o);
    if (!status && (!T || !gl)) status = gb_error_set(GB_ENOMEM, "out of memory for the separatrix table");
    if (!status) {
        T->model = *m, T->orbit = *o, T->weight = weight, T->omega_max = omega_max;
        P.m = &T->model, P.o = &T->orbit;
        table_segment(T, &P, gl, T->orbit.q_u, T->orbit.q0, -1, &T->tail[0]);
        if (!P.status) table_segment(T, &P, gl, T->orbit.q_end, T->orbit.q0, +1, &T->tail[1]);
        status = P.status;
    }
    path_close(&P);
    if (gl) gsl_integration_glfixed_table_free(gl);
    if (status) {
        gb_melnikov_table_free(T);
        return status;
    }
    *out = T;
    return GB_OK;
}

size_t gb_melnikov_table_nodes(const gb_melnikov_table *T) { return T->n; }

void gb_melnikov_table_free(gb_melnikov_table *T)
{
    if (!T) return;
    free(T->node);
    free(T);
}

int gb_melnikov_table_integrals(const gb_melnikov_table *T, double omega, gb_melnikov_integrals *out)
{
    memset(out, 0, sizeof *out);
    out->omega = omega;
    if (!(omega > 0.0 && omega <= T->omega_max))
        return gb_error_set(GB_EDOM, "omega = %g (allowed: 0 < omega <= %g, the table's omega_max)", omega, T->omega_max);
    path P;
    memset(&P, 0, sizeof P);
    P.m = &T->model, P.o = &T->orbit, P.weight = T->weight, P.F = harmonic_F;
    P.outer = gsl_integration_workspace_alloc(WORK);
    if (!P.outer) return gb_error_set(GB_ENOMEM, "out of memory for quadrature");
    harmonic h[6] = {{omega, 0}, {omega, 1}, {omega, 2}, {2 * omega, 1}, {2 * omega, 2}, {omega, 3}};
    double *slot[6] = {&out->D, &out->C1, &out->S1, &out->C2, &out->S2, &out->D_mass};
    for (int k = 0; k < 6 && !P.status; k++) {
        P.context = &h[k];
        double sum = 0.0;
        for (size_t i = 0; i < T->n; i++) {
            const table_node *n = &T->node[i];
            sum += n->weight * along(&P, n->q, n->t, n->mom, &n->v);
        }
        for (int s = 0; s < 2; s++) {
            const table_tail *L = &T->tail[s];
            P.sign_t = L->sign_t;
            tail tl = {.P = &P, .q = L->q, .u = L->u, .t = L->t, .mom = L->mom, .v = L->v};
            gsl_function F = {tail_integrand, &tl};
            double rest = 0.0, error = 0.0;
            const int st = gsl_integration_qagiu(&F, L->u, 1e-13, 1e-10, WORK, P.outer, &rest, &error);
            if (st != GSL_SUCCESS && st != GSL_EROUND)
                fail(&P, gb_error_set(GB_ENUMERIC, "the saddle tail's quadrature failed: %s", gsl_strerror(st)));
            sum += rest;
        }
        *slot[k] = sum;
    }
    gsl_integration_workspace_free(P.outer);
    out->A1 = hypot(out->C1, out->S1);
    out->A2 = hypot(out->C2, out->S2);
    return P.status;
}

typedef struct direct {
    const gb_melnikov_forcing *f;
    double t0;
} direct;

static double perturbation(void *context, double q, double p, double t, const gb_melnikov_values *v)
{
    (void)q;
    const direct *d = context;
    const double s = t + d->t0;
    return -d->f->mu * (d->f->damping_per_mass ? p / v->M : p) + d->f->nu1 * v->S * cos(d->f->omega * s) + d->f->nu2 * v->S * cos(2.0 * d->f->omega * s + d->f->psi);
}

int gb_melnikov_direct(const gb_melnikov_model *m, const gb_melnikov_orbit *o, const gb_melnikov_forcing *f,
                       gb_melnikov_weight weight, double t0, double *value)
{
    direct d = {f, t0};
    return path_integral(m, o, weight, perturbation, &d, 2.0 * f->omega, 0, value);
}

/* ---- tables per octave of ω ---------------------------------------------------------------------- */

enum { OCTAVES = 5 }; /* ω_max = 16 · 2^k, k < OCTAVES: up to GB_MELNIKOV_TABLES_OMEGA */

struct gb_melnikov_tables {
    gb_melnikov_model model;
    gb_melnikov_orbit orbit;
    gb_melnikov_weight weight;
    gb_melnikov_table *table[OCTAVES];
};

/* The octave that serves ω (−1: above the tables, the adaptive path). */
static int octave(double omega)
{
    for (int k = 0; k < OCTAVES; k++)
        if (omega <= ldexp(16.0, k)) return k;
    return -1;
}

int gb_melnikov_tables_create(const gb_melnikov_model *m, const gb_melnikov_orbit *o, gb_melnikov_weight weight,
                              gb_melnikov_tables **out)
{
    *out = NULL;
    if (!(m->period > 0.0))
        return gb_error_set(GB_EDOM, "tables need a rotation (period > 0; a loop is integrated adaptively)");
    gb_melnikov_tables *T = calloc(1, sizeof *T);
    if (!T) return gb_error_set(GB_ENOMEM, "out of memory for the separatrix tables");
    T->model = *m, T->orbit = *o, T->weight = weight;
    *out = T;
    return GB_OK;
}

int gb_melnikov_tables_prepare(gb_melnikov_tables *T, double omega)
{
    if (!(isfinite(omega) && omega > 0.0)) return gb_error_set(GB_EDOM, "omega = %g (allowed: > 0)", omega);
    const int k = octave(omega);
    if (k < 0 || T->table[k]) return GB_OK;
    return gb_melnikov_table_create(&T->model, &T->orbit, T->weight, ldexp(16.0, k), &T->table[k]);
}

int gb_melnikov_tables_integrals(const gb_melnikov_tables *T, double omega, gb_melnikov_integrals *out)
{
    if (!(isfinite(omega) && omega > 0.0)) return gb_error_set(GB_EDOM, "omega = %g (allowed: > 0)", omega);
    const int k = octave(omega);
    if (k < 0) return gb_melnikov_integrals_compute(&T->model, &T->orbit, omega, T->weight, out);
    if (!T->table[k]) return gb_error_set(GB_EINVAL, "the separatrix table for omega = %g was not prepared", omega);
    return gb_melnikov_table_integrals(T->table[k], omega, out);
}

void gb_melnikov_tables_free(gb_melnikov_tables *T)
{
    if (!T) return;
    for (int k = 0; k < OCTAVES; k++) gb_melnikov_table_free(T->table[k]);
    free(T);
}
