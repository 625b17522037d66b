/* The public surface: every function libgomboc.so exports has a caller outside the library (the command, the
 * examples, the fuzzers, the benchmarks or this harness; scripts/check_exports.py --callers enforces it), and
 * those that only the library itself called are called here, each against what its header says:
 * - names and their parsers round-trip (equation variants, certificates, contact laws, integrators, switch
 *   kinds, gb_error_parse_name itself), and an unknown name is refused listing the allowed ones;
 * - the strict number readers (angles, counts) and their reasons in words;
 * - the attitude's quaternion and rotation are inverse to rounding; g_eff and its rate at once are the two
 *   calls' values bit for bit; the impact law's ranges of μ and e;
 * - a run's contact law and the laws' keys; a mesh as a body, with its mass properties in closed form;
 * - a scene read with an override; the certificate's counters; the program's reserved file names;
 * - an integration session driven in pieces (its nominal steps, its counters, a sampler that stops it);
 * - the Lyapunov pair observed by a caller's sampler: the same λ as gb_run's;
 * - the BLAS on one thread where OpenBLAS serves. */
#include "gb_body.h"
#include "gb_case.h"
#include "gb_certify.h"
#include "gb_check.h"
#include "gb_contact.h"
#include "gb_dynamics.h"
#include "gb_error.h"
#include "gb_file.h"
#include "gb_forcing.h"
#include "gb_impact.h"
#include "gb_integrate.h"
#include "gb_lyapunov_body.h"
#include "gb_massprops.h"
#include "gb_parse.h"
#include "gb_run.h"
#include "verify_sections.h"

#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* The BLAS on one thread: where OpenBLAS serves (found by name, as the library finds it), its own count reads 1. */
static void test_blas_single_thread(void)
{
    const int found = gb_integrate_blas_single_thread();
    void *symbol = dlsym(RTLD_DEFAULT, "openblas_get_num_threads");
    int threads = -1;
    if (symbol) {
        int (*get_threads)(void);
        memcpy(&get_threads, &symbol, sizeof get_threads);
        threads = get_threads();
    }
    gb_check c = {"-", "-", "gb_integrate_blas_single_thread, then OpenBLAS's openblas_get_num_threads",
                  "1 thread where OpenBLAS is the BLAS (and the call says it found it); 0 and nothing changed where it is not",
                  "exact"};
    gb_check_true(&c, found ? threads == 1 : symbol == NULL, "OpenBLAS %s; its threads %d", found ? "found" : "not found", threads);
}

static void test_names(void)
{
    int ok = 1, count = 0;
    for (int k = 0; k < 2; k++) {
        gb_dynamics_variant v;
        gb_dynamics_certificate c;
        ok &= !gb_dynamics_variant_parse(gb_dynamics_variant_name((gb_dynamics_variant)k), &v) && (int)v == k;
        ok &= !gb_dynamics_certificate_parse(gb_dynamics_certificate_name((gb_dynamics_certificate)k), &c) && (int)c == k;
        count += 2;
    }
    for (int k = 0; gb_dynamics_contact_law_name((gb_contact_law)k); k++, count++) {
        gb_contact_law l;
        ok &= !gb_dynamics_contact_law_parse(gb_dynamics_contact_law_name((gb_contact_law)k), &l) && (int)l == k;
    }
    for (int k = 0; gb_integrate_name((gb_integrator)k); k++, count++) {
        gb_integrator m;
        ok &= !gb_integrate_parse(gb_integrate_name((gb_integrator)k), &m) && (int)m == k;
    }
    const char *s0 = gb_contact_switch_name(GB_CONTACT_SAME_BRANCH), *s1 = gb_contact_switch_name(GB_CONTACT_OVERTAKEN),
               *s2 = gb_contact_switch_name(GB_CONTACT_BRANCH_LOST);
    ok &= s0 && s1 && s2 && strcmp(s0, s1) && strcmp(s1, s2) && strcmp(s0, s2) && !strcmp(gb_contact_switch_name((gb_contact_switch_kind)3), "unknown");
    gb_integrator m;
    const int unknown = gb_integrate_parse("rk5", &m);
    const int listed = unknown == GB_EINVAL && strstr(gb_error_message(), "allowed: rk4, rk8pd, rkf45, rk4imp, bsimp, msbdf");
    gb_error_clear();
    static const char *const fruit[] = {"apple", "pear"};
    int index = -1;
    ok &= !gb_error_parse_name("pear", fruit, 2, "fruit", &index) && index == 1;
    ok &= gb_error_parse_name("plum", fruit, 2, "fruit", &index) == GB_EINVAL && strstr(gb_error_message(), "allowed: apple, pear");
    gb_error_clear();
    gb_check c = {"-", "-", "every name of the variants, certificates, contact laws, integrators and switch kinds, parsed back; "
                  "an unknown integrator, switch kind and name of a caller's list",
                  "the same value; GB_EINVAL listing the allowed names (a switch kind: \"unknown\")", "exact"};
    gb_check_true(&c, ok && listed, "%d names round-trip: %s; unknown integrator listed: %s", count, ok ? "yes" : "no",
                  listed ? "yes" : "no");
}

static void test_numbers(void)
{
    double angle = NAN;
    unsigned long long n = 0, big = 0;
    const gb_parse_result a = gb_parse_angle("2*pi/3", &angle), b = gb_parse_count("123", 1000, &n),
                          l = gb_parse_count("1001", 1000, &big), bad = gb_parse_angle("pi/0", &angle);
    const char *why = gb_parse_describe(GB_PARSE_OVERFLOW, "a number");
    gb_check c = {"-", "-", "gb_parse_angle(\"2*pi/3\"), gb_parse_count(\"123\" of at most 1000, and \"1001\"), "
                  "gb_parse_angle(\"pi/0\"), gb_parse_describe(overflow)",
                  "2 pi/3 to one rounding; 123; GB_PARSE_LIMIT; refused; \"beyond the range of a double\"", "exact"};
    gb_check_true(&c, a == GB_PARSE_OK && fabs(angle - 2.0 * M_PI / 3.0) <= 4.5e-16 && b == GB_PARSE_OK && n == 123 &&
                          l == GB_PARSE_LIMIT && bad != GB_PARSE_OK && why && strstr(why, "beyond the range of a double"),
                  "angle %.17g, count %llu, limit %d, pi/0 %d, reason '%s'", angle, n, (int)l, (int)bad, why ? why : "(null)");
}

static void test_attitude_and_forcing(void)
{
    unsigned long long seed = 20261128ULL;
    double worst = 0.0;
    for (int k = 0; k < 1000; k++) {
        double q[4], n = 0.0;
        for (int i = 0; i < 4; i++) {
            seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
            q[i] = (double)(seed >> 11) / 9007199254740992.0 - 0.5;
            n += q[i] * q[i];
        }
        for (int i = 0; i < 4; i++) q[i] /= sqrt(n);
        double R[9], back[4];
        gb_dynamics_rotation(q, R);
        gb_dynamics_quaternion(R, back);
        const double sign = back[0] * q[0] + back[1] * q[1] + back[2] * q[2] + back[3] * q[3] < 0.0 ? -1.0 : 1.0;
        for (int i = 0; i < 4; i++) worst = fmax(worst, fabs(sign * back[i] - q[i]));
    }
    gb_check cq = {"3", "21-23", "1000 random unit quaternions through gb_dynamics_rotation and gb_dynamics_quaternion",
                   "the same quaternion up to its sign: worst component error", "1e-15: Shepperd's method divides by the "
                   "largest component (at least 1/2), a few roundings of unit-sized terms"};
    gb_check_close(&cq, worst, 0.0, 0.0, 1e-15);
    const gb_forcing f = gb_dynamics_default_def().forcing;
    int same = 1;
    for (int k = 0; k < 200; k++) {
        const double t = 0.0137 * k, g1 = gb_forcing_geff(&f, t), r1 = gb_forcing_geff_rate(&f, t);
        double g2, r2;
        gb_forcing_geff_with_rate(&f, t, &g2, &r2);
        same &= !memcmp(&g1, &g2, sizeof g1) && !memcmp(&r1, &r2, sizeof r1);
    }
    gb_check cf = {"3", "25-26", "g_eff and its rate at 200 times of Table 1's forcing by gb_forcing_geff_with_rate",
                   "gb_forcing_geff and gb_forcing_geff_rate, bit for bit (its header's promise)", "exact"};
    gb_check_true(&cf, same, "%s", same ? "the same bits" : "bits differ");
    const int ranges = !gb_impact_friction_check(0.3) && !gb_impact_friction_check(INFINITY) &&
                       gb_impact_friction_check(0.0) == GB_EDOM && !gb_impact_restitution_check(0.0) &&
                       !gb_impact_restitution_check(1.0) && gb_impact_restitution_check(1.1) == GB_EDOM &&
                       gb_impact_restitution_check(-0.1) == GB_EDOM;
    gb_error_clear();
    gb_check cr = {"-", "-", "the impact law's ranges: mu 0.3, rough, 0; e 0, 1, 1.1, -0.1",
                   "accepted, accepted, refused; accepted, accepted, refused, refused (GB_EDOM)", "exact"};
    gb_check_true(&cr, ranges, "%s", ranges ? "as documented" : "not as documented");
}

static void test_laws_and_bodies(void)
{
    /* the laws' keys: each names its law, and a compliant run's law is the compliant row */
    const size_t keys = gb_dynamics_law_key_count();
    int named = keys > 0 && !gb_dynamics_law_key_at(keys, NULL);
    for (size_t k = 0; k < keys; k++) {
        const gb_dynamics_law *law = NULL;
        const gb_dynamics_law_key *key = gb_dynamics_law_key_at(k, &law);
        named &= key && law && key->name && key->slot >= 0 && key->slot < GB_DYNAMICS_LAW_COEFFICIENTS &&
                 key->fallback >= key->min && key->fallback <= key->max;
    }
    gb_dynamics_def def = gb_dynamics_default_def();
    def.contact = GB_CONTACT_MODEL_CONTINUOUS, def.contact_law = GB_CONTACT_LAW_COMPLIANT, def.friction = 0.5;
    gb_surface sphere;
    gb_dynamics *d = NULL;
    const double R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, w0[3] = {0, 0, 0};
    double y[GB_STATE_SIZE];
    int status = gb_surface_init(&sphere, "I", 0.0);
    if (!status) status = gb_dynamics_start(&sphere, &def, R0, w0, &d, y);
    const int row = !status && gb_dynamics_get_law(d) == gb_dynamics_law_of(GB_CONTACT_LAW_COMPLIANT, 0.5) &&
                    gb_dynamics_get_law(d)->id == GB_CONTACT_LAW_COMPLIANT;
    gb_dynamics_free(d);
    gb_check cl = {"-", "-", "the laws' keys (gb_dynamics_law_key_count, _at) and a compliant run's law (gb_dynamics_get_law)",
                   "every key named, with its law, a slot and a default in its range, none past the count; the run's row "
                   "is gb_dynamics_law_of's", "exact"};
    gb_check_true(&cl, named && row, "%zu keys; named %d; row %d; %s", keys, named, row, status ? gb_error_message() : "");
    gb_error_clear();
    /* a mesh as a body: Housner's block, its mass properties in closed form through the body kind's hook */
    gb_surface block;
    gb_massprops props;
    gb_massprops_def mdef = gb_massprops_default_def();
    status = gb_body_mesh("cases/bodies/housner-block.off", &block);
    if (!status) status = gb_massprops_compute(&block, &mdef, &props);
    const double a = 0.2, b = 0.3, h = 0.8, m = mdef.mass;
    gb_check cv = {"2", "-", "gb_body_mesh of cases/bodies/housner-block.off (0.2 x 0.3 x 0.8 m), its volume by gb_massprops",
                   "a b h = 0.048 m^3", "1e-15: the closed form's rounding"};
    if (!status) gb_check_close(&cv, props.volume, a * b * h, 0.0, 1e-15);
    else gb_check_true(&cv, 0, "%s", gb_error_message());
    gb_check ci = {"2", "-", "the same block's inertia about its centroid, I_zz", "m (a^2 + b^2) / 12", "1e-15 relative"};
    gb_check_close(&ci, status ? NAN : props.inertia[2][2], m * (a * a + b * b) / 12.0, 1e-15, 0.0);
}

static void test_scene_and_files(void)
{
    const char *text = "[forcing]\nomega = 18\n";
    const gb_case_override over = {"forcing", "omega", "20", "the check's override"}, unknown = {"forcing", "omegas", "1", "x"};
    gb_case scene;
    int status = gb_case_load_text_with("over.ini", text, strlen(text), &over, 1, &scene);
    const int took = !status && scene.dynamics.forcing.omega == 20.0;
    const int refused = gb_case_load_text_with("over.ini", text, strlen(text), &unknown, 1, &scene) == GB_EINVAL &&
                        strstr(gb_error_message(), "unknown scene key");
    gb_error_clear();
    gb_check co = {"-", "-", "gb_case_load_text_with: [forcing] omega = 20 over the file's 18, and an unknown key",
                   "the override's value; GB_EINVAL naming the unknown key", "exact"};
    gb_check_true(&co, took && refused, "override taken %d, unknown refused %d", took, refused);
    /* locate_switches not given follows the law (cases/README.md) */
    static const struct {
        const char *text;
        int expected;
    } laws[] = {{"[model]\ncontact_law = held\n", 0}, {"[model]\ncontact_law = unilateral\n", 1},
                {"[model]\ncontact_law = compliant\nfriction = 0.5\n", 1},
                {"[model]\ncontact_law = unilateral\nfriction = 0.5\n[integrator]\nstrategy = time-stepping\n", 0}};
    int followed = 0;
    for (size_t k = 0; k < sizeof laws / sizeof laws[0]; k++)
        followed += gb_case_load_text("law.ini", laws[k].text, strlen(laws[k].text), &scene) == GB_OK &&
                    scene.integrate.locate_switches == laws[k].expected;
    gb_error_clear();
    gb_check cl = {"-", "-", "locate_switches not given: held, unilateral, compliant, unilateral time-stepped",
                   "no, yes, yes, no: the default follows the law (cases/README.md)", "exact"};
    gb_check_true(&cl, followed == 4, "%d of 4 as documented", followed);
    /* the documented status of a file that is not one (gb_case.h): a missing path and a directory, made here */
    char dir[GB_CHECK_TEMPDIR_SIZE], missing[320];
    const int made = !gb_check_tempdir("verify", dir, sizeof dir);
    snprintf(missing, sizeof missing, "%s/none.ini", dir);
    const int missing_status = made ? gb_case_load(missing, &scene) : -1;
    const int named = strstr(gb_error_message(), "none.ini") != NULL;
    const int dir_status = made ? gb_case_load(dir, &scene) : -1;
    gb_error_clear();
    if (made) gb_check_tempdir_remove(dir);
    gb_check cf = {"-", "-", "gb_case_load of a missing file and of a directory (made under a temporary directory)",
                   "GB_EINVAL both, the path named (gb_case.h)", "exact"};
    gb_check_true(&cf, missing_status == GB_EINVAL && named && dir_status == GB_EINVAL, "missing: %d (path named %d), directory: %d",
                  missing_status, named, dir_status);
    /* the certificate's counters after one check */
    gb_surface body;
    gb_certify *cert = NULL;
    gb_certify_def cdef = gb_certify_default_def();
    gb_contact_refine_def rdef = gb_contact_refine_default_def();
    const double zb[3] = {0.0, 0.0, -1.0};
    gb_contact_point p;
    gb_certify_result r;
    gb_certify_stats st = {0};
    status = gb_surface_init(&body, "II", 0.12);
    if (!status) status = gb_certify_create(&body, &cdef, &cert);
    if (!status) status = gb_certify_global_minimum(cert, zb, &rdef, &p);
    if (!status) status = gb_certify_check(cert, zb, &p, &rdef, &r);
    if (!status) gb_certify_get_stats(cert, &st);
    gb_certify_free(cert);
    gb_check cc = {"4", "-", "gb_certify_get_stats after gb_certify_global_minimum and one gb_certify_check (Gomboc II, "
                   "z_b = -e_z)", "at least one check, counted as global", "exact"};
    gb_check_true(&cc, !status && st.checks >= 1 && st.global >= 1, "checks %zu, global %zu; %s", st.checks, st.global,
                  status ? gb_error_message() : "");
    gb_error_clear();
    gb_check cn = {"-", "-", "gb_file_reserved_name of \".gomboc-x\", \".gomboc-\", \"x.gomboc-\", \"gomboc-x\"",
                   "1, 1, 0, 0: only the program's temporaries", "exact"};
    gb_check_true(&cn, gb_file_reserved_name(".gomboc-x") && gb_file_reserved_name(".gomboc-") && !gb_file_reserved_name("x.gomboc-") &&
                           !gb_file_reserved_name("gomboc-x"), "as documented");
}

/* A sampler that counts, and stops after `stop` samples (0: never). */
typedef struct counter {
    size_t seen, stop;
} counter;

static int count_sample(void *context, double t, const double y[GB_STATE_SIZE])
{
    (void)t, (void)y;
    counter *c = context;
    c->seen++;
    return c->stop && c->seen >= c->stop;
}

static void test_session(void)
{
    gb_dynamics_def def = gb_dynamics_default_def();
    gb_integrate_def idef = gb_integrate_default_def();
    const double R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, w0[3] = {0, 0, 0};
    double y[GB_STATE_SIZE];
    gb_dynamics *d = NULL;
    gb_integrate_session *s = NULL;
    counter c = {0, 5};
    int status = gb_dynamics_start(gb_check_body("I", 0.12), &def, R0, w0, &d, y);
    if (!status) status = gb_integrate_begin(d, &idef, 0.0, &s);
    size_t per_period = 0, steps_after = 0;
    int stopped_before = -1, stopped_after = -1;
    if (!status) {
        per_period = gb_integrate_steps_for(s, 1.0);
        status = gb_integrate_advance(s, 10, y, NULL, NULL);
        steps_after = gb_integrate_session_stats(s)->steps;
        stopped_before = gb_integrate_stopped(s);
        if (!status) status = gb_integrate_advance(s, 100, y, count_sample, &c);
        stopped_after = gb_integrate_stopped(s);
    }
    gb_integrate_end(s);
    gb_dynamics_free(d);
    gb_check c1 = {"8", "-", "an integration session of Table 1 (rk4, 160 steps a period) driven in pieces: steps in a period, "
                   "steps after advancing 10, stopped before and after a sampler that stops at its 5th sample",
                   "160; 10; 0; 1, with 5 samples seen", "exact"};
    gb_check_true(&c1, !status && per_period == idef.steps_per_period && steps_after == 10 && stopped_before == 0 &&
                           stopped_after == 1 && c.seen == 5,
                  "%zu a period, %zu steps, stopped %d then %d, %zu samples; %s", per_period, steps_after, stopped_before,
                  stopped_after, c.seen, status ? gb_error_message() : "");
}

static void test_lyapunov_observed(void)
{
    const char *text = "[body]\nmorphology = I\n[integrator]\nperiods = 6\n[diagnostics]\nlyapunov = yes\n"
                       "[lyapunov]\ntransient_periods = 1\nwarmup_intervals = 0\nbatches = 5\n";
    gb_case scene;
    gb_run_result run;
    gb_lyapunov_result mine = {0};
    gb_lyapunov_body *body = NULL;
    counter c = {0, 0};
    int status = gb_case_load_text("lyapunov.ini", text, strlen(text), &scene);
    int ran = 0;
    if (!status) status = gb_run(&scene, NULL, &run);
    if (!status) {
        ran = 1;
        status = gb_lyapunov_body_create(&scene.body, &scene.dynamics, &scene.integrate, scene.attitude, scene.omega0,
                                         scene.omega_scale, &body);
    }
    if (!status) {
        gb_lyapunov_body_observe(body, count_sample, &c);
        const gb_lyapunov_pair_system system = gb_lyapunov_body_pair(body);
        status = gb_lyapunov_pair(&system, body, &scene.lyapunov_def, 0.0, NULL, &mine);
    }
    const int same = !status && !memcmp(&mine.lambda_max, &run.lyapunov.lambda_max, sizeof mine.lambda_max);
    gb_check cl = {"6", "77", "Table 1, Gomboc I, 6 periods: lambda of a Lyapunov pair a caller observes sample by sample "
                   "(gb_lyapunov_body_observe), against gb_run's", "the same lambda_max bit for bit, every step's sample "
                   "delivered (960 = 6 x 160)", "exact: observing changes no step"};
    gb_check_true(&cl, same && c.seen == 6 * scene.integrate.steps_per_period, "lambda %.17g against %.17g; %zu samples; %s",
                  mine.lambda_max, ran ? run.lyapunov.lambda_max : NAN, c.seen, status ? gb_error_message() : "");
    gb_lyapunov_result_free(&mine);
    gb_lyapunov_body_free(body);
    if (ran) gb_run_result_free(&run);
    gb_error_clear();
}

int verify_register_surface(void)
{
    static const verify_test tests[] = {
        {"surface: names and their parsers round-trip", test_names, NULL},
        {"surface: the strict number readers", test_numbers, NULL},
        {"surface: the attitude's quaternion, g_eff with its rate, the impact law's ranges", test_attitude_and_forcing, NULL},
        {"surface: the laws' keys, a run's law, a mesh as a body", test_laws_and_bodies, NULL},
        {"surface: a scene with an override, the certificate's counters, reserved file names", test_scene_and_files, NULL},
        {"surface: an integration session in pieces", test_session, NULL},
        {"surface: a Lyapunov pair observed by its caller", test_lyapunov_observed, NULL},
        {"surface: the BLAS behind Siconos's solvers on one thread", test_blas_single_thread, NULL},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("The public surface: every exported function called", tests);
}
