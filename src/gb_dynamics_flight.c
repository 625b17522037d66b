/* gb_dynamics_flight — the mode "flight" (docs/impact.md): where the last contact's normal force reaches 0
 * the body leaves the plane; its centroid moves under g_eff in closed form, the body turns torque-free but
 * for the damping torque −c ω (eq 42, kept in flight), and `contact` is its lowest point, continued and
 * certified as a contact is. It ends where that point reaches the plane (gb_dynamics_events.c, the
 * landing in gb_dynamics_jumps.c). */
#include "gb_dynamics_internal.h"

#include "gb_dynamics_protocol_internal.h"
#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <string.h>

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
void gb_dyn_flight_state(const gb_dynamics *d, double t, double *zeta, double v[3])
{
    double once, twice;
    geff_integrals(&d->def.forcing, d->flight.t0, t, &once, &twice);
    *zeta = d->flight.zeta0 + d->flight.v0[2] * (t - d->flight.t0) - twice;
    v[0] = d->flight.v0[0], v[1] = d->flight.v0[1], v[2] = d->flight.v0[2] - once;
}

/* Torque-free but for the damping torque −c ω (eq 42, which the scene keeps in flight): I_G ω̇ + ω × I_G ω = −c ω. */
int gb_dyn_free_acceleration(const gb_dynamics *d, const double omega[3], double omega_dot[3])
{
    double I[3][3], Iw[3], gyro[3], rhs[3];
    memcpy(I, d->inertia, sizeof I);
    gb_dyn_mat_vec(I, omega, Iw);
    gb_vec_cross(omega, Iw, gyro);
    for (int k = 0; k < 3; k++) rhs[k] = -gyro[k] - d->def.damping * omega[k];
    return gb_dyn_solve3(I, rhs, omega_dot);
}

/* The body leaves the plane (or bounces) at time t: its centroid at height zeta above the plane, moving
 * with v_body (body axes) relative to it. */
void gb_dyn_start_flight(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double v_body[3], double zeta)
{
    d->gap_allow = GB_DYN_GAP_TOL;
    double R[9];
    gb_dynamics_rotation(y + GB_STATE_Q, R);
    for (int i = 0; i < 3; i++) d->flight.v0[i] = R[3 * i] * v_body[0] + R[3 * i + 1] * v_body[1] + R[3 * i + 2] * v_body[2];
    d->flight.t0 = t;
    d->flight.zeta0 = zeta;
    gb_dyn_set_mode(d, GB_DYN_FLIGHT, t);
}

/* The centroid's motion is in closed form; only the turning is integrated. */
int gb_dyn_flight_field(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double omega[3], const double zb[3],
                        double geff, double omega_dot[3], double *zeta, gb_dyn_rates *rates)
{
    (void)y, (void)zb;
    const int status = gb_dyn_free_acceleration(d, omega, omega_dot);
    if (status) return status;
    double v[3];
    gb_dyn_flight_state(d, t, zeta, v);
    if (rates) rates->acc[0] = rates->acc[1] = 0.0, rates->acc[2] = -geff; /* the weight alone, in the plane's frame */
    return GB_OK;
}

/* The lowest point: continued, certified, and relabelled when a lower minimum takes over (no impact). */
int gb_dyn_flight_accept(gb_dynamics *d, double t, double y[GB_STATE_SIZE])
{
    gb_contact_point continued, other;
    int found;
    int status = gb_dyn_competitor(d, t, y, &continued, &other, &found);
    if (status) return status;
    gb_dyn_set_contact(d, found ? &other : &continued);
    d->memo_valid = 0;
    if (found) d->last_valid = 0;
    double zeta, v[3];
    gb_dyn_flight_state(d, t, &zeta, v);
    const double clearance = zeta + d->def.length * d->contact.height;
    if (clearance > 0.0) d->gap_allow = GB_DYN_GAP_TOL; /* the gap has opened */
    if (clearance < -d->def.length * d->gap_allow)
        return gb_error_set(GB_ENUMERIC, "flight at t = %.9g: the lowest point is %.3g m below the plane, a landing "
                            "that the step's event location did not find", t, -clearance);
    d->flight.hop_max = fmax(d->flight.hop_max, clearance);
    return gb_dyn_remember_rate(d, t, y);
}

/* The lowest point for the clearance; no contact force. */
int gb_dyn_flight_observe(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_observables *o)
{
    gb_dyn_contact c;
    int status = gb_dyn_contact_at(d, t, o->zb, o->omega, &c);
    if (!status) status = gb_dyn_free_acceleration(d, o->omega, o->omega_dot);
    if (status) return status;
    gb_dyn_flight_state(d, t, &o->zeta, o->velocity);
    memcpy(o->rc, c.rc, sizeof o->rc);
    memcpy(o->rc_dot, c.rc_dot, sizeof o->rc_dot);
    o->index = c.index;
    o->height = gb_vec_dot(o->zb, c.rc);
    o->clearance = o->zeta + o->height;
    gb_dyn_observe_free_energy(d, y, o);
    o->contacts = 0;
    return GB_OK;
}

void gb_dynamics_flight_stats(const gb_dynamics *d, double t, gb_dynamics_flight_summary *out)
{
    const int flying = d->mode == GB_DYN_FLIGHT;
    out->time = gb_dyn_mode_time(d, GB_DYN_FLIGHT, t);
    out->lift_offs = d->flight.lift_offs;
    out->landings = d->flight.landings;
    out->bounces = d->flight.bounces;
    out->flying_on = d->flight.flying_on;
    out->hop_max = d->flight.hop_max;
    out->flying = flying;
}

int gb_dynamics_flight_displace(gb_dynamics *d, double t, double dzeta, const double dv[3])
{
    if (d->mode != GB_DYN_FLIGHT) return gb_error_set(GB_EINVAL, "the body is not in flight at t = %.9g", t);
    double zeta, v[3];
    gb_dyn_flight_state(d, t, &zeta, v);
    d->flight.t0 = t;
    d->flight.zeta0 = zeta + dzeta;
    for (int k = 0; k < 3; k++) d->flight.v0[k] = v[k] + dv[k];
    d->memo_valid = 0;
    return GB_OK;
}

/* The closed form of the flight's start (gb_dyn_flight_state). */
void gb_dyn_flight_translate(const gb_dynamics *d, double t, double y[GB_STATE_SIZE])
{
    gb_dyn_flight_state(d, t, y + GB_STATE_ZETA, y + GB_STATE_VELOCITY);
}
