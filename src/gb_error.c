#include "gb_error.h"

#include <gsl/gsl_errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static _Thread_local char error_message[GB_ERROR_MAX];
static _Thread_local int error_at_limit; /* the message is a model's limit (gb_error_set_limit), or wraps one */

/* The message formatted apart first: the arguments may hold the last message itself (a message wrapped in context),
 * which keeps its limit. */
static void record(int limit, const char *fmt, va_list args)
{
    char text[GB_ERROR_MAX];
    vsnprintf(text, sizeof text, fmt, args);
    error_at_limit = limit || (error_at_limit && error_message[0] && strstr(text, error_message));
    memcpy(error_message, text, strlen(text) + 1);
}

int gb_error_set(int code, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    record(0, fmt, args);
    va_end(args);
    return code;
}

int gb_error_set_limit(int code, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    record(1, fmt, args);
    va_end(args);
    return code;
}

int gb_error_at_limit(void) { return error_at_limit && error_message[0]; }

const char *gb_error_message(void) { return error_message; }

void gb_error_clear(void) { error_message[0] = '\0', error_at_limit = 0; }

void gb_error_init_gsl(void)
{
    /* GSL's default (no handler set) aborts the process: only that is replaced; a handler the host program
     * installed is put back as it was */
    gsl_error_handler_t *previous = gsl_set_error_handler_off();
    if (previous) gsl_set_error_handler(previous);
}

int gb_error_parse_name(const char *name, const char *const *names, int count, const char *what, int *index)
{
    char allowed[256] = "";
    size_t used = 0;
    for (int k = 0; k < count; k++) {
        if (name && strcmp(name, names[k]) == 0) {
            *index = k;
            return GB_OK;
        }
        used += (size_t)snprintf(allowed + used, sizeof allowed - used, "%s%s", k ? ", " : "", names[k]);
        if (used >= sizeof allowed) used = sizeof allowed - 1;
    }
    return gb_error_set(GB_EINVAL, "%s '%s' is unknown (allowed: %s)", what, name ? name : "(null)", allowed);
}
