/* gb_certify_internal — what the per-vertical certificate (gb_certify) and the atlas of verticals
 * (gb_atlas) share: the cover of the sphere of directions by root boxes of two charts, and the
 * box tests' arithmetic (internal to the library).
 *
 * The cover: (φ, θ) for 0.8 ≤ φ ≤ π − 0.8, and two polar-x caps (α, γ) ∈ [0.75, π − 0.75]² and
 * [0.75, π − 0.75] × [π + 0.75, 2π − 0.75], which overlap it (gb_certify.h says why). */
#ifndef GB_CERTIFY_INTERNAL_H
#define GB_CERTIFY_INTERNAL_H

#include "gb_certify.h"
#include "gb_interval.h"
#include "gb_surface_internal.h"

#include <math.h>

/* Rounding allowances of the box tests, which use plain double sums of a few products of O(1)
 * numbers (error ~1e-16): a margin must exceed these before a verdict is given. */
#define GB_CERTIFY_SLACK_ROUNDING 1e-13
#define GB_CERTIFY_HESSIAN_ROUNDING 1e-12
/* A point counts as inside a box only this far from its edges [rad]; Newton's points are within
 * ~1e-14 of the exact critical points, so the exact point is then inside too. */
#define GB_CERTIFY_INSIDE_MARGIN 1e-9

enum { GB_REGION_EQUATOR = 0, GB_REGION_NORTH = 1, GB_REGION_SOUTH = 2, GB_REGIONS = 3 };
enum { GB_ROOTS_A_EQ = 4, GB_ROOTS_B_EQ = 16, GB_ROOTS_CAP = 4 };
#define GB_ROOT_COUNT (GB_ROOTS_A_EQ * GB_ROOTS_B_EQ + 2 * GB_ROOTS_CAP * GB_ROOTS_CAP)

/* The three regions' parameter ranges {a_lo, a_hi, b_lo, b_hi}. */
static const double gb_region_range[GB_REGIONS][4] = {
    {0.8, GB_INTERVAL_PI - 0.8, 0.0, 2.0 * GB_INTERVAL_PI},
    {0.75, GB_INTERVAL_PI - 0.75, 0.75, GB_INTERVAL_PI - 0.75},
    {0.75, GB_INTERVAL_PI - 0.75, GB_INTERVAL_PI + 0.75, 2.0 * GB_INTERVAL_PI - 0.75},
};

static inline gb_surface_chart gb_region_chart(int region)
{
    return region == GB_REGION_EQUATOR ? GB_SURFACE_CHART_POLAR_Z : GB_SURFACE_CHART_POLAR_X;
}

/* Root box k of the cover: its region and range (k < GB_ROOT_COUNT, regions in order). */
static inline void gb_root_box(int k, int *region, double box[4])
{
    int r = 0, first = 0;
    for (; r < GB_REGIONS; r++) {
        const int count = r == GB_REGION_EQUATOR ? GB_ROOTS_A_EQ * GB_ROOTS_B_EQ : GB_ROOTS_CAP * GB_ROOTS_CAP;
        if (k < first + count) break;
        first += count;
    }
    const double *g = gb_region_range[r];
    const int nb = r == GB_REGION_EQUATOR ? GB_ROOTS_B_EQ : GB_ROOTS_CAP, na = r == GB_REGION_EQUATOR ? GB_ROOTS_A_EQ : GB_ROOTS_CAP;
    const int i = (k - first) / nb, j = (k - first) % nb;
    box[0] = g[0] + (g[1] - g[0]) * i / na, box[1] = i + 1 == na ? g[1] : g[0] + (g[1] - g[0]) * (i + 1) / na;
    box[2] = g[2] + (g[3] - g[2]) * j / nb, box[3] = j + 1 == nb ? g[3] : g[2] + (g[3] - g[2]) * (j + 1) / nb;
    *region = r;
}

/* √(Σ mag(v_k)²), rounded up: a bound of |v| over the box. */
static inline double gb_certify_norm_of_mags(const gb_interval v[3])
{
    const double a = gb_interval_mag(v[0]), b = gb_interval_mag(v[1]), c = gb_interval_mag(v[2]);
    return sqrt(a * a + b * b + c * c) * (1.0 + 1e-12);
}

/* A box of `region` enclosed (gb_surface_enclose in the region's chart), with the bounds of |x_a|, |x_b|,
 * |x_aa|, |x_ab|, |x_bb| over it in mags[0..4]: what the certificate's and the atlas's boxes keep. */
static inline void gb_certify_enclose_box(const gb_surface *surface, int region, double a_lo, double a_hi, double b_lo,
                                          double b_hi, gb_surface_enclosure *e, double mags[5])
{
    gb_surface_enclose(surface, gb_region_chart(region), a_lo, a_hi, b_lo, b_hi, e);
    mags[0] = gb_certify_norm_of_mags(e->x_a), mags[1] = gb_certify_norm_of_mags(e->x_b);
    mags[2] = gb_certify_norm_of_mags(e->x_aa), mags[3] = gb_certify_norm_of_mags(e->x_ab);
    mags[4] = gb_certify_norm_of_mags(e->x_bb);
}

/* Σ d_k v_k over intervals v_k, in plain double arithmetic (see GB_CERTIFY_SLACK_ROUNDING). */
static inline gb_interval gb_certify_dot(const double d[3], const gb_interval v[3])
{
    gb_interval s = {0.0, 0.0};
    for (int k = 0; k < 3; k++) {
        const double p = d[k] * v[k].lo, q = d[k] * v[k].hi;
        s.lo += gb_interval_min(p, q);
        s.hi += gb_interval_max(p, q);
    }
    return s;
}

/* A lower bound of d·x over the box: the direct enclosure met with the Taylor form about the box
 * centre with d applied first (see gb_surface_enclosure), whose first-order term is the gradient of h
 * at the centre times the offset, not Σ|d_k| |∂x_k| times it. Near a critical point that is the
 * difference between a bound good to O(size²) and one good to O(size). Haa, Hab, Hbb: d·x'' over the
 * box. Plain double sums (see GB_CERTIFY_SLACK_ROUNDING). */
static inline double gb_certify_height_lower_bound(const double d[3], const gb_surface_enclosure *e, gb_interval Haa,
                                                   gb_interval Hab, gb_interval Hbb)
{
    const double direct = gb_certify_dot(d, e->x).lo;
    const gb_interval hc = gb_certify_dot(d, e->x_c), ga = gb_certify_dot(d, e->x_a_c), gb = gb_certify_dot(d, e->x_b_c);
    const gb_interval second = gb_interval_add(
        gb_interval_add(gb_interval_mul(Haa, gb_interval_sqr(e->da)), gb_interval_mul(Hbb, gb_interval_sqr(e->db))),
        gb_interval_scale(2.0, gb_interval_mul(Hab, gb_interval_mul(e->da, e->db))));
    const double taylor = hc.lo + gb_interval_mul(ga, e->da).lo + gb_interval_mul(gb, e->db).lo + 0.5 * second.lo;
    return gb_interval_max(direct, taylor);
}

/* Is the symmetric interval matrix [[Haa, Hab], [Hab, Hbb]] positive definite throughout? */
static inline int gb_certify_definite(gb_interval Haa, gb_interval Hab, gb_interval Hbb)
{
    if (!(Haa.lo > GB_CERTIFY_HESSIAN_ROUNDING && Hbb.lo > GB_CERTIFY_HESSIAN_ROUNDING)) return 0;
    const double m = gb_interval_max(fabs(Hab.lo), fabs(Hab.hi));
    return Haa.lo * Hbb.lo - m * m > GB_CERTIFY_HESSIAN_ROUNDING;
}

/* Is b in [lo, hi] modulo 2π, at least `margin` inside? */
static inline int gb_certify_inside_periodic(double b, double lo, double hi, double margin)
{
    for (int k = -1; k <= 1; k++) {
        const double t = b + 2.0 * GB_INTERVAL_PI * k;
        if (t >= lo + margin && t <= hi - margin) return 1;
    }
    return 0;
}

/* Is [lo, hi] inside [outer_lo, outer_hi] modulo 2π? */
static inline int gb_certify_range_inside_periodic(double lo, double hi, double outer_lo, double outer_hi)
{
    for (int k = -1; k <= 1; k++)
        if (lo + 2.0 * GB_INTERVAL_PI * k >= outer_lo && hi + 2.0 * GB_INTERVAL_PI * k <= outer_hi) return 1;
    return 0;
}

/* gb_certify_global_minimum's first candidate: Newton from the lowest root-box centre at the unit vertical d of zb
 * (into d). A caller that certifies it global another way (the atlas) has the point gb_certify_global_minimum
 * returns when its first check says GLOBAL, bit for bit. */
int gb_certify_first_candidate(const gb_certify *certify, const double zb[3], const gb_contact_refine_def *refine,
                               double d[3], gb_contact_point *out);

#endif
