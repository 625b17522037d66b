/* gb_parse — strict whole-token parsers of numbers, counts, lists and angles (see gb_parse.h). */
#include "gb_parse.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

const char *gb_parse_describe(gb_parse_result result, const char *what)
{
    switch (result) {
    case GB_PARSE_OK: return "accepted";
    case GB_PARSE_OVERFLOW: return "beyond the range of a double";
    case GB_PARSE_LIMIT: return "too large";
    default: return what;
    }
}

static int is_digit(char c) { return c >= '0' && c <= '9'; }

/* The length of the decimal number at the start of `text` ([+-]d[.d][e[+-]d]), or 0 when there is none. */
static size_t number_length(const char *text)
{
    size_t k = 0, digits = 0;
    if (text[k] == '+' || text[k] == '-') k++;
    while (is_digit(text[k])) k++, digits++;
    if (text[k] == '.') {
        k++;
        while (is_digit(text[k])) k++, digits++;
    }
    if (!digits) return 0;
    if (text[k] == 'e' || text[k] == 'E') {
        size_t e = k + 1, exponent_digits = 0;
        if (text[e] == '+' || text[e] == '-') e++;
        while (is_digit(text[e])) e++, exponent_digits++;
        if (!exponent_digits) return 0; /* "1e" or "1e+" */
        k = e;
    }
    return k;
}

/* Convert the number in text[0 .. length) (already checked to be one). */
static gb_parse_result convert(const char *text, size_t length, double *value)
{
    char small[64], *copy = length < sizeof small ? small : malloc(length + 1);
    if (!copy) return GB_PARSE_SYNTAX;
    memcpy(copy, text, length);
    copy[length] = '\0';
    errno = 0;
    const double v = strtod(copy, NULL);
    const int range = errno == ERANGE;
    if (copy != small) free(copy);
    if (range && isinf(v)) return GB_PARSE_OVERFLOW; /* beyond DBL_MAX; an underflow is the nearest double */
    *value = v;
    return GB_PARSE_OK;
}

gb_parse_result gb_parse_double(const char *text, double *value)
{
    const size_t n = number_length(text);
    if (!n || text[n] != '\0') return GB_PARSE_SYNTAX;
    return convert(text, n, value);
}

gb_parse_result gb_parse_count(const char *text, unsigned long long max, unsigned long long *value)
{
    unsigned long long v = 0;
    size_t k = 0;
    for (; is_digit(text[k]); k++) {
        const unsigned digit = (unsigned)(text[k] - '0');
        if (digit > max || v > (max - digit) / 10) { /* (max − digit) must not wrap below 0 */
            /* Still a count, only too large: say so, once the rest is known to be digits. */
            while (is_digit(text[k])) k++;
            return text[k] == '\0' ? GB_PARSE_LIMIT : GB_PARSE_SYNTAX;
        }
        v = 10 * v + digit;
    }
    if (k == 0 || text[k] != '\0') return GB_PARSE_SYNTAX;
    *value = v;
    return GB_PARSE_OK;
}

static const char *skip_blanks(const char *p)
{
    while (*p == ' ' || *p == '\t') p++;
    return p;
}

gb_parse_result gb_parse_list(const char *text, double *values, int n)
{
    const char *p = skip_blanks(text);
    for (int k = 0; k < n; k++) {
        const size_t len = number_length(p);
        if (!len) return GB_PARSE_SYNTAX;
        const gb_parse_result r = convert(p, len, &values[k]);
        if (r) return r;
        p = skip_blanks(p + len);
        if (k < n - 1) {
            if (*p != ',') return *p == '\0' ? GB_PARSE_LIMIT : GB_PARSE_SYNTAX;
            p = skip_blanks(p + 1);
        }
    }
    if (*p == ',') return GB_PARSE_LIMIT;
    return *p == '\0' ? GB_PARSE_OK : GB_PARSE_SYNTAX;
}

gb_parse_result gb_parse_angle(const char *text, double *value)
{
    if (gb_parse_double(text, value) == GB_PARSE_OK) return GB_PARSE_OK;
    double p = 1.0, q = 1.0;
    const char *s = text;
    const size_t len = number_length(s);
    if (len) {
        const gb_parse_result r = convert(s, len, &p);
        if (r) return r;
        s += len;
        if (*s == '*') s++;
    } else if (*s == '-' || *s == '+') {
        p = *s == '-' ? -1.0 : 1.0; /* "-pi/3" */
        s++;
    }
    if (strncmp(s, "pi", 2) != 0) return GB_PARSE_SYNTAX;
    s += 2;
    if (*s == '/') {
        const gb_parse_result r = gb_parse_double(s + 1, &q);
        if (r) return r;
        if (q == 0.0) return GB_PARSE_SYNTAX;
    } else if (*s != '\0') {
        return GB_PARSE_SYNTAX;
    }
    const double v = p * M_PI / q;
    if (!isfinite(v)) return GB_PARSE_OVERFLOW;
    *value = v;
    return GB_PARSE_OK;
}

gb_parse_result gb_parse_pair(const char *text, unsigned long long max, unsigned long long *a, unsigned long long *b)
{
    const char *x = strpbrk(text, "xX");
    if (!x || x == text) return GB_PARSE_SYNTAX;
    char first[32];
    const size_t n = (size_t)(x - text);
    if (n >= sizeof first) return GB_PARSE_SYNTAX;
    memcpy(first, text, n);
    first[n] = '\0';
    const gb_parse_result ra = gb_parse_count(first, max, a), rb = gb_parse_count(x + 1, max, b);
    if (ra == GB_PARSE_SYNTAX || rb == GB_PARSE_SYNTAX) return GB_PARSE_SYNTAX;
    return ra ? ra : rb;
}
