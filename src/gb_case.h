/* gb_case — scenes: INI files read with libinih into one struct, defaults in code.
 *
 * Every key is optional; gb_case_default() holds every default, once. A scene names its model, its
 * outputs and its diagnostics; nothing else is computed or written. The sections ([scene], [body],
 * [forcing], [model], [integrator], [initial], [output], [diagnostics], [strobe], [spectrum],
 * [lyapunov]), their keys and each key's physical range are one table in gb_case.c, read through
 * gb_case_key_count and gb_case_key_allowed; cases/README.md lists them in the same words (a check
 * compares the two).
 *
 * The reader is strict: a file is read whole (a regular file of at most GB_CASE_FILE_MAX bytes) and
 * every line is checked by gb_ini before libinih sees it (at most GB_INI_LINE_MAX bytes, UTF-8 with no
 * NUL and no control character but TAB, no indented continuation line, only known sections, each
 * once). Every key is given at most once, and its value is one whole token
 * inside the key's physical range (gb_case_key_allowed); adaptive steppers are refused with grid
 * contact. Errors name the file, the line, the key and the allowed values, with status GB_EINVAL or
 * GB_EDOM (bad input); nothing is returned half-filled. */
#ifndef GB_CASE_H
#define GB_CASE_H

#include "gb_export.h"

#include "gb_dynamics.h"
#include "gb_integrate.h"
#include "gb_lyapunov.h"
#include "gb_spectrum.h"
#include "gb_strobe.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A scene file holds at most this many bytes; a text value at most GB_CASE_TEXT_MAX - 1. */
#define GB_CASE_FILE_MAX (1 << 20)
#define GB_CASE_TEXT_MAX 256
#define GB_CASE_KEY_MAX 64

typedef struct gb_case {
    char description[GB_CASE_TEXT_MAX];
    gb_surface body;              /* [body] morphology and beta (eqs 3-9), or a body of one's own (gb_body.h): one
                                   * value, as every module takes it */
    char mesh[GB_CASE_TEXT_MAX];  /* [body] mesh as written ("" when not given; relative to the scene's folder) */
    char r_text[GB_CASE_TEXT_MAX], chi_text[GB_CASE_TEXT_MAX]; /* [body] r, chi as written ("": not given) */
    gb_dynamics_def dynamics;     /* forcing in m/s² after reading amplitude_units */
    int amplitudes_in_g;          /* 1 when A1, A2 were given in units of g (eq 61) */
    double A1, A2;                /* as written in the file */
    gb_integrate_def integrate;
    double attitude[9];           /* R0, row-major */
    char attitude_text[GB_CASE_TEXT_MAX];
    double omega0[3];
    int write_history, write_summary;
    int write_impacts;            /* [output] impacts: NAME-impacts.csv (the unilateral law) */
    int monitors;
    int strobe, spectrum, lyapunov;  /* [diagnostics] */
    gb_strobe_def strobe_def;
    size_t spectrum_transient;
    gb_spectrum_window spectrum_window;
    gb_lyapunov_def lyapunov_def;     /* interval in seconds and intervals set from the scene's periods */
    size_t lyapunov_interval_periods;
    size_t lyapunov_window_periods;   /* windowed exponents over this many periods; 0: none */
    double omega_scale;               /* [rad/s]; the forcing omega unless given */
    int key_line[GB_CASE_KEY_MAX];    /* the line each key was read from (0: the default), by key index */
    const char *key_origin[GB_CASE_KEY_MAX]; /* while the scene is read: who set a key over the file (an
                                               * override's origin, for messages), else NULL; all NULL after */
} gb_case;

/* The defaults: Table 1 with the paper's model (m/s² reading of A1, A2; R0 = I; ω0 = 0). */
GB_API gb_case gb_case_default(void);

/* Read `path` over the defaults. GB_EINVAL when `path` is not a readable regular file (missing, a directory, no
 * permission) or is too large, GB_EIO when reading it fails midway (gb_file_read); GB_EINVAL / GB_EDOM with
 * "FILE:LINE: [section] key = value: reason (allowed: ...)" for its contents. */
GB_API int gb_case_load(const char *path, gb_case *out);

/* The same for `size` bytes of `text` (NUL bytes and all), named `name` in messages. */
GB_API int gb_case_load_text(const char *name, const char *text, size_t size, gb_case *out);

/* A key set over what the scene file says (a scan point's coordinate): the same parser and range as
 * the file's own line, before the checks no single key can make. `origin` names where it comes from
 * in messages ("scan.ini:12"). */
typedef struct gb_case_override {
    const char *section, *key, *value, *origin;
} gb_case_override;

/* gb_case_load and gb_case_load_text with overrides applied in order. */
GB_API int gb_case_load_with(const char *path, const gb_case_override *overrides, size_t count, gb_case *out);
GB_API int gb_case_load_text_with(const char *name, const char *text, size_t size, const gb_case_override *overrides,
                                  size_t count, gb_case *out);

/* The path of the scene's [body] mesh as the reader opened it: as written when absolute or when the scene's
 * path has no folder, else in the scene's folder ("" when the scene has no mesh). GB_EINVAL when it does not
 * fit in `size` bytes (out then holds nothing usable). */
GB_API int gb_case_mesh_path(const char *scene_path, const gb_case *c, char *out, size_t size);

/* The keys a scene may set: their count, and for key `index` its section, name and allowed values
 * in words (the text every error message and cases/README.md use). GB_EDOM past the last key. It
 * leaves no library message behind (gb_error_message() is cleared). */
GB_API size_t gb_case_key_count(void);
GB_API int gb_case_key_allowed(size_t index, const char **section, const char **name, char *allowed, size_t size);
/* Does [section] name take one number (a real, an angle, a count)? 1, 0, or -1 for no such key. */
GB_API int gb_case_key_numeric(const char *section, const char *name);

/* The [lyapunov] section against the run (gb_case_load does this when [diagnostics] lyapunov = yes;
 * `gomboc lyapunov` asks for it whatever the flag): sets lyapunov_def.interval [s] and .intervals and
 * omega_scale. GB_EDOM with "FILE:LINE: [lyapunov] key: reason (allowed: ...)". */
GB_API int gb_case_lyapunov_check(const char *path, gb_case *c);
/* What a scene may ask: at most GB_CASE_STEPS_MAX steps, and records (spectrum, strobe, λ) of at most
 * half the machine's memory (or of RLIMIT_AS) bytes, as gb_case.c estimates them.
 * gb_case_load refuses more (GB_EDOM naming [integrator] periods). */
#define GB_CASE_STEPS_MAX 1e12

#ifdef __cplusplus
}
#endif

#endif
