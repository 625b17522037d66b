/* gb_melnikov_split — the splitting of the manifolds measured directly, the oracle of the integrals: the
 * perturbed system (eq 84) integrated from the saddle's stable and unstable manifolds to a section across
 * the separatrix, under damping alone and under the full perturbation (gb_melnikov.h). */
#include "gb_melnikov.h"
#include "gb_melnikov_internal.h"

#include "gb_error.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <string.h>

/* ---- direct splitting under damping alone ------------------------------------------------------- */

typedef gb_melnikov_forced forced;

int gb_melnikov_forced_rhs(double t, const double y[], double dydt[], void *params)
{
    forced *F = params;
    gb_melnikov_values v;
    const int s = gb_melnikov_model_at(F->m, y[0], &v);
    if (s) {
        if (!F->status) F->status = s;
        return GSL_EBADFUNC;
    }
    const gb_melnikov_forcing *f = F->f;
    const double G = -f->mu * (f->damping_per_mass ? y[1] / v.M : y[1]) + f->nu1 * v.S * cos(f->omega * t) +
                     f->nu2 * v.S * cos(2.0 * f->omega * t + f->psi);
    dydt[0] = y[1] / v.M;
    dydt[1] = y[1] * y[1] * v.dM / (2.0 * v.M * v.M) - v.dU + F->epsilon * G;
    return GSL_SUCCESS;
}

/* Flow y from the saddle neighbourhood (forward when sign > 0, backward otherwise) until it crosses the
 * section through x0 normal to f0 within `window` of x0 (a crossing of the line farther away is the
 * orbit passing elsewhere); y is left on the section, located by bisection on the step. */
static int to_section(forced *F, double sign, double limit, const double x0[2], const double f0[2], double window, double y[2],
                      double *t_cross)
{
    gsl_odeiv2_system sys = {gb_melnikov_forced_rhs, NULL, 2, F};
    gsl_odeiv2_step *step = gsl_odeiv2_step_alloc(gsl_odeiv2_step_rk8pd, 2);
    gsl_odeiv2_control *control = gsl_odeiv2_control_y_new(1e-14, 1e-13);
    gsl_odeiv2_evolve *evolve = gsl_odeiv2_evolve_alloc(2);
    int status = step && control && evolve ? GB_OK : gb_error_set(GB_ENOMEM, "out of memory for the stepper"), crossed = 0;
    double t = 0.0, h = sign * 1e-3;
    while (!status && !crossed && fabs(t) < limit) {
        double before[2] = {y[0], y[1]};
        const double t_before = t, g0 = (y[0] - x0[0]) * f0[0] + (y[1] - x0[1]) * f0[1];
        const int s = gsl_odeiv2_evolve_apply(evolve, control, step, &sys, &t, sign * limit, &h, y);
        if (s != GSL_SUCCESS) {
            status = F->status ? F->status : gb_error_set(GB_ENUMERIC, "the manifold's integration failed: %s", gsl_strerror(s));
            break;
        }
        const double g = (y[0] - x0[0]) * f0[0] + (y[1] - x0[1]) * f0[1];
        if (g * g0 > 0.0 || g0 == 0.0) continue;
        /* Bisect the step for the crossing. */
        double lo = 0.0, hi = t - t_before, mid[2] = {y[0], y[1]};
        for (int it = 0; it < 200 && fabs(hi - lo) > 1e-16 * fmax(1.0, fabs(t)); it++) {
            const double dt = 0.5 * (lo + hi);
            double err[2];
            memcpy(mid, before, sizeof mid);
            gsl_odeiv2_step_reset(step);
            if (gsl_odeiv2_step_apply(step, t_before, dt, mid, err, NULL, NULL, &sys) != GSL_SUCCESS) {
                status = F->status ? F->status : gb_error_set(GB_ENUMERIC, "the manifold's crossing could not be located");
                break;
            }
            const double gm = (mid[0] - x0[0]) * f0[0] + (mid[1] - x0[1]) * f0[1];
            if (gm * g0 > 0.0) lo = dt;
            else hi = dt;
        }
        gsl_odeiv2_step_reset(step);
        gsl_odeiv2_evolve_reset(evolve);
        if (hypot(mid[0] - x0[0], mid[1] - x0[1]) < window) {
            memcpy(y, mid, sizeof mid), crossed = 1;
            if (t_cross) *t_cross = t_before + 0.5 * (lo + hi);
        }
    }
    if (evolve) gsl_odeiv2_evolve_free(evolve);
    if (control) gsl_odeiv2_control_free(control);
    if (step) gsl_odeiv2_step_free(step);
    if (!status && !crossed) status = gb_error_set(GB_ENOCONV, "the manifold did not reach the section within t = %g", limit);
    return status;
}

int gb_melnikov_split_damped(const gb_melnikov_model *m, const gb_melnikov_orbit *o, double epsilon_mu, double *measured,
                             double *flow_speed)
{
    gb_melnikov_values v0, vu, ve;
    int status = gb_melnikov_model_at(m, o->q0, &v0);
    if (!status) status = gb_melnikov_model_at(m, o->q_u, &vu);
    if (!status) status = gb_melnikov_model_at(m, m->period > 0.0 ? o->q_end : o->q_u, &ve);
    if (status) return status;
    /* x_h(0) and the unperturbed field there. */
    const int dir = m->direction;
    const double p0 = m->period > 0.0 ? dir * sqrt(2.0 * v0.M * fmax(o->E_s - v0.U, 0.0)) : 0.0;
    const double x0[2] = {o->q0, p0};
    const double f0[2] = {p0 / v0.M, p0 * p0 * v0.dM / (2.0 * v0.M * v0.M) - v0.dU};
    *flow_speed = hypot(f0[0], f0[1]);
    /* Eigenvalues of the damped saddle: λ² + εμλ + U″/M = 0; eigenvectors (1, λM). */
    const double disc = sqrt(epsilon_mu * epsilon_mu - 4.0 * o->curvature / vu.M);
    const double up = 0.5 * (-epsilon_mu + disc), down_end = 0.5 * (-epsilon_mu - sqrt(epsilon_mu * epsilon_mu - 4.0 * o->curvature / ve.M));
    const double delta = 1e-7, limit = 200.0 / o->rate;
    const gb_melnikov_forcing damping = {1.0, 0.0, 0.0, 1.0, 0.0, 0};
    forced F = {m, &damping, epsilon_mu, GB_OK};
    double yu[2] = {o->q_u + dir * delta, dir * delta * up * vu.M};
    /* The stable manifold: of the far copy of the saddle (a rotation) or of the saddle itself, entered
     * from the side of the loop (q̇ of sign −dir on the way back). */
    const double s_end = m->period > 0.0 ? o->q_end : o->q_u, side = m->period > 0.0 ? -dir : dir;
    double ys[2] = {s_end + side * delta, side * delta * down_end * ve.M};
    /* The crossing must lie within a tenth of the orbit's distance from the saddle to x_h(0). */
    const double window = 0.1 * hypot(x0[0] - o->q_u, x0[1]);
    status = to_section(&F, +1.0, limit, x0, f0, window, yu, NULL);
    if (!status) status = to_section(&F, -1.0, limit, x0, f0, window, ys, NULL);
    if (status) return status;
    const double n[2] = {-f0[1] / *flow_speed, f0[0] / *flow_speed};
    *measured = (yu[0] - ys[0]) * n[0] + (yu[1] - ys[1]) * n[1];
    return GB_OK;
}

int gb_melnikov_flight_time(const gb_melnikov_model *m, const gb_melnikov_orbit *o, double q_a, double q_b, double *dt)
{
    gb_melnikov_values vu;
    int status = gb_melnikov_model_at(m, o->q_u, &vu);
    if (status) return status;
    const int dir = m->direction;
    const double delta = 1e-9, up = o->rate, limit = 200.0 / o->rate;
    const gb_melnikov_forcing none = {0.0, 0.0, 0.0, 1.0, 0.0, 0};
    forced F = {m, &none, 0.0, GB_OK};
    double y[2] = {o->q_u + dir * delta, dir * delta * up * vu.M};
    /* The levels as sections: the line q = level, crossed where the orbit reaches it; the time counts
     * from the first crossing. */
    const double xa[2] = {q_a, 0.0}, xb[2] = {q_b, 0.0}, fq[2] = {1.0, 0.0};
    *dt = NAN;
    status = to_section(&F, +1.0, limit, xa, fq, INFINITY, y, NULL);
    if (!status) status = to_section(&F, +1.0, limit, xb, fq, INFINITY, y, dt);
    return status;
}

/* ---- direct splitting under the full perturbation ---------------------------------------------- */

int gb_melnikov_forced_flow(forced *F, double t_from, double t_to, double y[2])
{
    gsl_odeiv2_system sys = {gb_melnikov_forced_rhs, NULL, 2, F};
    const double h = t_to > t_from ? 1e-3 : -1e-3;
    gsl_odeiv2_driver *d = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, h, 1e-14, 1e-13);
    if (!d) return gb_error_set(GB_ENOMEM, "out of memory for the stepper");
    double t = t_from;
    const int s = gsl_odeiv2_driver_apply(d, &t, t_to, y);
    gsl_odeiv2_driver_free(d);
    if (s != GSL_SUCCESS) return F->status ? F->status : gb_error_set(GB_ENUMERIC, "the forced flow failed: %s", gsl_strerror(s));
    return GB_OK;
}

int gb_melnikov_saddle_orbit(forced *F, double q_u, double t0, double x[2], double vu[2], double vs[2],
                             double multipliers[2])
{
    const double T = 2.0 * M_PI / F->f->omega, h = 1e-7;
    x[0] = q_u, x[1] = 0.0;
    double J[2][2];
    int status = GB_OK;
    for (int it = 0; it < 30 && !status; it++) {
        double P[2] = {x[0], x[1]};
        status = gb_melnikov_forced_flow(F, t0, t0 + T, P);
        for (int j = 0; j < 2 && !status; j++) {
            double a[2] = {x[0], x[1]}, b[2] = {x[0], x[1]};
            a[j] += h, b[j] -= h;
            status = gb_melnikov_forced_flow(F, t0, t0 + T, a);
            if (!status) status = gb_melnikov_forced_flow(F, t0, t0 + T, b);
            for (int i = 0; i < 2; i++) J[i][j] = (a[i] - b[i]) / (2 * h);
        }
        if (status) break;
        /* Newton on P(x) − x = 0. */
        const double A[2][2] = {{J[0][0] - 1, J[0][1]}, {J[1][0], J[1][1] - 1}}, r[2] = {P[0] - x[0], P[1] - x[1]};
        const double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
        const double dx[2] = {(A[1][1] * r[0] - A[0][1] * r[1]) / det, (-A[1][0] * r[0] + A[0][0] * r[1]) / det};
        x[0] -= dx[0], x[1] -= dx[1];
        if (hypot(dx[0], dx[1]) < 1e-15) break;
    }
    if (status) return status;
    const double tr = J[0][0] + J[1][1], det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    const double disc = sqrt(fmax(0.0, 0.25 * tr * tr - det)), lu = 0.5 * tr + disc, ls = 0.5 * tr - disc;
    if (!(lu > 1.0 && fabs(ls) < 1.0)) return gb_error_set(GB_ENUMERIC, "the periodic orbit is not hyperbolic (multipliers %g, %g)", lu, ls);
    /* Eigenvectors of J: (J01, λ − J00), normalised. */
    const double eu[2] = {J[0][1], lu - J[0][0]}, es[2] = {J[0][1], ls - J[0][0]};
    const double nu = hypot(eu[0], eu[1]), ns = hypot(es[0], es[1]);
    vu[0] = eu[0] / nu, vu[1] = eu[1] / nu, vs[0] = es[0] / ns, vs[1] = es[1] / ns;
    if (multipliers) multipliers[0] = lu, multipliers[1] = ls;
    return GB_OK;
}

/* A point of the manifold (unstable: forward from t0 − kT; stable: backward from t0 + kT) on the section
 * through x0 normal to f0, near x0. The displacement s along v from the periodic orbit that arrives at
 * time t0 is estimated from the unperturbed flight time (`arrival`: the time from s to x_h(0), as
 * ln(s_ref/s)/λ + t_ref), bracketed on a fine logarithmic grid around it, and found by bisection. */
static int manifold_on_section(forced *F, double t0, const double xp[2], const double v[2], double side, int unstable,
                               const double x0[2], const double f0[2], double window, double rate, double t_ref,
                               double s_ref, double out[2])
{
    const double T = 2.0 * M_PI / F->f->omega;
    const int k0 = (int)floor((t_ref + log(s_ref / 1e-3) / rate) / T), k1 = (int)ceil((t_ref + log(s_ref / 1e-10) / rate) / T);
    for (int k = k0 < 1 ? 1 : k0; k <= k1; k++) {
        const double t_start = unstable ? t0 - k * T : t0 + k * T;
        /* s arriving after k T: ln(s_ref/s)/λ + t_ref = kT */
        const double s_mid = s_ref * exp(-rate * (k * T - t_ref));
        double prev_g = NAN, prev_s = NAN;
        for (int j = 0; j <= 80; j++) {
            const double s = s_mid * pow(10.0, -1.0 + 2.0 * j / 80.0);
            double y[2] = {xp[0] + side * s * v[0], xp[1] + side * s * v[1]};
            int status = gb_melnikov_forced_flow(F, t_start, t0, y);
            if (status) return status;
            const double g = (y[0] - x0[0]) * f0[0] + (y[1] - x0[1]) * f0[1];
            if (j > 0 && g * prev_g <= 0.0) {
                double lo = prev_s, hi = s, glo = prev_g, z[2] = {y[0], y[1]};
                for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; it++) {
                    const double mid = sqrt(lo * hi);
                    z[0] = xp[0] + side * mid * v[0], z[1] = xp[1] + side * mid * v[1];
                    status = gb_melnikov_forced_flow(F, t_start, t0, z);
                    if (status) return status;
                    const double gm = (z[0] - x0[0]) * f0[0] + (z[1] - x0[1]) * f0[1];
                    if (gm * glo > 0.0) lo = mid, glo = gm;
                    else hi = mid;
                }
                if (hypot(z[0] - x0[0], z[1] - x0[1]) < window) {
                    memcpy(out, z, sizeof z);
                    return GB_OK;
                }
            }
            prev_g = g, prev_s = s;
        }
    }
    return gb_error_set(GB_ENOCONV, "no point of the %s manifold reached the section near x_h(0)", unstable ? "unstable" : "stable");
}

int gb_melnikov_split_forced(const gb_melnikov_model *m, const gb_melnikov_orbit *o, const gb_melnikov_forcing *f,
                             double epsilon, double t0, double *measured, double *flow_speed)
{
    gb_melnikov_values v0;
    int status = gb_melnikov_model_at(m, o->q0, &v0);
    if (status) return status;
    const int dir = m->direction;
    const double p0 = m->period > 0.0 ? dir * sqrt(2.0 * v0.M * fmax(o->E_s - v0.U, 0.0)) : 0.0;
    const double x0[2] = {o->q0, p0};
    const double f0[2] = {p0 / v0.M, p0 * p0 * v0.dM / (2.0 * v0.M * v0.M) - v0.dU};
    *flow_speed = hypot(f0[0], f0[1]);
    forced F = {m, f, epsilon, GB_OK};
    double xp[2], vu[2] = {0, 0}, vs[2] = {0, 0};
    status = gb_melnikov_saddle_orbit(&F, o->q_u, t0, xp, vu, vs, NULL);
    if (status) return status;
    /* The unstable manifold leaves towards `dir`; the stable one is entered from the side of the loop, or
     * is that of the far copy of the periodic orbit (a rotation). */
    const double su = vu[0] * dir >= 0.0 ? 1.0 : -1.0;
    double xs[2] = {xp[0], xp[1]};
    if (m->period > 0.0) xs[0] += dir * m->period;
    const double toward = m->period > 0.0 ? -dir : dir, ss = vs[0] * toward >= 0.0 ? 1.0 : -1.0;
    const double window = 0.1 * hypot(x0[0] - o->q_u, x0[1]);
    /* The unperturbed flight time from a displacement s_ref off the saddle to x_h(0). */
    const double s_ref = 1e-4;
    double t_out, t_back;
    status = gb_melnikov_time(m, o, o->q_u + dir * s_ref, &t_out);
    if (!status) status = gb_melnikov_time(m, o, m->period > 0.0 ? o->q_end - dir * s_ref : o->q_u + dir * s_ref, &t_back);
    if (status) return status;
    double yu[2], ys[2];
    status = manifold_on_section(&F, t0, xp, vu, su, 1, x0, f0, window, o->rate, fabs(t_out), s_ref, yu);
    if (!status) status = manifold_on_section(&F, t0, xs, vs, ss, 0, x0, f0, window, o->rate, fabs(t_back), s_ref, ys);
    if (status) return status;
    const double n[2] = {-f0[1] / *flow_speed, f0[0] / *flow_speed};
    *measured = (yu[0] - ys[0]) * n[0] + (yu[1] - ys[1]) * n[1];
    return GB_OK;
}
