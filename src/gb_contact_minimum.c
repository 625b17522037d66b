/* gb_contact_minimum — the continuous contact (paper §4, eqs 29–39, 70–72): Newton on the stationarity
 * conditions with a simplex fallback, every local minimum (branches) seeded on a grid, switch
 * detection between two verticals, and the contact's sensitivity and rate (see gb_contact.h). */
#include "gb_contact_internal.h"
#include "gb_surface_internal.h"

#include "gb_error.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_multimin.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- the continuous minimiser */

gb_contact_refine_def gb_contact_refine_default_def(void)
{
    return (gb_contact_refine_def){.max_iterations = 60, .step_tol = 1e-14, .pole_guard = 1e-6,
                                   .force_fallback = 0};
}

/* Keep φ in [0, π] and θ in [0, 2π): stepping over a pole continues on the other meridian. */
static void wrap_angles(double *phi, double *theta)
{
    if (*phi < 0.0) {
        *phi = -*phi;
        *theta += M_PI;
    } else if (*phi > M_PI) {
        *phi = 2.0 * M_PI - *phi;
        *theta += M_PI;
    }
    if (!(*theta >= 0.0 && *theta < 2.0 * M_PI)) *theta = fmod(*theta, 2.0 * M_PI); /* fmod returns θ there */
    if (*theta < 0.0) *theta += 2.0 * M_PI;
}

/* The surface at chart coordinates (a, b): eq 1's (φ, θ) through the paper's formulas, or POLAR_X. */
static void eval_in(const gb_surface *surface, gb_surface_chart chart, double a, double b, gb_surface_point *p)
{
    if (chart == GB_SURFACE_CHART_POLAR_Z) gb_surface_eval_jet(surface, a, b, p);
    else gb_surface_eval_chart(surface, chart, a, b, p);
}

static double height_in(const gb_surface *surface, gb_surface_chart chart, const double d[3], double a, double b)
{
    double x[3], phi = a, theta = b;
    if (chart != GB_SURFACE_CHART_POLAR_Z) gb_surface_chart_angles(chart, a, b, &phi, &theta);
    gb_surface_position(surface, phi, theta, x);
    return gb_vec_dot(d, x);
}

/* sin² of the chart's own polar angle at the evaluated point: its distance from the chart's poles. */
static double chart_sin2(gb_surface_chart chart, const gb_surface_point *p)
{
    return chart == GB_SURFACE_CHART_POLAR_Z ? p->u[0] * p->u[0] + p->u[1] * p->u[1]
                                             : p->u[1] * p->u[1] + p->u[2] * p->u[2];
}

/* h, its gradient (eqs 31–32) and Hessian (eq 34) at chart coordinates (a, b) for the unit vertical d. */
static void height_derivatives(const gb_surface *surface, gb_surface_chart chart, const double d[3], double phi,
                               double theta, gb_surface_point *p, double *h, double g[2],
                               double H[3])
{
    eval_in(surface, chart, phi, theta, p); /* the normal only at the point returned */
    *h = gb_vec_dot(d, p->x);
    g[0] = gb_vec_dot(d, p->x_phi);
    g[1] = gb_vec_dot(d, p->x_theta);
    H[0] = gb_vec_dot(d, p->x_phiphi);
    H[1] = gb_vec_dot(d, p->x_phitheta);
    H[2] = gb_vec_dot(d, p->x_thetatheta);
}

/* A stationary-point record from the surface evaluated at it (no new evaluation). */
static void fill_point_from(const gb_surface_point *p, gb_surface_chart chart, double a, double b, const double d[3],
                            gb_contact_point *out)
{
    out->chart = chart;
    out->chart_a = chart == GB_SURFACE_CHART_POLAR_Z ? 0.0 : a;
    out->chart_b = chart == GB_SURFACE_CHART_POLAR_Z ? 0.0 : b;
    out->height = gb_vec_dot(d, p->x);
    out->gradient[0] = gb_vec_dot(d, p->x_phi);
    out->gradient[1] = gb_vec_dot(d, p->x_theta);
    out->hessian[0] = gb_vec_dot(d, p->x_phiphi);
    out->hessian[1] = gb_vec_dot(d, p->x_phitheta);
    out->hessian[2] = gb_vec_dot(d, p->x_thetatheta);
    out->phi = p->phi;
    out->theta = p->theta;
    memcpy(out->rc, p->x, sizeof out->rc);
    memcpy(out->n_hat, p->n_hat, sizeof out->n_hat);
    memcpy(out->x_phi, p->x_phi, sizeof out->x_phi);
    memcpy(out->x_theta, p->x_theta, sizeof out->x_theta);
    double c[3];
    gb_vec_cross(d, p->n_hat, c);
    out->residual = gb_vec_norm(c);
    const double *H = out->hessian;
    out->is_minimum = H[0] > 0.0 && H[0] * H[2] - H[1] * H[1] > 0.0;
}

static void fill_point(const gb_surface *surface, gb_surface_chart chart, const double d[3], double a, double b,
                       gb_contact_point *out)
{
    gb_surface_point p;
    if (chart == GB_SURFACE_CHART_POLAR_Z) {
        gb_surface_eval(surface, a, b, &p);
    } else {
        gb_surface_eval_chart(surface, chart, a, b, &p);
        gb_surface_normal(&p);
    }
    fill_point_from(&p, chart, a, b, d, out);
}

/* Safeguarded Newton. Step: −H⁻¹g (Cramer's rule) when H is positive definite with λ_min > 1e-8 λ_max,
 * else the "saddle-free" step that divides each eigen-component of g by |λ|, floored at 1e-8 λ_max (a
 * descent direction); at most 0.5 rad; backtracking on
 * h with the Armijo factor 1e-4. Converged when the step is below step_tol, or when it stops
 * shrinking below 1e-8 rad (the rounding floor of the gradient). Returns 0 when converged to a
 * point with positive-definite Hessian, 1 otherwise (including nearing a pole). */
#define WHOLE_STEP 1e-4
static int newton(const gb_surface *surface, gb_surface_chart chart, const double d[3], double *phi, double *theta,
                  const gb_contact_refine_def *def, int *iterations, gb_surface_point *p)
{
    double h, g[2], H[3], previous_step = INFINITY;
    height_derivatives(surface, chart, d, *phi, *theta, p, &h, g, H);
    for (int it = 0; it < def->max_iterations; it++) {
        *iterations = it + 1;
        if (chart_sin2(chart, p) < def->pole_guard * def->pole_guard) return 1;
        double s[2];
        int definite;
        const double trace = H[0] + H[2], det = H[0] * H[2] - H[1] * H[1];
        if (H[0] > 0.0 && det > 1e-8 * trace * trace) {
            /* well-conditioned positive definite (λ_min ≥ det / trace > 1e-8 λ_max): s = −H⁻¹g */
            definite = 1;
            s[0] = -(H[2] * g[0] - H[1] * g[1]) / det;
            s[1] = -(H[0] * g[1] - H[1] * g[0]) / det;
        } else {
            /* Eigen-decomposition of the symmetric 2 × 2 Hessian. */
            const double mean = 0.5 * (H[0] + H[2]), half_diff = 0.5 * (H[0] - H[2]);
            const double radius = sqrt(half_diff * half_diff + H[1] * H[1]);
            const double lambda[2] = {mean - radius, mean + radius};
            double v0[2];
            if (radius > 0.0) {
                /* eigenvector of lambda[0]: (H01, λ0 − H00) or (λ0 − H11, H01), the better conditioned */
                double a0 = H[1], a1 = lambda[0] - H[0];
                if (fabs(H[0] - lambda[0]) < fabs(H[2] - lambda[0])) a0 = lambda[0] - H[2], a1 = H[1];
                const double n = sqrt(a0 * a0 + a1 * a1);
                v0[0] = a0 / n, v0[1] = a1 / n;
            } else {
                v0[0] = 1.0, v0[1] = 0.0;
            }
            const double v1[2] = {-v0[1], v0[0]};
            definite = lambda[0] > 0.0;
            const double scale = fmax(fabs(lambda[1]), 1e-300);
            const double floor_lambda = 1e-8 * scale;
            const double c0 = (v0[0] * g[0] + v0[1] * g[1]) / fmax(fabs(lambda[0]), floor_lambda);
            const double c1 = (v1[0] * g[0] + v1[1] * g[1]) / fmax(fabs(lambda[1]), floor_lambda);
            s[0] = -(c0 * v0[0] + c1 * v1[0]), s[1] = -(c0 * v0[1] + c1 * v1[1]);
        }
        double step = sqrt(s[0] * s[0] + s[1] * s[1]);
        if (!isfinite(step)) return 1;
        if (step > 0.5) s[0] *= 0.5 / step, s[1] *= 0.5 / step, step = 0.5;
        if (definite && (step < def->step_tol || (step < 1e-8 && step > 0.5 * previous_step)))
            return 0;
        previous_step = step;
        const double slope = g[0] * s[0] + g[1] * s[1];
        double t = 1.0, new_phi = *phi, new_theta = *theta, new_h = h;
        /* A definite step below WHOLE_STEP rad is taken whole, without computing its height. By
         * Taylor's theorem h(x + s) − h(x) ≤ −½ sᵀHs + |h‴| |s|³ / 6, so the Armijo test below passes
         * whenever λ_min(H) ≥ |h‴| |s| / 3; for a nearly flat minimum it may not, but a Newton step on a
         * positive-definite Hessian this short still converges locally, every iterate's Hessian is
         * tested again, and the point returned is tested as a minimum. Over 20 periods of the Table 1
         * rolling run of I (16 000 continuation solves, certificate skipped in a build for measuring)
         * height evaluations fell from 12 718 to 2 988, and the run ended in the same bits. */
        int accepted = definite && step < WHOLE_STEP;
        if (accepted) new_phi += s[0], new_theta += s[1], wrap_angles(&new_phi, &new_theta);
        for (int k = 0; k < 50 && !accepted; k++, t *= 0.5) {
            new_phi = *phi + t * s[0];
            new_theta = *theta + t * s[1];
            wrap_angles(&new_phi, &new_theta);
            new_h = height_in(surface, chart, d, new_phi, new_theta);
            accepted = new_h <= h + 1e-4 * t * slope || (definite && t * step < WHOLE_STEP);
        }
        if (!accepted) return 1;
        *phi = new_phi;
        *theta = new_theta;
        height_derivatives(surface, chart, d, *phi, *theta, p, &h, g, H);
    }
    return 1;
}

/* The fallback: nmsimplex2 over a tangent chart of the sphere of directions centred at u0,
 * u(s, t) = (u0 + s e1 + t e2)/|·|, which has no pole; h = d·r(u) u with r from (φ, θ) of u. */
typedef struct chart {
    const gb_surface *surface;
    double d[3], u0[3], e1[3], e2[3];
} chart;

static void chart_angles(const chart *c, double s, double t, double *phi, double *theta)
{
    double u[3];
    for (int k = 0; k < 3; k++) u[k] = c->u0[k] + s * c->e1[k] + t * c->e2[k];
    const double n = gb_vec_norm(u);
    *phi = acos(fmax(-1.0, fmin(1.0, u[2] / n)));
    *theta = atan2(u[1], u[0]);
    if (*theta < 0.0) *theta += 2.0 * M_PI;
}

static double chart_height(const gsl_vector *v, void *params)
{
    const chart *c = params;
    double phi, theta, x[3];
    chart_angles(c, gsl_vector_get(v, 0), gsl_vector_get(v, 1), &phi, &theta);
    gb_surface_position(c->surface, phi, theta, x);
    return gb_vec_dot(c->d, x);
}

static int simplex_fallback(const gb_surface *surface, const double d[3], double *phi,
                            double *theta)
{
    chart c = {.surface = surface};
    memcpy(c.d, d, sizeof c.d);
    gb_surface_direction(*phi, *theta, c.u0);
    /* e1 ⊥ u0 from the coordinate axis least aligned with u0; e2 = u0 × e1. */
    int axis = 0;
    for (int k = 1; k < 3; k++)
        if (fabs(c.u0[k]) < fabs(c.u0[axis])) axis = k;
    double e[3] = {0, 0, 0};
    e[axis] = 1.0;
    gb_vec_cross(c.u0, e, c.e1);
    const double n1 = gb_vec_norm(c.e1);
    for (int k = 0; k < 3; k++) c.e1[k] /= n1;
    gb_vec_cross(c.u0, c.e1, c.e2);

    gsl_multimin_function f = {.n = 2, .f = chart_height, .params = &c};
    gsl_multimin_fminimizer *m = gsl_multimin_fminimizer_alloc(gsl_multimin_fminimizer_nmsimplex2, 2);
    gsl_vector *x = gsl_vector_calloc(2), *step = gsl_vector_alloc(2);
    if (!m || !x || !step) {
        gsl_multimin_fminimizer_free(m);
        gsl_vector_free(x);
        gsl_vector_free(step);
        return gb_error_set(GB_ENOMEM, "out of memory for the contact fallback minimiser");
    }
    gsl_vector_set_all(step, 0.02);
    int status = gsl_multimin_fminimizer_set(m, &f, x, step);
    int converged = 0;
    /* Converged when the simplex is below 1e-8, or when, below 1e-6, its best value has not moved
     * for 100 iterations: a quadratic minimum is flat to rounding within √(ε/λ) of its centre,
     * which exceeds 1e-8 when the Hessian's smaller eigenvalue λ is below ~1. */
    double last_best = INFINITY;
    int still = 0;
    for (int it = 0; !status && it < 5000 && !converged; it++) {
        status = gsl_multimin_fminimizer_iterate(m);
        if (status) break;
        const double size = gsl_multimin_fminimizer_size(m), best = gsl_multimin_fminimizer_minimum(m);
        still = best < last_best ? 0 : still + 1;
        last_best = fmin(last_best, best);
        converged = gsl_multimin_test_size(size, 1e-8) == GSL_SUCCESS || (size < 1e-6 && still >= 100);
    }
    if (converged)
        chart_angles(&c, gsl_vector_get(gsl_multimin_fminimizer_x(m), 0), gsl_vector_get(gsl_multimin_fminimizer_x(m), 1), phi, theta);
    gsl_multimin_fminimizer_free(m);
    gsl_vector_free(x);
    gsl_vector_free(step);
    if (!converged)
        return gb_error_set(GB_ENOCONV,
                            "contact fallback (nmsimplex2) did not converge for z_b = (%.6g, %.6g, %.6g)",
                            d[0], d[1], d[2]);
    return GB_OK;
}

/* The chart Newton works in from (φ, θ): POLAR_X within the polar cap, where ∂θx → 0 makes the
 * (φ, θ) Hessian singular (the sphere's minimum at ±e_z is a regular point of POLAR_X). */
static gb_surface_chart chart_for(double phi)
{
    /* sin φ < CAP decided by comparing φ with the two roots of sin φ = CAP, asin(CAP) and π − asin(CAP),
     * where φ lies more than 1e-9 rad from both: there the true sin differs from CAP by more than 1e-11
     * and libm's sin by less than an ulp from the true one, so the comparison is the one sin(φ) would
     * give, without its cost (one sin a Newton solve, 3 % of a continuous run). Elsewhere, and for φ
     * outside [0, π], sin itself. verify/s4_contact.c checks the roots and the rule on both sides. */
    static const double root = 0.010000166674167114; /* asin(1e-2), within an ulp */
    if (phi >= 0.0 && phi <= M_PI && fabs(phi - root) > 1e-9 && fabs(phi - (M_PI - root)) > 1e-9)
        return phi < root || phi > M_PI - root ? GB_SURFACE_CHART_POLAR_X : GB_SURFACE_CHART_POLAR_Z;
    return sin(phi) < GB_CONTACT_POLAR_CAP ? GB_SURFACE_CHART_POLAR_X : GB_SURFACE_CHART_POLAR_Z;
}

/* Newton in `chart` from (φ, θ): on success (φ, θ) is the minimum and (*a, *b) its chart coordinates. */
static int newton_in(const gb_surface *surface, gb_surface_chart chart, const double d[3], double *phi, double *theta,
                     const gb_contact_refine_def *def, int *iterations, gb_surface_point *p, double *a, double *b)
{
    gb_surface_chart_coordinates(chart, *phi, *theta, a, b);
    int its = 0;
    const int status = newton(surface, chart, d, a, b, def, &its, p);
    *iterations += its;
    if (status) return status;
    if (chart == GB_SURFACE_CHART_POLAR_Z) *phi = *a, *theta = *b; /* the iterate's own bits */
    else gb_surface_chart_angles(chart, *a, *b, phi, theta);
    return 0;
}

/* Newton from (φ, θ) in the chart chart_for picks, and once more in POLAR_X when the (φ, θ) chart's
 * iterates run into its pole. A minimum found in one chart but lying in the other's domain is polished
 * there (one or two iterations), so that the chart of a point returned is chart_for(φ) of the point itself;
 * if that polish fails, the first answer stands. On success (φ, θ) is the minimum and (*chart, *a, *b) its chart. */
static int newton_charted(const gb_surface *surface, const double d[3], double *phi, double *theta,
                          const gb_contact_refine_def *def, int *iterations, gb_surface_point *p,
                          gb_surface_chart *chart, double *a, double *b)
{
    double at[2] = {*phi, *theta};
    *chart = chart_for(*phi);
    if (newton_in(surface, *chart, d, &at[0], &at[1], def, iterations, p, a, b)) {
        if (*chart != GB_SURFACE_CHART_POLAR_Z || chart_sin2(*chart, p) >= def->pole_guard * def->pole_guard) return 1;
        *chart = GB_SURFACE_CHART_POLAR_X;
        at[0] = *phi, at[1] = *theta;
        if (newton_in(surface, *chart, d, &at[0], &at[1], def, iterations, p, a, b)) return 1;
    }
    const gb_surface_chart own = chart_for(at[0]);
    if (own != *chart) {
        double again[2] = {at[0], at[1]}, a2, b2;
        gb_surface_point q;
        if (newton_in(surface, own, d, &again[0], &again[1], def, iterations, &q, &a2, &b2) == 0) {
            *chart = own, *p = q, *a = a2, *b = b2;
            at[0] = again[0], at[1] = again[1];
        }
    }
    *phi = at[0], *theta = at[1];
    return 0;
}

int gb_contact_refine(const gb_surface *surface, const double zb[3], double phi0, double theta0,
                      const gb_contact_refine_def *def, gb_contact_point *out)
{
    double d[3];
    int status = gb_contact_unit_vertical(zb, d);
    if (status) return status;
    if (!(isfinite(phi0) && isfinite(theta0)))
        return gb_error_set(GB_EDOM, "contact start (%g, %g) is not finite", phi0, theta0);
    double phi = phi0, theta = theta0;
    wrap_angles(&phi, &theta);
    int iterations = 0, fallback = def->force_fallback;
    gb_surface_point at; /* the surface at the returned point, when Newton evaluated it last */
    gb_surface_chart chart = GB_SURFACE_CHART_POLAR_Z;
    double a = phi, b = theta;
    int have_point = 0;
    if (!fallback) {
        double try_phi = phi, try_theta = theta;
        if (newton_charted(surface, d, &try_phi, &try_theta, def, &iterations, &at, &chart, &a, &b) == 0) {
            phi = try_phi, theta = try_theta;
            have_point = 1;
        } else {
            fallback = 1;
        }
    }
    if (fallback) {
        status = simplex_fallback(surface, d, &phi, &theta);
        if (status) return status;
        /* Polish with Newton; keep the simplex point if that fails. */
        double polish_phi = phi, polish_theta = theta;
        int polish_iterations = 0;
        gb_contact_refine_def polish = *def;
        if (newton_charted(surface, d, &polish_phi, &polish_theta, &polish, &polish_iterations, &at, &chart, &a, &b) == 0 &&
            hypot(sin(phi) * (polish_theta - theta), polish_phi - phi) < 1e-4) {
            phi = polish_phi, theta = polish_theta;
            have_point = 1;
        }
        iterations += polish_iterations;
    }
    if (have_point) {
        gb_surface_normal(&at);
        fill_point_from(&at, chart, a, b, d, out);
    } else {
        chart = chart_for(phi);
        gb_surface_chart_coordinates(chart, phi, theta, &a, &b);
        fill_point(surface, chart, d, a, b, out);
    }
    out->phi = phi, out->theta = theta;
    out->iterations = iterations;
    out->used_fallback = fallback;
    return GB_OK;
}

void gb_contact_chart_offset(const gb_contact_point *p, double da, double db, double *phi, double *theta)
{
    if (p->chart == GB_SURFACE_CHART_POLAR_Z) {
        *phi = p->phi + da, *theta = p->theta + db;
        return;
    }
    double a = p->chart_a + da, b = p->chart_b + db;
    wrap_angles(&a, &b);
    gb_surface_chart_angles(p->chart, a, b, phi, theta);
}

/* The length of a chart step (Δa, Δb) at `p` on the unit sphere of directions, √(Δa² + sin²a Δb²). */
static double chart_step_length(const gb_contact_point *p, double da, double db)
{
    return hypot(da, sin(p->chart == GB_SURFACE_CHART_POLAR_Z ? p->phi : p->chart_a) * db);
}

/* ---------------------------------------------------------------- branches */

/* Is node (i, j) no higher than its 8 neighbours? θ is periodic; across a pole the neighbour row
 * is the same row on the opposite meridian (θ + π). The same-row neighbours are tested first, which
 * rejects most nodes after one or two comparisons. */
static int is_discrete_minimum(const double *h, const gb_contact_grid_def *def, size_t i, size_t j)
{
    const size_t np = def->n_phi, nt = def->n_theta;
    const double *row = h + i * nt;
    const double centre = row[j];
    const size_t jm = j ? j - 1 : nt - 1, jp = j + 1 < nt ? j + 1 : 0;
    if (row[jm] < centre || row[jp] < centre) return 0;
    for (int di = -1; di <= 1; di += 2) {
        const long r = (long)i + di;
        const int across_pole = r < 0 || r >= (long)np;
        const double *other = across_pole ? row : h + (size_t)r * nt;
        const size_t shift = across_pole ? nt / 2 : 0;
        const size_t cols[3] = {(jm + shift) % nt, (j + shift) % nt, (jp + shift) % nt};
        for (int c = 0; c < 3; c++)
            if (other[cols[c]] < centre) return 0;
    }
    return 1;
}

static int same_point(const double a[3], const double b[3])
{
    const double dx[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    return gb_vec_norm(dx) < 1e-7;
}

static int compare_height(const void *a, const void *b)
{
    const double ha = ((const gb_contact_point *)a)->height, hb = ((const gb_contact_point *)b)->height;
    return (ha > hb) - (ha < hb);
}

int gb_contact_branches_find(const gb_contact_grid *grid, const double zb[3],
                             const gb_contact_refine_def *def, gb_contact_branches *out)
{
    double d[3];
    int status = gb_contact_unit_vertical(zb, d);
    if (status) return status;
    const gb_contact_grid_def *gd = &grid->def;
    double *h = malloc(grid->size * sizeof *h);
    if (!h) return gb_error_set(GB_ENOMEM, "out of memory for %zu node heights", grid->size);
    for (size_t k = 0; k < grid->size; k++) h[k] = node_height(d, grid->x + 3 * k);
    out->count = 0;
    out->seeds = 0;
    const double *last_seed = NULL;
    for (size_t i = 0; i < gd->n_phi && !status; i++)
        for (size_t j = 0; j < gd->n_theta && !status; j++) {
            if (!is_discrete_minimum(h, gd, i, j)) continue;
            const double *x = grid->x + 3 * (i * gd->n_theta + j);
            if (last_seed && memcmp(x, last_seed, 3 * sizeof *x) == 0) continue; /* a repeated pole */
            last_seed = x;
            out->seeds++;
            gb_contact_point p;
            status = gb_contact_refine(&grid->surface, d, node_phi(gd, i), node_theta(gd, j), def, &p);
            if (status || !p.is_minimum) continue;
            int known = 0;
            for (size_t b = 0; b < out->count && !known; b++) known = same_point(out->branch[b].rc, p.rc);
            if (known) continue;
            if (out->count == GB_CONTACT_BRANCH_MAX)
                status = gb_error_set(GB_ENUMERIC, "more than %d local minima of the height",
                                      GB_CONTACT_BRANCH_MAX);
            else
                out->branch[out->count++] = p;
        }
    free(h);
    if (status) return status;
    if (out->count == 0)
        return gb_error_set(GB_ENOCONV,
                            "no local minimum of the height converged for z_b = (%.6g, %.6g, %.6g)",
                            d[0], d[1], d[2]);
    qsort(out->branch, out->count, sizeof out->branch[0], compare_height);
    out->gap = out->count > 1 ? out->branch[1].height - out->branch[0].height : INFINITY;
    return GB_OK;
}

/* ---------------------------------------------------------------- switching */

const char *gb_contact_switch_name(gb_contact_switch_kind kind)
{
    static const char *const names[] = {"same-branch", "overtaken", "branch-lost"};
    return (unsigned)kind < 3 ? names[kind] : "unknown";
}

int gb_contact_switch_detect(const gb_contact_grid *grid, const double zb_from[3],
                             const gb_contact_point *previous, const double zb_to[3],
                             double max_step, const gb_contact_refine_def *def,
                             gb_contact_switch *out)
{
    double a[3], b[3];
    int status = gb_contact_unit_vertical(zb_from, a);
    if (!status) status = gb_contact_unit_vertical(zb_to, b);
    if (status) return status;
    if (!(max_step > 0.0 && max_step <= 0.5))
        return gb_error_set(GB_EDOM, "continuation step %g rad is out of range (allowed: 0 < step <= 0.5)",
                            max_step);
    const double angle = acos(fmax(-1.0, fmin(1.0, gb_vec_dot(a, b))));
    if (angle > M_PI - 1e-6)
        return gb_error_set(GB_EDOM, "z_b turns by %.6g rad: the great circle to continue along is "
                            "not defined for opposite verticals", angle);
    const int steps = angle > 0.0 ? (int)ceil(angle / max_step) : 1;
    const gb_surface *surface = &grid->surface;
    gb_contact_point current = *previous;
    double current_zb[3];
    memcpy(current_zb, a, sizeof a);
    int lost = !previous->is_minimum;
    for (int k = 1; k <= steps && !lost; k++) {
        /* Spherical interpolation between a and b. */
        double z[3];
        const double s = angle > 0.0 ? sin(angle) : 1.0;
        const double wa = angle > 0.0 ? sin((1.0 - (double)k / steps) * angle) / s : 0.0;
        const double wb = angle > 0.0 ? sin((double)k / steps * angle) / s : 1.0;
        for (int i = 0; i < 3; i++) z[i] = wa * a[i] + wb * b[i];
        /* Predictor from eq 72, then Newton; a jump far beyond the prediction means the branch
         * folded away and Newton slid into another basin. */
        double dq[2][3], predicted[2] = {current.phi, current.theta};
        double step_norm = 0.0;
        if (gb_contact_sensitivity(surface, current_zb, &current, dq) == GB_OK) {
            const double dz[3] = {z[0] - current_zb[0], z[1] - current_zb[1], z[2] - current_zb[2]};
            gb_contact_chart_offset(&current, gb_vec_dot(dq[0], dz), gb_vec_dot(dq[1], dz), &predicted[0], &predicted[1]);
            step_norm = chart_step_length(&current, gb_vec_dot(dq[0], dz), gb_vec_dot(dq[1], dz));
        } else {
            lost = 1;
            break;
        }
        gb_contact_point next;
        status = gb_contact_refine(surface, z, predicted[0], predicted[1], def, &next);
        if (status) return status;
        double xp[3];
        gb_surface_position(surface, predicted[0], predicted[1], xp);
        const double dx[3] = {next.rc[0] - xp[0], next.rc[1] - xp[1], next.rc[2] - xp[2]};
        if (!next.is_minimum || gb_vec_norm(dx) > 0.5 * step_norm + 1e-3) lost = 1;
        current = next;
        memcpy(current_zb, z, sizeof z);
    }
    gb_contact_branches branches;
    status = gb_contact_branches_find(grid, b, def, &branches);
    if (status) return status;
    out->continued = current;
    out->global = branches.branch[0];
    if (lost) out->kind = GB_CONTACT_BRANCH_LOST;
    else if (same_point(current.rc, out->global.rc) || current.height <= out->global.height)
        out->kind = GB_CONTACT_SAME_BRANCH;
    else out->kind = GB_CONTACT_OVERTAKEN;
    return GB_OK;
}

/* ---------------------------------------------------------------- sensitivity */

int gb_contact_sensitivity(const gb_surface *surface, const double zb[3],
                           const gb_contact_point *contact, double dq_dzb[2][3])
{
    (void)surface;
    const int status = gb_contact_vertical_check(zb); /* the Hessian and tangents are the contact's: z_b only checked */
    if (status) return status;
    const double *H = contact->hessian;
    const double det = H[0] * H[2] - H[1] * H[1];
    const double size = fmax(fabs(H[0]), fmax(fabs(H[1]), fabs(H[2])));
    if (!(fabs(det) > 1e-12 * size * size))
        return gb_error_set(GB_ENUMERIC,
                            "contact Hessian (eq 34) is singular at (phi, theta) = (%.9g, %.9g): "
                            "det = %.3g, the minimiser is not locally well defined (eq 72)",
                            contact->phi, contact->theta, det);
    /* −H⁻¹ = −(1/det) [[H_θθ, −H_φθ], [−H_φθ, H_φφ]] applied to [∂φxᵀ; ∂θxᵀ] (eq 72). */
    for (int k = 0; k < 3; k++) {
        dq_dzb[0][k] = -(H[2] * contact->x_phi[k] - H[1] * contact->x_theta[k]) / det;
        dq_dzb[1][k] = -(-H[1] * contact->x_phi[k] + H[0] * contact->x_theta[k]) / det;
    }
    return GB_OK;
}

int gb_contact_rate(const gb_surface *surface, const double zb[3], const gb_contact_point *contact,
                    const double omega[3], double rc_dot[3], double q_dot[2])
{
    double d[3], dq[2][3];
    int status = gb_contact_unit_vertical(zb, d);
    if (!status) status = gb_contact_sensitivity(surface, d, contact, dq);
    if (status) return status;
    gb_contact_rate_from(dq, d, contact, omega, rc_dot, q_dot);
    return GB_OK;
}

void gb_contact_rate_from(const double dq_dzb[2][3], const double d[3], const gb_contact_point *contact,
                          const double omega[3], double rc_dot[3], double q_dot[2])
{
    double zb_dot[3];
    gb_vec_cross(d, omega, zb_dot); /* ż_b = −ω × z_b = z_b × ω (eq 24) */
    const double rates[2] = {gb_vec_dot(dq_dzb[0], zb_dot), gb_vec_dot(dq_dzb[1], zb_dot)};
    for (int k = 0; k < 3; k++) rc_dot[k] = contact->x_phi[k] * rates[0] + contact->x_theta[k] * rates[1];
    if (q_dot) q_dot[0] = rates[0], q_dot[1] = rates[1];
}

