#include "gb_scan.h"

#include "gb_hash.h"

#include "gb_error.h"
#include "gb_file.h"
#include "gb_ini.h"
#include "gb_melnikov_body.h"
#include "gb_parse.h"
#include "gb_seal.h"
#include "gb_run.h"

#include <gsl/gsl_rng.h>

#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <stddef.h>
#include <string.h>

static const char *const scan_sections[] = {"scan", "x", "y"};

static const struct {
    unsigned bit;
    const char *name;
} metric_names[] = {{GB_SCAN_OMEGA_RMS, "omega_rms"},     {GB_SCAN_SWITCH_RATE, "switch_rate"},
                    {GB_SCAN_STROBE_SD, "strobe_sd"},     {GB_SCAN_MEAN_HEIGHT, "mean_height"},
                    {GB_SCAN_MONITORS, "monitors"},       {GB_SCAN_LAMBDA, "lambda"},
                    {GB_SCAN_MELNIKOV, "melnikov"}};
enum { METRIC_COUNT = sizeof metric_names / sizeof metric_names[0] };
#define METRIC_LIST "omega_rms, switch_rate, strobe_sd, mean_height, monitors, lambda, melnikov, or all"

size_t gb_scan_metric_names(unsigned metrics, const char **names, size_t max)
{
    size_t n = 0;
    for (int k = 0; k < METRIC_COUNT; k++)
        if ((metrics & metric_names[k].bit) && n < max) names[n++] = metric_names[k].name;
    return n;
}

/* ---- the scan file ----------------------------------------------------------------------------- */

typedef struct scan_reader {
    gb_scan *scan;
    int seen[3][8]; /* the line of each key, per section, for "given twice" */
} scan_reader;

static int once(gb_ini_reader *ini, scan_reader *r, int section, int key, const char *sname, const char *kname,
                const char *value)
{
    if (r->seen[section][key])
        return gb_ini_fail(ini, "[%s] %s = %s: given twice (first at line %d; allowed: each key once)", sname, kname, value,
                           r->seen[section][key]);
    r->seen[section][key] = gb_ini_line(ini);
    return 1;
}

static int number(gb_ini_reader *ini, const char *s, const char *k, const char *value, double lo, double hi, double *out)
{
    double x;
    const gb_parse_result p = gb_parse_double(value, &x);
    if (p || !(x >= lo && x <= hi))
        return gb_ini_fail(ini, "[%s] %s = %s: %s (allowed: %.15g <= %s <= %.15g)", s, k, value,
                           p ? gb_parse_describe(p, "not a number") : "out of range", lo, k, hi);
    *out = x;
    return 1;
}

static int count(gb_ini_reader *ini, const char *s, const char *k, const char *value, unsigned long long lo,
                 unsigned long long hi, size_t *out)
{
    unsigned long long n;
    const gb_parse_result p = gb_parse_count(value, hi, &n);
    if (p || n < lo)
        return gb_ini_fail(ini, "[%s] %s = %s: %s (allowed: an integer from %llu to %llu)", s, k, value,
                           p == GB_PARSE_SYNTAX ? "not an integer" : "out of range", lo, hi);
    *out = (size_t)n;
    return 1;
}

static int parse_metrics(gb_ini_reader *ini, const char *value, unsigned *out)
{
    if (!strcmp(value, "all")) return *out = GB_SCAN_METRICS_ALL, 1;
    unsigned bits = 0;
    const char *p = value;
    for (;;) {
        while (*p == ' ' || *p == '\t') p++;
        size_t n = strcspn(p, ", \t");
        int found = -1;
        for (int k = 0; k < METRIC_COUNT && found < 0; k++)
            if (strlen(metric_names[k].name) == n && !strncmp(metric_names[k].name, p, n)) found = k;
        if (found < 0)
            return gb_ini_fail(ini, "[scan] metrics = %s: unknown metric '%.*s' (allowed: a comma-separated list of " METRIC_LIST ")",
                               value, (int)n, p);
        if (bits & metric_names[found].bit)
            return gb_ini_fail(ini, "[scan] metrics = %s: '%s' twice (allowed: each metric once)", value, metric_names[found].name);
        bits |= metric_names[found].bit;
        p += n;
        while (*p == ' ' || *p == '\t') p++;
        if (!*p) break;
        if (*p != ',') return gb_ini_fail(ini, "[scan] metrics = %s: not a list (allowed: names separated by commas)", value);
        p++;
    }
    *out = bits;
    return 1;
}

static int axis_key(gb_ini_reader *ini, const char *s, const char *value, gb_scan_axis *a)
{
    const char *dot = strchr(value, '.');
    const size_t ns = dot ? (size_t)(dot - value) : 0, nk = dot ? strlen(dot + 1) : 0;
    if (!dot || ns == 0 || nk == 0 || ns >= sizeof a->section || nk >= sizeof a->key)
        return gb_ini_fail(ini, "[%s] key = %s: not a scene key (allowed: SECTION.KEY of cases/README.md, e.g. forcing.omega)",
                           s, value);
    memcpy(a->section, value, ns);
    a->section[ns] = '\0';
    memcpy(a->key, dot + 1, nk + 1);
    /* What the scan itself sets on every point cannot be an axis. */
    static const char *const own[] = {"integrator.periods", "output.", "diagnostics.", "strobe.transient_periods",
                                      "lyapunov.transient_periods", "lyapunov.interval_periods", "lyapunov.window_periods"};
    for (size_t k = 0; k < sizeof own / sizeof own[0]; k++) {
        const size_t n = strlen(own[k]);
        if (own[k][n - 1] == '.' ? !strncmp(value, own[k], n) : !strcmp(value, own[k]))
            return gb_ini_fail(ini, "[%s] key = %s: set by the scan on every point (allowed: a key of [body], [forcing], "
                               "[model], [integrator] other than periods, [initial], [strobe] phase, [spectrum] or "
                               "[lyapunov] delta0, warmup_intervals, batches, omega_scale)", s, value);
    }
    /* A key the scan sets to numbers (or, on a random axis, to attitudes). */
    const int numeric = gb_case_key_numeric(a->section, a->key);
    if (numeric < 0)
        return gb_ini_fail(ini, "[%s] key = %s: not a scene key (allowed: SECTION.KEY of cases/README.md, e.g. forcing.omega)",
                           s, value);
    if (!numeric && strcmp(value, "initial.attitude"))
        return gb_ini_fail(ini, "[%s] key = %s: not a key that takes one number (allowed: a numeric key such as forcing.omega, "
                           "or initial.attitude with scale = random)", s, value);
    a->line = gb_ini_line(ini);
    return 1;
}

static int scan_handler(gb_ini_reader *ini, void *user, const char *section, const char *key, const char *value)
{
    scan_reader *r = user;
    gb_scan *scan = r->scan;
    if (!strcmp(section, "scan")) {
        static const char *const names[] = {"description", "base",          "periods", "transient_periods",
                                            "metrics",     "failed_points", "atlas",   "atlas_file"};
        for (int k = 0; k < 8; k++) {
            if (strcmp(key, names[k])) continue;
            if (!once(ini, r, 0, k, section, key, value)) return 0;
            switch (k) {
            case 0: snprintf(scan->description, sizeof scan->description, "%s", value); return 1;
            case 1:
                if (!value[0] || strlen(value) >= sizeof scan->base)
                    return gb_ini_fail(ini, "[scan] base = %s: not a path (allowed: a scene file, relative to the scan file)", value);
                snprintf(scan->base, sizeof scan->base, "%s", value);
                return 1;
            case 2: return number(ini, section, key, value, 1.0, 1e7, &scan->periods);
            case 3: return count(ini, section, key, value, 0, 10000000, &scan->transient_periods);
            case 4: return parse_metrics(ini, value, &scan->metrics);
            case 6:
                if (strcmp(value, "none") && strcmp(value, "shared"))
                    return gb_ini_fail(ini, "[scan] atlas = %s: unknown (allowed: none, shared)", value);
                scan->atlas_shared = !strcmp(value, "shared"), scan->atlas_line = gb_ini_line(ini);
                return 1;
            case 7:
                /* a plain name: the file lies in the output directory, beside the outputs (its length is bounded
                 * by the line: GB_INI_LINE_MAX less "atlas_file = ") */
                if (!value[0] || strchr(value, '/') || !strcmp(value, ".") || !strcmp(value, "..") || gb_file_reserved_name(value))
                    return gb_ini_fail(ini, "[scan] atlas_file = %s: not a file name (allowed: a name without '/', of at "
                                       "most %d bytes, of a file in the output directory, not named like the program's "
                                       "temporaries '.gomboc-...')", value, GB_SCAN_ATLAS_NAME_MAX);
                snprintf(scan->atlas_name, sizeof scan->atlas_name, "%s", value), scan->atlas_name_line = gb_ini_line(ini);
                return 1;
            default:
                if (strcmp(value, "stop") && strcmp(value, "record"))
                    return gb_ini_fail(ini, "[scan] failed_points = %s: unknown (allowed: stop, record)", value);
                scan->record_failures = !strcmp(value, "record");
                return 1;
            }
        }
        return gb_ini_fail(ini, "[scan] %s = %s: unknown key (allowed in [scan]: description, base, periods, "
                           "transient_periods, metrics, failed_points, atlas, atlas_file)", key, value);
    }
    const int s = !strcmp(section, "x") ? 1 : 2;
    gb_scan_axis *a = &scan->axis[s - 1];
    static const char *const names[] = {"key", "from", "to", "count", "scale", "seed"};
    for (int k = 0; k < 6; k++) {
        if (strcmp(key, names[k])) continue;
        if (!once(ini, r, s, k, section, key, value)) return 0;
        switch (k) {
        case 0: return axis_key(ini, section, value, a);
        case 1: return number(ini, section, key, value, -1e6, 1e6, &a->from);
        case 2: return number(ini, section, key, value, -1e6, 1e6, &a->to);
        case 3: return count(ini, section, key, value, 1, GB_SCAN_AXIS_MAX, &a->count);
        case 4:
            if (!strcmp(value, "linear")) a->scale = GB_SCAN_LINEAR;
            else if (!strcmp(value, "pi")) a->scale = GB_SCAN_PI;
            else if (!strcmp(value, "random")) a->scale = GB_SCAN_RANDOM;
            else return gb_ini_fail(ini, "[%s] scale = %s: unknown scale (allowed: linear, pi, random)", section, value);
            return 1;
        default: {
            size_t seed = 0;
            if (!count(ini, section, key, value, 0, 4294967295ull, &seed)) return 0;
            a->seed = (unsigned long)seed;
            return 1;
        }
        }
    }
    return gb_ini_fail(ini, "[%s] %s = %s: unknown key (allowed in [%s]: key, from, to, count, scale, seed)", section, key,
                       value, section);
}

size_t gb_scan_points(const gb_scan *scan) { return scan->axis[0].count * scan->axis[1].count; }

static double axis_value(const gb_scan_axis *a, size_t k)
{
    if (a->scale == GB_SCAN_RANDOM) return (double)k;
    const double u = a->count > 1 ? a->from + (a->to - a->from) * (double)k / (double)(a->count - 1) : a->from;
    return a->scale == GB_SCAN_PI ? u * M_PI : u;
}

void gb_scan_coordinates(const gb_scan *scan, size_t index, double *x, double *y)
{
    *x = axis_value(&scan->axis[0], index % scan->axis[0].count);
    *y = axis_value(&scan->axis[1], index / scan->axis[0].count);
}

int gb_scan_point_case(const gb_scan *scan, size_t index, gb_case *out)
{
    double x, y;
    gb_scan_coordinates(scan, index, &x, &y);
    char xv[160], yv[160], periods[40], transient[24], origin_x[GB_SCAN_PATH_MAX + 48], origin_y[GB_SCAN_PATH_MAX + 48],
        origin[GB_SCAN_PATH_MAX + 16], origin_atlas[GB_SCAN_PATH_MAX + 48];
    if (scan->axis[0].scale == GB_SCAN_RANDOM) gb_scan_random_attitude(scan->axis[0].seed, (size_t)x, xv, sizeof xv);
    else snprintf(xv, sizeof xv, "%.17g", x);
    if (scan->axis[1].scale == GB_SCAN_RANDOM) gb_scan_random_attitude(scan->axis[1].seed, (size_t)y, yv, sizeof yv);
    else snprintf(yv, sizeof yv, "%.17g", y);
    snprintf(periods, sizeof periods, "%.17g", scan->periods);
    snprintf(transient, sizeof transient, "%zu", scan->transient_periods);
    snprintf(origin_x, sizeof origin_x, "%s:%d (point %zu)", scan->path, scan->axis[0].line, index);
    snprintf(origin_y, sizeof origin_y, "%s:%d (point %zu)", scan->path, scan->axis[1].line, index);
    snprintf(origin, sizeof origin, "%s [scan]", scan->path);
    snprintf(origin_atlas, sizeof origin_atlas, "%s:%d [scan] atlas = shared", scan->path, scan->atlas_line);
    const int strobe = (scan->metrics & GB_SCAN_STROBE_SD) != 0, lambda = (scan->metrics & GB_SCAN_LAMBDA) != 0;
    const gb_case_override o[] = {
        {scan->axis[0].section, scan->axis[0].key, xv, origin_x},
        {scan->axis[1].section, scan->axis[1].key, yv, origin_y},
        {"integrator", "periods", periods, origin},
        {"output", "history", "no", origin},
        {"output", "summary", "no", origin},
        {"diagnostics", "spectrum", "no", origin},
        {"diagnostics", "monitors", scan->metrics & GB_SCAN_MONITORS ? "yes" : "no", origin},
        {"diagnostics", "strobe", strobe ? "yes" : "no", origin},
        {"strobe", "transient_periods", transient, origin},
        {"diagnostics", "lyapunov", lambda ? "yes" : "no", origin},
        {"lyapunov", "transient_periods", transient, origin},
        {"lyapunov", "interval_periods", "1", origin},
        {"lyapunov", "window_periods", "0", origin}, /* a file of gomboc run; the scan has its own windows */
        {"model", "certificate", "atlas", origin_atlas}, /* the last: only with atlas = shared */
    };
    const size_t n = sizeof o / sizeof o[0] - !scan->atlas_shared;
    return gb_case_load_text_with(scan->base, scan->base_text, scan->base_size, o, n, out);
}

void gb_scan_free(gb_scan *scan)
{
    free(scan->base_text);
    scan->base_text = NULL;
}

int gb_scan_parse(const char *path, const char *text, size_t size, gb_scan *out)
{
    memset(out, 0, sizeof *out);
    if (strlen(path) >= sizeof out->path) return gb_error_set(GB_EINVAL, "%s: the path is too long", path);
    snprintf(out->path, sizeof out->path, "%s", path);
    out->periods = 100.0;
    out->transient_periods = 20;
    out->metrics = GB_SCAN_METRICS_DEFAULT;
    scan_reader r = {.scan = out};
    int status = gb_ini_read(path, text, size, scan_sections, 3, scan_handler, &r);
    out->fingerprint = gb_hash_add(GB_HASH_OFFSET, text, size);
    if (status) return status;
    /* What every scan must say. */
    static const char *const required[3][2] = {{"scan", "base"}, {"x", "key"}, {"y", "key"}};
    const int required_key[3] = {1, 0, 0};
    for (int s = 0; s < 3; s++)
        if (!r.seen[s][required_key[s]])
            return gb_error_set(GB_EINVAL, "%s: [%s] %s is missing (allowed: see cases/README.md, \"Scan files\")", path,
                                required[s][0], required[s][1]);
    for (int s = 0; s < 2; s++) {
        const char *name = s ? "y" : "x";
        gb_scan_axis *a = &out->axis[s];
        const int random = a->scale == GB_SCAN_RANDOM, is_attitude = !strcmp(a->section, "initial") && !strcmp(a->key, "attitude");
        if (random != is_attitude)
            return gb_error_set(GB_EINVAL, "%s:%d: [%s] key = %s.%s with scale = %s (allowed: initial.attitude with scale = "
                                "random and a seed, every other key with linear or pi)", path, a->line, name, a->section, a->key,
                                random ? "random" : a->scale == GB_SCAN_PI ? "pi" : "linear");
        if (random && (!r.seen[s + 1][3] || !r.seen[s + 1][5] || r.seen[s + 1][1] || r.seen[s + 1][2]))
            return gb_error_set(GB_EINVAL, "%s: [%s] a random axis takes count and seed, not from or to (allowed: see "
                                "cases/README.md, \"Scan files\")", path, name);
        if (!random && r.seen[s + 1][5])
            return gb_error_set(GB_EINVAL, "%s:%d: [%s] seed: only a random axis takes a seed", path, r.seen[s + 1][5], name);
        if (!random && (!r.seen[s + 1][1] || !r.seen[s + 1][2] || !r.seen[s + 1][3]))
            return gb_error_set(GB_EINVAL, "%s: [%s] needs from, to and count (allowed: see cases/README.md, \"Scan files\")",
                                path, name);
        if (!random && a->count > 1 && !(a->to > a->from))
            return gb_error_set(GB_EINVAL, "%s:%d: [%s] to = %.17g: an empty range (allowed: to > from = %.17g when count > 1)",
                                path, r.seen[s + 1][2], name, a->to, a->from);
    }
    if (!strcmp(out->axis[0].section, out->axis[1].section) && !strcmp(out->axis[0].key, out->axis[1].key))
        return gb_error_set(GB_EINVAL, "%s:%d: [y] key = %s.%s: the same key as [x] (allowed: two different keys)", path,
                            out->axis[1].line, out->axis[1].section, out->axis[1].key);
    if (out->axis[0].count > GB_SCAN_POINTS_MAX / out->axis[1].count)
        return gb_error_set(GB_EINVAL, "%s:%d: [y] count = %zu: %zu x %zu points (allowed: at most %d points in all)", path,
                            r.seen[2][3], out->axis[1].count, out->axis[0].count, out->axis[1].count, GB_SCAN_POINTS_MAX);
    if (!((double)out->transient_periods + 1.0 <= out->periods)) {
        char at[24] = "";
        if (r.seen[0][3]) snprintf(at, sizeof at, ":%d", r.seen[0][3]);
        return gb_error_set(GB_EINVAL, "%s%s: [scan] transient_periods%s = %zu leaves less than one period (allowed: <= "
                            "periods - 1 = %g)", path, at, r.seen[0][3] ? "" : " (default)", out->transient_periods,
                            out->periods - 1.0);
    }
    if (!out->metrics)
        return gb_error_set(GB_EINVAL, "%s:%d: [scan] metrics: none (allowed: " METRIC_LIST ")", path, r.seen[0][4]);
    /* The base scene, relative to the scan file's directory. */
    if (out->base[0] != '/') {
        const char *slash = strrchr(path, '/');
        char joined[2 * GB_SCAN_PATH_MAX];
        snprintf(joined, sizeof joined, "%.*s%s", slash ? (int)(slash - path + 1) : 0, path, out->base);
        const size_t length = strlen(joined);
        if (length >= sizeof out->base)
            return gb_error_set(GB_EINVAL, "%s:%d: [scan] base: the path is too long", path, r.seen[0][1]);
        memcpy(out->base, joined, length + 1);
    }
    out->base_line = r.seen[0][1];
    return GB_OK;
}

int gb_scan_load(const char *path, gb_scan *out)
{
    char *text;
    size_t size;
    memset(out, 0, sizeof *out);
    int status = gb_file_read(path, GB_SCAN_FILE_MAX, "scan file", "a scan file, see cases/README.md", &text, &size);
    if (status) return status;
    status = gb_scan_parse(path, text, size, out);
    if (status) {
        free(text);
        return status;
    }
    status = gb_file_read(out->base, GB_CASE_FILE_MAX, "case file", "a scene file, see cases/README.md", &out->base_text,
                          &out->base_size);
    if (!status) { /* the scan's name: no other scan file and base scene can be made to carry it */
        const uint64_t sizes[2] = {size, out->base_size};
        const gb_seal_piece pieces[3] = {{sizes, sizeof sizes}, {text, size}, {out->base_text, out->base_size}};
        gb_seal_digest(pieces, 3, out->identity);
    }
    free(text);
    if (status) {
        const char *slash = strrchr(path, '/');
        return gb_error_set(status, "%s:%d: [scan] base = %s: %s (a relative base is read from the scan file's directory, "
                            "'%.*s')", path, out->base_line, out->base, gb_error_message(),
                            slash ? (int)(slash - path + (slash == path)) : 1, slash ? path : ".");
    }
    out->fingerprint = gb_hash_add(out->fingerprint, out->base_text, out->base_size);
    /* Every point's scene, before any run; a shared atlas only where the contact is continuous. */
    gb_case scene;
    if (out->atlas_name[0] && !out->atlas_shared) {
        status = gb_error_set(GB_EINVAL, "%s:%d: [scan] atlas_file = %s without atlas = shared (allowed: atlas_file with "
                              "[scan] atlas = shared)", path, out->atlas_name_line, out->atlas_name);
        gb_scan_free(out);
        return status;
    }
    if (out->atlas_shared) {
        out->atlas_shared = 0;
        status = gb_scan_point_case(out, 0, &scene);
        out->atlas_shared = 1;
        if (!status && scene.dynamics.contact != GB_CONTACT_MODEL_CONTINUOUS)
            status = gb_error_set(GB_EINVAL, "%s:%d: [scan] atlas = shared: the base scene %s has no continuous contact "
                                  "(allowed: shared with [model] contact = continuous, which the atlas certifies; none)",
                                  path, out->atlas_line, out->base);
    }
    for (size_t k = 0; k < gb_scan_points(out) && !status; k++) status = gb_scan_point_case(out, k, &scene);
    if (status) gb_scan_free(out);
    return status;
}

void gb_scan_random_attitude(unsigned long seed, size_t k, char *text, size_t size)
{
    /* Shoemake's uniform quaternion from three uniform numbers of the k-th draw. */
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    double u[3] = {0.5, 0.5, 0.5};
    if (rng) {
        gsl_rng_set(rng, seed + 1000003ul * (unsigned long)k);
        for (int i = 0; i < 3; i++) u[i] = gsl_rng_uniform(rng);
        gsl_rng_free(rng);
    }
    const double a = sqrt(1.0 - u[0]), b = sqrt(u[0]);
    double q[4] = {b * cos(2 * M_PI * u[2]), a * sin(2 * M_PI * u[1]), a * cos(2 * M_PI * u[1]), b * sin(2 * M_PI * u[2])};
    if (q[0] < 0.0) /* −q is the same rotation: keep the angle in [0, π] */
        for (int i = 0; i < 4; i++) q[i] = -q[i];
    const double n = sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(n > 0.0)) {
        snprintf(text, size, "identity");
        return;
    }
    snprintf(text, size, "axis-angle %.17g,%.17g,%.17g,%.17g", q[1] / n, q[2] / n, q[3] / n, 2.0 * atan2(n, q[0]));
}

/* ---- a point ----------------------------------------------------------------------------------- */

void gb_scan_accumulate(gb_scan_accumulator *a, double t, const double omega[3], double height, size_t switches)
{
    if (!(t >= a->first_t)) return;
    if (a->samples == 0) a->t_start = t, a->switches_start = switches;
    a->samples++;
    a->omega2_sum += omega[0] * omega[0] + omega[1] * omega[1] + omega[2] * omega[2];
    a->height_sum += height;
    a->t_last = t;
    a->switches_last = switches;
}

void gb_scan_accumulated(const gb_scan_accumulator *a, double *omega_rms, double *mean_height, double *switch_rate)
{
    const double n = (double)a->samples;
    *omega_rms = a->samples ? sqrt(a->omega2_sum / n) : NAN;
    *mean_height = a->samples ? a->height_sum / n : NAN;
    *switch_rate = a->samples > 1 && a->t_last > a->t_start
                       ? (double)(a->switches_last - a->switches_start) / (a->t_last - a->t_start)
                       : NAN;
}

static int accumulate_sample(void *context, const gb_run_sample *s)
{
    gb_scan_accumulate(context, s->t, s->o->omega, s->o->height, s->o->grid_switches + s->o->branch_switches);
    return GB_OK;
}

/* ---- the Melnikov margin ------------------------------------------------------------------------ */

/* A reduced model: the key (what gb_melnikov_body_create reads) and what it yields. */
typedef struct melnikov_body {
    const gb_morphology *morphology;
    double beta, mass, g;
    int computed, status;       /* status GB_EDOM: not defined here (margins NAN) */
    gb_melnikov_body *body;
    gb_melnikov_model model;
    gb_melnikov_orbit orbit;
    double M_u;                 /* M(q_u): μ = c / M_u */
    gb_melnikov_tables *tables; /* its separatrix tabulated once for the planned ω */
} melnikov_body;

/* The integrals of one body at one ω. */
typedef struct melnikov_frequency {
    size_t body;
    double omega;
    int computed, status;
    gb_melnikov_integrals integrals;
} melnikov_frequency;

struct gb_scan_melnikov {
    melnikov_body *bodies;
    size_t n_bodies;
    melnikov_frequency *frequencies;
    size_t n_frequencies;
};

static int same_bits(double a, double b) { return !memcmp(&a, &b, sizeof a); }

static int body_matches(const melnikov_body *b, const gb_case *scene)
{
    return b->morphology == scene->body.morphology && same_bits(b->beta, scene->body.beta) &&
           same_bits(b->mass, scene->dynamics.mass) && same_bits(b->g, scene->dynamics.forcing.g);
}

/* Where the scene's body and ω sit in the plan (SIZE_MAX: not planned). */
static void plan_find(const gb_scan_melnikov *p, const gb_case *scene, size_t *body, size_t *frequency)
{
    *body = *frequency = SIZE_MAX;
    for (size_t k = 0; k < p->n_bodies && *body == SIZE_MAX; k++)
        if (body_matches(&p->bodies[k], scene)) *body = k;
    for (size_t k = 0; *body != SIZE_MAX && k < p->n_frequencies && *frequency == SIZE_MAX; k++)
        if (p->frequencies[k].body == *body && same_bits(p->frequencies[k].omega, scene->dynamics.forcing.omega))
            *frequency = k;
}

/* Add the scene's body and ω to the plan unless there (the reduced model needs g > 0). */
static int plan_add(gb_scan_melnikov *p, const gb_case *scene)
{
    if (!(scene->dynamics.forcing.g > 0.0)) return GB_OK;
    size_t b, f;
    plan_find(p, scene, &b, &f);
    if (b == SIZE_MAX) {
        melnikov_body *grown = realloc(p->bodies, (p->n_bodies + 1) * sizeof *grown);
        if (!grown) return gb_error_set(GB_ENOMEM, "out of memory for the reduced models of a scan");
        p->bodies = grown;
        b = p->n_bodies++;
        p->bodies[b] = (melnikov_body){.morphology = scene->body.morphology, .beta = scene->body.beta,
                                       .mass = scene->dynamics.mass, .g = scene->dynamics.forcing.g};
    }
    if (f == SIZE_MAX) {
        melnikov_frequency *grown = realloc(p->frequencies, (p->n_frequencies + 1) * sizeof *grown);
        if (!grown) return gb_error_set(GB_ENOMEM, "out of memory for the Melnikov integrals of a scan");
        p->frequencies = grown;
        p->frequencies[p->n_frequencies++] = (melnikov_frequency){.body = b, .omega = scene->dynamics.forcing.omega};
    }
    return GB_OK;
}

int gb_scan_melnikov_plan(const gb_scan *scan, const size_t *points, size_t count, gb_scan_melnikov **out)
{
    *out = NULL;
    gb_scan_melnikov *p = calloc(1, sizeof *p);
    if (!p) return gb_error_set(GB_ENOMEM, "out of memory for a scan's reduced models");
    int status = GB_OK;
    for (size_t k = 0; k < count && !status && (scan->metrics & GB_SCAN_MELNIKOV); k++) {
        gb_case scene;
        status = gb_scan_point_case(scan, points[k], &scene);
        if (!status) status = plan_add(p, &scene);
    }
    if (status) {
        gb_scan_melnikov_free(p);
        return status;
    }
    *out = p;
    return GB_OK;
}

size_t gb_scan_melnikov_bodies(const gb_scan_melnikov *plan) { return plan->n_bodies; }
size_t gb_scan_melnikov_frequencies(const gb_scan_melnikov *plan) { return plan->n_frequencies; }

int gb_scan_melnikov_body(gb_scan_melnikov *plan, size_t i)
{
    melnikov_body *b = &plan->bodies[i];
    const gb_surface surface = {b->morphology, b->beta};
    int status = gb_melnikov_body_create(&surface, b->mass, b->g, GB_MELNIKOV_BODY_NODES, &b->body);
    if (!status) {
        b->model = gb_melnikov_body_model(b->body, GB_MELNIKOV_MASS_AT_TOP);
        status = gb_melnikov_orbit_find(&b->model, &b->orbit);
    }
    gb_melnikov_values top;
    if (!status) status = b->model.eval(b->model.context, b->orbit.q_u, &top);
    if (!status) b->M_u = top.M;
    if (!status) status = gb_melnikov_tables_create(&b->model, &b->orbit, GB_MELNIKOV_EXACT, &b->tables);
    for (size_t k = 0; !status && k < plan->n_frequencies; k++)
        if (plan->frequencies[k].body == i) status = gb_melnikov_tables_prepare(b->tables, plan->frequencies[k].omega);
    b->status = status, b->computed = 1;
    return status == GB_EDOM ? GB_OK : status; /* not defined for this body: its margins are NAN */
}

int gb_scan_melnikov_frequency(gb_scan_melnikov *plan, size_t i)
{
    melnikov_frequency *f = &plan->frequencies[i];
    const melnikov_body *b = &plan->bodies[f->body];
    if (!b->computed) return gb_error_set(GB_EINVAL, "the Melnikov integrals at omega = %g before their body", f->omega);
    f->status = b->status ? b->status : gb_melnikov_tables_integrals(b->tables, f->omega, &f->integrals);
    f->computed = 1;
    return f->status == GB_EDOM ? GB_OK : f->status;
}

void gb_scan_melnikov_free(gb_scan_melnikov *plan)
{
    if (!plan) return;
    for (size_t k = 0; k < plan->n_bodies; k++) {
        gb_melnikov_tables_free(plan->bodies[k].tables);
        gb_melnikov_body_free(plan->bodies[k].body);
    }
    free(plan->bodies);
    free(plan->frequencies);
    free(plan);
}

/* The margins of `scene` from a computed plan that holds it. */
static int plan_margins(const gb_scan_melnikov *p, const gb_case *scene, double *margin, double *margin_eq93)
{
    *margin = *margin_eq93 = NAN;
    if (!(scene->dynamics.forcing.g > 0.0)) return GB_OK;
    size_t b, f;
    plan_find(p, scene, &b, &f);
    if (f == SIZE_MAX || !p->frequencies[f].computed)
        return gb_error_set(GB_EINVAL, "the Melnikov margins of a point the scan did not plan (omega = %g)",
                            scene->dynamics.forcing.omega);
    const melnikov_frequency *w = &p->frequencies[f];
    if (w->status) return GB_OK;
    const gb_forcing *F = &scene->dynamics.forcing;
    const double mu = scene->dynamics.damping / p->bodies[b].M_u, damping = mu * w->integrals.D;
    const gb_melnikov_forcing forcing = {mu, F->a1, F->a2, F->omega, F->psi, 0};
    gb_melnikov_criterion c;
    gb_melnikov_judge(&w->integrals, &forcing, &c);
    *margin = c.oscillatory_max / damping;
    *margin_eq93 = (fabs(F->a1) * w->integrals.A1 + fabs(F->a2) * w->integrals.A2) / damping;
    return GB_OK;
}

int gb_scan_melnikov_margins(const gb_case *scene, double *margin, double *margin_eq93)
{
    gb_scan_melnikov p = {0};
    int status = plan_add(&p, scene);
    for (size_t k = 0; !status && k < p.n_bodies; k++) status = gb_scan_melnikov_body(&p, k);
    for (size_t k = 0; !status && k < p.n_frequencies; k++) status = gb_scan_melnikov_frequency(&p, k);
    if (!status) status = plan_margins(&p, scene, margin, margin_eq93);
    for (size_t k = 0; k < p.n_bodies; k++) {
        gb_melnikov_tables_free(p.bodies[k].tables);
        gb_melnikov_body_free(p.bodies[k].body);
    }
    free(p.bodies);
    free(p.frequencies);
    return status;
}

/* ---- a point's run ------------------------------------------------------------------------------ */

int gb_scan_point_run(const gb_scan *scan, const gb_scan_melnikov *melnikov, size_t index, gb_scan_metrics *out)
{
    return gb_scan_point_run_in(scan, melnikov, index, NULL, out);
}

int gb_scan_point_run_in(const gb_scan *scan, const gb_scan_melnikov *melnikov, size_t index, gb_dynamics_context *context,
                         gb_scan_metrics *out)
{
    gb_case scene;
    int status = gb_scan_point_case(scan, index, &scene);
    if (status) return status;
    gb_scan_metrics m = {.omega_rms = NAN, .switch_rate = NAN, .mean_height = NAN, .lambda = NAN, .lambda_error = NAN,
                         .strobe_sd = NAN, .geff_nonpositive = NAN, .lift_off = NAN, .lambda_early = NAN,
                         .lambda_late = NAN, .chaos_lifetime = NAN, .melnikov_margin = NAN, .melnikov_margin_eq93 = NAN};
    gb_scan_coordinates(scan, index, &m.x, &m.y);
    if (scan->metrics & GB_SCAN_MELNIKOV) {
        status = melnikov ? plan_margins(melnikov, &scene, &m.melnikov_margin, &m.melnikov_margin_eq93)
                          : gb_scan_melnikov_margins(&scene, &m.melnikov_margin, &m.melnikov_margin_eq93);
        if (status) return status;
    }
    if (!(scan->metrics & ~(unsigned)GB_SCAN_MELNIKOV)) { /* margins alone: no dynamics */
        *out = m;
        return GB_OK;
    }
    const double T = gb_forcing_period(&scene.dynamics.forcing);
    const double step = gb_forcing_step(&scene.dynamics.forcing, scene.integrate.steps_per_period);
    /* Samples from the first one at the end of the transient (half a step of slack for rounding). */
    gb_scan_accumulator acc = {.first_t = (double)scan->transient_periods * T - 0.5 * step};
    const gb_run_sinks sinks = {accumulate_sample, &acc, NULL};
    gb_run_result r;
    status = gb_run_in(&scene, context, &sinks, &r);
    if (status) return status;
    double rms, height, rate;
    gb_scan_accumulated(&acc, &rms, &height, &rate);
    m.omega_rms = scan->metrics & GB_SCAN_OMEGA_RMS ? rms : NAN;
    m.mean_height = scan->metrics & GB_SCAN_MEAN_HEIGHT ? height : NAN;
    m.switch_rate = scan->metrics & GB_SCAN_SWITCH_RATE ? rate : NAN;
    if (r.has_strobe && r.strobe.count) {
        double mean[3], sd[3];
        gb_strobe_spread(r.strobe.x, r.strobe.count, 3, mean, sd);
        m.strobe_sd = sd[0];
    }
    if (r.has_monitors) {
        m.geff_nonpositive = (double)r.monitors.geff_nonpositive / (double)r.samples;
        m.lift_off = (double)r.monitors.lift_off / (double)r.samples;
    }
    if (r.has_lyapunov) {
        const gb_lyapunov_result *l = &r.lyapunov;
        m.lambda = l->lambda_max, m.lambda_error = l->error_bar;
        const size_t half = l->intervals / 2;
        double early = 0.0, late = 0.0;
        for (size_t k = 0; k < l->intervals; k++) {
            if (k < half) early += l->instantaneous[k];
            else late += l->instantaneous[k];
        }
        m.lambda_early = early / (double)half, m.lambda_late = late / (double)(l->intervals - half);
        m.chaos_lifetime = gb_scan_chaos_lifetime(l->instantaneous, l->intervals,
                                                  l->interval * scene.dynamics.forcing.omega / (2.0 * M_PI));
    }
    m.certificate_undecided = r.has_certificate ? r.certificate.undecided : 0;
    m.state_fingerprint = r.state_fingerprint;
    m.switch_fingerprint = r.switch_fingerprint;
    gb_run_result_free(&r);
    *out = m;
    return GB_OK;
}

double gb_scan_chaos_lifetime(const double *lambda, size_t n, double periods_per_interval)
{
    const size_t window = n / 12;
    if (window < 20) return NAN;
    double mean[12];
    const size_t count = gb_lyapunov_windows(lambda, 12 * window, window, mean);
    const double windows = gb_lyapunov_lifetime(mean, count, 1.0); /* in windows */
    return isinf(windows) ? windows : windows * (double)window * periods_per_interval;
}

/* ---- rows -------------------------------------------------------------------------------------- */

int gb_scan_csv_header(const gb_scan *scan, char *out, size_t size)
{
    const int n = snprintf(out, size, "index,%s.%s,%s.%s,%s", scan->axis[0].section, scan->axis[0].key, scan->axis[1].section,
                           scan->axis[1].key, gb_scan_csv_metric_columns());
    return n > 0 && (size_t)n < size ? GB_OK : gb_error_set(GB_EINVAL, "the scan's CSV header does not fit %zu bytes", size);
}

/* The CSV's numeric columns after index, x and y, from one list: the column's name and its field, in row
 * order. A new metric is a field of gb_scan_metrics and a line here; the header, the row, its parser and the
 * NaNs of a failed point follow. certificate_undecided (a count) and the two fingerprints (hex) close every
 * row. */
#define SCAN_COLUMNS(X)                                                                                                \
    X(omega_rms, omega_rms)                                                                                            \
    X(switch_rate, switch_rate)                                                                                        \
    X(strobe_sd, strobe_sd)                                                                                            \
    X(mean_height, mean_height)                                                                                        \
    X(geff_nonpositive_fraction, geff_nonpositive)                                                                     \
    X(lift_off_fraction, lift_off)                                                                                     \
    X(lambda_max, lambda)                                                                                              \
    X(lambda_error, lambda_error)                                                                                      \
    X(lambda_first_half, lambda_early)                                                                                 \
    X(lambda_second_half, lambda_late)                                                                                 \
    X(chaos_lifetime_periods, chaos_lifetime)                                                                          \
    X(melnikov_margin, melnikov_margin)                                                                                \
    X(melnikov_margin_eq93, melnikov_margin_eq93)
#define COLUMN_OFFSET(name, field) offsetof(gb_scan_metrics, field),
#define COLUMN_NAME(name, field) #name ","
static const size_t column_offsets[] = {SCAN_COLUMNS(COLUMN_OFFSET)};
enum { COLUMN_COUNT = sizeof column_offsets / sizeof column_offsets[0] };

static double *column(gb_scan_metrics *m, size_t k) { return (double *)((char *)m + column_offsets[k]); }
static double column_of(const gb_scan_metrics *m, size_t k) { return *(const double *)((const char *)m + column_offsets[k]); }

const char *gb_scan_csv_metric_columns(void)
{
    return SCAN_COLUMNS(COLUMN_NAME) "certificate_undecided,state_fingerprint,switch_fingerprint\n";
}

void gb_scan_failed_metrics(const gb_scan *scan, size_t index, gb_scan_metrics *out)
{
    memset(out, 0, sizeof *out);
    gb_scan_coordinates(scan, index, &out->x, &out->y);
    for (size_t k = 0; k < COLUMN_COUNT; k++) *column(out, k) = NAN;
}

int gb_scan_csv_row(const gb_scan_metrics *m, size_t index, char *out, size_t size)
{
    size_t n = (size_t)snprintf(out, size, "%zu,%.17g,%.17g", index, m->x, m->y);
    for (size_t k = 0; k < COLUMN_COUNT && n < size; k++) n += (size_t)snprintf(out + n, size - n, ",%.17g", column_of(m, k));
    if (n < size)
        n += (size_t)snprintf(out + n, size - n, ",%zu,%016" PRIx64 ",%016" PRIx64 "\n", m->certificate_undecided,
                              m->state_fingerprint, m->switch_fingerprint);
    return n < size ? GB_OK : gb_error_set(GB_EINVAL, "a scan row does not fit %zu bytes", size);
}

int gb_scan_csv_parse(const char *line, size_t *index, gb_scan_metrics *out)
{
    gb_scan_metrics m;
    double *fields[2 + COLUMN_COUNT] = {&m.x, &m.y};
    for (size_t k = 0; k < COLUMN_COUNT; k++) fields[2 + k] = column(&m, k);
    char *end;
    const char *p = line;
    if (*p < '0' || *p > '9') return GB_EINVAL; /* digits only: strtoull would take "-1" or " 7" */
    const unsigned long long i = strtoull(p, &end, 10);
    if (end == p || *end != ',') return GB_EINVAL;
    for (size_t k = 0; k < sizeof fields / sizeof fields[0]; k++) {
        p = end + 1;
        *fields[k] = strtod(p, &end);
        if (end == p || *end != ',') return GB_EINVAL;
    }
    p = end + 1;
    if (*p < '0' || *p > '9') return GB_EINVAL;
    m.certificate_undecided = (size_t)strtoull(p, &end, 10);
    if (end == p || *end != ',') return GB_EINVAL;
    p = end + 1;
    m.state_fingerprint = strtoull(p, &end, 16);
    if (end != p + 16 || *end != ',') return GB_EINVAL;
    p = end + 1;
    m.switch_fingerprint = strtoull(p, &end, 16);
    if (end != p + 16 || (*end != '\n' && *end != '\0')) return GB_EINVAL;
    *index = (size_t)i;
    *out = m;
    return GB_OK;
}

/* ---- the journal --------------------------------------------------------------------------------- */

void gb_scan_journal_header(const gb_scan *scan, uint64_t binary, char *out, size_t size)
{
    char identity[GB_SEAL_HEX];
    gb_seal_hex(scan->identity, identity);
    snprintf(out, size, "gomboc scan journal 3: scan %s, binary %016" PRIx64 ", %zu points\n", identity, binary,
             gb_scan_points(scan));
}

/* The seal of a row: gb_seal of the header and the row (without its '\n'). */
static int row_seal(const char *header, const char *row, size_t length, unsigned char seal[GB_SEAL_BYTES])
{
    const gb_seal_piece pieces[2] = {{header, strlen(header)}, {row, length}};
    return gb_seal_compute(pieces, 2, seal);
}

int gb_scan_journal_line(const char *header, const char *row, char *out, size_t size)
{
    const size_t length = strcspn(row, "\n");
    unsigned char seal[GB_SEAL_BYTES];
    char hex[GB_SEAL_HEX];
    const int status = row_seal(header, row, length, seal);
    if (status) return gb_error_set(status, "cannot seal a journal line: %s", gb_error_message());
    gb_seal_hex(seal, hex);
    const int n = snprintf(out, size, "%.*s,%s\n", (int)length, row, hex);
    return n > 0 && (size_t)n < size ? GB_OK : gb_error_set(GB_EINVAL, "a journal line does not fit %zu bytes", size);
}

/* A journal's first line as it may be quoted: printable ASCII, at most 100 characters. */
static void quoted(const char *text, size_t length, char *out, size_t size)
{
    size_t n = 0;
    for (size_t k = 0; k < length && n + 4 < size && k < 100; k++)
        out[n++] = text[k] >= 0x20 && text[k] < 0x7f ? text[k] : '?';
    if (length > 100 && n + 4 < size) memcpy(out + n, "...", 3), n += 3;
    out[n] = '\0';
}

/* One complete line (without its '\n') of the journal: GB_OK with the point in *index and *m, or
 * GB_EINVAL with the reason. */
static int journal_row(const gb_scan *scan, const char *header, const char *line, size_t length, size_t *index,
                       gb_scan_metrics *m)
{
    if (memchr(line, '\0', length)) return gb_error_set(GB_EINVAL, "a NUL byte");
    if (length > GB_SCAN_JOURNAL_LINE_MAX) return gb_error_set(GB_EINVAL, "%zu bytes long", length);
    char row[GB_SCAN_JOURNAL_LINE_MAX + 2];
    const size_t tail = 2 * GB_SEAL_BYTES + 1; /* ",<64 hexadecimal digits>" */
    if (length < tail + 1 || line[length - tail] != ',') return gb_error_set(GB_EINVAL, "no seal at its end");
    const size_t row_length = length - tail;
    unsigned char seal[GB_SEAL_BYTES];
    if (!gb_seal_from_hex(line + row_length + 1, seal) ||
        !gb_seal_verify((const gb_seal_piece[2]){{header, strlen(header)}, {line, row_length}}, 2, seal))
        return gb_error_set(GB_EINVAL, "its seal does not verify: edited, damaged, or written under another key (see "
                            "GOMBOC_KEY)");
    memcpy(row, line, row_length);
    row[row_length] = '\n', row[row_length + 1] = '\0';
    if (gb_scan_csv_parse(row, index, m)) return gb_error_set(GB_EINVAL, "not a row of this command");
    if (*index >= gb_scan_points(scan))
        return gb_error_set(GB_EINVAL, "point %zu of a scan of %zu points", *index, gb_scan_points(scan));
    /* Every value must read back to the same text, and the coordinates must be the point's own. */
    double x, y;
    gb_scan_coordinates(scan, *index, &x, &y);
    m->x = x, m->y = y;
    char again[GB_SCAN_JOURNAL_LINE_MAX + 2];
    if (gb_scan_csv_row(m, *index, again, sizeof again) || strcmp(again, row))
        return gb_error_set(GB_EINVAL, "its values do not read back to the same row (the coordinates of point %zu are x = "
                            "%.17g, y = %.17g)", *index, x, y);
    return GB_OK;
}

int gb_scan_journal_read(const gb_scan *scan, const char *name, const char *header, const char *text, size_t size,
                         gb_scan_metrics *results, unsigned char *done, size_t *count, size_t *keep)
{
    static const char *const allowed = "(allowed: a journal this command wrote for this scan file, base scene and binary; "
                                       "remove it to start again)";
    *count = 0, *keep = 0;
    const char *newline = memchr(text, '\n', size);
    const size_t header_length = strlen(header);
    if (!size) return GB_OK; /* an empty journal (from a kill before its header): no points, the header written anew */
    if (!newline) return gb_error_set(GB_EINVAL, "%s: %s %s", name, "an incomplete first line", allowed);
    if ((size_t)(newline - text) + 1 != header_length || memcmp(text, header, header_length)) {
        char have[128], want[128];
        quoted(text, (size_t)(newline - text), have, sizeof have);
        quoted(header, header_length - 1, want, sizeof want);
        return gb_error_set(GB_EINVAL, "%s:1: not this scan's journal (its header: '%s'; this scan and binary: '%s') %s", name,
                            have, want, allowed);
    }
    size_t at = header_length;
    int number = 1;
    while (at < size) {
        number++;
        const char *line = text + at, *end = memchr(line, '\n', size - at);
        if (!end) break; /* a half-written last line: dropped */
        const size_t length = (size_t)(end - line);
        size_t index;
        gb_scan_metrics m;
        if (journal_row(scan, header, line, length, &index, &m))
            return gb_error_set(GB_EINVAL, "%s:%d: %s %s", name, number, gb_error_message(), allowed);
        if (done[index]) {
            char first[GB_SCAN_JOURNAL_LINE_MAX + 2], again[GB_SCAN_JOURNAL_LINE_MAX + 2];
            gb_scan_csv_row(&results[index], index, first, sizeof first);
            gb_scan_csv_row(&m, index, again, sizeof again);
            if (strcmp(first, again))
                return gb_error_set(GB_EINVAL, "%s:%d: point %zu a second time, with other values %s", name, number, index,
                                    allowed);
        } else {
            results[index] = m, done[index] = 1;
            ++*count;
        }
        at += length + 1;
    }
    *keep = at;
    return GB_OK;
}
