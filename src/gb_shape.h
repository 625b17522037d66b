/* gb_shape — the paper's claims about the bodies (§2), tested: convexity, static equilibria, and
 * the equilibria of the convex hull on which a non-convex body rests.
 *
 * Curvature sign convention: principal curvatures are taken with respect to the inward normal, so
 * the unit sphere has κ₁ = κ₂ = 1, K = 1, H = 1. A surface is strictly convex when κ₁ > 0 everywhere
 * (κ₁ ≤ κ₂); the Gaussian curvature alone cannot tell a convex cap from a concave one. */
#ifndef GB_SHAPE_H
#define GB_SHAPE_H

#include "gb_export.h"

#include "gb_surface.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gb_curvature {
    double K;               /* Gaussian curvature */
    double H;               /* mean curvature */
    double kappa_min, kappa_max;
    double area_element;    /* ‖∂φx × ∂θx‖, the surface area per dφ dθ */
} gb_curvature;

/* Curvature at one interior parameter point (0 < φ < π); from the analytic first and second
 * derivatives of gb_surface through the first and second fundamental forms. */
GB_API void gb_shape_curvature(const gb_surface *surface, double phi, double theta, gb_curvature *out);

typedef struct gb_shape_def {
    size_t survey_phi, survey_theta; /* midpoint grid for the curvature survey */
    size_t refine_starts;            /* lowest grid nodes polished by a local minimiser */
    double beta_tol;                 /* absolute tolerance on the convexity limit of β */
    size_t equilibria_phi, equilibria_theta; /* grid that seeds Newton for critical points of r */
    double polar_cap;                /* colatitude of the polar caps checked separately [rad] */
    size_t hull_phi, hull_theta;     /* surface sample for the convex hull */
    double hull_neighbourhood;       /* angular radius [rad] within which a hull equilibrium must
                                        be extreme to count as robust (see gb_hull_equilibria) */
} gb_shape_def;

GB_API gb_shape_def gb_shape_default_def(void);

typedef struct gb_curvature_survey {
    double K_min, K_min_phi, K_min_theta;
    double kappa_min, kappa_min_phi, kappa_min_theta;
    double negative_fraction; /* area fraction where K < 0 (midpoint rule on the survey grid) */
    double area;              /* total area by the same rule */
} gb_curvature_survey;

GB_API int gb_shape_curvature_survey(const gb_surface *surface, const gb_shape_def *def, gb_curvature_survey *out);

/* The supremum of β for which the morphology is strictly convex: the root of β ↦ min κ₁(β),
 * bracketed in (0, 1/4) and solved with Brent's method to def->beta_tol. *where_phi/_theta get the
 * place where convexity is lost (may be NULL). */
GB_API int gb_shape_convexity_limit(const gb_morphology *morphology, const gb_shape_def *def, double *beta_limit,
                                    double *where_phi, double *where_theta);

enum gb_equilibrium_type { GB_EQ_STABLE = 0, GB_EQ_SADDLE = 1, GB_EQ_UNSTABLE = 2 };
GB_API const char *gb_shape_equilibrium_name(int type);

typedef struct gb_equilibrium {
    int type;
    double phi, theta, r;
    double gradient_norm; /* |∇r| at the converged point */
} gb_equilibrium;

#define GB_SHAPE_MAX_EQUILIBRIA 64

typedef struct gb_equilibria {
    size_t count;
    gb_equilibrium points[GB_SHAPE_MAX_EQUILIBRIA];
    int stable, saddle, unstable;
    double polar_gradient_min; /* min |∇r| in the polar caps, where the chart is not used */
} gb_equilibria;

/* Every critical point of r(φ, θ), the distance from the centroid (at the origin, see
 * gb_massprops): a minimum is a stable resting point on a plane, a maximum an unstable one. Newton
 * with the analytic Hessian from every grid node where |∇r| is a local minimum; duplicates merged.
 * The polar caps (φ < polar_cap or φ > π − polar_cap) are not searched: polar_gradient_min reports
 * the smallest sphere gradient there, so a caller can see that no critical point hides in them. */
GB_API int gb_shape_equilibria(const gb_surface *surface, const gb_shape_def *def, gb_equilibria *out);

typedef struct gb_hull_rest {
    double normal[3]; /* outward normal of the resting face: the body's "down" direction */
    double height;    /* distance from the centroid to the face plane */
} gb_hull_rest;

/* Equilibria of the convex hull of a surface sample. As a polyhedron the sampled hull has "raw"
 * equilibria: resting triangles (the centroid projects inside) lower than every triangle sharing a
 * vertex with them, and vertices farther from the centroid than every neighbour. Where the true hull is nearly flat
 * or ruled (it bridges concave regions) sampling creates spurious raw equilibria at the scale of
 * the sample spacing. A raw equilibrium is robust when it is also extreme within the angular
 * neighbourhood def->hull_neighbourhood: a resting face whose support distance is the smallest of
 * all facets whose normals lie within that angle, a vertex whose distance is the largest of all
 * vertices within that angle. Robust equilibria are stored; raw ones only counted. */
typedef struct gb_hull_equilibria {
    size_t vertices, facets;
    size_t raw_stable, raw_unstable;
    size_t stable, unstable;
    gb_hull_rest rests[GB_SHAPE_MAX_EQUILIBRIA];
    double unstable_points[GB_SHAPE_MAX_EQUILIBRIA][3];
    double sampled_fraction_on_hull; /* fraction of sample points that are hull vertices */
} gb_hull_equilibria;

/* Convex hull of a hull_phi × hull_theta midpoint sample plus both poles (Qhull). */
GB_API int gb_shape_hull_equilibria(const gb_surface *surface, const gb_shape_def *def, gb_hull_equilibria *out);

#ifdef __cplusplus
}
#endif

#endif
