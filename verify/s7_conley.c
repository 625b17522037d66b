/* Proved on Arb's balls: the discrete Conley index of a map of the plane on a grid of boxes, over Z2, and the entropy
 * bound of the sofic shift its index map forces (gb_proof_conley).
 *
 * Oracles, none sharing code with what they check:
 * - linear maps whose Conley index is known in closed form: a sink (H_0 = Z2), a saddle with its unstable direction
 *   kept or flipped (H_1 = Z2, the index map 1) and a source (H_2 = Z2), each on a grid around the fixed point;
 * - Hénon's map at a = 6, b = 0.3, a full horseshoe (Devaney and Nitecki 1979): the bound at depths 5 ... 8 must come
 *   within 1e-9 of ln 2 and, by Friedland and Milnor's h_top ≤ ln 2 for every Hénon map, never above it;
 * - the classical Hénon map from its periodic points of periods 1 ... 6: their number, 20 points, is the published
 *   count of its orbits (two fixed points, one orbit each of periods 2 and 4, two of period 6; Davis, MacKay and
 *   Sannami 1991); a positive bound, at most ln 2; the same seeds with an orbit of period 6 left out or one of
 *   period 7 added by name (6 and 7 boxes fewer or more), and names matching no orbit refused;
 * - the sofic graph on index maps written by hand: the golden-mean shift (entropy ln φ), and a map whose only
 *   return to a region passes through a vector its block sends to zero (a product that is nilpotent: entropy 0, where
 *   counting that vector's transition would give ln φ);
 * - negative controls with teeth: each of the index pair's three conditions broken by a change of P0 or P1 is refused,
 *   with nothing claimed;
 * - the definitions' ranges: each bad grid, pair or dimension refused with GB_EDOM naming it. */
#include "gb_check.h"
#include "gb_error.h"
#include "gb_proof_conley.h"
#include "gb_proof_conley_sofic_internal.h"
#include "gb_proof_cover.h"
#include "verify_sections.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The pair built on N = every box off the grid's edge, then proved; 0 or the status. */
static int whole_grid(gb_proof_conley_def *def, gb_proof_conley_result *r, uint32_t **p1, size_t *n1, uint32_t **p0,
                      size_t *n0)
{
    const long side = 1L << def->depth;
    uint32_t *N = malloc((size_t)(side * side) * sizeof *N);
    size_t n = 0;
    if (!N) return GB_ENOMEM;
    for (long j = 1; j < side - 1; j++)
        for (long i = 1; i < side - 1; i++) N[n++] = (uint32_t)(j * side + i);
    int status = gb_proof_conley_pair(def, N, n, p1, n1, p0, n0);
    free(N);
    if (status) return status;
    def->p1 = *p1, def->p1_count = *n1, def->p0 = *p0, def->p0_count = *n0;
    return gb_proof_conley(def, r);
}

static gb_proof_field linear_map(long a, long a_den, long d, long d_den)
{
    gb_proof_field f;
    memset(&f, 0, sizeof f);
    f.dimension = 2;
    f.L[0][0] = (gb_proof_rational){a, a_den}, f.L[1][1] = (gb_proof_rational){d, d_den};
    return f;
}

static void test_linear(void)
{
    static const struct {
        const char *name;
        long a, a_den, d, d_den;
        long h[3];
    } maps[] = {{"sink (x/2, y/2)", 1, 2, 1, 2, {1, 0, 0}},
                {"saddle (2x, y/2)", 2, 1, 1, 2, {0, 1, 0}},
                {"saddle, flipped (-2x, y/2)", -2, 1, 1, 2, {0, 1, 0}},
                {"source (2x, 2y)", 2, 1, 2, 1, {0, 0, 1}}};
    int met = 0, status = GB_OK;
    char first[300] = "";
    for (size_t k = 0; k < sizeof maps / sizeof maps[0] && !status; k++) {
        gb_proof_field f = linear_map(maps[k].a, maps[k].a_den, maps[k].d, maps[k].d_den);
        gb_proof_conley_def def = gb_proof_conley_def_default();
        def.map = &f, def.depth = 5, def.x = (gb_proof_interval){-1, 1}, def.y = (gb_proof_interval){-1, 1};
        gb_proof_conley_result r;
        uint32_t *p1 = NULL, *p0 = NULL;
        size_t n1, n0;
        status = whole_grid(&def, &r, &p1, &n1, &p0, &n0);
        free(p1), free(p0);
        /* the saddle's index map on H_1 = Z2 is 1: one symbol with a loop; the others have no H_1 */
        const int map_ok = maps[k].h[1] ? r.symbols == 1 && r.transitions == 1 : r.symbols == 0;
        const int ok = !status && r.index_pair && r.h0 == maps[k].h[0] && r.h1 == maps[k].h[1] &&
                       r.h2 == maps[k].h[2] && map_ok && r.entropy == 0.0;
        met += ok;
        if (!ok && !first[0])
            snprintf(first, sizeof first, "; %s: index pair %d, H = (%ld, %ld, %ld), %ld symbols, %ld transitions%s%s",
                     maps[k].name, r.index_pair, r.h0, r.h1, r.h2, r.symbols, r.transitions, status ? ": " : "",
                     status ? gb_error_message() : "");
    }
    gb_check c = {"-", "-", "the Conley index of linear maps' fixed points: sink, saddle (kept and flipped), source",
                  "closed form: H_*(P1, P0; Z2) is Z2 in the dimension of the unstable directions (0, 1, 1, 2), the "
                  "saddle's index map 1",
                  "exact: ranks and the map over Z2"};
    gb_check_true(&c, met == 4, "%d of 4 met%s", met, first);
}

static void test_horseshoe(void)
{
    int met = 0, status = GB_OK;
    double worst = 0.0, above = -1.0;
    char first[300] = "";
    for (int depth = 5; depth <= 8 && !status; depth++) {
        gb_proof_field f;
        gb_proof_conley_def def;
        uint32_t *N = NULL, *p1 = NULL, *p0 = NULL;
        size_t n, n1, n0;
        gb_proof_conley_result r;
        status = gb_proof_conley_henon_horseshoe(depth, &f, &def, &N, &n);
        if (!status) status = gb_proof_conley_pair(&def, N, n, &p1, &n1, &p0, &n0);
        if (!status) def.p1 = p1, def.p1_count = n1, def.p0 = p0, def.p0_count = n0, status = gb_proof_conley(&def, &r);
        free(N), free(p1), free(p0);
        if (status) break;
        const double gap = log(2.0) - r.entropy;
        worst = fmax(worst, gap), above = fmax(above, -gap);
        const int ok = r.index_pair && gap >= 0.0 && gap < 1e-9;
        met += ok;
        if (!ok && !first[0])
            snprintf(first, sizeof first, "; depth %d: index pair %d, h_top >= %.12f (%s)", depth, r.index_pair,
                     r.entropy, r.failure);
    }
    gb_check c = {"-", "-", "Henon at a = 6, b = 0.3 by its discrete Conley index, depths 5 ... 8",
                  "ln 2 (Devaney & Nitecki's full horseshoe; Friedland & Milnor: h_top <= ln 2 for every Henon map)",
                  "a lower bound within 1e-9 below ln 2 (Arb's logarithm rounded down), never above it"};
    gb_check_true(&c, !status && met == 4, "%d of 4 depths at ln 2 - %.2g (the largest gap)%s%s%s", met, worst, first,
                  status ? ": " : "", status ? gb_error_message() : "");
}

static void test_classical(void)
{
    gb_proof_field f;
    gb_proof_conley_def def;
    uint32_t *seeds = NULL, *N = NULL, *p1 = NULL, *p0 = NULL;
    size_t count = 0, n = 0, n1 = 0, n0 = 0;
    gb_proof_conley_result r = {0};
    int status = gb_proof_conley_henon_classical(6, 9, &f, &def, &seeds, &count);
    if (!status) status = gb_proof_conley_isolate(&def, seeds, count, 100000, &N, &n);
    if (!status) status = gb_proof_conley_pair(&def, N, n, &p1, &n1, &p0, &n0);
    if (!status) def.p1 = p1, def.p1_count = n1, def.p0 = p0, def.p0_count = n0, status = gb_proof_conley(&def, &r);
    free(seeds), free(N), free(p1), free(p0);
    gb_check c = {
        "-", "-",
        "the classical Henon map by its discrete Conley index: depth 9, N grown from its periodic points of "
        "periods 1 ... 6",
        "20 periodic points (the published orbit count: 2 fixed points, one orbit of period 2, one of 4, two of "
        "6, each point in its own box); a positive bound, at most ln 2 (Friedland & Milnor)",
        "exact count; the bound a proved one (h_top >= it), 0 < bound <= ln 2"};
    gb_check_true(&c, !status && count == 20 && r.index_pair && r.entropy > 0.0 && r.entropy <= log(2.0),
                  "%zu seeds, N %zu boxes, P1 %zu, P0 %zu, index pair %d, H_1 of rank %ld on %ld regions, %ld symbols, "
                  "h_top >= %.9f%s%s",
                  count, n, n1, n0, r.index_pair, r.h1, r.regions, r.symbols, r.entropy, status ? ": " : "",
                  status ? gb_error_message() : "");
}

/* The orbits kept, changed by name: at depth 9 every periodic point of periods up to 7 has a box of its own, so leaving
 * out an orbit of period 6 and adding one of period 7 move the seeds by 6 and 7; a name that matches no orbit, or a
 * period beyond 16, is refused. The least x are those of the orbits (Newton on doubles, printed to 9 decimals). */
static void test_orbits(void)
{
    static const gb_proof_conley_orbit out6[] = {{6, -0.804219901}}, in7[] = {{7, -0.926173277}}, none[] = {{7, -0.5}},
                                       long17[] = {{17, 0.0}};
    const struct {
        const gb_proof_conley_orbit *toggle;
        size_t expect;    /* seeds; 0: refused */
        const char *must; /* in the refusal */
    } cases[] = {{NULL, 20, NULL}, {out6, 14, NULL}, {in7, 27, NULL}, {none, 0, "exactly one"}, {long17, 0, "period"}};
    enum { CASES = sizeof cases / sizeof *cases };
    int met = 0;
    char got[400] = "", *at = got;
    for (int k = 0; k < CASES; k++) {
        gb_proof_field f;
        gb_proof_conley_def def;
        uint32_t *seeds = NULL;
        size_t count = 0;
        const int status =
            gb_proof_conley_henon_orbits(6, cases[k].toggle, cases[k].toggle ? 1 : 0, 9, &f, &def, &seeds, &count);
        free(seeds);
        met += cases[k].expect ? status == GB_OK && count == cases[k].expect
                               : status == GB_EDOM && strstr(gb_error_message(), cases[k].must) &&
                                     strstr(gb_error_message(), "allowed");
        at += snprintf(at, (size_t)(got + sizeof got - at), "%s%s", k ? "; " : "",
                       status ? (status == GB_EDOM ? "refused" : "failed") : "");
        if (!status) at += snprintf(at, (size_t)(got + sizeof got - at), "%zu seeds", count);
    }
    gb_check c = {"-", "-",
                  "the classical Henon map's seeds changed orbit by orbit (depth 9, periods up to 6): none named, an "
                  "orbit of period 6 left out, one of period 7 added, a name matching no orbit, period 17",
                  "20, 14 and 27 seeds (each point its own box); GB_EDOM naming the orbit and what is allowed",
                  "exact"};
    gb_check_true(&c, met == CASES, "%d of %d as expected: %s", met, CASES, got);
}

/* Regions B = box (3, 3) with generator b and A = box (8, 8) with a1, a2 on a grid of depth 4; the index map's columns
 * (images of b, a1, a2) as bit masks over the rows (b, a1, a2). */
static int sofic_by_hand(const unsigned columns[3], conley_sofic *out)
{
    static const uint32_t boxes[2] = {3 * 16 + 3, 8 * 16 + 8};
    uint8_t state[256] = {0};
    state[boxes[0]] = state[boxes[1]] = CONLEY_P1 | CONLEY_Q;
    const conley_grid g = {.depth = 4, .n = 16, .state = state, .p1_count = 2, .p1 = boxes};
    uint64_t map[3] = {0, 0, 0};
    int32_t square[3] = {(int32_t)boxes[0], (int32_t)boxes[1], (int32_t)boxes[1]};
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++)
            if (columns[c] >> r & 1) map[r] |= 1ull << c;
    const conley_homology h = {.h1 = 3, .generators = 3, .words = 1, .map = map, .square = square};
    return conley_sofic_entropy(&g, &h, 128, 6, out);
}

static void test_sofic(void)
{
    /* golden mean: b -> b + a1, a1 -> b, a2 -> 0; cancelling: b -> b + a1 + a2, a1 -> b, a2 -> b */
    const unsigned golden[3] = {1 | 2, 1, 0}, cancelling[3] = {1 | 2 | 4, 1, 1};
    conley_sofic rg = {0}, rc = {0};
    const int status = sofic_by_hand(golden, &rg) || sofic_by_hand(cancelling, &rc);
    const double phi = log(0.5 * (1.0 + sqrt(5.0)));
    gb_check c = {"-", "-", "the sofic graph of an index map's blocks, on maps written by hand",
                  "closed forms: the golden-mean shift ln((1 + sqrt 5) / 2); a block product that is nilpotent (B -> A "
                  "-> B through a vector A's block sends to zero) 0",
                  "a lower bound within 1e-9 below ln phi, never above; exactly 0"};
    gb_check_true(&c, !status && rg.entropy <= phi && rg.entropy > phi - 1e-9 && rc.entropy == 0.0 && rc.regions == 2,
                  "golden mean: %.12f against %.12f (%ld symbols, %ld transitions); the nilpotent product: %.12f (%ld "
                  "symbols, %ld transitions)%s%s",
                  rg.entropy, phi, rg.symbols, rg.transitions, rc.entropy, rc.symbols, rc.transitions,
                  status ? ": " : "", status ? gb_error_message() : "");
}

/* Each condition broken in turn: proved nothing. */
static void test_controls(void)
{
    gb_proof_field f;
    gb_proof_conley_def def;
    uint32_t *N = NULL, *p1 = NULL, *p0 = NULL;
    size_t n, n1 = 0, n0 = 0;
    gb_proof_conley_result r;
    int status = gb_proof_conley_henon_horseshoe(6, &f, &def, &N, &n);
    if (!status) status = gb_proof_conley_pair(&def, N, n, &p1, &n1, &p0, &n0);
    int exit_broken = 0, invariance_broken = 0, isolation_broken = 0;
    char what[3][200] = {"", "", ""};
    if (!status) { /* P0 emptied: F(P1) \ P1 now touches P1 \ P0 */
        def.p1 = p1, def.p1_count = n1, def.p0 = p0, def.p0_count = 0;
        status = gb_proof_conley(&def, &r);
        exit_broken = !status && !r.exit_set && !r.index_pair && r.entropy == 0.0 && strstr(r.failure, "exit set");
        memcpy(what[0], r.failure, sizeof what[0]);
    }
    uint32_t *more = NULL;
    if (!status) { /* the box of the fixed point (0.3539, 0.1062) added to P0: F(P0) meets P1 \ P0 there */
        const long side = 1L << def.depth;
        const uint32_t fixed =
            (uint32_t)((long)floor((0.1062 + 1.0) / 2.0 * side) * side + (long)floor((0.3539 + 1.0) / 2.0 * side));
        more = malloc((n0 + 1) * sizeof *more);
        size_t m = 0;
        for (size_t k = 0; more && k < n0; k++) more[m++] = p0[k];
        if (more) more[m++] = fixed, qsort(more, m, sizeof *more, conley_compare_boxes);
        def.p0 = more, def.p0_count = m;
        status = more ? gb_proof_conley(&def, &r) : GB_ENOMEM;
        invariance_broken = !status && !r.positively_invariant && !r.index_pair && r.entropy == 0.0;
        memcpy(what[1], r.failure, sizeof what[1]);
    }
    free(more), free(N), free(p1), free(p0), p1 = p0 = NULL;
    if (!status) { /* the sink's 6 x 6 boxes with their outer ring as P0: its invariant boxes touch P0 */
        gb_proof_field sink = linear_map(1, 2, 1, 2);
        def = gb_proof_conley_def_default();
        def.map = &sink, def.depth = 5, def.x = (gb_proof_interval){-1, 1}, def.y = (gb_proof_interval){-1, 1};
        uint32_t box[36], ring[20];
        size_t b = 0, q = 0;
        for (long j = 13; j <= 18; j++)
            for (long i = 13; i <= 18; i++) {
                box[b++] = (uint32_t)(j * 32 + i);
                if (i == 13 || i == 18 || j == 13 || j == 18) ring[q++] = (uint32_t)(j * 32 + i);
            }
        def.p1 = box, def.p1_count = b, def.p0 = ring, def.p0_count = q;
        status = gb_proof_conley(&def, &r);
        isolation_broken = !status && !r.isolated && !r.index_pair && r.entropy == 0.0;
        memcpy(what[2], r.failure, sizeof what[2]);
    }
    gb_check c = {"-", "-", "the index pair's conditions: negative controls",
                  "a = 6's pair with P0 emptied (exit set), with the fixed point's box added to P0 (positive "
                  "invariance); the sink's boxes with their ring as P0 (isolation)",
                  "exact: each refused, nothing claimed"};
    gb_check_true(&c, !status && exit_broken && invariance_broken && isolation_broken,
                  "exit set %s (%s); positive invariance %s (%s); isolation %s (%s)%s%s",
                  exit_broken ? "refused" : "NOT REFUSED", what[0], invariance_broken ? "refused" : "NOT REFUSED",
                  what[1], isolation_broken ? "refused" : "NOT REFUSED", what[2], status ? ": " : "",
                  status ? gb_error_message() : "");
}

static void test_refused(void)
{
    gb_proof_field f = gb_proof_cover_henon(6, 1, 3, 10);
    const gb_proof_field three_d = gb_proof_flow_rossler(1, 5, 1, 5, 57, 10);
    gb_proof_conley_def good = gb_proof_conley_def_default();
    good.map = &f, good.depth = 4, good.x = (gb_proof_interval){-1, 1}, good.y = (gb_proof_interval){-1, 1};
    static const uint32_t p1[] = {17, 18, 33, 34}, p0[] = {18}, unordered[] = {18, 17}, edge[] = {1, 17},
                          stray[] = {20};
    good.p1 = p1, good.p1_count = 4, good.p0 = p0, good.p0_count = 1;
    enum { BAD = 9 };
    struct {
        const char *what, *must;
        gb_proof_conley_def def;
    } bad[BAD];
    for (int k = 0; k < BAD; k++) bad[k].def = good;
    bad[0].what = "depth 15", bad[0].must = "depth", bad[0].def.depth = 15;
    bad[1].what = "depth 1", bad[1].must = "depth", bad[1].def.depth = 1;
    bad[2].what = "x of length 3", bad[2].must = "x =", bad[2].def.x = (gb_proof_interval){-1, 2};
    bad[3].what = "y off the boxes' lattice", bad[3].must = "y =", bad[3].def.y = (gb_proof_interval){-0.9, 1.1};
    bad[4].what = "P1 out of order", bad[4].must = "p1[1]", bad[4].def.p1 = unordered, bad[4].def.p1_count = 2,
    bad[4].def.p0_count = 0;
    bad[5].what = "a box on the grid's edge", bad[5].must = "edge", bad[5].def.p1 = edge, bad[5].def.p1_count = 2,
    bad[5].def.p0_count = 0;
    bad[6].what = "P0 outside P1", bad[6].must = "p0[0]", bad[6].def.p0 = stray;
    bad[7].what = "region dimension 13", bad[7].must = "region_dimension", bad[7].def.region_dimension = 13;
    bad[8].what = "a field of R^3", bad[8].must = "dimension", bad[8].def.map = &three_d;
    int refused = 0;
    char first[300] = "";
    for (int k = 0; k < BAD; k++) {
        gb_proof_conley_result r;
        const int status = gb_proof_conley(&bad[k].def, &r);
        const int ok =
            status == GB_EDOM && strstr(gb_error_message(), bad[k].must) && strstr(gb_error_message(), "allowed");
        refused += ok;
        if (!ok && !first[0])
            snprintf(first, sizeof first, "; %s gave %d: %s", bad[k].what, status, gb_error_message());
    }
    gb_proof_conley_result r;
    const int good_runs = gb_proof_conley(&good, &r) == GB_OK;
    gb_check c = {"-", "-", "gb_proof_conley: definitions out of range",
                  "GB_EDOM naming the field and what is allowed; the unchanged definition runs", "exact"};
    gb_check_true(&c, refused == BAD && good_runs, "%d of %d refused, the good one %s%s", refused, BAD,
                  good_runs ? "runs" : "FAILED", first);
}

int verify_register_s7_conley(void)
{
    static const verify_test tests[] = {
        {"conley: linear maps' fixed points", test_linear,
         "the discrete Conley index of a sink, a saddle and a source meets its closed form"},
        {"conley: Henon at a = 6", test_horseshoe,
         "the index map of Henon's full horseshoe proves h_top >= ln 2 at every depth tried"},
        {"conley: the classical Henon map", test_classical,
         "grown from its periodic points, an index pair of the classical Henon map proves positive entropy"},
        {"conley: the classical map's orbits by name", test_orbits,
         "the seeds' orbits are left out and added by their period and least x; names matching no orbit are refused"},
        {"conley: the sofic graph by hand", test_sofic,
         "the entropy of the sofic shift forced by index maps written by hand meets closed forms"},
        {"conley: negative controls", test_controls, "pairs that break each condition prove nothing"},
        {"conley: definitions out of range", test_refused, NULL},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Proved on Arb's balls: the discrete Conley index and its sofic shift", tests);
}
