/* gb_contact_grid — node placement, the patch tree, the paper's brute-force grid search and the exact
 * fast search (paper §8, eq 29 on a grid); see gb_contact.h and gb_contact_internal.h. */
#include "gb_contact_internal.h"

#include "gb_error.h"
#include "gb_polyhedron.h"

#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- the vertical */

/* z_b·z_b = n2, or GB_EDOM: √n2 is finite and positive exactly when n2 is, so the test needs no root. */
static int vertical_square(const double zb[3], double *n2)
{
    *n2 = gb_vec_dot(zb, zb);
    if (!(isfinite(*n2) && *n2 > 0.0))
        return gb_error_set(GB_EDOM,
                            "z_b = (%g, %g, %g) has no direction: the body-frame vertical must be a "
                            "finite, non-zero vector",
                            zb[0], zb[1], zb[2]);
    return GB_OK;
}

int gb_contact_vertical_check(const double zb[3])
{
    double n2;
    return vertical_square(zb, &n2);
}

int gb_contact_unit_vertical(const double zb[3], double unit[3])
{
    double n2;
    const int status = vertical_square(zb, &n2);
    if (status) return status;
    const double n = sqrt(n2); /* gb_vec_norm's root of the same sum */
    for (int i = 0; i < 3; i++) unit[i] = zb[i] / n;
    return GB_OK;
}

/* ---------------------------------------------------------------- node placement */

static const char *const node_names[] = {"centred", "linspace"};

const char *gb_contact_nodes_name(gb_contact_nodes nodes)
{
    return (unsigned)nodes < 2 ? node_names[nodes] : NULL;
}

int gb_contact_nodes_parse(const char *name, gb_contact_nodes *nodes)
{
    int k = 0;
    const int status = gb_error_parse_name(name, node_names, 2, "grid node placement", &k);
    if (!status) *nodes = (gb_contact_nodes)k;
    return status;
}

static const char *const model_names[] = {"grid", "fast-grid", "continuous"};

const char *gb_contact_model_name(gb_contact_model model)
{
    return (unsigned)model < 3 ? model_names[model] : NULL;
}

int gb_contact_model_parse(const char *name, gb_contact_model *model)
{
    int k = 0;
    const int status = gb_error_parse_name(name, model_names, 3, "contact model", &k);
    if (!status) *model = (gb_contact_model)k;
    return status;
}

gb_contact_grid_def gb_contact_grid_default_def(void)
{
    return (gb_contact_grid_def){.n_phi = 90, .n_theta = 180, .nodes = GB_CONTACT_NODES_CENTRED,
                                 .leaf_size = 32};
}

gb_contact_grid_def gb_contact_default_branch_grid(void)
{
    gb_contact_grid_def def = gb_contact_grid_default_def();
    def.n_phi = 180;
    def.n_theta = 360;
    return def;
}

static int32_t patch_build(gb_contact_grid *g, uint32_t i0, uint32_t i1, uint32_t j0, uint32_t j1,
                           int depth)
{
    if (g->patch_count == g->patch_capacity || depth >= PATCH_STACK / 2) return -1;
    const int32_t id = (int32_t)g->patch_count++;
    patch *p = &g->patches[id];
    memset(p, 0, sizeof *p);
    p->i0 = i0, p->i1 = i1, p->j0 = j0, p->j1 = j1;
    p->child[0] = p->child[1] = -1;

    const size_t nt = g->def.n_theta;
    double sum[3] = {0, 0, 0}, r_lo = INFINITY, r_hi = 0.0;
    for (uint32_t i = i0; i < i1; i++)
        for (uint32_t j = j0; j < j1; j++) {
            const double *x = g->x + 3 * (i * nt + j);
            const double r = gb_vec_norm(x);
            for (int k = 0; k < 3; k++) sum[k] += x[k] / r;
            r_lo = fmin(r_lo, r);
            r_hi = fmax(r_hi, r);
        }
    const double sum_norm = gb_vec_norm(sum);
    double cos_alpha = 1.0;
    if (sum_norm > 1e-6) {
        for (int k = 0; k < 3; k++) p->a[k] = sum[k] / sum_norm;
        for (uint32_t i = i0; i < i1; i++)
            for (uint32_t j = j0; j < j1; j++) {
                const double *x = g->x + 3 * (i * nt + j);
                cos_alpha = fmin(cos_alpha, gb_vec_dot(x, p->a) / gb_vec_norm(x));
            }
        cos_alpha -= BOUND_MARGIN;
    } else {
        p->a[2] = 1.0;
        cos_alpha = -1.0; /* the whole sphere */
    }
    p->cos_alpha = fmax(cos_alpha, -1.0);
    p->sin_alpha = sqrt(fmax(0.0, 1.0 - p->cos_alpha * p->cos_alpha));
    p->r_lo = r_lo * (1.0 - BOUND_MARGIN);
    p->r_hi = r_hi * (1.0 + BOUND_MARGIN);

    const size_t rows = i1 - i0, cols = j1 - j0;
    if (rows * cols <= g->def.leaf_size) return id;
    /* Split across the longer side in angle (θ extent weighted by the largest sin φ of the rows). */
    double max_sin = 0.0;
    for (uint32_t i = i0; i < i1; i++) max_sin = fmax(max_sin, sin(node_phi(&g->def, i)));
    const double extent_phi = rows * M_PI / g->def.n_phi;
    const double extent_theta = cols * 2.0 * M_PI / g->def.n_theta * max_sin;
    int32_t left, right;
    if ((extent_phi >= extent_theta && rows > 1) || cols == 1) {
        const uint32_t mid = i0 + (uint32_t)(rows / 2);
        left = patch_build(g, i0, mid, j0, j1, depth + 1);
        right = left < 0 ? -1 : patch_build(g, mid, i1, j0, j1, depth + 1);
    } else {
        const uint32_t mid = j0 + (uint32_t)(cols / 2);
        left = patch_build(g, i0, i1, j0, mid, depth + 1);
        right = left < 0 ? -1 : patch_build(g, i0, i1, mid, j1, depth + 1);
    }
    if (left < 0 || right < 0) return -1;
    g->patches[id].child[0] = left;
    g->patches[id].child[1] = right;
    return id;
}

int gb_contact_grid_create(const gb_surface *surface, const gb_contact_grid_def *grid_def,
                           gb_contact_grid **out)
{
    *out = NULL;
    const gb_polyhedron *poly = surface->morphology->polyhedron;
    gb_contact_grid_def poly_def = *grid_def;
    if (poly) poly_def.n_phi = 1, poly_def.n_theta = poly->vertex_count, poly_def.nodes = GB_CONTACT_NODES_CENTRED;
    const gb_contact_grid_def *def = poly ? &poly_def : grid_def;
    const size_t min_phi = def->nodes == GB_CONTACT_NODES_LINSPACE ? 2 : 1;
    const size_t min_theta = def->nodes == GB_CONTACT_NODES_LINSPACE ? 3 : 2;
    if (!gb_contact_nodes_name(def->nodes)) {
        gb_contact_nodes unused;
        return gb_contact_nodes_parse(NULL, &unused); /* "… is unknown (allowed: …)" from the name table */
    }
    if (def->n_phi < min_phi || def->n_theta < min_theta || def->n_phi > GB_CONTACT_GRID_MAX_NODES ||
        def->n_theta > GB_CONTACT_GRID_MAX_NODES ||
        def->n_phi * def->n_theta > GB_CONTACT_GRID_MAX_NODES)
        return gb_error_set(GB_EDOM,
                            "contact grid %zu x %zu is out of range (allowed: N_phi >= %zu, N_theta "
                            ">= %zu, N_phi N_theta <= %zu)",
                            def->n_phi, def->n_theta, min_phi, min_theta, GB_CONTACT_GRID_MAX_NODES);
    if (def->leaf_size < 1)
        return gb_error_set(GB_EDOM, "contact grid leaf_size %zu is out of range (allowed: >= 1)",
                            def->leaf_size);
    gb_contact_grid *g = calloc(1, sizeof *g);
    if (!g) return gb_error_set(GB_ENOMEM, "out of memory for the contact grid");
    g->surface = *surface;
    g->def = *def;
    g->size = def->n_phi * def->n_theta;
    g->x = malloc(3 * g->size * sizeof *g->x);
    /* A binary tree whose leaves hold ≥ leaf_size/4 nodes (each split halves a side; a side of
     * one cannot be split) has fewer than 2·size patches; 2·size + 1 bounds it for any leaf size. */
    g->patch_capacity = 2 * g->size + 1;
    g->patches = malloc(g->patch_capacity * sizeof *g->patches);
    if (!g->x || !g->patches) {
        gb_contact_grid_free(g);
        return gb_error_set(GB_ENOMEM, "out of memory for a %zu x %zu contact grid", def->n_phi,
                            def->n_theta);
    }
    if (poly) /* a polyhedron's nodes are its hull's vertices, one row (gb_body.h) */
        memcpy(g->x, poly->vertices, 3 * g->size * sizeof *g->x);
    for (size_t i = 0; !poly && i < def->n_phi; i++) {
        const double phi = node_phi(def, i);
        for (size_t j = 0; j < def->n_theta; j++)
            gb_surface_position(surface, phi, node_theta(def, j), g->x + 3 * (i * def->n_theta + j));
    }
    if (patch_build(g, 0, (uint32_t)def->n_phi, 0, (uint32_t)def->n_theta, 0) != 0) {
        gb_contact_grid_free(g);
        return gb_error_set(GB_ENUMERIC, "cannot build the patch tree of a %zu x %zu grid",
                            def->n_phi, def->n_theta);
    }
    *out = g;
    return GB_OK;
}

void gb_contact_grid_free(gb_contact_grid *grid)
{
    if (!grid) return;
    free(grid->x);
    free(grid->patches);
    free(grid);
}

size_t gb_contact_grid_size(const gb_contact_grid *grid) { return grid->size; }
const gb_contact_grid_def *gb_contact_grid_get_def(const gb_contact_grid *grid) { return &grid->def; }
const gb_surface *gb_contact_grid_surface(const gb_contact_grid *grid) { return &grid->surface; }

void gb_contact_grid_node(const gb_contact_grid *grid, size_t index, double *phi, double *theta,
                          double x[3])
{
    const size_t i = index / grid->def.n_theta, j = index % grid->def.n_theta;
    const double *p = grid->x + 3 * index;
    if (grid->surface.morphology->polyhedron) { /* a vertex: the angles of its direction from the centroid */
        if (phi) *phi = acos(fmax(-1.0, fmin(1.0, p[2] / gb_vec_norm(p))));
        if (theta) *theta = atan2(p[1], p[0]) < 0.0 ? atan2(p[1], p[0]) + 2.0 * M_PI : atan2(p[1], p[0]);
    } else {
        if (phi) *phi = node_phi(&grid->def, i);
        if (theta) *theta = node_theta(&grid->def, j);
    }
    if (x) memcpy(x, p, 3 * sizeof *x);
}

void gb_contact_grid_fill_node(const gb_contact_grid *grid, size_t index, double height, size_t visited,
                               gb_contact_node *out)
{
    out->index = index;
    out->height = height;
    out->visited = visited;
    gb_contact_grid_node(grid, index, &out->phi, &out->theta, out->x);
}

int gb_contact_grid_brute(const gb_contact_grid *grid, const double zb[3], gb_contact_node *out)
{
    double d[3];
    int status = gb_contact_unit_vertical(zb, d);
    if (status) return status;
    double best = INFINITY;
    size_t best_index = 0;
    for (size_t k = 0; k < grid->size; k++) {
        const double h = node_height(d, grid->x + 3 * k);
        if (h < best) {
            best = h;
            best_index = k;
        }
    }
    gb_contact_grid_fill_node(grid, best_index, best, grid->size, out);
    return GB_OK;
}

/* Branch and bound; `hint` (a node index, or SIZE_MAX) seeds the best height with a real node, so
 * a good guess prunes most of the tree at once without changing the answer. */
static int search(const gb_contact_grid *grid, const double zb[3], size_t hint, const size_t *except, int n_except,
                  gb_contact_node *out)
{
    double d[3];
    int status = gb_contact_unit_vertical(zb, d);
    if (status) return status;
    int32_t stack[PATCH_STACK];
    double stack_bound[PATCH_STACK];
    int top = 0;
    stack[0] = 0;
    stack_bound[0] = patch_bound(&grid->patches[0], d);
    top = 1;
    double best = INFINITY;
    size_t best_index = SIZE_MAX, visited = 0;
    if (hint < grid->size) {
        best = node_height(d, grid->x + 3 * hint);
        best_index = hint;
        visited = 1;
    }
    while (top > 0) {
        top--;
        if (stack_bound[top] > best) continue;
        const patch *p = &grid->patches[stack[top]];
        if (p->child[0] < 0) {
            visited += scan_leaf_except(grid, p, d, except, n_except, &best, &best_index);
            continue;
        }
        const double b0 = patch_bound(&grid->patches[p->child[0]], d);
        const double b1 = patch_bound(&grid->patches[p->child[1]], d);
        /* Push the farther child first so the nearer is searched first and tightens `best`. */
        const int near = b1 < b0;
        const double bn = near ? b1 : b0, bf = near ? b0 : b1;
        const int32_t cn = p->child[near], cf = p->child[!near];
        if (top + 2 > PATCH_STACK)
            return gb_error_set(GB_ENUMERIC, "patch tree deeper than %d levels", PATCH_STACK / 2);
        if (bf <= best) stack[top] = cf, stack_bound[top++] = bf;
        if (bn <= best) stack[top] = cn, stack_bound[top++] = bn;
    }
    gb_contact_grid_fill_node(grid, best_index, best, visited, out);
    return GB_OK;
}

int gb_contact_grid_search(const gb_contact_grid *grid, const double zb[3], size_t hint, gb_contact_node *out)
{
    return search(grid, zb, hint, NULL, 0, out);
}

int gb_contact_grid_fast(const gb_contact_grid *grid, const double zb[3], gb_contact_node *out)
{
    return search(grid, zb, SIZE_MAX, NULL, 0, out);
}

int gb_contact_grid_lowest_except(const gb_contact_grid *grid, const double zb[3], size_t hint, const size_t *except,
                                  int n_except, gb_contact_node *out)
{
    if (n_except < 0 || n_except > 2 || (size_t)n_except >= grid->size)
        return gb_error_set(GB_EINVAL, "%d nodes left out of a grid of %zu (allowed: 0 to 2, fewer than the grid)", n_except,
                            grid->size);
    for (int e = 0; e < n_except; e++)
        if (hint == except[e]) hint = SIZE_MAX;
    return search(grid, zb, hint, except, n_except, out);
}
