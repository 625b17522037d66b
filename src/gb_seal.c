/* gb_seal — keyed BLAKE2b-256 over what the program trusts on reading (gb_seal.h). */
#include "gb_seal.h"

#include "gb_error.h"

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <sodium.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static pthread_once_t key_once = PTHREAD_ONCE_INIT;
static unsigned char key[crypto_generichash_KEYBYTES];
static int key_status = GB_OK;
static char key_message[4096 + 1024]; /* the key file's path (up to 4096 bytes) and what is wrong */
static char key_file[4096];

/* The key file's path: $GOMBOC_KEY, $XDG_CONFIG_HOME/gomboc/key or $HOME/.config/gomboc/key. */
static void resolve_path(void)
{
    const char *explicit = getenv("GOMBOC_KEY"), *config = getenv("XDG_CONFIG_HOME"), *home = getenv("HOME");
    if (explicit && explicit[0]) snprintf(key_file, sizeof key_file, "%s", explicit);
    else if (config && config[0] == '/') snprintf(key_file, sizeof key_file, "%s/gomboc/key", config);
    else if (home && home[0] == '/') snprintf(key_file, sizeof key_file, "%s/.config/gomboc/key", home);
    else key_file[0] = '\0';
}

/* mkdir -p of the key file's directory, each new directory private (0700). */
static int make_directory_of(const char *path)
{
    char dir[sizeof key_file];
    snprintf(dir, sizeof dir, "%s", path);
    char *slash = strrchr(dir, '/');
    if (!slash || slash == dir) return 0;
    *slash = '\0';
    for (char *p = dir + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            if (mkdir(dir, 0700) != 0 && errno != EEXIST) return -1;
            *p = '/';
        }
    return mkdir(dir, 0700) != 0 && errno != EEXIST ? -1 : 0;
}

/* A new key: 32 random bytes in a private temporary beside the key file, then linked to its name, so
 * that of two processes making it at once one key wins and both read it. */
static int make_key(void)
{
    if (make_directory_of(key_file) != 0) return -1;
    char tmp[sizeof key_file + 32];
    snprintf(tmp, sizeof tmp, "%s.new-XXXXXX", key_file);
    const int fd = mkostemp(tmp, O_CLOEXEC);
    if (fd < 0) return -1;
    unsigned char fresh[sizeof key];
    randombytes_buf(fresh, sizeof fresh);
    const int written = fchmod(fd, 0600) == 0 && write(fd, fresh, sizeof fresh) == (ssize_t)sizeof fresh && fsync(fd) == 0;
    sodium_memzero(fresh, sizeof fresh);
    close(fd);
    const int linked = written && (link(tmp, key_file) == 0 || errno == EEXIST);
    const int err = errno;
    unlink(tmp);
    errno = err;
    return linked ? 0 : -1;
}

static void load_key(void)
{
    if (sodium_init() < 0) {
        key_status = GB_EIO;
        snprintf(key_message, sizeof key_message, "libsodium could not be initialised");
        return;
    }
    resolve_path();
    if (!key_file[0]) {
        key_status = GB_EIO;
        snprintf(key_message, sizeof key_message, "no key file for the seals of caches and journals: neither GOMBOC_KEY, "
                 "XDG_CONFIG_HOME nor HOME is set (allowed: GOMBOC_KEY=FILE)");
        return;
    }
    /* O_NONBLOCK: a FIFO at the key's path is refused below (not a regular file), never waited on */
    int fd = open(key_file, O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0 && errno == ENOENT) {
        if (make_key() != 0) {
            key_status = GB_EIO;
            snprintf(key_message, sizeof key_message, "cannot make the key file '%s': %s (allowed: a writable place, or "
                     "GOMBOC_KEY=FILE)", key_file, strerror(errno));
            return;
        }
        fd = open(key_file, O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
    }
    struct stat st;
    const char *why = NULL;
    if (fd < 0) why = strerror(errno);
    else if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) why = "not a regular file";
    else if (st.st_uid != geteuid()) why = "owned by another user";
    else if (st.st_mode & 077) why = "group or others may read or write it (allowed: mode 0600)";
    else if (st.st_size != (off_t)sizeof key || read(fd, key, sizeof key) != (ssize_t)sizeof key)
        why = "not 32 bytes (allowed: the key file this program made)";
    if (fd >= 0) close(fd);
    if (why) { /* a key file that is there but not a key is bad input (exit 2), as any other input */
        key_status = GB_EINVAL;
        snprintf(key_message, sizeof key_message, "the key file '%s' is refused: %s (allowed: a regular file of 32 bytes, "
                 "mode 0600, of this user, that this program made; or GOMBOC_KEY=FILE naming a new one)", key_file, why);
    }
}

int gb_seal_key_ready(void)
{
    pthread_once(&key_once, load_key);
    return key_status ? gb_error_set(key_status, "%s", key_message) : GB_OK;
}

const char *gb_seal_key_path(void)
{
    pthread_once(&key_once, load_key);
    return key_file;
}

static void hash_pieces(const unsigned char *with_key, const gb_seal_piece *pieces, size_t count,
                        unsigned char out[GB_SEAL_BYTES])
{
    crypto_generichash_state state;
    crypto_generichash_init(&state, with_key, with_key ? sizeof key : 0, GB_SEAL_BYTES);
    for (size_t k = 0; k < count; k++) crypto_generichash_update(&state, pieces[k].bytes, pieces[k].size);
    crypto_generichash_final(&state, out, GB_SEAL_BYTES);
}

_Static_assert(sizeof(crypto_generichash_state) <= sizeof(gb_seal_state), "gb_seal_state holds libsodium's state");

int gb_seal_begin(gb_seal_state *state)
{
    const int status = gb_seal_key_ready();
    if (!status) crypto_generichash_init((crypto_generichash_state *)state->opaque, key, sizeof key, GB_SEAL_BYTES);
    return status;
}

void gb_seal_add(gb_seal_state *state, const void *bytes, size_t size)
{
    crypto_generichash_update((crypto_generichash_state *)state->opaque, bytes, size);
}

void gb_seal_end(gb_seal_state *state, unsigned char seal[GB_SEAL_BYTES])
{
    crypto_generichash_final((crypto_generichash_state *)state->opaque, seal, GB_SEAL_BYTES);
}

int gb_seal_compute(const gb_seal_piece *pieces, size_t count, unsigned char seal[GB_SEAL_BYTES])
{
    const int status = gb_seal_key_ready();
    if (status) return status;
    hash_pieces(key, pieces, count, seal);
    return GB_OK;
}

int gb_seal_verify(const gb_seal_piece *pieces, size_t count, const unsigned char seal[GB_SEAL_BYTES])
{
    unsigned char want[GB_SEAL_BYTES];
    if (gb_seal_compute(pieces, count, want)) {
        gb_error_clear();
        return 0;
    }
    return sodium_memcmp(want, seal, GB_SEAL_BYTES) == 0;
}

void gb_seal_digest(const gb_seal_piece *pieces, size_t count, unsigned char digest[GB_SEAL_BYTES])
{
    if (sodium_init() < 0) {
        memset(digest, 0, GB_SEAL_BYTES);
        return;
    }
    hash_pieces(NULL, pieces, count, digest);
}

void gb_seal_hex(const unsigned char bytes[GB_SEAL_BYTES], char hex[GB_SEAL_HEX])
{
    static const char digits[] = "0123456789abcdef";
    for (int k = 0; k < GB_SEAL_BYTES; k++) hex[2 * k] = digits[bytes[k] >> 4], hex[2 * k + 1] = digits[bytes[k] & 15];
    hex[2 * GB_SEAL_BYTES] = '\0';
}

int gb_seal_from_hex(const char *hex, unsigned char bytes[GB_SEAL_BYTES])
{
    for (int k = 0; k < 2 * GB_SEAL_BYTES; k++) {
        const char c = hex[k];
        const int v = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
        if (v < 0) return 0;
        if (k % 2 == 0) bytes[k / 2] = (unsigned char)(v << 4);
        else bytes[k / 2] |= (unsigned char)v;
    }
    return 1;
}
