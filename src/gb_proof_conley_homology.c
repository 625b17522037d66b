/* gb_proof_conley_homology — H_*(P1, P0; Z2) of a cubical pair on the grid and the index map on H_1.
 *
 * The relative complex: the squares of Q = P1 ∖ P0, the edges and vertices of P1's boxes that are not faces of a box of
 * P0. Its H_1 by tree–cotree: T a spanning forest of the graph of its vertices and edges with every vertex of P0 taken
 * as one vertex G (grown from G first), C a spanning forest of the graph of its squares and one vertex VOID for the
 * outside of P1 (grown from VOID first) over the edges not in T; the edges in neither, L, are H_1's generators. The
 * generator of e ∈ L is its cycle e + (T's path between e's ends); the cocycle of e is e + (C's path between the two
 * sides of e): it meets every square's boundary an even number of times and, among the generators' cycles, only e's.
 * So the coordinate of a relative cycle z along e is |z ∩ cocycle(e)| mod 2, computed for every e at once from W(x),
 * the parity of z's edges on C's path from a square x to its root: [e ∈ z] + W(a) + W(b), a and b e's sides.
 * Ranks: rank ∂1 = |T|, rank ∂2 = |Q| − h2 (h2 the components of squares the outside does not reach over any edge); the
 * decomposition is checked: |C| must equal rank ∂2, or the function refuses.
 *
 * The index map: f_* from the chain selector φ of the carrier Φ(σ) = ∩ F(R) over the boxes R ⊂ P1 that hold the cell σ
 * (a rectangle of boxes, non-empty, holding f(σ), growing from a cell to its cofaces): φ(v) the rectangle's lowest
 * left corner, φ(edge) the path right or left, then up or down, between its ends' images, inside the edge's rectangle.
 * A chain map carried by an acyclic carrier that carries f induces f_* (acyclic carriers; Kaczynski, Mischaikow and
 * Mrozek, Computational Homology, 2004, ch. 6); cells of P0 go into P̄0 = P0 ∪ E. With the exit condition
 * (E ∩ P1 ⊂ P0, cell by cell) the pairs (P1, P0) and (P̄1, P̄0) have the same relative complex, so the inclusion's
 * inverse is the identity on it: the coordinates of φ(z) with its edges outside the relative complex dropped. */
#include "gb_proof_conley_homology_internal.h"

#include "gb_error.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- a table of cells: number on the grid → index */

typedef struct cell_table {
    uint64_t *key; /* key + 1; 0 marks an empty slot */
    int32_t *value;
    size_t mask;
} cell_table;

static int table_init(cell_table *t, size_t count)
{
    size_t size = 16;
    while (size < 2 * count + 16) size *= 2;
    t->key = calloc(size, sizeof *t->key);
    t->value = malloc(size * sizeof *t->value);
    t->mask = size - 1;
    return t->key && t->value ? GB_OK : gb_error_set(GB_ENOMEM, "out of memory for the relative complex's cells");
}

static void table_free(cell_table *t) { free(t->key), free(t->value); }

static size_t table_slot(const cell_table *t, uint64_t key)
{
    size_t s = (size_t)((key + 1) * 0x9E3779B97F4A7C15ull >> 17) & t->mask;
    while (t->key[s] && t->key[s] != key + 1) s = (s + 1) & t->mask;
    return s;
}

static void table_put(cell_table *t, uint64_t key, int32_t value)
{
    const size_t s = table_slot(t, key);
    t->key[s] = key + 1, t->value[s] = value;
}

static int32_t table_get(const cell_table *t, uint64_t key)
{
    const size_t s = table_slot(t, key);
    return t->key[s] ? t->value[s] : -1;
}

/* ---------------------------------------------------------------- the relative complex */

typedef struct complex {
    const conley_grid *g;
    long V;               /* n + 1: vertices a side */
    size_t squares;       /* |Q| */
    uint32_t *square_box; /* Q's boxes */
    cell_table square_of; /* box → 1 + index (0 is VOID) */
    size_t edges;
    uint64_t *edge_id;   /* 2 (j V + i) + 0 horizontal ((i, j)–(i + 1, j)), + 1 vertical ((i, j)–(i, j + 1)) */
    int32_t (*ends)[2];  /* vertex nodes (0 = G) */
    int32_t (*sides)[2]; /* square nodes (0 = VOID) */
    cell_table edge_of;  /* edge id → index */
    size_t nodes;        /* vertex nodes, G included */
} complex;

static int p0_vertex(const conley_grid *g, long i, long j)
{
    return conley_is(g, i - 1, j - 1, CONLEY_P0) || conley_is(g, i, j - 1, CONLEY_P0) ||
           conley_is(g, i - 1, j, CONLEY_P0) || conley_is(g, i, j, CONLEY_P0);
}

static int add_edge(complex *c, cell_table *vertex_of, long i, long j, int vertical, long side_i, long side_j,
                    int32_t this_square)
{
    const conley_grid *g = c->g;
    if (conley_is(g, side_i, side_j, CONLEY_P0)) return 0; /* a face of P0 */
    const size_t k = c->edges++;
    c->edge_id[k] = 2 * (uint64_t)(j * c->V + i) + (uint64_t)vertical;
    const long ends[2][2] = {{i, j}, {vertical ? i : i + 1, vertical ? j + 1 : j}};
    for (int e = 0; e < 2; e++) {
        int32_t node = 0;
        if (!p0_vertex(g, ends[e][0], ends[e][1])) {
            const uint64_t id = (uint64_t)(ends[e][1] * c->V + ends[e][0]);
            node = table_get(vertex_of, id);
            if (node < 0) node = (int32_t)c->nodes++, table_put(vertex_of, id, node);
        }
        c->ends[k][e] = node;
    }
    const int32_t other =
        conley_is(g, side_i, side_j, CONLEY_Q) ? table_get(&c->square_of, (uint64_t)(side_j * g->n + side_i)) : 0;
    /* sides in the order (below, above) or (left, right) */
    const int other_first = vertical ? side_i < i : side_j < j;
    c->sides[k][0] = other_first ? other : this_square;
    c->sides[k][1] = other_first ? this_square : other;
    table_put(&c->edge_of, c->edge_id[k], (int32_t)k);
    return 1;
}

/* Every box of Q owns its lower and left edges, and its upper and right ones where no box of Q lies beyond. */
static int complex_build(const conley_grid *g, complex *c)
{
    memset(c, 0, sizeof *c);
    c->g = g, c->V = g->n + 1;
    for (size_t k = 0; k < g->p1_count; k++) c->squares += (g->state[g->p1[k]] & CONLEY_Q) != 0;
    cell_table vertex_of = {0};
    c->square_box = malloc((c->squares + 1) * sizeof *c->square_box);
    c->edge_id = malloc((4 * c->squares + 1) * sizeof *c->edge_id);
    c->ends = malloc((4 * c->squares + 1) * sizeof *c->ends);
    c->sides = malloc((4 * c->squares + 1) * sizeof *c->sides);
    if (!c->square_box || !c->edge_id || !c->ends || !c->sides || table_init(&c->square_of, c->squares) ||
        table_init(&c->edge_of, 4 * c->squares) || table_init(&vertex_of, 4 * c->squares)) {
        table_free(&vertex_of);
        return gb_error_set(GB_ENOMEM, "out of memory for the relative complex");
    }
    size_t q = 0;
    for (size_t k = 0; k < g->p1_count; k++)
        if (g->state[g->p1[k]] & CONLEY_Q)
            c->square_box[q] = g->p1[k], table_put(&c->square_of, g->p1[k], (int32_t)++q);
    c->nodes = 1; /* G */
    for (size_t s = 0; s < c->squares; s++) {
        const long i = (long)(c->square_box[s] % (uint32_t)g->n), j = (long)(c->square_box[s] / (uint32_t)g->n);
        const int32_t me = (int32_t)s + 1;
        add_edge(c, &vertex_of, i, j, 0, i, j - 1, me);
        add_edge(c, &vertex_of, i, j, 1, i - 1, j, me);
        if (!conley_is(g, i, j + 1, CONLEY_Q)) add_edge(c, &vertex_of, i, j + 1, 0, i, j + 1, me);
        if (!conley_is(g, i + 1, j, CONLEY_Q)) add_edge(c, &vertex_of, i + 1, j, 1, i + 1, j, me);
    }
    table_free(&vertex_of);
    return GB_OK;
}

static void complex_free(complex *c)
{
    free(c->square_box), free(c->edge_id), free(c->ends), free(c->sides);
    table_free(&c->square_of), table_free(&c->edge_of);
}

/* ---------------------------------------------------------------- spanning forests */

/* A forest grown breadth first over the edges allowed, from node 0 first: each node's parent, parent edge (−1 at a
 * root), depth, and the order reached; used[e] set for the forest's edges. Returns the number of roots, or −1. */
typedef struct forest {
    int32_t *parent, *edge, *depth, *order;
} forest;

static long forest_grow(size_t nodes, size_t edges, int32_t (*link)[2], const uint8_t *allowed, uint8_t *used,
                        forest *f)
{
    int32_t *start = calloc(nodes + 1, sizeof *start), *adj = malloc((2 * edges + 1) * sizeof *adj);
    f->parent = malloc(nodes * sizeof *f->parent), f->edge = malloc(nodes * sizeof *f->edge);
    f->depth = malloc(nodes * sizeof *f->depth), f->order = malloc(nodes * sizeof *f->order);
    if (!start || !adj || !f->parent || !f->edge || !f->depth || !f->order) {
        free(start), free(adj);
        return -1;
    }
    for (size_t e = 0; e < edges; e++)
        if (allowed[e]) start[link[e][0] + 1]++, start[link[e][1] + 1]++;
    for (size_t v = 0; v < nodes; v++) start[v + 1] += start[v];
    int32_t *fill = malloc((nodes + 1) * sizeof *fill);
    if (!fill) {
        free(start), free(adj);
        return -1;
    }
    memcpy(fill, start, (nodes + 1) * sizeof *fill);
    for (size_t e = 0; e < edges; e++)
        if (allowed[e]) adj[fill[link[e][0]]++] = (int32_t)e, adj[fill[link[e][1]]++] = (int32_t)e;
    free(fill);
    for (size_t v = 0; v < nodes; v++) f->parent[v] = -2;
    long roots = 0;
    size_t head = 0, tail = 0;
    for (size_t r = 0; r < nodes; r++) {
        if (f->parent[r] != -2) continue;
        roots++;
        f->parent[r] = -1, f->edge[r] = -1, f->depth[r] = 0, f->order[tail++] = (int32_t)r;
        while (head < tail) {
            const int32_t u = f->order[head++];
            for (int32_t a = start[u]; a < start[u + 1]; a++) {
                const int32_t e = adj[a], w = link[e][0] == u ? link[e][1] : link[e][0];
                if (f->parent[w] != -2) continue;
                f->parent[w] = u, f->edge[w] = e, f->depth[w] = f->depth[u] + 1, f->order[tail++] = w;
                used[e] = 1;
            }
        }
    }
    free(start), free(adj);
    return roots;
}

static void forest_free(forest *f) { free(f->parent), free(f->edge), free(f->depth), free(f->order); }

/* ---------------------------------------------------------------- the chain selector */

/* Φ of the cell whose boxes (up to four, k of them) are listed: the intersection of their rectangles, P1's only. */
static void carrier(const conley_grid *g, const long (*boxes)[2], int k, long out[4])
{
    out[0] = out[2] = -(1L << 40), out[1] = out[3] = 1L << 40;
    for (int b = 0; b < k; b++) {
        if (!conley_is(g, boxes[b][0], boxes[b][1], CONLEY_P1)) continue;
        const int32_t *r = g->rect[conley_p1_position(g, (uint32_t)(boxes[b][1] * g->n + boxes[b][0]))];
        if (r[0] > out[0]) out[0] = r[0];
        if (r[1] < out[1]) out[1] = r[1];
        if (r[2] > out[2]) out[2] = r[2];
        if (r[3] < out[3]) out[3] = r[3];
    }
}

static void phi_vertex(const conley_grid *g, long i, long j, long out[2])
{
    const long boxes[4][2] = {{i - 1, j - 1}, {i, j - 1}, {i - 1, j}, {i, j}};
    long r[4];
    carrier(g, boxes, 4, r);
    out[0] = r[0], out[1] = r[2];
}

/* Adds φ(edge) to the chain in bit 0 of `mark` (over the relative complex's edges; those outside it are dropped); bit 1
 * lists an edge in `touched` once. */
static void phi_edge(const complex *c, uint64_t id, uint8_t *mark, int32_t *touched, size_t *touched_count)
{
    const conley_grid *g = c->g;
    const long v = (long)(id / 2), i = v % c->V, j = v / c->V;
    const int vertical = (int)(id & 1);
    long p[2], q[2];
    phi_vertex(g, i, j, p);
    phi_vertex(g, vertical ? i : i + 1, vertical ? j + 1 : j, q);
    long x = p[0], y = p[1];
    while (x != q[0] || y != q[1]) {
        long ei = x, ej = y;
        int ev = 0;
        if (x < q[0])
            x++;
        else if (x > q[0])
            ei = --x;
        else if (y < q[1])
            ev = 1, y++;
        else
            ev = 1, ej = --y;
        if (ei < 0 || ej < 0 || ei > g->n || ej > g->n) continue; /* beyond the grid: in E */
        const int32_t k = table_get(&c->edge_of, 2 * (uint64_t)(ej * c->V + ei) + (uint64_t)ev);
        if (k < 0) continue;
        if (!(mark[k] & 2)) touched[(*touched_count)++] = k, mark[k] |= 2; /* listed once, for the reset */
        mark[k] ^= 1;
    }
}

/* ---------------------------------------------------------------- H_1 and the index map */

int conley_homology_compute(const conley_grid *g, conley_homology *out, char *failure, size_t failure_size)
{
    memset(out, 0, sizeof *out);
    complex c;
    int status = complex_build(g, &c);
    uint8_t *allowed = NULL, *in_T = NULL, *in_C = NULL, *mark = NULL, *W = NULL;
    int32_t *up = NULL, *touched = NULL, *generator = NULL;
    forest T = {0}, C = {0};
    if (status) goto done;
    const size_t E = c.edges, D = c.squares + 1;
    allowed = malloc(E + 1), in_T = calloc(E + 1, 1), in_C = calloc(E + 1, 1), mark = calloc(E + 1, 1);
    W = malloc(D), up = malloc(D * sizeof *up), touched = malloc((E + 1) * sizeof *touched);
    if (!allowed || !in_T || !in_C || !mark || !W || !up || !touched) {
        status = gb_error_set(GB_ENOMEM, "out of memory for H_1");
        goto done;
    }
    memset(allowed, 1, E + 1);
    const long primal_roots = forest_grow(c.nodes, E, c.ends, allowed, in_T, &T);
    for (size_t e = 0; e < E; e++) allowed[e] = !in_T[e];
    const long dual_roots = primal_roots < 0 ? -1 : forest_grow(D, E, c.sides, allowed, in_C, &C);
    if (dual_roots < 0) {
        status = gb_error_set(GB_ENOMEM, "out of memory for H_1's forests");
        goto done;
    }
    /* rank ∂2 over every edge */
    for (size_t x = 0; x < D; x++) up[x] = (int32_t)x;
    for (size_t e = 0; e < E; e++) {
        const long a = conley_root(up, c.sides[e][0]), b = conley_root(up, c.sides[e][1]);
        if (a != b) up[a > b ? a : b] = (int32_t)(a < b ? a : b); /* the root of VOID's component stays 0 */
    }
    long h2 = 0, tree = 0, cotree = 0;
    for (size_t x = 1; x < D; x++) h2 += conley_root(up, (long)x) == (long)x;
    for (size_t e = 0; e < E; e++) tree += in_T[e], cotree += in_C[e];
    const long rank2 = (long)c.squares - h2;
    out->h0 = primal_roots - 1, out->h2 = h2, out->h1 = (long)E - tree - rank2;
    if (cotree != rank2) {
        snprintf(failure, failure_size, "tree-cotree: the cotree has %ld edges, rank of the squares' boundaries %ld",
                 cotree, rank2);
        status = gb_error_set(GB_ENUMERIC, "%s", failure);
        goto done;
    }
    size_t L = 0;
    generator = malloc((size_t)(out->h1 + 1) * sizeof *generator);
    out->square = malloc((size_t)(out->h1 + 1) * sizeof *out->square);
    out->words = ((size_t)out->h1 + 63) / 64;
    out->map = calloc((size_t)out->h1 * out->words + 1, sizeof *out->map);
    if (!generator || !out->square || !out->map) {
        status = gb_error_set(GB_ENOMEM, "out of memory for the index map");
        goto done;
    }
    for (size_t e = 0; e < E; e++)
        if (!in_T[e] && !in_C[e]) {
            generator[L] = (int32_t)e;
            const int32_t s = c.sides[e][0] ? c.sides[e][0] : c.sides[e][1];
            out->square[L++] = (int32_t)c.square_box[s - 1];
        }
    out->generators = L;
    for (size_t col = 0; col < L; col++) {
        size_t touched_count = 0;
        /* the generator's cycle: its edge and T's path between its ends, mapped edge by edge */
        int32_t u = c.ends[generator[col]][0], v = c.ends[generator[col]][1];
        phi_edge(&c, c.edge_id[generator[col]], mark, touched, &touched_count);
        while (u != v) {
            int32_t *w = T.depth[u] >= T.depth[v] ? &u : &v;
            phi_edge(&c, c.edge_id[T.edge[*w]], mark, touched, &touched_count);
            *w = T.parent[*w];
        }
        for (size_t k = 0; k < D; k++) {
            const int32_t x = C.order[k];
            W[x] = C.parent[x] < 0 ? 0 : (uint8_t)(W[C.parent[x]] ^ (mark[C.edge[x]] & 1));
        }
        for (size_t row = 0; row < L; row++) {
            const int32_t f = generator[row];
            if ((mark[f] & 1) ^ W[c.sides[f][0]] ^ W[c.sides[f][1]])
                out->map[row * out->words + col / 64] |= 1ull << (col % 64);
        }
        for (size_t k = 0; k < touched_count; k++) mark[touched[k]] = 0;
    }
done:
    if (status) conley_homology_free(out);
    forest_free(&T), forest_free(&C);
    free(allowed), free(in_T), free(in_C), free(mark), free(W), free(up), free(touched), free(generator);
    if (c.g) complex_free(&c);
    return status;
}

void conley_homology_free(conley_homology *h)
{
    free(h->map), free(h->square);
    h->map = NULL, h->square = NULL;
}
