/* gb_scan_internal — what the scan's own files (gb_scan*.c), the command and the checks share beyond the
 * public API of gb_scan.h: the file's text alone (the fuzzer), the random attitudes of a random axis, the
 * Melnikov plan a run computes once for its points, a point's run in a thread's context, the metrics'
 * accumulators, the CSV's parser and the journal of an interrupted scan. Not installed, not exported. */
#ifndef GB_SCAN_INTERNAL_H
#define GB_SCAN_INTERNAL_H

#include "gb_scan.h"

#include <stdint.h>

/* The scan file's text alone (`path` for messages; the base scene is neither read nor checked): what
 * gb_scan_load does before it reads the base scene. For the fuzzer. */
int gb_scan_parse(const char *path, const char *text, size_t size, gb_scan *out);

/* The k-th uniformly random attitude of a random axis, as the case file's "axis-angle X,Y,Z,ANGLE". */
void gb_scan_random_attitude(unsigned long seed, size_t k, char *text, size_t size);

/* ---- the Melnikov plan (gb_scan_plan.c) ----
 * The reduced model costs a table per body (mass, g) and the integrals (eqs 88–90) once per ω, about a
 * second each, while the margin of a point is then a one-dimensional maximisation. A scan computes them
 * once for the points it will run: plan the distinct bodies and frequencies of `points[0..count)`, then
 * compute every body (gb_scan_melnikov_body) before any frequency (gb_scan_melnikov_frequency); distinct
 * indices may run on threads at once. A point's margins from the plan are those of
 * gb_scan_melnikov_margins, bit for bit. A scan without the metric plans nothing. */
typedef struct gb_scan_melnikov gb_scan_melnikov;

int gb_scan_melnikov_plan(const gb_scan *scan, const size_t *points, size_t count, gb_scan_melnikov **out);
size_t gb_scan_melnikov_bodies(const gb_scan_melnikov *plan);
size_t gb_scan_melnikov_frequencies(const gb_scan_melnikov *plan);
int gb_scan_melnikov_body(gb_scan_melnikov *plan, size_t i);
int gb_scan_melnikov_frequency(gb_scan_melnikov *plan, size_t i);
void gb_scan_melnikov_free(gb_scan_melnikov *plan);
/* The margins of `scene` from a computed plan that holds it (GB_EINVAL when it does not). */
int gb_scan_melnikov_planned(const gb_scan_melnikov *plan, const gb_case *scene, double *margin, double *margin_eq93);

/* ---- a point (gb_scan_point.c) ----
 * Point `index` with its margins from `melnikov` (computed; it must have planned this point; NULL: computed
 * for this point alone), in `context` (gb_dynamics_context: the body's set-up and the atlas of verticals,
 * read from scan->atlas_file by the first point that needs it; writing it back is the caller's; NULL: the
 * point's own). The results are those of gb_scan_point_run, bit for bit. */
int gb_scan_point_run_in(const gb_scan *scan, const gb_scan_melnikov *melnikov, size_t index, gb_dynamics_context *context,
                         gb_scan_metrics *out);

/* The accumulators of the per-sample metrics (apart for their checks against closed forms). */
typedef struct gb_scan_accumulator {
    double first_t;                    /* samples at t ≥ first_t count */
    size_t samples;
    double omega2_sum, height_sum, t_start, t_last;
    size_t switches_start, switches_last;
    /* the unilateral law's mechanism (GB_SCAN_CONTACTS): samples by points on the plane (0 … 3) and with a
     * point slipping, impacts and landings at t ≥ first_t and the kinetic energy they took, friction's work
     * at the first and the last sample counted */
    size_t on_plane[4], slipping, impacts, landings;
    double impact_loss, friction_start, friction_last;
} gb_scan_accumulator;

void gb_scan_accumulate(gb_scan_accumulator *a, double t, const double omega[3], double height, size_t switches);
/* A sample's contact mode (points on the plane, points slipping, friction's work so far), after
 * gb_scan_accumulate of the same sample; and an impact of the unilateral law. */
void gb_scan_accumulate_mode(gb_scan_accumulator *a, double t, int contacts, int sliding, double friction_work);
void gb_scan_accumulate_impact(gb_scan_accumulator *a, const gb_dynamics_impact *e);
/* omega_rms, mean height and switch rate of what was accumulated (NAN when nothing was). */
void gb_scan_accumulated(const gb_scan_accumulator *a, double *omega_rms, double *mean_height, double *switch_rate);

/* The lifetime of the chaos in a record λ_inst[0..n) (see gb_scan_metrics.chaos_lifetime). */
double gb_scan_chaos_lifetime(const double *lambda, size_t n, double periods_per_interval);

/* ---- rows and the journal (gb_scan_rows.c) ---- */

/* The metric columns of the CSV (after index and the two axes), comma-separated. */
const char *gb_scan_csv_metric_columns(void);
/* The metrics of a point that failed under failed_points = record: its coordinates, every metric NaN,
 * no certificate counts, zero fingerprints. */
void gb_scan_failed_metrics(const gb_scan *scan, size_t index, gb_scan_metrics *out);
/* Parse a row written by gb_scan_csv_row (a journal line): 0, or GB_EINVAL. */
int gb_scan_csv_parse(const char *line, size_t *index, gb_scan_metrics *out);

#endif
