/* gb_atlas_internal — what the atlas's two files share: its cells, sites and surface boxes, and the
 * atlas itself (gb_atlas.c builds and proves cells; gb_atlas_file.c saves, loads and merges them). Not
 * installed, not exported. */
#ifndef GB_ATLAS_INTERNAL_H
#define GB_ATLAS_INTERNAL_H

#include "gb_atlas.h"
#include "gb_arena.h"
#include "gb_certify_internal.h"

#include <pthread.h>
#include <stdio.h>

/* Site boxes are built where the minimum lies within this distance of a chart's root boxes [rad]
 * (as gb_certify's basins). */
#define SITE_REACH 0.1
#define SITE_MAX_HALF_WIDTH 0.3
#define SITE_MIN_HALF_WIDTH 2e-3
#define SITE_WIDTH_STEP 0.75
/* A site box's Hessian is tested on one enclosure, or on its 4 or 16 sub-boxes (each must pass). */
#define SITE_SPLITS 2
/* Two minima closer than this are the same site [body length]. */
#define SAME_POINT 1e-7

/* A cell's state. CELL_BUILDING: claimed by the view that proves it (never in a file: written as unbuilt). A view
 * reads a cell's state with acquire and publishes it with release (gb_atlas.c, "sharing"): what a cell holds is
 * written before its state says so, and a published cell never changes while views share the atlas. */
enum { CELL_UNBUILT = 0, CELL_SPLIT = 1, CELL_CERTIFIED = 2, CELL_FAILED = 3, CELL_BUILDING = 4 };
enum { SETTLED = 0, UNSETTLED = 1 };

typedef struct box {
    struct box *child; /* four, or NULL */
    gb_surface_enclosure *e;
    double a_lo, a_hi, b_lo, b_hi;
    double xa_mag, xb_mag, xaa_mag, xab_mag, xbb_mag; /* bounds of |x_a|, ... over the box */
    unsigned char region, depth;
} box;

typedef struct box_quad {
    box n[4];
    gb_surface_enclosure e[4];
} box_quad;

typedef struct site {
    int boxes;
    gb_atlas_site_box box[2];
    int looked_up[2];            /* 0: a polar-x box whose directions all lie in the (φ, θ) band (below) */
    double x0[3];                /* its minimum at the cell's centre (the FAR reference) */
    double hint_phi, hint_theta; /* where Newton starts: the last minimum found in it */
} site;

typedef struct cell {
    struct cell *child; /* four, or NULL */
    double u_lo, u_hi, v_lo, v_hi;
    unsigned char face, level, state, sites;
    site site[2];
} cell;

typedef struct cell_quad {
    cell c[4];
} cell_quad;

/* The views waiting for cells are woken by lists, a cell's by its address: a cell's completion wakes the views
 * that wait for it (and the few that share its list), not all of them. */
#define GB_ATLAS_WAKE_LISTS 64

/* What the views of one atlas share: the body, the surface cover and the cells (gb_atlas.c, "sharing"). */
typedef struct gb_atlas_core {
    gb_surface surface;
    gb_atlas_def def;
    box roots[GB_ROOT_COUNT];
    gb_surface_enclosure root_enclosures[GB_ROOT_COUNT];
    gb_arena box_quads, cell_quads;
    cell faces[6];
    pthread_mutex_t lock;  /* the arenas, the counters below, the views' count and the wake-ups */
    pthread_cond_t built[GB_ATLAS_WAKE_LISTS]; /* a claimed cell was published: the list of its address's waiters */
    size_t views;          /* the views that hold it (the last one frees it) */
    gb_certify **certifiers; /* the global minimum at a cell's centre: one is taken by a view while it proves a
                              * cell, and given back, so that their refined boxes serve every view */
    size_t certifiers_free, certifiers_cap;
    size_t max_bytes;      /* no cell is built beyond this memory (0: no bound); its checks are undecided then */
    size_t cells_held;     /* the cells taken from the arena: the six faces and four a split */
    double radius;         /* ≥ |x| over the whole surface (the root boxes' enclosures) */
    gb_atlas_stats stats;  /* the cells and boxes: cells, cells_failed, two_site_cells, cells_split, boxes,
                            * deepest_level, build_seconds, and the waits (wait_seconds, waits) */
} gb_atlas_core;

/* An atlas as one thread sees it: the shared core, and what only this view's checks touch. */
struct gb_atlas {
    gb_atlas_core *core;
    cell *last;          /* the cell of the last check */
    double hint[2][2];   /* where Newton starts in each site of `last`: the last minimum found there */
    double ref_d[2][3],
        ref_h[2]; /* each site's minimum of `last` at a vertical: its height there (the skip, gb_atlas.c) */
    double last_half_width;
    gb_atlas_stats stats; /* this view's checks: checks, answered, lower_found, newton_runs, boxes_tested */
};

/* A fresh cover: the six faces unbuilt, every cell below them released. */
void gb_atlas_faces_reset(gb_atlas *A);
/* Split cell c into its four children (unbuilt). GB_ENOMEM. */
int gb_atlas_cell_split(gb_atlas *A, cell *c);
/* Is every direction of a polar-x site box inside the (φ, θ) band (gb_atlas.c says why a check then need
 * not look in it)? */
int gb_atlas_site_in_band(const gb_atlas_site_box *b);
/* gb_atlas_merge, then gb_atlas_save, with the file's directory locked (gb_file_lock) in between, so
 * that writers of one file, threads or processes, take turns and every cell any of them proved stays in
 * it. A file that is missing, of another atlas or damaged is replaced. GB_EIO when the lock stays held
 * beyond GB_FILE_LOCK_SECONDS or $GOMBOC_LOCK_SECONDS (nothing is written then). */
int gb_atlas_merge_save(gb_atlas *atlas, const char *path);
/* Another view of `atlas`'s cells, for another thread: its cells are built once, by the first view that needs
 * them, and read by every view without a lock (gb_atlas.c, "sharing"). Free it with gb_atlas_free; the cells
 * go with the last view. GB_ENOMEM. */
int gb_atlas_share(gb_atlas *atlas, gb_atlas **view);
/* No cell is built once the atlas holds this many bytes (0: no bound): checks in cells not built say undecided. */
void gb_atlas_set_max_bytes(gb_atlas *atlas, size_t bytes);
/* How many views hold the atlas's cells. */
size_t gb_atlas_views(const gb_atlas *atlas);
/* The atlas written to f as its file is (header, cells, seal): what gb_atlas_save writes and gb_atlas_load_buffer
 * reads. 0, or 1 when a write failed. */
int gb_atlas_write(const gb_atlas *atlas, FILE *f);

#endif
