/* A plane of finite friction (2 of 2): the dynamics between impacts (gb_dynamics, [model] friction = μ); the
 * impacts themselves are s5_friction_impact.c. Oracles:
 * - A ball (β = 0, radius R) launched on the plane with speed v0 and backspin ω0 slides until
 *   t = 2 (v0 + R ω0) / (7 μ g), then rolls at (5 v0 − 2 R ω0) / 7; friction took the kinetic energy lost.
 * - The same ball dropped with a horizontal speed lands sticking or sliding at the closed-form ratio, as
 *   the impact law alone does, through the dynamics' flight and landing.
 * - Painlevé's paradox: a Gömböc sliding on one point with ω = 0 has the normal force g / K(μ) of a closed
 *   form in its mass properties and contact, and beyond the μ* where K vanishes the run stops, naming it.
 * - μ → ∞: a Table 1 run is the rough plane's to rounding; the energy ledger E − E0 − W + L closes with
 *   friction's work in L (a ball's to rounding; a Table 1 run's to the integration's accuracy, which falls
 *   with the step). */
#include "gb_case.h"
#include "gb_check.h"
#include "gb_dynamics.h"
#include "gb_error.h"
#include "gb_impact.h"
#include "gb_integrate.h"
#include "gb_massprops.h"
#include "gb_run.h"
#include "s5_friction.h"
#include "verify_sections.h"

#include <cjson/cJSON.h>
#include <gsl/gsl_linalg.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* ---- the dynamics: a ball on a plane of finite friction ----------------------------------------- */

typedef struct ball_log {
    int landings;
    gb_dynamics_impact first;
} ball_log;

static int ball_impact(void *context, const gb_dynamics_impact *e)
{
    ball_log *log = context;
    if (e->kind == GB_DYNAMICS_IMPACT_LANDING && !log->landings++) log->first = *e;
    return GB_OK;
}

/* A ball (morphology I at β = 0: the unit sphere) on a fixed plane (A1 = A2 = 0, no damping), continuous
 * contact, the rolling equation, unilateral contact with friction mu; `periods` forcing periods of RK4, 160
 * steps a period. */
static int ball_run(double mu, double e, double height, const double v0[3], const double w0[3], double periods,
                    double y[GB_STATE_SIZE], gb_dynamics_sliding_summary *sliding, ball_log *log, double *residual)
{
    gb_surface ball;
    int status = gb_surface_init(&ball, "I", 0.0);
    gb_dynamics_def def = gb_dynamics_default_def();
    def.variant = GB_VARIANT_ROLLING, def.contact = GB_CONTACT_MODEL_CONTINUOUS, def.contact_law = GB_CONTACT_LAW_UNILATERAL;
    def.friction = mu, def.restitution = e, def.damping = 0.0, def.height0 = height;
    def.forcing.a1 = def.forcing.a2 = 0.0;
    memcpy(def.velocity0, v0, sizeof def.velocity0);
    gb_integrate_def idef = gb_integrate_default_def();
    idef.locate_switches = 1, idef.periods = periods;
    const double R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    gb_dynamics *d = NULL;
    if (!status) status = gb_dynamics_start(&ball, &def, R0, w0, &d, y);
    if (!status && log) gb_dynamics_set_impact_sink(d, ball_impact, log);
    gb_integrate_stats stats;
    if (!status) status = gb_integrate_run(d, &idef, 0.0, y, NULL, NULL, &stats);
    const double t = periods * gb_forcing_period(&def.forcing);
    gb_dynamics_observables o;
    if (!status) status = gb_dynamics_observe(d, t, y, &o);
    if (!status) gb_dynamics_sliding_stats(d, t, y, sliding), *residual = o.residual;
    gb_dynamics_free(d);
    return status;
}

static void test_ball_slides_then_rolls(void)
{
    const double mu = 0.3, g = 9.81, v0 = 3.0, w0 = 2.0, R = 1.0, I = 0.4; /* m = 1 */
    const double v[3] = {v0, 0.0, 0.0}, w[3] = {0.0, -w0, 0.0}; /* backspin: ω_y < 0 for a motion along +x */
    double y[GB_STATE_SIZE], residual = NAN;
    gb_dynamics_sliding_summary sl;
    const int status = ball_run(mu, 0.0, 0.0, v, w, 3.0, y, &sl, NULL, &residual);
    const double t_star = 2.0 * (v0 + R * w0) / (7.0 * mu * g), v_end = (5.0 * v0 - 2.0 * R * w0) / 7.0;
    gb_check ct = {"-", "-", "a ball launched at 3 m/s with backspin 2 rad/s on a plane of mu 0.3: the time it slides",
                   "closed form 2 (v0 + R w0) / (7 mu g)",
                   "1e-6 s: the slip is taken as stopped at 1e-6 of the motion's speeds (about 6e-6 m/s), which it crosses at "
                   "(7/2) mu g = 10 m/s^2"};
    gb_check_close(&ct, status ? NAN : sl.time, t_star, 0.0, 1e-6);
    gb_check cv = {"-", "-", "the same ball after: its velocity and R omega_y", "closed form (5 v0 - 2 R w0) / 7, rolling",
                   "1e-12 relative: the stop's slip removed by the impulse friction would have spent (the ball's Delassus "
                   "operator is isotropic), rounding"};
    gb_check_close(&cv, status ? NAN : y[GB_STATE_VELOCITY], v_end, 1e-12, 0.0);
    gb_check_close(&cv, status ? NAN : R * y[GB_STATE_OMEGA + 1], v_end, 1e-12, 0.0);
    const double lost = 0.5 * (v0 * v0 + I * w0 * w0) - 0.5 * (v_end * v_end + I * v_end * v_end / (R * R));
    gb_check cl = {"-", "-", "the same ball: the work friction did", "the kinetic energy lost, (1/2)(v0^2 + I w0^2) - (1/2)(1 + I/R^2) v_end^2",
                   "1e-11 J: the slip left at the stop (1e-6 of the speeds, 6e-6 m/s) is taken by the hold's impulse, "
                   "(1/2) (2/7) m (6e-6)^2 = 5e-12 J booked with the impacts' part of L, not friction's"};
    gb_check_close(&cl, status ? NAN : sl.friction_loss, lost, 0.0, 1e-11);
    gb_check cr = {"-", "46-51", "the same ball: the ledger E - E0 - W + L", "0", "1e-12 J: rounding of the integrated friction power"};
    gb_check_close(&cr, status ? NAN : residual, 0.0, 0.0, 1e-12);
    gb_check cs = {"-", "-", "the same ball: its changes", "the launch's slip ended by one stick, no slip after, rolling at the end",
                   "exact"};
    gb_check_true(&cs, !status && sl.sticks == 1 && sl.slips == 0 && !sl.sliding, "%zu slips, %zu sticks, sliding at the end %d", sl.slips,
                  sl.sticks, sl.sliding);
}

static void test_ball_lands(void)
{
    const double mu = 0.3, g = 9.81, height = 0.5, un = sqrt(2.0 * g * height);
    for (int ie = 0; ie < 2; ie++) {
        const double e = ie ? 0.5 : 0.0, critical = 3.5 * mu * (1.0 + e);
        int classified = 0, cases = 0, failures = 0;
        double worst = 0.0, worst_pn = 0.0;
        for (double ratio = 0.4; ratio < 6.0; ratio *= 1.5) {
            const double v[3] = {ratio * un, 0.0, 0.0}, w[3] = {0.0, 0.0, 0.0};
            double y[GB_STATE_SIZE], residual;
            gb_dynamics_sliding_summary sl;
            ball_log log = {0};
            if (ball_run(mu, e, height, v, w, 2.0, y, &sl, &log, &residual) || !log.landings) {
                failures++;
                gb_error_clear();
                continue;
            }
            const double slip = ratio <= critical ? 0.0 : (ratio - critical) * un;
            worst = fmax(worst, fabs(norm(log.first.slip_after) - slip) / (ratio * un));
            worst_pn = fmax(worst_pn, fabs(log.first.normal_impulse - (1.0 + e) * un) / un);
            classified += log.first.slides_after == (ratio > critical);
            cases++;
        }
        char q[200];
        snprintf(q, sizeof q, "a ball dropped from 0.5 m with horizontal speeds of 0.4 ... 5 times its landing speed (mu 0.3, e %.1f): "
                 "the slip after its first landing", e);
        gb_check c = {"-", "-", q, "closed form: 0 when the ratio <= 3.5 mu (1 + e), else the ratio less that, times |u_n|",
                      "1e-9 of the slip: the landing is located where the ball is 1e-12 body lengths deep (the flight's "
                      "closed form), and Darboux-Keller's steps"};
        gb_check_close(&c, failures ? NAN : fmax(worst, worst_pn), 0.0, 0.0, 1e-9);
        gb_check cc = {"-", "-", q, "sticks below the critical ratio, slides above", "exact"};
        gb_check_true(&cc, !failures && cases == 7 && classified == cases, "%d of %d classified, %d failed", classified, cases, failures);
    }
}

/* ---- Painlevé's paradox ----------------------------------------------------------------------------- */

/* Gömböc I (β = 0.12) on a still plane at attitude R0, launched with centroid velocity v (inertial axes,
 * ω = 0) on a plane of friction mu; with `run`, a thousandth of a period integrated. Returns the status;
 * o the observables at t = 0 (when the start succeeded). */
static int painleve_start(double mu, const double R0[9], const double v[3], int run, gb_dynamics_observables *o)
{
    gb_surface body;
    int status = gb_surface_init(&body, "I", 0.12);
    gb_dynamics_def def = gb_dynamics_default_def();
    def.variant = GB_VARIANT_ROLLING, def.contact = GB_CONTACT_MODEL_CONTINUOUS, def.contact_law = GB_CONTACT_LAW_UNILATERAL;
    def.friction = mu, def.damping = 0.0, def.forcing.a1 = def.forcing.a2 = 0.0;
    memcpy(def.velocity0, v, sizeof def.velocity0);
    const double w0[3] = {0.0, 0.0, 0.0};
    gb_dynamics *d = NULL;
    double y[GB_STATE_SIZE];
    if (!status) status = gb_dynamics_start(&body, &def, R0, w0, &d, y);
    if (!status) status = gb_dynamics_observe(d, 0.0, y, o);
    if (!status && run) {
        gb_integrate_def idef = gb_integrate_default_def();
        idef.locate_switches = 1, idef.periods = 1e-3;
        gb_integrate_stats stats;
        status = gb_integrate_run(d, &idef, 0.0, y, NULL, NULL, &stats);
    }
    gb_dynamics_free(d);
    return status;
}

/* The closed form: one point sliding along s (horizontal, unit) with ω = 0 takes the force N (z − μ s), and its
 * normal acceleration is −g + N K(μ), K(μ) = 1/m + (r × z)·I⁻¹(r × z) − μ (r × z)·I⁻¹(r × s): the normal force
 * N = g / K grows without bound as μ rises to μ* = (1/m + (r × z)·I⁻¹(r × z)) / ((r × z)·I⁻¹(r × s)), and beyond
 * it no N ≥ 0 keeps the point on the plane (or two do): Painlevé's paradox. s is chosen to make the last term
 * largest: the horizontal part of (I⁻¹(r × z)) × r. The attitude R0: a tilt of 0.7 rad about x, where the normal's
 * line passes far from the centroid; v the launch, 0.5 m/s along s (inertial axes); d1, d2 the two terms. */
int verify_painleve_launch(double R0[9], double *mu_star, double *d1, double *d2, double v[3])
{
    const double a = 0.7, R[9] = {1, 0, 0, 0, cos(a), -sin(a), 0, sin(a), cos(a)}, still[3] = {0, 0, 0};
    memcpy(R0, R, sizeof R);
    gb_dynamics_observables o0;
    int status = painleve_start(INFINITY, R0, still, 0, &o0);
    gb_surface body;
    gb_massprops mp;
    gb_massprops_def mdef = gb_massprops_default_def();
    if (!status) status = gb_surface_init(&body, "I", 0.12);
    if (!status) status = gb_massprops_compute(&body, &mdef, &mp);
    double s[3] = {0, 0, 0};
    *mu_star = *d1 = *d2 = NAN;
    for (int i = 0; i < 3; i++) v[i] = 0.0;
    if (!status) {
        gsl_matrix_view I = gsl_matrix_view_array(&mp.inertia[0][0], 3, 3);
        double inv[9];
        gsl_matrix_view Iinv = gsl_matrix_view_array(inv, 3, 3);
        gsl_matrix *lu = gsl_matrix_alloc(3, 3);
        gsl_permutation *perm = gsl_permutation_alloc(3);
        int sign;
        gsl_matrix_memcpy(lu, &I.matrix);
        gsl_linalg_LU_decomp(lu, perm, &sign);
        gsl_linalg_LU_invert(lu, perm, &Iinv.matrix);
        gsl_matrix_free(lu), gsl_permutation_free(perm);
        const double *r = o0.rc, *z = o0.zb;
        double rz[3], u[3], w[3];
        cross(r, z, rz);
        for (int i = 0; i < 3; i++) u[i] = inv[3 * i] * rz[0] + inv[3 * i + 1] * rz[1] + inv[3 * i + 2] * rz[2];
        cross(u, r, w);
        const double wz = dot(w, z);
        for (int i = 0; i < 3; i++) s[i] = w[i] - wz * z[i];
        const double size = norm(s);
        for (int i = 0; i < 3; i++) s[i] /= size;
        *d1 = 1.0 / mp.mass + dot(rz, u);
        *d2 = dot(s, w); /* (r × z)·I⁻¹(r × s) = s·((I⁻¹(r × z)) × r) */
        *mu_star = *d1 / *d2;
        for (int i = 0; i < 3; i++) v[i] = 0.5 * (R0[3 * i] * s[0] + R0[3 * i + 1] * s[1] + R0[3 * i + 2] * s[2]);
    }
    return status;
}

static void test_painleve(void)
{
    double R0[9], mu_star, d1, d2, v[3];
    int status = verify_painleve_launch(R0, &mu_star, &d1, &d2, v);
    /* below μ*: the run's normal force is the closed form's, and the slide runs on */
    const double below[3] = {0.25, 0.5, 0.9};
    double worst = 0.0;
    int ran = 0;
    for (int k = 0; k < 3 && !status; k++) {
        const double mu = below[k] * mu_star;
        gb_dynamics_observables o;
        const int st = painleve_start(mu, R0, v, 1, &o);
        if (st) break;
        ran++;
        const double N = 9.81 / (d1 - mu * d2);
        worst = fmax(worst, fabs(o.normal_force - N) / N);
        if (o.sliding != 1) worst = INFINITY;
    }
    char detail[240];
    snprintf(detail, sizeof detail, "%s; mu* = %.6g (tilt 0.7 rad); %d of 3 slides ran; largest relative error of N %.3g",
             status ? gb_error_message() : "measured", mu_star, ran, worst);
    gb_check cn = {"-", "-", "Gomboc I tilted 0.7 rad, launched sliding on a still plane at 0.25, 0.5, 0.9 mu*: its normal force",
                   "closed form g / K(mu), K = 1/m + (r x z).I^-1 (r x (z - mu s)), growing without bound at mu*",
                   "1e-12 relative: the same mass properties and contact on both sides (the force solver's algebra is "
                   "what is checked), rounding amplified by 1/(1 - mu/mu*) = 10 at 0.9 mu*"};
    gb_check_true(&cn, !status && ran == 3 && worst <= 1e-12 && mu_star > 0.0 && mu_star < 1000.0, "%s", detail);
    /* beyond μ*: the run stops at once, naming the paradox */
    const double above[2] = {1.1, 2.0};
    int stopped = 0;
    char message[240] = "";
    for (int k = 0; k < 2 && !status; k++) {
        gb_dynamics_observables o;
        const int st = painleve_start(above[k] * mu_star, R0, v, 1, &o);
        if (st == GB_ENUMERIC && strstr(gb_error_message(), "Painleve")) stopped++;
        snprintf(message, sizeof message, "%s", st ? gb_error_message() : "ran on");
        gb_error_clear();
    }
    gb_check cp = {"-", "-", "the same launch at 1.1 and 2 mu*: Painleve's paradox",
                   "detected, never integrated through: the run stops (a numerical failure, exit 1) naming the paradox",
                   "exact"};
    gb_check_true(&cp, !status && stopped == 2, "%d of 2 stopped; last: %s", stopped, message);
}

/* ---- two runs that once had no end -------------------------------------------------------------------- */

/* Table 1, Gömböc II, units of g with flight (e = 0), μ = 0.3, from two attitudes of the ensemble of `make
 * study` (ensemble-gomboc-II-g-units-friction, members 14 and 6) whose runs once stopped at 4096 changes of
 * contact inside one step: a switch that left the body in flight at the plane with no impulse (landed again
 * at once, without end), and a chatter between two minima while sliding, whose lifted point's return the
 * rolling estimate did not see (the settle rule never ended it). */
static int zeno_run(const char *attitude, const char *periods, gb_run_result *r)
{
    const gb_case_override set[] = {{"initial", "attitude", attitude, "verify"}, {"model", "friction", "0.3", "verify"},
                                    {"integrator", "periods", periods, "verify"}, {"diagnostics", "lyapunov", "no", "verify"},
                                    {"diagnostics", "strobe", "no", "verify"}, {"diagnostics", "spectrum", "no", "verify"}};
    gb_case scene;
    int status = gb_case_load_with("cases/table1-gomboc-II-g-units-unilateral.ini", set, 6, &scene);
    if (status) return status;
    scene.write_history = scene.write_impacts = 0;
    scene.strobe = scene.spectrum = scene.lyapunov = 0;
    return gb_run(&scene, NULL, r);
}

static void test_zeno(void)
{
    /* the attitudes as the scan draws them (gb_scan_random_attitude, seed 20261125, members 14 and 6) */
    static const char *const attitude[2] = {
        "axis-angle 0.50871810735746525,0.1898326378162537,-0.83974368521969944,2.1402669574043758",
        "axis-angle -0.18341829099344259,0.58501676974082117,0.79000829720393428,2.2830675997745278"};
    /* member 14 through the switch at t = 76.86 s that once looped (at 76.94 s its crease meets Painlevé's
     * paradox, a stop of its own), member 6 through the chatter at 272.06 s */
    static const char *const periods[2] = {"220.3", "790"};
    for (int k = 0; k < 2; k++) {
        gb_run_result r;
        memset(&r, 0, sizeof r);
        const int status = zeno_run(attitude[k], periods[k], &r);
        gb_check c = {"5", "-", k ? "Table 1, Gomboc II, units of g, mu = 0.3, ensemble member 6, 790 periods: a chatter between two minima while sliding"
                                  : "Table 1, Gomboc II, units of g, mu = 0.3, ensemble member 14, 220.3 periods: a switch that leaves the plane with no impulse",
                      "the run reaches its end: the chatter ends by the settle rule (the lifted point's return under the sliding "
                      "forces), a flight from the plane lands only on a return below where it started",
                      "exact (the run once stopped at 4096 changes inside one step)"};
        gb_check_true(&c, !status && r.t_end > 0.0, "%s; %zu impacts, sliding %.1f %% of the time, |E - E0 - W + L| at most %.3g J",
                      status ? gb_error_message() : "ran to its end", r.impacts,
                      status ? NAN : 100.0 * r.sliding.time / r.t_end, r.residual_max);
        gb_run_result_free(&r);
        gb_error_clear();
    }
}

/* ---- two points that stop together ------------------------------------------------------------------ */

/* A wedge (a triangular prism 0.4 m long, its cross-section 0.2 m wide and 0.3 m high, apex down) standing on its
 * sharp edge, its centroid above it, launched at v0 along the edge on a plane of μ: both ends of the edge slip
 * as one, decelerate at μg and stop together at v0/(μg), after which the wedge stands. The second end's stop
 * is no event of its own (its slip is the first one's): it must stop with the first, not stay "sliding" at a
 * rounding's speed. */
static void test_edge_stops(void)
{
    const double v0 = 1.0, mu = 0.3, g = 9.81, periods = 0.51;
    static const char mesh[] = "OFF\n6 5 0\n0 -0.2 0\n0.1 -0.2 0.3\n-0.1 -0.2 0.3\n0 0.2 0\n0.1 0.2 0.3\n-0.1 0.2 0.3\n"
                               "3 0 2 1\n3 3 4 5\n4 0 1 4 3\n4 1 2 5 4\n4 2 0 3 5\n";
    char dir[GB_CHECK_TEMPDIR_SIZE], path[320], scene_path[320], text[900];
    gb_check c = {"-", "-", "a wedge on its edge sliding along it at v0 = 1 m/s on mu = 0.3, event-driven (rk4, 2000 steps/s): the "
                  "time spent sliding [s]",
                  "v0/(mu g) = 0.33979 s, both ends stopped together (not sliding at the end, one stop)",
                  "1e-5 s: the stop is located where the slip falls to its stop speed, ~2e-6 m/s here, which mu g = 2.94 "
                  "m/s^2 reaches within 1e-6 s"};
    if (gb_check_tempdir("wedge", dir, sizeof dir)) {
        gb_check_true(&c, 0, "cannot make a temporary directory");
        return;
    }
    snprintf(path, sizeof path, "%s/wedge.off", dir);
    snprintf(scene_path, sizeof scene_path, "%s/wedge.ini", dir);
    FILE *f = fopen(path, "w");
    const int written = f && fputs(mesh, f) >= 0;
    if (f) fclose(f);
    snprintf(text, sizeof text,
             "[body]\nmesh = wedge.off\nmass = 1\n[forcing]\ng = %.17g\nA1 = 0\nA2 = 0\nomega = 6.283185307179586\n"
             "[model]\ncontact = fast-grid\ndamping = 0\ncontact_law = unilateral\nfriction = %.17g\n[integrator]\n"
             "method = rk4\nsteps_per_period = 2000\nperiods = %.17g\nlocate_switches = yes\n[initial]\nvelocity = 0,%.17g,0\n",
             g, mu, periods, v0);
    gb_case scene;
    gb_run_result r;
    memset(&r, 0, sizeof r);
    int status = written ? gb_case_load_text(scene_path, text, strlen(text), &scene) : gb_error_set(GB_EIO, "cannot write %s", path);
    if (!status) status = gb_run(&scene, NULL, &r);
    const double expected = v0 / (mu * g);
    if (status || !r.has_sliding || r.sliding.sliding || r.sliding.sticks != 1)
        gb_check_true(&c, 0, "%s; sliding %s at the end, %zu stops, %.6f s", status ? gb_error_message() : "ran",
                      r.has_sliding && r.sliding.sliding ? "still" : "not", r.has_sliding ? r.sliding.sticks : 0,
                      r.has_sliding ? r.sliding.time : NAN);
    else
        gb_check_close(&c, r.sliding.time, expected, 0.0, 1e-5);
    gb_check cl = {"-", "-", "the same run: what friction and the impacts took, against the kinetic energy at the launch [J]",
                   "m v0^2 / 2 = 0.5 J: the wedge stands still at the end, and its centroid never rose or fell",
                   "1e-6 J: the ledger's integration error at 2000 steps/s (its largest residual is recorded)"};
    gb_check_close(&cl, status ? NAN : r.sliding.friction_loss + r.impact_energy_lost, 0.5 * v0 * v0, 0.0, 1e-6);
    if (!status) gb_run_result_free(&r);
    remove(path);
    gb_check_tempdir_remove(dir);
}

/* ---- Table 1 on a plane of finite friction --------------------------------------------------------- */

static int table1_friction_run(double mu, size_t steps, double periods, gb_run_result *r)
{
    gb_case scene;
    int status = gb_case_load("cases/table1-gomboc-II-unilateral.ini", &scene);
    if (status) return status;
    scene.dynamics.friction = mu;
    scene.integrate.steps_per_period = steps, scene.integrate.periods = periods;
    scene.write_history = scene.write_impacts = 0;
    scene.strobe = scene.spectrum = scene.lyapunov = 0;
    return gb_run(&scene, NULL, r);
}

static void test_table1_friction(void)
{
    gb_run_result rough, big, fine, coarse;
    memset(&rough, 0, sizeof rough), memset(&big, 0, sizeof big), memset(&fine, 0, sizeof fine), memset(&coarse, 0, sizeof coarse);
    int status = table1_friction_run(INFINITY, 160, 20.0, &rough);
    if (!status) status = table1_friction_run(1e8, 160, 20.0, &big);
    double gap = 0.0;
    for (int i = 0; i < GB_STATE_FINGERPRINT && !status; i++) gap = fmax(gap, fabs(big.y[i] - rough.y[i]));
    gb_check cr = {"5", "-", "Table 1, Gomboc II, unilateral contact, 20 periods: mu = 1e8 against the rough plane",
                   "the rough plane's final state (q, omega, W) and impact count",
                   "1e-10: rounding of the two impact solvers (SVD; Darboux-Keller's steps) and the O(1/mu) slip stage, "
                   "about 1e-14 an impact, grown over the run (measured 3e-13)"};
    gb_check_true(&cr, !status && gap <= 1e-10 && big.impacts == rough.impacts, "largest |y - y_rough| %.3g; impacts %zu and %zu",
                  gap, big.impacts, rough.impacts);
    if (!status) status = table1_friction_run(0.3, 160, 60.0, &coarse);
    if (!status) status = table1_friction_run(0.3, 640, 60.0, &fine);
    char detail[200];
    snprintf(detail, sizeof detail, "%s; |E - E0 - W + L| at most %.3g J (160 steps a period) and %.3g J (640); sliding %.2f %%, "
             "%zu slips, friction took %.4g J", status ? gb_error_message() : "ran", coarse.residual_max, fine.residual_max,
             status ? NAN : 100.0 * coarse.sliding.time / coarse.t_end, coarse.sliding.slips, coarse.sliding.friction_loss);
    gb_check cl = {"5", "46-51", "Table 1, Gomboc II, unilateral contact, mu = 0.3, 60 periods: the energy ledger with friction's work in L",
                   "closes to the integration's accuracy, second order in the step: a quarter of the step takes it down by 8 or more",
                   "a stop is taken where the slip would turn by a quarter radian in a step (the rest of it booked in L), which "
                   "costs RK4 two orders (measured 4.7e-5, 9.1e-6, 2.2e-6, 6.0e-7 J at 160, 320, 640, 1280 steps); a rough run closes "
                   "to 1e-8"};
    gb_check_true(&cl, !status && fine.residual_max * 8.0 <= coarse.residual_max && coarse.sliding.slips > 0 &&
                  coarse.sliding.friction_loss > 0.0, "%s", detail);
    gb_run_result_free(&rough), gb_run_result_free(&big), gb_run_result_free(&coarse), gb_run_result_free(&fine);
    gb_error_clear();
}

int verify_register_s5_friction(void)
{
    static const verify_test tests[] = {
        {"friction: a ball launched with backspin slides, then rolls (closed form)", test_ball_slides_then_rolls,
         "the sliding mode gives a ball the closed form of its slide and its roll, and books friction's work"},
        {"friction: a ball dropped with a horizontal speed lands sticking or sliding (closed form)", test_ball_lands, NULL},
        {"friction: Painleve's paradox detected at the closed form's mu*, never integrated through", test_painleve,
         "a sliding Gomboc's normal force follows the closed form and the paradox beyond mu* stops the run"},
        {"friction: two runs that once had no end (a flight from the plane, a chatter while sliding)", test_zeno, NULL},
        {"friction: Table 1 at mu -> infinity is the rough plane's; the ledger closes with friction", test_table1_friction, NULL},
        {"friction: two points that stop slipping together stop together (a wedge on its edge)", test_edge_stops,
         "a body sliding on two points whose slips are one stops sliding on both at v0/(mu g), reported so"},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("A plane of finite friction: Coulomb's law", tests);
}
