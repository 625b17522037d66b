#include "gomboc_cli.h"

#include "gb_error.h"
#include "gb_surface.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int cli_input_error(const char *command, const char *fmt, const char *what, const char *allowed)
{
    fprintf(stderr, "gomboc %s: ", command);
    fprintf(stderr, fmt, what, allowed);
    fprintf(stderr, "\n(see 'gomboc %s --help')\n", command);
    return EXIT_INPUT;
}

int cli_parse_double(const char *text, double *value)
{
    char *end;
    errno = 0;
    *value = strtod(text, &end);
    return text[0] != '\0' && *end == '\0' && errno == 0 && isfinite(*value);
}

static int listed(const char *opt, const char *const *names)
{
    for (; *names; names++)
        if (!strcmp(opt, *names)) return 1;
    return 0;
}

/* --morphology or --beta: 0 when consumed, 1 when `opt` is neither, EXIT_INPUT on a bad value. */
static int body_option(const char *command, const char *opt, const char *value, cli_body *body)
{
    if (!strcmp(opt, "--morphology")) {
        if (!gb_surface_morphology_find(value))
            return cli_input_error(command, "--morphology '%s' is unknown%s", value, " (allowed: I, II)");
        body->morphology = value;
        return 0;
    }
    if (!strcmp(opt, "--beta")) {
        if (!cli_parse_double(value, &body->beta))
            return cli_input_error(command, "--beta '%s' is not a number%s", value, " (allowed: 0 <= beta < 0.25)");
        if (!(body->beta >= 0.0 && body->beta < GB_SURFACE_BETA_MAX))
            return cli_input_error(command, "--beta %s is out of range%s", value,
                                   " (allowed: 0 <= beta < 0.25, where r^4 = 1 + 4 beta sin(phi) cos(chi) > 0)");
        body->have_beta = 1;
        return 0;
    }
    return 1;
}

int cli_next_option(const char *command, int argc, char **argv, int *i, const char *usage,
                    const char *const *valued, const char *allowed, cli_body *body, int *json,
                    const char **value)
{
    const char *opt = argv[*i];
    if (!strcmp(opt, "--help") || !strcmp(opt, "-h")) {
        fputs(usage, stdout);
        return CLI_HELP;
    }
    if (!strcmp(opt, "--json")) {
        *json = 1;
        return CLI_NEXT;
    }
    const int is_body = body && (!strcmp(opt, "--morphology") || !strcmp(opt, "--beta"));
    if (!is_body && !listed(opt, valued)) return cli_input_error(command, "unknown option '%s'%s", opt, allowed);
    if (*i + 1 >= argc) return cli_input_error(command, "option '%s' needs a value%s", opt, "");
    *value = argv[++*i];
    if (!is_body) return CLI_VALUE;
    return body_option(command, opt, *value, body) == 0 ? CLI_NEXT : EXIT_INPUT;
}

int cli_body_required(const char *command, const cli_body *body)
{
    if (!body->morphology) return cli_input_error(command, "missing %s%s", "--morphology", " (allowed: I, II)");
    if (!body->have_beta) return cli_input_error(command, "missing %s%s", "--beta", " (allowed: 0 <= beta < 0.25)");
    return 0;
}
/* Write `text` to `path` atomically: a temporary file beside it, then rename. */
int cli_write_atomically(const char *path, const char *text)
{
    size_t len = strlen(path) + 16;
    char *tmp = malloc(len);
    if (!tmp) return gb_error_set(GB_ENOMEM, "out of memory");
    snprintf(tmp, len, "%s.tmp%ld", path, (long)getpid());
    FILE *f = fopen(tmp, "w");
    int ok = f && fputs(text, f) >= 0;
    if (f && fclose(f) != 0) ok = 0;
    if (ok && rename(tmp, path) != 0) ok = 0;
    if (!ok) {
        remove(tmp);
        free(tmp);
        return gb_error_set(GB_EIO, "cannot write '%s': %s", path, strerror(errno));
    }
    free(tmp);
    return GB_OK;
}

int cli_failure(const char *command, int status)
{
    fprintf(stderr, "gomboc %s: %s\n", command, gb_error_message());
    return status == GB_EDOM || status == GB_EINVAL ? EXIT_INPUT : EXIT_COMPUTE;
}

cJSON *cli_json_vector(const double *v, int n) { return cJSON_CreateDoubleArray(v, n); }

void cli_print_json(const cJSON *root)
{
    char *text = cJSON_Print(root);
    puts(text);
    free(text);
}
