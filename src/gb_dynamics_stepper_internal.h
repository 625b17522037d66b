/* gb_dynamics_stepper_internal — the time-stepping strategy's state, shared by its files (internal): the step
 * (gb_dynamics_stepping.c), its rotation (gb_dynamics_stepping_rotation.c), a smooth body's tracked minima
 * (gb_dynamics_stepping_minima.c) and the hand-over between the strategies (gb_dynamics_handover.c). docs/stepping.md. */
#ifndef GB_DYNAMICS_STEPPER_INTERNAL_H
#define GB_DYNAMICS_STEPPER_INTERNAL_H

#include "gb_contact_problem.h"
#include "gb_dynamics_internal.h"

/* The candidates' threshold above the plane [body lengths]: far above the rounding of a height (1e-16 of the body),
 * far below any length of the problem; a gap the step closes to this is a contact. */
#define GB_DYNAMICS_STEPPING_ACTIVATION 1e-12
/* A step with more candidates than gb_integrate_def.stepping_first poses the most urgent that many first, and adds
 * those the solution would let through the plane, GB_DYNAMICS_STEPPING_ADD at a time, the most violated first, until
 * none would: a grid polyhedron's polar cap lands with hundreds of nodes in reach, of which a few carry it. Zero
 * impulse at the points left out, which do not go through, completes the posed problem's solution to one of the whole
 * problem (Moreau's law holds at each of them). */
#define GB_DYNAMICS_STEPPING_ADD 16
/* An excluded candidate whose normal velocity after the step, with Newton's e u_n⁻, is below −this times the step's
 * speed scale (|v_z| + |ω| r_max + |g| h) goes through the plane: far above the solver's 1e-12, far below any
 * velocity of the problem. */
#define GB_DYNAMICS_STEPPING_THROUGH 1e-9
/* A smooth body's candidates: the local minima of its height tracked at once (the global one and those that came down
 * to the plane near it: two on a crease, a third where three tie), and how far above the plane [body lengths] a minimum
 * other than the global one is still followed (one farther returns, when it matters, as the certificate's lower
 * minimum). */
#define GB_DYNAMICS_STEPPING_SLOTS 8
#define GB_DYNAMICS_STEPPING_KEEP 0.05

/* The contacts one step solves, and what the last step left. */
struct gb_dyn_stepper {
    double theta, h;
    size_t first;                  /* the candidates a step poses first (0: all) */
    int siconos;                   /* linearised as Siconos's MoreauJeanOSI (gb_integrate_def.stepping_siconos) */
    size_t nodes;                  /* the grid's nodes, the body's points [m] (body axes): the candidates */
    double (*points)[3];
    int smooth;                    /* continuous contact: the nodes are slots of tracked minima (below) */
    gb_contact_point slot[GB_DYNAMICS_STEPPING_SLOTS]; /* a smooth body's minima (unit body), by slot */
    unsigned char active[GB_DYNAMICS_STEPPING_SLOTS];
    size_t next_slot;              /* where the search for a free slot starts: a slot just freed is taken last */
    double radius;                 /* the farthest point's distance from the centroid [m] */
    double *gaps;                  /* every point's gap above the plane at the state `scanned` (scanned_valid) */
    size_t *candidates;            /* this step's candidates (nodes), [nodes] */
    double *keys;                  /* their urgency: the gap half a step ahead (−∞: a point that carried the body) */
    unsigned char *posed;          /* a candidate is in the problem (by candidate) */
    double *scratch;               /* the keys, sorted [nodes] */
    double scanned[GB_STATE_SIZE];
    int scanned_valid;
    gb_contact_problem *problem;
    double tolerance;              /* the problem's (solver_tolerance) */
    size_t contact_steps;          /* steps with a point that carried the body (the statistics' minimum over them) */
    struct gb_dyn_stepped_step {   /* the step being taken, for the enumeration (enumerate) */
        double m, A[3][3], R[9], R0[9], vf[3], wf[3], v[3], w[3], e, mu; /* R: the relations'; R0: the start's */
    } step;
    size_t capacity;               /* of the buffers below, in contacts */
    double *W, *q, *mu, *r, *u;    /* the problem (W: (3 capacity)², column-major) */
    size_t *node;                  /* the candidates' nodes */
    double (*B)[3][3];             /* their relations' rotational parts */
    double (*C)[3][3];             /* M_ω⁻¹ B_iᵀ */
    /* the last step */
    int touching, sliding;         /* points with a normal impulse; of them, points slipping after the step */
    double normal_impulse, tangential[3], slip_max; /* Σ P_n, Σ P_t (inertial), the largest slip after [m/s] */
    size_t lowest;                 /* the lowest node after the step */
    double clearance;              /* its height above the plane [m] */
    size_t *touched, *touching_now; /* the nodes touching after the previous step (to count new touches), and this one's */
    int touched_count;
    int *starts;                    /* this step's points (problem indices) that begin to carry the body */
    size_t *last_node;              /* the previous problem's points and impulses: the solver starts from them (a body
                                     * at rest needs a sweep or two, not hundreds) */
    double *last_r;
    int last_count;
    gb_dynamics_stepping_stats stats;
};

/* The stepped mode, every mode index of it (a dynamics stepped in time has this table). */
extern const gb_dyn_mode gb_dyn_stepped_modes[GB_DYN_MODES];
/* Every point's gap at state y (vertical zb), the lowest and its clearance, kept for the same state; a smooth body's
 * minima brought to y first. */
int gb_dyn_stepping_scan(gb_dynamics *d, const double y[GB_STATE_SIZE], const double zb[3]);
/* The step, θ and solver of a stepping that begins or resumes, from no carrying point (fresh) or those its start marked. */
int gb_dyn_stepping_set(gb_dyn_stepper *s, double h, double theta, const gb_contact_problem_def *solver, int fresh);
/* A smooth body's minimum p takes a slot (a free one, else the highest but `keep`'s): its slot. */
int gb_dyn_stepping_take_slot(gb_dyn_stepper *s, const gb_contact_point *p, int keep);
/* A smooth body's tracked minima brought to state y (vertical zb), the lowest certified global: its slot in *global. */
int gb_dyn_stepping_track_minima(gb_dynamics *d, gb_dyn_stepper *s, const double y[GB_STATE_SIZE], const double zb[3],
                                 int *global);

/* The step's rotation (gb_dynamics_stepping_rotation.c): the free angular velocity ω_f of a step of h at θ with damping c,
 * its rotational mass A and A⁻¹ (gomboc's linearisation, or Siconos's where `siconos`); the attitude after turning at ω
 * for h, by the exact exponential or by Siconos's (its small-angle series, docs/siconos.md). */
int gb_dyn_stepping_free_rotation(double I[3][3], double c, const double w[3], double h, double th, int siconos,
                                  double A[3][3], double Ainv[3][3], double wf[3]);
void gb_dyn_stepping_attitude(const double q[4], const double w[3], double h, double out[4]);
void gb_dyn_stepping_siconos_attitude(const double q[4], const double w[3], double h, double out[4]);

#endif
