/* gb_proof_body_flow — the Gömböcs' reduced field at a forcing, integrated on Arb's balls (gb_proof_body.h).
 *
 * The state is (q, P, c, s) with P = q̇ and (c, s) = (cos ωt, sin ωt), so that the forcing is quadratic:
 * q̇ = P, Ṗ = −(m/M) a H′(q) − μP with a = g + A₁c + A₂((c² − s²) cos ψ − 2cs sin ψ), ċ = −ωs, ṡ = ωc. Everything
 * but H′ is the quadratic field gb_proof_flow integrates; H′ is its one-variable term (gb_proof_flow_term.c), whose
 * Taylor coefficients over each ball of q a step needs come from gb_proof_body_jet_enclose (G = H′: g_k = (k + 1) H_{k+1}).
 * M and ψ enter as balls, so the image holds the flow for every M and ψ in their intervals. */
#include "gb_proof_body.h"

#include "gb_error.h"
#include "gb_proof_body_arcs_internal.h"
#include "gb_proof_body_boxes_internal.h"
#include "gb_proof_flow_internal.h"
#include "gb_proof_internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The jet's context: the definition, the last arc asked (a step asks the same ball several times) and the first
 * failure's message. */
typedef struct jets {
    const gb_proof_body_def *def;
    int branch;      /* 1: one branch at the tie q_s (below it, or above), the state's q read as q − shift */
    double q_s, shift;
    int above;
    double lo, hi;
    int order;
    gb_proof_interval H[GB_PROOF_BODY_JET_ORDER_MAX + 1];
    int failed;
    char why[400];
} jets;

static int h_prime(void *context, const arb_t x, int order, arb_ptr g)
{
    jets *J = context;
    gb_proof_interval q = gb_proof_interval_of(x);
    if (J->branch) { /* the state is q − q_s */
        arb_t y;
        arb_init(y);
        arb_set_d(y, J->shift);
        arb_add(y, y, x, J->def->precision);
        q = gb_proof_interval_of(y);
        arb_clear(y);
    }
    if (!(q.hi - q.lo <= GB_PROOF_BODY_JET_ARC_MAX) || order + 1 > GB_PROOF_BODY_JET_ORDER_MAX) {
        if (!J->failed)
            snprintf(J->why, sizeof J->why,
                     "a step's enclosure spans q in [%.9g, %.9g], wider than the arcs H' is enclosed "
                     "over (at most %g)",
                     q.lo, q.hi, GB_PROOF_BODY_JET_ARC_MAX);
        J->failed = 1;
        return 1;
    }
    if (!(q.lo == J->lo && q.hi == J->hi && order + 1 <= J->order)) {
        gb_proof_body_jet jet;
        const int served = !J->branch && gb_proof_body_arcs_jet(J->def->arcs, J->def, q.lo, q.hi, order + 1, jet.H);
        if (!served && (J->branch ? gb_proof_body_jet_branch(J->def, q.lo, q.hi, order + 1, J->q_s, J->above, &jet)
                                  : gb_proof_body_jet_enclose(J->def, q.lo, q.hi, order + 1, &jet))) {
            if (!J->failed) snprintf(J->why, sizeof J->why, "%s", gb_error_message());
            gb_error_clear();
            J->failed = 1;
            J->order = -1;
            return 1;
        }
        J->lo = q.lo, J->hi = q.hi, J->order = order + 1;
        memcpy(J->H, jet.H, sizeof jet.H);
    }
    for (int k = 0; k <= order; k++) {
        gb_proof_ball_of(g + k, J->H[k + 1], J->def->precision);
        arb_mul_ui(g + k, g + k, (ulong)k + 1, J->def->precision);
    }
    return 0;
}

static int check_forcing(const gb_proof_body_forcing *f, int order, const gb_proof_interval box[2])
{
    if (!(f->damping >= 0.0 && isfinite(f->damping)))
        return gb_error_set(GB_EDOM, "damping = %g is out of range (allowed: >= 0)", f->damping);
    if (!(isfinite(f->A1) && isfinite(f->A2)))
        return gb_error_set(GB_EDOM, "A1 = %g, A2 = %g: the amplitudes must be finite", f->A1, f->A2);
    if (!(f->omega > 0.0 && f->omega <= 1000.0))
        return gb_error_set(GB_EDOM, "omega = %g is out of range (allowed: 0 < omega <= 1000)", f->omega);
    if (!(isfinite(f->psi.lo) && isfinite(f->psi.hi) && f->psi.lo <= f->psi.hi))
        return gb_error_set(GB_EDOM, "psi = [%g, %g] is not a finite interval (allowed: lo <= hi)", f->psi.lo,
                            f->psi.hi);
    if (!(order >= GB_PROOF_ORDER_MIN && order < GB_PROOF_BODY_JET_ORDER_MAX))
        return gb_error_set(GB_EDOM, "order = %d is out of range (allowed: %d to %d)", order, GB_PROOF_ORDER_MIN,
                            GB_PROOF_BODY_JET_ORDER_MAX - 1);
    for (int i = 0; i < 2; i++)
        if (!(isfinite(box[i].lo) && isfinite(box[i].hi) && box[i].lo <= box[i].hi))
            return gb_error_set(GB_EDOM, "box component %d = [%g, %g] is not a finite interval (allowed: lo <= hi)", i,
                                box[i].lo, box[i].hi);
    return GB_OK;
}

/* The field in (q, P, c, s) at the forcing, its term's jets in *J (gb_proof_flow_field_clear releases it). */
static void reduced_field(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing, int order, jets *J,
                          field_balls *F)
{
    const slong prec = def->precision;
    const gb_proof_field shape = {.dimension = 4};
    gb_proof_flow_field_init(F, &shape, order, prec);
    arb_t mM, x, y;
    arb_init(mM), arb_init(x), arb_init(y);
    /* m / M, μ = c / M */
    gb_proof_ball_of(x, def->inertia, prec);
    arb_set_d(mM, def->mass);
    arb_div(mM, mM, x, prec);
    arb_one(&F->L[0][1]);
    arb_set_d(y, forcing->damping);
    arb_div(y, y, x, prec);
    arb_neg(&F->L[1][1], y);
    arb_set_d(&F->L[3][2], forcing->omega);
    arb_neg(&F->L[2][3], &F->L[3][2]);
    /* the term −(m/M) a(c, s) H′(q) of row 1 */
    field_term *T = &F->term;
    T->row = 1, T->var = 0;
    arb_set_d(x, def->g);
    arb_mul(&T->a0, x, mM, prec);
    arb_neg(&T->a0, &T->a0);
    arb_set_d(x, forcing->A1);
    arb_mul(&T->a1[2], x, mM, prec);
    arb_neg(&T->a1[2], &T->a1[2]);
    gb_proof_ball_of(y, forcing->psi, prec);
    arb_cos(x, y, prec);
    arb_set_d(y, forcing->A2);
    arb_mul(y, y, mM, prec); /* (m/M) A₂ */
    arb_mul(&T->a2[2][2], y, x, prec);
    arb_neg(&T->a2[2][2], &T->a2[2][2]); /* −(m/M) A₂ cos ψ c² */
    arb_neg(&T->a2[3][3], &T->a2[2][2]); /* +(m/M) A₂ cos ψ s² */
    gb_proof_ball_of(x, forcing->psi, prec);
    arb_sin(x, x, prec);
    arb_mul(&T->a2[2][3], y, x, prec);
    arb_mul_2exp_si(&T->a2[2][3], &T->a2[2][3], 1); /* +2 (m/M) A₂ sin ψ c s */
    *J = (jets){.def = def, .lo = NAN, .hi = NAN, .order = -1}; /* one contact; the caller may choose a branch */
    T->jet = h_prime, T->context = J;
    arb_clear(mM), arb_clear(x), arb_clear(y);
}

static int check_all(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing, const gb_proof_interval box[2],
                     int order)
{
    const int status = check_forcing(forcing, order, box);
    if (status) return status;
    return gb_proof_check_precision(def->precision);
}

/* The message of a failed integration, with the jets' reason when one failed (a failure the step's halving cured is no
 * failure). */
static int failure(int status, const jets *J, const char *what)
{
    if (status && J->failed)
        return gb_error_set(GB_ENUMERIC, "the reduced field's %s: %s (%s)", what, J->why, gb_error_message());
    return status;
}

int gb_proof_body_flow(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing,
                       const gb_proof_interval box[2], double t0, double t, int order, gb_proof_interval image[2])
{
    int status = check_all(def, forcing, box, order);
    if (!status && !(t > 0.0 && t <= 100.0))
        status = gb_error_set(GB_EDOM, "t = %g is out of range (allowed: 0 < t <= 100, a multiple of 2^-30)", t);
    if (!status && !isfinite(t0)) status = gb_error_set(GB_EDOM, "t0 = %g is not finite (allowed: a finite time)", t0);
    if (status) return status;
    const slong prec = def->precision;
    field_balls F;
    jets J;
    reduced_field(def, forcing, order, &J, &F);
    arb_t x, y;
    arb_init(x), arb_init(y);
    gb_proof_interval start[4] = {box[0], box[1], {0, 0}, {0, 0}}, end[4];
    arb_set_d(x, forcing->omega);
    arb_set_d(y, t0);
    arb_mul(x, x, y, prec);
    arb_sin_cos(y, x, x, prec);
    start[2] = gb_proof_interval_of(x), start[3] = gb_proof_interval_of(y);
    arb_clear(x), arb_clear(y);
    const gb_proof_field shape = {.dimension = 4};
    gb_proof_flow_def fdef = gb_proof_flow_def_default(&shape);
    fdef.order = order, fdef.precision = prec, fdef.step_max = 0.05;
    status = failure(gb_proof_flow_time_of(&F, &fdef, start, t, end), &J, "flow");
    if (!status) image[0] = end[0], image[1] = end[1];
    gb_proof_flow_field_clear(&F);
    return status;
}

int gb_proof_body_period_map(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing,
                             const gb_proof_interval box[2], int periods, int order, int derivative,
                             gb_proof_body_return *out)
{
    memset(out, 0, sizeof *out);
    int status = check_all(def, forcing, box, order);
    if (!status && !(periods >= 1 && periods <= 16))
        status = gb_error_set(GB_EDOM, "periods = %d is out of range (allowed: 1 to 16)", periods);
    if (status) return status;
    field_balls F;
    jets J;
    reduced_field(def, forcing, order, &J, &F);
    const gb_proof_interval start[4] = {box[0], box[1], {1.0, 1.0}, {0.0, 0.0}};
    const gb_proof_field shape = {.dimension = 4};
    gb_proof_flow_def fdef = gb_proof_flow_def_default(&shape);
    fdef.order = order, fdef.precision = def->precision, fdef.step_max = 0.05;
    fdef.coordinate = 3, fdef.direction = 1, fdef.returns = periods, fdef.derivative = derivative != 0;
    fdef.time_max = 100.0;
    gb_proof_flow_crossing C;
    status = failure(gb_proof_flow_section_map_of(&F, &fdef, start, &C), &J, "period map");
    if (!status) {
        out->q = C.image[0], out->P = C.image[1], out->time = C.time, out->steps = C.steps, out->seconds = C.seconds;
        for (int a = 0; a < 2 && derivative; a++)
            for (int b = 0; b < 2; b++) out->jacobian[a][b] = C.jacobian[a][b];
    }
    gb_proof_flow_field_clear(&F);
    return status;
}

/* The sliver [q_a, q_b] about a tie, crossed with bounds. In q as the independent variable the state y = (P, c, s)
 * moves by dP/dq = −(m/M) a(c, s) H′(q)/P − μ, dc/dq = −ωs/P, ds/dq = ωc/P. The sliver is cut at the tie's enclosure
 * [t₋, t₊]: below it H′ is the branch below's, above it the branch above's, and across the enclosure itself (about
 * 1e-15 wide) within the hull of both. Over one part [q₀, q₀ + w], H′ within the ball H there, from y₀ (boxes):
 * - a priori, P stays in G = [0.9 P₀, 1.1 P₀] (checked: P₀ + [0, w] dP/dq over G lies inside G), so the part takes
 *   τ ≤ w / min G and (c, s) stay within ωτ of (c₀, s₀) (cos and sin are 1-Lipschitz in ωt);
 * - P at its end lies in P₀ + w dP/dq over (G's verified hull P̄, the phase boxes), the time τ in w / P̄, and (c, s)
 *   is (c₀, s₀) turned by ωτ (exact: t moves by τ);
 * - the derivative ∂y/∂y₀ solves J′ = A J, J(q₀) = I, A = ∂(dy/dq)/∂y: by Grönwall ‖J − I‖∞ ≤ δ = e^{Lw} − 1 with
 *   L = ‖A‖∞ over the same boxes, and then J(q₀ + w) = I + ∫ A J dq lies in I + w A (I ± δ).
 * The map across the sliver is the composition of the parts' section maps q = const, so no saltation enters: the
 * state (P, t) is continuous across the tie. */
typedef struct sliver {
    const gb_proof_body_forcing *forcing;
    double g;
    slong prec;
    arb_t mM, mu, cp, sp; /* m/M, μ = c/M, cos ψ, sin ψ */
} sliver;

/* out = x + d for a double d (exact as a ball). */
static void add_d(arb_t out, const arb_t x, double d, slong prec)
{
    arb_t y;
    arb_init(y);
    arb_set_d(y, d);
    arb_add(out, x, y, prec);
    arb_clear(y);
}

/* dP/dq = −(m/M) a H / P − μ over the boxes. */
static void slope(const sliver *K, const arb_t a, const arb_t H, const arb_t P, arb_t out)
{
    arb_mul(out, K->mM, a, K->prec);
    arb_mul(out, out, H, K->prec);
    arb_div(out, out, P, K->prec);
    arb_add(out, out, K->mu, K->prec);
    arb_neg(out, out);
}

/* One part [q_from, q_to] of the sliver, H′ within the ball H over it: y = (P, c, s) at q_from becomes y at q_to, τ
 * grows by the part's time and J (3 × 3) is multiplied on the left by the part's derivative. */
static int sliver_part(const sliver *K, const arb_t H, double q_from, double q_to, gb_proof_interval y[3], arb_t tau,
                       arb_mat_t J)
{
    const slong prec = K->prec;
    const double omega = K->forcing->omega, A1 = K->forcing->A1, A2 = K->forcing->A2;
    const gb_proof_interval P0 = y[0];
    arb_t w, G, C, S, a, ac, as, x, z, gP, Pv, t, c0, s0;
    arb_ptr v[] = {w, G, C, S, a, ac, as, x, z, gP, Pv, t, c0, s0};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) arb_init(v[i]);
    arf_t bound;
    arf_init(bound);
    arb_set_d(w, q_to);
    add_d(w, w, -q_from, prec);
    gb_proof_ball_of(G, (gb_proof_interval){0.9 * P0.lo, 1.1 * P0.hi}, prec);
    gb_proof_ball_of(c0, y[1], prec);
    gb_proof_ball_of(s0, y[2], prec);
    /* τ ≤ w / min G: the phase boxes (c₀, s₀) ± ωτ */
    arb_div(x, w, G, prec);
    gb_proof_mul_d(x, x, omega, prec);
    arb_get_abs_ubound_arf(bound, x, prec);
    arb_zero_pm_one(z);
    arb_mul_arf(z, z, bound, prec);
    arb_add(C, c0, z, prec);
    arb_add(S, s0, z, prec);
    /* a = g + A₁c + A₂((c² − s²) cos ψ − 2cs sin ψ), and its partial derivatives a_c, a_s */
    arb_sqr(x, C, prec);
    arb_sqr(z, S, prec);
    arb_sub(x, x, z, prec);
    arb_mul(x, x, K->cp, prec);
    arb_mul(z, C, S, prec);
    arb_mul(z, z, K->sp, prec);
    arb_mul_2exp_si(z, z, 1);
    arb_sub(x, x, z, prec);
    gb_proof_mul_d(a, x, A2, prec);
    gb_proof_mul_d(x, C, A1, prec);
    arb_add(a, a, x, prec);
    add_d(a, a, K->g, prec);
    arb_mul(x, C, K->cp, prec);
    arb_mul(z, S, K->sp, prec);
    arb_sub(x, x, z, prec);
    gb_proof_mul_d(ac, x, 2.0 * A2, prec);
    add_d(ac, ac, A1, prec);
    arb_mul(x, S, K->cp, prec);
    arb_mul(z, C, K->sp, prec);
    arb_add(x, x, z, prec);
    gb_proof_mul_d(as, x, -2.0 * A2, prec);
    /* P over the part: P₀ + [0, w] dP/dq over G, inside G */
    slope(K, a, H, G, gP);
    arb_zero_pm_one(x);
    add_d(x, x, 1.0, prec);
    arb_mul_2exp_si(x, x, -1); /* [0, 1] */
    arb_mul(x, x, w, prec);
    arb_mul(x, x, gP, prec);
    gb_proof_ball_of(Pv, P0, prec);
    arb_add(Pv, Pv, x, prec);
    const gb_proof_interval Gi = gb_proof_interval_of(G), Pi = gb_proof_interval_of(Pv);
    int status = GB_OK;
    if (!(P0.lo > 0.0 && Pi.lo > Gi.lo && Pi.hi < Gi.hi))
        status = gb_error_set(GB_ENUMERIC, "the tie's sliver is not crossed within the guess of q' (q' in [%g, %g])",
                              P0.lo, P0.hi);
    if (!status) {
        /* P at the end, the time τ = ∫ dq / P, (c, s) turned by ωτ */
        slope(K, a, H, Pv, gP);
        arb_mul(gP, gP, w, prec);
        gb_proof_ball_of(x, P0, prec);
        arb_add(x, x, gP, prec);
        y[0] = gb_proof_interval_of(x);
        arb_div(t, w, Pv, prec);
        arb_add(tau, tau, t, prec);
        gb_proof_mul_d(x, t, omega, prec);
        arb_t st, ct;
        arb_init(st), arb_init(ct);
        arb_sin_cos(st, ct, x, prec);
        arb_mul(x, c0, ct, prec);
        arb_mul(z, s0, st, prec);
        arb_sub(x, x, z, prec);
        y[1] = gb_proof_interval_of(x);
        arb_mul(x, s0, ct, prec);
        arb_mul(z, c0, st, prec);
        arb_add(x, x, z, prec);
        y[2] = gb_proof_interval_of(x);
        arb_clear(st), arb_clear(ct);
        /* A over (P̄, C, S): rows dP/dq, dc/dq, ds/dq; columns ∂/∂P, ∂/∂c, ∂/∂s */
        arb_mat_t A, B, Jp;
        arb_mat_init(A, 3, 3), arb_mat_init(B, 3, 3), arb_mat_init(Jp, 3, 3);
        arb_mul(x, K->mM, H, prec);
        arb_sqr(z, Pv, prec);
        arb_mul(arb_mat_entry(A, 0, 0), x, a, prec);
        arb_div(arb_mat_entry(A, 0, 0), arb_mat_entry(A, 0, 0), z, prec);
        arb_mul(arb_mat_entry(A, 0, 1), x, ac, prec);
        arb_div(arb_mat_entry(A, 0, 1), arb_mat_entry(A, 0, 1), Pv, prec);
        arb_neg(arb_mat_entry(A, 0, 1), arb_mat_entry(A, 0, 1));
        arb_mul(arb_mat_entry(A, 0, 2), x, as, prec);
        arb_div(arb_mat_entry(A, 0, 2), arb_mat_entry(A, 0, 2), Pv, prec);
        arb_neg(arb_mat_entry(A, 0, 2), arb_mat_entry(A, 0, 2));
        gb_proof_mul_d(arb_mat_entry(A, 1, 0), S, omega, prec);
        arb_div(arb_mat_entry(A, 1, 0), arb_mat_entry(A, 1, 0), z, prec);
        arb_set_d(x, omega);
        arb_div(x, x, Pv, prec);
        arb_neg(arb_mat_entry(A, 1, 2), x);
        gb_proof_mul_d(arb_mat_entry(A, 2, 0), C, -omega, prec);
        arb_div(arb_mat_entry(A, 2, 0), arb_mat_entry(A, 2, 0), z, prec);
        arb_set(arb_mat_entry(A, 2, 1), x);
        /* L = the largest row sum of |A| (an upper bound); δ = e^{Lw} − 1; J over the part I ± δ, at its end
         * I + w A (I ± δ) */
        arb_zero(z);
        for (int i = 0; i < 3; i++) {
            arb_zero(x);
            for (int j = 0; j < 3; j++) {
                arb_get_abs_ubound_arf(bound, arb_mat_entry(A, i, j), prec);
                arb_add_arf(x, x, bound, prec);
            }
            arb_get_ubound_arf(bound, x, prec);
            arb_set_arf(x, bound);
            arb_max(z, z, x, prec);
        }
        arb_mul(z, z, w, prec);
        arb_expm1(z, z, prec);
        arb_get_ubound_arf(bound, z, prec);
        arb_mat_one(B);
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) arb_add_error_arf(arb_mat_entry(B, i, j), bound);
        arb_mat_mul(Jp, A, B, prec);
        arb_mat_scalar_mul_arb(Jp, Jp, w, prec);
        arb_mat_one(B);
        arb_mat_add(Jp, Jp, B, prec);
        arb_mat_mul(B, Jp, J, prec);
        arb_mat_set(J, B);
        arb_mat_clear(A), arb_mat_clear(B), arb_mat_clear(Jp);
    }
    arf_clear(bound);
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) arb_clear(v[i]);
    return status;
}

/* The sliver [q_a, q_b] from phase 1's end (x, P, c, s): again = (0, P, c, s) at q_b, the time across it, and Js =
 * ∂(P, c, s)(q_b)/∂(P, c, s)(q_a). */
static int sliver_cross(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing,
                        const gb_proof_body_tie *tie, double q_s, const gb_proof_interval end[4], double q_a,
                        double q_b, gb_proof_interval again[4], gb_proof_interval *time, arb_mat_t Js)
{
    const slong prec = def->precision;
    /* the parts' ends: the tie's enclosure, on either side of q_s (the branches are told apart on arcs short of it) */
    const double cut[2] = {fmin(tie->q.lo, nextafter(q_s, -INFINITY)), fmax(tie->q.hi, nextafter(q_s, INFINITY))};
    gb_proof_body_jet below, above, both[2];
    int status = gb_proof_body_jet_branch(def, q_a, cut[0], 1, q_s, 0, &below);
    if (!status) status = gb_proof_body_jet_components(def, cut[0], cut[1], 1, both);
    if (!status) status = gb_proof_body_jet_branch(def, cut[1], q_b, 1, q_s, 1, &above);
    if (status) return status;
    sliver K = {.forcing = forcing, .g = def->g, .prec = prec};
    arb_init(K.mM), arb_init(K.mu), arb_init(K.cp), arb_init(K.sp);
    arb_t x, H[3], tau;
    arb_init(x), arb_init(tau);
    for (int i = 0; i < 3; i++) arb_init(H[i]);
    gb_proof_ball_of(x, def->inertia, prec);
    arb_set_d(K.mM, def->mass);
    arb_div(K.mM, K.mM, x, prec);
    arb_set_d(K.mu, forcing->damping);
    arb_div(K.mu, K.mu, x, prec);
    gb_proof_ball_of(x, forcing->psi, prec);
    arb_sin_cos(K.sp, K.cp, x, prec);
    gb_proof_ball_of(H[0], below.H[1], prec);
    gb_proof_ball_of(
        H[1], (gb_proof_interval){fmin(both[0].H[1].lo, both[1].H[1].lo), fmax(both[0].H[1].hi, both[1].H[1].hi)},
        prec);
    gb_proof_ball_of(H[2], above.H[1], prec);
    const double ends[4] = {q_a, cut[0], cut[1], q_b};
    gb_proof_interval y[3] = {end[1], end[2], end[3]};
    arb_mat_one(Js);
    for (int part = 0; part < 3 && !status; part++)
        status = sliver_part(&K, H[part], ends[part], ends[part + 1], y, tau, Js);
    if (!status) {
        again[0] = (gb_proof_interval){0.0, 0.0}, again[1] = y[0], again[2] = y[1], again[3] = y[2];
        *time = gb_proof_interval_of(tau);
    }
    arb_clear(K.mM), arb_clear(K.mu), arb_clear(K.cp), arb_clear(K.sp);
    arb_clear(x), arb_clear(tau);
    for (int i = 0; i < 3; i++) arb_clear(H[i]);
    return status;
}

/* The section at the tie: phase 1's crossing of q = q_a (the branch below), the sliver to q_b, then phase 2 from it
 * (the branch above) to the period's end; with derivative, the three derivatives composed (the chain rule through the
 * sections q = q_a and q = q_b, on which the state is (P, c, s)). */
int gb_proof_body_period_map_tie(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing,
                                 const gb_proof_interval box[2], const gb_proof_body_tie *tie, int order,
                                 int derivative, gb_proof_body_return *out)
{
    memset(out, 0, sizeof *out);
    int status = check_all(def, forcing, box, order);
    if (!status && !(tie->proved && tie->q.lo <= tie->q.hi && tie->jump.hi < INFINITY && box[0].hi < tie->q.lo && box[1].lo > 0.0))
        status = gb_error_set(GB_EDOM, "the box must lie below a proved tie and move up (allowed: q_hi < the tie's q, q' > 0)");
    if (status) return status;
    const slong prec = def->precision;
    const double q_s = 0.5 * tie->q.lo + 0.5 * tie->q.hi, delta = fmax(q_s - tie->q.lo, tie->q.hi - q_s);
    const gb_proof_field shape = {.dimension = 4};
    gb_proof_flow_def fdef = gb_proof_flow_def_default(&shape);
    fdef.order = order, fdef.precision = prec, fdef.step_max = 0.01, fdef.direction = 1, fdef.returns = 1;
    fdef.derivative = derivative != 0;
    field_balls F;
    jets J;
    gb_proof_flow_crossing C1 = {0}, C2 = {0};
    arb_t x, y, z;
    arb_init(x), arb_init(y), arb_init(z);
    arb_mat_t Js;
    arb_mat_init(Js, 3, 3);
    /* phase 1: the branch below the tie, in x = q − q_a, to x = 0 (q_a = q_s − η, below the tie by more than its
     * enclosure's width) in two sections: first to q_s − Δ, where the whole set crosses well short of the tie (a set
     * crossing a section straddles it by its own width, and the branch below has no coefficients past the tie), then
     * from that section, where every point has the same q and the set's spread in q stays far below η, to q_a; then
     * the sliver [q_a, q_b] (q_b = q_s + η) crossed with bounds; then phase 2 from q_b on the branch above */
    const double eta = 1e-7, q_a = q_s - eta, q_b = q_s + eta, q_early = q_s - 2e-4;
    reduced_field(def, forcing, order, &J, &F);
    J.branch = 1, J.q_s = q_s, J.shift = q_early, J.above = 0;
    gb_proof_interval start[4] = {box[0], box[1], {1.0, 1.0}, {0.0, 0.0}};
    gb_proof_ball_of(x, box[0], prec);
    arb_set_d(y, q_early);
    arb_sub(x, x, y, prec);
    start[0] = gb_proof_interval_of(x);
    fdef.coordinate = 0;
    gb_proof_flow_crossing C0 = {0};
    if (!(delta < 0.01 * eta && box[0].hi < q_early))
        status =
            gb_error_set(GB_ENUMERIC, "the tie's enclosure (%g wide) or the box is too close to the tie (q_hi >= %.9g)",
                         2 * delta, q_early);
    if (!status) status = failure(gb_proof_flow_section_map_of(&F, &fdef, start, &C0), &J, "flow to the tie");
    if (!status) {
        J.shift = q_a;
        arb_set_d(x, q_early);
        arb_set_d(y, q_a);
        arb_sub(x, x, y, prec);
        start[0] = gb_proof_interval_of(x);
        for (int i = 1; i < 4; i++) start[i] = C0.image[i];
        status = failure(gb_proof_flow_section_map_of(&F, &fdef, start, &C1), &J, "flow to the tie");
    }
    if (!status) { /* phase 1 whole: the times add, the derivatives compose (C0's row x is 0) */
        gb_proof_ball_of(x, C0.time, prec), gb_proof_ball_of(y, C1.time, prec);
        arb_add(x, x, y, prec);
        C1.time = gb_proof_interval_of(x);
        C1.steps += C0.steps, C1.seconds += C0.seconds;
        if (derivative) {
            arb_mat_t A, B, D;
            arb_mat_init(A, 4, 4), arb_mat_init(B, 4, 4), arb_mat_init(D, 4, 4);
            for (int a = 0; a < 4; a++)
                for (int b = 0; b < 4; b++) {
                    gb_proof_ball_of(arb_mat_entry(A, a, b), C1.jacobian[a][b], prec);
                    gb_proof_ball_of(arb_mat_entry(B, a, b), C0.jacobian[a][b], prec);
                }
            arb_mat_mul(D, A, B, prec);
            for (int a = 0; a < 4; a++)
                for (int b = 0; b < 4; b++) C1.jacobian[a][b] = gb_proof_interval_of(arb_mat_entry(D, a, b));
            arb_mat_clear(A), arb_mat_clear(B), arb_mat_clear(D);
        }
    }
    gb_proof_flow_field_clear(&F);
    /* within the period, moving up */
    arb_const_pi(z, prec);
    arb_mul_2exp_si(z, z, 1);
    arb_set_d(y, forcing->omega);
    arb_div(z, z, y, prec); /* T = 2π/ω */
    gb_proof_interval T = gb_proof_interval_of(z);
    if (!status && !(C1.time.hi < T.lo && C1.image[1].lo > 0.0))
        status = gb_error_set(GB_ENUMERIC, "the tie is not crossed moving up within the period (t in [%g, %g], q' in [%g, %g])",
                              C1.time.lo, C1.time.hi, C1.image[1].lo, C1.image[1].hi);
    gb_proof_interval again[4], sliver_time = {0, 0};
    if (!status) status = sliver_cross(def, forcing, tie, q_s, C1.image, q_a, q_b, again, &sliver_time, Js);
    if (!status) {
        /* phase 2: the branch above the tie, from q_b to the period's end (the upward crossing of sin ωt = 0) */
        reduced_field(def, forcing, order, &J, &F);
        J.branch = 1, J.q_s = q_s, J.shift = q_b, J.above = 1;
        fdef.coordinate = 3;
        if (again[3].lo <= 0.0 && again[3].hi >= 0.0)
            status = gb_error_set(GB_ENUMERIC, "the tie is crossed at the period's end (sin wt in [%g, %g])", again[3].lo, again[3].hi);
        if (!status) status = failure(gb_proof_flow_section_map_of(&F, &fdef, again, &C2), &J, "flow from the tie");
        gb_proof_flow_field_clear(&F);
    }
    if (!status) {
        gb_proof_ball_of(x, C2.image[0], prec);
        arb_set_d(y, q_b);
        arb_add(x, x, y, prec);
        out->q = gb_proof_interval_of(x), out->P = C2.image[1];
        gb_proof_ball_of(x, C1.time, prec), gb_proof_ball_of(y, C2.time, prec);
        arb_add(x, x, y, prec);
        gb_proof_ball_of(y, sliver_time, prec);
        arb_add(x, x, y, prec);
        out->time = gb_proof_interval_of(x);
        out->steps = C1.steps + C2.steps, out->seconds = C1.seconds + C2.seconds;
    }
    if (!status && derivative) {
        /* D = D₂ E D₁: D₁ = ∂(x, P, c, s)/∂(q₀, P₀) at q = q_a (row x zero), E the sliver's J on (P, c, s), D₂ from q_b */
        arb_mat_t D1, E, D2, D;
        arb_mat_init(D1, 4, 2), arb_mat_init(E, 4, 4), arb_mat_init(D2, 4, 4), arb_mat_init(D, 4, 2);
        for (int a = 0; a < 4; a++) {
            for (int b = 0; b < 2; b++) gb_proof_ball_of(arb_mat_entry(D1, a, b), C1.jacobian[a][b], prec);
            for (int b = 0; b < 4; b++) {
                gb_proof_ball_of(arb_mat_entry(D2, a, b), C2.jacobian[a][b], prec);
                if (a > 0 && b > 0) arb_set(arb_mat_entry(E, a, b), arb_mat_entry(Js, a - 1, b - 1));
            }
        }
        arb_mat_mul(D, E, D1, prec);
        arb_mat_mul(D1, D2, D, prec);
        for (int a = 0; a < 2; a++)
            for (int b = 0; b < 2; b++) out->jacobian[a][b] = gb_proof_interval_of(arb_mat_entry(D1, a, b));
        arb_mat_clear(D1), arb_mat_clear(E), arb_mat_clear(D2), arb_mat_clear(D);
    }
    arb_mat_clear(Js);
    arb_clear(x), arb_clear(y), arb_clear(z);
    return status;
}
