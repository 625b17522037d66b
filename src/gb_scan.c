/* gb_scan — the scan file: its strict reader, the base scene read once, every point's scene (the base
 * with the point's keys set over it) and its coordinates (gb_scan.h). The plan of the Melnikov margins is
 * gb_scan_plan.c, a point's run gb_scan_point.c, rows and the journal gb_scan_rows.c, the runner of all the
 * points gb_scan_run.c. */
#include "gb_scan_internal.h"

#include "gb_hash.h"
#include "gb_mesh.h"

#include "gb_error.h"
#include "gb_file.h"
#include "gb_ini.h"
#include "gb_parse.h"
#include "gb_seal.h"

#include <gsl/gsl_rng.h>

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const scan_sections[] = {"scan", "x", "y"};

static const struct {
    unsigned bit;
    const char *name;
} metric_names[] = {{GB_SCAN_OMEGA_RMS, "omega_rms"},     {GB_SCAN_SWITCH_RATE, "switch_rate"},
                    {GB_SCAN_STROBE_SD, "strobe_sd"},     {GB_SCAN_MEAN_HEIGHT, "mean_height"},
                    {GB_SCAN_MONITORS, "monitors"},       {GB_SCAN_LAMBDA, "lambda"},
                    {GB_SCAN_MELNIKOV, "melnikov"},       {GB_SCAN_CONTACTS, "contacts"}};
enum { METRIC_COUNT = sizeof metric_names / sizeof metric_names[0] };
#define METRIC_LIST "omega_rms, switch_rate, strobe_sd, mean_height, monitors, lambda, melnikov, contacts, or all"

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
    int seen[3][9]; /* the line of each key, per section, for "given twice" */
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
                                            "metrics",     "failed_points", "atlas",   "atlas_file", "hand_over"};
        for (int k = 0; k < 9; k++) {
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
            case 8:
                if (strcmp(value, "none") && strcmp(value, "time-stepping"))
                    return gb_ini_fail(ini, "[scan] hand_over = %s: unknown (allowed: none, time-stepping)", value);
                scan->hand_over = !strcmp(value, "time-stepping"), scan->hand_over_line = gb_ini_line(ini);
                return 1;
            default:
                if (strcmp(value, "stop") && strcmp(value, "record"))
                    return gb_ini_fail(ini, "[scan] failed_points = %s: unknown (allowed: stop, record)", value);
                scan->record_failures = !strcmp(value, "record");
                return 1;
            }
        }
        return gb_ini_fail(ini, "[scan] %s = %s: unknown key (allowed in [scan]: description, base, periods, "
                           "transient_periods, metrics, failed_points, atlas, atlas_file, hand_over)", key, value);
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
        origin[GB_SCAN_PATH_MAX + 16], origin_atlas[GB_SCAN_PATH_MAX + 48], origin_hand[GB_SCAN_PATH_MAX + 64];
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
    snprintf(origin_hand, sizeof origin_hand, "%s:%d [scan] hand_over = time-stepping", scan->path, scan->hand_over_line);
    const int strobe = (scan->metrics & GB_SCAN_STROBE_SD) != 0, lambda = (scan->metrics & GB_SCAN_LAMBDA) != 0;
    gb_case_override o[] = {
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
        {"model", "certificate", "atlas", origin_atlas}, /* only with atlas = shared */
        {"integrator", "hand_over", "time-stepping", origin_hand}, /* only with hand_over = time-stepping */
    };
    size_t n = sizeof o / sizeof o[0] - 2;
    if (scan->atlas_shared) o[n++] = o[sizeof o / sizeof o[0] - 2];
    if (scan->hand_over) o[n++] = o[sizeof o / sizeof o[0] - 1];
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

/* The scan's name, by content: the scan file, its base scene and every file the base reads (a mesh; no axis can
 * name another), so that no other scan, base or body can be made to carry it — a resumed scan whose mesh changed
 * is another scan, and starts anew. `scene` is a point's scene, whose body is every point's. */
static int scan_identity(gb_scan *out, const gb_case *scene, const char *text, size_t size)
{
    char *mesh = NULL;
    size_t mesh_size = 0;
    if (scene->mesh[0]) {
        char file[PATH_MAX];
        int status = gb_case_mesh_path(out->base, scene, file, sizeof file);
        if (!status) status = gb_file_read(file, GB_MESH_FILE_MAX, "mesh file", "an OFF, OBJ or STL file", &mesh, &mesh_size);
        if (status) return status;
    }
    const uint64_t sizes[3] = {size, out->base_size, mesh_size};
    /* without a mesh, the name the scans had before meshes counted (two sizes, three pieces) */
    const gb_seal_piece pieces[4] = {{sizes, mesh ? sizeof sizes : 2 * sizeof sizes[0]}, {text, size}, {out->base_text, out->base_size},
                                     {mesh, mesh_size}};
    gb_seal_digest(pieces, mesh ? 4 : 3, out->identity);
    if (mesh) out->fingerprint = gb_hash_add(out->fingerprint, mesh, mesh_size);
    free(mesh);
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
    if (status) {
        free(text);
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
        free(text);
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
    if (!status) status = scan_identity(out, &scene, text, size);
    free(text);
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
