/* gomboc — the command. Subcommands map onto the library's modules; options are parsed strictly
 * (an unknown or malformed option is an error naming it and its allowed form). Exit status: 0 on
 * success, 2 for bad input, 1 when a computation fails or its output cannot be written (standard
 * output included). */
#include "gomboc_cli.h"

#include "gb_body.h"

#include "gb_error.h"
#include "gb_integrate.h"
#if defined(__has_include)
#if __has_include("gomboc_version.h")
#include "gomboc_version.h" /* GOMBOC_VERSION, written by the Makefile */
#endif
#endif
#ifndef GOMBOC_VERSION
#define GOMBOC_VERSION "unknown" /* a build without the Makefile's header (the option fuzzer's) */
#endif

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *usage_main =
    "usage: gomboc <command> [options]\n"
    "\n"
    "commands:\n"
    "  shape     volume, centroid, inertia, L, curvature, convexity limit and static equilibria\n"
    "            of one body (paper section 2)\n"
    "  contact   the contact point for one body-frame vertical z_b: the paper's grid, the exact\n"
    "            fast grid search or continuous minimisation, and every local minimum (section 4)\n"
    "  run       integrate one scene (a case file) and write its time histories and summary\n"
    "            (sections 3, 5, 8)\n"
    "  lyapunov  the maximal Lyapunov exponent of one scene, with its error bar and convergence\n"
    "            record (section 6, eq 77)\n"
    "  scan      a map over two keys of a scene, parallel and resumable (section 8.3, Figs 10-13)\n"
    "  melnikov  the reduced separatrix-splitting criterion for a scene's body and forcing (section 7)\n"
    "  check     that every file a run's or a scan's manifest lists stands beside it, whole\n"
    "  prove     statements proved on Arb's ball arithmetic: the Melnikov oracles (docs/proofs.md)\n"
    "\n"
    "'gomboc <command> --help' (or 'gomboc help <command>') describes each command's options; an option's\n"
    "value follows it as the next word or after '=' (--beta 0.12, --beta=0.12). 'gomboc --version' prints\n"
    "the version.\n";

static const struct {
    const char *name;
    int (*run)(int argc, char **argv);
} commands[] = {{"shape", command_shape}, {"contact", command_contact}, {"run", command_run}, {"lyapunov", command_lyapunov},
                {"scan", command_scan}, {"melnikov", command_melnikov}, {"check", command_check},
                {"prove", command_prove}};

/* What was printed must have reached standard output (a full disk, a closed pipe). */
static int stdout_written(const char *command, int status)
{
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "gomboc%s%s: cannot write standard output: %s\n", command ? " " : "", command ? command : "",
                strerror(errno ? errno : EIO));
        if (!status) status = EXIT_COMPUTE;
    }
    return status;
}

/* The subcommand's words with every "--name=value" split into "--name" "value" (malloc'd; NULL when out of
 * memory), so that each command's parser sees one form; the values so attached are recorded
 * (cli_value_attached: such a value may start with "--"). */
static char **split_equals(int argc, char **argv, int *out_argc)
{
    char **words = malloc((size_t)(2 * argc + 1) * sizeof *words);
    const char **attached = malloc((size_t)(argc + 1) * sizeof *attached);
    if (!words || !attached) {
        free(words), free(attached);
        return NULL;
    }
    int n = 0, values = 0;
    for (int k = 0; k < argc; k++) {
        char *eq = strncmp(argv[k], "--", 2) ? NULL : strchr(argv[k], '=');
        if (eq && eq > argv[k] + 2) {
            *eq = '\0'; /* argv's strings are ours to modify */
            words[n++] = argv[k];
            words[n++] = eq + 1;
            attached[values++] = eq + 1;
        } else {
            words[n++] = argv[k];
        }
    }
    words[n] = NULL;
    *out_argc = n;
    cli_attached_values(attached, values);
    return words;
}

/* The command (main without the process): the option fuzzer calls it with cli_parse_only set. */
int gomboc_main(int argc, char **argv)
{
    gb_error_init_gsl();
    gb_integrate_blas_single_thread();
    if (argc < 2) {
        fputs(usage_main, stderr);
        return EXIT_INPUT;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || (!strcmp(argv[1], "help") && argc == 2)) {
        fputs(usage_main, stdout);
        return stdout_written(NULL, 0);
    }
    if (!strcmp(argv[1], "--version")) {
        printf("gomboc %s\n", GOMBOC_VERSION);
        return stdout_written(NULL, 0);
    }
    const int help = !strcmp(argv[1], "help");
    if (help && argc > 3) {
        fprintf(stderr, "gomboc help: one topic at a time (allowed: gomboc help [COMMAND])\n");
        return EXIT_INPUT;
    }
    const char *name = help ? argv[2] : argv[1];
    for (size_t k = 0; k < sizeof commands / sizeof commands[0]; k++)
        if (!strcmp(name, commands[k].name)) {
            if (help) return stdout_written(name, commands[k].run(1, (char *[]){"--help", NULL}));
            cli_install_cleanup();
            int n;
            char **words = split_equals(argc - 2, argv + 2, &n);
            if (!words) {
                fprintf(stderr, "gomboc %s: out of memory\n", name);
                return EXIT_COMPUTE;
            }
            const int status = stdout_written(name, commands[k].run(n, words));
            cli_attached_values(NULL, 0);
            free(words);
            gb_body_release(); /* the bodies of one's own the command made */
            return status;
        }
    if (help) {
        fprintf(stderr, "gomboc help: unknown topic '%s' (allowed:", name);
        for (size_t k = 0; k < sizeof commands / sizeof commands[0]; k++) fprintf(stderr, "%s %s", k ? "," : "", commands[k].name);
        fprintf(stderr, ")\n");
        return EXIT_INPUT;
    }
    fprintf(stderr, "gomboc: unknown command '%s' (allowed:", argv[1]);
    for (size_t k = 0; k < sizeof commands / sizeof commands[0]; k++) fprintf(stderr, "%s %s", k ? "," : "", commands[k].name);
    fprintf(stderr, ")\n\n%s", usage_main);
    return EXIT_INPUT;
}

#ifndef GOMBOC_NO_MAIN
int main(int argc, char **argv) { return gomboc_main(argc, argv); }
#endif
