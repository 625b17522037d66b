/* The verdict rules themselves (verify/gb_verdict.h), before any finding uses them: each rule is fed
 * synthetic evidence built to hold, to fail and to stay undecided, and must reach all three outcomes
 * (a rule that cannot fail, or can fail only one way, is caught here). Non-finite evidence is undecided. */
#include "gb_check.h"
#include "gb_verdict.h"
#include "verify_sections.h"

#include <math.h>
#include <stdio.h>

typedef struct case_row {
    const char *rule, *evidence;
    gb_verdict got, expected;
} case_row;

static void judge_rows(const case_row *rows, size_t n)
{
    for (size_t k = 0; k < n; k++) {
        char q[240];
        snprintf(q, sizeof q, "rule '%s' on synthetic evidence %s gives '%s'", rows[k].rule, rows[k].evidence,
                 gb_verdict_name(rows[k].expected));
        gb_check c = {"-", "-", q, "the rule as written in gb_verdict.h", "exact"};
        gb_check_true(&c, rows[k].got == rows[k].expected, "got '%s'", gb_verdict_name(rows[k].got));
    }
}

#define ROW(rule, evidence, call, expected) {rule, evidence, call, expected}

static void test_above_and_equivalent(void)
{
    const case_row rows[] = {
        ROW("above", "x = 2.53 +- 0.12 (4 sigma), threshold 0.01", gb_verdict_above(2.53, 0.12, 0.01), GB_VERDICT_HOLDS),
        ROW("above", "x = 0.003 +- 0.004, threshold 0.01", gb_verdict_above(0.003, 0.004, 0.01), GB_VERDICT_FAILS),
        ROW("above", "x = 0.030 +- 0.12, threshold 0.01", gb_verdict_above(0.030, 0.12, 0.01), GB_VERDICT_UNDECIDED),
        ROW("above", "x = NaN", gb_verdict_above(NAN, 0.1, 0.01), GB_VERDICT_UNDECIDED),
        ROW("above", "x = -7.18, u = 1e-9, threshold 0 (a curvature)", gb_verdict_above(-7.18, 1e-9, 0.0), GB_VERDICT_FAILS),
        ROW("above at a resolution", "x = 0.30 +- 0.04, threshold 0.01, resolution 0.05", gb_verdict_above_at(0.30, 0.04, 0.01, 0.05),
            GB_VERDICT_HOLDS),
        ROW("above at a resolution", "x = -0.001 +- 0.04 (a regular motion, record long enough), threshold 0.01, resolution 0.05",
            gb_verdict_above_at(-0.001, 0.04, 0.01, 0.05), GB_VERDICT_FAILS),
        ROW("above at a resolution", "x = -0.001 +- 0.136 (the same motion, a record too short), threshold 0.01, resolution 0.05",
            gb_verdict_above_at(-0.001, 0.136, 0.01, 0.05), GB_VERDICT_UNDECIDED),
        ROW("above at a resolution", "x = 0.03 +- 0.016 (clearly positive, below the resolution: shown positive)",
            gb_verdict_above_at(0.03, 0.016, 0.01, 0.05), GB_VERDICT_HOLDS),
        ROW("above at a resolution", "resolution below the threshold is refused", gb_verdict_above_at(0.0, 0.001, 0.05, 0.01),
            GB_VERDICT_UNDECIDED),
        ROW("above at a resolution", "u = NaN", gb_verdict_above_at(0.3, NAN, 0.01, 0.05), GB_VERDICT_UNDECIDED),
        ROW("equivalent", "delta 0.11 +- 0.067 x 2.26, margin 0.52", gb_verdict_equivalent(0.11, 0.067, 2.26, 0.52), GB_VERDICT_HOLDS),
        ROW("equivalent", "delta -0.9 +- 0.05 x 2.26, margin 0.2", gb_verdict_equivalent(-0.9, 0.05, 2.26, 0.2), GB_VERDICT_FAILS),
        ROW("equivalent", "delta 0.2 +- 0.072 x 2.26, margin 0.07", gb_verdict_equivalent(0.2, 0.072, 2.26, 0.07), GB_VERDICT_UNDECIDED),
        ROW("equivalent", "a noisier difference is not easier to call equivalent: 0.05 +- 1.0, margin 0.2",
            gb_verdict_equivalent(0.05, 1.0, 2.26, 0.2), GB_VERDICT_UNDECIDED),
        ROW("equivalent", "sigma = inf", gb_verdict_equivalent(0.0, INFINITY, 2.26, 0.2), GB_VERDICT_UNDECIDED),
    };
    judge_rows(rows, sizeof rows / sizeof rows[0]);
}

static void test_fit_change(void)
{
    /* A line through exact points: the fitted change is the rise over the range, its error from the
     * weights (closed form for two points: sqrt(s1^2 + s2^2)). */
    const double x[4] = {0, 1, 2, 3}, steady[4] = {2.530, 2.599, 2.668, 2.737}, flat[4] = {2.5, 2.5, 2.5, 2.5},
                 sigma[4] = {0.03, 0.03, 0.03, 0.03};
    double change, error;
    int status = gb_verdict_fit_change(x, steady, sigma, 4, &change, &error);
    gb_check c = {"-", "-", "fitted change of a steady rise 2.530 -> 2.737 over its range", "0.207 exactly", "1e-12"};
    gb_check_close(&c, status ? NAN : change, 0.207, 0.0, 1e-12);
    const double x2[2] = {-7, -11}, y2[2] = {0.45, 0.47}, s2[2] = {0.03, 0.04};
    status = gb_verdict_fit_change(x2, y2, s2, 2, &change, &error);
    gb_check c2 = {"-", "-", "fit of two points: change and its error", "y2 - y1 = -0.02 over the range (x falls), error 0.05", "1e-12"};
    gb_check_close(&c2, status ? NAN : fabs(change) + error, 0.02 + 0.05, 0.0, 1e-12);
    const double same[2] = {1, 1};
    gb_check c3 = {"-", "-", "fit over one x value is refused", "status 1", "exact"};
    gb_check_true(&c3, gb_verdict_fit_change(same, y2, s2, 2, &change, &error) == 1, "status");
    /* The three outcomes through the fit, as the independence findings use it (margin 10 % of 2.53). */
    double ch_steady, e_steady, ch_flat, e_flat;
    gb_verdict_fit_change(x, steady, sigma, 4, &ch_steady, &e_steady);
    gb_verdict_fit_change(x, flat, sigma, 4, &ch_flat, &e_flat);
    const double wide[4] = {0.3, 0.3, 0.3, 0.3}, big_rise[4] = {2.0, 2.5, 3.0, 3.5};
    double ch_wide, e_wide, ch_big, e_big;
    gb_verdict_fit_change(x, flat, wide, 4, &ch_wide, &e_wide);
    gb_verdict_fit_change(x, big_rise, sigma, 4, &ch_big, &e_big);
    const case_row rows[] = {
        ROW("fit + equivalent", "flat 2.5 +- 0.03 over 4 grids", gb_verdict_equivalent(ch_flat, e_flat, 2.26, 0.253), GB_VERDICT_HOLDS),
        ROW("fit + equivalent", "rise 2.0 -> 3.5 +- 0.03", gb_verdict_equivalent(ch_big, e_big, 2.26, 0.253), GB_VERDICT_FAILS),
        ROW("fit + equivalent", "flat but +- 0.3", gb_verdict_equivalent(ch_wide, e_wide, 2.26, 0.253), GB_VERDICT_UNDECIDED),
        ROW("fit + equivalent", "steady rise 2.530 -> 2.737 +- 0.03", gb_verdict_equivalent(ch_steady, e_steady, 2.26, 0.253),
            GB_VERDICT_UNDECIDED),
    };
    judge_rows(rows, sizeof rows / sizeof rows[0]);
}

static void test_order_conserved_counts_pivot(void)
{
    const double fourth[3] = {1.6e-4, 1.0e-5, 6.25e-7}, first[3] = {1e-2, 5e-3, 2.5e-3}, between[3] = {1e-3, 1.6e-4, 2.2e-5},
                 wobbly[3] = {2.09e-4, 2.32e-4, 1.42e-4};
    const size_t one[2] = {1, 1}, two[2] = {2, 2}, mixed[2] = {2, 3};
    const case_row rows[] = {
        ROW("order", "errors fall 16x a halving (order 4)", gb_verdict_order(fourth, 4.0), GB_VERDICT_HOLDS),
        ROW("order", "errors fall 2x a halving (order 1)", gb_verdict_order(first, 4.0), GB_VERDICT_FAILS),
        ROW("order", "order 2.86 after 2.64", gb_verdict_order(between, 4.0), GB_VERDICT_FAILS),
        ROW("order", "errors 2.09e-4, 2.32e-4, 1.42e-4 (not monotone)", gb_verdict_order(wobbly, 4.0), GB_VERDICT_UNDECIDED),
        ROW("order", "last order 3.2 (between 3 and 3.5)", gb_verdict_order((double[]){1e-3, 1e-4, 1.0e-4 / 9.19}, 4.0),
            GB_VERDICT_UNDECIDED),
        ROW("conserved", "1e-11 at the finest step, floor 1e-11", gb_verdict_conserved(1e-6, 1e-11, 1e-11), GB_VERDICT_HOLDS),
        ROW("conserved", "0.013 stalls from 0.014, floor 1e-12", gb_verdict_conserved(0.014, 0.013, 1e-12), GB_VERDICT_FAILS),
        ROW("conserved", "falls 1e-3 -> 1e-5, floor 1e-9", gb_verdict_conserved(1e-3, 1e-5, 1e-9), GB_VERDICT_UNDECIDED),
        ROW("counts", "(1, 1) at both resolutions", gb_verdict_counts(one, one, 1, 1), GB_VERDICT_HOLDS),
        ROW("counts", "(2, 1) at both resolutions", gb_verdict_counts(two, one, 1, 1), GB_VERDICT_FAILS),
        ROW("counts", "(2, 1) then (3, 1)", gb_verdict_counts(mixed, one, 1, 1), GB_VERDICT_UNDECIDED),
        ROW("pivot", "every ratio within 6 % of 1", gb_verdict_pivot(0.99, 0.96, 1.02, 0.06), GB_VERDICT_FAILS),
        ROW("pivot", "unforced 0.1, convex 0.2, baseline 0.95", gb_verdict_pivot(0.95, 0.1, 0.2, 0.9), GB_VERDICT_HOLDS),
        ROW("pivot", "unforced 0.7, convex 0.2", gb_verdict_pivot(0.95, 0.7, 0.2, 0.8), GB_VERDICT_UNDECIDED),
        ROW("pivot", "a NaN ratio", gb_verdict_pivot(NAN, 0.1, 0.2, 0.9), GB_VERDICT_UNDECIDED),
    };
    judge_rows(rows, sizeof rows / sizeof rows[0]);
}

int verify_register_s0_verdicts(void)
{
    static const verify_test tests[] = {
        {"verdict rules: above and equivalent reach holds, fails and undecided", test_above_and_equivalent,
         "the rules 'above' and 'equivalent' reach holds, fails and undecided on synthetic evidence, and a noisier "
         "difference is not easier to call equivalent"},
        {"verdict rules: the fitted change over a range", test_fit_change,
         "the weighted fit returns the change over the range exactly and drives holds, fails and undecided"},
        {"verdict rules: order, conserved, counts and pivot", test_order_conserved_counts_pivot,
         "the rules 'order', 'conserved', 'counts' and 'pivot' reach holds, fails and undecided; non-monotone errors give "
         "no order"},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("The verdict rules (gb_verdict.h)", tests);
}
