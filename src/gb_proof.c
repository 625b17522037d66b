#include "gb_proof.h"

#include "gb_error.h"
#include "gb_proof_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <time.h>

#include <acb.h>
#include <flint/flint.h>
#include <acb_calc.h>
#include <arb.h>

/* Why Arb and no code of our own: its balls carry a proven radius through every operation, its elementary functions
 * (sech, tanh, cos of a complex ball) have proven error bounds, and its quadrature (acb_calc_integrate: Gauss–Legendre
 * on subintervals, the error bounded through the integrand's analytic continuation on ellipses) is the published
 * rigorous method (Johansson 2018). gb_interval.h, the certificate's fast arithmetic, has none of these. */

double gb_proof_cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t); /* the thread's: proofs may run side by side (gomboc prove) */
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void gb_proof_thread_done(void) { flint_cleanup(); }

const char *gb_proof_system_name(gb_proof_system s)
{
    return s == GB_PROOF_PENDULUM ? "pendulum" : s == GB_PROOF_DUFFING ? "Duffing" : NULL;
}

const char *gb_proof_verdict_name(gb_proof_verdict v)
{
    static const char *const names[] = {"simple zeros proved", "no zero proved", "undecided"};
    return (unsigned)v < 3 ? names[v] : NULL;
}

void gb_proof_mul_d(arb_t out, const arb_t x, double d, slong prec)
{
    arb_t t;
    arb_init(t);
    arb_set_d(t, d);
    arb_mul(out, x, t, prec);
    arb_clear(t);
}

gb_proof_interval gb_proof_interval_of(const arb_t x)
{
    arf_t lo, hi;
    arf_init(lo), arf_init(hi);
    arb_get_lbound_arf(lo, x, 64);
    arb_get_ubound_arf(hi, x, 64);
    const gb_proof_interval out = {arf_get_d(lo, ARF_RND_FLOOR), arf_get_d(hi, ARF_RND_CEIL)};
    arf_clear(lo), arf_clear(hi);
    return out;
}

gb_proof_interval gb_proof_half(gb_proof_interval x, int upper)
{
    const double middle = 0.5 * (x.lo + x.hi);
    return upper ? (gb_proof_interval){middle, x.hi} : (gb_proof_interval){x.lo, middle};
}

int gb_proof_halvable(gb_proof_interval x)
{
    const double middle = 0.5 * (x.lo + x.hi);
    return middle > x.lo && middle < x.hi;
}

void gb_proof_ball_of(arb_t out, gb_proof_interval x, slong prec)
{
    arf_t lo, hi;
    arf_init(lo), arf_init(hi);
    arf_set_d(lo, x.lo), arf_set_d(hi, x.hi);
    arb_set_interval_arf(out, lo, hi, prec);
    arf_clear(lo), arf_clear(hi);
}

int gb_proof_check_precision(long precision)
{
    if (precision < GB_PROOF_PRECISION_MIN || precision > GB_PROOF_PRECISION_MAX)
        return gb_error_set(GB_EDOM, "precision = %ld bits is out of range (allowed: %d to %d)", precision,
                            GB_PROOF_PRECISION_MIN, GB_PROOF_PRECISION_MAX);
    return GB_OK;
}

/* ---- the oracles' integrals --------------------------------------------------------------------------------- */

/* What an integrand evaluates: p_h(t)² (which 0), or p_h(t) cos(Ωt) (1), or p_h(t) sin(Ωt) (2). */
typedef struct integrand {
    gb_proof_system system;
    int which;
    const arb_struct *frequency; /* Ω */
} integrand;

/* p_h at the complex ball t: 2 sech t (pendulum), −√2 sech t tanh t (Duffing). Meromorphic: Arb's sech and tanh of a
 * ball that holds a pole are not finite, which the quadrature sees and subdivides (order 1 needs no other check). */
static void momentum(acb_t out, const acb_t t, gb_proof_system system, slong prec)
{
    acb_sech(out, t, prec);
    if (system == GB_PROOF_PENDULUM) {
        acb_mul_2exp_si(out, out, 1);
    } else {
        acb_t th;
        arb_t r2;
        acb_init(th), arb_init(r2);
        acb_tanh(th, t, prec);
        acb_mul(out, out, th, prec);
        arb_sqrt_ui(r2, 2, prec);
        acb_mul_arb(out, out, r2, prec);
        acb_neg(out, out);
        acb_clear(th), arb_clear(r2);
    }
}

static int evaluate(acb_ptr out, const acb_t t, void *param, slong order, slong prec)
{
    const integrand *f = param;
    if (order > 1) flint_abort(); /* acb_calc_integrate asks for values (0) or values with holomorphy (1) only */
    momentum(out, t, f->system, prec);
    if (f->which == 0) {
        acb_sqr(out, out, prec);
        return 0;
    }
    acb_t wt, trig;
    acb_init(wt), acb_init(trig);
    acb_mul_arb(wt, t, f->frequency, prec);
    if (f->which == 1) acb_cos(trig, wt, prec);
    else acb_sin(trig, wt, prec);
    acb_mul(out, out, trig, prec);
    acb_clear(wt), acb_clear(trig);
    return 0;
}

/* ∫ over [−T, T] rigorously, plus the two tails as an error: |p_h| ≤ c e^{−|t|} (sech t ≤ 2 e^{−|t|}, |tanh| ≤ 1;
 * c = 4 for the pendulum, 2√2 < 3 for Duffing), so a tail of p_h² is at most c² e^{−2T}/2 and one of p_h times a
 * cosine or a sine at most c e^{−T}. */
static int integral(arb_t out, gb_proof_system system, int which, const arb_t frequency, double T, slong prec)
{
    integrand f = {system, which, frequency};
    acb_t a, b, res;
    acb_init(a), acb_init(b), acb_init(res);
    acb_set_d(a, -T), acb_set_d(b, T);
    mag_t tol;
    mag_init(tol);
    mag_set_ui_2exp_si(tol, 1, -prec);
    acb_calc_integrate_opt_t options;
    acb_calc_integrate_opt_init(options);
    options->eval_limit = 100000000;
    acb_calc_integrate(res, evaluate, &f, a, b, prec, tol, options, prec);
    const double c = system == GB_PROOF_PENDULUM ? 4.0 : 3.0;
    arb_t tail;
    arb_init(tail);
    arb_set_d(tail, which == 0 ? -2.0 * T : -T);
    arb_exp(tail, tail, prec);
    gb_proof_mul_d(tail, tail, which == 0 ? c * c : 2.0 * c, prec); /* both tails */
    arb_set(out, acb_realref(res));
    /* the imaginary part of the enclosure is an enclosure of 0: its radius adds nothing to the real part's */
    arb_add_error(out, tail);
    /* a finite enclosure 40 bits good, relative or (an integral that is 0 by parity) absolute: a failed quadrature's
     * wide ball would otherwise meet any closed form */
    const int ok = arb_is_finite(out) && (arb_rel_accuracy_bits(out) > 40 || mag_cmp_2exp_si(arb_radref(out), -40) <= 0);
    acb_clear(a), acb_clear(b), acb_clear(res), arb_clear(tail), mag_clear(tol);
    return ok ? GB_OK : gb_error_set(GB_ENUMERIC, "Arb's quadrature of the %s's integral %d did not reach 40 bits",
                                     gb_proof_system_name(system), which);
}

/* The closed forms: pendulum ∫ p² = 8, ∫ p cos Ωt = 2π sech(πΩ/2), ∫ p sin Ωt = 0; Duffing ∫ p² = 4/3,
 * ∫ p cos Ωt = 0, ∫ p sin Ωt = −√2 π Ω sech(πΩ/2). */
static void closed_form(arb_t out, gb_proof_system system, int which, const arb_t frequency, slong prec)
{
    if (which == 0) {
        arb_set_ui(out, system == GB_PROOF_PENDULUM ? 8 : 4);
        if (system == GB_PROOF_DUFFING) arb_div_ui(out, out, 3, prec);
        return;
    }
    if ((system == GB_PROOF_PENDULUM) != (which == 1)) {
        arb_zero(out);
        return;
    }
    arb_t pi, x;
    arb_init(pi), arb_init(x);
    arb_const_pi(pi, prec);
    arb_mul(x, pi, frequency, prec);
    arb_mul_2exp_si(x, x, -1);
    arb_sech(out, x, prec);
    arb_mul(out, out, pi, prec);
    if (system == GB_PROOF_PENDULUM) {
        arb_mul_2exp_si(out, out, 1);
    } else {
        arb_sqrt_ui(x, 2, prec);
        arb_mul(out, out, x, prec);
        arb_mul(out, out, frequency, prec);
        arb_neg(out, out);
    }
    arb_clear(pi), arb_clear(x);
}

int gb_proof_oracle_integrals(gb_proof_system system, double omega, long precision, gb_proof_integrals *out)
{
    memset(out, 0, sizeof *out);
    if (!gb_proof_system_name(system)) return gb_error_set(GB_EDOM, "system %d is unknown (allowed: pendulum, Duffing)", (int)system);
    if (!(omega > 0.0 && omega <= 64.0)) return gb_error_set(GB_EDOM, "omega = %g is out of range (allowed: 0 < omega <= 64)", omega);
    int status = gb_proof_check_precision(precision);
    if (status) return status;
    const double start = gb_proof_cpu_seconds();
    out->system = system, out->omega = omega, out->precision = precision;
    /* e^{−T} = 2^{−precision−8}: the tails below the quadrature's own target */
    const double T = ((double)precision + 8.0) * M_LN2;
    out->horizon = T;
    arb_t frequency, value, closed;
    arb_init(frequency), arb_init(value), arb_init(closed);
    gb_proof_interval *slots[5] = {&out->D, &out->C1, &out->S1, &out->C2, &out->S2};
    out->consistent = 1;
    for (int k = 0; k < 5 && !status; k++) {
        const int which = k == 0 ? 0 : (k - 1) % 2 + 1, harmonic = k <= 2 ? 1 : 2;
        arb_set_d(frequency, omega);
        arb_mul_ui(frequency, frequency, (ulong)harmonic, precision);
        status = integral(value, system, which, frequency, T, precision);
        closed_form(closed, system, which, frequency, precision);
        *slots[k] = gb_proof_interval_of(value);
        out->closed[k] = gb_proof_interval_of(closed);
        out->consistent = out->consistent && arb_overlaps(value, closed);
    }
    arb_clear(frequency), arb_clear(value), arb_clear(closed);
    out->seconds = gb_proof_cpu_seconds() - start;
    return status;
}

/* ---- the zeros of M(t₀) ----------------------------------------------------------------------------------- */

/* M(s) = a0 + a1 cos s + b1 sin s + a2 cos 2s + b2 sin 2s (s = ωt₀) and M′(s) = dM/ds, at the ball s. */
typedef struct trig {
    arb_t a0, a1, b1, a2, b2;
} trig;

static void trig_eval(arb_t M, arb_t dM, const trig *m, const arb_t s, slong prec)
{
    arb_t c1, s1, c2, s2, s2x, t;
    arb_init(c1), arb_init(s1), arb_init(c2), arb_init(s2), arb_init(s2x), arb_init(t);
    arb_sin_cos(s1, c1, s, prec);
    arb_mul_2exp_si(s2x, s, 1);
    arb_sin_cos(s2, c2, s2x, prec);
    if (M) {
        arb_set(M, m->a0);
        arb_addmul(M, m->a1, c1, prec);
        arb_addmul(M, m->b1, s1, prec);
        arb_addmul(M, m->a2, c2, prec);
        arb_addmul(M, m->b2, s2, prec);
    }
    if (dM) {
        arb_mul(dM, m->b1, c1, prec);
        arb_submul(dM, m->a1, s1, prec);
        arb_mul(t, m->b2, c2, prec);
        arb_submul(t, m->a2, s2, prec);
        arb_mul_2exp_si(t, t, 1);
        arb_add(dM, dM, t, prec);
    }
    arb_clear(c1), arb_clear(s1), arb_clear(c2), arb_clear(s2), arb_clear(s2x), arb_clear(t);
}

/* A piece of the period decided on its own: M bounded away from 0 on it, or M monotone on it (M′ bounded away from 0,
 * its sign in `rising`; the piece's ends kept), or undecided at the deepest halving. */
enum { LEAF_NO_ZERO = 0, LEAF_MONOTONE = 1, LEAF_UNDECIDED = 2 };
typedef struct leaf {
    int kind, rising;
    double slope;      /* a lower bound of |dM/dt₀| on a monotone piece */
    arb_struct lo, hi; /* a monotone piece's ends */
} leaf;

typedef struct search {
    const trig *m;
    slong prec;
    int depth;
    gb_proof_zeros *out;
    double omega;
    leaf *leaves;      /* in the order of s over the period */
    size_t n, cap;
    int failed;        /* out of memory */
} search;

/* The ball [lo, hi] of s (the endpoints given as balls: multiples of 2π/2^k are not doubles). */
static void span(arb_t s, const arb_t lo, const arb_t hi, slong prec)
{
    arb_union(s, lo, hi, prec);
}

/* *least = min(*least, a lower bound of |x| scale) (scale > 0), rounded down. */
static void lower_abs(double *least, const arb_t x, double scale, slong prec)
{
    arb_t a;
    arb_init(a);
    arb_abs(a, x);
    gb_proof_mul_d(a, a, scale, prec);
    arf_t b;
    arf_init(b);
    arb_get_lbound_arf(b, a, prec);
    const double bound = arf_get_d(b, ARF_RND_FLOOR);
    if (bound < *least) *least = bound;
    arf_clear(b), arb_clear(a);
}

static void push_leaf(search *S, int kind, int rising, double slope, const arb_t lo, const arb_t hi)
{
    if (S->n == S->cap) {
        const size_t cap = S->cap ? 2 * S->cap : 256;
        leaf *at = realloc(S->leaves, cap * sizeof *at);
        if (!at) {
            S->failed = 1;
            return;
        }
        S->leaves = at, S->cap = cap;
    }
    leaf *l = &S->leaves[S->n++];
    l->kind = kind, l->rising = rising, l->slope = slope;
    arb_init(&l->lo), arb_init(&l->hi);
    if (kind == LEAF_MONOTONE) arb_set(&l->lo, lo), arb_set(&l->hi, hi);
}

/* Classify [lo, hi]: M bounded away from 0 by the mean value form, or M′ bounded away from 0 (monotone), or halve. The
 * zeros are decided afterwards on runs of adjacent monotone pieces (a zero's band of uncertain sign may be wider than
 * any piece on which M′ is bounded away from 0; a run can span it). */
static void decide(search *S, const arb_t lo, const arb_t hi, int level)
{
    const slong prec = S->prec;
    arb_t s, mid, M, dM, w;
    arb_init(s), arb_init(mid), arb_init(M), arb_init(dM), arb_init(w);
    S->out->boxes++;
    span(s, lo, hi, prec);
    arb_add(mid, lo, hi, prec);
    arb_mul_2exp_si(mid, mid, -1);
    trig_eval(NULL, dM, S->m, s, prec);
    trig_eval(M, NULL, S->m, mid, prec);
    arb_sub(w, s, mid, prec); /* M(s) ⊂ M(mid) + M′(s)(s − mid) */
    arb_addmul(M, dM, w, prec);
    if (!arb_contains_zero(M)) {
        lower_abs(&S->out->margin, M, 1.0, prec);
        push_leaf(S, LEAF_NO_ZERO, 0, 0.0, lo, hi);
    } else if (!arb_contains_zero(dM)) {
        double slope = INFINITY;
        lower_abs(&slope, dM, S->omega, prec); /* dM/dt₀ = ω dM/ds */
        push_leaf(S, LEAF_MONOTONE, arb_is_positive(dM), slope, lo, hi);
    } else if (level >= S->depth) {
        S->out->undecided++;
        push_leaf(S, LEAF_UNDECIDED, 0, 0.0, lo, hi);
    } else {
        decide(S, lo, mid, level + 1);
        decide(S, mid, hi, level + 1);
    }
    arb_clear(s), arb_clear(mid), arb_clear(M), arb_clear(dM), arb_clear(w);
}

/* A run of adjacent monotone pieces [a, b] (b may pass 2π): M is monotone on it, so strict signs of opposite kinds at its
 * ends prove exactly one zero there, simple (|M′| bounded below); strict signs alike prove none (and |M| ≥ the smaller
 * end's); an end whose sign is not proved leaves the run undecided. */
static void decide_run(search *S, const arb_t a, const arb_t b, int rising, double slope)
{
    const slong prec = S->prec;
    arb_t Ma, Mb, lo, hi, c, Mc, t;
    arb_init(Ma), arb_init(Mb), arb_init(lo), arb_init(hi), arb_init(c), arb_init(Mc), arb_init(t);
    trig_eval(Ma, NULL, S->m, a, prec);
    trig_eval(Mb, NULL, S->m, b, prec);
    if (arb_contains_zero(Ma) || arb_contains_zero(Mb)) {
        S->out->undecided++;
    } else if (arb_is_positive(Ma) == arb_is_positive(Mb)) {
        lower_abs(&S->out->margin, Ma, 1.0, prec);
        lower_abs(&S->out->margin, Mb, 1.0, prec);
    } else {
        if (S->out->zeros < GB_PROOF_ZEROS_MAX) {
            /* narrowed by halving while the middle's sign is proved (the zero is unique in the run) */
            arb_set(lo, a), arb_set(hi, b);
            for (int k = 0; k < 60; k++) {
                arb_add(c, lo, hi, prec);
                arb_mul_2exp_si(c, c, -1);
                trig_eval(Mc, NULL, S->m, c, prec);
                if (arb_contains_zero(Mc)) break;
                if (arb_is_positive(Mc) == rising) arb_set(hi, c);
                else arb_set(lo, c);
            }
            span(c, lo, hi, prec);
            arb_set_d(t, S->omega);
            arb_div(c, c, t, prec);
            S->out->where[S->out->zeros] = gb_proof_interval_of(c);
        } else {
            S->out->undecided++;
        }
        S->out->zeros++;
        if (slope < S->out->slope_min) S->out->slope_min = slope;
    }
    arb_clear(Ma), arb_clear(Mb), arb_clear(lo), arb_clear(hi), arb_clear(c), arb_clear(Mc), arb_clear(t);
}

/* The runs of the period's pieces, the one across s = 2π ≡ 0 joined. */
static void decide_runs(search *S, const arb_t two_pi)
{
    const size_t n = S->n;
    if (n == 0) return;
    const leaf *L = S->leaves;
    /* start where a run cannot continue from the piece before (across the period's end) */
    size_t start = 0;
    while (start < n && L[start].kind == LEAF_MONOTONE && L[(start + n - 1) % n].kind == LEAF_MONOTONE &&
           L[(start + n - 1) % n].rising == L[start].rising)
        start++;
    if (start == n) { /* M′ of one sign over a whole period: impossible for a periodic M; the enclosure decides nothing */
        S->out->undecided++;
        return;
    }
    arb_t a, b;
    arb_init(a), arb_init(b);
    for (size_t i = 0; i < n;) {
        const size_t k = (start + i) % n;
        if (L[k].kind != LEAF_MONOTONE) {
            i++;
            continue;
        }
        size_t j = i;
        double slope = INFINITY;
        while (j < n && L[(start + j) % n].kind == LEAF_MONOTONE && L[(start + j) % n].rising == L[k].rising) {
            slope = fmin(slope, L[(start + j) % n].slope);
            j++;
        }
        const size_t last = (start + j - 1) % n;
        arb_set(a, &L[k].lo);
        arb_set(b, &L[last].hi);
        if (last < k) arb_add(b, b, two_pi, S->prec); /* the run passes s = 2π */
        decide_run(S, a, b, L[k].rising, slope);
        i = j;
    }
    arb_clear(a), arb_clear(b);
}

int gb_proof_melnikov_zeros(const gb_proof_melnikov *def, gb_proof_zeros *out)
{
    memset(out, 0, sizeof *out);
    int status = gb_proof_check_precision(def->precision);
    if (status) return status;
    if (def->depth < 1 || def->depth > 40) return gb_error_set(GB_EDOM, "depth = %d is out of range (allowed: 1 to 40)", def->depth);
    if (!(def->omega > 0.0 && isfinite(def->omega))) return gb_error_set(GB_EDOM, "omega = %g is out of range (allowed: > 0)", def->omega);
    if (!(def->mu >= 0.0 && isfinite(def->mu) && isfinite(def->nu1) && isfinite(def->nu2)))
        return gb_error_set(GB_EDOM, "mu = %g, nu1 = %g, nu2 = %g (allowed: mu >= 0, all finite)", def->mu, def->nu1, def->nu2);
    const gb_proof_interval in[6] = {def->D, def->C1, def->S1, def->C2, def->S2, def->psi};
    for (int k = 0; k < 6; k++)
        if (!(in[k].lo <= in[k].hi) || !isfinite(in[k].lo) || !isfinite(in[k].hi))
            return gb_error_set(GB_EDOM, "interval %d of the integrals and the phase is [%g, %g] (allowed: finite, lo <= hi)", k,
                                in[k].lo, in[k].hi);
    const double start = gb_proof_cpu_seconds();
    const slong prec = def->precision;
    trig m;
    arb_init(m.a0), arb_init(m.a1), arb_init(m.b1), arb_init(m.a2), arb_init(m.b2);
    arb_t x, c, sn, psi, C2, S2, lo, hi, two_pi;
    arb_init(x), arb_init(c), arb_init(sn), arb_init(psi), arb_init(C2), arb_init(S2), arb_init(lo), arb_init(hi), arb_init(two_pi);
    /* a0 = −μD; a1 = ν₁C₁; b1 = −ν₁S₁; cos(2s + ψ) and sin(2s + ψ) expanded: a2 = ν₂(C₂ cos ψ − S₂ sin ψ),
     * b2 = −ν₂(C₂ sin ψ + S₂ cos ψ) */
    gb_proof_ball_of(x, def->D, prec), gb_proof_mul_d(m.a0, x, -def->mu, prec);
    gb_proof_ball_of(x, def->C1, prec), gb_proof_mul_d(m.a1, x, def->nu1, prec);
    gb_proof_ball_of(x, def->S1, prec), gb_proof_mul_d(m.b1, x, -def->nu1, prec);
    gb_proof_ball_of(psi, def->psi, prec), gb_proof_ball_of(C2, def->C2, prec), gb_proof_ball_of(S2, def->S2, prec);
    arb_sin_cos(sn, c, psi, prec);
    arb_mul(m.a2, C2, c, prec), arb_submul(m.a2, S2, sn, prec), gb_proof_mul_d(m.a2, m.a2, def->nu2, prec);
    arb_mul(m.b2, C2, sn, prec), arb_addmul(m.b2, S2, c, prec), gb_proof_mul_d(m.b2, m.b2, -def->nu2, prec);
    out->margin = INFINITY, out->slope_min = INFINITY;
    search S = {.m = &m, .prec = prec, .depth = def->depth, .out = out, .omega = def->omega};
    /* the period in 64 pieces first (their ends multiples of 2π/64, as balls), each decided or halved */
    arb_const_pi(two_pi, prec);
    arb_mul_2exp_si(two_pi, two_pi, 1);
    enum { PIECES = 64 };
    for (int k = 0; k < PIECES; k++) {
        arb_mul_ui(lo, two_pi, (ulong)k, prec), arb_div_ui(lo, lo, PIECES, prec);
        arb_mul_ui(hi, two_pi, (ulong)(k + 1), prec), arb_div_ui(hi, hi, PIECES, prec);
        decide(&S, lo, hi, 0);
    }
    /* A zero exactly at a run's end makes M(end) ∋ 0: undecided there, never miscounted. */
    if (!S.failed) decide_runs(&S, two_pi);
    for (size_t k = 0; k < S.n; k++) arb_clear(&S.leaves[k].lo), arb_clear(&S.leaves[k].hi);
    free(S.leaves);
    if (S.failed) status = gb_error_set(GB_ENOMEM, "out of memory for the pieces of the period");
    out->verdict = out->undecided ? GB_PROOF_UNDECIDED : out->zeros ? GB_PROOF_SIMPLE_ZEROS : GB_PROOF_NO_ZERO;
    if (out->verdict == GB_PROOF_NO_ZERO && !status) {
        /* the margin again on 4096 equal pieces (a sharper lower bound of |M| than the coarse pieces' that decided it) */
        enum { FINE = 4096 };
        double margin = INFINITY;
        arb_t s, mid, M, dM, w;
        arb_init(s), arb_init(mid), arb_init(M), arb_init(dM), arb_init(w);
        for (int k = 0; k < FINE && margin > 0.0; k++) {
            arb_mul_ui(lo, two_pi, (ulong)k, prec), arb_div_ui(lo, lo, FINE, prec);
            arb_mul_ui(hi, two_pi, (ulong)(k + 1), prec), arb_div_ui(hi, hi, FINE, prec);
            span(s, lo, hi, prec);
            arb_add(mid, lo, hi, prec);
            arb_mul_2exp_si(mid, mid, -1);
            trig_eval(NULL, dM, &m, s, prec);
            trig_eval(M, NULL, &m, mid, prec);
            arb_sub(w, s, mid, prec);
            arb_addmul(M, dM, w, prec);
            if (arb_contains_zero(M)) margin = 0.0;
            else lower_abs(&margin, M, 1.0, prec);
        }
        if (margin > out->margin) out->margin = margin;
        arb_clear(s), arb_clear(mid), arb_clear(M), arb_clear(dM), arb_clear(w);
    }
    if (out->verdict != GB_PROOF_NO_ZERO) out->margin = NAN;
    if (out->verdict != GB_PROOF_SIMPLE_ZEROS) out->slope_min = NAN;
    arb_clear(m.a0), arb_clear(m.a1), arb_clear(m.b1), arb_clear(m.a2), arb_clear(m.b2);
    arb_clear(x), arb_clear(c), arb_clear(sn), arb_clear(psi), arb_clear(C2), arb_clear(S2), arb_clear(lo), arb_clear(hi);
    arb_clear(two_pi);
    out->seconds = gb_proof_cpu_seconds() - start;
    return status;
}

int gb_proof_pi_fraction(long num, long den, gb_proof_interval *out)
{
    if (den < 1 || den > 1000000 || num < -1000000 || num > 1000000)
        return gb_error_set(GB_EDOM, "pi %ld/%ld (allowed: 1 <= den <= 1e6, |num| <= 1e6)", num, den);
    arb_t x;
    arb_init(x);
    arb_const_pi(x, 128);
    arb_mul_si(x, x, num, 128);
    arb_div_si(x, x, den, 128);
    *out = gb_proof_interval_of(x);
    arb_clear(x);
    return GB_OK;
}

/* ---- gb_interval.h's reference -------------------------------------------------------------------------------- */

int gb_proof_encloses(const char *operation, double x, double y, double lo, double hi, int *holds)
{
    static const char *const names[] = {"add", "sub", "mul", "recip", "sqrt", "sin", "cos", "root4"};
    *holds = -1;
    int op = -1;
    for (int k = 0; k < 8; k++)
        if (operation && !strcmp(operation, names[k])) op = k;
    if (op < 0)
        return gb_error_set(GB_EDOM, "operation '%s' is unknown (allowed: add, sub, mul, recip, sqrt, sin, cos, root4)",
                            operation ? operation : "(null)");
    if (!isfinite(x) || !isfinite(y) || !(lo <= hi)) return gb_error_set(GB_EDOM, "x = %g, y = %g, [%g, %g] (allowed: finite, lo <= hi)", x, y, lo, hi);
    if ((op == 3 && x == 0.0) || ((op == 4 || op == 7) && x < 0.0))
        return gb_error_set(GB_EDOM, "%s of %g is outside its domain", operation, x);
    arb_t a, b, range;
    arb_init(a), arb_init(b), arb_init(range);
    gb_proof_ball_of(range, (gb_proof_interval){lo, hi}, 64);
    for (slong prec = 256; prec <= 4096 && *holds < 0; prec *= 2) {
        arb_set_d(a, x), arb_set_d(b, y);
        switch (op) {
        case 0: arb_add(a, a, b, prec); break;
        case 1: arb_sub(a, a, b, prec); break;
        case 2: arb_mul(a, a, b, prec); break;
        case 3: arb_inv(a, a, prec); break;
        case 4: arb_sqrt(a, a, prec); break;
        case 5: arb_sin(a, a, prec); break;
        case 6: arb_cos(a, a, prec); break;
        default: arb_root_ui(a, a, 4, prec); break;
        }
        if (arb_contains(range, a)) *holds = 1;
        else if (!arb_overlaps(range, a)) *holds = 0;
    }
    arb_clear(a), arb_clear(b), arb_clear(range);
    return GB_OK;
}
