/* gb_melnikov internals for the harness (verify/s7_melnikov.c): not installed. */
#ifndef GB_MELNIKOV_INTERNAL_H
#define GB_MELNIKOV_INTERNAL_H

#include "gb_melnikov.h"

/* gb_melnikov_integrals_compute with every oscillating integral taken in pieces of a few periods at
 * once: what it falls back to where one adaptive quadrature cannot resolve the oscillations (ω of
 * thousands of rad/s). The check compares the two where both succeed. */
int gb_melnikov_integrals_in_pieces(const gb_melnikov_model *model, const gb_melnikov_orbit *orbit, double omega,
                                    gb_melnikov_weight weight, gb_melnikov_integrals *out);

#endif
