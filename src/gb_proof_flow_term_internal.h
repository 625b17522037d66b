/* gb_proof_flow_term_internal — a field's one non-polynomial term for the rigorous integrator (gb_proof_flow_term.c): what
 * gb_proof_flow's Taylor recursion, variational part and field evaluation call, on the term alone (the state's dimension
 * n and Arb's precision passed), so that the integrator uses the term and the term knows nothing of the integrator.
 * Internal to the library. */
#ifndef GB_PROOF_FLOW_TERM_INTERNAL_H
#define GB_PROOF_FLOW_TERM_INTERNAL_H

#include <arb.h>

enum { GB_PROOF_TERM_DIMENSION_MAX = 4 };

/* f_row += A(x) G(x_var): A = a0 + Σ_l a1_l x_l + Σ_{l ≤ m} a2_lm x_l x_m (balls), G a function of the one variable
 * x_var given by its Taylor coefficients over a ball: jet(context, x, order, g) sets g[k] ∋ G⁽ᵏ⁾(y)/k! for every y in
 * x, k = 0 … order, and returns 0; nonzero when it cannot (the coefficients are then indeterminate, and no step that
 * needs them holds). The Gömböcs' reduced field: G = H′ (gb_proof_body_flow.c). */
typedef struct field_term {
    int row, var; /* row < 0: no term */
    arb_struct a0, a1[GB_PROOF_TERM_DIMENSION_MAX], a2[GB_PROOF_TERM_DIMENSION_MAX][GB_PROOF_TERM_DIMENSION_MAX];
    int (*jet)(void *context, const arb_t x, int order, arb_ptr g);
    void *context;
} field_term;

/* Init and clear (row −1: none); G's coefficients 0 … order over the ball x (indeterminate when the jet fails);
 * A(x) G(x_var) over the box x (n components) added to *out; the k-th coefficient of A G along the series xs (stride w,
 * coefficients 0 … k), g G's coefficients at xs's x_var(0); the coefficients m < len of the term's row of Df along xs
 * added to J (J[m n² + row n + q]), g G's coefficients 0 … len there. */
void gb_proof_flow_term_init(field_term *T);
void gb_proof_flow_term_clear(field_term *T);
void gb_proof_flow_term_jet(const field_term *T, const arb_t x, int order, arb_ptr g);
void gb_proof_flow_term_eval(const field_term *T, int n, slong prec, arb_srcptr x, arb_t out);
void gb_proof_flow_term_coefficient(const field_term *T, int n, slong prec, arb_srcptr xs, int w, int k, arb_srcptr g,
                                    arb_t out);
void gb_proof_flow_term_jacobian(const field_term *T, int n, slong prec, arb_srcptr xs, int w, int len, arb_srcptr g,
                                 arb_ptr J);

#endif
