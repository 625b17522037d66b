#include "gb_dynamics.h"

#include "gb_impact.h"

#include "gb_contact.h"
#include "gb_error.h"
#include "gb_massprops.h"
#include "gb_vec.h"

#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static const char *const variant_names[] = {"paper", "rolling"};

const char *gb_dynamics_variant_name(gb_dynamics_variant v) { return (unsigned)v < 2 ? variant_names[v] : NULL; }

int gb_dynamics_variant_parse(const char *name, gb_dynamics_variant *variant)
{
    int k = 0;
    const int status = gb_error_parse_name(name, variant_names, 2, "equation variant", &k);
    if (!status) *variant = (gb_dynamics_variant)k;
    return status;
}


static const char *const certificate_names[] = {"per-vertical", "atlas"};

const char *gb_dynamics_certificate_name(gb_dynamics_certificate c) { return (unsigned)c < 2 ? certificate_names[c] : NULL; }

int gb_dynamics_certificate_parse(const char *name, gb_dynamics_certificate *certificate)
{
    int k = 0;
    const int status = gb_error_parse_name(name, certificate_names, 2, "contact certificate", &k);
    if (!status) *certificate = (gb_dynamics_certificate)k;
    return status;
}

static const char *const contact_law_names[] = {"held", "unilateral"};

const char *gb_dynamics_contact_law_name(gb_contact_law l) { return (unsigned)l < 2 ? contact_law_names[l] : NULL; }

int gb_dynamics_contact_law_parse(const char *name, gb_contact_law *law)
{
    int k = 0;
    const int status = gb_error_parse_name(name, contact_law_names, 2, "contact law", &k);
    if (!status) *law = (gb_contact_law)k;
    return status;
}

gb_dynamics_def gb_dynamics_default_def(void)
{
    gb_dynamics_def def = {
        .variant = GB_VARIANT_PAPER,
        .contact = GB_CONTACT_MODEL_GRID,
        .mass = 1.0,
        .length = 1.0,
        .damping = 0.02,
        .forcing = {.g = 9.81, .a1 = 2.0, .a2 = 1.0, .omega = 18.0, .psi = M_PI / 3.0},
        .grid = gb_contact_grid_default_def(),
        .certify = gb_certify_default_def(),
        .friction = INFINITY,
        .atlas = gb_atlas_default_def(),
    };
    /* Leaves of 16 nodes were the fastest of 8–32 for the patch tree's searches (make bench); the leaf
     * size changes no result, only the work. */
    def.grid.leaf_size = 16;
    return def;
}

struct gb_dynamics {
    gb_surface surface;
    gb_dynamics_def def;
    double inertia[3][3]; /* I_C [kg m²] */
    double mean_radius;   /* L [m] (eq 53) */
    gb_contact_grid *grid;
    gb_contact_tracker *tracker; /* exact grid search along the trajectory (fast-grid) */
    int grid_borrowed;           /* grid (and tracker) belong to def.cache */
    gb_certify *certify;         /* the global-minimum certificate (continuous) */
    gb_atlas *atlas;             /* certificate = atlas */
    int atlas_borrowed;          /* the atlas belongs to another gb_dynamics (gb_dynamics_share_atlas) */
    size_t atlas_fallbacks;      /* checks the atlas left to gb_certify */
    int atlas_loaded;
    int hull_loaded;             /* 1: the tracker's hull came from def.hull_file */
    gb_contact_refine_def refine;
    /* The contact at the last accepted state. */
    size_t index;
    gb_contact_point contact;
    /* Newton's predictor for continuous contact: (φ, θ) ≈ contact + rate (t − contact_time), with the
     * rate of eq 72 at the accepted state; the start changes which minimum is reached only across a fold,
     * and otherwise its last bits at most. */
    double contact_time, contact_rate[2];
    /* ... or, when valid, from the last contact found (at any evaluation since the accepted state) by its
     * sensitivity (eq 70): (φ, θ) ≈ last + ∂(φ, θ)/∂z_b (z_b − z_b,last). Between the two middle stages of
     * RK4 the verticals differ by O(h²) and this start is the minimum to ~1e-12 rad. */
    int last_valid;
    double last_zb[3], last_dq[2][3];
    gb_contact_point last_point; /* that contact: an evaluation at the same vertical takes it as it is */
    double energy0, t0;
    size_t grid_switches, branch_switches;
    size_t contact_queries, nodes_visited; /* grid models: the searches' work */
    double last_switch_time; /* of the latest grid or branch switch (NAN before the first) */
    size_t branches_lost; /* continuous: evaluations where the continued branch had no minimum */
    /* The unilateral law: impacts, the kinetic energy they took (L), the largest friction needed. */
    size_t impacts;
    double impact_loss, impact_friction_max;
    size_t impacts_over_friction; /* that needed more than def.friction */
    size_t next_hint; /* a grid body: the last next node found (next_node) */
    gb_dynamics_impact_sink impact_sink;
    void *impact_context;
    /* The two-point mode: the body rolls on `contact` (P) and `contact2` (Q) at once, since two_point_since;
     * the time spent in it before, and how often it was entered. `pending`: the event that
     * gb_dynamics_switch_pending found in this mode, for gb_dynamics_branch_gap and gb_dynamics_switch_to. */
    int two_point, pending;
    /* Q's Newton predictor, as last_* for P: the last Q found, its vertical and sensitivity (q_valid) */
    int q_valid;
    double q_zb[3], q_dq[2][3];
    gb_contact_point q_last; /* that Q (its chart and coordinates start the predictor) */
    int resting;       /* on three points at rest (ω = 0) since rest_since */
    double rest_since;
    gb_contact_point contact2;
    double two_point_since, two_point_time;
    size_t two_point_entries, settled, lifts, third_points;
    /* Flight (the unilateral law): since fly_t0 the centroid moves under g_eff alone, from height fly_zeta0
     * above the plane with velocity fly_v0 (inertial, relative to the plane): closed form (flight_state).
     * `contact` is then the lowest point, continued and certified as a contact is. flight_event: the event
     * gb_dynamics_switch_pending found (FLIGHT_NONE, FLIGHT_LIFT_OFF, FLIGHT_LANDING), for
     * gb_dynamics_branch_gap, gb_dynamics_switch_to and gb_dynamics_jump. */
    /* After a lift of the two-point mode (continuous contact): the point that lifted, and how far below the
     * contact it may dip before its return counts as a change of contact (LIFT_OFF_DIP_MAX), until its gap
     * has opened (lift_allow is 0 when none is pending). */
    gb_contact_point lifted;
    double lift_allow;
    int flying, flight_event;
    double gap_allow; /* a landing is the lowest point this far below the plane [body lengths]: FLIGHT_GAP_TOL,
                       * or a lift-off's dip until the gap has opened */
    double fly_t0, fly_zeta0, fly_v0[3];
    double flight_since, flight_time, hop_max;
    size_t lift_offs, landings, bounces;
    /* The last competitor() answer and the state it was for: with switch location, the step's end is
     * checked by gb_dynamics_switch_pending and then again by gb_dynamics_accept at the same state. */
    int memo_valid, memo_found, memo_pending;
    double memo_key[8];
    gb_contact_point memo_continued, memo_other;
};

const gb_dynamics_def *gb_dynamics_get_def(const gb_dynamics *d) { return &d->def; }
double gb_dynamics_mean_radius(const gb_dynamics *d) { return d->mean_radius; }
struct gb_dynamics_cache {
    gb_surface props_surface; /* the body and mass of `props` (has_props) */
    double props_mass;
    gb_massprops props;
    int has_props;
    gb_surface grid_surface;  /* the body and definition of `grid` (and `tracker`) */
    gb_contact_grid_def grid_def;
    gb_contact_grid *grid;
    gb_contact_tracker *tracker;
    int hull_loaded;          /* the tracker came from a hull file */
};

int gb_dynamics_cache_create(gb_dynamics_cache **out)
{
    *out = calloc(1, sizeof **out);
    return *out ? GB_OK : gb_error_set(GB_ENOMEM, "out of memory for the dynamics cache");
}

void gb_dynamics_cache_free(gb_dynamics_cache *c)
{
    if (!c) return;
    gb_contact_tracker_free(c->tracker);
    gb_contact_grid_free(c->grid);
    free(c);
}

static int same_body(const gb_surface *a, const gb_surface *b)
{
    return a->morphology == b->morphology && !memcmp(&a->beta, &b->beta, sizeof a->beta);
}

static int same_grid(const gb_contact_grid_def *a, const gb_contact_grid_def *b)
{
    return a->n_phi == b->n_phi && a->n_theta == b->n_theta && a->nodes == b->nodes && a->leaf_size == b->leaf_size;
}

/* The body's mass properties: from the cache when it holds this body's and mass's, else computed (and
 * kept there). */
static int body_massprops(const gb_surface *surface, const gb_dynamics_def *def, gb_massprops *props)
{
    gb_dynamics_cache *c = def->cache;
    if (c && c->has_props && same_body(&c->props_surface, surface) && !memcmp(&c->props_mass, &def->mass, sizeof def->mass)) {
        *props = c->props;
        return GB_OK;
    }
    gb_massprops_def mdef = gb_massprops_default_def();
    mdef.mass = def->mass;
    const int status = gb_massprops_compute(surface, &mdef, props);
    if (!status && c) c->props_surface = *surface, c->props_mass = def->mass, c->props = *props, c->has_props = 1;
    return status;
}

/* The grid, and for the fast grid its tracker (from def.hull_file when it holds this grid's hull, else
 * by Qhull): borrowed from the cache when it holds this body's and grid's, else built, and kept in an
 * empty cache. */
static int body_grid(gb_dynamics *d, const gb_surface *surface, const gb_dynamics_def *def)
{
    gb_dynamics_cache *c = def->cache;
    const int fast = def->contact == GB_CONTACT_MODEL_FAST_GRID;
    const int cached = c && c->grid && same_body(&c->grid_surface, surface) && same_grid(&c->grid_def, &def->grid);
    int status = GB_OK;
    if (cached) {
        d->grid = c->grid, d->grid_borrowed = 1;
        if (!fast) return GB_OK;
        if (c->tracker) {
            d->tracker = c->tracker, d->hull_loaded = c->hull_loaded;
            return GB_OK;
        }
    } else {
        status = gb_contact_grid_create(surface, &def->grid, &d->grid);
        if (status) return status;
        if (c && !c->grid) c->grid = d->grid, c->grid_surface = *surface, c->grid_def = def->grid, d->grid_borrowed = 1;
        if (!fast) return GB_OK;
    }
    /* a hull file that is missing, stale or damaged is built anew by Qhull (and replaced when saved) */
    d->hull_loaded = def->hull_file && gb_contact_tracker_load(d->grid, def->hull_file, &d->tracker) == GB_OK;
    if (!d->hull_loaded) {
        gb_error_clear();
        status = gb_contact_tracker_create(d->grid, &d->tracker);
    }
    if (!status && d->grid_borrowed) c->tracker = d->tracker, c->hull_loaded = d->hull_loaded;
    return status;
}

size_t gb_dynamics_grid_size(const gb_dynamics *d) { return d->grid ? gb_contact_grid_size(d->grid) : 0; }

int gb_dynamics_create(const gb_surface *surface, const gb_dynamics_def *def, gb_dynamics **out)
{
    *out = NULL;
    if (!gb_dynamics_variant_name(def->variant) || !gb_contact_model_name(def->contact))
        return gb_error_set(GB_EINVAL, "unknown equation variant %d or contact model %d", (int)def->variant,
                            (int)def->contact);
    if (!(isfinite(def->mass) && def->mass > 0.0))
        return gb_error_set(GB_EDOM, "mass = %g is out of range (allowed: finite, > 0)", def->mass);
    if (!(isfinite(def->length) && def->length > 0.0))
        return gb_error_set(GB_EDOM, "length = %g is out of range (allowed: finite, > 0)", def->length);
    if (!(def->friction > 0.0)) /* INFINITY: no monitor */
        return gb_error_set(GB_EDOM, "friction = %g is out of range (allowed: > 0)", def->friction);
    if (!(isfinite(def->damping) && def->damping >= 0.0))
        return gb_error_set(GB_EDOM, "damping c = %g is out of range (allowed: finite, >= 0)", def->damping);
    if (!(def->restitution >= 0.0 && def->restitution <= 1.0))
        return gb_error_set(GB_EDOM, "restitution e = %g is out of range (allowed: 0 <= e <= 1)", def->restitution);
    if (!(isfinite(def->height0) && def->height0 >= 0.0) ||
        !(isfinite(def->velocity0[0]) && isfinite(def->velocity0[1]) && isfinite(def->velocity0[2])))
        return gb_error_set(GB_EDOM, "initial height %g or velocity is out of range (allowed: height finite, >= 0; "
                            "velocity finite)", def->height0);
    if (def->contact_law != GB_CONTACT_LAW_UNILATERAL &&
        (def->restitution != 0.0 || def->height0 != 0.0 || def->velocity0[0] != 0.0 || def->velocity0[1] != 0.0 ||
         def->velocity0[2] != 0.0))
        return gb_error_set(GB_EINVAL, "restitution, an initial height and an initial velocity need the unilateral "
                            "law (allowed with held: e = 0, height 0, velocity 0)");
    /* Under the unilateral law a grid body is a polyhedron pivoting about a vertex between impacts: ṙ_c = 0,
     * where eq 44 and the rolling equation are the same equation. Continuous contact moves the contact along
     * the surface, where only the rolling equation conserves energy (docs/rolling.md). */
    if (!gb_dynamics_contact_law_name(def->contact_law) ||
        (def->contact_law == GB_CONTACT_LAW_UNILATERAL && def->contact == GB_CONTACT_MODEL_CONTINUOUS &&
         def->variant != GB_VARIANT_ROLLING))
        return gb_error_set(GB_EINVAL, "contact law %d with contact model %s and equation %s (allowed: held with any; "
                            "unilateral with a grid model and either equation, or with continuous contact and the "
                            "rolling equation)", (int)def->contact_law, gb_contact_model_name(def->contact),
                            gb_dynamics_variant_name(def->variant));
    int status = gb_forcing_validate(&def->forcing);
    if (status) return status;
    gb_dynamics *d = calloc(1, sizeof *d);
    if (!d) return gb_error_set(GB_ENOMEM, "out of memory for the dynamics");
    d->surface = *surface;
    d->def = *def;
    d->refine = gb_contact_refine_default_def();
    gb_massprops props;
    status = body_massprops(surface, def, &props);
    if (!status) {
        const double l2 = def->length * def->length;
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) d->inertia[i][j] = props.inertia[i][j] * l2;
        d->mean_radius = props.L * def->length;
        /* Only what the contact model needs: a grid (and its tracker) or the certificate. */
        if (def->contact == GB_CONTACT_MODEL_CONTINUOUS) {
            status = gb_certify_create(surface, &def->certify, &d->certify);
            if (!status && def->certificate == GB_CERTIFICATE_ATLAS && def->atlas_shared) {
                d->atlas = def->atlas_shared;
                d->atlas_borrowed = 1;
            } else if (!status && def->certificate == GB_CERTIFICATE_ATLAS) {
                gb_atlas_def adef = def->atlas;
                adef.height_tol = def->certify.height_tol;
                status = gb_atlas_create(surface, &adef, &d->atlas);
                /* a file that is missing, stale or damaged is built anew (and replaced when saved) */
                if (!status && def->atlas_file) {
                    d->atlas_loaded = gb_atlas_load(d->atlas, def->atlas_file) == GB_OK;
                    if (!d->atlas_loaded) gb_error_clear();
                }
            }
        } else
            status = body_grid(d, surface, def);
    }
    if (status) {
        gb_dynamics_free(d);
        return status;
    }
    *out = d;
    return GB_OK;
}

void gb_dynamics_free(gb_dynamics *d)
{
    if (!d) return;
    if (!d->grid_borrowed) {
        gb_contact_tracker_free(d->tracker);
        gb_contact_grid_free(d->grid);
    }
    gb_certify_free(d->certify);
    if (!d->atlas_borrowed) gb_atlas_free(d->atlas);
    free(d);
}

/* ---------------------------------------------------------------- attitude */

/* z_b = Rᵀ e_z, the third row of R (eq 21), alone: the same arithmetic as gb_dynamics_rotation's. */
static void vertical_of_quaternion(const double q[4], double zb[3])
{
    const double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    zb[0] = 2 * (x * z - w * y), zb[1] = 2 * (y * z + w * x), zb[2] = 1 - 2 * (x * x + y * y);
}

void gb_dynamics_rotation(const double q[4], double R[9])
{
    const double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    R[0] = 1 - 2 * (y * y + z * z), R[1] = 2 * (x * y - w * z), R[2] = 2 * (x * z + w * y);
    R[3] = 2 * (x * y + w * z), R[4] = 1 - 2 * (x * x + z * z), R[5] = 2 * (y * z - w * x);
    R[6] = 2 * (x * z - w * y), R[7] = 2 * (y * z + w * x), R[8] = 1 - 2 * (x * x + y * y);
}

void gb_dynamics_quaternion(const double R[9], double q[4])
{
    /* Shepperd's method: divide by the largest of the four candidate components. */
    const double tr = R[0] + R[4] + R[8];
    if (tr >= R[0] && tr >= R[4] && tr >= R[8]) {
        const double s = 2 * sqrt(1 + tr);
        q[0] = s / 4, q[1] = (R[7] - R[5]) / s, q[2] = (R[2] - R[6]) / s, q[3] = (R[3] - R[1]) / s;
    } else if (R[0] >= R[4] && R[0] >= R[8]) {
        const double s = 2 * sqrt(1 + R[0] - R[4] - R[8]);
        q[0] = (R[7] - R[5]) / s, q[1] = s / 4, q[2] = (R[1] + R[3]) / s, q[3] = (R[2] + R[6]) / s;
    } else if (R[4] >= R[8]) {
        const double s = 2 * sqrt(1 + R[4] - R[0] - R[8]);
        q[0] = (R[2] - R[6]) / s, q[1] = (R[1] + R[3]) / s, q[2] = s / 4, q[3] = (R[5] + R[7]) / s;
    } else {
        const double s = 2 * sqrt(1 + R[8] - R[0] - R[4]);
        q[0] = (R[3] - R[1]) / s, q[1] = (R[2] + R[6]) / s, q[2] = (R[5] + R[7]) / s, q[3] = s / 4;
    }
}

/* ---------------------------------------------------------------- contact at a state */

typedef struct contact_eval {
    double rc[3], rc_dot[3];
    size_t index;
    gb_contact_point point; /* continuous model; grid models under the unilateral law */
} contact_eval;

static int grid_unilateral(const gb_dynamics *d)
{
    return d->def.contact != GB_CONTACT_MODEL_CONTINUOUS && d->def.contact_law == GB_CONTACT_LAW_UNILATERAL;
}

/* Grid node `index` as a contact point at vertical zb: fixed in the body, its height ẑ_b·x. */
static void grid_point(const gb_dynamics *d, size_t index, const double zb[3], gb_contact_point *p)
{
    double unit[3];
    gb_contact_unit_vertical(zb, unit); /* a state's vertical: never zero */
    memset(p, 0, sizeof *p);
    gb_contact_grid_node(d->grid, index, &p->phi, &p->theta, p->rc);
    p->height = gb_vec_dot(unit, p->rc);
    p->is_minimum = 1;
    p->node = index;
}

/* The lowest grid node at zb, by the model's search (the paper's brute force, the tracker, or the
 * scene's lowest-node function). */
static int lowest_node(gb_dynamics *d, const double zb[3], gb_contact_node *node)
{
    int status;
    if (d->def.contact == GB_CONTACT_MODEL_GRID && d->def.grid_lowest) {
        double unit[3];
        status = gb_contact_unit_vertical(zb, unit);
        if (!status) {
            node->index = d->def.grid_lowest(d->def.grid_lowest_context, unit);
            node->visited = 0;
            if (node->index < gb_contact_grid_size(d->grid)) gb_contact_grid_node(d->grid, node->index, NULL, NULL, node->x);
            else status = gb_error_set(GB_EINVAL, "the lowest-node search returned node %zu of a grid of %zu",
                                       node->index, gb_contact_grid_size(d->grid));
        }
    } else {
        status = d->def.contact == GB_CONTACT_MODEL_GRID ? gb_contact_grid_brute(d->grid, zb, node)
                                                         : gb_contact_tracker_find(d->tracker, zb, node);
    }
    if (!status) d->contact_queries++, d->nodes_visited += node->visited;
    return status;
}

/* Two grid nodes whose heights differ by less than this [body length] are tied, not one below the other:
 * a few units of the last place of h (|x| < 1.19). Nodes of a ring around a chart pole tie exactly at
 * some attitudes; a tie is not a crossing, and the event is located where the new node is lower by this. */
#define GRID_TIE 4e-15

/* A grid body under the unilateral law: the lowest node at zb but the node(s) it stands on (P; and Q on
 * two points), the one it meets the plane with next. Its gap to them is continuous in time (a minimum
 * of continuous heights), so an event located on it is the first node to reach the plane. */
static int next_node(gb_dynamics *d, const double zb[3], gb_contact_point *other)
{
    const size_t stands[2] = {d->index, d->contact2.node};
    gb_contact_node node;
    const int status = gb_contact_grid_lowest_except(d->grid, zb, d->next_hint, stands, 1 + d->two_point, &node);
    if (status) return status;
    grid_point(d, node.index, zb, other);
    d->next_hint = node.index; /* the search's seed next time (it changes no answer) */
    d->contact_queries++, d->nodes_visited += node.visited;
    return GB_OK;
}

/* The contact point `from` continued to vertical zb: Newton from its angles (continuous), or the same
 * node (grid). */
static int point_at(gb_dynamics *d, const double zb[3], const gb_contact_point *from, gb_contact_point *out)
{
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) {
        grid_point(d, from->node, zb, out);
        return GB_OK;
    }
    return gb_contact_refine(&d->surface, zb, from->phi, from->theta, &d->refine, out);
}

/* ṙ of contact point p per the angular velocity w (eq 72; a grid node is fixed in the body: 0). */
static int point_rate(const gb_dynamics *d, const double zb[3], const gb_contact_point *p, const double w[3], double v[3])
{
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) {
        memset(v, 0, 3 * sizeof *v);
        return GB_OK;
    }
    return gb_contact_rate(&d->surface, zb, p, w, v, NULL);
}

/* The contact for vertical zb (unit) and angular velocity ω, warm-started from the accepted one. */
static int contact_at(gb_dynamics *d, double t, const double zb[3], const double omega[3], contact_eval *c)
{
    const double l = d->def.length;
    memset(c->rc_dot, 0, sizeof c->rc_dot);
    if (grid_unilateral(d)) {
        /* the node the body pivots about: a change of node is an impact, located as an event */
        grid_point(d, d->index, zb, &c->point);
        for (int k = 0; k < 3; k++) c->rc[k] = l * c->point.rc[k];
        c->index = d->index;
        return GB_OK;
    }
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) {
        gb_contact_node node;
        const int status = lowest_node(d, zb, &node);
        if (status) return status;
        for (int k = 0; k < 3; k++) c->rc[k] = l * node.x[k];
        c->index = node.index;
        return GB_OK; /* ṙ_c = 0 between grid switches */
    }
    double unit[3], start[2];
    int status = gb_contact_unit_vertical(zb, unit);
    if (status) return status;
    const int same = d->last_valid && memcmp(unit, d->last_zb, sizeof unit) == 0;
    if (same) {
        c->point = d->last_point;
    } else if (d->last_valid) {
        const double step[3] = {unit[0] - d->last_zb[0], unit[1] - d->last_zb[1], unit[2] - d->last_zb[2]};
        gb_contact_chart_offset(&d->last_point, gb_vec_dot(d->last_dq[0], step), gb_vec_dot(d->last_dq[1], step),
                                &start[0], &start[1]);
    } else {
        const double dt = t - d->contact_time;
        gb_contact_chart_offset(&d->contact, d->contact_rate[0] * dt, d->contact_rate[1] * dt, &start[0], &start[1]);
    }
    if (!same) status = gb_contact_refine(&d->surface, unit, start[0], start[1], &d->refine, &c->point);
    if ((status == GB_ENOCONV || (!status && !c->point.is_minimum)) && d->certify) {
        /* The continued branch has no minimum here (a fold of h inside the step): the contact is the
         * global minimum at this state, found and certified from scratch. */
        d->branches_lost++;
        status = gb_certify_global_minimum(d->certify, zb, &d->refine, &c->point);
    }
    if (!status && !c->point.is_minimum)
        status = gb_error_set(GB_ENOCONV, "continuous contact lost: Newton from the previous contact ended on a "
                              "point that is not a minimum (eq 35) at z_b = (%g, %g, %g)", zb[0], zb[1], zb[2]);
    /* the sensitivity (eq 70) serves ṙ_c (eq 72) and the next start */
    if (!status && !same) {
        status = gb_contact_sensitivity(&d->surface, unit, &c->point, d->last_dq);
        d->last_valid = !status;
        memcpy(d->last_zb, unit, sizeof d->last_zb);
        d->last_point = c->point;
    }
    if (status) return status;
    gb_contact_rate_from(d->last_dq, unit, &c->point, omega, c->rc_dot, NULL);
    for (int k = 0; k < 3; k++) c->rc[k] = l * c->point.rc[k], c->rc_dot[k] *= l;
    c->index = 0;
    return GB_OK;
}

/* The global contact at zb from scratch (initial state). */
static int contact_global(gb_dynamics *d, const double zb[3])
{
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) {
        gb_contact_node node;
        const int status = gb_contact_grid_brute(d->grid, zb, &node);
        if (!status) d->index = node.index, grid_point(d, node.index, zb, &d->contact);
        return status;
    }
    gb_certify_forget(d->certify);
    return gb_certify_global_minimum(d->certify, zb, &d->refine, &d->contact);
}

/* ---------------------------------------------------------------- equations of motion */

static void zb_of(const double R[9], double zb[3])
{
    zb[0] = R[6], zb[1] = R[7], zb[2] = R[8]; /* z_b = Rᵀ e_z: the third row of R (eq 21) */
}

/* I_P = I_C − m [r_c]×[r_c]× = I_C + m (|r_c|² I − r_c r_cᵀ) (eq 40). */
static void inertia_about_contact(const gb_dynamics *d, const double rc[3], double IP[3][3])
{
    const double m = d->def.mass, r2 = gb_vec_dot(rc, rc);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) IP[i][j] = d->inertia[i][j] + m * ((i == j) * r2 - rc[i] * rc[j]);
}

static void mat_vec(double A[3][3], const double v[3], double out[3])
{
    for (int i = 0; i < 3; i++) out[i] = A[i][0] * v[0] + A[i][1] * v[1] + A[i][2] * v[2];
}

/* Solve A x = b for a symmetric positive-definite 3 × 3 A by cofactors. */
static int solve3(double A[3][3], const double b[3], double x[3])
{
    const double c00 = A[1][1] * A[2][2] - A[1][2] * A[2][1], c01 = A[1][2] * A[2][0] - A[1][0] * A[2][2],
                 c02 = A[1][0] * A[2][1] - A[1][1] * A[2][0];
    const double det = A[0][0] * c00 + A[0][1] * c01 + A[0][2] * c02;
    if (!(det > 0.0) || !isfinite(det)) return gb_error_set(GB_ENUMERIC, "inertia about the contact is singular (det %g)", det);
    const double inv[3][3] = {
        {c00, A[0][2] * A[2][1] - A[0][1] * A[2][2], A[0][1] * A[1][2] - A[0][2] * A[1][1]},
        {c01, A[0][0] * A[2][2] - A[0][2] * A[2][0], A[0][2] * A[1][0] - A[0][0] * A[1][2]},
        {c02, A[0][1] * A[2][0] - A[0][0] * A[2][1], A[0][0] * A[1][1] - A[0][1] * A[1][0]}};
    for (int i = 0; i < 3; i++) x[i] = (inv[i][0] * b[0] + inv[i][1] * b[1] + inv[i][2] * b[2]) / det;
    return GB_OK;
}

/* ω̇ from eq 44 (paper) or the rolling equation, for the contact c and g_eff at the time. */
static int angular_acceleration(const gb_dynamics *d, double geff, const double zb[3], const double omega[3],
                                const contact_eval *c, double omega_dot[3])
{
    const double m = d->def.mass;
    double IP[3][3], IPw[3], gyro[3], tau[3], rhs[3], tmp[3], tmp2[3];
    inertia_about_contact(d, c->rc, IP);
    mat_vec(IP, omega, IPw);
    gb_vec_cross(omega, IPw, gyro);
    gb_vec_cross(c->rc, zb, tau); /* τ_g = m g_eff r_c × z_b (eq 41) */
    for (int k = 0; k < 3; k++) tau[k] = m * geff * tau[k] - d->def.damping * omega[k]; /* eqs 42–43 */
    for (int k = 0; k < 3; k++) rhs[k] = tau[k] - gyro[k];
    /* m r_c × (ṙ_c × ω), present in both variants' algebra */
    gb_vec_cross(c->rc_dot, omega, tmp);
    gb_vec_cross(c->rc, tmp, tmp2);
    if (d->def.variant == GB_VARIANT_ROLLING) {
        for (int k = 0; k < 3; k++) rhs[k] += m * tmp2[k];
    } else {
        /* İ_P ω = −m (ṙ_c × (r_c × ω) + r_c × (ṙ_c × ω)) (eq 45), moved to the right-hand side */
        double a[3], b[3];
        gb_vec_cross(c->rc, omega, a);
        gb_vec_cross(c->rc_dot, a, b);
        for (int k = 0; k < 3; k++) rhs[k] += m * (b[k] + tmp2[k]);
    }
    return solve3(IP, rhs, omega_dot);
}

/* The centroid's acceleration relative to the support under rolling kinematics (body frame), a_G = ω ×
 * (r_c × ω) + ṙ_c × ω + r_c × ω̇, into acc, and the normal force N = m (g_eff + z_b·a_G). */
static double normal_force_of(const gb_dynamics *d, double geff, const double zb[3], const double omega[3],
                              const double omega_dot[3], const contact_eval *c, double acc[3])
{
    double a[3], b[3], e[3], f[3];
    gb_vec_cross(c->rc, omega, a);
    gb_vec_cross(omega, a, b);
    gb_vec_cross(c->rc_dot, omega, e);
    gb_vec_cross(c->rc, omega_dot, f);
    for (int k = 0; k < 3; k++) acc[k] = b[k] + e[k] + f[k];
    return d->def.mass * (geff + gb_vec_dot(acc, zb));
}

/* The accepted contact (P) becomes p; a grid body's node index with it. */
static void set_contact(gb_dynamics *d, const gb_contact_point *p)
{
    d->contact = *p;
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) d->index = p->node;
}

/* ---------------------------------------------------------------- flight (unilateral law) */

enum { FLIGHT_NONE = 0, FLIGHT_LIFT_OFF = 1, FLIGHT_LANDING = 2 };

/* A landing is the lowest point this far below the plane [body lengths]. At a lift-off the gap opens as
 * the cube of the time (N = 0 there: the gap's first two derivatives vanish), where its rounding (1e-16 of
 * the centroid's height) would meet the plane again at once; 1e-12 is far above that rounding and far
 * below any length of the problem. */
#define FLIGHT_GAP_TOL GB_DYNAMICS_LANDING_TOL
/* The deepest dip a lift-off may make [body lengths] (lift_off_consistent): a micrometre for a body of a metre,
 * below the elastic compliance of any real body under its own weight. */
#define LIFT_OFF_DIP_MAX 1e-6

/* ∫ g_eff ds over [t0, t] and its integral again, ∫∫ g_eff du ds, in closed form from eq 25. */
static void geff_integrals(const gb_forcing *f, double t0, double t, double *once, double *twice)
{
    const double dt = t - t0;
    const double amp[2] = {f->a1, f->a2}, w[2] = {f->omega, 2.0 * f->omega}, phase[2] = {0.0, f->psi};
    *once = f->g * dt;
    *twice = 0.5 * f->g * dt * dt;
    for (int k = 0; k < 2; k++) {
        if (amp[k] == 0.0) continue; /* as gb_forcing skips it */
        const double s0 = sin(w[k] * t0 + phase[k]), c0 = cos(w[k] * t0 + phase[k]);
        const double s1 = sin(w[k] * t + phase[k]), c1 = cos(w[k] * t + phase[k]);
        *once += amp[k] / w[k] * (s1 - s0);
        *twice += amp[k] / w[k] * ((c0 - c1) / w[k] - s0 * dt);
    }
}

/* In flight at time t: the centroid's height above the plane and its velocity relative to the plane
 * (inertial axes). In the plane's frame the only force is the weight m g_eff: ζ̈ = −g_eff, and the
 * horizontal velocity is constant. */
static void flight_state(const gb_dynamics *d, double t, double *zeta, double v[3])
{
    double once, twice;
    geff_integrals(&d->def.forcing, d->fly_t0, t, &once, &twice);
    *zeta = d->fly_zeta0 + d->fly_v0[2] * (t - d->fly_t0) - twice;
    v[0] = d->fly_v0[0], v[1] = d->fly_v0[1], v[2] = d->fly_v0[2] - once;
}

/* Torque-free but for the damping torque −c ω (eq 42, which the scene keeps in flight): I_G ω̇ + ω × I_G ω = −c ω. */
static int free_angular_acceleration(const gb_dynamics *d, const double omega[3], double omega_dot[3])
{
    double I[3][3], Iw[3], gyro[3], rhs[3];
    memcpy(I, d->inertia, sizeof I);
    mat_vec(I, omega, Iw);
    gb_vec_cross(omega, Iw, gyro);
    for (int k = 0; k < 3; k++) rhs[k] = -gyro[k] - d->def.damping * omega[k];
    return solve3(I, rhs, omega_dot);
}

/* The body leaves the plane (or bounces) at time t: its centroid at height zeta above the plane, moving
 * with v_body (body axes) relative to it. */
static void start_flight(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double v_body[3], double zeta)
{
    d->gap_allow = FLIGHT_GAP_TOL;
    double R[9];
    gb_dynamics_rotation(y + GB_STATE_Q, R);
    for (int i = 0; i < 3; i++) d->fly_v0[i] = R[3 * i] * v_body[0] + R[3 * i + 1] * v_body[1] + R[3 * i + 2] * v_body[2];
    d->fly_t0 = t;
    d->fly_zeta0 = zeta;
    if (!d->flying) d->flight_since = t;
    d->flying = 1;
}

/* Rolling on the accepted contact alone at state y: its normal force N = m (g_eff + z_b·a_G). */
static int one_point_normal(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], double *n)
{
    double zb[3], geff, geff_rate, w_dot[3], acc[3];
    contact_eval c;
    vertical_of_quaternion(y + GB_STATE_Q, zb);
    gb_forcing_geff_with_rate(&d->def.forcing, t, &geff, &geff_rate);
    int status = contact_at(d, t, zb, y + GB_STATE_OMEGA, &c);
    if (!status) status = angular_acceleration(d, geff, zb, y + GB_STATE_OMEGA, &c, w_dot);
    *n = status ? NAN : normal_force_of(d, geff, zb, y + GB_STATE_OMEGA, w_dot, &c, acc);
    return status;
}

/* Newton's restitution at a point approaching the plane with normal speed `approach` (> 0) at time t,
 * and the end to bouncing: a rebound e·approach that would fall back within settle_time under g_eff
 * (2 e approach / g_eff < settle_time) is taken as plastic, so that a bounce sequence ends in finite time. */
static double restitution_at(const gb_dynamics *d, double t, double approach)
{
    const double e = d->def.restitution;
    if (e == 0.0) return 0.0;
    const double geff = gb_forcing_geff(&d->def.forcing, t);
    return e * approach < 0.5 * fmax(geff, 0.0) * d->def.settle_time ? 0.0 : e;
}

/* ---------------------------------------------------------------- the two-point mode (unilateral law) */

/* The body rolling on P (the accepted contact, continued) and Q (contact2, continued) at state y. */
typedef struct two_point_eval {
    contact_eval p;           /* P, continued as the one-point contact is */
    gb_contact_point q;       /* Q, continued by Newton from the accepted Q */
    double rp[3], rq[3];      /* [m], from the centroid */
    double u[3], dist;        /* (r_P − r_Q) / |r_P − r_Q|, |r_P − r_Q| */
    double sigma, omega_dot[3];
    double normal[2];         /* N_P, N_Q */
    double friction_needed, balance;
    int merged;               /* the end of a crease: Q merged with P or vanished; only p is filled */
} two_point_eval;

static void vertical_of(const double y[GB_STATE_SIZE], double zb[3]);

/* Q of the two-point mode at vertical zb: Newton (continuous contact) from the last Q found since the
 * accepted state moved by its sensitivity (eq 70), as P is (contact_at); then Q's sensitivity for its rate
 * and the next start. A grid node as it is. */
static int second_point(gb_dynamics *d, const double zb[3], gb_contact_point *q)
{
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) return point_at(d, zb, &d->contact2, q);
    double unit[3], start[2] = {d->contact2.phi, d->contact2.theta};
    int status = gb_contact_unit_vertical(zb, unit);
    if (status) return status;
    if (d->q_valid) {
        const double step[3] = {unit[0] - d->q_zb[0], unit[1] - d->q_zb[1], unit[2] - d->q_zb[2]};
        gb_contact_chart_offset(&d->q_last, gb_vec_dot(d->q_dq[0], step), gb_vec_dot(d->q_dq[1], step), &start[0],
                                &start[1]);
    }
    status = gb_contact_refine(&d->surface, unit, start[0], start[1], &d->refine, q);
    if (status || !q->is_minimum) return status;
    d->q_valid = gb_contact_sensitivity(&d->surface, unit, q, d->q_dq) == GB_OK;
    memcpy(d->q_zb, unit, sizeof d->q_zb);
    d->q_last = *q;
    return GB_OK;
}

/* The mode at state y: the points, σ and ω̇; with `forces`, the normal forces, the friction they need and
 * the balance too (events and observables need them; the vector field does not). */
static int two_point_eval_at(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], two_point_eval *tp, int forces)
{
    const double L = d->def.length, m = d->def.mass, c = d->def.damping;
    const double *omega = y + GB_STATE_OMEGA;
    double zb[3];
    vertical_of(y, zb);
    const size_t lost = d->branches_lost;
    int status = contact_at(d, t, zb, omega, &tp->p);
    if (!status && d->branches_lost != lost)
        status = gb_error_set(GB_ENUMERIC, "two-point contact at t = %.9g: P has no minimum of height left (a fold)", t);
    if (!status) status = second_point(d, zb, &tp->q);
    if (status) return status;
    double dvec[3];
    for (int k = 0; k < 3; k++) tp->rp[k] = L * tp->p.point.rc[k], tp->rq[k] = L * tp->q.rc[k], dvec[k] = tp->rp[k] - tp->rq[k];
    tp->dist = gb_vec_norm(dvec);
    /* The end of a crease: Q's minimum of height merges with P's, or vanishes in a fold (Newton from Q ends on
     * a point that is not a minimum). The state is the body rolling on P alone, with no jump. */
    tp->merged = !tp->q.is_minimum || !(tp->dist > 1e-9 * L);
    if (tp->merged) return GB_OK;
    for (int k = 0; k < 3; k++) tp->u[k] = dvec[k] / tp->dist;
    const double *u = tp->u;
    tp->sigma = gb_vec_dot(omega, u);
    /* ṙ_P, ṙ_Q per unit σ (eq 72 with ω = u: the rates are linear in ω), and u̇ per unit σ */
    double vp[3], vq[3], du[3];
    /* each point's rate from the sensitivity its Newton solve left (contact_at's for P, second_point's for Q) */
    if (d->def.contact == GB_CONTACT_MODEL_CONTINUOUS && d->last_valid) gb_contact_rate_from(d->last_dq, d->last_zb, &tp->p.point, u, vp, NULL);
    else status = point_rate(d, zb, &tp->p.point, u, vp);
    if (!status && d->q_valid) gb_contact_rate_from(d->q_dq, d->q_zb, &tp->q, u, vq, NULL);
    else if (!status) status = point_rate(d, zb, &tp->q, u, vq);
    if (status) return status;
    for (int k = 0; k < 3; k++) vp[k] *= L, vq[k] *= L;
    const double rel[3] = {vp[0] - vq[0], vp[1] - vq[1], vp[2] - vq[2]}, along = gb_vec_dot(u, rel);
    for (int k = 0; k < 3; k++) du[k] = (rel[k] - along * u[k]) / tp->dist;
    /* I_u = uᵀ I_P u and its rate per unit σ, K = 2 uᵀ I_P u̇ + uᵀ İ_P u, İ_P = m (2 r·ṙ I − ṙ rᵀ − r ṙᵀ) */
    double IP[3][3], IPu[3];
    inertia_about_contact(d, tp->rp, IP);
    mat_vec(IP, u, IPu);
    const double Iu = gb_vec_dot(u, IPu);
    const double K = 2.0 * gb_vec_dot(IPu, du) + 2.0 * m * (gb_vec_dot(tp->rp, vp) - gb_vec_dot(u, vp) * gb_vec_dot(u, tp->rp));
    double geff, geff_rate, zxu[3];
    gb_forcing_geff_with_rate(&d->def.forcing, t, &geff, &geff_rate);
    gb_vec_cross(zb, u, zxu);
    /* d/dt(½ I_u σ²) = σ (I_u σ̇ + ½ K σ²) = −m g_eff ζ̇ − c σ², ζ̇ = −σ (z_b × u)·r_P */
    const double s = tp->sigma;
    const double sigma_dot = (m * geff * gb_vec_dot(zxu, tp->rp) - c * s - 0.5 * K * s * s) / Iu;
    for (int k = 0; k < 3; k++) tp->omega_dot[k] = sigma_dot * u[k] + s * s * du[k];
    if (!forces) {
        tp->normal[0] = tp->normal[1] = tp->friction_needed = tp->balance = NAN;
        return GB_OK;
    }
    /* Newton–Euler with these accelerations: the contact forces F = m a_G + m g_eff z_b, their moment
     * about G, M = I_G ω̇ + ω × I_G ω + c ω = r_P × F_P + r_Q × F_Q, so (r_P − r_Q) × F_P = M − r_Q × F
     * fixes F_P across PQ; its part along PQ (and Q's) is the internal force statics leaves open. */
    double acc[3], F[3], Iw[3], gyro[3], Iwd[3], M[3], rqF[3], X[3], FP[3];
    contact_eval at_p = {.rc_dot = {s * vp[0], s * vp[1], s * vp[2]}}; /* r_P moving at σ ṙ_P₁ */
    memcpy(at_p.rc, tp->rp, sizeof at_p.rc);
    normal_force_of(d, geff, zb, omega, tp->omega_dot, &at_p, acc);
    for (int k = 0; k < 3; k++) F[k] = m * (acc[k] + geff * zb[k]);
    mat_vec(d->inertia, omega, Iw);
    gb_vec_cross(omega, Iw, gyro);
    mat_vec(d->inertia, tp->omega_dot, Iwd);
    gb_vec_cross(tp->rq, F, rqF);
    for (int k = 0; k < 3; k++) M[k] = Iwd[k] + gyro[k] + c * omega[k], X[k] = (M[k] - rqF[k]) / tp->dist;
    tp->balance = fabs(gb_vec_dot(X, u)) * tp->dist / fmax(gb_vec_norm(M) + gb_vec_norm(rqF), 1e-300);
    gb_vec_cross(X, u, FP);
    tp->normal[0] = gb_vec_dot(zb, FP);
    tp->normal[1] = gb_vec_dot(zb, F) - tp->normal[0];
    const double n = tp->normal[0] + tp->normal[1], share = n > 0.0 ? tp->normal[0] / n : 0.5, fu = gb_vec_dot(F, u);
    double tan_p[3], tan_q[3];
    for (int k = 0; k < 3; k++) {
        tan_p[k] = FP[k] - tp->normal[0] * zb[k] + share * fu * u[k];
        tan_q[k] = F[k] - FP[k] - tp->normal[1] * zb[k] - share * fu * u[k];
    }
    tp->friction_needed = tp->normal[0] > 0.0 && tp->normal[1] > 0.0
                              ? fmax(gb_vec_norm(tan_p) / tp->normal[0], gb_vec_norm(tan_q) / tp->normal[1])
                              : INFINITY;
    return GB_OK;
}

static int two_point_at(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], two_point_eval *tp)
{
    return two_point_eval_at(d, t, y, tp, 1);
}

static int diverged(double t)
{
    return gb_error_set(GB_ENUMERIC, "t = %.9g: the state is no longer finite: the integration diverged (a step too "
                        "large for the scene's stiffest rate, such as the damping c over the inertia?)", t);
}

int gb_dynamics_state_finite(double t, const double y[GB_STATE_SIZE])
{
    for (int i = 0; i < GB_STATE_SIZE; i++)
        if (!isfinite(y[i])) return diverged(t);
    return GB_OK;
}

int gb_dynamics_rhs(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], double dydt[GB_STATE_SIZE])
{
    double zb[3];
    static const double at_rest[3] = {0.0, 0.0, 0.0};
    /* at rest on three points nothing turns, whatever rounding is left in the state's ω */
    const double *q = y + GB_STATE_Q, *omega = d->resting ? at_rest : y + GB_STATE_OMEGA;
    if (gb_dynamics_state_finite(t, y)) return GB_ENUMERIC;
    vertical_of_quaternion(q, zb);
    if (!(isfinite(zb[0]) && isfinite(zb[1]) && isfinite(zb[2]))) return diverged(t); /* a quaternion overflowed */
    contact_eval c;
    int status = GB_OK;
    double geff, geff_rate;
    gb_forcing_geff_with_rate(&d->def.forcing, t, &geff, &geff_rate);
    double zeta = NAN;
    if (d->flying) {
        /* the centroid's motion is in closed form; only the turning is integrated */
        double v[3];
        status = free_angular_acceleration(d, omega, dydt + GB_STATE_OMEGA);
        if (status) return status;
        flight_state(d, t, &zeta, v);
    } else if (d->resting) {
        status = contact_at(d, t, zb, omega, &c);
        if (status) return status;
        memset(dydt + GB_STATE_OMEGA, 0, 3 * sizeof *dydt);
    } else if (d->two_point) {
        two_point_eval tp;
        status = two_point_eval_at(d, t, y, &tp, 0);
        if (status) return status;
        c = tp.p;
        if (tp.merged) status = angular_acceleration(d, geff, zb, omega, &c, dydt + GB_STATE_OMEGA); /* on P alone */
        else memcpy(dydt + GB_STATE_OMEGA, tp.omega_dot, sizeof tp.omega_dot);
        if (status) return status;
    } else {
        status = contact_at(d, t, zb, omega, &c);
        if (!status) status = angular_acceleration(d, geff, zb, omega, &c, dydt + GB_STATE_OMEGA);
        if (status) return status;
    }
    /* q̇ = ½ q ⊗ (0, ω) (eq 23) */
    dydt[0] = -0.5 * (q[1] * omega[0] + q[2] * omega[1] + q[3] * omega[2]);
    dydt[1] = 0.5 * (q[0] * omega[0] + q[2] * omega[2] - q[3] * omega[1]);
    dydt[2] = 0.5 * (q[0] * omega[1] + q[3] * omega[0] - q[1] * omega[2]);
    dydt[3] = 0.5 * (q[0] * omega[2] + q[1] * omega[1] - q[2] * omega[0]);
    /* Ẇ = P_d + m ġ_eff ζ with ζ = −z_b·r_c in contact (eqs 37, 50); in flight E = ½ m |v|² + ½ ω·I_G ω +
     * m g_eff ζ obeys the same balance, since d/dt(½ m |v|²) = −m g_eff ζ̇ there */
    if (!d->flying) zeta = -gb_vec_dot(zb, c.rc);
    dydt[GB_STATE_WORK] = -d->def.damping * gb_vec_dot(omega, omega) +
                          d->def.mass * geff_rate * zeta;
    return GB_OK;
}

/* Store the accepted contact's time and its (φ̇, θ̇) (eq 72) for the next Newton starts. */
static int remember_rate(gb_dynamics *d, double t, const double y[GB_STATE_SIZE])
{
    double zb[3], rc_dot[3];
    vertical_of(y, zb);
    d->contact_time = t;
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) return GB_OK; /* a node does not move on the body */
    if (gb_contact_rate(&d->surface, zb, &d->contact, y + GB_STATE_OMEGA, rc_dot, d->contact_rate) != GB_OK)
        d->contact_rate[0] = d->contact_rate[1] = 0.0; /* a singular Hessian: start from the point itself */
    return GB_OK;
}

/* The vertical of state y (q need not be normalised). */
static void vertical_of(const double y[GB_STATE_SIZE], double zb[3]) { vertical_of_quaternion(y + GB_STATE_Q, zb); }

/* Is `candidate` the global minimum at zb? The atlas answers where it can, gb_certify elsewhere. */
static int check_global(gb_dynamics *d, const double zb[3], const gb_contact_point *candidate, gb_certify_result *r)
{
    if (d->atlas) {
        const int status = gb_atlas_check(d->atlas, zb, candidate, &d->refine, r);
        if (status || r->verdict != GB_CERTIFY_UNDECIDED) return status;
        d->atlas_fallbacks++;
    }
    return gb_certify_check(d->certify, zb, candidate, &d->refine, r);
}

/* A switch target, whichever search found it, polished by Newton from its angles rounded to 2⁻²⁰ rad:
 * the same minimum then has the same bits whether the atlas or gb_certify found it, from whatever
 * start (two finds differ by ~1e-15 rad; their rounded angles differ only if a multiple of 2⁻²⁰ lies
 * between them). Newton converges from 1e-6 rad in a few steps to the same minimum. */
static int canonical_minimum(gb_dynamics *d, const double zb[3], gb_contact_point *p)
{
    const double grid = 1048576.0;
    gb_contact_point q;
    const int status = gb_contact_refine(&d->surface, zb, nearbyint(p->phi * grid) / grid,
                                         nearbyint(p->theta * grid) / grid, &d->refine, &q);
    if (status) return status;
    if (!q.is_minimum)
        return gb_error_set(GB_ENOCONV, "polishing the switch target at (%.17g, %.17g) ended on a point that is "
                            "not a minimum", p->phi, p->theta);
    *p = q;
    return GB_OK;
}

/* Two contact points within 1e-7 body lengths of each other: the same point. */
static int same_point(const gb_contact_point *a, const gb_contact_point *b)
{
    const double dx[3] = {a->rc[0] - b->rc[0], a->rc[1] - b->rc[1], a->rc[2] - b->rc[2]};
    return gb_vec_norm(dx) < 1e-7;
}

/* Continuous contact at state y: the continued branch (*continued) and, when the certificate finds a
 * lower local minimum, that minimum (*other, *found = 1). */
static int competitor(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *continued,
                      gb_contact_point *other, int *found)
{
    double zb[3];
    vertical_of(y, zb);
    /* For the same z_b, t, ω and accepted contact the answer is the same minimum (its last bits depend
     * on Newton's start, the last contact found), and a run makes the same calls in the same order, so
     * the memo changes no result. The accepted contact changes only in gb_dynamics_accept and
     * gb_dynamics_switch_to (they clear the memo). */
    const double key[8] = {zb[0], zb[1], zb[2], t, y[GB_STATE_OMEGA], y[GB_STATE_OMEGA + 1], y[GB_STATE_OMEGA + 2], 0.0};
    if (d->memo_valid && memcmp(key, d->memo_key, sizeof key) == 0) {
        *continued = d->memo_continued;
        *found = d->memo_found;
        if (*found) *other = d->memo_other;
        return GB_OK;
    }
    contact_eval c;
    int status = contact_at(d, t, zb, y + GB_STATE_OMEGA, &c);
    if (status) return status;
    *continued = c.point;
    *found = 0;
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) {
        /* a grid body: the next node, when it is strictly lower than the one the body pivots about */
        status = next_node(d, zb, other);
        if (status) return status;
        *found = other->height < continued->height - GRID_TIE;
        memcpy(d->memo_key, key, sizeof key);
        d->memo_continued = *continued, d->memo_found = *found, d->memo_other = *other, d->memo_valid = 1;
        return GB_OK;
    }
    /* A lower minimum found is checked in turn, until the lowest is proved global: with several
     * lower minima the switch goes to the global one, whichever the search met first. */
    gb_contact_point candidate = c.point;
    for (int round = 0; round < 16; round++) {
        gb_certify_result r;
        status = check_global(d, zb, &candidate, &r);
        if (status) return status;
        if (r.verdict != GB_CERTIFY_LOWER_FOUND) break;
        candidate = r.lower;
        *other = r.lower;
        *found = 1;
    }
    if (*found) status = canonical_minimum(d, zb, other);
    if (status) return status;
    /* Under the unilateral law a lower minimum within 1e-7 of the continued one is the same contact (a tie
     * where minima crowd together at the end of a crease), as in the two-point mode: an impact between two
     * coincident points has no meaning. (The held law keeps its switches as they always were.) */
    if (*found && d->def.contact_law == GB_CONTACT_LAW_UNILATERAL && same_point(other, continued)) *found = 0;
    if (*found && continued->height - other->height < d->lift_allow) *found = 0; /* a lifted point's dip */
    memcpy(d->memo_key, key, sizeof key);
    d->memo_continued = *continued;
    d->memo_found = *found;
    if (*found) d->memo_other = *other;
    d->memo_valid = 1;
    return GB_OK;
}

void gb_dynamics_contact_work(const gb_dynamics *d, size_t *queries, size_t *nodes)
{
    const int counted = d->def.contact != GB_CONTACT_MODEL_CONTINUOUS && !(d->def.contact == GB_CONTACT_MODEL_GRID &&
                                                                          d->def.grid_lowest);
    *queries = counted ? d->contact_queries : 0;
    *nodes = counted ? d->nodes_visited : 0;
}

int gb_dynamics_certify_stats(const gb_dynamics *d, gb_certify_stats *out)
{
    if (!d->certify) return gb_error_set(GB_EINVAL, "the certificate belongs to continuous contact only");
    gb_certify_get_stats(d->certify, out);
    return GB_OK;
}

int gb_dynamics_atlas_stats(const gb_dynamics *d, gb_atlas_stats *out, size_t *fallbacks, int *loaded)
{
    if (!d->atlas) return gb_error_set(GB_EINVAL, "the atlas belongs to continuous contact with certificate = atlas only");
    gb_atlas_get_stats(d->atlas, out);
    *fallbacks = d->atlas_fallbacks;
    *loaded = d->atlas_loaded;
    return GB_OK;
}

void gb_dynamics_share_atlas(gb_dynamics *to, const gb_dynamics *from)
{
    if (!to->atlas || !from->atlas) return;
    if (!to->atlas_borrowed) gb_atlas_free(to->atlas);
    to->atlas = from->atlas;
    to->atlas_borrowed = 1;
}

int gb_dynamics_hull_stats(const gb_dynamics *d, size_t *vertices, int *loaded)
{
    if (!d->tracker) return gb_error_set(GB_EINVAL, "the contact model %s has no hull (allowed: fast-grid)",
                                         gb_contact_model_name(d->def.contact));
    *vertices = gb_contact_tracker_vertices(d->tracker);
    *loaded = d->hull_loaded;
    return GB_OK;
}

int gb_dynamics_save_hull(const gb_dynamics *d)
{
    if (!d->tracker || !d->def.hull_file || d->hull_loaded || !gb_contact_tracker_vertices(d->tracker)) return GB_OK;
    return gb_contact_tracker_save(d->tracker, d->def.hull_file);
}

int gb_dynamics_save_atlas(const gb_dynamics *d)
{
    if (!d->atlas || !d->def.atlas_file) return GB_OK;
    /* loaded from the file and no cell proved since: the file holds everything this run has */
    gb_atlas_stats st;
    gb_atlas_get_stats(d->atlas, &st);
    if (d->atlas_loaded && st.build_seconds == 0.0) return GB_OK;
    /* the cells another run wrote there since this one loaded it are kept (missing or stale: replaced) */
    return gb_atlas_merge_save(d->atlas, d->def.atlas_file);
}

static const char *const impact_kind_names[] = {"switch", "two-point", "lift", "third-point", "lift-off", "landing", "bounce",
                                                "crease-end"};

const char *gb_dynamics_impact_kind_name(gb_dynamics_impact_kind k) { return (unsigned)k < 8 ? impact_kind_names[k] : NULL; }

/* The plastic impact (gb_impact, body axes, the plane's normal z_b) of the body turning with the ω of y
 * about the point `rest` (at rest on the plane before), on the plane at `count` points [m]. */
static int impact_solve(const gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double rest[3],
                        const double (*points)[3], int count, double e, double v_before[3], gb_impact_result *r)
{
    double zb[3];
    vertical_of(y, zb);
    const double arm[3] = {-rest[0], -rest[1], -rest[2]}; /* G − P */
    gb_vec_cross(y + GB_STATE_OMEGA, arm, v_before);
    gb_impact_body body = {d->def.mass, {{0}}};
    memcpy(body.inertia, d->inertia, sizeof body.inertia);
    if (gb_impact_solve(&body, zb, e, points, count, v_before, y + GB_STATE_OMEGA, r))
        return gb_error_set(GB_ENUMERIC, "unilateral contact at t = %.9g: %s; a finite friction coefficient is not built yet",
                            t, gb_error_message());
    return GB_OK;
}

/* The plane can only push. The normal impulse at every point of an impact is at least −(rounding: 1e-9
 * of the momentum m (|v_G| + |ω| ℓ) the impact acts on, ℓ the farthest point); of an impact the settle rule
 * lumped (`settled`), the points it holds that were already on the plane may pull by the weight's impulse
 * over the return the rule removes, at most m g_max settle_time (g_max the largest g_eff; the Table 1 runs
 * pull by at most 0.4 of it). Beyond, the plane would have to pull: GB_ENUMERIC, "the plane cannot absorb
 * the impact". The new point is `arriving` (its impulse is never a pull). */
static int pulling_point(const gb_dynamics *d, const gb_impact_result *r, const double (*points)[3], int count,
                         int arriving, int settled, const double v_before[3], const double omega_before[3], double *allowed)
{
    const gb_forcing *f = &d->def.forcing;
    double reach = 0.0;
    for (int k = 0; k < count; k++) reach = fmax(reach, gb_vec_norm(points[k]));
    const double m = d->def.mass, rounding = 1e-9 * m * (gb_vec_norm(v_before) + gb_vec_norm(omega_before) * reach);
    const double lumped = settled ? m * (f->g + fabs(f->a1) + fabs(f->a2)) * d->def.settle_time : 0.0;
    for (int k = 0; k < count; k++) {
        *allowed = rounding + (k == arriving ? 0.0 : lumped);
        if (r->normal_impulse[k] < -*allowed) return k;
    }
    return -1;
}

static int plane_pushes(const gb_dynamics *d, double t, const gb_impact_result *r, const double (*points)[3], int count,
                        int arriving, int settled, const double v_before[3], const double omega_before[3])
{
    double allowed;
    const int k = pulling_point(d, r, points, count, arriving, settled, v_before, omega_before, &allowed);
    if (k < 0) return GB_OK;
    return gb_error_set(GB_ENUMERIC, "unilateral contact at t = %.9g: the plane cannot absorb the impact: it would have to "
                        "pull with a normal impulse of %.3g N s at point (%.6g, %.6g, %.6g) m (allowed: pushes, or a pull of "
                        "at most %.3g N s where the settle rule holds a point already on the plane) (the body moves at %.3g "
                        "m/s and turns at %.3g rad/s)", t, r->normal_impulse[k], points[k][0], points[k][1], points[k][2],
                        allowed, gb_vec_norm(v_before), gb_vec_norm(omega_before));
}

/* Book a change of contact: an impact's loss (a lift has none) and the sink. */
static int book(gb_dynamics *d, const gb_dynamics_impact *e)
{
    d->settled += (size_t)e->settled;
    d->lifts += e->kind == GB_IMPACT_LIFT;
    d->third_points += e->kind == GB_IMPACT_THIRD;
    d->lift_offs += e->kind == GB_IMPACT_LIFT_OFF;
    d->landings += e->kind == GB_IMPACT_LANDING;
    d->bounces += e->kind == GB_IMPACT_BOUNCE || (e->kind == GB_IMPACT_LANDING && e->rebound);
    if (e->kind != GB_IMPACT_LIFT && e->kind != GB_IMPACT_LIFT_OFF && e->kind != GB_IMPACT_CREASE_END) {
        d->impacts++;
        d->impact_loss += e->kinetic_before - e->kinetic_after - e->potential_jump;
        d->impact_friction_max = fmax(d->impact_friction_max, e->friction_needed);
        d->impacts_over_friction += e->friction_needed > d->def.friction;
    }
    d->memo_valid = 0; /* ω may have changed */
    return d->impact_sink ? d->impact_sink(d->impact_context, e) : GB_OK;
}

/* Fill an impact record from its points and the solver's answer at the new point `k` and the old one
 * `k_old` (−1: none); ω in y takes its value after. */
static void record(gb_dynamics_impact *e, double y[GB_STATE_SIZE], const double old_point[3], const double new_point[3],
                   const double v_before[3], const gb_impact_result *r, int k, int k_old)
{
    double *omega = y + GB_STATE_OMEGA;
    memcpy(e->old_point, old_point, sizeof e->old_point);
    memcpy(e->new_point, new_point, sizeof e->new_point);
    memcpy(e->omega_before, omega, sizeof e->omega_before);
    memcpy(e->v_before, v_before, sizeof e->v_before);
    memcpy(omega, r->omega, sizeof r->omega);
    memcpy(e->omega_after, r->omega, sizeof e->omega_after);
    memcpy(e->v_after, r->v, sizeof e->v_after);
    e->normal_impulse = r->normal_impulse[k], e->tangential_impulse = r->tangential_impulse[k];
    e->old_normal_impulse = k_old >= 0 ? r->normal_impulse[k_old] : 0.0;
    e->friction_needed = r->friction_needed;
    e->kinetic_before = r->energy_before, e->kinetic_after = r->energy_after;
}

/* The plastic impact that stops both P and Q (r_P, r_Q [m]), from the state y turning about P: ω⁺ = σ u
 * along PQ with u·H_P kept (the impulses at P and Q have no moment about the line PQ), H_P = I_G ω + m
 * (G − P) × v_G; the impulses from the momentum and moment jumps, the part along PQ split as the normal
 * impulses (as for the two-point mode's forces). */
static void hold_both(const gb_dynamics *d, const double y[GB_STATE_SIZE], const double rp[3], const double rq[3],
                      const double v_before[3], gb_impact_result *r)
{
    const double m = d->def.mass, *omega = y + GB_STATE_OMEGA;
    double zb[3], dvec[3], u[3], IP[3][3], IPu[3], Iw[3], gp[3], HP[3];
    vertical_of(y, zb);
    for (int k = 0; k < 3; k++) dvec[k] = rp[k] - rq[k];
    const double dist = gb_vec_norm(dvec);
    if (dist <= GB_IMPACT_SAME_POINT * fmax(gb_vec_norm(rp), gb_vec_norm(rq))) {
        /* P and Q are one point (GB_IMPACT_SAME_POINT): it is held at rest, and the impulse is Q's */
        const double both[2][3] = {{rp[0], rp[1], rp[2]}, {rq[0], rq[1], rq[2]}};
        gb_impact_body body = {m, {{0}}};
        memcpy(body.inertia, d->inertia, sizeof body.inertia);
        if (gb_impact_hold_all(&body, zb, both, 2, v_before, omega, r) == GB_OK) {
            r->normal_impulse[1] = r->normal_impulse[0], r->tangential_impulse[1] = r->tangential_impulse[0];
            r->normal_impulse[0] = r->tangential_impulse[0] = 0.0;
            memcpy(r->impulse[1], r->impulse[0], sizeof r->impulse[1]);
            memset(r->impulse[0], 0, sizeof r->impulse[0]);
        }
        gb_error_clear();
        return;
    }
    for (int k = 0; k < 3; k++) u[k] = dvec[k] / dist;
    mat_vec((double (*)[3])d->inertia, omega, Iw);
    gb_vec_cross((const double[3]){-rp[0], -rp[1], -rp[2]}, v_before, gp);
    for (int k = 0; k < 3; k++) HP[k] = Iw[k] + m * gp[k];
    inertia_about_contact(d, rp, IP);
    mat_vec(IP, u, IPu);
    const double sigma = gb_vec_dot(u, HP) / gb_vec_dot(u, IPu);
    memset(r, 0, sizeof *r);
    for (int k = 0; k < 3; k++) r->omega[k] = sigma * u[k];
    gb_vec_cross(r->omega, (const double[3]){-rp[0], -rp[1], -rp[2]}, r->v);
    gb_impact_body body = {m, {{0}}};
    memcpy(body.inertia, d->inertia, sizeof body.inertia);
    r->energy_before = gb_impact_energy(&body, v_before, omega);
    r->energy_after = gb_impact_energy(&body, r->v, r->omega);
    double Pi[3], dH[3], dw[3], rqPi[3], X[3], PP[3];
    for (int k = 0; k < 3; k++) Pi[k] = m * (r->v[k] - v_before[k]), dw[k] = r->omega[k] - omega[k];
    mat_vec((double (*)[3])d->inertia, dw, dH);
    gb_vec_cross(rq, Pi, rqPi);
    for (int k = 0; k < 3; k++) X[k] = (dH[k] - rqPi[k]) / dist;
    gb_vec_cross(X, u, PP);
    r->normal_impulse[0] = gb_vec_dot(zb, PP);
    r->normal_impulse[1] = gb_vec_dot(zb, Pi) - r->normal_impulse[0];
    const double n = r->normal_impulse[0] + r->normal_impulse[1], share = n > 0.0 ? r->normal_impulse[0] / n : 0.5;
    const double pu = gb_vec_dot(Pi, u);
    double tp[3], tq[3];
    for (int k = 0; k < 3; k++) {
        tp[k] = PP[k] - r->normal_impulse[0] * zb[k] + share * pu * u[k];
        tq[k] = Pi[k] - PP[k] - r->normal_impulse[1] * zb[k] - share * pu * u[k];
    }
    r->tangential_impulse[0] = gb_vec_norm(tp), r->tangential_impulse[1] = gb_vec_norm(tq);
    /* at Q, which lands; P's normal impulse may be a small pull (see gb_dynamics_impact.old_normal_impulse) */
    r->friction_needed = r->normal_impulse[1] > 0.0   ? r->tangential_impulse[1] / r->normal_impulse[1]
                         : r->tangential_impulse[1] > 0.0 ? INFINITY
                                                          : 0.0; /* no impulse at all (a point arriving at rest) */
    r->holds[0] = r->holds[1] = 1;
    r->feasible_sets = 1;
}

/* After an impact at which P lifts and the body rolls on Q with ω (y): how soon P falls back, 2 v_n/|a_n|
 * from P's normal velocity and acceleration under the rolling equation about Q (INFINITY when a_n >= 0). */
static double return_time(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *q,
                          const double v[3], const double rp[3])
{
    const double L = d->def.length, *omega = y + GB_STATE_OMEGA;
    double zb[3], geff, geff_rate, w_dot[3];
    vertical_of(y, zb);
    gb_forcing_geff_with_rate(&d->def.forcing, t, &geff, &geff_rate);
    contact_eval c;
    memset(&c, 0, sizeof c);
    if (point_rate(d, zb, q, omega, c.rc_dot)) return INFINITY;
    for (int k = 0; k < 3; k++) c.rc[k] = L * q->rc[k], c.rc_dot[k] *= L;
    if (angular_acceleration(d, geff, zb, omega, &c, w_dot)) {
        gb_error_clear();
        return INFINITY;
    }
    /* a_G rolling about Q, then P's material point: a_P = a_G + ω̇ × r_P + ω × (ω × r_P) */
    double acc[3], g[3], h[3], wr[3];
    normal_force_of(d, geff, zb, omega, w_dot, &c, acc);
    gb_vec_cross(w_dot, rp, g);
    gb_vec_cross(omega, rp, wr);
    gb_vec_cross(omega, wr, h);
    double an = 0.0, vn = gb_vec_dot(zb, v) + gb_vec_dot(zb, wr);
    for (int k = 0; k < 3; k++) an += zb[k] * (acc[k] + g[k] + h[k]);
    return an < 0.0 ? 2.0 * fmax(vn, 0.0) / -an : INFINITY;
}

/* Does the new point q [m] meet the plane at rest: no impulse at all, and its normal velocity (the body
 * turning with the ω of y about P, the centroid at v) below 1e-9 of √(g_max L), the rounding of a located
 * event's time? */
static int grazing(const gb_dynamics *d, const double y[GB_STATE_SIZE], const double v[3], const gb_impact_result *r,
                   const double q[3])
{
    const gb_forcing *f = &d->def.forcing;
    double zb[3], wq[3];
    vertical_of(y, zb);
    gb_vec_cross(y + GB_STATE_OMEGA, q, wq);
    const double vn = gb_vec_dot(zb, v) + gb_vec_dot(zb, wq);
    const double scale = sqrt((f->g + fabs(f->a1) + fabs(f->a2)) * d->def.length);
    return r->normal_impulse[0] == 0.0 && r->normal_impulse[1] == 0.0 && fabs(vn) <= 1e-9 * scale;
}

/* The outcome of the impact at a change of contact from P (`from`) to Q (`to`) at state y while rolling on
 * one point, nothing booked: the body rolling about P meets the plane at Q; *both: both points hold after
 * (the two-point mode begins), else P lifts; a lift whose fall back would come within def.settle_time is
 * taken as both held (the settle rule). *bounce: 0, or with restitution 1 (Q rebounds, P holds) and 2 (both
 * leave), or 3 (e = 0 where Moreau's law would need a pull: Q's slip stopped leaves Q moving away, and P
 * too: the body hops). Also: the points [m], the centroid's velocity before, the solver's answer (the
 * settle rule applied), P's return time and whether both points hold. */
static int impact_outcome(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *from,
                          const gb_contact_point *to, double points[2][3], double v[3], gb_impact_result *r, double *back,
                          int *both, int *bounce)
{
    const double L = d->def.length;
    for (int k = 0; k < 3; k++) points[0][k] = L * from->rc[k], points[1][k] = L * to->rc[k];
    double e = 0.0;
    *bounce = 0;
    if (d->def.restitution > 0.0) {
        /* Q's approach speed, the body turning about P */
        double zb[3], vg[3], wq[3];
        vertical_of(y, zb);
        gb_vec_cross(y + GB_STATE_OMEGA, (const double[3]){-points[0][0], -points[0][1], -points[0][2]}, vg);
        gb_vec_cross(y + GB_STATE_OMEGA, points[1], wq);
        e = restitution_at(d, t, -(gb_vec_dot(zb, vg) + gb_vec_dot(zb, wq)));
    }
    int status = impact_solve(d, t, y, points[0], (const double (*)[3])points, 2, e, v, r);
    if (status == GB_ENUMERIC && e == 0.0) {
        /* Moreau's law has no answer: holding Q would need the plane to pull. The rough plane's one-point law
         * (gb_impact_rough_point, a landing's) at Q: Q's slip stopped first, then its approach if any is
         * left; it stands when P then moves away from the plane (P lifts with no impulse). If Q leaves too,
         * the body hops. */
        double zb[3], uP[3];
        gb_impact_result q;
        gb_impact_body body = {d->def.mass, {{0}}};
        memcpy(body.inertia, d->inertia, sizeof body.inertia);
        vertical_of(y, zb);
        if (gb_impact_rough_point(&body, zb, 0.0, points[1], v, y + GB_STATE_OMEGA, &q) == GB_OK) {
            gb_vec_cross(q.omega, points[0], uP);
            for (int k = 0; k < 3; k++) uP[k] += q.v[k];
            if (gb_vec_dot(zb, uP) >= -1e-10 * gb_vec_norm(v)) {
                gb_error_clear();
                memset(r, 0, sizeof *r);
                memcpy(r->v, q.v, sizeof r->v);
                memcpy(r->omega, q.omega, sizeof r->omega);
                r->holds[1] = q.holds[0];
                memcpy(r->impulse[1], q.impulse[0], sizeof r->impulse[1]);
                r->normal_impulse[1] = q.normal_impulse[0], r->tangential_impulse[1] = q.tangential_impulse[0];
                r->friction_needed = q.friction_needed;
                r->energy_before = q.energy_before, r->energy_after = q.energy_after;
                r->feasible_sets = 1;
                status = GB_OK;
                if (!q.holds[0]) { /* Q leaves with P: a hop */
                    *bounce = 3, *both = 0, *back = INFINITY;
                    return GB_OK;
                }
            }
        }
    }
    if (status) return status;
    if (e > 0.0) {
        /* Q rebounds at e times its approach speed and leaves the plane; P holds (the body rolls on about P)
         * or separates too (the body hops) */
        *bounce = r->holds[0] ? 1 : 2;
        *both = 0;
        *back = INFINITY;
        return GB_OK;
    }
    if (!r->holds[1] && grazing(d, y, v, r, points[1])) {
        /* Q arrives at rest (a grazing event, or two nodes tied at rest as a grid body may start): no
         * impulse, and the forces decide. On both points, the two-point mode's lift event follows at
         * once where one of its normal forces is below 0. */
        hold_both(d, y, points[0], points[1], v, r);
        *both = 1;
        *back = INFINITY;
        return GB_OK;
    }
    if (!r->holds[1])
        return gb_error_set(GB_ENUMERIC, "unilateral contact at t = %.9g: after the impact the new contact does not hold", t);
    *both = r->holds[0];
    *back = INFINITY;
    if (!*both) {
        double yafter[GB_STATE_SIZE];
        memcpy(yafter, y, sizeof yafter);
        memcpy(yafter + GB_STATE_OMEGA, r->omega, sizeof r->omega);
        *back = return_time(d, t, yafter, to, r->v, points[0]);
        if (*back < d->def.settle_time) {
            /* the settle rule lumps the chatter, unless the lumped impact would need the plane to pull beyond
             * the weight's impulse it stands for (P and Q close together, a couple with a short arm): then
             * Moreau's impact stands, and P's return is an impact of its own */
            gb_impact_result lumped;
            double allowed;
            hold_both(d, y, points[0], points[1], v, &lumped);
            if (pulling_point(d, &lumped, (const double(*)[3])points, 2, 1, 1, v, y + GB_STATE_OMEGA, &allowed) < 0)
                *r = lumped, *both = 1;
        }
    }
    return GB_OK;
}

/* That impact, booked: ω in y takes its value after. */
static int impact(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *from, const gb_contact_point *to,
                  int located, int *both, int *bounce)
{
    double points[2][3], v[3], back;
    gb_impact_result r;
    int status = impact_outcome(d, t, y, from, to, points, v, &r, &back, both, bounce);
    if (!status) status = plane_pushes(d, t, &r, (const double(*)[3])points, 2, 1, *both && isfinite(back), v, y + GB_STATE_OMEGA);
    if (status) return status;
    gb_dynamics_impact e = {.t = t, .located = located, .kind = *both ? GB_IMPACT_TWO_POINT : GB_IMPACT_SWITCH,
                            .contacts_after = 1 + *both, .settled = *both && isfinite(back), .return_time = back};
    if (*bounce == 1 || *bounce == 2) e.kind = GB_IMPACT_BOUNCE, e.contacts_after = *bounce == 1, e.rebound = 1;
    else if (*bounce == 3) e.contacts_after = 0; /* Q's slip stopped and Q leaves with P: the body hops */
    record(&e, y, points[0], points[1], v, &r, 1, 0);
    if (*bounce >= 2) {
        /* both points leave the plane: the body flies, its centroid where it is, at its velocity after */
        double zb[3];
        vertical_of(y, zb);
        start_flight(d, t, y, r.v, -gb_vec_dot(zb, points[0]));
    }
    return book(d, &e);
}

/* A change of contact with no impulse (a lift, a lift-off, the end of a crease), the body turning with the ω
 * of y about the point `about` [m]: the centroid's velocity v = ω × (G − P), and the impact's record of
 * nothing changed. */
static void no_impulse(const gb_dynamics *d, const double y[GB_STATE_SIZE], const double about[3], double v[3],
                       gb_impact_result *r)
{
    memset(r, 0, sizeof *r);
    memcpy(r->omega, y + GB_STATE_OMEGA, sizeof r->omega);
    gb_vec_cross(y + GB_STATE_OMEGA, (const double[3]){-about[0], -about[1], -about[2]}, v);
    memcpy(r->v, v, sizeof r->v);
    gb_impact_body body = {d->def.mass, {{0}}};
    memcpy(body.inertia, d->inertia, sizeof body.inertia);
    r->energy_before = r->energy_after = gb_impact_energy(&body, v, r->omega);
}

/* At a lift-off from one point the normal force is 0 but the rolling contact's tangential force F_t
 * generally is not (the friction it needs, |F_t|/N, grows without bound as N reaches 0). Without F_t the
 * point's normal acceleration changes by −n·W F_t (W the point's Delassus operator, as in gb_impact): if
 * that drives the point into the plane, neither rolling (N < 0 after) nor flight (the point would
 * penetrate) continues the motion: on a plane of finite friction the body slides before it lifts, which
 * this model (rough, no slip) does not follow. GB_ENUMERIC then, saying so. */
static int lift_off_consistent(gb_dynamics *d, double t, const double y[GB_STATE_SIZE])
{
    const double m = d->def.mass, *omega = y + GB_STATE_OMEGA;
    double zb[3], geff, geff_rate, w_dot[3], acc[3], F[3], rxF[3], I[3][3], dw[3], dv[3];
    contact_eval c;
    if (d->two_point) return GB_OK; /* left by its lift event first: a lift-off is from one point */
    vertical_of(y, zb);
    gb_forcing_geff_with_rate(&d->def.forcing, t, &geff, &geff_rate);
    int status = contact_at(d, t, zb, omega, &c);
    if (!status) status = angular_acceleration(d, geff, zb, omega, &c, w_dot);
    if (status) return status;
    normal_force_of(d, geff, zb, omega, w_dot, &c, acc);
    for (int k = 0; k < 3; k++) F[k] = m * (acc[k] + geff * zb[k]); /* the contact force rolling needs */
    /* W F = F/m + (I⁻¹ (r × F)) × r: the contact point's acceleration that F makes */
    memcpy(I, d->inertia, sizeof I);
    gb_vec_cross(c.rc, F, rxF);
    status = solve3(I, rxF, dw);
    if (status) return status;
    gb_vec_cross(dw, c.rc, dv);
    const double drop = gb_vec_dot(zb, F) / m + gb_vec_dot(zb, dv); /* n·W F */
    if (!(drop > 0.0)) return GB_OK;
    /* The gap then opens as −a t²/2 + b t³/6 (a = drop, b = −Ṅ/m, N falling through 0), whose deepest dip is
     * (2/3) a³/b² at t = 2a/b: within the landing tolerance (FLIGHT_GAP_TOL) the lift-off stands. Ṅ by a
     * forward difference along the rolling flow over 1e-6 of the step. */
    double f[GB_STATE_SIZE], y2[GB_STATE_SIZE], n2;
    const double delta = 1e-6 * (d->def.settle_time > 0.0 ? d->def.settle_time : gb_forcing_period(&d->def.forcing) / 160.0);
    status = gb_dynamics_rhs(d, t, y, f);
    for (int k = 0; k < GB_STATE_SIZE; k++) y2[k] = y[k] + delta * f[k];
    if (!status) status = one_point_normal(d, t + delta, y2, &n2);
    if (status) return status;
    const double b = -n2 / (delta * m), dip = b > 0.0 ? 2.0 / 3.0 * drop * drop * drop / (b * b) : INFINITY;
    if (dip > LIFT_OFF_DIP_MAX * d->def.length) {
        const double fn = gb_vec_dot(zb, F), ft[3] = {F[0] - fn * zb[0], F[1] - fn * zb[1], F[2] - fn * zb[2]};
        char depth[96] = "into the plane and kept below it (the normal force reaches 0 without falling through)";
        if (isfinite(dip)) snprintf(depth, sizeof depth, "%.3g m into the plane", dip);
        return gb_error_set(GB_ENUMERIC, "lift-off at t = %.9g: the normal force reaches 0 while rolling still needs a "
                            "friction force of %.3g N, without which the contact point is driven %s: on a plane of finite "
                            "friction the body slides before it lifts, which this rough-plane model does not follow "
                            "(sliding is not built)", t, gb_vec_norm(ft), depth);
    }
    /* the flight's landing waits below the dip (twice the estimate) until the gap has opened */
    d->gap_allow = fmax(d->gap_allow, FLIGHT_GAP_TOL + 2.0 * dip / d->def.length);
    return GB_OK;
}

/* The last contact's normal force (or g_eff on three points at rest) has reached 0 at state y: the body
 * leaves the plane with the velocity it has, no impulse. Ends the two-point mode or the rest. */
static int lift_off(gb_dynamics *d, double t, double y[GB_STATE_SIZE])
{
    const double L = d->def.length;
    double zb[3], rp[3], v[3];
    vertical_of(y, zb);
    gb_contact_point p;
    int status = point_at(d, zb, &d->contact, &p);
    double allow = FLIGHT_GAP_TOL;
    if (!status && !d->resting) {
        d->gap_allow = FLIGHT_GAP_TOL;
        status = lift_off_consistent(d, t, y);
        allow = d->gap_allow;
    }
    if (status) return status;
    if (d->resting) memset(y + GB_STATE_OMEGA, 0, 3 * sizeof *y); /* at rest nothing turns (gb_dynamics_rhs) */
    for (int k = 0; k < 3; k++) rp[k] = L * p.rc[k];
    gb_impact_result r;
    no_impulse(d, y, rp, v, &r);
    gb_dynamics_impact e = {.t = t, .located = 1, .kind = GB_IMPACT_LIFT_OFF, .contacts_after = 0, .return_time = INFINITY};
    record(&e, y, rp, rp, v, &r, 0, -1);
    if (d->two_point) d->two_point = 0, d->two_point_time += t - d->two_point_since;
    d->resting = 0;
    set_contact(d, &p);
    start_flight(d, t, y, v, -gb_vec_dot(zb, rp));
    d->gap_allow = allow;
    return book(d, &e);
}

/* In flight, the lowest point q (continued to state y) reaches the plane: Moreau's impact at q with
 * Newton's restitution (restitution_at). A plastic landing leaves the body rolling on q, unless its normal
 * force is below 0 there (g_eff pulls the plane away faster): then it flies on from q at rest. */
static int landing(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *q)
{
    const double L = d->def.length;
    double zb[3], R[9], zeta, v_in[3], v[3], rq[3], wq[3];
    gb_dynamics_rotation(y + GB_STATE_Q, R);
    zb_of(R, zb);
    flight_state(d, t, &zeta, v_in);
    for (int i = 0; i < 3; i++) v[i] = R[i] * v_in[0] + R[3 + i] * v_in[1] + R[6 + i] * v_in[2]; /* Rᵀ v */
    for (int k = 0; k < 3; k++) rq[k] = L * q->rc[k];
    gb_vec_cross(y + GB_STATE_OMEGA, rq, wq);
    const double e = restitution_at(d, t, -(gb_vec_dot(zb, v) + gb_vec_dot(zb, wq)));
    gb_impact_body body = {d->def.mass, {{0}}};
    memcpy(body.inertia, d->inertia, sizeof body.inertia);
    gb_impact_result r;
    if (gb_impact_rough_point(&body, zb, e, rq, v, y + GB_STATE_OMEGA, &r))
        return gb_error_set(GB_ENUMERIC, "landing at t = %.9g: %s", t, gb_error_message());
    const int pushes = plane_pushes(d, t, &r, (const double(*)[3])&rq, 1, 0, 0, v, y + GB_STATE_OMEGA);
    if (pushes) return pushes;
    gb_dynamics_impact rec = {.t = t, .located = 1, .kind = GB_IMPACT_LANDING, .rebound = e > 0.0 && r.holds[0],
                              .return_time = INFINITY};
    record(&rec, y, rq, rq, v, &r, 0, -1);
    set_contact(d, q);
    int flies = e > 0.0 || !r.holds[0]; /* a rebound, or the slip stopped and the point leaves */
    double allow = FLIGHT_GAP_TOL;
    if (!flies) {
        double n;
        int status = one_point_normal(d, t, y, &n);
        flies = !status && n < 0.0;
        if (flies) {
            /* the plane still falls away faster than gravity: the body leaves the point at rest, as at a
             * lift-off, and its dip is bounded the same way */
            d->gap_allow = FLIGHT_GAP_TOL;
            status = lift_off_consistent(d, t, y);
            allow = d->gap_allow;
        }
        if (status) return status;
    }
    if (flies) {
        /* the flight goes on from where the point is, up to the landing tolerance below the plane: the next
         * landing is a return below that */
        const double depth = -(zeta + L * gb_vec_dot(zb, q->rc)) / L;
        start_flight(d, t, y, r.v, zeta);
        d->gap_allow = fmax(allow, fmax(depth, 0.0) + FLIGHT_GAP_TOL);
    } else {
        d->flying = 0;
        d->flight_time += t - d->flight_since;
        rec.contacts_after = 1;
        rec.potential_jump = -d->def.mass * gb_forcing_geff(&d->def.forcing, t) * (zeta + L * gb_vec_dot(zb, q->rc));
    }
    return book(d, &rec);
}

/* Flight at state y: does the lowest point (continued, or a lower minimum the certificate finds) lie
 * below the plane? Then *other is it and the event is a landing. */
static int flight_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found)
{
    gb_contact_point continued, lower;
    int lower_found;
    const int status = competitor(d, t, y, &continued, &lower, &lower_found);
    if (status) return status;
    const gb_contact_point *lowest = lower_found ? &lower : &continued;
    double zeta, v[3];
    flight_state(d, t, &zeta, v);
    *found = zeta + d->def.length * (lowest->height + d->gap_allow) < 0.0;
    if (*found) *other = *lowest, d->flight_event = FLIGHT_LANDING;
    return GB_OK;
}

static int check_global(gb_dynamics *d, const double zb[3], const gb_contact_point *candidate, gb_certify_result *r);
static int canonical_minimum(gb_dynamics *d, const double zb[3], gb_contact_point *p);

enum { PENDING_THIRD = 0, PENDING_LIFT = 1 };



static int two_point_search(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found);

/* Two-point mode at state y: is an event due? A normal force below 0 (PENDING_LIFT), or a third minimum
 * lower than both points, proved by the certificate (PENDING_THIRD, *other). */
static int two_point_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found)
{
    /* The step's end is checked by gb_dynamics_switch_pending and again by gb_dynamics_accept at the same
     * state: the memo (as competitor()'s, its last key 1 for this mode) answers the second. */
    double zkey[3];
    vertical_of(y, zkey);
    const double key[8] = {zkey[0], zkey[1], zkey[2], t, y[GB_STATE_OMEGA], y[GB_STATE_OMEGA + 1], y[GB_STATE_OMEGA + 2], 1.0};
    if (d->memo_valid && memcmp(key, d->memo_key, sizeof key) == 0) {
        *found = d->memo_found;
        if (*found) *other = d->memo_other, d->pending = d->memo_pending;
        return GB_OK;
    }
    int status = two_point_search(d, t, y, other, found);
    if (status) return status;
    memcpy(d->memo_key, key, sizeof key);
    d->memo_found = *found;
    if (*found) d->memo_other = *other, d->memo_pending = d->pending;
    d->memo_valid = 1;
    return GB_OK;
}

static int two_point_search(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found)
{
    two_point_eval tp;
    *found = 0;
    int status = two_point_at(d, t, y, &tp);
    if (status || tp.merged) return status; /* the end of a crease: gb_dynamics_accept leaves the mode */
    if (fmin(tp.normal[0], tp.normal[1]) < 0.0) {
        d->pending = PENDING_LIFT;
        *other = tp.q;
        *found = 1;
        return GB_OK;
    }
    double zb[3];
    vertical_of(y, zb);
    d->pending = PENDING_THIRD;
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) {
        /* a grid body on an edge: a third node strictly lower than both */
        status = next_node(d, zb, other);
        *found = !status && other->height < fmin(tp.p.point.height, tp.q.height) - GRID_TIE;
        return status;
    }
    gb_contact_point candidate = tp.p.point.height <= tp.q.height ? tp.p.point : tp.q;
    for (int round = 0; round < 16; round++) {
        gb_certify_result r;
        status = check_global(d, zb, &candidate, &r);
        if (status) return status;
        if (r.verdict != GB_CERTIFY_LOWER_FOUND) break;
        candidate = *other = r.lower;
        *found = 1;
    }
    if (*found) status = canonical_minimum(d, zb, other);
    if (!status && *found && (same_point(other, &tp.p.point) || same_point(other, &tp.q))) *found = 0; /* P and Q tie */
    d->pending = PENDING_THIRD;
    return status;
}

/* The outcome of a third point `third` [m] landing while the body rolls on P and Q (points[0], points[1] [m];
 * points[2] is `third`), nothing booked: Moreau's impact over the three, then the settle rule (a point of the
 * old pair that would fall back within the settle time is held with the third; both: the body stops on all
 * three). *held: the points held after (2 or 3, or 1: the third alone), *back: the first return time, *settled:
 * the settle rule decided. */
static int third_point_outcome(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *third,
                               const double points[3][3], double v[3], gb_impact_result *r, int *held, double *back,
                               int *settled)
{
    int status = impact_solve(d, t, y, points[0], points, 3, 0.0, v, r);
    if (status) return status;
    *held = r->holds[0] + r->holds[1] + r->holds[2];
    *back = INFINITY;
    *settled = 0;
    if (!r->holds[2])
        return gb_error_set(GB_ENUMERIC, "unilateral contact at t = %.9g: a third point reaches the plane and does not "
                            "hold after the impact", t);
    if (*held == 1) {
        /* The settle rule, as at a switch: P or Q lifts and would fall back within the settle time, so the
         * body is held on the third point and that one (the lumped chatter, hold_both). */
        double yafter[GB_STATE_SIZE];
        memcpy(yafter, y, sizeof yafter);
        memcpy(yafter + GB_STATE_OMEGA, r->omega, sizeof r->omega);
        const double back_p = return_time(d, t, yafter, third, r->v, points[0]);
        const double back_q = return_time(d, t, yafter, third, r->v, points[1]);
        const int k = back_q < back_p;
        *back = fmin(back_p, back_q);
        /* A lumped impact is taken only where it pushes within the weight's impulse it stands for
         * (pulling_point): a thin triangle or a short edge would need a couple the plane cannot give, and
         * then the next lumping is tried, and last Moreau's impact stands. */
        double allowed;
        if (fmax(back_p, back_q) < d->def.settle_time) {
            /* both would fall back within it: the body stops on the three points (the chatter's limit) */
            double zb[3];
            vertical_of(y, zb);
            gb_impact_body body = {d->def.mass, {{0}}};
            memcpy(body.inertia, d->inertia, sizeof body.inertia);
            gb_impact_result all;
            status = gb_impact_hold_all(&body, zb, points, 3, v, y + GB_STATE_OMEGA, &all);
            if (status) return status;
            if (pulling_point(d, &all, points, 3, 2, 1, v, y + GB_STATE_OMEGA, &allowed) < 0) {
                *r = all, *held = 3, *settled = 1;
                return GB_OK;
            }
        }
        if (*back < d->def.settle_time) {
            gb_impact_result h; /* its slots: 0 the third point, 1 the one held with it */
            hold_both(d, y, points[2], points[k], v, &h);
            gb_impact_result two = h;
            for (int j = 0; j < 3; j++) {
                const int from = j == 2 ? 0 : j == k ? 1 : -1;
                two.holds[j] = from >= 0;
                two.normal_impulse[j] = from >= 0 ? h.normal_impulse[from] : 0.0;
                two.tangential_impulse[j] = from >= 0 ? h.tangential_impulse[from] : 0.0;
            }
            /* at the third point, which lands (the one held with it may pull, as P in the settle rule) */
            two.friction_needed = two.normal_impulse[2] > 0.0 ? two.tangential_impulse[2] / two.normal_impulse[2] : INFINITY;
            if (pulling_point(d, &two, points, 3, 2, 1, v, y + GB_STATE_OMEGA, &allowed) < 0) *r = two, *held = 2, *settled = 1;
        }
    }
    return GB_OK;
}

/* Two-point mode: the located event at state y (its `other` from two_point_pending, continued). */
static int two_point_event(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *third)
{
    two_point_eval tp;
    int status = two_point_at(d, t, y, &tp);
    if (!status && tp.merged)
        status = gb_error_set(GB_ENUMERIC, "two-point contact at t = %.9g: the crease ends at a located event", t);
    if (status) return status;
    if (d->pending == PENDING_LIFT) {
        const int lifts = tp.normal[0] < tp.normal[1] ? 0 : 1; /* the point whose force reached 0 */
        const double *up = lifts ? tp.rq : tp.rp, *stays = lifts ? tp.rp : tp.rq;
        gb_dynamics_impact e = {.t = t, .located = 1, .kind = GB_IMPACT_LIFT, .contacts_after = 1};
        gb_impact_result r;
        double v[3];
        no_impulse(d, y, stays, v, &r);
        record(&e, y, up, stays, v, &r, 0, -1);
        d->two_point = 0;
        d->two_point_time += t - d->two_point_since;
        set_contact(d, lifts ? &tp.p.point : &tp.q);
        if (d->def.contact == GB_CONTACT_MODEL_CONTINUOUS) {
            /* As at a lift-off, the lifted point's gap opens only at third order while the rough contact it
             * leaves still needed a friction force: it may dip below the plane by a micrometre a metre of body
             * (LIFT_OFF_DIP_MAX) before its return is a change of contact, until its gap has opened. */
            d->lifted = lifts ? tp.q : tp.p.point;
            d->lift_allow = LIFT_OFF_DIP_MAX;
        }
        return book(d, &e);
    }
    const double L = d->def.length;
    const double points[3][3] = {{tp.rp[0], tp.rp[1], tp.rp[2]}, {tp.rq[0], tp.rq[1], tp.rq[2]},
                                 {L * third->rc[0], L * third->rc[1], L * third->rc[2]}};
    double v[3], back;
    gb_impact_result r;
    int held, settled;
    status = third_point_outcome(d, t, y, third, points, v, &r, &held, &back, &settled);
    if (!status) status = plane_pushes(d, t, &r, points, 3, 2, settled, v, y + GB_STATE_OMEGA);
    if (status) return status;
    gb_dynamics_impact e = {.t = t, .located = 1, .kind = GB_IMPACT_THIRD, .contacts_after = held,
                            .settled = settled, .return_time = back};
    const int old = held == 2 && r.holds[1]; /* the one that stays (P when none does) */
    record(&e, y, points[old], points[2], v, &r, 2, old);
    if (held == 3) {
        /* Three points stop the body (ω = 0). With the vertical forcing alone (g_eff > 0) it stays at rest
         * if its weight falls inside the triangle: the static normal forces are m g_eff times the
         * barycentric weights of G's foot, w_k = z_b·(p_i × p_j) / z_b·((p_j − p_i) × (p_k − p_i)) for
         * the cyclic (i, j, k). One weight below 0: it tips about the other two points, from rest (the
         * impact's record says three held: the tip begins after it). */
        double zb[3], w[3], a[3], b[3], n[3];
        vertical_of(y, zb);
        for (int k = 0; k < 3; k++) a[k] = points[1][k] - points[0][k], b[k] = points[2][k] - points[0][k];
        gb_vec_cross(a, b, n);
        const double area = gb_vec_dot(zb, n);
        int negative = 0, tip = -1;
        for (int i = 0; i < 3; i++) {
            gb_vec_cross(points[(i + 1) % 3], points[(i + 2) % 3], n);
            w[i] = gb_vec_dot(zb, n) / area;
            if (w[i] < 0.0) negative++, tip = i;
        }
        if (negative > 1 || !isfinite(w[0] + w[1] + w[2]))
            return gb_error_set(GB_ENUMERIC, "unilateral contact at t = %.9g: the body stops on three points whose "
                                "triangle holds neither its weight nor an edge to tip about (weights %.3g, %.3g, %.3g)",
                                t, w[0], w[1], w[2]);
        if (!negative) {
            d->two_point = 0;
            d->two_point_time += t - d->two_point_since;
            d->resting = 1;
            d->rest_since = t;
            set_contact(d, third);
            return book(d, &e);
        }
        /* tips about the edge opposite the negative weight: that edge's points, P first */
        const gb_contact_point *const pts[3] = {&tp.p.point, &tp.q, third};
        set_contact(d, pts[(tip + 1) % 3]);
        d->contact2 = *pts[(tip + 2) % 3];
        d->q_valid = 0;
        return book(d, &e);
    }
    if (held == 2) {
        d->contact2 = r.holds[0] ? tp.p.point : tp.q;
        d->q_valid = 0;
    } else {
        d->two_point = 0;
        d->two_point_time += t - d->two_point_since;
    }
    set_contact(d, third);
    return book(d, &e);
}

int gb_dynamics_accept(gb_dynamics *d, double t, double y[GB_STATE_SIZE], double *norm_drift)
{
    double *q = y + GB_STATE_Q;
    const double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(isfinite(n) && n > 0.0) || gb_dynamics_state_finite(t, y)) return diverged(t);
    if (norm_drift) *norm_drift = n - 1.0;
    for (int k = 0; k < 4; k++) q[k] /= n;
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS && !grid_unilateral(d)) {
        double zb[3];
        vertical_of(y, zb);
        contact_eval c;
        const int status = contact_at(d, t, zb, y + GB_STATE_OMEGA, &c);
        if (status) return status;
        if (c.index != d->index) d->grid_switches++, d->last_switch_time = t;
        d->index = c.index;
        return GB_OK;
    }
    gb_contact_point continued, other;
    int found;
    if (d->flying) {
        /* the lowest point: continued, certified, and relabelled when a lower minimum takes over (no impact) */
        int status = competitor(d, t, y, &continued, &other, &found);
        if (status) return status;
        set_contact(d, found ? &other : &continued);
        d->memo_valid = 0;
        if (found) d->last_valid = 0;
        double zeta, v[3];
        flight_state(d, t, &zeta, v);
        const double clearance = zeta + d->def.length * d->contact.height;
        if (clearance > 0.0) d->gap_allow = FLIGHT_GAP_TOL; /* the gap has opened */
        if (clearance < -d->def.length * d->gap_allow)
            return gb_error_set(GB_ENUMERIC, "flight at t = %.9g: the lowest point is %.3g m below the plane, a landing "
                                "that the step's event location did not find", t, -clearance);
        d->hop_max = fmax(d->hop_max, clearance);
        return remember_rate(d, t, y);
    }
    if (d->resting) {
        if (gb_forcing_geff(&d->def.forcing, t) < 0.0)
            return gb_error_set(GB_ENUMERIC, "unilateral contact at t = %.9g: g_eff < 0 on three points, a lift-off that "
                                "the step's event location did not find", t);
        return GB_OK;
    }
    if (d->two_point) {
        /* Every event of the mode is located inside its step; one found here is a second inside one step. */
        int status = two_point_pending(d, t, y, &other, &found);
        if (!status && found)
            status = gb_error_set(GB_ENUMERIC, "unilateral contact at t = %.9g: a second change of contact inside one "
                                  "step of the two-point mode (%s)", t, d->pending == PENDING_LIFT ? "a normal force below 0"
                                  : "a third point lower than both");
        two_point_eval tp;
        if (!status) status = two_point_eval_at(d, t, y, &tp, 0);
        if (status) return status;
        set_contact(d, &tp.p.point);
        d->memo_valid = 0;
        if (tp.merged) {
            /* the end of a crease inside the step (not located: the state is continuous there, and the mode
             * whose constraint ends has nothing to jump): the body rolls on P alone from here */
            const double L = d->def.length;
            double rp[3], v[3];
            for (int k = 0; k < 3; k++) rp[k] = L * tp.p.point.rc[k];
            gb_impact_result r;
            no_impulse(d, y, rp, v, &r);
            gb_dynamics_impact e = {.t = t, .located = 0, .kind = GB_IMPACT_CREASE_END, .contacts_after = 1,
                                    .return_time = INFINITY};
            double qr[3];
            for (int k = 0; k < 3; k++) qr[k] = L * d->contact2.rc[k];
            record(&e, y, qr, rp, v, &r, 0, -1);
            d->two_point = 0;
            d->two_point_time += t - d->two_point_since;
            d->last_valid = 0;
            status = book(d, &e);
            if (status) return status;
            return remember_rate(d, t, y);
        }
        d->contact2 = tp.q;
        return remember_rate(d, t, y);
    }
    int status = competitor(d, t, y, &continued, &other, &found);
    /* Under the unilateral law every contact change is located inside its step; one found here is a second
     * change inside one step: the body chatters between two points, coming to rest on both. */
    if (!status && found && d->def.contact_law == GB_CONTACT_LAW_UNILATERAL)
        status = gb_error_set(GB_ENUMERIC, "unilateral contact at t = %.9g: a change of contact at the step's end that the "
                              "step's event location did not find (%zu impacts so far)", t, d->impacts);
    /* (N < 0 at the step's end was a lift-off event, located by gb_dynamics_switch_pending) */
    if (status) return status;
    if (d->lift_allow > 0.0) {
        /* has the lifted point's gap opened (or its minimum gone)? */
        double zb[3];
        gb_contact_point q;
        vertical_of(y, zb);
        if (point_at(d, zb, &d->lifted, &q) || !q.is_minimum || q.height > continued.height) d->lift_allow = 0.0;
        else d->lifted = q;
        gb_error_clear();
    }
    set_contact(d, found ? &other : &continued);
    d->memo_valid = 0; /* the accepted contact changed */
    if (found) d->last_valid = 0; /* the last contact found is on the branch left */
    d->branch_switches += found;
    if (found) d->last_switch_time = t;
    return remember_rate(d, t, y);
}

int gb_dynamics_switch_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other,
                               int *found)
{
    *found = 0;
    d->flight_event = FLIGHT_NONE;
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS && !grid_unilateral(d)) return GB_OK; /* held grid: the paper's rule */
    if (d->flying) return flight_pending(d, t, y, other, found);
    if (d->resting) {
        /* on three points the weight m g_eff holds the body; it lifts off them all where g_eff reaches 0 */
        if (gb_forcing_geff(&d->def.forcing, t) < 0.0) *other = d->contact, *found = 1, d->flight_event = FLIGHT_LIFT_OFF;
        return GB_OK;
    }
    if (d->two_point) return two_point_pending(d, t, y, other, found);
    gb_contact_point continued;
    int status = competitor(d, t, y, &continued, other, found);
    if (!status && !*found && d->def.contact_law == GB_CONTACT_LAW_UNILATERAL) {
        /* a plane that can only push cannot hold the body down: where N reaches 0 it leaves the plane */
        double n;
        status = one_point_normal(d, t, y, &n);
        if (!status && n < 0.0) *other = continued, *found = 1, d->flight_event = FLIGHT_LIFT_OFF;
    }
    return status;
}

int gb_dynamics_branch_gap(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other,
                           double *gap, gb_contact_point *other_here)
{
    double zb[3];
    vertical_of(y, zb);
    gb_contact_point here;
    if (d->flight_event == FLIGHT_LIFT_OFF) {
        /* −N of the last contact (at rest on three points: −g_eff, to which all three forces are proportional) */
        double n;
        const int status = d->resting ? (n = gb_forcing_geff(&d->def.forcing, t), GB_OK) : one_point_normal(d, t, y, &n);
        *gap = -n;
        *other_here = *other;
        return status;
    }
    if (d->flying) {
        /* −(the lowest point's height above the plane): the lower of the lowest point at the step's start and
         * the one at its end (`other`), both continued, since the lowest point may change branch inside the step */
        double zeta, v[3];
        int status = point_at(d, zb, other, other_here);
        if (!status && !same_point(other, &d->contact)) {
            status = point_at(d, zb, &d->contact, &here);
            if (!status && here.height < other_here->height) *other_here = here;
        }
        flight_state(d, t, &zeta, v);
        *gap = -(zeta + d->def.length * (other_here->height + d->gap_allow));
        return status;
    }
    if (d->two_point && d->pending == PENDING_LIFT) {
        two_point_eval tp;
        int status = two_point_at(d, t, y, &tp);
        if (!status && tp.merged)
            status = gb_error_set(GB_ENUMERIC, "two-point contact at t = %.9g: the crease ends while a lift is located", t);
        if (status) return status;
        *gap = -fmin(tp.normal[0], tp.normal[1]);
        *other_here = *other;
        return GB_OK;
    }
    int status = point_at(d, zb, &d->contact, &here);
    if (!status && d->two_point) {
        /* a third point against the lower of P and Q */
        gb_contact_point q;
        status = point_at(d, zb, &d->contact2, &q);
        if (!status && q.height < here.height) here = q;
    }
    /* a grid body: the next node at this state, whichever it is (continuous: `other`, continued) */
    if (!status) status = d->def.contact == GB_CONTACT_MODEL_CONTINUOUS ? point_at(d, zb, other, other_here)
                                                                        : next_node(d, zb, other_here);
    if (status) return status;
    *gap = here.height - other_here->height; /* > 0: the other branch is lower (eq 39) */
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) *gap -= GRID_TIE;
    /* Under the unilateral law: where Newton from the other branch ends on the contact itself, that branch is
     * not born yet (it appears in a fold inside the step, above the contact, since the lowest height is
     * continuous), so it is not lower: the crossing is located where it has been born and passes below. */
    else if (d->def.contact_law == GB_CONTACT_LAW_UNILATERAL && !d->two_point && same_point(other_here, &here))
        *gap = -1e-15;
    else if (!d->two_point)
        *gap -= d->lift_allow;
    return GB_OK;
}

int gb_dynamics_switch_to(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    d->lift_allow = 0.0; /* any change of contact ends a lifted point's allowance (a lift sets a new one) */
    if (d->flight_event != FLIGHT_NONE) {
        /* a lift-off or a landing: neither is a switch of contact branch */
        const int status = d->flight_event == FLIGHT_LIFT_OFF ? lift_off(d, t, y) : landing(d, t, y, branch);
        d->flight_event = FLIGHT_NONE;
        d->memo_valid = 0;
        d->contact_rate[0] = d->contact_rate[1] = 0.0;
        d->last_valid = 0;
        return status;
    }
    if (d->two_point) {
        const int status = two_point_event(d, t, y, branch);
        if (status) return status;
    } else if (d->def.contact_law == GB_CONTACT_LAW_UNILATERAL) {
        /* the old contact continued to this state: the point P that the body rolls about */
        double zb[3];
        vertical_of(y, zb);
        gb_contact_point here;
        int both = 0, bounce = 0;
        int status = point_at(d, zb, &d->contact, &here);
        if (!status) status = impact(d, t, y, &here, branch, 1, &both, &bounce);
        if (status) return status;
        if (bounce != 1) set_contact(d, branch); /* a rebound of Q off P that holds: the body rolls on about P */
        if (both) {
            d->two_point = 1;
            d->contact2 = here;
            d->q_valid = 0;
            d->two_point_since = t;
            d->two_point_entries++;
        }
    } else {
        d->contact = *branch;
    }
    d->last_switch_time = t;
    d->memo_valid = 0;
    d->contact_rate[0] = d->contact_rate[1] = 0.0; /* no predictor until the next accepted step */
    d->last_valid = 0;
    if (d->def.contact == GB_CONTACT_MODEL_CONTINUOUS) d->branch_switches++;
    else d->grid_switches++;
    return GB_OK;
}

int gb_dynamics_jump(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                     double out[GB_STATE_SIZE])
{
    memcpy(out, y, GB_STATE_SIZE * sizeof *out);
    if (d->flying || d->flight_event != FLIGHT_NONE)
        return gb_error_set(GB_EINVAL, "t = %.9g: the variational estimator does not follow lift-off and flight (the "
                            "centroid's height and velocity are not in its tangent space); use [lyapunov] estimator = "
                            "pair", t);
    if (d->def.contact_law != GB_CONTACT_LAW_UNILATERAL || (d->two_point && d->pending == PENDING_LIFT)) return GB_OK;
    const double L = d->def.length;
    double zb[3], v[3];
    vertical_of(y, zb);
    gb_contact_point p, q, r;
    gb_impact_result res;
    int status = point_at(d, zb, &d->contact, &p);
    if (!status && d->two_point) {
        status = point_at(d, zb, &d->contact2, &q);
        if (!status) status = point_at(d, zb, branch, &r);
        const double points[3][3] = {{L * p.rc[0], L * p.rc[1], L * p.rc[2]}, {L * q.rc[0], L * q.rc[1], L * q.rc[2]},
                                     {L * r.rc[0], L * r.rc[1], L * r.rc[2]}};
        double back;
        int held, settled;
        if (!status) status = third_point_outcome(d, t, y, &r, points, v, &res, &held, &back, &settled);
    } else if (!status) {
        double points[2][3], back;
        int both, bounce;
        status = point_at(d, zb, branch, &q);
        if (!status) status = impact_outcome(d, t, y, &p, &q, points, v, &res, &back, &both, &bounce);
        if (!status && bounce >= 2)
            status = gb_error_set(GB_EINVAL, "t = %.9g: the variational estimator does not follow a hop (restitution "
                                  "lifts both points); use [lyapunov] estimator = pair", t);
    }
    if (!status) memcpy(out + GB_STATE_OMEGA, res.omega, sizeof res.omega);
    return status;
}

void gb_dynamics_set_impact_sink(gb_dynamics *d, gb_dynamics_impact_sink sink, void *context)
{
    d->impact_sink = sink, d->impact_context = context;
}

void gb_dynamics_impact_stats(const gb_dynamics *d, size_t *impacts, double *energy_lost, double *friction_max)
{
    if (impacts) *impacts = d->impacts;
    if (energy_lost) *energy_lost = d->impact_loss;
    if (friction_max) *friction_max = d->impact_friction_max;
}

size_t gb_dynamics_impacts_over_friction(const gb_dynamics *d) { return d->impacts_over_friction; }

void gb_dynamics_two_point_stats(const gb_dynamics *d, double t, gb_dynamics_two_point_summary *out)
{
    out->time = d->two_point_time + (d->two_point ? t - d->two_point_since : 0.0);
    out->entries = d->two_point_entries;
    out->settled = d->settled;
    out->lifts = d->lifts;
    out->third_points = d->third_points;
    out->rest_since = d->rest_since;
}

void gb_dynamics_flight_stats(const gb_dynamics *d, double t, gb_dynamics_flight_summary *out)
{
    out->time = d->flight_time + (d->flying ? t - d->flight_since : 0.0);
    out->lift_offs = d->lift_offs;
    out->landings = d->landings;
    out->bounces = d->bounces;
    out->hop_max = d->hop_max;
    out->flying = d->flying;
}

int gb_dynamics_flight_displace(gb_dynamics *d, double t, double dzeta, const double dv[3])
{
    if (!d->flying) return gb_error_set(GB_EINVAL, "the body is not in flight at t = %.9g", t);
    double zeta, v[3];
    flight_state(d, t, &zeta, v);
    d->fly_t0 = t;
    d->fly_zeta0 = zeta + dzeta;
    for (int k = 0; k < 3; k++) d->fly_v0[k] = v[k] + dv[k];
    d->memo_valid = 0;
    return GB_OK;
}

size_t gb_dynamics_switch_count(const gb_dynamics *d) { return d->grid_switches + d->branch_switches; }

double gb_dynamics_last_switch_time(const gb_dynamics *d) { return d->last_switch_time; }

void gb_dynamics_adopt_contact(gb_dynamics *to, const gb_dynamics *from)
{
    to->memo_valid = 0;
    to->last_valid = 0;
    to->index = from->index;
    to->contact = from->contact;
    to->two_point = from->two_point;
    to->resting = from->resting, to->rest_since = from->rest_since;
    to->contact2 = from->contact2;
    to->q_valid = 0;
    to->two_point_since = from->two_point_since;
    to->flying = from->flying, to->flight_event = FLIGHT_NONE, to->gap_allow = from->gap_allow;
    to->lifted = from->lifted, to->lift_allow = from->lift_allow;
    to->fly_t0 = from->fly_t0, to->fly_zeta0 = from->fly_zeta0, to->flight_since = from->flight_since;
    memcpy(to->fly_v0, from->fly_v0, sizeof to->fly_v0);
    to->contact_time = from->contact_time;
    memcpy(to->contact_rate, from->contact_rate, sizeof to->contact_rate);
}

int gb_dynamics_init_state(gb_dynamics *d, double t0, const double R0[9], const double omega0[3],
                           double y[GB_STATE_SIZE])
{
    double worst = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            const double dot = R0[3 * 0 + i] * R0[3 * 0 + j] + R0[3 * 1 + i] * R0[3 * 1 + j] + R0[3 * 2 + i] * R0[3 * 2 + j];
            worst = fmax(worst, fabs(dot - (i == j)));
        }
    if (!(worst < 1e-12))
        return gb_error_set(GB_EDOM, "initial attitude is not a rotation: max |R^T R - I| = %.3g (allowed: < 1e-12)", worst);
    if (!(isfinite(omega0[0]) && isfinite(omega0[1]) && isfinite(omega0[2])))
        return gb_error_set(GB_EDOM, "initial angular velocity must be finite");
    gb_dynamics_quaternion(R0, y + GB_STATE_Q);
    memcpy(y + GB_STATE_OMEGA, omega0, 3 * sizeof *omega0);
    y[GB_STATE_WORK] = 0.0;
    double R[9], zb[3];
    gb_dynamics_rotation(y + GB_STATE_Q, R);
    zb_of(R, zb);
    int status = contact_global(d, zb);
    if (status) return status;
    if (d->def.contact == GB_CONTACT_MODEL_CONTINUOUS) remember_rate(d, t0, y);
    d->last_valid = 0;
    d->grid_switches = d->branch_switches = d->branches_lost = 0;
    d->impacts = 0, d->impact_loss = d->impact_friction_max = 0.0;
    d->impacts_over_friction = 0;
    d->two_point = d->pending = 0, d->two_point_time = 0.0;
    d->next_hint = SIZE_MAX;
    d->resting = 0, d->rest_since = NAN;
    d->q_valid = 0;
    d->two_point_entries = d->settled = d->lifts = d->third_points = 0;
    d->flying = 0, d->flight_event = FLIGHT_NONE;
    d->gap_allow = FLIGHT_GAP_TOL;
    d->lift_allow = 0.0;
    d->flight_time = d->hop_max = 0.0;
    d->lift_offs = d->landings = d->bounces = 0;
    const double *v0 = d->def.velocity0;
    if (d->def.height0 > 0.0 || v0[0] != 0.0 || v0[1] != 0.0 || v0[2] != 0.0) {
        /* in flight: the lowest point (the contact found) at height0 above the plane, the centroid at v0 */
        double vb[3];
        for (int i = 0; i < 3; i++) vb[i] = R[i] * v0[0] + R[3 + i] * v0[1] + R[6 + i] * v0[2]; /* Rᵀ v0 */
        start_flight(d, t0, y, vb, d->def.height0 - d->def.length * gb_vec_dot(zb, d->contact.rc));
        d->hop_max = d->def.height0;
    }
    d->last_switch_time = NAN;
    d->memo_valid = 0;
    d->t0 = t0;
    d->energy0 = 0.0;
    gb_dynamics_observables o;
    status = gb_dynamics_observe(d, t0, y, &o);
    if (!status) d->energy0 = o.energy;
    return status;
}

/* max |RᵀR − I| */
static double orthonormality_of(const double R[9])
{
    double worst = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            const double dot = R[i] * R[j] + R[3 + i] * R[3 + j] + R[6 + i] * R[6 + j];
            worst = fmax(worst, fabs(dot - (i == j)));
        }
    return worst;
}

int gb_dynamics_observe(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_observables *o)
{
    memset(o, 0, sizeof *o);
    o->t = t;
    gb_dynamics_rotation(y + GB_STATE_Q, o->R);
    zb_of(o->R, o->zb);
    memcpy(o->omega, y + GB_STATE_OMEGA, sizeof o->omega);
    contact_eval c;
    two_point_eval tp;
    int status = GB_OK;
    tp.merged = 0;
    gb_forcing_geff_with_rate(&d->def.forcing, t, &o->geff, &o->geff_rate);
    if (d->flying) {
        /* the lowest point for the clearance; no contact force */
        const double m = d->def.mass;
        double Iw[3], I[3][3];
        status = contact_at(d, t, o->zb, o->omega, &c);
        if (!status) status = free_angular_acceleration(d, o->omega, o->omega_dot);
        if (status) return status;
        flight_state(d, t, &o->zeta, o->velocity);
        memcpy(o->rc, c.rc, sizeof o->rc);
        memcpy(o->rc_dot, c.rc_dot, sizeof o->rc_dot);
        o->index = c.index;
        o->height = gb_vec_dot(o->zb, c.rc);
        o->clearance = o->zeta + o->height;
        memcpy(I, d->inertia, sizeof I);
        mat_vec(I, o->omega, Iw);
        o->kinetic = 0.5 * m * gb_vec_dot(o->velocity, o->velocity) + 0.5 * gb_vec_dot(o->omega, Iw);
        o->potential = m * o->geff * o->zeta;
        o->energy = o->kinetic + o->potential;
        o->power_gravity = -m * o->geff * o->velocity[2];
        o->power_damping = -d->def.damping * gb_vec_dot(o->omega, o->omega);
        o->work = y[GB_STATE_WORK];
        o->residual = o->energy - d->energy0 - o->work + d->impact_loss;
        o->contacts = 0;
        o->orthonormality = orthonormality_of(o->R);
        o->grid_switches = d->grid_switches;
        o->branch_switches = d->branch_switches;
        o->branches_lost = d->branches_lost;
        return GB_OK;
    }
    if (d->resting) {
        status = contact_at(d, t, o->zb, o->omega, &c); /* ω̇ = 0 */
        if (status) return status;
    } else if (d->two_point && (status = two_point_at(d, t, y, &tp)) == GB_OK && !tp.merged) {
        c = tp.p;
        memcpy(o->omega_dot, tp.omega_dot, sizeof tp.omega_dot);
    } else {
        if (status) return status; /* (the end of a crease is observed as rolling on P) */
        status = contact_at(d, t, o->zb, o->omega, &c);
        if (!status) status = angular_acceleration(d, o->geff, o->zb, o->omega, &c, o->omega_dot);
        if (status) return status;
    }
    const double m = d->def.mass;
    memcpy(o->rc, c.rc, sizeof o->rc);
    memcpy(o->rc_dot, c.rc_dot, sizeof o->rc_dot);
    o->index = c.index;
    o->height = gb_vec_dot(o->zb, c.rc);
    o->zeta = -o->height;
    double IP[3][3], IPw[3], tau_g[3];
    inertia_about_contact(d, c.rc, IP);
    mat_vec(IP, o->omega, IPw);
    o->kinetic = 0.5 * gb_vec_dot(o->omega, IPw);
    o->potential = m * o->geff * o->zeta;
    o->energy = o->kinetic + o->potential;
    gb_vec_cross(c.rc, o->zb, tau_g);
    o->power_gravity = m * o->geff * gb_vec_dot(o->omega, tau_g);
    o->power_damping = -d->def.damping * gb_vec_dot(o->omega, o->omega);
    o->work = y[GB_STATE_WORK];
    o->residual = o->energy - d->energy0 - o->work;
    if (d->def.contact_law == GB_CONTACT_LAW_UNILATERAL) o->residual += d->impact_loss; /* the ledger */
    double acc[3];
    o->normal_force = normal_force_of(d, o->geff, o->zb, o->omega, o->omega_dot, &c, acc);
    const double vertical = gb_vec_dot(acc, o->zb);
    double horizontal[3];
    for (int k = 0; k < 3; k++) horizontal[k] = acc[k] - vertical * o->zb[k];
    o->friction_needed = o->normal_force > 0.0 ? m * gb_vec_norm(horizontal) / o->normal_force : INFINITY;
    const int two = d->two_point && !d->resting && !tp.merged;
    o->contacts = d->resting ? 3 : 1 + two;
    double vb[3];
    gb_vec_cross(o->omega, (const double[3]){-c.rc[0], -c.rc[1], -c.rc[2]}, vb); /* v_G = ω × (G − P) */
    for (int i = 0; i < 3; i++) o->velocity[i] = o->R[3 * i] * vb[0] + o->R[3 * i + 1] * vb[1] + o->R[3 * i + 2] * vb[2];
    o->normal_forces[0] = o->normal_force;
    if (two) {
        memcpy(o->rc_other, tp.rq, sizeof o->rc_other);
        memcpy(o->normal_forces, tp.normal, sizeof tp.normal);
        o->friction_needed = tp.friction_needed;
        o->balance = tp.balance;
        o->tie = d->def.length * (tp.p.point.height - tp.q.height);
    }
    o->orthonormality = orthonormality_of(o->R);
    o->grid_switches = d->grid_switches;
    o->branch_switches = d->branch_switches;
    o->branches_lost = d->branches_lost;
    return GB_OK;
}

int gb_dynamics_start(const gb_surface *body, const gb_dynamics_def *def, const double R0[9], const double omega0[3],
                      gb_dynamics **out, double y[GB_STATE_SIZE])
{
    *out = NULL;
    int status = gb_dynamics_create(body, def, out);
    if (!status) status = gb_dynamics_init_state(*out, 0.0, R0, omega0, y);
    if (status) {
        gb_dynamics_free(*out);
        *out = NULL;
    }
    return status;
}
