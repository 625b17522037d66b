/* Sections 4 and 8.3: one atlas of verticals for a whole scan: the points of a scan share the atlas through its
 * file (--atlas FILE, [scan] atlas = shared, atlas_file), with the per-vertical certificate's results bit for bit,
 * across threads, scans and runs at once. The binary comes from $GOMBOC_BIN. */
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

/* ---- one atlas of verticals for a whole scan ------------------------------------------------------- */

/* A rolling-model scan of 2 x 2 points with the per-vertical certificate, and the same with the atlas shared
 * through --atlas FILE (made by the first points, then loaded): the same CSV bytes, and the file written. */
/* Write the scan file DIR/NAME.ini with `text` and run `gomboc scan` on it into DIR with `options`: its exit. */
static int scan_file_run(const char *dir, const char *name, const char *text, const char *options, char *out, size_t size)
{
    char path[300], args[700];
    snprintf(path, sizeof path, "%s/%s.ini", dir, name);
    s8_spill(path, text);
    snprintf(args, sizeof args, "scan '%s' --out '%s'%s", path, dir, options);
    return s8_run(args, out, size);
}

static void test_scan_atlas(void)
{
    s8_scan_dir d;
    gb_check cs = {"4, 8.3", "29", "gomboc scan --atlas FILE: a rolling-model scan (2 x 2 points, 4 periods, continuous "
                   "contact) with one atlas of verticals for every point, made by the first points, then loaded",
                   "the CSV of the per-vertical certificate, byte for byte; the atlas file written", "exact"};
    if (gb_check_tempdir("scan", d.path, sizeof d.path)) return;
    static const char base[] = "[body]\nmorphology = I\nbeta = 0.12\n[forcing]\nA1 = 2.0\nA2 = 1.0\nomega = 18\npsi = pi/3\n"
                               "[model]\nequation = rolling\ncontact = continuous\ncertificate = %s\ndamping = 0.02\n"
                               "[integrator]\nmethod = rk4\nsteps_per_period = 160\nlocate_switches = yes\n";
    static const char scan[] = "[scan]\nbase = %s.ini\nperiods = 4\ntransient_periods = 1\nmetrics = omega_rms, switch_rate\n"
                               "[x]\nkey = forcing.omega\nfrom = 17\nto = 19\ncount = 2\n[y]\nkey = forcing.A1\nfrom = 1.5\nto = 2\n"
                               "count = 2\n";
    char text[1024], path[200], atlas[200], args[1024], out[1 << 14], *csv[3] = {NULL, NULL, NULL};
    int codes[3] = {-1, -1, -1};
    static const char *const names[2] = {"per-vertical", "atlas"};
    for (int k = 0; k < 2; k++) {
        snprintf(text, sizeof text, base, names[k]);
        snprintf(path, sizeof path, "%s/%s.ini", d.path, names[k]);
        s8_spill(path, text);
        snprintf(text, sizeof text, scan, names[k]);
        snprintf(path, sizeof path, "%s/scan-%s.ini", d.path, names[k]);
        s8_spill(path, text);
    }
    snprintf(atlas, sizeof atlas, "%s/shared.atlas", d.path);
    for (int k = 0; k < 3; k++) {
        const int shared = k > 0;
        snprintf(args, sizeof args, "scan '%s/scan-%s.ini' --out '%s' --threads 2%s%s%s", d.path, names[shared], d.path,
                 shared ? " --atlas '" : "", shared ? atlas : "", shared ? "'" : "");
        codes[k] = s8_run(args, out, sizeof out);
        snprintf(path, sizeof path, "%s/scan-%s-scan.csv", d.path, names[shared]);
        csv[k] = gb_check_read_file(path);
    }
    struct stat st;
    const int written = stat(atlas, &st) == 0 && st.st_size > 0;
    /* the CSVs differ only in nothing: the same axes, metrics and fingerprints */
    const int same = csv[0] && csv[1] && csv[2] && !strcmp(csv[0], csv[1]) && !strcmp(csv[0], csv[2]);
    gb_check_true(&cs, codes[0] == 0 && codes[1] == 0 && codes[2] == 0 && same && written,
                  "exits %d, %d, %d; CSVs %s; atlas file %s: %.200s", codes[0], codes[1], codes[2], same ? "equal" : "DIFFER",
                  written ? "written" : "MISSING", out);
    for (int k = 0; k < 3; k++) free(csv[k]);
    /* --atlas with a base scene that certifies per vertical: refused before any run, as gomboc run's */
    snprintf(args, sizeof args, "scan '%s/scan-per-vertical.ini' --out '%s' --atlas '%s/other.atlas'", d.path, d.path, d.path);
    const int refused = s8_run(args, out, sizeof out);
    snprintf(path, sizeof path, "%s/other.atlas", d.path);
    gb_check cr = {"8.3", "-", "gomboc scan --atlas FILE with a base scene whose certificate is per vertical",
                   "exit 2 naming --atlas, the base scene and the allowed value; no atlas written", "exact"};
    gb_check_true(&cr, refused == 2 && strstr(out, "--atlas") && strstr(out, "has no atlas") &&
                       strstr(out, "certificate = atlas") && stat(path, &st) != 0,
                  "exit %d: %.300s", refused, out);
    /* [scan] atlas = shared over the per-vertical base: the atlas beside the outputs, the same CSV */
    snprintf(text, sizeof text, "[scan]\nbase = per-vertical.ini\natlas = shared\nperiods = 4\ntransient_periods = 1\n"
             "metrics = omega_rms, switch_rate\n[x]\nkey = forcing.omega\nfrom = 17\nto = 19\ncount = 2\n[y]\n"
             "key = forcing.A1\nfrom = 1.5\nto = 2\ncount = 2\n");
    const int code = scan_file_run(d.path, "scan-shared", text, " --threads 2", out, sizeof out);
    snprintf(path, sizeof path, "%s/scan-per-vertical-scan.csv", d.path);
    char *reference = gb_check_read_file(path);
    snprintf(path, sizeof path, "%s/scan-shared-scan.csv", d.path);
    char *shared_csv = gb_check_read_file(path);
    snprintf(path, sizeof path, "%s/scan-shared-scan.atlas", d.path);
    const int own = stat(path, &st) == 0 && st.st_size > 0;
    gb_check ck = {"4, 8.3", "29", "[scan] atlas = shared over a base scene that certifies per vertical (2 x 2 points, 2 threads)",
                   "the per-vertical scan's CSV, byte for byte; NAME-scan.atlas written beside it", "exact"};
    const int equal = reference && shared_csv && !strcmp(reference, shared_csv);
    gb_check_true(&ck, code == 0 && equal && own, "exit %d; CSV %s; atlas %s: %.200s", code, equal ? "equal" : "DIFFERS",
                  own ? "written" : "MISSING", out);
    /* [scan] atlas_file: two scans name one atlas in the output directory (as the ensembles of one body do);
     * the second takes every cell from it (none proved: the file is not written again) */
    char named_path[2][512];
    struct stat named_st[2];
    int named_code[2], named_equal = 1;
    for (int k = 0; k < 2; k++) {
        snprintf(text, sizeof text, "[scan]\nbase = per-vertical.ini\natlas = shared\natlas_file = body.atlas\nperiods = 4\n"
                 "transient_periods = 1\nmetrics = omega_rms, switch_rate\n[x]\nkey = forcing.omega\nfrom = 17\nto = 19\n"
                 "count = 2\n[y]\nkey = forcing.A1\nfrom = 1.5\nto = 2\ncount = 2\n");
        named_code[k] = scan_file_run(d.path, k ? "named-again" : "named", text, k ? " --threads 1" : " --threads 2", out, sizeof out);
        snprintf(path, sizeof path, "%s/%s-scan.csv", d.path, k ? "named-again" : "named");
        char *csv = gb_check_read_file(path);
        named_equal &= reference && csv && !strcmp(reference, csv);
        free(csv);
        snprintf(named_path[k], sizeof named_path[k], "%s/body.atlas", d.path);
        if (stat(named_path[k], &named_st[k])) named_st[k].st_ino = 0, named_st[k].st_size = 0;
    }
    snprintf(path, sizeof path, "%s/named-scan.atlas", d.path);
    const int no_own = stat(path, &st) != 0;
    gb_check ca = {"4, 8.3", "29", "[scan] atlas_file = body.atlas in two scans (2 x 2 points each)",
                   "the per-vertical scan's CSV, byte for byte, twice; one atlas file, not written again by the second scan",
                   "exact"};
    const int kept = named_st[0].st_size > 0 && named_st[0].st_ino == named_st[1].st_ino &&
                     named_st[0].st_mtim.tv_sec == named_st[1].st_mtim.tv_sec &&
                     named_st[0].st_mtim.tv_nsec == named_st[1].st_mtim.tv_nsec;
    gb_check_true(&ca, named_code[0] == 0 && named_code[1] == 0 && named_equal && kept && no_own,
                  "exits %d, %d; CSVs %s; body.atlas %s (%lld bytes); NAME-scan.atlas %s", named_code[0], named_code[1],
                  named_equal ? "equal" : "DIFFER", kept ? "read, not rewritten" : "REWRITTEN OR MISSING",
                  (long long)named_st[0].st_size, no_own ? "not written" : "WRITTEN");
    /* ... a name with a directory, or without atlas = shared: refused before any run */
    snprintf(text, sizeof text, "[scan]\nbase = per-vertical.ini\natlas = shared\natlas_file = ../body.atlas\nperiods = 4\n"
             "transient_periods = 1\n[x]\nkey = forcing.omega\nfrom = 17\nto = 19\ncount = 2\n[y]\nkey = forcing.A1\nfrom = 1.5\n"
             "to = 2\ncount = 2\n");
    const int slash_code = scan_file_run(d.path, "named-slash", text, "", out, sizeof out);
    const int slash_named = strstr(out, "named-slash.ini:4: [scan] atlas_file = ../body.atlas: not a file name") != NULL;
    snprintf(text, sizeof text, "[scan]\nbase = per-vertical.ini\natlas_file = body.atlas\nperiods = 4\n"
             "transient_periods = 1\n[x]\nkey = forcing.omega\nfrom = 17\nto = 19\ncount = 2\n[y]\nkey = forcing.A1\nfrom = 1.5\n"
             "to = 2\ncount = 2\n");
    const int alone_code = scan_file_run(d.path, "named-alone", text, "", out, sizeof out);
    const int alone_named = strstr(out, "named-alone.ini:3: [scan] atlas_file = body.atlas without atlas = shared") != NULL;
    gb_check cb = {"8.3", "-", "[scan] atlas_file = ../body.atlas, and atlas_file without atlas = shared",
                   "exit 2 naming the file, line, key and what is allowed", "exact"};
    gb_check_true(&cb, slash_code == 2 && slash_named && alone_code == 2 && alone_named, "exits %d, %d: %.300s", slash_code,
                  alone_code, out);
    free(reference);
    free(shared_csv);
    /* 3 x 3 points on one thread: the thread's atlas is merged with the file and written back after its
     * 8th point and at its end (gomboc_scan.c), and the CSV is still the per-vertical one */
    static const char nine[] = "[scan]\nbase = per-vertical.ini\n%speriods = 4\ntransient_periods = 1\n"
                               "metrics = omega_rms, switch_rate\n[x]\nkey = forcing.omega\nfrom = 17\nto = 19\n"
                               "count = 3\n[y]\nkey = forcing.A1\nfrom = 1.5\nto = 2\ncount = 3\n";
    int nine_code[2];
    char *nine_csv[2];
    for (int k = 0; k < 2; k++) {
        snprintf(text, sizeof text, nine, k ? "atlas = shared\n" : "");
        nine_code[k] = scan_file_run(d.path, k ? "nine-shared" : "nine-per-vertical", text, " --threads 1", out, sizeof out);
        snprintf(path, sizeof path, "%s/%s-scan.csv", d.path, k ? "nine-shared" : "nine-per-vertical");
        nine_csv[k] = gb_check_read_file(path);
    }
    snprintf(path, sizeof path, "%s/nine-shared-scan.atlas", d.path);
    const int nine_atlas = stat(path, &st) == 0 && st.st_size > 0;
    gb_check cn = {"4, 8.3", "29", "[scan] atlas = shared, 3 x 3 points on one thread (its atlas kept in memory, merged with "
                   "the file after 8 points and at the end)", "the per-vertical scan's CSV, byte for byte; the atlas written",
                   "exact"};
    const int nine_equal = nine_csv[0] && nine_csv[1] && !strcmp(nine_csv[0], nine_csv[1]);
    gb_check_true(&cn, nine_code[0] == 0 && nine_code[1] == 0 && nine_equal && nine_atlas, "exits %d, %d; CSV %s; atlas %s",
                  nine_code[0], nine_code[1], nine_equal ? "equal" : "DIFFERS", nine_atlas ? "written" : "MISSING");
    free(nine_csv[0]);
    free(nine_csv[1]);
    /* ... and over a base without continuous contact: refused, naming the scan file's line */
    snprintf(path, sizeof path, "%s/grid.ini", d.path);
    s8_spill(path, "[body]\nmorphology = I\nbeta = 0.12\n[model]\ncontact = fast-grid\n");
    snprintf(text, sizeof text, "[scan]\nbase = grid.ini\nperiods = 4\ntransient_periods = 1\natlas = shared\n[x]\n"
             "key = forcing.omega\nfrom = 17\nto = 19\ncount = 2\n[y]\nkey = forcing.A1\nfrom = 1.5\nto = 2\ncount = 2\n");
    const int grid_code = scan_file_run(d.path, "scan-grid", text, "", out, sizeof out);
    snprintf(path, sizeof path, "%s/scan-grid-scan.csv", d.path);
    gb_check cg = {"8.3", "-", "[scan] atlas = shared with a base scene of fast-grid contact",
                   "exit 2 naming the scan file's line 5, the key and the allowed values; no output", "exact"};
    gb_check_true(&cg, grid_code == 2 && strstr(out, "scan-grid.ini:5: [scan] atlas = shared") && strstr(out, "allowed") &&
                       stat(path, &st) != 0,
                  "exit %d: %.300s", grid_code, out);
    /* Two scans of one atlas_file at once, 2 threads each, 3 times: then both again, one after the other,
     * prove nothing (the file is byte for byte what the two left): the merge kept every cell either proved,
     * where the two decomposed a cell differently too (a cell's fate depends on the verticals that first
     * needed it). */
    static const char racing[] = "[scan]\nbase = race-base.ini\natlas = shared\natlas_file = race.atlas\nperiods = 12\n"
                                 "transient_periods = 1\nmetrics = omega_rms\n[x]\nkey = forcing.omega\nfrom = %s\nto = %s\n"
                                 "count = 4\n[y]\nkey = forcing.A1\nfrom = 1.5\nto = 2.5\ncount = 2\n";
    snprintf(path, sizeof path, "%s/race-base.ini", d.path);
    s8_spill(path, "[model]\nequation = rolling\ncontact = continuous\n[integrator]\nperiods = 12\nlocate_switches = yes\n");
    for (int k = 0; k < 2; k++) {
        snprintf(text, sizeof text, racing, k ? "16" : "15", k ? "19" : "17");
        snprintf(path, sizeof path, "%s/race-%c.ini", d.path, 'a' + k);
        s8_spill(path, text);
    }
    int race_kept = 0, race_codes = 0;
    for (int trial = 0; trial < 3; trial++) {
        snprintf(path, sizeof path, "%s/race.atlas", d.path);
        remove(path);
        snprintf(args, sizeof args, "scan '%s/race-a.ini' --out '%s' --threads 2 2>/dev/null & %s scan '%s/race-b.ini' --out '%s' "
                 "--threads 2 2>/dev/null; wait $!", d.path, d.path, s8_binary(), d.path, d.path);
        race_codes += s8_run(args, out, sizeof out) != 0;
        char *left = gb_check_read_file(path);
        struct stat before_st;
        const int had = stat(path, &before_st) == 0;
        for (int k = 0; k < 2; k++) {
            snprintf(args, sizeof args, "scan '%s/race-%c.ini' --out '%s' --threads 1", d.path, 'a' + k, d.path);
            race_codes += s8_run(args, out, sizeof out) != 0;
        }
        char *again = gb_check_read_file(path);
        race_kept += had && left && again && before_st.st_size > 0 && !memcmp(left, again, (size_t)before_st.st_size) &&
                     strlen(left) == strlen(again);
        free(left), free(again);
    }
    gb_check cc = {"4, 8.3", "29", "two scans sharing [scan] atlas_file at once (4 x 2 points, 2 threads each), then each again "
                   "alone, 3 trials", "every run exit 0; the reruns prove no cell (the atlas file unchanged)", "exact"};
    gb_check_true(&cc, race_codes == 0 && race_kept == 3, "%d runs failed; the file unchanged by the reruns in %d of 3 trials",
                  race_codes, race_kept);
    s8_remove_scan_dir(&d);
}

int verify_register_s8_scan_atlas(void)
{
    static const verify_test tests[] = {
        {"sections 4, 8.3: one atlas of verticals for a whole scan", test_scan_atlas,
         "the points of a scan can share one atlas of verticals through its file, with the per-vertical certificate's results"},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Sections 4, 8.3: one atlas of verticals for a scan", tests);
}
