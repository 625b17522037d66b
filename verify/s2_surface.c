/* Paper §2, eqs 1–19 and 66–68: the surface and its derivatives.
 *
 * Oracle for every derivative: central finite differences (gsl_deriv_central) of the quantity one
 * order lower. The tolerance is GSL's own estimate of the difference's error (truncation plus
 * round-off) times 10, plus 64 ulp of the value's scale; a correct analytic derivative sits well
 * inside it, a wrong sign or a missing term (of order β) does not. */
#include "gb_check.h"
#include "gb_error.h"
#include "gb_surface.h"
#include "verify_sections.h"

#include <float.h>
#include <gsl/gsl_deriv.h>
#include <math.h>
#include <string.h>

/* High-entropy sample points (GSL design guide: not 0, 1 or π/2). */
static const double sample_points[][2] = {{0.7183, 2.385}, {2.2461, 5.1234}, {1.3127, 0.4123},
                                          {0.1377, 3.7701}, {2.9311, 1.0472}};
static const double sample_beta = 0.1237;
#define NPOINTS (sizeof sample_points / sizeof sample_points[0])

static const char *fd_origin = "10 x gsl_deriv_central error estimate + 64 ulp";

/* Which scalar of a gb_surface_point to differentiate, and along which angle. */
typedef struct fd_target {
    const gb_surface *surface;
    double phi, theta;
    int along_theta;
    size_t offset; /* byte offset of a double inside gb_surface_point */
} fd_target;

static double fd_eval(double t, void *params)
{
    const fd_target *f = params;
    gb_surface_point p;
    gb_surface_eval(f->surface, f->along_theta ? f->phi : t, f->along_theta ? t : f->theta, &p);
    return *(const double *)((const char *)&p + f->offset);
}

#define FIELD(name) offsetof(gb_surface_point, name)

static void check_derivative(const gb_surface *s, const double pt[2], size_t of, size_t wrt_offset,
                             int along_theta, const char *equation, const char *name)
{
    fd_target f = {s, pt[0], pt[1], along_theta, of};
    gsl_function fn = {fd_eval, &f};
    double fd, fd_err;
    gsl_deriv_central(&fn, along_theta ? pt[1] : pt[0], 1e-3, &fd, &fd_err);
    gb_surface_point p;
    gb_surface_eval(s, pt[0], pt[1], &p);
    const double analytic = *(const double *)((const char *)&p + wrt_offset);
    char quantity[160];
    snprintf(quantity, sizeof quantity, "%s, morphology %s, (phi, theta) = (%.4f, %.4f)", name,
             s->morphology->name, pt[0], pt[1]);
    gb_check c = {"2", equation, quantity, "gsl_deriv_central", fd_origin};
    gb_check_close(&c, analytic, fd, 0.0, 10.0 * fd_err + 64.0 * DBL_EPSILON * (1.0 + fabs(fd)));
}

/* eqs 18–19: the phase table's derivatives against differences of χ itself. */
static void test_eq18_19_phase_derivatives(void)
{
    for (size_t m = 0; m < gb_surface_morphology_count(); m++) {
        gb_surface s;
        gb_surface_init(&s, gb_surface_morphology_at(m)->name, sample_beta);
        for (size_t k = 0; k < NPOINTS; k++) {
            check_derivative(&s, sample_points[k], FIELD(phase.chi), FIELD(phase.chi_phi), 0, m ? "19" : "18", "d chi / d phi");
            check_derivative(&s, sample_points[k], FIELD(phase.chi), FIELD(phase.chi_theta), 1, m ? "19" : "18", "d chi / d theta");
            check_derivative(&s, sample_points[k], FIELD(phase.chi_phi), FIELD(phase.chi_phiphi), 0, m ? "19" : "18", "d2 chi / d phi2");
        }
    }
}

/* eqs 13, 14, 15 and the second derivatives the Hessian of h (eq 34) needs. */
static void test_eq13_14_15_34_derivatives(void)
{
    static const struct { size_t f, d; int theta; const char *eq, *name; } pairs[] = {
        {FIELD(S), FIELD(S_phi), 0, "13", "dS/dphi"},
        {FIELD(S), FIELD(S_theta), 1, "13", "dS/dtheta"},
        {FIELD(S_phi), FIELD(S_phiphi), 0, "13 (2nd order)", "d2S/dphi2"},
        {FIELD(S_phi), FIELD(S_phitheta), 1, "13 (2nd order)", "d2S/dphi dtheta"},
        {FIELD(S_theta), FIELD(S_thetatheta), 1, "13 (2nd order)", "d2S/dtheta2"},
        {FIELD(r), FIELD(r_phi), 0, "14", "dr/dphi"},
        {FIELD(r), FIELD(r_theta), 1, "14", "dr/dtheta"},
        {FIELD(r_phi), FIELD(r_phiphi), 0, "14 (2nd order)", "d2r/dphi2"},
        {FIELD(r_theta), FIELD(r_phitheta), 0, "14 (2nd order)", "d2r/dphi dtheta"},
        {FIELD(r_theta), FIELD(r_thetatheta), 1, "14 (2nd order)", "d2r/dtheta2"},
    };
    for (size_t m = 0; m < gb_surface_morphology_count(); m++) {
        gb_surface s;
        gb_surface_init(&s, gb_surface_morphology_at(m)->name, sample_beta);
        for (size_t k = 0; k < NPOINTS; k++) {
            for (size_t q = 0; q < sizeof pairs / sizeof pairs[0]; q++)
                check_derivative(&s, sample_points[k], pairs[q].f, pairs[q].d, pairs[q].theta, pairs[q].eq, pairs[q].name);
            for (int i = 0; i < 3; i++) {
                char name[64];
                const size_t x = FIELD(x) + i * sizeof(double), xp = FIELD(x_phi) + i * sizeof(double),
                             xt = FIELD(x_theta) + i * sizeof(double);
                snprintf(name, sizeof name, "dx_%d/dphi", i);
                check_derivative(&s, sample_points[k], x, xp, 0, "15", name);
                snprintf(name, sizeof name, "dx_%d/dtheta", i);
                check_derivative(&s, sample_points[k], x, xt, 1, "15", name);
                snprintf(name, sizeof name, "d2x_%d/dphi2", i);
                check_derivative(&s, sample_points[k], xp, FIELD(x_phiphi) + i * sizeof(double), 0, "34", name);
                snprintf(name, sizeof name, "d2x_%d/dphi dtheta", i);
                check_derivative(&s, sample_points[k], xp, FIELD(x_phitheta) + i * sizeof(double), 1, "34", name);
                snprintf(name, sizeof name, "d2x_%d/dtheta2", i);
                check_derivative(&s, sample_points[k], xt, FIELD(x_thetatheta) + i * sizeof(double), 1, "34", name);
            }
        }
    }
}

/* The central difference's error against its step: slope 2 while truncation dominates, then
 * round-off (≈ eps/h) takes over. Shown on dS/dphi of morphology II, whose χ is not linear. */
static void test_eq13_fd_convergence_order(void)
{
    gb_surface s;
    gb_surface_init(&s, "II", sample_beta);
    const double phi = 0.7183, theta = 2.385;
    gb_surface_point p;
    gb_surface_eval(&s, phi, theta, &p);
    double h[10], e[10];
    for (int k = 0; k < 10; k++) {
        h[k] = 0.2 * pow(0.25, k);
        e[k] = fabs((gb_surface_kernel(&s, phi + h[k], theta) - gb_surface_kernel(&s, phi - h[k], theta)) /
                        (2.0 * h[k]) - p.S_phi);
    }
    for (int k = 0; k + 1 < 4; k++) {
        char quantity[128];
        snprintf(quantity, sizeof quantity, "observed order of the central difference of S, h = %.3g -> %.3g", h[k], h[k + 1]);
        gb_check c = {"2", "13", quantity, "Taylor: O(h^2) truncation",
                      "+-0.1 around 2: the O(h^4) term is below 1.3% of the error for h <= 0.2"};
        gb_check_close(&c, gb_check_observed_order(e[k], e[k + 1], h[k], h[k + 1]), 2.0, 0.0, 0.1);
    }
    gb_check c = {"2", "13", "central difference at h = 7.6e-7 is dominated by round-off",
                  "round-off model eps/h", "the error must exceed the truncation extrapolated from h = 0.2"};
    const double truncation = e[0] * pow(h[9] / h[0], 2);
    gb_check_true(&c, e[9] > 10.0 * truncation, "error %.3g at h = %.3g vs extrapolated truncation %.3g", e[9], h[9], truncation);
}

/* eqs 66–68: β-sensitivity against a difference in β. */
typedef struct beta_target { const char *morphology; double phi, theta; int what; } beta_target;
static double beta_eval(double beta, void *params)
{
    const beta_target *t = params;
    gb_surface s;
    gb_surface_init(&s, t->morphology, beta);
    double x[3];
    gb_surface_position(&s, t->phi, t->theta, x);
    return t->what < 0 ? gb_surface_radius(&s, t->phi, t->theta)
                       : t->what < 3 ? x[t->what] : 0.2385 * x[0] - 0.5012 * x[1] + 0.8323 * x[2];
}

static void test_eq66_67_68_beta_sensitivity(void)
{
    const double zb[3] = {0.2385, -0.5012, 0.8323}; /* h = z_b · x, eq 68, z_b not normalised */
    for (size_t m = 0; m < gb_surface_morphology_count(); m++) {
        const char *name = gb_surface_morphology_at(m)->name;
        gb_surface s;
        gb_surface_init(&s, name, sample_beta);
        for (size_t k = 0; k < NPOINTS; k++) {
            const double phi = sample_points[k][0], theta = sample_points[k][1];
            double dx[3];
            gb_surface_position_dbeta(&s, phi, theta, dx);
            const double analytic[5] = {gb_surface_radius_dbeta(&s, phi, theta), dx[0], dx[1], dx[2],
                                        gb_surface_height_dbeta(&s, phi, theta, zb)};
            static const char *eqs[5] = {"66", "67", "67", "67", "68"};
            static const char *names[5] = {"dr/dbeta", "dx_0/dbeta", "dx_1/dbeta", "dx_2/dbeta", "dh/dbeta"};
            for (int q = 0; q < 5; q++) {
                beta_target t = {name, phi, theta, q == 0 ? -1 : q == 4 ? 3 : q - 1};
                gsl_function fn = {beta_eval, &t};
                double fd, fd_err;
                gsl_deriv_central(&fn, sample_beta, 1e-3, &fd, &fd_err);
                char quantity[128];
                snprintf(quantity, sizeof quantity, "%s, morphology %s, (phi, theta) = (%.4f, %.4f)", names[q], name, phi, theta);
                gb_check c = {"6", eqs[q], quantity, "gsl_deriv_central in beta", fd_origin};
                gb_check_close(&c, analytic[q], fd, 0.0, 10.0 * fd_err + 64.0 * DBL_EPSILON * (1.0 + fabs(fd)));
            }
        }
    }
}

/* eqs 16–17: tangents ⟂ normal, |n̂| = 1, and n points outward with n·u = r² sin φ exactly
 * (the radial graph identity (r_φ u + r u_φ) × (r_θ u + r u_θ) · u = r² (u_φ × u_θ) · u). */
static void test_eq16_17_normal(void)
{
    for (size_t m = 0; m < gb_surface_morphology_count(); m++) {
        gb_surface s;
        gb_surface_init(&s, gb_surface_morphology_at(m)->name, sample_beta);
        double worst_perp = 0.0, worst_unit = 0.0, worst_outward = 0.0, min_dot = INFINITY;
        for (int i = 0; i < 60; i++)
            for (int j = 0; j < 120; j++) {
                gb_surface_point p;
                gb_surface_eval(&s, (i + 0.5) * M_PI / 60, (j + 0.5) * M_PI / 60, &p);
                const double tp = sqrt(p.x_phi[0] * p.x_phi[0] + p.x_phi[1] * p.x_phi[1] + p.x_phi[2] * p.x_phi[2]);
                const double tt = sqrt(p.x_theta[0] * p.x_theta[0] + p.x_theta[1] * p.x_theta[1] + p.x_theta[2] * p.x_theta[2]);
                const double a = fabs(p.x_phi[0] * p.n_hat[0] + p.x_phi[1] * p.n_hat[1] + p.x_phi[2] * p.n_hat[2]) / tp;
                const double b = fabs(p.x_theta[0] * p.n_hat[0] + p.x_theta[1] * p.n_hat[1] + p.x_theta[2] * p.n_hat[2]) / tt;
                worst_perp = fmax(worst_perp, fmax(a, b));
                worst_unit = fmax(worst_unit, fabs(sqrt(p.n_hat[0] * p.n_hat[0] + p.n_hat[1] * p.n_hat[1] + p.n_hat[2] * p.n_hat[2]) - 1.0));
                const double nu = p.n[0] * p.u[0] + p.n[1] * p.u[1] + p.n[2] * p.u[2];
                const double expected = p.r * p.r * sin(p.phi);
                worst_outward = fmax(worst_outward, fabs(nu - expected) / expected);
                min_dot = fmin(min_dot, nu);
            }
        char q[96];
        snprintf(q, sizeof q, "max |cos(tangent, n_hat)| over a 60x120 grid, morphology %s", s.morphology->name);
        gb_check c1 = {"2", "16", q, "orthogonality of a cross product", "16 eps: a few roundings in each of two products"};
        gb_check_close(&c1, worst_perp, 0.0, 0.0, 16.0 * DBL_EPSILON);
        snprintf(q, sizeof q, "max ||n_hat| - 1| over the grid, morphology %s", s.morphology->name);
        gb_check c2 = {"2", "17", q, "definition of a unit vector", "4 eps: one sqrt and one division"};
        gb_check_close(&c2, worst_unit, 0.0, 0.0, 4.0 * DBL_EPSILON);
        snprintf(q, sizeof q, "max relative deviation of n.u from r^2 sin(phi), morphology %s", s.morphology->name);
        gb_check c3 = {"2", "16", q, "closed form r^2 sin(phi) for a radial graph", "64 eps: cancellation in the cross product"};
        gb_check_close(&c3, worst_outward, 0.0, 0.0, 64.0 * DBL_EPSILON);
        gb_check c4 = {"2", "16", "n points outward (n.u > 0 everywhere)", "sign of r^2 sin(phi)", "exact"};
        gb_check_true(&c4, min_dot > 0.0, "min n.u = %.3g", min_dot);
    }
}

/* β = 0 is the unit sphere exactly; at equal β the morphologies differ only in phase:
 * r_II(φ, θ') = r_I(φ, θ) when χ_II(φ, θ') = χ_I(φ, θ). */
static void test_eq7_sphere_and_phase_only(void)
{
    double worst_sphere = 0.0, worst_phase = 0.0;
    gb_surface one, two, sphere;
    gb_surface_init(&sphere, "II", 0.0);
    gb_surface_init(&one, "I", sample_beta);
    gb_surface_init(&two, "II", sample_beta);
    for (int i = 0; i < 45; i++)
        for (int j = 0; j < 90; j++) {
            const double phi = (i + 0.5) * M_PI / 45, theta = (j + 0.5) * M_PI / 45;
            double x[3], u[3];
            gb_surface_position(&sphere, phi, theta, x);
            gb_surface_direction(phi, theta, u);
            for (int k = 0; k < 3; k++) worst_sphere = fmax(worst_sphere, fabs(x[k] - u[k]));
            gb_phase_value v1, v2;
            one.morphology->phase(one.morphology, phi, theta, &v1);
            two.morphology->phase(two.morphology, phi, 0.0, &v2);
            const double theta_two = v1.chi - v2.chi; /* χ_II(φ, θ') = θ' + χ_II(φ, 0) */
            worst_phase = fmax(worst_phase, fabs(gb_surface_radius(&one, phi, theta) - gb_surface_radius(&two, phi, theta_two)));
        }
    gb_check c1 = {"2", "7", "max |x - u| at beta = 0", "unit sphere", "exact: pow(1, 0.25) = 1"};
    gb_check_close(&c1, worst_sphere, 0.0, 0.0, 0.0);
    gb_check c2 = {"2", "7-9", "max |r_I - r_II| at equal chi", "the same kernel S", "8 eps: cos of arguments equal mod 2 pi to a few ulp"};
    gb_check_close(&c2, worst_phase, 0.0, 0.0, 8.0 * DBL_EPSILON);
}

/* Bad input: β ≥ 1/4, β < 0, NaN, an unknown morphology. */
static void test_surface_error_paths(void)
{
    static const struct { const char *m; double beta; int code; const char *must_name; } cases[] = {
        {"I", 0.25, GB_EDOM, "0.25"}, {"II", -0.01, GB_EDOM, "[0, 0.25)"}, {"I", NAN, GB_EDOM, "beta"},
        {"III", 0.1, GB_EINVAL, "III"}, {NULL, 0.1, GB_EINVAL, "allowed: I, II"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        gb_surface s;
        const int status = gb_surface_init(&s, cases[k].m, cases[k].beta);
        gb_check c = {"2", "7", "gb_surface_init refuses bad input with a message naming the range", "expected status and text", "exact"};
        gb_check_true(&c, status == cases[k].code && strstr(gb_error_message(), cases[k].must_name) != NULL,
                      "morphology %s beta %g -> status %d, message '%s'", cases[k].m ? cases[k].m : "(null)",
                      cases[k].beta, status, gb_error_message());
    }
}

int verify_register_s2_surface(void)
{
    static const verify_test tests[] = {
        {"eq 18-19: phase derivatives vs finite differences", test_eq18_19_phase_derivatives, NULL},
        {"eq 13-15, 34: kernel, radius, tangents and second derivatives vs finite differences", test_eq13_14_15_34_derivatives, NULL},
        {"eq 13: observed O(h^2) order of the central difference, then round-off", test_eq13_fd_convergence_order, NULL},
        {"eq 66-68: beta-sensitivity vs finite differences in beta", test_eq66_67_68_beta_sensitivity, NULL},
        {"eq 16-17: normal orthogonal, unit, outward", test_eq16_17_normal, NULL},
        {"eq 7-9: beta = 0 is the unit sphere; morphologies differ only in phase", test_eq7_sphere_and_phase_only, NULL},
        {"eq 7: bad beta or morphology refused", test_surface_error_paths, NULL},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Section 2: surface geometry (eqs 1-19, 66-68)", tests);
}
