/* gb_certify — proof, at one vertical, that a local minimum of h is the global one (paper §4, eq 29).
 *
 * The contact is the global minimiser of h = ẑ_b·x over the surface. A Newton-continued minimum is only
 * a local one; the grid-based searches can miss a basin narrower than their spacing. This module
 * proves, with interval enclosures of x and its chart derivatives over parameter boxes
 * (gb_surface_enclose), that no surface point is lower than a given minimum p by more than η, or finds
 * a lower minimum, or says it could not decide.
 *
 * The sphere of directions is covered by three charts of boxes: (φ, θ) for 0.8 ≤ φ ≤ π − 0.8, and two
 * polar-x caps (α, γ) ∈ [0.75, π − 0.75]² and [0.75, π − 0.75] × [π + 0.75, 2π − 0.75], which overlap
 * it. The global minimiser is a critical point in every regular chart, and (where the surface is C²) has a
 * positive-semidefinite chart Hessian. A box is settled, for the unit vertical d, when
 *   - FAR:    its lower bound of d·x is at least H − η (H = h(p)); the bound is the direct enclosure
 *             met with the Taylor form about the box centre with d applied first, whose first-order
 *             term is h's own gradient there (small near a critical point), so it is good to O(size²); or
 *   - SLOPE:  an interval of ∂_a h or ∂_b h excludes 0 (no critical point); or
 *   - NO-MIN: (C² boxes) an interval of ∂_aa h or ∂_bb h lies below 0 (no local minimum); or
 *   - BASIN:  it lies inside a basin of p: a box around p on which the interval Hessian of h is positive
 *             definite (h strictly convex there, so p is its minimum; C¹,¹ suffices).
 * Otherwise it is split in four, down to max_depth. A box with a regular interval Hessian that holds
 * a critical point other than p is resolved by Newton from inside it: the point found there is its only
 * critical point; lower than H − η makes it a lower minimum.
 *
 * Along a trajectory the verdicts are kept: a FAR, SLOPE or NO-MIN verdict at vertical d₀ holds at d
 * while its margin exceeds its Lipschitz bound times |d − d₀|. FAR is measured from an anchor x_A, a
 * point fixed while it lives: d·x(q) − d·x_A moves by at most |d − d₀|·max|x(q) − x_A| over the box, and
 * the verdict holds while that bound stays above H − d·x_A − η. Any fixed x_A is valid; a near one
 * makes the bound last. A few anchors live at once: one near the checked minimum and one near each
 * other minimum with a basin, and each box takes the nearest (two minima at a tie, a body on two
 * points, both have boxes with small margins around them). |d − d₀| is bounded by the path length of
 * the verticals checked since. A BASIN verdict holds while that basin is positive definite at d and
 * still holds its minimum: the checked one, or another continued by Newton (a basin changes owner when
 * the checked minimum moves into or out of it, as two tied minima take turns as the lower). A split
 * box keeps a summary of its children's verdicts (the earliest due, the chord of their FAR margins,
 * moved to one anchor, their common basin), so a settled subtree is not walked; when the summary
 * lapses the box is tested again as a whole before its children, so that verdicts do not pile up at
 * the deepest level. A check therefore re-tests only the boxes whose margin ran out. */
#ifndef GB_CERTIFY_H
#define GB_CERTIFY_H

#include "gb_export.h"

#include "gb_contact.h"
#include "gb_surface.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gb_certify_def {
    double height_tol;  /* η: allowed depth of a lower point [body length units] (default 1e-12) */
    int max_depth;      /* splits of a root box (default 24: boxes down to ~2.3e-8 rad) */
    size_t max_nodes;   /* boxes kept with their enclosures; beyond it the cache restarts (default 2^18) */
    int time_checks;    /* 1: add each check's wall time to the stats (make bench; default 0) */
} gb_certify_def;

GB_API gb_certify_def gb_certify_default_def(void);

typedef enum gb_certify_verdict {
    GB_CERTIFY_GLOBAL = 0,       /* no point is lower than the minimum by more than η */
    GB_CERTIFY_LOWER_FOUND = 1,  /* another local minimum is lower by more than η: see `lower` */
    GB_CERTIFY_UNDECIDED = 2     /* some box could be neither settled nor split further */
} gb_certify_verdict;

typedef struct gb_certify_result {
    gb_certify_verdict verdict;
    gb_contact_point lower;  /* LOWER_FOUND: the lower minimum (polished by gb_contact_refine) */
    size_t boxes_tested;     /* boxes whose tests ran in this call (kept verdicts not counted) */
    size_t newton_runs;      /* Newton solves inside boxes in this call */
} gb_certify_result;

typedef struct gb_certify_stats {
    size_t checks, global, lower_found, undecided;
    size_t boxes_tested, newton_runs, basins_built, cache_restarts;
    size_t boxes_kept;       /* boxes with enclosures now held */
    int deepest;             /* deepest split level reached */
    /* basins built for the checked minimum, and the sum of the logarithms of their half-widths [rad]
     * (their geometric mean is exp(sum / count)) */
    size_t minimum_basins;
    double basin_log_width_sum;
    double check_seconds;    /* wall time inside gb_certify_check, when def.time_checks is 1 (else 0) */
} gb_certify_stats;

typedef struct gb_certify gb_certify;

GB_API int gb_certify_create(const gb_surface *surface, const gb_certify_def *def, gb_certify **out);
GB_API void gb_certify_free(gb_certify *certify);

/* Check that `minimum` (a minimum of h for vertical zb, as gb_contact_refine returns it for this zb) is
 * the global one. Consecutive calls along a trajectory reuse verdicts (see above); any vertical may be
 * passed in any order. GB_EDOM for a bad vertical, GB_ENOMEM. */
GB_API int gb_certify_check(gb_certify *certify, const double zb[3], const gb_contact_point *minimum,
                            const gb_contact_refine_def *refine, gb_certify_result *out);

/* Forget every kept verdict (not the enclosures): the next check tests from the root boxes. */
GB_API void gb_certify_forget(gb_certify *certify);

/* The global minimum of h for vertical zb from scratch: Newton from the lowest root-box centre, then
 * check; a lower minimum found replaces it until the check says GLOBAL. GB_ENOCONV when undecided. */
GB_API int gb_certify_global_minimum(gb_certify *certify, const double zb[3], const gb_contact_refine_def *refine,
                                     gb_contact_point *out);

GB_API void gb_certify_get_stats(const gb_certify *certify, gb_certify_stats *out);

#ifdef __cplusplus
}
#endif

#endif
