/* gb_dynamics_events — the events that end a mode: for each mode, whether one is due at a state (pending:
 * the step's end is checked, and the kind of event into d->event), and the event's function, < 0 before it
 * and > 0 after (gap), which gb_integrate's one locator brings to 0 inside the step.
 *   one point   another minimum lower than the contact (eq 39, a change of contact); with impacts, the
 *               normal force reaching 0 (lift-off)
 *   two points  a normal force reaching 0 (a lift); a third point reaching the plane
 *   at rest     g_eff reaching 0 (lift-off)
 *   flight      the lowest point reaching the plane (landing) */
#include "gb_dynamics_internal.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <string.h>

/* ---- one point ------------------------------------------------------------------------------------ */

static int one_point_margin(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], double *margin);
static int switch_gap(gb_dynamics *d, const double y[GB_STATE_SIZE], const gb_contact_point *other, double *gap,
                      gb_contact_point *other_here);

/* The held law's grid has no event (the paper's rule: the lowest node at every evaluation). */
int gb_dyn_one_point_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found)
{
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS && !gb_dyn_pivots(d)) return GB_OK;
    gb_contact_point continued;
    int status = gb_dyn_competitor(d, t, y, &continued, other, found);
    if (!status && *found) d->event = GB_DYN_EVENT_SWITCH;
    if (!status && !*found && d->law->slips) {
        /* the force rolling needs at the cone's edge: the point slips (before N can reach 0, unless F_t is 0) */
        double margin;
        status = one_point_margin(d, t, y, &margin);
        if (!status && margin < 0.0) *other = continued, *found = 1, d->event = GB_DYN_EVENT_SLIP;
    }
    if (!status && !*found && d->law->translates) {
        /* a plane that can only push cannot hold the body down: where N reaches 0 it leaves the plane */
        double n;
        status = gb_dyn_one_point_normal(d, t, y, &n);
        if (!status && n < 0.0) *other = continued, *found = 1, d->event = GB_DYN_EVENT_LIFT_OFF;
    }
    return status;
}

/* Rolling on the accepted contact alone at state y: how far its force is inside the cone. */
static int one_point_margin(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], double *margin)
{
    double zb[3], geff, geff_rate, w_dot[3];
    gb_dyn_contact c;
    gb_dyn_vertical(y, zb);
    gb_forcing_geff_with_rate(&d->def.forcing, t, &geff, &geff_rate);
    int status = gb_dyn_contact_at(d, t, zb, y + GB_STATE_OMEGA, &c);
    if (!status) status = gb_dyn_angular_acceleration(d, geff, zb, y + GB_STATE_OMEGA, &c, w_dot);
    *margin = status ? NAN : gb_dyn_one_point_margin(d, geff, zb, y + GB_STATE_OMEGA, w_dot, &c);
    return status;
}

int gb_dyn_one_point_gap(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other,
                         double *gap, gb_contact_point *other_here)
{
    if (d->event == GB_DYN_EVENT_LIFT_OFF || d->event == GB_DYN_EVENT_SLIP) { /* −N, or −the cone's margin */
        double n;
        const int status = d->event == GB_DYN_EVENT_SLIP ? one_point_margin(d, t, y, &n) : gb_dyn_one_point_normal(d, t, y, &n);
        *gap = -n;
        *other_here = *other;
        return status;
    }
    return switch_gap(d, y, other, gap, other_here);
}

/* Another minimum against the contact (eq 39): > 0 where it is lower. */
static int switch_gap(gb_dynamics *d, const double y[GB_STATE_SIZE], const gb_contact_point *other, double *gap,
                      gb_contact_point *other_here)
{
    double zb[3];
    gb_dyn_vertical(y, zb);
    gb_contact_point here;
    int status = gb_dyn_point_at(d, zb, &d->contact, &here);
    /* a grid body: the next node at this state, whichever it is (continuous: `other`, continued) */
    if (!status) status = d->def.contact == GB_CONTACT_MODEL_CONTINUOUS ? gb_dyn_point_at(d, zb, other, other_here)
                                                                        : gb_dyn_next_node(d, zb, other_here);
    if (status) return status;
    *gap = here.height - other_here->height; /* > 0: the other branch is lower (eq 39) */
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) *gap -= GB_DYN_GRID_TIE;
    /* With impacts: where Newton from the other branch ends on the contact itself, that branch is not born yet
     * (it appears in a fold inside the step, above the contact, since the lowest height is continuous), so it
     * is not lower: the crossing is located where it has been born and passes below. */
    else if (d->law->impacts && gb_dyn_same_point(other_here, &here))
        *gap = -1e-15;
    else
        *gap -= d->lift_allow;
    return GB_OK;
}

/* ---- two points ----------------------------------------------------------------------------------- */

static int two_point_search(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found);
static int third_point_search(gb_dynamics *d, const double zb[3], const gb_contact_point *p, const gb_contact_point *q,
                              gb_contact_point *other, int *found);
static int third_gap(gb_dynamics *d, const double y[GB_STATE_SIZE], const gb_contact_point *other, double *gap,
                     gb_contact_point *other_here);

/* Two points at state y: is an event due? A normal force below 0 (GB_DYN_EVENT_LIFT), or a third minimum
 * lower than both points, proved by the certificate (GB_DYN_EVENT_THIRD, *other). */
int gb_dyn_two_point_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found)
{
    /* The step's end is checked by gb_dynamics_switch_pending and again by gb_dynamics_accept at the same
     * state: the memo (as gb_dyn_competitor()'s, its last key 1 for this mode) answers the second. */
    double zkey[3];
    gb_dyn_vertical(y, zkey);
    const double key[8] = {zkey[0], zkey[1], zkey[2], t, y[GB_STATE_OMEGA], y[GB_STATE_OMEGA + 1], y[GB_STATE_OMEGA + 2], 1.0};
    if (d->memo_valid && memcmp(key, d->memo_key, sizeof key) == 0) {
        *found = d->memo_found;
        if (*found) *other = d->memo_other, d->event = d->memo_event;
        return GB_OK;
    }
    int status = two_point_search(d, t, y, other, found);
    if (status) return status;
    memcpy(d->memo_key, key, sizeof key);
    d->memo_found = *found;
    if (*found) d->memo_other = *other, d->memo_event = d->event;
    d->memo_valid = 1;
    return GB_OK;
}

static int two_point_search(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found)
{
    gb_dyn_two_point tp;
    *found = 0;
    int status = gb_dyn_two_point_eval(d, t, y, &tp, 1);
    if (status || tp.merged) return status; /* the end of a crease: gb_dynamics_accept leaves the mode */
    if (d->law->slips) { /* the cone holds the crease's forces whatever their open split? */
        int alone;
        if (gb_dyn_crease_margin(d->def.friction, tp.normal, (const double(*)[3])tp.tangent, tp.u, &alone) < 0.0) {
            d->event = GB_DYN_EVENT_SLIP;
            *other = tp.q;
            *found = 1;
            return GB_OK;
        }
    }
    if (fmin(tp.normal[0], tp.normal[1]) < 0.0) {
        d->event = GB_DYN_EVENT_LIFT;
        *other = tp.q;
        *found = 1;
        return GB_OK;
    }
    double zb[3];
    gb_dyn_vertical(y, zb);
    return third_point_search(d, zb, &tp.p.point, &tp.q, other, found);
}

/* A third minimum lower than both points p and q, proved by the certificate (a grid body: a node strictly
 * lower than both): GB_DYN_EVENT_THIRD with *other. */
static int third_point_search(gb_dynamics *d, const double zb[3], const gb_contact_point *p, const gb_contact_point *q,
                              gb_contact_point *other, int *found)
{
    int status;
    d->event = GB_DYN_EVENT_THIRD;
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) {
        status = gb_dyn_next_node(d, zb, other);
        *found = !status && other->height < fmin(p->height, q->height) - GB_DYN_GRID_TIE;
        return status;
    }
    gb_contact_point candidate = p->height <= q->height ? *p : *q;
    for (int round = 0; round < 16; round++) {
        gb_certify_result r;
        status = gb_dyn_check_global(d, zb, &candidate, &r);
        if (status) return status;
        if (r.verdict != GB_CERTIFY_LOWER_FOUND) break;
        candidate = *other = r.lower;
        *found = 1;
    }
    if (*found) status = gb_dyn_canonical_minimum(d, zb, other);
    if (!status && *found && (gb_dyn_same_point(other, p) || gb_dyn_same_point(other, q))) *found = 0; /* P and Q tie */
    d->event = GB_DYN_EVENT_THIRD;
    return status;
}

int gb_dyn_two_point_gap(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other,
                         double *gap, gb_contact_point *other_here)
{
    if (d->event == GB_DYN_EVENT_LIFT || d->event == GB_DYN_EVENT_SLIP) { /* −min(N_P, N_Q), or −the cone's margin */
        gb_dyn_two_point tp;
        int status = gb_dyn_two_point_eval(d, t, y, &tp, 1);
        if (!status && tp.merged)
            status = gb_error_set_limit(GB_ENUMERIC, "two-point contact at t = %.9g: the crease ends while a lift or a slip is "
                                        "located", t);
        if (status) return status;
        int alone;
        *gap = d->event == GB_DYN_EVENT_LIFT ? -fmin(tp.normal[0], tp.normal[1])
                                             : -gb_dyn_crease_margin(d->def.friction, tp.normal, (const double(*)[3])tp.tangent, tp.u, &alone);
        *other_here = *other;
        return GB_OK;
    }
    return third_gap(d, y, other, gap, other_here);
}

/* A third point against the lower of the two the body is on (contact, contact2). */
static int third_gap(gb_dynamics *d, const double y[GB_STATE_SIZE], const gb_contact_point *other, double *gap,
                     gb_contact_point *other_here)
{
    double zb[3];
    gb_dyn_vertical(y, zb);
    gb_contact_point here, q;
    int status = gb_dyn_point_at(d, zb, &d->contact, &here);
    if (!status) status = gb_dyn_point_at(d, zb, &d->contact2, &q);
    if (!status && q.height < here.height) here = q;
    if (!status) status = d->def.contact == GB_CONTACT_MODEL_CONTINUOUS ? gb_dyn_point_at(d, zb, other, other_here)
                                                                        : gb_dyn_next_node(d, zb, other_here);
    if (status) return status;
    *gap = here.height - other_here->height;
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) *gap -= GB_DYN_GRID_TIE;
    return GB_OK;
}

/* ---- at rest -------------------------------------------------------------------------------------- */

/* On three points the weight m g_eff holds the body; it lifts off them all where g_eff reaches 0. */
int gb_dyn_rest_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found)
{
    (void)y;
    if (gb_forcing_geff(&d->def.forcing, t) < 0.0) *other = d->contact, *found = 1, d->event = GB_DYN_EVENT_LIFT_OFF;
    return GB_OK;
}

/* −g_eff, to which all three normal forces are proportional. */
int gb_dyn_rest_gap(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other, double *gap,
                    gb_contact_point *other_here)
{
    (void)y;
    *gap = -gb_forcing_geff(&d->def.forcing, t);
    *other_here = *other;
    return GB_OK;
}

/* ---- flight ---------------------------------------------------------------------------------------- */

/* Flight at state y: does the lowest point (continued, or a lower minimum the certificate finds) lie
 * below the plane? Then *other is it and the event is a landing. */
int gb_dyn_flight_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found)
{
    gb_contact_point continued, lower;
    int lower_found;
    const int status = gb_dyn_competitor(d, t, y, &continued, &lower, &lower_found);
    if (status) return status;
    const gb_contact_point *lowest = lower_found ? &lower : &continued;
    double zeta, v[3];
    gb_dyn_flight_state(d, t, &zeta, v);
    *found = zeta + d->def.length * (lowest->height + d->gap_allow) < 0.0;
    if (*found) *other = *lowest, d->event = GB_DYN_EVENT_LANDING;
    return GB_OK;
}

/* −(the lowest point's height above the plane): the lower of the lowest point at the step's start and the
 * one at its end (`other`), both continued, since the lowest point may change branch inside the step. */
int gb_dyn_flight_gap(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other, double *gap,
                      gb_contact_point *other_here)
{
    double zb[3], zeta, v[3];
    gb_dyn_vertical(y, zb);
    gb_contact_point here;
    int status = gb_dyn_point_at(d, zb, other, other_here);
    if (!status && !gb_dyn_same_point(other, &d->contact)) {
        status = gb_dyn_point_at(d, zb, &d->contact, &here);
        if (!status && here.height < other_here->height) *other_here = here;
    }
    gb_dyn_flight_state(d, t, &zeta, v);
    *gap = -(zeta + d->def.length * (other_here->height + d->gap_allow));
    return status;
}

/* ---- sliding -------------------------------------------------------------------------------------- */

/* A slipping point's stop: > 0 where its slip has fallen to the stop's speed (gb_dyn_slip_stop_speed) or
 * turned against its direction at the accepted state. */
static double stop_gap(const gb_dynamics *d, const double y[GB_STATE_SIZE], const double zb[3], const double r[3],
                       const double slip_acc[3], int k)
{
    double s[3], body[3];
    gb_dyn_slip_of(y, zb, r, body);
    gb_dyn_to_inertial(y, body, s);
    return -fmin(gb_vec_dot(s, d->slide.ref[k]), gb_vec_norm(body) - gb_dyn_slip_stop_speed(d, y, body, slip_acc));
}

/* Sliding at state y: a slip stopped or turned back (its slip against its direction at the accepted
 * state: GB_DYN_EVENT_STICK), a sticking point's force at the cone's edge (GB_DYN_EVENT_SLIP), a normal force
 * below 0 (a lift, or the lift-off of the last point), a new point on the plane (a switch; a third point). */
int gb_dyn_sliding_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found)
{
    gb_dyn_friction_point points[2];
    gb_dyn_friction_forces f;
    int status = gb_dyn_sliding_eval(d, t, y, points, &f);
    if (status) return status;
    double zb[3];
    gb_dyn_vertical(y, zb);
    *other = d->contact;
    for (int k = 0; k < d->slide.count && !*found; k++) {
        if (!d->slide.slides[k] || !d->slide.armed[k]) continue; /* a slip still at rounding's size has no stop yet */
        if (stop_gap(d, y, zb, points[k].r, f.slip_acc[k], k) >= 0.0) *found = 1, d->event = GB_DYN_EVENT_STICK, d->event_point = k;
    }
    for (int k = 0; k < d->slide.count && !*found; k++)
        if (!d->slide.slides[k] && f.margin[k] < 0.0) *found = 1, d->event = GB_DYN_EVENT_SLIP, d->event_point = k;
    for (int k = 0; k < d->slide.count && !*found; k++)
        if (f.normal[k] < 0.0)
            *found = 1, d->event = d->slide.count == 2 ? GB_DYN_EVENT_LIFT : GB_DYN_EVENT_LIFT_OFF, d->event_point = k;
    if (*found) return GB_OK;
    if (d->slide.count == 1) {
        gb_contact_point continued;
        status = gb_dyn_competitor(d, t, y, &continued, other, found);
        if (!status && *found) d->event = GB_DYN_EVENT_SWITCH;
        return status;
    }
    gb_contact_point p, q;
    status = gb_dyn_point_at(d, zb, &d->contact, &p);
    if (!status) status = gb_dyn_second_point(d, zb, &q);
    if (!status) status = third_point_search(d, zb, &p, &q, other, found);
    return status;
}

int gb_dyn_sliding_gap(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other, double *gap,
                       gb_contact_point *other_here)
{
    if (d->event == GB_DYN_EVENT_SWITCH) return switch_gap(d, y, other, gap, other_here);
    if (d->event == GB_DYN_EVENT_THIRD) return third_gap(d, y, other, gap, other_here);
    *other_here = *other;
    const int k = d->event_point;
    gb_dyn_friction_point points[2];
    gb_dyn_friction_forces f;
    const int status = gb_dyn_sliding_eval(d, t, y, points, &f);
    if (status) return status;
    if (d->event == GB_DYN_EVENT_STICK) {
        double zb[3];
        gb_dyn_vertical(y, zb);
        *gap = stop_gap(d, y, zb, points[k].r, f.slip_acc[k], k);
        return GB_OK;
    }
    *gap = d->event == GB_DYN_EVENT_SLIP ? -f.margin[k] : -f.normal[k];
    return GB_OK;
}
