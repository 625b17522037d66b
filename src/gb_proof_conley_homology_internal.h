/* gb_proof_conley_homology_internal — H_1(P1, P0; Z2) and the index map on it (gb_proof_conley_homology.c), for
 * gb_proof_conley.c. Not installed, not exported. */
#ifndef GB_PROOF_CONLEY_HOMOLOGY_INTERNAL_H
#define GB_PROOF_CONLEY_HOMOLOGY_INTERNAL_H

#include "gb_proof_conley_grid_internal.h"

/* GB_OK, or GB_ENOMEM; GB_ENUMERIC when the decomposition does not span (the reason in failure). */
int conley_homology_compute(const conley_grid *g, conley_homology *out, char *failure, size_t failure_size);
void conley_homology_free(conley_homology *h);

#endif
