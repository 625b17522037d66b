/* gb_proof_flow_term — the one non-polynomial term a field of the rigorous integrator may have, f_row += A(x) G(x_var)
 * (gb_proof_flow_internal.h): A quadratic, G a function of one variable known only through its Taylor coefficients
 * over balls (the Gömböcs' H′, gb_proof_body_jet_enclose). Along a solution's series x(t) = Σ x_k t^k, G(x_var(t)) is
 * the composition of G's Taylor polynomial at x_var(0) with x_var(t) − x_var(0): exact to the series' length, since that
 * difference has no constant term; with x_var(0) a ball, G's coefficients over the ball hold those at each of its
 * points, so the composition holds the series of every solution from it. */
#include "gb_proof_flow_term_internal.h"

#include <arb_poly.h>

void gb_proof_flow_term_init(field_term *T)
{
    T->row = -1, T->var = 0, T->jet = NULL, T->context = NULL;
    arb_init(&T->a0);
    for (int l = 0; l < GB_PROOF_TERM_DIMENSION_MAX; l++) {
        arb_init(&T->a1[l]);
        for (int m = 0; m < GB_PROOF_TERM_DIMENSION_MAX; m++) arb_init(&T->a2[l][m]);
    }
}

void gb_proof_flow_term_clear(field_term *T)
{
    arb_clear(&T->a0);
    for (int l = 0; l < GB_PROOF_TERM_DIMENSION_MAX; l++) {
        arb_clear(&T->a1[l]);
        for (int m = 0; m < GB_PROOF_TERM_DIMENSION_MAX; m++) arb_clear(&T->a2[l][m]);
    }
}

void gb_proof_flow_term_jet(const field_term *T, const arb_t x, int order, arb_ptr g)
{
    if (T->jet(T->context, x, order, g))
        for (int k = 0; k <= order; k++) arb_indeterminate(g + k);
}

/* The series x_l(t) of length len from xs (coefficient k of x_l at xs[l w + k]). */
static void state_series(int n, arb_srcptr xs, int w, int len, arb_poly_struct *x)
{
    for (int l = 0; l < n; l++) {
        arb_poly_fit_length(x + l, len);
        for (int k = 0; k < len; k++) arb_set(x[l].coeffs + k, xs + l * w + k);
        _arb_poly_set_length(x + l, len);
        _arb_poly_normalise(x + l);
    }
}

/* A(x(t)), and when dA is not NULL each ∂A/∂x_l(x(t)) = a1_l + Σ_{m ≥ l} a2_lm x_m + Σ_{m ≤ l} a2_ml x_m, length len. */
static void series_A(const field_term *T, int n, const arb_poly_struct *x, int len, slong prec, arb_poly_t A,
                     arb_poly_struct *dA)
{
    arb_poly_t p;
    arb_poly_init(p);
    arb_poly_set_arb(A, &T->a0);
    for (int l = 0; l < n; l++) {
        arb_poly_scalar_mul(p, x + l, &T->a1[l], prec);
        arb_poly_add(A, A, p, prec);
        if (dA) arb_poly_set_arb(dA + l, &T->a1[l]);
    }
    for (int l = 0; l < n; l++)
        for (int m = l; m < n; m++) {
            if (arb_is_zero(&T->a2[l][m])) continue;
            arb_poly_mullow(p, x + l, x + m, len, prec);
            arb_poly_scalar_mul(p, p, &T->a2[l][m], prec);
            arb_poly_add(A, A, p, prec);
            if (!dA) continue;
            arb_poly_scalar_mul(p, x + m, &T->a2[l][m], prec);
            arb_poly_add(dA + l, dA + l, p, prec);
            arb_poly_scalar_mul(p, x + l, &T->a2[l][m], prec);
            arb_poly_add(dA + m, dA + m, p, prec);
        }
    arb_poly_clear(p);
}

/* G(x_var(t)) and, when dG is not NULL, G′(x_var(t)), length len, from G's coefficients g[0 … len] at x_var(0). */
static void series_G(const field_term *T, const arb_poly_struct *x, arb_srcptr g, int len, slong prec, arb_poly_t G,
                     arb_poly_t dG)
{
    arb_poly_t u, c;
    arb_poly_init(u), arb_poly_init(c);
    arb_poly_set(u, x + T->var);
    arb_poly_set_coeff_si(u, 0, 0);
    arb_poly_fit_length(c, len);
    for (int k = 0; k < len; k++) arb_set(c->coeffs + k, g + k);
    _arb_poly_set_length(c, len);
    _arb_poly_normalise(c);
    arb_poly_compose_series(G, c, u, len, prec);
    if (dG) {
        arb_poly_fit_length(c, len);
        for (int k = 0; k < len; k++) arb_mul_ui(c->coeffs + k, g + k + 1, (ulong)k + 1, prec);
        _arb_poly_set_length(c, len);
        _arb_poly_normalise(c);
        arb_poly_compose_series(dG, c, u, len, prec);
    }
    arb_poly_clear(u), arb_poly_clear(c);
}

void gb_proof_flow_term_eval(const field_term *T, int n, slong prec, arb_srcptr x, arb_t out)
{
    arb_t g, a;
    arb_init(g), arb_init(a);
    gb_proof_flow_term_jet(T, x + T->var, 0, g);
    arb_poly_struct xs[GB_PROOF_TERM_DIMENSION_MAX];
    for (int l = 0; l < n; l++) arb_poly_init(xs + l), arb_poly_set_arb(xs + l, x + l);
    arb_poly_t A;
    arb_poly_init(A);
    series_A(T, n, xs, 1, prec, A, NULL);
    arb_poly_get_coeff_arb(a, A, 0);
    arb_addmul(out, a, g, prec);
    for (int l = 0; l < n; l++) arb_poly_clear(xs + l);
    arb_poly_clear(A);
    arb_clear(g), arb_clear(a);
}

void gb_proof_flow_term_coefficient(const field_term *T, int n, slong prec, arb_srcptr xs, int w, int k, arb_srcptr g,
                                    arb_t out)
{
    const int len = k + 1;
    arb_poly_struct x[GB_PROOF_TERM_DIMENSION_MAX];
    for (int l = 0; l < n; l++) arb_poly_init(x + l);
    arb_poly_t A, G;
    arb_poly_init(A), arb_poly_init(G);
    state_series(n, xs, w, len, x);
    series_A(T, n, x, len, prec, A, NULL);
    series_G(T, x, g, len, prec, G, NULL);
    arb_poly_mullow(A, A, G, len, prec);
    arb_poly_get_coeff_arb(out, A, k);
    for (int l = 0; l < n; l++) arb_poly_clear(x + l);
    arb_poly_clear(A), arb_poly_clear(G);
}

void gb_proof_flow_term_jacobian(const field_term *T, int n, slong prec, arb_srcptr xs, int w, int len, arb_srcptr g,
                                 arb_ptr J)
{
    const int nn = n * n, row = T->row;
    arb_poly_struct x[GB_PROOF_TERM_DIMENSION_MAX], dA[GB_PROOF_TERM_DIMENSION_MAX];
    for (int l = 0; l < n; l++) arb_poly_init(x + l), arb_poly_init(dA + l);
    arb_poly_t A, G, dG, p;
    arb_poly_init(A), arb_poly_init(G), arb_poly_init(dG), arb_poly_init(p);
    state_series(n, xs, w, len, x);
    series_A(T, n, x, len, prec, A, dA);
    series_G(T, x, g, len, prec, G, dG);
    arb_t c;
    arb_init(c);
    for (int q = 0; q < n; q++) { /* ∂(A G)/∂x_q = ∂A/∂x_q G + [q = var] A G′ */
        arb_poly_mullow(p, dA + q, G, len, prec);
        if (q == T->var) {
            arb_poly_mullow(A, A, dG, len, prec); /* A is not needed again */
            arb_poly_add(p, p, A, prec);
        }
        for (int m = 0; m < len; m++) {
            arb_poly_get_coeff_arb(c, p, m);
            arb_add(J + m * nn + row * n + q, J + m * nn + row * n + q, c, prec);
        }
    }
    arb_clear(c);
    for (int l = 0; l < n; l++) arb_poly_clear(x + l), arb_poly_clear(dA + l);
    arb_poly_clear(A), arb_poly_clear(G), arb_poly_clear(dG), arb_poly_clear(p);
}
