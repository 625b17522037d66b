#include "gb_lyapunov.h"

#include "gb_error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

gb_lyapunov_def gb_lyapunov_default_def(void)
{
    return (gb_lyapunov_def){.delta0 = 1e-7, .interval = 1.0, .intervals = 300, .transient = 0,
                             .warmup = GB_LYAPUNOV_CHOSEN, .batches = GB_LYAPUNOV_CHOSEN};
}

void gb_lyapunov_result_free(gb_lyapunov_result *result)
{
    if (!result) return;
    free(result->instantaneous);
    free(result->running);
    result->instantaneous = result->running = NULL;
}

/* MSER-5's warm-up of x[0..n) (a multiple of 5, at most n/2), and whether its minimum is interior. */
static size_t mser5(const double *x, size_t n, int *found)
{
    const size_t m = n / 5;
    *found = 0;
    if (m < 4) return 0; /* too short to tell a warm-up from noise */
    /* Suffix sums of the block means give every candidate's variance in one pass. */
    double *z = malloc(m * sizeof *z);
    if (!z) return 0;
    for (size_t j = 0; j < m; j++) {
        double s = 0.0;
        for (size_t i = 0; i < 5; i++) s += x[5 * j + i];
        z[j] = s / 5.0;
    }
    size_t best = 0;
    double best_value = INFINITY, s = 0.0, s2 = 0.0;
    for (size_t d = m; d-- > 0;) {
        s += z[d], s2 += z[d] * z[d];
        if (d > m / 2) continue;
        const double k = (double)(m - d), value = fmax(0.0, s2 - s * s / k) / (k * k);
        if (value <= best_value) best_value = value, best = d; /* ties: the shorter warm-up */
    }
    free(z);
    *found = best < m / 2;
    return 5 * best;
}

/* Mean of x over batch k of B equal batches of x[0..n). */
static double batch_mean(const double *x, size_t n, size_t B, size_t k)
{
    const size_t lo = k * n / B, hi = (k + 1) * n / B;
    double s = 0.0;
    for (size_t i = lo; i < hi; i++) s += x[i];
    return s / (double)(hi - lo);
}

/* Standard error and lag-1 autocorrelation of the B batch means of x[0..n). */
static void batch_statistics(const double *x, size_t n, size_t B, double *error_bar, double *correlation)
{
    double mean = 0.0;
    for (size_t k = 0; k < B; k++) mean += batch_mean(x, n, B, k);
    mean /= (double)B;
    double var = 0.0, lag = 0.0, previous = NAN;
    for (size_t k = 0; k < B; k++) {
        const double d = batch_mean(x, n, B, k) - mean;
        var += d * d;
        if (k) lag += d * previous;
        previous = d;
    }
    *error_bar = sqrt(var / (double)(B - 1) / (double)B);
    *correlation = var > 0.0 ? lag / var : 0.0;
}

int gb_lyapunov_statistics(const double *x, size_t n, const gb_lyapunov_def *def, gb_lyapunov_result *out, double *mean)
{
    double whole = 0.0;
    for (size_t i = 0; i < n; i++) whole += x[i];
    out->whole_record = n ? whole / (double)n : NAN;
    if (def->warmup == GB_LYAPUNOV_CHOSEN) {
        out->warmup = mser5(x, n, &out->warmup_found);
    } else {
        if (2 * def->warmup >= n) {
            return gb_error_set(GB_EDOM, "warm-up = %zu intervals is out of range (allowed: < half the record of %zu)",
                                def->warmup, n);
        }
        out->warmup = def->warmup, out->warmup_found = 1;
    }
    const double *kept = x + out->warmup;
    const size_t k = n - out->warmup;
    if (def->batches == GB_LYAPUNOV_CHOSEN) {
        const size_t fewest = k < 10 ? k : 10;
        out->batches = 0;
        for (size_t b = 1; k / b >= fewest && fewest >= 2; b *= 2) {
            batch_statistics(kept, k, k / b, &out->error_bar, &out->batch_correlation);
            out->batches = k / b;
            if (fabs(out->batch_correlation) <= 2.0 / sqrt((double)out->batches)) break;
        }
        if (out->batches < 2) {
            return gb_error_set(GB_EDOM, "a record of %zu kept intervals is too short for batch means (allowed: >= 2)", k);
        }
        if (!(fabs(out->batch_correlation) <= 2.0 / sqrt((double)out->batches)) && out->batches != fewest) {
            out->batches = fewest;
            batch_statistics(kept, k, fewest, &out->error_bar, &out->batch_correlation);
        }
    } else {
        if (def->batches < 2 || def->batches > k) {
            return gb_error_set(GB_EDOM, "batches = %zu is out of range (allowed: 2 ... the %zu intervals after the warm-up)",
                                def->batches, k);
        }
        out->batches = def->batches;
        batch_statistics(kept, k, out->batches, &out->error_bar, &out->batch_correlation);
    }
    out->batches_independent = fabs(out->batch_correlation) <= 2.0 / sqrt((double)out->batches);
    /* The running mean of the kept part over its last quarter. */
    double lo = INFINITY, hi = -INFINITY, running = 0.0;
    for (size_t i = 0; i < k; i++) {
        running += kept[i];
        if (4 * (i + 1) > 3 * k) {
            const double r = running / (double)(i + 1);
            lo = fmin(lo, r), hi = fmax(hi, r);
        }
    }
    out->late_drift = hi - lo;
    out->converged = out->warmup_found && out->batches_independent && out->late_drift <= 2.0 * out->error_bar;
    *mean = running / (double)k;
    return GB_OK;
}

static int check_def(const gb_lyapunov_def *def, int pair)
{
    if (pair && !(isfinite(def->delta0) && def->delta0 > 0.0 && def->delta0 < 1.0))
        return gb_error_set(GB_EDOM, "delta0 = %g is out of range (allowed: 0 < delta0 < 1)", def->delta0);
    if (!(isfinite(def->interval) && def->interval > 0.0))
        return gb_error_set(GB_EDOM, "renormalisation interval = %g is out of range (allowed: finite, > 0)", def->interval);
    if (def->intervals < 2)
        return gb_error_set(GB_EDOM, "intervals = %zu is out of range (allowed: >= 2)", def->intervals);
    if (def->warmup != GB_LYAPUNOV_CHOSEN && 2 * def->warmup >= def->intervals)
        return gb_error_set(GB_EDOM, "warm-up = %zu is out of range (allowed: < intervals / 2 = %zu / 2)", def->warmup,
                            def->intervals);
    const size_t kept = def->intervals - (def->warmup == GB_LYAPUNOV_CHOSEN ? 0 : def->warmup);
    if (def->batches != GB_LYAPUNOV_CHOSEN && (def->batches < 2 || def->batches > kept))
        return gb_error_set(GB_EDOM, "batches = %zu is out of range (allowed: 2 ... intervals - warm-up = %zu)",
                            def->batches, kept);
    return GB_OK;
}

static int start_result(const gb_lyapunov_def *def, gb_lyapunov_result *out)
{
    memset(out, 0, sizeof *out);
    out->intervals = def->intervals;
    out->interval = def->interval;
    out->instantaneous = malloc(def->intervals * sizeof *out->instantaneous);
    out->running = malloc(def->intervals * sizeof *out->running);
    if (!out->instantaneous || !out->running) {
        gb_lyapunov_result_free(out);
        return gb_error_set(GB_ENOMEM, "out of memory for a Lyapunov record of %zu intervals", def->intervals);
    }
    return GB_OK;
}

/* The running mean, the statistics, and the k exponents as the means of their kept parts; rates holds
 * the per-interval rate of exponent j at rates[j N + n] (row 0 is the instantaneous record). */
static int finish_result(const gb_lyapunov_def *def, size_t k, const double *rates, gb_lyapunov_result *out)
{
    double running = 0.0;
    for (size_t n = 0; n < def->intervals; n++) {
        running += out->instantaneous[n];
        out->running[n] = running / (double)(n + 1);
    }
    out->count = k;
    const int status = gb_lyapunov_statistics(out->instantaneous, def->intervals, def, out, &out->exponent[0]);
    if (status) return status;
    for (size_t j = 1; j < k; j++) {
        double s = 0.0;
        for (size_t n = out->warmup; n < def->intervals; n++) s += rates[j * def->intervals + n];
        out->exponent[j] = s / (double)(def->intervals - out->warmup);
    }
    out->lambda_max = out->exponent[0];
    return GB_OK;
}

static double norm(const double *e, size_t n)
{
    double s = 0.0;
    for (size_t i = 0; i < n; i++) s += e[i] * e[i];
    return sqrt(s);
}

int gb_lyapunov_pair(const gb_lyapunov_pair_system *system, void *context, const gb_lyapunov_def *def,
                     double t0, const double *direction, gb_lyapunov_result *out)
{
    memset(out, 0, sizeof *out);
    int status = check_def(def, 1);
    if (status) return status;
    const size_t n = system->dimension;
    double *e = malloc(n * sizeof *e);
    if (!e) return gb_error_set(GB_ENOMEM, "out of memory for a separation of dimension %zu", n);
    for (size_t k = 0; k < def->transient && !status; k++)
        status = system->advance(context, 0, t0 + (double)k * def->interval, def->interval);
    const double t = t0 + (double)def->transient * def->interval;
    if (!status) status = start_result(def, out);
    if (!status) {
        for (size_t i = 0; i < n; i++) e[i] = direction ? direction[i] : 1.0;
        const double size = norm(e, n);
        if (!(size > 0.0 && isfinite(size))) status = gb_error_set(GB_EDOM, "initial perturbation direction is zero or not finite");
        for (size_t i = 0; i < n && !status; i++) e[i] *= def->delta0 / size;
    }
    for (size_t k = 0; k < def->intervals && !status; k++) {
        const double tk = t + (double)k * def->interval;
        status = system->place(context, e);
        if (!status) status = system->advance(context, 0, tk, def->interval);
        if (!status) status = system->advance(context, 1, tk, def->interval);
        if (!status) status = system->separation(context, e);
        if (status) break;
        const double delta = norm(e, n);
        if (!(delta > 0.0 && isfinite(delta))) {
            status = gb_error_set(GB_ENUMERIC, "Lyapunov pair: separation %g after interval %zu (t = %g) is zero or not "
                                  "finite", delta, k + 1, tk + def->interval);
            break;
        }
        out->instantaneous[k] = log(delta / def->delta0) / def->interval; /* eq 77, one term */
        for (size_t i = 0; i < n; i++) e[i] *= def->delta0 / delta; /* back to δ₀ along the separation */
    }
    free(e);
    if (status) {
        gb_lyapunov_result_free(out);
        return status;
    }
    out->delta0 = def->delta0;
    status = finish_result(def, 1, out->instantaneous, out);
    if (status) gb_lyapunov_result_free(out);
    return status;
}

int gb_lyapunov_tangent(const gb_lyapunov_tangent_system *system, void *context, const gb_lyapunov_def *def,
                        double t0, size_t k, gb_lyapunov_result *out)
{
    memset(out, 0, sizeof *out);
    int status = check_def(def, 0);
    if (status) return status;
    const size_t n = system->dimension;
    if (k < 1 || k > n || k > GB_LYAPUNOV_MAX_EXPONENTS)
        return gb_error_set(GB_EDOM, "tangent vectors = %zu is out of range (allowed: 1 ... min(%zu, %d))", k, n,
                            GB_LYAPUNOV_MAX_EXPONENTS);
    double *v = calloc(k * n, sizeof *v);
    if (!v) return gb_error_set(GB_ENOMEM, "out of memory for %zu tangent vectors", k);
    for (size_t j = 0; j < k; j++) v[j * n + j] = 1.0;
    for (size_t s = 0; s < def->transient && !status; s++)
        status = system->advance(context, t0 + (double)s * def->interval, def->interval);
    const double t = t0 + (double)def->transient * def->interval;
    if (!status) status = start_result(def, out);
    double *rates = status ? NULL : malloc(k * def->intervals * sizeof *rates);
    if (!status && !rates) status = gb_error_set(GB_ENOMEM, "out of memory for %zu records of %zu intervals", k, def->intervals);
    for (size_t s = 0; s < def->intervals && !status; s++) {
        const double ts = t + (double)s * def->interval;
        status = system->advance_tangent(context, ts, def->interval, k, v);
        if (status) break;
        /* Modified Gram–Schmidt: the j-th norm after removing the earlier directions is the growth
         * of the j-dimensional volume over that of the (j−1)-dimensional one. */
        for (size_t j = 0; j < k && !status; j++) {
            double *vj = v + j * n;
            for (size_t i = 0; i < j; i++) {
                const double *vi = v + i * n;
                double dot = 0.0;
                for (size_t m = 0; m < n; m++) dot += vi[m] * vj[m];
                for (size_t m = 0; m < n; m++) vj[m] -= dot * vi[m];
            }
            const double size = norm(vj, n);
            if (!(size > 0.0 && isfinite(size))) {
                status = gb_error_set(GB_ENUMERIC, "Lyapunov tangent: vector %zu has norm %g after interval %zu (t = %g)",
                                      j + 1, size, s + 1, ts + def->interval);
                break;
            }
            for (size_t m = 0; m < n; m++) vj[m] /= size;
            rates[j * def->intervals + s] = log(size) / def->interval;
            if (j == 0) out->instantaneous[s] = rates[s];
        }
    }
    free(v);
    if (!status) status = finish_result(def, k, rates, out);
    free(rates);
    if (status) gb_lyapunov_result_free(out);
    return status;
}

size_t gb_lyapunov_windows(const double *lambda, size_t n, size_t per_window, double *mean)
{
    if (per_window == 0 || per_window > n) return 0;
    const size_t count = n / per_window;
    for (size_t w = 0; w < count; w++) {
        double sum = 0.0;
        for (size_t k = w * per_window; k < (w + 1) * per_window; k++) sum += lambda[k];
        mean[w] = sum / (double)per_window;
    }
    return count;
}

double gb_lyapunov_lifetime(const double *mean, size_t count, double per_window)
{
    size_t last = 0; /* windows up to and including the last chaotic one */
    for (size_t w = 0; w < count; w++)
        if (mean[w] > GB_LYAPUNOV_CHAOTIC) last = w + 1;
    return count && last == count ? INFINITY : (double)last * per_window;
}
