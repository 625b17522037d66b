/* gb_forcing — the biharmonic vertical excitation of the support (paper §3, eqs 25–26; §6 eq 62).
 *
 * In the frame of the support the body feels the effective gravity
 *   g_eff(t) = g + a₁ cos ωt + a₂ cos(2ωt + ψ)                       (eq 25)
 *   ġ_eff(t) = −a₁ ω sin ωt − 2 a₂ ω sin(2ωt + ψ)                    (eq 26)
 * and g_eff/g = 1 + A₁ cos τ + A₂ cos(2τ + ψ) with A_i = a_i/g, τ = ωt (eqs 61–62). A harmonic whose
 * amplitude is zero is skipped, not evaluated (the harmonic benchmark, eq 94, has a₂ = 0). */
#ifndef GB_FORCING_H
#define GB_FORCING_H

#include "gb_export.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gb_forcing {
    double g;      /* gravitational acceleration [m/s²] (Table 1: 9.81) */
    double a1, a2; /* acceleration amplitudes of the two harmonics [m/s²] */
    double omega;  /* forcing angular frequency [rad/s] (Table 1: 18) */
    double psi;    /* phase of the second harmonic [rad] (Table 1: π/3) */
} gb_forcing;

/* GB_EDOM unless g ≥ 0, ω > 0 and every value is finite. */
GB_API int gb_forcing_validate(const gb_forcing *forcing);

GB_API double gb_forcing_geff(const gb_forcing *forcing, double t);
GB_API double gb_forcing_geff_rate(const gb_forcing *forcing, double t);
/* Both at once, with one sincos a harmonic: the same values as the two calls above. */
GB_API void gb_forcing_geff_with_rate(const gb_forcing *forcing, double t, double *geff, double *rate);

/* The forcing period T = 2π/ω. */
GB_API double gb_forcing_period(const gb_forcing *forcing);
/* The fixed step of a run with `steps_per_period` steps a forcing period: gb_forcing_period / steps_per_period,
 * the one place it is computed (the integrator, the run's observer, a scan's metrics, the settle time). */
GB_API double gb_forcing_step(const gb_forcing *forcing, size_t steps_per_period);

/* The fraction of one period in which g_eff ≤ 0 (the support pulls the body down faster than it can
 * follow: a single-contact model is then invalid), and the smallest g_eff on the samples. Sign
 * changes are bracketed on 4096 samples and refined by bisection to 1e-14 of the period. */
GB_API int gb_forcing_nonpositive_fraction(const gb_forcing *forcing, double *fraction, double *geff_min);

#ifdef __cplusplus
}
#endif

#endif
