/* gb_case — scene files: a strict line reader in front of libinih, one table of keys with their
 * physical ranges, and the checks no single key can make (see gb_case.h). */
#include "gb_case.h"

#include "gb_error.h"
#include "gb_parse.h"

#include <errno.h>
#include <fcntl.h>
#include <ini.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

gb_case gb_case_default(void)
{
    gb_case c;
    memset(&c, 0, sizeof c);
    snprintf(c.description, sizeof c.description, "Table 1 defaults");
    gb_surface_init(&c.body, "I", 0.12);
    c.dynamics = gb_dynamics_default_def();
    c.A1 = c.dynamics.forcing.a1;
    c.A2 = c.dynamics.forcing.a2;
    c.integrate = gb_integrate_default_def();
    const double identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    memcpy(c.attitude, identity, sizeof identity);
    snprintf(c.attitude_text, sizeof c.attitude_text, "identity");
    c.write_history = c.write_summary = 1;
    c.monitors = 1;
    /* The paper samples "after transients" without saying how long: we discard the first 50 of the 300
     * periods for the strobe and the spectrum, and none for λ (Fig 9 starts at period 0). */
    c.strobe_def = (gb_strobe_def){.transient = 50, .phase = 0.0};
    c.spectrum_transient = 50;
    c.spectrum_window = GB_WINDOW_HANN;
    c.lyapunov_def = gb_lyapunov_default_def();
    c.lyapunov_interval_periods = 1;
    c.omega_scale = 0.0; /* the forcing omega */
    return c;
}

/* ---- the keys ---------------------------------------------------------------------------------- */

typedef enum key_kind {
    KEY_TEXT,      /* free text, a char array of GB_CASE_TEXT_MAX */
    KEY_NAME,      /* one of a module's names, parsed by `name` */
    KEY_REAL,      /* a number in [min, max] (ends open per `open`) */
    KEY_ANGLE,     /* a number or a multiple of pi, in [min, max] */
    KEY_COUNT,     /* an integer in [min, max], stored as size_t */
    KEY_FLAG,      /* yes/no, stored as int */
    KEY_VECTOR,    /* three numbers, each in [min, max] */
    KEY_GRID,      /* NPxNT */
    KEY_ATTITUDE   /* identity | axis-angle AX,AY,AZ,ANGLE */
} key_kind;

enum { OPEN_MIN = 1, OPEN_MAX = 2 };

typedef struct key_def {
    const char *section, *name;
    key_kind kind;
    double min, max;
    int open;           /* OPEN_MIN, OPEN_MAX: the range excludes that end */
    const char *units;  /* appended to the range, e.g. "[kg]" */
    size_t offset;      /* of the field in gb_case */
    int (*name_parse)(const char *value, gb_case *c); /* KEY_NAME: GB_OK, or GB_EINVAL with "(allowed: …)" */
} key_def;

static int parse_morphology(const char *value, gb_case *c)
{
    gb_surface body;
    const int status = gb_surface_init(&body, value, 0.0); /* its message lists the morphologies */
    if (!status) c->body.morphology = body.morphology;
    return status;
}
static int parse_units(const char *value, gb_case *c)
{
    static const char *const names[] = {"m/s2", "g"};
    int k;
    const int status = gb_error_parse_name(value, names, 2, "amplitude unit", &k);
    if (!status) c->amplitudes_in_g = k == 1;
    return status;
}
static int parse_equation(const char *value, gb_case *c) { return gb_dynamics_variant_parse(value, &c->dynamics.variant); }
static int parse_contact(const char *value, gb_case *c) { return gb_contact_model_parse(value, &c->dynamics.contact); }
static int parse_nodes(const char *value, gb_case *c) { return gb_contact_nodes_parse(value, &c->dynamics.grid.nodes); }
static int parse_method(const char *value, gb_case *c) { return gb_integrate_parse(value, &c->integrate.method); }
static int parse_window(const char *value, gb_case *c) { return gb_window_parse(value, &c->spectrum_window); }

#define AT(field) offsetof(gb_case, field)
#define NAME(sec, key, fn) {sec, key, KEY_NAME, 0, 0, 0, NULL, 0, fn}
#define REAL(sec, key, lo, hi, open, units, field) {sec, key, KEY_REAL, lo, hi, open, units, AT(field), NULL}
#define COUNT(sec, key, lo, hi, field) {sec, key, KEY_COUNT, lo, hi, 0, NULL, AT(field), NULL}
#define FLAG(sec, key, field) {sec, key, KEY_FLAG, 0, 0, 0, NULL, AT(field), NULL}

/* Every key a scene may set, with its physical range. The ranges are wide (they refuse what has no
 * physical meaning or would overflow later, not what is unusual) and are documented, generated from
 * this table, in cases/README.md. */
static const key_def keys[] = {
    {"scene", "description", KEY_TEXT, 0, 0, 0, NULL, AT(description), NULL},
    NAME("body", "morphology", parse_morphology),
    REAL("body", "beta", 0.0, GB_SURFACE_BETA_MAX, OPEN_MAX, "(r^4 = 1 + 4 beta sin(phi) cos(chi) > 0)", body.beta),
    REAL("body", "mass", 1e-6, 1e6, 0, "[kg]", dynamics.mass),
    REAL("forcing", "g", 0.0, 1000.0, 0, "[m/s2]", dynamics.forcing.g),
    REAL("forcing", "A1", -1000.0, 1000.0, 0, "[amplitude_units]", A1),
    REAL("forcing", "A2", -1000.0, 1000.0, 0, "[amplitude_units]", A2),
    NAME("forcing", "amplitude_units", parse_units),
    REAL("forcing", "omega", 0.01, 10000.0, 0, "[rad/s]", dynamics.forcing.omega),
    {"forcing", "psi", KEY_ANGLE, -1000.0, 1000.0, 0, "[rad]", AT(dynamics.forcing.psi), NULL},
    NAME("model", "equation", parse_equation),
    NAME("model", "contact", parse_contact),
    {"model", "grid", KEY_GRID, 0, 0, 0, NULL, 0, NULL},
    NAME("model", "nodes", parse_nodes),
    REAL("model", "damping", 0.0, 1000.0, 0, "[N m s]", dynamics.damping),
    NAME("integrator", "method", parse_method),
    COUNT("integrator", "steps_per_period", 1, 100000000, integrate.steps_per_period),
    REAL("integrator", "periods", 0.0, 1e7, OPEN_MIN, "[forcing periods]", integrate.periods),
    REAL("integrator", "rtol", 1e-15, 0.1, 0, "", integrate.rtol),
    REAL("integrator", "atol", 1e-15, 0.1, 0, "", integrate.atol),
    FLAG("integrator", "locate_switches", integrate.locate_switches),
    {"initial", "attitude", KEY_ATTITUDE, 0, 0, 0, NULL, 0, NULL},
    {"initial", "omega", KEY_VECTOR, -1000.0, 1000.0, 0, "[rad/s]", AT(omega0), NULL},
    FLAG("output", "history", write_history),
    FLAG("output", "summary", write_summary),
    COUNT("output", "sample_every", 1, 100000000, integrate.sample_every),
    FLAG("diagnostics", "monitors", monitors),
    FLAG("diagnostics", "strobe", strobe),
    FLAG("diagnostics", "spectrum", spectrum),
    FLAG("diagnostics", "lyapunov", lyapunov),
    COUNT("strobe", "transient_periods", 0, 10000000, strobe_def.transient),
    REAL("strobe", "phase", 0.0, 1.0, OPEN_MAX, "[forcing periods]", strobe_def.phase),
    COUNT("spectrum", "transient_periods", 0, 10000000, spectrum_transient),
    NAME("spectrum", "window", parse_window),
    REAL("lyapunov", "delta0", 1e-15, 0.1, 0, "", lyapunov_def.delta0),
    COUNT("lyapunov", "transient_periods", 0, 10000000, lyapunov_def.transient),
    COUNT("lyapunov", "interval_periods", 1, 10000000, lyapunov_interval_periods),
    COUNT("lyapunov", "batches", 2, 1000000, lyapunov_def.batches),
    REAL("lyapunov", "omega_scale", 1e-3, 1e6, 0, "[rad/s]", omega_scale),
};
enum { KEY_TOTAL = sizeof keys / sizeof keys[0] };
_Static_assert(KEY_TOTAL <= GB_CASE_KEY_MAX, "gb_case.key_line has a slot for every key");

static const char *const sections[] = {"scene", "body", "forcing", "model", "integrator", "initial",
                                       "output", "diagnostics", "strobe", "spectrum", "lyapunov"};
enum { SECTION_TOTAL = sizeof sections / sizeof sections[0] };

/* The range [min, max] of a key in words: "0 <= beta < 0.25", "an integer from 1 to 100000000". */
static void range_text(const key_def *k, char *out, size_t size)
{
    if (k->kind == KEY_COUNT) {
        snprintf(out, size, "an integer from %.0f to %.0f", k->min, k->max);
        return;
    }
    const char *what = k->kind == KEY_VECTOR ? "each component" : k->name;
    snprintf(out, size, "%.15g %s %s %s %.15g%s%s", k->min, k->open & OPEN_MIN ? "<" : "<=", what,
             k->open & OPEN_MAX ? "<" : "<=", k->max, k->units && k->units[0] ? " " : "", k->units ? k->units : "");
}

int gb_case_key_allowed(size_t index, const char **section, const char **name, char *allowed, size_t size)
{
    if (index >= KEY_TOTAL) return GB_EDOM;
    const key_def *k = &keys[index];
    *section = k->section;
    *name = k->name;
    char range[160];
    switch (k->kind) {
    case KEY_TEXT: snprintf(allowed, size, "text of at most %d bytes, UTF-8 without control characters", GB_CASE_TEXT_MAX - 1); break;
    case KEY_FLAG: snprintf(allowed, size, "yes, no"); break;
    case KEY_GRID: snprintf(allowed, size, "NPxNT with NP >= 2, NT >= 3, NP*NT <= %zu", GB_CONTACT_GRID_MAX_NODES); break;
    case KEY_ATTITUDE:
        snprintf(allowed, size, "identity, or axis-angle AX,AY,AZ,ANGLE with a non-zero axis, -1e6 <= AX, AY, AZ <= 1e6, -1000 <= ANGLE <= 1000 [rad]");
        break;
    case KEY_NAME: {
        gb_case scratch = gb_case_default();
        k->name_parse("", &scratch); /* no name is empty: the message lists the allowed ones */
        const char *list = strstr(gb_error_message(), "(allowed: ");
        snprintf(allowed, size, "%.*s", list ? (int)strlen(list + 10) - 1 : 0, list ? list + 10 : "");
        gb_error_clear();
        break;
    }
    case KEY_ANGLE:
        range_text(k, range, sizeof range);
        snprintf(allowed, size, "a number or p*pi/q, %s", range);
        break;
    case KEY_VECTOR:
        range_text(k, range, sizeof range);
        snprintf(allowed, size, "X,Y,Z, %s", range);
        break;
    default: range_text(k, allowed, size); break;
    }
    return GB_OK;
}

size_t gb_case_key_count(void) { return KEY_TOTAL; }

/* ---- the reader -------------------------------------------------------------------------------- */

typedef struct reader {
    gb_case *scene;
    const char *name;          /* the file, for messages */
    const char *text;          /* the whole file */
    size_t size, pos;
    int line;                  /* the line last handed to libinih */
    int error_line;            /* the first error found by the reader or the handler (0: none) */
    char message[768];         /* its text, without the file and line */
    int section_line[SECTION_TOTAL];
} reader;

static int reader_fail(reader *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int reader_fail(reader *r, const char *fmt, ...)
{
    if (r->error_line) return 0;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(r->message, sizeof r->message, fmt, ap);
    va_end(ap);
    r->error_line = r->line;
    return 0;
}

/* The length of the valid UTF-8 character at s (at most n bytes), or 0. Overlong forms, surrogates
 * and code points above U+10FFFF are not valid. *code gets the code point. */
static size_t utf8_length(const unsigned char *s, size_t n, unsigned *code)
{
    const unsigned c = s[0];
    size_t len;
    unsigned min;
    if (c < 0x80) return *code = c, 1;
    if (c >= 0xC2 && c <= 0xDF) len = 2, min = 0x80, *code = c & 0x1F;
    else if (c >= 0xE0 && c <= 0xEF) len = 3, min = 0x800, *code = c & 0x0F;
    else if (c >= 0xF0 && c <= 0xF4) len = 4, min = 0x10000, *code = c & 0x07;
    else return 0;
    if (len > n) return 0;
    for (size_t k = 1; k < len; k++) {
        if ((s[k] & 0xC0) != 0x80) return 0;
        *code = (*code << 6) | (s[k] & 0x3F);
    }
    if (*code < min || *code > 0x10FFFF || (*code >= 0xD800 && *code <= 0xDFFF)) return 0;
    return len;
}

/* Check one line's bytes: UTF-8, no NUL, no control character but TAB (C0, DEL, C1). */
static int line_bytes_ok(reader *r, const unsigned char *s, size_t n)
{
    for (size_t k = 0; k < n;) {
        unsigned code;
        const size_t len = utf8_length(s + k, n - k, &code);
        if (!len) return reader_fail(r, "byte 0x%02X at column %zu is not UTF-8 (allowed: UTF-8 text)", s[k], k + 1);
        if (code == 0) return reader_fail(r, "a NUL byte at column %zu (allowed: text without NUL bytes)", k + 1);
        if ((code < 0x20 && code != '\t') || (code >= 0x7F && code <= 0x9F))
            return reader_fail(r, "control character U+%04X at column %zu (allowed: printable text and TAB)", code, k + 1);
        k += len;
    }
    return 1;
}

static int section_index(const char *name, size_t len)
{
    for (int k = 0; k < SECTION_TOTAL; k++)
        if (strlen(sections[k]) == len && !strncmp(sections[k], name, len)) return k;
    return -1;
}

static void section_list(char *out, size_t size)
{
    size_t used = 0;
    for (int k = 0; k < SECTION_TOTAL && used < size; k++)
        used += (size_t)snprintf(out + used, size - used, "%s%s", k ? ", " : "", sections[k]);
}

/* A section header line (after leading blanks): known, and only once. */
static int check_section(reader *r, const char *p, size_t n)
{
    const char *end = memchr(p, ']', n);
    if (!end) return 1; /* libinih reports it as malformed */
    const size_t len = (size_t)(end - p - 1);
    /* libinih ignores what follows the ']': "[body] beta = 0.2" would lose its key without a word. */
    const char *rest = end + 1;
    while (rest < p + n && (*rest == ' ' || *rest == '\t')) rest++;
    if (rest < p + n && *rest != ';' && *rest != '#')
        return reader_fail(r, "text after [%.*s] (allowed: a section header alone on its line, or with a ; comment)",
                           (int)len, p + 1);
    const int k = section_index(p + 1, len);
    char list[256];
    section_list(list, sizeof list);
    if (k < 0) return reader_fail(r, "unknown section [%.*s] (allowed: %s)", (int)len, p + 1, list);
    if (r->section_line[k])
        return reader_fail(r, "[%s] again (first at line %d; allowed: each section once)", sections[k], r->section_line[k]);
    r->section_line[k] = r->line;
    return 1;
}

/* libinih's reader: hands over one line at a time, each checked first. An error ends the file. */
static char *next_line(char *out, int capacity, void *stream)
{
    reader *r = stream;
    if (r->error_line || r->pos >= r->size) return NULL;
    const char *start = r->text + r->pos;
    const char *newline = memchr(start, '\n', r->size - r->pos);
    size_t n = newline ? (size_t)(newline - start) : r->size - r->pos;
    r->pos += n + (newline != NULL);
    r->line++;
    if (n && start[n - 1] == '\r') n--; /* CRLF */
    if (r->line == 1 && n >= 3 && !memcmp(start, "\xEF\xBB\xBF", 3)) start += 3, n -= 3; /* a UTF-8 BOM */
    const size_t limit = (size_t)capacity - 2; /* the line, its newline and the NUL in libinih's buffer */
    if (n > limit) {
        reader_fail(r, "the line is %zu bytes long (allowed: at most %zu bytes a line)", n, limit);
        return NULL;
    }
    if (!line_bytes_ok(r, (const unsigned char *)start, n)) return NULL;
    size_t lead = 0;
    while (lead < n && (start[lead] == ' ' || start[lead] == '\t')) lead++;
    if (lead < n && start[lead] != ';' && start[lead] != '#') {
        if (lead > 0) {
            reader_fail(r, "an indented line (allowed: keys and [sections] start in the first column; continuation "
                           "lines are not read)");
            return NULL;
        }
        if (start[0] == '[' && !check_section(r, start, n)) return NULL;
    }
    memcpy(out, start, n);
    out[n] = '\n';
    out[n + 1] = '\0';
    return out;
}

static int key_fail(reader *r, const key_def *k, const char *value, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
static int key_fail(reader *r, const key_def *k, const char *value, const char *fmt, ...)
{
    char reason[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(reason, sizeof reason, fmt, ap);
    va_end(ap);
    return reader_fail(r, "[%s] %s = %s: %s", k->section, k->name, value, reason);
}

/* "not a number (allowed: …)", "out of range (allowed: …)", from a parse result and the key. */
static int value_fail(reader *r, const key_def *k, size_t index, const char *value, gb_parse_result result)
{
    const char *s, *n;
    char allowed[256];
    gb_case_key_allowed(index, &s, &n, allowed, sizeof allowed);
    const char *what = k->kind == KEY_COUNT ? "not an integer" : k->kind == KEY_FLAG ? "not a flag"
                     : k->kind == KEY_VECTOR ? "not three numbers" : k->kind == KEY_ANGLE ? "not an angle"
                     : k->kind == KEY_GRID ? "not a grid" : k->kind == KEY_ATTITUDE ? "not an attitude" : "not a number";
    /* GB_PARSE_LIMIT is a count too large, or a list of the wrong length (not of the allowed form). */
    const int wrong_form = result == GB_PARSE_SYNTAX || (result == GB_PARSE_LIMIT && k->kind != KEY_COUNT);
    const char *reason = wrong_form ? what : result == GB_PARSE_OVERFLOW ? "beyond the range of a double" : "out of range";
    return key_fail(r, k, value, "%s (allowed: %s)", reason, allowed);
}

static int in_range(const key_def *k, double x)
{
    const int above = k->open & OPEN_MIN ? x > k->min : x >= k->min;
    const int below = k->open & OPEN_MAX ? x < k->max : x <= k->max;
    return above && below;
}

/* R = rotation by `angle` about the unit `axis` (Rodrigues), row-major. */
static void axis_angle(const double axis[3], double angle, double R[9])
{
    const double c = cos(angle), s = sin(angle), t = 1 - c, x = axis[0], y = axis[1], z = axis[2];
    const double M[9] = {t * x * x + c, t * x * y - s * z, t * x * z + s * y, t * x * y + s * z, t * y * y + c,
                         t * y * z - s * x, t * x * z - s * y, t * y * z + s * x, t * z * z + c};
    memcpy(R, M, sizeof M);
}

static int set_attitude(reader *r, const key_def *k, size_t index, const char *value)
{
    gb_case *c = r->scene;
    if (!strcmp(value, "identity")) {
        const double identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        memcpy(c->attitude, identity, sizeof identity);
    } else {
        double v[4];
        const gb_parse_result p = strncmp(value, "axis-angle ", 11) ? GB_PARSE_SYNTAX : gb_parse_list(value + 11, v, 4);
        if (p) return value_fail(r, k, index, value, p);
        const double n = hypot(hypot(v[0], v[1]), v[2]);
        if (!(fabs(v[0]) <= 1e6 && fabs(v[1]) <= 1e6 && fabs(v[2]) <= 1e6 && n > 0.0 && fabs(v[3]) <= 1000.0))
            return value_fail(r, k, index, value, GB_PARSE_OK);
        const double axis[3] = {v[0] / n, v[1] / n, v[2] / n};
        axis_angle(axis, v[3], c->attitude);
    }
    snprintf(c->attitude_text, sizeof c->attitude_text, "%s", value);
    return 1;
}

static int set_value(reader *r, const key_def *k, size_t index, const char *value)
{
    gb_case *c = r->scene;
    char *field = (char *)c + k->offset;
    double x, v[3];
    unsigned long long n, np, nt;
    gb_parse_result p;
    switch (k->kind) {
    case KEY_TEXT:
        snprintf(field, GB_CASE_TEXT_MAX, "%s", value);
        return 1;
    case KEY_NAME:
        if (k->name_parse(value, c) == GB_OK) return 1;
        {
            const char *list = strstr(gb_error_message(), "(allowed: ");
            return key_fail(r, k, value, "unknown %s", list ? list : "");
        }
    case KEY_FLAG:
        if (!strcmp(value, "yes") || !strcmp(value, "true") || !strcmp(value, "1")) *(int *)field = 1;
        else if (!strcmp(value, "no") || !strcmp(value, "false") || !strcmp(value, "0")) *(int *)field = 0;
        else return value_fail(r, k, index, value, GB_PARSE_SYNTAX);
        return 1;
    case KEY_REAL:
    case KEY_ANGLE:
        p = k->kind == KEY_REAL ? gb_parse_double(value, &x) : gb_parse_angle(value, &x);
        if (p || !in_range(k, x)) return value_fail(r, k, index, value, p);
        *(double *)field = x;
        return 1;
    case KEY_COUNT:
        p = gb_parse_count(value, (unsigned long long)k->max, &n);
        if (p || (double)n < k->min) return value_fail(r, k, index, value, p);
        *(size_t *)field = (size_t)n;
        return 1;
    case KEY_VECTOR:
        p = gb_parse_list(value, v, 3);
        if (p || !in_range(k, v[0]) || !in_range(k, v[1]) || !in_range(k, v[2])) return value_fail(r, k, index, value, p);
        memcpy(field, v, sizeof v);
        return 1;
    case KEY_GRID:
        p = gb_parse_pair(value, GB_CONTACT_GRID_MAX_NODES, &np, &nt);
        if (p || np < 2 || nt < 3 || np > GB_CONTACT_GRID_MAX_NODES / nt) return value_fail(r, k, index, value, p);
        c->dynamics.grid.n_phi = (size_t)np;
        c->dynamics.grid.n_theta = (size_t)nt;
        return 1;
    case KEY_ATTITUDE: return set_attitude(r, k, index, value);
    }
    return 0;
}

static int handler(void *user, const char *section, const char *name, const char *value)
{
    reader *r = user;
    if (r->error_line) return 0;
    if (!section[0]) return reader_fail(r, "%s = %s: a key before any [section] (allowed: [section] first)", name, value);
    size_t index = KEY_TOTAL;
    char allowed[512] = "";
    size_t used = 0;
    for (size_t k = 0; k < KEY_TOTAL; k++) {
        if (strcmp(keys[k].section, section)) continue;
        if (!strcmp(keys[k].name, name)) index = k;
        used += (size_t)snprintf(allowed + used, sizeof allowed - used, "%s%s", used ? ", " : "", keys[k].name);
        if (used >= sizeof allowed) used = sizeof allowed - 1;
    }
    if (index == KEY_TOTAL) return reader_fail(r, "[%s] %s = %s: unknown key (allowed in [%s]: %s)", section, name, value, section, allowed);
    gb_case *c = r->scene;
    if (c->key_line[index])
        return reader_fail(r, "[%s] %s = %s: given twice (first at line %d; allowed: each key once)", section, name, value,
                           c->key_line[index]);
    c->key_line[index] = r->line;
    return set_value(r, &keys[index], index, value);
}

/* ---- what no single key can say ---------------------------------------------------------------- */

static int key_index(const char *section, const char *name)
{
    for (size_t k = 0; k < KEY_TOTAL; k++)
        if (!strcmp(keys[k].section, section) && !strcmp(keys[k].name, name)) return (int)k;
    return -1;
}

static int cross_fail(const char *path, const gb_case *c, const char *section, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 5, 6)));

static int cross_fail(const char *path, const gb_case *c, const char *section, const char *key, const char *fmt, ...)
{
    char reason[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(reason, sizeof reason, fmt, ap);
    va_end(ap);
    const int index = key_index(section, key), line = index >= 0 ? c->key_line[index] : 0;
    if (line) return gb_error_set(GB_EDOM, "%s:%d: [%s] %s: %s", path, line, section, key, reason);
    return gb_error_set(GB_EDOM, "%s: [%s] %s (default): %s", path, section, key, reason);
}

static int cross_check(const char *path, gb_case *c)
{
    const double periods = c->integrate.periods;
    const size_t spp = c->integrate.steps_per_period;
    /* The grid contact is piecewise constant in the attitude: the right-hand side jumps whenever the
     * lowest node changes, and an adaptive stepper's error control shrinks its step at every jump
     * (millions of steps a period). Such a pair has no useful result. */
    if (c->integrate.method != GB_INTEGRATOR_RK4 && c->dynamics.contact != GB_CONTACT_MODEL_CONTINUOUS)
        return cross_fail(path, c, "integrator", "method",
                          "= %s with [model] contact = %s: an adaptive stepper cannot cross the jumps of a grid "
                          "contact (its steps collapse at every node change) (allowed: rk4 with grid or fast-grid; "
                          "any method with contact = continuous)",
                          gb_integrate_name(c->integrate.method), gb_contact_model_name(c->dynamics.contact));
    if (c->strobe || c->spectrum || c->lyapunov) {
        if (spp % c->integrate.sample_every)
            return cross_fail(path, c, "output", "sample_every",
                              "%zu does not divide [integrator] steps_per_period = %zu (allowed: a divisor, so that "
                              "every strobe instant and the spectrum's samples fall on a sample)",
                              c->integrate.sample_every, spp);
    }
    if (c->strobe) {
        if (!((double)c->strobe_def.transient < periods))
            return cross_fail(path, c, "strobe", "transient_periods",
                              "= %zu leaves no strobe samples (allowed: < [integrator] periods = %g)",
                              c->strobe_def.transient, periods);
        const double on_grid = c->strobe_def.phase * (double)(spp / c->integrate.sample_every);
        if (fabs(on_grid - nearbyint(on_grid)) > 1e-9)
            return cross_fail(path, c, "strobe", "phase", "= %g is not on the sample grid (allowed: a multiple of %zu/%zu)",
                              c->strobe_def.phase, c->integrate.sample_every, spp);
    }
    if (c->spectrum && !((double)c->spectrum_transient + 1.0 <= periods))
        return cross_fail(path, c, "spectrum", "transient_periods",
                          "= %zu leaves less than one period (allowed: <= [integrator] periods - 1 = %g)",
                          c->spectrum_transient, periods - 1.0);
    if (c->lyapunov) return gb_case_lyapunov_check(path, c);
    return GB_OK;
}

int gb_case_lyapunov_check(const char *path, gb_case *c)
{
    gb_lyapunov_def *l = &c->lyapunov_def;
    const double periods = c->integrate.periods, k = (double)c->lyapunov_interval_periods;
    const double record = periods - (double)l->transient, intervals = record / k;
    if (!(record >= 2.0 * k) || fabs(intervals - nearbyint(intervals)) > 1e-9)
        return cross_fail(path, c, "lyapunov", "interval_periods",
                          "= %zu with transient_periods = %zu does not divide the %g periods of the run into whole "
                          "intervals (allowed: periods - transient_periods = a multiple of interval_periods, at least 2 "
                          "intervals)",
                          c->lyapunov_interval_periods, l->transient, periods);
    if ((double)l->batches > nearbyint(intervals))
        return cross_fail(path, c, "lyapunov", "batches",
                          "= %zu exceeds the %g intervals of the record (allowed: 2 <= batches <= intervals)", l->batches,
                          nearbyint(intervals));
    l->interval = k * 2.0 * M_PI / c->dynamics.forcing.omega;
    l->intervals = (size_t)nearbyint(intervals);
    if (c->omega_scale == 0.0) c->omega_scale = c->dynamics.forcing.omega;
    return GB_OK;
}

/* The text of line `line` (1-based) of `text`, at most `cap` bytes, for a message. */
static void line_text(const char *text, size_t size, int line, char *out, size_t cap)
{
    size_t pos = 0;
    for (int k = 1; k < line && pos < size; k++) {
        const char *nl = memchr(text + pos, '\n', size - pos);
        pos = nl ? (size_t)(nl - text) + 1 : size;
    }
    size_t n = 0;
    while (pos + n < size && text[pos + n] != '\n' && text[pos + n] != '\r' && n + 1 < cap) n++;
    memcpy(out, text + pos, n);
    out[n] = '\0';
}

int gb_case_load_text(const char *name, const char *text, size_t size, gb_case *out)
{
    gb_case scene = gb_case_default();
    reader r = {.scene = &scene, .name = name, .text = text, .size = size};
    const int ret = ini_parse_stream(next_line, &r, handler, &r);
    if (ret == -2) return gb_error_set(GB_ENOMEM, "%s: out of memory while reading", name);
    if (ret > 0 && (!r.error_line || ret < r.error_line)) {
        char bad[256];
        line_text(text, size, ret, bad, sizeof bad);
        return gb_error_set(GB_EINVAL, "%s:%d: malformed line '%s' (allowed: [section], key = value, ; comment)", name, ret, bad);
    }
    if (r.error_line) return gb_error_set(GB_EINVAL, "%s:%d: %s", name, r.error_line, r.message);
    const int status = cross_check(name, &scene);
    if (status) return status;
    /* Amplitudes in m/s² for the dynamics. */
    const double unit = scene.amplitudes_in_g ? scene.dynamics.forcing.g : 1.0;
    scene.dynamics.forcing.a1 = scene.A1 * unit;
    scene.dynamics.forcing.a2 = scene.A2 * unit;
    *out = scene;
    return GB_OK;
}

int gb_case_load(const char *path, gb_case *out)
{
    const int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return gb_error_set(GB_EINVAL, "%s: cannot open the case file: %s", path, strerror(errno));
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(fd);
        return gb_error_set(GB_EINVAL, "%s: not a regular file (allowed: a scene file, see cases/README.md)", path);
    }
    if (st.st_size > GB_CASE_FILE_MAX) {
        close(fd);
        return gb_error_set(GB_EINVAL, "%s: %lld bytes (allowed: a scene file of at most %d bytes)", path,
                            (long long)st.st_size, GB_CASE_FILE_MAX);
    }
    char *text = malloc((size_t)st.st_size + 1);
    if (!text) {
        close(fd);
        return gb_error_set(GB_ENOMEM, "%s: out of memory for %lld bytes", path, (long long)st.st_size);
    }
    size_t size = 0;
    for (;;) {
        const ssize_t got = read(fd, text + size, (size_t)st.st_size + 1 - size);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) {
            const int err = errno;
            free(text);
            close(fd);
            return gb_error_set(GB_EIO, "%s: cannot read the case file: %s", path, strerror(err));
        }
        if (got == 0) break;
        size += (size_t)got;
        if (size > (size_t)st.st_size) break; /* grew while read: at most the limit is read */
    }
    close(fd);
    int status;
    if (size > GB_CASE_FILE_MAX)
        status = gb_error_set(GB_EINVAL, "%s: more than %d bytes (allowed: a scene file of at most %d bytes)", path,
                              GB_CASE_FILE_MAX, GB_CASE_FILE_MAX);
    else
        status = gb_case_load_text(path, text, size, out);
    free(text);
    return status;
}
