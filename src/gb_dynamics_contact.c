/* gb_dynamics_contact — the contact at a state: a grid's nodes (the paper's search, the tracker, the
 * next node a pivoting body meets), Newton's continuation of a continuous contact with its predictors,
 * and the competitor the certificate proves or finds lower (gb_dynamics_internal.h). */
#include "gb_dynamics_internal.h"

#include "gb_certify_internal.h"
#include "gb_contact.h"
#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

int gb_dyn_pivots(const gb_dynamics *d)
{
    return d->def.contact != GB_CONTACT_MODEL_CONTINUOUS && d->law->pivots;
}

/* Grid node `index` as a contact point at vertical zb: fixed in the body, its height ẑ_b·x. */
void gb_dyn_grid_point(const gb_dynamics *d, size_t index, const double zb[3], gb_contact_point *p)
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
    gb_dynamics_lowest_node lowest;
    void *user;
    if (d->def.contact == GB_CONTACT_MODEL_GRID && gb_dyn_lowest_hook(d, &lowest, &user)) {
        double unit[3];
        status = gb_contact_unit_vertical(zb, unit);
        if (!status) {
            node->index = lowest(user, unit);
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

/* A grid body under the unilateral law: the lowest node at zb but the node(s) it stands on (P; and Q on
 * two points), the one it meets the plane with next. Its gap to them is continuous in time (a minimum
 * of continuous heights), so an event located on it is the first node to reach the plane. */
int gb_dyn_next_node(gb_dynamics *d, const double zb[3], gb_contact_point *other)
{
    const size_t stands[2] = {d->index, d->contact2.node};
    gb_contact_node node;
    const int status = gb_contact_grid_lowest_except(d->grid, zb, d->next_hint, stands, 1 + (d->mode == GB_DYN_TWO_POINT), &node);
    if (status) return status;
    gb_dyn_grid_point(d, node.index, zb, other);
    d->next_hint = node.index; /* the search's seed next time (it changes no answer) */
    d->contact_queries++, d->nodes_visited += node.visited;
    return GB_OK;
}

/* The contact point `from` continued to vertical zb: Newton from its angles (continuous), or the same
 * node (grid). */
int gb_dyn_point_at(gb_dynamics *d, const double zb[3], const gb_contact_point *from, gb_contact_point *out)
{
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) {
        gb_dyn_grid_point(d, from->node, zb, out);
        return GB_OK;
    }
    return gb_contact_refine(&d->surface, zb, from->phi, from->theta, &d->refine, out);
}

/* ṙ of contact point p per the angular velocity w (eq 72; a grid node is fixed in the body: 0). */
int gb_dyn_point_rate(const gb_dynamics *d, const double zb[3], const gb_contact_point *p, const double w[3], double v[3])
{
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) {
        memset(v, 0, 3 * sizeof *v);
        return GB_OK;
    }
    return gb_contact_rate(&d->surface, zb, p, w, v, NULL);
}

/* Store the accepted contact's time, and what its (φ̇, θ̇) (eq 72) is computed from when a Newton start needs it. */
int gb_dyn_remember_rate(gb_dynamics *d, double t, const double y[GB_STATE_SIZE])
{
    d->contact_time = t;
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) return GB_OK; /* a node does not move on the body */
    gb_dyn_vertical(y, d->rate_zb);
    memcpy(d->rate_omega, y + GB_STATE_OMEGA, sizeof d->rate_omega);
    d->rate_contact = d->contact;
    d->rate_pending = 1;
    return GB_OK;
}

void gb_dyn_forget_rate(gb_dynamics *d)
{
    d->contact_rate[0] = d->contact_rate[1] = 0.0;
    d->rate_pending = 0;
}

/* The accepted contact's (φ̇, θ̇), computed from what gb_dyn_remember_rate kept the first time it is asked for. */
static const double *accepted_rate(gb_dynamics *d)
{
    double rc_dot[3];
    if (d->rate_pending &&
        gb_contact_rate(&d->surface, d->rate_zb, &d->rate_contact, d->rate_omega, rc_dot, d->contact_rate) != GB_OK)
        d->contact_rate[0] = d->contact_rate[1] = 0.0; /* a singular Hessian: start from the point itself */
    d->rate_pending = 0;
    return d->contact_rate;
}

/* The contact for vertical zb (unit) and angular velocity ω, warm-started from the accepted one. */
int gb_dyn_contact_at(gb_dynamics *d, double t, const double zb[3], const double omega[3], gb_dyn_contact *c)
{
    const double l = d->def.length;
    memset(c->rc_dot, 0, sizeof c->rc_dot);
    if (gb_dyn_pivots(d)) {
        /* the node the body pivots about: a change of node is an impact, located as an event */
        gb_dyn_grid_point(d, d->index, zb, &c->point);
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
        const double dt = t - d->contact_time, *rate = accepted_rate(d);
        gb_contact_chart_offset(&d->contact, rate[0] * dt, rate[1] * dt, &start[0], &start[1]);
    }
    if (!same) status = gb_contact_refine(&d->surface, unit, start[0], start[1], &d->refine, &c->point);
    if ((status == GB_ENOCONV || (!status && !c->point.is_minimum)) && (d->certify || d->starts)) {
        /* The continued branch has no minimum here (a fold of h inside the step): the contact is the
         * global minimum at this state, found and certified from scratch. */
        d->branches_lost++;
        status = gb_dyn_global_minimum(d, zb, &c->point);
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
int gb_dyn_contact_global(gb_dynamics *d, const double zb[3])
{
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) {
        gb_contact_node node;
        const int status = gb_contact_grid_brute(d->grid, zb, &node);
        if (!status) d->index = node.index, gb_dyn_grid_point(d, node.index, zb, &d->contact);
        return status;
    }
    if (d->certify) gb_certify_forget(d->certify);
    return gb_dyn_global_minimum(d, zb, &d->contact);
}

/* certificate = multi-start: the lowest of the branch grid's local minima polished by Newton (uncertified). */
static int multistart_lowest(gb_dynamics *d, const double zb[3], gb_contact_point *out)
{
    gb_contact_branches b;
    const int status = gb_contact_branches_find(d->starts, zb, &d->refine, &b);
    if (status) return status;
    d->multistart_seeds += b.seeds;
    if (!b.count)
        return gb_error_set(GB_ENOCONV, "multi-start: no local minimum of h found at z_b = (%g, %g, %g)", zb[0], zb[1], zb[2]);
    *out = b.branch[0];
    return GB_OK;
}

/* certificate = atlas: gb_certify_global_minimum's first candidate when the atlas proves it global, which is then
 * the point gb_certify would return (its first check deciding the same predicate), without its boxes; 0 otherwise
 * (undecided, a lower minimum, or an error), and gb_certify is asked as before. */
static int atlas_global_minimum(gb_dynamics *d, const double zb[3], gb_contact_point *out)
{
    double unit[3];
    gb_contact_point p;
    gb_certify_result r;
    if (gb_certify_first_candidate(d->certify, zb, &d->refine, unit, &p) ||
        gb_atlas_check(d->atlas, unit, &p, &d->refine, &r)) {
        gb_error_clear(); /* gb_certify meets the same error, and says it */
        return 0;
    }
    if (r.verdict != GB_CERTIFY_GLOBAL) return 0;
    *out = p;
    return 1;
}

/* The global minimum at zb from scratch: certified (the atlas where it can, gb_certify), or the multi-start's lowest. */
int gb_dyn_global_minimum(gb_dynamics *d, const double zb[3], gb_contact_point *out)
{
    if (d->starts) return multistart_lowest(d, zb, out);
    if (d->atlas && atlas_global_minimum(d, zb, out)) return GB_OK;
    return gb_certify_global_minimum(d->certify, zb, &d->refine, out);
}

/* The accepted contact (P) becomes p; a grid body's node index with it. */
void gb_dyn_set_contact(gb_dynamics *d, const gb_contact_point *p)
{
    d->contact = *p;
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) d->index = p->node;
}

/* Is `candidate` the global minimum at zb? The atlas answers where it can, gb_certify elsewhere. */
int gb_dyn_check_global(gb_dynamics *d, const double zb[3], const gb_contact_point *candidate, gb_certify_result *r)
{
    if (d->starts) { /* uncertified: GLOBAL when no polished minimum lies lower by more than η */
        gb_contact_point lowest;
        const size_t seeds = d->multistart_seeds;
        const int status = multistart_lowest(d, zb, &lowest);
        if (status) return status;
        memset(r, 0, sizeof *r);
        r->newton_runs = d->multistart_seeds - seeds;
        d->multistart_checks++;
        if (lowest.height < candidate->height - d->def.certify.height_tol && !gb_dyn_same_point(&lowest, candidate)) {
            r->verdict = GB_CERTIFY_LOWER_FOUND, r->lower = lowest;
            d->multistart_lower++;
        } else {
            r->verdict = GB_CERTIFY_GLOBAL;
        }
        return GB_OK;
    }
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
int gb_dyn_canonical_minimum(gb_dynamics *d, const double zb[3], gb_contact_point *p)
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
int gb_dyn_same_point(const gb_contact_point *a, const gb_contact_point *b)
{
    const double dx[3] = {a->rc[0] - b->rc[0], a->rc[1] - b->rc[1], a->rc[2] - b->rc[2]};
    return gb_vec_norm(dx) < 1e-7;
}

/* Continuous contact at state y: the continued branch (*continued) and, when the certificate finds a
 * lower local minimum, that minimum (*other, *found = 1). */
int gb_dyn_competitor(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *continued,
                      gb_contact_point *other, int *found)
{
    double zb[3];
    gb_dyn_vertical(y, zb);
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
    gb_dyn_contact c;
    int status = gb_dyn_contact_at(d, t, zb, y + GB_STATE_OMEGA, &c);
    if (status) return status;
    *continued = c.point;
    *found = 0;
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) {
        /* a grid body: the next node, when it is strictly lower than the one the body pivots about */
        status = gb_dyn_next_node(d, zb, other);
        if (status) return status;
        *found = other->height < continued->height - GB_DYN_GRID_TIE;
        memcpy(d->memo_key, key, sizeof key);
        d->memo_continued = *continued, d->memo_found = *found, d->memo_other = *other, d->memo_valid = 1;
        return GB_OK;
    }
    /* A lower minimum found is checked in turn, until the lowest is proved global: with several
     * lower minima the switch goes to the global one, whichever the search met first. */
    gb_contact_point candidate = c.point;
    for (int round = 0; round < 16; round++) {
        gb_certify_result r;
        status = gb_dyn_check_global(d, zb, &candidate, &r);
        if (status) return status;
        if (r.verdict != GB_CERTIFY_LOWER_FOUND) break;
        candidate = r.lower;
        *other = r.lower;
        *found = 1;
    }
    if (*found) status = gb_dyn_canonical_minimum(d, zb, other);
    if (status) return status;
    /* Under a law with impacts a lower minimum within 1e-7 of the continued one is the same contact (a tie
     * where minima crowd together at the end of a crease), as on two points: an impact between two
     * coincident points has no meaning. (The held law keeps its switches as they always were.) */
    if (*found && d->law->impacts && gb_dyn_same_point(other, continued)) *found = 0;
    if (*found && continued->height - other->height < d->lift_allow) *found = 0; /* a lifted point's dip */
    memcpy(d->memo_key, key, sizeof key);
    d->memo_continued = *continued;
    d->memo_found = *found;
    if (*found) d->memo_other = *other;
    d->memo_valid = 1;
    return GB_OK;
}

