/* gb_impact_internal — what the impact law's two files share (gb_impact.c: Moreau's law on a rough plane;
 * gb_impact_coulomb.c: a plane of finite friction): the body's algebra, the Delassus system of the held
 * points, and the result's bookkeeping. Not installed, not exported. */
#ifndef GB_IMPACT_INTERNAL_H
#define GB_IMPACT_INTERNAL_H

#include "gb_impact.h"

#include <stddef.h>

/* Relative tolerances: a Delassus system solved by SVD keeps about 1e-13 of its scale; the signs of the
 * law are judged 1e-10 of the impact's own scale beyond that, so that a contact exactly at the edge of
 * holding (a normal impulse or velocity of rounding size) is not refused. */
#define GB_IMPACT_SINGULAR_CUT 1e-12
#define GB_IMPACT_SIGN_TOL 1e-10
#define GB_IMPACT_RESIDUAL_TOL 1e-9

/* The inverse of a symmetric positive definite 3×3 matrix: 0, or 1 when it is not positive definite. */
int gb_impact_invert(const double a[3][3], double out[3][3]);
/* [r]×, the matrix of r × . */
void gb_impact_cross_matrix(const double r[3], double out[3][3]);
/* The velocities after impulses P[k] at the points: v⁺ = v⁻ + ΣP/m, ω⁺ = ω⁻ + I⁻¹ Σ r × P. */
void gb_impact_apply(const gb_impact_body *body, const double inv[3][3], const double (*points)[3], int count,
                     const double (*P)[3], const double v[3], const double omega[3], double v_out[3], double omega_out[3]);
/* The velocity of the body point r: v + ω × r. */
void gb_impact_point_velocity(const double v[3], const double omega[3], const double r[3], double u[3]);
/* The block W_kj = I/m − [r_k]× I⁻¹ [r_j]× of the Delassus operator: the velocity of point k per impulse at j. */
void gb_impact_delassus(const gb_impact_body *body, const double inv[3][3], const double rk[3], const double rj[3],
                        double out[3][3]);
/* The impulses at the held contacts (mask) that change their velocities by rhs[k]: the Delassus system by
 * SVD (minimum norm where it is singular). 0, or 1 when it has no solution. */
int gb_impact_held(const gb_impact_body *body, const double inv[3][3], const double (*points)[3], int count, unsigned mask,
                   const double (*rhs)[3], double (*P)[3]);
/* The minimum-norm solution x of the square system a x = b (size ≤ GB_IMPACT_SYSTEM_MAX) by SVD (singular
 * values below GB_IMPACT_SINGULAR_CUT of the largest cut); a is overwritten by U, v_data and s_data keep V
 * and the singular values (the cut ones' columns of V span what the system leaves open). 0, or 1 when the
 * residual exceeds GB_IMPACT_RESIDUAL_TOL of b. */
#define GB_IMPACT_SYSTEM_MAX (3 * GB_IMPACT_CONTACTS_MAX)
int gb_impact_min_norm(double *a, const double *b, size_t size, double *x, double *v_data, double *s_data);
/* The body's inverse inertia, and the count of points, checked (GB_EDOM). */
int gb_impact_check_body(const gb_impact_body *body, int count, double inv[3][3]);
/* The result's impulses, their normal and tangential parts and the friction they need, from P. */
void gb_impact_fill(const double normal[3], int count, unsigned mask, const double (*P)[3], double impulse_tol,
                    gb_impact_result *out);
/* The distinct points (GB_IMPACT_SAME_POINT): their number, the points in `unique`, each point's first twin. */
int gb_impact_distinct(const double (*points)[3], int count, double (*unique)[3], int *twin);
/* A result over the distinct points spread back over all of them (a later twin holds as its first, with no
 * impulse of its own). */
void gb_impact_spread(const gb_impact_result *reduced, const int *twin, int count, gb_impact_result *out);
/* A tangent basis t1, t2 of the plane of unit normal n (right-handed with n). */
void gb_impact_tangents(const double n[3], double t1[3], double t2[3]);
/* The settle rule's lumped impact on a plane of finite friction: every point held at rest in the normal
 * direction (plastic), each sticking or sliding by the cone, a pull allowed (the caller bounds it) — as
 * gb_impact_hold_all on the rough plane. GB_ENUMERIC when no split into sticking and sliding does it. */
int gb_impact_coulomb_hold(const gb_impact_body *body, const double normal[3], double mu, const double (*points)[3],
                           int count, const double v[3], const double omega[3], gb_impact_result *out);
/* Moreau's law with Coulomb's cone at the velocity level, as a time step of Moreau and Jean poses it: the held points
 * leave at the normal velocities target[k] (−e u_n at the step's start), sticking or sliding against the slip after;
 * the others do not fall below their target; the held points' velocities within `tolerance` of the speed of their
 * targets (the speed: the largest velocity before or target). Every set of held points is enumerated, the smallest first, each split
 * into sticking and sliding as gb_impact_coulomb does for several points; the first that satisfies the law's signs.
 * The time-stepping strategy's answer on at most GB_IMPACT_CONTACTS_MAX points where Siconos's solvers stall
 * (gb_dynamics_stepping.c). GB_ENUMERIC when no set does it. */
int gb_impact_coulomb_targets(const gb_impact_body *body, const double normal[3], double mu, const double (*points)[3],
                              int count, const double v[3], const double omega[3], const double *target,
                              double tolerance, gb_impact_result *out);

#endif
