/* gb_dynamics_slips — the jumps of a plane of finite friction (docs/friction.md): a sticking point whose force
 * reaches the cone's edge starts to slip, a slip that stops sticks where the cone holds the force that keeps
 * it stopped (else it slips on), a slipping point's normal force at 0 lifts it, and every impact (a change of
 * contact, a third point, a landing) is Coulomb's (gb_impact_coulomb: Darboux–Keller at one point, Moreau's
 * law with the cone at several), after which the points held and how each moves decide the mode: rolling
 * on one or two points, sliding, at rest, or flight. Every change is booked as the rough plane's are. */
#include "gb_dynamics_internal.h"

#include "gb_error.h"
#include "gb_impact_internal.h"
#include "gb_vec.h"

#include <math.h>
#include <string.h>

/* The centroid's velocity relative to the plane in body axes: sliding, the state's; in flight, the closed
 * form's; rolling (one point, two, at rest), the rolling velocity about the contact continued to y, ω × (G −
 * P), which the mode's energy is made of (the state's is that to the integration's accuracy). */
static int velocity_body(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], double v[3])
{
    double R[9], V[3], zeta;
    if (d->mode != GB_DYN_SLIDING && d->mode != GB_DYN_FLIGHT) {
        double zb[3];
        gb_contact_point p;
        gb_dyn_vertical(y, zb);
        const int status = gb_dyn_point_at(d, zb, &d->contact, &p);
        if (status) return status;
        const double L = d->def.length, gp[3] = {-L * p.rc[0], -L * p.rc[1], -L * p.rc[2]};
        gb_vec_cross(y + GB_STATE_OMEGA, gp, v);
        return GB_OK;
    }
    memcpy(V, y + GB_STATE_VELOCITY, sizeof V);
    if (d->mode == GB_DYN_FLIGHT) gb_dyn_flight_state(d, t, &zeta, V);
    gb_dynamics_rotation(y + GB_STATE_Q, R);
    for (int i = 0; i < 3; i++) v[i] = R[i] * V[0] + R[3 + i] * V[1] + R[6 + i] * V[2];
    return GB_OK;
}

/* The state's velocity set from a body-axes one. */
static void set_velocity(double y[GB_STATE_SIZE], const double v_body[3])
{
    gb_dyn_to_inertial(y, v_body, y + GB_STATE_VELOCITY);
}

/* The unit direction, in inertial axes, opposite the body-axes force f's tangential part (a slip starts
 * against the friction the sticking point needed); 0 where that part is 0. */
static void against(const double y[GB_STATE_SIZE], const double zb[3], const double f[3], double out[3])
{
    const double n = gb_vec_dot(f, zb), t[3] = {f[0] - n * zb[0], f[1] - n * zb[1], f[2] - n * zb[2]};
    const double size = gb_vec_norm(t);
    double unit[3] = {0.0, 0.0, 0.0};
    if (size > 0.0)
        for (int i = 0; i < 3; i++) unit[i] = -t[i] / size;
    gb_dyn_to_inertial(y, unit, out);
}

/* Enter the rolling mode the points all sticking make (one point; two: the crease), the velocity set to the
 * rolling one (the slip left is the located event's rounding). */
static int stick_all(gb_dynamics *d, double t, double y[GB_STATE_SIZE], int count)
{
    if (d->mode == GB_DYN_SLIDING) d->slide.sticks++;
    const int sticks[2] = {1, 1};
    const int status = gb_dyn_hold_velocities(d, y, count, sticks);
    gb_dyn_set_mode(d, count == 2 ? GB_DYN_TWO_POINT : GB_DYN_ONE_POINT, t);
    if (count == 2) d->crease.entries++, d->crease.q_valid = 0;
    return status;
}

/* A change with no impulse (a lift, a lift-off) booked with the body's own velocity: the record of nothing
 * changed about the point rp [m]. */
static void no_impulse(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double rp[3], double v[3],
                       gb_impact_result *r)
{
    gb_dyn_no_impulse(d, y, rp, v, r);
    if (velocity_body(d, t, y, v)) gb_error_clear(); /* the no-impulse record's rolling v stands */
    memcpy(r->v, v, sizeof r->v);
    gb_impact_body body = {d->def.mass, {{0}}};
    memcpy(body.inertia, d->inertia, sizeof body.inertia);
    r->energy_before = r->energy_after = gb_impact_energy(&body, v, r->omega);
}

/* ---------------------------------------------------------------- slip and stick, no impulse */

int gb_dyn_slip_start(gb_dynamics *d, double t, double y[GB_STATE_SIZE])
{
    double zb[3], geff, geff_rate, start[2][3] = {{0}};
    int slides[2] = {1, 0};
    gb_dyn_vertical(y, zb);
    gb_forcing_geff_with_rate(&d->def.forcing, t, &geff, &geff_rate);
    const double m = d->def.mass, *omega = y + GB_STATE_OMEGA;
    if (d->mode == GB_DYN_ONE_POINT) {
        gb_dyn_contact c;
        double w_dot[3], acc[3], F[3];
        int status = gb_dyn_contact_at(d, t, zb, omega, &c);
        if (!status) status = gb_dyn_angular_acceleration(d, geff, zb, omega, &c, w_dot);
        if (status) return status;
        gb_dyn_normal_force(d, geff, zb, omega, w_dot, &c, acc);
        for (int k = 0; k < 3; k++) F[k] = m * (acc[k] + geff * zb[k]);
        against(y, zb, F, start[0]);
        gb_dyn_start_sliding(d, t, y, 1, slides, (const double(*)[3])start);
        return GB_OK;
    }
    /* the crease: the point the cone cannot hold whatever the open split slips, the other sticks; where each
     * could but not both at once, both slip (along the tangential forces of the deepest split) */
    gb_dyn_two_point tp;
    int status = gb_dyn_two_point_eval(d, t, y, &tp, 1);
    if (status) return status;
    int alone;
    gb_dyn_crease_margin(d->def.friction, tp.normal, (const double(*)[3])tp.tangent, tp.u, &alone);
    slides[0] = alone != 2, slides[1] = alone != 1;
    against(y, zb, tp.tangent[0], start[0]);
    against(y, zb, tp.tangent[1], start[1]);
    d->contact2 = tp.q;
    gb_dyn_start_sliding(d, t, y, 2, slides, (const double(*)[3])start);
    return GB_OK;
}

/* A slipping point's slip has stopped (point k): it sticks where the cone holds the force that keeps it
 * stopped, and the body rolls when every point sticks; else it slips on against that force. */
static int slip_stops(gb_dynamics *d, double t, double y[GB_STATE_SIZE], int k)
{
    double zb[3], force[3];
    gb_dyn_vertical(y, zb);
    gb_dyn_friction_point points[2];
    gb_dyn_friction_forces f;
    int status = gb_dyn_sliding_eval(d, t, y, points, &f);
    if (status) return status;
    {
        /* the event is the slip down to the stop's speed (gb_dyn_slip_stop_speed), or turned against its
         * direction at the accepted state: then, its speed well above, a slip that swung by a right angle in a
         * step too long for how fast it turns, which slips on along its new direction. Which of the two the
         * event was is read from the gap's terms at the located state (stop_gap: the slip along its direction
         * against its speed less the stop's): a slip whose speed met the stop's stops, even where the stop's
         * speed jumps just after the located state (as where another point starts to slip). */
        double s[3], w[3];
        gb_dyn_slip_of(y, zb, points[k].r, s);
        const double speed = gb_vec_norm(s);
        gb_dyn_to_inertial(y, s, w);
        const double stop = gb_dyn_slip_stop_speed(d, y, s, f.slip_acc[k]);
        if (gb_vec_dot(w, d->slide.ref[k]) < speed - stop && speed > 2.0 * stop) {
            for (int i = 0; i < 3; i++) s[i] /= speed;
            gb_dyn_to_inertial(y, s, w);
            memcpy(d->slide.ref[k], w, sizeof w);
            return GB_OK;
        }
    }
    const int was[2] = {d->slide.slides[0], d->slide.slides[1]};
    d->slide.slides[k] = 0;
    /* Points that stop together: another slipping point whose slip is within twice its own stop's speed at this
     * state (the band below which a slip is not armed, gb_dyn_sliding_accept) stops with k: a body sliding on an
     * edge, its two ends' slips one slip, whose second event would never come, left "sliding" at a rounding's speed. */
    for (int q = 0; q < d->slide.count; q++) {
        if (q == k || !d->slide.slides[q]) continue;
        double sq[3];
        gb_dyn_slip_of(y, zb, points[q].r, sq);
        if (gb_vec_norm(sq) <= 2.0 * gb_dyn_slip_stop_speed(d, y, sq, f.slip_acc[q])) d->slide.slides[q] = 0;
    }
    int any = 0;
    for (int q = 0; q < d->slide.count; q++) any |= d->slide.slides[q];
    double margin;
    if (!any && d->slide.count == 2) {
        /* both would stick: the crease's forces, their open split taken deepest in the cones */
        gb_dyn_two_point tp;
        int alone;
        status = gb_dyn_two_point_eval(d, t, y, &tp, 1);
        if (status) return status;
        margin = tp.merged ? -1.0 : gb_dyn_crease_margin(d->def.friction, tp.normal, (const double(*)[3])tp.tangent, tp.u, &alone);
        memcpy(force, tp.tangent[k], sizeof force);
    } else if (!any) {
        double geff, geff_rate, w_dot[3], acc[3];
        gb_dyn_contact c;
        gb_forcing_geff_with_rate(&d->def.forcing, t, &geff, &geff_rate);
        status = gb_dyn_contact_at(d, t, zb, y + GB_STATE_OMEGA, &c);
        if (!status) status = gb_dyn_angular_acceleration(d, geff, zb, y + GB_STATE_OMEGA, &c, w_dot);
        if (status) return status;
        margin = gb_dyn_one_point_margin(d, geff, zb, y + GB_STATE_OMEGA, w_dot, &c);
        gb_dyn_normal_force(d, geff, zb, y + GB_STATE_OMEGA, w_dot, &c, acc);
        for (int i = 0; i < 3; i++) force[i] = d->def.mass * (acc[i] + geff * zb[i]);
    } else {
        margin = f.margin[k];
        memcpy(force, f.force[k], sizeof force);
    }
    if (margin >= 0.0) {
        if (any) d->slide.sticks++; /* one of two sticks, the other slips on */
        else return stick_all(d, t, y, d->slide.count);
        return GB_OK;
    }
    /* the cone cannot hold it stopped: it slips on, against the force that would have held it (and a point that
     * stopped with it slips on as it was) */
    for (int q = 0; q < d->slide.count; q++)
        if (q != k) d->slide.slides[q] = was[q];
    d->slide.slides[k] = was[k], d->slide.armed[k] = 0;
    against(y, zb, force, d->slide.start[k]);
    memcpy(d->slide.ref[k], d->slide.start[k], sizeof d->slide.ref[k]);
    return GB_OK;
}

/* ---------------------------------------------------------------- impacts */

/* The lumped impact of the settle rule on a plane of finite friction: both points held at rest in the
 * normal direction, each sticking or sliding by the cone (gb_impact_coulomb_hold). 1 when it stands (found,
 * and the plane pulls at most by the weight's impulse it stands for). */
static int settle(const gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double (*r)[3], int count,
                  int arriving, const double v[3], gb_impact_result *out)
{
    double zb[3];
    gb_dyn_vertical(y, zb);
    gb_impact_body body = {d->def.mass, {{0}}};
    memcpy(body.inertia, d->inertia, sizeof body.inertia);
    if (gb_impact_coulomb_hold(&body, zb, d->def.friction, r, count, v, y + GB_STATE_OMEGA, out)) {
        gb_error_clear();
        return 0;
    }
    if (gb_dyn_plane_pushes(d, t, out, r, count, arriving, 1, v, y + GB_STATE_OMEGA)) {
        gb_error_clear();
        return 0;
    }
    return 1;
}

/* gb_dyn_return_time where the new point q slides after the impact along `slip` (body axes): how soon the
 * lifted point rp [m] falls back, 2 v_n/|a_n| from its normal velocity and acceleration under the sliding
 * mode's forces on q (INFINITY when a_n >= 0 or the forces have no consistent value). */
static double sliding_return_time(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *q,
                                  const double slip[3], const double v[3], const double rp[3])
{
    const double L = d->def.length, *omega = y + GB_STATE_OMEGA, size = gb_vec_norm(slip);
    double zb[3], geff, geff_rate;
    gb_dyn_vertical(y, zb);
    gb_forcing_geff_with_rate(&d->def.forcing, t, &geff, &geff_rate);
    gb_dyn_friction_point point = {.slides = size > 0.0};
    if (gb_dyn_point_rate(d, zb, q, omega, point.rdot)) {
        gb_error_clear();
        return INFINITY;
    }
    for (int k = 0; k < 3; k++) point.r[k] = L * q->rc[k], point.rdot[k] *= L, point.slip[k] = size > 0.0 ? slip[k] / size : 0.0;
    gb_dyn_friction_forces f;
    if (gb_dyn_friction_solve(d, t, geff, zb, omega, &point, 1, &f)) {
        gb_error_clear();
        return INFINITY;
    }
    /* P's material point: a_P = a_G + ω̇ × r_P + ω × (ω × r_P) */
    double g[3], h[3], wr[3];
    gb_vec_cross(f.omega_dot, rp, g);
    gb_vec_cross(omega, rp, wr);
    gb_vec_cross(omega, wr, h);
    double an = 0.0;
    for (int k = 0; k < 3; k++) an += zb[k] * (f.acc[k] + g[k] + h[k]);
    const double vn = gb_vec_dot(zb, v) + gb_vec_dot(zb, wr);
    return an < 0.0 ? 2.0 * fmax(vn, 0.0) / -an : INFINITY;
}

/* A flight that starts with its lowest point at or just below the plane: the next landing is a return
 * below where it is now (the rough law's landing does the same). */
static int flight_allowance(gb_dynamics *d, double t, const double y[GB_STATE_SIZE])
{
    gb_contact_point continued, lower;
    int found;
    const int status = gb_dyn_competitor(d, t, y, &continued, &lower, &found);
    if (status) return status;
    double zeta, v[3];
    gb_dyn_flight_state(d, t, &zeta, v);
    const double depth = -(zeta / d->def.length + (found ? lower.height : continued.height));
    d->gap_allow = fmax(d->gap_allow, fmax(depth, 0.0) + GB_DYN_GAP_TOL);
    return GB_OK;
}

int gb_dyn_friction_impact(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *points, int count,
                           int arriving, gb_dynamics_impact_kind kind, int located)
{
    const double L = d->def.length, *omega = y + GB_STATE_OMEGA;
    double zb[3], r[3][3], v[3], zeta = y[GB_STATE_ZETA], V[3];
    gb_dyn_vertical(y, zb);
    for (int k = 0; k < count; k++)
        for (int i = 0; i < 3; i++) r[k][i] = L * points[k].rc[i];
    int status = velocity_body(d, t, y, v);
    if (status) return status;
    if (d->mode == GB_DYN_FLIGHT) gb_dyn_flight_state(d, t, &zeta, V);
    double wq[3];
    gb_vec_cross(omega, r[arriving], wq);
    const double approach = -(gb_vec_dot(zb, v) + gb_vec_dot(zb, wq));
    const double e = kind == GB_DYNAMICS_IMPACT_THIRD ? 0.0 : gb_dyn_restitution_at(d, t, approach);
    gb_impact_body body = {d->def.mass, {{0}}};
    memcpy(body.inertia, d->inertia, sizeof body.inertia);
    gb_impact_result res;
    if (gb_impact_coulomb(&body, zb, e, d->def.friction, (const double(*)[3])r, count, v, omega, &res))
        return gb_error_set(GB_ENUMERIC, "impact at t = %.9g on a plane of friction mu = %g: %s", t, d->def.friction,
                            gb_error_message());
    int held = 0, settled = 0;
    for (int k = 0; k < count; k++) held += res.holds[k];
    double back = INFINITY;
    if (count >= 2 && e == 0.0 && held == 1 && res.holds[arriving]) {
        /* the settle rule: a point of the old ones falling back within the settle time is held with the new */
        double yafter[GB_STATE_SIZE];
        memcpy(yafter, y, sizeof yafter);
        memcpy(yafter + GB_STATE_OMEGA, res.omega, sizeof res.omega);
        for (int k = 0; k < count; k++)
            if (k != arriving)
                back = fmin(back, res.slides[arriving] ? sliding_return_time(d, t, yafter, &points[arriving], res.slip_after[arriving], res.v, r[k])
                                                       : gb_dyn_return_time(d, t, yafter, &points[arriving], res.v, r[k]));
        gb_impact_result lumped;
        if (back < d->settle_time && settle(d, t, y, (const double(*)[3])r, count, arriving, v, &lumped)) res = lumped, settled = 1;
        held = 0;
        for (int k = 0; k < count; k++) held += res.holds[k];
    }
    status = gb_dyn_plane_pushes(d, t, &res, (const double(*)[3])r, count, arriving, settled, v, omega);
    if (status) return status;
    const int old = arriving ? 0 : (count > 1 ? 1 : 0);
    gb_dynamics_impact rec = {.t = t, .located = located, .kind = kind, .contacts_after = held, .settled = settled,
                              .return_time = back, .rebound = e > 0.0};
    gb_dyn_record(&rec, y, r[old], r[arriving], v, &res, arriving, count > 1 ? old : -1);
    memcpy(rec.slip_before, res.slip_before[arriving], sizeof rec.slip_before);
    memcpy(rec.slip_after, res.slip_after[arriving], sizeof rec.slip_after);
    const double pn = res.normal_impulse[arriving];
    for (int i = 0; i < 3; i++) rec.tangential[i] = res.impulse[arriving][i] - pn * zb[i];
    rec.slides_after = res.slides[arriving];
    set_velocity(y, res.v);
    if (kind == GB_DYNAMICS_IMPACT_LANDING && held)
        rec.potential_jump = -d->def.mass * gb_forcing_geff(&d->def.forcing, t) * (zeta + gb_vec_dot(zb, r[arriving]));
    /* the mode the points that stay on the plane make: held, and not leaving it at a rebound (u_n⁺ > 0) */
    int which[3], n = 0, sliding = 0;
    const double speed = gb_vec_norm(v) + L * gb_vec_norm(rec.omega_before) + 1e-300;
    for (int k = 0; k < count; k++) {
        double u[3];
        gb_vec_cross(res.omega, r[k], u);
        if (res.holds[k] && gb_vec_dot(zb, res.v) + gb_vec_dot(zb, u) <= 1e-9 * speed) which[n++] = k, sliding += res.slides[k];
    }
    if (e > 0.0 && n < held) rec.kind = kind == GB_DYNAMICS_IMPACT_LANDING ? kind : GB_DYNAMICS_IMPACT_BOUNCE;
    rec.contacts_after = n;
    if (!n) {
        /* no point stays: flight from here, the centroid at its velocity after; the flight goes on from where
         * the body is, its lowest point up to the landing tolerance below that (a point that left the plane
         * at a vanishing speed, as at the end of a crease, is not landed again at once) */
        gb_dyn_set_contact(d, &points[arriving]);
        gb_dyn_start_flight(d, t, y, res.v, kind == GB_DYNAMICS_IMPACT_LANDING ? zeta : -gb_vec_dot(zb, r[arriving]));
        status = flight_allowance(d, t, y);
        if (status) return status;
        return gb_dyn_book(d, &rec);
    }
    if (n == 3) {
        if (sliding)
            return gb_error_set_limit(GB_ENUMERIC, "impact at t = %.9g: the body slides on three points after it, which this "
                                      "model does not follow", t);
        gb_dyn_set_mode(d, GB_DYN_REST, t);
        gb_dyn_set_contact(d, &points[arriving]);
        memset(y + GB_STATE_OMEGA, 0, 3 * sizeof *y);
        memset(y + GB_STATE_VELOCITY, 0, 3 * sizeof *y);
        return gb_dyn_book(d, &rec);
    }
    gb_dyn_set_contact(d, &points[which[0]]);
    if (n == 2) d->contact2 = points[which[1]], d->crease.q_valid = 0;
    if (!sliding) {
        if (d->mode == GB_DYN_SLIDING) d->slide.sticks++;
        gb_dyn_set_mode(d, n == 2 ? GB_DYN_TWO_POINT : GB_DYN_ONE_POINT, t);
        if (n == 2) d->crease.entries++;
    } else {
        int slides[2] = {res.slides[which[0]], n == 2 ? res.slides[which[1]] : 0};
        double start[2][3] = {{0}};
        for (int q = 0; q < n; q++) {
            const double *s = res.slip_after[which[q]], size = gb_vec_norm(s);
            double unit[3] = {0, 0, 0};
            if (size > 0.0)
                for (int i = 0; i < 3; i++) unit[i] = s[i] / size;
            gb_dyn_to_inertial(y, unit, start[q]);
        }
        gb_dyn_start_sliding(d, t, y, n, slides, (const double(*)[3])start);
    }
    return gb_dyn_book(d, &rec);
}

/* ---------------------------------------------------------------- the sliding mode's events */

int gb_dyn_sliding_event(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    const int k = d->event_point, event = d->event;
    d->event = GB_DYN_EVENT_NONE;
    d->memo_valid = 0;
    d->last_valid = 0;
    if (event == GB_DYN_EVENT_STICK) return slip_stops(d, t, y, k);
    if (event == GB_DYN_EVENT_SLIP) {
        double zb[3];
        gb_dyn_friction_point points[2];
        gb_dyn_friction_forces f;
        const int status = gb_dyn_sliding_eval(d, t, y, points, &f);
        if (status) return status;
        gb_dyn_vertical(y, zb);
        d->slide.slides[k] = 1, d->slide.slips++, d->slide.armed[k] = 0;
        against(y, zb, f.force[k], d->slide.start[k]);
        memcpy(d->slide.ref[k], d->slide.start[k], sizeof d->slide.ref[k]);
        return GB_OK;
    }
    if (event == GB_DYN_EVENT_LIFT) { /* one of two points leaves: the other goes on as it was */
        const double L = d->def.length;
        double zb[3];
        gb_dyn_vertical(y, zb);
        gb_contact_point now[2]; /* the two points at this state */
        int status = gb_dyn_point_at(d, zb, &d->contact, &now[0]);
        if (!status) status = gb_dyn_second_point(d, zb, &now[1]);
        if (status) return status;
        const gb_contact_point *left = &now[1 - k], *lifted = &now[k];
        const double rp[3] = {L * lifted->rc[0], L * lifted->rc[1], L * lifted->rc[2]};
        gb_impact_result none;
        double v[3];
        no_impulse(d, t, y, rp, v, &none);
        gb_dynamics_impact rec = {.t = t, .located = 1, .kind = GB_DYNAMICS_IMPACT_LIFT, .contacts_after = 1,
                                  .return_time = INFINITY};
        gb_dyn_record(&rec, y, rp, (const double[3]){L * left->rc[0], L * left->rc[1], L * left->rc[2]}, v, &none, 0, -1);
        const int slides = d->slide.slides[1 - k];
        gb_dyn_set_contact(d, left);
        d->slide.count = 1, d->slide.slides[0] = slides, d->slide.slides[1] = 0;
        memcpy(d->slide.start[0], d->slide.start[1 - k], sizeof d->slide.start[0]);
        memcpy(d->slide.ref[0], d->slide.ref[1 - k], sizeof d->slide.ref[0]);
        d->slide.armed[0] = d->slide.armed[1 - k], d->slide.armed[1] = 0;
        status = slides ? GB_OK : stick_all(d, t, y, 1);
        return status ? status : gb_dyn_book(d, &rec);
    }
    if (event == GB_DYN_EVENT_LIFT_OFF) { /* the last point leaves: flight, with the velocity the body has */
        const double L = d->def.length;
        double zb[3], v[3];
        gb_dyn_vertical(y, zb);
        gb_contact_point p;
        const int status = gb_dyn_point_at(d, zb, &d->contact, &p);
        if (status) return status;
        gb_dyn_set_contact(d, &p);
        const double rp[3] = {L * p.rc[0], L * p.rc[1], L * p.rc[2]};
        gb_impact_result none;
        no_impulse(d, t, y, rp, v, &none);
        gb_dynamics_impact rec = {.t = t, .located = 1, .kind = GB_DYNAMICS_IMPACT_LIFT_OFF, .contacts_after = 0,
                                  .return_time = INFINITY};
        gb_dyn_record(&rec, y, rp, rp, v, &none, 0, -1);
        gb_dyn_start_flight(d, t, y, v, -gb_vec_dot(zb, rp));
        return gb_dyn_book(d, &rec);
    }
    /* a new point: a switch (from one point) or a third point (from two) */
    double zb[3];
    gb_dyn_vertical(y, zb);
    gb_contact_point pts[3];
    int status = gb_dyn_point_at(d, zb, &d->contact, &pts[0]), count = 2;
    if (!status && d->slide.count == 2) status = gb_dyn_second_point(d, zb, &pts[1]), count = 3;
    if (status) return status;
    pts[count - 1] = *branch;
    if (d->def.contact == GB_CONTACT_MODEL_CONTINUOUS) d->branch_switches++;
    else d->grid_switches++;
    d->last_switch_time = t;
    return gb_dyn_friction_impact(d, t, y, pts, count, count - 1,
                                  count == 3 ? GB_DYNAMICS_IMPACT_THIRD : GB_DYNAMICS_IMPACT_SWITCH, 1);
}
