#include "gb_atlas.h"
#include "gb_clock.h"

#include "gb_arena.h"
#include "gb_file.h"
#include "gb_certify_internal.h"
#include "gb_error.h"
#include "gb_seal.h"
#include "gb_vec.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <time.h>
#include <unistd.h>

/* Site boxes are built where the minimum lies within this distance of a chart's root boxes [rad]
 * (as gb_certify's basins). */
#define SITE_REACH 0.1
#define SITE_MAX_HALF_WIDTH 0.3
#define SITE_MIN_HALF_WIDTH 2e-3
#define SITE_WIDTH_STEP 0.75
/* A site box's Hessian is tested on one enclosure, or on its 4 or 16 sub-boxes (each must pass). */
#define SITE_SPLITS 2
/* Two minima closer than this are the same site [body length]. */
#define SAME_POINT 1e-7

enum { CELL_UNBUILT = 0, CELL_SPLIT = 1, CELL_CERTIFIED = 2, CELL_FAILED = 3 };
enum { SETTLED = 0, UNSETTLED = 1 };

/* A box of the surface cover, kept with its enclosure for every cell's proof. */
typedef struct box {
    struct box *child; /* four, or NULL */
    gb_surface_enclosure *e;
    double a_lo, a_hi, b_lo, b_hi;
    double xa_mag, xb_mag, xaa_mag, xab_mag, xbb_mag; /* bounds of |x_a|, ... over the box */
    unsigned char region, depth;
} box;

typedef struct box_quad {
    box n[4];
    gb_surface_enclosure e[4];
} box_quad;

typedef struct site {
    int boxes;
    gb_atlas_site_box box[2];
    int looked_up[2];            /* 0: a polar-x box whose directions all lie in the (φ, θ) band (below) */
    double x0[3];                /* its minimum at the cell's centre (the FAR reference) */
    double hint_phi, hint_theta; /* where Newton starts: the last minimum found in it */
} site;

typedef struct cell {
    struct cell *child; /* four, or NULL */
    double u_lo, u_hi, v_lo, v_hi;
    unsigned char face, level, state, sites;
    site site[2];
} cell;

typedef struct cell_quad {
    cell c[4];
} cell_quad;

struct gb_atlas {
    gb_surface surface;
    gb_atlas_def def;
    gb_certify *certify; /* the global minimum at a cell's centre */
    box roots[GB_ROOT_COUNT];
    gb_surface_enclosure root_enclosures[GB_ROOT_COUNT];
    gb_arena box_quads, cell_quads;
    cell faces[6];
    cell *last; /* the cell of the last check */
    double last_half_width;
    gb_atlas_stats stats;
};

gb_atlas_def gb_atlas_default_def(void)
{
    return (gb_atlas_def){.height_tol = 1e-12, .first_level = 5, .max_level = 13, .max_depth = 14};
}


/* ---------------------------------------------------------------- the surface boxes */

static void box_fill(const gb_atlas *A, box *n, gb_surface_enclosure *e, int region, int depth, double a_lo, double a_hi,
                     double b_lo, double b_hi)
{
    memset(n, 0, sizeof *n);
    n->e = e;
    n->a_lo = a_lo, n->a_hi = a_hi, n->b_lo = b_lo, n->b_hi = b_hi;
    n->region = (unsigned char)region;
    n->depth = (unsigned char)depth;
    double mags[5];
    gb_certify_enclose_box(&A->surface, region, a_lo, a_hi, b_lo, b_hi, e, mags);
    n->xa_mag = mags[0], n->xb_mag = mags[1], n->xaa_mag = mags[2], n->xab_mag = mags[3], n->xbb_mag = mags[4];
}

static int box_split(gb_atlas *A, box *n)
{
    if (n->child) return GB_OK;
    box_quad *q = gb_arena_take(&A->box_quads);
    if (!q) return gb_error_set(GB_ENOMEM, "out of memory for the atlas's surface boxes");
    const double am = 0.5 * (n->a_lo + n->a_hi), bm = 0.5 * (n->b_lo + n->b_hi);
    box_fill(A, &q->n[0], &q->e[0], n->region, n->depth + 1, n->a_lo, am, n->b_lo, bm);
    box_fill(A, &q->n[1], &q->e[1], n->region, n->depth + 1, am, n->a_hi, n->b_lo, bm);
    box_fill(A, &q->n[2], &q->e[2], n->region, n->depth + 1, n->a_lo, am, bm, n->b_hi);
    box_fill(A, &q->n[3], &q->e[3], n->region, n->depth + 1, am, n->a_hi, bm, n->b_hi);
    n->child = q->n;
    A->stats.boxes += 4;
    return GB_OK;
}

/* An interval widened by r on both sides: d·v over the cell from d₀·v (|d − d₀| ≤ ρ, r = ρ|v|). */
static gb_interval widen(gb_interval a, double r) { return (gb_interval){a.lo - r, a.hi + r}; }

/* ---------------------------------------------------------------- the cells' geometry */

/* The unit vertical through (u, v) of a cube face: face = 2k + (1 for the −e_k face). */
static void face_point(int face, double u, double v, double d[3])
{
    const int k = face >> 1;
    double p[3];
    p[k] = face & 1 ? -1.0 : 1.0;
    p[(k + 1) % 3] = u;
    p[(k + 2) % 3] = v;
    const double n = gb_vec_norm(p);
    for (int i = 0; i < 3; i++) d[i] = p[i] / n;
}

static void face_of(const double d[3], int *face, double *u, double *v)
{
    int k = 0;
    if (fabs(d[1]) > fabs(d[k])) k = 1;
    if (fabs(d[2]) > fabs(d[k])) k = 2;
    const double m = fabs(d[k]);
    *face = 2 * k + (d[k] < 0.0);
    *u = d[(k + 1) % 3] / m;
    *v = d[(k + 2) % 3] / m;
}

/* The centre d₀ of a cell and a radius ρ ≥ |d − d₀| for every vertical of it. The cell's verticals are
 * the unit vectors of the convex cone spanned by its corners, and {d : d·d₀ ≥ t|d|} is a convex cone,
 * so the farthest vertical is a corner. The padding covers a vertical whose (u, v), rounded, fell in a
 * neighbouring cell. */
static void cell_geometry(const cell *c, double d0[3], double *rho)
{
    face_point(c->face, 0.5 * (c->u_lo + c->u_hi), 0.5 * (c->v_lo + c->v_hi), d0);
    double worst = 0.0;
    for (int k = 0; k < 4; k++) {
        double corner[3];
        face_point(c->face, k & 1 ? c->u_hi : c->u_lo, k & 2 ? c->v_hi : c->v_lo, corner);
        const double step[3] = {corner[0] - d0[0], corner[1] - d0[1], corner[2] - d0[2]};
        worst = gb_interval_max(worst, gb_vec_norm(step));
    }
    *rho = worst * (1.0 + 1e-12) + 1e-13;
}

static int cell_split(gb_atlas *A, cell *c)
{
    cell_quad *q = gb_arena_take(&A->cell_quads);
    if (!q) return gb_error_set(GB_ENOMEM, "out of memory for the atlas's cells");
    const double um = 0.5 * (c->u_lo + c->u_hi), vm = 0.5 * (c->v_lo + c->v_hi);
    for (int k = 0; k < 4; k++) {
        cell *child = &q->c[k];
        memset(child, 0, sizeof *child);
        child->face = c->face;
        child->level = (unsigned char)(c->level + 1);
        child->u_lo = k & 1 ? um : c->u_lo, child->u_hi = k & 1 ? c->u_hi : um;
        child->v_lo = k & 2 ? vm : c->v_lo, child->v_hi = k & 2 ? c->v_hi : vm;
    }
    c->child = q->c;
    c->state = CELL_SPLIT;
    if (c->level + 1 > A->stats.deepest_level) A->stats.deepest_level = c->level + 1;
    return GB_OK;
}

/* ---------------------------------------------------------------- sites */

static int site_box_holds(const gb_atlas_site_box *b, double a, double bb)
{
    return a >= b->a_lo + GB_CERTIFY_INSIDE_MARGIN && a <= b->a_hi - GB_CERTIFY_INSIDE_MARGIN &&
           gb_certify_inside_periodic(bb, b->b_lo, b->b_hi, GB_CERTIFY_INSIDE_MARGIN);
}

/* Does the point (φ, θ) lie inside every looked-up box of the site, and inside how many? */
static int site_holds(const site *s, double phi, double theta, int *count)
{
    int inside = 0, boxes = 0;
    for (int k = 0; k < s->boxes; k++) {
        if (!s->looked_up[k]) continue;
        double a, b;
        gb_surface_chart_coordinates(s->box[k].chart, phi, theta, &a, &b);
        inside += site_box_holds(&s->box[k], a, b);
        boxes++;
    }
    if (count) *count = inside;
    return inside == boxes;
}

/* Is every direction of a polar-x box inside the (φ, θ) band 0.8 ≤ φ ≤ π − 0.8, i.e. |u_z| ≤ cos 0.8
 * with u_z = sin α sin γ? A global minimum there lies in the band, whose boxes the proof settled
 * against the (φ, θ) site boxes, so it is in one of those: a check need not look in this box. (The
 * (φ, θ) boxes are always looked in, so the two charts never defer to each other.) */
static int inside_band(const gb_atlas_site_box *b)
{
    if (b->chart != GB_SURFACE_CHART_POLAR_X) return 0;
    const gb_interval uz = gb_interval_mul(gb_interval_sin((gb_interval){b->a_lo, b->a_hi}),
                                           gb_interval_sin((gb_interval){b->b_lo, b->b_hi}));
    return gb_interval_mag(uz) < cos(gb_region_range[GB_REGION_EQUATOR][0]) - 1e-12;
}

/* Is d·x'' positive definite over the box for every vertical of the cell? Tested on the box's
 * enclosure, else on its four quarters, down to `splits` levels. */
static int definite_over_cell(const gb_atlas *A, gb_surface_chart chart, double a_lo, double a_hi, double b_lo,
                              double b_hi, const double d0[3], double rho, int splits)
{
    gb_surface_enclosure e;
    gb_surface_enclose(&A->surface, chart, a_lo, a_hi, b_lo, b_hi, &e);
    const gb_interval Haa = widen(gb_certify_dot(d0, e.x_aa), rho * gb_certify_norm_of_mags(e.x_aa));
    const gb_interval Hab = widen(gb_certify_dot(d0, e.x_ab), rho * gb_certify_norm_of_mags(e.x_ab));
    const gb_interval Hbb = widen(gb_certify_dot(d0, e.x_bb), rho * gb_certify_norm_of_mags(e.x_bb));
    if (gb_certify_definite(Haa, Hab, Hbb)) return 1;
    if (splits == 0 || !(Haa.hi > 0.0 && Hbb.hi > 0.0)) return 0;
    const double am = 0.5 * (a_lo + a_hi), bm = 0.5 * (b_lo + b_hi);
    return definite_over_cell(A, chart, a_lo, am, b_lo, bm, d0, rho, splits - 1) &&
           definite_over_cell(A, chart, am, a_hi, b_lo, bm, d0, rho, splits - 1) &&
           definite_over_cell(A, chart, a_lo, am, bm, b_hi, d0, rho, splits - 1) &&
           definite_over_cell(A, chart, am, a_hi, bm, b_hi, d0, rho, splits - 1);
}

/* Is the point near enough to a region of `chart` that boxes there may need a site box? */
static int chart_needs_box(gb_surface_chart chart, double a, double b)
{
    for (int r = 0; r < GB_REGIONS; r++) {
        if (gb_region_chart(r) != chart) continue;
        const double *g = gb_region_range[r];
        if (a >= g[0] - SITE_REACH && a <= g[1] + SITE_REACH &&
            (r == GB_REGION_EQUATOR || gb_certify_inside_periodic(b, g[2] - SITE_REACH, g[3] + SITE_REACH, 0.0)))
            return 1;
    }
    return 0;
}

/* A site around the minimum p at the cell's centre: in each chart that needs one, the widest centred
 * box (from the last width that worked, ×1/SITE_WIDTH_STEP, down by SITE_WIDTH_STEP) on which d·x'' is
 * positive definite over the cell. 0 when a chart has none down to SITE_MIN_HALF_WIDTH. */
static int site_build(gb_atlas *A, const double d0[3], double rho, const gb_contact_point *p, site *s)
{
    memset(s, 0, sizeof *s);
    memcpy(s->x0, p->rc, sizeof s->x0);
    s->hint_phi = p->phi, s->hint_theta = p->theta;
    for (int chart = 0; chart < 2; chart++) {
        double a, b;
        gb_surface_chart_coordinates((gb_surface_chart)chart, p->phi, p->theta, &a, &b);
        if (!chart_needs_box((gb_surface_chart)chart, a, b)) continue;
        int built = 0;
        for (double w = gb_interval_min(SITE_MAX_HALF_WIDTH, A->last_half_width / SITE_WIDTH_STEP);
             w >= SITE_MIN_HALF_WIDTH && !built; w *= SITE_WIDTH_STEP) {
            const double a_lo = gb_interval_max(a - w, 0.05), a_hi = gb_interval_min(a + w, M_PI - 0.05);
            if (!(a > a_lo + GB_CERTIFY_INSIDE_MARGIN && a < a_hi - GB_CERTIFY_INSIDE_MARGIN)) continue;
            if (!definite_over_cell(A, (gb_surface_chart)chart, a_lo, a_hi, b - w, b + w, d0, rho, SITE_SPLITS)) continue;
            s->box[s->boxes] = (gb_atlas_site_box){(gb_surface_chart)chart, a_lo, a_hi, b - w, b + w};
            s->looked_up[s->boxes] = !inside_band(&s->box[s->boxes]);
            s->boxes++;
            A->last_half_width = w;
            built = 1;
        }
        if (!built) return 0;
    }
    return s->boxes > 0;
}

/* ---------------------------------------------------------------- a cell's proof */

typedef struct proof {
    double d0[3], rho;
    const site *site;
    int sites;
    const box *unsettled; /* the first box that did not settle */
} proof;

static int inside_site_box(const box *n, const gb_atlas_site_box *b)
{
    return b->chart == gb_region_chart(n->region) && n->a_lo >= b->a_lo && n->a_hi <= b->a_hi &&
           gb_certify_range_inside_periodic(n->b_lo, n->b_hi, b->b_lo, b->b_hi);
}

/* Settle box n for every vertical of the cell (see gb_atlas.h), splitting it as needed. */
static int settle(gb_atlas *A, box *n, proof *p, int *status)
{
    A->stats.boxes_tested++;
    for (int s = 0; s < p->sites; s++)
        for (int k = 0; k < p->site[s].boxes; k++)
            if (inside_site_box(n, &p->site[s].box[k])) return SETTLED;
    const gb_surface_enclosure *e = n->e;
    const double *d0 = p->d0, rho = p->rho;
    const gb_interval Haa0 = gb_certify_dot(d0, e->x_aa), Hab0 = gb_certify_dot(d0, e->x_ab), Hbb0 = gb_certify_dot(d0, e->x_bb);
    /* FAR: d·(x − x_s) ≥ d₀·(x − x_s) − ρ max|x − x_s| > 0: higher than the site's point for every d. */
    const double h_lo = gb_certify_height_lower_bound(d0, e, Haa0, Hab0, Hbb0);
    for (int s = 0; s < p->sites; s++) {
        const double *xs = p->site[s].x0;
        gb_interval rel[3];
        for (int k = 0; k < 3; k++) rel[k] = (gb_interval){e->x[k].lo - xs[k], e->x[k].hi - xs[k]};
        if (h_lo - gb_vec_dot(d0, xs) - rho * gb_certify_norm_of_mags(rel) > GB_CERTIFY_SLACK_ROUNDING) return SETTLED;
    }
    /* SLOPE: a first derivative keeps its sign for every d. */
    const gb_interval ga = widen(gb_certify_dot(d0, e->x_a), rho * n->xa_mag);
    const gb_interval gb = widen(gb_certify_dot(d0, e->x_b), rho * n->xb_mag);
    if (ga.lo > GB_CERTIFY_SLACK_ROUNDING || ga.hi < -GB_CERTIFY_SLACK_ROUNDING || gb.lo > GB_CERTIFY_SLACK_ROUNDING ||
        gb.hi < -GB_CERTIFY_SLACK_ROUNDING)
        return SETTLED;
    /* NO-MIN (where C²): a minimum needs ∂_aa h ≥ 0, ∂_bb h ≥ 0 and det ≥ 0. */
    if (e->smooth) {
        const gb_interval Haa = widen(Haa0, rho * n->xaa_mag), Hab = widen(Hab0, rho * n->xab_mag),
                          Hbb = widen(Hbb0, rho * n->xbb_mag);
        if (Haa.hi < -GB_CERTIFY_HESSIAN_ROUNDING || Hbb.hi < -GB_CERTIFY_HESSIAN_ROUNDING) return SETTLED;
        const double hab_min = Hab.lo * Hab.hi > 0.0 ? gb_interval_min(fabs(Hab.lo), fabs(Hab.hi)) : 0.0;
        const double prod_max = gb_interval_max(gb_interval_max(Haa.lo * Hbb.lo, Haa.lo * Hbb.hi),
                                                gb_interval_max(Haa.hi * Hbb.lo, Haa.hi * Hbb.hi));
        if (prod_max + GB_CERTIFY_HESSIAN_ROUNDING < hab_min * hab_min) return SETTLED;
    }
    if (n->depth >= A->def.max_depth) {
        p->unsettled = n;
        return UNSETTLED;
    }
    *status = box_split(A, n);
    if (*status) return UNSETTLED;
    for (int k = 0; k < 4; k++)
        if (settle(A, &n->child[k], p, status) != SETTLED) return UNSETTLED;
    return SETTLED;
}

static int settle_all(gb_atlas *A, proof *p, int *status)
{
    for (int k = 0; k < GB_ROOT_COUNT; k++)
        if (settle(A, &A->roots[k], p, status) != SETTLED) return UNSETTLED;
    return SETTLED;
}

/* Prove cell c: CERTIFIED, split (its children unbuilt), or FAILED at max_level. */
static int cell_prove(gb_atlas *A, cell *c, const gb_contact_refine_def *refine)
{
    const double start = gb_wall_seconds();
    proof p = {.sites = 0};
    cell_geometry(c, p.d0, &p.rho);
    gb_contact_point p0;
    int status = gb_certify_global_minimum(A->certify, p.d0, refine, &p0);
    int certified = 0;
    if (status == GB_ENOCONV) {
        gb_error_clear();
        status = GB_OK;
    } else if (!status && site_build(A, p.d0, p.rho, &p0, &c->site[0])) {
        p.site = c->site;
        p.sites = 1;
        for (int round = 0; round < 2 && !status && !certified; round++) {
            p.unsettled = NULL;
            certified = settle_all(A, &p, &status) == SETTLED;
            if (certified || status || p.sites == 2 || !p.unsettled) break;
            /* A box that did not settle may hold another minimum as low: make it a second site. */
            const box *n = p.unsettled;
            double phi, theta;
            gb_surface_chart_angles(gb_region_chart(n->region), 0.5 * (n->a_lo + n->a_hi), 0.5 * (n->b_lo + n->b_hi), &phi,
                                    &theta);
            gb_contact_point q;
            if (gb_contact_refine(&A->surface, p.d0, phi, theta, refine, &q) || !q.is_minimum) {
                gb_error_clear();
                break;
            }
            const double apart[3] = {q.rc[0] - p0.rc[0], q.rc[1] - p0.rc[1], q.rc[2] - p0.rc[2]};
            if (gb_vec_norm(apart) < SAME_POINT || !site_build(A, p.d0, p.rho, &q, &c->site[1])) break;
            p.sites = 2;
        }
    }
    if (!status) {
        if (certified) {
            c->state = CELL_CERTIFIED;
            c->sites = (unsigned char)p.sites;
            A->stats.cells++;
            A->stats.two_site_cells += p.sites == 2;
        } else if (c->level < A->def.max_level) {
            status = cell_split(A, c);
            A->stats.cells_split++;
        } else {
            c->state = CELL_FAILED;
            A->stats.cells_failed++;
        }
    }
    A->stats.build_seconds += gb_wall_seconds() - start;
    return status;
}

/* The cell holding unit vertical d, built (or split) as needed. */
static int find_cell(gb_atlas *A, const double d[3], const gb_contact_refine_def *refine, cell **out)
{
    int face;
    double u, v;
    face_of(d, &face, &u, &v);
    cell *c = A->last;
    if (c && c->face == face && u >= c->u_lo && u <= c->u_hi && v >= c->v_lo && v <= c->v_hi) {
        *out = c;
        return GB_OK;
    }
    c = &A->faces[face];
    for (;;) {
        if (c->state == CELL_UNBUILT) {
            const int status = c->level < A->def.first_level ? cell_split(A, c) : cell_prove(A, c, refine);
            if (status) return status;
        }
        if (c->state != CELL_SPLIT) break;
        const double um = 0.5 * (c->u_lo + c->u_hi), vm = 0.5 * (c->v_lo + c->v_hi);
        c = &c->child[(u >= um) + 2 * (v >= vm)];
    }
    A->last = c;
    *out = c;
    return GB_OK;
}

/* ---------------------------------------------------------------- public */

static void faces_reset(gb_atlas *A)
{
    gb_arena_release(&A->cell_quads);
    for (int f = 0; f < 6; f++) {
        memset(&A->faces[f], 0, sizeof A->faces[f]);
        A->faces[f].face = (unsigned char)f;
        A->faces[f].u_lo = A->faces[f].v_lo = -1.0;
        A->faces[f].u_hi = A->faces[f].v_hi = 1.0;
    }
    A->last = NULL;
}

int gb_atlas_create(const gb_surface *surface, const gb_atlas_def *def, gb_atlas **out)
{
    *out = NULL;
    if (!(def->height_tol >= 0.0 && def->height_tol <= 1e-3))
        return gb_error_set(GB_EDOM, "atlas height tolerance %g is out of range (allowed: [0, 1e-3])", def->height_tol);
    if (def->first_level < 0 || def->first_level > 20 || def->max_level < def->first_level || def->max_level > 20)
        return gb_error_set(GB_EDOM, "atlas levels %d..%d are out of range (allowed: 0 <= first <= max <= 20)",
                            def->first_level, def->max_level);
    if (def->max_depth < 0 || def->max_depth > 40)
        return gb_error_set(GB_EDOM, "atlas max_depth %d is out of range (allowed: 0..40)", def->max_depth);
    gb_atlas *A = calloc(1, sizeof *A);
    if (!A) return gb_error_set(GB_ENOMEM, "out of memory for the atlas");
    A->surface = *surface;
    A->def = *def;
    gb_certify_def cdef = gb_certify_default_def();
    cdef.height_tol = def->height_tol;
    const int status = gb_certify_create(surface, &cdef, &A->certify);
    if (status) {
        free(A);
        return status;
    }
    gb_arena_init(&A->box_quads, sizeof(box_quad));
    gb_arena_init(&A->cell_quads, sizeof(cell_quad));
    for (int k = 0; k < GB_ROOT_COUNT; k++) {
        int region;
        double g[4];
        gb_root_box(k, &region, g);
        box_fill(A, &A->roots[k], &A->root_enclosures[k], region, 0, g[0], g[1], g[2], g[3]);
    }
    A->stats.boxes = GB_ROOT_COUNT;
    A->last_half_width = SITE_MAX_HALF_WIDTH;
    faces_reset(A);
    *out = A;
    return GB_OK;
}

void gb_atlas_free(gb_atlas *A)
{
    if (!A) return;
    gb_arena_release(&A->box_quads);
    gb_arena_release(&A->cell_quads);
    gb_certify_free(A->certify);
    free(A);
}

/* The minimum of site s at d by Newton from its hint: 1 when it is a minimum inside every box of the
 * site (then the site's only critical point), 0 when that could not be shown. */
static int site_minimum(gb_atlas *A, site *s, const double d[3], const gb_contact_refine_def *refine,
                        gb_contact_point *q, gb_certify_result *out)
{
    out->newton_runs++;
    A->stats.newton_runs++;
    if (gb_contact_refine(&A->surface, d, s->hint_phi, s->hint_theta, refine, q)) {
        gb_error_clear();
        return 0;
    }
    if (!q->is_minimum || !site_holds(s, q->phi, q->theta, NULL)) return 0;
    s->hint_phi = q->phi, s->hint_theta = q->theta;
    return 1;
}

int gb_atlas_check(gb_atlas *A, const double zb[3], const gb_contact_point *minimum, const gb_contact_refine_def *refine,
                   gb_certify_result *out)
{
    memset(out, 0, sizeof *out);
    out->verdict = GB_CERTIFY_UNDECIDED;
    double d[3];
    int status = gb_contact_unit_vertical(zb, d);
    if (status) return status;
    A->stats.checks++;
    cell *c;
    status = find_cell(A, d, refine, &c);
    if (status || c->state != CELL_CERTIFIED) return status;
    const double H = gb_vec_dot(d, minimum->rc), eta = A->def.height_tol;
    int home = -1;
    for (int s = 0; s < c->sites && home < 0; s++) {
        int inside;
        if (site_holds(&c->site[s], minimum->phi, minimum->theta, &inside)) home = s;
        else if (inside) return GB_OK; /* in some of the site's boxes only: not decided here */
    }
    gb_contact_point best;
    double best_height = INFINITY;
    for (int s = 0; s < c->sites; s++) {
        if (s == home) continue;
        gb_contact_point q;
        if (!site_minimum(A, &c->site[s], d, refine, &q, out)) return GB_OK;
        if (q.height < best_height) best = q, best_height = q.height;
    }
    if (home < 0 && !isfinite(best_height)) return GB_OK;
    A->stats.answered++;
    if (best_height < H - eta) {
        out->verdict = GB_CERTIFY_LOWER_FOUND;
        out->lower = best;
        A->stats.lower_found++;
    } else {
        out->verdict = GB_CERTIFY_GLOBAL;
    }
    return GB_OK;
}

static void cell_info(const cell *c, gb_atlas_cell_info *out)
{
    memset(out, 0, sizeof *out);
    cell_geometry(c, out->d0, &out->rho);
    for (int k = 0; k < 4; k++) face_point(c->face, k & 1 ? c->u_hi : c->u_lo, k & 2 ? c->v_hi : c->v_lo, out->corner[k]);
    out->level = c->level;
    out->sites = c->state == CELL_CERTIFIED ? c->sites : 0;
    for (int s = 0; s < out->sites; s++) {
        out->boxes[s] = c->site[s].boxes;
        memcpy(out->box[s], c->site[s].box, sizeof out->box[s]);
    }
}

int gb_atlas_cell(gb_atlas *A, const double zb[3], gb_atlas_cell_info *out)
{
    memset(out, 0, sizeof *out);
    double d[3];
    int status = gb_contact_unit_vertical(zb, d);
    cell *c = NULL;
    const gb_contact_refine_def refine = gb_contact_refine_default_def();
    if (!status) status = find_cell(A, d, &refine, &c);
    if (status) return status;
    cell_info(c, out);
    return GB_OK;
}

static void list_cells(const cell *c, gb_atlas_cell_info *out, size_t max, size_t *count)
{
    if (c->state == CELL_SPLIT)
        for (int k = 0; k < 4; k++) list_cells(&c->child[k], out, max, count);
    if (c->state != CELL_CERTIFIED) return;
    if (*count < max) cell_info(c, &out[*count]);
    ++*count;
}

void gb_atlas_cells(const gb_atlas *A, gb_atlas_cell_info *out, size_t max, size_t *count)
{
    *count = 0;
    for (int f = 0; f < 6; f++) list_cells(&A->faces[f], out, max, count);
}

static size_t count_cells(const cell *c)
{
    size_t n = 1;
    if (c->state == CELL_SPLIT)
        for (int k = 0; k < 4; k++) n += count_cells(&c->child[k]);
    return n;
}

void gb_atlas_get_stats(const gb_atlas *A, gb_atlas_stats *out)
{
    *out = A->stats;
    size_t cells = 0;
    for (int f = 0; f < 6; f++) cells += count_cells(&A->faces[f]);
    out->bytes = cells * sizeof(cell) + (A->stats.boxes / 4) * sizeof(box_quad);
}

/* ---------------------------------------------------------------- the file */

/* The file: a header (magic, format, morphology, β, η, levels, depth, site build constants), the cells
 * of the six faces in preorder (state; for a certified cell its sites), and the seal (gb_seal) of
 * everything before it. Written as a gb_file set of one, so a reader never sees half a file. */
#define ATLAS_MAGIC GB_ATLAS_FILE_MAGIC
#define ATLAS_FORMAT 3u

typedef struct header {
    char magic[16];
    uint32_t format, first_level, max_level, max_depth;
    char morphology[16];
    double beta, height_tol, site_reach, site_max, site_min, site_step;
    uint32_t site_splits, cell_bytes;
} header;

static void header_of(const gb_atlas *A, header *h)
{
    memset(h, 0, sizeof *h);
    memcpy(h->magic, ATLAS_MAGIC, sizeof ATLAS_MAGIC);
    h->format = ATLAS_FORMAT;
    h->first_level = (uint32_t)A->def.first_level, h->max_level = (uint32_t)A->def.max_level;
    h->max_depth = (uint32_t)A->def.max_depth;
    snprintf(h->morphology, sizeof h->morphology, "%s", A->surface.morphology->name);
    h->beta = A->surface.beta, h->height_tol = A->def.height_tol;
    h->site_reach = SITE_REACH, h->site_max = SITE_MAX_HALF_WIDTH, h->site_min = SITE_MIN_HALF_WIDTH;
    h->site_step = SITE_WIDTH_STEP, h->site_splits = SITE_SPLITS;
    h->cell_bytes = (uint32_t)sizeof(site);
}

typedef struct writer {
    FILE *f;
    gb_seal_state seal;
    int failed;
} writer;

static void put(writer *w, const void *bytes, size_t size)
{
    gb_seal_add(&w->seal, bytes, size);
    if (fwrite(bytes, 1, size, w->f) != size) w->failed = 1;
}

static void put_cell(writer *w, const cell *c)
{
    const unsigned char state = c->state;
    put(w, &state, 1);
    if (state == CELL_SPLIT)
        for (int k = 0; k < 4; k++) put_cell(w, &c->child[k]);
    if (state == CELL_CERTIFIED) {
        put(w, &c->sites, 1);
        put(w, c->site, c->sites * sizeof(site));
    }
}

/* Write the atlas to `path` as a set of one; `locked`: the caller holds the lock of its directory. */
static int atlas_save(const gb_atlas *A, const char *path, int locked)
{
    gb_file_set set = {.directory_locked = locked};
    writer w = {0};
    int status = gb_seal_begin(&w.seal);
    if (status) return gb_error_set(status, "cannot seal the atlas file %s: %s", path, gb_error_message());
    w.f = gb_file_set_open(&set, path, &status);
    if (!w.f) return gb_error_set(status, "cannot write the atlas file: %s", gb_error_message());
    header h;
    header_of(A, &h);
    put(&w, &h, sizeof h);
    for (int f = 0; f < 6; f++) put_cell(&w, &A->faces[f]);
    unsigned char seal[GB_SEAL_BYTES];
    gb_seal_end(&w.seal, seal);
    if (fwrite(seal, sizeof seal, 1, w.f) != 1) w.failed = 1;
    if (w.failed) status = gb_error_set(GB_EIO, "cannot write the atlas file %s: %s", path, strerror(errno ? errno : EIO));
    return gb_file_set_commit(&set, status);
}

int gb_atlas_save(const gb_atlas *A, const char *path) { return atlas_save(A, path, 0); }

typedef struct reader {
    const unsigned char *p, *end;
} reader;

static int take(reader *r, void *bytes, size_t size)
{
    if ((size_t)(r->end - r->p) < size) return 0;
    memcpy(bytes, r->p, size);
    r->p += size;
    return 1;
}

static int take_cell(gb_atlas *A, reader *r, cell *c)
{
    unsigned char state;
    if (!take(r, &state, 1)) return 0;
    if (state == CELL_SPLIT) {
        if (c->level >= A->def.max_level || cell_split(A, c)) return 0;
        for (int k = 0; k < 4; k++)
            if (!take_cell(A, r, &c->child[k])) return 0;
        return 1;
    }
    if (state == CELL_CERTIFIED) {
        unsigned char sites;
        if (c->level < A->def.first_level || !take(r, &sites, 1) || sites < 1 || sites > 2 ||
            !take(r, c->site, sites * sizeof(site)))
            return 0;
        for (int s = 0; s < sites; s++) {
            site *t = &c->site[s];
            if (t->boxes < 1 || t->boxes > 2 || !isfinite(t->hint_phi) || !isfinite(t->hint_theta)) return 0;
            for (int k = 0; k < 3; k++)
                if (!isfinite(t->x0[k])) return 0;
            for (int k = 0; k < t->boxes; k++) {
                const gb_atlas_site_box *b = &t->box[k];
                if (b->chart != GB_SURFACE_CHART_POLAR_Z && b->chart != GB_SURFACE_CHART_POLAR_X) return 0;
                if (!(b->a_lo < b->a_hi && b->b_lo < b->b_hi && b->a_lo >= 0.0 && b->a_hi <= M_PI &&
                      b->b_hi - b->b_lo <= 2.0 * M_PI && fabs(b->b_lo) <= 4.0 * M_PI))
                    return 0;
                t->looked_up[k] = !inside_band(b); /* recomputed, not read */
            }
        }
        c->state = CELL_CERTIFIED;
        c->sites = sites;
        A->stats.cells++;
        A->stats.two_site_cells += sites == 2;
        return 1;
    }
    if (state == CELL_FAILED) {
        /* a cell whose proof failed at max_level stays without a certificate (its checks go to gb_certify) */
        if (c->level != A->def.max_level) return 0;
        c->state = CELL_FAILED;
        A->stats.cells_failed++;
        return 1;
    }
    return state == CELL_UNBUILT;
}

size_t gb_atlas_file_limit(const gb_atlas *A)
{
    /* Every cell of every face split down to max_level, each leaf certified with two sites: no file of
     * these levels is larger; and none beyond GB_ATLAS_FILE_MAX, whatever its levels declare. */
    double bytes = (double)sizeof(header) + GB_SEAL_BYTES;
    for (int level = 0; level <= A->def.max_level && bytes <= (double)GB_ATLAS_FILE_MAX; level++)
        bytes += 6.0 * pow(4.0, level) * (level < A->def.max_level ? 1.0 : 2.0 + 2.0 * sizeof(site));
    return bytes < (double)GB_ATLAS_FILE_MAX ? (size_t)bytes : (size_t)GB_ATLAS_FILE_MAX;
}

int gb_atlas_load(gb_atlas *A, const char *path)
{
    char *data;
    size_t size;
    const int status = gb_file_read(path, gb_atlas_file_limit(A), "atlas file", "an atlas file this command wrote", &data, &size);
    if (status) return gb_error_set(GB_EIO, "atlas file refused: %s", gb_error_message());
    const int parsed = gb_atlas_load_buffer(A, (const unsigned char *)data, size, path);
    free(data);
    return parsed;
}

/* The counters of the cells of a subtree read apart (merge_cell's scratch), now taken into the atlas. */
static void count_subtree(gb_atlas *A, const cell *c)
{
    if (c->state == CELL_SPLIT)
        for (int k = 0; k < 4; k++) count_subtree(A, &c->child[k]);
    A->stats.cells += c->state == CELL_CERTIFIED;
    A->stats.two_site_cells += c->state == CELL_CERTIFIED && c->sites == 2;
    A->stats.cells_failed += c->state == CELL_FAILED;
    if (c->level > A->stats.deepest_level) A->stats.deepest_level = c->level;
}

/* A certificate holds for every vertical of its cell (gb_atlas.h), so for every vertical of a cell inside
 * it: every cell of c's subtree that has none (unbuilt, or failed) takes a copy of `from`'s sites. */
static void inherit(gb_atlas *A, cell *c, const cell *from)
{
    if (c->state == CELL_SPLIT) {
        for (int k = 0; k < 4; k++) inherit(A, &c->child[k], from);
        return;
    }
    if (c->state == CELL_CERTIFIED) return;
    if (c->state == CELL_FAILED) A->stats.cells_failed--;
    c->state = CELL_CERTIFIED;
    c->sites = from->sites;
    memcpy(c->site, from->site, sizeof c->site);
    A->stats.cells++;
    A->stats.two_site_cells += from->sites == 2;
}

/* The file's cells merged into c, so that nothing either side proved is lost:
 *  - c unbuilt: the file's cell (and its subtree) is taken;
 *  - both split: their children are merged;
 *  - one side split, the other certified (a cell's fate depends on the verticals that first needed it, so
 *    two runs can decompose one cell differently): the finer decomposition is kept, its cells without a
 *    certificate taking the coarser certificate (inherit);
 *  - c failed, the file's certified: the file's certificate;
 *  - elsewhere c is kept (the same cell, proved either way).
 * 0 when the bytes do not parse. */
static int merge_cell(gb_atlas *A, reader *r, cell *c)
{
    if (c->state == CELL_UNBUILT) return take_cell(A, r, c);
    if (r->p == r->end) return 0;
    if (c->state == CELL_SPLIT && *r->p == CELL_SPLIT) {
        r->p++;
        for (int k = 0; k < 4; k++)
            if (!merge_cell(A, r, &c->child[k])) return 0;
        return 1;
    }
    cell scratch = {.u_lo = c->u_lo, .u_hi = c->u_hi, .v_lo = c->v_lo, .v_hi = c->v_hi, .face = c->face, .level = c->level};
    const gb_atlas_stats kept = A->stats;
    const int ok = take_cell(A, r, &scratch);
    A->stats = kept;
    if (!ok) return 0;
    if (c->state == CELL_SPLIT && scratch.state == CELL_CERTIFIED) {
        inherit(A, c, &scratch);
    } else if (c->state == CELL_CERTIFIED && scratch.state == CELL_SPLIT) {
        const cell coarse = *c;
        c->state = CELL_SPLIT;
        c->child = scratch.child; /* the file's subtree, from this atlas's arena */
        A->stats.cells--, A->stats.two_site_cells -= coarse.sites == 2;
        for (int k = 0; k < 4; k++) count_subtree(A, &c->child[k]);
        inherit(A, c, &coarse);
    } else if (c->state == CELL_FAILED && scratch.state == CELL_CERTIFIED) {
        A->stats.cells_failed--;
        *c = scratch;
        A->stats.cells++, A->stats.two_site_cells += scratch.sites == 2;
    }
    return 1;
}

/* The header and checksum of an atlas file's bytes: NULL when they are this atlas's, else why not. */
static const char *refused(const gb_atlas *A, const unsigned char *data, size_t size)
{
    header want, have;
    header_of(A, &want);
    if (size < sizeof have + GB_SEAL_BYTES) return "it is not an atlas of this body, beta, eta and build, or it is damaged";
    memcpy(&have, data, sizeof have);
    if (memcmp(&want, &have, sizeof want)) return "it is not an atlas of this body, beta, eta and build";
    const gb_seal_piece content = {data, size - GB_SEAL_BYTES};
    if (!gb_seal_verify(&content, 1, data + size - GB_SEAL_BYTES))
        return "its seal does not verify: damaged, changed since it was written, or written under another key "
               "(see GOMBOC_KEY)";
    return NULL;
}

int gb_atlas_merge(gb_atlas *A, const char *path)
{
    char *data;
    size_t size;
    int status = gb_file_read(path, gb_atlas_file_limit(A), "atlas file", "an atlas file this command wrote", &data, &size);
    if (status) return gb_error_set(GB_EIO, "atlas file refused: %s", gb_error_message());
    const char *why = refused(A, (const unsigned char *)data, size);
    if (!why) {
        reader r = {(const unsigned char *)data + sizeof(header), (const unsigned char *)data + size - GB_SEAL_BYTES};
        int ok = 1;
        for (int face = 0; face < 6 && ok; face++) ok = merge_cell(A, &r, &A->faces[face]);
        if (!ok || r.p != r.end) why = "its cells do not parse (the cells read before the fault are kept)";
    }
    free(data);
    if (why) return gb_error_set(GB_EIO, "atlas file %s is not merged: %s", path, why);
    return GB_OK;
}

int gb_atlas_merge_save(gb_atlas *A, const char *path)
{
    /* The lock: gb_file_lock's, on the file's directory (the file itself is replaced by a rename, so a
     * lock on it would not be held by the next writer), waited for a bounded time. Without one (a
     * directory that cannot be locked) the writers are still safe, and a cell can only be lost, to be
     * proved again when needed. */
    int lock;
    int status = gb_file_lock(path, "merging the shared atlas of verticals", &lock);
    if (status) return status;
    if (gb_atlas_merge(A, path)) gb_error_clear(); /* missing, stale or damaged: replaced */
    status = atlas_save(A, path, lock >= 0);
    gb_file_unlock(lock);
    return status;
}

int gb_atlas_load_buffer(gb_atlas *A, const unsigned char *data, size_t size, const char *name)
{
    const char *path = name;
    const char *why = refused(A, data, size);
    int ok = !why;
    if (ok) {
        const gb_atlas_stats kept = A->stats;
        faces_reset(A);
        A->stats.cells = A->stats.two_site_cells = A->stats.cells_failed = 0;
        reader r = {data + sizeof(header), data + size - GB_SEAL_BYTES};
        for (int face = 0; face < 6 && ok; face++) ok = take_cell(A, &r, &A->faces[face]);
        ok = ok && r.p == r.end;
        if (!ok) {
            faces_reset(A);
            A->stats = kept;
            why = "its cells do not parse";
        }
    }
    if (!ok) return gb_error_set(GB_EIO, "atlas file %s is refused: %s", path, why);
    return GB_OK;
}
