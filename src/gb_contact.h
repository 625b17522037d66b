/* gb_contact — which surface point touches the plane (paper §4, eqs 27–39, and §6, eqs 70–72).
 *
 * The height of a body point above the centroid's level is h(φ, θ) = z_b·x(φ, θ) (eq 28), with
 * z_b = Rᵀe_z the upward vertical in the body frame; the contact is its global minimiser (eq 29).
 * Every function here normalises z_b first (a zero or non-finite z_b is GB_EDOM), so heights are
 * distances along the unit vertical and the result does not depend on |z_b|.
 *
 * Three ways to find the contact:
 *  - the paper's grid (§8): the lowest of a fixed N_φ × N_θ set of surface nodes, by brute force;
 *  - an exact fast grid search: the very node brute force returns (same ties), found by a
 *    branch-and-bound over a tree of node patches, visiting far fewer nodes;
 *  - the continuous minimiser: every local minimum of h polished by Newton on eqs 31–32 with the
 *    analytic Hessian (eq 34), the lowest one being the contact.
 *
 * Grid nodes. The paper does not say where they sit; two placements are offered (a scene option):
 *  GB_CONTACT_NODES_CENTRED   φ_i = (i + ½)π/N_φ, θ_j = 2πj/N_θ: no node on a pole, none repeated;
 *  GB_CONTACT_NODES_LINSPACE  φ_i = iπ/(N_φ − 1), θ_j = 2πj/(N_θ − 1): what linspace(0, π, N_φ) ×
 *                             linspace(0, 2π, N_θ) gives, the poles repeated N_θ times and the
 *                             seam θ = 0 ≡ 2π twice.
 * Nodes are numbered index = i·N_θ + j. Ties in height are broken towards the lower index. */
#ifndef GB_CONTACT_H
#define GB_CONTACT_H

#include "gb_export.h"

#include "gb_surface.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum gb_contact_nodes {
    GB_CONTACT_NODES_CENTRED = 0,
    GB_CONTACT_NODES_LINSPACE = 1
} gb_contact_nodes;

/* "centred" / "linspace"; NULL for an unknown value. */
GB_API const char *gb_contact_nodes_name(gb_contact_nodes nodes);
/* Parse a name; GB_EINVAL naming the allowed values when unknown. */
GB_API int gb_contact_nodes_parse(const char *name, gb_contact_nodes *nodes);

/* The contact models a run may use: the paper's brute-force grid (§8), the same nodes found by the
 * exact fast search and tracker, and the certified continuous minimum. */
typedef enum gb_contact_model {
    GB_CONTACT_MODEL_GRID = 0,
    GB_CONTACT_MODEL_FAST_GRID = 1,
    GB_CONTACT_MODEL_CONTINUOUS = 2
} gb_contact_model;

/* "grid" / "fast-grid" / "continuous"; NULL for an unknown value. */
GB_API const char *gb_contact_model_name(gb_contact_model model);
/* Parse a name; GB_EINVAL naming the allowed values when unknown (or NULL). */
GB_API int gb_contact_model_parse(const char *name, gb_contact_model *model);

typedef struct gb_contact_grid_def {
    size_t n_phi, n_theta;   /* Table 1: 90 × 180; each at least 2 (linspace) or 1 (centred) */
    gb_contact_nodes nodes;  /* default centred */
    size_t leaf_size;        /* fast search: the most nodes in one leaf patch (default 32) */
} gb_contact_grid_def;

GB_API gb_contact_grid_def gb_contact_grid_default_def(void);

/* Largest grid accepted: 2^26 nodes (1.6 GB of node data). */
#define GB_CONTACT_GRID_MAX_NODES ((size_t)1 << 26)

typedef struct gb_contact_grid gb_contact_grid;

/* Build the node set (x at every node) and the patch tree of the fast search, once per body. */
GB_API int gb_contact_grid_create(const gb_surface *surface, const gb_contact_grid_def *def, gb_contact_grid **out);
GB_API void gb_contact_grid_free(gb_contact_grid *grid);

GB_API size_t gb_contact_grid_size(const gb_contact_grid *grid);
GB_API const gb_contact_grid_def *gb_contact_grid_get_def(const gb_contact_grid *grid);
GB_API const gb_surface *gb_contact_grid_surface(const gb_contact_grid *grid);
/* Parameters and body-frame point of node `index` (< size). */
GB_API void gb_contact_grid_node(const gb_contact_grid *grid, size_t index, double *phi, double *theta, double x[3]);

/* The lowest grid node for one vertical. `visited` counts the nodes whose height was computed. */
typedef struct gb_contact_node {
    size_t index;
    double phi, theta, height;
    double x[3];
    size_t visited;
} gb_contact_node;

/* Brute force, as the paper: every node, the first (lowest index) of the lowest. */
GB_API int gb_contact_grid_brute(const gb_contact_grid *grid, const double zb[3], gb_contact_node *out);
/* The same node, by branch and bound over the patch tree (see gb_contact.c for the bound). */
GB_API int gb_contact_grid_fast(const gb_contact_grid *grid, const double zb[3], gb_contact_node *out);
/* The lowest node but the `n_except` (0 to 2) nodes listed, exactly (ties to the lower index): the node a
 * grid body pivoting about one node, or rocking on an edge of two, meets the plane with next. `hint` (a
 * node index, or SIZE_MAX) seeds the search, as for the fast search; it changes no answer. */
GB_API int gb_contact_grid_lowest_except(const gb_contact_grid *grid, const double zb[3], size_t hint,
                                         const size_t *except, int n_except, gb_contact_node *out);

/* Exact grid search along a trajectory: a descent over the vertices of the nodes' convex hull from
 * the previous answer (the lowest node is a hull vertex, and on a convex polytope a vertex no higher
 * than its neighbours is the lowest), then a certified search of the vertices within 1e-11 of where it
 * stopped and of the nodes Qhull finds within 1e-12 of a facet (see gb_contact_tracker.c): the very
 * node brute force returns, ties included, for the heights of a few dozen nodes a query. Where Qhull
 * cannot build the hull it falls back to gb_contact_grid_search. */
typedef struct gb_contact_tracker gb_contact_tracker;

GB_API int gb_contact_tracker_create(const gb_contact_grid *grid, gb_contact_tracker **out);
GB_API void gb_contact_tracker_free(gb_contact_tracker *tracker);
/* The hull's vertices (0 when the tracker fell back to the patch-tree search). */
GB_API size_t gb_contact_tracker_vertices(const gb_contact_tracker *tracker);
/* The hull as a file, a cache per grid: gb_contact_tracker_save writes the tracker's hull graph
 * atomically and sealed (gb_seal: a keyed BLAKE2b-256 of its bytes; GB_EINVAL when it has no hull, GB_EIO
 * when there is no key); gb_contact_tracker_load makes a tracker from a file written for this very grid
 * (the bits of its nodes, Qhull's release) whose seal verifies, and refuses any other with GB_EIO and
 * why. A loaded tracker answers every query as the one Qhull built, bit for bit. Every hull file starts
 * with the 8 bytes GB_CONTACT_HULL_MAGIC. */
#define GB_CONTACT_HULL_MAGIC {'G', 'B', 'H', 'U', 'L', 'L', '\0', '\0'}
GB_API int gb_contact_tracker_save(const gb_contact_tracker *tracker, const char *path);
GB_API int gb_contact_tracker_load(const gb_contact_grid *grid, const char *path, gb_contact_tracker **out);
/* The same from a file's bytes (`name` for the message). */
GB_API int gb_contact_tracker_load_buffer(const gb_contact_grid *grid, const unsigned char *data, size_t size,
                                          const char *name, gb_contact_tracker **out);
GB_API int gb_contact_tracker_find(gb_contact_tracker *tracker, const double zb[3], gb_contact_node *out);

#define GB_CONTACT_POLAR_CAP 1e-2 /* sin φ below which Newton works in the POLAR_X chart */

/* A stationary point of h polished by the continuous minimiser. Derivatives are taken in the point's chart: (φ, θ) itself (GB_SURFACE_CHART_POLAR_Z, the paper's
 * eqs), or, within GB_CONTACT_POLAR_CAP of the poles ±e_z where ∂θx vanishes, the chart
 * GB_SURFACE_CHART_POLAR_X (coordinates (a, b) = chart_a, chart_b, poles ±e_x); then the fields named
 * after φ and θ hold the derivatives by a and b, and sensitivities and rates (eqs 70–72) are in (a, b). */
typedef struct gb_contact_point {
    double phi, theta;
    double height;          /* h = ẑ_b·x (eq 28) */
    double rc[3];           /* x(φ, θ), the contact vector (eq 30) */
    double n_hat[3];        /* unit outward normal (eq 17) */
    double gradient[2];     /* ∂φh, ∂θh (eqs 31–32), in the point's chart */
    double hessian[3];      /* H_φφ, H_φθ, H_θθ (eq 34), in the point's chart */
    double x_phi[3], x_theta[3]; /* the tangents ∂φx, ∂θx (eq 15) at the point, in the point's chart */
    gb_surface_chart chart; /* the chart of the derivatives: POLAR_Z (0) unless near ±e_z */
    double chart_a, chart_b; /* the point's coordinates in a POLAR_X chart (unused for POLAR_Z) */
    double residual;        /* |ẑ_b × n̂| (eq 33) */
    int is_minimum;         /* eq 35: H_φφ > 0 and H_φφ H_θθ − H_φθ² > 0 */
    int iterations;         /* Newton iterations */
    int used_fallback;      /* 1 when GSL multimin had to take over */
    size_t node;            /* grid contact models: the grid node this point is (0 for continuous contact) */
} gb_contact_point;

typedef struct gb_contact_refine_def {
    int max_iterations;       /* Newton iterations before the fallback (default 60) */
    double step_tol;          /* stop when the Newton step is below this [rad] (default 1e-14) */
    double pole_guard;        /* leave the (φ, θ) chart when sin φ falls below this (default 1e-6) */
    int force_fallback;       /* skip Newton: for testing the fallback path (default 0) */
} gb_contact_refine_def;

GB_API gb_contact_refine_def gb_contact_refine_default_def(void);


/* The local minimum of h reached from (φ0, θ0): safeguarded Newton (positive-definite Hessian or a
 * shifted one, backtracking on h), falling back to GSL's nmsimplex2 in a pole-free tangent chart
 * when Newton fails or nears a pole, and then polishing again. GB_ENOCONV when neither converges. */
GB_API int gb_contact_refine(const gb_surface *surface, const double zb[3], double phi0, double theta0,
                             const gb_contact_refine_def *def, gb_contact_point *out);

/* All local minima of h for one vertical. */
#define GB_CONTACT_BRANCH_MAX 64

typedef struct gb_contact_branches {
    size_t count;                                /* distinct strict local minima found */
    gb_contact_point branch[GB_CONTACT_BRANCH_MAX]; /* sorted by height: branch[0] is the contact */
    double gap;                                  /* Δh = h₂ − h₁ ≥ 0 (eqs 38–39), +inf if one */
    size_t seeds;                                /* discrete local minima of the grid polished */
} gb_contact_branches;

/* Every discrete local minimum of h on `grid` (8 neighbours, θ periodic, across the poles) is
 * polished by gb_contact_refine; duplicates (contact vectors closer than 1e-7) merge, and only
 * points passing eq 35 are kept. A minimum whose basin holds no node of `grid` can be missed:
 * gb_contact_default_branch_grid gives the grid the checks validate. */
GB_API int gb_contact_branches_find(const gb_contact_grid *grid, const double zb[3], const gb_contact_refine_def *def,
                                    gb_contact_branches *out);

/* The grid the continuous minimiser seeds from: 180 × 360 centred nodes. */
GB_API gb_contact_grid_def gb_contact_default_branch_grid(void);

/* Branch switching between two verticals (eqs 38–39). The branch of `previous` (a minimum at
 * zb_from) is continued to zb_to by Newton along the great circle, in steps of at most
 * `max_step` rad; then the global minimum at zb_to is found on `grid`. */
typedef enum gb_contact_switch_kind {
    GB_CONTACT_SAME_BRANCH = 0,  /* the continued branch is still the global minimum */
    GB_CONTACT_OVERTAKEN = 1,    /* another branch became lower (Δh changed sign) */
    GB_CONTACT_BRANCH_LOST = 2   /* the branch ceased to be a minimum (a fold of h) */
} gb_contact_switch_kind;

typedef struct gb_contact_switch {
    gb_contact_switch_kind kind;
    gb_contact_point continued;  /* the previous branch at zb_to (meaningless if lost) */
    gb_contact_point global;     /* the global minimum at zb_to */
} gb_contact_switch;

/* The kind's name ("same-branch", "overtaken", "branch-lost"), or "unknown" for another value. */
GB_API const char *gb_contact_switch_name(gb_contact_switch_kind kind);

GB_API int gb_contact_switch_detect(const gb_contact_grid *grid, const double zb_from[3],
                                    const gb_contact_point *previous, const double zb_to[3], double max_step,
                                    const gb_contact_refine_def *def, gb_contact_switch *out);

/* Contact sensitivity (eq 72): with F = (∂φh, ∂θh) and J = ∂F/∂(φ, θ) = H (eq 34),
 * d(φ*, θ*)/dz_b = −H⁻¹ [∂φxᵀ; ∂θxᵀ], a 2 × 3 matrix, for the unit vertical. Uses the Hessian and
 * tangents stored in `contact`, which must be the point gb_contact_refine returned for this z_b.
 * GB_ENUMERIC when H is singular (the minimiser is not locally well defined). */
GB_API int gb_contact_sensitivity(const gb_surface *surface, const double zb[3], const gb_contact_point *contact,
                                  double dq_dzb[2][3]);

/* The contact's rates for body angular velocity ω: ż_b = −ω × z_b (eq 24), (φ̇*, θ̇*) from eq 72,
 * and ṙ_c = ∂φx φ̇* + ∂θx θ̇*, which eq 45 needs. `q_dot` may be NULL. */
GB_API int gb_contact_rate(const gb_surface *surface, const double zb[3], const gb_contact_point *contact,
                           const double omega[3], double rc_dot[3], double q_dot[2]);

/* Normalise z_b into `unit`; GB_EDOM for a zero or non-finite vector. */
GB_API int gb_contact_unit_vertical(const double zb[3], double unit[3]);

#ifdef __cplusplus
}
#endif

#endif
