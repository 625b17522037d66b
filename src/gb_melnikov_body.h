/* gb_melnikov_body — the reduced model of §7 derived from a Gömböc (docs/melnikov.md).
 *
 * The body rocks about one horizontal body axis a through its top, the unstable equilibrium where r is
 * largest (resting there the centroid is highest). With z₀ the vertical at the top and e the direction of
 * the steepest descent of the centroid height H from it (the eigenvector of H's Hessian at the top with
 * the most negative curvature: "the dominant rocking direction"), a = z₀ × e and the vertical of
 * attitude q is z(q) = cos q z₀ + sin q e. Over q ∈ [0, 2π] the body rolls once over: the separatrix is
 * the rotation orbit over the top (H ≤ r_max everywhere, with equality only at the top).
 *
 *   U(q) = m g (H(q) − r_max),  H(q) = −min_x x·z(q) (the support function: the certified global
 *          minimum), U(0) = 0 = E_s (eqs 81–82)
 *   U′   = m g H′,  H′ = −x_c·z′ (the contact is stationary: envelope theorem)
 *   M(q) = aᵀ I_P a = aᵀ I_c a + m (|d|² − (a·d)²), d = x_c (the centroid is the origin): the moment
 *          of inertia about the contact line of a body rolling about a
 *   S(q) = −m H′(q): U is proportional to g_eff, so the vertical excitation a(t) enters as −m a(t) H′,
 *          and ν₁ = A₁, ν₂ = A₂ in m/s² with the phases of g_eff (eq 25)
 *
 * H is only piecewise smooth: where two contact branches tie (the body touches at two points) H′ jumps.
 * The model is tabulated once on each smooth piece (ties located by bisection on the height gap of the
 * two branches, each continued by Newton; every node certified global by gb_certify) and evaluated by
 * cubic Hermite interpolation on exact values and derivatives (H, H′, H″ from the contact sensitivity
 * of eq 72; M, M′). The damping −cω of the full model is −c q̇ = −(c/M(q)) p here: the paper's −μp holds
 * only for constant M, with μ = c/M(q_u). */
#ifndef GB_MELNIKOV_BODY_H
#define GB_MELNIKOV_BODY_H

#include "gb_export.h"

#include "gb_melnikov.h"
#include "gb_surface.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gb_melnikov_body gb_melnikov_body;

/* The table density `gomboc melnikov` and the scans' margins use (points a smooth piece per radian). */
#define GB_MELNIKOV_BODY_NODES 256

/* The reduced model of `body` with mass `mass` [kg] under gravity g [m/s²]; `nodes` table points a
 * smooth piece per radian (≥ 64). GB_EDOM when the body has no top that is a strict maximum of r (β =
 * 0: a sphere has no unstable equilibrium to rock over). */
GB_API int gb_melnikov_body_create(const gb_surface *body, double mass, double g, size_t nodes, gb_melnikov_body **out);
GB_API void gb_melnikov_body_free(gb_melnikov_body *body);

/* M(q) is the body's inertia about its contact, which jumps where the contact jumps (a tie): with it the
 * reduced system is not conservative across the ties (p = M q̇ continuous, M not: the energy jumps), and
 * the separatrix the paper assumes does not exist. GB_MELNIKOV_MASS_AT_TOP freezes M at M(q_u), the
 * reading under which μ = c/M(q_u) is exact and H₀ is conserved (U is continuous, only U′ jumps). */
typedef enum gb_melnikov_body_mass { GB_MELNIKOV_MASS_AT_TOP = 0, GB_MELNIKOV_MASS_VARIABLE = 1 } gb_melnikov_body_mass;

/* The model for gb_melnikov (saddle at q = 0, a rotation of period 2π in the direction of e); it reads
 * `body`, which must outlive it. Models of both readings may be used side by side. */
GB_API gb_melnikov_model gb_melnikov_body_model(gb_melnikov_body *body, gb_melnikov_body_mass mass);

typedef struct gb_melnikov_body_info {
    double top[3];            /* x at the top (body frame) */
    double r_max;             /* |top| */
    double vertical[3];       /* z₀ */
    double rocking[3];        /* e */
    double axis[3];           /* a = z₀ × e */
    double curvatures[2];     /* of H at the top along e and across it [1/rad²·length] */
    size_t kinks;             /* branch ties over one turn */
    double kink_q[16];        /* their q (the first 16) */
    double kink_jump[16];     /* the jump of H′ there */
    size_t table_nodes;       /* points tabulated in all */
} gb_melnikov_body_info;

GB_API void gb_melnikov_body_get_info(const gb_melnikov_body *body, gb_melnikov_body_info *out);

/* H, H′ and M at q computed directly (continuation from the nearest table node and certification), not
 * interpolated: the tables' oracle. */
GB_API int gb_melnikov_body_direct(gb_melnikov_body *body, double q, double *H, double *dH, double *M);

#ifdef __cplusplus
}
#endif

#endif
