/* gb_nondim — the nondimensional form of paper §6 (eqs 53–65).
 *
 * With L the mean radius (eq 53), time τ = ωt (eq 54), Ω = ω_body/ω (eq 55), P_c = r_c/L (eq 56),
 * J = I/(mL²) (eqs 57–58), the groups are γ = c/(mL²ω) (eq 59), κ = g/(Lω²) (eq 60) and
 * A_i = a_i/g (eq 61), so that g_eff/g = 1 + A₁ cos τ + A₂ cos(2τ + ψ) (eq 62) and the torques scale
 * by mL²ω² (eq 63). The dimensionless problem is the dimensional one with m = 1, lengths in units of
 * L, c = γ, g = κ, a_i = κA_i and ω = 1: gb_nondim_scaled_def builds that definition, so one code
 * path integrates both and the check compares them after rescaling. */
#ifndef GB_NONDIM_H
#define GB_NONDIM_H

#include "gb_export.h"

#include "gb_dynamics.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gb_nondim {
    double L;               /* mean radius [m] (eq 53) */
    double omega;           /* forcing frequency [rad/s]: the time scale is 1/omega */
    double gamma, kappa;    /* eqs 59, 60 */
    double A1, A2, psi;     /* eq 61 and the phase */
    double energy_scale;    /* m L² ω² [J] */
} gb_nondim;

/* The groups of `def` for a body of mean radius L (gb_dynamics_mean_radius). GB_EDOM when g = 0
 * (A_i = a_i/g is then undefined). */
GB_API int gb_nondim_groups(const gb_dynamics_def *def, double L, gb_nondim *out);

/* The dimensionless problem as a gb_dynamics_def (see above). */
GB_API gb_dynamics_def gb_nondim_scaled_def(const gb_dynamics_def *def, const gb_nondim *groups);

#ifdef __cplusplus
}
#endif

#endif
