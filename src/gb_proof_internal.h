/* gb_proof_internal — what the proofs' files share: Arb's balls to and from intervals of doubles, the precision's
 * range, the CPU clock. Not exported. */
#ifndef GB_PROOF_INTERNAL_H
#define GB_PROOF_INTERNAL_H

#include "gb_proof.h"

#include <arb.h>

/* The ball x as an interval of doubles rounded outwards. */
gb_proof_interval gb_proof_interval_of(const arb_t x);

/* The interval [lo, hi] of doubles as a ball (exact endpoints). */
void gb_proof_ball_of(arb_t out, gb_proof_interval x, slong prec);

/* The lower (upper = 0) or upper half of x, split at its middle; and whether that middle lies strictly inside x (a
 * piece can still be halved). */
gb_proof_interval gb_proof_half(gb_proof_interval x, int upper);
int gb_proof_halvable(gb_proof_interval x);

/* out = x d for a double d (exact as a ball). */
void gb_proof_mul_d(arb_t out, const arb_t x, double d, slong prec);

/* The top of the paper's bodies: sinφ cos χ = 1 only at φ = π/2, χ = 0, which is θ = π/2 for I (χ = θ − 5φ) and θ = 0
 * for II; there χ_θ = 1 and χ_φ = −5 (I), 3π/2 (II). s₀ (a coordinate axis), u_θ there, χ_φ as a number times π when
 * *pi_multiple. GB_EDOM for another body or β outside (0, 1/4) (gb_proof_body.c). */
struct gb_surface;
int gb_proof_body_top(const struct gb_surface *s, double s0[3], double tangent_theta[3], double *chi_phi_num, int *pi_multiple);

/* The rocking direction e as a unit vector ⊥ s₀ on Arb's balls (the component along the axis s₀ dropped, then
 * normalised): GB_EDOM when nothing is left across s₀ (gb_proof_body.c). */
int gb_proof_body_axis(arb_ptr e, const double rocking[3], const double s0[3], slong prec);

/* GB_EDOM naming the allowed range when precision is outside it. */
int gb_proof_check_precision(long precision);

/* CPU seconds of the calling thread. */
double gb_proof_cpu_seconds(void);

/* task(ctx, k) for k = 0 … count − 1 on up to `threads` threads (1 or less: in turn on the caller's), each k once,
 * handed to whichever thread is free; after a task fails no other starts. Tasks must write only their own outputs.
 * The first failure's status, its message set on the caller's thread; GB_ENOMEM. *seconds (NULL: not wanted): the CPU
 * time of the threads made for the tasks (0 when the caller's ran them, its own clock counting them then). */
int gb_proof_for_each(size_t count, int threads, int (*task)(void *ctx, size_t k), void *ctx, double *seconds);

#endif
