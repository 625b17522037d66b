/* gb_proof_body_chain — the h-sets of a horseshoe of the Gömböcs' period map, placed on floats along one homoclinic
 * orbit (gb_proof_body.h). Nothing here is proved: the sets are the proof's input, and gb_proof_body_cover_link proves
 * (or not) their covering relations on Arb's balls.
 *
 * The float field is the proof's, q̇ = P, Ṗ = −(m/M) a(t) H′(q) − μP, with H′ from the body's tabulated model
 * (gb_melnikov_body, the `top` reading), M the middle of def->inertia and ψ the middle of forcing->psi; the period map
 * P from phase 0 by GSL's rk8pd (tolerances 1e-13), its derivative by central differences (step 1e-6). At the saddle
 * (0, 0), an equilibrium of the forced field (H′(0) = 0), DP's eigenvectors v_u, v_s. The homoclinic point: Newton's
 * method on P^{n_u}(δ v_u) = P^{−n_s}((2π, 0) − σ v_s) in (δ, σ), from the definition's seeds, so that the orbit leaves
 * the saddle along W^u and reaches its copy 2π on along W^s. Along the orbit z_k (k = 0 … n_u + n_s) the frames: u_k
 * carried forward from v_u (u_{k+1} = DP(z_k) u_k / α_k), s_k carried backward from v_s (s_k = DP(z_k)⁻¹ s_{k+1} β_k),
 * so that DP(z_k) maps u_k to α_k u_{k+1} and s_k to β_k s_{k+1}. The sets: N₀ = v_u [−r_u, r_u] + v_s [−r_s, r_s] at
 * the saddle; N_i at z_{first + i − 1} (i = 1 … m) in the frame (u, s) with half-widths a_1, b_1 and then
 * a_{i+1} = α a_i / ρ, b_{i+1} = max(ρ β b_i, b_min): each image is a ρ-th longer across and a ρ-th thinner along
 * than the next set, in the linear part; the last set's image must cross N₀ 2π on. */
#include "gb_proof_body.h"

#include "gb_error.h"
#include "gb_melnikov_body.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct float_field {
    gb_melnikov_model model;
    double mass_g, m_over_M, mu, A1, A2, omega, psi, g, period;
} float_field;

static int rhs(double t, const double y[], double f[], void *context)
{
    const float_field *F = context;
    const double turn = 2.0 * M_PI, q = y[0] - turn * floor(y[0] / turn); /* H is 2π-periodic */
    gb_melnikov_values v;
    if (F->model.eval(F->model.context, q, &v)) return GSL_EBADFUNC;
    const double a = F->g + F->A1 * cos(F->omega * t) + F->A2 * cos(2.0 * F->omega * t + F->psi);
    f[0] = y[1];
    f[1] = -F->m_over_M * a * v.dU / F->mass_g - F->mu * y[1];
    return GSL_SUCCESS;
}

/* x ↦ P^n(x) (n < 0: the inverse's |n|-th iterate). */
static int period_map(const float_field *F, const double x[2], int n, double out[2])
{
    out[0] = x[0], out[1] = x[1];
    gsl_odeiv2_system sys = {rhs, NULL, 2, (void *)F};
    gsl_odeiv2_driver *d =
        gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, n < 0 ? -1e-4 : 1e-4, 1e-13, 1e-13);
    if (!d) return gb_error_set(GB_ENOMEM, "the chain's float period map: no memory for the integrator");
    int status = GSL_SUCCESS;
    for (int k = 0; k < abs(n) && status == GSL_SUCCESS; k++) {
        double t = n < 0 ? F->period : 0.0;
        gsl_odeiv2_driver_reset(d);
        status = gsl_odeiv2_driver_apply(d, &t, n < 0 ? 0.0 : F->period, out);
    }
    gsl_odeiv2_driver_free(d);
    return status == GSL_SUCCESS ? GB_OK
                                 : gb_error_set(GB_ENUMERIC, "the chain's float period map failed (GSL status %d)", status);
}

static int derivative(const float_field *F, const double x[2], double J[2][2])
{
    const double h = 1e-6;
    for (int j = 0; j < 2; j++) {
        double a[2] = {x[0], x[1]}, b[2] = {x[0], x[1]}, pa[2], pb[2];
        a[j] += h, b[j] -= h;
        int status = period_map(F, a, 1, pa);
        if (!status) status = period_map(F, b, 1, pb);
        if (status) return status;
        for (int i = 0; i < 2; i++) J[i][j] = (pa[i] - pb[i]) / (2.0 * h);
    }
    return GB_OK;
}

/* Table 1's rolling forcing (cases/table1-gomboc-*-rolling.ini). Gömböc II: a crossing of W^u's 29th image of its
 * fundamental domain from 1e-7 with W^s's 30th (the float tangle's), sets from z_16 (0.017 from the saddle) to z_47
 * (8e-4 from its copy). Gömböc I: the same pair of images (their only crossing), sets from z_15 (0.015) to z_48
 * (6e-4), N_1 thinner across (the images' curvature by the copy). */
static const struct {
    const char *morphology;
    gb_proof_body_chain_def def;
} defaults[] = {
    {"II",
     {.unstable_iterates = 29,
      .stable_iterates = 30,
      .unstable_seed = 1.3632e-7,
      .stable_seed = 1.1336e-7,
      .first = 16,
      .last = 47,
      .saddle_half = {0.011, 5e-4},
      .first_half = {4e-7, 2.6e-4},
      .rho = 1.05,
      .along_min = 1e-6}},
    {"I",
     {.unstable_iterates = 29,
      .stable_iterates = 30,
      .unstable_seed = 2.0445e-7,
      .stable_seed = 1.6313e-7,
      .first = 15,
      .last = 48,
      .saddle_half = {0.0093, 4e-4},
      .first_half = {1e-7, 2.1e-4},
      .rho = 1.05,
      .along_min = 1e-6}},
};

int gb_proof_body_chain_default(const char *morphology, gb_proof_body_chain_def *out)
{
    for (size_t k = 0; morphology && k < sizeof defaults / sizeof defaults[0]; k++)
        if (!strcmp(morphology, defaults[k].morphology)) {
            *out = defaults[k].def;
            return GB_OK;
        }
    return gb_error_set(GB_EDOM, "the chain's body '%s' has no default sets (allowed: I, II)",
                        morphology ? morphology : "(none)");
}

static int check_chain_def(const gb_proof_body_chain_def *c)
{
    const int n = c->unstable_iterates + c->stable_iterates;
    if (!(c->unstable_iterates >= 1 && c->stable_iterates >= 1 && n <= GB_PROOF_BODY_CHAIN_MAX))
        return gb_error_set(GB_EDOM, "the chain's iterates %d and %d are out of range (allowed: each >= 1, sum <= %d)",
                            c->unstable_iterates, c->stable_iterates, GB_PROOF_BODY_CHAIN_MAX);
    if (!(c->unstable_seed > 0.0 && c->unstable_seed <= 1e-3 && c->stable_seed > 0.0 && c->stable_seed <= 1e-3))
        return gb_error_set(GB_EDOM, "the chain's seeds %g and %g are out of range (allowed: 0 < seed <= 1e-3)",
                            c->unstable_seed, c->stable_seed);
    if (!(c->first >= 1 && c->first < c->last && c->last < n))
        return gb_error_set(GB_EDOM, "the chain's first and last orbit points %d and %d are out of range (allowed: 1 <= "
                                     "first < last < %d)",
                            c->first, c->last, n);
    for (int i = 0; i < 2; i++)
        if (!(c->saddle_half[i] > 0.0 && c->saddle_half[i] < 1.0 && c->first_half[i] > 0.0 && c->first_half[i] < 1.0))
            return gb_error_set(GB_EDOM, "the chain's half-widths must lie in (0, 1) (allowed: 0 < r, a, b < 1)");
    if (!(c->rho > 1.0 && c->rho <= 2.0))
        return gb_error_set(GB_EDOM, "rho = %g is out of range (allowed: 1 < rho <= 2)", c->rho);
    if (!(c->along_min >= 0.0 && c->along_min < 1.0))
        return gb_error_set(GB_EDOM, "along_min = %g is out of range (allowed: 0 <= along_min < 1)", c->along_min);
    return GB_OK;
}

int gb_proof_body_chain_design(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing,
                               const gb_proof_body_chain_def *cd, gb_proof_body_chain *out)
{
    memset(out, 0, sizeof *out);
    int status = check_chain_def(cd);
    if (status) return status;
    gb_melnikov_body *body = NULL;
    status = gb_melnikov_body_create(def->surface, def->mass, def->g, GB_MELNIKOV_BODY_NODES, &body);
    if (status) return status;
    gb_melnikov_body_info info;
    gb_melnikov_body_get_info(body, &info);
    const double M = 0.5 * def->inertia.lo + 0.5 * def->inertia.hi;
    const float_field F = {gb_melnikov_body_model(body, GB_MELNIKOV_MASS_AT_TOP),
                           def->mass * def->g,
                           def->mass / M,
                           forcing->damping / M,
                           forcing->A1,
                           forcing->A2,
                           forcing->omega,
                           0.5 * forcing->psi.lo + 0.5 * forcing->psi.hi,
                           def->g,
                           2.0 * M_PI / forcing->omega};
    /* the saddle's eigenvectors: v_u with q > 0, v_s with q > 0 (so that (2π, 0) − σ v_s lies below the copy) */
    const double o[2] = {0.0, 0.0};
    double J[2][2], v[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
    status = derivative(&F, o, J);
    if (!status) {
        const double tr = J[0][0] + J[1][1], det = J[0][0] * J[1][1] - J[0][1] * J[1][0], disc = tr * tr / 4.0 - det;
        if (!(disc > 0.0)) status = gb_error_set(GB_ENUMERIC, "the saddle's multipliers are not real");
        for (int k = 0; k < 2 && !status; k++) {
            out->multipliers[k] = tr / 2.0 + (k ? -1.0 : 1.0) * sqrt(disc);
            const double x = J[0][1], y = out->multipliers[k] - J[0][0], r = hypot(x, y), sign = x < 0 ? -1.0 : 1.0;
            v[k][0] = sign * x / r, v[k][1] = sign * y / r;
        }
    }
    /* the homoclinic point: Newton on (δ, σ), the derivative by forward differences (relative step 1e-6) */
    const int nu = cd->unstable_iterates, n = nu + cd->stable_iterates;
    double d = cd->unstable_seed, sg = cd->stable_seed, best = INFINITY, best_d = d, best_sg = sg, a[2], b[2];
    for (int it = 0; it < 12 && !status; it++) {
        const double x[2] = {d * v[0][0], d * v[0][1]}, y[2] = {2.0 * M_PI - sg * v[1][0], -sg * v[1][1]};
        status = period_map(&F, x, nu, a);
        if (!status) status = period_map(&F, y, -cd->stable_iterates, b);
        const double r = hypot(a[0] - b[0], a[1] - b[1]), before = best;
        if (!status && r < best) best = r, best_d = d, best_sg = sg;
        if (status || !(r < 0.5 * before) || r < 1e-12) break; /* converged to the integration's noise */
        const double hd = 1e-6 * d, hs = 1e-6 * sg, xd[2] = {(d + hd) * v[0][0], (d + hd) * v[0][1]},
                     ys[2] = {2.0 * M_PI - (sg + hs) * v[1][0], -(sg + hs) * v[1][1]};
        double ad[2], bs[2];
        status = period_map(&F, xd, nu, ad);
        if (!status) status = period_map(&F, ys, -cd->stable_iterates, bs);
        if (status) break;
        const double A[2][2] = {{(ad[0] - a[0]) / hd, -(bs[0] - b[0]) / hs}, {(ad[1] - a[1]) / hd, -(bs[1] - b[1]) / hs}};
        const double det = A[0][0] * A[1][1] - A[0][1] * A[1][0], f0 = a[0] - b[0], f1 = a[1] - b[1];
        if (!(fabs(det) > 0.0)) break;
        d -= (A[1][1] * f0 - A[0][1] * f1) / det, sg -= (-A[1][0] * f0 + A[0][0] * f1) / det;
    }
    d = best_d, sg = best_sg;
    out->residual = best;
    if (!status && !(best < 1e-6))
        status = gb_error_set(GB_ENUMERIC, "no homoclinic point near the seeds (the manifolds' points stay %g apart)", best);
    /* the orbit, forward from W^u up to the meeting, backward from W^s after it */
    double(*z)[2] = NULL, (*u)[2] = NULL, (*s)[2] = NULL, *alpha = NULL, *beta = NULL;
    if (!status) {
        z = calloc((size_t)n + 1, sizeof *z), u = calloc((size_t)n + 1, sizeof *u), s = calloc((size_t)n + 1, sizeof *s);
        alpha = calloc((size_t)n + 1, sizeof *alpha), beta = calloc((size_t)n + 1, sizeof *beta);
        if (!z || !u || !s || !alpha || !beta) status = gb_error_set(GB_ENOMEM, "the chain's orbit: no memory");
    }
    if (!status) {
        z[0][0] = d * v[0][0], z[0][1] = d * v[0][1];
        for (int k = 1; k <= nu && !status; k++) status = period_map(&F, z[k - 1], 1, z[k]);
        z[n][0] = 2.0 * M_PI - sg * v[1][0], z[n][1] = -sg * v[1][1];
        for (int k = n - 1; k > nu && !status; k--) status = period_map(&F, z[k + 1], -1, z[k]);
    }
    /* the frames */
    u[0][0] = v[0][0], u[0][1] = v[0][1];
    for (int k = 0; k < n && !status; k++) {
        status = derivative(&F, z[k], J);
        const double w0 = J[0][0] * u[k][0] + J[0][1] * u[k][1], w1 = J[1][0] * u[k][0] + J[1][1] * u[k][1];
        alpha[k] = hypot(w0, w1), u[k + 1][0] = w0 / alpha[k], u[k + 1][1] = w1 / alpha[k];
    }
    if (!status) s[n][0] = v[1][0], s[n][1] = v[1][1];
    for (int k = n - 1; k >= 0 && !status; k--) {
        status = derivative(&F, z[k], J);
        const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
        const double w0 = (J[1][1] * s[k + 1][0] - J[0][1] * s[k + 1][1]) / det,
                     w1 = (-J[1][0] * s[k + 1][0] + J[0][0] * s[k + 1][1]) / det, r = hypot(w0, w1);
        beta[k] = 1.0 / r, s[k][0] = w0 / r, s[k][1] = w1 / r;
    }
    /* the sets: N₀, N_1 … N_m, and the links' ties */
    const int m = cd->last - cd->first + 1;
    if (!status) {
        out->set = calloc((size_t)m + 1, sizeof *out->set), out->tie = calloc((size_t)m + 1, sizeof *out->tie);
        if (!out->set || !out->tie) status = gb_error_set(GB_ENOMEM, "the chain's sets: no memory");
    }
    if (!status) {
        out->sets = (size_t)m + 1, out->orbit_points = (size_t)n + 1;
        out->homoclinic[0] = z[nu][0], out->homoclinic[1] = z[nu][1];
        out->set[0] = (gb_proof_body_hset){{0.0, 0.0}, {{v[0][0], v[1][0]}, {v[0][1], v[1][1]}}, {cd->saddle_half[0], cd->saddle_half[1]}};
        out->tie[0] = -1;
        double ah = cd->first_half[0], bh = cd->first_half[1], product = 1.0;
        for (int i = 1; i <= m; i++) {
            const int j = cd->first + i - 1;
            out->set[i] = (gb_proof_body_hset){{z[j][0], z[j][1]}, {{u[j][0], s[j][0]}, {u[j][1], s[j][1]}}, {ah, bh}};
            ah *= alpha[j] / cd->rho, bh = fmax(bh * beta[j] * cd->rho, cd->along_min);
            out->tie[i] = -1; /* the link N_i ⇒ N_{i+1} (N₀ 2π on for the last) crosses the tie between z_j and z_{j+1} */
            for (size_t t = 0; t < info.kinks && t < 16; t++)
                if (z[j][0] < info.kink_q[t] && z[j + 1][0] > info.kink_q[t]) out->tie[i] = (int)t;
        }
        for (int k = 0; k < n; k++) product *= alpha[k] * beta[k];
        out->liouville = product; /* ∏ α_k β_k: det DP's product along the orbit, the frames at both ends the saddle's */
    }
    free(z), free(u), free(s), free(alpha), free(beta);
    gb_melnikov_body_free(body);
    if (status) gb_proof_body_chain_free(out);
    return status;
}

void gb_proof_body_chain_free(gb_proof_body_chain *chain)
{
    free(chain->set), free(chain->tie);
    chain->set = NULL, chain->tie = NULL, chain->sets = 0;
}
