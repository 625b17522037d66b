#include "gb_strobe.h"

#include "gb_error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int gb_strobe_init(gb_strobe *s, size_t dimension, double t0, double period, size_t steps_per_period,
                   const gb_strobe_def *def)
{
    memset(s, 0, sizeof *s);
    if (dimension < 1) return gb_error_set(GB_EDOM, "strobe dimension must be >= 1");
    if (!(isfinite(period) && period > 0.0 && steps_per_period >= 1))
        return gb_error_set(GB_EDOM, "strobe period %g with %zu steps is out of range (allowed: period > 0, steps >= 1)",
                            period, steps_per_period);
    if (!(def->phase >= 0.0 && def->phase < 1.0))
        return gb_error_set(GB_EDOM, "strobe phase = %g is out of range (allowed: 0 <= phase < 1)", def->phase);
    const double on_grid = def->phase * (double)steps_per_period;
    if (fabs(on_grid - nearbyint(on_grid)) > 1e-9)
        return gb_error_set(GB_EDOM,
                            "strobe phase = %g is not on the run's grid (allowed: a multiple of 1/%zu, one step)",
                            def->phase, steps_per_period);
    s->dimension = dimension;
    s->t0 = t0;
    s->step = period / (double)steps_per_period;
    s->steps_per_period = steps_per_period;
    s->phase_step = (size_t)nearbyint(on_grid);
    s->first_step = def->transient * steps_per_period + s->phase_step;
    return GB_OK;
}

void gb_strobe_free(gb_strobe *s)
{
    free(s->t);
    free(s->x);
    s->t = s->x = NULL;
    s->count = s->capacity = 0;
}

int gb_strobe_offer(gb_strobe *s, double t, const double *x, int *kept)
{
    if (kept) *kept = 0;
    const double k_real = (t - s->t0) / s->step;
    const double k_round = nearbyint(k_real);
    /* Samples come at grid times; anything else (an adaptive stepper's own time) is not a strobe instant. */
    if (!(k_round >= 0.0) || fabs(k_real - k_round) > 1e-6) return GB_OK;
    const size_t k = (size_t)k_round;
    if (k < s->first_step || (k - s->phase_step) % s->steps_per_period != 0) return GB_OK;
    if (s->count == s->capacity) {
        const size_t capacity = s->capacity ? 2 * s->capacity : 256;
        double *t_new = realloc(s->t, capacity * sizeof *t_new);
        if (!t_new) return gb_error_set(GB_ENOMEM, "out of memory for %zu strobe samples", capacity);
        s->t = t_new;
        double *x_new = realloc(s->x, capacity * s->dimension * sizeof *x_new);
        if (!x_new) return gb_error_set(GB_ENOMEM, "out of memory for %zu strobe samples", capacity);
        s->x = x_new;
        s->capacity = capacity;
    }
    s->t[s->count] = t;
    memcpy(s->x + s->count * s->dimension, x, s->dimension * sizeof *x);
    s->count++;
    if (kept) *kept = 1;
    return GB_OK;
}

size_t gb_strobe_period(const double *x, size_t count, size_t dimension, size_t window, size_t max_period, double tol)
{
    if (window > count) window = count;
    const double *w = x + (count - window) * dimension;
    for (size_t p = 1; p <= max_period && p < window; p++) {
        int periodic = 1;
        for (size_t n = 0; periodic && n + p < window; n++)
            for (size_t j = 0; j < dimension; j++)
                if (!(fabs(w[(n + p) * dimension + j] - w[n * dimension + j]) <= tol)) {
                    periodic = 0;
                    break;
                }
        if (periodic) return p;
    }
    return 0;
}

void gb_strobe_spread(const double *x, size_t count, size_t dimension, double *mean, double *sd)
{
    for (size_t j = 0; j < dimension; j++) {
        double m = 0.0, v = 0.0;
        for (size_t n = 0; n < count; n++) m += x[n * dimension + j];
        m = count ? m / (double)count : NAN;
        for (size_t n = 0; n < count; n++) v += (x[n * dimension + j] - m) * (x[n * dimension + j] - m);
        mean[j] = m;
        sd[j] = count ? sqrt(v / (double)count) : NAN;
    }
}
