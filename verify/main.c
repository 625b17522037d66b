/* The verification harness: every check of every section runs; the process exits non-zero when any
 * failed. CUnit's run summary goes to standard output; the rows go to --results for the report. */
#include "gb_body.h"
#include "gb_check.h"
#include "gb_error.h"
#include "gb_integrate.h"
#include "verify_sections.h"

#include <CUnit/Basic.h>
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The seals' key of this harness and of every gomboc it starts (GOMBOC_KEY, inherited): a key of its own
 * in a directory of its own, so that the checks neither read nor make the user's key. */
static char key_dir[64];

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

static void remove_key_dir(void)
{
    if (key_dir[0]) nftw(key_dir, remove_entry, 8, FTW_DEPTH | FTW_PHYS);
}

int main(int argc, char **argv)
{
    const char *results = "checks.json", *only = NULL, *test = NULL;
    /* the commands the checks run keep nothing in the user's cache (a check of it names its own directory) */
    setenv("GOMBOC_CACHE", "off", 1);
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--results") && i + 1 < argc) results = argv[++i];
        else if (!strcmp(argv[i], "--data") && i + 1 < argc) gb_check_data_dir = argv[++i];
        else if (!strcmp(argv[i], "--full")) gb_check_full = 1;
        else if (!strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
        else if (!strcmp(argv[i], "--test") && i + 1 < argc) test = argv[++i];
        else {
            fprintf(stderr, "usage: %s [--results FILE] [--data DIR] [--full] [--only TEXT] [--test TEXT]\n"
                            "  --only TEXT  run only the suites whose name contains TEXT (for development)\n"
                            "  --test TEXT  run only the tests whose name contains TEXT (for development)\n", argv[0]);
            return 2;
        }
    }
    gb_error_init_gsl();
    gb_integrate_blas_single_thread(); /* as the command: the harness time-steps in its own process */
    snprintf(key_dir, sizeof key_dir, "/tmp/gomboc-key-XXXXXX");
    if (!mkdtemp(key_dir)) {
        perror("verify: cannot make a directory for the seals' key");
        return 1;
    }
    atexit(remove_key_dir);
    char key[96];
    snprintf(key, sizeof key, "%s/key", key_dir);
    setenv("GOMBOC_KEY", key, 1);
    if (CU_initialize_registry() != CUE_SUCCESS) return 1;
    static int (*const registrations[])(void) = {
        verify_register_s0_verdicts,      verify_register_s2_surface,
        verify_register_s2_massprops,     verify_register_s2_shape,
        verify_register_s2_polyhedron,    verify_register_s2_bodies,
        verify_register_s2_expression,    verify_register_s4_contact,
        verify_register_s4_grid,          verify_register_s4_certify,
        verify_register_s4_atlas,         verify_register_s5_dynamics,
        verify_register_s5_references,    verify_register_s5_impact,
        verify_register_s5_flight,        verify_register_s5_friction_impact,
        verify_register_s5_friction,      verify_register_s5_compliant,
        verify_register_s5_stepping,      verify_register_s6_estimators,
        verify_register_s6_chaos,         verify_register_s6_diagnostics,
        verify_register_s7_melnikov,      verify_register_s7_tangle,
        verify_register_s7_proofs,        verify_register_s7_proofs_body,
        verify_register_s7_covering,      verify_register_s7_returns,
        verify_register_s8_scan,          verify_register_s8_scan_runs,
        verify_register_s8_scan_atlas,    verify_register_s8_ensembles,
        verify_register_siconos,          verify_register_command,
        verify_register_python,           verify_register_surface,
        verify_register_figures,          verify_register_bad_input,
        verify_register_bad_input_bodies, verify_register_bad_input_processes,
    };
    for (size_t k = 0; k < sizeof registrations / sizeof registrations[0]; k++)
        if (registrations[k]()) {
            fprintf(stderr, "verify: cannot register suites: %s\n", CU_get_error_msg());
            CU_cleanup_registry();
            return 1;
        }
    CU_basic_set_mode(CU_BRM_VERBOSE);
    if (only || test) {
        for (CU_pSuite suite = CU_get_registry()->pSuite; suite; suite = suite->pNext) {
            if (only && !strstr(suite->pName, only)) continue;
            if (!test) CU_basic_run_suite(suite);
            else
                for (CU_pTest t = suite->pTest; t; t = t->pNext)
                    if (strstr(t->pName, test)) CU_basic_run_test(suite, t);
        }
    } else {
        CU_basic_run_tests();
    }
    const unsigned failures = CU_get_number_of_failures() + CU_get_number_of_tests_failed();
    const int write_failed = gb_check_write(results);
    CU_cleanup_registry();
    gb_body_release(); /* the bodies of one's own the checks made */
    printf("\n");
    return failures || write_failed ? 1 : 0;
}
