/* gb_proof_body_ties — the piecewise structure of H on one cell of q, proved from the cell's kept boxes
 * (gb_proof_body_ties.c says how). Internal to the library. */
#ifndef GB_PROOF_BODY_TIES_INTERNAL_H
#define GB_PROOF_BODY_TIES_INTERNAL_H

#include "gb_proof_body_boxes_internal.h"

typedef enum gb_proof_body_piece {
    GB_PROOF_BODY_SMOOTH = 0, /* one contact, C² in q: one component of boxes on which x·v is strictly concave */
    GB_PROOF_BODY_TIE = 1,    /* two such components whose heights' difference is strictly monotone: at most one tie */
    GB_PROOF_BODY_OPEN = 2    /* neither proved */
} gb_proof_body_piece;

/* A component's region and hull {a_lo, a_hi, b_lo, b_hi} in its chart, where x·v is proved strictly concave. */
typedef struct gb_proof_body_hull {
    int region;
    double box[4];
} gb_proof_body_hull;

/* The piece the arc [q_lo, q_hi] is; when hulls is not NULL also the components' hulls (one for SMOOTH, where the
 * maximiser lies for every q of the arc; two for TIE, each holding the maximiser where its branch is the higher). */
gb_proof_body_piece gb_proof_body_structure(const gb_surface *surface, const gb_proof_axes *axes, const boxes *kept,
                                            double q_lo, double q_hi, gb_proof_body_hull hulls[2]);

#endif
