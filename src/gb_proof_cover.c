#include "gb_proof_cover.h"

#include "gb_error.h"
#include "gb_proof_flow_internal.h"
#include "gb_proof_internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <arb.h>

gb_proof_cover_def gb_proof_cover_def_default(void)
{
    gb_proof_cover_def d;
    memset(&d, 0, sizeof d);
    d.kind = GB_PROOF_MAP_RETURN;
    d.precision = GB_PROOF_PRECISION_DEFAULT;
    d.iterates = 1;
    d.sets = 1;
    d.pieces = 64;
    d.depth = 6;
    return d;
}

gb_proof_field gb_proof_cover_henon(long a_num, long a_den, long b_num, long b_den)
{
    gb_proof_field f;
    memset(&f, 0, sizeof f);
    f.dimension = 2;
    f.c[0] = (gb_proof_rational){1, 1};
    f.Q[0][0][0] = (gb_proof_rational){-a_num, a_den};
    f.L[0][1] = (gb_proof_rational){1, 1};
    f.L[1][0] = (gb_proof_rational){b_num, b_den};
    return f;
}

static int interval_ok(gb_proof_interval x)
{
    return isfinite(x.lo) && isfinite(x.hi) && x.lo <= x.hi;
}

static int check_cover_def(const gb_proof_cover_def *def)
{
    if (!def) return gb_error_set(GB_EINVAL, "covering relations need a definition");
    if (def->kind != GB_PROOF_MAP_RETURN && def->kind != GB_PROOF_MAP_QUADRATIC)
        return gb_error_set(GB_EDOM, "map kind = %d is out of range (allowed: 0 return map, 1 quadratic map)", (int)def->kind);
    const int dimension = def->kind == GB_PROOF_MAP_RETURN ? 3 : 2;
    const gb_proof_field *f = def->kind == GB_PROOF_MAP_RETURN ? def->section.field : def->map;
    if (!f) return gb_error_set(GB_EINVAL, "covering relations need a field");
    if (f->dimension != dimension)
        return gb_error_set(GB_EDOM, "field dimension = %d is out of range (allowed: %d for a %s)", f->dimension, dimension,
                            dimension == 3 ? "return map to a plane" : "map of the plane");
    if (def->kind == GB_PROOF_MAP_QUADRATIC) {
        const int status = gb_proof_check_precision(def->precision);
        if (status) return status;
    }
    if (def->u < 0 || def->u >= dimension || def->s < 0 || def->s >= dimension || def->u == def->s ||
        (def->kind == GB_PROOF_MAP_RETURN && (def->u == def->section.coordinate || def->s == def->section.coordinate)))
        return gb_error_set(GB_EDOM, "plane coordinates u = %d, s = %d are out of range (allowed: two different coordinates "
                            "from 0 to %d, neither the section's)", def->u, def->s, dimension - 1);
    if (def->iterates < 1 || def->iterates > 16)
        return gb_error_set(GB_EDOM, "iterates = %d is out of range (allowed: 1 to 16)", def->iterates);
    if (def->trap && def->kind != GB_PROOF_MAP_RETURN)
        return gb_error_set(GB_EDOM, "trap = 1 is out of range for a map of the plane (allowed: 0)");
    if (def->sets < 1 || def->sets > GB_PROOF_HSETS_MAX)
        return gb_error_set(GB_EDOM, "sets = %zu is out of range (allowed: 1 to %d)", def->sets, GB_PROOF_HSETS_MAX);
    if (def->pieces < 1 || def->pieces > 100000)
        return gb_error_set(GB_EDOM, "pieces = %d is out of range (allowed: 1 to 100000)", def->pieces);
    if (def->depth < 0 || def->depth > 20) return gb_error_set(GB_EDOM, "depth = %d is out of range (allowed: 0 to 20)", def->depth);
    if (!interval_ok(def->strip) || !(def->strip.lo < def->strip.hi))
        return gb_error_set(GB_EDOM, "strip = [%g, %g] is out of range (allowed: a finite interval with lo < hi)", def->strip.lo,
                            def->strip.hi);
    if (def->trap && (!interval_ok(def->region_u) || !(def->region_u.lo < def->region_u.hi)))
        return gb_error_set(GB_EDOM, "region_u = [%g, %g] is out of range (allowed: a finite interval with lo < hi)",
                            def->region_u.lo, def->region_u.hi);
    for (size_t i = 0; i < def->sets; i++) {
        if (!interval_ok(def->set_u[i]) || !(def->set_u[i].lo < def->set_u[i].hi))
            return gb_error_set(GB_EDOM, "set %zu = [%g, %g] is out of range (allowed: a finite interval with lo < hi)", i,
                                def->set_u[i].lo, def->set_u[i].hi);
        for (size_t j = 0; j < i; j++)
            if (def->set_u[i].lo <= def->set_u[j].hi && def->set_u[j].lo <= def->set_u[i].hi)
                return gb_error_set(GB_EDOM, "sets %zu and %zu overlap (allowed: disjoint h-sets)", j, i);
    }
    if (def->kind == GB_PROOF_MAP_RETURN) {
        const int status = gb_proof_flow_def_check(&def->section);
        if (status) return status;
    }
    return GB_OK;
}

/* f^k of the rectangle u × s on the plane: its extents across (*image_u) and along (*image_s). GB_ENUMERIC with the
 * flow's message when the enclosure is not carried. */
static int image_of(const gb_proof_cover_def *def, gb_proof_interval u, gb_proof_interval s, int iterates,
                    gb_proof_interval *image_u, gb_proof_interval *image_s)
{
    if (def->kind == GB_PROOF_MAP_RETURN) {
        gb_proof_flow_def map = def->section;
        map.returns = iterates;
        gb_proof_interval box[3];
        box[map.coordinate] = (gb_proof_interval){0.0, 0.0};
        box[def->u] = u, box[def->s] = s;
        gb_proof_flow_crossing r;
        const int status = gb_proof_flow_section_map(&map, box, &r);
        if (status) return status;
        *image_u = r.image[def->u], *image_s = r.image[def->s];
        return GB_OK;
    }
    const slong prec = def->precision;
    arb_struct x[2], y[2];
    for (int i = 0; i < 2; i++) arb_init(&x[i]), arb_init(&y[i]);
    gb_proof_ball_of(&x[def->u], u, prec), gb_proof_ball_of(&x[def->s], s, prec);
    for (int k = 0; k < iterates; k++) {
        gb_proof_field_image(def->map, x, y, prec);
        for (int i = 0; i < 2; i++) arb_swap(&x[i], &y[i]);
    }
    *image_u = gb_proof_interval_of(&x[def->u]), *image_s = gb_proof_interval_of(&x[def->s]);
    const int finite = arb_is_finite(&x[0]) && arb_is_finite(&x[1]);
    for (int i = 0; i < 2; i++) arb_clear(&x[i]), arb_clear(&y[i]);
    return finite ? GB_OK : gb_error_set(GB_ENUMERIC, "the map's enclosure is not finite");
}

/* What a range across must prove of each piece's image. */
typedef struct inclusion {
    const gb_proof_cover_def *def;
    int iterates;
    int check_u;                  /* the image across inside int region_u (the trap) */
    gb_proof_interval hull_u, hull_s;
    int any;
    gb_proof_cover_result *out;
} inclusion;

static int inside(gb_proof_interval x, gb_proof_interval box)
{
    return x.lo > box.lo && x.hi < box.hi;
}

/* 1 when f^k(u × S) lies in int S along (and in int region_u across, for the trap), halving u on failure to depth;
 * 0 with out->failure naming the first piece that fails at the deepest halving. */
static int prove_piece(inclusion *I, gb_proof_interval u, int level)
{
    const gb_proof_cover_def *def = I->def;
    gb_proof_interval iu, is;
    const int status = image_of(def, u, def->strip, I->iterates, &iu, &is);
    I->out->pieces++;
    const int ok = !status && inside(is, def->strip) && (!I->check_u || inside(iu, def->region_u));
    if (ok) { /* the hull of the images that proved their inclusion */
        if (!I->any)
            I->hull_u = iu, I->hull_s = is, I->any = 1;
        else
            I->hull_u.lo = fmin(I->hull_u.lo, iu.lo), I->hull_u.hi = fmax(I->hull_u.hi, iu.hi),
            I->hull_s.lo = fmin(I->hull_s.lo, is.lo), I->hull_s.hi = fmax(I->hull_s.hi, is.hi);
        return 1;
    }
    if (level < def->depth) {
        const double middle = 0.5 * (u.lo + u.hi);
        if (middle > u.lo && middle < u.hi)
            return prove_piece(I, (gb_proof_interval){u.lo, middle}, level + 1) &&
                   prove_piece(I, (gb_proof_interval){middle, u.hi}, level + 1);
    }
    I->out->failed_pieces++;
    if (!I->out->failure[0]) {
        I->out->failed_u = u;
        I->out->failed_image_u = status ? (gb_proof_interval){NAN, NAN} : iu;
        I->out->failed_image_s = status ? (gb_proof_interval){NAN, NAN} : is;
        if (status)
            snprintf(I->out->failure, sizeof I->out->failure, "u in [%.9g, %.9g]: %s", u.lo, u.hi, gb_error_message());
        else
            snprintf(I->out->failure, sizeof I->out->failure, "u in [%.9g, %.9g]: image across [%.9g, %.9g], along [%.9g, %.9g]",
                     u.lo, u.hi, iu.lo, iu.hi, is.lo, is.hi);
    }
    return 0;
}

/* Every piece of the range across, cut first into def->pieces. */
static int prove_range(inclusion *I, gb_proof_interval u)
{
    const int n = I->def->pieces;
    for (int k = 0; k < n; k++) {
        const double lo = k ? u.lo + (u.hi - u.lo) * k / n : u.lo, hi = k + 1 < n ? u.lo + (u.hi - u.lo) * (k + 1) / n : u.hi;
        if (!prove_piece(I, (gb_proof_interval){lo, hi}, 0)) return 0;
    }
    return 1;
}

int gb_proof_cover_entropy_bound(const int *matrix, size_t n, double *log_rho, double *rho)
{
    if (!matrix || !log_rho || !rho || n < 1 || n > GB_PROOF_HSETS_MAX)
        return gb_error_set(GB_EDOM, "a transition matrix of n = %zu sets is out of range (allowed: 1 to %d)", n, GB_PROOF_HSETS_MAX);
    double v[GB_PROOF_HSETS_MAX], w[GB_PROOF_HSETS_MAX];
    for (size_t i = 0; i < n; i++) v[i] = 1.0;
    for (int iteration = 0; iteration < 200; iteration++) { /* power iteration on A + I (same Perron vector, aperiodic) */
        double norm = 0.0;
        for (size_t i = 0; i < n; i++) {
            w[i] = v[i];
            for (size_t j = 0; j < n; j++) w[i] += matrix[i * n + j] ? v[j] : 0.0;
            norm = fmax(norm, w[i]);
        }
        for (size_t i = 0; i < n; i++) v[i] = fmax(w[i] / norm, 1e-3); /* kept positive: Collatz–Wielandt needs v > 0 */
    }
    arb_t least, ratio, sum, term;
    arb_init(least), arb_init(ratio), arb_init(sum), arb_init(term);
    const slong prec = 128;
    for (size_t i = 0; i < n; i++) {
        arb_zero(sum);
        for (size_t j = 0; j < n; j++)
            if (matrix[i * n + j]) arb_set_d(term, v[j]), arb_add(sum, sum, term, prec);
        arb_set_d(term, v[i]);
        arb_div(ratio, sum, term, prec);
        if (!i)
            arb_set(least, ratio);
        else
            arb_min(least, least, ratio, prec);
    }
    *rho = gb_proof_interval_of(least).lo;
    *log_rho = 0.0;
    arb_sub_ui(sum, least, 1, prec);
    if (arb_is_positive(sum)) { /* ρ > 1 proved: ln ρ ≥ ln of the bound */
        arb_log(ratio, least, prec);
        *log_rho = gb_proof_interval_of(ratio).lo;
    }
    arb_clear(least), arb_clear(ratio), arb_clear(sum), arb_clear(term);
    return GB_OK;
}

int gb_proof_cover(const gb_proof_cover_def *def, gb_proof_cover_result *out)
{
    int status = check_cover_def(def);
    if (status) return status;
    if (!out) return gb_error_set(GB_EINVAL, "covering relations need a result");
    memset(out, 0, sizeof *out);
    out->failed_u = out->failed_image_u = out->failed_image_s = (gb_proof_interval){NAN, NAN};
    const double start = gb_proof_cpu_seconds();
    if (def->trap) {
        inclusion I = {def, 1, 1, {0, 0}, {0, 0}, 0, out};
        out->trapped = prove_range(&I, def->region_u);
        out->trap_image_u = I.hull_u, out->trap_image_s = I.hull_s;
    }
    for (size_t i = 0; i < def->sets; i++) {
        const gb_proof_interval U = def->set_u[i];
        if (def->trap) {
            out->strip[i] = out->trapped && U.lo >= def->region_u.lo && U.hi <= def->region_u.hi;
            out->image_s[i] = out->trap_image_s;
        } else {
            inclusion I = {def, def->iterates, 0, {0, 0}, {0, 0}, 0, out};
            out->strip[i] = prove_range(&I, U);
            out->image_s[i] = I.hull_s;
        }
        for (int side = 0; side < 2; side++) {
            const double at = side ? U.hi : U.lo;
            gb_proof_interval along;
            const int edge_status = image_of(def, (gb_proof_interval){at, at}, def->strip, def->iterates, &out->edge[i][side], &along);
            if (edge_status) {
                out->edge[i][side] = (gb_proof_interval){NAN, NAN};
                if (!out->failure[0])
                    snprintf(out->failure, sizeof out->failure, "set %zu's edge u = %.9g: %s", i, at, gb_error_message());
            }
        }
    }
    int matrix[GB_PROOF_HSETS_MAX * GB_PROOF_HSETS_MAX] = {0};
    for (size_t i = 0; i < def->sets; i++)
        for (size_t j = 0; j < def->sets; j++) {
            const gb_proof_interval lo = out->edge[i][0], hi = out->edge[i][1], V = def->set_u[j];
            const int across = (lo.hi < V.lo && hi.lo > V.hi) || (hi.hi < V.lo && lo.lo > V.hi); /* NaN compares false */
            out->covers[i][j] = out->strip[i] && across;
            matrix[i * def->sets + j] = out->covers[i][j];
        }
    status = gb_proof_cover_entropy_bound(matrix, def->sets, &out->entropy, &out->rho);
    out->seconds = gb_proof_cpu_seconds() - start;
    return status;
}
