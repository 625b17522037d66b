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

/* ---------------------------------------------------------------- a Gömböc as a pair system */

struct gb_lyapunov_body {
    gb_dynamics *dynamics[2];
    double y[2][GB_STATE_SIZE];
    gb_integrate_def integrate;
    double period, omega_scale;
};

int gb_lyapunov_body_create(const char *morphology, double beta, const gb_dynamics_def *dynamics,
                            const gb_integrate_def *integrate, const double R0[9], const double omega0[3],
                            double omega_scale, gb_lyapunov_body **out)
{
    *out = NULL;
    if (!(isfinite(omega_scale) && omega_scale > 0.0))
        return gb_error_set(GB_EDOM, "omega_scale = %g is out of range (allowed: finite, > 0)", omega_scale);
    gb_lyapunov_body *b = calloc(1, sizeof *b);
    if (!b) return gb_error_set(GB_ENOMEM, "out of memory for a Lyapunov pair");
    b->integrate = *integrate;
    b->period = 2.0 * M_PI / dynamics->forcing.omega;
    b->omega_scale = omega_scale;
    int status = GB_OK;
    for (int k = 0; k < 2 && !status; k++)
        status = gb_dynamics_start(morphology, beta, dynamics, R0, omega0, &b->dynamics[k], b->y[k]);
    if (status) {
        gb_lyapunov_body_free(b);
        return status;
    }
    *out = b;
    return GB_OK;
}

void gb_lyapunov_body_free(gb_lyapunov_body *body)
{
    if (!body) return;
    gb_dynamics_free(body->dynamics[0]);
    gb_dynamics_free(body->dynamics[1]);
    free(body);
}

gb_dynamics *gb_lyapunov_body_dynamics(gb_lyapunov_body *body) { return body->dynamics[0]; }
const double *gb_lyapunov_body_state(const gb_lyapunov_body *body) { return body->y[0]; }

/* Hamilton product a ⊗ b of quaternions (w, x, y, z). */
static void quaternion_product(const double a[4], const double b[4], double out[4])
{
    out[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3];
    out[1] = a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2];
    out[2] = a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1];
    out[3] = a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0];
}

static int body_advance(void *context, int which, double t, double interval)
{
    gb_lyapunov_body *b = context;
    gb_integrate_def def = b->integrate;
    def.periods = interval / b->period;
    gb_integrate_stats stats;
    return gb_integrate_run(b->dynamics[which], &def, t, b->y[which], NULL, NULL, &stats);
}

static int body_separation(void *context, double *e)
{
    gb_lyapunov_body *b = context;
    const double *qa = b->y[0] + GB_STATE_Q, *qb = b->y[1] + GB_STATE_Q;
    const double na = sqrt(qa[0] * qa[0] + qa[1] * qa[1] + qa[2] * qa[2] + qa[3] * qa[3]);
    const double conj[4] = {qa[0] / na, -qa[1] / na, -qa[2] / na, -qa[3] / na};
    double dq[4];
    quaternion_product(conj, qb, dq);
    const double sign = dq[0] < 0.0 ? -1.0 : 1.0; /* q and −q are the same attitude */
    const double v = sqrt(dq[1] * dq[1] + dq[2] * dq[2] + dq[3] * dq[3]);
    const double angle = 2.0 * atan2(v, sign * dq[0]);
    for (int k = 0; k < 3; k++) e[k] = v > 0.0 ? angle * sign * dq[k + 1] / v : 0.0;
    for (int k = 0; k < 3; k++) e[3 + k] = (b->y[1][GB_STATE_OMEGA + k] - b->y[0][GB_STATE_OMEGA + k]) / b->omega_scale;
    return GB_OK;
}

static int body_place(void *context, const double *e)
{
    gb_lyapunov_body *b = context;
    const double angle = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    const double s = angle > 0.0 ? sin(0.5 * angle) / angle : 0.5;
    const double dq[4] = {cos(0.5 * angle), s * e[0], s * e[1], s * e[2]};
    memcpy(b->y[1], b->y[0], sizeof b->y[1]);
    quaternion_product(b->y[0] + GB_STATE_Q, dq, b->y[1] + GB_STATE_Q);
    for (int k = 0; k < 3; k++) b->y[1][GB_STATE_OMEGA + k] = b->y[0][GB_STATE_OMEGA + k] + b->omega_scale * e[3 + k];
    gb_dynamics_adopt_contact(b->dynamics[1], b->dynamics[0]);
    return GB_OK;
}

gb_lyapunov_pair_system gb_lyapunov_body_pair(void)
{
    return (gb_lyapunov_pair_system){6, body_advance, body_separation, body_place};
}
