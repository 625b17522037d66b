/* gb_melnikov internals: what its files share (gb_melnikov.c, gb_melnikov_split.c) and what the harness
 * (verify/s7_melnikov.c) reaches for. Not installed, not exported. */
#ifndef GB_MELNIKOV_INTERNAL_H
#define GB_MELNIKOV_INTERNAL_H

#include "gb_melnikov.h"

/* gb_melnikov_integrals_compute with every oscillating integral taken in pieces of a few periods at
 * once: what it falls back to where one adaptive quadrature cannot resolve the oscillations (ω of
 * thousands of rad/s). The check compares the two where both succeed. */
int gb_melnikov_integrals_in_pieces(const gb_melnikov_model *model, const gb_melnikov_orbit *orbit, double omega,
                                    gb_melnikov_weight weight, gb_melnikov_integrals *out);

/* The model at q, checked: M > 0 and every value finite (eq 80), else GB_EDOM naming them. */
int gb_melnikov_model_at(const gb_melnikov_model *m, double q, gb_melnikov_values *v);

#endif
