/* Section 8.2: ensembles and the chaos in a record: random initial attitudes (seeded, uniform on the rotations),
 * the lifetime of the chaos in windows of a record, and windowed exponents against known records and gomboc
 * run's windows file. The binary comes from $GOMBOC_BIN. */
#include "gb_check.h"
#include "gb_error.h"
#include "gb_run.h"
#include "gb_scan_internal.h"
#include "gb_seal.h"
#include "s8_scan.h"
#include "verify_sections.h"

#include <cjson/cJSON.h>
#include <dirent.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

/* The random axis: the k-th attitude depends only on (seed, k), and the draws are uniform on the
 * rotations: the rotation angle θ of a uniform rotation has the density (1 − cos θ)/π on [0, π], so its
 * mean is π/2 + 2/π. */
static void test_random_attitudes(void)
{
    enum { DRAWS = 4096 };
    double sum = 0.0, sum2 = 0.0;
    int same = 1;
    for (size_t k = 0; k < DRAWS; k++) {
        char a[160], b[160];
        gb_scan_random_attitude(20261123ul, k, a, sizeof a);
        gb_scan_random_attitude(20261123ul, k, b, sizeof b);
        same = same && !strcmp(a, b);
        double x, y, z, angle;
        if (sscanf(a, "axis-angle %lf,%lf,%lf,%lf", &x, &y, &z, &angle) != 4) angle = NAN;
        sum += angle, sum2 += angle * angle;
    }
    const double mean = sum / DRAWS, sd = sqrt(fmax(0.0, sum2 / DRAWS - mean * mean));
    gb_check cd = {"8.3", "-", "random attitudes: the same (seed, k), the same text", "determinism", "exact"};
    gb_check_true(&cd, same, "%s", same ? "4096 draws repeated identically" : "a draw differs");
    gb_check cm = {"8.3", "-", "random attitudes: mean rotation angle of 4096 draws", "pi/2 + 2/pi (uniform on SO(3))",
                   "4 standard errors of the mean (sd / sqrt 4096)"};
    gb_check_close(&cm, mean, M_PI / 2 + 2 / M_PI, 0.0, 4.0 * sd / sqrt((double)DRAWS));
}

/* The lifetime of the chaos on records whose answer is known: 12 windows of 25 intervals. */
static void test_chaos_lifetime(void)
{
    enum { N = 300 };
    double record[N];
    gb_check c = {"8.2", "77", "chaos lifetime of synthetic records (12 windows of 25 intervals, 2 periods an interval)",
                  "chaotic for 5 windows: 250 periods; for all 12: +inf; never: 0; a record of 200: too short (NaN)", "exact"};
    for (int k = 0; k < N; k++) record[k] = k < 5 * 25 ? 0.4 + 0.3 * sin(k) : 0.01 * sin(k); /* 5 chaotic windows */
    const double five = gb_scan_chaos_lifetime(record, N, 2.0);
    for (int k = 0; k < N; k++) record[k] = 0.2;
    const double all = gb_scan_chaos_lifetime(record, N, 2.0);
    for (int k = 0; k < N; k++) record[k] = k % 2 ? 0.04 : -0.04;
    const double none = gb_scan_chaos_lifetime(record, N, 2.0);
    const double short_record = gb_scan_chaos_lifetime(record, 200, 2.0);
    /* chaos that pauses and returns counts to its last window */
    for (int k = 0; k < N; k++) record[k] = (k < 50 || (k >= 200 && k < 225)) ? 0.3 : 0.0;
    const double returning = gb_scan_chaos_lifetime(record, N, 2.0);
    gb_check_true(&c, five == 250.0 && isinf(all) && all > 0 && none == 0.0 && isnan(short_record) && returning == 450.0,
                  "%g, %g, %g, %g, %g (returning chaos to window 9: 450)", five, all, none, short_record, returning);
}

/* Windowed exponents: a record whose window means are known (each window a constant plus a zero-sum
 * oscillation), and `gomboc run`'s windows file against the means of its own λ record (lyapunov.csv,
 * 12 significant digits), recomputed here. */
static void test_windowed_exponents(void)
{
    enum { N = 230, PER = 40 };
    double record[N], mean[N];
    for (int k = 0; k < N; k++) record[k] = 0.1 * (k / PER) + (k % 2 ? 0.25 : -0.25);
    const size_t count = gb_lyapunov_windows(record, N, PER, mean);
    double worst = 0.0;
    for (size_t w = 0; w < count; w++) worst = fmax(worst, fabs(mean[w] - 0.1 * (double)w));
    gb_check ck = {"8.2", "77", "windowed exponents of a record of 230 intervals in windows of 40: count and worst error",
                   "5 windows (the incomplete sixth left out), means 0, 0.1, ..., 0.4 (closed form)",
                   "4e-16: a sum of 40 terms of size 0.4 in double precision"};
    gb_check_true(&ck, count == 5 && gb_lyapunov_windows(record, N, 0, mean) == 0 &&
                  gb_lyapunov_windows(record, 10, PER, mean) == 0, "%zu windows", count);
    gb_check_close(&ck, worst, 0.0, 0.0, 4e-16);

    s8_scan_dir d;
    char out[1 << 14], text[8192], scene[200], args[600], path[200];
    gb_check cr = {"8.2", "77", "gomboc run's windowed exponents (40 periods, 5 windows of 8) against its own lambda record",
                   "the means of lambda_inst in NAME-lyapunov.csv, recomputed",
                   "1e-11 of the largest |lambda_inst|: the record is printed with 12 significant digits"};
    if (s8_make_scan_dir(&d, &cr)) return;
    s8_scene_text(text, sizeof text, 18.0, 1.0, 40.0, 0, 0);
    strncat(text, "window_periods = 8\n", sizeof text - strlen(text) - 1);
    snprintf(scene, sizeof scene, "%s/windows.ini", d.path);
    snprintf(args, sizeof args, "run '%s' --out '%s'", scene, d.path);
    const int code = s8_spill(scene, text) ? -1 : s8_run(args, out, sizeof out);
    double inst[40], largest = 0.0, windows[5], error = NAN;
    size_t got = 0, rows = 0;
    snprintf(path, sizeof path, "%s/windows-lyapunov.csv", d.path);
    FILE *f = fopen(path, "r");
    char line[512];
    if (f && fgets(line, sizeof line, f))
        while (rows < 40 && fgets(line, sizeof line, f) && sscanf(line, "%*d,%*d,%lf", &inst[rows]) == 1)
            largest = fmax(largest, fabs(inst[rows++]));
    if (f) fclose(f);
    snprintf(path, sizeof path, "%s/windows-lyapunov-windows.csv", d.path);
    f = fopen(path, "r");
    if (f && fgets(line, sizeof line, f))
        while (got < 5 && fgets(line, sizeof line, f) && sscanf(line, "%*d,%*d,%*d,%lf", &windows[got]) == 1) got++;
    if (f) fclose(f);
    if (code == 0 && rows == 40 && got == 5) {
        error = 0.0;
        for (size_t w = 0; w < 5; w++) {
            double sum = 0.0;
            for (size_t k = 8 * w; k < 8 * (w + 1); k++) sum += inst[k];
            error = fmax(error, fabs(windows[w] - sum / 8.0));
        }
    }
    gb_check_close(&cr, error, 0.0, 0.0, 1e-11 * largest);
    s8_remove_scan_dir(&d);
}

int verify_register_s8_ensembles(void)
{
    static const verify_test tests[] = {
        {"ensembles: random initial attitudes, seeded and uniform on the rotations", test_random_attitudes, NULL},
        {"ensembles: the lifetime of the chaos in a record", test_chaos_lifetime, NULL},
        {"windowed exponents: known records, and gomboc run's windows file", test_windowed_exponents, NULL},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Section 8.2: ensembles, and the chaos in a record", tests);
}
