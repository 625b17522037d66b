/* gomboc — the command. Subcommands map onto the library's modules; options are parsed strictly
 * (an unknown or malformed option is an error naming it and its allowed form). Exit status: 0 on
 * success, 2 for bad input, 1 when a computation fails. */
#include "gomboc_cli.h"

#include "gb_error.h"

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
    "\n"
    "'gomboc <command> --help' describes each command's options.\n";

static const struct {
    const char *name;
    int (*run)(int argc, char **argv);
} commands[] = {{"shape", command_shape}, {"contact", command_contact}, {"run", command_run}, {"lyapunov", command_lyapunov}};

int main(int argc, char **argv)
{
    gb_error_init_gsl();
    if (argc < 2) {
        fputs(usage_main, stderr);
        return EXIT_INPUT;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h")) {
        fputs(usage_main, stdout);
        return 0;
    }
    for (size_t k = 0; k < sizeof commands / sizeof commands[0]; k++)
        if (!strcmp(argv[1], commands[k].name)) return commands[k].run(argc - 2, argv + 2);
    fprintf(stderr, "gomboc: unknown command '%s' (allowed: shape, contact, run, lyapunov)\n\n%s", argv[1], usage_main);
    return EXIT_INPUT;
}
