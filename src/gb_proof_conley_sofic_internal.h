/* gb_proof_conley_sofic_internal — Q's regions, the sofic graph of the index map's blocks and its entropy
 * (gb_proof_conley_sofic.c), for gb_proof_conley.c. Not installed, not exported. */
#ifndef GB_PROOF_CONLEY_SOFIC_INTERNAL_H
#define GB_PROOF_CONLEY_SOFIC_INTERNAL_H

#include "gb_proof_conley_grid_internal.h"

/* What the sofic graph gives (gb_proof_conley_result's fields of the same names). */
typedef struct conley_sofic {
    long regions, regions_used, symbols, transitions, component;
    double rho, entropy;
    int capped;
} conley_sofic;

/* GB_ENOMEM, or GB_OK with out filled. */
int conley_sofic_entropy(const conley_grid *g, const conley_homology *h, long precision, int region_dimension,
                         conley_sofic *out);

#endif
