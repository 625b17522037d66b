/* fuzz_wrap — the file readers' fuzz targets (atlas, hull) put a valid header before each input and its
 * FNV-1a checksum after it, so that the parser behind the checksum meets every input. */
#ifndef FUZZ_WRAP_H
#define FUZZ_WRAP_H

#include "gb_hash.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* header, data, checksum of both, in a new buffer of *total bytes (abort when out of memory) */
static inline unsigned char *fuzz_wrap(const unsigned char *header, size_t header_size, const uint8_t *data, size_t size,
                                       size_t *total)
{
    unsigned char *file = malloc(header_size + size + sizeof(uint64_t));
    if (!file) abort();
    memcpy(file, header, header_size);
    if (size) memcpy(file + header_size, data, size);
    const uint64_t sum = gb_hash_add(GB_HASH_OFFSET, file, header_size + size);
    memcpy(file + header_size + size, &sum, sizeof sum);
    *total = header_size + size + sizeof sum;
    return file;
}

#endif
