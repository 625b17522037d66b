/* libFuzzer target: the atlas file reader (gb_atlas_load_buffer) on arbitrary cells.
 *
 * The input is the cell stream of a file; the target wraps it in the valid header of Gömböc II at
 * β = 0.12 (from an atlas saved once) and appends its seal, so that the parser of the cells, not
 * only the seal, meets every input. Beyond not crashing (ASan, UBSan), an atlas the reader accepts
 * must hold only cells it can use: levels within the build's, one or two sites of one or two boxes in a
 * known chart. A refused input must say why and leave the atlas usable. */
#include "gb_atlas.h"
#include "gb_error.h"
#include "fuzz_wrap.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static gb_atlas *atlas;
static unsigned char *header;
static size_t header_size;
static gb_atlas_cell_info cells[4096];

static void require(int condition)
{
    if (!condition) abort();
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc, (void)argv;
    gb_surface body;
    const gb_atlas_def def = gb_atlas_default_def();
    require(gb_surface_init(&body, "II", 0.12) == GB_OK && gb_atlas_create(&body, &def, &atlas) == GB_OK);
    /* an empty atlas's file: the header, six unbuilt faces (one byte each) and the seal */
    char path[64];
    snprintf(path, sizeof path, "/tmp/gomboc-fuzz-atlas-%ld", (long)getpid());
    require(gb_atlas_save(atlas, path) == GB_OK);
    FILE *f = fopen(path, "rb");
    require(f != NULL);
    static unsigned char file[4096];
    const size_t size = fread(file, 1, sizeof file, f);
    fclose(f);
    remove(path);
    require(size > 6 + GB_SEAL_BYTES);
    header_size = size - 6 - GB_SEAL_BYTES;
    header = malloc(header_size);
    require(header != NULL);
    memcpy(header, file, header_size);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    size_t total;
    unsigned char *file = fuzz_wrap(header, header_size, data, size, &total);
    const int status = gb_atlas_load_buffer(atlas, file, total, "fuzz.atlas");
    free(file);
    if (status) {
        require(status == GB_EIO && gb_error_message()[0] != '\0');
        gb_error_clear();
    }
    const gb_atlas_def def = gb_atlas_default_def();
    size_t count = 0;
    gb_atlas_cells(atlas, cells, sizeof cells / sizeof cells[0], &count);
    for (size_t k = 0; k < count && k < sizeof cells / sizeof cells[0]; k++) {
        const gb_atlas_cell_info *c = &cells[k];
        require(c->level >= def.first_level && c->level <= def.max_level && c->sites >= 1 && c->sites <= 2);
        for (int s = 0; s < c->sites; s++) {
            require(c->boxes[s] >= 1 && c->boxes[s] <= 2);
            for (int b = 0; b < c->boxes[s]; b++)
                require(c->box[s][b].chart == GB_SURFACE_CHART_POLAR_Z || c->box[s][b].chart == GB_SURFACE_CHART_POLAR_X);
        }
    }
    return 0;
}
