#include "gb_nondim.h"

#include "gb_error.h"

int gb_nondim_groups(const gb_dynamics_def *def, double L, gb_nondim *out)
{
    if (!(def->forcing.g > 0.0))
        return gb_error_set(GB_EDOM, "g = %g: the amplitudes A_i = a_i/g (eq 61) need g > 0", def->forcing.g);
    if (!(L > 0.0)) return gb_error_set(GB_EDOM, "mean radius L = %g is out of range (allowed: > 0)", L);
    const double m = def->mass, w = def->forcing.omega;
    out->L = L;
    out->omega = w;
    out->gamma = def->damping / (m * L * L * w);     /* eq 59 */
    out->kappa = def->forcing.g / (L * w * w);       /* eq 60 */
    out->A1 = def->forcing.a1 / def->forcing.g;      /* eq 61 */
    out->A2 = def->forcing.a2 / def->forcing.g;
    out->psi = def->forcing.psi;
    out->energy_scale = m * L * L * w * w;
    return GB_OK;
}

gb_dynamics_def gb_nondim_scaled_def(const gb_dynamics_def *def, const gb_nondim *g)
{
    gb_dynamics_def s = *def;
    s.mass = 1.0;
    s.length = def->length / g->L;
    s.damping = g->gamma;
    s.forcing.g = g->kappa;
    s.forcing.a1 = g->kappa * g->A1;
    s.forcing.a2 = g->kappa * g->A2;
    s.forcing.omega = 1.0;
    s.forcing.psi = g->psi;
    return s;
}
