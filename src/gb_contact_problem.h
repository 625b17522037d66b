/* gb_contact_problem — the one-step frictional contact problem of the time-stepping strategy, solved by Siconos's
 * numerics library (Debian libsiconos-numerics-dev: fc3d, the non-smooth Gauss–Seidel with a Newton solver per
 * contact); internal.
 *
 * Over n contacts, each in its local frame (normal, then two tangents), the local velocities u (3n) depend on the
 * impulses r (3n) through the Delassus operator W (3n × 3n, symmetric positive semi-definite) and a free part q:
 *     u = W r + q.
 * Coulomb's law in De Saxcé's form at every contact i: r_i in the cone K_i = {|r_t| ≤ μ_i r_n}, the modified velocity
 * (u_n + μ_i |u_t|, u_t) in its dual, the two orthogonal. With a contact that sticks, u_i = 0; one that slides has
 * r_t = −μ r_n u_t/|u_t|; one that separates has r_i = 0 and u_n ≥ 0. Newton's impact law enters through q (the
 * caller adds e u_n⁻ to q_n). Siconos chose the method; a problem that does not converge to the tolerance is
 * reported, never taken.
 *
 * Why Siconos here and no code of our own: its fc3d solvers are the field's reference (the same library its own
 * MoreauJeanOSI calls), robust where W is singular (four corners of a face on the plane: the impulses are not unique,
 * the velocities are), and many times faster than enumerating contact sets beyond three points. The enumeration
 * (gb_impact_coulomb) stays as the check on 1–3 points (verify/s5_stepping.c). */
#ifndef GB_CONTACT_PROBLEM_H
#define GB_CONTACT_PROBLEM_H

#include "gb_impact.h"

#include <stddef.h>

/* The most contacts one step takes (the candidates within the gap threshold of a step): a mesh's face or a grid
 * polyhedron's few lowest nodes are far fewer. */
#define GB_CONTACT_PROBLEM_MAX 256
/* the Gauss–Seidel sweeps a problem is given before the proximal point method takes it from there, and the proximal
 * point method's iterations before ADMM does (gb_contact_problem.c) */
#define GB_CONTACT_PROBLEM_NSGS_SWEEPS 200
#define GB_CONTACT_PROBLEM_PROX_ITERATIONS 2000

typedef struct gb_contact_problem_def {
    double tolerance;  /* Siconos's relative error of the solution (its natural-map residual over |q|) */
    size_t iterations; /* the most Gauss–Seidel sweeps */
    size_t first;      /* the time-stepping's candidates posed first (0: all; gb_integrate_def.stepping_first) */
    int siconos;       /* the time-stepping's step linearised where Siconos's MoreauJeanOSI does (gb_integrate_def) */
} gb_contact_problem_def;

/* What the solver did: its sweeps, the residual it reached, and whether it met the tolerance. */
typedef struct gb_contact_problem_report {
    size_t iterations;
    double residual;
    int converged;
    int fallback; /* the Gauss–Seidel stalled and another of Siconos's methods (the proximal point method, ADMM) finished */
    int exact;    /* every method stalled and the caller's exact answer met the tolerance */
} gb_contact_problem_report;

typedef struct gb_contact_problem gb_contact_problem;

/* An exact answer to a problem of at most GB_CONTACT_PROBLEM_EXACT_MAX contacts, from the caller who knows the body
 * (the time-stepping's enumeration of Moreau's law, gb_impact_coulomb_targets): impulses into r (3 count); GB_OK, or
 * an error when it has none. Tried where Siconos's methods have all stalled (the Gauss–Seidel, the proximal point
 * method, ADMM), and taken where Siconos's own measure of it meets the tolerance. */
typedef int (*gb_contact_problem_exact)(void *context, int count, double *r);
#define GB_CONTACT_PROBLEM_EXACT_MAX 4

int gb_contact_problem_create(const gb_contact_problem_def *def, gb_contact_problem **out);
void gb_contact_problem_free(gb_contact_problem *problem);
/* The exact answer the solver may ask for (NULL: none). */
void gb_contact_problem_set_exact(gb_contact_problem *problem, gb_contact_problem_exact exact, void *context);

/* Solve u = W r + q under Coulomb's law at `count` contacts (W column-major 3count × 3count, overwritten by nothing;
 * mu[count]); r and u out (3count each; r is also the start). GB_OK when it met the tolerance; GB_ENOCONV naming
 * the contacts, sweeps and residual when it did not (r, u and the report hold what it reached). */
int gb_contact_problem_solve(gb_contact_problem *problem, int count, double *W, double *q, double *mu, double *r,
                             double *u, gb_contact_problem_report *report);

/* An impact of `body` (velocities v, ω about its centroid) at `count` points (relative to the centroid, at most
 * GB_IMPACT_CONTACTS_MAX) on the plane of normal e_z, posed as the one-step problem (q: the points' velocities before,
 * less their targets in the normal; W_ij = I/m + B_i I⁻¹ B_jᵀ, B_i = −[p_i]×) and solved: each held point leaves at
 * its normal target (target NULL: 0, a plastic impact), the others not below it. The answer as gb_impact_result has it
 * (impulses, velocities after; a point holds where its normal impulse is above 1e-10 of m times the speed |v| + |ω|
 * (+ its target), slides where its slip after is above 1e-8 of the speed: the solver's residual below that is none).
 * The check of the time-stepping strategy's problem against the enumeration (gb_impact_coulomb, and
 * gb_impact_coulomb_targets where the step has targets) and make bench's timing of the two. */
int gb_contact_problem_impact(gb_contact_problem *problem, const gb_impact_body *body, const double (*points)[3], int count,
                              double mu, const double v[3], const double omega[3], const double *target,
                              gb_impact_result *out, gb_contact_problem_report *report);

#endif
