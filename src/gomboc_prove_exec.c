/* gomboc prove in its own program. The proofs' ball arithmetic — Arb, FLINT and NTL under it, and C++'s library under
 * NTL — makes 17 000 of the 22 000 symbol relocations a process of the command would otherwise make at every start
 * (8 of the 14 ms `gomboc --version` took). So gomboc is linked without the proofs (and, --as-needed, without those
 * libraries), and `gomboc prove` runs gomboc-prove — the command with the proofs linked in — from gomboc's own
 * directory, with the words the command was given. Where the proofs are linked into this program (gomboc-prove itself, the
 * option fuzzer, gomboc-mpi) the weak reference finds them and they run here. */
#include "gomboc_cli.h"

#include <errno.h>
#include <limits.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#pragma weak command_prove_in_process

int command_prove(int argc, char **argv)
{
    if (command_prove_in_process) return command_prove_in_process(argc, argv);
    char self[PATH_MAX], helper[PATH_MAX + 16];
    const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    char **words = malloc((size_t)(argc + 3) * sizeof *words);
    if (n <= 0 || !words) {
        fprintf(stderr, "gomboc prove: cannot find gomboc's own directory: %s (allowed: gomboc-prove installed beside gomboc)\n",
                strerror(errno ? errno : ENOENT));
        free(words);
        return EXIT_COMPUTE;
    }
    self[n] = '\0';
    char *slash = strrchr(self, '/');
    if (slash) *slash = '\0';
    snprintf(helper, sizeof helper, "%s/gomboc-prove", slash ? self : ".");
    /* the command's words as its parser gets them ("--name=value" already split in two), after "gomboc prove";
     * argv[0] stays "gomboc": its messages name the command the user typed */
    words[0] = (char *)"gomboc", words[1] = (char *)"prove";
    for (int k = 0; k < argc; k++) words[k + 2] = argv[k];
    words[argc + 2] = NULL;
    fflush(stdout), fflush(stderr);
    execv(helper, words);
    fprintf(stderr, "gomboc prove: cannot run %s: %s (allowed: gomboc-prove installed beside gomboc)\n", helper, strerror(errno));
    free(words);
    return EXIT_COMPUTE;
}
