/* gb_dynamics — the state of the hybrid system (gb_dynamics_internal.h), below every mode: the definition
 * and its defaults, the attitude (quaternion, rotation, vertical), the mode the state is in and the time
 * booked to each, the vector field of the current mode (gb_dyn_field, through the table the state carries),
 * the counters, and the 3 × 3 algebra the modes share. The table itself and the public calls that go
 * through it are gb_dynamics_hybrid.c, above the modes. */
#include "gb_dynamics_internal.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static const char *const variant_names[] = {"paper", "rolling"};

const char *gb_dynamics_variant_name(gb_dynamics_variant v) { return (unsigned)v < 2 ? variant_names[v] : NULL; }

int gb_dynamics_variant_parse(const char *name, gb_dynamics_variant *variant)
{
    int k = 0;
    const int status = gb_error_parse_name(name, variant_names, 2, "equation variant", &k);
    if (!status) *variant = (gb_dynamics_variant)k;
    return status;
}

static const char *const certificate_names[] = {"per-vertical", "atlas", "multi-start"};

const char *gb_dynamics_certificate_name(gb_dynamics_certificate c) { return (unsigned)c < 3 ? certificate_names[c] : NULL; }

int gb_dynamics_certificate_parse(const char *name, gb_dynamics_certificate *certificate)
{
    int k = 0;
    const int status = gb_error_parse_name(name, certificate_names, 3, "contact certificate", &k);
    if (!status) *certificate = (gb_dynamics_certificate)k;
    return status;
}

gb_dynamics_def gb_dynamics_default_def(void)
{
    gb_dynamics_def def = {
        .variant = GB_VARIANT_PAPER,
        .contact = GB_CONTACT_MODEL_FAST_GRID,
        .mass = 1.0,
        .length = 1.0,
        .damping = 0.02,
        .forcing = {.g = 9.81, .a1 = 2.0, .a2 = 1.0, .omega = 18.0, .psi = M_PI / 3.0},
        .grid = gb_contact_grid_default_def(),
        .certify = gb_certify_default_def(),
        .friction = INFINITY,
        .atlas = gb_atlas_default_def(),
        .law_coefficients = {NAN, NAN, NAN, NAN},
    };
    /* Leaves of 16 nodes were the fastest of 8–32 for the patch tree's searches (make bench); the leaf
     * size changes no result, only the work. */
    def.grid.leaf_size = 16;
    return def;
}

void gb_dyn_set_mode(gb_dynamics *d, gb_dyn_mode_id mode, double t)
{
    if (d->mode == mode) return;
    d->mode_time[d->mode] += t - d->mode_since[d->mode];
    d->mode_since[mode] = t;
    d->mode = mode;
}

double gb_dyn_mode_time(const gb_dynamics *d, gb_dyn_mode_id mode, double t)
{
    return d->mode_time[mode] + (d->mode == mode ? t - d->mode_since[mode] : 0.0);
}

const gb_dynamics_def *gb_dynamics_get_def(const gb_dynamics *d) { return &d->def; }

const gb_dynamics_law *gb_dynamics_get_law(const gb_dynamics *d) { return d->law; }

double gb_dyn_coefficient(const gb_dynamics *d, int slot)
{
    const double value = d->def.law_coefficients[slot];
    if (!isnan(value)) return value;
    for (size_t k = 0; k < d->law->key_count; k++)
        if (d->law->keys[k].slot == slot) return d->law->keys[k].fallback;
    return NAN;
}

double gb_dynamics_mean_radius(const gb_dynamics *d) { return d->mean_radius; }

/* ---------------------------------------------------------------- attitude */

/* z_b = Rᵀ e_z, the third row of R (eq 21), alone: the same arithmetic as gb_dynamics_rotation's. */
void gb_dyn_vertical_of_quaternion(const double q[4], double zb[3])
{
    const double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    zb[0] = 2 * (x * z - w * y), zb[1] = 2 * (y * z + w * x), zb[2] = 1 - 2 * (x * x + y * y);
}

void gb_dynamics_rotation(const double q[4], double R[9])
{
    const double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    R[0] = 1 - 2 * (y * y + z * z), R[1] = 2 * (x * y - w * z), R[2] = 2 * (x * z + w * y);
    R[3] = 2 * (x * y + w * z), R[4] = 1 - 2 * (x * x + z * z), R[5] = 2 * (y * z - w * x);
    R[6] = 2 * (x * z - w * y), R[7] = 2 * (y * z + w * x), R[8] = 1 - 2 * (x * x + y * y);
}

void gb_dynamics_quaternion(const double R[9], double q[4])
{
    /* Shepperd's method: divide by the largest of the four candidate components. */
    const double tr = R[0] + R[4] + R[8];
    if (tr >= R[0] && tr >= R[4] && tr >= R[8]) {
        const double s = 2 * sqrt(1 + tr);
        q[0] = s / 4, q[1] = (R[7] - R[5]) / s, q[2] = (R[2] - R[6]) / s, q[3] = (R[3] - R[1]) / s;
    } else if (R[0] >= R[4] && R[0] >= R[8]) {
        const double s = 2 * sqrt(1 + R[0] - R[4] - R[8]);
        q[0] = (R[7] - R[5]) / s, q[1] = s / 4, q[2] = (R[1] + R[3]) / s, q[3] = (R[2] + R[6]) / s;
    } else if (R[4] >= R[8]) {
        const double s = 2 * sqrt(1 + R[4] - R[0] - R[8]);
        q[0] = (R[2] - R[6]) / s, q[1] = (R[1] + R[3]) / s, q[2] = s / 4, q[3] = (R[5] + R[7]) / s;
    } else {
        const double s = 2 * sqrt(1 + R[8] - R[0] - R[4]);
        q[0] = (R[3] - R[1]) / s, q[1] = (R[2] + R[6]) / s, q[2] = (R[5] + R[7]) / s, q[3] = s / 4;
    }
}

void gb_dyn_vertical(const double y[GB_STATE_SIZE], double zb[3]) { gb_dyn_vertical_of_quaternion(y + GB_STATE_Q, zb); }

/* ---------------------------------------------------------------- the vector field */

int gb_dyn_diverged(double t)
{
    return gb_error_set(GB_ENUMERIC, "t = %.9g: the state is no longer finite: the integration diverged (a step too "
                        "large for the scene's stiffest rate, such as the damping c over the inertia?)", t);
}

int gb_dyn_state_finite(double t, const double y[GB_STATE_SIZE])
{
    double nan_if_not = 0.0; /* y·0 is ±0 for a finite y, NaN for ±inf and NaN: one test for the whole state */
    for (int i = 0; i < GB_STATE_SIZE; i++) nan_if_not += y[i] * 0.0;
    return nan_if_not == nan_if_not ? GB_OK : gb_dyn_diverged(t);
}

void gb_dyn_to_inertial(const double y[GB_STATE_SIZE], const double body[3], double out[3])
{
    double R[9];
    gb_dynamics_rotation(y + GB_STATE_Q, R);
    for (int i = 0; i < 3; i++) out[i] = R[3 * i] * body[0] + R[3 * i + 1] * body[1] + R[3 * i + 2] * body[2];
}

int gb_dyn_field(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], double dydt[GB_STATE_SIZE])
{
    double zb[3];
    static const double at_rest[3] = {0.0, 0.0, 0.0};
    const gb_dyn_mode *mode = gb_dyn_current(d);
    /* where nothing turns (at rest), ω is 0 whatever rounding is left in the state's */
    const double *q = y + GB_STATE_Q, *omega = mode->turns ? y + GB_STATE_OMEGA : at_rest;
    if (gb_dyn_state_finite(t, y)) return GB_ENUMERIC;
    gb_dyn_vertical_of_quaternion(q, zb);
    if (!(isfinite(zb[0]) && isfinite(zb[1]) && isfinite(zb[2]))) return gb_dyn_diverged(t); /* a quaternion overflowed */
    double zeta = NAN;
    if (!d->forcing_valid || t != d->forcing_t) {
        gb_forcing_geff_with_rate(&d->def.forcing, t, &d->forcing_geff, &d->forcing_rate);
        d->forcing_t = t, d->forcing_valid = 1;
    }
    const double geff = d->forcing_geff;
    /* under a law with a free centroid the translation is integrated: the mode gives its rates */
    const int translating = d->law->free_centroid;
    gb_dyn_rates rates = {{0.0, 0.0, 0.0}, 0.0, 0.0};
    const int status = mode->field(d, t, y, omega, zb, geff, dydt + GB_STATE_OMEGA, &zeta, translating ? &rates : NULL);
    if (status) return status;
    for (int k = GB_STATE_ZETA; k < GB_STATE_SIZE; k++) dydt[k] = 0.0; /* written by the mode at each accepted step */
    if (translating) {
        dydt[GB_STATE_ZETA] = rates.zeta_rate;
        for (int k = 0; k < 3; k++) dydt[GB_STATE_VELOCITY + k] = rates.acc[k];
        dydt[GB_STATE_POSITION] = y[GB_STATE_VELOCITY], dydt[GB_STATE_POSITION + 1] = y[GB_STATE_VELOCITY + 1];
        dydt[GB_STATE_FRICTION] = rates.friction_power;
    }
    /* q̇ = ½ q ⊗ (0, ω) (eq 23) */
    dydt[0] = -0.5 * (q[1] * omega[0] + q[2] * omega[1] + q[3] * omega[2]);
    dydt[1] = 0.5 * (q[0] * omega[0] + q[2] * omega[2] - q[3] * omega[1]);
    dydt[2] = 0.5 * (q[0] * omega[1] + q[3] * omega[0] - q[1] * omega[2]);
    dydt[3] = 0.5 * (q[0] * omega[2] + q[1] * omega[1] - q[2] * omega[0]);
    /* Ẇ = P_d + m ġ_eff ζ with ζ = −z_b·r_c on the plane (eqs 37, 50); in flight E = ½ m |v|² + ½ ω·I_G ω +
     * m g_eff ζ obeys the same balance, since d/dt(½ m |v|²) = −m g_eff ζ̇ there */
    dydt[GB_STATE_WORK] = -d->def.damping * gb_vec_dot(omega, omega) +
                          d->def.mass * d->forcing_rate * zeta;
    return GB_OK;
}

int gb_dynamics_rhs(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], double dydt[GB_STATE_SIZE])
{
    return gb_dyn_field(d, t, y, dydt);
}

/* ---------------------------------------------------------------- counters */

void gb_dynamics_set_impact_sink(gb_dynamics *d, gb_dynamics_impact_sink sink, void *context)
{
    d->impact_sink = sink, d->impact_context = context;
}

void gb_dynamics_impact_stats(const gb_dynamics *d, size_t *impacts, double *energy_lost, double *friction_max)
{
    if (impacts) *impacts = d->impacts;
    if (energy_lost) *energy_lost = d->impact_loss;
    if (friction_max) *friction_max = d->impact_friction_max;
}


void gb_dynamics_two_point_stats(const gb_dynamics *d, double t, gb_dynamics_two_point_summary *out)
{
    out->time = gb_dyn_mode_time(d, GB_DYN_TWO_POINT, t);
    out->entries = d->crease.entries;
    out->settled = d->crease.settled;
    out->lifts = d->crease.lifts;
    out->third_points = d->crease.third_points;
    out->rest_since = d->mode_since[GB_DYN_REST];
}

size_t gb_dynamics_switch_count(const gb_dynamics *d) { return d->grid_switches + d->branch_switches; }

double gb_dynamics_last_switch_time(const gb_dynamics *d) { return d->last_switch_time; }

void gb_dyn_observe_free_energy(const gb_dynamics *d, const double y[GB_STATE_SIZE], gb_dynamics_observables *o)
{
    const double m = d->def.mass;
    double Iw[3];
    gb_dyn_mat_vec((double(*)[3])d->inertia, o->omega, Iw);
    o->kinetic = 0.5 * m * gb_vec_dot(o->velocity, o->velocity) + 0.5 * gb_vec_dot(o->omega, Iw);
    o->potential = m * o->geff * o->zeta;
    o->energy = o->kinetic + o->potential;
    o->power_gravity = -m * o->geff * o->velocity[2];
    o->power_damping = -d->def.damping * gb_vec_dot(o->omega, o->omega);
    o->work = y[GB_STATE_WORK];
    o->friction_work = y[GB_STATE_FRICTION];
    o->residual = o->energy - d->energy0 - o->work + d->impact_loss;
    if (d->law->free_centroid) o->residual -= o->friction_work; /* the ledger's L: the impacts' and friction's */
}

/* ---------------------------------------------------------------- 3 x 3 algebra */

void gb_dyn_mat_vec(double A[3][3], const double v[3], double out[3])
{
    for (int i = 0; i < 3; i++) out[i] = A[i][0] * v[0] + A[i][1] * v[1] + A[i][2] * v[2];
}

/* Solve A x = b for a symmetric positive-definite 3 × 3 A by cofactors. */
int gb_dyn_solve3(double A[3][3], const double b[3], double x[3])
{
    const double c00 = A[1][1] * A[2][2] - A[1][2] * A[2][1], c01 = A[1][2] * A[2][0] - A[1][0] * A[2][2],
                 c02 = A[1][0] * A[2][1] - A[1][1] * A[2][0];
    const double det = A[0][0] * c00 + A[0][1] * c01 + A[0][2] * c02;
    if (!(det > 0.0) || !isfinite(det)) return gb_error_set(GB_ENUMERIC, "inertia about the contact is singular (det %g)", det);
    const double inv[3][3] = {
        {c00, A[0][2] * A[2][1] - A[0][1] * A[2][2], A[0][1] * A[1][2] - A[0][2] * A[1][1]},
        {c01, A[0][0] * A[2][2] - A[0][2] * A[2][0], A[0][2] * A[1][0] - A[0][0] * A[1][2]},
        {c02, A[0][1] * A[2][0] - A[0][0] * A[2][1], A[0][0] * A[1][1] - A[0][1] * A[1][0]}};
    for (int i = 0; i < 3; i++) x[i] = (inv[i][0] * b[0] + inv[i][1] * b[1] + inv[i][2] * b[2]) / det;
    return GB_OK;
}
