/* gb_massprops — volume, centroid, inertia tensor and the length scale L of a homogeneous body
 * (paper §2; §6 eq 53), by nested one-dimensional GSL adaptive quadrature over the sphere.
 *
 * With dΩ = sin φ dφ dθ, the integrals over the solid reduce to surface integrals of powers of r:
 *   V = ∫ r³/3 dΩ,  ∫x dV = ∫ r⁴/4 u dΩ,  ∫x xᵀ dV = ∫ r⁵/5 u uᵀ dΩ,  L = (1/4π) ∫ r dΩ (eq 53).
 * The inner integral runs over φ ∈ [0, π], the outer over θ ∈ [0, 2π]; both with gsl_integration_qag.
 * The paper never states the inertia tensor: we take the body homogeneous with mass m. */
#ifndef GB_MASSPROPS_H
#define GB_MASSPROPS_H

#include "gb_export.h"

#include "gb_surface.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gb_massprops_def {
    double mass;         /* m > 0 (Table 1: 1) */
    double epsabs;       /* absolute target of each 1-D quadrature */
    double epsrel;       /* relative target of each 1-D quadrature */
    size_t limit;        /* subintervals per 1-D quadrature */
} gb_massprops_def;

GB_API gb_massprops_def gb_massprops_default_def(void);

typedef struct gb_massprops {
    double mass, density;
    double volume, volume_err;
    double centroid[3], centroid_err[3];
    double inertia[3][3], inertia_err[3][3]; /* about the centroid, body axes */
    double L, L_err;
    size_t evaluations;                      /* integrand evaluations, all integrals */
} gb_massprops;

/* GB_EDOM for a non-positive mass or tolerances; GB_ENOCONV when a quadrature fails. The error
 * estimates bound |computed − exact| as outer abserr + 2π · max inner abserr (the inner errors
 * enter the outer integral at most with weight 2π), propagated through the formulas above. */
GB_API int gb_massprops_compute(const gb_surface *surface, const gb_massprops_def *def, gb_massprops *out);

#ifdef __cplusplus
}
#endif

#endif
