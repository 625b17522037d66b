/* gb_dynamics_body — what a run of one body is built on: its mass properties, its grid of nodes and the
 * fast grid's tracker (kept in a gb_dynamics_cache the caller may share between runs), the certificate
 * and the atlas of verticals, and the caches written back after a run (the atlas and hull files). */
#include "gb_dynamics_internal.h"

#include "gb_contact.h"
#include "gb_error.h"

#include <stdlib.h>
#include <string.h>

struct gb_dynamics_cache {
    gb_surface props_surface; /* the body and mass of `props` (has_props) */
    double props_mass;
    gb_massprops props;
    int has_props;
    gb_surface grid_surface;  /* the body and definition of `grid` (and `tracker`) */
    gb_contact_grid_def grid_def;
    gb_contact_grid *grid;
    gb_contact_tracker *tracker;
    int hull_loaded;          /* the tracker came from a hull file */
};

int gb_dynamics_cache_create(gb_dynamics_cache **out)
{
    *out = calloc(1, sizeof **out);
    return *out ? GB_OK : gb_error_set(GB_ENOMEM, "out of memory for the dynamics cache");
}

void gb_dynamics_cache_free(gb_dynamics_cache *c)
{
    if (!c) return;
    gb_contact_tracker_free(c->tracker);
    gb_contact_grid_free(c->grid);
    free(c);
}

static int same_body(const gb_surface *a, const gb_surface *b)
{
    return a->morphology == b->morphology && !memcmp(&a->beta, &b->beta, sizeof a->beta);
}

static int same_grid(const gb_contact_grid_def *a, const gb_contact_grid_def *b)
{
    return a->n_phi == b->n_phi && a->n_theta == b->n_theta && a->nodes == b->nodes && a->leaf_size == b->leaf_size;
}

/* The body's mass properties: from the cache when it holds this body's and mass's, else computed (and
 * kept there). */
static int body_massprops(const gb_surface *surface, const gb_dynamics_def *def, gb_massprops *props)
{
    gb_dynamics_cache *c = def->cache;
    if (c && c->has_props && same_body(&c->props_surface, surface) && !memcmp(&c->props_mass, &def->mass, sizeof def->mass)) {
        *props = c->props;
        return GB_OK;
    }
    gb_massprops_def mdef = gb_massprops_default_def();
    mdef.mass = def->mass;
    const int status = gb_massprops_compute(surface, &mdef, props);
    if (!status && c) c->props_surface = *surface, c->props_mass = def->mass, c->props = *props, c->has_props = 1;
    return status;
}

/* The grid, and for the fast grid its tracker (from def.hull_file when it holds this grid's hull, else
 * by Qhull): borrowed from the cache when it holds this body's and grid's, else built, and kept in an
 * empty cache. */
static int body_grid(gb_dynamics *d, const gb_surface *surface, const gb_dynamics_def *def)
{
    gb_dynamics_cache *c = def->cache;
    const int fast = def->contact == GB_CONTACT_MODEL_FAST_GRID;
    const int cached = c && c->grid && same_body(&c->grid_surface, surface) && same_grid(&c->grid_def, &def->grid);
    int status = GB_OK;
    if (cached) {
        d->grid = c->grid, d->grid_borrowed = 1;
        if (!fast) return GB_OK;
        if (c->tracker) {
            d->tracker = c->tracker, d->hull_loaded = c->hull_loaded;
            return GB_OK;
        }
    } else {
        status = gb_contact_grid_create(surface, &def->grid, &d->grid);
        if (status) return status;
        if (c && !c->grid) c->grid = d->grid, c->grid_surface = *surface, c->grid_def = def->grid, d->grid_borrowed = 1;
        if (!fast) return GB_OK;
    }
    /* a hull file that is missing, stale or damaged is built anew by Qhull (and replaced when saved) */
    d->hull_loaded = def->hull_file && gb_contact_tracker_load(d->grid, def->hull_file, &d->tracker) == GB_OK;
    if (!d->hull_loaded) {
        gb_error_clear();
        status = gb_contact_tracker_create(d->grid, &d->tracker);
    }
    if (!status && d->grid_borrowed) c->tracker = d->tracker, c->hull_loaded = d->hull_loaded;
    return status;
}

/* The body's set-up for d (its surface and def set): the inertia and L scaled to its length, and only what
 * its contact model needs, a grid (and its tracker) or the certificate (and the atlas). */
int gb_dyn_body_create(gb_dynamics *d)
{
    const gb_surface *surface = &d->surface;
    const gb_dynamics_def *def = &d->def;
    gb_massprops props;
    int status = body_massprops(surface, def, &props);
    if (status) return status;
    const double l2 = def->length * def->length;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) d->inertia[i][j] = props.inertia[i][j] * l2;
    d->mean_radius = props.L * def->length;
    if (def->contact != GB_CONTACT_MODEL_CONTINUOUS) return body_grid(d, surface, def);
    status = gb_certify_create(surface, &def->certify, &d->certify);
    if (!status && def->certificate == GB_CERTIFICATE_ATLAS && def->atlas_shared) {
        d->atlas = def->atlas_shared;
        d->atlas_borrowed = 1;
    } else if (!status && def->certificate == GB_CERTIFICATE_ATLAS) {
        gb_atlas_def adef = def->atlas;
        adef.height_tol = def->certify.height_tol;
        status = gb_atlas_create(surface, &adef, &d->atlas);
        /* a file that is missing, stale or damaged is built anew (and replaced when saved) */
        if (!status && def->atlas_file) {
            d->atlas_loaded = gb_atlas_load(d->atlas, def->atlas_file) == GB_OK;
            if (!d->atlas_loaded) gb_error_clear();
        }
    }
    return status;
}

void gb_dyn_body_free(gb_dynamics *d)
{
    if (!d->grid_borrowed) {
        gb_contact_tracker_free(d->tracker);
        gb_contact_grid_free(d->grid);
    }
    gb_certify_free(d->certify);
    if (!d->atlas_borrowed) gb_atlas_free(d->atlas);
}

size_t gb_dynamics_grid_size(const gb_dynamics *d) { return d->grid ? gb_contact_grid_size(d->grid) : 0; }

void gb_dynamics_contact_work(const gb_dynamics *d, size_t *queries, size_t *nodes)
{
    const int counted = d->def.contact != GB_CONTACT_MODEL_CONTINUOUS && !(d->def.contact == GB_CONTACT_MODEL_GRID &&
                                                                          d->def.grid_lowest);
    *queries = counted ? d->contact_queries : 0;
    *nodes = counted ? d->nodes_visited : 0;
}

int gb_dynamics_certify_stats(const gb_dynamics *d, gb_certify_stats *out)
{
    if (!d->certify) return gb_error_set(GB_EINVAL, "the certificate belongs to continuous contact only");
    gb_certify_get_stats(d->certify, out);
    return GB_OK;
}

int gb_dynamics_atlas_stats(const gb_dynamics *d, gb_atlas_stats *out, size_t *fallbacks, int *loaded)
{
    if (!d->atlas) return gb_error_set(GB_EINVAL, "the atlas belongs to continuous contact with certificate = atlas only");
    gb_atlas_get_stats(d->atlas, out);
    *fallbacks = d->atlas_fallbacks;
    *loaded = d->atlas_loaded;
    return GB_OK;
}

void gb_dynamics_share_atlas(gb_dynamics *to, const gb_dynamics *from)
{
    if (!to->atlas || !from->atlas) return;
    if (!to->atlas_borrowed) gb_atlas_free(to->atlas);
    to->atlas = from->atlas;
    to->atlas_borrowed = 1;
}

int gb_dynamics_hull_stats(const gb_dynamics *d, size_t *vertices, int *loaded)
{
    if (!d->tracker) return gb_error_set(GB_EINVAL, "the contact model %s has no hull (allowed: fast-grid)",
                                         gb_contact_model_name(d->def.contact));
    *vertices = gb_contact_tracker_vertices(d->tracker);
    *loaded = d->hull_loaded;
    return GB_OK;
}

int gb_dynamics_save_hull(const gb_dynamics *d)
{
    if (!d->tracker || !d->def.hull_file || d->hull_loaded || !gb_contact_tracker_vertices(d->tracker)) return GB_OK;
    return gb_contact_tracker_save(d->tracker, d->def.hull_file);
}

int gb_dynamics_save_atlas(const gb_dynamics *d)
{
    if (!d->atlas || !d->def.atlas_file) return GB_OK;
    /* loaded from the file and no cell proved since: the file holds everything this run has */
    gb_atlas_stats st;
    gb_atlas_get_stats(d->atlas, &st);
    if (d->atlas_loaded && st.build_seconds == 0.0) return GB_OK;
    /* the cells another run wrote there since this one loaded it are kept (missing or stale: replaced) */
    return gb_atlas_merge_save(d->atlas, d->def.atlas_file);
}

