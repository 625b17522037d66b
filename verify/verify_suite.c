#include "gb_check.h"
#include "gb_error.h"
#include "verify_sections.h"

/* Every test starts with the row timer at zero and no library message left from an earlier test, so a
 * passing row can never print an error text that belongs to another computation. */
static void test_setup(void)
{
    gb_error_clear();
    gb_check_test_start();
}
static void test_teardown(void) {}

int verify_register_suite(const char *name, const verify_test *tests)
{
    CU_pSuite suite = CU_add_suite_with_setup_and_teardown(name, NULL, NULL, test_setup, test_teardown);
    if (!suite) return 1;
    for (const verify_test *t = tests; t->name; t++)
        if (!CU_add_test(suite, t->name, t->function) || gb_check_register_test(name, t->name, t->establishes)) return 1;
    return 0;
}
