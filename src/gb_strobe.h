/* gb_strobe — stroboscopic sampling (paper eqs 73–74) and what the paper reads from it (Fig 7, and
 * std(ω_x) of the scans in §8.3).
 *
 * A run delivers samples on its nominal grid t_k = t0 + k·h, h = T/steps_per_period. The strobe keeps
 * the samples at t_n = t0 + (n + phase)·T, n ≥ transient (eq 74 after a stated transient), so the
 * phase must lie on that grid: phase·steps_per_period must be a whole number. The sample at a strobe
 * instant is the state the flow map P (eq 73) carries from one instant to the next. */
#ifndef GB_STROBE_H
#define GB_STROBE_H

#include "gb_export.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gb_strobe_def {
    size_t transient;  /* periods discarded before the first strobe sample */
    double phase;      /* where in the period to sample, in [0, 1) (0: t_n = t0 + nT) */
} gb_strobe_def;

typedef struct gb_strobe {
    size_t dimension;        /* numbers per sample */
    size_t count, capacity;
    double *t;               /* strobe times [count] */
    double *x;               /* samples, row-major [count × dimension] */
    double t0, step;         /* the run's grid */
    size_t steps_per_period, phase_step, first_step;
} gb_strobe;

/* An empty strobe for a run started at t0 with steps_per_period steps per period T. GB_EDOM when the
 * phase is outside [0, 1) or not on the grid. */
GB_API int gb_strobe_init(gb_strobe *strobe, size_t dimension, double t0, double period, size_t steps_per_period,
                          const gb_strobe_def *def);
GB_API void gb_strobe_free(gb_strobe *strobe);

/* Offer the run's sample (t, x[dimension]); kept when t is a strobe instant. *kept (may be NULL) says
 * whether it was. GB_ENOMEM when the record cannot grow. */
GB_API int gb_strobe_offer(gb_strobe *strobe, double t, const double *x, int *kept);

/* The least p in 1..max_period with |x_{n+p} − x_n| ≤ tol for every pair of the last `window` samples
 * (max norm over the components); 0 when there is none: no period up to max_period. */
GB_API size_t gb_strobe_period(const double *x, size_t count, size_t dimension, size_t window, size_t max_period,
                               double tol);

/* Mean and (population) standard deviation of each component. */
GB_API void gb_strobe_spread(const double *x, size_t count, size_t dimension, double *mean, double *sd);

#ifdef __cplusplus
}
#endif

#endif
