/* gb_dynamics — the core of the hybrid system (gb_dynamics_internal.h): the definition, the state, and
 * every public call passed to the current mode through one table. */
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


static const char *const certificate_names[] = {"per-vertical", "atlas"};

const char *gb_dynamics_certificate_name(gb_dynamics_certificate c) { return (unsigned)c < 2 ? certificate_names[c] : NULL; }

int gb_dynamics_certificate_parse(const char *name, gb_dynamics_certificate *certificate)
{
    int k = 0;
    const int status = gb_error_parse_name(name, certificate_names, 2, "contact certificate", &k);
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
    };
    /* Leaves of 16 nodes were the fastest of 8–32 for the patch tree's searches (make bench); the leaf
     * size changes no result, only the work. */
    def.grid.leaf_size = 16;
    return def;
}

/* The modes, by gb_dyn_mode_id: the one table every public call goes through. */
static const gb_dyn_mode *const modes[GB_DYN_MODES] = {&gb_dyn_mode_one_point, &gb_dyn_mode_two_point, &gb_dyn_mode_rest,
                                                       &gb_dyn_mode_flight};

static const gb_dyn_mode *mode_of(const gb_dynamics *d) { return modes[d->mode]; }

void gb_dyn_set_mode(gb_dynamics *d, gb_dyn_mode_id mode, double t)
{
    if (d->mode == mode) return;
    if (d->mode == GB_DYN_TWO_POINT) d->two_point_time += t - d->two_point_since;
    if (d->mode == GB_DYN_FLIGHT) d->flight_time += t - d->flight_since;
    if (mode == GB_DYN_TWO_POINT) d->two_point_since = t;
    if (mode == GB_DYN_FLIGHT) d->flight_since = t;
    if (mode == GB_DYN_REST) d->rest_since = t;
    d->mode = mode;
}

const gb_dynamics_def *gb_dynamics_get_def(const gb_dynamics *d) { return &d->def; }
double gb_dynamics_mean_radius(const gb_dynamics *d) { return d->mean_radius; }

int gb_dynamics_create_in(const gb_surface *surface, const gb_dynamics_def *def, gb_dynamics_context *context,
                          gb_dynamics **out)
{
    *out = NULL;
    if (!gb_dynamics_variant_name(def->variant) || !gb_contact_model_name(def->contact))
        return gb_error_set(GB_EINVAL, "unknown equation variant %d or contact model %d", (int)def->variant,
                            (int)def->contact);
    if (!(isfinite(def->mass) && def->mass > 0.0))
        return gb_error_set(GB_EDOM, "mass = %g is out of range (allowed: finite, > 0)", def->mass);
    if (!(isfinite(def->length) && def->length > 0.0))
        return gb_error_set(GB_EDOM, "length = %g is out of range (allowed: finite, > 0)", def->length);
    if (!(def->friction > 0.0)) /* INFINITY: no monitor */
        return gb_error_set(GB_EDOM, "friction = %g is out of range (allowed: > 0)", def->friction);
    if (!(isfinite(def->damping) && def->damping >= 0.0))
        return gb_error_set(GB_EDOM, "damping c = %g is out of range (allowed: finite, >= 0)", def->damping);
    if (!(def->restitution >= 0.0 && def->restitution <= 1.0))
        return gb_error_set(GB_EDOM, "restitution e = %g is out of range (allowed: 0 <= e <= 1)", def->restitution);
    if (!(isfinite(def->height0) && def->height0 >= 0.0) ||
        !(isfinite(def->velocity0[0]) && isfinite(def->velocity0[1]) && isfinite(def->velocity0[2])))
        return gb_error_set(GB_EDOM, "initial height %g or velocity is out of range (allowed: height finite, >= 0; "
                            "velocity finite)", def->height0);
    int status = gb_dyn_law_check(def);
    if (status) return status;
    status = gb_forcing_validate(&def->forcing);
    if (status) return status;
    gb_dynamics *d = calloc(1, sizeof *d);
    if (!d) return gb_error_set(GB_ENOMEM, "out of memory for the dynamics");
    d->surface = *surface;
    d->def = *def;
    d->refine = gb_contact_refine_default_def();
    d->law = gb_dyn_law_of(def->contact_law);
    d->settle_time = def->settle_time;
    d->context = context;
    status = gb_dyn_body_create(d);
    if (status) {
        gb_dynamics_free(d);
        return status;
    }
    *out = d;
    return GB_OK;
}

int gb_dynamics_create(const gb_surface *surface, const gb_dynamics_def *def, gb_dynamics **out)
{
    return gb_dynamics_create_in(surface, def, NULL, out);
}

void gb_dynamics_use_step(gb_dynamics *d, double h)
{
    if (d->def.settle_time == 0.0) d->settle_time = h;
}

void gb_dynamics_free(gb_dynamics *d)
{
    if (!d) return;
    gb_dyn_body_free(d);
    free(d);
}

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

/* z_b = Rᵀ e_z: the third row of R (eq 21). */
static void zb_of(const double R[9], double zb[3])
{
    zb[0] = R[6], zb[1] = R[7], zb[2] = R[8];
}

/* ---------------------------------------------------------------- the vector field */

int gb_dyn_diverged(double t)
{
    return gb_error_set(GB_ENUMERIC, "t = %.9g: the state is no longer finite: the integration diverged (a step too "
                        "large for the scene's stiffest rate, such as the damping c over the inertia?)", t);
}

int gb_dynamics_state_finite(double t, const double y[GB_STATE_SIZE])
{
    for (int i = 0; i < GB_STATE_SIZE; i++)
        if (!isfinite(y[i])) return gb_dyn_diverged(t);
    return GB_OK;
}

int gb_dyn_field(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], double dydt[GB_STATE_SIZE])
{
    double zb[3];
    static const double at_rest[3] = {0.0, 0.0, 0.0};
    const gb_dyn_mode *mode = mode_of(d);
    /* where nothing turns (at rest), ω is 0 whatever rounding is left in the state's */
    const double *q = y + GB_STATE_Q, *omega = mode->turns ? y + GB_STATE_OMEGA : at_rest;
    if (gb_dynamics_state_finite(t, y)) return GB_ENUMERIC;
    gb_dyn_vertical_of_quaternion(q, zb);
    if (!(isfinite(zb[0]) && isfinite(zb[1]) && isfinite(zb[2]))) return gb_dyn_diverged(t); /* a quaternion overflowed */
    double geff, geff_rate, zeta = NAN;
    gb_forcing_geff_with_rate(&d->def.forcing, t, &geff, &geff_rate);
    const int status = mode->field(d, t, y, omega, zb, geff, dydt + GB_STATE_OMEGA, &zeta);
    if (status) return status;
    for (int k = GB_STATE_ZETA; k < GB_STATE_SIZE; k++) dydt[k] = 0.0; /* written by the mode at each accepted step */
    /* q̇ = ½ q ⊗ (0, ω) (eq 23) */
    dydt[0] = -0.5 * (q[1] * omega[0] + q[2] * omega[1] + q[3] * omega[2]);
    dydt[1] = 0.5 * (q[0] * omega[0] + q[2] * omega[2] - q[3] * omega[1]);
    dydt[2] = 0.5 * (q[0] * omega[1] + q[3] * omega[0] - q[1] * omega[2]);
    dydt[3] = 0.5 * (q[0] * omega[2] + q[1] * omega[1] - q[2] * omega[0]);
    /* Ẇ = P_d + m ġ_eff ζ with ζ = −z_b·r_c on the plane (eqs 37, 50); in flight E = ½ m |v|² + ½ ω·I_G ω +
     * m g_eff ζ obeys the same balance, since d/dt(½ m |v|²) = −m g_eff ζ̇ there */
    dydt[GB_STATE_WORK] = -d->def.damping * gb_vec_dot(omega, omega) +
                          d->def.mass * geff_rate * zeta;
    return GB_OK;
}

int gb_dynamics_rhs(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], double dydt[GB_STATE_SIZE])
{
    return gb_dyn_field(d, t, y, dydt);
}

/* ---------------------------------------------------------------- steps and events, by mode */

int gb_dynamics_accept(gb_dynamics *d, double t, double y[GB_STATE_SIZE], double *norm_drift)
{
    double *q = y + GB_STATE_Q;
    const double n = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(isfinite(n) && n > 0.0) || gb_dynamics_state_finite(t, y)) return gb_dyn_diverged(t);
    if (norm_drift) *norm_drift = n - 1.0;
    for (int k = 0; k < 4; k++) q[k] /= n;
    const int status = mode_of(d)->accept(d, t, y);
    if (!status) mode_of(d)->translate(d, t, y); /* by the mode the step ends in */
    return status;
}

int gb_dynamics_switch_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other,
                               int *found)
{
    *found = 0;
    d->event = GB_DYN_EVENT_NONE;
    return mode_of(d)->pending(d, t, y, other, found);
}

int gb_dynamics_branch_gap(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other,
                           double *gap, gb_contact_point *other_here)
{
    return mode_of(d)->gap(d, t, y, other, gap, other_here);
}

int gb_dynamics_switch_to(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    d->lift_allow = 0.0; /* any change of contact ends a lifted point's allowance (a lift sets a new one) */
    return mode_of(d)->event(d, t, y, branch);
}

int gb_dynamics_jump(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                     double out[GB_STATE_SIZE])
{
    return mode_of(d)->jump(d, t, y, branch, out);
}

/* ---------------------------------------------------------------- counters and the state's start */

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

size_t gb_dynamics_impacts_over_friction(const gb_dynamics *d) { return d->impacts_over_friction; }

void gb_dynamics_two_point_stats(const gb_dynamics *d, double t, gb_dynamics_two_point_summary *out)
{
    out->time = d->two_point_time + (d->mode == GB_DYN_TWO_POINT ? t - d->two_point_since : 0.0);
    out->entries = d->two_point_entries;
    out->settled = d->settled;
    out->lifts = d->lifts;
    out->third_points = d->third_points;
    out->rest_since = d->rest_since;
}

size_t gb_dynamics_switch_count(const gb_dynamics *d) { return d->grid_switches + d->branch_switches; }

double gb_dynamics_last_switch_time(const gb_dynamics *d) { return d->last_switch_time; }

void gb_dynamics_adopt_contact(gb_dynamics *to, const gb_dynamics *from)
{
    to->memo_valid = 0;
    to->last_valid = 0;
    to->index = from->index;
    to->contact = from->contact;
    to->mode = from->mode, to->event = GB_DYN_EVENT_NONE;
    to->rest_since = from->rest_since;
    to->contact2 = from->contact2;
    to->q_valid = 0;
    to->two_point_since = from->two_point_since;
    to->gap_allow = from->gap_allow;
    to->lifted = from->lifted, to->lift_allow = from->lift_allow;
    to->fly_t0 = from->fly_t0, to->fly_zeta0 = from->fly_zeta0, to->flight_since = from->flight_since;
    memcpy(to->fly_v0, from->fly_v0, sizeof to->fly_v0);
    to->contact_time = from->contact_time;
    memcpy(to->contact_rate, from->contact_rate, sizeof to->contact_rate);
}

int gb_dynamics_init_state(gb_dynamics *d, double t0, const double R0[9], const double omega0[3],
                           double y[GB_STATE_SIZE])
{
    double worst = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            const double dot = R0[3 * 0 + i] * R0[3 * 0 + j] + R0[3 * 1 + i] * R0[3 * 1 + j] + R0[3 * 2 + i] * R0[3 * 2 + j];
            worst = fmax(worst, fabs(dot - (i == j)));
        }
    if (!(worst < 1e-12))
        return gb_error_set(GB_EDOM, "initial attitude is not a rotation: max |R^T R - I| = %.3g (allowed: < 1e-12)", worst);
    if (!(isfinite(omega0[0]) && isfinite(omega0[1]) && isfinite(omega0[2])))
        return gb_error_set(GB_EDOM, "initial angular velocity must be finite");
    gb_dynamics_quaternion(R0, y + GB_STATE_Q);
    memcpy(y + GB_STATE_OMEGA, omega0, 3 * sizeof *omega0);
    y[GB_STATE_WORK] = 0.0;
    double R[9], zb[3];
    gb_dynamics_rotation(y + GB_STATE_Q, R);
    zb_of(R, zb);
    int status = gb_dyn_contact_global(d, zb);
    if (status) return status;
    if (d->def.contact == GB_CONTACT_MODEL_CONTINUOUS) gb_dyn_remember_rate(d, t0, y);
    d->last_valid = 0;
    d->grid_switches = d->branch_switches = d->branches_lost = 0;
    d->impacts = 0, d->impact_loss = d->impact_friction_max = 0.0;
    d->impacts_over_friction = 0;
    d->mode = GB_DYN_ONE_POINT, d->event = GB_DYN_EVENT_NONE, d->two_point_time = 0.0;
    d->next_hint = SIZE_MAX;
    d->rest_since = NAN;
    d->q_valid = 0;
    d->two_point_entries = d->settled = d->lifts = d->third_points = 0;
    d->gap_allow = GB_DYN_GAP_TOL;
    d->lift_allow = 0.0;
    d->flight_time = d->hop_max = 0.0;
    d->lift_offs = d->landings = d->bounces = 0;
    const double *v0 = d->def.velocity0;
    if (d->def.height0 > 0.0 || v0[0] != 0.0 || v0[1] != 0.0 || v0[2] != 0.0) {
        /* in flight: the lowest point (the contact found) at height0 above the plane, the centroid at v0 */
        double vb[3];
        for (int i = 0; i < 3; i++) vb[i] = R[i] * v0[0] + R[3 + i] * v0[1] + R[6 + i] * v0[2]; /* Rᵀ v0 */
        gb_dyn_start_flight(d, t0, y, vb, d->def.height0 - d->def.length * gb_vec_dot(zb, d->contact.rc));
        d->hop_max = d->def.height0;
    }
    d->last_switch_time = NAN;
    d->memo_valid = 0;
    mode_of(d)->translate(d, t0, y);
    d->t0 = t0;
    d->energy0 = 0.0;
    gb_dynamics_observables o;
    status = gb_dynamics_observe(d, t0, y, &o);
    if (!status) d->energy0 = o.energy;
    return status;
}

/* max |RᵀR − I| */
static double orthonormality_of(const double R[9])
{
    double worst = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            const double dot = R[i] * R[j] + R[3 + i] * R[3 + j] + R[6 + i] * R[6 + j];
            worst = fmax(worst, fabs(dot - (i == j)));
        }
    return worst;
}

int gb_dynamics_observe(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_observables *o)
{
    memset(o, 0, sizeof *o);
    o->t = t;
    gb_dynamics_rotation(y + GB_STATE_Q, o->R);
    zb_of(o->R, o->zb);
    memcpy(o->omega, y + GB_STATE_OMEGA, sizeof o->omega);
    gb_forcing_geff_with_rate(&d->def.forcing, t, &o->geff, &o->geff_rate);
    const int status = mode_of(d)->observe(d, t, y, o);
    if (status) return status;
    o->orthonormality = orthonormality_of(o->R);
    o->grid_switches = d->grid_switches;
    o->branch_switches = d->branch_switches;
    o->branches_lost = d->branches_lost;
    return GB_OK;
}

int gb_dynamics_start_in(const gb_surface *body, const gb_dynamics_def *def, gb_dynamics_context *context, const double R0[9],
                         const double omega0[3], gb_dynamics **out, double y[GB_STATE_SIZE])
{
    *out = NULL;
    int status = gb_dynamics_create_in(body, def, context, out);
    if (!status) status = gb_dynamics_init_state(*out, 0.0, R0, omega0, y);
    if (status) {
        gb_dynamics_free(*out);
        *out = NULL;
    }
    return status;
}

int gb_dynamics_start(const gb_surface *body, const gb_dynamics_def *def, const double R0[9], const double omega0[3],
                      gb_dynamics **out, double y[GB_STATE_SIZE])
{
    return gb_dynamics_start_in(body, def, NULL, R0, omega0, out, y);
}
