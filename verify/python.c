/* The Python package (python/gomboc, cffi over the shared library's gb_handle interface): the same bits as the
 * command. verify/python_check.py loads Table 1's Gömböc I scene from its file and from its text, runs it 60
 * periods and raises three bad inputs; this suite runs `gomboc run` on the same scene and compares: the fingerprints
 * bit for bit, the samples, the last row of the history file against the arrays (to the file's printed digits),
 * the errors' attributes. The package is found through PYTHONPATH=python and the library through GOMBOC_LIB (the
 * Makefile sets it to the build's shared library). */
#include "gb_check.h"
#include "gb_scan_internal.h"
#include "verify_sections.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *binary(void) { return getenv("GOMBOC_BIN") ? getenv("GOMBOC_BIN") : "build/gomboc"; }

/* The last line of a CSV file, its fields as doubles (at most `n`): the count read. */
static int last_row(const char *path, double *out, int n)
{
    char *text = gb_check_read_file(path);
    if (!text) return 0;
    size_t len = strlen(text);
    while (len && (text[len - 1] == '\n')) text[--len] = '\0';
    const char *line = strrchr(text, '\n');
    line = line ? line + 1 : text;
    int k = 0;
    for (char *p = (char *)line, *end; k < n && *p; k++) {
        out[k] = strtod(p, &end);
        if (end == p) break;
        p = *end == ',' ? end + 1 : end;
    }
    free(text);
    return k;
}

static void test_same_bits(void)
{
    const char *lib = getenv("GOMBOC_LIB");
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("python", dir, sizeof dir)) return;
    /* the scene at 60 periods, as a file for the command */
    char scene[256], args[1024];
    snprintf(scene, sizeof scene, "%s/table1.ini", dir);
    char *text = gb_check_read_file("cases/table1-gomboc-I.ini");
    char *at = text ? strstr(text, "\nperiods = ") : NULL; /* [integrator] periods, the file's only such line */
    FILE *f = at ? fopen(scene, "w") : NULL;
    if (f) {
        fwrite(text, 1, (size_t)(at - text), f);
        fputs("\nperiods = 60", f);
        fputs(strchr(at + 1, '\n'), f);
        fclose(f);
    }
    free(text);
    static char out[1 << 16], py[1 << 16];
    snprintf(args, sizeof args, "run %s --out %s", scene, dir);
    const int code = gb_check_command(binary(), args, out, sizeof out);
    /* the summary file (a --json copy on standard output may interleave with standard error's line) */
    char summary_path[300];
    snprintf(summary_path, sizeof summary_path, "%s/table1-summary.json", dir);
    char *summary_text = code == 0 ? gb_check_read_file(summary_path) : NULL;
    cJSON *command = summary_text ? cJSON_Parse(summary_text) : NULL;
    free(summary_text);
    const cJSON *fp = cJSON_GetObjectItem(command, "fingerprint");
    const char *state = cJSON_GetStringValue(cJSON_GetObjectItem(fp, "final_state")),
               *switches = cJSON_GetStringValue(cJSON_GetObjectItem(fp, "switches"));
    /* the same scene through the package: its own file with the override */
    char command_line[2048];
    snprintf(command_line, sizeof command_line, "env GOMBOC_LIB=%s PYTHONPATH=python /usr/bin/python3 verify/python_check.py "
             "cases/table1-gomboc-I.ini 60 %s", lib ? lib : "", dir);
    const int pcode = gb_check_command("", command_line, py, sizeof py);
    char *mark = strstr(py, "@@exit=");
    if (mark) *mark = '\0';
    cJSON *package = pcode == 0 ? cJSON_Parse(py) : NULL;
    const cJSON *pfp = cJSON_GetObjectItem(package, "fingerprint"), *ptext = cJSON_GetObjectItem(package, "from_text");
    const char *p0 = cJSON_GetStringValue(cJSON_GetArrayItem(pfp, 0)), *p1 = cJSON_GetStringValue(cJSON_GetArrayItem(pfp, 1));
    const char *t0 = cJSON_GetStringValue(cJSON_GetArrayItem(ptext, 0)), *t1 = cJSON_GetStringValue(cJSON_GetArrayItem(ptext, 1));
    const int same = state && switches && p0 && p1 && !strcmp(state, p0) && !strcmp(switches, p1) && t0 && t1 &&
                     !strcmp(t0, p0) && !strcmp(t1, p1);
    gb_check c = {"-", "-", "the Python package: Table 1's Gomboc I, 60 periods, loaded from the file and from its text, run",
                  "gomboc run of the same scene: its fingerprints", "exact: bit for bit"};
    gb_check_true(&c, same, "command %s/%s, package %s/%s, from text %s/%s (exit %d, %d)%s%.300s", state ? state : "-",
                  switches ? switches : "-", p0 ? p0 : "-", p1 ? p1 : "-", t0 ? t0 : "-", t1 ? t1 : "-", code, pcode,
                  package ? "" : "; python said: ", package ? "" : py);
    /* the history's last row against the file's, to its printed digits (t %.10g, omega %.12g, E %.15g) */
    char csv[300];
    snprintf(csv, sizeof csv, "%s/table1-history.csv", dir);
    double row[7];
    const int got = last_row(csv, row, 7);
    const cJSON *last = cJSON_GetObjectItem(package, "last");
    const double samples = cJSON_GetNumberValue(cJSON_GetObjectItem(package, "samples")),
                 csv_samples = cJSON_GetNumberValue(cJSON_GetObjectItem(command, "samples"));
    static const char *const names[] = {"t", "omega_x", "omega_y", "omega_z"};
    static const double digits[] = {5e-10, 5e-12, 5e-12, 5e-12}; /* half a unit of the last printed digit, relative */
    int close = got >= 4;
    double worst = 0.0;
    for (int k = 0; k < 4 && close; k++) {
        const double v = cJSON_GetNumberValue(cJSON_GetObjectItem(last, names[k])), err = fabs(v - row[k]) / fmax(fabs(row[k]), 1e-300);
        worst = fmax(worst, err / digits[k]);
        close = close && err <= digits[k];
    }
    gb_check ch = {"-", "-", "the Python package's history arrays against the command's history file (last row: t, omega)",
                   "the file's numbers", "the file's rounding: half a unit of its last digit (t 10, omega 12 significant: 5e-10, 5e-12 "
                   "relative)"};
    gb_check_true(&ch, close && samples == csv_samples, "%d fields read, worst %.3g of the digits; %g samples "
                  "(command %g)", got, worst, samples, csv_samples);
    /* the errors: a value out of range (file, line, key, range), an unknown override key, a missing file */
    const cJSON *errors = cJSON_GetObjectItem(package, "errors");
    const cJSON *e0 = cJSON_GetArrayItem(errors, 0), *e1 = cJSON_GetArrayItem(errors, 1), *e2 = cJSON_GetArrayItem(errors, 2);
    const char *k0 = cJSON_GetStringValue(cJSON_GetObjectItem(e0, "key")), *a0 = cJSON_GetStringValue(cJSON_GetObjectItem(e0, "allowed")),
               *f0 = cJSON_GetStringValue(cJSON_GetObjectItem(e0, "file")), *k1 = cJSON_GetStringValue(cJSON_GetObjectItem(e1, "key"));
    const double l0 = cJSON_GetNumberValue(cJSON_GetObjectItem(e0, "line")), s2 = cJSON_GetNumberValue(cJSON_GetObjectItem(e2, "status"));
    const int errors_ok = k0 && !strcmp(k0, "omega") && f0 && !strcmp(f0, "bad.ini") && l0 == 2 && a0 && strstr(a0, "omega") &&
                          k1 && !strcmp(k1, "omegas") && s2 == 2;
    gb_check ce = {"-", "-", "the Python package's errors: omega = -3 in a dict, an unknown override key, a missing file",
                   "GombocError with file, line, key and the allowed range; the key named; status 2 (bad input)", "exact"};
    char *shown = errors ? cJSON_PrintUnformatted(errors) : NULL;
    gb_check_true(&ce, errors_ok, "%.400s", shown ? shown : py);
    free(shown);
    /* the manifolds: tangle() against `gomboc melnikov --tangle 0.05 --json` for the same scene */
    static char tangled[1 << 16];
    snprintf(args, sizeof args, "melnikov cases/table1-gomboc-I.ini --tangle 0.05 --json");
    const int tcode = gb_check_command(binary(), args, tangled, sizeof tangled);
    cJSON *tj = tcode == 0 && strchr(tangled, '{') ? cJSON_Parse(strchr(tangled, '{')) : NULL;
    const cJSON *tt = cJSON_GetObjectItem(tj, "tangle"), *pt = cJSON_GetObjectItem(package, "tangle");
    const double want[4] = {cJSON_GetNumberValue(cJSON_GetObjectItem(tt, "homoclinic_orbits")),
                            cJSON_GetNumberValue(cJSON_GetObjectItem(tt, "smallest_angle_deg")),
                            cJSON_GetNumberValue(cJSON_GetArrayItem(cJSON_GetObjectItem(tt, "multipliers"), 0)),
                            cJSON_GetNumberValue(cJSON_GetArrayItem(cJSON_GetObjectItem(tt, "multipliers"), 1))};
    int tangle_equal = tt && cJSON_GetArraySize(pt) == 4;
    for (int i = 0; i < 4 && tangle_equal; i++) tangle_equal = cJSON_GetNumberValue(cJSON_GetArrayItem(pt, i)) == want[i];
    const char *tangle_refused = cJSON_GetStringValue(cJSON_GetObjectItem(package, "tangle_refused"));
    gb_check ct = {"7", "91", "the Python package's tangle(0.05) of Table 1's Gomboc I, and tangle(0.5)",
                   "gomboc melnikov --tangle 0.05 --json: orbits, smallest angle, multipliers; GombocError naming the range",
                   "exact: bit for bit"};
    gb_check_true(&ct, tangle_equal && tangle_refused && strstr(tangle_refused, "1e-4 to 0.1"),
                  "command exit %d; %g orbits, smallest angle %.6g deg (command) %s the package's; 0.5: %s", tcode, want[0],
                  want[1], tangle_equal ? "equal to" : "DIFFERENT FROM", tangle_refused ? tangle_refused : "not refused");
    cJSON_Delete(tj);
    /* the body: `gomboc shape --scene` and `gomboc contact --method continuous` against the package's */
    static char shape[1 << 16], contact[1 << 16];
    snprintf(args, sizeof args, "shape --scene cases/table1-gomboc-I.ini --json");
    const int scode = gb_check_command(binary(), args, shape, sizeof shape);
    snprintf(args, sizeof args, "contact --morphology I --beta 0.12 --zb 0.6,0.6,-0.5 --method continuous --json");
    const int ccode = gb_check_command(binary(), args, contact, sizeof contact);
    cJSON *sj = scode == 0 && strchr(shape, '{') ? cJSON_Parse(strchr(shape, '{')) : NULL,
          *cj = ccode == 0 && strchr(contact, '{') ? cJSON_Parse(strchr(contact, '{')) : NULL;
    const cJSON *pm = cJSON_GetObjectItem(package, "massprops"), *pc = cJSON_GetObjectItem(package, "contact");
    double expected[19];
    expected[0] = cJSON_GetNumberValue(cJSON_GetObjectItem(sj, "volume"));
    for (int i = 0; i < 3; i++) {
        expected[1 + i] = cJSON_GetNumberValue(cJSON_GetArrayItem(cJSON_GetObjectItem(sj, "centroid"), i));
        for (int j = 0; j < 3; j++)
            expected[4 + 3 * i + j] = cJSON_GetNumberValue(cJSON_GetArrayItem(cJSON_GetArrayItem(cJSON_GetObjectItem(sj, "inertia"), i), j));
    }
    expected[13] = cJSON_GetNumberValue(cJSON_GetObjectItem(cj, "phi"));
    expected[14] = cJSON_GetNumberValue(cJSON_GetObjectItem(cj, "theta"));
    expected[15] = cJSON_GetNumberValue(cJSON_GetObjectItem(cj, "height"));
    for (int i = 0; i < 3; i++) expected[16 + i] = cJSON_GetNumberValue(cJSON_GetArrayItem(cJSON_GetObjectItem(cj, "rc"), i));
    int equal = 0;
    for (int k = 0; k < 19; k++) {
        const double got = cJSON_GetNumberValue(k < 13 ? cJSON_GetArrayItem(pm, k) : cJSON_GetArrayItem(pc, k - 13));
        equal += got == expected[k];
    }
    gb_check cb = {"-", "-", "the Python package's body: massprops() and contact([0.6, 0.6, -0.5]) of Table 1's Gomboc I",
                   "gomboc shape --scene and gomboc contact --method continuous: volume, centroid, inertia; phi, theta, height, r_c",
                   "exact: bit for bit (both print doubles that read back to themselves)"};
    gb_check_true(&cb, equal == 19, "%d of 19 numbers equal (exit %d, %d)", equal, scode, ccode);
    /* the equilibria: the package's rows against `gomboc shape`'s, type and phi, theta, r bit for bit */
    const cJSON *se = cJSON_GetObjectItem(sj, "equilibria"), *pe = cJSON_GetObjectItem(package, "equilibria");
    int rows = cJSON_GetArraySize(se), same_rows = 0;
    for (int k = 0; k < rows && rows == cJSON_GetArraySize(pe); k++) {
        const cJSON *c = cJSON_GetArrayItem(se, k), *q = cJSON_GetArrayItem(pe, k);
        const char *type = cJSON_GetStringValue(cJSON_GetObjectItem(c, "type")), *ptype = cJSON_GetStringValue(cJSON_GetArrayItem(q, 0));
        same_rows += type && ptype && !strcmp(type, ptype) &&
                     cJSON_GetNumberValue(cJSON_GetObjectItem(c, "phi")) == cJSON_GetNumberValue(cJSON_GetArrayItem(q, 1)) &&
                     cJSON_GetNumberValue(cJSON_GetObjectItem(c, "theta")) == cJSON_GetNumberValue(cJSON_GetArrayItem(q, 2)) &&
                     cJSON_GetNumberValue(cJSON_GetObjectItem(c, "r")) == cJSON_GetNumberValue(cJSON_GetArrayItem(q, 3));
    }
    gb_check cq = {"-", "-", "the Python package's equilibria() of Table 1's Gomboc I", "gomboc shape --scene: every critical "
                   "point of r, its type, phi, theta and r", "exact: bit for bit, the same rows in the same order"};
    gb_check_true(&cq, rows > 0 && same_rows == rows && cJSON_GetArraySize(pe) == rows, "%d of %d rows equal (the package %d)",
                  same_rows, rows, cJSON_GetArraySize(pe));
    cJSON_Delete(sj), cJSON_Delete(cj);
    /* a 2 x 2 scan: the package's CSV against the command's, byte for byte */
    static char scanned[1 << 12];
    snprintf(args, sizeof args, "scan %s/tiny.ini --out %s --threads 2", dir, dir);
    const int xcode = gb_check_command(binary(), args, scanned, sizeof scanned);
    char path_a[300], path_b[300];
    snprintf(path_a, sizeof path_a, "%s/tiny-scan.csv", dir), snprintf(path_b, sizeof path_b, "%s/python-scan.csv", dir);
    char *a = gb_check_read_file(path_a), *b = gb_check_read_file(path_b);
    const cJSON *ps = cJSON_GetObjectItem(package, "scan");
    const double points = cJSON_GetNumberValue(cJSON_GetObjectItem(ps, "points")),
                 calls = cJSON_GetNumberValue(cJSON_GetObjectItem(ps, "progress_calls"));
    const int phases = cJSON_GetArraySize(cJSON_GetObjectItem(ps, "phases"));
    gb_check cs = {"-", "-", "the Python package's scan: a 2 x 2 map of Table 1's Gomboc I (30 periods), on 2 threads, with a "
                   "progress callback", "gomboc scan of the same file: its CSV", "exact: byte for byte; the callback heard both phases"};
    gb_check_true(&cs, xcode == 0 && a && b && !strcmp(a, b) && points == 4 && calls >= 4 && phases == 2,
                  "command exit %d, CSVs %s (%zu and %zu bytes), %g points, %g progress calls over %d phases", xcode,
                  a && b && !strcmp(a, b) ? "equal" : "differ", a ? strlen(a) : 0, b ? strlen(b) : 0, points, calls, phases);
    /* the Melnikov margins: melnikov() of each point's scene against the command's columns for it */
    int margins = 0, margins_equal = 0;
    const cJSON *pmel = cJSON_GetObjectItem(package, "melnikov");
    for (const char *line = a ? strchr(a, '\n') : NULL; line && line[1]; line = strchr(line + 1, '\n')) {
        size_t index;
        gb_scan_metrics m;
        if (gb_scan_csv_parse(line + 1, &index, &m)) break;
        const cJSON *row = cJSON_GetArrayItem(pmel, (int)index);
        margins++;
        margins_equal += row && cJSON_GetNumberValue(cJSON_GetArrayItem(row, 0)) == m.melnikov_margin &&
                         cJSON_GetNumberValue(cJSON_GetArrayItem(row, 1)) == m.melnikov_margin_eq93;
    }
    gb_check cm = {"7", "91, 93", "the Python package's melnikov() of the 2 x 2 map's scenes (the base with each point's omega and A1)",
                   "gomboc scan's columns melnikov_margin and melnikov_margin_eq93 for the point", "exact: bit for bit"};
    gb_check_true(&cm, margins == 4 && margins_equal == 4, "%d of %d points equal", margins_equal, margins);
    free(a), free(b);
    /* the plotters as functions: a scan's figure, a run's page, an unknown metric refused */
    const cJSON *pp = cJSON_GetObjectItem(package, "plot");
    const double figure_bytes = cJSON_GetNumberValue(cJSON_GetObjectItem(pp, "figure_bytes")),
                 page_bytes = cJSON_GetNumberValue(cJSON_GetObjectItem(pp, "page_bytes"));
    const char *refused = cJSON_GetStringValue(cJSON_GetObjectItem(pp, "refused"));
    gb_check cp = {"-", "-", "gomboc.plot: scan() of the 2 x 2 map, run() of the 60-period run, scan() of an unknown metric",
                   "the scripts' outputs: a PNG, the run's page; GombocError naming the metric and the allowed ones", "exact"};
    gb_check_true(&cp, figure_bytes > 1000 && page_bytes > 100 && refused && strstr(refused, "nonesuch") && strstr(refused, "allowed"),
                  "figure %g bytes, page %g bytes, refused: %.150s", figure_bytes, page_bytes, refused ? refused : "no");
    cJSON_Delete(command), cJSON_Delete(package);
    gb_check_tempdir_remove(dir);
}

int verify_register_python(void)
{
    static const verify_test tests[] = {
        {"python: import gomboc gives the command's bits, its arrays and its errors", test_same_bits,
         "the Python package runs a scene to the command's fingerprints, gives the command's mass properties, contact and "
         "scan CSV bit for bit, and raises the command's errors with their file, line, key and range"},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("The Python package", tests);
}
