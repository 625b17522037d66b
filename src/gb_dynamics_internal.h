/* gb_dynamics_internal — the hybrid system's parts, shared by the files of the dynamics (internal).
 *
 * The body on the plane is a hybrid system: a few modes, each with smooth equations, joined by events (a
 * function of the state crossing zero, located by gb_integrate's one locator) and jumps (a map from the
 * state just before an event to the state just after it). The files, from the top down (each calls only
 * files below it; docs/layout.md draws them):
 *   gb_dynamics_hybrid.c    the hybrid system as a whole: the one table of modes (each mode's field, step,
 *                           observables and translation with its events and jumps), creation and start,
 *                           and every public call that goes to the current mode
 *   gb_dynamics_jumps.c     the jump maps at the events, each calling the generic impact law (gb_impact)
 *   gb_dynamics_faces.c     a polyhedron's face landing flat: several nodes reaching the plane at once
 *   gb_dynamics_events.c    the events that end a mode: their functions (pending, gap)
 *   gb_dynamics_two_point.c the mode "rolling on two points" (the crease)
 *   gb_dynamics_rest.c      the mode "at rest on three points"
 *   gb_dynamics_flight.c    the mode "flight"
 *   gb_dynamics_compliant.c the compliant law: its row, its keys and its one smooth mode
 *   gb_dynamics_rolling.c   the mode "rolling on one point" (eq 44 and the rolling equation)
 *   gb_dynamics_impulses.c  what every jump shares: restitution, the plane only pushing, a return's time
 *   gb_dynamics_on_plane.c  the kinematics every mode on the plane shares (eq 40, ω̇, N, the translation)
 *   gb_dynamics_ledger.c    what every change of contact leaves: its record, the counters, the energy taken,
 *                           the caller's sink
 *   gb_dynamics_contact.c   the contact at a state: the grid's nodes, Newton's continuation, the
 *                           certificate's competitor
 *   gb_dynamics_context.c   the body's set-up (mass properties, grid, tracker, certificate, atlas), kept in
 *                           the caller's context with the files of its caches
 *   gb_dynamics_laws.c      the contact laws (held, unilateral, compliant) as a table of what each does; the only
 *                           file that tells one law from another
 *   gb_dynamics.c           the state: the definition, the attitude, the mode and its time, the vector
 *                           field of the current mode through the table the state carries, the counters
 * A mode asks for another's accelerations through gb_dyn_field alone (the lift-off test's look along the
 * flow included), never by name. */
#ifndef GB_DYNAMICS_INTERNAL_H
#define GB_DYNAMICS_INTERNAL_H

#include "gb_dynamics.h"
#include "gb_contact_internal.h"
#include "gb_impact.h"
#include "gb_massprops.h"

#include <stddef.h>

/* ---- the modes and the events ------------------------------------------------------------------- */

typedef enum gb_dyn_mode_id {
    GB_DYN_ONE_POINT = 0, /* rolling on one point (the held law's only mode) */
    GB_DYN_TWO_POINT = 1, /* rolling on two points along a crease */
    GB_DYN_REST = 2,      /* at rest on three points */
    GB_DYN_FLIGHT = 3,    /* off the plane */
    GB_DYN_SLIDING = 4,   /* on one or two points, at least one slipping (a plane of finite friction) */
    GB_DYN_MODES = 5
} gb_dyn_mode_id;

/* The event gb_dynamics_switch_pending found, for gb_dynamics_branch_gap, gb_dynamics_switch_to and
 * gb_dynamics_jump. */
typedef enum gb_dyn_event {
    GB_DYN_EVENT_NONE = 0,
    GB_DYN_EVENT_SWITCH = 1,   /* one point: another minimum lower than the contact (a change of contact) */
    GB_DYN_EVENT_LIFT_OFF = 2, /* one point or at rest: the normal force (g_eff at rest) reaches 0 */
    GB_DYN_EVENT_LANDING = 3,  /* flight: the lowest point reaches the plane */
    GB_DYN_EVENT_LIFT = 4,     /* two points: a normal force reaches 0 */
    GB_DYN_EVENT_THIRD = 5,    /* two points: a third point reaches the plane */
    GB_DYN_EVENT_SLIP = 6,     /* finite friction: a sticking contact's force reaches the cone's edge */
    GB_DYN_EVENT_STICK = 7     /* finite friction: a slipping contact's slip stops (or turns back) */
} gb_dyn_event;

/* What a mode's vector field gives besides ω̇ and ζ where the translation is integrated (a plane of finite
 * friction): the centroid's acceleration relative to the plane (inertial axes) and the power of friction. */
typedef struct gb_dyn_rates {
    double acc[3];
    double friction_power; /* the power of the contact's dissipative forces (<= 0) */
    double zeta_rate;      /* ζ̇ where the mode integrates the height too (a law of its own); else 0, the mode
                            * writing ζ at each accepted step */
} gb_dyn_rates;

/* What a mode is: its vector field and what ends it. The state's attitude and ω are integrated; `turns`
 * 0 makes ω read as 0 whatever the state holds (at rest). */
typedef struct gb_dyn_mode {
    const char *name;
    int turns;
    /* ω̇ and the centroid's height ζ above the plane at (t, y), with ω (0 where nothing turns), vertical zb and
     * g_eff */
    int (*field)(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double omega[3], const double zb[3],
                 double geff, double omega_dot[3], double *zeta, gb_dyn_rates *rates /* NULL: not wanted */);
    /* after an accepted step: the contact continued and checked, changes with no jump made */
    int (*accept)(gb_dynamics *d, double t, double y[GB_STATE_SIZE]);
    /* is an event of this mode due at y? (its kind into d->event) */
    int (*pending)(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found);
    /* the pending event's function, < 0 before it and > 0 after */
    int (*gap)(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other, double *gap,
               gb_contact_point *other_here);
    /* the jump at the located event (booked) */
    int (*event)(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch);
    /* what the jump would make of y, nothing booked (the saltation's map) */
    int (*jump)(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                double out[GB_STATE_SIZE]);
    int (*observe)(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_observables *o);
    /* the translation the mode fixes, written into y at an accepted state (time t) */
    void (*translate)(const gb_dynamics *d, double t, double y[GB_STATE_SIZE]);
    /* a law's own mode: its start at t0 from the definition's height0 and velocity0, the contact found and y's
     * attitude and ω set (NULL: the hybrid system's start in gb_dynamics_init_state) */
    int (*start)(gb_dynamics *d, double t0, double y[GB_STATE_SIZE]);
} gb_dyn_mode;

/* The modes' own functions (gb_dynamics_hybrid.c puts them in its table with their events and jumps). */
int gb_dyn_one_point_field(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double omega[3], const double zb[3],
                           double geff, double omega_dot[3], double *zeta, gb_dyn_rates *rates);
int gb_dyn_one_point_accept(gb_dynamics *d, double t, double y[GB_STATE_SIZE]);
int gb_dyn_one_point_observe(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_observables *o);
int gb_dyn_two_point_field(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double omega[3], const double zb[3],
                           double geff, double omega_dot[3], double *zeta, gb_dyn_rates *rates);
int gb_dyn_two_point_accept(gb_dynamics *d, double t, double y[GB_STATE_SIZE]);
int gb_dyn_two_point_observe(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_observables *o);
int gb_dyn_rest_field(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double omega[3], const double zb[3],
                      double geff, double omega_dot[3], double *zeta, gb_dyn_rates *rates);
int gb_dyn_rest_accept(gb_dynamics *d, double t, double y[GB_STATE_SIZE]);
int gb_dyn_rest_observe(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_observables *o);
void gb_dyn_rest_translate(const gb_dynamics *d, double t, double y[GB_STATE_SIZE]);
int gb_dyn_flight_field(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double omega[3], const double zb[3],
                        double geff, double omega_dot[3], double *zeta, gb_dyn_rates *rates);
int gb_dyn_flight_accept(gb_dynamics *d, double t, double y[GB_STATE_SIZE]);
int gb_dyn_flight_observe(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_observables *o);
void gb_dyn_flight_translate(const gb_dynamics *d, double t, double y[GB_STATE_SIZE]);

/* ---- the contact laws ------------------------------------------------------------------------------ */

/* The laws are rows of gb_dynamics_law (gb_dynamics.h): the rest of the library reads their traits and never tells
 * one law from another. */
/* The compliant law's row and its one mode (gb_dynamics_compliant.c). */
extern const gb_dynamics_law gb_dyn_compliant_law;
extern const gb_dyn_mode gb_dyn_compliant_mode;
/* The definition's law against its contact model and equation: GB_OK, or GB_EINVAL saying what is allowed. */
int gb_dyn_law_check(const gb_dynamics_def *def);

/* ---- the modes' own state --------------------------------------------------------------------------- */

/* Flight's (gb_dynamics_flight.c): since t0 the centroid moves under g_eff alone, from height zeta0 above the
 * plane with velocity v0 (inertial, relative to the plane): closed form (gb_dyn_flight_state); the highest gap
 * between the lowest point and the plane at an accepted step of a flight, and the lift-offs, landings and
 * bounces so far. */
typedef struct gb_dyn_flight {
    double t0, zeta0, v0[3];
    double hop_max;
    size_t lift_offs, landings, bounces;
    size_t flying_on; /* landings after which no point stayed on the plane, with no rebound: a point struck, the body
                       * turned off the plane */
} gb_dyn_flight;

/* The two-point mode's (gb_dynamics_two_point.c): how often it was entered from one point, the impacts the settle
 * rule ended (`settled`), the lifts and the third points that ended it; and Q's Newton predictor, as the state's
 * last_* for P: the last Q found, its vertical and sensitivity (q_valid). */
typedef struct gb_dyn_crease {
    size_t entries, settled, lifts, third_points;
    int q_valid;
    double q_zb[3], q_dq[2][3];
    gb_contact_point q_last; /* that Q (its chart and coordinates start the predictor) */
} gb_dyn_crease;

/* The sliding mode's (a plane of finite friction, gb_dynamics_sliding.c): the body is on `count` points (contact,
 * and contact2 when 2), each sticking or slipping (slides[k]); a point that slips from rest slips first along
 * start[k] (inertial axes, horizontal), after which its slip's own direction takes over; ref[k] is its direction at
 * the accepted state (the stop's event function), armed[k] whether the slip has grown past rounding since it
 * started (its stop is then an event); the changes from sticking to slipping and back so far. */
typedef struct gb_dyn_sliding {
    int count, slides[2];
    double start[2][3], ref[2][3];
    int armed[2];
    size_t slips, sticks;
} gb_dyn_sliding;

/* ---- the state ----------------------------------------------------------------------------------- */


struct gb_dynamics {
    gb_surface surface;
    gb_dynamics_def def;
    const gb_dynamics_law *law;
    const gb_dyn_mode *modes;    /* the one table of modes (gb_dynamics_hybrid.c), indexed by mode */
    gb_dyn_mode_id mode;
    gb_dyn_event event;          /* the event gb_dynamics_switch_pending found (GB_DYN_EVENT_NONE: none) */
    double settle_time;   /* the end to chatter [s]: def.settle_time, or the integrator's step where it is 0 */
    double step;          /* the integrator's step [s] (gb_dynamics_use_step; 0 before a run) */
    double inertia[3][3]; /* I_C [kg m²] */
    double mean_radius;   /* L [m] (eq 53) */
    gb_dynamics_context *context; /* the caller's, or the run's own (own_context) */
    int own_context;
    gb_contact_grid *grid;
    gb_contact_tracker *tracker; /* exact grid search along the trajectory (fast-grid) */
    int grid_borrowed;           /* grid (and tracker) belong to the context */
    gb_certify *certify;         /* the global-minimum certificate (continuous) */
    gb_atlas *atlas;             /* certificate = atlas */
    gb_contact_grid *starts;     /* certificate = multi-start: the grid whose local minima seed Newton */
    size_t multistart_checks, multistart_lower, multistart_seeds;
    int atlas_borrowed;          /* the atlas belongs to the context */
    size_t atlas_fallbacks;      /* checks the atlas left to gb_certify */
    gb_contact_refine_def refine;
    /* The contact at the last accepted state. */
    size_t index;
    gb_contact_point contact;
    /* Newton's predictor for continuous contact: (φ, θ) ≈ contact + rate (t − contact_time), with the
     * rate of eq 72 at the accepted state; the start changes which minimum is reached only across a fold,
     * and otherwise its last bits at most. The rate is computed when a start first needs it (rate_pending:
     * from the accepted state's vertical, ω and contact, kept as they were), which is seldom: the start
     * below serves every evaluation but the first after a switch or an event. */
    double contact_time, contact_rate[2];
    int rate_pending;
    double rate_zb[3], rate_omega[3];
    gb_contact_point rate_contact;
    /* ... or, when valid, from the last contact found (at any evaluation since the accepted state) by its
     * sensitivity (eq 70): (φ, θ) ≈ last + ∂(φ, θ)/∂z_b (z_b − z_b,last). Between the two middle stages of
     * RK4 the verticals differ by O(h²) and this start is the minimum to ~1e-12 rad. */
    int last_valid;
    double last_zb[3], last_dq[2][3];
    gb_contact_point last_point; /* that contact: an evaluation at the same vertical takes it as it is */
    double energy0, t0;
    size_t grid_switches, branch_switches;
    size_t contact_queries, nodes_visited; /* grid models: the searches' work */
    double last_switch_time; /* of the latest grid or branch switch (NAN before the first) */
    size_t branches_lost; /* continuous: evaluations where the continued branch had no minimum */
    /* Impacts (a law with impacts): how many, the kinetic energy they took (L), the largest friction needed. */
    size_t impacts;
    double impact_loss, impact_friction_max;
    size_t next_hint; /* a grid body: the last next node found (gb_dyn_next_node) */
    gb_dynamics_impact_sink impact_sink;
    void *impact_context;
    /* The time booked to each mode (gb_dyn_set_mode): since when the body is in it (the last entry; NAN before
     * the first), and how long it was in it before. */
    double mode_since[GB_DYN_MODES], mode_time[GB_DYN_MODES];
    /* On two points (rolling on a crease, sliding on two): `contact` (P) and `contact2` (Q) at once. */
    gb_contact_point contact2;
    gb_dyn_crease crease; /* the two-point mode's own (gb_dynamics_two_point.c) */
    /* After a lift from two points (continuous contact): the point that lifted, and how far below the
     * contact it may dip before its return counts as a change of contact (GB_DYN_LIFT_OFF_DIP_MAX), until
     * its gap has opened (lift_allow is 0 when none is pending). */
    gb_contact_point lifted;
    double lift_allow;
    /* In flight `contact` is the lowest point, continued and certified as a contact is; a landing is that point
     * gap_allow below the plane [body lengths]: GB_DYN_GAP_TOL, or a lift-off's dip until the gap has opened. */
    double gap_allow;
    gb_dyn_flight flight;  /* flight's own (gb_dynamics_flight.c) */
    gb_dyn_sliding slide;  /* the sliding mode's own (gb_dynamics_sliding.c) */
    int event_point;       /* the point (0: contact, 1: contact2) the pending slip, stop or lift is of */
    /* The last competitor() answer and the state it was for: with switch location, the step's end is
     * checked by gb_dynamics_switch_pending and then again by gb_dynamics_accept at the same state. */
    int memo_valid, memo_found;
    gb_dyn_event memo_event;
    /* g_eff and its rate at the field's last time: RK4's second and third stages share their time, and a
     * step's first stage has its predecessor's last (the forcing is fixed for the dynamics' life) */
    int forcing_valid;
    double forcing_t, forcing_geff, forcing_rate;
    double memo_key[8];
    gb_contact_point memo_continued, memo_other;
    struct gb_dyn_stepper *stepper; /* the time-stepping strategy's (gb_dynamics_stepping.c; NULL: events) */
    const gb_dyn_mode *event_modes;       /* a run handed to time-stepping: the event-driven modes it returns to */
    char start_limit[512];                /* handed over at its start: the limit the start met ("" otherwise) */
    /* Impacts held back from the sink (gb_dynamics_hold_impacts): a step that may be taken again (a hand-over) sends
     * its records only once it is kept. */
    int holding;
    gb_dynamics_impact *held;
    size_t held_count, held_capacity;
};

typedef struct gb_dyn_stepper gb_dyn_stepper;
/* The time-stepping strategy's state, released (gb_dynamics_stepping.c); and copied from another dynamics of the same
 * body (the points that carried the body, the impulses the solver starts from: gb_dynamics_adopt_contact). */
void gb_dyn_stepping_free(gb_dynamics *d);
/* A change of contact's record to the caller's sink, or held back while impacts are held (gb_dynamics_ledger.c). */
int gb_dyn_emit(gb_dynamics *d, const gb_dynamics_impact *e);
void gb_dyn_stepping_adopt(gb_dynamics *to, const gb_dynamics *from);
/* A start the law refuses at one of its limits (gb_dynamics_init_or_hand_over): the dynamics in the stepped mode before
 * its start, the limit's message kept; after the stepped start, the lowest point marked as carrying the body. */
int gb_dyn_stepping_take_start(gb_dynamics *d, const char *limit);
void gb_dyn_stepping_stand(gb_dynamics *d);

/* ---- the state (gb_dynamics.c) --------------------------------------------------------------------- */

/* The current mode's entry in the table. */
static inline const gb_dyn_mode *gb_dyn_current(const gb_dynamics *d) { return &d->modes[d->mode]; }

/* The vertical z_b = Rᵀ e_z of state y (q need not be normalised), and of a quaternion. */
void gb_dyn_vertical(const double y[GB_STATE_SIZE], double zb[3]);
void gb_dyn_vertical_of_quaternion(const double q[4], double zb[3]);
/* The current mode's vector field: dy/dt at (t, y) (the one way a mode asks for another's accelerations). */
int gb_dyn_field(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], double dydt[GB_STATE_SIZE]);
/* The run's law coefficient in `slot`: the definition's, or its key's fallback where it is NAN. */
double gb_dyn_coefficient(const gb_dynamics *d, int slot);
/* Enter mode `mode` at time t: the time spent in the mode left is booked, the new one's start noted. */
void gb_dyn_set_mode(gb_dynamics *d, gb_dyn_mode_id mode, double t);
/* The time spent in mode `mode` up to t. */
double gb_dyn_mode_time(const gb_dynamics *d, gb_dyn_mode_id mode, double t);
/* "t = ...: the state is no longer finite" (GB_ENUMERIC). */
int gb_dyn_diverged(double t);
/* GB_ENUMERIC (gb_dyn_diverged) when a component of y is not finite; GB_OK otherwise. */
int gb_dyn_state_finite(double t, const double y[GB_STATE_SIZE]);
/* A body vector in inertial axes at state y: R b. */
void gb_dyn_to_inertial(const double y[GB_STATE_SIZE], const double body[3], double out[3]);
/* A v, and the solution of A x = b for a symmetric positive-definite 3 × 3 A (GB_ENUMERIC when singular). */
void gb_dyn_mat_vec(double A[3][3], const double v[3], double out[3]);
/* A body whose centroid moves freely (flight, sliding), o's velocity, ω, g_eff and ζ set: its kinetic,
 * potential and total energy, the powers, W, friction's work and the ledger E − E0 − W + L. */
void gb_dyn_observe_free_energy(const gb_dynamics *d, const double y[GB_STATE_SIZE], gb_dynamics_observables *o);
int gb_dyn_solve3(double A[3][3], const double b[3], double x[3]);

/* ---- the body and its context (gb_dynamics_context.c) --------------------------------------------- */

/* The body's set-up for d (surface, def and context set; a context of its own when none): mass properties,
 * and the grid and tracker or the certificate and atlas its contact model needs; and its release. */
int gb_dyn_body_create(gb_dynamics *d);
void gb_dyn_body_free(gb_dynamics *d);
/* The context's lowest-node search of one's own (make bench): 1 with it, 0 when there is none. */
int gb_dyn_lowest_hook(const gb_dynamics *d, gb_dynamics_lowest_node *lowest, void **user);

/* ---- the contact at a state (gb_dynamics_contact.c) ------------------------------------------------ */

/* The contact at a state: r_c and ṙ_c [m, m/s], the grid node, the point. */
typedef struct gb_dyn_contact {
    double rc[3], rc_dot[3];
    size_t index;
    gb_contact_point point; /* continuous model; grid models under a law with impacts */
} gb_dyn_contact;

/* Two grid nodes whose heights differ by less than this [body length] are tied, not one below the other:
 * a few units of the last place of h (|x| < 1.19). Nodes of a ring around a chart pole tie exactly at
 * some attitudes; a tie is not a crossing, and the event is located where the new node is lower by this. */
#define GB_DYN_GRID_TIE 4e-15

/* A grid body that pivots about its node until an event (a law with impacts), rather than taking the lowest
 * node at every evaluation (the held law's grid). */
int gb_dyn_pivots(const gb_dynamics *d);
void gb_dyn_grid_point(const gb_dynamics *d, size_t index, const double zb[3], gb_contact_point *p);
int gb_dyn_next_node(gb_dynamics *d, const double zb[3], gb_contact_point *other);
int gb_dyn_point_at(gb_dynamics *d, const double zb[3], const gb_contact_point *from, gb_contact_point *out);
int gb_dyn_point_rate(const gb_dynamics *d, const double zb[3], const gb_contact_point *p, const double w[3], double v[3]);
int gb_dyn_contact_at(gb_dynamics *d, double t, const double zb[3], const double omega[3], gb_dyn_contact *c);
int gb_dyn_contact_global(gb_dynamics *d, const double zb[3]);
int gb_dyn_remember_rate(gb_dynamics *d, double t, const double y[GB_STATE_SIZE]);
void gb_dyn_forget_rate(gb_dynamics *d); /* no predictor until the next accepted step */
/* The global minimum at zb from scratch: gb_certify's, or with certificate = multi-start the lowest polished local
 * minimum of the branch grid (gb_dynamics_contact.c). */
int gb_dyn_global_minimum(gb_dynamics *d, const double zb[3], gb_contact_point *out);
int gb_dyn_check_global(gb_dynamics *d, const double zb[3], const gb_contact_point *candidate, gb_certify_result *r);
int gb_dyn_canonical_minimum(gb_dynamics *d, const double zb[3], gb_contact_point *p);
int gb_dyn_same_point(const gb_contact_point *a, const gb_contact_point *b);
int gb_dyn_competitor(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *continued,
                      gb_contact_point *other, int *found);
void gb_dyn_set_contact(gb_dynamics *d, const gb_contact_point *p);

/* ---- on the plane (gb_dynamics_on_plane.c): what every mode on the plane shares ------------------------ */

/* I_P = I_C − m [r_c]×[r_c]× (eq 40). */
void gb_dyn_inertia_about(const gb_dynamics *d, const double rc[3], double IP[3][3]);
/* ω̇ from eq 44 (paper) or the rolling equation, for the contact c and g_eff at the time. */
int gb_dyn_angular_acceleration(const gb_dynamics *d, double geff, const double zb[3], const double omega[3],
                                const gb_dyn_contact *c, double omega_dot[3]);
/* The centroid's acceleration under rolling kinematics into acc, and the normal force N = m (g_eff + z_b·a_G). */
double gb_dyn_normal_force(const gb_dynamics *d, double geff, const double zb[3], const double omega[3],
                           const double omega_dot[3], const gb_dyn_contact *c, double acc[3]);
/* On the plane: the centroid's height −z_b·r_c and velocity R (ω × (G − P)) about the accepted contact P. */
void gb_dyn_translate_on_plane(const gb_dynamics *d, double t, double y[GB_STATE_SIZE]);
/* The observables every mode on the plane shares, from its contact c, ω̇ (in o) and point count. */
void gb_dyn_observe_on_plane(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_dyn_contact *c, int contacts,
                             gb_dynamics_observables *o);

/* ---- rolling on one point (gb_dynamics_rolling.c) --------------------------------------------------- */

/* Rolling on the accepted contact alone at state y: its normal force. */
int gb_dyn_one_point_normal(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], double *n);

/* ---- rolling on two points (gb_dynamics_two_point.c) ------------------------------------------------ */

typedef struct gb_dyn_two_point {
    gb_dyn_contact p;         /* P, continued as the one-point contact is */
    gb_contact_point q;       /* Q, continued by Newton from the accepted Q */
    double rp[3], rq[3];      /* [m], from the centroid */
    double u[3], dist;        /* (r_P − r_Q) / |r_P − r_Q|, |r_P − r_Q| */
    double sigma, omega_dot[3];
    double normal[2];         /* N_P, N_Q */
    double friction_needed, balance;
    double acc[3];            /* with forces: the centroid's acceleration (body axes) */
    double tangent[2][3];     /* with forces: the tangential forces at P and Q, their open part along PQ split
                               * as the normal forces (gb_dyn_crease_margin moves it) */
    int merged;               /* the end of a crease: Q merged with P or vanished; only p is filled */
} gb_dyn_two_point;

/* Q of the two-point mode at vertical zb (Newton from the last Q, by its sensitivity; a grid node as it is). */
int gb_dyn_second_point(gb_dynamics *d, const double zb[3], gb_contact_point *q);

/* The mode at state y: the points, σ and ω̇; with `forces`, the normal forces, the friction they need and
 * the balance too. */
int gb_dyn_two_point_eval(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dyn_two_point *tp, int forces);

/* A polyhedron's face landing flat while the body rolls on its edge PQ (gb_dynamics_faces.c): the third
 * point R of the located event and the nodes tied with it; *handled 0 (nothing done) when no node ties. */
int gb_dyn_face_landing(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_dyn_two_point *tp,
                        const gb_contact_point *third, int *handled);
/* How many nodes other than P, Q and R tie with R's height at vertical zb (0 for a smooth body's grid). */
int gb_dyn_face_ties(const gb_dynamics *d, const double zb[3], const gb_contact_point *p, const gb_contact_point *q,
                     const gb_contact_point *third);

/* ---- flight (gb_dynamics_flight.c) ---------------------------------------------------------------- */

/* A landing is the lowest point this far below the plane [body lengths] (gb_dynamics.h). */
#define GB_DYN_GAP_TOL GB_DYNAMICS_LANDING_TOL
/* The deepest dip a lift-off may make [body lengths]: a micrometre for a body of a metre, below the elastic
 * compliance of any real body under its own weight. */
#define GB_DYN_LIFT_OFF_DIP_MAX 1e-6

/* In flight at time t: the centroid's height above the plane and its velocity relative to it (inertial). */
void gb_dyn_flight_state(const gb_dynamics *d, double t, double *zeta, double v[3]);
/* Torque-free but for the damping torque: I_G ω̇ + ω × I_G ω = −c ω. */
int gb_dyn_free_acceleration(const gb_dynamics *d, const double omega[3], double omega_dot[3]);
/* The body leaves the plane (or bounces) at time t: its centroid at height zeta, moving with v_body (body
 * axes) relative to the plane. */
void gb_dyn_start_flight(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double v_body[3], double zeta);

/* ---- a plane of finite friction (gb_dynamics_sliding.c) ------------------------------------------ */

/* Coulomb's law at the points of contact between impacts: each point sticks (its material point's
 * acceleration is the rolling contact's, its force unknown) or slips along `slip` (body axes, horizontal,
 * unit: its force N (z_b − μ slip), N unknown, and only its height held on the plane). */
typedef struct gb_dyn_friction_point {
    double r[3], rdot[3];    /* from the centroid, and its rate on the surface [m, m/s] (body axes) */
    int slides;
    double slip[3];
} gb_dyn_friction_point;

typedef struct gb_dyn_friction_forces {
    double omega_dot[3], acc[3];  /* ω̇, and the centroid's acceleration (body axes) */
    double force[2][3];           /* each point's force (body axes) */
    double normal[2], margin[2];  /* N, and μ N − |F_t| (a sticking point; μ N for a slipping one) */
    double slip_acc[2][3];        /* each material point's tangential acceleration (body axes) */
} gb_dyn_friction_forces;

/* The accelerations and forces of 1 or 2 points (one at least slipping, or one sticking alone), by
 * Newton–Euler with the points' constraints. GB_ENUMERIC on Painlevé's paradox: the normal forces of the
 * slipping points have no consistent value (their compliance matrix K, ∂(normal acceleration)/∂N, is not a
 * P-matrix: no solution, or more than one). */
int gb_dyn_friction_solve(const gb_dynamics *d, double t, double geff, const double zb[3], const double omega[3],
                          const gb_dyn_friction_point *points, int count, gb_dyn_friction_forces *out);
/* The slip of a body point r [m] (body axes): its velocity relative to the plane with the centroid at the
 * state's velocity, less its normal part, in body axes. */
void gb_dyn_slip_of(const double y[GB_STATE_SIZE], const double zb[3], const double r[3], double slip[3]);
/* A slip below this speed has stopped: 1e-6 of the speeds the body's motion is made of (√(g_max L), |V|,
 * |ω| L), or, where the slip turns (its acceleration across it, a_⊥), the speed at which it would turn by a
 * quarter radian in one step, |a_⊥| h / 0.25. Close to a stop the slip's direction turns fast and the
 * equations lose their smoothness inside a step (RK4 would lose its order, and the friction's work its
 * balance with the energy); the stop is taken there, the slip left removed by the impulse friction would
 * have spent (booked in L) where the cone holds, else the slip restarts. A slip must first grow past twice
 * this before its stop is watched. `slip` and `slip_acc`: the point's slip and tangential acceleration. */
double gb_dyn_slip_stop_speed(const gb_dynamics *d, const double y[GB_STATE_SIZE], const double slip[3],
                              const double slip_acc[3]);
/* One sticking point (the one-point mode): how far its force is inside the cone, μ N − |F_t|. */
double gb_dyn_one_point_margin(const gb_dynamics *d, double geff, const double zb[3], const double omega[3],
                               const double omega_dot[3], const gb_dyn_contact *c);
/* Two sticking points (the two-point mode's forces, their tangential parts open along PQ): the largest over
 * that open part of min(μ N_P − |T_P|, μ N_Q − |T_Q|), and which cannot stick whatever the split (bit 0: P,
 * bit 1: Q; 3: each could, not both at once). */
double gb_dyn_crease_margin(double mu, const double normal[2], const double tangent[2][3], const double u[3], int *alone);
/* The points' constraints at velocity level, which the accelerations keep only to the integration's
 * accuracy: on two points both stay on the plane (ω projected, the least change in I's metric; both
 * sticking: a turn about PQ keeping the angular momentum about it), a sticking point at rest (the centroid's
 * velocity the rolling one). The kinetic energy this changes (rounding's size) is booked in L. */
int gb_dyn_hold_velocities(gb_dynamics *d, double y[GB_STATE_SIZE], int count, const int sticks[2]);
/* The sliding mode. */
int gb_dyn_sliding_field(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double omega[3], const double zb[3],
                         double geff, double omega_dot[3], double *zeta, gb_dyn_rates *rates);
int gb_dyn_sliding_accept(gb_dynamics *d, double t, double y[GB_STATE_SIZE]);
int gb_dyn_sliding_observe(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_observables *o);
void gb_dyn_sliding_translate(const gb_dynamics *d, double t, double y[GB_STATE_SIZE]);
/* The sliding mode's points at state y and their forces (points[k].slides as d->slides). */
int gb_dyn_sliding_eval(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dyn_friction_point *points,
                        gb_dyn_friction_forces *f);
/* Enter the sliding mode at t on `count` points (contact, contact2) with these slips; a point slipping from
 * rest starts along start[k] (inertial axes). */
void gb_dyn_start_sliding(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], int count, const int slides[2],
                          const double start[2][3]);

/* ---- the events (gb_dynamics_events.c) ------------------------------------------------------------- */

int gb_dyn_one_point_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found);
int gb_dyn_one_point_gap(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other,
                         double *gap, gb_contact_point *other_here);
int gb_dyn_two_point_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found);
int gb_dyn_two_point_gap(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other,
                         double *gap, gb_contact_point *other_here);
int gb_dyn_rest_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found);
int gb_dyn_rest_gap(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other,
                    double *gap, gb_contact_point *other_here);
int gb_dyn_flight_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found);
int gb_dyn_flight_gap(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other,
                      double *gap, gb_contact_point *other_here);
int gb_dyn_sliding_pending(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_contact_point *other, int *found);
int gb_dyn_sliding_gap(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *other,
                       double *gap, gb_contact_point *other_here);

/* ---- the jumps (gb_dynamics_jumps.c) --------------------------------------------------------------- */

/* A law's impact map: what a change of contact does to the state, where the hybrid modes meet one (the law row's
 * `impact_map`; the held, rough and Coulomb maps are in gb_dynamics_jumps.c). Events every law shares (a lift-off,
 * a lift from two points, a slip starting) stay the modes'; nothing else tells the laws apart at a jump. */
typedef struct gb_dyn_impact_map {
    /* one point: the contact changes onto `branch` (ω kept, Newton's impact, or Coulomb's) */
    int (*change)(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch);
    /* two points: a third point `branch` reaches the plane */
    int (*third)(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch);
    /* flight: the lowest point `branch` lands */
    int (*landing)(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch);
    /* the variational estimator's saltation at a one-point change and at a two-point event (gb_dyn_no_jump: not
     * followed) */
    int (*change_jump)(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                       double out[GB_STATE_SIZE]);
    int (*two_point_jump)(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                          double out[GB_STATE_SIZE]);
} gb_dyn_impact_map;
extern const gb_dyn_impact_map gb_dyn_held_impacts, gb_dyn_rough_impacts, gb_dyn_coulomb_impacts;

int gb_dyn_one_point_event(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch);
int gb_dyn_one_point_jump(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                          double out[GB_STATE_SIZE]);
int gb_dyn_two_point_event(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch);
int gb_dyn_two_point_jump(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                          double out[GB_STATE_SIZE]);
int gb_dyn_rest_event(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch);
int gb_dyn_flight_event(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch);
/* ---- the jumps of a plane of finite friction (gb_dynamics_slips.c) --------------------------------- */
int gb_dyn_sliding_event(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *branch);
/* A sticking mode's point reaches the cone's edge: the body slides from there (no impulse). */
int gb_dyn_slip_start(gb_dynamics *d, double t, double y[GB_STATE_SIZE]);
/* A change of contact or a landing on a plane of finite friction: the impact over `count` points [m] (the
 * state's velocity before), the point `arriving` the new one, and the mode it leaves (one point, two points,
 * rest: the points held; sliding; flight), booked as `kind`. */
int gb_dyn_friction_impact(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_contact_point *points, int count,
                           int arriving, gb_dynamics_impact_kind kind, int located);
/* The variational estimator cannot follow flight: the jump from or into it (GB_EINVAL). */
int gb_dyn_no_jump(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *branch,
                   double out[GB_STATE_SIZE]);
/* ---- the impulses every jump shares (gb_dynamics_impulses.c) ------------------------------------- */

/* Newton's restitution at a point approaching at `approach` (> 0) at time t: def.restitution, or 0 where
 * the rebound would fall back within the settle time (the end to bouncing). */
double gb_dyn_restitution_at(const gb_dynamics *d, double t, double approach);
/* The plane only pushes: GB_OK, or GB_ENUMERIC naming the point an impact would need it to pull at beyond
 * rounding (and, `settled`, beyond the weight's impulse over the return the settle rule removes). */
int gb_dyn_plane_pushes(const gb_dynamics *d, double t, const gb_impact_result *r, const double (*points)[3], int count,
                        int arriving, int settled, const double v_before[3], const double omega_before[3]);
/* The first of the `count` points whose normal impulse is a pull beyond what is allowed there (*allowed), or −1. */
int gb_dyn_pulling_point(const gb_dynamics *d, const gb_impact_result *r, const double (*points)[3], int count,
                         int arriving, int settled, const double v_before[3], const double omega_before[3], double *allowed);
/* How soon the point rp [m] falls back after an impact that leaves the body rolling on q with ω (y) and the
 * centroid at v (body axes): 2 v_n / |a_n| (INFINITY when it does not). */
double gb_dyn_return_time(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const gb_contact_point *q,
                          const double v[3], const double rp[3]);

/* ---- the ledger (gb_dynamics_ledger.c) ------------------------------------------------------------ */

/* A change of contact with no impulse: the record of nothing changed, the body turning with the ω of y about
 * `about` [m]; v the centroid's velocity. */
void gb_dyn_no_impulse(const gb_dynamics *d, const double y[GB_STATE_SIZE], const double about[3], double v[3],
                       gb_impact_result *r);
/* Fill an impact record; ω in y takes its value after. */
void gb_dyn_record(gb_dynamics_impact *e, double y[GB_STATE_SIZE], const double old_point[3], const double new_point[3],
                   const double v_before[3], const gb_impact_result *r, int k, int k_old);
/* Book a change of contact: an impact's loss (a lift has none) and the sink. */
int gb_dyn_book(gb_dynamics *d, const gb_dynamics_impact *e);

#endif
