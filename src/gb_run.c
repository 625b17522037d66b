#include "gb_run.h"

#include "gb_hash.h"

#include "gb_dynamics_protocol_internal.h"
#include "gb_error.h"
#include "gb_lyapunov_body.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>


/* What the observer keeps between samples. */
typedef struct observer {
    const gb_case *scene;
    const gb_run_sinks *sinks;
    gb_dynamics *dynamics;
    gb_run_result *out;
    double period, step;
    /* switching-rate window: switch counts at the samples of the last period */
    size_t *window;
    size_t window_size, window_fill, window_next;
    size_t last_grid, last_branch;
    double last_residual; /* the ledger at the previous sample (NAN before the first) */
    /* spectrum: ω_x from its first sample after the transient on */
    double *spectrum_x;
    size_t spectrum_capacity, spectrum_first_step;
    int status;
    char *failure; /* the message of the status that stopped the sampling (malloc'd) */
} observer;

/* The sample's failure, kept: whoever stopped the run after it (the Lyapunov pair) reports it, not its own
 * "stopped" message. Returns 1, what a sampler returns to stop. */
static int stopped(observer *s)
{
    if (!s->failure) s->failure = strdup(gb_error_message());
    return 1;
}

/* The status of the sampling's failure with its own message (for a caller whose message came after). */
static int sampling_failure(const observer *s)
{
    return gb_error_set(s->status, "%s", s->failure ? s->failure : "the sampling failed");
}

static int collect_spectrum(observer *s, double t, double omega_x)
{
    if (llround(t / s->step) < (long long)s->spectrum_first_step) return GB_OK;
    gb_run_result *r = s->out;
    if (r->spectrum_samples == s->spectrum_capacity) {
        const size_t capacity = s->spectrum_capacity ? 2 * s->spectrum_capacity : 4096;
        double *grown = realloc(s->spectrum_x, capacity * sizeof *grown);
        if (!grown) return gb_error_set(GB_ENOMEM, "out of memory for %zu spectrum samples", capacity);
        s->spectrum_x = grown;
        s->spectrum_capacity = capacity;
    }
    s->spectrum_x[r->spectrum_samples++] = omega_x;
    return GB_OK;
}

static int observe(void *context, double t, const double y[GB_STATE_SIZE])
{
    observer *s = context;
    gb_run_result *r = s->out;
    gb_dynamics_observables o;
    s->status = gb_dynamics_observe(s->dynamics, t, y, &o);
    if (s->status) return stopped(s);
    const size_t switches = o.grid_switches + o.branch_switches;
    const int grid_switch = o.grid_switches != s->last_grid, branch_switch = o.branch_switches != s->last_branch;
    s->last_grid = o.grid_switches;
    s->last_branch = o.branch_switches;
    if (grid_switch || branch_switch) {
        const uint64_t event[4] = {r->samples, o.index, o.grid_switches, o.branch_switches};
        r->switch_fingerprint = gb_hash_add(r->switch_fingerprint, event, sizeof event);
    }
    /* Switching rate: switches in the trailing forcing period, per second. */
    const size_t oldest = s->window_fill < s->window_size ? (s->window_fill ? s->window[0] : switches)
                                                          : s->window[s->window_next];
    const double span = s->window_fill < s->window_size ? (double)s->window_fill : (double)s->window_size;
    const double rate = span > 0 ? (double)(switches - oldest) / (s->period * span / (double)s->window_size) : 0.0;
    s->window[s->window_next] = switches;
    s->window_next = (s->window_next + 1) % s->window_size;
    if (s->window_fill < s->window_size) s->window_fill++;
    r->samples++;
    if (s->scene->strobe && (s->status = gb_strobe_offer(&r->strobe, t, o.omega, NULL))) return stopped(s);
    if (s->scene->spectrum && (s->status = collect_spectrum(s, t, o.omega[0]))) return stopped(s);
    r->residual_max = fmax(r->residual_max, fabs(o.residual));
    if (!isnan(s->last_residual) && fabs(o.residual - s->last_residual) > r->residual_jump)
        r->residual_jump = fabs(o.residual - s->last_residual), r->residual_jump_t = t;
    s->last_residual = o.residual;
    r->orthonormality_max = fmax(r->orthonormality_max, o.orthonormality);
    if (s->scene->monitors) {
        gb_run_monitors *m = &r->monitors;
        m->geff_nonpositive += o.geff <= 0.0;
        m->lift_off += o.normal_force <= 0.0;
        m->friction_over_half += o.friction_needed > 0.5;
        m->sliding += o.sliding > 0;
        m->slip_max = fmax(m->slip_max, o.slip_speed);
        m->geff_min = fmin(m->geff_min, o.geff);
        m->normal_min = fmin(m->normal_min, o.normal_force);
        if (isfinite(o.friction_needed)) m->friction_max = fmax(m->friction_max, o.friction_needed);
    }
    if (s->sinks && s->sinks->sample) {
        const gb_run_sample sample = {t, y, &o, grid_switch, branch_switch, rate};
        if ((s->status = s->sinks->sample(s->sinks->context, &sample))) return stopped(s);
    }
    return 0;
}

void gb_run_result_free(gb_run_result *r)
{
    if (!r) return;
    gb_strobe_free(&r->strobe);
    gb_spectrum_free(&r->spectrum);
    gb_lyapunov_result_free(&r->lyapunov);
    r->has_strobe = r->has_spectrum = r->has_lyapunov = 0;
}

/* The trajectory as the reference of the Lyapunov pair, λ beside it. */
static int run_with_lyapunov(const gb_case *scene, gb_dynamics_context *context, observer *s, gb_dynamics **dynamics,
                             gb_lyapunov_body **body)
{
    gb_run_result *r = s->out;
    int status = gb_lyapunov_body_create_in(&scene->body, &scene->dynamics, context, &scene->integrate, scene->attitude,
                                            scene->omega0, scene->omega_scale, body);
    if (status) return status;
    *dynamics = s->dynamics = gb_lyapunov_body_dynamics(*body);
    if (s->sinks && s->sinks->impact) gb_dynamics_set_impact_sink(*dynamics, s->sinks->impact, s->sinks->context);
    /* The sample at t = 0 is ours; the reference delivers the rest as a plain run would. */
    if (observe(s, 0.0, gb_lyapunov_body_state(*body)))
        return s->status ? sampling_failure(s) : gb_error_set(GB_EINVAL, "the sampler stopped the run at t = 0");
    gb_lyapunov_body_observe(*body, observe, s);
    const gb_lyapunov_pair_system system = gb_lyapunov_body_pair(*body);
    status = gb_lyapunov_pair(&system, *body, &scene->lyapunov_def, 0.0, NULL, &r->lyapunov);
    if (status) return s->status ? sampling_failure(s) : status;
    r->has_lyapunov = 1;
    memcpy(r->y, gb_lyapunov_body_state(*body), sizeof r->y);
    r->stats = *gb_lyapunov_body_stats(*body, 0);
    r->pair_stats = *gb_lyapunov_body_stats(*body, 1);
    return GB_OK;
}

int gb_run(const gb_case *scene, const gb_run_sinks *sinks, gb_run_result *out)
{
    return gb_run_in(scene, NULL, sinks, out);
}

int gb_run_in(const gb_case *scene, gb_dynamics_context *context, const gb_run_sinks *sinks, gb_run_result *out)
{
    memset(out, 0, sizeof *out);
    if (scene->lyapunov && scene->lyapunov_def.intervals == 0)
        return gb_error_set(GB_EINVAL, "the scene's Lyapunov record is not laid out (read it with gb_case_load)");
    out->switch_fingerprint = GB_HASH_OFFSET;
    out->has_monitors = scene->monitors;
    out->monitors = (gb_run_monitors){.geff_min = INFINITY, .normal_min = INFINITY};
    observer s = {.scene = scene, .sinks = sinks, .out = out, .last_residual = NAN};
    out->residual_jump_t = NAN;
    s.period = gb_forcing_period(&scene->dynamics.forcing);
    s.step = gb_forcing_step(&scene->dynamics.forcing, scene->integrate.steps_per_period);
    s.spectrum_first_step = scene->spectrum_transient * scene->integrate.steps_per_period;
    s.window_size = scene->integrate.steps_per_period / scene->integrate.sample_every;
    if (s.window_size < 1) s.window_size = 1;
    s.window = calloc(s.window_size, sizeof *s.window);
    int status = s.window ? GB_OK : gb_error_set(GB_ENOMEM, "out of memory for the switching-rate window");
    if (!status && scene->strobe) {
        status = gb_strobe_init(&out->strobe, 3, 0.0, s.period, scene->integrate.steps_per_period, &scene->strobe_def);
        out->has_strobe = !status;
    }

    gb_dynamics *dynamics = NULL;
    gb_lyapunov_body *body = NULL;
    const clock_t start = clock();
    if (!status && scene->lyapunov) {
        status = run_with_lyapunov(scene, context, &s, &dynamics, &body);
    } else if (!status) {
        status = gb_dynamics_create_in(&scene->body, &scene->dynamics, context, &dynamics);
        /* time-stepping: the body placed as the first step's problem will find it, no mode's start */
        if (!status && scene->integrate.strategy == GB_STRATEGY_TIME_STEPPING) status = gb_dynamics_stepping_prepare(dynamics);
        if (!status) status = gb_dynamics_init_or_hand_over(dynamics, 0.0, scene->attitude, scene->omega0, out->y,
                                                           scene->integrate.hand_over);
        s.dynamics = dynamics;
        if (!status && sinks && sinks->impact) gb_dynamics_set_impact_sink(dynamics, sinks->impact, sinks->context);
        if (!status) status = gb_integrate_run(dynamics, &scene->integrate, 0.0, out->y, observe, &s, &out->stats);
        if (!status) status = s.status;
    }
    out->seconds = (double)(clock() - start) / CLOCKS_PER_SEC;
    free(s.window);
    free(s.failure);

    if (!status && scene->spectrum) {
        status = gb_spectrum_compute(s.spectrum_x, out->spectrum_samples, s.step * (double)scene->integrate.sample_every,
                                     scene->spectrum_window, &out->spectrum);
        out->has_spectrum = !status;
    }
    free(s.spectrum_x);
    if (!status) {
        out->t_end = scene->integrate.periods * s.period;
        status = gb_dynamics_observe(dynamics, out->t_end, out->y, &out->final);
    }
    if (!status) {
        out->state_fingerprint = gb_hash_add(GB_HASH_OFFSET, out->y, GB_STATE_FINGERPRINT * sizeof *out->y);
        gb_dynamics_impact_stats(dynamics, &out->impacts, &out->impact_energy_lost, &out->impact_friction_max);
        out->has_sliding = gb_dynamics_get_law(dynamics)->slips;
        gb_dynamics_sliding_stats(dynamics, out->t_end, out->y, &out->sliding);
        gb_dynamics_two_point_stats(dynamics, out->t_end, &out->two_point);
        gb_dynamics_flight_stats(dynamics, out->t_end, &out->flight);
        const gb_dynamics_stepping_stats *stepping = gb_dynamics_stepping_stats_of(dynamics);
        out->has_stepping = stepping != NULL;
        if (stepping) out->stepping = *stepping;
        out->has_certificate = gb_dynamics_certify_stats(dynamics, &out->certificate) == GB_OK;
        gb_error_clear(); /* a grid model has no certificate: not an error of the run */
        out->has_atlas = gb_dynamics_atlas_stats(dynamics, &out->atlas, &out->atlas_fallbacks, &out->atlas_loaded) == GB_OK;
        gb_error_clear();
        out->has_hull = gb_dynamics_hull_stats(dynamics, &out->hull_vertices, &out->hull_loaded) == GB_OK;
        gb_error_clear();
        out->massprops_loaded = gb_dynamics_massprops_loaded(dynamics);
    }
    if (body) gb_lyapunov_body_free(body);
    else gb_dynamics_free(dynamics);
    if (status) gb_run_result_free(out);
    return status;
}
