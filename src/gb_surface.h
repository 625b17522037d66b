/* gb_surface — the two analytical Gömböcs of paper §2 and their differential geometry.
 *
 * A body is r(φ,θ) = S(φ,θ)^(1/4) with the kernel S = 1 + 4β sinφ cos χ(φ,θ) (eqs 7, 11, 12); the
 * morphologies differ only in the phase function χ (eqs 8, 9), so each is one row of a table that
 * holds χ and its derivatives up to second order (eqs 18, 19). Adding a morphology means adding a row.
 *
 * Angles: φ ∈ (0, π) is colatitude and θ ∈ [0, 2π) longitude (eq 1). The parametrisation is singular
 * at the poles (sin φ = 0): the tangent ∂θx vanishes there and the normal of eq 16 is the zero vector. */
#ifndef GB_SURFACE_H
#define GB_SURFACE_H

#include "gb_export.h"


#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* χ and its derivatives at one (φ, θ). */
struct gb_jet; /* an interval jet: gb_interval.h, internal */

typedef struct gb_phase_value {
    double chi, chi_phi, chi_theta, chi_phiphi, chi_phitheta, chi_thetatheta;
} gb_phase_value;

struct gb_morphology;
struct gb_polyhedron; /* gb_polyhedron.h */

struct gb_massprops; /* gb_massprops.h */

typedef struct gb_morphology {
    const char *name;        /* "I", "II": the value a scene or the command names; a body of one's own: its file
                              * or expression (gb_body.h) */
    const char *chi_formula; /* the paper's χ, for reports */
    const char *equations;   /* where the paper defines it ("" for a body of one's own) */
    /* χ and its derivatives; `self` is this row (a body of one's own reads its expression from user) */
    void (*phase)(const struct gb_morphology *self, double phi, double theta, gb_phase_value *out);
    /* The same and sin χ, cos χ, from sin and cos of φ and θ (gb_surface_eval's fast path). */
    void (*phase_eval)(const struct gb_morphology *self, double phi, double theta, double sin_phi, double cos_phi,
                       double sin_theta, double cos_theta, gb_phase_value *out, double *sin_chi, double *cos_chi);
    /* sinφ cos χ as an interval jet of the unit direction s (for gb_surface_enclose); returns 1 when
     * it is C² over the jet's box, 0 when its second derivatives hold the Hessian only where it exists.
     * NULL: no enclosure is known (a body given by an expression): the body is not certified. */
    int (*kernel_jet)(const struct gb_jet *s, struct gb_jet *out); /* s: three jets (gb_interval.h) */
    /* A unit vector on the body's two-fold rotation axis through the minimum of r (see
     * gb_shape): the rotation by π about it maps the surface onto itself; 0 when none is known. */
    double symmetry_axis[3];
    /* A body given by r itself (gb_body.h): the kernel S = r⁴ and its derivatives S, S_φ, S_θ, S_φφ, S_φθ,
     * S_θθ, in place of the phase (phase and phase_eval NULL). NULL for a body given by χ. */
    void (*kernel)(const struct gb_morphology *self, double beta, double phi, double theta, double S[6]);
    const void *user;                         /* a body of one's own: its expression (gb_body.c) */
    const struct gb_polyhedron *polyhedron;   /* a convex polyhedron ([body] mesh): no phase; its hull's vertices,
                                               * centred on the centroid, are the body's points (gb_body.h) */
    /* Where the chart's origin (the point r is measured from) lies in the body's axes, whose origin is the
     * centroid: x = r u + origin (eq 2, moved). Zero for the paper's bodies, whose centroid is their chart's
     * origin exactly (docs/bodies.md); a body given by an expression is moved to its centroid (gb_body.h). */
    double origin[3];
    int moved; /* origin is not zero */
    /* The body kind's own mass properties for `mass` (its volume, centroid, inertia and L; gb_massprops.h), in closed
     * form (a polyhedron's: gb_body.c); NULL: gb_massprops integrates the surface. */
    int (*massprops)(const struct gb_morphology *self, double mass, struct gb_massprops *out);
} gb_morphology;


GB_API size_t gb_surface_morphology_count(void);
GB_API const gb_morphology *gb_surface_morphology_at(size_t index);
/* The morphology called `name`, or NULL. */
GB_API const gb_morphology *gb_surface_morphology_find(const char *name);

/* β must satisfy 0 ≤ β < 1/4: S ≥ 1 − 4β on the sphere, with equality reached, so r is real and
 * positive everywhere exactly when β < 1/4. */
#define GB_SURFACE_BETA_MAX 0.25

typedef struct gb_surface {
    const gb_morphology *morphology;
    double beta;
} gb_surface;

/* 1 when the body is a convex polyhedron (a mesh: the grid contact models only, nodes = its vertices), 0 when
 * it is r(φ, θ) of eq 12; the certificate needs kernel_jet as well. */
static inline int gb_surface_is_polyhedron(const gb_surface *surface) { return surface->morphology->polyhedron != 0; }

/* Fill `surface`; GB_EINVAL for an unknown morphology, GB_EDOM for β outside [0, 1/4). */
GB_API int gb_surface_init(gb_surface *surface, const char *morphology, double beta);

/* Everything §2 defines at one parameter point. Derivatives of the kernel and radius are eq 13/14
 * and their second-order extensions; tangents eq 15; n = ∂φx × ∂θx (eq 16), outward; n̂ eq 17. */
typedef struct gb_surface_point {
    double phi, theta;
    gb_phase_value phase;
    double S, S_phi, S_theta, S_phiphi, S_phitheta, S_thetatheta;
    double r, r_phi, r_theta, r_phiphi, r_phitheta, r_thetatheta;
    double u[3], u_phi[3], u_theta[3], u_phiphi[3], u_phitheta[3], u_thetatheta[3];
    double x[3], x_phi[3], x_theta[3], x_phiphi[3], x_phitheta[3], x_thetatheta[3];
    double n[3], n_hat[3];
} gb_surface_point;

GB_API void gb_surface_eval(const gb_surface *surface, double phi, double theta, gb_surface_point *point);

/* Cheap paths for hot loops: the kernel S (eq 11), r (eq 12) and x (eq 2) only. */
GB_API double gb_surface_kernel(const gb_surface *surface, double phi, double theta);
GB_API double gb_surface_radius(const gb_surface *surface, double phi, double theta);
GB_API void gb_surface_position(const gb_surface *surface, double phi, double theta, double x[3]);

/* β-sensitivity at fixed (φ, θ): ∂r/∂β (eq 66), ∂x/∂β (eq 67), ∂h/∂β = z_bᵀ ∂x/∂β (eq 68). */
GB_API double gb_surface_radius_dbeta(const gb_surface *surface, double phi, double theta); /* NaN: r given by an expression */
GB_API void gb_surface_position_dbeta(const gb_surface *surface, double phi, double theta, double dx[3]);
GB_API double gb_surface_height_dbeta(const gb_surface *surface, double phi, double theta, const double zb[3]);

/* The unit direction u(φ, θ) of eq 1. */
GB_API void gb_surface_direction(double phi, double theta, double u[3]);

/* Enclosures over parameter boxes (the certified contact search, gb_certify, uses them).
 *
 * Two charts of the sphere of directions, both regular away from their own poles:
 *  GB_SURFACE_CHART_POLAR_Z  (a, b) = (φ, θ): u = (sin a cos b, sin a sin b, cos a), eq 1;
 *  GB_SURFACE_CHART_POLAR_X  (a, b) = (α, γ): u = (cos a, sin a cos b, sin a sin b), whose poles are ±e_x,
 *                            so it covers the (φ, θ) poles ±e_z regularly. */
typedef enum gb_surface_chart { GB_SURFACE_CHART_POLAR_Z = 0, GB_SURFACE_CHART_POLAR_X = 1 } gb_surface_chart;

/* Chart coordinates of the direction (φ, θ) (b in [0, 2π) for POLAR_X), and back (θ in [0, 2π)). */
GB_API void gb_surface_chart_coordinates(gb_surface_chart chart, double phi, double theta, double *a, double *b);
GB_API void gb_surface_chart_angles(gb_surface_chart chart, double a, double b, double *phi, double *theta);

#ifdef __cplusplus
}
#endif

#endif
