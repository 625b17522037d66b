/* gb_case — scene files: a strict line reader in front of libinih and one table of keys with their physical ranges
 * (see gb_case.h); the checks no single key can make are gb_case_check.c's. */
#include "gb_case.h"
#include "gb_case_internal.h"

#include "gb_body.h"
#include "gb_error.h"
#include "gb_file.h"
#include "gb_impact.h"
#include "gb_ini.h"
#include "gb_parse.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/resource.h>

gb_case gb_case_default(void)
{
    gb_case c;
    memset(&c, 0, sizeof c);
    snprintf(c.description, sizeof c.description, "Table 1 defaults");
    gb_surface_init(&c.body, "I", 0.12);
    c.dynamics = gb_dynamics_default_def(); /* the library's defaults are the scene's */
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
    c.spectrum_window = GB_SPECTRUM_WINDOW_HANN;
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

enum {
    OPEN_MIN = 1,
    OPEN_MAX = 2,
    COUNT_CHOSEN = 4, /* a count that may be "chosen" (GB_LYAPUNOV_CHOSEN) */
    REAL_ROUGH = 8    /* a number that may be "rough" (INFINITY: the friction of a perfectly rough plane) */
};

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
static int parse_certificate(const char *value, gb_case *c)
{
    return gb_dynamics_certificate_parse(value, &c->dynamics.certificate);
}
static int parse_contact_law(const char *value, gb_case *c)
{
    return gb_dynamics_contact_law_parse(value, &c->dynamics.contact_law);
}
static int parse_nodes(const char *value, gb_case *c) { return gb_contact_nodes_parse(value, &c->dynamics.grid.nodes); }
static int parse_method(const char *value, gb_case *c) { return gb_integrate_parse(value, &c->integrate.method); }
static int parse_strategy(const char *value, gb_case *c) { return gb_integrate_strategy_parse(value, &c->integrate.strategy); }
static int parse_hand_over(const char *value, gb_case *c)
{
    static const char *const names[] = {"none", "time-stepping"};
    return gb_error_parse_name(value, names, 2, "hand_over", &c->integrate.hand_over);
}
static int parse_window(const char *value, gb_case *c) { return gb_spectrum_window_parse(value, &c->spectrum_window); }

#define AT(field) offsetof(gb_case, field)
#define NAME(sec, key, fn) {sec, key, KEY_NAME, 0, 0, 0, NULL, 0, fn}
#define REAL(sec, key, lo, hi, open, units, field) {sec, key, KEY_REAL, lo, hi, open, units, AT(field), NULL}
#define COUNT(sec, key, lo, hi, field) {sec, key, KEY_COUNT, lo, hi, 0, NULL, AT(field), NULL}
#define CHOSEN_COUNT(sec, key, lo, hi, field) {sec, key, KEY_COUNT, lo, hi, COUNT_CHOSEN, NULL, AT(field), NULL}
#define FLAG(sec, key, field) {sec, key, KEY_FLAG, 0, 0, 0, NULL, AT(field), NULL}

/* Every key a scene may set, with its physical range. The ranges are wide (they refuse what has no
 * physical meaning or would overflow later, not what is unusual) and are documented, generated from
 * this table, in cases/README.md. */
static const key_def keys[] = {
    {"scene", "description", KEY_TEXT, 0, 0, 0, NULL, AT(description), NULL},
    NAME("body", "morphology", parse_morphology),
    REAL("body", "beta", 0.0, GB_SURFACE_BETA_MAX, OPEN_MAX, "(r^4 = 1 + 4 beta sin(phi) cos(chi) > 0)", body.beta),
    {"body", "mesh", KEY_TEXT, 0, 0, 0, NULL, AT(mesh), NULL},
    {"body", "r", KEY_TEXT, 0, 0, 0, NULL, AT(r_text), NULL},
    {"body", "chi", KEY_TEXT, 0, 0, 0, NULL, AT(chi_text), NULL},
    REAL("body", "mass", 1e-6, 1e6, 0, "[kg]", dynamics.mass),
    REAL("forcing", "g", 0.0, 1000.0, 0, "[m/s2]", dynamics.forcing.g),
    REAL("forcing", "A1", -1000.0, 1000.0, 0, "[amplitude_units]", A1),
    REAL("forcing", "A2", -1000.0, 1000.0, 0, "[amplitude_units]", A2),
    NAME("forcing", "amplitude_units", parse_units),
    REAL("forcing", "omega", 0.01, 10000.0, 0, "[rad/s]", dynamics.forcing.omega),
    {"forcing", "psi", KEY_ANGLE, -1000.0, 1000.0, 0, "[rad]", AT(dynamics.forcing.psi), NULL},
    NAME("model", "equation", parse_equation),
    NAME("model", "contact", parse_contact),
    NAME("model", "certificate", parse_certificate),
    NAME("model", "contact_law", parse_contact_law),
    {"model", "grid", KEY_GRID, 0, 0, 0, NULL, 0, NULL},
    NAME("model", "nodes", parse_nodes),
    REAL("model", "damping", 0.0, 1000.0, 0, "[N m s]", dynamics.damping),
    REAL("model", "friction", 0.0, 1000.0, OPEN_MIN | REAL_ROUGH, "(the plane's Coulomb mu; needs contact_law = unilateral or compliant)",
         dynamics.friction),
    REAL("model", "restitution", 0.0, GB_IMPACT_RESTITUTION_MAX, 0, "(Newton's e; needs contact_law = unilateral)", dynamics.restitution),
    NAME("integrator", "method", parse_method),
    COUNT("integrator", "steps_per_period", 1, 100000000, integrate.steps_per_period),
    REAL("integrator", "periods", 0.0, 1e7, OPEN_MIN, "[forcing periods]", integrate.periods),
    REAL("integrator", "rtol", 1e-15, 0.1, 0, "", integrate.rtol),
    REAL("integrator", "atol", 1e-15, 0.1, 0, "", integrate.atol),
    FLAG("integrator", "locate_switches", integrate.locate_switches),
    NAME("integrator", "strategy", parse_strategy),
    NAME("integrator", "hand_over", parse_hand_over),
    REAL("integrator", "theta", 0.5, 1.0, 0, "(the theta-method's weight of the step's end; needs strategy or hand_over = time-stepping)",
         integrate.theta),
    REAL("integrator", "solver_tolerance", 1e-16, 1e-3, 0, "(the contact problem's relative residual; needs strategy or hand_over = "
         "time-stepping)", integrate.solver_tolerance),
    COUNT("integrator", "solver_iterations", 1, 100000000, integrate.solver_iterations),
    {"initial", "attitude", KEY_ATTITUDE, 0, 0, 0, NULL, 0, NULL},
    {"initial", "omega", KEY_VECTOR, -1000.0, 1000.0, 0, "[rad/s]", AT(omega0), NULL},
    REAL("initial", "height", 0.0, 1e6, 0, "[m] (the lowest point above the plane; needs contact_law = unilateral)",
         dynamics.height0),
    {"initial", "velocity", KEY_VECTOR, -1e4, 1e4, 0, "[m/s] (the centroid, inertial axes; needs contact_law = unilateral)",
     AT(dynamics.velocity0), NULL},
    FLAG("output", "history", write_history),
    FLAG("output", "summary", write_summary),
    FLAG("output", "impacts", write_impacts),
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
    COUNT("lyapunov", "window_periods", 0, 10000000, lyapunov_window_periods),
    CHOSEN_COUNT("lyapunov", "warmup_intervals", 0, 10000000, lyapunov_def.warmup),
    CHOSEN_COUNT("lyapunov", "batches", 2, 1000000, lyapunov_def.batches),
    REAL("lyapunov", "omega_scale", 1e-3, 1e6, 0, "[rad/s]", omega_scale),
};
enum { KEY_TOTAL = sizeof keys / sizeof keys[0] };
_Static_assert(KEY_TOTAL <= GB_CASE_KEY_MAX, "gb_case.key_line has a slot for every key");

/* Every key: this table's, then each contact law's own (gb_dynamics_law_key_at: [model] reals in the law's slots of
 * law_coefficients), numbered after them. */
static size_t key_total(void)
{
    const size_t n = KEY_TOTAL + gb_dynamics_law_key_count();
    return n <= GB_CASE_KEY_MAX ? n : GB_CASE_KEY_MAX; /* more: every scene is refused (gb_case_load_text_with) */
}

/* Key `index` (< key_total()), into *scratch for a law's key. */
static const key_def *key_at(size_t index, key_def *scratch)
{
    if (index < KEY_TOTAL) return &keys[index];
    const gb_dynamics_law_key *k = gb_dynamics_law_key_at(index - KEY_TOTAL, NULL);
    *scratch = (key_def){"model", k->name, KEY_REAL, k->min, k->max, k->open_min ? OPEN_MIN : 0, k->meaning,
                         AT(dynamics.law_coefficients) + (size_t)k->slot * sizeof(double), NULL};
    return scratch;
}

static const char *const sections[] = {"scene", "body", "forcing", "model", "integrator", "initial",
                                       "output", "diagnostics", "strobe", "spectrum", "lyapunov"};
enum { SECTION_TOTAL = sizeof sections / sizeof sections[0] };

/* The range [min, max] of a key in words: "0 <= beta < 0.25", "an integer from 1 to 100000000". */
static void range_text(const key_def *k, char *out, size_t size)
{
    if (k->kind == KEY_COUNT) {
        snprintf(out, size, "%san integer from %.0f to %.0f", k->open & COUNT_CHOSEN ? "chosen (from the record), or " : "",
                 k->min, k->max);
        return;
    }
    const char *what = k->kind == KEY_VECTOR ? "each component" : k->name;
    snprintf(out, size, "%s%.15g %s %s %s %.15g%s%s", k->open & REAL_ROUGH ? "rough, or " : "", k->min,
             k->open & OPEN_MIN ? "<" : "<=", what, k->open & OPEN_MAX ? "<" : "<=", k->max, k->units && k->units[0] ? " " : "",
             k->units ? k->units : "");
}

int gb_case_key_numeric(const char *section, const char *name)
{
    key_def scratch;
    for (size_t i = 0; i < key_total(); i++) {
        const key_def *k = key_at(i, &scratch);
        if (!strcmp(k->section, section) && !strcmp(k->name, name))
            return k->kind == KEY_REAL || k->kind == KEY_ANGLE || k->kind == KEY_COUNT;
    }
    return -1;
}

int gb_case_key_allowed(size_t index, const char **section, const char **name, char *allowed, size_t size)
{
    if (index >= key_total()) return GB_EDOM;
    key_def scratch;
    const key_def *k = key_at(index, &scratch);
    *section = k->section;
    *name = k->name;
    char range[160];
    switch (k->kind) {
    case KEY_TEXT: /* what fits on its line beside "key = " */
        snprintf(allowed, size, "text of at most %d bytes (a line holds %d), UTF-8 without control characters",
                 GB_INI_LINE_MAX - (int)strlen(k->name) - 3, GB_INI_LINE_MAX);
        break;
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

size_t gb_case_key_count(void) { return KEY_TOTAL + gb_dynamics_law_key_count(); }
size_t gb_case_table_key_count(void) { return KEY_TOTAL; }
size_t gb_case_key_total(void) { return key_total(); }

/* ---- the reader -------------------------------------------------------------------------------- */

/* The scene being read: by gb_ini's handler (ini set) or by an override (the message kept here). */
typedef struct reader {
    gb_ini_reader *ini;
    gb_case *scene;
    char message[768];
} reader;

static int reader_fail(reader *r, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int reader_fail(reader *r, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(r->message, sizeof r->message, fmt, ap);
    va_end(ap);
    return r->ini ? gb_ini_fail(r->ini, "%s", r->message) : 0;
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
        if (!(fabs(v[0]) <= 1e6 && fabs(v[1]) <= 1e6 && fabs(v[2]) <= 1e6 && fabs(v[3]) <= 1000.0))
            return value_fail(r, k, index, value, GB_PARSE_OK);
        /* An axis of tiny components (subnormal ones carry few bits, and their squares vanish) is scaled by its
         * largest first; any other is normalised as written, so that its bits are those it always had. */
        const double largest = fmax(fabs(v[0]), fmax(fabs(v[1]), fabs(v[2])));
        if (largest > 0.0 && largest < 1e-100)
            for (int i = 0; i < 3; i++) v[i] /= largest;
        const double n = hypot(hypot(v[0], v[1]), v[2]);
        if (!(n > 0.0)) return value_fail(r, k, index, value, GB_PARSE_OK);
        const double axis[3] = {v[0] / n, v[1] / n, v[2] / n};
        axis_angle(axis, v[3], c->attitude);
        double worst = 0.0; /* as gb_dynamics_init_state will judge it */
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) {
                const double *R = c->attitude, dot = R[i] * R[j] + R[3 + i] * R[3 + j] + R[6 + i] * R[6 + j];
                worst = fmax(worst, fabs(dot - (i == j)));
            }
        if (!(worst < 1e-12)) return value_fail(r, k, index, value, GB_PARSE_OK);
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
        if ((k->open & REAL_ROUGH) && !strcmp(value, "rough")) {
            *(double *)field = INFINITY;
            return 1;
        }
        p = k->kind == KEY_REAL ? gb_parse_double(value, &x) : gb_parse_angle(value, &x);
        if (p || !in_range(k, x)) return value_fail(r, k, index, value, p);
        *(double *)field = x;
        return 1;
    case KEY_COUNT:
        if ((k->open & COUNT_CHOSEN) && !strcmp(value, "chosen")) {
            *(size_t *)field = GB_LYAPUNOV_CHOSEN;
            return 1;
        }
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

static int handler(gb_ini_reader *ini, void *user, const char *section, const char *name, const char *value)
{
    reader *r = &(reader){.ini = ini, .scene = user};
    const size_t total = key_total();
    size_t index = total;
    char allowed[640] = "";
    size_t used = 0;
    key_def scratch, found;
    for (size_t k = 0; k < total; k++) {
        const key_def *key = key_at(k, &scratch);
        if (strcmp(key->section, section)) continue;
        if (!strcmp(key->name, name)) index = k, found = *key;
        used += (size_t)snprintf(allowed + used, sizeof allowed - used, "%s%s", used ? ", " : "", key->name);
        if (used >= sizeof allowed) used = sizeof allowed - 1;
    }
    if (index == total) return reader_fail(r, "[%s] %s = %s: unknown key (allowed in [%s]: %s)", section, name, value, section, allowed);
    gb_case *c = r->scene;
    if (c->key_line[index])
        return reader_fail(r, "[%s] %s = %s: given twice (first at line %d; allowed: each key once)", section, name, value,
                           c->key_line[index]);
    c->key_line[index] = gb_ini_line(ini);
    return set_value(r, &found, index, value);
}

/* The index of key [section] name in the table (-1: none): gb_case_check.c names keys by it. */
int gb_case_key_index(const char *section, const char *name)
{
    key_def scratch;
    for (size_t k = 0; k < key_total(); k++) {
        const key_def *key = key_at(k, &scratch);
        if (!strcmp(key->section, section) && !strcmp(key->name, name)) return (int)k;
    }
    return -1;
}

/* Set key [section] name to `value` over what the file said (an override of `origin`). */
static int apply_override(gb_case *scene, const gb_case_override *o)
{
    const int index = gb_case_key_index(o->section, o->key);
    if (index < 0)
        return gb_error_set(GB_EINVAL, "%s: [%s] %s: unknown scene key (allowed: the keys of cases/README.md)", o->origin,
                            o->section, o->key);
    reader r = {.scene = scene};
    key_def scratch;
    if (!set_value(&r, key_at((size_t)index, &scratch), (size_t)index, o->value)) return gb_error_set(GB_EINVAL, "%s: %s", o->origin, r.message);
    scene->key_line[index] = 0; /* no line of the scene file */
    scene->key_origin[index] = o->origin;
    return GB_OK;
}

int gb_case_read_keys(const char *name, const char *text, size_t size, const gb_case_override *overrides, size_t count,
                      gb_case *scene)
{
    /* a key with no slot of its own would read as unknown: the table and the laws' keys must fit */
    if (KEY_TOTAL + gb_dynamics_law_key_count() > GB_CASE_KEY_MAX)
        return gb_error_set(GB_EINVAL, "the scene table holds %zu keys, more than GB_CASE_KEY_MAX = %d (gb_case.h)",
                            KEY_TOTAL + gb_dynamics_law_key_count(), GB_CASE_KEY_MAX);
    *scene = gb_case_default();
    int status = gb_ini_read(name, text, size, sections, SECTION_TOTAL, handler, scene);
    for (size_t k = 0; k < count && !status; k++) status = apply_override(scene, &overrides[k]);
    return status;
}
