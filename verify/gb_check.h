/* gb_check — the one comparison helper every check uses.
 *
 * A check names what the paper says (section, equation), what is measured (quantity), against what
 * (oracle), and why the tolerance is what it is (origin). gb_check_close compares with a combined
 * relative/absolute tolerance, treats NaN and infinities explicitly, prints %.17g on failure, asserts
 * through CUnit, and records a row {section, equation, quantity, oracle, measured, expected, error,
 * tolerance, origin, seconds, passed} that gb_check_write saves as JSON for the report. The time of a
 * row is the wall time since the previous row of the same test (or the test's start). */
#ifndef GB_CHECK_H
#define GB_CHECK_H

#include "gb_surface.h"
#include "gb_verdict.h"

#include <stddef.h>

typedef struct gb_check {
    const char *section;  /* paper section, e.g. "2" */
    const char *equation; /* equation number(s), e.g. "13" */
    const char *quantity;
    const char *oracle;
    const char *origin;   /* where the tolerance comes from */
} gb_check;

/* Pass when |measured − expected| ≤ abs_tol + rel_tol·|expected|; NaN never passes unless both are
 * NaN; equal infinities pass. Returns 1 on pass. */
int gb_check_close_at(const gb_check *check, double measured, double expected, double rel_tol,
                      double abs_tol, const char *file, int line);
#define gb_check_close(check, measured, expected, rel_tol, abs_tol) \
    gb_check_close_at(check, measured, expected, rel_tol, abs_tol, __FILE__, __LINE__)

/* A check with no numeric error (a count, a verdict, an error path); `detail` is printf-formatted. */
int gb_check_true_at(const gb_check *check, int condition, const char *file, int line,
                     const char *detail, ...) __attribute__((format(printf, 5, 6)));
#define gb_check_true(check, condition, ...) \
    gb_check_true_at(check, condition, __FILE__, __LINE__, __VA_ARGS__)

/* A finding about the paper, decided by a rule of gb_verdict.h written before the data: `verdict` is
 * holds, fails or undecided, and `rule` states the rule, its margin and where the margin comes from. The
 * CUnit assertion is that the evidence was computed (`evidence_ok`: runs completed, numbers finite),
 * never the verdict: the finding is recomputed and re-judged on every run. The row records claim,
 * verdict, rule and the measured text (printf-formatted). */
int gb_check_verdict_at(const gb_check *check, const char *claim, int evidence_ok, gb_verdict verdict, const char *rule,
                        const char *file, int line, const char *measured, ...) __attribute__((format(printf, 8, 9)));
#define gb_check_verdict(check, claim, evidence_ok, verdict, rule, ...) \
    gb_check_verdict_at(check, claim, evidence_ok, verdict, rule, __FILE__, __LINE__, __VA_ARGS__)

/* The body a check names by literals (morphology, beta), for calls that take one body value. The
 * literals are known valid: a failure is a bug in the check, and aborts. The pointer stays valid for the
 * next 63 calls (the callee copies the body). */
const gb_surface *gb_check_body(const char *morphology, double beta);

/* Observed order of convergence p = log(e1/e2) / log(h1/h2). */
double gb_check_observed_order(double e1, double e2, double h1, double h2);

/* Per-test timer reset (a CUnit test setup function). */
void gb_check_test_start(void);

/* Write every registered test and every recorded row to `path` (atomically) as {"schema":
 * GB_CHECK_SCHEMA, "tests": [...], "rows": [...]}; each row also names its CUnit suite and test and the
 * source file and line of the check (the report's index from equation to checks). Returns 0 on success. */
#define GB_CHECK_SCHEMA 5

/* Record a registered test: its suite, its name and what it establishes when all its rows pass (may be
 * NULL); written as "tests" beside the rows. Returns 0, or 1 when out of memory. */
int gb_check_register_test(const char *suite, const char *test, const char *establishes);
int gb_check_write(const char *path);

/* Run `BINARY ARGS` through the shell, its standard output and error into `out` (at most cap − 1 bytes,
 * NUL-terminated); the exit status, or -1 when it could not be run. */
int gb_check_command(const char *binary, const char *args, char *out, size_t cap);

/* The harness in two processes (main's --jobs 2): the second runs some suites and writes its rows with the
 * message and label each assertion had, and the tests it ran to their end (gb_check_test_end, at each test's
 * end); the first replays them in their place, each row asserted again through CUnit with its message and
 * recorded as it was. gb_check_replay returns 1 when the second process ran the test to its end. */
struct cJSON;
void gb_check_second_process(void);
void gb_check_test_end(void);
int gb_check_replay(const struct cJSON *document, const char *suite, const char *test);
/* The place of a suite in the report's order: gb_check_write lists the tests and rows by it (stably; a suite without
 * one goes last), whatever the order the suites ran in. */
void gb_check_suite_rank(const char *suite, int rank);

/* A fresh directory of the test's own, $TMPDIR/gomboc-TAG-XXXXXX (/tmp when TMPDIR is unset or empty), its
 * path in `dir` (GB_CHECK_TEMPDIR_SIZE bytes hold it for a TMPDIR of up to 120 characters). Returns 0 on
 * success; otherwise the test gets a failing row saying why and nothing is made. The harness lists what it
 * made: gb_check_tempdir_remove takes a directory off the list with all it holds, and gb_check_tempdirs_left
 * names those a test left behind. */
#define GB_CHECK_TEMPDIR_SIZE 160
int gb_check_tempdir(const char *tag, char *dir, size_t size);
void gb_check_tempdir_remove(const char *dir);
/* How many directories gb_check_tempdir has made so far; those of them still there, joined by ", " into
 * `out`, and their number (each is then removed: a leftover is reported once). */
size_t gb_check_tempdirs_made(void);
size_t gb_check_tempdirs_left(char *out, size_t size);

/* The whole file at `path`, NUL-terminated, malloc'd (the caller frees it); NULL when it cannot be read. */
char *gb_check_read_file(const char *path);

/* 1 under `make verify-full` (main's --full): the long studies run too. */
extern int gb_check_full;

/* Where data files for the report go (set by main from --data). */
extern const char *gb_check_data_dir;

/* Save `document` as gb_check_data_dir/name (atomically) for the report. Returns 0 on success. */
int gb_check_write_data(const char *name, const struct cJSON *document);
/* The same for a text as it stands (a command's JSON, whose numbers cJSON's printing would round). */
int gb_check_write_text(const char *name, const char *text);

/* Parse references/<name> (or $GOMBOC_REFERENCE_DIR/<name>) and record the check that it is readable
 * and holds a non-empty "cases" array (paper section `section`). Returns that array, or NULL; *root
 * gets the document to free with cJSON_Delete (NULL when unreadable). */
const struct cJSON *gb_check_reference_cases(const char *name, const char *section, struct cJSON **root);

/* gb_check_reference_cases, then `check` on every case of the file (nothing when it is unreadable: that
 * is recorded as a failed check already). */
void gb_check_each_reference_case(const char *name, const char *section, void (*check)(const struct cJSON *reference_case));

#endif
