/* gb_proof_conley — the discrete Conley index of a quadratic map f of the plane on a grid of boxes, over Z2, and the
 * lower bound of topological entropy its index map proves.
 *
 * The grid: 2^depth × 2^depth closed boxes over a rectangle. F(b), for a box b, is every box that touches Arb's
 * enclosure of f(b); so f(x) lies in a box of F(b) for every x of b, and a box holding f(x) is one of F(b).
 * (P1, P0), unions of boxes with P0 ⊂ P1, is an index pair when (checked box by box, so that they hold of f):
 *   (positive invariance) f(P0) ∩ P1 ⊂ P0: no box of F(P0) lies in P1 ∖ P0;
 *   (exit set) cl(f(P1) ∖ P1) ∩ P1 ⊂ P0: every cell a box of E = F(P1) ∖ P1 shares with a box of P1 is a face of a
 *     box of P0;
 *   (isolation) Inv(cl(P1 ∖ P0)) ⊂ int(P1 ∖ P0): every box on a bi-infinite path of F inside Q = P1 ∖ P0 has its
 *     eight neighbours in Q.
 * The index map on H_1(P1, P0; Z2) (gb_proof_conley_homology.c) is f_* followed by the inverse of the inclusion
 * (P1, P0) ⊂ (P1 ∪ E, P0 ∪ E), an isomorphism by the exit condition (Robbin and Salamon 1988; Mrozek 1990).
 *
 * Regions: the components of Q (boxes touching at a corner are one component), so their closures are disjoint; H_1
 * splits over them and the index map into blocks f_ji. The theorem (Szymczak 1995, Fund. Math. 148, the Conley index
 * of a decomposition; used by Day, Frongillo and Treviño 2008, SIAM J. Appl. Dyn. Syst. 7): if the product of the
 * blocks along a cyclic word w of regions is not nilpotent, some orbit of f visits the regions in the order of w
 * forever. The symbolic system: the graph on pairs (region i, non-zero v ∈ H_1 of region i), an edge to (j, f_ji v)
 * when that is not zero, labelled j (grown breadth first from every class of the small regions and the generators
 * of the others: a subgraph, whose cycles are the graph's); a cycle through (i, v) with label w has product P with
 * P v = v, so P is not nilpotent. Its edges' labels form a sofic shift with a right-resolving presentation, whose
 * entropy is ln ρ of the graph's adjacency (Lind and Marcus, Thm 4.3.3); within one strongly connected component its
 * periodic points are dense, each is the label of a cycle, so (compactness) every sequence of the component is
 * followed by an orbit, and coding an orbit by its regions maps the orbits followed onto the shift: h_top(f) ≥ ln ρ,
 * ρ bounded below by Collatz–Wielandt's min (A v)_i / v_i on Arb for a positive v (power iteration in doubles). Only
 * H_1 is used (a product not nilpotent on H_1 is not nilpotent on H_*). */
#ifndef GB_PROOF_CONLEY_H
#define GB_PROOF_CONLEY_H

#include "gb_export.h"
#include "gb_proof.h"
#include "gb_proof_flow.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

enum {
    GB_PROOF_CONLEY_DEPTH_MIN = 2,
    GB_PROOF_CONLEY_DEPTH_MAX = 14,
    GB_PROOF_CONLEY_REGION_DIMENSION_MAX = 12,
    GB_PROOF_CONLEY_PERIOD_MAX = 16
};

typedef struct gb_proof_conley_def {
    const gb_proof_field *map; /* the map of the plane (dimension 2) */
    long precision;            /* Arb's bits */
    gb_proof_interval x, y;    /* the grid's rectangle: each side's length a power of two, its lower end a multiple
                                     of the boxes' side */
    int depth;                 /* 2^depth boxes a side: 2 ... 14 (a byte a box of the grid: 256 MiB at 14, mapped
                                     lazily) */
    size_t p1_count, p0_count; /* the boxes, numbered j 2^depth + i, strictly increasing; none on the grid's edge */
    const uint32_t *p1, *p0;   /* P0 ⊂ P1 */
    int region_dimension;      /* regions with at most this many generators start the sofic graph with every class,
                                  the others with their generators alone: 1 ... 12 */
} gb_proof_conley_def;

typedef struct gb_proof_conley_result {
    int positively_invariant, exit_set, isolated; /* each proved */
    int index_pair;                               /* all three */
    long h0, h1, h2;                              /* dimensions of H_*(P1, P0; Z2) */
    long regions, regions_used;                   /* Q's components; those with 1 ... region_dimension generators */
    int capped;                                   /* the sofic graph reached its most vertices (2^20): edges to more
                                                     were left out, which can only lower the bound */
    long invariant_boxes;                         /* boxes on bi-infinite paths of F inside Q */
    long symbols, transitions;                    /* the sofic graph's vertices and edges */
    long component;                               /* the vertices of its component with the largest ρ */
    double rho;                                   /* a proved lower bound of that ρ (0 when none exceeds 1) */
    double entropy;                               /* ln rho, rounded down: h_top(f) ≥ entropy */
    char failure[200];                            /* the first condition that failed, or "" */
    double seconds;
} gb_proof_conley_result;

/* Default: precision 128, depth 6, region dimension 6; the caller fills the map, the rectangle and the pair. */
GB_API gb_proof_conley_def gb_proof_conley_def_default(void);

/* GB_EDOM for a definition out of range (named with its range); GB_ENUMERIC when an enclosure is not finite or the
 * homology's decomposition fails. GB_OK otherwise: out says which conditions hold and, when all do, the bound. */
GB_API int gb_proof_conley(const gb_proof_conley_def *def, gb_proof_conley_result *out);

/* An index pair from a set N of boxes (n, strictly increasing, none on the grid's edge), with the grid and map of def
 * (its pair ignored): S the boxes on bi-infinite paths of F inside N, K = S and its neighbours, P1 the boxes reached
 * from K along F inside N, P0 those of P1 from which no path inside N reaches K. *p1 and *p0 are allocated (free()).
 * GB_EDOM as gb_proof_conley; GB_ENOCONV when a neighbour of S lies outside N (N does not isolate S). */
GB_API int gb_proof_conley_pair(const gb_proof_conley_def *def, const uint32_t *n_boxes, size_t n, uint32_t **p1,
                                size_t *p1_count, uint32_t **p0, size_t *p0_count);

/* An isolating neighbourhood grown from seed boxes (strictly increasing, none on the grid's edge): N starts as the
 * seeds, and the neighbours of S and of Q = P1 ∖ P0 (gb_proof_conley_pair's construction) that lie outside N are
 * added until none does; so the pair built on N has its invariant part isolated and Q inside N's interior (E lies
 * beyond N, so the exit condition holds). *n_boxes is allocated (free()). GB_EDOM as gb_proof_conley (and max_boxes
 * below the seeds' number); GB_ENOCONV when N reaches the grid's edge or passes max_boxes boxes. */
GB_API int gb_proof_conley_isolate(const gb_proof_conley_def *def, const uint32_t *seeds, size_t count,
                                   size_t max_boxes, uint32_t **n_boxes, size_t *n);

/* Hénon's map at a = 6, b = 0.3 (Devaney and Nitecki's full horseshoe: h_top = ln 2) on [−1, 1]² at `depth` (2 ... 14),
 * and N every box off the grid's edge (*n_boxes allocated: free()). */
GB_API int gb_proof_conley_henon_horseshoe(int depth, gb_proof_field *field, gb_proof_conley_def *def,
                                           uint32_t **n_boxes, size_t *n);

/* The classical Hénon map (a = 7/5, b = 3/10) on [−2, 2] × [−1, 1] at `depth`, region_dimension 12, and seeds: the
 * boxes of its periodic points of least period 1 ... period_max (≤ GB_PROOF_CONLEY_PERIOD_MAX, 16), found by Newton on
 * doubles from 4000 points of one orbit (every 7th after 1000 iterates from (0.1, 0.1)); they only place N
 * (gb_proof_conley_isolate), nothing proved rests on them. *seeds allocated (free()). */
GB_API int gb_proof_conley_henon_classical(int period_max, int depth, gb_proof_field *field, gb_proof_conley_def *def,
                                           uint32_t **seeds, size_t *count);

/* A periodic orbit of the classical Hénon map, named by its least period and the least x of its points. */
typedef struct gb_proof_conley_orbit {
    int period;
    double x;
} gb_proof_conley_orbit;

/* As gb_proof_conley_henon_classical, with the orbits kept changed orbit by orbit: each orbit named in toggle (least
 * period 1 ... 16, least x within 1e-6) is left out when its period is at most period_max and kept when it is longer.
 * GB_EDOM when a named orbit is not exactly one of the orbits found (with the name, its period and x). The 1e-6: two
 * orbits of one period up to 16 differ in least x by 5.2e-5 at the least (two of period 16), and x printed to 9
 * decimals is within 5e-10 of the orbit's. */
GB_API int gb_proof_conley_henon_orbits(int period_max, const gb_proof_conley_orbit *toggle, size_t toggles, int depth,
                                        gb_proof_field *field, gb_proof_conley_def *def, uint32_t **seeds,
                                        size_t *count);

#ifdef __cplusplus
}
#endif

#endif
