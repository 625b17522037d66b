/* gb_proof_body_flow — the Gömböcs' reduced field at a forcing, integrated on Arb's balls (gb_proof_body.h).
 *
 * The state is (q, P, c, s) with P = q̇ and (c, s) = (cos ωt, sin ωt), so that the forcing is quadratic:
 * q̇ = P, Ṗ = −(m/M) a H′(q) − μP with a = g + A₁c + A₂((c² − s²) cos ψ − 2cs sin ψ), ċ = −ωs, ṡ = ωc. Everything
 * but H′ is the quadratic field gb_proof_flow integrates; H′ is its one-variable term (gb_proof_flow_term.c), whose
 * Taylor coefficients over each ball of q a step needs come from gb_proof_body_jet_enclose (G = H′: g_k = (k + 1) H_{k+1}).
 * M and ψ enter as balls, so the image holds the flow for every M and ψ in their intervals. */
#include "gb_proof_body.h"

#include "gb_error.h"
#include "gb_proof_body_boxes.h"
#include "gb_proof_flow_internal.h"
#include "gb_proof_internal.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* The jet's context: the definition, the last arc asked (a step asks the same ball several times) and the first
 * failure's message. */
typedef struct jets {
    const gb_proof_body_def *def;
    int branch;      /* 1: one branch at the tie q_s (below it, or above), the state's q read as q − shift */
    double q_s, shift;
    int above;
    double lo, hi;
    int order;
    gb_proof_interval H[GB_PROOF_BODY_JET_ORDER_MAX + 1];
    int failed;
    char why[400];
} jets;

static int h_prime(void *context, const arb_t x, int order, arb_ptr g)
{
    jets *J = context;
    gb_proof_interval q = gb_proof_interval_of(x);
    if (J->branch) { /* the state is q − q_s */
        arb_t y;
        arb_init(y);
        arb_set_d(y, J->shift);
        arb_add(y, y, x, J->def->precision);
        q = gb_proof_interval_of(y);
        arb_clear(y);
    }
    if (!(q.hi - q.lo <= GB_PROOF_BODY_JET_ARC_MAX) || order + 1 > GB_PROOF_BODY_JET_ORDER_MAX) {
        if (!J->failed)
            snprintf(J->why, sizeof J->why,
                     "a step's enclosure spans q in [%.9g, %.9g], wider than the arcs H' is enclosed "
                     "over (at most %g)",
                     q.lo, q.hi, GB_PROOF_BODY_JET_ARC_MAX);
        J->failed = 1;
        return 1;
    }
    if (!(q.lo == J->lo && q.hi == J->hi && order + 1 <= J->order)) {
        gb_proof_body_jet jet;
        if (J->branch ? gb_proof_body_jet_branch(J->def, q.lo, q.hi, order + 1, J->q_s, J->above, &jet)
                      : gb_proof_body_jet_enclose(J->def, q.lo, q.hi, order + 1, &jet)) {
            if (!J->failed) snprintf(J->why, sizeof J->why, "%s", gb_error_message());
            gb_error_clear();
            J->failed = 1;
            J->order = -1;
            return 1;
        }
        J->lo = q.lo, J->hi = q.hi, J->order = order + 1;
        memcpy(J->H, jet.H, sizeof jet.H);
    }
    for (int k = 0; k <= order; k++) {
        gb_proof_ball_of(g + k, J->H[k + 1], J->def->precision);
        arb_mul_ui(g + k, g + k, (ulong)k + 1, J->def->precision);
    }
    return 0;
}

static int check_forcing(const gb_proof_body_forcing *f, int order, const gb_proof_interval box[2])
{
    if (!(f->damping >= 0.0 && isfinite(f->damping)))
        return gb_error_set(GB_EDOM, "damping = %g is out of range (allowed: >= 0)", f->damping);
    if (!(isfinite(f->A1) && isfinite(f->A2)))
        return gb_error_set(GB_EDOM, "A1 = %g, A2 = %g: the amplitudes must be finite", f->A1, f->A2);
    if (!(f->omega > 0.0 && f->omega <= 1000.0))
        return gb_error_set(GB_EDOM, "omega = %g is out of range (allowed: 0 < omega <= 1000)", f->omega);
    if (!(isfinite(f->psi.lo) && isfinite(f->psi.hi) && f->psi.lo <= f->psi.hi))
        return gb_error_set(GB_EDOM, "psi = [%g, %g] is not a finite interval (allowed: lo <= hi)", f->psi.lo,
                            f->psi.hi);
    if (!(order >= GB_PROOF_ORDER_MIN && order < GB_PROOF_BODY_JET_ORDER_MAX))
        return gb_error_set(GB_EDOM, "order = %d is out of range (allowed: %d to %d)", order, GB_PROOF_ORDER_MIN,
                            GB_PROOF_BODY_JET_ORDER_MAX - 1);
    for (int i = 0; i < 2; i++)
        if (!(isfinite(box[i].lo) && isfinite(box[i].hi) && box[i].lo <= box[i].hi))
            return gb_error_set(GB_EDOM, "box component %d = [%g, %g] is not a finite interval (allowed: lo <= hi)", i,
                                box[i].lo, box[i].hi);
    return GB_OK;
}

/* The field in (q, P, c, s) at the forcing, its term's jets in *J (gb_proof_flow_field_clear releases it). */
static void reduced_field(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing, int order, jets *J,
                          field_balls *F)
{
    const slong prec = def->precision;
    const gb_proof_field shape = {.dimension = 4};
    gb_proof_flow_field_init(F, &shape, order, prec);
    arb_t mM, x, y;
    arb_init(mM), arb_init(x), arb_init(y);
    /* m / M, μ = c / M */
    gb_proof_ball_of(x, def->inertia, prec);
    arb_set_d(mM, def->mass);
    arb_div(mM, mM, x, prec);
    arb_one(&F->L[0][1]);
    arb_set_d(y, forcing->damping);
    arb_div(y, y, x, prec);
    arb_neg(&F->L[1][1], y);
    arb_set_d(&F->L[3][2], forcing->omega);
    arb_neg(&F->L[2][3], &F->L[3][2]);
    /* the term −(m/M) a(c, s) H′(q) of row 1 */
    field_term *T = &F->term;
    T->row = 1, T->var = 0;
    arb_set_d(x, def->g);
    arb_mul(&T->a0, x, mM, prec);
    arb_neg(&T->a0, &T->a0);
    arb_set_d(x, forcing->A1);
    arb_mul(&T->a1[2], x, mM, prec);
    arb_neg(&T->a1[2], &T->a1[2]);
    gb_proof_ball_of(y, forcing->psi, prec);
    arb_cos(x, y, prec);
    arb_set_d(y, forcing->A2);
    arb_mul(y, y, mM, prec); /* (m/M) A₂ */
    arb_mul(&T->a2[2][2], y, x, prec);
    arb_neg(&T->a2[2][2], &T->a2[2][2]); /* −(m/M) A₂ cos ψ c² */
    arb_neg(&T->a2[3][3], &T->a2[2][2]); /* +(m/M) A₂ cos ψ s² */
    gb_proof_ball_of(x, forcing->psi, prec);
    arb_sin(x, x, prec);
    arb_mul(&T->a2[2][3], y, x, prec);
    arb_mul_2exp_si(&T->a2[2][3], &T->a2[2][3], 1); /* +2 (m/M) A₂ sin ψ c s */
    *J = (jets){.def = def, .lo = NAN, .hi = NAN, .order = -1}; /* one contact; the caller may choose a branch */
    T->jet = h_prime, T->context = J;
    arb_clear(mM), arb_clear(x), arb_clear(y);
}

static int check_all(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing, const gb_proof_interval box[2],
                     int order)
{
    const int status = check_forcing(forcing, order, box);
    if (status) return status;
    return gb_proof_check_precision(def->precision);
}

/* The message of a failed integration, with the jets' reason when one failed (a failure the step's halving cured is no
 * failure). */
static int failure(int status, const jets *J, const char *what)
{
    if (status && J->failed)
        return gb_error_set(GB_ENUMERIC, "the reduced field's %s: %s (%s)", what, J->why, gb_error_message());
    return status;
}

int gb_proof_body_flow(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing,
                       const gb_proof_interval box[2], double t0, double t, int order, gb_proof_interval image[2])
{
    int status = check_all(def, forcing, box, order);
    if (!status && !(t > 0.0 && t <= 100.0))
        status = gb_error_set(GB_EDOM, "t = %g is out of range (allowed: 0 < t <= 100, a multiple of 2^-30)", t);
    if (!status && !isfinite(t0)) status = gb_error_set(GB_EDOM, "t0 = %g is not finite (allowed: a finite time)", t0);
    if (status) return status;
    const slong prec = def->precision;
    field_balls F;
    jets J;
    reduced_field(def, forcing, order, &J, &F);
    arb_t x, y;
    arb_init(x), arb_init(y);
    gb_proof_interval start[4] = {box[0], box[1], {0, 0}, {0, 0}}, end[4];
    arb_set_d(x, forcing->omega);
    arb_set_d(y, t0);
    arb_mul(x, x, y, prec);
    arb_sin_cos(y, x, x, prec);
    start[2] = gb_proof_interval_of(x), start[3] = gb_proof_interval_of(y);
    arb_clear(x), arb_clear(y);
    const gb_proof_field shape = {.dimension = 4};
    gb_proof_flow_def fdef = gb_proof_flow_def_default(&shape);
    fdef.order = order, fdef.precision = prec, fdef.step_max = 0.05;
    status = failure(gb_proof_flow_time_of(&F, &fdef, start, t, end), &J, "flow");
    if (!status) image[0] = end[0], image[1] = end[1];
    gb_proof_flow_field_clear(&F);
    return status;
}

int gb_proof_body_period_map(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing,
                             const gb_proof_interval box[2], int periods, int order, int derivative,
                             gb_proof_body_return *out)
{
    memset(out, 0, sizeof *out);
    int status = check_all(def, forcing, box, order);
    if (!status && !(periods >= 1 && periods <= 16))
        status = gb_error_set(GB_EDOM, "periods = %d is out of range (allowed: 1 to 16)", periods);
    if (status) return status;
    field_balls F;
    jets J;
    reduced_field(def, forcing, order, &J, &F);
    const gb_proof_interval start[4] = {box[0], box[1], {1.0, 1.0}, {0.0, 0.0}};
    const gb_proof_field shape = {.dimension = 4};
    gb_proof_flow_def fdef = gb_proof_flow_def_default(&shape);
    fdef.order = order, fdef.precision = def->precision, fdef.step_max = 0.05;
    fdef.coordinate = 3, fdef.direction = 1, fdef.returns = periods, fdef.derivative = derivative != 0;
    fdef.time_max = 100.0;
    gb_proof_flow_crossing C;
    status = failure(gb_proof_flow_section_map_of(&F, &fdef, start, &C), &J, "period map");
    if (!status) {
        out->q = C.image[0], out->P = C.image[1], out->time = C.time, out->steps = C.steps, out->seconds = C.seconds;
        for (int a = 0; a < 2 && derivative; a++)
            for (int b = 0; b < 2; b++) out->jacobian[a][b] = C.jacobian[a][b];
    }
    gb_proof_flow_field_clear(&F);
    return status;
}

/* The section at the tie: phase 1's crossing of q = q_s (the branch below), then phase 2 from it (the branch above) to
 * the period's end. */
int gb_proof_body_period_map_tie(const gb_proof_body_def *def, const gb_proof_body_forcing *forcing,
                                 const gb_proof_interval box[2], const gb_proof_body_tie *tie, int order,
                                 gb_proof_body_return *out)
{
    memset(out, 0, sizeof *out);
    int status = check_all(def, forcing, box, order);
    if (!status && !(tie->proved && tie->q.lo <= tie->q.hi && tie->jump.hi < INFINITY && box[0].hi < tie->q.lo && box[1].lo > 0.0))
        status = gb_error_set(GB_EDOM, "the box must lie below a proved tie and move up (allowed: q_hi < the tie's q, q' > 0)");
    if (status) return status;
    const slong prec = def->precision;
    const double q_s = 0.5 * tie->q.lo + 0.5 * tie->q.hi, delta = fmax(q_s - tie->q.lo, tie->q.hi - q_s);
    const gb_proof_field shape = {.dimension = 4};
    gb_proof_flow_def fdef = gb_proof_flow_def_default(&shape);
    fdef.order = order, fdef.precision = prec, fdef.step_max = 0.01, fdef.direction = 1, fdef.returns = 1;
    field_balls F;
    jets J;
    gb_proof_flow_crossing C1 = {0}, C2 = {0};
    arb_t x, y, z;
    arb_init(x), arb_init(y), arb_init(z);
    /* phase 1: the branch below the tie, in x = q − q_a, to x = 0, q_a = q_s − η below the tie by more than its
     * enclosure's width; then the sliver [q_a, q_b] (q_b = q_s + η) crossed with H′ bounded by both branches'; then
     * phase 2 from q_b on the branch above */
    const double eta = 1e-7, q_a = q_s - eta, q_b = q_s + eta;
    reduced_field(def, forcing, order, &J, &F);
    J.branch = 1, J.q_s = q_s, J.shift = q_a, J.above = 0;
    gb_proof_interval start[4] = {box[0], box[1], {1.0, 1.0}, {0.0, 0.0}};
    gb_proof_ball_of(x, box[0], prec);
    arb_set_d(y, q_a);
    arb_sub(x, x, y, prec);
    start[0] = gb_proof_interval_of(x);
    fdef.coordinate = 0;
    if (!(delta < 0.01 * eta && box[0].hi < q_a))
        status = gb_error_set(GB_ENUMERIC, "the tie's enclosure (%g wide) or the box is too close to the sliver", 2 * delta);
    if (!status) status = failure(gb_proof_flow_section_map_of(&F, &fdef, start, &C1), &J, "flow to the tie");
    gb_proof_flow_field_clear(&F);
    /* within the period, moving up */
    arb_const_pi(z, prec);
    arb_mul_2exp_si(z, z, 1);
    arb_set_d(y, forcing->omega);
    arb_div(z, z, y, prec); /* T = 2π/ω */
    gb_proof_interval T = gb_proof_interval_of(z);
    if (!status && !(C1.time.hi < T.lo && C1.image[1].lo > 0.0))
        status = gb_error_set(GB_ENUMERIC, "the tie is not crossed moving up within the period (t in [%g, %g], q' in [%g, %g])",
                              C1.time.lo, C1.time.hi, C1.image[1].lo, C1.image[1].hi);
    gb_proof_interval again[4], sliver_time = {0, 0};
    if (!status) {
        /* the sliver: H′ is one of the two branches' at every q of it (the tie lies inside), so |q″| ≤ (m/M) max|a|
         * max|H′| + μ max|q′| while q′ stays in its guess G, which it does since it moves by less than G's margin in the
         * crossing's longest time (q_b − q_a)/G.lo; |(cos, sin)′| ≤ ω */
        gb_proof_body_jet both[2];
        status = gb_proof_body_jet_components(def, q_a, q_b, 1, both);
        const gb_proof_body_jet A = both[0], B = both[1];
        if (!status) {
            const double Hp = fmax(fmax(fabs(A.H[1].lo), fabs(A.H[1].hi)), fmax(fabs(B.H[1].lo), fabs(B.H[1].hi)));
            const double amax = def->g + fabs(forcing->A1) + fabs(forcing->A2);
            const gb_proof_interval P0 = C1.image[1];
            const gb_proof_interval G = {0.9 * P0.lo, 1.1 * P0.hi};
            const double width = q_b - q_a; /* exact (Sterbenz) */
            const double dt = width / G.lo * (1.0 + 1e-12);
            const double acc = (def->mass / def->inertia.lo * amax * Hp + forcing->damping / def->inertia.lo * G.hi) * (1.0 + 1e-12);
            const double dP = acc * dt, dphase = forcing->omega * dt * (1.0 + 1e-12);
            if (!(P0.lo - dP > G.lo && P0.hi + dP < G.hi))
                status = gb_error_set(GB_ENUMERIC, "the tie's sliver is not crossed within the guess of q'");
            again[0] = (gb_proof_interval){0.0, 0.0}, again[1] = (gb_proof_interval){P0.lo - dP, P0.hi + dP};
            again[2] = (gb_proof_interval){C1.image[2].lo - dphase, C1.image[2].hi + dphase};
            again[3] = (gb_proof_interval){C1.image[3].lo - dphase, C1.image[3].hi + dphase};
            sliver_time = (gb_proof_interval){width / G.hi * (1.0 - 1e-12), dt};
        }
    }
    if (!status) {
        /* phase 2: the branch above the tie, from q_b to the period's end (the upward crossing of sin ωt = 0) */
        reduced_field(def, forcing, order, &J, &F);
        J.branch = 1, J.q_s = q_s, J.shift = q_b, J.above = 1;
        fdef.coordinate = 3;
        if (again[3].lo <= 0.0 && again[3].hi >= 0.0)
            status = gb_error_set(GB_ENUMERIC, "the tie is crossed at the period's end (sin wt in [%g, %g])", again[3].lo, again[3].hi);
        if (!status) status = failure(gb_proof_flow_section_map_of(&F, &fdef, again, &C2), &J, "flow from the tie");
        gb_proof_flow_field_clear(&F);
    }
    if (!status) {
        gb_proof_ball_of(x, C2.image[0], prec);
        arb_set_d(y, q_b);
        arb_add(x, x, y, prec);
        out->q = gb_proof_interval_of(x), out->P = C2.image[1];
        gb_proof_ball_of(x, C1.time, prec), gb_proof_ball_of(y, C2.time, prec);
        arb_add(x, x, y, prec);
        gb_proof_ball_of(y, sliver_time, prec);
        arb_add(x, x, y, prec);
        out->time = gb_proof_interval_of(x);
        out->steps = C1.steps + C2.steps, out->seconds = C1.seconds + C2.seconds;
    }
    arb_clear(x), arb_clear(y), arb_clear(z);
    return status;
}
