/* gb_ini — the strict line reader in front of libinih (see gb_ini.h). */
#include "gb_ini.h"

#include "gb_error.h"

#include <errno.h>
#include <fcntl.h>
#include <ini.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

enum { SECTIONS_MAX = 32 };

struct gb_ini_reader {
    const char *name;          /* the file, for messages */
    const char *text;          /* the whole file */
    size_t size, pos;
    const char *const *sections;
    size_t section_count;
    int section_line[SECTIONS_MAX];
    int sections_seen;         /* section headers read */
    int line;                  /* the line last handed to libinih */
    int error_line;            /* the first error found by the reader or the handler (0: none) */
    char message[768];         /* its text, without the file and line */
    int errors;                /* the errors found: a handler's (a key's value) leave the file read on, so that every
                                * key's fault is said at once; the reader's (a line it cannot read) end it */
    char more[GB_INI_MORE_MAX]; /* the second and later ones, each "\nFILE:LINE: reason", the first GB_INI_ERRORS_MAX */
    gb_ini_handler handler;
    void *user;
};

static int vfail(gb_ini_reader *r, const char *fmt, va_list ap)
{
    if (r->errors++ == 0) {
        vsnprintf(r->message, sizeof r->message, fmt, ap);
        r->error_line = r->line;
    } else if (r->errors <= GB_INI_ERRORS_MAX) {
        char text[768];
        vsnprintf(text, sizeof text, fmt, ap);
        const size_t used = strlen(r->more);
        snprintf(r->more + used, sizeof r->more - used, "\n%s:%d: %s", r->name, r->line, text);
    }
    return 0;
}

int gb_ini_fail(gb_ini_reader *r, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vfail(r, fmt, ap);
    va_end(ap);
    return 0;
}

int gb_ini_line(const gb_ini_reader *r) { return r->line; }

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
static int line_bytes_ok(gb_ini_reader *r, const unsigned char *s, size_t n)
{
    for (size_t k = 0; k < n;) {
        unsigned code;
        const size_t len = utf8_length(s + k, n - k, &code);
        if (!len) return gb_ini_fail(r, "byte 0x%02X at column %zu is not UTF-8 (allowed: UTF-8 text)", s[k], k + 1);
        if (code == 0) return gb_ini_fail(r, "a NUL byte at column %zu (allowed: text without NUL bytes)", k + 1);
        if ((code < 0x20 && code != '\t') || (code >= 0x7F && code <= 0x9F))
            return gb_ini_fail(r, "control character U+%04X at column %zu (allowed: printable text and TAB)", code, k + 1);
        k += len;
    }
    return 1;
}

/* A section header line (after leading blanks): known, and only once. */
static int check_section(gb_ini_reader *r, const char *p, size_t n)
{
    const char *end = memchr(p, ']', n);
    if (!end) return 1; /* libinih reports it as malformed */
    const size_t len = (size_t)(end - p - 1);
    /* libinih ignores what follows the ']': "[body] beta = 0.2" would lose its key without a word. */
    const char *rest = end + 1;
    while (rest < p + n && (*rest == ' ' || *rest == '\t')) rest++;
    if (rest < p + n && *rest != ';' && *rest != '#')
        return gb_ini_fail(r, "text after [%.*s] (allowed: a section header alone on its line, or with a ; comment)",
                           (int)len, p + 1);
    int k = -1;
    for (size_t j = 0; j < r->section_count && k < 0; j++)
        if (strlen(r->sections[j]) == len && !strncmp(r->sections[j], p + 1, len)) k = (int)j;
    if (k < 0) {
        char list[512];
        size_t used = 0;
        for (size_t j = 0; j < r->section_count && used < sizeof list; j++)
            used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", j ? ", " : "", r->sections[j]);
        return gb_ini_fail(r, "unknown section [%.*s] (allowed: %s)", (int)len, p + 1, list);
    }
    if (r->section_line[k])
        return gb_ini_fail(r, "[%s] again (first at line %d; allowed: each section once)", r->sections[k], r->section_line[k]);
    r->section_line[k] = r->line;
    r->sections_seen++;
    return 1;
}

/* libinih's reader: hands over one line at a time, each checked first. A line it cannot read ends the file; a key's
 * fault (its handler's) does not. */
static char *next_line(char *out, int capacity, void *stream)
{
    gb_ini_reader *r = stream;
    if (r->pos >= r->size) return NULL;
    const char *start = r->text + r->pos;
    const char *newline = memchr(start, '\n', r->size - r->pos);
    size_t n = newline ? (size_t)(newline - start) : r->size - r->pos;
    r->pos += n + (newline != NULL);
    r->line++;
    if (n && start[n - 1] == '\r') n--; /* CRLF */
    if (r->line == 1 && n >= 3 && !memcmp(start, "\xEF\xBB\xBF", 3)) start += 3, n -= 3; /* a UTF-8 BOM */
    const size_t limit = (size_t)capacity - 2; /* the line, its newline and the NUL in libinih's buffer */
    if (n > limit) {
        gb_ini_fail(r, "the line is %zu bytes long (allowed: at most %zu bytes a line)", n, limit);
        return NULL;
    }
    if (!line_bytes_ok(r, (const unsigned char *)start, n)) return NULL;
    size_t lead = 0;
    while (lead < n && (start[lead] == ' ' || start[lead] == '\t')) lead++;
    if (lead < n && start[lead] != ';' && start[lead] != '#') {
        if (lead > 0) {
            gb_ini_fail(r, "an indented line (allowed: keys and [sections] start in the first column; continuation "
                           "lines are not read)");
            return NULL;
        }
        if (start[0] == '[' && !check_section(r, start, n)) return NULL;
        /* libinih also takes "key : value"; the formats are documented, and read, as "key = value" only */
        const char *colon = memchr(start, ':', n), *equals = memchr(start, '=', n);
        if (start[0] != '[' && colon && (!equals || colon < equals)) {
            gb_ini_fail(r, "'%.*s': a key and its value separated by ':' (allowed: key = value)", (int)n, start);
            return NULL;
        }
    }
    memcpy(out, start, n);
    out[n] = '\n';
    out[n + 1] = '\0';
    return out;
}

static int on_key(void *user, const char *section, const char *name, const char *value)
{
    gb_ini_reader *r = user;
    if (!section[0]) return gb_ini_fail(r, "%s = %s: a key before any [section] (allowed: [section] first)", name, value);
    return r->handler(r, r->user, section, name, value);
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

int gb_ini_read(const char *name, const char *text, size_t size, const char *const *sections, size_t count,
                gb_ini_handler handler, void *user)
{
    if (count > SECTIONS_MAX) return gb_error_set(GB_EINVAL, "%s: %zu sections (allowed: at most %d)", name, count, SECTIONS_MAX);
    gb_ini_reader r = {.name = name, .text = text, .size = size, .sections = sections, .section_count = count,
                       .handler = handler, .user = user};
    const int ret = ini_parse_stream(next_line, &r, on_key, &r);
    if (ret == -2) return gb_error_set(GB_ENOMEM, "%s: out of memory while reading", name);
    if (ret > 0 && (!r.error_line || ret < r.error_line)) {
        char bad[256];
        line_text(text, size, ret, bad, sizeof bad);
        return gb_error_set(GB_EINVAL, "%s:%d: malformed line '%s' (allowed: [section], key = value, ; comment)", name, ret, bad);
    }
    if (r.errors > GB_INI_ERRORS_MAX)
        return gb_error_set(GB_EINVAL, "%s:%d: %s%s\n%s: %d faults in all, the first %d said", name, r.error_line, r.message,
                            r.more, name, r.errors, GB_INI_ERRORS_MAX);
    if (r.errors) return gb_error_set(GB_EINVAL, "%s:%d: %s%s", name, r.error_line, r.message, r.more);
    /* A file with no section says nothing: an empty file (a copy that failed, a truncated write) is not
     * read as "all defaults". */
    if (!r.sections_seen)
        return gb_error_set(GB_EINVAL, "%s: no [section] in %zu bytes: an empty file, or only blank lines and comments "
                            "(allowed: at least one [section], e.g. [scene] alone for every default)", name, size);
    return GB_OK;
}
