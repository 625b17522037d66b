#include "gb_proof_flow.h"

#include "gb_error.h"
#include "gb_proof_flow_internal.h"
#include "gb_proof_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <arb.h>
#include <arb_mat.h>

/* Why our own integrator on Arb: Arb has balls, power series and matrices with proven bounds but no ODE solver;
 * CAPD, which has one (C++), is not packaged in Debian. The method is the published C⁰ Lohner algorithm (see the
 * header); every bound is Arb's. */



static void rational_ball(arb_t out, gb_proof_rational q, slong prec)
{
    if (!q.den || !q.num) {
        arb_zero(out);
        return;
    }
    arb_set_si(out, q.num);
    arb_div_si(out, out, q.den, prec);
}

void gb_proof_flow_field_init(field_balls *F, const gb_proof_field *f, int order, slong prec)
{
    memset(F, 0, sizeof *F);
    F->n = f->dimension, F->order = order, F->prec = prec;
    gb_proof_flow_term_init(&F->term);
    for (int i = 0; i < NMAX; i++) {
        arb_init(&F->c[i]);
        for (int j = 0; j < NMAX; j++) {
            arb_init(&F->L[i][j]);
            for (int k = 0; k < NMAX; k++) arb_init(&F->Q[i][j][k]);
        }
    }
    for (int i = 0; i < F->n; i++) {
        rational_ball(&F->c[i], f->c[i], prec);
        for (int j = 0; j < F->n; j++) {
            rational_ball(&F->L[i][j], f->L[i][j], prec);
            for (int k = j; k < F->n; k++) {
                rational_ball(&F->Q[i][j][k], f->Q[i][j][k], prec);
                F->has_Q[i][j][k] = !arb_is_zero(&F->Q[i][j][k]);
                F->pair_used[j][k] |= F->has_Q[i][j][k];
            }
        }
    }
}

void gb_proof_flow_field_clear(field_balls *F)
{
    gb_proof_flow_term_clear(&F->term);
    for (int i = 0; i < NMAX; i++) {
        arb_clear(&F->c[i]);
        for (int j = 0; j < NMAX; j++) {
            arb_clear(&F->L[i][j]);
            for (int k = 0; k < NMAX; k++) arb_clear(&F->Q[i][j][k]);
        }
    }
}

/* f(x) over the box x. */
void gb_proof_flow_field_eval(const field_balls *F, arb_srcptr x, arb_ptr out)
{
    arb_t t;
    arb_init(t);
    for (int i = 0; i < F->n; i++) {
        arb_set(out + i, &F->c[i]);
        for (int j = 0; j < F->n; j++) {
            arb_addmul(out + i, &F->L[i][j], x + j, F->prec);
            for (int k = j; k < F->n; k++)
                if (F->has_Q[i][j][k]) {
                    arb_mul(t, x + j, x + k, F->prec);
                    arb_addmul(out + i, &F->Q[i][j][k], t, F->prec);
                }
        }
    }
    if (F->term.row >= 0) gb_proof_flow_term_eval(&F->term, F->n, F->prec, x, out + F->term.row);
    arb_clear(t);
}

/* The Taylor coefficients x_0 … x_order of the solution through every point of the box x0: xs[i (order + 1) + k].
 * The recursion of a quadratic field: (k + 1) x_{k+1} = [k = 0] c + L x_k + Σ Q (x ⋆ x)_k, ⋆ the Cauchy product. */
static void taylor(const field_balls *F, arb_srcptr x0, int order, arb_ptr xs)
{
    const int n = F->n, w = order + 1;
    arb_t acc, conv;
    arb_init(acc), arb_init(conv);
    for (int i = 0; i < n; i++) arb_set(xs + i * w, x0 + i);
    arb_struct products[NMAX][NMAX];
    for (int j = 0; j < n; j++)
        for (int k = 0; k < n; k++) arb_init(&products[j][k]);
    arb_ptr g = F->term.row >= 0 ? _arb_vec_init(order + 1) : NULL;
    if (g) gb_proof_flow_term_jet(&F->term, x0 + F->term.var, order, g);
    for (int k = 0; k < order; k++) {
        for (int j = 0; j < n; j++)
            for (int l = j; l < n; l++) {
                if (!F->pair_used[j][l]) continue;
                arb_zero(&products[j][l]);
                for (int m = 0; m <= k; m++) arb_addmul(&products[j][l], xs + j * w + m, xs + l * w + k - m, F->prec);
            }
        for (int i = 0; i < n; i++) {
            if (k == 0)
                arb_set(acc, &F->c[i]);
            else
                arb_zero(acc);
            for (int j = 0; j < n; j++) {
                if (!arb_is_zero(&F->L[i][j])) arb_addmul(acc, &F->L[i][j], xs + j * w + k, F->prec);
                for (int l = j; l < n; l++)
                    if (F->has_Q[i][j][l]) arb_addmul(acc, &F->Q[i][j][l], &products[j][l], F->prec);
            }
            if (i == F->term.row) {
                gb_proof_flow_term_coefficient(&F->term, F->n, F->prec, xs, w, k, g, conv);
                arb_add(acc, acc, conv, F->prec);
            }
            arb_div_ui(xs + i * w + k + 1, acc, (ulong)(k + 1), F->prec);
        }
    }
    for (int j = 0; j < n; j++)
        for (int k = 0; k < n; k++) arb_clear(&products[j][k]);
    if (g) _arb_vec_clear(g, order + 1);
    arb_clear(acc), arb_clear(conv);
}

/* The variational coefficients V_0 = I, …, V_order (n × n each, V[(k n + a) n + b]) along the series xs: the
 * derivatives of x_k with respect to the initial point, (k + 1) V_{k+1} = Σ_m J_m V_{k−m}, J_m the m-th coefficient
 * of Df along the solution. */
static void variational_from(const field_balls *F, arb_srcptr xs, int order, const arb_mat_t V0, arb_ptr V)
{
    const int n = F->n, w = order + 1, nn = n * n;
    arb_ptr J = _arb_vec_init(order * nn);
    for (int m = 0; m < order; m++)
        for (int a = 0; a < n; a++)
            for (int q = 0; q < n; q++) {
                arb_ptr e = J + m * nn + a * n + q;
                if (m == 0) arb_set(e, &F->L[a][q]);
                for (int l = q; l < n; l++)
                    if (F->has_Q[a][q][l]) arb_addmul(e, &F->Q[a][q][l], xs + l * w + m, F->prec);
                for (int j = 0; j <= q; j++)
                    if (F->has_Q[a][j][q]) arb_addmul(e, &F->Q[a][j][q], xs + j * w + m, F->prec);
            }
    if (F->term.row >= 0 && order > 0) {
        arb_ptr g = _arb_vec_init(order + 1);
        gb_proof_flow_term_jet(&F->term, xs + F->term.var * w, order, g);
        gb_proof_flow_term_jacobian(&F->term, F->n, F->prec, xs, w, order, g, J);
        _arb_vec_clear(g, order + 1);
    }
    _arb_vec_zero(V, w * nn);
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++)
            if (V0) arb_set(V + a * n + b, arb_mat_entry(V0, a, b));
            else if (a == b) arb_one(V + a * n + b);
    arb_t acc;
    arb_init(acc);
    for (int k = 0; k < order; k++)
        for (int a = 0; a < n; a++)
            for (int b = 0; b < n; b++) {
                arb_zero(acc);
                for (int m = 0; m <= k; m++)
                    for (int q = 0; q < n; q++) {
                        arb_srcptr j = J + m * nn + a * n + q;
                        if (!arb_is_zero(j)) arb_addmul(acc, j, V + (k - m) * nn + q * n + b, F->prec);
                    }
                arb_div_ui(V + (k + 1) * nn + a * n + b, acc, (ulong)(k + 1), F->prec);
            }
    arb_clear(acc);
    _arb_vec_clear(J, order * nn);
}

static void variational(const field_balls *F, arb_srcptr xs, int order, arb_ptr V)
{
    variational_from(F, xs, order, NULL, V);
}

void gb_proof_flow_field_derivative(const field_balls *F, arb_srcptr x, arb_mat_t J)
{
    for (int i = 0; i < F->n; i++)
        for (int m = 0; m < F->n; m++) { /* J_im = L_im + Σ_{k ≥ m} Q_imk x_k + Σ_{j ≤ m} Q_ijm x_j */
            arb_ptr e = arb_mat_entry(J, i, m);
            arb_set(e, &F->L[i][m]);
            for (int k = m; k < F->n; k++)
                if (F->has_Q[i][m][k]) arb_addmul(e, &F->Q[i][m][k], x + k, F->prec);
            for (int j = 0; j <= m; j++)
                if (F->has_Q[i][j][m]) arb_addmul(e, &F->Q[i][j][m], x + j, F->prec);
        }
    if (F->term.row >= 0) {
        const int n = F->n;
        arb_ptr g = _arb_vec_init(2), row = _arb_vec_init(n * n);
        gb_proof_flow_term_jet(&F->term, x + F->term.var, 1, g);
        gb_proof_flow_term_jacobian(&F->term, F->n, F->prec, x, 1, 1, g, row);
        for (int m = 0; m < n; m++)
            arb_add(arb_mat_entry(J, F->term.row, m), arb_mat_entry(J, F->term.row, m), row + F->term.row * n + m,
                    F->prec);
        _arb_vec_clear(g, 2), _arb_vec_clear(row, n * n);
    }
}

static void widen(arb_t x, slong prec);

/* The variational equation's Picard test: W with I + [0, h] Df(B) W ⊆ W holds DΦ_t of every solution in B over
 * [0, h] (V' = Df(x) V, V(0) = I). 1 when found. */
static int a_priori_variational(const field_balls *F, arb_srcptr B, const arb_t span, arb_mat_t W)
{
    const int n = F->n;
    arb_mat_t J, Y;
    arb_mat_init(J, n, n), arb_mat_init(Y, n, n);
    gb_proof_flow_field_derivative(F, B, J);
    arb_mat_scalar_mul_arb(J, J, span, F->prec); /* [0, h] Df(B) */
    arb_mat_one(W);
    int found = 0;
    for (int attempt = 0; attempt < 12 && !found; attempt++) {
        arb_mat_mul(Y, J, W, F->prec);
        for (int a = 0; a < n; a++) arb_add_ui(arb_mat_entry(Y, a, a), arb_mat_entry(Y, a, a), 1, F->prec);
        found = 1;
        for (int a = 0; a < n && found; a++)
            for (int b = 0; b < n && found; b++)
                found = arb_is_finite(arb_mat_entry(Y, a, b)) &&
                        arb_contains(arb_mat_entry(W, a, b), arb_mat_entry(Y, a, b));
        if (found)
            arb_mat_set(W, Y);
        else
            for (int a = 0; a < n; a++)
                for (int b = 0; b < n; b++) {
                    arb_union(arb_mat_entry(W, a, b), arb_mat_entry(W, a, b), arb_mat_entry(Y, a, b), F->prec);
                    widen(arb_mat_entry(W, a, b), F->prec);
                }
    }
    arb_mat_clear(J), arb_mat_clear(Y);
    return found;
}

/* Σ_k a[k·stride] t^k by Horner, for a ball t. */
static void horner(arb_t out, arb_srcptr a, int stride, int degree, const arb_t t, slong prec)
{
    arb_set(out, a + degree * stride);
    for (int k = degree - 1; k >= 0; k--) {
        arb_mul(out, out, t, prec);
        arb_add(out, out, a + k * stride, prec);
    }
}


static void set_init(lohner_set *S, int n)
{
    for (int i = 0; i < NMAX; i++) arb_init(&S->x[i]), arb_init(&S->r[i]);
    arb_mat_init(S->A, n, n);
    arb_mat_one(S->A);
}

static void set_clear(lohner_set *S)
{
    for (int i = 0; i < NMAX; i++) arb_clear(&S->x[i]), arb_clear(&S->r[i]);
    arb_mat_clear(S->A);
}

/* The box x̂ + A r. */
void gb_proof_flow_set_hull(const field_balls *F, const lohner_set *S, arb_ptr out)
{
    for (int i = 0; i < F->n; i++) {
        arb_set(out + i, &S->x[i]);
        for (int j = 0; j < F->n; j++) arb_addmul(out + i, arb_mat_entry(S->A, i, j), &S->r[j], F->prec);
    }
}

/* The box of doubles [lo − 0.1 w − tiny, hi + 0.1 w + tiny] around a ball: a candidate a-priori enclosure. */
static void widen(arb_t x, slong prec)
{
    gb_proof_interval v = gb_proof_interval_of(x);
    const double w = v.hi - v.lo, tiny = 1e-12 * (1.0 + fmax(fabs(v.lo), fabs(v.hi)));
    v.lo -= 0.1 * w + tiny, v.hi += 0.1 * w + tiny;
    gb_proof_ball_of(x, v, prec);
}

/* Picard's test: a box B with X + [0, h] f(B) ⊆ B holds every solution from X over [0, h]. 1 when found. */
static int a_priori(const field_balls *F, arb_srcptr X, const arb_t span, arb_ptr B)
{
    const int n = F->n;
    arb_struct fx[NMAX], Y[NMAX];
    for (int i = 0; i < n; i++) arb_init(&fx[i]), arb_init(&Y[i]);
    gb_proof_flow_field_eval(F, X, fx);
    for (int i = 0; i < n; i++) {
        arb_mul(B + i, &fx[i], span, F->prec);
        arb_add(B + i, B + i, X + i, F->prec);
        arb_union(B + i, B + i, X + i, F->prec);
        widen(B + i, F->prec);
    }
    int found = 0;
    for (int attempt = 0; attempt < 6 && !found; attempt++) {
        gb_proof_flow_field_eval(F, B, fx);
        found = 1;
        for (int i = 0; i < n; i++) {
            arb_mul(&Y[i], &fx[i], span, F->prec);
            arb_add(&Y[i], &Y[i], X + i, F->prec);
            found &= arb_is_finite(&Y[i]) && arb_contains(B + i, &Y[i]); /* an infinite B holds anything */
        }
        if (found)
            for (int i = 0; i < n; i++) arb_set(B + i, &Y[i]); /* Y ⊆ B gives X + [0, h] f(Y) ⊆ Y as well */
        else
            for (int i = 0; i < n; i++) {
                arb_union(B + i, B + i, &Y[i], F->prec);
                widen(B + i, F->prec);
            }
    }
    for (int i = 0; i < n; i++) arb_clear(&fx[i]), arb_clear(&Y[i]);
    return found;
}


static void step_init(step_data *D, int order)
{
    D->order = order;
    D->centre = _arb_vec_init(NMAX * (order + 2));
    D->V = _arb_vec_init((order + 1) * NMAX * NMAX);
    D->Vrem = _arb_vec_init(NMAX * NMAX);
    D->c1 = 0;
    for (int i = 0; i < NMAX; i++) arb_init(&D->B[i]), arb_init(&D->Ar[i]), arb_init(&D->hull[i]);
}

static void step_clear(step_data *D)
{
    _arb_vec_clear(D->centre, NMAX * (D->order + 2));
    _arb_vec_clear(D->V, (D->order + 1) * NMAX * NMAX);
    _arb_vec_clear(D->Vrem, NMAX * NMAX);
    for (int i = 0; i < NMAX; i++) arb_clear(&D->B[i]), arb_clear(&D->Ar[i]), arb_clear(&D->hull[i]);
}

/* A step length from the coefficients at x̂: a quarter of the radius the last two suggest, at most step_max. */
static double step_length(const field_balls *F, const lohner_set *S, double step_max, arb_ptr scratch)
{
    const int p = F->order, w = p + 1;
    taylor(F, S->x, p, scratch);
    double h = step_max;
    for (int k = p - 1; k <= p; k++) {
        double size = 0.0;
        for (int i = 0; i < F->n; i++) size = fmax(size, fabs(arf_get_d(arb_midref(scratch + i * w + k), ARF_RND_NEAR)));
        if (size > 0.0) h = fmin(h, 0.25 * pow(size, -1.0 / k));
    }
    return h;
}

/* Prepares a step of length h (exact double) from S: 1 with D filled, 0 when no a-priori enclosure is found. */
static int step_prepare(const field_balls *F, const lohner_set *S, double h, step_data *D)
{
    const int n = F->n, p = F->order;
    arb_t span;
    arb_init(span);
    arf_t zero, end;
    arf_init(zero), arf_init(end);
    arf_set_d(end, h);
    arb_set_interval_arf(span, zero, end, F->prec);
    gb_proof_flow_set_hull(F, S, D->hull);
    int found = a_priori(F, D->hull, span, D->B);
    arb_mat_t W;
    arb_mat_init(W, n, n);
    if (found && D->c1) found = a_priori_variational(F, D->B, span, W);
    arb_clear(span), arf_clear(zero), arf_clear(end);
    if (!found) {
        arb_mat_clear(W);
        return 0;
    }
    /* x_{p+1} over B, into the centre's place p + 1 after the centre's own coefficients */
    arb_ptr over_B = _arb_vec_init(n * (p + 2));
    taylor(F, D->B, p + 1, over_B);
    if (D->c1) { /* V_{p+1} along solutions in B from V(ξ) ∈ W: the variational remainder's coefficient */
        arb_ptr VB = _arb_vec_init((p + 2) * n * n);
        variational_from(F, over_B, p + 1, W, VB);
        _arb_vec_set(D->Vrem, VB + (p + 1) * n * n, n * n);
        _arb_vec_clear(VB, (p + 2) * n * n);
    }
    arb_mat_clear(W);
    arb_ptr at_centre = _arb_vec_init(n * (p + 1));
    taylor(F, S->x, p, at_centre);
    for (int i = 0; i < n; i++) {
        for (int k = 0; k <= p; k++) arb_set(D->centre + i * (p + 2) + k, at_centre + i * (p + 1) + k);
        arb_set(D->centre + i * (p + 2) + p + 1, over_B + i * (p + 2) + p + 1);
    }
    _arb_vec_clear(at_centre, n * (p + 1));
    _arb_vec_clear(over_B, n * (p + 2));
    arb_ptr over_hull = _arb_vec_init(n * (p + 1));
    taylor(F, D->hull, p, over_hull);
    variational(F, over_hull, p, D->V);
    _arb_vec_clear(over_hull, n * (p + 1));
    for (int i = 0; i < n; i++) {
        arb_zero(&D->Ar[i]);
        for (int j = 0; j < n; j++) arb_addmul(&D->Ar[i], arb_mat_entry(S->A, i, j), &S->r[j], F->prec);
    }
    return 1;
}

/* The derivative of the Taylor polynomial at time t (a ball) over the hull. */
static void derivative_at(const field_balls *F, const step_data *D, const arb_t t, arb_mat_t out)
{
    const int n = F->n, nn = n * n;
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++) horner(arb_mat_entry(out, a, b), D->V + a * n + b, nn, F->order, t, F->prec);
}

void gb_proof_flow_derivative_at(const field_balls *F, const step_data *D, const arb_t t, arb_mat_t out)
{
    derivative_at(F, D, t, out);
    if (!D->c1) return;
    const int n = F->n;
    arb_t tp;
    arb_init(tp);
    arb_pow_ui(tp, t, (ulong)F->order + 1, F->prec);
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++) arb_addmul(arb_mat_entry(out, a, b), tp, D->Vrem + a * n + b, F->prec);
    arb_clear(tp);
}

/* Every solution from the set at every time of the ball t ⊆ [0, h]: a box. */
void gb_proof_flow_enclose_at(const field_balls *F, const step_data *D, const arb_t t, arb_ptr out)
{
    const int n = F->n, p = F->order;
    arb_mat_t DP;
    arb_mat_init(DP, n, n);
    derivative_at(F, D, t, DP);
    for (int i = 0; i < n; i++) {
        horner(out + i, D->centre + i * (p + 2), 1, p + 1, t, F->prec);
        for (int j = 0; j < n; j++) arb_addmul(out + i, arb_mat_entry(DP, i, j), &D->Ar[j], F->prec);
    }
    arb_mat_clear(DP);
}

void gb_proof_flow_new_frame(int n, const arb_mat_t M, arb_srcptr r, arb_mat_t Q)
{
    double m[NMAX][NMAX], weight[NMAX];
    int order[NMAX];
    for (int b = 0; b < n; b++) {
        double norm = 0.0;
        for (int a = 0; a < n; a++) {
            m[a][b] = arf_get_d(arb_midref(arb_mat_entry(M, a, b)), ARF_RND_NEAR);
            norm += m[a][b] * m[a][b];
        }
        weight[b] = sqrt(norm) * (r ? mag_get_d(arb_radref(r + b)) : 1.0);
        order[b] = b;
    }
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && weight[order[j]] > weight[order[j - 1]]; j--) {
            const int t = order[j];
            order[j] = order[j - 1], order[j - 1] = t;
        }
    double q[NMAX][NMAX];
    for (int c = 0; c < n; c++) {
        double v[NMAX];
        for (int a = 0; a < n; a++) v[a] = m[a][order[c]];
        for (int pass = 0; pass < 2; pass++)
            for (int d = 0; d < c; d++) {
                double dot = 0.0;
                for (int a = 0; a < n; a++) dot += q[a][d] * v[a];
                for (int a = 0; a < n; a++) v[a] -= dot * q[a][d];
            }
        double norm = 0.0;
        for (int a = 0; a < n; a++) norm += v[a] * v[a];
        norm = sqrt(norm);
        if (!(norm > 1e-300)) { /* a degenerate column: any unit vector orthogonal to the others */
            for (int e = 0; e < n && !(norm > 0.5); e++) {
                for (int a = 0; a < n; a++) v[a] = a == e;
                for (int d = 0; d < c; d++) {
                    double dot = q[e][d];
                    for (int a = 0; a < n; a++) v[a] -= dot * q[a][d];
                }
                norm = 0.0;
                for (int a = 0; a < n; a++) norm += v[a] * v[a];
                norm = sqrt(norm);
            }
        }
        for (int a = 0; a < n; a++) q[a][c] = v[a] / norm;
    }
    for (int a = 0; a < n; a++)
        for (int c = 0; c < n; c++) arb_set_d(arb_mat_entry(Q, a, c), q[a][c]);
}

/* Ends the step: S becomes the set at time h, x̂' = mid(Φ_p(x̂) + R), A' the new frame, r' = A'⁻¹(DΦ_p A) r +
 * A'⁻¹ e. 0 when A' cannot be inverted. */
int gb_proof_flow_step_finish(const field_balls *F, lohner_set *S, const step_data *D, double h)
{
    const int n = F->n, p = F->order;
    arb_t t;
    arb_init(t);
    arb_set_d(t, h);
    arb_mat_t DP, M, Anew, Ainv, C;
    arb_mat_init(DP, n, n), arb_mat_init(M, n, n), arb_mat_init(Anew, n, n), arb_mat_init(Ainv, n, n), arb_mat_init(C, n, n);
    derivative_at(F, D, t, DP);
    arb_mat_mul(M, DP, S->A, F->prec);
    arb_struct image[NMAX], e[NMAX], rn[NMAX];
    for (int i = 0; i < n; i++) arb_init(&image[i]), arb_init(&e[i]), arb_init(&rn[i]);
    for (int i = 0; i < n; i++) {
        horner(&image[i], D->centre + i * (p + 2), 1, p + 1, t, F->prec);
        arb_get_mid_arb(&S->x[i], &image[i]);
        arb_sub(&e[i], &image[i], &S->x[i], F->prec);
    }
    gb_proof_flow_new_frame(n, M, S->r, Anew);
    const int invertible = arb_mat_inv(Ainv, Anew, F->prec);
    if (invertible) {
        arb_mat_mul(C, Ainv, M, F->prec);
        for (int i = 0; i < n; i++) {
            arb_zero(&rn[i]);
            for (int j = 0; j < n; j++) {
                arb_addmul(&rn[i], arb_mat_entry(C, i, j), &S->r[j], F->prec);
                arb_addmul(&rn[i], arb_mat_entry(Ainv, i, j), &e[j], F->prec);
            }
        }
        for (int i = 0; i < n; i++) arb_set(&S->r[i], &rn[i]);
        arb_mat_set(S->A, Anew);
    }
    for (int i = 0; i < n; i++) arb_clear(&image[i]), arb_clear(&e[i]), arb_clear(&rn[i]);
    arb_mat_clear(DP), arb_mat_clear(M), arb_mat_clear(Anew), arb_mat_clear(Ainv), arb_mat_clear(C);
    arb_clear(t);
    return invertible;
}

void gb_proof_field_image(const gb_proof_field *field, arb_srcptr x, arb_ptr out, slong prec)
{
    field_balls F;
    gb_proof_flow_field_init(&F, field, GB_PROOF_ORDER_MIN, prec);
    gb_proof_flow_field_eval(&F, x, out);
    gb_proof_flow_field_clear(&F);
}

gb_proof_field gb_proof_flow_rossler(long a_num, long a_den, long b_num, long b_den, long c_num, long c_den)
{
    gb_proof_field f;
    memset(&f, 0, sizeof f);
    f.dimension = 3;
    f.L[0][1] = f.L[0][2] = (gb_proof_rational){-1, 1};
    f.L[1][0] = (gb_proof_rational){1, 1};
    f.L[1][1] = (gb_proof_rational){a_num, a_den};
    f.c[2] = (gb_proof_rational){b_num, b_den};
    f.L[2][2] = (gb_proof_rational){-c_num, c_den};
    f.Q[2][0][2] = (gb_proof_rational){1, 1};
    return f;
}

gb_proof_flow_def gb_proof_flow_def_default(const gb_proof_field *field)
{
    return (gb_proof_flow_def){field, 0, +1, 1, GB_PROOF_ORDER_DEFAULT, GB_PROOF_PRECISION_DEFAULT, 100.0, 0.5, 64, 0};
}

int gb_proof_flow_def_check(const gb_proof_flow_def *def)
{
    if (!def || !def->field) return gb_error_set(GB_EINVAL, "a section map needs a definition and a field");
    const gb_proof_field *f = def->field;
    if (f->dimension < 1 || f->dimension > NMAX)
        return gb_error_set(GB_EDOM, "field dimension = %d is out of range (allowed: 1 to %d)", f->dimension, NMAX);
    int status = gb_proof_check_precision(def->precision);
    if (status) return status;
    if (def->order < GB_PROOF_ORDER_MIN || def->order > GB_PROOF_ORDER_MAX)
        return gb_error_set(GB_EDOM, "order = %d is out of range (allowed: %d to %d)", def->order, GB_PROOF_ORDER_MIN,
                            GB_PROOF_ORDER_MAX);
    if (def->coordinate < 0 || def->coordinate >= f->dimension)
        return gb_error_set(GB_EDOM, "section coordinate = %d is out of range (allowed: 0 to %d)", def->coordinate, f->dimension - 1);
    if (def->direction != 1 && def->direction != -1)
        return gb_error_set(GB_EDOM, "section direction = %d is out of range (allowed: +1 or -1)", def->direction);
    if (def->returns < 1 || def->returns > 16)
        return gb_error_set(GB_EDOM, "returns = %d is out of range (allowed: 1 to 16)", def->returns);
    if (!(def->time_max > 0.0 && def->time_max <= 1e4))
        return gb_error_set(GB_EDOM, "time_max = %g is out of range (allowed: above 0, at most 1e4)", def->time_max);
    if (!(def->step_max > 0.0 && def->step_max <= 1e3))
        return gb_error_set(GB_EDOM, "step_max = %g is out of range (allowed: above 0, at most 1e3)", def->step_max);
    if (def->time_pieces < 2 || def->time_pieces > 4096)
        return gb_error_set(GB_EDOM, "time_pieces = %d is out of range (allowed: 2 to 4096)", def->time_pieces);
    for (int i = 0; i < f->dimension; i++)
        for (int j = 0; j < f->dimension; j++) {
            if (f->L[i][j].den < 0 || f->c[i].den < 0)
                return gb_error_set(GB_EDOM, "a coefficient's denominator is negative (allowed: 0 for none, or positive)");
            for (int k = 0; k < f->dimension; k++)
                if (f->Q[i][j][k].den < 0)
                    return gb_error_set(GB_EDOM, "a coefficient's denominator is negative (allowed: 0 for none, or positive)");
        }
    return GB_OK;
}

int gb_proof_flow_check(const gb_proof_flow_def *def, const gb_proof_interval *box)
{
    const int status = gb_proof_flow_def_check(def);
    if (status) return status;
    if (!box) return gb_error_set(GB_EINVAL, "a section map needs a box");
    for (int i = 0; i < def->field->dimension; i++)
        if (!(isfinite(box[i].lo) && isfinite(box[i].hi) && box[i].lo <= box[i].hi))
            return gb_error_set(GB_EDOM, "box component %d = [%g, %g] is not a finite interval with lo <= hi", i, box[i].lo, box[i].hi);
    return GB_OK;
}

/* The set of the box: x̂ its middle (exact), A = I, r the box minus x̂. */
static void set_of_box(const field_balls *F, lohner_set *S, const gb_proof_interval *box)
{
    arb_t b;
    arb_init(b);
    for (int i = 0; i < F->n; i++) {
        gb_proof_ball_of(b, box[i], F->prec);
        arb_get_mid_arb(&S->x[i], b);
        arb_sub(&S->r[i], b, &S->x[i], F->prec);
    }
    arb_clear(b);
}

/* A field with a term (its coefficients over an arc can be far wider than at a point): the step's Lagrange remainder
 * x_{p+1}(B) h^{p+1} at most 1e-10 plus a thousandth of the set's own width, so that the set does not grow by it. Quadratic
 * fields: always (their steps as they were). */
static int remainder_small(const field_balls *F, const step_data *D, double h)
{
    if (F->term.row < 0) return 1;
    const int p = F->order;
    double own = 0.0;
    for (int i = 0; i < F->n; i++) own = fmax(own, mag_get_d(arb_radref(&D->hull[i])));
    for (int i = 0; i < F->n; i++) {
        const double r = mag_get_d(arb_radref(D->centre + i * (p + 2) + p + 1)) +
                         fabs(arf_get_d(arb_midref(D->centre + i * (p + 2) + p + 1), ARF_RND_UP));
        if (!(r * pow(h, p + 1) <= 1e-10 + 1e-3 * own)) return 0;
    }
    return 1;
}

/* Takes one step from S at time *t (advanced): a step length chosen and halved until Picard's test holds. */
int gb_proof_flow_step_take(const field_balls *F, lohner_set *S, step_data *D, const gb_proof_flow_def *def, double h_cap,
                     arb_ptr scratch, double *h_taken, const arb_t t_now)
{
    /* steps are multiples of 2^-30, so that their sums (the times) are exact doubles */
    double h = floor(ldexp(fmin(step_length(F, S, def->step_max, scratch), h_cap), 30));
    h = ldexp(fmax(h, 1.0), -30);
    while (!step_prepare(F, S, h, D) || !remainder_small(F, D, h)) {
        h = ldexp(floor(ldexp(h, 29)), -30);
        if (h < 1e-9) {
            return gb_error_set(GB_ENUMERIC, "no a-priori enclosure of the set's solutions at t = %.6g even for a step of 1e-9 "
                                "(the set has grown too wide to follow)", arf_get_d(arb_midref(t_now), ARF_RND_NEAR));
        }
    }
    *h_taken = h;
    return GB_OK;
}

/* Follows the integration's set to t_end: the image's box. */
static int run_time(integration *I, const gb_proof_flow_def *def, double t_end, gb_proof_interval *image)
{
    int status = GB_OK;
    arb_t t;
    arb_init(t);
    arb_struct hull[NMAX];
    for (int i = 0; i < NMAX; i++) arb_init(&hull[i]);
    double done = 0.0; /* the time reached: multiples of 2^-30, exact */
    while (!status && done < t_end) {
        double h;
        arb_set_d(t, done);
        status = gb_proof_flow_step_take(&I->F, &I->S, &I->D, def, t_end - done, I->scratch, &h, t);
        if (!status && !gb_proof_flow_step_finish(&I->F, &I->S, &I->D, h))
            status = gb_error_set(GB_ENUMERIC, "at t = %g the Lohner frame is singular", done);
        for (int i = 0; i < I->F.n && !status; i++)
            if (!arb_is_finite(&I->S.x[i]) || !arb_is_finite(&I->S.r[i]))
                status = gb_error_set(GB_ENUMERIC, "at t = %g the set's enclosure is no longer finite", done + h);
        done += h;
    }
    if (!status) {
        gb_proof_flow_set_hull(&I->F, &I->S, hull);
        for (int i = 0; i < I->F.n; i++) image[i] = gb_proof_interval_of(&hull[i]);
    }
    for (int i = 0; i < NMAX; i++) arb_clear(&hull[i]);
    arb_clear(t);
    return status;
}

static int check_time(const gb_proof_flow_def *def, const gb_proof_interval *box, double t_end,
                      gb_proof_interval *image)
{
    int status = gb_proof_flow_check(def, box);
    if (status) return status;
    if (!(t_end >= 0.0 && t_end <= def->time_max) || ldexp(t_end, 30) != floor(ldexp(t_end, 30)))
        return gb_error_set(GB_EDOM, "t = %g is out of range (allowed: 0 to time_max = %g, a multiple of 2^-30)", t_end,
                            def->time_max);
    return image ? GB_OK : gb_error_set(GB_EINVAL, "a flow needs an image");
}

int gb_proof_flow_time(const gb_proof_flow_def *def, const gb_proof_interval *box, double t_end,
                       gb_proof_interval *image)
{
    int status = check_time(def, box, t_end, image);
    if (status) return status;
    field_balls F;
    gb_proof_flow_field_init(&F, def->field, def->order, def->precision);
    status = gb_proof_flow_time_of(&F, def, box, t_end, image);
    gb_proof_flow_field_clear(&F);
    return status;
}

int gb_proof_flow_time_of(const field_balls *F, const gb_proof_flow_def *def, const gb_proof_interval *box,
                          double t_end, gb_proof_interval *image)
{
    int status = check_time(def, box, t_end, image);
    if (!status && (F->n != def->field->dimension || F->order != def->order))
        status = gb_error_set(GB_EINVAL, "the field's dimension and order are not the definition's");
    if (status) return status;
    integration I;
    gb_proof_flow_integration_borrow(&I, F, box);
    status = run_time(&I, def, t_end, image);
    gb_proof_flow_integration_release(&I);
    return status;
}

void gb_proof_flow_integration_borrow(integration *I, const field_balls *F, const gb_proof_interval *box)
{
    I->F = *F; /* borrowed: gb_proof_flow_integration_release does not clear it */
    set_init(&I->S, F->n);
    set_of_box(&I->F, &I->S, box);
    step_init(&I->D, F->order);
    I->scratch = _arb_vec_init(F->n * (F->order + 1));
}

void gb_proof_flow_integration_release(integration *I)
{
    _arb_vec_clear(I->scratch, I->F.n * (I->F.order + 1));
    step_clear(&I->D);
    set_clear(&I->S);
}
