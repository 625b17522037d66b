#!/usr/bin/python3
"""The search, on floats, behind `gomboc prove`'s classical Hénon horseshoe (gb_proof_cover_henon_classical).

Hénon's map H(x, y) = (1 - 1.4 x^2 + y, 0.3 x) is read in the affine frame (x, y) = o + F (u, s) with the rationals
gb_proof_cover_henon_classical uses. For the 7th iterate, candidate h-sets are U x [-S, S] with U a piece of the frame's
u-axis. A window [L, R] is scanned along u (step 1e-5): a point is usable when its images at 17 heights s in [-S, S] stay
inside 0.8 S along; the pieces are the shortest runs of usable points whose two ends' images (at every height) lie beyond
the window by 0.005, one below L and one above R. Every such piece crosses every other, so k pieces give a full
horseshoe on k symbols and h_top >= ln k / 7. The scan over S, L and R keeps the most pieces (then the widest S).

Nothing here is a proof: `gomboc prove` proves the relations of the sets this prints on Arb's balls.
Usage: python3 scripts/henon_horseshoe_search.py   (about 10 s; numpy)
"""
import numpy as np

A, B = 1.4, 0.3
ORIGIN = np.array([3157 / 5000, 947 / 5000])
FRAME = np.array([[-1.0, -13 / 25], [39 / 250, -1.0]])
INVERSE = np.linalg.inv(FRAME)
ITERATES, HEIGHTS, INSIDE, BEYOND = 7, 17, 0.8, 0.005


def iterate(u, s):
    """H^7 of the frame's points (u, s), back in the frame's coordinates."""
    x = ORIGIN[0] + FRAME[0, 0] * u + FRAME[0, 1] * s
    y = ORIGIN[1] + FRAME[1, 0] * u + FRAME[1, 1] * s
    for _ in range(ITERATES):
        x, y = 1 - A * x * x + y, B * x
    d = np.vstack([x - ORIGIN[0], y - ORIGIN[1]])
    return INVERSE @ d


def pieces(u, images_u_min, images_u_max, usable, low, high):
    """The shortest runs of usable points from an end imaged below `low` to one imaged above `high` (or back)."""
    inside = usable & (u >= low) & (u <= high)
    below, above = images_u_max < low - BEYOND, images_u_min > high + BEYOND
    found = []
    index = np.nonzero(inside)[0]
    if not len(index):
        return found
    for run in np.split(index, np.nonzero(np.diff(index) > 1)[0] + 1):
        label = np.where(below[run], -1, np.where(above[run], 1, 0))
        last, at = 0, None
        for k in np.nonzero(label)[0]:
            if last and label[k] != last:
                found.append((u[run[at]], u[run[k]]))
                last, at = 0, None
                continue
            last, at = label[k], k
    return found


def main():
    u = np.linspace(-0.6, 0.3, 90001)
    best = (0, 0.0, 0.0, 0.0, [])
    with np.errstate(all="ignore"):
        for strip in (0.03, 0.035, 0.04, 0.045, 0.05):
            images = [iterate(u, np.full_like(u, s)) for s in np.linspace(-strip, strip, HEIGHTS)]
            image_u = np.array([im[0] for im in images])
            usable = np.max([np.abs(im[1]) for im in images], axis=0) < INSIDE * strip
            for low in np.arange(-0.45, -0.38, 0.0025):
                for high in np.arange(0.0, 0.06, 0.0025):
                    found = pieces(u, image_u.min(axis=0), image_u.max(axis=0), usable, low, high)
                    if (len(found), strip) > (best[0], best[1]):
                        best = (len(found), strip, low, high, found)
    count, strip, low, high, found = best
    print(f"{count} pieces, S = {strip:g}, window [{low:.4f}, {high:.4f}]: h_top >= ln {count} / {ITERATES} = "
          f"{np.log(count) / ITERATES:.6f} if proved")
    for lo, hi in found:
        print(f"  U = [{lo:.5f}, {hi:.5f}]")


if __name__ == "__main__":
    main()
