/* gb_file — every file the library and the command read or write, under one rule.
 *
 * Inputs are opened without blocking (a FIFO or a device never hangs a run), checked to be regular
 * files, held to a size limit, then read whole.
 *
 * Outputs are judged before any computation (gb_file_check): an output is never an input of the same
 * run nor another output of it, nor a file the run removes as a stale output of an earlier run (device
 * and inode compared, not names); never an existing directory, link, device or FIFO; never a name of
 * the program's own temporaries (".gomboc-*"); and its directory exists and is writable. A cache (the
 * hull, the atlas: read, then written back) is replaced only when it holds a cache of its kind: an
 * existing file without the kind's magic bytes is some other file, and is refused. A message names the
 * option, the path and the allowed range.
 *
 * Outputs are then written as a set (gb_file_set): each member to its own temporary
 * ".gomboc-PID-XXXXXX" created beside it with O_EXCL (mkstemp: a unique name, no link followed) and
 * locked (flock) by its writer at once and until it is renamed or removed; only
 * when the whole set is written are the members renamed into place, in the order they were opened,
 * with the directory locked (gb_file_lock) so that two sets written to one directory at once are never
 * mixed. rename() is the only visible step. A set whose last member is a manifest (the run summary, the
 * scan JSON) records every other member's size and FNV-1a 64 checksum (gb_file_set_seal), so that a
 * set mixed by a kill between two renames is detectable (`gomboc check`).
 *
 * Temporaries are removed on failure, by gb_file_remove_temporaries (async-signal-safe, for a signal
 * handler), and, when their writer died outright, by the next set written to the same directory: a
 * temporary is removed only when its lock can be taken, which proves its writer gone whatever machine or
 * PID namespace it ran in (its PID is never judged). A writer finds its temporary removed in the instant
 * between creating and locking it (the link count is 0) and makes another.
 *
 * Every lock waits a bounded time (GB_FILE_LOCK_SECONDS, or $GOMBOC_LOCK_SECONDS), then fails naming
 * the directory and what holds it. A directory that cannot be locked at all (NFS without lock support)
 * is written without the lock, as a single writer would. */
#ifndef GB_FILE_H
#define GB_FILE_H

#include "gb_export.h"

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Read the regular file `path` whole into a malloc'd, NUL-terminated buffer of at most max_bytes
 * (plus the NUL). `noun` names it in messages ("case file"), `allowed` says what is allowed. GB_EINVAL
 * for a path that is not a readable regular file or is too large, GB_EIO for a failed read. */
GB_API int gb_file_read(const char *path, size_t max_bytes, const char *noun, const char *allowed, char **text,
                        size_t *size);

/* How a run uses a path. */
enum {
    GB_FILE_INPUT = 1,  /* read */
    GB_FILE_OUTPUT = 2, /* written (replaced) */
    GB_FILE_CACHE = 4,  /* with INPUT | OUTPUT: read when it is a cache of its kind, and written back */
    GB_FILE_SWEPT = 8   /* removed when present (a stale output of an earlier run): no other use may name it */
};
typedef struct gb_file_use {
    const char *path;  /* NULL: not used by this run */
    const char *what;  /* how the user named it: "--atlas", "CASE", "[scan] base" */
    int role;          /* GB_FILE_* */
    const char *kind;  /* GB_FILE_CACHE: what a cache of this kind is called ("a hull file") */
    const void *magic; /* GB_FILE_CACHE: the first bytes of every cache of this kind */
    size_t magic_size;
} gb_file_use;

/* A use by its path, name and role; a cache with its kind and magic. */
#define GB_FILE_USE(path_, what_, role_) ((gb_file_use){.path = (path_), .what = (what_), .role = (role_)})
#define GB_FILE_CACHE_USE(path_, what_, kind_, magic_, magic_size_)                                                \
    ((gb_file_use){.path = (path_), .what = (what_), .role = GB_FILE_INPUT | GB_FILE_OUTPUT | GB_FILE_CACHE,        \
                   .kind = (kind_), .magic = (magic_), .magic_size = (magic_size_)})

/* The rule, before any work: every output is a new or regular file in an existing writable directory,
 * not named like a temporary of this program; a cache that exists starts with its kind's magic; and no
 * two uses name the same file (an output that is also the input of the same use is allowed: the atlas
 * read and written back). GB_EINVAL with "WHAT 'PATH' ... (allowed: ...)", or GB_OK. */
GB_API int gb_file_check(const gb_file_use *uses, size_t count);

/* Is `name` (a base name) one of the program's temporaries, ".gomboc-" followed by anything? */
GB_API int gb_file_reserved_name(const char *name);

/* The lock of the directory that holds `path`: an exclusive flock on the directory, waited for at most
 * GB_FILE_LOCK_SECONDS (or $GOMBOC_LOCK_SECONDS). *fd is the lock to give to gb_file_unlock (-1 when the directory could not be
 * locked at all, which is not an error). GB_EIO after the wait, naming the directory and `what` it was
 * to be locked for. */
GB_API int gb_file_lock(const char *path, const char *what, int *fd);
GB_API void gb_file_unlock(int fd);
/* GB_FILE_LOCK_SECONDS, or $GOMBOC_LOCK_SECONDS when it is a number from 0 to 86400. */
#define GB_FILE_LOCK_SECONDS 60.0

/* --out DIR: an existing, writable directory. GB_EINVAL with "WHAT 'DIR' ... (allowed: ...)". */
GB_API int gb_file_check_directory(const char *dir, const char *what);

enum { GB_FILE_SET_MAX = 8 };
typedef struct gb_file_member {
    char *path, *tmp;
    FILE *file;
    int lock_fd;              /* the temporary's lock, held until it is renamed or removed */
    int sealed;
    uint64_t bytes, checksum; /* of the sealed content */
} gb_file_member;
typedef struct gb_file_set {
    gb_file_member member[GB_FILE_SET_MAX];
    int count;
    int directory_locked; /* the caller holds the lock of the members' directory (gb_file_lock): commit
                           * does not take it again */
} gb_file_set;

/* A new member, open for writing (NULL with *status set on failure; nothing when *status is already
 * non-zero). The path is checked again (a non-regular file that appeared since gb_file_check is
 * refused). */
GB_API FILE *gb_file_set_open(gb_file_set *set, const char *path, int *status);

/* Close member `index` and record its size and checksum (for the manifest). gb_ status. */
GB_API int gb_file_set_seal(gb_file_set *set, int index);

/* With status GB_OK, seal what is open and rename every member into place in order, the directory of
 * the last member locked; otherwise, or when a write, a close, the lock or a rename fails, remove the
 * temporaries and the members already renamed. Returns the final status. The set is empty afterwards. */
GB_API int gb_file_set_commit(gb_file_set *set, int status);

/* Write `size` bytes as a set of one. */
GB_API int gb_file_write_atomically(const char *path, const void *bytes, size_t size);
/* Write `size` bytes to `path` only if it does not exist yet: whole under a temporary, then linked to its
 * name (link fails where the name exists), so that the file never stands there half written and never
 * replaces another. GB_EINVAL when `path` exists, GB_EIO when the write fails. */
GB_API int gb_file_write_new(const char *path, const void *bytes, size_t size);

/* The size and FNV-1a 64 checksum of a file as it is now: GB_OK, or GB_EIO when it cannot be read. */
GB_API int gb_file_digest(const char *path, uint64_t *bytes, uint64_t *checksum);

/* Remove every temporary of this process (async-signal-safe). */
GB_API void gb_file_remove_temporaries(void);

#ifdef __cplusplus
}
#endif

#endif
