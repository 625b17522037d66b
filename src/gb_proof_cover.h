/* gb_proof_cover — covering relations of h-sets on a plane, and the lower bound of topological entropy they prove.
 *
 * The map f is either P^k, the k-th return of a quadratic flow in R³ to a plane x[c] = 0 (gb_proof_flow.h), or the
 * k-th iterate of a quadratic map of R² (the field's formula read as a map: Hénon's). On the plane, coordinates u
 * (across: the expanding direction) and s (along: the contracting one). The h-sets are rectangles N_i = U_i × S,
 * with disjoint U_i and one common S.
 *
 * The theorem (Zgliczyński 1997, Nonlinearity 10; Gidea & Zgliczyński 2004, J. Differential Equations 202, Def. 6 and
 * Thm 9): N_i covers N_j (N_i ⇒ N_j) when f is continuous on N_i and
 *   (strip) f(N_i) ⊂ R × int S, and
 *   (edges) f maps the two edges {min U_i} × S and {max U_i} × S to opposite sides beyond U_j
 *           (one wholly below min U_j, the other wholly above max U_j);
 * the straight-line homotopy to (u, s) ↦ (A u, mid S), A affine taking the edges to the same sides, keeps the edges
 * off N_j and the image off S's ends, which is the definition. The strip is proved either directly (f(N_i) on
 * pieces of U_i) or, for a return map, from a trapping rectangle R = U_R × S with P(R) ⊂ int R (then
 * P^k(N_i) ⊂ int R for every N_i ⊂ R). Covering relations with the transition matrix A (A_ij = 1 for N_i ⇒ N_j)
 * give, for every sequence the matrix admits, an orbit of f visiting the sets in that order (Thm 9); the sets
 * being disjoint, f on the invariant part of their union is semiconjugate to the subshift of A, so
 * h_top(f) ≥ ln ρ(A), ρ bounded below by Collatz–Wielandt's min_i (A v)_i / v_i for a positive v, on Arb.
 * Continuity of a return map on N_i: every crossing proved transversal (x'[c] of one sign). */
#ifndef GB_PROOF_COVER_H
#define GB_PROOF_COVER_H

#include "gb_export.h"
#include "gb_proof.h"
#include "gb_proof_flow.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

enum { GB_PROOF_HSETS_MAX = 8 };

typedef enum gb_proof_map_kind {
    GB_PROOF_MAP_RETURN = 0,   /* the k-th return of a flow in R³ to the plane x[section.coordinate] = 0 */
    GB_PROOF_MAP_QUADRATIC = 1 /* the k-th iterate of x ↦ f(x) on R², f a gb_proof_field read as a map */
} gb_proof_map_kind;

typedef struct gb_proof_cover_def {
    gb_proof_map_kind kind;
    gb_proof_flow_def section; /* RETURN: the flow and its plane (its returns field is set from iterates) */
    const gb_proof_field *map;    /* QUADRATIC: the map (dimension 2) */
    long precision;               /* QUADRATIC: Arb's bits */
    int u, s;                     /* the plane's coordinates in the state: u across, s along */
    int iterates;                 /* k: the relations are for f = P^k (or the k-th iterate): 1 ... 16 */
    int trap;                     /* 1: the strip from a trapping rectangle (RETURN only); 0: proved directly */
    gb_proof_interval region_u;   /* trap: R's extent across */
    gb_proof_interval strip;      /* S: every h-set's extent along, and R's */
    size_t sets;                  /* 1 ... 8 */
    gb_proof_interval set_u[GB_PROOF_HSETS_MAX]; /* U_i: disjoint */
    int pieces;                   /* the first cut of a range across: 1 ... 100000 */
    int strip_pieces;             /* the cut of S along, for every piece across and every edge: 1 ... 100000 */
    int halve_along;              /* 1: a piece that fails is halved along as well as across, and an edge's piece whose
                                     image holds an end of an h-set is halved along (to depth); 0: across only */
    int depth;                    /* the most halvings of a piece that does not prove its inclusion: 0 ... 20 */
} gb_proof_cover_def;

typedef struct gb_proof_cover_result {
    int trapped;                                  /* trap: P(R) ⊂ int R proved */
    gb_proof_interval trap_image_u, trap_image_s; /* trap: the hull of P(R)'s enclosures */
    int strip[GB_PROOF_HSETS_MAX];                /* f(N_i) ⊂ R × int S proved (or from the trap) */
    gb_proof_interval image_s[GB_PROOF_HSETS_MAX];/* direct strip: the hull of f(N_i)'s extent along */
    gb_proof_interval edge[GB_PROOF_HSETS_MAX][2];/* f's image of N_i's low and high edges: their extent across */
    int covers[GB_PROOF_HSETS_MAX][GB_PROOF_HSETS_MAX]; /* N_i ⇒ N_j proved */
    double entropy;                               /* a proved lower bound of h_top(f): ln ρ(A) (0 when ρ ≤ 1) */
    double entropy_map;                           /* of the map iterated: h_top(f) / k, k the iterates (rounded down) */
    double rho;                                   /* the Collatz–Wielandt lower bound of ρ(A) */
    long pieces;                                  /* pieces enclosed, after halvings */
    long failed_pieces;                           /* pieces whose inclusion failed at the deepest halving */
    char failure[200];                            /* the first such failure, or "" */
    gb_proof_interval failed_u;                   /* that piece across (NaN when none, or when its map failed) */
    gb_proof_interval failed_image_u, failed_image_s; /* its image's enclosure: wholly outside refutes the inclusion */
    double seconds;
} gb_proof_cover_result;

/* Default: RETURN, iterates 1, no trap, 1 set, 64 pieces, S whole (1 strip piece), halved across only, depth 6; the caller fills the map, the plane and the sets. */
GB_API gb_proof_cover_def gb_proof_cover_def_default(void);

/* GB_EDOM for a definition out of range (named with its range); GB_ENUMERIC when an enclosure cannot be carried
 * (the flow's message). GB_OK otherwise, with every relation proved or not in out (a relation not proved is not a
 * relation disproved). */
GB_API int gb_proof_cover(const gb_proof_cover_def *def, gb_proof_cover_result *out);

/* A proved lower bound of ln ρ(A) for a 0/1 matrix (n ≤ 8, row-major), by Collatz–Wielandt on Arb with v from power
 * iteration; 0 when the bound is not above 1. *rho receives the bound of ρ. */
GB_API int gb_proof_cover_entropy_bound(const int *matrix, size_t n, double *log_rho, double *rho);

/* Hénon's map (x, y) ↦ (1 − a x² + y, b x), a = a_num/a_den, b = b_num/b_den, as a quadratic field read as a map. */
GB_API gb_proof_field gb_proof_cover_henon(long a_num, long a_den, long b_num, long b_den);

/* Hénon's map read in the affine frame v ↦ origin + frame·v: g(v) = frame⁻¹(H(origin + frame·v) − origin), every
 * coefficient exact (FLINT's rationals). g is conjugate to H by an affine homeomorphism, so covering relations of
 * h-sets of g (rectangles in the frame: parallelograms in the plane) are those of H, and h_top(g) = h_top(H). GB_EDOM
 * when the frame is singular or a coefficient does not fit a long (named with what is allowed). */
GB_API int gb_proof_cover_henon_framed(long a_num, long a_den, long b_num, long b_den, const gb_proof_rational origin[2],
                                       const gb_proof_rational frame[2][2], gb_proof_field *out);

/* The classical Hénon map (a = 7/5, b = 3/10) in the frame o = (3157/5000, 947/5000), F = [[−1, −13/25], [39/250, −1]]
 * (o near the fixed point, F's columns near its unstable and stable eigenvectors), and five h-sets U_i × [−0.045, 0.045]
 * of its 7th iterate found by a search on floats (scripts/henon_horseshoe_search.py): *field the framed map, *def the covering relations to prove (a full
 * horseshoe on 5 symbols: h_top ≥ ln 5 / 7). */
GB_API int gb_proof_cover_henon_classical(gb_proof_field *field, gb_proof_cover_def *def);

#ifdef __cplusplus
}
#endif

#endif
