/* A plane that pushes where the body dips in: the compliant law (gb_dynamics_compliant.c, docs/compliant.md).
 *
 * Oracles, each in closed form or another law of this library run apart:
 * - Hunt and Crossley's bounce: a body meeting the plane at approach speed v⁻ under N = k δ^n (1 + (3/2) α δ̇)
 *   leaves it at e v⁻, e the root of x − ln(1 + x) = −e x − ln(1 − e x), x = (3/2) α v⁻, whatever k and n
 *   (integrate m v dv/dδ = −k δ^n (1 + (3/2) α v) round the closed path of δ); the weight, left out of it, is
 *   a share of the contact force that falls as k^(−1/(n+1)) (the contact force grows as k^(1/(n+1))): the
 *   sphere's measured e tends to the closed form at that order, and α = 0 gives e = 1 at every k;
 * - the rigid limit: the sphere's first apex tends to that of the unilateral law with Newton's e set to the
 *   closed form's, at the same order (the contact's duration falls as k^(−1/(n+1)));
 * - the ledger E + Σ k δ^(n+1)/(n+1) − E0 − W − W_contact closes (the dissipative forces' work integrated
 *   beside the state) in every run, flight, bounce, rocking and forcing alike;
 * - Housner's block at rest on its face: each of the 4 vertices of the face at the static depth
 *   (m g / (4 k))^(1/n), the face level; the block rocking on an edge meets the plane with its other edge at a
 *   time that tends to the unilateral law's first impact;
 * - Table 1's grid polyhedron (make verify-full): its rest attitude on a still plane tends to the unilateral law's
 *   as k grows, at first order (the rest face's compression m g / k tilts it);
 * - Painlevé's launch of verify/s5_friction.c beyond μ*, where the rigid law has no consistent force and
 *   stops: the compliant law runs through it, and what it gives is recorded. */
#include "gb_case.h"
#include "gb_check.h"
#include "gb_dynamics.h"
#include "gb_error.h"
#include "gb_integrate.h"
#include "gb_contact.h"
#include "gb_massprops.h"
#include "gb_polyhedron.h"
#include "gb_run.h"
#include "verify_sections.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const double G = 9.81, H = 0.1; /* the sphere's drop: its lowest point H above a still plane */

/* Hunt and Crossley's restitution: the root e of x − ln(1 + x) = −e x − ln(1 − e x), by bisection on [0, 1]. */
static double hunt_crossley_restitution(double x)
{
    const double a = x - log1p(x);
    double lo = 0.0, hi = 1.0;
    for (int k = 0; k < 200; k++) {
        const double e = 0.5 * (lo + hi);
        if (a - (-e * x - log1p(-e * x)) > 0.0) lo = e;
        else hi = e;
    }
    return 0.5 * (lo + hi);
}

/* What every run's samples tell of its ledger: E at the start and the worst |residual|. */
typedef struct ledger {
    double energy0, residual_max;
} ledger;

static void ledger_note(ledger *l, const gb_run_sample *s)
{
    if (s->t == 0.0) l->energy0 = s->o->energy;
    l->residual_max = fmax(l->residual_max, fabs(s->o->residual));
}

/* The first flight after the first contact, seen from a sample: the rebound speed at the plane's level, from the
 * ballistic energy (v_z² + 2 g clearance), and the apex time t + v_z / g. */
typedef struct bounce {
    int risen; /* a sample has seen the sphere off the plane and rising */
    double rebound, apex;
    ledger ledger;
} bounce;

static int bounce_sample(void *context, const gb_run_sample *s)
{
    bounce *b = context;
    const gb_dynamics_observables *o = s->o;
    ledger_note(&b->ledger, s);
    if (!b->risen && o->contacts == 0 && o->velocity[2] > 0.0) {
        b->risen = 1;
        b->rebound = sqrt(o->velocity[2] * o->velocity[2] + 2.0 * G * o->clearance);
        b->apex = s->t + o->velocity[2] / G;
    }
    return GB_OK;
}

/* The sphere (β = 0) dropped from H: under the compliant law of stiffness k and dissipation alpha (n = 1.5), or,
 * k = 0, under the unilateral law with Newton's e. */
static int sphere_drop(double k, double alpha, double e, bounce *out)
{
    char text[1400];
    const char *law = k > 0.0 ? "compliant" : "unilateral";
    char coefficients[200];
    if (k > 0.0) snprintf(coefficients, sizeof coefficients, "friction = 0.5\nstiffness = %.17g\nexponent = 1.5\ndissipation = %.17g\n", k, alpha);
    else snprintf(coefficients, sizeof coefficients, "equation = rolling\nrestitution = %.17g\n", e);
    snprintf(text, sizeof text,
             "[body]\nmorphology = I\nbeta = 0\n[forcing]\ng = %.17g\nA1 = 0\nA2 = 0\nomega = 6.283185307179586\n"
             "[model]\ncontact = continuous\ncontact_law = %s\ndamping = 0\n%s"
             "[integrator]\nmethod = rk8pd\nsteps_per_period = 4000\nperiods = 0.3\nrtol = 1e-11\natol = 1e-13\n"
             "locate_switches = yes\n[initial]\nheight = %.17g\n",
             G, law, coefficients, H);
    gb_case scene;
    gb_run_result result;
    memset(out, 0, sizeof *out);
    const gb_run_sinks sinks = {bounce_sample, out, NULL};
    int status = gb_case_load_text("sphere-drop.ini", text, strlen(text), &scene);
    if (!status) status = gb_run(&scene, &sinks, &result);
    if (!status) gb_run_result_free(&result);
    if (!status && !out->risen) status = gb_error_set(GB_ENUMERIC, "the sphere did not leave the plane again");
    return status;
}

enum { STIFFNESSES = 4 };
static const double stiffness[STIFFNESSES] = {1e6, 1e7, 1e8, 1e9};

static void test_bounce(void)
{
    const double v_minus = sqrt(2.0 * G * H), x = 0.5, alpha = x / (1.5 * v_minus), e_closed = hunt_crossley_restitution(x);
    double e[STIFFNESSES], elastic_worst = 0.0, ledger_worst = 0.0;
    int status = GB_OK;
    char failed[300] = "";
    for (int i = 0; i < STIFFNESSES && !status; i++) {
        bounce b, elastic;
        status = sphere_drop(stiffness[i], alpha, 0.0, &b);
        if (!status) status = sphere_drop(stiffness[i], 0.0, 0.0, &elastic);
        if (status) {
            snprintf(failed, sizeof failed, "k = %g: %s", stiffness[i], gb_error_message());
            break;
        }
        e[i] = b.rebound / v_minus;
        elastic_worst = fmax(elastic_worst, fabs(elastic.rebound / v_minus - 1.0));
        ledger_worst = fmax(ledger_worst, fmax(b.ledger.residual_max, elastic.ledger.residual_max) / b.ledger.energy0);
    }
    const int ok = !status;
    /* the weight's share falls as k^(−1/(n+1)): successive decades' errors in the ratio 10^0.4 */
    double order_worst = 0.4;
    for (int i = 0; ok && i + 1 < STIFFNESSES; i++) {
        const double p = log10((e_closed - e[i]) / (e_closed - e[i + 1]));
        if (fabs(p - 0.4) > fabs(order_worst - 0.4)) order_worst = p;
    }
    const double r = pow(10.0, 0.4), extrapolated = ok ? e[3] + (e[3] - e[2]) / (r - 1.0) : NAN;
    gb_check co = {"-", "-",
                   "sphere dropped from 0.1 m on the compliant plane (n = 1.5, x = (3/2) alpha v- = 0.5), k = 1e6 ... 1e9: "
                   "the order at which its restitution tends to Hunt and Crossley's closed form, worst of 3 decades",
                   "1/(n + 1) = 0.4: the weight, left out of the closed form, is a share k^(-1/(n+1)) of the contact force",
                   "0.025: the next term of the weight's share, the error squared relative (4e-2 at k = 1e6)"};
    if (ok) gb_check_close(&co, order_worst, 0.4, 0.0, 0.025);
    else gb_check_true(&co, 0, "%s", failed);
    gb_check ce = {"-", "-",
                   "the same bounces' restitution extrapolated to k -> infinity (Richardson at order 0.4 from k = 1e8, 1e9)",
                   "Hunt and Crossley's closed form: the root e of x - ln(1 + x) = -e x - ln(1 - e x)",
                   "2e-5: the extrapolation's next term, (the error at 1e9, 1e-3) times the order's spread over the decades"};
    gb_check_close(&ce, extrapolated, e_closed, 0.0, 2e-5);
    gb_check cl = {"-", "-", "the same bounces and the elastic ones (alpha = 0): the elastic restitution, worst |e - 1| over k",
                   "1: energy is conserved, the elastic force k d^n a potential's",
                   "1e-8: the integrator's tolerance (rtol 1e-11) over the bounce's some 2000 steps"};
    gb_check_close(&cl, ok ? elastic_worst : NAN, 0.0, 0.0, 1e-8);
    gb_check cg = {"-", "-", "the same runs: the ledger E + sum k d^(n+1)/(n+1) - E0 - W - W_contact, worst over samples, "
                   "relative to E0", "0: energy balance with the dissipative forces' work integrated beside the state",
                   "1e-9: rtol 1e-11 over the some 3000 steps of a run"};
    gb_check_close(&cg, ok ? ledger_worst : NAN, 0.0, 0.0, 1e-9);
}

static void test_rigid_limit(void)
{
    const double v_minus = sqrt(2.0 * G * H), x = 0.5, alpha = x / (1.5 * v_minus), e_closed = hunt_crossley_restitution(x);
    bounce rigid, b;
    int status = sphere_drop(0.0, 0.0, e_closed, &rigid);
    double gap[STIFFNESSES];
    for (int i = 0; i < STIFFNESSES && !status; i++) {
        status = sphere_drop(stiffness[i], alpha, 0.0, &b);
        if (!status) gap[i] = b.apex - rigid.apex;
    }
    char detail[300];
    snprintf(detail, sizeof detail, "%s", status ? gb_error_message() : "");
    double order_worst = 0.4;
    for (int i = 0; !status && i + 1 < STIFFNESSES; i++) {
        const double p = log10(gap[i] / gap[i + 1]);
        if (fabs(p - 0.4) > fabs(order_worst - 0.4)) order_worst = p;
    }
    gb_check co = {"-", "-",
                   "sphere's first apex on the compliant plane (k = 1e6 ... 1e9) against the unilateral law's with Newton's e "
                   "= Hunt and Crossley's: the order at which the gap closes, worst of 3 decades",
                   "1/(n + 1) = 0.4: the contact lasts a time of order k^(-1/(n+1)), and e tends at that order",
                   "0.03: the next terms (the gap is 6e-3 s at k = 1e6)"};
    if (!status) gb_check_close(&co, order_worst, 0.4, 0.0, 0.03);
    else gb_check_true(&co, 0, "%s", detail);
    gb_check cu = {"-", "-", "the unilateral law's apex in the same drop", "t1 + e v-/g, t1 = sqrt(2H/g): its landing and "
                   "rebound in closed form", "1e-9 s: the rebound located to the event tolerance, rk8pd at rtol 1e-11"};
    gb_check_close(&cu, status ? NAN : rigid.apex, sqrt(2.0 * H / G) + e_closed * v_minus / G, 0.0, 1e-9);
}

/* ---- Housner's block ------------------------------------------------------------------------------- */

typedef struct rocking {
    double level;          /* when the bottom face is first level (z_b's x component changes sign), interpolated */
    double previous_t, previous_x;
    ledger ledger;
    double zeta, tilt;
    double first_impact;   /* the unilateral law: its first impact after the start's settling onto the edge */
} rocking;

static int rocking_sample(void *context, const gb_run_sample *s)
{
    rocking *r = context;
    const gb_dynamics_observables *o = s->o;
    ledger_note(&r->ledger, s);
    const double x = o->zb[0]; /* ± the sine of the tilt about y */
    if (isnan(r->level) && s->t > 0.0 && (x > 0.0) != (r->previous_x > 0.0))
        r->level = r->previous_t + (s->t - r->previous_t) * r->previous_x / (r->previous_x - x);
    r->previous_t = s->t, r->previous_x = x;
    r->zeta = o->zeta;
    r->tilt = asin(fmin(1.0, hypot(o->zb[0], o->zb[1])));
    return GB_OK;
}

/* The start on the edge is itself a change of contact (one vertex, then the edge's two): the first impact after
 * a millisecond is the other edge's. */
static int rocking_impact(void *context, const gb_dynamics_impact *impact)
{
    rocking *r = context;
    if (isnan(r->first_impact) && impact->t > 1e-3) r->first_impact = impact->t;
    return GB_OK;
}

/* The block of cases/bodies/housner-block.off tilted 0.1 rad about y, released from rest for `periods` seconds:
 * compliant (k > 0, n = 1, the friction's slip speed, dissipation alpha, μ = 1, body damping c, msbdf at rtol) or
 * unilateral (k = 0, rough, undamped, rk4 with located impacts). */
static int housner(double k, double slip_speed, double alpha, double c, double rtol, double periods, rocking *out)
{
    char text[1400], coefficients[400];
    if (k > 0.0)
        snprintf(coefficients, sizeof coefficients, "damping = %.17g\ncontact_law = compliant\nfriction = 1\nstiffness = %.17g\n"
                 "exponent = 1\ndissipation = %.17g\nslip_speed = %.17g\n[integrator]\nmethod = msbdf\nrtol = %.17g\n"
                 "atol = 1e-12\nsteps_per_period = 20000\nlocate_switches = yes\n", c, k, alpha, slip_speed, rtol);
    else
        snprintf(coefficients, sizeof coefficients, "damping = 0\ncontact_law = unilateral\n[integrator]\nmethod = rk4\n"
                 "steps_per_period = 20000\nlocate_switches = yes\n");
    snprintf(text, sizeof text,
             "[body]\nmesh = housner-block.off\nmass = 1\n[forcing]\ng = %.17g\nA1 = 0\nA2 = 0\nomega = 6.283185307179586\n"
             "[model]\ncontact = fast-grid\n%speriods = %.17g\n[initial]\nattitude = axis-angle 0,1,0,0.1\n",
             G, coefficients, periods);
    gb_case scene;
    gb_run_result result;
    memset(out, 0, sizeof *out);
    out->first_impact = out->level = NAN;
    const gb_run_sinks sinks = {rocking_sample, out, rocking_impact};
    int status = gb_case_load_text("cases/bodies/housner-compliant.ini", text, strlen(text), &scene);
    if (!status) status = gb_run(&scene, &sinks, &result);
    if (!status) gb_run_result_free(&result);
    return status;
}

static void test_housner(void)
{
    /* at rest on its face: 4 vertices at the static depth m g / (4 k) (n = 1) */
    const double k_rest = 1e6, depth = G / (4.0 * k_rest);
    rocking rest, coarse;
    int status = housner(k_rest, 1e-4, 20.0, 2.0, 1e-10, 3.0, &rest);
    if (!status) status = housner(k_rest, 1e-4, 20.0, 2.0, 1e-8, 3.0, &coarse);
    char detail[300];
    snprintf(detail, sizeof detail, "%s", status ? gb_error_message() : "");
    gb_check cf = {"-", "-",
                   "Housner's block (0.2 x 0.3 x 0.8 m, 1 kg) released tilted 0.1 rad on the compliant plane (k = 1e6 N/m, n = "
                   "1, alpha = 20 s/m, mu = 1, body damping c = 2 N m s), after 3 s: its tilt [rad]",
                   "0: at rest on the face it rocked on, as under the unilateral law (cases/bodies/housner-block.ini)",
                   "1e-12 rad: the state's rounding at rest and the integrator's atol 1e-12"};
    if (!status) gb_check_close(&cf, rest.tilt, 0.0, 0.0, 1e-12);
    else gb_check_true(&cf, 0, "%s", detail);
    gb_check ch = {"-", "-", "the same block at rest: its centroid's height [m]",
                   "h - m g / (4 k): the half height 0.4 m less the static depth of the face's 4 vertices (n = 1)",
                   "1e-12 m: the integrator's atol on the height"};
    gb_check_close(&ch, status ? NAN : rest.zeta, 0.4 - depth, 0.0, 1e-12);
    gb_check cg = {"-", "-", "the same run: the ledger's worst |residual| over samples at rtol 1e-10, against the run at 1e-8",
                   "integration error: it falls as the tolerance tightens, by 10 at least over the factor 100",
                   "a factor 10 = sqrt(100): a tolerance-controlled method of order p >= 1 has a global error "
                   "of order tol^(p/(p+1)), at least the square root of the tolerance"};
    gb_check_true(&cg, !status && rest.ledger.residual_max * 10.0 <= coarse.ledger.residual_max,
                  "ledger %.3g J at rtol 1e-8, %.3g J at 1e-10 (E0 %.4g J)", coarse.ledger.residual_max,
                  rest.ledger.residual_max, rest.ledger.energy0);

    /* the moment the face is first level, against the unilateral law's first impact (which is that moment). A rocking
     * edge needs friction, and regularised friction lets it creep at a speed of order the slip speed s: the rigid
     * limit is k → ∞ and s → 0 together (at fixed s = 1e-4 m/s the gap stays near 9e-6 s from k = 1e7 on). */
    rocking rigid;
    int st = housner(0.0, 0.0, 0.0, 0.0, 0.0, 0.5, &rigid);
    const double ks[3] = {1e6, 1e7, 1e8};
    double gap[3] = {NAN, NAN, NAN};
    for (int i = 0; i < 3 && !st; i++) {
        rocking r;
        st = housner(ks[i], 100.0 / ks[i], 2.0, 0.0, 1e-10, 0.5, &r);
        if (!st) gap[i] = r.level - rigid.first_impact;
    }
    snprintf(detail, sizeof detail, "%s; gaps %.4g, %.4g, %.4g s; unilateral first impact at %.9g s",
             st ? gb_error_message() : "measured", gap[0], gap[1], gap[2], rigid.first_impact);
    gb_check cm = {"-", "-",
                   "the same block rocking undamped on its edge (k = 1e6, 1e7, 1e8 N/m with the friction's slip speed s = "
                   "100/k m/s, n = 1, alpha = 2 s/m): when its bottom face is first level, against the unilateral law's first "
                   "impact", "the gap closes at first order in 1/k: by a factor 5 at least each decade",
                   "5: half the factor 10 of first order (the edge's compression ~ 1/k, its creep ~ s)"};
    gb_check_true(&cm, !st && fabs(gap[1]) * 5.0 < fabs(gap[0]) && fabs(gap[2]) * 5.0 < fabs(gap[1]), "%s", detail);
}

/* ---- Painlevé's launch ------------------------------------------------------------------------------ */

typedef struct launch {
    double normal_max, slip_first, slip_last, lift_time;
    ledger ledger;
} launch;

static int launch_sample(void *context, const gb_run_sample *s)
{
    launch *l = context;
    const gb_dynamics_observables *o = s->o;
    ledger_note(&l->ledger, s);
    l->normal_max = fmax(l->normal_max, o->normal_force);
    if (o->contacts == 0 && isnan(l->lift_time) && s->t > 0.0) l->lift_time = s->t;
    return GB_OK;
}

typedef struct painleve_watch {
    gb_dynamics *d;
    launch *out;
} painleve_watch;

/* Every step's end of a library run, as a run's sample. */
static int painleve_sample(void *context, double t, const double y[GB_STATE_SIZE])
{
    painleve_watch *w = context;
    gb_dynamics_observables o;
    const int status = gb_dynamics_observe(w->d, t, y, &o);
    if (status) return 1;
    const gb_run_sample s = {t, y, &o, 0, 0, 0.0};
    launch_sample(w->out, &s);
    return 0;
}

/* Painlevé's launch (verify_painleve_launch) under the compliant law (k = 1e7, n = 1.5, alpha = 0.5) on a plane of
 * friction mu, 0.05 s by rk8pd at rtol (atol 1e-3 rtol): the contact lasts some 13 ms, and the flight after it is
 * smooth, where msbdf's low orders would drift the rotation's energy. */
static int painleve_compliant(const double R0[9], const double v[3], double mu, double rtol, launch *out)
{
    const double w0[3] = {0, 0, 0};
    gb_surface body;
    int status = gb_surface_init(&body, "I", 0.12);
    gb_dynamics_def def = gb_dynamics_default_def();
    def.contact = GB_CONTACT_MODEL_CONTINUOUS, def.contact_law = GB_CONTACT_LAW_COMPLIANT;
    def.friction = mu, def.damping = 0.0, def.forcing.a1 = def.forcing.a2 = 0.0;
    def.law_coefficients[0] = 1e7, def.law_coefficients[1] = 1.5, def.law_coefficients[2] = 0.5;
    memcpy(def.velocity0, v, sizeof def.velocity0);
    gb_dynamics *d = NULL;
    double y[GB_STATE_SIZE];
    memset(out, 0, sizeof *out);
    out->lift_time = NAN;
    if (!status) status = gb_dynamics_start(&body, &def, R0, w0, &d, y);
    gb_dynamics_observables o;
    if (!status) status = gb_dynamics_observe(d, 0.0, y, &o);
    if (!status) {
        const gb_run_sample first = {0.0, y, &o, 0, 0, 0.0};
        launch_sample(out, &first);
        out->slip_first = hypot(y[GB_STATE_VELOCITY], y[GB_STATE_VELOCITY + 1]);
        gb_integrate_def idef = gb_integrate_default_def();
        idef.method = GB_INTEGRATOR_RK8PD, idef.rtol = rtol, idef.atol = 1e-3 * rtol, idef.steps_per_period = 20000;
        idef.locate_switches = 1;
        const double period = gb_forcing_period(&def.forcing);
        idef.periods = 0.05 / period;
        gb_integrate_stats stats;
        status = gb_integrate_run(d, &idef, 0.0, y, painleve_sample, &(painleve_watch){d, out}, &stats);
        if (!status) status = gb_dynamics_observe(d, 0.05, y, &o);
        if (!status) out->slip_last = hypot(o.velocity[0], o.velocity[1]);
    }
    gb_dynamics_free(d);
    return status;
}

static void test_painleve(void)
{
    double R0[9], mu_star, d1, d2, v[3];
    int status = verify_painleve_launch(R0, &mu_star, &d1, &d2, v);
    const double above[2] = {1.1, 2.0};
    launch l[2];
    for (int k = 0; k < 2 && !status; k++) status = painleve_compliant(R0, v, above[k] * mu_star, 1e-10, &l[k]);
    char detail[600];
    if (status) snprintf(detail, sizeof detail, "%s", gb_error_message());
    else
        snprintf(detail, sizeof detail,
                 "mu* = %.4g; at 1.1 mu*: peak N %.4g N, the centroid's horizontal speed %.4g -> %.4g m/s, first flight at "
                 "%.4g s, ledger %.3g J of E0 %.4g J; at 2 mu*: peak N %.4g N, %.4g -> %.4g m/s, first flight at %.4g s, "
                 "ledger %.3g J", mu_star, l[0].normal_max, l[0].slip_first, l[0].slip_last, l[0].lift_time,
                 l[0].ledger.residual_max, l[0].ledger.energy0, l[1].normal_max, l[1].slip_first, l[1].slip_last,
                 l[1].lift_time, l[1].ledger.residual_max);
    gb_check cp = {"-", "-",
                   "Gomboc I tilted 0.7 rad, launched sliding at 0.5 m/s on the compliant plane (k = 1e7, n = 1.5, alpha = "
                   "0.5) at 1.1 and 2 mu*, where the rigid law has no consistent force and stops (s5_friction), 0.05 s by "
                   "rk8pd at rtol 1e-10",
                   "the runs go through and the ledger closes; what the launch gives (peak force, slip, a lift) is recorded",
                   "rtol x E0: the stepper's relative tolerance on the energy's components"};
    gb_check_true(&cp, !status && l[0].ledger.residual_max <= 1e-10 * l[0].ledger.energy0 &&
                           l[1].ledger.residual_max <= 1e-10 * l[1].ledger.energy0, "%s",
                  detail);
}

/* ---- Table 1 on the compliant plane ------------------------------------------------------------------ */

/* Gömböc II under Table 1's forcing on the compliant plane, 5 periods by msbdf at rtol (atol 1e-3 rtol): the
 * ledger's worst |residual| [J]. */
static int table1(double rtol, double *residual, double *energy)
{
    char text[600];
    snprintf(text, sizeof text,
             "[body]\nmorphology = II\n[model]\nequation = rolling\ncontact = continuous\ncontact_law = compliant\n"
             "friction = 0.5\nstiffness = 1e6\n[integrator]\nmethod = msbdf\nrtol = %.17g\natol = %.17g\nperiods = 5\n"
             "locate_switches = yes\n"
             "[initial]\nattitude = axis-angle 1,2,3,0.3\n", rtol, 1e-3 * rtol);
    gb_case scene;
    gb_run_result result;
    int status = gb_case_load_text("table1-compliant.ini", text, strlen(text), &scene);
    if (!status) status = gb_run(&scene, NULL, &result);
    if (!status) {
        *residual = result.residual_max, *energy = result.final.energy;
        gb_run_result_free(&result);
    }
    return status;
}

static void test_table1(void)
{
    double fine = NAN, coarse = NAN, energy = NAN;
    int status = table1(1e-10, &fine, &energy);
    if (!status) status = table1(1e-8, &coarse, &energy);
    gb_check c = {"3, 5", "46-51", "Gomboc II, Table 1 forcing, on the compliant plane (k = 1e6 N/m, n = 1.5, alpha = 0, mu = "
                  "0.5), 5 periods by msbdf at rtol 1e-10 and 1e-8: the ledger's worst |residual|",
                  "E + elastic - E0 - W - W_contact, W the forcing's and damping's work (eqs 46-51), W_contact friction's: "
                  "integration error, falling by 10 at least as the tolerance tightens by 100",
                  "a factor 10 = sqrt(100): a tolerance-controlled method of order p >= 1 has a global error "
                   "of order tol^(p/(p+1)), at least the square root of the tolerance"};
    gb_check_true(&c, !status && fine * 10.0 <= coarse, "%s; ledger %.3g J at rtol 1e-8, %.3g J at 1e-10 (E %.4g J)",
                  status ? gb_error_message() : "ran", coarse, fine, energy);
}

/* ---- Table 1's grid polyhedron at rest (make verify-full) --------------------------------------------- */

/* Gömböc II's 90 x 180 grid polyhedron (its hull, as a mesh in `dir`) released tilted 0.3 rad on a still plane,
 * body damping c = 3, 50 periods of 18 rad/s: unilateral on a rough plane (k = 0: rk4, 160 steps a period, located
 * impacts) or compliant (n = 1, alpha = 5 s/m, mu = 10, msbdf at rtol 1e-6). Its vertical at the end (body axes),
 * |ω| and the ledger's worst residual. */
static int polyhedron_rest(const char *dir, double k, double zb[3], double *spin, double *residual)
{
    char text[1400], name[96], law[400];
    if (k > 0.0)
        snprintf(law, sizeof law, "contact_law = compliant\nfriction = 10\nstiffness = %.17g\nexponent = 1\ndissipation = 5\n"
                 "[integrator]\nmethod = msbdf\nrtol = 1e-6\natol = 1e-9\n", k);
    else
        snprintf(law, sizeof law, "contact_law = unilateral\n[integrator]\nmethod = rk4\n");
    snprintf(text, sizeof text,
             "[body]\nmesh = polyhedron.obj\nmass = 1\n[forcing]\ng = %.17g\nA1 = 0\nA2 = 0\nomega = 18\n[model]\n"
             "equation = paper\ncontact = fast-grid\ndamping = 3\n%ssteps_per_period = 160\nperiods = 50\n"
             "locate_switches = yes\n[initial]\nattitude = axis-angle 1,0,0,0.3\n", G, law);
    snprintf(name, sizeof name, "%s/rest.ini", dir);
    gb_case scene;
    gb_run_result r;
    int status = gb_case_load_text(name, text, strlen(text), &scene);
    if (!status) status = gb_run(&scene, NULL, &r);
    if (status) return status;
    memcpy(zb, r.final.zb, 3 * sizeof *zb);
    *spin = sqrt(r.final.omega[0] * r.final.omega[0] + r.final.omega[1] * r.final.omega[1] + r.final.omega[2] * r.final.omega[2]);
    *residual = r.residual_max;
    gb_run_result_free(&r);
    return GB_OK;
}

/* Write the hull of Gömböc II's 90 x 180 grid (Table 1's β) as an OBJ mesh at `path`. */
static int write_grid_polyhedron(const char *path)
{
    gb_contact_grid_def def = gb_contact_grid_default_def();
    gb_contact_grid *g = NULL;
    gb_polyhedron h = {0};
    int status = gb_contact_grid_create(gb_check_body("II", 0.12), &def, &g);
    const size_t n = status ? 0 : gb_contact_grid_size(g);
    double *nodes = n ? malloc(3 * n * sizeof *nodes) : NULL;
    if (!status && !nodes) status = gb_error_set(GB_ENOMEM, "out of memory");
    for (size_t i = 0; !status && i < n; i++) {
        double phi, theta;
        gb_contact_grid_node(g, i, &phi, &theta, nodes + 3 * i);
    }
    if (!status) status = gb_polyhedron_from_points(nodes, n, "grid", &h);
    FILE *f = status ? NULL : fopen(path, "w");
    if (!status && !f) status = gb_error_set(GB_EIO, "cannot write %s", path);
    for (size_t i = 0; f && i < h.vertex_count; i++)
        fprintf(f, "v %.17g %.17g %.17g\n", h.vertices[3 * i], h.vertices[3 * i + 1], h.vertices[3 * i + 2]);
    for (size_t i = 0; f && i < h.triangle_count; i++)
        fprintf(f, "f %zu %zu %zu\n", h.triangles[3 * i] + 1, h.triangles[3 * i + 1] + 1, h.triangles[3 * i + 2] + 1);
    if (f && fclose(f)) status = gb_error_set(GB_EIO, "cannot write %s", path);
    if (h.vertices) gb_polyhedron_free(&h);
    free(nodes);
    gb_contact_grid_free(g);
    return status;
}

/* The rigid limit on Table 1's polyhedron: the compliant law's rest attitude tends to the unilateral law's as k
 * grows. Two compliant runs of about two and four minutes: make verify-full only. */
static void test_polyhedron_rest(void)
{
    if (!gb_check_full) return;
    char dir[GB_CHECK_TEMPDIR_SIZE], path[320];
    gb_check c = {"5", "-",
                  "Gomboc II's 90 x 180 grid polyhedron (12 326 hull vertices) released tilted 0.3 rad on a still plane, c = 3, "
                  "after 50 periods: the angle between its rest vertical under the compliant law (k = 1e5, 1e6 N/m, n = 1, "
                  "alpha = 5 s/m, mu = 10) and under the unilateral law (rough plane)",
                  "the same rest face, and the angle falls at first order in 1/k: by a factor 5 at least over the decade, "
                  "the body still (|omega| <= 1e-5 rad/s) in all three runs",
                  "5: half the factor 10 of first order (the face's compression ~ m g / k, and its tilt with it)"};
    if (gb_check_tempdir("polyhedron", dir, sizeof dir)) {
        gb_check_true(&c, 0, "cannot make a temporary directory");
        return;
    }
    snprintf(path, sizeof path, "%s/polyhedron.obj", dir);
    double z0[3], z1[3], z2[3], s0 = NAN, s1 = NAN, s2 = NAN, r0, r1, r2;
    int status = write_grid_polyhedron(path);
    if (!status) status = polyhedron_rest(dir, 0.0, z0, &s0, &r0);
    if (!status) status = polyhedron_rest(dir, 1e5, z1, &s1, &r1);
    if (!status) status = polyhedron_rest(dir, 1e6, z2, &s2, &r2);
    double a1 = NAN, a2 = NAN;
    if (!status) {
        const double d1 = z0[0] * z1[0] + z0[1] * z1[1] + z0[2] * z1[2], d2 = z0[0] * z2[0] + z0[1] * z2[1] + z0[2] * z2[2];
        double x1[3], x2[3];
        x1[0] = z0[1] * z1[2] - z0[2] * z1[1], x1[1] = z0[2] * z1[0] - z0[0] * z1[2], x1[2] = z0[0] * z1[1] - z0[1] * z1[0];
        x2[0] = z0[1] * z2[2] - z0[2] * z2[1], x2[1] = z0[2] * z2[0] - z0[0] * z2[2], x2[2] = z0[0] * z2[1] - z0[1] * z2[0];
        a1 = atan2(sqrt(x1[0] * x1[0] + x1[1] * x1[1] + x1[2] * x1[2]), d1);
        a2 = atan2(sqrt(x2[0] * x2[0] + x2[1] * x2[1] + x2[2] * x2[2]), d2);
    }
    gb_check_true(&c, !status && a2 * 5.0 <= a1 && fmax(s0, fmax(s1, s2)) <= 1e-5,
                  "%s; angle %.3g rad at k = 1e5, %.3g at 1e6 (order %.2f); |omega| %.2g, %.2g, %.2g rad/s; ledger worst "
                  "%.2g J (unilateral), %.2g, %.2g J (compliant, rtol 1e-6)", status ? gb_error_message() : "ran", a1, a2,
                  log10(a1 / a2), s0, s1, s2, status ? NAN : r0, status ? NAN : r1, status ? NAN : r2);
    remove(path);
    gb_check_tempdir_remove(dir);
}

int verify_register_s5_compliant(void)
{
    static const verify_test tests[] = {
        {"compliant: a sphere's bounce tends to Hunt and Crossley's restitution at order 1/(n+1)", test_bounce,
         "the compliant law's normal force, its elastic energy and the dissipative work booked in the ledger are those of "
         "Hunt and Crossley's law"},
        {"compliant: the rigid limit of a bounce is the unilateral law's", test_rigid_limit, NULL},
        {"compliant: Housner's block rests on its face at the static depth; its rocking tends to the unilateral law's",
         test_housner, NULL},
        {"compliant: Painleve's launch, where the rigid law stops, runs through", test_painleve, NULL},
        {"compliant: Table 1 on the compliant plane closes its ledger", test_table1, NULL},
        {"compliant: Table 1's grid polyhedron rests on the unilateral law's face as k grows (make verify-full)",
         test_polyhedron_rest, NULL},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("A plane that pushes where the body dips in: the compliant law", tests);
}
