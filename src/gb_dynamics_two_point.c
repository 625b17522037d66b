/* gb_dynamics_two_point — the mode "rolling on two points" (docs/impact.md): the plane is tangent to the
 * body at P and Q, so ω lies along PQ and the vertical moves along the crease of the support function
 * where two minima of height tie. One degree of freedom, σ = ω·u, by the power balance; both normal
 * forces from Newton–Euler. It ends at a normal force reaching 0, a third point reaching the plane
 * (gb_dynamics_events.c, gb_dynamics_jumps.c) or the end of the crease (here, at an accepted step). */
#include "gb_dynamics_internal.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <string.h>

/* Q of the two-point mode at vertical zb: Newton (continuous contact) from the last Q found since the
 * accepted state moved by its sensitivity (eq 70), as P is (gb_dyn_contact_at); then Q's sensitivity for its rate
 * and the next start. A grid node as it is. */
int gb_dyn_second_point(gb_dynamics *d, const double zb[3], gb_contact_point *q)
{
    if (d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) return gb_dyn_point_at(d, zb, &d->contact2, q);
    double unit[3], start[2] = {d->contact2.phi, d->contact2.theta};
    int status = gb_contact_unit_vertical(zb, unit);
    if (status) return status;
    if (d->crease.q_valid) {
        const double step[3] = {unit[0] - d->crease.q_zb[0], unit[1] - d->crease.q_zb[1], unit[2] - d->crease.q_zb[2]};
        gb_contact_chart_offset(&d->crease.q_last, gb_vec_dot(d->crease.q_dq[0], step), gb_vec_dot(d->crease.q_dq[1], step), &start[0],
                                &start[1]);
    }
    status = gb_contact_refine(&d->surface, unit, start[0], start[1], &d->refine, q);
    if (status || !q->is_minimum) return status;
    d->crease.q_valid = gb_contact_sensitivity(&d->surface, unit, q, d->crease.q_dq) == GB_OK;
    memcpy(d->crease.q_zb, unit, sizeof d->crease.q_zb);
    d->crease.q_last = *q;
    return GB_OK;
}

/* The mode at state y: the points, σ and ω̇; with `forces`, the normal forces, the friction they need and
 * the balance too (events and observables need them; the vector field does not). */
int gb_dyn_two_point_eval(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dyn_two_point *tp, int forces)
{
    const double L = d->def.length, m = d->def.mass, c = d->def.damping;
    const double *omega = y + GB_STATE_OMEGA;
    double zb[3];
    gb_dyn_vertical(y, zb);
    const size_t lost = d->branches_lost;
    int status = gb_dyn_contact_at(d, t, zb, omega, &tp->p);
    if (!status && d->branches_lost != lost)
        status = gb_error_set_limit(GB_ENUMERIC, "two-point contact at t = %.9g: P has no minimum of height left (a fold)", t);
    if (!status) status = gb_dyn_second_point(d, zb, &tp->q);
    if (status) return status;
    double dvec[3];
    for (int k = 0; k < 3; k++) tp->rp[k] = L * tp->p.point.rc[k], tp->rq[k] = L * tp->q.rc[k], dvec[k] = tp->rp[k] - tp->rq[k];
    tp->dist = gb_vec_norm(dvec);
    /* The end of a crease: Q's minimum of height merges with P's, or vanishes in a fold (Newton from Q ends on
     * a point that is not a minimum). The state is the body rolling on P alone, with no jump. */
    tp->merged = !tp->q.is_minimum || !(tp->dist > 1e-9 * L);
    if (tp->merged) return GB_OK;
    for (int k = 0; k < 3; k++) tp->u[k] = dvec[k] / tp->dist;
    const double *u = tp->u;
    tp->sigma = gb_vec_dot(omega, u);
    /* ṙ_P, ṙ_Q per unit σ (eq 72 with ω = u: the rates are linear in ω), and u̇ per unit σ */
    double vp[3], vq[3], du[3];
    /* each point's rate from the sensitivity its Newton solve left (gb_dyn_contact_at's for P, second_point's for Q) */
    if (d->def.contact == GB_CONTACT_MODEL_CONTINUOUS && d->last_valid) gb_contact_rate_from(d->last_dq, d->last_zb, &tp->p.point, u, vp, NULL);
    else status = gb_dyn_point_rate(d, zb, &tp->p.point, u, vp);
    if (!status && d->crease.q_valid) gb_contact_rate_from(d->crease.q_dq, d->crease.q_zb, &tp->q, u, vq, NULL);
    else if (!status) status = gb_dyn_point_rate(d, zb, &tp->q, u, vq);
    if (status) return status;
    for (int k = 0; k < 3; k++) vp[k] *= L, vq[k] *= L;
    const double rel[3] = {vp[0] - vq[0], vp[1] - vq[1], vp[2] - vq[2]}, along = gb_vec_dot(u, rel);
    for (int k = 0; k < 3; k++) du[k] = (rel[k] - along * u[k]) / tp->dist;
    /* I_u = uᵀ I_P u and its rate per unit σ, K = 2 uᵀ I_P u̇ + uᵀ İ_P u, İ_P = m (2 r·ṙ I − ṙ rᵀ − r ṙᵀ) */
    double IP[3][3], IPu[3];
    gb_dyn_inertia_about(d, tp->rp, IP);
    gb_dyn_mat_vec(IP, u, IPu);
    const double Iu = gb_vec_dot(u, IPu);
    const double K = 2.0 * gb_vec_dot(IPu, du) + 2.0 * m * (gb_vec_dot(tp->rp, vp) - gb_vec_dot(u, vp) * gb_vec_dot(u, tp->rp));
    double geff, geff_rate, zxu[3];
    gb_forcing_geff_with_rate(&d->def.forcing, t, &geff, &geff_rate);
    gb_vec_cross(zb, u, zxu);
    /* d/dt(½ I_u σ²) = σ (I_u σ̇ + ½ K σ²) = −m g_eff ζ̇ − c σ², ζ̇ = −σ (z_b × u)·r_P */
    const double s = tp->sigma;
    const double sigma_dot = (m * geff * gb_vec_dot(zxu, tp->rp) - c * s - 0.5 * K * s * s) / Iu;
    for (int k = 0; k < 3; k++) tp->omega_dot[k] = sigma_dot * u[k] + s * s * du[k];
    if (!forces) {
        tp->normal[0] = tp->normal[1] = tp->friction_needed = tp->balance = NAN;
        return GB_OK;
    }
    /* Newton–Euler with these accelerations: the contact forces F = m a_G + m g_eff z_b, their moment
     * about G, M = I_G ω̇ + ω × I_G ω + c ω = r_P × F_P + r_Q × F_Q, so (r_P − r_Q) × F_P = M − r_Q × F
     * fixes F_P across PQ; its part along PQ (and Q's) is the internal force statics leaves open. */
    double acc[3], F[3], Iw[3], gyro[3], Iwd[3], M[3], rqF[3], X[3], FP[3];
    gb_dyn_contact at_p = {.rc_dot = {s * vp[0], s * vp[1], s * vp[2]}}; /* r_P moving at σ ṙ_P₁ */
    memcpy(at_p.rc, tp->rp, sizeof at_p.rc);
    gb_dyn_normal_force(d, geff, zb, omega, tp->omega_dot, &at_p, acc);
    memcpy(tp->acc, acc, sizeof tp->acc);
    for (int k = 0; k < 3; k++) F[k] = m * (acc[k] + geff * zb[k]);
    gb_dyn_mat_vec(d->inertia, omega, Iw);
    gb_vec_cross(omega, Iw, gyro);
    gb_dyn_mat_vec(d->inertia, tp->omega_dot, Iwd);
    gb_vec_cross(tp->rq, F, rqF);
    for (int k = 0; k < 3; k++) M[k] = Iwd[k] + gyro[k] + c * omega[k], X[k] = (M[k] - rqF[k]) / tp->dist;
    tp->balance = fabs(gb_vec_dot(X, u)) * tp->dist / fmax(gb_vec_norm(M) + gb_vec_norm(rqF), 1e-300);
    gb_vec_cross(X, u, FP);
    tp->normal[0] = gb_vec_dot(zb, FP);
    tp->normal[1] = gb_vec_dot(zb, F) - tp->normal[0];
    const double n = tp->normal[0] + tp->normal[1], share = n > 0.0 ? tp->normal[0] / n : 0.5, fu = gb_vec_dot(F, u);
    double tan_p[3], tan_q[3];
    for (int k = 0; k < 3; k++) {
        tan_p[k] = FP[k] - tp->normal[0] * zb[k] + share * fu * u[k];
        tan_q[k] = F[k] - FP[k] - tp->normal[1] * zb[k] - share * fu * u[k];
    }
    memcpy(tp->tangent[0], tan_p, sizeof tan_p), memcpy(tp->tangent[1], tan_q, sizeof tan_q);
    tp->friction_needed = tp->normal[0] > 0.0 && tp->normal[1] > 0.0
                              ? fmax(gb_vec_norm(tan_p) / tp->normal[0], gb_vec_norm(tan_q) / tp->normal[1])
                              : INFINITY;
    return GB_OK;
}

int gb_dyn_two_point_field(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double omega[3], const double zb[3],
                           double geff, double omega_dot[3], double *zeta, gb_dyn_rates *rates)
{
    gb_dyn_two_point tp;
    int status = gb_dyn_two_point_eval(d, t, y, &tp, rates != NULL);
    if (status) return status;
    const gb_dyn_contact c = tp.p;
    if (tp.merged) status = gb_dyn_angular_acceleration(d, geff, zb, omega, &c, omega_dot); /* on P alone */
    else memcpy(omega_dot, tp.omega_dot, sizeof tp.omega_dot);
    if (!status) *zeta = -gb_vec_dot(zb, c.rc);
    if (!status && rates) {
        double acc[3];
        if (tp.merged) gb_dyn_normal_force(d, geff, zb, omega, omega_dot, &c, acc);
        else memcpy(acc, tp.acc, sizeof acc);
        gb_dyn_to_inertial(y, acc, rates->acc);
    }
    return status;
}

/* After an accepted step: every event of the mode is located inside its step, so one found here is a
 * second inside one step; the points continued; and the end of a crease (Q merged with P or gone in a
 * fold), where the state is continuous and the mode whose constraint ends has nothing to jump: the body
 * rolls on P alone from here. */
int gb_dyn_two_point_accept(gb_dynamics *d, double t, double y[GB_STATE_SIZE])
{
    gb_contact_point other;
    int found;
    int status = gb_dyn_current(d)->pending(d, t, y, &other, &found); /* this mode's, through the table */
    if (!status && found)
        status = gb_error_set_limit(GB_ENUMERIC, "unilateral contact at t = %.9g: a second change of contact inside one "
                                    "step of the two-point mode (%s)", t, d->event == GB_DYN_EVENT_LIFT ? "a normal force below 0"
                                    : "a third point lower than both");
    gb_dyn_two_point tp;
    if (!status) status = gb_dyn_two_point_eval(d, t, y, &tp, 0);
    if (status) return status;
    gb_dyn_set_contact(d, &tp.p.point);
    d->memo_valid = 0;
    if (tp.merged) {
        const double L = d->def.length;
        double rp[3], v[3];
        for (int k = 0; k < 3; k++) rp[k] = L * tp.p.point.rc[k];
        gb_impact_result r;
        gb_dyn_no_impulse(d, y, rp, v, &r);
        gb_dynamics_impact e = {.t = t, .located = 0, .kind = GB_DYNAMICS_IMPACT_CREASE_END, .contacts_after = 1,
                                .return_time = INFINITY};
        double qr[3];
        for (int k = 0; k < 3; k++) qr[k] = L * d->contact2.rc[k];
        gb_dyn_record(&e, y, qr, rp, v, &r, 0, -1);
        gb_dyn_set_mode(d, GB_DYN_ONE_POINT, t);
        d->last_valid = 0;
        status = gb_dyn_book(d, &e);
        if (status) return status;
        return gb_dyn_remember_rate(d, t, y);
    }
    d->contact2 = tp.q;
    return gb_dyn_remember_rate(d, t, y);
}

/* (the end of a crease is observed as rolling on P) */
int gb_dyn_two_point_observe(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_observables *o)
{
    gb_dyn_two_point tp;
    int status = gb_dyn_two_point_eval(d, t, y, &tp, 1);
    if (status) return status;
    if (tp.merged) {
        gb_dyn_contact c;
        status = gb_dyn_contact_at(d, t, o->zb, o->omega, &c);
        if (!status) status = gb_dyn_angular_acceleration(d, o->geff, o->zb, o->omega, &c, o->omega_dot);
        if (!status) gb_dyn_observe_on_plane(d, t, y, &c, 1, o);
        return status;
    }
    memcpy(o->omega_dot, tp.omega_dot, sizeof tp.omega_dot);
    gb_dyn_observe_on_plane(d, t, y, &tp.p, 2, o);
    memcpy(o->rc_other, tp.rq, sizeof o->rc_other);
    memcpy(o->normal_forces, tp.normal, sizeof tp.normal);
    o->friction_needed = tp.friction_needed;
    o->balance = tp.balance;
    o->tie = d->def.length * (tp.p.point.height - tp.q.height);
    return GB_OK;
}
