/* gb_impact — Moreau's impact law for a rigid body on a rough plane (gb_impact.h). */
#include "gb_impact_internal.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <gsl/gsl_linalg.h>
#include <math.h>
#include <string.h>


double gb_impact_energy(const gb_impact_body *body, const double v[3], const double omega[3])
{
    double spin = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) spin += omega[i] * body->inertia[i][j] * omega[j];
    return 0.5 * body->mass * gb_vec_dot(v, v) + 0.5 * spin;
}

/* The inverse of a symmetric positive definite 3×3 matrix (adjugate over determinant): 0, or 1 when it
 * is not positive definite. */
int gb_impact_invert(const double a[3][3], double out[3][3])
{
    const double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1], c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2],
                 c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
    const double det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
    if (!(det > 0.0 && a[0][0] > 0.0 && a[0][0] * a[1][1] - a[0][1] * a[1][0] > 0.0)) return 1;
    out[0][0] = c00 / det, out[1][0] = c01 / det, out[2][0] = c02 / det;
    out[0][1] = (a[0][2] * a[2][1] - a[0][1] * a[2][2]) / det;
    out[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) / det;
    out[2][1] = (a[0][1] * a[2][0] - a[0][0] * a[2][1]) / det;
    out[0][2] = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) / det;
    out[1][2] = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) / det;
    out[2][2] = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) / det;
    return 0;
}

void gb_impact_cross_matrix(const double r[3], double out[3][3])
{
    const double m[3][3] = {{0.0, -r[2], r[1]}, {r[2], 0.0, -r[0]}, {-r[1], r[0], 0.0}};
    memcpy(out, m, sizeof m);
}

/* The velocities after impulses P[k] at the points: v⁺ = v⁻ + ΣP/m, ω⁺ = ω⁻ + I⁻¹ Σ r × P. */
void gb_impact_apply(const gb_impact_body *body, const double inv[3][3], const double (*points)[3], int count,
                  const double (*P)[3], const double v[3], const double omega[3], double v_out[3], double omega_out[3])
{
    double total[3] = {0, 0, 0}, moment[3] = {0, 0, 0};
    for (int k = 0; k < count; k++) {
        double m[3];
        gb_vec_cross(points[k], P[k], m);
        for (int i = 0; i < 3; i++) total[i] += P[k][i], moment[i] += m[i];
    }
    for (int i = 0; i < 3; i++) {
        v_out[i] = v[i] + total[i] / body->mass;
        omega_out[i] = omega[i] + inv[i][0] * moment[0] + inv[i][1] * moment[1] + inv[i][2] * moment[2];
    }
}

void gb_impact_point_velocity(const double v[3], const double omega[3], const double r[3], double u[3])
{
    double w[3];
    gb_vec_cross(omega, r, w);
    for (int i = 0; i < 3; i++) u[i] = v[i] + w[i];
}

void gb_impact_delassus(const gb_impact_body *body, const double inv[3][3], const double r_k[3], const double r_j[3],
                        double out[3][3])
{
    double rk[3][3], rj[3][3], left[3][3] = {{0}};
    gb_impact_cross_matrix(r_k, rk);
    gb_impact_cross_matrix(r_j, rj);
    for (int i = 0; i < 3; i++) /* [r_k]× I⁻¹ */
        for (int j = 0; j < 3; j++)
            for (int l = 0; l < 3; l++) left[i][j] += rk[i][l] * inv[l][j];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double term = 0.0;
            for (int l = 0; l < 3; l++) term += left[i][l] * rj[l][j];
            out[i][j] = (i == j ? 1.0 / body->mass : 0.0) - term;
        }
}

void gb_impact_tangents(const double n[3], double t1[3], double t2[3])
{
    const double pick[3] = {fabs(n[0]) < 0.6 ? 1.0 : 0.0, fabs(n[0]) < 0.6 ? 0.0 : 1.0, 0.0};
    gb_vec_cross(n, pick, t1);
    const double n1 = gb_vec_norm(t1);
    for (int i = 0; i < 3; i++) t1[i] /= n1;
    gb_vec_cross(n, t1, t2);
}

int gb_impact_min_norm(double *a, const double *b, size_t size, double *x, double *v_data, double *s_data)
{
    double w_copy[GB_IMPACT_SYSTEM_MAX * GB_IMPACT_SYSTEM_MAX], work_data[GB_IMPACT_SYSTEM_MAX], y[GB_IMPACT_SYSTEM_MAX];
    memcpy(w_copy, a, size * size * sizeof a[0]);
    gsl_matrix_view A = gsl_matrix_view_array(a, size, size), V = gsl_matrix_view_array(v_data, size, size);
    gsl_vector_view S = gsl_vector_view_array(s_data, size), work = gsl_vector_view_array(work_data, size);
    if (gsl_linalg_SV_decomp(&A.matrix, &V.matrix, &S.vector, &work.vector)) return 1;
    const double cut = GB_IMPACT_SINGULAR_CUT * s_data[0];
    for (size_t i = 0; i < size; i++) { /* y = S⁺ Uᵀ b */
        double dot = 0.0;
        for (size_t r = 0; r < size; r++) dot += a[r * size + i] * b[r];
        y[i] = s_data[i] > cut ? dot / s_data[i] : 0.0;
    }
    for (size_t r = 0; r < size; r++) {
        x[r] = 0.0;
        for (size_t i = 0; i < size; i++) x[r] += v_data[r * size + i] * y[i];
    }
    double residual = 0.0, scale = 0.0;
    for (size_t r = 0; r < size; r++) {
        double row = 0.0;
        for (size_t c = 0; c < size; c++) row += w_copy[r * size + c] * x[c];
        residual = fmax(residual, fabs(row - b[r]));
        scale = fmax(scale, fabs(b[r]));
    }
    return residual > GB_IMPACT_RESIDUAL_TOL * scale + 1e-300;
}

/* The impulses at the held contacts (mask) that give them the velocity target[k]: the Delassus system
 * W P = target − u⁻, W_kj = I/m − [r_k]× I⁻¹ [r_j]×, by SVD (minimum norm where W is singular). 0, or 1
 * when the system has no solution (its residual exceeds GB_IMPACT_RESIDUAL_TOL of its scale). */
int gb_impact_held(const gb_impact_body *body, const double inv[3][3], const double (*points)[3], int count,
                         unsigned mask, const double (*rhs)[3], double (*P)[3])
{
    int held[GB_IMPACT_CONTACTS_MAX], n = 0;
    for (int k = 0; k < count; k++)
        if (mask & (1u << k)) held[n++] = k;
    const size_t size = (size_t)(3 * n);
    double a[9 * GB_IMPACT_CONTACTS_MAX * GB_IMPACT_CONTACTS_MAX], b[3 * GB_IMPACT_CONTACTS_MAX] = {0};
    for (int p = 0; p < n; p++) {
        for (int q = 0; q < n; q++) {
            double block[3][3];
            gb_impact_delassus(body, inv, points[held[p]], points[held[q]], block);
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++) a[(3 * p + i) * size + 3 * q + j] = block[i][j];
        }
        for (int i = 0; i < 3; i++) b[3 * p + i] = rhs[held[p]][i];
    }
    double x[3 * GB_IMPACT_CONTACTS_MAX], v_data[9 * GB_IMPACT_CONTACTS_MAX * GB_IMPACT_CONTACTS_MAX], s_data[3 * GB_IMPACT_CONTACTS_MAX];
    if (gb_impact_min_norm(a, b, size, x, v_data, s_data)) return 1;
    for (int k = 0; k < count; k++) memset(P[k], 0, sizeof P[k]);
    for (int p = 0; p < n; p++)
        for (int i = 0; i < 3; i++) P[held[p]][i] = x[3 * p + i];
    return 0;
}

/* The body's inverse inertia, and the count of points, checked. */
int gb_impact_check_body(const gb_impact_body *body, int count, double inv[3][3])
{
    if (!(body->mass > 0.0) || gb_impact_invert(body->inertia, inv))
        return gb_error_set(GB_EDOM, "impact: mass %g, inertia not positive definite (allowed: mass > 0, a positive definite "
                            "inertia about the centroid)", body->mass);
    if (count < 1 || count > GB_IMPACT_CONTACTS_MAX)
        return gb_error_set(GB_EDOM, "impact: %d contact points (allowed: 1 to %d)", count, GB_IMPACT_CONTACTS_MAX);
    return GB_OK;
}

/* The result's impulses, their normal and tangential parts and the friction they need, from P. */
void gb_impact_fill(const double normal[3], int count, unsigned mask, const double (*P)[3], double impulse_tol,
                          gb_impact_result *out)
{
    for (int k = 0; k < count; k++) {
        out->holds[k] = (mask >> k) & 1;
        memcpy(out->impulse[k], P[k], sizeof out->impulse[k]);
        out->normal_impulse[k] = gb_vec_dot(P[k], normal);
        double tangential[3];
        for (int i = 0; i < 3; i++) tangential[i] = P[k][i] - out->normal_impulse[k] * normal[i];
        out->tangential_impulse[k] = gb_vec_norm(tangential);
        if (out->holds[k] && out->normal_impulse[k] > impulse_tol)
            out->friction_needed = fmax(out->friction_needed, out->tangential_impulse[k] / out->normal_impulse[k]);
    }
}

/* The distinct points of `points` (GB_IMPACT_SAME_POINT): their number, the points in `unique`, and for each
 * point the index of its first twin in `unique`. */
int gb_impact_distinct(const double (*points)[3], int count, double (*unique)[3], int *twin)
{
    double reach = 0.0;
    for (int k = 0; k < count; k++) reach = fmax(reach, gb_vec_norm(points[k]));
    int n = 0;
    for (int k = 0; k < count; k++) {
        twin[k] = -1;
        for (int j = 0; j < n && twin[k] < 0; j++) {
            const double d[3] = {points[k][0] - unique[j][0], points[k][1] - unique[j][1], points[k][2] - unique[j][2]};
            if (gb_vec_norm(d) <= GB_IMPACT_SAME_POINT * reach) twin[k] = j;
        }
        if (twin[k] < 0) memcpy(unique[n], points[k], sizeof unique[n]), twin[k] = n++;
    }
    return n;
}

/* A result over the distinct points spread back over all of them: a point's first twin carries the
 * impulse, every later twin holds as it does with none of its own. */
void gb_impact_spread(const gb_impact_result *reduced, const int *twin, int count, gb_impact_result *out)
{
    *out = *reduced;
    int seen[GB_IMPACT_CONTACTS_MAX] = {0};
    for (int k = 0; k < count; k++) {
        const int j = twin[k], first = !seen[j];
        seen[j] = 1;
        out->holds[k] = reduced->holds[j];
        for (int i = 0; i < 3; i++) out->impulse[k][i] = first ? reduced->impulse[j][i] : 0.0;
        out->normal_impulse[k] = first ? reduced->normal_impulse[j] : 0.0;
        out->tangential_impulse[k] = first ? reduced->tangential_impulse[j] : 0.0;
    }
}

static int hold_all_distinct(const gb_impact_body *body, const double normal[3], const double (*points)[3], int count,
                             const double v[3], const double omega[3], gb_impact_result *out);
static int solve_distinct(const gb_impact_body *body, const double normal[3], double e, const double (*points)[3], int count,
                          const double v[3], const double omega[3], gb_impact_result *out);

int gb_impact_hold_all(const gb_impact_body *body, const double normal[3], const double (*points)[3], int count,
                       const double v[3], const double omega[3], gb_impact_result *out)
{
    double unique[GB_IMPACT_CONTACTS_MAX][3];
    int twin[GB_IMPACT_CONTACTS_MAX];
    if (count < 1 || count > GB_IMPACT_CONTACTS_MAX) return hold_all_distinct(body, normal, points, count, v, omega, out);
    const int n = gb_impact_distinct(points, count, unique, twin);
    if (n == count) return hold_all_distinct(body, normal, points, count, v, omega, out);
    gb_impact_result reduced;
    const int status = hold_all_distinct(body, normal, (const double(*)[3])unique, n, v, omega, &reduced);
    if (!status) gb_impact_spread(&reduced, twin, count, out);
    return status;
}

int gb_impact_restitution_check(double e)
{
    if (e >= 0.0 && e <= GB_IMPACT_RESTITUTION_MAX) return GB_OK;
    return gb_error_set(GB_EDOM, "restitution e = %g is out of range (allowed: 0 <= e <= %g)", e, GB_IMPACT_RESTITUTION_MAX);
}

int gb_impact_solve(const gb_impact_body *body, const double normal[3], double e, const double (*points)[3], int count,
                    const double v[3], const double omega[3], gb_impact_result *out)
{
    double unique[GB_IMPACT_CONTACTS_MAX][3];
    int twin[GB_IMPACT_CONTACTS_MAX];
    if (count < 1 || count > GB_IMPACT_CONTACTS_MAX) return solve_distinct(body, normal, e, points, count, v, omega, out);
    const int n = gb_impact_distinct(points, count, unique, twin);
    if (n == count) return solve_distinct(body, normal, e, points, count, v, omega, out);
    gb_impact_result reduced;
    const int status = solve_distinct(body, normal, e, (const double(*)[3])unique, n, v, omega, &reduced);
    if (!status) gb_impact_spread(&reduced, twin, count, out);
    return status;
}

static int hold_all_distinct(const gb_impact_body *body, const double normal[3], const double (*points)[3], int count,
                             const double v[3], const double omega[3], gb_impact_result *out)
{
    memset(out, 0, sizeof *out);
    double inv[3][3], rhs[GB_IMPACT_CONTACTS_MAX][3], speed = 0.0;
    int status = gb_impact_check_body(body, count, inv);
    if (status) return status;
    for (int k = 0; k < count; k++) {
        gb_impact_point_velocity(v, omega, points[k], rhs[k]);
        speed = fmax(speed, gb_vec_norm(rhs[k]));
        for (int i = 0; i < 3; i++) rhs[k][i] = -rhs[k][i];
    }
    double P[GB_IMPACT_CONTACTS_MAX][3] = {{0}};
    const unsigned all = (1u << count) - 1u;
    if (gb_impact_held(body, inv, points, count, all, (const double(*)[3])rhs, P))
        return gb_error_set(GB_ENUMERIC, "impact: no impulses hold all %d points at rest", count);
    gb_impact_apply(body, inv, points, count, (const double(*)[3])P, v, omega, out->v, out->omega);
    out->energy_before = gb_impact_energy(body, v, omega);
    out->energy_after = gb_impact_energy(body, out->v, out->omega);
    gb_impact_fill(normal, count, all, (const double(*)[3])P, GB_IMPACT_SIGN_TOL * body->mass * (speed + 1e-300), out);
    out->feasible_sets = 1;
    return GB_OK;
}

static int solve_distinct(const gb_impact_body *body, const double normal[3], double e, const double (*points)[3], int count,
                          const double v[3], const double omega[3], gb_impact_result *out)
{
    memset(out, 0, sizeof *out);
    double inv[3][3];
    int status = gb_impact_check_body(body, count, inv);
    if (status) return status;
    status = gb_impact_restitution_check(e);
    if (status) return status;
    /* What each held contact's velocity must become, less what it is: −e u⁻·n n − u⁻. */
    double before[GB_IMPACT_CONTACTS_MAX][3], rhs[GB_IMPACT_CONTACTS_MAX][3];
    double speed = 0.0;
    for (int k = 0; k < count; k++) {
        gb_impact_point_velocity(v, omega, points[k], before[k]);
        const double approach = gb_vec_dot(before[k], normal);
        for (int i = 0; i < 3; i++) rhs[k][i] = -e * fmin(approach, 0.0) * normal[i] - before[k][i];
        speed = fmax(speed, gb_vec_norm(before[k]));
    }
    /* The impact's own scales: a velocity, and the impulse that would stop the mass at that speed. */
    const double velocity_tol = GB_IMPACT_SIGN_TOL * (speed + 1e-300), impulse_tol = GB_IMPACT_SIGN_TOL * body->mass * (speed + 1e-300);
    out->energy_before = gb_impact_energy(body, v, omega);
    int chosen = -1, best_size = GB_IMPACT_CONTACTS_MAX + 1;
    double chosen_P[GB_IMPACT_CONTACTS_MAX][3];
    for (unsigned mask = 0; mask < (1u << count); mask++) {
        double P[GB_IMPACT_CONTACTS_MAX][3] = {{0}};
        if (mask && gb_impact_held(body, inv, points, count, mask, (const double(*)[3])rhs, P)) continue;
        double v_after[3], omega_after[3];
        gb_impact_apply(body, inv, points, count, (const double(*)[3])P, v, omega, v_after, omega_after);
        int feasible = 1, size = 0;
        for (int k = 0; k < count && feasible; k++) {
            if (mask & (1u << k)) {
                size++;
                feasible = gb_vec_dot(P[k], normal) >= -impulse_tol;
            } else {
                double u[3];
                gb_impact_point_velocity(v_after, omega_after, points[k], u);
                feasible = gb_vec_dot(u, normal) >= -velocity_tol;
            }
        }
        if (!feasible) continue;
        out->feasible_sets++;
        if (size < best_size) {
            best_size = size, chosen = (int)mask;
            memcpy(chosen_P, P, sizeof P);
            memcpy(out->v, v_after, sizeof out->v);
            memcpy(out->omega, omega_after, sizeof out->omega);
        }
    }
    if (chosen < 0) return gb_error_set(GB_ENUMERIC, "impact: no set of held contacts satisfies Moreau's law (%d points)", count);
    gb_impact_fill(normal, count, (unsigned)chosen, (const double(*)[3])chosen_P, impulse_tol, out);
    out->energy_after = gb_impact_energy(body, out->v, out->omega);
    return GB_OK;
}

int gb_impact_rough_point(const gb_impact_body *body, const double normal[3], double e, const double point[3],
                          const double v[3], const double omega[3], gb_impact_result *out)
{
    memset(out, 0, sizeof *out);
    double inv[3][3];
    int status = gb_impact_check_body(body, 1, inv);
    if (status) return status;
    status = gb_impact_restitution_check(e);
    if (status) return status;
    /* The Delassus operator of the point: Δu = W P, W = I/m − [r]× I⁻¹ [r]× */
    double rx[3][3], a[3][3], W[3][3];
    gb_impact_cross_matrix(point, rx);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) a[i][j] = inv[i][0] * rx[0][j] + inv[i][1] * rx[1][j] + inv[i][2] * rx[2][j];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            W[i][j] = (i == j) / body->mass - (rx[i][0] * a[0][j] + rx[i][1] * a[1][j] + rx[i][2] * a[2][j]);
    /* a tangent basis t1, t2 of the plane */
    double t1[3], t2[3];
    gb_impact_tangents(normal, t1, t2);
    double u[3], Wt1[3], Wt2[3];
    gb_impact_point_velocity(v, omega, point, u);
    const double speed = gb_vec_norm(u);
    for (int i = 0; i < 3; i++) {
        Wt1[i] = W[i][0] * t1[0] + W[i][1] * t1[1] + W[i][2] * t1[2];
        Wt2[i] = W[i][0] * t2[0] + W[i][1] * t2[1] + W[i][2] * t2[2];
    }
    /* Stage 1, the slip stopped by a tangential impulse (W_tt x = −u_t); stage 2, compression and restitution
     * at no slip, when the point still approaches after stage 1 */
    const double k11 = gb_vec_dot(t1, Wt1), k12 = gb_vec_dot(t1, Wt2), k22 = gb_vec_dot(t2, Wt2);
    const double det = k11 * k22 - k12 * k12, b1 = -gb_vec_dot(t1, u), b2 = -gb_vec_dot(t2, u);
    const double x1 = (k22 * b1 - k12 * b2) / det, x2 = (k11 * b2 - k12 * b1) / det;
    double P[1][3];
    for (int i = 0; i < 3; i++) P[0][i] = x1 * t1[i] + x2 * t2[i];
    const double approach = gb_vec_dot(normal, u) + x1 * gb_vec_dot(normal, Wt1) + x2 * gb_vec_dot(normal, Wt2);
    const double velocity_tol = GB_IMPACT_SIGN_TOL * (speed + 1e-300);
    const int compresses = approach < -velocity_tol;
    if (compresses) {
        /* W P₂ = −(1 + e) u′_n n: the point's velocity becomes −e u′_n n */
        double Winv[3][3], dn[3];
        if (gb_impact_invert(W, Winv)) return gb_error_set(GB_ENUMERIC, "impact: the point's Delassus operator is singular");
        for (int i = 0; i < 3; i++) dn[i] = -(1.0 + e) * approach * normal[i];
        for (int i = 0; i < 3; i++) P[0][i] += Winv[i][0] * dn[0] + Winv[i][1] * dn[1] + Winv[i][2] * dn[2];
    }
    gb_impact_apply(body, inv, (const double(*)[3])&point[0], 1, (const double(*)[3])P, v, omega, out->v, out->omega);
    out->energy_before = gb_impact_energy(body, v, omega);
    out->energy_after = gb_impact_energy(body, out->v, out->omega);
    const double impulse_tol = GB_IMPACT_SIGN_TOL * body->mass * (speed + 1e-300);
    gb_impact_fill(normal, 1, (unsigned)compresses, (const double(*)[3])P, impulse_tol, out);
    if (!compresses && out->tangential_impulse[0] > impulse_tol) out->friction_needed = INFINITY;
    out->feasible_sets = 1;
    return GB_OK;
}
