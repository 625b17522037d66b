/* gb_dynamics_stepping — the time-stepping strategy (Moreau–Jean), docs/stepping.md: at each step one frictional
 * contact problem over every point of the body the step would bring into the plane, at the level of velocities and
 * impulses; no event is located, no mode is followed. The law poses the problem (its row's time_steps: Newton's
 * impact law on the normal velocity, Coulomb's cone); Siconos's fc3d solves it (gb_contact_problem).
 *
 * One step from (t, q, ω, ζ, v) of size h, with the generalised velocity V = (v, ω) (v inertial, relative to the
 * plane; ω body axes) and the θ-method for the smooth forces:
 *   free velocities   v_f = v − h g_θ e_z,  (I + hθc) ω_f = I ω − h ω × I ω − h (1 − θ) c ω    (g_θ = θ g₁ + (1−θ) g₀)
 *   candidates        the grid's nodes r_i (a mesh's vertices, a grid polyhedron's nodes) whose gap after half a
 *                     step at today's speed, g_i + h u_n,i / 2, is ≤ 0 (Siconos's MoreauJeanOSI's index set, γ = 1/2);
 *                     a smooth body's (continuous contact): the local minima of its height function it tracks, each
 *                     continued by Newton to the step's vertical, the global one certified (gb_certify, the atlas),
 *                     taken where it stands at the step's start (fixed in the body over the step)
 *   relation          u_i = v + R(ω × r_i) = v + B_i ω, B_i = −[R r_i]× R, in the frame (e_z, e_x, e_y)
 *   problem           u = W P + q, W_ij = 1/m + B_i M_ω⁻¹ B_jᵀ (3 × 3 blocks) (M_ω = I + hθc), q_i = u_i(V_f) + e u_n,i(V) e_z
 *   impulses          V⁺ = V_f + M̂⁻¹ Σ H_iᵀ P_i
 *   positions         x⁺ = x + h (θ v⁺ + (1−θ) v), q⁺ = q ⊗ exp(h ω_θ / 2)
 * The ledger: a free flight of the centroid under a constant g keeps E = T + m g ζ exactly at θ = 1/2; the contacts'
 * impulses take D = −Σ P_i · (u_i⁺ + ũ_i) / 2, ũ_i the free velocity without gravity's kick (a body at rest takes 0),
 * booked as the impacts' loss (normal part) and friction's work (tangential part); the forcing's work
 * m (g₁ − g₀)(ζ₀ + ζ₁)/2 and damping's −c h ω_θ·ω̄ enter W. What the ledger leaves is the scheme's first-order error. */
#include "gb_dynamics_internal.h"
#include "gb_dynamics_protocol_internal.h"
#include "gb_dynamics_stepper_internal.h"

#include "gb_contact_problem.h"
#include "gb_error.h"
#include "gb_impact_internal.h"
#include "gb_vec.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void stepper_free(gb_dyn_stepper *s)
{
    if (!s) return;
    gb_contact_problem_free(s->problem);
    free(s->W), free(s->q), free(s->mu), free(s->r), free(s->u), free(s->node), free(s->B), free(s->C), free(s->touched), free(s->touching_now), free(s->last_node), free(s->last_r), free(s->points), free(s->gaps), free(s->starts);
    free(s->candidates), free(s->keys), free(s->posed), free(s->scratch);
    free(s);
}

void gb_dyn_stepping_free(gb_dynamics *d)
{
    stepper_free(d->stepper);
    d->stepper = NULL;
}

static int grow(gb_dyn_stepper *s, size_t count)
{
    if (count <= s->capacity) return GB_OK;
    size_t capacity = s->capacity ? s->capacity : 8;
    while (capacity < count) capacity *= 2;
    const size_t n = 3 * capacity;
    double *W = realloc(s->W, n * n * sizeof *W), *q = realloc(s->q, n * sizeof *q);
    if (W) s->W = W;
    if (q) s->q = q;
    double *mu = realloc(s->mu, capacity * sizeof *mu), *r = realloc(s->r, n * sizeof *r), *u = realloc(s->u, n * sizeof *u);
    if (mu) s->mu = mu;
    if (r) s->r = r;
    if (u) s->u = u;
    size_t *node = realloc(s->node, capacity * sizeof *node), *touched = realloc(s->touched, capacity * sizeof *touched);
    size_t *now = realloc(s->touching_now, capacity * sizeof *now), *last = realloc(s->last_node, capacity * sizeof *last);
    double *last_r = realloc(s->last_r, n * sizeof *last_r);
    int *starts = realloc(s->starts, capacity * sizeof *starts);
    if (starts) s->starts = starts;
    if (last) s->last_node = last;
    if (last_r) s->last_r = last_r;
    if (node) s->node = node;
    if (touched) s->touched = touched;
    if (now) s->touching_now = now;
    double(*B)[3][3] = realloc(s->B, capacity * sizeof *B), (*C)[3][3] = realloc(s->C, capacity * sizeof *C);
    if (B) s->B = B;
    if (C) s->C = C;
    if (!(W && q && mu && r && u && node && touched && now && last && last_r && starts && B && C))
        return gb_error_set(GB_ENOMEM, "out of memory for a contact problem of %zu points", count);
    s->capacity = capacity;
    return GB_OK;
}

/* ---- the mode the dynamics is in while time is stepped: its field is the free motion (no contact), its observables
 * the last step's --------------------------------------------------------------------------------------------- */

static int stepped_field(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double omega[3], const double zb[3],
                         double geff, double omega_dot[3], double *zeta, gb_dyn_rates *rates)
{
    (void)t, (void)zb;
    const int status = gb_dyn_free_acceleration(d, omega, omega_dot);
    *zeta = y[GB_STATE_ZETA];
    if (rates) {
        rates->acc[0] = rates->acc[1] = 0.0, rates->acc[2] = -geff;
        rates->zeta_rate = y[GB_STATE_VELOCITY + 2];
    }
    return status;
}

static int stepped_accept(gb_dynamics *d, double t, double y[GB_STATE_SIZE])
{
    (void)d, (void)t, (void)y;
    return GB_OK;
}

static int stepped_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found)
{
    (void)d, (void)t, (void)y, (void)other;
    *found = 0;
    return GB_OK;
}

static int stepped_gap(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other, double *gap,
                       gb_contact_point *other_here)
{
    (void)d, (void)y, (void)other, (void)gap, (void)other_here;
    return gb_error_set(GB_EINVAL, "t = %.9g: time-stepping locates no event", t);
}

static int stepped_event(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch)
{
    (void)d, (void)y, (void)branch;
    return gb_error_set(GB_EINVAL, "t = %.9g: time-stepping applies no jump at an event", t);
}

static int stepped_jump(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                        double out[GB_STATE_SIZE])
{
    (void)out;
    return stepped_event(d, t, (double *)y, branch);
}

/* Every point's gap above the plane at state y (vertical zb), the lowest point and its clearance: one pass over the
 * points (a smooth body's tracked minima first brought to y), kept for the same state (the step that follows it, and
 * the observer of the step that made it). */
int gb_dyn_stepping_scan(gb_dynamics *d, const double y[GB_STATE_SIZE], const double zb[3])
{
    gb_dyn_stepper *s = d->stepper;
    if (s->scanned_valid && !memcmp(s->scanned, y, sizeof s->scanned)) return GB_OK;
    if (s->smooth) {
        int global = 0;
        const int status = gb_dyn_stepping_track_minima(d, s, y, zb, &global);
        if (status) return status;
        for (size_t i = 0; i < s->nodes; i++) {
            for (int k = 0; k < 3; k++) s->points[i][k] = s->active[i] ? d->def.length * s->slot[i].rc[k] : 0.0;
            const double *x = s->points[i];
            s->gaps[i] = s->active[i] ? y[GB_STATE_ZETA] + zb[0] * x[0] + zb[1] * x[1] + zb[2] * x[2] : INFINITY;
        }
        s->lowest = (size_t)global;
        s->clearance = s->gaps[global];
    } else {
        double best = INFINITY;
        for (size_t i = 0; i < s->nodes; i++) {
            const double *x = s->points[i];
            const double gap = y[GB_STATE_ZETA] + zb[0] * x[0] + zb[1] * x[1] + zb[2] * x[2];
            s->gaps[i] = gap;
            if (gap < best) best = gap, s->lowest = i;
        }
        s->clearance = best;
    }
    memcpy(s->scanned, y, sizeof s->scanned);
    s->scanned_valid = 1;
    return GB_OK;
}

/* The vertical of state y. */
static void vertical_of(const double y[GB_STATE_SIZE], double zb[3])
{
    double R[9];
    gb_dynamics_rotation(y + GB_STATE_Q, R);
    zb[0] = R[6], zb[1] = R[7], zb[2] = R[8];
}

static int stepped_observe(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_observables *o)
{
    (void)t;
    gb_dyn_stepper *s = d->stepper;
    int status = gb_dyn_stepping_scan(d, y, o->zb);
    if (status) return status;
    o->index = s->lowest;
    memcpy(o->rc, s->points[s->lowest], sizeof o->rc);
    status = gb_dyn_free_acceleration(d, o->omega, o->omega_dot);
    o->zeta = y[GB_STATE_ZETA];
    memcpy(o->velocity, y + GB_STATE_VELOCITY, sizeof o->velocity);
    o->height = gb_vec_dot(o->zb, o->rc);
    o->clearance = fmax(0.0, s->clearance);
    gb_dyn_observe_free_energy(d, y, o);
    if (s->stats.steps) {
        o->contacts = s->touching;
    } else { /* no step yet: the points on the plane to the activation threshold */
        o->contacts = 0;
        for (size_t i = 0; i < s->nodes; i++) o->contacts += s->gaps[i] <= GB_DYNAMICS_STEPPING_ACTIVATION * d->mean_radius;
    }
    if (s->touching && s->h > 0.0) {
        o->normal_force = s->normal_impulse / s->h; /* the step's mean */
        o->normal_forces[0] = o->normal_force;
        o->friction_needed = hypot(s->tangential[0], s->tangential[1]) / s->normal_impulse;
    }
    o->sliding = s->sliding;
    o->slip_speed = s->slip_max;
    return status;
}

static void stepped_translate(const gb_dynamics *d, double t, double y[GB_STATE_SIZE])
{
    (void)d, (void)t, (void)y;
}

static int stepped_start(gb_dynamics *d, double t0, double y[GB_STATE_SIZE]);
#define STEPPED {"time-stepping", 1, stepped_field, stepped_accept, stepped_pending, stepped_gap, stepped_event, \
                 stepped_jump, stepped_observe, stepped_translate, stepped_start}
/* Every mode index is the stepped mode: the modes' time accounting (flight, sliding, on one, two, three points) follows
 * the steps, and every call goes to the one mode. */
const gb_dyn_mode gb_dyn_stepped_modes[GB_DYN_MODES] = {STEPPED, STEPPED, STEPPED, STEPPED, STEPPED};

/* ---- the step ----------------------------------------------------------------------------------------------- */

int gb_dynamics_stepping_prepare(gb_dynamics *d)
{
    if (!d->law->time_steps)
        return gb_error_set(GB_EINVAL, "the %s law poses no one-step contact problem (allowed with time-stepping: "
                            "contact_law = unilateral on a plane of finite friction)", d->law->name);
    const int smooth = d->def.contact == GB_CONTACT_MODEL_CONTINUOUS;
    if (!d->grid && !(smooth && (d->certify || d->starts)))
        return gb_error_set(GB_EINVAL, "contact = %s gives time-stepping no points to test (allowed: grid or fast-grid, "
                            "whose nodes are a mesh's vertices or a smooth body's grid polyhedron; continuous, the "
                            "smooth body's minima)", gb_contact_model_name(d->def.contact));
    if (d->stepper) return GB_OK;
    gb_dyn_stepper *s = calloc(1, sizeof *s);
    if (!s) return gb_error_set(GB_ENOMEM, "out of memory for the time-stepping strategy");
    int status = grow(s, 8);
    s->smooth = smooth;
    s->nodes = smooth ? GB_DYNAMICS_STEPPING_SLOTS : gb_contact_grid_size(d->grid);
    s->points = status ? NULL : calloc(s->nodes, sizeof *s->points);
    s->gaps = status ? NULL : malloc(s->nodes * sizeof *s->gaps);
    s->candidates = status ? NULL : malloc(s->nodes * sizeof *s->candidates);
    s->keys = status ? NULL : malloc(s->nodes * sizeof *s->keys);
    s->posed = status ? NULL : malloc(s->nodes * sizeof *s->posed);
    s->scratch = status ? NULL : malloc(s->nodes * sizeof *s->scratch);
    if (!status && !(s->points && s->gaps && s->candidates && s->keys && s->posed && s->scratch)) status = gb_error_set(GB_ENOMEM, "out of memory for %zu points", s->nodes);
    for (size_t i = 0; !status && !smooth && i < s->nodes; i++) {
        double phi, theta, x[3];
        gb_contact_grid_node(d->grid, i, &phi, &theta, x);
        for (int k = 0; k < 3; k++) s->points[i][k] = d->def.length * x[k];
        s->radius = fmax(s->radius, gb_vec_norm(s->points[i]));
    }
    /* a smooth body's farthest point, for the reach of a step (how fast a point can near the plane): the farthest on
     * a 1° net of directions, 1 % over it (the distance varies by far less than 1 % between the net's nodes) */
    for (int i = 0; !status && smooth && i <= 180; i++)
        for (int j = 0; j < 360; j++) {
            double x[3];
            gb_surface_position(&d->surface, M_PI * i / 180.0, M_PI * j / 180.0, x);
            s->radius = fmax(s->radius, 1.01 * d->def.length * gb_vec_norm(x));
        }
    if (status) {
        stepper_free(s);
        return status;
    }
    d->stepper = s;
    d->modes = gb_dyn_stepped_modes;
    return GB_OK;
}

static int enumerate(void *context, int n, double *r);

/* The step, θ and solver of a stepping that begins or resumes (a hand-over), from no carrying point (`fresh`) or from
 * those its start marked. */
int gb_dyn_stepping_set(gb_dyn_stepper *s, double h, double theta, const gb_contact_problem_def *solver, int fresh)
{
    if (!(theta >= 0.5 && theta <= 1.0))
        return gb_error_set(GB_EDOM, "theta = %g is out of range (allowed: 0.5 <= theta <= 1)", theta);
    gb_contact_problem *problem = NULL;
    const int status = gb_contact_problem_create(solver, &problem);
    if (status) return status;
    gb_contact_problem_free(s->problem);
    s->problem = problem;
    gb_contact_problem_set_exact(problem, enumerate, s);
    s->theta = theta, s->h = h, s->first = solver->first, s->tolerance = solver->tolerance, s->siconos = solver->siconos;
    if (fresh) s->touched_count = s->last_count = 0;
    s->scanned_valid = 0;
    return GB_OK;
}

int gb_dynamics_stepping_begin(gb_dynamics *d, double t0, double h, double theta, const gb_contact_problem_def *solver)
{
    (void)t0;
    int status = gb_dynamics_stepping_prepare(d);
    if (!status) status = gb_dyn_stepping_set(d->stepper, h, theta, solver, 1);
    if (!status) d->stepper->stats = (gb_dynamics_stepping_stats){0}, d->stepper->contact_steps = 0;
    return status;
}

/* The stepped mode's start, from the definition's height0 and velocity0 (gb_dynamics_init_state, the attitude and ω
 * set): the lowest node height0 above the plane, the centroid at velocity0 (all three components: no mode fixes any),
 * the horizontal position and friction's work 0. No mode's checks: what the plane does is the first step's problem. */
static int stepped_start(gb_dynamics *d, double t0, double y[GB_STATE_SIZE])
{
    double zb[3];
    vertical_of(y, zb);
    y[GB_STATE_ZETA] = 0.0;
    d->stepper->scanned_valid = 0;
    const int status = gb_dyn_stepping_scan(d, y, zb);
    if (status) return status;
    y[GB_STATE_ZETA] = d->def.height0 - d->stepper->clearance;
    const double *v0 = d->def.velocity0;
    memcpy(y + GB_STATE_VELOCITY, v0, 3 * sizeof *y);
    if (d->def.height0 == 0.0) {
        /* on the plane, as the event-driven start reads the scene: the body rolls about its lowest node, at v0's
         * horizontal part where v0 is given (the vertical one the attitude's) */
        double R[9], a[3], wi[3], roll[3];
        gb_dynamics_rotation(y + GB_STATE_Q, R);
        const double *r = d->stepper->points[d->stepper->lowest], *w = y + GB_STATE_OMEGA;
        for (int i = 0; i < 3; i++)
            a[i] = R[3 * i] * r[0] + R[3 * i + 1] * r[1] + R[3 * i + 2] * r[2], wi[i] = R[3 * i] * w[0] + R[3 * i + 1] * w[1] + R[3 * i + 2] * w[2];
        gb_vec_cross(a, wi, roll); /* ω × (G − P) = −ω × a = a × ω */
        const int moving = v0[0] != 0.0 || v0[1] != 0.0 || v0[2] != 0.0;
        y[GB_STATE_VELOCITY + 2] = roll[2];
        if (!moving) y[GB_STATE_VELOCITY] = roll[0], y[GB_STATE_VELOCITY + 1] = roll[1];
    }
    d->stepper->scanned_valid = 0;
    if (d->def.height0 > 0.0) gb_dyn_set_mode(d, GB_DYN_FLIGHT, t0), d->flight.hop_max = d->def.height0;
    return GB_OK;
}

/* The local frame's order: the normal e_z first, then e_x, e_y. */
static const int axis[3] = {2, 0, 1};

/* u = v + B ω at a point, inertial. */
static void point_velocity(const double v[3], double B[3][3], const double w[3], double u[3])
{
    for (int i = 0; i < 3; i++) u[i] = v[i] + B[i][0] * w[0] + B[i][1] * w[1] + B[i][2] * w[2];
}

/* The mode whose time the step books: flight, sliding, or on one, two, three points. */
static gb_dyn_mode_id mode_of(int touching, int sliding)
{
    if (!touching) return GB_DYN_FLIGHT;
    if (sliding) return GB_DYN_SLIDING;
    return touching == 1 ? GB_DYN_ONE_POINT : touching == 2 ? GB_DYN_TWO_POINT : GB_DYN_REST;
}

/* The kinetic energy of (v, ω). */
static double kinetic(const gb_dynamics *d, const double v[3], const double w[3])
{
    double Iw[3];
    gb_dyn_mat_vec((double(*)[3])d->inertia, w, Iw);
    return 0.5 * d->def.mass * gb_vec_dot(v, v) + 0.5 * gb_vec_dot(w, Iw);
}

/* The points that began to carry the body in the step ending at t, each as a record to the caller's sink (kind landing
 * from flight, else switch; the point, its impulses, the body's velocities and kinetic energy before and after the
 * step); the sink's status. */
static int touches(gb_dynamics *d, double t, int from_flight, int count, int touching, const double v[3], const double w[3],
                   const double vplus[3], const double wplus[3])
{
    const gb_dyn_stepper *s = d->stepper;
    for (int k = 0; k < count && d->impact_sink; k++) {
        const int i = s->starts[k];
        const double Pn = s->r[3 * i], Pt = hypot(s->r[3 * i + 1], s->r[3 * i + 2]);
        gb_dynamics_impact e = {.t = t, .kind = from_flight ? GB_DYNAMICS_IMPACT_LANDING : GB_DYNAMICS_IMPACT_SWITCH,
                                .normal_impulse = Pn, .tangential_impulse = Pt, .friction_needed = Pt / Pn,
                                .kinetic_before = kinetic(d, v, w), .kinetic_after = kinetic(d, vplus, wplus),
                                .contacts_after = touching, .return_time = INFINITY};
        memcpy(e.new_point, s->points[s->node[i]], sizeof e.new_point);
        memcpy(e.omega_before, w, sizeof e.omega_before), memcpy(e.omega_after, wplus, sizeof e.omega_after);
        memcpy(e.v_before, v, sizeof e.v_before), memcpy(e.v_after, vplus, sizeof e.v_after);
        const int status = gb_dyn_emit(d, &e);
        if (status) return status;
    }
    return GB_OK;
}

static int compare_keys(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The normal velocity at the step's start of problem point i (attitude R, the centroid's velocity v, ω body w and
 * inertial wi), the velocity Newton's impact law reverses: through its relation B_i where the relations are taken at the
 * step's start (the same bits as the problem's), else (v + ω × R x)_z. */
static double start_normal_velocity(const gb_dyn_stepper *s, int i, const double R[9], const double v[3], const double w[3],
                                    const double wi[3])
{
    if (!s->siconos) {
        double u[3];
        point_velocity(v, s->B[i], w, u);
        return u[2];
    }
    const double *x = s->points[s->node[i]];
    const double a[2] = {R[0] * x[0] + R[1] * x[1] + R[2] * x[2], R[3] * x[0] + R[4] * x[1] + R[5] * x[2]};
    return v[2] + wi[0] * a[1] - wi[1] * a[0];
}

/* Problem point n is node i: its relation B = −[a]× R (a = R r_i) and C = M_ω⁻¹ Bᵀ. */
static void pose(gb_dyn_stepper *s, int n, size_t i, const double R[9], const double Minv[3][3])
{
    const double *x = s->points[i];
    const double a[3] = {R[0] * x[0] + R[1] * x[1] + R[2] * x[2], R[3] * x[0] + R[4] * x[1] + R[5] * x[2],
                         R[6] * x[0] + R[7] * x[1] + R[8] * x[2]};
    s->node[n] = i;
    /* B = −[a]× R: column j is −a × R e_j = R e_j × a */
    for (int j = 0; j < 3; j++) {
        const double col[3] = {R[j], R[3 + j], R[6 + j]};
        double bc[3];
        gb_vec_cross(col, a, bc);
        for (int k = 0; k < 3; k++) s->B[n][k][j] = bc[k];
    }
    for (int k = 0; k < 3; k++) /* C = M_ω⁻¹ Bᵀ */
        for (int j = 0; j < 3; j++)
            s->C[n][k][j] = Minv[k][0] * s->B[n][j][0] + Minv[k][1] * s->B[n][j][1] + Minv[k][2] * s->B[n][j][2];
}

/* The step's problem on a few points solved by enumerating Moreau's law with the cone (gb_impact_coulomb_targets): the
 * body's mass, its rotational mass I + hθc turned to the inertial frame, the free velocities vf, wf (ω in the body's
 * frame), each point leaving at −e times its normal velocity at the step's start (v, w): what Siconos's methods
 * approach only slowly (a contact at the cone's edge whose slip, 1e-14 m/s, has a direction rounding sets) is the
 * enumeration's exact case. The contact problem asks for it where all of Siconos's methods have stalled
 * (gb_contact_problem_exact), the last resort, and measures it: a step they solve is theirs, as before. */
static int enumerate(void *context, int n, double *r)
{
    gb_dyn_stepper *s = context;
    const struct gb_dyn_stepped_step *st = &s->step;
    if (n > GB_IMPACT_CONTACTS_MAX) return gb_error_set(GB_EDOM, "%d points (allowed: at most %d)", n, GB_IMPACT_CONTACTS_MAX);
    const double *R = st->R;
    gb_impact_body body = {.mass = st->m};
    for (int i = 0; i < 3; i++) /* R (I + hθc) Rᵀ */
        for (int j = 0; j < 3; j++) {
            double x = 0.0;
            for (int k = 0; k < 3; k++)
                for (int l = 0; l < 3; l++) x += R[3 * i + k] * st->A[k][l] * R[3 * j + l];
            body.inertia[i][j] = x;
        }
    double points[GB_IMPACT_CONTACTS_MAX][3] = {{0}}, target[GB_IMPACT_CONTACTS_MAX] = {0};
    const double *wf = st->wf;
    const double wi[3] = {R[0] * wf[0] + R[1] * wf[1] + R[2] * wf[2], R[3] * wf[0] + R[4] * wf[1] + R[5] * wf[2],
                          R[6] * wf[0] + R[7] * wf[1] + R[8] * wf[2]};
    for (int i = 0; i < n; i++) {
        const double *x = s->points[s->node[i]];
        for (int k = 0; k < 3; k++) points[i][k] = R[3 * k] * x[0] + R[3 * k + 1] * x[1] + R[3 * k + 2] * x[2];
        const double *R0 = st->R0, wi0[3] = {R0[0] * st->w[0] + R0[1] * st->w[1] + R0[2] * st->w[2],
                                             R0[3] * st->w[0] + R0[4] * st->w[1] + R0[5] * st->w[2],
                                             R0[6] * st->w[0] + R0[7] * st->w[1] + R0[8] * st->w[2]};
        target[i] = -st->e * start_normal_velocity(s, i, R0, st->v, st->w, wi0);
    }
    static const double normal[3] = {0.0, 0.0, 1.0};
    gb_impact_result out;
    const int status = gb_impact_coulomb_targets(&body, normal, st->mu, (const double(*)[3])points, n, st->vf, wi, target,
                                                 s->tolerance, &out);
    if (status) return status;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) r[3 * i + k] = out.impulse[i][axis[k]];
    return GB_OK;
}

int gb_dynamics_stepping_step(gb_dynamics *d, double t, double h, double y[GB_STATE_SIZE])
{
    gb_dyn_stepper *s = d->stepper;
    if (!s) return gb_error_set(GB_EINVAL, "time-stepping was not begun");
    const double m = d->def.mass, c = d->def.damping, th = s->theta;
    const double g0 = gb_forcing_geff(&d->def.forcing, t), g1 = gb_forcing_geff(&d->def.forcing, t + h);
    const double gth = th * g1 + (1.0 - th) * g0;
    double R[9];
    gb_dynamics_rotation(y + GB_STATE_Q, R);
    const double zb[3] = {R[6], R[7], R[8]};
    double v[3], w[3]; /* the step's start (y is overwritten at its end) */
    memcpy(v, y + GB_STATE_VELOCITY, sizeof v), memcpy(w, y + GB_STATE_OMEGA, sizeof w);

    /* free velocities */
    double Minv[3][3], wf[3], vf[3] = {v[0], v[1], v[2] - h * gth};
    double rotational_mass[3][3]; /* I + hθc (Siconos's linearisation: I + hθ J) */
    int status = gb_dyn_stepping_free_rotation(d->inertia, c, w, h, th, s->siconos, rotational_mass, Minv, wf);
    if (status) return status;
    /* the relations are taken at the step's start, or (Siconos's linearisation) at the attitude the step predicts from
     * it, q ⊗ exp(h ω / 2) (its Newton loop evaluates the relation at q_k + h v_k), by Siconos's own exponential (1) or
     * the exact one (2); the gaps and the restitution's velocities at the step's start either way */
    double Rp[9];
    memcpy(Rp, R, sizeof Rp);
    if (s->siconos) {
        double qp[4];
        if (s->siconos == 1) gb_dyn_stepping_siconos_attitude(y + GB_STATE_Q, w, h, qp);
        else gb_dyn_stepping_attitude(y + GB_STATE_Q, w, h, qp);
        gb_dynamics_rotation(qp, Rp);
    }

    /* the candidates: nodes whose gap, half a step ahead at today's speed, is closed */
    const double wi[3] = {R[0] * w[0] + R[1] * w[1] + R[2] * w[2], R[3] * w[0] + R[4] * w[1] + R[5] * w[2],
                          R[6] * w[0] + R[7] * w[1] + R[8] * w[2]};
    /* a point on the plane to rounding is on it: its gap is the rounding of ζ and of the attitude */
    const double activation = GB_DYNAMICS_STEPPING_ACTIVATION * d->mean_radius;
    /* no point moves faster than |v_z| + |ω| r_max + h |g| towards the plane in a step (the weight's kick in it too): one
     * farther than a step of that is far above */
    const double reach = activation + h * (fabs(v[2]) + gb_vec_norm(wi) * s->radius + h * fabs(gth));
    if ((status = gb_dyn_stepping_scan(d, y, zb))) return status;
    const size_t lowest_before = s->lowest;
    size_t count = 0;
    for (size_t i = 0; i < s->nodes; i++) {
        const double *x = s->points[i], gap = s->gaps[i];
        if (gap > reach) continue;
        const double a[3] = {R[0] * x[0] + R[1] * x[1] + R[2] * x[2], R[3] * x[0] + R[4] * x[1] + R[5] * x[2],
                             R[6] * x[0] + R[7] * x[1] + R[8] * x[2]};
        const double un = v[2] + wi[0] * a[1] - wi[1] * a[0]; /* (v + ω × a)_z */
        /* a point that carried the body in the last step stays in the problem within a step's reach: one the body pivots
         * on drifts off the plane by O(h² ω² r) a step (the relation is taken at the step's start), and would otherwise
         * leave it for a step of spurious flight; a point that separates takes no impulse and leaves by its velocity */
        int carried = 0;
        for (int k = 0; k < s->touched_count && !carried; k++) carried = s->touched[k] == i;
        if (gap + 0.5 * h * un > activation && !carried) continue;
        s->candidates[count] = i;
        s->keys[count] = carried ? -INFINITY : gap + 0.5 * h * un;
        s->posed[count++] = 0;
    }
    /* the problem: every candidate, or the most urgent first (in the nodes' order either way) */
    if (s->first && count > s->first) {
        size_t first = 0;
        for (size_t c = 0; c < count; c++) first += s->keys[c] == -INFINITY; /* every carrying point, at least */
        if (first < s->first) first = s->first;
        memcpy(s->scratch, s->keys, count * sizeof *s->scratch);
        qsort(s->scratch, count, sizeof *s->scratch, compare_keys);
        const double cut = s->scratch[first - 1];
        size_t posed = 0;
        for (size_t c = 0; c < count && posed < first; c++)
            if (s->keys[c] <= cut) s->posed[c] = 1, posed++;
    } else {
        for (size_t c = 0; c < count; c++) s->posed[c] = 1;
    }
    int n = 0;
    for (size_t c = 0; c < count; c++) {
        if (!s->posed[c]) continue;
        if ((size_t)n == GB_CONTACT_PROBLEM_MAX)
            return gb_error_set(GB_ENUMERIC, "t = %.9g: more than %d points of the body carry it in one step", t,
                                GB_CONTACT_PROBLEM_MAX);
        if ((status = grow(s, (size_t)n + 1))) return status;
        pose(s, n++, s->candidates[c], Rp, Minv);
    }

    /* the problem and its solution */
    double P[3] = {0}, vplus[3], wplus[3];
    memcpy(vplus, vf, sizeof vplus);
    memcpy(wplus, wf, sizeof wplus);
    const double e = d->def.restitution, mu = d->def.friction;
    s->step = (struct gb_dyn_stepped_step){.m = m, .e = e, .mu = mu};
    memcpy(s->step.A, rotational_mass, sizeof s->step.A), memcpy(s->step.R, Rp, sizeof s->step.R);
    memcpy(s->step.R0, R, sizeof s->step.R0);
    memcpy(s->step.vf, vf, sizeof vf), memcpy(s->step.wf, wf, sizeof wf);
    memcpy(s->step.v, v, sizeof v), memcpy(s->step.w, w, sizeof w);
    /* a candidate left out goes through the plane where its normal velocity after the step falls below this */
    const double through = -GB_DYNAMICS_STEPPING_THROUGH * (fabs(v[2]) + gb_vec_norm(wi) * s->radius + fabs(gth) * h);
    for (int solved = 0, round = 0; n > 0; round++) {
        const int N = 3 * n;
        for (int i = 0; i < n; i++) {
            double uf[3];
            point_velocity(vf, s->B[i], wf, uf);
            for (int k = 0; k < 3; k++) s->q[3 * i + k] = uf[axis[k]];
            s->q[3 * i] += e * start_normal_velocity(s, i, R, v, w, wi);
            s->mu[i] = mu;
            for (int j = 0; j < n; j++) {
                double BC[3][3];
                for (int a = 0; a < 3; a++)
                    for (int bb = 0; bb < 3; bb++)
                        BC[a][bb] = (a == bb) / m + s->B[i][a][0] * s->C[j][0][bb] + s->B[i][a][1] * s->C[j][1][bb] +
                                    s->B[i][a][2] * s->C[j][2][bb];
                for (int a = 0; a < 3; a++)
                    for (int bb = 0; bb < 3; bb++) s->W[(size_t)(3 * j + bb) * (size_t)N + (size_t)(3 * i + a)] = BC[axis[a]][axis[bb]];
            }
        }
        /* warm start: a point of the previous step's problem from its impulse there; a point added after a solution,
         * from 0 (the others keep the solution's) */
        for (int i = solved; i < n; i++) {
            int k = 0;
            while (!round && k < s->last_count && s->last_node[k] != s->node[i]) k++;
            for (int a = 0; a < 3; a++) s->r[3 * i + a] = !round && k < s->last_count ? s->last_r[3 * k + a] : 0.0;
        }
        gb_contact_problem_report report;
        status = gb_contact_problem_solve(s->problem, n, s->W, s->q, s->mu, s->r, s->u, &report);
        s->stats.problems++;
        s->stats.sweeps += report.iterations;
        s->stats.fallbacks += (size_t)report.fallback;
        s->stats.enumerated += (size_t)report.exact;
        s->stats.residual_max = fmax(s->stats.residual_max, report.residual);
        if ((size_t)n > s->stats.contacts_max) s->stats.contacts_max = (size_t)n;
        if (status)
            return gb_error_set(GB_ENOCONV, "time-stepping at t = %.9g (step %zu, %d contact points): %s", t,
                                s->stats.steps + 1, n, gb_error_message());
        P[0] = P[1] = P[2] = 0.0;
        memcpy(vplus, vf, sizeof vplus);
        memcpy(wplus, wf, sizeof wplus);
        for (int i = 0; i < n; i++) {
            const double Pi[3] = {s->r[3 * i + 1], s->r[3 * i + 2], s->r[3 * i]}; /* inertial x, y, z */
            for (int k = 0; k < 3; k++) {
                P[k] += Pi[k];
                for (int j = 0; j < 3; j++) wplus[k] += s->C[i][k][j] * Pi[j];
            }
        }
        for (int k = 0; k < 3; k++) vplus[k] += P[k] / m;
        solved = n;
        /* the candidates left out: zero impulse is their answer where they do not go through the plane (then the
         * solution is the whole problem's); the most violated of those that would are added, and it is solved again */
        const double wp[3] = {Rp[0] * wplus[0] + Rp[1] * wplus[1] + Rp[2] * wplus[2],
                              Rp[3] * wplus[0] + Rp[4] * wplus[1] + Rp[5] * wplus[2],
                              Rp[6] * wplus[0] + Rp[7] * wplus[1] + Rp[8] * wplus[2]};
        int added = 0;
        for (int pass = 0; pass < GB_DYNAMICS_STEPPING_ADD; pass++) {
            size_t worst = count;
            double worst_u = through;
            for (size_t c = 0; c < count; c++) {
                if (s->posed[c]) continue;
                const double *x = s->points[s->candidates[c]];
                const double a[3] = {Rp[0] * x[0] + Rp[1] * x[1] + Rp[2] * x[2], Rp[3] * x[0] + Rp[4] * x[1] + Rp[5] * x[2],
                                     Rp[6] * x[0] + Rp[7] * x[1] + Rp[8] * x[2]};
                const double u = vplus[2] + wp[0] * a[1] - wp[1] * a[0] + e * (v[2] + wi[0] * (R[3] * x[0] + R[4] * x[1] + R[5] * x[2]) -
                                                                               wi[1] * (R[0] * x[0] + R[1] * x[1] + R[2] * x[2]));
                if (u < worst_u) worst_u = u, worst = c;
            }
            if (worst == count) break;
            if ((size_t)n == GB_CONTACT_PROBLEM_MAX)
                return gb_error_set(GB_ENUMERIC, "t = %.9g: more than %d points of the body carry it in one step", t,
                                    GB_CONTACT_PROBLEM_MAX);
            if ((status = grow(s, (size_t)n + 1))) return status;
            s->posed[worst] = 1;
            pose(s, n++, s->candidates[worst], R, Minv);
            added++;
        }
        if (!added) break;
        s->stats.grown++;
    }
    if (count > s->stats.candidates_max) s->stats.candidates_max = count;
    memcpy(s->last_node, s->node, (size_t)n * sizeof *s->node);
    s->last_count = n;
    memcpy(s->last_r, s->r, (size_t)(3 * n) * sizeof *s->r);

    /* what the contacts did: who touches, who slips, the energy the impulses took */
    /* a slip is a slip above a millionth of the speed the weight gives in one step (1 m/s² standing in for a plane
     * without weight): far above the solver's residual (1e-12 of the problem's velocities), far below any slide */
    const double slip_tol = 1e-6 * (fabs(gth) + 1.0) * h;
    int touching = 0, sliding = 0, new_touches = 0;
    double loss = 0.0, friction = 0.0, slip_max = 0.0, taken = 0.0, taken_scale = 0.0;
    for (int i = 0; i < n; i++) {
        const double Pi[3] = {s->r[3 * i + 1], s->r[3 * i + 2], s->r[3 * i]};
        if (!(Pi[2] > 0.0)) continue;
        double up[3], uf[3];
        point_velocity(vplus, s->B[i], wplus, up);
        point_velocity(vf, s->B[i], wf, uf);
        for (int k = 0; k < 3; k++) {
            taken -= Pi[k] * (up[k] + uf[k]) / 2.0;
            taken_scale += fabs(Pi[k]) * (fabs(up[k]) + fabs(uf[k]));
        }
        uf[2] += h * gth; /* without gravity's kick: a body at rest takes nothing */
        const double dn = -Pi[2] * (up[2] + uf[2]) / 2.0, dt = -(Pi[0] * (up[0] + uf[0]) + Pi[1] * (up[1] + uf[1])) / 2.0;
        loss += dn, friction -= dt;
        const double slip = hypot(up[0], up[1]);
        slip_max = fmax(slip_max, slip);
        sliding += slip > slip_tol;
        int before = 0;
        for (int k = 0; k < s->touched_count && !before; k++) before = s->touched[k] == s->node[i];
        if (!before) s->starts[new_touches++] = i; /* a point begins to carry the body */
        s->touching_now[touching++] = s->node[i];
    }
    size_t *swap = s->touched;
    s->touched = s->touching_now, s->touching_now = swap, s->touched_count = touching;
    /* the step's dissipation: the impulses' work at all points together (at one of several points that share a load it
     * has no meaning: the impulses the solver spreads over a face are not unique) */
    const double dissipation = loss - friction;
    s->stats.dissipation_min = fmin(s->stats.dissipation_min, dissipation);
    s->stats.energy_gained += fmax(0.0, -dissipation);
    s->stats.negative_dissipation += dissipation < -1e-12 * (m * fabs(gth) * fabs(gth) * h * h + fabs(loss) + fabs(friction));
    /* what the problem took from the free motion: below zero only by the solver's residual (its tolerance of the
     * problem's velocities, times the impulses) and rounding */
    if (touching) {
        s->stats.contact_dissipation_min = s->contact_steps++ ? fmin(s->stats.contact_dissipation_min, taken) : taken;
        s->stats.contact_negative += taken < -fmax(s->tolerance, 1e-13) * taken_scale;
    }
    d->impacts += (size_t)new_touches;
    d->impact_loss += loss;
    if (touching) d->impact_friction_max = fmax(d->impact_friction_max, hypot(P[0], P[1]) / P[2]);

    /* positions */
    double vt[3], wt[3];
    for (int k = 0; k < 3; k++) vt[k] = th * vplus[k] + (1.0 - th) * v[k], wt[k] = th * wplus[k] + (1.0 - th) * w[k];
    const double zeta0 = y[GB_STATE_ZETA], zeta1 = zeta0 + h * vt[2];
    double wbar[3];
    for (int k = 0; k < 3; k++) wbar[k] = 0.5 * (wplus[k] + w[k]);
    y[GB_STATE_WORK] += m * (g1 - g0) * (zeta0 + zeta1) / 2.0 - c * h * gb_vec_dot(wt, wbar);
    y[GB_STATE_ZETA] = zeta1;
    y[GB_STATE_POSITION] += h * vt[0];
    y[GB_STATE_POSITION + 1] += h * vt[1];
    y[GB_STATE_FRICTION] += friction;
    memcpy(y + GB_STATE_VELOCITY, vplus, sizeof vplus);
    double qn[4];
    gb_dyn_stepping_attitude(y + GB_STATE_Q, wt, h, qn);
    memcpy(y + GB_STATE_Q, qn, sizeof qn);
    memcpy(y + GB_STATE_OMEGA, wplus, sizeof wplus);
    status = gb_dyn_state_finite(t + h, y);
    if (status) return status;

    /* the counters: the mode booked, lift-offs and landings, slips and sticks, the lowest node's changes */
    const gb_dyn_mode_id before = d->mode, after = mode_of(touching, sliding);
    if (before != GB_DYN_FLIGHT && after == GB_DYN_FLIGHT) d->flight.lift_offs++;
    if (before == GB_DYN_FLIGHT && after != GB_DYN_FLIGHT) d->flight.landings++;
    if (before != GB_DYN_SLIDING && after == GB_DYN_SLIDING) d->slide.slips++;
    if (before == GB_DYN_SLIDING && after != GB_DYN_SLIDING && after != GB_DYN_FLIGHT) d->slide.sticks++;
    gb_dyn_set_mode(d, after, t + h);
    double zb1[3];
    vertical_of(y, zb1);
    if ((status = gb_dyn_stepping_scan(d, y, zb1))) return status; /* the next step's and the observer's */
    if (s->lowest != lowest_before) d->grid_switches++, d->last_switch_time = t + h;
    if (after == GB_DYN_FLIGHT) d->flight.hop_max = fmax(d->flight.hop_max, s->clearance);
    s->touching = touching, s->sliding = sliding, s->slip_max = slip_max;
    s->normal_impulse = P[2];
    memcpy(s->tangential, P, sizeof s->tangential);
    s->stats.steps++;
    s->stats.contact_points += (size_t)n;
    return touches(d, t + h, before == GB_DYN_FLIGHT, new_touches, touching, v, w, vplus, wplus);
}

const gb_dynamics_stepping_stats *gb_dynamics_stepping_stats_of(const gb_dynamics *d)
{
    return d->stepper ? &d->stepper->stats : NULL;
}

void gb_dyn_stepping_adopt(gb_dynamics *to, const gb_dynamics *from)
{
    gb_dyn_stepper *t = to->stepper;
    const gb_dyn_stepper *f = from->stepper;
    if (!t || !f || grow(t, f->capacity)) return; /* a failed growth: the copy starts cold, as a fresh run does */
    t->touched_count = f->touched_count, t->last_count = f->last_count;
    memcpy(t->touched, f->touched, (size_t)f->touched_count * sizeof *t->touched);
    memcpy(t->last_node, f->last_node, (size_t)f->last_count * sizeof *t->last_node);
    memcpy(t->last_r, f->last_r, 3 * (size_t)f->last_count * sizeof *t->last_r);
    t->touching = f->touching, t->sliding = f->sliding, t->slip_max = f->slip_max;
    t->normal_impulse = f->normal_impulse;
    memcpy(t->tangential, f->tangential, sizeof t->tangential);
    t->lowest = f->lowest;
    t->scanned_valid = 0;
    if (t->smooth) { /* the minima the nodes name */
        memcpy(t->slot, f->slot, sizeof t->slot), memcpy(t->active, f->active, sizeof t->active);
        t->next_slot = f->next_slot;
    }
}
