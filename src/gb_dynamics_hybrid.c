/* gb_dynamics_hybrid — the hybrid system as a whole (gb_dynamics_internal.h), above its modes, events and
 * jumps: the one table of modes, the creation of a run and its start, and every public call that goes to
 * the current mode (a step accepted, an event pending and its function, the jump at it, the
 * observables). */
#include "gb_dynamics_internal.h"

#include "gb_dynamics_protocol_internal.h"
#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* The hybrid system in one table, by gb_dyn_mode_id: each mode's vector field, step, observables and
 * translation (its own file), the events that end it (gb_dynamics_events.c) and the jumps they make
 * (gb_dynamics_jumps.c). Every public call below goes through it; gb_dyn_field reaches it through the
 * state (gb_dynamics.c). */
static const gb_dyn_mode modes[GB_DYN_MODES] = {
    /* start NULL: the hybrid system's own start */
    [GB_DYN_ONE_POINT] = {"one point", 1, gb_dyn_one_point_field, gb_dyn_one_point_accept, gb_dyn_one_point_pending,
                          gb_dyn_one_point_gap, gb_dyn_one_point_event, gb_dyn_one_point_jump, gb_dyn_one_point_observe,
                          gb_dyn_translate_on_plane, NULL},
    [GB_DYN_TWO_POINT] = {"two points", 1, gb_dyn_two_point_field, gb_dyn_two_point_accept, gb_dyn_two_point_pending,
                          gb_dyn_two_point_gap, gb_dyn_two_point_event, gb_dyn_two_point_jump, gb_dyn_two_point_observe,
                          gb_dyn_translate_on_plane, NULL},
    [GB_DYN_REST] = {"at rest", 0, gb_dyn_rest_field, gb_dyn_rest_accept, gb_dyn_rest_pending, gb_dyn_rest_gap,
                     gb_dyn_rest_event, gb_dyn_no_jump, gb_dyn_rest_observe, gb_dyn_rest_translate, NULL},
    [GB_DYN_FLIGHT] = {"flight", 1, gb_dyn_flight_field, gb_dyn_flight_accept, gb_dyn_flight_pending, gb_dyn_flight_gap,
                       gb_dyn_flight_event, gb_dyn_no_jump, gb_dyn_flight_observe, gb_dyn_flight_translate, NULL},
    [GB_DYN_SLIDING] = {"sliding", 1, gb_dyn_sliding_field, gb_dyn_sliding_accept, gb_dyn_sliding_pending,
                        gb_dyn_sliding_gap, gb_dyn_sliding_event, gb_dyn_no_jump, gb_dyn_sliding_observe,
                        gb_dyn_sliding_translate, NULL},
};

int gb_dynamics_create_in(const gb_surface *surface, const gb_dynamics_def *def, gb_dynamics_context *context,
                          gb_dynamics **out)
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
    if (gb_impact_restitution_check(def->restitution)) return GB_EDOM;
    if (!(isfinite(def->height0) && def->height0 >= 0.0) ||
        !(isfinite(def->velocity0[0]) && isfinite(def->velocity0[1]) && isfinite(def->velocity0[2])))
        return gb_error_set(GB_EDOM, "initial height %g or velocity is out of range (allowed: height finite, >= 0; "
                            "velocity finite)", def->height0);
    int status = gb_dyn_law_check(def);
    if (status) return status;
    status = gb_forcing_validate(&def->forcing);
    if (status) return status;
    gb_dynamics *d = calloc(1, sizeof *d);
    if (!d) return gb_error_set(GB_ENOMEM, "out of memory for the dynamics");
    d->surface = *surface;
    d->def = *def;
    d->refine = gb_contact_refine_default_def();
    d->law = gb_dynamics_law_of(def->contact_law, def->friction);
    d->modes = d->law->mode ? d->law->mode : modes; /* a law of its own is one mode, index 0 */
    d->settle_time = def->settle_time;
    d->context = context;
    status = gb_dyn_body_create(d);
    if (status) {
        gb_dynamics_free(d);
        return status;
    }
    *out = d;
    return GB_OK;
}

int gb_dynamics_create(const gb_surface *surface, const gb_dynamics_def *def, gb_dynamics **out)
{
    return gb_dynamics_create_in(surface, def, NULL, out);
}

void gb_dynamics_free(gb_dynamics *d)
{
    if (!d) return;
    gb_dyn_stepping_free(d);
    gb_dyn_body_free(d);
    free(d->held);
    free(d);
}

size_t gb_dynamics_snapshot_size(void) { return sizeof(gb_dynamics); }

void gb_dynamics_snapshot(const gb_dynamics *d, void *out)
{
    memcpy(out, d, sizeof *d);
}

void gb_dynamics_restore(gb_dynamics *d, const void *snapshot)
{
    /* what the step may have allocated is the dynamics' own now: kept */
    struct gb_dyn_stepper *stepper = d->stepper;
    gb_dynamics_impact *held = d->held;
    const size_t capacity = d->held_capacity, count = d->held_count;
    memcpy(d, snapshot, sizeof *d);
    d->stepper = stepper, d->held = held, d->held_capacity = capacity, d->held_count = count;
}

/* z_b = Rᵀ e_z: the third row of R (eq 21). */
static void zb_of(const double R[9], double zb[3])
{
    zb[0] = R[6], zb[1] = R[7], zb[2] = R[8];
}

void gb_dynamics_use_step(gb_dynamics *d, double h)
{
    if (d->def.settle_time == 0.0) d->settle_time = h;
    d->step = h;
}

int gb_dynamics_state_finite(double t, const double y[GB_STATE_SIZE]) { return gb_dyn_state_finite(t, y); }

int gb_dynamics_accept(gb_dynamics *d, double t, double y[GB_STATE_SIZE], double *norm_drift)
{
    double *q = y + GB_STATE_Q;
    const double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(isfinite(n) && n > 0.0) || gb_dynamics_state_finite(t, y)) return gb_dyn_diverged(t);
    if (norm_drift) *norm_drift = n - 1.0;
    for (int k = 0; k < 4; k++) q[k] /= n;
    const int status = gb_dyn_current(d)->accept(d, t, y);
    if (!status) gb_dyn_current(d)->translate(d, t, y); /* by the mode the step ends in */
    return status;
}

int gb_dynamics_switch_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other,
                               int *found)
{
    *found = 0;
    d->event = GB_DYN_EVENT_NONE;
    return gb_dyn_current(d)->pending(d, t, y, other, found);
}

int gb_dynamics_branch_gap(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other,
                           double *gap, gb_contact_point *other_here)
{
    return gb_dyn_current(d)->gap(d, t, y, other, gap, other_here);
}

int gb_dynamics_switch_to(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    d->lift_allow = 0.0; /* any change of contact ends a lifted point's allowance (a lift sets a new one) */
    return gb_dyn_current(d)->event(d, t, y, branch);
}

int gb_dynamics_jump(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                     double out[GB_STATE_SIZE])
{
    return gb_dyn_current(d)->jump(d, t, y, branch, out);
}

/* ---------------------------------------------------------------- the state's start and its observables */

void gb_dynamics_adopt_contact(gb_dynamics *to, const gb_dynamics *from)
{
    to->memo_valid = 0;
    to->last_valid = 0;
    to->index = from->index;
    to->contact = from->contact;
    to->mode = from->mode, to->event = GB_DYN_EVENT_NONE;
    memcpy(to->mode_since, from->mode_since, sizeof to->mode_since);
    to->contact2 = from->contact2;
    to->crease.q_valid = 0;
    to->gap_allow = from->gap_allow;
    to->lifted = from->lifted, to->lift_allow = from->lift_allow;
    to->flight.t0 = from->flight.t0, to->flight.zeta0 = from->flight.zeta0;
    memcpy(to->flight.v0, from->flight.v0, sizeof to->flight.v0);
    to->contact_time = from->contact_time;
    memcpy(to->contact_rate, from->contact_rate, sizeof to->contact_rate);
    to->rate_pending = from->rate_pending;
    memcpy(to->rate_zb, from->rate_zb, sizeof to->rate_zb);
    memcpy(to->rate_omega, from->rate_omega, sizeof to->rate_omega);
    to->rate_contact = from->rate_contact;
    to->slide.count = from->slide.count;
    memcpy(to->slide.slides, from->slide.slides, sizeof to->slide.slides);
    memcpy(to->slide.start, from->slide.start, sizeof to->slide.start);
    memcpy(to->slide.ref, from->slide.ref, sizeof to->slide.ref);
    memcpy(to->slide.armed, from->slide.armed, sizeof to->slide.armed);
    gb_dyn_stepping_adopt(to, from);
}

int gb_dynamics_init_or_hand_over(gb_dynamics *d, double t0, const double R0[9], const double omega0[3],
                                  double y[GB_STATE_SIZE], int hand_over)
{
    int status = gb_dynamics_init_state(d, t0, R0, omega0, y);
    if (!status || !hand_over || !gb_error_at_limit() || !d->law->time_steps || gb_dynamics_stepped(d)) return status;
    status = gb_dyn_stepping_take_start(d, gb_error_message());
    gb_error_clear();
    if (!status) status = gb_dynamics_init_state(d, t0, R0, omega0, y);
    if (!status) gb_dyn_stepping_stand(d);
    return status;
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
    int status = gb_dyn_contact_global(d, zb);
    if (status) return status;
    if (d->def.contact == GB_CONTACT_MODEL_CONTINUOUS) gb_dyn_remember_rate(d, t0, y);
    d->last_valid = 0;
    d->grid_switches = d->branch_switches = d->branches_lost = 0;
    d->impacts = 0, d->impact_loss = d->impact_friction_max = 0.0;
    d->mode = GB_DYN_ONE_POINT, d->event = GB_DYN_EVENT_NONE;
    for (int m = 0; m < GB_DYN_MODES; m++) d->mode_since[m] = NAN, d->mode_time[m] = 0.0;
    d->mode_since[GB_DYN_ONE_POINT] = t0;
    d->next_hint = SIZE_MAX;
    d->crease.q_valid = 0;
    d->crease.entries = d->crease.settled = d->crease.lifts = d->crease.third_points = 0;
    d->gap_allow = GB_DYN_GAP_TOL;
    d->lift_allow = 0.0;
    d->flight.hop_max = 0.0;
    d->flight.lift_offs = d->flight.landings = d->flight.bounces = d->flight.flying_on = 0;
    d->slide.count = 0, d->slide.slides[0] = d->slide.slides[1] = 0;
    d->slide.slips = d->slide.sticks = 0;
    for (int k = GB_STATE_POSITION; k < GB_STATE_SIZE; k++) y[k] = 0.0;
    const double *v0 = d->def.velocity0;
    const int moving = v0[0] != 0.0 || v0[1] != 0.0 || v0[2] != 0.0;
    if (gb_dyn_current(d)->start) { /* a law of its own starts its mode */
        status = gb_dyn_current(d)->start(d, t0, y);
        if (status) return status;
    } else if (d->law->slips && d->def.height0 == 0.0 && moving) {
        /* on the plane at v0 (its horizontal part; the vertical one is the attitude's): the contact point
         * slips where that differs from rolling */
        gb_dyn_translate_on_plane(d, t0, y);
        y[GB_STATE_VELOCITY] = v0[0], y[GB_STATE_VELOCITY + 1] = v0[1];
        double s[3], rc[3];
        for (int k = 0; k < 3; k++) rc[k] = d->def.length * d->contact.rc[k];
        gb_dyn_slip_of(y, zb, rc, s);
        if (gb_vec_norm(s) > 1e-12 * (gb_vec_norm(v0) + 1e-300)) {
            double start[2][3] = {{0}};
            const int slides[2] = {1, 0};
            const double size = gb_vec_norm(s), unit[3] = {s[0] / size, s[1] / size, s[2] / size};
            gb_dyn_to_inertial(y, unit, start[0]);
            gb_dyn_start_sliding(d, t0, y, 1, slides, (const double(*)[3])start);
            d->slide.slips = 0; /* a start, not a change */
        }
    } else if (d->def.height0 > 0.0 || moving) {
        /* in flight: the lowest point (the contact found) at height0 above the plane, the centroid at v0 */
        double vb[3];
        for (int i = 0; i < 3; i++) vb[i] = R[i] * v0[0] + R[3 + i] * v0[1] + R[6 + i] * v0[2]; /* Rᵀ v0 */
        gb_dyn_start_flight(d, t0, y, vb, d->def.height0 - d->def.length * gb_vec_dot(zb, d->contact.rc));
        d->flight.hop_max = d->def.height0;
    }
    d->last_switch_time = NAN;
    d->memo_valid = 0;
    gb_dyn_current(d)->translate(d, t0, y);
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
    gb_forcing_geff_with_rate(&d->def.forcing, t, &o->geff, &o->geff_rate);
    const int status = gb_dyn_current(d)->observe(d, t, y, o);
    if (status) return status;
    o->orthonormality = orthonormality_of(o->R);
    o->grid_switches = d->grid_switches;
    o->branch_switches = d->branch_switches;
    o->branches_lost = d->branches_lost;
    return GB_OK;
}

int gb_dynamics_start_in(const gb_surface *body, const gb_dynamics_def *def, gb_dynamics_context *context, const double R0[9],
                         const double omega0[3], gb_dynamics **out, double y[GB_STATE_SIZE])
{
    *out = NULL;
    int status = gb_dynamics_create_in(body, def, context, out);
    if (!status) status = gb_dynamics_init_state(*out, 0.0, R0, omega0, y);
    if (status) {
        gb_dynamics_free(*out);
        *out = NULL;
    }
    return status;
}

int gb_dynamics_start(const gb_surface *body, const gb_dynamics_def *def, const double R0[9], const double omega0[3],
                      gb_dynamics **out, double y[GB_STATE_SIZE])
{
    return gb_dynamics_start_in(body, def, NULL, R0, omega0, out, y);
}
