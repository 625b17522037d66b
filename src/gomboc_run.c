/* gomboc run — integrate one scene (a case file) and write what it asks for. */
#include "gomboc_cli.h"

#include "gb_body.h"

#include "gb_case.h"
#include "gb_error.h"
#include "gb_integrate.h"
#include "gb_run.h"
#include "gb_spectrum.h"
#include "gb_strobe.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The scene's contact law (gb_dynamics_law_of): what it does, never its name. */
static const gb_dynamics_law *scene_law(const gb_case *scene)
{
    return gb_dynamics_law_of(scene->dynamics.contact_law, scene->dynamics.friction);
}

/* The step judged by the ledger too: under a law whose ledger closes to integration accuracy (the unilateral law:
 * E − E0 − W + L), a residual beyond LEDGER_FRACTION of the energy the run holds and its impacts took is a step too
 * coarse, whatever the turn of each step (steps_per_period = 2: 94.6 J on a 12 J body). The held law's residual
 * is eq 44's own spurious work (a finding), not the step's. Shipped unilateral scenes stay below 5e-4. */
#define LEDGER_FRACTION 0.01

static int ledger_too_coarse(const gb_case *scene, const gb_run_result *r)
{
    return scene_law(scene)->impacts &&
           r->residual_max > LEDGER_FRACTION * (fabs(r->final.energy) + r->impact_energy_lost);
}

static const char *usage_run =
    "usage: gomboc run CASE [--out DIR] [--atlas FILE] [--hull FILE] [--json]\n"
    "\n"
    "  CASE       a scene file (INI; see cases/README.md for every key and its allowed values)\n"
    "  --out DIR  where to write the outputs the scene asks for (default: the current directory):\n"
    "             NAME-history.csv ([output] history = yes): t, omega, h*, E, energy-balance residual,\n"
    "             g_eff, contact index, switch markers, switching rate, r_c, N, required friction,\n"
    "             points on the plane, centroid height, clearance, attitude quaternion, second point;\n"
    "             NAME-summary.json ([output] summary = yes): the scene as read, the final state,\n"
    "             switch counts, energy residual and validity monitors. NAME is CASE without .ini.\n"
    "  --atlas FILE  ([model] certificate = atlas) load the atlas of verticals from FILE when it was\n"
    "             built for this body, beta and certificate (else build it), and write it back after the run\n"
    "  --hull FILE  ([model] contact = fast-grid) load the tracker's hull of the grid nodes from FILE when it\n"
    "             was written for these very nodes (else build it with Qhull and write it there after the run);\n"
    "             without it the hull is kept in the user's cache, $XDG_CACHE_HOME/gomboc (or ~/.cache/gomboc),\n"
    "             by the grid's content (GOMBOC_CACHE=off: no cache)\n"
    "  --json     also print the summary on standard output\n";

/* The history file: one row a sample. */
static const char history_header[] = "t,omega_x,omega_y,omega_z,h,E,residual,geff,index,grid_switch,branch_switch,"
                                     "switch_rate,rc_x,rc_y,rc_z,normal_force,friction_needed,contacts,zeta,clearance,"
                                     "q_w,q_x,q_y,q_z,rq_x,rq_y,rq_z";
/* A plane of finite friction adds the points slipping and the largest slip speed [m/s]. */
static const char history_friction_header[] = ",sliding,slip_speed";

/* Where the run's streams go: the history (a sample a row) and the impacts (an impact a row). */
typedef struct streams {
    FILE *history, *impacts;
    int friction; /* a plane of finite friction: the slip columns */
} streams;

static int history_row(void *context, const gb_run_sample *s)
{
    const gb_dynamics_observables *o = s->o;
    FILE *history = ((streams *)context)->history;
    if (!history) return GB_OK;
    int bad = fprintf(history, "%.10g,%.12g,%.12g,%.12g,%.15g,%.15g,%.6e,%.12g,%zu,%d,%d,%.6g,%.12g,%.12g,%.12g,%.10g,%.6g,%d,%.12g,%.12g",
                      s->t, o->omega[0], o->omega[1], o->omega[2], o->height, o->energy, o->residual, o->geff, o->index,
                      s->grid_switch, s->branch_switch, s->switch_rate, o->rc[0], o->rc[1], o->rc[2], o->normal_force,
                      o->friction_needed, o->contacts, o->zeta, o->clearance) < 0;
    /* the attitude as a unit quaternion (R(q) takes body axes to inertial ones), and the second contact point */
    const double *q = s->y + GB_STATE_Q, n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    bad |= fprintf(history, ",%.15g,%.15g,%.15g,%.15g,%.12g,%.12g,%.12g", q[0] / n, q[1] / n, q[2] / n, q[3] / n, o->rc_other[0],
                   o->rc_other[1], o->rc_other[2]) < 0;
    if (((streams *)context)->friction) bad |= fprintf(history, ",%d,%.12g", o->sliding, o->slip_speed) < 0;
    bad |= fputc('\n', history) == EOF;
    if (bad) return gb_error_set(GB_EIO, "cannot write the history: %s", strerror(errno));
    return GB_OK;
}

/* The impacts file: one row an impact, body axes with the centroid at the origin. */
static const char impacts_header[] = "t,kind,settled,contacts_after,located,old_x,old_y,old_z,new_x,new_y,new_z,omega_before_x,omega_before_y,"
                                     "omega_before_z,omega_after_x,omega_after_y,omega_after_z,v_before_x,v_before_y,"
                                     "v_before_z,v_after_x,v_after_y,v_after_z,normal_impulse,tangential_impulse,"
                                     "friction_needed,old_normal_impulse,return_time,kinetic_before,kinetic_after";

/* A plane of finite friction adds, per impact, the new point's slip before and after, the tangential impulse
 * there (body axes) and whether it slides after. */
static const char impacts_friction_header[] = ",slip_before_x,slip_before_y,slip_before_z,slip_after_x,slip_after_y,"
                                              "slip_after_z,tangential_x,tangential_y,tangential_z,slides_after";

static int impact_row(void *context, const gb_dynamics_impact *e)
{
    const streams *st = context;
    FILE *impacts = st->impacts;
    if (!impacts) return GB_OK;
    int bad = fprintf(impacts, "%.17g,%s,%d,%d,%d", e->t, gb_dynamics_impact_kind_name(e->kind), e->settled,
                      e->contacts_after, e->located) < 0;
    const double *vectors[] = {e->old_point, e->new_point, e->omega_before, e->omega_after, e->v_before, e->v_after};
    for (int k = 0; k < 6; k++) bad |= fprintf(impacts, ",%.17g,%.17g,%.17g", vectors[k][0], vectors[k][1], vectors[k][2]) < 0;
    bad |= fprintf(impacts, ",%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", e->normal_impulse, e->tangential_impulse,
                   e->friction_needed, e->old_normal_impulse, e->return_time, e->kinetic_before, e->kinetic_after) < 0;
    if (st->friction) {
        const double *more[] = {e->slip_before, e->slip_after, e->tangential};
        for (int k = 0; k < 3; k++) bad |= fprintf(impacts, ",%.17g,%.17g,%.17g", more[k][0], more[k][1], more[k][2]) < 0;
        bad |= fprintf(impacts, ",%d", e->slides_after) < 0;
    }
    bad |= fputc('\n', impacts) == EOF;
    return bad ? gb_error_set(GB_EIO, "cannot write the impacts: %s", strerror(errno)) : GB_OK;
}

static cJSON *scene_json(const gb_case *c, const char *path)
{
    const gb_dynamics_def *d = &c->dynamics;
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "file", path);
    cJSON_AddStringToObject(o, "description", c->description);
    /* the body: the paper's morphology, or one's own (its kind, and the mesh file as opened or the expression) */
    cJSON_AddStringToObject(o, "body", c->mesh[0] ? "mesh" : c->r_text[0] ? "r" : c->chi_text[0] ? "chi" : "morphology");
    if (c->mesh[0]) {
        char mesh[PATH_MAX];
        if (!gb_case_mesh_path(path, c, mesh, sizeof mesh)) cJSON_AddStringToObject(o, "mesh", mesh); /* it was read so */
    }
    cJSON_AddStringToObject(o, "body_certificate", gb_surface_is_polyhedron(&c->body)   ? "exact"
                                                   : c->body.morphology->kernel_jet ? "certified"
                                                                                    : "not certified");
    cJSON_AddStringToObject(o, "morphology", c->body.morphology->name);
    cli_json_add(o, "beta", c->body.beta);
    cli_json_add(o, "mass", d->mass);
    cli_json_add(o, "g", d->forcing.g);
    cli_json_add(o, "A1", c->A1);
    cli_json_add(o, "A2", c->A2);
    cJSON_AddStringToObject(o, "amplitude_units", c->amplitudes_in_g ? "g" : "m/s2");
    cli_json_add(o, "a1", d->forcing.a1);
    cli_json_add(o, "a2", d->forcing.a2);
    cli_json_add(o, "omega", d->forcing.omega);
    cli_json_add(o, "psi", d->forcing.psi);
    cJSON_AddStringToObject(o, "equation", gb_dynamics_variant_name(d->variant));
    cJSON_AddStringToObject(o, "contact", gb_contact_model_name(d->contact));
    cJSON_AddStringToObject(o, "contact_law", gb_dynamics_contact_law_name(d->contact_law));
    if (d->contact == GB_CONTACT_MODEL_CONTINUOUS) {
        cJSON_AddStringToObject(o, "certificate", gb_dynamics_certificate_name(d->certificate));
        cli_json_add(o, "certificate_height_tol", d->certify.height_tol);
        cli_json_add(o, "certificate_max_depth", d->certify.max_depth);
    } else {
        cJSON_AddItemToObject(o, "grid", cli_json_vector((double[]){(double)d->grid.n_phi, (double)d->grid.n_theta}, 2));
        cJSON_AddStringToObject(o, "nodes", gb_contact_nodes_name(d->grid.nodes));
    }
    cli_json_add(o, "damping", d->damping);
    if (isfinite(d->friction)) cli_json_add(o, "friction", d->friction);
    else cJSON_AddStringToObject(o, "friction", "rough");
    for (size_t k = 0; k < scene_law(c)->key_count; k++) { /* the law's own coefficients, as its keys name them */
        const gb_dynamics_law_key *key = &scene_law(c)->keys[k];
        const double value = d->law_coefficients[key->slot];
        cli_json_add(o, key->name, isnan(value) ? key->fallback : value);
    }
    if (c->integrate.strategy == GB_STRATEGY_TIME_STEPPING) { /* its own scheme: no stepper of the event-driven one */
        cJSON_AddStringToObject(o, "strategy", gb_integrate_strategy_name(c->integrate.strategy));
        cli_json_add(o, "theta", c->integrate.theta);
        cli_json_add(o, "solver_tolerance", c->integrate.solver_tolerance);
        cli_json_add(o, "solver_iterations", (double)c->integrate.solver_iterations);
    } else {
        cJSON_AddStringToObject(o, "integrator", gb_integrate_name(c->integrate.method));
    }
    cli_json_add(o, "steps_per_period", (double)c->integrate.steps_per_period);
    cli_json_add(o, "periods", c->integrate.periods);
    if (c->dynamics.contact == GB_CONTACT_MODEL_CONTINUOUS) cJSON_AddBoolToObject(o, "locate_switches", c->integrate.locate_switches);
    if (c->integrate.method != GB_INTEGRATOR_RK4) {
        cli_json_add(o, "rtol", c->integrate.rtol);
        cli_json_add(o, "atol", c->integrate.atol);
    }
    cJSON_AddStringToObject(o, "attitude", c->attitude_text);
    cJSON_AddItemToObject(o, "omega0", cli_json_vector(c->omega0, 3));
    if (scene_law(c)->impacts) {
        cli_json_add(o, "restitution", d->restitution);
        cli_json_add(o, "height0", d->height0);
        cJSON_AddItemToObject(o, "velocity0", cli_json_vector(d->velocity0, 3));
    }
    cJSON_AddBoolToObject(o, "history", c->write_history);
    cJSON_AddBoolToObject(o, "monitors", c->monitors);
    cli_json_add(o, "sample_every", (double)c->integrate.sample_every);
    cJSON_AddBoolToObject(o, "strobe", c->strobe);
    if (c->strobe) {
        cli_json_add(o, "strobe_transient_periods", (double)c->strobe_def.transient);
        cli_json_add(o, "strobe_phase", c->strobe_def.phase);
    }
    cJSON_AddBoolToObject(o, "spectrum", c->spectrum);
    if (c->spectrum) {
        cli_json_add(o, "spectrum_transient_periods", (double)c->spectrum_transient);
        cJSON_AddStringToObject(o, "spectrum_window", gb_spectrum_window_name(c->spectrum_window));
    }
    cJSON_AddBoolToObject(o, "lyapunov", c->lyapunov);
    return o;
}

/* The files a run may write. They are one gb_file set: renamed into place, the summary last, when the
 * whole run succeeded, removed otherwise; then the files of this name that this run did not write (left
 * by an earlier run of another scene of the same name) are removed. The summary lists every other file
 * of the set with its size and checksum, so that a set mixed by a kill between two renames is found
 * by `gomboc check`. */
enum { OUT_HISTORY, OUT_STROBE, OUT_SPECTRUM, OUT_LYAPUNOV, OUT_WINDOWS, OUT_IMPACTS, OUT_SUMMARY, OUT_COUNT };
const char *const cli_run_suffixes[OUT_COUNT + 1] = {"history.csv",  "strobe.csv",           "spectrum.csv", "lyapunov.csv",
                                                     "lyapunov-windows.csv", "impacts.csv", "summary.json", NULL};

typedef struct run_outputs {
    gb_file_set set;
    const char *dir, *case_path;
    int written[OUT_COUNT];
} run_outputs;

static FILE *stage_open(run_outputs *out, int which, int *status)
{
    if (*status) return NULL;
    char *path = cli_output_name(out->dir, out->case_path, cli_run_suffixes[which]);
    if (!path) {
        *status = gb_error_set(GB_ENOMEM, "out of memory for an output name");
        return NULL;
    }
    FILE *file = gb_file_set_open(&out->set, path, status);
    if (file) out->written[which] = out->set.count; /* its place in the set, from 1 */
    free(path);
    return file;
}

/* The error of a failed write to member `which`. */
static int stage_error(const run_outputs *out, int which)
{
    char *path = cli_output_name(out->dir, out->case_path, cli_run_suffixes[which]);
    const int status = gb_error_set(GB_EIO, "cannot write '%s': %s", path ? path : cli_run_suffixes[which], strerror(errno));
    free(path);
    return status;
}

/* The set renamed into place and the stale outputs of this NAME removed, the directory locked over both
 * (gb_file_lock): two runs of one NAME into one directory leave one whole set, the later one's. */
static int stage_commit(run_outputs *out, int status)
{
    int lock = -1;
    if (!status) {
        char *path = cli_output_name(out->dir, out->case_path, cli_run_suffixes[OUT_SUMMARY]);
        status = path ? gb_file_lock(path, "writing a run's outputs", &lock) : gb_error_set(GB_ENOMEM, "out of memory");
        free(path);
        out->set.directory_locked = lock >= 0;
    }
    status = gb_file_set_commit(&out->set, status);
    for (int k = 0; !status && k < OUT_COUNT; k++) {
        if (out->written[k]) continue;
        char *path = cli_output_name(out->dir, out->case_path, cli_run_suffixes[k]);
        struct stat st;
        if (path && lstat(path, &st) == 0 && S_ISREG(st.st_mode) && unlink(path) != 0)
            status = gb_error_set(GB_EIO, "cannot remove the stale '%s': %s", path, strerror(errno));
        free(path);
    }
    gb_file_unlock(lock);
    return status;
}

/* Does the scene ask for output `which`? */
static int asks_for(const gb_case *scene, int which)
{
    switch (which) {
    case OUT_HISTORY: return scene->write_history;
    case OUT_STROBE: return scene->strobe;
    case OUT_SPECTRUM: return scene->spectrum;
    case OUT_LYAPUNOV: return scene->lyapunov;
    case OUT_WINDOWS: return scene->lyapunov && scene->lyapunov_window_periods;
    case OUT_IMPACTS: return scene->write_impacts;
    default: return scene->write_summary;
    }
}

/* Every file of the run by the rule of gb_file, before the run: the scene file, the outputs it asks
 * for and the ones it would remove as stale, the atlas and the hull (caches: each read, then written
 * back, and only over a cache of its kind). */
static int check_files(const gb_case *scene, const char *case_path, const char *dir, const char *atlas, const char *hull)
{
    static const char hull_magic[] = GB_CONTACT_HULL_MAGIC;
    gb_file_use uses[OUT_COUNT + 3] = {
        GB_FILE_USE(case_path, "CASE", GB_FILE_INPUT),
        GB_FILE_CACHE_USE(atlas, "--atlas", "an atlas file", GB_ATLAS_FILE_MAGIC, sizeof GB_ATLAS_FILE_MAGIC),
        GB_FILE_CACHE_USE(hull, "--hull", "a hull file", hull_magic, sizeof hull_magic)};
    char *names[OUT_COUNT] = {NULL};
    int bad = 0;
    for (int k = 0; k < OUT_COUNT; k++) {
        names[k] = cli_output_name(dir, case_path, cli_run_suffixes[k]);
        if (!names[k]) bad = cli_input_error("run", "out of memory for an output name");
        uses[3 + k] = GB_FILE_USE(names[k], "--out", asks_for(scene, k) ? GB_FILE_OUTPUT : GB_FILE_SWEPT);
    }
    if (!bad) bad = cli_files_check("run", uses, OUT_COUNT + 3);
    for (int k = 0; k < OUT_COUNT; k++) free(names[k]);
    return bad;
}

static int write_strobe(run_outputs *out, const gb_strobe *strobe, double period)
{
    int status = GB_OK;
    FILE *file = stage_open(out, OUT_STROBE, &status);
    if (!file) return status;
    if (fputs("n,t,omega_x,omega_y,omega_z\n", file) < 0) status = GB_EIO;
    for (size_t n = 0; !status && n < strobe->count; n++) {
        const double *w = strobe->x + 3 * n;
        if (fprintf(file, "%.0f,%.10g,%.12g,%.12g,%.12g\n", nearbyint(strobe->t[n] / period), strobe->t[n], w[0], w[1],
                    w[2]) < 0)
            status = GB_EIO;
    }
    return status == GB_EIO ? stage_error(out, OUT_STROBE) : status;
}

static int write_spectrum(run_outputs *out, const gb_spectrum *spectrum)
{
    int status = GB_OK;
    FILE *file = stage_open(out, OUT_SPECTRUM, &status);
    if (!file) return status;
    if (fputs("frequency_hz,power\n", file) < 0) status = GB_EIO;
    for (size_t k = 0; !status && k < spectrum->count; k++)
        if (fprintf(file, "%.10g,%.10e\n", spectrum->frequency[k], spectrum->power[k]) < 0) status = GB_EIO;
    return status == GB_EIO ? stage_error(out, OUT_SPECTRUM) : status;
}

static int write_lyapunov(run_outputs *out, const gb_case *scene, const gb_lyapunov_result *r)
{
    int status = GB_OK;
    FILE *file = stage_open(out, OUT_LYAPUNOV, &status);
    if (!file) return status;
    if (fputs("interval,period_end,lambda_inst,lambda_running\n", file) < 0) status = GB_EIO;
    for (size_t n = 0; !status && n < r->intervals; n++)
        if (fprintf(file, "%zu,%zu,%.12g,%.12g\n", n + 1,
                    scene->lyapunov_def.transient + (n + 1) * scene->lyapunov_interval_periods, r->instantaneous[n],
                    r->running[n]) < 0)
            status = GB_EIO;
    return status == GB_EIO ? stage_error(out, OUT_LYAPUNOV) : status;
}

/* The windowed exponents ([lyapunov] window_periods): the record's means over consecutive windows. */
typedef struct windows {
    size_t count, per_window; /* windows, and intervals a window */
    double *mean;
} windows;

static int windows_of(const gb_case *scene, const gb_lyapunov_result *r, windows *w)
{
    w->per_window = scene->lyapunov_window_periods / scene->lyapunov_interval_periods;
    w->mean = malloc((r->intervals / w->per_window + 1) * sizeof *w->mean);
    if (!w->mean) return gb_error_set(GB_ENOMEM, "out of memory for the windowed exponents");
    w->count = gb_lyapunov_windows(r->instantaneous, r->intervals, w->per_window, w->mean);
    return GB_OK;
}

static int write_windows(run_outputs *out, const gb_case *scene, const windows *w)
{
    int status = GB_OK;
    FILE *file = stage_open(out, OUT_WINDOWS, &status);
    if (!file) return status;
    if (fputs("window,period_start,period_end,lambda_window,chaotic\n", file) < 0) status = GB_EIO;
    const size_t first = scene->lyapunov_def.transient, length = scene->lyapunov_window_periods;
    for (size_t k = 0; !status && k < w->count; k++)
        if (fprintf(file, "%zu,%zu,%zu,%.17g,%d\n", k + 1, first + k * length, first + (k + 1) * length, w->mean[k],
                    w->mean[k] > GB_LYAPUNOV_CHAOTIC) < 0)
            status = GB_EIO;
    return status == GB_EIO ? stage_error(out, OUT_WINDOWS) : status;
}

static cJSON *windows_json(const gb_case *scene, const windows *w)
{
    cJSON *o = cJSON_CreateObject();
    size_t chaotic = 0;
    for (size_t k = 0; k < w->count; k++) chaotic += w->mean[k] > GB_LYAPUNOV_CHAOTIC;
    const double length = (double)scene->lyapunov_window_periods;
    const double lifetime = gb_lyapunov_lifetime(w->mean, w->count, length);
    cli_json_add(o, "window_periods", length);
    cli_json_add(o, "windows", (double)w->count);
    cli_json_add(o, "chaotic_threshold", GB_LYAPUNOV_CHAOTIC);
    cli_json_add(o, "chaotic_windows", (double)chaotic);
    /* The end of the last chaotic window, in periods after the transient; chaotic to the end: censored. */
    if (isinf(lifetime)) cJSON_AddStringToObject(o, "chaos_lifetime_periods", "censored: chaotic to the end of the record");
    else cli_json_add(o, "chaos_lifetime_periods", lifetime);
    cJSON_AddItemToObject(o, "lambda_window", cli_json_vector(w->mean, w->count));
    return o;
}

static cJSON *strobe_json(const gb_strobe *strobe)
{
    cJSON *o = cJSON_CreateObject();
    double mean[3] = {NAN, NAN, NAN}, sd[3] = {NAN, NAN, NAN};
    if (strobe->count) gb_strobe_spread(strobe->x, strobe->count, 3, mean, sd);
    cli_json_add(o, "samples", (double)strobe->count);
    cJSON_AddItemToObject(o, "mean", cli_json_vector(mean, 3));
    cJSON_AddItemToObject(o, "sd", cli_json_vector(sd, 3));
    /* Is the stroboscopic sequence periodic? The least p ≤ 16 with |ω_{n+p} − ω_n| ≤ 1e-6 rad/s over
     * the last 64 samples, or 0. */
    cli_json_add(o, "period_detected", (double)gb_strobe_period(strobe->x, strobe->count, 3, 64, 16, 1e-6));
    return o;
}

static cJSON *spectrum_json(const gb_case *scene, const gb_spectrum *spectrum, size_t samples)
{
    cJSON *o = cJSON_CreateObject();
    cli_json_add(o, "samples", (double)samples);
    cJSON_AddStringToObject(o, "window", gb_spectrum_window_name(scene->spectrum_window));
    cli_json_add(o, "df_hz", spectrum->df);
    const size_t peak = gb_spectrum_peak(spectrum);
    cli_json_add(o, "peak_hz", spectrum->frequency[peak]);
    cli_json_add(o, "forcing_hz", scene->dynamics.forcing.omega / (2.0 * M_PI));
    return o;
}

/* A summary's block of named numbers, in order. */
typedef struct named_value {
    const char *name;
    double value;
} named_value;

static void add_values(cJSON *object, const named_value *values, size_t count)
{
    for (size_t k = 0; k < count; k++) cli_json_add(object, values[k].name, values[k].value);
}

/* The run's summary (NAME-summary.json) but for its list of files: the scene as read, the final state,
 * counts, residuals, fingerprints, and what the scene's model and diagnostics computed. */
/* A smooth body of one's own (given by an expression) run on a grid model: its grid polyhedron stands for it. */
static int smooth_on_grid(const gb_case *scene)
{
    return gb_body_is_own(&scene->body) && !gb_surface_is_polyhedron(&scene->body) &&
           scene->dynamics.contact != GB_CONTACT_MODEL_CONTINUOUS;
}

/* A smooth body of one's own run as its grid polyhedron with λ: λ again on the grid twice as fine each way (the same scene,
 * no output), so that the page and the summary show how much λ depends on the grid. *lambda NAN where it is not asked. */
typedef struct second_grid {
    size_t n_phi, n_theta;
    double lambda, error;
} second_grid;

static int lambda_second_grid(const gb_case *scene, second_grid *out)
{
    *out = (second_grid){0, 0, NAN, NAN};
    if (!smooth_on_grid(scene) || !scene->lyapunov) return GB_OK;
    gb_case second = *scene;
    second.dynamics.grid.n_phi *= 2, second.dynamics.grid.n_theta *= 2;
    if (second.dynamics.grid.n_phi > GB_CONTACT_GRID_MAX_NODES / second.dynamics.grid.n_theta) return GB_OK; /* no finer */
    second.strobe = second.spectrum = 0;
    gb_run_result r;
    const int status = gb_run(&second, NULL, &r);
    if (status) return status;
    *out = (second_grid){second.dynamics.grid.n_phi, second.dynamics.grid.n_theta, r.lyapunov.lambda_max, r.lyapunov.error_bar};
    gb_run_result_free(&r);
    return GB_OK;
}

static cJSON *summary_json(const gb_case *scene, const char *path, const gb_run_result *r, const windows *w,
                           const char *state_print, const char *switch_print, const second_grid *finer)
{
    const gb_dynamics_observables *o = &r->final;
    cJSON *root = cJSON_CreateObject();
    cJSON_AddItemToObject(root, "scene", scene_json(scene, path));
    cli_json_add(root, "t_end", r->t_end);
    cJSON_AddItemToObject(root, "quaternion", cli_json_vector(r->y + GB_STATE_Q, 4));
    cJSON_AddItemToObject(root, "omega", cli_json_vector(r->y + GB_STATE_OMEGA, 3));
    cli_json_add(root, "grid_switches", (double)o->grid_switches);
    cli_json_add(root, "branch_switches", (double)o->branch_switches);
    cli_json_add(root, "energy_residual_final", o->residual);
    cli_json_add(root, "energy_residual_max", r->residual_max);
    cli_json_add(root, "orthonormality_max", r->orthonormality_max);
    cli_json_add(root, "quaternion_drift_max", r->stats.max_norm_drift);
    cli_json_add(root, "steps", (double)r->stats.steps);
    /* the largest turn |ω| h of an accepted step [rad], and the RK4 steps that turned beyond the bound */
    cli_json_add(root, "step_rotation_max", r->stats.max_step_rotation);
    cli_json_add(root, "steps_too_coarse", (double)r->stats.coarse_steps);
    cJSON_AddBoolToObject(root, "ledger_too_coarse", ledger_too_coarse(scene, r));
    /* where the ledger grew most: its largest change between two samples and the time of the later one */
    cli_json_add(root, "energy_residual_largest_jump", r->residual_jump);
    cli_json_add(root, "energy_residual_largest_jump_t", r->residual_jump_t);
    cli_json_add(root, "rhs_evaluations", (double)r->stats.rhs_evaluations);
    cli_json_add(root, "samples", (double)r->samples);
    if (smooth_on_grid(scene)) {
        /* a smooth body of one's own (an expression) has no certified continuous contact: it runs as the polyhedron of
         * its grid's nodes, and what the run computes (λ above all) is that polyhedron's, at that grid */
        cJSON *g = cJSON_AddObjectToObject(root, "grid_model_of_smooth_body");
        cJSON_AddItemToObject(g, "grid", cli_json_vector((double[]){(double)scene->dynamics.grid.n_phi,
                                                                     (double)scene->dynamics.grid.n_theta}, 2));
        cJSON_AddStringToObject(g, "note", "a smooth body run as its grid polyhedron: the contact, the switches and lambda are "
                                           "the polyhedron's and depend on the grid (docs/bodies.md); with lambda, the run is "
                                           "repeated on the grid twice as fine each way for lambda alone");
        if (finer->n_phi) {
            cJSON_AddItemToObject(g, "second_grid", cli_json_vector((double[]){(double)finer->n_phi, (double)finer->n_theta}, 2));
            cli_json_add(g, "lambda_max_second_grid", finer->lambda);
            cli_json_add(g, "lambda_error_second_grid", finer->error);
        }
    }
    cJSON *fp = cJSON_AddObjectToObject(root, "fingerprint");
    cJSON_AddStringToObject(fp, "final_state", state_print);
    cJSON_AddStringToObject(fp, "switches", switch_print);
    cJSON_AddStringToObject(fp, "method", "FNV-1a 64: the bytes of the final state (q, omega, W); the (sample, "
                            "contact index, grid and branch switch counts) of every sample with a switch");
    if (r->has_monitors) {
        const gb_run_monitors *mo = &r->monitors;
        const double n = (double)r->samples;
        cJSON *m = cJSON_AddObjectToObject(root, "monitors");
        cli_json_add(m, "geff_nonpositive_fraction", (double)mo->geff_nonpositive / n);
        cli_json_add(m, "geff_min", mo->geff_min);
        cli_json_add(m, "lift_off_fraction", (double)mo->lift_off / n);
        cli_json_add(m, "normal_force_min", mo->normal_min);
        cli_json_add(m, "friction_needed_max", mo->friction_max);
        cli_json_add(m, "friction_over_half_fraction", (double)mo->friction_over_half / n);
        if (r->has_sliding) {
            cli_json_add(m, "sliding_fraction", (double)mo->sliding / n);
            cli_json_add(m, "slip_speed_max", mo->slip_max);
        }
    }
    if (r->has_certificate) {
        const gb_certify_stats *cs = &r->certificate;
        const named_value certificate[] = {
            {"checks", (double)cs->checks},         {"global", (double)cs->global},
            {"lower_found", (double)cs->lower_found}, {"undecided", (double)cs->undecided},
            {"boxes_tested", (double)cs->boxes_tested}, {"newton_runs", (double)cs->newton_runs},
            {"basins_built", (double)cs->basins_built}, {"boxes_kept", (double)cs->boxes_kept},
            {"deepest_split", cs->deepest},          {"branches_lost", (double)o->branches_lost}};
        add_values(cJSON_AddObjectToObject(root, "certificate"), certificate, sizeof certificate / sizeof certificate[0]);
    }
    if (r->has_atlas) {
        const gb_atlas_stats *as = &r->atlas;
        const named_value atlas[] = {
            {"loaded", r->atlas_loaded},                 {"checks", (double)as->checks},
            {"answered", (double)as->answered},          {"fallbacks", (double)r->atlas_fallbacks},
            {"lower_found", (double)as->lower_found},    {"newton_runs", (double)as->newton_runs},
            {"cells", (double)as->cells},                {"two_site_cells", (double)as->two_site_cells},
            {"cells_failed", (double)as->cells_failed},  {"deepest_level", as->deepest_level},
            {"boxes", (double)as->boxes},                {"boxes_tested", (double)as->boxes_tested},
            {"build_seconds", as->build_seconds},        {"bytes", (double)as->bytes}};
        add_values(cJSON_AddObjectToObject(root, "atlas"), atlas, sizeof atlas / sizeof atlas[0]);
    }
    cli_json_add(cJSON_AddObjectToObject(root, "massprops"), "loaded", r->massprops_loaded);
    if (r->has_hull) {
        cJSON *h = cJSON_AddObjectToObject(root, "hull");
        cli_json_add(h, "vertices", (double)r->hull_vertices);
        cli_json_add(h, "loaded", r->hull_loaded);
    }
    if (scene_law(scene)->impacts) {
        /* energy_residual_* above is the ledger E − E0 − W + L, L the energy the impacts took */
        cJSON *m = cJSON_AddObjectToObject(root, "impacts");
        cli_json_add(m, "count", (double)r->impacts);
        cli_json_add(m, "energy_lost", r->impact_energy_lost);
        cli_json_add(m, "friction_needed_max", r->impact_friction_max);
        cli_json_add(m, "settled", (double)r->two_point.settled);

        cJSON *tp = cJSON_AddObjectToObject(root, "two_point");
        cli_json_add(tp, "time_fraction", r->two_point.time / r->t_end);
        cli_json_add(tp, "entries", (double)r->two_point.entries);
        cli_json_add(tp, "lifts", (double)r->two_point.lifts);
        cli_json_add(tp, "third_points", (double)r->two_point.third_points);
        /* when the body came to rest on three points (a grid body on a face), null if it did not */
        cli_json_add(tp, "rest_since", r->two_point.rest_since);
        cJSON *fl = cJSON_AddObjectToObject(root, "flight");
        cli_json_add(fl, "restitution", scene->dynamics.restitution);
        cli_json_add(fl, "flight_time_fraction", r->flight.time / r->t_end);
        cli_json_add(fl, "lift_offs", (double)r->flight.lift_offs);
        cli_json_add(fl, "landings", (double)r->flight.landings);
        cli_json_add(fl, "bounces", (double)r->flight.bounces);
        /* landings after which the body flew on with no rebound: a point struck, the body turned off the plane */
        cli_json_add(fl, "landings_flying_on", (double)r->flight.flying_on);
        /* the highest gap between the lowest point and the plane at the accepted steps of a flight [m] */
        cli_json_add(fl, "max_hop_height", r->flight.hop_max);
        cJSON_AddBoolToObject(fl, "flying_at_end", r->flight.flying);
    }
    if (r->has_sliding) {
        /* a plane of finite friction: energy_residual_* above is E − E0 − W + L, L the impacts' and friction's */
        cJSON *sl = cJSON_AddObjectToObject(root, "sliding");
        cli_json_add(sl, "friction", scene->dynamics.friction);
        cli_json_add(sl, "time_fraction", r->sliding.time / r->t_end);
        cli_json_add(sl, "slips", (double)r->sliding.slips);
        cli_json_add(sl, "sticks", (double)r->sliding.sticks);
        cli_json_add(sl, "friction_loss", r->sliding.friction_loss);
        cJSON_AddBoolToObject(sl, "sliding_at_end", r->sliding.sliding);
    }
    if (r->has_stepping) {
        /* the time-stepping strategy: its contact problems (Siconos's fc3d) and the energy its impulses took and gave */
        const gb_dynamics_stepping_stats *st = &r->stepping;
        cJSON *ts = cJSON_AddObjectToObject(root, "stepping");
        cJSON_AddStringToObject(ts, "strategy", gb_integrate_strategy_name(scene->integrate.strategy));
        const named_value stepping[] = {
            {"theta", scene->integrate.theta},            {"steps", (double)st->steps},
            {"problems", (double)st->problems},           {"contact_points", (double)st->contact_points},
            {"contacts_max", (double)st->contacts_max},   {"sweeps", (double)st->sweeps},
            {"residual_max", st->residual_max},           {"fallbacks", (double)st->fallbacks},
            {"dissipation_min", st->dissipation_min},     {"steps_giving_energy", (double)st->negative_dissipation},
            {"energy_given", st->energy_gained},          {"candidates_max", (double)st->candidates_max},
            {"grown", (double)st->grown},                 {"enumerated", (double)st->enumerated},
            {"contact_dissipation_min", st->contact_dissipation_min},
            {"steps_contacts_giving_energy", (double)st->contact_negative}};
        add_values(ts, stepping, sizeof stepping / sizeof stepping[0]);
    }
    if (scene->integrate.hand_over) {
        /* where the event-driven law met a limit, the steps time-stepping took, and its returns in flight */
        cJSON *ho = cJSON_AddObjectToObject(root, "hand_over");
        const gb_integrate_stats *st = &r->stats;
        const named_value hand[] = {{"hand_overs", (double)st->hand_overs},
                                    {"returns", (double)st->hand_backs},
                                    {"stepped_steps", (double)st->stepped_steps},
                                    {"stepped_fraction", st->steps ? (double)st->stepped_steps / (double)st->steps : 0.0},
                                    {"first_time", st->hand_overs ? st->hand_over_first : NAN},
                                    {"pair_unmatched_steps", r->has_lyapunov ? (double)r->pair_stats.unmatched : 0.0}};
        add_values(ho, hand, sizeof hand / sizeof hand[0]);
        cJSON_AddStringToObject(ho, "first_reason", st->hand_over_reason);
    }
    if (r->has_strobe) cJSON_AddItemToObject(root, "strobe", strobe_json(&r->strobe));
    if (r->has_spectrum) cJSON_AddItemToObject(root, "spectrum", spectrum_json(scene, &r->spectrum, r->spectrum_samples));
    if (r->has_lyapunov) {
        cJSON *l = cli_lyapunov_json(scene, &r->lyapunov, 0);
        if (w->mean) cJSON_AddItemToObject(l, "windows", windows_json(scene, w));
        cJSON_AddItemToObject(root, "lyapunov", l);
    }
    return root;
}

/* The scene's law poses the one-step problem time-stepping solves (its row's question, not the friction's value). */
static int time_steps(const gb_case *scene)
{
    const gb_dynamics_law *law = gb_dynamics_law_of(scene->dynamics.contact_law, scene->dynamics.friction);
    return law && law->time_steps;
}

int command_run(int argc, char **argv)
{
    const char *case_path = NULL, *dir = ".", *atlas = NULL, *hull = NULL;
    int json = 0;
    static const char *const valued[] = {"--out", "--atlas", "--hull", NULL};
    for (int i = 0; i < argc; i++) {
        const char *opt = argv[i], *value = NULL;
        const int positional = cli_positional("run", opt, &case_path, "case file", "CASE");
        if (positional) {
            if (positional == 1) continue;
            return positional;
        }
        const int kind = cli_next_option("run", argc, argv, &i, usage_run, valued, " (allowed: --out, --atlas, --hull, --json, --help)",
                                         NULL, &json, &value);
        if (kind != CLI_VALUE) {
            if (kind == CLI_NEXT) continue;
            return kind == CLI_HELP ? 0 : kind;
        }
        if (strcmp(opt, "--atlas") == 0) atlas = value;
        else if (strcmp(opt, "--hull") == 0) hull = value;
        else dir = value;
    }
    if (!case_path) return cli_input_error("run", "missing %s%s", "CASE", " (allowed: a scene file, e.g. cases/table1-gomboc-I.ini)");
    if (cli_output_dir_check("run", "--out", dir)) return EXIT_INPUT;
    gb_case scene;
    int status = gb_case_load(case_path, &scene);
    if (status) return cli_failure("run", status);
    if (atlas && scene.dynamics.certificate != GB_CERTIFICATE_ATLAS)
        return cli_input_error("run", "--atlas %s: %s has no atlas (allowed: a scene with [model] certificate = atlas)",
                               atlas, case_path);
    if (hull && scene.dynamics.contact != GB_CONTACT_MODEL_FAST_GRID)
        return cli_input_error("run", "--hull %s: %s has no hull (allowed: a scene with [model] contact = fast-grid)", hull,
                               case_path);
    if (check_files(&scene, case_path, dir, atlas, hull)) return EXIT_INPUT;
    if (cli_parse_only) return 0;
    char *summary_path = cli_output_name(dir, case_path, cli_run_suffixes[OUT_SUMMARY]);
    int held = !summary_path || cli_lock_probe("run", summary_path, "checking that the outputs can be written");
    if (!held && atlas) held = cli_lock_probe("run", atlas, "checking that the atlas can be written back");
    if (!held && hull) held = cli_lock_probe("run", hull, "checking that the hull can be written");
    free(summary_path);
    if (held) return EXIT_COMPUTE;

    run_outputs files = {.dir = dir, .case_path = case_path};
    streams out = {NULL, NULL, scene_law(&scene)->slips};
    if (scene.write_history) {
        out.history = stage_open(&files, OUT_HISTORY, &status);
        if (out.history && (fputs(history_header, out.history) < 0 ||
                            (out.friction && fputs(history_friction_header, out.history) < 0) || fputc('\n', out.history) == EOF))
            status = stage_error(&files, OUT_HISTORY);
    }
    if (scene.write_impacts) {
        out.impacts = stage_open(&files, OUT_IMPACTS, &status);
        if (out.impacts && (fputs(impacts_header, out.impacts) < 0 ||
                            (out.friction && fputs(impacts_friction_header, out.impacts) < 0) || fputc('\n', out.impacts) == EOF))
            status = stage_error(&files, OUT_IMPACTS);
    }
    const gb_run_sinks sinks = {history_row, &out, impact_row};
    gb_run_result r;
    memset(&r, 0, sizeof r);
    /* the caches: read by the run when it first needs them, written back after it */
    gb_dynamics_context *context = NULL;
    if (!status) status = gb_dynamics_context_create(&context);
    if (!status) status = gb_dynamics_context_files(context, atlas, hull);
    if (!status) status = cli_user_cache(context); /* a hull file named with --hull is used, not the cache's */
    if (!status) status = gb_run_in(&scene, context, out.history || out.impacts ? &sinks : NULL, &r);
    if (!status) status = gb_dynamics_context_save(context);
    gb_dynamics_context_free(context);
    /* a stream that failed is named by its path (the sink's message says only which stream) */
    if (out.history && ferror(out.history) && (!status || status == GB_EIO)) status = stage_error(&files, OUT_HISTORY);
    if (out.impacts && ferror(out.impacts) && (!status || status == GB_EIO)) status = stage_error(&files, OUT_IMPACTS);
    const double period = gb_forcing_period(&scene.dynamics.forcing);
    if (!status && scene.strobe) status = write_strobe(&files, &r.strobe, period);
    if (!status && scene.spectrum) status = write_spectrum(&files, &r.spectrum);
    if (!status && scene.lyapunov) status = write_lyapunov(&files, &scene, &r.lyapunov);
    windows w = {0};
    if (!status && scene.lyapunov && scene.lyapunov_window_periods) {
        status = windows_of(&scene, &r.lyapunov, &w);
        if (!status) status = write_windows(&files, &scene, &w);
    }

    second_grid finer = {0, 0, NAN, NAN};
    if (!status) status = lambda_second_grid(&scene, &finer);
    cJSON *root = NULL;
    char state_print[17] = "", switch_print[17] = "";
    snprintf(state_print, sizeof state_print, "%016llx", (unsigned long long)r.state_fingerprint);
    snprintf(switch_print, sizeof switch_print, "%016llx", (unsigned long long)r.switch_fingerprint);
    if (!status) {
        root = summary_json(&scene, case_path, &r, &w, state_print, switch_print, &finer);
        /* Exactly the files of this run (any other NAME-* output of an earlier run is removed), each
         * with its size and checksum: the summary is the set's manifest. */
        cJSON *list = cJSON_AddArrayToObject(root, "files");
        for (int k = 0; !status && k < OUT_SUMMARY; k++)
            if (files.written[k]) {
                status = gb_file_set_seal(&files.set, files.written[k] - 1);
                if (!status) cli_manifest_add(list, &files.set.member[files.written[k] - 1]);
            }
    }
    char *text = root ? cJSON_Print(root) : NULL;
    if (!status && scene.write_summary) {
        FILE *file = stage_open(&files, OUT_SUMMARY, &status);
        if (file && fputs(text, file) < 0) status = stage_error(&files, OUT_SUMMARY);
    }
    status = stage_commit(&files, status);
    if (!status && json) puts(text);
    free(text);
    cJSON_Delete(root);
    free(w.mean);
    gb_run_result_free(&r);
    if (status) return cli_failure("run", status);
    fprintf(stderr, "gomboc run: %s: contact law %s", case_path, gb_dynamics_contact_law_name(scene.dynamics.contact_law));
    if (scene_law(&scene)->impacts)
        fprintf(stderr, " (restitution %g; %zu impact%s, %zu landing%s", scene.dynamics.restitution, r.impacts,
                r.impacts == 1 ? "" : "s", r.flight.landings, r.flight.landings == 1 ? "" : "s");
    if (scene_law(&scene)->impacts && r.flight.flying_on) fprintf(stderr, " (%zu flying on)", r.flight.flying_on);
    if (scene_law(&scene)->impacts) fprintf(stderr, ", %.1f %% of the time in flight)", 100.0 * r.flight.time / r.t_end);
    fprintf(stderr, "; %zu steps in %.2f s CPU; fingerprint %s/%s\n", r.stats.steps, r.seconds, state_print, switch_print);
    if (smooth_on_grid(&scene))
        fprintf(stderr, "gomboc run: %s: note: a smooth body of one's own runs as its %zu x %zu grid polyhedron: its contact, "
                "switches and lambda are the polyhedron's and depend on the grid (docs/bodies.md)\n", case_path,
                scene.dynamics.grid.n_phi, scene.dynamics.grid.n_theta);
    if (finer.n_phi)
        fprintf(stderr, "gomboc run: %s: lambda_max %.4f +- %.2g 1/s on the %zu x %zu grid, %.4f +- %.2g on the %zu x %zu one\n",
                case_path, r.lyapunov.lambda_max, r.lyapunov.error_bar, scene.dynamics.grid.n_phi, scene.dynamics.grid.n_theta,
                finer.lambda, finer.error, finer.n_phi, finer.n_theta);
    if (r.stats.coarse_steps)
        fprintf(stderr, "gomboc run: %s: warning: %zu of %zu steps turned the body by more than %g rad (at most %.3g rad): "
                "the step is too coarse for the body's spin (RK4's error grows as the fifth power of the turn); the "
                "energy ledger drifted by up to %.3g J against an energy of %.3g J; more [integrator] steps_per_period "
                "resolve it\n", case_path, r.stats.coarse_steps, r.stats.steps, GB_INTEGRATE_ROTATION_MAX,
                r.stats.max_step_rotation, r.residual_max, fabs(r.final.energy));
    else if (ledger_too_coarse(&scene, &r))
        fprintf(stderr, "gomboc run: %s: warning: the energy ledger drifted by up to %.3g J, more than %g of the %.3g J the run "
                "holds and its impacts took, most (%.3g J) in the samples ending at t = %.9g s: the step is too coarse (no "
                "step turned the body by more than %g rad); more [integrator] steps_per_period resolve it%s\n", case_path,
                r.residual_max, LEDGER_FRACTION, fabs(r.final.energy) + r.impact_energy_lost, r.residual_jump,
                r.residual_jump_t, GB_INTEGRATE_ROTATION_MAX,
                scene.integrate.strategy == GB_STRATEGY_EVENT_DRIVEN && time_steps(&scene)
                    ? ", or [integrator] strategy = time-stepping where impacts crowd (docs/stepping.md)" : "");
    if (r.stats.hand_overs)
        fprintf(stderr, "gomboc run: %s: handed over to time-stepping %zu time%s where the event-driven law could not follow "
                "(first at t = %.9g s: %s), back in flight %zu time%s: %zu of %zu steps stepped (%.1f %%)%s\n", case_path,
                r.stats.hand_overs, r.stats.hand_overs == 1 ? "" : "s", r.stats.hand_over_first, r.stats.hand_over_reason,
                r.stats.hand_backs, r.stats.hand_backs == 1 ? "" : "s", r.stats.stepped_steps, r.stats.steps,
                r.stats.steps ? 100.0 * (double)r.stats.stepped_steps / (double)r.stats.steps : 0.0,
                r.has_lyapunov && r.pair_stats.unmatched ? "; the Lyapunov pair's copy could not match the reference's "
                                                           "strategy at some steps (pair_unmatched_steps)" : "");
    if (r.has_stepping)
        fprintf(stderr, "gomboc run: %s: time-stepping (theta %g): %zu contact problems, up to %zu points (of %zu candidates; "
                "%zu posed again with a point that went through), %.1f sweeps each, residual <= %.3g; the impulses gave %.3g J in %zu step%s (a body turning about a held point: O(h)); "
                "the contact problems took >= %.3g J a step from the free motion (%zu step%s gave)\n",
                case_path, scene.integrate.theta, r.stepping.problems, r.stepping.contacts_max, r.stepping.candidates_max,
                r.stepping.grown, r.stepping.problems ? (double)r.stepping.sweeps / (double)r.stepping.problems : 0.0, r.stepping.residual_max,
                r.stepping.energy_gained, r.stepping.negative_dissipation, r.stepping.negative_dissipation == 1 ? "" : "s",
                r.stepping.contact_dissipation_min, r.stepping.contact_negative, r.stepping.contact_negative == 1 ? "" : "s");
    if (r.has_sliding)
        fprintf(stderr, "gomboc run: %s: friction mu = %g: sliding %.1f %% of the time, %zu slips and %zu sticks, friction took "
                "%.4g J\n", case_path, scene.dynamics.friction, 100.0 * r.sliding.time / r.t_end, r.sliding.slips,
                r.sliding.sticks, r.sliding.friction_loss);
    return 0;
}
