/* gomboc run — integrate one scene (a case file) and write what it asks for. */
#include "gomboc_cli.h"

#include "gb_case.h"
#include "gb_error.h"
#include "gb_integrate.h"
#include "gb_spectrum.h"
#include "gb_strobe.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

static const char *usage_run =
    "usage: gomboc run CASE [--out DIR] [--json]\n"
    "\n"
    "  CASE       a scene file (INI; see cases/README.md for every key and its allowed values)\n"
    "  --out DIR  where to write the outputs the scene asks for (default: the current directory):\n"
    "             NAME-history.csv ([output] history = yes): t, omega, h*, E, energy-balance residual,\n"
    "             g_eff, contact index, switch markers, switching rate, r_c, N, required friction;\n"
    "             NAME-summary.json ([output] summary = yes): the scene as read, the final state,\n"
    "             switch counts, energy residual and validity monitors. NAME is CASE without .ini.\n"
    "  --json     also print the summary on standard output\n";

typedef struct run_state {
    gb_dynamics *dynamics;
    const gb_case *scene;
    FILE *history;
    double period;
    /* switching-rate window: switch counts at the samples of the last period */
    size_t *window;
    size_t window_size, window_fill, window_next;
    size_t last_grid, last_branch;
    /* monitors */
    size_t samples, geff_nonpositive, lift_off, friction_over_half;
    double geff_min, normal_min, friction_max, residual_max, orthonormality_max;
    /* diagnostics the scene asked for */
    uint64_t switch_hash;   /* the switch sequence's fingerprint (see fingerprint_add) */
    gb_strobe strobe;
    double *spectrum_x, step;
    size_t spectrum_count, spectrum_capacity, spectrum_first_step;
    int status;
} run_state;

/* Fingerprints: FNV-1a (64 bits) over bytes. Two runs with the same final state and the same switches
 * (at the same samples, to the same contact) have the same two fingerprints; one line compares runs. */
static const uint64_t FNV_OFFSET = 14695981039346656037ull;

static uint64_t fingerprint_add(uint64_t hash, const void *bytes, size_t size)
{
    const unsigned char *p = bytes;
    for (size_t k = 0; k < size; k++) hash = (hash ^ p[k]) * 1099511628211ull;
    return hash;
}

/* ω_x for the spectrum, from the first sample after its transient on. */
static int collect_spectrum(run_state *s, double t, double omega_x)
{
    if (llround(t / s->step) < (long long)s->spectrum_first_step) return GB_OK;
    if (s->spectrum_count == s->spectrum_capacity) {
        const size_t capacity = s->spectrum_capacity ? 2 * s->spectrum_capacity : 4096;
        double *grown = realloc(s->spectrum_x, capacity * sizeof *grown);
        if (!grown) return gb_error_set(GB_ENOMEM, "out of memory for %zu spectrum samples", capacity);
        s->spectrum_x = grown;
        s->spectrum_capacity = capacity;
    }
    s->spectrum_x[s->spectrum_count++] = omega_x;
    return GB_OK;
}

static int sample(void *context, double t, const double y[GB_STATE_SIZE])
{
    run_state *s = context;
    gb_dynamics_observables o;
    s->status = gb_dynamics_observe(s->dynamics, t, y, &o);
    if (s->status) return 1;
    const size_t switches = o.grid_switches + o.branch_switches;
    const int grid_switch = o.grid_switches != s->last_grid, branch_switch = o.branch_switches != s->last_branch;
    s->last_grid = o.grid_switches;
    s->last_branch = o.branch_switches;
    if (grid_switch || branch_switch) {
        const uint64_t event[4] = {s->samples, o.index, o.grid_switches, o.branch_switches};
        s->switch_hash = fingerprint_add(s->switch_hash, event, sizeof event);
    }
    /* Switching rate: switches in the trailing forcing period, per second. */
    const size_t oldest = s->window_fill < s->window_size ? (s->window_fill ? s->window[0] : switches)
                                                          : s->window[s->window_next];
    const double span = s->window_fill < s->window_size ? (double)s->window_fill : (double)s->window_size;
    const double rate = span > 0 ? (double)(switches - oldest) / (s->period * span / (double)s->window_size) : 0.0;
    s->window[s->window_next] = switches;
    s->window_next = (s->window_next + 1) % s->window_size;
    if (s->window_fill < s->window_size) s->window_fill++;
    s->samples++;
    if (s->scene->strobe && (s->status = gb_strobe_offer(&s->strobe, t, o.omega, NULL))) return 1;
    if (s->scene->spectrum && (s->status = collect_spectrum(s, t, o.omega[0]))) return 1;
    s->residual_max = fmax(s->residual_max, fabs(o.residual));
    s->orthonormality_max = fmax(s->orthonormality_max, o.orthonormality);
    if (s->scene->monitors) {
        s->geff_nonpositive += o.geff <= 0.0;
        s->lift_off += o.normal_force <= 0.0;
        s->friction_over_half += o.friction_needed > 0.5;
        s->geff_min = fmin(s->geff_min, o.geff);
        s->normal_min = fmin(s->normal_min, o.normal_force);
        if (isfinite(o.friction_needed)) s->friction_max = fmax(s->friction_max, o.friction_needed);
    }
    if (s->history &&
        fprintf(s->history, "%.10g,%.12g,%.12g,%.12g,%.15g,%.15g,%.6e,%.12g,%zu,%d,%d,%.6g,%.12g,%.12g,%.12g,%.10g,%.6g\n", t,
                o.omega[0], o.omega[1], o.omega[2], o.height, o.energy, o.residual, o.geff, o.index, grid_switch,
                branch_switch, rate, o.rc[0], o.rc[1], o.rc[2], o.normal_force, o.friction_needed) < 0) {
        s->status = gb_error_set(GB_EIO, "cannot write the history: %s", strerror(errno));
        return 1;
    }
    return 0;
}

static cJSON *scene_json(const gb_case *c)
{
    const gb_dynamics_def *d = &c->dynamics;
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "description", c->description);
    cJSON_AddStringToObject(o, "morphology", c->body.morphology->name);
    cJSON_AddNumberToObject(o, "beta", c->body.beta);
    cJSON_AddNumberToObject(o, "mass", d->mass);
    cJSON_AddNumberToObject(o, "g", d->forcing.g);
    cJSON_AddNumberToObject(o, "A1", c->A1);
    cJSON_AddNumberToObject(o, "A2", c->A2);
    cJSON_AddStringToObject(o, "amplitude_units", c->amplitudes_in_g ? "g" : "m/s2");
    cJSON_AddNumberToObject(o, "a1", d->forcing.a1);
    cJSON_AddNumberToObject(o, "a2", d->forcing.a2);
    cJSON_AddNumberToObject(o, "omega", d->forcing.omega);
    cJSON_AddNumberToObject(o, "psi", d->forcing.psi);
    cJSON_AddStringToObject(o, "equation", gb_dynamics_variant_name(d->variant));
    cJSON_AddStringToObject(o, "contact", gb_contact_model_name(d->contact));
    if (d->contact == GB_CONTACT_MODEL_CONTINUOUS) {
        cJSON_AddNumberToObject(o, "certificate_height_tol", d->certify.height_tol);
        cJSON_AddNumberToObject(o, "certificate_max_depth", d->certify.max_depth);
    } else {
        cJSON_AddItemToObject(o, "grid", cli_json_vector((double[]){(double)d->grid.n_phi, (double)d->grid.n_theta}, 2));
        cJSON_AddStringToObject(o, "nodes", gb_contact_nodes_name(d->grid.nodes));
    }
    cJSON_AddNumberToObject(o, "damping", d->damping);
    cJSON_AddStringToObject(o, "integrator", gb_integrate_name(c->integrate.method));
    cJSON_AddNumberToObject(o, "steps_per_period", (double)c->integrate.steps_per_period);
    cJSON_AddNumberToObject(o, "periods", c->integrate.periods);
    if (c->dynamics.contact == GB_CONTACT_MODEL_CONTINUOUS) cJSON_AddBoolToObject(o, "locate_switches", c->integrate.locate_switches);
    if (c->integrate.method != GB_INTEGRATOR_RK4) {
        cJSON_AddNumberToObject(o, "rtol", c->integrate.rtol);
        cJSON_AddNumberToObject(o, "atol", c->integrate.atol);
    }
    cJSON_AddStringToObject(o, "attitude", c->attitude_text);
    cJSON_AddItemToObject(o, "omega0", cli_json_vector(c->omega0, 3));
    cJSON_AddBoolToObject(o, "history", c->write_history);
    cJSON_AddBoolToObject(o, "monitors", c->monitors);
    cJSON_AddNumberToObject(o, "sample_every", (double)c->integrate.sample_every);
    cJSON_AddBoolToObject(o, "strobe", c->strobe);
    if (c->strobe) {
        cJSON_AddNumberToObject(o, "strobe_transient_periods", (double)c->strobe_def.transient);
        cJSON_AddNumberToObject(o, "strobe_phase", c->strobe_def.phase);
    }
    cJSON_AddBoolToObject(o, "spectrum", c->spectrum);
    if (c->spectrum) {
        cJSON_AddNumberToObject(o, "spectrum_transient_periods", (double)c->spectrum_transient);
        cJSON_AddStringToObject(o, "spectrum_window", gb_window_name(c->spectrum_window));
    }
    cJSON_AddBoolToObject(o, "lyapunov", c->lyapunov);
    return o;
}

/* "DIR/NAME-suffix" where NAME is the case file's base name without ".ini" (malloc'd, NULL when out of
 * memory). */
static char *output_path(const char *dir, const char *case_path, const char *suffix)
{
    const char *slash = strrchr(case_path, '/'), *name = slash ? slash + 1 : case_path;
    size_t len = strlen(name);
    if (len > 4 && !strcmp(name + len - 4, ".ini")) len -= 4;
    const size_t size = strlen(dir) + len + strlen(suffix) + 3;
    char *out = malloc(size);
    if (out) snprintf(out, size, "%s/%.*s-%s", dir, (int)len, name, suffix);
    return out;
}

/* The files a run may write. They are one set (cli_outputs): renamed into place together when the whole
 * run succeeded, removed otherwise; then the files of this name that this run did not write (left by an
 * earlier run of another scene of the same name) are removed, so that what stands beside the summary is
 * this run's. */
enum { OUT_HISTORY, OUT_STROBE, OUT_SPECTRUM, OUT_LYAPUNOV, OUT_SUMMARY, OUT_COUNT };
static const char *const out_suffix[OUT_COUNT] = {"history.csv", "strobe.csv", "spectrum.csv", "lyapunov.csv",
                                                  "summary.json"};

typedef struct run_outputs {
    cli_outputs set;
    const char *dir, *case_path;
    int written[OUT_COUNT];
} run_outputs;

static FILE *stage_open(run_outputs *out, int which, int *status)
{
    if (*status) return NULL;
    char *path = output_path(out->dir, out->case_path, out_suffix[which]);
    if (!path) {
        *status = gb_error_set(GB_ENOMEM, "out of memory for an output name");
        return NULL;
    }
    FILE *file = cli_outputs_open(&out->set, path, status);
    if (file) out->written[which] = 1;
    free(path);
    return file;
}

/* The error of a failed write to member `which`. */
static int stage_error(const run_outputs *out, int which)
{
    char *path = output_path(out->dir, out->case_path, out_suffix[which]);
    const int status = gb_error_set(GB_EIO, "cannot write '%s': %s", path ? path : out_suffix[which], strerror(errno));
    free(path);
    return status;
}

static int stage_commit(run_outputs *out, int status)
{
    status = cli_outputs_commit(&out->set, status);
    for (int k = 0; !status && k < OUT_COUNT; k++) {
        if (out->written[k]) continue;
        char *path = output_path(out->dir, out->case_path, out_suffix[k]);
        struct stat st;
        if (path && lstat(path, &st) == 0 && S_ISREG(st.st_mode) && unlink(path) != 0)
            status = gb_error_set(GB_EIO, "cannot remove the stale '%s': %s", path, strerror(errno));
        free(path);
    }
    return status;
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

static cJSON *strobe_json(const gb_strobe *strobe)
{
    cJSON *o = cJSON_CreateObject();
    double mean[3] = {NAN, NAN, NAN}, sd[3] = {NAN, NAN, NAN};
    if (strobe->count) gb_strobe_spread(strobe->x, strobe->count, 3, mean, sd);
    cJSON_AddNumberToObject(o, "samples", (double)strobe->count);
    cJSON_AddItemToObject(o, "mean", cli_json_vector(mean, 3));
    cJSON_AddItemToObject(o, "sd", cli_json_vector(sd, 3));
    /* Is the stroboscopic sequence periodic? The least p ≤ 16 with |ω_{n+p} − ω_n| ≤ 1e-6 rad/s over
     * the last 64 samples, or 0. */
    cJSON_AddNumberToObject(o, "period_detected", (double)gb_strobe_period(strobe->x, strobe->count, 3, 64, 16, 1e-6));
    return o;
}

static cJSON *spectrum_json(const gb_case *scene, const gb_spectrum *spectrum, size_t samples)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "samples", (double)samples);
    cJSON_AddStringToObject(o, "window", gb_window_name(scene->spectrum_window));
    cJSON_AddNumberToObject(o, "df_hz", spectrum->df);
    const size_t peak = gb_spectrum_peak(spectrum);
    cJSON_AddNumberToObject(o, "peak_hz", spectrum->frequency[peak]);
    cJSON_AddNumberToObject(o, "forcing_hz", scene->dynamics.forcing.omega / (2.0 * M_PI));
    return o;
}

int command_run(int argc, char **argv)
{
    const char *case_path = NULL, *dir = ".";
    int json = 0;
    static const char *const valued[] = {"--out", NULL};
    for (int i = 0; i < argc; i++) {
        const char *opt = argv[i], *value = NULL;
        if (opt[0] != '-' || opt[1] == '\0') {
            if (case_path) return cli_input_error("run", "a second case file '%s'%s", opt, " (allowed: one CASE)");
            case_path = opt;
            continue;
        }
        const int kind = cli_next_option("run", argc, argv, &i, usage_run, valued, " (allowed: --out, --json, --help)",
                                         NULL, &json, &value);
        if (kind != CLI_VALUE) {
            if (kind == CLI_NEXT) continue;
            return kind == CLI_HELP ? 0 : kind;
        }
        dir = value;
    }
    if (!case_path) return cli_input_error("run", "missing %s%s", "CASE", " (allowed: a scene file, e.g. cases/table1-gomboc-I.ini)");
    if (cli_output_dir_check("run", "--out", dir)) return EXIT_INPUT;
    gb_case scene;
    int status = gb_case_load(case_path, &scene);
    if (status) return cli_failure("run", status);
    if (cli_parse_only) return 0;

    run_outputs files = {.dir = dir, .case_path = case_path};
    run_state s = {.scene = &scene, .geff_min = INFINITY, .normal_min = INFINITY, .switch_hash = FNV_OFFSET};
    s.period = gb_forcing_period(&scene.dynamics.forcing);
    s.step = s.period / (double)scene.integrate.steps_per_period;
    s.spectrum_first_step = scene.spectrum_transient * scene.integrate.steps_per_period;
    s.window_size = scene.integrate.steps_per_period / scene.integrate.sample_every;
    if (s.window_size < 1) s.window_size = 1;
    s.window = calloc(s.window_size, sizeof *s.window);
    if (!s.window) status = gb_error_set(GB_ENOMEM, "out of memory for the switching-rate window");
    if (!status && scene.strobe)
        status = gb_strobe_init(&s.strobe, 3, 0.0, s.period, scene.integrate.steps_per_period, &scene.strobe_def);
    if (!status && scene.write_history) {
        s.history = stage_open(&files, OUT_HISTORY, &status);
        if (s.history)
            fputs("t,omega_x,omega_y,omega_z,h,E,residual,geff,index,grid_switch,branch_switch,switch_rate,"
                  "rc_x,rc_y,rc_z,normal_force,friction_needed\n", s.history);
    }

    /* The run: plain, or as the reference of the Lyapunov pair when the scene asks for λ. */
    gb_dynamics *dynamics = NULL;
    gb_lyapunov_body *body = NULL;
    gb_lyapunov_result lyapunov = {0};
    double y[GB_STATE_SIZE];
    gb_integrate_stats stats = {0};
    const clock_t start = clock();
    if (!status && scene.lyapunov) {
        status = cli_scene_lyapunov(&scene, sample, &s, &s.dynamics, &body, &lyapunov);
        if (!status) {
            dynamics = gb_lyapunov_body_dynamics(body);
            memcpy(y, gb_lyapunov_body_state(body), sizeof y);
            stats = *gb_lyapunov_body_stats(body, 0);
        }
    } else if (!status) {
        status = gb_dynamics_start(&scene.body, &scene.dynamics, scene.attitude, scene.omega0, &dynamics, y);
        s.dynamics = dynamics;
        if (!status) status = gb_integrate_run(dynamics, &scene.integrate, 0.0, y, sample, &s, &stats);
    }
    if (!status) status = s.status;
    const double seconds = (double)(clock() - start) / CLOCKS_PER_SEC;
    if (s.history && ferror(s.history) && !status) status = stage_error(&files, OUT_HISTORY);
    free(s.window);

    gb_spectrum spectrum = {0};
    if (!status && scene.spectrum)
        status = gb_spectrum_compute(s.spectrum_x, s.spectrum_count, s.step * (double)scene.integrate.sample_every,
                                     scene.spectrum_window, &spectrum);
    if (!status && scene.strobe) status = write_strobe(&files, &s.strobe, s.period);
    if (!status && scene.spectrum) status = write_spectrum(&files, &spectrum);
    if (!status && scene.lyapunov) status = write_lyapunov(&files, &scene, &lyapunov);

    cJSON *root = NULL;
    char state_print[17] = "", switch_print[17] = "";
    snprintf(state_print, sizeof state_print, "%016llx", (unsigned long long)fingerprint_add(FNV_OFFSET, y, sizeof y));
    snprintf(switch_print, sizeof switch_print, "%016llx", (unsigned long long)s.switch_hash);
    if (!status) {
        gb_dynamics_observables o;
        const double t_end = scene.integrate.periods * s.period;
        gb_dynamics_observe(dynamics, t_end, y, &o);
        root = cJSON_CreateObject();
        cJSON_AddItemToObject(root, "scene", scene_json(&scene));
        cJSON_AddNumberToObject(root, "t_end", t_end);
        cJSON_AddItemToObject(root, "quaternion", cli_json_vector(y + GB_STATE_Q, 4));
        cJSON_AddItemToObject(root, "omega", cli_json_vector(y + GB_STATE_OMEGA, 3));
        cJSON_AddNumberToObject(root, "grid_switches", (double)o.grid_switches);
        cJSON_AddNumberToObject(root, "branch_switches", (double)o.branch_switches);
        cJSON_AddNumberToObject(root, "energy_residual_final", o.residual);
        cJSON_AddNumberToObject(root, "energy_residual_max", s.residual_max);
        cJSON_AddNumberToObject(root, "orthonormality_max", s.orthonormality_max);
        cJSON_AddNumberToObject(root, "quaternion_drift_max", stats.max_norm_drift);
        cJSON_AddNumberToObject(root, "steps", (double)stats.steps);
        cJSON_AddNumberToObject(root, "rhs_evaluations", (double)stats.rhs_evaluations);
        cJSON_AddNumberToObject(root, "samples", (double)s.samples);
        cJSON *fp = cJSON_AddObjectToObject(root, "fingerprint");
        cJSON_AddStringToObject(fp, "final_state", state_print);
        cJSON_AddStringToObject(fp, "switches", switch_print);
        cJSON_AddStringToObject(fp, "method", "FNV-1a 64: the bytes of the final state (q, omega, W); the (sample, "
                                "contact index, grid and branch switch counts) of every sample with a switch");
        if (scene.monitors) {
            cJSON *m = cJSON_AddObjectToObject(root, "monitors");
            cJSON_AddNumberToObject(m, "geff_nonpositive_fraction", (double)s.geff_nonpositive / (double)s.samples);
            cJSON_AddNumberToObject(m, "geff_min", s.geff_min);
            cJSON_AddNumberToObject(m, "lift_off_fraction", (double)s.lift_off / (double)s.samples);
            cJSON_AddNumberToObject(m, "normal_force_min", s.normal_min);
            cJSON_AddNumberToObject(m, "friction_needed_max", s.friction_max);
            cJSON_AddNumberToObject(m, "friction_over_half_fraction", (double)s.friction_over_half / (double)s.samples);
        }
        gb_certify_stats cs;
        if (gb_dynamics_certify_stats(dynamics, &cs) == GB_OK) {
            cJSON *m = cJSON_AddObjectToObject(root, "certificate");
            cJSON_AddNumberToObject(m, "checks", (double)cs.checks);
            cJSON_AddNumberToObject(m, "global", (double)cs.global);
            cJSON_AddNumberToObject(m, "lower_found", (double)cs.lower_found);
            cJSON_AddNumberToObject(m, "undecided", (double)cs.undecided);
            cJSON_AddNumberToObject(m, "boxes_tested", (double)cs.boxes_tested);
            cJSON_AddNumberToObject(m, "newton_runs", (double)cs.newton_runs);
            cJSON_AddNumberToObject(m, "basins_built", (double)cs.basins_built);
            cJSON_AddNumberToObject(m, "boxes_kept", (double)cs.boxes_kept);
            cJSON_AddNumberToObject(m, "deepest_split", cs.deepest);
            cJSON_AddNumberToObject(m, "branches_lost", (double)o.branches_lost);
        }
        if (scene.strobe) cJSON_AddItemToObject(root, "strobe", strobe_json(&s.strobe));
        if (scene.spectrum) cJSON_AddItemToObject(root, "spectrum", spectrum_json(&scene, &spectrum, s.spectrum_count));
        if (scene.lyapunov) cJSON_AddItemToObject(root, "lyapunov", cli_lyapunov_json(&scene, &lyapunov, 0));
        /* Exactly the files of this run (any other NAME-* output of an earlier run is removed). */
        cJSON *list = cJSON_AddArrayToObject(root, "files");
        for (int k = 0; k < OUT_COUNT; k++)
            if (files.written[k] || (k == OUT_SUMMARY && scene.write_summary)) {
                char *path = output_path(dir, case_path, out_suffix[k]);
                if (path) cJSON_AddItemToArray(list, cJSON_CreateString(strrchr(path, '/') + 1));
                free(path);
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
    gb_spectrum_free(&spectrum);
    gb_strobe_free(&s.strobe);
    free(s.spectrum_x);
    gb_lyapunov_result_free(&lyapunov);
    if (body) gb_lyapunov_body_free(body);
    else gb_dynamics_free(dynamics);
    if (status) return cli_failure("run", status);
    fprintf(stderr, "gomboc run: %s: %zu steps in %.2f s CPU; fingerprint %s/%s\n", case_path, stats.steps, seconds,
            state_print, switch_print);
    return 0;
}
