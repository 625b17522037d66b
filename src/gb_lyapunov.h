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

#endif
