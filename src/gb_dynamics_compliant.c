/* gb_dynamics_compliant — the compliant contact law (contact_law = compliant; docs/compliant.md): the plane
 * pushes where the body dips into it, with Hunt and Crossley's normal force and Coulomb's friction made smooth,
 * so the whole motion is one smooth mode: no events, no impacts, no modes to switch. The canonical stiff problem:
 * as the stiffness grows, its bounces and rests tend to the unilateral law's (the rigid limit).
 *
 * At every point of the body below the plane, at depth δ > 0 with approach speed δ̇ (the material point's
 * downward velocity relative to the plane):
 *   N   = max(0, k δ^n (1 + (3/2) α δ̇))                           (Hunt and Crossley 1975)
 *   F_t = −μ N u_t / √(|u_t|² + s²)                               (Coulomb's law, regularised at slip speed s)
 * The points: a polyhedron's vertices (each one below the plane pushes); a smooth body's lowest point, its
 * contact found and certified as in every other mode (a smooth convex body meets the plane in one cap, whose
 * force this point carries), its changes located as events where two minima tie (locate_switches = yes). The state: the attitude and ω, the centroid's height ζ, velocity and horizontal
 * position (integrated, GB_STATE_ZETA ... POSITION), and the work of the dissipative forces (GB_STATE_FRICTION:
 * the Hunt–Crossley part of N and friction). The ledger E − E0 − W − W_contact counts the elastic energy
 * k δ^{n+1} / (n + 1) of each point in E.
 * A rigid impact at approach speed v⁻ becomes a bounce with restitution e(x), x = (3/2) α v⁻, the root of
 * x − ln(1 + x) = −e x − ln(1 − e x) whatever k and n (weight neglected during the contact): docs/compliant.md. */
#include "gb_dynamics_internal.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <string.h>

enum { STIFFNESS = 0, EXPONENT = 1, DISSIPATION = 2, SLIP_SPEED = 3 };

/* The compliant law's [model] keys: the scene table reads them from the law's row. */
static const gb_dynamics_law_key compliant_keys[] = {
    {"stiffness", STIFFNESS, 0.0, 1e15, 1, 1e6, "[N/m^exponent] (k; needs contact_law = compliant)"},
    {"exponent", EXPONENT, 1.0, 3.0, 0, 1.5, "(n: 1 linear, 1.5 Hertz; needs contact_law = compliant)"},
    {"dissipation", DISSIPATION, 0.0, 1000.0, 0, 0.0, "[s/m] (Hunt and Crossley's alpha; needs contact_law = compliant)"},
    {"slip_speed", SLIP_SPEED, 0.0, 1000.0, 1, 1e-4, "[m/s] (the friction's regularisation; needs contact_law = compliant)"},
};

/* The law's coefficients for one run. */
typedef struct law {
    double k, n, alpha, s, mu;
} law;

static law law_of(const gb_dynamics *d)
{
    return (law){gb_dyn_coefficient(d, STIFFNESS), gb_dyn_coefficient(d, EXPONENT), gb_dyn_coefficient(d, DISSIPATION),
                 gb_dyn_coefficient(d, SLIP_SPEED), d->def.friction};
}

/* What the plane does at a state. */
typedef struct forces {
    double force[3];  /* on the centroid, inertial axes [N] */
    double torque[3]; /* about the centroid, body axes [N m] */
    double normal;    /* Σ N [N] */
    double tangential; /* |Σ F_t| [N] */
    double elastic;   /* Σ k δ^{n+1} / (n + 1) [J] */
    double power;     /* the dissipative forces' power [W] (<= 0) */
    int points;       /* points below the plane */
    double depth;     /* the deepest point's δ [m] (< 0: the lowest point's clearance) */
    double lowest[3]; /* that point, body axes [m] */
} forces;

/* The force at body point r [m] (body axes) of the state, added into f. */
static void push(const law *c, const double y[GB_STATE_SIZE], const double R[9], const double r[3], forces *f)
{
    const double zb[3] = {R[6], R[7], R[8]}, *w = y + GB_STATE_OMEGA;
    const double depth = -(y[GB_STATE_ZETA] + gb_vec_dot(zb, r));
    if (depth > f->depth) f->depth = depth, memcpy(f->lowest, r, sizeof f->lowest);
    if (!(depth > 0.0)) return;
    double wr[3], u[3];
    gb_vec_cross(w, r, wr);
    for (int i = 0; i < 3; i++) u[i] = y[GB_STATE_VELOCITY + i] + R[3 * i] * wr[0] + R[3 * i + 1] * wr[1] + R[3 * i + 2] * wr[2];
    const double rate = -u[2], elastic = c->k * pow(depth, c->n);
    const double normal = fmax(0.0, elastic * (1.0 + 1.5 * c->alpha * rate));
    const double slip = hypot(u[0], u[1]), scale = c->mu * normal / sqrt(slip * slip + c->s * c->s);
    const double F[3] = {-scale * u[0], -scale * u[1], normal};
    double Fb[3], tau[3];
    for (int i = 0; i < 3; i++) Fb[i] = R[i] * F[0] + R[3 + i] * F[1] + R[6 + i] * F[2]; /* Rᵀ F */
    gb_vec_cross(r, Fb, tau);
    for (int i = 0; i < 3; i++) f->force[i] += F[i], f->torque[i] += tau[i];
    f->normal += normal;
    f->elastic += c->k * pow(depth, c->n + 1.0) / (c->n + 1.0);
    f->power += -(normal - elastic) * rate - scale * slip * slip; /* N's dissipative part, and friction's */
    f->points++;
}

/* Every force of the plane at state y (time t). */
static int plane_forces(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], forces *f)
{
    const law c = law_of(d);
    double R[9];
    gb_dynamics_rotation(y + GB_STATE_Q, R);
    memset(f, 0, sizeof *f);
    f->depth = -INFINITY;
    const double l = d->def.length;
    if (gb_surface_is_polyhedron(&d->surface) && d->grid) { /* every vertex */
        const size_t count = gb_contact_grid_size(d->grid);
        for (size_t i = 0; i < count; i++) {
            double phi, theta, x[3];
            gb_contact_grid_node(d->grid, i, &phi, &theta, x);
            const double r[3] = {l * x[0], l * x[1], l * x[2]};
            push(&c, y, R, r, f);
        }
        return GB_OK;
    }
    const double zb[3] = {R[6], R[7], R[8]};
    gb_dyn_contact contact;
    const int status = gb_dyn_contact_at(d, t, zb, y + GB_STATE_OMEGA, &contact); /* the lowest point */
    if (status) return status;
    push(&c, y, R, contact.rc, f);
    return GB_OK;
}

/* I_G ω̇ + ω × I_G ω = τ − c ω, and the centroid's acceleration relative to the plane, F/m − g_eff e_z. */
static int accelerations(gb_dynamics *d, const double omega[3], double geff, const forces *f, double omega_dot[3],
                         double acc[3])
{
    double Iw[3], gyro[3], rhs[3];
    gb_dyn_mat_vec(d->inertia, omega, Iw);
    gb_vec_cross(omega, Iw, gyro);
    for (int k = 0; k < 3; k++) rhs[k] = f->torque[k] - gyro[k] - d->def.damping * omega[k];
    for (int k = 0; k < 3; k++) acc[k] = f->force[k] / d->def.mass;
    acc[2] -= geff;
    return gb_dyn_solve3(d->inertia, rhs, omega_dot);
}

static int compliant_field(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double omega[3],
                           const double zb[3], double geff, double omega_dot[3], double *zeta, gb_dyn_rates *rates)
{
    (void)zb;
    forces f;
    int status = plane_forces(d, t, y, &f);
    double acc[3];
    if (!status) status = accelerations(d, omega, geff, &f, omega_dot, acc);
    if (status) return status;
    *zeta = y[GB_STATE_ZETA];
    if (rates) {
        memcpy(rates->acc, acc, sizeof acc);
        rates->zeta_rate = y[GB_STATE_VELOCITY + 2];
        rates->friction_power = f.power;
    }
    return GB_OK;
}

/* A smooth body's lowest point continued and certified, a lower minimum taking over (no jump: the force is
 * continuous across it to the certificate's tolerance); a polyhedron's vertices need nothing. */
static int compliant_accept(gb_dynamics *d, double t, double y[GB_STATE_SIZE])
{
    if (gb_surface_is_polyhedron(&d->surface) && d->grid) return GB_OK;
    gb_contact_point continued, other;
    int found;
    const int status = gb_dyn_competitor(d, t, y, &continued, &other, &found);
    if (status) return status;
    gb_dyn_set_contact(d, found ? &other : &continued);
    d->memo_valid = 0;
    if (found) d->last_valid = 0, d->branch_switches++, d->last_switch_time = t;
    return gb_dyn_remember_rate(d, t, y);
}

/* A polyhedron's vertices are pushed by no search: no events. A smooth body's lowest point changes where another
 * minimum of height passes below it (a non-convex body's): that change is an event, located (locate_switches) where
 * the two tie so that the force moves to the new point at equal depth (the elastic energy continuous); the contact
 * moves there and the state is kept. */
static int compliant_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found)
{
    *found = 0;
    if ((gb_surface_is_polyhedron(&d->surface) && d->grid) || d->def.contact != GB_CONTACT_MODEL_CONTINUOUS) return GB_OK;
    gb_contact_point continued;
    return gb_dyn_competitor(d, t, y, &continued, other, found);
}

/* The lowest point's height less the other minimum's, both continued to y: > 0 once the other is lower. */
static int compliant_gap(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other,
                         double *gap, gb_contact_point *other_here)
{
    (void)t;
    double zb[3];
    gb_dyn_vertical(y, zb);
    gb_contact_point here;
    int status = gb_dyn_point_at(d, zb, &d->contact, &here);
    if (!status) status = gb_dyn_point_at(d, zb, other, other_here);
    *gap = status ? NAN : here.height - other_here->height;
    return status;
}

/* The force moves to the other minimum at the tie; the state is kept (no jump). */
static int compliant_switch(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    (void)y;
    gb_dyn_set_contact(d, branch);
    d->branch_switches++, d->last_switch_time = t;
    d->memo_valid = d->last_valid = 0;
    gb_dyn_forget_rate(d);
    return GB_OK;
}

static int compliant_jump(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                          double out[GB_STATE_SIZE])
{
    (void)d, (void)t, (void)branch;
    memcpy(out, y, GB_STATE_SIZE * sizeof *out);
    return GB_OK;
}

static int compliant_observe(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_observables *o)
{
    forces f;
    double acc[3];
    int status = plane_forces(d, t, y, &f);
    if (!status) status = accelerations(d, o->omega, o->geff, &f, o->omega_dot, acc);
    if (status) return status;
    o->zeta = y[GB_STATE_ZETA];
    memcpy(o->velocity, y + GB_STATE_VELOCITY, sizeof o->velocity);
    memcpy(o->rc, f.lowest, sizeof o->rc);
    o->height = gb_vec_dot(o->zb, f.lowest);
    o->clearance = -f.depth; /* < 0: the deepest point's depth */
    o->normal_force = f.normal;
    o->normal_forces[0] = f.normal;
    o->friction_needed = f.normal > 0.0 ? hypot(f.force[0], f.force[1]) / f.normal : 0.0;
    o->contacts = f.points;
    o->index = d->def.contact != GB_CONTACT_MODEL_CONTINUOUS ? d->index : 0;
    gb_dyn_observe_free_energy(d, y, o); /* with the dissipative work in the ledger */
    o->potential += f.elastic;
    o->energy += f.elastic;
    o->residual += f.elastic;
    o->slip_speed = 0.0;
    return GB_OK;
}

/* The translation is integrated: nothing to write. */
static void compliant_translate(const gb_dynamics *d, double t, double y[GB_STATE_SIZE]) { (void)d, (void)t, (void)y; }

/* The start: the lowest point height0 above the plane (0: touching it), the centroid at velocity0. */
static int compliant_start(gb_dynamics *d, double t0, double y[GB_STATE_SIZE])
{
    (void)t0;
    double zb[3];
    gb_dyn_vertical(y, zb);
    double lowest = gb_vec_dot(zb, d->contact.rc);
    if (gb_surface_is_polyhedron(&d->surface) && d->grid) /* the lowest vertex */
        for (size_t i = 0; i < gb_contact_grid_size(d->grid); i++) {
            double phi, theta, x[3];
            gb_contact_grid_node(d->grid, i, &phi, &theta, x);
            lowest = fmin(lowest, gb_vec_dot(zb, x));
        }
    y[GB_STATE_ZETA] = d->def.height0 - d->def.length * lowest;
    memcpy(y + GB_STATE_VELOCITY, d->def.velocity0, 3 * sizeof *y);
    return GB_OK;
}

const gb_dyn_mode gb_dyn_compliant_mode = {"compliant",       1,
                                           compliant_field,   compliant_accept,
                                           compliant_pending, compliant_gap,
                                           compliant_switch,  compliant_jump,
                                           compliant_observe, compliant_translate,
                                           compliant_start};

const gb_dynamics_law gb_dyn_compliant_law = {
    "compliant (Hunt and Crossley, regularised Coulomb friction)",
    GB_CONTACT_LAW_COMPLIANT,
    0, /* impacts: none, its contact forces follow from the state */
    1, /* translates */
    0, /* pivots */
    1, /* several events per step: a smooth body's changes of lowest point, located */
    0, /* slips: no sliding modes, its friction is smooth */
    1, /* free centroid */
    1, /* needs a finite μ */
    1, /* pushes every vertex of a polyhedron */
    0, /* time steps: none, its forces are smooth and any stepper takes them */
    NULL, /* impact map: no impacts */
    &gb_dyn_compliant_mode,
    compliant_keys,
    sizeof compliant_keys / sizeof compliant_keys[0],
};
