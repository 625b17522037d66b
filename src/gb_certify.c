#include "gb_certify.h"
#include "gb_clock.h"

#include "gb_arena.h"
#include "gb_error.h"
#include "gb_certify_internal.h"
#include "gb_vec.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define BASIN_SLOTS 8
#define BASIN_MAX_HALF_WIDTH 0.25
#define BASIN_MIN_HALF_WIDTH 1e-3
/* Basins are built where the minimum lies within this distance of a chart's root boxes [rad]. */
#define BASIN_REACH 0.35
/* A FAR verdict is measured from the nearest of a few anchors (points of the surface, fixed while
 * they live): the checked minimum's, and one at each other minimum with a basin. A minimum farther than
 * this from every anchor gets an anchor of its own [body length]. */
#define ANCHOR_REACH 0.05
#define ANCHOR_SLOTS 4
/* |x| on the surface, bounded for every β < 1/4: r⁴ ≤ 1 + 4β < 2 */
#define SURFACE_RADIUS_BOUND 1.19


typedef enum reason { R_NONE = 0, R_FAR, R_SLOPE, R_NOMIN, R_BASIN, R_SPLIT } reason;

/* A box. Its enclosure lives apart (see quad), so the fields a check reads on its way down the tree
 * stay small and close together. */
typedef struct node {
    /* read by every walk that passes the box (the first 64 bytes) */
    struct node *child;                            /* four, or NULL */
    unsigned long epoch;                           /* the epoch of the kept verdict */
    double due;                                    /* SLOPE, NO-MIN: path length up to which it holds */
    double far_s, far_d;                           /* FAR: holds while far_s − path·far_d ≥ e_A − η (below) */
    unsigned long basin_serial;
    unsigned char region, depth, verdict, has_hint;
    unsigned int anchor;                           /* the serial of the anchor A of far_s, far_d */
    /* read when the box is tested */
    gb_surface_enclosure *e;
    double a_lo, a_hi, b_lo, b_hi;
    double xa_mag, xb_mag, xaa_mag, xbb_mag;       /* Lipschitz constants in the vertical (SLOPE, NO-MIN) */
    double hint_phi, hint_theta;                   /* last critical point found inside */
    double retest;                                 /* a split box is tested again as a whole from this path on */
} node;

/* Four children and their enclosures, taken together from a block (below). */
typedef struct quad {
    struct node n[4];
    gb_surface_enclosure e[4];
} quad;

typedef enum owner { OWNER_FREE = 0, OWNER_MINIMUM, OWNER_OTHER } owner;

typedef struct basin {
    owner owner;
    gb_surface_chart chart;
    double a_lo, a_hi, b_lo, b_hi;
    gb_interval x_aa[3], x_ab[3], x_bb[3];
    unsigned long serial;
    int valid, used;
    gb_contact_point point; /* its minimum at the current vertical */
} basin;

/* The split boxes' quads come from an arena (gb_arena: 2 MiB blocks, huge-page advice), released all at
 * once (a cache restart, or gb_certify_free): a run creates tens of thousands of quads and never frees
 * one alone. On this machine each first touch of a 4 KiB page cost about 5 µs (a virtualised page
 * fault), 10 % of the certified run before the arena. */

struct gb_certify {
    gb_surface surface;
    gb_certify_def def;
    node roots[GB_ROOT_COUNT];
    gb_surface_enclosure root_enclosures[GB_ROOT_COUNT];
    int roots_enclosed; /* the roots' enclosures are made by the first check (a run whose atlas answers needs none) */
    gb_arena quads;  /* every split box's four children */
    size_t nodes;
    unsigned long epoch, next_serial;
    basin basins[BASIN_SLOTS];
    double last_half_width;
    /* the trajectory of checked verticals */
    int has_previous;
    double previous[3], path;
    /* FAR verdicts' anchors: x_A, a serial (0: a free slot; a verdict whose serial is gone no longer
     * holds), e_A = H − d·x_A at the current check, and the last check that claimed it */
    struct anchor {
        double x[3], excess;
        unsigned int serial;
        size_t claimed;
    } anchors[ANCHOR_SLOTS];
    unsigned int next_anchor;
    int current_anchor;  /* the checked minimum's */
    gb_certify_stats stats;
};

typedef struct pass {
    double d[3];
    double H, eta;
    double ab[2][2];       /* the minimum's coordinates in chart POLAR_Z, POLAR_X */
    const gb_contact_refine_def *refine;
    gb_certify_result *out;
} pass;

gb_certify_def gb_certify_default_def(void)
{
    return (gb_certify_def){.height_tol = 1e-12, .max_depth = 24, .max_nodes = (size_t)1 << 18};
}

/* ---------------------------------------------------------------- boxes */

static void node_fill(const gb_certify *c, node *n, gb_surface_enclosure *e, int region, int depth, double a_lo,
                      double a_hi, double b_lo, double b_hi)
{
    memset(n, 0, sizeof *n);
    n->e = e;
    n->a_lo = a_lo, n->a_hi = a_hi, n->b_lo = b_lo, n->b_hi = b_hi;
    n->region = (unsigned char)region;
    n->depth = (unsigned char)depth;
    double mags[5];
    gb_certify_enclose_box(&c->surface, region, a_lo, a_hi, b_lo, b_hi, e, mags);
    n->xa_mag = mags[0], n->xb_mag = mags[1], n->xaa_mag = mags[2], n->xbb_mag = mags[4];
}

static quad *quad_take(gb_certify *c) { return gb_arena_take(&c->quads); }

/* Release every quad: the roots lose their children. */
static void quads_release(gb_certify *c)
{
    for (int k = 0; k < GB_ROOT_COUNT; k++) c->roots[k].child = NULL;
    gb_arena_release(&c->quads);
}

static int node_split(gb_certify *c, node *n)
{
    if (n->child) return GB_OK;
    quad *q = quad_take(c);
    if (!q) return gb_error_set(GB_ENOMEM, "out of memory for the contact certificate's boxes");
    const double am = 0.5 * (n->a_lo + n->a_hi), bm = 0.5 * (n->b_lo + n->b_hi);
    node_fill(c, &q->n[0], &q->e[0], n->region, n->depth + 1, n->a_lo, am, n->b_lo, bm);
    node_fill(c, &q->n[1], &q->e[1], n->region, n->depth + 1, am, n->a_hi, n->b_lo, bm);
    node_fill(c, &q->n[2], &q->e[2], n->region, n->depth + 1, n->a_lo, am, bm, n->b_hi);
    node_fill(c, &q->n[3], &q->e[3], n->region, n->depth + 1, am, n->a_hi, bm, n->b_hi);
    n->child = q->n;
    c->nodes += 4;
    if (n->depth + 1 > c->stats.deepest) c->stats.deepest = n->depth + 1;
    return GB_OK;
}

/* Is the interval Hessian d·x'' positive definite over the whole box? */
static int hessian_definite(const double d[3], const gb_interval aa[3], const gb_interval ab[3], const gb_interval bb[3])
{
    return gb_certify_definite(gb_certify_dot(d, aa), gb_certify_dot(d, ab), gb_certify_dot(d, bb));
}

static int point_in_node(const node *n, const double ab[2])
{
    return ab[0] >= n->a_lo + GB_CERTIFY_INSIDE_MARGIN && ab[0] <= n->a_hi - GB_CERTIFY_INSIDE_MARGIN &&
           gb_certify_inside_periodic(ab[1], n->b_lo, n->b_hi, GB_CERTIFY_INSIDE_MARGIN);
}

/* ---------------------------------------------------------------- basins */

static void basin_coordinates(const basin *b, const gb_contact_point *p, double ab[2])
{
    gb_surface_chart_coordinates(b->chart, p->phi, p->theta, &ab[0], &ab[1]);
}

static int basin_holds(const basin *b, const double ab[2])
{
    return ab[0] >= b->a_lo + GB_CERTIFY_INSIDE_MARGIN && ab[0] <= b->a_hi - GB_CERTIFY_INSIDE_MARGIN &&
           gb_certify_inside_periodic(ab[1], b->b_lo, b->b_hi, GB_CERTIFY_INSIDE_MARGIN);
}

/* Is the point in the middle half of the basin (so a new one need not be built yet)? */
static int basin_holds_well(const basin *b, const double ab[2])
{
    const double qa = 0.25 * (b->a_hi - b->a_lo), qb = 0.25 * (b->b_hi - b->b_lo);
    return ab[0] >= b->a_lo + qa && ab[0] <= b->a_hi - qa && gb_certify_inside_periodic(ab[1], b->b_lo, b->b_hi, qb);
}

/* Build a basin of `point` in `chart`: the widest centred box (halving from the last width that
 * worked, doubled) on which d·x'' is positive definite. 0 when none down to BASIN_MIN_HALF_WIDTH. */
static int basin_build(gb_certify *c, basin *b, gb_surface_chart chart, const double ab[2], const double d[3],
                       const gb_contact_point *point, owner who, double last_half_width)
{
    double w = gb_interval_min(BASIN_MAX_HALF_WIDTH, 2.0 * last_half_width);
    for (; w >= BASIN_MIN_HALF_WIDTH; w *= 0.5) {
        /* stay clear of the chart's own poles (a = 0, π) */
        const double a_lo = gb_interval_max(ab[0] - w, 0.05), a_hi = gb_interval_min(ab[0] + w, M_PI - 0.05);
        if (!(ab[0] > a_lo + GB_CERTIFY_INSIDE_MARGIN && ab[0] < a_hi - GB_CERTIFY_INSIDE_MARGIN)) continue;
        gb_surface_enclosure e;
        gb_surface_enclose(&c->surface, chart, a_lo, a_hi, ab[1] - w, ab[1] + w, &e);
        if (!hessian_definite(d, e.x_aa, e.x_ab, e.x_bb)) continue;
        b->owner = who;
        b->chart = chart;
        b->a_lo = a_lo, b->a_hi = a_hi, b->b_lo = ab[1] - w, b->b_hi = ab[1] + w;
        memcpy(b->x_aa, e.x_aa, sizeof b->x_aa);
        memcpy(b->x_ab, e.x_ab, sizeof b->x_ab);
        memcpy(b->x_bb, e.x_bb, sizeof b->x_bb);
        b->serial = ++c->next_serial;
        b->valid = 1;
        b->used = 1;
        b->point = *point;
        c->stats.basins_built++;
        if (who == OWNER_MINIMUM) {
            c->last_half_width = w;
            c->stats.minimum_basins++;
            c->stats.basin_log_width_sum += log(w);
        }

        return 1;
    }
    return 0;
}

static basin *basin_slot(gb_certify *c)
{
    for (int k = 0; k < BASIN_SLOTS; k++)
        if (c->basins[k].owner == OWNER_FREE) return &c->basins[k];
    /* all taken: reuse the first one that is not valid now, else the oldest */
    basin *oldest = &c->basins[0];
    for (int k = 0; k < BASIN_SLOTS; k++) {
        if (!c->basins[k].valid) return &c->basins[k];
        if (c->basins[k].serial < oldest->serial) oldest = &c->basins[k];
    }
    return oldest;
}

/* Is the minimum near enough to a region of `chart` that boxes there may need its basin? */
static int chart_needs_basin(gb_surface_chart chart, const double ab[2])
{
    for (int r = 0; r < GB_REGIONS; r++) {
        if (gb_region_chart(r) != chart) continue;
        const double *g = gb_region_range[r];
        if (ab[0] >= g[0] - BASIN_REACH && ab[0] <= g[1] + BASIN_REACH &&
            (r == GB_REGION_EQUATOR || gb_certify_inside_periodic(ab[1], g[2] - BASIN_REACH, g[3] + BASIN_REACH, 0.0)))
            return 1;
    }
    return 0;
}

/* Bring the basins to the vertical d: drop those no longer definite or without their minimum, move the
 * other minima's basins along by Newton, and make sure the checked minimum has a basin in every chart
 * near it. */
static int basins_update(gb_certify *c, pass *p, const gb_contact_point *minimum)
{
    for (int k = 0; k < BASIN_SLOTS; k++) {
        basin *b = &c->basins[k];
        if (b->owner == OWNER_FREE) continue;
        b->valid = 0;
        double ab[2];
        basin_coordinates(b, minimum, ab);
        if (basin_holds(b, ab)) {
            /* it holds the checked minimum (where the basin is definite, its one critical point) */
            b->owner = OWNER_MINIMUM;
            b->point = *minimum;
        } else if (b->owner == OWNER_MINIMUM || b->used) {
            /* another minimum's, or the one checked before (two minima near a tie take turns as the lower):
             * its minimum continued by Newton */
            gb_contact_point q;
            if (gb_contact_refine(&c->surface, p->d, b->point.phi, b->point.theta, p->refine, &q) || !q.is_minimum) {
                b->owner = OWNER_FREE;
                continue;
            }
            p->out->newton_runs++;
            b->owner = OWNER_OTHER;
            b->point = q;
            basin_coordinates(b, &b->point, ab);
        } else {
            b->owner = OWNER_FREE; /* an other minimum's basin no box used */
            continue;
        }
        b->valid = basin_holds(b, ab) && hessian_definite(p->d, b->x_aa, b->x_ab, b->x_bb);
        if (!b->valid && b->owner == OWNER_OTHER) b->owner = OWNER_FREE;
        b->used = 0;
        /* an other minimum that drifted out of its basin's middle half: centred again, as the checked
         * minimum's are below (a tied second minimum moves as far as the checked one) */
        if (b->valid && b->owner == OWNER_OTHER && !basin_holds_well(b, ab)) {
            const basin old = *b;
            if (!basin_build(c, b, b->chart, ab, p->d, &old.point, OWNER_OTHER, 0.5 * (old.b_hi - old.b_lo))) *b = old;
        }
    }
    for (int chart = 0; chart < 2; chart++) {
        const double *ab = p->ab[chart];
        if (!chart_needs_basin((gb_surface_chart)chart, ab)) continue;
        int have = 0;
        for (int k = 0; k < BASIN_SLOTS && !have; k++) {
            const basin *b = &c->basins[k];
            have = b->valid && b->owner == OWNER_MINIMUM && b->chart == (gb_surface_chart)chart && basin_holds_well(b, ab);
        }
        if (!have) basin_build(c, basin_slot(c), (gb_surface_chart)chart, ab, p->d, minimum, OWNER_MINIMUM, c->last_half_width);
    }
    return GB_OK;
}

/* ---------------------------------------------------------------- the pass */

enum { SETTLED = 0, FOUND = 1, UNDECIDED = 2 };

static int lower_found(pass *p, const gb_contact_point *q)
{
    p->out->lower = *q;
    return FOUND;
}

static int visit(gb_certify *c, node *n, pass *p, int *status);

/* The kept verdict of a box settled by basin `serial`: SETTLED or FOUND while that basin is valid (its
 * minimum then bounds the box from below), −1 when it is gone. */
static int basin_verdict(gb_certify *c, pass *p, unsigned long serial)
{
    for (int k = 0; k < BASIN_SLOTS; k++) {
        basin *b = &c->basins[k];
        if (b->serial != serial || !b->valid) continue;
        b->used = 1;
        return b->point.height >= p->H - p->eta ? SETTLED : lower_found(p, &b->point);
    }
    return -1;
}

/* ---------------------------------------------------------------- anchors */

/* The anchor with this serial, or NULL when its slot was taken by another (its verdicts then lapse). */
static const struct anchor *anchor_of(const gb_certify *c, unsigned int serial)
{
    for (int k = 0; serial && k < ANCHOR_SLOTS; k++)
        if (c->anchors[k].serial == serial) return &c->anchors[k];
    return NULL;
}

/* Does the FAR relation (s, d) from anchor `serial` hold at the current path? */
static int far_holds(const gb_certify *c, const pass *p, unsigned int serial, double s, double d)
{
    const struct anchor *a = anchor_of(c, serial);
    return a && s - c->path * d >= a->excess - p->eta + GB_CERTIFY_SLACK_ROUNDING;
}

/* The anchor nearest x within ANCHOR_REACH, else a new one at x in a free slot or the one claimed longest
 * ago (never slot `keep`); claimed by this check. Its slot. */
static int anchor_claim(gb_certify *c, const double x[3], int keep)
{
    int best = -1;
    double nearest = ANCHOR_REACH;
    for (int k = 0; k < ANCHOR_SLOTS; k++) {
        const double *a = c->anchors[k].x, dx[3] = {x[0] - a[0], x[1] - a[1], x[2] - a[2]};
        if (c->anchors[k].serial && gb_vec_norm(dx) <= nearest) best = k, nearest = gb_vec_norm(dx);
    }
    if (best < 0) {
        for (int k = 0; k < ANCHOR_SLOTS; k++) {
            if (k == keep) continue;
            if (best < 0 || !c->anchors[k].serial ||
                (c->anchors[best].serial && c->anchors[k].claimed < c->anchors[best].claimed))
                best = k;
        }
        if (++c->next_anchor == 0) { /* the serials wrapped: no kept verdict may name a reused one */
            c->epoch++;
            c->next_anchor = 1;
        }
        memcpy(c->anchors[best].x, x, sizeof c->anchors[best].x);
        c->anchors[best].serial = c->next_anchor;
    }
    c->anchors[best].claimed = c->stats.checks + 1;
    return best;
}

/* The FAR verdicts of a split box's children, (s_i, d_i), hold while s_i − path·d_i ≥ e_A − η. Their
 * minimum f(path) = min_i (s_i − path·d_i) is concave, so on [p0, p1] it lies above its chord: the box
 * keeps that chord as (far_s, far_d), valid up to p1 (a due). p0 is the current path and p1 the path at
 * which the first child would expire at the current e_A; beyond p1 the box is walked again. Taking
 * min s_i with max d_i instead, one near child and one far child together would expire at once. */
static void far_chord(const gb_certify *c, const pass *p, double excess, const double s[4], const double d[4], int count,
                      double *far_s, double *far_d, double *due)
{
    const double p0 = c->path, level = excess - p->eta + GB_CERTIFY_SLACK_ROUNDING;
    double p1 = INFINITY, steepest = 0.0, f0 = INFINITY;
    for (int k = 0; k < count; k++) {
        f0 = gb_interval_min(f0, s[k] - p0 * d[k]);
        steepest = gb_interval_max(steepest, d[k]);
        if (d[k] > 0.0) p1 = gb_interval_min(p1, (s[k] - level) / d[k]);
    }
    if (count == 0) {
        *far_s = INFINITY, *far_d = 0.0;
        return;
    }
    if (!(p1 > p0 * (1.0 + 1e-12) + 1e-15) || !isfinite(p1)) {
        /* through (p0, f0) with the steepest slope: below every child for every path ≥ p0 */
        *far_d = steepest;
        *far_s = f0 + p0 * steepest;
        return;
    }
    double f1 = INFINITY;
    for (int k = 0; k < count; k++) f1 = gb_interval_min(f1, s[k] - p1 * d[k]);
    *far_d = (f0 - f1) / (p1 - p0) * (1.0 + 1e-12);
    *far_s = f0 + p0 * *far_d - GB_CERTIFY_SLACK_ROUNDING;
    *due = gb_interval_min(*due, p1);
}

/* A split box keeps the weakest of its children's kept verdicts: the earliest due of the SLOPE and
 * NO-MIN ones, the chord of the FAR ones (far_chord), and the basin of the BASIN ones when they share
 * one. While all hold, the whole subtree holds without being walked. Children settled by different
 * basins, or a child not settled, leave the box to be walked at every check. */
static int visit_children(gb_certify *c, node *n, pass *p, int *status)
{
    int undecided = 0, fars = 0;
    double due = INFINITY, far_s = INFINITY, far_d = 0.0, child_s[4], child_d[4];
    unsigned long serial = 0;
    const struct anchor *to = NULL; /* the box's anchor: its first FAR child's; the others' relations moved to it */
    for (int k = 0; k < 4; k++) {
        const node *child = &n->child[k];
        const int r = visit(c, &n->child[k], p, status);
        if (*status || r == FOUND) {
            n->due = -INFINITY;
            return r;
        }
        undecided |= r == UNDECIDED;
        const reason v = child->epoch == c->epoch && r == SETTLED ? (reason)child->verdict : R_NONE;
        if (v == R_SLOPE || v == R_NOMIN || v == R_SPLIT) due = gb_interval_min(due, child->due);
        if ((v == R_FAR || v == R_SPLIT) && isfinite(child->far_s)) {
            /* from anchor B to A: d'·x − d'·x_A = (d'·x − d'·x_B) + d'·(x_B − x_A), and d'·(x_B − x_A) ≥
             * d·(x_B − x_A) − (path' − path) |x_B − x_A| */
            const struct anchor *from = anchor_of(c, child->anchor);
            if (!to) to = from;
            if (!from) {
                due = -INFINITY;
                continue;
            }
            const double gap[3] = {from->x[0] - to->x[0], from->x[1] - to->x[1], from->x[2] - to->x[2]};
            const double D = gb_vec_norm(gap) * (1.0 + 1e-12);
            child_s[fars] = from == to ? child->far_s : child->far_s + gb_vec_dot(p->d, gap) + c->path * D - GB_CERTIFY_SLACK_ROUNDING;
            child_d[fars++] = child->far_d + D;
        }
        const unsigned long child_serial = v == R_BASIN || v == R_SPLIT ? child->basin_serial : 0;
        if (child_serial && serial && child_serial != serial) due = -INFINITY;
        if (child_serial) serial = child_serial;
        if (v == R_NONE) due = -INFINITY;
    }
    far_chord(c, p, to ? to->excess : 0.0, child_s, child_d, fars, &far_s, &far_d, &due);
    n->due = due, n->far_s = far_s, n->far_d = far_d, n->basin_serial = serial, n->anchor = to ? to->serial : 0;
    return undecided ? UNDECIDED : SETTLED;
}

/* A basin holding the whole box, whose minimum then bounds the box from below. */
static const basin *basin_around(const gb_certify *c, const node *n)
{
    const gb_surface_chart chart = gb_region_chart(n->region);
    for (int k = 0; k < BASIN_SLOTS; k++) {
        const basin *b = &c->basins[k];
        if (b->valid && b->chart == chart && n->a_lo >= b->a_lo && n->a_hi <= b->a_hi &&
            gb_certify_range_inside_periodic(n->b_lo, n->b_hi, b->b_lo, b->b_hi))
            return b;
    }
    return NULL;
}

/* The box's kept verdict, if it still holds at this vertical: its answer, or −1 when the box must be tested
 * again. A split box whose own test lapsed recently goes to its children. */
static int kept_verdict(gb_certify *c, node *n, pass *p, int *status)
{
    if (n->epoch != c->epoch) return -1;
    switch ((reason)n->verdict) {
    case R_FAR:
        if (far_holds(c, p, n->anchor, n->far_s, n->far_d)) return SETTLED;
        break;
    case R_SLOPE:
    case R_NOMIN:
        if (c->path <= n->due) return SETTLED;
        break;
    case R_BASIN: {
        const int r = basin_verdict(c, p, n->basin_serial);
        if (r >= 0) return r;
        break;
    }
    case R_SPLIT:
        if (c->path <= n->due && (!isfinite(n->far_s) || far_holds(c, p, n->anchor, n->far_s, n->far_d))) {
            const int r = n->basin_serial ? basin_verdict(c, p, n->basin_serial) : SETTLED;
            if (r >= 0) return r;
        }
        /* tested again as a whole first (a coarse verdict may hold where its children lapsed), unless its
         * last such test missed by more than the vertical can have moved its bound since */
        if (c->path < n->retest) return visit_children(c, n, p, status);
        break;
    case R_NONE:
        break;
    }
    return -1;
}

/* A box whose interval Hessian is positive definite holds at most one critical point, a strict minimum: the
 * checked minimum itself, another known one (with a basin), or one Newton finds in it (then kept with a
 * basin). Its answer, or −1 when none of them settles it. */
static int definite_box(gb_certify *c, node *n, pass *p)
{
    const double *d = p->d;
    const gb_surface_chart chart = gb_region_chart(n->region);
    if (point_in_node(n, p->ab[chart])) return SETTLED; /* its one critical point is the minimum */
    for (int k = 0; k < BASIN_SLOTS; k++) {
        /* ... or another minimum already known (with a basin, continued to this vertical) */
        basin *o = &c->basins[k];
        double qab[2];
        if (!o->valid || o->owner != OWNER_OTHER || o->chart != chart) continue;
        basin_coordinates(o, &o->point, qab);
        if (!point_in_node(n, qab)) continue;
        o->used = 1;
        return o->point.height >= p->H - p->eta ? SETTLED : lower_found(p, &o->point);
    }
    if (n->depth >= 1 && !(n->child && !n->has_hint)) { /* a box split before without a point found: its children */
        double phi, theta;
        if (n->has_hint) {
            phi = n->hint_phi, theta = n->hint_theta;
        } else {
            gb_surface_chart_angles(chart, 0.5 * (n->a_lo + n->a_hi), 0.5 * (n->b_lo + n->b_hi), &phi, &theta);
        }
        gb_contact_point q;
        p->out->newton_runs++;
        if (gb_contact_refine(&c->surface, d, phi, theta, p->refine, &q) == GB_OK && q.is_minimum) {
            double qab[2];
            gb_surface_chart_coordinates(chart, q.phi, q.theta, &qab[0], &qab[1]);
            if (point_in_node(n, qab)) {
                n->has_hint = 1;
                n->hint_phi = q.phi, n->hint_theta = q.theta;
                if (q.height < p->H - p->eta) return lower_found(p, &q);
                /* keep a basin for it, so the next checks settle the box without Newton */
                basin_build(c, basin_slot(c), chart, qab, d, &q, OWNER_OTHER, c->last_half_width);
                return SETTLED;
            }
        }
    }
    return -1;
}

/* One box at this vertical: its kept verdict if it holds, else its tests (FAR, BASIN, SLOPE, NO-MIN, a
 * definite Hessian) in that order, else its children. */
static int visit(gb_certify *c, node *n, pass *p, int *status)
{
    const int kept = kept_verdict(c, n, p, status);
    if (kept >= 0) return kept;
    p->out->boxes_tested++;
    n->epoch = c->epoch;
    n->verdict = R_NONE;
    const double *d = p->d;
    /* FAR: nothing in the box lower than H − η. */
    /* h's interval Hessian over the box: the Taylor bound of FAR and the NO-MIN and definiteness tests */
    const gb_interval Haa = gb_certify_dot(d, n->e->x_aa), Hab = gb_certify_dot(d, n->e->x_ab), Hbb = gb_certify_dot(d, n->e->x_bb);
    const double h_lo = gb_certify_height_lower_bound(d, n->e, Haa, Hab, Hbb);
    const double slack = h_lo - (p->H - p->eta) - GB_CERTIFY_SLACK_ROUNDING;
    if (slack > 0.0) {
        /* For q in the box and a later vertical d': d'·x(q) − d'·x_A ≥ (lb − d·x_A) − |d' − d|·max|x(q) − x_A|,
         * from the anchor that makes max|x(q) − x_A| the smallest. */
        const struct anchor *a = NULL;
        n->far_d = INFINITY;
        for (int j = 0; j < ANCHOR_SLOTS; j++) {
            const struct anchor *b = &c->anchors[j];
            if (!b->serial) continue;
            gb_interval rel[3];
            for (int k = 0; k < 3; k++) rel[k] = (gb_interval){n->e->x[k].lo - b->x[k], n->e->x[k].hi - b->x[k]};
            const double reach = gb_certify_norm_of_mags(rel);
            if (reach < n->far_d) n->far_d = reach, a = b;
        }
        n->verdict = R_FAR;
        n->anchor = a->serial;
        n->far_s = (h_lo - gb_vec_dot(d, a->x)) + c->path * n->far_d;
        n->due = INFINITY;
        return SETTLED;
    }
    /* BASIN */
    basin *b = (basin *)basin_around(c, n);
    if (b) {
        b->used = 1;
        n->verdict = R_BASIN;
        n->basin_serial = b->serial;
        return b->point.height >= p->H - p->eta ? SETTLED : lower_found(p, &b->point);
    }
    /* SLOPE: no critical point. */
    const gb_interval ga = gb_certify_dot(d, n->e->x_a), gb = gb_certify_dot(d, n->e->x_b);
    const double ma = gb_interval_max(ga.lo, -ga.hi) - GB_CERTIFY_SLACK_ROUNDING, mb = gb_interval_max(gb.lo, -gb.hi) - GB_CERTIFY_SLACK_ROUNDING;
    if (ma > 0.0 || mb > 0.0) {
        n->verdict = R_SLOPE;
        n->due = c->path + gb_interval_max(ma > 0.0 ? ma / n->xa_mag : 0.0, mb > 0.0 ? mb / n->xb_mag : 0.0);
        return SETTLED;
    }
    /* NO-MIN: where C², a minimum needs ∂_aa h ≥ 0, ∂_bb h ≥ 0 and det ≥ 0. */
    const double hab_max = gb_interval_max(fabs(Hab.lo), fabs(Hab.hi));
    const double hab_min = Hab.lo * Hab.hi > 0.0 ? gb_interval_min(fabs(Hab.lo), fabs(Hab.hi)) : 0.0;
    const double prod_max = gb_interval_max(gb_interval_max(Haa.lo * Hbb.lo, Haa.lo * Hbb.hi), gb_interval_max(Haa.hi * Hbb.lo, Haa.hi * Hbb.hi));
    if (n->e->smooth) {
        const double na = -Haa.hi - GB_CERTIFY_HESSIAN_ROUNDING, nb = -Hbb.hi - GB_CERTIFY_HESSIAN_ROUNDING;
        if (na > 0.0 || nb > 0.0) {
            n->verdict = R_NOMIN;
            n->far_s = INFINITY, n->far_d = 0.0;
            n->due = c->path + gb_interval_max(na > 0.0 ? na / n->xaa_mag : 0.0, nb > 0.0 ? nb / n->xbb_mag : 0.0);
            return SETTLED;
        }
        if (prod_max + GB_CERTIFY_HESSIAN_ROUNDING < hab_min * hab_min) return SETTLED; /* det < 0: saddles only */
    }
    /* A positive-definite interval Hessian: at most one critical point in the box (the gradient map
     * is injective on it, by the mean-value theorem), and h is strictly convex there. */
    const int definite = Haa.lo > GB_CERTIFY_HESSIAN_ROUNDING && Hbb.lo > GB_CERTIFY_HESSIAN_ROUNDING &&
                         Haa.lo * Hbb.lo - hab_max * hab_max > GB_CERTIFY_HESSIAN_ROUNDING;
    if (definite) {
        const int r = definite_box(c, n, p);
        if (r >= 0) return r;
    }
    if (n->depth >= c->def.max_depth) return UNDECIDED;
    /* FAR missed by −slack; d·x moves by at most |x| ≤ SURFACE_RADIUS_BOUND per unit of path, and so does H */
    if (n->child) n->retest = c->path + -slack / (2.0 * SURFACE_RADIUS_BOUND);
    *status = node_split(c, n);
    if (*status) return UNDECIDED;
    n->verdict = R_SPLIT;
    return visit_children(c, n, p, status);
}

/* ---------------------------------------------------------------- public */

static void restart_cache(gb_certify *c)
{
    quads_release(c);
    c->nodes = GB_ROOT_COUNT;
    c->epoch++;
    c->stats.cache_restarts++;
}

int gb_certify_create(const gb_surface *surface, const gb_certify_def *def, gb_certify **out)
{
    *out = NULL;
    if (!surface->morphology->kernel_jet)
        return gb_error_set(GB_EINVAL, "the body '%s' has no interval enclosure: it cannot be certified (allowed: a "
                            "morphology of the paper, I or II)", surface->morphology->name);
    if (!(def->height_tol >= 0.0 && def->height_tol <= 1e-3))
        return gb_error_set(GB_EDOM, "certificate height tolerance %g is out of range (allowed: [0, 1e-3])", def->height_tol);
    if (def->max_depth < 0 || def->max_depth > 40)
        return gb_error_set(GB_EDOM, "certificate max_depth %d is out of range (allowed: 0..40)", def->max_depth);
    if (def->time_checks != 0 && def->time_checks != 1)
        return gb_error_set(GB_EDOM, "certificate time_checks %d is out of range (allowed: 0 or 1)", def->time_checks);
    if (def->max_nodes < 4 * (size_t)GB_ROOT_COUNT)
        return gb_error_set(GB_EDOM, "certificate max_nodes %zu is out of range (allowed: >= %d)", def->max_nodes,
                            4 * GB_ROOT_COUNT);
    gb_certify *c = calloc(1, sizeof *c);
    if (!c) return gb_error_set(GB_ENOMEM, "out of memory for the contact certificate");
    c->surface = *surface;
    c->def = *def;
    gb_arena_init(&c->quads, sizeof(quad));
    c->epoch = 1;
    c->last_half_width = BASIN_MAX_HALF_WIDTH;
    for (int k = 0; k < GB_ROOT_COUNT; k++) { /* their boxes; enclosed by roots_enclose */
        int region;
        double box[4];
        gb_root_box(k, &region, box);
        node *n = &c->roots[k];
        n->a_lo = box[0], n->a_hi = box[1], n->b_lo = box[2], n->b_hi = box[3];
        n->region = (unsigned char)region;
    }
    c->nodes = GB_ROOT_COUNT;
    *out = c;
    return GB_OK;
}

void gb_certify_free(gb_certify *c)
{
    if (!c) return;
    quads_release(c);
    free(c);
}

void gb_certify_forget(gb_certify *c)
{
    c->epoch++;
    c->has_previous = 0;
}

static int certify_check(gb_certify *c, const double zb[3], const gb_contact_point *minimum,
                         const gb_contact_refine_def *refine, gb_certify_result *out);


int gb_certify_check(gb_certify *c, const double zb[3], const gb_contact_point *minimum,
                     const gb_contact_refine_def *refine, gb_certify_result *out)
{
    if (!c->def.time_checks) return certify_check(c, zb, minimum, refine, out);
    const double start = gb_wall_seconds();
    const int status = certify_check(c, zb, minimum, refine, out);
    c->stats.check_seconds += gb_wall_seconds() - start;
    return status;
}

/* The root boxes enclosed, once, before a check first reads them (as gb_certify_create once did). */
static void roots_enclose(gb_certify *c)
{
    if (c->roots_enclosed) return;
    for (int k = 0; k < GB_ROOT_COUNT; k++) {
        node *n = &c->roots[k];
        node_fill(c, n, &c->root_enclosures[k], n->region, 0, n->a_lo, n->a_hi, n->b_lo, n->b_hi);
    }
    c->roots_enclosed = 1;
}

static int certify_check(gb_certify *c, const double zb[3], const gb_contact_point *minimum,
                         const gb_contact_refine_def *refine, gb_certify_result *out)
{
    memset(out, 0, sizeof *out);
    roots_enclose(c);
    pass p = {.eta = c->def.height_tol, .refine = refine, .out = out};
    int status = gb_contact_unit_vertical(zb, p.d);
    if (status) return status;
    if (c->nodes > c->def.max_nodes) restart_cache(c);
    if (c->has_previous) {
        const double step[3] = {p.d[0] - c->previous[0], p.d[1] - c->previous[1], p.d[2] - c->previous[2]};
        c->path += gb_vec_norm(step) * (1.0 + 1e-12);
    }
    p.H = gb_vec_dot(p.d, minimum->rc);
    /* FAR verdicts are anchored at points x_A with H = d·x_A + e_A: the minimum's anchor first */
    c->current_anchor = anchor_claim(c, minimum->rc, -1);
    memcpy(c->previous, p.d, sizeof c->previous);
    c->has_previous = 1;
    for (int chart = 0; chart < 2; chart++)
        gb_surface_chart_coordinates((gb_surface_chart)chart, minimum->phi, minimum->theta, &p.ab[chart][0], &p.ab[chart][1]);
    status = basins_update(c, &p, minimum);
    if (status) return status;
    /* ... then one at each other minimum with a basin (boxes near it have small margins, which an
     * anchor far away would spend at once), and every anchor's e_A at this vertical */
    for (int k = 0; k < BASIN_SLOTS; k++)
        if (c->basins[k].valid && c->basins[k].owner == OWNER_OTHER) anchor_claim(c, c->basins[k].point.rc, c->current_anchor);
    for (int k = 0; k < ANCHOR_SLOTS; k++)
        if (c->anchors[k].serial) c->anchors[k].excess = p.H - gb_vec_dot(p.d, c->anchors[k].x);
    int verdict = SETTLED;
    for (int k = 0; k < GB_ROOT_COUNT && verdict != FOUND && !status; k++) {
        const int r = visit(c, &c->roots[k], &p, &status);
        if (r != SETTLED) verdict = r;
    }
    if (status) return status;
    out->verdict = verdict == FOUND ? GB_CERTIFY_LOWER_FOUND : verdict == UNDECIDED ? GB_CERTIFY_UNDECIDED : GB_CERTIFY_GLOBAL;
    c->stats.checks++;
    c->stats.global += out->verdict == GB_CERTIFY_GLOBAL;
    c->stats.lower_found += out->verdict == GB_CERTIFY_LOWER_FOUND;
    c->stats.undecided += out->verdict == GB_CERTIFY_UNDECIDED;
    c->stats.boxes_tested += out->boxes_tested;
    c->stats.newton_runs += out->newton_runs;
    return GB_OK;
}

int gb_certify_first_candidate(const gb_certify *c, const double zb[3], const gb_contact_refine_def *refine,
                               double d[3], gb_contact_point *out)
{
    int status = gb_contact_unit_vertical(zb, d);
    if (status) return status;
    /* start: the lowest root-box centre */
    double best = INFINITY, phi0 = 0.0, theta0 = 0.0;
    for (int k = 0; k < GB_ROOT_COUNT; k++) {
        const node *n = &c->roots[k];
        double phi, theta, x[3];
        gb_surface_chart_angles(gb_region_chart(n->region), 0.5 * (n->a_lo + n->a_hi), 0.5 * (n->b_lo + n->b_hi), &phi, &theta);
        gb_surface_position(&c->surface, phi, theta, x);
        const double h = gb_vec_dot(d, x);
        if (h < best) best = h, phi0 = phi, theta0 = theta;
    }
    return gb_contact_refine(&c->surface, d, phi0, theta0, refine, out);
}

int gb_certify_global_minimum(gb_certify *c, const double zb[3], const gb_contact_refine_def *refine,
                              gb_contact_point *out)
{
    double d[3];
    int status = gb_certify_first_candidate(c, zb, refine, d, out);
    for (int round = 0; !status && round < 64; round++) {
        gb_certify_result r;
        status = gb_certify_check(c, d, out, refine, &r);
        if (status) return status;
        if (r.verdict == GB_CERTIFY_GLOBAL) return GB_OK;
        if (r.verdict == GB_CERTIFY_UNDECIDED)
            return gb_error_set(GB_ENOCONV, "the global contact for z_b = (%g, %g, %g) could not be certified: a box "
                                "at the deepest split level (%d) stayed undecided", d[0], d[1], d[2], c->def.max_depth);
        *out = r.lower;
    }
    if (!status) status = gb_error_set(GB_ENOCONV, "the global contact search did not settle in 64 rounds");
    return status;
}

void gb_certify_get_stats(const gb_certify *c, gb_certify_stats *out)
{
    *out = c->stats;
    out->boxes_kept = c->nodes;
}
