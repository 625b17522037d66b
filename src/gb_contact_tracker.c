/* gb_contact_tracker — the exact grid search along a trajectory (see gb_contact.h): a descent over the
 * vertices of the nodes' convex hull, warm-started at the previous answer, and a short certified
 * neighbourhood search around where it stops. It returns the brute-force node bit for bit.
 *
 * Why the hull. The lowest node for a vertical d minimises the linear function h = d·x over the nodes,
 * and a linear function over a finite point set is least at a vertex of its convex hull. On a convex
 * polytope a vertex no higher than its neighbours (along the hull's edges) is the lowest of all, so a
 * descent from vertex to lower neighbour ends at the minimum; along a trajectory the previous answer is
 * the minimum or next to it, and a query costs the heights of a vertex's few neighbours.
 *
 * Why the answer is brute force's, rounding and ties included. Heights are computed by node_height,
 * the one rounding of d·x every grid search shares, with an error below 1e-15 (|x| ≈ 1). Let h* be the
 * computed height where the descent stops.
 *  - Every hull vertex whose computed height could be the least lies within TIE of h*: the exact
 *    sublevel set {v : d·v ≤ c} of a polytope's vertices is connected along edges (from any of them a
 *    decreasing path leads to the minimum), so a search from the stopping vertex over the vertices with
 *    computed height ≤ h* + TIE reaches every one of them.
 *  - A node that is not a hull vertex lies inside the hull. If it is deeper than COPLANAR below every
 *    facet plane, its exact height exceeds the minimum by more than COPLANAR (moving down along −d it
 *    stays inside for that distance), far more than any rounding: it can never be brute force's answer.
 *    The nodes within COPLANAR of a facet are Qhull's coplanar points (option Qc with U = COPLANAR,
 *    each kept with its nearest facet): repeated nodes (the poles and the seam of the linspace
 *    placement) and vertices lost to Qhull's merging of nearly coplanar facets. Every query examines
 *    all of them. (Kept with their facet's vertices instead, a seam node that Qhull filed under a
 *    neighbouring facet was missed on 90 of 10^5 random verticals of the linspace sphere.) The centred
 *    placement of Table 1 has none on either body.
 * Among the nodes examined the least computed height wins, ties to the lowest index, as in brute force.
 * Where Qhull cannot build the hull (a degenerate grid), the tracker falls back to the exact search over
 * the patch tree (gb_contact_grid_search), warm-started at the previous answer. */
#include "gb_contact_internal.h"

#include "gb_error.h"
#include "gb_file.h"
#include "gb_hash.h"
#include "gb_seal.h"

#include <libqhull_r/qhull_ra.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

_Static_assert(GB_CONTACT_GRID_MAX_NODES < UINT32_MAX, "node indices fit the tracker's 32-bit arrays");

static const double COPLANAR = 1e-12; /* Qhull's coplanar distance (option U) [body length] */
static const double TIE = 1e-11;      /* the certified search's margin above h* [body length] */

struct gb_contact_tracker {
    const gb_contact_grid *grid;
    size_t vertices;          /* hull vertices; 0: no hull, the patch-tree search instead */
    uint32_t *node;           /* [vertices] the grid node of each vertex */
    uint32_t *edge_start;     /* [vertices + 1] CSR of the hull's edges (of its triangulated facets) */
    uint32_t *edge;
    uint32_t *near;           /* [coplanar] the nodes within COPLANAR of a facet, not vertices */
    size_t coplanar;
    uint32_t *mark, epoch;    /* the certified search's visited marks */
    uint32_t *queue;
    uint32_t start;           /* the vertex where the previous descent stopped */
    size_t last_index;        /* the previous answer (the fallback's warm start) */
};

void gb_contact_tracker_free(gb_contact_tracker *t)
{
    if (!t) return;
    free(t->node), free(t->edge_start), free(t->edge), free(t->near);
    free(t->mark), free(t->queue);
    free(t);
}

static int compare_pairs(const void *p, const void *q)
{
    const uint64_t a = *(const uint64_t *)p, b = *(const uint64_t *)q;
    return (a > b) - (a < b);
}

/* The pairs (a, b) (a < n) as CSR over `n` rows, each row's b ascending and without repeats: what sorting the pairs
 * and dropping repeats gives, by counting rows instead (a hull has ~12 pairs a row). */
static int build_csr(const uint64_t *pairs, size_t count, size_t n, uint32_t **start_out, uint32_t **list_out)
{
    uint32_t *start = calloc(n + 1, sizeof *start), *list = malloc((count ? count : 1) * sizeof *list);
    uint32_t *fill = malloc((n ? n : 1) * sizeof *fill);
    if (!start || !list || !fill) {
        free(start), free(list), free(fill);
        return gb_error_set(GB_ENOMEM, "out of memory for the contact tracker");
    }
    for (size_t k = 0; k < count; k++) start[(pairs[k] >> 32) + 1]++;
    for (size_t v = 0; v < n; v++) start[v + 1] += start[v], fill[v] = start[v];
    for (size_t k = 0; k < count; k++) list[fill[pairs[k] >> 32]++] = (uint32_t)pairs[k];
    size_t m = 0;
    for (size_t v = 0; v < n; v++) { /* each row sorted by insertion, its repeats dropped, moved down to m */
        const uint32_t from = start[v], to = start[v + 1];
        for (uint32_t i = from + 1; i < to; i++) {
            const uint32_t b = list[i];
            uint32_t j = i;
            for (; j > from && list[j - 1] > b; j--) list[j] = list[j - 1];
            list[j] = b;
        }
        start[v] = (uint32_t)m;
        for (uint32_t i = from; i < to; i++)
            if (i == from || list[i] != list[i - 1]) list[m++] = list[i];
    }
    start[n] = (uint32_t)m;
    free(fill);
    *start_out = start, *list_out = list;
    return GB_OK;
}

/* The hull of the grid's nodes: vertices, edges and coplanar nodes. GB_ENUMERIC when Qhull fails. */
static int build_hull(gb_contact_tracker *t)
{
    const gb_contact_grid *g = t->grid;
    FILE *errors = tmpfile();
    qhT qh_storage, *qh = &qh_storage;
    qh_zero(qh, errors);
    char command[64];
    snprintf(command, sizeof command, "qhull Qt Qc U%g", COPLANAR);
    int status = GB_OK;
    const int exitcode = qh_new_qhull(qh, 3, (int)g->size, g->x, False, command, NULL, errors);
    uint32_t *vertex_of = NULL;
    uint64_t *edges = NULL, *nears = NULL;
    if (exitcode) status = gb_error_set(GB_ENUMERIC, "Qhull could not build the hull of the grid (code %d)", exitcode);
    if (!status) {
        vertex_of = malloc(g->size * sizeof *vertex_of);
        edges = malloc(6 * (size_t)qh->num_facets * sizeof *edges);
        if (!vertex_of || !edges) status = gb_error_set(GB_ENOMEM, "out of memory for the contact tracker");
    }
    size_t vertices = 0, nedges = 0, nnear = 0, near_cap = 0;
    if (!status) {
        for (size_t k = 0; k < g->size; k++) vertex_of[k] = UINT32_MAX;
        vertexT *vertex, **vertexp;
        facetT *facet;
        FORALLvertices vertex_of[qh_pointid(qh, vertex->point)] = (uint32_t)vertices++;
        t->node = malloc((vertices ? vertices : 1) * sizeof *t->node);
        if (!t->node) status = gb_error_set(GB_ENOMEM, "out of memory for the contact tracker");
        FORALLvertices if (t->node) t->node[vertex_of[qh_pointid(qh, vertex->point)]] = (uint32_t)qh_pointid(qh, vertex->point);
        FORALLfacets {
            if (status) break;
            uint32_t v[3];
            int nv = 0;
            FOREACHvertex_(facet->vertices) if (nv < 3) v[nv++] = vertex_of[qh_pointid(qh, vertex->point)];
            if (nv != 3 || qh_setsize(qh, facet->vertices) != 3) {
                status = gb_error_set(GB_ENUMERIC, "Qhull returned a facet that is not a triangle");
                break;
            }
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++)
                    if (a != b) edges[nedges++] = (uint64_t)v[a] << 32 | v[b];
            pointT *point, **pointp;
            FOREACHpoint_(facet->coplanarset) {
                if (nnear == near_cap) {
                    near_cap = 2 * near_cap + 16;
                    uint64_t *grown = realloc(nears, near_cap * sizeof *nears);
                    if (!grown) {
                        status = gb_error_set(GB_ENOMEM, "out of memory for the contact tracker");
                        break;
                    }
                    nears = grown;
                }
                nears[nnear++] = (uint32_t)qh_pointid(qh, point);
            }
        }
    }
    if (!status) status = build_csr(edges, nedges, vertices, &t->edge_start, &t->edge);
    if (!status && nnear) { /* each coplanar node once, in index order */
        qsort(nears, nnear, sizeof *nears, compare_pairs);
        t->near = malloc(nnear * sizeof *t->near);
        if (!t->near) status = gb_error_set(GB_ENOMEM, "out of memory for the contact tracker");
        for (size_t k = 0; !status && k < nnear; k++)
            if (!k || nears[k] != nears[k - 1]) t->near[t->coplanar++] = (uint32_t)nears[k];
    }
    if (!status) {
        t->mark = calloc(vertices, sizeof *t->mark);
        t->queue = malloc(vertices * sizeof *t->queue);
        if (!t->mark || !t->queue) status = gb_error_set(GB_ENOMEM, "out of memory for the contact tracker");
    }
    if (!status) t->vertices = vertices;
    free(vertex_of), free(edges), free(nears);
    qh_freeqhull(qh, !qh_ALL);
    int curlong, totlong;
    qh_memfreeshort(qh, &curlong, &totlong);
    if (errors) fclose(errors);
    return status;
}

int gb_contact_tracker_create(const gb_contact_grid *grid, gb_contact_tracker **out)
{
    *out = NULL;
    gb_contact_tracker *t = calloc(1, sizeof *t);
    if (!t) return gb_error_set(GB_ENOMEM, "out of memory for the contact tracker");
    t->grid = grid;
    t->last_index = SIZE_MAX;
    const int status = build_hull(t);
    if (status == GB_ENOMEM) {
        gb_contact_tracker_free(t);
        return status;
    }
    if (status) { /* no hull: the patch-tree search, with everything the hull would have used freed */
        free(t->node), free(t->edge_start), free(t->edge), free(t->near);
        free(t->mark), free(t->queue);
        t->node = t->edge_start = t->edge = t->near = t->mark = t->queue = NULL;
        t->vertices = t->coplanar = 0;
    }
    *out = t;
    return GB_OK;
}

size_t gb_contact_tracker_vertices(const gb_contact_tracker *t) { return t->vertices; }

/* Keep (h, k) when lower than the best, or equal with a lower index. */
static inline void keep_lowest(double h, size_t k, double *best, size_t *best_index)
{
    if (h < *best || (h == *best && k < *best_index)) *best = h, *best_index = k;
}

int gb_contact_tracker_find(gb_contact_tracker *t, const double zb[3], gb_contact_node *out)
{
    if (!t->vertices) {
        const int status = gb_contact_grid_search(t->grid, zb, t->last_index, out);
        if (!status) t->last_index = out->index;
        return status;
    }
    double d[3];
    const int status = gb_contact_unit_vertical(zb, d);
    if (status) return status;
    const double *x = t->grid->x;
    size_t visited = 1;
    /* Descent: to the lowest neighbour while it is strictly lower. */
    uint32_t v = t->start;
    double h = node_height(d, x + 3 * (size_t)t->node[v]);
    for (;;) {
        uint32_t next = v;
        double lowest = h;
        for (uint32_t e = t->edge_start[v]; e < t->edge_start[v + 1]; e++) {
            const uint32_t w = t->edge[e];
            const double hw = node_height(d, x + 3 * (size_t)t->node[w]);
            visited++;
            if (hw < lowest) lowest = hw, next = w;
        }
        if (next == v) break;
        v = next, h = lowest;
    }
    t->start = v;
    /* The certified search: the coplanar nodes, and every vertex within TIE of h* connected to v. */
    if (++t->epoch == 0) { /* the marks wrapped around: clear them */
        memset(t->mark, 0, t->vertices * sizeof *t->mark);
        t->epoch = 1;
    }
    double best = h;
    size_t best_index = t->node[v];
    const double limit = h + TIE;
    for (size_t n = 0; n < t->coplanar; n++) keep_lowest(node_height(d, x + 3 * (size_t)t->near[n]), t->near[n], &best, &best_index);
    visited += t->coplanar;
    size_t head = 0, tail = 0;
    t->queue[tail++] = v;
    t->mark[v] = t->epoch;
    while (head < tail) {
        const uint32_t u = t->queue[head++];
        for (uint32_t e = t->edge_start[u]; e < t->edge_start[u + 1]; e++) {
            const uint32_t w = t->edge[e];
            if (t->mark[w] == t->epoch) continue;
            t->mark[w] = t->epoch;
            const double hw = node_height(d, x + 3 * (size_t)t->node[w]);
            visited++;
            if (hw <= limit) {
                keep_lowest(hw, t->node[w], &best, &best_index);
                t->queue[tail++] = w;
            }
        }
    }
    t->last_index = best_index;
    gb_contact_grid_fill_node(t->grid, best_index, best, visited, out);
    return GB_OK;
}

/* The hull file: a header, the graph's arrays and an FNV-1a checksum of everything before it. The header
 * names what the graph was built from (the nodes' bits, their count, COPLANAR and the Qhull release), so
 * that a file is taken only for the very grid it describes. */
enum { HULL_FILE_VERSION = 2 };
static const char hull_magic[8] = GB_CONTACT_HULL_MAGIC;
typedef struct hull_header {
    char magic[8];
    uint64_t version, nodes, nodes_hash, coplanar_bits, qhull_hash;
    uint64_t vertices, edges, coplanar;
} hull_header;

/* The fingerprint of the nodes' coordinates: FNV-1a over their 64-bit words (the file only has to tell
 * this grid from any other one, not resist a forger). */
static uint64_t nodes_hash(const gb_contact_grid *g)
{
    uint64_t h = GB_HASH_OFFSET;
    for (size_t k = 0; k < 3 * g->size; k++) {
        uint64_t w;
        memcpy(&w, &g->x[k], sizeof w);
        h = (h ^ w) * 1099511628211ull;
        h ^= h >> 29;
    }
    return h;
}

static void hull_header_of(const gb_contact_grid *g, hull_header *h)
{
    memset(h, 0, sizeof *h);
    memcpy(h->magic, hull_magic, sizeof h->magic);
    h->version = HULL_FILE_VERSION;
    h->nodes = g->size;
    h->nodes_hash = nodes_hash(g);
    memcpy(&h->coplanar_bits, &COPLANAR, sizeof h->coplanar_bits);
    h->qhull_hash = gb_hash_add(GB_HASH_OFFSET, qh_version, strlen(qh_version));
}

int gb_contact_tracker_save(const gb_contact_tracker *t, const char *path)
{
    if (!t->vertices) return gb_error_set(GB_EINVAL, "the contact tracker has no hull to save (Qhull could not build it)");
    hull_header h;
    hull_header_of(t->grid, &h);
    h.vertices = t->vertices, h.edges = t->edge_start[t->vertices], h.coplanar = t->coplanar;
    const size_t words = t->vertices + (t->vertices + 1) + h.edges + t->coplanar;
    const size_t size = sizeof h + words * sizeof(uint32_t) + GB_SEAL_BYTES;
    unsigned char *bytes = malloc(size), *p = bytes;
    if (!bytes) return gb_error_set(GB_ENOMEM, "out of memory for the hull file");
    memcpy(p, &h, sizeof h), p += sizeof h;
    memcpy(p, t->node, t->vertices * sizeof(uint32_t)), p += t->vertices * sizeof(uint32_t);
    memcpy(p, t->edge_start, (t->vertices + 1) * sizeof(uint32_t)), p += (t->vertices + 1) * sizeof(uint32_t);
    memcpy(p, t->edge, h.edges * sizeof(uint32_t)), p += h.edges * sizeof(uint32_t);
    if (t->coplanar) memcpy(p, t->near, t->coplanar * sizeof(uint32_t)), p += t->coplanar * sizeof(uint32_t);
    int status = gb_seal_compute(&(gb_seal_piece){bytes, (size_t)(p - bytes)}, 1, p);
    if (status) status = gb_error_set(status, "cannot seal the hull file %s: %s", path, gb_error_message());
    else status = gb_file_write_atomically(path, bytes, size);
    free(bytes);
    return status;
}

/* Copy `count` 32-bit words from the file's bytes into a new array (at least one element). */
static uint32_t *take_words(const unsigned char **p, size_t count)
{
    uint32_t *a = malloc((count ? count : 1) * sizeof *a);
    if (a && count) memcpy(a, *p, count * sizeof *a);
    *p += count * sizeof *a;
    return a;
}

/* Why the bytes are not a hull of this grid (NULL when they are): header, seal, sizes, and every
 * index within its range (a vertex a node, an edge's end a vertex, the CSR's starts in order). */
static const char *hull_refused(const gb_contact_grid *g, const unsigned char *data, size_t size, hull_header *have)
{
    hull_header want;
    hull_header_of(g, &want);
    if (size < sizeof *have + GB_SEAL_BYTES) return "it is too short to be a hull file";
    memcpy(have, data, sizeof *have);
    if (memcmp(have->magic, want.magic, sizeof want.magic) || have->version != want.version) return "it is not a hull file of this build";
    if (have->nodes != want.nodes || have->nodes_hash != want.nodes_hash || have->coplanar_bits != want.coplanar_bits)
        return "it was built for other grid nodes (another body, beta, grid or placement)";
    if (have->qhull_hash != want.qhull_hash) return "it was built by another release of Qhull";
    if (!have->vertices || have->vertices > g->size || have->coplanar > g->size || have->edges > 6 * have->vertices)
        return "its sizes are out of range";
    const uint64_t words = 2 * have->vertices + 1 + have->edges + have->coplanar;
    if (size != sizeof *have + words * sizeof(uint32_t) + GB_SEAL_BYTES) return "its size does not match its header";
    if (!gb_seal_verify(&(gb_seal_piece){data, size - GB_SEAL_BYTES}, 1, data + size - GB_SEAL_BYTES))
        return "its seal does not verify: damaged, changed since it was written, or written under another key (see "
               "GOMBOC_KEY)";
    return NULL;
}

int gb_contact_tracker_load_buffer(const gb_contact_grid *grid, const unsigned char *data, size_t size, const char *name,
                                   gb_contact_tracker **out)
{
    *out = NULL;
    hull_header h;
    const char *why = hull_refused(grid, data, size, &h);
    gb_contact_tracker *t = NULL;
    if (!why) {
        t = calloc(1, sizeof *t);
        if (!t) return gb_error_set(GB_ENOMEM, "out of memory for the contact tracker");
        t->grid = grid;
        t->last_index = SIZE_MAX;
        const unsigned char *p = data + sizeof h;
        t->node = take_words(&p, h.vertices);
        t->edge_start = take_words(&p, h.vertices + 1);
        t->edge = take_words(&p, h.edges);
        t->near = take_words(&p, h.coplanar);
        t->mark = calloc(h.vertices, sizeof *t->mark);
        t->queue = malloc(h.vertices * sizeof *t->queue);
        if (!t->node || !t->edge_start || !t->edge || !t->near || !t->mark || !t->queue) {
            gb_contact_tracker_free(t);
            return gb_error_set(GB_ENOMEM, "out of memory for the contact tracker");
        }
        t->vertices = h.vertices, t->coplanar = h.coplanar;
        for (size_t k = 0; !why && k < h.vertices; k++)
            if (t->node[k] >= grid->size) why = "a vertex is not a node";
        if (!why && (t->edge_start[0] != 0 || t->edge_start[h.vertices] != h.edges)) why = "its edge lists do not add up";
        for (size_t k = 0; !why && k < h.vertices; k++)
            if (t->edge_start[k] > t->edge_start[k + 1]) why = "its edge lists are out of order";
        for (size_t k = 0; !why && k < h.edges; k++)
            if (t->edge[k] >= h.vertices) why = "an edge ends outside the hull";
        for (size_t k = 0; !why && k < h.coplanar; k++)
            if (t->near[k] >= grid->size) why = "a coplanar node is not a node";
    }
    if (why) {
        gb_contact_tracker_free(t);
        return gb_error_set(GB_EIO, "hull file %s is refused: %s", name, why);
    }
    *out = t;
    return GB_OK;
}

/* The largest hull file of this grid. */
static size_t file_limit(const gb_contact_grid *grid)
{
    /* no hull of this grid is larger: every node a vertex and coplanar, fewer than 6 directed edges a vertex */
    return sizeof(hull_header) + (9 * grid->size + 1) * sizeof(uint32_t) + GB_SEAL_BYTES;
}

int gb_contact_tracker_load(const gb_contact_grid *grid, const char *path, gb_contact_tracker **out)
{
    *out = NULL;
    char *data;
    size_t size;
    const int status = gb_file_read(path, file_limit(grid), "hull file", "a hull file this command wrote",
                                    &data, &size);
    if (status) return gb_error_set(GB_EIO, "hull file refused: %s", gb_error_message());
    const int loaded = gb_contact_tracker_load_buffer(grid, (const unsigned char *)data, size, path, out);
    free(data);
    return loaded;
}
