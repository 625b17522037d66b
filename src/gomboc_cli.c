#include "gomboc_cli.h"

#include "gb_error.h"
#include "gb_file.h"
#include "gb_parse.h"
#include "gb_surface.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

int cli_input_error(const char *command, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "gomboc %s: ", command);
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n(see 'gomboc %s --help')\n", command);
    va_end(ap);
    return EXIT_INPUT;
}

int cli_parse_only = 0;

const char *cli_allowed(void)
{
    const char *list = strstr(gb_error_message(), "(allowed: ");
    return list ? list : "";
}

int cli_number(const char *command, const char *option, const char *value, double min, double max, int open,
               const char *allowed, double *out)
{
    double x;
    const gb_parse_result p = gb_parse_double(value, &x);
    char what[320];
    snprintf(what, sizeof what, "%s '%.256s'", option, value);
    if (p == GB_PARSE_OVERFLOW) return cli_input_error(command, "%s is beyond the range of a double%s", what, allowed);
    if (p) return cli_input_error(command, "%s is not a number%s", what, allowed);
    const int above = open & CLI_OPEN_MIN ? x > min : x >= min, below = open & CLI_OPEN_MAX ? x < max : x <= max;
    if (!(above && below)) return cli_input_error(command, "%s is out of range%s", what, allowed);
    *out = x;
    return 0;
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
        if (gb_surface_init(&(gb_surface){0}, value, 0.0))
            return cli_input_error(command, "--morphology '%s' is unknown %s", value, cli_allowed());
        body->morphology = value;
        return 0;
    }
    if (!strcmp(opt, "--beta")) {
        if (cli_number(command, "--beta", value, 0.0, GB_SURFACE_BETA_MAX, CLI_OPEN_MAX,
                       " (allowed: 0 <= beta < 0.25, where r^4 = 1 + 4 beta sin(phi) cos(chi) > 0)", &body->beta))
            return EXIT_INPUT;
        body->have_beta = 1;
        return 0;
    }
    return 1;
}

/* The values written "--name=value" (split_equals), which alone may start with "--". */
static const char **attached_values;
static int attached_count;

void cli_attached_values(const char **values, int count)
{
    free(attached_values);
    attached_values = values, attached_count = count;
}

static int attached(const char *value)
{
    for (int k = 0; k < attached_count; k++)
        if (attached_values[k] == value) return 1;
    return 0;
}

int cli_flag(const char *command, const char *opt, int *flag)
{
    if (*flag) return cli_input_error(command, "option '%s' is given twice (allowed: each option once)", opt);
    *flag = 1;
    return 0;
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
    if (json && !strcmp(opt, "--json")) return cli_flag(command, opt, json) ? EXIT_INPUT : CLI_NEXT;
    const int is_body = body && (!strcmp(opt, "--morphology") || !strcmp(opt, "--beta"));
    if (!is_body && !listed(opt, valued)) return cli_input_error(command, "unknown option '%s'%s", opt, allowed);
    if (*i + 1 >= argc) return cli_input_error(command, "option '%s' needs a value%s", opt, "");
    if (!strncmp(argv[*i + 1], "--", 2) && !attached(argv[*i + 1]))
        return cli_input_error(command, "option '%s' needs a value, and '%s' is an option (allowed: %s VALUE, or %s=VALUE "
                               "for a value that starts with --)", opt, argv[*i + 1], opt, opt);
    /* Given before? The words before it, read as this parser reads them (a valued option takes the next). */
    for (int j = 0; j < *i; j++) {
        const int takes = listed(argv[j], valued) || (body && (!strcmp(argv[j], "--morphology") || !strcmp(argv[j], "--beta")));
        if (takes && !strcmp(argv[j], opt))
            return cli_input_error(command, "option '%s' is given twice ('%s', then '%s') (allowed: each option once)", opt,
                                   argv[j + 1], argv[*i + 1]);
        j += takes;
    }
    *value = argv[++*i];
    if (!is_body) return CLI_VALUE;
    return body_option(command, opt, *value, body) == 0 ? CLI_NEXT : EXIT_INPUT;
}

int cli_body_required(const char *command, const cli_body *body)
{
    if (!body->morphology) {
        gb_surface_init(&(gb_surface){0}, NULL, 0.0); /* its message lists the morphologies */
        return cli_input_error(command, "missing --morphology %s", cli_allowed());
    }
    if (!body->have_beta) return cli_input_error(command, "missing %s%s", "--beta", " (allowed: 0 <= beta < 0.25)");
    return 0;
}
/* ---- files: gb_file's rule, with the command's name on its messages ------------------------------ */

static void remove_temporaries(int sig)
{
    gb_file_remove_temporaries();
    signal(sig, SIG_DFL);
    raise(sig);
}

void cli_catch_signals(void (*handler)(int))
{
    static const int signals[] = {SIGINT, SIGTERM, SIGHUP};
    for (size_t k = 0; k < sizeof signals / sizeof signals[0]; k++) {
        struct sigaction now;
        if (sigaction(signals[k], NULL, &now) == 0 && now.sa_handler == SIG_IGN) continue; /* ignored by the parent */
        signal(signals[k], handler);
    }
}

void cli_install_cleanup(void)
{
    cli_catch_signals(remove_temporaries);
    /* A write beyond the file-size limit (ulimit -f) fails with EFBIG, reported as any failed write, its
     * temporaries removed, instead of killing the process with them left behind. */
    signal(SIGXFSZ, SIG_IGN);
}

int cli_files_check(const char *command, const gb_file_use *uses, size_t count)
{
    if (gb_file_check(uses, count)) return cli_input_error(command, "%s", gb_error_message());
    return 0;
}

int cli_lock_probe(const char *command, const char *path, const char *what)
{
    int lock;
    if (gb_file_lock(path, what, &lock)) {
        fprintf(stderr, "gomboc %s: %s\n", command, gb_error_message());
        return EXIT_COMPUTE;
    }
    gb_file_unlock(lock);
    return 0;
}

int cli_output_dir_check(const char *command, const char *option, const char *dir)
{
    if (gb_file_check_directory(dir, option)) return cli_input_error(command, "%s", gb_error_message());
    return 0;
}

void cli_manifest_add(cJSON *list, const gb_file_member *member)
{
    const char *slash = strrchr(member->path, '/');
    char checksum[17];
    snprintf(checksum, sizeof checksum, "%016llx", (unsigned long long)member->checksum);
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "name", slash ? slash + 1 : member->path);
    cli_json_add(o, "bytes", (double)member->bytes);
    cJSON_AddStringToObject(o, "fnv1a64", checksum);
    cJSON_AddItemToArray(list, o);
}

int cli_write_atomically(const char *path, const char *text)
{
    return gb_file_write_atomically(path, text, strlen(text));
}

int cli_failure(const char *command, int status)
{
    fprintf(stderr, "gomboc %s: %s\n", command, gb_error_message());
    return status == GB_EDOM || status == GB_EINVAL ? EXIT_INPUT : EXIT_COMPUTE;
}

/* cJSON prints a double with 15 digits whenever they read back to within its epsilon, so two numbers
 * that differ in the last bits can print alike: the command's JSON holds the shortest decimal (15, 16
 * or 17 digits) that reads back to the same double, and null for what is not finite. */
cJSON *cli_json_number(double value)
{
    if (!isfinite(value)) return cJSON_CreateNull();
    char text[40];
    for (int digits = 15; digits <= 17; digits++) {
        snprintf(text, sizeof text, "%.*g", digits, value);
        if (strtod(text, NULL) == value) break;
    }
    return cJSON_CreateRaw(text);
}

cJSON *cli_json_add(cJSON *object, const char *key, double value)
{
    cJSON *item = cli_json_number(value);
    cJSON_AddItemToObject(object, key, item);
    return item;
}

cJSON *cli_json_vector(const double *v, int n)
{
    cJSON *array = cJSON_CreateArray();
    for (int k = 0; k < n; k++) cJSON_AddItemToArray(array, cli_json_number(v[k]));
    return array;
}

void cli_print_json(const cJSON *root)
{
    char *text = cJSON_Print(root);
    puts(text);
    free(text);
}

char *cli_output_name(const char *dir, const char *input, const char *suffix)
{
    const char *slash = strrchr(input, '/'), *name = slash ? slash + 1 : input;
    size_t len = strlen(name);
    if (len > 4 && !strcmp(name + len - 4, ".ini")) len -= 4;
    const size_t size = strlen(dir) + len + strlen(suffix) + 3;
    char *out = malloc(size);
    if (out) snprintf(out, size, "%s/%.*s-%s", dir, (int)len, name, suffix);
    return out;
}

int cli_positional(const char *command, const char *opt, const char **slot, const char *what, const char *name)
{
    if (opt[0] == '-' && opt[1] != '\0') return 0;
    if (*slot) return cli_input_error(command, "a second %s '%s' (allowed: one %s)", what, opt, name);
    *slot = opt;
    return 1;
}

/* The user's cache of hulls (the fast grid's, by the grid's content) and of the paper's bodies' mass properties (by
 * the body, β, mass and quadrature): $XDG_CACHE_HOME/gomboc, else
 * $HOME/.cache/gomboc, made when missing (0700); none when GOMBOC_CACHE=off, when neither variable is set,
 * or when the directory cannot be made. A cache never fails a run. */
int cli_user_cache(gb_dynamics_context *context)
{
    const char *off = getenv("GOMBOC_CACHE"), *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    if (off && !strcmp(off, "off")) return GB_OK;
    char dir[PATH_MAX];
    int n;
    if (xdg && xdg[0] == '/') n = snprintf(dir, sizeof dir, "%s/gomboc", xdg);
    else if (home && home[0] == '/') n = snprintf(dir, sizeof dir, "%s/.cache/gomboc", home);
    else return GB_OK;
    if (n < 0 || n >= (int)sizeof dir) return GB_OK;
    char *slash = strrchr(dir, '/');
    *slash = '\0';
    if (mkdir(dir, 0700) && errno != EEXIST) return GB_OK; /* $XDG_CACHE_HOME or ~/.cache itself */
    *slash = '/';
    if (mkdir(dir, 0700) && errno != EEXIST) return GB_OK;
    return gb_dynamics_context_cache(context, dir);
}
