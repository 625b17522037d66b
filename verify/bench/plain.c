/* The plain loop over every node, written the way a careful user would write it for speed, and kept
 * apart from the library so that it is its own code path: the nodes as three aligned arrays; the lowest
 * height as a vectorised min-reduction (OpenMP simd, so that the compiler may reorder the comparisons of
 * a reduction it otherwise must keep in order); then the first node with that height, a second pass that
 * stops there (ties to the lowest index, as brute force). make bench builds this file with
 * -O3 -march=native -fopenmp-simd and prints its time beside the library's own loop (an array of
 * structures with a branch per node) built the same way.
 *
 * The height is d0 x + d1 y + d2 z, summed in that order and without fused multiply-adds
 * (-ffp-contract=off), as the library's node_height: both loops compute the same doubles and so return
 * the same node, which make bench checks. */
#include "plain.h"

#include <math.h>
#include <stdlib.h>

int plain_grid_create(const gb_contact_grid *grid, plain_grid *out)
{
    const size_t n = gb_contact_grid_size(grid), bytes = (n * sizeof(double) + 63) / 64 * 64;
    out->n = n;
    out->x = aligned_alloc(64, bytes), out->y = aligned_alloc(64, bytes), out->z = aligned_alloc(64, bytes);
    if (!out->x || !out->y || !out->z) {
        plain_grid_free(out);
        return 1;
    }
    for (size_t k = 0; k < n; k++) {
        double p[3];
        gb_contact_grid_node(grid, k, NULL, NULL, p);
        out->x[k] = p[0], out->y[k] = p[1], out->z[k] = p[2];
    }
    return 0;
}

void plain_grid_free(plain_grid *grid)
{
    free(grid->x), free(grid->y), free(grid->z);
    grid->x = grid->y = grid->z = NULL;
}

size_t plain_lowest(void *context, const double d[3])
{
    const plain_grid *g = context;
    const double *restrict x = g->x, *restrict y = g->y, *restrict z = g->z;
    const double d0 = d[0], d1 = d[1], d2 = d[2];
    const size_t n = g->n;
    double lowest = INFINITY;
#pragma omp simd reduction(min : lowest) aligned(x, y, z : 64)
    for (size_t k = 0; k < n; k++) {
        const double h = d0 * x[k] + d1 * y[k] + d2 * z[k];
        lowest = h < lowest ? h : lowest;
    }
    size_t k = 0;
    while (k < n && d0 * x[k] + d1 * y[k] + d2 * z[k] != lowest) k++;
    return k;
}
