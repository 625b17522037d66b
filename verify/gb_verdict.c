/* gb_verdict — the three-way rules of the findings (see gb_verdict.h). */
#include "gb_verdict.h"

#include <math.h>

const char *gb_verdict_name(gb_verdict verdict)
{
    return verdict == GB_VERDICT_HOLDS ? "holds" : verdict == GB_VERDICT_FAILS ? "fails" : "undecided";
}

gb_verdict gb_verdict_above(double x, double u, double threshold)
{
    if (!(isfinite(x) && isfinite(u) && u >= 0.0 && isfinite(threshold))) return GB_VERDICT_UNDECIDED;
    if (x - u > threshold) return GB_VERDICT_HOLDS;
    if (x + u < threshold) return GB_VERDICT_FAILS;
    return GB_VERDICT_UNDECIDED;
}

gb_verdict gb_verdict_above_at(double x, double u, double threshold, double resolution)
{
    if (!(isfinite(x) && isfinite(u) && u >= 0.0 && isfinite(threshold) && isfinite(resolution) && resolution >= threshold))
        return GB_VERDICT_UNDECIDED;
    if (x - u > threshold) return GB_VERDICT_HOLDS;
    if (x + u < resolution) return GB_VERDICT_FAILS;
    return GB_VERDICT_UNDECIDED;
}

gb_verdict gb_verdict_equivalent(double delta, double sigma, double k, double margin)
{
    if (!(isfinite(delta) && isfinite(sigma) && sigma >= 0.0 && isfinite(k) && k >= 0.0 && isfinite(margin) && margin > 0.0))
        return GB_VERDICT_UNDECIDED;
    if (fabs(delta) + k * sigma <= margin) return GB_VERDICT_HOLDS;
    if (fabs(delta) - k * sigma > margin) return GB_VERDICT_FAILS;
    return GB_VERDICT_UNDECIDED;
}

int gb_verdict_fit_change(const double *x, const double *y, const double *sigma, size_t n, double *change,
                          double *change_error)
{
    if (n < 2) return 1;
    double S = 0, Sx = 0, Sy = 0, Sxx = 0, Sxy = 0, lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        if (!(isfinite(x[i]) && isfinite(y[i]) && isfinite(sigma[i]) && sigma[i] > 0.0)) return 1;
        const double w = 1.0 / (sigma[i] * sigma[i]);
        S += w, Sx += w * x[i], Sy += w * y[i], Sxx += w * x[i] * x[i], Sxy += w * x[i] * y[i];
        lo = fmin(lo, x[i]), hi = fmax(hi, x[i]);
    }
    const double det = S * Sxx - Sx * Sx;
    if (!(det > 0.0) || !(hi > lo)) return 1;
    const double slope = (S * Sxy - Sx * Sy) / det, slope_error = sqrt(S / det);
    *change = slope * (hi - lo);
    *change_error = slope_error * (hi - lo);
    return 0;
}

gb_verdict gb_verdict_order(const double e[3], double expected)
{
    for (int k = 0; k < 3; k++)
        if (!(isfinite(e[k]) && e[k] > 0.0)) return GB_VERDICT_UNDECIDED;
    if (!(e[0] > e[1] && e[1] > e[2])) return GB_VERDICT_UNDECIDED; /* no order to speak of */
    const double order = log2(e[1] / e[2]);
    if (order >= expected - 0.5) return GB_VERDICT_HOLDS;
    if (order <= expected - 1.0) return GB_VERDICT_FAILS;
    return GB_VERDICT_UNDECIDED;
}

gb_verdict gb_verdict_conserved(double first, double last, double floor)
{
    if (!(isfinite(first) && isfinite(last) && isfinite(floor) && floor >= 0.0)) return GB_VERDICT_UNDECIDED;
    if (last <= 10.0 * floor) return GB_VERDICT_HOLDS;
    if (last > 0.5 * first && last > 1000.0 * floor) return GB_VERDICT_FAILS;
    return GB_VERDICT_UNDECIDED;
}

gb_verdict gb_verdict_counts(const size_t a[2], const size_t b[2], size_t want_a, size_t want_b)
{
    if (a[0] != a[1] || b[0] != b[1]) return GB_VERDICT_UNDECIDED;
    return a[0] == want_a && b[0] == want_b ? GB_VERDICT_HOLDS : GB_VERDICT_FAILS;
}

gb_verdict gb_verdict_pivot(double ratio_baseline, double ratio_unforced, double ratio_convex, double worst)
{
    if (!(isfinite(ratio_baseline) && isfinite(ratio_unforced) && isfinite(ratio_convex) && isfinite(worst)))
        return GB_VERDICT_UNDECIDED;
    if (worst <= 0.15) return GB_VERDICT_FAILS;
    if (ratio_unforced < 0.5 && ratio_convex < 0.5 && ratio_baseline >= 0.85) return GB_VERDICT_HOLDS;
    return GB_VERDICT_UNDECIDED;
}
