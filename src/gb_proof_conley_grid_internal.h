/* gb_proof_conley_grid_internal — the grid of boxes, F on P1 and the map's homology, as gb_proof_conley.c (the map's
 * boxes, the index pair's conditions), gb_proof_conley_homology.c (H_1(P1, P0; Z2) and the index map) and
 * gb_proof_conley_sofic.c (regions, the sofic graph, its entropy) share them. Not installed, not exported. */
#ifndef GB_PROOF_CONLEY_GRID_INTERNAL_H
#define GB_PROOF_CONLEY_GRID_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

/* What a box of the grid is: in P1, in P0 (⊂ P1), in Q = P1 ∖ P0, in E = F(P1) ∖ P1. */
enum { CONLEY_P1 = 1, CONLEY_P0 = 2, CONLEY_Q = 4, CONLEY_E = 8 };

/* The grid of 2^depth × 2^depth boxes, box (i, j) = [x0 + i hx, x0 + (i + 1) hx] × [y0 + j hy, y0 + (j + 1) hy], its
 * number j n + i; and F on P1: for P1's k-th box, the boxes i0 ≤ i ≤ i1, j0 ≤ j ≤ j1 its image's enclosure touches
 * (−1 and n stand for every box beyond the grid on that side). */
typedef struct conley_grid {
    int depth;
    long n;
    double x0, y0, hx, hy;
    uint8_t *state; /* n² flags */
    size_t p1_count;
    const uint32_t *p1; /* strictly increasing */
    int32_t (*rect)[4]; /* p1_count rectangles: i0, i1, j0, j1 */
} conley_grid;

static inline int conley_is(const conley_grid *g, long i, long j, int flag)
{
    return i >= 0 && j >= 0 && i < g->n && j < g->n && (g->state[j * g->n + i] & flag);
}

/* The position of box `box` in P1 (binary search), or −1. */
static inline long conley_p1_position(const conley_grid *g, uint32_t box)
{
    size_t lo = 0, hi = g->p1_count;
    while (lo < hi) {
        const size_t mid = (lo + hi) / 2;
        if (g->p1[mid] < box)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < g->p1_count && g->p1[lo] == box ? (long)lo : -1;
}

/* The root of x in a union-find forest (up[x] == x at a root), halving the path on the way. */
static inline long conley_root(int32_t *up, long x)
{
    while (up[x] != x) up[x] = up[up[x]], x = up[x];
    return x;
}

/* qsort's order of box numbers. */
static inline int conley_compare_boxes(const void *a, const void *b)
{
    const uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

/* H_*(P1, P0; Z2) of the cubical pair and the index map on H_1 in the basis of its generators (tree–cotree: the
 * edges of the relative complex neither in a spanning forest of its vertices, P0's collapsed to one, nor in a spanning
 * forest of its squares and the outside over the remaining edges). map: generators × words, bit c of row r the r-th
 * coordinate of the image of generator c; square: a box of Q beside each generator's edge. */
typedef struct conley_homology {
    long h0, h1, h2;
    size_t generators, words;
    uint64_t *map;
    int32_t *square; /* the box's number on the grid */
} conley_homology;

#endif
