/* gb_file — every file the library and the command read or write, under one rule.
 *
 * Inputs are opened without blocking (a FIFO or a device never hangs a run), checked to be regular
 * files, held to a size limit, then read whole.
 *
 * Outputs are judged before any computation (gb_file_check): an output is never an input of the same
 * run nor another output of it (device and inode compared, not names), never an existing directory,
 * link, device or FIFO, and its directory exists and is writable. A message names the option, the path
 * and the allowed range.
 *
 * Outputs are then written as a set (gb_file_set): each member to its own temporary
 * ".gomboc-PID-XXXXXX" created beside it with O_EXCL (mkstemp: a unique name, no link followed), and
 * only when the whole set is written are the members renamed into place, in the order they were
 * opened. rename() is the only visible step. A set whose last member is a manifest (the run summary, the
 * scan JSON) records every other member's size and FNV-1a 64 checksum (gb_file_set_seal), so that a
 * set mixed by a kill between two renames is detectable (`gomboc check`). Temporaries are removed on
 * failure, by gb_file_remove_temporaries (async-signal-safe, for a signal handler), and, when a process
 * died outright, by the next set written to the same directory. */
#ifndef GB_FILE_H
#define GB_FILE_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Read the regular file `path` whole into a malloc'd, NUL-terminated buffer of at most max_bytes
 * (plus the NUL). `noun` names it in messages ("case file"), `allowed` says what is allowed. GB_EINVAL
 * for a path that is not a readable regular file or is too large, GB_EIO for a failed read. */
int gb_file_read(const char *path, size_t max_bytes, const char *noun, const char *allowed, char **text, size_t *size);

/* How a run uses a path. */
enum { GB_FILE_INPUT = 1, GB_FILE_OUTPUT = 2 };
typedef struct gb_file_use {
    const char *path; /* NULL: not used by this run */
    const char *what; /* how the user named it: "--atlas", "CASE", "[scan] base" */
    int role;         /* GB_FILE_INPUT, GB_FILE_OUTPUT, or both (a file read, then written back) */
} gb_file_use;

/* The rule, before any work: every output is a new or regular file in an existing writable directory,
 * and no two uses name the same file (an output that is also the input of the same use is allowed:
 * the atlas read and written back). GB_EINVAL with "WHAT 'PATH' ... (allowed: ...)", or GB_OK. */
int gb_file_check(const gb_file_use *uses, size_t count);

/* --out DIR: an existing, writable directory. GB_EINVAL with "WHAT 'DIR' ... (allowed: ...)". */
int gb_file_check_directory(const char *dir, const char *what);

enum { GB_FILE_SET_MAX = 8 };
typedef struct gb_file_member {
    char *path, *tmp;
    FILE *file;
    int sealed;
    uint64_t bytes, checksum; /* of the sealed content */
} gb_file_member;
typedef struct gb_file_set {
    gb_file_member member[GB_FILE_SET_MAX];
    int count;
} gb_file_set;

/* A new member, open for writing (NULL with *status set on failure; nothing when *status is already
 * non-zero). The path is checked again (a non-regular file that appeared since gb_file_check is
 * refused). */
FILE *gb_file_set_open(gb_file_set *set, const char *path, int *status);

/* Close member `index` and record its size and checksum (for the manifest). gb_ status. */
int gb_file_set_seal(gb_file_set *set, int index);

/* With status GB_OK, seal what is open and rename every member into place in order; otherwise, or
 * when a write, a close or a rename fails, remove the temporaries and the members already renamed.
 * Returns the final status. The set is empty afterwards. */
int gb_file_set_commit(gb_file_set *set, int status);

/* Write `size` bytes as a set of one. */
int gb_file_write_atomically(const char *path, const void *bytes, size_t size);

/* The size and FNV-1a 64 checksum of a file as it is now: GB_OK, or GB_EIO when it cannot be read. */
int gb_file_digest(const char *path, uint64_t *bytes, uint64_t *checksum);

/* Remove every temporary of this process (async-signal-safe). */
void gb_file_remove_temporaries(void);

#ifdef __cplusplus
}
#endif

#endif
