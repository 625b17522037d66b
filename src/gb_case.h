/* gb_case — scenes: INI files read with libinih into one struct, defaults in code.
 *
 * Every key is optional; gb_case_default() holds every default, once. A scene names its model, its
 * outputs and its diagnostics; nothing else is computed or written. Sections and keys:
 *
 *   [scene]       description = free text
 *   [body]        morphology = I | II;  beta = 0 <= B < 0.25;  mass = m > 0 [kg]
 *   [forcing]     g [m/s²] >= 0; A1, A2 (amplitudes, finite); amplitude_units = m/s2 | g (A_i are a_i
 *                 in m/s², or a_i/g as eq 61); omega > 0 [rad/s]; psi [rad] (a number, or "pi/3"-style
 *                 p/q multiples of pi)
 *   [model]       equation = paper | rolling; contact = grid | fast-grid | continuous;
 *                 grid = NPxNT; nodes = centred | linspace; damping = c >= 0 [N m s]
 *   [integrator]  method = rk4 | rk8pd | rkf45 | rk4imp; steps_per_period >= 1; periods > 0;
 *                 rtol, atol in (0, 1); locate_switches = yes | no (RK4, continuous contact)
 *   [initial]     attitude = identity | axis-angle AX,AY,AZ,ANGLE (rotation body → inertial, radians);
 *                 omega = WX,WY,WZ [rad/s]
 *   [output]      history = yes | no (time histories CSV); summary = yes | no (JSON);
 *                 sample_every = n >= 1 (nominal steps between history rows)
 *   [diagnostics] monitors = yes | no (validity monitors: g_eff, normal force, friction);
 *                 strobe, spectrum, lyapunov = yes | no (Figs 7, 8, 9: what `gomboc run` computes and writes)
 *   [strobe]      transient_periods = n >= 0 (< periods); phase = p in [0, 1), on the step grid
 *   [spectrum]    transient_periods = n >= 0 (< periods); window = hann | rectangular
 *   [lyapunov]    delta0 in (0, 1); transient_periods = n >= 0; interval_periods = k >= 1 (the record,
 *                 periods − transient, must be a whole number of intervals, at least 2 and at least
 *                 `batches`); batches = b >= 2; omega_scale = Ω > 0 [rad/s] (the separation's
 *                 ω-part is Δω/Ω; default: the forcing omega)
 *
 * The reader is strict: a file is read whole (a regular file of at most GB_CASE_FILE_MAX bytes) and
 * every line is checked before libinih sees it: at most 198 bytes (libinih's buffer, less the newline
 * and the NUL), UTF-8 with no NUL and no control character but TAB, no indented (continuation) line,
 * only known sections, each once. Every key is given at most once, and its value is one whole token
 * inside the key's physical range (gb_case_key_allowed); adaptive steppers are refused with grid
 * contact. Errors name the file, the line, the key and the allowed values, with status GB_EINVAL or
 * GB_EDOM (bad input); nothing is returned half-filled. */
#ifndef GB_CASE_H
#define GB_CASE_H

#include "gb_dynamics.h"
#include "gb_integrate.h"
#include "gb_lyapunov.h"
#include "gb_spectrum.h"
#include "gb_strobe.h"

/* A scene file holds at most this many bytes; a text value at most GB_CASE_TEXT_MAX - 1. */
#define GB_CASE_FILE_MAX (1 << 20)
#define GB_CASE_TEXT_MAX 256
#define GB_CASE_KEY_MAX 48

typedef struct gb_case {
    char description[GB_CASE_TEXT_MAX];
    gb_surface body;              /* [body] morphology and beta (eqs 3-9): one value, as every module takes it */
    gb_dynamics_def dynamics;     /* forcing in m/s² after reading amplitude_units */
    int amplitudes_in_g;          /* 1 when A1, A2 were given in units of g (eq 61) */
    double A1, A2;                /* as written in the file */
    gb_integrate_def integrate;
    double attitude[9];           /* R0, row-major */
    char attitude_text[GB_CASE_TEXT_MAX];
    double omega0[3];
    int write_history, write_summary;
    int monitors;
    int strobe, spectrum, lyapunov;  /* [diagnostics] */
    gb_strobe_def strobe_def;
    size_t spectrum_transient;
    gb_window spectrum_window;
    gb_lyapunov_def lyapunov_def;     /* interval in seconds and intervals set from the scene's periods */
    size_t lyapunov_interval_periods;
    double omega_scale;               /* [rad/s]; the forcing omega unless given */
    int key_line[GB_CASE_KEY_MAX];    /* the line each key was read from (0: the default), by key index */
} gb_case;

/* The defaults: Table 1 with the paper's model (m/s² reading of A1, A2; R0 = I; ω0 = 0). */
gb_case gb_case_default(void);

/* Read `path` over the defaults. GB_EIO when the file cannot be read; GB_EINVAL / GB_EDOM with
 * "FILE:LINE: [section] key = value: reason (allowed: ...)". */
int gb_case_load(const char *path, gb_case *out);

/* The same for `size` bytes of `text` (NUL bytes and all), named `name` in messages. */
int gb_case_load_text(const char *name, const char *text, size_t size, gb_case *out);

/* The keys a scene may set: their count, and for key `index` its section, name and allowed values
 * in words (the text every error message and cases/README.md use). GB_EDOM past the last key. */
size_t gb_case_key_count(void);
int gb_case_key_allowed(size_t index, const char **section, const char **name, char *allowed, size_t size);

/* The [lyapunov] section against the run (gb_case_load does this when [diagnostics] lyapunov = yes;
 * `gomboc lyapunov` asks for it whatever the flag): sets lyapunov_def.interval [s] and .intervals and
 * omega_scale. GB_EDOM with "FILE:LINE: [lyapunov] key: reason (allowed: ...)". */
int gb_case_lyapunov_check(const char *path, gb_case *c);

#endif
