/* gb_error — the library's single error path.
 *
 * Every fallible function returns an int status: GB_OK (0) on success, one of the codes below
 * otherwise, and leaves a message saying what went wrong, where, and the allowed range. The library
 * never exits and never prints; the caller decides what to do with the message. */
#ifndef GB_ERROR_H
#define GB_ERROR_H

#include "gb_export.h"

#ifdef __cplusplus
extern "C" {
#endif

enum gb_status {
    GB_OK = 0,
    GB_EDOM = 1,     /* a value outside its allowed range */
    GB_EINVAL = 2,   /* malformed or unknown input */
    GB_ENOMEM = 3,   /* allocation failed */
    GB_ENOCONV = 4,  /* an iteration or quadrature did not converge */
    GB_EIO = 5,      /* a file could not be read or written */
    GB_ENUMERIC = 6  /* a GSL or Qhull routine reported failure */
};

/* The longest message kept, in bytes: room for two paths of PATH_MAX and the text around them. */
#define GB_ERROR_MAX 16384

/* Record a message (printf format) for status `code` and return `code`, so a failing function can
 * end with `return gb_error_set(GB_EDOM, "...")`. The arguments may include gb_error_message(), to
 * wrap the last message in its context. */
GB_API int gb_error_set(int code, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* As gb_error_set, for a configuration the model does not follow: a limit of the model, not a failure of a
 * computation (Painlevé's paradox under the event-driven law, a face that lands flat on a rough plane...). A message
 * that wraps it (holds its text) is at the limit too; any other message is not. */
GB_API int gb_error_set_limit(int code, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* 1 when the most recent failure in this thread is a model's limit (gb_error_set_limit), 0 otherwise. */
GB_API int gb_error_at_limit(void);

/* The message of the most recent failure in this thread ("" if none). */
GB_API const char *gb_error_message(void);

/* Forget the last message. */
GB_API void gb_error_clear(void);

/* Look `name` up in `names` (count entries); on success store its position in *index. Otherwise
 * GB_EINVAL with the message "<what> '<name>' is unknown (allowed: a, b, c)". */
GB_API int gb_error_parse_name(const char *name, const char *const *names, int count, const char *what, int *index);

/* Opt-in, once, before the GSL-backed modules: where the program has left GSL's default handler (which aborts
 * the process on any GSL failure), turn GSL's handler off, so that GSL failures come back as status codes that
 * the library turns into gb_ messages. A handler the host program installed itself is left in place (the host
 * then decides what a GSL failure does: its own handler may abort). Not calling it leaves GSL's handler alone. */
GB_API void gb_error_init_gsl(void);

#ifdef __cplusplus
}
#endif

#endif
