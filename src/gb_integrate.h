/* gb_integrate — time stepping of gb_dynamics (paper §8: "a fixed-step fourth-order scheme").
 *
 *  GB_INTEGRATOR_RK4     classical fixed-step RK4, steps_per_period steps per forcing period (the
 *                        paper: 160); the contact is re-evaluated at every stage.
 *  GB_INTEGRATOR_RK8PD   GSL odeiv2 Prince–Dormand 8(9), adaptive
 *  GB_INTEGRATOR_RKF45   GSL odeiv2 Runge–Kutta–Fehlberg 4(5), adaptive
 *  GB_INTEGRATOR_RK4IMP  GSL odeiv2 implicit Gauss 4th order, adaptive, Jacobian by central differences
 *  GB_INTEGRATOR_BSIMP   GSL odeiv2 implicit Bulirsch–Stoer (Bader–Deuflhard), adaptive, the same Jacobian
 *  GB_INTEGRATOR_MSBDF   GSL odeiv2 multistep BDF of variable order 1–5, adaptive, the same Jacobian; its
 *                        history is kept from step to step (the other steppers restart at each accepted
 *                        step), and restarted at a located event
 *
 * After every accepted step gb_dynamics_accept renormalises the quaternion and updates the contact.
 * With locate_switches (continuous contact, any method) a branch switch found at the end of a step is
 * moved to the time inside the step where the two branches are equally low (eqs 38–39): the step is
 * redone up to that time on the old branch and finished on the new one, by the same stepper (an
 * adaptive one takes both parts as single steps without error control: together they replace an
 * accepted step that met the tolerance).
 * Samples are delivered every `sample_every` nominal steps (T / steps_per_period) to a callback. */
#ifndef GB_INTEGRATE_H
#define GB_INTEGRATE_H

#include "gb_export.h"

#include "gb_dynamics.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum gb_integrator {
    GB_INTEGRATOR_RK4 = 0,
    GB_INTEGRATOR_RK8PD = 1,
    GB_INTEGRATOR_RKF45 = 2,
    GB_INTEGRATOR_RK4IMP = 3,
    GB_INTEGRATOR_BSIMP = 4,
    GB_INTEGRATOR_MSBDF = 5
} gb_integrator;

GB_API const char *gb_integrate_name(gb_integrator method);
GB_API int gb_integrate_parse(const char *name, gb_integrator *method);

/* How time is stepped (docs/stepping.md):
 *  GB_STRATEGY_EVENT_DRIVEN  the modes' smooth equations by `method`, every event located and its jump applied
 *                            exactly (the default: exact, cheap while events are few)
 *  GB_STRATEGY_TIME_STEPPING Moreau–Jean: at each step of T / steps_per_period one frictional contact problem over
 *                            every point of the body that the step would bring into the plane, at the level of
 *                            velocities and impulses (Siconos's fc3d), the θ-method for the smooth forces; first
 *                            order, no event located, robust where events crowd (chatter, faces, many points,
 *                            Painlevé). Needs a law that poses such a problem (gb_dynamics_law.time_steps). */
typedef enum gb_strategy { GB_STRATEGY_EVENT_DRIVEN = 0, GB_STRATEGY_TIME_STEPPING = 1 } gb_strategy;

GB_API const char *gb_integrate_strategy_name(gb_strategy strategy);
GB_API int gb_integrate_strategy_parse(const char *name, gb_strategy *strategy);
/* Opt-in, process-wide: the BLAS behind Siconos's solvers on one thread (OpenBLAS's openblas_set_num_threads, found
 * by name; nothing where another BLAS serves). Time-stepping solves problems of a few hundred rows, where
 * OpenBLAS's threads spin on the cores a scan's own threads use: Gömböc II in units of g at μ = 0.5, 2 periods
 * time-stepped, 7.1 s wall with them against 2.6 s. The command calls it; a host program that runs its own BLAS
 * threads decides for itself (or sets OPENBLAS_NUM_THREADS=1). Returns 1 when it found OpenBLAS. */
GB_API int gb_integrate_blas_single_thread(void);

typedef struct gb_integrate_def {
    gb_integrator method;
    size_t steps_per_period; /* RK4 step and sampling grid (Table 1: 160) */
    double periods;          /* run length in forcing periods (Table 1: 300) */
    double rtol, atol;       /* adaptive steppers (default 1e-10, 1e-12) */
    size_t sample_every;     /* deliver every n-th nominal step (default 1) */
    size_t max_steps;        /* adaptive steppers: give up (GB_ENOCONV) after this many steps; 0: no limit */
    int locate_switches;     /* continuous contact: find the time where Δh = 0 inside the step (Illinois on
                                the step fraction), switch there, finish the step (default 0) */
    gb_strategy strategy;    /* event-driven (default) or time-stepping */
    double theta;            /* time-stepping: the θ of the θ-method, 1/2 <= θ <= 1 (default 1/2) */
    double solver_tolerance; /* time-stepping: the contact problem's relative residual (default 1e-12) */
    size_t solver_iterations; /* time-stepping: its most sweeps (default 20000) */
    size_t stepping_first;    /* time-stepping: a step with more candidates poses the most urgent this many first and adds
                               * those the solution would let through the plane (default 64; 0: every candidate at once,
                               * the reduction's check; docs/stepping.md). No scene key: either gives a solution of the whole
                               * problem (the same state to 3e-14 on a polar cap landing, verify/s5_stepping.c) */
    int stepping_siconos;     /* time-stepping: 1 linearises the step where Siconos's MoreauJeanOSI on a NewtonEulerDS does
                               * (the relations at the attitude the step predicts, q ⊗ exp(h ω / 2) by Siconos's quaternion
                               * exponential, whose small-angle series is tan(x)/x's, and the rotation's forces ω × Iω + c ω
                               * θ-implicit linearised at the step's start) instead of at the step's start with the
                               * gyroscopic term explicit (0, the default); 2 as 1 with the exact exponential: the harness's
                               * step-for-step comparison with Siconos's kernel (verify/siconos.c). No scene key;
                               * docs/stepping.md */
    int hand_over;            /* event-driven with RK4: where the law meets a configuration it does not follow (a model's
                               * limit, gb_error_at_limit: Painlevé's paradox, three points sliding, a face landing on a
                               * plane of finite friction...), the step is taken again by time-stepping (θ, the solver
                               * above) and the run goes on so until the body flies, where the events take it back
                               * (default 0: the run stops there, exit 1); docs/stepping.md */
} gb_integrate_def;

GB_API gb_integrate_def gb_integrate_default_def(void);

typedef struct gb_integrate_stats {
    size_t steps, rhs_evaluations, failed_steps;
    double max_norm_drift;    /* largest |q| − 1 removed by renormalisation */
    double max_step_rotation; /* largest |ω| h at the end of an accepted step [rad] */
    size_t coarse_steps;      /* fixed-step RK4: accepted steps with |ω| h > GB_INTEGRATE_ROTATION_MAX */
    /* def.hand_over: the run's hand-overs to time-stepping and its returns to the events, the steps stepped, the
     * first hand-over's time and reason (the limit's message); a trajectory that follows another (a Lyapunov pair's
     * copy) hands over and back at the other's steps, and counts the steps where it could not (unmatched) */
    size_t hand_overs, hand_backs, stepped_steps, unmatched;
    double hand_over_first;
    char hand_over_reason[512];
} gb_integrate_stats;

/* The turn a fixed RK4 step may make and still resolve the spin: at |ω| h = 0.25 rad the scheme's error
 * on a rotation is (ω h)⁵/120 ≈ 8e-6 rad a step in phase and (ω h)⁶/72 ≈ 3e-6 of the kinetic energy a step
 * (the amplification factor of RK4 on ẏ = iωy is 1 − (ωh)⁶/144 + …), which over the 48 000 steps of a
 * Table 1 run reaches the percent. Beyond it a run is warned about (gomboc run) and counted
 * (coarse_steps); every shipped scene turns by at most 0.013 rad a step (Table 1 in units of g, paper model). */
#define GB_INTEGRATE_ROTATION_MAX 0.25

/* Called at t0 and every sample; return non-zero to stop (the run then returns GB_OK early). */
typedef int (*gb_integrate_sample)(void *context, double t, const double y[GB_STATE_SIZE]);

/* Integrate from t0 over def->periods periods, y in/out: gb_integrate_begin, the sample at t0, one
 * gb_integrate_advance over every step, gb_integrate_end. Every GSL status is checked. */
GB_API int gb_integrate_run(gb_dynamics *dynamics, const gb_integrate_def *def, double t0, double y[GB_STATE_SIZE],
                            gb_integrate_sample sample, void *context, gb_integrate_stats *stats);

/* A run in pieces. The nominal grid t_n = t0 + n·T/steps_per_period is global to the session and an
 * adaptive stepper keeps its state between pieces, so advancing by n₁ then n₂ steps takes exactly the
 * steps of one advance by n₁ + n₂ (the Lyapunov pair advances its reference period by period and
 * stays bit-identical to a plain run). Samples go to `sample` at every global step index that is a
 * multiple of sample_every; the sample at t0 is the caller's. def->periods is not used by a session. */
typedef struct gb_integrate_session gb_integrate_session;

GB_API int gb_integrate_begin(gb_dynamics *dynamics, const gb_integrate_def *def, double t0,
                              gb_integrate_session **out);
/* Advance y by `steps` nominal steps. After a sample callback has asked to stop, does nothing. */
GB_API int gb_integrate_advance(gb_integrate_session *session, size_t steps, double y[GB_STATE_SIZE],
                                gb_integrate_sample sample, void *context);
/* The nominal steps in `periods` forcing periods (rounded to the nearest whole step). */
GB_API size_t gb_integrate_steps_for(const gb_integrate_session *session, double periods);
GB_API double gb_integrate_time(const gb_integrate_session *session);
GB_API int gb_integrate_stopped(const gb_integrate_session *session);
GB_API const gb_integrate_stats *gb_integrate_session_stats(const gb_integrate_session *session);
GB_API void gb_integrate_end(gb_integrate_session *session);

#ifdef __cplusplus
}
#endif

#endif
