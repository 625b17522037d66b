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
 * Statistics, chosen from the record. A record of λ_inst starts with the time the perturbation takes
 * to align with the most unstable direction, and a transiently chaotic motion ends with a different
 * rate than it starts with: how much of the record to leave out, and how long the batches of the error
 * bar must be, are read from the record itself rather than fixed in advance.
 *
 *  - Warm-up: MSER-5 (White 1997; Franklin & White 2008). The record is cut into blocks of 5 intervals,
 *    z_j their means (m blocks); the warm-up is 5·d for the d in 0 … ⌊m/2⌋ that minimises
 *    Σ_{j>d} (z_j − z̄_d)² / (m − d)², the squared standard error of what is kept. A minimum at the
 *    last admissible d means the record never settled (`warmup_found` = 0).
 *  - Batches: of what is kept (n intervals), batches of b = 1, 2, 4, … intervals, the first b whose
 *    B = ⌊n/b⌋ batch means have a lag-1 autocorrelation within ±2/√B (the 95 % band of uncorrelated
 *    means), with B ≥ 10; if none, B = 10 and `batches_independent` = 0 (the error bar is then a lower
 *    bound). Batch k holds the kept intervals [k n/B, (k + 1) n/B).
 *  - error = sd(batch means)/√B; late_drift = max − min of the running mean of the kept part over its
 *    last quarter; converged when the warm-up was found, the batches are independent and late_drift ≤
 *    2·error.
 *
 * Either choice may be fixed instead (gb_lyapunov_def.warmup, .batches), as a case file may ask. */
#ifndef GB_LYAPUNOV_H
#define GB_LYAPUNOV_H

#include "gb_export.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gb_lyapunov_def {
    double delta0;          /* pair: the separation restored after every interval (Table 1: 1e-7) */
    double interval;        /* τ: time between renormalisations (1 for a map; T for a forced flow) */
    size_t intervals;       /* N: the record length in intervals (after the transient) */
    size_t transient;       /* intervals the reference runs alone before the record starts */
    size_t warmup;          /* intervals of the record left out of the means (< N/2), or GB_LYAPUNOV_CHOSEN */
    size_t batches;         /* batch means for the error bar (2 <= batches <= N − warmup), or GB_LYAPUNOV_CHOSEN */
} gb_lyapunov_def;

/* A warm-up or a batch count chosen from the record (the default of both). */
#define GB_LYAPUNOV_CHOSEN ((size_t)-1)

GB_API gb_lyapunov_def gb_lyapunov_default_def(void);

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
    double late_drift;                           /* max − min of the kept part's running λ_max, last quarter */
    int converged;                               /* warm-up found, batches independent, late_drift ≤ 2·error_bar */
    size_t warmup;                               /* intervals left out at the start of the record */
    int warmup_found;                            /* MSER's minimum lies inside its range (or fixed) */
    size_t batches;                              /* batches of the error bar */
    double batch_correlation;                    /* lag-1 autocorrelation of the batch means */
    int batches_independent;                     /* |batch_correlation| ≤ 2/√batches */
    double whole_record;                         /* mean of λ_inst over the whole record, warm-up included */
    size_t intervals;
    double interval, delta0;                     /* as run (delta0 = 0 for the tangent estimator) */
    double *instantaneous;                       /* λ_inst per interval [intervals], owned */
    double *running;                             /* running mean of λ_inst [intervals], owned */
} gb_lyapunov_result;

GB_API void gb_lyapunov_result_free(gb_lyapunov_result *result);

/* The pair estimator (eq 77). After `transient` intervals of the reference alone, trajectory 1 is
 * placed at δ₀ along `direction` (a vector of `dimension`, normalised here; NULL for (1, 1, …, 1)) and
 * put back at δ₀ along the separation after every interval. GB_ENUMERIC when the separation becomes
 * zero or non-finite. */
GB_API int gb_lyapunov_pair(const gb_lyapunov_pair_system *system, void *context, const gb_lyapunov_def *def, double t0,
                            const double *direction, gb_lyapunov_result *out);

/* The tangent estimator with k vectors (1 <= k <= min(dimension, GB_LYAPUNOV_MAX_EXPONENTS)), started
 * from the first k unit vectors. */
GB_API int gb_lyapunov_tangent(const gb_lyapunov_tangent_system *system, void *context, const gb_lyapunov_def *def,
                               double t0, size_t k, gb_lyapunov_result *out);

/* The statistics of a record x[0..n) as the estimators compute them: warm-up and batches as `def` asks
 * (chosen from the record by default); fills warmup, warmup_found, batches, batch_correlation,
 * batches_independent, error_bar, late_drift, converged and whole_record of `out`, and puts the mean of
 * the kept part in *mean. GB_EDOM when a fixed warm-up or batch count does not fit n. */
GB_API int gb_lyapunov_statistics(const double *x, size_t n, const gb_lyapunov_def *def, gb_lyapunov_result *out,
                                  double *mean);


/* Windowed exponents: the record λ_inst[0..n) cut into consecutive windows of `per_window` intervals
 * from its start (an incomplete last window is left out), and the mean of each in mean[0..n/per_window).
 * Where the running mean still remembers a chaotic start, the windows show when the chaos ended. Returns
 * the number of windows (0 when per_window is 0 or exceeds n). */
GB_API size_t gb_lyapunov_windows(const double *lambda, size_t n, size_t per_window, double *mean);

/* A window whose mean exponent exceeds this [1/s] counts as chaotic: a separation growing by e^(0.05 t),
 * one e-fold in 20 s (57 forcing periods at Table 1's ω = 18 rad/s). */
#define GB_LYAPUNOV_CHAOTIC 0.05

/* The lifetime of the chaos in `count` window means, each `per_window` long (any unit: the result is
 * in the same): the end of the last chaotic window; 0 when none is, +inf when the last one is (chaotic
 * to the end of the record: censored). */
GB_API double gb_lyapunov_lifetime(const double *mean, size_t count, double per_window);

#ifdef __cplusplus
}
#endif

#endif
