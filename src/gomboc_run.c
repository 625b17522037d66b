/* gomboc run — integrate one scene (a case file) and write what it asks for. */
#include "gomboc_cli.h"

#include "gb_case.h"
#include "gb_error.h"
#include "gb_integrate.h"

#include <errno.h>
#include <libgen.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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
    int status;
} run_state;

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
    /* Switching rate: switches in the trailing forcing period, per second. */
    const size_t oldest = s->window_fill < s->window_size ? (s->window_fill ? s->window[0] : switches)
                                                          : s->window[s->window_next];
    const double span = s->window_fill < s->window_size ? (double)s->window_fill : (double)s->window_size;
    const double rate = span > 0 ? (double)(switches - oldest) / (s->period * span / (double)s->window_size) : 0.0;
    s->window[s->window_next] = switches;
    s->window_next = (s->window_next + 1) % s->window_size;
    if (s->window_fill < s->window_size) s->window_fill++;
    s->samples++;
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
    cJSON_AddStringToObject(o, "morphology", c->morphology);
    cJSON_AddNumberToObject(o, "beta", c->beta);
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
    cJSON_AddStringToObject(o, "contact", gb_dynamics_contact_name(d->contact));
    const gb_contact_grid_def *g = d->contact == GB_CONTACT_MODEL_CONTINUOUS ? &d->seed_grid : &d->grid;
    cJSON_AddItemToObject(o, d->contact == GB_CONTACT_MODEL_CONTINUOUS ? "seed_grid" : "grid",
                          cli_json_vector((double[]){(double)g->n_phi, (double)g->n_theta}, 2));
    cJSON_AddStringToObject(o, "nodes", gb_contact_nodes_name(g->nodes));
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
    return o;
}

/* "DIR/NAME-suffix" where NAME is the case file's base name without ".ini". */
static void output_path(const char *dir, const char *case_path, const char *suffix, char *out, size_t size)
{
    char copy[1024];
    snprintf(copy, sizeof copy, "%s", case_path);
    char *name = basename(copy), *dot = strrchr(name, '.');
    if (dot && !strcmp(dot, ".ini")) *dot = '\0';
    snprintf(out, size, "%s/%s-%s", dir, name, suffix);
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
    gb_case scene;
    int status = gb_case_load(case_path, &scene);
    if (status) return cli_failure("run", status);

    gb_dynamics *dynamics = NULL;
    double y[GB_STATE_SIZE];
    status = gb_dynamics_start(scene.morphology, scene.beta, &scene.dynamics, scene.attitude, scene.omega0, &dynamics, y);
    if (status) return cli_failure("run", status);
    char history_path[1200], history_tmp[1300], summary_path[1200];
    output_path(dir, case_path, "history.csv", history_path, sizeof history_path);
    output_path(dir, case_path, "summary.json", summary_path, sizeof summary_path);
    snprintf(history_tmp, sizeof history_tmp, "%s.tmp%ld", history_path, (long)getpid());
    run_state s = {.dynamics = dynamics, .scene = &scene, .geff_min = INFINITY, .normal_min = INFINITY};
    s.period = gb_forcing_period(&scene.dynamics.forcing);
    s.window_size = scene.integrate.steps_per_period / scene.integrate.sample_every;
    if (s.window_size < 1) s.window_size = 1;
    s.window = calloc(s.window_size, sizeof *s.window);
    if (!s.window) status = gb_error_set(GB_ENOMEM, "out of memory for the switching-rate window");
    if (!status && scene.write_history) {
        s.history = fopen(history_tmp, "w");
        if (!s.history) status = gb_error_set(GB_EIO, "cannot write '%s': %s", history_path, strerror(errno));
        else fputs("t,omega_x,omega_y,omega_z,h,E,residual,geff,index,grid_switch,branch_switch,switch_rate,"
                   "rc_x,rc_y,rc_z,normal_force,friction_needed\n", s.history);
    }
    gb_integrate_stats stats = {0};
    const clock_t start = clock();
    if (!status) status = gb_integrate_run(dynamics, &scene.integrate, 0.0, y, sample, &s, &stats);
    if (!status) status = s.status;
    const double seconds = (double)(clock() - start) / CLOCKS_PER_SEC;
    if (s.history && fclose(s.history) != 0 && !status)
        status = gb_error_set(GB_EIO, "cannot write '%s': %s", history_path, strerror(errno));
    if (!status && scene.write_history && rename(history_tmp, history_path) != 0)
        status = gb_error_set(GB_EIO, "cannot write '%s': %s", history_path, strerror(errno));
    if (status) remove(history_tmp); /* nothing half-written that looks complete */
    free(s.window);
    if (status) {
        gb_dynamics_free(dynamics);
        return cli_failure("run", status);
    }
    gb_dynamics_observables o;
    const double t_end = scene.integrate.periods * s.period;
    gb_dynamics_observe(dynamics, t_end, y, &o);
    cJSON *root = cJSON_CreateObject();
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
    if (scene.monitors) {
        cJSON *m = cJSON_AddObjectToObject(root, "monitors");
        cJSON_AddNumberToObject(m, "geff_nonpositive_fraction", (double)s.geff_nonpositive / (double)s.samples);
        cJSON_AddNumberToObject(m, "geff_min", s.geff_min);
        cJSON_AddNumberToObject(m, "lift_off_fraction", (double)s.lift_off / (double)s.samples);
        cJSON_AddNumberToObject(m, "normal_force_min", s.normal_min);
        cJSON_AddNumberToObject(m, "friction_needed_max", s.friction_max);
        cJSON_AddNumberToObject(m, "friction_over_half_fraction", (double)s.friction_over_half / (double)s.samples);
    }
    char *text = cJSON_Print(root);
    if (scene.write_summary) status = cli_write_atomically(summary_path, text);
    if (!status && json) puts(text);
    free(text);
    cJSON_Delete(root);
    gb_dynamics_free(dynamics);
    if (status) return cli_failure("run", status);
    fprintf(stderr, "gomboc run: %s: %zu steps in %.2f s CPU\n", case_path, stats.steps, seconds);
    return 0;
}
