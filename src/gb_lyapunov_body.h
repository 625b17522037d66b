/* gb_lyapunov_body — a Gömböc as a system for the estimators of gb_lyapunov (paper §6, eqs 75–77): as a
 * pair system (two copies of the dynamics, the reference bit for bit a plain run of the scene) and, for
 * continuous contact with located switches, as a tangent system (the variational equation carried by
 * RK4, with a saltation at every located branch switch). gb_lyapunov itself knows no body. */
#ifndef GB_LYAPUNOV_BODY_H
#define GB_LYAPUNOV_BODY_H

#include "gb_export.h"

#include "gb_dynamics.h"
#include "gb_integrate.h"
#include "gb_lyapunov.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A Gömböc as a pair system (eq 77): two copies of the dynamics, each a resumable integration
 * (gb_integrate_session) with `integrate` that starts at t = 0; the pair advances them interval by
 * interval, and the reference takes exactly the steps of one plain run of the scene. The separation is a 6-vector: the rotation vector δθ that turns the
 * reference attitude into the perturbed one (body frame, rad), and (ω₂ − ω₁)/Ω with Ω =
 * omega_scale [rad/s] (the paper gives no norm; the forcing frequency makes both parts
 * dimensionless, and the exponent does not depend on the choice). After each placement the
 * perturbed copy takes over the reference's contact (gb_dynamics_adopt_contact). */
typedef struct gb_lyapunov_body gb_lyapunov_body;

GB_API int gb_lyapunov_body_create(const gb_surface *body, const gb_dynamics_def *dynamics,
                                   const gb_integrate_def *integrate, const double R0[9], const double omega0[3],
                                   double omega_scale, gb_lyapunov_body **out);
/* The same with the copies' dynamics in `context` (gb_dynamics_context; NULL: the pair's own): both share
 * the body's set-up and its atlas. */
GB_API int gb_lyapunov_body_create_in(const gb_surface *body, const gb_dynamics_def *dynamics,
                                      gb_dynamics_context *context, const gb_integrate_def *integrate,
                                      const double R0[9], const double omega0[3], double omega_scale,
                                      gb_lyapunov_body **out);
GB_API void gb_lyapunov_body_free(gb_lyapunov_body *body);
/* The pair system of `body`. Under the unilateral law the separation has four more coordinates, the
 * centroid's height and velocity relative to the plane, (ζ₂ − ζ₁)/L and (v₂ − v₁)/(Ω L) (inertial axes, L
 * the mean radius, eq 53), non-zero only while either copy flies (in contact both follow from the attitude
 * and ω); they are placed when the reference flies (gb_dynamics_flight_displace), and when it does not the
 * rotational part is scaled to the whole displacement's length, so that the copy always starts δ₀ away. */
GB_API gb_lyapunov_pair_system gb_lyapunov_body_pair(const gb_lyapunov_body *body);
/* The reference copy's dynamics and state (for its observables). */
GB_API gb_dynamics *gb_lyapunov_body_dynamics(gb_lyapunov_body *body);
GB_API const double *gb_lyapunov_body_state(const gb_lyapunov_body *body);
/* The step statistics of trajectory `which` (0: reference, 1: perturbed). */
GB_API const gb_integrate_stats *gb_lyapunov_body_stats(const gb_lyapunov_body *body, int which);
/* Deliver the reference's samples (every sample_every steps, as gb_integrate_run does; the sample at
 * t = 0 is the caller's) to `sample`. A sampler that asks to stop ends the estimate with an error. */
GB_API void gb_lyapunov_body_observe(gb_lyapunov_body *body, gb_integrate_sample sample, void *context);

/* The same body for the tangent estimator (eq 75): the reference stepped by RK4 (steps_per_period of
 * its integrate definition) together with k tangent vectors in the coordinates of the pair's
 * separation, e = (δθ, δω/Ω). Per step, the vectors obey the RK4 discretisation of Ẏ = A(t) Y, with A·Y by
 * central differences of the vector field (the contact re-solved at both points) and the radial part
 * of δq projected out. A branch switch is located inside its step (Δh = 0, eq 39), and the vectors
 * cross it with the saltation matrix S = I + (f⁺ − f⁻)∇gᵀ/(∇g·f⁻), g = Δh. Continuous contact, RK4 and
 * the held contact law only (gb_lyapunov_body_tangent_ready says why not); a body serves one estimator, not both. */
GB_API gb_lyapunov_tangent_system gb_lyapunov_body_tangent(void);
GB_API int gb_lyapunov_body_tangent_ready(const gb_lyapunov_body *body);
/* Switches crossed with a saltation; switches the accepted step's global check found that were not
 * located inside a step (no saltation applied); located switches grazing the flow (∇g·f⁻ = 0). */
GB_API void gb_lyapunov_body_tangent_counts(const gb_lyapunov_body *body, size_t *saltations, size_t *unlocated,
                                            size_t *grazing);
/* Of the located switches, those with no sign change of Δh inside the step (a branch born or lost in a
 * fold): the saltation formula assumes a crossing Δh = 0 and is only approximate there. */
GB_API size_t gb_lyapunov_body_tangent_jumps(const gb_lyapunov_body *body);

#ifdef __cplusplus
}
#endif

#endif
