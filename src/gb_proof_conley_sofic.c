/* gb_proof_conley_sofic — Q's regions, the sofic graph of the index map's blocks and the lower bound of its entropy
 * (see gb_proof_conley.h). */
#include "gb_proof_conley_sofic_internal.h"
#include "gb_proof_internal.h"

#include "gb_error.h"

#include <arb.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

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
                    const long a = conley_root(region, (long)k),
                               b = conley_root(region, conley_p1_position(g, (uint32_t)((j + dj) * g->n + i + di)));
                    if (a != b) region[a > b ? a : b] = (int32_t)(a < b ? a : b);
                }
    }
    for (size_t k = 0; k < m; k++) region[k] = (int32_t)conley_root(region, (long)k); /* every box to its root */
    long count = 0;
    for (size_t k = 0; k < m; k++)
        if ((g->state[g->p1[k]] & CONLEY_Q) && label[region[k]] < 0) label[region[k]] = (int32_t)count++;
    for (size_t k = 0; k < m; k++) region[k] = g->state[g->p1[k]] & CONLEY_Q ? label[region[k]] : -1;
    free(label);
    return count;
}

/* A directed graph in compressed rows. */
typedef struct digraph {
    size_t nodes, edges, room, start_room;
    int32_t *start, *next;
} digraph;

/* Vertex u's edges start here (vertices are opened in order). */
static int digraph_open(digraph *d, size_t u)
{
    if (u + 1 >= d->start_room) {
        const size_t room = d->start_room ? 2 * d->start_room : 1024;
        int32_t *more = realloc(d->start, (room + 1) * sizeof *more);
        if (!more) return 1;
        d->start = more, d->start_room = room;
    }
    d->start[u] = (int32_t)d->edges;
    return 0;
}

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

/* Vertex u has an edge to itself. */
static int has_loop(const digraph *d, int32_t u)
{
    for (int32_t a = d->start[u]; a < d->start[u + 1]; a++)
        if (d->next[a] == u) return 1;
    return 0;
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

/* ρ of a component's adjacency (its vertices `member`, k of them; comp[] names each vertex's component) estimated by
 * power iteration of A + I (its diagonal keeps v positive); v returned on the members. */
static double power_rho(const digraph *d, const int32_t *comp, const int32_t *member, size_t k, double *v, double *w)
{
    double rho = 0.0;
    const int32_t c = comp[member[0]];
    for (size_t m = 0; m < k; m++) v[member[m]] = 1.0;
    for (int it = 0; it < 5000; it++) {
        double top = 0.0;
        for (size_t m = 0; m < k; m++) {
            const int32_t i = member[m];
            double s = v[i];
            for (int32_t a = d->start[i]; a < d->start[i + 1]; a++)
                if (comp[d->next[a]] == c) s += v[d->next[a]];
            w[i] = s, top = fmax(top, s);
        }
        double change = 0.0;
        for (size_t m = 0; m < k; m++) {
            const int32_t i = member[m];
            change = fmax(change, fabs(w[i] / top - v[i])), v[i] = w[i] / top;
        }
        rho = top - 1.0;
        if (change < 1e-14) break;
    }
    return rho;
}

/* min_i (A v)_i / v_i over the component, on Arb: a lower bound of its ρ (Collatz–Wielandt), rounded down. */
static double collatz_wielandt(const digraph *d, const int32_t *comp, const int32_t *member, size_t k, const double *v,
                               long precision)
{
    arb_t s, r;
    arf_t lo;
    arb_init(s), arb_init(r), arf_init(lo);
    double best = INFINITY;
    const int32_t c = comp[member[0]];
    for (size_t m = 0; m < k; m++) {
        const int32_t i = member[m];
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

/* Words of a class of a region with k generators. */
static size_t words_of(int k) { return ((size_t)k + 63) / 64; }

/* The sofic graph's vertices: (region, class as a bit vector over the region's generators), found by hashing. At most
 * SYMBOLS_MAX: past it no vertex is made and the edge to it is left out (a subgraph: its cycles are the graph's). */
enum { SYMBOLS_MAX = 1 << 20 };
typedef struct symbols {
    size_t count, room, pool_used, pool_room, mask;
    int32_t *region;
    size_t *offset;
    uint64_t *pool;
    int32_t *slot; /* vertex or −1 */
    int capped;
} symbols;

static int symbols_init(symbols *S)
{
    S->room = 1024, S->pool_room = 4096, S->mask = 2047;
    S->region = malloc(S->room * sizeof *S->region), S->offset = malloc(S->room * sizeof *S->offset);
    S->pool = malloc(S->pool_room * sizeof *S->pool), S->slot = malloc((S->mask + 1) * sizeof *S->slot);
    if (!S->region || !S->offset || !S->pool || !S->slot) return 1;
    for (size_t k = 0; k <= S->mask; k++) S->slot[k] = -1;
    return 0;
}

static void symbols_free(symbols *S) { free(S->region), free(S->offset), free(S->pool), free(S->slot); }

static uint64_t symbol_hash(int32_t region, const uint64_t *vec, size_t words)
{
    uint64_t h = 0x9E3779B97F4A7C15ull * (uint64_t)(region + 1);
    for (size_t k = 0; k < words; k++) h = (h ^ vec[k]) * 0xBF58476D1CE4E5B9ull, h ^= h >> 31;
    return h;
}

static size_t symbol_slot(const symbols *S, int32_t region, const uint64_t *vec, size_t words)
{
    size_t s = (size_t)symbol_hash(region, vec, words) & S->mask;
    while (S->slot[s] >= 0 &&
           !(S->region[S->slot[s]] == region && !memcmp(S->pool + S->offset[S->slot[s]], vec, words * sizeof *vec)))
        s = (s + 1) & S->mask;
    return s;
}

/* The vertex (region, vec): its number, made if new; −1 past SYMBOLS_MAX; −2 out of memory. */
static long symbols_add(symbols *S, int32_t region, const uint64_t *vec, size_t words)
{
    size_t s = symbol_slot(S, region, vec, words);
    if (S->slot[s] >= 0) return S->slot[s];
    if (S->count >= SYMBOLS_MAX) return S->capped = 1, -1;
    if (S->count == S->room) {
        int32_t *r = realloc(S->region, 2 * S->room * sizeof *r);
        if (r) S->region = r;
        size_t *o = realloc(S->offset, 2 * S->room * sizeof *o);
        if (o) S->offset = o;
        if (!r || !o) return -2;
        S->room *= 2;
    }
    while (S->pool_used + words > S->pool_room) {
        uint64_t *p = realloc(S->pool, 2 * S->pool_room * sizeof *p);
        if (!p) return -2;
        S->pool = p, S->pool_room *= 2;
    }
    const size_t id = S->count++;
    S->region[id] = region, S->offset[id] = S->pool_used;
    memcpy(S->pool + S->pool_used, vec, words * sizeof *vec), S->pool_used += words;
    S->slot[s] = (int32_t)id;
    if (2 * S->count > S->mask) { /* rehash at half full */
        int32_t *slot = malloc(2 * (S->mask + 1) * sizeof *slot);
        if (!slot) return -2;
        free(S->slot), S->slot = slot, S->mask = 2 * S->mask + 1;
        for (size_t k = 0; k <= S->mask; k++) S->slot[k] = -1;
        for (size_t v = 0; v < S->count; v++) {
            const size_t end = v + 1 < S->count ? S->offset[v + 1] : S->pool_used;
            S->slot[symbol_slot(S, S->region[v], S->pool + S->offset[v], end - S->offset[v])] = (int32_t)v;
        }
    }
    return (long)id;
}

int conley_sofic_entropy(const conley_grid *g, const conley_homology *h, long precision, int region_dimension,
                         conley_sofic *out)
{
    memset(out, 0, sizeof *out);
    const size_t m = g->p1_count, L = h->generators;
    int32_t *region = malloc((m + 1) * sizeof *region), *gen_region = malloc((L + 1) * sizeof *gen_region);
    int32_t *local = malloc((L + 1) * sizeof *local), *col_start = calloc(L + 2, sizeof *col_start), *col_row = NULL;
    int32_t *dims = NULL, *mask = NULL, *touched = NULL, *comp = NULL;
    uint8_t *acc = calloc(L + 1, 1);
    double *v = NULL, *w = NULL;
    digraph d = {0};
    int status = GB_OK;
    const long regions = region && gen_region && local && col_start && acc ? regions_find(g, region) : -1;
    if (regions < 0) goto nomem;
    out->regions = regions;
    dims = calloc((size_t)regions + 1, sizeof *dims);
    mask = calloc((size_t)regions + 1, sizeof *mask), touched = malloc((L + (size_t)regions + 1) * sizeof *touched);
    if (!dims || !mask || !touched) goto nomem;
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
    /* generators of each region in order: their numbers; each region's words in the scratch vector */
    int32_t *members = malloc((L + 1) * sizeof *members), *first = calloc((size_t)regions + 1, sizeof *first);
    size_t *scratch_at = malloc(((size_t)regions + 1) * sizeof *scratch_at), scratch_words = 0;
    symbols S = {0};
    uint64_t *scratch = NULL;
    size_t nodes = 0;
    if (!members || !first || !scratch_at) {
        status = 1;
        goto fail;
    }
    for (size_t k = 0; k < L; k++) first[gen_region[k] + 1]++;
    for (long r = 0; r < regions; r++) first[r + 1] += first[r];
    for (size_t k = 0; k < L; k++) members[first[gen_region[k]] + local[k]] = (int32_t)k;
    for (long r = 0; r < regions; r++) scratch_at[r] = scratch_words, scratch_words += words_of(dims[r]);
    scratch = calloc(scratch_words + 1, sizeof *scratch);
    if (!scratch || symbols_init(&S)) {
        status = 1;
        goto fail;
    }
    /* the first vertices: every class of a region of at most region_dimension generators, the generators of the others */
    for (long r = 0; r < regions && !status; r++) {
        uint64_t *vec = scratch + scratch_at[r];
        if (dims[r] >= 1 && dims[r] <= region_dimension) {
            out->regions_used++;
            for (uint64_t bits = 1; bits < (1ull << dims[r]) && !status; bits++)
                vec[0] = bits, status = symbols_add(&S, (int32_t)r, vec, 1) < -1;
            vec[0] = 0;
        } else {
            for (int t = 0; t < dims[r] && !status; t++) {
                vec[t / 64] = 1ull << (t % 64);
                status = symbols_add(&S, (int32_t)r, vec, words_of(dims[r])) < -1;
                vec[t / 64] = 0;
            }
        }
    }
    /* then breadth first: a vertex's image under its region's blocks, one vertex for each region it reaches */
    for (size_t u = 0; u < S.count && !status; u++) {
        if (digraph_open(&d, u)) {
            status = GB_ENOMEM;
            break;
        }
        const int32_t r = S.region[u];
        const uint64_t *vec = S.pool + S.offset[u];
        size_t rows = 0, hit = 0;
        for (int t = 0; t < dims[r]; t++) {
            if (!(vec[t / 64] >> (t % 64) & 1)) continue;
            const int32_t c = members[first[r] + t];
            for (int32_t a = col_start[c]; a < col_start[c + 1]; a++) { /* bit 1: listed once in touched */
                if (!(acc[col_row[a]] & 2)) touched[rows++] = col_row[a], acc[col_row[a]] |= 2;
                acc[col_row[a]] ^= 1;
            }
        }
        int32_t *regions_hit = touched + L;
        for (size_t k = 0; k < rows; k++) {
            const int32_t row = touched[k], r2 = gen_region[row];
            if (acc[row] & 1) {
                uint64_t *target = scratch + scratch_at[r2];
                if (!mask[r2]) regions_hit[hit++] = r2, mask[r2] = 1;
                target[local[row] / 64] ^= 1ull << (local[row] % 64);
            }
            acc[row] = 0;
        }
        for (size_t k = 0; k < hit && !status; k++) { /* rows left set: a vector never 0 */
            const int32_t r2 = regions_hit[k];
            uint64_t *target = scratch + scratch_at[r2];
            const long id = symbols_add(&S, r2, target, words_of(dims[r2]));
            if (id < -1)
                status = GB_ENOMEM;
            else if (id >= 0)
                status = push_edge(&d, (int32_t)id); /* −1: past the cap, the edge left out */
            memset(target, 0, words_of(dims[r2]) * sizeof *target), mask[r2] = 0;
        }
    }
    out->capped = S.capped, nodes = S.count;
fail:
    free(members), free(first), free(scratch_at), free(scratch), symbols_free(&S);
    if (status) { /* out of memory, here or in a push */
        status = gb_error_set(GB_ENOMEM, "out of memory for the sofic graph");
        goto done;
    }
    d.nodes = nodes;
    if (digraph_open(&d, nodes)) goto nomem;
    out->symbols = (long)nodes, out->transitions = (long)d.edges;
    comp = malloc((nodes + 1) * sizeof *comp), v = malloc((nodes + 1) * sizeof *v), w = malloc((nodes + 1) * sizeof *w);
    const long count = comp && v && w ? components(&d, comp) : -1;
    if (count < 0) goto nomem;
    /* the component with the largest ρ by power iteration (each over its own vertices), then its bound; a component
     * with ρ ≤ 1 proves nothing, and one within 1e-9 of the best so far (the power iteration's own change, 1e-14, is
     * far below) does not replace it */
    int32_t best = -1;
    double best_rho = 1.0;
    int32_t *start = calloc((size_t)count + 2, sizeof *start), *member = malloc((nodes + 1) * sizeof *member);
    if (!start || !member) {
        free(start), free(member);
        goto nomem;
    }
    for (size_t i = 0; i < nodes; i++) start[comp[i] + 2]++;
    for (long c = 0; c < count; c++) start[c + 2] += start[c + 1];
    for (size_t i = 0; i < nodes; i++) member[start[comp[i] + 1]++] = (int32_t)i;
    for (long c = 0; c < count; c++) {
        const size_t k = (size_t)(start[c + 1] - start[c]);
        if (k < 2 && !(k == 1 && has_loop(&d, member[start[c]]))) continue; /* no cycle */
        const double rho = power_rho(&d, comp, member + start[c], k, v, w);
        if (rho > best_rho + 1e-9) best_rho = rho, best = (int32_t)c;
    }
    if (best >= 0) {
        const size_t k = (size_t)(start[best + 1] - start[best]);
        power_rho(&d, comp, member + start[best], k, v, w);
        out->component = (long)k;
        const double rho = collatz_wielandt(&d, comp, member + start[best], k, v, precision);
        if (rho > 1.0) {
            arb_t x;
            arf_t lo;
            arb_init(x), arf_init(lo);
            arb_set_d(x, rho), arb_log(x, x, precision), arb_get_lbound_arf(lo, x, precision);
            out->rho = rho, out->entropy = fmax(0.0, arf_get_d(lo, ARF_RND_FLOOR));
            arb_clear(x), arf_clear(lo);
        }
    }
    free(start), free(member);
    goto done;
nomem:
    status = gb_error_set(GB_ENOMEM, "out of memory for the index map's regions");
done:
    free(region), free(gen_region), free(local), free(col_start), free(col_row), free(dims), free(mask);
    free(touched), free(comp), free(acc), free(v), free(w), free(d.start), free(d.next);
    return status;
}
