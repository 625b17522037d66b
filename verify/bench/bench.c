/* make bench: speed, measured in one run and printed as ratios (never asserted in `make verify`).
 *
 * Contact selection (paper §4, §8): the exact fast grid search against the paper's brute-force scan
 * on the same nodes and the same seeded verticals, for grids from Table 1's 90 × 180 to 720 × 1440;
 * and the continuous minimiser, both as a full branch search and as a Newton polish from the fast
 * grid's node (the way a time-stepper would use it). Each timing is the best of REPEATS passes over
 * the verticals, which removes most scheduling noise; the nodes are checked equal as a sanity test. */
#include "gb_case.h"
#include "gb_contact.h"
#include "gb_error.h"
#include "gb_integrate.h"
#include "gb_lyapunov_body.h"
#include "gb_massprops.h"
#include "gb_melnikov_body.h"
#include "gb_surface_internal.h"
#include "bench.h"
#include "plain.h"
#include <cjson/cJSON.h>

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <ftw.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdint.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
/* The body (morphology, beta) of a bench run; the names are literals known valid. */
const gb_surface *bench_body(const char *morphology, double beta)
{
    static gb_surface body;
    if (gb_surface_init(&body, morphology, beta)) {
        fprintf(stderr, "bench: %s\n", gb_error_message());
        exit(1);
    }
    return &body;
}


double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Remove the folder `dir` the bench made and everything under it (without a shell); 0 on success, else a
 * message on stderr and 1. */
static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

int bench_remove_tree(const char *dir)
{
    if (nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS) == 0) return 0;
    fprintf(stderr, "bench: cannot remove %s\n", dir);
    return 1;
}

typedef int (*grid_search)(const gb_contact_grid *, const double[3], gb_contact_node *);

/* Best-of-REPEATS seconds per query; the found indices go to `index`. */
static double time_search(const gb_contact_grid *g, double (*zb)[3], grid_search search, size_t *index)
{
    double best = 1e300;
    for (int r = 0; r < REPEATS; r++) {
        const double start = now();
        for (int k = 0; k < VERTICALS; k++) {
            gb_contact_node n;
            search(g, zb[k], &n);
            index[k] = n.index;
        }
        const double t = (now() - start) / VERTICALS;
        if (t < best) best = t;
    }
    return best;
}

/* The certificate's counters of the last continuous run timed (for the printout). */
gb_certify_stats last_certificate;
/* contact = grid through a search of one's own (the plain loop), when set; and the grid searches' work
 * in the fastest repeat of the last run timed. */
static gb_dynamics_lowest_node run_lowest;
static void *run_lowest_context;
size_t last_queries, last_nodes;
double last_setup; /* seconds of gb_dynamics_create and init_state in the fastest repeat */
/* continuous contact: the certificate of the runs timed, the atlas file (NULL: none), and the atlas's
 * counters of the fastest repeat */
gb_dynamics_certificate run_certificate = GB_CERTIFICATE_PER_VERTICAL;
gb_contact_law run_law = GB_CONTACT_LAW_HELD;
int run_locate; /* locate every change of contact inside its step (the rolling scenes' setting) */
double run_units_g = 1.0;  /* 9.81: Table 1's amplitudes read in units of g (eq 61) */
double run_restitution;    /* the unilateral law's e */
double run_friction = INFINITY; /* the unilateral law's μ (INFINITY: the rough plane) */
const char *run_atlas_file;
const char *run_cache_dir;
gb_atlas_stats last_atlas;
size_t last_atlas_fallbacks;
int last_atlas_loaded;

/* One Table 1 run (300 periods, RK4 160 steps per period, R0 = I, ω0 = 0) of morphology `m` with
 * `contact`/`variant`; returns the CPU seconds of the integration (best of `repeats`), the final state
 * in y and the grid-index changes in *switches. */
double time_run_with(const char *m, gb_contact_model contact, gb_dynamics_variant variant, int repeats,
                            const gb_certify_def *certify, double y[GB_STATE_SIZE], size_t *switches);

double time_run(const char *m, gb_contact_model contact, gb_dynamics_variant variant, int repeats,
                       double y[GB_STATE_SIZE], size_t *switches)
{
    return time_run_with(m, contact, variant, repeats, NULL, y, switches);
}

/* A fresh context for one timed run: the atlas file (continuous contact), the cache directory where a row
 * names one, and the grid's lowest-node search the bench is comparing, nothing else shared between repeats. */
static gb_dynamics_context *bench_context(gb_contact_model contact)
{
    gb_dynamics_context *context = NULL;
    if (gb_dynamics_context_create(&context) ||
        gb_dynamics_context_files(context, contact == GB_CONTACT_MODEL_CONTINUOUS ? run_atlas_file : NULL, NULL) ||
        gb_dynamics_context_cache(context, run_cache_dir)) {
        fprintf(stderr, "bench: %s\n", gb_error_message());
        exit(1);
    }
    if (contact == GB_CONTACT_MODEL_GRID) gb_dynamics_context_lowest(context, run_lowest, run_lowest_context);
    return context;
}

/* time_run with the certificate's definition `certify` (NULL: the default); the certificate's counters
 * kept are those of the fastest repeat. */
double time_run_with(const char *m, gb_contact_model contact, gb_dynamics_variant variant, int repeats,
                            const gb_certify_def *certify, double y[GB_STATE_SIZE], size_t *switches)
{
    double best = 1e300;
    for (int r = 0; r < repeats; r++) {
        gb_surface s;
        gb_surface_init(&s, m, 0.12);
        gb_dynamics_def def = gb_dynamics_default_def();
        def.contact = contact;
        def.variant = variant;
        if (certify) def.certify = *certify;
        def.contact_law = run_law;
        def.forcing.a1 *= run_units_g, def.forcing.a2 *= run_units_g;
        def.restitution = run_restitution;
        def.friction = run_friction;
        if (run_law == GB_CONTACT_LAW_UNILATERAL) /* one step, as a scene's (gb_case) */
            def.settle_time = gb_forcing_period(&def.forcing) / (double)gb_integrate_default_def().steps_per_period;
        if (contact == GB_CONTACT_MODEL_CONTINUOUS) def.certificate = run_certificate;
        gb_dynamics *d;
        const double R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, w0[3] = {0, 0, 0};
        const double setup_start = now();
        gb_dynamics_context *context = bench_context(contact);
        if (gb_dynamics_create_in(&s, &def, context, &d) || gb_dynamics_init_state(d, 0.0, R0, w0, y)) {
            fprintf(stderr, "bench: %s\n", gb_error_message());
            exit(1);
        }
        const double setup = now() - setup_start;
        gb_integrate_def idef = gb_integrate_default_def();
        idef.locate_switches = run_locate;
        gb_integrate_stats stats;
        const double start = now();
        if (gb_integrate_run(d, &idef, 0.0, y, NULL, NULL, &stats)) {
            fprintf(stderr, "bench: %s\n", gb_error_message());
            exit(1);
        }
        const double t = now() - start;
        gb_dynamics_observables o;
        gb_dynamics_observe(d, 300 * 2 * M_PI / 18.0, y, &o);
        *switches = o.grid_switches + o.branch_switches;
        if (contact == GB_CONTACT_MODEL_CONTINUOUS && t < best) gb_dynamics_certify_stats(d, &last_certificate);
        if (def.certificate == GB_CERTIFICATE_ATLAS && t < best)
            gb_dynamics_atlas_stats(d, &last_atlas, &last_atlas_fallbacks, &last_atlas_loaded);
        if (t < best) gb_dynamics_contact_work(d, &last_queries, &last_nodes), last_setup = setup;
        if (t < best) best = t;
        gb_dynamics_free(d);
        if (gb_dynamics_context_save(context)) {
            fprintf(stderr, "bench: %s\n", gb_error_message());
            exit(1);
        }
        gb_dynamics_context_free(context);
    }
    return best;
}

/* λ_max over the same 300 periods (the pair of eq 77, renormalised every period): CPU seconds, best of
 * `repeats`, and the reference's final state in y (which must be the plain run's). */
double time_lyapunov(const char *m, gb_contact_model contact, gb_dynamics_variant variant, int repeats,
                            double y[GB_STATE_SIZE], double *lambda)
{
    double best = 1e300;
    for (int r = 0; r < repeats; r++) {
        gb_dynamics_def def = gb_dynamics_default_def();
        def.contact = contact;
        def.variant = variant;
        if (contact == GB_CONTACT_MODEL_CONTINUOUS) def.certificate = run_certificate;
        const gb_integrate_def idef = gb_integrate_default_def();
        const double R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, w0[3] = {0, 0, 0};
        gb_lyapunov_def ldef = gb_lyapunov_default_def();
        ldef.interval = 2.0 * M_PI / def.forcing.omega;
        ldef.intervals = 300;
        const double start = now();
        gb_lyapunov_body *body;
        gb_lyapunov_result res;
        gb_dynamics_context *context = bench_context(contact);
        int status = gb_lyapunov_body_create_in(bench_body(m, 0.12), &def, context, &idef, R0, w0, def.forcing.omega, &body);
        if (!status) {
            const gb_lyapunov_pair_system ps = gb_lyapunov_body_pair(body);
            status = gb_lyapunov_pair(&ps, body, &ldef, 0.0, NULL, &res);
        }
        if (status) {
            fprintf(stderr, "bench: %s\n", gb_error_message());
            exit(1);
        }
        const double t = now() - start;
        if (t < best) best = t;
        memcpy(y, gb_lyapunov_body_state(body), GB_STATE_SIZE * sizeof *y);
        *lambda = res.lambda_max;
        gb_lyapunov_result_free(&res);
        gb_lyapunov_body_free(body);
        if (gb_dynamics_context_save(context)) {
            fprintf(stderr, "bench: %s\n", gb_error_message());
            exit(1);
        }
        gb_dynamics_context_free(context);
    }
    return best;
}

FILE *record; /* bench.json for the report, when a path was given */
double plain_seconds[2]; /* the plain loop's Table 1 run per body (bench_dynamics) */

/* The honest baseline: the best plain loop (plain.c: its own translation unit, the nodes as three
 * aligned arrays, a vectorised reduction) with the library's equations of motion around it, all built
 * apart with the best flags of this compiler (make bench builds bench-gomboc-native from this file,
 * plain.c and a library compiled with -O3 -march=native), and run here, side by side, as a subprocess:
 * "--plain-only" prints, per body, "BODY SECONDS STATE-HASH SWITCHES MISMATCHES LIBRARY-SECONDS SETUP": the
 * plain loop's run, its final state's hash and grid switches, the verticals (of 10^4 seeded) on which its
 * node differs from the library's brute force, the library's own loop in the same build, and the plain
 * run's set-up (the body, the grid and the plain loop's copy of it). */
uint64_t state_hash(const double y[GB_STATE_SIZE])
{
    uint64_t h = 14695981039346656037ull;
    const unsigned char *p = (const unsigned char *)y;
    for (size_t k = 0; k < GB_STATE_SIZE * sizeof *y; k++) h = (h ^ p[k]) * 1099511628211ull;
    return h;
}

static int plain_only(void)
{
    for (int m = 0; m < 2; m++) {
        const char *name = m ? "II" : "I";
        const gb_dynamics_def def = gb_dynamics_default_def();
        gb_contact_grid *grid;
        plain_grid plain;
        const double layout_start = now();
        if (gb_contact_grid_create(bench_body(name, 0.12), &def.grid, &grid) || plain_grid_create(grid, &plain)) {
            fprintf(stderr, "bench: cannot build the plain loop's grid\n");
            return 1;
        }
        const double layout = now() - layout_start; /* the plain loop's own copy of the nodes */
        gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
        gsl_rng_set(rng, 20261123UL);
        size_t mismatches = 0;
        for (int k = 0; k < 10000; k++) {
            double zb[3], d[3];
            gsl_ran_dir_3d(rng, &zb[0], &zb[1], &zb[2]);
            gb_contact_node node;
            if (gb_contact_unit_vertical(zb, d) || gb_contact_grid_brute(grid, zb, &node)) return 1;
            mismatches += plain_lowest(&plain, d) != node.index;
        }
        gsl_rng_free(rng);
        double y[GB_STATE_SIZE], y_library[GB_STATE_SIZE];
        size_t switches, switches_library;
        run_lowest = plain_lowest, run_lowest_context = &plain;
        const double t = time_run(name, GB_CONTACT_MODEL_GRID, GB_VARIANT_PAPER, 2, y, &switches);
        const double setup = last_setup + layout;
        run_lowest = NULL, run_lowest_context = NULL;
        const double library = time_run(name, GB_CONTACT_MODEL_GRID, GB_VARIANT_PAPER, 2, y_library, &switches_library);
        printf("%s %.6f %016llx %zu %zu %.6f %.6f\n", name, t, (unsigned long long)state_hash(y), switches, mismatches, library,
               setup);
        plain_grid_free(&plain);
        gb_contact_grid_free(grid);
    }
    return 0;
}

/* `bench-gomboc-native --plain-process BODY`: the plain loop's whole job as a process of its own (the body's
 * grid, its copy of the nodes, the Table 1 run of 300 periods), for bench_whole_process to time from outside; it
 * prints the state's hash, the run's seconds and the set-up's (grid, copy, dynamics) for bench_atlas's pairs. */
static int plain_process(const char *name)
{
    const gb_dynamics_def def = gb_dynamics_default_def();
    gb_contact_grid *grid;
    plain_grid plain;
    const double layout_start = now();
    if (gb_contact_grid_create(bench_body(name, 0.12), &def.grid, &grid) || plain_grid_create(grid, &plain)) return 1;
    const double layout = now() - layout_start;
    double y[GB_STATE_SIZE];
    size_t switches;
    run_lowest = plain_lowest, run_lowest_context = &plain;
    const double t = time_run(name, GB_CONTACT_MODEL_GRID, GB_VARIANT_PAPER, 1, y, &switches);
    printf("%016llx %.6f %.6f\n", (unsigned long long)state_hash(y), t, last_setup + layout);
    plain_grid_free(&plain);
    gb_contact_grid_free(grid);
    return 0;
}

static const char usage[] =
    "usage: bench-gomboc [FILE [NATIVE [GOMBOC]]]\n"
    "  every section; the whole-run ratios also as JSON to FILE (written to FILE.tmp, renamed when all pass),\n"
    "  against the plain loop of NATIVE (bench-gomboc-native), scans and whole processes through GOMBOC\n"
    "one section alone, for development:\n"
    "  bench-gomboc --plain-only | --work-precision | --unilateral | --stepping | --friction\n"
    "  bench-gomboc --certified NATIVE | --shared-atlas GOMBOC | --unilateral-maps GOMBOC\n"
    "  bench-gomboc --whole-process NATIVE GOMBOC | --plain-process I|II\n";

/* Which words a section takes after its option; -1: not an option of this program. */
static int section_words(const char *option)
{
    static const struct { const char *name; int words; } sections[] = {
        {"--plain-only", 0},    {"--work-precision", 0}, {"--unilateral", 0},     {"--stepping", 0},
        {"--friction", 0},      {"--certified", 1},      {"--shared-atlas", 1},   {"--unilateral-maps", 1},
        {"--whole-process", 2}, {"--plain-process", 1},
    };
    for (size_t k = 0; k < sizeof sections / sizeof sections[0]; k++)
        if (!strcmp(option, sections[k].name)) return sections[k].words;
    return -1;
}

int main(int argc, char **argv)
{
    char tmp[1024] = "";
    if (argc > 1 && (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h"))) {
        fputs(usage, stdout);
        return 0;
    }
    if (argc > 1 && argv[1][0] == '-') {
        const int words = section_words(argv[1]);
        if (words < 0 || argc != 2 + words ||
            (!strcmp(argv[1], "--plain-process") && strcmp(argv[2], "I") && strcmp(argv[2], "II"))) {
            fprintf(stderr, "bench-gomboc: %s%s: %s\n%s", argv[1], words < 0 ? "" : " ...",
                    words < 0 ? "not an option of this program" : "wrong words after the option", usage);
            return 2;
        }
    } else if (argc > 4) {
        fprintf(stderr, "bench-gomboc: %d words given (allowed: at most FILE NATIVE GOMBOC)\n%s", argc - 1, usage);
        return 2;
    }
    gb_error_init_gsl();
    if (argc > 1 && !strcmp(argv[1], "--plain-only")) return plain_only();
    if (argc > 1 && !strcmp(argv[1], "--work-precision")) /* that section alone, for development */
        return bench_work_precision(getenv("PYTHON") ? getenv("PYTHON") : "python3") ? 1 : 0;
    if (argc > 3 && !strcmp(argv[1], "--whole-process")) /* that section alone, for development */
        return bench_whole_process(argv[2], argv[3], NULL) ? 1 : 0;
    if (argc > 2 && !strcmp(argv[1], "--unilateral-maps")) /* that section alone, for development */
        return bench_unilateral_maps(argv[2], NULL) ? 1 : 0;
    if (argc > 2 && !strcmp(argv[1], "--certified")) { /* that section alone, for development: NATIVE */
        run_native(argv[2]);
        return bench_atlas() ? 1 : 0;
    }
    if (argc > 2 && !strcmp(argv[1], "--shared-atlas")) /* that section alone, for development */
        return bench_shared_atlas_cpu(argv[2], NULL) ? 1 : 0;
    if (argc > 1 && !strcmp(argv[1], "--unilateral")) { /* that section alone, for development */
        bench_unilateral();
        return 0;
    }
    if (argc > 1 && !strcmp(argv[1], "--stepping")) { /* that section alone, for development */
        bench_stepping();
        return 0;
    }
    if (argc > 1 && !strcmp(argv[1], "--friction")) { /* that section alone, for development */
        bench_friction();
        return 0;
    }
    if (argc > 2 && !strcmp(argv[1], "--plain-process")) return plain_process(argv[2]);
    if (argc > 1) {
        snprintf(tmp, sizeof tmp, "%s.tmp", argv[1]);
        record = fopen(tmp, "w");
        if (!record) {
            fprintf(stderr, "bench-gomboc: cannot write '%s' (allowed: FILE in an existing, writable directory)\n", tmp);
            return 2;
        }
        fputs("[\n", record);
    }
    if (argc > 2) run_native(argv[2]);
    static double zb[VERTICALS][3];
    static size_t brute_index[VERTICALS], fast_index[VERTICALS];
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 20261122UL);
    for (int k = 0; k < VERTICALS; k++) gsl_ran_dir_3d(rng, &zb[k][0], &zb[k][1], &zb[k][2]);
    gsl_rng_free(rng);
    static const size_t sizes[] = {90, 180, 360, 720};
    int mismatches = 0;
    printf("bench: contact selection, %d seeded verticals, best of %d passes, beta = 0.12\n\n", VERTICALS, REPEATS);
    printf("%-4s %-10s %14s %14s %10s %16s\n", "body", "grid", "brute [us]", "fast [us]", "speed-up", "nodes visited");
    for (int m = 0; m < 2; m++) {
        gb_surface s;
        gb_surface_init(&s, m ? "II" : "I", 0.12);
        for (size_t q = 0; q < sizeof sizes / sizeof sizes[0]; q++) {
            gb_contact_grid_def def = gb_contact_grid_default_def();
            def.n_phi = sizes[q];
            def.n_theta = 2 * sizes[q];
            gb_contact_grid *g;
            if (gb_contact_grid_create(&s, &def, &g)) {
                fprintf(stderr, "bench: %s\n", gb_error_message());
                return 1;
            }
            const double brute = time_search(g, zb, gb_contact_grid_brute, brute_index);
            const double fast = time_search(g, zb, gb_contact_grid_fast, fast_index);
            double visited = 0;
            for (int k = 0; k < VERTICALS; k++) {
                gb_contact_node n;
                gb_contact_grid_fast(g, zb[k], &n);
                visited += (double)n.visited / VERTICALS;
                mismatches += brute_index[k] != fast_index[k];
            }
            printf("%-4s %4zux%-5zu %14.2f %14.2f %9.1fx %9.0f (%.2f %%)\n", m ? "II" : "I", def.n_phi, def.n_theta,
                   brute * 1e6, fast * 1e6, brute / fast, visited, 100.0 * visited / (double)gb_contact_grid_size(g));
            gb_contact_grid_free(g);
        }
    }
    printf("\n%-4s %28s %30s\n", "body", "all branches (180x360) [us]", "Newton from 90x180 fast node [us]");
    for (int m = 0; m < 2; m++) {
        gb_surface s;
        gb_surface_init(&s, m ? "II" : "I", 0.12);
        gb_contact_grid_def seed_def = gb_contact_default_branch_grid(), table1 = gb_contact_grid_default_def();
        gb_contact_grid *seeds, *grid;
        gb_contact_grid_create(&s, &seed_def, &seeds);
        gb_contact_grid_create(&s, &table1, &grid);
        gb_contact_refine_def refine = gb_contact_refine_default_def();
        double all = 1e300, polish = 1e300;
        for (int r = 0; r < REPEATS; r++) {
            double start = now();
            for (int k = 0; k < VERTICALS; k++) {
                gb_contact_branches b;
                gb_contact_branches_find(seeds, zb[k], &refine, &b);
            }
            const double t_all = (now() - start) / VERTICALS;
            start = now();
            for (int k = 0; k < VERTICALS; k++) {
                gb_contact_node n;
                gb_contact_point p;
                gb_contact_grid_fast(grid, zb[k], &n);
                gb_contact_refine(&s, zb[k], n.phi, n.theta, &refine, &p);
            }
            const double t_polish = (now() - start) / VERTICALS;
            if (t_all < all) all = t_all;
            if (t_polish < polish) polish = t_polish;
        }
        printf("%-4s %28.2f %30.2f\n", m ? "II" : "I", all * 1e6, polish * 1e6);
        gb_contact_grid_free(seeds);
        gb_contact_grid_free(grid);
    }
    if (mismatches) {
        fprintf(stderr, "bench: %d fast-grid nodes differ from brute force\n", mismatches);
        return 1;
    }
    int failures = bench_dynamics();
    failures += bench_atlas();
    bench_unilateral();
    bench_flight();
    bench_friction();
    bench_stepping();
    bench_headroom();
    failures += bench_melnikov();
    failures += bench_work_precision(getenv("PYTHON") ? getenv("PYTHON") : "python3");
    if (argc > 3) failures += bench_whole_process(argv[2], argv[3], record);
    if (argc > 3) failures += bench_scans(argv[3], record);
    if (argc > 3) failures += bench_unilateral_maps(argv[3], record);
    if (argc > 3) failures += bench_shared_atlas_cpu(argv[3], record);
    if (record) {
        fputs("\n]\n", record);
        if (fclose(record) == 0 && !failures) rename(tmp, argv[1]);
        else remove(tmp);
    }
    return failures ? 1 : 0;
}
