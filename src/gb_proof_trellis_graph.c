/* gb_proof_trellis_graph — the strips' graph of a trellis: Perron root and closed walks (the internal header states
 * what each function gives). */
#include "gb_proof_trellis_graph_internal.h"

#include "gb_error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { POWER_ITERATIONS = 4000 };

/* Power iteration on A + I, whose Perron root is ρ + 1 and which has no other eigenvalue of that modulus when A is
 * irreducible, so the iteration settles even when A is periodic. */
double trellis_perron(const trellis_edge *e, size_t m, size_t nodes, size_t cand[TRELLIS_CANDIDATES], size_t *nc)
{
    double *x = malloc(nodes * sizeof *x), *y = malloc(nodes * sizeof *y), *nx = malloc(nodes * sizeof *nx),
           *ny = malloc(nodes * sizeof *ny);
    double rho = 0.0;
    *nc = 0;
    if (!m || !x || !y || !nx || !ny) goto done;
    for (size_t i = 0; i < nodes; i++) x[i] = y[i] = 1.0;
    for (int it = 0; it < POWER_ITERATIONS; it++) {
        memcpy(nx, x, nodes * sizeof *x), memcpy(ny, y, nodes * sizeof *y);
        for (size_t k = 0; k < m; k++) nx[e[k].to] += x[e[k].from], ny[e[k].from] += y[e[k].to];
        double sx = 0.0, sy = 0.0, before = 0.0;
        for (size_t i = 0; i < nodes; i++) sx += nx[i], sy += ny[i], before += x[i];
        rho = sx / before - 1.0;
        for (size_t i = 0; i < nodes; i++) x[i] = nx[i] / sx, y[i] = ny[i] / sy;
    }
    for (size_t i = 0; i < nodes; i++) nx[i] = x[i] * y[i];
    while (*nc < TRELLIS_CANDIDATES && *nc < nodes) {
        size_t best = 0;
        for (size_t i = 1; i < nodes; i++)
            if (nx[i] > nx[best]) best = i;
        if (!(nx[best] > 0.0)) break;
        cand[(*nc)++] = best, nx[best] = -1.0;
    }
done:
    free(x), free(y), free(nx), free(ny);
    return rho > 0.0 ? log(rho) : -INFINITY;
}

static int bit_length(uint64_t v)
{
    int b = 0;
    while (v) b++, v >>= 1;
    return b;
}

int trellis_walks_below_many(const trellis_edge *e, size_t m, size_t nodes, const size_t *q, size_t nq, long n,
                             int bits, uint64_t *mantissa, long *exponent)
{
    if (nq < 1 || nq > TRELLIS_CANDIDATES)
        return gb_error_set(GB_EDOM, "trellis walks: %zu starting nodes (allowed: 1 to %d)", nq, TRELLIS_CANDIDATES);
    for (size_t c = 0; c < nq; c++) mantissa[c] = 0, exponent[c] = 0;
    if (bits < 2 || bits > 63)
        return gb_error_set(GB_EDOM, "trellis walks: bits = %d is out of range (allowed: 2 to 63)", bits);
    for (size_t c = 0; c < nq; c++)
        if (q[c] >= nodes)
            return gb_error_set(GB_EDOM, "trellis walks: node %zu is out of range (allowed: below %zu)", q[c], nodes);
    /* the counts of the nq walks side by side, node by node: one cache line serves them all */
    uint64_t *x = calloc(nodes * nq, sizeof *x), *y = calloc(nodes * nq, sizeof *y), *in = calloc(nodes, sizeof *in);
    if (!x || !y || !in) {
        free(x), free(y), free(in);
        return gb_error_set(GB_ENOMEM, "trellis walks: out of memory");
    }
    uint64_t most = 0;
    for (size_t k = 0; k < m; k++)
        if (++in[e[k].to] > most) most = in[e[k].to];
    free(in);
    /* Counts below 2^bits and at most `most` of them summed: below 2^(bits + bit_length(most)) ≤ 2^63. */
    if (bits > 63 - bit_length(most)) bits = 63 - bit_length(most);
    const uint64_t limit = (uint64_t)1 << bits;
    long shifted[TRELLIS_CANDIDATES] = {0};
    for (size_t c = 0; c < nq; c++) x[q[c] * nq + c] = 1;
    for (long step = 0; step < n; step++) {
        memset(y, 0, nodes * nq * sizeof *y);
        for (size_t k = 0; k < m; k++) {
            const uint64_t *from = x + (size_t)e[k].from * nq;
            uint64_t *to = y + (size_t)e[k].to * nq;
            for (size_t c = 0; c < nq; c++) to[c] += from[c];
        }
        uint64_t top[TRELLIS_CANDIDATES] = {0};
        for (size_t i = 0; i < nodes; i++)
            for (size_t c = 0; c < nq; c++)
                if (y[i * nq + c] > top[c]) top[c] = y[i * nq + c];
        for (size_t c = 0; c < nq; c++)
            if (top[c] >= limit) { /* every count rounded down: still at most the walks it stands for */
                const int s = bit_length(top[c]) - bits;
                for (size_t i = 0; i < nodes; i++) y[i * nq + c] >>= s;
                shifted[c] += s;
            }
        uint64_t *t = x;
        x = y, y = t;
    }
    for (size_t c = 0; c < nq; c++) mantissa[c] = x[q[c] * nq + c], exponent[c] = mantissa[c] ? shifted[c] : 0;
    free(x), free(y);
    return GB_OK;
}

int trellis_walks_below(const trellis_edge *e, size_t m, size_t nodes, size_t q, long n, int bits, uint64_t *mantissa,
                        long *exponent)
{
    return trellis_walks_below_many(e, m, nodes, &q, 1, n, bits, mantissa, exponent);
}
