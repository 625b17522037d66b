/* gb_seal — what the program trusts on reading is sealed by a key only its user holds.
 *
 * A file the program reads back and acts on without recomputing it — the fast grid's hull, the atlas of
 * verticals, a scan journal's rows — carries a seal: the keyed BLAKE2b-256 of its bytes (libsodium's
 * crypto_generichash with a 32-byte key). A checksum anyone can recompute (FNV-1a, or an unkeyed
 * SHA-256) tells damage from intact bytes but not an edit from this program's own writing: whoever
 * changes a value can recompute it. A seal cannot be made without the key, so a file that verifies was
 * written by a gomboc of the same user (or of whoever shares the key file), and was not changed since.
 *
 * The key is 32 random bytes (randombytes_buf) in the file $GOMBOC_KEY, or else
 * $XDG_CONFIG_HOME/gomboc/key, or else $HOME/.config/gomboc/key; it is made on first use (mode 0600, by
 * a link so that two processes making it at once agree on one) and refused when group or others may
 * read or write it. Machines that share a scan's directory (MPI ranks on several nodes, NFS) share the
 * key through the same file; a cache sealed under another key is rebuilt, a journal under another key
 * refused.
 *
 * A content digest (gb_seal_digest) is the unkeyed BLAKE2b-256: it names bytes (a scan file and its base
 * scene) so that no other bytes can be made to carry the same name. Thread-safe. */
#ifndef GB_SEAL_H
#define GB_SEAL_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

enum { GB_SEAL_BYTES = 32, GB_SEAL_HEX = 2 * GB_SEAL_BYTES + 1 };

/* One piece of the bytes sealed: the seal of several pieces is that of their concatenation. */
typedef struct gb_seal_piece {
    const void *bytes;
    size_t size;
} gb_seal_piece;

/* The key, loaded (or made) once per process: GB_OK, or GB_EIO naming the key file and what is wrong. */
int gb_seal_key_ready(void);
/* The key file's path as it will be used (for messages). */
const char *gb_seal_key_path(void);

/* A seal made piece by piece (a file written as it is sealed): begin (GB_OK, or the status of
 * gb_seal_key_ready), add the bytes in order, end with the seal. */
typedef struct gb_seal_state {
    _Alignas(64) unsigned char opaque[448]; /* libsodium's crypto_generichash_state */
} gb_seal_state;
int gb_seal_begin(gb_seal_state *state);
void gb_seal_add(gb_seal_state *state, const void *bytes, size_t size);
void gb_seal_end(gb_seal_state *state, unsigned char seal[GB_SEAL_BYTES]);

/* The seal of the pieces: GB_OK, or the status of gb_seal_key_ready. */
int gb_seal_compute(const gb_seal_piece *pieces, size_t count, unsigned char seal[GB_SEAL_BYTES]);
/* 1 when `seal` is the pieces' seal under this user's key (compared in constant time), 0 otherwise,
 * including when there is no key. */
int gb_seal_verify(const gb_seal_piece *pieces, size_t count, const unsigned char seal[GB_SEAL_BYTES]);

/* The unkeyed BLAKE2b-256 of the pieces. */
void gb_seal_digest(const gb_seal_piece *pieces, size_t count, unsigned char digest[GB_SEAL_BYTES]);

/* Lower-case hexadecimal, and back (0 when `hex` is not 64 hexadecimal digits). */
void gb_seal_hex(const unsigned char bytes[GB_SEAL_BYTES], char hex[GB_SEAL_HEX]);
int gb_seal_from_hex(const char *hex, unsigned char bytes[GB_SEAL_BYTES]);

#ifdef __cplusplus
}
#endif

#endif
