/* make bench: what a user waits for, whole processes: `gomboc run` against the plain loop's process, scans, the
 * unilateral maps. */
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
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

/* Best of `repeats` wall seconds of a shell command (its output discarded); INFINITY if it fails. */
static double time_command(const char *command, int repeats)
{
    double best = INFINITY;
    for (int r = 0; r < repeats; r++) {
        const double start = now();
        if (system(command) != 0) return INFINITY;
        best = fmin(best, now() - start);
    }
    return best;
}

/* What a user waits for: the whole `gomboc run` process of Table 1 with the paper's model and the fast grid
 * (the trajectory and its summary, no history or diagnostics) against the plain loop's whole process (built
 * with -O3 -march=native), both timed from outside, best of 3: the first run of a body (Qhull builds the
 * hull and --hull writes it) and every run after it (--hull reads it); and the command's start-up, the
 * whole process of a one-period run with the hull read. */
int bench_whole_process(const char *native, const char *gomboc, FILE *out)
{
    char dir[] = "/tmp/gomboc-bench-XXXXXX";
    if (!mkdtemp(dir)) return 1;
    printf("\nbench: whole processes, Table 1, paper model (eq 44), fast grid 90x180, 300 periods, summary only; "
           "timed from outside, best of 3\n\n");
    printf("%-4s %16s %22s %10s %22s %10s %24s %14s\n", "body", "plain loop [s]", "gomboc run, Qhull [s]", "ratio",
           "gomboc run, --hull [s]", "ratio", "start-up (1 period) [s]", "the rest [s]");
    int failures = 0;
    for (int m = 0; m < 2; m++) {
        const char *name = m ? "II" : "I";
        char scene[2][256], command[2048];
        for (int k = 0; k < 2; k++) {
            snprintf(scene[k], sizeof scene[k], "%s/table1-%s-%d.ini", dir, name, k ? 300 : 1);
            FILE *f = fopen(scene[k], "w");
            if (!f) return 1;
            fprintf(f, "[body]\nmorphology = %s\nbeta = 0.12\n[forcing]\nA1 = 2.0\nA2 = 1.0\nomega = 18\npsi = pi/3\n"
                       "[model]\nequation = paper\ncontact = fast-grid\ngrid = 90x180\n[integrator]\nmethod = rk4\n"
                       "steps_per_period = 160\nperiods = %d\n[output]\nhistory = no\nsummary = yes\n", name, k ? 300 : 1);
            fclose(f);
        }
        snprintf(command, sizeof command, "'%s' --plain-process %s > /dev/null", native, name);
        const double plain = time_command(command, 3);
        snprintf(command, sizeof command, "'%s' run '%s' --out '%s' 2>/dev/null", gomboc, scene[1], dir);
        const double cold = time_command(command, 3);
        /* the hull file: written by the first run with --hull, read by the timed ones */
        snprintf(command, sizeof command, "'%s' run '%s' --out '%s' --hull '%s/%s.hull' 2>/dev/null", gomboc, scene[1], dir, dir,
                 name);
        const double whole = time_command(command, 1) < INFINITY ? time_command(command, 3) : INFINITY;
        snprintf(command, sizeof command, "'%s' run '%s' --out '%s' --hull '%s/%s.hull' 2>/dev/null", gomboc, scene[0], dir, dir,
                 name);
        const double start = time_command(command, 3);
        failures += !isfinite(plain) || !isfinite(cold) || !isfinite(whole) || !isfinite(start);
        printf("%-4s %16.3f %22.3f %9.1fx %22.3f %9.1fx %24.3f %14.3f\n", name, plain, cold, plain / cold, whole, plain / whole,
               start, whole - start);
        if (out)
            fprintf(out, ",\n  {\"whole_process_body\": \"%s\", \"plain_process_seconds\": %.6f, \"gomboc_cold_process_seconds\": %.6f, "
                         "\"cold_process_ratio\": %.4f, \"gomboc_process_seconds\": %.6f, \"process_ratio\": %.4f, "
                         "\"startup_process_seconds\": %.6f}",
                    name, plain, cold, plain / cold, whole, plain / whole, start);
    }
    printf("\n(target, issue 30: the whole gomboc run process >= 30x the plain loop's whole process; the hull built by "
           "Qhull or read from its file)\n");
    /* Where the start-up goes: the stages of a fast-grid run's set-up, each timed alone in this process (best
     * of 5), and the process that does nothing (gomboc --version) for the cost of starting one. */
    char command[2048];
    snprintf(command, sizeof command, "'%s' --version > /dev/null", gomboc);
    const double process = time_command(command, 5);
    printf("\nbench: the start-up of a fast-grid run by stage, best of 5 [ms] (a process that only prints its version: "
           "%.1f ms)\n\n", 1e3 * process);
    printf("%-4s %14s %18s %22s %20s %18s %16s\n", "body", "scene read", "mass properties", "grid nodes, patch tree",
           "hull (Qhull) + graph", "hull from its file", "first period");
    for (int m = 0; m < 2; m++) {
        const char *name = m ? "II" : "I";
        char scene_path[256], hull_path[256];
        snprintf(scene_path, sizeof scene_path, "%s/table1-%s-1.ini", dir, name);
        snprintf(hull_path, sizeof hull_path, "%s/%s.hull", dir, name);
        double best[6] = {INFINITY, INFINITY, INFINITY, INFINITY, INFINITY, INFINITY};
        for (int r = 0; r < 5; r++) {
            gb_case scene;
            gb_massprops props;
            gb_massprops_def mdef = gb_massprops_default_def();
            gb_contact_grid *grid = NULL;
            gb_contact_tracker *tracker = NULL;
            double t[7];
            t[0] = now();
            int status = gb_case_load(scene_path, &scene);
            t[1] = now();
            if (!status) status = gb_massprops_compute(&scene.body, &mdef, &props);
            t[2] = now();
            if (!status) status = gb_contact_grid_create(&scene.body, &scene.dynamics.grid, &grid);
            t[3] = now();
            if (!status) status = gb_contact_tracker_create(grid, &tracker);
            t[4] = now();
            gb_contact_tracker *loaded = NULL; /* the file the whole-process runs above wrote */
            const double load_start = now();
            if (!status) status = gb_contact_tracker_load(grid, hull_path, &loaded);
            best[5] = fmin(best[5], now() - load_start);
            gb_contact_tracker_free(loaded);
            gb_dynamics *d = NULL;
            gb_integrate_stats stats;
            double y[GB_STATE_SIZE];
            if (!status) status = gb_dynamics_start(&scene.body, &scene.dynamics, scene.attitude, scene.omega0, &d, y);
            t[5] = now();
            if (!status) status = gb_integrate_run(d, &scene.integrate, 0.0, y, NULL, NULL, &stats);
            t[6] = now();
            gb_dynamics_free(d);
            gb_contact_tracker_free(tracker);
            gb_contact_grid_free(grid);
            if (status) {
                fprintf(stderr, "bench: %s\n", gb_error_message());
                failures++;
                break;
            }
            for (int k = 0; k < 4; k++) best[k] = fmin(best[k], t[k + 1] - t[k]);
            best[4] = fmin(best[4], t[6] - t[5]); /* the period alone (gb_dynamics_start built the same again) */
        }
        const double first = best[4];
        printf("%-4s %14.2f %18.2f %22.2f %20.2f %18.2f %16.2f\n", name, 1e3 * best[0], 1e3 * best[1], 1e3 * best[2],
               1e3 * best[3], 1e3 * best[5], 1e3 * first);
        if (out)
            fprintf(out, ",\n  {\"startup_body\": \"%s\", \"process_ms\": %.3f, \"scene_ms\": %.3f, \"massprops_ms\": %.3f, "
                         "\"grid_ms\": %.3f, \"hull_ms\": %.3f, \"hull_file_ms\": %.3f, \"first_period_ms\": %.3f}",
                    name, 1e3 * process, 1e3 * best[0], 1e3 * best[1], 1e3 * best[2], 1e3 * best[3], 1e3 * best[5],
                    1e3 * first);
    }
    bench_remove_tree(dir);
    return failures;
}

/* Scans (section 8.3) through the command: points per second for each model on 1 and 2 threads, and the
 * parallel efficiency t1 / (2 t2), each the best of 2. The scan is 4 x 4 points of 50 periods around Table 1, lambda included;
 * the Melnikov margins apart (a scan of them alone: the reduced model once, the integrals at the 4 ω). */
int bench_scans(const char *gomboc, FILE *out)
{
    static const struct {
        const char *name, *scene, *metrics;
    } models[] = {{"paper model (fast grid)", "cases/table1-gomboc-I.ini", "omega_rms, switch_rate, strobe_sd, mean_height, monitors, lambda"},
                  {"rolling, certified continuous", "cases/table1-gomboc-I-rolling.ini", "omega_rms, switch_rate, strobe_sd, mean_height, monitors, lambda"},
                  {"Melnikov margins alone", "cases/table1-gomboc-I.ini", "melnikov"}};
    char dir[] = "/tmp/gomboc-bench-XXXXXX";
    if (!mkdtemp(dir)) return 1;
    printf("\nbench: scans through gomboc scan (4 x 4 points of 50 periods, omega and A1 around Table 1, lambda included; the margins alone apart; best of 2)\n\n");
    printf("%-32s %14s %14s %12s\n", "model", "1 thread [pt/s]", "2 threads [pt/s]", "efficiency");
    int failures = 0;
    for (size_t k = 0; k < sizeof models / sizeof models[0]; k++) {
        char base[4096], path[256], command[8192];
        if (!realpath(models[k].scene, base)) return 1;
        snprintf(path, sizeof path, "%s/bench.ini", dir);
        FILE *f = fopen(path, "w");
        if (!f) return 1;
        fprintf(f, "[scan]\nbase = %s\nperiods = 50\ntransient_periods = 10\nmetrics = %s\n"
                   "[x]\nkey = forcing.omega\nfrom = 16\nto = 20\ncount = 4\n[y]\nkey = forcing.A1\nfrom = 1.5\nto = 2.5\ncount = 4\n",
                base, models[k].metrics);
        fclose(f);
        double seconds[2] = {INFINITY, INFINITY};
        for (int repeat = 0; repeat < 2; repeat++) /* best of 2: the first run of each pays for a cold start */
            for (int threads = 1; threads <= 2; threads++) {
                snprintf(command, sizeof command, "'%s' scan '%s' --out '%s' --threads %d 2>/dev/null", gomboc, path, dir, threads);
                const double start = now();
                failures += system(command) != 0;
                seconds[threads - 1] = fmin(seconds[threads - 1], now() - start);
            }
        const double efficiency = seconds[0] / (2.0 * seconds[1]);
        printf("%-32s %14.2f %14.2f %11.0f%%\n", models[k].name, 16.0 / seconds[0], 16.0 / seconds[1], 100.0 * efficiency);
        if (out)
            fprintf(out, ",\n  {\"scan_model\": \"%s\", \"points_per_second_1\": %.4f, \"points_per_second_2\": %.4f, "
                         "\"parallel_efficiency\": %.4f}", models[k].name, 16.0 / seconds[0], 16.0 / seconds[1], efficiency);
    }
    /* A whole map of the paper's model, whose points cost 1/7 of what they did before each thread kept
     * its body's set-up (gb_dynamics_context): in the 4 x 4 scan above the threads' own set-up and the
     * process's start now weigh against 16 points of ~14 ms; here against 625 (once each: ~20 s). */
    double seconds[2] = {INFINITY, INFINITY};
    for (int threads = 1; threads <= 2; threads++) {
        char command[8192];
        snprintf(command, sizeof command, "'%s' scan cases/scans/fig12-gomboc-II-omega-A1-paper.ini --out '%s' --threads %d 2>/dev/null",
                 gomboc, dir, threads);
        const double start = now();
        failures += system(command) != 0;
        seconds[threads - 1] = now() - start;
    }
    const char *map = "paper model, the Fig 12 map (625 points of 100 periods, lambda included)";
    printf("%-32s %14.2f %14.2f %11.0f%%\n", "paper model, Fig 12 map (625)", 625.0 / seconds[0], 625.0 / seconds[1],
           100.0 * seconds[0] / (2.0 * seconds[1]));
    if (out)
        fprintf(out, ",\n  {\"scan_model\": \"%s\", \"points_per_second_1\": %.4f, \"points_per_second_2\": %.4f, "
                     "\"parallel_efficiency\": %.4f}", map, 625.0 / seconds[0], 625.0 / seconds[1], seconds[0] / (2.0 * seconds[1]));
    printf("\n(target, issue 19: parallel efficiency >= 90 %% on 2 threads)\n");
    bench_remove_tree(dir);
    return failures;
}

/* CPU seconds of the finished children so far (user + system). */
static double children_cpu(void)
{
    struct rusage u;
    getrusage(RUSAGE_CHILDREN, &u);
    return (double)u.ru_utime.tv_sec + 1e-6 * (double)u.ru_utime.tv_usec + (double)u.ru_stime.tv_sec + 1e-6 * (double)u.ru_stime.tv_usec;
}

/* A map whose points share an atlas of verticals (Fig 10 under the unilateral law, 6 x 6 points of 100 periods,
 * lambda included), each run cold in a new folder, on 1, 2 and 16 threads: its points per CPU-second and their
 * ratio to one thread's (issue 57: >= 0.9, no more than 10 % duplicated or waiting work). The threads share one
 * atlas, each cell proved once (gb_atlas.c, "sharing"): CPU time, unlike wall time, shows what more threads than
 * cores would cost in cells built again or in waiting. */
int bench_shared_atlas_cpu(const char *gomboc, FILE *out)
{
    char dir[] = "/tmp/gomboc-bench-XXXXXX";
    if (!mkdtemp(dir)) return 1;
    char base[4096], scan[300];
    if (!realpath("cases/table1-gomboc-I-unilateral.ini", base)) return 1;
    snprintf(scan, sizeof scan, "%s/atlas-map.ini", dir);
    FILE *f = fopen(scan, "w");
    if (!f) return 1;
    fprintf(f, "[scan]\nbase = %s\nperiods = 100\ntransient_periods = 20\nmetrics = all\natlas = shared\nfailed_points = record\n"
               "[x]\nkey = forcing.omega\nfrom = 12\nto = 24\ncount = 6\n[y]\nkey = forcing.A1\nfrom = 0\nto = 4\ncount = 6\n", base);
    fclose(f);
    printf("\nbench: a map sharing an atlas (Fig 10 unilateral, 6 x 6 points of 100 periods, lambda), cold, CPU of the whole process\n\n");
    printf("%8s %12s %12s %18s %14s\n", "threads", "CPU [s]", "wall [s]", "points / CPU-s", "ratio to 1");
    static const int threads[3] = {1, 2, 16};
    double rate1 = NAN;
    int failures = 0;
    for (int k = 0; k < 3; k++) {
        char out_dir[400], command[8192];
        snprintf(out_dir, sizeof out_dir, "%s/t%d", dir, threads[k]);
        snprintf(command, sizeof command, "mkdir -p '%s' && GOMBOC_CACHE=off '%s' scan '%s' --out '%s' --threads %d 2>/dev/null", out_dir,
                 gomboc, scan, out_dir, threads[k]);
        const double cpu0 = children_cpu(), start = now();
        failures += system(command) != 0;
        const double wall = now() - start, cpu = children_cpu() - cpu0, rate = 36.0 / cpu;
        if (k == 0) rate1 = rate;
        printf("%8d %12.2f %12.2f %18.2f %14.2f\n", threads[k], cpu, wall, rate, rate / rate1);
        if (out)
            fprintf(out, ",\n  {\"shared_atlas_map_threads\": %d, \"cpu_seconds\": %.3f, \"wall_seconds\": %.3f, \"points_per_cpu_second\": %.4f, "
                         "\"ratio_to_one_thread\": %.4f}", threads[k], cpu, wall, rate, rate / rate1);
    }
    printf("\n(target, issue 57: points per CPU-second at N threads >= 0.9 of one thread's)\n");
    bench_remove_tree(dir);
    return failures;
}

/* Every map under the unilateral law (cases/scans: NAME-unilateral, NAME-g-units-bouncing, NAME-grid-unilateral:
 * 625 points of 100 periods, lambda included) through gomboc scan on 2 threads, the shared atlas of each body
 * built by the first map of that body in this run; wall seconds against the target of issue 42, 300 s. */
int bench_unilateral_maps(const char *gomboc, FILE *out)
{
    static const char *const maps[] = {
        "fig10-gomboc-I-omega-A1-unilateral", "fig11-gomboc-I-A2-psi-unilateral", "fig12-gomboc-II-omega-A1-unilateral",
        "fig13-gomboc-II-A2-psi-unilateral", "fig10-gomboc-I-omega-A1-g-units-bouncing", "fig11-gomboc-I-A2-psi-g-units-bouncing",
        "fig12-gomboc-II-omega-A1-g-units-bouncing", "fig13-gomboc-II-A2-psi-g-units-bouncing",
        "fig10-gomboc-I-omega-A1-grid-unilateral", "fig12-gomboc-II-omega-A1-grid-unilateral"};
    char dir[] = "/tmp/gomboc-bench-XXXXXX";
    if (!mkdtemp(dir)) return 1;
    printf("\nbench: the maps under the unilateral law (625 points of 100 periods, lambda included), gomboc scan on 2 threads\n\n");
    printf("%-44s %12s %10s\n", "map", "wall [s]", "<= 300 s");
    int failures = 0;
    double worst = 0.0;
    for (size_t k = 0; k < sizeof maps / sizeof maps[0]; k++) {
        char command[8192];
        snprintf(command, sizeof command, "'%s' scan cases/scans/%s.ini --out '%s' --threads 2 2>/dev/null", gomboc, maps[k], dir);
        const double start = now();
        const int status = system(command);
        const double seconds = now() - start;
        failures += status != 0;
        worst = fmax(worst, seconds);
        printf("%-44s %12.1f %10s\n", maps[k], seconds, status ? "failed" : seconds <= 300.0 ? "met" : "NOT met");
        if (out) fprintf(out, ",\n  {\"unilateral_map\": \"%s\", \"wall_seconds\": %.3f}", maps[k], seconds);
    }
    printf("\ntarget (issue 42): every unilateral map <= 300 s on 2 cores; the slowest here %.1f s\n", worst);
    bench_remove_tree(dir);
    return failures;
}
