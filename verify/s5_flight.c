/* A plane that can only push (2 of 2): lift-off, flight, landing and restitution.
 *
 * Oracles, each in closed form or a law of mechanics:
 * - the one-point impact of a rough plane (gb_impact_rough_point) against Moreau's law where both apply,
 *   and in any case: the angular momentum about the point kept, T⁺ ≤ T⁻, the slip stopped;
 * - a ball dropped from height H on a still plane: landing k at t₁(1 + 2e + … + 2e^(k−1)), t₁ = √(2H/g),
 *   rebound speeds e^k √(2gH), and the bouncing ended by the Zeno rule no later than t∞ = t₁(1 + e)/(1 − e)
 *   and no earlier than t∞ − h/(1 − e) (h the step: the rule takes as plastic a rebound that would return
 *   within one step, and the flights it removes sum to less than h/(1 − e));
 * - the bouncing ball on a plane with g_eff = g + a₁ cos ωt: the period-1 orbit (one impact a period) hits
 *   where the plane's velocity (a₁/ω) sin ωt is (πg/ω)(1 − e)/(1 + e), at ωt = π − arcsin(Γ₁/Γ), Γ = a₁/g,
 *   Γ₁ = π(1 − e)/(1 + e). The exact impact map's Jacobian there has determinant e² and trace
 *   1 + e² − (1 + e)² √(Γ² − Γ₁²), so the orbit is stable for Γ₁ < Γ < Γ₂ = √(Γ₁² + (2(1 + e²)/(1 + e)²)²).
 *   The check finds both edges by bisection on runs of the sphere started near the orbit;
 * - a ball dropped on Table 1's plane read in units of g (e = 0.5): its landings in closed form (the ballistic
 *   height in the plane's frame, references/siconos/bouncing_ball.py), and the same drop in another engine,
 *   Siconos's Moreau–Jean time stepping, whose landings converge to them at first order in its step;
 * - a Gömböc dropped with spin on a still plane: at every landing the angular momentum about the landing
 *   point is kept and the momentum jump is the plane's impulse; in flight the horizontal velocity is
 *   constant; the ledger E − E0 − W + L closes;
 * - Table 1 in units of g (eq 61), whose support accelerates downward faster than gravity for 27.6 % of a
 *   period: with e = 0 and e = 0.5 the run goes through every lift-off and landing, the ledger closes to
 *   the integration's accuracy (it converges with the step), and what the body does is measured. */
#include "gb_case.h"
#include "gb_check.h"
#include "gb_dynamics.h"
#include "gb_error.h"
#include "gb_impact.h"
#include "gb_integrate.h"
#include "gb_massprops.h"
#include "gb_run.h"
#include "gb_surface_internal.h"
#include "verify_sections.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double UP[3] = {0.0, 0.0, 1.0};

static void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1], out[1] = a[2] * b[0] - a[0] * b[2], out[2] = a[0] * b[1] - a[1] * b[0];
}

static double norm3(const double a[3]) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

/* I ω + m (G − q) × v */
static void momentum_about(const gb_impact_body *b, const double q[3], const double v[3], const double w[3], double out[3])
{
    double l[3];
    cross((const double[3]){-q[0], -q[1], -q[2]}, v, l);
    for (int i = 0; i < 3; i++) out[i] = b->inertia[i][0] * w[0] + b->inertia[i][1] * w[1] + b->inertia[i][2] * w[2] + b->mass * l[i];
}

static double uniform(unsigned long long *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) / 9007199254740992.0;
}

/* ---- the one-point impact of a rough plane ----------------------------------------------------------- */

static void test_rough_point(void)
{
    unsigned long long seed = 20261125ULL;
    double worst_momentum = 0.0, worst_slip = 0.0, worst_moreau = 0.0, worst_kelvin = 0.0, worst_gain = -INFINITY;
    size_t compared = 0, slip_only = 0, moreau_refused = 0, cases = 0;
    int bad = 0;
    for (int n = 0; n < 20000 && !bad; n++) {
        /* a random body: a box of random half-sides, turned; a point on its surface below the centroid */
        const double a = 0.2 + uniform(&seed), c = 0.2 + uniform(&seed), h = 0.2 + uniform(&seed), m = 0.5 + 2 * uniform(&seed);
        gb_impact_body body = {m, {{m * (c * c + h * h) / 3.0, 0, 0}, {0, m * (a * a + h * h) / 3.0, 0}, {0, 0, m * (a * a + c * c) / 3.0}}};
        const double point[3] = {(2 * uniform(&seed) - 1) * a, (2 * uniform(&seed) - 1) * c, -h};
        double v[3], w[3];
        for (int i = 0; i < 3; i++) v[i] = 2 * uniform(&seed) - 1, w[i] = 4 * uniform(&seed) - 2;
        const double e = n % 3 == 0 ? 0.0 : uniform(&seed);
        double u[3];
        cross(w, point, u);
        for (int i = 0; i < 3; i++) u[i] += v[i];
        if (u[2] >= -1e-3) continue; /* the point approaches the plane */
        cases++;
        gb_impact_result r, s;
        if (gb_impact_rough_point(&body, UP, e, point, v, w, &r)) {
            bad = 1;
            break;
        }
        double before[3], after[3], ua[3];
        momentum_about(&body, point, v, w, before);
        momentum_about(&body, point, r.v, r.omega, after);
        for (int i = 0; i < 3; i++) worst_momentum = fmax(worst_momentum, fabs(after[i] - before[i]) / norm3(before));
        cross(r.omega, point, ua);
        for (int i = 0; i < 3; i++) ua[i] += r.v[i];
        const double speed = norm3(u);
        worst_slip = fmax(worst_slip, hypot(ua[0], ua[1]) / speed);
        worst_gain = fmax(worst_gain, (r.energy_after - r.energy_before) / r.energy_before);
        if (r.holds[0]) {
            /* compression happened: the point leaves at e times its approach after the slip stopped */
            if (e == 0.0) {
                double dv[3], dw[3];
                for (int i = 0; i < 3; i++) dv[i] = r.v[i] - v[i], dw[i] = r.omega[i] - w[i];
                worst_kelvin = fmax(worst_kelvin, fabs(r.energy_before - r.energy_after - gb_impact_energy(&body, dv, dw)) /
                                                      r.energy_before);
            }
            if (gb_impact_solve(&body, UP, e, (const double(*)[3])&point[0], 1, v, w, &s) == GB_OK && s.holds[0] && e == 0.0) {
                compared++;
                for (int i = 0; i < 3; i++)
                    worst_moreau = fmax(worst_moreau, fmax(fabs(s.v[i] - r.v[i]), fabs(s.omega[i] - r.omega[i])) / speed);
            }
        } else {
            slip_only++;
            bad |= !(r.normal_impulse[0] == 0.0 && isinf(r.friction_needed) && ua[2] >= -1e-12 * speed);
            moreau_refused += gb_impact_solve(&body, UP, e, (const double(*)[3])&point[0], 1, v, w, &s) != GB_OK;
            gb_error_clear();
        }
    }
    gb_check cm = {"3, 5", "-", "one-point rough impact (gb_impact_rough_point), random boxes: the angular momentum about the point",
                   "kept (the plane's impulse acts at the point), max relative change", "1e-13: rounding of 3 x 3 solves"};
    gb_check_close(&cm, bad ? NAN : worst_momentum, 0.0, 0.0, 1e-13);
    gb_check cs = {"3, 5", "-", "one-point rough impact: the point's slip after", "0, relative to its speed before (rough: the slip stops)",
                   "1e-13: rounding"};
    gb_check_close(&cs, bad ? NAN : worst_slip, 0.0, 0.0, 1e-13);
    gb_check ce = {"3, 5", "-", "one-point rough impact: (T+ - T-) / T-, max", "<= 0: an impact never makes energy",
                   "1e-14: rounding of the energies"};
    gb_check_true(&ce, !bad && worst_gain <= 1e-14, "max (T+ - T-)/T- = %.3g over %zu impacts", worst_gain, cases);
    gb_check ck = {"3, 5", "-", "one-point rough impact, e = 0, compressing: T- - T+ against the energy of the velocity jump",
                   "Kelvin's theorem (the point ends at rest), max relative", "1e-12: rounding"};
    gb_check_close(&ck, bad ? NAN : worst_kelvin, 0.0, 0.0, 1e-12);
    gb_check cc = {"3, 5", "-", "one-point rough impact against Moreau's law (gb_impact_solve, one held point), e = 0",
                   "the same velocities where Moreau's law holds the point with a pushing impulse",
                   "1e-12 of the point's speed: rounding of two routes to the same impulse"};
    gb_check_close(&cc, bad || !compared ? NAN : worst_moreau, 0.0, 0.0, 1e-12);
    gb_check cn = {"3, 5", "-", "one-point rough impact: where stopping the slip leaves the point moving away",
                   "no normal impulse, friction needed infinite, the point leaves; counted, and Moreau's law with a held "
                   "point refused there (it would need the plane to pull)", "exact"};
    gb_check_true(&cn, !bad && slip_only > 0, "%zu of %zu impacts end when the slip stops (Moreau's law refused %zu of them); "
                  "%zu compared with Moreau's law", slip_only, cases, moreau_refused, compared);
}

/* ---- a sphere ----------------------------------------------------------------------------------------- */

/* Landings recorded by the impact sink. */
typedef struct landings {
    size_t n, cap;
    double *t, *v_before, *v_after; /* times; the normal approach and rebound speeds of the point */
    int *contacts_after;
    size_t lift_offs;
    gb_impact_body body;
    double worst_momentum, worst_impulse, worst_gain;
    /* in flight: the horizontal velocity (inertial) at the flight's first sample, and the largest change */
    int in_flight;
    double horizontal[2], worst_horizontal;
    double residual_max;
    /* the ledger's change over each step: over steps with a change of contact (an event since the last sample)
     * and over steps without */
    int event_since, have_residual;
    double last_residual, step_event_max, step_smooth_max;
    gb_dynamics *d;
    int status;
} landings;

static int landing_sink(void *context, const gb_dynamics_impact *e)
{
    landings *l = context;
    l->event_since = 1;
    if (e->kind == GB_DYNAMICS_IMPACT_LANDING) l->in_flight = 0; /* a new flight begins after a bounce */
    if (e->kind == GB_DYNAMICS_IMPACT_LIFT_OFF) {
        l->lift_offs++;
        return GB_OK;
    }
    if (e->kind != GB_DYNAMICS_IMPACT_LANDING) return GB_OK;
    if (l->n == l->cap) {
        l->cap = l->cap ? 2 * l->cap : 64;
        l->t = realloc(l->t, l->cap * sizeof *l->t);
        l->v_before = realloc(l->v_before, l->cap * sizeof *l->v_before);
        l->v_after = realloc(l->v_after, l->cap * sizeof *l->v_after);
        l->contacts_after = realloc(l->contacts_after, l->cap * sizeof *l->contacts_after);
        if (!l->t || !l->v_before || !l->v_after || !l->contacts_after) return gb_error_set(GB_ENOMEM, "out of memory");
    }
    /* the point's speed along the centroid-to-point line's complement: its velocity v + ω × r */
    double ub[3], ua[3], before[3], after[3], dv[3];
    cross(e->omega_before, e->new_point, ub);
    cross(e->omega_after, e->new_point, ua);
    for (int i = 0; i < 3; i++) ub[i] += e->v_before[i], ua[i] += e->v_after[i], dv[i] = e->v_after[i] - e->v_before[i];
    l->t[l->n] = e->t;
    l->v_before[l->n] = norm3(ub);
    l->v_after[l->n] = norm3(ua);
    l->contacts_after[l->n] = e->contacts_after;
    l->n++;
    momentum_about(&l->body, e->new_point, e->v_before, e->omega_before, before);
    momentum_about(&l->body, e->new_point, e->v_after, e->omega_after, after);
    /* relative to the momentum before, or, where that is nearly 0, to m |v| times a 1 mm arm (a thousandth of
     * the body's size: a momentum the landing's impulse could change by far more than rounding) */
    const double scale = fmax(norm3(before), l->body.mass * norm3(e->v_before) * 1e-3);
    for (int i = 0; i < 3; i++) l->worst_momentum = fmax(l->worst_momentum, fabs(after[i] - before[i]) / scale);
    const double impulse = hypot(e->normal_impulse, e->tangential_impulse);
    l->worst_impulse = fmax(l->worst_impulse, fabs(l->body.mass * norm3(dv) - impulse) / fmax(impulse, 1e-300));
    l->worst_gain = fmax(l->worst_gain, e->kinetic_after - e->kinetic_before);
    return GB_OK;
}

static int landing_sample(void *context, double t, const double y[GB_STATE_SIZE])
{
    landings *l = context;
    gb_dynamics_observables o;
    l->status = gb_dynamics_observe(l->d, t, y, &o);
    if (l->status) return 1;
    l->residual_max = fmax(l->residual_max, fabs(o.residual));
    if (l->have_residual) {
        const double step = fabs(o.residual - l->last_residual);
        if (l->event_since) l->step_event_max = fmax(l->step_event_max, step);
        else l->step_smooth_max = fmax(l->step_smooth_max, step);
    }
    l->have_residual = 1, l->last_residual = o.residual, l->event_since = 0;
    if (o.contacts == 0) {
        if (!l->in_flight) l->horizontal[0] = o.velocity[0], l->horizontal[1] = o.velocity[1];
        l->worst_horizontal = fmax(l->worst_horizontal, hypot(o.velocity[0] - l->horizontal[0], o.velocity[1] - l->horizontal[1]));
    }
    l->in_flight = o.contacts == 0;
    return 0;
}

static void landings_free(landings *l)
{
    free(l->t), free(l->v_before), free(l->v_after), free(l->contacts_after);
    memset(l, 0, sizeof *l);
}

/* A unilateral run of `body` (morphology, beta) on the plane of `forcing` for `periods` periods, 160 steps a
 * period, the Zeno rule's settle time one step, from attitude R0 at height H with velocity v0 and spin w0. */
static int flight_run(const char *morphology, double beta, const gb_forcing *forcing, double e, double periods, const double R0[9],
                      double H, const double v0[3], const double w0[3], landings *l, size_t steps_per_period)
{
    gb_dynamics_def def = gb_dynamics_default_def();
    def.variant = GB_VARIANT_ROLLING;
    def.contact = GB_CONTACT_MODEL_CONTINUOUS;
    def.contact_law = GB_CONTACT_LAW_UNILATERAL;
    def.damping = 0.0;
    def.forcing = *forcing;
    def.restitution = e;
    def.height0 = H;
    memcpy(def.velocity0, v0, sizeof def.velocity0);
    gb_integrate_def idef = gb_integrate_default_def();
    idef.steps_per_period = steps_per_period;
    idef.periods = periods;
    idef.locate_switches = 1;
    def.settle_time = gb_forcing_period(forcing) / (double)steps_per_period;
    const gb_surface *surface = gb_check_body(morphology, beta);
    gb_massprops props;
    gb_massprops_def mdef = gb_massprops_default_def();
    mdef.mass = def.mass;
    double y[GB_STATE_SIZE];
    int status = gb_massprops_compute(surface, &mdef, &props);
    if (!status) status = gb_dynamics_start(surface, &def, R0, w0, &l->d, y);
    if (!status) {
        l->body.mass = def.mass;
        memcpy(l->body.inertia, props.inertia, sizeof l->body.inertia);
        l->worst_gain = -INFINITY;
        gb_dynamics_set_impact_sink(l->d, landing_sink, l);
        gb_integrate_stats stats;
        status = gb_integrate_run(l->d, &idef, 0.0, y, landing_sample, l, &stats);
        if (!status) status = l->status;
    }
    gb_dynamics_free(l->d);
    l->d = NULL;
    return status;
}

/* An attitude whose lowest point is off the chart's poles: a turn of 1.2 rad about x. */
static void tilted(double R[9])
{
    const double c = cos(1.2), s = sin(1.2), M[9] = {1, 0, 0, 0, c, -s, 0, s, c};
    memcpy(R, M, sizeof M);
}

static void test_ball_drop(void)
{
    const double H = 0.5, g = 9.81, t1 = sqrt(2.0 * H / g), rates[3] = {0.0, 0.5, 0.8};
    const gb_forcing still = {g, 0.0, 0.0, 18.0, 0.0};
    const double h = gb_forcing_period(&still) / 160.0, zero[3] = {0, 0, 0};
    double R[9];
    tilted(R);
    for (int k = 0; k < 3; k++) {
        const double e = rates[k], t_inf = t1 * (1.0 + e) / (1.0 - e);
        landings l = {0};
        /* e = 0.5 lands on the (φ, θ) chart's pole (R0 = I), the others off it */
        const double identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        const int status = flight_run("I", 0.0, &still, e, ceil(1.5 * t_inf / gb_forcing_period(&still)), k == 1 ? identity : R,
                                      H, zero, zero, &l, 160);
        const int ran = !status && l.n > 0;
        /* A landing is located where the lowest point is GB_DYNAMICS_LANDING_TOL below the plane: the first
         * one is late by ε/v₀, and each rebound, from ε lower at a speed larger by gε/v, lengthens the next
         * flight by at most 2eε/v_k: the allowed error grows by those terms (plus rounding, 1e-14 s a landing). */
        const double eps = GB_DYNAMICS_LANDING_TOL;
        double worst_time = 0.0, worst_speed = 0.0, expected = t1, speed = sqrt(2.0 * g * H), allowed = 0.0, excess = 0.0;
        allowed = eps / speed;
        for (size_t i = 0; ran && i < l.n; i++) {
            if (l.contacts_after[i]) break; /* the Zeno rule's plastic landing: the bouncing ends */
            allowed += 1e-14;
            worst_time = fmax(worst_time, fabs(l.t[i] - expected));
            excess = fmax(excess, fabs(l.t[i] - expected) / allowed);
            worst_speed = fmax(worst_speed, fabs(l.v_after[i] - e * speed) / sqrt(2.0 * g * H));
            allowed += 2.0 * e * eps / speed;
            speed *= e;
            expected += 2.0 * speed / g;
        }
        char q[240];
        snprintf(q, sizeof q, "ball dropped from H = %g m, e = %g%s: landing times before the bouncing ends", H, e,
                 k == 1 ? " onto the chart's pole" : "");
        gb_check ct = {"-", "-", q, "t_k = t1 (1 + 2e + ... + 2e^(k-1)), t1 = sqrt(2H/g): max |error| / its allowance",
                       "1: the allowance eps/v0 + sum 2 e eps/v_k + 1e-14 s a landing, from the landing tolerance eps = 1e-12 m "
                       "(the flight is in closed form)"};
        if (!gb_check_close(&ct, ran ? excess : NAN, 0.0, 0.0, 1.0)) fprintf(stderr, "max |error| %.3g s\n", worst_time);
        snprintf(q, sizeof q, "ball dropped from H = %g m, e = %g: rebound speeds", H, e);
        gb_check cv = {"-", "-", q, "e^k sqrt(2gH): apex heights e^(2k) H, max |error| / sqrt(2gH)", "1e-12: rounding"};
        gb_check_close(&cv, ran ? worst_speed : NAN, 0.0, 0.0, 1e-12);
        snprintf(q, sizeof q, "ball dropped from H = %g m, e = %g: when the bouncing ends (the Zeno rule)", H, e);
        gb_check cz = {"-", "-", q, "in [t_inf - h/(1 - e), t_inf], t_inf = t1 (1 + e)/(1 - e), h the step (the rule "
                       "removes flights shorter than one step, which sum to less than h/(1 - e))", "the rule's own bound"};
        const double t_end = ran ? l.t[l.n - 1] : NAN;
        gb_check_true(&cz, ran && l.contacts_after[l.n - 1] == 1 && t_end <= t_inf + 1e-12 && t_end >= t_inf - h / (1.0 - e),
                      "%zu landings; at rest from t = %.12g s; t_inf = %.12g s, t_inf - h/(1 - e) = %.12g s", l.n, t_end,
                      t_inf, t_inf - h / (1.0 - e));
        snprintf(q, sizeof q, "ball dropped from H = %g m, e = %g: |E - E0 - W + L| over the run", H, e);
        gb_check cl = {"-", "46-51", q, "the energy ledger closes across flight and landings",
                       "1e-9 J: closed-form flight; the rest on one point is exact"};
        gb_check_close(&cl, ran ? l.residual_max : NAN, 0.0, 0.0, 1e-9);
        landings_free(&l);
    }
}

/* The bouncing ball: the orbit's state at t = 0 (phase 0), relative to the plane, for Γ, e and ω. */
static void orbit_start(double Gamma, double e, double omega, double g, double *H, double *vz)
{
    const double T = 2.0 * M_PI / omega, a1 = Gamma * g, G1 = M_PI * (1.0 - e) / (1.0 + e);
    /* below Γ₁ there is no orbit: start from the one at Γ₁ (a ball at the same height and speed) */
    const double phase = M_PI - asin(fmin(G1 / Gamma, 1.0)), t_hit = phase / omega, tau0 = T - t_hit, u = g * T / 2.0;
    const double s_hit = -a1 / (omega * omega) * cos(phase), s0 = -a1 / (omega * omega);
    *H = s_hit - s0 + u * tau0 - 0.5 * g * tau0 * tau0;
    *vz = u - g * tau0; /* the plane's velocity at phase 0 is 0 */
}

/* Does the ball started 2 % above the orbit lock onto it within `periods`: its last 20 flights last one
 * period to 1e-6 of it and hit at the orbit's phase to 1e-5 rad? */
static int locks(double Gamma, double e, double periods, double *phase_error, double *flight_error, int *status)
{
    const double g = 9.81, omega = 18.0, T = 2.0 * M_PI / omega, zero[3] = {0, 0, 0};
    const gb_forcing plane = {g, Gamma * g, 0.0, omega, 0.0};
    double H, vz, R[9];
    orbit_start(Gamma, e, omega, g, &H, &vz);
    tilted(R);
    landings l = {0};
    *status = flight_run("I", 0.0, &plane, e, periods, R, 1.02 * H, (const double[3]){0.0, 0.0, vz}, zero, &l, 160);
    const double phase = M_PI - asin(fmin(M_PI * (1.0 - e) / (1.0 + e) / Gamma, 1.0));
    *phase_error = *flight_error = INFINITY;
    if (!*status && l.n > 21) {
        *phase_error = *flight_error = 0.0;
        for (size_t i = l.n - 21; i < l.n; i++) {
            const double p = fmod(omega * l.t[i], 2.0 * M_PI);
            *phase_error = fmax(*phase_error, fabs(p - phase));
            if (i > l.n - 21) *flight_error = fmax(*flight_error, fabs(l.t[i] - l.t[i - 1] - T) / T);
        }
    }
    landings_free(&l);
    return *phase_error < 1e-5 && *flight_error < 1e-6;
}

static void test_bouncing_ball(void)
{
    const double e = 0.5, G1 = M_PI * (1.0 - e) / (1.0 + e), q = 2.0 * (1.0 + e * e) / ((1.0 + e) * (1.0 + e));
    const double G2 = sqrt(G1 * G1 + q * q), periods = 300.0;
    int status = GB_OK, s;
    double pe, fe, pe_mid, fe_mid;
    const int mid = locks(0.5 * (G1 + G2), e, periods, &pe_mid, &fe_mid, &s);
    status |= s;
    /* the edges by bisection: locked inside, not outside */
    double lo[2] = {0.9 * G1, 0.5 * (G1 + G2)}, hi[2] = {0.5 * (G1 + G2), 1.1 * G2};
    int outside[2];
    outside[0] = !locks(lo[0], e, periods, &pe, &fe, &s), status |= s;
    outside[1] = !locks(hi[1], e, periods, &pe, &fe, &s), status |= s;
    for (int edge = 0; edge < 2 && !status; edge++)
        for (int it = 0; it < 7 && !status; it++) {
            const double m = 0.5 * (lo[edge] + hi[edge]);
            const int in = locks(m, e, periods, &pe, &fe, &s);
            status |= s;
            if ((edge == 0) == in) hi[edge] = m;
            else lo[edge] = m;
        }
    const double found[2] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])};
    char why[200];
    snprintf(why, sizeof why, "%s", status ? gb_error_message() : "ran");
    gb_check cm = {"-", "-", "bouncing ball, e = 0.5, Gamma midway in the stable range: locks onto the period-1 orbit",
                   "the last 20 impacts at omega t = pi - arcsin(Gamma1/Gamma) (max |error| [rad]), flights of one period",
                   "1e-5 rad: 300 periods at |lambda| = e a period bring a 2 % start within rounding"};
    gb_check_true(&cm, !status && mid && pe_mid < 1e-5 && fe_mid < 1e-6, "phase error %.3g rad, flight error %.3g of T; %s",
                  pe_mid, fe_mid, why);
    gb_check co = {"-", "-", "bouncing ball, e = 0.5: outside the stable range (0.9 Gamma1 and 1.1 Gamma2)",
                   "no lock onto the period-1 orbit", "exact"};
    gb_check_true(&co, !status && outside[0] && outside[1], "locked below: %s, above: %s", outside[0] ? "no" : "yes",
                  outside[1] ? "no" : "yes");
    gb_check c1 = {"-", "-", "bouncing ball, e = 0.5: the lower edge of the stable range found by bisection on runs",
                   "Gamma1 = pi (1 - e)/(1 + e), where the period-1 orbit is born",
                   "3 %: near an edge one eigenvalue of the map approaches 1 in modulus, and a run of 300 periods locks "
                   "only where |lambda|^300 is below the lock test's 1e-6 (the bisection's own width is 0.3 %)"};
    gb_check_close(&c1, status ? NAN : found[0], G1, 0.03, 0.0);
    gb_check c2 = {"-", "-", "bouncing ball, e = 0.5: the upper edge of the stable range found by bisection on runs",
                   "Gamma2 = sqrt(Gamma1^2 + (2 (1 + e^2)/(1 + e)^2)^2), where the orbit loses stability (period doubling)",
                   "3 %: as for the lower edge"};
    gb_check_close(&c2, status ? NAN : found[1], G2, 0.03, 0.0);
}

/* ---- against Siconos: the ball on Table 1's plane in units of g ------------------------------------ */

/* references/siconos/bouncing_ball.json: the ball dropped from 0.2 m (its lowest point) on the plane of Table 1
 * read in units of g, e = 0.5; the landing times in closed form and from Siconos's Moreau-Jean time stepping
 * at T/160 ... T/2560. gomboc runs the same drop (the sphere, R0 = I, continuous contact, 160 steps a period). */
static void siconos_bouncing_case(const cJSON *c)
{
    const cJSON *exact = cJSON_GetObjectItem(c, "closed_form"), *runs = cJSON_GetObjectItem(c, "siconos");
    const int n = cJSON_GetArraySize(exact);
    const cJSON *f = cJSON_GetObjectItem(c, "forcing");
    const gb_forcing plane = {cJSON_GetNumberValue(cJSON_GetObjectItem(f, "g")), cJSON_GetNumberValue(cJSON_GetObjectItem(f, "a1")),
                              cJSON_GetNumberValue(cJSON_GetObjectItem(f, "a2")), cJSON_GetNumberValue(cJSON_GetObjectItem(f, "omega")),
                              cJSON_GetNumberValue(cJSON_GetObjectItem(f, "psi"))};
    const double identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, zero[3] = {0, 0, 0};
    const double e = cJSON_GetNumberValue(cJSON_GetObjectItem(c, "restitution")), H = cJSON_GetNumberValue(cJSON_GetObjectItem(c, "height"));
    landings l = {0};
    /* the 8 landings come within 7.4 periods */
    const int status = gb_forcing_validate(&plane) ? GB_EDOM : flight_run("I", 0.0, &plane, e, 8.0, identity, H, zero, zero, &l, 160);
    double worst = 0.0;
    int compared = 0;
    for (int k = 0; !status && k < n && (size_t)k < l.n; k++, compared++)
        worst = fmax(worst, fabs(l.t[k] - cJSON_GetNumberValue(cJSON_GetObjectItem(cJSON_GetArrayItem(exact, k), "t"))));
    /* the landing is located where the lowest point is GB_DYNAMICS_LANDING_TOL below the plane (late by that
     * over the approach speed, >= 1.7 m/s here); a rebound started that much late moves the next landings by
     * as much again, growing with the flights' sensitivity: 1e-9 s over 8 landings, with room */
    gb_check cg = {"-", "-", "a ball dropped from 0.2 m on Table 1's plane read in units of g, e = 0.5: gomboc's first 8 landing times",
                   "closed form (references/siconos/bouncing_ball.py: the ballistic height in the plane's frame, each root to 1e-14 s)",
                   "1e-9 s: the landing tolerance over the approach speed, carried from landing to landing"};
    gb_check_true(&cg, !status && compared == n && worst <= 1e-9, "%s; %d of %d landings compared, largest difference %.3g s",
                  status ? gb_error_message() : "ran", compared, n, worst);
    landings_free(&l);
    /* Siconos: its landings are step ends, so each is late by up to a step; the largest error over the 8 falls
     * with the step */
    double err[8] = {0}, steps[8] = {0};
    int m = 0;
    const cJSON *run;
    cJSON_ArrayForEach(run, runs) {
        if (m == 8) break;
        const cJSON *times = cJSON_GetObjectItem(run, "landings");
        double e = cJSON_GetArraySize(times) == n ? 0.0 : INFINITY;
        for (int k = 0; k < n && isfinite(e); k++)
            e = fmax(e, fabs(cJSON_GetNumberValue(cJSON_GetArrayItem(times, k)) -
                             cJSON_GetNumberValue(cJSON_GetObjectItem(cJSON_GetArrayItem(exact, k), "t"))));
        steps[m] = cJSON_GetNumberValue(cJSON_GetObjectItem(run, "steps_per_period")), err[m++] = e;
    }
    const double T = gb_forcing_period(&plane);
    int within = m > 1;
    for (int k = 0; k < m; k++) within = within && err[k] <= 2.0 * T / steps[k];
    char detail[400];
    int len = snprintf(detail, sizeof detail, "largest landing-time error against the closed form:");
    for (int k = 0; k < m && len < (int)sizeof detail; k++)
        len += snprintf(detail + len, sizeof detail - (size_t)len, " %.3g s at T/%.0f%s", err[k], steps[k], k + 1 < m ? "," : "");
    gb_check cs = {"-", "-", "the same drop in Siconos (Moreau-Jean, theta 1/2, LCP): its first 8 landing times",
                   "the closed form, to within the time-stepping's resolution",
                   "two steps at every step size: a landing is known to the step that holds it, and the rebound it starts "
                   "inherits that error (first order)"};
    gb_check_true(&cs, within, "%s", detail);
}

static void test_siconos_bouncing(void)
{
    gb_check_each_reference_case("siconos/bouncing_ball.json", "-", siconos_bouncing_case);
}

/* ---- a Gömböc dropped with spin ----------------------------------------------------------------------- */

static void test_gomboc_drop(void)
{
    const gb_forcing still = {9.81, 0.0, 0.0, 18.0, 0.0};
    const double rates[2] = {0.0, 0.5}, w0[3] = {3.0, -2.0, 1.0}, v0[3] = {0.3, -0.2, 0.0};
    double R[9];
    tilted(R);
    for (int k = 0; k < 2; k++) {
        landings l = {0};
        const int status = flight_run("I", 0.12, &still, rates[k], 20.0, R, 0.2, v0, w0, &l, 160);
        char why[300], q[240];
        snprintf(why, sizeof why, "%s", status ? gb_error_message() : "ran to the end");
        const int ran = !status && l.n > 0;
        snprintf(q, sizeof q, "Gomboc I dropped from 0.2 m with spin, e = %g: at every landing", rates[k]);
        gb_check cm = {"3, 5", "-", q, "the angular momentum about the landing point kept, and m |v+ - v-| equal to the "
                       "plane's impulse |P| (max relative)", "1e-12: rounding"};
        gb_check_close(&cm, ran ? fmax(l.worst_momentum, l.worst_impulse) : NAN, 0.0, 0.0, 1e-12);
        snprintf(q, sizeof q, "Gomboc I dropped with spin, e = %g: the centroid's horizontal velocity in flight", rates[k]);
        gb_check ch = {"3, 5", "-", q, "constant (the plane pushes only at landings; gravity is vertical), max change [m/s]",
                       "1e-13 m/s: closed-form flight"};
        gb_check_close(&ch, ran ? l.worst_horizontal : NAN, 0.0, 0.0, 1e-13);
        snprintf(q, sizeof q, "Gomboc I dropped with spin, e = %g: |E - E0 - W + L| over 20 periods, %zu landings", rates[k], l.n);
        gb_check cl = {"3, 5", "46-51", q, "the ledger closes across flight, landings and rolling; T+ <= T- at every landing",
                       "1e-7 J: RK4 at 160 steps a period between impacts (the Table 1 unilateral runs keep 5e-8 J)"};
        gb_check_close(&cl, ran && l.worst_gain <= 1e-14 ? l.residual_max : NAN, 0.0, 0.0, 1e-7);
        gb_check cw = {"3, 5", "-", q, "what the body does: landings, lift-offs, the end", "exact"};
        gb_check_true(&cw, ran, "%zu landings, %zu lift-offs; the last landing at t = %.6g s with %d contact(s) after; %s", l.n,
                      l.lift_offs, ran ? l.t[l.n - 1] : NAN, ran ? l.contacts_after[l.n - 1] : -1, why);
        landings_free(&l);
    }
}

/* ---- Table 1 in units of g, physically ---------------------------------------------------------------- */

static void test_table1_g_units(void)
{
    static const char *const scenes[] = {"cases/table1-gomboc-I-g-units-unilateral.ini", "cases/table1-gomboc-I-g-units-bouncing.ini",
                                         "cases/table1-gomboc-II-g-units-unilateral.ini", "cases/table1-gomboc-II-g-units-bouncing.ini"};
    for (int k = 0; k < 4; k++) {
        gb_case scene;
        landings l = {0};
        gb_dynamics_flight_summary fs = {0};
        double period = NAN, periods = NAN;
        int status = gb_case_load(scenes[k], &scene);
        if (!status) {
            period = gb_forcing_period(&scene.dynamics.forcing);
            periods = scene.integrate.periods;
            double y[GB_STATE_SIZE];
            gb_massprops props;
            gb_massprops_def mdef = gb_massprops_default_def();
            mdef.mass = scene.dynamics.mass;
            status = gb_massprops_compute(&scene.body, &mdef, &props);
            if (!status) status = gb_dynamics_start(&scene.body, &scene.dynamics, scene.attitude, scene.omega0, &l.d, y);
            if (!status) {
                gb_integrate_stats stats;
                l.body.mass = scene.dynamics.mass;
                memcpy(l.body.inertia, props.inertia, sizeof l.body.inertia);
                l.worst_gain = -INFINITY;
                gb_dynamics_set_impact_sink(l.d, landing_sink, &l);
                status = gb_integrate_run(l.d, &scene.integrate, 0.0, y, landing_sample, &l, &stats);
                if (!status) status = l.status;
                gb_dynamics_flight_stats(l.d, periods * period, &fs);
            }
            gb_dynamics_free(l.d);
        }
        char why[300], q[300];
        snprintf(why, sizeof why, "%s", status ? gb_error_message() : "ran to the end");
        const int ran = !status && l.n > 0;
        snprintf(q, sizeof q, "%s: the ledger's change over steps with a lift-off, landing or impact", scenes[k]);
        gb_check cl = {"3, 6", "46-51, 61", q, "of the size of the smooth steps' (max |change of E - E0 - W + L| a step; "
                       "ratio of the event steps' max to the smooth steps')", "10: a step with events is two or more RK4 "
                       "pieces and a located event; a jump booked wrong would change the ledger by the jump's energy, "
                       "0.1-2 J here, 1e5 times the smooth steps' max"};
        gb_check_close(&cl, ran ? l.step_event_max / fmax(l.step_smooth_max, 1e-12) : NAN, 0.0, 0.0, 10.0);
        snprintf(q, sizeof q, "%s: at every landing", scenes[k]);
        gb_check cm = {"3, 6", "61", q, "the angular momentum about the landing point kept, m |v+ - v-| equal to the plane's "
                       "impulse (max relative), T+ <= T-", "1e-12: rounding"};
        gb_check_close(&cm, ran && l.worst_gain <= 1e-12 ? fmax(l.worst_momentum, l.worst_impulse) : NAN, 0.0, 0.0, 1e-12);
        snprintf(q, sizeof q, "%s: what the body does in units of g", scenes[k]);
        gb_check cw = {"3, 6", "61", q, "measured: the share of the run in flight, landings a period, the highest hop, "
                       "lift-offs, the ledger over the run", "exact"};
        gb_check_true(&cw, ran, "%.1f %% of the time in flight; %.3f landings a period (%zu); highest hop %.4g m; %zu lift-offs, "
                      "%zu bounces; max |E - E0 - W + L| %.3g J (max a smooth step %.3g J, a step with an event %.3g J); %s",
                      100.0 * fs.time / (periods * period), (double)l.n / periods, l.n, fs.hop_max, fs.lift_offs, fs.bounces,
                      l.residual_max, l.step_smooth_max, l.step_event_max, why);
        landings_free(&l);
    }
}

/* ---------------------------------------------------------------- the sphere at the chart's pole */

/* x and its derivatives in the POLAR_X chart (gb_surface_eval_chart) against central differences of the
 * position at (a, b): the worst absolute error of x and its first and second derivatives. */
static double chart_fd_error(const gb_surface *surface, double a, double b, double h)
{
    gb_surface_point p;
    gb_surface_eval_chart(surface, GB_SURFACE_CHART_POLAR_X, a, b, &p);
    double at[3][3][3]; /* x at (a + i h, b + j h) for i, j in -1, 0, 1 */
    for (int i = -1; i <= 1; i++)
        for (int j = -1; j <= 1; j++) {
            double phi, theta;
            gb_surface_chart_angles(GB_SURFACE_CHART_POLAR_X, a + i * h, b + j * h, &phi, &theta);
            gb_surface_position(surface, phi, theta, at[i + 1][j + 1]);
        }
    double worst = 0.0;
    for (int k = 0; k < 3; k++) {
        const double fd[5] = {(at[2][1][k] - at[0][1][k]) / (2 * h), (at[1][2][k] - at[1][0][k]) / (2 * h),
                              (at[2][1][k] - 2 * at[1][1][k] + at[0][1][k]) / (h * h),
                              (at[2][2][k] - at[2][0][k] - at[0][2][k] + at[0][0][k]) / (4 * h * h),
                              (at[1][2][k] - 2 * at[1][1][k] + at[1][0][k]) / (h * h)};
        const double jet[5] = {p.x_phi[k], p.x_theta[k], p.x_phiphi[k], p.x_phitheta[k], p.x_thetatheta[k]};
        for (int m = 0; m < 5; m++) worst = fmax(worst, fabs(jet[m] - fd[m]));
        worst = fmax(worst, fabs(p.x[k] - at[1][1][k]));
    }
    return worst;
}

static int spin_sample(void *context, const gb_run_sample *s)
{
    double *omega_max = context;
    *omega_max = fmax(*omega_max, norm3(s->y + GB_STATE_OMEGA));
    return 0;
}

static void test_sphere_at_pole(void)
{
    /* The POLAR_X chart's derivatives where the (φ, θ) chart is singular: II and the sphere at ±e_z itself, I
     * (C¹,¹ but not C² at ±e_z) 0.005 rad off it; all inside the polar cap where Newton uses this chart. */
    const struct {
        const char *morphology;
        double beta, phi, theta;
    } at[] = {{"II", 0.12, 0.0, 0.0}, {"II", 0.12, 0.004, 2.0}, {"I", 0.12, 0.005, 1.0}, {"I", 0.12, M_PI - 0.005, 4.0},
              {"I", 0.0, 0.0, 0.0},   {"I", 0.0, M_PI, 0.0}};
    double worst = 0.0, slowest = INFINITY;
    for (size_t k = 0; k < sizeof at / sizeof at[0]; k++) {
        double a, b;
        gb_surface_chart_coordinates(GB_SURFACE_CHART_POLAR_X, at[k].phi, at[k].theta, &a, &b);
        const gb_surface *surface = gb_check_body(at[k].morphology, at[k].beta);
        const double fine = chart_fd_error(surface, a, b, 1e-4), coarse = chart_fd_error(surface, a, b, 1e-3);
        if (strcmp(at[k].morphology, "I") || at[k].beta == 0.0) worst = fmax(worst, coarse);
        else slowest = fmin(slowest, coarse / fine);
    }
    gb_check cd = {"2", "1, 2",
                   "x and its first and second derivatives in the POLAR_X chart at the (phi, theta) poles and near them (II "
                   "at beta = 0.12, the sphere)", "central differences of x, step h = 1e-3: max |error|",
                   "1e-6: the differences' truncation h^2 |x^(4)| / 12 (|x^(4)| of order 10: II's phase turns by 3 pi / 2) and "
                   "their rounding eps / (h^2 sin phi) <= 6e-8 (the position near the pole goes through acos)"};
    gb_check_close(&cd, worst, 0.0, 0.0, 1e-6);
    gb_check c1 = {"2", "1, 2",
                   "the same for I at beta = 0.12, 0.005 rad from the poles (C^1,1 but not C^2 at them: its fourth "
                   "derivatives there are too large for a fixed tolerance)",
                   "central differences converge to the chart's derivatives as h^2: min of error(h = 1e-3) / error(1e-4)",
                   ">= 50: 100 for second order, halved for rounding"};
    gb_check_true(&c1, slowest >= 50.0, "min ratio %.4g", slowest);

    /* The sphere's contact for verticals at and near the poles, from starts at both poles and off them: the
     * point -ẑ_b itself, a regular minimum. */
    const gb_surface *sphere = gb_check_body("I", 0.0);
    const gb_contact_refine_def refine = gb_contact_refine_default_def();
    const double verticals[][3] = {{0, 0, 1}, {0, 0, -1}, {1e-9, 0, 1}, {0, -3e-7, -1}, {0.004, 0.003, 1}};
    const double starts[][2] = {{0.0, 0.0}, {M_PI, 0.0}, {0.3, 1.0}, {2.8, 5.0}};
    double worst_point = 0.0, worst_rate = 0.0;
    int minima = 0, tried = 0;
    for (size_t k = 0; k < sizeof verticals / sizeof verticals[0]; k++)
        for (size_t j = 0; j < sizeof starts / sizeof starts[0]; j++) {
            const double *z = verticals[k], n = norm3(z);
            double u[3];
            gb_surface_direction(starts[j][0], starts[j][1], u);
            if ((u[0] * z[0] + u[1] * z[1] + u[2] * z[2]) / n > 0.99) continue; /* at the maximum: h has no slope */
            gb_contact_point c;
            tried++;
            if (gb_contact_refine(sphere, z, starts[j][0], starts[j][1], &refine, &c) || !c.is_minimum) continue;
            minima++;
            const double off[3] = {c.rc[0] + z[0] / n, c.rc[1] + z[1] / n, c.rc[2] + z[2] / n};
            worst_point = fmax(worst_point, norm3(off));
            /* the rate through the chart's sensitivity (eqs 70-72): r_c = -z_b moves as -z_b x omega */
            const double w[3] = {0.3, -0.2, 0.5}, unit[3] = {z[0] / n, z[1] / n, z[2] / n};
            double rate[3], expected[3];
            cross(unit, w, expected);
            if (gb_contact_rate(sphere, z, &c, w, rate, NULL) != GB_OK) {
                worst_rate = INFINITY;
                continue;
            }
            const double dr[3] = {rate[0] + expected[0], rate[1] + expected[1], rate[2] + expected[2]};
            worst_rate = fmax(worst_rate, norm3(dr));
        }
    gb_check cp = {"4", "28-35",
                   "the sphere's contact for verticals at and within 0.005 rad of the chart's poles, from the poles and two "
                   "other starts (none at the maximum): "
                   "a minimum (eq 35)", "the point -z_b: max |r_c + z_b|",
                   "1e-15: rounding of a unit vector"};
    if (!gb_check_close(&cp, minima == tried ? worst_point : NAN, 0.0, 0.0, 1e-15))
        fprintf(stderr, "%d of %d refinements ended on a minimum\n", minima, tried);
    gb_check cv = {"4", "70-72", "the sphere's contact above: its rate through the sensitivity in the point's chart, omega = "
                   "(0.3, -0.2, 0.5) rad/s", "r_c = -z_b, so dr_c/dt = -z_b x omega: max |error| [1/s]",
                   "1e-14: rounding of a 2 x 2 solve with a unit Hessian"};
    gb_check_close(&cv, minima == tried ? worst_rate : NAN, 0.0, 0.0, 1e-14);

    /* Runs from R0 = I, whose lowest point is the pole, under every contact law and contact model (eq 44 only
     * held: the unilateral law refuses it, cases/README.md). */
    static const char *const models[][3] = {{"held", "continuous", "rolling"},       {"held", "continuous", "paper"},
                                            {"held", "grid", "rolling"},             {"held", "fast-grid", "paper"},
                                            {"unilateral", "continuous", "rolling"}, {"unilateral", "grid", "rolling"},
                                            {"unilateral", "fast-grid", "rolling"}};
    const int count = (int)(sizeof models / sizeof models[0]);
    int ran = 0;
    double spin = 0.0;
    char failed[600] = "";
    for (int k = 0; k < count; k++) {
        const int unilateral = !strcmp(models[k][0], "unilateral");
        char text[1400];
        snprintf(text, sizeof text,
                 "[body]\nmorphology = I\nbeta = 0\n[forcing]\nA1 = 2.0\nA2 = 1.0\namplitude_units = %s\nomega = 18\n"
                 "psi = pi/3\n[model]\nequation = %s\ncontact = %s\ndamping = 0.02\ncontact_law = %s\n%s"
                 "[integrator]\nmethod = rk4\nsteps_per_period = 160\nperiods = 20\nlocate_switches = yes\n"
                 "[initial]\nattitude = identity\n",
                 unilateral ? "g" : "m/s2", models[k][2], models[k][1], models[k][0], unilateral ? "restitution = 0.5\n" : "");
        gb_case scene;
        gb_run_result result;
        double omega_max = 0.0;
        const gb_run_sinks sinks = {spin_sample, &omega_max, NULL};
        int status = gb_case_load_text("sphere.ini", text, strlen(text), &scene);
        if (!status) status = gb_run(&scene, &sinks, &result);
        if (status) {
            snprintf(failed + strlen(failed), sizeof failed - strlen(failed), " %s/%s/%s: %s;", models[k][0],
                     models[k][1], models[k][2], gb_error_message());
            continue;
        }
        gb_run_result_free(&result);
        ran++;
        /* a grid body is a polyhedron, and one standing on its pole vertex is an inverted pendulum: it tips */
        if (!strcmp(models[k][1], "continuous")) spin = fmax(spin, omega_max);
    }
    gb_check cr = {"3, 5", "-",
                   "the sphere from R0 = I (its lowest point the (phi, theta) chart's pole), 20 Table 1 periods under each "
                   "contact law and model: held (continuous rolling and eq 44, grid, fast grid), unilateral with flight in "
                   "units of g, e = 0.5 (continuous, grid, fast grid)",
                   "every run completes", "exact"};
    gb_check_true(&cr, ran == count, "%d of %d ran;%s", ran, count, failed);
    gb_check cw = {"3, 5", "-", "the sphere from R0 = I, the runs above with continuous contact (a grid body is a "
                   "polyhedron, which standing on its pole vertex tips over)", "omega stays 0: max |omega| [rad/s]",
                   "1e-12: the centroid is the centre, so neither g_eff nor the plane's push has a moment about it and "
                   "omega0 = 0 stays 0 but for rounding"};
    gb_check_close(&cw, ran ? spin : NAN, 0.0, 0.0, 1e-12);
}

int verify_register_s5_flight(void)
{
    static const verify_test tests[] = {
        {"impact law: one point on a rough plane, the slip stopped first", test_rough_point,
         "the landing's impact keeps the angular momentum about the point, stops the slip, never makes energy, and agrees "
         "with Moreau's law wherever both apply"},
        {"flight: a ball dropped on a still plane", test_ball_drop,
         "flight, landing, restitution and the end to bouncing follow the closed forms of a dropped ball"},
        {"flight: the bouncing ball's period-1 orbit and its stable range", test_bouncing_ball,
         "on a vibrating plane a sphere locks onto the period-1 bouncing orbit exactly where the exact impact map says it "
         "is stable"},
        {"flight: a ball on Table 1's plane in units of g, against the closed form and Siconos", test_siconos_bouncing,
         "gomboc's landings are the closed form's, and Siconos's converge to them with its step"},
        {"flight: a Gomboc dropped with spin", test_gomboc_drop,
         "a spinning Gomboc's landings obey the impulse-momentum laws, its flights keep the horizontal momentum, and the "
         "ledger closes"},
        {"the sphere at the (phi, theta) chart's pole", test_sphere_at_pole,
         "beta = 0 runs under every contact law and contact model from an attitude whose lowest point is the chart's "
         "pole, and the second chart there has the surface's derivatives"},
        {"sections 3, 6: Table 1 in units of g, with lift-off and flight", test_table1_g_units,
         "Table 1 read in units of g runs through every lift-off and landing under the unilateral law with e = 0 and 0.5, "
         "and its ledger closes to the integration's accuracy"},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("A plane that can only push: lift-off, flight and landing", tests);
}
