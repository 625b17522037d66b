/* gb_contact_internal — what the three files of the contact module share (private to src/ and
 * verify/): the grid and its patch tree, and the node height that every grid search uses, so that
 * brute force, the fast search, the tracker and the branch search compare bit-identical values.
 *
 *   gb_contact_grid.c     node placement, the patch tree, brute force and the exact fast search
 *   gb_contact_tracker.c  the trajectory tracker (a descent over the nodes' convex hull)
 *   gb_contact_minimum.c  the continuous minimiser, branches, switch detection, sensitivity (eq 72) */
#ifndef GB_CONTACT_INTERNAL_H
#define GB_CONTACT_INTERNAL_H

#include "gb_contact.h"
#include "gb_vec.h"

#include <math.h>
#include <stdint.h>

/* The height of one stored node. Brute force, the fast search, the tracker and the branch search all
 * call this one function, so they compare bit-identical values (the build uses -ffp-contract=off: no
 * fused multiply-add may make one path round differently from another). */
static inline double node_height(const double d[3], const double *x)
{
    return d[0] * x[0] + d[1] * x[1] + d[2] * x[2];
}

static inline double node_phi(const gb_contact_grid_def *def, size_t i)
{
    return def->nodes == GB_CONTACT_NODES_CENTRED ? (i + 0.5) * M_PI / def->n_phi
                                                  : i * M_PI / (def->n_phi - 1);
}

static inline double node_theta(const gb_contact_grid_def *def, size_t j)
{
    return def->nodes == GB_CONTACT_NODES_CENTRED ? j * 2.0 * M_PI / def->n_theta
                                                  : j * 2.0 * M_PI / (def->n_theta - 1);
}

/* ---------------------------------------------------------------- the patch tree
 *
 * Each tree node covers an index rectangle [i0, i1) × [j0, j1) of the grid and stores a region that
 * contains every one of its stored points: the directions u = x/|x| lie in a spherical cap of
 * centre a and half-angle α, and |x| ∈ [r_lo, r_hi]. For a unit vertical d let γ be the angle
 * between a and −d. Over the cap, d·u ≥ m = −cos(max(γ − α, 0)), so every point of the patch has
 * h = |x| (d·u) ≥ r_hi·m when m < 0 and ≥ r_lo·m otherwise. The cap and radii are widened by 1e-12
 * and the bound lowered by 1e-12, far above the few ulps (≈ 1e-16) by which the rounded bound or a
 * rounded node height can be off, so a pruned patch never holds a node whose computed height is
 * ≤ the best computed height: the search is exact, ties included. */
typedef struct patch {
    uint32_t i0, i1, j0, j1;
    int32_t child[2]; /* −1 for a leaf */
    double a[3], cos_alpha, sin_alpha, r_lo, r_hi;
} patch;

struct gb_contact_grid {
    gb_surface surface;
    gb_contact_grid_def def;
    size_t size;
    double *x; /* 3 × size, node index order */
    patch *patches;
    size_t patch_count, patch_capacity;
};

enum { PATCH_STACK = 256 };
static const double BOUND_MARGIN = 1e-12;

static inline double patch_bound(const patch *p, const double d[3])
{
    const double cos_gamma = -gb_vec_dot(d, p->a);
    double m;
    if (cos_gamma >= p->cos_alpha) {
        m = -1.0;
    } else {
        const double sin_gamma = sqrt(fmax(0.0, 1.0 - cos_gamma * cos_gamma));
        m = -(cos_gamma * p->cos_alpha + sin_gamma * p->sin_alpha);
    }
    return (m < 0.0 ? p->r_hi * m : p->r_lo * m) - BOUND_MARGIN;
}

/* Scan every node of leaf p but the `n_except` nodes listed, keeping the lowest (ties to the lower index)
 * in *best, *best_index; returns the number of nodes scanned. Brute force, the search and the tracker
 * share node_height. */
static inline size_t scan_leaf_except(const gb_contact_grid *grid, const patch *p, const double d[3], const size_t *except,
                                      int n_except, double *best, size_t *best_index)
{
    const size_t nt = grid->def.n_theta;
    for (uint32_t i = p->i0; i < p->i1; i++)
        for (uint32_t j = p->j0; j < p->j1; j++) {
            const size_t k = i * nt + j;
            int skip = 0;
            for (int e = 0; e < n_except; e++) skip |= k == except[e];
            if (skip) continue;
            const double h = node_height(d, grid->x + 3 * k);
            if (h < *best || (h == *best && k < *best_index)) {
                *best = h;
                *best_index = k;
            }
        }
    return (size_t)(p->i1 - p->i0) * (p->j1 - p->j0);
}

static inline size_t scan_leaf(const gb_contact_grid *grid, const patch *p, const double d[3], double *best, size_t *best_index)
{
    return scan_leaf_except(grid, p, d, NULL, 0, best, best_index);
}

/* Fill *out with node `index` (its angles and position), its height and the count of nodes visited. */
void gb_contact_grid_fill_node(const gb_contact_grid *grid, size_t index, double height, size_t visited,
                               gb_contact_node *out);

/* The exact lowest node for the unit vertical d by branch and bound; `hint` (a node index, or
 * SIZE_MAX) seeds the best height with a real node. */
int gb_contact_grid_search(const gb_contact_grid *grid, const double d[3], size_t hint, gb_contact_node *out);
/* The (φ, θ) of the point at chart offsets (Δa, Δb) from `p` in p's chart: a predictor's start, such as
 * p + (∂q/∂z_b)·Δz_b with the sensitivity of gb_contact_sensitivity. For POLAR_Z it is (φ + Δa, θ + Δb)
 * unwrapped (gb_contact_refine wraps its start). */
void gb_contact_chart_offset(const gb_contact_point *p, double da, double db, double *phi, double *theta);
/* gb_contact_unit_vertical's check alone (GB_EDOM for a zero or non-finite z_b), without dividing. */
int gb_contact_vertical_check(const double zb[3]);
/* gb_contact_rate for a contact whose sensitivity ∂(φ, θ)/∂z_b (gb_contact_sensitivity) is already known, at
 * the unit vertical d: ṙ_c and the chart rates (q_dot may be NULL), eq 72; for a caller that keeps the
 * sensitivity (the dynamics reuse it as the next Newton start's predictor). */
void gb_contact_rate_from(const double dq_dzb[2][3], const double d[3], const gb_contact_point *contact,
                          const double omega[3], double rc_dot[3], double q_dot[2]);

#endif
