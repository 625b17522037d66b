/* The `gomboc` command: good input gives the JSON keys the issue names; output is byte-identical
 * between runs; a failed write leaves no file behind (bad input: verify/bad_input.c). The binary
 * comes from $GOMBOC_BIN. */
#include "bad_input.h"
#include "gb_check.h"
#include "gb_contact.h"
#include "gb_error.h"
#include "gb_massprops.h"
#include "gb_scan_internal.h"
#include "verify_sections.h"

#include <cjson/cJSON.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

static const char *binary(void) { return getenv("GOMBOC_BIN") ? getenv("GOMBOC_BIN") : "build/gomboc"; }

static int run(const char *args, char *out, size_t cap) { return gb_check_command(binary(), args, out, cap); }

static void test_json_keys_and_determinism(void)
{
    static char first[1 << 16], second[1 << 16];
    const int code = run("shape --morphology II --beta 0.02 --json", first, sizeof first);
    run("shape --morphology II --beta 0.02 --json", second, sizeof second);
    char *mark = strstr(first, "@@exit=");
    if (mark) *mark = '\0';
    cJSON *root = cJSON_Parse(first);
    static const char *keys[] = {"volume", "centroid", "inertia", "L", "curvature_min", "curvature_min_at",
                                 "negative_curvature_fraction", "convexity_beta_limit", "convex", "equilibria",
                                 "hull_equilibria", "mono_monostatic"};
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++) {
        gb_check c = {"2", "-", "gomboc shape --json has the key", keys[k], "exact"};
        gb_check_true(&c, code == 0 && cJSON_GetObjectItem(root, keys[k]) != NULL, "exit %d, key %s", code, keys[k]);
    }
    gb_check cm = {"2", "3-6", "a convex body at beta 0.02 is reported convex and mono-monostatic", "critical points of r", "exact"};
    gb_check_true(&cm, cJSON_IsTrue(cJSON_GetObjectItem(root, "convex")) && cJSON_IsTrue(cJSON_GetObjectItem(root, "mono_monostatic")),
                  "convex %d, mono_monostatic %d", cJSON_IsTrue(cJSON_GetObjectItem(root, "convex")),
                  cJSON_IsTrue(cJSON_GetObjectItem(root, "mono_monostatic")));
    if (mark) *mark = '@';
    gb_check cd = {"2", "-", "same command, same binary: identical output bytes", "determinism", "exact"};
    gb_check_true(&cd, strcmp(first, second) == 0, "%zu and %zu bytes", strlen(first), strlen(second));
    cJSON_Delete(root);
}

static void test_failed_write_leaves_nothing(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("verify", dir, sizeof dir)) return;
    char path[256], args[512], out[8192] = "";
    snprintf(path, sizeof path, "%s/missing-folder/map.csv", dir);
    snprintf(args, sizeof args, "shape --morphology I --beta 0.02 --radial-map %s", path);
    const int code = run(args, out, sizeof out);
    gb_check c = {"2", "-", "a --radial-map in a missing directory is refused before any work and leaves no file",
                  "exit status and file system", "exact"};
    gb_check_true(&c, code == 2 && access(path, F_OK) != 0 && strstr(out, "its directory does not exist"), "exit %d, output: %.200s",
                  code, out);
    snprintf(path, sizeof path, "%s/map.csv", dir);
    snprintf(args, sizeof args, "shape --morphology I --beta 0.02 --radial-map %s", path);
    const int good = run(args, out, sizeof out);
    FILE *f = fopen(path, "r");
    size_t lines = 0;
    for (int ch; f && (ch = fgetc(f)) != EOF;) lines += ch == '\n';
    if (f) fclose(f);
    gb_check c2 = {"2", "-", "--radial-map writes the header, column line and 90 x 180 rows", "line count", "exact"};
    gb_check_true(&c2, good == 0 && lines == 2 + 90 * 180, "exit %d, %zu lines", good, lines);
    remove(path);
    /* --grid-nodes: the scenes' default contact grid, every node to the last bit (what another engine reads) */
    snprintf(path, sizeof path, "%s/nodes.csv", dir);
    snprintf(args, sizeof args, "shape --morphology II --beta 0.12 --grid-nodes %s", path);
    const int written = run(args, out, sizeof out);
    gb_contact_grid *grid = NULL;
    const gb_contact_grid_def def = gb_contact_grid_default_def();
    size_t rows = 0, equal = 0;
    f = fopen(path, "r");
    if (f && !gb_contact_grid_create(gb_check_body("II", 0.12), &def, &grid)) {
        char line[512];
        while (fgets(line, sizeof line, f)) {
            double v[5];
            unsigned long index;
            if (sscanf(line, "%lu,%lf,%lf,%lf,%lf,%lf", &index, v, v + 1, v + 2, v + 3, v + 4) != 6) continue;
            double phi, theta, x[3];
            rows++;
            if (index >= gb_contact_grid_size(grid)) continue;
            gb_contact_grid_node(grid, index, &phi, &theta, x);
            equal += index == rows - 1 && phi == v[0] && theta == v[1] && x[0] == v[2] && x[1] == v[3] && x[2] == v[4];
        }
    }
    if (f) fclose(f);
    gb_check c3 = {"4", "29", "--grid-nodes writes every node of the 90 x 180 centred grid, in order, to the last bit",
                   "the library's own grid (gb_contact_grid_node)", "exact: %.17g reads back to the same double"};
    gb_check_true(&c3, written == 0 && grid && rows == gb_contact_grid_size(grid) && equal == rows, "exit %d, %zu rows, %zu equal",
                  written, rows, equal);
    gb_contact_grid_free(grid);
    remove(path);
    gb_check_tempdir_remove(dir);
}

/* Run a contact query and parse its JSON (NULL on failure). */
static cJSON *contact_json(const char *method_and_options, int *code)
{
    static char out[1 << 17];
    char args[512];
    snprintf(args, sizeof args, "contact --morphology II --beta 0.12 --zb 0.2385,-0.731,0.4417 --json %s", method_and_options);
    *code = run(args, out, sizeof out);
    char *mark = strstr(out, "@@exit=");
    if (mark) *mark = '\0';
    return cJSON_Parse(out);
}

static double number(const cJSON *root, const char *key) { return cJSON_GetNumberValue(cJSON_GetObjectItem(root, key)); }

static void test_contact_command(void)
{
    int code_grid, code_fast, code_cont;
    cJSON *grid = contact_json("--method grid", &code_grid);
    cJSON *fast = contact_json("--method fast-grid", &code_fast);
    cJSON *cont = contact_json("--method continuous", &code_cont);
    static const char *keys[] = {"phi", "theta", "height", "rc", "index", "branches"};
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++) {
        gb_check c = {"4", "29-30", "gomboc contact --json has the key (grid, fast-grid, continuous)", keys[k], "exact"};
        gb_check_true(&c, code_grid == 0 && code_fast == 0 && code_cont == 0 && cJSON_GetObjectItem(grid, keys[k]) &&
                      cJSON_GetObjectItem(fast, keys[k]) && cJSON_GetObjectItem(cont, keys[k]),
                      "exits %d %d %d, key %s", code_grid, code_fast, code_cont, keys[k]);
    }
    gb_check ci = {"8", "29", "gomboc contact: grid and fast-grid return the same node", "brute force", "exact"};
    gb_check_true(&ci, number(grid, "index") == number(fast, "index") && number(grid, "height") == number(fast, "height"),
                  "index %.0f vs %.0f", number(grid, "index"), number(fast, "index"));
    gb_check cn = {"4", "29", "gomboc contact: the continuous index is null (no grid node)", "JSON null", "exact"};
    gb_check_true(&cn, cJSON_IsNull(cJSON_GetObjectItem(cont, "index")), "index item type %d",
                  cJSON_GetObjectItem(cont, "index") ? cJSON_GetObjectItem(cont, "index")->type : -1);
    gb_check cb = {"4", "29, 36", "gomboc contact: continuous h* <= the grid node's height", "every node is a surface point",
                   "8 eps"};
    gb_check_true(&cb, number(cont, "height") <= number(grid, "height") + 8 * 2.2e-16, "h* %.17g, grid %.17g",
                  number(cont, "height"), number(grid, "height"));
    const cJSON *first = cJSON_GetArrayItem(cJSON_GetObjectItem(cont, "branches"), 0);
    gb_check cf = {"4", "29", "gomboc contact: the contact is the lowest listed branch", "branches[0]", "exact"};
    gb_check_true(&cf, first && number(first, "height") == number(cont, "height"), "branch %.17g, contact %.17g",
                  first ? number(first, "height") : NAN, number(cont, "height"));
    int code_scaled;
    static char a[1 << 17], b[1 << 17];
    run("contact --morphology II --beta 0.12 --zb 0.2385,-0.731,0.4417 --method fast-grid --json", a, sizeof a);
    code_scaled = run("contact --morphology II --beta 0.12 --zb 2.385,-7.31,4.417 --method fast-grid --json", b, sizeof b);
    cJSON *ja = cJSON_Parse(a), *jb = cJSON_Parse(b);
    gb_check cs = {"4", "28", "gomboc contact: z_b need not be normalised", "same node for z_b and 10 z_b", "exact"};
    gb_check_true(&cs, code_scaled == 0 && number(ja, "index") == number(jb, "index"), "index %.0f vs %.0f",
                  number(ja, "index"), number(jb, "index"));
    cJSON_Delete(ja);
    cJSON_Delete(jb);
    cJSON_Delete(grid);
    cJSON_Delete(fast);
    cJSON_Delete(cont);
}

/* Write `text` as a case file in `dir`; returns its path in `path`. */
static void write_case(const char *dir, const char *name, const char *text, char *path, size_t size)
{
    snprintf(path, size, "%s/%s.ini", dir, name);
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

static const char *SHORT_SCENE =
    "[body]\nmorphology = II\nbeta = 0.12\n[integrator]\nsteps_per_period = 40\nperiods = 2\n"
    "[model]\ncontact = fast-grid\n";

/* From a run's --json output: its state fingerprint and hull.loaded (-1 when missing); returns code. */
static int summary_hull(int code, const char *out, char *fingerprint, size_t size, int *loaded)
{
    cJSON *root = cJSON_Parse(strchr(out, '{') ? strchr(out, '{') : out);
    const cJSON *print = cJSON_GetObjectItem(cJSON_GetObjectItem(root, "fingerprint"), "final_state");
    snprintf(fingerprint, size, "%s", cJSON_IsString(print) ? print->valuestring : "none");
    const cJSON *h = cJSON_GetObjectItem(cJSON_GetObjectItem(root, "hull"), "loaded");
    *loaded = cJSON_IsNumber(h) ? h->valueint : -1;
    cJSON_Delete(root);
    return code;
}

/* `gomboc run CASE --out DIR --hull HULL --json`: its exit status, the summary's state fingerprint and
 * hull.loaded (-1 when missing). */
static int run_with_hull(const char *scene, const char *dir, const char *hull, char *fingerprint, size_t size, int *loaded)
{
    static char out[1 << 16];
    char args[800];
    snprintf(args, sizeof args, "run %s --out %s --hull %s --json", scene, dir, hull);
    const int code = run(args, out, sizeof out);
    return summary_hull(code, out, fingerprint, size, loaded);
}

/* `gomboc run CASE --out DIR --json` with the user's cache at XDG_CACHE_HOME = cache (the harness runs with
 * GOMBOC_CACHE=off otherwise): as run_with_hull. */
static int run_with_cache(const char *scene, const char *dir, const char *cache, char *fingerprint, size_t size, int *loaded)
{
    static char out[1 << 16];
    char args[800];
    snprintf(args, sizeof args, "run %s --out %s --json", scene, dir);
    setenv("GOMBOC_CACHE", "on", 1), setenv("XDG_CACHE_HOME", cache, 1);
    const int code = run(args, out, sizeof out);
    setenv("GOMBOC_CACHE", "off", 1), unsetenv("XDG_CACHE_HOME");
    return summary_hull(code, out, fingerprint, size, loaded);
}

/* The files KIND-HEX.EXT in the user's cache at `cache` (−1 when it cannot be listed). */
static int cache_files(const char *cache, const char *kind, const char *ext)
{
    char listing[600];
    snprintf(listing, sizeof listing, "ls %s/gomboc | grep -c '^%s-[0-9a-f]*\\.%s$'", cache, kind, ext);
    FILE *ls = popen(listing, "r");
    int files = -1;
    if (ls) {
        if (fscanf(ls, "%d", &files) != 1) files = -1;
        pclose(ls);
    }
    return files;
}

/* Three runs that exited 0 and ended in one fingerprint (not "none"). */
static int same_three(const int code[3], char prints[3][32])
{
    int same = 1;
    for (int k = 0; k < 3; k++) same &= code[k] == 0 && !strcmp(prints[k], prints[0]) && strcmp(prints[k], "none");
    return same;
}

/* The user's cache: without --hull the hull is kept in $XDG_CACHE_HOME/gomboc by the grid's content, built and written
 * by the first run of a body, read by every run after it in any process; a cache that cannot be made (its parent a
 * file) leaves the run as it was. */
static void test_run_cache(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("cache", dir, sizeof dir)) return;
    char scene[256], cache[300], blocked[300], prints[3][32];
    write_case(dir, "short", SHORT_SCENE, scene, sizeof scene);
    snprintf(cache, sizeof cache, "%s/cache", dir);
    snprintf(blocked, sizeof blocked, "%s/a-file", dir);
    FILE *f = fopen(blocked, "w");
    if (f) fputs("not a directory\n", f), fclose(f);
    int loaded[3], code[3];
    code[0] = run_with_cache(scene, dir, cache, prints[0], sizeof prints[0], &loaded[0]);
    code[1] = run_with_cache(scene, dir, cache, prints[1], sizeof prints[1], &loaded[1]);
    code[2] = run_with_cache(scene, dir, blocked, prints[2], sizeof prints[2], &loaded[2]);
    const int files = cache_files(cache, "hull", "gbh");
    gb_check c = {"8", "29", "gomboc run without --hull, the user's cache at XDG_CACHE_HOME: first run, second run, a cache "
                  "whose parent is a file", "the first builds and writes one hull file, the second reads it, the third runs "
                  "without a cache; the same state bits", "exact: the state fingerprint"};
    gb_check_true(&c, same_three(code, prints) && files == 1 && loaded[0] == 0 && loaded[1] == 1 && loaded[2] == 0,
                  "exit %d %d %d; loaded %d %d %d; %d hull file(s) in the cache; fingerprints %s %s %s", code[0], code[1], code[2],
                  loaded[0], loaded[1], loaded[2], files, prints[0], prints[1], prints[2]);
    gb_check_tempdir_remove(dir);
}

/* The mass properties in the user's cache: written by the first run of a paper body, read by the next; a file whose
 * values were changed (the seal no longer matches) is not read — had it been, the changed inertia would change the
 * state bits; a body of one's own writes none. */
static int massprops_loaded(int code, const char *out, char *fingerprint, size_t size)
{
    int hull;
    summary_hull(code, out, fingerprint, size, &hull);
    cJSON *root = cJSON_Parse(strchr(out, '{') ? strchr(out, '{') : out);
    const cJSON *l = cJSON_GetObjectItem(cJSON_GetObjectItem(root, "massprops"), "loaded");
    const int loaded = cJSON_IsNumber(l) ? l->valueint : -1;
    cJSON_Delete(root);
    return loaded;
}

static void test_run_massprops_cache(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("massprops", dir, sizeof dir)) return;
    static const char *const own = "[body]\nchi = theta - 5 * phi\nbeta = 0.12\n[integrator]\nsteps_per_period = 40\n"
                                   "periods = 1\n[model]\ncontact = fast-grid\n";
    char scene[256], mine[256], cache[300], prints[4][32], path[400] = "";
    write_case(dir, "short", SHORT_SCENE, scene, sizeof scene);
    write_case(dir, "mine", own, mine, sizeof mine);
    snprintf(cache, sizeof cache, "%s/cache", dir);
    static char out[1 << 16];
    int loaded[4], code[4];
    char args[800];
    snprintf(args, sizeof args, "run %s --out %s --json", scene, dir);
    setenv("GOMBOC_CACHE", "on", 1), setenv("XDG_CACHE_HOME", cache, 1);
    for (int k = 0; k < 2; k++) code[k] = run(args, out, sizeof out), loaded[k] = massprops_loaded(code[k], out, prints[k], sizeof prints[k]);
    /* change the cached inertia's bits (the file: magic, the struct, the seal) */
    char listing[600];
    snprintf(listing, sizeof listing, "ls %s/gomboc/massprops-*.gbm 2>/dev/null", cache);
    FILE *ls = popen(listing, "r");
    int files = 0;
    if (ls) {
        char line[400];
        while (fgets(line, sizeof line, ls)) files++, line[strcspn(line, "\n")] = '\0', snprintf(path, sizeof path, "%s", line);
        pclose(ls);
    }
    FILE *f = files == 1 ? fopen(path, "r+b") : NULL;
    int changed = 0;
    if (f) {
        unsigned char b[8];
        const long at = 8 + (long)offsetof(gb_massprops, inertia);
        if (fseek(f, at, SEEK_SET) == 0 && fread(b, 8, 1, f) == 1) {
            double x;
            memcpy(&x, b, 8);
            x *= 1.5;
            changed = fseek(f, at, SEEK_SET) == 0 && fwrite(&x, 8, 1, f) == 1;
        }
        fclose(f);
    }
    code[2] = run(args, out, sizeof out), loaded[2] = massprops_loaded(code[2], out, prints[2], sizeof prints[2]);
    snprintf(args, sizeof args, "run %s --out %s --json", mine, dir);
    code[3] = run(args, out, sizeof out), loaded[3] = massprops_loaded(code[3], out, prints[3], sizeof prints[3]);
    setenv("GOMBOC_CACHE", "off", 1), unsetenv("XDG_CACHE_HOME");
    ls = popen(listing, "r");
    int after = 0;
    if (ls) {
        char line[400];
        while (fgets(line, sizeof line, ls)) after++;
        pclose(ls);
    }
    gb_check c = {"2", "-", "gomboc run's mass properties in the user's cache: first run, second run, a cache file with its "
                  "inertia changed, a body of one's own", "the first writes one file, the second reads it (the same state "
                  "bits), the changed file is not read (the same bits again: read, its inertia would change them) and is "
                  "replaced, the body of one's own adds no file", "exact: the state fingerprint"};
    const int same = same_three(code, prints);
    gb_check_true(&c, same && code[3] == 0 && files == 1 && changed && after == 1 && loaded[0] == 0 && loaded[1] == 1 &&
                          loaded[2] == 0 && loaded[3] == 0,
                  "exit %d %d %d %d; loaded %d %d %d %d; files %d then %d, changed %d; fingerprints %s %s %s", code[0], code[1],
                  code[2], code[3], loaded[0], loaded[1], loaded[2], loaded[3], files, after, changed, prints[0], prints[1],
                  prints[2]);
    gb_check_tempdir_remove(dir);
}

/* The atlas of a `certificate = atlas` run in the user's cache: its cells proved by the first run, read by the next
 * (none proved again), the same state bits; with --atlas FILE the named file is used and the cache gains none. */
static void test_run_atlas_cache(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("atlascache", dir, sizeof dir)) return;
    static const char *const text = "[body]\nmorphology = II\n[model]\nequation = rolling\ncontact = continuous\n"
                                    "certificate = atlas\n[initial]\nomega = 1.3,-0.7,0.4\n[integrator]\nsteps_per_period = 40\n"
                                    "periods = 1\nlocate_switches = yes\n";
    char scene[256], cache[300], named[300], prints[3][32];
    write_case(dir, "atlas", text, scene, sizeof scene);
    snprintf(cache, sizeof cache, "%s/cache", dir);
    snprintf(named, sizeof named, "%s/named.gba", dir);
    static char out[1 << 16];
    int loaded[3], code[3];
    double built[3];
    setenv("GOMBOC_CACHE", "on", 1), setenv("XDG_CACHE_HOME", cache, 1);
    for (int k = 0; k < 3; k++) {
        char args[800];
        if (k < 2) snprintf(args, sizeof args, "run %s --out %s --json", scene, dir);
        else snprintf(args, sizeof args, "run %s --out %s --atlas %s --json", scene, dir, named);
        code[k] = run(args, out, sizeof out);
        int hull;
        summary_hull(code[k], out, prints[k], sizeof prints[k], &hull);
        cJSON *root = cJSON_Parse(strchr(out, '{') ? strchr(out, '{') : out);
        const cJSON *a = cJSON_GetObjectItem(root, "atlas");
        loaded[k] = cJSON_IsNumber(cJSON_GetObjectItem(a, "loaded")) ? cJSON_GetObjectItem(a, "loaded")->valueint : -1;
        built[k] = cJSON_GetNumberValue(cJSON_GetObjectItem(a, "build_seconds"));
        cJSON_Delete(root);
    }
    setenv("GOMBOC_CACHE", "off", 1), unsetenv("XDG_CACHE_HOME");
    const int files = cache_files(cache, "atlas", "gba");
    FILE *f = fopen(named, "rb");
    const int named_written = f != NULL;
    if (f) fclose(f);
    gb_check c = {"4", "29", "gomboc run with certificate = atlas, the user's cache at XDG_CACHE_HOME: first run, second run, "
                  "a run naming --atlas", "the first proves the cells and writes one atlas file, the second reads it and proves "
                  "none, the third writes the named file and adds none to the cache; the same state bits", "exact"};
    const int same = same_three(code, prints);
    gb_check_true(&c, same && loaded[0] == 0 && loaded[1] == 1 && built[0] > 0.0 && built[1] == 0.0 && files == 1 && named_written,
                  "exit %d %d %d; loaded %d %d %d; build seconds %.3g %.3g; %d atlas file(s) in the cache, named file %s; "
                  "fingerprints %s %s %s", code[0], code[1], code[2], loaded[0], loaded[1], loaded[2], built[0], built[1], files,
                  named_written ? "written" : "missing", prints[0], prints[1], prints[2]);
    gb_check_tempdir_remove(dir);
}

/* --hull FILE: the first run builds the hull and writes it, the next reads it, a damaged file is built anew
 * and replaced; the same state bits every time. */
static void test_run_hull(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("hull", dir, sizeof dir)) return;
    char scene[256], hull[300], prints[4][32];
    write_case(dir, "short", SHORT_SCENE, scene, sizeof scene);
    snprintf(hull, sizeof hull, "%s/II.hull", dir);
    int loaded[4], code[4];
    code[0] = run_with_hull(scene, dir, hull, prints[0], sizeof prints[0], &loaded[0]);
    code[1] = run_with_hull(scene, dir, hull, prints[1], sizeof prints[1], &loaded[1]);
    FILE *f = fopen(hull, "r+b"); /* one byte of the edge lists changed: the checksum no longer matches */
    int damaged = f && !fseek(f, 60000, SEEK_SET) && fputc(0x5a, f) != EOF;
    if (f) damaged &= fclose(f) == 0;
    code[2] = run_with_hull(scene, dir, hull, prints[2], sizeof prints[2], &loaded[2]);
    code[3] = run_with_hull(scene, dir, hull, prints[3], sizeof prints[3], &loaded[3]);
    gb_check c = {"8", "29", "gomboc run --hull F: built and written, read, damaged and built anew, read again",
                  "the same scene without the file's help", "exact: the state fingerprint"};
    int same = 1;
    for (int k = 0; k < 4; k++) same &= code[k] == 0 && !strcmp(prints[k], prints[0]) && strcmp(prints[k], "none");
    gb_check_true(&c, same && damaged && loaded[0] == 0 && loaded[1] == 1 && loaded[2] == 0 && loaded[3] == 1,
                  "exit %d %d %d %d; loaded %d %d %d %d; fingerprints %s %s %s %s", code[0], code[1], code[2], code[3], loaded[0],
                  loaded[1], loaded[2], loaded[3], prints[0], prints[1], prints[2], prints[3]);
    char summary[300];
    snprintf(summary, sizeof summary, "%s/short-summary.json", dir);
    remove(summary), remove(hull), remove(scene), gb_check_tempdir_remove(dir);
}

static void test_run_command(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("run", dir, sizeof dir)) return;
    /* A good short scene, twice: identical bytes; history = no writes no history. */
    char path[256], args[600], out[1 << 14] = "", first[1 << 14], second[1 << 14];
    write_case(dir, "short", SHORT_SCENE, path, sizeof path);
    snprintf(args, sizeof args, "run %s --out %s --json", path, dir);
    const int code = run(args, first, sizeof first);
    run(args, second, sizeof second);
    /* The CPU-time line on stderr differs between runs: cut it out of both. */
    for (char *text = first; text; text = text == first ? second : NULL) {
        char *line = strstr(text, "gomboc run:"), *end = line ? strchr(line, '\n') : NULL;
        if (line && end) memmove(line, end + 1, strlen(end + 1) + 1);
    }
    gb_check cd = {"8", "-", "gomboc run: same scene, same binary, identical summary bytes", "determinism", "exact"};
    gb_check_true(&cd, code == 0 && strcmp(first, second) == 0 && strstr(first, "grid_switches"), "exit %d, %zu and %zu bytes",
                  code, strlen(first), strlen(second));
    char history[300];
    snprintf(history, sizeof history, "%s/short-history.csv", dir);
    gb_check ch = {"8", "-", "gomboc run writes the history the scene asked for", "file exists", "exact"};
    gb_check_true(&ch, access(history, F_OK) == 0, "%s", history);
    remove(history);
    char text[1024];
    snprintf(text, sizeof text, "%s[output]\nhistory = no\nsummary = no\n", SHORT_SCENE);
    write_case(dir, "quiet", text, path, sizeof path);
    snprintf(args, sizeof args, "run %s --out %s", path, dir);
    const int quiet = run(args, out, sizeof out);
    char summary[300];
    snprintf(history, sizeof history, "%s/quiet-history.csv", dir);
    snprintf(summary, sizeof summary, "%s/quiet-summary.json", dir);
    gb_check cq = {"8", "-", "a scene with history = no and summary = no writes no file", "file system", "exact"};
    gb_check_true(&cq, quiet == 0 && access(history, F_OK) != 0 && access(summary, F_OK) != 0, "exit %d", quiet);
    remove(path);
    snprintf(path, sizeof path, "%s/short.ini", dir);
    remove(path);
    snprintf(summary, sizeof summary, "%s/short-summary.json", dir);
    remove(summary);

    /* The diagnostics: only what the scene asks for is written; gomboc lyapunov's keys. */
    snprintf(text, sizeof text, "%s[output]\nhistory = no\nsummary = no\n[diagnostics]\nstrobe = yes\n"
                                "[strobe]\ntransient_periods = 0\n", SHORT_SCENE);
    write_case(dir, "strobe-only", text, path, sizeof path);
    snprintf(args, sizeof args, "run %s --out %s", path, dir);
    const int strobe_code = run(args, out, sizeof out);
    char strobe[300], spectrum[300], lyapunov[300];
    snprintf(strobe, sizeof strobe, "%s/strobe-only-strobe.csv", dir);
    snprintf(spectrum, sizeof spectrum, "%s/strobe-only-spectrum.csv", dir);
    snprintf(lyapunov, sizeof lyapunov, "%s/strobe-only-lyapunov.csv", dir);
    gb_check cs = {"6", "73-74", "a scene asking only for the strobe writes only NAME-strobe.csv", "file system", "exact"};
    gb_check_true(&cs, strobe_code == 0 && access(strobe, F_OK) == 0 && access(spectrum, F_OK) != 0 && access(lyapunov, F_OK) != 0,
                  "exit %d: %.300s", strobe_code, out);
    remove(strobe);
    remove(path);
    snprintf(text, sizeof text, "[body]\nmorphology = II\nbeta = 0.12\n[integrator]\nsteps_per_period = 40\nperiods = 4\n"
                                "[model]\ncontact = fast-grid\n[lyapunov]\nbatches = 2\n");
    write_case(dir, "lyap", text, path, sizeof path);
    snprintf(args, sizeof args, "lyapunov %s --json", path);
    static char json[1 << 16];
    const int lcode = run(args, json, sizeof json);
    cJSON *root = cJSON_Parse(strchr(json, '{') ? strchr(json, '{') : json);
    static const char *keys[] = {"lambda_max", "error_bar", "periods", "delta0", "running"};
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++) {
        gb_check ck = {"6", "77", "gomboc lyapunov --json has the key", keys[k], "exact"};
        gb_check_true(&ck, lcode == 0 && root && cJSON_GetObjectItem(root, keys[k]), "exit %d: %.200s", lcode, json);
    }
    gb_check cr = {"6", "77", "gomboc lyapunov: running has one value per period, and ends at lambda_max", "its definition", "exact"};
    const cJSON *running = root ? cJSON_GetObjectItem(root, "running") : NULL;
    gb_check_true(&cr, running && cJSON_GetArraySize(running) == 4 &&
                       cJSON_GetNumberValue(cJSON_GetArrayItem(running, 3)) == number(root, "lambda_max"),
                  "%d values", running ? cJSON_GetArraySize(running) : -1);
    cJSON_Delete(root);
    remove(path);
    gb_check_tempdir_remove(dir);
}

/* The command's conventions: --version, --option=value as --option value, help TOPIC as TOPIC --help. */
static void test_conventions(void)
{
    static char a[1 << 16], b[1 << 16];
    int code = run("--version", a, sizeof a);
    gb_check cv = {"-", "-", "gomboc --version", "prints 'gomboc VERSION' and exits 0", "exact"};
    gb_check_true(&cv, code == 0 && !strncmp(a, "gomboc ", 7) && strlen(a) > 8, "exit %d: %.60s", code, a);
    const int c1 = run("shape --morphology=II --beta=0.02 --json", a, sizeof a);
    const int c2 = run("shape --morphology II --beta 0.02 --json", b, sizeof b);
    gb_check ce = {"-", "-", "gomboc shape --morphology=II --beta=0.02 against --morphology II --beta 0.02",
                   "the same output bytes and exit status", "exact"};
    gb_check_true(&ce, c1 == 0 && c2 == 0 && !strcmp(a, b), "exits %d and %d, %zu and %zu bytes", c1, c2, strlen(a), strlen(b));
    const int c3 = run("shape --beta=0.3 --morphology=I", a, sizeof a);
    gb_check cr = {"-", "-", "gomboc shape --beta=0.3", "refused as --beta 0.3 is: exit 2, naming --beta and its range", "exact"};
    gb_check_true(&cr, c3 == 2 && strstr(a, "--beta") && strstr(a, "0 <= beta < 0.25"), "exit %d: %.120s", c3, a);
    static const char *const topics[] = {"shape", "contact", "run", "lyapunov", "scan", "melnikov"};
    for (size_t k = 0; k < sizeof topics / sizeof topics[0]; k++) {
        char args[64];
        snprintf(args, sizeof args, "help %s", topics[k]);
        const int h1 = run(args, a, sizeof a);
        snprintf(args, sizeof args, "%s --help", topics[k]);
        const int h2 = run(args, b, sizeof b);
        char q[96];
        snprintf(q, sizeof q, "gomboc help %s against gomboc %s --help", topics[k], topics[k]);
        gb_check ch = {"-", "-", q, "the same text, exit 0", "exact"};
        gb_check_true(&ch, h1 == 0 && h2 == 0 && !strcmp(a, b), "exits %d and %d", h1, h2);
    }
    const int c4 = run("help bogus", a, sizeof a);
    gb_check cu = {"-", "-", "gomboc help bogus", "exit 2, listing the topics", "exact"};
    gb_check_true(&cu, c4 == 2 && strstr(a, "allowed: shape"), "exit %d: %.120s", c4, a);
}

/* docs/outputs.md's columns of `file` (its "### file" section, the first cell of each table row, every
 * table until the next section) as one comma-separated line; "" when the section is missing. */
static void documented_columns(const char *file, char *out, size_t size)
{
    out[0] = '\0';
    FILE *f = fopen("docs/outputs.md", "r");
    if (!f) return;
    char line[1024], heading[160];
    snprintf(heading, sizeof heading, "### %s\n", file);
    int inside = 0;
    size_t used = 0;
    while (fgets(line, sizeof line, f)) {
        if (!strncmp(line, "### ", 4)) inside = !strcmp(line, heading);
        if (!inside || strncmp(line, "| `", 3)) continue;
        const char *end = strchr(line + 3, '`');
        if (!end) continue;
        used += (size_t)snprintf(out + used, size - used, "%s%.*s", used ? "," : "", (int)(end - line - 3), line + 3);
        if (used >= size) break;
    }
    fclose(f);
}

/* The first line of `path` without its newline ("" when unreadable). */
static void header_of(const char *path, char *out, size_t size)
{
    out[0] = '\0';
    FILE *f = fopen(path, "r");
    if (f && fgets(out, (int)size, f)) out[strcspn(out, "\n")] = '\0';
    if (f) fclose(f);
}

/* Every CSV the command writes has its columns in docs/outputs.md, in order: a run that writes them all
 * (history, impacts, strobe, spectrum, λ and its windows) on a rough plane and one on a plane of finite
 * friction, and the scan's header from the library's own list. */
static void test_outputs_documented(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("columns", dir, sizeof dir)) return;
    static const char *const scene_text =
        "[body]\nmorphology = I\nbeta = 0.12\n[forcing]\nA1 = 19.62\nA2 = 9.81\n[integrator]\nsteps_per_period = 40\n"
        "periods = 8\nlocate_switches = yes\n[model]\ncontact = fast-grid\ncontact_law = unilateral\n%s"
        "[output]\nimpacts = yes\n[diagnostics]\nstrobe = yes\nspectrum = yes\nlyapunov = yes\n"
        "[strobe]\ntransient_periods = 0\n[spectrum]\ntransient_periods = 0\n[lyapunov]\nwindow_periods = 4\n";
    static const char *const files[] = {"history.csv", "impacts.csv", "strobe.csv", "spectrum.csv", "lyapunov.csv",
                                        "lyapunov-windows.csv"};
    char text[1024], path[300], args[800], out[1 << 12];
    for (int friction = 0; friction < 2; friction++) {
        const char *name = friction ? "mu" : "rough";
        snprintf(text, sizeof text, scene_text, friction ? "friction = 0.6\n" : "");
        write_case(dir, name, text, path, sizeof path);
        snprintf(args, sizeof args, "run %s --out %s", path, dir);
        const int code = run(args, out, sizeof out);
        for (size_t k = 0; k < sizeof files / sizeof files[0]; k++) {
            if (friction && k > 1) break; /* friction adds columns to the history and the impacts only */
            char file[300], written[2048], documented[2048], key[64];
            snprintf(file, sizeof file, "%s/%s-%s", dir, name, files[k]);
            header_of(file, written, sizeof written);
            snprintf(key, sizeof key, "NAME-%s", files[k]);
            documented_columns(key, documented, sizeof documented);
            /* a plane of finite friction: the section's two tables together; rough: the first table alone */
            if (!friction && (k == 0 || k == 1)) {
                const char *extra = k == 0 ? ",sliding,slip_speed" : ",slip_before_x";
                char *cut = strstr(documented, extra);
                if (cut) *cut = '\0';
            }
            char quantity[200];
            snprintf(quantity, sizeof quantity, "NAME-%s%s: every column in docs/outputs.md, in order", files[k],
                     friction ? " (friction = 0.6)" : "");
            gb_check c = {"8", "-", quantity, "the header gomboc run writes", "exact"};
            gb_check_true(&c, code == 0 && written[0] && !strcmp(written, documented), "exit %d; written '%.300s'; documented '%.300s'",
                          code, written, documented);
            remove(file);
        }
        remove(path);
        snprintf(path, sizeof path, "%s/%s-summary.json", dir, name);
        remove(path);
    }
    /* the scan: index, the two axes (documented as X and Y), the metrics from the library's list */
    char written[2048], documented[2048];
    snprintf(written, sizeof written, "index,X,Y,%s", gb_scan_csv_metric_columns());
    written[strcspn(written, "\n")] = '\0';
    documented_columns("NAME-scan.csv", documented, sizeof documented);
    gb_check cs = {"8", "-", "NAME-scan.csv: every column in docs/outputs.md, in order", "gb_scan's list of columns", "exact"};
    gb_check_true(&cs, !strcmp(written, documented), "written '%.300s'; documented '%.300s'", written, documented);
    gb_check_tempdir_remove(dir);
}

/* `gomboc help` names every command the program runs: each word a command accepts ("gomboc WORD --help"
 * answers with its own usage) appears in the list. */
/* gb_error_init_gsl and a host program's own GSL handler: the library's opt-in turns off only GSL's aborting
 * default, never a handler the host installed. The harness's own state (handler off) is restored after. */
static void host_handler(const char *reason, const char *file, int line, int gsl_errno)
{
    (void)reason, (void)file, (void)line, (void)gsl_errno;
}

static void test_gsl_handler_of_host(void)
{
    gsl_error_handler_t *saved = gsl_set_error_handler(host_handler);
    gb_error_init_gsl();
    gsl_error_handler_t *kept = gsl_set_error_handler(NULL); /* GSL's default: abort */
    gb_error_init_gsl();
    gsl_error_handler_t *replaced = gsl_set_error_handler(saved);
    gb_check c = {"-", "-", "gb_error_init_gsl with a host's own GSL handler installed, and with GSL's default",
                  "the host's handler left in place; GSL's aborting default turned off (a handler that is not NULL)", "exact"};
    gb_check_true(&c, kept == host_handler && replaced != NULL && replaced != host_handler, "kept %s, default %s",
                  kept == host_handler ? "the host's" : "ANOTHER", replaced ? "turned off" : "LEFT TO ABORT");
}

static void test_help_lists_commands(void)
{
    static char list[1 << 13], usage[1 << 13];
    const int code = run("help", list, sizeof list);
    static const char *const words[] = {"shape", "contact", "run", "lyapunov", "scan", "melnikov", "check", "prove"};
    int listed = 0, runnable = 0;
    char missing[256] = "";
    for (size_t k = 0; k < sizeof words / sizeof words[0]; k++) {
        char args[64], entry[64];
        snprintf(args, sizeof args, "%s --help", words[k]);
        runnable += run(args, usage, sizeof usage) == 0 && strstr(usage, "usage: gomboc ") != NULL;
        snprintf(entry, sizeof entry, "\n  %s ", words[k]);
        if (strstr(list, entry)) listed++;
        else snprintf(missing + strlen(missing), sizeof missing - strlen(missing), " %s", words[k]);
    }
    gb_check c = {"-", "-", "gomboc help: every command the program runs is listed", "each command's own --help", "exact"};
    gb_check_true(&c, code == 0 && listed == runnable && runnable == (int)(sizeof words / sizeof words[0]),
                  "%d of %d commands run, %d listed; missing:%s", runnable, (int)(sizeof words / sizeof words[0]), listed,
                  missing[0] ? missing : " none");
}

int verify_register_command(void)
{
    static const verify_test tests[] = {
        {"command: JSON keys, verdicts and determinism", test_json_keys_and_determinism, NULL},
        {"command: atomic output", test_failed_write_leaves_nothing, NULL},
        {"command: gomboc contact, its methods and keys", test_contact_command, NULL},
        {"command: gomboc run, case files and outputs", test_run_command, NULL},
        {"command: gomboc run without --hull: the hull in the user's cache", test_run_cache,
         "the fast grid's hull is built once per body and read from the user's cache by every later run, with the same bits"},
        {"command: gomboc run: the mass properties in the user's cache", test_run_massprops_cache,
         "the paper's bodies' mass properties are computed once and read back sealed from the user's cache, with the same "
         "bits; a changed file is not read"},
        {"command: gomboc run: the atlas of verticals in the user's cache", test_run_atlas_cache,
         "a certificate = atlas run's cells are proved once per body and read back from the user's cache, with the same bits"},
        {"command: gomboc run --hull, the fast grid's hull from its file", test_run_hull,
         "a fast-grid run gives the same state bits with the hull Qhull builds and with the hull read from "
         "its file, and a damaged file is built anew"},
        {"command: gomboc help lists every command", test_help_lists_commands, NULL},
        {"library: gb_error_init_gsl leaves a host's own GSL handler in place", test_gsl_handler_of_host, NULL},
        {"command: every CSV column documented", test_outputs_documented,
         "every column of every CSV the command writes is in docs/outputs.md, with its unit, in the header's order"},
        {"command: --version, --option=value, help TOPIC", test_conventions,
         "the command follows the usual conventions: a version, options written either way, help by topic"},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("The gomboc command", tests);
}
