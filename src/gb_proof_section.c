/* The crossings of a plane by the rigorous integrator's sets (gb_proof_flow.h: the Poincaré map's contract). A step
 * whose a-priori enclosure meets the plane must have x'[coordinate] of one strict sign there; crossings in the stated
 * direction come in windows of consecutive such steps, bracketed by the whole set on the side it leaves and on the
 * side it enters; the k-th window's crossing is the hull of the set over the pieces of its steps' times whose
 * enclosure meets the plane. */
#include "gb_proof_flow.h"

#include "gb_error.h"
#include "gb_proof_flow_internal.h"
#include "gb_proof_internal.h"

#include <math.h>
#include <string.h>

#include <arb.h>

/* Is every point of the ball x strictly on the side sign (+1: above 0, −1: below)? */
static int strictly_on(const arb_t x, int sign)
{
    return sign > 0 ? arb_is_positive(x) : arb_is_negative(x);
}

/* The crossing of a window: the hull of the set over the sub-intervals of time whose enclosure meets the plane. */
typedef struct crossing {
    arb_struct image[NMAX];
    arb_t time;
    int collected;
    /* the C¹ step (derivative on): DΦ from time 0 to the step's start for every point, as DA DQ (DA a point frame
     * following the products' directions, DQ a box matrix: Lohner's QR device for the derivative, so that growth then
     * contraction along different directions is not re-wrapped each step), and the hull of DΦ at the pieces kept
     * (Dcross); scratch Dstep, Dw, Dinv */
    int c1, derived;
    arb_mat_t DA, DQ, Dcross, Dstep, Dw, Dinv;
} crossing;

static void crossing_init(crossing *C, int n, int c1)
{
    for (int i = 0; i < NMAX; i++) arb_init(&C->image[i]);
    arb_init(C->time);
    C->collected = 0;
    C->c1 = c1, C->derived = 0;
    arb_mat_init(C->DA, n, n), arb_mat_init(C->DQ, n, n), arb_mat_init(C->Dcross, n, n), arb_mat_init(C->Dstep, n, n);
    arb_mat_init(C->Dw, n, n), arb_mat_init(C->Dinv, n, n);
    arb_mat_one(C->DA), arb_mat_one(C->DQ);
}

static void crossing_clear(crossing *C)
{
    for (int i = 0; i < NMAX; i++) arb_clear(&C->image[i]);
    arb_clear(C->time);
    arb_mat_clear(C->DA), arb_mat_clear(C->DQ), arb_mat_clear(C->Dcross), arb_mat_clear(C->Dstep), arb_mat_clear(C->Dw);
    arb_mat_clear(C->Dinv);
}

/* The most halvings of a sub-interval of a crossing step: to 2^-20 of it. */
enum { CROSSING_HALVINGS = 20 };

/* Adds to C the set over the times [lo, hi] of the step (after t0) if its enclosure meets the plane x[s] = 0,
 * halving [lo, hi] while the time's spread, not the set's own width, makes the enclosure wide (its width along s
 * above 1.25 times the set's at the time lo). Every solution crossing within [lo, hi] crosses in one of the
 * pieces kept, so their hull holds its crossing. */
static void collect(const field_balls *F, const step_data *D, int s, const arb_t t0, const arf_t lo, const arf_t hi, int halvings,
                    crossing *C)
{
    const int n = F->n;
    arb_struct piece[NMAX];
    for (int i = 0; i < n; i++) arb_init(&piece[i]);
    arb_t sub;
    arb_init(sub);
    arb_set_interval_arf(sub, lo, hi, F->prec);
    gb_proof_flow_enclose_at(F, D, sub, piece);
    int keep = arb_contains_zero(&piece[s]);
    if (keep && halvings > 0) {
        arb_struct thin[NMAX];
        for (int i = 0; i < n; i++) arb_init(&thin[i]);
        arb_set_arf(sub, lo);
        gb_proof_flow_enclose_at(F, D, sub, thin);
        const double wide = mag_get_d(arb_radref(&piece[s])), own = mag_get_d(arb_radref(&thin[s]));
        for (int i = 0; i < n; i++) arb_clear(&thin[i]);
        if (wide > 1.25 * own) {
            arb_set_interval_arf(sub, lo, hi, F->prec); /* its midpoint: a point of [lo, hi] */
            arf_t middle;
            arf_init(middle);
            arf_set(middle, arb_midref(sub));
            collect(F, D, s, t0, lo, middle, halvings - 1, C);
            collect(F, D, s, t0, middle, hi, halvings - 1, C);
            arf_clear(middle);
            keep = 0;
        }
        arb_set_interval_arf(sub, lo, hi, F->prec);
    }
    if (keep && C->c1) { /* DΦ at the piece's times after DA DQ, into the hull */
        gb_proof_flow_derivative_at(F, D, sub, C->Dstep);
        arb_mat_mul(C->Dinv, C->Dstep, C->DA, F->prec);
        arb_mat_mul(C->Dw, C->Dinv, C->DQ, F->prec);
        if (!C->derived++)
            arb_mat_set(C->Dcross, C->Dw);
        else
            for (int a = 0; a < n; a++)
                for (int b = 0; b < n; b++)
                    arb_union(arb_mat_entry(C->Dcross, a, b), arb_mat_entry(C->Dcross, a, b), arb_mat_entry(C->Dw, a, b), F->prec);
    }
    if (keep) {
        arb_add(sub, sub, t0, F->prec);
        if (!C->collected++) {
            for (int i = 0; i < n; i++) arb_set(&C->image[i], &piece[i]);
            arb_set(C->time, sub);
        } else {
            for (int i = 0; i < n; i++) arb_union(&C->image[i], &C->image[i], &piece[i], F->prec);
            arb_union(C->time, C->time, sub, F->prec);
        }
    }
    for (int i = 0; i < n; i++) arb_clear(&piece[i]);
    arb_clear(sub);
}

static int check_section(const gb_proof_flow_def *def, const gb_proof_interval *box, gb_proof_flow_crossing *out)
{
    int status = gb_proof_flow_check(def, box);
    if (status) return status;
    if (!out) return gb_error_set(GB_EINVAL, "a section map needs a result");
    const int s = def->coordinate;
    if (box[s].lo != 0.0 || box[s].hi != 0.0)
        return gb_error_set(GB_EDOM, "box component %d = [%g, %g] is not on the section (allowed: [0, 0])", s, box[s].lo, box[s].hi);
    return GB_OK;
}

static int section_map(integration *Ip, const gb_proof_flow_def *def, gb_proof_flow_crossing *out);

int gb_proof_flow_section_map(const gb_proof_flow_def *def, const gb_proof_interval *box, gb_proof_flow_crossing *out)
{
    int status = check_section(def, box, out);
    if (status) return status;
    field_balls F;
    gb_proof_flow_field_init(&F, def->field, def->order, def->precision);
    status = gb_proof_flow_section_map_of(&F, def, box, out);
    gb_proof_flow_field_clear(&F);
    return status;
}

int gb_proof_flow_section_map_of(const field_balls *F, const gb_proof_flow_def *def, const gb_proof_interval *box,
                                 gb_proof_flow_crossing *out)
{
    const gb_proof_interval b = box[def->coordinate];
    const int off = b.hi < 0.0 || b.lo > 0.0; /* wholly off the plane: its first crossing is crossing 1 */
    int status = off ? gb_proof_flow_check(def, box) : check_section(def, box, out);
    if (!status && (F->n != def->field->dimension || F->order != def->order))
        status = gb_error_set(GB_EINVAL, "the field's dimension and order are not the definition's");
    if (status) return status;
    integration I;
    gb_proof_flow_integration_borrow(&I, F, box);
    status = section_map(&I, def, out);
    gb_proof_flow_integration_release(&I);
    return status;
}

/* The k-th crossing of the integration's set (the box on the section). */
static int section_map(integration *Ip, const gb_proof_flow_def *def, gb_proof_flow_crossing *out)
{
    integration I = *Ip;
    int status = GB_OK;
    const int s = def->coordinate, dir = def->direction;
    memset(out, 0, sizeof *out);
    const double start = gb_proof_cpu_seconds();
    field_balls *const F = &I.F;
    lohner_set *const S = &I.S;
    step_data *const D = &I.D;
    const int n = F->n;
    arb_struct fB[NMAX], piece[NMAX];
    for (int i = 0; i < NMAX; i++) arb_init(&fB[i]), arb_init(&piece[i]);
    crossing C;
    crossing_init(&C, n, def->derivative);
    D->c1 = def->derivative;
    arb_t t;
    arb_init(t);
    /* a set on the plane is in window 0 (its own); one off it, on the side the crossings leave, in none yet */
    const gb_proof_interval b = gb_proof_interval_of(&S->x[s]);
    int window = 0, in_window = b.lo == 0.0 && b.hi == 0.0 && arb_is_zero(&S->r[s]), done = 0;
    out->step_min = INFINITY;
    while (!status && !done) {
        if (arf_cmp_d(arb_midref(t), def->time_max) > 0) {
            status = gb_error_set(GB_ENUMERIC, "crossing %d of %d not reached by t = %g (time_max)", window, def->returns, def->time_max);
            break;
        }
        double h;
        status = gb_proof_flow_step_take(F, S, D, def, INFINITY, I.scratch, &h, t);
        if (status) break;
        const int touches = arb_contains_zero(&D->B[s]);
        int sign = 0;
        if (touches) {
            gb_proof_flow_field_eval(F, D->B, fB);
            sign = arb_is_positive(&fB[s]) ? 1 : arb_is_negative(&fB[s]) ? -1 : 0;
            if (!sign) {
                status = gb_error_set(GB_ENUMERIC, "at t = %.6g the set meets the section where x'[%d] has no sign (a tangency, or "
                                      "the set too wide): the crossing's direction is undecided", arf_get_d(arb_midref(t), ARF_RND_NEAR), s);
                break;
            }
        }
        gb_proof_flow_set_hull(F, S, piece);
        if (touches && sign == dir) {
            if (!in_window) {
                if (!strictly_on(&piece[s], -dir)) {
                    status = gb_error_set(GB_ENUMERIC, "at t = %.6g a crossing begins while the set is not wholly on the side it leaves",
                                          arf_get_d(arb_midref(t), ARF_RND_NEAR));
                    break;
                }
                window++, in_window = 1;
            }
            if (window == def->returns) {
                arf_t lo, hi;
                arf_init(lo), arf_init(hi);
                for (int j = 0; j < def->time_pieces; j++) {
                    arf_set_d(lo, h * j), arf_div_ui(lo, lo, (ulong)def->time_pieces, F->prec, ARF_RND_FLOOR);
                    arf_set_d(hi, h * (j + 1)), arf_div_ui(hi, hi, (ulong)def->time_pieces, F->prec, ARF_RND_CEIL);
                    if (j == 0) arf_zero(lo);
                    if (j == def->time_pieces - 1) arf_set_d(hi, h);
                    collect(F, D, s, t, lo, hi, CROSSING_HALVINGS, &C);
                }
                arf_clear(lo), arf_clear(hi);
            }
        } else if (in_window) {
            if (!strictly_on(&piece[s], dir)) {
                status = gb_error_set(GB_ENUMERIC, "at t = %.6g a crossing ends while the set is not wholly on the side it enters",
                                      arf_get_d(arb_midref(t), ARF_RND_NEAR));
                break;
            }
            in_window = 0;
            if (window == def->returns) {
                done = 1;
                break;
            }
        }
        if (C.c1) { /* DA DQ advanced by the step's DΦ at t = h: B = DΦ DA, DA' the frame of mid B, DQ' = (DA'⁻¹ B) DQ */
            arb_t end;
            arb_init(end);
            arb_set_d(end, h);
            gb_proof_flow_derivative_at(F, D, end, C.Dstep);
            arb_mat_mul(C.Dw, C.Dstep, C.DA, F->prec);
            gb_proof_flow_new_frame(n, C.Dw, NULL, C.DA);
            if (!arb_mat_inv(C.Dinv, C.DA, F->prec)) {
                status = gb_error_set(GB_ENUMERIC, "at t = %.6g the derivative's frame is singular", arf_get_d(arb_midref(t), ARF_RND_NEAR));
                arb_clear(end);
                break;
            }
            arb_mat_mul(C.Dstep, C.Dinv, C.Dw, F->prec);
            arb_mat_mul(C.Dw, C.Dstep, C.DQ, F->prec);
            arb_mat_swap(C.DQ, C.Dw);
            arb_clear(end);
        }
        if (!gb_proof_flow_step_finish(F, S, D, h)) {
            status = gb_error_set(GB_ENUMERIC, "at t = %.6g the Lohner frame is singular", arf_get_d(arb_midref(t), ARF_RND_NEAR));
            break;
        }
        arb_t hb;
        arb_init(hb);
        arb_set_d(hb, h);
        arb_add(t, t, hb, F->prec);
        arb_clear(hb);
        out->steps++;
        out->step_min = fmin(out->step_min, h);
        /* the k-th window ends once the set lies wholly on the side it enters: no further step is needed to see it
         * (a field defined only up to the plane, as a branch of the Gömböcs' H′ up to its tie, has none beyond) */
        if (in_window && window == def->returns) {
            gb_proof_flow_set_hull(F, S, piece);
            done = strictly_on(&piece[s], dir);
        }
    }
    if (!status && !C.collected) status = gb_error_set(GB_ENUMERIC, "the crossing was not enclosed");
    if (!status) {
        for (int i = 0; i < n; i++) out->image[i] = gb_proof_interval_of(&C.image[i]);
        out->image[s] = (gb_proof_interval){0.0, 0.0};
        out->time = gb_proof_interval_of(C.time);
    }
    if (!status && C.c1) { /* DP = (I − f e_sᵀ / f_s) DΦ with f over the crossing's enclosure (the time's derivative: x_s = 0) */
        arb_struct fC[NMAX];
        for (int i = 0; i < NMAX; i++) arb_init(&fC[i]);
        gb_proof_flow_field_eval(F, C.image, fC);
        arb_t ratio;
        arb_init(ratio);
        for (int i = 0; i < n; i++) {
            arb_div(ratio, &fC[i], &fC[s], F->prec);
            for (int b = 0; b < n; b++) {
                arb_ptr e = arb_mat_entry(C.Dw, i, b);
                arb_set(e, arb_mat_entry(C.Dcross, i, b));
                if (i == s) arb_zero(e);
                else arb_submul(e, ratio, arb_mat_entry(C.Dcross, s, b), F->prec);
            }
        }
        for (int a = 0; a < n; a++)
            for (int b = 0; b < n; b++) out->jacobian[a][b] = gb_proof_interval_of(arb_mat_entry(C.Dw, a, b));
        arb_clear(ratio);
        for (int i = 0; i < NMAX; i++) arb_clear(&fC[i]);
        if (!arb_mat_is_finite(C.Dw)) status = gb_error_set(GB_ENUMERIC, "the return map's derivative is not finite");
    }
    for (int i = 0; i < NMAX; i++) arb_clear(&fB[i]), arb_clear(&piece[i]);
    crossing_clear(&C);
    arb_clear(t);
    *Ip = I;
    out->seconds = gb_proof_cpu_seconds() - start;
    return status;
}
