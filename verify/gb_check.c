#include "gb_check.h"

#include "gb_error.h"

#include <CUnit/CUnit.h>
#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

const char *gb_check_data_dir = ".";
int gb_check_full = 0;
static cJSON *rows, *tests;
static double last_time;

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
    return new_row(c, kind, passed, seconds, file, line);
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

int gb_check_write(const char *path)
{
    cJSON *document = cJSON_CreateObject();
    cJSON_AddNumberToObject(document, "schema", GB_CHECK_SCHEMA);
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
