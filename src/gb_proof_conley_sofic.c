/* gb_proof_conley_sofic — Q's regions, the sofic graph of the index map's blocks and the lower bound of its entropy
 * (see gb_proof_conley.h). */
#include "gb_proof_conley_sofic_internal.h"
#include "gb_proof_internal.h"

#include "gb_error.h"

#include <arb.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static long root_of(int32_t *up, long x)
{
    while (up[x] != x) up[x] = up[up[x]], x = up[x];
    return x;
}

/* Q's components (boxes touching at a corner joined), numbered 0 ... count − 1, by position in P1 (−1 outside Q). */
static long regions_find(const conley_grid *g, int32_t *region)
{
    const size_t m = g->p1_count;
    int32_t *label = malloc((m + 1) * sizeof *label);
    if (!label) return -1;
    for (size_t k = 0; k < m; k++) region[k] = (int32_t)k, label[k] = -1;
    for (size_t k = 0; k < m; k++) {
        if (!(g->state[g->p1[k]] & CONLEY_Q)) continue;
        const long i = (long)(g->p1[k] % (uint32_t)g->n), j = (long)(g->p1[k] / (uint32_t)g->n);
        for (long dj = -1; dj <= 1; dj++)
            for (long di = -1; di <= 1; di++)
                if (conley_is(g, i + di, j + dj, CONLEY_Q)) {
                    const long a = root_of(region, (long)k),
                               b = root_of(region, conley_p1_position(g, (uint32_t)((j + dj) * g->n + i + di)));
                    if (a != b) region[a > b ? a : b] = (int32_t)(a < b ? a : b);
                }
    }
    for (size_t k = 0; k < m; k++) region[k] = (int32_t)root_of(region, (long)k); /* every box to its root */
    long count = 0;
    for (size_t k = 0; k < m; k++)
        if ((g->state[g->p1[k]] & CONLEY_Q) && label[region[k]] < 0) label[region[k]] = (int32_t)count++;
    for (size_t k = 0; k < m; k++) region[k] = g->state[g->p1[k]] & CONLEY_Q ? label[region[k]] : -1;
    free(label);
    return count;
}

/* A directed graph in compressed rows. */
typedef struct digraph {
    size_t nodes, edges, room;
    int32_t *start, *next;
} digraph;

static int push_edge(digraph *d, int32_t to)
{
    if (d->edges == d->room) {
        const size_t room = d->room ? 2 * d->room : 1024;
        int32_t *more = realloc(d->next, room * sizeof *more);
        if (!more) return gb_error_set(GB_ENOMEM, "out of memory for the sofic graph");
        d->next = more, d->room = room;
    }
    d->next[d->edges++] = to;
    return GB_OK;
}

/* Strongly connected components (Tarjan's, iteratively): comp[v], returns their number or −1. */
static long components(const digraph *d, int32_t *comp)
{
    const size_t n = d->nodes;
    int32_t *index = malloc((n + 1) * sizeof *index), *low = malloc((n + 1) * sizeof *low);
    int32_t *stack = malloc((n + 1) * sizeof *stack), *call = malloc((n + 1) * sizeof *call);
    int32_t *edge = malloc((n + 1) * sizeof *edge);
    uint8_t *on = calloc(n + 1, 1);
    long count = -1;
    if (!index || !low || !stack || !call || !edge || !on) goto done;
    for (size_t v = 0; v < n; v++) index[v] = -1;
    int32_t next_index = 0, top = 0;
    count = 0;
    for (size_t root = 0; root < n; root++) {
        if (index[root] >= 0) continue;
        int32_t depth = 0;
        call[0] = (int32_t)root, edge[0] = d->start[root];
        index[root] = low[root] = next_index++, stack[top++] = (int32_t)root, on[root] = 1;
        while (depth >= 0) {
            const int32_t v = call[depth];
            if (edge[depth] < d->start[v + 1]) {
                const int32_t w = d->next[edge[depth]++];
                if (index[w] < 0) {
                    index[w] = low[w] = next_index++, stack[top++] = w, on[w] = 1;
                    call[++depth] = w, edge[depth] = d->start[w];
                } else if (on[w] && index[w] < low[v]) {
                    low[v] = index[w];
                }
                continue;
            }
            if (low[v] == index[v]) {
                int32_t w;
                do w = stack[--top], on[w] = 0, comp[w] = (int32_t)count;
                while (w != v);
                count++;
            }
            if (--depth >= 0 && low[v] < low[call[depth]]) low[call[depth]] = low[v];
        }
    }
done:
    free(index), free(low), free(stack), free(call), free(edge), free(on);
    return count;
}

/* ρ of the component's adjacency estimated by power iteration of A + I (its diagonal keeps v positive); v returned. */
static double power_rho(const digraph *d, const int32_t *comp, int32_t c, double *v, double *w)
{
    double rho = 0.0;
    for (size_t i = 0; i < d->nodes; i++) v[i] = comp[i] == c ? 1.0 : 0.0;
    for (int it = 0; it < 5000; it++) {
        double top = 0.0;
        for (size_t i = 0; i < d->nodes; i++) {
            if (comp[i] != c) continue;
            double s = v[i];
            for (int32_t a = d->start[i]; a < d->start[i + 1]; a++)
                if (comp[d->next[a]] == c) s += v[d->next[a]];
            w[i] = s, top = fmax(top, s);
        }
        double change = 0.0;
        for (size_t i = 0; i < d->nodes; i++)
            if (comp[i] == c) change = fmax(change, fabs(w[i] / top - v[i])), v[i] = w[i] / top;
        rho = top - 1.0;
        if (change < 1e-14) break;
    }
    return rho;
}

/* min_i (A v)_i / v_i over the component, on Arb: a lower bound of its ρ (Collatz–Wielandt), rounded down. */
static double collatz_wielandt(const digraph *d, const int32_t *comp, int32_t c, const double *v, long precision)
{
    arb_t s, r;
    arf_t lo;
    arb_init(s), arb_init(r), arf_init(lo);
    double best = INFINITY;
    for (size_t i = 0; i < d->nodes; i++) {
        if (comp[i] != c) continue;
        arb_zero(s);
        for (int32_t a = d->start[i]; a < d->start[i + 1]; a++)
            if (comp[d->next[a]] == c) arb_set_d(r, v[d->next[a]]), arb_add(s, s, r, precision);
        arb_set_d(r, v[i]);
        arb_div(s, s, r, precision);
        arb_get_lbound_arf(lo, s, precision);
        best = fmin(best, arf_get_d(lo, ARF_RND_FLOOR));
    }
    arb_clear(s), arb_clear(r), arf_clear(lo);
    return best;
}

int conley_sofic_entropy(const conley_grid *g, const conley_homology *h, long precision, int region_dimension,
                         conley_sofic *out)
{
    memset(out, 0, sizeof *out);
    const size_t m = g->p1_count, L = h->generators;
    int32_t *region = malloc((m + 1) * sizeof *region), *gen_region = malloc((L + 1) * sizeof *gen_region);
    int32_t *local = malloc((L + 1) * sizeof *local), *col_start = calloc(L + 2, sizeof *col_start), *col_row = NULL;
    int32_t *dims = NULL, *base = NULL, *mask = NULL, *touched = NULL, *comp = NULL;
    uint8_t *acc = calloc(L + 1, 1);
    double *v = NULL, *w = NULL;
    digraph d = {0};
    int status = GB_OK;
    const long regions = region && gen_region && local && col_start && acc ? regions_find(g, region) : -1;
    if (regions < 0) goto nomem;
    out->regions = regions;
    dims = calloc((size_t)regions + 1, sizeof *dims), base = malloc(((size_t)regions + 1) * sizeof *base);
    mask = calloc((size_t)regions + 1, sizeof *mask), touched = malloc((L + (size_t)regions + 1) * sizeof *touched);
    if (!dims || !base || !mask || !touched) goto nomem;
    for (size_t k = 0; k < L; k++) {
        gen_region[k] = region[conley_p1_position(g, (uint32_t)h->square[k])];
        local[k] = dims[gen_region[k]]++;
    }
    /* the map's columns as lists of rows */
    for (size_t r = 0; r < L; r++)
        for (size_t c = 0; c < L; c++)
            if (h->map[r * h->words + c / 64] >> (c % 64) & 1) col_start[c + 2]++;
    for (size_t c = 0; c < L; c++) col_start[c + 2] += col_start[c + 1];
    col_row = malloc(((size_t)col_start[L + 1] + 1) * sizeof *col_row);
    if (!col_row) goto nomem;
    for (size_t r = 0; r < L; r++)
        for (size_t c = 0; c < L; c++)
            if (h->map[r * h->words + c / 64] >> (c % 64) & 1) col_row[col_start[c + 1]++] = (int32_t)r;
    size_t nodes = 0;
    for (long r = 0; r < regions; r++) {
        base[r] = (int32_t)nodes;
        if (dims[r] >= 1 && dims[r] <= region_dimension) nodes += ((size_t)1 << dims[r]) - 1, out->regions_used++;
    }
    /* generators of each region in order: their numbers */
    int32_t *members = malloc((L + 1) * sizeof *members), *first = calloc((size_t)regions + 1, sizeof *first);
    if (!members || !first) {
        free(members), free(first);
        goto nomem;
    }
    for (size_t k = 0; k < L; k++) first[gen_region[k] + 1]++;
    for (long r = 0; r < regions; r++) first[r + 1] += first[r];
    for (size_t k = 0; k < L; k++) members[first[gen_region[k]] + local[k]] = (int32_t)k;
    d.nodes = nodes, d.start = malloc((nodes + 1) * sizeof *d.start);
    if (!d.start) {
        free(members), free(first);
        goto nomem;
    }
    for (long r = 0; r < regions && !status; r++) {
        if (dims[r] < 1 || dims[r] > region_dimension) continue;
        for (int32_t bits = 1; bits < (1 << dims[r]) && !status; bits++) {
            d.start[base[r] + bits - 1] = (int32_t)d.edges;
            size_t rows = 0, hit = 0;
            for (int t = 0; t < dims[r]; t++) {
                if (!(bits >> t & 1)) continue;
                const int32_t c = members[first[r] + t];
                for (int32_t a = col_start[c]; a < col_start[c + 1]; a++) {
                    if (!acc[col_row[a]]) touched[rows++] = col_row[a];
                    acc[col_row[a]] ^= 1;
                }
            }
            int32_t *regions_hit = touched + L;
            for (size_t k = 0; k < rows; k++) {
                const int32_t row = touched[k], r2 = gen_region[row];
                if (acc[row] && dims[r2] <= region_dimension) {
                    if (!mask[r2]) regions_hit[hit++] = r2;
                    mask[r2] ^= 1 << local[row];
                }
                acc[row] = 0;
            }
            for (size_t k = 0; k < hit && !status; k++) {
                const int32_t r2 = regions_hit[k];
                status = push_edge(&d, base[r2] + mask[r2] - 1); /* rows left set: a mask never 0 */
                mask[r2] = 0;
            }
        }
    }
    free(members), free(first);
    if (status) goto done;
    d.start[nodes] = (int32_t)d.edges;
    out->symbols = (long)nodes, out->transitions = (long)d.edges;
    comp = malloc((nodes + 1) * sizeof *comp), v = malloc((nodes + 1) * sizeof *v), w = malloc((nodes + 1) * sizeof *w);
    const long count = comp && v && w ? components(&d, comp) : -1;
    if (count < 0) goto nomem;
    /* the component with the largest ρ by power iteration, then its bound */
    int32_t best = -1;
    double best_rho = 1.0;
    int32_t *size = calloc((size_t)count + 1, sizeof *size);
    if (!size) goto nomem;
    for (size_t i = 0; i < nodes; i++) size[comp[i]]++;
    for (long c = 0; c < count; c++) {
        const double rho = power_rho(&d, comp, (int32_t)c, v, w);
        if (rho > best_rho + 1e-9) best_rho = rho, best = (int32_t)c;
    }
    if (best >= 0) {
        power_rho(&d, comp, best, v, w);
        out->component = size[best];
        const double rho = collatz_wielandt(&d, comp, best, v, precision);
        if (rho > 1.0) {
            arb_t x;
            arf_t lo;
            arb_init(x), arf_init(lo);
            arb_set_d(x, rho), arb_log(x, x, precision), arb_get_lbound_arf(lo, x, precision);
            out->rho = rho, out->entropy = fmax(0.0, arf_get_d(lo, ARF_RND_FLOOR));
            arb_clear(x), arf_clear(lo);
        }
    }
    free(size);
    goto done;
nomem:
    status = gb_error_set(GB_ENOMEM, "out of memory for the index map's regions");
done:
    free(region), free(gen_region), free(local), free(col_start), free(col_row), free(dims), free(base), free(mask);
    free(touched), free(comp), free(acc), free(v), free(w), free(d.start), free(d.next);
    return status;
}
