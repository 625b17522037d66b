/* gb_lyapunov — the maximal Lyapunov exponent (paper §6, eqs 75–77), by two estimators that share no
 * code path beyond the statistics:
 *
 *  - gb_lyapunov_pair: two nearby trajectories, the second put back at distance δ₀ along the current
 *    separation after every interval τ (eq 77): λ_inst,n = ln(δ_n/δ₀)/τ, λ_max = mean of λ_inst.
 *  - gb_lyapunov_tangent: tangent vectors carried by the variational equation (eq 75) or the map's
 *    Jacobian, re-orthonormalised (modified Gram–Schmidt) after every interval (Benettin et al.); with
 *    k vectors it returns the k largest exponents, whose sum is the mean log-volume growth.
 *
 * Both work on any system through a small table of callbacks, so the same estimator is checked on maps
 * and flows whose exponents are known (logistic, Hénon, Lorenz, Ueda) before it is used on a Gömböc.
 *
 * Statistics. The error bar is the standard error of the mean by batch means: the record of λ_inst is
 * cut into `batches` equal consecutive batches, and error = sd(batch means)/√batches. The running
 * estimate is "converged" when, over the last quarter of the record, it stays within a band of
 * width 2·error (the band, `late_drift`, is reported either way). */
#ifndef GB_LYAPUNOV_H
#define GB_LYAPUNOV_H

#include "gb_dynamics.h"
#include "gb_integrate.h"

#include <stddef.h>

typedef struct gb_lyapunov_def {
    double delta0;          /* pair: the separation restored after every interval (Table 1: 1e-7) */
    double interval;        /* τ: time between renormalisations (1 for a map; T for a forced flow) */
    size_t intervals;       /* N: the record length in intervals (after the transient) */
    size_t transient;       /* intervals the reference runs alone before the record starts */
    size_t batches;         /* batch means for the error bar (default 10; 2 <= batches <= N) */
} gb_lyapunov_def;

gb_lyapunov_def gb_lyapunov_default_def(void);

/* Two trajectories (0: reference, 1: perturbed) of a system whose separation lives in a
 * `dimension`-dimensional tangent space. */
typedef struct gb_lyapunov_pair_system {
    size_t dimension;
    /* Advance trajectory `which` from time t by `interval`. */
    int (*advance)(void *context, int which, double t, double interval);
    /* The separation of trajectory 1 from trajectory 0, as a tangent vector e[dimension]. */
    int (*separation)(void *context, double *e);
    /* Place trajectory 1 at trajectory 0 displaced by the tangent vector e. */
    int (*place)(void *context, const double *e);
} gb_lyapunov_pair_system;

/* A reference trajectory and k tangent vectors (row-major k × dimension). */
typedef struct gb_lyapunov_tangent_system {
    size_t dimension;
    /* Advance the reference from t by `interval` (the transient). */
    int (*advance)(void *context, double t, double interval);
    /* Advance the reference and the k tangent vectors together from t by `interval`. */
    int (*advance_tangent)(void *context, double t, double interval, size_t k, double *vectors);
} gb_lyapunov_tangent_system;

#define GB_LYAPUNOV_MAX_EXPONENTS 8

typedef struct gb_lyapunov_result {
    size_t count;                                /* exponents estimated (1 for the pair) */
    double exponent[GB_LYAPUNOV_MAX_EXPONENTS];  /* λ₁ ≥ λ₂ ≥ … per unit time */
    double lambda_max;                           /* exponent[0] */
    double error_bar;                            /* batch-means standard error of λ_max */
    double late_drift;                           /* max − min of the running λ_max over the last quarter */
    int converged;                               /* late_drift ≤ 2·error_bar */
    size_t intervals;
    double interval, delta0;                     /* as run (delta0 = 0 for the tangent estimator) */
    double *instantaneous;                       /* λ_inst per interval [intervals], owned */
    double *running;                             /* running mean of λ_inst [intervals], owned */
} gb_lyapunov_result;

void gb_lyapunov_result_free(gb_lyapunov_result *result);

/* The pair estimator (eq 77). After `transient` intervals of the reference alone, trajectory 1 is
 * placed at δ₀ along `direction` (a vector of `dimension`, normalised here; NULL for (1, 1, …, 1)) and
 * put back at δ₀ along the separation after every interval. GB_ENUMERIC when the separation becomes
 * zero or non-finite. */
int gb_lyapunov_pair(const gb_lyapunov_pair_system *system, void *context, const gb_lyapunov_def *def,
                     double t0, const double *direction, gb_lyapunov_result *out);

/* The tangent estimator with k vectors (1 <= k <= min(dimension, GB_LYAPUNOV_MAX_EXPONENTS)), started
 * from the first k unit vectors. */
int gb_lyapunov_tangent(const gb_lyapunov_tangent_system *system, void *context, const gb_lyapunov_def *def,
                        double t0, size_t k, gb_lyapunov_result *out);

/* Batch-means mean and standard error of x[0..n); the convergence band of its running mean. */
void gb_lyapunov_statistics(const double *x, size_t n, size_t batches, double *mean, double *error_bar,
                            double *late_drift);

/* A Gömböc as a pair system (eq 77): two copies of the dynamics, each a resumable integration
 * (gb_integrate_session) with `integrate` that starts at t = 0; the pair advances them interval by
 * interval, and the reference takes exactly the steps of one plain run of the scene. The separation is a 6-vector: the rotation vector δθ that turns the
 * reference attitude into the perturbed one (body frame, rad), and (ω₂ − ω₁)/Ω with Ω =
 * omega_scale [rad/s] (the paper gives no norm; the forcing frequency makes both parts
 * dimensionless, and the exponent does not depend on the choice). After each placement the
 * perturbed copy takes over the reference's contact (gb_dynamics_adopt_contact). */
typedef struct gb_lyapunov_body gb_lyapunov_body;

int gb_lyapunov_body_create(const char *morphology, double beta, const gb_dynamics_def *dynamics,
                            const gb_integrate_def *integrate, const double R0[9], const double omega0[3],
                            double omega_scale, gb_lyapunov_body **out);
void gb_lyapunov_body_free(gb_lyapunov_body *body);
gb_lyapunov_pair_system gb_lyapunov_body_pair(void);
/* The reference copy's dynamics and state (for its observables). */
gb_dynamics *gb_lyapunov_body_dynamics(gb_lyapunov_body *body);
const double *gb_lyapunov_body_state(const gb_lyapunov_body *body);
/* The step statistics of trajectory `which` (0: reference, 1: perturbed). */
const gb_integrate_stats *gb_lyapunov_body_stats(const gb_lyapunov_body *body, int which);
/* Deliver the reference's samples (every sample_every steps, as gb_integrate_run does; the sample at
 * t = 0 is the caller's) to `sample`. A sampler that asks to stop ends the estimate with an error. */
void gb_lyapunov_body_observe(gb_lyapunov_body *body, gb_integrate_sample sample, void *context);

/* The same body for the tangent estimator (eq 75): the reference stepped by RK4 (steps_per_period of
 * its integrate definition) together with k tangent vectors in the coordinates of the pair's
 * separation, e = (δθ, δω/Ω). Per step, the vectors obey the RK4 discretisation of Ẏ = A(t) Y, with A·Y by
 * central differences of the vector field (the contact re-solved at both points) and the radial part
 * of δq projected out. A branch switch is located inside its step (Δh = 0, eq 39), and the vectors
 * cross it with the saltation matrix S = I + (f⁺ − f⁻)∇gᵀ/(∇g·f⁻), g = Δh. Continuous contact and RK4
 * only (gb_lyapunov_body_tangent_ready says why not); a body serves one estimator, not both. */
gb_lyapunov_tangent_system gb_lyapunov_body_tangent(void);
int gb_lyapunov_body_tangent_ready(const gb_lyapunov_body *body);
/* Switches crossed with a saltation; switches the accepted step's global check found that were not
 * located inside a step (no saltation applied); located switches grazing the flow (∇g·f⁻ = 0). */
void gb_lyapunov_body_tangent_counts(const gb_lyapunov_body *body, size_t *saltations, size_t *unlocated,
                                     size_t *grazing);
/* Of the located switches, those with no sign change of Δh inside the step (a branch born or lost in a
 * fold): the saltation formula assumes a crossing Δh = 0 and is only approximate there. */
size_t gb_lyapunov_body_tangent_jumps(const gb_lyapunov_body *body);

#endif
