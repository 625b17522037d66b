/* gb_dynamics_handover — a run handed between the strategies (docs/stepping.md, "The hand-over"): from the
 * event-driven modes to the stepped one where the law meets a limit (or before a start it refuses), and back in flight. */
#include "gb_dynamics_stepper_internal.h"

#include "gb_dynamics_protocol_internal.h"
#include "gb_error.h"

#include <stdio.h>
#include <string.h>

int gb_dynamics_stepped(const gb_dynamics *d) { return d->modes == gb_dyn_stepped_modes; }

int gb_dynamics_hand_over(gb_dynamics *d, double h, double theta, const gb_contact_problem_def *solver)
{
    if (gb_dynamics_stepped(d)) /* stepped already; handed over at its start: its solver now */
        return d->stepper->problem ? GB_OK : gb_dyn_stepping_set(d->stepper, h, theta, solver, 0);
    const gb_dyn_mode *modes = d->modes;
    int status = gb_dynamics_stepping_prepare(d);
    if (!status) status = gb_dyn_stepping_set(d->stepper, h, theta, solver, 1);
    if (status) return status;
    gb_dyn_stepper *s = d->stepper;
    d->event_modes = modes, d->modes = gb_dyn_stepped_modes;
    /* the points the body stood on carry it into the first step (and stay in its problem within a step's reach) */
    const gb_dyn_mode_id mode = d->mode;
    const int on = mode != GB_DYN_FLIGHT;
    const int two = mode == GB_DYN_TWO_POINT || mode == GB_DYN_REST || (mode == GB_DYN_SLIDING && d->slide.count == 2);
    const gb_contact_point *stood[2] = {&d->contact, &d->contact2};
    if (s->smooth) memset(s->active, 0, sizeof s->active);
    for (int k = 0; k < on + (on && two); k++) {
        const size_t node = s->smooth ? (size_t)gb_dyn_stepping_take_slot(s, stood[k], -1) : stood[k]->node;
        s->touched[s->touched_count++] = node;
    }
    s->touching = s->touched_count, s->sliding = mode == GB_DYN_SLIDING;
    return GB_OK;
}

int gb_dyn_stepping_take_start(gb_dynamics *d, const char *limit)
{
    snprintf(d->start_limit, sizeof d->start_limit, "%s", limit);
    const gb_dyn_mode *modes = d->modes;
    const int status = gb_dynamics_stepping_prepare(d);
    if (!status) d->modes = gb_dyn_stepped_modes, d->event_modes = modes;
    return status;
}

void gb_dyn_stepping_stand(gb_dynamics *d)
{
    /* a body started on the plane stands on its lowest point, as the law's start had it: that point carries it into the
     * first step (a trajectory placed beside it a hair above the plane then is not in flight for a step) */
    gb_dyn_stepper *s = d->stepper;
    if (s && d->def.height0 == 0.0) s->touched[0] = s->lowest, s->touched_count = 1, s->touching = 1;
}

const char *gb_dynamics_start_limit(const gb_dynamics *d) { return d->start_limit[0] ? d->start_limit : NULL; }

void gb_dynamics_hand_back_now(gb_dynamics *d)
{
    if (!d->event_modes) return;
    d->modes = d->event_modes, d->event_modes = NULL;
    d->last_valid = d->memo_valid = 0, d->event = GB_DYN_EVENT_NONE;
}

int gb_dynamics_hand_back(gb_dynamics *d, double t, double y[GB_STATE_SIZE], int *back)
{
    *back = 0;
    gb_dyn_stepper *s = d->stepper;
    if (!d->event_modes || !s || s->touching || !(s->clearance > 0.0)) return GB_OK;
    double R[9], zb[3], vb[3];
    gb_dynamics_rotation(y + GB_STATE_Q, R);
    zb[0] = R[6], zb[1] = R[7], zb[2] = R[8];
    int status = gb_dyn_stepping_scan(d, y, zb);
    if (status) return status;
    gb_contact_point lowest;
    if (s->smooth) lowest = s->slot[s->lowest];
    else gb_dyn_grid_point(d, s->lowest, zb, &lowest);
    d->modes = d->event_modes, d->event_modes = NULL;
    gb_dyn_set_contact(d, &lowest);
    d->last_valid = d->memo_valid = 0, d->event = GB_DYN_EVENT_NONE, d->lift_allow = 0.0;
    const double *v = y + GB_STATE_VELOCITY; /* into body axes: Rᵀ v */
    for (int i = 0; i < 3; i++) vb[i] = R[i] * v[0] + R[3 + i] * v[1] + R[6 + i] * v[2];
    gb_dyn_start_flight(d, t, y, vb, y[GB_STATE_ZETA]);
    status = gb_dyn_remember_rate(d, t, y);
    *back = !status;
    return status;
}

