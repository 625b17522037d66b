/* libFuzzer target: the hull file reader (gb_contact_tracker_load_buffer) on arbitrary graphs.
 *
 * The input is a hull file of Gömböc I at β = 0.12 on a grid of 8 × 16 nodes from its counts on (the
 * vertices, the edges, the coplanar nodes, then the arrays): the target puts the file's own first 48
 * bytes (what it was built from) before it and appends the seal, so that the reader's checks of
 * sizes and indices, not only the seal, meet every input. Beyond not crashing (ASan, UBSan), a hull
 * the reader accepts must answer queries with a node of the grid; a refused input must say why. The seed
 * (verify/fuzz/hull.seed) is such a file as `gomboc run --hull` writes it, from its counts on. */
#include "gb_contact.h"
#include "gb_error.h"
#include "gb_surface.h"
#include "fuzz_wrap.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { BUILT_FROM = 48 }; /* the header's bytes before its counts: magic, version, nodes, their hash, U, Qhull */

static gb_contact_grid *grid;
static unsigned char header[BUILT_FROM];

static void require(int condition)
{
    if (!condition) abort();
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc, (void)argv;
    static gb_surface body;
    gb_contact_grid_def def = gb_contact_grid_default_def();
    def.n_phi = 8, def.n_theta = 16;
    gb_contact_tracker *t = NULL;
    require(gb_surface_init(&body, "I", 0.12) == GB_OK && gb_contact_grid_create(&body, &def, &grid) == GB_OK &&
            gb_contact_tracker_create(grid, &t) == GB_OK);
    char path[64];
    snprintf(path, sizeof path, "/tmp/gomboc-fuzz-hull-%ld", (long)getpid());
    require(gb_contact_tracker_save(t, path) == GB_OK);
    gb_contact_tracker_free(t);
    FILE *f = fopen(path, "rb");
    require(f != NULL && fread(header, 1, sizeof header, f) == sizeof header);
    /* the counts follow BUILT_FROM: vertices, edges, coplanar nodes, and they size the file (2V + 1 + E + C
     * words after them, then the seal); a header laid out otherwise stops the target here */
    uint64_t counts[3];
    require(fread(counts, sizeof counts[0], 3, f) == 3 && counts[0] > 0 && !fseek(f, 0, SEEK_END));
    const long size = ftell(f);
    require(size == (long)(BUILT_FROM + sizeof counts + (2 * counts[0] + 1 + counts[1] + counts[2]) * sizeof(uint32_t) +
                           GB_SEAL_BYTES));
    fclose(f);
    remove(path);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    size_t total;
    unsigned char *file = fuzz_wrap(header, BUILT_FROM, data, size, &total);
    gb_contact_tracker *t = NULL;
    const int status = gb_contact_tracker_load_buffer(grid, file, total, "fuzz.hull", &t);
    free(file);
    if (status) {
        require(status == GB_EIO && t == NULL && gb_error_message()[0] != '\0');
        gb_error_clear();
        return 0;
    }
    static const double verticals[4][3] = {{0, 0, -1}, {0.3, -0.8, 0.1}, {-1, 0.2, 0.4}, {0.5, 0.5, 0.7}};
    for (int k = 0; k < 4; k++) {
        gb_contact_node n;
        require(gb_contact_tracker_find(t, verticals[k], &n) == GB_OK && n.index < 8 * 16);
    }
    gb_contact_tracker_free(t);
    return 0;
}
