/* gb_proof_manifold_cross — the crossings of an unstable manifold P of f with an unstable manifold R of f⁻¹ (the
 * stable manifold of f) over two arcs: each proved by Krawczyk's operator, and no other, by bisection
 * (gb_proof_manifold.h states the argument). */
#include "gb_proof_manifold.h"

#include "gb_error.h"
#include "gb_proof_internal.h"
#include "gb_proof_manifold_internal.h"

#include <arb.h>
#include <arb_mat.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { PIECES_MAX = 1 << 22 };

typedef struct piece {
    gb_proof_interval par, box[2];
} piece;

/* A crossing proved, and the box of (s, t) where it is the only zero. */
typedef struct found {
    gb_proof_manifold_crossing c;
    gb_proof_interval unique[2];
} found;

typedef struct cross_ctx {
    const gb_proof_manifold *p, *r;
    const gb_proof_manifold_crossings_def *def;
    double t0; /* R's parameters are t0 + t: t relative to t0 (0 for the public call) */
    slong prec;
    found *list;
    size_t count, cap, undecided;
    int failed; /* an error or a crossing that cannot be placed: the message is in failure */
    char failure[200];
} cross_ctx;

static double width_of(const gb_proof_interval b[2]) { return fmax(b[0].hi - b[0].lo, b[1].hi - b[1].lo); }

static int meet(const gb_proof_interval a[2], const gb_proof_interval b[2])
{
    return a[0].lo <= b[0].hi && b[0].lo <= a[0].hi && a[1].lo <= b[1].hi && b[1].lo <= a[1].hi;
}

static int inside(gb_proof_interval x, gb_proof_interval in) { return x.lo >= in.lo && x.hi <= in.hi; }

static void fail(cross_ctx *x, const char *message)
{
    if (!x->failed) snprintf(x->failure, sizeof x->failure, "%s", message);
    x->failed = 1;
}

/* The manifold over origin + s (s relative; origin 0: gb_proof_manifold_enclose itself), the sum exact on Arb. */
static int enclose_at(const gb_proof_manifold *m, double origin, gb_proof_interval s, gb_proof_interval out[2])
{
    if (origin == 0.0) return gb_proof_manifold_enclose(m, s, out, NULL);
    const slong prec = gb_proof_manifold_precision(m);
    arb_t S, o;
    arb_init(S), arb_init(o);
    gb_proof_ball_of(S, s, prec);
    arb_set_d(o, origin);
    arb_add(S, S, o, prec);
    arb_ptr z = _arb_vec_init(2), dz = _arb_vec_init(2);
    const int status = gb_proof_manifold_ball(m, S, z, dz);
    if (!status)
        for (int i = 0; i < 2; i++) out[i] = gb_proof_interval_of(z + i);
    _arb_vec_clear(z, 2), _arb_vec_clear(dz, 2);
    arb_clear(S), arb_clear(o);
    return status;
}

/* The arc's pieces: halved until their enclosure is at most width wide (or cannot be halved); the parameters relative
 * to origin. */
static int arc_pieces(const gb_proof_manifold *m, double origin, gb_proof_interval range, double width, piece **out,
                      size_t *count)
{
    size_t cap = 1024, n = 0, top = 0, stack_cap = 256;
    piece *list = malloc(cap * sizeof *list);
    gb_proof_interval *stack = malloc(stack_cap * sizeof *stack);
    int status = list && stack ? GB_OK : gb_error_set(GB_ENOMEM, "crossings: out of memory");
    if (!status) stack[top++] = range;
    while (!status && top) {
        const gb_proof_interval s = stack[--top];
        piece q = {s, {{0, 0}, {0, 0}}};
        status = enclose_at(m, origin, s, q.box);
        if (status) break;
        if (width_of(q.box) <= width || !gb_proof_halvable(s)) {
            if (n == cap) {
                piece *grown = cap < PIECES_MAX ? realloc(list, 2 * cap * sizeof *list) : NULL;
                if (!grown) {
                    status = gb_error_set(GB_ENOMEM, "crossings: more than %d pieces of an arc (widen the width)",
                                          PIECES_MAX);
                    break;
                }
                list = grown, cap *= 2;
            }
            list[n++] = q;
            continue;
        }
        if (top + 2 > stack_cap) {
            gb_proof_interval *grown = realloc(stack, 2 * stack_cap * sizeof *stack);
            if (!grown) {
                status = gb_error_set(GB_ENOMEM, "crossings: out of memory");
                break;
            }
            stack = grown, stack_cap *= 2;
        }
        stack[top++] = gb_proof_half(s, 1), stack[top++] = gb_proof_half(s, 0);
    }
    free(stack);
    if (status) {
        free(list);
        return status;
    }
    *out = list, *count = n;
    return GB_OK;
}

/* arc_pieces on several threads with the same pieces in the same order: the first halvings are made here, breadth
 * first, in order, until there are enough intervals still too wide to share out; each is then cut as arc_pieces
 * would cut it, on whichever thread is free, and the lists are joined in order. */
typedef struct split {
    gb_proof_interval s;
    piece done; /* when pending is 0 */
    int pending;
    piece *list;
    size_t count;
} split;

typedef struct split_job {
    const gb_proof_manifold *m;
    double origin, width;
    split *item;
} split_job;

static int split_task(void *ctx, size_t k)
{
    const split_job *J = ctx;
    split *it = &J->item[k];
    return it->pending ? arc_pieces(J->m, J->origin, it->s, J->width, &it->list, &it->count) : GB_OK;
}

static int arc_pieces_on(const gb_proof_manifold *m, double origin, gb_proof_interval range, double width, int threads,
                         piece **out, size_t *count, double *seconds)
{
    *seconds = 0.0;
    if (threads <= 1) return arc_pieces(m, origin, range, width, out, count);
    const size_t want = 16 * (size_t)threads;
    size_t n = 1, pending = 1;
    split *item = calloc(1, sizeof *item);
    if (!item) return gb_error_set(GB_ENOMEM, "crossings: out of memory");
    item[0] = (split){.s = range, .pending = 1};
    int status = GB_OK;
    for (int level = 0; level < 16 && pending && pending < want && !status; level++) {
        split *next = calloc(2 * n, sizeof *next);
        if (!next) {
            status = gb_error_set(GB_ENOMEM, "crossings: out of memory");
            break;
        }
        size_t k = 0;
        pending = 0;
        for (size_t i = 0; i < n && !status; i++) {
            if (!item[i].pending) {
                next[k++] = item[i];
                continue;
            }
            piece q = {item[i].s, {{0, 0}, {0, 0}}};
            status = enclose_at(m, origin, item[i].s, q.box);
            if (status) break;
            if (width_of(q.box) <= width || !gb_proof_halvable(item[i].s)) {
                next[k++] = (split){.s = item[i].s, .done = q};
                continue;
            }
            next[k++] = (split){.s = gb_proof_half(item[i].s, 0), .pending = 1};
            next[k++] = (split){.s = gb_proof_half(item[i].s, 1), .pending = 1};
            pending += 2;
        }
        free(item);
        item = next, n = k;
    }
    split_job job = {m, origin, width, item};
    if (!status) status = gb_proof_for_each(n, threads, split_task, &job, seconds);
    size_t total = 0;
    for (size_t i = 0; i < n; i++) total += item[i].pending ? item[i].count : 1;
    piece *list = status ? NULL : malloc((total ? total : 1) * sizeof *list);
    if (!status && !list) status = gb_error_set(GB_ENOMEM, "crossings: out of memory");
    size_t at = 0;
    for (size_t i = 0; i < n; i++) {
        if (!status && item[i].pending)
            for (size_t j = 0; j < item[i].count; j++) list[at++] = item[i].list[j];
        else if (!status)
            list[at++] = item[i].done;
        free(item[i].list);
    }
    free(item);
    if (status) return status;
    *out = list, *count = total;
    return GB_OK;
}

/* G(s, t) = P(s) − R(t) over the balls X = (S, T) (g NULL: not wanted), and DG = [P'(S), −R'(T)] (A NULL: not
 * wanted): over a box in mean value form, at a point (X exact) by the plain enclosure, which is as narrow there. */
static int eval_g(const cross_ctx *x, arb_srcptr X, arb_ptr g, arb_mat_t A)
{
    arb_ptr zp = _arb_vec_init(2), dp = _arb_vec_init(2), zr = _arb_vec_init(2), dr = _arb_vec_init(2);
    const int box = !arb_is_exact(X) || !arb_is_exact(X + 1);
    arb_t T; /* t0 + t: exact for a thin t at Arb's precision */
    arb_init(T);
    arb_set_d(T, x->t0);
    arb_add(T, T, X + 1, x->prec);
    int status = box ? gb_proof_manifold_ball(x->p, X, zp, dp) : gb_proof_manifold_point(x->p, X, zp, A ? dp : NULL);
    if (!status)
        status = box ? gb_proof_manifold_ball(x->r, T, zr, dr) : gb_proof_manifold_point(x->r, T, zr, A ? dr : NULL);
    arb_clear(T);
    if (!status && g) _arb_vec_sub(g, zp, zr, 2, x->prec);
    if (!status && A)
        for (int i = 0; i < 2; i++) {
            arb_set(arb_mat_entry(A, i, 0), dp + i);
            arb_neg(arb_mat_entry(A, i, 1), dr + i);
        }
    _arb_vec_clear(zp, 2), _arb_vec_clear(dp, 2), _arb_vec_clear(zr, 2), _arb_vec_clear(dr, 2);
    return status;
}

/* Krawczyk's verdict on the box s × t (gb_proof_krawczyk2), K in k; −2 on an error. */
static int krawczyk_box(const cross_ctx *x, gb_proof_interval s, gb_proof_interval t, gb_proof_interval k[2])
{
    arb_ptr X = _arb_vec_init(2), m = _arb_vec_init(2), g = _arb_vec_init(2), K = _arb_vec_init(2);
    arb_mat_t A;
    arb_mat_init(A, 2, 2);
    gb_proof_ball_of(X, s, x->prec), gb_proof_ball_of(X + 1, t, x->prec);
    for (int i = 0; i < 2; i++) arf_set(arb_midref(m + i), arb_midref(X + i)), mag_zero(arb_radref(m + i));
    int verdict = -2;
    if (!eval_g(x, m, g, NULL) && !eval_g(x, X, NULL, A)) verdict = gb_proof_krawczyk2(X, m, g, A, K, x->prec);
    if (verdict >= -1)
        for (int i = 0; i < 2; i++) k[i] = gb_proof_interval_of(K + i);
    _arb_vec_clear(X, 2), _arb_vec_clear(m, 2), _arb_vec_clear(g, 2), _arb_vec_clear(K, 2);
    arb_mat_clear(A);
    return verdict;
}

/* Newton on doubles from (s, t) through the balls' middles: 1 when its step fell below 1e-15 of the point's scale;
 * the speeds |P'(s)|, |R'(t)| there. */
static int newton(const cross_ctx *x, double *s, double *t, double speed[2])
{
    arb_ptr X = _arb_vec_init(2), g = _arb_vec_init(2);
    arb_mat_t A;
    arb_mat_init(A, 2, 2);
    int converged = 0;
    for (int it = 0; it < 40 && !converged; it++) {
        arb_set_d(X, *s), arb_set_d(X + 1, *t);
        if (eval_g(x, X, g, A)) break;
        double a[2][2], r[2];
        for (int i = 0; i < 2; i++) {
            r[i] = arf_get_d(arb_midref(g + i), ARF_RND_NEAR);
            for (int j = 0; j < 2; j++) a[i][j] = arf_get_d(arb_midref(arb_mat_entry(A, i, j)), ARF_RND_NEAR);
        }
        speed[0] = hypot(a[0][0], a[1][0]), speed[1] = hypot(a[0][1], a[1][1]);
        const double det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
        if (!(isfinite(det) && det != 0.0)) break;
        const double ds = (a[1][1] * r[0] - a[0][1] * r[1]) / det, dt = (a[0][0] * r[1] - a[1][0] * r[0]) / det;
        if (!(isfinite(ds) && isfinite(dt)) || fabs(ds) > 1e3 || fabs(dt) > 1e3) break;
        *s -= ds, *t -= dt;
        converged = fabs(ds) <= 1e-15 * (1.0 + fabs(*s)) && fabs(dt) <= 1e-15 * (1.0 + fabs(*t));
        if (!converged && it > 5 && fabs(ds) * speed[0] + fabs(dt) * speed[1] < 1e-14) converged = 1;
    }
    _arb_vec_clear(X, 2), _arb_vec_clear(g, 2);
    arb_mat_clear(A);
    return converged;
}

static int add_found(cross_ctx *x, const found *f)
{
    if (x->count == x->cap) {
        const size_t cap = x->cap ? 2 * x->cap : 64;
        found *grown = realloc(x->list, cap * sizeof *grown);
        if (!grown) return gb_error_set(GB_ENOMEM, "crossings: out of memory");
        x->list = grown, x->cap = cap;
    }
    x->list[x->count++] = *f;
    return GB_OK;
}

/* Newton on Arb's midpoints at Arb's precision from m (exact), m left at its last point: 1 when the last step was
 * below 2^(40 − prec) of the point's scale. A near-tangent crossing's Jacobian is nearly singular, so Newton in doubles
 * wanders about it by the doubles' rounding over the angle; at Arb's precision it settles. The speeds |P'|, |R'| at m. */
static int newton_fine(const cross_ctx *x, arb_ptr m, double speed[2])
{
    arb_ptr g = _arb_vec_init(2);
    arb_mat_t A, G, D;
    arb_mat_init(A, 2, 2), arb_mat_init(G, 2, 1), arb_mat_init(D, 2, 1);
    int converged = 0;
    for (int it = 0; it < 30 && !converged; it++) {
        if (eval_g(x, m, g, A)) break;
        for (int i = 0; i < 2; i++) arb_set(arb_mat_entry(G, i, 0), g + i);
        if (!arb_mat_approx_solve(D, A, G, x->prec)) break;
        speed[0] = hypot(arf_get_d(arb_midref(arb_mat_entry(A, 0, 0)), ARF_RND_NEAR),
                         arf_get_d(arb_midref(arb_mat_entry(A, 1, 0)), ARF_RND_NEAR));
        speed[1] = hypot(arf_get_d(arb_midref(arb_mat_entry(A, 0, 1)), ARF_RND_NEAR),
                         arf_get_d(arb_midref(arb_mat_entry(A, 1, 1)), ARF_RND_NEAR));
        converged = 1;
        for (int i = 0; i < 2; i++) {
            arf_struct *step = arb_midref(arb_mat_entry(D, i, 0));
            if (!arf_is_finite(step)) converged = -1;
            arf_sub(arb_midref(m + i), arb_midref(m + i), step, x->prec, ARF_RND_NEAR);
            const double scale = 1.0 + fabs(arf_get_d(arb_midref(m + i), ARF_RND_NEAR));
            if (converged == 1 && !(fabs(arf_get_d(step, ARF_RND_NEAR)) <= ldexp(scale, 40 - (int)x->prec)))
                converged = 0;
        }
        if (converged < 0) break;
    }
    _arb_vec_clear(g, 2);
    arb_mat_clear(A), arb_mat_clear(G), arb_mat_clear(D);
    return converged == 1;
}

/* The crossing's enclosure narrowed: Newton at Arb's precision from its middle, then Krawczyk's operator on balls about
 * that point, δ/|P'| × δ/|R'| in radius from δ = 2^(48 − prec) up (×256), the first proved inside the box of
 * uniqueness giving the enclosure (the same zero, the box's only one) when it is narrower. Near-tangent crossings lie
 * close (a trellis orders them along each arc), and their enclosures come out an ulp or two wide. */
static void tighten(const cross_ctx *x, found *f)
{
    arb_ptr m = _arb_vec_init(2), X = _arb_vec_init(2), g = _arb_vec_init(2), K = _arb_vec_init(2);
    arb_mat_t A;
    arb_mat_init(A, 2, 2);
    arb_set_d(m, 0.5 * (f->c.s.lo + f->c.s.hi)), arb_set_d(m + 1, 0.5 * (f->c.t.lo + f->c.t.hi));
    double speed[2] = {1.0, 1.0};
    const int settled = newton_fine(x, m, speed);
    if (!settled) gb_error_clear();
    for (double delta = ldexp(1.0, 48 - (int)x->prec); settled && delta <= 1e-12; delta *= 256.0) {
        for (int i = 0; i < 2; i++) {
            arb_set(X + i, m + i);
            mag_set_d(arb_radref(X + i), delta / fmax(speed[i], 1e-300));
        }
        const gb_proof_interval S = gb_proof_interval_of(X), T = gb_proof_interval_of(X + 1);
        if (!(inside(S, f->unique[0]) && inside(T, f->unique[1]))) break;
        if (eval_g(x, m, g, NULL) || eval_g(x, X, NULL, A)) {
            gb_error_clear(); /* the enclosure proved already stands */
            break;
        }
        if (gb_proof_krawczyk2(X, m, g, A, K, x->prec) != 1) continue;
        const gb_proof_interval k[2] = {gb_proof_interval_of(K), gb_proof_interval_of(K + 1)};
        if (k[0].hi - k[0].lo < f->c.s.hi - f->c.s.lo || k[1].hi - k[1].lo < f->c.t.hi - f->c.t.lo)
            f->c.s = k[0], f->c.t = k[1];
        break;
    }
    _arb_vec_clear(m, 2), _arb_vec_clear(X, 2), _arb_vec_clear(g, 2), _arb_vec_clear(K, 2);
    arb_mat_clear(A);
}

/* A crossing proved (its enclosure and its box of uniqueness): listed unless it is one listed already, or lies
 * outside the arcs; one on an arc's end cannot be placed. */
static void record(cross_ctx *x, found *f)
{
    tighten(x, f);
    for (size_t i = 0; i < x->count; i++) { /* enclosures that miss each other hold two zeros; else one zero twice */
        const found *o = &x->list[i];
        const gb_proof_interval ks[2] = {f->c.s, f->c.t}, ko[2] = {o->c.s, o->c.t};
        if (!meet(ks, ko)) continue;
        if ((inside(f->c.s, o->unique[0]) && inside(f->c.t, o->unique[1])) ||
            (inside(o->c.s, f->unique[0]) && inside(o->c.t, f->unique[1])))
            return;
        fail(x, "two crossings' enclosures meet outside each other's box of uniqueness");
        return;
    }
    const gb_proof_interval as = x->def->s, at = x->def->t;
    const int within = f->c.s.lo > as.lo && f->c.s.hi < as.hi && f->c.t.lo > at.lo && f->c.t.hi < at.hi;
    const int outside = f->c.s.hi < as.lo || f->c.s.lo > as.hi || f->c.t.hi < at.lo || f->c.t.lo > at.hi;
    if (!within && !outside) {
        fail(x, "a crossing lies on an arc's end (move the end)");
        return;
    }
    if (outside) return;
    if (gb_proof_manifold_enclose(x->p, f->c.s, f->c.point, NULL) || add_found(x, f)) fail(x, gb_error_message());
}

/* The crossing Newton found near (s, t): Krawczyk on boxes δ/|P'| × δ/|R'| wide, δ = 1e-12 … 1e-2 (×4), the first
 * proved giving its enclosure, the last its box of uniqueness. Not proved: left to the bisection, which finds every
 * zero the arcs hold. */
static void prove_zero(cross_ctx *x, double s, double t, const double speed[2])
{
    found f;
    memset(&f, 0, sizeof f);
    int proved = 0;
    for (double delta = 1e-12; delta <= 1e-2; delta *= 4.0) {
        const double hs = delta / fmax(speed[0], 1e-300), ht = delta / fmax(speed[1], 1e-300);
        const gb_proof_interval S = {s - hs, s + hs}, T = {t - ht, t + ht};
        gb_proof_interval k[2];
        const int verdict = krawczyk_box(x, S, T, k);
        if (verdict == -2) {
            fail(x, gb_error_message());
            return;
        }
        if (verdict != 1) break;
        if (!proved) f.c.s = k[0], f.c.t = k[1];
        f.unique[0] = S, f.unique[1] = T, proved = 1;
    }
    if (proved) record(x, &f);
}

static int covered(const cross_ctx *x, gb_proof_interval s, gb_proof_interval t)
{
    for (size_t i = 0; i < x->count; i++)
        if (inside(s, x->list[i].unique[0]) && inside(t, x->list[i].unique[1])) return 1;
    return 0;
}

/* No zero in s × t but those listed: the box is inside a listed zero's box of uniqueness, or P(s) and R(t) do not
 * meet, or Krawczyk's image misses it; a box where Krawczyk's image lies inside holds exactly one zero, listed (the
 * box its box of uniqueness); else halved. */
static void exclude(cross_ctx *x, gb_proof_interval s, gb_proof_interval t, int depth)
{
    if (x->failed || covered(x, s, t)) return;
    gb_proof_interval bp[2], br[2], k[2];
    if (gb_proof_manifold_enclose(x->p, s, bp, NULL) || enclose_at(x->r, x->t0, t, br)) {
        fail(x, gb_error_message());
        return;
    }
    if (!meet(bp, br)) return;
    const int verdict = krawczyk_box(x, s, t, k);
    if (verdict == -2) {
        fail(x, gb_error_message());
        return;
    }
    if (verdict == -1) return;
    if (verdict == 1) { /* exactly one zero in s × t, in k */
        found f;
        memset(&f, 0, sizeof f);
        f.c.s = k[0], f.c.t = k[1], f.unique[0] = s, f.unique[1] = t;
        record(x, &f);
        return;
    }
    const int split_s = gb_proof_halvable(s), split_t = gb_proof_halvable(t);
    if (depth >= x->def->depth || (!split_s && !split_t)) {
        x->undecided++;
        return;
    }
    if (split_s && (!split_t || width_of(bp) >= width_of(br))) {
        exclude(x, gb_proof_half(s, 0), t, depth + 1);
        exclude(x, gb_proof_half(s, 1), t, depth + 1);
    } else {
        exclude(x, s, gb_proof_half(t, 0), depth + 1);
        exclude(x, s, gb_proof_half(t, 1), depth + 1);
    }
}

static int check_range(const char *name, gb_proof_interval x)
{
    if (!(isfinite(x.lo) && isfinite(x.hi) && x.lo < x.hi && fabs(x.lo) <= 1e12 && fabs(x.hi) <= 1e12))
        return gb_error_set(GB_EDOM, "crossings: %s = [%g, %g] must be finite, ordered, within ±1e12", name, x.lo,
                            x.hi);
    return GB_OK;
}

static int by_s(const void *a, const void *b)
{
    const gb_proof_manifold_crossing *x = a, *y = b;
    return (x->s.lo > y->s.lo) - (x->s.lo < y->s.lo);
}

/* The pairs (i, j) of pieces whose enclosures meet, in the order of i then j: the pieces of R bucketed in a grid of
 * cells as wide as the widest piece, each piece of P compared with those of the cells it touches, a pair kept in the
 * cell of its boxes' common lower corner only. */
typedef struct pair {
    size_t i, j;
} pair;

typedef struct bucket {
    long long cell;
    size_t j;
} bucket;

static int by_cell(const void *a, const void *b)
{
    const bucket *x = a, *y = b;
    return x->cell != y->cell ? (x->cell > y->cell) - (x->cell < y->cell) : (x->j > y->j) - (x->j < y->j);
}

static int by_pair(const void *a, const void *b)
{
    const pair *x = a, *y = b;
    return x->i != y->i ? (x->i > y->i) - (x->i < y->i) : (x->j > y->j) - (x->j < y->j);
}

static long long cell_of(long cx, long cy) { return (long long)cx * 4294967296LL + (long long)cy; }

static int meeting_pairs(const piece *ps, size_t np, const piece *rs, size_t nr, pair **out, size_t *count)
{
    *out = NULL, *count = 0;
    double h = 0.0;
    for (size_t i = 0; i < np; i++) h = fmax(h, width_of(ps[i].box));
    for (size_t j = 0; j < nr; j++) h = fmax(h, width_of(rs[j].box));
    if (!(h > 0.0 && isfinite(h))) h = 1.0;
    gb_proof_interval all[2] = {{INFINITY, -INFINITY}, {INFINITY, -INFINITY}}; /* R's pieces' hull */
    for (size_t j = 0; j < nr; j++)
        for (int a = 0; a < 2; a++)
            all[a].lo = fmin(all[a].lo, rs[j].box[a].lo), all[a].hi = fmax(all[a].hi, rs[j].box[a].hi);
    for (int a = 0; a < 2; a++) /* cells beyond a long's range: one cell for all */
        if (!(fabs(all[a].lo) / h < 1e9 && fabs(all[a].hi) / h < 1e9)) h = 1e300;
    bucket *b = malloc((4 * nr + 1) * sizeof *b);
    size_t nb = 0, cap = 1024, m = 0;
    pair *list = malloc(cap * sizeof *list);
    if (!b || !list) {
        free(b), free(list);
        return gb_error_set(GB_ENOMEM, "crossings: out of memory");
    }
    for (size_t j = 0; j < nr; j++)
        for (long cx = (long)floor(rs[j].box[0].lo / h); cx <= (long)floor(rs[j].box[0].hi / h); cx++)
            for (long cy = (long)floor(rs[j].box[1].lo / h); cy <= (long)floor(rs[j].box[1].hi / h); cy++)
                b[nb++] = (bucket){cell_of(cx, cy), j};
    qsort(b, nb, sizeof *b, by_cell);
    for (size_t i = 0; i < np; i++) {
        const gb_proof_interval *q = ps[i].box;
        if (!nr || !meet(q, all)) continue; /* then q lies within the hull widened by h: its cells fit a long */
        for (long cx = (long)floor(q[0].lo / h); cx <= (long)floor(q[0].hi / h); cx++)
            for (long cy = (long)floor(q[1].lo / h); cy <= (long)floor(q[1].hi / h); cy++) {
                const long long key = cell_of(cx, cy);
                size_t lo = 0, hi = nb;
                while (lo < hi) {
                    const size_t mid = (lo + hi) / 2;
                    if (b[mid].cell < key)
                        lo = mid + 1;
                    else
                        hi = mid;
                }
                for (size_t k = lo; k < nb && b[k].cell == key; k++) {
                    const piece *rj = &rs[b[k].j];
                    if (!meet(q, rj->box)) continue;
                    const double x0 = fmax(q[0].lo, rj->box[0].lo), y0 = fmax(q[1].lo, rj->box[1].lo);
                    if ((long)floor(x0 / h) != cx || (long)floor(y0 / h) != cy) continue;
                    if (m == cap) {
                        pair *grown = realloc(list, 2 * cap * sizeof *grown);
                        if (!grown) {
                            free(b), free(list);
                            return gb_error_set(GB_ENOMEM, "crossings: out of memory");
                        }
                        list = grown, cap *= 2;
                    }
                    list[m++] = (pair){i, b[k].j};
                }
            }
    }
    free(b);
    if (m) qsort(list, m, sizeof *list, by_pair);
    *out = list, *count = m;
    return GB_OK;
}

/* One t-arc against the s-arc's pieces ps: def->t is the arc (def->s, the s-arc, only places the crossings found). */
static int crossings_of(const gb_proof_manifold *p, const gb_proof_manifold *r,
                        const gb_proof_manifold_crossings_def *def, double t0, const piece *ps, size_t np,
                        gb_proof_manifold_crossings_result *out)
{
    memset(out, 0, sizeof *out);
    const double start = gb_proof_cpu_seconds();
    cross_ctx x = {.p = p, .r = r, .def = def, .t0 = t0, .prec = gb_proof_manifold_precision(p)};
    piece *rs = NULL;
    size_t nr = 0, npairs = 0;
    pair *pairs = NULL;
    int status = arc_pieces(r, t0, def->t, def->width, &rs, &nr);
    if (!status) status = meeting_pairs(ps, np, rs, nr, &pairs, &npairs);
    out->pairs = npairs;
    for (size_t k = 0; k < npairs && !status && !x.failed; k++) {
        const piece *pi = &ps[pairs[k].i], *rj = &rs[pairs[k].j];
        double s = 0.5 * (pi->par.lo + pi->par.hi), t = 0.5 * (rj->par.lo + rj->par.hi), speed[2] = {1.0, 1.0};
        const double ws = pi->par.hi - pi->par.lo, wt = rj->par.hi - rj->par.lo;
        if (newton(&x, &s, &t, speed) && s >= pi->par.lo - ws && s <= pi->par.hi + ws && t >= rj->par.lo - wt &&
            t <= rj->par.hi + wt && !covered(&x, (gb_proof_interval){s, s}, (gb_proof_interval){t, t}))
            prove_zero(&x, s, t, speed);
    }
    for (size_t k = 0; k < npairs && !status && !x.failed; k++) exclude(&x, ps[pairs[k].i].par, rs[pairs[k].j].par, 0);
    free(rs), free(pairs);
    if (status) {
        free(x.list);
        return status;
    }
    out->pieces_s = np, out->pieces_t = nr, out->undecided = x.undecided;
    out->crossings = x.count ? malloc(x.count * sizeof *out->crossings) : NULL;
    if (x.count && !out->crossings) {
        free(x.list);
        return gb_error_set(GB_ENOMEM, "crossings: out of memory");
    }
    for (size_t i = 0; i < x.count; i++) out->crossings[i] = x.list[i].c;
    out->count = x.count;
    free(x.list);
    if (out->count) qsort(out->crossings, out->count, sizeof *out->crossings, by_s);
    if (x.failed)
        snprintf(out->failure, sizeof out->failure, "%s", x.failure);
    else if (x.undecided)
        snprintf(out->failure, sizeof out->failure, "%zu boxes of (s, t) left undecided at depth %d", x.undecided,
                 def->depth);
    out->proved = !x.failed && !x.undecided;
    out->seconds = gb_proof_cpu_seconds() - start;
    return GB_OK;
}

static int check_def(const gb_proof_manifold *p, const gb_proof_manifold *r, const gb_proof_manifold_crossings_def *def)
{
    int status = check_range("s", def->s);
    if (!status) status = check_range("t", def->t);
    if (!status && !(def->width > 0.0 && def->width <= 1.0))
        status =
            gb_error_set(GB_EDOM, "crossings: width = %g is out of range (allowed: above 0, at most 1)", def->width);
    if (!status && (def->depth < 1 || def->depth > 60))
        status = gb_error_set(GB_EDOM, "crossings: depth = %d is out of range (allowed: 1 to 60)", def->depth);
    gb_proof_manifold_info ip, ir;
    gb_proof_manifold_info_of(p, &ip), gb_proof_manifold_info_of(r, &ir);
    for (int i = 0; i < 2 && !status; i++)
        if (!(ip.fixed[i].lo <= ir.fixed[i].hi && ir.fixed[i].lo <= ip.fixed[i].hi))
            status = gb_error_set(GB_EDOM, "crossings: the two manifolds are not of one fixed point");
    return status;
}

/* One arc of R against P's pieces: a task of gb_proof_for_each. */
typedef struct arcs_job {
    const gb_proof_manifold *p, *r;
    const gb_proof_manifold_crossings_def *defs;
    const double *t_origin;
    const piece *ps;
    size_t np;
    gb_proof_manifold_crossings_result *out;
} arcs_job;

static int arc_task(void *ctx, size_t k)
{
    const arcs_job *J = ctx;
    return crossings_of(J->p, J->r, &J->defs[k], J->t_origin ? J->t_origin[k] : 0.0, J->ps, J->np, &J->out[k]);
}

int gb_proof_manifold_crossings_arcs(const gb_proof_manifold *p, const gb_proof_manifold *r,
                                     const gb_proof_manifold_crossings_def *defs, const double *t_origin, size_t count,
                                     int threads, gb_proof_manifold_crossings_result *out, double *worker_seconds)
{
    if (worker_seconds) *worker_seconds = 0.0;
    for (size_t k = 0; k < count; k++) memset(&out[k], 0, sizeof out[k]);
    int status = GB_OK;
    for (size_t k = 0; k < count && !status; k++) {
        status = check_def(p, r, &defs[k]);
        if (!status && (defs[k].s.lo != defs[0].s.lo || defs[k].s.hi != defs[0].s.hi || defs[k].width != defs[0].width))
            status = gb_error_set(GB_EDOM, "crossings: the arcs of P and the widths must be one");
    }
    if (status || !count) return status;
    const double start = gb_proof_cpu_seconds();
    piece *ps = NULL;
    size_t np = 0;
    double split_seconds = 0.0, arc_seconds = 0.0;
    status = arc_pieces_on(p, 0.0, defs[0].s, defs[0].width, threads, &ps, &np, &split_seconds);
    const double shared = gb_proof_cpu_seconds() - start + split_seconds;
    arcs_job job = {p, r, defs, t_origin, ps, np, out};
    if (!status) status = gb_proof_for_each(count, threads, arc_task, &job, &arc_seconds);
    if (worker_seconds) *worker_seconds = split_seconds + arc_seconds;
    out[0].seconds += shared;
    free(ps);
    if (status)
        for (size_t k = 0; k < count; k++) gb_proof_manifold_crossings_free(&out[k]);
    return status;
}

int gb_proof_manifold_crossings(const gb_proof_manifold *p, const gb_proof_manifold *r,
                                const gb_proof_manifold_crossings_def *def, gb_proof_manifold_crossings_result *out)
{
    return gb_proof_manifold_crossings_arcs(p, r, def, NULL, 1, 1, out, NULL);
}

void gb_proof_manifold_crossings_free(gb_proof_manifold_crossings_result *out)
{
    free(out->crossings);
    out->crossings = NULL, out->count = 0;
}
