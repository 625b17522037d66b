/* gomboc — the command. Subcommands map onto the library's modules; options are parsed strictly
 * (an unknown or malformed option is an error naming it and its allowed form). Exit status: 0 on
 * success, 2 for bad input, 1 when a computation fails or its output cannot be written (standard
 * output included). */
#include "gomboc_cli.h"

#include "gb_error.h"

#include <errno.h>
#include <stdio.h>
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
    "\n"
    "'gomboc <command> --help' describes each command's options.\n";

static const struct {
    const char *name;
    int (*run)(int argc, char **argv);
} commands[] = {{"shape", command_shape}, {"contact", command_contact}, {"run", command_run}, {"lyapunov", command_lyapunov},
                {"scan", command_scan}, {"melnikov", command_melnikov}, {"check", command_check}};

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

/* The command (main without the process): the option fuzzer calls it with cli_parse_only set. */
int gomboc_main(int argc, char **argv)
{
    gb_error_init_gsl();
    if (argc < 2) {
        fputs(usage_main, stderr);
        return EXIT_INPUT;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
        fputs(usage_main, stdout);
        return stdout_written(NULL, 0);
    }
    for (size_t k = 0; k < sizeof commands / sizeof commands[0]; k++)
        if (!strcmp(argv[1], commands[k].name)) {
            cli_install_cleanup();
            return stdout_written(argv[1], commands[k].run(argc - 2, argv + 2));
        }
    fprintf(stderr, "gomboc: unknown command '%s' (allowed:", argv[1]);
    for (size_t k = 0; k < sizeof commands / sizeof commands[0]; k++) fprintf(stderr, "%s %s", k ? "," : "", commands[k].name);
    fprintf(stderr, ")\n\n%s", usage_main);
    return EXIT_INPUT;
}

#ifndef GOMBOC_NO_MAIN
int main(int argc, char **argv) { return gomboc_main(argc, argv); }
#endif
