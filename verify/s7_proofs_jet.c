/* Proved on Arb's balls: the Taylor coefficients of the Gömböcs' support function H(q) (gb_proof_body_jet_enclose), what
 * a Taylor step of the reduced field q̇ = p/M, ṗ = −m a(t) H′(q) − μp needs from the body.
 *
 * Oracles, none sharing code with what they check:
 * - at points: today's float model (gb_melnikov_body_direct: the contact continued by Newton in doubles and certified)
 *   for H and H′, and its central differences of H′ for H″ and H‴; at the top, the closed form of H″(0)
 *   (gb_proof_body's top model, r_max² e_tᵀ(r_max I − K)⁻¹ e_t − r_max);
 * - over arcs, the enclosures' own consistency: every point's coefficients inside its arc's, and Taylor's theorem with
 *   Lagrange's remainder, Σ_{k<K} H_k(q₀) w^k + H_K(arc) w^K, holding H at the arc's far end (enclosed alone);
 * - ties (the float model's kinks of H′) refused, and bad definitions refused naming their ranges. */
#include "gb_check.h"
#include "gb_error.h"
#include "gb_melnikov_body.h"
#include "gb_proof_body.h"
#include "verify_sections.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

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
        {-0.1, 0.0, 2, "arc"},   {6.2, 6.3, 2, "arc"},
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
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Proved on Arb's balls: the reduced field's Taylor coefficients (section 7)", tests);
}
