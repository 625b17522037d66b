/* gb_proof_body_jet — the Taylor coefficients of a Gömböc's support function H(q) = max_x x·v(q) over an arc of q, on
 * Arb's balls (gb_proof_body.h; docs/proofs.md, "The reduced field's Taylor coefficients").
 *
 * Everything is a truncated power series in t = q − q₀ with ball coefficients, q₀ the arc as one ball: the chart
 * coordinates a(t), b(t) of the contact, the direction s(a, b) and its chart derivatives, the kernel S = 1 + 4β k(s)
 * through the unit direction (k = sinφ cos χ as gb_surface's interval jets write it, so that one formula serves both
 * charts), r = S^{1/4}, x = r s, v(q) = cos q s₀ − sin q e. The stationarity F = (x_a·v, x_b·v) = 0 fixes a and b
 * order by order: F's k-th coefficient is J (a_k, b_k) + R_k, J = ∂F/∂(a, b) at (a₀, b₀, q₀) and R_k the same
 * coefficient computed with a_k = b_k = 0, so (a_k, b_k) = −J⁻¹ R_k. Every quantity is evaluated on balls that hold
 * its value at each q of the arc (J over the contact's whole enclosure), so each coefficient holds the true one at each
 * q: by inclusion, the arc's coefficients enclose the Lagrange remainder of a Taylor step across the arc. */
#include "gb_proof_body.h"

#include "gb_certify_internal.h"
#include "gb_error.h"
#include "gb_proof_body_ties_internal.h"
#include "gb_proof_internal.h"

#include <arb_poly.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct body {
    int one;                /* morphology I (else II) */
    gb_surface_chart chart; /* the contact's chart */
    arb_t beta, c2;         /* β; II's (3/2)π */
    double s0[3];
    arb_struct e[3];
    slong prec;
} body;

enum { SCRATCH = 48 };

/* The series of one evaluation, each of length n. */
typedef struct series {
    slong n, prec;
    arb_poly_struct t[SCRATCH];
    int used;
} series;

static arb_poly_struct *tmp(series *w) { return &w->t[w->used++]; }

static void mul(series *w, arb_poly_t out, const arb_poly_t x, const arb_poly_t y)
{
    arb_poly_mullow(out, x, y, w->n, w->prec);
}

/* out = x · c / d for small integers c and d. */
static void scale(arb_poly_t out, const arb_poly_t x, slong c, slong d, slong prec)
{
    arb_t f;
    arb_init(f);
    arb_set_si(f, c);
    arb_div_si(f, f, d, prec);
    arb_poly_scalar_mul(out, x, f, prec);
    arb_clear(f);
}

/* out = Σ x_i y_i over three components. */
static void dot3(series *w, arb_poly_t out, const arb_poly_struct *x, const arb_poly_struct *y)
{
    arb_poly_struct *p = tmp(w);
    arb_poly_zero(out);
    for (int i = 0; i < 3; i++) {
        mul(w, p, x + i, y + i);
        arb_poly_add(out, out, p, w->prec);
    }
    w->used--;
}

/* k(s) and its gradient in s (an extension off the sphere; only its tangential part enters, through s_a and s_b).
 * I: k = s_x T₅(s_z) + s_y ρ U₄(s_z), ρ = √(s_x² + s_y²) (cos 5φ = T₅(cos φ), sin 5φ = sin φ U₄(cos φ));
 * II: k = s_x cos f + s_y sin f, f = (3π/2)(s_z − s_z³/3). */
static void kernel(const body *B, series *w, const arb_poly_struct *s, arb_poly_t k, arb_poly_struct *g)
{
    const slong prec = w->prec;
    arb_poly_struct *z2 = tmp(w), *p = tmp(w), *q = tmp(w), *u = tmp(w);
    mul(w, z2, s + 2, s + 2);
    if (B->one) {
        arb_poly_struct *T5 = tmp(w), *U4 = tmp(w), *dT5 = tmp(w), *dU4 = tmp(w), *rho = tmp(w), *irho = tmp(w);
        /* T₅ = z(5 + z²(−20 + 16z²)), U₄ = 1 + z²(−12 + 16z²), T₅′ = 5 + z²(−60 + 80z²), U₄′ = z(−24 + 64z²) */
        arb_poly_scalar_mul_2exp_si(p, z2, 4);
        arb_poly_add_si(p, p, -20, prec);
        mul(w, p, p, z2);
        arb_poly_add_si(p, p, 5, prec);
        mul(w, T5, p, s + 2);
        arb_poly_scalar_mul_2exp_si(p, z2, 4);
        arb_poly_add_si(p, p, -12, prec);
        mul(w, p, p, z2);
        arb_poly_add_si(U4, p, 1, prec);
        arb_poly_scalar_mul_2exp_si(p, z2, 4);
        scale(p, p, 5, 1, prec);
        arb_poly_add_si(p, p, -60, prec);
        mul(w, p, p, z2);
        arb_poly_add_si(dT5, p, 5, prec);
        arb_poly_scalar_mul_2exp_si(p, z2, 6);
        arb_poly_add_si(p, p, -24, prec);
        mul(w, dU4, p, s + 2);
        mul(w, p, s + 0, s + 0);
        mul(w, q, s + 1, s + 1);
        arb_poly_add(p, p, q, prec);
        arb_poly_sqrt_series(rho, p, w->n, prec);
        arb_poly_inv_series(irho, rho, w->n, prec);
        /* k */
        mul(w, k, s + 0, T5);
        mul(w, p, rho, U4);
        mul(w, q, s + 1, p);
        arb_poly_add(k, k, q, prec);
        /* g_x = T₅ + s_y s_x U₄ / ρ */
        mul(w, u, U4, irho);
        mul(w, p, s + 0, s + 1);
        mul(w, q, p, u);
        arb_poly_add(g + 0, T5, q, prec);
        /* g_y = ρ U₄ + s_y² U₄ / ρ */
        mul(w, p, s + 1, s + 1);
        mul(w, q, p, u);
        mul(w, p, rho, U4);
        arb_poly_add(g + 1, p, q, prec);
        /* g_z = s_x T₅′ + s_y ρ U₄′ */
        mul(w, g + 2, s + 0, dT5);
        mul(w, p, rho, dU4);
        mul(w, q, s + 1, p);
        arb_poly_add(g + 2, g + 2, q, prec);
        w->used -= 6;
    } else {
        arb_poly_struct *sf = tmp(w), *cf = tmp(w);
        /* f = c(z − z³/3), f′ = c(1 − z²) */
        mul(w, p, z2, s + 2);
        scale(p, p, 1, 3, prec);
        arb_poly_sub(p, s + 2, p, prec);
        arb_poly_scalar_mul(p, p, B->c2, prec);
        arb_poly_sin_cos_series(sf, cf, p, w->n, prec);
        mul(w, k, s + 0, cf);
        mul(w, q, s + 1, sf);
        arb_poly_add(k, k, q, prec);
        arb_poly_set(g + 0, cf);
        arb_poly_set(g + 1, sf);
        mul(w, p, s + 1, cf);
        mul(w, q, s + 0, sf);
        arb_poly_sub(p, p, q, prec);
        arb_poly_neg(u, z2);
        arb_poly_add_si(u, u, 1, prec);
        arb_poly_scalar_mul(u, u, B->c2, prec);
        mul(w, g + 2, p, u);
        w->used -= 2;
    }
    w->used -= 4;
}

/* h = x·v and F = (x_a·v, x_b·v) as series of length w->n at the chart coordinates a(t), b(t) and q(t). */
static void evaluate(const body *B, series *w, const arb_poly_t a, const arb_poly_t b, const arb_poly_t q, arb_poly_t h,
                     arb_poly_t Fa, arb_poly_t Fb)
{
    const slong prec = w->prec, n = w->n;
    arb_poly_struct *sa = tmp(w), *ca = tmp(w), *sb = tmp(w), *cb = tmp(w), *k = tmp(w), *p = tmp(w), *r = tmp(w);
    arb_poly_struct *s = &w->t[w->used], *s_a = s + 3, *s_b = s + 6, *g = s + 9, *v = s + 12;
    w->used += 15;
    arb_poly_sin_cos_series(sa, ca, a, n, prec);
    arb_poly_sin_cos_series(sb, cb, b, n, prec);
    if (B->chart == GB_SURFACE_CHART_POLAR_Z) { /* s = (sin a cos b, sin a sin b, cos a) */
        mul(w, s + 0, sa, cb), mul(w, s + 1, sa, sb), arb_poly_set(s + 2, ca);
        mul(w, s_a + 0, ca, cb), mul(w, s_a + 1, ca, sb), arb_poly_neg(s_a + 2, sa);
        mul(w, s_b + 0, sa, sb), arb_poly_neg(s_b + 0, s_b + 0), mul(w, s_b + 1, sa, cb), arb_poly_zero(s_b + 2);
    } else { /* POLAR_X: s = (cos a, sin a cos b, sin a sin b) */
        arb_poly_set(s + 0, ca), mul(w, s + 1, sa, cb), mul(w, s + 2, sa, sb);
        arb_poly_neg(s_a + 0, sa), mul(w, s_a + 1, ca, cb), mul(w, s_a + 2, ca, sb);
        arb_poly_zero(s_b + 0), mul(w, s_b + 1, sa, sb), arb_poly_neg(s_b + 1, s_b + 1), mul(w, s_b + 2, sa, cb);
    }
    kernel(B, w, s, k, g);
    /* S = 1 + 4βk, r = S^{1/4}, ∂r = β r / S · ∂k */
    arb_poly_scalar_mul(p, k, B->beta, prec);
    arb_poly_scalar_mul_2exp_si(p, p, 2);
    arb_poly_add_si(p, p, 1, prec);
    arb_poly_sqrt_series(r, p, n, prec);
    arb_poly_sqrt_series(r, r, n, prec);
    arb_poly_div_series(p, r, p, n, prec);
    arb_poly_scalar_mul(p, p, B->beta, prec); /* β r / S */
    /* v = cos q s₀ − sin q e */
    arb_poly_sin_cos_series(sa, ca, q, n, prec);
    for (int i = 0; i < 3; i++) {
        arb_poly_scalar_mul(v + i, sa, B->e + i, prec);
        arb_poly_neg(v + i, v + i);
        if (B->s0[i] != 0.0) {
            scale(cb, ca, (slong)B->s0[i], 1, prec);
            arb_poly_add(v + i, v + i, cb, prec);
        }
    }
    /* h = r (s·v); F_a = ∂r (s·v) + r (s_a·v) with ∂r = βr/S · (∇k·s_a); the same in b */
    arb_poly_struct *sv = sb, *dk = cb;
    dot3(w, sv, s, v);
    mul(w, h, r, sv);
    arb_poly_struct *F[2] = {Fa, Fb};
    const arb_poly_struct *tangent[2] = {s_a, s_b};
    for (int j = 0; j < 2; j++) {
        arb_poly_struct *out = F[j];
        dot3(w, dk, g, tangent[j]);
        mul(w, dk, dk, p);
        mul(w, out, dk, sv);
        dot3(w, dk, tangent[j], v);
        mul(w, dk, dk, r);
        arb_poly_add(out, out, dk, prec);
    }
    w->used -= 22;
}

static void series_init(series *w, slong n, slong prec)
{
    w->n = n, w->prec = prec, w->used = 0;
    for (int i = 0; i < SCRATCH; i++) arb_poly_init(&w->t[i]);
}

static void series_clear(series *w)
{
    for (int i = 0; i < SCRATCH; i++) arb_poly_clear(&w->t[i]);
}

/* The 2 × 2 ball matrix J = ∂F/∂(a, b) over the contact's enclosure (A, B) and the arc Q: F's first coefficients
 * along a and along b. */
static void jacobian(const body *Bd, const arb_t A, const arb_t Bv, const arb_t Q, arb_t J[2][2])
{
    series w;
    series_init(&w, 2, Bd->prec);
    arb_poly_t a, b, q, h, Fa, Fb;
    arb_poly_init(a), arb_poly_init(b), arb_poly_init(q), arb_poly_init(h), arb_poly_init(Fa), arb_poly_init(Fb);
    arb_poly_set_coeff_arb(q, 0, Q);
    for (int j = 0; j < 2; j++) {
        arb_poly_zero(a), arb_poly_zero(b);
        arb_poly_set_coeff_arb(a, 0, A), arb_poly_set_coeff_arb(b, 0, Bv);
        arb_poly_set_coeff_si(j ? b : a, 1, 1);
        evaluate(Bd, &w, a, b, q, h, Fa, Fb);
        arb_poly_get_coeff_arb(J[0][j], Fa, 1);
        arb_poly_get_coeff_arb(J[1][j], Fb, 1);
    }
    arb_poly_clear(a), arb_poly_clear(b), arb_poly_clear(q), arb_poly_clear(h), arb_poly_clear(Fa), arb_poly_clear(Fb);
    series_clear(&w);
}

/* F at the point (a, b) and the arc Q. */
static void residual(const body *Bd, const arb_t a0, const arb_t b0, const arb_t Q, arb_t F[2])
{
    series w;
    series_init(&w, 1, Bd->prec);
    arb_poly_t a, b, q, h, Fa, Fb;
    arb_poly_init(a), arb_poly_init(b), arb_poly_init(q), arb_poly_init(h), arb_poly_init(Fa), arb_poly_init(Fb);
    arb_poly_set_coeff_arb(a, 0, a0), arb_poly_set_coeff_arb(b, 0, b0), arb_poly_set_coeff_arb(q, 0, Q);
    evaluate(Bd, &w, a, b, q, h, Fa, Fb);
    arb_poly_get_coeff_arb(F[0], Fa, 0);
    arb_poly_get_coeff_arb(F[1], Fb, 0);
    arb_poly_clear(a), arb_poly_clear(b), arb_poly_clear(q), arb_poly_clear(h), arb_poly_clear(Fa), arb_poly_clear(Fb);
    series_clear(&w);
}

/* Krawczyk's operator on X = (x[0], x[1]) for F(·, Q) = 0, met with X: K = c − C F(c) + (I − C J(X)) (X − c), c the
 * midpoint, C the inverse of J's midpoint in doubles. Every zero in X lies in K. Returns 0 when K ∩ X is empty (no
 * zero in X: the contact is not where the boxes say); *interior: K ⊂ int X, which proves a zero in X for every q of Q,
 * unique (Krawczyk 1969; Neumaier 1990, Thm 5.1.7). */
static int krawczyk(const body *Bd, const arb_t Q, arb_t x[2], int *interior)
{
    const slong prec = Bd->prec;
    arb_t J[2][2], c[2], F[2], d[2], k[2], t, u;
    for (int i = 0; i < 2; i++) {
        arb_init(c[i]), arb_init(F[i]), arb_init(d[i]), arb_init(k[i]);
        for (int j = 0; j < 2; j++) arb_init(J[i][j]);
    }
    arb_init(t), arb_init(u);
    jacobian(Bd, x[0], x[1], Q, J);
    for (int i = 0; i < 2; i++) arb_set_arf(c[i], arb_midref(x[i])), arb_sub(d[i], x[i], c[i], prec);
    residual(Bd, c[0], c[1], Q, F);
    const double m00 = arf_get_d(arb_midref(J[0][0]), ARF_RND_NEAR), m01 = arf_get_d(arb_midref(J[0][1]), ARF_RND_NEAR);
    const double m10 = arf_get_d(arb_midref(J[1][0]), ARF_RND_NEAR), m11 = arf_get_d(arb_midref(J[1][1]), ARF_RND_NEAR);
    const double det = m00 * m11 - m01 * m10;
    const double C[2][2] = {{m11 / det, -m01 / det}, {-m10 / det, m00 / det}};
    int held = isfinite(det) && det != 0.0;
    for (int i = 0; i < 2 && held; i++) {
        arb_set(k[i], c[i]);
        for (int j = 0; j < 2; j++) {
            gb_proof_mul_d(t, F[j], C[i][j], prec); /* − (C F(c))_i */
            arb_sub(k[i], k[i], t, prec);
            /* (I − C J)_ij d_j */
            gb_proof_mul_d(t, J[0][j], C[i][0], prec);
            gb_proof_mul_d(u, J[1][j], C[i][1], prec);
            arb_add(t, t, u, prec);
            arb_neg(t, t);
            if (i == j) arb_add_ui(t, t, 1, prec);
            arb_addmul(k[i], t, d[j], prec);
        }
    }
    *interior = held && arb_contains_interior(x[0], k[0]) && arb_contains_interior(x[1], k[1]);
    for (int i = 0; i < 2 && held; i++) held = arb_intersection(x[i], x[i], k[i], prec);
    for (int i = 0; i < 2; i++) {
        arb_clear(c[i]), arb_clear(F[i]), arb_clear(d[i]), arb_clear(k[i]);
        for (int j = 0; j < 2; j++) arb_clear(J[i][j]);
    }
    arb_clear(t), arb_clear(u);
    return held;
}

/* The arc's contact. branch −1: its kept boxes form one component on which x·v is strictly concave
 * (gb_proof_body_structure), so the maximiser of every q of the arc is the one critical point in that component's hull;
 * branch 0 or 1: the arc holds a tie (two components, H the larger of their maxima) and X is that component's hull (its
 * critical point then proved by Krawczyk's test). X = the hull, in its chart. */
static int contact_hull(const gb_proof_body_def *def, double q_lo, double q_hi, int branch, body *Bd, arb_t x[2],
                        size_t *kept)
{
    gb_proof_axes axes;
    boxes k = {0};
    const double size = fmin(fmax(q_hi - q_lo, 1e-4), 1e-3);
    int status = gb_proof_body_arc_boxes(def, q_lo, q_hi, size, &axes, &k);
    gb_proof_body_hull hulls[2];
    *kept = k.n;
    const gb_proof_body_piece want = branch < 0 ? GB_PROOF_BODY_SMOOTH : GB_PROOF_BODY_TIE;
    if (!status && gb_proof_body_structure(def->surface, &axes, &k, q_lo, q_hi, hulls) != want)
        status = gb_error_set(GB_ENUMERIC,
                              branch < 0 ? "H is not proved C2 with one contact on q in [%.17g, %.17g] (a tie, "
                                           "or boxes the structure leaves open): the arc has no Taylor "
                                           "coefficients here"
                                         : "q in [%.17g, %.17g] is not proved to hold one tie of two contacts",
                              q_lo, q_hi);
    if (!status) {
        const gb_proof_body_hull *h = &hulls[branch < 0 ? 0 : branch];
        Bd->chart = gb_region_chart(h->region);
        for (int i = 0; i < 3; i++) {
            Bd->s0[i] = axes.s0[i];
            gb_proof_ball_of(Bd->e + i, (gb_proof_interval){axes.e[i].lo, axes.e[i].hi}, Bd->prec);
        }
        for (int i = 0; i < 2; i++)
            gb_proof_ball_of(x[i], (gb_proof_interval){h->box[2 * i], h->box[2 * i + 1]}, Bd->prec);
    }
    free(k.at);
    return status;
}

static int check_arc(double q_lo, double q_hi, int order)
{
    const double two_pi = 2.0 * GB_INTERVAL_PI;
    if (!(order >= 0 && order <= GB_PROOF_BODY_JET_ORDER_MAX))
        return gb_error_set(GB_EDOM, "order = %d is out of range (allowed: 0 to %d)", order,
                            GB_PROOF_BODY_JET_ORDER_MAX);
    if (!(q_lo >= -two_pi && q_lo <= q_hi && q_hi <= 2.0 * two_pi && q_hi - q_lo <= GB_PROOF_BODY_JET_ARC_MAX))
        return gb_error_set(GB_EDOM,
                            "the arc [%g, %g] is out of range (allowed: -2 pi <= q_lo <= q_hi <= 4 pi, at most %g "
                            "wide)",
                            q_lo, q_hi, GB_PROOF_BODY_JET_ARC_MAX);
    return GB_OK;
}

static void body_open(body *Bd, slong prec)
{
    *Bd = (body){.prec = prec};
    arb_init(Bd->beta), arb_init(Bd->c2);
    for (int i = 0; i < 3; i++) arb_init(Bd->e + i);
}

static void body_close(body *Bd)
{
    arb_clear(Bd->beta), arb_clear(Bd->c2);
    for (int i = 0; i < 3; i++) arb_clear(Bd->e + i);
}

/* The body's constants on balls, once contact_hull has set its chart and axes. */
static void body_constants(const gb_proof_body_def *def, body *Bd)
{
    Bd->one = strcmp(def->surface->morphology->name, "I") == 0;
    arb_set_d(Bd->beta, def->surface->beta);
    arb_const_pi(Bd->c2, Bd->prec);
    arb_mul_ui(Bd->c2, Bd->c2, 3, Bd->prec);
    arb_mul_2exp_si(Bd->c2, Bd->c2, -1);
}

/* H's coefficients 0 … order over the ball Q of q evaluated directly, every quantity a ball over Q (into H), from the
 * contact's hull X0 (narrowed by Krawczyk's operator first; with `existence`, its first image must lie inside X0); the
 * contact's enclosure and the steps into *out. */
static int coefficients(const body *Bd, arb_t X0[2], const arb_t Q, int order, int existence, arb_ptr H,
                        gb_proof_body_jet *out)
{
    const slong prec = Bd->prec;
    int status = GB_OK;
    arb_t x[2], J[2][2], det, R[2], t;
    arb_init(x[0]), arb_init(x[1]), arb_init(det), arb_init(R[0]), arb_init(R[1]), arb_init(t);
    for (int i = 0; i < 4; i++) arb_init(J[i / 2][i % 2]);
    arb_set(x[0], X0[0]), arb_set(x[1], X0[1]);
    arb_poly_t a, b, q, h, Fa, Fb;
    arb_poly_init(a), arb_poly_init(b), arb_poly_init(q), arb_poly_init(h), arb_poly_init(Fa), arb_poly_init(Fb);
    const gb_proof_interval range = gb_proof_interval_of(Q);
    /* narrow the hull while a step takes off more than 1 % of its width */
    for (int step = 0; step < 60 && !status; step++) {
        const double before = mag_get_d(arb_radref(x[0])) + mag_get_d(arb_radref(x[1]));
        int interior = 0;
        if (!krawczyk(Bd, Q, x, &interior))
            status = gb_error_set(GB_ENUMERIC,
                                  "the Newton step leaves no contact in the kept boxes' hull for q in "
                                  "[%.17g, %.17g]",
                                  range.lo, range.hi);
        else if (existence && step == 0 && !interior)
            status = gb_error_set(GB_ENUMERIC,
                                  "a branch's contact is not proved to exist in its hull for q in "
                                  "[%.17g, %.17g] (Krawczyk's image not inside it)",
                                  range.lo, range.hi);
        out->newton_steps = step + 1;
        if (!(mag_get_d(arb_radref(x[0])) + mag_get_d(arb_radref(x[1])) < 0.99 * before)) break;
    }
    if (!status) {
        jacobian(Bd, x[0], x[1], Q, J);
        arb_mul(det, J[0][0], J[1][1], prec);
        arb_submul(det, J[0][1], J[1][0], prec);
        if (!arb_is_positive(det))
            status = gb_error_set(GB_ENUMERIC,
                                  "the chart Hessian of x.v is not proved definite over the contact for q in "
                                  "[%.17g, %.17g]",
                                  range.lo, range.hi);
    }
    series w;
    series_init(&w, order + 1, prec);
    if (!status) {
        arb_poly_set_coeff_arb(a, 0, x[0]), arb_poly_set_coeff_arb(b, 0, x[1]);
        arb_poly_set_coeff_arb(q, 0, Q), arb_poly_set_coeff_si(q, 1, 1);
        for (slong k = 1; k <= order; k++) {
            w.n = k + 1; /* a_k = b_k = 0 here: F's k-th coefficient is R_k */
            evaluate(Bd, &w, a, b, q, h, Fa, Fb);
            arb_poly_get_coeff_arb(R[0], Fa, k), arb_poly_get_coeff_arb(R[1], Fb, k);
            /* (a_k, b_k) = −J⁻¹ R = −[[J11, −J01], [−J10, J00]] R / det */
            arb_mul(t, J[1][1], R[0], prec), arb_submul(t, J[0][1], R[1], prec);
            arb_div(t, t, det, prec), arb_neg(t, t);
            arb_poly_set_coeff_arb(a, k, t);
            arb_mul(t, J[0][0], R[1], prec), arb_submul(t, J[1][0], R[0], prec);
            arb_div(t, t, det, prec), arb_neg(t, t);
            arb_poly_set_coeff_arb(b, k, t);
        }
        w.n = order + 1;
        evaluate(Bd, &w, a, b, q, h, Fa, Fb);
        for (int k = 0; k <= order && !status; k++) {
            arb_poly_get_coeff_arb(H + k, h, k);
            if (!arb_is_finite(H + k))
                status = gb_error_set(GB_ENUMERIC, "H's coefficient %d is not finite on [%.17g, %.17g]", k, range.lo,
                                      range.hi);
        }
        out->a = gb_proof_interval_of(x[0]), out->b = gb_proof_interval_of(x[1]);
        out->chart = (int)Bd->chart;
    }
    series_clear(&w);
    arb_poly_clear(a), arb_poly_clear(b), arb_poly_clear(q), arb_poly_clear(h), arb_poly_clear(Fa), arb_poly_clear(Fb);
    arb_clear(x[0]), arb_clear(x[1]), arb_clear(det), arb_clear(R[0]), arb_clear(R[1]), arb_clear(t);
    for (int i = 0; i < 4; i++) arb_clear(J[i / 2][i % 2]);
    return status;
}

/* H's coefficients 0 … order on the arc of one contact, evaluated directly over it (into H). */
static int direct(const gb_proof_body_def *def, double q_lo, double q_hi, int order, slong prec, arb_ptr H,
                  gb_proof_body_jet *out)
{
    body Bd;
    body_open(&Bd, prec);
    arb_t x[2], Q;
    arb_init(x[0]), arb_init(x[1]), arb_init(Q);
    int status = contact_hull(def, q_lo, q_hi, -1, &Bd, x, &out->kept);
    if (!status) {
        body_constants(def, &Bd);
        gb_proof_ball_of(Q, (gb_proof_interval){q_lo, q_hi}, prec);
        status = coefficients(&Bd, x, Q, order, 0, H, out);
    }
    arb_clear(x[0]), arb_clear(x[1]), arb_clear(Q);
    body_close(&Bd);
    return status;
}

/* The result's coefficients (when H is not NULL), arc, order and CPU seconds since start. */
static void fill_jet(gb_proof_body_jet *out, arb_srcptr H, int order, double q_lo, double q_hi, double start)
{
    for (int k = 0; k <= order && H; k++) out->H[k] = gb_proof_interval_of(H + k);
    out->q_lo = q_lo, out->q_hi = q_hi, out->order = order;
    out->seconds = gb_proof_cpu_seconds() - start;
}

/* H_k met with mid_k + (k + 1) H_{k+1} T for k = 0 … order (T: the arc less its middle). */
static int centred(arb_ptr H, arb_srcptr mid, const arb_t T, int order, slong prec, double q_lo, double q_hi)
{
    arb_t t;
    arb_init(t);
    int status = GB_OK;
    for (int k = 0; k <= order && !status; k++) {
        arb_mul_ui(t, H + k + 1, (ulong)k + 1, prec);
        arb_mul(t, t, T, prec);
        arb_add(t, t, mid + k, prec);
        if (!arb_intersection(H + k, H + k, t, prec))
            status = gb_error_set(GB_ENUMERIC,
                                  "H's coefficient %d: the centred form misses the direct enclosure on "
                                  "[%.17g, %.17g]",
                                  k, q_lo, q_hi);
    }
    arb_clear(t);
    return status;
}

/* On an arc, each coefficient is also the centred form c_k(q_m) + (k + 1) c_{k+1}(Q) (q − q_m) (the mean value theorem:
 * c_k′ = (k + 1) c_{k+1}), c_k(q_m) at the arc's middle and c_{k+1}(Q) the direct enclosure, met with the direct one:
 * the direct evaluation loses the cancellations between the contact's and v's variation over the arc. */
int gb_proof_body_jet_enclose(const gb_proof_body_def *def, double q_lo, double q_hi, int order, gb_proof_body_jet *out)
{
    memset(out, 0, sizeof *out);
    int status = check_arc(q_lo, q_hi, order);
    if (status) return status;
    const double start = gb_proof_cpu_seconds();
    const slong prec = def->precision >= GB_PROOF_PRECISION_MIN ? def->precision : GB_PROOF_PRECISION_DEFAULT;
    const int arc = q_hi > q_lo;
    arb_ptr H = _arb_vec_init(order + 2), mid = _arb_vec_init(order + 2);
    arb_t T, t;
    arb_init(T), arb_init(t);
    status = direct(def, q_lo, q_hi, order + arc, prec, H, out);
    if (!status && arc) {
        const double q_m = 0.5 * q_lo + 0.5 * q_hi;
        gb_proof_body_jet at_mid;
        status = direct(def, q_m, q_m, order, prec, mid, &at_mid);
        gb_proof_ball_of(T, (gb_proof_interval){q_lo, q_hi}, prec);
        arb_set_d(t, q_m);
        arb_sub(T, T, t, prec);
        if (!status) status = centred(H, mid, T, order, prec, q_lo, q_hi);
    }
    fill_jet(out, status ? NULL : H, order, q_lo, q_hi, start);
    _arb_vec_clear(H, order + 2), _arb_vec_clear(mid, order + 2);
    arb_clear(T), arb_clear(t);
    return status;
}

/* The contact of one branch at a tie q_s, on an arc wholly on the branch's side (a branch is followed up to its tie,
 * not across it): the arc's one contact where its structure is SMOOTH; on an arc where the structure still sees the
 * tie's two components, the one that is the higher at the arc's end away from the tie (told apart by their heights). Its hull into X, the chart and constants into Bd; *tie: two
 * components (the contact's existence over the arc then still to be proved). */
static int branch_hull(const gb_proof_body_def *def, double q_lo, double q_hi, double q_s, int above, body *Bd,
                       arb_t X[2], int *tie, size_t *kept)
{
    *tie = 0;
    if (above ? q_lo <= q_s : q_hi >= q_s)
        return gb_error_set(GB_ENUMERIC, "the branch %s the tie at %.17g is not followed to q in [%.17g, %.17g]",
                            above ? "above" : "below", q_s, q_lo, q_hi);
    int status = contact_hull(def, q_lo, q_hi, -1, Bd, X, kept);
    if (!status) {
        body_constants(def, Bd);
        return GB_OK;
    }
    gb_error_clear();
    body other;
    body_open(&other, Bd->prec);
    arb_t Y[2], end, h[2];
    arb_init(Y[0]), arb_init(Y[1]), arb_init(end), arb_init(h[0]), arb_init(h[1]);
    status = contact_hull(def, q_lo, q_hi, 0, Bd, X, kept);
    if (!status) status = contact_hull(def, q_lo, q_hi, 1, &other, Y, kept);
    if (!status) {
        body_constants(def, Bd), body_constants(def, &other);
        arb_set_d(end, above ? q_hi : q_lo);
        gb_proof_body_jet scratch;
        status = coefficients(Bd, X, end, 0, 0, h[0], &scratch);
        if (!status) status = coefficients(&other, Y, end, 0, 0, h[1], &scratch);
    }
    if (!status && arb_lt(h[0], h[1])) { /* the other component is the branch's */
        body swap = *Bd;
        *Bd = other, other = swap;
        arb_swap(X[0], Y[0]), arb_swap(X[1], Y[1]);
    } else if (!status && !arb_gt(h[0], h[1])) {
        status = gb_error_set(GB_ENUMERIC, "at q = %.17g the two contacts are not told apart", above ? q_hi : q_lo);
    }
    *tie = 1;
    arb_clear(Y[0]), arb_clear(Y[1]), arb_clear(end), arb_clear(h[0]), arb_clear(h[1]);
    body_close(&other);
    return status;
}

int gb_proof_body_jet_branch(const gb_proof_body_def *def, double q_lo, double q_hi, int order, double q_s, int above,
                             gb_proof_body_jet *out)
{
    memset(out, 0, sizeof *out);
    int status = check_arc(q_lo, q_hi, order);
    if (status) return status;
    const double start = gb_proof_cpu_seconds();
    const slong prec = def->precision >= GB_PROOF_PRECISION_MIN ? def->precision : GB_PROOF_PRECISION_DEFAULT;
    body Bd;
    body_open(&Bd, prec);
    arb_t X[2], Q, T, t;
    arb_init(X[0]), arb_init(X[1]), arb_init(Q), arb_init(T), arb_init(t);
    arb_ptr H = _arb_vec_init(order + 2), mid = _arb_vec_init(order + 2);
    int tie = 0;
    status = branch_hull(def, q_lo, q_hi, q_s, above, &Bd, X, &tie, &out->kept);
    gb_proof_ball_of(Q, (gb_proof_interval){q_lo, q_hi}, prec);
    if (!status) status = coefficients(&Bd, X, Q, order + 1, tie, H, out);
    if (!status && q_hi > q_lo) { /* the centred form about the middle, from the same hull */
        const double q_m = 0.5 * q_lo + 0.5 * q_hi;
        gb_proof_body_jet at_mid;
        arb_set_d(t, q_m);
        status = coefficients(&Bd, X, t, order, 0, mid, &at_mid);
        arb_sub(T, Q, t, prec);
        if (!status) status = centred(H, mid, T, order, prec, q_lo, q_hi);
    }
    fill_jet(out, status ? NULL : H, order, q_lo, q_hi, start);
    _arb_vec_clear(H, order + 2), _arb_vec_clear(mid, order + 2);
    arb_clear(X[0]), arb_clear(X[1]), arb_clear(Q), arb_clear(T), arb_clear(t);
    body_close(&Bd);
    return status;
}

int gb_proof_body_jet_components(const gb_proof_body_def *def, double q_lo, double q_hi, int order,
                                 gb_proof_body_jet out[2])
{
    memset(out, 0, 2 * sizeof *out);
    int status = check_arc(q_lo, q_hi, order);
    const slong prec = def->precision >= GB_PROOF_PRECISION_MIN ? def->precision : GB_PROOF_PRECISION_DEFAULT;
    arb_t X[2], Q;
    arb_init(X[0]), arb_init(X[1]), arb_init(Q);
    arb_ptr H = _arb_vec_init(order + 1);
    gb_proof_ball_of(Q, (gb_proof_interval){q_lo, q_hi}, prec);
    for (int br = 0; br < 2 && !status; br++) {
        body Bd;
        body_open(&Bd, prec);
        status = contact_hull(def, q_lo, q_hi, br, &Bd, X, &out[br].kept);
        if (!status) body_constants(def, &Bd), status = coefficients(&Bd, X, Q, order, 1, H, &out[br]);
        for (int k = 0; k <= order && !status; k++) out[br].H[k] = gb_proof_interval_of(H + k);
        out[br].q_lo = q_lo, out[br].q_hi = q_hi, out[br].order = order;
        body_close(&Bd);
    }
    _arb_vec_clear(H, order + 1);
    arb_clear(X[0]), arb_clear(X[1]), arb_clear(Q);
    return status;
}

/* d = h_A − h_B and its derivative over the ball Q: the two branches' coefficients 0 and 1 from their hulls. */
static int difference(const body Bd[2], arb_t X[2][2], const arb_t Q, arb_t d, arb_t dd, arb_t h, arb_t dh0,
                      int existence)
{
    arb_ptr H[2] = {_arb_vec_init(2), _arb_vec_init(2)};
    gb_proof_body_jet scratch;
    int status = GB_OK;
    for (int br = 0; br < 2 && !status; br++) status = coefficients(&Bd[br], X[br], Q, 1, existence, H[br], &scratch);
    if (!status) {
        arb_sub(d, H[0], H[1], Bd[0].prec);
        arb_sub(dd, H[0] + 1, H[1] + 1, Bd[0].prec);
        arb_set(h, H[0]), arb_set(dh0, H[0] + 1);
    }
    _arb_vec_clear(H[0], 2), _arb_vec_clear(H[1], 2);
    return status;
}

int gb_proof_body_tie_locate(const gb_proof_body_def *def, double q_lo, double q_hi, gb_proof_body_tie *out)
{
    memset(out, 0, sizeof *out);
    int status = check_arc(q_lo, q_hi, 1);
    if (!status && !(q_hi > q_lo))
        status = gb_error_set(GB_EDOM, "the arc [%g, %g] is a point (allowed: q_lo < q_hi)", q_lo, q_hi);
    if (status) return status;
    const double start = gb_proof_cpu_seconds();
    const slong prec = def->precision >= GB_PROOF_PRECISION_MIN ? def->precision : GB_PROOF_PRECISION_DEFAULT;
    body Bd[2];
    arb_t X[2][2], Q, m, d, dd, h, dh, N;
    for (int br = 0; br < 2; br++) body_open(&Bd[br], prec), arb_init(X[br][0]), arb_init(X[br][1]);
    arb_init(Q), arb_init(m), arb_init(d), arb_init(dd), arb_init(h), arb_init(dh), arb_init(N);
    size_t kept;
    for (int br = 0; br < 2 && !status; br++) {
        status = contact_hull(def, q_lo, q_hi, br, &Bd[br], X[br], &kept);
        if (!status) body_constants(def, &Bd[br]);
    }
    gb_proof_ball_of(Q, (gb_proof_interval){q_lo, q_hi}, prec);
    /* each branch's contact proved over the whole arc, and d′ away from 0 there */
    if (!status) status = difference(Bd, X, Q, d, dd, h, dh, 1);
    if (!status && arb_contains_zero(dd))
        status =
            gb_error_set(GB_ENUMERIC, "the heights' difference is not proved monotone on [%.17g, %.17g]", q_lo, q_hi);
    /* Newton: N = m − d(m)/d′(Q), Q ← N ∩ Q, while it narrows */
    for (int step = 0; step < 40 && !status; step++) {
        const double before = mag_get_d(arb_radref(Q));
        arb_set_arf(m, arb_midref(Q));
        arb_t dm, unused, unused2, unused3;
        arb_init(dm), arb_init(unused), arb_init(unused2), arb_init(unused3);
        status = difference(Bd, X, m, dm, unused, unused2, unused3, 0);
        if (!status) status = difference(Bd, X, Q, unused, dd, unused2, unused3, 0);
        if (!status) {
            arb_div(N, dm, dd, prec);
            arb_sub(N, m, N, prec);
            out->proved |= arb_contains_interior(Q, N);
            if (!arb_intersection(Q, Q, N, prec))
                status =
                    gb_error_set(GB_ENUMERIC, "no tie lies in [%.17g, %.17g] (the Newton image misses it)", q_lo, q_hi);
        }
        arb_clear(dm), arb_clear(unused), arb_clear(unused2), arb_clear(unused3);
        out->newton_steps = step + 1;
        if (!status && !(mag_get_d(arb_radref(Q)) < 0.99 * before)) break;
    }
    /* at the tie: H and the jump of H′, |d′| */
    if (!status) status = difference(Bd, X, Q, d, dd, h, dh, 0);
    if (!status) {
        arb_abs(dd, dd);
        out->q = gb_proof_interval_of(Q), out->H = gb_proof_interval_of(h), out->jump = gb_proof_interval_of(dd);
        if (!out->proved)
            status = gb_error_set(GB_ENUMERIC,
                                  "a tie in [%.17g, %.17g] is not proved (the Newton image never "
                                  "fell inside the arc)",
                                  q_lo, q_hi);
    }
    out->seconds = gb_proof_cpu_seconds() - start;
    for (int br = 0; br < 2; br++) body_close(&Bd[br]), arb_clear(X[br][0]), arb_clear(X[br][1]);
    arb_clear(Q), arb_clear(m), arb_clear(d), arb_clear(dd), arb_clear(h), arb_clear(dh), arb_clear(N);
    return status;
}
