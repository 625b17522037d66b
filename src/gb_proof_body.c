#include "gb_proof_body.h"

#include "gb_certify_internal.h"
#include "gb_error.h"
#include "gb_proof_body_ties_internal.h"
#include "gb_proof_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <arb.h>

/* The branch-and-bound runs on gb_interval.h (the certificate's arithmetic, every operation widened outwards and
 * checked against Arb op by op in verify/s7_proofs.c) because the surface's enclosures over boxes exist there
 * (gb_surface_enclose, with the phase's interval jets); the sums along the orbit, where widths would accumulate, run
 * on Arb's balls. */

typedef struct run {
    const gb_proof_body_def *def;
    gb_proof_axes axes;
    gb_proof_body_model *model;
    struct gb_proof_body_cells *cells;
} run;

enum { ARC_TOP = 64, DEPTH_MAX = 40 };

/* One cell of q: H(q) ∈ H and H′(q) ∈ dH for q in [q_lo, q_hi], H at the middle in H_mid. */
typedef struct cell {
    double q_lo, q_hi;
    gb_interval H, dH, H_mid;
    gb_interval d2H; /* H″ on the cell where `curved` (one contact, C², its Hessian proved definite) */
    int curved;
} cell;

struct gb_proof_body_cells {
    cell *at;
    size_t n, cap;
    gb_proof_interval *t;  /* t at the cells' ends: n + 1 */
    gb_proof_interval *left, *sigma; /* each cell's time from its start to its middle, and M/p over it: n */
    cell tail[2];  /* [0, cut] and [2π − cut, 2π] */
    size_t origin; /* cells below it lie left of the origin */
};

/* Appends the `size`-byte item x to the array *at of *n items (capacity *cap, doubled from `first`). */
static int push(void **at, size_t *n, size_t *cap, size_t size, size_t first, const void *x, const char *what)
{
    if (*n == *cap) {
        const size_t grown = *cap ? 2 * *cap : first;
        void *more = realloc(*at, grown * size);
        if (!more) return gb_error_set(GB_ENOMEM, "out of memory for %s", what);
        *at = more, *cap = grown;
    }
    memcpy((char *)*at + (*n)++ * size, x, size);
    return GB_OK;
}

static int push_box(boxes *b, const pbox *x)
{
    void *at = b->at;
    const int status = push(&at, &b->n, &b->cap, sizeof *x, 64, x, "the surface's boxes");
    b->at = at;
    return status;
}

static int push_cell(struct gb_proof_body_cells *c, const cell *x)
{
    void *at = c->at;
    const int status = push(&at, &c->n, &c->cap, sizeof *x, 1024, x, "the cells of q");
    c->at = at;
    return status;
}

static void fill_box(run *r, pbox *b, int region, double a_lo, double a_hi, double b_lo, double b_hi)
{
    b->a_lo = a_lo, b->a_hi = a_hi, b->b_lo = b_lo, b->b_hi = b_hi, b->region = region;
    gb_surface_enclose(r->def->surface, gb_region_chart(region), a_lo, a_hi, b_lo, b_hi, &b->e);
    r->model->boxes++;
}

/* An upper bound of (x − x*)·v over the box and the arc: the direct enclosure met with the Taylor form about the box
 * centre (whose first-order term is the gradient of x·v there, small near the maximiser). */
static double excess_upper(const pbox *b, const gb_interval xs[3], const gb_interval v[3])
{
    gb_interval d[3], dc[3];
    for (int k = 0; k < 3; k++) d[k] = gb_interval_sub(b->e.x[k], xs[k]), dc[k] = gb_interval_sub(b->e.x_c[k], xs[k]);
    const double direct = gb_proof_body_dot(d, v).hi;
    const gb_interval ga = gb_proof_body_dot(b->e.x_a_c, v), gb = gb_proof_body_dot(b->e.x_b_c, v);
    const gb_interval haa = gb_proof_body_dot(b->e.x_aa, v), hab = gb_proof_body_dot(b->e.x_ab, v), hbb = gb_proof_body_dot(b->e.x_bb, v);
    gb_interval t = gb_proof_body_dot(dc, v);
    t = gb_interval_add(t, gb_interval_add(gb_interval_mul(ga, b->e.da), gb_interval_mul(gb, b->e.db)));
    const gb_interval second = gb_interval_add(
        gb_interval_add(gb_interval_mul(haa, gb_interval_sqr(b->e.da)), gb_interval_mul(hbb, gb_interval_sqr(b->e.db))),
        gb_interval_scale(2.0, gb_interval_mul(hab, gb_interval_mul(b->e.da, b->e.db))));
    t = gb_interval_add(t, gb_interval_scale(0.5, second));
    return gb_interval_min(direct, t.hi);
}

/* No critical point of x·v(q) in the box for any q of the arc: a chart derivative's interval excludes 0. */
static int sloped(const pbox *b, const gb_interval v[3])
{
    const gb_interval ga = gb_proof_body_dot(b->e.x_a, v), gb = gb_proof_body_dot(b->e.x_b, v);
    return ga.lo > 0.0 || ga.hi < 0.0 || gb.lo > 0.0 || gb.hi < 0.0;
}

/* The surface point x* for the arc: the centre of the kept box whose centre is highest in the arc's middle
 * direction (a point of the surface: its enclosure is a few ulps wide). */
static const pbox *candidate(const run *r, const boxes *list, double q_mid)
{
    gb_interval v[3], dv[3];
    gb_proof_body_directions(&r->axes, q_mid, q_mid, v, dv);
    const pbox *best = NULL;
    double best_h = -INFINITY;
    for (size_t k = 0; k < list->n; k++) {
        const double h = gb_proof_body_dot(list->at[k].e.x_c, v).lo;
        if (h > best_h) best_h = h, best = &list->at[k];
    }
    return best;
}

static double box_size(const pbox *b) { return gb_interval_max(b->a_hi - b->a_lo, b->b_hi - b->b_lo); }

/* One pass of `keep` with the surface point x*. */
static int keep_pass(run *r, const boxes *in, const gb_interval v[3], double size, const gb_interval xs[3], boxes *out,
                     double *excess)
{
    boxes stack = {0};
    int status = GB_OK;
    for (size_t k = 0; k < in->n && !status; k++) status = push_box(&stack, &in->at[k]);
    out->n = 0;
    *excess = 0.0;
    while (!status && stack.n) {
        const pbox b = stack.at[--stack.n];
        const double up = excess_upper(&b, xs, v);
        if (up < 0.0 || sloped(&b, v)) continue;
        if (box_size(&b) > size) {
            const double am = 0.5 * (b.a_lo + b.a_hi), bm = 0.5 * (b.b_lo + b.b_hi);
            const double a[3] = {b.a_lo, am, b.a_hi}, bb[3] = {b.b_lo, bm, b.b_hi};
            for (int i = 0; i < 2 && !status; i++)
                for (int j = 0; j < 2 && !status; j++) {
                    pbox child;
                    fill_box(r, &child, b.region, a[i], a[i + 1], bb[j], bb[j + 1]);
                    status = push_box(&stack, &child);
                }
            continue;
        }
        *excess = gb_interval_max(*excess, up);
        status = push_box(out, &b);
    }
    free(stack.at);
    return status;
}

/* Keep of `in` (and their quarters, split while wider than `size`) the boxes that may hold the maximiser of x·v(q)
 * for some q in the arc; x*: the centre of a kept box highest in the arc's middle direction, chosen again from the
 * boxes kept until it no longer changes (at most 4 passes); *excess: the largest bound of (x − x*)·v over those kept. */
static int keep(run *r, const boxes *in, double q_lo, double q_hi, double size, boxes *out, gb_interval xs[3],
                double *excess)
{
    gb_interval v[3], dv[3];
    gb_proof_body_directions(&r->axes, q_lo, q_hi, v, dv);
    boxes from = {0}, to = {0};
    int status = GB_OK;
    for (size_t k = 0; k < in->n && !status; k++) status = push_box(&from, &in->at[k]);
    for (int pass = 0; pass < 4 && !status; pass++) {
        const pbox *c = candidate(r, &from, 0.5 * (q_lo + q_hi));
        if (!c) break;
        if (pass > 0 && memcmp(xs, c->e.x_c, 3 * sizeof *xs) == 0) break;
        memcpy(xs, c->e.x_c, 3 * sizeof *xs);
        status = keep_pass(r, &from, v, size, xs, &to, excess);
        const boxes swap = from;
        from = to, to = swap;
        if (!status && from.n == 0) break;
    }
    free(to.at);
    *out = from;
    if (!status && out->n == 0) status = gb_error_set(GB_ENUMERIC, "every surface box was dropped for q in [%.17g, %.17g]", q_lo, q_hi);
    return status;
}

/* The cell [q_lo, q_hi] from its kept boxes. */
static void cell_of(run *r, const boxes *kept, const gb_interval xs[3], double excess, double q_lo, double q_hi, cell *out)
{
    gb_interval v[3], dv[3], v_mid[3], dv_mid[3];
    gb_proof_body_directions(&r->axes, q_lo, q_hi, v, dv);
    const gb_interval base = gb_proof_body_dot(xs, v);
    out->q_lo = q_lo, out->q_hi = q_hi;
    out->H = (gb_interval){base.lo, gb_interval_up(base.hi + excess)};
    const double q_mid = 0.5 * (q_lo + q_hi);
    gb_proof_body_directions(&r->axes, q_mid, q_mid, v_mid, dv_mid);
    const gb_interval mid = gb_proof_body_dot(xs, v_mid);
    out->H_mid = (gb_interval){mid.lo, gb_interval_up(mid.hi + excess)};
    /* H′(q) = x*(q)·v′(q) for every q of the cell: x* in a kept box, v′(q) in v′ over the whole cell (v′ at the middle
     * alone misses H′ by up to H·w/2 where H″ < −H/2, as near the saddle) */
    for (size_t k = 0; k < kept->n; k++) {
        const gb_interval d = gb_proof_body_dot(kept->at[k].e.x, dv);
        out->dH = k ? gb_interval_hull(out->dH, d) : d;
    }
    out->curved = 0;
    switch (gb_proof_body_structure(r->def->surface, &r->axes, kept, q_lo, q_hi, NULL)) {
    case GB_PROOF_BODY_SMOOTH: {
        r->model->smooth_cells++;
        gb_interval term;
        if (gb_proof_body_second(kept, v, dv, &term)) {
            out->d2H = gb_interval_sub(term, out->H), out->curved = 1;
            r->model->curved_cells++;
            r->model->second_width_max = gb_interval_max(r->model->second_width_max, out->d2H.hi - out->d2H.lo);
        }
        break;
    }
    case GB_PROOF_BODY_TIE:
        if (r->model->tie_cells < 8) r->model->tie_q[r->model->tie_cells][0] = q_lo, r->model->tie_q[r->model->tie_cells][1] = q_hi;
        r->model->tie_cells++;
        break;
    default: r->model->open_cells++; break;
    }
    if (kept->n > r->model->kept_max) r->model->kept_max = kept->n;
    if (excess > r->model->height_spread_max) r->model->height_spread_max = excess;
}

/* The arc [q_lo, q_hi] from its parent's boxes, halved down to the cells. */
static int arc(run *r, const boxes *parent, double q_lo, double q_hi, int depth)
{
    const double w = q_hi - q_lo, two_pi = 2.0 * GB_INTERVAL_PI;
    const double dist = gb_interval_max(r->def->cut, gb_interval_min(q_lo, two_pi - q_hi));
    const int leaf = w <= r->def->resolution * dist || depth >= DEPTH_MAX;
    boxes kept = {0};
    gb_interval xs[3];
    double excess;
    int status = keep(r, parent, q_lo, q_hi, gb_interval_max(w, 1e-12), &kept, xs, &excess);
    if (!status && leaf) {
        cell c;
        cell_of(r, &kept, xs, excess, q_lo, q_hi, &c);
        status = push_cell(r->cells, &c);
    } else if (!status) {
        const double mid = q_lo + 0.5 * w;
        status = arc(r, &kept, q_lo, mid, depth + 1);
        if (!status) status = arc(r, &kept, mid, q_hi, depth + 1);
    }
    free(kept.at);
    return status;
}

/* ---- the top, exactly ------------------------------------------------------------------------------------------- */

int gb_proof_body_top(const gb_surface *s, double s0[3], double tangent_theta[3], double *chi_phi_num, int *pi_multiple)
{
    const char *name = s->morphology->name;
    if (s->morphology->phase == NULL || !name || (strcmp(name, "I") && strcmp(name, "II")))
        return gb_error_set(GB_EDOM, "the body is %s: the proof reads the top in closed form for the paper's bodies only "
                            "(allowed: morphology I or II)", name ? name : "a body of one's own");
    if (!(s->beta > 0.0 && s->beta < GB_SURFACE_BETA_MAX))
        return gb_error_set(GB_EDOM, "beta = %g is out of range (allowed: 0 < beta < 0.25)", s->beta);
    const int one = strcmp(name, "I") == 0;
    const double a[3] = {0.0, 1.0, 0.0}, b[3] = {1.0, 0.0, 0.0}, ta[3] = {-1.0, 0.0, 0.0}, tb[3] = {0.0, 1.0, 0.0};
    memcpy(s0, one ? a : b, sizeof a);
    memcpy(tangent_theta, one ? ta : tb, sizeof ta);
    *chi_phi_num = one ? -5.0 : 1.5; /* I: −5; II: (3/2) π */
    *pi_multiple = !one;
    return GB_OK;
}

int gb_proof_body_axis(arb_ptr e, const double rocking[3], const double s0[3], slong prec)
{
    arb_t n;
    arb_init(n);
    for (int k = 0; k < 3; k++) arb_set_d(e + k, s0[k] != 0.0 ? 0.0 : rocking[k]); /* s₀ is a coordinate axis */
    for (int k = 0; k < 3; k++) arb_addmul(n, e + k, e + k, prec);
    const int across = arb_is_positive(n);
    if (across) arb_rsqrt(n, n, prec);
    for (int k = 0; k < 3 && across; k++) arb_mul(e + k, e + k, n, prec);
    arb_clear(n);
    return across ? GB_OK
                  : gb_error_set(GB_EDOM, "the rocking direction is parallel to the top (allowed: a direction with a part across it)");
}

/* r_max, H″(0) = r_max² e_tᵀ (r_max I − K)⁻¹ e_t − r_max with K = β r_max⁻³ Hess f, Hess f = −[[1 + χ_φ², χ_φ],
 * [χ_φ, 1]] in (φ, θ) at the top (the sphere's metric is the identity on the equator and the gradient vanishes), e_t
 * = (e·u_φ, e·u_θ), u_φ = −e_z. And the unit e, projected on the plane ⊥ s₀. */
static int top_model(run *r, slong prec)
{
    const gb_proof_body_def *def = r->def;
    double tt[3] = {0, 0, 0}, cp = 0.0;
    int pim = 0;
    int status = gb_proof_body_top(def->surface, r->axes.s0, tt, &cp, &pim);
    if (status) return status;
    arb_t rm, K11, K12, K22, t, u, ephi, eth, det, q;
    arb_struct e[3];
    arb_init(rm), arb_init(K11), arb_init(K12), arb_init(K22), arb_init(t), arb_init(u);
    arb_init(ephi), arb_init(eth), arb_init(det), arb_init(q);
    for (int k = 0; k < 3; k++) arb_init(e + k);
    /* r_max = (1 + 4β)^{1/4} */
    arb_set_d(t, def->surface->beta);
    arb_mul_2exp_si(t, t, 2);
    arb_add_ui(t, t, 1, prec);
    arb_root_ui(rm, t, 4, prec);
    /* e ⊥ s₀, unit */
    status = gb_proof_body_axis(e, def->rocking, r->axes.s0, prec);
    if (status) goto done;
    for (int k = 0; k < 3; k++) r->axes.e[k] = (gb_interval){gb_proof_interval_of(e + k).lo, gb_proof_interval_of(e + k).hi};
    arb_neg(ephi, e + 2); /* e·u_φ, u_φ = −e_z */
    arb_zero(eth);
    for (int k = 0; k < 3; k++)
        if (tt[k] != 0.0) arb_mul_si(eth, e + k, (slong)tt[k], prec);
    /* χ_φ */
    arb_set_d(q, cp);
    if (pim) {
        arb_const_pi(t, prec);
        arb_mul(q, q, t, prec);
    }
    /* β r_max⁻³ */
    arb_pow_ui(t, rm, 3, prec);
    arb_set_d(u, def->surface->beta);
    arb_div(u, u, t, prec);
    /* K = −u [[1 + χ_φ², χ_φ], [χ_φ, 1]];  A = r_max I − K = [[r + u(1 + χ_φ²), u χ_φ], [u χ_φ, r + u]] */
    arb_sqr(t, q, prec);
    arb_add_ui(t, t, 1, prec);
    arb_mul(K11, u, t, prec);
    arb_add(K11, K11, rm, prec);
    arb_mul(K12, u, q, prec);
    arb_add(K22, rm, u, prec);
    arb_mul(det, K11, K22, prec);
    arb_submul(det, K12, K12, prec);
    /* e_tᵀ A⁻¹ e_t = (A22 eφ² − 2 A12 eφ eθ + A11 eθ²) / det */
    arb_sqr(t, ephi, prec);
    arb_mul(t, t, K22, prec);
    arb_mul(u, ephi, eth, prec);
    arb_mul(u, u, K12, prec);
    arb_mul_2exp_si(u, u, 1);
    arb_sub(t, t, u, prec);
    arb_sqr(u, eth, prec);
    arb_addmul(t, u, K11, prec);
    arb_div(t, t, det, prec);
    arb_sqr(u, rm, prec);
    arb_mul(t, t, u, prec);
    arb_sub(t, t, rm, prec);
    r->model->curvature = gb_proof_interval_of(t);
    r->model->r_max = gb_proof_interval_of(rm);
    /* λ = √(−m g H″(0) / M) */
    arb_neg(t, t);
    gb_proof_mul_d(t, t, def->mass, prec);
    gb_proof_mul_d(t, t, def->g, prec);
    gb_proof_ball_of(u, def->inertia, prec);
    arb_div(t, t, u, prec);
    arb_sqrt(t, t, prec);
    r->model->rate = gb_proof_interval_of(t);
    memcpy(r->model->top, r->axes.s0, sizeof r->axes.s0);
done:
    arb_clear(rm), arb_clear(K11), arb_clear(K12), arb_clear(K22), arb_clear(t), arb_clear(u);
    arb_clear(ephi), arb_clear(eth), arb_clear(det), arb_clear(q);
    for (int k = 0; k < 3; k++) arb_clear(e + k);
    return status;
}

/* ---- the sums on Arb's balls ------------------------------------------------------------------------------------ */

static int check_def(const gb_proof_body_def *d)
{
    const double two_pi = 2.0 * GB_INTERVAL_PI;
    if (!d->surface) return gb_error_set(GB_EINVAL, "no body");
    if (!(d->mass > 0.0 && isfinite(d->mass))) return gb_error_set(GB_EDOM, "mass = %g is out of range (allowed: > 0)", d->mass);
    if (!(d->g > 0.0 && isfinite(d->g))) return gb_error_set(GB_EDOM, "g = %g is out of range (allowed: > 0)", d->g);
    if (!(d->inertia.lo > 0.0 && d->inertia.lo <= d->inertia.hi && isfinite(d->inertia.hi)))
        return gb_error_set(GB_EDOM, "inertia = [%g, %g] is out of range (allowed: 0 < lo <= hi)", d->inertia.lo, d->inertia.hi);
    if (!(d->cut >= GB_PROOF_BODY_CUT_MIN && d->cut <= GB_PROOF_BODY_CUT_MAX))
        return gb_error_set(GB_EDOM, "cut = %g is out of range (allowed: %g to %g)", d->cut, GB_PROOF_BODY_CUT_MIN, GB_PROOF_BODY_CUT_MAX);
    if (!(d->resolution >= GB_PROOF_BODY_RESOLUTION_MIN && d->resolution <= GB_PROOF_BODY_RESOLUTION_MAX))
        return gb_error_set(GB_EDOM, "resolution = %g is out of range (allowed: %g to %g)", d->resolution,
                            GB_PROOF_BODY_RESOLUTION_MIN, GB_PROOF_BODY_RESOLUTION_MAX);
    if (!(d->origin > d->cut && d->origin < two_pi - d->cut))
        return gb_error_set(GB_EDOM, "origin = %g is out of range (allowed: cut < origin < 2 pi - cut)", d->origin);
    return gb_proof_check_precision(d->precision);
}

/* 2 M m g as a ball. */
static void energy_scale(arb_t out, const gb_proof_body_def *def, slong prec)
{
    gb_proof_ball_of(out, def->inertia, prec);
    gb_proof_mul_d(out, out, def->mass, prec);
    gb_proof_mul_d(out, out, def->g, prec);
    arb_mul_2exp_si(out, out, 1);
}

/* ∫₀^L du / √(a + b u) = 2L / (X + Y) and ∫₀^L √(a + b u) du = (2L/3)(X² + XY + Y²)/(X + Y), X = √(a + bL), Y = √a,
 * at the balls a and b (no division by b: b may hold 0). 0 unless a > 0 and a + bL > 0 are proved. */
static int half_integrals(arb_t time, arb_t root, const arb_t a, const arb_t b, const arb_t L, slong prec)
{
    arb_t X, Y, s, n;
    arb_init(X), arb_init(Y), arb_init(s), arb_init(n);
    arb_mul(X, b, L, prec);
    arb_add(X, X, a, prec);
    const int ok = arb_is_positive(X) && arb_is_positive(a);
    if (ok) {
        arb_sqrt(X, X, prec);
        arb_sqrt(Y, a, prec);
        arb_add(s, X, Y, prec);
        arb_mul_2exp_si(n, L, 1);
        arb_div(time, n, s, prec);
        arb_sqr(n, X, prec);
        arb_addmul(n, X, Y, prec);
        arb_addmul(n, Y, Y, prec);
        arb_mul(n, n, time, prec); /* 2L/(X + Y) (X² + XY + Y²) */
        arb_div_ui(root, n, 3, prec);
    }
    arb_clear(X), arb_clear(Y), arb_clear(s), arb_clear(n);
    return ok;
}

/* ∫ over the cell of dq/√(c₂ gap), gap = r_max − H: about the middle q_m the gap lies between the lines gap(q_m) ∓
 * H′(q − q_m) with H′ at its bounds on each side (H is Lipschitz with H′ in dH), and 1/√ is decreasing, so the
 * integral lies between those of the two bounding lines (closed form), a width of order w² |dH| rather than w²|H′|.
 * 0 when a bounding gap is not proved positive (the caller then uses the hull). */
static int cell_time(arb_t out, arb_t left, arb_t root, const cell *x, const arb_t rm, const arb_t c2, slong prec)
{
    arb_t gm, lo, hi, a, b, L, part, sum_lo, sum_hi, left_lo, left_hi, rpart, root_lo, root_hi;
    arb_init(gm), arb_init(lo), arb_init(hi), arb_init(a), arb_init(b), arb_init(L), arb_init(part);
    arb_init(sum_lo), arb_init(sum_hi), arb_init(left_lo), arb_init(left_hi), arb_init(rpart), arb_init(root_lo), arb_init(root_hi);
    arb_zero(root_lo), arb_zero(root_hi);
    gb_proof_ball_of(gm, (gb_proof_interval){x->H_mid.lo, x->H_mid.hi}, prec);
    arb_sub(gm, rm, gm, prec);
    arf_t bound;
    arf_init(bound);
    arb_get_lbound_arf(bound, gm, prec);
    arb_set_arf(lo, bound);
    arb_get_ubound_arf(bound, gm, prec);
    arb_set_arf(hi, bound);
    arf_clear(bound);
    arb_zero(sum_lo), arb_zero(sum_hi);
    const double q_mid = 0.5 * (x->q_lo + x->q_hi);
    int ok = 1;
    for (int side = 0; side < 2 && ok; side++) {
        /* side 0: u = q − q_m ∈ [0, q_hi − q_m], gap ∈ [lo − dH.hi u, hi − dH.lo u];
         * side 1: u = q_m − q ∈ [0, q_m − q_lo], gap ∈ [lo + dH.lo u, hi + dH.hi u] */
        arb_set_d(L, side ? q_mid : x->q_hi);
        arb_set_d(part, side ? x->q_lo : q_mid);
        arb_sub(L, L, part, prec);
        const double slope_low = side ? x->dH.lo : -x->dH.hi, slope_high = side ? x->dH.hi : -x->dH.lo;
        arb_mul(a, lo, c2, prec);
        arb_set_d(b, slope_low);
        arb_mul(b, b, c2, prec);
        ok = half_integrals(part, rpart, a, b, L, prec); /* the lower gap: the larger time, the smaller root */
        if (ok) arb_add(sum_hi, sum_hi, part, prec), arb_add(root_lo, root_lo, rpart, prec);
        if (ok && side) arb_set(left_hi, part);
        arb_mul(a, hi, c2, prec);
        arb_set_d(b, slope_high);
        arb_mul(b, b, c2, prec);
        if (ok) ok = half_integrals(part, rpart, a, b, L, prec);
        if (ok) arb_add(sum_lo, sum_lo, part, prec), arb_add(root_hi, root_hi, rpart, prec);
        if (ok && side) arb_set(left_lo, part);
    }
    if (ok) arb_union(out, sum_lo, sum_hi, prec);
    if (ok) arb_union(left, left_lo, left_hi, prec);
    if (ok) arb_union(root, root_lo, root_hi, prec);
    arb_clear(gm), arb_clear(lo), arb_clear(hi), arb_clear(a), arb_clear(b), arb_clear(L), arb_clear(part);
    arb_clear(sum_lo), arb_clear(sum_hi), arb_clear(left_lo), arb_clear(left_hi), arb_clear(rpart), arb_clear(root_lo);
    arb_clear(root_hi);
    return ok;
}

/* p, D and t at the cells' ends, from t(origin) = 0. */
static int sweep(run *r, slong prec)
{
    struct gb_proof_body_cells *c = r->cells;
    const gb_proof_body_def *def = r->def;
    c->t = malloc((c->n + 1) * sizeof *c->t);
    c->left = malloc((c->n + 1) * sizeof *c->left);
    c->sigma = malloc((c->n + 1) * sizeof *c->sigma);
    arb_ptr dt = _arb_vec_init((slong)c->n);
    if (!c->t || !c->left || !c->sigma || !dt) {
        _arb_vec_clear(dt, (slong)c->n);
        return gb_error_set(GB_ENOMEM, "out of memory for the separatrix's times");
    }
    arb_t rm, scale, M, H, p, w, a, D, t;
    arb_init(rm), arb_init(scale), arb_init(M), arb_init(H), arb_init(p), arb_init(w), arb_init(a), arb_init(D), arb_init(t);
    arb_set_d(t, def->surface->beta);
    arb_mul_2exp_si(t, t, 2);
    arb_add_ui(t, t, 1, prec);
    arb_root_ui(rm, t, 4, prec);
    energy_scale(scale, def, prec);
    gb_proof_ball_of(M, def->inertia, prec);
    arb_zero(D);
    int status = GB_OK;
    r->model->gap_min = INFINITY;
    for (size_t k = 0; k < c->n + 2 && !status; k++) {
        const cell *x = k < c->n ? &c->at[k] : &c->tail[k - c->n];
        gb_proof_ball_of(H, (gb_proof_interval){x->H.lo, x->H.hi}, prec);
        arb_sub(H, rm, H, prec); /* the gap r_max − H */
        arb_set_d(w, x->q_hi), arb_set_d(a, x->q_lo);
        arb_sub(w, w, a, prec);
        if (k >= c->n) {
            /* a neighbourhood of the saddle: 0 ≤ ∫ p dq ≤ cut · max p */
            arb_get_ubound_arf(arb_midref(a), H, prec);
            mag_zero(arb_radref(a));
            arb_mul(a, a, scale, prec);
            arb_sqrt(a, a, prec);
            arb_mul(a, a, w, prec);
            arb_mul_2exp_si(a, a, -1);
            arb_add_error(a, a);
            arb_add(D, D, a, prec);
            continue;
        }
        const double gap = gb_proof_interval_of(H).lo;
        if (!(gap > 0.0)) {
            status = gb_error_set(GB_ENUMERIC, "r_max - H is not proved positive on q in [%.17g, %.17g] (allowed: a "
                                  "finer resolution)", x->q_lo, x->q_hi);
            break;
        }
        if (gap < r->model->gap_min) r->model->gap_min = gap;
        arb_mul(p, H, scale, prec);
        arb_sqrt(p, p, prec);
        arb_t left, root;
        arb_init(left), arb_init(root);
        if (cell_time(a, left, root, x, rm, scale, prec)) {
            arb_mul(dt + k, a, M, prec);
            arb_mul(left, left, M, prec);
            arb_add(D, D, root, prec);
        } else {
            arb_addmul(D, w, p, prec);
            arb_mul(a, w, M, prec);
            arb_div(dt + k, a, p, prec);
            arb_mul_2exp_si(left, dt + k, -1);
            arb_add_error(left, left); /* anywhere in [0, dt] */
        }
        c->left[k] = gb_proof_interval_of(left);
        arb_clear(left), arb_clear(root);
        arb_div(a, M, p, prec);
        c->sigma[k] = gb_proof_interval_of(a);
    }
    if (!status) {
        arb_zero(t);
        c->t[c->origin] = gb_proof_interval_of(t);
        for (size_t k = c->origin; k < c->n; k++) {
            arb_add(t, t, dt + k, prec);
            c->t[k + 1] = gb_proof_interval_of(t);
        }
        arb_zero(t);
        for (size_t k = c->origin; k-- > 0;) {
            arb_sub(t, t, dt + k, prec);
            c->t[k] = gb_proof_interval_of(t);
        }
        r->model->D = gb_proof_interval_of(D);
    }
    _arb_vec_clear(dt, (slong)c->n);
    arb_clear(rm), arb_clear(scale), arb_clear(M), arb_clear(H), arb_clear(p), arb_clear(w), arb_clear(a), arb_clear(D), arb_clear(t);
    return status;
}

int gb_proof_body_cell_at(const gb_proof_body_model *model, double q, gb_proof_body_cell *out)
{
    const struct gb_proof_body_cells *c = model ? model->cells_data : NULL;
    if (!c) return gb_error_set(GB_EINVAL, "the model holds no cells (allowed: one enclosed and not freed)");
    const cell *found = NULL;
    for (size_t k = 0; k < c->n + 2; k++) {
        const cell *x = k < c->n ? &c->at[k] : &c->tail[k - c->n];
        if (q >= x->q_lo && q <= x->q_hi && (!found || (!found->curved && x->curved))) found = x;
    }
    if (!found) return gb_error_set(GB_EDOM, "q = %.17g lies in no cell (allowed: 0 <= q <= 2 pi)", q);
    *out = (gb_proof_body_cell){found->q_lo, found->q_hi, {found->H.lo, found->H.hi}, {found->dH.lo, found->dH.hi},
                                {-INFINITY, INFINITY}, found->curved};
    if (found->curved) out->d2H = (gb_proof_interval){found->d2H.lo, found->d2H.hi};
    return GB_OK;
}

void gb_proof_body_free(gb_proof_body_model *model)
{
    if (!model || !model->cells_data) return;
    free(model->cells_data->at);
    free(model->cells_data->t);
    free(model->cells_data->left);
    free(model->cells_data->sigma);
    free(model->cells_data);
    model->cells_data = NULL;
}

/* The certificate's root cover of the surface, enclosed. */
static int root_boxes(run *r, boxes *roots)
{
    int status = GB_OK;
    for (int k = 0; k < GB_ROOT_COUNT && !status; k++) {
        int region;
        double b[4];
        gb_root_box(k, &region, b);
        pbox x;
        fill_box(r, &x, region, b[0], b[1], b[2], b[3]);
        status = push_box(roots, &x);
    }
    return status;
}

int gb_proof_body_arc_boxes(const gb_proof_body_def *def, double q_lo, double q_hi, double size, gb_proof_axes *axes,
                            boxes *out)
{
    *out = (boxes){0};
    int status = check_def(def);
    if (status) return status;
    gb_proof_body_model scratch = {0};
    run r = {.def = def, .model = &scratch};
    boxes roots = {0};
    gb_interval xs[3];
    double excess;
    status = top_model(&r, def->precision);
    if (!status) status = root_boxes(&r, &roots);
    if (!status) status = keep(&r, &roots, q_lo, q_hi, size, out, xs, &excess);
    free(roots.at);
    *axes = r.axes;
    return status;
}

/* The cells of [lo, hi] in ARC_TOP / 2 arcs, from the root boxes. */
static int range(run *r, const boxes *roots, double lo, double hi)
{
    const int n = ARC_TOP / 2;
    int status = GB_OK;
    for (int i = 0; i < n && !status; i++) {
        const double a = i == 0 ? lo : lo + (hi - lo) * i / n, b = i + 1 == n ? hi : lo + (hi - lo) * (i + 1) / n;
        status = arc(r, roots, a, b, 0);
    }
    return status;
}

/* A neighbourhood of the saddle as one cell (its boxes no wider than the neighbourhood). */
static int tail(run *r, const boxes *roots, double lo, double hi, cell *out)
{
    boxes kept = {0};
    gb_interval xs[3];
    double excess;
    const int status = keep(r, roots, lo, hi, hi - lo, &kept, xs, &excess);
    if (!status) cell_of(r, &kept, xs, excess, lo, hi, out);
    free(kept.at);
    return status;
}

int gb_proof_body_enclose(const gb_proof_body_def *def, gb_proof_body_model *out)
{
    memset(out, 0, sizeof *out);
    int status = check_def(def);
    if (status) return status;
    const double start = gb_proof_cpu_seconds(), two_pi = 2.0 * GB_INTERVAL_PI;
    run r = {.def = def, .model = out};
    r.cells = calloc(1, sizeof *r.cells);
    if (!r.cells) return gb_error_set(GB_ENOMEM, "out of memory for the cells of q");
    out->cells_data = r.cells;
    status = top_model(&r, def->precision);
    boxes roots = {0};
    if (!status) status = root_boxes(&r, &roots);
    if (!status) status = range(&r, &roots, def->cut, def->origin);
    r.cells->origin = r.cells->n;
    if (!status) status = range(&r, &roots, def->origin, two_pi - def->cut);
    if (!status) status = tail(&r, &roots, 0.0, def->cut, &r.cells->tail[0]);
    if (!status) status = tail(&r, &roots, two_pi - def->cut, two_pi, &r.cells->tail[1]);
    free(roots.at);
    out->cells = r.cells->n;
    if (!status) status = sweep(&r, def->precision);
    out->seconds = gb_proof_cpu_seconds() - start;
    if (status) gb_proof_body_free(out);
    return status;
}

int gb_proof_body_integrals_compute(const gb_proof_body_def *def, const gb_proof_body_model *model, double omega,
                                    gb_proof_body_integrals *out)
{
    memset(out, 0, sizeof *out);
    if (!model->cells_data || !model->cells_data->t) return gb_error_set(GB_EINVAL, "the model is not enclosed");
    if (!(omega > 0.0 && omega <= 1000.0)) return gb_error_set(GB_EDOM, "omega = %g is out of range (allowed: 0 < omega <= 1000)", omega);
    const double start = gb_proof_cpu_seconds();
    const slong prec = def->precision;
    const struct gb_proof_body_cells *c = model->cells_data;
    arb_t sum[4], T, S, w, a, s, co, tail;
    for (int k = 0; k < 4; k++) arb_init(sum[k]), arb_zero(sum[k]);
    arb_init(T), arb_init(S), arb_init(w), arb_init(a), arb_init(s), arb_init(co), arb_init(tail);
    arb_t sc, Ll, Lr, Jc, Js, kk, err, cm, sm, part;
    arb_init(sc), arb_init(Ll), arb_init(Lr), arb_init(Jc), arb_init(Js), arb_init(kk), arb_init(err), arb_init(cm), arb_init(sm);
    arb_init(part);
    for (size_t k = 0; k < c->n; k++) {
        const cell *x = &c->at[k];
        /* S over the cell, and its middle's time t_m */
        gb_proof_ball_of(S, (gb_proof_interval){x->dH.lo, x->dH.hi}, prec);
        gb_proof_mul_d(S, S, -def->mass, prec);
        gb_proof_ball_of(T, c->t[k], prec);
        gb_proof_ball_of(a, c->left[k], prec);
        arb_add(T, T, a, prec);
        const double q_mid = 0.5 * (x->q_lo + x->q_hi);
        arb_set_d(Ll, q_mid), arb_set_d(a, x->q_lo);
        arb_sub(Ll, Ll, a, prec);
        arb_set_d(Lr, x->q_hi), arb_set_d(a, q_mid);
        arb_sub(Lr, Lr, a, prec);
        /* t(q) = t_m + τ(u), u = q − q_m, |τ(u) − σ_c u| ≤ ρ_σ |u| (σ = M/p over the cell in [σ_c − ρ_σ, σ_c + ρ_σ]) */
        gb_proof_ball_of(sc, c->sigma[k], prec);
        arb_sqr(err, Ll, prec);
        arb_addmul(err, Lr, Lr, prec);
        arb_mul_2exp_si(err, err, -1);
        arb_get_rad_arb(a, sc);
        arb_mul(err, err, a, prec);
        arb_get_mid_arb(sc, sc);
        for (int h = 0; h < 2; h++) {
            const double Omega = omega * (h + 1); /* ω and 2ω: doubling is exact */
            /* ∫_{−Ll}^{Lr} e^{iΩσ_c u} du = Jc + i Js in closed form */
            gb_proof_mul_d(kk, sc, Omega, prec);
            arb_mul(a, kk, Lr, prec);
            arb_sin_cos(s, co, a, prec);
            arb_mul(a, kk, Ll, prec);
            arb_sin_cos(Jc, Js, a, prec);
            arb_add(Jc, Jc, s, prec);
            arb_sub(Js, Js, co, prec);
            arb_div(Jc, Jc, kk, prec);
            arb_div(Js, Js, kk, prec);
            /* times e^{iΩ t_m}; |e^{iΩτ} − e^{iΩσ_c u}| ≤ Ω ρ_σ |u| adds Ω ρ_σ (Ll² + Lr²)/2 to each part */
            gb_proof_mul_d(a, T, Omega, prec);
            arb_sin_cos(sm, cm, a, prec);
            gb_proof_mul_d(a, err, Omega, prec);
            arb_mul(part, cm, Jc, prec);
            arb_submul(part, sm, Js, prec);
            arb_add_error(part, a);
            arb_addmul(sum[2 * h], S, part, prec);
            arb_mul(part, sm, Jc, prec);
            arb_addmul(part, cm, Js, prec);
            arb_add_error(part, a);
            arb_addmul(sum[2 * h + 1], S, part, prec);
        }
    }
    arb_clear(sc), arb_clear(Ll), arb_clear(Lr), arb_clear(Jc), arb_clear(Js), arb_clear(kk), arb_clear(err), arb_clear(cm);
    arb_clear(sm), arb_clear(part);
    /* each neighbourhood of the saddle adds at most cut · m · max |H′| to each integral */
    arb_zero(tail);
    for (int h = 0; h < 2; h++) {
        const cell *x = &c->tail[h];
        arb_set_d(a, gb_interval_mag(x->dH));
        gb_proof_mul_d(a, a, def->mass, prec);
        arb_set_d(w, x->q_hi), arb_set_d(s, x->q_lo);
        arb_sub(w, w, s, prec);
        arb_mul(a, a, w, prec);
        arb_add(tail, tail, a, prec);
    }
    arb_get_ubound_arf(arb_midref(a), tail, prec);
    arb_zero(w);
    arb_add_error_arf(w, arb_midref(a));
    for (int k = 0; k < 4; k++) arb_add(sum[k], sum[k], w, prec);
    out->omega = omega;
    out->C1 = gb_proof_interval_of(sum[0]), out->S1 = gb_proof_interval_of(sum[1]);
    out->C2 = gb_proof_interval_of(sum[2]), out->S2 = gb_proof_interval_of(sum[3]);
    out->time_span = (gb_proof_interval){gb_interval_down(c->t[c->n].lo - c->t[0].hi), gb_interval_up(c->t[c->n].hi - c->t[0].lo)};
    for (int k = 0; k < 4; k++) arb_clear(sum[k]);
    arb_clear(T), arb_clear(S), arb_clear(w), arb_clear(a), arb_clear(s), arb_clear(co), arb_clear(tail);
    out->seconds = gb_proof_cpu_seconds() - start;
    return GB_OK;
}

int gb_proof_body_melnikov(const gb_proof_body_def *def, const gb_proof_body_model *model, const gb_proof_body_forcing *f,
                           gb_proof_body_result *out)
{
    memset(out, 0, sizeof *out);
    if (!(f->damping >= 0.0 && isfinite(f->damping)))
        return gb_error_set(GB_EDOM, "damping = %g is out of range (allowed: >= 0)", f->damping);
    int status = gb_proof_body_integrals_compute(def, model, f->omega, &out->integrals);
    if (status) return status;
    const slong prec = def->precision;
    arb_t mu, M, D;
    arb_init(mu), arb_init(M), arb_init(D);
    arb_set_d(mu, f->damping);
    gb_proof_ball_of(M, def->inertia, prec);
    arb_div(mu, mu, M, prec);
    gb_proof_ball_of(D, model->D, prec);
    arb_mul(D, D, mu, prec);
    out->mu = gb_proof_interval_of(mu), out->mu_D = gb_proof_interval_of(D);
    arb_clear(mu), arb_clear(M), arb_clear(D);
    const gb_proof_body_integrals *I = &out->integrals;
    const gb_proof_melnikov m = {out->mu_D, I->C1, I->S1, I->C2, I->S2, 1.0, f->A1, f->A2, f->omega, f->psi, def->precision, f->depth};
    return gb_proof_melnikov_zeros(&m, &out->zeros);
}
