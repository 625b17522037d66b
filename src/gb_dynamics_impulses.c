/* gb_dynamics_impulses — what the jumps of every mode share about an impulse, below the files that make the jumps
 * (gb_dynamics_jumps.c, _slips.c, _faces.c): Newton's restitution with the end to bouncing, the check that the plane
 * only pushes, and how soon a point that lifts at an impact falls back (the settle rule's return time). */
#include "gb_dynamics_internal.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <string.h>

/* Newton's restitution at a point approaching the plane with normal speed `approach` (> 0) at time t,
 * and the end to bouncing: a rebound e·approach that would fall back within settle_time under g_eff
 * (2 e approach / g_eff < settle_time) is taken as plastic, so that a bounce sequence ends in finite time. */
double gb_dyn_restitution_at(const gb_dynamics *d, double t, double approach)
{
    const double e = d->def.restitution;
    if (e == 0.0) return 0.0;
    const double geff = gb_forcing_geff(&d->def.forcing, t);
    return e * approach < 0.5 * fmax(geff, 0.0) * d->settle_time ? 0.0 : e;
}

/* The plane can only push. The normal impulse at every point of an impact is at least −(rounding: 1e-9
 * of the momentum m (|v_G| + |ω| ℓ) the impact acts on, ℓ the farthest point); of an impact the settle rule
 * lumped (`settled`), the points it holds that were already on the plane may pull by the weight's impulse
 * over the return the rule removes, at most m g_max settle_time (g_max the largest g_eff; the Table 1 runs
 * pull by at most 0.4 of it). Beyond, the plane would have to pull: GB_ENUMERIC, "the plane cannot absorb
 * the impact". The new point is `arriving` (its impulse is never a pull). */
int gb_dyn_pulling_point(const gb_dynamics *d, const gb_impact_result *r, const double (*points)[3], int count,
                         int arriving, int settled, const double v_before[3], const double omega_before[3], double *allowed)
{
    const gb_forcing *f = &d->def.forcing;
    double reach = 0.0;
    for (int k = 0; k < count; k++) reach = fmax(reach, gb_vec_norm(points[k]));
    const double m = d->def.mass, rounding = 1e-9 * m * (gb_vec_norm(v_before) + gb_vec_norm(omega_before) * reach);
    const double lumped = settled ? m * (f->g + fabs(f->a1) + fabs(f->a2)) * d->settle_time : 0.0;
    for (int k = 0; k < count; k++) {
        *allowed = rounding + (k == arriving ? 0.0 : lumped);
        if (r->normal_impulse[k] < -*allowed) return k;
    }
    return -1;
}

int gb_dyn_plane_pushes(const gb_dynamics *d, double t, const gb_impact_result *r, const double (*points)[3], int count,
                        int arriving, int settled, const double v_before[3], const double omega_before[3])
{
    double allowed;
    const int k = gb_dyn_pulling_point(d, r, points, count, arriving, settled, v_before, omega_before, &allowed);
    if (k < 0) return GB_OK;
    return gb_error_set(GB_ENUMERIC, "unilateral contact at t = %.9g: the plane cannot absorb the impact: it would have to "
                        "pull with a normal impulse of %.3g N s at point (%.6g, %.6g, %.6g) m (allowed: pushes, or a pull of "
                        "at most %.3g N s where the settle rule holds a point already on the plane) (the body moves at %.3g "
                        "m/s and turns at %.3g rad/s)", t, r->normal_impulse[k], points[k][0], points[k][1], points[k][2],
                        allowed, gb_vec_norm(v_before), gb_vec_norm(omega_before));
}

/* After an impact at which P lifts and the body rolls on Q with ω (y): how soon P falls back, 2 v_n/|a_n|
 * from P's normal velocity and acceleration under the rolling equation about Q (INFINITY when a_n >= 0). */
double gb_dyn_return_time(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *q,
                          const double v[3], const double rp[3])
{
    const double L = d->def.length, *omega = y + GB_STATE_OMEGA;
    double zb[3], geff, geff_rate, w_dot[3];
    gb_dyn_vertical(y, zb);
    gb_forcing_geff_with_rate(&d->def.forcing, t, &geff, &geff_rate);
    gb_dyn_contact c;
    memset(&c, 0, sizeof c);
    if (gb_dyn_point_rate(d, zb, q, omega, c.rc_dot)) return INFINITY;
    for (int k = 0; k < 3; k++) c.rc[k] = L * q->rc[k], c.rc_dot[k] *= L;
    if (gb_dyn_angular_acceleration(d, geff, zb, omega, &c, w_dot)) {
        gb_error_clear();
        return INFINITY;
    }
    /* a_G rolling about Q, then P's material point: a_P = a_G + ω̇ × r_P + ω × (ω × r_P) */
    double acc[3], g[3], h[3], wr[3];
    gb_dyn_normal_force(d, geff, zb, omega, w_dot, &c, acc);
    gb_vec_cross(w_dot, rp, g);
    gb_vec_cross(omega, rp, wr);
    gb_vec_cross(omega, wr, h);
    double an = 0.0, vn = gb_vec_dot(zb, v) + gb_vec_dot(zb, wr);
    for (int k = 0; k < 3; k++) an += zb[k] * (acc[k] + g[k] + h[k]);
    return an < 0.0 ? 2.0 * fmax(vn, 0.0) / -an : INFINITY;
}
