/* What the benchmarks of make bench share (verify/bench/bench*.c): the body of a run, the clock, the settings of
 * the runs timed (law, certificate, units, restitution, friction, atlas file) and what the last one left (its
 * certificate's and atlas's counters, the grid searches' work, its set-up), the record for the report, the plain
 * loop's and the native baseline's seconds; each benchmark's entry point. */
#ifndef BENCH_H
#define BENCH_H

#include "gb_case.h"
#include "gb_contact.h"
#include "gb_dynamics.h"
#include "gb_integrate.h"
#include "gb_lyapunov.h"

#include <stdint.h>
#include <stdio.h>

enum { VERTICALS = 2000, REPEATS = 3 };

extern gb_atlas_stats last_atlas;
extern size_t last_atlas_fallbacks;
extern int last_atlas_loaded;
extern gb_certify_stats last_certificate;
extern size_t last_nodes;
extern size_t last_queries;
extern double last_setup;
extern double native_seconds[2];
extern double plain_seconds[2];
extern FILE *record;
extern const char *run_atlas_file;
extern const char *run_cache_dir; /* the contexts' cache directory (mass properties, hull); NULL: none */
extern gb_dynamics_certificate run_certificate;
extern double run_friction;
extern gb_contact_law run_law;
extern int run_locate;
extern double run_restitution;
extern double run_units_g;

int bench_atlas(void);
/* Remove the folder `dir` the bench made and everything under it; 0 on success, else a message and 1. */
int bench_remove_tree(const char *dir);
/* The native build's path (bench-gomboc-native), for the paired whole-run ratios; NULL: none. */
extern const char *native_path;
const gb_surface *bench_body(const char *morphology, double beta);
int bench_dynamics(void);
void bench_flight(void);
void bench_friction(void);
void bench_headroom(void);
int bench_melnikov(void);
int bench_scans(const char *gomboc, FILE *out);
void bench_stepping(void);
void bench_unilateral(void);
int bench_unilateral_maps(const char *gomboc, FILE *out);
int bench_shared_atlas_cpu(const char *gomboc, FILE *out);
int bench_whole_process(const char *native, const char *gomboc, FILE *out);
int bench_work_precision(const char *python);
double now(void);
/* qsort's comparison of doubles, ascending. */
int bench_compare_doubles(const void *a, const void *b);
void run_native(const char *path);
uint64_t state_hash(const double y[GB_STATE_SIZE]);
double time_lyapunov(const char *m, gb_contact_model contact, gb_dynamics_variant variant, int repeats, double y[GB_STATE_SIZE], double *lambda);
double time_run(const char *m, gb_contact_model contact, gb_dynamics_variant variant, int repeats, double y[GB_STATE_SIZE], size_t *switches);
double time_run_with(const char *m, gb_contact_model contact, gb_dynamics_variant variant, int repeats, const gb_certify_def *certify, double y[GB_STATE_SIZE], size_t *switches);

#endif
