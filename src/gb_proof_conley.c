/* gb_proof_conley — the grid and F on Arb's balls, an index pair's three conditions and its construction from a set
 * of boxes (see gb_proof_conley.h); H_1 and the index map in gb_proof_conley_homology.c, the regions and the sofic
 * shift's entropy in gb_proof_conley_sofic.c. */
#include "gb_proof_conley.h"
#include "gb_proof_conley_grid_internal.h"
#include "gb_proof_conley_homology_internal.h"
#include "gb_proof_conley_sofic_internal.h"
#include "gb_proof_flow_internal.h"
#include "gb_proof_internal.h"

#include "gb_error.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

gb_proof_conley_def gb_proof_conley_def_default(void)
{
    return (gb_proof_conley_def){.precision = 128, .depth = 6, .region_dimension = 6};
}

/* ---------------------------------------------------------------- the definition */

static int check_side(const char *name, gb_proof_interval side, int depth, double *h)
{
    const double w = side.hi - side.lo;
    int e;
    if (!(isfinite(side.lo) && isfinite(side.hi) && w > 0.0) || frexp(w, &e) != 0.5 ||
        fmod(side.lo, ldexp(w, -depth)) != 0.0)
        return gb_error_set(GB_EDOM,
                            "%s = [%g, %g] is not allowed: its length must be a power of two and its lower end "
                            "a multiple of the boxes' side (length / 2^depth)",
                            name, side.lo, side.hi);
    *h = ldexp(w, -depth);
    return GB_OK;
}

static int check_boxes(const char *name, const uint32_t *boxes, size_t count, long n)
{
    for (size_t k = 0; k < count; k++) {
        const long i = (long)(boxes[k] % (uint32_t)n), j = (long)(boxes[k] / (uint32_t)n);
        if (boxes[k] >= (uint64_t)(n * n) || (k && boxes[k] <= boxes[k - 1]))
            return gb_error_set(
                GB_EDOM, "%s[%zu] = %u is out of order or range (allowed: numbers 0 ... %ld, strictly increasing)",
                name, k, boxes[k], n * n - 1);
        if (i == 0 || j == 0 || i == n - 1 || j == n - 1)
            return gb_error_set(GB_EDOM, "%s[%zu] = %u lies on the grid's edge (allowed: boxes 1 ... %ld a side)", name,
                                k, boxes[k], n - 2);
    }
    return GB_OK;
}

static int check_def(const gb_proof_conley_def *def, conley_grid *g)
{
    if (!def->map || def->map->dimension != 2)
        return gb_error_set(GB_EDOM, "map: its dimension is not 2 (allowed: a map of the plane, dimension 2)");
    int status = gb_proof_check_precision(def->precision);
    if (status) return status;
    if (def->depth < GB_PROOF_CONLEY_DEPTH_MIN || def->depth > GB_PROOF_CONLEY_DEPTH_MAX)
        return gb_error_set(GB_EDOM, "depth = %d is out of range (allowed: %d to %d)", def->depth,
                            GB_PROOF_CONLEY_DEPTH_MIN, GB_PROOF_CONLEY_DEPTH_MAX);
    if (def->region_dimension < 1 || def->region_dimension > GB_PROOF_CONLEY_REGION_DIMENSION_MAX)
        return gb_error_set(GB_EDOM, "region_dimension = %d is out of range (allowed: 1 to %d)", def->region_dimension,
                            GB_PROOF_CONLEY_REGION_DIMENSION_MAX);
    memset(g, 0, sizeof *g);
    g->depth = def->depth, g->n = 1L << def->depth, g->x0 = def->x.lo, g->y0 = def->y.lo;
    if ((status = check_side("x", def->x, def->depth, &g->hx)) ||
        (status = check_side("y", def->y, def->depth, &g->hy)))
        return status;
    return GB_OK;
}

/* ---------------------------------------------------------------- the grid and F */

/* The smallest k whose box's upper end reaches lo, and the largest whose lower end is at most hi, within −1 ... n
 * (every grid line x0 + k h is a double: h a power of two, x0 a multiple of it). */
static int32_t index_low(double lo, double x0, double h, long n)
{
    if (lo <= x0) return -1;
    if (lo > x0 + (double)n * h) return (int32_t)n;
    long k = (long)floor((lo - x0) / h) - 1;
    while (x0 + (double)(k + 1) * h < lo) k++;
    while (k >= 0 && x0 + (double)k * h >= lo) k--;
    return (int32_t)k;
}

static int32_t index_high(double hi, double x0, double h, long n)
{
    if (hi < x0) return -1;
    if (hi >= x0 + (double)n * h) return (int32_t)n;
    long k = (long)floor((hi - x0) / h);
    while (k > 0 && x0 + (double)k * h > hi) k--;
    while (x0 + (double)(k + 1) * h <= hi) k++;
    return (int32_t)k;
}

/* The state map and F on the boxes of the list g->p1 (P1, or N for the construction); F of a box also on the list
 * `known` (strictly increasing, with its rectangles; may be empty) is copied from it. */
static int grid_enclose(conley_grid *g, const gb_proof_field *map, long precision, const uint32_t *known,
                        int32_t (*known_rect)[4], size_t known_count)
{
    g->state = calloc((size_t)(g->n * g->n), 1);
    g->rect = malloc((g->p1_count + 1) * sizeof *g->rect);
    if (!g->state || !g->rect) return gb_error_set(GB_ENOMEM, "out of memory for a grid of depth %d", g->depth);
    field_balls F;
    gb_proof_flow_field_init(&F, map, 1, precision);
    arb_ptr x = _arb_vec_init(2), y = _arb_vec_init(2);
    int status = GB_OK;
    size_t at = 0;
    for (size_t k = 0; k < g->p1_count && !status; k++) {
        const long i = (long)(g->p1[k] % (uint32_t)g->n), j = (long)(g->p1[k] / (uint32_t)g->n);
        g->state[g->p1[k]] = CONLEY_P1;
        while (at < known_count && known[at] < g->p1[k]) at++;
        if (at < known_count && known[at] == g->p1[k]) {
            memcpy(g->rect[k], known_rect[at], sizeof g->rect[k]);
            continue;
        }
        gb_proof_ball_of(x + 0, (gb_proof_interval){g->x0 + (double)i * g->hx, g->x0 + (double)(i + 1) * g->hx},
                         precision);
        gb_proof_ball_of(x + 1, (gb_proof_interval){g->y0 + (double)j * g->hy, g->y0 + (double)(j + 1) * g->hy},
                         precision);
        gb_proof_flow_field_eval(&F, x, y);
        const gb_proof_interval u = gb_proof_interval_of(y + 0), v = gb_proof_interval_of(y + 1);
        if (!(isfinite(u.lo) && isfinite(u.hi) && isfinite(v.lo) && isfinite(v.hi))) {
            status = gb_error_set(GB_ENUMERIC, "the image of box %u is not finite", g->p1[k]);
            break;
        }
        g->rect[k][0] = index_low(u.lo, g->x0, g->hx, g->n), g->rect[k][1] = index_high(u.hi, g->x0, g->hx, g->n);
        g->rect[k][2] = index_low(v.lo, g->y0, g->hy, g->n), g->rect[k][3] = index_high(v.hi, g->y0, g->hy, g->n);
    }
    _arb_vec_clear(x, 2), _arb_vec_clear(y, 2);
    gb_proof_flow_field_clear(&F);
    return status;
}

static void grid_free(conley_grid *g)
{
    free(g->state), free(g->rect);
    g->state = NULL, g->rect = NULL;
}

/* F restricted to the boxes of the list carrying `flag`: successors by position in the list (CSR). */
typedef struct box_graph {
    int32_t *start, *next;
} box_graph;

static int graph_build(const conley_grid *g, int flag, box_graph *G)
{
    size_t edges = 0, room = 4 * g->p1_count + 16;
    G->start = malloc((g->p1_count + 1) * sizeof *G->start), G->next = malloc(room * sizeof *G->next);
    if (!G->start || !G->next) return gb_error_set(GB_ENOMEM, "out of memory for F's graph");
    for (size_t k = 0; k < g->p1_count; k++) {
        G->start[k] = (int32_t)edges;
        if (!(g->state[g->p1[k]] & flag)) continue;
        const int32_t *r = g->rect[k];
        for (long j = r[2] > 0 ? r[2] : 0; j <= r[3] && j < g->n; j++)
            for (long i = r[0] > 0 ? r[0] : 0; i <= r[1] && i < g->n; i++) {
                if (!(g->state[j * g->n + i] & flag)) continue;
                if (edges == room) {
                    int32_t *more = realloc(G->next, 2 * room * sizeof *more);
                    if (!more) return gb_error_set(GB_ENOMEM, "out of memory for F's graph");
                    G->next = more, room *= 2;
                }
                G->next[edges++] = (int32_t)conley_p1_position(g, (uint32_t)(j * g->n + i));
            }
    }
    G->start[g->p1_count] = (int32_t)edges;
    return GB_OK;
}

static void graph_free(box_graph *G) { free(G->start), free(G->next); }

/* G's predecessor lists, in the same form. */
static int graph_reverse(const conley_grid *g, const box_graph *G, box_graph *R)
{
    const size_t m = g->p1_count;
    R->start = calloc(m + 1, sizeof *R->start), R->next = malloc(((size_t)G->start[m] + 1) * sizeof *R->next);
    int32_t *cursor = malloc((m + 1) * sizeof *cursor);
    if (!R->start || !R->next || !cursor) {
        free(cursor);
        return gb_error_set(GB_ENOMEM, "out of memory for F's graph");
    }
    for (int32_t a = 0; a < G->start[m]; a++) R->start[G->next[a] + 1]++;
    for (size_t k = 0; k < m; k++) R->start[k + 1] += R->start[k];
    memcpy(cursor, R->start, (m + 1) * sizeof *cursor);
    for (size_t k = 0; k < m; k++)
        for (int32_t a = G->start[k]; a < G->start[k + 1]; a++) R->next[cursor[G->next[a]]++] = (int32_t)k;
    free(cursor);
    return GB_OK;
}

/* alive[k] for the boxes of the list carrying `flag` that lie on a bi-infinite path of G through such boxes: every box
 * without a successor or a predecessor left is taken out until none is. Returns their number, or −1. */
static long invariant_part(const conley_grid *g, int flag, const box_graph *G, const box_graph *R, uint8_t *alive)
{
    const size_t m = g->p1_count;
    int32_t *out = malloc((m + 1) * sizeof *out), *in = malloc((m + 1) * sizeof *in),
            *queue = malloc((m + 1) * sizeof *queue);
    if (!out || !in || !queue) {
        free(out), free(in), free(queue);
        return -1;
    }
    size_t head = 0, tail = 0;
    for (size_t k = 0; k < m; k++) {
        alive[k] = (g->state[g->p1[k]] & flag) != 0;
        out[k] = G->start[k + 1] - G->start[k], in[k] = R->start[k + 1] - R->start[k];
        if (alive[k] && (!out[k] || !in[k])) alive[k] = 0, queue[tail++] = (int32_t)k;
    }
    while (head < tail) {
        const int32_t k = queue[head++];
        for (int32_t a = G->start[k]; a < G->start[k + 1]; a++) {
            const int32_t w = G->next[a];
            if (alive[w] && --in[w] == 0) alive[w] = 0, queue[tail++] = w;
        }
        for (int32_t a = R->start[k]; a < R->start[k + 1]; a++) {
            const int32_t w = R->next[a];
            if (alive[w] && --out[w] == 0) alive[w] = 0, queue[tail++] = w;
        }
    }
    long count = 0;
    for (size_t k = 0; k < m; k++) count += alive[k];
    free(out), free(in), free(queue);
    return count;
}

/* The first of a box's eight neighbours lacking `flag`, as its number, or −1. */
static long neighbour_without(const conley_grid *g, uint32_t box, int flag)
{
    const long i = (long)(box % (uint32_t)g->n), j = (long)(box / (uint32_t)g->n);
    for (long dj = -1; dj <= 1; dj++)
        for (long di = -1; di <= 1; di++)
            if (!conley_is(g, i + di, j + dj, flag)) return (j + dj) * g->n + i + di;
    return -1;
}

/* ---------------------------------------------------------------- the three conditions */

static int fail(gb_proof_conley_result *out, const char *format, long a, long b)
{
    if (!out->failure[0]) snprintf(out->failure, sizeof out->failure, format, a, b);
    return 0;
}

static int positively_invariant(const conley_grid *g, gb_proof_conley_result *out)
{
    for (size_t k = 0; k < g->p1_count; k++) {
        if (!(g->state[g->p1[k]] & CONLEY_P0)) continue;
        const int32_t *r = g->rect[k];
        for (long j = r[2]; j <= r[3]; j++)
            for (long i = r[0]; i <= r[1]; i++)
                if (conley_is(g, i, j, CONLEY_Q))
                    return fail(out, "positive invariance: F of P0's box %ld meets box %ld of P1 \\ P0", (long)g->p1[k],
                                j * g->n + i);
    }
    return 1;
}

/* E's box (i, j) may share with P1 only faces of P0's boxes: an edge with a box of P0, a corner with a box of P1 \ P0
 * only when one of the corner's two other boxes is in P0. */
static int exit_box(const conley_grid *g, long i, long j, gb_proof_conley_result *out)
{
    static const int side[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}},
                     corner[4][2] = {{-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
    for (int s = 0; s < 4; s++)
        if (conley_is(g, i + side[s][0], j + side[s][1], CONLEY_Q))
            return fail(out, "exit set: box %ld of F(P1) \\ P1 shares an edge with box %ld of P1 \\ P0", j * g->n + i,
                        (j + side[s][1]) * g->n + i + side[s][0]);
    for (int s = 0; s < 4; s++) {
        const long a = i + corner[s][0], b = j + corner[s][1];
        if (conley_is(g, a, b, CONLEY_Q) && !conley_is(g, a, j, CONLEY_P0) && !conley_is(g, i, b, CONLEY_P0))
            return fail(out, "exit set: box %ld of F(P1) \\ P1 shares a corner with box %ld of P1 \\ P0", j * g->n + i,
                        b * g->n + a);
    }
    return 1;
}

static int exit_set(conley_grid *g, gb_proof_conley_result *out)
{
    int holds = 1;
    for (size_t k = 0; k < g->p1_count && holds; k++) {
        const int32_t *r = g->rect[k];
        for (long j = r[2] > 0 ? r[2] : 0; j <= r[3] && j < g->n && holds; j++)
            for (long i = r[0] > 0 ? r[0] : 0; i <= r[1] && i < g->n && holds; i++) {
                uint8_t *s = &g->state[j * g->n + i];
                if (*s & (CONLEY_P1 | CONLEY_E)) continue;
                *s |= CONLEY_E; /* beyond the grid E cannot touch P1: P1 keeps off the grid's edge */
                holds = exit_box(g, i, j, out);
            }
    }
    return holds;
}

/* ---------------------------------------------------------------- the proof */

static int load_pair(conley_grid *g, const gb_proof_conley_def *def)
{
    for (size_t k = 0; k < def->p0_count; k++) {
        const long at = conley_p1_position(g, def->p0[k]);
        if (at < 0)
            return gb_error_set(GB_EDOM, "p0[%zu] = %u is not a box of p1 (allowed: boxes of P1, as P0 lies in P1)", k,
                                def->p0[k]);
        g->state[def->p0[k]] |= CONLEY_P0;
    }
    for (size_t k = 0; k < g->p1_count; k++)
        if (!(g->state[g->p1[k]] & CONLEY_P0)) g->state[g->p1[k]] |= CONLEY_Q;
    return GB_OK;
}

int gb_proof_conley(const gb_proof_conley_def *def, gb_proof_conley_result *out)
{
    memset(out, 0, sizeof *out);
    const double start = gb_proof_cpu_seconds();
    conley_grid g;
    int status = check_def(def, &g);
    if (status) return status;
    if ((status = check_boxes("p1", def->p1, def->p1_count, g.n)) ||
        (status = check_boxes("p0", def->p0, def->p0_count, g.n)))
        return status;
    if (!def->p1_count) return gb_error_set(GB_EDOM, "p1_count = 0 (allowed: 1 or more boxes)");
    g.p1 = def->p1, g.p1_count = def->p1_count;
    box_graph G = {0}, R = {0};
    uint8_t *alive = NULL;
    conley_homology H = {0};
    if ((status = grid_enclose(&g, def->map, def->precision, NULL, NULL, 0)) || (status = load_pair(&g, def)))
        goto done;
    out->positively_invariant = positively_invariant(&g, out);
    out->exit_set = exit_set(&g, out);
    alive = malloc(g.p1_count + 1);
    if (!alive || (status = graph_build(&g, CONLEY_Q, &G)) || (status = graph_reverse(&g, &G, &R))) {
        status = status ? status : gb_error_set(GB_ENOMEM, "out of memory for the isolation check");
        goto done;
    }
    out->invariant_boxes = invariant_part(&g, CONLEY_Q, &G, &R, alive);
    if (out->invariant_boxes < 0) {
        status = gb_error_set(GB_ENOMEM, "out of memory for the isolation check");
        goto done;
    }
    out->isolated = 1;
    for (size_t k = 0; k < g.p1_count && out->isolated; k++) {
        const long outside = alive[k] ? neighbour_without(&g, g.p1[k], CONLEY_Q) : -1;
        if (outside >= 0)
            out->isolated = fail(out,
                                 "isolation: box %ld, on a bi-infinite path of F inside P1 \\ P0, touches box %ld "
                                 "outside it",
                                 (long)g.p1[k], outside);
    }
    out->index_pair = out->positively_invariant && out->exit_set && out->isolated;
    if (!out->index_pair) goto done;
    if ((status = conley_homology_compute(&g, &H, out->failure, sizeof out->failure))) goto done;
    out->h0 = H.h0, out->h1 = H.h1, out->h2 = H.h2;
    conley_sofic sofic;
    status = conley_sofic_entropy(&g, &H, def->precision, def->region_dimension, &sofic);
    out->regions = sofic.regions, out->regions_used = sofic.regions_used, out->symbols = sofic.symbols;
    out->transitions = sofic.transitions, out->component = sofic.component, out->rho = sofic.rho;
    out->entropy = sofic.entropy, out->capped = sofic.capped;
done:
    conley_homology_free(&H);
    graph_free(&G), graph_free(&R);
    free(alive);
    grid_free(&g);
    out->seconds = gb_proof_cpu_seconds() - start;
    return status;
}

/* ---------------------------------------------------------------- the construction */

/* Appends box `box` to a growing list. */
static int list_push(uint32_t **list, size_t *count, size_t *room, uint32_t box)
{
    if (*count == *room) {
        const size_t more = *room ? 2 * *room : 256;
        uint32_t *grown = realloc(*list, more * sizeof *grown);
        if (!grown) return gb_error_set(GB_ENOMEM, "out of memory for an index pair");
        *list = grown, *room = more;
    }
    (*list)[(*count)++] = box;
    return GB_OK;
}

/* For N = g's list: mark bit 0 for P1, bit 1 for the boxes reaching K, bit 2 for K (S and its neighbours); the boxes
 * outside N that are neighbours of S (and, with `interior`, of Q = P1 ∖ P0) appended to *missing. */
static int pair_marks(const conley_grid *g, const box_graph *G, const box_graph *R, int interior, uint8_t *mark,
                      uint32_t **missing, size_t *missing_count, size_t *missing_room)
{
    const size_t n = g->p1_count;
    uint8_t *in_S = malloc(n + 1);
    int32_t *queue = malloc((n + 1) * sizeof *queue);
    int status = GB_OK;
    if (!in_S || !queue || invariant_part(g, CONLEY_P1, G, R, in_S) < 0) {
        status = gb_error_set(GB_ENOMEM, "out of memory for an index pair");
        goto done;
    }
    memset(mark, 0, n);
    size_t head = 0, tail = 0;
    for (size_t k = 0; k < n && !status; k++) {
        if (!in_S[k]) continue;
        const long i = (long)(g->p1[k] % (uint32_t)g->n), j = (long)(g->p1[k] / (uint32_t)g->n);
        for (long dj = -1; dj <= 1 && !status; dj++)
            for (long di = -1; di <= 1 && !status; di++) {
                const uint32_t box = (uint32_t)((j + dj) * g->n + i + di);
                const long at = conley_p1_position(g, box);
                if (at < 0)
                    status = list_push(missing, missing_count, missing_room, box);
                else if (!(mark[at] & 1))
                    mark[at] |= 5, queue[tail++] = (int32_t)at;
                else
                    mark[at] |= 4;
            }
    }
    if (status || *missing_count) goto done;
    while (head < tail) { /* P1: forward from K inside N */
        const int32_t k = queue[head++];
        for (int32_t a = G->start[k]; a < G->start[k + 1]; a++)
            if (!(mark[G->next[a]] & 1)) mark[G->next[a]] |= 1, queue[tail++] = G->next[a];
    }
    /* backward from K: the boxes from which a path inside N reaches K. Q = P1 ∖ P0 then holds K, and
     * Inv(Q) ⊂ Inv(N) = S, so Q holds the neighbours of its invariant part (isolation); a box of P0 cannot map into
     * Q (positive invariance); E lies beyond N (P1 is closed under F inside N). */
    head = tail = 0;
    for (size_t k = 0; k < n; k++)
        if (mark[k] & 4) mark[k] |= 2, queue[tail++] = (int32_t)k;
    while (head < tail) {
        const int32_t k = queue[head++];
        for (int32_t a = R->start[k]; a < R->start[k + 1]; a++)
            if (!(mark[R->next[a]] & 2)) mark[R->next[a]] |= 2, queue[tail++] = R->next[a];
    }
    for (size_t k = 0; k < n && interior && !status; k++) {
        if ((mark[k] & 3) != 3) continue;
        const long i = (long)(g->p1[k] % (uint32_t)g->n), j = (long)(g->p1[k] / (uint32_t)g->n);
        for (long dj = -1; dj <= 1 && !status; dj++)
            for (long di = -1; di <= 1 && !status; di++) {
                const uint32_t box = (uint32_t)((j + dj) * g->n + i + di);
                if (conley_p1_position(g, box) < 0) status = list_push(missing, missing_count, missing_room, box);
            }
    }
done:
    free(in_S), free(queue);
    return status;
}

/* The grid over the list and F's graphs on it. */
static int pair_grid(const gb_proof_conley_def *def, conley_grid *g, const uint32_t *boxes, size_t count, box_graph *G,
                     box_graph *R, const uint32_t *known, int32_t (*known_rect)[4], size_t known_count)
{
    g->p1 = boxes, g->p1_count = count;
    int status = grid_enclose(g, def->map, def->precision, known, known_rect, known_count);
    if (!status) status = graph_build(g, CONLEY_P1, G);
    if (!status) status = graph_reverse(g, G, R);
    return status;
}

int gb_proof_conley_pair(const gb_proof_conley_def *def, const uint32_t *n_boxes, size_t n, uint32_t **p1,
                         size_t *p1_count, uint32_t **p0, size_t *p0_count)
{
    *p1 = *p0 = NULL, *p1_count = *p0_count = 0;
    conley_grid g;
    int status = check_def(def, &g);
    if (status || (status = check_boxes("n", n_boxes, n, g.n))) return status;
    box_graph G = {0}, R = {0};
    uint8_t *mark = malloc(n + 1);
    uint32_t *missing = NULL;
    size_t missing_count = 0, missing_room = 0;
    if (!mark) status = gb_error_set(GB_ENOMEM, "out of memory for an index pair");
    if (!status) status = pair_grid(def, &g, n_boxes, n, &G, &R, NULL, NULL, 0);
    if (!status) status = pair_marks(&g, &G, &R, 0, mark, &missing, &missing_count, &missing_room);
    if (!status && missing_count)
        status = gb_error_set(GB_ENOCONV,
                              "N does not isolate its invariant part: box %u, a neighbour of it, lies "
                              "outside N",
                              missing[0]);
    if (!status) {
        *p1 = malloc((n + 1) * sizeof **p1), *p0 = malloc((n + 1) * sizeof **p0);
        if (!*p1 || !*p0) status = gb_error_set(GB_ENOMEM, "out of memory for an index pair");
    }
    for (size_t k = 0; k < n && !status; k++)
        if (mark[k] & 1) {
            (*p1)[(*p1_count)++] = n_boxes[k];
            if (!(mark[k] & 2)) (*p0)[(*p0_count)++] = n_boxes[k];
        }
    if (status) free(*p1), free(*p0), *p1 = *p0 = NULL, *p1_count = *p0_count = 0;
    graph_free(&G), graph_free(&R);
    free(mark), free(missing);
    grid_free(&g);
    return status;
}

int gb_proof_conley_isolate(const gb_proof_conley_def *def, const uint32_t *seeds, size_t count, size_t max_boxes,
                            uint32_t **n_boxes, size_t *n)
{
    *n_boxes = NULL, *n = 0;
    conley_grid g;
    int status = check_def(def, &g);
    if (status || (status = check_boxes("seeds", seeds, count, g.n))) return status;
    if (!count || max_boxes < count)
        return gb_error_set(
            GB_EDOM, "max_boxes = %zu with %zu seeds (allowed: one seed or more, and max_boxes at least their number)",
            max_boxes, count);
    uint32_t *list = malloc(count * sizeof *list), *missing = NULL;
    size_t size = count, missing_count = 0, missing_room = 0;
    if (!list) return gb_error_set(GB_ENOMEM, "out of memory for an isolating neighbourhood");
    memcpy(list, seeds, count * sizeof *list);
    uint32_t *known = NULL; /* the last round's boxes and their F: the next round copies F from them */
    int32_t(*known_rect)[4] = NULL;
    size_t known_count = 0;
    for (int round = 0; !status; round++) {
        box_graph G = {0}, R = {0};
        uint8_t *mark = malloc(size + 1);
        missing_count = 0;
        status = mark ? pair_grid(def, &g, list, size, &G, &R, known, known_rect, known_count)
                      : gb_error_set(GB_ENOMEM, "out of memory");
        if (!status) status = pair_marks(&g, &G, &R, 1, mark, &missing, &missing_count, &missing_room);
        free(known), free(known_rect);
        known = list, known_rect = g.rect, known_count = size, g.rect = NULL; /* list now belongs to known */
        graph_free(&G), graph_free(&R), free(mark), grid_free(&g);
        if (status || !missing_count) break;
        qsort(missing, missing_count, sizeof *missing, conley_compare_boxes);
        uint32_t *merged = malloc((size + missing_count) * sizeof *merged);
        if (!merged) {
            status = gb_error_set(GB_ENOMEM, "out of memory for an isolating neighbourhood");
            break;
        }
        size_t a = 0, b = 0, m = 0;
        while (a < size || b < missing_count) {
            const uint32_t next = b == missing_count || (a < size && list[a] <= missing[b]) ? list[a++] : missing[b++];
            if (!m || merged[m - 1] != next) merged[m++] = next;
        }
        list = merged, size = m;
        if ((status = check_boxes("the grown neighbourhood", list, size, g.n)))
            status = gb_error_set(GB_ENOCONV,
                                  "the neighbourhood grown from the seeds reaches the grid's edge (round %d)", round);
        else if (size > max_boxes)
            status =
                gb_error_set(GB_ENOCONV, "the neighbourhood grown from the seeds passed max_boxes = %zu (round %d)",
                             max_boxes, round);
    }
    free(missing), free(known_rect);
    if (known != list) free(known);
    if (status)
        free(list);
    else
        *n_boxes = list, *n = size;
    return status;
}
