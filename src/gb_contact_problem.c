#include "gb_contact_problem.h"

#include "gb_error.h"

#include <dlfcn.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include <FrictionContactProblem.h>
#include <Friction_cst.h>
#include <NonSmoothDrivers.h>
#include <NumericsMatrix.h>
#include <SolverOptions.h>
#include <fc3d_compute_error.h>

/* The solvers, in the order they are tried: each starts from the best answer so far and the best is kept (the order
 * and the Gauss–Seidel's budget: gb_contact_problem_create). */
static const struct {
    int id;
    const char *name;
} chain[] = {{SICONOS_FRICTION_3D_NSGS, "NSGS"},
             {SICONOS_FRICTION_3D_PROX, "the proximal point method"},
             {SICONOS_FRICTION_3D_ADMM, "ADMM"}};
enum { CHAIN = sizeof chain / sizeof chain[0] };

struct gb_contact_problem {
    gb_contact_problem_def def;
    SolverOptions *options[CHAIN];
    double *best_r, *best_u; /* the best answer so far (3 GB_CONTACT_PROBLEM_MAX each) */
    gb_contact_problem_exact exact;
    void *exact_context;
};

void gb_contact_problem_set_exact(gb_contact_problem *p, gb_contact_problem_exact exact, void *context)
{
    p->exact = exact, p->exact_context = context;
}

/* Siconos's numerics, opened when the first problem is made (dlopen), not when the process starts: the library
 * and what it needs (LAPACK, MUMPS, SCOTCH, gfortran, ...) cost every process about 10 ms of loading, and only a
 * time-stepped run uses them. GB_SICONOS_NUMERICS is the library's soname, found when gomboc is built. */
#ifndef GB_SICONOS_NUMERICS
#define GB_SICONOS_NUMERICS "libsiconos_numerics.so"
#endif
static struct {
    __typeof__(solver_options_create) *options_create;
    __typeof__(solver_options_delete) *options_delete;
    __typeof__(NM_create_from_data) *matrix_create;
    __typeof__(NM_free) *matrix_free;
    __typeof__(fc3d_driver) *driver;
    __typeof__(fc3d_compute_error) *compute_error;
    char error[256];
} siconos;
static pthread_once_t siconos_once = PTHREAD_ONCE_INIT;

static void siconos_open(void)
{
    void *lib = dlopen(GB_SICONOS_NUMERICS, RTLD_NOW | RTLD_LOCAL);
    const char *missing = NULL;
    if (lib) {
        /* through a union: ISO C has no cast from an object pointer (dlsym's) to a function pointer */
        union { void *object; void (*function)(void); } f;
#define SICONOS_SYMBOL(field, name) \
    if (!missing && !(f.object = dlsym(lib, #name))) missing = #name; \
    else if (!missing) memcpy(&siconos.field, &f.function, sizeof siconos.field);
        SICONOS_SYMBOL(options_create, solver_options_create)
        SICONOS_SYMBOL(options_delete, solver_options_delete)
        SICONOS_SYMBOL(matrix_create, NM_create_from_data)
        SICONOS_SYMBOL(matrix_free, NM_free)
        SICONOS_SYMBOL(driver, fc3d_driver)
        SICONOS_SYMBOL(compute_error, fc3d_compute_error)
#undef SICONOS_SYMBOL
    }
    if (!lib || missing)
        snprintf(siconos.error, sizeof siconos.error, "%s", lib ? missing : dlerror());
    if (missing) siconos.driver = NULL;
    /* Its BLAS on one thread, where the BLAS under it is OpenBLAS: a problem has at most a few hundred unknowns, and
     * OpenBLAS's threads would split its sums by the machine's cores, so that a run's last bits (and, through the
     * chaos, its trajectory) would depend on the machine (measured: the shipped time-stepped scene's fingerprint
     * moved with OPENBLAS_NUM_THREADS). */
    union { void *object; void (*function)(int); } one_thread = {.object = lib ? dlsym(lib, "openblas_set_num_threads") : NULL};
    if (one_thread.object) one_thread.function(1);
}

/* GB_OK once Siconos's numerics are open; else GB_EIO naming the library and why. */
static int siconos_ready(void)
{
    pthread_once(&siconos_once, siconos_open);
    if (siconos.driver) return GB_OK;
    return gb_error_set(GB_EIO, "time-stepping needs Siconos's numerics library (%s, Debian package "
                        "libsiconos-numerics7): it cannot be opened (%s)", GB_SICONOS_NUMERICS, siconos.error);
}

int gb_contact_problem_create(const gb_contact_problem_def *def, gb_contact_problem **out)
{
    *out = NULL;
    if (!(def->tolerance > 0.0 && def->tolerance < 1.0))
        return gb_error_set(GB_EDOM, "solver_tolerance = %g is out of range (allowed: 0 < tolerance < 1)", def->tolerance);
    if (def->iterations < 1 || def->iterations > 100000000)
        return gb_error_set(GB_EDOM, "solver_iterations = %zu is out of range (allowed: 1 to 1e8)", def->iterations);
    const int opened = siconos_ready();
    if (opened) return opened;
    gb_contact_problem *p = calloc(1, sizeof *p);
    if (!p) return gb_error_set(GB_ENOMEM, "out of memory for a contact problem");
    p->def = *def;
    p->best_r = malloc(3 * GB_CONTACT_PROBLEM_MAX * sizeof *p->best_r);
    p->best_u = malloc(3 * GB_CONTACT_PROBLEM_MAX * sizeof *p->best_u);
    /* The non-smooth Gauss–Seidel over the contacts, each solved by its own Newton method (Siconos's default local
     * solver); where it stalls (contacts coupled strongly: two points on an edge, three in a plane), the alternating
     * direction method of multipliers, then the proximal point method. Not Alart and Curnier's global Newton method:
     * on the singular Delassus operator of a face (four coplanar points) its LU factorisation fails and prints so on
     * standard output, which a library of ours never writes to. */
    for (int k = 0; k < CHAIN; k++) {
        p->options[k] = siconos.options_create(chain[k].id);
        if (!p->options[k]) break;
        p->options[k]->dparam[SICONOS_DPARAM_TOL] = def->tolerance;
        p->options[k]->iparam[SICONOS_IPARAM_MAX_ITER] = (int)def->iterations;
    }
    /* The Gauss–Seidel converges linearly, at a rate the Delassus operator's conditioning sets: on a landing of a
     * grid polyhedron's polar cap (a hundred and more nearly coplanar points, an operator of rank 6) it crawls
     * (residual 3e-5 after 1000 sweeps at 190 points), where the proximal point method from its answer meets the
     * tolerance in 1 to 4 iterations (ADMM, tried second, had not in 20 000). The Gauss–Seidel has
     * GB_CONTACT_PROBLEM_NSGS_SWEEPS sweeps at most, the proximal point method GB_CONTACT_PROBLEM_PROX_ITERATIONS
     * (where it meets the tolerance it does so within a few hundred: at most 308 in the shipped scenes; on the impact
     * without collision of Painlevé's launch of a smooth body it stalls at 4e-4 after 20 000, 5.8 s, where ADMM then
     * meets it at once), ADMM the whole budget. */
    if (p->options[0] && def->iterations > GB_CONTACT_PROBLEM_NSGS_SWEEPS)
        p->options[0]->iparam[SICONOS_IPARAM_MAX_ITER] = GB_CONTACT_PROBLEM_NSGS_SWEEPS;
    if (p->options[1] && def->iterations > GB_CONTACT_PROBLEM_PROX_ITERATIONS)
        p->options[1]->iparam[SICONOS_IPARAM_MAX_ITER] = GB_CONTACT_PROBLEM_PROX_ITERATIONS;
    /* The Gauss–Seidel's error in full at every sweep: its default, an incremental error checked in full at the end,
     * rescales its tolerance by their ratio, 0 where a sweep meets the problem exactly, and then warns on standard
     * output (a library of ours never prints). */
    p->options[0]->iparam[SICONOS_FRICTION_3D_IPARAM_ERROR_EVALUATION] = SICONOS_FRICTION_3D_NSGS_ERROR_EVALUATION_FULL;
    if (!p->options[CHAIN - 1] || !p->best_r || !p->best_u) {
        gb_contact_problem_free(p);
        return gb_error_set(GB_ENOMEM, "out of memory for Siconos's solver options");
    }
    *out = p;
    return GB_OK;
}

void gb_contact_problem_free(gb_contact_problem *p)
{
    if (!p) return;
    for (int k = 0; k < CHAIN; k++)
        if (p->options[k]) siconos.options_delete(p->options[k]);
    free(p->best_r), free(p->best_u);
    free(p);
}

int gb_contact_problem_solve(gb_contact_problem *p, int count, double *W, double *q, double *mu, double *r, double *u,
                             gb_contact_problem_report *report)
{
    *report = (gb_contact_problem_report){0, INFINITY, 1, 0, 0};
    if (count < 1) return GB_OK;
    if (count > GB_CONTACT_PROBLEM_MAX)
        return gb_error_set(GB_EDOM, "%d contacts in one step (allowed: at most %d)", count, GB_CONTACT_PROBLEM_MAX);
    /* Siconos's dense matrix over our buffer: detached before it is freed, so that the buffer stays ours. */
    NumericsMatrix *M = siconos.matrix_create(NM_DENSE, 3 * count, 3 * count, W);
    if (!M) return gb_error_set(GB_ENOMEM, "out of memory for Siconos's matrix");
    FrictionContactProblem problem = {.dimension = 3, .numberOfContacts = count, .M = M, .q = q, .mu = mu};
    const size_t n = (size_t)(3 * count);
    int used = 0;
    for (int k = 0; k < CHAIN && !(report->residual <= p->def.tolerance); k++) {
        if (k) memcpy(r, p->best_r, n * sizeof *r); /* from the best so far */
        const int info = siconos.driver(&problem, r, u, p->options[k]);
        report->iterations += (size_t)p->options[k]->iparam[SICONOS_IPARAM_ITER_DONE];
        const double residual = p->options[k]->dparam[SICONOS_DPARAM_RESIDU];
        int finite = 1;
        for (size_t i = 0; i < n; i++) finite = finite && isfinite(r[i]) && isfinite(u[i]);
        if (finite && (info == 0 || residual < report->residual) && !(residual > report->residual)) {
            report->residual = info == 0 ? fmin(residual, report->residual) : residual;
            memcpy(p->best_r, r, n * sizeof *r), memcpy(p->best_u, u, n * sizeof *u);
            used = k;
        }
    }
    if (!(report->residual <= p->def.tolerance) && p->exact && count <= GB_CONTACT_PROBLEM_EXACT_MAX &&
        !p->exact(p->exact_context, count, r)) {
        /* the caller's exact answer where every method stalled, measured as Siconos measures its own (the natural
         * map's residual over the largest of |q|, |r|, |u|, as its solvers call it) */
        double norm_q = 0.0, error = INFINITY;
        for (size_t i = 0; i < n; i++) norm_q += q[i] * q[i];
        siconos.compute_error(&problem, r, u, p->def.tolerance, p->options[0], sqrt(norm_q), &error);
        if (error <= p->def.tolerance) {
            report->residual = error, report->exact = 1;
            memcpy(p->best_r, r, n * sizeof *r), memcpy(p->best_u, u, n * sizeof *u);
            used = 0;
        }
    }
    memcpy(r, p->best_r, n * sizeof *r), memcpy(u, p->best_u, n * sizeof *u);
    M->matrix0 = NULL;
    siconos.matrix_free(M); /* frees the matrix's struct too */
    report->fallback = used > 0;
    report->converged = report->residual <= p->def.tolerance;
    if (!report->converged)
        return gb_error_set(GB_ENOCONV, "Siconos's fc3d did not converge on %d contacts (NSGS, the proximal point method, "
                            "ADMM): residual %.3g after %zu iterations in all (allowed: <= solver_tolerance "
                            "= %.3g within solver_iterations = %zu each)", count, report->residual, report->iterations,
                            p->def.tolerance, p->def.iterations);
    return GB_OK;
}

/* a × b */
static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1], out[1] = a[2] * b[0] - a[0] * b[2], out[2] = a[0] * b[1] - a[1] * b[0];
}

int gb_contact_problem_impact(gb_contact_problem *p, const gb_impact_body *b, const double (*points)[3], int count, double mu,
                              const double v[3], const double w[3], const double *target, gb_impact_result *r,
                              gb_contact_problem_report *report)
{
    static const int axis[3] = {2, 0, 1}; /* the local frame: the normal e_z, then e_x, e_y */
    enum { MAX = GB_IMPACT_CONTACTS_MAX };
    if (count < 1 || count > MAX) return gb_error_set(GB_EDOM, "%d points (allowed: 1 to %d)", count, MAX);
    /* I⁻¹ by cofactors (I symmetric positive definite) */
    const double (*I)[3] = b->inertia;
    double Iinv[3][3];
    const double det = I[0][0] * (I[1][1] * I[2][2] - I[1][2] * I[2][1]) - I[0][1] * (I[1][0] * I[2][2] - I[1][2] * I[2][0]) +
                       I[0][2] * (I[1][0] * I[2][1] - I[1][1] * I[2][0]);
    if (!(b->mass > 0.0) || !(det > 0.0)) return gb_error_set(GB_EDOM, "a body of mass %g and inertia determinant %g (allowed: > 0)", b->mass, det);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            const int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
            Iinv[i][j] = (I[i1][j1] * I[i2][j2] - I[i1][j2] * I[i2][j1]) / det;
        }
    double B[MAX][3][3], W[9 * MAX * MAX], q[3 * MAX], mus[MAX], P[3 * MAX], u[3 * MAX];
    for (int k = 0; k < count; k++) {
        const double *x = points[k];
        const double skew[3][3] = {{0.0, x[2], -x[1]}, {-x[2], 0.0, x[0]}, {x[1], -x[0], 0.0}}; /* −[p]× */
        memcpy(B[k], skew, sizeof skew);
        double c[3];
        cross3(w, x, c);
        for (int a = 0; a < 3; a++) q[3 * k + a] = v[axis[a]] + c[axis[a]], P[3 * k + a] = 0.0;
        if (target) q[3 * k] -= target[k];
        mus[k] = mu;
    }
    const int n = 3 * count;
    for (int i = 0; i < count; i++)
        for (int j = 0; j < count; j++)
            for (int a = 0; a < 3; a++)
                for (int c = 0; c < 3; c++) {
                    double x = a == c ? 1.0 / b->mass : 0.0; /* the centroid's velocity is every point's */
                    for (int k = 0; k < 3; k++)
                        for (int l = 0; l < 3; l++) x += B[i][axis[a]][k] * Iinv[k][l] * B[j][axis[c]][l];
                    W[(3 * j + c) * n + 3 * i + a] = x;
                }
    const int status = gb_contact_problem_solve(p, count, W, q, mus, P, u, report);
    memset(r, 0, sizeof *r);
    double total[3] = {0, 0, 0}, moment[3] = {0, 0, 0};
    for (int k = 0; k < count; k++) {
        r->impulse[k][0] = P[3 * k + 1], r->impulse[k][1] = P[3 * k + 2], r->impulse[k][2] = P[3 * k];
        double m[3];
        cross3(points[k], r->impulse[k], m);
        for (int i = 0; i < 3; i++) total[i] += r->impulse[k][i], moment[i] += m[i];
    }
    for (int i = 0; i < 3; i++) {
        r->v[i] = v[i] + total[i] / b->mass;
        r->omega[i] = w[i] + Iinv[i][0] * moment[0] + Iinv[i][1] * moment[1] + Iinv[i][2] * moment[2];
    }
    const double speed = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (int k = 0; k < count; k++) {
        double c[3];
        cross3(r->omega, points[k], c);
        r->holds[k] = r->impulse[k][2] > 1e-10 * b->mass * (speed + (target ? fabs(target[k]) : 0.0));
        r->slides[k] = r->holds[k] && hypot(r->v[0] + c[0], r->v[1] + c[1]) > 1e-8 * speed;
        if (!r->holds[k]) memset(r->impulse[k], 0, sizeof r->impulse[k]);
    }
    return status;
}
