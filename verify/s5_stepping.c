/* The time-stepping strategy (Moreau–Jean, [integrator] strategy = time-stepping; gb_dynamics_stepping.c): one
 * frictional contact problem over every point near the plane at each step, solved by Siconos's fc3d. Its one-step
 * problem is checked against the law and the enumeration in s5_friction_impact.c; here, the motions it must follow
 * to the end, each against a closed form or the event-driven strategy:
 * - a box sliding flat on its face stops after v0²/(2μg) at v0/(μg) (the block of cases/bodies/housner-block.off,
 *   half-sides b = 0.1 along the slide and h = 0.4 up);
 * - the same box tips instead where the friction's moment about the centroid beats the weight's about the leading
 *   edge: μ > b/h;
 * - Housner's block released tilted on a plane of finite μ: above μ_c = 3bh/(b² + 4h²) the first impact keeps
 *   ω⁺/ω⁻ = 1 − (3/2) sin²α (α = atan(b/h)) as h → 0; below it the new edge slides;
 * - the die and the coin of cases/bodies on planes of μ = 0.3 and 0.6 come to rest on a face;
 * - Gömböc II's grid polyhedron under Table 1's forcing at μ = 0.5, one period: the state tends to the event-driven
 *   strategy's as the step falls, at order 1 at least;
 * - energy: the ledger E − E0 − W + L closes to rounding (the impulses' work is booked exactly); the impulses take
 *   energy at every step of a box sliding flat, and where the body turns about a held point they give O(h²) a step,
 *   O(h) over the run (docs/stepping.md: the centripetal separation at the step's new attitude). */
#include "gb_case.h"
#include "gb_check.h"
#include "gb_dynamics.h"
#include "gb_error.h"
#include "gb_integrate.h"
#include "gb_run.h"
#include "verify_sections.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double G = 9.81;

/* What a run's samples show: the largest tilt of the body's z axis [rad], the first sample (after sliding) where
 * nothing slides on the plane, and around the first impact of a rocking block (ω falling by more than 1 % between
 * two samples): the rate before and after, and the friction the impact's step needed (|Σ P_t| / Σ P_n). */
typedef struct motion {
    double tilt_max, stop;
    int slid;
    double rate_before, rate_after, last_rate, impact_friction;
    int impacts_seen;
    double kinetic_end, energy0, energy_end;
    int contacts_end;
} motion;

static int observe(void *context, const gb_run_sample *s)
{
    motion *m = context;
    const gb_dynamics_observables *o = s->o;
    m->tilt_max = fmax(m->tilt_max, acos(fmin(1.0, o->R[8])));
    if (o->sliding) m->slid = 1;
    else if (m->slid && isnan(m->stop) && o->contacts) m->stop = s->t;
    const double rate = fabs(o->omega[1]);
    if (!m->impacts_seen && m->last_rate > 0.0 && rate < 0.99 * m->last_rate && s->t > 0.01) {
        m->impacts_seen = 1;
        m->rate_before = m->last_rate, m->rate_after = rate, m->impact_friction = o->friction_needed;
    }
    m->last_rate = rate;
    m->kinetic_end = o->kinetic;
    m->contacts_end = o->contacts;
    if (s->t == 0.0) m->energy0 = o->energy;
    m->energy_end = o->energy;
    return GB_OK;
}

/* Run the scene text (its mesh relative to cases/bodies), the samples into *m. */
static int run_text(const char *text, motion *m, gb_run_result *result)
{
    memset(m, 0, sizeof *m);
    m->stop = NAN;
    gb_case scene;
    const gb_run_sinks sinks = {observe, m, NULL};
    int status = gb_case_load_text("cases/bodies/stepping.ini", text, strlen(text), &scene);
    if (!status) status = gb_run(&scene, &sinks, result);
    return status;
}

/* The block of housner-block.off standing on its face (or tilted `tilt` rad about y onto its bottom edge) on a
 * still plane of friction mu, launched along x at v0, `spp` steps of time-stepping over `seconds`. */
static int block(double mu, double v0, double tilt, size_t spp, double seconds, motion *m, gb_run_result *result)
{
    char text[1200];
    snprintf(text, sizeof text,
             "[body]\nmesh = housner-block.off\nmass = 1\n[forcing]\ng = %.17g\nA1 = 0\nA2 = 0\nomega = 6.283185307179586\n"
             "[model]\ncontact = fast-grid\ncontact_law = unilateral\ndamping = 0\nfriction = %.17g\n[integrator]\n"
             "strategy = time-stepping\nsteps_per_period = %zu\nperiods = %.17g\n[initial]\nattitude = axis-angle 0,1,0,%.17g\n"
             "velocity = %.17g,0,0\n", G, mu, spp, seconds, tilt, v0);
    return run_text(text, m, result);
}

static void test_sliding_box(void)
{
    const double mu = 0.2, v0 = 1.0, distance = v0 * v0 / (2.0 * mu * G), stop = v0 / (mu * G);
    static const size_t spp[3] = {250, 1000, 4000};
    double error[3] = {NAN, NAN, NAN}, stop_error[3] = {NAN, NAN, NAN}, ledger = 0.0;
    size_t negative = 0;
    int status = GB_OK;
    for (int k = 0; k < 3 && !status; k++) {
        motion m;
        gb_run_result r;
        status = block(mu, v0, 0.0, spp[k], 1.0, &m, &r);
        if (status) break;
        error[k] = fabs(r.y[GB_STATE_POSITION] - distance);
        stop_error[k] = fabs(m.stop - stop) * (double)spp[k]; /* in steps */
        negative += r.stepping.negative_dissipation;
        ledger = fmax(ledger, r.residual_max / (0.5 * v0 * v0));
        gb_run_result_free(&r);
    }
    const double order = gb_check_observed_order(error[1], error[2], 1.0 / 1000.0, 1.0 / 4000.0);
    gb_check c = {"-", "-", "a box (cases/bodies/housner-block.off) sliding flat on its face, v0 = 1 m/s, mu = 0.2, time-stepping at "
                  "250, 1000, 4000 steps a second: the distance to rest, observed order between the two finest",
                  "v0^2 / (2 mu g) = 0.2548 m (Coulomb's law, constant deceleration mu g)",
                  "the scheme's order 1 (Moreau-Jean; 2 for this motion at theta = 1/2 with constant forces), as a lower "
                  "bound with 10 % for the rounding of the finest error"};
    gb_check_true(&c, !status && order >= 0.9, "%s; errors %.3g, %.3g, %.3g m, order %.3f", status ? gb_error_message() : "ran",
                  error[0], error[1], error[2], order);
    gb_check ct = {"-", "-", "the same runs: the time the slide stops, in steps", "v0 / (mu g) = 0.5097 s",
                   "one step: the slide stops inside the step whose end first sees it stopped"};
    gb_check_true(&ct, !status && stop_error[0] <= 1.0 && stop_error[1] <= 1.0 && stop_error[2] <= 1.0,
                  "%.3g, %.3g, %.3g steps off", stop_error[0], stop_error[1], stop_error[2]);
    gb_check ce = {"-", "-", "the same runs: the steps whose impulses gave energy, and the ledger's worst |E - E0 - W + L| over "
                   "the kinetic energy", "none: sliding flat, friction only takes (the impulses' work is -mu P_n |u_t| <= 0); the ledger "
                   "books the impulses' work exactly", "exact count; the ledger to 1e-12, rounding over a thousand steps"};
    gb_check_true(&ce, !status && negative == 0 && ledger <= 1e-12, "%zu steps gave energy; ledger %.3g", negative, ledger);
}

static void test_tipping_box(void)
{
    const double b = 0.1, h = 0.4, threshold = b / h;
    motion below, above;
    gb_run_result r;
    int status = block(threshold - 0.005, 1.0, 0.0, 1000, 1.0, &below, &r);
    if (!status) gb_run_result_free(&r), status = block(threshold + 0.005, 1.0, 0.0, 1000, 1.0, &above, &r);
    if (!status) gb_run_result_free(&r);
    gb_check c = {"-", "-", "the same box launched at 1 m/s on planes of mu = 0.245 and 0.255: the largest tilt of its axis",
                  "it slides flat below mu = b/h = 0.25 (the normal force's resultant reaches the leading edge there: mu N h = N b) "
                  "and tips above", "flat: 1e-9 rad (rounding of the attitude); tips: more than 0.01 rad"};
    gb_check_true(&c, !status && below.tilt_max <= 1e-9 && above.tilt_max > 0.01, "%s; tilt %.3g rad at mu = 0.245, %.3g rad at 0.255",
                  status ? gb_error_message() : "ran", below.tilt_max, above.tilt_max);
}

static void test_housner(void)
{
    const double b = 0.1, h = 0.4, alpha = atan(b / h), ratio = 1.0 - 1.5 * sin(alpha) * sin(alpha);
    const double critical = 3.0 * b * h / (b * b + 4.0 * h * h);
    static const size_t spp[3] = {2000, 8000, 32000};
    double error[3] = {NAN, NAN, NAN}, needed[3] = {NAN, NAN, NAN};
    int status = GB_OK;
    for (int k = 0; k < 3 && !status; k++) {
        motion m;
        gb_run_result r;
        status = block(0.5, 0.0, 0.1, spp[k], 0.3, &m, &r);
        if (status) break;
        gb_run_result_free(&r);
        error[k] = m.impacts_seen ? fabs(m.rate_after / m.rate_before - ratio) : NAN;
        needed[k] = m.impacts_seen ? fabs(m.impact_friction - critical) : NAN;
    }
    const double order = gb_check_observed_order(error[1], error[2], 1.0 / 8000.0, 1.0 / 32000.0);
    gb_check c = {"-", "-", "Housner's block (housner-block.off) released tilted 0.1 rad on a plane of mu = 0.5 > mu_c, time-stepping "
                  "at 2000, 8000, 32000 steps a second: omega after over before its first impact, observed order",
                  "1 - (3/2) sin^2(alpha) = 0.911765 (Housner 1963: angular momentum about the new edge kept)",
                  "order 1 (the impact falls in the step that first sees the face closed, O(h) from the instant), as a lower "
                  "bound with 20 % for the samples' rates"};
    gb_check_true(&c, !status && order >= 0.8 && error[2] <= 1e-3, "%s; errors %.3g, %.3g, %.3g, order %.3f",
                  status ? gb_error_message() : "ran", error[0], error[1], error[2], order);
    const double friction_order = gb_check_observed_order(needed[1], needed[2], 1.0 / 8000.0, 1.0 / 32000.0);
    gb_check cs = {"-", "-", "the same runs: the friction the impact's step needed, |sum P_t| / sum P_n, observed order",
                   "mu_c = 3bh/(b^2 + 4h^2) = 0.184615: the friction Housner's impact needs at the new edge, the threshold "
                   "between sticking and sliding there (the event-driven strategy's impact on the rough plane needs it to 1e-13)",
                   "order 1 (the step's impulses hold the weight's m g h beside the impact's), as a lower bound with 20 %"};
    gb_check_true(&cs, !status && friction_order >= 0.8 && needed[2] <= 1e-2 * critical, "%s; |needed - mu_c| %.3g, %.3g, %.3g, "
                  "order %.3f", status ? gb_error_message() : "ran", needed[0], needed[1], needed[2], friction_order);
}

static void test_energy(void)
{
    static const size_t spp[4] = {500, 1000, 2000, 4000};
    double gained[4] = {NAN, NAN, NAN, NAN}, worst[4] = {NAN, NAN, NAN, NAN}, ledger = 0.0, taken_min = INFINITY;
    size_t contact_gave = 0, gave = 0;
    int status = GB_OK;
    for (int k = 0; k < 4 && !status; k++) {
        motion m;
        gb_run_result r;
        status = block(0.255, 1.0, 0.0, spp[k], 1.0, &m, &r);
        if (status) break;
        gained[k] = r.stepping.energy_gained, worst[k] = -r.stepping.dissipation_min;
        taken_min = fmin(taken_min, r.stepping.contact_dissipation_min);
        contact_gave += r.stepping.contact_negative, gave += r.stepping.negative_dissipation;
        ledger = fmax(ledger, r.residual_max / 0.5);
        gb_run_result_free(&r);
    }
    const double order = gb_check_observed_order(gained[2], gained[3], 1.0 / 2000.0, 1.0 / 4000.0);
    const double step_order = gb_check_observed_order(worst[2], worst[3], 1.0 / 2000.0, 1.0 / 4000.0);
    gb_check c = {"-", "-", "the box that tips (mu = 0.255), 500 ... 4000 steps a second: the energy the impulses gave over the run, "
                  "observed order between the two finest; the most one step gave, its order",
                  "a held point the body turns about separates by h omega^2 r at the step's new attitude: 1/2 P_n h omega^2 r a step, "
                  "O(h^2) a step and O(h) over the run, vanishing with h",
                  "orders 1 and 2 within 0.2 (the rates vary along the run)"};
    gb_check_true(&c, !status && fabs(order - 1.0) <= 0.2 && fabs(step_order - 2.0) <= 0.2,
                  "%s; gained %.3g, %.3g, %.3g, %.3g J (order %.3f); worst step %.3g, %.3g, %.3g, %.3g J (order %.3f)",
                  status ? gb_error_message() : "ran", gained[0], gained[1], gained[2], gained[3], order, worst[0], worst[1],
                  worst[2], worst[3], step_order);
    gb_check cd = {"-", "-", "the same runs: what each step's contact problem took from the step's free motion, "
                   "D_c = T(v_f) - T(v+) = -sum P.(u+ + u_f)/2 (u_f with gravity's kick), at every step with a point carrying the body",
                   "D_c >= P'WP/2 >= 0: Signorini's law gives P_n u_n+ = 0 and Coulomb's P_t.u_t+ <= 0 at every point (e = 0); "
                   "the energy above is given where the impulses work against the weight's kick, not the free motion",
                   "no step below -(solver tolerance) x sum |P||u|, the residual the solver leaves"};
    gb_check_true(&cd, !status && contact_gave == 0 && taken_min >= 0.0,
                  "%s; %zu steps below it (the ledger's impulse work was negative at %zu); least D_c %.3g J",
                  status ? gb_error_message() : "ran", contact_gave, gave, taken_min);
    gb_check cl = {"-", "-", "the same runs: the ledger's worst |E - E0 - W + L| over the launch's kinetic energy",
                   "0: L books each step's impulses' work exactly, W the forcing's and damping's", "1e-12: rounding over 4000 steps"};
    gb_check_close(&cl, status ? NAN : ledger, 0.0, 0.0, 1e-12);
}

/* The shipped scene `name` (cases/bodies) on a plane of friction mu, time-stepping: its text without the keys the
 * strategy refuses or replaces, and those keys set. */
static int shipped(const char *name, double mu, motion *m, gb_run_result *r)
{
    static const char *const dropped[] = {"method", "locate_switches", "impacts", "friction"};
    char path[256];
    snprintf(path, sizeof path, "cases/bodies/%s.ini", name);
    char *base = gb_check_read_file(path);
    if (!base) return gb_error_set(GB_EIO, "cannot read %s", path);
    const size_t size = strlen(base) + 400;
    char *text = malloc(size);
    if (!text) {
        free(base);
        return gb_error_set(GB_ENOMEM, "out of memory");
    }
    size_t used = 0;
    for (char *line = strtok(base, "\n"); line; line = strtok(NULL, "\n")) {
        int keep = 1;
        for (size_t k = 0; k < sizeof dropped / sizeof dropped[0]; k++)
            keep = keep && !(strncmp(line, dropped[k], strlen(dropped[k])) == 0 && strchr(" =", line[strlen(dropped[k])]));
        if (!keep) continue;
        used += (size_t)snprintf(text + used, size - used, "%s\n%s", line,
                                 strcmp(line, "[model]") ? (strcmp(line, "[integrator]") ? "" : "strategy = time-stepping\n") : "");
        if (!strcmp(line, "[model]")) used += (size_t)snprintf(text + used, size - used, "friction = %.17g\n", mu);
    }
    free(base);
    memset(m, 0, sizeof *m);
    m->stop = NAN;
    gb_case scene;
    const gb_run_sinks sinks = {observe, m, NULL};
    int status = gb_case_load_text(path, text, strlen(text), &scene);
    free(text);
    if (!status) status = gb_run(&scene, &sinks, r);
    return status;
}

static void test_die_and_coin(void)
{
    static const char *const bodies[2] = {"die-drop", "coin"};
    static const double mus[2] = {0.3, 0.6};
    char detail[800] = "";
    int ok = 1;
    for (int b = 0; b < 2; b++)
        for (int k = 0; k < 2; k++) {
            motion m;
            gb_run_result r;
            const int status = shipped(bodies[b], mus[k], &m, &r);
            const size_t used = strlen(detail);
            if (status) {
                ok = 0;
                snprintf(detail + used, sizeof detail - used, "%s at mu %g: %s; ", bodies[b], mus[k], gb_error_message());
                continue;
            }
            const int rests = m.contacts_end >= 3 && m.kinetic_end <= 1e-12 * (m.energy0 - m.energy_end) && !r.final.sliding;
            ok = ok && rests;
            snprintf(detail + used, sizeof detail - used, "%s at mu %g: %d points, kinetic %.3g J, %zu touches, most %zu points a step; ",
                     bodies[b], mus[k], m.contacts_end, m.kinetic_end, r.impacts, r.stepping.contacts_max);
            gb_run_result_free(&r);
        }
    gb_check c = {"-", "-", "the die dropped 5 cm and the coin falling from its rim (cases/bodies), on planes of mu = 0.3 and 0.6, "
                  "time-stepping at the scenes' steps: the end", "at rest on a face: three points or more on the plane, nothing "
                  "sliding, the kinetic energy gone", "1e-12 of the energy it fell through: rounding"};
    gb_check_true(&c, ok, "%s", detail);
}

/* Gömböc II's grid polyhedron (Table 1's scene, the m/s2 reading) on a plane of μ = 0.5, one period. */
static int table1(int stepping, size_t spp, double y[GB_STATE_SIZE])
{
    char text[1600];
    snprintf(text, sizeof text,
             "[body]\nmorphology = II\nbeta = 0.12\nmass = 1\n[forcing]\ng = 9.81\nA1 = 2.0\nA2 = 1.0\namplitude_units = m/s2\n"
             "omega = 18.0\npsi = pi/3\n[model]\nequation = paper\ncontact = fast-grid\ngrid = 90x180\nnodes = centred\n"
             "damping = 0.02\ncontact_law = unilateral\nfriction = 0.5\n[integrator]\n%s\nsteps_per_period = %zu\nperiods = 1\n",
             stepping ? "strategy = time-stepping" : "method = rk4\nlocate_switches = yes", spp);
    gb_case scene;
    gb_run_result r;
    int status = gb_case_load_text("table1-stepping.ini", text, strlen(text), &scene);
    if (!status) status = gb_run(&scene, NULL, &r);
    if (!status) memcpy(y, r.y, sizeof r.y), gb_run_result_free(&r);
    return status;
}

/* max |ω − ω_event-driven| at the end of `run` time-stepped at each of the n steps a period against its event-driven run
 * at `reference` steps a period (run(stepped, steps_per_period, y)): error[k], NaN from a failure on. */
static int stepped_errors(int (*run)(int stepped, size_t spp, double y[GB_STATE_SIZE]), size_t reference, const size_t *spp,
                          int n, double *error)
{
    double y0[GB_STATE_SIZE], y[GB_STATE_SIZE];
    for (int k = 0; k < n; k++) error[k] = NAN;
    int status = run(0, reference, y0);
    for (int k = 0; k < n && !status; k++) {
        if ((status = run(1, spp[k], y))) break;
        error[k] = 0.0;
        for (int i = 0; i < 3; i++) error[k] = fmax(error[k], fabs(y[GB_STATE_OMEGA + i] - y0[GB_STATE_OMEGA + i]));
    }
    return status;
}

static void test_table1_agrees(void)
{
    static const size_t spp[4] = {640, 2560, 10240, 40960};
    double error[4];
    const int status = stepped_errors(table1, 5120, spp, 4, error);
    const double order = gb_check_observed_order(error[0], error[1], 1.0 / 640.0, 1.0 / 2560.0);
    gb_check c = {"5", "44", "Gomboc II's grid polyhedron, Table 1's forcing (m/s2), mu = 0.5, one period from rest: |omega - "
                  "omega_event-driven| at the end, time-stepping at 640, 2560, 10240, 40960 steps a period; observed order "
                  "between the first two, and the error at the finer ones",
                  "the event-driven strategy (rk4, 5120 steps, every impact and slip located; the same to 1e-9 at 2560 and "
                  "20480): the same law",
                  "order 0.9 at least (Moreau-Jean is first order) where the step dominates; below 1e-5 rad/s finer, where "
                  "the error after each of the run's two node switches depends on where the switch falls within its step "
                  "(a factor up to 10 between neighbouring steps; make verify-full measures its envelope: docs/stepping.md)"};
    gb_check_true(&c, !status && order >= 0.9 && error[2] <= 1e-5 && error[3] <= 1e-5,
                  "%s; errors %.3g, %.3g, %.3g, %.3g rad/s, order %.3f", status ? gb_error_message() : "ran", error[0], error[1],
                  error[2], error[3], order);
}

/* A ball (morphology I at beta = 0, the unit sphere, m = 1) launched at 3 m/s with backspin 2 rad/s on a plane of mu =
 * 0.3, time-stepped on its lowest point (continuous contact), one second at `spp` steps a second. */
static int stepped_ball(size_t spp, gb_run_result *r)
{
    char text[900];
    snprintf(text, sizeof text,
             "[body]\nmorphology = I\nbeta = 0\nmass = 1\n[forcing]\ng = 9.81\nA1 = 0\nA2 = 0\nomega = 6.283185307179586\n"
             "[model]\nequation = rolling\ncontact = continuous\ncontact_law = unilateral\ndamping = 0\nfriction = 0.3\n"
             "[integrator]\nstrategy = time-stepping\nsteps_per_period = %zu\nperiods = 1\n[initial]\nvelocity = 3,0,0\n"
             "omega = 0,-2,0\n", spp);
    gb_case scene;
    int status = gb_case_load_text("ball-stepping.ini", text, strlen(text), &scene);
    return status ? status : gb_run(&scene, NULL, r);
}

static void test_ball_stepped(void)
{
    const double mu = 0.3, g = 9.81, v0 = 3.0, w0 = 2.0, R = 1.0;
    const double t_star = 2.0 * (v0 + R * w0) / (7.0 * mu * g), v_end = (5.0 * v0 - 2.0 * R * w0) / 7.0;
    const double lost = 0.5 * (v0 * v0 + 0.4 * w0 * w0) - 0.5 * 1.4 * v_end * v_end;
    static const size_t spp[3] = {1000, 4000, 16000};
    double slide_error[3] = {NAN, NAN, NAN}, roll_error = 0.0, loss_error = 0.0;
    size_t changes_wrong = 0;
    int status = GB_OK;
    for (int k = 0; k < 3 && !status; k++) {
        gb_run_result r;
        if ((status = stepped_ball(spp[k], &r))) break;
        slide_error[k] = r.has_sliding ? fabs(r.sliding.time - t_star) * (double)spp[k] : NAN; /* in steps */
        roll_error = fmax(roll_error, fmax(fabs(r.y[GB_STATE_VELOCITY] - v_end), fabs(R * r.y[GB_STATE_OMEGA + 1] - v_end)) / v_end);
        loss_error = fmax(loss_error, fabs(r.sliding.friction_loss - lost));
        changes_wrong += !r.has_sliding || r.sliding.slips != 1 || r.sliding.sticks != 1 || r.sliding.sliding;
        gb_run_result_free(&r);
    }
    gb_check c = {"-", "-", "a ball (the unit sphere, continuous contact) launched at 3 m/s with backspin 2 rad/s on a plane of "
                  "mu = 0.3, time-stepped on its lowest point at 1000, 4000, 16000 steps a second: the time it slides, in steps; "
                  "its velocity and R omega_y after; the work friction did",
                  "closed forms, which the event-driven strategy meets (verify/s5_friction.c): 2 (v0 + R w0) / (7 mu g), "
                  "(5 v0 - 2 R w0) / 7 rolling, the kinetic energy lost",
                  "the slide's end within one step (the step that first sees the slip stopped: first order); the rolling "
                  "velocity to 1e-12 relative and the loss to 1e-12 J (the stick is exact once reached); one slip's end, "
                  "one stick, no slip after"};
    gb_check_true(&c, !status && slide_error[0] <= 1.0 && slide_error[1] <= 1.0 && slide_error[2] <= 1.0 && roll_error <= 1e-12 &&
                      loss_error <= 1e-12 && changes_wrong == 0,
                  "%s; slide's end %.3g, %.3g, %.3g steps off; rolling %.3g relative; loss %.3g J; %zu runs with other changes",
                  status ? gb_error_message() : "ran", slide_error[0], slide_error[1], slide_error[2], roll_error, loss_error,
                  changes_wrong);
}

/* The same runs at 8 steps a period within a factor 15/8 of each of 2560, 10240, 40960 and 163840 (make verify-full): the
 * largest |ω − ω_event-driven| of each group, over the node switches' positions within their steps. */
static void test_table1_envelope(void)
{
    if (!gb_check_full) return;
    static const size_t base[4] = {2560, 10240, 40960, 163840};
    double envelope[4] = {0.0, 0.0, 0.0, 0.0}, least[4] = {INFINITY, INFINITY, INFINITY, INFINITY};
    int status = GB_OK;
    for (int g = 0; g < 4 && !status; g++) {
        size_t spp[8];
        double error[8];
        for (int m = 0; m < 8; m++) spp[m] = base[g] * (size_t)(8 + m) / 8;
        status = stepped_errors(table1, 5120, spp, 8, error);
        for (int m = 0; m < 8 && !status; m++) envelope[g] = fmax(envelope[g], error[m]), least[g] = fmin(least[g], error[m]);
    }
    const double order = gb_check_observed_order(envelope[0], envelope[3], 1.0 / 2560.0, 1.0 / 163840.0);
    gb_check c = {"5", "44", "the same scene, time-stepping at 8 steps a period within 15/8 of each of 2560, 10240, 40960, 163840: "
                  "the largest |omega - omega_event-driven| at the end of each group (over where the run's two node switches "
                  "fall within their steps); its observed order from the first group to the last (a step 64 times smaller)",
                  "the event-driven strategy, as above: the same law",
                  "order 0.9 at least: Moreau-Jean is first order, and a switch inside a step costs O(h) times a factor of "
                  "its position in the step, which the 8 steps of a group sample (a floor would give order 0)"};
    gb_check_true(&c, !status && order >= 0.9, "%s; largest %.3g, %.3g, %.3g, %.3g rad/s (least %.3g, %.3g, %.3g, %.3g), "
                  "order %.3f", status ? gb_error_message() : "ran", envelope[0], envelope[1], envelope[2], envelope[3], least[0],
                  least[1], least[2], least[3], order);
}

/* Painlevé's launch (verify_painleve_launch: Gömböc I tilted 0.7 rad, sliding at 0.5 m/s along the direction that
 * makes K(μ) vanish at μ*) on its grid polyhedron under time-stepping, 0.1 s at 20000 steps a second: the first steps'
 * normal impulse over the weight's m g h, the slip after them, the energy the impulses gave. */
typedef struct jam {
    double first_impulse_ratio, slip_after, kinetic0, kinetic_after;
    int samples;
} jam;

static int jam_sample(void *context, const gb_run_sample *s)
{
    jam *l = context;
    const gb_dynamics_observables *o = s->o;
    if (l->samples == 0) l->kinetic0 = o->kinetic;
    if (l->samples == 1) l->first_impulse_ratio = o->normal_force / (1.0 * 9.81), l->slip_after = o->slip_speed,
                         l->kinetic_after = o->kinetic;
    l->samples++;
    return GB_OK;
}

static int painleve(double mu, const double R0[9], const double v[3], jam *l, gb_run_result *r)
{
    char text[1400], attitude[200];
    /* R0 is a rotation about x by 0.7 rad */
    snprintf(attitude, sizeof attitude, "axis-angle 1,0,0,%.17g", atan2(R0[7], R0[8]));
    snprintf(text, sizeof text,
             "[body]\nmorphology = I\nbeta = 0.12\nmass = 1\n[forcing]\ng = 9.81\nA1 = 0\nA2 = 0\nomega = 6.283185307179586\n"
             "[model]\ncontact = fast-grid\ncontact_law = unilateral\ndamping = 0\nfriction = %.17g\n[integrator]\n"
             "strategy = time-stepping\nsteps_per_period = 20000\nperiods = 0.1\n[initial]\nattitude = %s\n"
             "velocity = %.17g,%.17g,%.17g\n", mu, attitude, v[0], v[1], v[2]);
    memset(l, 0, sizeof *l);
    gb_case scene;
    const gb_run_sinks sinks = {jam_sample, l, NULL};
    int status = gb_case_load_text("painleve-stepping.ini", text, strlen(text), &scene);
    if (!status) status = gb_run(&scene, &sinks, r);
    return status;
}

static void test_painleve(void)
{
    double R0[9], mu_star, d1, d2, v[3];
    int status = verify_painleve_launch(R0, &mu_star, &d1, &d2, v);
    static const double factors[3] = {0.5, 1.1, 2.0};
    char detail[900] = "";
    jam l[3];
    gb_run_result r[3];
    int ran = 0;
    for (int k = 0; k < 3 && !status; k++) {
        status = painleve(factors[k] * mu_star, R0, v, &l[k], &r[k]);
        if (status) break;
        ran++;
        const size_t used = strlen(detail);
        snprintf(detail + used, sizeof detail - used, "%g mu*: first step's P_n / (m g h) %.4g, slip after %.3g m/s, kinetic "
                 "%.4g -> %.4g J, energy given %.3g J in %zu steps; ", factors[k], l[k].first_impulse_ratio, l[k].slip_after,
                 l[k].kinetic0, l[k].kinetic_after, r[k].stepping.energy_gained, r[k].stepping.negative_dissipation);
        gb_run_result_free(&r[k]);
    }
    gb_check c = {"-", "-", "Painleve's launch (Gomboc I tilted 0.7 rad, sliding at 0.5 m/s; mu* from the closed form) on its grid "
                  "polyhedron under time-stepping at 0.5, 1.1 and 2 mu*, 0.1 s at 20000 steps a second: the first step",
                  "below mu*: the slide goes on, its normal force g / K(mu) (the first step's P_n / (m g h) = 1/(m K), 2 at 0.5 "
                  "mu* when 1/m dominates); beyond mu*, where no force is consistent, the impact without collision of Genot and "
                  "Brogliato (1999): an impulse at a point that does not approach stops the slip at once, taking energy, and the "
                  "run goes on (the event-driven strategy stops there, naming the paradox)",
                  "beyond mu*: the first step's impulse over 100 m g h, the slip after below 1e-6 m/s, the kinetic energy "
                  "fallen; below: the slide on (slip after above 0.4 m/s); every run to its end"};
    int ok = !status && ran == 3 && l[0].slip_after > 0.4;
    for (int k = 1; k < 3 && ok; k++)
        ok = l[k].first_impulse_ratio > 100.0 && l[k].slip_after < 1e-6 && l[k].kinetic_after < l[k].kinetic0;
    gb_check_true(&c, ok, "%s; mu* = %.6g; %s", status ? gb_error_message() : "ran", mu_star, detail);
}

/* Gömböc I (continuous contact: the smooth body's minima) launched as Painlevé's (verify_painleve_launch) at friction mu,
 * the forcing and integrator lines given, `periods` of `spp` steps, λ or not: its run and the first samples (jam). */
static int smooth_launch(double mu, const double R0[9], const double v[3], const char *forcing, const char *integrator,
                         double periods, size_t spp, int lambda, jam *l, gb_run_result *r)
{
    char text[2000], attitude[200];
    snprintf(attitude, sizeof attitude, "axis-angle 1,0,0,%.17g", atan2(R0[7], R0[8]));
    snprintf(text, sizeof text,
             "[body]\nmorphology = I\nbeta = 0.12\nmass = 1\n[forcing]\ng = 9.81\n%s[model]\nequation = rolling\ncontact = continuous\n"
             "contact_law = unilateral\ndamping = 0.02\nfriction = %.17g\n[integrator]\n%ssteps_per_period = %zu\n"
             "periods = %.17g\n[initial]\nattitude = %s\nvelocity = %.17g,%.17g,%.17g\n[diagnostics]\nlyapunov = %s\n"
             "[lyapunov]\ndelta0 = 1e-7\ntransient_periods = 0\ninterval_periods = 1\n",
             forcing, mu, integrator, spp, periods, attitude, v[0], v[1], v[2], lambda ? "yes" : "no");
    memset(l, 0, sizeof *l);
    gb_case scene;
    const gb_run_sinks sinks = {jam_sample, l, NULL};
    int status = gb_case_load_text("painleve-smooth.ini", text, strlen(text), &scene);
    if (!status) status = gb_run(&scene, &sinks, r);
    return status;
}

static const char still[] = "A1 = 0\nA2 = 0\nomega = 6.283185307179586\n";
static const char table1_g[] = "A1 = 2\nA2 = 1\namplitude_units = g\nomega = 18\npsi = pi/3\n";

/* Table 1's Gömböc I in units of g on continuous contact at μ = 0.5, one period from rest on the plane (R0 = I): ω at
 * the end, time-stepped on the smooth body's minima or event-driven. */
static int smooth_table1(int stepped, size_t spp, double y[GB_STATE_SIZE])
{
    char text[1200];
    snprintf(text, sizeof text,
             "[body]\nmorphology = I\nbeta = 0.12\nmass = 1\n[forcing]\n%s[model]\nequation = rolling\n"
             "contact = continuous\ndamping = 0.02\ncontact_law = unilateral\nfriction = 0.5\n[integrator]\n%s\n"
             "steps_per_period = %zu\nperiods = 1\n", table1_g, stepped ? "strategy = time-stepping" : "locate_switches = yes",
             spp);
    gb_case scene;
    gb_run_result r;
    int status = gb_case_load_text("table1-smooth.ini", text, strlen(text), &scene);
    if (!status) status = gb_run(&scene, NULL, &r);
    if (status) return status;
    memcpy(y, r.y, sizeof r.y);
    gb_run_result_free(&r);
    return GB_OK;
}

static void test_smooth_agrees(void)
{
    static const size_t spp[4] = {640, 2560, 10240, 40960};
    double error[4];
    const int status = stepped_errors(smooth_table1, 2560, spp, 4, error);
    double order[3];
    for (int k = 0; k < 3; k++) order[k] = gb_check_observed_order(error[k], error[k + 1], 1.0 / (double)spp[k], 1.0 / (double)spp[k + 1]);
    gb_check c = {"5", "44", "Gomboc I on continuous contact (the smooth body: its certified lowest minimum and the minima near "
                  "the plane are the step's points), Table 1 in units of g, mu = 0.5, one period from rest: |omega - "
                  "omega_event-driven| at the end, time-stepping at 640, 2560, 10240, 40960 steps a period; the observed "
                  "orders",
                  "the event-driven strategy on the same continuous contact (rk4, 2560 steps, every impact, lift-off and "
                  "landing located): the same law on the same body",
                  "order 0.9 at least on every quartering, to the finest (Moreau-Jean is first order; a smooth body has no "
                  "node switches whose position within a step scatters single runs, as the grid polyhedron's do)"};
    gb_check_true(&c, !status && order[0] >= 0.9 && order[1] >= 0.9 && order[2] >= 0.9,
                  "%s; errors %.3g, %.3g, %.3g, %.3g rad/s, orders %.3f, %.3f, %.3f", status ? gb_error_message() : "ran",
                  error[0], error[1], error[2], error[3], order[0], order[1], order[2]);
}

/* The hand-over ([integrator] hand_over = time-stepping) on Painlevé's launch of Gömböc I on continuous contact. */
/* Painlevé's launch (verify_painleve_launch) run `count` times by smooth_launch, run k at factor[k] μ* with integrator[k]
 * and λ or not: the runs done in *ran (each to free), μ* in *mu_star; the first failure's status. */
static int launches(int count, const double *factor, const char *const *integrator, const int *lambda, const char *forcing,
                    double periods, size_t spp, jam *l, gb_run_result *r, int *ran, double *mu_star)
{
    double R0[9], d1, d2, v[3];
    int status = verify_painleve_launch(R0, mu_star, &d1, &d2, v);
    *ran = 0;
    for (int k = 0; k < count && !status; k++)
        if (!(status = smooth_launch(factor[k] * *mu_star, R0, v, forcing, integrator[k], periods, spp, lambda[k], &l[k], &r[k])))
            (*ran)++;
    return status;
}

static const char handed[] = "locate_switches = yes\nhand_over = time-stepping\n";

static void test_hand_over(void)
{
    jam l[4];
    gb_run_result r[4];
    int ran = 0;
    double mu_star;
    /* 1.1 mu*: time-stepped throughout, and event-driven handed over; 0.5 mu*: event-driven with and without hand-over */
    static const char *const integrator[4] = {"strategy = time-stepping\n", handed, handed, "locate_switches = yes\n"};
    static const double factor[4] = {1.1, 1.1, 0.5, 0.5};
    static const int no_lambda[4] = {0, 0, 0, 0};
    const int status = launches(4, factor, integrator, no_lambda, still, 0.1, 20000, l, r, &ran, &mu_star);
    const gb_integrate_stats *h = ran > 1 ? &r[1].stats : NULL;
    const int jammed = ran > 0 && l[0].first_impulse_ratio > 100.0 && l[0].slip_after < 1e-6 && l[0].kinetic_after < l[0].kinetic0;
    const int over = h && h->hand_overs == 1 && h->hand_over_first == 0.0 && h->hand_backs == 0 &&
                     h->stepped_steps == h->steps && strstr(h->hand_over_reason, "Painleve") != NULL;
    const int same_stepped = ran > 1 && r[0].state_fingerprint == r[1].state_fingerprint;
    const int untouched = ran == 4 && r[2].stats.hand_overs == 0 && r[2].state_fingerprint == r[3].state_fingerprint &&
                          r[2].switch_fingerprint == r[3].switch_fingerprint;
    char detail[800];
    snprintf(detail, sizeof detail, "(%zu problems, %zu sweeps, %zu fallbacks, %zu enumerated, residual <= %.2g) mu* = %.6g; stepped: first step's P_n / (m g h) %.4g, slip after %.3g m/s, kinetic %.4g -> "
             "%.4g J; handed over %zu time(s) at t = %g (%s...), %zu of %zu steps stepped, final state %s the stepped run's; "
             "0.5 mu*: %zu hand-overs, fingerprints %s", ran > 0 ? r[0].stepping.problems : 0, ran > 0 ? r[0].stepping.sweeps : 0,
             ran > 0 ? r[0].stepping.fallbacks : 0, ran > 0 ? r[0].stepping.enumerated : 0, ran > 0 ? r[0].stepping.residual_max : NAN, mu_star, ran > 0 ? l[0].first_impulse_ratio : NAN,
             ran > 0 ? l[0].slip_after : NAN, ran > 0 ? l[0].kinetic0 : NAN, ran > 0 ? l[0].kinetic_after : NAN,
             h ? h->hand_overs : 0, h ? h->hand_over_first : NAN, h ? strndupa(h->hand_over_reason, 60) : "",
             h ? h->stepped_steps : 0, h ? h->steps : 0, same_stepped ? "equal to" : "differs from",
             ran == 4 ? r[2].stats.hand_overs : 0, untouched ? "equal with and without" : "differ");
    for (int k = 0; k < ran; k++) gb_run_result_free(&r[k]);
    gb_check c = {"-", "-", "Painleve's launch of Gomboc I on continuous contact (still plane, 0.1 s at 20000 steps a second): "
                  "time-stepped on the smooth body's minima at 1.1 mu*; event-driven with hand_over = time-stepping at 1.1 mu* "
                  "and at 0.5 mu*",
                  "time-stepping resolves the paradox by the impact without collision (as on the grid polyhedron); the "
                  "event-driven law meets it at the first step and hands the step over, the run then time-stepping's bit for "
                  "bit (the same state, steps and points); where the law follows (0.5 mu*) the hand-over changes nothing",
                  "impulse over 100 m g h, slip after below 1e-6 m/s; one hand-over at t = 0 naming the paradox, every step "
                  "stepped, equal fingerprints; at 0.5 mu* no hand-over and equal fingerprints"};
    gb_check_true(&c, !status && jammed && over && same_stepped && untouched, "%s; %s", status ? gb_error_message() : "ran", detail);
}

/* The law's limits are marked where they are raised (gb_error_set_limit): a message that wraps one keeps the mark, any
 * other message drops it; Painlevé's launch beyond μ* without a hand-over stops at a limit, a bad key is no limit. */
static void test_limits(void)
{
    gb_error_set_limit(GB_ENUMERIC, "friction at t = 0: a limit");
    const int marked = gb_error_at_limit();
    gb_error_set(GB_ENUMERIC, "a step at t = 1: %s", gb_error_message());
    const int wrapped = gb_error_at_limit();
    gb_error_set(GB_ENUMERIC, "GSL failed at t = 2");
    const int other = gb_error_at_limit();
    gb_error_set_limit(GB_ENUMERIC, "another limit");
    gb_error_clear();
    const int cleared = gb_error_at_limit();
    jam l[1];
    gb_run_result r[1];
    int ran = 0;
    double mu_star;
    static const char *const events[1] = {"locate_switches = yes\n"};
    static const double factor[1] = {1.1};
    static const int no_lambda[1] = {0};
    const int status = launches(1, factor, events, no_lambda, still, 0.1, 20000, l, r, &ran, &mu_star);
    const int stopped = status == GB_ENUMERIC && gb_error_at_limit() && strstr(gb_error_message(), "Painleve") != NULL;
    char message[200];
    snprintf(message, sizeof message, "%s", status ? gb_error_message() : "ran");
    for (int k = 0; k < ran; k++) gb_run_result_free(&r[k]);
    gb_case scene;
    static const char bad_text[] = "[integrator]\nhand_over = sometimes\n";
    const int bad = gb_case_load_text("bad.ini", bad_text, strlen(bad_text), &scene);
    const int not_limit = bad == GB_EINVAL && !gb_error_at_limit();
    gb_error_clear();
    gb_check c = {"-", "-", "the law's limits, marked where they are raised: a mark, a message wrapping it, another message, "
                  "a cleared one; Painleve's launch at 1.1 mu* event-driven without a hand-over; a bad scene key",
                  "marked 1, wrapped 1, other 0, cleared 0; the run stops at a limit naming the paradox; a bad key is no limit",
                  "exact"};
    gb_check_true(&c, marked && wrapped && !other && !cleared && stopped && not_limit,
                  "marked %d, wrapped %d, other %d, cleared %d; the launch: %.120s; bad key: limit %d", marked, wrapped, other,
                  cleared, message, !not_limit);
}

/* Painlevé's launch on Table 1's plane in units of g: the hand-over, the return in flight, λ by the pair. */
static void test_hand_back(void)
{
    jam l[2];
    gb_run_result r[2];
    int ran = 0;
    double mu_star;
    static const char *const integrator[2] = {handed, handed};
    static const double factor[2] = {1.1, 1.1};
    static const int with_lambda[2] = {0, 1};
    const int status = launches(2, factor, integrator, with_lambda, table1_g, 10, 160, l, r, &ran, &mu_star);
    const gb_integrate_stats *h = ran ? &r[0].stats : NULL;
    const int cycled = h && h->hand_overs >= 1 && h->hand_backs >= 1 && h->stepped_steps < h->steps;
    const int reference = ran == 2 && r[0].state_fingerprint == r[1].state_fingerprint &&
                          r[0].switch_fingerprint == r[1].switch_fingerprint;
    const double lambda = ran == 2 ? r[1].lyapunov.lambda_max : NAN;
    const size_t unmatched = ran == 2 ? r[1].pair_stats.unmatched : 0;
    const double residual = ran ? fabs(r[0].final.residual) : NAN, given = ran ? r[0].stepping.energy_gained : NAN;
    char detail[400];
    snprintf(detail, sizeof detail, "%zu hand-overs, %zu returns, %zu of %zu steps stepped; pair: reference %s, lambda %.4g 1/s, "
             "%zu steps of the copy unmatched; final ledger residual %.3g J, the impulses gave %.3g J",
             h ? h->hand_overs : 0, h ? h->hand_backs : 0, h ? h->stepped_steps : 0, h ? h->steps : 0,
             reference ? "bit for bit the plain run" : "differs", lambda, unmatched, residual, given);
    for (int k = 0; k < ran; k++) gb_run_result_free(&r[k]);
    gb_check c = {"-", "-", "Painleve's launch of Gomboc I (1.1 mu*) on Table 1's plane in units of g, event-driven with "
                  "hand_over = time-stepping, 10 periods at 160 steps, with and without lambda",
                  "the run is handed over at the paradox and taken back by the events where the body flies; the pair "
                  "estimator's reference is the plain run bit for bit, its copy handed over and back at the reference's "
                  "steps (the separation never mixes the two strategies' errors)",
                  "at least one hand-over and one return, some steps event-driven; equal fingerprints; lambda finite; no "
                  "unmatched step"};
    gb_check_true(&c, !status && cycled && reference && isfinite(lambda) && unmatched == 0, "%s; %s",
                  status ? gb_error_message() : "ran", detail);
}

/* Table 1's Gömböc II grid polyhedron at μ = 0.5 (m/s²), 20 periods stepped in time, with and without λ. */
static int table1_lambda(int lambda, gb_run_result *r)
{
    char text[1600];
    snprintf(text, sizeof text,
             "[body]\nmorphology = II\nbeta = 0.12\nmass = 1\n[forcing]\ng = 9.81\nA1 = 2.0\nA2 = 1.0\namplitude_units = m/s2\n"
             "omega = 18.0\npsi = pi/3\n[model]\nequation = paper\ncontact = fast-grid\ngrid = 90x180\nnodes = centred\n"
             "damping = 0.02\ncontact_law = unilateral\nfriction = 0.5\n[integrator]\nstrategy = time-stepping\n"
             "steps_per_period = 160\nperiods = 20\n[diagnostics]\nlyapunov = %s\n[lyapunov]\ndelta0 = 1e-7\n"
             "transient_periods = 0\ninterval_periods = 1\n", lambda ? "yes" : "no");
    gb_case scene;
    int status = gb_case_load_text("table1-stepping-lambda.ini", text, strlen(text), &scene);
    if (!status) status = gb_run(&scene, NULL, r);
    return status;
}

/* Gömböc II's grid polyhedron under Table 1's forcing in units of g, μ = 0.5, released at R0 = I (its polar cap, 180
 * nearly level nodes, on the plane), 2 periods stepped at 160 a period: its final state, with the step posing the
 * 64 most urgent candidates first (`first` 64) or every candidate at once (0). */
static int polar_cap(size_t first, gb_run_result *r)
{
    static const char text[] =
        "[body]\nmorphology = II\n[forcing]\nA1 = 2\nA2 = 1\namplitude_units = g\n[model]\nequation = paper\n"
        "contact = fast-grid\ncontact_law = unilateral\nfriction = 0.5\n[integrator]\nstrategy = time-stepping\n"
        "steps_per_period = 160\nperiods = 2\nlocate_switches = no\n[initial]\nattitude = identity\n";
    gb_case scene;
    int status = gb_case_load_text("polar-cap.ini", text, strlen(text), &scene);
    if (status) return status;
    scene.integrate.stepping_first = first;
    return gb_run(&scene, NULL, r);
}

static void test_polar_cap(void)
{
    gb_run_result reduced, whole;
    int status = polar_cap(64, &reduced);
    if (!status && (status = polar_cap(0, &whole))) gb_run_result_free(&reduced);
    double dq = NAN, dw = NAN;
    size_t candidates = 0, posed = 0, posed_whole = 0, grown = 0;
    if (!status) {
        dq = dw = 0.0;
        for (int i = 0; i < 4; i++) dq = fmax(dq, fabs(reduced.y[GB_STATE_Q + i] - whole.y[GB_STATE_Q + i]));
        for (int i = 0; i < 3; i++)
            dw = fmax(dw, fabs(reduced.y[GB_STATE_OMEGA + i] - whole.y[GB_STATE_OMEGA + i]));
        candidates = reduced.stepping.candidates_max, posed = reduced.stepping.contacts_max;
        posed_whole = whole.stepping.contacts_max, grown = reduced.stepping.grown;
        gb_run_result_free(&reduced), gb_run_result_free(&whole);
    }
    gb_check c = {"5", "44", "Gomboc II's grid polyhedron, Table 1 in units of g, mu = 0.5, from R0 = I (its polar cap on the plane), "
                  "2 periods at 160 steps: the final |q| and |omega| differences between a step that poses the 64 most urgent "
                  "candidates first and adds those that would go through the plane, and one that poses every candidate",
                  "the same state: zero impulse at the points left out that do not go through completes the posed solution "
                  "to one of the whole problem (and the reduction engages: more than 64 candidates, fewer posed)",
                  "1e-8 (rad/s and in q): the solver's relative 1e-12 a step over 320 steps, grown by the flow's exp(lambda t) "
                  "~ 6 over 0.7 s"};
    gb_check_true(&c, !status && dq <= 1e-8 && dw <= 1e-8 && candidates > 64 && posed < candidates,
                  "%s; |dq| %.2g, |domega| %.2g rad/s; up to %zu candidates, %zu posed (%zu posed again with a point that went "
                  "through), %zu posed at once", status ? gb_error_message() : "ran", dq, dw, candidates, posed, grown, posed_whole);
}

static void test_lambda(void)
{
    gb_run_result with, without;
    int status = table1_lambda(1, &with);
    if (!status) {
        status = table1_lambda(0, &without);
        if (status) gb_run_result_free(&with);
    }
    const int same = !status && with.state_fingerprint == without.state_fingerprint && with.switch_fingerprint == without.switch_fingerprint;
    const double lambda = status ? NAN : with.lyapunov.lambda_max, error = status ? NAN : with.lyapunov.error_bar;
    if (!status) gb_run_result_free(&with), gb_run_result_free(&without);
    gb_check c = {"6", "77", "Gomboc II's grid polyhedron, Table 1 (m/s2), mu = 0.5, 20 periods stepped in time: the pair estimator's "
                  "reference against the plain run, and lambda",
                  "the reference takes exactly the plain run's steps (the same fingerprints of the final state and of the switches); "
                  "the perturbed copy starts from the reference's contacts and impulses (gb_dynamics_adopt_contact), its height "
                  "and velocity displaced as the state's own",
                  "bit for bit; lambda finite with a finite error bar"};
    gb_check_true(&c, same && isfinite(lambda) && isfinite(error), "%s; fingerprints %s; lambda %.4g +- %.3g 1/s",
                  status ? gb_error_message() : "ran", same ? "equal" : "differ", lambda, error);
}

static void test_names(void)
{
    gb_strategy strategy = GB_STRATEGY_EVENT_DRIVEN;
    const int parsed = gb_integrate_strategy_parse("time-stepping", &strategy) == GB_OK && strategy == GB_STRATEGY_TIME_STEPPING &&
                       !strcmp(gb_integrate_strategy_name(strategy), "time-stepping");
    const int refused = gb_integrate_strategy_parse("moreau", &strategy) == GB_EINVAL &&
                        strstr(gb_error_message(), "allowed: event-driven, time-stepping") != NULL;
    gb_error_clear();
    /* a dynamics stepped in time reports its work; one driven by events has none */
    const gb_dynamics_def def = gb_dynamics_default_def();
    const double R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, w0[3] = {0, 0, 0};
    double y[GB_STATE_SIZE];
    gb_dynamics *d = NULL;
    const int status = gb_dynamics_start(gb_check_body("II", 0.12), &def, R0, w0, &d, y);
    const int none = !status && gb_dynamics_stepping_stats_of(d) == NULL;
    gb_dynamics_free(d);
    gb_check c = {"-", "-", "the strategies' names; the time-stepping statistics of an event-driven run",
                  "event-driven and time-stepping read and written back, another name refused naming both; none for events",
                  "exact"};
    gb_check_true(&c, parsed && refused && none, "parsed %d, refused %d, no statistics %d", parsed, refused, none);
}

int verify_register_s5_stepping(void)
{
    static const verify_test tests[] = {
        {"time-stepping: a box slides flat to v0^2/(2 mu g) in v0/(mu g)", test_sliding_box,
         "the time-stepping strategy follows sliding on a face (four points) to rest as Coulomb's law does"},
        {"time-stepping: a box tips instead of sliding above mu = b/h", test_tipping_box, NULL},
        {"time-stepping: Housner's block on finite mu rocks with Housner's ratio above mu_c and slides below", test_housner, NULL},
        {"time-stepping: the impulses' energy, exact in the ledger; gained only where the body turns about a held point, O(h)",
         test_energy, NULL},
        {"time-stepping: the die and the coin at mu = 0.3 and 0.6 come to rest on a face", test_die_and_coin,
         "bodies the event-driven strategy cannot follow on a plane of finite friction run to the end under time-stepping"},
        {"time-stepping: Table 1's grid polyhedron at mu = 0.5 tends to the event-driven strategy's", test_table1_agrees,
         "where both strategies run they agree: the time-stepping at order 1 or better, the error after a node switch "
         "scattered by the switch's position within its step"},
        {"time-stepping: a ball slides, then rolls, as the closed form says", test_ball_stepped,
         "the smooth body's lowest point under time-stepping: the slide ends within a step of the closed form's time"},
        {"time-stepping: the same, its envelope over the switches' positions in their steps (make verify-full)",
         test_table1_envelope, "no floor: first order over a step 64 times smaller"},
        {"time-stepping: Painleve's launch beyond mu* runs through an impact without collision", test_painleve,
         "where the event-driven strategy meets Painleve's paradox and stops, time-stepping resolves it at the impulse level"},
        {"time-stepping: on a smooth body's minima (continuous contact) it tends to the event-driven strategy's at order 1",
         test_smooth_agrees, NULL},
        {"hand-over: where the event-driven law meets Painleve's paradox the step is time-stepped, and only there",
         test_hand_over, "a run the event-driven law cannot follow goes on under time-stepping where it is asked to"},
        {"hand-over: the events take the run back in flight; the Lyapunov pair hands over together", test_hand_back, NULL},
        {"hand-over: the law's limits are marked where they are raised, and only they", test_limits, NULL},
        {"time-stepping: a polar cap's hundreds of candidates, the most urgent posed first, give every candidate's answer",
         test_polar_cap, NULL},
        {"time-stepping: lambda by the pair estimator, its reference the plain run bit for bit", test_lambda, NULL},
        {"time-stepping: the strategies' names", test_names, NULL},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Time-stepping: Moreau-Jean with Siconos's fc3d on every point near the plane", tests);
}
