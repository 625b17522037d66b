/* gb_expression — a body's expression as a tree, at a point and on intervals (gb_expression.h). */
#include "gb_expression.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef enum node_kind { NUMBER, PHI, THETA, BETA, ADD, SUB, MUL, DIV, POW, NEG, CALL } node_kind;

typedef enum function_id { F_EXP, F_LOG, F_SQRT, F_SIN, F_COS, F_SINH, F_COSH, F_TANH, F_ATAN, F_ASINH, F_ERF } function_id;

struct gb_expression {
    node_kind kind;
    double value;        /* NUMBER */
    function_id function; /* CALL */
    struct gb_expression *left, *right;
};

static const struct {
    const char *name;
    function_id id;
} enclosed[] = {{"exp", F_EXP},   {"log", F_LOG},   {"sqrt", F_SQRT}, {"sin", F_SIN},     {"cos", F_COS}, {"sinh", F_SINH},
                {"cosh", F_COSH}, {"tanh", F_TANH}, {"atan", F_ATAN}, {"asinh", F_ASINH}, {"erf", F_ERF}};
static const char *const not_smooth[] = {"abs", "step", "delta", "nandelta"};

typedef struct reader {
    const char *text, *at;
    gb_expression_fault fault;
    char *detail;
    size_t cap;
} reader;

static gb_expression *node(node_kind kind, gb_expression *left, gb_expression *right)
{
    gb_expression *e = calloc(1, sizeof *e);
    if (e) e->kind = kind, e->left = left, e->right = right;
    else gb_expression_free(left), gb_expression_free(right);
    return e;
}

static gb_expression *fail(reader *r, gb_expression_fault fault, const char *what)
{
    if (!r->fault) {
        r->fault = fault;
        snprintf(r->detail, r->cap, "%s", what);
    }
    return NULL;
}

static void skip_space(reader *r)
{
    while (*r->at == ' ' || *r->at == '\t') r->at++;
}

static gb_expression *sum(reader *r);

static gb_expression *primary(reader *r)
{
    skip_space(r);
    const char *p = r->at;
    if (*p == '(') {
        r->at++;
        gb_expression *inner = sum(r);
        skip_space(r);
        if (!inner) return NULL;
        if (*r->at != ')') return gb_expression_free(inner), fail(r, GB_EXPRESSION_SYNTAX, "a ')' is missing");
        r->at++;
        return inner;
    }
    if (isdigit((unsigned char)*p) || (*p == '.' && isdigit((unsigned char)p[1]))) { /* [0-9]*.?[0-9]*([eE][+-]?[0-9]+)? */
        const char *q = p;
        while (isdigit((unsigned char)*q)) q++;
        if (*q == '.') q++;
        while (isdigit((unsigned char)*q)) q++;
        if ((*q == 'e' || *q == 'E') && (isdigit((unsigned char)q[1]) || ((q[1] == '+' || q[1] == '-') && isdigit((unsigned char)q[2])))) {
            q += 2;
            while (isdigit((unsigned char)*q)) q++;
        }
        char number[128];
        if ((size_t)(q - p) >= sizeof number) return fail(r, GB_EXPRESSION_SYNTAX, "a number of more than 127 characters");
        memcpy(number, p, (size_t)(q - p));
        number[q - p] = '\0';
        gb_expression *e = node(NUMBER, NULL, NULL);
        if (e) e->value = strtod(number, NULL);
        r->at = q;
        return e;
    }
    if (isalpha((unsigned char)*p) || *p == '_') {
        const char *q = p;
        while (isalnum((unsigned char)*q) || *q == '_') q++;
        char name[64];
        snprintf(name, sizeof name, "%.*s", (int)(q - p < 63 ? q - p : 63), p);
        r->at = q;
        skip_space(r);
        if (*r->at == '(') {
            for (size_t k = 0; k < sizeof not_smooth / sizeof not_smooth[0]; k++)
                if (!strcmp(name, not_smooth[k])) return fail(r, GB_EXPRESSION_NOT_SMOOTH, name);
            for (size_t k = 0; k < sizeof enclosed / sizeof enclosed[0]; k++)
                if (!strcmp(name, enclosed[k].name)) {
                    r->at++;
                    gb_expression *arg = sum(r);
                    skip_space(r);
                    if (!arg) return NULL;
                    if (*r->at != ')') return gb_expression_free(arg), fail(r, GB_EXPRESSION_SYNTAX, "a ')' is missing");
                    r->at++;
                    gb_expression *e = node(CALL, arg, NULL);
                    if (e) e->function = enclosed[k].id;
                    return e;
                }
            return fail(r, GB_EXPRESSION_NO_ENCLOSURE, name);
        }
        if (!strcmp(name, "phi")) return node(PHI, NULL, NULL);
        if (!strcmp(name, "theta")) return node(THETA, NULL, NULL);
        if (!strcmp(name, "beta")) return node(BETA, NULL, NULL);
        gb_expression *e = node(NUMBER, NULL, NULL);
        if (e && !strcmp(name, "pi")) e->value = M_PI;
        else if (e && !strcmp(name, "e")) e->value = M_E;
        else return gb_expression_free(e), fail(r, GB_EXPRESSION_SYNTAX, name);
        return e;
    }
    return fail(r, GB_EXPRESSION_SYNTAX, *p ? "an unexpected character" : "the text ends early");
}

static gb_expression *power(reader *r);

/* After '^': a unary minus takes the whole power chain that follows it (libmatheval: 2^-1^2 = 2^(-(1^2))). */
static gb_expression *exponent(reader *r)
{
    skip_space(r);
    if (*r->at == '-') {
        r->at++;
        gb_expression *inner = power(r);
        return inner ? node(NEG, inner, NULL) : NULL;
    }
    return primary(r);
}

static gb_expression *power(reader *r) /* left-associative: 2^3^2 = (2^3)^2 */
{
    gb_expression *e = primary(r);
    for (skip_space(r); e && *r->at == '^'; skip_space(r)) {
        r->at++;
        gb_expression *x = exponent(r);
        e = x ? node(POW, e, x) : (gb_expression_free(e), NULL);
    }
    return e;
}

static gb_expression *unary(reader *r) /* -a^b = -(a^b); -a*b = (-a)*b */
{
    skip_space(r);
    if (*r->at == '-') {
        r->at++;
        gb_expression *inner = unary(r);
        return inner ? node(NEG, inner, NULL) : NULL;
    }
    return power(r);
}

static gb_expression *product(reader *r)
{
    gb_expression *e = unary(r);
    for (skip_space(r); e && (*r->at == '*' || *r->at == '/'); skip_space(r)) {
        const node_kind kind = *r->at++ == '*' ? MUL : DIV;
        gb_expression *x = unary(r);
        e = x ? node(kind, e, x) : (gb_expression_free(e), NULL);
    }
    return e;
}

static gb_expression *sum(reader *r)
{
    gb_expression *e = product(r);
    for (skip_space(r); e && (*r->at == '+' || *r->at == '-'); skip_space(r)) {
        const node_kind kind = *r->at++ == '+' ? ADD : SUB;
        gb_expression *x = product(r);
        e = x ? node(kind, e, x) : (gb_expression_free(e), NULL);
    }
    return e;
}

gb_expression *gb_expression_parse(const char *text, gb_expression_fault *fault, char *detail, size_t cap)
{
    reader r = {text, text, GB_EXPRESSION_OK, detail, cap};
    if (cap) detail[0] = '\0';
    gb_expression *e = sum(&r);
    skip_space(&r);
    if (e && *r.at) {
        gb_expression_free(e);
        e = fail(&r, GB_EXPRESSION_SYNTAX, "words after the expression");
    }
    if (!e && !r.fault) r.fault = GB_EXPRESSION_SYNTAX, snprintf(detail, cap, "out of memory");
    *fault = r.fault;
    return e;
}

void gb_expression_free(gb_expression *e)
{
    if (!e) return;
    gb_expression_free(e->left);
    gb_expression_free(e->right);
    free(e);
}

static double apply(function_id f, double x)
{
    switch (f) {
    case F_EXP: return exp(x);
    case F_LOG: return log(x);
    case F_SQRT: return sqrt(x);
    case F_SIN: return sin(x);
    case F_COS: return cos(x);
    case F_SINH: return sinh(x);
    case F_COSH: return cosh(x);
    case F_TANH: return tanh(x);
    case F_ATAN: return atan(x);
    case F_ASINH: return asinh(x);
    default: return erf(x);
    }
}

double gb_expression_eval(const gb_expression *e, double phi, double theta, double beta)
{
    switch (e->kind) {
    case NUMBER: return e->value;
    case PHI: return phi;
    case THETA: return theta;
    case BETA: return beta;
    case NEG: return -gb_expression_eval(e->left, phi, theta, beta);
    case CALL: return apply(e->function, gb_expression_eval(e->left, phi, theta, beta));
    default: break;
    }
    const double a = gb_expression_eval(e->left, phi, theta, beta), b = gb_expression_eval(e->right, phi, theta, beta);
    switch (e->kind) {
    case ADD: return a + b;
    case SUB: return a - b;
    case MUL: return a * b;
    case DIV: return a / b;
    default: return pow(a, b);
    }
}

static const gb_interval whole_line = {-INFINITY, INFINITY};

/* An enclosure whose end is NaN (0·∞, ∞ − ∞) encloses nothing known: the whole line. */
static gb_interval known(gb_interval a) { return isnan(a.lo) || isnan(a.hi) ? whole_line : a; }

/* [lo, hi] widened by 8 ulps relative (and DBL_MIN): glibc's libm documents at most 3 ulps of error for exp, log,
 * sinh, cosh, tanh, atan, asinh and erf on x86-64 (its libm-test-ulps), which gb_interval_make's 2ε relative
 * (2 ulps at worst) would not always cover. */
static gb_interval libm_enclosure(double lo, double hi)
{
    const double slack = 8.0 * DBL_EPSILON;
    return known((gb_interval){lo - slack * fabs(lo) - DBL_MIN, hi + slack * fabs(hi) + DBL_MIN});
}

/* A function increasing over the interval (its domain checked by the caller). */
static gb_interval increasing(function_id f, gb_interval a) { return libm_enclosure(apply(f, a.lo), apply(f, a.hi)); }

static gb_interval enclose_call(function_id f, gb_interval a)
{
    switch (f) {
    case F_SIN: return gb_interval_sin(a);
    case F_COS: return gb_interval_cos(a);
    case F_LOG:
    case F_SQRT: return a.lo > 0.0 ? increasing(f, a) : whole_line; /* undefined (NaN) below 0: not bounded */
    case F_COSH: {
        const double m = gb_interval_max(fabs(a.lo), fabs(a.hi));
        const double low = a.lo <= 0.0 && a.hi >= 0.0 ? 1.0 : cosh(gb_interval_min(fabs(a.lo), fabs(a.hi)));
        return libm_enclosure(low, cosh(m));
    }
    default: return increasing(f, a); /* exp, sinh, tanh, atan, asinh, erf */
    }
}

/* A constant integer exponent (a number, or minus one, written as an integer up to 1024): *n. */
static int integer_exponent(const gb_expression *e, double *n)
{
    const int negative = e->kind == NEG;
    if (negative) e = e->left;
    if (e->kind != NUMBER || e->value != nearbyint(e->value) || fabs(e->value) > 1024.0) return 0;
    *n = negative ? -e->value : e->value;
    return 1;
}

static gb_interval enclose_power(gb_interval a, gb_interval b, const gb_expression *exponent_node)
{
    double n;
    if (integer_exponent(exponent_node, &n)) { /* x^n for an integer n */
        if (n == 0.0) return gb_interval_point(1.0);
        gb_interval m = a; /* |a| for an even n */
        if (fmod(n, 2.0) == 0.0) {
            const double lo = a.lo <= 0.0 && a.hi >= 0.0 ? 0.0 : gb_interval_min(fabs(a.lo), fabs(a.hi));
            m = (gb_interval){lo, gb_interval_max(fabs(a.lo), fabs(a.hi))};
        }
        const double k = fabs(n);
        /* x^k increasing on [0, ∞) and, for an odd k, on the whole line; pow's error widened by k ulps */
        gb_interval p = known((gb_interval){pow(m.lo, k), pow(m.hi, k)});
        const double slack = k * 2.0 * DBL_EPSILON;
        p = (gb_interval){p.lo - slack * fabs(p.lo) - DBL_MIN, p.hi + slack * fabs(p.hi) + DBL_MIN};
        return n > 0.0 ? p : known(gb_interval_recip(p));
    }
    if (!(a.lo > 0.0)) return whole_line; /* a real power of a base that may be ≤ 0 */
    /* a^b = exp(b log a) */
    return enclose_call(F_EXP, known(gb_interval_mul(b, enclose_call(F_LOG, a))));
}

gb_interval gb_expression_enclose(const gb_expression *e, gb_interval phi, gb_interval theta, double beta)
{
    switch (e->kind) {
    case NUMBER: return gb_interval_make(e->value, e->value); /* pi and e are one rounding from their values */
    case PHI: return phi;
    case THETA: return theta;
    case BETA: return gb_interval_point(beta);
    case NEG: return gb_interval_neg(gb_expression_enclose(e->left, phi, theta, beta));
    case CALL: return enclose_call(e->function, gb_expression_enclose(e->left, phi, theta, beta));
    default: break;
    }
    const gb_interval a = gb_expression_enclose(e->left, phi, theta, beta), b = gb_expression_enclose(e->right, phi, theta, beta);
    switch (e->kind) {
    case ADD: return known(gb_interval_add(a, b));
    case SUB: return known(gb_interval_sub(a, b));
    case MUL: return known(gb_interval_mul(a, b));
    case DIV: return known(gb_interval_mul(a, gb_interval_recip(b)));
    default: return enclose_power(a, b, e->right);
    }
}
