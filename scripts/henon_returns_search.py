#!/usr/bin/python3
"""The search, on floats, behind `gomboc prove`'s renewal bound for the classical Hénon map
(gb_proof_returns_henon_classical).

Hénon's map H(x, y) = (1 - 1.4 x^2 + y, 0.3 x) is read in the frame of scripts/henon_horseshoe_search.py and then in the
chart (u, s - K (u - V)^2), which straightens a band bent along the parabola s = K (u - V)^2 (the attractor's layers
near the fixed point bend so). R = W x [-S, S] in the chart is a band along the fixed point's unstable direction. For
m = 1, 2, ... a point u of W is usable when the images of its segment {u} x [-S, S] (9 heights) that land in W across
lie inside 0.9 S along; a strip is the shortest run of
usable points from one whose images all land below W (by BEYOND) to one whose images all land above it (or back): its
m-th image runs across R. Strips already found are taken out before the next m, so the strips are disjoint and each
has one return time. Their return times m_i give h_top >= ln x, x the root above 1 of sum_i x^-m_i = 1, once
`gomboc prove` has proved the returns on Arb's balls. The scan over S, K, V and W keeps the largest root.

Nothing here is a proof. Usage: python3 scripts/henon_returns_search.py [--scan]
(a few seconds; --scan: about two minutes; numpy)
"""
import math
import sys

import numpy as np

from henon_horseshoe_search import A, B, FRAME, INVERSE, ORIGIN

BEYOND, INSIDE, HEIGHTS, RETURNS, SAMPLES = 1e-3, 0.9, 9, 18, 400001
CHOSEN = (0.018, -0.42, 0.3, 0.14, 0.05)  # S, W's ends, K, V: the scan's best
SCAN_S, SCAN_K, SCAN_V = (0.015, 0.018, 0.025), (0.0, 0.1, 0.14, 0.2), (0.0, 0.05)
SCAN_LOW, SCAN_HIGH = (-0.45, -0.42), (0.2, 0.3)


def search(strip, low, high, bend=0.0, vertex=0.0):
    """The strips (u_lo, u_hi, m) for R = [low, high] x [-strip, strip] in the chart of the band's centre line
    s = bend (u - vertex)^2, shortest returns first."""
    u = np.linspace(low, high, SAMPLES)
    heights = np.linspace(-strip, strip, HEIGHTS)[:, None] + bend * (u[None, :] - vertex) ** 2
    x = ORIGIN[0] + FRAME[0, 0] * u[None, :] + FRAME[0, 1] * heights
    y = ORIGIN[1] + FRAME[1, 0] * u[None, :] + FRAME[1, 1] * heights
    taken = np.zeros(SAMPLES, bool)
    strips = []
    with np.errstate(all="ignore"):
        for m in range(1, RETURNS + 1):
            x, y = 1 - A * x * x + y, B * x
            dx, dy = x - ORIGIN[0], y - ORIGIN[1]
            iu = INVERSE[0, 0] * dx + INVERSE[0, 1] * dy
            is_ = INVERSE[1, 0] * dx + INVERSE[1, 1] * dy - bend * (iu - vertex) ** 2
            in_window = (iu >= low - BEYOND) & (iu <= high + BEYOND)
            usable = ~np.any(in_window & ~(np.abs(is_) < INSIDE * strip), axis=0) & ~taken
            label = np.where(iu.max(axis=0) < low - BEYOND, -1, np.where(iu.min(axis=0) > high + BEYOND, 1, 0))
            run = np.cumsum(~usable)
            index = np.nonzero(usable & (label != 0))[0]
            if len(index) < 2:
                continue
            crossing = (run[index[1:]] == run[index[:-1]]) & (label[index[1:]] != label[index[:-1]])
            last = -1
            for k in np.nonzero(crossing)[0]:
                a, b = index[k], index[k + 1]
                if a == last:
                    continue
                strips.append((u[a], u[b], m))
                taken[max(a - 1, 0):b + 2] = True
                last = b
    return strips


def bound(strips):
    """ln x, x the root above 1 of sum x^-m = 1 (0 when there is none)."""
    def excess(h):
        return sum(math.exp(-h * m) for _, _, m in strips) - 1.0
    lo, hi = 0.0, 3.0
    if not strips or excess(1e-12) <= 0:
        return 0.0
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if excess(mid) >= 0 else (lo, mid)
    return lo


def main():
    best = (bound(search(*CHOSEN)),) + CHOSEN
    if "--scan" in sys.argv:
        for strip in SCAN_S:
            for bend in SCAN_K:
                for vertex in SCAN_V:
                    for low in SCAN_LOW:
                        for high in SCAN_HIGH:
                            found = bound(search(strip, low, high, bend, vertex))
                            if found > best[0]:
                                best = (found, strip, low, high, bend, vertex)
    h, strip, low, high, bend, vertex = best
    strips = search(strip, low, high, bend, vertex)
    print(f"S = {strip:g}, W = [{low:g}, {high:g}], centre line s = {bend:g} (u - {vertex:g})^2: {len(strips)} strips, "
          f"h_top >= {h:.6f} if proved")
    for lo, hi, m in sorted(strips):
        print(f"  {{{lo:.9f}, {hi:.9f}, {m}}},")


if __name__ == "__main__":
    main()
