/* Proved on Arb's balls, stage 2: the rigorous integrator (gb_proof_flow) and covering relations (gb_proof_cover).
 *
 * Oracles, none sharing code with what they check:
 * - a linear field that turns and contracts (x' = −3x/10 − 2y, y' = 2x − 3y/10, z' = 1 − z) in closed form: the
 *   enclosure of a point holds the exact solution and not the solution 1e-9 later (teeth); a box's enclosure after
 *   three turns is the exact image's bounding box to Arb's radii's rounding (Lohner's frame: boxes re-wrapped at every
 *   step would grow by |cos| + |sin| a step);
 * - Rössler's flow by GSL's rk8pd at 1e-13 with its crossings located by bisection: the enclosures of the first
 *   return and of the second return of points of the horseshoe's edges hold GSL's points and times;
 * - negative controls with teeth: CAPD's set M moved right by 0.2 must lose M ⇒ M, and its left edge's second
 *   return is proved on the wrong side (a refutation of that relation, not a failure to prove it); a strip narrowed
 *   to [0.030, 0.034] must not be proved trapping, the returns of a piece of it proved below it; Hénon's map at the classical a = 1.4 with the sets that prove the
 *   horseshoe at a = 6 must prove no relation, its edges proved on one side;
 * - Collatz–Wielandt's bound against matrices of known spectral radius (the full 2-shift: 2; the golden mean shift:
 *   (1 + √5)/2; a nilpotent matrix: 0);
 * - the definitions' ranges: each bad field, set, plane or iterate refused with GB_EDOM naming it. */
#include "gb_check.h"
#include "gb_error.h"
#include "gb_proof_cover.h"
#include "gb_proof_flow.h"
#include "verify_sections.h"

#include <float.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static int holds(gb_proof_interval a, double x) { return a.lo <= x && x <= a.hi; }

/* x' = −3x/10 − 2y, y' = 2x − 3y/10, z' = 1 − z. */
static gb_proof_field turning_field(void)
{
    gb_proof_field f;
    memset(&f, 0, sizeof f);
    f.dimension = 3;
    f.L[0][0] = f.L[1][1] = (gb_proof_rational){-3, 10};
    f.L[0][1] = (gb_proof_rational){-2, 1};
    f.L[1][0] = (gb_proof_rational){2, 1};
    f.c[2] = (gb_proof_rational){1, 1};
    f.L[2][2] = (gb_proof_rational){-1, 1};
    return f;
}

static void turning_exact(const double x0[3], double t, double out[3])
{
    const double d = exp(-0.3 * t), c = cos(2 * t), s = sin(2 * t);
    out[0] = d * (c * x0[0] - s * x0[1]);
    out[1] = d * (s * x0[0] + c * x0[1]);
    out[2] = 1.0 + (x0[2] - 1.0) * exp(-t);
}

static void test_linear_flow(void)
{
    const gb_proof_field f = turning_field();
    gb_proof_flow_def d = gb_proof_flow_def_default(&f);
    const double x0[3] = {0.9137, 0.2385, 0.5172}, t = 9.5; /* 9.5 s: three turns */
    gb_proof_interval point[3], image[3];
    for (int i = 0; i < 3; i++) point[i] = (gb_proof_interval){x0[i], x0[i]};
    int status = gb_proof_flow_time(&d, point, t, image);
    double exact[3], later[3], widest = 0.0;
    turning_exact(x0, t, exact);
    turning_exact(x0, t + 1e-9, later);
    int held = 0, teeth = 0;
    for (int i = 0; i < 3 && !status; i++) {
        /* the closed form in doubles: a few ulps of the values (4 ulps of 1 as the margin) */
        const gb_proof_interval wide = {image[i].lo - 4 * DBL_EPSILON, image[i].hi + 4 * DBL_EPSILON};
        held += holds(wide, exact[i]);
        if (i < 2) teeth += !holds(wide, later[i]); /* z moves by 1e-9 (1 − z0) e^-t ~ 4e-14 in 1e-9 s: not a tooth */
        widest = fmax(widest, image[i].hi - image[i].lo);
    }
    gb_check c = {"-", "-", "the rigorous integrator on a linear field that turns and contracts: the solution from a point at t = 9.5",
                  "the closed form e^(-0.3 t) R(2t) x0, 1 + (z0 - 1) e^-t, in doubles",
                  "proof: the enclosure (widened by 4 ulps of 1, the closed form's own rounding) holds it; the same 1e-9 s later "
                  "lies outside in x and y (teeth); width at most 1e-13 (128 bits, order 20, 1e-15 a step and rounding)"};
    gb_check_true(&c, !status && held == 3 && teeth == 2 && widest <= 1e-13, "%d of 3 held, %d of 2 (x, y) with teeth, width %.3g%s%s", held,
                  teeth, widest, status ? ": " : "", status ? gb_error_message() : "");
    /* a box 0.01 wide in x and y after three turns: its exact image is the box turned by 2t and shrunk by e^-0.3t */
    const double w = 0.01;
    gb_proof_interval box[3] = {{x0[0] - w / 2, x0[0] + w / 2}, {x0[1] - w / 2, x0[1] + w / 2}, {x0[2], x0[2]}};
    status = gb_proof_flow_time(&d, box, t, image);
    const double span = exp(-0.3 * t) * w * (fabs(cos(2 * t)) + fabs(sin(2 * t)));
    double worst = 0.0;
    for (int i = 0; i < 2 && !status; i++) worst = fmax(worst, fabs((image[i].hi - image[i].lo) / span - 1.0));
    gb_check cw = {"-", "-", "the rigorous integrator's wrapping: a box 0.01 wide turned three times (t = 9.5)",
                   "the exact image's bounding box: e^(-0.3 t) w (|cos 2t| + |sin 2t|) across",
                   "proof of Lohner's frame: the hull within 1e-5 relative of the exact bounding box, the budget of Arb's "
                   "radii (kept to 30 bits: each operation rounds a radius up by up to 2^-30, some 30 operations a step over "
                   "20 steps, 6e-7); a box re-wrapped every step would grow by up to sqrt 2 a step"};
    gb_check_true(&cw, !status && worst <= 1e-5, "widths off the exact bounding box by %.3g relative%s%s", worst, status ? ": " : "",
                  status ? gb_error_message() : "");
}

/* ---- Rössler by GSL ------------------------------------------------------------------------------------------ */

static int rossler_rhs(double t, const double y[], double f[], void *params)
{
    (void)t, (void)params;
    f[0] = -y[1] - y[2];
    f[1] = y[0] + 0.2 * y[1];
    f[2] = 0.2 + y[2] * (y[0] - 5.7);
    return GSL_SUCCESS;
}

/* The k-th crossing of x = 0 with x increasing from (0, y0, z0), by rk8pd at 1e-13 and bisection in time. */
static int rossler_return(double y0, double z0, int k, double out[3], double *time)
{
    gsl_odeiv2_system sys = {rossler_rhs, NULL, 3, NULL};
    gsl_odeiv2_driver *drv = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-3, 1e-13, 1e-13);
    double y[3] = {0.0, y0, z0}, t = 0.0;
    const double dt = 0.01;
    int crossings = 0, status = GSL_SUCCESS;
    while (crossings < k && t < 100.0 && status == GSL_SUCCESS) {
        double prev[3] = {y[0], y[1], y[2]}, tp = t;
        status = gsl_odeiv2_driver_apply(drv, &t, tp + dt, y);
        if (status || !(prev[0] < 0.0 && y[0] >= 0.0)) continue;
        if (++crossings < k) continue;
        double lo = tp, hi = t, at[3];
        for (int it = 0; it < 60; it++) { /* bisection: re-integrate from the step's start to the middle */
            const double mid = 0.5 * (lo + hi);
            double tt = tp;
            memcpy(at, prev, sizeof at);
            gsl_odeiv2_driver_reset(drv);
            status |= gsl_odeiv2_driver_apply(drv, &tt, mid, at);
            if (at[0] < 0.0) lo = mid;
            else hi = mid;
        }
        double tt = tp;
        memcpy(out, prev, sizeof prev);
        gsl_odeiv2_driver_reset(drv);
        status |= gsl_odeiv2_driver_apply(drv, &tt, hi, out);
        *time = hi;
    }
    gsl_odeiv2_driver_free(drv);
    return status == GSL_SUCCESS && crossings == k ? 0 : -1;
}

static void test_rossler_against_gsl(void)
{
    const gb_proof_field f = gb_proof_flow_rossler(1, 5, 1, 5, 57, 10);
    gb_proof_flow_def d = gb_proof_flow_def_default(&f);
    /* CAPD's sets' four edges at z = 0.028, 0.031, 0.034: their first and second returns */
    const double edges[4] = {-8.4, -7.6, -5.7, -4.6}, heights[3] = {0.028, 0.031, 0.034};
    int tried = 0, held = 0, status = GB_OK;
    double widest = 0.0, far = 0.0;
    char first[200] = "";
    for (int e = 0; e < 4 && !status; e++)
        for (int h = 0; h < 3 && !status; h++)
            for (int k = 1; k <= 2 && !status; k++) {
                d.returns = k;
                gb_proof_interval box[3] = {{0, 0}, {edges[e], edges[e]}, {heights[h], heights[h]}};
                gb_proof_flow_crossing r;
                status = gb_proof_flow_section_map(&d, box, &r);
                double p[3] = {0, 0, 0}, time = 0.0;
                if (status || rossler_return(edges[e], heights[h], k, p, &time)) break;
                /* GSL's own error: 1e-13 a unit time over about 12 time units, amplified by the flow's expansion
                 * (|P'| ~ 10 over two returns): 1e-10 absolute, on both sides */
                const double bar = 1e-10;
                const int ok = p[1] >= r.image[1].lo - bar && p[1] <= r.image[1].hi + bar && p[2] >= r.image[2].lo - bar &&
                               p[2] <= r.image[2].hi + bar && time >= r.time.lo - bar && time <= r.time.hi + bar;
                tried++, held += ok;
                widest = fmax(widest, fmax(r.image[1].hi - r.image[1].lo, r.time.hi - r.time.lo));
                far = fmax(far, fmax(fabs(p[1] - 0.5 * (r.image[1].lo + r.image[1].hi)), fabs(p[2] - 0.5 * (r.image[2].lo + r.image[2].hi))));
                if (!ok && !first[0])
                    snprintf(first, sizeof first, "; first miss: y0 %g z0 %g k %d: GSL (%.12g, %.12g) at %.12g, enclosure y [%.12g, %.12g]", edges[e],
                             heights[h], k, p[1], p[2], time, r.image[1].lo, r.image[1].hi);
            }
    gb_check c = {"-", "-", "the rigorous return map of Roessler's flow (a = b = 0.2, c = 5.7) to x = 0: the first and second returns "
                  "of 12 points on the edges of CAPD's sets, and their times",
                  "GSL rk8pd at 1e-13, crossings located by bisection in time to 1e-15 s",
                  "proof: every GSL point and time within the enclosure, give or take GSL's own error of 1e-10 (1e-13 a unit "
                  "time over 12 units, times the flow's expansion ~10)"};
    gb_check_true(&c, !status && tried == 24 && held == tried, "%d of %d held (GSL's points at most %.3g from the enclosures' middles, "
                  "enclosures at most %.3g wide)%s%s%s", held, tried, far, widest, first, status ? ": " : "", status ? gb_error_message() : "");
}

/* The C¹ step: the linear field's return map to y = 0 in closed form, Rössler's return map's derivative against GSL's
 * central differences, and Rössler's period-1 orbit by Krawczyk against GSL's Newton. */
static void test_c1_and_orbit(void)
{
    /* 1. x' = −3x/10 − 2y, y' = 2x − 3y/10, z' = 1 − z: from y = 0, x > 0 the first return to y = 0 (y' > 0) is at
     * t = π, P(x, z) = (x e^(−0.3π), 1 + (z − 1) e^(−π)), DP = diag(e^(−0.3π), e^(−π)) on the plane */
    const gb_proof_field turning = turning_field();
    gb_proof_flow_def d = gb_proof_flow_def_default(&turning);
    d.coordinate = 1, d.direction = 1, d.derivative = 1;
    gb_proof_interval box[3] = {{0.5, 0.5 + 1e-6}, {0, 0}, {0.25, 0.25 + 1e-6}};
    gb_proof_flow_crossing r;
    int status = gb_proof_flow_section_map(&d, box, &r);
    const double exact[2][2] = {{exp(-0.3 * M_PI), 0.0}, {0.0, exp(-M_PI)}};
    static const int plane[2] = {0, 2};
    int held = 0, teeth = 0;
    double widest = 0.0;
    for (int a = 0; a < 2 && !status; a++)
        for (int b = 0; b < 2; b++) {
            const gb_proof_interval e = r.jacobian[plane[a]][plane[b]];
            held += holds(e, exact[a][b]);
            widest = fmax(widest, e.hi - e.lo);
            if (a == b) teeth += !holds(e, exact[a][b] * (1 + 1e-5)); /* the value 1e-5 off is outside */
        }
    gb_check cl = {"-", "-", "the C1 step on the linear field that turns and contracts: the return map to y = 0's derivative over a box "
                   "1e-6 wide", "closed form: DP = diag(exp(-0.3 pi), exp(-pi)) in (x, z)",
                   "proof: the 4 entries inside, at most 1e-6 wide (the box's own width), and each diagonal entry 1e-5 off outside"};
    gb_check_true(&cl, !status && held == 4 && teeth == 2 && widest <= 1e-6, "%d of 4 inside, widest %.3g, %d of 2 moved values "
                  "outside%s%s", held, widest, teeth, status ? ": " : "", status ? gb_error_message() : "");

    /* 2. Rössler: the period-1 orbit by Newton on GSL's return map (central differences), then its box proved */
    double v[2] = {-8.38, 0.0296}, time = 0.0, J[2][2] = {{0}};
    const double h = 1e-5;
    int gsl = 0;
    for (int it = 0; it < 8 && !gsl; it++) {
        double p[3], plus[3], minus[3], t2;
        gsl |= rossler_return(v[0], v[1], 1, p, &time);
        for (int b = 0; b < 2 && !gsl; b++) {
            const double up[2] = {v[0] + (b == 0) * h, v[1] + (b == 1) * h}, down[2] = {v[0] - (b == 0) * h, v[1] - (b == 1) * h};
            gsl |= rossler_return(up[0], up[1], 1, plus, &t2) || rossler_return(down[0], down[1], 1, minus, &t2);
            J[0][b] = (plus[1] - minus[1]) / (2 * h), J[1][b] = (plus[2] - minus[2]) / (2 * h);
        }
        /* Newton on P(v) − v: (J − I) dv = −(P(v) − v) */
        const double A = J[0][0] - 1, B = J[0][1], C = J[1][0], D = J[1][1] - 1, det = A * D - B * C;
        const double r0 = -(p[1] - v[0]), r1 = -(p[2] - v[1]);
        v[0] += (D * r0 - B * r1) / det, v[1] += (A * r1 - C * r0) / det;
    }
    const gb_proof_field ro = gb_proof_flow_rossler(1, 5, 1, 5, 57, 10);
    gb_proof_flow_def rd = gb_proof_flow_def_default(&ro);
    const double y0 = -8.38094174, z0 = 0.02959006;
    gb_proof_interval wide[3] = {{0, 0}, {y0 - 1e-3, y0 + 1e-3}, {z0 - 1e-3, z0 + 1e-3}};
    gb_proof_interval narrow[3] = {{0, 0}, {y0 - 1e-7, y0 + 1e-7}, {z0 - 1e-7, z0 + 1e-7}};
    gb_proof_interval shifted[3] = {{0, 0}, {y0 + 0.01 - 1e-3, y0 + 0.01 + 1e-3}, {z0 - 1e-3, z0 + 1e-3}};
    gb_proof_flow_orbit ow, on, os;
    status = gb_proof_flow_periodic_orbit(&rd, wide, &ow);
    if (!status) status = gb_proof_flow_periodic_orbit(&rd, narrow, &on);
    if (!status) status = gb_proof_flow_periodic_orbit(&rd, shifted, &os);
    /* DP over the narrow box against GSL's central differences at the orbit: their error h² P‴/6 + 1e-13/h ~ 1e-8 */
    int dp_held = 0;
    for (int a = 0; a < 2 && !status && !gsl; a++)
        for (int b = 0; b < 2; b++) {
            const gb_proof_interval e = on.jacobian[a + 1][b + 1];
            dp_held += J[a][b] >= e.lo - 1e-7 && J[a][b] <= e.hi + 1e-7;
        }
    const int inside = !status && !gsl && holds(ow.krawczyk[1], v[0]) && holds(ow.krawczyk[2], v[1]) && holds(on.krawczyk[1], v[0]) &&
                       holds(on.krawczyk[2], v[1]) && holds(on.period, time);
    gb_check co = {"-", "-", "Roessler's period-1 orbit by Krawczyk's operator on the return map to x = 0 (the C1 step for DP)",
                   "GSL rk8pd at 1e-13: Newton on its return map with central differences (h = 1e-5) for the orbit, its period "
                   "and DP",
                   "proof: the boxes 2e-3 and 2e-7 wide proved (K inside), GSL's orbit in both K and its period in the "
                   "enclosure; DP over the narrow box holds GSL's differences within their error 1e-7 (h^2 times P's third derivative / 6, plus 1e-13 / h); "
                   "a box shifted by 0.01 in y excluded (K misses it)"};
    gb_check_true(&co, !status && !gsl && ow.proved && on.proved && inside && dp_held == 4 && os.excluded && !os.proved,
                  "wide %s, narrow %s (y in [%.12g, %.12g], period [%.12g, %.12g]); GSL's orbit (%.12g, %.12g), period %.12g: %s; "
                  "DP %d of 4; shifted %s%s%s", ow.proved ? "proved" : "NOT proved", on.proved ? "proved" : "NOT proved",
                  on.krawczyk[1].lo, on.krawczyk[1].hi, on.period.lo, on.period.hi, v[0], v[1], time, inside ? "inside" : "OUTSIDE",
                  dp_held, os.excluded ? "excluded" : "NOT excluded", status ? ": " : "", status ? gb_error_message() : "");
}

static void test_covering_controls(void)
{
    const gb_proof_field f = gb_proof_flow_rossler(1, 5, 1, 5, 57, 10);
    gb_proof_flow_def d = gb_proof_flow_def_default(&f);
    d.returns = 2;
    /* M moved right by 0.2: [-8.2, -7.4]; its left edge must come back left of -8.2 for M => M */
    gb_proof_interval box[3] = {{0, 0}, {-8.2, -8.2}, {0.028, 0.034}};
    gb_proof_flow_crossing r;
    int status = gb_proof_flow_section_map(&d, box, &r);
    const int refuted = !status && r.image[1].lo > -8.2;
    gb_check c = {"-", "-", "a negative control: CAPD's set M moved right by 0.2 ([-8.2, -7.4])",
                  "the covering relation M => M, which needs P^2(left edge) left of -8.2",
                  "proof of the opposite: P^2 of the left edge lies wholly right of -8.2, so the relation fails (and "
                  "would be refused)"};
    gb_check_true(&c, refuted, "P^2(left edge) across [%.9g, %.9g]%s%s", r.image[1].lo, r.image[1].hi, status ? ": " : "",
                  status ? gb_error_message() : "");

    gb_proof_cover_def t = gb_proof_cover_def_default();
    t.section = gb_proof_flow_def_default(&f);
    t.u = 1, t.s = 2, t.iterates = 2, t.trap = 1;
    t.region_u = (gb_proof_interval){-10.7, -2.3}, t.strip = (gb_proof_interval){0.030, 0.034};
    t.sets = 1, t.set_u[0] = (gb_proof_interval){-8.4, -7.6};
    t.pieces = 200, t.depth = 2;
    gb_proof_cover_result tr;
    status = gb_proof_cover(&t, &tr);
    /* the opposite, proved apart: the returns of a piece of R lie wholly below the narrowed strip */
    d.returns = 1;
    gb_proof_interval low[3] = {{0, 0}, {-8.5, -8.49}, {0.030, 0.034}};
    gb_proof_flow_crossing lr;
    const int below = !gb_proof_flow_section_map(&d, low, &lr) && lr.image[2].hi < t.strip.lo;
    gb_check ct = {"-", "-", "a negative control: Roessler's trapping rectangle with its strip narrowed to [0.030, 0.034]",
                   "P(R) in int R, which needs every return of R inside the strip",
                   "proof of the opposite: not proved (the first piece that fails named), and the returns of the piece "
                   "[-8.5, -8.49] x [0.030, 0.034] enclosed wholly below z = 0.030"};
    gb_check_true(&ct, !status && !tr.trapped && !tr.covers[0][0] && below, "trapped %d, M => M %d, first failing piece u in "
                  "[%.9g, %.9g] (returns to z in [%.9g, %.9g]); u in [-8.5, -8.49] returns to z in [%.9g, %.9g]%s%s", tr.trapped,
                  tr.covers[0][0], tr.failed_u.lo, tr.failed_u.hi, tr.failed_image_s.lo, tr.failed_image_s.hi, lr.image[2].lo,
                  lr.image[2].hi, status ? ": " : "", status ? gb_error_message() : "");

    const gb_proof_field classical = gb_proof_cover_henon(7, 5, 3, 10), wide = gb_proof_cover_henon(6, 1, 3, 10);
    gb_proof_cover_def h = gb_proof_cover_def_default();
    h.kind = GB_PROOF_MAP_QUADRATIC, h.u = 0, h.s = 1, h.strip = (gb_proof_interval){-0.22, 0.22};
    h.sets = 2, h.set_u[0] = (gb_proof_interval){-0.7, -0.1}, h.set_u[1] = (gb_proof_interval){0.1, 0.7}, h.pieces = 16;
    gb_proof_cover_result at6, at14;
    h.map = &wide;
    status = gb_proof_cover(&h, &at6);
    h.map = &classical;
    if (!status) status = gb_proof_cover(&h, &at14);
    int none = 1;
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++) none &= !at14.covers[i][j];
    /* at a = 1.4 the edges' images, rigorously, lie on one side: x = 1 - 1.4 x0^2 + y > 0 for |x0| <= 0.7, |y| <= 0.22 */
    const int one_side = at14.edge[0][0].lo > 0.0 && at14.edge[0][1].lo > 0.0 && at14.edge[1][0].lo > 0.0 && at14.edge[1][1].lo > 0.0;
    gb_check ch = {"-", "-", "Henon's map (x, y) -> (1 - a x^2 + y, 0.3 x): the sets [-0.7, -0.1] and [0.1, 0.7] x [-0.22, 0.22]",
                   "a = 6: a full horseshoe (Devaney & Nitecki 1979: a > (5 + 2 sqrt 5)(1.3)^2 / 4 = 4.0), h_top = ln 2 (Friedland & "
                   "Milnor's upper bound); a = 1.4: no horseshoe on these sets",
                   "proof: at a = 6 all 4 relations, h_top >= ln 2 to the last ulp; at a = 1.4 none, every edge's image proved on "
                   "the side x > 0 (a negative control with teeth)"};
    gb_check_true(&ch, !status && at6.entropy >= log(2.0) * (1 - 4 * DBL_EPSILON) && at6.entropy <= log(2.0) && none && one_side &&
                           at14.entropy == 0.0,
                  "a = 6: h_top >= %.17g; a = 1.4: %s relation, edges' images from %.6g up, bound %g%s%s", at6.entropy, none ? "no" : "some",
                  fmin(fmin(at14.edge[0][0].lo, at14.edge[0][1].lo), fmin(at14.edge[1][0].lo, at14.edge[1][1].lo)), at14.entropy,
                  status ? ": " : "", status ? gb_error_message() : "");

    /* Collatz–Wielandt against known spectral radii */
    const int full[4] = {1, 1, 1, 1}, golden[4] = {1, 1, 1, 0}, nilpotent[4] = {0, 1, 0, 0};
    double l_full = NAN, r_full = NAN, l_golden = NAN, r_golden = NAN, l_nil = NAN, r_nil = NAN; /* NaN where a call failed */
    status = gb_proof_cover_entropy_bound(full, 2, &l_full, &r_full) || gb_proof_cover_entropy_bound(golden, 2, &l_golden, &r_golden) ||
             gb_proof_cover_entropy_bound(nilpotent, 2, &l_nil, &r_nil);
    const double phi = 0.5 * (1.0 + sqrt(5.0));
    gb_check ce = {"-", "-", "the entropy bound ln rho(A) from a transition matrix (Collatz-Wielandt on Arb)",
                   "the full 2-shift rho = 2, the golden mean shift rho = (1 + sqrt 5)/2, a nilpotent matrix rho = 0",
                   "a lower bound never above the exact value (4 ulps for the doubles' rounding) and within 1e-12 of it"};
    gb_check_true(&ce, !status && r_full <= 2.0 && r_full >= 2.0 - 1e-12 && l_full <= log(2.0) * (1 + 4 * DBL_EPSILON) &&
                           r_golden <= phi * (1 + 4 * DBL_EPSILON) && r_golden >= phi - 1e-12 && l_golden >= log(phi) - 1e-12 &&
                           l_golden <= log(phi) * (1 + 4 * DBL_EPSILON) && l_nil == 0.0,
                  "full %.17g (ln %.17g), golden %.17g (ln %.17g), nilpotent %.3g (ln %.3g)", r_full, l_full, r_golden, l_golden, r_nil,
                  l_nil);
}

/* Hénon's map directly, in long double: (x, y) ↦ (1 − 1.4 x² + y, 0.3 x). */
static void henon_direct(long double p[2])
{
    const long double x = p[0];
    p[0] = 1.0L - 1.4L * x * x + p[1], p[1] = 0.3L * x;
}

/* The classical frame's affine map and its inverse, in long double, from its rationals. */
static const long double frame_o[2] = {3157.0L / 5000, 947.0L / 5000};
static const long double frame_F[2][2] = {{-1.0L, -13.0L / 25}, {39.0L / 250, -1.0L}};

static void frame_to_plane(const double v[2], long double p[2])
{
    for (int i = 0; i < 2; i++) p[i] = frame_o[i] + frame_F[i][0] * v[0] + frame_F[i][1] * v[1];
}

static void plane_to_frame(const long double p[2], long double v[2])
{
    const long double det = frame_F[0][0] * frame_F[1][1] - frame_F[0][1] * frame_F[1][0];
    const long double d0 = p[0] - frame_o[0], d1 = p[1] - frame_o[1];
    v[0] = (frame_F[1][1] * d0 - frame_F[0][1] * d1) / det, v[1] = (frame_F[0][0] * d1 - frame_F[1][0] * d0) / det;
}

static long double rational_value(gb_proof_rational r) { return r.den ? (long double)r.num / (long double)r.den : 0.0L; }

static void test_henon_classical(void)
{
    gb_proof_field g;
    gb_proof_cover_def def;
    int status = gb_proof_cover_henon_classical(&g, &def);
    /* 1. the framed map's exact coefficients against the map read through the frame directly */
    double worst = 0.0;
    for (int k = 0; k < 400 && !status; k++) {
        const double v[2] = {-0.6 + 1.2 * ((k * 37) % 400) / 399.0, -0.3 + 0.6 * ((k * 101) % 400) / 399.0};
        long double p[2], direct[2];
        frame_to_plane(v, p);
        henon_direct(p);
        plane_to_frame(p, direct);
        for (int i = 0; i < 2; i++) {
            long double sum = rational_value(g.c[i]);
            for (int j = 0; j < 2; j++) sum += rational_value(g.L[i][j]) * v[j];
            sum += rational_value(g.Q[i][0][0]) * v[0] * v[0] + rational_value(g.Q[i][0][1]) * v[0] * v[1] +
                   rational_value(g.Q[i][1][1]) * v[1] * v[1];
            worst = fmax(worst, (double)fabsl(sum - direct[i]));
        }
    }
    gb_check cf = {"-", "-", "Henon's map (a = 7/5, b = 3/10) read in the classical frame: its exact quadratic coefficients",
                   "the map through the frame directly, F^-1 (H(o + F v) - o), at 400 points of [-0.6, 0.6] x [-0.3, 0.3]",
                   "1e-15: both in long double (64-bit mantissa), values of order 1"};
    gb_check_true(&cf, !status && worst <= 1e-15, "largest difference %.3g%s%s", worst, status ? ": " : "", status ? gb_error_message() : "");

    /* 2. the horseshoe: every relation, the bound, and the enclosures holding the floats */
    gb_proof_cover_result r;
    if (!status) status = gb_proof_cover(&def, &r);
    int relations = 0, held = 0, tried = 0;
    for (size_t i = 0; !status && i < def.sets; i++) {
        for (size_t j = 0; j < def.sets; j++) relations += r.covers[i][j];
        for (int k = 0; k <= 200; k++) { /* points of the set and of its two edges, iterated 7 times in long double */
            const double s = def.strip.lo + (def.strip.hi - def.strip.lo) * k / 200.0;
            const double u_in = def.set_u[i].lo + (def.set_u[i].hi - def.set_u[i].lo) * ((k * 53) % 201) / 200.0;
            const double at[3] = {def.set_u[i].lo, def.set_u[i].hi, u_in};
            for (int e = 0; e < 3; e++) {
                long double p[2], v[2];
                frame_to_plane((const double[2]){at[e], s}, p);
                for (int n = 0; n < def.iterates; n++) henon_direct(p);
                plane_to_frame(p, v);
                const int inside = e < 2 ? holds(r.edge[i][e], (double)v[0]) : holds(r.image_s[i], (double)v[1]);
                tried++, held += inside;
            }
        }
    }
    const double ln5_7 = log(5.0) / 7.0;
    gb_check ch = {"-", "-", "Henon's map at the classical a = 1.4, b = 0.3: H^7 on five parallelograms of the frame (a search's sets)",
                   "a full horseshoe on 5 symbols: h_top(H^7) >= ln 5, h_top(H) >= ln 5 / 7 = 0.22992; Friedland & Milnor: "
                   "h_top <= ln 2; the published lower bounds 0.4320 and 0.46469 lie above it; each edge's enclosure holds "
                   "the floats' H^7 of 201 of its points, each strip's the images along of 201 points inside",
                   "exact for the relations; the bound within 8 ulps below ln 5 / 7 (Arb's rounding of ln rho and of the "
                   "division); the floats' iterates inside (their error ~1e-16 against enclosures ~1e-3 from the ends)"};
    gb_check_true(&ch, !status && relations == 25 && r.entropy_map <= ln5_7 && r.entropy_map >= ln5_7 * (1 - 8 * DBL_EPSILON) &&
                           r.entropy_map <= log(2.0) && held == tried && tried == 5 * 201 * 3,
                  "%d of 25 relations, h_top(H) >= %.17g (ln 5 / 7 = %.17g), %d of %d floats inside, %ld pieces, %.3g s%s%s", relations,
                  r.entropy_map, ln5_7, held, tried, r.pieces, r.seconds, status ? ": " : "", status ? gb_error_message() : "");

    /* 3. teeth: the strip narrowed below the images' reach, and the set at the fixed point moved right of where the
     * edges' images reach */
    gb_proof_cover_def narrow = def, moved = def;
    narrow.strip = (gb_proof_interval){-0.02, 0.02};
    moved.set_u[4] = (gb_proof_interval){0.02, 0.02573};
    gb_proof_cover_result rn, rm;
    int s2 = gb_proof_cover(&narrow, &rn);
    if (!s2) s2 = gb_proof_cover(&moved, &rm);
    int narrow_relations = 0, narrow_kept = 0, into_moved = 0;
    for (size_t i = 0; !s2 && i < def.sets; i++) {
        for (size_t j = 0; j < def.sets; j++) narrow_relations += i < 4 && rn.covers[i][j], narrow_kept += i == 4 && rn.covers[i][j];
        into_moved += rm.covers[i][4];
    }
    /* why the moved set is not covered: set 0's low edge has a point whose float image lands inside its new range */
    double lands = NAN;
    for (int k = 0; k <= 2000 && isnan(lands); k++) {
        const double s = def.strip.lo + (def.strip.hi - def.strip.lo) * k / 2000.0;
        long double p[2], v[2];
        frame_to_plane((const double[2]){def.set_u[0].lo, s}, p);
        for (int n = 0; n < def.iterates; n++) henon_direct(p);
        plane_to_frame(p, v);
        if ((double)v[0] > moved.set_u[4].lo && (double)v[0] < moved.set_u[4].hi) lands = s;
    }
    gb_check ct = {"-", "-", "negative controls of the classical horseshoe: the strip narrowed to [-0.02, 0.02], and U4 moved to "
                   "[0.02, 0.02573]", "no relation from U0 ... U3 with the narrowed strip (their images reach s = 0.026 ... 0.032; "
                   "U4's, 0.019, keeps its 5); no set proved to cover the moved U4, into which a point of U0's low edge falls",
                   "exact: 0 relations from U0 ... U3, the first failure named, 0 relations into the moved set"};
    gb_check_true(&ct, !s2 && narrow_relations == 0 && narrow_kept == 5 && rn.failure[0] && into_moved == 0 && !isnan(lands),
                  "narrowed: %d relations from U0 ... U3, %d from U4 (first failure: %s); moved: %d into it, U0's low edge at s = %.5f "
                  "lands inside it%s%s", narrow_relations, narrow_kept, rn.failure, into_moved, lands, s2 ? ": " : "",
                  s2 ? gb_error_message() : ""); /* the moved set's own relations are not asserted: not what the control tests */
}

static void test_definitions_refused(void)
{
    const gb_proof_field f = gb_proof_flow_rossler(1, 5, 1, 5, 57, 10), henon = gb_proof_cover_henon(7, 5, 3, 10);
    gb_proof_cover_def good = gb_proof_cover_def_default();
    good.section = gb_proof_flow_def_default(&f);
    good.u = 1, good.s = 2, good.strip = (gb_proof_interval){0.028, 0.034};
    good.sets = 2, good.set_u[0] = (gb_proof_interval){-8.4, -7.6}, good.set_u[1] = (gb_proof_interval){-5.7, -4.6};
    struct {
        const char *what, *must;
        gb_proof_cover_def def;
    } bad[9];
    for (int k = 0; k < 9; k++) bad[k].def = good;
    bad[0].what = "overlapping sets", bad[0].must = "overlap", bad[0].def.set_u[1] = (gb_proof_interval){-7.8, -4.6};
    bad[1].what = "iterates 0", bad[1].must = "iterates", bad[1].def.iterates = 0;
    bad[2].what = "the plane's u on the section's coordinate", bad[2].must = "plane coordinates", bad[2].def.u = 0;
    bad[3].what = "a map of the plane given a flow in R^3", bad[3].must = "dimension", bad[3].def.kind = GB_PROOF_MAP_QUADRATIC,
    bad[3].def.map = &f;
    bad[4].what = "a trap for a map of the plane", bad[4].must = "trap", bad[4].def.kind = GB_PROOF_MAP_QUADRATIC,
    bad[4].def.map = &henon, bad[4].def.u = 0, bad[4].def.s = 1, bad[4].def.trap = 1;
    bad[5].what = "a strip with lo > hi", bad[5].must = "strip", bad[5].def.strip = (gb_proof_interval){0.034, 0.028};
    bad[6].what = "order 3", bad[6].must = "order", bad[6].def.section.order = 3;
    bad[7].what = "9 sets", bad[7].must = "sets", bad[7].def.sets = 9;
    bad[8].what = "no cut along", bad[8].must = "strip pieces", bad[8].def.strip_pieces = 0;
    int refused = 0;
    char first[300] = "";
    for (int k = 0; k < 9; k++) {
        gb_proof_cover_result r;
        const int status = gb_proof_cover(&bad[k].def, &r);
        const int ok = status == GB_EDOM && strstr(gb_error_message(), bad[k].must) && strstr(gb_error_message(), "allowed");
        refused += ok;
        if (!ok && !first[0]) snprintf(first, sizeof first, "; %s gave %d: %s", bad[k].what, status, gb_error_message());
    }
    /* a box off the section, and a flow time that is not a multiple of 2^-30 */
    gb_proof_flow_def d = gb_proof_flow_def_default(&f);
    gb_proof_interval box[3] = {{0.1, 0.1}, {-8.0, -8.0}, {0.03, 0.03}}, image[3];
    gb_proof_flow_crossing r;
    const int off = gb_proof_flow_section_map(&d, box, &r) == GB_EDOM && strstr(gb_error_message(), "not on the section");
    box[0] = (gb_proof_interval){0, 0};
    const int time = gb_proof_flow_time(&d, box, 0.1, image) == GB_EDOM && strstr(gb_error_message(), "2^-30");
    /* a frame that is singular, and one whose map's coefficients would not fit a long */
    gb_proof_field framed;
    const gb_proof_rational o[2] = {{1, 2}, {1, 3}}, singular[2][2] = {{{1, 1}, {2, 1}}, {{2, 1}, {4, 1}}};
    const gb_proof_rational fine[2][2] = {{{1, 1}, {1, 3037000493}}, {{1, 3037000453}, {1, 1}}};
    const int frames = gb_proof_cover_henon_framed(7, 5, 3, 10, o, singular, &framed) == GB_EDOM &&
                       strstr(gb_error_message(), "singular") && strstr(gb_error_message(), "allowed") &&
                       gb_proof_cover_henon_framed(7, 5, 3, 10, o, fine, &framed) == GB_EDOM && strstr(gb_error_message(), "long") &&
                       strstr(gb_error_message(), "allowed");
    gb_check c = {"-", "-", "covering relations and the rigorous integrator: definitions out of range",
                  "GB_EDOM naming the field and its allowed range", "exact"};
    gb_check_true(&c, refused == 9 && off && time && frames,
                  "%d of 9 definitions refused, a box off the plane %s, t = 0.1 %s, a singular frame and one too fine %s%s", refused,
                  off ? "refused" : "accepted", time ? "refused" : "accepted", frames ? "refused" : "NOT both refused", first);
}

int verify_register_s7_covering(void)
{
    static const verify_test tests[] = {
        {"covering: the rigorous integrator against a linear field's closed form", test_linear_flow,
         "the Taylor-Lohner integrator on Arb encloses exact solutions and does not wrap a turning box"},
        {"covering: Roessler's return map against GSL", test_rossler_against_gsl,
         "the rigorous return map of Roessler's flow holds an independent high-accuracy integration"},
        {"covering: the C1 step and Roessler's period-1 orbit", test_c1_and_orbit,
         "the return map's derivative against a closed form and GSL, and a periodic orbit proved by Krawczyk's operator"},
        {"covering: negative controls and the entropy bound", test_covering_controls,
         "covering relations that are false are refuted or refused, and the entropy bound meets known spectral radii"},
        {"covering: the classical Henon map in a frame", test_henon_classical,
         "a horseshoe of the classical Henon map's 7th iterate on parallelograms, its framed map and enclosures against floats"},
        {"covering: definitions out of range", test_definitions_refused, NULL},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Proved on Arb's balls: a rigorous integrator and covering relations", tests);
}
