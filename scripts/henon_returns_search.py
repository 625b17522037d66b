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

--partial adds strips that return across part of R: W is cut at the middles of the gaps between the strips found,
and for m = 1, ..., 14 and each run of those pieces T (widest first, W itself left out) a strip is the shortest run of
usable points (now: their images that land in T lie inside 0.9 S) from below T to above it, taken out as before. Each
strip's image then covers the strips inside its reach T; the bound is ln x, x the root of rho(M(x)) = 1 with
M(x)_ij = x^-m_i where strip j lies in strip i's reach (`gomboc prove` proves it as M(x0) v >= v for a positive v).

Nothing here is a proof. Usage: python3 scripts/henon_returns_search.py [--scan | --partial]
(a few seconds; --partial: about 20 seconds; --scan: about two minutes; numpy)
"""
import math
import sys

import numpy as np

from henon_horseshoe_search import A, B, FRAME, INVERSE, ORIGIN

BEYOND, INSIDE, HEIGHTS, RETURNS, SAMPLES = 1e-3, 0.9, 9, 18, 400001
# the partial returns' longest: at 18 iterates the 9 heights miss where an edge lands (the two strips found there were
# not proved), and 15 ... 17 find none
PARTIAL_RETURNS = 14
CHOSEN = (0.018, -0.42, 0.3, 0.14, 0.05)  # S, W's ends, K, V: the scan's best
SCAN_S, SCAN_K, SCAN_V = (0.015, 0.018, 0.025), (0.0, 0.1, 0.14, 0.2), (0.0, 0.05)
SCAN_LOW, SCAN_HIGH = (-0.45, -0.42), (0.2, 0.3)


def band_points(strip, low, high, bend, vertex):
    """W's SAMPLES points across, HEIGHTS heights along each, in the frame's plane coordinates: u, x, y."""
    u = np.linspace(low, high, SAMPLES)
    heights = np.linspace(-strip, strip, HEIGHTS)[:, None] + bend * (u[None, :] - vertex) ** 2
    x = ORIGIN[0] + FRAME[0, 0] * u[None, :] + FRAME[0, 1] * heights
    y = ORIGIN[1] + FRAME[1, 0] * u[None, :] + FRAME[1, 1] * heights
    return u, x, y


def iterate(x, y, bend, vertex):
    """One iterate of H, and the image in the band's chart: x, y, u across, s along."""
    x, y = 1 - A * x * x + y, B * x
    dx, dy = x - ORIGIN[0], y - ORIGIN[1]
    iu = INVERSE[0, 0] * dx + INVERSE[0, 1] * dy
    return x, y, iu, INVERSE[1, 0] * dx + INVERSE[1, 1] * dy - bend * (iu - vertex) ** 2


def crossings(usable, label, taken):
    """The shortest runs of usable points from a label to the other (indices a, b), each taken out as it is found."""
    run = np.cumsum(~usable)
    index = np.nonzero(usable & (label != 0))[0]
    if len(index) < 2:
        return
    crossing = (run[index[1:]] == run[index[:-1]]) & (label[index[1:]] != label[index[:-1]])
    last = -1
    for k in np.nonzero(crossing)[0]:
        a, b = index[k], index[k + 1]
        if a == last:
            continue
        taken[max(a - 1, 0):b + 2] = True
        last = b
        yield a, b


def search(strip, low, high, bend=0.0, vertex=0.0):
    """The strips (u_lo, u_hi, m) for R = [low, high] x [-strip, strip] in the chart of the band's centre line
    s = bend (u - vertex)^2, shortest returns first."""
    u, x, y = band_points(strip, low, high, bend, vertex)
    taken = np.zeros(SAMPLES, bool)
    strips = []
    with np.errstate(all="ignore"):
        for m in range(1, RETURNS + 1):
            x, y, iu, is_ = iterate(x, y, bend, vertex)
            in_window = (iu >= low - BEYOND) & (iu <= high + BEYOND)
            usable = ~np.any(in_window & ~(np.abs(is_) < INSIDE * strip), axis=0) & ~taken
            label = np.where(iu.max(axis=0) < low - BEYOND, -1, np.where(iu.min(axis=0) > high + BEYOND, 1, 0))
            strips += [(u[a], u[b], m) for a, b in crossings(usable, label, taken)]
    return strips


def search_partial(full, strip, low, high, bend=0.0, vertex=0.0):
    """The strips (u_lo, u_hi, m, t_lo, t_hi) returning across part [t_lo, t_hi] of R, beside the strips `full`."""
    u, x, y = band_points(strip, low, high, bend, vertex)
    taken = np.zeros(SAMPLES, bool)
    for a, b, _ in full:
        taken[max(np.searchsorted(u, a) - 1, 0):np.searchsorted(u, b) + 2] = True
    ordered = sorted(full)
    cuts = np.array([low] + [0.5 * (ordered[k][1] + ordered[k + 1][0]) for k in range(len(ordered) - 1)] + [high])
    cells = len(cuts) - 1
    reaches = sorted(((p, q) for p in range(cells + 1) for q in range(p + 1, cells + 1) if (p, q) != (0, cells)),
                     key=lambda t: -(cuts[t[1]] - cuts[t[0]]))
    found = []

    def cell_of(v):  # -1 below W, `cells` above it
        return np.searchsorted(cuts, np.nan_to_num(v, nan=1e9, posinf=1e9, neginf=-1e9), side="right") - 1

    with np.errstate(all="ignore"):
        for m in range(1, PARTIAL_RETURNS + 1):
            x, y, iu, is_ = iterate(x, y, bend, vertex)
            bad = ~(np.abs(is_) < INSIDE * strip) | ~np.isfinite(iu)
            hits = np.zeros(SAMPLES, np.int64)  # a bit for each piece of W an image outside 0.9 S lands in (by BEYOND)
            for side in (-BEYOND, BEYOND):
                c = cell_of(iu + side)
                hit = bad & (c >= 0) & (c < cells)
                hits |= np.bitwise_or.reduce(np.where(hit, np.left_shift(1, np.where(hit, c, 0)), 0), axis=0)
            top, bottom = cell_of(iu.max(axis=0) + BEYOND), cell_of(iu.min(axis=0) - BEYOND)
            for p, q in reaches:
                usable = ((hits & (((1 << q) - 1) ^ ((1 << p) - 1))) == 0) & ~taken
                label = np.where(top < p, -1, np.where(bottom >= q, 1, 0))
                found += [(u[a], u[b], m, cuts[p], cuts[q]) for a, b in crossings(usable, label, taken)]
    return found


def graph_bound(strips):
    """ln x, x the root of rho(M(x)) = 1, M(x)_ij = x^-m_i where strip j = (lo, hi, ...) lies in strip i's reach."""
    reach = np.array([[float(o[0] >= s[3] and o[1] <= s[4]) for o in strips] for s in strips])
    times = np.array([s[2] for s in strips], float)

    def rho(h):
        return max(abs(np.linalg.eigvals(np.exp(-h * times)[:, None] * reach)))
    lo, hi = 0.0, 3.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if rho(mid) >= 1 else (lo, mid)
    return lo


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
    if "--partial" in sys.argv:
        partial = search_partial(strips, strip, low, high, bend, vertex)
        h = graph_bound([(lo, hi, m, low, high) for lo, hi, m in strips] + partial)
        print(f"and {len(partial)} strips returning across part of W (u, m, reach): h_top >= {h:.6f} if proved")
        for lo, hi, m, t_lo, t_hi in partial:
            print(f"  {{{lo:.9f}, {hi:.9f}, {m}, {t_lo:.9f}, {t_hi:.9f}}},")


if __name__ == "__main__":
    main()
