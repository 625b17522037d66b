/* gb_impact — the impact of a rigid body on a plane that can only push (Moreau's impact law).
 *
 * A pure function of a generic rigid body: its mass, its inertia about the centroid, the points that
 * may touch the plane (relative to the centroid) and the velocities just before (the centroid's,
 * relative to the plane, and the angular velocity), all in one frame. It knows nothing of Gömböcs: a
 * cuboid, a sphere or a Gömböc at a contact switch are the same problem.
 *
 * The plane is rough (no slip at a contact that holds) and restitutive in the normal direction by
 * Newton's law with coefficient e (0: plastic). Moreau's law over the contacts: after the impact each
 * contact either holds, its velocity (-e times its normal approach speed) n and its normal impulse
 * >= 0, or separates, its impulse 0 and its normal velocity >= 0. This is a small linear
 * complementarity problem, solved exactly by enumerating which contacts hold: for each set, the
 * impulses that give the held contacts their velocities (the Delassus system, by SVD: two or three
 * held points leave internal impulses undetermined, which change no velocity), then the signs are
 * checked. A well-posed impact has one feasible set; the smallest is taken when several are.
 *
 * With e = 0 the kinetic energy lost is the kinetic energy of the velocity jump (Kelvin's theorem);
 * when the new point alone holds, the angular momentum about it is conserved. verify/s5_impact.c checks
 * both, and Housner's rocking block (1963), in closed form. */
#ifndef GB_IMPACT_H
#define GB_IMPACT_H

#include "gb_export.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { GB_IMPACT_CONTACTS_MAX = 4 };

/* Points closer than this fraction of the farthest point's distance from the centroid are one point: the
 * impulses of coincident points are not determined, and a law that divides by their distance would make
 * them any size. gb_impact_solve and gb_impact_hold_all solve for the distinct points and give each
 * coincident one the state of the first of its kind, with no impulse of its own. */
#define GB_IMPACT_SAME_POINT 1e-9

typedef struct gb_impact_body {
    double mass;          /* > 0 */
    double inertia[3][3]; /* about the centroid, symmetric positive definite */
} gb_impact_body;

typedef struct gb_impact_result {
    double v[3], omega[3];                        /* after the impact */
    int holds[GB_IMPACT_CONTACTS_MAX];            /* 1: the contact holds after the impact; 0: it separates */
    double impulse[GB_IMPACT_CONTACTS_MAX][3];    /* the plane's impulse at each contact */
    double normal_impulse[GB_IMPACT_CONTACTS_MAX], tangential_impulse[GB_IMPACT_CONTACTS_MAX];
    double friction_needed;                       /* max |P_t| / P_n over the contacts that hold (0: none) */
    double energy_before, energy_after;           /* kinetic energy [J] */
    int feasible_sets;                            /* contact sets that satisfy the law (1 when well posed) */
    /* A plane of finite friction (gb_impact_coulomb): which held contacts slide after, each point's slip
     * (the tangential part of its velocity) before and after, and the stages of a one-point impact (slip,
     * stick, slip again: gb_impact_coulomb_point). 0 under the rough law. */
    int slides[GB_IMPACT_CONTACTS_MAX];
    double slip_before[GB_IMPACT_CONTACTS_MAX][3], slip_after[GB_IMPACT_CONTACTS_MAX][3];
    int stages;
} gb_impact_result;

/* Newton's restitution e, its one range: 0 ≤ e ≤ GB_IMPACT_RESTITUTION_MAX (the scene table reads it from
 * here). gb_impact_restitution_check: GB_OK, or GB_EDOM naming the range. */
#define GB_IMPACT_RESTITUTION_MAX 1.0
GB_API int gb_impact_restitution_check(double e);

/* The impact of `body` moving with centroid velocity v and angular velocity omega, at the `count`
 * points (relative to the centroid) that may touch the plane of unit normal `normal`, with
 * restitution e. GB_OK; GB_EDOM for a bad body, count or e (the message says the allowed range);
 * GB_ENUMERIC when no contact set satisfies the law (not seen for a body with positive mass). */
GB_API int gb_impact_solve(const gb_impact_body *body, const double normal[3], double e, const double (*points)[3],
                           int count, const double v[3], const double omega[3], gb_impact_result *out);

/* The plastic impact that holds all `count` points at rest after, whatever the signs of its impulses: a
 * chatter of impacts lumped into one (the dynamics' settle rule). Where the impulses are indeterminate
 * (coincident points, three points), the minimum-norm ones. The system always has a solution (the
 * points' velocities lie in the range of the Delassus operator); GB_ENUMERIC only if its SVD solve
 * misses it by more than its residual tolerance. GB_EDOM as gb_impact_solve. */
GB_API int gb_impact_hold_all(const gb_impact_body *body, const double normal[3], const double (*points)[3], int count,
                              const double v[3], const double omega[3], gb_impact_result *out);
/* One point meeting the plane, rough in the limit of Coulomb friction μ → ∞ of the Darboux–Keller impulse
 * process: the slip is stopped first by a tangential impulse (no normal impulse is needed for it when μ is
 * unbounded); if the point still approaches the plane after that, the normal impulse brings its velocity
 * to −e times that approach at no slip (holds[0] = 1); if it no longer approaches, the impact ends there and
 * the point leaves (holds[0] = 0, friction_needed INFINITY: a tangential impulse with no normal one). Where
 * Moreau's law with a held point (gb_impact_solve, count 1) has a pushing solution and the slip-stopping
 * stage leaves the point approaching, the two laws give the same impulse; where Moreau's would need the
 * plane to pull, this one has the answer. The kinetic energy never grows (each stage takes the energy of
 * its velocity jump, less e² of the normal part's). GB_EDOM as gb_impact_solve. */
GB_API int gb_impact_rough_point(const gb_impact_body *body, const double normal[3], double e, const double point[3],
                                 const double v[3], const double omega[3], gb_impact_result *out);
/* ---- a plane of finite friction (gb_impact_coulomb.c; docs/friction.md) ----
 * Coulomb's law: at a contact that holds, the tangential impulse lies in the cone |P_t| ≤ μ P_n, and a
 * contact that slides after the impact takes the cone's edge against its slip.
 *
 * One point (gb_impact_coulomb_point): the impact integrated in the normal impulse p as Darboux and
 * Keller do, du/dp = W (n + f), f = −μ u_t/|u_t| while the point slips; when the slip stops the point
 * sticks if the cone holds the impulse that keeps it stopped (f = −W_tt⁻¹ W_tn, |f| ≤ μ), else it slips on
 * in the one direction the law allows. Compression ends where u_n = 0; the impact ends where the normal
 * impulse's work in restitution is e² times that in compression (Stronge's energetic coefficient: the
 * kinetic energy never grows, which Newton's coefficient does not guarantee once slip changes during the
 * impact; where slip does not change the two coincide). μ = INFINITY is gb_impact_rough_point.
 *
 * Several points (gb_impact_coulomb): the set of contacts that take impulse is enumerated from the
 * smallest, as gb_impact_solve does; a single point by Darboux–Keller above; two or more at once by
 * Moreau's law with Coulomb's cone at the velocity level (each held contact sticks, u⁺ = −e u_n⁻ n, or
 * slides, u_n⁺ = −e u_n⁻ with P_t = −μ P_n u_t⁺/|u_t⁺|; the slip directions found by root finding), the
 * first set and status that satisfy every sign taken. Newton's coefficient there: with e > 0 and friction
 * it may add energy (the result says so: energy_after > energy_before). μ = INFINITY is gb_impact_solve. */
GB_API int gb_impact_coulomb_point(const gb_impact_body *body, const double normal[3], double e, double mu,
                                   const double point[3], const double v[3], const double omega[3], gb_impact_result *out);
GB_API int gb_impact_coulomb(const gb_impact_body *body, const double normal[3], double e, double mu,
                             const double (*points)[3], int count, const double v[3], const double omega[3],
                             gb_impact_result *out);
/* μ's range: 0 < μ (INFINITY: rough). GB_OK, or GB_EDOM naming it. */
GB_API int gb_impact_friction_check(double mu);

/* The kinetic energy ½ m |v|² + ½ ω·Iω. */
GB_API double gb_impact_energy(const gb_impact_body *body, const double v[3], const double omega[3]);

#ifdef __cplusplus
}
#endif

#endif
