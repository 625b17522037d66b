/* gb_atlas_file — the atlas's file (gb_atlas.h): saved as a sealed set of one, loaded only whole and for
 * the same body and build constants, merged cell by cell with what another run proved. */
#include "gb_atlas_internal.h"

#include "gb_error.h"
#include "gb_file.h"
#include "gb_seal.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The file: a header (magic, format, morphology, β, η, levels, depth, site build constants), the cells
 * of the six faces in preorder (state; for a certified cell its sites), and the seal (gb_seal) of
 * everything before it. Written as a gb_file set of one, so a reader never sees half a file. */
#define ATLAS_MAGIC GB_ATLAS_FILE_MAGIC
#define ATLAS_FORMAT 3u

typedef struct header {
    char magic[16];
    uint32_t format, first_level, max_level, max_depth;
    char morphology[16];
    double beta, height_tol, site_reach, site_max, site_min, site_step;
    uint32_t site_splits, cell_bytes;
} header;

static void header_of(const gb_atlas *A, header *h)
{
    memset(h, 0, sizeof *h);
    memcpy(h->magic, ATLAS_MAGIC, sizeof ATLAS_MAGIC);
    h->format = ATLAS_FORMAT;
    h->first_level = (uint32_t)A->core->def.first_level, h->max_level = (uint32_t)A->core->def.max_level;
    h->max_depth = (uint32_t)A->core->def.max_depth;
    snprintf(h->morphology, sizeof h->morphology, "%s", A->core->surface.morphology->name);
    h->beta = A->core->surface.beta, h->height_tol = A->core->def.height_tol;
    h->site_reach = SITE_REACH, h->site_max = SITE_MAX_HALF_WIDTH, h->site_min = SITE_MIN_HALF_WIDTH;
    h->site_step = SITE_WIDTH_STEP, h->site_splits = SITE_SPLITS;
    h->cell_bytes = (uint32_t)sizeof(site);
}

typedef struct writer {
    FILE *f;
    gb_seal_state seal;
    int failed;
} writer;

static void put(writer *w, const void *bytes, size_t size)
{
    gb_seal_add(&w->seal, bytes, size);
    if (fwrite(bytes, 1, size, w->f) != size) w->failed = 1;
}

/* A cell as the file holds it: one a view is proving now is written unbuilt (gb_atlas.c, "sharing"). */
static void put_cell(writer *w, const cell *c)
{
    unsigned char state = __atomic_load_n(&c->state, __ATOMIC_ACQUIRE);
    if (state == CELL_BUILDING) state = CELL_UNBUILT;
    put(w, &state, 1);
    if (state == CELL_SPLIT)
        for (int k = 0; k < 4; k++) put_cell(w, &c->child[k]);
    if (state == CELL_CERTIFIED) {
        put(w, &c->sites, 1);
        put(w, c->site, c->sites * sizeof(site));
    }
}

int gb_atlas_write(const gb_atlas *A, FILE *f)
{
    writer w = {.f = f};
    if (gb_seal_begin(&w.seal)) return 1;
    header h;
    header_of(A, &h);
    put(&w, &h, sizeof h);
    for (int face = 0; face < 6; face++) put_cell(&w, &A->core->faces[face]);
    unsigned char seal[GB_SEAL_BYTES];
    gb_seal_end(&w.seal, seal);
    if (fwrite(seal, sizeof seal, 1, w.f) != 1) w.failed = 1;
    return w.failed;
}

/* Write the atlas to `path` as a set of one; `locked`: the caller holds the lock of its directory. */
static int atlas_save(const gb_atlas *A, const char *path, int locked)
{
    const int keyed = gb_seal_key_ready();
    if (keyed) return gb_error_set(keyed, "cannot seal the atlas file %s: %s", path, gb_error_message());
    gb_file_set set = {.directory_locked = locked};
    int status = GB_OK;
    FILE *f = gb_file_set_open(&set, path, &status);
    if (!f) return gb_error_set(status, "cannot write the atlas file: %s", gb_error_message());
    errno = 0;
    if (gb_atlas_write(A, f))
        status = gb_error_set(GB_EIO, "cannot write the atlas file %s: %s", path, strerror(errno ? errno : EIO));
    return gb_file_set_commit(&set, status);
}

int gb_atlas_save(const gb_atlas *A, const char *path) { return atlas_save(A, path, 0); }

typedef struct reader {
    const unsigned char *p, *end;
} reader;

static int take(reader *r, void *bytes, size_t size)
{
    if ((size_t)(r->end - r->p) < size) return 0;
    memcpy(bytes, r->p, size);
    r->p += size;
    return 1;
}

static int take_cell(gb_atlas *A, reader *r, cell *c)
{
    unsigned char state;
    if (!take(r, &state, 1)) return 0;
    if (state == CELL_SPLIT) {
        if (c->level >= A->core->def.max_level || gb_atlas_cell_split(A, c)) return 0;
        for (int k = 0; k < 4; k++)
            if (!take_cell(A, r, &c->child[k])) return 0;
        return 1;
    }
    if (state == CELL_CERTIFIED) {
        unsigned char sites;
        if (c->level < A->core->def.first_level || !take(r, &sites, 1) || sites < 1 || sites > 2 ||
            !take(r, c->site, sites * sizeof(site)))
            return 0;
        for (int s = 0; s < sites; s++) {
            site *t = &c->site[s];
            if (t->boxes < 1 || t->boxes > 2 || !isfinite(t->hint_phi) || !isfinite(t->hint_theta)) return 0;
            for (int k = 0; k < 3; k++)
                if (!isfinite(t->x0[k])) return 0;
            for (int k = 0; k < t->boxes; k++) {
                const gb_atlas_site_box *b = &t->box[k];
                if (b->chart != GB_SURFACE_CHART_POLAR_Z && b->chart != GB_SURFACE_CHART_POLAR_X) return 0;
                if (!(b->a_lo < b->a_hi && b->b_lo < b->b_hi && b->a_lo >= 0.0 && b->a_hi <= M_PI &&
                      b->b_hi - b->b_lo <= 2.0 * M_PI && fabs(b->b_lo) <= 4.0 * M_PI))
                    return 0;
                t->looked_up[k] = !gb_atlas_site_in_band(b); /* recomputed, not read */
            }
        }
        c->state = CELL_CERTIFIED;
        c->sites = sites;
        A->core->stats.cells++;
        A->core->stats.two_site_cells += sites == 2;
        return 1;
    }
    if (state == CELL_FAILED) {
        /* a cell whose proof failed at max_level stays without a certificate (its checks go to gb_certify) */
        if (c->level != A->core->def.max_level) return 0;
        c->state = CELL_FAILED;
        A->core->stats.cells_failed++;
        return 1;
    }
    return state == CELL_UNBUILT;
}

/* The largest file an atlas of these levels can be (every cell split down to max_level, every leaf certified
 * with two sites), and never more than GB_ATLAS_FILE_MAX. */
static size_t file_limit(const gb_atlas *A)
{
    /* Every cell of every face split down to max_level, each leaf certified with two sites: no file of
     * these levels is larger; and none beyond GB_ATLAS_FILE_MAX, whatever its levels declare. */
    double bytes = (double)sizeof(header) + GB_SEAL_BYTES;
    for (int level = 0; level <= A->core->def.max_level && bytes <= (double)GB_ATLAS_FILE_MAX; level++)
        bytes += 6.0 * pow(4.0, level) * (level < A->core->def.max_level ? 1.0 : 2.0 + 2.0 * sizeof(site));
    return bytes < (double)GB_ATLAS_FILE_MAX ? (size_t)bytes : (size_t)GB_ATLAS_FILE_MAX;
}

int gb_atlas_load(gb_atlas *A, const char *path)
{
    char *data;
    size_t size;
    const int status = gb_file_read(path, file_limit(A), "atlas file", "an atlas file this command wrote", &data, &size);
    if (status) return gb_error_set(GB_EIO, "atlas file refused: %s", gb_error_message());
    const int parsed = gb_atlas_load_buffer(A, (const unsigned char *)data, size, path);
    free(data);
    return parsed;
}

/* The counters of the cells of a subtree read apart (merge_cell's scratch), now taken into the atlas. */
static void count_subtree(gb_atlas *A, const cell *c)
{
    if (c->state == CELL_SPLIT)
        for (int k = 0; k < 4; k++) count_subtree(A, &c->child[k]);
    A->core->stats.cells += c->state == CELL_CERTIFIED;
    A->core->stats.two_site_cells += c->state == CELL_CERTIFIED && c->sites == 2;
    A->core->stats.cells_failed += c->state == CELL_FAILED;
    if (c->level > A->core->stats.deepest_level) A->core->stats.deepest_level = c->level;
}

/* A certificate holds for every vertical of its cell (gb_atlas.h), so for every vertical of a cell inside
 * it: every cell of c's subtree that has none (unbuilt, or failed) takes a copy of `from`'s sites. */
static void inherit(gb_atlas *A, cell *c, const cell *from)
{
    if (c->state == CELL_SPLIT) {
        for (int k = 0; k < 4; k++) inherit(A, &c->child[k], from);
        return;
    }
    if (c->state == CELL_CERTIFIED) return;
    if (c->state == CELL_FAILED) A->core->stats.cells_failed--;
    c->state = CELL_CERTIFIED;
    c->sites = from->sites;
    memcpy(c->site, from->site, sizeof c->site);
    A->core->stats.cells++;
    A->core->stats.two_site_cells += from->sites == 2;
}

/* The file's cells merged into c, so that nothing either side proved is lost:
 *  - c unbuilt: the file's cell (and its subtree) is taken;
 *  - both split: their children are merged;
 *  - one side split, the other certified (a cell's fate depends on the verticals that first needed it, so
 *    two runs can decompose one cell differently): the finer decomposition is kept, its cells without a
 *    certificate taking the coarser certificate (inherit);
 *  - c failed, the file's certified: the file's certificate;
 *  - elsewhere c is kept (the same cell, proved either way).
 * 0 when the bytes do not parse. */
static int merge_cell(gb_atlas *A, reader *r, cell *c)
{
    if (c->state == CELL_UNBUILT) return take_cell(A, r, c);
    if (r->p == r->end) return 0;
    if (c->state == CELL_SPLIT && *r->p == CELL_SPLIT) {
        r->p++;
        for (int k = 0; k < 4; k++)
            if (!merge_cell(A, r, &c->child[k])) return 0;
        return 1;
    }
    cell scratch = {.u_lo = c->u_lo, .u_hi = c->u_hi, .v_lo = c->v_lo, .v_hi = c->v_hi, .face = c->face, .level = c->level};
    const gb_atlas_stats kept = A->core->stats;
    const int ok = take_cell(A, r, &scratch);
    A->core->stats = kept;
    if (!ok) return 0;
    if (c->state == CELL_SPLIT && scratch.state == CELL_CERTIFIED) {
        inherit(A, c, &scratch);
    } else if (c->state == CELL_CERTIFIED && scratch.state == CELL_SPLIT) {
        const cell coarse = *c;
        c->state = CELL_SPLIT;
        c->child = scratch.child; /* the file's subtree, from this atlas's arena */
        A->core->stats.cells--, A->core->stats.two_site_cells -= coarse.sites == 2;
        for (int k = 0; k < 4; k++) count_subtree(A, &c->child[k]);
        inherit(A, c, &coarse);
    } else if (c->state == CELL_FAILED && scratch.state == CELL_CERTIFIED) {
        A->core->stats.cells_failed--;
        *c = scratch;
        A->core->stats.cells++, A->core->stats.two_site_cells += scratch.sites == 2;
    }
    return 1;
}

/* The header and checksum of an atlas file's bytes: NULL when they are this atlas's, else why not. */
static const char *refused(const gb_atlas *A, const unsigned char *data, size_t size)
{
    header want, have;
    header_of(A, &want);
    if (size < sizeof have + GB_SEAL_BYTES) return "it is not an atlas of this body, beta, eta and build, or it is damaged";
    memcpy(&have, data, sizeof have);
    if (memcmp(&want, &have, sizeof want)) return "it is not an atlas of this body, beta, eta and build";
    const gb_seal_piece content = {data, size - GB_SEAL_BYTES};
    if (!gb_seal_verify(&content, 1, data + size - GB_SEAL_BYTES))
        return "its seal does not verify: damaged, changed since it was written, or written under another key "
               "(see GOMBOC_KEY)";
    return NULL;
}

int gb_atlas_merge(gb_atlas *A, const char *path)
{
    char *data;
    size_t size;
    int status = gb_file_read(path, file_limit(A), "atlas file", "an atlas file this command wrote", &data, &size);
    if (status) return gb_error_set(GB_EIO, "atlas file refused: %s", gb_error_message());
    const char *why = refused(A, (const unsigned char *)data, size);
    if (!why) {
        reader r = {(const unsigned char *)data + sizeof(header), (const unsigned char *)data + size - GB_SEAL_BYTES};
        int ok = 1;
        for (int face = 0; face < 6 && ok; face++) ok = merge_cell(A, &r, &A->core->faces[face]);
        if (!ok || r.p != r.end) why = "its cells do not parse (the cells read before the fault are kept)";
    }
    free(data);
    if (why) return gb_error_set(GB_EIO, "atlas file %s is not merged: %s", path, why);
    return GB_OK;
}

/* The cells of `A` as they are now in a new atlas of their own (a copy that no other view reads). */
static int atlas_copy(const gb_atlas *A, gb_atlas **out)
{
    *out = NULL;
    char *bytes = NULL;
    size_t size = 0;
    FILE *f = open_memstream(&bytes, &size);
    if (!f) return gb_error_set(GB_ENOMEM, "out of memory for a copy of the atlas");
    const int failed = gb_atlas_write(A, f);
    if (fclose(f) || failed) {
        free(bytes);
        return gb_error_set(GB_ENOMEM, "out of memory for a copy of the atlas");
    }
    int status = gb_atlas_create(&A->core->surface, &A->core->def, out);
    if (!status) status = gb_atlas_load_buffer(*out, (const unsigned char *)bytes, size, "the atlas's copy");
    free(bytes);
    if (status) gb_atlas_free(*out), *out = NULL;
    return status;
}

int gb_atlas_merge_save(gb_atlas *A, const char *path)
{
    /* Shared by other views: the file's cells are merged into a copy, and the copy written, so that no cell the
     * views read changes under them (gb_atlas.c, "sharing"); the cells other runs proved then enter the file,
     * not this atlas. */
    if (gb_atlas_views(A) > 1) {
        gb_atlas *copy;
        int status = atlas_copy(A, &copy);
        if (!status) status = gb_atlas_merge_save(copy, path);
        gb_atlas_free(copy);
        return status;
    }
    /* The lock: gb_file_lock's, on the file's directory (the file itself is replaced by a rename, so a
     * lock on it would not be held by the next writer), waited for a bounded time. Without one (a
     * directory that cannot be locked) the writers are still safe, and a cell can only be lost, to be
     * proved again when needed. */
    int lock;
    int status = gb_file_lock(path, "merging the shared atlas of verticals", &lock);
    if (status) return status;
    if (gb_atlas_merge(A, path)) gb_error_clear(); /* missing, stale or damaged: replaced */
    status = atlas_save(A, path, lock >= 0);
    gb_file_unlock(lock);
    return status;
}

int gb_atlas_load_buffer(gb_atlas *A, const unsigned char *data, size_t size, const char *name)
{
    const char *path = name;
    const char *why = refused(A, data, size);
    int ok = !why;
    if (ok) {
        const gb_atlas_stats kept = A->core->stats;
        gb_atlas_faces_reset(A);
        A->core->stats.cells = A->core->stats.two_site_cells = A->core->stats.cells_failed = 0;
        reader r = {data + sizeof(header), data + size - GB_SEAL_BYTES};
        for (int face = 0; face < 6 && ok; face++) ok = take_cell(A, &r, &A->core->faces[face]);
        ok = ok && r.p == r.end;
        if (!ok) {
            gb_atlas_faces_reset(A);
            A->core->stats = kept;
            why = "its cells do not parse";
        }
    }
    if (!ok) return gb_error_set(GB_EIO, "atlas file %s is refused: %s", path, why);
    return GB_OK;
}
