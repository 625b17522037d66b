#include "gb_proof_returns.h"

#include "gb_error.h"
#include "gb_proof_cover.h"
#include "gb_proof_flow_internal.h"
#include "gb_proof_internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <arb.h>

gb_proof_returns_def gb_proof_returns_def_default(void)
{
    gb_proof_returns_def d;
    memset(&d, 0, sizeof d);
    d.precision = GB_PROOF_PRECISION_DEFAULT;
    d.sets = 1;
    d.returns[0] = 1;
    d.pieces = 16;
    d.depth = 16;
    return d;
}

static int proper(gb_proof_interval x) { return isfinite(x.lo) && isfinite(x.hi) && x.lo < x.hi; }

static int check_def(const gb_proof_returns_def *def)
{
    if (!def) return gb_error_set(GB_EINVAL, "returns across a band need a definition");
    if (!def->map) return gb_error_set(GB_EINVAL, "returns across a band need a map");
    if (def->map->dimension != 2)
        return gb_error_set(GB_EDOM, "field dimension = %d is out of range (allowed: 2 for a map of the plane)",
                            def->map->dimension);
    int status = gb_proof_check_precision(def->precision);
    if (status) return status;
    if (!proper(def->window))
        return gb_error_set(GB_EDOM, "window = [%g, %g] is out of range (allowed: a finite interval with lo < hi)",
                            def->window.lo, def->window.hi);
    if (!isfinite(def->curvature) || fabs(def->curvature) > 100.0 || !isfinite(def->vertex) || fabs(def->vertex) > 1e6)
        return gb_error_set(GB_EDOM,
                            "the band's centre line %g (u - %g)^2 is out of range (allowed: |curvature| <= 100, "
                            "|vertex| <= 1e6, both finite)",
                            def->curvature, def->vertex);
    if (!proper(def->strip))
        return gb_error_set(GB_EDOM, "strip = [%g, %g] is out of range (allowed: a finite interval with lo < hi)",
                            def->strip.lo, def->strip.hi);
    if (def->sets < 1 || def->sets > GB_PROOF_RETURNS_MAX)
        return gb_error_set(GB_EDOM, "sets = %zu is out of range (allowed: 1 to %d)", def->sets, GB_PROOF_RETURNS_MAX);
    if (def->pieces < 1 || def->pieces > 100000)
        return gb_error_set(GB_EDOM, "pieces = %d is out of range (allowed: 1 to 100000)", def->pieces);
    if (def->depth < 0 || def->depth > 30)
        return gb_error_set(GB_EDOM, "depth = %d is out of range (allowed: 0 to 30)", def->depth);
    for (size_t i = 0; i < def->sets; i++) {
        const gb_proof_interval U = def->set_u[i];
        if (!proper(U) || U.lo < def->window.lo || U.hi > def->window.hi)
            return gb_error_set(GB_EDOM,
                                "set %zu = [%g, %g] is out of range (allowed: lo < hi inside the window [%g, %g])", i,
                                U.lo, U.hi, def->window.lo, def->window.hi);
        if (def->returns[i] < 1 || def->returns[i] > GB_PROOF_RETURN_TIME_MAX)
            return gb_error_set(GB_EDOM, "set %zu's return time = %d is out of range (allowed: 1 to %d)", i,
                                def->returns[i], GB_PROOF_RETURN_TIME_MAX);
        for (size_t j = 0; j < i; j++)
            if (U.lo <= def->set_u[j].hi && def->set_u[j].lo <= U.hi)
                return gb_error_set(GB_EDOM, "sets %zu and %zu overlap (allowed: disjoint strips)", j, i);
    }
    return GB_OK;
}

/* The band's centre line κ (u − u₀)² over the ball u, into out. */
static void centre_line(const gb_proof_returns_def *def, const arb_t u, arb_t out, slong prec)
{
    arb_set_d(out, def->vertex);
    arb_sub(out, u, out, prec);
    arb_sqr(out, out, prec);
    gb_proof_mul_d(out, out, def->curvature, prec);
}

/* f^m of the piece u × s of the band's chart (u across, s along the band: the frame's s less the centre line):
 * enclosed in the frame as a box, mapped, and read back in the chart; 0 when the enclosure is not finite. */
static int image(const gb_proof_returns_def *def, const field_balls *F, gb_proof_interval u, gb_proof_interval s, int m,
                 gb_proof_interval *iu, gb_proof_interval *is)
{
    arb_struct x[2];
    arb_t line;
    arb_init(&x[0]), arb_init(&x[1]), arb_init(line);
    gb_proof_ball_of(&x[0], u, F->prec), gb_proof_ball_of(&x[1], s, F->prec);
    centre_line(def, &x[0], line, F->prec);
    arb_add(&x[1], &x[1], line, F->prec);
    const int finite = gb_proof_affine_image(F, x, m);
    centre_line(def, &x[0], line, F->prec);
    arb_sub(&x[1], &x[1], line, F->prec);
    *iu = gb_proof_interval_of(&x[0]), *is = gb_proof_interval_of(&x[1]);
    arb_clear(&x[0]), arb_clear(&x[1]), arb_clear(line);
    return finite && arb_is_finite(&x[1]);
}

typedef struct walk {
    const gb_proof_returns_def *def;
    const field_balls *F;
    int m;
    size_t set;
    gb_proof_returns_result *out;
} walk;

static void note_failure(walk *w, const char *what, gb_proof_interval u, gb_proof_interval s, gb_proof_interval iu,
                         gb_proof_interval is)
{
    if (w->out->failure[0]) return;
    snprintf(
        w->out->failure, sizeof w->out->failure,
        "set %zu (%d iterates), %s u in [%.9g, %.9g], s in [%.6g, %.6g]: image across [%.9g, %.9g], along [%.6g, %.6g]",
        w->set, w->m, what, u.lo, u.hi, s.lo, s.hi, iu.lo, iu.hi, is.lo, is.hi);
}

/* Where the edge {at} × s lands across: -1 wholly below W, 1 wholly above, 0 not proved (halved along to depth); the
 * hull of its images joins *hull. */
static int edge_side(walk *w, double at, gb_proof_interval s, int level, gb_proof_interval *hull, int *any)
{
    const gb_proof_interval W = w->def->window;
    gb_proof_interval iu, is;
    const int finite = image(w->def, w->F, (gb_proof_interval){at, at}, s, w->m, &iu, &is);
    w->out->pieces++;
    int side = !finite ? 0 : iu.hi < W.lo ? -1 : iu.lo > W.hi ? 1 : 0;
    if (!side && finite && level < w->def->depth && gb_proof_halvable(s)) {
        const int low = edge_side(w, at, gb_proof_half(s, 0), level + 1, hull, any);
        const int high = low ? edge_side(w, at, gb_proof_half(s, 1), level + 1, hull, any) : 0;
        if (low && high && low != high) {
            w->out->failed_pieces++;
            note_failure(w, "an edge lands on both sides of the window:", (gb_proof_interval){at, at}, s, *hull, s);
        }
        return low == high ? low : 0;
    }
    if (finite) {
        if (!*any)
            *hull = iu, *any = 1;
        else
            hull->lo = fmin(hull->lo, iu.lo), hull->hi = fmax(hull->hi, iu.hi);
    }
    if (!side) {
        w->out->failed_pieces++;
        note_failure(w, "an edge does not land beyond the window:", (gb_proof_interval){at, at}, s, iu, is);
    }
    return side;
}

/* 1 when every point of u × s whose image lies in W across has its image in int S along: an image wholly beyond W, or
 * wholly inside S, proves its piece; otherwise the piece is halved across and along, to depth. */
static int across_piece(walk *w, gb_proof_interval u, gb_proof_interval s, int level)
{
    const gb_proof_interval W = w->def->window, S = w->def->strip;
    gb_proof_interval iu, is;
    const int finite = image(w->def, w->F, u, s, w->m, &iu, &is);
    w->out->pieces++;
    if (finite && (iu.hi < W.lo || iu.lo > W.hi || (is.lo > S.lo && is.hi < S.hi))) return 1;
    if (finite && level < w->def->depth && gb_proof_halvable(u)) {
        if (!gb_proof_halvable(s))
            return across_piece(w, gb_proof_half(u, 0), s, level + 1) &&
                   across_piece(w, gb_proof_half(u, 1), s, level + 1);
        for (int k = 0; k < 4; k++)
            if (!across_piece(w, gb_proof_half(u, k & 1), gb_proof_half(s, k >> 1), level + 1)) return 0;
        return 1;
    }
    w->out->failed_pieces++;
    note_failure(w, finite ? "a piece's image in the window leaves the strip:" : "a piece's image is not finite:", u, s,
                 iu, is);
    return 0;
}

/* The root above 1 of Σ x^-m_i = 1 as ln x, by bisection on doubles (the sum falls as x grows). */
static double renewal_root(const int *returns, size_t n)
{
    double lo = 0.0, hi = log((double)n) + 1.0;
    for (int k = 0; k < 200; k++) {
        const double mid = 0.5 * (lo + hi);
        double sum = 0.0;
        for (size_t i = 0; i < n; i++) sum += exp(-mid * returns[i]);
        if (sum >= 1.0)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* 1 when Σ exp(-h m_i) ≥ 1 is proved on Arb's balls (h exact). */
static int renewal_holds(const int *returns, size_t n, double h)
{
    arb_t sum, term;
    arb_init(sum), arb_init(term);
    const slong prec = 128;
    for (size_t i = 0; i < n; i++) {
        arb_set_d(term, h);
        arb_mul_si(term, term, -returns[i], prec);
        arb_exp(term, term, prec);
        arb_add(sum, sum, term, prec);
    }
    arb_sub_ui(sum, sum, 1, prec);
    const int holds = arb_is_nonnegative(sum);
    arb_clear(sum), arb_clear(term);
    return holds;
}

int gb_proof_returns_entropy_bound(const int *returns, size_t n, double *log_x)
{
    if (!returns || !log_x) return gb_error_set(GB_EINVAL, "the renewal bound needs return times and an output");
    if (n < 1 || n > GB_PROOF_RETURNS_MAX)
        return gb_error_set(GB_EDOM, "return times: %zu is out of range (allowed: 1 to %d)", n, GB_PROOF_RETURNS_MAX);
    for (size_t i = 0; i < n; i++)
        if (returns[i] < 1 || returns[i] > GB_PROOF_RETURN_TIME_MAX)
            return gb_error_set(GB_EDOM, "return time %zu = %d is out of range (allowed: 1 to %d)", i, returns[i],
                                GB_PROOF_RETURN_TIME_MAX);
    *log_x = 0.0;
    const double root = renewal_root(returns, n);
    for (int k = 40; k >= 1 && root > 0.0; k--) { /* the float root, lowered until the sum is proved at least 1 there */
        const double h = root * (1.0 - ldexp(1.0, -k));
        if (renewal_holds(returns, n, h)) {
            *log_x = h;
            break;
        }
    }
    return GB_OK;
}

int gb_proof_returns(const gb_proof_returns_def *def, gb_proof_returns_result *out)
{
    int status = check_def(def);
    if (status) return status;
    if (!out) return gb_error_set(GB_EINVAL, "returns across a band need a result");
    memset(out, 0, sizeof *out);
    const double start = gb_proof_cpu_seconds();
    field_balls F;
    gb_proof_flow_field_init(&F, def->map, GB_PROOF_ORDER_MIN, def->precision);
    int times[GB_PROOF_RETURNS_MAX];
    for (size_t i = 0; i < def->sets; i++) {
        walk w = {def, &F, def->returns[i], i, out};
        const gb_proof_interval U = def->set_u[i];
        for (int e = 0; e < 2; e++) {
            int any = 0;
            out->edge[i][e] = (gb_proof_interval){NAN, NAN};
            out->side[i][e] = edge_side(&w, e ? U.hi : U.lo, def->strip, 0, &out->edge[i][e], &any);
        }
        int across = out->side[i][0] && out->side[i][1] == -out->side[i][0];
        for (int k = 0; k < def->pieces && across; k++) {
            const gb_proof_interval piece = {k ? U.lo + (U.hi - U.lo) * k / def->pieces : U.lo,
                                             k + 1 < def->pieces ? U.lo + (U.hi - U.lo) * (k + 1) / def->pieces : U.hi};
            across = across_piece(&w, piece, def->strip, 0);
        }
        out->across[i] = across;
        if (across) times[out->proved++] = def->returns[i];
    }
    gb_proof_flow_field_clear(&F);
    if (out->proved) status = gb_proof_returns_entropy_bound(times, out->proved, &out->entropy);
    out->seconds = gb_proof_cpu_seconds() - start;
    return status;
}

int gb_proof_returns_henon_classical(gb_proof_field *field, gb_proof_returns_def *def)
{
    static const gb_proof_rational origin[2] = {{3157, 5000}, {947, 5000}};
    static const gb_proof_rational frame[2][2] = {{{-1, 1}, {-13, 25}}, {{39, 250}, {-1, 1}}};
    /* scripts/henon_returns_search.py's strips: U_i and m_i */
    static const struct {
        double lo, hi;
        int m;
    } strips[] = {{-0.415654800, -0.393925200, 7},  {-0.383728200, -0.355896600, 7},  {-0.355477200, -0.349800000, 12},
                  {-0.338796600, -0.333385800, 12}, {-0.246510600, -0.211851600, 7},  {-0.206250000, -0.167074800, 6},
                  {-0.157981200, -0.152912400, 14}, {-0.152876400, -0.147962400, 14}, {-0.126661200, -0.117261600, 9},
                  {-0.115580400, -0.104251200, 9},  {-0.098257200, -0.088180800, 10}, {-0.086218800, -0.076167600, 10},
                  {-0.069660600, -0.059625600, 9},  {-0.057888600, -0.046489200, 8},  {-0.040203600, 0.071218200, 3},
                  {0.092215200, 0.116234400, 7},    {0.119060400, 0.141036600, 8},    {0.153256800, 0.179509800, 9},
                  {0.180435000, 0.202233000, 9},    {0.213769200, 0.241377600, 8},    {0.242117400, 0.266934000, 8}};
    if (!field || !def) return gb_error_set(GB_EINVAL, "the classical Henon returns need a field and a definition");
    const int status = gb_proof_cover_henon_framed(7, 5, 3, 10, origin, frame, field);
    if (status) return status;
    *def = gb_proof_returns_def_default();
    def->map = field;
    def->window = (gb_proof_interval){-0.42, 0.3};
    def->strip = (gb_proof_interval){-0.018, 0.018};
    def->curvature = 0.14, def->vertex = 0.05;
    def->sets = sizeof strips / sizeof strips[0];
    for (size_t i = 0; i < def->sets; i++)
        def->set_u[i] = (gb_proof_interval){strips[i].lo, strips[i].hi}, def->returns[i] = strips[i].m;
    return GB_OK;
}
