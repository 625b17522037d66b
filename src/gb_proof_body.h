/* gb_proof_body — the Melnikov integrals of a Gömböc's reduced model (paper §7, eqs 78–93) enclosed from the body.
 *
 * The model is gb_melnikov_body's under the `top` mass reading: the body rocks about the axis a = z₀ × e through its
 * top, U(q) = m g (H(q) − r_max) with H(q) = max_x x·v(q) the support function in the direction v(q) = cos q s₀ −
 * sin q e (s₀ the top's direction, −z₀), M frozen at the top, S(q) = −m H′(q) (docs/melnikov.md). Its separatrix is
 * the rotation over the top from q = 0 to 2π, on which p = √(2 M m g (r_max − H(q))) and dt = M dq / p.
 *
 * What is enclosed, and how (docs/proofs.md, "The Gömböcs' reduced models"):
 * - the top: for the paper's bodies (S = 1 + 4β sinφ cos χ with χ_θ = 1) sinφ cos χ ≤ 1 with equality at one point
 *   only (φ = π/2 and χ = 0 there), so r_max = (1 + 4β)^{1/4} and s₀ is a coordinate axis, exactly; H(q) < r_max for
 *   0 < q < 2π (the only point at distance r_max is the top, reached only in the direction s₀); H″(0) from the
 *   Hessian of r at the top in closed form (negative: a hyperbolic saddle);
 * - H and H′ on cells of q: a branch-and-bound over boxes of the surface's charts (gb_surface_enclose, the
 *   certificate's interval arithmetic, checked against Arb in verify/s7_proofs.c). For an arc Q of q and a surface
 *   point x* a box is dropped when (x − x*)·v(q) < 0 over the box and Q (the maximiser for every q in Q is elsewhere),
 *   or when a chart derivative of x·v excludes 0 (no critical point). Then H(q) ∈ x*·v(q) + [0, E] on the cell, E the
 *   largest bound of (x − x*)·v over the boxes kept, and H′ (= x_c·v′ where the contact is unique, and between the
 *   one-sided values at a tie) lies in the hull of x·v′ over them. Arcs are halved, each keeping its parent's boxes,
 *   down to cells of width `resolution` × their distance to the saddle (at least `cut`);
 * - on Arb's balls: p on each cell, t(q) at the cells' ends summed from t(origin) = 0, and D = ∫ p dq,
 *   C_k = ∫ S cos(kωt) dq, S_k = ∫ S sin(kωt) dq as sums of cell enclosures; within `cut` of the saddle only bounds:
 *   0 ≤ ∫ p dq ≤ cut · max p and |∫ S (…) dq| ≤ cut · max |S| there;
 * - the piecewise structure of H on each cell from its kept boxes (gb_proof_body_ties.c): C², or at most one tie;
 *   on a C² cell H″ = −H − gᵀK⁻¹g (K the chart Hessian of x·v, g = (x_a·v′, x_b·v′)) over the kept boxes.
 * M enters as an interval (gb_proof_body_inertia encloses it): the statement holds for every M in it. */
#ifndef GB_PROOF_BODY_H
#define GB_PROOF_BODY_H

#include "gb_export.h"

#include "gb_proof.h"
#include "gb_surface.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Ranges of the definition. */
#define GB_PROOF_BODY_CUT_MIN 1e-4
#define GB_PROOF_BODY_CUT_MAX 0.2
#define GB_PROOF_BODY_RESOLUTION_MIN 1e-5
#define GB_PROOF_BODY_RESOLUTION_MAX 0.1

typedef struct gb_proof_body_arcs gb_proof_body_arcs;

typedef struct gb_proof_body_def {
    const gb_surface *surface;  /* the paper's Gömböc I or II, 0 < β < 1/4 */
    double mass, g;             /* m [kg] > 0, g [m/s²] > 0 */
    double rocking[3];          /* e (gb_melnikov_body_info.rocking): projected on the plane ⊥ s₀ and normalised on balls */
    gb_proof_interval inertia;  /* M, the moment of inertia about the contact line at the top [kg m²], lo > 0 */
    double origin;              /* where t = 0, in (cut, 2π − cut) */
    double cut;                 /* the saddle's neighbourhoods [0, cut] and [2π − cut, 2π] (GB_PROOF_BODY_CUT_MIN … MAX) */
    double resolution;          /* a cell's width over its distance to the saddle (GB_PROOF_BODY_RESOLUTION_MIN … MAX) */
    long precision;             /* Arb's bits */
    gb_proof_body_arcs *arcs;   /* NULL, or H's coefficients over fixed cells of q made for this definition
                                   (gb_proof_body_arcs_create), which the reduced field's integrations share */
} gb_proof_body_def;

typedef struct gb_proof_body_model {
    double top[3];              /* s₀ (exact) */
    gb_proof_interval r_max;    /* (1 + 4β)^{1/4} */
    gb_proof_interval curvature;/* H″(0) (closed form at the top): < 0 is the saddle's hyperbolicity */
    gb_proof_interval rate;     /* λ = √(−m g H″(0) / M) [1/s] */
    size_t cells;               /* cells of q enclosed */
    size_t boxes;               /* surface boxes enclosed in all */
    size_t kept_max;            /* the most boxes a cell kept */
    size_t smooth_cells;        /* cells (the two neighbourhoods of the saddle among them) on which H is proved C² */
    size_t tie_cells;           /* cells proved to hold at most one tie (two contacts, their heights' difference monotone) */
    size_t open_cells;          /* cells on which neither is proved (gb_proof_body_ties.c) */
    size_t curved_cells;        /* C² cells on which H″ is enclosed (the chart Hessian of x·v proved definite there) */
    double second_width_max;    /* the widest of those enclosures */
    double tie_q[8][2];         /* the first 8 tie cells' ranges of q */
    double gap_min;             /* the least lower bound of r_max − H over the cells (> 0: the orbit is a rotation) */
    double height_spread_max;   /* the widest E over the cells (H's excess over x*·v) */
    gb_proof_interval D;        /* ∫ p dq over [0, 2π] */
    double seconds;             /* CPU */
    struct gb_proof_body_cells *cells_data; /* for gb_proof_body_integrals; freed by gb_proof_body_free */
} gb_proof_body_model;

/* Encloses H, H′ and p over the separatrix and D. GB_EDOM for a definition out of range (named with its range) or a
 * body that is not the paper's I or II; GB_ENUMERIC when a cell cannot be enclosed (the gap not proved positive). */
GB_API int gb_proof_body_enclose(const gb_proof_body_def *def, gb_proof_body_model *out);

/* C₁, S₁ at ω and C₂, S₂ at 2ω (eqs 89–90 with the exact weight and S = −m H′), from an enclosed model. ω in
 * (0, 1000]. */
typedef struct gb_proof_body_integrals {
    double omega;
    gb_proof_interval C1, S1, C2, S2;
    gb_proof_interval time_span;  /* t(2π − cut) − t(cut): the separatrix's time between the neighbourhoods */
    double seconds;
} gb_proof_body_integrals;

GB_API int gb_proof_body_integrals_compute(const gb_proof_body_def *def, const gb_proof_body_model *model, double omega,
                                           gb_proof_body_integrals *out);

/* The Melnikov function of eq 91 for a forcing: μ = c / M (the paper's damping −μp), μD enclosed, C and S at ω and 2ω,
 * and its zeros decided by gb_proof_melnikov_zeros (with μ = 1 and D replaced by the interval μD). */
typedef struct gb_proof_body_forcing {
    double damping;             /* c [N m s] ≥ 0 */
    double A1, A2, omega;       /* ν₁ = A₁, ν₂ = A₂ [m/s²], ω [rad/s] in (0, 1000] */
    gb_proof_interval psi;      /* the second harmonic's phase */
    int depth;                  /* gb_proof_melnikov's depth */
} gb_proof_body_forcing;

typedef struct gb_proof_body_result {
    gb_proof_body_integrals integrals;
    gb_proof_interval mu, mu_D;
    gb_proof_zeros zeros;
} gb_proof_body_result;

GB_API int gb_proof_body_melnikov(const gb_proof_body_def *def, const gb_proof_body_model *model,
                                  const gb_proof_body_forcing *forcing, gb_proof_body_result *out);

/* The cell of the model holding q: its range, H and H′ enclosed over it, and H″ where `curved` (a C² cell whose chart
 * Hessian of x·v is proved definite on every kept box: H″ = −H − gᵀK⁻¹g with g = (x_a·v′, x_b·v′), the implicit
 * function theorem at the unique maximiser; the linear part a Lohner step of the reduced field needs). Where two cells
 * share q the curved one is given. GB_EDOM when q lies outside [0, 2π]; GB_EINVAL for a model without cells. */
typedef struct gb_proof_body_cell {
    double q_lo, q_hi;
    gb_proof_interval H, dH, d2H; /* d2H: the whole line unless curved */
    int curved;
} gb_proof_body_cell;

GB_API int gb_proof_body_cell_at(const gb_proof_body_model *model, double q, gb_proof_body_cell *out);

GB_API void gb_proof_body_free(gb_proof_body_model *model);

/* The Taylor coefficients of H over an arc of q (src/gb_proof_body_jet.c, docs/proofs.md): H_k ∋ H⁽ᵏ⁾(q)/k! for every
 * q in [q_lo, q_hi] (−2π ≤ q_lo ≤ q_hi ≤ 4π: H is 2π-periodic) and k = 0 … order, where H is C² with one contact on
 * the arc. The contact x*(q) = x(a, b) is the
 * maximiser of x·v(q), in the chart of the arc's kept boxes: it lies in their hull, where x·v is strictly concave
 * (gb_proof_body_structure), and an interval Newton step (Krawczyk's) narrows that hull to (a, b). Its coefficients
 * then solve the chart's stationarity (x_a·v, x_b·v) = 0 order by order in Taylor arithmetic on Arb's balls, the k-th
 * from the chart Hessian of x·v and the lower ones, and H = x*·v is their product with v. A point's coefficients come
 * from the arc [q, q]; an arc's enclose the remainder of a Taylor step across it. GB_EDOM for an order or arc out of
 * range or a definition gb_proof_body_enclose refuses; GB_ENUMERIC where H is not proved C² with one contact on the
 * arc (a tie, boxes kept in two charts) or the Newton step does not hold the contact. */
#define GB_PROOF_BODY_JET_ORDER_MAX 32
#define GB_PROOF_BODY_JET_ARC_MAX 0.1

typedef struct gb_proof_body_jet {
    double q_lo, q_hi;
    int order;
    gb_proof_interval H[GB_PROOF_BODY_JET_ORDER_MAX + 1]; /* H⁽ᵏ⁾(q)/k! over the arc */
    int chart;                                            /* gb_surface_chart of the contact's coordinates */
    gb_proof_interval a, b;                               /* the contact's chart coordinates over the arc */
    size_t kept;                                          /* the arc's kept boxes */
    int newton_steps;                                     /* Krawczyk steps taken */
    double seconds;                                       /* CPU */
} gb_proof_body_jet;

GB_API int gb_proof_body_jet_enclose(const gb_proof_body_def *def, double q_lo, double q_hi, int order,
                                     gb_proof_body_jet *out);

/* H's coefficients H_0 … H_order over the fixed cells [i w, (i + 1) w] of q, w = 2^−level, each enclosed once by
 * gb_proof_body_jet_enclose when an integration first needs it and kept (src/gb_proof_body_arcs.c). With def->arcs set,
 * the reduced field's integrations (gb_proof_body_flow, gb_proof_body_period_map, gb_proof_body_cover_link) take H's
 * coefficients over an arc as the hull of those of the cells covering it (at most 64): H and H′ for Picard's test of a
 * step's a-priori enclosure over any arc, the higher ones of a step's remainder over arcs of four cells or more. An arc
 * touching a refused cell (a tie in it), a narrower one's higher coefficients (a step's centre) and a branch followed to
 * its tie are enclosed as without the table. The hull holds H⁽ᵏ⁾(q)/k! at every q of the arc, as the arc's own
 * enclosure does, so the statements proved are of the same kind; their margins may differ slightly. The table may be
 * shared by threads (one mutex; a cell enclosed outside it) and keeps at most 2¹⁶ cells; what it answers does not depend
 * on the threads' order. GB_EDOM for a level or order (1 … GB_PROOF_BODY_JET_ORDER_MAX) out of range or a precision
 * gb_proof_body_enclose refuses. */
#define GB_PROOF_BODY_ARCS_LEVEL_MIN 6
#define GB_PROOF_BODY_ARCS_LEVEL_MAX 16

typedef struct gb_proof_body_arcs_stats {
    size_t cells;    /* cells enclosed and kept */
    size_t refused;  /* cells that could not be enclosed (kept as such) */
    size_t served;   /* arcs answered from the cells */
    size_t declined; /* arcs left to their own enclosure because a cell was refused */
    double seconds;  /* CPU spent enclosing the cells kept */
} gb_proof_body_arcs_stats;

GB_API int gb_proof_body_arcs_create(const gb_proof_body_def *def, int level, int order, gb_proof_body_arcs **out);
GB_API void gb_proof_body_arcs_get_stats(gb_proof_body_arcs *arcs, gb_proof_body_arcs_stats *out);
GB_API void gb_proof_body_arcs_free(gb_proof_body_arcs *arcs);

/* A tie of H on an arc (src/gb_proof_body_jet.c): the q* where the arc's two contacts are equally high, by interval
 * Newton steps on their heights' difference d = h_A − h_B (each contact's coefficients from its component's hull, its
 * existence there proved by Krawczyk's test over the whole arc, d′ proved away from 0), and H′'s jump there, |d′(q*)|
 * (H = max(h_A, h_B): its derivative jumps up). A Newton image inside the arc proves the tie and its uniqueness. GB_EDOM
 * for an arc out of range; GB_ENUMERIC when the arc is not proved to hold one tie of two contacts. */
typedef struct gb_proof_body_tie {
    gb_proof_interval q, H, jump;
    int proved, newton_steps;
    double seconds;
} gb_proof_body_tie;

GB_API int gb_proof_body_tie_locate(const gb_proof_body_def *def, double q_lo, double q_hi, gb_proof_body_tie *out);

/* The reduced field at a forcing, not averaged and not linearised in ε, integrated on Arb's balls (src/gb_proof_body_flow.c):
 * q̇ = P, Ṗ = −(m/M) a(t) H′(q) − μP with P = q̇, a(t) = g + A₁ cos ωt + A₂ cos(2ωt + ψ) and μ = c/M (the forcing's
 * damping c, its depth unused). image[0] ∋ q and image[1] ∋ P at t0 + t of every solution from the box (q, P) at t0, for
 * every M and ψ in their intervals. The C⁰ Lohner integrator of gb_proof_flow (order 4 … 31), H′'s Taylor coefficients
 * from gb_proof_body_jet_enclose over each ball of q a step needs. GB_EDOM for a forcing, box, order or t out of range
 * (t a multiple of 2⁻³⁰ in (0, 100]); GB_ENUMERIC when the set cannot be followed, naming why (a step's q across a tie, or
 * wider than GB_PROOF_BODY_JET_ARC_MAX). */
GB_API int gb_proof_body_flow(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing,
                              const gb_proof_interval box[2], double t0, double t, int order,
                              gb_proof_interval image[2]);

/* The period map of the same field from the forcing's phase 0: the return of (q, P) at the k-th upward crossing of the
 * section sin ωt = 0 (the flow in (q, P, cos ωt, sin ωt); the period 2π/ω is not a double, the section is exact),
 * periods = k (1 … 16); with derivative, also ∂(q, P)/∂(q₀, P₀) over the box (the integrator's C¹ step). Errors as
 * gb_proof_body_flow's, and GB_ENUMERIC when a crossing is not decided. */
typedef struct gb_proof_body_return {
    gb_proof_interval q, P;           /* at the k-th return */
    gb_proof_interval time;           /* its time (holds 2πk/ω) */
    gb_proof_interval jacobian[2][2]; /* derivative: the period map's derivative over the box */
    long steps;
    double seconds;
} gb_proof_body_return;

GB_API int gb_proof_body_period_map(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing,
                                    const gb_proof_interval box[2], int periods, int order, int derivative,
                                    gb_proof_body_return *out);

/* The period map (one period from phase 0) of a box below a tie that moves up in q (q̇ > 0) and meets the tie once within
 * the period (the tie as gb_proof_body_tie_locate proved it, its enclosure narrower than 2e-9): the branch below the tie
 * integrated to the section q = q_s − 2e-4 (q_s the enclosure's middle; the box lies below it) and from there to the
 * section q = q_s − 1e-7 (a set on a section keeps its spread in q far below 1e-7, so that its crossing needs no
 * coefficients past the tie), the sliver [q_s − 1e-7, q_s + 1e-7], which
 * holds the tie, crossed with bounds (in q as the independent variable, H′ in the hull of both branches'; the time
 * turns the forcing's phase exactly), and the branch above from q_s + 1e-7 to the period's end. The return's time is
 * the sum of the three. With derivative, also the period map's derivative over the box: the three parts' derivatives
 * composed through the sections q = q_s ∓ 1e-7 (the sliver's by Grönwall's bound on its variational equation). GB_EDOM
 * for a box not below the tie or not moving up; GB_ENUMERIC when a part cannot be followed or the tie is not met within
 * the period. */
GB_API int gb_proof_body_period_map_tie(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing,
                                        const gb_proof_interval box[2], const gb_proof_body_tie *tie, int order,
                                        int derivative, gb_proof_body_return *out);

/* An h-set of the period map's plane (q, P): the parallelogram c + F diag(a, b) [−1, 1]², F's first column the direction
 * across (the one the map stretches), its second the one along; every number a double, taken exact. */
typedef struct gb_proof_body_hset {
    double centre[2];
    double frame[2][2]; /* frame[i][j]: component i of column j */
    double half[2];     /* a, b > 0 */
} gb_proof_body_hset;

typedef struct gb_proof_body_link {
    int covers;          /* N ⇒ M proved */
    int strip, edges;    /* its two parts proved */
    int orientation;     /* covers: +1 when N's edge x = −1 maps below M (ξ < −1), −1 when above */
    double strip_margin; /* strip: 1 − the largest |η| proved over N's image (M's units) */
    double edge_margin;  /* edges: the least distance proved of the edges' images beyond ξ = ±1 */
    long pieces, maps;   /* pieces enclosed, period maps computed */
    double seconds;      /* CPU */
    char failure[300];   /* the first piece whose part was not proved, and why, or "" */
} gb_proof_body_link;

/* The covering relation N ⇒ M of the period map (one period from phase 0; with `tie`, N's points cross it moving up within
 * the period: gb_proof_body_period_map_tie, else gb_proof_body_period_map): P(N) inside M's strip |η| < 1 and N's
 * edges x = ±1 mapped beyond M's ends ξ = ∓1, one each (Zgliczyński & Gidea 2004, Def. 6; gb_proof_cover.h). The image
 * by the mean value form on pieces of N: P of each piece's middle, and DP over the piece's box hull; `pieces` across
 * (1 … 4096) to start, each halved across (an edge's, along) up to `depth` times (0 … 20) while its part is not proved.
 * M is taken `turns` (−1, 0, 1) times 2π on in q, exactly: the period map lives on the cylinder q mod 2π. GB_EDOM for
 * an h-set that is not finite or whose frame is singular, or turns, pieces, depth or precision out of range; otherwise
 * GB_OK with the relation proved or not in out (a relation not proved is not disproved; out->failure says where it
 * stopped). */
GB_API int gb_proof_body_cover_link(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing,
                                    const gb_proof_body_tie *tie, const gb_proof_body_hset *N,
                                    const gb_proof_body_hset *M, int turns, int pieces, int depth, int order,
                                    gb_proof_body_link *out);

/* 1 when A and B are proved disjoint on the cylinder q mod 2π (B moved by −2π, 0 and 2π in q): for each, one of the
 * four sides of A's or B's coordinates has every corner of the other beyond it (the separating axis of two
 * parallelograms), on Arb's balls at the precision. */
GB_API int gb_proof_body_hsets_disjoint(const gb_proof_body_hset *A, const gb_proof_body_hset *B, long precision);

/* A proved lower bound of ln ρ for the graph of a self-loop at N₀ and a cycle N₀ ⇒ N₁ ⇒ … ⇒ N_{L−1} ⇒ N₀ (length L,
 * 2 … 10000): ρ the root above 1 of x^L = x^{L−1} + 1, bounded below by a bisection on Arb's balls (f(x) = x^{L−1}(x − 1)
 * − 1 increases above 1, so f(x₀) < 0 proves ρ > x₀). GB_EDOM for L out of range. */
GB_API int gb_proof_body_chain_entropy(int length, double *log_rho);

/* The h-sets of a horseshoe of the period map placed on floats along one homoclinic orbit (src/gb_proof_body_chain.c:
 * nothing there is proved; the sets are the input of gb_proof_body_cover_link). The orbit leaves the saddle (0, 0)
 * along W^u and reaches its copy (2π, 0) along W^s: Newton's method on P^{n_u}(δ v_u) = P^{−n_s}((2π, 0) − σ v_s) from
 * the seeds; N₀ is the saddle's box in its eigenvectors, N_1 … N_m lie at the orbit's points first … last in frames
 * carried along it (across: W^u's tangent, along: W^s's), their half-widths shrinking across and growing along by rho
 * a period against the linear part; the chain is N₀ ⇒ N₀, N₀ ⇒ N_1 ⇒ … ⇒ N_m ⇒ N₀ (2π on). */
enum { GB_PROOF_BODY_CHAIN_MAX = 200 };

typedef struct gb_proof_body_chain_def {
    int unstable_iterates, stable_iterates; /* n_u, n_s ≥ 1, their sum at most GB_PROOF_BODY_CHAIN_MAX */
    double unstable_seed, stable_seed;      /* δ and σ to start Newton from, in (0, 1e-3] */
    int first, last;                        /* the orbit's points of N_1 and N_m: 1 ≤ first < last < n_u + n_s */
    double saddle_half[2];                  /* N₀'s r_u, r_s in (0, 1) */
    double first_half[2];                   /* N_1's a_1, b_1 in (0, 1) */
    double rho;                             /* the margin a period, in (1, 2] */
    double along_min;                       /* the least half-width along, in [0, 1) */
} gb_proof_body_chain_def;

/* The sets docs/proofs.md describes for Gömböc "I" or "II" at Table 1's rolling forcing; GB_EDOM for another name. */
GB_API int gb_proof_body_chain_default(const char *morphology, gb_proof_body_chain_def *out);

typedef struct gb_proof_body_chain {
    size_t sets; /* m + 1: N₀, N_1 … N_m */
    gb_proof_body_hset *set;
    int *tie;              /* tie[i]: the float model's tie (gb_melnikov_body_info.kink_q's index) the link from N_i
                                  crosses, or −1 */
    size_t orbit_points;   /* n_u + n_s + 1 */
    double homoclinic[2];  /* the orbit's point n_u */
    double residual;       /* |P^{n_u}(δ v_u) − P^{−n_s}(…)| at Newton's end */
    double multipliers[2]; /* the saddle's, unstable and stable */
    double liouville; /* ∏ α_k β_k along the orbit: det DP's product there (frames at both ends the saddle's) */
} gb_proof_body_chain;

/* GB_EDOM for a definition out of range (named with its range); GB_ENUMERIC when the float integration fails or Newton
 * ends farther than 1e-6 from a homoclinic point. gb_proof_body_chain_free releases it. */
GB_API int gb_proof_body_chain_design(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing,
                                      const gb_proof_body_chain_def *chain, gb_proof_body_chain *out);
GB_API void gb_proof_body_chain_free(gb_proof_body_chain *chain);

/* M = aᵀ I_c a + m r_max² of the paper's body I or II (homogeneous, mass m; a = e × s₀ with e projected ⊥ s₀ and
 * normalised) and its volume, by Arb's quadrature nested over the sphere (src/gb_proof_mass.c). GB_EDOM for another body
 * or the precision out of range; GB_ENUMERIC when the quadrature does not enclose them. */
GB_API int gb_proof_body_inertia(const gb_surface *surface, double mass, const double rocking[3], long precision,
                                 gb_proof_interval *M, gb_proof_interval *volume);

#ifdef __cplusplus
}
#endif

#endif
