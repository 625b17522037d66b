/* Section 4, eq 29: the atlas of verticals (gb_atlas), which certifies the global contact of a whole
 * cell of verticals at once. Its verdicts are checked against an exhaustive search at random
 * verticals (and each vertical's cell against the same search: the global minimum must lie in one of
 * the sites the cell names), its runs against the per-vertical certificate's runs of Table 1, and its
 * file against damage and staleness. */
#include "gb_atlas.h"
#include "gb_atlas_internal.h"
#include "gb_check.h"
#include "gb_dynamics.h"
#include "gb_error.h"
#include "gb_integrate.h"
#include "gb_vec.h"
#include "verify_sections.h"

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int in_box(const gb_atlas_site_box *b, double a, double bb)
{
    int wrapped = 0;
    for (int w = -1; w <= 1; w++) wrapped |= bb + 2.0 * M_PI * w >= b->b_lo && bb + 2.0 * M_PI * w <= b->b_hi;
    return a >= b->a_lo && a <= b->a_hi && wrapped;
}

/* What a cell's certificate claims about the global minimum (φ, θ): in each region of the cover of the
 * sphere of directions whose parameter range holds the point, a site box of that region's chart holds it
 * (boxes of that region outside the site boxes were proved to hold no global minimum). */
static int cell_holds(const gb_atlas_cell_info *cell, double phi, double theta)
{
    static const double range[3][4] = {{0.8, M_PI - 0.8, 0.0, 2.0 * M_PI},
                                       {0.75, M_PI - 0.75, 0.75, M_PI - 0.75},
                                       {0.75, M_PI - 0.75, M_PI + 0.75, 2.0 * M_PI - 0.75}};
    for (int r = 0; r < 3; r++) {
        const gb_surface_chart chart = r ? GB_SURFACE_CHART_POLAR_X : GB_SURFACE_CHART_POLAR_Z;
        double a, b;
        gb_surface_chart_coordinates(chart, phi, theta, &a, &b);
        const gb_atlas_site_box region = {chart, range[r][0], range[r][1], range[r][2], range[r][3]};
        if (!in_box(&region, a, b)) continue;
        int held = 0;
        for (int s = 0; s < cell->sites; s++)
            for (int k = 0; k < cell->boxes[s]; k++) held |= cell->box[s][k].chart == chart && in_box(&cell->box[s][k], a, b);
        if (!held) return 0;
    }
    return 1;
}

/* At random verticals (uniform on the sphere, seeded): the exhaustive search's global minimum (Newton
 * from every discrete local minimum of a 180 × 360 grid) is GLOBAL for the atlas and lies in a site of
 * its cell; every other minimum higher by more than η is refused with the global one as the lower. */
static void test_random_verticals(void)
{
    enum { VERTICALS = 5000 };
    for (int m = 0; m < 2; m++) {
        gb_surface s;
        gb_surface_init(&s, m ? "II" : "I", 0.12);
        gb_contact_grid_def gd = gb_contact_default_branch_grid();
        gb_contact_grid *grid = NULL;
        gb_atlas *atlas = NULL;
        const gb_atlas_def ad = gb_atlas_default_def();
        const gb_contact_refine_def rd = gb_contact_refine_default_def();
        int status = gb_contact_grid_create(&s, &gd, &grid);
        if (!status) status = gb_atlas_create(&s, &ad, &atlas);
        gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
        gsl_rng_set(rng, 20261123UL + (unsigned long)m);
        size_t global = 0, undecided = 0, wrong = 0, in_cell = 0, others = 0, refused = 0, other_undecided = 0;
        double worst = 0.0;
        for (int k = 0; !status && k < VERTICALS; k++) {
            double zb[3];
            gsl_ran_dir_3d(rng, &zb[0], &zb[1], &zb[2]);
            gb_contact_branches br;
            status = gb_contact_branches_find(grid, zb, &rd, &br);
            gb_certify_result r;
            if (!status) status = gb_atlas_check(atlas, zb, &br.branch[0], &rd, &r);
            gb_atlas_cell_info cell;
            if (!status) status = gb_atlas_cell(atlas, zb, &cell);
            if (status) break;
            global += r.verdict == GB_CERTIFY_GLOBAL;
            undecided += r.verdict == GB_CERTIFY_UNDECIDED;
            wrong += r.verdict == GB_CERTIFY_LOWER_FOUND;
            /* a cell without a certificate claims nothing */
            in_cell += cell.sites == 0 || cell_holds(&cell, br.branch[0].phi, br.branch[0].theta);
            for (size_t j = 1; j < br.count && !status; j++) {
                if (br.branch[j].height - br.branch[0].height <= ad.height_tol) continue; /* a tie */
                others++;
                status = gb_atlas_check(atlas, zb, &br.branch[j], &rd, &r);
                other_undecided += !status && r.verdict == GB_CERTIFY_UNDECIDED;
                if (!status && r.verdict == GB_CERTIFY_LOWER_FOUND) {
                    const double diff = fabs(r.lower.height - br.branch[0].height);
                    worst = fmax(worst, diff);
                    refused += diff <= 1e-12;
                }
            }
        }
        gb_atlas_stats as = {0};
        if (atlas) gb_atlas_get_stats(atlas, &as);
        gsl_rng_free(rng);
        gb_atlas_free(atlas);
        gb_contact_grid_free(grid);
        char q[220];
        snprintf(q, sizeof q, "Gomboc %s: the atlas at %d random verticals: global minimum certified and inside a site of "
                 "its cell, every other minimum refused for the global one", m ? "II" : "I", VERTICALS);
        gb_check c = {"4", "29", q, "exhaustive search: Newton from every discrete local minimum of a 180 x 360 grid",
                      "exact verdicts; undecided allowed (the run then asks the per-vertical certificate) at under 5 % "
                      "of the verticals, so that an atlas deciding nothing cannot pass; the lower minimum's height "
                      "equal to the search's to 1e-12 (eta)"};
        gb_check_true(&c, !status && wrong == 0 && global + undecided == VERTICALS && in_cell == VERTICALS &&
                              refused + other_undecided == others && undecided * 20 < VERTICALS,
                      "%s; %zu of %d certified global, %zu undecided, %zu refused; global minimum in a site of its cell at "
                      "%zu; %zu of %zu other minima refused for the global one (worst height difference %.3g), %zu "
                      "undecided; %zu cells (%zu with two sites, %zu without a certificate), deepest level %d, %zu boxes",
                      status ? gb_error_message() : "ran", global, VERTICALS, undecided, wrong, in_cell, refused, others,
                      worst, other_undecided, as.cells, as.two_site_cells, as.cells_failed, as.deepest_level, as.boxes);
    }
}

/* Every certified cell of an atlas file, at its centre and at four points 9/10 of the way to its corners:
 * the exhaustive search's global minimum lies where the cell's certificate says, and the atlas certifies
 * it global. Returns the verticals checked; *wrong counts the failures. */
static size_t recheck_cells(const char *body, const char *path, size_t *cells, size_t *wrong, int *status)
{
    gb_atlas *atlas = NULL;
    gb_contact_grid *grid = NULL;
    const gb_atlas_def ad = gb_atlas_default_def();
    const gb_contact_refine_def rd = gb_contact_refine_default_def();
    gb_contact_grid_def gd = gb_contact_default_branch_grid();
    gb_atlas_cell_info *info = NULL;
    size_t checked = 0;
    *wrong = 0, *cells = 0;
    *status = gb_atlas_create(gb_check_body(body, 0.12), &ad, &atlas);
    if (!*status) *status = gb_atlas_load(atlas, path);
    if (!*status) *status = gb_contact_grid_create(gb_check_body(body, 0.12), &gd, &grid);
    if (!*status) {
        gb_atlas_cells(atlas, NULL, 0, cells);
        info = malloc((*cells ? *cells : 1) * sizeof *info);
        if (!info) *status = gb_error_set(GB_ENOMEM, "out of memory for the atlas's cells");
    }
    if (!*status) gb_atlas_cells(atlas, info, *cells, cells);
    for (size_t k = 0; !*status && k < *cells; k++) {
        for (int j = 0; j < 5 && !*status; j++) {
            double zb[3];
            for (int i = 0; i < 3; i++) zb[i] = j ? info[k].d0[i] + 0.9 * (info[k].corner[j - 1][i] - info[k].d0[i]) : info[k].d0[i];
            gb_contact_branches br;
            gb_certify_result r;
            gb_atlas_cell_info here;
            *status = gb_contact_branches_find(grid, zb, &rd, &br);
            if (!*status) *status = gb_atlas_cell(atlas, zb, &here);
            if (!*status) *status = gb_atlas_check(atlas, zb, &br.branch[0], &rd, &r);
            if (*status) break;
            checked++;
            *wrong += here.level != info[k].level || !cell_holds(&info[k], br.branch[0].phi, br.branch[0].theta) ||
                      r.verdict == GB_CERTIFY_LOWER_FOUND;
        }
    }
    free(info);
    gb_contact_grid_free(grid);
    gb_atlas_free(atlas);
    return checked;
}

/* One Table 1 rolling run (300 periods, RK4 160 steps a period, located switches, R0 = I, ω0 = 0). */
static int table1_run(const char *body, gb_dynamics_certificate certificate, const char *atlas_file,
                      double y[GB_STATE_SIZE], size_t *switches, gb_atlas_stats *as, size_t *fallbacks, int *loaded)
{
    gb_dynamics_def def = gb_dynamics_default_def();
    def.contact = GB_CONTACT_MODEL_CONTINUOUS, def.variant = GB_VARIANT_ROLLING;
    def.certificate = certificate;
    const double R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, w0[3] = {0, 0, 0};
    gb_dynamics *d = NULL;
    gb_dynamics_context *context = NULL;
    int status = gb_dynamics_context_create(&context);
    if (!status) status = gb_dynamics_context_files(context, atlas_file, NULL);
    if (!status) status = gb_dynamics_start_in(gb_check_body(body, 0.12), &def, context, R0, w0, &d, y);
    gb_integrate_def idef = gb_integrate_default_def();
    idef.locate_switches = 1;
    gb_integrate_stats stats;
    if (!status) status = gb_integrate_run(d, &idef, 0.0, y, NULL, NULL, &stats);
    if (!status) *switches = gb_dynamics_switch_count(d);
    if (!status && certificate == GB_CERTIFICATE_ATLAS) status = gb_dynamics_atlas_stats(d, as, fallbacks, loaded);
    gb_dynamics_free(d);
    if (!status) status = gb_dynamics_context_save(context);
    gb_dynamics_context_free(context);
    return status;
}

static int flip_byte(const char *path, long offset)
{
    FILE *f = fopen(path, "r+b");
    if (!f) return 0;
    int ok = fseek(f, offset, SEEK_SET) == 0;
    const int c = ok ? fgetc(f) : EOF;
    ok = ok && c != EOF && fseek(f, offset, SEEK_SET) == 0 && fputc(c ^ 0x5a, f) != EOF;
    return fclose(f) == 0 && ok;
}

/* The atlas run of each Table 1 rolling scene equals the per-vertical certificate's run bit for bit
 * (same switches, same final state): every step made the same decision, since the motion is chaotic and
 * one different switch would have moved the state by far more than rounding. The same run with its
 * atlas saved and loaded again, with that file damaged, and with a file built for another β. */
static void test_table1_runs(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE], path[GB_CHECK_TEMPDIR_SIZE + 16];
    if (gb_check_tempdir("atlas-check", dir, sizeof dir)) return;
    snprintf(path, sizeof path, "%s/check.atlas", dir);
    for (int m = 0; m < 2; m++) {
        const char *body = m ? "II" : "I";
        double y[4][GB_STATE_SIZE];
        size_t switches[4] = {0}, fallbacks[4] = {0};
        gb_atlas_stats as[4] = {{0}};
        int loaded[4] = {0};
        remove(path);
        int status = table1_run(body, GB_CERTIFICATE_PER_VERTICAL, NULL, y[0], &switches[0], NULL, NULL, NULL);
        /* 1: built during the run and saved; 2: loaded from the file; 3: from the file with one byte changed */
        for (int run = 1; run < 4 && !status; run++) {
            if (run == 3 && !flip_byte(path, 200)) status = gb_error_set(GB_EIO, "cannot change a byte of %s", path);
            if (!status)
                status = table1_run(body, GB_CERTIFICATE_ATLAS, path, y[run], &switches[run], &as[run], &fallbacks[run],
                                    &loaded[run]);
        }
        int same = !status;
        for (int run = 1; run < 4 && same; run++)
            same = memcmp(y[run], y[0], sizeof y[0]) == 0 && switches[run] == switches[0];
        size_t cells = 0, wrong = 0, checked = 0;
        int recheck = status;
        if (!status) checked = recheck_cells(body, path, &cells, &wrong, &recheck);
        char q[220];
        snprintf(q, sizeof q, "Gomboc %s, Table 1 rolling: every certified cell of the run's atlas, at its centre and "
                 "four points towards its corners", body);
        gb_check r = {"4", "29", q, "exhaustive search: Newton from every discrete local minimum of a 180 x 360 grid",
                      "exact: the global minimum inside a site box of every region holding it, certified global"};
        gb_check_true(&r, !recheck && checked == 5 * cells && cells > 0 && wrong == 0,
                      "%s; %zu cells, %zu verticals, %zu where the cell's claim or the atlas's verdict disagrees with the "
                      "search", recheck ? gb_error_message() : "ran", cells, checked, wrong);
        snprintf(q, sizeof q, "Gomboc %s, Table 1, continuous rolling, located switches, 300 periods: the atlas's run is "
                 "the per-vertical certificate's run, with the atlas built, loaded, and rebuilt from a damaged file", body);
        gb_check c = {"4, 8", "29", q, "the run certified per vertical (gb_certify at every step)",
                      "exact (final state bits, switch count): the same minimum polished from the same rounded start"};
        gb_check_true(&c, same && loaded[1] == 0 && loaded[2] == 1 && loaded[3] == 0,
                      "%s; %s; %zu switches per-vertical; atlas built in the run: %zu cells (%zu with two sites) in %.3f s, "
                      "%zu of %zu checks answered by the atlas (%zu left to the per-vertical certificate); loaded: %d; "
                      "damaged file refused and rebuilt: %d",
                      status ? gb_error_message() : "ran", same ? "the four runs agree" : "THE RUNS DIFFER", switches[0], as[1].cells, as[1].two_site_cells,
                      as[1].build_seconds, as[1].answered, as[1].checks, fallbacks[1], loaded[2], loaded[3] == 0);
    }
    /* a file of another body, β or η is refused, naming why */
    gb_atlas *a = NULL;
    gb_atlas_def ad = gb_atlas_default_def();
    int status = gb_atlas_create(gb_check_body("II", 0.11), &ad, &a);
    const int beta = status ? status : gb_atlas_load(a, path);
    const int beta_named = strstr(gb_error_message(), "not an atlas of this body") != NULL;
    gb_atlas_free(a);
    ad.height_tol = 1e-11;
    status = gb_atlas_create(gb_check_body("II", 0.12), &ad, &a);
    const int eta = status ? status : gb_atlas_load(a, path);
    gb_atlas_free(a);
    ad = gb_atlas_default_def();
    status = gb_atlas_create(gb_check_body("II", 0.12), &ad, &a);
    const int same = status ? status : gb_atlas_load(a, path);
    gb_atlas_free(a);
    gb_check_tempdir_remove(dir);
    gb_check k = {"4", "29", "an atlas file built for another beta or eta is refused; the file of this body loads",
                  "error path", "exact"};
    gb_check_true(&k, beta == GB_EIO && beta_named && eta == GB_EIO && same == GB_OK,
                  "beta 0.11: status %d; eta 1e-11: status %d; same body: status %d", beta, eta, same);
}

/* Two runs that share one atlas file at once (both started before either wrote it): each merges the
 * file's cells before it writes, so that the file ends with the cells of both, and a third atlas loaded
 * from it holds them all and builds nothing for the verticals of either. */
static void test_merged_writers(void)
{
    char dir[GB_CHECK_TEMPDIR_SIZE], path[GB_CHECK_TEMPDIR_SIZE + 16];
    if (gb_check_tempdir("atlas-merge", dir, sizeof dir)) return;
    snprintf(path, sizeof path, "%s/merge.atlas", dir);
    remove(path);
    gb_atlas *a[3] = {NULL, NULL, NULL};
    gb_atlas_def ad = gb_atlas_default_def();
    int status = GB_OK;
    for (int k = 0; k < 3 && !status; k++) status = gb_atlas_create(gb_check_body("I", 0.12), &ad, &a[k]);
    /* a[0] around +z, a[1] around +x: two faces of the cube of verticals, no cell in common */
    double z[2][8][3];
    for (int j = 0; j < 8; j++) {
        const double t = 0.8 * j, r = 0.1 + 0.08 * j, c = r * cos(t), s = r * sin(t), n = sqrt(1.0 + r * r);
        const double up[3] = {c, s, 1.0}, side[3] = {1.0, c, s};
        for (int i = 0; i < 3; i++) z[0][j][i] = up[i] / n, z[1][j][i] = side[i] / n;
    }
    size_t count[3] = {0, 0, 0};
    gb_atlas_cell_info info;
    for (int k = 0; k < 2 && !status; k++)
        for (int j = 0; j < 8 && !status; j++) status = gb_atlas_cell(a[k], z[k][j], &info);
    for (int k = 0; k < 2 && !status; k++) gb_atlas_cells(a[k], NULL, 0, &count[k]);
    if (!status) status = gb_atlas_save(a[0], path);
    int merged = status ? status : gb_atlas_merge(a[1], path);
    if (!status && !merged) status = gb_atlas_save(a[1], path);
    if (!status && !merged) status = gb_atlas_load(a[2], path);
    gb_atlas_stats before = {0}, after = {0};
    if (!status && !merged) {
        gb_atlas_cells(a[2], NULL, 0, &count[2]);
        gb_atlas_get_stats(a[2], &before);
        for (int k = 0; k < 2 && !status; k++)
            for (int j = 0; j < 8 && !status; j++) status = gb_atlas_cell(a[2], z[k][j], &info);
        gb_atlas_get_stats(a[2], &after);
    }
    /* a file of another atlas is not merged, and leaves the atlas as it was */
    gb_atlas *other = NULL;
    size_t kept = 0;
    int refused = GB_OK;
    if (!status && !gb_atlas_create(gb_check_body("II", 0.12), &ad, &other)) {
        refused = gb_atlas_merge(other, path);
        gb_atlas_cells(other, NULL, 0, &kept);
    }
    gb_atlas_free(other);
    for (int k = 0; k < 3; k++) gb_atlas_free(a[k]);
    gb_check_tempdir_remove(dir);
    gb_check c = {"4", "29", "two atlases of Gomboc I built apart (8 verticals within 0.6 rad of +z, 8 of +x), written to one "
                  "file in turn, the second merging the first's cells",
                  "the file holds both: its cells are the sum, and no cell is built for the 16 verticals", "exact"};
    gb_check_true(&c, !status && !merged && count[0] > 0 && count[1] > 0 && count[2] == count[0] + count[1] &&
                      after.build_seconds == before.build_seconds && after.cells == before.cells,
                  "%s; cells %zu + %zu, the merged file %zu; built after loading it: %zu cells in %.3g s",
                  status || merged ? gb_error_message() : "ran", count[0], count[1], count[2], after.cells - before.cells,
                  after.build_seconds - before.build_seconds);
    gb_check r = {"4", "29", "an atlas file of Gomboc I merged into an atlas of Gomboc II", "refused (GB_EIO), no cell taken",
                  "exact"};
    gb_check_true(&r, refused == GB_EIO && kept == 0, "status %d, %zu cells: %s", refused, kept, gb_error_message());
}

/* ---- one atlas, several threads (gb_atlas_share) ---------------------------------------------------- */

enum { SHARED_VERTICALS = 400, SHARED_THREADS = 8 };

typedef struct shared_run {
    gb_atlas *view;
    const double (*zb)[3];
    const gb_contact_point *minimum;
    int verdict[SHARED_VERTICALS];
    int status;
} shared_run;

static void *shared_checks(void *arg)
{
    shared_run *r = arg;
    const gb_contact_refine_def rd = gb_contact_refine_default_def();
    for (int k = 0; k < SHARED_VERTICALS && !r->status; k++) {
        gb_certify_result out;
        r->status = gb_atlas_check(r->view, r->zb[k], &r->minimum[k], &rd, &out);
        r->verdict[k] = out.verdict;
    }
    return NULL;
}

/* Eight threads check the same 400 verticals (within 0.5 rad of +z, seeded), in the same order, each through its
 * own view of one atlas (gb_atlas_share), at once; one atlas alone checks them too. */
static void test_shared_views(void)
{
    static double zb[SHARED_VERTICALS][3];
    static gb_contact_point minimum[SHARED_VERTICALS];
    static shared_run run[SHARED_THREADS + 1];
    const gb_surface *s = gb_check_body("I", 0.12);
    const gb_atlas_def ad = gb_atlas_default_def();
    const gb_contact_refine_def rd = gb_contact_refine_default_def();
    gb_contact_grid_def gd = gb_contact_default_branch_grid();
    gb_contact_grid *grid = NULL;
    int status = gb_contact_grid_create(s, &gd, &grid);
    gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
    gsl_rng_set(rng, 20261129UL);
    for (int k = 0; k < SHARED_VERTICALS && !status; k++) {
        const double r = 0.5 * sqrt(gsl_rng_uniform(rng)), t = 2.0 * M_PI * gsl_rng_uniform(rng);
        zb[k][0] = sin(r) * cos(t), zb[k][1] = sin(r) * sin(t), zb[k][2] = cos(r);
        gb_contact_branches br;
        status = gb_contact_branches_find(grid, zb[k], &rd, &br);
        if (!status) minimum[k] = br.branch[0];
    }
    gsl_rng_free(rng);
    gb_contact_grid_free(grid);
    gb_atlas *alone = NULL, *shared = NULL;
    if (!status) status = gb_atlas_create(s, &ad, &alone);
    if (!status) status = gb_atlas_create(s, &ad, &shared);
    run[0] = (shared_run){.view = alone, .zb = (const double (*)[3])zb, .minimum = minimum};
    if (!status) shared_checks(&run[0]), status = run[0].status;
    int views = 0;
    for (int t = 1; t <= SHARED_THREADS && !status; t++) {
        run[t] = (shared_run){.view = t == 1 ? shared : NULL, .zb = (const double (*)[3])zb, .minimum = minimum};
        if (t > 1) status = gb_atlas_share(shared, &run[t].view);
        views += !status;
    }
    pthread_t id[SHARED_THREADS];
    int started = 0;
    for (; !status && started < SHARED_THREADS; started++)
        if (pthread_create(&id[started], NULL, shared_checks, &run[1 + started])) break;
    for (int t = 0; t < started; t++) pthread_join(id[t], NULL);
    size_t contradictions = 0, decided = 0, agreed = 0, listed = 0;
    for (int t = 1; t <= started; t++) {
        if (run[t].status && !status) status = run[t].status;
        for (int k = 0; k < SHARED_VERTICALS; k++) {
            const int a = run[0].verdict[k], b = run[t].verdict[k];
            decided += b != GB_CERTIFY_UNDECIDED;
            agreed += a == b;
            contradictions += a != GB_CERTIFY_UNDECIDED && b != GB_CERTIFY_UNDECIDED && a != b;
        }
    }
    /* an atlas already past its memory bound builds no cell: each check is left to gb_certify (undecided) */
    gb_atlas *full = NULL;
    size_t full_undecided = 0;
    gb_atlas_stats full_stats = {0};
    if (!status) status = gb_atlas_create(s, &ad, &full);
    if (!status) gb_atlas_set_max_bytes(full, 1);
    for (int k = 0; k < 20 && !status; k++) {
        gb_certify_result out;
        status = gb_atlas_check(full, zb[k], &minimum[k], &rd, &out);
        full_undecided += out.verdict == GB_CERTIFY_UNDECIDED;
    }
    if (full) gb_atlas_get_stats(full, &full_stats);
    gb_atlas_free(full);
    gb_atlas_stats st = {0}, solo = {0};
    if (shared) gb_atlas_get_stats(shared, &st), gb_atlas_cells(shared, NULL, 0, &listed);
    if (alone) gb_atlas_get_stats(alone, &solo);
    for (int t = 2; t <= SHARED_THREADS; t++) gb_atlas_free(run[t].view);
    gb_atlas_free(shared);
    gb_atlas_free(alone);
    gb_check c = {"4", "29", "Gomboc I: 8 threads check the same 400 verticals near +z in the same order at once, each through "
                  "its own view of one atlas (gb_atlas_share); one atlas alone checks them too",
                  "each cell proved once (the certified cells proved = the certified cells the atlas holds); no verdict "
                  "against the lone atlas's (a global minimum is a fact, whichever cells proved it)", "exact"};
    gb_check_true(&c, !status && started == SHARED_THREADS && views == SHARED_THREADS && st.cells == listed &&
                      contradictions == 0 && decided > 0,
                  "%s; %d threads; certified cells proved %zu, held %zu (alone: %zu); %zu of %d verdicts decided, %zu the "
                  "lone atlas's, %zu against it; %zu waits for a cell another thread was proving (%.3f s)",
                  status ? gb_error_message() : "ran", started, st.cells, listed, solo.cells, decided,
                  SHARED_THREADS * SHARED_VERTICALS, agreed, contradictions, st.waits, st.wait_seconds);
    gb_check cf = {"4", "29", "an atlas whose memory bound (1 byte) is already passed, 20 of those verticals",
                   "no cell built, every check undecided (left to the per-vertical certificate)", "exact"};
    gb_check_true(&cf, !status && full_undecided == 20 && full_stats.cells + full_stats.cells_failed + full_stats.cells_split == 0,
                  "%s; %zu of 20 undecided, %zu cells proved", status ? gb_error_message() : "ran", full_undecided,
                  full_stats.cells + full_stats.cells_failed + full_stats.cells_split);
}

/* The bound a check trusts instead of a Newton solve (gb_atlas.c, site_no_lower): at a vertical d of a cell, each
 * site's lowest point lies no lower than h_r − R |d − d_r| from the site's minimum at the cell's centre d_r (height
 * h_r), R ≥ |x| on the surface. Here against the site's minimum solved at d, at the centres and 0.9 and 0.99 of the
 * way to the corners of the two-site cells that 400 verticals near +z and 400 near +x fall in; and the bound without
 * its term R |d - d_r| must fail somewhere (else this comparison could not tell). */
static void test_skip_bound(void)
{
    for (int m = 0; m < 2; m++) {
        const gb_surface *s = gb_check_body(m ? "II" : "I", 0.12);
        const gb_atlas_def ad = gb_atlas_default_def();
        const gb_contact_refine_def rd = gb_contact_refine_default_def();
        gb_atlas *atlas = NULL;
        int status = gb_atlas_create(s, &ad, &atlas);
        gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
        gsl_rng_set(rng, 20261202UL + (unsigned long)m);
        size_t cells = 0, tested = 0, below = 0, bare_below = 0, unsolved = 0;
        double worst = INFINITY, used = 0.0; /* the largest share of R |d - d_r| a minimum fell by */
        const void *seen[64];
        for (int k = 0; k < 800 && !status; k++) {
            const double r = 0.5 * sqrt(gsl_rng_uniform(rng)), t = 2.0 * M_PI * gsl_rng_uniform(rng);
            const double a[3] = {sin(r) * cos(t), sin(r) * sin(t), cos(r)},
                         zb[3] = {k < 400 ? a[0] : a[2], a[1], k < 400 ? a[2] : a[0]};
            gb_atlas_cell_info info;
            status = gb_atlas_cell(atlas, zb, &info);
            if (status || info.sites != 2) continue;
            int known = 0;
            for (size_t j = 0; j < cells && j < 64; j++) known |= seen[j] == (const void *)atlas->last;
            if (known || cells == 64) continue;
            seen[cells++] = atlas->last;
            const double centre[3] = {info.d0[0], info.d0[1], info.d0[2]};
            status = gb_atlas_cell(atlas, centre, &info); /* the same cell: its references are its centre's */
            static const double toward[3] = {0.0, 0.9, 0.99};
            for (int j = 0; j < 9 && !status; j++) {
                const double f = toward[(j + 3) / 4];
                const double *corner = info.corner[j ? (j - 1) % 4 : 0];
                double z[3], d[3];
                for (int i = 0; i < 3; i++) z[i] = info.d0[i] + f * (corner[i] - info.d0[i]);
                status = gb_contact_unit_vertical(z, d);
                for (int site = 0; site < 2 && !status; site++) {
                    gb_contact_point q;
                    if (gb_contact_refine(s, d, atlas->hint[site][0], atlas->hint[site][1], &rd, &q) || !q.is_minimum) {
                        gb_error_clear();
                        unsolved++;
                        continue;
                    }
                    const double step[3] = {d[0] - atlas->ref_d[site][0], d[1] - atlas->ref_d[site][1],
                                            d[2] - atlas->ref_d[site][2]};
                    const double reach = atlas->core->radius * gb_vec_norm(step);
                    const double margin = q.height - (atlas->ref_h[site] - reach - GB_CERTIFY_SLACK_ROUNDING);
                    tested++;
                    below += margin < 0.0;
                    bare_below += q.height < atlas->ref_h[site] - GB_CERTIFY_SLACK_ROUNDING;
                    if (reach > 0.0) used = fmax(used, (atlas->ref_h[site] - q.height) / reach);
                    worst = fmin(worst, margin);
                }
            }
        }
        gsl_rng_free(rng);
        gb_atlas_free(atlas);
        char q[240];
        snprintf(q, sizeof q,
                 "Gomboc %s: the bound that spares a check the Newton solve of a site, h_r - R |d - d_r|, at the "
                 "centres and near the corners of two-site cells",
                 m ? "II" : "I");
        gb_check c = {"4", "29", q,
                      "the site's minimum at each vertical, by Newton from the cell's hint; h_r alone as the control",
                      "every minimum at or above its bound (no slack beyond the bound's own 1e-13); h_r alone broken "
                      "somewhere"};
        gb_check_true(&c, !status && tested > 100 && below == 0 && bare_below > 0,
                      "%s; %zu two-site cells, %zu site minima against the bound (%zu not solved), %zu below it, least "
                      "margin %.3g, at most %.3f of R |d - d_r| used; below h_r alone: %zu",
                      status ? gb_error_message() : "ran", cells, tested, unsolved, below, worst, used, bare_below);
    }
}

/* A bad atlas definition is refused with its allowed range. */
static void test_bad_definition(void)
{
    gb_atlas_def def = gb_atlas_default_def();
    def.max_level = def.first_level - 1;
    gb_atlas *a = NULL;
    const int status = gb_atlas_create(gb_check_body("I", 0.12), &def, &a);
    gb_check k = {"4", "29", "atlas levels out of order are refused, naming the allowed range", "error path", "exact"};
    gb_check_true(&k, status == GB_EDOM && a == NULL && strstr(gb_error_message(), "allowed") != NULL, "%s",
                  gb_error_message());
}

int verify_register_s4_atlas(void)
{
    static const verify_test tests[] = {
        {"eq 29: atlas verdicts and cells against an exhaustive search", test_random_verticals, NULL},
        {"eq 29: the atlas's Table 1 runs are the per-vertical certificate's runs; its file", test_table1_runs, NULL},
        {"eq 29: runs sharing one atlas file add up their cells", test_merged_writers, NULL},
        {"eq 29: threads sharing one atlas in memory prove each cell once", test_shared_views, NULL},
        {"eq 29: the bound that spares a site's Newton solve holds", test_skip_bound, NULL},
        {"eq 29: atlas definition out of range", test_bad_definition, NULL},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Section 4: the atlas of verticals", tests);
}
