/* gb_melnikov internals: what its files share (gb_melnikov.c, gb_melnikov_split.c, gb_melnikov_tangle.c) and what the harness
 * (verify/s7_melnikov.c) reaches for. Not installed, not exported. */
#ifndef GB_MELNIKOV_INTERNAL_H
#define GB_MELNIKOV_INTERNAL_H

#include "gb_melnikov.h"

/* gb_melnikov_integrals_compute with every oscillating integral taken in pieces of a few periods at
 * once: what it falls back to where one adaptive quadrature cannot resolve the oscillations (ω of
 * thousands of rad/s). The check compares the two where both succeed. */
int gb_melnikov_integrals_in_pieces(const gb_melnikov_model *model, const gb_melnikov_orbit *orbit, double omega,
                                    gb_melnikov_weight weight, gb_melnikov_integrals *out);

/* The perturbed system (eq 84) with its perturbation εG (eq 85) at scale ε; damping alone is ν₁ = ν₂ = 0.
 * What the direct splitting (gb_melnikov_split.c) and the tangle (gb_melnikov_tangle.c) integrate; `status`
 * keeps the model's first failure. */
typedef struct gb_melnikov_forced {
    const gb_melnikov_model *m;
    const gb_melnikov_forcing *f;
    double epsilon;
    int status;
} gb_melnikov_forced;

/* Its right-hand side in GSL's form (y = (q, p)). */
int gb_melnikov_forced_rhs(double t, const double y[], double dydt[], void *params);

/* y ← its flow from t_from to t_to (either direction), rk8pd at 1e-13. */
int gb_melnikov_forced_flow(gb_melnikov_forced *F, double t_from, double t_to, double y[2]);

/* The hyperbolic periodic orbit near the saddle q_u at phase t0: a fixed point x of the period map (Newton
 * with a central-difference Jacobian), the map's unstable and stable unit eigenvectors and (if not NULL)
 * its multipliers (unstable, stable). GB_ENUMERIC when the fixed point is not hyperbolic. */
int gb_melnikov_saddle_orbit(gb_melnikov_forced *F, double q_u, double t0, double x[2], double vu[2], double vs[2],
                             double multipliers[2]);

/* The model at q, checked: M > 0 and every value finite (eq 80), else GB_EDOM naming them. */
int gb_melnikov_model_at(const gb_melnikov_model *m, double q, gb_melnikov_values *v);

#endif
