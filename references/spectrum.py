#!/usr/bin/python3
"""Reference power spectra for gb_spectrum (paper Fig 8): scipy.signal.periodogram.

Each case is a deterministic signal, stored with its samples so that the C side reads the same numbers:
two sinusoids (one on a bin, one between bins) plus an offset and a slowly varying term, and a
logistic-map sequence (broadband); lengths even, odd and prime, so that GSL's mixed-radix FFT is
exercised beyond powers of two. scipy computes the one-sided density with the mean removed
(detrend='constant'), for the rectangular ('boxcar') and the periodic Hann window.
Run by `make references`; the output (JSON, on stdout) is committed as references/spectrum.json.
"""
import math
import os
import sys

import numpy
from scipy import signal

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from provenance import emit, versions  # noqa: E402


def sinusoids(n, dt):
    t = numpy.arange(n) * dt
    f1 = 8.0 / (n * dt)          # exactly on bin 8
    f2 = 21.37 / (n * dt)        # between bins
    return 0.7 + 1.5 * numpy.sin(2 * math.pi * f1 * t + 0.3) + 0.4 * numpy.cos(2 * math.pi * f2 * t) + 0.05 * t


def logistic(n):
    x = numpy.empty(n)
    v = 0.3141592653589793
    for i in range(n):
        v = 4.0 * v * (1.0 - v)
        x[i] = v
    return x


def main():
    cases = []
    for name, n, dt, make in (("sinusoids, n = 256", 256, 0.01, lambda n, dt: sinusoids(n, dt)),
                              ("sinusoids, n = 1000", 1000, 0.002, lambda n, dt: sinusoids(n, dt)),
                              ("sinusoids, n = 499 (odd, prime)", 499, 0.05, lambda n, dt: sinusoids(n, dt)),
                              ("logistic map, n = 360", 360, 1.0 / 160.0, lambda n, dt: logistic(n))):
        x = make(n, dt)
        for window, scipy_window in (("rectangular", "boxcar"), ("hann", "hann")):
            f, p = signal.periodogram(x, fs=1.0 / dt, window=scipy_window, detrend="constant", scaling="density",
                                      return_onesided=True)
            cases.append({"name": name, "window": window, "dt": dt, "signal": x.tolist(), "frequency": f.tolist(),
                          "power": p.tolist()})
    emit({"provenance": {"script": "references/spectrum.py",
                         "method": "scipy.signal.periodogram(x, fs=1/dt, window=boxcar|hann (periodic), "
                                   "detrend='constant', scaling='density', return_onesided=True)",
                         **versions()},
          "cases": cases}, indent=None)


if __name__ == "__main__":
    main()
