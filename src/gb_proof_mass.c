/* The reduced model's M enclosed: the volume and the moment of inertia about the rocking axis a through the centroid of a
 * paper body, by Arb's rigorous quadrature nested over the sphere (docs/proofs.md).
 *
 * With S = r⁴ = 1 + 4β sinφ cos χ and u the unit direction: V = (1/3) ∫∫ S^{3/4} sinφ dφ dθ and aᵀI_c a = (m/V) (1/5)
 * ∫∫ S^{5/4} (1 − (a·u)²) sinφ dφ dθ (a homogeneous body about its centroid, which is the chart's origin exactly for the
 * paper's bodies: docs/bodies.md). The contact at the top is d = r_max s₀ with a ⊥ s₀, so M = aᵀI_c a + m r_max².
 *
 * The integral over θ ∈ [0, 2π] (a periodic analytic integrand) is the trapezoidal rule with its error bounded through
 * the integrand's bound on a strip of complex θ (Trefethen and Weideman 2014); as a function of φ that is analytic
 * wherever the root is (Arb's analytic square root checks the branch cut), so the integral over φ ∈ [0, π] is Arb's
 * quadrature (acb_calc_integrate, Johansson 2018), which asks for values on complex balls of φ. Arb's quadrature nested
 * in both variables gives the same enclosure about a thousand times slower. */
#include "gb_proof_body.h"

#include "gb_error.h"
#include "gb_proof_internal.h"


#include <acb.h>
#include <acb_calc.h>

typedef struct mass_integrand {
    int two;             /* morphology II */
    int power;           /* 3 (volume) or 5 (inertia) */
    arb_struct beta4;    /* 4β */
    const arb_struct *a; /* the axis (power 5) */
} mass_integrand;

enum { NODES = 64, STRIP_BOXES = 32 };
#define STRIP 0.8 /* the half-width σ of the strip of θ on which the integrand is bounded */

/* S^{power/4} w sinφ at (φ, θ): w = 1 (power 3) or 1 − (a·u)² (power 5); the roots analytic (a ball that meets the
 * branch cut gives a non-finite value). */
static void integrand(acb_t out, const mass_integrand *f, const acb_t phi, const acb_t theta, slong prec)
{
    acb_t sp, cp, st, ct, chi, S, r, t, u;
    acb_init(sp), acb_init(cp), acb_init(st), acb_init(ct), acb_init(chi), acb_init(S), acb_init(r), acb_init(t), acb_init(u);
    acb_sin_cos(sp, cp, phi, prec);
    acb_sin_cos(st, ct, theta, prec);
    /* χ = θ − 5φ (I), θ − (3π/2)(cos φ − cos³φ/3) (II) */
    if (f->two) {
        acb_cube(t, cp, prec);
        acb_div_ui(t, t, 3, prec);
        acb_sub(t, cp, t, prec);
        acb_const_pi(u, prec);
        acb_mul(t, t, u, prec);
        acb_mul_ui(t, t, 3, prec);
        acb_mul_2exp_si(t, t, -1);
    } else {
        acb_mul_ui(t, phi, 5, prec);
    }
    acb_sub(chi, theta, t, prec);
    acb_cos(t, chi, prec);
    acb_mul(S, sp, t, prec);
    acb_mul_arb(S, S, &f->beta4, prec);
    acb_add_ui(S, S, 1, prec);
    acb_sqrt_analytic(r, S, 1, prec);
    acb_sqrt_analytic(r, r, 1, prec); /* S^{1/4} */
    if (f->power == 3) {
        acb_div(out, S, r, prec);
    } else {
        acb_mul(out, S, r, prec);
        /* 1 − (a·u)², u = (sinφ cosθ, sinφ sinθ, cosφ) */
        acb_mul(t, sp, ct, prec);
        acb_mul_arb(u, t, &f->a[0], prec);
        acb_mul(t, sp, st, prec);
        acb_mul_arb(t, t, &f->a[1], prec);
        acb_add(u, u, t, prec);
        acb_mul_arb(t, cp, &f->a[2], prec);
        acb_add(u, u, t, prec);
        acb_sqr(u, u, prec);
        acb_sub_ui(u, u, 1, prec);
        acb_neg(u, u);
        acb_mul(out, out, u, prec);
    }
    acb_mul(out, out, sp, prec);
    acb_clear(sp), acb_clear(cp), acb_clear(st), acb_clear(ct), acb_clear(chi), acb_clear(S), acb_clear(r), acb_clear(t);
    acb_clear(u);
}

/* ∫₀^{2π} (integrand) dθ at the complex ball φ by the trapezoidal rule on NODES points, whose error for a 2π-periodic
 * function analytic in the strip |Im θ| < σ and bounded there by B is at most 4πB / (e^{σN} − 1) (Trefethen and
 * Weideman 2014, Theorem 3.2). B and the analyticity come from STRIP_BOXES balls covering [0, 2π] × [−σ, σ]: each must
 * evaluate to a finite value (the roots analytic on it), else the value is non-finite and the φ quadrature subdivides.
 * Analytic in φ wherever it is finite, so Arb's quadrature in φ may ask for holomorphy. */
static int over_theta(acb_ptr out, const acb_t phi, void *param, slong order, slong prec)
{
    const mass_integrand *f = param;
    if (order > 1) flint_abort();
    acb_t theta, g, sum;
    arb_t pi, x;
    mag_t B, m;
    acb_init(theta), acb_init(g), acb_init(sum), arb_init(pi), arb_init(x), mag_init(B), mag_init(m);
    arb_const_pi(pi, prec);
    mag_zero(B);
    int finite = 1;
    for (int k = 0; k < STRIP_BOXES && finite; k++) {
        /* the box [2πk/K, 2π(k+1)/K] × [−σ, σ] */
        arb_mul_ui(x, pi, 2 * (ulong)k + 1, prec);
        arb_div_ui(x, x, STRIP_BOXES, prec);
        arb_set(acb_realref(theta), x);
        arb_div_ui(x, pi, STRIP_BOXES, prec);
        arb_add_error(acb_realref(theta), x);
        arb_zero(acb_imagref(theta));
        arb_set_d(x, STRIP);
        arb_add_error(acb_imagref(theta), x);
        integrand(g, f, phi, theta, prec);
        finite = acb_is_finite(g);
        acb_get_mag(m, g);
        mag_max(B, B, m);
    }
    if (finite) {
        acb_zero(sum);
        for (int j = 0; j < NODES; j++) {
            arb_mul_ui(acb_realref(theta), pi, 2 * (ulong)j, prec);
            arb_div_ui(acb_realref(theta), acb_realref(theta), NODES, prec);
            arb_zero(acb_imagref(theta));
            integrand(g, f, phi, theta, prec);
            acb_add(sum, sum, g, prec);
        }
        arb_mul_2exp_si(x, pi, 1);
        arb_div_ui(x, x, NODES, prec);
        acb_mul_arb(out, sum, x, prec);
        /* 4πB / (e^{σN} − 1) */
        arb_set_d(x, STRIP * NODES);
        arb_expm1(x, x, prec);
        arb_mul_2exp_si(pi, pi, 2);
        arb_div(x, pi, x, prec);
        arb_get_mag(m, x);
        mag_mul(m, m, B);
        acb_add_error_mag(out, m);
    }
    if (!finite || !acb_is_finite(out)) acb_indeterminate(out);
    acb_clear(theta), acb_clear(g), acb_clear(sum), arb_clear(pi), arb_clear(x), mag_clear(B), mag_clear(m);
    return 0;
}

/* ∫₀^π (over_theta) dφ by Arb's quadrature. */
static void quadrature(acb_t out, mass_integrand *f, slong prec)
{
    acb_t a, b;
    acb_init(a), acb_init(b);
    acb_zero(a);
    acb_const_pi(b, prec);
    mag_t tol;
    mag_init(tol);
    mag_set_ui_2exp_si(tol, 1, -(prec - 16));
    acb_calc_integrate_opt_t options;
    acb_calc_integrate_opt_init(options);
    options->eval_limit = 10000000;
    acb_calc_integrate(out, over_theta, f, a, b, prec, tol, options, prec);
    mag_clear(tol);
    acb_clear(a), acb_clear(b);
}

int gb_proof_body_inertia(const gb_surface *surface, double mass, const double rocking[3], long precision,
                          gb_proof_interval *M, gb_proof_interval *volume)
{
    int status = gb_proof_check_precision(precision);
    if (status) return status;
    double s0[3], tt[3], cp;
    int two;
    status = gb_proof_body_top(surface, s0, tt, &cp, &two); /* II's χ_φ is a multiple of π */
    if (status) return status;
    if (!(mass > 0.0)) return gb_error_set(GB_EDOM, "mass = %g is out of range (allowed: > 0)", mass);
    const slong prec = precision;
    /* e ⊥ s₀ normalised, a = e × s₀ */
    arb_struct e[3], a[3];
    arb_t t, V, J, rm;
    arb_init(t), arb_init(V), arb_init(J), arb_init(rm);
    for (int k = 0; k < 3; k++) arb_init(&e[k]), arb_init(&a[k]);
    status = gb_proof_body_axis(e, rocking, s0, prec);
    if (status) goto done;
    for (int k = 0; k < 3; k++) {
        const int i = (k + 1) % 3, j = (k + 2) % 3; /* a_k = e_i s0_j − e_j s0_i */
        arb_mul_si(&a[k], &e[i], (slong)s0[j], prec);
        arb_mul_si(t, &e[j], (slong)s0[i], prec);
        arb_sub(&a[k], &a[k], t, prec);
    }
    mass_integrand f = {.two = two, .a = a};
    arb_init(&f.beta4);
    arb_set_d(&f.beta4, surface->beta);
    arb_mul_2exp_si(&f.beta4, &f.beta4, 2);
    acb_t result;
    acb_init(result);
    f.power = 3;
    quadrature(result, &f, prec);
    arb_div_ui(V, acb_realref(result), 3, prec);
    f.power = 5;
    quadrature(result, &f, prec);
    arb_div_ui(J, acb_realref(result), 5, prec);
    const int finite = arb_is_finite(V) && arb_is_finite(J) && arb_is_positive(V);
    acb_clear(result);
    arb_clear(&f.beta4);
    if (!finite) {
        status = gb_error_set(GB_ENUMERIC, "Arb's quadrature did not enclose the volume and inertia at %ld bits", precision);
        goto done;
    }
    /* M = (m/V) J + m r_max², r_max² = √(1 + 4β) */
    arb_div(J, J, V, prec);
    arb_set_d(t, surface->beta);
    arb_mul_2exp_si(t, t, 2);
    arb_add_ui(t, t, 1, prec);
    arb_sqrt(rm, t, prec);
    arb_add(J, J, rm, prec);
    arb_set_d(t, mass);
    arb_mul(J, J, t, prec);
    *M = gb_proof_interval_of(J);
    if (volume) *volume = gb_proof_interval_of(V);
done:
    for (int k = 0; k < 3; k++) arb_clear(&e[k]), arb_clear(&a[k]);
    arb_clear(t), arb_clear(V), arb_clear(J), arb_clear(rm);
    return status;
}
