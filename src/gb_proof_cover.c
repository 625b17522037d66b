#include "gb_proof_cover.h"

#include "gb_error.h"
#include "gb_proof_flow_internal.h"
#include "gb_proof_internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <arb.h>
#include <flint/fmpq.h>

gb_proof_cover_def gb_proof_cover_def_default(void)
{
    gb_proof_cover_def d;
    memset(&d, 0, sizeof d);
    d.kind = GB_PROOF_MAP_RETURN;
    d.precision = GB_PROOF_PRECISION_DEFAULT;
    d.iterates = 1;
    d.sets = 1;
    d.pieces = 64;
    d.strip_pieces = 1;
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

/* fmpq of a rational (den 0 reads as 0, as the field does). */
static void fmpq_of(fmpq_t q, gb_proof_rational r)
{
    if (r.den == 0) {
        fmpq_zero(q);
        return;
    }
    fmpq_set_si(q, r.num, (ulong)labs(r.den));
    if (r.den < 0) fmpq_neg(q, q);
}

/* q into a rational of longs: 1 when it fits, 0 when its numerator or denominator does not. */
static int rational_of(const fmpq_t q, gb_proof_rational *r)
{
    if (!fmpz_fits_si(fmpq_numref(q)) || !fmpz_fits_si(fmpq_denref(q))) return 0;
    r->num = fmpz_get_si(fmpq_numref(q)), r->den = fmpz_get_si(fmpq_denref(q));
    return 1;
}

int gb_proof_cover_henon_framed(long a_num, long a_den, long b_num, long b_den, const gb_proof_rational origin[2],
                                const gb_proof_rational frame[2][2], gb_proof_field *out)
{
    if (!origin || !frame || !out) return gb_error_set(GB_EINVAL, "Henon's map in a frame needs an origin, a frame and a field");
    if (a_den == 0 || b_den == 0)
        return gb_error_set(GB_EDOM, "Henon's a = %ld/%ld, b = %ld/%ld is out of range (allowed: nonzero denominators)", a_num,
                            a_den, b_num, b_den);
    /* every coefficient exact: x = o0 + F00 v0 + F01 v1, y = o1 + F10 v0 + F11 v1; h = H(x, y) - o; g = F^-1 h, with
     * h_i = hc_i + hl_ij v_j + hq_i . (v0^2, v0 v1, v1^2) */
    fmpq_t a, b, o[2], F[2][2], G[2][2], det, t, u, hc[2], hl[2][2], hq[2][3];
    fmpq_init(a), fmpq_init(b), fmpq_init(det), fmpq_init(t), fmpq_init(u);
    for (int i = 0; i < 2; i++) {
        fmpq_init(o[i]), fmpq_init(hc[i]);
        for (int j = 0; j < 2; j++) fmpq_init(F[i][j]), fmpq_init(G[i][j]), fmpq_init(hl[i][j]);
        for (int k = 0; k < 3; k++) fmpq_init(hq[i][k]);
    }
    fmpq_of(a, (gb_proof_rational){a_num, a_den}), fmpq_of(b, (gb_proof_rational){b_num, b_den});
    for (int i = 0; i < 2; i++) {
        fmpq_of(o[i], origin[i]);
        for (int j = 0; j < 2; j++) fmpq_of(F[i][j], frame[i][j]);
    }
    fmpq_mul(det, F[0][0], F[1][1]), fmpq_mul(t, F[0][1], F[1][0]), fmpq_sub(det, det, t);
    int status = GB_OK;
    if (fmpq_is_zero(det)) {
        status = gb_error_set(GB_EDOM, "the frame's matrix is singular (allowed: an invertible 2 x 2 matrix)");
    } else {
        /* h0 = 1 - a x^2 + y - o0 */
        fmpq_mul(t, o[0], o[0]), fmpq_mul(t, t, a), fmpq_one(hc[0]), fmpq_sub(hc[0], hc[0], t);
        fmpq_add(hc[0], hc[0], o[1]), fmpq_sub(hc[0], hc[0], o[0]);
        for (int j = 0; j < 2; j++) /* -2 a o0 F0j + F1j */
            fmpq_mul(t, a, o[0]), fmpq_mul_si(t, t, -2), fmpq_mul(t, t, F[0][j]), fmpq_add(hl[0][j], t, F[1][j]);
        fmpq_mul(t, F[0][0], F[0][0]), fmpq_mul(hq[0][0], t, a), fmpq_neg(hq[0][0], hq[0][0]);
        fmpq_mul(t, F[0][0], F[0][1]), fmpq_mul(t, t, a), fmpq_mul_si(hq[0][1], t, -2);
        fmpq_mul(t, F[0][1], F[0][1]), fmpq_mul(hq[0][2], t, a), fmpq_neg(hq[0][2], hq[0][2]);
        /* h1 = b x - o1 */
        fmpq_mul(t, b, o[0]), fmpq_sub(hc[1], t, o[1]);
        for (int j = 0; j < 2; j++) fmpq_mul(hl[1][j], b, F[0][j]);
        /* G = F^-1 */
        fmpq_div(G[0][0], F[1][1], det), fmpq_div(G[1][1], F[0][0], det);
        fmpq_div(G[0][1], F[0][1], det), fmpq_neg(G[0][1], G[0][1]);
        fmpq_div(G[1][0], F[1][0], det), fmpq_neg(G[1][0], G[1][0]);
        memset(out, 0, sizeof *out);
        out->dimension = 2;
        int fits = 1;
        static const int slot[3][2] = {{0, 0}, {0, 1}, {1, 1}};
        for (int i = 0; i < 2; i++) {
            fmpq_mul(t, G[i][0], hc[0]), fmpq_mul(u, G[i][1], hc[1]), fmpq_add(t, t, u);
            fits &= rational_of(t, &out->c[i]);
            for (int j = 0; j < 2; j++) {
                fmpq_mul(t, G[i][0], hl[0][j]), fmpq_mul(u, G[i][1], hl[1][j]), fmpq_add(t, t, u);
                fits &= rational_of(t, &out->L[i][j]);
            }
            for (int k = 0; k < 3; k++) { /* h1 has no quadratic part */
                fmpq_mul(t, G[i][0], hq[0][k]);
                fits &= rational_of(t, &out->Q[i][slot[k][0]][slot[k][1]]);
            }
        }
        if (!fits)
            status = gb_error_set(GB_EDOM, "Henon's map in this frame has a coefficient whose numerator or denominator exceeds a "
                                  "long (allowed: an origin and a frame with smaller denominators)");
    }
    fmpq_clear(a), fmpq_clear(b), fmpq_clear(det), fmpq_clear(t), fmpq_clear(u);
    for (int i = 0; i < 2; i++) {
        fmpq_clear(o[i]), fmpq_clear(hc[i]);
        for (int j = 0; j < 2; j++) fmpq_clear(F[i][j]), fmpq_clear(G[i][j]), fmpq_clear(hl[i][j]);
        for (int k = 0; k < 3; k++) fmpq_clear(hq[i][k]);
    }
    return status;
}

int gb_proof_cover_henon_classical(gb_proof_field *field, gb_proof_cover_def *def)
{
    static const gb_proof_rational origin[2] = {{3157, 5000}, {947, 5000}};
    static const gb_proof_rational frame[2][2] = {{{-1, 1}, {-13, 25}}, {{39, 250}, {-1, 1}}};
    static const double U[5][2] = {{-0.41079, -0.3875}, {-0.38371, -0.3596}, {-0.24016, -0.20567}, {-0.20529, -0.17745},
                                   {-0.00009, 0.00564}};
    if (!field || !def) return gb_error_set(GB_EINVAL, "the classical Henon horseshoe needs a field and a definition");
    const int status = gb_proof_cover_henon_framed(7, 5, 3, 10, origin, frame, field);
    if (status) return status;
    *def = gb_proof_cover_def_default();
    def->kind = GB_PROOF_MAP_QUADRATIC, def->map = field;
    def->u = 0, def->s = 1, def->iterates = 7, def->halve_along = 1, def->depth = 8, def->pieces = 8;
    def->strip = (gb_proof_interval){-0.045, 0.045};
    def->sets = 5;
    for (int i = 0; i < 5; i++) def->set_u[i] = (gb_proof_interval){U[i][0], U[i][1]};
    return GB_OK;
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
    if (def->strip_pieces < 1 || def->strip_pieces > 100000)
        return gb_error_set(GB_EDOM, "strip pieces = %d is out of range (allowed: 1 to 100000)", def->strip_pieces);
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

/* f^k of the box x (2 balls) for a quadratic map, in affine form (the C⁰ Lohner algorithm for maps): the set is
 * ĉ + A r with r the box's half-widths, A a point matrix and ĉ a box; a step is, by the mean value theorem with J = Df
 * over the hull X = ĉ + A r (convex, holding mid ĉ), f(mid ĉ) + J (ĉ − mid ĉ) + (J A − A') r + A' r, A' = mid(J A).
 * The linear part is carried exactly, so a thin box turned and stretched k times is not re-wrapped at every step. */
int gb_proof_affine_image(const field_balls *F, arb_ptr x, int iterates)
{
    const slong prec = F->prec;
    arb_struct c[2], r[2], e[2], hull[2], y[2];
    arb_mat_t A, J, JA;
    arb_mat_init(A, 2, 2), arb_mat_init(J, 2, 2), arb_mat_init(JA, 2, 2);
    for (int i = 0; i < 2; i++) {
        arb_init(&c[i]), arb_init(&r[i]), arb_init(&e[i]), arb_init(&hull[i]), arb_init(&y[i]);
        arb_set_arf(&c[i], arb_midref(x + i));                  /* the box's middle, exact */
        arb_zero(&r[i]), mag_set(arb_radref(&r[i]), arb_radref(x + i)); /* its half-widths about 0 */
    }
    arb_mat_one(A);
    for (int k = 0; k < iterates; k++) {
        for (int i = 0; i < 2; i++) { /* the hull X = ĉ + A r, and e = ĉ − mid ĉ */
            arb_set(&hull[i], &c[i]);
            for (int j = 0; j < 2; j++) arb_addmul(&hull[i], arb_mat_entry(A, i, j), &r[j], prec);
            arb_zero(&e[i]), mag_set(arb_radref(&e[i]), arb_radref(&c[i]));
            arb_set_arf(&c[i], arb_midref(&c[i]));
        }
        gb_proof_flow_field_derivative(F, hull, J);
        gb_proof_flow_field_eval(F, c, y); /* f(mid ĉ) */
        arb_mat_mul(JA, J, A, prec);
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++) { /* A' = mid(J A); the rest of J A joins ĉ */
                arb_set_arf(arb_mat_entry(A, i, j), arb_midref(arb_mat_entry(JA, i, j)));
                arb_sub(arb_mat_entry(JA, i, j), arb_mat_entry(JA, i, j), arb_mat_entry(A, i, j), prec);
            }
        for (int i = 0; i < 2; i++)
            for (int j = 0; j < 2; j++)
                arb_addmul(&y[i], arb_mat_entry(J, i, j), &e[j], prec), arb_addmul(&y[i], arb_mat_entry(JA, i, j), &r[j], prec);
        for (int i = 0; i < 2; i++) arb_swap(&c[i], &y[i]);
    }
    for (int i = 0; i < 2; i++) { /* the box ĉ + A r */
        arb_set(x + i, &c[i]);
        for (int j = 0; j < 2; j++) arb_addmul(x + i, arb_mat_entry(A, i, j), &r[j], prec);
    }
    const int finite = arb_is_finite(x) && arb_is_finite(x + 1);
    for (int i = 0; i < 2; i++) arb_clear(&c[i]), arb_clear(&r[i]), arb_clear(&e[i]), arb_clear(&hull[i]), arb_clear(&y[i]);
    arb_mat_clear(A), arb_mat_clear(J), arb_mat_clear(JA);
    return finite;
}

/* f^k of the rectangle u × s on the plane: its extents across (*image_u) and along (*image_s). F: the quadratic map's
 * balls (NULL for a return map). GB_ENUMERIC with the flow's message when the enclosure is not carried. */
static int image_of(const gb_proof_cover_def *def, const field_balls *F, gb_proof_interval u, gb_proof_interval s, int iterates,
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
    arb_struct x[2];
    for (int i = 0; i < 2; i++) arb_init(&x[i]);
    gb_proof_ball_of(&x[def->u], u, F->prec), gb_proof_ball_of(&x[def->s], s, F->prec);
    const int finite = gb_proof_affine_image(F, x, iterates);
    *image_u = gb_proof_interval_of(&x[def->u]), *image_s = gb_proof_interval_of(&x[def->s]);
    for (int i = 0; i < 2; i++) arb_clear(&x[i]);
    return finite ? GB_OK : gb_error_set(GB_ENUMERIC, "the map's enclosure is not finite");
}

/* What a range across must prove of each piece's image. */
typedef struct inclusion {
    const gb_proof_cover_def *def;
    const field_balls *F;
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

/* 1 when f^k(u × s) lies in int S along (and in int region_u across, for the trap), halving u (and s, with
 * halve_along) on failure to depth; 0 with out->failure naming the first piece that fails at the deepest halving. */
static int prove_piece(inclusion *I, gb_proof_interval u, gb_proof_interval s, int level)
{
    const gb_proof_cover_def *def = I->def;
    gb_proof_interval iu, is;
    const int status = image_of(def, I->F, u, s, I->iterates, &iu, &is);
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
    if (level < def->depth && gb_proof_halvable(u)) {
        if (!def->halve_along || !gb_proof_halvable(s))
            return prove_piece(I, gb_proof_half(u, 0), s, level + 1) &&
                   prove_piece(I, gb_proof_half(u, 1), s, level + 1);
        for (int k = 0; k < 4; k++)
            if (!prove_piece(I, gb_proof_half(u, k & 1), gb_proof_half(s, k >> 1), level + 1)) return 0;
        return 1;
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

/* The k-th of n equal cuts of x (its ends exact). */
static gb_proof_interval cut(gb_proof_interval x, int k, int n)
{
    return (gb_proof_interval){k ? x.lo + (x.hi - x.lo) * k / n : x.lo, k + 1 < n ? x.lo + (x.hi - x.lo) * (k + 1) / n : x.hi};
}

/* Every piece of the range across × S, cut first into def->pieces × def->strip_pieces. */
static int prove_range(inclusion *I, gb_proof_interval u)
{
    const gb_proof_cover_def *def = I->def;
    for (int k = 0; k < def->pieces; k++)
        for (int m = 0; m < def->strip_pieces; m++)
            if (!prove_piece(I, cut(u, k, def->pieces), cut(def->strip, m, def->strip_pieces), 0)) return 0;
    return 1;
}

/* Whether the interval x holds an end of some h-set across (where an edge's image decides nothing). */
static int holds_an_end(const gb_proof_cover_def *def, gb_proof_interval x)
{
    for (size_t j = 0; j < def->sets; j++)
        if ((x.lo <= def->set_u[j].lo && def->set_u[j].lo <= x.hi) || (x.lo <= def->set_u[j].hi && def->set_u[j].hi <= x.hi))
            return 1;
    return 0;
}

/* The image across of the edge {at} × s, into the hull *image_u (*any: started); with halve_along, a piece whose image
 * holds an end of an h-set is halved along, to depth. */
static int edge_image(const gb_proof_cover_def *def, const field_balls *F, double at, gb_proof_interval s, int level, gb_proof_interval *image_u,
                      int *any, long *pieces)
{
    gb_proof_interval iu, is;
    const int status = image_of(def, F, (gb_proof_interval){at, at}, s, def->iterates, &iu, &is);
    ++*pieces;
    if (status) return status;
    if (def->halve_along && level < def->depth && gb_proof_halvable(s) && holds_an_end(def, iu)) {
        const int low = edge_image(def, F, at, gb_proof_half(s, 0), level + 1, image_u, any, pieces);
        return low ? low : edge_image(def, F, at, gb_proof_half(s, 1), level + 1, image_u, any, pieces);
    }
    if (!*any) *image_u = iu, *any = 1;
    else image_u->lo = fmin(image_u->lo, iu.lo), image_u->hi = fmax(image_u->hi, iu.hi);
    return GB_OK;
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
    field_balls balls, *F = NULL; /* a quadratic map's coefficients as balls, once */
    if (def->kind == GB_PROOF_MAP_QUADRATIC) gb_proof_flow_field_init(&balls, def->map, GB_PROOF_ORDER_MIN, def->precision), F = &balls;
    if (def->trap) {
        inclusion I = {def, F, 1, 1, {0, 0}, {0, 0}, 0, out};
        out->trapped = prove_range(&I, def->region_u);
        out->trap_image_u = I.hull_u, out->trap_image_s = I.hull_s;
    }
    for (size_t i = 0; i < def->sets; i++) {
        const gb_proof_interval U = def->set_u[i];
        if (def->trap) {
            out->strip[i] = out->trapped && U.lo >= def->region_u.lo && U.hi <= def->region_u.hi;
            out->image_s[i] = out->trap_image_s;
        } else {
            inclusion I = {def, F, def->iterates, 0, {0, 0}, {0, 0}, 0, out};
            out->strip[i] = prove_range(&I, U);
            out->image_s[i] = I.hull_s;
        }
        for (int side = 0; side < 2; side++) {
            const double at = side ? U.hi : U.lo;
            int edge_status = GB_OK, any = 0;
            for (int m = 0; m < def->strip_pieces && !edge_status; m++)
                edge_status = edge_image(def, F, at, cut(def->strip, m, def->strip_pieces), 0, &out->edge[i][side], &any, &out->pieces);
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
    if (F) gb_proof_flow_field_clear(F);
    status = gb_proof_cover_entropy_bound(matrix, def->sets, &out->entropy, &out->rho);
    if (!status) { /* h_top(g^k) = k h_top(g): the bound divided by k, its lower end */
        arb_t e;
        arb_init(e);
        arb_set_d(e, out->entropy);
        arb_div_si(e, e, def->iterates, 64);
        out->entropy_map = fmax(0.0, gb_proof_interval_of(e).lo);
        arb_clear(e);
    }
    out->seconds = gb_proof_cpu_seconds() - start;
    return status;
}
