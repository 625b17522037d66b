/* gb_melnikov — separatrix splitting in a reduced one-degree-of-freedom model (paper §7, eqs 78–93).
 *
 * The model: H₀ = p²/(2M(q)) + U(q) (eqs 79–80) with a saddle q_u of U (U′ = 0, U″ < 0, eq 81),
 * perturbed by ṗ += ε G, G = −μp + ν₁S(q) cos ωt + ν₂S(q) cos(2ωt + ψ) (eqs 84–85). Its separatrix
 * orbit (eq 83) is either a loop (from the saddle to a turning point q_t where U(q_t) = E_s, and back)
 * or, for a potential of period P, a rotation from q_u to q_u ± P.
 *
 * The orbit is computed two independent ways: t(q) = ∫ M/|p| dq by GSL quadrature in q (QAWS for the
 * square-root singularity at a turning point), and the flow of eq 78 integrated with GSL's rk8pd from
 * the saddle's unstable direction. The integrals of eqs 88–90 are GSL adaptive quadratures in q, with the
 * ends at the saddle mapped to u = −ln|q − q_u| ∈ [u₀, ∞) (QAGIU), where the integrand decays as e^{−u}.
 *
 * The weight. For ṗ = −∂H₀/∂q + εG the first-order splitting is ∫ q̇_h G dt (the wedge of the vector
 * field with (0, G)); eq 86 writes ∫ p_h G dt, the same only when M ≡ 1. Both are offered:
 * GB_MELNIKOV_EXACT (q̇ = p/M) and GB_MELNIKOV_PAPER (p); the direct-splitting check tells them apart.
 *
 * The criterion. With the integrals, M(t₀) = −μD + ν₁(C₁ cos ωt₀ − S₁ sin ωt₀) + ν₂(C₂ cos(2ωt₀ + ψ) −
 * S₂ sin(2ωt₀ + ψ)) (eq 91). Eq 93, ν₁A₁* + ν₂A₂* > μD, bounds the oscillatory part from above: it is
 * necessary for a sign change, and sufficient only when both harmonics peak at the same t₀. The exact
 * condition is max over t₀ of the oscillatory part > μD, a one-dimensional maximisation. */
#ifndef GB_MELNIKOV_H
#define GB_MELNIKOV_H

#include "gb_export.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gb_melnikov_values {
    double M, dM, U, dU, S; /* at one q: the effective mass and its derivative, the potential and its
                               derivative, the coupling of the vertical excitation */
} gb_melnikov_values;

typedef int (*gb_melnikov_eval)(void *context, double q, gb_melnikov_values *out);

typedef struct gb_melnikov_model {
    gb_melnikov_eval eval;
    void *context;
    double saddle_lo, saddle_hi; /* a bracket in which U′ changes sign once, at the saddle */
    int direction;               /* +1: the orbit leaves the saddle towards larger q; −1: smaller */
    double period;               /* > 0: U, M, S have this period and the orbit is a rotation; 0: a loop */
    double reach;                /* a loop's turning point lies within |q − q_u| < reach */
    double origin;               /* a rotation's t = 0 point (NAN: where U is lowest); keep it where U
                                    is smooth: the splitting is measured on the normal to the flow there */
    const double *knots;         /* optional: the q in [0, period) where eval's pieces join (its
                                    interpolation nodes and ties), ascending; a table's panels end there */
    size_t n_knots;
} gb_melnikov_model;

typedef struct gb_melnikov_orbit {
    double q_u, E_s, curvature;  /* the saddle, U(q_u) (eq 82), U″(q_u) */
    double rate;                 /* the saddle's unstable rate λ = √(−U″/M) at q_u */
    double q_end;                /* a loop's turning point q_t, or a rotation's q_u ± P */
    double q0;                   /* where t = 0: the turning point, or a rotation's lowest U */
} gb_melnikov_orbit;

/* The saddle (GSL Brent on U′ in the bracket), E_s, the rate and the far end of the separatrix.
 * GB_EDOM when the bracket holds no saddle (U′ keeps its sign, or U″ ≥ 0 there: a sphere has none),
 * when M ≤ 0, or when a loop finds no turning point within `reach` (the orbit escapes). */
GB_API int gb_melnikov_orbit_find(const gb_melnikov_model *model, gb_melnikov_orbit *out);

/* t(q) on the separatrix by quadrature in q (t = 0 at q0; t < 0 between the saddle and q0 on the way
 * out, for a loop the outgoing half). */
GB_API int gb_melnikov_time(const gb_melnikov_model *model, const gb_melnikov_orbit *orbit, double q, double *t);

typedef enum gb_melnikov_weight { GB_MELNIKOV_EXACT = 0, GB_MELNIKOV_PAPER = 1 } gb_melnikov_weight;

typedef struct gb_melnikov_integrals {
    double omega;
    double D, C1, S1, C2, S2;    /* eqs 88–90 with the chosen weight */
    double D_mass;               /* ∫ w p/M dt: the damping integral of −c q̇ = −(c/M(q)) p */
    double A1, A2;               /* eq 92 */
} gb_melnikov_integrals;

GB_API int gb_melnikov_integrals_compute(const gb_melnikov_model *model, const gb_melnikov_orbit *orbit, double omega,
                                         gb_melnikov_weight weight, gb_melnikov_integrals *out);

typedef struct gb_melnikov_forcing {
    double mu, nu1, nu2, omega, psi;
    int damping_per_mass;        /* 0: G ∋ −μp (eq 85); 1: −μ p/M(q) (the full model's −c q̇, μ = c) */
} gb_melnikov_forcing;

/* Eq 91. */
GB_API double gb_melnikov_function(const gb_melnikov_integrals *integrals, const gb_melnikov_forcing *forcing,
                                   double t0);

/* Eq 86 directly: ∫ w G(q_h, p_h, t + t₀) dt by quadrature along the orbit (w = q̇ or p). */
GB_API int gb_melnikov_direct(const gb_melnikov_model *model, const gb_melnikov_orbit *orbit,
                              const gb_melnikov_forcing *forcing, gb_melnikov_weight weight, double t0, double *value);

typedef struct gb_melnikov_criterion {
    int eq93;                    /* |ν₁|A₁* + |ν₂|A₂* > μD */
    int sign_change;             /* max over t₀ of the oscillatory part > μD */
    double oscillatory_max;      /* that maximum */
    double t0_max;               /* where it is reached, in [0, 2π/ω) */
} gb_melnikov_criterion;

GB_API void gb_melnikov_judge(const gb_melnikov_integrals *integrals, const gb_melnikov_forcing *forcing,
                              gb_melnikov_criterion *out);

/* The critical scale of the forcing: the smallest s such that (sν₁, sν₂) makes M(t₀) change sign, by
 * eq 93 (s = μD/(ν₁A₁* + ν₂A₂*)) and exactly (s = μD / max oscillatory part at s = 1). */
GB_API void gb_melnikov_threshold(const gb_melnikov_integrals *integrals, const gb_melnikov_forcing *forcing,
                                  double *by_eq93, double *exact);

/* The separatrix of a rotation (period > 0) tabulated once for every frequency up to omega_max: the
 * path of gb_melnikov_integrals_compute cut into panels in u (ending at the model's knots, each at
 * most 0.5 wide and spanning a phase 2 omega_max |dt| of at most 1.5 rad), with t, q, |p|
 * and the model's values at each panel's Gauss–Legendre nodes (t itself by Gauss–Legendre from the
 * panel's start). The integrals at a frequency are then sums over the nodes plus the saddle tails: the
 * same integrals as gb_melnikov_integrals_compute, to its tolerance (the harness compares the two).
 * GB_EDOM for a loop (period 0) and for omega_max outside (0, 10⁴]. */
typedef struct gb_melnikov_table gb_melnikov_table;

GB_API int gb_melnikov_table_create(const gb_melnikov_model *model, const gb_melnikov_orbit *orbit,
                                    gb_melnikov_weight weight, double omega_max, gb_melnikov_table **out);
/* GB_EDOM for omega outside (0, omega_max]. */
GB_API int gb_melnikov_table_integrals(const gb_melnikov_table *table, double omega, gb_melnikov_integrals *out);
GB_API size_t gb_melnikov_table_nodes(const gb_melnikov_table *table);
GB_API void gb_melnikov_table_free(gb_melnikov_table *table);

/* The integrals at any ω from tables kept per octave of ω (a table of ω_max = 16, 32, 64, 128 or
 * 256 rad/s serves the ω above the octave below: 16 serves every ω ≤ 16), so that an ω's integrals do
 * not depend on which other ω were asked for: a scan's margins and `gomboc melnikov`'s agree bit for
 * bit. Above 256 rad/s the adaptive path (gb_melnikov_integrals_compute). `prepare` builds the octave's
 * table if missing (not thread-safe); `integrals` only reads (thread-safe), GB_EINVAL if unprepared. */
#define GB_MELNIKOV_TABLES_OMEGA 256.0
typedef struct gb_melnikov_tables gb_melnikov_tables;

GB_API int gb_melnikov_tables_create(const gb_melnikov_model *model, const gb_melnikov_orbit *orbit,
                                     gb_melnikov_weight weight, gb_melnikov_tables **out);
GB_API int gb_melnikov_tables_prepare(gb_melnikov_tables *tables, double omega);
GB_API int gb_melnikov_tables_integrals(const gb_melnikov_tables *tables, double omega, gb_melnikov_integrals *out);
GB_API void gb_melnikov_tables_free(gb_melnikov_tables *tables);

/* The first-order splitting distance ε M(t₀)/|f(x_h(0))| predicted at the orbit's t = 0 point, and its
 * direct measurement for a perturbation of damping alone (G = −μp; the saddle stays put): the unstable
 * manifold integrated forward and the stable one backward (rk8pd) to the line through x_h(0) normal to
 * the flow, their signed distance along (−f_p, f_q)/|f|. */
GB_API int gb_melnikov_split_damped(const gb_melnikov_model *model, const gb_melnikov_orbit *orbit, double epsilon_mu,
                                    double *measured, double *flow_speed);

/* The same under the whole perturbation εG at phase t₀: the saddle becomes a hyperbolic periodic orbit
 * (a fixed point of the period map, by Newton); points of its unstable manifold at time t₀ are flowed
 * from t₀ − kT, of its stable manifold from t₀ + kT, both found on the section normal to the flow at
 * x_h(0) by bisection on their displacement along the map's eigenvectors. To compare with
 * ε M(t₀)/|f(x_h(0))|. */
GB_API int gb_melnikov_split_forced(const gb_melnikov_model *model, const gb_melnikov_orbit *orbit,
                                    const gb_melnikov_forcing *forcing, double epsilon, double t0, double *measured,
                                    double *flow_speed);

/* The manifolds of a rotation's saddle under the whole perturbation εG, away from ε → 0: where the first
 * order's verdict (a zero of M(t₀) or none) can be compared with the manifolds themselves. The period map P
 * at phase t₀ (the flow from t₀ to t₀ + T, T = 2π/ω) has the saddle's periodic orbit as a hyperbolic fixed
 * point x (gb_melnikov_split_forced's Newton); the unstable branch leaving x in the orbit's direction and the
 * stable branch entering its copy x ± (P, 0) are grown from a fundamental domain each: the points x + s v
 * with s from `start` to `start` times the multiplier (log-uniform in s, the domain's parameter σ ∈ [0, 1]),
 * mapped by P (unstable) or P⁻¹ (stable) `iterates` times, with points inserted wherever neighbouring images
 * are more than `spacing` apart (each inserted point mapped afresh from its σ). Every crossing of the two
 * curves is located; a crossing is a homoclinic point of the map on the cylinder (q mod P), and each
 * homoclinic orbit crosses each fundamental domain of the unstable branch once. The count in one domain,
 * u ∈ [k, k + 1) with k half the unperturbed passage (both branches well inside their iterates), is the
 * number of homoclinic orbits whose passage is at most that of the separatrix plus about three periods:
 * at small ε, the simple zeros of M(t₀) in a period. Rotations only (GB_EDOM for a loop). */
typedef struct gb_melnikov_tangle_def {
    double epsilon;    /* the perturbation's scale: 1 is the forcing as given (> 0) */
    double t0;         /* the period map's phase [s] */
    double start;      /* the fundamental domains' first displacement from the fixed point (1e-12 to 1e-3) */
    double spacing;    /* the largest distance between neighbouring points of a curve (1e-4 to 0.1) */
    size_t max_points; /* a branch's points in all (≥ 100); GB_ENOCONV beyond */
    int keep_curves;   /* 1: the result keeps both branches' points (curve[], below) */
} gb_melnikov_tangle_def;

GB_API gb_melnikov_tangle_def gb_melnikov_tangle_default_def(void); /* 1, 0, 1e-7, 0.01, 400000, 0 */

typedef struct gb_melnikov_crossing {
    double u, s;       /* where on the unstable and the stable branch: iterates + σ */
    double q, p;       /* the homoclinic point at phase t₀ (q unwrapped: from the saddle towards its copy) */
    double angle;      /* between the two curves there [rad], in (0, π/2] */
    int confirmed;     /* 1: the curves' pieces around it, drawn within 1e-6, cross (u, s, q, p, angle are
                          theirs); 0: only the chords did; −1: outside the window, not examined */
    size_t segment_unstable, segment_stable; /* the chords that crossed */
} gb_melnikov_crossing;

typedef struct gb_melnikov_tangle {
    double saddle[2];             /* the fixed point x */
    double multipliers[2];        /* unstable, stable */
    double passage;               /* the separatrix's time from q_u + start to its copy − start, in periods */
    int iterates;                 /* each branch's images of its fundamental domain: ⌈passage/2⌉ + 2 */
    int window;                   /* k: the fundamental domain u ∈ [k, k + 1) counted */
    size_t points_unstable, points_stable;
    double widest_gap;            /* the largest distance left between neighbouring points (σ could not be split) */
    size_t crossings;             /* all crossings found */
    gb_melnikov_crossing *crossing; /* sorted by u */
    size_t in_window;             /* confirmed crossings with u in the window: homoclinic orbits */
    double smallest_angle;        /* among those [rad]; NAN when none */
    double *curve[2];             /* with keep_curves: the unstable [0] and stable [1] branch as (u or s, q, p)
                                     triples in the order grown, curve_points[k] of them; else NULL */
    size_t curve_points[2];
} gb_melnikov_tangle;

GB_API int gb_melnikov_tangle_compute(const gb_melnikov_model *model, const gb_melnikov_orbit *orbit,
                                      const gb_melnikov_forcing *forcing, const gb_melnikov_tangle_def *def,
                                      gb_melnikov_tangle *out);
GB_API void gb_melnikov_tangle_free(gb_melnikov_tangle *tangle);

/* The scale s of the forcing's harmonics (ν₁, ν₂ times s, the damping kept) at which the manifolds start
 * to cross, bracketed: bracket[0] a scale without a confirmed crossing in the window, bracket[1] one with.
 * s = 0 (damping alone: the energy only falls) has none; s = 1, 2, 4, 8, 16 are tried until one crosses
 * (none: bracket[1] = ∞), then `halvings` bisections (0 to 30). Crossing need not be monotone in s: the
 * bracket holds a transition, not necessarily the first. To set against the first order's threshold
 * (gb_melnikov_threshold's exact scale). */
GB_API int gb_melnikov_tangle_threshold(const gb_melnikov_model *model, const gb_melnikov_orbit *orbit,
                                        const gb_melnikov_forcing *forcing, const gb_melnikov_tangle_def *def,
                                        int halvings, double bracket[2]);

/* The second, independent orbit: the flow of eq 78 (rk8pd) started on the saddle's unstable direction,
 * and the time it takes from q = q_a to q = q_b (both on the way out from the saddle, before a loop's
 * turning point). To compare with gb_melnikov_time(q_b) − gb_melnikov_time(q_a). */
GB_API int gb_melnikov_flight_time(const gb_melnikov_model *model, const gb_melnikov_orbit *orbit, double q_a,
                                   double q_b, double *dt);

#ifdef __cplusplus
}
#endif

#endif
