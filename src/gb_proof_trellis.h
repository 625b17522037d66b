/* gb_proof_trellis — a lower bound of the topological entropy of a planar diffeomorphism f from a trellis: an arc U of
 * the unstable manifold of a saddle fixed point and a finite union W of arcs of its stable manifold with f(W) ⊂ W
 * (docs/proofs.md, item 13, states the theorem and its proof).
 *
 * Every crossing of f(U) with W is proved (gb_proof_manifold_crossings: transverse, and no other), with the
 * orientation of the pair of tangents there. From them, exactly: the rectangles, the faces of the arrangement of
 * U ∪ W with four sides, two on U and two on W; the strips, the faces F of the arrangement of f(U) ∪ W with four sides
 * that lie in a rectangle Q_j, touch both of its sides on W, and are bounded on f(U) by the images of both sides on U
 * of one rectangle Q_i. Each strip is an edge i → j of a graph; K = f⁻¹(F) ⊂ Q_i is stretched by f across Q_j along
 * paths (Pireddu and Zanolin's SAP), the strips leaving Q_i are ordered across it, and two of them touch only if they
 * are neighbours. The closed walks of n edges from a rectangle Q to itself, (Aⁿ)_QQ of them, ordered so that only
 * neighbours can touch, leave ⌈(Aⁿ)_QQ / 2⌉ pairwise disjoint compact sets stretched by fⁿ across Q: fⁿ is
 * semiconjugate on an invariant set to the full shift on that many symbols, so
 *     h_top(f) ≥ (1/n) log ⌈N / 2⌉ for any N ≤ (Aⁿ)_QQ,
 * which tends to log ρ(A) as n grows. N is counted in integers, every count rounded down to 63 bits with a shared
 * exponent, so that n can be large (the work is n times the strips). Whatever is not proved (an orientation, a
 * parameter not placed) leaves a strip out, which only lowers the bound; whatever the argument needs (every crossing, their order along each arc) stops
 * the proof when it is not proved. */
#ifndef GB_PROOF_TRELLIS_H
#define GB_PROOF_TRELLIS_H

#include "gb_export.h"
#include "gb_proof.h"
#include "gb_proof_manifold.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

enum { GB_PROOF_TRELLIS_PIECES_MAX = 4096, GB_PROOF_TRELLIS_POWER_MAX = 10000000, GB_PROOF_TRELLIS_THREADS_MAX = 256 };

typedef struct gb_proof_trellis_def {
    double u;                        /* S: U = P([−S, S]), above 0, at most 1e5 (f(U) is P([−|λ| S, |λ| S])) */
    const gb_proof_interval
        *stable; /* W = ∪ R(stable[k]): ordered, pairwise disjoint, f(W) ⊂ W; each read as its middle
                                      * m plus [lo − m, hi − m] in doubles (W is exactly that union) */
    size_t stable_count;             /* 1 ... GB_PROOF_TRELLIS_PIECES_MAX */
    double width;                    /* the crossings' pieces (gb_proof_manifold_crossings_def) */
    int depth;
    int power;   /* n: 1 ... GB_PROOF_TRELLIS_POWER_MAX */
    int threads; /* the crossings of W's pieces and the walks on up to this many threads: 0 or 1 (the caller's
                  * alone) ... GB_PROOF_TRELLIS_THREADS_MAX; the result is the same */
} gb_proof_trellis_def;

typedef struct gb_proof_trellis_result {
    int proved;                /* every crossing proved and placed: the bound holds */
    size_t crossings;          /* of f(U) with W */
    size_t vertices;           /* of U with W */
    size_t rectangles, strips; /* the graph's vertices and edges */
    size_t strips_left;        /* four-sided faces of f(U) ∪ W in a rectangle that were not proved strips */
    double log_rho;            /* log ρ(A) by power iteration in doubles: an estimate, not proved */
    size_t rectangle;          /* Q, the rectangle whose closed walks give the bound */
    double log_walks;          /* log N in doubles, N ≤ (Aⁿ)_QQ the walks' count carried in 63-bit integers
                                * rounded down (exact while it fits) */
    double bound;              /* h_top(f) ≥ bound (rounded down; 0 when no walk returns) */
    char failure[200];         /* why not proved, or "" */
    double seconds;            /* CPU, every thread's */
} gb_proof_trellis_result;

/* The bound of the trellis of P (an unstable manifold of f) and R (one of f⁻¹, the same fixed point) over def. f's
 * Jacobian determinant must not vanish on the trellis (its sign is proved where a strip needs it). GB_EDOM for a
 * definition out of range (named with its range), stable pieces out of order or overlapping, or f(W) ⊄ W not proved;
 * GB_OK otherwise, out->proved saying whether the bound holds. */
GB_API int gb_proof_trellis_entropy(const gb_proof_manifold *p, const gb_proof_manifold *r,
                                    const gb_proof_trellis_def *def, gb_proof_trellis_result *out);

#ifdef __cplusplus
}
#endif

#endif
