/* gb_impact_coulomb — the impact of a rigid body on a plane of finite friction μ (gb_impact.h, "a plane of
 * finite friction"; docs/friction.md): one point by Darboux–Keller with Stronge's energetic restitution,
 * several points at once by Moreau's law with Coulomb's cone, the contacts that take impulse enumerated
 * as the rough law enumerates them. */
#include "gb_impact_internal.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <string.h>

int gb_impact_friction_check(double mu)
{
    if (mu > 0.0) return GB_OK; /* INFINITY: the rough plane */
    return gb_error_set(GB_EDOM, "friction mu = %g is out of range (allowed: mu > 0, or rough)", mu);
}

/* ---------------------------------------------------------------- one point: Darboux–Keller */

/* The point's velocity u = (u_1, u_2, u_n) in the basis (t1, t2, n), the impulse (P_1, P_2, p) so far, and
 * the normal impulse's work W_n = ∫ u_n dp. */
typedef struct dk_state {
    double u[3], P[3], work;
} dk_state;

typedef struct dk {
    double W[3][3]; /* the Delassus operator in the basis (t1, t2, n) */
    double mu;
} dk;

/* d/dp of the state while the point slips along `slip` (a unit tangent; the friction is −μ slip). */
static void dk_slide_rate(const dk *k, const dk_state *s, const double slip[2], dk_state *rate)
{
    const double f[3] = {-k->mu * slip[0], -k->mu * slip[1], 1.0};
    for (int i = 0; i < 3; i++) rate->u[i] = k->W[i][0] * f[0] + k->W[i][1] * f[1] + k->W[i][2] * f[2];
    memcpy(rate->P, f, sizeof f);
    rate->work = s->u[2];
}

/* The slip direction of a state: u_t / |u_t|; `ref` (the direction at the step's start) where the slip is 0
 * or has turned against it, so that a step carries the slip smoothly through its stop, whose event (u_t·ref
 * = 0) is then located inside the step. */
static void dk_slip(const dk_state *s, const double ref[2], double slip[2])
{
    const double speed = sqrt(s->u[0] * s->u[0] + s->u[1] * s->u[1]); /* no overflow at a body's speeds; hypot's care costs a third of an impact */
    if (speed > 0.0 && s->u[0] * ref[0] + s->u[1] * ref[1] > 0.0) slip[0] = s->u[0] / speed, slip[1] = s->u[1] / speed;
    else slip[0] = ref[0], slip[1] = ref[1];
}

/* One RK4 step of size h while slipping (the direction re-taken at every stage, ref where it would turn). */
static void dk_step(const dk *k, const dk_state *s, double h, const double ref[2], dk_state *out)
{
    dk_state stage[4], y;
    double slip[2];
    dk_slip(s, ref, slip);
    dk_slide_rate(k, s, slip, &stage[0]);
    for (int q = 1; q < 4; q++) {
        const double c = q == 3 ? h : 0.5 * h;
        for (int i = 0; i < 3; i++) y.u[i] = s->u[i] + c * stage[q - 1].u[i], y.P[i] = s->P[i] + c * stage[q - 1].P[i];
        y.work = s->work + c * stage[q - 1].work;
        dk_slip(&y, ref, slip);
        dk_slide_rate(k, &y, slip, &stage[q]);
    }
    for (int i = 0; i < 3; i++) {
        out->u[i] = s->u[i] + h / 6.0 * (stage[0].u[i] + 2.0 * stage[1].u[i] + 2.0 * stage[2].u[i] + stage[3].u[i]);
        out->P[i] = s->P[i] + h / 6.0 * (stage[0].P[i] + 2.0 * stage[1].P[i] + 2.0 * stage[2].P[i] + stage[3].P[i]);
    }
    out->work = s->work + h / 6.0 * (stage[0].work + 2.0 * stage[1].work + 2.0 * stage[2].work + stage[3].work);
}

/* The friction that keeps a stopped point stopped: W_tt f = −W_tn (2 × 2). */
static void dk_stick_friction(const dk *k, double f[2])
{
    const double a = k->W[0][0], b = k->W[0][1], c = k->W[1][0], d = k->W[1][1], det = a * d - b * c;
    f[0] = -(d * k->W[0][2] - b * k->W[1][2]) / det;
    f[1] = -(a * k->W[1][2] - c * k->W[0][2]) / det;
}

/* A stopped point that the cone cannot hold slips on in the direction s with W_t (n − μ s) = λ s, λ > 0:
 * s = (λ + μ W_tt)⁻¹ W_tn, |s| = 1, whose norm falls from above 1 at λ = 0 to 0: bisection on λ. */
static void dk_restart(const dk *k, double slip[2])
{
    double lo = 0.0, hi = 1.0;
    const double bn[2] = {k->W[0][2], k->W[1][2]};
    for (;;) { /* |s(hi)| < 1 */
        const double a = hi + k->mu * k->W[0][0], b = k->mu * k->W[0][1], c = k->mu * k->W[1][0], d = hi + k->mu * k->W[1][1];
        const double det = a * d - b * c, s0 = (d * bn[0] - b * bn[1]) / det, s1 = (a * bn[1] - c * bn[0]) / det;
        if (hypot(s0, s1) < 1.0 || hi > 1e300) break;
        lo = hi, hi *= 2.0;
    }
    for (int it = 0; it < 200; it++) {
        const double mid = 0.5 * (lo + hi);
        if (mid == lo || mid == hi) break;
        const double a = mid + k->mu * k->W[0][0], b = k->mu * k->W[0][1], c = k->mu * k->W[1][0], d = mid + k->mu * k->W[1][1];
        const double det = a * d - b * c, s0 = (d * bn[0] - b * bn[1]) / det, s1 = (a * bn[1] - c * bn[0]) / det;
        if (hypot(s0, s1) > 1.0) lo = mid;
        else hi = mid;
    }
    const double a = hi + k->mu * k->W[0][0], b = k->mu * k->W[0][1], c = k->mu * k->W[1][0], d = hi + k->mu * k->W[1][1];
    const double det = a * d - b * c, s0 = (d * bn[0] - b * bn[1]) / det, s1 = (a * bn[1] - c * bn[0]) / det, n = hypot(s0, s1);
    slip[0] = s0 / n, slip[1] = s1 / n;
}

/* The events of a slipping stretch, as functions of the state that change sign at them: the end of
 * compression (u_n from below to 0), the end of the impact (the work back to its target), the slip's stop
 * (u_t · the direction at the stretch's start). */
enum { DK_COMPRESSION = 0, DK_END = 1, DK_STOP = 2, DK_EVENTS = 3 };

static void dk_events(const dk_state *s, int compressed, double target, const double ref[2], double g[DK_EVENTS])
{
    g[DK_COMPRESSION] = compressed ? -1.0 : s->u[2];
    g[DK_END] = compressed ? s->work - target : -1.0;
    g[DK_STOP] = -(s->u[0] * ref[0] + s->u[1] * ref[1]);
}

/* Stick: u_t stays 0, the normal velocity grows at k_n = W_nn + W_nt f per unit p: from state s, the
 * impulse dp to the end of compression (if not yet) and then to the end of the impact. Exact (linear). */
static void dk_stick(const dk *k, const double f[2], dk_state *s, int *compressed, double *target, double e)
{
    const double rate = k->W[2][2] + k->W[2][0] * f[0] + k->W[2][1] * f[1];
    double dp = 0.0;
    if (!*compressed) {
        dp = -s->u[2] / rate; /* u_n < 0 → 0 */
        s->work += -0.5 * s->u[2] * s->u[2] / rate;
        s->u[2] = 0.0;
        *compressed = 1;
        *target = (1.0 - e * e) * s->work;
        s->P[0] += f[0] * dp, s->P[1] += f[1] * dp, s->P[2] += dp;
    }
    /* restitution from u_n ≥ 0: work + u_n dp + ½ rate dp² = target */
    const double gain = fmax(*target - s->work, 0.0), un = sqrt(s->u[2] * s->u[2] + 2.0 * rate * gain), dr = (un - s->u[2]) / rate;
    s->u[2] = un, s->work = *target;
    s->P[0] += f[0] * dr, s->P[1] += f[1] * dr, s->P[2] += dr;
}

int gb_impact_coulomb_point(const gb_impact_body *body, const double normal[3], double e, double mu, const double point[3],
                            const double v[3], const double omega[3], gb_impact_result *out)
{
    if (isinf(mu) && mu > 0.0) return gb_impact_rough_point(body, normal, e, point, v, omega, out);
    memset(out, 0, sizeof *out);
    double inv[3][3];
    int status = gb_impact_check_body(body, 1, inv);
    if (!status) status = gb_impact_restitution_check(e);
    if (!status) status = gb_impact_friction_check(mu);
    if (status) return status;
    double W[3][3], t1[3], t2[3], u0[3];
    gb_impact_delassus(body, inv, point, point, W);
    gb_impact_tangents(normal, t1, t2);
    const double *basis[3] = {t1, t2, normal};
    dk k = {.mu = mu};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double Wb[3];
            for (int r = 0; r < 3; r++) Wb[r] = W[r][0] * basis[j][0] + W[r][1] * basis[j][1] + W[r][2] * basis[j][2];
            k.W[i][j] = gb_vec_dot(basis[i], Wb);
        }
    gb_impact_point_velocity(v, omega, point, u0);
    dk_state s = {{gb_vec_dot(t1, u0), gb_vec_dot(t2, u0), gb_vec_dot(normal, u0)}, {0, 0, 0}, 0.0};
    const double speed = gb_vec_norm(u0), velocity_tol = GB_IMPACT_SIGN_TOL * (speed + 1e-300);
    for (int i = 0; i < 3; i++) out->slip_before[0][i] = u0[i] - s.u[2] * normal[i];
    out->energy_before = gb_impact_energy(body, v, omega);
    memcpy(out->v, v, sizeof out->v), memcpy(out->omega, omega, sizeof out->omega);
    out->feasible_sets = 1;
    if (!(s.u[2] < -velocity_tol)) { /* not approaching: no impact */
        memcpy(out->slip_after[0], out->slip_before[0], sizeof out->slip_after[0]);
        out->energy_after = out->energy_before;
        return GB_OK;
    }
    /* The impulse's scale: a frictionless compression takes −u_n / W_nn; steps of 1/4000 of it (RK4: its
     * error ~ 1e-14 of the scale), and at most 10⁶ of them (a normal velocity that friction keeps from
     * growing, a jam, is refused). */
    const double scale = -s.u[2] / k.W[2][2] * (1.0 + e), h = scale / 4000.0;
    int compressed = 0, sticking = 0, steps = 0;
    double target = 0.0, f_stick[2], slip[2] = {0.0, 0.0};
    dk_stick_friction(&k, f_stick);
    const int cone_holds = hypot(f_stick[0], f_stick[1]) <= mu * (1.0 + 1e-12);
    out->stages = 1;
    if (hypot(s.u[0], s.u[1]) <= velocity_tol) { /* no slip before: stick, or slip as the law allows */
        s.u[0] = s.u[1] = 0.0;
        if (cone_holds) sticking = 1;
        else dk_restart(&k, slip);
    } else {
        const double speed0 = hypot(s.u[0], s.u[1]);
        slip[0] = s.u[0] / speed0, slip[1] = s.u[1] / speed0;
    }
    /* The slip turns at most by |du_t/dp| / |u_t| per unit p, |du_t/dp| ≤ |W_tn| + μ |W_tt|: steps of at most
     * 1/20 of |u_t| over that keep the turn per step small, and the slip's stop is where |u_t| falls below
     * 1e-13 of the speed (a geometric approach: some 600 steps from any slip). */
    const double turn_rate = hypot(k.W[0][2], k.W[1][2]) +
                             mu * sqrt(k.W[0][0] * k.W[0][0] + k.W[0][1] * k.W[0][1] + k.W[1][0] * k.W[1][0] + k.W[1][1] * k.W[1][1]);
    const double slip_floor = 1e-13 * (speed + 1e-300);
    while (!sticking) {
        /* slip: RK4 steps until an event; the event found by bisection on the step from its start */
        const double slip_speed = hypot(s.u[0], s.u[1]);
        if (slip_speed <= slip_floor && steps > 0) { /* stopped */
            s.u[0] = s.u[1] = 0.0;
            out->stages++;
            if (cone_holds) sticking = 1;
            else dk_restart(&k, slip);
            if (sticking) break;
        }
        /* the stretch's direction: the slip's, or the restart's after a stop (taken before the stop, it would be put
         * back by the step's closing dk_slip, and friction would go on opposing the slip that stopped) */
        const double ref[2] = {slip[0], slip[1]};
        const double step = slip_speed > slip_floor ? fmin(h, 0.05 * slip_speed / turn_rate) : h;
        double g0[DK_EVENTS], g1[DK_EVENTS];
        dk_state next;
        dk_events(&s, compressed, target, ref, g0);
        dk_step(&k, &s, step, slip, &next);
        dk_events(&next, compressed, target, ref, g1);
        int hit = -1;
        for (int q = 0; q < DK_EVENTS && hit < 0; q++)
            if (g0[q] < 0.0 && g1[q] >= 0.0) hit = q;
        if (hit < 0) {
            s = next;
            dk_slip(&s, ref, slip);
            if (++steps > 1000000)
                return gb_error_set(GB_ENUMERIC, "impact: the normal velocity does not grow while the point slips (a jam: "
                                    "mu %g): the impact does not end", mu);
            continue;
        }
        /* the earliest event inside the step: bisect the step's length for each and keep the shortest */
        double best = step;
        int which = hit;
        for (int q = 0; q < DK_EVENTS; q++) {
            double lo = 0.0, hi = step, gq[DK_EVENTS];
            dk_state probe;
            dk_step(&k, &s, hi, slip, &probe);
            dk_events(&probe, compressed, target, ref, gq);
            if (!(g0[q] < 0.0 && gq[q] >= 0.0)) continue;
            for (int it = 0; it < 80; it++) {
                const double mid = 0.5 * (lo + hi);
                if (mid == lo || mid == hi) break;
                dk_step(&k, &s, mid, slip, &probe);
                dk_events(&probe, compressed, target, ref, gq);
                if (gq[q] >= 0.0) hi = mid;
                else lo = mid;
            }
            if (hi < best) best = hi, which = q;
        }
        dk_step(&k, &s, best, slip, &next);
        s = next;
        if (which == DK_COMPRESSION) {
            s.u[2] = fmax(s.u[2], 0.0);
            compressed = 1, target = (1.0 - e * e) * s.work;
            if (e == 0.0) break; /* plastic: the impact ends with compression */
            dk_slip(&s, ref, slip);
        } else if (which == DK_END) {
            break;
        } else { /* the slip stopped */
            s.u[0] = s.u[1] = 0.0;
            out->stages++;
            if (cone_holds) sticking = 1;
            else dk_restart(&k, slip);
        }
    }
    if (sticking && !(compressed && e == 0.0)) dk_stick(&k, f_stick, &s, &compressed, &target, e);
    /* the impulse back in the body's frame, applied */
    double P[1][3];
    for (int i = 0; i < 3; i++) P[0][i] = s.P[0] * t1[i] + s.P[1] * t2[i] + s.P[2] * normal[i];
    gb_impact_apply(body, inv, (const double(*)[3])&point[0], 1, (const double(*)[3])P, v, omega, out->v, out->omega);
    out->energy_after = gb_impact_energy(body, out->v, out->omega);
    const double impulse_tol = GB_IMPACT_SIGN_TOL * body->mass * (speed + 1e-300);
    gb_impact_fill(normal, 1, 1u, (const double(*)[3])P, impulse_tol, out);
    double u1[3];
    gb_impact_point_velocity(out->v, out->omega, point, u1);
    const double un = gb_vec_dot(normal, u1);
    for (int i = 0; i < 3; i++) out->slip_after[0][i] = u1[i] - un * normal[i];
    out->slides[0] = gb_vec_norm(out->slip_after[0]) > velocity_tol;
    return GB_OK;
}

/* ---------------------------------------------------------------- several points: Moreau with the cone */

/* A candidate: the held contacts (mask), which of them slide (slide) and in which directions (angle in the
 * tangent basis). The impulses that give every held contact its normal target and every sticking one its
 * tangential target 0, with a sliding contact's impulse along n − μ d: by SVD (minimum norm). 0, or 1
 * when the system has no solution. */
typedef struct coulomb {
    const gb_impact_body *body;
    const double (*inv)[3];
    const double *normal, *t1, *t2;
    const double (*points)[3];
    int count;
    double mu;
    double before[GB_IMPACT_CONTACTS_MAX][3]; /* each point's velocity before */
    double target[GB_IMPACT_CONTACTS_MAX];    /* each point's normal velocity after, if held: −e u_n⁻ */
    double floor[GB_IMPACT_CONTACTS_MAX];     /* the least normal velocity after of a point that is not held: 0 (an
                                               * impact), its target (a time step's velocity-level law) */
    double exact; /* > 0: the held points' velocities after within this of their targets (normal, and tangential 0
                   * where they stick): the Delassus system of a set may be solvable only in the least-squares sense,
                   * and then another split is the law's answer */
} coulomb;

static void direction(const coulomb *c, double angle, double d[3])
{
    for (int i = 0; i < 3; i++) d[i] = cos(angle) * c->t1[i] + sin(angle) * c->t2[i];
}

/* The internal impulses a set leaves open (a null space: impulses that change no velocity), at most 3. */
typedef struct internal {
    int count;
    double pattern[3][GB_IMPACT_CONTACTS_MAX][3];
} internal;

static int coulomb_solve(const coulomb *c, unsigned mask, unsigned slide, const double *angle, double (*P)[3],
                         internal *open)
{
    enum { MAX = 3 * GB_IMPACT_CONTACTS_MAX };
    double column[MAX][GB_IMPACT_CONTACTS_MAX][3]; /* each unknown's impulse pattern: the impulse at every point */
    int unknowns = 0, rows = 0;
    double a[MAX * MAX] = {0}, b[MAX], row_dir[MAX][3];
    int row_point[MAX];
    memset(column, 0, sizeof column);
    for (int k = 0; k < c->count; k++) {
        if (!(mask & (1u << k))) continue;
        if (slide & (1u << k)) {
            double d[3];
            direction(c, angle[k], d);
            for (int i = 0; i < 3; i++) column[unknowns][k][i] = c->normal[i] - c->mu * d[i];
            unknowns++;
            row_point[rows] = k, memcpy(row_dir[rows], c->normal, sizeof row_dir[rows]), rows++;
        } else {
            const double *axes[3] = {c->t1, c->t2, c->normal};
            for (int q = 0; q < 3; q++) { /* the unknowns P_x, P_y, P_z; the rows along t1, t2, n */
                column[unknowns][k][q] = 1.0;
                unknowns++;
                row_point[rows] = k, memcpy(row_dir[rows], axes[q], sizeof row_dir[rows]), rows++;
            }
        }
    }
    /* a[r][j] = row_dir_r · Σ_points W_{row point, point} column_j(point) */
    for (int r = 0; r < rows; r++) {
        const int k = row_point[r];
        double target[3] = {0, 0, 0};
        target[0] = -c->before[k][0], target[1] = -c->before[k][1], target[2] = -c->before[k][2];
        for (int i = 0; i < 3; i++) target[i] += c->target[k] * c->normal[i];
        b[r] = gb_vec_dot(row_dir[r], target);
        for (int j = 0; j < unknowns; j++) {
            double sum = 0.0;
            for (int q = 0; q < c->count; q++) {
                const double *col = column[j][q];
                if (col[0] == 0.0 && col[1] == 0.0 && col[2] == 0.0) continue;
                double Wkq[3][3], Wc[3];
                gb_impact_delassus(c->body, c->inv, c->points[k], c->points[q], Wkq);
                for (int i = 0; i < 3; i++) Wc[i] = Wkq[i][0] * col[0] + Wkq[i][1] * col[1] + Wkq[i][2] * col[2];
                sum += gb_vec_dot(row_dir[r], Wc);
            }
            a[r * unknowns + j] = sum;
        }
    }
    /* the system (rows = unknowns) by SVD, minimum norm; no held point: no impulse */
    const size_t n = (size_t)unknowns;
    if (!n) {
        memset(P, 0, sizeof P[0] * (size_t)c->count);
        if (open) open->count = 0;
        return 0;
    }
    double v_data[MAX * MAX], s_data[MAX], x[MAX];
    if (gb_impact_min_norm(a, b, n, x, v_data, s_data)) return 1;
    const double cut = GB_IMPACT_SINGULAR_CUT * s_data[0];
    for (int k = 0; k < c->count; k++) memset(P[k], 0, sizeof P[k]);
    for (int j = 0; j < unknowns; j++)
        for (int k = 0; k < c->count; k++)
            for (int i = 0; i < 3; i++) P[k][i] += x[j] * column[j][k][i];
    if (open) { /* the right singular vectors of the cut singular values, as impulse patterns */
        open->count = 0;
        for (size_t i = 0; i < n && open->count < 3; i++) {
            if (s_data[i] > cut) continue;
            double (*pat)[3] = open->pattern[open->count++];
            for (int k = 0; k < c->count; k++) memset(pat[k], 0, sizeof pat[k]);
            for (int j = 0; j < unknowns; j++)
                for (int k = 0; k < c->count; k++)
                    for (int q = 0; q < 3; q++) pat[k][q] += v_data[(size_t)j * n + i] * column[j][k][q];
        }
    }
    return 0;
}

/* How far the held contacts' impulses are inside the law: the least of μ P_n − |P_t| over the sticking ones
 * and μ P_n over the sliding ones (≥ 0 when the cones and the signs hold); the index of the least in *at. */
static double margin(const coulomb *c, unsigned mask, unsigned slide, const double (*P)[3], int *at)
{
    double least = INFINITY;
    for (int k = 0; k < c->count; k++) {
        if (!(mask & (1u << k))) continue;
        const double pn = gb_vec_dot(P[k], c->normal);
        double m = c->mu * pn;
        if (!(slide & (1u << k))) {
            const double pt[3] = {P[k][0] - pn * c->normal[0], P[k][1] - pn * c->normal[1], P[k][2] - pn * c->normal[2]};
            m -= gb_vec_norm(pt);
        }
        if (m < least) least = m, *at = k;
    }
    return least;
}

/* The impulses P + Σ z_j pattern_j at z. */
static void shifted(const coulomb *c, const double (*P)[3], const internal *open, const double *z, double (*out)[3])
{
    for (int k = 0; k < c->count; k++)
        for (int i = 0; i < 3; i++) {
            out[k][i] = P[k][i];
            for (int j = 0; j < open->count; j++) out[k][i] += z[j] * open->pattern[j][k][i];
        }
}

/* The internal impulses (which change no velocity: every sign but the cones' is the same whatever they are)
 * that put the held contacts deepest inside the law: the margin, a concave function of z, maximised by the
 * central-cut ellipsoid method (one dimension: bisection on its slope), from a ball of the impulses' own
 * size. P is moved there. */
static void deepest(const coulomb *c, unsigned mask, unsigned slide, double (*P)[3], const internal *open)
{
    const int dim = open->count;
    if (!dim) return;
    double size = 0.0, z[3] = {0, 0, 0}, best_z[3] = {0, 0, 0}, Q[GB_IMPACT_CONTACTS_MAX][3];
    for (int k = 0; k < c->count; k++) size = fmax(size, gb_vec_norm(P[k]));
    size = 10.0 * size + 1e-300;
    int at = 0;
    double best = margin(c, mask, slide, (const double(*)[3])P, &at);
    double E[3][3] = {{0}}; /* the ellipsoid {z: (z − c)ᵀ E⁻¹ (z − c) ≤ 1} */
    for (int i = 0; i < dim; i++) E[i][i] = size * size;
    for (int it = 0; it < 60 * (dim + 1) * (dim + 1); it++) {
        shifted(c, (const double(*)[3])P, open, z, Q);
        const double m = margin(c, mask, slide, (const double(*)[3])Q, &at);
        if (m > best) best = m, memcpy(best_z, z, sizeof z);
        /* the gradient of the least margin along the patterns: μ n·pattern − t̂·pattern_t (sticking) */
        const double pn = gb_vec_dot(Q[at], c->normal);
        double pt[3], g[3] = {0, 0, 0};
        for (int i = 0; i < 3; i++) pt[i] = Q[at][i] - pn * c->normal[i];
        const double ptn = gb_vec_norm(pt);
        for (int j = 0; j < dim; j++) {
            const double *q = open->pattern[j][at], qn = gb_vec_dot(q, c->normal);
            g[j] = c->mu * qn;
            if (!(slide & (1u << at)) && ptn > 0.0) g[j] -= (gb_vec_dot(pt, q) - pn * 0.0 - qn * gb_vec_dot(pt, c->normal)) / ptn;
        }
        /* cut: keep {gᵀ (z' − z) ≥ 0} */
        double Eg[3] = {0, 0, 0}, gEg = 0.0;
        for (int i = 0; i < dim; i++)
            for (int j = 0; j < dim; j++) Eg[i] += E[i][j] * g[j];
        for (int i = 0; i < dim; i++) gEg += g[i] * Eg[i];
        if (!(gEg > 0.0)) break; /* the gradient vanishes: the optimum */
        const double root = sqrt(gEg);
        if (dim == 1) {
            z[0] += 0.5 * Eg[0] / root; /* the interval's half towards the slope */
            E[0][0] *= 0.25;
            continue;
        }
        const double nd = (double)dim;
        for (int i = 0; i < dim; i++) z[i] += Eg[i] / ((nd + 1.0) * root);
        for (int i = 0; i < dim; i++)
            for (int j = 0; j < dim; j++)
                E[i][j] = nd * nd / (nd * nd - 1.0) * (E[i][j] - 2.0 / (nd + 1.0) * Eg[i] * Eg[j] / gEg);
    }
    shifted(c, (const double(*)[3])P, open, best_z, Q);
    memcpy(P, Q, sizeof Q[0] * (size_t)c->count);
}

/* The velocities after impulses P: each point's. */
static void after(const coulomb *c, const double (*P)[3], const double v[3], const double omega[3], double v_out[3],
                  double omega_out[3], double (*u)[3])
{
    gb_impact_apply(c->body, (const double(*)[3])c->inv, c->points, c->count, P, v, omega, v_out, omega_out);
    for (int k = 0; k < c->count; k++) gb_impact_point_velocity(v_out, omega_out, c->points[k], u[k]);
}

/* A sliding contact's mismatch at the angles: (d × u_t⁺)·n, and its alignment d·u_t⁺ (> 0 when it slides
 * against the friction). */
static int mismatch(const coulomb *c, unsigned mask, unsigned slide, const double *angle, const double v[3],
                    const double omega[3], double *res, double *align)
{
    double P[GB_IMPACT_CONTACTS_MAX][3], v1[3], w1[3], u[GB_IMPACT_CONTACTS_MAX][3];
    if (coulomb_solve(c, mask, slide, angle, P, NULL)) return 1;
    after(c, (const double(*)[3])P, v, omega, v1, w1, u);
    int n = 0;
    for (int k = 0; k < c->count; k++) {
        if (!(slide & (1u << k))) continue;
        double d[3], dxu[3];
        direction(c, angle[k], d);
        gb_vec_cross(d, u[k], dxu);
        res[n] = gb_vec_dot(dxu, c->normal), align[n] = gb_vec_dot(d, u[k]);
        n++;
    }
    return 0;
}

/* The law's signs for a solution: held impulses push, sticking ones inside the cone, sliding ones slide
 * against it, the others do not approach. 1 when every sign holds. */
static int feasible(const coulomb *c, unsigned mask, unsigned slide, const double *angle, const double (*P)[3],
                    const double (*u)[3], double velocity_tol, double impulse_tol)
{
    const int hold = isinf(impulse_tol); /* gb_impact_coulomb_hold: every point held, a pull allowed */
    for (int k = 0; k < c->count; k++) {
        const double pn = gb_vec_dot(P[k], c->normal), un = gb_vec_dot(u[k], c->normal);
        if (!(mask & (1u << k))) {
            if (un - c->floor[k] < -velocity_tol) return 0;
            continue;
        }
        if (pn < -impulse_tol) return 0;
        if (c->exact > 0.0) {
            const double miss_n = un - c->target[k], miss_t = hypot(gb_vec_dot(u[k], c->t1), gb_vec_dot(u[k], c->t2));
            if (fabs(miss_n) > c->exact || (!(slide & (1u << k)) && miss_t > c->exact)) return 0;
        }
        const double pt[3] = {P[k][0] - pn * c->normal[0], P[k][1] - pn * c->normal[1], P[k][2] - pn * c->normal[2]};
        const double bound = c->mu * (hold ? fabs(pn) : fmax(pn, 0.0)) * (1.0 + 1e-9);
        if (slide & (1u << k)) {
            double d[3];
            direction(c, angle[k], d);
            if (!(gb_vec_dot(d, u[k]) > velocity_tol)) return 0;
        } else if (gb_vec_norm(pt) > bound + (hold ? 0.0 : impulse_tol)) {
            return 0;
        }
    }
    return 1;
}

/* Newton on the sliding contacts' angles from `angle` (k sliding, k ≤ 3): 1 when it converged. */
static int newton_angles(const coulomb *c, unsigned mask, unsigned slide, double *angle, const double v[3],
                         const double omega[3], double velocity_scale)
{
    int idx[GB_IMPACT_CONTACTS_MAX], n = 0;
    for (int k = 0; k < c->count; k++)
        if (slide & (1u << k)) idx[n++] = k;
    for (int it = 0; it < 60; it++) {
        double r[GB_IMPACT_CONTACTS_MAX], al[GB_IMPACT_CONTACTS_MAX], J[3][3], step[3];
        if (mismatch(c, mask, slide, angle, v, omega, r, al)) return 0;
        double worst = 0.0;
        for (int i = 0; i < n; i++) worst = fmax(worst, fabs(r[i]));
        if (worst <= 1e-14 * velocity_scale) return 1;
        for (int j = 0; j < n; j++) {
            const double keep = angle[idx[j]], dh = 1e-7;
            double rp[GB_IMPACT_CONTACTS_MAX], ap[GB_IMPACT_CONTACTS_MAX];
            angle[idx[j]] = keep + dh;
            const int bad = mismatch(c, mask, slide, angle, v, omega, rp, ap);
            angle[idx[j]] = keep;
            if (bad) return 0;
            for (int i = 0; i < n; i++) J[i][j] = (rp[i] - r[i]) / dh;
        }
        /* solve J step = −r (n ≤ 3) by Gaussian elimination with partial pivoting */
        double M[3][4];
        for (int i = 0; i < n; i++) {
            for (int j = 0; j < n; j++) M[i][j] = J[i][j];
            M[i][n] = -r[i];
        }
        for (int col = 0; col < n; col++) {
            int piv = col;
            for (int i = col + 1; i < n; i++)
                if (fabs(M[i][col]) > fabs(M[piv][col])) piv = i;
            if (!(fabs(M[piv][col]) > 0.0)) return 0;
            for (int j = 0; j <= n; j++) {
                const double tmp = M[col][j];
                M[col][j] = M[piv][j], M[piv][j] = tmp;
            }
            for (int i = col + 1; i < n; i++) {
                const double f = M[i][col] / M[col][col];
                for (int j = col; j <= n; j++) M[i][j] -= f * M[col][j];
            }
        }
        for (int i = n - 1; i >= 0; i--) {
            double sum = M[i][n];
            for (int j = i + 1; j < n; j++) sum -= M[i][j] * step[j];
            step[i] = sum / M[i][i];
        }
        for (int j = 0; j < n; j++) angle[idx[j]] += fmax(-0.5, fmin(0.5, step[j]));
    }
    return 0;
}

/* Moreau with the cone over the held contacts `mask`: every split into sticking and sliding, sticking first,
 * a sliding contact's direction by Newton from the sticking solution's and from a grid of starts, the internal
 * impulses (which change no velocity) deepest inside the cones. The first split that satisfies the law's
 * signs (impulse_tol INFINITY: every point held, pulls allowed, gb_impact_coulomb_hold) into *out: 1, or 0. */
static int moreau(const coulomb *c, unsigned mask, const double v[3], const double omega[3], double speed, double velocity_tol,
                  double impulse_tol, gb_impact_result *out)
{
    const int size = __builtin_popcount(mask), count = c->count;
    for (int sliding = 0; sliding <= size; sliding++)
        for (unsigned slide = 0; slide < (1u << count); slide++) {
            if ((slide & ~mask) || __builtin_popcount(slide) != sliding) continue;
            double angle[GB_IMPACT_CONTACTS_MAX] = {0};
            int starts = 1;
            const int per = 8;
            for (int q = 0; q < sliding; q++) starts *= per;
            starts += 1;
            for (int start = 0; start < starts; start++) {
                if (sliding) {
                    if (start == 0) {
                        double Ps[GB_IMPACT_CONTACTS_MAX][3];
                        if (coulomb_solve(c, mask, 0u, angle, Ps, NULL)) continue;
                        for (int k = 0; k < count; k++)
                            if (slide & (1u << k)) angle[k] = atan2(-gb_vec_dot(Ps[k], c->t2), -gb_vec_dot(Ps[k], c->t1));
                    } else {
                        int code = start - 1;
                        for (int k = 0; k < count; k++)
                            if (slide & (1u << k)) angle[k] = 2.0 * M_PI * (code % per) / per, code /= per;
                    }
                    if (!newton_angles(c, mask, slide, angle, v, omega, speed + 1e-300)) continue;
                } else if (start > 0) {
                    break;
                }
                internal open;
                double P[GB_IMPACT_CONTACTS_MAX][3], v1[3], w1[3], u[GB_IMPACT_CONTACTS_MAX][3];
                if (coulomb_solve(c, mask, slide, angle, P, &open)) continue;
                deepest(c, mask, slide, P, &open);
                after(c, (const double(*)[3])P, v, omega, v1, w1, u);
                if (!feasible(c, mask, slide, angle, (const double(*)[3])P, (const double(*)[3])u, velocity_tol, impulse_tol))
                    continue;
                memcpy(out->v, v1, sizeof out->v), memcpy(out->omega, w1, sizeof out->omega);
                memset(out->holds, 0, sizeof out->holds), out->friction_needed = 0.0;
                gb_impact_fill(c->normal, count, mask, (const double(*)[3])P, isinf(impulse_tol) ? 0.0 : impulse_tol, out);
                for (int k = 0; k < count; k++) out->slides[k] = (slide >> k) & 1;
                out->stages = 1;
                return 1;
            }
        }
    return 0;
}

/* The setup both entries share: the body, the points' velocities before and their normal targets. */
static int coulomb_setup(coulomb *c, double inv[3][3], double t1[3], double t2[3], const gb_impact_body *body,
                         const double normal[3], double e, double mu, const double (*points)[3], int count, const double v[3],
                         const double omega[3], gb_impact_result *out, double *speed)
{
    memset(out, 0, sizeof *out);
    int status = gb_impact_check_body(body, count, inv);
    if (!status) status = gb_impact_restitution_check(e);
    if (!status) status = gb_impact_friction_check(mu);
    if (status) return status;
    gb_impact_tangents(normal, t1, t2);
    *c = (coulomb){body, (const double(*)[3])inv, normal, t1, t2, points, count, mu, {{0}}, {0}, {0}, 0};
    *speed = 0.0;
    for (int k = 0; k < count; k++) {
        gb_impact_point_velocity(v, omega, points[k], c->before[k]);
        const double un = gb_vec_dot(c->before[k], normal);
        c->target[k] = -e * fmin(un, 0.0);
        *speed = fmax(*speed, gb_vec_norm(c->before[k]));
        for (int i = 0; i < 3; i++) out->slip_before[k][i] = c->before[k][i] - un * normal[i];
    }
    out->energy_before = gb_impact_energy(body, v, omega);
    return GB_OK;
}

/* The slips after and the energy after, from the result's velocities. */
static void coulomb_finish(const gb_impact_body *body, const double normal[3], const double (*points)[3], int count,
                           gb_impact_result *out)
{
    for (int k = 0; k < count; k++) {
        double u1[3];
        gb_impact_point_velocity(out->v, out->omega, points[k], u1);
        const double un = gb_vec_dot(u1, normal);
        for (int i = 0; i < 3; i++) out->slip_after[k][i] = u1[i] - un * normal[i];
    }
    out->energy_after = gb_impact_energy(body, out->v, out->omega);
}

int gb_impact_coulomb_hold(const gb_impact_body *body, const double normal[3], double mu, const double (*points)[3], int count,
                           const double v[3], const double omega[3], gb_impact_result *out)
{
    double inv[3][3], t1[3], t2[3], speed;
    coulomb c;
    int status = coulomb_setup(&c, inv, t1, t2, body, normal, 0.0, mu, points, count, v, omega, out, &speed);
    if (status) return status;
    if (!moreau(&c, (1u << count) - 1u, v, omega, speed, GB_IMPACT_SIGN_TOL * (speed + 1e-300), INFINITY, out))
        return gb_error_set(GB_ENUMERIC, "impact: no split into sticking and sliding holds all %d points at rest in the "
                            "normal direction within Coulomb's cone (mu %g)", count, mu);
    out->feasible_sets = 1;
    coulomb_finish(body, normal, points, count, out);
    return GB_OK;
}

int gb_impact_coulomb(const gb_impact_body *body, const double normal[3], double e, double mu, const double (*points)[3],
                      int count, const double v[3], const double omega[3], gb_impact_result *out)
{
    if (isinf(mu) && mu > 0.0) return gb_impact_solve(body, normal, e, points, count, v, omega, out);
    double inv[3][3], t1[3], t2[3], speed;
    coulomb c;
    int status = coulomb_setup(&c, inv, t1, t2, body, normal, e, mu, points, count, v, omega, out, &speed);
    if (status) return status;
    const double velocity_tol = GB_IMPACT_SIGN_TOL * (speed + 1e-300), impulse_tol = GB_IMPACT_SIGN_TOL * body->mass * (speed + 1e-300);
    /* the sets by size, the smallest first; within a size by index; the first that satisfies the law */
    int found = 0;
    for (int wanted = 0; wanted <= count && !found; wanted++)
    for (unsigned mask = 0; mask < (1u << count) && !found; mask++) {
        const int size = __builtin_popcount(mask);
        if (size != wanted) continue;
        double P[GB_IMPACT_CONTACTS_MAX][3] = {{0}}, v1[3], w1[3], u[GB_IMPACT_CONTACTS_MAX][3];
        if (size <= 1) {
            /* no impulse, or one point by Darboux–Keller: no point approaches after (the struck one leaves at
             * −e u_n⁻ ≥ 0). A single point that Darboux–Keller leaves with another approaching is tried by
             * Moreau's law below (the two differ only in how the slip evolves inside the impact). */
            gb_impact_result one;
            memset(&one, 0, sizeof one);
            int k = 0, dk_ok = 1;
            while (size == 1 && !(mask & (1u << k))) k++;
            if (size == 1) {
                if (!(gb_vec_dot(c.before[k], normal) < -velocity_tol)) continue;
                dk_ok = !gb_impact_coulomb_point(body, normal, e, mu, points[k], v, omega, &one);
                if (dk_ok) memcpy(P[k], one.impulse[0], sizeof P[k]);
            }
            if (dk_ok) {
                after(&c, (const double(*)[3])P, v, omega, v1, w1, u);
                dk_ok = feasible(&c, 0u, 0u, NULL, (const double(*)[3])P, (const double(*)[3])u, velocity_tol, impulse_tol);
            }
            if (dk_ok) {
                out->feasible_sets++;
                found = 1;
                memcpy(out->v, v1, sizeof out->v), memcpy(out->omega, w1, sizeof out->omega);
                gb_impact_fill(normal, count, mask, (const double(*)[3])P, impulse_tol, out);
                out->stages = one.stages;
                if (size == 1) out->slides[k] = one.slides[0];
                continue;
            }
            if (size == 0) continue;
        }
        if (moreau(&c, mask, v, omega, speed, velocity_tol, impulse_tol, out)) found = 1, out->feasible_sets++;
    }
    if (!found)
        return gb_error_set(GB_ENUMERIC, "impact: no set of contacts satisfies Moreau's law with Coulomb's cone (%d points, "
                            "mu %g)", count, mu);
    coulomb_finish(body, normal, points, count, out);
    return GB_OK;
}

int gb_impact_coulomb_targets(const gb_impact_body *body, const double normal[3], double mu, const double (*points)[3],
                              int count, const double v[3], const double omega[3], const double *target,
                              double tolerance, gb_impact_result *out)
{
    double inv[3][3], t1[3], t2[3], speed;
    coulomb c;
    int status = coulomb_setup(&c, inv, t1, t2, body, normal, 0.0, mu, points, count, v, omega, out, &speed);
    if (status) return status;
    for (int k = 0; k < count; k++) {
        if (!isfinite(target[k])) return gb_error_set(GB_EDOM, "impact: target %d is %g (allowed: finite)", k, target[k]);
        c.target[k] = c.floor[k] = target[k];
        speed = fmax(speed, fabs(target[k]));
    }
    if (!(tolerance > 0.0 && tolerance < 1.0))
        return gb_error_set(GB_EDOM, "impact: tolerance %g (allowed: 0 < tolerance < 1)", tolerance);
    c.exact = tolerance * (speed + 1e-300);
    const double velocity_tol = GB_IMPACT_SIGN_TOL * (speed + 1e-300), impulse_tol = GB_IMPACT_SIGN_TOL * body->mass * (speed + 1e-300);
    /* the sets by size, the smallest first (none: every point keeps its velocity), within a size by index */
    int found = 0;
    for (int wanted = 0; wanted <= count && !found; wanted++)
        for (unsigned mask = 0; mask < (1u << count) && !found; mask++)
            if (__builtin_popcount(mask) == wanted && moreau(&c, mask, v, omega, speed, velocity_tol, impulse_tol, out))
                found = 1, out->feasible_sets++;
    if (!found)
        return gb_error_set(GB_ENUMERIC, "no set of contacts satisfies Moreau's law with Coulomb's cone at the velocity "
                            "level (%d points, mu %g)", count, mu);
    coulomb_finish(body, normal, points, count, out);
    return GB_OK;
}
