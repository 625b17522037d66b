/* gb_melnikov_criterion — the Melnikov function of the integrals (eq 86) and what it decides: the maximum
 * over t₀ of its oscillatory part against the damping (eq 91, the exact condition for a sign change), the
 * bound of eq 93, and the thresholds of both (gb_melnikov.h). */
#include "gb_melnikov.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_min.h>
#include <math.h>

double gb_melnikov_function(const gb_melnikov_integrals *I, const gb_melnikov_forcing *f, double t0)
{
    const double a = f->omega * t0, b = 2.0 * f->omega * t0 + f->psi;
    return -f->mu * (f->damping_per_mass ? I->D_mass : I->D) + f->nu1 * (I->C1 * cos(a) - I->S1 * sin(a)) + f->nu2 * (I->C2 * cos(b) - I->S2 * sin(b));
}

static double damping_term(const gb_melnikov_integrals *I, const gb_melnikov_forcing *f)
{
    return f->mu * (f->damping_per_mass ? I->D_mass : I->D);
}

static double oscillatory(const gb_melnikov_integrals *I, const gb_melnikov_forcing *f, double t0)
{
    return gb_melnikov_function(I, f, t0) + damping_term(I, f);
}

typedef struct judged {
    const gb_melnikov_integrals *I;
    const gb_melnikov_forcing *f;
} judged;

static double minus_oscillatory(double t0, void *p)
{
    const judged *j = p;
    return -oscillatory(j->I, j->f, t0);
}

void gb_melnikov_judge(const gb_melnikov_integrals *I, const gb_melnikov_forcing *f, gb_melnikov_criterion *out)
{
    const double T = 2.0 * M_PI / f->omega;
    enum { N = 4096 };
    double best = -INFINITY, at = 0.0;
    for (int k = 0; k < N; k++) {
        const double t0 = T * k / N, v = oscillatory(I, f, t0);
        if (v > best) best = v, at = t0;
    }
    /* Refine the sampled maximum with Brent's minimiser on −oscillatory. */
    judged j = {I, f};
    gsl_function F = {minus_oscillatory, &j};
    gsl_min_fminimizer *s = gsl_min_fminimizer_alloc(gsl_min_fminimizer_brent);
    const double h = T / N;
    if (s && -minus_oscillatory(at, &j) > fmax(-minus_oscillatory(at - h, &j), -minus_oscillatory(at + h, &j)) &&
        gsl_min_fminimizer_set(s, &F, at, at - h, at + h) == GSL_SUCCESS) {
        for (int it = 0; it < 100; it++) {
            if (gsl_min_fminimizer_iterate(s) != GSL_SUCCESS) break;
            if (gsl_min_test_interval(gsl_min_fminimizer_x_lower(s), gsl_min_fminimizer_x_upper(s), 1e-14 * T, 0.0) == GSL_SUCCESS) break;
        }
        at = gsl_min_fminimizer_x_minimum(s);
        best = fmax(best, oscillatory(I, f, at));
    }
    if (s) gsl_min_fminimizer_free(s);
    out->oscillatory_max = best;
    out->t0_max = fmod(fmod(at, T) + T, T);
    out->eq93 = fabs(f->nu1) * I->A1 + fabs(f->nu2) * I->A2 > damping_term(I, f); /* A* ≥ 0: |ν| bounds a harmonic of either sign */
    out->sign_change = best > damping_term(I, f);
}

void gb_melnikov_threshold(const gb_melnikov_integrals *I, const gb_melnikov_forcing *f, double *by_eq93, double *exact)
{
    gb_melnikov_criterion c;
    gb_melnikov_judge(I, f, &c);
    *by_eq93 = damping_term(I, f) / (fabs(f->nu1) * I->A1 + fabs(f->nu2) * I->A2);
    *exact = damping_term(I, f) / c.oscillatory_max;
}
