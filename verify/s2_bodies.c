/* Bodies of one's own as scenes: a mesh's polyhedron rocking, tumbling and falling flat under the unilateral
 * law, and smooth bodies given by expressions, against closed forms and against the paper's own bodies.
 *
 * - Housner's block (cases/bodies/housner-block.ini): at every impact the angular velocity keeps its axis
 *   and shrinks by 1 − (3/2) sin²α (angular momentum about the landing edge conserved, Housner 1963); each
 *   half-cycle between impacts lasts what the energy integral of the rocking equation gives,
 *   t = ∫ dθ / √((2 m g R / I_O)(cos(α − θ_m) − cos(α − θ))) (GSL's adaptive quadrature, the root singularity
 *   removed by θ = θ_m − u²), with the amplitude θ_m from the speed after the impact; the speed before the
 *   next impact is the speed after this one (no damping).
 * - a die dropped on a table (cases/bodies/die-drop.ini) comes to rest on a face gb_polyhedron_rest_faces
 *   lists, its centroid the half side above the plane, ω = 0;
 * - a coin leaning on its rim edge (cases/bodies/coin.ini) falls flat: its 64-vertex face lands at once and
 *   the body stops, its centroid the half thickness above the plane;
 * - the paper's χ₁ and χ₂ given as [body] chi expressions (GNU libmatheval) make the same body: the same mass
 *   properties and grid nodes bit for bit, and Table 1's grid scenes end in the same fingerprint; r given as
 *   an expression (r = S^(1/4) written out) makes the same body to rounding (its mass properties to 1e-13);
 * - every distinct body the shipped scenes name is a closed surface: its critical points of r obey
 *   Poincare-Hopf (stable - saddle + unstable = 2), a polyhedron's hull Euler's formula (V - E + F = 2) with
 *   at least one stable rest face;
 * - a scene with a bad body of its own is refused, naming the scene's line and the mesh's line or the
 *   expression's fault. */
#include "gb_body.h"
#include "gb_case.h"
#include "gb_check.h"
#include "gb_contact.h"
#include "gb_error.h"
#include "gb_massprops.h"
#include "gb_polyhedron.h"
#include "gb_run.h"
#include "verify_sections.h"

#include "gb_shape.h"

#include <cjson/cJSON.h>
#include <dirent.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { MAX_IMPACTS = 64 };

typedef struct impacts {
    size_t count;
    gb_dynamics_impact e[MAX_IMPACTS];
} impacts;

static int on_impact(void *context, const gb_dynamics_impact *impact)
{
    impacts *list = context;
    if (list->count < MAX_IMPACTS) list->e[list->count++] = *impact;
    return 0;
}

/* Load the scene at `path` with its text edited: each edits[k][0] (first occurrence) replaced by edits[k][1]. */
static int load_edited(const char *path, const char *const (*edits)[2], size_t count, gb_case *scene)
{
    static char text[1 << 16], edited[1 << 16];
    FILE *f = fopen(path, "rb");
    if (!f) return gb_error_set(GB_EIO, "%s: cannot open", path);
    const size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = '\0';
    for (size_t k = 0; k < count; k++) {
        const char *at = strstr(text, edits[k][0]);
        if (!at) return gb_error_set(GB_EINVAL, "%s: no text '%s' to replace", path, edits[k][0]);
        snprintf(edited, sizeof edited, "%.*s%s%s", (int)(at - text), text, edits[k][1], at + strlen(edits[k][0]));
        memcpy(text, edited, strlen(edited) + 1);
    }
    return gb_case_load_text(path, text, strlen(text), scene);
}

/* Run the scene at `path` (edited as load_edited does); its impacts into `list` when given. */
static int run_scene(const char *path, const char *const (*edits)[2], size_t count, impacts *list, gb_run_result *r)
{
    gb_case scene;
    const int status = load_edited(path, edits, count, &scene);
    if (status) return status;
    if (list) memset(list, 0, sizeof *list);
    const gb_run_sinks sinks = {NULL, list, list ? on_impact : NULL};
    return gb_run(&scene, &sinks, r);
}

/* ---- Housner's block ---------------------------------------------------------------------------- */

/* The larger of the two, NaN if either is (fmax would drop a NaN: a failed quadrature must fail the check). */
static double worst_of(double worst, double x) { return isnan(worst) || isnan(x) || x > worst ? (isnan(worst) ? worst : x) : worst; }

typedef struct rocking {
    double k, alpha, theta_m; /* 2 m g R / I_O [1/s²], the slenderness, the amplitude */
} rocking;

static double half_swing_integrand(double u, void *params)
{
    const rocking *p = params;
    if (u == 0.0) return 2.0 / sqrt(p->k * sin(p->alpha - p->theta_m)); /* the limit u → 0 */
    /* cos(α − θ_m) − cos(α − θ) with θ = θ_m − u², written without cancellation */
    const double gap = 2.0 * sin(p->alpha - p->theta_m + 0.5 * u * u) * sin(0.5 * u * u);
    return 2.0 * u / sqrt(p->k * gap);
}

/* The time from the amplitude θ_m back to θ = 0 (a quarter of a rocking cycle), by quadrature. */
static double quarter_time(const rocking *p, double *abserr)
{
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(200);
    gsl_function f = {half_swing_integrand, (void *)p};
    double t = NAN;
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    if (gsl_integration_qag(&f, 0.0, sqrt(p->theta_m), 1e-15, 1e-13, 200, GSL_INTEG_GAUSS61, w, &t, abserr)) t = NAN;
    gsl_set_error_handler(old);
    gsl_integration_workspace_free(w);
    return t;
}

static void test_housner(void)
{
    const char *path = "cases/bodies/housner-block.ini";
    gb_case scene;
    impacts list;
    gb_run_result r;
    int status = gb_case_load(path, &scene);
    if (!status) status = run_scene(path, NULL, 0, &list, &r);
    gb_check ran = {"2", "-", "Housner's block: the scene runs", "exit 0", "exact"};
    gb_check_true(&ran, !status, "%s", status ? gb_error_message() : "ran");
    if (status) return;
    /* the block: half widths b (x), h (z) from its hull; R, α, I_O about the edge (the y axis) */
    const gb_polyhedron *poly = gb_body_polyhedron(&scene.body);
    double b = 0.0, h = 0.0;
    for (size_t k = 0; k < poly->vertex_count; k++) b = fmax(b, poly->vertices[3 * k]), h = fmax(h, poly->vertices[3 * k + 2]);
    const double m = scene.dynamics.mass, g = scene.dynamics.forcing.g, R = hypot(b, h), alpha = atan2(b, h);
    const double I_O = 4.0 / 3.0 * m * R * R, ratio = 1.0 - 1.5 * sin(alpha) * sin(alpha);
    double worst_ratio = 0.0, worst_axis = 0.0, worst_time = 0.0, worst_energy = 0.0, quad_err = 0.0;
    size_t rocks = 0;
    double t_prev = 0.0, omega_after_prev = NAN;
    rocking p = {2.0 * m * g * R / I_O, alpha, 0.0};
    /* the release: θ_m = the initial tilt (axis-angle about y), from rest */
    p.theta_m = acos(scene.attitude[0]);
    for (size_t k = 0; k < list.count; k++) {
        const gb_dynamics_impact *e = &list.e[k];
        if (e->kind != GB_DYNAMICS_IMPACT_THIRD) continue; /* the first rows: the release onto the edge */
        rocks++;
        const double before = e->omega_before[1], after = e->omega_after[1];
        worst_ratio = worst_of(worst_ratio, fabs(after / before - ratio));
        worst_axis = worst_of(worst_axis, hypot(e->omega_after[0], e->omega_after[2]) / fabs(after));
        double err;
        const double predicted = (isnan(omega_after_prev) ? 1.0 : 2.0) * quarter_time(&p, &err);
        quad_err = worst_of(quad_err, err);
        worst_time = worst_of(worst_time, fabs((e->t - t_prev) - predicted));
        if (!isnan(omega_after_prev)) worst_energy = worst_of(worst_energy, fabs(fabs(before) / fabs(omega_after_prev) - 1.0));
        /* the next swing's amplitude, the centroid raised from R cos α to R cos(α − θ_m): ½ I_O ω² = m g R
         * (cos(α − θ_m) − cos α) */
        p.theta_m = alpha - acos(cos(alpha) + 0.5 * I_O * after * after / (m * g * R));
        t_prev = e->t, omega_after_prev = after;
    }
    char measured[96];
    snprintf(measured, sizeof measured, "%zu impacts", rocks);
    gb_check cr = {"2", "-", "Housner's block: ω after / ω before at every impact (the face lands flat, the block rocks on the other edge)",
                   "1 - (3/2) sin^2 alpha (angular momentum about the landing edge)",
                   "1e-12: the impact's SVD solve in double precision (measured 1e-15)"};
    gb_check_true(&cr, rocks >= 8, "%s", measured);
    gb_check_close(&cr, worst_ratio, 0.0, 0.0, 1e-12);
    gb_check ca = {"2", "-", "Housner's block: the turning axis after every impact stays the edge's (|ω_x, ω_z| / |ω_y|)", "0 (symmetry)",
                   "1e-12: rounding of the four-point impact"};
    gb_check_close(&ca, worst_axis, 0.0, 0.0, 1e-12);
    gb_check ct = {"2", "-", "Housner's block: the time between impacts, impact by impact [s]",
                   "the energy integral of the rocking equation (GSL qag, 1e-13), amplitude from the speed after the impact",
                   "1e-10 s: RK4 at h = 5e-4 s, error ~ p^4 t h^4 = 6e-11 s over 3 s (p^2 = 3g/4R); the event located to 1e-13 s"};
    gb_check_close(&ct, worst_time, 0.0, 0.0, 1e-10 + quad_err);
    gb_check ce = {"2", "-", "Housner's block: |ω| before an impact / |ω| after the previous one (no damping)", "1 (energy conserved)",
                   "1e-9: RK4's energy error at h = 5e-4 s"};
    gb_check_close(&ce, worst_energy, 0.0, 0.0, 1e-9);
    gb_run_result_free(&r);
}

/* On a plane of finite friction a face landing is not followed (gb_dynamics_faces.c): the run stops, saying so,
 * instead of landing one vertex of the edge alone. */
static void test_face_friction(void)
{
    const char *const edits[1][2] = {{"damping = 0\n", "damping = 0\nfriction = 0.6\n"}};
    gb_run_result r;
    const int status = run_scene("cases/bodies/housner-block.ini", edits, 1, NULL, &r);
    gb_check c = {"2", "-", "Housner's block on a plane of friction mu = 0.6: its first face landing",
                  "stops the run (a computation not followed, exit 1), naming the face and the rough plane", "exact"};
    gb_check_true(&c, status == GB_ENUMERIC && strstr(gb_error_message(), "lands flat") &&
                          strstr(gb_error_message(), "friction = rough"),
                  "status %d: %s", status, status ? gb_error_message() : "ran");
    if (!status) gb_run_result_free(&r);
    gb_error_clear();
}

/* ---- a die and a coin come to rest -------------------------------------------------------------- */

/* The body's final state: at rest on a face whose outward normal is −z_b (body axes), the centroid at the
 * face's distance above the plane, and the energy ledger closed. */
static void check_rest(const char *path, const char *what)
{
    gb_case scene;
    gb_run_result r;
    int status = gb_case_load(path, &scene);
    if (!status) status = run_scene(path, NULL, 0, NULL, &r);
    char quantity[200];
    snprintf(quantity, sizeof quantity, "%s: the scene runs and ends at rest on three or more vertices", what);
    gb_check ran = {"2", "-", quantity, "exit 0, contacts = 3, ω = 0", "|ω| <= 1e-12 rad/s: the rounding of the impact that stopped it"};
    const double spin = status ? NAN : hypot(hypot(r.final.omega[0], r.final.omega[1]), r.final.omega[2]);
    gb_check_true(&ran, !status && r.final.contacts == 3 && spin <= 1e-12, "%s, %d contacts, |omega| = %.3g rad/s",
                  status ? gb_error_message() : "ran", status ? 0 : r.final.contacts, spin);
    if (status) return;
    const gb_polyhedron *poly = gb_body_polyhedron(&scene.body);
    gb_massprops m;
    double normals[128][3];
    size_t count = 0;
    status = gb_polyhedron_massprops(poly, 1.0, &m);
    if (!status) status = gb_polyhedron_rest_faces(poly, m.centroid, normals, 128, &count);
    const double *zb = r.final.zb;
    double best = -2.0, distance = 0.0;
    for (size_t f = 0; f < count && f < 128; f++) {
        const double c = -(normals[f][0] * zb[0] + normals[f][1] * zb[1] + normals[f][2] * zb[2]);
        if (c > best) best = c;
    }
    for (size_t k = 0; k < poly->vertex_count; k++) { /* the face's distance: the lowest vertex's depth */
        const double *x = poly->vertices + 3 * k;
        distance = fmax(distance, -(zb[0] * x[0] + zb[1] * x[1] + zb[2] * x[2]));
    }
    snprintf(quantity, sizeof quantity, "%s: the face it rests on against the stable rest faces (1 - n.(-z_b), best face)", what);
    gb_check cf = {"2", "-", quantity, "0: a face gb_polyhedron_rest_faces lists",
                   "1e-9: the attitude's drift over the run (orthonormality ~1e-15)"};
    gb_check_close(&cf, 1.0 - best, 0.0, 0.0, 1e-9);
    snprintf(quantity, sizeof quantity, "%s: the centroid's height above the plane at rest [m]", what);
    gb_check cz = {"2", "-", quantity, "the face's distance from the centroid (its lowest vertex)",
                   "1e-10 body lengths: a face lands flat to the tie of its vertices' heights (GB_DYN_FACE_TIE)"};
    gb_check_close(&cz, r.final.zeta, distance, 0.0, 1e-10 * scene.dynamics.length);
    snprintf(quantity, sizeof quantity, "%s: the energy ledger E - E0 - W + L at the end [J]", what);
    gb_check ce = {"2", "-", quantity, "0", "1e-9 of m g L: the impacts' rounding and RK4's energy error"};
    gb_check_close(&ce, r.final.residual, 0.0, 0.0, 1e-9 * scene.dynamics.mass * scene.dynamics.forcing.g * poly->size);
    gb_run_result_free(&r);
}

static void test_die_and_coin(void)
{
    check_rest("cases/bodies/die-drop.ini", "a die dropped 5 cm");
    check_rest("cases/bodies/coin.ini", "a coin falling flat");
}

/* ---- expressions -------------------------------------------------------------------------------- */

static const char *const CHI[2] = {"theta - 5*phi", "theta - 3*pi/2*(cos(phi) - cos(phi)*cos(phi)*cos(phi)/3)"};

static void test_expressions_same_body(void)
{
    for (int k = 0; k < 2; k++) {
        const char *name = k ? "II" : "I";
        gb_surface own, paper;
        int status = gb_body_expression(GB_BODY_PHASE, CHI[k], 0.12, &own);
        if (!status) status = gb_surface_init(&paper, name, 0.12);
        gb_massprops a, b;
        const gb_massprops_def def = gb_massprops_default_def();
        if (!status) status = gb_massprops_compute(&own, &def, &a);
        if (!status) status = gb_massprops_compute(&paper, &def, &b);
        gb_contact_grid *ga = NULL, *gb = NULL;
        const gb_contact_grid_def gdef = gb_contact_grid_default_def();
        if (!status) status = gb_contact_grid_create(&own, &gdef, &ga);
        if (!status) status = gb_contact_grid_create(&paper, &gdef, &gb);
        size_t differ = 0;
        for (size_t i = 0; !status && i < gb_contact_grid_size(ga); i++) {
            double x[3], y[3];
            gb_contact_grid_node(ga, i, NULL, NULL, x);
            gb_contact_grid_node(gb, i, NULL, NULL, y);
            differ += memcmp(x, y, sizeof x) != 0;
        }
        char quantity[200];
        snprintf(quantity, sizeof quantity, "chi = %s (the paper's chi_%d as an expression): mass properties and 90 x 180 grid nodes", CHI[k], k + 1);
        gb_check c = {"2", k ? "9" : "8", quantity, "Gomboc's built-in morphology, bit for bit", "exact: libmatheval evaluates the same operations in the same order"};
        gb_check_true(&c, !status && !memcmp(&a.volume, &b.volume, sizeof a.volume) && !memcmp(a.inertia, b.inertia, sizeof a.inertia) &&
                              !memcmp(&a.L, &b.L, sizeof a.L) && differ == 0,
                      "%s; %zu nodes differ, volume %.17g against %.17g", status ? gb_error_message() : "computed", differ, a.volume, b.volume);
        gb_contact_grid_free(ga);
        gb_contact_grid_free(gb);
    }
    /* r itself: S^(1/4) by pow against two square roots */
    gb_surface own, paper;
    int status = gb_body_expression(GB_BODY_RADIUS, "(1 + 4*beta*sin(phi)*cos(theta - 5*phi))^(1/4)", 0.12, &own);
    if (!status) status = gb_surface_init(&paper, "I", 0.12);
    gb_massprops a, b;
    const gb_massprops_def def = gb_massprops_default_def();
    if (!status) status = gb_massprops_compute(&own, &def, &a);
    if (!status) status = gb_massprops_compute(&paper, &def, &b);
    gb_check cr = {"2", "12", "r = (1 + 4 beta sin(phi) cos(theta - 5 phi))^(1/4) as an expression: volume and I_zz",
                   "Gomboc I's built-in r (eq 12)", "1e-13 relative: pow against sqrt(sqrt), an ulp a node, through the quadrature"};
    gb_check_true(&cr, !status, "%s", status ? gb_error_message() : "computed");
    if (!status) {
        gb_check_close(&cr, a.volume, b.volume, 1e-13, 0.0);
        gb_check_close(&cr, a.inertia[2][2], b.inertia[2][2], 1e-13, 0.0);
    }
}

static void test_expressions_table1(void)
{
    static const char *const scenes[2] = {"cases/table1-gomboc-I.ini", "cases/table1-gomboc-II.ini"};
    for (int k = 0; k < 2; k++) {
        gb_run_result a, b;
        char chi[160];
        snprintf(chi, sizeof chi, "chi = %s\n", CHI[k]);
        /* without λ: the reference trajectory is the same run bit for bit (gb_run.h) */
        const char *const paper[1][2] = {{"lyapunov = yes", "lyapunov = no"}};
        const char *const own[2][2] = {{"lyapunov = yes", "lyapunov = no"}, {k ? "morphology = II\n" : "morphology = I\n", chi}};
        int status = run_scene(scenes[k], paper, 1, NULL, &a);
        if (!status) {
            status = run_scene(scenes[k], own, 2, NULL, &b);
            if (status) gb_run_result_free(&a);
        }
        char quantity[200];
        snprintf(quantity, sizeof quantity, "%s with chi = %s: the run's fingerprints (final state, switches)", scenes[k] + 6, CHI[k]);
        gb_check c = {"8", "8, 9", quantity, "the built-in morphology's run", "exact: the same body bit for bit"};
        gb_check_true(&c, !status && a.state_fingerprint == b.state_fingerprint && a.switch_fingerprint == b.switch_fingerprint,
                      "%s: %016llx/%016llx against %016llx/%016llx", status ? gb_error_message() : "ran",
                      status ? 0ULL : (unsigned long long)b.state_fingerprint, status ? 0ULL : (unsigned long long)b.switch_fingerprint,
                      status ? 0ULL : (unsigned long long)a.state_fingerprint, status ? 0ULL : (unsigned long long)a.switch_fingerprint);
        if (!status) gb_run_result_free(&a), gb_run_result_free(&b);
    }
}

/* ---- bad bodies in a scene ---------------------------------------------------------------------- */

static void test_bad_bodies(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("bodies", dir, sizeof dir)) return;
    char mesh[512], scene[512];
    snprintf(mesh, sizeof mesh, "%s/dent.off", dir);
    /* a cube with its top centre pushed in: the vertex (0, 0, 0.5) inside the hull */
    FILE *f = fopen(mesh, "w");
    if (f) {
        fputs("OFF\n9 14 0\n-1 -1 -1\n1 -1 -1\n1 1 -1\n-1 1 -1\n-1 -1 1\n1 -1 1\n1 1 1\n-1 1 1\n0 0 0.5\n"
              "3 0 2 1\n3 0 3 2\n3 0 1 5\n3 0 5 4\n3 1 2 6\n3 1 6 5\n3 2 3 7\n3 2 7 6\n3 3 0 4\n3 3 4 7\n"
              "3 4 5 8\n3 5 6 8\n3 6 7 8\n3 7 4 8\n", f);
        fclose(f);
    }
    static const struct {
        const char *text, *want[3];
    } rows[] = {
        {"[body]\nmesh = dent.off\n", {"scene.ini:2: [body] mesh:", "dent.off:11:", "convex"}},
        {"[body]\nmesh = none.off\n", {"scene.ini:2: [body] mesh:", "none.off", "allowed"}},
        {"[body]\nmorphology = II\nmesh = dent.off\n", {"scene.ini:3: [body] mesh", "with [body] morphology", "allowed: one of them"}},
        {"[body]\nmesh = dent.off\n[model]\ncontact = continuous\n", {"scene.ini:4: [model] contact = continuous", "vertex", "allowed: grid or fast-grid"}},
        {"[body]\nchi = theta - 5*\n", {"scene.ini:2: [body] chi:", "does not parse", "allowed"}},
        {"[body]\nchi = theta - 5*psi\n", {"scene.ini:2: [body] chi:", "'psi'", "allowed: phi, theta, beta"}},
        {"[body]\nr = sin(phi) - 0.5\n", {"scene.ini:2: [body] r:", "r <= 0", "allowed: r > 0"}},
        {"[body]\nr = 1 + 0.1*theta\n", {"scene.ini:2: [body] r:", "not one surface", "periodic"}},
        {"[body]\nr = 1 + 1/sin(phi)\n", {"scene.ini:2: [body] r:", "not finite", "allowed"}},
        {"[body]\nr = 1\nchi = theta\n", {"scene.ini:3: [body] chi", "with [body] r", "allowed: one of them"}},
    };
    for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        snprintf(scene, sizeof scene, "%s/scene.ini", dir);
        f = fopen(scene, "w");
        if (f) fputs(rows[k].text, f), fclose(f);
        gb_case c;
        const int status = gb_case_load(scene, &c);
        const char *msg = gb_error_message();
        int found = status == GB_EINVAL || status == GB_EDOM;
        for (int i = 0; i < 3; i++) found &= strstr(msg, rows[k].want[i]) != NULL;
        char quantity[200];
        snprintf(quantity, sizeof quantity, "a scene's bad body: %.*s", (int)strcspn(rows[k].text + 7, "\n"), rows[k].text + 7);
        gb_check c1 = {"2", "-", quantity, "refused (bad input), naming the scene's line, the fault and what is allowed", "exact"};
        gb_check_true(&c1, found, "status %d: %s", status, msg);
        gb_error_clear();
    }
    unlink(mesh);
    unlink(scene);
    gb_check_tempdir_remove(dir);
}

/* ---- every shipped scene's body ------------------------------------------------------------------ */

/* The bodies of the scenes in `dir` not yet in `seen` (by row and β), appended; returns the new count. */
static size_t scene_bodies(const char *dir, gb_surface *seen, char (*from)[600], size_t count, size_t cap)
{
    DIR *d = opendir(dir);
    if (!d) return count;
    struct dirent *e;
    while ((e = readdir(d)) && count < cap) {
        const size_t n = strlen(e->d_name);
        if (n < 5 || strcmp(e->d_name + n - 4, ".ini")) continue;
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        gb_case c;
        if (gb_case_load(path, &c)) { /* a scene that does not load: its own suites say so */
            gb_error_clear();
            continue;
        }
        int known = 0;
        for (size_t k = 0; k < count; k++) known |= seen[k].morphology == c.body.morphology && seen[k].beta == c.body.beta;
        if (!known) seen[count] = c.body, snprintf(from[count], sizeof from[count], "%s", path), count++;
    }
    closedir(d);
    return count;
}

static void test_scene_bodies(void)
{
    enum { CAP = 32 };
    gb_surface bodies[CAP];
    char from[CAP][600];
    size_t count = 0;
    static const char *const dirs[] = {"cases", "cases/bodies", "cases/siconos"};
    for (size_t k = 0; k < 3; k++) count = scene_bodies(dirs[k], bodies, from, count, CAP);
    gb_check cn = {"2", "-", "the distinct bodies of the shipped scenes (cases/, cases/bodies/, cases/siconos/)", "at least the "
                   "paper's two and the three meshes", "exact"};
    gb_check_true(&cn, count >= 5, "%zu bodies", count);
    for (size_t k = 0; k < count; k++) {
        const gb_surface *b = &bodies[k];
        char quantity[512];
        if (gb_surface_is_polyhedron(b)) {
            const gb_polyhedron *p = gb_body_polyhedron(b);
            gb_massprops m;
            double normals[128][3];
            size_t rests = 0;
            int status = gb_polyhedron_massprops(p, 1.0, &m);
            if (!status) status = gb_polyhedron_rest_faces(p, m.centroid, normals, 128, &rests);
            snprintf(quantity, sizeof quantity, "%.80s (the body of %.100s): Euler's formula V - E + F on its hull, and a stable face",
                     b->morphology->name, from[k]);
            gb_check c = {"2", "-", quantity, "2 (a convex polyhedron is a sphere), at least one rest face", "exact"};
            /* a triangulated hull: E = 3F/2 */
            gb_check_true(&c, !status && 2 * p->vertex_count == 4 + p->triangle_count && rests >= 1, "%s: V = %zu, F = %zu, %zu rest faces",
                          status ? gb_error_message() : "computed", p->vertex_count, p->triangle_count, rests);
        } else {
            gb_equilibria eq;
            const gb_shape_def def = gb_shape_default_def();
            const int status = gb_shape_equilibria(b, &def, &eq);
            snprintf(quantity, sizeof quantity, "%.80s, beta = %g (the body of %.100s): critical points of r, stable - saddle + unstable",
                     b->morphology->name, b->beta, from[k]);
            gb_check c = {"2", "-", quantity, "2 (Poincare-Hopf on the sphere)", "exact"};
            gb_check_true(&c, !status && eq.stable - eq.saddle + eq.unstable == 2, "%s: %d stable, %d saddle, %d unstable",
                          status ? gb_error_message() : "computed", eq.stable, eq.saddle, eq.unstable);
        }
        gb_error_clear();
    }
}

/* gomboc shape --scene states beta only where it enters the body: an r expression without it says "beta not used" */
static void test_beta_stated(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    const char *bin = getenv("GOMBOC_BIN") ? getenv("GOMBOC_BIN") : "build/gomboc";
    static const struct {
        const char *body, *must, *never;
    } cases[] = {{"r = 1 + 0.1*cos(theta)*sin(phi)", "beta not used", "beta = "},
                 {"r = (1 + 4*beta*sin(phi)*cos(theta - 5*phi))^0.25", "beta = 0.12", "beta not used"},
                 {"morphology = II", "beta = 0.12", "beta not used"}};
    int right = 0;
    char first[300] = "";
    if (!gb_check_tempdir("beta", dir, sizeof dir))
        for (size_t k = 0; k < 3; k++) {
            char path[320], args[360];
            static char out[1 << 14];
            snprintf(path, sizeof path, "%s/body%zu.ini", dir, k);
            FILE *f = fopen(path, "w");
            if (!f) continue;
            fprintf(f, "[body]\n%s\n[model]\ncontact = fast-grid\n", cases[k].body);
            fclose(f);
            snprintf(args, sizeof args, "shape --scene %s", path);
            const int code = gb_check_command(bin, args, out, sizeof out);
            const char *line = strstr(out, "body ");
            const char *end = line ? strchr(line, '\n') : NULL;
            char head[256] = "";
            if (line) snprintf(head, sizeof head, "%.*s", (int)(end ? end - line : 200), line);
            const int ok = code == 0 && strstr(head, cases[k].must) && !strstr(head, cases[k].never);
            right += ok;
            if (!ok && !first[0]) snprintf(first, sizeof first, "; '%s': exit %d, '%s'", cases[k].body, code, head);
            remove(path);
        }
    gb_check_tempdir_remove(dir);
    gb_check c = {"2", "-", "gomboc shape --scene: the body line of an r expression without beta, one with it, the paper's II",
                  "'beta not used'; 'beta = 0.12' twice", "exact"};
    gb_check_true(&c, right == 3, "%d of 3 as stated%s", right, first);
}

/* `gomboc run` of the scene `text` written as DIR/NAME.ini: its exit status, its standard error (and output) in out, its
 * summary parsed (NULL where there is none); the files removed. */
static cJSON *run_scene_text(const char *dir, const char *name, const char *text, int *code, char *out, size_t size)
{
    const char *bin = getenv("GOMBOC_BIN") ? getenv("GOMBOC_BIN") : "build/gomboc";
    char path[200], summary[240], args[500];
    snprintf(path, sizeof path, "%s/%s.ini", dir, name);
    snprintf(summary, sizeof summary, "%s/%s-summary.json", dir, name);
    *code = -1;
    FILE *f = fopen(path, "w");
    if (!f) return NULL;
    fputs(text, f);
    fclose(f);
    snprintf(args, sizeof args, "run %s --out %s", path, dir);
    *code = gb_check_command(bin, args, out, size);
    char *json = gb_check_read_file(summary);
    cJSON *root = json ? cJSON_Parse(json) : NULL;
    free(json);
    remove(path), remove(summary);
    return root;
}

/* A smooth body of one's own on a grid model says so (summary, standard error); the paper's body on its grid does not
 * (the paper's own model) */
static void test_grid_model_said(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    static const struct {
        const char *body;
        int said;
    } cases[] = {{"r = 1 + 0.1*cos(theta)*sin(phi)", 1}, {"morphology = I", 0}};
    int right = 0;
    if (!gb_check_tempdir("grid", dir, sizeof dir))
        for (size_t k = 0; k < 2; k++) {
            char text[300], name[16];
            static char out[1 << 14];
            snprintf(text, sizeof text, "[body]\n%s\n[model]\ncontact = fast-grid\n[integrator]\nperiods = 2\n[output]\n"
                     "summary = yes\nhistory = no\n", cases[k].body);
            snprintf(name, sizeof name, "body%zu", k);
            int code;
            cJSON *root = run_scene_text(dir, name, text, &code, out, sizeof out);
            const int in_summary = cJSON_GetObjectItem(root, "grid_model_of_smooth_body") != NULL,
                      in_note = strstr(out, "runs as its 90 x 180 grid polyhedron") != NULL;
            right += code == 0 && in_summary == cases[k].said && in_note == cases[k].said;
            cJSON_Delete(root);
        }
    gb_check_tempdir_remove(dir);
    gb_check c = {"2", "-", "a run of an r expression on the fast grid, and of the paper's Gomboc I on it",
                  "the first says it runs as its grid polyhedron (summary key, note on standard error); the second does not",
                  "exact"};
    gb_check_true(&c, right == 2, "%d of 2 as stated", right);
}

/* Continuous contact for a body given by an expression (certificate = multi-start, uncertified: the branch grid's local
 * minima polished by Newton). Oracle: Gömböc I under Table 1's forcing on the rolling equation, 5 periods, with the
 * per-vertical certificate (each contact proved global): the same body with certificate = multi-start, and the same
 * body given as r = (1 + 4 beta sin(phi) cos(theta - 5 phi))^(1/4) (whose contact nothing certifies: multi-start by
 * default), must switch at the same samples (the fingerprint's switch half) and end at the same ω to rounding (a
 * from-scratch contact's last bits depend on Newton's start; the expression evaluates the surface by another path). */
static void test_continuous_own(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("continuous-own", dir, sizeof dir)) return;
    static char out[1 << 14];
    static const char *const bodies[3] = {"morphology = I\nbeta = 0.12\n[model]\ncertificate = per-vertical",
                                          "morphology = I\nbeta = 0.12\n[model]\ncertificate = multi-start",
                                          "r = (1 + 4*beta*sin(phi)*cos(theta - 5*phi))^(1/4)\nbeta = 0.12\n[model]"};
    char switches[3][40] = {"", "", ""}, certificate[3][40] = {"", "", ""};
    double omega[3][3];
    int code = 0;
    for (int k = 0; k < 3; k++) {
        char text[700], name[16];
        snprintf(text, sizeof text, "[body]\n%s\nequation = rolling\ncontact = continuous\n[integrator]\nperiods = 5\n"
                 "[output]\nsummary = yes\nhistory = no\n", bodies[k]);
        snprintf(name, sizeof name, "cert%d", k);
        int c;
        cJSON *root = run_scene_text(dir, name, text, &c, out, sizeof out);
        code |= c;
        const char *sw = cJSON_GetStringValue(cJSON_GetObjectItem(cJSON_GetObjectItem(root, "fingerprint"), "switches")),
                   *cert = cJSON_GetStringValue(cJSON_GetObjectItem(cJSON_GetObjectItem(root, "scene"), "certificate"));
        snprintf(switches[k], sizeof switches[k], "%s", sw ? sw : "");
        snprintf(certificate[k], sizeof certificate[k], "%s", cert ? cert : "");
        const cJSON *w = cJSON_GetObjectItem(root, "omega");
        for (int i = 0; i < 3; i++) omega[k][i] = cJSON_GetArraySize(w) == 3 ? cJSON_GetNumberValue(cJSON_GetArrayItem(w, i)) : NAN;
        cJSON_Delete(root);
    }
    double apart[2] = {0.0, 0.0};
    for (int k = 1; k < 3; k++)
        for (int i = 0; i < 3; i++) apart[k - 1] = fmax(apart[k - 1], isnan(omega[k][i]) ? INFINITY : fabs(omega[k][i] - omega[0][i]));
    gb_check c = {"4", "27-39", "Gomboc I, Table 1's forcing, rolling equation, continuous contact, 5 periods: certificate = multi-start, "
                  "and the same body as an r expression (multi-start by default, named so in the summary)",
                  "the per-vertical certificate's run (each contact proved global): its switches and final omega",
                  "the same switch samples; final omega within 1e-9 rad/s (rounding of the initial contact and of the expression's "
                  "surface, 1e-16, grown by the flow's expansion over 5 periods)"};
    gb_check_true(&c, code == 0 && switches[0][0] && !strcmp(switches[0], switches[1]) && !strcmp(switches[0], switches[2]) &&
                          apart[0] <= 1e-9 && apart[1] <= 1e-9 && !strcmp(certificate[1], "multi-start") &&
                          !strcmp(certificate[2], "multi-start"),
                  "switches %s, %s, %s; final omega apart by %.3g and %.3g rad/s; certificates %s, %s, %s", switches[0], switches[1],
                  switches[2], apart[0], apart[1], certificate[0], certificate[1], certificate[2]);
    gb_check_tempdir_remove(dir);
}

/* λ of a smooth body of one's own on a grid, and on the grid twice as fine: `gomboc run`'s summary gives both, the second
 * the λ of the same scene run on that grid */
static void test_second_grid(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    double lambda[2] = {NAN, NAN}, second = NAN;
    int code[2] = {-1, -1};
    if (!gb_check_tempdir("second-grid", dir, sizeof dir))
        for (int k = 0; k < 2; k++) {
            char text[500], name[16];
            static char out[1 << 14];
            snprintf(text, sizeof text, "[body]\nr = 1 + 0.1*cos(theta)*sin(phi)\n[model]\ncontact = fast-grid\ngrid = %s\n"
                     "[integrator]\nperiods = 20\n[diagnostics]\nlyapunov = yes\n[lyapunov]\ndelta0 = 1e-7\n"
                     "transient_periods = 0\ninterval_periods = 1\n[output]\nsummary = yes\nhistory = no\n",
                     k ? "60x120" : "30x60");
            snprintf(name, sizeof name, "egg%d", k);
            cJSON *root = run_scene_text(dir, name, text, &code[k], out, sizeof out);
            lambda[k] = cJSON_GetNumberValue(cJSON_GetObjectItem(cJSON_GetObjectItem(root, "lyapunov"), "lambda_max"));
            const cJSON *g = cJSON_GetObjectItem(root, "grid_model_of_smooth_body"),
                        *grid = cJSON_GetObjectItem(g, "second_grid");
            if (k == 0 && cJSON_GetNumberValue(cJSON_GetArrayItem(grid, 0)) == 60.0 &&
                cJSON_GetNumberValue(cJSON_GetArrayItem(grid, 1)) == 120.0)
                second = cJSON_GetNumberValue(cJSON_GetObjectItem(g, "lambda_max_second_grid"));
            cJSON_Delete(root);
        }
    gb_check_tempdir_remove(dir);
    gb_check c = {"2", "77", "an r expression on a 30 x 60 fast grid with lambda (20 periods): the summary's lambda on the grid "
                  "twice as fine", "the same scene run on the 60 x 120 grid: its lambda_max", "exact: the same run, bit for bit"};
    gb_check_true(&c, code[0] == 0 && code[1] == 0 && isfinite(second) && second == lambda[1],
                  "exit %d, %d; lambda %.6g on 30 x 60, %.6g on 60 x 120 in the first run's summary, %.6g run apart", code[0],
                  code[1], lambda[0], second, lambda[1]);
}

/* Every flight begins at the release (a body dropped from height), a lift-off, a bounce or a landing the body flew on
 * from; every one that ended is a landing: landings + (flying at the end) = released + lift-offs + bounces + flown on */
static void test_flights_counted(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    const char *bin = getenv("GOMBOC_BIN") ? getenv("GOMBOC_BIN") : "build/gomboc";
    static const char *const scenes[] = {"cases/bodies/die-drop.ini", "cases/table1-gomboc-II-g-units-unilateral.ini",
                                         "cases/table1-gomboc-I-g-units-bouncing.ini"};
    int closed = 0, flying_on = 0;
    char detail[600] = "";
    if (!gb_check_tempdir("flights", dir, sizeof dir))
        for (size_t k = 0; k < 3; k++) {
            char args[300];
            static char out[1 << 12];
            snprintf(args, sizeof args, "run %s --out %s", scenes[k], dir);
            const int code = gb_check_command(bin, args, out, sizeof out);
            /* the summary file (the --json copy on standard output would interleave with standard error's line) */
            const char *base = strrchr(scenes[k], '/') + 1;
            char summary[300];
            snprintf(summary, sizeof summary, "%s/%.*s-summary.json", dir, (int)(strlen(base) - 4), base);
            char *text = code == 0 ? gb_check_read_file(summary) : NULL;
            cJSON *root = text ? cJSON_Parse(text) : NULL;
            free(text);
            const cJSON *f = cJSON_GetObjectItem(root, "flight");
            const double landings = cJSON_GetNumberValue(cJSON_GetObjectItem(f, "landings")),
                         lift_offs = cJSON_GetNumberValue(cJSON_GetObjectItem(f, "lift_offs")),
                         bounces = cJSON_GetNumberValue(cJSON_GetObjectItem(f, "bounces")),
                         on = cJSON_GetNumberValue(cJSON_GetObjectItem(f, "landings_flying_on")),
                         height0 = cJSON_GetNumberValue(cJSON_GetObjectItem(cJSON_GetObjectItem(root, "scene"), "height0"));
            const int flying = cJSON_IsTrue(cJSON_GetObjectItem(f, "flying_at_end")), released = height0 > 0.0;
            closed += f && landings + flying == released + lift_offs + bounces + on;
            flying_on += on > 0;
            if (!f) snprintf(detail + strlen(detail), sizeof detail - strlen(detail), "%s%s: exit %d, %.120s", k ? "; " : "",
                             scenes[k], code, out);
            else snprintf(detail + strlen(detail), sizeof detail - strlen(detail), "%s%s: %g landings + %d flying at the end = %d "
                     "released + %g lift-offs + %g bounces + %g flown on", k ? "; " : "", scenes[k], landings, flying, released,
                     lift_offs, bounces, on);
            cJSON_Delete(root);
        }
    gb_check_tempdir_remove(dir);
    gb_check c = {"-", "-", "the flights counted: the die dropped, Table 1's Gomboc II in units of g, Gomboc I bouncing",
                  "landings + flying at the end = released + lift-offs + bounces + landings flown on, in each; some flown on",
                  "exact: counts"};
    gb_check_true(&c, closed == 3 && flying_on >= 2, "%s", detail);
}

int verify_register_s2_bodies(void)
{
    static const verify_test tests[] = {
        {"Housner's rocking block", test_housner,
         "a mesh's polyhedron rocks as Housner's block: omega ratio per impact and the period-amplitude relation in closed form"},
        {"a face landing on a plane of finite friction", test_face_friction,
         "a face landing the friction law cannot follow stops the run saying so, never a wrong motion"},
        {"a die and a coin come to rest", test_die_and_coin,
         "a dropped die stops on one of its stable faces, a coin falls flat: whole faces land at once"},
        {"the paper's chi as an expression", test_expressions_same_body,
         "a body given by an expression is the same body as the built-in morphology, bit for bit (chi) or to rounding (r)"},
        {"Table 1 with the paper's chi as an expression", test_expressions_table1,
         "Table 1's grid runs end in the same fingerprint with chi given as an expression"},
        {"every shipped scene's body", test_scene_bodies,
         "the bodies the scenes name, whatever they are, are closed surfaces: Euler's formula, Poincare-Hopf"},
        {"beta stated only where it enters the body", test_beta_stated, NULL},
        {"a smooth body on its grid says so", test_grid_model_said, NULL},
        {"a smooth body on its grid with lambda: lambda on the grid twice as fine too", test_second_grid, NULL},
        {"continuous contact for a body given by an expression (multi-start)", test_continuous_own,
         "a body given by an expression runs on continuous contact, uncertified and named so, switching where the certificate does"},
        {"every flight counted where it began", test_flights_counted, NULL},
        {"bad bodies in a scene", test_bad_bodies,
         "a mesh or an expression that is not a body is refused, naming the scene's line and the fault"},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Section 2: bodies of one's own as scenes", tests);
}
