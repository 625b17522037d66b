/* libFuzzer target: the `gomboc` option parser. The input is split at NUL bytes into argv[1..]; the
 * command runs with cli_parse_only set, so it reads and judges every option, output target and scene
 * file it is given, then stops before any computation or output. The exit status must be 0 or 2,
 * never anything else, and nothing may crash. */
#include "gomboc_cli.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    enum { ARGS_MAX = 24 };
    char *text = malloc(size + 1), *argv[ARGS_MAX + 2];
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    int argc = 0;
    argv[argc++] = "gomboc";
    for (size_t start = 0; start <= size && argc <= ARGS_MAX; start += strlen(text + start) + 1) argv[argc++] = text + start;
    argv[argc] = NULL;
    cli_parse_only = 1;
    const int status = gomboc_main(argc, argv);
    if (status != 0 && status != EXIT_INPUT) abort();
    free(text);
    return 0;
}
