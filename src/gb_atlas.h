/* gb_atlas — an atlas of verticals: where the global contact can be, proved once per cell of
 * verticals, so that a step of a continuous-contact run is certified by a lookup (paper §4, eq 29).
 *
 * gb_certify proves the contact global at one vertical at a time; along a run that proof is most of
 * the cost (docs/certificate.md). The atlas proves a statement about a whole set of verticals instead.
 * The sphere of verticals d is cut into cells: the six faces of a cube, each a quadtree of squares,
 * a square's verticals being the unit vectors through it. A cell C has a centre d₀ and a radius ρ
 * (every d in C has |d − d₀| ≤ ρ). Its certificate names one or two *sites*: a site is a box in each
 * chart of the surface's parameters that lies near its minimum, on which the chart Hessian d·x'' is
 * positive definite for every d in C. Then, for every d in C:
 *   - each site box holds at most one critical point of h = d·x, a minimum (h is strictly convex on it);
 *   - every other box of the cover of the sphere of directions (gb_certify's three charts) holds no
 *     global minimum, because for every d in C it has no critical point (SLOPE: d·x_a or d·x_b keeps
 *     its sign; the intervals at d₀ widened by ρ|x_a|), or no minimum (NO-MIN: d·x_aa or d·x_bb < 0,
 *     or a negative determinant), or lies higher than a site's point x_s (FAR: d·(x − x_s) > 0, bounded
 *     by the Taylor form at d₀ minus ρ max|x − x_s|).
 * So the global minimum at d is the critical point of one of the named sites. A check at d finds the
 * cell (a lookup), sees whether the contact lies in every looked-up box of a site (it is then that
 * site's critical point), and finds the critical point of each other site by Newton from where it was
 * last (inside its looked-up boxes: it is then that site's only one). A polar-x site box whose
 * directions all lie in the (φ, θ) band 0.8 ≤ φ ≤ π − 0.8 is not looked up: a global minimum in it lies
 * in the band, where the proof confined it to the (φ, θ) site boxes. The lowest is the global minimum; a switch is
 * made, as gb_certify makes it, when it is lower than the contact by more than η.
 *
 * Cells are built when a check first needs them (lazily, along the trajectory), from level
 * first_level; a cell whose certificate cannot be completed (its boxes do not settle by max_depth
 * splits, or it needs a third site) is split into four, down to max_level; a cell at max_level that
 * still fails is marked, and checks there say UNDECIDED (the caller then runs gb_certify). A check whose
 * Newton solve fails, or whose contact lies in only some of its site's looked-up boxes, is UNDECIDED too.
 *
 * The atlas can be saved to and loaded from a file keyed by morphology, β, η, the build parameters and
 * the library's atlas format and sealed (gb_seal: a keyed BLAKE2b-256 of its bytes); a file that does not
 * match, or whose seal does not verify, is refused. */
#ifndef GB_ATLAS_H
#define GB_ATLAS_H

#include "gb_export.h"

#include "gb_certify.h"
#include "gb_contact.h"
#include "gb_surface.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gb_atlas_def {
    double height_tol;   /* η, as gb_certify_def (default 1e-12) */
    int first_level;     /* cells are first built at this quadtree level of a cube face (default 5) */
    int max_level;       /* a failing cell is split down to this level (default 13) */
    int max_depth;       /* splits of a root box of the surface cover in a cell's proof (default 14) */
} gb_atlas_def;

GB_API gb_atlas_def gb_atlas_default_def(void);

typedef struct gb_atlas_stats {
    size_t checks;         /* gb_atlas_check calls */
    size_t answered;       /* ... answered GLOBAL or LOWER_FOUND (the rest: UNDECIDED) */
    size_t lower_found;
    size_t newton_runs;    /* Newton solves for other sites' minima */
    size_t cells;          /* cells certified */
    size_t cells_failed;   /* cells at max_level without a certificate */
    size_t two_site_cells; /* certified cells with two sites */
    size_t cells_split;    /* cells split because their proof failed */
    size_t boxes;          /* surface boxes with enclosures held */
    size_t boxes_tested;   /* box tests in cell proofs */
    int deepest_level;
    double build_seconds;  /* wall time spent building cells */
    size_t bytes;          /* memory held by cells and boxes */
    size_t waits;          /* checks that waited for a cell another view (thread) was proving */
    double wait_seconds;   /* wall time they waited */
} gb_atlas_stats;

typedef struct gb_atlas gb_atlas;

GB_API int gb_atlas_create(const gb_surface *surface, const gb_atlas_def *def, gb_atlas **out);
GB_API void gb_atlas_free(gb_atlas *atlas);

/* As gb_certify_check: is `minimum` (a local minimum of h at zb, as gb_contact_refine returns it) the
 * global one (GLOBAL), or is another minimum lower by more than η (LOWER_FOUND, the lowest of them in
 * out->lower)? UNDECIDED when the cell has no certificate or a Newton solve failed: the caller then
 * asks gb_certify. Builds the cell if needed. GB_EDOM for a bad vertical, GB_ENOMEM. */
GB_API int gb_atlas_check(gb_atlas *atlas, const double zb[3], const gb_contact_point *minimum,
                          const gb_contact_refine_def *refine, gb_certify_result *out);

/* The certificate of the cell of zb (built if needed), for the harness: its centre d0, radius rho,
 * level, site count (0 when the cell has no certificate) and each site's boxes. */
typedef struct gb_atlas_site_box {
    gb_surface_chart chart;
    double a_lo, a_hi, b_lo, b_hi;
} gb_atlas_site_box;

typedef struct gb_atlas_cell_info {
    double d0[3], rho;
    double corner[4][3];     /* the unit verticals at its corners */
    int level, sites;
    int boxes[2];
    gb_atlas_site_box box[2][2];
} gb_atlas_cell_info;

GB_API int gb_atlas_cell(gb_atlas *atlas, const double zb[3], gb_atlas_cell_info *out);
/* Every certified cell held (in preorder of the six faces' quadtrees): up to `max` of them into out,
 * and their number in *count. */
GB_API void gb_atlas_cells(const gb_atlas *atlas, gb_atlas_cell_info *out, size_t max, size_t *count);

/* Save the cells built so far (with those that have no certificate, so that they are not proved
 * again) as a gb_file set of one: a unique temporary renamed into place, so that concurrent writers of
 * one file never cost each other their outputs (the last complete one wins; gb_atlas_merge_save
 * merges the file's cells first, under a lock, so that they add up). Load a saved atlas (its
 * cells replace the ones held): GB_EIO for a file that is not a regular file, is larger than
 * an atlas of its levels can be (gb_atlas_file.c), is not an atlas of this body, β, η and build
 * parameters, or whose seal does not verify (damaged, edited, or sealed under another key): the caller then builds anew. GB_EIO too when the
 * file cannot be sealed (no key: gb_seal_key_ready). */
GB_API int gb_atlas_save(const gb_atlas *atlas, const char *path);
/* Every atlas file starts with these bytes (the string with its NUL). */
#define GB_ATLAS_FILE_MAGIC "gomboc-atlas"
GB_API int gb_atlas_load(gb_atlas *atlas, const char *path);
/* The largest file an atlas of these levels can be (every cell split down to max_level, every leaf
 * certified with two sites), and never more than GB_ATLAS_FILE_MAX: a larger file is refused unread. */
#define GB_ATLAS_FILE_MAX ((size_t)64 << 20)
/* The cells of the atlas file at `path` that this atlas lacks, added to it (a cell both hold is kept as
 * it is: its proof does not depend on the run that made it). What gb_dynamics_context_save does before it
 * writes, so that concurrent runs sharing one file add up their cells. GB_EIO when the file is missing,
 * of another atlas or damaged (the atlas is then unchanged, or holds the cells read before the fault). */
GB_API int gb_atlas_merge(gb_atlas *atlas, const char *path);

/* gb_atlas_load on the bytes of a file already read (`name` for messages). */
GB_API int gb_atlas_load_buffer(gb_atlas *atlas, const unsigned char *data, size_t size, const char *name);

GB_API void gb_atlas_get_stats(const gb_atlas *atlas, gb_atlas_stats *out);

#ifdef __cplusplus
}
#endif

#endif
