/* gb_hash — FNV-1a, 64 bits: the fingerprints of runs and scans and the atlas file's checksum
 * (internal). Not cryptographic: it tells equal bytes from accidentally different ones. */
#ifndef GB_HASH_H
#define GB_HASH_H

#include <stddef.h>
#include <stdint.h>

#define GB_HASH_OFFSET 14695981039346656037ull

static inline uint64_t gb_hash_add(uint64_t hash, const void *bytes, size_t size)
{
    const unsigned char *p = bytes;
    for (size_t k = 0; k < size; k++) hash = (hash ^ p[k]) * 1099511628211ull;
    return hash;
}

#endif
