/* Reports: every figure drawn from the data it names, in this run.
 *
 * - reports/run_report.py on two shipped scenes (Table 1's Gömböc I with Figs 7-9, Housner's block under the
 *   unilateral law): every number a figure's title quotes is the summary's (λ_max and its error bar to the
 *   three decimals printed, the strobe's samples, the count of impacts or grid-node changes), Fig 9's bold
 *   curve ends at the quoted λ_max, every figure the manifest lists exists and the page links exactly those,
 *   and a figure of an earlier run (a Fig 9 the block never asked for, planted) is removed and not linked;
 * - reports/animate.py on Table 1's Gömböc I under the unilateral law: every frame's attitude is R(q) of its
 *   history row, its contact point is R r_c lifted by ζ and lies on the plane, and the lowest point of the
 *   drawn surface touches the plane beside it (to the radial map's sampling); the contact marker's colour is on the
 *   image where the point lands (drawn over the body, never hidden by it);
 * - the same for a mesh body (the die, from its hull's faces) and an expression body (an egg), and a GIF's frame
 *   times against the rate asked (its delays in hundredths of a second, rounded so as not to drift).
 * - every figure of those runs and Fig 1 measured on matplotlib's renderer as a reader sees it (no data under a
 *   legend, no marker cut by an axes' edge, nothing within 3 pixels of anything else, whole ticks on an index,
 *   every axes labelled), and the paper's figure numbers in the titles; a λ map's points whose sign is not known
 *   dotted, counted against the CSV;
 * The commands run in a directory of their own under TMPDIR (/tmp when unset). */
#include "gb_check.h"
#include "gb_dynamics.h"
#include "verify_sections.h"

#include <cjson/cJSON.h>
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *gomboc(void) { return getenv("GOMBOC_BIN") ? getenv("GOMBOC_BIN") : "build/gomboc"; }

/* DIR/NAME read whole (malloc'd, NULL when unreadable), and parsed as JSON. */
static char *read_text(const char *dir, const char *name)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return gb_check_read_file(path);
}

static cJSON *read_json(const char *dir, const char *name)
{
    char *text = read_text(dir, name);
    cJSON *json = text ? cJSON_Parse(text) : NULL;
    free(text);
    return json;
}

static double number(const cJSON *o, const char *a, const char *b)
{
    const cJSON *v = cJSON_GetObjectItem(o, a);
    if (b) v = cJSON_GetObjectItem(v, b);
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

/* The number after `mark` in `title` (NAN when absent). */
static double after(const char *title, const char *mark)
{
    const char *at = title ? strstr(title, mark) : NULL;
    return at ? strtod(at + strlen(mark), NULL) : NAN;
}

/* The number before the last `mark` in `title` (the title's own numbers follow the scene's description): the
 * digits that end where mark begins. */
static double before(const char *title, const char *mark)
{
    const char *at = NULL;
    for (const char *p = title; p && (p = strstr(p, mark)); p++) at = p;
    if (!at) return NAN;
    const char *p = at;
    while (p > title && (p[-1] == '.' || (p[-1] >= '0' && p[-1] <= '9'))) p--;
    return p < at ? strtod(p, NULL) : NAN;
}

/* Run a reports/ script (its arguments in `args`) and record that it ran; 0 when it did. */
static int script(const char *args, const char *what, char *out, size_t cap)
{
    const int code = gb_check_command("/usr/bin/python3", args, out, cap);
    gb_check ran = {"-", "-", what, "exit 0", "exact"};
    gb_check_true(&ran, code == 0, "exit %d: %.300s", code, out);
    return code;
}

/* The layout facts a figure's manifest entry carries (reports/common.py layout_facts): each fault counted, the
 * first named. */
typedef struct layout_count {
    int figures, faults;
    char first[300];
} layout_count;

static void layout_tally(const cJSON *fig, const char *file, layout_count *count)
{
    const cJSON *layout = cJSON_GetObjectItem(fig, "layout");
    if (!cJSON_IsObject(layout)) return;
    count->figures++;
    static const char *const keys[] = {"legend_points_covered", "markers_outside_axes", "overlapping", "fractional_index_ticks",
                                       "unlabelled_axes"};
    int faults = 0;
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++) {
        const double v = number(layout, keys[k], NULL);
        faults += isnan(v) ? 1 : (int)v;
    }
    count->faults += faults;
    if (faults && !count->first[0])
        snprintf(count->first, sizeof count->first, "%s: %s", file,
                 cJSON_GetStringValue(cJSON_GetArrayItem(cJSON_GetObjectItem(layout, "where"), 0)) ?: "a fact missing");
}

static void test_figures(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("figures", dir, sizeof dir)) return;
    char args[1024], out[8192];
    int code = 0;
    static const char *const scenes[2] = {"cases/table1-gomboc-I.ini", "cases/bodies/housner-block.ini"};
    for (int k = 0; k < 2 && !code; k++) {
        snprintf(args, sizeof args, "run %s --out %s", scenes[k], dir);
        code = gb_check_command(gomboc(), args, out, sizeof out);
    }
    char stale[600], users[600], manifest[600];
    snprintf(stale, sizeof stale, "%s/fig9-lyapunov-housner-block.png", dir);
    snprintf(users, sizeof users, "%s/fig7-strobe-housner-block.png", dir);
    snprintf(manifest, sizeof manifest, "%s/housner-block-figures.json", dir);
    /* an earlier run's figure, which its manifest lists and this run of the block does not draw; and a user's file
     * named like a figure this script could draw, which no manifest of it lists */
    FILE *f = fopen(stale, "w");
    if (f) fputs("not a figure of this run", f), fclose(f);
    f = fopen(users, "w");
    if (f) fputs("a user's own file", f), fclose(f);
    f = fopen(manifest, "w");
    if (f) fputs("{\"scene\": \"housner-block\", \"figures\": [{\"kind\": \"fig9-lyapunov\", \"file\": "
                 "\"fig9-lyapunov-housner-block.png\"}, {\"kind\": \"x\", \"file\": \"../outside.png\"}]}", f), fclose(f);
    gb_check runs = {"-", "-", "gomboc run on table1-gomboc-I and housner-block", "exit 0", "exact"};
    gb_check_true(&runs, code == 0, "exit %d: %.300s", code, out);
    snprintf(args, sizeof args, "reports/run_report.py %s table1-gomboc-I housner-block --page page.md", dir);
    if (code || script(args, "run_report.py on table1-gomboc-I and housner-block", out, sizeof out)) {
        gb_check_tempdir_remove(dir);
        return;
    }
    cJSON *s1 = read_json(dir, "table1-gomboc-I-summary.json"), *s2 = read_json(dir, "housner-block-summary.json");
    cJSON *m1 = read_json(dir, "table1-gomboc-I-figures.json"), *m2 = read_json(dir, "housner-block-figures.json");
    char *page = read_text(dir, "page.md");
    int kinds = 0, listed = 0, linked = 0, present = 0, numbered = 0;
    layout_count layout = {0};
    double lam_title = NAN, err_title = NAN, curve_end = NAN, samples_title = NAN, switches_title = NAN, impacts_title = NAN;
    const cJSON *manifests[2] = {m1, m2};
    for (int k = 0; k < 2; k++) {
        const cJSON *fig;
        cJSON_ArrayForEach(fig, cJSON_GetObjectItem(manifests[k], "figures")) {
            const char *kind = cJSON_GetStringValue(cJSON_GetObjectItem(fig, "kind"));
            const char *file = cJSON_GetStringValue(cJSON_GetObjectItem(fig, "file"));
            const char *title = cJSON_GetStringValue(cJSON_GetObjectItem(fig, "title"));
            if (!kind || !file) continue;
            listed++;
            layout_tally(fig, file, &layout);
            if (title && !strcmp(kind, "fig-timeseries")) numbered += k == 0 ? !strncmp(title, "Fig 3: ", 7) : !strstr(title, "Fig ");
            if (title && !strcmp(kind, "fig-contact")) numbered += k == 0 ? !strncmp(title, "Fig 4: ", 7) : !strstr(title, "Fig ");
            char path[700], link[700];
            snprintf(path, sizeof path, "%s/%s", dir, file);
            present += access(path, R_OK) == 0;
            snprintf(link, sizeof link, "(%s)", file);
            linked += page && strstr(page, link) != NULL;
            if (k == 0 && !strcmp(kind, "fig9-lyapunov")) {
                kinds |= 1;
                lam_title = after(title, "λ_max = "), err_title = after(title, "± ");
                curve_end = number(fig, "curve_end", NULL);
            } else if (k == 0 && !strcmp(kind, "fig7-strobe")) {
                kinds |= 2;
                samples_title = after(title, "(");
            } else if (k == 0 && !strcmp(kind, "fig-timeseries")) {
                kinds |= 4;
                switches_title = before(title, " grid-node changes");
            } else if (k == 1 && !strcmp(kind, "fig-timeseries")) {
                kinds |= 8;
                impacts_title = before(title, " impacts");
            } else if (!strcmp(kind, "fig8-spectrum") || !strcmp(kind, "fig-contact")) {
                kinds |= !strcmp(kind, "fig8-spectrum") ? 16 : 32;
            }
        }
    }
    const double lam = number(s1, "lyapunov", "lambda_max"), err = number(s1, "lyapunov", "error_bar");
    gb_check c9 = {"8.2", "77", "Fig 9's title: lambda_max and its error bar, as printed (3 decimals)", "the summary's lambda_max, error_bar",
                   "5e-4: the title's rounding to 3 decimals"};
    gb_check_close(&c9, lam_title, lam, 0.0, 5.000001e-4);
    gb_check_close(&c9, err_title, err, 0.0, 5.000001e-4);
    gb_check ce = {"8.2", "77", "Fig 9's bold curve (the running mean after the warm-up): its last value", "the quoted lambda_max",
                   "1e-9 relative: the mean of the same intervals summed in another order"};
    gb_check_close(&ce, curve_end, lam, 1e-9, 0.0);
    gb_check c7 = {"8.1", "73", "Fig 7's title: the strobe's samples", "the summary's strobe samples", "exact"};
    gb_check_close(&c7, samples_title, number(s1, "strobe", "samples"), 0.0, 0.0);
    gb_check ct = {"-", "-", "the time series' titles: grid-node changes (held law), impacts (unilateral law)",
                   "the summary's grid_switches, impacts.count", "exact"};
    gb_check_close(&ct, switches_title, number(s1, "grid_switches", NULL), 0.0, 0.0);
    gb_check_close(&ct, impacts_title, number(s2, "impacts", "count"), 0.0, 0.0);
    gb_check cf = {"-", "-", "every figure kind drawn, every figure the manifest lists present and linked, and only those",
                   "6 kinds; listed = present = linked = the page's figure links", "exact"};
    int page_links = 0;
    for (const char *p = page; p && (p = strstr(p, "](")); p += 2) page_links++;
    gb_check_true(&cf, kinds == 63 && listed == present && listed == linked && page_links == listed,
                  "kinds %#x, %d listed, %d present, %d linked, %d links on the page", kinds, listed, present, linked, page_links);
    gb_check cl = {"-", "-", "what a reader sees of every figure of table1-gomboc-I and housner-block, measured on matplotlib's "
                   "renderer: data under a legend, markers at or beyond an axes' edge, axes, colour bars or legends within 3 "
                   "pixels of each other, fractional ticks on a grid index, unlabelled axes",
                   "none of each", "exact"};
    gb_check_true(&cl, layout.figures == listed && listed > 0 && layout.faults == 0, "%d of %d figures measured, %d faults%s%s",
                  layout.figures, listed, layout.faults, layout.first[0] ? ": " : "", layout.first);
    gb_check cn = {"-", "-", "the paper's figure numbers in the titles: Table 1's time series and contact figures, and a still "
                   "plane's", "Fig 3 and Fig 4 (biharmonic forcing, as the paper numbers them); no number for the block", "exact"};
    gb_check_true(&cn, numbered == 4, "%d of 4 titles numbered so", numbered);
    gb_check cs = {"-", "-", "a figure of an earlier run (a Fig 9 the block's run did not draw, listed in its previous "
                   "NAME-figures.json), and a user's file named like a Fig 7 of the block, which no manifest lists",
                   "the earlier figure removed and not linked; the user's file left as it was", "exact"};
    char *kept = gb_check_read_file(users);
    gb_check_true(&cs, access(stale, F_OK) != 0 && page && !strstr(page, "fig9-lyapunov-housner-block") && kept &&
                       !strcmp(kept, "a user's own file"),
                  "earlier figure %s; user's file %s", access(stale, F_OK) == 0 ? "still there" : "removed",
                  kept ? "kept" : "REMOVED");
    free(kept);
    /* a number of 15 significant digits or more on the page is a double printed whole (17 digits), unrounded */
    int long_numbers = 0;
    char first_long[64] = "";
    for (const char *p = page; p && *p; p++) {
        if (!isdigit((unsigned char)*p) || (p > page && (isdigit((unsigned char)p[-1]) || p[-1] == '.'))) continue;
        int digits = 0, dots = 0;
        const char *q = p;
        for (; isdigit((unsigned char)*q) || (*q == '.' && !dots++ && isdigit((unsigned char)q[1])); q++) digits += *q != '.';
        if (digits >= 15 && !long_numbers++) snprintf(first_long, sizeof first_long, "%.*s", (int)(q - p < 40 ? q - p : 40), p);
    }
    gb_check cd = {"-", "-", "the run pages of table1-gomboc-I and housner-block: numbers of 15 significant digits or more",
                   "none: every number is rounded to what it means (a double printed whole has 17 digits)", "exact"};
    gb_check_true(&cd, page && long_numbers == 0, "%d such numbers%s%s", long_numbers, long_numbers ? ", the first " : "",
                  first_long);
    cJSON_Delete(s1), cJSON_Delete(s2), cJSON_Delete(m1), cJSON_Delete(m2);
    free(page);
    gb_check_tempdir_remove(dir);
}

/* The report writers against bad input: a malformed CSV is one line naming the file, row and column, exit 2,
 * never a traceback; a link at an output's name is replaced, never written through. */
static void test_writers_bad_input(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("writers", dir, sizeof dir)) return;
    char args[1024], out[8192], path[700];
    snprintf(args, sizeof args, "run cases/bodies/housner-block.ini --out %s", dir);
    const int ran = gb_check_command(gomboc(), args, out, sizeof out);
    snprintf(path, sizeof path, "%s/housner-block-history.csv", dir);
    char *history = gb_check_read_file(path);
    const char *body = history ? strchr(history, '\n') : NULL;
    static const struct {
        const char *what, *file, *text, *script, *expect;
    } cases[] = {
        {"a history without its 'contacts' column", "housner-block-history.csv", "t,omega_x\n0,1\n", "run_report.py @D@ housner-block",
         "housner-block-history.csv:1: no column 'contacts'"},
        {"a history of its header alone", "housner-block-history.csv", "@HEADER@", "run_report.py @D@ housner-block",
         "housner-block-history.csv:2: no rows after the header"},
        {"a scan CSV whose axis holds inf", "a-scan.csv", "index,forcing.omega,forcing.A1,omega_rms\n0,inf,1,0.5\n1,2,1,0.6\n",
         "plot_scan.py @D@/a-scan.csv", "a-scan.csv:2: column 'forcing.omega': inf is not a finite number"},
        {"a scan CSV whose axis spans -1e308 .. 1e308", "b-scan.csv", "index,forcing.omega,forcing.A1,omega_rms\n0,1e308,1,0.5\n1,-1e308,1,0.6\n",
         "plot_scan.py @D@/b-scan.csv", "beyond the range of a double"},
        {"a scan CSV whose axis holds NaN", "c-scan.csv", "index,forcing.omega,forcing.A1,omega_rms\n0,nan,1,0.5\n",
         "plot_scan.py @D@/c-scan.csv", "c-scan.csv:2: column 'forcing.omega': nan is not a finite number"},
        {"a scan CSV with a short row", "d-scan.csv", "index,forcing.omega,forcing.A1,omega_rms\n0,1,1\n", "plot_scan.py @D@/d-scan.csv",
         "d-scan.csv:2: 3 values where the header names 4 columns"},
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        snprintf(path, sizeof path, "%s/%s", dir, cases[k].file);
        FILE *f = fopen(path, "w");
        if (f && !strcmp(cases[k].text, "@HEADER@") && history && body) fwrite(history, 1, (size_t)(body - history + 1), f);
        else if (f) fputs(cases[k].text, f);
        if (f) fclose(f);
        char script_args[800];
        const char *at = strstr(cases[k].script, "@D@");
        snprintf(script_args, sizeof script_args, "reports/%.*s%s%s", (int)(at - cases[k].script), cases[k].script, dir, at + 3);
        const int code = gb_check_command("/usr/bin/python3", script_args, out, sizeof out);
        char q[200];
        snprintf(q, sizeof q, "%s of %s", strchr(cases[k].script, ' ') ? "a report writer" : cases[k].script, cases[k].what);
        gb_check c = {"-", "-", q, "exit 2, one line naming the file, the row and the column, no traceback", "exact"};
        const char *mark = strstr(out, "@@exit="), *first_end = strchr(out, '\n'); /* the writer's output, then the status */
        gb_check_true(&c, ran == 0 && code == 2 && strstr(out, cases[k].expect) && !strstr(out, "Traceback") && mark &&
                          first_end && first_end + 1 == mark,
                      "exit %d: %.400s", code, out);
        if (history && !strcmp(cases[k].file, "housner-block-history.csv")) { /* the run's own history back */
            f = fopen(path, "w");
            if (f) fputs(history, f), fclose(f);
        }
    }
    /* --help: the script's text, its usage with its name in it, on standard output, exit 0 (not a file named --help) */
    static const char *const scripts[] = {"plot_scan.py", "run_report.py", "animate.py"};
    for (size_t k = 0; k < sizeof scripts / sizeof scripts[0]; k++) {
        char script_args[200], q[120];
        snprintf(script_args, sizeof script_args, "reports/%s --help", scripts[k]);
        const int code = gb_check_command("/usr/bin/python3", script_args, out, sizeof out);
        snprintf(q, sizeof q, "%s --help", scripts[k]);
        gb_check ch = {"-", "-", q, "exit 0 with the script's usage naming it, no traceback", "exact"};
        gb_check_true(&ch, code == 0 && strstr(out, scripts[k]) && !strstr(out, "Traceback"), "exit %d: %.200s", code, out);
    }
    /* a link at plot_scan's output name: replaced by the figure, the file it pointed at left as it was */
    snprintf(path, sizeof path, "%s/e-scan.csv", dir);
    FILE *f = fopen(path, "w");
    if (f) fputs("index,forcing.omega,forcing.A1,omega_rms\n0,1,1,0.5\n1,2,1,0.7\n", f), fclose(f);
    char target[700], link[700];
    snprintf(target, sizeof target, "%s/keep.txt", dir);
    snprintf(link, sizeof link, "%s/e-scan-omega_rms.png", dir);
    f = fopen(target, "w");
    if (f) fputs("keep", f), fclose(f);
    const int linked = symlink("keep.txt", link);
    snprintf(args, sizeof args, "reports/plot_scan.py %s", path);
    const int code = gb_check_command("/usr/bin/python3", args, out, sizeof out);
    char *kept = gb_check_read_file(target);
    struct stat st;
    const int replaced = lstat(link, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 1000;
    gb_check cl = {"-", "-", "plot_scan.py whose output name is a symbolic link to another file",
                   "the link replaced by the figure (an atomic rename), the file it pointed at unchanged", "exact"};
    gb_check_true(&cl, linked == 0 && code == 0 && replaced && kept && !strcmp(kept, "keep"), "exit %d, %s, target %s: %.200s", code,
                  replaced ? "replaced" : "not replaced", kept && !strcmp(kept, "keep") ? "unchanged" : "CHANGED", out);
    free(kept), free(history);
    gb_check_tempdir_remove(dir);
}

/* ---- the animation ---------------------------------------------------------------------------------- */

enum { COLUMNS = 40 };

/* The history's columns by name, the data rows kept as text lines. */
typedef struct history {
    char *text;
    char **rows;
    size_t count;
    char names[COLUMNS][24];
    int columns;
} history;

static int history_read(const char *dir, const char *name, history *h)
{
    memset(h, 0, sizeof *h);
    char file[300];
    snprintf(file, sizeof file, "%s-history.csv", name);
    h->text = read_text(dir, file);
    if (!h->text) return -1;
    size_t lines = 0;
    for (const char *p = h->text; *p; p++) lines += *p == '\n';
    h->rows = calloc(lines + 1, sizeof *h->rows);
    char *save = NULL, *line = strtok_r(h->text, "\n", &save);
    for (char *col = line; col && h->columns < COLUMNS;) { /* the header */
        char *comma = strchr(col, ',');
        snprintf(h->names[h->columns++], sizeof h->names[0], "%.*s", comma ? (int)(comma - col) : (int)strlen(col), col);
        col = comma ? comma + 1 : NULL;
    }
    while ((line = strtok_r(NULL, "\n", &save))) h->rows[h->count++] = line;
    return 0;
}

static double history_value(const history *h, size_t row, const char *column)
{
    int c = 0;
    while (c < h->columns && strcmp(h->names[c], column)) c++;
    if (c == h->columns || row >= h->count) return NAN;
    const char *p = h->rows[row];
    for (int k = 0; k < c && p; k++) p = strchr(p, ','), p = p ? p + 1 : NULL;
    return p ? strtod(p, NULL) : NAN;
}

/* Of the frames of an animation's manifest that draw a contact point, how many show the marker's colour where the
 * point lands on the image (within 40 of 255 a channel: antialiasing at the marker's rim), and the worst distance. */
static void contact_shown(const cJSON *a, int *with, int *shown, double *worst)
{
    *with = *shown = 0, *worst = 0.0;
    const cJSON *marker = cJSON_GetObjectItem(a, "marker_colour"), *fr;
    cJSON_ArrayForEach(fr, cJSON_GetObjectItem(a, "frames")) {
        if (!cJSON_IsArray(cJSON_GetObjectItem(fr, "contact_drawn"))) continue;
        const cJSON *colour = cJSON_GetObjectItem(fr, "contact_colour");
        double d = INFINITY;
        if (cJSON_GetArraySize(colour) == 3 && cJSON_GetArraySize(marker) == 3) {
            d = 0.0;
            for (int i = 0; i < 3; i++)
                d = fmax(d, fabs(cJSON_GetArrayItem(colour, i)->valuedouble - cJSON_GetArrayItem(marker, i)->valuedouble));
        }
        (*with)++, *shown += d <= 40.0, *worst = fmax(*worst, d);
    }
}

/* A GIF's frame delays read back: the largest |Σ_{j<k} delay_j − 1000 k / fps| [ms] (0 for an MP4, whose rate is
 * exact; -1 when the manifest has neither). */
static double delay_drift(const cJSON *a, int *frames)
{
    const cJSON *delays = cJSON_GetObjectItem(a, "delays_ms");
    const double fps = number(a, "fps", NULL);
    *frames = cJSON_GetArraySize(delays);
    if (cJSON_IsNull(delays)) return 0.0;
    if (!cJSON_IsArray(delays) || !(fps > 0)) return -1.0;
    double sum = 0.0, drift = 0.0;
    int k = 0;
    const cJSON *d;
    cJSON_ArrayForEach(d, delays) sum += d->valuedouble, k++, drift = fmax(drift, fabs(sum - 1000.0 * k / fps));
    return drift;
}

static void test_animation(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("animation", dir, sizeof dir)) return;
    char args[1024], out[8192];
    snprintf(args, sizeof args, "run cases/table1-gomboc-I-unilateral.ini --out %s", dir);
    int code = gb_check_command(gomboc(), args, out, sizeof out);
    if (!code) {
        snprintf(args, sizeof args, "shape --scene cases/table1-gomboc-I-unilateral.ini --json --radial-map %s/map.csv > /dev/null", dir);
        code = gb_check_command(gomboc(), args, out, sizeof out);
    }
    gb_check runs = {"-", "-", "gomboc run and shape --scene on table1-gomboc-I-unilateral", "exit 0", "exact"};
    gb_check_true(&runs, code == 0, "exit %d: %.300s", code, out);
    /* files of the animation's names that no manifest of animate.py lists: a user's, left alone */
    char own_mp4[600], own_gif[600];
    snprintf(own_mp4, sizeof own_mp4, "%s/table1-gomboc-I-unilateral-animation.mp4", dir);
    snprintf(own_gif, sizeof own_gif, "%s/table1-gomboc-I-unilateral-animation.gif", dir);
    const int has_ffmpeg = system("command -v ffmpeg > /dev/null 2>&1") == 0;
    FILE *planted = fopen(has_ffmpeg ? own_gif : own_mp4, "w"); /* the format this machine's animate.py does not draw */
    if (planted) fputs("a user's own file", planted), fclose(planted);
    snprintf(args, sizeof args, "reports/animate.py %s table1-gomboc-I-unilateral --surface %s/map.csv --seconds 1 --fps 10", dir, dir);
    if (code || script(args, "animate.py on table1-gomboc-I-unilateral (1 s, 10 frames a second)", out, sizeof out)) {
        gb_check_tempdir_remove(dir);
        return;
    }
    char *kept = gb_check_read_file(has_ffmpeg ? own_gif : own_mp4);
    gb_check ck = {"-", "-", "animate.py beside a user's file named like its other format's output, which no manifest of it lists",
                   "the user's file left as it was", "exact"};
    gb_check_true(&ck, kept && !strcmp(kept, "a user's own file"), "%s", kept ? "kept" : "REMOVED");
    free(kept);
    cJSON *a = read_json(dir, "table1-gomboc-I-unilateral-animation.json");
    history h;
    const int read = history_read(dir, "table1-gomboc-I-unilateral", &h);
    double worst_R = 0.0, worst_p = 0.0, worst_plane = 0.0, lowest_max = -INFINITY, lowest_min = INFINITY, apart = 0.0;
    int frames = 0;
    const cJSON *fr;
    cJSON_ArrayForEach(fr, cJSON_GetObjectItem(a, "frames")) {
        const size_t row = (size_t)number(fr, "row", NULL);
        const double q[4] = {history_value(&h, row, "q_w"), history_value(&h, row, "q_x"), history_value(&h, row, "q_y"),
                             history_value(&h, row, "q_z")};
        double R[9];
        gb_dynamics_rotation(q, R);
        const cJSON *Rd = cJSON_GetObjectItem(fr, "R");
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                const double v = cJSON_GetArrayItem(cJSON_GetArrayItem(Rd, i), j)->valuedouble;
                worst_R = fmax(worst_R, isnan(v) ? INFINITY : fabs(v - R[3 * i + j]));
            }
        const double rc[3] = {history_value(&h, row, "rc_x"), history_value(&h, row, "rc_y"), history_value(&h, row, "rc_z")};
        const double zeta = history_value(&h, row, "zeta"), clearance = history_value(&h, row, "clearance");
        const cJSON *drawn = cJSON_GetObjectItem(fr, "contact_drawn"), *low = cJSON_GetObjectItem(fr, "lowest_drawn");
        double p[3];
        for (int i = 0; i < 3; i++) p[i] = R[3 * i] * rc[0] + R[3 * i + 1] * rc[1] + R[3 * i + 2] * rc[2] + (i == 2 ? zeta : 0.0);
        if (cJSON_IsArray(drawn))
            for (int i = 0; i < 3; i++) worst_p = fmax(worst_p, fabs(cJSON_GetArrayItem(drawn, i)->valuedouble - p[i]));
        worst_plane = fmax(worst_plane, fabs(p[2] - clearance));
        const double lz = cJSON_GetArrayItem(low, 2)->valuedouble;
        lowest_max = fmax(lowest_max, lz - clearance), lowest_min = fmin(lowest_min, lz - clearance);
        apart = fmax(apart, hypot(cJSON_GetArrayItem(low, 0)->valuedouble - p[0], cJSON_GetArrayItem(low, 1)->valuedouble - p[1]));
        frames++;
    }
    gb_check cn = {"-", "-", "the animation's frames read back with their history rows", "10 frames", "exact"};
    gb_check_true(&cn, a && !read && frames == 10, "%d frames", frames);
    gb_check cr = {"5", "-", "each frame's attitude against R(q) of its history row (max |R_drawn - R(q)|)", "0",
                   "1e-12: the same formula in Python and C on the same printed q"};
    gb_check_close(&cr, worst_R, 0.0, 0.0, 1e-12);
    gb_check cp = {"5", "-", "each frame's contact point against R r_c + zeta e_z from its row [m]", "0", "1e-12: the same"};
    gb_check_close(&cp, worst_p, 0.0, 0.0, 1e-12);
    gb_check cz = {"5", "-", "each frame's contact point: its height above the plane minus the row's clearance [m]", "0 (on the plane)",
                   "1e-9 m: the history's printed digits (12 significant)"};
    gb_check_close(&cz, worst_plane, 0.0, 0.0, 1e-9);
    gb_check cl = {"5", "-", "the drawn surface's lowest point: height above the plane [m], highest over the frames",
                   "0, the sampled surface's lowest point just above the contact",
                   "1e-3 m: a 90 x 180 midpoint sample misses the true minimum by up to r (pi/90)^2 / 2 ~ 1.7e-3 m, curvature allowing"};
    gb_check_close(&cl, lowest_max, 0.0, 0.0, 1e-3);
    gb_check cb = {"5", "-", "the drawn surface never dips below the plane (lowest height over the frames) [m]", ">= 0",
                   "1e-9 m: the printed digits"};
    gb_check_true(&cb, lowest_min >= -1e-9, "lowest %.3g m", lowest_min);
    gb_check ca = {"5", "-", "the drawn lowest point beside the contact point (horizontal distance) [m]", "0",
                   "0.06 m: a cell of the 90 x 180 sample at r <= 1.1 spans 1.1 pi/90 = 0.038 m"};
    gb_check_close(&ca, apart, 0.0, 0.0, 0.06);
    int with, shown;
    double worst;
    contact_shown(a, &with, &shown, &worst);
    gb_check cv = {"5", "-", "the contact point visible: the marker's colour where the point lands in each frame that draws it",
                   "tab:red (214, 39, 40)", "40 of 255 a channel (the marker's antialiased rim); drawn after the body, not hidden by it"};
    gb_check_true(&cv, with > 0 && shown == with, "%d of %d frames show it (worst channel distance %.0f)", shown, with, worst);
    cJSON_Delete(a);
    free(h.text), free(h.rows);
    gb_check_tempdir_remove(dir);
}

/* Fig 1 (reports/shape_report.py) measured as a reader sees it; and a scan's λ map saying where its sign is not
 * known (reports/plot_scan.py: a dot where |λ| ≤ 2 lambda_error), counted against the CSV it was drawn from. */
static void test_figure_one_and_maps(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("figure-one", dir, sizeof dir)) return;
    char args[1024], out[8192];
    snprintf(args, sizeof args, "shape --scene cases/table1-gomboc-I.ini --json --radial-map %s/radial-map-table1-gomboc-I.csv "
             "> %s/shape-table1-gomboc-I.json", dir, dir);
    int code = gb_check_command(gomboc(), args, out, sizeof out);
    gb_check ran = {"-", "-", "gomboc shape --scene table1-gomboc-I with its radial map", "exit 0", "exact"};
    gb_check_true(&ran, code == 0, "exit %d: %.300s", code, out);
    snprintf(args, sizeof args, "reports/shape_report.py %s table1-gomboc-I", dir);
    if (!code && !script(args, "shape_report.py on table1-gomboc-I (Fig 1)", out, sizeof out)) {
        cJSON *m = read_json(dir, "shape-figures.json");
        layout_count layout = {0};
        const cJSON *fig;
        cJSON_ArrayForEach(fig, cJSON_GetObjectItem(m, "figures")) layout_tally(fig, "fig1-morphologies.png", &layout);
        gb_check c = {"2", "1-9", "Fig 1 as a reader sees it: its 3-D surface's axis labels, its colour bars and its radial map",
                      "nothing within 3 pixels of anything else, every axes labelled", "exact"};
        gb_check_true(&c, layout.figures == 1 && layout.faults == 0, "%d figure measured, %d faults%s%s", layout.figures, layout.faults,
                      layout.first[0] ? ": " : "", layout.first);
        cJSON_Delete(m);
    }
    /* a 4 x 3 map whose λ and error bars are known here: |λ| <= 2 err at the points so marked */
    static const double lam[12] = {0.4137, 0.0213, -0.2385, 0.1812, -0.0461, 0.7329, 0.0987, -0.5126, 0.2764, 0.0049, -0.1953, 0.3318};
    static const double err[12] = {0.0521, 0.0344, 0.0917, 0.0948, 0.0386, 0.1102, 0.0391, 0.0645, 0.1873, 0.0122, 0.0911, 0.0407};
    char text[2048];
    size_t used = (size_t)snprintf(text, sizeof text, "index,forcing.omega,forcing.A1,lambda_max,lambda_error\n");
    int unsure = 0;
    for (int k = 0; k < 12; k++) {
        used += (size_t)snprintf(text + used, sizeof text - used, "%d,%g,%g,%.4f,%.4f\n", k, 2.0 + k % 4, 1.0 + k / 4, lam[k], err[k]);
        unsure += !(fabs(lam[k]) > 2.0 * err[k]);
    }
    char csv[300];
    snprintf(csv, sizeof csv, "%s/map-scan.csv", dir);
    FILE *f = fopen(csv, "w");
    if (f) fputs(text, f), fclose(f);
    snprintf(args, sizeof args, "reports/plot_scan.py %s lambda_max lambda_error 2>&1", csv); /* its note on standard error */
    if (!script(args, "plot_scan.py on a 4 x 3 map of lambda_max and lambda_error", out, sizeof out)) {
        const char *said = strstr(out, "lambda_max: ");
        int dotted = -1, of = -1;
        if (said) sscanf(said, "lambda_max: %d of %d", &dotted, &of);
        gb_check c = {"8.3", "-", "the lambda_max map: points whose sign is not known (|lambda| <= 2 lambda_error) marked with a dot",
                      "the count from the CSV it was drawn from", "exact"};
        gb_check_true(&c, dotted == unsure && of == 12, "%d of %d dotted, %d expected", dotted, of, unsure);
    }
    gb_check_tempdir_remove(dir);
}

/* The body in motion for bodies of one's own: the die (a mesh: its hull's faces from gomboc shape --faces) and an egg
 * (an expression: its radial map), each animated from its run; the frames' contact points on the plane and
 * visible, the lowest drawn point where the body touches, and a GIF's frame times as the rate asked. */
static void test_animation_bodies(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("animation-bodies", dir, sizeof dir)) return;
    char args[1024], out[8192];
    snprintf(args, sizeof args, "run cases/bodies/die-drop.ini --out %s 2>&1 > /dev/null && %s shape --scene cases/bodies/die-drop.ini "
             "--faces %s/faces-die-drop.csv > /dev/null", dir, gomboc(), dir);
    int code = gb_check_command(gomboc(), args, out, sizeof out);
    char *scene = gb_check_read_file("cases/table1-gomboc-I-unilateral.ini");
    char *body = scene ? strstr(scene, "morphology = I\nbeta = 0.12\n") : NULL, *contact = scene ? strstr(scene, "contact = continuous\n") : NULL;
    if (!code && body && contact) { /* the same scene with an egg of one's own on the fast grid */
        char egg[600];
        snprintf(egg, sizeof egg, "%s/egg.ini", dir);
        FILE *f = fopen(egg, "w");
        if (f) {
            fprintf(f, "%.*sr = 1 + 0.1*cos(theta)*sin(phi)\n%.*scontact = fast-grid\n%s", (int)(body - scene), scene,
                    (int)(contact - body - strlen("morphology = I\nbeta = 0.12\n")), body + strlen("morphology = I\nbeta = 0.12\n"),
                    contact + strlen("contact = continuous\n"));
            fclose(f);
        }
        snprintf(args, sizeof args, "run %s/egg.ini --out %s 2>&1 > /dev/null && %s shape --scene %s/egg.ini --json --radial-map "
                 "%s/radial-map-egg.csv > /dev/null", dir, dir, gomboc(), dir, dir);
        code = gb_check_command(gomboc(), args, out, sizeof out);
    }
    free(scene);
    gb_check runs = {"-", "-", "gomboc run and shape on the die (--faces) and an egg r = 1 + 0.1 cos(theta) sin(phi) (--radial-map)",
                     "exit 0", "exact"};
    gb_check_true(&runs, code == 0 && body && contact, "exit %d: %.300s", code, out);
    if (code || !body || !contact) {
        gb_check_tempdir_remove(dir);
        return;
    }
    static const char *const names[2] = {"die-drop", "egg"};
    for (int b = 0; b < 2; b++) {
        snprintf(args, sizeof args, "reports/animate.py %s %s --seconds %s --fps 15", dir, names[b], b ? "2" : "1");
        char what[200];
        snprintf(what, sizeof what, "animate.py on %s (its surface found by its name; 15 frames a second)", names[b]);
        if (script(args, what, out, sizeof out)) continue;
        char file[300];
        snprintf(file, sizeof file, "%s-animation.json", names[b]);
        cJSON *a = read_json(dir, file);
        history h;
        const int read = history_read(dir, names[b], &h);
        double plane = 0.0, lowest_max = -INFINITY, lowest_min = INFINITY;
        int frames = 0;
        const cJSON *fr;
        cJSON_ArrayForEach(fr, cJSON_GetObjectItem(a, "frames")) {
            const size_t row = (size_t)number(fr, "row", NULL);
            const double clearance = history_value(&h, row, "clearance");
            const cJSON *drawn = cJSON_GetObjectItem(fr, "contact_drawn"), *low = cJSON_GetObjectItem(fr, "lowest_drawn");
            if (cJSON_IsArray(drawn)) plane = fmax(plane, fabs(cJSON_GetArrayItem(drawn, 2)->valuedouble - clearance));
            const double lz = cJSON_GetArrayItem(low, 2)->valuedouble - clearance;
            lowest_max = fmax(lowest_max, lz), lowest_min = fmin(lowest_min, lz);
            frames++;
        }
        int with, shown, delays;
        double worst;
        contact_shown(a, &with, &shown, &worst);
        const double drift = delay_drift(a, &delays);
        const char *kind = cJSON_GetStringValue(cJSON_GetObjectItem(a, "surface_kind"));
        char q[300];
        snprintf(q, sizeof q, "%s in motion (%s): contact points on the plane and visible, the drawn surface touching the plane, "
                 "frame times", names[b], kind ? kind : "?");
        /* the die's drawn vertices are the body's (written to 17 digits): its lowest is the contact, to the history's
         * printed digits; the egg's 90 x 180 sample misses its minimum by up to r (pi/90)^2 / 2 ~ 1.7e-3 m */
        const double touch = b ? 2e-3 : 1e-9;
        gb_check c = {"5", "-", q, "the history's rows: contact at the clearance, the lowest drawn point at it; the marker's colour "
                      "at the point; a GIF's k-th frame starting at k/15 s",
                      "1e-9 m (printed digits); the lowest point within 1e-9 m (the die's exact vertices) or 2e-3 m (the egg's "
                      "sampled surface) above and never 1e-9 m below; 40 of 255 a channel; 10 ms (a GIF counts hundredths)"};
        gb_check_true(&c, a && !read && frames > 0 && with > 0 && shown == with && plane <= 1e-9 && lowest_max <= touch &&
                              lowest_min >= -1e-9 && drift >= 0.0 && drift <= 10.0 + 1e-9 && kind &&
                              !strcmp(kind, b ? "radial map" : "faces"),
                      "%d frames, %d of %d show the contact (worst %.0f), contact off the plane by %.3g m, lowest drawn point "
                      "%.3g .. %.3g m above the plane, %d delays drifting at most %.3g ms", frames, shown, with, worst, plane,
                      lowest_min, lowest_max, delays, drift);
        cJSON_Delete(a);
        free(h.text), free(h.rows);
    }
    gb_check_tempdir_remove(dir);
}

/* A run on a plane of finite friction: its page states the summary's sliding section (μ, the time sliding, the slips
 * and sticks, friction's work) in the summary's own numbers. */
static void test_friction_on_page(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("friction-page", dir, sizeof dir)) return;
    char args[800], out[8192];
    snprintf(args, sizeof args, "run cases/bodies/coin-friction.ini --out %s", dir);
    const int code = gb_check_command(gomboc(), args, out, sizeof out);
    snprintf(args, sizeof args, "reports/run_report.py %s coin-friction --page page.md", dir);
    gb_check c = {"-", "-", "the run page of cases/bodies/coin-friction.ini (mu = 0.3): its friction line",
                  "the summary's sliding section: mu, the time sliding [%], the slips and sticks, friction's work [J] to 4 digits",
                  "exact: the same numbers as printed from the summary"};
    if (code || script(args, "run_report.py on coin-friction", out, sizeof out)) {
        gb_check_true(&c, 0, "exit %d: %.300s", code, out);
        gb_check_tempdir_remove(dir);
        return;
    }
    cJSON *summary = read_json(dir, "coin-friction-summary.json");
    const cJSON *sliding = cJSON_GetObjectItem(summary, "sliding");
    char *page = read_text(dir, "page.md"), expected[300] = "";
    if (sliding) {
        const double slips = cJSON_GetNumberValue(cJSON_GetObjectItem(sliding, "slips"));
        const double sticks = cJSON_GetNumberValue(cJSON_GetObjectItem(sliding, "sticks"));
        snprintf(expected, sizeof expected, "friction μ = %g: sliding %.1f %% of the run, %.0f slip%s and %.0f stick%s, ",
                 cJSON_GetNumberValue(cJSON_GetObjectItem(sliding, "friction")),
                 100.0 * cJSON_GetNumberValue(cJSON_GetObjectItem(sliding, "time_fraction")), slips, slips == 1 ? "" : "s",
                 sticks, sticks == 1 ? "" : "s");
    }
    gb_check_true(&c, sliding && page && strstr(page, expected), "expected \"%s\" on the page: %s", expected,
                  page && strstr(page, expected) ? "found" : "missing");
    free(page);
    cJSON_Delete(summary);
    gb_check_tempdir_remove(dir);
}

/* A body at rest with λ and its windows (Housner's block standing on its face, 24 periods, windows of 2): the page's λ
 * lines say what the record says, not a chaos that "lasts to period 0". */
static void test_rest_on_page(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("rest-page", dir, sizeof dir)) return;
    char path[300], args[800], out[8192];
    snprintf(path, sizeof path, "%s/rest.ini", dir);
    FILE *f = fopen(path, "w");
    if (f) {
        fprintf(f, "[body]\nmesh = %s/cases/bodies/housner-block.off\nmass = 1\n[forcing]\nA1 = 0\nA2 = 0\nomega = 6.283185307179586\n"
                "[model]\ncontact = fast-grid\ncontact_law = unilateral\n[integrator]\nsteps_per_period = 400\nperiods = 24\n"
                "[diagnostics]\nlyapunov = yes\n[lyapunov]\ndelta0 = 1e-7\ntransient_periods = 0\ninterval_periods = 1\n"
                "window_periods = 2\n", getcwd(args, sizeof args) ? args : ".");
        fclose(f);
    }
    snprintf(args, sizeof args, "run %s --out %s", path, dir);
    const int code = gb_check_command(gomboc(), args, out, sizeof out);
    snprintf(args, sizeof args, "reports/run_report.py %s rest --page page.md", dir);
    gb_check c = {"-", "-", "the run page of a block standing at rest on a still plane, with lambda and its 12 windows",
                  "the summary's windows: none above the threshold; the page says no window is chaotic (not that chaos "
                  "lasts to period 0) and, where the record is not converged, why", "exact"};
    if (code || script(args, "run_report.py on a body at rest", out, sizeof out)) {
        gb_check_true(&c, 0, "exit %d: %.300s", code, out);
        gb_check_tempdir_remove(dir);
        return;
    }
    cJSON *summary = read_json(dir, "rest-summary.json");
    const cJSON *windows = cJSON_GetObjectItem(cJSON_GetObjectItem(summary, "lyapunov"), "windows");
    const double chaotic = cJSON_GetNumberValue(cJSON_GetObjectItem(windows, "chaotic_windows"));
    const int converged = cJSON_IsTrue(cJSON_GetObjectItem(cJSON_GetObjectItem(summary, "lyapunov"), "converged"));
    char *page = read_text(dir, "page.md");
    const int none = page && strstr(page, "no window chaotic: no chaos in the record") && !strstr(page, "lasts to period 0");
    const int why = converged || (page && strstr(page, "not converged (") && !strstr(page, "not converged ("")"));
    gb_check_true(&c, windows && chaotic == 0 && none && why, "%g chaotic windows; page: %s; converged %d%s", chaotic,
                  none ? "no window chaotic" : "WRONG", converged, why ? "" : ", no reason given");
    free(page);
    cJSON_Delete(summary);
    gb_check_tempdir_remove(dir);
}

int verify_register_figures(void)
{
    static const verify_test tests[] = {
        {"report writers: malformed CSVs named in one line, links replaced, --help answered", test_writers_bad_input, NULL},
        {"figures quote the summary, stale figures never linked", test_figures,
         "every figure's title quotes the numbers the text states, Fig 9 draws what it quotes, and a page links only this run's figures"},
        {"a run on a plane of finite friction states its sliding on its page", test_friction_on_page, NULL},
        {"Fig 1 measured as drawn, and a lambda map's unknown signs marked", test_figure_one_and_maps,
         "Fig 1's labels and colour bars do not collide, and a lambda map marks every point whose sign is not known"},
        {"bodies of one's own in motion: a mesh's faces and an expression's surface", test_animation_bodies,
         "a mesh body and an expression body are animated with their contact points on the plane and in view"},
        {"a body at rest: its page says no window is chaotic", test_rest_on_page, NULL},
        {"the animation's frames against the history", test_animation,
         "the body in motion is drawn in the attitude the run computed, touching the plane at the contact point"},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Reports: figures drawn from the data they name", tests);
}
