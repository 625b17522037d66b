/* gb_dynamics_protocol_internal — what the library's other modules call of a dynamics (internal): the steppers
 * (gb_integrate) and the Lyapunov pair (gb_lyapunov_body) accept a step, ask for the event pending at its end, its
 * function and its jump, and place one trajectory beside another; a scan's threads bound the memory of a context's
 * atlas; gb_run reports the fast grid's hull. A caller of the library runs scenes through gb_integrate, gb_run or
 * gb_lyapunov_body and never needs these; the harness checks them through this header. */
#ifndef GB_DYNAMICS_PROTOCOL_INTERNAL_H
#define GB_DYNAMICS_PROTOCOL_INTERNAL_H

#include "gb_contact_problem.h"
#include "gb_dynamics.h"

/* The step h of the integrator the run uses: the end to chatter where def.settle_time is 0 (gb_integrate
 * calls it when a run begins). */
void gb_dynamics_use_step(gb_dynamics *dynamics, double h);

/* The time-stepping strategy (gb_dynamics_stepping.c): begin it at t0 with step h, the θ of its θ-method and its
 * contact problem's solver (the dynamics stays in its one stepped mode from then on); advance y by one step from t.
 * GB_EINVAL for a law that poses no one-step problem or a contact model with no points; GB_ENOCONV naming the step,
 * its contact points and the residual when the solver does not converge. */
int gb_dynamics_stepping_begin(gb_dynamics *dynamics, double t0, double h, double theta, const gb_contact_problem_def *solver);
/* Put a new dynamics in the stepped mode before its start (gb_dynamics_init_state): the start then only places the
 * body (no mode's checks, such as Painlevé's at a launch on the plane). gb_dynamics_stepping_begin does it if not done. */
int gb_dynamics_stepping_prepare(gb_dynamics *dynamics);
int gb_dynamics_stepping_step(gb_dynamics *dynamics, double t, double h, double y[GB_STATE_SIZE]);

/* A run handed from the event-driven strategy to time-stepping where the former cannot follow (gb_integrate, [integrator]
 * hand_over; docs/stepping.md): gb_dynamics_hand_over puts the dynamics in the stepped mode (the points it stood on
 * become the first step's carrying points) with step h, θ and the solver, keeping the stepping's counters of an earlier
 * hand-over; gb_dynamics_hand_back returns it to the event-driven modes in flight at (t, y) after a step in which no
 * point carried it and its lowest point is above the plane (*back = 1), else leaves it (*back = 0);
 * gb_dynamics_hand_back_now returns it to them as it is (a trajectory whose contact is then adopted from another's). */
int gb_dynamics_hand_over(gb_dynamics *dynamics, double h, double theta, const gb_contact_problem_def *solver);
int gb_dynamics_hand_back(gb_dynamics *dynamics, double t, double y[GB_STATE_SIZE], int *back);
void gb_dynamics_hand_back_now(gb_dynamics *dynamics);
/* gb_dynamics_init_state, and where its start meets a limit of the law (hand_over, a law that time-steps: Painlevé's
 * paradox in a slide launched on the plane) the dynamics handed over before its start, which then only places the body
 * (as a time-stepped run's); gb_dynamics_start_limit is then that limit's message (NULL: the start was the law's). */
int gb_dynamics_init_or_hand_over(gb_dynamics *dynamics, double t0, const double R0[9], const double omega0[3],
                                  double y[GB_STATE_SIZE], int hand_over);
const char *gb_dynamics_start_limit(const gb_dynamics *dynamics);
/* 1 while the dynamics is handed to time-stepping (or was begun stepped), else 0. */
int gb_dynamics_stepped(const gb_dynamics *dynamics);

/* A step that may be taken again: the dynamics' scalars (modes, contacts, counters, the ledger) copied into a buffer of
 * gb_dynamics_snapshot_size() bytes and put back; the impacts of the step held back from the sink meanwhile, and sent
 * (keep = 1) or dropped (keep = 0). */
size_t gb_dynamics_snapshot_size(void);
void gb_dynamics_snapshot(const gb_dynamics *dynamics, void *out);
void gb_dynamics_restore(gb_dynamics *dynamics, const void *snapshot);
void gb_dynamics_hold_impacts(gb_dynamics *dynamics, int hold);
int gb_dynamics_release_impacts(gb_dynamics *dynamics, int keep);

/* GB_ENUMERIC, with a message that names t and says the integration diverged, when a component of y is
 * not finite (the steppers check each step's result, gb_dynamics_rhs its argument); GB_OK otherwise. */
int gb_dynamics_state_finite(double t, const double y[GB_STATE_SIZE]);

/* After an accepted step to (t, y): renormalise q (returns the |q| − 1 it removed), update the
 * contact and count switches. Continuous contact: the branch is continued by Newton, then gb_certify
 * proves it the global minimum or returns a lower minimum, which becomes the contact (a branch
 * switch). A check left undecided keeps the continued branch and is counted. */
int gb_dynamics_accept(gb_dynamics *dynamics, double t, double y[GB_STATE_SIZE], double *norm_drift);

/* Switch-event location (continuous contact; gb_integrate uses these). At state y, is another branch
 * lower than the continued one? Then *found = 1 and *other is that minimum. */
int gb_dynamics_switch_pending(gb_dynamics *dynamics, double t, const double y[GB_STATE_SIZE],
                               gb_contact_point *other, int *found);
/* Δh = h(current branch) − h(the branch of `other`) at state y, both continued by Newton (eq 39);
 * *other_here is the other branch at y. In the two-point mode the event's own function, < 0 before it
 * and > 0 after: a third point's Δh against the lower of the two, or −min(N_P, N_Q). */
int gb_dynamics_branch_gap(gb_dynamics *dynamics, double t, const double y[GB_STATE_SIZE],
                           const gb_contact_point *other, double *gap, gb_contact_point *other_here);
/* Make `branch` the contact from time t on (a located switch at state y). Under the unilateral law this
 * is an impact: ω in y jumps. GB_ENUMERIC for an impact the law cannot take (see gb_contact_law). */
int gb_dynamics_switch_to(gb_dynamics *dynamics, double t, double y[GB_STATE_SIZE],
                          const gb_contact_point *branch);

/* What gb_dynamics_switch_to would make of the state y at time t (the impact's ω after, under the
 * unilateral law; y itself under the held law and at a lift), into out, changing nothing: the jump map
 * whose derivative the variational estimator's saltation needs. The contacts are continued to y from
 * the accepted ones and from `branch`. */
int gb_dynamics_jump(gb_dynamics *dynamics, double t, const double y[GB_STATE_SIZE],
                     const gb_contact_point *branch, double out[GB_STATE_SIZE]);

/* In flight: move the centroid by dzeta [m] up and change its velocity by dv [m/s] (inertial) at time t (a
 * Lyapunov perturbation). GB_EINVAL when the body is not in flight. */
int gb_dynamics_flight_displace(gb_dynamics *dynamics, double t, double dzeta, const double dv[3]);

/* Take over the accepted contact of `from` (same body and model): for a trajectory placed next to
 * another one (a Lyapunov perturbation), whose contact is then continued from there. The next accepted
 * step re-checks it as every step does. Switch counters are left alone. */
void gb_dynamics_adopt_contact(gb_dynamics *to, const gb_dynamics *from);
/* The threads of a process share one atlas (gb_atlas_share): `context`'s runs take a view of `lead`'s atlas,
 * which the first of them that needs it makes there (from lead's atlas file, bounded to the bytes set on lead
 * before any run: gb_dynamics_context_atlas_bound, 0: none); a run of another body or atlas definition keeps its
 * own. `lead` outlives `context`; contexts sharing it may run on threads at once. gb_dynamics_context_save on
 * `context` leaves the atlas to gb_dynamics_context_save_shared on `lead` (any thread, at any time: the file takes
 * the cells built so far). The lead's atlas's counters and the cells it read from the file: 0 when it has none. */
void gb_dynamics_context_share(gb_dynamics_context *context, gb_dynamics_context *lead);
void gb_dynamics_context_atlas_bound(gb_dynamics_context *lead, size_t max_bytes);
int gb_dynamics_context_save_shared(gb_dynamics_context *lead);
int gb_dynamics_context_shared_stats(gb_dynamics_context *lead, gb_atlas_stats *out, size_t *cells_read);
/* contact = fast-grid: the tracker's hull vertices (0: no hull, the patch-tree search) and whether the hull
 * came from the context's hull file (1) or Qhull (0); GB_EINVAL for another model. */
int gb_dynamics_hull_stats(const gb_dynamics *dynamics, size_t *vertices, int *loaded);
/* 1 when the run's mass properties came from its context's cache file (the user's cache). */
int gb_dynamics_massprops_loaded(const gb_dynamics *dynamics);

#endif
