/* gb_dynamics_context — what a run of one body is built on, kept apart from its physics (gb_dynamics.h):
 * the mass properties, the grid of nodes and the fast grid's tracker, the certificate and the atlas of
 * verticals; the caller's context shares them between runs and holds the files of the caches, read when a
 * run first needs them and written by gb_dynamics_context_save. The dynamics never touch a file. */
#include "gb_dynamics_internal.h"

#include "gb_atlas_internal.h"
#include "gb_contact.h"
#include "gb_dynamics_protocol_internal.h"
#include "gb_error.h"
#include "gb_hash.h"
#include "gb_seal.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

struct gb_dynamics_context {
    gb_surface props_surface; /* the body and mass of `props` (has_props) */
    double props_mass;
    gb_massprops props;
    int has_props;
    int props_loaded;         /* `props` came from the cache's file */
    gb_surface grid_surface;  /* the body and definition of `grid` (and `tracker`) */
    gb_contact_grid_def grid_def;
    gb_contact_grid *grid;
    gb_contact_tracker *tracker;
    int hull_loaded;          /* the tracker came from hull_file (else Qhull built it: saved when named) */
    int hull_written;         /* hull_file holds the tracker's hull (saved) */
    gb_surface atlas_surface; /* the body and definition of `atlas` */
    gb_atlas_def atlas_def;
    gb_atlas *atlas;
    int atlas_loaded;         /* the atlas came from atlas_file */
    int atlas_written;        /* atlas_file holds this atlas as of atlas_saved_build (loaded or saved) */
    double atlas_saved_build; /* the atlas's build seconds at its load or last save */
    char *atlas_file, *hull_file;
    char *cache_dir;          /* the user's cache: the hull by the grid's content (hull_file then names it: hull_cached), the
                               * paper's bodies' mass properties */
    int hull_cached;
    gb_dynamics_lowest_node lowest;
    void *lowest_user;
    gb_dynamics_context *lead; /* the context whose atlas this one's runs view (gb_dynamics_context_share) */
    size_t atlas_max_bytes;    /* a lead's: the bound of the atlas it makes */
    size_t atlas_cells_read;   /* a lead's: the cells its atlas read from the file */
    pthread_mutex_t share;     /* a lead's: its atlas made, viewed and saved by one thread at a time */
};

int gb_dynamics_context_create(gb_dynamics_context **out)
{
    *out = calloc(1, sizeof **out);
    if (!*out) return gb_error_set(GB_ENOMEM, "out of memory for the dynamics context");
    if (pthread_mutex_init(&(*out)->share, NULL)) {
        free(*out), *out = NULL;
        return gb_error_set(GB_ENOMEM, "the dynamics context: no mutex");
    }
    return GB_OK;
}

void gb_dynamics_context_free(gb_dynamics_context *c)
{
    if (!c) return;
    gb_contact_tracker_free(c->tracker);
    gb_contact_grid_free(c->grid);
    gb_atlas_free(c->atlas);
    free(c->atlas_file);
    free(c->hull_file);
    free(c->cache_dir);
    pthread_mutex_destroy(&c->share);
    free(c);
}

static int set_path(char **slot, const char *path)
{
    free(*slot);
    *slot = path ? strdup(path) : NULL;
    return !path || *slot ? GB_OK : gb_error_set(GB_ENOMEM, "out of memory for a file name");
}

int gb_dynamics_context_files(gb_dynamics_context *c, const char *atlas_file, const char *hull_file)
{
    const int status = set_path(&c->atlas_file, atlas_file);
    return status ? status : set_path(&c->hull_file, hull_file);
}

int gb_dynamics_context_cache(gb_dynamics_context *c, const char *dir)
{
    return set_path(&c->cache_dir, dir);
}

/* With a cache directory and no hull file named: the file the grid's nodes key there. */
static int cached_hull_file(gb_dynamics_context *c, const gb_contact_grid *grid)
{
    if (c->hull_file || !c->cache_dir) return GB_OK;
    uint64_t key = GB_HASH_OFFSET;
    const size_t count = gb_contact_grid_size(grid);
    for (size_t k = 0; k < count; k++) {
        double node[5];
        gb_contact_grid_node(grid, k, &node[0], &node[1], node + 2);
        key = gb_hash_add(key, node, sizeof node);
    }
    char path[4096];
    if (snprintf(path, sizeof path, "%s/hull-%016llx.gbh", c->cache_dir, (unsigned long long)key) >= (int)sizeof path)
        return GB_OK; /* a cache too deep to name: none */
    c->hull_cached = 1;
    return set_path(&c->hull_file, path);
}

void gb_dynamics_context_lowest(gb_dynamics_context *c, gb_dynamics_lowest_node lowest, void *user)
{
    c->lowest = lowest, c->lowest_user = user;
}

void gb_dynamics_context_share(gb_dynamics_context *c, gb_dynamics_context *lead) { c->lead = lead; }

void gb_dynamics_context_atlas_bound(gb_dynamics_context *lead, size_t max_bytes) { lead->atlas_max_bytes = max_bytes; }

int gb_dynamics_context_save_shared(gb_dynamics_context *lead)
{
    pthread_mutex_lock(&lead->share);
    const int status = gb_dynamics_context_save(lead);
    pthread_mutex_unlock(&lead->share);
    return status;
}

int gb_dynamics_context_shared_stats(gb_dynamics_context *lead, gb_atlas_stats *out, size_t *cells_read)
{
    memset(out, 0, sizeof *out);
    pthread_mutex_lock(&lead->share);
    const int held = lead->atlas != NULL;
    *cells_read = lead->atlas_cells_read;
    if (held) gb_atlas_get_stats(lead->atlas, out);
    pthread_mutex_unlock(&lead->share);
    return held;
}

int gb_dynamics_context_save(gb_dynamics_context *c)
{
    int status = GB_OK;
    if (c->atlas && c->atlas_file && !c->lead) {
        /* the file holds this atlas already when it was loaded or saved and no cell was proved since */
        gb_atlas_stats st;
        gb_atlas_get_stats(c->atlas, &st);
        if (!c->atlas_written || st.build_seconds != c->atlas_saved_build) {
            /* the cells another run wrote there since are kept (missing or stale: replaced) */
            status = gb_atlas_merge_save(c->atlas, c->atlas_file);
            if (!status) c->atlas_written = 1, c->atlas_saved_build = st.build_seconds;
        }
    }
    if (!status && c->tracker && c->hull_file && !c->hull_loaded && !c->hull_written && gb_contact_tracker_vertices(c->tracker)) {
        status = gb_contact_tracker_save(c->tracker, c->hull_file);
        c->hull_written = !status;
        if (status && c->hull_cached) { /* a cache that cannot be written (read-only, full, no key): the run stands */
            gb_error_clear();
            status = GB_OK;
        }
    }
    return status;
}

static int same_body(const gb_surface *a, const gb_surface *b)
{
    return a->morphology == b->morphology && !memcmp(&a->beta, &b->beta, sizeof a->beta);
}

static int same_grid(const gb_contact_grid_def *a, const gb_contact_grid_def *b)
{
    return a->n_phi == b->n_phi && a->n_theta == b->n_theta && a->nodes == b->nodes && a->leaf_size == b->leaf_size;
}

/* The mass properties in the user's cache (the context's cache directory), keyed by the body's content: the paper's
 * bodies only — a body of one's own is named by a file or an expression whose content the key would not see, and a
 * polyhedron's are in closed form (cheap). The key holds the morphology's name, β, the quadrature's definition (with
 * the mass) and MASSPROPS_REVISION, raised whenever gb_massprops' results change; the file is sealed like the hull
 * (gb_seal: a file another hand wrote, or this program under another key, is not read) and written whole (a
 * temporary file renamed). 8 ms of a run's start-up for Table 1's bodies. */
#define MASSPROPS_REVISION 1u
static const char massprops_magic[8] = "gbmp01\n";

static int massprops_cache_path(const gb_dynamics_context *c, const gb_surface *s, const gb_massprops_def *def, char *path,
                                size_t size)
{
    const gb_morphology *m = s->morphology;
    if (!c->cache_dir || !m->phase || m->user || m->polyhedron || m->kernel || !m->name) return 0;
    const unsigned revision = MASSPROPS_REVISION, bytes = (unsigned)sizeof(gb_massprops);
    uint64_t key = gb_hash_add(GB_HASH_OFFSET, m->name, strlen(m->name));
    key = gb_hash_add(key, &s->beta, sizeof s->beta);
    const double numbers[3] = {def->mass, def->epsabs, def->epsrel};
    key = gb_hash_add(key, numbers, sizeof numbers);
    key = gb_hash_add(key, &def->limit, sizeof def->limit);
    key = gb_hash_add(key, &revision, sizeof revision);
    key = gb_hash_add(key, &bytes, sizeof bytes);
    const int n = snprintf(path, size, "%s/massprops-%016llx.gbm", c->cache_dir, (unsigned long long)key);
    return n > 0 && (size_t)n < size;
}

static int massprops_load(const char *path, double mass, gb_massprops *out)
{
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    char magic[sizeof massprops_magic];
    gb_massprops props;
    unsigned char seal[GB_SEAL_BYTES], extra;
    const int whole = fread(magic, sizeof magic, 1, f) == 1 && fread(&props, sizeof props, 1, f) == 1 &&
                      fread(seal, sizeof seal, 1, f) == 1 && fread(&extra, 1, 1, f) == 0;
    fclose(f);
    const gb_seal_piece pieces[2] = {{magic, sizeof magic}, {&props, sizeof props}};
    if (!whole || memcmp(magic, massprops_magic, sizeof magic) || !gb_seal_verify(pieces, 2, seal) ||
        memcmp(&props.mass, &mass, sizeof mass))
        return 0;
    *out = props;
    return 1;
}

/* Best effort: a cache that cannot be written is no error (the next run computes them again). */
static void massprops_save(const char *path, const gb_massprops *props)
{
    const gb_seal_piece pieces[2] = {{massprops_magic, sizeof massprops_magic}, {props, sizeof *props}};
    unsigned char seal[GB_SEAL_BYTES];
    if (gb_seal_compute(pieces, 2, seal)) {
        gb_error_clear();
        return;
    }
    char tmp[4200];
    if (snprintf(tmp, sizeof tmp, "%s.%ld.tmp", path, (long)getpid()) >= (int)sizeof tmp) return;
    FILE *f = fopen(tmp, "wb");
    if (!f) return;
    const int ok = fwrite(massprops_magic, sizeof massprops_magic, 1, f) == 1 && fwrite(props, sizeof *props, 1, f) == 1 &&
                   fwrite(seal, sizeof seal, 1, f) == 1;
    if (fclose(f) || !ok || rename(tmp, path)) remove(tmp);
}

/* The body's mass properties: the context's when it holds this body's and mass's, else read from the user's cache,
 * else computed (and kept there and in the cache: they follow the last body). */
static int body_massprops(gb_dynamics_context *c, const gb_surface *surface, const gb_dynamics_def *def, gb_massprops *props)
{
    if (c->has_props && same_body(&c->props_surface, surface) && !memcmp(&c->props_mass, &def->mass, sizeof def->mass)) {
        *props = c->props;
        return GB_OK;
    }
    gb_massprops_def mdef = gb_massprops_default_def();
    mdef.mass = def->mass;
    char path[4096];
    const int cached = massprops_cache_path(c, surface, &mdef, path, sizeof path);
    int status = GB_OK;
    const int loaded = cached && massprops_load(path, def->mass, props);
    if (!loaded) {
        status = gb_massprops_compute(surface, &mdef, props);
        if (!status && cached) massprops_save(path, props);
    }
    if (!status) c->props_surface = *surface, c->props_mass = def->mass, c->props = *props, c->has_props = 1, c->props_loaded = loaded;
    return status;
}

/* The grid, and for the fast grid its tracker (from the hull file when it holds this grid's hull, else by
 * Qhull): the context's when it holds this body's and grid's; else built, and kept in a context that holds
 * none (the first body's stay, so a run never loses what another run uses), or else the run's own. */
static int body_grid(gb_dynamics *d, gb_dynamics_context *c, const gb_surface *surface, const gb_dynamics_def *def)
{
    const int fast = def->contact == GB_CONTACT_MODEL_FAST_GRID;
    const int cached = c->grid && same_body(&c->grid_surface, surface) && same_grid(&c->grid_def, &def->grid);
    int status = GB_OK;
    if (cached) {
        d->grid = c->grid, d->grid_borrowed = 1;
        if (!fast) return GB_OK;
        if (c->tracker) {
            d->tracker = c->tracker;
            return GB_OK;
        }
    } else {
        status = gb_contact_grid_create(surface, &def->grid, &d->grid);
        if (status) return status;
        if (!c->grid) c->grid = d->grid, c->grid_surface = *surface, c->grid_def = def->grid, d->grid_borrowed = 1;
        if (!fast) return GB_OK;
    }
    /* a hull file that is missing, stale or damaged is built anew by Qhull (and replaced when saved) */
    if (d->grid_borrowed) status = cached_hull_file(c, d->grid);
    if (status) return status;
    const int loaded = d->grid_borrowed && c->hull_file && gb_contact_tracker_load(d->grid, c->hull_file, &d->tracker) == GB_OK;
    if (!loaded) {
        gb_error_clear();
        status = gb_contact_tracker_create(d->grid, &d->tracker);
    }
    if (!status && d->grid_borrowed) c->tracker = d->tracker, c->hull_loaded = loaded;
    return status;
}

/* Field by field: the struct's padding holds no value (memcmp read it: valgrind's uninitialised-value error). The
 * tolerance by its bits, as the atlas file records it. */
static int same_atlas_def(const gb_atlas_def *a, const gb_atlas_def *b)
{
    return !memcmp(&a->height_tol, &b->height_tol, sizeof a->height_tol) && a->first_level == b->first_level &&
           a->max_level == b->max_level && a->max_depth == b->max_depth;
}

/* With a cache directory and no atlas file named: the file keyed there by the body and the atlas's definition (the
 * paper's bodies only, as the mass properties), so that a `certificate = atlas` run's first cells are proved once per
 * body, not once per run. The file's own header names its body and definition: one that does not match is built anew
 * and replaced; it is merged and written as a named one is (gb_dynamics_context_save). */
static int cached_atlas_file(gb_dynamics_context *c, const gb_surface *s, const gb_atlas_def *adef)
{
    const gb_morphology *m = s->morphology;
    if (c->atlas_file || !c->cache_dir || !m->phase || m->user || m->polyhedron || m->kernel || !m->name) return GB_OK;
    uint64_t key = gb_hash_add(GB_HASH_OFFSET, m->name, strlen(m->name));
    key = gb_hash_add(key, &s->beta, sizeof s->beta);
    key = gb_hash_add(key, &adef->height_tol, sizeof adef->height_tol);
    const int levels[3] = {adef->first_level, adef->max_level, adef->max_depth};
    key = gb_hash_add(key, levels, sizeof levels);
    char path[4096];
    if (snprintf(path, sizeof path, "%s/atlas-%016llx.gba", c->cache_dir, (unsigned long long)key) >= (int)sizeof path)
        return GB_OK; /* a cache too deep to name: none */
    return set_path(&c->atlas_file, path);
}

/* Lead's atlas for this body and definition, made there (and read from lead's atlas file) when lead has none:
 * NULL when lead holds another body's. Under lead's lock. */
static int made_atlas(gb_dynamics_context *lead, const gb_surface *surface, const gb_atlas_def *adef, gb_atlas **out)
{
    *out = NULL;
    if (lead->atlas) {
        if (same_body(&lead->atlas_surface, surface) && same_atlas_def(&lead->atlas_def, adef)) *out = lead->atlas;
        return GB_OK;
    }
    int status = cached_atlas_file(lead, surface, adef);
    if (!status) status = gb_atlas_create(surface, adef, &lead->atlas);
    if (status) return status;
    lead->atlas_surface = *surface, lead->atlas_def = *adef;
    if (lead->atlas_max_bytes) gb_atlas_set_max_bytes(lead->atlas, lead->atlas_max_bytes);
    /* a file that is missing, stale or damaged is built anew (and replaced when saved) */
    lead->atlas_loaded = lead->atlas_file && gb_atlas_load(lead->atlas, lead->atlas_file) == GB_OK;
    if (!lead->atlas_loaded) gb_error_clear();
    lead->atlas_written = lead->atlas_loaded, lead->atlas_saved_build = 0.0;
    gb_atlas_stats read;
    gb_atlas_get_stats(lead->atlas, &read);
    lead->atlas_cells_read = read.cells + read.cells_failed;
    *out = lead->atlas;
    return GB_OK;
}

/* The atlas of verticals: the context's when it was made for this body and definition, made there (and read
 * from the atlas file, when it holds this atlas) when the context has none, else the run's own. A context that
 * shares a lead's (gb_dynamics_context_share) holds a view of the lead's atlas instead. */
static int body_atlas(gb_dynamics *d, gb_dynamics_context *c, const gb_surface *surface, const gb_dynamics_def *def)
{
    gb_atlas_def adef = def->atlas;
    adef.height_tol = def->certify.height_tol;
    if (c->atlas && same_body(&c->atlas_surface, surface) && same_atlas_def(&c->atlas_def, &adef)) {
        d->atlas = c->atlas, d->atlas_borrowed = 1;
        return GB_OK;
    }
    if (c->lead && !c->atlas) {
        gb_dynamics_context *lead = c->lead;
        pthread_mutex_lock(&lead->share);
        gb_atlas *shared;
        int status = made_atlas(lead, surface, &adef, &shared);
        if (!status && shared) status = gb_atlas_share(shared, &c->atlas);
        if (!status && shared) c->atlas_surface = *surface, c->atlas_def = adef, c->atlas_loaded = lead->atlas_loaded;
        pthread_mutex_unlock(&lead->share);
        if (status) return status;
        if (shared) {
            d->atlas = c->atlas, d->atlas_borrowed = 1;
            return GB_OK;
        }
    }
    int status = c->atlas ? GB_OK : cached_atlas_file(c, surface, &adef);
    if (!status) status = gb_atlas_create(surface, &adef, &d->atlas);
    if (status || c->atlas) return status;
    c->atlas = d->atlas, c->atlas_surface = *surface, c->atlas_def = adef, d->atlas_borrowed = 1;
    /* a file that is missing, stale or damaged is built anew (and replaced when saved) */
    c->atlas_loaded = c->atlas_file && gb_atlas_load(c->atlas, c->atlas_file) == GB_OK;
    if (!c->atlas_loaded) gb_error_clear();
    c->atlas_written = c->atlas_loaded, c->atlas_saved_build = 0.0;
    return GB_OK;
}

int gb_dyn_body_create(gb_dynamics *d)
{
    if (!d->context) {
        const int status = gb_dynamics_context_create(&d->context);
        if (status) return status;
        d->own_context = 1;
    }
    gb_dynamics_context *c = d->context;
    const gb_surface *surface = &d->surface;
    const gb_dynamics_def *def = &d->def;
    gb_massprops props;
    int status = body_massprops(c, surface, def, &props);
    if (status) return status;
    const double l2 = def->length * def->length;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) d->inertia[i][j] = props.inertia[i][j] * l2;
    d->mean_radius = props.L * def->length;
    if (def->contact != GB_CONTACT_MODEL_CONTINUOUS) return body_grid(d, c, surface, def);
    if (def->certificate == GB_CERTIFICATE_MULTISTART) { /* no certificate: the branch grid's minima, polished */
        const gb_contact_grid_def starts = gb_contact_default_branch_grid();
        return gb_contact_grid_create(surface, &starts, &d->starts);
    }
    status = gb_certify_create(surface, &def->certify, &d->certify);
    if (!status && def->certificate == GB_CERTIFICATE_ATLAS) status = body_atlas(d, c, surface, def);
    return status;
}

void gb_dyn_body_free(gb_dynamics *d)
{
    if (!d->grid_borrowed) {
        gb_contact_tracker_free(d->tracker);
        gb_contact_grid_free(d->grid);
    }
    gb_certify_free(d->certify);
    gb_contact_grid_free(d->starts);
    if (!d->atlas_borrowed) gb_atlas_free(d->atlas);
    if (d->own_context) gb_dynamics_context_free(d->context);
}

int gb_dyn_lowest_hook(const gb_dynamics *d, gb_dynamics_lowest_node *lowest, void **user)
{
    if (!d->context || !d->context->lowest) return 0;
    *lowest = d->context->lowest, *user = d->context->lowest_user;
    return 1;
}

size_t gb_dynamics_grid_size(const gb_dynamics *d) { return d->grid ? gb_contact_grid_size(d->grid) : 0; }

void gb_dynamics_contact_work(const gb_dynamics *d, size_t *queries, size_t *nodes)
{
    gb_dynamics_lowest_node lowest;
    void *user;
    const int counted = d->def.contact != GB_CONTACT_MODEL_CONTINUOUS &&
                        !(d->def.contact == GB_CONTACT_MODEL_GRID && gb_dyn_lowest_hook(d, &lowest, &user));
    *queries = counted ? d->contact_queries : 0;
    *nodes = counted ? d->nodes_visited : 0;
}

int gb_dynamics_certify_stats(const gb_dynamics *d, gb_certify_stats *out)
{
    if (d->starts) { /* multi-start: its checks (none undecided, none proved) and its Newton polishes */
        memset(out, 0, sizeof *out);
        out->checks = d->multistart_checks, out->lower_found = d->multistart_lower;
        out->global = d->multistart_checks - d->multistart_lower, out->newton_runs = d->multistart_seeds;
        return GB_OK;
    }
    if (!d->certify) return gb_error_set(GB_EINVAL, "the certificate belongs to continuous contact only");
    gb_certify_get_stats(d->certify, out);
    return GB_OK;
}

int gb_dynamics_atlas_stats(const gb_dynamics *d, gb_atlas_stats *out, size_t *fallbacks, int *loaded)
{
    if (!d->atlas) return gb_error_set(GB_EINVAL, "the atlas belongs to continuous contact with certificate = atlas only");
    gb_atlas_get_stats(d->atlas, out);
    *fallbacks = d->atlas_fallbacks;
    *loaded = d->atlas == d->context->atlas && d->context->atlas_loaded;
    return GB_OK;
}

int gb_dynamics_massprops_loaded(const gb_dynamics *d) { return d->context && d->context->props_loaded; }

int gb_dynamics_hull_stats(const gb_dynamics *d, size_t *vertices, int *loaded)
{
    if (!d->tracker) return gb_error_set(GB_EINVAL, "the contact model %s has no hull (allowed: fast-grid)",
                                         gb_contact_model_name(d->def.contact));
    *vertices = gb_contact_tracker_vertices(d->tracker);
    *loaded = d->tracker == d->context->tracker && d->context->hull_loaded;
    return GB_OK;
}
