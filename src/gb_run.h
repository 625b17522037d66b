/* gb_run — one scene, run as its case file asks: the trajectory, its validity monitors, the switching
 * rate, the fingerprints, and the diagnostics the scene names (strobe, spectrum, λ). `gomboc run`,
 * `gomboc lyapunov`, the parameter scan and the harness all call it, so a scan point is, bit for bit,
 * the run of the same scene.
 *
 * One path. With λ asked for, the trajectory is the reference of the Lyapunov pair (eq 77), which takes
 * exactly the steps of a plain run (gb_lyapunov_body); otherwise it is a plain run. Either way every
 * sample goes through the same observer, so the monitors, the strobe and the spectrum are the same
 * whether λ is computed or not.
 *
 * A scene computes only what it asks for: the monitors when [diagnostics] monitors = yes, the strobe,
 * the spectrum and λ when asked; the caller receives the samples (for a history file) only through
 * `sinks`. */
#ifndef GB_RUN_H
#define GB_RUN_H

#include "gb_export.h"

#include "gb_case.h"
#include "gb_certify.h"
#include "gb_spectrum.h"
#include "gb_strobe.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* One sample of the run, as the observer saw it. */
typedef struct gb_run_sample {
    double t;
    const double *y;                      /* the state [GB_STATE_SIZE] */
    const gb_dynamics_observables *o;
    int grid_switch, branch_switch;       /* a switch since the previous sample */
    double switch_rate;                   /* switches in the trailing forcing period, per second */
} gb_run_sample;

typedef struct gb_run_sinks {
    /* Every sample, t = 0 included (may be NULL). Non-zero stops the run with that gb_ status. */
    int (*sample)(void *context, const gb_run_sample *sample);
    void *context;
    /* Every impact of the unilateral contact law on the reference trajectory, with the same context
     * (may be NULL). */
    gb_dynamics_impact_sink impact;
} gb_run_sinks;

/* The validity monitors of the single-contact model (computed when the scene asks for them). */
typedef struct gb_run_monitors {
    size_t geff_nonpositive, lift_off, friction_over_half; /* samples with g_eff ≤ 0, N ≤ 0, |F_t|/N > 0.5 */
    size_t sliding;                                        /* samples with a point slipping (finite friction) */
    double slip_max;                                       /* the largest slip speed sampled [m/s] */
    double geff_min, normal_min, friction_max;
} gb_run_monitors;

typedef struct gb_run_result {
    double y[GB_STATE_SIZE];             /* the final state */
    double t_end;
    gb_dynamics_observables final;       /* at t_end: switch counts, energy residual, … */
    gb_integrate_stats stats;            /* of the (reference) trajectory */
    gb_integrate_stats pair_stats;       /* of the Lyapunov pair's copy (has_lyapunov) */
    size_t samples;
    double residual_max, orthonormality_max;
    double residual_jump, residual_jump_t; /* the ledger's largest change between two samples [J], and the sample's
                                            * time it ended at [s] (0, NAN: none): where a drifting ledger grew */
    int has_monitors;
    gb_run_monitors monitors;
    int has_certificate;                 /* continuous contact */
    gb_certify_stats certificate;
    int has_atlas;                       /* certificate = atlas */
    gb_atlas_stats atlas;
    size_t atlas_fallbacks;              /* checks the atlas left to the per-vertical certificate */
    int atlas_loaded;                    /* 1: the atlas came from the context's atlas file */
    int has_hull;                        /* contact = fast-grid */
    size_t hull_vertices;                /* the tracker's hull (0: the patch-tree search) */
    int hull_loaded;                     /* 1: the hull came from the context's hull file */
    int massprops_loaded;                /* 1: the mass properties came from the context's cache (the user's) */
    size_t impacts;                      /* the unilateral law: impacts, the kinetic energy they took (L of */
    double impact_energy_lost;           /* the ledger; energy_residual is E − E0 − W + L) and the largest */
    double impact_friction_max;          /* friction coefficient an impact needed */
    int has_sliding;                     /* a plane of finite friction: its sliding over the run */
    gb_dynamics_sliding_summary sliding;
    gb_dynamics_two_point_summary two_point; /* the unilateral law's two-point mode over the run */
    gb_dynamics_flight_summary flight;       /* the unilateral law's flights over the run */
    int has_stepping;                        /* strategy = time-stepping: its steps, problems and energy */
    gb_dynamics_stepping_stats stepping;
    /* Fingerprints (FNV-1a 64): the bytes of the final state; the (sample, contact index, grid and
     * branch switch counts) of every sample with a switch. Equal runs have equal fingerprints. */
    uint64_t state_fingerprint, switch_fingerprint;
    int has_strobe, has_spectrum, has_lyapunov;
    gb_strobe strobe;
    gb_spectrum spectrum;
    size_t spectrum_samples;
    gb_lyapunov_result lyapunov;
    double seconds;                      /* CPU time of the trajectory and λ */
} gb_run_result;

/* Run `scene` (as gb_case_load returned it). The result owns its strobe, spectrum and λ record:
 * gb_run_result_free. On failure nothing is left to free. */
GB_API int gb_run(const gb_case *scene, const gb_run_sinks *sinks, gb_run_result *out);
/* The same in `context` (gb_dynamics_context; NULL: the run's own): the body's set-up and the caches the
 * context holds (its files read when first needed); writing them back is the caller's, by
 * gb_dynamics_context_save. */
GB_API int gb_run_in(const gb_case *scene, gb_dynamics_context *context, const gb_run_sinks *sinks, gb_run_result *out);
GB_API void gb_run_result_free(gb_run_result *result);

#ifdef __cplusplus
}
#endif

#endif
