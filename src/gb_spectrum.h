/* gb_spectrum — the power spectrum of a sampled signal (paper Fig 8: ω_x against frequency in Hz).
 *
 * The one-sided power spectral density of x[0..n) sampled every dt seconds, by GSL's mixed-radix real
 * FFT (any n): the mean is removed (detrend), the window w applied, and
 *     P_k = c_k |X_k|² / (f_s Σ w²),  f_k = k f_s / n [Hz], k = 0 … ⌊n/2⌋,
 * with c_k = 2 except at k = 0 and, for even n, the Nyquist bin (c_k = 1): the density whose sum
 * times Δf = f_s/n is the mean square of the windowed signal over the mean square of the window
 * (Parseval) — the same convention as scipy.signal.periodogram(scaling='density'). */
#ifndef GB_SPECTRUM_H
#define GB_SPECTRUM_H

#include "gb_export.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum gb_spectrum_window { GB_SPECTRUM_WINDOW_RECTANGULAR = 0, GB_SPECTRUM_WINDOW_HANN = 1 } gb_spectrum_window;

GB_API const char *gb_spectrum_window_name(gb_spectrum_window window);
GB_API int gb_spectrum_window_parse(const char *name, gb_spectrum_window *window);

typedef struct gb_spectrum {
    size_t count;        /* ⌊n/2⌋ + 1 bins */
    double *frequency;   /* [Hz] */
    double *power;       /* [units² / Hz] */
    double df;           /* bin width f_s / n [Hz] */
} gb_spectrum;

/* GB_EDOM for n < 2 or dt ≤ 0; GB_ENOMEM; GB_ENUMERIC when GSL's FFT fails. */
GB_API int gb_spectrum_compute(const double *x, size_t n, double dt, gb_spectrum_window window, gb_spectrum *out);
GB_API void gb_spectrum_free(gb_spectrum *spectrum);

/* The bin of largest power among k ≥ 1 (the mean was removed). */
GB_API size_t gb_spectrum_peak(const gb_spectrum *spectrum);

#ifdef __cplusplus
}
#endif

#endif
