/* gb_proof_body_cover — covering relations of parallelograms under the Gömböcs' period map, their disjointness on the
 * cylinder, and the entropy of a chain of them (gb_proof_body.h).
 *
 * N ⇒ M (Zgliczyński & Gidea 2004, Def. 6, for one direction across and one along; as gb_proof_cover.h states it): P
 * continuous on N, P(N) inside M's strip |η| < 1 (η along, in M's units), and N's two edges x = ±1 mapped beyond M's
 * two ends ξ = ∓1 (or ±1), one each. The image is met by the mean value form on pieces X × Y of N's coordinates:
 * for z = c_N + F_N D_N (x_m, y_m) the piece's middle and every x of the piece,
 *   P(x) ∈ P(z) + DP(hull) (x − z),  x − z ∈ F_N D_N (X − x_m, Y − y_m) + (the rounding of z, enclosed),
 * DP over the piece's box hull from the period map's C¹ step, P(z) from the period map of z's ball; in M's units
 * G = K (P(x) − c_M), K = D_M⁻¹ F_M⁻¹ (F_M's doubles taken exact). A piece whose strip is not proved is halved across
 * (x) until depth; an edge's piece whose side is not proved is halved along (y). P is continuous on N: the flow is,
 * and the enclosures prove every solution from N crosses its tie (if any) moving up. */
#include "gb_proof_body.h"

#include "gb_error.h"
#include "gb_proof_internal.h"

#include <arb_mat.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct link_context {
    const gb_proof_body_def *def;
    const gb_proof_body_forcing *forcing;
    const gb_proof_body_tie *tie;
    const gb_proof_body_hset *N, *M;
    int order;
    slong prec;
    arb_mat_t FD, K; /* F_N D_N and D_M⁻¹ F_M⁻¹ */
    arb_struct cM[2];
    gb_proof_body_link *out;
} link_context;

static int check_hset(const gb_proof_body_hset *h, const char *name)
{
    int finite = 1;
    for (int i = 0; i < 2; i++) {
        finite &= isfinite(h->centre[i]) && h->half[i] > 0.0 && isfinite(h->half[i]);
        for (int j = 0; j < 2; j++) finite &= isfinite(h->frame[i][j]);
    }
    const double det = h->frame[0][0] * h->frame[1][1] - h->frame[0][1] * h->frame[1][0];
    if (!finite || !(fabs(det) > 1e-12))
        return gb_error_set(GB_EDOM, "h-set %s: its centre, frame and half-widths must be finite, the half-widths > 0 and "
                                     "the frame invertible (allowed: |det| > 1e-12; det = %g)",
                            name, det);
    return GB_OK;
}

/* K = diag(1/a, 1/b) F⁻¹ of h; 0 when F is not proved invertible. */
static int frame_inverse(const gb_proof_body_hset *h, slong prec, arb_mat_t K)
{
    arb_mat_t F;
    arb_mat_init(F, 2, 2);
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) arb_set_d(arb_mat_entry(F, i, j), h->frame[i][j]);
    const int ok = arb_mat_inv(K, F, prec);
    arb_t x;
    arb_init(x);
    for (int i = 0; ok && i < 2; i++) {
        arb_set_d(x, h->half[i]);
        for (int j = 0; j < 2; j++) arb_div(arb_mat_entry(K, i, j), arb_mat_entry(K, i, j), x, prec);
    }
    arb_clear(x);
    arb_mat_clear(F);
    return ok;
}

/* The period map of a box, across the tie when there is one. */
static int period_map(const link_context *L, const gb_proof_interval box[2], int derivative, gb_proof_body_return *r)
{
    L->out->maps++;
    if (L->tie) return gb_proof_body_period_map_tie(L->def, L->forcing, box, L->tie, L->order, derivative, r);
    return gb_proof_body_period_map(L->def, L->forcing, box, 1, L->order, derivative, r);
}

/* G ⊇ M's coordinates of P over the piece X × Y of N (balls in N's coordinates, x_m, y_m their middles). */
static int piece_image(link_context *L, gb_proof_interval X, gb_proof_interval Y, arb_struct G[2])
{
    const slong prec = L->prec;
    arb_t xm, ym, dx, dy, t;
    arb_init(xm), arb_init(ym), arb_init(dx), arb_init(dy), arb_init(t);
    arb_struct Z[2], H[2], D[2], V[2];
    for (int i = 0; i < 2; i++) arb_init(Z + i), arb_init(H + i), arb_init(D + i), arb_init(V + i);
    const double x_m = 0.5 * X.lo + 0.5 * X.hi, y_m = 0.5 * Y.lo + 0.5 * Y.hi;
    arb_set_d(xm, x_m), arb_set_d(ym, y_m);
    gb_proof_ball_of(dx, X, prec), gb_proof_ball_of(dy, Y, prec);
    gb_proof_interval zbox[2], hull[2];
    for (int i = 0; i < 2; i++) {
        /* z and the piece's hull: c + FD (x, y) */
        arb_mul(Z + i, arb_mat_entry(L->FD, i, 0), xm, prec);
        arb_addmul(Z + i, arb_mat_entry(L->FD, i, 1), ym, prec);
        arb_set_d(t, L->N->centre[i]);
        arb_add(Z + i, Z + i, t, prec);
        arb_mul(H + i, arb_mat_entry(L->FD, i, 0), dx, prec);
        arb_addmul(H + i, arb_mat_entry(L->FD, i, 1), dy, prec);
        arb_add(H + i, H + i, t, prec);
        zbox[i] = gb_proof_interval_of(Z + i), hull[i] = gb_proof_interval_of(H + i);
    }
    gb_proof_body_return at_z, over;
    int status = period_map(L, zbox, 0, &at_z);
    if (!status) status = period_map(L, hull, 1, &over);
    if (!status) {
        /* G = K (P(z) − c_M) + (K DP F D) (X − x_m, Y − y_m) + K DP e, e = z's rounding (Z − Z): the matrix product
         * first, so that the piece stays a parallelogram */
        arb_mat_t J, Q;
        arb_mat_init(J, 2, 2), arb_mat_init(Q, 2, 2);
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) gb_proof_ball_of(arb_mat_entry(J, i, j), over.jacobian[i][j], prec);
        arb_sub(dx, dx, xm, prec), arb_sub(dy, dy, ym, prec);
        gb_proof_ball_of(V + 0, at_z.q, prec), gb_proof_ball_of(V + 1, at_z.P, prec);
        for (int i = 0; i < 2; i++) {
            arb_sub(V + i, V + i, L->cM + i, prec);
            arb_sub(D + i, Z + i, Z + i, prec);
        }
        for (int i = 0; i < 2; i++) /* V += DP e */
            for (int j = 0; j < 2; j++) arb_addmul(V + i, arb_mat_entry(J, i, j), D + j, prec);
        arb_mat_mul(Q, J, L->FD, prec);
        arb_mat_mul(Q, L->K, Q, prec);
        for (int i = 0; i < 2; i++) {
            arb_mul(G + i, arb_mat_entry(L->K, i, 0), V + 0, prec);
            arb_addmul(G + i, arb_mat_entry(L->K, i, 1), V + 1, prec);
            arb_addmul(G + i, arb_mat_entry(Q, i, 0), dx, prec);
            arb_addmul(G + i, arb_mat_entry(Q, i, 1), dy, prec);
        }
        arb_mat_clear(J), arb_mat_clear(Q);
    }
    L->out->pieces++;
    arb_clear(xm), arb_clear(ym), arb_clear(dx), arb_clear(dy), arb_clear(t);
    for (int i = 0; i < 2; i++) arb_clear(Z + i), arb_clear(H + i), arb_clear(D + i), arb_clear(V + i);
    return status;
}

/* Notes the first piece that failed. */
static void note_failure(link_context *L, const char *what, gb_proof_interval X, gb_proof_interval Y, const arb_struct *G,
                         int status)
{
    if (L->out->failure[0]) return;
    if (status)
        snprintf(L->out->failure, sizeof L->out->failure, "%s: piece x in [%.6g, %.6g], y in [%.6g, %.6g]: %s", what,
                 X.lo, X.hi, Y.lo, Y.hi, gb_error_message());
    else {
        const gb_proof_interval g0 = gb_proof_interval_of(G), g1 = gb_proof_interval_of(G + 1);
        snprintf(L->out->failure, sizeof L->out->failure,
                 "%s: piece x in [%.6g, %.6g], y in [%.6g, %.6g] maps to xi in [%.6g, %.6g], eta in [%.6g, %.6g]", what,
                 X.lo, X.hi, Y.lo, Y.hi, g0.lo, g0.hi, g1.lo, g1.hi);
    }
    gb_error_clear();
}

/* The strip over X × Y: |η| < 1 proved, halving across to depth; *eta the largest |η| bound. GB_OK when proved. */
static int strip(link_context *L, gb_proof_interval X, gb_proof_interval Y, int depth, double *eta)
{
    arb_struct G[2];
    arb_init(G), arb_init(G + 1);
    int status = piece_image(L, X, Y, G), proved = 0;
    if (!status) {
        const gb_proof_interval e = gb_proof_interval_of(G + 1);
        proved = e.lo > -1.0 && e.hi < 1.0;
        if (proved) *eta = fmax(*eta, fmax(-e.lo, e.hi));
    }
    if (!proved && depth > 0 && gb_proof_halvable(X)) {
        gb_error_clear();
        arb_clear(G), arb_clear(G + 1);
        const int low = strip(L, gb_proof_half(X, 0), Y, depth - 1, eta);
        return low ? low : strip(L, gb_proof_half(X, 1), Y, depth - 1, eta);
    }
    if (!proved) note_failure(L, "strip", X, Y, G, status);
    arb_clear(G), arb_clear(G + 1);
    return proved ? GB_OK : GB_ENUMERIC;
}

/* The edge x = e over Y: its image wholly on one side beyond M (side −1: ξ < −1, +1: ξ > 1), halving along to depth;
 * *side 0 before the first piece; *beyond the least distance past ±1. GB_OK when proved. */
static int edge(link_context *L, double e, gb_proof_interval Y, int depth, int *side, double *beyond)
{
    arb_struct G[2];
    arb_init(G), arb_init(G + 1);
    int status = piece_image(L, (gb_proof_interval){e, e}, Y, G), proved = 0;
    if (!status) {
        const gb_proof_interval x = gb_proof_interval_of(G);
        const int here = x.hi < -1.0 ? -1 : x.lo > 1.0 ? 1 : 0;
        proved = here != 0 && (*side == 0 || *side == here);
        if (proved) *side = here, *beyond = fmin(*beyond, here < 0 ? -1.0 - x.hi : x.lo - 1.0);
    }
    if (!proved && depth > 0 && gb_proof_halvable(Y)) {
        gb_error_clear();
        arb_clear(G), arb_clear(G + 1);
        const int low = edge(L, e, gb_proof_half(Y, 0), depth - 1, side, beyond);
        return low ? low : edge(L, e, gb_proof_half(Y, 1), depth - 1, side, beyond);
    }
    if (!proved) note_failure(L, e < 0 ? "edge x = -1" : "edge x = +1", (gb_proof_interval){e, e}, Y, G, status);
    arb_clear(G), arb_clear(G + 1);
    return proved ? GB_OK : GB_ENUMERIC;
}

int gb_proof_body_cover_link(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing,
                             const gb_proof_body_tie *tie, const gb_proof_body_hset *N, const gb_proof_body_hset *M,
                             int turns, int pieces, int depth, int order, gb_proof_body_link *out)
{
    memset(out, 0, sizeof *out);
    int status = check_hset(N, "N");
    if (!status) status = check_hset(M, "M");
    if (!status && !(pieces >= 1 && pieces <= 4096))
        status = gb_error_set(GB_EDOM, "pieces = %d is out of range (allowed: 1 to 4096)", pieces);
    if (!status && !(turns >= -1 && turns <= 1))
        status = gb_error_set(GB_EDOM, "turns = %d is out of range (allowed: -1, 0, 1)", turns);
    if (!status && !(depth >= 0 && depth <= 20))
        status = gb_error_set(GB_EDOM, "depth = %d is out of range (allowed: 0 to 20)", depth);
    if (!status) status = gb_proof_check_precision(def->precision);
    if (status) return status;
    const double start = gb_proof_cpu_seconds();
    link_context L = {.def = def, .forcing = forcing, .tie = tie, .N = N, .M = M, .order = order,
                      .prec = def->precision, .out = out};
    arb_mat_init(L.FD, 2, 2), arb_mat_init(L.K, 2, 2);
    arb_init(L.cM), arb_init(L.cM + 1);
    arb_const_pi(L.cM, L.prec); /* M's centre, moved by turns 2π in q */
    arb_mul_si(L.cM, L.cM, 2 * turns, L.prec);
    arb_zero(L.cM + 1);
    for (int i = 0; i < 2; i++) {
        arb_t c;
        arb_init(c);
        arb_set_d(c, M->centre[i]);
        arb_add(L.cM + i, L.cM + i, c, L.prec);
        arb_clear(c);
        for (int j = 0; j < 2; j++) {
            arb_set_d(arb_mat_entry(L.FD, i, j), N->frame[i][j]);
            gb_proof_mul_d(arb_mat_entry(L.FD, i, j), arb_mat_entry(L.FD, i, j), N->half[j], L.prec);
        }
    }
    if (!frame_inverse(M, L.prec, L.K)) status = gb_error_set(GB_EDOM, "h-set M: its frame is not proved invertible");
    double eta = 0.0, beyond[2] = {INFINITY, INFINITY};
    int strip_ok = !status, side[2] = {0, 0}, edges_ok = !status;
    const gb_proof_interval whole = {-1.0, 1.0};
    for (int p = 0; p < pieces && strip_ok; p++) {
        const gb_proof_interval X = {-1.0 + 2.0 * p / pieces, p + 1 == pieces ? 1.0 : -1.0 + 2.0 * (p + 1) / pieces};
        strip_ok = strip(&L, X, whole, depth, &eta) == GB_OK;
    }
    for (int e = 0; e < 2 && edges_ok && strip_ok; e++)
        edges_ok = edge(&L, e ? 1.0 : -1.0, whole, depth, side + e, beyond + e) == GB_OK;
    if (edges_ok && strip_ok && side[0] == side[1]) {
        edges_ok = 0;
        if (!out->failure[0])
            snprintf(out->failure, sizeof out->failure, "both edges map to the same side of M (%s)",
                     side[0] < 0 ? "xi < -1" : "xi > 1");
    }
    out->strip = strip_ok, out->edges = strip_ok && edges_ok;
    out->covers = out->strip && out->edges;
    out->orientation = out->covers ? -side[0] : 0;
    out->strip_margin = strip_ok ? 1.0 - eta : NAN;
    out->edge_margin = out->edges ? fmin(beyond[0], beyond[1]) : NAN;
    out->seconds = gb_proof_cpu_seconds() - start;
    arb_mat_clear(L.FD), arb_mat_clear(L.K);
    arb_clear(L.cM), arb_clear(L.cM + 1);
    return status;
}

/* The corners of B (moved by 2π turns in q) in A's coordinates: 1 when all lie beyond one side of A's square. */
static int beyond_a_side(const gb_proof_body_hset *A, const gb_proof_body_hset *B, int turns, slong prec)
{
    arb_mat_t K;
    arb_mat_init(K, 2, 2);
    int separated = 0;
    if (frame_inverse(A, prec, K)) {
        arb_t v[2], w, t;
        arb_init(v[0]), arb_init(v[1]), arb_init(w), arb_init(t);
        int below[2] = {1, 1}, above[2] = {1, 1};
        for (int corner = 0; corner < 4; corner++) {
            const double sx = corner & 1 ? 1.0 : -1.0, sy = corner & 2 ? 1.0 : -1.0;
            for (int i = 0; i < 2; i++) { /* B's corner minus A's centre */
                arb_set_d(v[i], B->centre[i]);
                arb_set_d(t, B->frame[i][0]);
                gb_proof_mul_d(t, t, sx * B->half[0], prec);
                arb_add(v[i], v[i], t, prec);
                arb_set_d(t, B->frame[i][1]);
                gb_proof_mul_d(t, t, sy * B->half[1], prec);
                arb_add(v[i], v[i], t, prec);
                if (i == 0) {
                    arb_const_pi(t, prec);
                    arb_mul_si(t, t, 2 * turns, prec);
                    arb_add(v[i], v[i], t, prec);
                }
                arb_set_d(t, A->centre[i]);
                arb_sub(v[i], v[i], t, prec);
            }
            for (int i = 0; i < 2; i++) {
                arb_mul(w, arb_mat_entry(K, i, 0), v[0], prec);
                arb_addmul(w, arb_mat_entry(K, i, 1), v[1], prec);
                const gb_proof_interval c = gb_proof_interval_of(w);
                below[i] &= c.hi < -1.0, above[i] &= c.lo > 1.0;
            }
        }
        separated = below[0] || below[1] || above[0] || above[1];
        arb_clear(v[0]), arb_clear(v[1]), arb_clear(w), arb_clear(t);
    }
    arb_mat_clear(K);
    return separated;
}

int gb_proof_body_hsets_disjoint(const gb_proof_body_hset *A, const gb_proof_body_hset *B, long precision)
{
    if (check_hset(A, "A") || check_hset(B, "B") || gb_proof_check_precision(precision)) {
        gb_error_clear();
        return 0;
    }
    for (int k = -1; k <= 1; k++)
        if (!beyond_a_side(A, B, k, precision) && !beyond_a_side(B, A, -k, precision)) return 0;
    return 1;
}

int gb_proof_body_chain_entropy(int length, double *log_rho)
{
    *log_rho = 0.0;
    if (!(length >= 2 && length <= 10000))
        return gb_error_set(GB_EDOM, "the cycle's length = %d is out of range (allowed: 2 to 10000)", length);
    const slong prec = 128;
    arb_t x, f, t;
    arb_init(x), arb_init(f), arb_init(t);
    /* bisection on doubles in (1, 2]: f(2) = 2^{L−1} − 1 > 0, f(1) = −1 */
    double lo = 1.0, hi = 2.0;
    for (int k = 0; k < 60; k++) {
        const double mid = 0.5 * lo + 0.5 * hi;
        arb_set_d(x, mid);
        arb_pow_ui(f, x, (ulong)length - 1, prec);
        arb_sub_ui(t, x, 1, prec);
        arb_mul(f, f, t, prec);
        arb_sub_ui(f, f, 1, prec);
        if (arb_is_negative(f))
            lo = mid;
        else
            hi = mid;
    }
    /* ln ρ > ln lo, rounded down */
    arb_set_d(x, lo);
    arb_log(x, x, prec);
    *log_rho = gb_proof_interval_of(x).lo;
    arb_clear(x), arb_clear(f), arb_clear(t);
    return GB_OK;
}
