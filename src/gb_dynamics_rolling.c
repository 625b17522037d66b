/* gb_dynamics_rolling — the mode "rolling on one point" (paper §5, eqs 40–45): the body turns about the
 * contact point with the plane, by eq 44 as written or by the rolling equation (gb_dynamics.h); the
 * paper's held law has this mode alone. Its events are in gb_dynamics_events.c, its jumps in
 * gb_dynamics_jumps.c. */
#include "gb_dynamics_internal.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <string.h>

/* Rolling on the accepted contact alone at state y: its normal force N = m (g_eff + z_b·a_G). */
int gb_dyn_one_point_normal(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], double *n)
{
    double zb[3], geff, geff_rate, w_dot[3], acc[3];
    gb_dyn_contact c;
    gb_dyn_vertical_of_quaternion(y + GB_STATE_Q, zb);
    gb_forcing_geff_with_rate(&d->def.forcing, t, &geff, &geff_rate);
    int status = gb_dyn_contact_at(d, t, zb, y + GB_STATE_OMEGA, &c);
    if (!status) status = gb_dyn_angular_acceleration(d, geff, zb, y + GB_STATE_OMEGA, &c, w_dot);
    *n = status ? NAN : gb_dyn_normal_force(d, geff, zb, y + GB_STATE_OMEGA, w_dot, &c, acc);
    return status;
}

/* ω̇ and ζ = −z_b·r_c on the contact (eqs 37, 44). */
int gb_dyn_one_point_field(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double omega[3], const double zb[3],
                           double geff, double omega_dot[3], double *zeta, gb_dyn_rates *rates)
{
    gb_dyn_contact c;
    int status = gb_dyn_contact_at(d, t, zb, omega, &c);
    if (!status) status = gb_dyn_angular_acceleration(d, geff, zb, omega, &c, omega_dot);
    if (!status) *zeta = -gb_vec_dot(zb, c.rc);
    if (!status && rates) { /* the centroid's acceleration under rolling, in inertial axes */
        double acc[3];
        gb_dyn_normal_force(d, geff, zb, omega, omega_dot, &c, acc);
        gb_dyn_to_inertial(y, acc, rates->acc);
    }
    return status;
}

/* After an accepted step: the held law's grid takes the lowest node and counts its changes (the paper's
 * rule); otherwise the contact is continued and checked by the certificate, a lower minimum becoming the
 * contact (a switch at the step's end, which a law with impacts must have located inside the step). */
int gb_dyn_one_point_accept(gb_dynamics *d, double t, double y[GB_STATE_SIZE])
{
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS && !gb_dyn_pivots(d)) {
        double zb[3];
        gb_dyn_vertical(y, zb);
        gb_dyn_contact c;
        const int status = gb_dyn_contact_at(d, t, zb, y + GB_STATE_OMEGA, &c);
        if (status) return status;
        if (c.index != d->index) d->grid_switches++, d->last_switch_time = t;
        d->index = c.index;
        return GB_OK;
    }
    gb_contact_point continued, other;
    int found;
    int status = gb_dyn_competitor(d, t, y, &continued, &other, &found);
    /* Under a law with impacts every contact change is located inside its step; one found here is a second
     * change inside one step: the body chatters between two points, coming to rest on both. */
    if (!status && found && d->law->several_events_per_step)
        status = gb_error_set(GB_ENUMERIC, "unilateral contact at t = %.9g: a change of contact at the step's end that the "
                              "step's event location did not find (%zu impacts so far)", t, d->impacts);
    /* (N < 0 at the step's end was a lift-off event, located by gb_dynamics_switch_pending) */
    if (status) return status;
    if (d->lift_allow > 0.0) {
        /* has the lifted point's gap opened (or its minimum gone)? */
        double zb[3];
        gb_contact_point q;
        gb_dyn_vertical(y, zb);
        if (gb_dyn_point_at(d, zb, &d->lifted, &q) || !q.is_minimum || q.height > continued.height) d->lift_allow = 0.0;
        else d->lifted = q;
        gb_error_clear();
    }
    gb_dyn_set_contact(d, found ? &other : &continued);
    d->memo_valid = 0; /* the accepted contact changed */
    if (found) d->last_valid = 0; /* the last contact found is on the branch left */
    d->branch_switches += found;
    if (found) d->last_switch_time = t;
    return gb_dyn_remember_rate(d, t, y);
}

int gb_dyn_one_point_observe(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_observables *o)
{
    gb_dyn_contact c;
    int status = gb_dyn_contact_at(d, t, o->zb, o->omega, &c);
    if (!status) status = gb_dyn_angular_acceleration(d, o->geff, o->zb, o->omega, &c, o->omega_dot);
    if (!status) gb_dyn_observe_on_plane(d, t, y, &c, 1, o);
    return status;
}

