/* gb_proof_body_arcs_internal — the cells' coefficients as the reduced field's integration asks for them
 * (gb_proof_body_arcs.c). Not exported. */
#ifndef GB_PROOF_BODY_ARCS_INTERNAL_H
#define GB_PROOF_BODY_ARCS_INTERNAL_H

#include "gb_proof_body.h"

/* H_0 … H_order over [q_lo, q_hi] as the hull of the cells' that cover it, into H: 1 when served, 0 when not (no table,
 * another definition, an order above the table's, more than 64 cells, an order above 2 on fewer than 4 cells, or a cell
 * refused): the caller then encloses the arc itself. */
int gb_proof_body_arcs_jet(gb_proof_body_arcs *arcs, const gb_proof_body_def *def, double q_lo, double q_hi, int order,
                           gb_proof_interval *H);

#endif
