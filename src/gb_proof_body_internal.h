/* gb_proof_body_internal — what the Gömböcs' enclosure (gb_proof_body.c) shares with the proof of its piecewise
 * structure (gb_proof_body_ties.c): the surface's chart boxes, the run, the directions of an arc. Not exported. */
#ifndef GB_PROOF_BODY_INTERNAL_H
#define GB_PROOF_BODY_INTERNAL_H

#include "gb_proof_body.h"
#include "gb_surface_internal.h"

/* A box of a chart of the surface with its enclosure. */
typedef struct pbox {
    double a_lo, a_hi, b_lo, b_hi;
    int region;
    gb_surface_enclosure e;
} pbox;

typedef struct boxes {
    pbox *at;
    size_t n, cap;
} boxes;

struct gb_proof_body_cells;

typedef struct run {
    const gb_proof_body_def *def;
    double s0[3];
    gb_interval e[3];
    gb_proof_body_model *model;
    struct gb_proof_body_cells *cells;
} run;

/* Σ a_k b_k, outwards. */
gb_interval gb_proof_body_dot(const gb_interval a[3], const gb_interval b[3]);

/* v(Q) = cos Q s₀ − sin Q e and v′(Q) = −sin Q s₀ − cos Q e over the arc [q_lo, q_hi]. */
void gb_proof_body_directions(const run *r, double q_lo, double q_hi, gb_interval v[3], gb_interval dv[3]);

/* What the kept boxes of a cell prove of H on it (gb_proof_body_ties.c). */
typedef enum gb_proof_body_piece {
    GB_PROOF_BODY_SMOOTH = 0, /* one contact, C² in q: one component of boxes on which x·v is strictly concave */
    GB_PROOF_BODY_TIE = 1,    /* two such components whose heights' difference is strictly monotone: at most one tie */
    GB_PROOF_BODY_OPEN = 2    /* neither proved */
} gb_proof_body_piece;

gb_proof_body_piece gb_proof_body_structure(const run *r, const boxes *kept, double q_lo, double q_hi);

#endif
