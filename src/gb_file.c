/* gb_file — inputs read safely, outputs checked before the work and written as sets (gb_file.h). */
#include "gb_file.h"

#include "gb_error.h"
#include "gb_hash.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

/* ---- inputs ------------------------------------------------------------------------------------- */

/* Open `path` for reading without blocking (a FIFO without a writer, a device), then require a regular
 * file and restore blocking reads: the descriptor, or -1 with the error set. */
static int open_regular(const char *path, const char *noun, const char *allowed, struct stat *st)
{
    const int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) {
        gb_error_set(GB_EINVAL, "%s: cannot open the %s: %s", path, noun, strerror(errno));
        return -1;
    }
    if (fstat(fd, st) != 0 || !S_ISREG(st->st_mode)) {
        close(fd);
        gb_error_set(GB_EINVAL, "%s: not a regular file (allowed: %s)", path, allowed);
        return -1;
    }
    const int flags = fcntl(fd, F_GETFL);
    if (flags < 0 || fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0) {
        close(fd);
        gb_error_set(GB_EIO, "%s: cannot read the %s: %s", path, noun, strerror(errno));
        return -1;
    }
    return fd;
}

int gb_file_read(const char *path, size_t max_bytes, const char *noun, const char *allowed, char **out, size_t *out_size)
{
    *out = NULL, *out_size = 0;
    struct stat st;
    const int fd = open_regular(path, noun, allowed, &st);
    if (fd < 0) return GB_EINVAL;
    if ((unsigned long long)st.st_size > max_bytes) {
        close(fd);
        return gb_error_set(GB_EINVAL, "%s: %lld bytes (allowed: a %s of at most %zu bytes)", path, (long long)st.st_size,
                            noun, max_bytes);
    }
    char *text = malloc((size_t)st.st_size + 2);
    if (!text) {
        close(fd);
        return gb_error_set(GB_ENOMEM, "%s: out of memory for %lld bytes", path, (long long)st.st_size);
    }
    size_t size = 0;
    for (;;) {
        const ssize_t got = read(fd, text + size, (size_t)st.st_size + 1 - size);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) {
            const int err = errno;
            free(text);
            close(fd);
            return gb_error_set(GB_EIO, "%s: cannot read the %s: %s", path, noun, strerror(err));
        }
        if (got == 0) break;
        size += (size_t)got;
        if (size > (size_t)st.st_size) break; /* grew while read: at most the limit is read */
    }
    close(fd);
    if (size > max_bytes) {
        free(text);
        return gb_error_set(GB_EINVAL, "%s: more than %zu bytes (allowed: a %s of at most %zu bytes)", path, max_bytes,
                            noun, max_bytes);
    }
    text[size] = '\0';
    *out = text, *out_size = size;
    return GB_OK;
}

int gb_file_digest(const char *path, uint64_t *bytes, uint64_t *checksum)
{
    struct stat st;
    const int fd = open_regular(path, "file", "a regular file", &st);
    if (fd < 0) return GB_EIO;
    uint64_t hash = GB_HASH_OFFSET, total = 0;
    unsigned char buffer[1 << 16];
    for (;;) {
        const ssize_t got = read(fd, buffer, sizeof buffer);
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) {
            const int err = errno;
            close(fd);
            return gb_error_set(GB_EIO, "cannot read '%s': %s", path, strerror(err));
        }
        if (got == 0) break;
        hash = gb_hash_add(hash, buffer, (size_t)got);
        total += (uint64_t)got;
    }
    close(fd);
    *bytes = total, *checksum = hash;
    return GB_OK;
}

/* ---- the rule for outputs ----------------------------------------------------------------------- */

static const char *const output_allowed =
    " (allowed: a new or regular file in an existing, writable directory, not an input or another output of this run)";

/* The directory part of `path` ("." when it has none), malloc'd. */
static char *directory_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash) return strdup(".");
    if (slash == path) return strdup("/");
    return strndup(path, (size_t)(slash - path));
}

/* What names a file: an existing one by its device and inode; one still to be created by its
 * directory's device and inode and its own name. */
typedef struct identity {
    int exists, known;
    dev_t dev;
    ino_t ino;
    const char *name;
} identity;

static identity identity_of(const char *path)
{
    identity id = {0};
    struct stat st;
    if (stat(path, &st) == 0) {
        id.exists = id.known = 1, id.dev = st.st_dev, id.ino = st.st_ino;
        return id;
    }
    char *dir = directory_of(path);
    if (dir && stat(dir, &st) == 0) {
        const char *slash = strrchr(path, '/');
        id.known = 1, id.dev = st.st_dev, id.ino = st.st_ino, id.name = slash ? slash + 1 : path;
    }
    free(dir);
    return id;
}

static int same_file(const identity *a, const identity *b)
{
    if (!a->known || !b->known || a->exists != b->exists || a->dev != b->dev || a->ino != b->ino) return 0;
    return a->exists || strcmp(a->name, b->name) == 0;
}

int gb_file_reserved_name(const char *name) { return strncmp(name, ".gomboc-", 8) == 0; }

/* An existing cache: does it start with its kind's magic? */
static int holds_magic(const gb_file_use *u)
{
    struct stat st;
    const int fd = open_regular(u->path, u->kind, "a regular file", &st);
    if (fd < 0) {
        gb_error_clear();
        return 0;
    }
    unsigned char head[64];
    const ssize_t got = u->magic_size <= sizeof head ? read(fd, head, u->magic_size) : -1;
    close(fd);
    return got == (ssize_t)u->magic_size && !memcmp(head, u->magic, u->magic_size);
}

static int check_output(const gb_file_use *u)
{
    if (!u->path[0]) return gb_error_set(GB_EINVAL, "%s '' is empty%s", u->what, output_allowed);
    const char *slash = strrchr(u->path, '/'), *base = slash ? slash + 1 : u->path;
    if (gb_file_reserved_name(base))
        return gb_error_set(GB_EINVAL, "%s '%s' is named like a temporary of this program ('.gomboc-...'), which a later "
                            "run may remove%s", u->what, u->path, output_allowed);
    char *dir = directory_of(u->path);
    if (!dir) return gb_error_set(GB_ENOMEM, "%s '%s': out of memory", u->what, u->path);
    struct stat st;
    int status = GB_OK;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode))
        status = gb_error_set(GB_EINVAL, "%s '%s': its directory does not exist%s", u->what, u->path, output_allowed);
    else if (access(dir, W_OK | X_OK) != 0)
        status = gb_error_set(GB_EINVAL, "%s '%s': its directory is not writable%s", u->what, u->path, output_allowed);
    else if (lstat(u->path, &st) == 0 && !S_ISREG(st.st_mode))
        status = gb_error_set(GB_EINVAL, "%s '%s' exists and is not a regular file (a directory, link, device or FIFO)%s",
                              u->what, u->path, output_allowed);
    else if ((u->role & GB_FILE_CACHE) && lstat(u->path, &st) == 0 && !holds_magic(u))
        status = gb_error_set(GB_EINVAL, "%s '%s' exists and is not %s (it lacks the first bytes every one has): it is left "
                              "alone (allowed: a new file, or %s this command wrote)", u->what, u->path, u->kind, u->kind);
    free(dir);
    return status;
}

int gb_file_check(const gb_file_use *uses, size_t count)
{
    for (size_t k = 0; k < count; k++) /* its own path first (an empty one cannot be compared) */
        if (uses[k].path && (uses[k].role & GB_FILE_OUTPUT) && !uses[k].path[0]) return check_output(&uses[k]);
    /* Each pair once, the later use named first (inputs come first in a command's list); a name the run
     * sweeps (SWEPT) is compared with every other use. A file that is two uses at once is said first,
     * before what either use makes of it. */
    for (size_t j = 0; j < count; j++) {
        if (!uses[j].path) continue;
        const identity later = identity_of(uses[j].path);
        for (size_t k = 0; k < j; k++) {
            if (!uses[k].path || !((uses[j].role | uses[k].role) & (GB_FILE_OUTPUT | GB_FILE_SWEPT))) continue;
            const identity earlier = identity_of(uses[k].path);
            if (!same_file(&later, &earlier)) continue;
            const gb_file_use *named = &uses[j], *other = &uses[k];
            if (named->role & GB_FILE_SWEPT) named = &uses[k], other = &uses[j];
            return gb_error_set(GB_EINVAL, "%s '%s' is also the %s file '%s'%s%s", named->what, named->path, other->what,
                                other->path, other->role & GB_FILE_SWEPT ? " (a name this run removes as a stale output "
                                "of an earlier run)" : "", output_allowed);
        }
    }
    for (size_t k = 0; k < count; k++)
        if (uses[k].path && (uses[k].role & GB_FILE_OUTPUT)) {
            const int status = check_output(&uses[k]);
            if (status) return status;
        }
    return GB_OK;
}

/* ---- locks -------------------------------------------------------------------------------------- */

static double lock_seconds(void)
{
    const char *text = getenv("GOMBOC_LOCK_SECONDS");
    char *end;
    const double s = text ? strtod(text, &end) : NAN;
    return text && end != text && !*end && s >= 0.0 && s <= 86400.0 ? s : GB_FILE_LOCK_SECONDS;
}

static double monotonic_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int gb_file_lock(const char *path, const char *what, int *fd)
{
    *fd = -1;
    char *dir = directory_of(path);
    if (!dir) return gb_error_set(GB_ENOMEM, "out of memory for a directory name");
    const int d = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (d < 0) {
        free(dir);
        return GB_OK; /* not lockable here: written as by a single writer */
    }
    const double limit = lock_seconds(), start = monotonic_seconds();
    for (;;) {
        if (flock(d, LOCK_EX | LOCK_NB) == 0) {
            free(dir);
            *fd = d;
            return GB_OK;
        }
        if (errno != EWOULDBLOCK && errno != EINTR) { /* no locks on this file system */
            close(d);
            free(dir);
            return GB_OK;
        }
        if (monotonic_seconds() - start >= limit) {
            close(d);
            char *whole = realpath(dir, NULL); /* named whole: "." says nothing in a message */
            const int status = gb_error_set(GB_EIO, "the directory '%s' stayed locked for %g s while %s: another gomboc "
                                            "writes there (one stopped with Ctrl-Z holds the lock until it goes on) "
                                            "(allowed: a wait of GOMBOC_LOCK_SECONDS = %g s, 0 to 86400)",
                                            whole ? whole : dir, limit, what, limit);
            free(whole);
            free(dir);
            return status;
        }
        nanosleep(&(struct timespec){0, 10000000}, NULL); /* 10 ms */
    }
}

void gb_file_unlock(int fd)
{
    if (fd < 0) return;
    flock(fd, LOCK_UN);
    close(fd);
}

int gb_file_check_directory(const char *dir, const char *what)
{
    static const char *const allowed = " (allowed: an existing, writable directory)";
    struct stat st;
    if (stat(dir, &st) != 0) return gb_error_set(GB_EINVAL, "%s '%s' does not exist%s", what, dir, allowed);
    if (!S_ISDIR(st.st_mode)) return gb_error_set(GB_EINVAL, "%s '%s' is not a directory%s", what, dir, allowed);
    if (access(dir, W_OK | X_OK) != 0) return gb_error_set(GB_EINVAL, "%s '%s' is not writable%s", what, dir, allowed);
    return GB_OK;
}

/* ---- sets ----------------------------------------------------------------------------------------- */

/* The temporaries of this process, for the signal handler: a slot is filled before the count grows. */
enum { TEMP_MAX = 16 };
static char *volatile temp_paths[TEMP_MAX];
static volatile sig_atomic_t temp_count;

void gb_file_remove_temporaries(void)
{
    for (sig_atomic_t k = 0; k < temp_count; k++)
        if (temp_paths[k]) unlink(temp_paths[k]);
}

static void temp_forget(const char *path)
{
    for (sig_atomic_t k = 0; k < temp_count; k++)
        if (temp_paths[k] == path) temp_paths[k] = NULL;
}

/* Remove the temporaries ".gomboc-PID-XXXXXX" in `dir` whose writers are gone: those whose lock can be
 * taken (a live writer holds it from the moment it made the file to the moment it renames or removes
 * it, on this machine or another, in this PID namespace or another). A regular file of that name whose
 * lock cannot be tested (no locks on this file system) is left. */
static void sweep_stale_temporaries(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    for (struct dirent *e; (e = readdir(d));) {
        long pid;
        char tail[8];
        int used = 0;
        if (sscanf(e->d_name, ".gomboc-%ld-%6[A-Za-z0-9]%n", &pid, tail, &used) != 2 || e->d_name[used] != '\0' ||
            strlen(tail) != 6)
            continue;
        char *path = malloc(strlen(dir) + strlen(e->d_name) + 2);
        if (!path) break;
        sprintf(path, "%s/%s", dir, e->d_name);
        const int fd = open(path, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
        struct stat held, named;
        if (fd >= 0 && fstat(fd, &held) == 0 && S_ISREG(held.st_mode) && flock(fd, LOCK_EX | LOCK_NB) == 0 &&
            lstat(path, &named) == 0 && named.st_dev == held.st_dev && named.st_ino == held.st_ino)
            unlink(path); /* its writer is gone; one that made it an instant ago finds it unlinked and makes another */
        if (fd >= 0) close(fd);
        free(path);
    }
    closedir(d);
}

/* A new temporary beside `dir`'s members, locked: its descriptor (its path in tmp), or -1 with errno. */
static int temporary_create(const char *dir, char *tmp, int *lock_fd)
{
    for (int attempt = 0; attempt < 16; attempt++) {
        sprintf(tmp, "%s/.gomboc-%ld-XXXXXX", dir, (long)getpid());
        const int fd = mkostemp(tmp, O_CLOEXEC); /* O_CREAT | O_EXCL: a new file, never a link's target */
        if (fd < 0) return -1;
        int locked;
        while (!(locked = flock(fd, LOCK_EX) == 0) && errno == EINTR) continue;
        struct stat st;
        if (locked && fstat(fd, &st) == 0 && st.st_nlink == 0) { /* swept between mkstemp and flock */
            close(fd);
            continue;
        }
        *lock_fd = locked ? dup(fd) : -1; /* the lock lives while this descriptor does (fclose closes fd) */
        if (locked && *lock_fd < 0) {
            const int err = errno;
            close(fd);
            unlink(tmp);
            errno = err;
            return -1;
        }
        return fd;
    }
    errno = EAGAIN;
    return -1;
}

FILE *gb_file_set_open(gb_file_set *set, const char *path, int *status)
{
    if (*status) return NULL;
    sig_atomic_t slot = 0; /* for the signal handler: one a committed set has freed, or a new one */
    while (slot < temp_count && temp_paths[slot]) slot++;
    if (set->count == GB_FILE_SET_MAX || slot == TEMP_MAX) {
        *status = gb_error_set(GB_ENOMEM, "too many output files at once (at most %d)", GB_FILE_SET_MAX);
        return NULL;
    }
    struct stat st;
    if (lstat(path, &st) == 0 && !S_ISREG(st.st_mode)) {
        *status = gb_error_set(GB_EIO, "cannot write '%s': it exists and is not a regular file", path);
        return NULL;
    }
    gb_file_member *m = &set->member[set->count];
    memset(m, 0, sizeof *m);
    m->lock_fd = -1;
    char *dir = directory_of(path);
    m->path = strdup(path);
    m->tmp = dir ? malloc(strlen(dir) + 40) : NULL;
    if (!dir || !m->path || !m->tmp) {
        free(dir), free(m->path), free(m->tmp);
        *status = gb_error_set(GB_ENOMEM, "out of memory for the output '%s'", path);
        return NULL;
    }
    sweep_stale_temporaries(dir);
    const int fd = temporary_create(dir, m->tmp, &m->lock_fd);
    free(dir);
    if (fd >= 0) {
        temp_paths[slot] = m->tmp;
        if (slot == temp_count) temp_count = temp_count + 1;
        const mode_t mask = umask(0);
        umask(mask);
        fchmod(fd, 0666 & ~mask); /* what fopen would have made */
        m->file = fdopen(fd, "w");
        if (!m->file) close(fd), unlink(m->tmp);
    }
    if (!m->file) {
        *status = gb_error_set(GB_EIO, "cannot write '%s': %s", path, strerror(errno));
        temp_forget(m->tmp);
        if (m->lock_fd >= 0) close(m->lock_fd);
        free(m->path), free(m->tmp);
        return NULL;
    }
    set->count++;
    return m->file;
}

int gb_file_set_seal(gb_file_set *set, int index)
{
    gb_file_member *m = &set->member[index];
    if (m->sealed) return GB_OK;
    m->sealed = 1;
    errno = 0;
    const int failed = ferror(m->file) | fclose(m->file);
    m->file = NULL;
    if (failed) return gb_error_set(GB_EIO, "cannot write '%s': %s", m->path, strerror(errno ? errno : EIO));
    return gb_file_digest(m->tmp, &m->bytes, &m->checksum);
}

int gb_file_set_commit(gb_file_set *set, int status)
{
    for (int k = 0; k < set->count; k++) {
        gb_file_member *m = &set->member[k];
        if (m->sealed) continue;
        if (status) {
            fclose(m->file);
            m->file = NULL;
            continue;
        }
        status = gb_file_set_seal(set, k);
    }
    /* The directory's lock over the renames: two sets of one directory are renamed one after the other. */
    int lock = -1;
    if (!status && set->count && !set->directory_locked)
        status = gb_file_lock(set->member[set->count - 1].path, "renaming a finished set of outputs into place", &lock);
    int renamed = 0; /* members [0, renamed) are in place */
    for (; !status && renamed < set->count; renamed++) {
        gb_file_member *m = &set->member[renamed];
        struct stat st;
        if (lstat(m->path, &st) == 0 && !S_ISREG(st.st_mode)) /* appeared during the run */
            status = gb_error_set(GB_EIO, "cannot write '%s': it is no longer a regular file", m->path);
        else if (rename(m->tmp, m->path) != 0)
            status = gb_error_set(GB_EIO, "cannot write '%s': %s", m->path, strerror(errno));
        if (status) break;
    }
    for (int k = 0; k < set->count; k++) {
        gb_file_member *m = &set->member[k];
        if (status) {
            unlink(m->tmp);
            if (k < renamed) unlink(m->path); /* the set would be mixed */
        }
        if (m->lock_fd >= 0) close(m->lock_fd);
        temp_forget(m->tmp);
        free(m->path);
        free(m->tmp);
    }
    gb_file_unlock(lock);
    set->count = 0;
    return status;
}

int gb_file_write_atomically(const char *path, const void *bytes, size_t size)
{
    gb_file_set set = {0};
    int status = GB_OK;
    FILE *f = gb_file_set_open(&set, path, &status);
    if (f && size && fwrite(bytes, 1, size, f) != size)
        status = gb_error_set(GB_EIO, "cannot write '%s': %s", path, strerror(errno));
    return gb_file_set_commit(&set, status);
}

int gb_file_write_new(const char *path, const void *bytes, size_t size)
{
    gb_file_set set = {0};
    int status = GB_OK;
    FILE *f = gb_file_set_open(&set, path, &status);
    if (!f) return status;
    gb_file_member *m = &set.member[0];
    if (size && fwrite(bytes, 1, size, f) != size) status = gb_error_set(GB_EIO, "cannot write '%s': %s", path, strerror(errno));
    if (!status) status = gb_file_set_seal(&set, 0);
    if (!status && link(m->tmp, path) != 0)
        status = errno == EEXIST ? gb_error_set(GB_EINVAL, "'%s' exists already (allowed: a new file)", path)
                                 : gb_error_set(GB_EIO, "cannot write '%s': %s", path, strerror(errno));
    /* the temporary goes either way (a failed commit removes it): linked, the file stands under its name;
     * else nothing was written */
    gb_file_set_commit(&set, GB_EIO);
    return status;
}
