/* gb_lyapunov_body — a Gömböc as a pair system and as a tangent system (see gb_lyapunov_body.h). */
#include "gb_lyapunov_body.h"

#include "gb_dynamics_protocol_internal.h"
#include "gb_error.h"
#include "gb_integrate_internal.h"
#include "gb_vec.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

_Static_assert(GB_LYAPUNOV_MAX_EXPONENTS <= GB_INTEGRATE_TANGENT_MAX, "one RK4 step carries every tangent vector");

/* ---------------------------------------------------------------- a Gömböc as a pair system */

/* The pair's separation: the rotation and ω (the tangent's GB_STATE_TANGENT), then, where the body may fly,
 * the centroid's height and velocity (the state's translation). */
enum { PAIR_ROTATION = GB_STATE_TANGENT, PAIR_TRANSLATION = GB_STATE_POSITION - GB_STATE_ZETA, /* ζ and v, not the
       * position on the plane (which no force depends on) nor the friction's work */
       PAIR_ALL = PAIR_ROTATION + PAIR_TRANSLATION };

struct gb_lyapunov_body {
    gb_dynamics *dynamics[2];
    gb_integrate_session *session[2];
    double y[2][GB_STATE_SIZE];
    double period, omega_scale;
    int translation; /* the unilateral law: the separation has the centroid's height and velocity too */
    int stepped;     /* begun time-stepping (a run handed over is stepped while it is: gb_dynamics_stepped) */
    gb_integrate_sample sample; /* the reference's samples (gb_lyapunov_body_observe) */
    void *sample_context;
    /* the variational estimator's own RK4 stepping of the reference */
    gb_integrator method;
    size_t steps_per_period, tangent_steps;
    size_t saltations, unlocated, grazing, jumps;
    gb_dynamics_context *context; /* the pair's own, when the caller named none */
};

int gb_lyapunov_body_create_in(const gb_surface *surface, const gb_dynamics_def *dynamics, gb_dynamics_context *context,
                               const gb_integrate_def *integrate, const double R0[9], const double omega0[3],
                               double omega_scale, gb_lyapunov_body **out)
{
    *out = NULL;
    if (!(isfinite(omega_scale) && omega_scale > 0.0))
        return gb_error_set(GB_EDOM, "omega_scale = %g is out of range (allowed: finite, > 0)", omega_scale);
    gb_lyapunov_body *b = calloc(1, sizeof *b);
    if (!b) return gb_error_set(GB_ENOMEM, "out of memory for a Lyapunov pair");
    b->period = gb_forcing_period(&dynamics->forcing);
    b->method = integrate->method;
    b->steps_per_period = integrate->steps_per_period;
    b->omega_scale = omega_scale;
    const gb_dynamics_law *law = gb_dynamics_law_of(dynamics->contact_law, dynamics->friction);
    b->translation = law && law->translates;
    int status = GB_OK;
    /* the two share one body (mass properties, grid, hull, atlas) through the caller's context or their own */
    if (!context) status = gb_dynamics_context_create(&b->context), context = b->context;
    b->stepped = integrate->strategy == GB_STRATEGY_TIME_STEPPING;
    for (int k = 0; k < 2 && !status; k++) {
        status = gb_dynamics_create_in(surface, dynamics, context, &b->dynamics[k]);
        /* time-stepping: placed as the first step's problem finds it, no mode's start (as gb_run) */
        if (!status && b->stepped) status = gb_dynamics_stepping_prepare(b->dynamics[k]);
        if (!status) status = gb_dynamics_init_or_hand_over(b->dynamics[k], 0.0, R0, omega0, b->y[k], integrate->hand_over);
        if (!status) status = gb_integrate_begin(b->dynamics[k], integrate, 0.0, &b->session[k]);
    }
    if (status) {
        gb_lyapunov_body_free(b);
        return status;
    }
    if (integrate->hand_over) gb_integrate_lead(b->session[1], b->session[0]);
    *out = b;
    return GB_OK;
}

void gb_lyapunov_body_free(gb_lyapunov_body *body)
{
    if (!body) return;
    gb_integrate_end(body->session[0]);
    gb_integrate_end(body->session[1]);
    gb_dynamics_free(body->dynamics[1]);
    gb_dynamics_free(body->dynamics[0]);
    gb_dynamics_context_free(body->context); /* last: both may use what it holds */
    free(body);
}

int gb_lyapunov_body_create(const gb_surface *surface, const gb_dynamics_def *dynamics, const gb_integrate_def *integrate,
                            const double R0[9], const double omega0[3], double omega_scale, gb_lyapunov_body **out)
{
    return gb_lyapunov_body_create_in(surface, dynamics, NULL, integrate, R0, omega0, omega_scale, out);
}

gb_dynamics *gb_lyapunov_body_dynamics(gb_lyapunov_body *body) { return body->dynamics[0]; }
const double *gb_lyapunov_body_state(const gb_lyapunov_body *body) { return body->y[0]; }
const gb_integrate_stats *gb_lyapunov_body_stats(const gb_lyapunov_body *body, int which)
{
    return gb_integrate_session_stats(body->session[which ? 1 : 0]);
}

void gb_lyapunov_body_observe(gb_lyapunov_body *body, gb_integrate_sample sample, void *context)
{
    body->sample = sample;
    body->sample_context = context;
}

static int body_advance(void *context, int which, double t, double interval)
{
    gb_lyapunov_body *b = context;
    gb_integrate_session *session = b->session[which];
    if (fabs(gb_integrate_time(session) - t) > 1e-9 * b->period)
        return gb_error_set(GB_EINVAL, "trajectory %d is at t = %.17g, asked to advance from t = %.17g", which,
                            gb_integrate_time(session), t);
    const size_t steps = gb_integrate_steps_for(session, interval / b->period);
    const int status = which == 0 ? gb_integrate_advance(session, steps, b->y[0], b->sample, b->sample_context)
                                  : gb_integrate_advance(session, steps, b->y[1], NULL, NULL);
    if (!status && gb_integrate_stopped(session))
        return gb_error_set(GB_EINVAL, "the reference run was stopped by its sampler at t = %.17g",
                            gb_integrate_time(session));
    return status;
}

static int body_separation(void *context, double *e)
{
    gb_lyapunov_body *b = context;
    const double *qa = b->y[0] + GB_STATE_Q, *qb = b->y[1] + GB_STATE_Q;
    const double na = sqrt(qa[0] * qa[0] + qa[1] * qa[1] + qa[2] * qa[2] + qa[3] * qa[3]);
    const double conj[4] = {qa[0] / na, -qa[1] / na, -qa[2] / na, -qa[3] / na};
    double dq[4];
    gb_vec_quaternion_product(conj, qb, dq);
    const double sign = dq[0] < 0.0 ? -1.0 : 1.0; /* q and −q are the same attitude */
    const double v = sqrt(dq[1] * dq[1] + dq[2] * dq[2] + dq[3] * dq[3]);
    const double angle = 2.0 * atan2(v, sign * dq[0]);
    for (int k = 0; k < 3; k++) e[k] = v > 0.0 ? angle * sign * dq[k + 1] / v : 0.0;
    for (int k = 0; k < 3; k++) e[3 + k] = (b->y[1][GB_STATE_OMEGA + k] - b->y[0][GB_STATE_OMEGA + k]) / b->omega_scale;
    if (!b->translation) return GB_OK;
    gb_dynamics_flight_summary f[2];
    gb_dynamics_sliding_summary sl[2];
    const double t = gb_integrate_time(b->session[0]);
    for (int k = 0; k < 2; k++) {
        gb_dynamics_flight_stats(b->dynamics[k], t, &f[k]);
        gb_dynamics_sliding_stats(b->dynamics[k], t, NULL, &sl[k]);
    }
    memset(e + PAIR_ROTATION, 0, PAIR_TRANSLATION * sizeof *e);
    /* the translation is the body's own in flight and, horizontally, while it slides; stepped in time, always */
    const int stepped = gb_dynamics_stepped(b->dynamics[0]) || gb_dynamics_stepped(b->dynamics[1]);
    if (!stepped && !f[0].flying && !f[1].flying && !sl[0].sliding && !sl[1].sliding) return GB_OK;
    /* the centroid's height and velocity, as the state holds them at its accepted steps */
    const double L = gb_dynamics_mean_radius(b->dynamics[0]), *ya = b->y[0], *yb = b->y[1];
    e[PAIR_ROTATION] = (yb[GB_STATE_ZETA] - ya[GB_STATE_ZETA]) / L;
    for (int k = 0; k < 3; k++)
        e[PAIR_ROTATION + 1 + k] = (yb[GB_STATE_VELOCITY + k] - ya[GB_STATE_VELOCITY + k]) / (b->omega_scale * L);
    return GB_OK;
}

static int body_place(void *context, const double *given)
{
    gb_lyapunov_body *b = context;
    double e[PAIR_ALL];
    memcpy(e, given, (b->translation ? PAIR_ALL : PAIR_ROTATION) * sizeof *e);
    gb_dynamics_flight_summary f;
    gb_dynamics_sliding_summary sl = {0};
    const double t = gb_integrate_time(b->session[0]);
    const int stepped = gb_dynamics_stepped(b->dynamics[0]); /* the copy is put in the reference's strategy below */
    if (b->translation) {
        gb_dynamics_flight_stats(b->dynamics[0], t, &f);
        gb_dynamics_sliding_stats(b->dynamics[0], t, NULL, &sl);
        if (!f.flying && !stepped) {
            /* on the plane the height and velocity follow from the attitude and ω (but for the horizontal
             * velocity of a sliding body): the rotational part takes the rest of the length */
            double all = 0.0, kept = 0.0;
            for (int k = 0; k < PAIR_ALL; k++) {
                const int free = k < PAIR_ROTATION || (sl.sliding && (k == PAIR_ROTATION + 1 || k == PAIR_ROTATION + 2));
                all += e[k] * e[k], kept += free ? e[k] * e[k] : 0.0;
            }
            const double scale = kept > 0.0 ? sqrt(all / kept) : 1.0;
            for (int k = 0; k < PAIR_ROTATION; k++) e[k] *= scale;
            if (sl.sliding) e[PAIR_ROTATION + 1] *= scale, e[PAIR_ROTATION + 2] *= scale;
        }
    }
    const double angle = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    const double s = angle > 0.0 ? sin(0.5 * angle) / angle : 0.5;
    const double dq[4] = {cos(0.5 * angle), s * e[0], s * e[1], s * e[2]};
    memcpy(b->y[1], b->y[0], sizeof b->y[1]);
    gb_vec_quaternion_product(b->y[0] + GB_STATE_Q, dq, b->y[1] + GB_STATE_Q);
    for (int k = 0; k < 3; k++) b->y[1][GB_STATE_OMEGA + k] = b->y[0][GB_STATE_OMEGA + k] + b->omega_scale * e[3 + k];
    const int status = gb_integrate_follow(b->session[1], b->session[0]);
    if (status) return status;
    gb_dynamics_adopt_contact(b->dynamics[1], b->dynamics[0]);
    if (stepped) { /* the height and velocity are the state's own: displaced as they are */
        const double L = gb_dynamics_mean_radius(b->dynamics[0]), scale = b->omega_scale * L;
        b->y[1][GB_STATE_ZETA] += L * e[PAIR_ROTATION];
        for (int k = 0; k < 3; k++) b->y[1][GB_STATE_VELOCITY + k] += scale * e[PAIR_ROTATION + 1 + k];
        return GB_OK;
    }
    if (b->translation && f.flying) {
        const double L = gb_dynamics_mean_radius(b->dynamics[0]), scale = b->omega_scale * L;
        const double *dv = e + PAIR_ROTATION + 1;
        return gb_dynamics_flight_displace(b->dynamics[1], t, L * e[PAIR_ROTATION],
                                           (const double[3]){scale * dv[0], scale * dv[1], scale * dv[2]});
    }
    if (b->translation && sl.sliding) { /* the horizontal velocity, the state's own */
        const double scale = b->omega_scale * gb_dynamics_mean_radius(b->dynamics[0]);
        b->y[1][GB_STATE_VELOCITY] += scale * e[PAIR_ROTATION + 1];
        b->y[1][GB_STATE_VELOCITY + 1] += scale * e[PAIR_ROTATION + 2];
    }
    return GB_OK;
}

gb_lyapunov_pair_system gb_lyapunov_body_pair(const gb_lyapunov_body *body)
{
    return (gb_lyapunov_pair_system){body->translation ? PAIR_ALL : PAIR_ROTATION, body_advance, body_separation, body_place};
}

/* ---------------------------------------------------------------- the variational equation on a Gömböc */

/* Tangent coordinates e = (δθ, δω/Ω) ↔ state displacements dy: δq = ½ q ⊗ (0, δθ), δω = Ω e_ω, δW = 0.
 * Back: δθ = 2 vec(q̄ ⊗ δq)/|q|², which drops the radial part of δq (the norm of q carries no attitude):
 * that projection is applied at every step. */
static void tangent_to_state(const double q[4], double scale, const double *e, double dy[GB_STATE_SIZE])
{
    const double v[4] = {0.0, e[0], e[1], e[2]};
    gb_vec_quaternion_product(q, v, dy);
    for (int k = 0; k < 4; k++) dy[k] *= 0.5;
    for (int k = 0; k < 3; k++) dy[GB_STATE_OMEGA + k] = scale * e[3 + k];
    for (int k = GB_STATE_WORK; k < GB_STATE_SIZE; k++) dy[k] = 0.0; /* W and the translation: not in the tangent */
}

static void state_to_tangent(const double q[4], double scale, const double dy[GB_STATE_SIZE], double *e)
{
    const double n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    const double conj[4] = {q[0], -q[1], -q[2], -q[3]};
    double p[4];
    gb_vec_quaternion_product(conj, dy, p);
    for (int k = 0; k < 3; k++) e[k] = 2.0 * p[k + 1] / n2;
    for (int k = 0; k < 3; k++) e[3 + k] = dy[GB_STATE_OMEGA + k] / scale;
}

/* A·dy at (t, y) by central differences of the vector field (the contact re-solved at both points). */
static int jacobian_times(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double dy[GB_STATE_SIZE],
                          double out[GB_STATE_SIZE])
{
    double size = 0.0, yp[GB_STATE_SIZE], ym[GB_STATE_SIZE], fp[GB_STATE_SIZE], fm[GB_STATE_SIZE];
    for (int i = 0; i < GB_STATE_SIZE; i++) size = fmax(size, fabs(dy[i]));
    if (size == 0.0) {
        memset(out, 0, GB_STATE_SIZE * sizeof *out);
        return GB_OK;
    }
    /* ε|dy| = 1e-6: the contact's Newton solves to ~1e-15, so the difference quotient carries ~1e-9
     * relative noise, and the O(ε²) truncation is ~1e-12 */
    const double eps = 1e-6 / size;
    for (int i = 0; i < GB_STATE_SIZE; i++) yp[i] = y[i] + eps * dy[i], ym[i] = y[i] - eps * dy[i];
    int status = gb_dynamics_rhs(d, t, yp, fp);
    if (!status) status = gb_dynamics_rhs(d, t, ym, fm);
    for (int i = 0; !status && i < GB_STATE_SIZE; i++) out[i] = (fp[i] - fm[i]) / (2.0 * eps);
    return status;
}

/* One classical RK4 step of size h of the reference and of k state displacements Y (k × 8, in place):
 * the RK4 discretisation of (ẏ = f, Ẏ = A(t) Y), eq 75. */
static int jacobian_along(void *context, gb_dynamics *d, double t, const double y[GB_STATE_SIZE],
                          const double dy[GB_STATE_SIZE], double out[GB_STATE_SIZE])
{
    (void)context;
    return jacobian_times(d, t, y, dy, out);
}

/* The reference y and k tangent vectors Y over one RK4 step, in place (the library's one RK4). */
static int tangent_rk4(gb_dynamics *d, double t, double h, double y[GB_STATE_SIZE], size_t k, double *Y)
{
    return gb_integrate_rk4_step(d, t, h, y, y, k, Y, jacobian_along, NULL, NULL);
}

/* The gap g(y) = Δh between the current branch and `other` (eq 39), differentiated along dy. */
static int gap_along(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other,
                     const double dy[GB_STATE_SIZE], double *derivative)
{
    double size = 0.0, yp[GB_STATE_SIZE], ym[GB_STATE_SIZE], gp, gm;
    for (int i = 0; i < GB_STATE_SIZE; i++) size = fmax(size, fabs(dy[i]));
    if (size == 0.0) return *derivative = 0.0, GB_OK;
    const double eps = 1e-6 / size;
    for (int i = 0; i < GB_STATE_SIZE; i++) yp[i] = y[i] + eps * dy[i], ym[i] = y[i] - eps * dy[i];
    gb_contact_point here;
    int status = gb_dynamics_branch_gap(d, t, yp, other, &gp, &here);
    if (!status) status = gb_dynamics_branch_gap(d, t, ym, other, &gm, &here);
    if (!status) *derivative = (gp - gm) / (2.0 * eps);
    return status;
}

/* A located switch inside the step (t, y) → t + h onto `other`: the time where Δh = 0 by the Illinois
 * method on the step fraction (the reference alone), then the tangent step to it on the old branch,
 * the saltation Y ← Y + (f⁺ − f⁻)(∇g·Y)/(∇g·f⁻) there, and the rest of the step on the new branch. */
static int tangent_switch_step(gb_lyapunov_body *b, double t, double h, double y[GB_STATE_SIZE], size_t k, double *Y,
                               const gb_contact_point *other)
{
    gb_dynamics *d = b->dynamics[0];
    /* The switch time by the library's one locator (the reference alone). No crossing inside the step
     * (the other branch lower already at its start, or only at its end, born or lost in a fold, where Δh
     * jumps): switch at that end, and count it. */
    gb_integrate_switch at;
    int status = gb_integrate_locate_switch(d, t, h, y, other, &at, NULL);
    if (status) return status;
    const double a = at.fraction;
    if (!at.crossed) b->jumps++;
    gb_contact_point there;
    /* To the switch on the old branch. */
    if (a > 0.0) status = tangent_rk4(d, t, a * h, y, k, Y);
    if (status) return status;
    double gap, f_old[GB_STATE_SIZE], f_new[GB_STATE_SIZE], g_flow;
    status = gb_dynamics_branch_gap(d, t + a * h, y, other, &gap, &there);
    if (!status) status = gb_dynamics_rhs(d, t + a * h, y, f_old);
    if (!status) status = gap_along(d, t + a * h, y, &there, f_old, &g_flow);
    double g_dir[GB_LYAPUNOV_MAX_EXPONENTS];
    for (size_t j = 0; j < k && !status; j++) status = gap_along(d, t + a * h, y, &there, Y + j * GB_STATE_SIZE, &g_dir[j]);
    if (status) return status;
    status = gb_dynamics_switch_to(d, t + a * h, y, &there); /* held: y unchanged (unilateral: tangent_impact_step) */
    if (!status) status = gb_dynamics_rhs(d, t + a * h, y, f_new);
    if (status) return status;
    if (g_flow != 0.0 && isfinite(g_flow)) {
        for (size_t j = 0; j < k; j++)
            for (int i = 0; i < GB_STATE_SIZE; i++) Y[j * GB_STATE_SIZE + i] += (f_new[i] - f_old[i]) * g_dir[j] / g_flow;
        b->saltations++;
    } else {
        b->grazing++;
    }
    return a < 1.0 ? tangent_rk4(d, t + a * h, (1.0 - a) * h, y, k, Y) : GB_OK;
}

/* The event function g(t, y) (gb_dynamics_branch_gap) differentiated along time at fixed y: zero for a
 * branch gap, not for the two-point mode's normal forces, which move with g_eff(t). */
static int gap_rate(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other, double *rate)
{
    const double dt = 1e-7 * (2.0 * M_PI / gb_dynamics_get_def(d)->forcing.omega);
    double gp, gm;
    gb_contact_point here;
    int status = gb_dynamics_branch_gap(d, t + dt, y, other, &gp, &here);
    if (!status) status = gb_dynamics_branch_gap(d, t - dt, y, other, &gm, &here);
    if (!status) *rate = (gp - gm) / (2.0 * dt);
    return status;
}

/* The jump map G (gb_dynamics_jump) differentiated along dy at y: DG·dy by central differences. */
static int jump_along(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other,
                      const double dy[GB_STATE_SIZE], double out[GB_STATE_SIZE])
{
    double size = 0.0, yp[GB_STATE_SIZE], ym[GB_STATE_SIZE], gp[GB_STATE_SIZE], gm[GB_STATE_SIZE];
    for (int i = 0; i < GB_STATE_SIZE; i++) size = fmax(size, fabs(dy[i]));
    if (size == 0.0) return memset(out, 0, GB_STATE_SIZE * sizeof *out), GB_OK;
    const double eps = 1e-6 / size;
    for (int i = 0; i < GB_STATE_SIZE; i++) yp[i] = y[i] + eps * dy[i], ym[i] = y[i] - eps * dy[i];
    int status = gb_dynamics_jump(d, t, yp, other, gp);
    if (!status) status = gb_dynamics_jump(d, t, ym, other, gm);
    for (int i = 0; !status && i < GB_STATE_SIZE; i++) out[i] = (gp[i] - gm[i]) / (2.0 * eps);
    return status;
}

/* Under the unilateral law, a change of contact inside the step (t, y) → t + h onto `other`, and every one
 * after it inside the same step (as gb_integrate locates them): at each, the state jumps by the impact
 * map G (ω changes; a lift leaves it), and the tangent vectors by the saltation of a jump,
 *   Y ← DG·Y + (f⁺ − DG·f⁻)(∇g·Y)/(∇g·f⁻ + ∂g/∂t),
 * with DG by central differences of gb_dynamics_jump and g the event's own function. */
static int tangent_impact_step(gb_lyapunov_body *b, double t, double h, double y[GB_STATE_SIZE], size_t k, double *Y,
                               const gb_contact_point *other)
{
    enum { S = GB_STATE_SIZE };
    gb_dynamics *d = b->dynamics[0];
    double tc = t, hc = h;
    gb_contact_point next = *other;
    for (int events = 0; events < GB_INTEGRATE_EVENTS_PER_STEP_MAX; events++) {
        gb_integrate_switch at;
        int status = events ? gb_integrate_locate_next(d, tc, hc, y, &next, &at, NULL)
                            : gb_integrate_locate_switch(d, tc, hc, y, &next, &at, NULL);
        if (status) return status;
        const double a = at.fraction, te = tc + a * hc;
        if (!at.crossed) b->jumps++;
        if (a > 0.0) status = tangent_rk4(d, tc, a * hc, y, k, Y);
        gb_contact_point there;
        double gap, f_old[S], f_new[S], g_flow = 0.0, g_time = 0.0, g_dir[GB_LYAPUNOV_MAX_EXPONENTS];
        double Gf[S], GY[GB_LYAPUNOV_MAX_EXPONENTS][S];
        if (!status) status = gb_dynamics_branch_gap(d, te, y, &next, &gap, &there);
        if (!status) status = gb_dynamics_rhs(d, te, y, f_old);
        if (!status) status = gap_along(d, te, y, &there, f_old, &g_flow);
        if (!status) status = gap_rate(d, te, y, &there, &g_time);
        for (size_t j = 0; j < k && !status; j++) status = gap_along(d, te, y, &there, Y + j * S, &g_dir[j]);
        if (!status) status = jump_along(d, te, y, &there, f_old, Gf);
        for (size_t j = 0; j < k && !status; j++) status = jump_along(d, te, y, &there, Y + j * S, GY[j]);
        if (!status) status = gb_dynamics_switch_to(d, te, y, &there); /* the impact: ω in y jumps */
        if (!status) status = gb_dynamics_rhs(d, te, y, f_new);
        if (status) return status;
        const double rate = g_flow + g_time;
        if (rate != 0.0 && isfinite(rate)) {
            for (size_t j = 0; j < k; j++)
                for (int i = 0; i < S; i++) Y[j * S + i] = GY[j][i] + (f_new[i] - Gf[i]) * g_dir[j] / rate;
            b->saltations++;
        } else {
            b->grazing++;
        }
        if (a >= 1.0) return GB_OK;
        /* the rest of the step, and the next change inside it, if any */
        double ye[S], Ye[GB_LYAPUNOV_MAX_EXPONENTS * S];
        memcpy(ye, y, sizeof ye);
        memcpy(Ye, Y, k * S * sizeof *Y);
        status = tangent_rk4(d, te, (1.0 - a) * hc, y, k, Y);
        int found = 0;
        if (!status) status = gb_dynamics_switch_pending(d, t + h, y, &next, &found);
        if (status || !found) return status;
        memcpy(y, ye, sizeof ye);
        memcpy(Y, Ye, k * S * sizeof *Y);
        tc = te, hc = (1.0 - a) * hc;
    }
    return gb_error_set(GB_ENUMERIC, "more than %d changes of contact inside the step from t = %.9g",
                        GB_INTEGRATE_EVENTS_PER_STEP_MAX, t);
}

static int tangent_steps(gb_lyapunov_body *b, double t, double interval, size_t k, double *vectors)
{
    gb_dynamics *d = b->dynamics[0];
    double *y = b->y[0];
    const size_t steps = (size_t)llround(interval / b->period * (double)b->steps_per_period);
    const double h = gb_forcing_step(&gb_dynamics_get_def(d)->forcing, b->steps_per_period);
    double Y[GB_LYAPUNOV_MAX_EXPONENTS * GB_STATE_SIZE];
    if (fabs(t - (double)b->tangent_steps * h) > 1e-9 * b->period)
        return gb_error_set(GB_EINVAL, "the variational reference is at t = %.17g, asked to advance from t = %.17g",
                            (double)b->tangent_steps * h, t);
    for (size_t n = 0; n < steps; n++, b->tangent_steps++) {
        const double tn = (double)b->tangent_steps * h;
        for (size_t j = 0; j < k; j++) tangent_to_state(y + GB_STATE_Q, b->omega_scale, vectors + GB_STATE_TANGENT * j, Y + j * GB_STATE_SIZE);
        double start[GB_STATE_SIZE], Ystart[GB_LYAPUNOV_MAX_EXPONENTS * GB_STATE_SIZE];
        memcpy(start, y, sizeof start);
        memcpy(Ystart, Y, k * GB_STATE_SIZE * sizeof *Y);
        int status = tangent_rk4(d, tn, h, y, k, Y);
        gb_contact_point other;
        int found = 0;
        if (!status) status = gb_dynamics_switch_pending(d, tn + h, y, &other, &found);
        if (!status && found) {
            memcpy(y, start, sizeof start);
            memcpy(Y, Ystart, k * GB_STATE_SIZE * sizeof *Y);
            status = gb_dynamics_get_law(d)->impacts /* a change of contact is a jump with its saltation */
                         ? tangent_impact_step(b, tn, h, y, k, Y, &other)
                         : tangent_switch_step(b, tn, h, y, k, Y, &other);
        }
        const size_t before = gb_dynamics_switch_count(d);
        double drift;
        if (!status) status = gb_dynamics_accept(d, tn + h, y, &drift);
        if (status) return status;
        b->unlocated += gb_dynamics_switch_count(d) - before;
        for (size_t j = 0; j < k; j++) state_to_tangent(y + GB_STATE_Q, b->omega_scale, Y + j * GB_STATE_SIZE, vectors + GB_STATE_TANGENT * j);
    }
    return GB_OK;
}

static int tangent_advance(void *context, double t, double interval)
{
    return tangent_steps(context, t, interval, 0, NULL);
}

static int tangent_advance_vectors(void *context, double t, double interval, size_t k, double *vectors)
{
    return tangent_steps(context, t, interval, k, vectors);
}

gb_lyapunov_tangent_system gb_lyapunov_body_tangent(void)
{
    return (gb_lyapunov_tangent_system){GB_STATE_TANGENT, tangent_advance, tangent_advance_vectors};
}

int gb_lyapunov_body_tangent_ready(const gb_lyapunov_body *body)
{
    const gb_dynamics_def *def = gb_dynamics_get_def(body->dynamics[0]);
    if (body->stepped)
        return gb_error_set(GB_EINVAL, "the variational estimator follows the event-driven strategy's events and jumps, "
                            "and time is stepped here (allowed: the pair estimator with time-stepping)");
    if ((def->contact != GB_CONTACT_MODEL_CONTINUOUS && !gb_dynamics_get_law(body->dynamics[0])->several_events_per_step) ||
        body->method != GB_INTEGRATOR_RK4)
        return gb_error_set(GB_EINVAL,
                            "the variational estimator needs RK4 and continuous contact or the unilateral law (got %s, %s, "
                            "%s): a held grid contact makes the vector field jump at node changes that are not located, "
                            "where no saltation can be applied", gb_contact_model_name(def->contact),
                            gb_integrate_name(body->method), gb_dynamics_contact_law_name(def->contact_law));
    if (body->tangent_steps == 0 && gb_integrate_time(body->session[0]) != 0.0)
        return gb_error_set(GB_EINVAL, "the body's reference has already been advanced by the pair estimator");
    return GB_OK;
}

size_t gb_lyapunov_body_tangent_jumps(const gb_lyapunov_body *body) { return body->jumps; }

void gb_lyapunov_body_tangent_counts(const gb_lyapunov_body *body, size_t *saltations, size_t *unlocated, size_t *grazing)
{
    *saltations = body->saltations;
    *unlocated = body->unlocated;
    *grazing = body->grazing;
}
