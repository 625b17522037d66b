/* Proved on Arb's balls: covering relations of Gömböc II's period map along one of its homoclinic orbits, at Table 1's
 * rolling forcing (gb_proof_body_chain_design, gb_proof_body_cover_link; docs/proofs.md, "A horseshoe of Gömböc II").
 *
 * Oracles, none sharing code with what they check:
 * - the float design: Liouville's det DP = e^{−μT} (the period map's area contraction, its return time exact) for the
 *   saddle's multipliers and for the product of the frames' stretchings along the orbit (the frames at both ends are
 *   the saddle's); the rigorous period map of each of the orbit's points holding the next point (the float model
 *   against the proof's own H′);
 * - the covering relations: proved where the linear part leaves a margin of 1/ρ, and refused (not proved) when the
 *   target is moved along by three of its half-widths (the image then lies outside its strip) or widened across by a
 *   fifth (the edges' images then fall inside it) — negative controls of each of the two conditions;
 * - disjointness: every pair of the chain's sets proved apart on the cylinder, and a set against itself 2π on never;
 * - H's coefficients over the shared cells of q (gb_proof_body_arcs, which the links use as `gomboc prove --horseshoe`
 *   does): the point coefficients at each arc's ends and middle inside the cells' hull and inside the arc's own
 *   enclosure (gb_proof_body_jet_enclose); a cell across a tie refused and its arc left to the caller; the same
 *   answer from a fresh table and from one filled by other arcs first;
 * - Gömböc I's default sets (their links are not proved here, and five of them not by `gomboc prove` either:
 *   docs/proofs.md): the same float design checks, five centres' rigorous images, and its sets pairwise apart;
 * - the entropy bound: against the golden ratio's closed form for a cycle of 2, and a float bisection for the chain. */
#include "gb_check.h"
#include "gb_error.h"
#include "gb_melnikov_body.h"
#include "gb_proof_body.h"
#include "gb_proof_body_arcs_internal.h"
#include "verify_sections.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Table 1's rolling forcing of Gömböc II (cases/table1-gomboc-II-rolling.ini), m = 1. */
static const gb_proof_body_forcing table1 = {
    .damping = 0.02, .A1 = 2.0, .A2 = 1.0, .omega = 18.0, .psi = {M_PI / 3.0, M_PI / 3.0}};

typedef struct chain_setup {
    gb_surface surface;
    gb_melnikov_body_info info;
    gb_proof_body_def def;
    gb_proof_body_chain chain;
} chain_setup;

/* A Gömböc's definition with its enclosed M, and its default chain: designed once a body for the suite's tests
 * (released at exit). Body 0 is Gömböc II (the horseshoe proved), body 1 Gömböc I (its sets, designed). */
static const char *const morphologies[2] = {"II", "I"};
static chain_setup shared[2];
static int shared_status[2] = {-1, -1};

static void release_shared(void)
{
    for (int b = 0; b < 2; b++)
        if (shared_status[b] == GB_OK) gb_proof_body_chain_free(&shared[b].chain);
}

static int setup_body(int b, chain_setup *s)
{
    chain_setup *h = &shared[b];
    if (shared_status[b] >= 0) {
        *s = *h;
        return shared_status[b];
    }
    memset(h, 0, sizeof *h);
    gb_melnikov_body *body = NULL;
    int status = gb_surface_init(&h->surface, morphologies[b], 0.12);
    if (!status) status = gb_melnikov_body_create(&h->surface, 1.0, 9.81, GB_MELNIKOV_BODY_NODES, &body);
    if (!status) {
        gb_melnikov_body_get_info(body, &h->info);
        gb_melnikov_body_free(body);
        h->def = (gb_proof_body_def){.surface = &h->surface,
                                     .mass = 1.0,
                                     .g = 9.81,
                                     .origin = 3.0,
                                     .cut = 2e-3,
                                     .resolution = 1e-3,
                                     .precision = GB_PROOF_PRECISION_DEFAULT};
        memcpy(h->def.rocking, h->info.rocking, sizeof h->def.rocking);
        status =
            gb_proof_body_inertia(&h->surface, 1.0, h->info.rocking, GB_PROOF_PRECISION_DEFAULT, &h->def.inertia, NULL);
    }
    gb_proof_body_chain_def cd;
    if (!status) status = gb_proof_body_chain_default(morphologies[b], &cd);
    if (!status) status = gb_proof_body_chain_design(&h->def, &table1, &cd, &h->chain);
    if (!status && shared_status[0] != GB_OK && shared_status[1] != GB_OK) atexit(release_shared);
    shared_status[b] = status;
    *s = *h;
    s->def.surface = &h->surface;
    return status;
}

static int setup_chain(chain_setup *s) { return setup_body(0, s); }

/* The cells `gomboc prove --horseshoe` shares among its links (src/gomboc_prove_chain.c): 2^-9 wide, to order 14. */
enum { CELL_LEVEL = 9, CELL_ORDER = 14 };

/* The float design of body b's chain against Liouville, and the rigorous period map of five of its centres; for
 * Gömböc I also its sets' disjointness (its links are not proved here: docs/proofs.md, "What is open"). */
static void design_check(int b)
{
    chain_setup s;
    int status = setup_body(b, &s), held = 0, points = 0, pairs = 0, apart = 0;
    const double T = 2.0 * M_PI / table1.omega;
    double e_saddle = NAN, e_orbit = NAN, widest = 0.0, farthest = 0.0, meeting = NAN;
    if (!status) {
        /* the orbit's two halves meet in the set at the homoclinic point: its smaller half-width */
        gb_proof_body_chain_def cd;
        status = gb_proof_body_chain_default(morphologies[b], &cd);
        const int at = cd.unstable_iterates - cd.first + 1;
        if (at >= 1 && (size_t)at < s.chain.sets) meeting = fmin(s.chain.set[at].half[0], s.chain.set[at].half[1]);
        const double M = 0.5 * s.def.inertia.lo + 0.5 * s.def.inertia.hi, e = exp(-table1.damping / M * T);
        e_saddle = s.chain.multipliers[0] * s.chain.multipliers[1] / e - 1.0;
        e_orbit = s.chain.liouville / pow(e, (double)(s.chain.orbit_points - 1)) - 1.0;
        /* the rigorous period map of the chain's centres holds the next centre (the float model's tables against the
         * proof's own H'): within 1e-8 */
        /* by the saddle and by its copy, where a period map costs the least (mid-excursion ones take seconds each) */
        const size_t m = s.chain.sets - 1, which[5] = {1, 2, 3, m - 2, m - 1};
        for (size_t k = 0; k < 5 && m > 4 && !status; k++) {
            const size_t i = which[k];
            const gb_proof_body_hset *a = &s.chain.set[i], *b = &s.chain.set[i + 1];
            if (s.chain.tie[i] >= 0) continue;
            const gb_proof_interval box[2] = {{a->centre[0], a->centre[0]}, {a->centre[1], a->centre[1]}};
            gb_proof_body_return r;
            status = gb_proof_body_period_map(&s.def, &table1, box, 1, 12, 0, &r);
            if (status) break;
            points++;
            const double dq = fmax(b->centre[0] - r.q.hi, r.q.lo - b->centre[0]),
                         dp = fmax(b->centre[1] - r.P.hi, r.P.lo - b->centre[1]);
            farthest = fmax(farthest, fmax(dq, dp));
            widest = fmax(widest, fmax(r.q.hi - r.q.lo, r.P.hi - r.P.lo));
            held += dq <= 1e-8 && dp <= 1e-8;
        }
    }
    for (size_t i = 0; b == 1 && !status && i < s.chain.sets; i++)
        for (size_t j = i + 1; j < s.chain.sets; j++)
            pairs++,
                apart += gb_proof_body_hsets_disjoint(&s.chain.set[i], &s.chain.set[j], GB_PROOF_PRECISION_DEFAULT);
    char what[160];
    snprintf(what, sizeof what,
             "a homoclinic orbit of Gomboc %s's period map and the chain's frames along it (floats)%s", morphologies[b],
             b ? "; its sets apart on the cylinder" : "");
    gb_check c = {"7", "78, 91", what,
                  "Liouville: det DP = exp(-mu T) at the saddle and along the orbit (the product of the frames' "
                  "stretchings); the rigorous period map of the sets' centres",
                  "central differences of the float map (step 1e-6, GSL 1e-13): 1e-6 relative; the float model's "
                  "tables against the rigorous H': 1e-8; Newton's residual a hundredth of the set where the orbit's "
                  "halves meet"};
    gb_check_true(&c,
                  !status && s.chain.residual < 0.01 * meeting && fabs(e_saddle) < 1e-6 && fabs(e_orbit) < 1e-5 &&
                      held == points && points >= 5 && apart == pairs && (b == 0 || pairs > 0),
                  "Newton's residual %.2g (the set there %.2g across or along); multipliers %.10f, %.10f (their "
                  "product against exp(-mu T): %.2g); along "
                  "%zu points: %.2g; %zu sets, %d of %d centres' images holding the next (farthest %.2g, enclosures "
                  "%.2g wide); %d of %d pairs apart%s%s",
                  s.chain.residual, meeting, s.chain.multipliers[0], s.chain.multipliers[1], e_saddle,
                  s.chain.orbit_points, e_orbit, s.chain.sets, held, points, farthest, widest, apart, pairs,
                  status ? ": " : "", status ? gb_error_message() : "");
}

static void test_design(void) { design_check(0); }
static void test_design_one(void) { design_check(1); }

/* The links by the saddle: N0 => N0, N0 => N1, N1 => N2, and the negative controls on N1 => N2. */
static void test_links(void)
{
    chain_setup s;
    int status = setup_chain(&s), proved = 0, strip_refused = 0, edges_refused = 0;
    double seconds = 0.0, strip_margin = INFINITY, edge_margin = INFINITY;
    char first[400] = "";
    gb_proof_body_arcs *arcs = NULL;
    if (!status) status = gb_proof_body_arcs_create(&s.def, CELL_LEVEL, CELL_ORDER, &arcs);
    s.def.arcs = arcs;
    if (!status) {
        const gb_proof_body_hset *N = s.chain.set;
        const int from[3] = {0, 0, 1}, to[3] = {0, 1, 2};
        for (int k = 0; k < 3 && !status; k++) {
            gb_proof_body_link r;
            status = gb_proof_body_cover_link(&s.def, &table1, NULL, &N[from[k]], &N[to[k]], 0, 1, 6, 12, &r);
            proved += r.covers, seconds += r.seconds;
            strip_margin = fmin(strip_margin, r.strip_margin), edge_margin = fmin(edge_margin, r.edge_margin);
            if (!r.covers && !first[0]) snprintf(first, sizeof first, "; N%d => N%d: %s", from[k], to[k], r.failure);
        }
        /* N2 moved along by three half-widths: the image leaves its strip */
        gb_proof_body_hset moved = N[2];
        for (int i = 0; i < 2; i++) moved.centre[i] += 3.0 * moved.half[1] * moved.frame[i][1];
        gb_proof_body_link r;
        if (!status) status = gb_proof_body_cover_link(&s.def, &table1, NULL, &N[1], &moved, 0, 1, 2, 12, &r);
        strip_refused = !status && !r.strip;
        /* N2 a fifth wider across: the edges' images fall inside it */
        gb_proof_body_hset wide = N[2];
        wide.half[0] *= 1.2;
        if (!status) status = gb_proof_body_cover_link(&s.def, &table1, NULL, &N[1], &wide, 0, 1, 2, 12, &r);
        edges_refused = !status && r.strip && !r.edges;
    }
    gb_proof_body_arcs_free(arcs);
    gb_check c = {"7", "78, 91",
                  "covering relations of Gomboc II's period map by the saddle: N0 => N0, N0 => N1, N1 => N2",
                  "the covering relation's two conditions proved on Arb's balls (mean value form, C1 period map, H's "
                  "coefficients from the shared cells as the command takes them); negative controls: the target moved "
                  "along by three half-widths, or a fifth wider across",
                  "proved or not proved: no tolerance (the design's margin is 1 - 1/rho = 0.048 of the target)"};
    gb_check_true(&c, !status && proved == 3 && strip_refused && edges_refused,
                  "%d of 3 proved (strip margin %.3f, edges beyond by %.3f of the target's half-widths), moved target "
                  "refused %d, widened target refused %d; %.1f s CPU%s%s%s",
                  proved, strip_margin, edge_margin, strip_refused, edges_refused, seconds, first, status ? ": " : "",
                  status ? gb_error_message() : "");
}

/* No tie of the float model within `gap` of [q0, q1]. */
static int clear_of_ties(const gb_melnikov_body_info *info, double q0, double q1, double gap)
{
    for (size_t k = 0; k < info->kinks && k < 16; k++)
        if (info->kink_q[k] > q0 - gap && info->kink_q[k] < q1 + gap) return 0;
    return 1;
}

static double width(gb_proof_interval x) { return x.hi - x.lo; }

/* H's coefficients over arcs as the links take them (the hull of the shared cells') against the points' at each arc's
 * ends and middle and against the arc's own enclosure; a tie's cell refused; one answer whatever the table held. */
static void test_cells(void)
{
    enum { ARCS = 16 };
    chain_setup s;
    int status = setup_chain(&s), arcs = 0, served = 0, inside_cells = 0, inside_own = 0, ties = 0, declined = 0;
    int same = 0, other_def = 0;
    double ratio_lo = INFINITY, ratio_hi = 0.0;
    char first[300] = "";
    gb_proof_body_arcs *A = NULL, *B = NULL;
    if (!status) status = gb_proof_body_arcs_create(&s.def, CELL_LEVEL, CELL_ORDER, &A);
    if (!status) status = gb_proof_body_arcs_create(&s.def, CELL_LEVEL, CELL_ORDER, &B);
    double q[ARCS][2];
    gb_proof_interval H[ARCS][CELL_ORDER + 1];
    int asked[ARCS] = {0};
    for (int k = 0; k < ARCS && !status; k++) { /* arcs 0.008 … 0.05 wide (the cells serve H_14 over 4 or more) */
        q[k][0] = 0.35 + 5.6 * k / ARCS, q[k][1] = q[k][0] + 0.008 + 0.042 * (k % 4) / 3.0;
        if (!clear_of_ties(&s.info, q[k][0], q[k][1], 0.06)) continue;
        arcs++, asked[k] = 1;
        if (!gb_proof_body_arcs_jet(A, &s.def, q[k][0], q[k][1], CELL_ORDER, H[k])) continue;
        served++, asked[k] = 2;
        gb_proof_body_jet own, at;
        status = gb_proof_body_jet_enclose(&s.def, q[k][0], q[k][1], CELL_ORDER, &own);
        int in_cells = 1, in_own = 1;
        for (int i = 0; i < 3 && !status; i++) {
            const double x = i == 1 ? 0.5 * q[k][0] + 0.5 * q[k][1] : q[k][i / 2];
            status = gb_proof_body_jet_enclose(&s.def, x, x, CELL_ORDER, &at);
            for (int c = 0; c <= CELL_ORDER && !status; c++) {
                in_cells &= at.H[c].lo >= H[k][c].lo && at.H[c].hi <= H[k][c].hi;
                in_own &= at.H[c].lo >= own.H[c].lo && at.H[c].hi <= own.H[c].hi;
            }
        }
        inside_cells += in_cells, inside_own += in_own;
        for (int c = 1; c <= CELL_ORDER && !status; c += CELL_ORDER - 1) {
            const double r = width(H[k][c]) / width(own.H[c]);
            ratio_lo = fmin(ratio_lo, r), ratio_hi = fmax(ratio_hi, r);
        }
        if (!in_cells && !first[0])
            snprintf(first, sizeof first, "; arc [%.6g, %.6g]: a point's coefficients outside the cells' hull", q[k][0],
                     q[k][1]);
    }
    for (size_t t = 0; t < s.info.kinks && t < 16 && !status; t++) { /* an arc across a tie */
        gb_proof_interval T[3];
        ties++;
        declined += !gb_proof_body_arcs_jet(A, &s.def, s.info.kink_q[t] - 3e-3, s.info.kink_q[t] + 3e-3, 2, T);
    }
    for (int k = ARCS - 1; k >= 0 && !status; k--) /* B answers the arcs in the other order */
        if (asked[k] == 2) {
            gb_proof_interval again[CELL_ORDER + 1];
            same += gb_proof_body_arcs_jet(B, &s.def, q[k][0], q[k][1], CELL_ORDER, again) &&
                    !memcmp(again, H[k], sizeof again);
        }
    gb_proof_body_arcs_stats stats = {0};
    if (A) gb_proof_body_arcs_get_stats(A, &stats);
    gb_proof_body_def other = s.def;
    other.precision = 2 * s.def.precision;
    gb_proof_interval T[3];
    other_def = !status && !gb_proof_body_arcs_jet(A, &other, 1.0, 1.01, 2, T);
    gb_proof_body_arcs_free(A), gb_proof_body_arcs_free(B);
    gb_check c = {
        "7", "78, 91",
        "Gomboc II's H over arcs 0.008 ... 0.05 wide at 16 places of q (those 0.06 clear of its ties) from cells of q "
        "2^-9 wide, to order 14, as the "
        "horseshoe's links take them",
        "each arc's ends' and middle's coefficients (enclosed alone) inside the cells' hull and inside the "
        "arc's own enclosure; arcs across the ties not served; a second table asked in the other order",
        "inclusion, exact (balls); the second table's answers bit for bit"};
    gb_check_true(&c,
                  !status && arcs >= 12 && served == arcs && inside_cells == served && inside_own == served &&
                      ties >= 1 && declined == ties && stats.refused >= (size_t)ties && same == served && other_def,
                  "%d of %d arcs served (%zu cells enclosed, %zu refused), points inside the cells' hull %d and the "
                  "arc's own %d; widths of H_1 and H_14 over the cells' hull / the arc's own %.2g to %.2g; %d of %d "
                  "arcs across a tie not served; %d answers the same from the second table; another definition not "
                  "served %d; %.1f s CPU in the cells%s%s%s",
                  served, arcs, stats.cells, stats.refused, inside_cells, inside_own, ratio_lo, ratio_hi, declined,
                  ties, same, other_def, stats.seconds, first, status ? ": " : "", status ? gb_error_message() : "");
}

/* The largest root of x^L = x^{L-1} + 1 in doubles (bisection on (1, 2]). */
static double cycle_root(int L)
{
    double lo = 1.0, hi = 2.0;
    for (int k = 0; k < 200; k++) {
        const double mid = 0.5 * (lo + hi);
        if (pow(mid, L - 1) * (mid - 1.0) < 1.0)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

static void test_disjoint_entropy(void)
{
    chain_setup s;
    int status = setup_chain(&s), pairs = 0, apart = 0, self = 0;
    double golden = NAN, chain_bound = NAN;
    if (!status) {
        for (size_t i = 0; i < s.chain.sets; i++)
            for (size_t j = i + 1; j < s.chain.sets; j++)
                pairs++, apart += gb_proof_body_hsets_disjoint(&s.chain.set[i], &s.chain.set[j], GB_PROOF_PRECISION_DEFAULT);
        gb_proof_body_hset copy = s.chain.set[0];
        copy.centre[0] += 2.0 * M_PI;
        self = gb_proof_body_hsets_disjoint(&s.chain.set[0], &s.chain.set[0], GB_PROOF_PRECISION_DEFAULT) +
               gb_proof_body_hsets_disjoint(&s.chain.set[0], &copy, GB_PROOF_PRECISION_DEFAULT);
        status = gb_proof_body_chain_entropy(2, &golden);
        if (!status) status = gb_proof_body_chain_entropy((int)s.chain.sets, &chain_bound);
    }
    const double phi = log(0.5 * (1.0 + sqrt(5.0))), root = log(cycle_root((int)s.chain.sets));
    gb_check c = {"7", "78, 91", "the chain's sets apart on the cylinder, and the entropy of a self-loop and a cycle",
                  "separating axes of parallelograms on Arb's balls; ln of the golden ratio (cycle of 2) and a float "
                  "bisection of x^L = x^(L-1) + 1",
                  "the bound lies below the root and within 1e-12 of it (a bisection to 60 halvings)"};
    gb_check_true(&c,
                  !status && apart == pairs && pairs > 0 && self == 0 && golden <= phi && golden > phi - 1e-12 &&
                      chain_bound <= root && chain_bound > root - 1e-12,
                  "%d of %d pairs apart, a set against itself or 2 pi on apart %d of 2; cycle of 2: %.15f (ln golden "
                  "ratio %.15f); cycle of %zu: %.15f (float root %.15f)%s%s",
                  apart, pairs, self, golden, phi, s.chain.sets, chain_bound, root, status ? ": " : "",
                  status ? gb_error_message() : "");
}

static void test_bad_chains(void)
{
    chain_setup s;
    int status = setup_chain(&s), refused = 0, named = 0, cases = 0;
    if (!status) {
        const gb_proof_body_hset good = s.chain.set[1];
        gb_proof_body_hset flat = good, singular = good;
        flat.half[1] = 0.0;
        singular.frame[0][1] = singular.frame[0][0], singular.frame[1][1] = singular.frame[1][0];
        struct {
            const gb_proof_body_hset *N, *M;
            int turns, pieces, depth;
            const char *word;
        } bad[] = {{&flat, &good, 0, 1, 2, "half-widths"}, {&good, &singular, 0, 1, 2, "frame"},
                   {&good, &good, 2, 1, 2, "turns"},       {&good, &good, 0, 0, 2, "pieces"},
                   {&good, &good, 0, 1, 21, "depth"}};
        for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++, cases++) {
            gb_proof_body_link r;
            const int st = gb_proof_body_cover_link(&s.def, &table1, NULL, bad[k].N, bad[k].M, bad[k].turns,
                                                    bad[k].pieces, bad[k].depth, 12, &r);
            refused += st == GB_EDOM, named += st == GB_EDOM && strstr(gb_error_message(), bad[k].word) != NULL;
            gb_error_clear();
        }
        gb_proof_body_chain_def cd;
        gb_proof_body_chain_default("II", &cd);
        gb_proof_body_chain_def defs[4] = {cd, cd, cd, cd};
        defs[0].rho = 1.0, defs[1].first = defs[1].last, defs[2].unstable_seed = 0.0, defs[3].stable_iterates = 0;
        const char *words[4] = {"rho", "first", "seeds", "iterates"};
        for (int k = 0; k < 4; k++, cases++) {
            gb_proof_body_chain out;
            const int st = gb_proof_body_chain_design(&s.def, &table1, &defs[k], &out);
            refused += st == GB_EDOM, named += st == GB_EDOM && strstr(gb_error_message(), words[k]) != NULL;
            gb_error_clear();
        }
        gb_proof_body_chain_def none;
        cases++;
        const int sd = gb_proof_body_chain_default("III", &none);
        refused += sd == GB_EDOM, named += sd == GB_EDOM && strstr(gb_error_message(), "I, II") != NULL;
        gb_error_clear();
        double h = 0.0;
        cases++;
        const int st = gb_proof_body_chain_entropy(1, &h);
        refused += st == GB_EDOM, named += st == GB_EDOM && strstr(gb_error_message(), "length") != NULL;
        gb_error_clear();
        const struct {
            int level, order;
            const char *word;
        } cells[4] = {{GB_PROOF_BODY_ARCS_LEVEL_MIN - 1, 2, "level"},
                      {GB_PROOF_BODY_ARCS_LEVEL_MAX + 1, 2, "level"},
                      {CELL_LEVEL, 0, "order"},
                      {CELL_LEVEL, GB_PROOF_BODY_JET_ORDER_MAX + 1, "order"}};
        for (int k = 0; k < 4; k++, cases++) {
            gb_proof_body_arcs *arcs = NULL;
            const int sc = gb_proof_body_arcs_create(&s.def, cells[k].level, cells[k].order, &arcs);
            refused += sc == GB_EDOM && !arcs, named += sc == GB_EDOM && strstr(gb_error_message(), cells[k].word) &&
                                                        strstr(gb_error_message(), "allowed");
            gb_error_clear();
            gb_proof_body_arcs_free(arcs);
        }
    }
    gb_check c = {"7", "78, 91", "bad h-sets, pieces, depths, turns, chains, bodies, cycles and cells refused",
                  "each names what is out of range", "exact"};
    gb_check_true(&c, !status && refused == cases && named == cases && cases == 15,
                  "%d of %d refused, %d naming the argument%s%s", refused, cases, named, status ? ": " : "",
                  status ? gb_error_message() : "");
}

int verify_register_s7_horseshoe(void)
{
    static const verify_test tests[] = {
        {"proofs: a homoclinic orbit of Gomboc II's period map and the chain's frames", test_design,
         "the h-sets of a horseshoe sit along a homoclinic orbit of the period map in frames of its manifolds"},
        {"proofs: covering relations of the period map by the saddle", test_links,
         "the period map's covering relations of parallelograms are proved, and refused when either condition "
         "fails"},
        {"proofs: the chain's sets apart and the entropy of its graph", test_disjoint_entropy,
         "a horseshoe's sets are disjoint on the cylinder, and its graph's entropy is bounded below rigorously"},
        {"proofs: Gomboc I's default sets along its homoclinic orbit", test_design_one,
         "the h-sets of a horseshoe sit along a homoclinic orbit of the period map in frames of its manifolds"},
        {"proofs: H's coefficients from the links' shared cells of q", test_cells,
         "a Taylor step of the period map may take H's coefficients over its arc from enclosures over fixed cells "
         "shared by all links"},
        {"proofs: bad h-sets and chains", test_bad_chains, NULL},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Proved on Arb's balls: covering relations of Gomboc II's period map along a "
                                 "homoclinic orbit, and Gomboc I's sets (section 7)",
                                 tests);
}
