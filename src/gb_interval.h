/* gb_interval — interval arithmetic and second-order interval jets (internal; gb_surface and
 * gb_certify use it, verify/ may include it).
 *
 * An interval [lo, hi] encloses a set of reals. Every operation returns an enclosure of the exact
 * result: the floating-point endpoints are widened outwards by 2ε relative plus DBL_MIN absolute,
 * which covers one round-to-nearest step (½ ulp) and the ≤ 1 ulp error of glibc's sqrt, sin and cos
 * on the already-widened operands. This is cheaper than switching the rounding mode and, since the
 * enclosures are computed once per box, the looser endpoints cost nothing measurable.
 *
 * A jet carries a function of two chart parameters (a, b) over a box: its value, its two first and
 * three second derivatives, each as an interval enclosing the quantity over the whole box. */
#ifndef GB_INTERVAL_H
#define GB_INTERVAL_H

#include <float.h>
#include <math.h>

/* π as glibc's M_PI writes it (the same double), so that this header needs no _GNU_SOURCE. */
#define GB_INTERVAL_PI 3.14159265358979323846

typedef struct gb_interval {
    double lo, hi;
} gb_interval;

/* fmin/fmax without NaN handling, which GCC inlines (the libm calls cost more than the arithmetic). */
static inline double gb_interval_min(double a, double b) { return a < b ? a : b; }
static inline double gb_interval_max(double a, double b) { return a > b ? a : b; }

static inline double gb_interval_down(double x) { return x - (2.0 * DBL_EPSILON * (x < 0 ? -x : x) + DBL_MIN); }
static inline double gb_interval_up(double x) { return x + (2.0 * DBL_EPSILON * (x < 0 ? -x : x) + DBL_MIN); }

static inline gb_interval gb_interval_make(double lo, double hi)
{
    return (gb_interval){gb_interval_down(lo), gb_interval_up(hi)};
}
/* The exact double x (no widening). */
static inline gb_interval gb_interval_point(double x) { return (gb_interval){x, x}; }
static inline gb_interval gb_interval_add(gb_interval a, gb_interval b) { return gb_interval_make(a.lo + b.lo, a.hi + b.hi); }
static inline gb_interval gb_interval_sub(gb_interval a, gb_interval b) { return gb_interval_make(a.lo - b.hi, a.hi - b.lo); }
static inline gb_interval gb_interval_neg(gb_interval a) { return (gb_interval){-a.hi, -a.lo}; }

static inline gb_interval gb_interval_mul(gb_interval a, gb_interval b)
{
    const double p0 = a.lo * b.lo, p1 = a.lo * b.hi, p2 = a.hi * b.lo, p3 = a.hi * b.hi;
    return gb_interval_make(gb_interval_min(gb_interval_min(p0, p1), gb_interval_min(p2, p3)), gb_interval_max(gb_interval_max(p0, p1), gb_interval_max(p2, p3)));
}

/* c·a for an exact double c. */
static inline gb_interval gb_interval_scale(double c, gb_interval a)
{
    return c >= 0.0 ? gb_interval_make(c * a.lo, c * a.hi) : gb_interval_make(c * a.hi, c * a.lo);
}

/* a² (not a·a: the square of an interval holding 0 starts at 0). */
static inline gb_interval gb_interval_sqr(gb_interval a)
{
    if (a.lo >= 0.0) return gb_interval_make(a.lo * a.lo, a.hi * a.hi);
    if (a.hi <= 0.0) return gb_interval_make(a.hi * a.hi, a.lo * a.lo);
    const double m = gb_interval_max(-a.lo, a.hi);
    return (gb_interval){0.0, gb_interval_up(m * m)};
}

/* 1/a; the whole line when a holds 0. */
static inline gb_interval gb_interval_recip(gb_interval a)
{
    if (a.lo > 0.0 || a.hi < 0.0) return gb_interval_make(1.0 / a.hi, 1.0 / a.lo);
    return (gb_interval){-INFINITY, INFINITY};
}

static inline gb_interval gb_interval_sqrt(gb_interval a)
{
    return (gb_interval){a.lo > 0.0 ? gb_interval_down(sqrt(a.lo)) : 0.0, gb_interval_up(sqrt(gb_interval_max(a.hi, 0.0)))};
}

/* Does the interval hold a point c + 2πk? Decided generously: a point within 1e-12 of an end counts,
 * so an extremum of sin or cos is never missed through the rounding of π. */
static inline int gb_interval_holds_phase(gb_interval a, double c)
{
    const double k = ceil((a.lo - c - 1e-12) / (2.0 * GB_INTERVAL_PI));
    return c + 2.0 * GB_INTERVAL_PI * k <= a.hi + 1e-12;
}

static inline gb_interval gb_interval_cos(gb_interval a)
{
    if (!(a.hi - a.lo < 2.0 * GB_INTERVAL_PI)) return (gb_interval){-1.0, 1.0};
    const double c0 = cos(a.lo), c1 = cos(a.hi);
    double lo = gb_interval_min(c0, c1), hi = gb_interval_max(c0, c1);
    if (gb_interval_holds_phase(a, 0.0)) hi = 1.0;
    if (gb_interval_holds_phase(a, GB_INTERVAL_PI)) lo = -1.0;
    return (gb_interval){gb_interval_max(-1.0, gb_interval_down(lo)), gb_interval_min(1.0, gb_interval_up(hi))};
}

static inline gb_interval gb_interval_sin(gb_interval a)
{
    if (!(a.hi - a.lo < 2.0 * GB_INTERVAL_PI)) return (gb_interval){-1.0, 1.0};
    const double s0 = sin(a.lo), s1 = sin(a.hi);
    double lo = gb_interval_min(s0, s1), hi = gb_interval_max(s0, s1);
    if (gb_interval_holds_phase(a, 0.5 * GB_INTERVAL_PI)) hi = 1.0;
    if (gb_interval_holds_phase(a, 1.5 * GB_INTERVAL_PI)) lo = -1.0;
    return (gb_interval){gb_interval_max(-1.0, gb_interval_down(lo)), gb_interval_min(1.0, gb_interval_up(hi))};
}

static inline gb_interval gb_interval_hull(gb_interval a, gb_interval b)
{
    return (gb_interval){gb_interval_min(a.lo, b.lo), gb_interval_max(a.hi, b.hi)};
}

/* a ∩ b, for two enclosures of the same quantity (never empty in exact arithmetic; if rounding
 * made it so, the hull is returned). */
static inline gb_interval gb_interval_meet(gb_interval a, gb_interval b)
{
    const gb_interval m = {gb_interval_max(a.lo, b.lo), gb_interval_min(a.hi, b.hi)};
    return m.lo <= m.hi ? m : gb_interval_hull(a, b);
}

static inline double gb_interval_mag(gb_interval a) { return gb_interval_max(fabs(a.lo), fabs(a.hi)); }

/* ---------------------------------------------------------------- jets */

/* `order` is 2 for a full jet and 1 for one that carries only the value and first derivatives (its
 * second-derivative fields are zero and mean nothing): the centre of a box needs no more, and the
 * operations then skip the second-order work, which is most of it. A result has the lower order of
 * its operands. */
typedef struct gb_jet {
    gb_interval v, a, b, aa, ab, bb;
    int order;
} gb_jet;

static inline gb_jet gb_jet_const(double c)
{
    const gb_interval z = {0.0, 0.0};
    return (gb_jet){gb_interval_point(c), z, z, z, z, z, 2};
}

static inline int gb_jet_order(gb_jet u, gb_jet w) { return u.order < w.order ? u.order : w.order; }

/* u with its second derivatives dropped. */
static inline gb_jet gb_jet_first_order(gb_jet u)
{
    const gb_interval z = {0.0, 0.0};
    u.aa = u.ab = u.bb = z;
    u.order = 1;
    return u;
}

/* The chart parameter a (or b) itself over [lo, hi]. */
static inline gb_jet gb_jet_param_a(double lo, double hi)
{
    const gb_interval z = {0.0, 0.0}, one = {1.0, 1.0};
    return (gb_jet){{lo, hi}, one, z, z, z, z, 2};
}
static inline gb_jet gb_jet_param_b(double lo, double hi)
{
    const gb_interval z = {0.0, 0.0}, one = {1.0, 1.0};
    return (gb_jet){{lo, hi}, z, one, z, z, z, 2};
}

static inline gb_jet gb_jet_add(gb_jet u, gb_jet w)
{
    return (gb_jet){gb_interval_add(u.v, w.v),   gb_interval_add(u.a, w.a),   gb_interval_add(u.b, w.b),
                    gb_interval_add(u.aa, w.aa), gb_interval_add(u.ab, w.ab), gb_interval_add(u.bb, w.bb),
                    gb_jet_order(u, w)};
}

static inline gb_jet gb_jet_scale(double c, gb_jet u)
{
    return (gb_jet){gb_interval_scale(c, u.v),  gb_interval_scale(c, u.a),  gb_interval_scale(c, u.b),
                    gb_interval_scale(c, u.aa), gb_interval_scale(c, u.ab), gb_interval_scale(c, u.bb), u.order};
}

static inline gb_jet gb_jet_add_const(double c, gb_jet u)
{
    u.v = gb_interval_add(u.v, gb_interval_point(c));
    return u;
}

/* (u w)' = u' w + u w';  (u w)'' = u'' w + u'₁ w'₂ + u'₂ w'₁ + u w''. */
static inline gb_jet gb_jet_mul(gb_jet u, gb_jet w)
{
    gb_jet r;
    r.v = gb_interval_mul(u.v, w.v);
    r.a = gb_interval_add(gb_interval_mul(u.a, w.v), gb_interval_mul(u.v, w.a));
    r.b = gb_interval_add(gb_interval_mul(u.b, w.v), gb_interval_mul(u.v, w.b));
    r.order = gb_jet_order(u, w);
    if (r.order < 2) {
        r.aa = r.ab = r.bb = (gb_interval){0.0, 0.0};
        return r;
    }
    r.aa = gb_interval_add(gb_interval_add(gb_interval_mul(u.aa, w.v), gb_interval_scale(2.0, gb_interval_mul(u.a, w.a))),
                           gb_interval_mul(u.v, w.aa));
    r.ab = gb_interval_add(gb_interval_add(gb_interval_mul(u.ab, w.v), gb_interval_mul(u.a, w.b)),
                           gb_interval_add(gb_interval_mul(u.b, w.a), gb_interval_mul(u.v, w.ab)));
    r.bb = gb_interval_add(gb_interval_add(gb_interval_mul(u.bb, w.v), gb_interval_scale(2.0, gb_interval_mul(u.b, w.b))),
                           gb_interval_mul(u.v, w.bb));
    return r;
}

/* F∘u from enclosures of F, F′, F″ over u's value range: (F∘u)'' = F′ u'' + F″ u'ᵢ u'ⱼ. */
static inline gb_jet gb_jet_chain(gb_jet u, gb_interval F, gb_interval F1, gb_interval F2)
{
    gb_jet r;
    r.v = F;
    r.a = gb_interval_mul(F1, u.a);
    r.b = gb_interval_mul(F1, u.b);
    r.order = u.order;
    if (r.order < 2) {
        r.aa = r.ab = r.bb = (gb_interval){0.0, 0.0};
        return r;
    }
    r.aa = gb_interval_add(gb_interval_mul(F1, u.aa), gb_interval_mul(F2, gb_interval_sqr(u.a)));
    r.ab = gb_interval_add(gb_interval_mul(F1, u.ab), gb_interval_mul(F2, gb_interval_mul(u.a, u.b)));
    r.bb = gb_interval_add(gb_interval_mul(F1, u.bb), gb_interval_mul(F2, gb_interval_sqr(u.b)));
    return r;
}

static inline gb_jet gb_jet_sin(gb_jet u)
{
    const gb_interval s = gb_interval_sin(u.v), c = gb_interval_cos(u.v);
    return gb_jet_chain(u, s, c, gb_interval_neg(s));
}

static inline gb_jet gb_jet_cos(gb_jet u)
{
    const gb_interval s = gb_interval_sin(u.v), c = gb_interval_cos(u.v);
    return gb_jet_chain(u, c, gb_interval_neg(s), gb_interval_neg(c));
}

/* u^(1/4) for u > 0: F′ = F/(4u), F″ = −3F/(16u²). */
static inline gb_jet gb_jet_root4(gb_jet u)
{
    const gb_interval F = gb_interval_sqrt(gb_interval_sqrt(u.v));
    const gb_interval inv = gb_interval_recip(u.v);
    const gb_interval F1 = gb_interval_scale(0.25, gb_interval_mul(F, inv));
    const gb_interval F2 = gb_interval_scale(-0.1875, gb_interval_mul(F, gb_interval_sqr(inv)));
    return gb_jet_chain(u, F, F1, F2);
}

/* c₀ + c₁u + … + cₙuⁿ over the interval u, by Horner, with interval coefficients. */
static inline gb_interval gb_interval_poly(gb_interval u, const gb_interval *c, int degree)
{
    gb_interval p = c[degree];
    for (int k = degree - 1; k >= 0; k--) p = gb_interval_add(gb_interval_mul(p, u), c[k]);
    return p;
}

/* P(u) = c₀ + c₁u + … + cₙuⁿ (n ≤ 8) by the chain rule, with P, P′ and P″ enclosed over u's range by
 * Horner: three interval polynomials instead of n jet products. The derivative's coefficients k·c_k
 * and k(k−1)·c_k are enclosed too (a product of doubles may round). */
static inline gb_jet gb_jet_poly(gb_jet u, const double *c, int degree)
{
    gb_interval c0[9], c1[8], c2[8];
    for (int k = 0; k <= degree; k++) c0[k] = gb_interval_point(c[k]);
    for (int k = 1; k <= degree; k++) c1[k - 1] = gb_interval_scale((double)k, c0[k]);
    for (int k = 2; k <= degree; k++) c2[k - 2] = gb_interval_scale((double)(k * (k - 1)), c0[k]);
    const gb_interval zero = {0.0, 0.0};
    const gb_interval P = gb_interval_poly(u.v, c0, degree);
    const gb_interval P1 = degree >= 1 ? gb_interval_poly(u.v, c1, degree - 1) : zero;
    const gb_interval P2 = degree >= 2 ? gb_interval_poly(u.v, c2, degree - 2) : zero;
    return gb_jet_chain(u, P, P1, P2);
}

/* g = y·√(x² + y²), which is C¹,¹ but not C² where x = y = 0. With ρ = √(x² + y²), c = x/ρ, s = y/ρ and
 * w_i = −s x_i + c y_i:  g_i = y_i ρ + y ρ_i,  ρ_i = c x_i + s y_i, and
 * g_ij = y_ij ρ + y_i ρ_j + y_j ρ_i + y (c x_ij + s y_ij) + s w_i w_j,
 * every term bounded even as ρ → 0 (y/ρ = s). Where the box may hold ρ = 0, c and s are only known to
 * lie in [−1, 1]; the second derivatives then enclose the Hessian wherever it exists. */
static inline gb_jet gb_jet_y_hypot(gb_jet x, gb_jet y)
{
    const gb_interval rho = gb_interval_sqrt(gb_interval_add(gb_interval_sqr(x.v), gb_interval_sqr(y.v)));
    const gb_interval unit = {-1.0, 1.0};
    gb_interval c = unit, s = unit;
    if (rho.lo > 0.0) {
        const gb_interval inv = gb_interval_recip(rho);
        c = gb_interval_meet(gb_interval_mul(x.v, inv), unit);
        s = gb_interval_meet(gb_interval_mul(y.v, inv), unit);
    }
    const gb_interval rho_a = gb_interval_add(gb_interval_mul(c, x.a), gb_interval_mul(s, y.a));
    const gb_interval rho_b = gb_interval_add(gb_interval_mul(c, x.b), gb_interval_mul(s, y.b));
    gb_jet g;
    g.v = gb_interval_mul(y.v, rho);
    g.a = gb_interval_add(gb_interval_mul(y.a, rho), gb_interval_mul(y.v, rho_a));
    g.b = gb_interval_add(gb_interval_mul(y.b, rho), gb_interval_mul(y.v, rho_b));
    g.order = gb_jet_order(x, y);
    if (g.order < 2) {
        g.aa = g.ab = g.bb = (gb_interval){0.0, 0.0};
        return g;
    }
    const gb_interval w_a = gb_interval_sub(gb_interval_mul(c, y.a), gb_interval_mul(s, x.a));
    const gb_interval w_b = gb_interval_sub(gb_interval_mul(c, y.b), gb_interval_mul(s, x.b));
#define GB_Y_HYPOT_SECOND(yij, xij, yi, yj, rhoi, rhoj, wwij)                                                       \
    gb_interval_add(gb_interval_add(gb_interval_mul(yij, rho),                                                      \
                                    gb_interval_add(gb_interval_mul(yi, rhoj), gb_interval_mul(yj, rhoi))),         \
                    gb_interval_add(gb_interval_mul(y.v, gb_interval_add(gb_interval_mul(c, xij), gb_interval_mul(s, yij))), \
                                    gb_interval_mul(s, wwij)))
    g.aa = GB_Y_HYPOT_SECOND(y.aa, x.aa, y.a, y.a, rho_a, rho_a, gb_interval_sqr(w_a));
    g.ab = GB_Y_HYPOT_SECOND(y.ab, x.ab, y.a, y.b, rho_a, rho_b, gb_interval_mul(w_a, w_b));
    g.bb = GB_Y_HYPOT_SECOND(y.bb, x.bb, y.b, y.b, rho_b, rho_b, gb_interval_sqr(w_b));
#undef GB_Y_HYPOT_SECOND
    return g;
}

#endif
