/* Section 2, bodies of one's own: the expression reader that bounds a body between the checked directions
 * (src/gb_expression.h).
 *
 * Three oracles: libmatheval itself (the tree's value at a point is the value libmatheval computes for the same
 * text, its precedences included); the point values inside a box (every sampled value of the expression lies in
 * the enclosure of the box); and the reader's own refusals (a function that is not smooth, one without an
 * enclosure, text it cannot read). */
#include "gb_check.h"
#include "gb_expression.h"
#include "verify_sections.h"

#include <gsl/gsl_rng.h>
#include <math.h>
#include <matheval.h>
#include <stdio.h>
#include <string.h>

/* High-entropy expressions over every operator, precedence corner and enclosed function. */
static const char *const expressions[] = {
    "1 + 0.05*sin(phi)^2*cos(2*theta) + 0.03*cos(phi)^3",
    "0.5*sin(phi)*cos(theta) + sqrt(0.75 + (0.5*sin(phi)*cos(theta))^2)",
    "(1 + 0.4*sin(phi)*cos(theta))^0.25",
    "-2^2 + 2^3^2/64 + 2^-1*4 - -phi*2 + theta/3.1",
    "exp(-0.3*(phi-1.2)^2) + log(2.5 + cos(theta)) + tanh(phi - theta) + atan(0.7*theta) + asinh(phi/2)",
    "cosh(0.4*(phi - 1.5)) + sinh(0.2*theta - 0.6) + erf(phi - 1) + beta*pi - e/10",
    "theta - 5*phi",
    "theta - 3*pi/2*(cos(phi) - cos(phi)*cos(phi)*cos(phi)/3)",
    "(phi + 0.1)^(theta/7 + 0.5) + 1.7e-3*phi^-2",
};

static void test_expression_against_libmatheval(void)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 5281);
    char *names[] = {"phi", "theta", "beta"};
    for (size_t k = 0; k < sizeof expressions / sizeof expressions[0]; k++) {
        gb_expression_fault fault;
        char detail[128];
        gb_expression *tree = gb_expression_parse(expressions[k], &fault, detail, sizeof detail);
        char *copy = strdup(expressions[k]);
        void *reference = evaluator_create(copy);
        free(copy);
        double worst = 0.0;
        for (int n = 0; tree && reference && n < 2000; n++) {
            double values[3] = {0.05 + 3.0 * gsl_rng_uniform(rng), 2.0 * M_PI * gsl_rng_uniform(rng), 0.2 * gsl_rng_uniform(rng)};
            const double want = evaluator_evaluate(reference, 3, names, values);
            const double got = gb_expression_eval(tree, values[0], values[1], values[2]);
            worst = fmax(worst, fabs(got - want) / (1.0 + fabs(want)));
        }
        char quantity[200];
        snprintf(quantity, sizeof quantity, "%s at 2000 random (phi, theta, beta): the tree's value", expressions[k]);
        gb_check c = {"2", "7", quantity, "libmatheval's value of the same text",
                      "1e-13 relative: the same operations, but for libmatheval's folding of constants (a few ulps)"};
        if (!tree || !reference) {
            gb_check_true(&c, 0, "not read: fault %d (%s), libmatheval %s", (int)fault, detail, reference ? "read it" : "did not");
        } else {
            gb_check_close(&c, worst, 0.0, 0.0, 1e-13);
        }
        if (reference) evaluator_destroy(reference);
        gb_expression_free(tree);
    }
    gsl_rng_free(rng);
}

static void test_expression_enclosures(void)
{
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 90210);
    size_t boxes = 0, outside = 0;
    double widest = 0.0;
    for (size_t k = 0; k < sizeof expressions / sizeof expressions[0]; k++) {
        gb_expression_fault fault;
        char detail[128];
        gb_expression *tree = gb_expression_parse(expressions[k], &fault, detail, sizeof detail);
        if (!tree) continue;
        for (int n = 0; n < 300; n++) {
            /* boxes from 1e-6 to 1 rad wide, anywhere on the chart */
            const double width = pow(10.0, -6.0 + 6.0 * gsl_rng_uniform(rng)), beta = 0.2 * gsl_rng_uniform(rng);
            const double phi0 = 0.05 + (3.0 - width) * gsl_rng_uniform(rng), theta0 = (2.0 * M_PI - width) * gsl_rng_uniform(rng);
            const gb_interval box = gb_expression_enclose(tree, gb_interval_make(phi0, phi0 + width),
                                                          gb_interval_make(theta0, theta0 + width), beta);
            boxes++;
            if (isfinite(box.lo) && isfinite(box.hi)) widest = fmax(widest, box.hi - box.lo);
            for (int m = 0; m < 40; m++) {
                const double phi = phi0 + width * gsl_rng_uniform(rng), theta = theta0 + width * gsl_rng_uniform(rng);
                const double v = gb_expression_eval(tree, phi, theta, beta);
                outside += !(v >= box.lo && v <= box.hi);
            }
        }
        gb_expression_free(tree);
    }
    gsl_rng_free(rng);
    gb_check c = {"2", "7", "enclosures over 2700 random boxes (1e-6 to 1 rad) of the nine expressions, 40 points each",
                  "every point's value inside its box's enclosure", "exact: an enclosure encloses or it does not"};
    gb_check_true(&c, boxes == 2700 && outside == 0, "%zu boxes, %zu of %zu values outside; widest finite enclosure %.3g", boxes,
                  outside, 40 * boxes, widest);
}

static void test_expression_refusals(void)
{
    static const struct {
        const char *text;
        gb_expression_fault fault;
        const char *detail;
    } rows[] = {
        {"1 + 0.3*abs(cos(phi))", GB_EXPRESSION_NOT_SMOOTH, "abs"},
        {"1 + 0.1*step(phi - 1)", GB_EXPRESSION_NOT_SMOOTH, "step"},
        {"1 + delta(phi)", GB_EXPRESSION_NOT_SMOOTH, "delta"},
        {"1 + 0.2*tan(phi)", GB_EXPRESSION_NO_ENCLOSURE, "tan"},
        {"1 + asin(phi/4)", GB_EXPRESSION_NO_ENCLOSURE, "asin"},
        {"1 + psi", GB_EXPRESSION_SYNTAX, "psi"},
        {"(1 + phi", GB_EXPRESSION_SYNTAX, "a ')' is missing"},
        {"1 + phi theta", GB_EXPRESSION_SYNTAX, "words after the expression"},
    };
    size_t right = 0;
    char report[1024] = "";
    for (size_t k = 0; k < sizeof rows / sizeof rows[0]; k++) {
        gb_expression_fault fault;
        char detail[128];
        gb_expression *tree = gb_expression_parse(rows[k].text, &fault, detail, sizeof detail);
        const int ok = !tree && fault == rows[k].fault && strstr(detail, rows[k].detail);
        right += ok;
        if (!ok) snprintf(report + strlen(report), sizeof report - strlen(report), "%s: fault %d '%s'; ", rows[k].text, (int)fault, detail);
        gb_expression_free(tree);
    }
    gb_check c = {"2", "7", "the reader's refusals: abs, step, delta (not smooth), tan, asin (no enclosure), an unknown name, "
                  "an open parenthesis, words after the expression", "the fault and the word it names", "exact"};
    gb_check_true(&c, right == sizeof rows / sizeof rows[0], "%zu of %zu right; %s", right, sizeof rows / sizeof rows[0], report);
}

int verify_register_s2_expression(void)
{
    static const verify_test tests[] = {
        {"an expression's tree against libmatheval", test_expression_against_libmatheval, NULL},
        {"an expression's enclosures hold its values", test_expression_enclosures, NULL},
        {"an expression the bounds cannot take is named", test_expression_refusals, NULL},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Section 2: a body's expression bounded on intervals", tests);
}
