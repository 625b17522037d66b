/* make bench's baseline: the best plain loop a user would write for the paper's contact search (eq 29),
 * in its own translation unit, built with the best flags of this compiler (see plain.c). */
#ifndef BENCH_PLAIN_H
#define BENCH_PLAIN_H

#include "gb_contact.h"

#include <stddef.h>

typedef struct plain_grid {
    size_t n;
    double *x, *y, *z; /* the nodes' coordinates, one array each, 64-byte aligned */
} plain_grid;

/* The nodes of `grid`, laid out for vector loads. 0, or 1 when out of memory. */
int plain_grid_create(const gb_contact_grid *grid, plain_grid *out);
void plain_grid_free(plain_grid *grid);

/* The lowest node for the unit vertical d, ties to the lowest index (a gb_dynamics_lowest_node; the
 * context is a plain_grid). */
size_t plain_lowest(void *context, const double d[3]);

#endif
