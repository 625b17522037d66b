/* Proved on Arb's balls: the unstable manifold of a saddle of a quadratic map of the plane, parametrised with a proved
 * tail, and the crossings of an unstable and a stable manifold, each proved transverse and no other (gb_proof_manifold,
 * the first pieces of a trellis).
 *
 * Oracles, none sharing code with what they check:
 * - a map whose manifolds are known in closed form: f(x, y) = (2x, y/4 + x²) has W^u(0) = {y = x²/3.75}, parametrised
 *   by P(s) = (±s, s²/3.75) (P(2s) = f(P(s))), and W^s(0) the y-axis; its eigenvalues are 2 and 1/4, and the two
 *   manifolds cross only at the fixed point;
 * - the classical Hénon map: the number of crossings of two arcs of its fixed point's manifolds against a count of
 *   the crossings of polylines through 40 000 and 8 000 points of the two arcs (segment against segment, in doubles),
 *   and every crossing's point iterated 12 times by Hénon's formula in doubles must come within 1e-5 of the fixed
 *   point (a point of W^s; the distance shrinks by 0.156 an iterate, the rounding grows by 1.92);
 * - the tail's bound: parametrisations of orders 4 and 8, whose tails are large, must hold order 30's value at the
 *   disc's edge;
 * - negative controls with teeth: an attracting fixed point (no saddle), a tail whose map is no contraction (order 2
 *   on a disc of radius 20), manifolds of two different fixed points, and an arc that ends on a crossing are each
 *   refused, with nothing claimed;
 * - the definitions' ranges: each bad field refused with GB_EDOM naming it;
 * - two crossings of f(U) with a stable arc far out (t ≈ −3.4·10⁸), 4.3e-14 apart along it: their parameters found
 *   by Newton in mpmath at 80 digits on a parametrisation of its own (references/henon_crossings.py: coefficients
 *   to order 60 from the same recursion, the arcs reached by iterating Hénon's map and its inverse), which the
 *   enclosures must hold, apart;
 * - the trellis's walks counted from below in 63-bit integers, against closed forms counted exactly by FLINT: the
 *   golden mean graph's closed walks from its loop node are Fibonacci numbers, k loops on one node give kⁿ, and a
 *   2-cycle gives 1 or 0 by the parity of n. */
#include "gb_check.h"
#include "gb_error.h"
#include "gb_proof_manifold.h"
#include "gb_proof_manifold_internal.h"
#include "gb_proof_trellis.h"
#include "gb_proof_trellis_graph_internal.h"
#include "verify_sections.h"

#include <cjson/cJSON.h>
#include <flint/fmpz.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* f(x, y) = (2x, y/4 + x²) and its inverse (x/2, 4y − x²). */
static void exact_maps(gb_proof_field *f, gb_proof_field *g)
{
    memset(f, 0, sizeof *f), memset(g, 0, sizeof *g);
    f->dimension = g->dimension = 2;
    f->L[0][0] = (gb_proof_rational){2, 1}, f->L[1][1] = (gb_proof_rational){1, 4},
    f->Q[1][0][0] = (gb_proof_rational){1, 1};
    g->L[0][0] = (gb_proof_rational){1, 2}, g->L[1][1] = (gb_proof_rational){4, 1},
    g->Q[1][0][0] = (gb_proof_rational){-1, 1};
}

/* The distance of x from the interval (0 inside). */
static double off(double x, gb_proof_interval i) { return x < i.lo ? i.lo - x : x > i.hi ? x - i.hi : 0.0; }

static void test_exact(void)
{
    gb_proof_field f, g;
    exact_maps(&f, &g);
    gb_proof_manifold_def def = gb_proof_manifold_def_default();
    def.map = &f, def.fixed[0] = 0.01, def.fixed[1] = -0.02;
    gb_proof_manifold *P = NULL, *R = NULL;
    int status = gb_proof_manifold_create(&def, &P);
    def.map = &g;
    if (!status) status = gb_proof_manifold_create(&def, &R);
    double worst = 0.0, worst_r = 0.0;
    int eigen = 0;
    gb_proof_manifold_crossings_result x = {0};
    if (!status) {
        gb_proof_manifold_info ip, ir;
        gb_proof_manifold_info_of(P, &ip), gb_proof_manifold_info_of(R, &ir);
        eigen = off(2.0, ip.lambda) == 0.0 && off(0.25, ip.other) == 0.0 && off(4.0, ir.lambda) == 0.0 &&
                off(0.5, ir.other) == 0.0;
        gb_proof_interval z[2], d[2], dr[2];
        status = gb_proof_manifold_enclose(P, (gb_proof_interval){0.0, 0.0}, z, d); /* the eigenvectors' orientations */
        if (!status) status = gb_proof_manifold_enclose(R, (gb_proof_interval){0.0, 0.0}, z, dr);
        const double sp = d[0].lo > 0.0 ? 1.0 : -1.0, sr = dr[1].lo > 0.0 ? 1.0 : -1.0;
        static const double s[] = {0.1, 0.4, -0.45, 3.0, -5.0, 17.0, 100.0};
        for (size_t k = 0; k < sizeof s / sizeof *s && !status; k++) {
            gb_proof_interval zp[2], zr[2];
            status = gb_proof_manifold_enclose(P, (gb_proof_interval){s[k], s[k]}, zp, NULL);
            if (!status) status = gb_proof_manifold_enclose(R, (gb_proof_interval){s[k], s[k]}, zr, NULL);
            if (status) break;
            const double x0 = sp * s[k], y0 = s[k] * s[k] / 3.75, ry = sr * s[k];
            worst = fmax(worst, fmax(off(x0, zp[0]) / (1.0 + fabs(x0)), off(y0, zp[1]) / (1.0 + y0)));
            worst_r = fmax(worst_r, fmax(off(0.0, zr[0]), off(ry, zr[1]) / (1.0 + fabs(ry))));
        }
        const gb_proof_manifold_crossings_def cd = {{-20.0, 20.5}, {-3.0, 3.5}, 0.05, 40};
        if (!status) status = gb_proof_manifold_crossings(P, R, &cd, &x);
    }
    const int crossed =
        !status && x.proved && x.count == 1 && off(0.0, x.crossings[0].s) == 0.0 && off(0.0, x.crossings[0].t) == 0.0;
    gb_check c = {
        "-", "-",
        "f(x, y) = (2x, y/4 + x^2): W^u(0) parametrised on Arb (order 30, disc of radius 1), P(s) at s = 0.1 "
        "... 100 (inside the disc and by iterates), W^s(0) likewise, and their crossings over s in [-20, 20.5], "
        "t in [-3, 3.5]",
        "closed forms: P(s) = (+-s, s^2/3.75), R(t) = (0, +-t), eigenvalues 2 and 1/4; the manifolds cross at "
        "the fixed point alone",
        "the closed form in doubles within 1e-14 relative of each enclosure (its rounding); the count exact"};
    gb_check_true(
        &c, !status && eigen && worst <= 1e-14 && worst_r <= 1e-14 && crossed,
        "eigenvalues enclosed %d; P off its closed form by %.2g, R by %.2g (relative); %zu crossing(s), proved "
        "%d%s%s",
        eigen, worst, worst_r, x.count, x.proved, status ? ": " : "", status ? gb_error_message() : "");
    gb_proof_manifold_crossings_free(&x);
    gb_proof_manifold_free(P), gb_proof_manifold_free(R);
}

/* The classical map's manifolds at its fixed point in the attractor (order 30, σ = 1, ρ = 1). */
static int henon_manifolds(double gx, double gy, gb_proof_manifold **P, gb_proof_manifold **R)
{
    static gb_proof_field f, g;
    int status = gb_proof_manifold_henon(7, 5, 3, 10, &f, &g);
    gb_proof_manifold_def def = gb_proof_manifold_def_default();
    def.fixed[0] = gx, def.fixed[1] = gy;
    def.map = &f;
    *P = *R = NULL;
    if (!status) status = gb_proof_manifold_create(&def, P);
    def.map = &g;
    if (!status) status = gb_proof_manifold_create(&def, R);
    return status;
}

/* Crossings of two polylines through n points of P over s and m points of R over t (the enclosures' middles). */
static long polyline_crossings(const gb_proof_manifold *P, const gb_proof_manifold *R, gb_proof_interval s,
                               gb_proof_interval t, int n, int m)
{
    double(*a)[2] = malloc((size_t)n * sizeof *a), (*b)[2] = malloc((size_t)m * sizeof *b);
    long count = a && b ? 0 : -1;
    for (int k = 0; k < n && count >= 0; k++) {
        const double u = s.lo + (s.hi - s.lo) * k / (n - 1);
        gb_proof_interval z[2];
        if (gb_proof_manifold_enclose(P, (gb_proof_interval){u, u}, z, NULL)) count = -1;
        a[k][0] = 0.5 * (z[0].lo + z[0].hi), a[k][1] = 0.5 * (z[1].lo + z[1].hi);
    }
    for (int k = 0; k < m && count >= 0; k++) {
        const double u = t.lo + (t.hi - t.lo) * k / (m - 1);
        gb_proof_interval z[2];
        if (gb_proof_manifold_enclose(R, (gb_proof_interval){u, u}, z, NULL)) count = -1;
        b[k][0] = 0.5 * (z[0].lo + z[0].hi), b[k][1] = 0.5 * (z[1].lo + z[1].hi);
    }
    for (int i = 0; i + 1 < n && count >= 0; i++)
        for (int j = 0; j + 1 < m; j++) {
            const double *p0 = a[i], *p1 = a[i + 1], *q0 = b[j], *q1 = b[j + 1];
            if (fmax(p0[0], p1[0]) < fmin(q0[0], q1[0]) || fmax(q0[0], q1[0]) < fmin(p0[0], p1[0]) ||
                fmax(p0[1], p1[1]) < fmin(q0[1], q1[1]) || fmax(q0[1], q1[1]) < fmin(p0[1], p1[1]))
                continue;
            const double d0 = p1[0] - p0[0], d1 = p1[1] - p0[1], e0 = q1[0] - q0[0], e1 = q1[1] - q0[1];
            const double det = d0 * e1 - d1 * e0;
            if (det == 0.0) continue;
            const double w0 = q0[0] - p0[0], w1 = q0[1] - p0[1];
            const double u = (w0 * e1 - w1 * e0) / det, v = (w0 * d1 - w1 * d0) / det;
            if (u >= 0.0 && u < 1.0 && v >= 0.0 && v < 1.0) count++;
        }
    free(a), free(b);
    return count;
}

static void test_henon(void)
{
    gb_proof_manifold *P, *R;
    int status = henon_manifolds(0.63, 0.19, &P, &R);
    gb_proof_manifold_crossings_result x = {0};
    const gb_proof_manifold_crossings_def cd = {{-26.0, 26.0}, {-3.0, 3.0}, 0.01, 40};
    if (!status) status = gb_proof_manifold_crossings(P, R, &cd, &x);
    long poly = -1;
    if (!status) poly = polyline_crossings(P, R, cd.s, cd.t, 40000, 8000);
    /* the tail's bound has teeth: low orders' enclosures at the disc's edge (s = ±ρ/2) hold order 30's value */
    int tails = 0;
    for (int order = 4; order <= 8 && !status; order += 4) {
        gb_proof_field f, g;
        gb_proof_manifold_henon(7, 5, 3, 10, &f, &g);
        gb_proof_manifold_def def = gb_proof_manifold_def_default();
        def.map = &f, def.fixed[0] = 0.63, def.fixed[1] = 0.19, def.order = order;
        gb_proof_manifold *low = NULL;
        status = gb_proof_manifold_create(&def, &low);
        for (int side = -1; side <= 1 && !status; side += 2) {
            gb_proof_interval zl[2], zh[2];
            status = gb_proof_manifold_enclose(low, (gb_proof_interval){0.5 * side, 0.5 * side}, zl, NULL);
            if (!status) status = gb_proof_manifold_enclose(P, (gb_proof_interval){0.5 * side, 0.5 * side}, zh, NULL);
            tails += !status && off(0.5 * (zh[0].lo + zh[0].hi), zl[0]) == 0.0 &&
                     off(0.5 * (zh[1].lo + zh[1].hi), zl[1]) == 0.0;
        }
        gb_proof_manifold_free(low);
    }
    int stable = 0;
    double farthest = 0.0;
    gb_proof_manifold_info ip = {0};
    if (!status) gb_proof_manifold_info_of(P, &ip);
    const double px = 0.5 * (ip.fixed[0].lo + ip.fixed[0].hi), py = 0.5 * (ip.fixed[1].lo + ip.fixed[1].hi);
    for (size_t k = 0; k < x.count; k++) {
        double u = 0.5 * (x.crossings[k].point[0].lo + x.crossings[k].point[0].hi),
               v = 0.5 * (x.crossings[k].point[1].lo + x.crossings[k].point[1].hi);
        for (int it = 0; it < 12; it++) {
            const double nu = 1.0 - 1.4 * u * u + v;
            v = 0.3 * u, u = nu;
        }
        const double dist = hypot(u - px, v - py);
        farthest = fmax(farthest, dist);
        stable += dist < 1e-5;
    }
    gb_check c = {
        "-", "-",
        "the classical Henon map (7/5, 3/10): the crossings of its fixed point's W^u over s in [-26, 26] and "
        "W^s over t in [-3, 3] (parametrised with |P'(0)| = 1), each proved transverse, and no other",
        "a count of the crossings of polylines through 40 000 and 8 000 of the arcs' points; every crossing's "
        "point iterated 12 times in doubles comes within 1e-5 of the fixed point (a point of W^s); the "
        "parametrisations of orders 4 and 8 (their tails 1e-2 and 4e-6) hold order 30's at s = +-1/2",
        "the count exact; 1e-5 from 0.156^12 |q - p| plus 1.92^12 times the doubles' rounding"};
    gb_check_true(&c,
                  !status && x.proved && (long)x.count == poly && x.count > 1 && stable == (int)x.count && tails == 4,
                  "orders 4 and 8 hold order 30 at s = +-1/2: %d of 4; %zu crossings proved (complete %d, %zu and %zu "
                  "pieces, %zu pairs met, %.2f s), the polylines cross %ld "
                  "times; %d of %zu iterate to the fixed point (farthest %.2g)%s%s%s",
                  tails, x.count, x.proved, x.pieces_s, x.pieces_t, x.pairs, x.seconds, poly, stable, x.count, farthest,
                  x.failure[0] ? "; " : "", x.failure, status ? gb_error_message() : "");
    gb_proof_manifold_crossings_free(&x);
    gb_proof_manifold_free(P), gb_proof_manifold_free(R);
}

static void test_controls(void)
{
    char first[300] = "";
    /* an attracting fixed point: Hénon at a = 1/10, b = 3/10, the fixed point near (1.217, 0.365) */
    gb_proof_field f, g;
    gb_proof_manifold_henon(1, 10, 3, 10, &f, &g);
    gb_proof_manifold_def def = gb_proof_manifold_def_default();
    def.map = &f, def.fixed[0] = 1.2, def.fixed[1] = 0.36;
    gb_proof_manifold *m = NULL;
    const int sink = gb_proof_manifold_create(&def, &m) == GB_ENUMERIC && !m;
    if (!sink) snprintf(first, sizeof first, "; the sink was not refused");
    gb_proof_manifold_free(m);
    /* order 2 on a disc of radius 20: the tail's map is no contraction */
    gb_proof_manifold_henon(7, 5, 3, 10, &f, &g);
    def.map = &f, def.fixed[0] = 0.63, def.fixed[1] = 0.19, def.order = 2, def.radius = 20.0, def.scale = 0.2;
    const int loose =
        gb_proof_manifold_create(&def, &m) == GB_ENUMERIC && !m && strstr(gb_error_message(), "contraction");
    if (!loose && !first[0]) snprintf(first, sizeof first, "; order 2 on radius 20 was not refused");
    gb_proof_manifold_free(m);
    /* the classical map's two fixed points: P of one and R of the other */
    gb_proof_manifold *P = NULL, *R = NULL, *P2 = NULL, *R2 = NULL;
    int status = henon_manifolds(0.63, 0.19, &P, &R);
    if (!status) status = henon_manifolds(-1.13, -0.34, &P2, &R2);
    gb_proof_manifold_crossings_result x = {0};
    const gb_proof_manifold_crossings_def cd = {{-7.2, 7.2}, {-1.5, 1.5}, 0.01, 40};
    const int apart = !status && gb_proof_manifold_crossings(P, R2, &cd, &x) == GB_EDOM && x.count == 0;
    if (!apart && !first[0]) snprintf(first, sizeof first, "; two fixed points' manifolds were not refused");
    /* the arcs [−7.2, 7.2] × [−1.5, 1.5] (as many crossings as their polylines, 5 when written); ending the arc on
     * one leaves it unplaced */
    size_t whole = 0;
    int ended = 0;
    if (!status && gb_proof_manifold_crossings(P, R, &cd, &x) == GB_OK && x.proved) {
        whole = (long)x.count == polyline_crossings(P, R, cd.s, cd.t, 20000, 4000) ? x.count : 0;
        gb_proof_manifold_crossings_def cut = cd;
        cut.s.hi = 0.5 * (x.crossings[x.count - 1].s.lo + x.crossings[x.count - 1].s.hi);
        gb_proof_manifold_crossings_free(&x);
        ended = gb_proof_manifold_crossings(P, R, &cut, &x) == GB_OK && !x.proved && strstr(x.failure, "end") != NULL;
    }
    if (!ended && !first[0])
        snprintf(first, sizeof first, "; the arc ending on a crossing was not refused (%s)", x.failure);
    gb_proof_manifold_crossings_free(&x);
    gb_proof_manifold_free(P), gb_proof_manifold_free(R), gb_proof_manifold_free(P2), gb_proof_manifold_free(R2);
    gb_check c = {"-", "-", "manifolds and crossings: negative controls",
                  "an attracting fixed point refused (not a saddle); a tail whose map is no contraction refused; the "
                  "manifolds of two fixed points refused; an arc "
                  "ending on a crossing gives no complete list",
                  "exact"};
    gb_check_true(&c, !status && sink && loose && apart && whole > 1 && ended,
                  "sink refused %d, no contraction refused %d, two fixed points refused %d, %zu crossings on the whole "
                  "arcs, the cut arc refused "
                  "%d%s%s%s",
                  sink, loose, apart, whole, ended, first, status ? ": " : "", status ? gb_error_message() : "");
}

static void test_refused(void)
{
    gb_proof_field f, g, three;
    gb_proof_manifold_henon(7, 5, 3, 10, &f, &g);
    memset(&three, 0, sizeof three);
    three.dimension = 3;
    gb_proof_manifold_def good = gb_proof_manifold_def_default();
    good.map = &f, good.fixed[0] = 0.63, good.fixed[1] = 0.19;
    enum { BAD = 10 };
    gb_proof_manifold_def bad[BAD];
    static const char *const what[BAD] = {"map NULL", "dimension 3", "guess NaN", "order 1",    "order 81",
                                          "scale 0",  "scale 1e4",   "radius 0",  "radius 1e4", "precision 10"};
    for (int k = 0; k < BAD; k++) bad[k] = good;
    bad[0].map = NULL, bad[1].map = &three, bad[2].fixed[1] = NAN, bad[3].order = 1, bad[4].order = 81;
    bad[5].scale = 0.0, bad[6].scale = 1e4, bad[7].radius = 0.0, bad[8].radius = 1e4, bad[9].precision = 10;
    int refused = 0;
    char first[300] = "";
    for (int k = 0; k < BAD; k++) {
        gb_proof_manifold *m = NULL;
        const int status = gb_proof_manifold_create(&bad[k], &m);
        const int ok = status == GB_EDOM && !m;
        refused += ok;
        if (!ok && !first[0]) snprintf(first, sizeof first, "; %s gave %d", what[k], status);
        gb_proof_manifold_free(m);
    }
    gb_proof_manifold *P = NULL, *R = NULL;
    const int made = henon_manifolds(0.63, 0.19, &P, &R) == GB_OK;
    enum { BAD_X = 6 };
    const gb_proof_manifold_crossings_def good_x = {{-7.2, 7.2}, {-1.5, 1.5}, 0.01, 40};
    gb_proof_manifold_crossings_def bx[BAD_X];
    for (int k = 0; k < BAD_X; k++) bx[k] = good_x;
    bx[0].s = (gb_proof_interval){1.0, -1.0}, bx[1].t.hi = NAN, bx[2].width = 0.0, bx[3].width = 2.0, bx[4].depth = 0;
    bx[5].depth = 61;
    int refused_x = 0;
    for (int k = 0; k < BAD_X && made; k++) {
        gb_proof_manifold_crossings_result x;
        const int status = gb_proof_manifold_crossings(P, R, &bx[k], &x);
        refused_x += status == GB_EDOM && x.count == 0;
        if (status == GB_OK) gb_proof_manifold_crossings_free(&x);
    }
    gb_proof_manifold_crossings_result x = {0};
    const int good_runs = made && gb_proof_manifold_crossings(P, R, &good_x, &x) == GB_OK && x.proved;
    gb_proof_manifold_crossings_free(&x);
    gb_proof_manifold_free(P), gb_proof_manifold_free(R);
    gb_check c = {"-", "-", "gb_proof_manifold and gb_proof_manifold_crossings: definitions out of range",
                  "GB_EDOM naming the field and what is allowed; the unchanged definitions run", "exact"};
    gb_check_true(&c, refused == BAD && refused_x == BAD_X && good_runs,
                  "%d of %d and %d of %d refused, the good ones %s%s", refused, BAD, refused_x, BAD_X,
                  good_runs ? "run" : "FAILED", first);
}

/* The trellis of the classical Hénon map's fixed point: U = P([−100, 100]) and six stable pieces (three levels in
 * Hénon's trapping quadrilateral). The independent oracle: a float prototype (numpy polylines through points 1e-3
 * apart, their segment crossings, the same rules for faces and strips, written apart from the library) found 164
 * crossings of f(U) with W, 98 on U, 61 rectangles, 87 strips and log ρ(A) = 0.30875; its counts are recorded here.
 * Upper oracles: h_top of a real Hénon map is at most log 2 (Friedland and Milnor 1989: a polynomial automorphism of
 * degree 2), and a bound from walks of n strips is below log ρ(A). */
static const gb_proof_interval trellis_pieces[] = {
    {-117.47737615678859, -116.39095869240464}, {-108.08266374441558, -107.76368456337674},
    {-27.255405824809898, -26.878994809520172}, {-18.494845885347054, -16.771802255804623},
    {-4.2712165300901237, -2.4338584409264143}, {-0.72954289379841097, 0.5}};

static void test_trellis(void)
{
    gb_proof_manifold *P, *R;
    int status = henon_manifolds(0.63, 0.19, &P, &R);
    const gb_proof_trellis_def td = {100.0, trellis_pieces, 6, 0.01, 40, 100, 2};
    gb_proof_trellis_result t = {0};
    if (!status) status = gb_proof_trellis_entropy(P, R, &td, &t);
    gb_check c = {"-", "-",
                  "the classical Henon map: the entropy bound of the trellis U = P([-100, 100]), six stable pieces, "
                  "walks of 100 strips",
                  "a float prototype's counts (164 crossings, 98 on U, 61 rectangles, 87 strips, log rho 0.30875); "
                  "log 2 (Friedland & Milnor) and log rho(A) above the bound",
                  "the counts exact; log rho to 1e-5 (the prototype's digits); the bound (log N - log 2)/100 from the "
                  "walks' count N to 1e-9 (log N, about 29, in doubles; N even or odd)"};
    gb_check_true(
        &c,
        !status && t.proved && t.crossings == 164 && t.vertices == 98 && t.rectangles == 61 && t.strips == 87 &&
            fabs(t.log_rho - 0.30875) < 1e-5 && t.bound > 0.0 &&
            fabs(t.bound - (t.log_walks - log(2.0)) / 100.0) < 1e-9 && t.bound < t.log_rho && t.bound < log(2.0),
        "%zu crossings, %zu on U, %zu rectangles, %zu strips (%zu left), log rho %.5f, bound %.6f (%.2f s)%s%s",
        t.crossings, t.vertices, t.rectangles, t.strips, t.strips_left, t.log_rho, t.bound, t.seconds,
        t.failure[0] ? "; " : "", status ? gb_error_message() : t.failure);
    /* on the caller's thread alone: the same trellis, graph and walks */
    gb_proof_trellis_def td1 = td;
    td1.threads = 1;
    gb_proof_trellis_result t1 = {0};
    if (!status) status = gb_proof_trellis_entropy(P, R, &td1, &t1);
    gb_check same = {"-", "-", "gb_proof_trellis_entropy on two threads against one",
                     "the same definition on the caller's thread alone",
                     "exact (the tasks' results do not depend on "
                     "the threads)"};
    gb_check_true(
        &same,
        !status && t1.proved == t.proved && t1.crossings == t.crossings && t1.vertices == t.vertices &&
            t1.rectangles == t.rectangles && t1.strips == t.strips && t1.strips_left == t.strips_left &&
            t1.rectangle == t.rectangle && t1.log_walks == t.log_walks && t1.bound == t.bound,
        "one thread: %zu crossings, %zu rectangles, %zu strips, Q %zu, bound %.17g; two: %zu, %zu, %zu, Q %zu, "
        "%.17g",
        t1.crossings, t1.rectangles, t1.strips, t1.rectangle, t1.bound, t.crossings, t.rectangles, t.strips,
        t.rectangle, t.bound);
    /* refused: W not invariant (a piece whose image lies in none), pieces overlapping or out of order, and the
     * ranges; each GB_EDOM with nothing claimed */
    const gb_proof_interval lone[] = {{1.0, 2.0}}, overlapping[] = {{-1.0, 0.5}, {0.4, 2.0}},
                            reversed[] = {{1.0, 2.0}, {-1.0, 0.5}};
    gb_proof_trellis_def bad[7];
    for (int k = 0; k < 7; k++) bad[k] = td;
    bad[0].stable = lone, bad[0].stable_count = 1;
    bad[1].stable = overlapping, bad[1].stable_count = 2;
    bad[2].stable = reversed, bad[2].stable_count = 2;
    bad[3].power = 0;
    bad[4].u = 0.0;
    bad[5].stable_count = 0;
    bad[6].threads = -1;
    int refused = 0;
    for (int k = 0; k < 7 && !status; k++) {
        gb_proof_trellis_result r;
        refused += gb_proof_trellis_entropy(P, R, &bad[k], &r) == GB_EDOM && !r.proved && r.bound == 0.0;
    }
    gb_check d = {"-", "-", "gb_proof_trellis_entropy: W not invariant, pieces overlapping or out of order, ranges",
                  "GB_EDOM, nothing proved", "exact"};
    gb_check_true(&d, !status && refused == 7, "%d of 7 refused", refused);
    gb_proof_manifold_free(P), gb_proof_manifold_free(R);
}

/* Two crossings of the trellis of S = 25 600 (eleven levels of W) on W's piece [−335744736.32183778,
 * −335744725.12147218], parametrised from its middle: at s = −42167.476… and −44588.037… f(U) crosses it at
 * τ = 4.900356471684892… and 4.900356471684935…, transversally (the sines of their angles ±0.59), 4.3e-14 apart: two
 * strands of the unstable manifold, not a fold. mpmath's values: references/henon_crossings.json. */
static void test_close(void)
{
    cJSON *root = NULL;
    const cJSON *cases = gb_check_reference_cases("henon_crossings.json", "-", &root), *arc = NULL;
    struct {
        double s, tau;
    } oracle[2] = {{NAN, NAN}, {NAN, NAN}};
    int cases_read = 0;
    for (const cJSON *one = cases ? cases->child : NULL; one && cases_read < 2; one = one->next, cases_read++) {
        const cJSON *s = cJSON_GetObjectItemCaseSensitive(one, "s"),
                    *tau = cJSON_GetObjectItemCaseSensitive(one, "tau");
        if (cJSON_IsString(s) && cJSON_IsString(tau))
            oracle[cases_read].s = strtod(s->valuestring, NULL),
            oracle[cases_read].tau = strtod(tau->valuestring, NULL);
    }
    if (root) arc = cJSON_GetObjectItemCaseSensitive(root, "stable_arc");
    const double piece_lo = cJSON_GetArraySize(arc) == 2 ? cJSON_GetArrayItem(arc, 0)->valuedouble : NAN,
                 piece_hi = cJSON_GetArraySize(arc) == 2 ? cJSON_GetArrayItem(arc, 1)->valuedouble : NAN;
    cJSON_Delete(root);
    const double origin = 0.5 * piece_lo + 0.5 * piece_hi;
    gb_proof_manifold *P, *R;
    int status = isfinite(origin) && isfinite(oracle[1].tau)
                     ? henon_manifolds(0.63, 0.19, &P, &R)
                     : gb_error_set(GB_EDOM, "references/henon_crossings.json: no stable arc or fewer than two cases");
    if (!isfinite(origin) || !isfinite(oracle[1].tau)) P = R = NULL;
    gb_proof_interval t[2] = {{0}};
    int held = 0, single = 0;
    for (int k = 0; k < 2 && !status; k++) {
        const gb_proof_manifold_crossings_def d = {
            {oracle[k].s - 0.01, oracle[k].s + 0.01}, {4.90035647, 4.90035648}, 0.01, 40};
        gb_proof_manifold_crossings_result x = {0};
        status = gb_proof_manifold_crossings_arcs(P, R, &d, &origin, 1, 1, &x, NULL);
        if (!status && x.proved && x.count == 1) {
            single++, t[k] = x.crossings[0].t;
            held += off(oracle[k].tau, t[k]) == 0.0 && off(oracle[k].s, x.crossings[0].s) == 0.0;
        }
        if (!status) gb_proof_manifold_crossings_free(&x);
    }
    gb_proof_manifold_free(P), gb_proof_manifold_free(R);
    const int apart = single == 2 && t[0].hi < t[1].lo;
    gb_check c = {"-", "-",
                  "two crossings of the classical Henon map's manifolds 4.3e-14 apart along a stable arc at t = "
                  "-3.4e8",
                  "Newton in mpmath at 80 digits on a parametrisation of its own (references/henon_crossings.json)",
                  "the enclosures hold mpmath's (s, tau) and are apart (their order along W proved)"};
    gb_check_true(&c, !status && single == 2 && held == 2 && apart,
                  "%d of 2 proved alone, %d of 2 holding mpmath's, tau in [%.17g, %.17g] and [%.17g, %.17g]%s%s",
                  single, held, t[0].lo, t[0].hi, t[1].lo, t[1].hi, status ? ": " : "",
                  status ? gb_error_message() : "");
}

/* mantissa · 2^exponent against the exact count: at most it, and short by at most `slack` relative. */
static int below_within(uint64_t mantissa, long exponent, const fmpz_t exact, double slack, double *deficit)
{
    fmpz_t low;
    fmpz_init(low);
    fmpz_set_ui(low, mantissa);
    fmpz_mul_2exp(low, low, (ulong)exponent);
    const int below = fmpz_cmp(low, exact) <= 0;
    fmpz_sub(low, exact, low);
    slong e1, e2;
    const double d = fmpz_get_d_2exp(&e1, low), x = fmpz_get_d_2exp(&e2, exact);
    *deficit = fmpz_is_zero(low) ? 0.0 : ldexp(d / x, (int)(e1 - e2));
    fmpz_clear(low);
    return below && *deficit <= slack;
}

/* The walks' lower bound (trellis_walks_below) on graphs whose closed walks have closed forms. The slack: each shift
 * rounds every count down by less than one unit of a count at least 2^(bits − 1) / (the ratio of the largest count to
 * the smallest), so n shifts lose less than n · 2^(1 − bits) · ratio relative (ratio 2 for the golden mean graph, 1
 * for one node). */
static void test_walks(void)
{
    const trellis_edge golden[] = {{0, 0}, {0, 1}, {1, 0}}, cycle[] = {{0, 1}, {1, 0}};
    trellis_edge loops[1000];
    for (int k = 0; k < 1000; k++) loops[k] = (trellis_edge){0, 0};
    fmpz_t exact;
    fmpz_init(exact);
    uint64_t w;
    long e;
    double deficit, worst = 0.0;
    int passed = 0, total = 0, status = 0, exact_fit = 0;
    static const struct {
        long n;
        int bits;
    } runs[] = {{80, 63}, {1000, 63}, {1000, 24}, {20000, 40}};
    for (size_t r = 0; r < sizeof runs / sizeof runs[0]; r++) { /* (Aⁿ)_00 = F(n + 1) */
        status |= trellis_walks_below(golden, 3, 2, 0, runs[r].n, runs[r].bits, &w, &e);
        fmpz_fib_ui(exact, (ulong)runs[r].n + 1);
        total++, passed += below_within(w, e, exact, runs[r].n * ldexp(4.0, -runs[r].bits), &deficit);
        worst = fmax(worst, deficit);
        if (r == 0) exact_fit = e == 0 && fmpz_equal_ui(exact, w);
    }
    for (int k = 2; k <= 1000; k += 998) /* kⁿ; 1000 loops lower the counts' bits to 53 */
        for (long n = 50; n <= 500; n += 450) {
            status |= trellis_walks_below(loops, (size_t)k, 1, 0, n, 63, &w, &e);
            fmpz_set_ui(exact, (ulong)k), fmpz_pow_ui(exact, exact, (ulong)n);
            total++, passed += below_within(w, e, exact, n * ldexp(2.0, -53), &deficit);
            worst = fmax(worst, deficit);
        }
    for (long n = 999; n <= 1000; n++) { /* a 2-cycle: 1 for n even, 0 for n odd */
        status |= trellis_walks_below(cycle, 2, 2, 0, n, 63, &w, &e);
        total++, passed += w == (uint64_t)(n % 2 == 0) && e == 0;
    }
    { /* from several nodes side by side: each as alone, bit for bit */
        const size_t from[3] = {1, 0, 1};
        uint64_t wm[3], w1;
        long em[3], e1;
        status |= trellis_walks_below_many(golden, 3, 2, from, 3, 1000, 24, wm, em);
        for (int c = 0; c < 3; c++) {
            status |= trellis_walks_below(golden, 3, 2, from[c], 1000, 24, &w1, &e1);
            total++, passed += wm[c] == w1 && em[c] == e1;
        }
    }
    int refused = trellis_walks_below(golden, 3, 2, 0, 10, 1, &w, &e) == GB_EDOM;
    refused += trellis_walks_below_many(golden, 3, 2, NULL, 0, 10, 63, &w, &e) == GB_EDOM;
    refused += trellis_walks_below(golden, 3, 2, 2, 10, 63, &w, &e) == GB_EDOM;
    fmpz_clear(exact);
    gb_check c = {"-", "-", "the trellis's closed walks counted from below in 63-bit integers",
                  "closed forms counted exactly by FLINT: Fibonacci numbers (golden mean graph), k^n (k loops), a "
                  "2-cycle's parity; exact while the counts fit; several starts side by side against each alone",
                  "at most the exact count; short by at most n 2^(2 - bits) relative (rounding down at each shift)"};
    gb_check_true(&c, !status && passed == total && exact_fit && refused == 3,
                  "%d of %d at most exact and within the slack, or side by side as alone (worst short by %.2g "
                  "relative), F(81) exact: %s, %d of 3 bad arguments refused",
                  passed, total, worst, exact_fit ? "yes" : "NO", refused);
}

int verify_register_s7_manifold(void)
{
    static const verify_test tests[] = {
        {"manifold: closed forms", test_exact,
         "a map's unstable and stable manifolds, parametrised on Arb, meet their closed forms and cross once"},
        {"manifold: the classical Henon map's crossings", test_henon,
         "the crossings of the classical Henon map's fixed point's manifolds over two arcs are proved, complete and "
         "homoclinic"},
        {"manifold: negative controls", test_controls,
         "a sink, two fixed points and an arc ending on a crossing prove nothing"},
        {"manifold: definitions out of range", test_refused, NULL},
        {"manifold: the classical Henon map's trellis bounds its entropy", test_trellis,
         "a trellis of the fixed point's manifolds bounds h_top from below, as an independent count of its rectangles "
         "and strips says"},
        {"manifold: two crossings 4e-14 apart far along the stable manifold", test_close,
         "two crossings of strands of the unstable manifold 4.3e-14 apart along a stable arc far out are proved, "
         "held by mpmath's and ordered"},
        {"manifold: the trellis's walks counted from below", test_walks,
         "the closed walks of a graph, counted in 63-bit integers rounded down, stay at or below closed forms and "
         "close to them"},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Proved on Arb's balls: invariant manifolds and their crossings", tests);
}
