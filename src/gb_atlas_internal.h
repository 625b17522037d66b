/* gb_atlas_internal — what the atlas's two files share: its cells, sites and surface boxes, and the
 * atlas itself (gb_atlas.c builds and proves cells; gb_atlas_file.c saves, loads and merges them). Not
 * installed, not exported. */
#ifndef GB_ATLAS_INTERNAL_H
#define GB_ATLAS_INTERNAL_H

#include "gb_atlas.h"
#include "gb_arena.h"
#include "gb_certify_internal.h"

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

enum { CELL_UNBUILT = 0, CELL_SPLIT = 1, CELL_CERTIFIED = 2, CELL_FAILED = 3 };
enum { SETTLED = 0, UNSETTLED = 1 };

/* A box of the surface cover, kept with its enclosure for every cell's proof. */
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

struct gb_atlas {
    gb_surface surface;
    gb_atlas_def def;
    gb_certify *certify; /* the global minimum at a cell's centre */
    box roots[GB_ROOT_COUNT];
    gb_surface_enclosure root_enclosures[GB_ROOT_COUNT];
    gb_arena box_quads, cell_quads;
    cell faces[6];
    cell *last; /* the cell of the last check */
    double last_half_width;
    gb_atlas_stats stats;
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

#endif
