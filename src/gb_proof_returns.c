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

/* T_i: the strip's reach, W where it is left {0, 0}. */
static gb_proof_interval reach_of(const gb_proof_returns_def *def, size_t i)
{
    const gb_proof_interval T = def->reach[i];
    return T.lo == 0.0 && T.hi == 0.0 ? def->window : T;
}

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
        const gb_proof_interval T = reach_of(def, i);
        if (!proper(T) || T.lo < def->window.lo || T.hi > def->window.hi)
            return gb_error_set(GB_EDOM,
                                "set %zu's reach = [%g, %g] is out of range (allowed: lo < hi inside the window [%g, "
                                "%g], or 0, 0 for the window)",
                                i, T.lo, T.hi, def->window.lo, def->window.hi);
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
    gb_proof_interval reach; /* T: W, or the part of it the strip returns across */
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

/* Where the edge {at} × s lands across: -1 wholly below T, 1 wholly above, 0 not proved (halved along to depth); the
 * hull of its images joins *hull. */
static int edge_side(walk *w, double at, gb_proof_interval s, int level, gb_proof_interval *hull, int *any)
{
    const gb_proof_interval W = w->reach;
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

/* 1 when every point of u × s whose image lies in T across has its image in int S along: an image wholly beyond T, or
 * wholly inside S, proves its piece; otherwise the piece is halved across and along, to depth. */
static int across_piece(walk *w, gb_proof_interval u, gb_proof_interval s, int level)
{
    const gb_proof_interval W = w->reach, S = w->def->strip;
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

/* GB_EDOM unless there are 1 ... 64 return times, each 1 ... 32. */
static int check_times(const int *returns, size_t n)
{
    if (n < 1 || n > GB_PROOF_RETURNS_MAX)
        return gb_error_set(GB_EDOM, "return times: %zu is out of range (allowed: 1 to %d)", n, GB_PROOF_RETURNS_MAX);
    for (size_t i = 0; i < n; i++)
        if (returns[i] < 1 || returns[i] > GB_PROOF_RETURN_TIME_MAX)
            return gb_error_set(GB_EDOM, "return time %zu = %d is out of range (allowed: 1 to %d)", i, returns[i],
                                GB_PROOF_RETURN_TIME_MAX);
    return GB_OK;
}

/* The float root ln x lowered by a relative 2^-40, 2^-39, ... until `proved` holds there on Arb's balls: that value,
 * or 0 when none is proved (or the root is not above 0). */
static double lowered_until_proved(double root, int (*proved)(const void *context, double h), const void *context)
{
    for (int k = 40; k >= 1 && root > 0.0; k--) {
        const double h = root * (1.0 - ldexp(1.0, -k));
        if (proved(context, h)) return h;
    }
    return 0.0;
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

typedef struct times {
    const int *returns;
    size_t n;
} times;

/* 1 when Σ exp(-h m_i) ≥ 1 is proved on Arb's balls (h exact). */
static int renewal_holds(const void *context, double h)
{
    const int *returns = ((const times *)context)->returns;
    const size_t n = ((const times *)context)->n;
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
    const int status = check_times(returns, n);
    if (status) return status;
    const times t = {returns, n};
    *log_x = lowered_until_proved(renewal_root(returns, n), renewal_holds, &t);
    return GB_OK;
}

/* M v on the vertices `alive` marks (row i: factor_i Σ_j edge_ij v_j, factor_i = e^(-h m_i)), in doubles. */
static void graph_apply(const double *factor, const unsigned char *edge, size_t n, const unsigned char *alive,
                        const double *v, double *out)
{
    for (size_t i = 0; i < n; i++) {
        double sum = 0.0;
        for (size_t j = 0; alive[i] && j < n; j++)
            if (alive[j] && edge[i * n + j]) sum += v[j];
        out[i] = alive[i] ? factor[i] * sum : 0.0;
    }
}

/* The positive vector v (largest entry 1) of the power iteration of M(e^h) + I on the alive vertices, the least ratio
 * (M v)_i / v_i over them (a lower bound of ρ by Collatz and Wielandt when v > 0) and, in *growth, the iteration's
 * estimate of ρ. */
static double graph_ratio(const int *returns, const unsigned char *edge, size_t n, const unsigned char *alive, double h,
                          double *v, size_t *worst, double *growth)
{
    double w[GB_PROOF_RETURNS_MAX], factor[GB_PROOF_RETURNS_MAX];
    for (size_t i = 0; i < n; i++) v[i] = alive[i] ? 1.0 : 0.0, factor[i] = exp(-h * returns[i]);
    for (int k = 0; k < 2000; k++) {
        graph_apply(factor, edge, n, alive, v, w);
        double top = 0.0;
        for (size_t i = 0; i < n; i++) w[i] += v[i], top = fmax(top, w[i]);
        for (size_t i = 0; i < n; i++) v[i] = top > 0.0 ? w[i] / top : 0.0;
        *growth = top - 1.0; /* v's largest entry was 1 */
    }
    graph_apply(factor, edge, n, alive, v, w);
    double least = INFINITY;
    for (size_t i = 0; i < n; i++)
        if (alive[i] && w[i] / v[i] < least) least = w[i] / v[i], *worst = i;
    return least;
}

typedef struct graph {
    const int *returns;
    const unsigned char *edge, *alive;
    const double *v;
    size_t n;
} graph;

/* 1 when M(e^h) v ≥ v is proved on Arb's balls on the alive vertices (h and v exact doubles). */
static int graph_holds(const void *context, double h)
{
    const graph *G = context;
    const int *returns = G->returns;
    const unsigned char *edge = G->edge, *alive = G->alive;
    const double *v = G->v;
    const size_t n = G->n;
    arb_t sum, factor, value;
    arb_init(sum), arb_init(factor), arb_init(value);
    const slong prec = 128;
    int holds = 1;
    for (size_t i = 0; i < n && holds; i++) {
        if (!alive[i]) continue;
        arb_zero(sum);
        for (size_t j = 0; j < n; j++)
            if (alive[j] && edge[i * n + j]) arb_set_d(value, v[j]), arb_add(sum, sum, value, prec);
        arb_set_d(factor, h);
        arb_mul_si(factor, factor, -returns[i], prec);
        arb_exp(factor, factor, prec);
        arb_mul(sum, sum, factor, prec);
        arb_set_d(value, v[i]);
        arb_sub(sum, sum, value, prec);
        holds = arb_is_nonnegative(sum);
    }
    arb_clear(sum), arb_clear(factor), arb_clear(value);
    return holds;
}

int gb_proof_returns_graph_bound(const int *returns, const unsigned char *edge, size_t n, double *log_x)
{
    if (!returns || !edge || !log_x)
        return gb_error_set(GB_EINVAL, "the graph bound needs return times, edges and an output");
    const int status = check_times(returns, n);
    if (status) return status;
    *log_x = 0.0;
    unsigned char alive[GB_PROOF_RETURNS_MAX];
    double v[GB_PROOF_RETURNS_MAX];
    memset(alive, 1, n);
    /* take out the vertices without an edge to one left, then, at the float root, those whose ratio stays below 1 */
    for (int pass = 0; pass < 2 * GB_PROOF_RETURNS_MAX; pass++) {
        int changed = 0;
        for (size_t i = 0; i < n; i++) {
            size_t out_edges = 0;
            for (size_t j = 0; alive[i] && j < n; j++) out_edges += alive[j] && edge[i * n + j];
            if (alive[i] && !out_edges) alive[i] = 0, changed = 1;
        }
        size_t left = 0, worst = 0;
        for (size_t i = 0; i < n; i++) left += alive[i];
        if (!left) return GB_OK;
        if (changed) continue;
        double lo = 0.0, hi = log((double)n) + 1.0, growth = 0.0;
        for (int k = 0; k < 60; k++) {
            const double mid = 0.5 * (lo + hi);
            graph_ratio(returns, edge, n, alive, mid, v, &worst, &growth);
            if (growth >= 1.0)
                lo = mid;
            else
                hi = mid;
        }
        if (lo <= 0.0) return GB_OK;
        const double least = graph_ratio(returns, edge, n, alive, lo, v, &worst, &growth);
        if (least < 1.0 - 1e-9) { /* a vertex that cannot keep up (a class of slower growth): without it */
            alive[worst] = 0;
            continue;
        }
        const graph G = {returns, edge, alive, v, n};
        *log_x = lowered_until_proved(lo, graph_holds, &G);
        return GB_OK;
    }
    return GB_OK;
}

/* The bound of the strips `counted` marks: the graph's, i → j when U_j lies in T_i (targets[i] gets the count of
 * each strip's), or the renewal bound's when every T_i is W (the same graph, whose matrix has rank one). */
static int strips_bound(const gb_proof_returns_def *def, const int *counted, size_t *targets, double *log_x)
{
    unsigned char edge[GB_PROOF_RETURNS_MAX * GB_PROOF_RETURNS_MAX];
    size_t index[GB_PROOF_RETURNS_MAX], n = 0;
    int times[GB_PROOF_RETURNS_MAX], partial = 0;
    for (size_t i = 0; i < def->sets; i++)
        if (counted[i]) times[n] = def->returns[i], index[n++] = i;
    *log_x = 0.0;
    if (!n) return GB_OK;
    for (size_t a = 0; a < n; a++) {
        const gb_proof_interval T = reach_of(def, index[a]);
        partial |= T.lo != def->window.lo || T.hi != def->window.hi;
        for (size_t b = 0; b < n; b++) {
            const gb_proof_interval U = def->set_u[index[b]];
            edge[a * n + b] = U.lo >= T.lo && U.hi <= T.hi;
            if (targets) targets[index[a]] += edge[a * n + b];
        }
    }
    return partial ? gb_proof_returns_graph_bound(times, edge, n, log_x)
                   : gb_proof_returns_entropy_bound(times, n, log_x);
}

int gb_proof_returns_table_bound(const gb_proof_returns_def *def, double *log_x)
{
    int status = check_def(def);
    if (status) return status;
    if (!log_x) return gb_error_set(GB_EINVAL, "the table's bound needs an output");
    int all[GB_PROOF_RETURNS_MAX];
    for (size_t i = 0; i < def->sets; i++) all[i] = 1;
    return strips_bound(def, all, NULL, log_x);
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
    for (size_t i = 0; i < def->sets; i++) {
        walk w = {def, &F, def->returns[i], i, reach_of(def, i), out};
        const gb_proof_interval U = def->set_u[i];
        for (int e = 0; e < 2; e++) {
            int any = 0;
            out->edge[i][e] = (gb_proof_interval){NAN, NAN};
            out->side[i][e] = edge_side(&w, e ? U.hi : U.lo, def->strip, 0, &out->edge[i][e], &any);
        }
        int across = out->side[i][0] && out->side[i][1] == -out->side[i][0];
        if (out->side[i][0] && out->side[i][1] == out->side[i][0])
            note_failure(
                &w, out->side[i][0] < 0 ? "both edges land below the reach:" : "both edges land above the reach:", U,
                def->strip,
                (gb_proof_interval){fmin(out->edge[i][0].lo, out->edge[i][1].lo),
                                    fmax(out->edge[i][0].hi, out->edge[i][1].hi)},
                def->strip);
        for (int k = 0; k < def->pieces && across; k++) {
            const gb_proof_interval piece = {k ? U.lo + (U.hi - U.lo) * k / def->pieces : U.lo,
                                             k + 1 < def->pieces ? U.lo + (U.hi - U.lo) * (k + 1) / def->pieces : U.hi};
            across = across_piece(&w, piece, def->strip, 0);
        }
        out->across[i] = across;
        out->proved += across != 0;
    }
    gb_proof_flow_field_clear(&F);
    if (out->proved) status = strips_bound(def, out->across, out->targets, &out->entropy);
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

int gb_proof_returns_henon_partial(gb_proof_field *field, gb_proof_returns_def *def)
{
    /* scripts/henon_returns_search.py --partial: U_i, m_i and the reach T_i of the strips returning across part of W */
    static const struct {
        double lo, hi;
        int m;
        double reach_lo, reach_hi;
    } strips[] = {{0.073716600, 0.091999200, 1, -0.162528000, -0.137311800},
                  {-0.046266000, -0.041672400, 2, -0.162528000, -0.152894400},
                  {-0.330352800, -0.313053000, 8, -0.420000000, -0.043346400},
                  {-0.293456400, -0.265914600, 8, -0.420000000, -0.043346400},
                  {-0.146245200, -0.139844400, 10, -0.388826700, 0.179972400},
                  {-0.166212600, -0.159757800, 10, -0.289948200, 0.147146700},
                  {-0.348754200, -0.345024600, 13, -0.420000000, -0.344298300},
                  {-0.344549400, -0.341161800, 13, -0.420000000, -0.344298300},
                  {-0.076126200, -0.073852800, 14, 0.147146700, 0.208001100}};
    const int status = gb_proof_returns_henon_classical(field, def);
    if (status) return status;
    for (size_t k = 0; k < sizeof strips / sizeof strips[0]; k++, def->sets++) {
        def->set_u[def->sets] = (gb_proof_interval){strips[k].lo, strips[k].hi};
        def->returns[def->sets] = strips[k].m;
        def->reach[def->sets] = (gb_proof_interval){strips[k].reach_lo, strips[k].reach_hi};
    }
    return GB_OK;
}
