/* gb_body — bodies of one's own as morphology rows made at run time (see gb_body.h). */
#include "gb_body.h"

#include "gb_error.h"
#include "gb_expression.h"
#include "gb_file.h"
#include "gb_massprops.h"
#include "gb_mesh.h"
#include "gb_polyhedron.h"
#include "gb_surface_internal.h"

#include <math.h>
#include <matheval.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* An expression and its symbolic derivatives: value, ∂φ, ∂θ, ∂φφ, ∂φθ, ∂θθ. */
enum { DERIVATIVES = 6 };
#define ENCLOSED_FUNCTIONS "exp, log, sqrt, sin, cos, sinh, cosh, tanh, atan, asinh, erf"

typedef struct own_body {
    gb_morphology row;
    char *name;         /* the row's name: "mesh FILE", "r = EXPR", "chi = EXPR" */
    unsigned char *key; /* what makes it this body: the mesh file's bytes, or the kind and the expression */
    size_t key_size;
    gb_polyhedron polyhedron; /* a mesh */
    void *eval[DERIVATIVES];  /* an expression */
    gb_expression *tree;      /* the same expression as a tree to bound on intervals (gb_expression.h) */
    double beta;              /* an expression: the β it was made for (a phase reads its β here) */
    struct own_body *next;
} own_body;

static own_body *bodies;
/* libmatheval's parser and evaluators keep state of their own: one lock for every call into it and for the
 * list of rows. */
static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;

static void body_free(own_body *b)
{
    for (int k = 0; k < DERIVATIVES; k++)
        if (b->eval[k]) evaluator_destroy(b->eval[k]);
    gb_expression_free(b->tree);
    gb_polyhedron_free(&b->polyhedron);
    free(b->name);
    free(b->key);
    free(b);
}

void gb_body_release(void)
{
    pthread_mutex_lock(&lock);
    while (bodies) {
        own_body *next = bodies->next;
        body_free(bodies);
        bodies = next;
    }
    pthread_mutex_unlock(&lock);
}

static const own_body *own_of(const gb_surface *surface)
{
    for (const own_body *b = bodies; b; b = b->next)
        if (&b->row == surface->morphology) return b;
    return NULL;
}

int gb_body_is_own(const gb_surface *surface)
{
    pthread_mutex_lock(&lock);
    const int own = own_of(surface) != NULL;
    pthread_mutex_unlock(&lock);
    return own;
}

int gb_body_names_beta(const gb_surface *surface)
{
    pthread_mutex_lock(&lock);
    const own_body *b = own_of(surface);
    int names = 0;
    if (b && b->eval[0]) {
        char **names_list;
        int count;
        evaluator_get_variables(b->eval[0], &names_list, &count);
        for (int k = 0; k < count; k++) names |= !strcmp(names_list[k], "beta");
    }
    pthread_mutex_unlock(&lock);
    return names;
}

const gb_polyhedron *gb_body_polyhedron(const gb_surface *surface) { return surface->morphology->polyhedron; }

/* The row already made for this key (under the lock), or NULL. */
static own_body *find_key(const unsigned char *key, size_t size)
{
    for (own_body *b = bodies; b; b = b->next)
        if (b->key_size == size && !memcmp(b->key, key, size)) return b;
    return NULL;
}

/* ---- a polyhedron ------------------------------------------------------------------------------- */

/* A polyhedron's mass properties in closed form (gb_polyhedron_massprops); L the radius of the sphere of its
 * volume. */
static int polyhedron_massprops(const gb_morphology *self, double mass, gb_massprops *out)
{
    const int status = gb_polyhedron_massprops(self->polyhedron, mass, out);
    if (!status) out->L = cbrt(3.0 * out->volume / (4.0 * M_PI)), out->L_err = out->L * out->volume_err / out->volume;
    return status;
}

int gb_body_mesh(const char *path, gb_surface *out)
{
    char *data;
    size_t size;
    int status = gb_file_read(path, GB_MESH_FILE_MAX, "mesh file", "an OFF, OBJ or STL file", &data, &size);
    if (status) return status;
    pthread_mutex_lock(&lock);
    own_body *b = find_key((const unsigned char *)data, size);
    if (b) {
        free(data);
        pthread_mutex_unlock(&lock);
        *out = (gb_surface){&b->row, 0.0};
        return GB_OK;
    }
    b = calloc(1, sizeof *b);
    gb_mesh mesh;
    status = b ? gb_mesh_read_buffer(path, (const unsigned char *)data, size, &mesh) : gb_error_set(GB_ENOMEM, "out of memory for a body");
    if (!status) {
        status = gb_polyhedron_from_mesh(&mesh, path, &b->polyhedron);
        gb_mesh_free(&mesh);
    }
    gb_massprops props;
    if (!status) status = gb_polyhedron_massprops(&b->polyhedron, 1.0, &props);
    if (!status) { /* about the centroid: the dynamics take body points relative to it */
        for (size_t k = 0; k < b->polyhedron.vertex_count; k++)
            for (int i = 0; i < 3; i++) b->polyhedron.vertices[3 * k + i] -= props.centroid[i];
        const size_t n = strlen(path) + 6;
        b->name = malloc(n);
        if (!b->name) status = gb_error_set(GB_ENOMEM, "out of memory for a body");
        else snprintf(b->name, n, "mesh %s", path);
    }
    if (status) {
        free(data);
        if (b) body_free(b);
        pthread_mutex_unlock(&lock);
        return status;
    }
    b->key = (unsigned char *)data, b->key_size = size;
    b->row = (gb_morphology){.name = b->name, .chi_formula = "(a convex polyhedron)", .equations = "",
                             .polyhedron = &b->polyhedron, .massprops = polyhedron_massprops};
    b->next = bodies, bodies = b;
    pthread_mutex_unlock(&lock);
    *out = (gb_surface){&b->row, 0.0};
    return GB_OK;
}

/* ---- an expression ------------------------------------------------------------------------------ */

static double evaluate(const own_body *b, int k, double beta, double phi, double theta)
{
    static char *names[] = {"phi", "theta", "beta"};
    double values[3] = {phi, theta, beta};
    return evaluator_evaluate(b->eval[k], 3, names, values);
}

/* All six at once (under the lock). */
static void evaluate_all(const own_body *b, double beta, double phi, double theta, double v[DERIVATIVES])
{
    pthread_mutex_lock(&lock);
    for (int k = 0; k < DERIVATIVES; k++) v[k] = evaluate(b, k, beta, phi, theta);
    pthread_mutex_unlock(&lock);
}

static void phase_expression(const gb_morphology *self, double phi, double theta, gb_phase_value *out)
{
    double v[DERIVATIVES];
    /* the phase's signature has no β: an expression naming it is read at the β its row was made for */
    const own_body *b = self->user;
    evaluate_all(b, b->beta, phi, theta, v);
    *out = (gb_phase_value){v[0], v[1], v[2], v[3], v[4], v[5]};
}

static void phase_expression_eval(const gb_morphology *self, double phi, double theta, double sp, double cp, double st,
                                  double ct, gb_phase_value *out, double *sin_chi, double *cos_chi)
{
    (void)sp, (void)cp, (void)st, (void)ct;
    phase_expression(self, phi, theta, out);
    sincos(out->chi, sin_chi, cos_chi);
}

/* S = r⁴: S_a = 4r³ r_a, S_ab = 4r³ r_ab + 12 r² r_a r_b. */
static void kernel_expression(const gb_morphology *self, double beta, double phi, double theta, double S[6])
{
    double v[DERIVATIVES];
    evaluate_all(self->user, beta, phi, theta, v);
    const double r = v[0], r2 = r * r, r3 = r2 * r;
    S[0] = copysign(r2 * r2, r); /* r < 0 is no body: S < 0 keeps the sign, so check_surface refuses it */
    S[1] = 4.0 * r3 * v[1], S[2] = 4.0 * r3 * v[2];
    S[3] = 4.0 * r3 * v[3] + 12.0 * r2 * v[1] * v[1];
    S[4] = 4.0 * r3 * v[4] + 12.0 * r2 * v[1] * v[2];
    S[5] = 4.0 * r3 * v[5] + 12.0 * r2 * v[2] * v[2];
}

/* Parse `text` and differentiate it (under the lock). GB_EINVAL naming what is wrong. */
static int parse(own_body *b, const char *what, const char *text)
{
    char *copy = strdup(text);
    if (!copy) return gb_error_set(GB_ENOMEM, "out of memory for an expression");
    b->eval[0] = evaluator_create(copy);
    free(copy);
    if (!b->eval[0])
        return gb_error_set(GB_EINVAL, "%s = %s does not parse (allowed: an expression in phi, theta, beta with + - * / ^, "
                                       "pi, e and the functions " ENCLOSED_FUNCTIONS ")", what, text);
    char **names;
    int count;
    evaluator_get_variables(b->eval[0], &names, &count);
    for (int k = 0; k < count; k++)
        if (strcmp(names[k], "phi") && strcmp(names[k], "theta") && strcmp(names[k], "beta"))
            return gb_error_set(GB_EINVAL, "%s = %s names '%s', which is unknown (allowed: phi, theta, beta, pi, e)", what, text,
                                names[k]);
    char *phi = "phi", *theta = "theta";
    b->eval[1] = evaluator_derivative(b->eval[0], phi);
    b->eval[2] = evaluator_derivative(b->eval[0], theta);
    if (b->eval[1]) b->eval[3] = evaluator_derivative(b->eval[1], phi);
    if (b->eval[1]) b->eval[4] = evaluator_derivative(b->eval[1], theta);
    if (b->eval[2]) b->eval[5] = evaluator_derivative(b->eval[2], theta);
    for (int k = 1; k < DERIVATIVES; k++)
        if (!b->eval[k]) return gb_error_set(GB_EINVAL, "%s = %s has no symbolic derivative in libmatheval", what, text);
    /* the tree that bounds it between grid points: smooth functions with enclosures only */
    gb_expression_fault fault;
    char detail[128];
    b->tree = gb_expression_parse(text, &fault, detail, sizeof detail);
    if (fault == GB_EXPRESSION_NOT_SMOOTH)
        return gb_error_set(GB_EINVAL, "%s = %s names %s, which is not smooth: a body's normal and curvature need derivatives "
                                       "(allowed: smooth functions: %s)", what, text, detail, ENCLOSED_FUNCTIONS);
    if (fault == GB_EXPRESSION_NO_ENCLOSURE)
        return gb_error_set(GB_EINVAL, "%s = %s names %s, which has no interval enclosure here, so the body cannot be bounded "
                                       "between the checked directions (allowed: %s)", what, text, detail, ENCLOSED_FUNCTIONS);
    if (fault)
        return gb_error_set(GB_EINVAL, "%s = %s cannot be read for its bounds: %s (allowed: numbers, phi, theta, beta, pi, e, "
                                       "+ - * / ^, parentheses and the functions %s)", what, text, detail, ENCLOSED_FUNCTIONS);
    return GB_OK;
}

/* r > 0 everywhere, not only at the checked directions: r's enclosure (for chi, S = 1 + 4β sinφ cos χ's) over
 * each cell of a 64 × 128 cover of [0, π] × [0, 2π] is positive, or the cell is halved until it is. A cell
 * narrower than 1e-7 rad whose enclosure still reaches 0 is decided at its centre: r <= 0 there refuses the body
 * (a spike between the grid's directions); r > 0 there refuses it as a body that cannot be bounded. At most
 * BOUND_CELLS cells are enclosed. */
enum { BOUND_CELLS = 4000000 };

static gb_interval kernel_enclosure(const gb_surface *s, gb_interval phi, gb_interval theta)
{
    const own_body *b = s->morphology->user;
    const gb_interval v = gb_expression_enclose(b->tree, phi, theta, s->beta);
    if (s->morphology->kernel) return v; /* r itself: r > 0 */
    const gb_interval term = gb_interval_mul(gb_interval_sin(phi), gb_interval_cos(v));
    return gb_interval_add(gb_interval_point(1.0), gb_interval_scale(4.0 * s->beta, term)); /* S > 0 */
}

static int bound_between(const gb_surface *s, const char *what, const char *text)
{
    typedef struct cell {
        double phi_lo, phi_hi, theta_lo, theta_hi;
    } cell;
    size_t cap = 1024, top = 0, enclosed = 0;
    cell *stack = malloc(cap * sizeof *stack);
    if (!stack) return gb_error_set(GB_ENOMEM, "out of memory to bound %s = %s", what, text);
    enum { NP = 64, NT = 128 };
    int status = GB_OK;
    for (int i = 0; i < NP && !status; i++)
        for (int j = 0; j < NT && !status; j++) {
            stack[top++] = (cell){M_PI * i / NP, M_PI * (i + 1) / NP, 2.0 * M_PI * j / NT, 2.0 * M_PI * (j + 1) / NT};
            while (top && !status) {
                const cell c = stack[--top];
                const gb_interval k = kernel_enclosure(s, gb_interval_make(c.phi_lo, c.phi_hi), gb_interval_make(c.theta_lo, c.theta_hi));
                if (k.lo > 0.0) continue;
                const double phi = 0.5 * (c.phi_lo + c.phi_hi), theta = 0.5 * (c.theta_lo + c.theta_hi);
                if (++enclosed > BOUND_CELLS || (c.phi_hi - c.phi_lo < 1e-7 && c.theta_hi - c.theta_lo < 1e-7)) {
                    const double S = gb_surface_kernel(s, phi, theta);
                    status = S <= 0.0 || !isfinite(S)
                                 ? gb_error_set(GB_EDOM, "%s = %s makes r <= 0 at phi = %.9g, theta = %.9g, between the directions "
                                                "checked (allowed: r > 0 on the whole sphere)", what, text, phi, theta)
                                 : gb_error_set(GB_EDOM, "%s = %s cannot be bounded above 0 near phi = %.9g, theta = %.9g: its "
                                                "enclosure reaches %.3g there after %zu cells (allowed: a body whose r is bounded "
                                                "away from 0)", what, text, phi, theta, k.lo, enclosed);
                    break;
                }
                if (top + 2 > cap) {
                    cell *grown = realloc(stack, 2 * cap * sizeof *stack);
                    if (!grown) {
                        status = gb_error_set(GB_ENOMEM, "out of memory to bound %s = %s", what, text);
                        break;
                    }
                    stack = grown, cap *= 2;
                }
                /* halve the wider side, θ's measured on the sphere (sin φ at the cell's widest) */
                const double width_theta = (c.theta_hi - c.theta_lo) * fmax(sin(c.phi_lo), sin(c.phi_hi));
                if ((c.phi_hi - c.phi_lo >= width_theta && c.phi_hi - c.phi_lo >= 1e-7) || c.theta_hi - c.theta_lo < 1e-7) {
                    stack[top++] = (cell){c.phi_lo, phi, c.theta_lo, c.theta_hi};
                    stack[top++] = (cell){phi, c.phi_hi, c.theta_lo, c.theta_hi};
                } else {
                    stack[top++] = (cell){c.phi_lo, c.phi_hi, c.theta_lo, theta};
                    stack[top++] = (cell){c.phi_lo, c.phi_hi, theta, c.theta_hi};
                }
            }
        }
    free(stack);
    return status;
}

/* Every value on a 180 × 360 grid of directions and at the poles finite, r > 0, one r at each pole, and r
 * periodic in θ (rows at θ = 0 and 2π), to 1e-9 relative: else GB_EDOM naming the first direction that fails. */
static int check_surface(const gb_surface *s, const char *what, const char *text)
{
    enum { NP = 180, NT = 360 };
    const double tol = 1e-9;
    for (int i = 0; i <= NP; i++) {
        const double phi = M_PI * i / NP;
        const double r_start = gb_surface_radius(s, phi, 0.0);
        for (int j = 0; j <= NT; j++) {
            const double theta = 2.0 * M_PI * j / NT;
            gb_surface_point p;
            gb_surface_eval_jet(s, phi, theta, &p);
            if (p.S <= 0.0) /* r ≤ 0 (a NaN S is not finite, below) */
                return gb_error_set(GB_EDOM, "%s = %s makes r <= 0 at phi = %.6g, theta = %.6g (allowed: r > 0 on the whole "
                                             "sphere)", what, text, phi, theta);
            const double d[] = {p.S, p.S_phi, p.S_theta, p.S_phiphi, p.S_phitheta, p.S_thetatheta, p.r};
            for (size_t k = 0; k < sizeof d / sizeof d[0]; k++)
                if (!isfinite(d[k]))
                    return gb_error_set(GB_EDOM, "%s = %s is not finite at phi = %.6g, theta = %.6g (it or a derivative; "
                                                 "allowed: a smooth, finite body on the whole sphere)", what, text, phi, theta);
            /* the tree that is bounded below is the expression libmatheval runs: the same value at every point */
            const own_body *b = s->morphology->user;
            pthread_mutex_lock(&lock);
            const double run = evaluate(b, 0, s->beta, phi, theta);
            pthread_mutex_unlock(&lock);
            const double read = gb_expression_eval(b->tree, phi, theta, s->beta);
            if (!(fabs(read - run) <= 1e-12 * (1.0 + fabs(run))))
                return gb_error_set(GB_EINVAL, "%s = %s is read two ways that disagree at phi = %.6g, theta = %.6g (%.17g by "
                                               "libmatheval, %.17g by the bounding reader), so it cannot be bounded (allowed: an "
                                               "expression both read alike; write its operators with parentheses)",
                                    what, text, phi, theta, run, read);
            const int pole = i == 0 || i == NP, end = j == NT;
            if ((pole || end) && fabs(p.r - r_start) > tol * fabs(r_start))
                return gb_error_set(GB_EDOM, "%s = %s is not one surface: r = %.17g at phi = %.6g, theta = %.6g but %.17g at "
                                             "theta = 0 (allowed: one r at each pole, r periodic in theta with period 2 pi)",
                                    what, text, p.r, phi, theta, r_start);
        }
    }
    return bound_between(s, what, text);
}

/* Every body is taken about its centroid (the dynamics' points, the equilibria, the inertia): an expression's r is
 * measured from its chart's origin, so the row records where that origin lies from the centroid, −c, and every
 * position is moved by it (gb_surface_eval, gb_surface_position; gb_massprops reports the centroid at 0). A centroid
 * within GB_BODY_CENTRED of the body's size (r at φ = π/2, θ = 0), or within its quadrature error, is the origin:
 * the paper's χ written as an expression keeps the built-in bodies' bits (their centroids are 0 exactly; the
 * quadrature finds 1e-16). */
static int move_to_centroid(gb_morphology *row, double beta, const char *what, const char *text)
{
    const gb_surface s = {row, beta};
    gb_massprops_def def = gb_massprops_default_def();
    gb_massprops props;
    const int status = gb_massprops_compute(&s, &def, &props);
    if (status) return gb_error_set(status, "%s = %s: its mass properties: %s", what, text, gb_error_message());
    const double size = gb_surface_radius(&s, 0.5 * M_PI, 0.0);
    const double c = sqrt(props.centroid[0] * props.centroid[0] + props.centroid[1] * props.centroid[1] +
                          props.centroid[2] * props.centroid[2]);
    const double err = sqrt(props.centroid_err[0] * props.centroid_err[0] + props.centroid_err[1] * props.centroid_err[1] +
                            props.centroid_err[2] * props.centroid_err[2]);
    if (c <= fmax(GB_BODY_CENTRED * size, err)) return GB_OK;
    for (int i = 0; i < 3; i++) row->origin[i] = -props.centroid[i];
    row->moved = 1;
    return GB_OK;
}

int gb_body_expression(gb_body_expression_kind kind, const char *text, double beta, gb_surface *out)
{
    const char *what = kind == GB_BODY_RADIUS ? "r" : "chi";
    if (!(beta >= 0.0 && beta < GB_SURFACE_BETA_MAX) && kind == GB_BODY_PHASE)
        return gb_error_set(GB_EDOM, "beta = %.17g is outside [0, 0.25) (allowed: r^4 = 1 + 4 beta sin(phi) cos(chi) > 0)", beta);
    /* the key: β, the kind and the text */
    const size_t len = strlen(text), size = sizeof(double) + 1 + len;
    unsigned char *key = malloc(size);
    if (!key) return gb_error_set(GB_ENOMEM, "out of memory for a body");
    memcpy(key, &beta, sizeof beta);
    key[sizeof beta] = (unsigned char)kind;
    memcpy(key + sizeof beta + 1, text, len);
    pthread_mutex_lock(&lock);
    own_body *b = find_key(key, size);
    if (b) {
        free(key);
        pthread_mutex_unlock(&lock);
        *out = (gb_surface){&b->row, beta};
        return GB_OK;
    }
    b = calloc(1, sizeof *b);
    int status = b ? parse(b, what, text) : gb_error_set(GB_ENOMEM, "out of memory for a body");
    if (!status) {
        const size_t n = len + 8;
        b->name = malloc(n);
        if (!b->name) status = gb_error_set(GB_ENOMEM, "out of memory for a body");
        else snprintf(b->name, n, "%s = %s", what, text);
    }
    if (status) {
        free(key);
        if (b) body_free(b);
        pthread_mutex_unlock(&lock);
        return status;
    }
    b->key = key, b->key_size = size, b->beta = beta;
    b->row = (gb_morphology){.name = b->name, .chi_formula = kind == GB_BODY_PHASE ? b->name + 6 : "(r given)", .equations = "",
                             .user = b};
    if (kind == GB_BODY_PHASE) b->row.phase = phase_expression, b->row.phase_eval = phase_expression_eval;
    else b->row.kernel = kernel_expression;
    pthread_mutex_unlock(&lock);
    const gb_surface s = {&b->row, beta};
    status = check_surface(&s, what, text); /* evaluates under the lock, call by call */
    if (!status) status = move_to_centroid(&b->row, beta, what, text);
    pthread_mutex_lock(&lock);
    if (status) body_free(b);
    else b->next = bodies, bodies = b;
    pthread_mutex_unlock(&lock);
    if (!status) *out = s;
    return status;
}
