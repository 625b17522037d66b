/* gb_melnikov_tangle — the manifolds of a rotation's saddle under the whole perturbation, grown from
 * fundamental domains by the period map and intersected (gb_melnikov.h). */
#include "gb_melnikov.h"
#include "gb_melnikov_internal.h"

#include "gb_error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

gb_melnikov_tangle_def gb_melnikov_tangle_default_def(void)
{
    return (gb_melnikov_tangle_def){1.0, 0.0, 1e-7, 0.01, 400000, 0};
}

/* A point of a fundamental domain (its σ) and its image after the branch's current iterate. */
typedef struct point {
    double sigma, y[2];
} point;

/* One branch: its fundamental domain, the map's direction, and the curve of every iterate so far. */
typedef struct branch {
    gb_melnikov_forced *F;
    double t0, T;      /* T < 0: the stable branch, mapped by P⁻¹ */
    double x[2], v[2]; /* the fixed point it leaves (or its copy) and the side's unit direction */
    double log_factor; /* ln of the domain's span: ln |λ_u| or −ln |λ_s| */
    double start, spacing;
    size_t max_points;
    point *now, *next; /* the current iterate's points by σ, and room for the refined list */
    size_t n, now_cap, next_cap;
    double *u, *q, *p; /* the curve: iterate + σ, and the point */
    size_t len, u_cap, q_cap, p_cap;
    double widest_gap;
} branch;

static int grow(void **array, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap) return GB_OK;
    size_t c = *cap ? *cap : 256;
    while (c < need) c *= 2;
    void *a = realloc(*array, c * size);
    if (!a) return gb_error_set(GB_ENOMEM, "out of memory for the manifolds' points");
    *array = a, *cap = c;
    return GB_OK;
}

/* The point of the domain at σ mapped `k` times. */
static int image(branch *b, double sigma, int k, point *out)
{
    const double s = b->start * exp(sigma * b->log_factor);
    out->sigma = sigma, out->y[0] = b->x[0] + s * b->v[0], out->y[1] = b->x[1] + s * b->v[1];
    for (int j = 0; j < k; j++) {
        const int status = gb_melnikov_forced_flow(b->F, b->t0, b->t0 + b->T, out->y);
        if (status) return status;
    }
    return GB_OK;
}

/* Appends a after refining the gap from a to c (both images after k maps): midpoints in σ, each mapped
 * afresh, until neighbours are within the spacing or σ cannot be split. */
static int refine(branch *b, const point *a, const point *c, int k, int depth, size_t *m)
{
    const double gap = hypot(c->y[0] - a->y[0], c->y[1] - a->y[1]);
    if (gap > b->spacing && depth < 48 && c->sigma - a->sigma > 1e-14) {
        point mid;
        int status = image(b, 0.5 * (a->sigma + c->sigma), k, &mid);
        if (!status) status = refine(b, a, &mid, k, depth + 1, m);
        if (!status) status = refine(b, &mid, c, k, depth + 1, m);
        return status;
    }
    if (gap > b->widest_gap) b->widest_gap = gap;
    if (b->len + *m + 2 > b->max_points)
        return gb_error_set(GB_ENOCONV, "a manifold needs more than %zu points at spacing %g by its %d-th iterate "
                            "(allowed: raise max_points or the spacing)", b->max_points, b->spacing, k);
    int status = grow((void **)&b->next, &b->next_cap, *m + 2, sizeof(point));
    if (!status) b->next[(*m)++] = *c;
    return status;
}

/* The branch's next iterate: every point mapped once, the gaps refined, the curve extended. */
static int step(branch *b, int k)
{
    for (size_t i = 0; i < b->n; i++) {
        const int status = gb_melnikov_forced_flow(b->F, b->t0, b->t0 + b->T, b->now[i].y);
        if (status) return status;
    }
    size_t m = 0;
    int status = grow((void **)&b->next, &b->next_cap, 1, sizeof(point));
    if (!status) b->next[m++] = b->now[0];
    for (size_t i = 0; i + 1 < b->n && !status; i++) status = refine(b, &b->now[i], &b->now[i + 1], k, 0, &m);
    if (status) return status;
    point *t = b->now;
    const size_t cap = b->now_cap;
    b->now = b->next, b->now_cap = b->next_cap, b->next = t, b->next_cap = cap, b->n = m;
    status = grow((void **)&b->u, &b->u_cap, b->len + m, sizeof(double));
    if (!status) status = grow((void **)&b->q, &b->q_cap, b->len + m, sizeof(double));
    if (!status) status = grow((void **)&b->p, &b->p_cap, b->len + m, sizeof(double));
    for (size_t i = 0; i < m && !status; i++)
        b->u[b->len] = k + b->now[i].sigma, b->q[b->len] = b->now[i].y[0], b->p[b->len] = b->now[i].y[1], b->len++;
    return status;
}

static int branch_grow(branch *b, int iterates)
{
    enum { FIRST = 64 };
    int status = grow((void **)&b->now, &b->now_cap, FIRST + 1, sizeof(point));
    for (int i = 0; i <= FIRST && !status; i++) status = image(b, (double)i / FIRST, 0, &b->now[i]);
    b->n = FIRST + 1;
    for (int k = 1; k <= iterates && !status; k++) status = step(b, k);
    return status;
}

static void branch_free(branch *b)
{
    free(b->now), free(b->next), free(b->u), free(b->q), free(b->p);
}

static int by_u(const void *a, const void *b)
{
    const double x = ((const gb_melnikov_crossing *)a)->u, y = ((const gb_melnikov_crossing *)b)->u;
    return (x > y) - (x < y);
}

/* Every crossing of the two curves: the stable curve's segments binned on a grid of cells as wide as the
 * spacing, each unstable segment tested against the segments of the cells its box meets. */
static int intersect(const branch *U, const branch *S, double cell, gb_melnikov_tangle *out)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t i = 0; i < S->len; i++) {
        lo[0] = fmin(lo[0], S->q[i]), hi[0] = fmax(hi[0], S->q[i]);
        lo[1] = fmin(lo[1], S->p[i]), hi[1] = fmax(hi[1], S->p[i]);
    }
    if (S->len < 2 || U->len < 2) return GB_OK;
    const size_t nx = (size_t)((hi[0] - lo[0]) / cell) + 1, ny = (size_t)((hi[1] - lo[1]) / cell) + 1;
    if (nx > 1u << 14 || ny > 1u << 14 || nx * ny > (size_t)1 << 24)
        return gb_error_set(GB_ENOCONV, "the stable branch spans %g x %g: too wide to bin at %g", hi[0] - lo[0],
                            hi[1] - lo[1], cell);
    size_t *start = calloc(nx * ny + 1, sizeof *start), *entry = NULL, *fill = NULL, entries = 0, cap = 0, found = 0;
    int status = start ? GB_OK : gb_error_set(GB_ENOMEM, "out of memory for the crossings' grid");
    /* two passes: count each cell's segments, then place them */
    for (int pass = 0; pass < 2 && !status; pass++) {
        if (pass == 1) {
            for (size_t c = 0; c < nx * ny; c++) start[c + 1] += start[c];
            entries = start[nx * ny];
            entry = malloc((entries ? entries : 1) * sizeof *entry), fill = calloc(nx * ny, sizeof *fill);
            if (!entry || !fill) status = gb_error_set(GB_ENOMEM, "out of memory for the crossings' grid");
        }
        for (size_t i = 0; i + 1 < S->len && !status; i++) {
            if (S->u[i] == S->u[i + 1]) continue; /* the join of two iterates: one point twice */
            const size_t x0 = (size_t)((fmin(S->q[i], S->q[i + 1]) - lo[0]) / cell),
                         x1 = (size_t)((fmax(S->q[i], S->q[i + 1]) - lo[0]) / cell);
            const size_t y0 = (size_t)((fmin(S->p[i], S->p[i + 1]) - lo[1]) / cell),
                         y1 = (size_t)((fmax(S->p[i], S->p[i + 1]) - lo[1]) / cell);
            for (size_t x = x0; x <= x1 && x < nx; x++)
                for (size_t y = y0; y <= y1 && y < ny; y++) {
                    if (pass == 0) start[x * ny + y + 1]++;
                    else entry[start[x * ny + y] + fill[x * ny + y]++] = i;
                }
        }
    }
    for (size_t i = 0; i + 1 < U->len && !status; i++) {
        if (U->u[i] == U->u[i + 1]) continue;
        const size_t first = found; /* this segment's crossings: a pair met in two cells is kept once */
        const double a[2] = {U->q[i], U->p[i]}, r[2] = {U->q[i + 1] - a[0], U->p[i + 1] - a[1]};
        const double bx0 = fmin(a[0], a[0] + r[0]), bx1 = fmax(a[0], a[0] + r[0]);
        const double by0 = fmin(a[1], a[1] + r[1]), by1 = fmax(a[1], a[1] + r[1]);
        if (bx1 < lo[0] || bx0 > hi[0] || by1 < lo[1] || by0 > hi[1]) continue;
        const size_t x0 = bx0 <= lo[0] ? 0 : (size_t)((bx0 - lo[0]) / cell), x1 = (size_t)((fmin(bx1, hi[0]) - lo[0]) / cell);
        const size_t y0 = by0 <= lo[1] ? 0 : (size_t)((by0 - lo[1]) / cell), y1 = (size_t)((fmin(by1, hi[1]) - lo[1]) / cell);
        for (size_t x = x0; x <= x1 && x < nx && !status; x++)
            for (size_t y = y0; y <= y1 && y < ny && !status; y++)
                for (size_t e = start[x * ny + y]; e < start[x * ny + y + 1] && !status; e++) {
                    const size_t j = entry[e];
                    const double c[2] = {S->q[j], S->p[j]}, s[2] = {S->q[j + 1] - c[0], S->p[j + 1] - c[1]};
                    const double den = r[0] * s[1] - r[1] * s[0];
                    if (den == 0.0) continue;
                    const double w[2] = {c[0] - a[0], c[1] - a[1]};
                    const double t = (w[0] * s[1] - w[1] * s[0]) / den, v = (w[0] * r[1] - w[1] * r[0]) / den;
                    /* half-open on both segments, so that a crossing at a shared end is counted once */
                    if (!(t >= 0.0 && t < 1.0 && v >= 0.0 && v < 1.0)) continue;
                    const double X = a[0] + t * r[0], Y = a[1] + t * r[1], sv = S->u[j] + v * (S->u[j + 1] - S->u[j]);
                    int again = 0;
                    for (size_t f = first; f < found; f++) again |= out->crossing[f].s == sv;
                    if (again) continue;
                    status = grow((void **)&out->crossing, &cap, found + 1, sizeof *out->crossing);
                    if (status) break;
                    const double sine = fabs(den) / (hypot(r[0], r[1]) * hypot(s[0], s[1]));
                    out->crossing[found++] = (gb_melnikov_crossing){U->u[i] + t * (U->u[i + 1] - U->u[i]), sv, X, Y,
                                                                    asin(fmin(1.0, sine)), -1, i, j};
                }
    }
    free(start), free(entry), free(fill);
    out->crossings = found;
    if (found) qsort(out->crossing, found, sizeof *out->crossing, by_u);
    return status;
}

/* ---- a crossing confirmed on the curves themselves ------------------------------------------------ */

/* A piece of one branch's iterate k over σ ∈ [a, b], as a polyline within about CHORD of the curve: a chord
 * is split while its midpoint's image lies farther than CHORD from its line or it is longer than the
 * spacing / 4 (50 halvings at most: a kink, where the flow crossed a tie line, ends there). */
enum { CHORD_DEPTH = 50 };
static const double CHORD = 1e-6;
static const double SAME_CROSSING = 1e-4; /* in u and in s: the same crossing confirmed twice */

typedef struct piece {
    double *sigma, *y; /* y: (q, p) pairs */
    size_t n, cap;
} piece;

static int piece_push(piece *c, const point *a)
{
    if (c->n + 1 > c->cap) {
        const size_t cap = c->cap ? 2 * c->cap : 64;
        double *sg = realloc(c->sigma, cap * sizeof *sg);
        if (sg) c->sigma = sg;
        double *y = sg ? realloc(c->y, 2 * cap * sizeof *y) : NULL;
        if (!y) return gb_error_set(GB_ENOMEM, "out of memory for a crossing's curves");
        c->y = y, c->cap = cap;
    }
    c->sigma[c->n] = a->sigma, c->y[2 * c->n] = a->y[0], c->y[2 * c->n + 1] = a->y[1], c->n++;
    return GB_OK;
}

static int piece_refine(branch *b, const point *a, const point *c, int k, int depth, piece *out)
{
    point mid;
    int status = GB_OK;
    if (depth < CHORD_DEPTH && c->sigma - a->sigma > 1e-15) {
        status = image(b, 0.5 * (a->sigma + c->sigma), k, &mid);
        if (status) return status;
        /* the midpoint's distance from the chord's line: along the chord it only moves the parameter */
        const double r[2] = {c->y[0] - a->y[0], c->y[1] - a->y[1]}, w[2] = {mid.y[0] - a->y[0], mid.y[1] - a->y[1]};
        const double length = hypot(r[0], r[1]);
        const double dev = length > 0.0 ? fabs(r[0] * w[1] - r[1] * w[0]) / length : hypot(w[0], w[1]);
        if (dev > CHORD || length > b->spacing / 4) {
            status = piece_refine(b, a, &mid, k, depth + 1, out);
            if (!status) status = piece_refine(b, &mid, c, k, depth + 1, out);
            return status;
        }
    }
    return piece_push(out, c);
}

/* The piece of segments i − 1 … i + 1 of a branch's curve (within the iterate of segment i). */
static int piece_around(branch *b, size_t i, piece *out)
{
    const int k = (int)floor(b->u[i]);
    const double lo = i > 0 && b->u[i - 1] >= k && b->u[i - 1] < b->u[i] ? b->u[i - 1] : b->u[i];
    const double hi = i + 2 < b->len && b->u[i + 2] <= k + 1 && b->u[i + 2] > b->u[i + 1] ? b->u[i + 2] : b->u[i + 1];
    point a, c;
    out->n = 0;
    int status = image(b, lo - k, k, &a);
    if (!status) status = image(b, hi - k, k, &c);
    if (!status) status = piece_push(out, &a);
    if (!status) status = piece_refine(b, &a, &c, k, 0, out);
    return status;
}

/* Crossing x stands when the two pieces around its segments cross: it then takes the nearest of their
 * crossings (u, s, point and angle from the fine chords); else it was the coarse chords' alone. */
static int confirm(branch *U, branch *S, gb_melnikov_crossing *x, piece *pu, piece *ps)
{
    int status = piece_around(U, x->segment_unstable, pu);
    if (!status) status = piece_around(S, x->segment_stable, ps);
    if (status) return status;
    const int ku = (int)floor(U->u[x->segment_unstable]), ks = (int)floor(S->u[x->segment_stable]);
    double best = INFINITY;
    x->confirmed = 0;
    for (size_t i = 0; i + 1 < pu->n; i++)
        for (size_t j = 0; j + 1 < ps->n; j++) {
            const double *a = pu->y + 2 * i, *c = ps->y + 2 * j;
            const double r[2] = {a[2] - a[0], a[3] - a[1]}, q[2] = {c[2] - c[0], c[3] - c[1]};
            const double den = r[0] * q[1] - r[1] * q[0], w[2] = {c[0] - a[0], c[1] - a[1]};
            if (den == 0.0) continue;
            const double t = (w[0] * q[1] - w[1] * q[0]) / den, v = (w[0] * r[1] - w[1] * r[0]) / den;
            if (!(t >= 0.0 && t < 1.0 && v >= 0.0 && v < 1.0)) continue;
            const double X = a[0] + t * r[0], Y = a[1] + t * r[1], d = hypot(X - x->q, Y - x->p);
            if (d >= best) continue;
            best = d, x->confirmed = 1, x->q = X, x->p = Y;
            x->u = ku + pu->sigma[i] + t * (pu->sigma[i + 1] - pu->sigma[i]);
            x->s = ks + ps->sigma[j] + v * (ps->sigma[j + 1] - ps->sigma[j]);
            x->angle = asin(fmin(1.0, fabs(den) / (hypot(r[0], r[1]) * hypot(q[0], q[1]))));
        }
    return GB_OK;
}

/* A branch's points kept in the result as (u, q, p) triples. */
static int keep_curve(const branch *b, gb_melnikov_tangle *out, int k)
{
    double *c = malloc((b->len ? b->len : 1) * 3 * sizeof *c);
    if (!c) return gb_error_set(GB_ENOMEM, "out of memory for the manifolds' curves");
    for (size_t i = 0; i < b->len; i++) c[3 * i] = b->u[i], c[3 * i + 1] = b->q[i], c[3 * i + 2] = b->p[i];
    out->curve[k] = c, out->curve_points[k] = b->len;
    return GB_OK;
}

static int def_check(const gb_melnikov_model *m, const gb_melnikov_forcing *f, const gb_melnikov_tangle_def *d)
{
    if (!(m->period > 0.0)) return gb_error_set(GB_EDOM, "the tangle is grown for a rotation only (allowed: period > 0)");
    if (!(d->epsilon > 0.0) || !isfinite(d->epsilon))
        return gb_error_set(GB_EDOM, "tangle epsilon = %g (allowed: finite and > 0)", d->epsilon);
    if (!isfinite(d->t0)) return gb_error_set(GB_EDOM, "tangle t0 = %g (allowed: finite)", d->t0);
    if (!(d->start >= 1e-12 && d->start <= 1e-3))
        return gb_error_set(GB_EDOM, "tangle start = %g (allowed: 1e-12 to 1e-3)", d->start);
    if (!(d->spacing >= 1e-4 && d->spacing <= 0.1))
        return gb_error_set(GB_EDOM, "tangle spacing = %g (allowed: 1e-4 to 0.1)", d->spacing);
    if (d->max_points < 100) return gb_error_set(GB_EDOM, "tangle max_points = %zu (allowed: 100 or more)", d->max_points);
    if (!(f->omega > 0.0) || !isfinite(f->omega))
        return gb_error_set(GB_EDOM, "tangle omega = %g (allowed: finite and > 0)", f->omega);
    return GB_OK;
}

int gb_melnikov_tangle_compute(const gb_melnikov_model *m, const gb_melnikov_orbit *o, const gb_melnikov_forcing *f,
                               const gb_melnikov_tangle_def *def, gb_melnikov_tangle *out)
{
    memset(out, 0, sizeof *out);
    out->smallest_angle = NAN;
    int status = def_check(m, f, def);
    if (status) return status;
    gb_melnikov_forced F = {m, f, def->epsilon, GB_OK};
    const double T = 2.0 * M_PI / f->omega;
    double x[2], vu[2], vs[2];
    status = gb_melnikov_saddle_orbit(&F, o->q_u, def->t0, x, vu, vs, out->multipliers);
    if (status) return status;
    if (!(out->multipliers[1] > 0.0))
        return gb_error_set(GB_EDOM, "the saddle's multipliers are %g and %g: a fundamental domain would alternate sides "
                            "(allowed: both positive)", out->multipliers[0], out->multipliers[1]);
    memcpy(out->saddle, x, sizeof x);
    /* the unperturbed passage between the two domains' first points (their q: `start` along each
     * eigenvector), in periods */
    const int dir = m->direction;
    double t_a, t_b;
    status = gb_melnikov_time(m, o, o->q_u + dir * def->start * fabs(vu[0]), &t_a);
    if (!status) status = gb_melnikov_time(m, o, o->q_end - dir * def->start * fabs(vs[0]), &t_b);
    if (status) return status;
    out->passage = fabs(t_b - t_a) / T;
    out->iterates = (int)ceil(0.5 * out->passage) + 2;
    out->window = (int)floor(0.5 * out->passage);
    /* the unstable branch leaves x towards `dir`; the stable one enters the copy x + dir P from behind */
    branch U = {.F = &F, .t0 = def->t0, .T = T, .x = {x[0], x[1]}, .v = {vu[0], vu[1]},
                .log_factor = log(out->multipliers[0]), .start = def->start, .spacing = def->spacing,
                .max_points = def->max_points};
    branch S = U;
    if (vu[0] * dir < 0.0) U.v[0] = -vu[0], U.v[1] = -vu[1];
    S.T = -T, S.x[0] = x[0] + dir * m->period, S.log_factor = -log(out->multipliers[1]);
    S.v[0] = vs[0], S.v[1] = vs[1];
    if (vs[0] * dir > 0.0) S.v[0] = -vs[0], S.v[1] = -vs[1];
    status = branch_grow(&U, out->iterates);
    if (!status) status = branch_grow(&S, out->iterates);
    if (!status) status = intersect(&U, &S, def->spacing, out);
    /* the window's crossings confirmed on fine pieces of the curves */
    piece pu = {0}, ps = {0};
    for (size_t i = 0; i < out->crossings && !status; i++) {
        gb_melnikov_crossing *x = &out->crossing[i];
        if (!(x->u >= out->window && x->u < out->window + 1)) continue;
        status = confirm(&U, &S, x, &pu, &ps);
        if (status || !x->confirmed) continue;
        /* two coarse crossings may confirm as the same one, placed by two pieces a little apart (each within
         * CHORD of the curves: a few 1e-6 in u and s at spacing 0.05) */
        int again = 0;
        for (size_t j = 0; j < i; j++)
            again |= out->crossing[j].confirmed == 1 && fabs(out->crossing[j].u - x->u) < SAME_CROSSING &&
                     fabs(out->crossing[j].s - x->s) < SAME_CROSSING;
        if (again) {
            x->confirmed = 0;
            continue;
        }
        out->in_window++;
        if (!(x->angle >= out->smallest_angle)) out->smallest_angle = x->angle;
    }
    free(pu.sigma), free(pu.y), free(ps.sigma), free(ps.y);
    if (!status && def->keep_curves) status = keep_curve(&U, out, 0);
    if (!status && def->keep_curves) status = keep_curve(&S, out, 1);
    out->points_unstable = U.len, out->points_stable = S.len;
    out->widest_gap = fmax(U.widest_gap, S.widest_gap);
    branch_free(&U), branch_free(&S);
    if (status) gb_melnikov_tangle_free(out);
    return status;
}

void gb_melnikov_tangle_free(gb_melnikov_tangle *t)
{
    free(t->crossing), free(t->curve[0]), free(t->curve[1]);
    t->crossing = NULL, t->crossings = 0, t->curve[0] = t->curve[1] = NULL, t->curve_points[0] = t->curve_points[1] = 0;
}

/* Whether the manifolds cross (a confirmed crossing in the window) with the harmonics scaled by s. */
static int crosses_at(const gb_melnikov_model *m, const gb_melnikov_orbit *o, const gb_melnikov_forcing *f,
                      const gb_melnikov_tangle_def *def, double s, int *crossed)
{
    gb_melnikov_forcing g = *f;
    g.nu1 *= s, g.nu2 *= s;
    gb_melnikov_tangle t;
    const int status = gb_melnikov_tangle_compute(m, o, &g, def, &t);
    *crossed = !status && t.in_window > 0;
    gb_melnikov_tangle_free(&t);
    return status;
}

int gb_melnikov_tangle_threshold(const gb_melnikov_model *m, const gb_melnikov_orbit *o, const gb_melnikov_forcing *f,
                                 const gb_melnikov_tangle_def *def, int halvings, double bracket[2])
{
    bracket[0] = 0.0, bracket[1] = NAN;
    if (halvings < 0 || halvings > 30) return gb_error_set(GB_EDOM, "tangle threshold halvings = %d (allowed: 0 to 30)", halvings);
    int crossed = 0, status = GB_OK;
    double s = 1.0;
    for (; s <= 16.0 && !status; s *= 2.0) {
        status = crosses_at(m, o, f, def, s, &crossed);
        if (status || crossed) break;
        bracket[0] = s;
    }
    if (status) return status;
    if (!crossed) return bracket[1] = INFINITY, GB_OK;
    bracket[1] = s;
    for (int k = 0; k < halvings && !status; k++) {
        const double mid = 0.5 * (bracket[0] + bracket[1]);
        status = crosses_at(m, o, f, def, mid, &crossed);
        if (!status) bracket[crossed ? 1 : 0] = mid;
    }
    return status;
}
