/* gb_proof_flow — a rigorous integrator on Arb's balls for quadratic vector fields, and their Poincaré maps.
 *
 * A quadratic field x' = c + L x + Q(x, x) in R^n (n ≤ 4: Rössler's, Lorenz's, the reduced models' polynomial
 * truncations) is integrated by Taylor's method of order p with the C⁰ Lohner algorithm (Lohner 1987;
 * Zgliczyński 2002, Found. Comput. Math.): the set is carried as x̂ + A r (x̂ a point, A a matrix of doubles taken
 * exact, r a box of balls), so that a set that turns is not wrapped in a box at every step. Each step of length h:
 *  1. an a-priori enclosure B of every solution from the set over [0, h] (X + [0, h] f(B) ⊂ B, Picard's test);
 *  2. the Taylor coefficients at x̂ (by the recursion of the quadratic field) and the variational coefficients over
 *     the set's hull (the derivative of the Taylor polynomial with respect to the initial point);
 *  3. the remainder h^{p+1} x_{p+1}(B) (Lagrange's form, componentwise: every intermediate point lies in B);
 *  4. Φ(X) ⊂ Φ_p(x̂) + R + DΦ_p(X) A r, rewritten in a new frame A' = Q of the QR factorisation of the middle of
 *     DΦ_p(X) A (the columns ordered by their width in r), r' enclosed with the inverse of A' computed by Arb.
 * Every operation is Arb's: the result encloses the exact one.
 *
 * The Poincaré map: the k-th crossing of the hyperplane x[coordinate] = 0 in a stated direction. A step whose
 * enclosure B meets the plane must have x'[coordinate] of one strict sign over B (else the crossing is undecided);
 * crossings in the stated direction come in windows of consecutive such steps, before which the whole set lies on
 * the side it leaves and after which on the side it enters, so every solution crosses exactly once a window; the
 * k-th window's crossing is enclosed by the set over sub-intervals of the step's time whose hull meets the plane.
 * The initial set lies on the plane (window 0). */
#ifndef GB_PROOF_FLOW_H
#define GB_PROOF_FLOW_H

#include "gb_export.h"
#include "gb_proof.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { GB_PROOF_FIELD_DIMENSION_MAX = 4 };

/* A rational number num/den (a field's coefficient: 5.7 is not a double); den = 0 reads as 0. */
typedef struct gb_proof_rational {
    long num, den;
} gb_proof_rational;

/* f_i(x) = c_i + Σ_j L_ij x_j + Σ_{j ≤ k} Q_ijk x_j x_k; the entries of Q with j > k are ignored. */
typedef struct gb_proof_field {
    int dimension; /* 1 ... 4 */
    gb_proof_rational c[GB_PROOF_FIELD_DIMENSION_MAX];
    gb_proof_rational L[GB_PROOF_FIELD_DIMENSION_MAX][GB_PROOF_FIELD_DIMENSION_MAX];
    gb_proof_rational Q[GB_PROOF_FIELD_DIMENSION_MAX][GB_PROOF_FIELD_DIMENSION_MAX][GB_PROOF_FIELD_DIMENSION_MAX];
} gb_proof_field;

/* Rössler's field x' = −y − z, y' = x + a y, z' = b + z (x − c) with a = a_num/a_den, b = b_num/b_den,
 * c = c_num/c_den (Zgliczyński 1997 and CAPD write it with (a, b) = (5.7, 0.2) for (c, a = b)). */
GB_API gb_proof_field gb_proof_flow_rossler(long a_num, long a_den, long b_num, long b_den, long c_num, long c_den);

/* The Taylor order of the integrator: 4 ... 40 (default 20). */
#define GB_PROOF_ORDER_MIN 4
#define GB_PROOF_ORDER_MAX 40
#define GB_PROOF_ORDER_DEFAULT 20

/* The k-th crossing of x[coordinate] = 0 in the stated direction, for every initial point in a box on the plane. */
typedef struct gb_proof_flow_def {
    const gb_proof_field *field;
    int coordinate;   /* 0 ... dimension − 1 */
    int direction;    /* +1: crossings where x[coordinate] increases; −1: decreases */
    int returns;      /* k: 1 ... 16 */
    int order;        /* the Taylor order */
    long precision;   /* Arb's bits */
    double time_max;  /* the longest time followed before giving up: > 0, at most 1e4 */
    double step_max;  /* the longest step: > 0 */
    int time_pieces;  /* the sub-intervals of a crossing step: 2 ... 4096 (default 64) */
    int derivative;   /* 1: also enclose the return map's derivative (the C¹ step: variational equations with their
                         own a-priori enclosure and remainder); 0: the map alone (default) */
} gb_proof_flow_def;

/* Defaults: coordinate 0, direction +1, 1 return, order 20, 128 bits, time_max 100, step_max 0.5, 64 pieces. */
GB_API gb_proof_flow_def gb_proof_flow_def_default(const gb_proof_field *field);

typedef struct gb_proof_flow_crossing {
    gb_proof_interval image[GB_PROOF_FIELD_DIMENSION_MAX]; /* encloses P^k(x) for every x of the box */
    gb_proof_interval time;                                /* encloses the time of the k-th crossing */
    long steps;                                            /* Taylor steps taken */
    double step_min;                                       /* the shortest step taken */
    double seconds;                                        /* CPU */
    /* derivative: DP^k(x) for every x of the box, DP = (I − f eᵀ/f_c) DΦ_t at the crossing (e the section's normal),
     * as the full n × n matrix (its row and column c are those of the plane's embedding: row c is 0) */
    gb_proof_interval jacobian[GB_PROOF_FIELD_DIMENSION_MAX][GB_PROOF_FIELD_DIMENSION_MAX];
} gb_proof_flow_crossing;

/* GB_EDOM for a definition or a box out of range (a box whose coordinate-th component is not {0}); GB_ENUMERIC when
 * the enclosure cannot be carried (the a-priori enclosure fails at the shortest step 1e-9, a crossing's direction is
 * undecided, the set does not leave one side before a window or reach the other after it, time_max is passed): the
 * message names the time and the reason. Nothing is enclosed then. */
GB_API int gb_proof_flow_section_map(const gb_proof_flow_def *def, const gb_proof_interval *box, gb_proof_flow_crossing *out);

/* Krawczyk's operator on the return map P^k − id over a box of the section. */
typedef struct gb_proof_flow_orbit {
    int proved;    /* K ⊂ int box: P^k has exactly one fixed point in the box (a periodic orbit through it) */
    int excluded;  /* K misses the box in some coordinate: P^k has no fixed point there */
    gb_proof_interval krawczyk[GB_PROOF_FIELD_DIMENSION_MAX];                          /* K (the section's coordinate 0) */
    gb_proof_interval time;                                                          /* the return time over the box */
    gb_proof_interval period; /* proved: the return time over K, which holds the fixed point (else NaN) */
    gb_proof_interval jacobian[GB_PROOF_FIELD_DIMENSION_MAX][GB_PROOF_FIELD_DIMENSION_MAX]; /* DP^k over the box */
    double seconds;
} gb_proof_flow_orbit;

/* K = x̂ − C (P^k(x̂) − x̂) + (I − C (DP^k(box) − I)) (box − x̂) on the plane, x̂ the box's middle, C the inverse of the
 * middle of DP^k(box) − I in doubles (taken exact), P^k and its derivative enclosed by the C¹ step. K ⊂ int box proves
 * a unique fixed point in the box (Krawczyk 1969; Neumaier 1990, Thm 5.1.7); K ∩ box = ∅ proves none. The
 * definition's own derivative flag is ignored. GB_EDOM / GB_ENUMERIC as gb_proof_flow_section_map, or when the middle
 * of DP^k − I is singular. */
GB_API int gb_proof_flow_periodic_orbit(const gb_proof_flow_def *def, const gb_proof_interval *box, gb_proof_flow_orbit *out);

/* The solution at time t of every initial point in the box (no section): the oracle's entry (a linear field against
 * its exponential, a nonlinear one against a tight non-rigorous integration). */
GB_API int gb_proof_flow_time(const gb_proof_flow_def *def, const gb_proof_interval *box, double t,
                              gb_proof_interval *image);

#ifdef __cplusplus
}
#endif

#endif
