#include "gb_melnikov_body.h"

#include "gb_certify.h"
#include "gb_contact.h"
#include "gb_error.h"
#include "gb_massprops.h"
#include "gb_shape.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { KINKS_MAX = 64, COARSE = 2048 };

/* One tabulated node of a smooth piece. */
typedef struct node {
    double H, dH, ddH, M, dM;
} node;

typedef struct piece {
    double start, length;  /* [start, start + length] ⊂ [0, 2π] */
    size_t n;              /* intervals; nodes n + 1 */
    node *nodes;
} piece;

/* One reading of the body's mass function: what a model's context points to. */
typedef struct reading {
    struct gb_melnikov_body *body;
    int constant_mass;      /* M frozen at M(q_u) */
} reading;

struct gb_melnikov_body {
    gb_surface surface;
    reading readings[2];    /* GB_MELNIKOV_MASS_AT_TOP, GB_MELNIKOV_MASS_VARIABLE */
    double mass_at_top;
    double mass, g, inertia[3][3], centroid[3];
    gb_melnikov_body_info info;
    gb_contact_refine_def refine;
    gb_certify *certify;
    size_t pieces;
    piece piece[KINKS_MAX + 1];
    double *knots;          /* every piece's nodes but its last, ascending: the model's knots */
    size_t n_knots;
};

static double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1], out[1] = a[2] * b[0] - a[0] * b[2], out[2] = a[0] * b[1] - a[1] * b[0];
}

static void vertical(const gb_melnikov_body *b, double q, double z[3], double dz[3])
{
    const double c = cos(q), s = sin(q);
    for (int k = 0; k < 3; k++) {
        z[k] = c * b->info.vertical[k] + s * b->info.rocking[k];
        if (dz) dz[k] = -s * b->info.vertical[k] + c * b->info.rocking[k];
    }
}

/* The contact of the branch reached from (φ, θ) at attitude q, and what the table needs from it. */
static int evaluate(gb_melnikov_body *b, double q, double *phi, double *theta, node *out, gb_contact_point *point)
{
    double z[3], dz[3];
    vertical(b, q, z, dz);
    gb_contact_point c;
    int status = gb_contact_refine(&b->surface, z, *phi, *theta, &b->refine, &c);
    if (status) return status;
    if (!c.is_minimum) return gb_error_set(GB_ENUMERIC, "the contact branch at q = %.17g is no longer a minimum (a fold)", q);
    double sens[2][3];
    status = gb_contact_sensitivity(&b->surface, z, &c, sens);
    if (status) return status;
    const double dphi = dot(sens[0], dz), dtheta = dot(sens[1], dz);
    double d[3], dd[3];
    for (int k = 0; k < 3; k++) d[k] = c.rc[k] - b->centroid[k], dd[k] = c.x_phi[k] * dphi + c.x_theta[k] * dtheta;
    const double *a = b->info.axis;
    double Ia = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) Ia += a[i] * b->inertia[i][j] * a[j];
    const double ad = dot(a, d);
    out->H = -dot(d, z);
    out->dH = -dot(d, dz);
    out->ddH = -dot(dd, dz) + dot(d, z);
    out->M = Ia + b->mass * (dot(d, d) - ad * ad);
    out->dM = b->mass * (2.0 * dot(d, dd) - 2.0 * ad * dot(a, dd));
    *phi = c.phi, *theta = c.theta;
    if (point) *point = c;
    return GB_OK;
}

/* Height of the branch continued from (φ, θ) at q (for locating ties). */
static int branch_height(gb_melnikov_body *b, double q, double phi, double theta, double *h)
{
    double z[3];
    vertical(b, q, z, NULL);
    gb_contact_point c;
    const int status = gb_contact_refine(&b->surface, z, phi, theta, &b->refine, &c);
    *h = c.height;
    return status;
}

static int certified(gb_melnikov_body *b, double q, const gb_contact_point *c, gb_certify_result *r)
{
    double z[3];
    vertical(b, q, z, NULL);
    const int status = gb_certify_check(b->certify, z, c, &b->refine, r);
    if (!status && r->verdict == GB_CERTIFY_UNDECIDED)
        return gb_error_set(GB_ENOCONV, "the contact at q = %.17g could not be certified global", q);
    return status;
}

/* The top, the rocking direction and the axis. */
static int find_top(gb_melnikov_body *b)
{
    if (b->surface.beta == 0.0)
        return gb_error_set(GB_EDOM, "beta = 0: a sphere has no unstable equilibrium to rock over (allowed: 0 < beta < 0.25)");
    gb_shape_def sdef = gb_shape_default_def();
    gb_equilibria eq;
    int status = gb_shape_equilibria(&b->surface, &sdef, &eq);
    if (status) return status;
    int best = -1;
    for (size_t k = 0; k < eq.count; k++)
        if (eq.points[k].type == GB_EQ_UNSTABLE && (best < 0 || eq.points[k].r > eq.points[best].r)) best = (int)k;
    if (best < 0) return gb_error_set(GB_EDOM, "the body has no maximum of r: no top to rock over");
    double x[3];
    gb_surface_position(&b->surface, eq.points[best].phi, eq.points[best].theta, x);
    const double r = sqrt(dot(x, x));
    memcpy(b->info.top, x, sizeof x);
    b->info.r_max = r;
    for (int k = 0; k < 3; k++) b->info.vertical[k] = -x[k] / r;
    /* A tangent basis at the top and H's Hessian there by central differences of the support function. */
    const double *z0 = b->info.vertical;
    double t1[3] = {0, 0, 0}, t2[3];
    t1[fabs(z0[0]) < 0.9 ? 0 : 1] = 1.0;
    const double p = dot(t1, z0);
    for (int k = 0; k < 3; k++) t1[k] -= p * z0[k];
    const double n1 = sqrt(dot(t1, t1));
    for (int k = 0; k < 3; k++) t1[k] /= n1;
    cross(z0, t1, t2);
    const double h = 1e-4;
    double Hs[3][3];
    for (int i = -1; i <= 1; i++)
        for (int j = -1; j <= 1; j++) {
            double z[3];
            for (int k = 0; k < 3; k++) z[k] = z0[k] + i * h * t1[k] + j * h * t2[k];
            const double nz = sqrt(dot(z, z));
            for (int k = 0; k < 3; k++) z[k] /= nz;
            gb_contact_point c;
            status = gb_contact_refine(&b->surface, z, eq.points[best].phi, eq.points[best].theta, &b->refine, &c);
            if (status) return status;
            /* H over the tangent-plane coordinates (the vertical normalised: H is 1-homogeneous) */
            Hs[i + 1][j + 1] = -c.height * nz;
        }
    const double a11 = (Hs[2][1] - 2 * Hs[1][1] + Hs[0][1]) / (h * h), a22 = (Hs[1][2] - 2 * Hs[1][1] + Hs[1][0]) / (h * h);
    const double a12 = (Hs[2][2] - Hs[2][0] - Hs[0][2] + Hs[0][0]) / (4 * h * h);
    /* On the unit sphere of verticals the curvature along a tangent adds −H (the normalisation). */
    const double tr = a11 + a22, det = a11 * a22 - a12 * a12, disc = sqrt(fmax(0.0, 0.25 * tr * tr - det));
    const double low = 0.5 * tr - disc, high = 0.5 * tr + disc;
    double v[2] = {a12, low - a11};
    if (fabs(v[0]) + fabs(v[1]) < 1e-300) v[0] = 1.0, v[1] = 0.0;
    const double nv = hypot(v[0], v[1]);
    for (int k = 0; k < 3; k++) b->info.rocking[k] = (v[0] * t1[k] + v[1] * t2[k]) / nv;
    cross(z0, b->info.rocking, b->info.axis);
    b->info.curvatures[0] = low - r, b->info.curvatures[1] = high - r;
    if (!(b->info.curvatures[0] < 0.0))
        return gb_error_set(GB_EDOM, "the top of r is not a strict maximum of the centroid height (curvature %g): no saddle",
                            b->info.curvatures[0]);
    return GB_OK;
}

/* Tabulate one smooth piece from its start, continuing the branch (φ, θ). */
static int tabulate(gb_melnikov_body *b, piece *P, size_t per_radian, double phi, double theta)
{
    P->n = (size_t)ceil(P->length * (double)per_radian);
    if (P->n < 8) P->n = 8;
    P->nodes = malloc((P->n + 1) * sizeof *P->nodes);
    if (!P->nodes) return gb_error_set(GB_ENOMEM, "out of memory for the reduced model's table");
    for (size_t j = 0; j <= P->n; j++) {
        const double q = P->start + P->length * (double)j / (double)P->n;
        gb_contact_point c;
        int status = evaluate(b, q, &phi, &theta, &P->nodes[j], &c);
        gb_certify_result r;
        if (!status && j > 0 && j < P->n) status = certified(b, q, &c, &r);
        if (!status && j > 0 && j < P->n && r.verdict == GB_CERTIFY_LOWER_FOUND)
            status = gb_error_set(GB_ENUMERIC, "a contact tie between the coarse nodes near q = %.9g was missed "
                                  "(allowed: more table nodes)", q);
        if (status) return status;
    }
    b->info.table_nodes += P->n + 1;
    return GB_OK;
}

void gb_melnikov_body_free(gb_melnikov_body *b)
{
    if (!b) return;
    for (size_t k = 0; k < b->pieces; k++) free(b->piece[k].nodes);
    free(b->knots);
    gb_certify_free(b->certify);
    free(b);
}

int gb_melnikov_body_create(const gb_surface *surface, double mass, double g, size_t per_radian, gb_melnikov_body **out)
{
    *out = NULL;
    if (!(mass > 0.0 && isfinite(mass))) return gb_error_set(GB_EDOM, "mass = %g (allowed: > 0)", mass);
    if (!(g > 0.0 && isfinite(g))) return gb_error_set(GB_EDOM, "g = %g (allowed: > 0: without gravity U has no saddle)", g);
    if (per_radian < 64) return gb_error_set(GB_EDOM, "table nodes = %zu a radian (allowed: >= 64)", per_radian);
    if (!surface->morphology->kernel_jet) /* a mesh or an expression (gb_body.h): its orbit's contact cannot be certified */
        return gb_error_set(GB_EINVAL, "the reduced model certifies the contact along its orbit, and the body '%s' has no "
                            "interval enclosure (allowed: a morphology of the paper, I or II)", surface->morphology->name);
    gb_melnikov_body *b = calloc(1, sizeof *b);
    if (!b) return gb_error_set(GB_ENOMEM, "out of memory for the reduced model");
    b->surface = *surface, b->mass = mass, b->g = g;
    b->refine = gb_contact_refine_default_def();
    gb_massprops_def mdef = gb_massprops_default_def();
    mdef.mass = mass;
    gb_massprops mp;
    int status = gb_massprops_compute(surface, &mdef, &mp);
    if (!status) {
        memcpy(b->inertia, mp.inertia, sizeof b->inertia);
        memcpy(b->centroid, mp.centroid, sizeof b->centroid);
        status = find_top(b);
    }
    const gb_certify_def cdef = gb_certify_default_def();
    if (!status) status = gb_certify_create(surface, &cdef, &b->certify);
    /* Walk once over: continue the contact, certify it; a lower minimum found is a tie in the last step. */
    double phi, theta, starts[KINKS_MAX + 1][2];
    double bounds[KINKS_MAX + 2];
    size_t kinks = 0;
    if (!status) {
        double z0[3];
        vertical(b, 0.0, z0, NULL);
        gb_contact_point c;
        const double x0 = -b->info.vertical[0], y0 = -b->info.vertical[1], w0 = -b->info.vertical[2];
        status = gb_contact_refine(surface, z0, acos(fmax(-1.0, fmin(1.0, w0))), atan2(y0, x0), &b->refine, &c);
        phi = c.phi, theta = c.theta;
        starts[0][0] = phi, starts[0][1] = theta;
    }
    bounds[0] = 0.0;
    for (int k = 1; !status && k <= COARSE; k++) {
        const double q0 = 2 * M_PI * (k - 1) / COARSE, q1 = 2 * M_PI * k / COARSE;
        double z[3];
        vertical(b, q1, z, NULL);
        gb_contact_point c;
        const double phi_prev = phi, theta_prev = theta;
        status = gb_contact_refine(surface, z, phi, theta, &b->refine, &c);
        gb_certify_result r;
        if (!status) status = certified(b, q1, &c, &r);
        if (status) break;
        if (r.verdict == GB_CERTIFY_GLOBAL || k == COARSE) {
            phi = c.phi, theta = c.theta;
            continue;
        }
        /* A tie between q0 (branch A) and q1 (branch B): bisection on h_A − h_B. */
        if (kinks == KINKS_MAX) {
            status = gb_error_set(GB_ENUMERIC, "more than %d contact ties over one turn", KINKS_MAX);
            break;
        }
        double lo = q0, hi = q1;
        for (int it = 0; it < 80 && !status && hi - lo > 4e-16 * (1.0 + fabs(hi)); it++) {
            const double mid = 0.5 * (lo + hi);
            double ha = 0.0, hb = 0.0;
            status = branch_height(b, mid, phi_prev, theta_prev, &ha);
            if (!status) status = branch_height(b, mid, r.lower.phi, r.lower.theta, &hb);
            if (ha > hb) hi = mid;
            else lo = mid;
        }
        const double tie = 0.5 * (lo + hi);
        node na, nb;
        double pa = phi_prev, ta = theta_prev, pb = r.lower.phi, tb = r.lower.theta;
        if (!status) status = evaluate(b, tie, &pa, &ta, &na, NULL);
        if (!status) status = evaluate(b, tie, &pb, &tb, &nb, NULL);
        if (status) break;
        if (kinks < 16) b->info.kink_q[kinks] = tie, b->info.kink_jump[kinks] = nb.dH - na.dH;
        bounds[++kinks] = tie;
        starts[kinks][0] = pb, starts[kinks][1] = tb;
        phi = r.lower.phi, theta = r.lower.theta;
    }
    bounds[kinks + 1] = 2 * M_PI;
    b->info.kinks = kinks;
    if (b->certify) gb_certify_forget(b->certify);
    for (size_t k = 0; !status && k <= kinks; k++) {
        piece *P = &b->piece[k];
        P->start = bounds[k], P->length = bounds[k + 1] - bounds[k];
        b->pieces = k + 1;
        status = tabulate(b, P, per_radian, starts[k][0], starts[k][1]);
    }
    if (!status && !(b->knots = malloc(b->info.table_nodes * sizeof *b->knots)))
        status = gb_error_set(GB_ENOMEM, "out of memory for the reduced model");
    for (size_t k = 0; !status && k < b->pieces; k++) {
        const piece *P = &b->piece[k];
        for (size_t j = 0; j < P->n; j++) b->knots[b->n_knots++] = P->start + P->length * (double)j / (double)P->n;
    }
    if (status) {
        gb_melnikov_body_free(b);
        return status;
    }
    *out = b;
    return GB_OK;
}

void gb_melnikov_body_get_info(const gb_melnikov_body *b, gb_melnikov_body_info *out) { *out = b->info; }

/* Cubic Hermite on [q_j, q_{j+1}] with u = (q − q_j)/h and w = (q_{j+1} − q)/h, each from its own node
 * (no digits lost next to either): value and derivative. */
static void hermite(double u, double w, double h, double f0, double d0, double f1, double d1, double *f, double *df)
{
    *f = w * w * (1.0 + 2.0 * u) * f0 + u * w * w * h * d0 + u * u * (1.0 + 2.0 * w) * f1 - u * u * w * h * d1;
    if (df) *df = (-6.0 * u * w * f0 + (w * w - 2.0 * u * w) * h * d0 + 6.0 * u * w * f1 + (u * u - 2.0 * u * w) * h * d1) / h;
}

static int body_eval(void *context, double q, gb_melnikov_values *v)
{
    const reading *r = context;
    gb_melnikov_body *b = r->body;
    /* Periodic in q; a q just below 0 is read against the node at 2π ≡ 0 (its offset keeps its digits). */
    const double turn = 2 * M_PI;
    double wrapped = q;
    int below_zero = 0;
    if (q < 0.0 && q > -1e-3) below_zero = 1;
    else wrapped = q - turn * floor(q / turn);
    size_t k = 0;
    if (below_zero) k = b->pieces - 1;
    else
        while (k + 1 < b->pieces && wrapped >= b->piece[k + 1].start) k++;
    const piece *P = &b->piece[k];
    const double h = P->length / (double)P->n;
    size_t j;
    double u, w;
    if (below_zero) {
        j = P->n - 1, w = -q / h, u = 1.0 - w;
    } else {
        const double x = (wrapped - P->start) / h;
        j = x <= 0.0 ? 0 : (size_t)x;
        if (j >= P->n) j = P->n - 1;
        const double qj = P->start + P->length * (double)j / (double)P->n;
        const double qj1 = j + 1 == P->n ? P->start + P->length : P->start + P->length * (double)(j + 1) / (double)P->n;
        u = (wrapped - qj) / h, w = (qj1 - wrapped) / h;
    }
    const node *a = &P->nodes[j], *c = &P->nodes[j + 1];
    double H, dH, M, dM;
    hermite(u, w, h, a->H, a->dH, c->H, c->dH, &H, NULL);
    hermite(u, w, h, a->dH, a->ddH, c->dH, c->ddH, &dH, NULL);
    hermite(u, w, h, a->M, a->dM, c->M, c->dM, &M, &dM);
    v->U = b->mass * b->g * (H - b->info.r_max);
    v->dU = b->mass * b->g * dH;
    if (r->constant_mass) M = b->mass_at_top, dM = 0.0;
    v->M = M, v->dM = dM;
    v->S = -b->mass * dH;
    return GB_OK;
}

gb_melnikov_model gb_melnikov_body_model(gb_melnikov_body *b, gb_melnikov_body_mass mass)
{
    reading *r = &b->readings[mass == GB_MELNIKOV_MASS_VARIABLE];
    r->body = b, r->constant_mass = mass != GB_MELNIKOV_MASS_VARIABLE;
    b->mass_at_top = b->piece[0].nodes[0].M;
    /* t = 0 in the middle of the longest smooth piece (the flow's normal is defined there). */
    size_t longest = 0;
    for (size_t k = 1; k < b->pieces; k++)
        if (b->piece[k].length > b->piece[longest].length) longest = k;
    const double origin = b->piece[longest].start + 0.5 * b->piece[longest].length;
    return (gb_melnikov_model){body_eval, r, -0.05, 0.05, 1, 2 * M_PI, 0.0, origin, b->knots, b->n_knots};
}

int gb_melnikov_body_direct(gb_melnikov_body *b, double q, double *H, double *dH, double *M)
{
    /* From the top, in steps of at most 0.01 rad: continue the contact, certify it, and take the lower
     * minimum whenever the certificate finds one (the support function, with no table). */
    const double turn = 2 * M_PI, wrapped = q - turn * floor(q / turn);
    const double *x = b->info.top, r = b->info.r_max;
    double phi = acos(fmax(-1.0, fmin(1.0, x[2] / r))), theta = atan2(x[1], x[0]);
    const size_t steps = (size_t)ceil(wrapped / 0.01) + 1;
    node n;
    int status = GB_OK;
    for (size_t s = 0; s <= steps && !status; s++) {
        const double qs = wrapped * (double)s / (double)steps;
        gb_contact_point c;
        status = evaluate(b, qs, &phi, &theta, &n, &c);
        gb_certify_result res;
        if (!status) status = certified(b, qs, &c, &res);
        if (!status && res.verdict == GB_CERTIFY_LOWER_FOUND) {
            phi = res.lower.phi, theta = res.lower.theta;
            status = evaluate(b, qs, &phi, &theta, &n, NULL);
        }
    }
    if (status) return status;
    *H = n.H, *dH = n.dH, *M = n.M;
    return GB_OK;
}
