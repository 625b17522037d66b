/* fuzz_wrap — the file readers' fuzz targets (atlas, hull) put a valid header before each input and its
 * seal (gb_seal, under the fuzzing process's key) after it, so that the parser behind the seal meets
 * every input: the seal a forger cannot make is made here, to reach what a forger with the key could. */
#ifndef FUZZ_WRAP_H
#define FUZZ_WRAP_H

#include "gb_seal.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* header, data, the seal of both, in a new buffer of *total bytes (abort when out of memory or without a
 * key) */
static inline unsigned char *fuzz_wrap(const unsigned char *header, size_t header_size, const uint8_t *data, size_t size,
                                       size_t *total)
{
    unsigned char *file = malloc(header_size + size + GB_SEAL_BYTES);
    if (!file) abort();
    memcpy(file, header, header_size);
    if (size) memcpy(file + header_size, data, size);
    if (gb_seal_compute(&(gb_seal_piece){file, header_size + size}, 1, file + header_size + size)) abort();
    *total = header_size + size + GB_SEAL_BYTES;
    return file;
}

#endif
