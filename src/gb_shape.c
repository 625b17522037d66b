#include "gb_shape.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_multimin.h>
#include <gsl/gsl_roots.h>
#include <libqhull_r/qhull_ra.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

gb_shape_def gb_shape_default_def(void)
{
    return (gb_shape_def){
        /* The survey grid resolves the narrowest curvature feature (the 5φ twist of morphology I
         * has period 2π/5 in φ, i.e. 36 survey cells) and the local minimiser does the rest. */
        .survey_phi = 180,
        .survey_theta = 360,
        .refine_starts = 4,
        .beta_tol = 1e-12,
        .equilibria_phi = 90,
        .equilibria_theta = 180,
        .polar_cap = 0.05,
        .hull_phi = 200,
        .hull_theta = 400,
        /* 0.1 rad is 6.4 sample spacings of the default 200-row sample and below the 0.63 rad
         * period of the narrowest feature (the 5φ twist of morphology I). */
        .hull_neighbourhood = 0.1,
    };
}

void gb_shape_curvature(const gb_surface *surface, double phi, double theta, gb_curvature *out)
{
    gb_surface_point p;
    gb_surface_eval(surface, phi, theta, &p);
    const double inward[3] = {-p.n_hat[0], -p.n_hat[1], -p.n_hat[2]};
    const double E = gb_vec_dot(p.x_phi, p.x_phi), F = gb_vec_dot(p.x_phi, p.x_theta),
                 G = gb_vec_dot(p.x_theta, p.x_theta);
    const double L = gb_vec_dot(p.x_phiphi, inward), M = gb_vec_dot(p.x_phitheta, inward),
                 N = gb_vec_dot(p.x_thetatheta, inward);
    const double det = E * G - F * F;
    out->K = (L * N - M * M) / det;
    out->H = (E * N - 2.0 * F * M + G * L) / (2.0 * det);
    const double disc = sqrt(fmax(out->H * out->H - out->K, 0.0));
    out->kappa_min = out->H - disc;
    out->kappa_max = out->H + disc;
    out->area_element = sqrt(gb_vec_dot(p.n, p.n));
}

/* ---- local refinement of a curvature minimum ------------------------------------------------ */

typedef struct curvature_target {
    const gb_surface *surface;
    int use_kappa; /* 1: κ₁, 0: K */
} curvature_target;

static double clamp_phi(double phi)
{
    const double margin = 1e-9;
    return fmin(fmax(phi, margin), M_PI - margin);
}

static double curvature_objective(const gsl_vector *v, void *params)
{
    const curvature_target *t = params;
    gb_curvature c;
    gb_shape_curvature(t->surface, clamp_phi(gsl_vector_get(v, 0)), gsl_vector_get(v, 1), &c);
    return t->use_kappa ? c.kappa_min : c.K;
}

/* Polish a grid minimum with the Nelder–Mead simplex (the objective is smooth away from the
 * poles; derivatives of the curvature would need third derivatives of x). */
static double refine_minimum(const curvature_target *t, double step, double *phi, double *theta)
{
    gsl_multimin_fminimizer *m = gsl_multimin_fminimizer_alloc(gsl_multimin_fminimizer_nmsimplex2, 2);
    gsl_vector *x = gsl_vector_alloc(2), *steps = gsl_vector_alloc(2);
    gsl_multimin_function f = {curvature_objective, 2, (void *)t};
    gsl_vector_set(x, 0, *phi);
    gsl_vector_set(x, 1, *theta);
    gsl_vector_set_all(steps, step);
    gsl_multimin_fminimizer_set(m, &f, x, steps);
    for (int iter = 0; iter < 1000; iter++) {
        if (gsl_multimin_fminimizer_iterate(m)) break;
        if (gsl_multimin_test_size(gsl_multimin_fminimizer_size(m), 1e-11) == GSL_SUCCESS) break;
    }
    *phi = clamp_phi(gsl_vector_get(m->x, 0));
    *theta = fmod(gsl_vector_get(m->x, 1), 2.0 * M_PI);
    if (*theta < 0.0) *theta += 2.0 * M_PI;
    const double value = m->fval;
    gsl_vector_free(x);
    gsl_vector_free(steps);
    gsl_multimin_fminimizer_free(m);
    return value;
}

/* Indices of up to `count` lowest local minima of a periodic-in-θ grid (8 neighbours). */
static size_t grid_local_minima(const double *values, size_t nphi, size_t ntheta, size_t count,
                                size_t *out)
{
    size_t found = 0;
    for (size_t i = 0; i < nphi; i++)
        for (size_t j = 0; j < ntheta; j++) {
            const double v = values[i * ntheta + j];
            int is_min = 1;
            for (int di = -1; di <= 1 && is_min; di++)
                for (int dj = -1; dj <= 1; dj++) {
                    if (!di && !dj) continue;
                    const long ii = (long)i + di;
                    if (ii < 0 || ii >= (long)nphi) continue;
                    const size_t jj = (j + ntheta + (size_t)(dj + 1) - 1) % ntheta;
                    if (values[(size_t)ii * ntheta + jj] < v) { is_min = 0; break; }
                }
            if (!is_min) continue;
            /* insertion into the sorted list of the best `count` */
            size_t k = found < count ? found++ : count;
            if (k == count && v >= values[out[count - 1]]) continue;
            if (k == count) k = count - 1;
            while (k > 0 && values[out[k - 1]] > v) { out[k] = out[k - 1]; k--; }
            out[k] = i * ntheta + j;
        }
    return found;
}

int gb_shape_curvature_survey(const gb_surface *surface, const gb_shape_def *def,
                              gb_curvature_survey *out)
{
    const size_t nphi = def->survey_phi, ntheta = def->survey_theta;
    if (nphi < 3 || ntheta < 3 || def->refine_starts < 1)
        return gb_error_set(GB_EDOM, "curvature survey grid %zux%zu must be at least 3x3 with at "
                            "least one refinement start", nphi, ntheta);
    double *K = malloc(nphi * ntheta * sizeof *K), *kappa = malloc(nphi * ntheta * sizeof *kappa);
    size_t *starts = malloc(def->refine_starts * sizeof *starts);
    if (!K || !kappa || !starts) {
        free(K), free(kappa), free(starts);
        return gb_error_set(GB_ENOMEM, "curvature survey: out of memory for %zux%zu", nphi, ntheta);
    }
    const double dphi = M_PI / nphi, dtheta = 2.0 * M_PI / ntheta;
    double area = 0.0, negative = 0.0;
    for (size_t i = 0; i < nphi; i++)
        for (size_t j = 0; j < ntheta; j++) {
            gb_curvature c;
            gb_shape_curvature(surface, (i + 0.5) * dphi, (j + 0.5) * dtheta, &c);
            K[i * ntheta + j] = c.K;
            kappa[i * ntheta + j] = c.kappa_min;
            const double dA = c.area_element * dphi * dtheta;
            area += dA;
            if (c.K < 0.0) negative += dA;
        }
    out->area = area;
    out->negative_fraction = negative / area;
    for (int which = 0; which < 2; which++) {
        const double *values = which ? kappa : K;
        curvature_target target = {surface, which};
        const size_t n = grid_local_minima(values, nphi, ntheta, def->refine_starts, starts);
        double best = INFINITY, best_phi = 0.0, best_theta = 0.0;
        for (size_t k = 0; k < n; k++) {
            double phi = (starts[k] / ntheta + 0.5) * dphi, theta = (starts[k] % ntheta + 0.5) * dtheta;
            const double grid_value = values[starts[k]];
            double value = refine_minimum(&target, 0.5 * dphi, &phi, &theta);
            if (!(value <= grid_value)) { /* the simplex never ends worse than its start */
                value = grid_value;
                phi = (starts[k] / ntheta + 0.5) * dphi;
                theta = (starts[k] % ntheta + 0.5) * dtheta;
            }
            if (value < best) best = value, best_phi = phi, best_theta = theta;
        }
        if (which) out->kappa_min = best, out->kappa_min_phi = best_phi, out->kappa_min_theta = best_theta;
        else out->K_min = best, out->K_min_phi = best_phi, out->K_min_theta = best_theta;
    }
    free(K), free(kappa), free(starts);
    return GB_OK;
}

/* ---- convexity limit ------------------------------------------------------------------------ */

typedef struct limit_params {
    const gb_morphology *morphology;
    const gb_shape_def *def;
    int status;
    gb_curvature_survey last;
} limit_params;

static double min_kappa_at_beta(double beta, void *params)
{
    limit_params *lp = params;
    gb_surface surface = {lp->morphology, beta};
    int status = gb_shape_curvature_survey(&surface, lp->def, &lp->last);
    if (status && !lp->status) lp->status = status;
    return lp->last.kappa_min;
}

int gb_shape_convexity_limit(const gb_morphology *morphology, const gb_shape_def *def,
                             double *beta_limit, double *where_phi, double *where_theta)
{
    limit_params lp = {.morphology = morphology, .def = def, .status = GB_OK};
    double lo = 1e-6, hi = 0.2;
    const double f_lo = min_kappa_at_beta(lo, &lp), f_hi = min_kappa_at_beta(hi, &lp);
    if (lp.status) return lp.status;
    if (!(f_lo > 0.0 && f_hi < 0.0))
        return gb_error_set(GB_ENOCONV,
                            "convexity limit of morphology %s not bracketed in [%g, %g]: min "
                            "kappa = %g, %g",
                            morphology->name, lo, hi, f_lo, f_hi);
    gsl_root_fsolver *solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    gsl_function f = {min_kappa_at_beta, &lp};
    gsl_root_fsolver_set(solver, &f, lo, hi);
    int status = GSL_CONTINUE;
    for (int iter = 0; iter < 200 && status == GSL_CONTINUE; iter++) {
        if ((status = gsl_root_fsolver_iterate(solver))) break;
        lo = gsl_root_fsolver_x_lower(solver);
        hi = gsl_root_fsolver_x_upper(solver);
        status = gsl_root_test_interval(lo, hi, def->beta_tol, 0.0);
    }
    *beta_limit = gsl_root_fsolver_root(solver);
    gsl_root_fsolver_free(solver);
    if (lp.status) return lp.status;
    if (status != GSL_SUCCESS)
        return gb_error_set(GB_ENOCONV, "convexity limit of morphology %s: Brent did not reach "
                            "%g (%s)", morphology->name, def->beta_tol, gsl_strerror(status));
    min_kappa_at_beta(*beta_limit, &lp);
    if (where_phi) *where_phi = lp.last.kappa_min_phi;
    if (where_theta) *where_theta = lp.last.kappa_min_theta;
    return GB_OK;
}

/* ---- critical points of r ------------------------------------------------------------------- */

const char *gb_shape_equilibrium_name(int type)
{
    static const char *names[] = {"stable", "saddle", "unstable"};
    return type >= 0 && type <= 2 ? names[type] : "unknown";
}

/* The surface at (φ, θ) with r and its derivatives those of the distance from the centroid, ρ = |x|: for a body
 * moved to its centroid (gb_morphology.origin) the equilibria are the critical points of ρ, not of the chart's r.
 * ρ_a = x·x_a / ρ, ρ_ab = (x_a·x_b + x·x_ab) / ρ − ρ_a ρ_b / ρ. The paper's bodies are not moved: r as it is. */
static void eval_about_centroid(const gb_surface *surface, double phi, double theta, gb_surface_point *p)
{
    gb_surface_eval(surface, phi, theta, p);
    if (!surface->morphology->moved) return;
    const double rho = sqrt(gb_vec_dot(p->x, p->x));
    const double ra = gb_vec_dot(p->x, p->x_phi) / rho, rb = gb_vec_dot(p->x, p->x_theta) / rho;
    p->r_phiphi = (gb_vec_dot(p->x_phi, p->x_phi) + gb_vec_dot(p->x, p->x_phiphi) - ra * ra) / rho;
    p->r_phitheta = (gb_vec_dot(p->x_phi, p->x_theta) + gb_vec_dot(p->x, p->x_phitheta) - ra * rb) / rho;
    p->r_thetatheta = (gb_vec_dot(p->x_theta, p->x_theta) + gb_vec_dot(p->x, p->x_thetatheta) - rb * rb) / rho;
    p->r = rho, p->r_phi = ra, p->r_theta = rb;
}

static double sphere_gradient(const gb_surface_point *p)
{
    const double g_theta = p->r_theta / sin(p->phi);
    return sqrt(p->r_phi * p->r_phi + g_theta * g_theta);
}

/* Newton on (r_φ, r_θ) = 0 with the analytic Hessian; steps capped at 0.1 rad. */
static int newton_critical_point(const gb_surface *surface, double *phi, double *theta,
                                 gb_surface_point *p)
{
    for (int iter = 0; iter < 100; iter++) {
        eval_about_centroid(surface, *phi, *theta, p);
        const double a = p->r_phiphi, b = p->r_phitheta, d = p->r_thetatheta;
        const double det = a * d - b * b;
        if (det == 0.0) return 0;
        double step_phi = -(d * p->r_phi - b * p->r_theta) / det;
        double step_theta = -(-b * p->r_phi + a * p->r_theta) / det;
        const double size = hypot(step_phi, step_theta);
        if (size > 0.1) step_phi *= 0.1 / size, step_theta *= 0.1 / size;
        *phi += step_phi;
        *theta += step_theta;
        if (*phi <= 0.0 || *phi >= M_PI) return 0;
        if (size < 1e-14) break;
    }
    *theta = fmod(*theta, 2.0 * M_PI);
    if (*theta < 0.0) *theta += 2.0 * M_PI;
    eval_about_centroid(surface, *phi, *theta, p);
    /* converged when the gradient is at round-off level of r ≈ 1 */
    return sphere_gradient(p) < 1e-12;
}

int gb_shape_equilibria(const gb_surface *surface, const gb_shape_def *def, gb_equilibria *out)
{
    const size_t nphi = def->equilibria_phi, ntheta = def->equilibria_theta;
    if (nphi < 3 || ntheta < 3 || !(def->polar_cap > 0.0 && def->polar_cap < 0.5))
        return gb_error_set(GB_EDOM, "equilibria grid %zux%zu must be at least 3x3 and the "
                            "polar cap in (0, 0.5) rad (got %g)", nphi, ntheta, def->polar_cap);
    double *g2 = malloc(nphi * ntheta * sizeof *g2);
    size_t *starts = malloc(nphi * ntheta * sizeof *starts);
    if (!g2 || !starts) {
        free(g2), free(starts);
        return gb_error_set(GB_ENOMEM, "equilibria: out of memory");
    }
    const double cap = def->polar_cap;
    const double dphi = (M_PI - 2.0 * cap) / nphi, dtheta = 2.0 * M_PI / ntheta;
    for (size_t i = 0; i < nphi; i++)
        for (size_t j = 0; j < ntheta; j++) {
            gb_surface_point p;
            eval_about_centroid(surface, cap + (i + 0.5) * dphi, (j + 0.5) * dtheta, &p);
            const double g = sphere_gradient(&p);
            g2[i * ntheta + j] = g * g;
        }
    const size_t n = grid_local_minima(g2, nphi, ntheta, nphi * ntheta, starts);
    *out = (gb_equilibria){0};
    int status = GB_OK;
    for (size_t k = 0; k < n && status == GB_OK; k++) {
        double phi = cap + (starts[k] / ntheta + 0.5) * dphi, theta = (starts[k] % ntheta + 0.5) * dtheta;
        gb_surface_point p;
        if (!newton_critical_point(surface, &phi, &theta, &p)) continue;
        int duplicate = 0;
        for (size_t e = 0; e < out->count && !duplicate; e++) {
            double ue[3];
            gb_surface_direction(out->points[e].phi, out->points[e].theta, ue);
            duplicate = gb_vec_dot(ue, p.u) > cos(1e-7);
        }
        if (duplicate) continue;
        if (out->count == GB_SHAPE_MAX_EQUILIBRIA) {
            status = gb_error_set(GB_EDOM, "more than %d critical points of r", GB_SHAPE_MAX_EQUILIBRIA);
            break;
        }
        const double det = p.r_phiphi * p.r_thetatheta - p.r_phitheta * p.r_phitheta;
        const int type = det < 0.0 ? GB_EQ_SADDLE : p.r_phiphi > 0.0 ? GB_EQ_STABLE : GB_EQ_UNSTABLE;
        out->points[out->count++] = (gb_equilibrium){type, phi, theta, p.r, sphere_gradient(&p)};
        if (type == GB_EQ_STABLE) out->stable++;
        else if (type == GB_EQ_SADDLE) out->saddle++;
        else out->unstable++;
    }
    /* polar caps: the smallest sphere gradient on a fine grid there */
    out->polar_gradient_min = INFINITY;
    for (int cap_side = 0; cap_side < 2; cap_side++)
        for (size_t i = 0; i < 64; i++)
            for (size_t j = 0; j < 256; j++) {
                const double a = (i + 0.5) * cap / 64;
                gb_surface_point p;
                eval_about_centroid(surface, cap_side ? M_PI - a : a, (j + 0.5) * 2.0 * M_PI / 256, &p);
                out->polar_gradient_min = fmin(out->polar_gradient_min, sphere_gradient(&p));
            }
    free(g2), free(starts);
    return status;
}

/* ---- the convex hull and its equilibria ----------------------------------------------------- */

typedef struct hull_facet {
    double normal[3], height; /* outward unit normal and distance of the plane from the centroid */
    size_t ids[3];
    int resting;              /* the centroid's foot lies in the triangle */
    double interiority;       /* smallest barycentric coordinate of the foot */
} hull_facet;

/* Fill `facets` (triangles of the Qt-triangulated hull) and mark hull vertices. */
static int hull_triangles(const coordT *points, size_t npoints, hull_facet **facets_out,
                          size_t *nfacets_out, char *is_vertex)
{
    FILE *qhull_errors = tmpfile();
    qhT qh_storage, *qh = &qh_storage;
    qh_zero(qh, qhull_errors);
    char command[] = "qhull Qt";
    int exitcode = qh_new_qhull(qh, 3, (int)npoints, (coordT *)points, False, command, NULL,
                                qhull_errors);
    int status = GB_OK;
    if (exitcode) {
        char text[256] = "";
        if (qhull_errors) {
            rewind(qhull_errors);
            text[fread(text, 1, sizeof text - 1, qhull_errors)] = '\0';
        }
        status = gb_error_set(GB_ENUMERIC, "Qhull failed with code %d: %s", exitcode, text);
    } else {
        hull_facet *facets = malloc((size_t)qh->num_facets * sizeof *facets);
        size_t n = 0;
        if (!facets) status = gb_error_set(GB_ENOMEM, "hull: out of memory");
        facetT *facet;
        vertexT *vertex, **vertexp;
        FORALLfacets {
            if (!facets) break;
            hull_facet *f = &facets[n];
            size_t nv = 0;
            FOREACHvertex_(facet->vertices) {
                if (nv < 3) f->ids[nv] = (size_t)qh_pointid(qh, vertex->point);
                nv++;
            }
            if (nv != 3) continue; /* Qt triangulates, so every facet has three vertices */
            for (int k = 0; k < 3; k++) f->normal[k] = facet->normal[k];
            f->height = -facet->offset;
            for (int a = 0; a < 3; a++) is_vertex[f->ids[a]] = 1;
            n++;
        }
        *facets_out = facets;
        *nfacets_out = n;
    }
    qh_freeqhull(qh, !qh_ALL);
    int curlong, totlong;
    qh_memfreeshort(qh, &curlong, &totlong);
    if (qhull_errors) fclose(qhull_errors);
    return status;
}

/* Barycentric test of the centroid's foot (−offset · normal) against one triangle. */
static void mark_resting(const coordT *points, hull_facet *f)
{
    double foot[3], e1[3], e2[3], twice_area[3];
    const double *v[3] = {&points[3 * f->ids[0]], &points[3 * f->ids[1]], &points[3 * f->ids[2]]};
    for (int k = 0; k < 3; k++) {
        foot[k] = f->height * f->normal[k];
        e1[k] = v[1][k] - v[0][k];
        e2[k] = v[2][k] - v[0][k];
    }
    gb_vec_cross(e1, e2, twice_area);
    const double total = gb_vec_dot(twice_area, f->normal);
    f->interiority = INFINITY;
    for (int a = 0; a < 3; a++) {
        double pa[3], pb[3], c[3];
        for (int k = 0; k < 3; k++) {
            pa[k] = v[(a + 1) % 3][k] - foot[k];
            pb[k] = v[(a + 2) % 3][k] - foot[k];
        }
        gb_vec_cross(pa, pb, c);
        f->interiority = fmin(f->interiority, gb_vec_dot(c, f->normal) / total);
    }
    f->resting = f->interiority >= -1e-12; /* on an edge counts: merging removes the double */
}

int gb_shape_hull_equilibria(const gb_surface *surface, const gb_shape_def *def,
                             gb_hull_equilibria *out)
{
    const size_t nphi = def->hull_phi, ntheta = def->hull_theta;
    if (nphi < 3 || ntheta < 3 || !(def->hull_neighbourhood > 0.0 && def->hull_neighbourhood < 1.0))
        return gb_error_set(GB_EDOM, "hull sample %zux%zu must be at least 3x3 and the "
                            "neighbourhood in (0, 1) rad (got %g)", nphi, ntheta,
                            def->hull_neighbourhood);
    const size_t npoints = nphi * ntheta + 2;
    coordT *points = malloc(3 * npoints * sizeof *points);
    char *is_vertex = calloc(npoints, 1), *dominated = calloc(npoints, 1);
    double *radius = malloc(npoints * sizeof *radius);
    size_t *lowest = NULL, nfacets = 0;
    hull_facet *facets = NULL;
    int status = GB_OK;
    *out = (gb_hull_equilibria){0};
    if (!points || !is_vertex || !dominated || !radius) {
        status = gb_error_set(GB_ENOMEM, "hull: out of memory for %zu points", npoints);
        goto done;
    }
    for (size_t i = 0; i < nphi; i++)
        for (size_t j = 0; j < ntheta; j++)
            gb_surface_position(surface, (i + 0.5) * M_PI / nphi, (j + 0.5) * 2.0 * M_PI / ntheta,
                                &points[3 * (i * ntheta + j)]);
    gb_surface_position(surface, 0.0, 0.0, &points[3 * (npoints - 2)]);
    gb_surface_position(surface, M_PI, 0.0, &points[3 * (npoints - 1)]);
    for (size_t i = 0; i < npoints; i++) radius[i] = sqrt(gb_vec_dot(&points[3 * i], &points[3 * i]));

    if ((status = hull_triangles(points, npoints, &facets, &nfacets, is_vertex))) goto done;
    out->facets = nfacets;
    /* Raw stable equilibria: resting triangles that are the lowest (by height, then index) of all
     * triangles at each of their three vertices — discrete local minima of the support function. */
    lowest = malloc(npoints * sizeof *lowest);
    if (!lowest) {
        status = gb_error_set(GB_ENOMEM, "hull: out of memory for %zu points", npoints);
        goto done;
    }
    for (size_t i = 0; i < npoints; i++) lowest[i] = SIZE_MAX;
    for (size_t a = 0; a < nfacets; a++) {
        mark_resting(points, &facets[a]);
        for (int i = 0; i < 3; i++) {
            const size_t v = facets[a].ids[i];
            if (lowest[v] == SIZE_MAX || facets[a].height < facets[lowest[v]].height) lowest[v] = a;
            for (int j = 0; j < 3; j++)
                if (i != j && radius[facets[a].ids[j]] >= radius[v]) dominated[v] = 1;
        }
    }
    const double cos_radius = cos(def->hull_neighbourhood);
    for (size_t a = 0; a < nfacets && status == GB_OK; a++) {
        const hull_facet *f = &facets[a];
        if (!f->resting || lowest[f->ids[0]] != a || lowest[f->ids[1]] != a || lowest[f->ids[2]] != a)
            continue;
        out->raw_stable++;
        /* robust: the lowest of all facets whose normals lie within the neighbourhood (equal
         * heights within round-off go to the lower index, so a tie is one equilibrium) */
        int robust = 1;
        const double tie = 1e-12 * f->height;
        for (size_t b = 0; b < nfacets && robust; b++) {
            if (b == a || gb_vec_dot(facets[b].normal, f->normal) <= cos_radius) continue;
            if (facets[b].height < f->height - tie || (facets[b].height <= f->height + tie && b < a)) robust = 0;
        }
        if (!robust) continue;
        if (out->stable == GB_SHAPE_MAX_EQUILIBRIA) {
            status = gb_error_set(GB_EDOM, "hull: more than %d robust resting faces", GB_SHAPE_MAX_EQUILIBRIA);
            break;
        }
        gb_hull_rest *rest = &out->rests[out->stable++];
        for (int k = 0; k < 3; k++) rest->normal[k] = f->normal[k];
        rest->height = f->height;
    }
    for (size_t i = 0; i < npoints && status == GB_OK; i++) {
        if (!is_vertex[i]) continue;
        out->vertices++;
        if (dominated[i]) continue;
        out->raw_unstable++;
        int robust = 1;
        const double tie = 1e-12 * radius[i];
        for (size_t j = 0; j < npoints && robust; j++) {
            if (!is_vertex[j] || j == i ||
                gb_vec_dot(&points[3 * i], &points[3 * j]) <= cos_radius * radius[i] * radius[j])
                continue;
            if (radius[j] > radius[i] + tie || (radius[j] >= radius[i] - tie && j < i)) robust = 0;
        }
        if (!robust) continue;
        if (out->unstable == GB_SHAPE_MAX_EQUILIBRIA) {
            status = gb_error_set(GB_EDOM, "hull: more than %d robust unstable vertices", GB_SHAPE_MAX_EQUILIBRIA);
            break;
        }
        memcpy(out->unstable_points[out->unstable++], &points[3 * i], 3 * sizeof(double));
    }
    out->sampled_fraction_on_hull = (double)out->vertices / npoints;
done:
    free(points), free(is_vertex), free(dominated), free(radius), free(lowest), free(facets);
    return status;
}
