#include "gb_case.h"

#include "gb_error.h"

#include <errno.h>
#include <ini.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

gb_case gb_case_default(void)
{
    gb_case c;
    memset(&c, 0, sizeof c);
    snprintf(c.description, sizeof c.description, "Table 1 defaults");
    snprintf(c.morphology, sizeof c.morphology, "I");
    c.beta = 0.12;
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

typedef struct reader {
    gb_case *scene;
    char message[768]; /* the first error, without its line */
} reader;

static int parse_number(const char *text, double *value)
{
    char *end;
    errno = 0;
    *value = strtod(text, &end);
    return text[0] != '\0' && *end == '\0' && errno == 0 && isfinite(*value);
}

/* A number, or p·pi/q written as "pi", "pi/3", "2pi/3", "2*pi/3". */
static int parse_angle(const char *text, double *value)
{
    if (parse_number(text, value)) return 1;
    double p = 1.0, q = 1.0;
    char rest[64];
    if (sscanf(text, "%lf*pi%63s", &p, rest) == 2 || sscanf(text, "%lfpi%63s", &p, rest) == 2) {
        if (sscanf(rest, "/%lf", &q) != 1) return 0;
    } else if (!strcmp(text, "pi")) {
        p = 1.0;
    } else if (sscanf(text, "pi/%lf", &q) == 1) {
        p = 1.0;
    } else if (sscanf(text, "%lf*pi", &p) != 1 && sscanf(text, "%lfpi", &p) != 1) {
        return 0;
    }
    if (!(q != 0.0 && isfinite(p) && isfinite(q))) return 0;
    *value = p * M_PI / q;
    return 1;
}

static int parse_vector(const char *text, double *v, int n)
{
    char *end;
    const char *p = text;
    for (int k = 0; k < n; k++) {
        errno = 0;
        v[k] = strtod(p, &end);
        if (end == p || errno || !isfinite(v[k])) return 0;
        if (k < n - 1) {
            if (*end != ',') return 0;
            p = end + 1;
        }
    }
    return *end == '\0';
}

static int parse_flag(const char *text, int *flag)
{
    if (!strcmp(text, "yes") || !strcmp(text, "true") || !strcmp(text, "1")) return *flag = 1, 1;
    if (!strcmp(text, "no") || !strcmp(text, "false") || !strcmp(text, "0")) return *flag = 0, 1;
    return 0;
}

static int parse_count(const char *text, size_t *value, size_t min, size_t max)
{
    char *end;
    errno = 0;
    const unsigned long long v = strtoull(text, &end, 10);
    if (text[0] == '\0' || text[0] == '-' || *end != '\0' || errno || v < min || v > max) return 0;
    *value = (size_t)v;
    return 1;
}

/* R = rotation by `angle` about the unit `axis` (Rodrigues), row-major. */
static void axis_angle(const double axis[3], double angle, double R[9])
{
    const double c = cos(angle), s = sin(angle), t = 1 - c, x = axis[0], y = axis[1], z = axis[2];
    const double M[9] = {t * x * x + c, t * x * y - s * z, t * x * z + s * y, t * x * y + s * z, t * y * y + c,
                         t * y * z - s * x, t * x * z - s * y, t * y * z + s * x, t * z * z + c};
    memcpy(R, M, sizeof M);
}

static int fail(reader *r, const char *section, const char *name, const char *value, const char *allowed)
{
    snprintf(r->message, sizeof r->message, "[%s] %s = %s: %s", section, name, value, allowed);
    return 0;
}

#define KEY(sec, key) (!strcmp(section, sec) && !strcmp(name, key))

static int handler(void *user, const char *section, const char *name, const char *value)
{
    reader *r = user;
    gb_case *c = r->scene;
    gb_dynamics_def *d = &c->dynamics;
    double x;
    if (r->message[0]) return 1; /* report only the first error */
    if (KEY("scene", "description")) {
        snprintf(c->description, sizeof c->description, "%s", value);
    } else if (KEY("body", "morphology")) {
        if (!gb_surface_morphology_find(value)) return fail(r, section, name, value, "unknown morphology (allowed: I, II)");
        snprintf(c->morphology, sizeof c->morphology, "%s", value);
    } else if (KEY("body", "beta")) {
        if (!parse_number(value, &x) || !(x >= 0.0 && x < GB_SURFACE_BETA_MAX))
            return fail(r, section, name, value, "out of range (allowed: 0 <= beta < 0.25, where r^4 > 0)");
        c->beta = x;
    } else if (KEY("body", "mass")) {
        if (!parse_number(value, &x) || !(x > 0.0)) return fail(r, section, name, value, "out of range (allowed: mass > 0)");
        d->mass = x;
    } else if (KEY("forcing", "g")) {
        if (!parse_number(value, &x) || !(x >= 0.0)) return fail(r, section, name, value, "out of range (allowed: g >= 0)");
        d->forcing.g = x;
    } else if (KEY("forcing", "A1") || KEY("forcing", "A2")) {
        if (!parse_number(value, &x)) return fail(r, section, name, value, "not a number (allowed: a finite amplitude)");
        *(name[1] == '1' ? &c->A1 : &c->A2) = x;
    } else if (KEY("forcing", "amplitude_units")) {
        if (!strcmp(value, "g")) c->amplitudes_in_g = 1;
        else if (!strcmp(value, "m/s2")) c->amplitudes_in_g = 0;
        else return fail(r, section, name, value, "unknown unit (allowed: m/s2, g)");
    } else if (KEY("forcing", "omega")) {
        if (!parse_number(value, &x) || !(x > 0.0)) return fail(r, section, name, value, "out of range (allowed: omega > 0)");
        d->forcing.omega = x;
    } else if (KEY("forcing", "psi")) {
        if (!parse_angle(value, &x)) return fail(r, section, name, value, "not an angle (allowed: a number, or p*pi/q)");
        d->forcing.psi = x;
    } else if (KEY("model", "equation")) {
        if (gb_dynamics_variant_parse(value, &d->variant)) return fail(r, section, name, value, "unknown (allowed: paper, rolling)");
    } else if (KEY("model", "contact")) {
        if (gb_dynamics_contact_parse(value, &d->contact))
            return fail(r, section, name, value, "unknown (allowed: grid, fast-grid, continuous)");
    } else if (KEY("model", "grid")) {
        size_t np = 0, nt = 0;
        char tail;
        if (sscanf(value, "%zux%zu%c", &np, &nt, &tail) != 2 || np < 2 || nt < 3 || np > GB_CONTACT_GRID_MAX_NODES / nt)
            return fail(r, section, name, value, "out of range (allowed: NPxNT, NP >= 2, NT >= 3, NP*NT <= 67108864)");
        d->grid.n_phi = np;
        d->grid.n_theta = nt;
    } else if (KEY("model", "nodes")) {
        if (gb_contact_nodes_parse(value, &d->grid.nodes)) return fail(r, section, name, value, "unknown (allowed: centred, linspace)");
    } else if (KEY("model", "damping")) {
        if (!parse_number(value, &x) || !(x >= 0.0)) return fail(r, section, name, value, "out of range (allowed: c >= 0)");
        d->damping = x;
    } else if (KEY("integrator", "method")) {
        if (gb_integrate_parse(value, &c->integrate.method))
            return fail(r, section, name, value, "unknown (allowed: rk4, rk8pd, rkf45, rk4imp)");
    } else if (KEY("integrator", "steps_per_period")) {
        if (!parse_count(value, &c->integrate.steps_per_period, 1, 100000000))
            return fail(r, section, name, value, "out of range (allowed: integer 1 to 1e8)");
    } else if (KEY("integrator", "periods")) {
        if (!parse_number(value, &x) || !(x > 0.0 && x <= 1e7))
            return fail(r, section, name, value, "out of range (allowed: 0 < periods <= 1e7)");
        c->integrate.periods = x;
    } else if (KEY("integrator", "locate_switches")) {
        if (!parse_flag(value, &c->integrate.locate_switches)) return fail(r, section, name, value, "not a flag (allowed: yes, no)");
    } else if (KEY("integrator", "rtol") || KEY("integrator", "atol")) {
        if (!parse_number(value, &x) || !(x > 0.0 && x < 1.0)) return fail(r, section, name, value, "out of range (allowed: 0 < tol < 1)");
        *(name[0] == 'r' ? &c->integrate.rtol : &c->integrate.atol) = x;
    } else if (KEY("initial", "attitude")) {
        double v[4];
        if (!strcmp(value, "identity")) {
            const double identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
            memcpy(c->attitude, identity, sizeof identity);
        } else if (!strncmp(value, "axis-angle ", 11) && parse_vector(value + 11, v, 4) && hypot(hypot(v[0], v[1]), v[2]) > 0.0) {
            const double n = hypot(hypot(v[0], v[1]), v[2]), axis[3] = {v[0] / n, v[1] / n, v[2] / n};
            axis_angle(axis, v[3], c->attitude);
        } else {
            return fail(r, section, name, value, "not an attitude (allowed: identity, axis-angle AX,AY,AZ,ANGLE with a non-zero axis)");
        }
        snprintf(c->attitude_text, sizeof c->attitude_text, "%s", value);
    } else if (KEY("initial", "omega")) {
        if (!parse_vector(value, c->omega0, 3)) return fail(r, section, name, value, "not a vector (allowed: WX,WY,WZ, finite)");
    } else if (KEY("output", "history")) {
        if (!parse_flag(value, &c->write_history)) return fail(r, section, name, value, "not a flag (allowed: yes, no)");
    } else if (KEY("output", "summary")) {
        if (!parse_flag(value, &c->write_summary)) return fail(r, section, name, value, "not a flag (allowed: yes, no)");
    } else if (KEY("output", "sample_every")) {
        if (!parse_count(value, &c->integrate.sample_every, 1, 100000000))
            return fail(r, section, name, value, "out of range (allowed: integer >= 1)");
    } else if (KEY("diagnostics", "monitors") || KEY("diagnostics", "strobe") || KEY("diagnostics", "spectrum") ||
               KEY("diagnostics", "lyapunov")) {
        int *flag = name[0] == 'm' ? &c->monitors : name[0] == 'l' ? &c->lyapunov : name[1] == 't' ? &c->strobe : &c->spectrum;
        if (!parse_flag(value, flag)) return fail(r, section, name, value, "not a flag (allowed: yes, no)");
    } else if (KEY("strobe", "transient_periods") || KEY("spectrum", "transient_periods") ||
               KEY("lyapunov", "transient_periods")) {
        size_t *n = section[1] == 't' ? &c->strobe_def.transient : section[1] == 'p' ? &c->spectrum_transient
                                                                                     : &c->lyapunov_def.transient;
        if (!parse_count(value, n, 0, 10000000)) return fail(r, section, name, value, "out of range (allowed: integer >= 0)");
    } else if (KEY("strobe", "phase")) {
        if (!parse_number(value, &x) || !(x >= 0.0 && x < 1.0))
            return fail(r, section, name, value, "out of range (allowed: 0 <= phase < 1, in forcing periods)");
        c->strobe_def.phase = x;
    } else if (KEY("spectrum", "window")) {
        if (gb_window_parse(value, &c->spectrum_window)) return fail(r, section, name, value, "unknown (allowed: hann, rectangular)");
    } else if (KEY("lyapunov", "delta0")) {
        if (!parse_number(value, &x) || !(x > 0.0 && x < 1.0)) return fail(r, section, name, value, "out of range (allowed: 0 < delta0 < 1)");
        c->lyapunov_def.delta0 = x;
    } else if (KEY("lyapunov", "interval_periods")) {
        if (!parse_count(value, &c->lyapunov_interval_periods, 1, 10000000))
            return fail(r, section, name, value, "out of range (allowed: integer >= 1)");
    } else if (KEY("lyapunov", "batches")) {
        if (!parse_count(value, &c->lyapunov_def.batches, 2, 1000000))
            return fail(r, section, name, value, "out of range (allowed: integer >= 2)");
    } else if (KEY("lyapunov", "omega_scale")) {
        if (!parse_number(value, &x) || !(x > 0.0)) return fail(r, section, name, value, "out of range (allowed: omega_scale > 0 [rad/s])");
        c->omega_scale = x;
    } else {
        return fail(r, section, name, value,
                    "unknown key (allowed sections and keys: see cases/README.md; e.g. [body] morphology, beta, mass)");
    }
    return 1;
}

/* The line of `key` in [section] of the file, for errors found after reading (0 when not written). */
static int key_line(const char *path, const char *section, const char *key)
{
    FILE *f = fopen(path, "r");
    if (!f) return 0;
    char text[1024], current[128] = "";
    int line = 0, found = 0;
    while (!found && fgets(text, sizeof text, f)) {
        line++;
        char *p = text;
        while (*p == ' ' || *p == '\t') p++;
        if (*p == '[') {
            char *end = strchr(p, ']');
            if (end) snprintf(current, sizeof current, "%.*s", (int)(end - p - 1), p + 1);
        } else if (!strcmp(current, section) && !strncmp(p, key, strlen(key))) {
            const char *q = p + strlen(key);
            while (*q == ' ' || *q == '\t') q++;
            found = *q == '=' || *q == ':';
        }
    }
    fclose(f);
    return found ? line : 0;
}

static int cross_fail(const char *path, const char *section, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

static int cross_fail(const char *path, const char *section, const char *key, const char *fmt, ...)
{
    char reason[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(reason, sizeof reason, fmt, ap);
    va_end(ap);
    const int line = key_line(path, section, key);
    if (line) return gb_error_set(GB_EDOM, "%s:%d: [%s] %s: %s", path, line, section, key, reason);
    return gb_error_set(GB_EDOM, "%s: [%s] %s (default): %s", path, section, key, reason);
}

/* What no single key can say: the diagnostics against the run's length and grid. */
static int cross_check(const char *path, gb_case *c)
{
    const double periods = c->integrate.periods;
    const size_t spp = c->integrate.steps_per_period;
    if (c->strobe || c->spectrum || c->lyapunov) {
        if (spp % c->integrate.sample_every)
            return cross_fail(path, "output", "sample_every",
                              "%zu does not divide [integrator] steps_per_period = %zu (allowed: a divisor, so that "
                              "every strobe instant and the spectrum's samples fall on a sample)",
                              c->integrate.sample_every, spp);
    }
    if (c->strobe) {
        if (!((double)c->strobe_def.transient < periods))
            return cross_fail(path, "strobe", "transient_periods", "= %zu leaves no strobe samples (allowed: < [integrator] periods = %g)",
                              c->strobe_def.transient, periods);
        const double on_grid = c->strobe_def.phase * (double)(spp / c->integrate.sample_every);
        if (fabs(on_grid - nearbyint(on_grid)) > 1e-9)
            return cross_fail(path, "strobe", "phase", "= %g is not on the sample grid (allowed: a multiple of %zu/%zu)",
                              c->strobe_def.phase, c->integrate.sample_every, spp);
    }
    if (c->spectrum && !((double)c->spectrum_transient + 1.0 <= periods))
        return cross_fail(path, "spectrum", "transient_periods", "= %zu leaves less than one period (allowed: <= [integrator] periods - 1 = %g)",
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
        return cross_fail(path, "lyapunov", "interval_periods",
                          "= %zu with transient_periods = %zu does not divide the %g periods of the run into whole "
                          "intervals (allowed: periods - transient_periods = a multiple of interval_periods, at least 2 "
                          "intervals)",
                          c->lyapunov_interval_periods, l->transient, periods);
    if ((double)l->batches > nearbyint(intervals))
        return cross_fail(path, "lyapunov", "batches", "= %zu exceeds the %g intervals of the record (allowed: 2 <= batches <= intervals)",
                          l->batches, nearbyint(intervals));
    l->interval = k * 2.0 * M_PI / c->dynamics.forcing.omega;
    l->intervals = (size_t)nearbyint(intervals);
    if (c->omega_scale == 0.0) c->omega_scale = c->dynamics.forcing.omega;
    return GB_OK;
}

int gb_case_load(const char *path, gb_case *out)
{
    FILE *f = fopen(path, "r");
    if (!f) return gb_error_set(GB_EIO, "%s: cannot read the case file: %s", path, strerror(errno));
    gb_case scene = gb_case_default();
    reader r = {&scene, ""};
    const int line = ini_parse_file(f, handler, &r);
    int status = GB_OK;
    fclose(f);
    if (line < 0) return gb_error_set(GB_EIO, "%s: cannot read the case file", path);
    if (line > 0)
        return gb_error_set(r.message[0] ? GB_EDOM : GB_EINVAL, "%s:%d: %s", path, line,
                            r.message[0] ? r.message : "malformed line (allowed: [section], key = value, ; comment)");
    status = cross_check(path, &scene);
    if (status) return status;
    /* Amplitudes in m/s² for the dynamics. */
    const double unit = scene.amplitudes_in_g ? scene.dynamics.forcing.g : 1.0;
    scene.dynamics.forcing.a1 = scene.A1 * unit;
    scene.dynamics.forcing.a2 = scene.A2 * unit;
    *out = scene;
    return GB_OK;
}
