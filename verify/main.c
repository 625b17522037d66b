/* The verification harness: every check of every section runs; the process exits non-zero when any
 * failed. CUnit's run summary goes to standard output; the rows go to --results for the report. */
#include "gb_body.h"
#include "gb_check.h"
#include "gb_error.h"
#include "gb_integrate.h"
#include "verify_sections.h"

#include <CUnit/Basic.h>
#include <cjson/cJSON.h>
#include <ftw.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

/* The seals' key of this harness and of every gomboc it starts (GOMBOC_KEY, inherited): a key of its own
 * in a directory of its own, so that the checks neither read nor make the user's key. */
static char key_dir[GB_CHECK_TEMPDIR_SIZE];

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

static pid_t harness_pid;

static void remove_key_dir(void)
{
    if (key_dir[0] && getpid() == harness_pid) nftw(key_dir, remove_entry, 8, FTW_DEPTH | FTW_PHYS);
}

/* ---- --jobs 2: the harness in two processes ------------------------------------------------------------
 * The suites a registration marks `second` run in a child process started before any test, beside the others;
 * its output goes to a log and its rows (each with its assertion's message) and the tests it ran to their end to a
 * file. In the first process each of those tests is a proxy that waits for the child once, then replays the
 * child's rows in the test's place: every row asserted through CUnit again with the message it had, so that one
 * CUnit run counts every test and assertion (the second's suites registered last, so run after the first's). A
 * test the child did not run to its end (the child crashed or was killed) fails, naming how the child ended. */
static pid_t second = -1;
static char second_results[4096], second_log[4096];
static cJSON *second_document;
static char second_end[128];

static void run_in_second_process(void)
{
    if (second > 0) {
        int status = 0;
        fflush(stdout);
        if (waitpid(second, &status, 0) != second)
            snprintf(second_end, sizeof second_end, "could not be waited for");
        else if (WIFSIGNALED(status))
            snprintf(second_end, sizeof second_end, "was ended by signal %d", WTERMSIG(status));
        else
            snprintf(second_end, sizeof second_end, "exited with status %d", WEXITSTATUS(status));
        second = 0;
        char *text = gb_check_read_file(second_results);
        second_document = text ? cJSON_Parse(text) : NULL;
        free(text);
        remove(second_results);
    }
    const char *suite = CU_get_current_suite()->pName, *test = CU_get_current_test()->pName;
    if (second_document && gb_check_replay(second_document, suite, test)) return;
    gb_check c = {"-", "-", "the test, run in the harness's second process", "its rows, written when it ends", "exact"};
    gb_check_true(&c, 0, "the second process %s before this test's end (its output: %s)", second_end, second_log);
}

/* After the run: the second process waited for (when no proxy ran, as under --only), its results file removed. */
static void finish_second_process(void)
{
    if (second > 0) waitpid(second, NULL, 0), second = 0;
    if (second_results[0]) remove(second_results);
    cJSON_Delete(second_document);
    second_document = NULL;
}

/* Run the registry's suites (those `mask` marks when it is not NULL) whose names contain `only`, and of those the
 * tests whose names contain `test` (NULL: every suite, every test, in CUnit's one run of the registry). */
static void run_selected(const char *only, const char *test, const unsigned char *mask)
{
    if (!only && !test && !mask) {
        CU_basic_run_tests();
        return;
    }
    size_t k = 0;
    for (CU_pSuite suite = CU_get_registry()->pSuite; suite; suite = suite->pNext, k++) {
        if ((mask && !mask[k]) || (only && !strstr(suite->pName, only))) continue;
        if (!test)
            CU_basic_run_suite(suite);
        else
            for (CU_pTest t = suite->pTest; t; t = t->pNext)
                if (strstr(t->pName, test)) CU_basic_run_test(suite, t);
    }
}

/* Start the child that runs the `second` suites; make the first process's copies of their tests proxies. */
static int start_second_process(const unsigned char *second_suite, const char *results, const char *only,
                                const char *test)
{
    const size_t stem =
        strlen(results) - (strlen(results) > 5 && !strcmp(results + strlen(results) - 5, ".json") ? 5 : 0);
    snprintf(second_results, sizeof second_results, "%.*s-second.json", (int)stem, results);
    snprintf(second_log, sizeof second_log, "%.*s-second.log", (int)stem, results);
    fflush(stdout), fflush(stderr);
    const pid_t child = fork();
    if (child < 0) return 1;
    if (child == 0) {
        prctl(PR_SET_PDEATHSIG, SIGTERM); /* never outlive the first process */
        if (!freopen(second_log, "w", stdout) || dup2(fileno(stdout), 2) < 0) _exit(3);
        gb_check_second_process();
        run_selected(only, test, second_suite);
        const int failed = gb_check_write(second_results);
        fflush(NULL);
        _exit(failed ? 1 : 0); /* the first process removes the key's directory and writes the results */
    }
    second = child;
    size_t k = 0, suites = 0;
    for (CU_pSuite suite = CU_get_registry()->pSuite; suite; suite = suite->pNext, k++)
        if (second_suite[k]) {
            suites++;
            for (CU_pTest t = suite->pTest; t; t = t->pNext) t->pTestFunc = run_in_second_process;
        }
    printf("verify: %zu suites run in a second process beside this one (its output: %s); their results follow this "
           "one's own suites\n",
           suites, second_log);
    return 0;
}

int main(int argc, char **argv)
{
    const char *results = "checks.json", *only = NULL, *test = NULL;
    int jobs = 1;
    harness_pid = getpid();
    /* `make verify` starts the harness in the background of its recipe's shell, which sets it to ignore SIGINT and
     * SIGQUIT: Ctrl-C must still stop it (and, through PR_SET_PDEATHSIG, its second process) */
    signal(SIGINT, SIG_DFL), signal(SIGQUIT, SIG_DFL);
    /* the commands the checks run keep nothing in the user's cache (a check of it names its own directory) */
    setenv("GOMBOC_CACHE", "off", 1);
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--results") && i + 1 < argc) results = argv[++i];
        else if (!strcmp(argv[i], "--data") && i + 1 < argc) gb_check_data_dir = argv[++i];
        else if (!strcmp(argv[i], "--full")) gb_check_full = 1;
        else if (!strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
        else if (!strcmp(argv[i], "--test") && i + 1 < argc) test = argv[++i];
        else if (!strcmp(argv[i], "--jobs") && i + 1 < argc) {
            char *end;
            const long n = strtol(argv[++i], &end, 10);
            if (*end || end == argv[i] || n < 1 || n > 256) {
                fprintf(stderr, "%s: --jobs '%s' is out of range (allowed: an integer from 1 to 256)\n", argv[0],
                        argv[i]);
                return 2;
            }
            jobs = (int)n;
        } else {
            fprintf(stderr,
                    "usage: %s [--results FILE] [--data DIR] [--full] [--only TEXT] [--test TEXT] [--jobs N]\n"
                    "  --only TEXT  run only the suites whose name contains TEXT (for development)\n"
                    "  --test TEXT  run only the tests whose name contains TEXT (for development)\n"
                    "  --jobs N     with N >= 2, the suites marked for it run in a second process\n",
                    argv[0]);
            return 2;
        }
    }
    gb_error_init_gsl();
    gb_integrate_blas_single_thread(); /* as the command: the harness time-steps in its own process */
    const char *temp = getenv("TMPDIR");
    const int n = snprintf(key_dir, sizeof key_dir, "%s/gomboc-key-XXXXXX", temp && *temp ? temp : "/tmp");
    if (n < 0 || (size_t)n >= sizeof key_dir || !mkdtemp(key_dir)) {
        perror("verify: cannot make a directory for the seals' key");
        return 1;
    }
    atexit(remove_key_dir);
    char key[GB_CHECK_TEMPDIR_SIZE + 8];
    snprintf(key, sizeof key, "%s/key", key_dir);
    setenv("GOMBOC_KEY", key, 1);
    if (CU_initialize_registry() != CUE_SUCCESS) return 1;
    /* The suites in the report's order; `second`: the suite runs in the second process under --jobs 2 (the Lyapunov
     * exponents, the Melnikov analysis and its proofs, Siconos's scenes, bodies of one's own as scenes and the Python
     * package: about half the checks' time; none of them reads what a suite of the first process writes, nor the
     * reverse). Under --jobs 2 the first process registers its own suites first, so that it runs them before it
     * waits for the second's; the rows are written in the report's order whatever the order they ran in
     * (gb_check_suite_rank). */
    static const struct {
        int (*add)(void);
        int second;
    } registrations[] = {
        {verify_register_s0_verdicts, 0},
        {verify_register_s2_surface, 0},
        {verify_register_s2_massprops, 0},
        {verify_register_s2_shape, 0},
        {verify_register_s2_polyhedron, 0},
        {verify_register_s2_bodies, 1},
        {verify_register_s2_expression, 0},
        {verify_register_s4_contact, 0},
        {verify_register_s4_grid, 0},
        {verify_register_s4_certify, 0},
        {verify_register_s4_atlas, 0},
        {verify_register_s5_dynamics, 0},
        {verify_register_s5_references, 0},
        {verify_register_s5_impact, 0},
        {verify_register_s5_flight, 0},
        {verify_register_s5_friction_impact, 0},
        {verify_register_s5_friction, 0},
        {verify_register_s5_compliant, 0},
        {verify_register_s5_stepping, 0},
        {verify_register_s6_estimators, 1},
        {verify_register_s6_chaos, 1},
        {verify_register_s6_diagnostics, 1},
        {verify_register_s7_melnikov, 1},
        {verify_register_s7_tangle, 1},
        {verify_register_s7_proofs, 1},
        {verify_register_s7_proofs_body, 1},
        {verify_register_s7_proofs_jet, 1},
        {verify_register_s7_horseshoe, 1},
        {verify_register_s7_covering, 1},
        {verify_register_s7_returns, 1},
        {verify_register_s7_conley, 1},
        {verify_register_s7_manifold, 1},
        {verify_register_s8_scan, 0},
        {verify_register_s8_scan_runs, 0},
        {verify_register_s8_scan_atlas, 0},
        {verify_register_s8_ensembles, 0},
        {verify_register_siconos, 1},
        {verify_register_command, 0},
        {verify_register_python, 1},
        {verify_register_surface, 0},
        {verify_register_figures, 0},
        {verify_register_bad_input, 0},
        {verify_register_bad_input_bodies, 0},
        {verify_register_bad_input_processes, 0},
    };
    enum { MAX_SUITES = 128 };
    unsigned char second_suite[MAX_SUITES] = {0};
    size_t suites = 0;
    const size_t count = sizeof registrations / sizeof registrations[0];
    for (int pass = jobs >= 2 ? 0 : -1; pass <= (jobs >= 2 ? 1 : -1); pass++)
        for (size_t k = 0; k < count; k++) {
            if (pass >= 0 && registrations[k].second != pass) continue;
            if (registrations[k].add()) {
                fprintf(stderr, "verify: cannot register suites: %s\n", CU_get_error_msg());
                CU_cleanup_registry();
                return 1;
            }
            CU_pSuite suite = CU_get_registry()->pSuite;
            for (size_t j = 0; suite; suite = suite->pNext, j++)
                if (j >= suites && j < MAX_SUITES) {
                    second_suite[j] = (unsigned char)(pass == 1);
                    gb_check_suite_rank(suite->pName, (int)k);
                }
            suites = CU_get_registry()->uiNumberOfSuites;
        }
    CU_basic_set_mode(CU_BRM_VERBOSE);
    if (jobs >= 2 && start_second_process(second_suite, results, only, test))
        fprintf(stderr, "verify: cannot start a second process; every suite runs in this one\n");
    run_selected(only, test, NULL);
    finish_second_process();
    const unsigned failures = CU_get_number_of_failures() + CU_get_number_of_tests_failed();
    const int write_failed = gb_check_write(results);
    CU_cleanup_registry();
    gb_body_release(); /* the bodies of one's own the checks made */
    printf("\n");
    return failures || write_failed ? 1 : 0;
}
