/* bad_input — the bad-input gate's row runner, shared by its tables (bad_input.c, bad_input_bodies.c). */
#ifndef VERIFY_BAD_INPUT_H
#define VERIFY_BAD_INPUT_H

#include <stddef.h>

/* `gomboc ARGS` (@CASE@ the row's scene, @D@ its directory) under `env` ("VAR=VALUE ..." or NULL), in a fresh
 * directory with the scene `text` (NULL: none; text_len 0: strlen) and a file `file_name` of `file_text`: 1 when it
 * exits `exit`, says every string of `must`, and leaves the directory as it was. */
int bad_input_row(const char *args, const char *env, const char *text, size_t text_len, const char *file_name,
                  const char *file_text, size_t file_len, int exit, const char *const must[3], char *out, size_t cap);

#endif
