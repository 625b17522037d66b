/* gb_proof_manifold — the unstable manifold of a saddle fixed point of a quadratic map f of the plane, proved on Arb's
 * balls as a parametrisation, and the crossings of two such manifolds (an unstable one of f and an unstable one of
 * f⁻¹, the stable one of f): the first pieces of a trellis (docs/proofs.md, item 12).
 *
 * The fixed point z* by Krawczyk's operator on f(z) − z; the eigenvalues of Df(z*) real, one λ with |λ| > 1 and the
 * other inside the unit circle (a saddle), proved. The parametrisation method (Cabré, Fontich and de la Llave 2003):
 * P(λ s) = f(P(s)), P(0) = z*, P'(0) = σ v (v a unit eigenvector of λ). Its Taylor coefficients solve
 * (λ^k I − Df(z*)) p_k = Σ_{j=1}^{k−1} Q(p_j, p_{k−j}) for k ≥ 2 (Q the quadratic part of f), up to the order N;
 * P = P_N + h on the disc |s| ≤ ρ, and h is proved small: h is the fixed point of
 * T h (s) = f(P_N(s/λ) + h(s/λ)) − P_N(s) = E(s) + Df(P_N(s/λ)) h(s/λ) + Q(h(s/λ), h(s/λ))
 * among functions analytic on the disc, vanishing to order N + 1 at 0, under the supremum norm (the largest
 * coordinate). By Schwarz's lemma |h(s/λ)| ≤ ‖h‖ κ with κ = |λ|^−(N+1), so T maps the ball of radius r into itself
 * and contracts there when ‖E‖ + M κ r + q κ² r² ≤ r and κ (M + 2 q κ r) < 1 (M bounds ‖Df(P_N(w))‖ for |w| ≤ ρ/|λ|,
 * q the quadratic form's norm, ‖E‖ by the coefficients of E of orders N + 1 … 2N, those up to N being 0 exactly).
 * Then |P(s) − P_N(s)| ≤ r (|s|/ρ)^(N+1), and for |s| ≤ ρ/2, |P'(s) − P_N'(s)| ≤ r ρ/(ρ − |s|)² (Cauchy). P(s) for
 * larger s is f^k(P(s/λ^k)), with k the least iterate that brings s/λ^k into [−ρ/2, ρ/2]: one parametrisation of the
 * whole unstable manifold, P(λ s) = f(P(s)) for every s. P is proved injective on [−ρ/2, ρ/2] (|P'(s) − p_1| < |p_1|
 * there), hence on the whole line when f is invertible, as Hénon's is (not checked here: f is the caller's).
 *
 * Crossings: the points P(s) = R(t) with s in an arc of P and t in an arc of R, R the unstable parametrisation of
 * f⁻¹ (the stable manifold of f). Each is proved by Krawczyk's operator on G(s, t) = P(s) − R(t) in a box of (s, t)
 * about a zero Newton found (K ⊂ int X: exactly one zero there, and every matrix of DG(X) = [P', −R'] regular: a
 * transverse crossing); the box is grown while the operator still proves it, and the rest of the two arcs is proved
 * to hold no other zero by bisection: two pieces whose enclosures of P and R do not meet, or whose Krawczyk image
 * misses them, hold none. Pieces of the arcs are enclosed in mean value form, P(s_c) + P'(S)(S − s_c), met with the
 * plain enclosure. */
#ifndef GB_PROOF_MANIFOLD_H
#define GB_PROOF_MANIFOLD_H

#include "gb_export.h"
#include "gb_proof.h"
#include "gb_proof_flow.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

enum { GB_PROOF_MANIFOLD_ORDER_MIN = 2, GB_PROOF_MANIFOLD_ORDER_MAX = 80 };

typedef struct gb_proof_manifold_def {
    const gb_proof_field *map; /* f, a quadratic map of the plane (dimension 2) */
    double fixed[2];           /* a guess of the saddle fixed point: Newton and Krawczyk start there */
    int order;                 /* N: 2 ... 80 */
    double scale;              /* σ = |P'(0)|: > 0, at most 1e3 */
    double radius;             /* ρ: the disc's radius, > 0, at most 1e3 */
    long precision;            /* Arb's bits */
} gb_proof_manifold_def;

/* Defaults: order 30, scale 1, radius 1, precision 128; the caller names the map and the guess. */
GB_API gb_proof_manifold_def gb_proof_manifold_def_default(void);

typedef struct gb_proof_manifold_info {
    gb_proof_interval fixed[2]; /* z* */
    gb_proof_interval lambda;   /* the unstable eigenvalue */
    gb_proof_interval other;    /* the other eigenvalue, |other| < 1 */
    double residual;            /* ‖E‖ on the disc, an upper bound */
    double lipschitz;           /* M κ, an upper bound (< 1) */
    double tail;                /* r: |P − P_N| ≤ r (|s|/ρ)^(N+1) on the disc */
    double seconds;
} gb_proof_manifold_info;

typedef struct gb_proof_manifold gb_proof_manifold;

/* GB_EDOM for a definition out of range (named with its range); GB_ENUMERIC when a step is not proved (the fixed
 * point, the saddle, the tail's contraction, the disc's injectivity: the message says which). */
GB_API int gb_proof_manifold_create(const gb_proof_manifold_def *def, gb_proof_manifold **out);
GB_API void gb_proof_manifold_free(gb_proof_manifold *m);
GB_API void gb_proof_manifold_info_of(const gb_proof_manifold *m, gb_proof_manifold_info *out);

/* P over the parameters s: out[0], out[1] enclose P(s) for every s of the interval, d[0], d[1] (NULL: not wanted) P'(s).
 * GB_EDOM for an interval that is not finite, wider than 1e6 or beyond ±1e12; GB_ENUMERIC when the enclosure is not finite. */
GB_API int gb_proof_manifold_enclose(const gb_proof_manifold *m, gb_proof_interval s, gb_proof_interval out[2],
                                     gb_proof_interval d[2]);

typedef struct gb_proof_manifold_crossing {
    gb_proof_interval s, t;     /* the parameters, each point one crossing's: exactly one zero of G in s × t */
    gb_proof_interval point[2]; /* the crossing */
} gb_proof_manifold_crossing;

typedef struct gb_proof_manifold_crossings_def {
    gb_proof_interval s, t; /* the arcs' parameters */
    double width;           /* pieces are halved until their enclosure is this wide: > 0, at most 1 */
    int depth;              /* bisections of a pair of pieces before it is left undecided: 1 ... 60 */
} gb_proof_manifold_crossings_def;

typedef struct gb_proof_manifold_crossings_result {
    int proved;   /* every crossing proved and no other: the list is complete */
    size_t count; /* crossings proved */
    gb_proof_manifold_crossing
        *crossings;            /* count of them, ordered by s (malloc'd: gb_proof_manifold_crossings_free) */
    size_t pieces_s, pieces_t; /* the arcs' pieces */
    size_t pairs;              /* pairs of pieces whose enclosures met */
    size_t undecided;          /* boxes left at the depth limit (proved is 0 when any) */
    char failure[200];         /* why not proved, or "" */
    double seconds;
} gb_proof_manifold_crossings_result;

/* The crossings of P (an unstable manifold of f) with R (one of f⁻¹, the same fixed point) over the arcs of def: the
 * zeros (s, t) of P(s) − R(t), the fixed point among them when both arcs hold 0. That R's map is f's inverse is the
 * caller's to ensure (gb_proof_manifold_henon gives Hénon's exactly); only the common fixed point is checked. GB_EDOM
 * for a definition out of range or two fixed points; GB_OK otherwise, out->proved saying whether the list is
 * complete. */
GB_API int gb_proof_manifold_crossings(const gb_proof_manifold *p, const gb_proof_manifold *r,
                                       const gb_proof_manifold_crossings_def *def,
                                       gb_proof_manifold_crossings_result *out);
GB_API void gb_proof_manifold_crossings_free(gb_proof_manifold_crossings_result *out);

/* Hénon's map H (x, y) ↦ (1 − a x² + y, b x) and its inverse (x, y) ↦ (y/b, x − 1 + (a/b²) y²), a = a_num/a_den,
 * b = b_num/b_den (b ≠ 0), as quadratic fields read as maps; GB_EDOM when a coefficient does not fit a long. */
GB_API int gb_proof_manifold_henon(long a_num, long a_den, long b_num, long b_den, gb_proof_field *map,
                                   gb_proof_field *inverse);

#ifdef __cplusplus
}
#endif

#endif
