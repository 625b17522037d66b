/* make bench: Table 1 runs against the plain loop and its native build (the fast grid, certified continuous
 * contact, λ beside a run), and the atlas of verticals. */
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
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <stdint.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* The native baseline's seconds, state hashes, node mismatches and the library loop's seconds in the
 * same build; 0 seconds when it could not be run. */
double native_seconds[2], native_library_seconds[2], native_setup[2];
static unsigned long long native_hash[2];
static size_t native_mismatches[2];

const char *native_path = NULL;

/* One whole plain run of body `name` in the native build's own process (--plain-process): its run's and its set-up's
 * seconds, as that process timed them. 0 when it could not be run. */
static int native_once(const char *name, double *run, double *setup)
{
    if (!native_path) return 0;
    char command[1200];
    snprintf(command, sizeof command, "'%s' --plain-process %s", native_path, name);
    FILE *p = popen(command, "r");
    if (!p) return 0;
    unsigned long long h;
    const int got = fscanf(p, "%llx %lf %lf", &h, run, setup) == 3;
    return pclose(p) == 0 && got;
}

int bench_compare_doubles(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void run_native(const char *path)
{
    native_path = path;
    char command[1200];
    snprintf(command, sizeof command, "'%s' --plain-only", path);
    FILE *p = popen(command, "r");
    if (!p) return;
    char body[8];
    double t, library, setup;
    unsigned long long h;
    size_t sw, mismatches;
    while (fscanf(p, "%7s %lf %llx %zu %zu %lf %lf", body, &t, &h, &sw, &mismatches, &library, &setup) == 7) {
        const int m = !strcmp(body, "II");
        native_seconds[m] = t, native_hash[m] = h, native_mismatches[m] = mismatches, native_library_seconds[m] = library;
        native_setup[m] = setup;
    }
    pclose(p);
}

int bench_dynamics(void)
{
    int failures = 0;
    printf(
        "\nbench: Table 1 runs (300 periods, RK4, 160 steps/period = 192000 contact queries), best of 2\n"
        "baseline: the best plain loop (verify/bench/plain.c, its own translation unit) with the library around it,\n"
        "all built with -O3 -march=native and run beside this build; then the library's own loop over every node\n"
        "in that build and in this build (the shipped flags); the fast grid and the certified continuous contact of "
        "this build\n\n");
    printf("%-4s %12s %14s %14s %12s %11s %9s %22s %9s\n", "body", "plain [s]", "lib native [s]", "library [s]",
           "fast grid [s]", "nodes/query", "speed-up", "continuous rolling [s]", "speed-up");
    for (int m = 0; m < 2; m++) {
        const char *name = m ? "II" : "I";
        double y_plain[GB_STATE_SIZE], y_fast[GB_STATE_SIZE], y_cont[GB_STATE_SIZE];
        size_t s_plain, s_fast, s_cont;
        const double plain = time_run(name, GB_CONTACT_MODEL_GRID, GB_VARIANT_PAPER, 2, y_plain, &s_plain);
        plain_seconds[m] = plain;
        const double fast = time_run(name, GB_CONTACT_MODEL_FAST_GRID, GB_VARIANT_PAPER, 2, y_fast, &s_fast);
        const double nodes = last_queries ? (double)last_nodes / (double)last_queries : NAN, fast_setup = last_setup;
        const double cont = time_run(name, GB_CONTACT_MODEL_CONTINUOUS, GB_VARIANT_ROLLING, 2, y_cont, &s_cont);
        const double cont_setup = last_setup;
        const int same = s_plain == s_fast && memcmp(y_plain, y_fast, sizeof y_plain) == 0;
        const gb_certify_stats cs = last_certificate;
        const int native = native_seconds[m] > 0.0;
        const double base = native ? native_seconds[m] : plain;
        const int native_same = native && native_hash[m] == state_hash(y_plain) && native_mismatches[m] == 0;
        failures += !same || (native && !native_same);
        printf("%-4s %12.3f %14.3f %14.3f %12.3f %11.1f %8.1fx %22.3f %8.1fx\n", name, native_seconds[m],
               native_library_seconds[m], plain, fast, nodes, base / fast, cont, base / cont);
        printf("     set-up (body, grid, tracker's hull or certificate) [s]: plain %.3f, fast grid %.3f, continuous %.3f; "
               "speed-ups with it: fast grid %.1fx, continuous %.1fx\n", native_setup[m], fast_setup, cont_setup,
               (base + native_setup[m]) / (fast + fast_setup), (base + native_setup[m]) / (cont + cont_setup));
        printf("     %s; %s\n",
               same ? "fast run identical to the library's loop (state bits, index changes)" : "FAST RUN DIFFERS",
               !native ? "NO NATIVE BASELINE (the ratios are against the library loop of this build)"
               : native_same
                   ? "the plain loop returns brute force's node on 10^4 seeded verticals and reaches the same state"
                   : "THE PLAIN LOOP'S NODES OR STATE DIFFER");
        printf("     continuous: %zu certificate checks: %zu global, %zu lower minimum found (switches), %zu undecided; "
               "%.1f boxes tested and %.2f Newton solves per check, %zu basins, %zu boxes kept\n",
               cs.checks, cs.global, cs.lower_found, cs.undecided, (double)cs.boxes_tested / (double)cs.checks,
               (double)cs.newton_runs / (double)cs.checks, cs.basins_built, cs.boxes_kept);
        if (record)
            fprintf(record, "%s{\"body\": \"%s\", \"baseline_seconds\": %.6f, \"baseline_same_state\": %s, "
                            "\"baseline_node_mismatches\": %zu, \"library_native_seconds\": %.6f, "
                            "\"plain_seconds\": %.6f, \"fast_seconds\": %.6f, \"fast_nodes_per_query\": %.3f, "
                            "\"baseline_setup_seconds\": %.6f, \"fast_setup_seconds\": %.6f, \"continuous_setup_seconds\": %.6f, "
                            "\"continuous_seconds\": %.6f, "
                            "\"fast_identical\": %s, \"certificate_checks\": %zu, \"certificate_global\": %zu, "
                            "\"certificate_lower_found\": %zu, \"certificate_undecided\": %zu, \"certificate_boxes_per_check\": %.2f}",
                    m ? ",\n  " : "  ", name, native_seconds[m], native_same ? "true" : "false", native_mismatches[m],
                    native_library_seconds[m], plain, fast, nodes, native_setup[m], fast_setup, cont_setup, cont, same ? "true" : "false", cs.checks, cs.global,
                    cs.lower_found, cs.undecided, (double)cs.boxes_tested / (double)cs.checks);
    }
    printf("\ntargets (issue 20): fast grid >= 20x and continuous (certified global at every step) >= 20x the plain loop\n");

    printf("\nbench: lambda_max over the same 300 periods (pair estimator, eq 77) against one run, best of 2\n"
           "(one run timed again here, beside the lambda run, in the same binary)\n\n");
    printf("%-4s %-22s %12s %14s %8s %10s\n", "body", "model", "one run [s]", "lambda run [s]", "ratio", "lambda");
    for (int m = 0; m < 2; m++) {
        const char *name = m ? "II" : "I";
        static const gb_contact_model contacts[3] = {GB_CONTACT_MODEL_FAST_GRID, GB_CONTACT_MODEL_CONTINUOUS,
                                                     GB_CONTACT_MODEL_CONTINUOUS};
        static const gb_dynamics_variant variants[3] = {GB_VARIANT_PAPER, GB_VARIANT_ROLLING, GB_VARIANT_ROLLING};
        static const char *const labels[3] = {"fast grid (paper)", "continuous rolling", "continuous, atlas file"};
        static const char *const models[3] = {"fast-grid", "continuous", "continuous with the atlas from its file"};
        char path[64];
        snprintf(path, sizeof path, "/tmp/gomboc-bench-lambda-%ld.atlas", (long)getpid());
        for (int k = 0; k < 3; k++) {
            double y_run[GB_STATE_SIZE], y_pair[GB_STATE_SIZE], lambda;
            size_t switches;
            if (k == 2) {
                /* the atlas file of this body, written by one untimed run */
                run_certificate = GB_CERTIFICATE_ATLAS, run_atlas_file = path;
                remove(path);
                time_run(name, contacts[k], variants[k], 1, y_run, &switches);
            }
            const double one = time_run(name, contacts[k], variants[k], 2, y_run, &switches);
            const double pair = time_lyapunov(name, contacts[k], variants[k], 2, y_pair, &lambda);
            run_certificate = GB_CERTIFICATE_PER_VERTICAL, run_atlas_file = NULL;
            if (k == 2) remove(path);
            const int same = memcmp(y_run, y_pair, sizeof y_run) == 0;
            failures += !same;
            printf("%-4s %-22s %12.3f %14.3f %7.2fx %10.4f   %s\n", name, labels[k], one, pair, pair / one, lambda,
                   same ? "reference = the run (state bits)" : "REFERENCE DIFFERS FROM THE RUN");
            if (record)
                fprintf(record, ",\n  {\"body\": \"%s\", \"lambda_model\": \"%s\", \"run_seconds\": %.6f, "
                                "\"lambda_seconds\": %.6f, \"reference_identical\": %s}",
                        name, models[k], one, pair, same ? "true" : "false");
        }
    }
    printf("\ntarget (issue 5): lambda over 300 periods <= 2.2x one run of the same scene\n");
    return failures;
}

/* ---------------------------------------------------------------- the atlas of verticals
 *
 * Certified continuous contact three ways on the Table 1 rolling runs: per vertical (gb_certify at every
 * step), with the atlas built during the run (no file), and with the atlas loaded from the file the
 * previous run wrote. The three must end in the same state bits. */
int bench_atlas(void)
{
    int failures = 0;
    printf("\nbench: certified continuous contact (Table 1 rolling, 300 periods, RK4 160/T), best of 2: per vertical,\n"
           "with the atlas of verticals built in the run, and with the atlas loaded from its file (load in the set-up)\n\n");
    printf("%-4s %14s %8s %16s %8s %9s %15s %8s %11s %7s %6s %8s %9s\n", "body", "per-vertical [s]", "speed-up",
           "atlas built [s]", "speed-up", "build [s]", "atlas file [s]", "speed-up", "load [s]", "cells", "2-site",
           "MiB", "fallback");
    char path[64];
    snprintf(path, sizeof path, "/tmp/gomboc-bench-%ld.atlas", (long)getpid());
    for (int m = 0; m < 2; m++) {
        const char *name = m ? "II" : "I";
        double y[3][GB_STATE_SIZE];
        size_t switches[3];
        const double base = native_seconds[m] > 0.0 ? native_seconds[m] : plain_seconds[m];
        run_certificate = GB_CERTIFICATE_PER_VERTICAL, run_atlas_file = NULL;
        const double per = time_run(name, GB_CONTACT_MODEL_CONTINUOUS, GB_VARIANT_ROLLING, 2, y[0], &switches[0]);
        run_certificate = GB_CERTIFICATE_ATLAS;
        const double built = time_run(name, GB_CONTACT_MODEL_CONTINUOUS, GB_VARIANT_ROLLING, 2, y[1], &switches[1]);
        const gb_atlas_stats as = last_atlas;
        const size_t fallbacks = last_atlas_fallbacks;
        remove(path);
        run_atlas_file = path;
        size_t ignored;
        double y_write[GB_STATE_SIZE];
        time_run(name, GB_CONTACT_MODEL_CONTINUOUS, GB_VARIANT_ROLLING, 1, y_write, &ignored); /* writes the file */
        const double cached = time_run(name, GB_CONTACT_MODEL_CONTINUOUS, GB_VARIANT_ROLLING, 2, y[2], &switches[2]);
        const double load = last_setup;
        const int loaded = last_atlas_loaded;
        const size_t cached_fallbacks = last_atlas_fallbacks;
        run_certificate = GB_CERTIFICATE_PER_VERTICAL, run_atlas_file = NULL;
        remove(path);
        const int same = memcmp(y[1], y[0], sizeof y[0]) == 0 && memcmp(y[2], y[0], sizeof y[0]) == 0 &&
                         switches[1] == switches[0] && switches[2] == switches[0] && loaded;
        failures += !same;
        printf("%-4s %14.3f %7.1fx %16.3f %7.1fx %9.3f %15.3f %7.1fx %11.3f %7zu %6zu %8.1f %9zu\n", name, per, base / per,
               built, base / built, as.build_seconds, cached, base / cached, load, as.cells, as.two_site_cells,
               (double)as.bytes / 1048576.0, cached_fallbacks);
        printf("     %s; atlas: %zu of %zu checks answered, %zu left to the per-vertical certificate, %zu Newton solves "
               "for other sites; deepest level %d, %zu cells without a certificate, %zu surface boxes\n",
               same ? "the three runs end in the same state bits" : "THE RUNS DIFFER", as.answered, as.checks, fallbacks,
               as.newton_runs, as.deepest_level, as.cells_failed, as.boxes);
        /* paired, set-up included: the plain loop's whole run (its own process) then the atlas-file run, PAIRS times;
         * the median of the ratios, since the two workloads drift apart on a shared machine (the plain loop is
         * memory-bound). The atlas run is a later run of the body, as a user's is: its atlas from the file and its
         * mass properties from a cache directory, both written by the run before the pairs. */
        enum { PAIRS = 15 };
        double ratio[PAIRS];
        int pairs = 0;
        char cache[] = "/tmp/gomboc-bench-cache-XXXXXX";
        run_cache_dir = mkdtemp(cache);
        run_certificate = GB_CERTIFICATE_ATLAS, run_atlas_file = path;
        time_run(name, GB_CONTACT_MODEL_CONTINUOUS, GB_VARIANT_ROLLING, 1, y_write, &ignored); /* writes both */
        for (int k = 0; k < PAIRS; k++) {
            double plain_run, plain_setup;
            if (!native_once(name, &plain_run, &plain_setup)) break;
            const double atlas_run = time_run(name, GB_CONTACT_MODEL_CONTINUOUS, GB_VARIANT_ROLLING, 1, y_write, &ignored);
            ratio[pairs++] = (plain_run + plain_setup) / (atlas_run + last_setup);
        }
        run_certificate = GB_CERTIFICATE_PER_VERTICAL, run_atlas_file = NULL;
        remove(path);
        if (run_cache_dir) bench_remove_tree(run_cache_dir), run_cache_dir = NULL;
        double median = NAN;
        if (pairs) {
            qsort(ratio, (size_t)pairs, sizeof *ratio, bench_compare_doubles);
            median = ratio[pairs / 2];
            printf("     atlas file against the plain loop, set-up included, %d pairs (the plain loop in its own process, "
                   "then the atlas run, its atlas and mass properties read): median %.1fx (%.1fx to %.1fx)\n", pairs, median, ratio[0], ratio[pairs - 1]);
        }
        if (record)
            fprintf(record, ",\n  {\"body\": \"%s\", \"atlas_per_vertical_seconds\": %.6f, \"atlas_built_seconds\": %.6f, "
                            "\"atlas_build_seconds\": %.6f, \"atlas_cached_seconds\": %.6f, \"atlas_load_seconds\": %.6f, "
                            "\"atlas_cells\": %zu, \"atlas_two_site_cells\": %zu, \"atlas_bytes\": %zu, "
                            "\"atlas_checks\": %zu, \"atlas_answered\": %zu, \"atlas_fallbacks\": %zu, "
                            "\"atlas_cached_fallbacks\": %zu, \"atlas_identical\": %s, \"atlas_paired_whole_ratio\": %.3f}",
                    name, per, built, as.build_seconds, cached, load, as.cells, as.two_site_cells, as.bytes, as.checks,
                    as.answered, fallbacks, cached_fallbacks, same ? "true" : "false", median);
    }
    printf("\ntargets: certified continuous contact >= 20x the plain loop (issue 20); the atlas file's paired whole run "
           ">= 25x (issue 57)\n");
    return failures;
}
