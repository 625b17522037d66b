/* gb_integrate_internal — the one RK4 step and the one switch locator of the library, shared by the
 * integrator (gb_integrate) and the variational estimator (gb_lyapunov_body); internal. */
#ifndef GB_INTEGRATE_INTERNAL_H
#define GB_INTEGRATE_INTERNAL_H

#include "gb_integrate.h"

/* The most changes of contact one step may hold under the unilateral law; more stop the run. A chatter
 * the settle rule has not yet ended is one source; a grid body is another: near a chart pole the grid's
 * nodes close up into rings of tiny facets, and a body rolling across one meets hundreds of them in a
 * step. */
#define GB_INTEGRATE_EVENTS_PER_STEP_MAX 4096

/* The most tangent vectors one step carries (gb_lyapunov's GB_LYAPUNOV_MAX_EXPONENTS). */
#define GB_INTEGRATE_TANGENT_MAX 8

/* The derivative of the vector field along a tangent vector: out = A(t, y)·dy (eq 75). */
typedef int (*gb_integrate_tangent)(void *context, gb_dynamics *dynamics, double t, const double y[GB_STATE_SIZE],
                                    const double dy[GB_STATE_SIZE], double out[GB_STATE_SIZE]);

/* One classical RK4 step of size h from (t, y) into out (out may be y). With k > 0 it also carries the
 * k tangent vectors Y (k × GB_STATE_SIZE, updated in place) by the same stages, the tangent's stage
 * derivatives from `tangent` at the reference's stage states. The reference's arithmetic does not
 * depend on k. stats (may be NULL) counts the right-hand sides. */
int gb_integrate_rk4_step(gb_dynamics *dynamics, double t, double h, const double y[GB_STATE_SIZE],
                          double out[GB_STATE_SIZE], size_t k, double *Y, gb_integrate_tangent tangent,
                          void *context, gb_integrate_stats *stats);

/* Where inside the RK4 step (t, y) → t + h the branch `other` becomes the lower one (eqs 38–39): the
 * fraction θ of the step at which Δh = 0, by the Illinois method on the RK4 step of size θh on the
 * current branch. */
typedef struct gb_integrate_switch {
    double fraction;                 /* θ: 0 when `other` is no higher at the start, 1 when it is lower
                                        only at the end (no sign change inside the step) */
    int crossed;                     /* 1 when Δh changes sign inside the step */
    double y[GB_STATE_SIZE];         /* the state at θ, on the current branch */
    gb_contact_point other;          /* `other` continued to that state */
} gb_integrate_switch;

int gb_integrate_locate_switch(gb_dynamics *dynamics, double t, double h, const double y[GB_STATE_SIZE],
                               const gb_contact_point *other, gb_integrate_switch *out, gb_integrate_stats *stats);

/* The same for a step that starts at a change of contact (the unilateral law's next event inside a step):
 * a gap ≥ 0 at the start is the tie the change left, and the crossing after it is located. */
int gb_integrate_locate_next(gb_dynamics *dynamics, double t, double h, const double y[GB_STATE_SIZE],
                             const gb_contact_point *other, gb_integrate_switch *out, gb_integrate_stats *stats);
/* Put `to` (a session of a second copy of the same scene) at the time, step count and step size of
 * `from`, in the strategy `from` is in (a run handed over to time-stepping: def.hand_over): for a trajectory placed
 * next to another one. Call it before gb_dynamics_adopt_contact, which then copies the stepping's state. */
int gb_integrate_follow(gb_integrate_session *to, const gb_integrate_session *from);
/* `follower` (a Lyapunov pair's copy) hands over to time-stepping and back at the steps where `leader` did, rather than
 * where its own law meets a limit or it flies (def.hand_over; a step it cannot match is counted, stats.unmatched); the
 * leader advances first over each stretch. */
void gb_integrate_lead(gb_integrate_session *follower, const gb_integrate_session *leader);

#endif
