/* Proved on Arb's balls: the Taylor coefficients of the Gömböcs' support function H(q) (gb_proof_body_jet_enclose), what
 * a Taylor step of the reduced field q̇ = p/M, ṗ = −m a(t) H′(q) − μp needs from the body.
 *
 * Oracles, none sharing code with what they check:
 * - at points: today's float model (gb_melnikov_body_direct: the contact continued by Newton in doubles and certified)
 *   for H and H′, and its central differences of H′ for H″ and H‴; at the top, the closed form of H″(0)
 *   (gb_proof_body's top model, r_max² e_tᵀ(r_max I − K)⁻¹ e_t − r_max);
 * - over arcs, the enclosures' own consistency: every point's coefficients inside its arc's, and Taylor's theorem with
 *   Lagrange's remainder, Σ_{k<K} H_k(q₀) w^k + H_K(arc) w^K, holding H at the arc's far end (enclosed alone);
 * - ties (the float model's kinks of H′) refused, and bad definitions refused naming their ranges;
 * - the reduced field's flow (gb_proof_body_flow) against GSL's rk8pd on the same field with the float model's H′, from
 *   points and the corners of boxes, and the saddle an equilibrium; a flow into a tie refused. */
#include "gb_check.h"
#include "gb_error.h"
#include "gb_melnikov_body.h"
#include "gb_proof_body.h"
#include "verify_sections.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

static const char *const bodies[2] = {"I", "II"};

typedef struct setup {
    gb_surface surface;
    gb_melnikov_body *body;
    gb_melnikov_body_info info;
    gb_proof_body_def def;
} setup;

/* A body's float model and the definition of its enclosures (M is not used by the coefficients: any valid interval). */
static int setup_body(setup *s, const char *name)
{
    memset(s, 0, sizeof *s);
    int status = gb_surface_init(&s->surface, name, 0.12);
    if (!status) status = gb_melnikov_body_create(&s->surface, 1.0, 9.81, GB_MELNIKOV_BODY_NODES, &s->body);
    if (status) return status;
    gb_melnikov_body_get_info(s->body, &s->info);
    s->def = (gb_proof_body_def){.surface = &s->surface,
                                 .mass = 1.0,
                                 .g = 9.81,
                                 .inertia = {1.0, 1.0},
                                 .origin = 3.0,
                                 .cut = 2e-3,
                                 .resolution = 1e-2,
                                 .precision = GB_PROOF_PRECISION_DEFAULT};
    memcpy(s->def.rocking, s->info.rocking, sizeof s->def.rocking);
    return GB_OK;
}

/* Within `bar` of the interval. */
static int near_interval(double x, gb_proof_interval i, double bar) { return x >= i.lo - bar && x <= i.hi + bar; }

static double mag(gb_proof_interval i) { return fmax(fabs(i.lo), fabs(i.hi)); }

/* No tie of the float model within `gap` of q. */
static int clear_of_ties(const gb_melnikov_body_info *info, double q, double gap)
{
    for (size_t k = 0; k < info->kinks && k < 16; k++)
        if (fabs(q - info->kink_q[k]) < gap) return 0;
    return 1;
}

static void test_points(void)
{
    int status = GB_OK, sampled = 0, inside = 0, teeth = 0, top = 0, refused = 0;
    double widest[2] = {0.0, 0.0}, seconds = 0.0; /* of c0, c1 and of c2, c3 */
    char first[400] = "";
    for (int b = 0; b < 2 && !status; b++) {
        setup s;
        status = setup_body(&s, bodies[b]);
        gb_proof_body_model model = {0};
        if (!status) status = gb_proof_body_enclose(&s.def, &model); /* for the top's closed form H″(0) */
        for (int k = 0; k < 40 && !status; k++) {
            const double q = 2.0 * M_PI * (k + 0.5) / 40.0;
            if (!clear_of_ties(&s.info, q, 0.01)) continue;
            gb_proof_body_jet j, moved;
            const int st = gb_proof_body_jet_enclose(&s.def, q, q, 6, &j);
            if (st == GB_ENUMERIC) { /* not proved C² with one contact at q (near a pole of I's C¹,¹ kernel) */
                refused++;
                continue;
            }
            double H, dH, M, Hp, dHp, Hm, dHm, H2p, dH2p, H2m, dH2m;
            const double h = 1e-4, h3 = 2e-3;
            status = st;
            if (!status) status = gb_proof_body_jet_enclose(&s.def, q + 1e-6, q + 1e-6, 1, &moved);
            if (!status) status = gb_melnikov_body_direct(s.body, q, &H, &dH, &M);
            if (!status) status = gb_melnikov_body_direct(s.body, q + h, &Hp, &dHp, &M);
            if (!status) status = gb_melnikov_body_direct(s.body, q - h, &Hm, &dHm, &M);
            if (!status) status = gb_melnikov_body_direct(s.body, q + h3, &H2p, &dH2p, &M);
            if (!status) status = gb_melnikov_body_direct(s.body, q - h3, &H2m, &dH2m, &M);
            if (status) break;
            seconds += j.seconds;
            /* H″ = 2 c₂ by (H′(q + h) − H′(q − h)) / 2h, off by h² H⁗/6 = 4 c₄ h² and the float H′'s 1e-12 over h;
             * H‴ = 6 c₃ by (H′(q + h) − 2H′(q) + H′(q − h)) / h², off by h² H⁽⁵⁾/12 = 10 c₅ h² and 4e-12 / h²; each
             * truncation bounded by twice the enclosure's own coefficient */
            const double d2 = (dHp - dHm) / (2.0 * h), d3 = (dH2p - 2.0 * dH + dH2m) / (h3 * h3);
            const gb_proof_interval c2 = {2.0 * j.H[2].lo, 2.0 * j.H[2].hi}, c3 = {6.0 * j.H[3].lo, 6.0 * j.H[3].hi};
            const int in = near_interval(H, j.H[0], 1e-12) + near_interval(dH, j.H[1], 1e-11) +
                           near_interval(d2, c2, 8.0 * mag(j.H[4]) * h * h + 1e-12 / h) +
                           near_interval(d3, c3, 20.0 * mag(j.H[5]) * h3 * h3 + 4e-12 / (h3 * h3));
            sampled += 4, inside += in;
            teeth += !near_interval(dH, moved.H[1], 1e-11);
            if (in < 4 && !first[0])
                snprintf(first, sizeof first,
                         "; %s at q = %.6g: H %.15g in [%.15g, %.15g], H' %.15g in [%.15g, %.15g], "
                         "H'' %.9g in [%.9g, %.9g], H''' %.6g in [%.6g, %.6g]",
                         bodies[b], q, H, j.H[0].lo, j.H[0].hi, dH, j.H[1].lo, j.H[1].hi, d2, c2.lo, c2.hi, d3, c3.lo,
                         c3.hi);
            for (int c = 0; c <= 3; c++)
                widest[c / 2] = fmax(widest[c / 2], (j.H[c].hi - j.H[c].lo) / fmax(1.0, mag(j.H[c])));
        }
        gb_proof_body_jet at_top;
        if (!status) status = gb_proof_body_jet_enclose(&s.def, 0.0, 0.0, 2, &at_top);
        if (!status) top += 2.0 * at_top.H[2].lo <= model.curvature.hi && 2.0 * at_top.H[2].hi >= model.curvature.lo;
        gb_proof_body_free(&model);
        gb_melnikov_body_free(s.body);
    }
    gb_check c = {
        "7", "78-80", "H(q)'s Taylor coefficients H, H', H''/2, H'''/6 at 40 q a body (Gomboc I and II, beta = 0.12)",
        "the float model's H and H' (Newton in doubles, certified), its central differences of H' for H'' "
        "(step 1e-4) and H''' (step 2e-3); H''(0) in closed form at the top",
        "H 1e-12, H' 1e-11 (the float's); the differences' truncation bounded by twice the enclosure's own next "
        "coefficients, plus the float's 1e-12 over the step; every enclosure narrower than its oracle's bar, so "
        "that the comparison decides (c0, c1 1e-11; c2, c3 1e-6, the differences' rounding over h^2; relative above "
        "1)"};
    gb_check_true(
        &c,
        !status && sampled >= 4 * 60 && inside == sampled && teeth == sampled / 4 && top == 2 && widest[0] <= 1e-11 &&
            widest[1] <= 1e-6,
        "%d of %d inside (%d q refused: not proved C2 with one contact), the enclosures at q + 1e-6 exclude "
        "the float H' at q %d of %d times, H''(0) meets the closed form %d of 2, widest c0, c1 %.2g, c2, c3 %.2g, "
        "%.2f s CPU%s%s%s",
        inside, sampled, refused, teeth, sampled / 4, top, widest[0], widest[1], seconds, first, status ? ": " : "",
        status ? gb_error_message() : "");
}

static void test_arcs(void)
{
    enum { ORDER = 8 };
    const double w = 1e-3;
    int status = GB_OK, arcs = 0, contained = 0, steps = 0, refused = 0, ties = 0, tie_arcs = 0;
    double step_width = 0.0, h0_ratio = 0.0, seconds = 0.0;
    char first[200] = "";
    for (int b = 0; b < 2 && !status; b++) {
        setup s;
        status = setup_body(&s, bodies[b]);
        for (int k = 0; k < 30 && !status; k++) {
            const double q0 = 2.0 * M_PI * k / 30.0 + 0.01, q1 = q0 + w;
            if (!clear_of_ties(&s.info, q0, 0.01)) continue;
            gb_proof_body_jet A, P[3];
            int st = gb_proof_body_jet_enclose(&s.def, q0, q1, ORDER, &A);
            if (st == GB_ENUMERIC) {
                refused++;
                continue;
            }
            const double at[3] = {q0, 0.5 * q0 + 0.5 * q1, q1};
            for (int i = 0; i < 3 && !st; i++) st = gb_proof_body_jet_enclose(&s.def, at[i], at[i], ORDER, &P[i]);
            status = st;
            if (status) break;
            seconds += A.seconds;
            arcs++;
            int in = 1;
            for (int i = 0; i < 3; i++)
                for (int c = 0; c <= ORDER; c++) in &= P[i].H[c].lo >= A.H[c].lo && P[i].H[c].hi <= A.H[c].hi;
            contained += in;
            /* Taylor's theorem from q0 across the arc: Σ_{c<ORDER} H_c(q0) w^c + H_ORDER(ξ) w^ORDER, ξ in the arc */
            double lo = 0.0, hi = 0.0, p = 1.0;
            for (int c = 0; c <= ORDER; c++, p *= w) {
                const gb_proof_interval x = c < ORDER ? P[0].H[c] : A.H[c];
                lo += fmin(x.lo * p, x.hi * p), hi += fmax(x.lo * p, x.hi * p);
            }
            const double slack = 4e-16 * (fabs(lo) + fabs(hi)); /* this sum's own rounding in doubles */
            const int holds = P[2].H[0].lo <= hi + slack && P[2].H[0].hi >= lo - slack;
            steps += holds;
            step_width = fmax(step_width, hi - lo);
            h0_ratio = fmax(h0_ratio, (A.H[0].hi - A.H[0].lo) / (w * fmax(mag(A.H[1]), 1e-3)));
            if ((!in || !holds) && !first[0])
                snprintf(first, sizeof first,
                         "; %s, arc [%.6g, %.6g]: points inside %d, step [%.15g, %.15g] against %.15g", bodies[b], q0,
                         q1, in, lo, hi, P[2].H[0].lo);
        }
        /* the ties of the float model: an arc across one has no Taylor coefficients */
        for (size_t k = 0; k < s.info.kinks && k < 16 && !status; k++) {
            gb_proof_body_jet j;
            const double q = s.info.kink_q[k];
            tie_arcs++;
            ties += gb_proof_body_jet_enclose(&s.def, q - 1e-4, q + 1e-4, 2, &j) == GB_ENUMERIC;
            gb_error_clear();
        }
        gb_melnikov_body_free(s.body);
    }
    gb_check c = {
        "7", "78-80", "H's Taylor coefficients (order 8) over arcs of q 1e-3 wide, 30 a body",
        "the points' own enclosures (arc ends and middle) and Taylor's theorem with Lagrange's remainder from the "
        "arc's start across it, against H enclosed at its end",
        "inclusion, exact (balls); the step's sum in doubles widened by 4e-16 relative"};
    gb_check_true(
        &c, !status && arcs >= 40 && contained == arcs && steps == arcs && ties == tie_arcs && tie_arcs >= 4,
        "%d arcs (%d refused: not proved C2 with one contact), points inside %d, Taylor steps holding %d, widest "
        "step %.2g; H over an arc at most %.1f x w |H'|; %d of %d arcs across a tie refused; %.2f s CPU%s%s%s",
        arcs, refused, contained, steps, step_width, h0_ratio, ties, tie_arcs, seconds, first, status ? ": " : "",
        status ? gb_error_message() : "");
}

static void test_bad_arcs(void)
{
    setup s;
    int status = setup_body(&s, "II"), named = 0, cases = 0;
    const struct {
        double q_lo, q_hi;
        int order;
        const char *names;
    } bad[] = {
        {1.0, 1.0, -1, "order"}, {1.0, 1.0, GB_PROOF_BODY_JET_ORDER_MAX + 1, "order"},
        {1.0, 0.9, 2, "arc"},    {1.0, 1.0 + 2.0 * GB_PROOF_BODY_JET_ARC_MAX, 2, "arc"},
        {-6.4, -6.3, 2, "arc"},  {12.5, 12.6, 2, "arc"},
        {NAN, 1.0, 2, "arc"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof *bad && !status; k++) {
        gb_proof_body_jet j;
        const int st = gb_proof_body_jet_enclose(&s.def, bad[k].q_lo, bad[k].q_hi, bad[k].order, &j);
        cases++;
        named += st == GB_EDOM && strstr(gb_error_message(), bad[k].names) && strstr(gb_error_message(), "allowed");
        gb_error_clear();
    }
    gb_proof_body_def wrong = s.def;
    wrong.precision = 8;
    gb_proof_body_jet j;
    cases++;
    named += !status && gb_proof_body_jet_enclose(&wrong, 1.0, 1.0, 2, &j) == GB_EDOM &&
             strstr(gb_error_message(), "precision");
    gb_error_clear();
    if (!status) gb_melnikov_body_free(s.body);
    gb_check c = {"-", "-", "gb_proof_body_jet_enclose: orders, arcs and definitions out of range",
                  "GB_EDOM naming the argument and its allowed range", "exact"};
    gb_check_true(&c, !status && named == cases, "%d of %d refused naming the argument", named, cases);
}

/* The ties: each of the float model's kinks (bisection on its branches' heights) located by interval Newton on an arc
 * 4e-4 wide about it, and its jump of H′; an arc without a tie refused. */
static void test_ties(void)
{
    int status = GB_OK, ties = 0, proved = 0, inside = 0, jumps = 0, teeth = 0, refused = 0;
    double widest = 0.0, seconds = 0.0;
    char first[300] = "";
    for (int b = 0; b < 2 && !status; b++) {
        setup s;
        status = setup_body(&s, bodies[b]);
        for (size_t k = 0; k < s.info.kinks && k < 16 && !status; k++) {
            const double q = s.info.kink_q[k];
            gb_proof_body_tie t;
            status = gb_proof_body_tie_locate(&s.def, q - 2e-4, q + 2e-4, &t);
            if (status) break;
            seconds += t.seconds;
            ties++, proved += t.proved;
            /* the float's bisection stops at 4e-16 relative on heights Newton polished to about 1e-14: over |d′| > 0.5,
             * 1e-13; its jump from two float H′, 1e-11 */
            const int in = near_interval(q, t.q, 1e-13), jump = near_interval(s.info.kink_jump[k], t.jump, 1e-11);
            inside += in, jumps += jump;
            teeth += !near_interval(q + 1e-12, t.q, 0.0) && !near_interval(q - 1e-12, t.q, 0.0);
            widest = fmax(widest, t.q.hi - t.q.lo);
            if ((!in || !jump) && !first[0])
                snprintf(first, sizeof first,
                         "; %s: kink %.17g (jump %.12g) against [%.17g, %.17g] (jump [%.12g, %.12g])", bodies[b], q,
                         s.info.kink_jump[k], t.q.lo, t.q.hi, t.jump.lo, t.jump.hi);
        }
        gb_proof_body_tie none;
        if (!status) refused += gb_proof_body_tie_locate(&s.def, 2.0, 2.0004, &none) == GB_ENUMERIC;
        gb_error_clear();
        if (s.body) gb_melnikov_body_free(s.body);
    }
    gb_check c = {"7", "78",
                  "the ties of H (where the two contacts are equally high) and H''s jumps there, Gomboc I and II",
                  "the float model's kinks (bisection on its branches' heights) and their jumps",
                  "1e-13 in q (the float heights' Newton tolerance over |d'| > 0.5), 1e-11 in the jump (two float H')"};
    gb_check_true(
        &c,
        !status && ties == 6 && proved == ties && inside == ties && jumps == ties && teeth == ties && refused == 2 &&
            widest <= 1e-14,
        "%d ties proved of %d (widest %.2g), the float's kinks inside %d and their jumps %d, the kinks moved by "
        "1e-12 outside %d, arcs without a tie refused %d of 2; %.2f s CPU%s%s%s",
        proved, ties, widest, inside, jumps, teeth, refused, seconds, first, status ? ": " : "",
        status ? gb_error_message() : "");
}

/* Table 1's rolling forcing of Gömböc II (cases/table1-gomboc-II-rolling.ini), m = 1. */
static const gb_proof_body_forcing table1 = {
    .damping = 0.02, .A1 = 2.0, .A2 = 1.0, .omega = 18.0, .psi = {M_PI / 3.0, M_PI / 3.0}};

typedef struct float_field {
    gb_melnikov_body *body;
    double m_over_M, mu;
} float_field;

/* The same field in doubles: q̇ = P, Ṗ = −(m/M) a(t) H′(q) − μP, H′ from the float model. */
static int float_rhs(double t, const double y[], double f[], void *context)
{
    const float_field *F = context;
    double H, dH, M;
    if (gb_melnikov_body_direct(F->body, y[0], &H, &dH, &M)) return GSL_EBADFUNC;
    const double a = 9.81 + table1.A1 * cos(table1.omega * t) + table1.A2 * cos(2.0 * table1.omega * t + table1.psi.lo);
    f[0] = y[1], f[1] = -F->m_over_M * a * dH - F->mu * y[1];
    return GSL_SUCCESS;
}

/* A body's set-up with its enclosed M, and the float field at M's middle. */
typedef struct flow_body {
    setup s;
    gb_proof_interval M;
    float_field F;
} flow_body;

static int setup_flow(flow_body *b, const char *name)
{
    int status = setup_body(&b->s, name);
    b->M = (gb_proof_interval){0, 0};
    if (!status)
        status = gb_proof_body_inertia(&b->s.surface, 1.0, b->s.info.rocking, GB_PROOF_PRECISION_DEFAULT, &b->M, NULL);
    if (status) return status;
    b->s.def.inertia = b->M;
    const double mid = 0.5 * b->M.lo + 0.5 * b->M.hi;
    b->F = (float_field){b->s.body, 1.0 / mid, table1.damping / mid};
    return GB_OK;
}

/* The state y at time t moved on by dt along the field (Euler): for the teeth, a state about |f| dt from the true one. */
static void later_by(const float_field *F, const double y[2], double t, double dt, double out[2])
{
    double f[2] = {0.0, 0.0};
    float_rhs(t, y, f, (void *)F);
    out[0] = y[0] + dt * f[0], out[1] = y[1] + dt * f[1];
}

/* GSL's rk8pd from y at t = 0 to t (tolerances 1e-13). */
static int float_flow(const float_field *F, double y[2], double t)
{
    gsl_odeiv2_system sys = {float_rhs, NULL, 2, (void *)F};
    gsl_odeiv2_driver *d = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, 1e-4, 1e-13, 1e-13);
    double now = 0.0;
    const int status = d ? gsl_odeiv2_driver_apply(d, &now, t, y) : GSL_ENOMEM;
    gsl_odeiv2_driver_free(d);
    return status;
}

static void test_flow(void)
{
    const double t = 0.375; /* a dyadic time just past the forcing's period 2 pi / 18 = 0.349 */
    int status = GB_OK, points = 0, inside = 0, teeth = 0, corners = 0, corners_in = 0, saddle = 0, tie = 0;
    double widest_point = 0.0, seconds = 0.0;
    char first[300] = "";
    flow_body fb;
    for (int b = 0; b < 2 && !status; b++) {
        status = setup_flow(&fb, bodies[b]);
        if (status) break;
        setup s = fb.s;
        const float_field F = fb.F;
        /* near the saddle, and across the middle of the turn moving away from the tie at pi */
        const double start[2][2] = {{0.05, 0.0}, {3.0, -0.5}};
        for (int k = 0; k < 2 && !status; k++) {
            const gb_proof_interval point[2] = {{start[k][0], start[k][0]}, {start[k][1], start[k][1]}};
            gb_proof_interval image[2];
            const clock_t c0 = clock();
            status = gb_proof_body_flow(&s.def, &table1, point, 0.0, t, 12, image);
            seconds += (double)(clock() - c0) / CLOCKS_PER_SEC;
            double y[2] = {start[k][0], start[k][1]}, later[2];
            if (!status) status = float_flow(&F, y, t);
            if (status) break;
            later_by(&F, y, t, 1e-6, later);
            /* GSL's error: its tolerances 1e-13 over about 400 steps, 1e-10 */
            const int in = near_interval(y[0], image[0], 1e-10) && near_interval(y[1], image[1], 1e-10);
            points++, inside += in;
            teeth += !near_interval(later[1], image[1], 1e-10);
            widest_point = fmax(widest_point, fmax(image[0].hi - image[0].lo, image[1].hi - image[1].lo));
            if (!in && !first[0])
                snprintf(first, sizeof first,
                         "; %s from (%g, %g): GSL (%.15g, %.15g) against [%.15g, %.15g] x [%.15g, %.15g]", bodies[b],
                         start[k][0], start[k][1], y[0], y[1], image[0].lo, image[0].hi, image[1].lo, image[1].hi);
        }
        /* a box 2e-6 wide about the first point: its corners' GSL images inside */
        const gb_proof_interval box[2] = {{0.05 - 1e-6, 0.05 + 1e-6}, {-1e-6, 1e-6}};
        gb_proof_interval image[2];
        const clock_t c0 = clock();
        if (!status) status = gb_proof_body_flow(&s.def, &table1, box, 0.0, t, 12, image);
        seconds += (double)(clock() - c0) / CLOCKS_PER_SEC;
        for (int c = 0; c < 4 && !status; c++) {
            double y[2] = {c & 1 ? box[0].hi : box[0].lo, c & 2 ? box[1].hi : box[1].lo};
            status = float_flow(&F, y, t);
            corners++, corners_in += near_interval(y[0], image[0], 1e-10) && near_interval(y[1], image[1], 1e-10);
        }
        /* the saddle (0, 0) is an equilibrium at every forcing (H′(0) = 0) */
        const gb_proof_interval top[2] = {{0.0, 0.0}, {0.0, 0.0}};
        if (!status) status = gb_proof_body_flow(&s.def, &table1, top, 0.0, t, 12, image);
        if (!status)
            saddle += image[0].lo <= 0.0 && image[0].hi >= 0.0 && image[1].lo <= 0.0 && image[1].hi >= 0.0 &&
                      fmax(image[0].hi - image[0].lo, image[1].hi - image[1].lo) <= 1e-15;
        /* from just before a tie of the float model, moving into it */
        if (!status && s.info.kinks && b == 1) { /* one body: the steps shrink toward the tie down to 1e-9 (3 s) */
            const gb_proof_interval before[2] = {{s.info.kink_q[0] - 0.01, s.info.kink_q[0] - 0.01}, {1.0, 1.0}};
            tie += gb_proof_body_flow(&s.def, &table1, before, 0.0, 0.125, 12, image) == GB_ENUMERIC;
            gb_error_clear();
        }
        gb_melnikov_body_free(s.body);
    }
    gb_check c = {"7", "78, 91",
                  "the reduced field at Table 1's rolling forcing (beta = 0.12, m = 1) over t = 0.375 s on Arb's balls",
                  "GSL's rk8pd (tolerances 1e-13) on the same field with the float model's H'",
                  "GSL's error, 1e-10 (its tolerances over about 400 steps); the saddle an equilibrium to 1e-15"};
    gb_check_true(
        &c,
        !status && points == 4 && inside == points && teeth == points && corners == 8 && corners_in == 8 &&
            saddle == 2 && tie == 1,
        "points inside %d of %d (widest image %.2g), GSL's state moved on 1e-6 s outside %d of %d, box corners inside "
        "%d of %d, the saddle kept %d of 2, a flow into II's first tie refused %d of 1, %.1f s CPU%s%s%s",
        inside, points, widest_point, teeth, points, corners_in, corners, saddle, tie, seconds, first,
        status ? ": " : "", status ? gb_error_message() : "");
}

/* The period map: the return to sin ωt = 0, against GSL's flow to 2π/ω and its central differences, and Liouville's
 * det DP = e^{−μT} (the (q, P) field's trace is −μ) at the saddle. */
/* det DP over the enclosures of a period map's derivative (outward in doubles, then widened by 1e-15). */
static gb_proof_interval det_of(const gb_proof_body_return *r)
{
    const gb_proof_interval *J0 = r->jacobian[0], *J1 = r->jacobian[1];
    const double p[4] = {J0[0].lo * J1[1].lo, J0[0].lo * J1[1].hi, J0[0].hi * J1[1].lo, J0[0].hi * J1[1].hi};
    const double q[4] = {J0[1].lo * J1[0].lo, J0[1].lo * J1[0].hi, J0[1].hi * J1[0].lo, J0[1].hi * J1[0].hi};
    double plo = p[0], phi = p[0], qlo = q[0], qhi = q[0];
    for (int k = 1; k < 4; k++)
        plo = fmin(plo, p[k]), phi = fmax(phi, p[k]), qlo = fmin(qlo, q[k]), qhi = fmax(qhi, q[k]);
    return (gb_proof_interval){plo - qhi - 1e-15, phi - qlo + 1e-15};
}

/* Liouville: the period map's det DP = e^{−μT}, μ = c/M, the time T exact (the section is at a fixed phase); 1 when
 * the enclosure of det DP holds e^{−μT} for some M of scale·M's interval. */
static int liouville_met(const gb_proof_body_return *r, gb_proof_interval M, double T, double scale)
{
    const gb_proof_interval d = det_of(r);
    const double e_lo = exp(-table1.damping / (scale * M.lo) * T), e_hi = exp(-table1.damping / (scale * M.hi) * T);
    return d.lo <= fmax(e_lo, e_hi) && d.hi >= fmin(e_lo, e_hi);
}

static void test_period_map(void)
{
    const double T = 2.0 * M_PI / table1.omega, h = 1e-6;
    int status = GB_OK, inside = 0, timed = 0, derivative = 0, liouville = 0, kept = 0, teeth = 0, liouville_teeth = 0;
    double lambda[2] = {NAN, NAN}, seconds = 0.0;
    char first[300] = "";
    flow_body fb;
    for (int b = 0; b < 2 && !status; b++) {
        status = setup_flow(&fb, bodies[b]);
        if (status) break;
        const double q0 = b == 1 ? 0.05 : 0.0; /* II from near the saddle, I from the saddle */
        const gb_proof_interval box[2] = {{q0, q0}, {0.0, 0.0}};
        gb_proof_body_return r;
        status = gb_proof_body_period_map(&fb.s.def, &table1, box, 1, 12, 1, &r);
        if (status) break;
        seconds += r.seconds;
        double y[2] = {q0, 0.0}, later[2], d[4][2] = {{q0 + h, 0}, {q0 - h, 0}, {q0, h}, {q0, -h}};
        status = float_flow(&fb.F, y, T);
        later_by(&fb.F, y, T, 1e-6, later);
        for (int k = 0; k < 4 && !status; k++) status = float_flow(&fb.F, d[k], T);
        if (status) break;
        inside += near_interval(y[0], r.q, 1e-10) && near_interval(y[1], r.P, 1e-10);
        if (q0 != 0.0) teeth += !near_interval(later[1], r.P, 1e-10); /* (the saddle does not move) */
        timed += r.time.lo <= T && r.time.hi >= T;
        /* central differences: truncation h² |P‴| / 6 and GSL's 1e-10 over h, 1e-4 */
        const double fd[2][2] = {{(d[0][0] - d[1][0]) / (2 * h), (d[2][0] - d[3][0]) / (2 * h)},
                                 {(d[0][1] - d[1][1]) / (2 * h), (d[2][1] - d[3][1]) / (2 * h)}};
        int in = 1;
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) in &= near_interval(fd[i][j], r.jacobian[i][j], 1e-4);
        derivative += in;
        if (!in && !first[0])
            snprintf(first, sizeof first,
                     "; %s: DP [[%.9g, %.9g], [%.9g, %.9g]] against differences [[%.9g, %.9g], [%.9g, %.9g]]",
                     bodies[b], r.jacobian[0][0].lo, r.jacobian[0][1].lo, r.jacobian[1][0].lo, r.jacobian[1][1].lo,
                     fd[0][0], fd[0][1], fd[1][0], fd[1][1]);
        if (q0 == 0.0) {
            kept += r.q.lo <= 0.0 && r.q.hi >= 0.0 && r.P.lo <= 0.0 && r.P.hi >= 0.0;
            liouville += liouville_met(&r, fb.M, T, 1.0);
            liouville_teeth += !liouville_met(&r, fb.M, T, 1.01); /* M 1 % larger */
            const gb_proof_interval *J0 = r.jacobian[0], *J1 = r.jacobian[1];
            const gb_proof_interval d = det_of(&r);
            const double tr = 0.5 * (J0[0].lo + J1[1].lo), det = 0.5 * (d.lo + d.hi);
            lambda[0] = tr + sqrt(tr * tr - det), lambda[1] = tr - sqrt(tr * tr - det);
        }
        gb_melnikov_body_free(fb.s.body);
    }
    gb_check c = {
        "7", "78, 91", "the reduced field's period map at Table 1's rolling forcing (the return to sin(omega t) = 0)",
        "GSL's rk8pd to 2 pi / omega and its central differences (step 1e-6); at the saddle Liouville's det DP = "
        "exp(-mu T)",
        "GSL's error 1e-10; the differences' truncation and GSL's error over the step, 1e-4; det 1e-15 (doubles)"};
    gb_check_true(
        &c,
        !status && inside == 2 && teeth == 1 && timed == 2 && derivative == 2 && kept == 1 && liouville == 1 &&
            liouville_teeth == 1,
        "GSL inside %d of 2 (moved on 1e-6 s outside %d of 1), the time holds 2 pi / omega %d of 2, DP inside the "
        "differences %d of 2, the saddle kept %d of 1, Liouville met %d of 1 (and missed with M 1 %% larger %d of "
        "1); I's saddle: multipliers %.6f and %.6f a period; %.1f s CPU%s%s%s",
        inside, teeth, timed, derivative, kept, liouville, liouville_teeth, lambda[0], lambda[1], seconds, first,
        status ? ": " : "", status ? gb_error_message() : "");
}

/* The period map across a tie: Gömböc II from (0.7, 1.0), which meets its tie near 0.78 a fifth into the period,
 * against GSL's rk8pd on the float model (whose H′ switches at its own kink); its derivative against GSL's central
 * differences and Liouville's det DP = e^{−μT}, which hold across the tie too (the flow is continuous there and the
 * return time exact). */
static void test_period_map_tie(void)
{
    const double T = 2.0 * M_PI / table1.omega, h = 1e-5;
    flow_body fb;
    int status = setup_flow(&fb, "II"), inside = 0, teeth = 0, timed = 0, derivative = 0, liouville = 0, moved = 0;
    gb_proof_body_tie tie;
    gb_proof_body_return r = {0};
    double y[2] = {0.7, 1.0}, later[2] = {0, 0},
           d[4][2] = {{0.7 + h, 1.0}, {0.7 - h, 1.0}, {0.7, 1.0 + h}, {0.7, 1.0 - h}};
    double fd[2][2] = {{NAN, NAN}, {NAN, NAN}};
    if (!status)
        status = gb_proof_body_tie_locate(&fb.s.def, fb.s.info.kink_q[0] - 2e-4, fb.s.info.kink_q[0] + 2e-4, &tie);
    const gb_proof_interval box[2] = {{0.7, 0.7}, {1.0, 1.0}};
    if (!status) status = gb_proof_body_period_map_tie(&fb.s.def, &table1, box, &tie, 12, 1, &r);
    if (!status) status = float_flow(&fb.F, y, T);
    for (int k = 0; k < 4 && !status; k++) status = float_flow(&fb.F, d[k], T);
    if (!status) {
        later_by(&fb.F, y, T, 1e-5, later);
        /* GSL across the kink: its tolerances 1e-13 against 1e-11 moved it by 1e-11; 1e-9 */
        inside = near_interval(y[0], r.q, 1e-9) && near_interval(y[1], r.P, 1e-9);
        teeth = !near_interval(later[0], r.q, 1e-9);
        timed = r.time.lo <= T && r.time.hi >= T;
        /* central differences: GSL's 1e-11 across the kink over 2h (5e-7), and h² |P‴| / 6: 1e-6 */
        derivative = 1;
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) {
                fd[i][j] = (d[2 * j][i] - d[2 * j + 1][i]) / (2.0 * h);
                derivative &= near_interval(fd[i][j], r.jacobian[i][j], 1e-6);
            }
        liouville = liouville_met(&r, fb.M, T, 1.0);
        moved = !liouville_met(&r, fb.M, T, 1.01);
    }
    const gb_proof_interval det = status ? (gb_proof_interval){NAN, NAN} : det_of(&r);
    if (fb.s.body) gb_melnikov_body_free(fb.s.body);
    gb_check c = {"7", "78, 91",
                  "the reduced field's period map of Gomboc II across its tie near q = 0.78, from (0.7, 1.0), and its "
                  "derivative",
                  "GSL's rk8pd to 2 pi / omega on the float model (its H' switching at its own kink) and its central "
                  "differences (step 1e-5); Liouville's det DP = exp(-mu T)",
                  "GSL's error across the kink, 1e-9 (tolerances 1e-13 and 1e-11 differ by 1e-11); the differences' "
                  "1e-11 over the step and truncation, 1e-6; det 1e-15 (doubles)"};
    gb_check_true(
        &c, !status && inside && teeth && timed && derivative && liouville && moved,
        "GSL (%.12g, %.12g) inside [%.12g, %.12g] x [%.12g, %.12g]: %d; moved on 1e-5 s outside: %d; the time holds "
        "2 pi / omega: %d; DP [[%.9g, %.9g], [%.9g, %.9g]] (widest %.2g) inside the differences [[%.9g, %.9g], "
        "[%.9g, %.9g]]: %d; det DP in [%.12g, %.12g] holds exp(-mu T): %d (not with M 1 %% larger: %d); %ld steps, "
        "%.1f s CPU%s%s",
        y[0], y[1], r.q.lo, r.q.hi, r.P.lo, r.P.hi, inside, teeth, timed, r.jacobian[0][0].lo, r.jacobian[0][1].lo,
        r.jacobian[1][0].lo, r.jacobian[1][1].lo,
        fmax(fmax(r.jacobian[0][0].hi - r.jacobian[0][0].lo, r.jacobian[0][1].hi - r.jacobian[0][1].lo),
             fmax(r.jacobian[1][0].hi - r.jacobian[1][0].lo, r.jacobian[1][1].hi - r.jacobian[1][1].lo)),
        fd[0][0], fd[0][1], fd[1][0], fd[1][1], derivative, det.lo, det.hi, liouville, moved, r.steps, r.seconds,
        status ? ": " : "", status ? gb_error_message() : "");
}

static void test_bad_flows(void)
{
    setup s;
    int status = setup_body(&s, "I"), named = 0, cases = 0;
    const gb_proof_interval box[2] = {{0.05, 0.05}, {0.0, 0.0}}, nan_box[2] = {{NAN, 0.05}, {0.0, 0.0}};
    gb_proof_interval image[2];
    gb_proof_body_forcing f[4] = {table1, table1, table1, table1};
    f[0].damping = -1.0, f[1].omega = 0.0, f[2].psi = (gb_proof_interval){1.0, 0.0}, f[3].A1 = INFINITY;
    const char *names[4] = {"damping", "omega", "psi", "A1"};
    for (int k = 0; k < 4 && !status; k++, cases++) {
        named += gb_proof_body_flow(&s.def, &f[k], box, 0.0, 0.25, 12, image) == GB_EDOM &&
                 strstr(gb_error_message(), names[k]);
        gb_error_clear();
    }
    const struct {
        double t;
        int order;
        const gb_proof_interval *box;
        const char *name;
    } bad[] = {{0.1, 12, box, "2^-30"},
               {0.25, 3, box, "order"},
               {0.25, GB_PROOF_BODY_JET_ORDER_MAX, box, "order"},
               {200.0, 12, box, "t ="},
               {0.25, 12, nan_box, "box"}};
    for (size_t k = 0; k < sizeof bad / sizeof *bad && !status; k++, cases++) {
        named += gb_proof_body_flow(&s.def, &table1, bad[k].box, 0.0, bad[k].t, bad[k].order, image) == GB_EDOM &&
                 strstr(gb_error_message(), bad[k].name) && strstr(gb_error_message(), "allowed");
        gb_error_clear();
    }
    if (!status) gb_melnikov_body_free(s.body);
    gb_check c = {"-", "-", "gb_proof_body_flow: forcings, orders, times and boxes out of range",
                  "GB_EDOM naming the argument (and its allowed range)", "exact"};
    gb_check_true(&c, !status && named == cases && cases == 9, "%d of %d refused naming the argument", named, cases);
}

int verify_register_s7_proofs_jet(void)
{
    static const verify_test tests[] = {
        {"proofs: H's Taylor coefficients at points hold the float model's", test_points,
         "the Taylor coefficients of the support function H(q), which a rigorous step of the reduced field needs, are "
         "enclosed where H is C2 with one contact"},
        {"proofs: H's Taylor coefficients over arcs hold the points' and Taylor's theorem", test_arcs,
         "the coefficients over an arc enclose the remainder of a Taylor step across it; arcs across a tie are "
         "refused"},
        {"proofs: bad arcs and orders of H's Taylor coefficients", test_bad_arcs, NULL},
        {"proofs: the ties of H located by interval Newton", test_ties,
         "each tie of the two contacts is proved unique and enclosed to rounding, with the jump of H' there"},
        {"proofs: the reduced field's flow holds GSL's solutions", test_flow,
         "the reduced field at the paper's forcing (not linearised in epsilon) is integrated rigorously where no tie "
         "is "
         "crossed"},
        {"proofs: the reduced field's period map and its derivative", test_period_map,
         "the period map of the reduced field at the paper's forcing and its derivative are enclosed rigorously"},
        {"proofs: the reduced field's period map across a tie", test_period_map_tie,
         "the period map of the reduced field and its derivative are enclosed across a tie of the contact, where H' "
         "jumps"},
        {"proofs: bad forcings, orders and times of the reduced field's flow", test_bad_flows, NULL},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Proved on Arb's balls: the reduced field's Taylor coefficients and flow (section 7)",
                                 tests);
}
