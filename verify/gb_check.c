#include "gb_check.h"

#include "gb_error.h"

#include <CUnit/CUnit.h>
#include <cjson/cJSON.h>
#include <errno.h>
#include <ftw.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

const char *gb_check_data_dir = ".";
int gb_check_full = 0;
static cJSON *rows, *tests;
static double last_time;
/* In a second process (gb_check_second_process): each row keeps the message and label its assertion had, and the
 * tests that ran to their end are listed, for the first process to replay (gb_check_replay). */
static int second_process;
static cJSON *completed;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void gb_check_test_start(void) { last_time = now(); }

static double lap(void)
{
    const double t = now(), dt = t - last_time;
    last_time = t;
    return dt;
}

static cJSON *new_row(const gb_check *c, const char *kind, int passed, double seconds, const char *file, int line)
{
    if (!rows) rows = cJSON_CreateArray();
    cJSON *row = cJSON_CreateObject();
    cJSON_AddStringToObject(row, "kind", kind);
    cJSON_AddStringToObject(row, "section", c->section);
    cJSON_AddStringToObject(row, "equation", c->equation);
    cJSON_AddStringToObject(row, "quantity", c->quantity);
    cJSON_AddStringToObject(row, "oracle", c->oracle);
    cJSON_AddStringToObject(row, "origin", c->origin ? c->origin : "");
    cJSON_AddStringToObject(row, "test", CU_get_current_test() ? CU_get_current_test()->pName : "");
    cJSON_AddStringToObject(row, "suite", CU_get_current_suite() ? CU_get_current_suite()->pName : "");
    cJSON_AddStringToObject(row, "file", file);
    cJSON_AddNumberToObject(row, "line", line);
    cJSON_AddNumberToObject(row, "seconds", seconds);
    cJSON_AddBoolToObject(row, "passed", passed);
    cJSON_AddItemToArray(rows, row);
    return row;
}

/* The common tail of every check: print a failure, assert through CUnit, record the row. */
static cJSON *assert_and_record(const gb_check *c, const char *kind, int passed, double seconds,
                                const char *file, int line, const char *label, const char *message)
{
    if (!passed) fprintf(stdout, "\n%s %s:%d %s\n", label, file, line, message);
    CU_assertImplementation(passed ? CU_TRUE : CU_FALSE, (unsigned)line, message, file, "", CU_FALSE);
    cJSON *row = new_row(c, kind, passed, seconds, file, line);
    if (second_process) cJSON_AddStringToObject(row, "message", message), cJSON_AddStringToObject(row, "label", label);
    return row;
}

void gb_check_second_process(void) { second_process = 1; }

void gb_check_test_end(void)
{
    if (!second_process) return;
    if (!completed) completed = cJSON_CreateArray();
    cJSON *t = cJSON_CreateObject();
    cJSON_AddStringToObject(t, "suite", CU_get_current_suite() ? CU_get_current_suite()->pName : "");
    cJSON_AddStringToObject(t, "test", CU_get_current_test() ? CU_get_current_test()->pName : "");
    cJSON_AddItemToArray(completed, t);
}

static int names_test(const cJSON *item, const char *suite, const char *test)
{
    return !strcmp(cJSON_GetStringValue(cJSON_GetObjectItem(item, "suite")) ?: "", suite) &&
           !strcmp(cJSON_GetStringValue(cJSON_GetObjectItem(item, "test")) ?: "", test);
}

int gb_check_replay(const cJSON *document, const char *suite, const char *test)
{
    const cJSON *row, *done;
    cJSON_ArrayForEach(row, cJSON_GetObjectItem(document, "rows"))
    {
        if (!names_test(row, suite, test)) continue;
        const int passed = cJSON_IsTrue(cJSON_GetObjectItem(row, "passed"));
        const char *file = cJSON_GetStringValue(cJSON_GetObjectItem(row, "file")) ?: "?",
                   *message = cJSON_GetStringValue(cJSON_GetObjectItem(row, "message")) ?: "",
                   *label = cJSON_GetStringValue(cJSON_GetObjectItem(row, "label")) ?: "FAILED";
        const int line = (int)cJSON_GetNumberValue(cJSON_GetObjectItem(row, "line"));
        if (!passed) fprintf(stdout, "\n%s %s:%d %s\n", label, file, line, message);
        CU_assertImplementation(passed ? CU_TRUE : CU_FALSE, (unsigned)line, message, file, "", CU_FALSE);
        cJSON *kept = cJSON_Duplicate(row, 1);
        cJSON_DeleteItemFromObject(kept, "message");
        cJSON_DeleteItemFromObject(kept, "label");
        if (!rows) rows = cJSON_CreateArray();
        cJSON_AddItemToArray(rows, kept);
    }
    cJSON_ArrayForEach(done, cJSON_GetObjectItem(document, "completed")) if (names_test(done, suite, test)) return 1;
    return 0;
}

/* JSON has no NaN or infinity: those go as strings. */
static void add_number(cJSON *row, const char *key, double value)
{
    if (isfinite(value)) cJSON_AddNumberToObject(row, key, value);
    else cJSON_AddStringToObject(row, key, isnan(value) ? "nan" : value > 0 ? "inf" : "-inf");
}

int gb_check_close_at(const gb_check *c, double measured, double expected, double rel_tol,
                      double abs_tol, const char *file, int line)
{
    const double seconds = lap();
    double error, tolerance = abs_tol + rel_tol * fabs(expected);
    int passed;
    if (isnan(expected) || isnan(measured)) {
        passed = isnan(expected) && isnan(measured);
        error = passed ? 0.0 : NAN;
    } else if (isinf(expected) || isinf(measured)) {
        passed = measured == expected;
        error = passed ? 0.0 : INFINITY;
    } else {
        error = fabs(measured - expected);
        passed = error <= tolerance;
    }
    char message[1024];
    snprintf(message, sizeof message,
             "[eq %s] %s vs %s: measured %.17g expected %.17g error %.3g tolerance %.3g (%s)",
             c->equation, c->quantity, c->oracle, measured, expected, error, tolerance,
             c->origin ? c->origin : "");
    cJSON *row = assert_and_record(c, "compare", passed, seconds, file, line, "FAILED", message);
    add_number(row, "measured", measured);
    add_number(row, "expected", expected);
    add_number(row, "error", error);
    add_number(row, "relative_error", expected != 0.0 ? error / fabs(expected) : error);
    add_number(row, "tolerance", tolerance);
    add_number(row, "rel_tol", rel_tol);
    add_number(row, "abs_tol", abs_tol);
    return passed;
}

/* Format `fmt` into the row's detail, prefix it with `head` for the message, assert and record. */
static cJSON *record_formatted(const gb_check *c, const char *kind, int passed, const char *file,
                               int line, const char *label, const char *head, const char *fmt,
                               va_list args)
{
    const double seconds = lap();
    char text[2048], message[3072];
    vsnprintf(text, sizeof text, fmt, args);
    snprintf(message, sizeof message, "%s%s", head, text);
    cJSON *row = assert_and_record(c, kind, passed, seconds, file, line, label, message);
    cJSON_AddStringToObject(row, "detail", text);
    return row;
}

int gb_check_true_at(const gb_check *c, int condition, const char *file, int line,
                     const char *detail, ...)
{
    char head[512];
    snprintf(head, sizeof head, "[eq %s] %s (%s): ", c->equation, c->quantity, c->oracle);
    va_list args;
    va_start(args, detail);
    record_formatted(c, "condition", condition, file, line, "FAILED", head, detail, args);
    va_end(args);
    return condition;
}

int gb_check_verdict_at(const gb_check *c, const char *claim, int evidence_ok, gb_verdict verdict, const char *rule,
                        const char *file, int line, const char *measured, ...)
{
    char head[1024];
    snprintf(head, sizeof head, "[finding, eq %s] paper: %s | verdict: %s | measured: ", c->equation, claim,
             gb_verdict_name(verdict));
    va_list args;
    va_start(args, measured);
    cJSON *row = record_formatted(c, "finding", evidence_ok, file, line, "EVIDENCE NOT COMPUTED", head, measured, args);
    va_end(args);
    cJSON_AddStringToObject(row, "claim", claim);
    cJSON_AddStringToObject(row, "verdict", gb_verdict_name(verdict));
    cJSON_AddStringToObject(row, "rule", rule);
    return evidence_ok;
}

double gb_check_observed_order(double e1, double e2, double h1, double h2)
{
    return log(e1 / e2) / log(h1 / h2);
}

/* Write `text` to `path` through a temporary file and a rename. */
static int write_text_atomically(const char *path, const char *text)
{
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s.tmp%ld", path, (long)getpid());
    FILE *f = fopen(tmp, "w");
    int ok = f && text && fputs(text, f) >= 0;
    if (f && fclose(f) != 0) ok = 0;
    if (ok && rename(tmp, path) == 0) return 0;
    remove(tmp);
    return 1;
}

int gb_check_register_test(const char *suite, const char *test, const char *establishes)
{
    if (!tests) tests = cJSON_CreateArray();
    cJSON *t = cJSON_CreateObject();
    if (!tests || !t) return 1;
    cJSON_AddStringToObject(t, "suite", suite);
    cJSON_AddStringToObject(t, "test", test);
    if (establishes) cJSON_AddStringToObject(t, "establishes", establishes);
    cJSON_AddItemToArray(tests, t);
    return 0;
}

static struct {
    char *suite;
    int rank;
} * ranks;
static size_t rank_count;

void gb_check_suite_rank(const char *suite, int rank)
{
    void *grown = realloc(ranks, (rank_count + 1) * sizeof *ranks);
    if (!grown) return;
    ranks = grown;
    ranks[rank_count].suite = strdup(suite);
    ranks[rank_count].rank = rank;
    if (ranks[rank_count].suite) rank_count++;
}

static int rank_of(const cJSON *item)
{
    const char *suite = cJSON_GetStringValue(cJSON_GetObjectItem(item, "suite"));
    for (size_t k = 0; suite && k < rank_count; k++)
        if (!strcmp(ranks[k].suite, suite)) return ranks[k].rank;
    return 1 << 30;
}

/* Reorder `array`'s items by their suite's rank, keeping the order within a rank (an insertion into runs by rank). */
static void order_by_suite(cJSON *array)
{
    const int n = cJSON_GetArraySize(array);
    if (!rank_count || n < 2) return;
    cJSON **items = malloc((size_t)n * sizeof *items);
    int *keys = malloc((size_t)n * sizeof *keys);
    if (!items || !keys) {
        free(items), free(keys);
        return;
    }
    for (int k = n - 1; k >= 0; k--) items[k] = cJSON_DetachItemFromArray(array, k);
    for (int k = 0; k < n; k++) keys[k] = rank_of(items[k]);
    for (int k = 1; k < n; k++) { /* stable insertion sort on runs: the items are already sorted within a suite */
        cJSON *item = items[k];
        const int key = keys[k];
        int j = k - 1;
        while (j >= 0 && keys[j] > key) items[j + 1] = items[j], keys[j + 1] = keys[j], j--;
        items[j + 1] = item, keys[j + 1] = key;
    }
    for (int k = 0; k < n; k++) cJSON_AddItemToArray(array, items[k]);
    free(items), free(keys);
}

int gb_check_write(const char *path)
{
    order_by_suite(tests);
    order_by_suite(rows);
    cJSON *document = cJSON_CreateObject();
    cJSON_AddNumberToObject(document, "schema", GB_CHECK_SCHEMA);
    if (second_process)
        cJSON_AddItemReferenceToObject(document, "completed",
                                       completed ? completed : (completed = cJSON_CreateArray()));
    cJSON_AddItemReferenceToObject(document, "tests", tests ? tests : (tests = cJSON_CreateArray()));
    cJSON_AddItemReferenceToObject(document, "rows", rows ? rows : (rows = cJSON_CreateArray()));
    char *text = cJSON_Print(document);
    cJSON_Delete(document);
    const int failed = write_text_atomically(path, text);
    free(text);
    if (failed) fprintf(stderr, "verify: cannot write results to '%s'\n", path);
    return failed;
}

int gb_check_write_text(const char *name, const char *text)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", gb_check_data_dir, name);
    const int failed = write_text_atomically(path, text);
    if (failed) fprintf(stderr, "verify: cannot write data to '%s'\n", path);
    return failed;
}

int gb_check_write_data(const char *name, const cJSON *document)
{
    char *text = cJSON_Print(document);
    const int failed = gb_check_write_text(name, text);
    free(text);
    return failed;
}

const cJSON *gb_check_reference_cases(const char *name, const char *section, cJSON **root)
{
    const char *dir = getenv("GOMBOC_REFERENCE_DIR") ? getenv("GOMBOC_REFERENCE_DIR") : "references";
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "r");
    char *text = NULL;
    long len = -1;
    if (f && fseek(f, 0, SEEK_END) == 0) len = ftell(f);
    if (f && len >= 0 && fseek(f, 0, SEEK_SET) == 0 && (text = calloc((size_t)len + 1, 1)) &&
        fread(text, 1, (size_t)len, f) != (size_t)len)
        text[0] = '\0';
    if (f) fclose(f);
    *root = text ? cJSON_Parse(text) : NULL;
    free(text);
    const cJSON *cases = cJSON_GetObjectItem(*root, "cases");
    gb_check c = {section, "-", "reference file readable, with cases", path, "exact"};
    return gb_check_true(&c, cJSON_GetArraySize(cases) > 0, "%d cases in %s", cJSON_GetArraySize(cases), path) ? cases : NULL;
}

const gb_surface *gb_check_body(const char *morphology, double beta)
{
    static gb_surface ring[64];
    static unsigned next;
    gb_surface *body = &ring[next++ % 64];
    if (gb_surface_init(body, morphology, beta)) {
        fprintf(stderr, "verify: gb_check_body: %s\n", gb_error_message());
        abort();
    }
    return body;
}

void gb_check_each_reference_case(const char *name, const char *section, void (*check)(const cJSON *reference_case))
{
    cJSON *root = NULL;
    const cJSON *cases = gb_check_reference_cases(name, section, &root), *one;
    if (cases) cJSON_ArrayForEach(one, cases) check(one);
    cJSON_Delete(root);
}

int gb_check_command(const char *binary, const char *args, char *out, size_t cap)
{
    char command[8192];
    snprintf(command, sizeof command, "%s %s 2>&1; echo \"@@exit=$?\"", binary, args);
    FILE *p = popen(command, "r");
    size_t used = 0;
    if (cap) out[0] = '\0';
    if (!p) return -1;
    while (used + 1 < cap && fgets(out + used, (int)(cap - used), p)) used += strlen(out + used);
    pclose(p);
    const char *mark = strstr(out, "@@exit=");
    return mark ? atoi(mark + 7) : -1;
}

char *gb_check_read_file(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *text = NULL;
    long n = -1;
    if (!fseek(f, 0, SEEK_END) && (n = ftell(f)) >= 0 && !fseek(f, 0, SEEK_SET)) text = malloc((size_t)n + 1);
    if (text && fread(text, 1, (size_t)n, f) != (size_t)n) free(text), text = NULL;
    if (text) text[n] = '\0';
    fclose(f);
    return text;
}

/* The directories gb_check_tempdir made, in order (a test makes a few; the harness a few hundred at most). */
static char **made;
static size_t made_count;

int gb_check_tempdir(const char *tag, char *dir, size_t size)
{
    const char *base = getenv("TMPDIR");
    if (!base || !*base) base = "/tmp";
    const int n = snprintf(dir, size, "%s/gomboc-%s-XXXXXX", base, tag);
    const char *why = NULL;
    char **grown = NULL;
    if (n < 0 || (size_t)n >= size)
        why = "the path is too long for the test's buffer";
    else if (!mkdtemp(dir))
        why = strerror(errno);
    else if (!(grown = realloc(made, (made_count + 1) * sizeof *made)) || !(grown[made_count] = strdup(dir)))
        why = "out of memory", rmdir(dir);
    if (grown) made = grown;
    if (why) {
        gb_check c = {"-", "-", "a temporary directory of the test's own", "mkdtemp under TMPDIR", "exact"};
        gb_check_true(&c, 0, "cannot make %s/gomboc-%s-XXXXXX: %s", base, tag, why);
        return 1;
    }
    made_count++;
    return 0;
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

void gb_check_tempdir_remove(const char *dir)
{
    nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
    for (size_t k = 0; k < made_count; k++)
        if (made[k] && !strcmp(made[k], dir)) free(made[k]), made[k] = NULL;
}

size_t gb_check_tempdirs_made(void) { return made_count; }

size_t gb_check_tempdirs_left(char *out, size_t size)
{
    size_t left = 0, used = 0;
    if (size) out[0] = '\0';
    for (size_t k = 0; k < made_count; k++) {
        struct stat st;
        if (!made[k] || lstat(made[k], &st) != 0) continue;
        left++;
        if (used < size) used += (size_t)snprintf(out + used, size - used, "%s%s", left > 1 ? ", " : "", made[k]);
        gb_check_tempdir_remove(made[k]);
    }
    return left;
}
