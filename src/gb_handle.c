#include "gb_handle.h"

#include "gb_case.h"
#include "gb_contact.h"
#include "gb_error.h"
#include "gb_massprops.h"
#include "gb_melnikov_body.h"
#include "gb_run.h"
#include "gb_scan.h"
#include "gb_shape.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct gb_handle_scene {
    gb_case scene;
};

struct gb_handle_run {
    gb_run_result result;
    double *history, *impacts; /* rows × columns each */
    size_t history_rows, impact_rows, history_capacity, impact_capacity;
    int keep_history, keep_impacts;
};

/* The history file's columns (gomboc run's NAME-history.csv, docs/outputs.md), with the slip's two. */
static const char *const columns[] = {"t", "omega_x", "omega_y", "omega_z", "h", "E", "residual", "geff", "index",
                                      "grid_switch", "branch_switch", "switch_rate", "rc_x", "rc_y", "rc_z", "normal_force",
                                      "friction_needed", "contacts", "zeta", "clearance", "q_w", "q_x", "q_y", "q_z", "rq_x",
                                      "rq_y", "rq_z", "sliding", "slip_speed", NULL};
enum { COLUMNS = sizeof columns / sizeof columns[0] - 1 };

/* The impacts file's numeric columns (its kind as the code of gb_dynamics_impact_kind). */
static const char *const impact_columns[] = {
    "t", "kind", "settled", "contacts_after", "located", "old_x", "old_y", "old_z", "new_x", "new_y", "new_z",
    "omega_before_x", "omega_before_y", "omega_before_z", "omega_after_x", "omega_after_y", "omega_after_z", "v_before_x",
    "v_before_y", "v_before_z", "v_after_x", "v_after_y", "v_after_z", "normal_impulse", "tangential_impulse",
    "friction_needed", "old_normal_impulse", "return_time", "kinetic_before", "kinetic_after", NULL};
enum { IMPACT_COLUMNS = sizeof impact_columns / sizeof impact_columns[0] - 1 };

static const char *const values[] = {"t_end", "steps", "samples", "energy_residual", "residual_max", "impacts",
                                     "impact_energy_lost", "grid_switches", "branch_switches", "seconds", "omega_x",
                                     "omega_y", "omega_z", "lambda_max", "lambda_error", "lambda_converged", NULL};

const char *const *gb_handle_columns(void) { return columns; }
const char *const *gb_handle_impact_columns(void) { return impact_columns; }
const char *const *gb_handle_values(void) { return values; }

/* The overrides as gb_case_override, their origin "the binding's override". */
static int overrides_of(const char *const *triples, size_t count, gb_case_override **out)
{
    *out = NULL;
    if (!count) return GB_OK;
    if (!triples) return gb_error_set(GB_EINVAL, "%zu overrides and no list of them", count);
    gb_case_override *o = calloc(count, sizeof *o);
    if (!o) return gb_error_set(GB_ENOMEM, "out of memory for %zu overrides", count);
    for (size_t k = 0; k < count; k++) {
        if (!triples[3 * k] || !triples[3 * k + 1] || !triples[3 * k + 2]) {
            free(o);
            return gb_error_set(GB_EINVAL, "override %zu: a section, a key and a value, none NULL", k);
        }
        o[k] = (gb_case_override){triples[3 * k], triples[3 * k + 1], triples[3 * k + 2], "an override"};
    }
    *out = o;
    return GB_OK;
}

static int scene_new(gb_handle_scene **out)
{
    *out = calloc(1, sizeof **out);
    return *out ? GB_OK : gb_error_set(GB_ENOMEM, "out of memory for a scene");
}

int gb_handle_scene_load(const char *path, const char *const *overrides, size_t count, gb_handle_scene **out)
{
    gb_case_override *o;
    int status = overrides_of(overrides, count, &o);
    if (!status) status = scene_new(out);
    if (!status) status = gb_case_load_with(path, o, count, &(*out)->scene);
    free(o);
    if (status && *out) free(*out), *out = NULL;
    return status;
}

int gb_handle_scene_text(const char *name, const char *text, const char *const *overrides, size_t count, gb_handle_scene **out)
{
    if (!text) return gb_error_set(GB_EINVAL, "a scene's text is NULL");
    gb_case_override *o;
    int status = overrides_of(overrides, count, &o);
    if (!status) status = scene_new(out);
    if (!status) status = gb_case_load_text_with(name ? name : "scene", text, strlen(text), o, count, &(*out)->scene);
    free(o);
    if (status && *out) free(*out), *out = NULL;
    return status;
}

void gb_handle_scene_free(gb_handle_scene *scene) { free(scene); }

/* Room for one more row of `width` in *rows (doubling). */
static double *row_in(double **data, size_t *used, size_t *capacity, size_t width)
{
    if (*used == *capacity) {
        const size_t grown = *capacity ? 2 * *capacity : 1024;
        double *more = realloc(*data, grown * width * sizeof *more);
        if (!more) return NULL;
        *data = more, *capacity = grown;
    }
    return *data + (*used)++ * width;
}

static int keep_sample(void *context, const gb_run_sample *s)
{
    gb_handle_run *r = context;
    if (!r->keep_history) return GB_OK;
    double *row = row_in(&r->history, &r->history_rows, &r->history_capacity, COLUMNS);
    if (!row) return gb_error_set(GB_ENOMEM, "out of memory for the history (%zu samples)", r->history_rows);
    const gb_dynamics_observables *o = s->o;
    const double *q = s->y + GB_STATE_Q, n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const double v[COLUMNS] = {s->t, o->omega[0], o->omega[1], o->omega[2], o->height, o->energy, o->residual, o->geff,
                               (double)o->index, s->grid_switch, s->branch_switch, s->switch_rate, o->rc[0], o->rc[1], o->rc[2],
                               o->normal_force, o->friction_needed, o->contacts, o->zeta, o->clearance, q[0] / n, q[1] / n,
                               q[2] / n, q[3] / n, o->rc_other[0], o->rc_other[1], o->rc_other[2], o->sliding, o->slip_speed};
    memcpy(row, v, sizeof v);
    return GB_OK;
}

static int keep_impact(void *context, const gb_dynamics_impact *e)
{
    gb_handle_run *r = context;
    if (!r->keep_impacts) return GB_OK;
    double *row = row_in(&r->impacts, &r->impact_rows, &r->impact_capacity, IMPACT_COLUMNS);
    if (!row) return gb_error_set(GB_ENOMEM, "out of memory for the impacts (%zu)", r->impact_rows);
    const double v[IMPACT_COLUMNS] = {
        e->t, (double)e->kind, e->settled, e->contacts_after, e->located, e->old_point[0], e->old_point[1], e->old_point[2],
        e->new_point[0], e->new_point[1], e->new_point[2], e->omega_before[0], e->omega_before[1], e->omega_before[2],
        e->omega_after[0], e->omega_after[1], e->omega_after[2], e->v_before[0], e->v_before[1], e->v_before[2], e->v_after[0],
        e->v_after[1], e->v_after[2], e->normal_impulse, e->tangential_impulse, e->friction_needed, e->old_normal_impulse,
        e->return_time, e->kinetic_before, e->kinetic_after};
    memcpy(row, v, sizeof v);
    return GB_OK;
}

int gb_handle_run_scene(const gb_handle_scene *scene, int keep_history, int keep_impacts, gb_handle_run **out)
{
    *out = NULL;
    if (!scene) return gb_error_set(GB_EINVAL, "no scene to run");
    gb_handle_run *r = calloc(1, sizeof *r);
    if (!r) return gb_error_set(GB_ENOMEM, "out of memory for a run");
    r->keep_history = keep_history != 0, r->keep_impacts = keep_impacts != 0;
    const gb_run_sinks sinks = {keep_sample, r, keep_impact};
    const int status = gb_run(&scene->scene, &sinks, &r->result);
    if (status) {
        free(r->history), free(r->impacts), free(r);
        return status;
    }
    *out = r;
    return GB_OK;
}

void gb_handle_run_free(gb_handle_run *r)
{
    if (!r) return;
    gb_run_result_free(&r->result);
    free(r->history), free(r->impacts), free(r);
}

const double *gb_handle_run_history(const gb_handle_run *r, size_t *rows)
{
    *rows = r ? r->history_rows : 0;
    return r ? r->history : NULL;
}

const double *gb_handle_run_impacts(const gb_handle_run *r, size_t *rows)
{
    *rows = r ? r->impact_rows : 0;
    return r ? r->impacts : NULL;
}

uint64_t gb_handle_run_fingerprint(const gb_handle_run *r, int which)
{
    return !r ? 0 : which ? r->result.switch_fingerprint : r->result.state_fingerprint;
}

double gb_handle_run_value(const gb_handle_run *r, const char *name)
{
    if (!r || !name) return NAN;
    const gb_run_result *x = &r->result;
    const double v[] = {x->t_end, (double)x->stats.steps, (double)x->samples, x->final.residual, x->residual_max,
                        (double)x->impacts, x->impact_energy_lost, (double)x->final.grid_switches,
                        (double)x->final.branch_switches, x->seconds, x->final.omega[0], x->final.omega[1], x->final.omega[2],
                        x->has_lyapunov ? x->lyapunov.lambda_max : NAN, x->has_lyapunov ? x->lyapunov.error_bar : NAN,
                        x->has_lyapunov ? (double)x->lyapunov.converged : NAN};
    for (size_t k = 0; values[k]; k++)
        if (!strcmp(name, values[k])) return v[k];
    return NAN;
}

int gb_handle_scene_massprops(const gb_handle_scene *scene, double out[13])
{
    if (!scene) return gb_error_set(GB_EINVAL, "no scene");
    gb_massprops_def def = gb_massprops_default_def();
    def.mass = scene->scene.dynamics.mass;
    gb_massprops mp;
    const int status = gb_massprops_compute(&scene->scene.body, &def, &mp);
    if (status) return status;
    out[0] = mp.volume;
    for (int i = 0; i < 3; i++) {
        out[1 + i] = mp.centroid[i];
        for (int j = 0; j < 3; j++) out[4 + 3 * i + j] = mp.inertia[i][j];
    }
    return GB_OK;
}

int gb_handle_scene_equilibria(const gb_handle_scene *scene, double *out, size_t capacity, size_t *count)
{
    if (!scene) return gb_error_set(GB_EINVAL, "no scene");
    if (gb_surface_is_polyhedron(&scene->scene.body))
        return gb_error_set(GB_EINVAL, "the scene's body is a mesh, whose equilibria are its hull's (allowed: a body r(phi, "
                            "theta); a mesh's: gomboc shape --mesh)");
    const gb_shape_def def = gb_shape_default_def();
    gb_equilibria *eq = malloc(sizeof *eq);
    if (!eq) return gb_error_set(GB_ENOMEM, "out of memory for the equilibria");
    const int status = gb_shape_equilibria(&scene->scene.body, &def, eq);
    if (!status) {
        *count = eq->count;
        for (size_t k = 0; k < eq->count && k < capacity; k++) {
            const gb_equilibrium *e = &eq->points[k];
            out[4 * k] = e->type, out[4 * k + 1] = e->phi, out[4 * k + 2] = e->theta, out[4 * k + 3] = e->r;
        }
    }
    free(eq);
    return status;
}

int gb_handle_scene_melnikov(const gb_handle_scene *scene, double out[2])
{
    if (!scene) return gb_error_set(GB_EINVAL, "no scene");
    return gb_scan_melnikov_margins(&scene->scene, &out[0], &out[1]);
}

int gb_handle_scene_tangle(const gb_handle_scene *scene, double spacing, int halvings, double out[6])
{
    if (!scene) return gb_error_set(GB_EINVAL, "no scene");
    const gb_forcing *F = &scene->scene.dynamics.forcing;
    if (!(F->g > 0.0))
        return gb_error_set(GB_EDOM, "[forcing] g = %g: without gravity the reduced potential has no saddle (allowed: g > 0)",
                            F->g);
    gb_melnikov_body *body = NULL;
    gb_melnikov_orbit orbit;
    gb_melnikov_values top;
    gb_melnikov_tangle t = {0};
    int status = gb_melnikov_body_create(&scene->scene.body, scene->scene.dynamics.mass, F->g, GB_MELNIKOV_BODY_NODES, &body);
    const gb_melnikov_model m = status ? (gb_melnikov_model){0} : gb_melnikov_body_model(body, GB_MELNIKOV_MASS_AT_TOP);
    if (!status) status = gb_melnikov_orbit_find(&m, &orbit);
    if (!status) status = m.eval(m.context, orbit.q_u, &top);
    const gb_melnikov_forcing f = {status ? 0.0 : scene->scene.dynamics.damping / top.M, F->a1, F->a2, F->omega, F->psi, 0};
    gb_melnikov_tangle_def def = gb_melnikov_tangle_default_def();
    def.spacing = spacing;
    double bracket[2] = {NAN, NAN};
    if (!status) status = gb_melnikov_tangle_compute(&m, &orbit, &f, &def, &t);
    if (!status && halvings > 0) {
        status = gb_melnikov_tangle_threshold(&m, &orbit, &f, &def, halvings, bracket);
        const double unit = F->a1 != 0.0 ? F->a1 : F->a2;
        bracket[0] *= unit, bracket[1] *= unit;
    }
    if (!status) {
        const double v[6] = {(double)t.in_window, t.in_window ? t.smallest_angle * 180 / M_PI : NAN, t.multipliers[0],
                             t.multipliers[1], bracket[0], bracket[1]};
        memcpy(out, v, sizeof v);
    }
    gb_melnikov_tangle_free(&t);
    gb_melnikov_body_free(body);
    return status;
}

int gb_handle_scene_contact(const gb_handle_scene *scene, const double zb[3], double out[6])
{
    if (!scene) return gb_error_set(GB_EINVAL, "no scene");
    /* as `gomboc contact --method continuous`: every discrete local minimum of the 180 × 360 seed grid polished, the
     * lowest first */
    const gb_contact_grid_def seed_def = gb_contact_default_branch_grid();
    const gb_contact_refine_def refine = gb_contact_refine_default_def();
    gb_contact_grid *seeds = NULL;
    gb_contact_branches branches;
    int status = gb_contact_grid_create(&scene->scene.body, &seed_def, &seeds);
    if (!status) status = gb_contact_branches_find(seeds, zb, &refine, &branches);
    gb_contact_grid_free(seeds);
    if (status) return status;
    const gb_contact_point *p = &branches.branch[0];
    const double v[6] = {p->phi, p->theta, p->height, p->rc[0], p->rc[1], p->rc[2]};
    memcpy(out, v, sizeof v);
    return GB_OK;
}

typedef struct scan_rows {
    char **rows; /* by index */
    gb_handle_progress progress;
    void *user;
} scan_rows;

static int keep_row(void *user, size_t index, const gb_scan_metrics *metrics, const char *row)
{
    (void)metrics;
    scan_rows *r = user;
    const size_t n = strlen(row) + 1;
    if (!(r->rows[index] = malloc(n))) return gb_error_set(GB_ENOMEM, "out of memory for the scan's row %zu", index);
    memcpy(r->rows[index], row, n);
    return GB_OK;
}

static void report_progress(void *user, const gb_scan_progress *p)
{
    const scan_rows *r = user;
    if (r->progress) r->progress(r->user, (int)p->phase, p->done, p->total, p->seconds);
}

int gb_handle_scan(const char *path, unsigned threads, gb_handle_progress progress, void *user, char **csv)
{
    *csv = NULL;
    gb_scan scan;
    int status = gb_scan_load(path, &scan);
    if (status) return status;
    const size_t points = gb_scan_points(&scan);
    scan_rows rows = {calloc(points ? points : 1, sizeof *rows.rows), progress, user};
    char header[8192];
    if (!rows.rows) status = gb_error_set(GB_ENOMEM, "out of memory for %zu rows", points);
    if (!status) status = gb_scan_csv_header(&scan, header, sizeof header);
    const gb_scan_runner runner = {.threads = threads, .finished = keep_row, .progress = report_progress, .user = &rows};
    if (!status) status = gb_scan_run(&scan, &runner, NULL);
    size_t length = strlen(header) + 1;
    for (size_t k = 0; !status && k < points; k++) {
        if (!rows.rows[k]) status = gb_error_set(GB_ENUMERIC, "the scan's point %zu has no row", k);
        else length += strlen(rows.rows[k]);
    }
    char *text = status ? NULL : malloc(length);
    if (!status && !text) status = gb_error_set(GB_ENOMEM, "out of memory for the scan's CSV (%zu bytes)", length);
    if (!status) {
        char *at = text;
        at += sprintf(at, "%s", header);
        for (size_t k = 0; k < points; k++) at += sprintf(at, "%s", rows.rows[k]);
        *csv = text;
    }
    for (size_t k = 0; rows.rows && k < points; k++) free(rows.rows[k]);
    free(rows.rows);
    gb_scan_free(&scan);
    return status;
}

void gb_handle_text_free(char *text) { free(text); }
