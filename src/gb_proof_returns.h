/* gb_proof_returns — strips of a band (a rectangle in a chart) that return across it, and the lower bound of
 * topological entropy their return times prove.
 *
 * A quadratic map f of the plane (gb_proof_field read as a map) in coordinates u (across: the expanding direction) and
 * s (along), read in the chart (u, s − κ (u − u₀)²) that straightens a band bent along the parabola s = κ (u − u₀)²
 * (κ = 0: the plain coordinates). In the chart R = W × S is a rectangle, V_i = U_i × S strips of it with disjoint U_i
 * inside W, and m_i a return time for each. The strip returns across R when
 *   (edges) f^m_i maps the edge {min U_i} × S wholly to one side beyond W and {max U_i} × S wholly to the other, and
 *   (across) every point of V_i whose image lies in W across has its image in int S along
 * (the image may leave R's band anywhere beyond W). Then V_i covers every V_j for f^m_i: in the charts of the h-sets
 * (affine onto [-1, 1]²), first (w_u, (1 - t) w_s) and then ((1 - t) w_u + 2 t σ v_u, 0), σ = ±1 the edges' order,
 * is a homotopy from the map to (v_u, v_s) ↦ (2 σ v_u, 0) that never brings an edge into V_j nor a point onto V_j's
 * ends along (the second condition is used in the first stage, the first in both): Gidea & Zgliczyński 2004
 * (J. Differential Equations 202), Definition 6. By their Theorem 9 (chains of covering relations of different maps),
 * every sequence i_0 i_1 … has an orbit in V_i0 at time 0, in V_i1 at time m_i0, and so on. Two sequences that first
 * differ at their k-th symbol put their orbits in two different strips at the same time, at least the strips' distance
 * apart: the number of (T, ε)-separated orbits grows like x^T, x the root above 1 of Σ_i x^-m_i = 1 (the growth of the
 * paths of a graph with one vertex and a cycle of m_i edges through it for each strip), so h_top(f) ≥ ln x. The bound
 * proved is ln x₀ for an x₀ with Σ x₀^-m_i ≥ 1 shown on Arb's balls (the sum falls as x grows).
 *
 * A strip may instead return across part of R: its reach T_i, an interval inside W, takes W's place in both conditions
 * (its edges' images beyond T_i on opposite sides, which may be inside W; its points whose image lies in T_i across
 * land in int S). The same homotopy, in the chart of a V_j with U_j inside T_i, shows V_i covers that V_j for f^m_i.
 * The strips are then the vertices of a graph, with an edge i → j of length m_i when U_j lies in T_i; counting its
 * paths of total length ≤ T as above, h_top(f) ≥ ln x₀ for any x₀ > 1 at which a positive vector v has
 * M(x₀) v ≥ v, M(x)_ij = x^-m_i on the edges (by induction on T the paths from i number at least c v_i x₀^T), a
 * vertex without an edge to a vertex left being taken out first. With every T_i = W, M(x) has rank one and this is
 * the renewal bound. */
#ifndef GB_PROOF_RETURNS_H
#define GB_PROOF_RETURNS_H

#include "gb_export.h"
#include "gb_proof.h"
#include "gb_proof_flow.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

enum { GB_PROOF_RETURNS_MAX = 64, GB_PROOF_RETURN_TIME_MAX = 32 };

typedef struct gb_proof_returns_def {
    const gb_proof_field *map; /* the map of the plane (dimension 2): coordinate 0 is u, 1 is s */
    long precision;            /* Arb's bits */
    gb_proof_interval window;  /* W: R across */
    gb_proof_interval strip;   /* S: R along, and every strip's extent along, about the band's centre line */
    double curvature, vertex;  /* the band's centre line s = curvature (u - vertex)² (0: a straight rectangle) */
    size_t sets;               /* 1 ... 64 */
    gb_proof_interval set_u[GB_PROOF_RETURNS_MAX]; /* U_i: disjoint, inside W */
    int returns[GB_PROOF_RETURNS_MAX];             /* m_i: 1 ... 32 */
    gb_proof_interval reach[GB_PROOF_RETURNS_MAX]; /* T_i: inside W; {0, 0} (the default): W itself */
    int pieces;                                    /* the first cut of a strip across: 1 ... 100000 */
    int depth; /* the most halvings (across and along) of a piece that does not prove itself: 0 ... 30 */
} gb_proof_returns_def;

typedef struct gb_proof_returns_result {
    int across[GB_PROOF_RETURNS_MAX];  /* V_i returns across R in m_i iterates: proved */
    int side[GB_PROOF_RETURNS_MAX][2]; /* where the low and high edges land: -1 below W, 1 above, 0 not proved */
    gb_proof_interval edge[GB_PROOF_RETURNS_MAX][2]; /* their images across (hulls of the enclosures) */
    size_t proved;                                   /* the strips whose return is proved */
    size_t targets[GB_PROOF_RETURNS_MAX];            /* the proved strips inside each strip's reach */
    double entropy;                                  /* ln x₀ from the proved strips' return times (0 when none) */
    long pieces;                                     /* pieces enclosed, after halvings */
    long failed_pieces;                              /* pieces undecided at the deepest halving */
    char failure[400];                               /* the first failure, or "" */
    double seconds;
} gb_proof_returns_result;

/* Default: 1 set, return time 1, 16 pieces, depth 16, precision 128; the caller fills the map, R and the strips. */
GB_API gb_proof_returns_def gb_proof_returns_def_default(void);

/* GB_EDOM for a definition out of range (named with its range). GB_OK otherwise, every strip proved or not in out (a
 * return not proved is not a return disproved). */
GB_API int gb_proof_returns(const gb_proof_returns_def *def, gb_proof_returns_result *out);

/* A proved lower bound ln x₀ of ln x, x the root above 1 of Σ_i x^-m_i = 1 (n ≤ 64 return times, each 1 ... 32): 0 when
 * the root is not above 1 (a single strip). GB_EDOM for counts or times out of range. */
GB_API int gb_proof_returns_entropy_bound(const int *returns, size_t n, double *log_x);

/* A proved lower bound ln x₀ of ln x, x the root above 1 of ρ(M(x)) = 1 for the graph of n ≤ 64 strips with return
 * times m_i (1 ... 32) and edges i → j where edge[i * n + j] is not 0 (M(x)_ij = x^-m_i there): ln x₀ with M(x₀) v ≥ v
 * proved on Arb's balls for a positive v (the Perron vector in doubles, on the vertices left once those without an edge
 * to a vertex left are taken out); 0 when no x₀ > 1 is proved. GB_EDOM for counts or times out of range. */
GB_API int gb_proof_returns_graph_bound(const int *returns, const unsigned char *edge, size_t n, double *log_x);

/* The bound the definition's strips would prove if every one returned (the graph's, or the renewal bound's when every
 * reach is W): what a statement claims before its returns are proved. GB_EDOM for a definition out of range. */
GB_API int gb_proof_returns_table_bound(const gb_proof_returns_def *def, double *log_x);

/* The classical Hénon map (a = 7/5, b = 3/10) in the frame of gb_proof_cover_henon_classical, the band about
 * s = 0.14 (u - 0.05)², R = [-0.42, 0.3] × [-0.018, 0.018] in its chart, and the strips of
 * scripts/henon_returns_search.py with their return times: *field the framed map, *def the returns to prove. */
GB_API int gb_proof_returns_henon_classical(gb_proof_field *field, gb_proof_returns_def *def);

/* The same band and strips, and the strips of scripts/henon_returns_search.py --partial that return across part of it
 * (each with its reach): *def the returns to prove, their bound the graph's. */
GB_API int gb_proof_returns_henon_partial(gb_proof_field *field, gb_proof_returns_def *def);

#ifdef __cplusplus
}
#endif

#endif
