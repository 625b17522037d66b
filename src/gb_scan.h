/* gb_scan — maps over two keys of a scene (paper §8.3, Figs 10–13).
 *
 * A scan file names a base scene, two of its keys (any section: ω, A₁, A₂, ψ, β, c, …) with their ranges
 * and counts, the run per point and the metrics (cases/README.md, "Scan files"). Every point is the base
 * scene with three kinds of keys set over it (gb_case_override): the two coordinates, the run length, and
 * what the metrics need (the strobe and λ when asked; no history, spectrum or files). A point is then
 * run by gb_run, the same call as `gomboc run`: a scan point is, bit for bit, the run of that scene.
 *
 * The scan file is read by the strict reader (gb_ini): known sections and keys, each once, every value
 * one whole token in its range; errors name the file, the line, the key and the allowed values. */
#ifndef GB_SCAN_H
#define GB_SCAN_H

#include "gb_export.h"

#include "gb_case.h"

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define GB_SCAN_FILE_MAX (64 * 1024)
#define GB_SCAN_AXIS_MAX 10000
#define GB_SCAN_POINTS_MAX 1000000 /* points in all: a scan's results are held in memory */
#define GB_SCAN_PATH_MAX 4096
/* [scan] atlas_file: what fits on its line (GB_INI_LINE_MAX = 198 bytes, less "atlas_file = ") */
#define GB_SCAN_ATLAS_NAME_MAX 185

/* linear: from … to; pi: from … to times π; random: `count` attitudes drawn uniformly on the rotations
 * (initial.attitude only), the k-th from a generator seeded with `seed` and k (the column holds k). */
typedef enum gb_scan_scale { GB_SCAN_LINEAR = 0, GB_SCAN_PI = 1, GB_SCAN_RANDOM = 2 } gb_scan_scale;

typedef struct gb_scan_axis {
    char section[32], key[32];  /* the scene key this axis sets */
    double from, to;            /* in the key's units; with scale = pi, in multiples of π */
    size_t count;               /* points along the axis (1: from alone) */
    gb_scan_scale scale;
    unsigned long seed;         /* random: the generator's seed */
    int line;                   /* the scan file's line of `key`, for messages */
} gb_scan_axis;

/* The metrics a point may compute (its `metrics` key lists them). */
enum {
    GB_SCAN_OMEGA_RMS = 1 << 0,   /* √(mean |ω|²) over the samples after the transient [rad/s] */
    GB_SCAN_SWITCH_RATE = 1 << 1, /* contact changes (grid + branch) after the transient, per second [1/s] */
    GB_SCAN_STROBE_SD = 1 << 2,   /* std of ω_x over the stroboscopic samples after the transient [rad/s] */
    GB_SCAN_MEAN_HEIGHT = 1 << 3, /* mean h* (eq 36) after the transient [body length units] */
    GB_SCAN_MONITORS = 1 << 4,    /* fractions of samples with g_eff ≤ 0 and with N ≤ 0 (the whole run) */
    GB_SCAN_LAMBDA = 1 << 5,      /* λ_max and its error bar over the record after the transient [1/s] */
    GB_SCAN_MELNIKOV = 1 << 6,    /* the reduced model's margins (§7): the point's forcing over the threshold */
    GB_SCAN_CONTACTS = 1 << 7,    /* the unilateral law's mechanism after the transient: time fractions on one
                                   * point, on two, at rest, in flight, sliding; impacts, landings and energy lost
                                   * per period; the contacts at the end (NAN under the held law) */
    GB_SCAN_METRICS_ALL = (1 << 8) - 1,
    /* What a scan file without `metrics` computes: what the run itself yields (no λ, no margins). */
    GB_SCAN_METRICS_DEFAULT = GB_SCAN_METRICS_ALL & ~(GB_SCAN_LAMBDA | GB_SCAN_MELNIKOV)
};

/* The names of the metrics in `metrics` (as a scan file writes them), in the CSV's order: their number. */
GB_API size_t gb_scan_metric_names(unsigned metrics, const char **names, size_t max);

typedef struct gb_scan {
    char path[GB_SCAN_PATH_MAX];       /* the scan file */
    char description[GB_CASE_TEXT_MAX];
    char base[GB_SCAN_PATH_MAX];       /* the base scene, resolved against the scan file's directory */
    gb_scan_axis axis[2];              /* x (columns), y (rows) */
    double periods;                    /* per point */
    size_t transient_periods;          /* metrics from this period on */
    unsigned metrics;                  /* GB_SCAN_* */
    int record_failures;               /* [scan] failed_points = record: a point whose computation fails (exit
                                        * status 1 of its run: a contact lost, an impact the model cannot take)
                                        * is a row of NaN metrics and zero fingerprints, and the scan goes on;
                                        * stop (0, the default): the scan stops there */
    int atlas_shared;                  /* [scan] atlas = shared: every point's scene certifies its contact with
                                        * the atlas of verticals ([model] certificate = atlas), and the points
                                        * share one atlas through atlas_file (`gomboc scan` sets it: --atlas
                                        * FILE, or NAME-scan.atlas in the output directory); the results are
                                        * those of the per-vertical certificate, bit for bit. none (0): the
                                        * base scene's certificate */
    int atlas_line;                    /* its line, for messages */
    int hand_over, hand_over_line;     /* [scan] hand_over = time-stepping (1): every point's scene hands its run to
                                        * time-stepping where the event-driven law cannot follow ([integrator]
                                        * hand_over); none (0): the base scene's own */
    char atlas_name[GB_SCAN_ATLAS_NAME_MAX + 1];              /* [scan] atlas_file (with atlas = shared): the shared atlas's file name in
                                        * the output directory, so that scans of one body share it ("": the
                                        * scan's own NAME-scan.atlas) */
    int atlas_name_line;
    uint64_t fingerprint;              /* FNV-1a of the scan file's and the base scene's bytes */
    unsigned char identity[32];        /* BLAKE2b-256 of the same bytes (gb_seal_digest, gb_scan_load): the name a
                                        * journal carries, which no other scan file and base can be made to carry */
    int base_line;                     /* the scan file's line of `base`, for messages */
    char *base_text;                   /* the base scene as read once (every point starts from it) */
    size_t base_size;
    /* The atlas file (NULL: none): every point whose scene has [model] certificate = atlas starts its atlas
     * of verticals from FILE and writes it back with the cells it added (as `gomboc run --atlas`), so that
     * the points share one atlas; the results are those of the per-vertical certificate. */
    const char *atlas_file;
} gb_scan;

/* Read a scan file and its base scene, and check every point's scene (each point loads: a bad range is
 * found before any run). GB_EINVAL / GB_EDOM with "FILE:LINE: [section] key = value: reason (allowed:
 * ...)". On success the scan holds the base scene's text: gb_scan_free. */
GB_API int gb_scan_load(const char *path, gb_scan *out);

GB_API void gb_scan_free(gb_scan *scan);

GB_API size_t gb_scan_points(const gb_scan *scan);

/* The coordinates of point `index` (row-major: index = iy · count_x + ix), in the keys' own units. */
GB_API void gb_scan_coordinates(const gb_scan *scan, size_t index, double *x, double *y);

/* The scene of point `index`. */
GB_API int gb_scan_point_case(const gb_scan *scan, size_t index, gb_case *out);

typedef struct gb_scan_metrics {
    double x, y;
    double omega_rms, switch_rate, strobe_sd, mean_height;
    double geff_nonpositive, lift_off;
    double lambda, lambda_error;
    double lambda_early, lambda_late;  /* means of λ_inst over the first and the second half of the record */
    /* The lifetime of the chaos: the record cut into 12 windows (of at least 20 intervals), the end of
     * the last window whose mean λ_inst exceeds GB_LYAPUNOV_CHAOTIC, in forcing periods from the record's
     * start; 0 when no window does, +inf when the last one does (still chaotic at the end: censored),
     * NAN when the record is too short. */
    double chaos_lifetime;
    /* The Melnikov margins of the point's scene (see gb_scan_melnikov_margins): > 1 where the reduced
     * model's manifolds cross; NAN where the reduced model is not defined (no top to rock over, g ≤ 0). */
    double melnikov_margin, melnikov_margin_eq93;
    /* GB_SCAN_CONTACTS (the unilateral law; NAN under the held law, which keeps one contact at all times):
     * fractions of the samples from the transient on with 1, 2, 3 (at rest) and 0 (in flight) points on the
     * plane and with a point slipping; impacts (the changes of contact the ledger books as impacts: landings
     * included; lifts, lift-offs and a crease's end not),
     * landings and the energy impacts and friction took, per forcing period from the transient on; the
     * points on the plane at the end (0 in flight … 3 at rest). */
    double one_point, two_point, at_rest, in_flight, sliding;
    double stepped;                    /* the share of the run's steps time-stepped after a hand-over (0: none) */
    double impacts_per_period, landings_per_period, energy_lost_per_period;
    double end_contacts;
    size_t certificate_undecided;      /* continuous contact: certificate checks left undecided */
    uint64_t state_fingerprint, switch_fingerprint; /* as `gomboc run` prints them */
} gb_scan_metrics;

/* ---- the Melnikov margin (paper §7, eqs 91–93; docs/melnikov.md) ----
 * The reduced model rocks the point's body over its top with M frozen at M(q_u), the splitting integral
 * weighted by q̇ (GB_MELNIKOV_EXACT) and the damping −μp, μ = c/M(q_u): the defaults of `gomboc melnikov`.
 * With the point's forcing (ν₁ = A₁, ν₂ = A₂ in m/s², its ω and ψ):
 *   margin       = max over t₀ of the oscillatory part of M(t₀) / μD  (> 1: M changes sign, eq 91)
 *   margin_eq93  = (ν₁A₁* + ν₂A₂*) / μD                               (> 1: eq 93 holds; ≥ margin)
 * Both are linear in the forcing's scale: a point at margin m is at m times its threshold A₁ with A₂/A₁
 * and ψ held. +inf without damping (NAN with neither damping nor forcing), NAN where the reduced model is
 * not defined (GB_EDOM from it: no strict top, no saddle; or g ≤ 0). */
GB_API int gb_scan_melnikov_margins(const gb_case *scene, double *margin, double *margin_eq93);

/* Run point `index` alone; metrics not asked for are NAN. A scan of margins alone runs no dynamics: the
 * run's fingerprints are then 0. */
GB_API int gb_scan_point_run(const gb_scan *scan, size_t index, gb_scan_metrics *out);

/* The CSV header and one row (every metric %.17g, fingerprints in hex); each ends with '\n'. The header names
 * the columns: index, the two axes by their keys (SECTION.KEY, such as forcing.omega), then the metrics. */
GB_API int gb_scan_csv_header(const gb_scan *scan, char *out, size_t size);
GB_API int gb_scan_csv_row(const gb_scan_metrics *m, size_t index, char *out, size_t size);

/* ---- running a scan ----
 * gb_scan_run runs the points of a scan on threads (POSIX threads: one work queue of points, each thread
 * pulling the next; docs/layout.md says why not OpenMP) and hands each finished point to the caller, one
 * at a time, as it finishes. The results do not depend on the number of threads: every point is the run
 * of its scene, bit for bit. Before the points, the reduced models and Melnikov integrals the points'
 * margins need are computed once each, on the same threads (bodies, then frequencies).
 *
 * Each thread keeps a gb_dynamics_context from point to point (the body's mass properties, grid and hull), so
 * that a point costs its integration, not its set-up. The threads of a process share one atlas of verticals
 * (scan->atlas_file): read from its file by the first point that needs it, each cell proved once, by the first
 * thread that needs it (gb_atlas.c, "sharing"), no cell built beyond GB_SCAN_ATLAS_MEMORY bytes (checks there go
 * to the per-vertical certificate), merged with its file and written back every GB_SCAN_ATLAS_SAVE_POINTS points
 * the process ran and at its end. */
#define GB_SCAN_ATLAS_SAVE_POINTS 8
#define GB_SCAN_ATLAS_MEMORY ((size_t)256 << 20)

typedef enum gb_scan_phase {
    GB_SCAN_PHASE_MELNIKOV = 0, /* the reduced models and their integrals (tasks: models + frequencies) */
    GB_SCAN_PHASE_POINTS = 1    /* the points */
} gb_scan_phase;

typedef struct gb_scan_progress {
    gb_scan_phase phase;
    size_t done, total;       /* the phase's tasks finished by this process, and their number */
    size_t models, frequencies; /* GB_SCAN_PHASE_MELNIKOV: the reduced models and the frequencies planned */
    double seconds;           /* wall time since the phase began */
} gb_scan_progress;

typedef struct gb_scan_runner {
    unsigned threads;         /* 0: one per online processor; at most 256 */
    /* This process runs the i-th point not yet done for i ≡ rank (mod ranks) (MPI ranks share a scan so):
     * 0 and 1 run them all. */
    size_t rank, ranks;
    const unsigned char *done; /* gb_scan_points entries: 1 where a point is done already (a journal's), not
                                * run again; NULL: none */
    /* A finished point: its metrics and its CSV row (gb_scan_csv_row). Called one at a time, from the
     * thread that ran it. Nonzero (a gb_ status, its message set by gb_error_set) stops the scan with it. */
    int (*finished)(void *user, size_t index, const gb_scan_metrics *metrics, const char *row);
    /* What the caller should hear without the scan stopping (may be NULL), one at a time: a point whose
     * computation failed under failed_points = record ("point K (...) failed, recorded with NaN metrics:
     * ...": its `finished` call follows), a shared atlas that could not be written. */
    void (*notice)(void *user, const char *message);
    /* Progress (may be NULL), one call at a time: at each phase's start (done = 0) and end (done = total),
     * and between at most every `progress_seconds` (0: 2 s). A phase with no task is not reported. */
    void (*progress)(void *user, const gb_scan_progress *progress);
    double progress_seconds;
    void *user;
} gb_scan_runner;

/* Run the scan's points (runner->done's excepted) as runner says. GB_OK, or the first failure: a point's
 * ("point K (SECTION.KEY = X, SECTION.KEY = Y) failed: why", its gb_ status; the points running then finish,
 * no new one starts), a `finished` call's, or GB_EINVAL for a runner out of range. *points_run (may be
 * NULL) counts the points this process finished. */
GB_API int gb_scan_run(const gb_scan *scan, const gb_scan_runner *runner, size_t *points_run);

/* The threads gb_scan_run uses for runner->threads = `threads` (0: one per online processor). */
GB_API unsigned gb_scan_threads(unsigned threads);

/* The journal of an interrupted scan. Its first line names the scan (the BLAKE2b-256 identity of the scan
 * file and base scene), the binary and the number of points; each further line is one finished point:
 * its CSV row (gb_scan_csv_row) and the seal (gb_seal: keyed BLAKE2b-256) of the header and the row. A
 * journal is verified, never trusted: every line must carry a seal that verifies under this user's key (so
 * an edited value is refused even when whoever edited it recomputed a checksum), read back to the same row,
 * hold the point's own coordinates, and name a point of the scan; a point twice must be the same twice.
 * Only a half-written last line (no '\n') may go; an empty journal holds no points. */
#define GB_SCAN_JOURNAL_LINE_MAX 1200
GB_API void gb_scan_journal_header(const gb_scan *scan, uint64_t binary, char *out, size_t size);
/* The journal line of a CSV row (GB_EIO when there is no key to seal it). */
GB_API int gb_scan_journal_line(const char *header, const char *row, char *out, size_t size);
/* Read a journal's bytes (`name` for messages) into results/done (each of gb_scan_points entries,
 * done zeroed by the caller): GB_OK with the points read in *count and in *keep the bytes to keep
 * (all but a half-written last line), or GB_EINVAL naming the line and what is wrong with it. */
GB_API int gb_scan_journal_read(const gb_scan *scan, const char *name, const char *header, const char *text, size_t size,
                                gb_scan_metrics *results, unsigned char *done, size_t *count, size_t *keep);

#ifdef __cplusplus
}
#endif

#endif
