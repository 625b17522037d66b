/* bad_input — the bad-input gate's row runner, shared by its tables (bad_input.c, bad_input_bodies.c). */
#ifndef VERIFY_BAD_INPUT_H
#define VERIFY_BAD_INPUT_H

#include <stddef.h>

/* `gomboc ARGS` (@CASE@ the row's scene, @D@ its directory) under `env` ("VAR=VALUE ..." or NULL), in a fresh
 * directory with the scene `text` (NULL: none; text_len 0: strlen) and a file `file_name` of `file_text`: 1 when it
 * exits `exit`, says every string of `must`, and leaves the directory as it was. */
int bad_input_row(const char *args, const char *env, const char *text, size_t text_len, const char *file_name,
                  const char *file_text, size_t file_len, int exit, const char *const must[3], char *out, size_t cap);

/* The table's helpers, for the checks of bad_input_processes.c: the binary (an absolute path), `command` run in
 * `dir` with its output (exit status, 124 after 60 s), a file written, a directory removed, a text that changes
 * with anything in a directory, the program's temporaries (".gomboc-*") in it. */
const char *bad_input_binary(void);
int bad_input_run_in(const char *dir, const char *command, char *out, size_t cap);
void bad_input_write_bytes(const char *path, const char *text, size_t len);
char *bad_input_snapshot(const char *dir);
int bad_input_count_temporaries(const char *dir);
/* In a started command's child: SIGHUP, SIGINT, SIGQUIT, SIGTERM at their defaults, none blocked, then `ignored`
 * (0: none) ignored; the dispositions a check depends on, never the harness's. */
void bad_input_child_signals(int ignored);

#endif
