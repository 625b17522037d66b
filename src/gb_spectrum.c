#include "gb_spectrum.h"

#include "gb_error.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_fft_real.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const window_names[] = {"rectangular", "hann"};

const char *gb_spectrum_window_name(gb_spectrum_window w) { return (unsigned)w < 2 ? window_names[w] : NULL; }

int gb_spectrum_window_parse(const char *name, gb_spectrum_window *window)
{
    int k = 0;
    const int status = gb_error_parse_name(name, window_names, 2, "window", &k);
    if (!status) *window = (gb_spectrum_window)k;
    return status;
}

void gb_spectrum_free(gb_spectrum *s)
{
    free(s->frequency);
    free(s->power);
    memset(s, 0, sizeof *s);
}

int gb_spectrum_compute(const double *x, size_t n, double dt, gb_spectrum_window window, gb_spectrum *out)
{
    memset(out, 0, sizeof *out);
    if (n < 2) return gb_error_set(GB_EDOM, "a spectrum needs at least 2 samples (got %zu)", n);
    if (!(isfinite(dt) && dt > 0.0)) return gb_error_set(GB_EDOM, "sample spacing dt = %g is out of range (allowed: > 0)", dt);
    if (!gb_spectrum_window_name(window)) return gb_error_set(GB_EINVAL, "window %d is unknown", (int)window);
    double *data = malloc(n * sizeof *data);
    const size_t bins = n / 2 + 1;
    out->frequency = malloc(bins * sizeof *out->frequency);
    out->power = malloc(bins * sizeof *out->power);
    gsl_fft_real_wavetable *table = gsl_fft_real_wavetable_alloc(n);
    gsl_fft_real_workspace *work = gsl_fft_real_workspace_alloc(n);
    int status = data && out->frequency && out->power && table && work
                     ? GB_OK
                     : gb_error_set(GB_ENOMEM, "out of memory for a spectrum of %zu samples", n);
    if (!status) {
        double mean = 0.0, w2 = 0.0;
        for (size_t i = 0; i < n; i++) mean += x[i];
        mean /= (double)n;
        for (size_t i = 0; i < n; i++) {
            /* The periodic Hann window (scipy's default for spectra): w_i = sin²(π i / n). */
            const double w = window == GB_SPECTRUM_WINDOW_HANN ? 0.5 - 0.5 * cos(2.0 * M_PI * (double)i / (double)n) : 1.0;
            data[i] = w * (x[i] - mean);
            w2 += w * w;
        }
        const int gsl_status = gsl_fft_real_transform(data, 1, n, table, work);
        if (gsl_status != GSL_SUCCESS)
            status = gb_error_set(GB_ENUMERIC, "GSL real FFT of %zu samples failed: %s", n, gsl_strerror(gsl_status));
        const double fs = 1.0 / dt, scale = 1.0 / (fs * w2);
        out->count = bins;
        out->df = fs / (double)n;
        /* Half-complex order: data[0] = X_0, then (Re X_k, Im X_k) at (2k − 1, 2k), and X_{n/2} last for even n. */
        for (size_t k = 0; !status && k < bins; k++) {
            double re, im = 0.0;
            if (k == 0) re = data[0];
            else if (2 * k == n) re = data[n - 1];
            else re = data[2 * k - 1], im = data[2 * k];
            const double c = (k == 0 || 2 * k == n) ? 1.0 : 2.0;
            out->frequency[k] = (double)k * out->df;
            out->power[k] = c * scale * (re * re + im * im);
        }
    }
    free(data);
    if (table) gsl_fft_real_wavetable_free(table);
    if (work) gsl_fft_real_workspace_free(work);
    if (status) gb_spectrum_free(out);
    return status;
}

size_t gb_spectrum_peak(const gb_spectrum *s)
{
    size_t best = s->count > 1 ? 1 : 0;
    for (size_t k = 2; k < s->count; k++)
        if (s->power[k] > s->power[best]) best = k;
    return best;
}
