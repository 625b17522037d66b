#include "gb_lyapunov.h"

#include "gb_error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

gb_lyapunov_def gb_lyapunov_default_def(void)
{
    return (gb_lyapunov_def){.delta0 = 1e-7, .interval = 1.0, .intervals = 300, .transient = 0, .batches = 10};
}

void gb_lyapunov_result_free(gb_lyapunov_result *result)
{
    if (!result) return;
    free(result->instantaneous);
    free(result->running);
    result->instantaneous = result->running = NULL;
}

void gb_lyapunov_statistics(const double *x, size_t n, size_t batches, double *mean, double *error_bar,
                            double *late_drift)
{
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) sum += x[i];
    *mean = n ? sum / (double)n : NAN;
    /* Batch b holds x[b n / B, (b + 1) n / B); the spread of the batch means gives the error. */
    double s = 0.0, s2 = 0.0;
    for (size_t b = 0; b < batches; b++) {
        const size_t lo = b * n / batches, hi = (b + 1) * n / batches;
        double batch = 0.0;
        for (size_t i = lo; i < hi; i++) batch += x[i];
        batch /= (double)(hi - lo);
        s += batch;
        s2 += batch * batch;
    }
    const double bm = s / (double)batches;
    const double var = fmax(0.0, (s2 - (double)batches * bm * bm) / (double)(batches - 1));
    *error_bar = sqrt(var / (double)batches);
    /* The running mean over the last quarter of the record. */
    double lo = INFINITY, hi = -INFINITY, running = 0.0;
    for (size_t i = 0; i < n; i++) {
        running += x[i];
        if (4 * (i + 1) > 3 * n) {
            const double r = running / (double)(i + 1);
            lo = fmin(lo, r), hi = fmax(hi, r);
        }
    }
    *late_drift = hi - lo;
}

static int check_def(const gb_lyapunov_def *def, int pair)
{
    if (pair && !(isfinite(def->delta0) && def->delta0 > 0.0 && def->delta0 < 1.0))
        return gb_error_set(GB_EDOM, "delta0 = %g is out of range (allowed: 0 < delta0 < 1)", def->delta0);
    if (!(isfinite(def->interval) && def->interval > 0.0))
        return gb_error_set(GB_EDOM, "renormalisation interval = %g is out of range (allowed: finite, > 0)", def->interval);
    if (def->intervals < 2)
        return gb_error_set(GB_EDOM, "intervals = %zu is out of range (allowed: >= 2)", def->intervals);
    if (def->batches < 2 || def->batches > def->intervals)
        return gb_error_set(GB_EDOM, "batches = %zu is out of range (allowed: 2 ... intervals = %zu)", def->batches,
                            def->intervals);
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

static void finish_result(const gb_lyapunov_def *def, gb_lyapunov_result *out)
{
    double running = 0.0;
    for (size_t n = 0; n < def->intervals; n++) {
        running += out->instantaneous[n];
        out->running[n] = running / (double)(n + 1);
    }
    double mean;
    gb_lyapunov_statistics(out->instantaneous, def->intervals, def->batches, &mean, &out->error_bar, &out->late_drift);
    out->lambda_max = out->exponent[0];
    out->converged = out->late_drift <= 2.0 * out->error_bar;
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
    double sum = 0.0;
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
        sum += out->instantaneous[k];
        for (size_t i = 0; i < n; i++) e[i] *= def->delta0 / delta; /* back to δ₀ along the separation */
    }
    free(e);
    if (status) {
        gb_lyapunov_result_free(out);
        return status;
    }
    out->count = 1;
    out->exponent[0] = sum / (double)def->intervals;
    out->delta0 = def->delta0;
    finish_result(def, out);
    return GB_OK;
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
    double sums[GB_LYAPUNOV_MAX_EXPONENTS] = {0};
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
            const double rate = log(size) / def->interval;
            sums[j] += rate;
            if (j == 0) out->instantaneous[s] = rate;
        }
    }
    free(v);
    if (status) {
        gb_lyapunov_result_free(out);
        return status;
    }
    out->count = k;
    for (size_t j = 0; j < k; j++) out->exponent[j] = sums[j] / (double)def->intervals;
    finish_result(def, out);
    return GB_OK;
}
