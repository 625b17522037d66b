/* gb_ini — the strict reader every file format of gomboc uses (scene files, scan files): a line checker
 * in front of libinih, so that no line is misread.
 *
 * A file is read whole (a regular file of at most `max_bytes`), then handed to libinih one checked line
 * at a time: at most GB_INI_LINE_MAX bytes (libinih's buffer, less the newline and the NUL), UTF-8 with
 * no NUL and no control character but TAB, no indented (continuation) line, a section header alone on
 * its line, only the format's sections, each once, no key before the first section, "key = value" (not
 * libinih's "key : value"), and at least one section (an empty file is refused). Every error
 * names the file and the line: "FILE:LINE: reason (allowed: ...)", status GB_EINVAL; the faults of several keys are
 * said together, one a line. What a key means,
 * its range and whether it was given twice is the format's handler's to say (gb_ini_fail). */
#ifndef GB_INI_H
#define GB_INI_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define GB_INI_LINE_MAX 198

typedef struct gb_ini_reader gb_ini_reader;

/* One key = value of section `section`. Returns 1 to go on, or the result of gb_ini_fail. */
typedef int (*gb_ini_handler)(gb_ini_reader *reader, void *user, const char *section, const char *key,
                              const char *value);

/* Read `size` bytes of `text`, named `name` in messages, whose sections are sections[0 .. count). */
int gb_ini_read(const char *name, const char *text, size_t size, const char *const *sections, size_t count,
                gb_ini_handler handler, void *user);

/* From a handler: record the error of the current line (printf-formatted, without file and line);
 * returns 0, what the handler returns. The file is read on: every key's fault is said at once, one a line
 * ("FILE:LINE: reason", the first GB_INI_ERRORS_MAX of them, then how many in all), the first first; a line the reader
 * cannot read (its bytes, its form) ends the file there. */
#define GB_INI_ERRORS_MAX 8
#define GB_INI_MORE_MAX (GB_INI_ERRORS_MAX * 1024)
int gb_ini_fail(gb_ini_reader *reader, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The line of the key being handled (1-based). */
int gb_ini_line(const gb_ini_reader *reader);

#ifdef __cplusplus
}
#endif

#endif
