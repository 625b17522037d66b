/* gb_proof_trellis — the entropy bound of a trellis of a saddle's stable and unstable manifolds (gb_proof_trellis.h
 * states the argument; docs/proofs.md, item 13, proves it). */
#include "gb_proof_trellis.h"

#include "gb_error.h"
#include "gb_proof_flow_internal.h"
#include "gb_proof_internal.h"
#include "gb_proof_manifold_internal.h"
#include "gb_proof_trellis_graph_internal.h"

#include <arb.h>
#include <arb_mat.h>
#include <flint/fmpz.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The four rays at a crossing: along U (increasing s, decreasing s) and along W (increasing t, decreasing t). A ray's
 * opposite is ray + 2 (mod 4); rays along U are even. */
enum { U_PLUS = 0, W_PLUS = 1, U_MINUS = 2, W_MINUS = 3 };
/* The candidates for Q are compared by their walks of at most this many strips; longer walks count from the best. */
enum { PROBE = 2000 };

typedef struct vertex {
    gb_proof_interval s, t;
    int piece; /* W's piece */
    int sign;  /* of det [P'(s), R'(t)]: +1 when W's increasing ray lies counterclockwise of U's, within a half turn */
    int on_u;  /* 1: a crossing of U itself (|s| < S) */
} vertex;

typedef struct key {
    gb_proof_interval at; /* s along U, or t along a piece */
    int vertex;
} key;

typedef struct trellis {
    const gb_proof_manifold *p, *r;
    const gb_proof_trellis_def *def;
    slong prec;
    double *origin; /* per piece of W: its parameters are origin + rel (the crossings' t relative too) */
    gb_proof_interval *rel;
    vertex *v;
    size_t n, cap;
    int *nb0, *nb1; /* 4 per vertex: the next crossing along each ray in U ∪ W (U's crossings only) and in f(U) ∪ W */
    key *u_keys;    /* U's crossings by s */
    size_t nu;
    key **w_keys; /* per piece, U's crossings on it by t */
    size_t *nw;
    long *rect_ids; /* the rectangles' faces, each named by its least (vertex, ray) */
    size_t rects;
    int failed;
    char failure[200];
    double worker_seconds; /* CPU of the threads the crossings and the walks ran on (0 on the caller's) */
} trellis;

static void fail(trellis *T, const char *message)
{
    if (!T->failed) snprintf(T->failure, sizeof T->failure, "%s", message);
    T->failed = 1;
}

static int by_at(const void *a, const void *b)
{
    const key *x = a, *y = b;
    return (x->at.lo > y->at.lo) - (x->at.lo < y->at.lo);
}

static int by_long(const void *a, const void *b)
{
    const long x = *(const long *)a, y = *(const long *)b;
    return (x > y) - (x < y);
}

/* The sign of the ball x: +1, −1, or 0 when it holds 0. */
static int sign_of(const arb_t x) { return arb_is_positive(x) ? 1 : arb_is_negative(x) ? -1 : 0; }

/* The sign of det [P'(s), R'(origin + t)] over the crossing's enclosure (0: not proved). */
static int orientation(const trellis *T, gb_proof_interval s, double origin, gb_proof_interval t)
{
    arb_t S, R, det;
    arb_ptr z = _arb_vec_init(8);
    arb_init(S), arb_init(R), arb_init(det);
    gb_proof_ball_of(S, s, T->prec), gb_proof_ball_of(R, t, T->prec);
    arb_t o;
    arb_init(o);
    arb_set_d(o, origin);
    arb_add(R, R, o, T->prec);
    arb_clear(o);
    int sign = 0;
    if (!gb_proof_manifold_point(T->p, S, z, z + 2) && !gb_proof_manifold_point(T->r, R, z + 4, z + 6)) {
        arb_mul(det, z + 2, z + 7, T->prec);
        arb_submul(det, z + 3, z + 6, T->prec);
        sign = sign_of(det);
    }
    gb_error_clear();
    arb_clear(S), arb_clear(R), arb_clear(det);
    _arb_vec_clear(z, 8);
    return sign;
}

/* sign(det Df(P(x))): 0 when not proved. */
static int jacobian_sign(const trellis *T, const arb_t x)
{
    arb_ptr z = _arb_vec_init(2);
    arb_mat_t J;
    arb_t det;
    arb_mat_init(J, 2, 2), arb_init(det);
    int sign = 0;
    if (!gb_proof_manifold_point(T->p, x, z, NULL)) {
        gb_proof_flow_field_derivative(gb_proof_manifold_field(T->p), z, J);
        arb_mat_det(det, J, T->prec);
        sign = sign_of(det);
    }
    gb_error_clear();
    arb_mat_clear(J), arb_clear(det);
    _arb_vec_clear(z, 2);
    return sign;
}

/* The crossings of f(U) with each piece of W, proved; their orientations; which lie on U. */
static int collect(trellis *T, const arb_t lambda_s)
{
    const gb_proof_trellis_def *def = T->def;
    const gb_proof_interval image = gb_proof_interval_of(lambda_s); /* |λ| S */
    const double reach = image.hi * (1.0 + 0x1p-20);
    gb_proof_manifold_crossings_def *cd = malloc(def->stable_count * sizeof *cd);
    gb_proof_manifold_crossings_result *all = calloc(def->stable_count, sizeof *all);
    if (!cd || !all) {
        free(cd), free(all);
        return gb_error_set(GB_ENOMEM, "trellis: out of memory");
    }
    for (size_t k = 0; k < def->stable_count; k++)
        cd[k] = (gb_proof_manifold_crossings_def){{-reach, reach}, T->rel[k], def->width, def->depth};
    /* f(U)'s pieces made once; each piece of W about its own origin */
    int status = gb_proof_manifold_crossings_arcs(T->p, T->r, cd, T->origin, def->stable_count, def->threads, all,
                                                  &T->worker_seconds);
    free(cd);
    for (size_t k = 0; k < def->stable_count && !status; k++) {
        gb_proof_manifold_crossings_result cr = all[k];
        all[k].crossings = NULL;
        if (!cr.proved && !T->failed) {
            snprintf(T->failure, sizeof T->failure, "W's piece %zu: %.140s", k, cr.failure);
            T->failed = 1;
        }
        for (size_t i = 0; i < cr.count && !T->failed; i++) {
            const gb_proof_interval s = cr.crossings[i].s, t = cr.crossings[i].t;
            /* |s| over the enclosure: [least, most] */
            const double most = fmax(fabs(s.lo), fabs(s.hi)),
                         least = s.lo > 0.0 || s.hi < 0.0 ? fmin(fabs(s.lo), fabs(s.hi)) : 0.0;
            if (least > image.hi) continue; /* beyond f(U) */
            if (most >= image.lo) {
                fail(T, "a crossing lies on f(U)'s end (move S)");
                break;
            }
            if (least <= def->u && most >= def->u) {
                fail(T, "a crossing lies on U's end (move S)");
                break;
            }
            const int sign = orientation(T, s, T->origin[k], t);
            if (!sign) {
                fail(T, "a crossing's orientation is not proved");
                break;
            }
            if (T->n == T->cap) {
                const size_t cap = T->cap ? 2 * T->cap : 256;
                vertex *grown = realloc(T->v, cap * sizeof *grown);
                if (!grown) {
                    status = gb_error_set(GB_ENOMEM, "trellis: out of memory");
                    break;
                }
                T->v = grown, T->cap = cap;
            }
            T->v[T->n++] = (vertex){s, t, (int)k, sign, most < def->u};
        }
        gb_proof_manifold_crossings_free(&cr);
    }
    for (size_t k = 0; k < def->stable_count; k++) gb_proof_manifold_crossings_free(&all[k]);
    free(all);
    return status;
}

static double middle(gb_proof_interval x) { return 0.5 * (x.lo + x.hi); }

/* The keys of the crossings `keep` selects, along U (piece −1) or along a piece, ordered; 0 when two are not apart. */
static int ordered(trellis *T, int on_u_only, int piece, key **out, size_t *count)
{
    key *k = malloc((T->n ? T->n : 1) * sizeof *k);
    if (!k) return -1;
    size_t m = 0;
    for (size_t i = 0; i < T->n; i++) {
        if (on_u_only && !T->v[i].on_u) continue;
        if (piece >= 0 && T->v[i].piece != piece) continue;
        k[m++] = (key){piece >= 0 ? T->v[i].t : T->v[i].s, (int)i};
    }
    if (m) qsort(k, m, sizeof *k, by_at);
    for (size_t i = 1; i < m; i++)
        if (!(k[i - 1].at.hi < k[i].at.lo)) {
            if (!T->failed) {
                const vertex *a = &T->v[k[i - 1].vertex], *b = &T->v[k[i].vertex];
                const gb_proof_interval oa = piece >= 0 ? a->s : a->t, ob = piece >= 0 ? b->s : b->t;
                snprintf(T->failure, sizeof T->failure,
                         "two crossings are not proved apart along %s %d: %s = %.17g ± %.1g and %.17g ± %.1g (%s = "
                         "%.12g and %.12g)",
                         piece >= 0 ? "W's piece" : "U (-1)", piece, piece >= 0 ? "t" : "s", middle(k[i - 1].at),
                         0.5 * (k[i - 1].at.hi - k[i - 1].at.lo), middle(k[i].at), 0.5 * (k[i].at.hi - k[i].at.lo),
                         piece >= 0 ? "s" : "t", middle(oa), middle(ob));
                T->failed = 1;
            }
            free(k);
            return 0;
        }
    *out = k, *count = m;
    return 1;
}

/* The neighbours along each ray in the arrangement of U's crossings (on_u_only) or of all; 0 when not ordered. */
static int link_rays(trellis *T, int on_u_only, int *nb)
{
    for (size_t i = 0; i < 4 * T->n; i++) nb[i] = -1;
    key *k;
    size_t m;
    int status = ordered(T, on_u_only, -1, &k, &m);
    if (status != 1) return status;
    for (size_t i = 1; i < m; i++)
        nb[4 * k[i - 1].vertex + U_PLUS] = k[i].vertex, nb[4 * k[i].vertex + U_MINUS] = k[i - 1].vertex;
    free(k);
    for (size_t c = 0; c < T->def->stable_count; c++) {
        status = ordered(T, on_u_only, (int)c, &k, &m);
        if (status != 1) return status;
        for (size_t i = 1; i < m; i++)
            nb[4 * k[i - 1].vertex + W_PLUS] = k[i].vertex, nb[4 * k[i].vertex + W_MINUS] = k[i - 1].vertex;
        free(k);
    }
    return 1;
}

/* The face on the left of the directed edge leaving vertex v along ray: 1 and its four (vertex, ray) in face when it
 * closes after four edges alternating between U and W; 0 otherwise (more sides, or an arc's loose end). At each
 * crossing the rays turn counterclockwise U+, W+, U−, W− (sign +1) or U+, W−, U−, W+ (sign −1); the next edge is the
 * first ray clockwise from the one arrived along. */
static int trace(const trellis *T, const int *nb, int v, int ray, long face[4])
{
    static const int turn[2][4] = {{U_PLUS, W_MINUS, U_MINUS, W_PLUS}, {U_PLUS, W_PLUS, U_MINUS, W_MINUS}};
    int at = v, r = ray;
    for (int k = 0; k < 4; k++) {
        face[k] = 4L * at + r;
        const int w = nb[4 * at + r];
        if (w < 0) return 0;
        const int *order = turn[T->v[w].sign > 0], back = (r + 2) % 4;
        int pos = 0;
        while (order[pos] != back) pos++;
        const int next = order[(pos + 3) % 4];
        if (nb[4 * w + next] < 0 || (next % 2) == (r % 2)) return 0;
        at = w, r = next;
        if (k < 3 && at == v && r == ray) return 0; /* a face of two sides */
    }
    return at == v && r == ray;
}

static long face_id(const long face[4])
{
    long id = face[0];
    for (int k = 1; k < 4; k++)
        if (face[k] < id) id = face[k];
    return id;
}

/* The rectangle (index) on the left of the directed edge leaving v along ray in U ∪ W; −1 when that face is none. */
static long rectangle_at(const trellis *T, int v, int ray)
{
    long face[4];
    if (!trace(T, T->nb0, v, ray, face)) return -1;
    const long id = face_id(face);
    const long *hit = bsearch(&id, T->rect_ids, T->rects, sizeof id, by_long);
    return hit ? hit - T->rect_ids : -1;
}

/* The index k with keys[k − 1] < x < keys[k], or −1. */
static long locate(const key *keys, size_t n, gb_proof_interval x)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        const size_t mid = (lo + hi) / 2;
        if (keys[mid].at.lo > x.hi)
            hi = mid;
        else
            lo = mid + 1;
    }
    return lo >= 1 && lo < n && keys[lo - 1].at.hi < x.lo ? (long)lo : -1;
}

/* A double strictly between two ordered intervals (NAN when there is none). */
static double between(gb_proof_interval a, gb_proof_interval b)
{
    if (b.hi < a.lo) {
        const gb_proof_interval c = a;
        a = b, b = c;
    }
    const double m = 0.5 * (a.hi + b.lo);
    return m > a.hi && m < b.lo ? m : NAN;
}

/* The rectangle whose side on W holds the edge of f(U) ∪ W leaving v along ray (a W ray), with the face on its left;
 * the side's index in *side. −1 when none. */
static long target_of(const trellis *T, int v, int ray, long *side)
{
    const int w = T->nb1[4 * v + ray], c = T->v[v].piece;
    const double m = between(T->v[v].t, T->v[w].t);
    if (isnan(m)) return -1;
    const long k = locate(T->w_keys[c], T->nw[c], (gb_proof_interval){m, m});
    if (k < 0) return -1;
    *side = (long)c << 32 | k;
    return ray == W_PLUS ? rectangle_at(T, T->w_keys[c][k - 1].vertex, W_PLUS)
                         : rectangle_at(T, T->w_keys[c][k].vertex, W_MINUS);
}

/* The rectangle Q with the edge of f(U) ∪ W leaving v along ray (a U ray) on f(Q)'s side, the face on its left; the
 * side's index in *side. −1 when none or not proved. */
static long source_of(const trellis *T, int v, int ray, const arb_t lambda, long *side)
{
    const int w = T->nb1[4 * v + ray];
    const double m = between(T->v[v].s, T->v[w].s);
    if (isnan(m)) return -1;
    arb_t x;
    arb_init(x);
    arb_set_d(x, m);
    arb_div(x, x, lambda, T->prec); /* f⁻¹ of P(m) is P(m/λ) */
    const gb_proof_interval at = gb_proof_interval_of(x);
    long rect = -1;
    const int jac = jacobian_sign(T, x);
    if (at.lo > -T->def->u && at.hi < T->def->u && jac) {
        const long k = locate(T->u_keys, T->nu, at);
        /* f carries the left of U at m/λ to the left of f(U) at m when sign(det Df) sign(λ) is +1 */
        const int left = (ray == U_PLUS ? 1 : -1) * jac * sign_of(lambda);
        if (k >= 0) {
            *side = k;
            rect = left > 0 ? rectangle_at(T, T->u_keys[k - 1].vertex, U_PLUS)
                            : rectangle_at(T, T->u_keys[k].vertex, U_MINUS);
        }
    }
    arb_clear(x);
    return rect;
}

/* The strips: the four-sided faces of f(U) ∪ W proved to lie in a rectangle Q_j across both its sides on W, bounded on
 * f(U) by the images of both sides on U of one rectangle Q_i. */
static int strips_of(const trellis *T, const arb_t lambda, trellis_edge **out, size_t *count, size_t *left)
{
    unsigned char *seen = calloc(4 * T->n + 1, 1);
    size_t cap = 256, m = 0;
    trellis_edge *list = malloc(cap * sizeof *list);
    if (!seen || !list) {
        free(seen), free(list);
        return gb_error_set(GB_ENOMEM, "trellis: out of memory");
    }
    *left = 0;
    for (size_t v = 0; v < T->n; v++)
        for (int ray = 0; ray < 4; ray++) {
            long face[4];
            if (seen[4 * v + ray] || T->nb1[4 * v + ray] < 0) continue;
            seen[4 * v + ray] = 1;
            if (!trace(T, T->nb1, (int)v, ray, face)) continue;
            for (int k = 0; k < 4; k++) seen[face[k]] = 1;
            long to[2], from[2], wside[2], uside[2];
            int nw = 0, nu = 0;
            for (int k = 0; k < 4; k++) {
                const int at = (int)(face[k] / 4), r = (int)(face[k] % 4);
                if (r % 2)
                    to[nw] = target_of(T, at, r, &wside[nw]), nw++;
                else
                    from[nu] = source_of(T, at, r, lambda, &uside[nu]), nu++;
            }
            if (to[0] < 0 || to[0] != to[1] || wside[0] == wside[1]) continue;
            if (from[0] < 0 || from[0] != from[1] || uside[0] == uside[1]) {
                (*left)++;
                continue;
            }
            if (m == cap) {
                trellis_edge *grown = realloc(list, 2 * cap * sizeof *grown);
                if (!grown) {
                    free(seen), free(list);
                    return gb_error_set(GB_ENOMEM, "trellis: out of memory");
                }
                list = grown, cap *= 2;
            }
            list[m++] = (trellis_edge){from[0], to[0]};
        }
    free(seen);
    *out = list, *count = m;
    return GB_OK;
}

static int check_def(const gb_proof_trellis_def *def)
{
    if (!(def->u > 0.0 && def->u <= 1e5))
        return gb_error_set(GB_EDOM, "trellis: u = %g is out of range (allowed: above 0, at most 1e5)", def->u);
    if (!def->stable || def->stable_count < 1 || def->stable_count > GB_PROOF_TRELLIS_PIECES_MAX)
        return gb_error_set(GB_EDOM, "trellis: %zu stable pieces (allowed: 1 to %d)",
                            def->stable ? def->stable_count : 0, GB_PROOF_TRELLIS_PIECES_MAX);
    for (size_t k = 0; k < def->stable_count; k++) {
        const gb_proof_interval t = def->stable[k];
        if (!(isfinite(t.lo) && isfinite(t.hi) && t.lo < t.hi && fabs(t.lo) <= 1e12 && fabs(t.hi) <= 1e12))
            return gb_error_set(GB_EDOM, "trellis: stable piece %zu = [%g, %g] must be finite, ordered, within ±1e12",
                                k, t.lo, t.hi);
        if (k && !(def->stable[k - 1].hi < t.lo))
            return gb_error_set(GB_EDOM, "trellis: stable pieces %zu and %zu overlap or are out of order", k - 1, k);
    }
    if (def->power < 1 || def->power > GB_PROOF_TRELLIS_POWER_MAX)
        return gb_error_set(GB_EDOM, "trellis: power = %d is out of range (allowed: 1 to %d)", def->power,
                            GB_PROOF_TRELLIS_POWER_MAX);
    if (def->threads < 0 || def->threads > GB_PROOF_TRELLIS_THREADS_MAX)
        return gb_error_set(GB_EDOM, "trellis: threads = %d is out of range (allowed: 0 to %d)", def->threads,
                            GB_PROOF_TRELLIS_THREADS_MAX);
    return GB_OK;
}

/* W's pieces as the proof reads them: origin (the piece's middle) + rel, rel = [lo − origin, hi − origin] in doubles; W is
 * that union exactly, whatever the rounding of rel. */
static int pieces_of(trellis *T)
{
    const gb_proof_trellis_def *def = T->def;
    T->origin = malloc(def->stable_count * sizeof *T->origin), T->rel = malloc(def->stable_count * sizeof *T->rel);
    if (!T->origin || !T->rel) return gb_error_set(GB_ENOMEM, "trellis: out of memory");
    for (size_t k = 0; k < def->stable_count; k++) {
        const gb_proof_interval t = def->stable[k];
        T->origin[k] = 0.5 * t.lo + 0.5 * t.hi;
        T->rel[k] = (gb_proof_interval){t.lo - T->origin[k], t.hi - T->origin[k]};
    }
    return GB_OK;
}

/* The ball origin + x, exact. */
static void at(arb_t out, double origin, double x, slong prec)
{
    arb_t o;
    arb_init(o);
    arb_set_d(out, x), arb_set_d(o, origin);
    arb_add(out, out, o, prec);
    arb_clear(o);
}

/* f(W) ⊂ W: each piece divided by R's eigenvalue (f(R(t)) = R(t/λ_R)) lies in a piece, compared on Arb. */
static int invariant(const trellis *T, const arb_t lambda_r)
{
    const gb_proof_trellis_def *def = T->def;
    arb_t a, b, lo, hi;
    arb_init(a), arb_init(b), arb_init(lo), arb_init(hi);
    int status = GB_OK;
    for (size_t k = 0; k < def->stable_count && !status; k++) {
        at(a, T->origin[k], T->rel[k].lo, T->prec), at(b, T->origin[k], T->rel[k].hi, T->prec);
        arb_div(a, a, lambda_r, T->prec), arb_div(b, b, lambda_r, T->prec);
        int held = 0;
        for (size_t j = 0; j < def->stable_count && !held; j++) {
            at(lo, T->origin[j], T->rel[j].lo, T->prec), at(hi, T->origin[j], T->rel[j].hi, T->prec);
            held = arb_ge(a, lo) && arb_ge(b, lo) && arb_le(a, hi) && arb_le(b, hi);
        }
        if (!held) {
            const gb_proof_interval ia = gb_proof_interval_of(a), ib = gb_proof_interval_of(b);
            status =
                gb_error_set(GB_EDOM, "trellis: f(W) ⊂ W is not proved: piece %zu's image [%g, %g] lies in no piece", k,
                             fmin(ia.lo, ib.lo), fmax(ia.hi, ib.hi));
        }
    }
    arb_clear(a), arb_clear(b), arb_clear(lo), arb_clear(hi);
    return status;
}

static void release(trellis *T)
{
    free(T->v), free(T->nb0), free(T->nb1), free(T->u_keys), free(T->rect_ids), free(T->origin), free(T->rel);
    if (T->w_keys)
        for (size_t c = 0; c < T->def->stable_count; c++) free(T->w_keys[c]);
    free(T->w_keys), free(T->nw);
}

/* The arrangements, the rectangles and the keys to find them. */
static int build(trellis *T)
{
    T->nb0 = malloc((4 * T->n + 1) * sizeof *T->nb0), T->nb1 = malloc((4 * T->n + 1) * sizeof *T->nb1);
    T->w_keys = calloc(T->def->stable_count, sizeof *T->w_keys), T->nw = calloc(T->def->stable_count, sizeof *T->nw);
    T->rect_ids = malloc((4 * T->n + 1) * sizeof *T->rect_ids);
    if (!T->nb0 || !T->nb1 || !T->w_keys || !T->nw || !T->rect_ids)
        return gb_error_set(GB_ENOMEM, "trellis: out of memory");
    int ok = link_rays(T, 1, T->nb0);
    if (ok == 1) ok = link_rays(T, 0, T->nb1);
    if (ok == 1) ok = ordered(T, 1, -1, &T->u_keys, &T->nu);
    for (size_t c = 0; c < T->def->stable_count && ok == 1; c++) ok = ordered(T, 1, (int)c, &T->w_keys[c], &T->nw[c]);
    if (ok < 0) return gb_error_set(GB_ENOMEM, "trellis: out of memory");
    if (!ok) {
        fail(T, "two crossings are not proved apart along an arc"); /* kept when ordered() said which */
        return GB_OK;
    }
    for (size_t v = 0; v < T->n; v++)
        for (int ray = 0; ray < 4 && T->v[v].on_u; ray++) {
            long face[4];
            if (T->nb0[4 * v + ray] >= 0 && trace(T, T->nb0, (int)v, ray, face))
                T->rect_ids[T->rects++] = face_id(face);
        }
    if (T->rects) qsort(T->rect_ids, T->rects, sizeof *T->rect_ids, by_long);
    size_t m = 0;
    for (size_t i = 0; i < T->rects; i++)
        if (!m || T->rect_ids[m - 1] != T->rect_ids[i]) T->rect_ids[m++] = T->rect_ids[i];
    T->rects = m;
    return GB_OK;
}

/* The walks from each candidate: tasks of gb_proof_for_each. */
typedef struct walks_job {
    const trellis_edge *e;
    size_t m, nodes;
    const size_t *cand;
    size_t nc, per; /* the candidates, and how many a task takes */
    long n;
    uint64_t mantissa[TRELLIS_CANDIDATES];
    long exponent[TRELLIS_CANDIDATES];
} walks_job;

static int walk_task(void *ctx, size_t k) /* the candidates k·per … (k + 1)·per − 1, side by side */
{
    walks_job *J = ctx;
    const size_t first = k * J->per, count = first + J->per <= J->nc ? J->per : J->nc - first;
    return trellis_walks_below_many(J->e, J->m, J->nodes, J->cand + first, count, J->n, 63, J->mantissa + first,
                                    J->exponent + first);
}

int gb_proof_trellis_entropy(const gb_proof_manifold *p, const gb_proof_manifold *r, const gb_proof_trellis_def *def,
                             gb_proof_trellis_result *out)
{
    memset(out, 0, sizeof *out);
    int status = check_def(def);
    if (status) return status;
    const double start = gb_proof_cpu_seconds();
    trellis T = {.p = p, .r = r, .def = def, .prec = gb_proof_manifold_precision(p)};
    gb_proof_manifold_info ip, ir;
    gb_proof_manifold_info_of(p, &ip), gb_proof_manifold_info_of(r, &ir);
    arb_t lambda, lambda_r, reach;
    arb_init(lambda), arb_init(lambda_r), arb_init(reach);
    gb_proof_ball_of(lambda, ip.lambda, T.prec), gb_proof_ball_of(lambda_r, ir.lambda, T.prec);
    status = pieces_of(&T);
    if (!status) status = invariant(&T, lambda_r);
    arb_abs(reach, lambda);
    gb_proof_mul_d(reach, reach, def->u, T.prec);
    if (!status) status = collect(&T, reach);
    if (!status && !T.failed) status = build(&T);
    trellis_edge *e = NULL;
    size_t m = 0;
    if (!status && !T.failed) status = strips_of(&T, lambda, &e, &m, &out->strips_left);
    if (!status && !T.failed) {
        size_t cand[TRELLIS_CANDIDATES], nc = 0;
        out->log_rho = trellis_perron(e, m, T.rects, cand, &nc);
        /* the candidates shared out evenly among the threads, a task each */
        const size_t threads = def->threads > 1 ? (size_t)def->threads : 1, tasks = threads < nc ? threads : nc,
                     per = tasks ? (nc + tasks - 1) / tasks : 1;
        /* every candidate's walks of at most PROBE strips, side by side; beyond, the best one's alone */
        const long probe = def->power < PROBE ? def->power : PROBE;
        walks_job job = {e, m, T.rects, cand, nc, per, probe, {0}, {0}};
        double seconds = 0.0;
        status = gb_proof_for_each(nc ? (nc + per - 1) / per : 0, def->threads, walk_task, &job, &seconds);
        T.worker_seconds += seconds;
        uint64_t best = 0;
        long shift = 0;
        for (size_t k = 0; k < nc && !status; k++) { /* the first of the largest, as the candidates are ordered */
            const uint64_t w = job.mantissa[k];
            const double log_w = w ? log((double)w) + (double)job.exponent[k] * log(2.0) : -INFINITY;
            if (w && (!best || log_w > out->log_walks))
                best = w, shift = job.exponent[k], out->rectangle = cand[k], out->log_walks = log_w;
        }
        if (!status && best && def->power > probe) {
            status = trellis_walks_below(e, m, T.rects, out->rectangle, def->power, 63, &best, &shift);
            out->log_walks = best ? log((double)best) + (double)shift * log(2.0) : 0.0; /* 0: no walk returns */
        }
        fmpz_t half; /* ⌈N/2⌉ for the walks' lower bound N = best · 2^shift */
        fmpz_init(half);
        fmpz_set_ui(half, best);
        if (shift)
            fmpz_mul_2exp(half, half, (ulong)(shift - 1));
        else
            fmpz_cdiv_q_2exp(half, half, 1);
        if (!status && fmpz_cmp_ui(half, 1) > 0) { /* h ≥ (1/n) log ⌈N/2⌉, rounded down */
            arb_t h;
            arb_init(h);
            arb_set_fmpz(h, half);
            arb_log(h, h, T.prec);
            arb_div_si(h, h, def->power, T.prec);
            out->bound = gb_proof_interval_of(h).lo;
            arb_clear(h);
        }
        fmpz_clear(half);
        out->proved = !status;
    }
    for (size_t v = 0; v < T.n; v++) out->vertices += T.v[v].on_u;
    out->crossings = T.n, out->rectangles = T.rects, out->strips = m;
    if (T.failed) snprintf(out->failure, sizeof out->failure, "%s", T.failure);
    free(e);
    release(&T);
    arb_clear(lambda), arb_clear(lambda_r), arb_clear(reach);
    out->seconds = gb_proof_cpu_seconds() - start + T.worker_seconds;
    return status;
}
