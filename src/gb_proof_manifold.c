/* gb_proof_manifold — an unstable manifold of a quadratic map of the plane by the parametrisation method, its tail
 * proved by a contraction on Arb's balls (gb_proof_manifold.h states the argument). Why our own: Arb has balls and
 * no invariant manifolds; CAPD, which has them (C++), is not packaged in Debian. */
#include "gb_proof_manifold.h"

#include "gb_error.h"
#include "gb_proof_cover.h"
#include "gb_proof_flow_internal.h"
#include "gb_proof_internal.h"
#include "gb_proof_manifold_internal.h"

#include <arb.h>
#include <arb_mat.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct gb_proof_manifold {
    field_balls F;
    slong prec;
    int order;
    arb_t lambda, rho, tail;
    arb_ptr p; /* 2 (order + 1): p_k = (p[2k], p[2k + 1]) */
    gb_proof_manifold_info info;
};

gb_proof_manifold_def gb_proof_manifold_def_default(void)
{
    gb_proof_manifold_def d;
    memset(&d, 0, sizeof d);
    d.order = 30, d.scale = 1.0, d.radius = 1.0, d.precision = GB_PROOF_PRECISION_DEFAULT;
    return d;
}

static int check_def(const gb_proof_manifold_def *def)
{
    if (!def->map || def->map->dimension != 2)
        return gb_error_set(GB_EDOM, "manifold: the map must be a quadratic map of the plane (dimension 2)");
    if (!isfinite(def->fixed[0]) || !isfinite(def->fixed[1]))
        return gb_error_set(GB_EDOM, "manifold: the fixed point's guess must be finite");
    if (def->order < GB_PROOF_MANIFOLD_ORDER_MIN || def->order > GB_PROOF_MANIFOLD_ORDER_MAX)
        return gb_error_set(GB_EDOM, "manifold: order = %d is out of range (allowed: %d to %d)", def->order,
                            GB_PROOF_MANIFOLD_ORDER_MIN, GB_PROOF_MANIFOLD_ORDER_MAX);
    if (!(def->scale > 0.0 && def->scale <= 1e3))
        return gb_error_set(GB_EDOM, "manifold: scale = %g is out of range (allowed: above 0, at most 1e3)",
                            def->scale);
    if (!(def->radius > 0.0 && def->radius <= 1e3))
        return gb_error_set(GB_EDOM, "manifold: radius = %g is out of range (allowed: above 0, at most 1e3)",
                            def->radius);
    return gb_proof_check_precision(def->precision);
}

/* out_i += Σ_{j ≤ l} Q_ijl u_j w_l: the quadratic part's share of one pair of coefficients in a Cauchy product. */
static void quad_product(const field_balls *F, arb_srcptr u, arb_srcptr w, arb_ptr out, arb_t t)
{
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            for (int l = j; l < 2; l++)
                if (F->has_Q[i][j][l]) {
                    arb_mul(t, u + j, w + l, F->prec);
                    arb_addmul(out + i, &F->Q[i][j][l], t, F->prec);
                }
}

/* An upper bound of the ball x as a double (rounded up). */
static double upper(const arb_t x) { return gb_proof_interval_of(x).hi; }

/* The inverse of the middle of a ball matrix by Arb's approximate solver at 64 bits (radii ignored, the result's
 * entries exact: any C serves Krawczyk's operator): 0 when that middle is singular. */
static int approx_inverse(const arb_mat_t A, arb_mat_t C) { return arb_mat_approx_inv(C, A, 64); }

int gb_proof_krawczyk2(arb_srcptr X, arb_srcptr m, arb_srcptr g, const arb_mat_t A, arb_ptr k, slong prec)
{
    arb_mat_t C, R;
    arb_mat_init(C, 2, 2), arb_mat_init(R, 2, 2);
    arb_t d;
    arb_init(d);
    int verdict = 0;
    if (approx_inverse(A, C)) {
        arb_mat_mul(R, C, A, prec);
        arb_mat_neg(R, R);
        for (int i = 0; i < 2; i++) arb_add_ui(arb_mat_entry(R, i, i), arb_mat_entry(R, i, i), 1, prec);
        for (int i = 0; i < 2; i++) {
            arb_set(k + i, m + i);
            for (int j = 0; j < 2; j++) {
                arb_submul(k + i, arb_mat_entry(C, i, j), g + j, prec);
                arb_sub(d, X + j, m + j, prec);
                arb_addmul(k + i, arb_mat_entry(R, i, j), d, prec);
            }
        }
        if (arb_contains_interior(X, k) && arb_contains_interior(X + 1, k + 1))
            verdict = 1;
        else if (!arb_overlaps(X, k) || !arb_overlaps(X + 1, k + 1))
            verdict = -1;
    }
    arb_clear(d);
    arb_mat_clear(C), arb_mat_clear(R);
    return verdict;
}

/* ---- the fixed point, the saddle, the coefficients, the tail ------------------------------------------------- */

static int fixed_point(const field_balls *F, const double guess[2], arb_ptr z)
{
    const slong prec = F->prec;
    arb_ptr x = _arb_vec_init(2), X = _arb_vec_init(2), g = _arb_vec_init(2), k = _arb_vec_init(2);
    arb_mat_t J, C;
    arb_mat_init(J, 2, 2), arb_mat_init(C, 2, 2);
    double at[2] = {guess[0], guess[1]};
    for (int it = 0; it < 60; it++) { /* Newton on doubles through the balls' middles */
        arb_set_d(x, at[0]), arb_set_d(x + 1, at[1]);
        gb_proof_flow_field_eval(F, x, g);
        _arb_vec_sub(g, g, x, 2, prec);
        gb_proof_flow_field_derivative(F, x, J);
        for (int i = 0; i < 2; i++) arb_sub_ui(arb_mat_entry(J, i, i), arb_mat_entry(J, i, i), 1, prec);
        if (!approx_inverse(J, C)) break;
        for (int i = 0; i < 2; i++)
            at[i] -=
                arf_get_d(arb_midref(arb_mat_entry(C, i, 0)), ARF_RND_NEAR) * arf_get_d(arb_midref(g), ARF_RND_NEAR) +
                arf_get_d(arb_midref(arb_mat_entry(C, i, 1)), ARF_RND_NEAR) *
                    arf_get_d(arb_midref(g + 1), ARF_RND_NEAR);
    }
    /* then at Arb's precision, so that the enclosure is as narrow as it allows: every point of the manifolds is
     * computed from it, far along them through many iterates of the map */
    arb_mat_t G, D;
    arb_mat_init(G, 2, 1), arb_mat_init(D, 2, 1);
    for (int i = 0; i < 2; i++) arb_set_d(x + i, isfinite(at[i]) ? at[i] : 0.0);
    for (int it = 0; it < 8 && isfinite(at[0]) && isfinite(at[1]); it++) {
        gb_proof_flow_field_eval(F, x, g);
        _arb_vec_sub(g, g, x, 2, prec);
        gb_proof_flow_field_derivative(F, x, J);
        for (int i = 0; i < 2; i++) arb_sub_ui(arb_mat_entry(J, i, i), arb_mat_entry(J, i, i), 1, prec);
        for (int i = 0; i < 2; i++) arb_set(arb_mat_entry(G, i, 0), g + i);
        if (!arb_mat_approx_solve(D, J, G, prec)) break;
        for (int i = 0; i < 2; i++)
            arf_sub(arb_midref(x + i), arb_midref(x + i), arb_midref(arb_mat_entry(D, i, 0)), prec, ARF_RND_NEAR);
    }
    arb_mat_clear(G), arb_mat_clear(D);
    int proved = 0;
    for (double delta = ldexp(1.0, 24 - (int)prec); delta < 1e-3 && !proved && isfinite(at[0]) && isfinite(at[1]);
         delta *= 256.0) {
        for (int i = 0; i < 2; i++) {
            arb_set(X + i, x + i);
            mag_set_d(arb_radref(X + i), delta * (1.0 + fabs(at[i])));
        }
        gb_proof_flow_field_eval(F, x, g);
        _arb_vec_sub(g, g, x, 2, prec);
        gb_proof_flow_field_derivative(F, X, J);
        for (int i = 0; i < 2; i++) arb_sub_ui(arb_mat_entry(J, i, i), arb_mat_entry(J, i, i), 1, prec);
        proved = gb_proof_krawczyk2(X, x, g, J, k, prec) == 1;
    }
    if (proved) _arb_vec_set(z, k, 2);
    _arb_vec_clear(x, 2), _arb_vec_clear(X, 2), _arb_vec_clear(g, 2), _arb_vec_clear(k, 2);
    arb_mat_clear(J), arb_mat_clear(C);
    return proved
               ? GB_OK
               : gb_error_set(GB_ENUMERIC, "manifold: no fixed point proved near (%.17g, %.17g)", guess[0], guess[1]);
}

/* λ (|λ| > 1) and the other eigenvalue (|μ| < 1) of J, both real, and the unit eigenvector v of λ. */
static int saddle(const arb_mat_t J, arb_t lambda, arb_t mu, arb_ptr v, slong prec)
{
    arb_t tr, det, disc, t;
    arb_init(tr), arb_init(det), arb_init(disc), arb_init(t);
    arb_add(tr, arb_mat_entry(J, 0, 0), arb_mat_entry(J, 1, 1), prec);
    arb_mul(det, arb_mat_entry(J, 0, 0), arb_mat_entry(J, 1, 1), prec);
    arb_submul(det, arb_mat_entry(J, 0, 1), arb_mat_entry(J, 1, 0), prec);
    arb_sqr(disc, tr, prec);
    arb_submul_ui(disc, det, 4, prec);
    int status = GB_OK;
    if (!arb_is_positive(disc)) {
        status =
            gb_error_set(GB_ENUMERIC, "manifold: the eigenvalues at the fixed point are not proved real and distinct");
    } else {
        arb_sqrt(disc, disc, prec);
        const int plus = arf_sgn(arb_midref(tr)) >= 0; /* the eigenvalue of larger modulus takes the trace's sign */
        (plus ? arb_add : arb_sub)(lambda, tr, disc, prec);
        arb_mul_2exp_si(lambda, lambda, -1);
        (plus ? arb_sub : arb_add)(mu, tr, disc, prec);
        arb_mul_2exp_si(mu, mu, -1);
        arb_abs(t, lambda);
        arb_sub_ui(t, t, 1, prec);
        const int expanding = arb_is_positive(t);
        arb_abs(t, mu);
        arb_sub_ui(t, t, 1, prec);
        if (!expanding || !arb_is_negative(t))
            status = gb_error_set(GB_ENUMERIC, "manifold: the fixed point is not proved a saddle (|λ| > 1 > |μ|)");
    }
    if (!status) { /* v ∝ (J01, λ − J00) or (λ − J11, J10), the longer */
        arb_ptr a = _arb_vec_init(2), b = _arb_vec_init(2);
        arb_set(a, arb_mat_entry(J, 0, 1));
        arb_sub(a + 1, lambda, arb_mat_entry(J, 0, 0), prec);
        arb_sub(b, lambda, arb_mat_entry(J, 1, 1), prec);
        arb_set(b + 1, arb_mat_entry(J, 1, 0));
        const double na = hypot(arf_get_d(arb_midref(a), ARF_RND_NEAR), arf_get_d(arb_midref(a + 1), ARF_RND_NEAR)),
                     nb = hypot(arf_get_d(arb_midref(b), ARF_RND_NEAR), arf_get_d(arb_midref(b + 1), ARF_RND_NEAR));
        arb_srcptr w = na >= nb ? a : b;
        arb_sqr(t, w, prec);
        arb_addmul(t, w + 1, w + 1, prec);
        arb_sqrt(t, t, prec);
        if (!arb_is_positive(t))
            status = gb_error_set(GB_ENUMERIC, "manifold: the unstable eigenvector is not proved");
        else
            _arb_vec_scalar_div(v, w, 2, t, prec);
        _arb_vec_clear(a, 2), _arb_vec_clear(b, 2);
    }
    arb_clear(tr), arb_clear(det), arb_clear(disc), arb_clear(t);
    return status;
}

/* p_k for k = 2 … N: (λ^k I − J) p_k = Σ_{j=1}^{k−1} Q(p_j, p_{k−j}). */
static int coefficients(gb_proof_manifold *m, const arb_mat_t J)
{
    const slong prec = m->prec;
    arb_t lk, det, t, a00, a11;
    arb_init(lk), arb_init(det), arb_init(t), arb_init(a00), arb_init(a11);
    arb_ptr rhs = _arb_vec_init(2);
    int status = GB_OK;
    arb_set(lk, m->lambda);
    for (int k = 2; k <= m->order && !status; k++) {
        arb_mul(lk, lk, m->lambda, prec);
        _arb_vec_zero(rhs, 2);
        for (int j = 1; j < k; j++) quad_product(&m->F, m->p + 2 * j, m->p + 2 * (k - j), rhs, t);
        arb_sub(a00, lk, arb_mat_entry(J, 0, 0), prec);
        arb_sub(a11, lk, arb_mat_entry(J, 1, 1), prec);
        arb_mul(det, a00, a11, prec);
        arb_submul(det, arb_mat_entry(J, 0, 1), arb_mat_entry(J, 1, 0), prec);
        if (arb_contains_zero(det)) {
            status = gb_error_set(GB_ENUMERIC, "manifold: λ^%d is not proved apart from the spectrum (a resonance)", k);
            break;
        }
        arb_ptr pk = m->p + 2 * k; /* Cramer: A = [[a00, −J01], [−J10, a11]] */
        arb_mul(pk, rhs, a11, prec);
        arb_addmul(pk, arb_mat_entry(J, 0, 1), rhs + 1, prec);
        arb_mul(pk + 1, a00, rhs + 1, prec);
        arb_addmul(pk + 1, arb_mat_entry(J, 1, 0), rhs, prec);
        arb_div(pk, pk, det, prec), arb_div(pk + 1, pk + 1, det, prec);
    }
    _arb_vec_clear(rhs, 2);
    arb_clear(lk), arb_clear(det), arb_clear(t), arb_clear(a00), arb_clear(a11);
    return status;
}

/* The tail: ‖E‖, M κ, and r with ‖E‖ + M κ r + q κ² r² ≤ r and κ (M + 2 q κ r) < 1. */
static int tail(gb_proof_manifold *m)
{
    const slong prec = m->prec;
    const int N = m->order;
    arb_ptr q = _arb_vec_init(2 * (N + 1)), e = _arb_vec_init(2), norm = _arb_vec_init(2), Z = _arb_vec_init(2);
    arb_t t, lk, rk, kappa, M, Qn, r, lhs, row;
    arb_init(t), arb_init(lk), arb_init(rk), arb_init(kappa), arb_init(M), arb_init(Qn), arb_init(r), arb_init(lhs);
    arb_init(row);
    arb_one(lk);
    for (int k = 0; k <= N; k++) { /* q_k = p_k λ^−k, Z_j = Σ |q_kj| ρ^k */
        _arb_vec_scalar_div(q + 2 * k, m->p + 2 * k, 2, lk, prec);
        arb_pow_ui(rk, m->rho, (ulong)k, prec);
        for (int j = 0; j < 2; j++) {
            arb_abs(t, q + 2 * k + j);
            arb_addmul(Z + j, t, rk, prec);
        }
        arb_mul(lk, lk, m->lambda, prec);
    }
    for (int k = N + 1; k <= 2 * N; k++) { /* E_k = Σ_{j=k−N}^{N} Q(q_j, q_{k−j}); ‖E‖ ≤ max_i Σ |E_ki| ρ^k */
        _arb_vec_zero(e, 2);
        for (int j = k - N; j <= N; j++) quad_product(&m->F, q + 2 * j, q + 2 * (k - j), e, t);
        arb_pow_ui(rk, m->rho, (ulong)k, prec);
        for (int i = 0; i < 2; i++) {
            arb_abs(t, e + i);
            arb_addmul(norm + i, t, rk, prec);
        }
    }
    arb_max(norm, norm, norm + 1, prec);
    arb_abs(t, m->lambda); /* κ = |λ|^−(N+1) */
    arb_pow_ui(kappa, t, (ulong)(N + 1), prec);
    arb_inv(kappa, kappa, prec);
    arb_zero(M), arb_zero(Qn);
    for (int i = 0; i < 2; i++) {
        arb_zero(row);
        for (int c = 0; c < 2; c++) { /* |Df_ic| ≤ |L_ic| + Σ_{l ≥ c} |Q_icl| Z_l + Σ_{j ≤ c} |Q_ijc| Z_j */
            arb_abs(t, &m->F.L[i][c]);
            arb_add(row, row, t, prec);
            for (int l = c; l < 2; l++) {
                arb_abs(t, &m->F.Q[i][c][l]);
                arb_addmul(row, t, Z + l, prec);
            }
            for (int j = 0; j <= c; j++) {
                arb_abs(t, &m->F.Q[i][j][c]);
                arb_addmul(row, t, Z + j, prec);
            }
        }
        arb_max(M, M, row, prec);
        arb_zero(row);
        for (int j = 0; j < 2; j++)
            for (int l = j; l < 2; l++) {
                arb_abs(t, &m->F.Q[i][j][l]);
                arb_add(row, row, t, prec);
            }
        arb_max(Qn, Qn, row, prec);
    }
    arb_mul(M, M, kappa, prec); /* from here M is M κ */
    m->info.residual = upper(norm);
    m->info.lipschitz = upper(M);
    int status = GB_OK;
    if (!(m->info.lipschitz < 1.0)) {
        status = gb_error_set(GB_ENUMERIC,
                              "manifold: the tail's map is not proved a contraction (M κ ≤ %.3g; raise the "
                              "order or lower the radius)",
                              m->info.lipschitz);
    } else {
        const double r0 = fmax(2.0 * m->info.residual / (1.0 - m->info.lipschitz), 1e-300);
        arb_set_d(r, r0);
        arb_mul(t, Qn, kappa, prec); /* q κ */
        arb_mul(lhs, t, kappa, prec);
        arb_mul(lhs, lhs, r, prec);
        arb_add(lhs, lhs, M, prec); /* M κ + q κ² r */
        arb_mul(lhs, lhs, r, prec);
        arb_add(lhs, lhs, norm, prec);
        arb_sub(lhs, lhs, r, prec); /* ‖E‖ + M κ r + q κ² r² − r ≤ 0 */
        arb_mul(row, t, r, prec);
        arb_mul_2exp_si(row, row, 1);
        arb_mul(row, row, kappa, prec);
        arb_add(row, row, M, prec);
        arb_sub_ui(row, row, 1, prec); /* κ (M + 2 q κ r) − 1 < 0 */
        if (!arb_is_nonpositive(lhs) || !arb_is_negative(row))
            status = gb_error_set(GB_ENUMERIC, "manifold: the tail's ball of radius %.3g is not proved invariant", r0);
        arb_set(m->tail, r);
        m->info.tail = r0;
    }
    _arb_vec_clear(q, 2 * (N + 1)), _arb_vec_clear(e, 2), _arb_vec_clear(norm, 2), _arb_vec_clear(Z, 2);
    arb_clear(t), arb_clear(lk), arb_clear(rk), arb_clear(kappa), arb_clear(M), arb_clear(Qn), arb_clear(r);
    arb_clear(lhs), arb_clear(row);
    return status;
}

/* P and P' at the ball w with |w| ≤ ρ/2 (checked by the caller): P_N and P_N' by Horner, with the tail's bounds
 * r (|w|/ρ)^(N+1) and r ρ/(ρ − |w|)² added to every coordinate. */
static void local_eval(const gb_proof_manifold *m, const arb_t w, arb_ptr z, arb_ptr d)
{
    const slong prec = m->prec;
    const int N = m->order;
    arb_t t, bound;
    arb_init(t), arb_init(bound);
    for (int i = 0; i < 2; i++) {
        arb_set(z + i, m->p + 2 * N + i);
        for (int k = N - 1; k >= 0; k--) {
            arb_mul(z + i, z + i, w, prec);
            arb_add(z + i, z + i, m->p + 2 * k + i, prec);
        }
        if (d) {
            arb_mul_si(d + i, m->p + 2 * N + i, N, prec);
            for (int k = N - 1; k >= 1; k--) {
                arb_mul(d + i, d + i, w, prec);
                arb_mul_si(t, m->p + 2 * k + i, k, prec);
                arb_add(d + i, d + i, t, prec);
            }
        }
    }
    arf_t u; /* |w| ≤ u, a point: a ball for |w| would widen (ρ − |w|)² until it held 0 */
    arf_init(u);
    arb_get_abs_ubound_arf(u, w, prec);
    arb_set_arf(t, u);
    arf_clear(u);
    arb_div(bound, t, m->rho, prec);
    arb_pow_ui(bound, bound, (ulong)(N + 1), prec);
    arb_mul(bound, bound, m->tail, prec);
    for (int i = 0; i < 2; i++) arb_add_error(z + i, bound);
    if (d) {
        arb_sub(bound, m->rho, t, prec);
        arb_sqr(bound, bound, prec);
        arb_div(bound, m->rho, bound, prec);
        arb_mul(bound, bound, m->tail, prec);
        for (int i = 0; i < 2; i++) arb_add_error(d + i, bound);
    }
    arb_clear(t), arb_clear(bound);
}

/* P(s) and P'(s) (d NULL: not wanted) for the ball s: f^k(P(s/λ^k)), k the least with |s/λ^k| ≤ ρ/2. */
static int global_eval(const gb_proof_manifold *m, const arb_t s, arb_ptr z, arb_ptr d)
{
    const slong prec = m->prec;
    arb_t w, lk, half, t;
    arb_init(w), arb_init(lk), arb_init(half), arb_init(t);
    arb_mul_2exp_si(half, m->rho, -1);
    arb_set(w, s), arb_one(lk);
    int k = 0;
    for (;; k++) {
        arb_abs(t, w);
        arb_sub(t, t, half, prec);
        if (arb_is_nonpositive(t) || k > 4000) break;
        arb_mul(lk, lk, m->lambda, prec);
        arb_div(w, s, lk, prec);
    }
    local_eval(m, w, z, d);
    arb_mat_t J;
    arb_mat_init(J, 2, 2);
    arb_ptr next = _arb_vec_init(2);
    if (d) _arb_vec_scalar_div(d, d, 2, lk, prec);
    for (int i = 0; i < k; i++) {
        if (d) {
            gb_proof_flow_field_derivative(&m->F, z, J);
            arb_mul(next, arb_mat_entry(J, 0, 0), d, prec);
            arb_addmul(next, arb_mat_entry(J, 0, 1), d + 1, prec);
            arb_mul(next + 1, arb_mat_entry(J, 1, 0), d, prec);
            arb_addmul(next + 1, arb_mat_entry(J, 1, 1), d + 1, prec);
            _arb_vec_set(d, next, 2);
        }
        gb_proof_flow_field_eval(&m->F, z, next);
        _arb_vec_set(z, next, 2);
    }
    const int finite = arb_is_finite(z) && arb_is_finite(z + 1) && (!d || (arb_is_finite(d) && arb_is_finite(d + 1)));
    _arb_vec_clear(next, 2);
    arb_mat_clear(J);
    arb_clear(w), arb_clear(lk), arb_clear(half), arb_clear(t);
    return finite && k <= 4000 ? GB_OK : gb_error_set(GB_ENUMERIC, "manifold: the enclosure of P is not finite");
}

/* |P'(s) − p_1| < |p_1| on |s| ≤ ρ/2 (√2 times the largest coordinate's bound against σ): P injective there. */
static int injective(const gb_proof_manifold *m, double scale)
{
    const slong prec = m->prec;
    arb_t w, t;
    arb_init(w), arb_init(t);
    arb_mul_2exp_si(w, m->rho, -1); /* ρ/2 */
    double bound = 0.0;
    for (int i = 0; i < 2; i++) { /* Σ_{k ≥ 2} k |p_ki| (ρ/2)^(k−1), plus the tail's 4 r / ρ */
        arb_zero(t);
        for (int k = m->order; k >= 2; k--) {
            arb_t c;
            arb_init(c);
            arb_abs(c, m->p + 2 * k + i);
            arb_mul_si(c, c, k, prec);
            arb_mul(t, t, w, prec);
            arb_add(t, t, c, prec);
            arb_clear(c);
        }
        arb_mul(t, t, w, prec);
        arb_t r4;
        arb_init(r4);
        arb_mul_2exp_si(r4, m->tail, 2);
        arb_div(r4, r4, m->rho, prec);
        arb_add(t, t, r4, prec);
        arb_clear(r4);
        bound = fmax(bound, upper(t));
    }
    arb_clear(w), arb_clear(t);
    return sqrt(2.0) * bound * (1.0 + 1e-12) < scale
               ? GB_OK
               : gb_error_set(GB_ENUMERIC, "manifold: P is not proved injective on |s| ≤ ρ/2 (lower the radius)");
}

int gb_proof_manifold_create(const gb_proof_manifold_def *def, gb_proof_manifold **out)
{
    *out = NULL;
    int status = check_def(def);
    if (status) return status;
    const double start = gb_proof_cpu_seconds();
    gb_proof_manifold *m = calloc(1, sizeof *m);
    if (!m) return gb_error_set(GB_ENOMEM, "manifold: out of memory");
    m->prec = def->precision, m->order = def->order;
    gb_proof_flow_field_init(&m->F, def->map, GB_PROOF_ORDER_MIN, m->prec);
    arb_init(m->lambda), arb_init(m->rho), arb_init(m->tail);
    arb_set_d(m->rho, def->radius);
    m->p = _arb_vec_init(2 * (def->order + 1));
    arb_t mu;
    arb_init(mu);
    arb_mat_t J;
    arb_mat_init(J, 2, 2);
    status = fixed_point(&m->F, def->fixed, m->p);
    if (!status) {
        gb_proof_flow_field_derivative(&m->F, m->p, J);
        status = saddle(J, m->lambda, mu, m->p + 2, m->prec);
    }
    if (!status) {
        arb_t sigma;
        arb_init(sigma);
        arb_set_d(sigma, def->scale);
        _arb_vec_scalar_mul(m->p + 2, m->p + 2, 2, sigma, m->prec);
        arb_clear(sigma);
        status = coefficients(m, J);
    }
    if (!status) status = tail(m);
    if (!status) status = injective(m, def->scale);
    for (int i = 0; i < 2; i++) m->info.fixed[i] = gb_proof_interval_of(m->p + i);
    m->info.lambda = gb_proof_interval_of(m->lambda);
    m->info.other = gb_proof_interval_of(mu);
    arb_clear(mu);
    arb_mat_clear(J);
    m->info.seconds = gb_proof_cpu_seconds() - start;
    if (status) {
        gb_proof_manifold_free(m);
        return status;
    }
    *out = m;
    return GB_OK;
}

void gb_proof_manifold_free(gb_proof_manifold *m)
{
    if (!m) return;
    gb_proof_flow_field_clear(&m->F);
    arb_clear(m->lambda), arb_clear(m->rho), arb_clear(m->tail);
    _arb_vec_clear(m->p, 2 * (m->order + 1));
    free(m);
}

void gb_proof_manifold_info_of(const gb_proof_manifold *m, gb_proof_manifold_info *out) { *out = m->info; }

long gb_proof_manifold_precision(const gb_proof_manifold *m) { return m->prec; }

const struct field_balls *gb_proof_manifold_field(const gb_proof_manifold *m) { return &m->F; }

int gb_proof_manifold_point(const gb_proof_manifold *m, const arb_t S, arb_ptr z, arb_ptr d)
{
    return global_eval(m, S, z, d);
}

int gb_proof_manifold_ball(const gb_proof_manifold *m, const arb_t S, arb_ptr z, arb_ptr d)
{
    const slong prec = m->prec;
    arb_ptr zc = _arb_vec_init(2);
    arb_t c, dS;
    arb_init(c), arb_init(dS);
    int status = global_eval(m, S, z, d);
    if (!status) {
        arf_set(arb_midref(c), arb_midref(S));
        mag_zero(arb_radref(c));
        status = global_eval(m, c, zc, NULL);
    }
    if (!status) {
        arb_sub(dS, S, c, prec);
        for (int i = 0; i < 2; i++) {
            arb_addmul(zc + i, d + i, dS, prec);
            arb_t both;
            arb_init(both);
            if (arb_intersection(both, z + i, zc + i, prec)) arb_set(z + i, both);
            arb_clear(both);
        }
    }
    _arb_vec_clear(zc, 2);
    arb_clear(c), arb_clear(dS);
    return status;
}

int gb_proof_manifold_enclose(const gb_proof_manifold *m, gb_proof_interval s, gb_proof_interval out[2],
                              gb_proof_interval d[2])
{
    if (!(isfinite(s.lo) && isfinite(s.hi) && s.lo <= s.hi && s.hi - s.lo <= 1e6 && fabs(s.lo) <= 1e12 &&
          fabs(s.hi) <= 1e12))
        return gb_error_set(
            GB_EDOM, "manifold: the parameters [%g, %g] must be finite, ordered, within ±1e12 (at most 1e6 wide)", s.lo,
            s.hi);
    arb_t S;
    arb_init(S);
    gb_proof_ball_of(S, s, m->prec);
    arb_ptr z = _arb_vec_init(2), dz = _arb_vec_init(2);
    const int status = gb_proof_manifold_ball(m, S, z, dz);
    if (!status)
        for (int i = 0; i < 2; i++) {
            out[i] = gb_proof_interval_of(z + i);
            if (d) d[i] = gb_proof_interval_of(dz + i);
        }
    _arb_vec_clear(z, 2), _arb_vec_clear(dz, 2);
    arb_clear(S);
    return status;
}

int gb_proof_manifold_henon(long a_num, long a_den, long b_num, long b_den, gb_proof_field *map,
                            gb_proof_field *inverse)
{
    if (a_den == 0 || b_den == 0 || b_num == 0)
        return gb_error_set(GB_EDOM, "Hénon: a = %ld/%ld, b = %ld/%ld: the denominators and b must not be 0", a_num,
                            a_den, b_num, b_den);
    long q_num, q_den;
    if (__builtin_mul_overflow(a_num, b_den, &q_num) || __builtin_mul_overflow(q_num, b_den, &q_num) ||
        __builtin_mul_overflow(a_den, b_num, &q_den) || __builtin_mul_overflow(q_den, b_num, &q_den))
        return gb_error_set(GB_EDOM, "Hénon: a/b² does not fit a long's numerator and denominator");
    *map = gb_proof_cover_henon(a_num, a_den, b_num, b_den);
    memset(inverse, 0, sizeof *inverse);
    inverse->dimension = 2;
    inverse->L[0][1] = (gb_proof_rational){b_den, b_num};
    inverse->c[1] = (gb_proof_rational){-1, 1};
    inverse->L[1][0] = (gb_proof_rational){1, 1};
    inverse->Q[1][1][1] = (gb_proof_rational){q_num, q_den};
    return GB_OK;
}
