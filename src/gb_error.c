#include "gb_error.h"

#include <gsl/gsl_errno.h>
#include <stdarg.h>
#include <stdio.h>

static _Thread_local char error_message[1024];

int gb_error_set(int code, const char *fmt, ...)
{
    va_list args;
    va_start(args, fmt);
    vsnprintf(error_message, sizeof error_message, fmt, args);
    va_end(args);
    return code;
}

const char *gb_error_message(void) { return error_message; }

void gb_error_clear(void) { error_message[0] = '\0'; }

void gb_error_init_gsl(void) { gsl_set_error_handler_off(); }
