#include "gb_check.h"
#include "gb_error.h"
#include "verify_sections.h"

#include <stdio.h>

/* Every test starts with the row timer at zero and no library message left from an earlier test, so a
 * passing row can never print an error text that belongs to another computation. */
static size_t tempdirs_before;

static void test_setup(void)
{
    gb_error_clear();
    gb_check_test_start();
    tempdirs_before = gb_check_tempdirs_made();
}

/* A test that made temporary directories of its own leaves none behind (a leftover is named, then removed); in the
 * harness's second process the test is then listed as run to its end. */
static void test_teardown(void)
{
    const size_t made = gb_check_tempdirs_made() - tempdirs_before;
    if (made) {
        char left[800], q[120];
        const size_t n = gb_check_tempdirs_left(left, sizeof left);
        snprintf(q, sizeof q, "the %zu temporary director%s the test made, gone at its end", made,
                 made == 1 ? "y" : "ies");
        gb_check c = {"-", "-", q, "the directories gb_check_tempdir listed", "exact"};
        gb_check_true(&c, n == 0, n ? "%zu left behind: %.600s" : "none left", n, left);
    }
    gb_check_test_end();
}

int verify_register_suite(const char *name, const verify_test *tests)
{
    CU_pSuite suite = CU_add_suite_with_setup_and_teardown(name, NULL, NULL, test_setup, test_teardown);
    if (!suite) return 1;
    for (const verify_test *t = tests; t->name; t++)
        if (!CU_add_test(suite, t->name, t->function) || gb_check_register_test(name, t->name, t->establishes)) return 1;
    return 0;
}
