/* gb_arena — memory for many small objects of one size that are released together (internal).
 *
 * Items come from 2 MiB-aligned blocks handed out in order; gb_arena_release frees every block at
 * once. Blocks are offered to the kernel as huge pages where it takes the advice (madvise): a run of the
 * certificate creates tens of thousands of items, and on a virtualised machine each first touch of a
 * 4 KiB page costs microseconds. The advice changes speed only, never a value. */
#ifndef GB_ARENA_H
#define GB_ARENA_H

#include <stddef.h>

typedef struct gb_arena_block gb_arena_block;

typedef struct gb_arena {
    size_t item_size, per_block;
    gb_arena_block *blocks; /* the newest first */
} gb_arena;

/* An empty arena of items of `item_size` bytes (at most 2 MiB). */
void gb_arena_init(gb_arena *arena, size_t item_size);
/* One uninitialised item, or NULL when memory is exhausted. */
void *gb_arena_take(gb_arena *arena);
/* Free every item; the arena is empty again and may be used on. */
void gb_arena_release(gb_arena *arena);

#endif
