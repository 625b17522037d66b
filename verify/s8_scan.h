/* What the scan checks share (verify/s8_scan*.c, s8_ensembles.c): the command, a scene file like a user's, and a
 * fresh directory with a base scene and a 3 x 3 scan of it. */
#ifndef S8_SCAN_H
#define S8_SCAN_H

#include "gb_check.h"

#include <cjson/cJSON.h>
#include <stddef.h>

/* $GOMBOC_BIN (else build/gomboc), and `gomboc ARGS` into out (the exit status). */
const char *s8_binary(void);
int s8_run(const char *args, char *out, size_t cap);
/* Write `text` to `path`: 0, or 1 on failure. */
int s8_spill(const char *path, const char *text);
/* A scene file with every key the comparisons need (history as asked, Table 1's forcing but ω and A2). */
void s8_scene_text(char *out, size_t size, double omega, double a2, double periods, int transient, int history);
/* o[a][b] as a number (NAN when missing). */
double s8_number_at(const cJSON *o, const char *a, const char *b);

typedef struct s8_scan_dir {
    char path[GB_CHECK_TEMPDIR_SIZE], scan[200], csv[200], journal[200];
} s8_scan_dir;
enum { SCAN_POINTS = 9 };

/* A fresh directory with the base scene and the scan file; on failure `check` fails and 1 returns. */
int s8_make_scan_dir(s8_scan_dir *d, const gb_check *check);
/* `gomboc scan` of the directory's scan file into it, with `extra` options; the exit status. */
int s8_scan_run(const s8_scan_dir *d, const char *extra, char *out, size_t cap);
void s8_remove_scan_dir(const s8_scan_dir *d);

#endif
