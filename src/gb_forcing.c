#include "gb_forcing.h"

#include "gb_error.h"

#include <math.h>

int gb_forcing_validate(const gb_forcing *f)
{
    if (!(isfinite(f->g) && f->g >= 0.0))
        return gb_error_set(GB_EDOM, "g = %g is out of range (allowed: finite, >= 0)", f->g);
    if (!(isfinite(f->omega) && f->omega > 0.0))
        return gb_error_set(GB_EDOM, "omega = %g is out of range (allowed: finite, > 0)", f->omega);
    if (!(isfinite(f->a1) && isfinite(f->a2) && isfinite(f->psi)))
        return gb_error_set(GB_EDOM, "forcing amplitudes and phase must be finite (a1 = %g, a2 = %g, psi = %g)",
                            f->a1, f->a2, f->psi);
    return GB_OK;
}

double gb_forcing_geff(const gb_forcing *f, double t)
{
    double g = f->g;
    if (f->a1 != 0.0) g += f->a1 * cos(f->omega * t);
    if (f->a2 != 0.0) g += f->a2 * cos(2.0 * f->omega * t + f->psi);
    return g;
}

double gb_forcing_geff_rate(const gb_forcing *f, double t)
{
    double rate = 0.0;
    if (f->a1 != 0.0) rate -= f->a1 * f->omega * sin(f->omega * t);
    if (f->a2 != 0.0) rate -= 2.0 * f->a2 * f->omega * sin(2.0 * f->omega * t + f->psi);
    return rate;
}

void gb_forcing_geff_with_rate(const gb_forcing *f, double t, double *geff, double *rate)
{
    double g = f->g, r = 0.0, s, c;
    if (f->a1 != 0.0) {
        sincos(f->omega * t, &s, &c);
        g += f->a1 * c;
        r -= f->a1 * f->omega * s;
    }
    if (f->a2 != 0.0) {
        sincos(2.0 * f->omega * t + f->psi, &s, &c);
        g += f->a2 * c;
        r -= 2.0 * f->a2 * f->omega * s;
    }
    *geff = g, *rate = r;
}

double gb_forcing_period(const gb_forcing *f) { return 2.0 * M_PI / f->omega; }
double gb_forcing_step(const gb_forcing *f, size_t steps_per_period) { return gb_forcing_period(f) / (double)steps_per_period; }

/* A root of g_eff in [a, b] where the signs differ, by bisection to tolerance tol. */
static double bisect(const gb_forcing *f, double a, double b, double tol)
{
    double fa = gb_forcing_geff(f, a);
    while (b - a > tol) {
        const double m = 0.5 * (a + b), fm = gb_forcing_geff(f, m);
        if ((fm > 0.0) == (fa > 0.0)) a = m, fa = fm;
        else b = m;
    }
    return 0.5 * (a + b);
}

int gb_forcing_nonpositive_fraction(const gb_forcing *f, double *fraction, double *geff_min)
{
    int status = gb_forcing_validate(f);
    if (status) return status;
    enum { SAMPLES = 4096 };
    const double T = gb_forcing_period(f), dt = T / SAMPLES, tol = 1e-14 * T;
    double measure = 0.0, minimum = INFINITY, start = 0.0;
    int inside = gb_forcing_geff(f, 0.0) <= 0.0;
    for (int k = 1; k <= SAMPLES; k++) {
        const double t = k * dt, value = gb_forcing_geff(f, t);
        minimum = fmin(minimum, value);
        if ((value <= 0.0) != inside) {
            const double root = bisect(f, t - dt, t, tol);
            if (inside) measure += root - start;
            else start = root;
            inside = !inside;
        }
    }
    if (inside) measure += T - start;
    *fraction = measure / T;
    *geff_min = minimum;
    return GB_OK;
}
