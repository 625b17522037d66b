/* gb_dynamics_sliding — the mode "sliding" of a plane of finite friction (docs/friction.md): the body on one
 * or two points, at least one of them slipping, by Newton–Euler with each point's constraint: a sticking
 * point's material point has the rolling contact's acceleration and takes any force inside the cone; a
 * slipping point keeps only its height on the plane and takes the force N (z_b − μ s) against its slip s.
 * The centroid's horizontal velocity is the body's own here (the state integrates it). The mode ends at a
 * slip's stop, a sticking point's force at the cone's edge, a normal force reaching 0 or a new point
 * reaching the plane (gb_dynamics_events.c; the jumps in gb_dynamics_slips.c). Also here: the forces'
 * solver and the cone's margins the sticking modes' slip events use. */
#include "gb_dynamics_internal.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <gsl/gsl_linalg.h>
#include <math.h>
#include <string.h>

void gb_dyn_slip_of(const double y[GB_STATE_SIZE], const double zb[3], const double r[3], double slip[3])
{
    double R[9], v[3], w[3];
    gb_dynamics_rotation(y + GB_STATE_Q, R);
    for (int i = 0; i < 3; i++) /* Rᵀ V: the centroid's velocity in body axes */
        v[i] = R[i] * y[GB_STATE_VELOCITY] + R[3 + i] * y[GB_STATE_VELOCITY + 1] + R[6 + i] * y[GB_STATE_VELOCITY + 2];
    gb_vec_cross(y + GB_STATE_OMEGA, r, w);
    for (int i = 0; i < 3; i++) v[i] += w[i];
    const double n = gb_vec_dot(v, zb);
    for (int i = 0; i < 3; i++) slip[i] = v[i] - n * zb[i];
}

double gb_dyn_one_point_margin(const gb_dynamics *d, double geff, const double zb[3], const double omega[3],
                               const double omega_dot[3], const gb_dyn_contact *c)
{
    const double m = d->def.mass;
    double acc[3], F[3];
    const double N = gb_dyn_normal_force(d, geff, zb, omega, omega_dot, c, acc);
    for (int k = 0; k < 3; k++) F[k] = m * (acc[k] + geff * zb[k]) - N * zb[k]; /* the tangential force */
    return d->def.friction * N - gb_vec_norm(F);
}

/* μ N − |T + λ u| for one point of the crease at the split λ. */
static double point_margin(double mu, double normal, const double tangent[3], double lambda, const double u[3])
{
    const double t[3] = {tangent[0] + lambda * u[0], tangent[1] + lambda * u[1], tangent[2] + lambda * u[2]};
    return mu * normal - gb_vec_norm(t);
}

double gb_dyn_crease_margin(double mu, const double normal[2], const double tangent[2][3], const double u[3], int *alone)
{
    /* P takes T_P + λ u, Q takes T_Q − λ u; each margin is concave in λ, largest at λ = −T_P·u and at T_Q·u,
     * so the least of the two is largest between them: golden section there. */
    const double mid_p = -gb_vec_dot(tangent[0], u), mid_q = gb_vec_dot(tangent[1], u);
    const double neg_u[3] = {-u[0], -u[1], -u[2]};
    *alone = (point_margin(mu, normal[0], tangent[0], mid_p, u) < 0.0) | (point_margin(mu, normal[1], tangent[1], mid_q, neg_u) < 0.0) << 1;
    double a = fmin(mid_p, mid_q), b = fmax(mid_p, mid_q);
    const double golden = 0.5 * (sqrt(5.0) - 1.0);
    double x1 = b - golden * (b - a), x2 = a + golden * (b - a);
    double f1 = fmin(point_margin(mu, normal[0], tangent[0], x1, u), point_margin(mu, normal[1], tangent[1], x1, neg_u));
    double f2 = fmin(point_margin(mu, normal[0], tangent[0], x2, u), point_margin(mu, normal[1], tangent[1], x2, neg_u));
    for (int it = 0; it < 200 && b - a > 1e-15 * (fabs(a) + fabs(b) + 1e-300); it++) {
        if (f1 < f2) {
            a = x1, x1 = x2, f1 = f2, x2 = a + golden * (b - a);
            f2 = fmin(point_margin(mu, normal[0], tangent[0], x2, u), point_margin(mu, normal[1], tangent[1], x2, neg_u));
        } else {
            b = x2, x2 = x1, f2 = f1, x1 = b - golden * (b - a);
            f1 = fmin(point_margin(mu, normal[0], tangent[0], x1, u), point_margin(mu, normal[1], tangent[1], x1, neg_u));
        }
    }
    return fmax(f1, f2);
}

/* ---------------------------------------------------------------- the forces */

int gb_dyn_friction_solve(const gb_dynamics *d, double t, double geff, const double zb[3], const double omega[3],
                          const gb_dyn_friction_point *points, int count, gb_dyn_friction_forces *out)
{
    enum { MAX = 12 };
    const double m = d->def.mass, mu = d->def.friction, c = d->def.damping;
    memset(out, 0, sizeof *out);
    /* The unknowns x = (a_G, ω̇, the sticking points' forces); the slipping points' normal forces N_j are
     * parameters: A x = b_0 + Σ N_j b_j. Rows: Newton m a_G − ΣF = −m g_eff z_b (+ N_j g_j), Euler I ω̇ −
     * Σ r × F = −ω × I ω − c ω (+ N_j r_j × g_j), g_j = z_b − μ s_j; a sticking point's a_G + ω̇ × r = κ, κ =
     * ω × (r × ω) + ṙ × ω (the rolling contact's acceleration). */
    int sticking = 0, slipping = 0, slip_index[2] = {0, 0};
    for (int k = 0; k < count; k++) {
        if (points[k].slides) slip_index[slipping++] = k;
        else sticking++;
    }
    const size_t n = (size_t)(6 + 3 * sticking);
    double A[MAX * MAX] = {0}, b[3][MAX] = {{0}}, kappa[2][3], g[2][3], Iw[3], gyro[3];
    for (int k = 0; k < count; k++) {
        double rw[3], wrw[3], rdw[3];
        gb_vec_cross(points[k].r, omega, rw);
        gb_vec_cross(omega, rw, wrw);
        gb_vec_cross(points[k].rdot, omega, rdw);
        for (int i = 0; i < 3; i++) kappa[k][i] = wrw[i] + rdw[i], g[k][i] = zb[i] - mu * points[k].slip[i];
    }
    gb_dyn_mat_vec((double(*)[3])d->inertia, omega, Iw);
    gb_vec_cross(omega, Iw, gyro);
    for (int i = 0; i < 3; i++) {
        A[i * n + i] = m;
        b[0][i] = -m * geff * zb[i];
        for (int j = 0; j < 3; j++) A[(3 + i) * n + 3 + j] = d->inertia[i][j];
        b[0][3 + i] = -gyro[i] - c * omega[i];
    }
    for (int q = 0; q < slipping; q++) {
        const int k = slip_index[q];
        double rg[3];
        gb_vec_cross(points[k].r, g[k], rg);
        for (int i = 0; i < 3; i++) b[1 + q][i] = g[k][i], b[1 + q][3 + i] = rg[i];
    }
    size_t col = 6;
    for (int k = 0; k < count; k++) {
        if (points[k].slides) continue;
        const double *r = points[k].r;
        const double rx[3][3] = {{0.0, -r[2], r[1]}, {r[2], 0.0, -r[0]}, {-r[1], r[0], 0.0}};
        const size_t row = col;
        for (int i = 0; i < 3; i++) {
            A[i * n + col + i] = -1.0;                                 /* −F in Newton */
            for (int j = 0; j < 3; j++) A[(3 + i) * n + col + j] = -rx[i][j]; /* −r × F in Euler */
            A[(row + i) * n + i] = 1.0;                                /* a_G */
            for (int j = 0; j < 3; j++) A[(row + i) * n + 3 + j] = -rx[i][j]; /* ω̇ × r = −r × ω̇ */
            b[0][row + i] = kappa[k][i];
        }
        col += 3;
    }
    gsl_matrix_view LU = gsl_matrix_view_array(A, n, n);
    size_t perm_data[MAX];
    gsl_permutation perm = {n, perm_data};
    int sign;
    double x[3][MAX];
    if (gsl_linalg_LU_decomp(&LU.matrix, &perm, &sign))
        return gb_error_set(GB_ENUMERIC, "friction at t = %.9g: the contact's equations are singular", t);
    for (int q = 0; q <= slipping; q++) {
        gsl_vector_view B = gsl_vector_view_array(b[q], n), X = gsl_vector_view_array(x[q], n);
        if (gsl_linalg_LU_solve(&LU.matrix, &perm, &B.vector, &X.vector))
            return gb_error_set(GB_ENUMERIC, "friction at t = %.9g: the contact's equations are singular", t);
    }
    /* each slipping point's normal acceleration, affine in the N: z_b·(a_G + ω̇ × r − κ) = α_0 + K N */
    double alpha[2] = {0, 0}, K[2][2] = {{0, 0}, {0, 0}};
    for (int p = 0; p < slipping; p++) {
        const int k = slip_index[p];
        for (int q = 0; q <= slipping; q++) {
            double wr[3];
            gb_vec_cross(x[q] + 3, points[k].r, wr);
            double a = 0.0;
            for (int i = 0; i < 3; i++) a += zb[i] * (x[q][i] + wr[i] - (q == 0 ? kappa[k][i] : 0.0));
            if (q == 0) alpha[p] = a;
            else K[p][q - 1] = a;
        }
    }
    /* Painlevé: the normal forces have one consistent value only where K is a P-matrix */
    double N[2] = {0, 0};
    if (slipping == 1) {
        if (!(K[0][0] > 0.0))
            return gb_error_set_limit(GB_ENUMERIC, "friction at t = %.9g: Painleve's paradox: the slipping point's normal "
                                      "acceleration falls as its normal force grows (dA/dN = %.3g; mu %g): no consistent or "
                                      "no unique contact force; the rigid model stops here", t, K[0][0], mu);
        N[0] = -alpha[0] / K[0][0];
    } else if (slipping == 2) {
        const double det = K[0][0] * K[1][1] - K[0][1] * K[1][0];
        if (!(K[0][0] > 0.0 && K[1][1] > 0.0 && det > 0.0))
            return gb_error_set_limit(GB_ENUMERIC, "friction at t = %.9g: Painleve's paradox: the slipping points' compliance "
                                      "is not a P-matrix (%.3g, %.3g; det %.3g; mu %g): no consistent or no unique contact "
                                      "forces; the rigid model stops here", t, K[0][0], K[1][1], det, mu);
        N[0] = (-alpha[0] * K[1][1] + alpha[1] * K[0][1]) / det;
        N[1] = (-alpha[1] * K[0][0] + alpha[0] * K[1][0]) / det;
    }
    double sol[MAX];
    for (size_t i = 0; i < n; i++) {
        sol[i] = x[0][i];
        for (int q = 0; q < slipping; q++) sol[i] += N[q] * x[1 + q][i];
    }
    memcpy(out->acc, sol, sizeof out->acc);
    memcpy(out->omega_dot, sol + 3, sizeof out->omega_dot);
    for (int k = 0; k < count; k++) { /* a_P = a_G + ω̇ × r + ω × (ω × r), its tangential part */
        double a[3], b[3], c2[3];
        gb_vec_cross(out->omega_dot, points[k].r, a);
        gb_vec_cross(omega, points[k].r, b);
        gb_vec_cross(omega, b, c2);
        double ap[3];
        for (int i = 0; i < 3; i++) ap[i] = out->acc[i] + a[i] + c2[i];
        const double n = gb_vec_dot(ap, zb);
        for (int i = 0; i < 3; i++) out->slip_acc[k][i] = ap[i] - n * zb[i];
    }
    col = 6;
    for (int k = 0, q = 0; k < count; k++) {
        if (points[k].slides) {
            for (int i = 0; i < 3; i++) out->force[k][i] = N[q] * g[k][i];
            out->normal[k] = N[q++];
            out->margin[k] = mu * out->normal[k];
        } else {
            memcpy(out->force[k], sol + col, sizeof out->force[k]);
            col += 3;
            out->normal[k] = gb_vec_dot(out->force[k], zb);
            double ft[3];
            for (int i = 0; i < 3; i++) ft[i] = out->force[k][i] - out->normal[k] * zb[i];
            out->margin[k] = mu * out->normal[k] - gb_vec_norm(ft);
        }
    }
    return GB_OK;
}

/* ---------------------------------------------------------------- the mode */

double gb_dyn_slip_stop_speed(const gb_dynamics *d, const double y[GB_STATE_SIZE], const double slip[3],
                              const double slip_acc[3])
{
    const gb_forcing *f = &d->def.forcing;
    const double L = d->def.length, g = f->g + fabs(f->a1) + fabs(f->a2);
    const double floor = 1e-6 * (sqrt(g * L) + gb_vec_norm(y + GB_STATE_VELOCITY) + L * gb_vec_norm(y + GB_STATE_OMEGA));
    const double speed = gb_vec_norm(slip);
    if (!(speed > 0.0) || !(d->step > 0.0)) return floor;
    const double along = gb_vec_dot(slip_acc, slip) / speed;
    double across[3];
    for (int i = 0; i < 3; i++) across[i] = slip_acc[i] - along * slip[i] / speed;
    return fmax(floor, gb_vec_norm(across) * d->step / 0.25);
}

/* A slip this small is no slip: 1e-13 of the speeds the body's motion is made of (its size times √(g_max /
 * L) and its centroid's speed), the rounding of a located event's state. */
static double slip_floor(const gb_dynamics *d, const double y[GB_STATE_SIZE])
{
    const gb_forcing *f = &d->def.forcing;
    const double L = d->def.length, g = f->g + fabs(f->a1) + fabs(f->a2);
    return 1e-13 * (sqrt(g * L) + gb_vec_norm(y + GB_STATE_VELOCITY) + L * gb_vec_norm(y + GB_STATE_OMEGA));
}

int gb_dyn_sliding_eval(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dyn_friction_point *points,
                        gb_dyn_friction_forces *f)
{
    const double L = d->def.length, *omega = y + GB_STATE_OMEGA;
    double zb[3], geff, geff_rate, R[9];
    gb_dyn_vertical(y, zb);
    gb_forcing_geff_with_rate(&d->def.forcing, t, &geff, &geff_rate);
    gb_dyn_contact c;
    int status = gb_dyn_contact_at(d, t, zb, omega, &c);
    if (status) return status;
    memcpy(points[0].r, c.rc, sizeof c.rc), memcpy(points[0].rdot, c.rc_dot, sizeof c.rc_dot);
    if (d->slide.count == 2) {
        gb_contact_point q;
        double rate[3];
        status = gb_dyn_second_point(d, zb, &q);
        if (!status) status = gb_dyn_point_rate(d, zb, &q, omega, rate);
        if (status) return status;
        for (int k = 0; k < 3; k++) points[1].r[k] = L * q.rc[k], points[1].rdot[k] = L * rate[k];
    }
    gb_dynamics_rotation(y + GB_STATE_Q, R);
    const double floor = slip_floor(d, y);
    for (int k = 0; k < d->slide.count; k++) {
        points[k].slides = d->slide.slides[k];
        if (!points[k].slides) continue;
        double s[3], ref[3];
        gb_dyn_slip_of(y, zb, points[k].r, s);
        const double speed = gb_vec_norm(s), *w = d->slide.armed[k] ? d->slide.ref[k] : d->slide.start[k];
        for (int i = 0; i < 3; i++) ref[i] = R[i] * w[0] + R[3 + i] * w[1] + R[6 + i] * w[2]; /* into body axes */
        /* the slip's own direction; along the accepted state's where the slip is rounding's size or has turned
         * back against it, so that a step carries the slip smoothly through its stop and the stop's event
         * (the slip against that direction) is located inside the step */
        if (speed > floor && gb_vec_dot(s, ref) > 0.0)
            for (int i = 0; i < 3; i++) points[k].slip[i] = s[i] / speed;
        else
            memcpy(points[k].slip, ref, sizeof ref);
    }
    return gb_dyn_friction_solve(d, t, geff, zb, omega, points, d->slide.count, f);
}

int gb_dyn_sliding_field(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double omega[3], const double zb[3],
                         double geff, double omega_dot[3], double *zeta, gb_dyn_rates *rates)
{
    (void)omega, (void)geff;
    gb_dyn_friction_point points[2];
    gb_dyn_friction_forces f;
    const int status = gb_dyn_sliding_eval(d, t, y, points, &f);
    if (status) return status;
    memcpy(omega_dot, f.omega_dot, sizeof f.omega_dot);
    *zeta = -gb_vec_dot(zb, points[0].r);
    if (rates) {
        gb_dyn_to_inertial(y, f.acc, rates->acc);
        rates->friction_power = 0.0;
        for (int k = 0; k < d->slide.count; k++) {
            if (!points[k].slides) continue;
            double s[3];
            gb_dyn_slip_of(y, zb, points[k].r, s);
            rates->friction_power += gb_vec_dot(f.force[k], s); /* −μ N |s| */
        }
    }
    return GB_OK;
}

void gb_dyn_start_sliding(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], int count, const int slides[2],
                          const double start[2][3])
{
    (void)y;
    d->slide.count = count;
    for (int k = 0; k < 2; k++) {
        d->slide.slides[k] = k < count && slides[k];
        d->slide.armed[k] = 0;
        for (int i = 0; i < 3; i++) d->slide.start[k][i] = start[k][i], d->slide.ref[k][i] = start[k][i];
    }
    if (d->mode != GB_DYN_SLIDING) d->slide.slips++;
    gb_dyn_set_mode(d, GB_DYN_SLIDING, t);
}

/* The accepted state: the points continued (the first by the certificate, as the one-point mode's; a change
 * there is an impact the step's location must have found), the second merged into the first at a crease's
 * end; each slip's direction kept for the stop's event. */
int gb_dyn_sliding_accept(gb_dynamics *d, double t, double y[GB_STATE_SIZE])
{
    double zb[3], R[9];
    gb_dyn_vertical(y, zb);
    gb_contact_point continued, other;
    int found = 0, status;
    if (d->slide.count == 1) {
        status = gb_dyn_competitor(d, t, y, &continued, &other, &found);
        if (!status && found)
            status = gb_error_set_limit(GB_ENUMERIC, "sliding at t = %.9g: a change of contact at the step's end that the "
                                        "step's event location did not find", t);
    } else {
        status = gb_dyn_point_at(d, zb, &d->contact, &continued); /* a third point is an event of its own */
    }
    if (status) return status;
    gb_dyn_set_contact(d, &continued);
    d->memo_valid = 0;
    if (d->slide.count == 2) {
        gb_contact_point q;
        status = gb_dyn_second_point(d, zb, &q);
        if (status) return status;
        const double gap[3] = {q.rc[0] - continued.rc[0], q.rc[1] - continued.rc[1], q.rc[2] - continued.rc[2]};
        if (!q.is_minimum || !(gb_vec_norm(gap) > 1e-9)) { /* the crease's end: on the first point alone */
            d->slide.count = 1;
            d->slide.slides[1] = 0;
        } else {
            d->contact2 = q;
        }
    }
    const int sticks[2] = {!d->slide.slides[0], d->slide.count == 2 && !d->slide.slides[1]};
    status = gb_dyn_hold_velocities(d, y, d->slide.count, sticks);
    if (status) return status;
    gb_dynamics_rotation(y + GB_STATE_Q, R);
    const double floor = slip_floor(d, y);
    gb_dyn_friction_point points[2];
    gb_dyn_friction_forces f;
    status = gb_dyn_sliding_eval(d, t, y, points, &f);
    if (status) return status;
    for (int k = 0; k < d->slide.count; k++) {
        if (!d->slide.slides[k]) continue;
        double s[3];
        gb_dyn_slip_of(y, zb, points[k].r, s);
        const double speed = gb_vec_norm(s);
        if (speed > floor) {
            for (int i = 0; i < 3; i++) d->slide.ref[k][i] = (R[3 * i] * s[0] + R[3 * i + 1] * s[1] + R[3 * i + 2] * s[2]) / speed;
            d->slide.armed[k] = d->slide.armed[k] || speed > 2.0 * gb_dyn_slip_stop_speed(d, y, s, f.slip_acc[k]);
        }
    }
    return gb_dyn_remember_rate(d, t, y);
}

int gb_dyn_sliding_observe(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_observables *o)
{
    gb_dyn_friction_point points[2];
    gb_dyn_friction_forces f;
    const int status = gb_dyn_sliding_eval(d, t, y, points, &f);
    if (status) return status;
    memcpy(o->omega_dot, f.omega_dot, sizeof o->omega_dot);
    memcpy(o->rc, points[0].r, sizeof o->rc);
    memcpy(o->rc_dot, points[0].rdot, sizeof o->rc_dot);
    if (d->slide.count == 2) memcpy(o->rc_other, points[1].r, sizeof o->rc_other);
    o->index = d->index;
    o->height = gb_vec_dot(o->zb, points[0].r);
    o->zeta = -o->height;
    memcpy(o->velocity, y + GB_STATE_VELOCITY, sizeof o->velocity);
    gb_dyn_observe_free_energy(d, y, o);
    o->contacts = d->slide.count;
    o->normal_force = f.normal[0] + (d->slide.count == 2 ? f.normal[1] : 0.0);
    o->normal_forces[0] = f.normal[0], o->normal_forces[1] = d->slide.count == 2 ? f.normal[1] : 0.0;
    o->friction_needed = d->def.friction;
    o->sliding = 0, o->slip_speed = 0.0;
    for (int k = 0; k < d->slide.count; k++) {
        double s[3];
        gb_dyn_slip_of(y, o->zb, points[k].r, s);
        o->sliding += d->slide.slides[k];
        if (d->slide.slides[k]) o->slip_speed = fmax(o->slip_speed, gb_vec_norm(s));
    }
    return GB_OK;
}

/* The height and the vertical velocity follow the attitude (the first point on the plane: ζ = −z_b·r, ζ̇ =
 * z_b·(r × ω)); the horizontal velocity is the state's own. */
void gb_dyn_sliding_translate(const gb_dynamics *d, double t, double y[GB_STATE_SIZE])
{
    (void)t;
    double zb[3], r[3], rw[3];
    gb_dyn_vertical(y, zb);
    const double L = d->def.length;
    for (int k = 0; k < 3; k++) r[k] = L * d->contact.rc[k];
    gb_vec_cross(r, y + GB_STATE_OMEGA, rw);
    y[GB_STATE_ZETA] = -gb_vec_dot(zb, r);
    y[GB_STATE_VELOCITY + 2] = gb_vec_dot(zb, rw);
}

void gb_dynamics_sliding_stats(const gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_sliding_summary *out)
{
    const int sliding = d->mode == GB_DYN_SLIDING;
    out->time = gb_dyn_mode_time(d, GB_DYN_SLIDING, t);
    out->slips = d->slide.slips;
    out->sticks = d->slide.sticks;
    out->friction_loss = y ? 0.0 - y[GB_STATE_FRICTION] : 0.0;
    out->sliding = sliding;
}

/* ---------------------------------------------------------------- the constraints held at velocity level */

static double kinetic(const gb_dynamics *d, const double y[GB_STATE_SIZE])
{
    double Iw[3];
    gb_dyn_mat_vec((double(*)[3])d->inertia, y + GB_STATE_OMEGA, Iw);
    return 0.5 * d->def.mass * gb_vec_dot(y + GB_STATE_VELOCITY, y + GB_STATE_VELOCITY) + 0.5 * gb_vec_dot(y + GB_STATE_OMEGA, Iw);
}

/* The centroid's velocity of a body turning about the point r [m] at rest: ω × (G − P), in inertial axes. */
static void rolling_velocity(double y[GB_STATE_SIZE], const double r[3])
{
    double vb[3];
    gb_vec_cross(y + GB_STATE_OMEGA, (const double[3]){-r[0], -r[1], -r[2]}, vb);
    gb_dyn_to_inertial(y, vb, y + GB_STATE_VELOCITY);
}

int gb_dyn_hold_velocities(gb_dynamics *d, double y[GB_STATE_SIZE], int count, const int sticks[2])
{
    const double L = d->def.length;
    double zb[3], rp[3], rq[3];
    gb_dyn_vertical(y, zb);
    /* the points at this state (an event's lies inside a step: the accepted contact continued to it) */
    gb_contact_point p, q = d->contact2;
    int status = gb_dyn_point_at(d, zb, &d->contact, &p);
    if (!status && count == 2) status = gb_dyn_second_point(d, zb, &q);
    if (status) return status;
    for (int k = 0; k < 3; k++) rp[k] = L * p.rc[k], rq[k] = L * q.rc[k];
    const double before = kinetic(d, y);
    double *omega = y + GB_STATE_OMEGA;
    gb_impact_body body = {d->def.mass, {{0}}};
    memcpy(body.inertia, d->inertia, sizeof body.inertia);
    const int stuck = sticks[0] + (count == 2 && sticks[1]);
    if (stuck) {
        /* the sticking points held at rest by the plastic impulse that does it (gb_impact_hold_all): the slip
         * the stop left goes as friction would have taken it, through the body's inertia */
        double R[9], v[3], held[2][3];
        int n = 0;
        if (sticks[0]) memcpy(held[n++], rp, sizeof rp);
        if (count == 2 && sticks[1]) memcpy(held[n++], rq, sizeof rq);
        gb_dynamics_rotation(y + GB_STATE_Q, R);
        for (int i = 0; i < 3; i++) /* Rᵀ V */
            v[i] = R[i] * y[GB_STATE_VELOCITY] + R[3 + i] * y[GB_STATE_VELOCITY + 1] + R[6 + i] * y[GB_STATE_VELOCITY + 2];
        gb_impact_result r;
        status = gb_impact_hold_all(&body, zb, (const double(*)[3])held, n, v, omega, &r);
        if (status) return status;
        memcpy(omega, r.omega, sizeof r.omega);
        gb_dyn_to_inertial(y, r.v, y + GB_STATE_VELOCITY);
    }
    if (count == 2 && stuck < 2) {
        /* both on the plane: ω on z_b·(ω × (r_Q − r_P)) = 0, the least change in I's metric, the sticking
         * point (if any) kept at rest */
        double c[3], Ic[3], I[3][3];
        const double dq[3] = {rq[0] - rp[0], rq[1] - rp[1], rq[2] - rp[2]};
        gb_vec_cross(dq, zb, c);
        memcpy(I, d->inertia, sizeof I);
        if (!gb_dyn_solve3(I, c, Ic)) {
            const double scale = gb_vec_dot(c, omega) / gb_vec_dot(c, Ic);
            for (int k = 0; k < 3; k++) omega[k] -= scale * Ic[k];
        }
        gb_error_clear();
        if (stuck) rolling_velocity(y, sticks[0] ? rp : rq);
    }
    d->impact_loss += before - kinetic(d, y); /* what the hold took: rounding's size, booked so the ledger closes */
    return GB_OK;
}
