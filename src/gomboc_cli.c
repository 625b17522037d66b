#include "gomboc_cli.h"

#include "gb_error.h"
#include "gb_parse.h"
#include "gb_surface.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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

int cli_next_option(const char *command, int argc, char **argv, int *i, const char *usage,
                    const char *const *valued, const char *allowed, cli_body *body, int *json,
                    const char **value)
{
    const char *opt = argv[*i];
    if (!strcmp(opt, "--help") || !strcmp(opt, "-h")) {
        fputs(usage, stdout);
        return CLI_HELP;
    }
    if (json && !strcmp(opt, "--json")) {
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
    if (!body->morphology) {
        gb_surface_init(&(gb_surface){0}, NULL, 0.0); /* its message lists the morphologies */
        return cli_input_error(command, "missing --morphology %s", cli_allowed());
    }
    if (!body->have_beta) return cli_input_error(command, "missing %s%s", "--beta", " (allowed: 0 <= beta < 0.25)");
    return 0;
}
/* ---- output files: checked before the work, written all or nothing ------------------------------ */

/* The temporaries of this process, for the signal handler: set before the count grows. */
enum { TEMP_MAX = 16 };
static char *volatile temp_paths[TEMP_MAX];
static volatile sig_atomic_t temp_count;

static void remove_temporaries(int sig)
{
    for (sig_atomic_t k = 0; k < temp_count; k++)
        if (temp_paths[k]) unlink(temp_paths[k]);
    signal(sig, SIG_DFL);
    raise(sig);
}

void cli_install_cleanup(void)
{
    static const int signals[] = {SIGINT, SIGTERM, SIGHUP};
    for (size_t k = 0; k < sizeof signals / sizeof signals[0]; k++) signal(signals[k], remove_temporaries);
}

static void temp_forget(const char *path)
{
    for (sig_atomic_t k = 0; k < temp_count; k++)
        if (temp_paths[k] == path) temp_paths[k] = NULL;
}

/* The directory part of `path` ("." when it has none), malloc'd. */
static char *directory_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash) return strdup(".");
    if (slash == path) return strdup("/");
    return strndup(path, (size_t)(slash - path));
}

/* Remove the temporaries ".gomboc-PID-XXXXXX" that a process no longer alive left in `dir`. */
static void sweep_stale_temporaries(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    for (struct dirent *e; (e = readdir(d));) {
        long pid;
        char tail[8];
        int used = 0;
        if (sscanf(e->d_name, ".gomboc-%ld-%6[A-Za-z0-9]%n", &pid, tail, &used) != 2 || e->d_name[used] != '\0' ||
            strlen(tail) != 6 || pid <= 0 || pid == (long)getpid())
            continue;
        if (kill((pid_t)pid, 0) == 0 || errno != ESRCH) continue; /* alive, or not ours to judge */
        char *path = malloc(strlen(dir) + strlen(e->d_name) + 2);
        if (!path) break;
        sprintf(path, "%s/%s", dir, e->d_name);
        struct stat st;
        if (lstat(path, &st) == 0 && S_ISREG(st.st_mode)) unlink(path);
        free(path);
    }
    closedir(d);
}

int cli_output_dir_check(const char *command, const char *option, const char *dir)
{
    struct stat st;
    if (stat(dir, &st) != 0)
        return cli_input_error(command, "%s '%s' does not exist%s", option, dir, " (allowed: an existing, writable directory)");
    if (!S_ISDIR(st.st_mode))
        return cli_input_error(command, "%s '%s' is not a directory%s", option, dir, " (allowed: an existing, writable directory)");
    if (access(dir, W_OK | X_OK) != 0)
        return cli_input_error(command, "%s '%s' is not writable%s", option, dir, " (allowed: an existing, writable directory)");
    return 0;
}

int cli_output_check(const char *command, const char *option, const char *path)
{
    static const char *const allowed = " (allowed: a new or regular file in an existing, writable directory)";
    if (!path[0]) return cli_input_error(command, "%s '%s' is empty%s", option, path, allowed);
    char *dir = directory_of(path);
    if (!dir) return cli_input_error(command, "%s '%s': out of memory", option, path);
    struct stat st;
    int status = 0;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))
        status = cli_input_error(command, "%s '%s': its directory does not exist%s", option, path, allowed);
    else if (access(dir, W_OK | X_OK) != 0)
        status = cli_input_error(command, "%s '%s': its directory is not writable%s", option, path, allowed);
    else if (lstat(path, &st) == 0 && !S_ISREG(st.st_mode))
        status = cli_input_error(command, "%s '%s' exists and is not a regular file (a directory, link or device)%s",
                                 option, path, allowed);
    free(dir);
    return status;
}

FILE *cli_outputs_open(cli_outputs *set, const char *path, int *status)
{
    if (*status) return NULL;
    /* A slot for the signal handler: one a committed set has freed, or a new one. */
    sig_atomic_t slot = 0;
    while (slot < temp_count && temp_paths[slot]) slot++;
    if (set->count == CLI_OUTPUTS_MAX || slot == TEMP_MAX) {
        *status = gb_error_set(GB_ENOMEM, "too many output files at once (at most %d)", CLI_OUTPUTS_MAX);
        return NULL;
    }
    cli_output *o = &set->items[set->count];
    memset(o, 0, sizeof *o);
    char *dir = directory_of(path);
    o->path = strdup(path);
    o->tmp = dir ? malloc(strlen(dir) + 40) : NULL;
    if (!dir || !o->path || !o->tmp) {
        free(dir), free(o->path), free(o->tmp);
        *status = gb_error_set(GB_ENOMEM, "out of memory for the output '%s'", path);
        return NULL;
    }
    sweep_stale_temporaries(dir);
    sprintf(o->tmp, "%s/.gomboc-%ld-XXXXXX", dir, (long)getpid());
    free(dir);
    const int fd = mkstemp(o->tmp);
    if (fd >= 0) {
        temp_paths[slot] = o->tmp;
        if (slot == temp_count) temp_count = temp_count + 1;
        const mode_t mask = umask(0);
        umask(mask);
        fchmod(fd, 0666 & ~mask); /* what fopen would have made */
        o->file = fdopen(fd, "w");
        if (!o->file) close(fd), unlink(o->tmp);
    }
    if (!o->file) {
        *status = gb_error_set(GB_EIO, "cannot write '%s': %s", path, strerror(errno));
        temp_forget(o->tmp);
        free(o->path), free(o->tmp);
        return NULL;
    }
    set->count++;
    return o->file;
}

int cli_outputs_commit(cli_outputs *set, int status)
{
    for (int k = 0; k < set->count; k++) {
        cli_output *o = &set->items[k];
        if (o->file && (ferror(o->file) | fclose(o->file)) && !status)
            status = gb_error_set(GB_EIO, "cannot write '%s': %s", o->path, strerror(errno ? errno : EIO));
        o->file = NULL;
    }
    int renamed = 0; /* items[0 .. renamed) are in place */
    for (; !status && renamed < set->count; renamed++) {
        cli_output *o = &set->items[renamed];
        struct stat st;
        if (lstat(o->path, &st) == 0 && !S_ISREG(st.st_mode)) /* appeared during the run */
            status = gb_error_set(GB_EIO, "cannot write '%s': it is no longer a regular file", o->path);
        else if (rename(o->tmp, o->path) != 0)
            status = gb_error_set(GB_EIO, "cannot write '%s': %s", o->path, strerror(errno));
        if (status) break;
    }
    for (int k = 0; k < set->count; k++) {
        cli_output *o = &set->items[k];
        if (status) {
            unlink(o->tmp);
            if (k < renamed) unlink(o->path); /* the set would be mixed */
        }
        temp_forget(o->tmp);
        free(o->path);
        free(o->tmp);
    }
    set->count = 0;
    return status;
}

int cli_write_atomically(const char *path, const char *text)
{
    cli_outputs set = {0};
    int status = GB_OK;
    FILE *f = cli_outputs_open(&set, path, &status);
    if (f && fputs(text, f) < 0) status = gb_error_set(GB_EIO, "cannot write '%s': %s", path, strerror(errno));
    return cli_outputs_commit(&set, status);
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
