/* gb_dynamics — the rocking body on the vertically excited plane (paper §3 and §5, eqs 20–52).
 *
 * State y (GB_STATE_SIZE doubles): the attitude as a quaternion q = (w, x, y, z) taking body to
 * inertial axes (R = R(q/|q|), so RᵀR = I to round-off whatever |q| drifts to; q̇ = ½ q ⊗ (0, ω) is eq 23
 * in quaternion form), the body-frame angular velocity ω (eq 44), the work W = ∫(P_d + m ġ_eff ζ) dt
 * that the energy balance needs, integrated along the run as an extra state, and the centroid's
 * translation: its height ζ above the plane and its velocity relative to the plane (inertial axes). Each
 * mode says how the translation follows: on the plane it is fixed by the attitude, ω and the contact
 * (ζ = −z_b·r_c, v = R (ω × (G − P))), in flight it is the closed form under g_eff; the mode writes it at
 * every accepted step and at the start. On a rough plane its rate in the vector field is 0 (the adaptive
 * steppers' error control sees only what is integrated); on a plane of finite friction (def.friction) the
 * velocity is integrated, since a sliding body's horizontal velocity is its own, and so are the centroid's
 * horizontal position and the work of friction (both 0 on a rough plane).
 *
 * Two equations of motion, each a named variant (see docs/rolling.md for the derivation):
 *  GB_VARIANT_PAPER    eq 44 as written: I_P ω̇ + İ_P ω + ω × I_P ω = τ, İ_P from eq 45;
 *  GB_VARIANT_ROLLING  rolling without slip from Newton–Euler about the centroid:
 *                      I_P ω̇ + ω × I_P ω − m r_c × (ṙ_c × ω) = τ.
 * They differ by the term −m ṙ_c × (r_c × ω), whose power is not zero: which one satisfies the
 * energy balance (eqs 46–51) is for the checks to show. For a grid contact ṙ_c = 0 between switches,
 * as the paper's scheme implies, and the variants coincide.
 *
 * Three contact models (gb_contact): the paper's grid by brute force, the same node by the exact
 * trajectory tracker (gb_contact_tracker), and continuous contact (Newton from the previous
 * contact at every evaluation; at every accepted step gb_certify proves it the global minimum or finds
 * the lower one, see gb_dynamics_accept). */
#ifndef GB_DYNAMICS_H
#define GB_DYNAMICS_H

#include "gb_export.h"

#include "gb_atlas.h"
#include "gb_certify.h"
#include "gb_contact.h"
#include "gb_forcing.h"
#include "gb_surface.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

enum {
    GB_STATE_Q = 0,
    GB_STATE_OMEGA = 4,
    GB_STATE_WORK = 7,
    GB_STATE_ZETA = 8,      /* the centroid's height above the plane [m] */
    GB_STATE_VELOCITY = 9,  /* the centroid's velocity relative to the plane, inertial axes [m/s] (3) */
    GB_STATE_POSITION = 12, /* finite friction: the centroid's horizontal position on the plane [m] (2) */
    GB_STATE_FRICTION = 14, /* finite friction: the work of the friction forces since the start [J] (<= 0) */
    GB_STATE_SIZE = 15,
    GB_STATE_FINGERPRINT = 8, /* the leading components a run's state fingerprint hashes: q, ω, W */
    GB_STATE_TANGENT = 6      /* the variational estimator's tangent: three rotations and ω (the translation
                               * is fixed by them on the plane, and flight is not followed) */
};

typedef enum gb_dynamics_variant { GB_VARIANT_PAPER = 0, GB_VARIANT_ROLLING = 1 } gb_dynamics_variant;

GB_API const char *gb_dynamics_variant_name(gb_dynamics_variant variant);
GB_API int gb_dynamics_variant_parse(const char *name, gb_dynamics_variant *variant);

/* A lowest-node search of one's own for contact = grid (make bench's plain loop): the index of the
 * lowest node of the grid for the unit vertical d (gb_contact_unit_vertical of z_b), ties to the lowest
 * index, exactly as gb_contact_grid_brute returns it (the grid's nodes: gb_contact_grid_node). */
typedef size_t (*gb_dynamics_lowest_node)(void *context, const double d[3]);

/* How continuous contact proves the contact global at every accepted step: by gb_certify at each
 * vertical, or by a lookup in an atlas of verticals (gb_atlas), with gb_certify where the atlas cannot
 * decide. Both make the same switches (the switch target is polished the same way, see
 * gb_dynamics_accept); the atlas is faster once its cells are built. MULTISTART proves nothing: the
 * contact is taken global when no lower minimum is found among the local minima of the 180 × 360 branch
 * grid polished by Newton (gb_contact_branches_find), for a body without interval enclosures (one given by
 * an expression), which the others cannot certify; a minimum whose basin holds no node can be missed. */
typedef enum gb_dynamics_certificate {
    GB_CERTIFICATE_PER_VERTICAL = 0,
    GB_CERTIFICATE_ATLAS = 1,
    GB_CERTIFICATE_MULTISTART = 2
} gb_dynamics_certificate;

GB_API const char *gb_dynamics_certificate_name(gb_dynamics_certificate certificate);
GB_API int gb_dynamics_certificate_parse(const char *name, gb_dynamics_certificate *certificate);

/* What happens when the contact point changes. HELD: the paper's rule, one contact at all times and ω
 * kept (the kinetic energy about the new point is what it is). UNILATERAL: the plane can only push, and
 * a change of contact is an impact (gb_impact: Moreau's law, rough, plastic). Built for continuous
 * contact with the rolling equation; every change is located (gb_case requires locate_switches = yes).
 *  - Rolling on one point P, the body meets the plane at Q: if P lifts, rolling goes on about Q with
 *    the ω after the impact; if both hold, the body rolls on two points.
 *  - Rolling on two points P and Q (the two-point mode, docs/impact.md): the plane is tangent to the
 *    body at both, so ω lies along PQ and the vertical moves along the crease of the support function
 *    where two minima of height tie. One degree of freedom, σ = ω·u (u along PQ), whose equation is the
 *    power balance d/dt(½ I_u σ²) = −m g_eff ζ̇ − c|ω|² (the rolling contacts do no work). Both normal
 *    forces come from Newton–Euler. It ends at a located event: a normal force reaching 0 (the body rolls
 *    on the other point, ω unchanged) or a third point reaching the plane (an impact over all three).
 *  - Lift-off, flight and landing (docs/impact.md): where the last contact's normal force reaches 0 (on three
 *    points at rest: g_eff) the body flies, its centroid under g_eff in closed form, the body turning
 *    torque-free but for −c ω; it lands where its lowest point (certified as a contact is) reaches the plane:
 *    a one-point impact of a rough plane (gb_impact_rough_point) with Newton's def.restitution. With e > 0 a
 *    change of contact from one point is a rebound too (kind bounce).
 *  - The end of a crease: where Q's minimum merges with P's or vanishes in a fold, the two-point mode ends
 *    at that step's end and the body rolls on P alone (no jump: the state is continuous there; kind
 *    crease-end). A lower minimum within 1e-7 of the contact is the same contact, not a switch.
 * Stops the run with GB_ENUMERIC, saying which: an impact a rough plane cannot absorb (stopping the slip
 * needs a pulling impulse; a finite friction coefficient is not built), three points whose triangle holds
 * neither the weight nor an edge, a lift-off the body would have to slide through (its lowest point driven
 * over 1e-6 body lengths into the plane), and a change of contact the step's event location missed. A chatter of impacts between P and Q (the lifted
 * point falling back ever sooner, as a bouncing ball's) is ended by def.settle_time, and so is a bounce
 * sequence (a rebound that would return within it is plastic). */
typedef enum gb_contact_law {
    GB_CONTACT_LAW_HELD = 0,
    GB_CONTACT_LAW_UNILATERAL = 1,
    GB_CONTACT_LAW_COMPLIANT = 2 /* the plane pushes where the body dips into it (gb_dynamics_compliant.c) */
} gb_contact_law;

GB_API const char *gb_dynamics_contact_law_name(gb_contact_law law);
GB_API int gb_dynamics_contact_law_parse(const char *name, gb_contact_law *law);
/* A contact law as the questions every module asks of it, never its name: the held law (the paper's), the
 * unilateral law on a rough plane, and the unilateral law with Coulomb's friction (a plane of finite μ) are three
 * rows of one table (gb_dynamics_laws.c, the one file that tells one law from another). */
/* A coefficient of a law of its own, set by a [model] key of the scene (gb_case reads the laws' keys from here): its
 * key, its slot in gb_dynamics_def.law_coefficients, its range (min excluded when open_min), its default and its
 * meaning in words with units. */
typedef struct gb_dynamics_law_key {
    const char *name;
    int slot;
    double min, max;
    int open_min;
    double fallback;
    const char *meaning;
} gb_dynamics_law_key;

struct gb_dyn_mode; /* a law's own mode (gb_dynamics_internal.h) */

typedef struct gb_dynamics_law {
    const char *name;
    gb_contact_law id;           /* the scene's contact_law that names it */
    int impacts;                 /* a change of contact is an impact (ω jumps): the body rolls on two points, rests on
                                  * three, coincident minima are one contact, and the energy ledger books what impacts
                                  * take (L); the held law keeps ω and one contact at all times */
    int translates;              /* the body may leave the plane: the centroid's height and velocity are state, and a
                                  * separation of two states (the pair estimator's) measures them */
    int pivots;                  /* a grid body pivots about its node between events (ṙ_c = 0) */
    int several_events_per_step; /* every change of contact is located, and several may follow inside one step */
    int slips;                   /* Coulomb's friction: sliding modes, the centroid's horizontal motion, friction's work
                                  * in the ledger; a rough plane never slips */
    int free_centroid;           /* the centroid's translation is integrated (its velocity and horizontal position are
                                  * state, and the work of the contact's dissipative forces is booked in the ledger):
                                  * a law that slips, or one whose contact forces follow from the state */
    int needs_friction;          /* the law needs a finite μ (its friction is regularised, never rough) */
    int pushes_every_vertex;     /* a polyhedron is pushed at each vertex below the plane, found by no search: its vector
                                  * field has no jumps where the lowest vertex changes, and an adaptive stepper takes it */
    int time_steps;              /* the law poses a one-step contact problem that the time-stepping strategy solves at every
                                  * step (Newton's impact law on the normal velocity, Coulomb's cone: Siconos's fc3d) */
    const struct gb_dyn_impact_map *impact_map; /* what a change of contact does to the state (NULL: a law of one
                                                 * smooth mode has none) */
    const struct gb_dyn_mode *mode; /* a law that is one smooth mode of its own (the run stays in it: no events, no
                                     * jumps); NULL: the hybrid system of modes, events and impacts */
    const gb_dynamics_law_key *keys; /* its own coefficients, as [model] keys (NULL: none) */
    size_t key_count;
} gb_dynamics_law;

/* The coefficients' slots in gb_dynamics_def.law_coefficients (a law names its own by its keys). */
#define GB_DYNAMICS_LAW_COEFFICIENTS 4

/* The keys of every law, in one list (gb_case's scene table reads them): the count, and key i with its law. */
GB_API size_t gb_dynamics_law_key_count(void);
GB_API const gb_dynamics_law_key *gb_dynamics_law_key_at(size_t i, const gb_dynamics_law **law);

/* The law of `contact_law` on a plane of `friction` (INFINITY: rough), or NULL for none (the held law on a
 * plane of finite friction: a held contact never slips). */
GB_API const gb_dynamics_law *gb_dynamics_law_of(gb_contact_law contact_law, double friction);

/* The unilateral law: a landing is located where the lowest point is this far below the plane [body
 * lengths] (far above the rounding of its height, far below any length of the problem). */
#define GB_DYNAMICS_LANDING_TOL 1e-12

/* What happened at a change of contact of the unilateral law. */
typedef enum gb_dynamics_impact_kind {
    /* rolling on P, the body meets the plane at Q; P lifts */
    GB_DYNAMICS_IMPACT_SWITCH = 0,
    /* rolling on P, the body meets the plane at Q; both hold (the two-point mode) */
    GB_DYNAMICS_IMPACT_TWO_POINT = 1,
    /* two-point mode: a normal force reaches 0, that point lifts (no impulse) */
    GB_DYNAMICS_IMPACT_LIFT = 2,
    /* two-point mode: a third point reaches the plane (an impact over all three) */
    GB_DYNAMICS_IMPACT_THIRD = 3,
    /* the last contact's normal force (or g_eff at rest) reaches 0: the body flies (no impulse; old point =
     * the one left, new point = the lowest point) */
    GB_DYNAMICS_IMPACT_LIFT_OFF = 4,
    /* in flight, the lowest point reaches the plane (contacts after: 1 when it holds, 0 when the body
     * bounces or is pulled off at once) */
    GB_DYNAMICS_IMPACT_LANDING = 5,
    /* restitution e > 0 at a change of contact: Q rebounds; P holds (contacts after 1, the body rolls on P)
     * or lifts too (0: the body hops) */
    GB_DYNAMICS_IMPACT_BOUNCE = 6,
    /* two-point mode: Q's minimum merges with P's or vanishes in a fold (the end of the crease); the body
     * rolls on P alone (no impulse; found at a step's end) */
    GB_DYNAMICS_IMPACT_CREASE_END = 7
} gb_dynamics_impact_kind;

GB_API const char *gb_dynamics_impact_kind_name(gb_dynamics_impact_kind kind);

/* One change of contact of the unilateral law, in body axes with the centroid at the origin. */
typedef struct gb_dynamics_impact {
    double t;
    gb_dynamics_impact_kind kind;
    int located;                          /* 1: at a located event; 0: a lower branch found at an accepted step */
    double old_point[3], new_point[3];    /* P and Q [m]: the point that lifts or holds before, the one that
                                           * touches (a lift: the point that lifts, the one that stays; a
                                           * third point: of the two points before, the one that stays when
                                           * two hold after, else P) */
    double omega_before[3], omega_after[3];
    double v_before[3], v_after[3];       /* the centroid's velocity relative to the plane */
    double normal_impulse, tangential_impulse, friction_needed; /* at the new point; friction = |P_t| / P_n */
    double old_normal_impulse;            /* at the old point: 0 but for the settle rule, where it is the pull
                                           * that stands for the weight's impulse over the return it removes */
    double kinetic_before, kinetic_after; /* [J] */
    int contacts_after;                   /* points on the plane after: 1, 2, or 3 (at rest) */
    int settled;                          /* two points held by the settle rule (def.settle_time): the old
                                           * point would have lifted and fallen back within the settle time
                                           * (kind two-point; or third-point, with the point of the two
                                           * before that would fall back first) */
    double potential_jump;                /* [J] a landing that ends in contact: the weight's energy m g_eff ×
                                           * the lowest point's depth below the plane (the event's tolerance),
                                           * by which the contact puts the body back on the plane; booked with
                                           * the kinetic energy lost (L) so that the ledger closes */
    int rebound;                          /* restitution applied: the new point leaves the plane at e times its
                                           * approach speed (kinds bounce and landing) */
    double return_time;                   /* kind switch or settled: 2 v_n / |a_n| of the point that lifts
                                           * after Moreau's impact (INFINITY when it does not fall back) */
    /* A plane of finite friction: the new point's slip (tangential velocity, body axes) before and after and
     * the tangential impulse there (body axes); whether it slides after. 0 on a rough plane. */
    double slip_before[3], slip_after[3], tangential[3];
    int slides_after;
} gb_dynamics_impact;

/* Called with every impact (the run's impacts file); a non-zero return stops the run with that status. */
typedef int (*gb_dynamics_impact_sink)(void *context, const gb_dynamics_impact *impact);

/* A context: what the runs of one body share, apart from their physics (gb_dynamics_def): the body's
 * mass properties, its grid of nodes and the fast grid's tracker, the atlas of verticals (certificate =
 * atlas), the files these caches live in, and a lowest-node search of one's own. A caller that runs many
 * scenes on one thread (a scan's thread, a Lyapunov pair) keeps one and creates each run in it
 * (gb_dynamics_create_in): a run takes from it what was built for its body (the same morphology, β and
 * mass; the same grid; the same atlas definition) and stores there what it builds. The first body's
 * grid, tracker and atlas stay (a run of another body builds its own), so a run never loses what another
 * run uses; the mass properties follow the last body. The files are read when a run first needs what
 * they hold (a file missing, stale, damaged or sealed under another key is built anew) and written by
 * gb_dynamics_context_save alone: the dynamics never touch a file. The results are those without a
 * context, bit for bit (the tracker returns brute force's node from any warm start; an atlas's answer is
 * a proof, whoever made it). One thread at a time; free it after the last run that used it. */
typedef struct gb_dynamics_context gb_dynamics_context;
GB_API int gb_dynamics_context_create(gb_dynamics_context **out);
GB_API void gb_dynamics_context_free(gb_dynamics_context *context);
/* The caches' files (NULL: none): the atlas of verticals and the fast grid's hull. */
GB_API int gb_dynamics_context_files(gb_dynamics_context *context, const char *atlas_file, const char *hull_file);
/* A directory the fast grid's hull is kept in by the grid's content when no hull file is named: read from
 * DIR/hull-KEY.gbh (KEY: FNV-1a of the grid's nodes) when it holds these very nodes' hull, else built by Qhull
 * and written there by gb_dynamics_context_save, whose failure to write it is not an error (a cache). NULL: none. */
GB_API int gb_dynamics_context_cache(gb_dynamics_context *context, const char *dir);
/* contact = grid: this search instead of brute force (make bench's plain loop). */
GB_API void gb_dynamics_context_lowest(gb_dynamics_context *context, gb_dynamics_lowest_node lowest, void *user);
/* Write the caches back to their files: the atlas, merged with the cells the file gained since it was read
 * (gb_atlas_merge_save: runs that share one file add up their cells), unless the file holds it already (it
 * was read or written and no cell was proved since); the hull when Qhull built it. gb_ status. */
GB_API int gb_dynamics_context_save(gb_dynamics_context *context);

typedef struct gb_dynamics_def {
    gb_dynamics_variant variant;
    gb_contact_model contact;
    double mass;                   /* m [kg] (Table 1: 1) */
    double length;                 /* size: body points are length · x(φ, θ) [m] (1: x in metres) */
    double damping;                /* c in τ_d = −c ω [N m s] (eq 42; Table 1: 0.02) */
    gb_forcing forcing;            /* eq 25 */
    gb_contact_grid_def grid;      /* the grid of the grid models (Table 1: 90 × 180) */
    gb_certify_def certify;        /* continuous contact: the certificate of the global minimum */
    gb_dynamics_certificate certificate; /* continuous contact: per vertical (default) or atlas */
    gb_contact_law contact_law;    /* held (the paper's, default) or unilateral */
    double settle_time;            /* unilateral: the end to chatter [s] (0, the default: one step of the
                                    * integrator the run uses, gb_dynamics_use_step). At an impact after which P
                                    * lifts, if P would fall back onto the plane within this time (its normal
                                    * separation speed v_n and acceleration a_n < 0 after: 2 v_n / |a_n|), both
                                    * points are taken as held instead: the impact that stops P and Q at once, unless
                                    * it would need the plane to pull by more than m g_max settle_time (the weight's
                                    * impulse it stands for): then Moreau's impact stands. One step, so that the
                                    * return the rule removes would fall inside one step. */
    double friction;               /* μ of the plane (INFINITY, the default: perfectly rough, no slip ever). A
                                    * finite μ > 0 (unilateral law only) is Coulomb's law at every contact, between
                                    * impacts (a contact sticks inside the cone |F_t| <= μ N and slides on its edge
                                    * against the slip) and inside them (gb_impact_coulomb); docs/friction.md */
    double restitution;            /* unilateral: Newton's e on the normal approach speed at a landing and at a
                                    * change of contact from one point, 0 <= e <= 1 (0, the default: plastic). A
                                    * third point meeting the two-point mode is plastic whatever e. The end to
                                    * bouncing (Zeno): a rebound e v_n that would return within settle_time under
                                    * g_eff, e v_n < g_eff settle_time / 2, is taken as plastic. */
    double height0;                /* unilateral: the initial gap [m] between the lowest point and the plane
                                    * (0, the default: in contact); > 0 starts in flight */
    double velocity0[3];           /* the centroid's initial velocity relative to the plane, inertial axes
                                    * [m/s] (default 0): with height0 > 0, or on the rough plane, the run starts
                                    * in flight; on a plane of finite friction with height0 = 0 it starts on the
                                    * plane at the horizontal part (the vertical follows the attitude), sliding
                                    * where that differs from rolling */
    gb_atlas_def atlas;            /* certificate = atlas: its cells (its height_tol is certify's) */
    double law_coefficients[GB_DYNAMICS_LAW_COEFFICIENTS]; /* a law's own coefficients by its keys' slots (NAN, the
                                                            * default: the key's fallback); a law with no keys
                                                            * ignores them */
} gb_dynamics_def;

/* Table 1 with the paper's model: variant paper, the paper's 90 × 180 grid by the exact fast search
 * (fast-grid: the brute-force node at every evaluation, bit for bit), m = 1, c = 0.02, g = 9.81, ω = 18,
 * ψ = π/3, and a₁ = 2, a₂ = 1 m/s² (the m/s² reading of Table 1; see gb_case). The scene's defaults
 * (gb_case_default) are these. */
GB_API gb_dynamics_def gb_dynamics_default_def(void);

typedef struct gb_dynamics gb_dynamics;

/* Build the body (mass properties by gb_massprops, scaled by mass and length) and only the grid its
 * contact model needs, in `context` (gb_dynamics_context; NULL: one of its own, no files). */
GB_API int gb_dynamics_create_in(const gb_surface *surface, const gb_dynamics_def *def, gb_dynamics_context *context,
                                 gb_dynamics **out);
GB_API int gb_dynamics_create(const gb_surface *surface, const gb_dynamics_def *def, gb_dynamics **out);
GB_API void gb_dynamics_free(gb_dynamics *dynamics);

GB_API const gb_dynamics_def *gb_dynamics_get_def(const gb_dynamics *dynamics);
/* Its contact law (gb_dynamics_law_of of its definition). */
GB_API const gb_dynamics_law *gb_dynamics_get_law(const gb_dynamics *dynamics);
/* L of eq 53 [m], for this length. */
GB_API double gb_dynamics_mean_radius(const gb_dynamics *dynamics);
/* The nodes of the grid built: the contact grid for grid models; 0 for continuous contact, which
 * builds none. */
GB_API size_t gb_dynamics_grid_size(const gb_dynamics *dynamics);

/* Grid models: the contact queries since creation and the nodes whose height they computed (the
 * searches' work: every node for brute force, far fewer for the tracker); 0 and 0 for continuous
 * contact and for a search of one's own. */
GB_API void gb_dynamics_contact_work(const gb_dynamics *dynamics, size_t *queries, size_t *nodes);

/* Continuous contact: the certificate's counters (checks, and how many ended global, lower-found or
 * undecided); GB_EINVAL for a grid model. */
GB_API int gb_dynamics_certify_stats(const gb_dynamics *dynamics, gb_certify_stats *out);
/* certificate = atlas: its counters, how many checks fell back to gb_certify, and whether it was read from
 * the context's atlas file (1) or built (0). */
GB_API int gb_dynamics_atlas_stats(const gb_dynamics *dynamics, gb_atlas_stats *out, size_t *fallbacks, int *loaded);

/* The initial state: attitude R0 (row-major 3 × 3, orthonormal), ω0; W = 0. Establishes the
 * initial contact (the global minimum) and E(0). */
GB_API int gb_dynamics_init_state(gb_dynamics *dynamics, double t0, const double R0[9], const double omega0[3],
                                  double y[GB_STATE_SIZE]);

/* gb_dynamics_create_in + gb_dynamics_init_state in one call for the body `body`; *out is NULL on failure. */
GB_API int gb_dynamics_start_in(const gb_surface *body, const gb_dynamics_def *def, gb_dynamics_context *context,
                                const double R0[9], const double omega0[3], gb_dynamics **out, double y[GB_STATE_SIZE]);
GB_API int gb_dynamics_start(const gb_surface *body, const gb_dynamics_def *def, const double R0[9],
                             const double omega0[3], gb_dynamics **out, double y[GB_STATE_SIZE]);


/* dy/dt (eqs 23, 44 or rolling, and Ẇ). GB_ENOCONV when the contact cannot be found; GB_ENUMERIC for a
 * state that is not finite. */
GB_API int gb_dynamics_rhs(gb_dynamics *dynamics, double t, const double y[GB_STATE_SIZE], double dydt[GB_STATE_SIZE]);



/* The unilateral law: a sink for every impact (NULL: none), and the impacts so far, the kinetic
 * energy they took (L) and the largest friction they needed. */
GB_API void gb_dynamics_set_impact_sink(gb_dynamics *dynamics, gb_dynamics_impact_sink sink, void *context);
GB_API void gb_dynamics_impact_stats(const gb_dynamics *dynamics, size_t *impacts, double *energy_lost,
                                     double *friction_max);
/* A plane of finite friction: the time spent sliding (one or two points slipping) up to t, the changes from
 * sticking to slipping and back, and the energy friction took so far (−∫ F_t·u_t dt, at the state y). */
typedef struct gb_dynamics_sliding_summary {
    double time;
    size_t slips, sticks;
    double friction_loss;
    int sliding; /* sliding at t */
} gb_dynamics_sliding_summary;
GB_API void gb_dynamics_sliding_stats(const gb_dynamics *dynamics, double t, const double y[GB_STATE_SIZE],
                                      gb_dynamics_sliding_summary *out);
/* The two-point mode up to time t: the time spent in it, how often it was entered from one point, the
 * impacts the settle rule ended (`settled`: entries and third points), how often it was left by a lift
 * and met a third point; when the body came to rest on three points (NAN: it did not). */
typedef struct gb_dynamics_two_point_summary {
    double time;
    size_t entries, settled, lifts, third_points;
    double rest_since;
} gb_dynamics_two_point_summary;

GB_API void gb_dynamics_two_point_stats(const gb_dynamics *dynamics, double t, gb_dynamics_two_point_summary *out);

/* Flight (the unilateral law) up to time t: the time spent in flight, lift-offs, landings, the highest
 * gap between the lowest point and the plane at the accepted steps of a flight [m] (0: none), and whether
 * the body is in flight now. */
typedef struct gb_dynamics_flight_summary {
    double time;
    size_t lift_offs, landings, bounces;
    size_t flying_on;        /* landings after which the body flew on without a rebound (a point struck, the body
                              * turned off the plane): a flight begun neither by a lift-off nor by a bounce */
    double hop_max;
    int flying;
} gb_dynamics_flight_summary;

GB_API void gb_dynamics_flight_stats(const gb_dynamics *dynamics, double t, gb_dynamics_flight_summary *out);

/* The time-stepping strategy's work (gb_integrate's strategy = time-stepping): its steps, the contact problems it
 * solved and the points they held (in all, and the most in one), the solver's sweeps and its largest residual, the
 * least energy one step's impulses took (D = −Σ P·(u⁺ + ũ)/2 over its points, ũ the free velocity without gravity's
 * kick; negative when they gave energy), the steps where they gave energy beyond rounding and the energy so given in
 * all [J], and the problems the Gauss–Seidel left to another of Siconos's methods (gb_contact_problem). A contact held while the body
 * turns about it gives energy: the point's velocity at the step's new attitude separates by h ω² r (the centripetal
 * part), on which the next impulse works, ½ P_n h ω² r a step: O(h²) a step, O(h) over a run (docs/stepping.md). */
typedef struct gb_dynamics_stepping_stats {
    size_t steps, problems, contact_points, contacts_max, sweeps;
    double residual_max, dissipation_min;
    size_t negative_dissipation;
    double energy_gained;
    size_t fallbacks;
    size_t candidates_max; /* the most candidates one step had (of more than 64, the problem poses the 64 most urgent
                            * first, docs/stepping.md) */
    size_t grown;          /* solutions that let a candidate left out through the plane, posed again with it */
    size_t enumerated;     /* problems of at most 4 points Siconos's methods left above the tolerance, answered within
                            * it by enumerating the law's contact sets (docs/stepping.md) */
    /* What the contact problem took from the step's free motion: D_c = T(v_f) − T(v⁺) = −Σ P·(u⁺ + u_f)/2 over its
     * points, u_f the free velocity with gravity's kick, T in the step's mass (m, I + hθc). Coulomb's law and Signorini's
     * make it ≥ ½ PᵀWP ≥ 0 at e = 0 on any number of points (P_n u_n⁺ = 0, P_t·u_t⁺ ≤ 0); Newton's e > 0 at two or
     * more points may give energy back. Its least value [J], and the steps below −(rounding) */
    double contact_dissipation_min;
    size_t contact_negative;
} gb_dynamics_stepping_stats;
/* NULL when time was not stepped. */
GB_API const gb_dynamics_stepping_stats *gb_dynamics_stepping_stats_of(const gb_dynamics *dynamics);


/* Grid-index changes plus branch switches so far. */
GB_API size_t gb_dynamics_switch_count(const gb_dynamics *dynamics);
/* The time of the latest switch: the located time for a located switch, else the accepted step's end
 * (NAN before the first). */
GB_API double gb_dynamics_last_switch_time(const gb_dynamics *dynamics);

typedef struct gb_dynamics_observables {
    double t;
    double R[9], zb[3], omega[3], omega_dot[3];
    double rc[3], rc_dot[3];
    double height;           /* h* = z_b·r_c (eq 36), < 0 */
    double zeta;             /* the centroid's height above the plane: −h* in contact (eq 37), + clearance in flight */
    double geff, geff_rate;  /* eqs 25–26 */
    double kinetic, potential, energy; /* eqs 46–48 */
    double power_damping, power_gravity; /* eqs 50–51 */
    double work;             /* W(t) = ∫(P_d + m ġ_eff ζ) dt */
    double residual;         /* E(t) − E(0) − W(t), + L(t) under the unilateral law (the ledger) */
    double normal_force;     /* N = m (g_eff + ζ̈), rolling kinematics (the sum of both in the two-point mode) */
    double friction_needed;  /* |horizontal contact force| / N (two-point mode: the larger of the two points',
                              * the force along PQ, which statics leaves open, split as the normal forces) */
    int contacts;            /* points on the plane: 0 in flight, 1, 2 in the two-point mode, 3 at rest */
    double clearance;        /* the lowest point's height above the plane [m] (0 in contact) */
    double velocity[3];      /* the centroid's velocity relative to the plane, inertial axes [m/s] */
    double rc_other[3];      /* two-point mode: the second contact Q [m] (else 0) */
    double normal_forces[2]; /* two-point mode: N_P, N_Q from Newton–Euler (else N, 0) */
    double balance;          /* two-point mode: Newton–Euler's moment about PQ left by the power balance's
                              * σ̇, relative (0 to rounding when the mode's equation is right; else 0) */
    double tie;              /* two-point mode: h_P − h_Q [m], 0 on the crease (the integration's drift off it) */
    double orthonormality;   /* max |RᵀR − I| */
    size_t index;            /* grid node of the contact (grid models), else 0 */
    size_t grid_switches, branch_switches;
    size_t branches_lost;    /* continuous: evaluations where the continued branch had no minimum left
                              * (a fold inside a step) and the certified global minimum was taken */
    /* A plane of finite friction: the points slipping (0 when every contact sticks), the largest slip speed
     * [m/s], and the work of friction so far [J] (<= 0). */
    int sliding;
    double slip_speed, friction_work;
} gb_dynamics_observables;

GB_API int gb_dynamics_observe(gb_dynamics *dynamics, double t, const double y[GB_STATE_SIZE],
                               gb_dynamics_observables *out);

/* R(q/|q|), row-major. */
GB_API void gb_dynamics_rotation(const double q[4], double R[9]);
/* The unit quaternion of an orthonormal R. */
GB_API void gb_dynamics_quaternion(const double R[9], double q[4]);

#ifdef __cplusplus
}
#endif

#endif
