/* Paper §4's grid search (eq 29): the grid's nodes where documented, the fast search and the trajectory tracker
 * against brute force over every node, the lowest node but one or two, the tracker's hull file. The sample of
 * verticals and the bodies are §4's (s4_contact.h); brute force is the oracle, and the answer must be the same
 * node bit for bit with the same tie-break. */
#include "gb_check.h"
#include "gb_contact.h"
#include "gb_error.h"
#include "gb_seal.h"
#include "s4_contact.h"
#include "verify_sections.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* ------------------------------------------------------------ grid nodes and bad input */

static void test_grid_nodes_and_errors(void)
{
    gb_surface s;
    gb_surface_init(&s, "II", 0.12);
    for (int placement = 0; placement < 2; placement++) {
        gb_contact_grid_def def = gb_contact_grid_default_def();
        def.nodes = (gb_contact_nodes)placement;
        gb_contact_grid *g;
        const int status = gb_contact_grid_create(&s, &def, &g);
        char q[160];
        snprintf(q, sizeof q, "Table 1 grid (90 x 180, %s nodes): nodes are x at the documented (phi, theta)",
                 gb_contact_nodes_name(def.nodes));
        double worst = status ? INFINITY : 0.0, pole_nodes = 0;
        for (size_t k = 0; !status && k < gb_contact_grid_size(g); k++) {
            const size_t i = k / 180, j = k % 180;
            const double phi = placement ? i * M_PI / 89 : (i + 0.5) * M_PI / 90;
            const double theta = placement ? j * 2 * M_PI / 179 : j * 2 * M_PI / 180;
            double x[3], node[3], node_phi, node_theta;
            gb_surface_position(&s, phi, theta, x);
            gb_contact_grid_node(g, k, &node_phi, &node_theta, node);
            worst = fmax(worst, fmax(s4_distance(x, node), fabs(node_phi - phi) + fabs(node_theta - theta)));
            pole_nodes += sin(phi) < 1e-12;
        }
        gb_check c = {"8", "2, 29", q, "gb_surface_position at the placement formula", "exact: the same arithmetic"};
        gb_check_close(&c, worst, 0.0, 0.0, 0.0);
        snprintf(q, sizeof q, "%s nodes on the poles", gb_contact_nodes_name(def.nodes));
        gb_check cp = {"8", "29", q, placement ? "2 x N_theta (linspace repeats each pole)" : "none", "exact"};
        gb_check_close(&cp, pole_nodes, placement ? 360.0 : 0.0, 0.0, 0.0);
        gb_contact_grid_free(g);
    }
    /* Every error path, provoked. */
    gb_contact_grid_def bad = gb_contact_grid_default_def();
    gb_contact_grid *g = NULL;
    bad.n_phi = 0;
    int status = gb_contact_grid_create(&s, &bad, &g);
    gb_check c1 = {"8", "29", "a 0 x 180 grid is refused", "GB_EDOM naming the allowed range", "exact"};
    gb_check_true(&c1, status == GB_EDOM && strstr(gb_error_message(), "N_phi >= 1") && !g, "status %d '%s'", status, gb_error_message());
    bad = gb_contact_grid_default_def();
    bad.nodes = GB_CONTACT_NODES_LINSPACE;
    bad.n_phi = 1;
    status = gb_contact_grid_create(&s, &bad, &g);
    gb_check c2 = {"8", "29", "a linspace grid with one colatitude is refused", "GB_EDOM", "exact"};
    gb_check_true(&c2, status == GB_EDOM && !g, "status %d '%s'", status, gb_error_message());
    bad = gb_contact_grid_default_def();
    bad.n_phi = 1 << 14;
    bad.n_theta = 1 << 14;
    status = gb_contact_grid_create(&s, &bad, &g);
    gb_check c3 = {"8", "29", "a grid over 2^26 nodes is refused before allocating", "GB_EDOM", "exact"};
    gb_check_true(&c3, status == GB_EDOM && !g, "status %d '%s'", status, gb_error_message());
    gb_contact_nodes nodes;
    status = gb_contact_nodes_parse("gauss", &nodes);
    gb_check c4 = {"8", "29", "an unknown node placement is refused", "GB_EINVAL naming centred and linspace", "exact"};
    gb_check_true(&c4, status == GB_EINVAL && strstr(gb_error_message(), "centred, linspace"), "status %d '%s'", status, gb_error_message());

    gb_contact_grid_def def = gb_contact_grid_default_def();
    gb_contact_grid_create(&s, &def, &g);
    gb_contact_node node;
    gb_contact_point point;
    gb_contact_branches branches;
    gb_contact_refine_def refine = gb_contact_refine_default_def();
    const double zero[3] = {0, 0, 0}, nan3[3] = {NAN, 0, 1};
    const int s1 = gb_contact_grid_brute(g, zero, &node), s2 = gb_contact_grid_fast(g, zero, &node);
    const int s3 = gb_contact_refine(&s, zero, 1.0, 1.0, &refine, &point);
    const int s4 = gb_contact_branches_find(g, nan3, &refine, &branches);
    gb_check c5 = {"4", "28", "a zero or NaN z_b is refused by every contact method", "GB_EDOM", "exact"};
    gb_check_true(&c5, s1 == GB_EDOM && s2 == GB_EDOM && s3 == GB_EDOM && s4 == GB_EDOM &&
                  strstr(gb_error_message(), "non-zero"), "statuses %d %d %d %d '%s'", s1, s2, s3, s4, gb_error_message());
    /* |z_b| does not matter: heights are along the unit vertical. */
    const double zb[3] = {0.2385, -0.731, 0.4417}, zb_scaled[3] = {2.385, -7.31, 4.417};
    gb_contact_node a, b;
    gb_contact_grid_fast(g, zb, &a);
    gb_contact_grid_fast(g, zb_scaled, &b);
    gb_check c6 = {"4", "28", "z_b and 10 z_b give the same node and height", "scale invariance of the argmin", "1 ulp of the normalised vertical"};
    gb_check_close(&c6, b.height, a.height, 4 * DBL_EPSILON, 0.0);
    gb_contact_grid_free(g);
}

/* ------------------------------------------------------------ fast grid search */

/* The fast search against brute force, for `count` sample verticals on one grid. */
/* 1 when the tracker's node for zb differs from brute force's (index or height bits); adds the nodes it
 * visited to *visited. */
static int tracker_differs(const gb_contact_grid *g, gb_contact_tracker *t, const double zb[3], double *visited)
{
    gb_contact_node a, b;
    gb_contact_grid_brute(g, zb, &a);
    gb_contact_tracker_find(t, zb, &b);
    *visited += (double)b.visited;
    return a.index != b.index || memcmp(&a.height, &b.height, sizeof a.height) != 0;
}

static void compare_fast_with_brute(int c, size_t n_phi, gb_contact_nodes nodes, int count)
{
    gb_contact_grid_def def = gb_contact_grid_default_def();
    def.n_phi = n_phi;
    def.n_theta = 2 * n_phi;
    def.nodes = nodes;
    gb_surface s;
    gb_surface_init(&s, s4_cases[c].morphology, s4_cases[c].beta);
    gb_contact_grid *g;
    const int status = gb_contact_grid_create(&s, &def, &g);
    int differ = status ? count : 0;
    double visited = 0.0, max_visited = 0.0;
    for (int k = 0; !status && k < count; k++) {
        gb_contact_node a, b;
        gb_contact_grid_brute(g, s4_sample_zb[k], &a);
        gb_contact_grid_fast(g, s4_sample_zb[k], &b);
        differ += a.index != b.index || memcmp(&a.height, &b.height, sizeof a.height) != 0;
        visited += (double)b.visited;
        max_visited = fmax(max_visited, (double)b.visited);
    }
    char label[64], q[256];
    s4_case_label(c, label, sizeof label);
    snprintf(q, sizeof q, "fast grid node == brute-force node (index and height bits), %zu x %zu %s, %s, %d verticals",
             def.n_phi, def.n_theta, gb_contact_nodes_name(nodes), label, count);
    gb_check check = {"8", "29", q, "brute force over every node", "exact: every vertical"};
    const size_t size = def.n_phi * def.n_theta;
    gb_check_true(&check, differ == 0 && max_visited < (double)size,
                  "%d differ; nodes visited: mean %.1f (%.4f of %zu), max %.0f", differ, visited / count,
                  visited / count / (double)size, size, max_visited);
    /* The trajectory tracker (a descent over the nodes' convex hull): on the same random verticals, each
     * a cold start from the previous one's answer, and along a slowly turning vertical (a warm start at
     * every query, as in a run: 0.002 rad a query about an axis that itself turns). */
    gb_contact_tracker *t = NULL;
    const int tracker_status = status ? status : gb_contact_tracker_create(g, &t);
    int cold = tracker_status ? count : 0, warm = tracker_status ? count : 0;
    double cold_visited = 0.0, warm_visited = 0.0;
    for (int k = 0; !tracker_status && k < count; k++) cold += tracker_differs(g, t, s4_sample_zb[k], &cold_visited);
    for (int k = 0; !tracker_status && k < count; k++) {
        const double s1 = 0.002 * k, s2 = 0.00037 * k;
        const double zb[3] = {cos(s1) * cos(s2), sin(s1) * cos(s2), sin(s2) + 0.3 * sin(0.0011 * k)};
        warm += tracker_differs(g, t, zb, &warm_visited);
    }
    snprintf(q, sizeof q, "tracker node == brute-force node (index and height bits), %zu x %zu %s, %s, %d random and %d "
             "turning verticals", def.n_phi, def.n_theta, gb_contact_nodes_name(nodes), label, count, count);
    gb_check tc = {"8", "29", q, "brute force over every node", "exact: every vertical"};
    gb_check_true(&tc, cold == 0 && warm == 0,
                  "%d and %d differ; hull vertices %zu of %zu; nodes visited: mean %.1f (random), %.1f (turning)", cold, warm,
                  t ? gb_contact_tracker_vertices(t) : 0, size, cold_visited / count, warm_visited / count);
    gb_contact_tracker_free(t);
    if (!status) gb_contact_grid_free(g);
}

/* The lowest node but one or two (what a grid body pivoting about a node, or rocking on an edge, meets
 * the plane with next; gb_contact_grid_lowest_except) against brute force over the nodes left in: every
 * case, the Table 1 grid, the sample's verticals, the nodes left out being the lowest (and the second
 * lowest) there, and a random hint; and on the sphere's exact ties along the axis. */
static void test_lowest_except(void)
{
    s4_draw_sample();
    size_t wrong = 0, queries = 0;
    for (int c = 0; c < CASE_COUNT; c++) {
        gb_surface s;
        gb_surface_init(&s, s4_cases[c].morphology, s4_cases[c].beta);
        gb_contact_grid_def def = gb_contact_grid_default_def();
        gb_contact_grid *g = NULL;
        if (gb_contact_grid_create(&s, &def, &g)) {
            wrong++;
            continue;
        }
        const size_t size = gb_contact_grid_size(g);
        double *x = malloc(3 * size * sizeof *x);
        for (size_t i = 0; x && i < size; i++) gb_contact_grid_node(g, i, NULL, NULL, x + 3 * i);
        for (int k = 0; x && k < 2000; k++) {
            const double *zb = s4_sample_zb[k];
            double d[3];
            gb_contact_unit_vertical(zb, d); /* the unit vertical every grid search uses */
            /* brute force: the three lowest (ties to the lower index), as node heights are computed */
            size_t order[3] = {SIZE_MAX, SIZE_MAX, SIZE_MAX};
            double best[3] = {INFINITY, INFINITY, INFINITY};
            for (size_t i = 0; i < size; i++) {
                const double h = d[0] * x[3 * i] + d[1] * x[3 * i + 1] + d[2] * x[3 * i + 2];
                for (int r = 0; r < 3; r++)
                    if (h < best[r]) {
                        for (int m = 2; m > r; m--) best[m] = best[m - 1], order[m] = order[m - 1];
                        best[r] = h, order[r] = i;
                        break;
                    }
            }
            for (int left_out = 1; left_out <= 2; left_out++) {
                gb_contact_node node;
                const size_t hint = (size_t)k * 7919 % size;
                queries++;
                if (gb_contact_grid_lowest_except(g, zb, hint, order, left_out, &node) || node.index != order[left_out])
                    wrong++;
            }
        }
        free(x);
        gb_contact_grid_free(g);
    }
    /* the sphere along its axis: a whole row ties; the first of it is left out, the second must come */
    gb_surface sphere;
    gb_surface_init(&sphere, "I", 0.0);
    gb_contact_grid_def def = gb_contact_grid_default_def();
    gb_contact_grid *g = NULL;
    int tie_ok = !gb_contact_grid_create(&sphere, &def, &g);
    if (tie_ok) {
        const double zb[3] = {0.0, 0.0, 1.0};
        gb_contact_node first, next;
        tie_ok = !gb_contact_grid_brute(g, zb, &first) &&
                 !gb_contact_grid_lowest_except(g, zb, SIZE_MAX, &first.index, 1, &next) && next.index == first.index + 1 &&
                 next.height == first.height;
    }
    size_t bad = 0;
    gb_contact_node none;
    tie_ok &= g && gb_contact_grid_lowest_except(g, (const double[3]){0, 0, 1}, SIZE_MAX, &bad, 3, &none) == GB_EINVAL;
    gb_error_clear();
    gb_contact_grid_free(g);
    gb_check c = {"4", "29", "the lowest grid node but one or two (a grid body's next node under the unilateral law)",
                  "brute force over the nodes left in (the 2000 first sample verticals, 4 bodies, grid 90 x 180)", "exact: the same node"};
    gb_check_true(&c, wrong == 0 && queries > 0 && tie_ok, "%zu of %zu queries differ; the sphere's tied row %s; 3 left out %s",
                  wrong, queries, tie_ok ? "gives its second node" : "fails", tie_ok ? "refused" : "not refused");
}

static void test_fast_equals_brute(void)
{
    s4_draw_sample();
    for (int c = 0; c < CASE_COUNT; c++)
        for (int placement = 0; placement < 2; placement++)
            compare_fast_with_brute(c, 90, (gb_contact_nodes)placement, SAMPLE_SIZE);
    /* the 720 x 1440 grids (a million nodes; Qhull's hull of them is most of this test's time): Gömböc I's centred
     * grid in every run, the other three behind make verify-full (6 s and 31 s) */
    for (int c = 0; c < 2; c++) {
        compare_fast_with_brute(c, 45, GB_CONTACT_NODES_CENTRED, SAMPLE_SIZE);
        if (c == 0 || gb_check_full) compare_fast_with_brute(c, 720, GB_CONTACT_NODES_CENTRED, 500);
        if (gb_check_full) compare_fast_with_brute(c, 720, GB_CONTACT_NODES_LINSPACE, 500);
    }
    /* Exact ties: on the sphere (β = 0) every node of a centred row has the same height for a
     * vertical along the axis; brute force keeps the first, and so must the fast search. Linspace
     * repeats each pole N_θ times. */
    gb_surface sphere;
    gb_surface_init(&sphere, "I", 0.0);
    int ties_ok = 1;
    size_t tie_index[4];
    for (int placement = 0; placement < 2; placement++)
        for (int up = 0; up < 2; up++) {
            gb_contact_grid_def def = gb_contact_grid_default_def();
            def.nodes = (gb_contact_nodes)placement;
            gb_contact_grid *g;
            gb_contact_grid_create(&sphere, &def, &g);
            const double zb[3] = {0.0, 0.0, up ? 1.0 : -1.0};
            gb_contact_node a, b, c;
            gb_contact_tracker *t = NULL;
            gb_contact_grid_brute(g, zb, &a);
            gb_contact_grid_fast(g, zb, &b);
            ties_ok &= !gb_contact_tracker_create(g, &t) && !gb_contact_tracker_find(t, zb, &c) && c.index == a.index;
            tie_index[2 * placement + up] = b.index;
            ties_ok &= a.index == b.index;
            gb_contact_tracker_free(t);
            gb_contact_grid_free(g);
        }
    /* A grid whose nodes are flat for Qhull (linspace 2 x 3: every node on a pole) has no hull: the
     * tracker falls back to the patch-tree search, and still returns brute force's node. */
    {
        gb_contact_grid_def def = gb_contact_grid_default_def();
        def.nodes = GB_CONTACT_NODES_LINSPACE, def.n_phi = 2, def.n_theta = 3;
        gb_contact_grid *g = NULL;
        gb_contact_tracker *t = NULL;
        int same = !gb_contact_grid_create(&sphere, &def, &g) && !gb_contact_tracker_create(g, &t);
        const size_t vertices = t ? gb_contact_tracker_vertices(t) : 1;
        for (int k = 0; same && k < 200; k++) {
            gb_contact_node a, b;
            gb_contact_grid_brute(g, s4_sample_zb[k], &a);
            same = !gb_contact_tracker_find(t, s4_sample_zb[k], &b) && a.index == b.index;
        }
        gb_check cf = {"8", "29", "tracker on a grid without a hull (linspace 2 x 3): the patch-tree fallback, 200 verticals",
                       "brute force", "exact"};
        gb_check_true(&cf, same && vertices == 0, "%s; %zu hull vertices", same ? "same nodes" : "DIFFERENT nodes", vertices);
        gb_contact_tracker_free(t);
        gb_contact_grid_free(g);
    }
    gb_check ct = {"8", "29", "exact ties (sphere, vertical along the axis): fast search and tracker pick brute force's first node",
                   "brute force", "exact"};
    gb_check_true(&ct, ties_ok, "indices centred %zu %zu, linspace %zu %zu", tie_index[0], tie_index[1], tie_index[2], tie_index[3]);
}

/* The tracker read from its hull file against the one Qhull built, on one grid: the node, the height
 * bits and the nodes visited of every sample vertical (equal visits: the same graph, walked the same way).
 * 1 when they all agree. */
static int hull_file_agrees(const gb_contact_grid *g, gb_contact_tracker *built, const char *path, size_t *vertices)
{
    gb_contact_tracker *loaded = NULL;
    if (gb_contact_tracker_save(built, path) || gb_contact_tracker_load(g, path, &loaded)) return 0;
    *vertices = gb_contact_tracker_vertices(loaded);
    int same = *vertices == gb_contact_tracker_vertices(built);
    for (int k = 0; same && k < SAMPLE_SIZE; k++) {
        gb_contact_node a, b;
        same = !gb_contact_tracker_find(built, s4_sample_zb[k], &a) && !gb_contact_tracker_find(loaded, s4_sample_zb[k], &b) &&
               a.index == b.index && !memcmp(&a.height, &b.height, sizeof a.height) && a.visited == b.visited;
    }
    gb_contact_tracker_free(loaded);
    return same;
}

/* 1 when loading `path` for grid g is refused with GB_EIO and a message containing `why`. */
static int hull_file_refused(const gb_contact_grid *g, const char *path, const char *why)
{
    gb_contact_tracker *t = NULL;
    const int status = gb_contact_tracker_load(g, path, &t);
    const int refused = status == GB_EIO && !t && strstr(gb_error_message(), why) != NULL;
    gb_error_clear();
    gb_contact_tracker_free(t);
    return refused;
}

static void test_hull_file(void)
{
    s4_draw_sample();
    char dir[GB_CHECK_TEMPDIR_SIZE];
    if (gb_check_tempdir("hull", dir, sizeof dir)) return;
    char path[320], other[320];
    snprintf(path, sizeof path, "%s/hull", dir);
    snprintf(other, sizeof other, "%s/hull-II", dir);
    /* Table 1's grids (centred) and the linspace placement, whose hull keeps coplanar nodes */
    for (int c = 0; c < 2; c++)
        for (int placement = 0; placement < 2; placement++) {
            gb_contact_grid_def def = gb_contact_grid_default_def();
            def.nodes = (gb_contact_nodes)placement;
            gb_contact_grid *g = NULL;
            gb_contact_tracker *t = NULL;
            size_t vertices = 0;
            const int same = !gb_contact_grid_create(gb_check_body(s4_cases[c].morphology, s4_cases[c].beta), &def, &g) &&
                             !gb_contact_tracker_create(g, &t) && hull_file_agrees(g, t, path, &vertices);
            char label[64], q[256];
            s4_case_label(c, label, sizeof label);
            snprintf(q, sizeof q, "tracker from its hull file == tracker Qhull built, 90 x 180 %s, %s, %d verticals",
                     gb_contact_nodes_name(def.nodes), label, SAMPLE_SIZE);
            gb_check check = {"8", "29", q, "the tracker Qhull built in the same process",
                              "exact: node, height bits and nodes visited of every vertical"};
            gb_check_true(&check, same, "%s; %zu hull vertices read", same ? "the same answers" : "DIFFERENT answers", vertices);
            gb_contact_tracker_free(t);
            gb_contact_grid_free(g);
        }
    /* A file is taken only for the grid it was written for, and whole */
    gb_contact_grid_def def = gb_contact_grid_default_def();
    gb_contact_grid *g1 = NULL, *g2 = NULL, *gb = NULL;
    gb_contact_tracker *t1 = NULL, *t2 = NULL;
    int refusals_ok = !gb_contact_grid_create(gb_check_body("I", 0.12), &def, &g1) &&
                      !gb_contact_grid_create(gb_check_body("II", 0.12), &def, &g2) &&
                      !gb_contact_grid_create(gb_check_body("I", 0.02), &def, &gb) && !gb_contact_tracker_create(g1, &t1) &&
                      !gb_contact_tracker_save(t1, path) && !gb_contact_tracker_create(g2, &t2) &&
                      !gb_contact_tracker_save(t2, other);
    const int other_body = refusals_ok && hull_file_refused(g2, path, "other grid nodes");
    const int other_beta = refusals_ok && hull_file_refused(gb, path, "other grid nodes");
    size_t bytes = 0;
    unsigned char *data = NULL;
    FILE *f = refusals_ok ? fopen(other, "rb") : NULL;
    if (f && !fseek(f, 0, SEEK_END) && (bytes = (size_t)ftell(f)) > 0 && !fseek(f, 0, SEEK_SET) && (data = malloc(bytes)))
        refusals_ok = fread(data, 1, bytes, f) == bytes;
    else
        refusals_ok = 0;
    if (f) fclose(f);
    int flipped = 0, truncated = 0, forged = 0;
    if (refusals_ok) {
        data[bytes / 2] ^= 0x10; /* one bit in the edge lists */
        f = fopen(other, "wb");
        refusals_ok = f && fwrite(data, 1, bytes, f) == bytes;
        if (f) fclose(f);
        flipped = refusals_ok && hull_file_refused(g2, other, "seal does not verify");
        /* the same bit, its digest recomputed as a forger without the key can (unkeyed BLAKE2b-256) */
        gb_seal_digest(&(gb_seal_piece){data, bytes - GB_SEAL_BYTES}, 1, data + bytes - GB_SEAL_BYTES);
        f = fopen(other, "wb");
        refusals_ok = refusals_ok && f && fwrite(data, 1, bytes, f) == bytes;
        if (f) fclose(f);
        forged = refusals_ok && hull_file_refused(g2, other, "seal does not verify");
        if (refusals_ok) refusals_ok = !gb_seal_compute(&(gb_seal_piece){data, bytes - GB_SEAL_BYTES}, 1, data + bytes - GB_SEAL_BYTES);
        data[bytes / 2] ^= 0x10;
        f = fopen(other, "wb");
        refusals_ok = refusals_ok && f && fwrite(data, 1, bytes - 4, f) == bytes - 4;
        if (f) fclose(f);
        truncated = refusals_ok && hull_file_refused(g2, other, "does not match");
    }
    free(data);
    char absent[320];
    snprintf(absent, sizeof absent, "%s/absent", dir);
    const int missing = hull_file_refused(g2, dir, "hull file refused") && hull_file_refused(g2, absent, "hull file refused");
    gb_check cr = {"8", "29", "a hull file is refused for another body or beta, with one bit flipped, with a bit flipped "
                   "and its digest recomputed without the key, cut short, a directory or missing",
                   "the grid the file was written for; its seal (keyed BLAKE2b-256) and size", "exact: every one refused with its reason"};
    gb_check_true(&cr, other_body && other_beta && flipped && forged && truncated && missing,
                  "other body %s, other beta %s, a bit flipped %s, forged %s, 4 bytes short %s, a directory and a missing file %s",
                  other_body ? "refused" : "TAKEN", other_beta ? "refused" : "TAKEN", flipped ? "refused" : "TAKEN",
                  forged ? "refused" : "TAKEN", truncated ? "refused" : "TAKEN", missing ? "refused" : "TAKEN");
    gb_contact_tracker_free(t1), gb_contact_tracker_free(t2);
    gb_contact_grid_free(g1), gb_contact_grid_free(g2), gb_contact_grid_free(gb);
    remove(path), remove(other), gb_check_tempdir_remove(dir);
}

int verify_register_s4_grid(void)
{
    static const verify_test tests[] = {
        {"eq 29: grid nodes where documented; every bad input refused", test_grid_nodes_and_errors, NULL},
        {"eq 29: the lowest node but one or two against brute force", test_lowest_except,
         "the next node a grid body meets the plane with is the lowest of the nodes it does not stand on"},
        {"eq 29: the exact fast grid search returns the brute-force node", test_fast_equals_brute,
         "the fast grid search returns the paper's brute-force node, bit for bit and with the same "
         "tie-break, for 10⁴ random verticals per body, β and node placement"},
        {"eq 29: the tracker's hull file gives the tracker Qhull builds", test_hull_file,
         "a hull read from its file (gomboc run --hull) answers every vertical as the hull Qhull builds, and a "
         "file written for any other grid, damaged or cut short is refused"},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Section 4: the grid search (eq 29)", tests);
}
