/* gb_handle — the library behind opaque pointers and flat arrays, for bindings (the Python package `gomboc`,
 * python/gomboc, over cffi's ABI mode: it declares these functions and calls the shared library, with no compiler
 * at import). The structs the rest of the library passes by value (gb_case, gb_run_result) stay on this side.
 *
 * A scene is loaded from a file or a text, with overrides (section, key, value) applied in order as a scan's axes
 * are: every error names the file, the line, the key and the allowed range (gb_error_message). A run is gb_run of
 * the scene (the same bits as `gomboc run`: its fingerprints are the command's), with every sample kept in memory
 * as a row of the history's columns (gb_handle_columns: the history file's, unrounded) and every impact as a row of
 * the impacts file's numeric columns, when asked. */
#ifndef GB_HANDLE_H
#define GB_HANDLE_H

#include "gb_export.h"

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct gb_handle_scene gb_handle_scene;
typedef struct gb_handle_run gb_handle_run;

/* overrides: `count` triples section, key, value (3 count strings). GB_EINVAL / GB_EDOM as gb_case_load. */
GB_API int gb_handle_scene_load(const char *path, const char *const *overrides, size_t count, gb_handle_scene **out);
GB_API int gb_handle_scene_text(const char *name, const char *text, const char *const *overrides, size_t count,
                                gb_handle_scene **out);
GB_API void gb_handle_scene_free(gb_handle_scene *scene);

/* Run `scene`; keep_history: every sample a row of gb_handle_columns(); keep_impacts: every impact a row of
 * gb_handle_impact_columns(). */
GB_API int gb_handle_run_scene(const gb_handle_scene *scene, int keep_history, int keep_impacts, gb_handle_run **out);
GB_API void gb_handle_run_free(gb_handle_run *run);

/* The history's columns (NULL-terminated names) and the rows kept: samples × columns, row-major. */
GB_API const char *const *gb_handle_columns(void);
GB_API const double *gb_handle_run_history(const gb_handle_run *run, size_t *rows);
GB_API const char *const *gb_handle_impact_columns(void);
GB_API const double *gb_handle_run_impacts(const gb_handle_run *run, size_t *rows);

/* The fingerprints (FNV-1a 64 of the final state's bytes, and of the switches): `gomboc run`'s. */
GB_API uint64_t gb_handle_run_fingerprint(const gb_handle_run *run, int which);

/* The run's scalar results by name (NULL-terminated names; NAN for an unknown name): t_end, steps, samples,
 * energy_residual, residual_max, impacts, impact_energy_lost, grid_switches, branch_switches, seconds, the final
 * state omega_x, omega_y, omega_z, and λ where the scene asks for it: lambda_max, lambda_error, lambda_converged. */
GB_API const char *const *gb_handle_values(void);
GB_API double gb_handle_run_value(const gb_handle_run *run, const char *name);

/* The scene's body: mass properties (volume, centroid x y z, inertia about the centroid row by row: 13 numbers, the
 * scene's mass) and the contact for the body-frame vertical zb as `gomboc contact --method continuous` finds it (every
 * local minimum of the 180 × 360 seed grid polished, the lowest: φ, θ, height, r_c x y z, 6 numbers). */
GB_API int gb_handle_scene_massprops(const gb_handle_scene *scene, double out[13]);
GB_API int gb_handle_scene_contact(const gb_handle_scene *scene, const double zb[3], double out[6]);
/* The body's equilibria as `gomboc shape` finds them (gb_shape_equilibria with its default def): every critical point
 * of r(φ, θ), a row each (type: 0 stable, 1 saddle, 2 unstable; φ; θ; r), the first `capacity` rows into out (4
 * numbers a row), the number found in *count. GB_EINVAL for a mesh body (its equilibria: `gomboc shape --mesh`). */
GB_API int gb_handle_scene_equilibria(const gb_handle_scene *scene, double *out, size_t capacity, size_t *count);
/* The scene's Melnikov margins (§7) as `gomboc scan`'s metric `melnikov` computes them for a point of this scene:
 * out[0] the largest oscillatory part of eq 91 over μD, out[1] eq 93's (A1 A1* + A2 A2*)/μD (> 1: the reduced
 * model's manifolds cross). */
GB_API int gb_handle_scene_melnikov(const gb_handle_scene *scene, double out[2]);

/* The reduced model's manifolds at the scene's whole forcing, as `gomboc melnikov CASE --tangle SPACING
 * [--tangle-threshold HALVINGS]` computes them (M frozen at the top, the paper's damping): out[0] the homoclinic
 * orbits a fundamental domain crosses, out[1] the smallest angle there [deg] (NaN without), out[2], out[3] the period
 * map's multipliers, out[4], out[5] the A1 bracket where the manifolds start to cross (HALVINGS > 0; else NaN). */
GB_API int gb_handle_scene_tangle(const gb_handle_scene *scene, double spacing, int halvings, double out[6]);

/* A scan file run as `gomboc scan` runs it, on `threads` threads (0: one per online processor), its CSV (header, then
 * every point's row in index order: the bytes of the command's NAME-scan.csv) into *csv (malloc'd; free it with
 * gb_handle_text_free). `progress` (may be NULL), one call at a time from the scan's threads: the phase (0 the
 * Melnikov margins' models and integrals, 1 the points), the tasks done and their number, the phase's wall
 * seconds; nonzero from it is ignored. Its scene keys' errors as gb_scan_load's; a failed point as the command's
 * (recorded with NaN metrics under failed_points = record). */
typedef void (*gb_handle_progress)(void *user, int phase, size_t done, size_t total, double seconds);
GB_API int gb_handle_scan(const char *path, unsigned threads, gb_handle_progress progress, void *user, char **csv);
GB_API void gb_handle_text_free(char *text);

#ifdef __cplusplus
}
#endif

#endif
