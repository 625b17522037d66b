/* gb_case_check — what no single key of a scene can say, judged once every key is read: the body its keys make, the
 * combinations of keys, the memory its records would take and λ's record (see gb_case.h). Every refusal names the
 * key, its line (or the file that set it over the scene) and what is allowed. The loaders are here: they read the
 * keys (gb_case.c), then judge them together. */
#include "gb_case.h"
#include "gb_case_internal.h"

#include "gb_body.h"
#include "gb_error.h"
#include "gb_file.h"
#include "gb_impact.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/resource.h>

static double memory_estimate(const gb_case *c);
static double memory_limit(void);


static int cross_fail(const char *path, const gb_case *c, const char *section, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

static int cross_fail(const char *path, const gb_case *c, const char *section, const char *key, const char *fmt, ...)
{
    char reason[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(reason, sizeof reason, fmt, ap);
    va_end(ap);
    /* "[s] k = v with …" when the reason starts with the value, else "[s] k: reason"; a key another file set
     * over the scene (a scan's axis) is named by that file's line */
    const char *joint = strncmp(reason, "= ", 2) ? ": " : " ";
    const int index = gb_case_key_index(section, key), line = index >= 0 ? c->key_line[index] : 0;
    const char *origin = index >= 0 ? c->key_origin[index] : NULL;
    if (origin) return gb_error_set(GB_EDOM, "%s: [%s] %s%s%s (in the scene %s)", origin, section, key, joint, reason, path);
    if (line) return gb_error_set(GB_EDOM, "%s:%d: [%s] %s%s%s", path, line, section, key, joint, reason);
    return gb_error_set(GB_EDOM, "%s: [%s] %s (default)%s%s", path, section, key, joint, reason);
}

static int given(const gb_case *c, const char *section, const char *key)
{
    const int k = gb_case_key_index(section, key);
    return c->key_line[k] || c->key_origin[k];
}

int gb_case_mesh_path(const char *scene, const gb_case *c, char *out, size_t size)
{
    const char *slash = strrchr(scene, '/'), *mesh = c->mesh;
    const int n = !mesh[0] || mesh[0] == '/' || !slash ? snprintf(out, size, "%s", mesh)
                                                      : snprintf(out, size, "%.*s/%s", (int)(slash - scene), scene, mesh);
    return n >= 0 && (size_t)n < size ? GB_OK
                                      : gb_error_set(GB_EINVAL, "the mesh's path in the scene's folder is longer than %zu bytes "
                                                                "(allowed: a shorter path)", size - 1);
}

/* [body]: the paper's morphology, or a body of one's own (gb_body.h), made here once every key is read. */
static int resolve_body(const char *path, gb_case *c)
{
    /* a key given with no value names no body: refused, never read as the default body */
    static const char *const own_keys[] = {"mesh", "r", "chi"};
    const char *const own_texts[] = {c->mesh, c->r_text, c->chi_text};
    for (int k = 0; k < 3; k++)
        if (given(c, "body", own_keys[k]) && !own_texts[k][strspn(own_texts[k], " \t")])
            return cross_fail(path, c, "body", own_keys[k], "is empty (allowed: %s)",
                              k == 0 ? "a mesh file's path" : "an expression in phi, theta, beta");
    const int mesh = c->mesh[0] != 0, r = c->r_text[0] != 0, chi = c->chi_text[0] != 0;
    const char *own = mesh ? "mesh" : r ? "r" : chi ? "chi" : NULL;
    if (!own) return GB_OK;
    if (mesh + r + chi > 1)
        return cross_fail(path, c, "body", r && chi ? "chi" : own,
                          "with [body] %s: a body is one of morphology, mesh, r and chi (allowed: one of them)",
                          mesh && r ? "r" : mesh ? "chi" : "r");
    if (given(c, "body", "morphology"))
        return cross_fail(path, c, "body", own, "with [body] morphology: a body is one of morphology, mesh, r and chi "
                                                "(allowed: one of them)");
    if (mesh && given(c, "body", "beta"))
        return cross_fail(path, c, "body", "beta", "with [body] mesh: a polyhedron has no beta (allowed: beta with "
                                                   "morphology, r or chi)");
    if (mesh && (given(c, "model", "grid") || given(c, "model", "nodes")))
        return cross_fail(path, c, "model", given(c, "model", "grid") ? "grid" : "nodes",
                          "with [body] mesh: a polyhedron's nodes are its hull's vertices (allowed: no grid or nodes key "
                          "with a mesh)");
    if (c->dynamics.contact == GB_CONTACT_MODEL_CONTINUOUS && mesh)
        return cross_fail(path, c, "model", "contact",
                          "= continuous with [body] mesh: a polyhedron's contact is always a vertex, found exactly on its nodes "
                          "(allowed: grid or fast-grid with a mesh)");
    if (c->dynamics.contact == GB_CONTACT_MODEL_CONTINUOUS) { /* an expression: no enclosure certifies its contact */
        if (!given(c, "model", "certificate")) c->dynamics.certificate = GB_CERTIFICATE_MULTISTART;
        else if (c->dynamics.certificate != GB_CERTIFICATE_MULTISTART)
            return cross_fail(path, c, "model", "certificate",
                              "= %s with [body] %s: the certificates prove the contact global by interval enclosures of the "
                              "surface, which an expression has not here (allowed: multi-start, uncertified, the default for "
                              "continuous contact with a body of one's own)", gb_dynamics_certificate_name(c->dynamics.certificate), own);
    }
    const int line = c->key_line[gb_case_key_index("body", own)];
    int status;
    if (mesh) {
        char file[PATH_MAX];
        status = gb_case_mesh_path(path, c, file, sizeof file);
        if (!status) status = gb_body_mesh(file, &c->body);
    } else {
        status = gb_body_expression(r ? GB_BODY_RADIUS : GB_BODY_PHASE, r ? c->r_text : c->chi_text, c->body.beta, &c->body);
    }
    if (!status) return GB_OK;
    char message[1024];
    snprintf(message, sizeof message, "%s%s", gb_error_message(),
             strstr(gb_error_message(), "allowed") ? "" : " (allowed: a readable OFF, OBJ or STL file, its path relative to the scene's folder)");
    const int index = gb_case_key_index("body", own);
    if (c->key_origin[index]) return gb_error_set(GB_EINVAL, "%s: [body] %s: %s (in the scene %s)", c->key_origin[index], own, message, path);
    return gb_error_set(GB_EINVAL, "%s:%d: [body] %s: %s", path, line, own, message);
}

int gb_case_cross_check(const char *path, gb_case *c)
{
    const int body = resolve_body(path, c);
    if (body) return body;
    const double periods = c->integrate.periods;
    const size_t spp = c->integrate.steps_per_period;
    /* The grid contact is piecewise constant in the attitude: the right-hand side jumps whenever the
     * lowest node changes, and an adaptive stepper's error control shrinks its step at every jump
     * (millions of steps a period). Such a pair has no useful result. */
    const gb_dynamics_law *law = gb_dynamics_law_of(c->dynamics.contact_law, INFINITY);
    const int without_jumps = law->pushes_every_vertex && c->mesh[0]; /* a polyhedron pushed at every vertex */
    const int stepping = c->integrate.strategy == GB_STRATEGY_TIME_STEPPING; /* its own scheme: judged below */
    /* locate_switches not given follows the law: yes where every event must be located inside its step (the
     * unilateral and compliant laws, event-driven), no otherwise (the held law's paper reading; time-stepping) */
    if (!given(c, "integrator", "locate_switches")) c->integrate.locate_switches = law->several_events_per_step && !stepping;
    if (c->integrate.method != GB_INTEGRATOR_RK4 && c->dynamics.contact != GB_CONTACT_MODEL_CONTINUOUS && !without_jumps &&
        !stepping)
        return cross_fail(path, c, "integrator", "method",
                          "= %s with [model] contact = %s: an adaptive stepper cannot cross the jumps of a grid "
                          "contact (its steps collapse at every node change) (allowed: rk4 with grid or fast-grid; "
                          "any method with contact = continuous, or with a mesh body under contact_law = compliant)",
                          gb_integrate_name(c->integrate.method), gb_contact_model_name(c->dynamics.contact));
    if (c->dynamics.certificate != GB_CERTIFICATE_PER_VERTICAL && c->dynamics.contact != GB_CONTACT_MODEL_CONTINUOUS)
        return cross_fail(path, c, "model", "certificate",
                          "= %s with [model] contact = %s: only continuous contact is certified (allowed: "
                          "per-vertical with any contact; atlas or multi-start with contact = continuous)",
                          gb_dynamics_certificate_name(c->dynamics.certificate), gb_contact_model_name(c->dynamics.contact));
    /* the contact law's traits (whatever the plane's friction; a friction the law cannot take is judged below, naming
     * its own key) */
    const char *law_name = gb_dynamics_contact_law_name(c->dynamics.contact_law);
    if (law->impacts && c->dynamics.contact == GB_CONTACT_MODEL_CONTINUOUS && c->dynamics.variant != GB_VARIANT_ROLLING)
        return cross_fail(path, c, "model", "contact_law",
                          "= %s with [model] contact = continuous, equation = %s: eq 44 makes and takes energy "
                          "where the contact moves on the surface, which the impacts' energy ledger cannot close (allowed: "
                          "held with any model; unilateral with equation = rolling, or with a grid model and either "
                          "equation; compliant with any model)", law_name, gb_dynamics_variant_name(c->dynamics.variant));
    if (stepping) {
        const gb_dynamics_law *posed = gb_dynamics_law_of(c->dynamics.contact_law, c->dynamics.friction);
        if (!posed || !posed->time_steps)
            return cross_fail(path, c, "integrator", "strategy",
                              "= time-stepping with [model] contact_law = %s, friction = %g: that law poses no one-step "
                              "contact problem (allowed: contact_law = unilateral with a finite friction; a rough plane's "
                              "unbounded tangential impulse is no cone Siconos's fc3d takes)",
                              law_name, c->dynamics.friction);
        if (c->integrate.locate_switches)
            return cross_fail(path, c, "integrator", "locate_switches",
                              "= yes with strategy = time-stepping, which locates no event (allowed: no)");
        if (c->integrate.method != GB_INTEGRATOR_RK4)
            return cross_fail(path, c, "integrator", "method",
                              "= %s with strategy = time-stepping, which steps by its own theta-method (allowed: rk4, "
                              "the default, which it ignores)", gb_integrate_name(c->integrate.method));
        if (c->integrate.hand_over)
            return cross_fail(path, c, "integrator", "hand_over",
                              "= time-stepping with strategy = time-stepping, which steps every step already (allowed: "
                              "none)");
    } else if (c->integrate.hand_over) {
        const gb_dynamics_law *posed = gb_dynamics_law_of(c->dynamics.contact_law, c->dynamics.friction);
        if (!posed || !posed->time_steps)
            return cross_fail(path, c, "integrator", "hand_over",
                              "= time-stepping with [model] contact_law = %s, friction = %g: that law poses no one-step "
                              "contact problem to hand over to (allowed: none; time-stepping with contact_law = "
                              "unilateral and a finite friction)", law_name, c->dynamics.friction);
        if (c->integrate.method != GB_INTEGRATOR_RK4)
            return cross_fail(path, c, "integrator", "hand_over",
                              "= time-stepping with [integrator] method = %s (allowed: with rk4, whose steps time-stepping "
                              "takes again on the same grid)", gb_integrate_name(c->integrate.method));
    } else {
        static const char *const own[] = {"theta", "solver_tolerance", "solver_iterations"};
        for (size_t k = 0; k < sizeof own / sizeof own[0]; k++)
            if (given(c, "integrator", own[k]))
                return cross_fail(path, c, "integrator", own[k], "needs [integrator] strategy = time-stepping or "
                                  "hand_over = time-stepping (allowed: with either only)");
    }
    if (law->several_events_per_step && !c->integrate.locate_switches && !stepping)
        return cross_fail(path, c, "integrator", "locate_switches",
                          "= no with [model] contact_law = %s: every %s is located inside its step (allowed: "
                          "yes with contact_law = %s)", law_name,
                          law->impacts ? "impact" : "change of the lowest point", law_name);
    {
        const double *v = c->dynamics.velocity0;
        const char *key = !law->impacts && c->dynamics.restitution != 0.0                          ? "restitution"
                          : !law->translates && c->dynamics.height0 != 0.0                         ? "height"
                          : !law->translates && (v[0] != 0.0 || v[1] != 0.0 || v[2] != 0.0)       ? "velocity"
                                                                                                   : NULL;
        if (key)
            return cross_fail(path, c, strcmp(key, "restitution") ? "initial" : "model", key,
                              "with [model] contact_law = %s: %s (allowed: the default, 0, with contact_law = %s; any "
                              "value in range with unilateral)", law_name,
                              law->translates ? "its impacts are its own forces, with no Newton's restitution"
                                              : "a held contact never leaves the plane and has no impacts",
                              law_name);
    }
    const gb_dynamics_law *on_plane = gb_dynamics_law_of(c->dynamics.contact_law, c->dynamics.friction);
    if (!on_plane || (on_plane->needs_friction && !isfinite(c->dynamics.friction)))
        return cross_fail(path, c, "model", "friction",
                          "= %g with [model] contact_law = %s: %s (allowed: rough with either held or unilateral; a "
                          "finite mu with contact_law = unilateral or compliant)", c->dynamics.friction, law_name,
                          law->needs_friction ? "its friction is Coulomb's, regularised, and needs a finite mu"
                                              : "a held contact never slips");
    if (c->write_impacts && !law->impacts)
        return cross_fail(path, c, "output", "impacts",
                          "= yes with [model] contact_law = %s: a %s contact has no impacts (allowed: yes with "
                          "contact_law = unilateral)", law_name, law_name);
    /* a law's own keys need that law */
    const size_t table = gb_case_table_key_count();
    for (size_t k = table; k < gb_case_key_total(); k++) {
        const gb_dynamics_law *owner;
        const gb_dynamics_law_key *key = gb_dynamics_law_key_at(k - table, &owner);
        if ((c->key_line[k] || c->key_origin[k]) && owner->id != c->dynamics.contact_law)
            return cross_fail(path, c, "model", key->name, "needs [model] contact_law = %s (allowed: with that law only)",
                              gb_dynamics_contact_law_name(owner->id));
    }
    if (c->strobe || c->spectrum || c->lyapunov) {
        if (spp % c->integrate.sample_every)
            return cross_fail(path, c, "output", "sample_every",
                              "%zu does not divide [integrator] steps_per_period = %zu (allowed: a divisor, so that "
                              "every strobe instant and the spectrum's samples fall on a sample)",
                              c->integrate.sample_every, spp);
    }
    if (c->strobe) {
        if (!((double)c->strobe_def.transient < periods))
            return cross_fail(path, c, "strobe", "transient_periods",
                              "= %zu leaves no strobe samples (allowed: < [integrator] periods = %g)",
                              c->strobe_def.transient, periods);
        const double on_grid = c->strobe_def.phase * (double)(spp / c->integrate.sample_every);
        if (fabs(on_grid - nearbyint(on_grid)) > 1e-9)
            return cross_fail(path, c, "strobe", "phase", "= %g is not on the sample grid (allowed: a multiple of %zu/%zu)",
                              c->strobe_def.phase, c->integrate.sample_every, spp);
    }
    if (c->spectrum && !((double)c->spectrum_transient + 1.0 <= periods))
        return cross_fail(path, c, "spectrum", "transient_periods",
                          "= %zu leaves less than one period (allowed: <= [integrator] periods - 1 = %g)",
                          c->spectrum_transient, periods - 1.0);
    /* What cannot be done: more steps than days of computing, or records larger than the machine can hold. */
    if ((double)spp * periods > GB_CASE_STEPS_MAX)
        return cross_fail(path, c, "integrator", "periods",
                          "= %g with steps_per_period = %zu: %.3g steps (allowed: periods x steps_per_period <= %g, some days "
                          "of computing at a microsecond a step)", periods, spp, (double)spp * periods, GB_CASE_STEPS_MAX);
    const double held = memory_estimate(c), limit = memory_limit();
    if (held > limit)
        return cross_fail(path, c, "integrator", "periods",
                          "= %g: the run would hold about %.3g GB of records (the spectrum's samples of omega_x, 24 bytes "
                          "each with its transform, and the strobe's) (allowed: at most %.3g GB, half this machine's memory "
                          "or the address-space limit; fewer periods, a larger [output] sample_every, or no spectrum)",
                          periods, held / 1e9, limit / 1e9);
    if (c->lyapunov) return gb_case_lyapunov_check(path, c);
    return GB_OK;
}

/* The bytes a scene's records (spectrum, strobe, λ) would take. */
static double memory_estimate(const gb_case *c)
{
    const double spp = (double)c->integrate.steps_per_period, periods = c->integrate.periods;
    const double samples_a_period = spp / (double)c->integrate.sample_every;
    double bytes = 0.0;
    if (c->spectrum) /* ω_x samples kept (a growing array, up to twice its fill) and the transform's copy */
        bytes += 24.0 * samples_a_period * (periods - (double)c->spectrum_transient);
    if (c->strobe) bytes += 2.0 * 8.0 * 8.0 * (periods - (double)c->strobe_def.transient); /* t and up to 7 coordinates */
    if (c->lyapunov) bytes += 3.0 * 8.0 * periods; /* per-interval rates, running mean, windows */
    return bytes;
}

/* Half the machine's memory, or of RLIMIT_AS: the most a scene's records may take. */
static double memory_limit(void)
{
    const double pages = (double)sysconf(_SC_PHYS_PAGES), page = (double)sysconf(_SC_PAGESIZE);
    double limit = pages > 0.0 && page > 0.0 ? 0.5 * pages * page : 1e12;
    struct rlimit as;
    if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY) limit = fmin(limit, 0.5 * (double)as.rlim_cur);
    return limit;
}

int gb_case_lyapunov_check(const char *path, gb_case *c)
{
    gb_lyapunov_def *l = &c->lyapunov_def;
    const double periods = c->integrate.periods, k = (double)c->lyapunov_interval_periods;
    const double record = periods - (double)l->transient, intervals = record / k;
    if (!(record >= 2.0 * k) || fabs(intervals - nearbyint(intervals)) > 1e-9)
        return cross_fail(path, c, "lyapunov", "interval_periods",
                          "= %zu with transient_periods = %zu does not divide the %g periods of the run into whole "
                          "intervals (allowed: periods - transient_periods = a multiple of interval_periods, at least 2 "
                          "intervals)",
                          c->lyapunov_interval_periods, l->transient, periods);
    /* A chosen warm-up is at most half the record (MSER-5). */
    const double warmup = l->warmup == GB_LYAPUNOV_CHOSEN ? floor(nearbyint(intervals) / 2.0) : (double)l->warmup;
    if (l->warmup != GB_LYAPUNOV_CHOSEN && !(2.0 * warmup < nearbyint(intervals)))
        return cross_fail(path, c, "lyapunov", "warmup_intervals",
                          "= %zu is not less than half the %g intervals of the record (allowed: chosen, or 0 <= "
                          "warmup_intervals < intervals / 2)",
                          l->warmup, nearbyint(intervals));
    if (l->batches != GB_LYAPUNOV_CHOSEN && (double)l->batches > nearbyint(intervals) - warmup)
        return cross_fail(path, c, "lyapunov", "batches",
                          "= %zu exceeds the %g intervals of the record after its longest warm-up (allowed: chosen, "
                          "or 2 <= batches <= intervals - warmup_intervals, where a chosen warm-up may reach half the "
                          "intervals)",
                          l->batches, nearbyint(intervals) - warmup);
    const size_t window = c->lyapunov_window_periods;
    if (window && (window % c->lyapunov_interval_periods != 0 || (double)window > record))
        return cross_fail(path, c, "lyapunov", "window_periods",
                          "= %zu is not a whole number of intervals of %zu periods within the record of %g periods "
                          "(allowed: 0 for no windows, or a multiple of interval_periods up to periods - "
                          "transient_periods)",
                          window, c->lyapunov_interval_periods, record);
    l->interval = (double)k * gb_forcing_period(&c->dynamics.forcing);
    l->intervals = (size_t)nearbyint(intervals);
    if (c->omega_scale == 0.0) c->omega_scale = c->dynamics.forcing.omega;
    return GB_OK;
}

/* ---- the loaders: the keys read (gb_case.c), then judged together ------------------------------ */

int gb_case_load_text_with(const char *name, const char *text, size_t size, const gb_case_override *overrides,
                           size_t count, gb_case *out)
{
    gb_case scene;
    int status = gb_case_read_keys(name, text, size, overrides, count, &scene);
    if (!status) status = gb_case_cross_check(name, &scene);
    memset(scene.key_origin, 0, sizeof scene.key_origin); /* the overrides' texts are the caller's */
    if (status) return status;
    /* Amplitudes in m/s² for the dynamics. */
    const double unit = scene.amplitudes_in_g ? scene.dynamics.forcing.g : 1.0;
    scene.dynamics.forcing.a1 = scene.A1 * unit;
    scene.dynamics.forcing.a2 = scene.A2 * unit;
    *out = scene;
    return GB_OK;
}

int gb_case_load_text(const char *name, const char *text, size_t size, gb_case *out)
{
    return gb_case_load_text_with(name, text, size, NULL, 0, out);
}

int gb_case_load_with(const char *path, const gb_case_override *overrides, size_t count, gb_case *out)
{
    char *text;
    size_t size;
    int status = gb_file_read(path, GB_CASE_FILE_MAX, "case file", "a scene file, see cases/README.md", &text, &size);
    if (status) return status;
    status = gb_case_load_text_with(path, text, size, overrides, count, out);
    free(text);
    return status;
}

int gb_case_load(const char *path, gb_case *out) { return gb_case_load_with(path, NULL, 0, out); }
