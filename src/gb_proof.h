/* gb_proof — statements proved on Arb's balls (Debian libflint-arb-dev: ball arithmetic whose every result
 * encloses the exact one, with proven bounds for the elementary functions and a rigorous quadrature).
 *
 * Nothing here is estimated: every number this module calls proved is an interval computed from Arb balls and
 * rounded outwards to doubles, and a statement is proved only when the intervals decide it; otherwise it says
 * undecided. The fast interval arithmetic of the certificate (gb_interval.h) stays where it is; it is checked
 * against Arb in verify/s7_proofs.c.
 *
 * Stage 1 of the separatrix splitting (paper §7, eqs 86–93), as far as it goes today (docs/proofs.md):
 * - the oracles: the Melnikov integrals of the pendulum q'' = −sin q and of Duffing's x'' = x − x³ enclosed by
 *   rigorous quadrature along their homoclinic orbits (closed forms in t), the tails beyond ±T bounded in closed
 *   form; and their closed forms (by residues) enclosed apart — the two must meet;
 * - the zeros of M(t₀) = −μD + ν₁(C₁ cos ωt₀ − S₁ sin ωt₀) + ν₂(C₂ cos(2ωt₀ + ψ) − S₂ sin(2ωt₀ + ψ)) (eq 91)
 *   over one period, for integrals given as intervals: simple zeros proved (a sign change with M′ bounded away
 *   from 0 on an interval that holds it: exactly one there), M ≠ 0 proved (|M| bounded below on a cover of the
 *   period), or undecided. */
#ifndef GB_PROOF_H
#define GB_PROOF_H

#include "gb_export.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* A closed interval of reals [lo, hi], rounded outwards from an Arb ball. */
typedef struct gb_proof_interval {
    double lo, hi;
} gb_proof_interval;

/* Arb's working precision in bits: allowed 64 ... 4096 (the default 128). */
#define GB_PROOF_PRECISION_MIN 64
#define GB_PROOF_PRECISION_MAX 4096
#define GB_PROOF_PRECISION_DEFAULT 128

typedef enum gb_proof_system { GB_PROOF_PENDULUM = 0, GB_PROOF_DUFFING = 1 } gb_proof_system;
GB_API const char *gb_proof_system_name(gb_proof_system system);

/* The Melnikov integrals of eqs 88–90 with the exact weight and S ≡ 1, at the forcing frequency ω and 2ω:
 *   pendulum q'' = −sin q (the rotation orbit over the saddle q = ±π: p_h = 2 sech t),
 *   Duffing x'' = x − x³ (the right loop: x_h = √2 sech t, p_h = −√2 sech t tanh t). */
typedef struct gb_proof_integrals {
    gb_proof_system system;
    double omega;              /* > 0, at most 64 */
    long precision;            /* bits */
    gb_proof_interval D, C1, S1, C2, S2; /* by quadrature: ∫ p_h² dt, ∫ p_h cos(kωt) dt, ∫ p_h sin(kωt) dt */
    gb_proof_interval closed[5];         /* the closed forms of the same five, enclosed apart */
    double horizon;            /* T: quadrature on [−T, T], the tails bounded in closed form */
    int consistent;            /* each quadrature interval meets its closed form's */
    double seconds;            /* CPU */
} gb_proof_integrals;

/* GB_EDOM for ω or the precision out of range; GB_ENUMERIC when Arb's quadrature does not reach the precision. */
GB_API int gb_proof_oracle_integrals(gb_proof_system system, double omega, long precision, gb_proof_integrals *out);

/* M(t₀) over one period 2π/ω of eq 91, from its integrals as intervals and its exact parameters. */
typedef struct gb_proof_melnikov {
    gb_proof_interval D, C1, S1, C2, S2;
    double mu, nu1, nu2, omega; /* μ ≥ 0, ν₁, ν₂ real, ω > 0 */
    gb_proof_interval psi;      /* the second harmonic's phase (an interval: π/3 is not a double) */
    long precision;
    int depth;                  /* the most bisections of an interval of t₀: 1 ... 40 (default 24) */
} gb_proof_melnikov;

typedef enum gb_proof_verdict {
    GB_PROOF_SIMPLE_ZEROS = 0, /* every zero in the period isolated in an interval with M′ ≠ 0 there: all simple */
    GB_PROOF_NO_ZERO = 1,      /* |M| > 0 over the whole period */
    GB_PROOF_UNDECIDED = 2     /* some interval decided neither way at the deepest bisection */
} gb_proof_verdict;
GB_API const char *gb_proof_verdict_name(gb_proof_verdict verdict);

enum { GB_PROOF_ZEROS_MAX = 16 };

typedef struct gb_proof_zeros {
    gb_proof_verdict verdict;
    size_t zeros;                                /* simple zeros proved in [0, 2π/ω) */
    gb_proof_interval where[GB_PROOF_ZEROS_MAX]; /* t₀ intervals, each holding exactly one of them */
    double slope_min;                            /* the least |dM/dt₀| proved on those intervals */
    double margin;                               /* NO_ZERO: a lower bound of |M| over the period */
    size_t boxes, undecided;                     /* intervals examined; left undecided */
    double seconds;
} gb_proof_zeros;

/* GB_EDOM for parameters out of range (named with their ranges); GB_OK with the verdict otherwise. */
GB_API int gb_proof_melnikov_zeros(const gb_proof_melnikov *def, gb_proof_zeros *out);

/* π num/den as an interval (den > 0, |num| ≤ 1e6, den ≤ 1e6): a phase such as ψ = π/3, which no double is. */
GB_API int gb_proof_pi_fraction(long num, long den, gb_proof_interval *out);

/* Does [lo, hi] hold the exact result of an operation of the gb_interval.h arithmetic the certificate uses, at
 * doubles x (and y)? "add", "sub", "mul" (x, y), "recip", "sqrt", "sin", "cos", "root4" (x). Decided by Arb at
 * rising precision (256 to 4096 bits: cos(1e-300) differs from 1 only at the 2000th bit): *holds 1 (inside), 0
 * (outside), −1 (undecided at 4096 bits). The check of that header against Arb. GB_EDOM for an unknown operation or
 * x outside its domain. */
GB_API int gb_proof_encloses(const char *operation, double x, double y, double lo, double hi, int *holds);

/* Frees the calling thread's caches of Arb and FLINT (constants such as π, kept per thread): a thread that proved
 * something calls it before it ends. The CPU seconds the proofs report are their own thread's. */
GB_API void gb_proof_thread_done(void);

#ifdef __cplusplus
}
#endif

#endif
