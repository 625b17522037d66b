/* Proved on Arb's balls: strips of a band (a rectangle in a chart) that return across it, and the renewal bound of
 * entropy (gb_proof_returns).
 *
 * Oracles, none sharing code with what they check:
 * - the renewal equation Σ x^-m_i = 1 in closed form: two strips of time 1 give x = 2 (the full 2-shift), times 2 and 3
 *   the plastic number (the real root of x³ = x + 1), times 1 and 2 the golden mean, a single strip nothing;
 * - Hénon's map iterated directly in long double in the plane's own coordinates (not the framed map the proof reads):
 *   the enclosures of every strip's edges hold the floats' images of 201 points of each edge, and points of each
 *   strip whose floats land inside the window have their floats inside the strip along;
 * - negative controls with teeth: the strip of the shortest return given a return time one shorter, a strip cut at
 *   its middle (its new edge's image lands in the window), and the band narrowed below where the images reach, each
 *   losing what it must, with the float point that shows why;
 * - the graph bound ln x, ρ(M(x)) = 1, in closed form: the golden-mean shift, the complete graph (the renewal bound),
 *   a vertex without an edge out and a downstream class of slower growth taken out, a graph without a cycle 0;
 * - the strips returning across part of the band, against the same floats and against the spectral radius in doubles
 *   (power iteration here); controls: a strip's reach widened to the window, a return time one shorter;
 * - the search that found the strips (scripts/henon_returns_search.py --partial), run again: it prints the table;
 * - the definitions' ranges: each bad window, strip, set, return time or count refused with GB_EDOM naming it. */
#include "gb_check.h"
#include "gb_error.h"
#include "gb_proof_returns.h"
#include "verify_sections.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void test_renewal_bound(void)
{
    const int two[2] = {1, 1}, plastic[2] = {2, 3}, golden[2] = {1, 2}, one[1] = {5};
    double l_two = NAN, l_plastic = NAN, l_golden = NAN, l_one = NAN; /* NaN where a call failed */
    const int status =
        gb_proof_returns_entropy_bound(two, 2, &l_two) || gb_proof_returns_entropy_bound(plastic, 2, &l_plastic) ||
        gb_proof_returns_entropy_bound(golden, 2, &l_golden) || gb_proof_returns_entropy_bound(one, 1, &l_one);
    /* the plastic number: the real root of x^3 = x + 1, by Cardano */
    const double rho = cbrt(0.5 + sqrt(23.0 / 108.0)) + cbrt(0.5 - sqrt(23.0 / 108.0)), phi = 0.5 * (1.0 + sqrt(5.0));
    const double e_two = log(2.0), e_plastic = log(rho), e_golden = log(phi);
    gb_check c = {
        "-", "-", "the renewal bound ln x, x the root above 1 of sum x^-m_i = 1, proved on Arb",
        "closed forms: m = (1, 1) ln 2, (2, 3) ln of the plastic number (x^3 = x + 1), (1, 2) ln of the golden mean, "
        "one strip 0",
        "a lower bound: never above the exact value (4 ulps for the closed forms' rounding) and within 1e-9 of it "
        "(the float root is lowered by a relative 2^-40, then 2^-39, ... until the sum is proved at 128 bits; the "
        "first try, 1e-12 below, decides these sums: 1e-9 leaves ten halvings)"};
    gb_check_true(&c,
                  !status && l_two <= e_two * (1 + 4 * DBL_EPSILON) && l_two >= e_two - 1e-9 &&
                      l_plastic <= e_plastic * (1 + 4 * DBL_EPSILON) && l_plastic >= e_plastic - 1e-9 &&
                      l_golden <= e_golden * (1 + 4 * DBL_EPSILON) && l_golden >= e_golden - 1e-9 && l_one == 0.0,
                  "(1, 1): %.17g against %.17g; (2, 3): %.17g against %.17g; (1, 2): %.17g against %.17g; (5): %g%s%s",
                  l_two, e_two, l_plastic, e_plastic, l_golden, e_golden, l_one, status ? ": " : "",
                  status ? gb_error_message() : "");
}

/* The classical frame in long double: the plane's point o + F v and back. */
static const long double frame_o[2] = {3157.0L / 5000, 947.0L / 5000};
static const long double frame_F[2][2] = {{-1.0L, -13.0L / 25}, {39.0L / 250, -1.0L}};

/* The point (u, s) of the band's chart (s about the centre line κ (u − u₀)²) through the frame into the plane, Hénon's
 * map (x, y) ↦ (1 − 1.4 x² + y, 0.3 x) iterated m times there, and back through the frame into the chart. */
static void iterate_through_plane(const gb_proof_returns_def *def, const double v[2], int m, long double out[2])
{
    const long double s = v[1] + def->curvature * ((long double)v[0] - def->vertex) * ((long double)v[0] - def->vertex);
    long double x = frame_o[0] + frame_F[0][0] * v[0] + frame_F[0][1] * s;
    long double y = frame_o[1] + frame_F[1][0] * v[0] + frame_F[1][1] * s;
    for (int n = 0; n < m; n++) {
        const long double x0 = x;
        x = 1.0L - 1.4L * x0 * x0 + y, y = 0.3L * x0;
    }
    const long double det = frame_F[0][0] * frame_F[1][1] - frame_F[0][1] * frame_F[1][0];
    const long double d0 = x - frame_o[0], d1 = y - frame_o[1];
    out[0] = (frame_F[1][1] * d0 - frame_F[0][1] * d1) / det, out[1] = (frame_F[0][0] * d1 - frame_F[1][0] * d0) / det;
    out[1] -= def->curvature * (out[0] - def->vertex) * (out[0] - def->vertex);
}

static int holds(gb_proof_interval a, double x) { return a.lo <= x && x <= a.hi; }

/* The floats' evidence for strips first ... sets - 1 as `r` proved them, each iterated in the plane: at 201 heights
 * along, each edge's image inside its enclosure and beyond the strip's reach (W when it has none); of 51 points
 * across at each height, those whose image lands in the reach, inside the band. */
typedef struct float_evidence {
    int held, tried, inside, landed;
} float_evidence;

static float_evidence floats_of(const gb_proof_returns_def *def, const gb_proof_returns_result *r, size_t first)
{
    float_evidence f = {0, 0, 0, 0};
    for (size_t i = first; i < def->sets; i++) {
        const int whole = def->reach[i].lo == 0.0 && def->reach[i].hi == 0.0;
        const gb_proof_interval T = whole ? def->window : def->reach[i];
        for (int k = 0; k <= 200; k++) {
            const double s = def->strip.lo + (def->strip.hi - def->strip.lo) * k / 200.0;
            for (int e = 0; e < 2; e++) {
                long double w[2];
                iterate_through_plane(def, (const double[2]){e ? def->set_u[i].hi : def->set_u[i].lo, s},
                                      def->returns[i], w);
                f.tried++, f.held += holds(r->edge[i][e], (double)w[0]) && (w[0] < T.lo || w[0] > T.hi);
            }
            for (int j = 0; j <= 50; j++) {
                const double u = def->set_u[i].lo + (def->set_u[i].hi - def->set_u[i].lo) * j / 50.0;
                long double w[2];
                iterate_through_plane(def, (const double[2]){u, s}, def->returns[i], w);
                if (w[0] >= T.lo && w[0] <= T.hi) f.landed++, f.inside += w[1] > def->strip.lo && w[1] < def->strip.hi;
            }
        }
    }
    return f;
}

static void test_henon_returns(void)
{
    gb_proof_field g;
    gb_proof_returns_def def;
    gb_proof_returns_result r;
    int status = gb_proof_returns_henon_classical(&g, &def);
    if (!status) status = gb_proof_returns(&def, &r);
    const float_evidence f = status ? (float_evidence){0, 0, 0, 0} : floats_of(&def, &r, 0);
    const int held = f.held, tried = f.tried, inside = f.inside, landed = f.landed;
    /* the proved bound against the same return times' renewal root in doubles (bisection here) */
    double lo = 0.0, hi = 1.0;
    for (int k = 0; k < 100; k++) {
        const double mid = 0.5 * (lo + hi);
        double sum = 0.0;
        for (size_t i = 0; i < def.sets; i++) sum += exp(-mid * def.returns[i]);
        if (sum >= 1.0)
            lo = mid;
        else
            hi = mid;
    }
    gb_check c = {
        "-", "-",
        "Henon's map at the classical a = 1.4, b = 0.3: the strips of a search returning across the band R = "
        "[-0.42, "
        "0.3] x [-0.018, 0.018] about s = 0.14 (u - 0.05)^2 (the horseshoe's frame)",
        "every return proved (edges beyond the window on opposite sides, the image in the window inside the band), so "
        "h_top >= ln x with sum x^-m_i = 1: above the horseshoe's ln 5 / 7 = 0.22992, below Friedland & Milnor's ln 2; "
        "each edge's enclosure holds the floats' images of 201 of its points, iterated in the plane, beyond W",
        "exact for the returns; the bound within 1e-9 below the root of the same return times in doubles (bisection "
        "here); the floats' iterates (error ~1e-13 after 13 steps) inside"};
    gb_check_true(&c,
                  !status && r.proved == def.sets && r.entropy <= lo * (1 + 4 * DBL_EPSILON) &&
                      r.entropy >= lo - 1e-9 && r.entropy > log(5.0) / 7.0 && r.entropy < log(2.0) && held == tried &&
                      tried == (int)def.sets * 201 * 2 && inside == landed && landed > 0 && r.failed_pieces == 0,
                  "%zu of %zu returns, h_top >= %.9f (doubles' root %.9f), %d of %d edge points inside their "
                  "enclosures and beyond W, %d of %d "
                  "points landing in the window inside the band, %ld pieces, %.3g s%s%s",
                  r.proved, def.sets, r.entropy, lo, held, tried, inside, landed, r.pieces, r.seconds,
                  status ? ": " : "", status ? gb_error_message() : "");
}

static void test_returns_controls(void)
{
    gb_proof_field g;
    gb_proof_returns_def def;
    int status = gb_proof_returns_henon_classical(&g, &def);
    /* 1. the strip with the shortest return (k: 3 iterates, the widest) asked to return one iterate sooner (it also
     * returns across in 4: that is a second return, not a control) */
    size_t k = 0;
    for (size_t i = 1; !status && i < def.sets; i++)
        if (def.returns[i] < def.returns[k]) k = i;
    gb_proof_returns_def later = def, cut = def, narrow = def;
    later.returns[k] = def.returns[k] - 1;
    /* 2. strip 0 (7 iterates) cut at its middle: its new high edge's image lands inside the window */
    cut.set_u[0].hi = 0.5 * (def.set_u[0].lo + def.set_u[0].hi);
    /* 3. the band narrowed to a third: the images of the strips in the window reach further along */
    narrow.strip = (gb_proof_interval){def.strip.lo / 3, def.strip.hi / 3};
    gb_proof_returns_result rl, rs, rn;
    if (!status) status = gb_proof_returns(&later, &rl);
    if (!status) status = gb_proof_returns(&cut, &rs);
    if (!status) status = gb_proof_returns(&narrow, &rn);
    /* why, in floats: an edge of the later strip lands in the window; so does the cut strip's new edge; a point of
     * strip k of the narrowed band lands in the window outside that band */
    long double w[2], w2[2];
    iterate_through_plane(&def, (const double[2]){def.set_u[k].lo, 0.0}, later.returns[k], w);
    iterate_through_plane(&def, (const double[2]){def.set_u[k].hi, 0.0}, later.returns[k], w2);
    const int sooner_lands = (w[0] > def.window.lo && w[0] < def.window.hi) ||
                             (w2[0] > def.window.lo && w2[0] < def.window.hi) ||
                             (w[0] - def.window.lo) * (w2[0] - def.window.lo) > 0;
    iterate_through_plane(&def, (const double[2]){cut.set_u[0].hi, 0.0}, def.returns[0], w);
    const int cut_lands = w[0] > def.window.lo && w[0] < def.window.hi;
    int narrow_leaves = 0;
    for (int j = 0; j <= 400 && !narrow_leaves; j++)
        for (int n = 0; n <= 20 && !narrow_leaves; n++) {
            const double u = def.set_u[k].lo + (def.set_u[k].hi - def.set_u[k].lo) * j / 400.0,
                         s = narrow.strip.lo + (narrow.strip.hi - narrow.strip.lo) * n / 20.0;
            iterate_through_plane(&def, (const double[2]){u, s}, def.returns[k], w);
            narrow_leaves = w[0] > def.window.lo && w[0] < def.window.hi && fabsl(w[1]) > narrow.strip.hi;
        }
    size_t others = 0;
    for (size_t i = 0; !status && i < def.sets; i++) others += i != k && rl.across[i];
    gb_check c = {
        "-", "-",
        "negative controls of the classical returns: the strip of the shortest return asked to return one iterate "
        "sooner, strip 0 cut at its middle, the band narrowed to a third",
        "each loses its return, the first failure named, and a float point shows why (an edge of the sooner strip "
        "lands in the window, or both on one side; the cut strip's new edge lands in the window; a point of the "
        "shortest strip lands in the window outside the narrowed band); the other 20 strips keep theirs when one "
        "strip's time is changed",
        "exact"};
    gb_check_true(
        &c,
        !status && !rl.across[k] && others == def.sets - 1 && !rs.across[0] && rs.side[0][1] == 0 && !rn.across[k] &&
            rl.failure[0] && rs.failure[0] && rn.failure[0] && sooner_lands && cut_lands && narrow_leaves,
        "sooner: strip %zu %s (%s); cut: strip 0 %s, high edge side %d; narrowed: strip %zu %s (%zu of %zu kept); "
        "floats: %d %d %d%s%s",
        k, rl.across[k] ? "PROVED" : "not proved", rl.failure, rs.across[0] ? "PROVED" : "not proved", rs.side[0][1], k,
        rn.across[k] ? "PROVED" : "not proved", rn.proved, def.sets, sooner_lands, cut_lands, narrow_leaves,
        status ? ": " : "", status ? gb_error_message() : "");
}

/* The table gb_proof_returns_henon_classical proves is the search's output: the script run again, its strips read
 * back. */
static void test_search_table(void)
{
    static char out[1 << 14];
    const int code = gb_check_command("/usr/bin/python3", "scripts/henon_returns_search.py --partial", out, sizeof out);
    gb_proof_field g;
    gb_proof_returns_def def, whole;
    const int status = gb_proof_returns_henon_partial(&g, &def) || gb_proof_returns_henon_classical(&g, &whole);
    size_t read = 0, same = 0;
    double printed = NAN, printed_partial = NAN;
    const char *at = strstr(out, "h_top >= "), *at2 = at ? strstr(at + 1, "h_top >= ") : NULL;
    if (at) printed = strtod(at + 9, NULL);
    if (at2) printed_partial = strtod(at2 + 9, NULL);
    for (const char *line = strchr(out, '{'); line && read < GB_PROOF_RETURNS_MAX; line = strchr(line + 1, '{')) {
        double lo, hi, t_lo = 0.0, t_hi = 0.0;
        int m;
        const int fields = sscanf(line, "{%lf, %lf, %d, %lf, %lf}", &lo, &hi, &m, &t_lo, &t_hi);
        if (fields != 3 && fields != 5) break;
        same += !status && read < def.sets && lo == def.set_u[read].lo && hi == def.set_u[read].hi &&
                m == def.returns[read] && t_lo == def.reach[read].lo && t_hi == def.reach[read].hi &&
                (fields == 3) == (read < whole.sets);
        read++;
    }
    gb_check c = {
        "-", "-", "the classical Henon returns' strips, their return times and reaches, as shipped",
        "scripts/henon_returns_search.py --partial run again (floats, numpy): the strips it prints, in order, and its "
        "two roots (the band's renewal bound, then the graph's)",
        "exact for the strips (both sides print 9 decimals); the roots to the 6 decimals printed"};
    double proved_root = NAN, partial_root = NAN;
    const int bound_status = status ? status
                                    : gb_proof_returns_entropy_bound(whole.returns, whole.sets, &proved_root) ||
                                          gb_proof_returns_table_bound(&def, &partial_root);
    gb_check_true(&c,
                  code == 0 && !status && !bound_status && read == def.sets && same == def.sets &&
                      fabs(printed - proved_root) < 5e-7 && fabs(printed_partial - partial_root) < 5e-7,
                  "exit %d, %zu strips printed, %zu equal to the table's %zu, roots %.6f and %.6f (the table gives "
                  "%.9f and %.9f)",
                  code, read, same, def.sets, printed, printed_partial, proved_root, partial_root);
}

static void test_graph_bound(void)
{
    const double phi = 0.5 * (1.0 + sqrt(5.0)), e_golden = log(phi);
    const double rho = cbrt(0.5 + sqrt(23.0 / 108.0)) + cbrt(0.5 - sqrt(23.0 / 108.0)), e_plastic = log(rho);
    /* the golden-mean shift: 0 -> 0, 0 -> 1, 1 -> 0, one iterate each */
    const int ones[3] = {1, 1, 1}, plastic[2] = {2, 3};
    const unsigned char golden[4] = {1, 1, 1, 0}, complete[4] = {1, 1, 1, 1};
    /* the same with a third vertex reached from 0 and without an edge out; then with a loop of its own (growth 1) */
    const unsigned char dead_end[9] = {1, 1, 1, 1, 0, 0, 0, 0, 0}, slow[9] = {1, 1, 1, 1, 0, 0, 0, 0, 1};
    const unsigned char acyclic[4] = {0, 1, 0, 0};
    double l_golden = NAN, l_plastic = NAN, l_dead = NAN, l_slow = NAN, l_acyclic = NAN; /* NaN where a call failed */
    const int status = gb_proof_returns_graph_bound(ones, golden, 2, &l_golden) ||
                       gb_proof_returns_graph_bound(plastic, complete, 2, &l_plastic) ||
                       gb_proof_returns_graph_bound(ones, dead_end, 3, &l_dead) ||
                       gb_proof_returns_graph_bound(ones, slow, 3, &l_slow) ||
                       gb_proof_returns_graph_bound(ones, acyclic, 2, &l_acyclic);
    const double exact[4] = {e_golden, e_plastic, e_golden, e_golden}, got[4] = {l_golden, l_plastic, l_dead, l_slow};
    int within = 0;
    for (int k = 0; k < 4; k++) within += got[k] <= exact[k] * (1 + 4 * DBL_EPSILON) && got[k] >= exact[k] - 1e-9;
    gb_check c = {"-", "-",
                  "the graph bound ln x0, M(x0) v >= v proved on Arb for a positive v, M(x)_ij = x^-m_i on the edges",
                  "closed forms: the golden-mean shift ln((1 + sqrt 5)/2); the complete graph of times 2 and 3, the "
                  "renewal bound's plastic number; the golden shift with a vertex without an edge out, and with a "
                  "loop of growth 1 downstream (both taken out); a graph without a cycle 0",
                  "a lower bound: never above the exact value (4 ulps for the closed forms' rounding) and within 1e-9 "
                  "of it (the float root lowered by 2^-40, 2^-39, ... until proved)"};
    gb_check_true(&c, !status && within == 4 && l_acyclic == 0.0,
                  "golden %.17g, complete %.17g (plastic %.17g), dead end %.17g, slow class %.17g against %.17g; "
                  "acyclic %g%s%s",
                  l_golden, l_plastic, e_plastic, l_dead, l_slow, e_golden, l_acyclic, status ? ": " : "",
                  status ? gb_error_message() : "");
}

/* The root of ρ(M(e^h)) = 1 in doubles: the spectral radius by the power iteration of M + I (max norm), bisection on h. */
static double float_graph_root(const gb_proof_returns_def *def)
{
    const size_t n = def->sets;
    double lo = 0.0, hi = 1.0;
    for (int b = 0; b < 60; b++) {
        const double h = 0.5 * (lo + hi);
        double v[GB_PROOF_RETURNS_MAX], w[GB_PROOF_RETURNS_MAX], growth = 0.0;
        for (size_t i = 0; i < n; i++) v[i] = 1.0;
        for (int k = 0; k < 3000; k++) {
            double top = 0.0;
            for (size_t i = 0; i < n; i++) {
                const gb_proof_interval T =
                    def->reach[i].lo == 0.0 && def->reach[i].hi == 0.0 ? def->window : def->reach[i];
                double sum = 0.0;
                for (size_t j = 0; j < n; j++)
                    if (def->set_u[j].lo >= T.lo && def->set_u[j].hi <= T.hi) sum += v[j];
                w[i] = exp(-h * def->returns[i]) * sum + v[i];
                top = fmax(top, w[i]);
            }
            growth = top; /* v's largest entry is 1 */
            for (size_t i = 0; i < n; i++) v[i] = w[i] / top;
        }
        if (growth - 1.0 >= 1.0)
            lo = h;
        else
            hi = h;
    }
    return lo;
}

static void test_henon_partial(void)
{
    gb_proof_field g;
    gb_proof_returns_def def;
    gb_proof_returns_result r;
    gb_proof_returns_def band;
    double band_bound = NAN;
    int status = gb_proof_returns_henon_partial(&g, &def) || gb_proof_returns_henon_classical(&g, &band) ||
                 gb_proof_returns_table_bound(&band, &band_bound);
    if (!status) status = gb_proof_returns(&def, &r);
    /* the partial strips follow the band's in the table: those have reaches, these none */
    size_t partial = 0, targets = 0, reached = 0;
    for (size_t i = 0; !status && i < def.sets; i++) {
        const int whole = def.reach[i].lo == 0.0 && def.reach[i].hi == 0.0;
        partial += i >= band.sets, reached += (i >= band.sets) == !whole, targets += r.targets[i];
    }
    const float_evidence f = status ? (float_evidence){0, 0, 0, 0} : floats_of(&def, &r, band.sets);
    const int held = f.held, tried = f.tried, inside = f.inside, landed = f.landed;
    const double root = status ? NAN : float_graph_root(&def);
    gb_check c = {
        "-", "-",
        "Henon's map at the classical a = 1.4, b = 0.3: the band's strips and more of a search returning across part "
        "of it (each across its reach T_i)",
        "every return proved (edges beyond the reach on opposite sides, the image in the reach inside the band), so "
        "h_top >= ln x0, M(x0) v >= v: above the band's own renewal bound (its table's, computed), below ln 2; the "
        "spectral radius's root "
        "in doubles (power iteration here); each partial strip's edges' floats, iterated in the plane, inside their "
        "enclosures and beyond the reach",
        "exact for the returns; the bound within 1e-8 below the float root (its own bisection to 1e-18, the power "
        "iteration's rate); the floats' iterates (error ~1e-13) inside"};
    gb_check_true(&c,
                  !status && r.proved == def.sets && partial > 0 && reached == def.sets && r.failed_pieces == 0 &&
                      r.entropy <= root + 1e-12 && r.entropy >= root - 1e-8 && r.entropy > band_bound &&
                      r.entropy < log(2.0) && held == tried && tried == (int)partial * 201 * 2 && inside == landed &&
                      landed > 0,
                  "%zu of %zu returns (%zu across part), %zu relations, h_top >= %.9f (doubles' root %.9f; the band's "
                  "alone %.9f), %d of %d "
                  "edge points inside their enclosures and beyond the reach, %d of %d points landing in the reach "
                  "inside the band, %ld pieces, %.3g s%s%s",
                  r.proved, def.sets, partial, targets, r.entropy, root, band_bound, held, tried, inside, landed,
                  r.pieces, r.seconds, status ? ": " : "", status ? gb_error_message() : "");
    /* controls: the 1-iterate strip asked to return across the whole window; a 13-iterate strip one iterate sooner */
    gb_proof_returns_def wide = def, sooner = def;
    size_t one = def.sets, thirteen = def.sets;
    for (size_t i = band.sets; i < def.sets; i++) {
        if (def.returns[i] == 1 && one == def.sets) one = i;
        if (def.returns[i] == 13 && thirteen == def.sets) thirteen = i;
    }
    gb_proof_returns_result rw, rs;
    int controls = one < def.sets && thirteen < def.sets;
    if (controls) {
        wide.reach[one] = (gb_proof_interval){0.0, 0.0}, sooner.returns[thirteen]--;
        controls = !gb_proof_returns(&wide, &rw) && !gb_proof_returns(&sooner, &rs);
    }
    long double w[2] = {0, 0};
    if (controls) iterate_through_plane(&def, (const double[2]){def.set_u[one].lo, 0.0}, 1, w);
    gb_check cc = {"-", "-",
                   "negative controls of the partial returns: the 1-iterate strip asked to cross the whole window, a "
                   "13-iterate strip one iterate sooner",
                   "each loses its return, the first failure named; the 1-iterate strip's low edge lands inside the "
                   "window in floats",
                   "exact"};
    gb_check_true(&cc,
                  controls && !rw.across[one] && rw.proved == def.sets - 1 && !rs.across[thirteen] && rw.failure[0] &&
                      rs.failure[0] && w[0] > def.window.lo && w[0] < def.window.hi,
                  "wide: strip %zu %s (%s); sooner: strip %zu %s (%s); the edge's float image at u = %.6Lf", one,
                  controls && rw.across[one] ? "PROVED" : "not proved", controls ? rw.failure : "", thirteen,
                  controls && rs.across[thirteen] ? "PROVED" : "not proved", controls ? rs.failure : "", w[0]);
}

static void test_returns_refused(void)
{
    gb_proof_field g;
    gb_proof_returns_def good;
    const int built = gb_proof_returns_henon_classical(&g, &good) == GB_OK;
    const gb_proof_field three_d = gb_proof_flow_rossler(1, 5, 1, 5, 57, 10);
    enum { BAD = 11 };
    struct {
        const char *what, *must;
        gb_proof_returns_def def;
    } bad[BAD];
    for (int k = 0; k < BAD; k++) bad[k].def = good;
    bad[0].what = "overlapping strips", bad[0].must = "overlap", bad[0].def.set_u[1].lo = good.set_u[0].hi - 0.001;
    bad[1].what = "a strip outside the window", bad[1].must = "inside the window",
    bad[1].def.set_u[good.sets - 1].hi = good.window.hi + 0.05;
    bad[2].what = "return time 0", bad[2].must = "return time", bad[2].def.returns[3] = 0;
    bad[3].what = "return time 33", bad[3].must = "return time", bad[3].def.returns[3] = 33;
    bad[4].what = "a window with lo > hi", bad[4].must = "window", bad[4].def.window = (gb_proof_interval){0.2, -0.38};
    bad[5].what = "a band of zero width", bad[5].must = "strip", bad[5].def.strip = (gb_proof_interval){0.01, 0.01};
    bad[6].what = "65 strips", bad[6].must = "sets", bad[6].def.sets = 65;
    bad[7].what = "depth 31", bad[7].must = "depth", bad[7].def.depth = 31;
    bad[9].what = "a centre line of curvature 1000", bad[9].must = "curvature", bad[9].def.curvature = 1000.0;
    bad[8].what = "a flow in R^3 for a map of the plane", bad[8].must = "dimension", bad[8].def.map = &three_d;
    bad[10].what = "a reach beyond the window", bad[10].must = "reach",
    bad[10].def.reach[2] = (gb_proof_interval){good.window.lo - 0.1, -0.2};
    int refused = 0;
    char first[300] = "";
    for (int k = 0; k < BAD; k++) {
        gb_proof_returns_result r;
        const int status = gb_proof_returns(&bad[k].def, &r);
        const int ok =
            status == GB_EDOM && strstr(gb_error_message(), bad[k].must) && strstr(gb_error_message(), "allowed");
        refused += ok;
        if (!ok && !first[0])
            snprintf(first, sizeof first, "; %s gave %d: %s", bad[k].what, status, gb_error_message());
    }
    /* the default leaves R and the strips to the caller: a window of zero width is refused */
    gb_proof_returns_def unset = gb_proof_returns_def_default();
    unset.map = &g;
    gb_proof_returns_result ru;
    const int default_refused = unset.sets == 1 && unset.returns[0] == 1 && gb_proof_returns(&unset, &ru) == GB_EDOM &&
                                strstr(gb_error_message(), "window");
    double h;
    const int times[2] = {1, 40};
    const int bound_refused =
        gb_proof_returns_entropy_bound(times, 2, &h) == GB_EDOM && strstr(gb_error_message(), "allowed");
    gb_check c = {"-", "-", "returns across a band: definitions out of range",
                  "GB_EDOM naming the field and its allowed range", "exact"};
    gb_check_true(&c, built && refused == BAD && bound_refused && default_refused,
                  "%d of %d definitions refused, a return time of 40 for the bound %s, the default's empty window %s%s",
                  refused, BAD, bound_refused ? "refused" : "accepted", default_refused ? "refused" : "accepted",
                  first);
}

int verify_register_s7_returns(void)
{
    static const verify_test tests[] = {
        {"returns: the renewal bound against closed forms", test_renewal_bound,
         "the entropy of strips with return times, proved on Arb, meets the roots of known renewal equations"},
        {"returns: the classical Henon map's strips", test_henon_returns,
         "the strips of a band return across it under the classical Henon map, against floats iterated in the "
         "plane"},
        {"returns: negative controls", test_returns_controls,
         "a wrong return time, a strip cut at its middle and a band too narrow each lose their return"},
        {"returns: the graph bound against closed forms", test_graph_bound,
         "the entropy of a graph of strips with return times, proved on Arb, meets closed forms"},
        {"returns: the classical Henon map's strips across part of the band", test_henon_partial,
         "more strips return across part of the band, and with the band's own raise the entropy bound above the "
         "band's"},
        {"returns: the shipped strips are the search's", test_search_table,
         "the strips the proof is given are what scripts/henon_returns_search.py prints"},
        {"returns: definitions out of range", test_returns_refused, NULL},
        {NULL, NULL, NULL},
    };
    return verify_register_suite(
        "Proved on Arb's balls: strips returning across a band or part of it (the renewal and graph bounds)", tests);
}
