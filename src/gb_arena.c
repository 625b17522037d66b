/* gb_arena — fixed-size items from 2 MiB blocks with huge-page advice (see gb_arena.h). */
#include "gb_arena.h"

#include <stdlib.h>
#include <sys/mman.h>

#define BLOCK_BYTES ((size_t)2 << 20)

struct gb_arena_block {
    gb_arena_block *next;
    size_t used;
    unsigned char *items;
};

void gb_arena_init(gb_arena *arena, size_t item_size)
{
    arena->item_size = item_size;
    arena->per_block = BLOCK_BYTES / item_size;
    arena->blocks = NULL;
}

void *gb_arena_take(gb_arena *arena)
{
    gb_arena_block *b = arena->blocks;
    if (!b || b->used == arena->per_block) {
        b = malloc(sizeof *b);
        void *mem = NULL;
        if (!b || posix_memalign(&mem, BLOCK_BYTES, arena->per_block * arena->item_size)) {
            free(b);
            return NULL;
        }
#ifdef MADV_HUGEPAGE
        madvise(mem, arena->per_block * arena->item_size, MADV_HUGEPAGE); /* advice only: ignored where unsupported */
#endif
        b->items = mem;
        b->used = 0;
        b->next = arena->blocks;
        arena->blocks = b;
    }
    return b->items + arena->item_size * b->used++;
}

void gb_arena_release(gb_arena *arena)
{
    while (arena->blocks) {
        gb_arena_block *b = arena->blocks;
        arena->blocks = b->next;
        free(b->items);
        free(b);
    }
}
