/* gb_dynamics_on_plane — the kinematics of a body on the plane, which every mode on it shares (rolling on one
 * or two points, at rest, sliding), below them: the inertia about a contact (eq 40), the angular acceleration by
 * eq 44 or the rolling equation, the centroid's acceleration and the normal force, the translation a contact
 * fixes, and the observables every mode on the plane reports. */
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
