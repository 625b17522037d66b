/* gb_dynamics_rolling — the mode "rolling on one point" (paper §5, eqs 40–45): the body turns about the
 * contact point with the plane, by eq 44 as written or by the rolling equation (gb_dynamics.h); the
 * paper's held law has this mode alone. Its events are in gb_dynamics_events.c, its jumps in
 * gb_dynamics_jumps.c. */
#include "gb_dynamics_internal.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <string.h>

/* I_P = I_C − m [r_c]×[r_c]× = I_C + m (|r_c|² I − r_c r_cᵀ) (eq 40). */
void gb_dyn_inertia_about(const gb_dynamics *d, const double rc[3], double IP[3][3])
{
    const double m = d->def.mass, r2 = gb_vec_dot(rc, rc);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) IP[i][j] = d->inertia[i][j] + m * ((i == j) * r2 - rc[i] * rc[j]);
}

/* ω̇ from eq 44 (paper) or the rolling equation, for the contact c and g_eff at the time. */
int gb_dyn_angular_acceleration(const gb_dynamics *d, double geff, const double zb[3], const double omega[3],
                                const gb_dyn_contact *c, double omega_dot[3])
{
    const double m = d->def.mass;
    double IP[3][3], IPw[3], gyro[3], tau[3], rhs[3], tmp[3], tmp2[3];
    gb_dyn_inertia_about(d, c->rc, IP);
    gb_dyn_mat_vec(IP, omega, IPw);
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
    return gb_dyn_solve3(IP, rhs, omega_dot);
}

/* The centroid's acceleration relative to the support under rolling kinematics (body frame), a_G = ω ×
 * (r_c × ω) + ṙ_c × ω + r_c × ω̇, into acc, and the normal force N = m (g_eff + z_b·a_G). */
double gb_dyn_normal_force(const gb_dynamics *d, double geff, const double zb[3], const double omega[3],
                              const double omega_dot[3], const gb_dyn_contact *c, double acc[3])
{
    double a[3], b[3], e[3], f[3];
    gb_vec_cross(c->rc, omega, a);
    gb_vec_cross(omega, a, b);
    gb_vec_cross(c->rc_dot, omega, e);
    gb_vec_cross(c->rc, omega_dot, f);
    for (int k = 0; k < 3; k++) acc[k] = b[k] + e[k] + f[k];
    return d->def.mass * (geff + gb_vec_dot(acc, zb));
}

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

void gb_dyn_observe_on_plane(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_dyn_contact *c, int contacts,
                             gb_dynamics_observables *o)
{
    (void)t;
    const double m = d->def.mass;
    memcpy(o->rc, c->rc, sizeof o->rc);
    memcpy(o->rc_dot, c->rc_dot, sizeof o->rc_dot);
    o->index = c->index;
    o->height = gb_vec_dot(o->zb, c->rc);
    o->zeta = -o->height;
    double IP[3][3], IPw[3], tau_g[3];
    gb_dyn_inertia_about(d, c->rc, IP);
    gb_dyn_mat_vec(IP, o->omega, IPw);
    o->kinetic = 0.5 * gb_vec_dot(o->omega, IPw);
    o->potential = m * o->geff * o->zeta;
    o->energy = o->kinetic + o->potential;
    gb_vec_cross(c->rc, o->zb, tau_g);
    o->power_gravity = m * o->geff * gb_vec_dot(o->omega, tau_g);
    o->power_damping = -d->def.damping * gb_vec_dot(o->omega, o->omega);
    o->work = y[GB_STATE_WORK];
    o->residual = o->energy - d->energy0 - o->work;
    if (d->law->impacts) o->residual += d->impact_loss; /* the ledger */
    o->friction_work = y[GB_STATE_FRICTION];
    if (d->law->slips) o->residual -= o->friction_work; /* and friction's part of L */
    double acc[3];
    o->normal_force = gb_dyn_normal_force(d, o->geff, o->zb, o->omega, o->omega_dot, c, acc);
    const double vertical = gb_vec_dot(acc, o->zb);
    double horizontal[3];
    for (int k = 0; k < 3; k++) horizontal[k] = acc[k] - vertical * o->zb[k];
    o->friction_needed = o->normal_force > 0.0 ? m * gb_vec_norm(horizontal) / o->normal_force : INFINITY;
    o->contacts = contacts;
    double vb[3];
    gb_vec_cross(o->omega, (const double[3]){-c->rc[0], -c->rc[1], -c->rc[2]}, vb); /* v_G = ω × (G − P) */
    for (int i = 0; i < 3; i++) o->velocity[i] = o->R[3 * i] * vb[0] + o->R[3 * i + 1] * vb[1] + o->R[3 * i + 2] * vb[2];
    o->normal_forces[0] = o->normal_force;
}

int gb_dyn_one_point_observe(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_observables *o)
{
    gb_dyn_contact c;
    int status = gb_dyn_contact_at(d, t, o->zb, o->omega, &c);
    if (!status) status = gb_dyn_angular_acceleration(d, o->geff, o->zb, o->omega, &c, o->omega_dot);
    if (!status) gb_dyn_observe_on_plane(d, t, y, &c, 1, o);
    return status;
}

void gb_dyn_translate_on_plane(const gb_dynamics *d, double t, double y[GB_STATE_SIZE])
{
    (void)t;
    double R[9], zb[3], rc[3], vb[3];
    gb_dynamics_rotation(y + GB_STATE_Q, R);
    zb[0] = R[6], zb[1] = R[7], zb[2] = R[8];
    gb_contact_point p = d->contact;
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS && !gb_dyn_pivots(d)) gb_dyn_grid_point(d, d->index, zb, &p);
    for (int k = 0; k < 3; k++) rc[k] = d->def.length * p.rc[k];
    y[GB_STATE_ZETA] = -gb_vec_dot(zb, rc);
    gb_vec_cross(y + GB_STATE_OMEGA, (const double[3]){-rc[0], -rc[1], -rc[2]}, vb); /* ω × (G − P) */
    for (int i = 0; i < 3; i++) y[GB_STATE_VELOCITY + i] = R[3 * i] * vb[0] + R[3 * i + 1] * vb[1] + R[3 * i + 2] * vb[2];
}
