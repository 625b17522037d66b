/* gb_dynamics_jumps — the jump maps at the events (docs/impact.md): what each located event does to the
 * state, each impact by the generic impact law of a rigid body on a plane (gb_impact), the settle rule's
 * lumped impacts, the check that the plane only pushes, and the book every change of contact is written
 * to (the ledger's L, the impacts file). The variational estimator's jump maps (nothing booked) call the
 * same outcome functions as the events themselves. */
#include "gb_dynamics_internal.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* z_b = Rᵀ e_z: the third row of R (eq 21). */
static void zb_of(const double R[9], double zb[3])
{
    zb[0] = R[6], zb[1] = R[7], zb[2] = R[8];
}

static const char *const impact_kind_names[] = {"switch", "two-point", "lift", "third-point", "lift-off", "landing", "bounce",
                                                "crease-end"};

const char *gb_dynamics_impact_kind_name(gb_dynamics_impact_kind k) { return (unsigned)k < 8 ? impact_kind_names[k] : NULL; }

/* The plastic impact (gb_impact, body axes, the plane's normal z_b) of the body turning with the ω of y
 * about the point `rest` (at rest on the plane before), on the plane at `count` points [m]. */
static int impact_solve(const gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double rest[3],
                        const double (*points)[3], int count, double e, double v_before[3], gb_impact_result *r)
{
    double zb[3];
    gb_dyn_vertical(y, zb);
    const double arm[3] = {-rest[0], -rest[1], -rest[2]}; /* G − P */
    gb_vec_cross(y + GB_STATE_OMEGA, arm, v_before);
    gb_impact_body body = {d->def.mass, {{0}}};
    memcpy(body.inertia, d->inertia, sizeof body.inertia);
    if (gb_impact_solve(&body, zb, e, points, count, v_before, y + GB_STATE_OMEGA, r))
        return gb_error_set(GB_ENUMERIC, "unilateral contact at t = %.9g: %s on a perfectly rough plane (a plane of finite "
                            "friction, [model] friction = mu, lets the point slip)", t, gb_error_message());
    return GB_OK;
}

/* The plastic impact that stops both P and Q (r_P, r_Q [m]), from the state y turning about P: ω⁺ = σ u
 * along PQ with u·H_P kept (the impulses at P and Q have no moment about the line PQ), H_P = I_G ω + m
 * (G − P) × v_G; the impulses from the momentum and moment jumps, the part along PQ split as the normal
 * impulses (as for the two-point mode's forces). */
static void hold_both(const gb_dynamics *d, const double y[GB_STATE_SIZE], const double rp[3], const double rq[3],
                      const double v_before[3], gb_impact_result *r)
{
    const double m = d->def.mass, *omega = y + GB_STATE_OMEGA;
    double zb[3], dvec[3], u[3], IP[3][3], IPu[3], Iw[3], gp[3], HP[3];
    gb_dyn_vertical(y, zb);
    for (int k = 0; k < 3; k++) dvec[k] = rp[k] - rq[k];
    const double dist = gb_vec_norm(dvec);
    if (dist <= GB_IMPACT_SAME_POINT * fmax(gb_vec_norm(rp), gb_vec_norm(rq))) {
        /* P and Q are one point (GB_IMPACT_SAME_POINT): it is held at rest, and the impulse is Q's */
        const double both[2][3] = {{rp[0], rp[1], rp[2]}, {rq[0], rq[1], rq[2]}};
        gb_impact_body body = {m, {{0}}};
        memcpy(body.inertia, d->inertia, sizeof body.inertia);
        if (gb_impact_hold_all(&body, zb, both, 2, v_before, omega, r) == GB_OK) {
            r->normal_impulse[1] = r->normal_impulse[0], r->tangential_impulse[1] = r->tangential_impulse[0];
            r->normal_impulse[0] = r->tangential_impulse[0] = 0.0;
            memcpy(r->impulse[1], r->impulse[0], sizeof r->impulse[1]);
            memset(r->impulse[0], 0, sizeof r->impulse[0]);
        }
        gb_error_clear();
        return;
    }
    for (int k = 0; k < 3; k++) u[k] = dvec[k] / dist;
    gb_dyn_mat_vec((double (*)[3])d->inertia, omega, Iw);
    gb_vec_cross((const double[3]){-rp[0], -rp[1], -rp[2]}, v_before, gp);
    for (int k = 0; k < 3; k++) HP[k] = Iw[k] + m * gp[k];
    gb_dyn_inertia_about(d, rp, IP);
    gb_dyn_mat_vec(IP, u, IPu);
    const double sigma = gb_vec_dot(u, HP) / gb_vec_dot(u, IPu);
    memset(r, 0, sizeof *r);
    for (int k = 0; k < 3; k++) r->omega[k] = sigma * u[k];
    gb_vec_cross(r->omega, (const double[3]){-rp[0], -rp[1], -rp[2]}, r->v);
    gb_impact_body body = {m, {{0}}};
    memcpy(body.inertia, d->inertia, sizeof body.inertia);
    r->energy_before = gb_impact_energy(&body, v_before, omega);
    r->energy_after = gb_impact_energy(&body, r->v, r->omega);
    double Pi[3], dH[3], dw[3], rqPi[3], X[3], PP[3];
    for (int k = 0; k < 3; k++) Pi[k] = m * (r->v[k] - v_before[k]), dw[k] = r->omega[k] - omega[k];
    gb_dyn_mat_vec((double (*)[3])d->inertia, dw, dH);
    gb_vec_cross(rq, Pi, rqPi);
    for (int k = 0; k < 3; k++) X[k] = (dH[k] - rqPi[k]) / dist;
    gb_vec_cross(X, u, PP);
    r->normal_impulse[0] = gb_vec_dot(zb, PP);
    r->normal_impulse[1] = gb_vec_dot(zb, Pi) - r->normal_impulse[0];
    const double n = r->normal_impulse[0] + r->normal_impulse[1], share = n > 0.0 ? r->normal_impulse[0] / n : 0.5;
    const double pu = gb_vec_dot(Pi, u);
    double tp[3], tq[3];
    for (int k = 0; k < 3; k++) {
        tp[k] = PP[k] - r->normal_impulse[0] * zb[k] + share * pu * u[k];
        tq[k] = Pi[k] - PP[k] - r->normal_impulse[1] * zb[k] - share * pu * u[k];
    }
    r->tangential_impulse[0] = gb_vec_norm(tp), r->tangential_impulse[1] = gb_vec_norm(tq);
    /* at Q, which lands; P's normal impulse may be a small pull (see gb_dynamics_impact.old_normal_impulse) */
    r->friction_needed = r->normal_impulse[1] > 0.0   ? r->tangential_impulse[1] / r->normal_impulse[1]
                         : r->tangential_impulse[1] > 0.0 ? INFINITY
                                                          : 0.0; /* no impulse at all (a point arriving at rest) */
    r->holds[0] = r->holds[1] = 1;
    r->feasible_sets = 1;
}

/* Does the new point q [m] meet the plane at rest: no impulse at all, and its normal velocity (the body
 * turning with the ω of y about P, the centroid at v) below 1e-9 of √(g_max L), the rounding of a located
 * event's time? */
static int grazing(const gb_dynamics *d, const double y[GB_STATE_SIZE], const double v[3], const gb_impact_result *r,
                   const double q[3])
{
    const gb_forcing *f = &d->def.forcing;
    double zb[3], wq[3];
    gb_dyn_vertical(y, zb);
    gb_vec_cross(y + GB_STATE_OMEGA, q, wq);
    const double vn = gb_vec_dot(zb, v) + gb_vec_dot(zb, wq);
    const double scale = sqrt((f->g + fabs(f->a1) + fabs(f->a2)) * d->def.length);
    return r->normal_impulse[0] == 0.0 && r->normal_impulse[1] == 0.0 && fabs(vn) <= 1e-9 * scale;
}

/* The outcome of the impact at a change of contact from P (`from`) to Q (`to`) at state y while rolling on
 * one point, nothing booked: the body rolling about P meets the plane at Q; *both: both points hold after
 * (the two-point mode begins), else P lifts; a lift whose fall back would come within the settle time is
 * taken as both held (the settle rule). *bounce: 0, or with restitution 1 (Q rebounds, P holds) and 2 (both
 * leave), or 3 (e = 0 where Moreau's law would need a pull: Q's slip stopped leaves Q moving away, and P
 * too: the body hops). Also: the points [m], the centroid's velocity before, the solver's answer (the
 * settle rule applied), P's return time and whether both points hold. */
static int impact_outcome(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *from,
                          const gb_contact_point *to, double points[2][3], double v[3], gb_impact_result *r, double *back,
                          int *both, int *bounce)
{
    const double L = d->def.length;
    for (int k = 0; k < 3; k++) points[0][k] = L * from->rc[k], points[1][k] = L * to->rc[k];
    double e = 0.0;
    *bounce = 0;
    if (d->def.restitution > 0.0) {
        /* Q's approach speed, the body turning about P */
        double zb[3], vg[3], wq[3];
        gb_dyn_vertical(y, zb);
        gb_vec_cross(y + GB_STATE_OMEGA, (const double[3]){-points[0][0], -points[0][1], -points[0][2]}, vg);
        gb_vec_cross(y + GB_STATE_OMEGA, points[1], wq);
        e = gb_dyn_restitution_at(d, t, -(gb_vec_dot(zb, vg) + gb_vec_dot(zb, wq)));
    }
    int status = impact_solve(d, t, y, points[0], (const double (*)[3])points, 2, e, v, r);
    if (status == GB_ENUMERIC && e == 0.0) {
        /* Moreau's law has no answer: holding Q would need the plane to pull. The rough plane's one-point law
         * (gb_impact_rough_point, a landing's) at Q: Q's slip stopped first, then its approach if any is
         * left; it stands when P then moves away from the plane (P lifts with no impulse). If Q leaves too,
         * the body hops. */
        double zb[3], uP[3];
        gb_impact_result q;
        gb_impact_body body = {d->def.mass, {{0}}};
        memcpy(body.inertia, d->inertia, sizeof body.inertia);
        gb_dyn_vertical(y, zb);
        if (gb_impact_rough_point(&body, zb, 0.0, points[1], v, y + GB_STATE_OMEGA, &q) == GB_OK) {
            gb_vec_cross(q.omega, points[0], uP);
            for (int k = 0; k < 3; k++) uP[k] += q.v[k];
            if (gb_vec_dot(zb, uP) >= -1e-10 * gb_vec_norm(v)) {
                gb_error_clear();
                memset(r, 0, sizeof *r);
                memcpy(r->v, q.v, sizeof r->v);
                memcpy(r->omega, q.omega, sizeof r->omega);
                r->holds[1] = q.holds[0];
                memcpy(r->impulse[1], q.impulse[0], sizeof r->impulse[1]);
                r->normal_impulse[1] = q.normal_impulse[0], r->tangential_impulse[1] = q.tangential_impulse[0];
                r->friction_needed = q.friction_needed;
                r->energy_before = q.energy_before, r->energy_after = q.energy_after;
                r->feasible_sets = 1;
                status = GB_OK;
                if (!q.holds[0]) { /* Q leaves with P: a hop */
                    *bounce = 3, *both = 0, *back = INFINITY;
                    return GB_OK;
                }
            }
        }
    }
    if (status) return status;
    if (e > 0.0) {
        /* Q rebounds at e times its approach speed and leaves the plane; P holds (the body rolls on about P)
         * or separates too (the body hops) */
        *bounce = r->holds[0] ? 1 : 2;
        *both = 0;
        *back = INFINITY;
        return GB_OK;
    }
    if (!r->holds[1] && grazing(d, y, v, r, points[1])) {
        /* Q arrives at rest (a grazing event, or two nodes tied at rest as a grid body may start): no
         * impulse, and the forces decide. On both points, the two-point mode's lift event follows at
         * once where one of its normal forces is below 0. */
        hold_both(d, y, points[0], points[1], v, r);
        *both = 1;
        *back = INFINITY;
        return GB_OK;
    }
    if (!r->holds[1])
        return gb_error_set_limit(GB_ENUMERIC, "unilateral contact at t = %.9g: after the impact the new contact does not hold", t);
    *both = r->holds[0];
    *back = INFINITY;
    if (!*both) {
        double yafter[GB_STATE_SIZE];
        memcpy(yafter, y, sizeof yafter);
        memcpy(yafter + GB_STATE_OMEGA, r->omega, sizeof r->omega);
        *back = gb_dyn_return_time(d, t, yafter, to, r->v, points[0]);
        if (*back < d->settle_time) {
            /* the settle rule lumps the chatter, unless the lumped impact would need the plane to pull beyond
             * the weight's impulse it stands for (P and Q close together, a couple with a short arm): then
             * Moreau's impact stands, and P's return is an impact of its own */
            gb_impact_result lumped;
            double allowed;
            hold_both(d, y, points[0], points[1], v, &lumped);
            if (gb_dyn_pulling_point(d, &lumped, (const double(*)[3])points, 2, 1, 1, v, y + GB_STATE_OMEGA, &allowed) < 0)
                *r = lumped, *both = 1;
        }
    }
    return GB_OK;
}

/* That impact, booked: ω in y takes its value after. */
static int impact(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *from, const gb_contact_point *to,
                  int located, int *both, int *bounce)
{
    double points[2][3], v[3], back;
    gb_impact_result r;
    int status = impact_outcome(d, t, y, from, to, points, v, &r, &back, both, bounce);
    if (!status) status = gb_dyn_plane_pushes(d, t, &r, (const double(*)[3])points, 2, 1, *both && isfinite(back), v, y + GB_STATE_OMEGA);
    if (status) return status;
    gb_dynamics_impact e = {.t = t, .located = located, .kind = *both ? GB_DYNAMICS_IMPACT_TWO_POINT : GB_DYNAMICS_IMPACT_SWITCH,
                            .contacts_after = 1 + *both, .settled = *both && isfinite(back), .return_time = back};
    if (*bounce == 1 || *bounce == 2) e.kind = GB_DYNAMICS_IMPACT_BOUNCE, e.contacts_after = *bounce == 1, e.rebound = 1;
    else if (*bounce == 3) e.contacts_after = 0; /* Q's slip stopped and Q leaves with P: the body hops */
    gb_dyn_record(&e, y, points[0], points[1], v, &r, 1, 0);
    if (*bounce >= 2) {
        /* both points leave the plane: the body flies, its centroid where it is, at its velocity after */
        double zb[3];
        gb_dyn_vertical(y, zb);
        gb_dyn_start_flight(d, t, y, r.v, -gb_vec_dot(zb, points[0]));
    }
    return gb_dyn_book(d, &e);
}

/* At a lift-off from one point the normal force is 0 but the rolling contact's tangential force F_t
 * generally is not (the friction it needs, |F_t|/N, grows without bound as N reaches 0). Without F_t the
 * point's normal acceleration changes by −n·W F_t (W the point's Delassus operator, as in gb_impact): if
 * that drives the point into the plane, neither rolling (N < 0 after) nor flight (the point would
 * penetrate) continues the motion: on a plane of finite friction the body slides before it lifts, which
 * this model (rough, no slip) does not follow. GB_ENUMERIC then, saying so. */
static int lift_off_consistent(gb_dynamics *d, double t, const double y[GB_STATE_SIZE])
{
    const double m = d->def.mass, *omega = y + GB_STATE_OMEGA;
    double zb[3], geff, geff_rate, w_dot[3], acc[3], F[3], rxF[3], I[3][3], dw[3], dv[3];
    gb_dyn_contact c;
    if (d->mode == GB_DYN_TWO_POINT) return GB_OK; /* left by its lift event first: a lift-off is from one point */
    gb_dyn_vertical(y, zb);
    gb_forcing_geff_with_rate(&d->def.forcing, t, &geff, &geff_rate);
    int status = gb_dyn_contact_at(d, t, zb, omega, &c);
    if (!status) status = gb_dyn_angular_acceleration(d, geff, zb, omega, &c, w_dot);
    if (status) return status;
    gb_dyn_normal_force(d, geff, zb, omega, w_dot, &c, acc);
    for (int k = 0; k < 3; k++) F[k] = m * (acc[k] + geff * zb[k]); /* the contact force rolling needs */
    /* W F = F/m + (I⁻¹ (r × F)) × r: the contact point's acceleration that F makes */
    memcpy(I, d->inertia, sizeof I);
    gb_vec_cross(c.rc, F, rxF);
    status = gb_dyn_solve3(I, rxF, dw);
    if (status) return status;
    gb_vec_cross(dw, c.rc, dv);
    const double drop = gb_vec_dot(zb, F) / m + gb_vec_dot(zb, dv); /* n·W F */
    if (!(drop > 0.0)) return GB_OK;
    /* The gap then opens as −a t²/2 + b t³/6 (a = drop, b = −Ṅ/m, N falling through 0), whose deepest dip is
     * (2/3) a³/b² at t = 2a/b: within the landing tolerance (GB_DYN_GAP_TOL) the lift-off stands. Ṅ by a
     * forward difference along the flow (the current mode's field, gb_dyn_field) over 1e-6 of the step. */
    double f[GB_STATE_SIZE], y2[GB_STATE_SIZE], n2;
    const double delta = 1e-6 * (d->settle_time > 0.0 ? d->settle_time : gb_forcing_period(&d->def.forcing) / 160.0);
    status = gb_dyn_field(d, t, y, f);
    for (int k = 0; k < GB_STATE_SIZE; k++) y2[k] = y[k] + delta * f[k];
    if (!status) status = gb_dyn_one_point_normal(d, t + delta, y2, &n2);
    if (status) return status;
    const double b = -n2 / (delta * m), dip = b > 0.0 ? 2.0 / 3.0 * drop * drop * drop / (b * b) : INFINITY;
    if (dip > GB_DYN_LIFT_OFF_DIP_MAX * d->def.length) {
        const double fn = gb_vec_dot(zb, F), ft[3] = {F[0] - fn * zb[0], F[1] - fn * zb[1], F[2] - fn * zb[2]};
        char depth[96] = "into the plane and kept below it (the normal force reaches 0 without falling through)";
        if (isfinite(dip)) snprintf(depth, sizeof depth, "%.3g m into the plane", dip);
        return gb_error_set(GB_ENUMERIC, "lift-off at t = %.9g: the normal force reaches 0 while rolling still needs a "
                            "friction force of %.3g N, without which the contact point is driven %s: on a plane of finite "
                            "friction the body slides before it lifts, which this rough-plane model does not follow "
                            "([model] friction = mu follows it)", t, gb_vec_norm(ft), depth);
    }
    /* the flight's landing waits below the dip (twice the estimate) until the gap has opened */
    d->gap_allow = fmax(d->gap_allow, GB_DYN_GAP_TOL + 2.0 * dip / d->def.length);
    return GB_OK;
}

/* The last contact's normal force (or g_eff on three points at rest) has reached 0 at state y: the body
 * leaves the plane with the velocity it has, no impulse. Ends the two-point mode or the rest. */
static int lift_off(gb_dynamics *d, double t, double y[GB_STATE_SIZE])
{
    const double L = d->def.length;
    double zb[3], rp[3], v[3];
    gb_dyn_vertical(y, zb);
    gb_contact_point p;
    int status = gb_dyn_point_at(d, zb, &d->contact, &p);
    double allow = GB_DYN_GAP_TOL;
    if (!status && d->mode != GB_DYN_REST) {
        d->gap_allow = GB_DYN_GAP_TOL;
        status = lift_off_consistent(d, t, y);
        allow = d->gap_allow;
    }
    if (status) return status;
    if (d->mode == GB_DYN_REST) memset(y + GB_STATE_OMEGA, 0, 3 * sizeof *y); /* at rest nothing turns */
    for (int k = 0; k < 3; k++) rp[k] = L * p.rc[k];
    gb_impact_result r;
    gb_dyn_no_impulse(d, y, rp, v, &r);
    gb_dynamics_impact e = {.t = t, .located = 1, .kind = GB_DYNAMICS_IMPACT_LIFT_OFF, .contacts_after = 0, .return_time = INFINITY};
    gb_dyn_record(&e, y, rp, rp, v, &r, 0, -1);
    gb_dyn_set_contact(d, &p);
    gb_dyn_start_flight(d, t, y, v, -gb_vec_dot(zb, rp));
    d->gap_allow = allow;
    return gb_dyn_book(d, &e);
}

/* In flight, the lowest point q (continued to state y) reaches the plane: Moreau's impact at q with
 * Newton's restitution (restitution_at). A plastic landing leaves the body rolling on q, unless its normal
 * force is below 0 there (g_eff pulls the plane away faster): then it flies on from q at rest. */
static int landing(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *q)
{
    const double L = d->def.length;
    double zb[3], R[9], zeta, v_in[3], v[3], rq[3], wq[3];
    gb_dynamics_rotation(y + GB_STATE_Q, R);
    zb_of(R, zb);
    gb_dyn_flight_state(d, t, &zeta, v_in);
    for (int i = 0; i < 3; i++) v[i] = R[i] * v_in[0] + R[3 + i] * v_in[1] + R[6 + i] * v_in[2]; /* Rᵀ v */
    for (int k = 0; k < 3; k++) rq[k] = L * q->rc[k];
    gb_vec_cross(y + GB_STATE_OMEGA, rq, wq);
    const double e = gb_dyn_restitution_at(d, t, -(gb_vec_dot(zb, v) + gb_vec_dot(zb, wq)));
    gb_impact_body body = {d->def.mass, {{0}}};
    memcpy(body.inertia, d->inertia, sizeof body.inertia);
    gb_impact_result r;
    if (gb_impact_rough_point(&body, zb, e, rq, v, y + GB_STATE_OMEGA, &r))
        return gb_error_set(GB_ENUMERIC, "landing at t = %.9g: %s", t, gb_error_message());
    const int pushes = gb_dyn_plane_pushes(d, t, &r, (const double(*)[3])&rq, 1, 0, 0, v, y + GB_STATE_OMEGA);
    if (pushes) return pushes;
    gb_dynamics_impact rec = {.t = t, .located = 1, .kind = GB_DYNAMICS_IMPACT_LANDING, .rebound = e > 0.0 && r.holds[0],
                              .return_time = INFINITY};
    gb_dyn_record(&rec, y, rq, rq, v, &r, 0, -1);
    gb_dyn_set_contact(d, q);
    int flies = e > 0.0 || !r.holds[0]; /* a rebound, or the slip stopped and the point leaves */
    double allow = GB_DYN_GAP_TOL;
    if (!flies) {
        double n;
        int status = gb_dyn_one_point_normal(d, t, y, &n);
        flies = !status && n < 0.0;
        if (flies) {
            /* the plane still falls away faster than gravity: the body leaves the point at rest, as at a
             * lift-off, and its dip is bounded the same way */
            d->gap_allow = GB_DYN_GAP_TOL;
            status = lift_off_consistent(d, t, y);
            allow = d->gap_allow;
        }
        if (status) return status;
    }
    if (flies) {
        /* the flight goes on from where the point is, up to the landing tolerance below the plane: the next
         * landing is a return below that */
        const double depth = -(zeta + L * gb_vec_dot(zb, q->rc)) / L;
        gb_dyn_start_flight(d, t, y, r.v, zeta);
        d->gap_allow = fmax(allow, fmax(depth, 0.0) + GB_DYN_GAP_TOL);
    } else {
        gb_dyn_set_mode(d, GB_DYN_ONE_POINT, t);
        rec.contacts_after = 1;
        rec.potential_jump = -d->def.mass * gb_forcing_geff(&d->def.forcing, t) * (zeta + L * gb_vec_dot(zb, q->rc));
    }
    return gb_dyn_book(d, &rec);
}

/* The outcome of a third point `third` [m] landing while the body rolls on P and Q (points[0], points[1] [m];
 * points[2] is `third`), nothing booked: Moreau's impact over the three, then the settle rule (a point of the
 * old pair that would fall back within the settle time is held with the third; both: the body stops on all
 * three). *held: the points held after (2 or 3, or 1: the third alone), *back: the first return time, *settled:
 * the settle rule decided. */
static int third_point_outcome(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *third,
                               const double points[3][3], double v[3], gb_impact_result *r, int *held, double *back,
                               int *settled)
{
    int status = impact_solve(d, t, y, points[0], points, 3, 0.0, v, r);
    if (status) return status;
    *held = r->holds[0] + r->holds[1] + r->holds[2];
    *back = INFINITY;
    *settled = 0;
    if (!r->holds[2])
        return gb_error_set_limit(GB_ENUMERIC, "unilateral contact at t = %.9g: a third point reaches the plane and does not "
                                  "hold after the impact", t);
    if (*held == 1) {
        /* The settle rule, as at a switch: P or Q lifts and would fall back within the settle time, so the
         * body is held on the third point and that one (the lumped chatter, hold_both). */
        double yafter[GB_STATE_SIZE];
        memcpy(yafter, y, sizeof yafter);
        memcpy(yafter + GB_STATE_OMEGA, r->omega, sizeof r->omega);
        const double back_p = gb_dyn_return_time(d, t, yafter, third, r->v, points[0]);
        const double back_q = gb_dyn_return_time(d, t, yafter, third, r->v, points[1]);
        const int k = back_q < back_p;
        *back = fmin(back_p, back_q);
        /* A lumped impact is taken only where it pushes within the weight's impulse it stands for
         * (gb_dyn_pulling_point): a thin triangle or a short edge would need a couple the plane cannot give, and
         * then the next lumping is tried, and last Moreau's impact stands. */
        double allowed;
        if (fmax(back_p, back_q) < d->settle_time) {
            /* both would fall back within it: the body stops on the three points (the chatter's limit) */
            double zb[3];
            gb_dyn_vertical(y, zb);
            gb_impact_body body = {d->def.mass, {{0}}};
            memcpy(body.inertia, d->inertia, sizeof body.inertia);
            gb_impact_result all;
            status = gb_impact_hold_all(&body, zb, points, 3, v, y + GB_STATE_OMEGA, &all);
            if (status) return status;
            if (gb_dyn_pulling_point(d, &all, points, 3, 2, 1, v, y + GB_STATE_OMEGA, &allowed) < 0) {
                *r = all, *held = 3, *settled = 1;
                return GB_OK;
            }
        }
        if (*back < d->settle_time) {
            gb_impact_result h; /* its slots: 0 the third point, 1 the one held with it */
            hold_both(d, y, points[2], points[k], v, &h);
            gb_impact_result two = h;
            for (int j = 0; j < 3; j++) {
                const int from = j == 2 ? 0 : j == k ? 1 : -1;
                two.holds[j] = from >= 0;
                two.normal_impulse[j] = from >= 0 ? h.normal_impulse[from] : 0.0;
                two.tangential_impulse[j] = from >= 0 ? h.tangential_impulse[from] : 0.0;
            }
            /* at the third point, which lands (the one held with it may pull, as P in the settle rule) */
            two.friction_needed = two.normal_impulse[2] > 0.0 ? two.tangential_impulse[2] / two.normal_impulse[2] : INFINITY;
            if (gb_dyn_pulling_point(d, &two, points, 3, 2, 1, v, y + GB_STATE_OMEGA, &allowed) < 0) *r = two, *held = 2, *settled = 1;
        }
    }
    return GB_OK;
}

/* Two points: the located event at state y (its `other` from gb_dyn_two_point_pending, continued). */
static int two_point_located(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *third)
{
    gb_dyn_two_point tp;
    int status = gb_dyn_two_point_eval(d, t, y, &tp, 1);
    if (!status && tp.merged)
        status = gb_error_set_limit(GB_ENUMERIC, "two-point contact at t = %.9g: the crease ends at a located event", t);
    if (status) return status;
    if (d->event == GB_DYN_EVENT_LIFT) {
        const int lifts = tp.normal[0] < tp.normal[1] ? 0 : 1; /* the point whose force reached 0 */
        const double *up = lifts ? tp.rq : tp.rp, *stays = lifts ? tp.rp : tp.rq;
        gb_dynamics_impact e = {.t = t, .located = 1, .kind = GB_DYNAMICS_IMPACT_LIFT, .contacts_after = 1};
        gb_impact_result r;
        double v[3];
        gb_dyn_no_impulse(d, y, stays, v, &r);
        gb_dyn_record(&e, y, up, stays, v, &r, 0, -1);
        gb_dyn_set_mode(d, GB_DYN_ONE_POINT, t);
        gb_dyn_set_contact(d, lifts ? &tp.p.point : &tp.q);
        if (d->def.contact == GB_CONTACT_MODEL_CONTINUOUS) {
            /* As at a lift-off, the lifted point's gap opens only at third order while the rough contact it
             * leaves still needed a friction force: it may dip below the plane by a micrometre a metre of body
             * (GB_DYN_LIFT_OFF_DIP_MAX) before its return is a change of contact, until its gap has opened. */
            d->lifted = lifts ? tp.q : tp.p.point;
            d->lift_allow = GB_DYN_LIFT_OFF_DIP_MAX;
        }
        return gb_dyn_book(d, &e);
    }
    int face = 0;
    status = gb_dyn_face_landing(d, t, y, &tp, third, &face);
    if (status || face) return status;
    const double L = d->def.length;
    const double points[3][3] = {{tp.rp[0], tp.rp[1], tp.rp[2]}, {tp.rq[0], tp.rq[1], tp.rq[2]},
                                 {L * third->rc[0], L * third->rc[1], L * third->rc[2]}};
    double v[3], back;
    gb_impact_result r;
    int held, settled;
    status = third_point_outcome(d, t, y, third, points, v, &r, &held, &back, &settled);
    if (!status) status = gb_dyn_plane_pushes(d, t, &r, points, 3, 2, settled, v, y + GB_STATE_OMEGA);
    if (status) return status;
    gb_dynamics_impact e = {.t = t, .located = 1, .kind = GB_DYNAMICS_IMPACT_THIRD, .contacts_after = held,
                            .settled = settled, .return_time = back};
    const int old = held == 2 && r.holds[1]; /* the one that stays (P when none does) */
    gb_dyn_record(&e, y, points[old], points[2], v, &r, 2, old);
    if (held == 3) {
        /* Three points stop the body (ω = 0). With the vertical forcing alone (g_eff > 0) it stays at rest
         * if its weight falls inside the triangle: the static normal forces are m g_eff times the
         * barycentric weights of G's foot, w_k = z_b·(p_i × p_j) / z_b·((p_j − p_i) × (p_k − p_i)) for
         * the cyclic (i, j, k). One weight below 0: it tips about the other two points, from rest (the
         * impact's record says three held: the tip begins after it). */
        double zb[3], w[3], a[3], b[3], n[3];
        gb_dyn_vertical(y, zb);
        for (int k = 0; k < 3; k++) a[k] = points[1][k] - points[0][k], b[k] = points[2][k] - points[0][k];
        gb_vec_cross(a, b, n);
        const double area = gb_vec_dot(zb, n);
        int negative = 0, tip = -1;
        for (int i = 0; i < 3; i++) {
            gb_vec_cross(points[(i + 1) % 3], points[(i + 2) % 3], n);
            w[i] = gb_vec_dot(zb, n) / area;
            if (w[i] < 0.0) negative++, tip = i;
        }
        if (negative > 1 || !isfinite(w[0] + w[1] + w[2]))
            return gb_error_set_limit(GB_ENUMERIC, "unilateral contact at t = %.9g: the body stops on three points whose "
                                      "triangle holds neither its weight nor an edge to tip about (weights %.3g, %.3g, %.3g)",
                                      t, w[0], w[1], w[2]);
        if (!negative) {
            gb_dyn_set_mode(d, GB_DYN_REST, t);
            gb_dyn_set_contact(d, third);
            return gb_dyn_book(d, &e);
        }
        /* tips about the edge opposite the negative weight: that edge's points, P first */
        const gb_contact_point *const pts[3] = {&tp.p.point, &tp.q, third};
        gb_dyn_set_contact(d, pts[(tip + 1) % 3]);
        d->contact2 = *pts[(tip + 2) % 3];
        d->crease.q_valid = 0;
        return gb_dyn_book(d, &e);
    }
    if (held == 2) {
        d->contact2 = r.holds[0] ? tp.p.point : tp.q;
        d->crease.q_valid = 0;
    } else {
        gb_dyn_set_mode(d, GB_DYN_ONE_POINT, t);
    }
    gb_dyn_set_contact(d, third);
    return gb_dyn_book(d, &e);
}

/* ---- the events' jumps, by mode ------------------------------------------------------------------ */

/* After a lift-off or a landing: neither is a switch of contact branch; no predictor until the next step. */
static int after_flight_event(gb_dynamics *d, int status)
{
    d->event = GB_DYN_EVENT_NONE;
    d->memo_valid = 0;
    gb_dyn_forget_rate(d);
    d->last_valid = 0;
    return status;
}

/* After a change of contact: a switch, counted. */
static int after_switch(gb_dynamics *d, double t)
{
    d->last_switch_time = t;
    d->memo_valid = 0;
    gb_dyn_forget_rate(d);
    d->last_valid = 0;
    if (d->def.contact == GB_CONTACT_MODEL_CONTINUOUS) d->branch_switches++;
    else d->grid_switches++;
    return GB_OK;
}

/* ---- the laws' impact maps ------------------------------------------------------------------------ */

/* The held law: the contact moves onto `branch` with ω kept (the paper's rule). */
static int held_change(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    (void)y;
    d->contact = *branch;
    return after_switch(d, t);
}

/* The held law keeps one contact: no two-point mode and no flight, so these are never reached. */
static int held_never(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    (void)d, (void)y, (void)branch;
    return gb_error_set(GB_EINVAL, "t = %.9g: the held law keeps one contact (no third point, no landing)", t);
}

/* The held law's saltation at a change of contact: none, ω is kept. */
static int held_change_jump(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                            double out[GB_STATE_SIZE])
{
    (void)d, (void)t, (void)branch;
    memcpy(out, y, GB_STATE_SIZE * sizeof *out);
    return GB_OK;
}

/* Newton's impact on a rough plane, from the point P the body rolls about (the old contact, continued) onto
 * `branch`, after which the body may roll on both points. */
static int rough_change(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    double zb[3];
    gb_dyn_vertical(y, zb);
    gb_contact_point here;
    int both = 0, bounce = 0;
    int status = gb_dyn_point_at(d, zb, &d->contact, &here);
    if (!status) status = impact(d, t, y, &here, branch, 1, &both, &bounce);
    if (status) return status;
    if (bounce != 1) gb_dyn_set_contact(d, branch); /* a rebound of Q off P that holds: the body rolls on about P */
    if (both) {
        gb_dyn_set_mode(d, GB_DYN_TWO_POINT, t);
        d->contact2 = here;
        d->crease.q_valid = 0;
        d->crease.entries++;
    }
    return after_switch(d, t);
}

/* A third point on a rough plane (or a lift from two points: the located event's own case). */
static int rough_third(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    const int status = two_point_located(d, t, y, branch);
    return status ? status : after_switch(d, t);
}

static int rough_landing(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    return after_flight_event(d, landing(d, t, y, branch));
}

/* The rough impact's ω at a change of contact (a hop: not followed). */
static int rough_change_jump(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                             double out[GB_STATE_SIZE])
{
    memcpy(out, y, GB_STATE_SIZE * sizeof *out);
    double zb[3], v[3], points[2][3], back;
    gb_dyn_vertical(y, zb);
    gb_contact_point p, q;
    gb_impact_result res;
    int both, bounce;
    int status = gb_dyn_point_at(d, zb, &d->contact, &p);
    if (!status) status = gb_dyn_point_at(d, zb, branch, &q);
    if (!status) status = impact_outcome(d, t, y, &p, &q, points, v, &res, &back, &both, &bounce);
    if (!status && bounce >= 2)
        status = gb_error_set(GB_EINVAL, "t = %.9g: the variational estimator does not follow a hop (restitution "
                              "lifts both points); use [lyapunov] estimator = pair", t);
    if (!status) memcpy(out + GB_STATE_OMEGA, res.omega, sizeof res.omega);
    return status;
}

/* Two points on a rough plane: a lift keeps the state (no impulse); a third point's impact, its ω. */
static int rough_two_point_jump(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                                double out[GB_STATE_SIZE])
{
    memcpy(out, y, GB_STATE_SIZE * sizeof *out);
    if (d->event == GB_DYN_EVENT_LIFT) return GB_OK;
    const double L = d->def.length;
    double zb[3], v[3];
    gb_dyn_vertical(y, zb);
    gb_contact_point p, q, r;
    gb_impact_result res;
    int status = gb_dyn_point_at(d, zb, &d->contact, &p);
    if (!status) status = gb_dyn_point_at(d, zb, &d->contact2, &q);
    if (!status) status = gb_dyn_point_at(d, zb, branch, &r);
    const double points[3][3] = {{L * p.rc[0], L * p.rc[1], L * p.rc[2]}, {L * q.rc[0], L * q.rc[1], L * q.rc[2]},
                                 {L * r.rc[0], L * r.rc[1], L * r.rc[2]}};
    double back;
    int held, settled;
    if (!status) status = third_point_outcome(d, t, y, &r, points, v, &res, &held, &back, &settled);
    if (!status) memcpy(out + GB_STATE_OMEGA, res.omega, sizeof res.omega);
    return status;
}

/* Coulomb's impact from P onto the new point. */
static int coulomb_change(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    double zb[3];
    gb_dyn_vertical(y, zb);
    gb_contact_point pts[2];
    int status = gb_dyn_point_at(d, zb, &d->contact, &pts[0]);
    pts[1] = *branch;
    if (!status) status = gb_dyn_friction_impact(d, t, y, pts, 2, 1, GB_DYNAMICS_IMPACT_SWITCH, 1);
    return status ? status : after_switch(d, t);
}

/* Coulomb's impact over the three (a face landing flat is not followed). */
static int coulomb_third(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    double zb[3];
    gb_dyn_vertical(y, zb);
    gb_contact_point pts[3];
    int status = gb_dyn_point_at(d, zb, &d->contact, &pts[0]);
    if (!status) status = gb_dyn_point_at(d, zb, &d->contact2, &pts[1]);
    pts[2] = *branch;
    const int ties = status ? 0 : gb_dyn_face_ties(d, zb, &pts[0], &pts[1], branch);
    if (ties)
        return gb_error_set_limit(GB_ENUMERIC, "a face of %d vertices lands flat at t = %.9g on a plane of friction mu = %g, which "
                                  "is not followed (Coulomb's impact here takes three points; the rough plane, [model] friction "
                                  "= rough, follows a face landing)", ties + 3, t, d->def.friction);
    if (!status) status = gb_dyn_friction_impact(d, t, y, pts, 3, 2, GB_DYNAMICS_IMPACT_THIRD, 1);
    return status ? status : after_switch(d, t);
}

/* Coulomb's impact at the landing point. */
static int coulomb_landing(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    return after_flight_event(d, gb_dyn_friction_impact(d, t, y, branch, 1, 0, GB_DYNAMICS_IMPACT_LANDING, 1));
}

const gb_dyn_impact_map gb_dyn_held_impacts = {held_change, held_never, held_never, held_change_jump, gb_dyn_no_jump};
const gb_dyn_impact_map gb_dyn_rough_impacts = {rough_change, rough_third, rough_landing, rough_change_jump,
                                                rough_two_point_jump};
const gb_dyn_impact_map gb_dyn_coulomb_impacts = {coulomb_change, coulomb_third, coulomb_landing, gb_dyn_no_jump,
                                                  gb_dyn_no_jump};

/* ---- the modes' events and jumps: the events every law shares, then the law's impact map -------------- */

int gb_dyn_one_point_event(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    if (d->event == GB_DYN_EVENT_LIFT_OFF) return after_flight_event(d, lift_off(d, t, y));
    if (d->event == GB_DYN_EVENT_SLIP) return after_flight_event(d, gb_dyn_slip_start(d, t, y));
    return d->law->impact_map->change(d, t, y, branch);
}

int gb_dyn_two_point_event(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    if (d->event == GB_DYN_EVENT_SLIP) return after_flight_event(d, gb_dyn_slip_start(d, t, y));
    if (d->event == GB_DYN_EVENT_THIRD) return d->law->impact_map->third(d, t, y, branch);
    const int status = two_point_located(d, t, y, branch); /* a lift: no impulse */
    return status ? status : after_switch(d, t);
}

int gb_dyn_rest_event(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    (void)branch;
    return after_flight_event(d, lift_off(d, t, y));
}

int gb_dyn_flight_event(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    return d->law->impact_map->landing(d, t, y, branch);
}

/* ---- the jump maps, nothing booked (the variational estimator's saltation) ------------------------ */

int gb_dyn_no_jump(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                   double out[GB_STATE_SIZE])
{
    (void)d, (void)branch;
    memcpy(out, y, GB_STATE_SIZE * sizeof *out);
    return gb_error_set(GB_EINVAL, "t = %.9g: the variational estimator does not follow lift-off, flight or sliding (the "
                        "centroid's translation is not in its tangent space); use [lyapunov] estimator = pair", t);
}

int gb_dyn_one_point_jump(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                          double out[GB_STATE_SIZE])
{
    if (d->event == GB_DYN_EVENT_LIFT_OFF) return gb_dyn_no_jump(d, t, y, branch, out);
    return d->law->impact_map->change_jump(d, t, y, branch, out);
}

int gb_dyn_two_point_jump(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                          double out[GB_STATE_SIZE])
{
    return d->law->impact_map->two_point_jump(d, t, y, branch, out);
}
