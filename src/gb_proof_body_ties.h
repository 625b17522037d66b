/* gb_proof_body_ties — the piecewise structure of H on one cell of q, proved from the cell's kept boxes
 * (gb_proof_body_ties.c says how). Internal to the library. */
#ifndef GB_PROOF_BODY_TIES_H
#define GB_PROOF_BODY_TIES_H

#include "gb_proof_body_boxes.h"

typedef enum gb_proof_body_piece {
    GB_PROOF_BODY_SMOOTH = 0, /* one contact, C² in q: one component of boxes on which x·v is strictly concave */
    GB_PROOF_BODY_TIE = 1,    /* two such components whose heights' difference is strictly monotone: at most one tie */
    GB_PROOF_BODY_OPEN = 2    /* neither proved */
} gb_proof_body_piece;

/* The piece the arc [q_lo, q_hi] is; for SMOOTH also the one component's region and hull {a_lo, a_hi, b_lo, b_hi} in
 * its chart (where x·v is proved strictly concave and the maximiser lies for every q of the arc), when the pointers
 * are not NULL. */
gb_proof_body_piece gb_proof_body_structure(const gb_surface *surface, const gb_proof_axes *axes, const boxes *kept,
                                            double q_lo, double q_hi, int *hull_region, double hull_box[4]);

#endif
