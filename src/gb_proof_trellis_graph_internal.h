/* gb_proof_trellis_graph_internal — the strips' graph of a trellis (gb_proof_trellis_graph.c): its Perron root in
 * doubles, the rectangles to count from, and a lower bound of its closed walks in integers; for gb_proof_trellis.c and
 * the harness. Not installed, not exported. */
#ifndef GB_PROOF_TRELLIS_GRAPH_INTERNAL_H
#define GB_PROOF_TRELLIS_GRAPH_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

/* A strip from rectangle `from` to rectangle `to`: an edge of the graph, a 1 in A's column from, row to. */
typedef struct trellis_edge {
    long from, to;
} trellis_edge;

enum { TRELLIS_CANDIDATES = 8 };

/* log ρ(A) by power iteration in doubles (an estimate, proves nothing), and up to TRELLIS_CANDIDATES nodes where the
 * left and right Perron vectors' product is largest, best first, in cand[0 .. *nc). -INFINITY without edges, or
 * when out of memory (then *nc = 0). */
double trellis_perron(const trellis_edge *e, size_t m, size_t nodes, size_t cand[TRELLIS_CANDIDATES], size_t *nc);

/* A lower bound of (Aⁿ)_qq, the closed walks of n edges from q: *mantissa · 2^*exponent ≤ (Aⁿ)_qq, in integers. The
 * walks' counts are carried in unsigned 64-bit integers below 2^bits with a shared exponent; when a step's largest
 * count reaches 2^bits, every count is shifted right (rounded down) to `bits` bits, so the result is exact while the
 * counts fit (then *exponent = 0) and otherwise short by a relative error of order n · 2^−bits times the ratio of
 * the largest count to the smallest that matters. bits is 2 ... 63 and lowered to 63 − (the bits of the largest
 * in-degree) so that no sum can overflow. GB_EDOM for bits or q out of range, GB_ENOMEM. */
int trellis_walks_below(const trellis_edge *e, size_t m, size_t nodes, size_t q, long n, int bits, uint64_t *mantissa,
                        long *exponent);

/* The same from each of q[0 .. nq) at once, nq at most TRELLIS_CANDIDATES, into mantissa[c], exponent[c]: each as
 * trellis_walks_below gives it alone, bit for bit (the counts side by side, so each edge reads one cache line for
 * all of them). GB_EDOM for nq out of range too. */
int trellis_walks_below_many(const trellis_edge *e, size_t m, size_t nodes, const size_t *q, size_t nq, long n,
                             int bits, uint64_t *mantissa, long *exponent);

#endif
