/* gb_scan_point — one point of a scan: its scene run by gb_run (the same call as `gomboc run`), the
 * per-sample metrics accumulated from its samples, λ and the chaos's lifetime from its record, and its
 * Melnikov margins from the scan's plan. */
#include "gb_scan_internal.h"

#include "gb_error.h"
#include "gb_run.h"

#include <math.h>
#include <stdlib.h>

void gb_scan_accumulate(gb_scan_accumulator *a, double t, const double omega[3], double height, size_t switches)
{
    if (!(t >= a->first_t)) return;
    if (a->samples == 0) a->t_start = t, a->switches_start = switches;
    a->samples++;
    a->omega2_sum += omega[0] * omega[0] + omega[1] * omega[1] + omega[2] * omega[2];
    a->height_sum += height;
    a->t_last = t;
    a->switches_last = switches;
}

void gb_scan_accumulated(const gb_scan_accumulator *a, double *omega_rms, double *mean_height, double *switch_rate)
{
    const double n = (double)a->samples;
    *omega_rms = a->samples ? sqrt(a->omega2_sum / n) : NAN;
    *mean_height = a->samples ? a->height_sum / n : NAN;
    *switch_rate = a->samples > 1 && a->t_last > a->t_start
                       ? (double)(a->switches_last - a->switches_start) / (a->t_last - a->t_start)
                       : NAN;
}

void gb_scan_accumulate_mode(gb_scan_accumulator *a, double t, int contacts, int sliding, double friction_work)
{
    if (!(t >= a->first_t)) return;
    if (a->samples == 1) a->friction_start = friction_work; /* the first sample counted */
    a->on_plane[contacts >= 0 && contacts <= 3 ? contacts : 0]++;
    a->slipping += sliding > 0;
    a->friction_last = friction_work;
}

void gb_scan_accumulate_impact(gb_scan_accumulator *a, const gb_dynamics_impact *e)
{
    /* as the ledger books them: a lift, a lift-off and a crease's end are changes without an impulse */
    if (!(e->t >= a->first_t) || e->kind == GB_DYNAMICS_IMPACT_LIFT || e->kind == GB_DYNAMICS_IMPACT_LIFT_OFF ||
        e->kind == GB_DYNAMICS_IMPACT_CREASE_END)
        return;
    a->impacts++;
    a->landings += e->kind == GB_DYNAMICS_IMPACT_LANDING;
    a->impact_loss += e->kinetic_before - e->kinetic_after - e->potential_jump;
}

static int accumulate_sample(void *context, const gb_run_sample *s)
{
    gb_scan_accumulate(context, s->t, s->o->omega, s->o->height, s->o->grid_switches + s->o->branch_switches);
    gb_scan_accumulate_mode(context, s->t, s->o->contacts, s->o->sliding, s->o->friction_work);
    return GB_OK;
}

static int accumulate_impact(void *context, const gb_dynamics_impact *e)
{
    gb_scan_accumulate_impact(context, e);
    return GB_OK;
}

/* The mechanism's metrics (GB_SCAN_CONTACTS) from the accumulator, over `periods` forcing periods from the
 * transient on. */
static void mode_metrics(const gb_scan_accumulator *a, double periods, int end_contacts, gb_scan_metrics *m)
{
    const double n = (double)a->samples;
    if (!a->samples) return;
    m->one_point = (double)a->on_plane[1] / n, m->two_point = (double)a->on_plane[2] / n;
    m->at_rest = (double)a->on_plane[3] / n, m->in_flight = (double)a->on_plane[0] / n;
    m->sliding = (double)a->slipping / n;
    m->impacts_per_period = (double)a->impacts / periods, m->landings_per_period = (double)a->landings / periods;
    m->energy_lost_per_period = (a->impact_loss - (a->friction_last - a->friction_start)) / periods; /* friction's work <= 0 */
    m->end_contacts = end_contacts;
}

int gb_scan_point_run(const gb_scan *scan, size_t index, gb_scan_metrics *out)
{
    return gb_scan_point_run_in(scan, NULL, index, NULL, out);
}

int gb_scan_point_run_in(const gb_scan *scan, const gb_scan_melnikov *melnikov, size_t index, gb_dynamics_context *context,
                         gb_scan_metrics *out)
{
    gb_case scene;
    int status = gb_scan_point_case(scan, index, &scene);
    if (status) return status;
    gb_scan_metrics m = {.omega_rms = NAN, .switch_rate = NAN, .mean_height = NAN, .lambda = NAN, .lambda_error = NAN,
                         .strobe_sd = NAN, .geff_nonpositive = NAN, .lift_off = NAN, .lambda_early = NAN,
                         .lambda_late = NAN, .chaos_lifetime = NAN, .melnikov_margin = NAN, .melnikov_margin_eq93 = NAN,
                         .one_point = NAN, .two_point = NAN, .at_rest = NAN, .in_flight = NAN, .sliding = NAN,
                         .impacts_per_period = NAN, .landings_per_period = NAN, .energy_lost_per_period = NAN,
                         .end_contacts = NAN, .stepped = NAN};
    gb_scan_coordinates(scan, index, &m.x, &m.y);
    if (scan->metrics & GB_SCAN_MELNIKOV) {
        status = melnikov ? gb_scan_melnikov_planned(melnikov, &scene, &m.melnikov_margin, &m.melnikov_margin_eq93)
                          : gb_scan_melnikov_margins(&scene, &m.melnikov_margin, &m.melnikov_margin_eq93);
        if (status) return status;
    }
    if (!(scan->metrics & ~(unsigned)GB_SCAN_MELNIKOV)) { /* margins alone: no dynamics */
        *out = m;
        return GB_OK;
    }
    const double T = gb_forcing_period(&scene.dynamics.forcing);
    const double step = gb_forcing_step(&scene.dynamics.forcing, scene.integrate.steps_per_period);
    /* Samples from the first one at the end of the transient (half a step of slack for rounding). */
    gb_scan_accumulator acc = {.first_t = (double)scan->transient_periods * T - 0.5 * step};
    const gb_dynamics_law *law = gb_dynamics_law_of(scene.dynamics.contact_law, scene.dynamics.friction);
    const int modes = (scan->metrics & GB_SCAN_CONTACTS) && law && law->impacts; /* the impacts' mode accounting */
    const gb_run_sinks sinks = {accumulate_sample, &acc, modes ? accumulate_impact : NULL};
    gb_run_result r;
    status = gb_run_in(&scene, context, &sinks, &r);
    if (status) return status;
    double rms, height, rate;
    gb_scan_accumulated(&acc, &rms, &height, &rate);
    m.omega_rms = scan->metrics & GB_SCAN_OMEGA_RMS ? rms : NAN;
    m.mean_height = scan->metrics & GB_SCAN_MEAN_HEIGHT ? height : NAN;
    m.switch_rate = scan->metrics & GB_SCAN_SWITCH_RATE ? rate : NAN;
    if (r.has_strobe && r.strobe.count) {
        double mean[3], sd[3];
        gb_strobe_spread(r.strobe.x, r.strobe.count, 3, mean, sd);
        m.strobe_sd = sd[0];
    }
    if (r.has_monitors) {
        m.geff_nonpositive = (double)r.monitors.geff_nonpositive / (double)r.samples;
        m.lift_off = (double)r.monitors.lift_off / (double)r.samples;
    }
    if (r.has_lyapunov) {
        const gb_lyapunov_result *l = &r.lyapunov;
        m.lambda = l->lambda_max, m.lambda_error = l->error_bar;
        const size_t half = l->intervals / 2;
        double early = 0.0, late = 0.0;
        for (size_t k = 0; k < l->intervals; k++) {
            if (k < half) early += l->instantaneous[k];
            else late += l->instantaneous[k];
        }
        m.lambda_early = early / (double)half, m.lambda_late = late / (double)(l->intervals - half);
        m.chaos_lifetime = gb_scan_chaos_lifetime(l->instantaneous, l->intervals,
                                                  l->interval * scene.dynamics.forcing.omega / (2.0 * M_PI));
    }
    if (modes) mode_metrics(&acc, scene.integrate.periods - (double)scan->transient_periods, r.final.contacts, &m);
    m.stepped = r.stats.steps ? (double)r.stats.stepped_steps / (double)r.stats.steps : 0.0;
    m.certificate_undecided = r.has_certificate ? r.certificate.undecided : 0;
    m.state_fingerprint = r.state_fingerprint;
    m.switch_fingerprint = r.switch_fingerprint;
    gb_run_result_free(&r);
    *out = m;
    return GB_OK;
}

double gb_scan_chaos_lifetime(const double *lambda, size_t n, double periods_per_interval)
{
    const size_t window = n / 12;
    if (window < 20) return NAN;
    double mean[12];
    const size_t count = gb_lyapunov_windows(lambda, 12 * window, window, mean);
    const double windows = gb_lyapunov_lifetime(mean, count, 1.0); /* in windows */
    return isinf(windows) ? windows : windows * (double)window * periods_per_interval;
}
