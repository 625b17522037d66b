/* gb_atlas — §4 eq 29: an atlas of verticals (gb_atlas.h): the cube's faces cut into cells of verticals,
 * each proved, over the surface's boxes, to hold its global minimum in one or two named sites, so that a
 * step's certificate is a lookup and a Newton solve. Its file (save, load, merge) is gb_atlas_file.c.
 *
 * Sharing. The cells and the surface boxes are a core that several views (one a thread) share
 * (gb_atlas_share): a cell is built once, by the first view that needs it, and read by all without a lock.
 *  - A cell's state is read with acquire and written with release: a view writes a cell's sites, or its
 *    children, before the state that publishes them, so a view that reads the state sees them whole.
 *  - A view claims an unbuilt cell by compare-and-swap (UNBUILT → BUILDING) and proves it alone; a view that
 *    needs a cell another is proving waits for it (a condition variable, no spinning): building it again
 *    would take at least as long as waiting for the build already under way.
 *  - Different cells are proved at once. Their proofs share the surface boxes, whose splits are the only
 *    writes into them: a split's four boxes are enclosed outside any lock, then published under the core's
 *    lock (taken from the arena there, the child pointer stored with release); a view that lost the race
 *    drops its copy. Counters of the core change under that lock, a view's own without one.
 *  - A published cell never changes while views share the core: a view's Newton hints live in the view (the
 *    results do not depend on them: gb_dyn_canonical_minimum), and the file is merged into a copy
 *    (gb_atlas_merge_save), not into the shared cells.
 *  - Memory: gb_atlas_set_max_bytes bounds the cells built; beyond it a check in an unbuilt cell is undecided
 *    (the caller then asks gb_certify), and the cells already built stay. */
#include "gb_atlas_internal.h"
#include "gb_clock.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

gb_atlas_def gb_atlas_default_def(void)
{
    return (gb_atlas_def){.height_tol = 1e-12, .first_level = 5, .max_level = 13, .max_depth = 14};
}


/* ---------------------------------------------------------------- the surface boxes */

/* A cell's state and a box's children as views share them (above, "sharing"). */
static unsigned char state_of(const cell *c) { return __atomic_load_n(&c->state, __ATOMIC_ACQUIRE); }
static void publish(cell *c, unsigned char state) { __atomic_store_n(&c->state, state, __ATOMIC_RELEASE); }
static box *children_of(const box *n) { return __atomic_load_n(&n->child, __ATOMIC_ACQUIRE); }


static void box_fill(const gb_atlas_core *K, box *n, gb_surface_enclosure *e, int region, int depth, double a_lo, double a_hi,
                     double b_lo, double b_hi)
{
    memset(n, 0, sizeof *n);
    n->e = e;
    n->a_lo = a_lo, n->a_hi = a_hi, n->b_lo = b_lo, n->b_hi = b_hi;
    n->region = (unsigned char)region;
    n->depth = (unsigned char)depth;
    double mags[5];
    gb_certify_enclose_box(&K->surface, region, a_lo, a_hi, b_lo, b_hi, e, mags);
    n->xa_mag = mags[0], n->xb_mag = mags[1], n->xaa_mag = mags[2], n->xab_mag = mags[3], n->xbb_mag = mags[4];
}

static int box_split(gb_atlas *A, box *n)
{
    if (children_of(n)) return GB_OK;
    gb_atlas_core *K = A->core;
    box_quad fresh; /* enclosed outside the lock; published, or dropped when another view split n first */
    const double am = 0.5 * (n->a_lo + n->a_hi), bm = 0.5 * (n->b_lo + n->b_hi);
    box_fill(K, &fresh.n[0], &fresh.e[0], n->region, n->depth + 1, n->a_lo, am, n->b_lo, bm);
    box_fill(K, &fresh.n[1], &fresh.e[1], n->region, n->depth + 1, am, n->a_hi, n->b_lo, bm);
    box_fill(K, &fresh.n[2], &fresh.e[2], n->region, n->depth + 1, n->a_lo, am, bm, n->b_hi);
    box_fill(K, &fresh.n[3], &fresh.e[3], n->region, n->depth + 1, am, n->a_hi, bm, n->b_hi);
    int status = GB_OK;
    pthread_mutex_lock(&K->lock);
    if (!n->child) {
        box_quad *q = gb_arena_take(&K->box_quads);
        if (q) {
            *q = fresh;
            for (int k = 0; k < 4; k++) q->n[k].e = &q->e[k];
            __atomic_store_n(&n->child, q->n, __ATOMIC_RELEASE);
            K->stats.boxes += 4;
        } else {
            status = GB_ENOMEM;
        }
    }
    pthread_mutex_unlock(&K->lock);
    return status ? gb_error_set(status, "out of memory for the atlas's surface boxes") : GB_OK;
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

int gb_atlas_cell_split(gb_atlas *A, cell *c)
{
    gb_atlas_core *K = A->core;
    pthread_mutex_lock(&K->lock);
    cell_quad *q = gb_arena_take(&K->cell_quads);
    if (q && c->level + 1 > K->stats.deepest_level) K->stats.deepest_level = c->level + 1;
    if (q) K->cells_held += 4;
    pthread_mutex_unlock(&K->lock);
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
    publish(c, CELL_SPLIT);
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
int gb_atlas_site_in_band(const gb_atlas_site_box *b)
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
    gb_surface_enclose(&A->core->surface, chart, a_lo, a_hi, b_lo, b_hi, &e);
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
            s->looked_up[s->boxes] = !gb_atlas_site_in_band(&s->box[s->boxes]);
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
    if (n->depth >= A->core->def.max_depth) {
        p->unsettled = n;
        return UNSETTLED;
    }
    *status = box_split(A, n);
    if (*status) return UNSETTLED;
    box *child = children_of(n);
    for (int k = 0; k < 4; k++)
        if (settle(A, &child[k], p, status) != SETTLED) return UNSETTLED;
    return SETTLED;
}

static int settle_all(gb_atlas *A, proof *p, int *status)
{
    for (int k = 0; k < GB_ROOT_COUNT; k++)
        if (settle(A, &A->core->roots[k], p, status) != SETTLED) return UNSETTLED;
    return SETTLED;
}

/* A certifier for a cell's centre from the core's pool (made when none is free), and given back. */
static int certifier_take(gb_atlas_core *K, gb_certify **out)
{
    pthread_mutex_lock(&K->lock);
    *out = K->certifiers_free ? K->certifiers[--K->certifiers_free] : NULL;
    pthread_mutex_unlock(&K->lock);
    if (*out) return GB_OK;
    gb_certify_def cdef = gb_certify_default_def();
    cdef.height_tol = K->def.height_tol;
    return gb_certify_create(&K->surface, &cdef, out);
}

static void certifier_give(gb_atlas_core *K, gb_certify *c)
{
    pthread_mutex_lock(&K->lock);
    if (K->certifiers_free == K->certifiers_cap) {
        const size_t cap = K->certifiers_cap ? 2 * K->certifiers_cap : 4;
        gb_certify **grown = realloc(K->certifiers, cap * sizeof *grown);
        if (grown) K->certifiers = grown, K->certifiers_cap = cap;
    }
    if (K->certifiers_free < K->certifiers_cap) K->certifiers[K->certifiers_free++] = c, c = NULL;
    pthread_mutex_unlock(&K->lock);
    gb_certify_free(c); /* no room to keep it */
}

/* Prove cell c, claimed by this view: CERTIFIED, split (its children unbuilt), or FAILED at max_level, published. */
static int cell_prove(gb_atlas *A, cell *c, const gb_contact_refine_def *refine)
{
    const double start = gb_wall_seconds();
    proof p = {.sites = 0};
    cell_geometry(c, p.d0, &p.rho);
    gb_contact_point p0;
    gb_certify *certify;
    int status = certifier_take(A->core, &certify);
    if (status) return status;
    status = gb_certify_global_minimum(certify, p.d0, refine, &p0);
    certifier_give(A->core, certify);
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
            if (gb_contact_refine(&A->core->surface, p.d0, phi, theta, refine, &q) || !q.is_minimum) {
                gb_error_clear();
                break;
            }
            const double apart[3] = {q.rc[0] - p0.rc[0], q.rc[1] - p0.rc[1], q.rc[2] - p0.rc[2]};
            if (gb_vec_norm(apart) < SAME_POINT || !site_build(A, p.d0, p.rho, &q, &c->site[1])) break;
            p.sites = 2;
        }
    }
    gb_atlas_core *K = A->core;
    const int split = !status && !certified && c->level < K->def.max_level;
    if (split) status = gb_atlas_cell_split(A, c);
    pthread_mutex_lock(&K->lock);
    if (!status && certified) K->stats.cells++, K->stats.two_site_cells += p.sites == 2;
    else if (!status && split) K->stats.cells_split++;
    else if (!status) K->stats.cells_failed++;
    K->stats.build_seconds += gb_wall_seconds() - start;
    pthread_mutex_unlock(&K->lock);
    if (!status && certified) c->sites = (unsigned char)p.sites, publish(c, CELL_CERTIFIED);
    else if (!status && !split) publish(c, CELL_FAILED);
    return status;
}

/* Memory the core's cells and boxes hold. */
static size_t core_bytes(gb_atlas_core *K);

/* The list of views waiting for cell c. */
static pthread_cond_t *wake_list(gb_atlas_core *K, const cell *c)
{
    return &K->built[((uintptr_t)c / sizeof *c) % GB_ATLAS_WAKE_LISTS];
}

/* Build unbuilt cell c (claimed here), or wait for the view that claimed it first. A cell that is not built because
 * the atlas is full, or whose proof failed, is left unbuilt. */
static int build_or_wait(gb_atlas *A, cell *c, const gb_contact_refine_def *refine)
{
    gb_atlas_core *K = A->core;
    unsigned char expected = CELL_UNBUILT;
    if (__atomic_compare_exchange_n(&c->state, &expected, CELL_BUILDING, 0, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE)) {
        int status = GB_OK;
        if (K->max_bytes && core_bytes(K) > K->max_bytes) publish(c, CELL_UNBUILT); /* full: undecided here */
        else if ((status = c->level < K->def.first_level ? gb_atlas_cell_split(A, c) : cell_prove(A, c, refine)))
            publish(c, CELL_UNBUILT);
        pthread_mutex_lock(&K->lock);
        pthread_cond_broadcast(wake_list(K, c));
        pthread_mutex_unlock(&K->lock);
        return status;
    }
    if (expected != CELL_BUILDING) return GB_OK;
    const double start = gb_wall_seconds();
    pthread_mutex_lock(&K->lock);
    while (state_of(c) == CELL_BUILDING) pthread_cond_wait(wake_list(K, c), &K->lock);
    K->stats.waits++, K->stats.wait_seconds += gb_wall_seconds() - start;
    pthread_mutex_unlock(&K->lock);
    return GB_OK;
}

/* The cell holding unit vertical d, built (or split) as needed; unbuilt when the atlas is full. A settled cell
 * becomes the view's last, its sites' Newton hints the view's. */
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
    c = &A->core->faces[face];
    unsigned char state;
    for (;;) {
        state = state_of(c);
        if (state == CELL_UNBUILT || state == CELL_BUILDING) {
            const int status = build_or_wait(A, c, refine);
            if (status) return status;
            state = state_of(c);
        }
        if (state != CELL_SPLIT) break;
        const double um = 0.5 * (c->u_lo + c->u_hi), vm = 0.5 * (c->v_lo + c->v_hi);
        c = &c->child[(u >= um) + 2 * (v >= vm)];
    }
    if (state == CELL_CERTIFIED || state == CELL_FAILED) {
        double d0[3]; /* the cell's centre, as cell_geometry and the proof had it */
        face_point(c->face, 0.5 * (c->u_lo + c->u_hi), 0.5 * (c->v_lo + c->v_hi), d0);
        for (int s = 0; s < 2; s++) {
            A->hint[s][0] = c->site[s].hint_phi, A->hint[s][1] = c->site[s].hint_theta;
            memcpy(A->ref_d[s], d0, sizeof d0);
            A->ref_h[s] = gb_vec_dot(d0, c->site[s].x0); /* the site was built around its minimum at the centre */
        }
        A->last = c;
    }
    *out = c;
    return GB_OK;
}

/* ---------------------------------------------------------------- public */

void gb_atlas_faces_reset(gb_atlas *A)
{
    gb_atlas_core *K = A->core;
    gb_arena_release(&K->cell_quads);
    K->cells_held = 6;
    for (int f = 0; f < 6; f++) {
        memset(&K->faces[f], 0, sizeof K->faces[f]);
        K->faces[f].face = (unsigned char)f;
        K->faces[f].u_lo = K->faces[f].v_lo = -1.0;
        K->faces[f].u_hi = K->faces[f].v_hi = 1.0;
    }
    A->last = NULL;
}

int gb_atlas_create(const gb_surface *surface, const gb_atlas_def *def, gb_atlas **out)
{
    *out = NULL;
    if (!surface->morphology->kernel_jet)
        return gb_error_set(GB_EINVAL, "the body '%s' has no interval enclosure: no atlas can be proved for it (allowed: a "
                            "morphology of the paper, I or II)", surface->morphology->name);
    if (!(def->height_tol >= 0.0 && def->height_tol <= 1e-3))
        return gb_error_set(GB_EDOM, "atlas height tolerance %g is out of range (allowed: [0, 1e-3])", def->height_tol);
    if (def->first_level < 0 || def->first_level > 20 || def->max_level < def->first_level || def->max_level > 20)
        return gb_error_set(GB_EDOM, "atlas levels %d..%d are out of range (allowed: 0 <= first <= max <= 20)",
                            def->first_level, def->max_level);
    if (def->max_depth < 0 || def->max_depth > 40)
        return gb_error_set(GB_EDOM, "atlas max_depth %d is out of range (allowed: 0..40)", def->max_depth);
    gb_atlas *A = calloc(1, sizeof *A);
    gb_atlas_core *K = calloc(1, sizeof *K);
    if (!A || !K) {
        free(A), free(K);
        return gb_error_set(GB_ENOMEM, "out of memory for the atlas");
    }
    if (pthread_mutex_init(&K->lock, NULL)) {
        free(A), free(K);
        return gb_error_set(GB_ENOMEM, "the atlas: no mutex");
    }
    int lists = 0;
    while (lists < GB_ATLAS_WAKE_LISTS && !pthread_cond_init(&K->built[lists], NULL)) lists++;
    if (lists < GB_ATLAS_WAKE_LISTS) {
        while (lists--) pthread_cond_destroy(&K->built[lists]);
        pthread_mutex_destroy(&K->lock);
        free(A), free(K);
        return gb_error_set(GB_ENOMEM, "the atlas: no condition variable");
    }
    A->core = K;
    K->views = 1;
    K->surface = *surface;
    K->def = *def;
    gb_arena_init(&K->box_quads, sizeof(box_quad));
    gb_arena_init(&K->cell_quads, sizeof(cell_quad));
    for (int k = 0; k < GB_ROOT_COUNT; k++) {
        int region;
        double g[4];
        gb_root_box(k, &region, g);
        box_fill(K, &K->roots[k], &K->root_enclosures[k], region, 0, g[0], g[1], g[2], g[3]);
    }
    K->stats.boxes = GB_ROOT_COUNT;
    for (int k = 0; k < GB_ROOT_COUNT; k++)
        K->radius = fmax(K->radius, gb_certify_norm_of_mags(K->root_enclosures[k].x));
    A->last_half_width = SITE_MAX_HALF_WIDTH;
    gb_atlas_faces_reset(A);
    *out = A;
    return GB_OK;
}

int gb_atlas_share(gb_atlas *atlas, gb_atlas **view)
{
    *view = NULL;
    gb_atlas *A = calloc(1, sizeof *A);
    if (!A) return gb_error_set(GB_ENOMEM, "out of memory for a view of the atlas");
    gb_atlas_core *K = atlas->core;
    A->core = K;
    A->last_half_width = SITE_MAX_HALF_WIDTH;
    pthread_mutex_lock(&K->lock);
    K->views++;
    pthread_mutex_unlock(&K->lock);
    *view = A;
    return GB_OK;
}

void gb_atlas_set_max_bytes(gb_atlas *A, size_t bytes) { A->core->max_bytes = bytes; }

size_t gb_atlas_views(const gb_atlas *A)
{
    gb_atlas_core *K = A->core;
    pthread_mutex_lock(&K->lock);
    const size_t views = K->views;
    pthread_mutex_unlock(&K->lock);
    return views;
}

void gb_atlas_free(gb_atlas *A)
{
    if (!A) return;
    gb_atlas_core *K = A->core;
    pthread_mutex_lock(&K->lock);
    const size_t left = --K->views;
    pthread_mutex_unlock(&K->lock);
    if (!left) {
        gb_arena_release(&K->box_quads);
        gb_arena_release(&K->cell_quads);
        for (int k = 0; k < GB_ATLAS_WAKE_LISTS; k++) pthread_cond_destroy(&K->built[k]);
        pthread_mutex_destroy(&K->lock);
        while (K->certifiers_free) gb_certify_free(K->certifiers[--K->certifiers_free]);
        free(K->certifiers);
        free(K);
    }
    free(A);
}

/* The minimum of site s of the view's last cell at d, by Newton from the view's hint: 1 when it is a minimum inside
 * every box of the site (then the site's only critical point), 0 when that could not be shown. */
static int site_minimum(gb_atlas *A, const site *st, int s, const double d[3], const gb_contact_refine_def *refine,
                        gb_contact_point *q, gb_certify_result *out)
{
    out->newton_runs++;
    A->stats.newton_runs++;
    if (gb_contact_refine(&A->core->surface, d, A->hint[s][0], A->hint[s][1], refine, q)) {
        gb_error_clear();
        return 0;
    }
    if (!q->is_minimum || !site_holds(st, q->phi, q->theta, NULL)) return 0;
    A->hint[s][0] = q->phi, A->hint[s][1] = q->theta;
    memcpy(A->ref_d[s], d, sizeof A->ref_d[s]);
    A->ref_h[s] = q->height;
    return 1;
}

/* Is site s of the view's last cell no lower than `floor` at d, from its minimum at the reference vertical d_r
 * (the cell's centre, or the site's last Newton solve), without a solve? At d_r that minimum, at height h_r, is
 * the site's critical point inside each of its boxes, on which d_r·x'' is positive definite (the cell's proof,
 * for every vertical of the cell): the lowest point of each box, so h_r = min over the boxes of d_r·x. For any d,
 * with x_d the lowest point of the boxes at d, min d·x = d_r·x_d + (d − d_r)·x_d ≥ h_r − R |d − d_r|, R ≥ |x|.
 * The slack covers the rounding of h_r (the minimum's position to ~1e-15) and of the sums here. */
static int site_no_lower(const gb_atlas *A, int s, const double d[3], double floor)
{
    const double step[3] = {d[0] - A->ref_d[s][0], d[1] - A->ref_d[s][1], d[2] - A->ref_d[s][2]};
    return A->ref_h[s] - A->core->radius * gb_vec_norm(step) - GB_CERTIFY_SLACK_ROUNDING >= floor;
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
    if (status || state_of(c) != CELL_CERTIFIED) return status;
    const double H = gb_vec_dot(d, minimum->rc), eta = A->core->def.height_tol;
    int home = -1;
    for (int s = 0; s < c->sites && home < 0; s++) {
        int inside;
        if (site_holds(&c->site[s], minimum->phi, minimum->theta, &inside)) home = s;
        else if (inside) return GB_OK; /* in some of the site's boxes only: not decided here */
    }
    gb_contact_point best;
    double best_height = INFINITY;
    int settled = 0; /* sites other than home known to lie no lower than H − η, or solved */
    for (int s = 0; s < c->sites; s++) {
        if (s == home) continue;
        settled++;
        if (site_no_lower(A, s, d, H - eta)) continue; /* what the solve below would conclude */
        gb_contact_point q;
        if (!site_minimum(A, &c->site[s], s, d, refine, &q, out)) return GB_OK;
        if (q.height < best_height) best = q, best_height = q.height;
    }
    if (home < 0 && !settled) return GB_OK;
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
    out->sites = state_of(c) == CELL_CERTIFIED ? c->sites : 0;
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
    if (state_of(c) == CELL_SPLIT)
        for (int k = 0; k < 4; k++) list_cells(&c->child[k], out, max, count);
    if (state_of(c) != CELL_CERTIFIED) return;
    if (*count < max) cell_info(c, &out[*count]);
    ++*count;
}

void gb_atlas_cells(const gb_atlas *A, gb_atlas_cell_info *out, size_t max, size_t *count)
{
    *count = 0;
    for (int f = 0; f < 6; f++) list_cells(&A->core->faces[f], out, max, count);
}

/* Counted as they are taken, not by walking the cells: every claim of a cell asks (a walk would make a run's
 * claims quadratic in its cells). A subtree a merge read and dropped still holds its memory, and counts. */
static size_t core_bytes(gb_atlas_core *K)
{
    pthread_mutex_lock(&K->lock);
    const size_t cells = K->cells_held, boxes = K->stats.boxes;
    pthread_mutex_unlock(&K->lock);
    return cells * sizeof(cell) + (boxes / 4) * sizeof(box_quad);
}

void gb_atlas_get_stats(const gb_atlas *A, gb_atlas_stats *out)
{
    gb_atlas_core *K = A->core;
    pthread_mutex_lock(&K->lock);
    *out = K->stats;
    pthread_mutex_unlock(&K->lock);
    out->checks = A->stats.checks, out->answered = A->stats.answered, out->lower_found = A->stats.lower_found;
    out->newton_runs = A->stats.newton_runs, out->boxes_tested = A->stats.boxes_tested;
    out->bytes = core_bytes(K);
}
