/* gb_proof_conley_henon — Hénon's maps for the discrete Conley index (see gb_proof_conley.h): at a = 6 on a whole grid,
 * and the classical map from its periodic points' boxes. */
#include "gb_proof_conley.h"
#include "gb_proof_conley_grid_internal.h"
#include "gb_proof_cover.h"

#include "gb_error.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int gb_proof_conley_henon_horseshoe(int depth, gb_proof_field *field, gb_proof_conley_def *def, uint32_t **n_boxes,
                                    size_t *n)
{
    *n_boxes = NULL, *n = 0;
    *field = gb_proof_cover_henon(6, 1, 3, 10);
    *def = gb_proof_conley_def_default();
    def->map = field, def->depth = depth, def->x = (gb_proof_interval){-1.0, 1.0},
    def->y = (gb_proof_interval){-1.0, 1.0};
    if (depth < GB_PROOF_CONLEY_DEPTH_MIN || depth > GB_PROOF_CONLEY_DEPTH_MAX)
        return gb_error_set(GB_EDOM, "depth = %d is out of range (allowed: %d to %d)", depth, GB_PROOF_CONLEY_DEPTH_MIN,
                            GB_PROOF_CONLEY_DEPTH_MAX);
    const long side = 1L << depth;
    *n_boxes = malloc((size_t)(side * side) * sizeof **n_boxes);
    if (!*n_boxes) return gb_error_set(GB_ENOMEM, "out of memory for N");
    for (long j = 1; j < side - 1; j++)
        for (long i = 1; i < side - 1; i++) (*n_boxes)[(*n)++] = (uint32_t)(j * side + i);
    return GB_OK;
}

/* H^p(x) − x = 0 by Newton in doubles from x; 1 with x the point when it converges to a point of least period p. */
static int periodic_point(double a, double b, int p, double x[2])
{
    for (int it = 0; it < 60; it++) {
        double y[2] = {x[0], x[1]}, J[2][2] = {{1.0, 0.0}, {0.0, 1.0}};
        for (int k = 0; k < p; k++) {
            const double D[2][2] = {{-2.0 * a * y[0], 1.0}, {b, 0.0}};
            const double M[2][2] = {{D[0][0] * J[0][0] + D[0][1] * J[1][0], D[0][0] * J[0][1] + D[0][1] * J[1][1]},
                                    {D[1][0] * J[0][0] + D[1][1] * J[1][0], D[1][0] * J[0][1] + D[1][1] * J[1][1]}};
            memcpy(J, M, sizeof J);
            const double next[2] = {1.0 - a * y[0] * y[0] + y[1], b * y[0]};
            y[0] = next[0], y[1] = next[1];
            if (!(fabs(y[0]) < 10.0 && fabs(y[1]) < 10.0)) return 0;
        }
        const double A[2][2] = {{J[0][0] - 1.0, J[0][1]}, {J[1][0], J[1][1] - 1.0}}, r[2] = {y[0] - x[0], y[1] - x[1]};
        const double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
        if (!(fabs(det) > 1e-12)) return 0;
        const double dx[2] = {-(A[1][1] * r[0] - A[0][1] * r[1]) / det, -(A[0][0] * r[1] - A[1][0] * r[0]) / det};
        x[0] += dx[0], x[1] += dx[1];
        if (hypot(dx[0], dx[1]) < 1e-13) {
            double z[2] = {x[0], x[1]};
            for (int k = 1; k < p; k++) { /* least period p: no earlier return */
                const double next[2] = {1.0 - a * z[0] * z[0] + z[1], b * z[0]};
                z[0] = next[0], z[1] = next[1];
                if (hypot(z[0] - x[0], z[1] - x[1]) < 1e-9) return 0;
            }
            return 1;
        }
    }
    return 0;
}

/* The orbits found: their least periods, least x and points (x, y pairs, period of them each). */
typedef struct henon_orbits {
    size_t count, room, points, point_room;
    int *period;
    double *least_x, *xy;
    size_t *first; /* the orbit's first point in xy */
} henon_orbits;

static void orbits_free(henon_orbits *o) { free(o->period), free(o->least_x), free(o->xy), free(o->first); }

/* The orbit through x (least period p) added unless one of its period with least x within 1e-9 is there (Newton
 * stops at a step below 1e-13; distinct orbits of one period up to 16 differ in least x by 5.2e-5 at the least). */
static int orbits_add(henon_orbits *o, double a, double b, int p, const double x[2])
{
    double z[2] = {x[0], x[1]}, least = x[0];
    for (int k = 1; k < p; k++) {
        const double next[2] = {1.0 - a * z[0] * z[0] + z[1], b * z[0]};
        z[0] = next[0], z[1] = next[1];
        least = fmin(least, z[0]);
    }
    for (size_t k = 0; k < o->count; k++)
        if (o->period[k] == p && fabs(o->least_x[k] - least) < 1e-9) return GB_OK;
    if (o->count == o->room) {
        const size_t room = o->room ? 2 * o->room : 64;
        int *period = realloc(o->period, room * sizeof *period);
        if (period) o->period = period;
        double *least_x = realloc(o->least_x, room * sizeof *least_x);
        if (least_x) o->least_x = least_x;
        size_t *first = realloc(o->first, room * sizeof *first);
        if (first) o->first = first;
        if (!period || !least_x || !first) return gb_error_set(GB_ENOMEM, "out of memory for the periodic orbits");
        o->room = room;
    }
    if (o->points + (size_t)p > o->point_room) {
        const size_t room = 2 * (o->point_room + (size_t)p);
        double *xy = realloc(o->xy, 2 * room * sizeof *xy);
        if (!xy) return gb_error_set(GB_ENOMEM, "out of memory for the periodic orbits");
        o->xy = xy, o->point_room = room;
    }
    o->period[o->count] = p, o->least_x[o->count] = least, o->first[o->count] = o->points;
    z[0] = x[0], z[1] = x[1];
    for (int k = 0; k < p; k++) {
        o->xy[2 * o->points] = z[0], o->xy[2 * o->points + 1] = z[1], o->points++;
        const double next[2] = {1.0 - a * z[0] * z[0] + z[1], b * z[0]};
        z[0] = next[0], z[1] = next[1];
    }
    o->count++;
    return GB_OK;
}

int gb_proof_conley_henon_classical(int period_max, int depth, gb_proof_field *field, gb_proof_conley_def *def,
                                    uint32_t **seeds, size_t *count)
{
    return gb_proof_conley_henon_orbits(period_max, NULL, 0, depth, field, def, seeds, count);
}

int gb_proof_conley_henon_orbits(int period_max, const gb_proof_conley_orbit *toggle, size_t toggles, int depth,
                                 gb_proof_field *field, gb_proof_conley_def *def, uint32_t **seeds, size_t *count)
{
    *seeds = NULL, *count = 0;
    *field = gb_proof_cover_henon(7, 5, 3, 10);
    *def = gb_proof_conley_def_default();
    def->map = field, def->depth = depth, def->x = (gb_proof_interval){-2.0, 2.0},
    def->y = (gb_proof_interval){-1.0, 1.0};
    def->region_dimension = GB_PROOF_CONLEY_REGION_DIMENSION_MAX;
    if (depth < GB_PROOF_CONLEY_DEPTH_MIN || depth > GB_PROOF_CONLEY_DEPTH_MAX)
        return gb_error_set(GB_EDOM, "depth = %d is out of range (allowed: %d to %d)", depth, GB_PROOF_CONLEY_DEPTH_MIN,
                            GB_PROOF_CONLEY_DEPTH_MAX);
    if (period_max < 1 || period_max > GB_PROOF_CONLEY_PERIOD_MAX)
        return gb_error_set(GB_EDOM, "period_max = %d is out of range (allowed: 1 to %d)", period_max,
                            GB_PROOF_CONLEY_PERIOD_MAX);
    if (toggles && !toggle) return gb_error_set(GB_EINVAL, "toggle is NULL with %zu orbits named", toggles);
    int longest = period_max;
    for (size_t t = 0; t < toggles; t++) {
        if (toggle[t].period < 1 || toggle[t].period > GB_PROOF_CONLEY_PERIOD_MAX || !isfinite(toggle[t].x))
            return gb_error_set(GB_EDOM,
                                "toggle[%zu]: period %d, least x %g is out of range (allowed: periods 1 to %d, "
                                "x finite)",
                                t, toggle[t].period, toggle[t].x, GB_PROOF_CONLEY_PERIOD_MAX);
        if (toggle[t].period > longest) longest = toggle[t].period;
    }
    enum { STARTS = 4000 };
    const double a = 1.4, b = 0.3;
    henon_orbits found = {0};
    double o[2] = {0.1, 0.1};
    for (int k = 0; k < 1000; k++) { /* onto the attractor */
        const double next[2] = {1.0 - a * o[0] * o[0] + o[1], b * o[0]};
        o[0] = next[0], o[1] = next[1];
    }
    for (int s = 0; s < STARTS; s++) {
        for (int k = 0; k < 7; k++) { /* the starts: every 7th point of the orbit */
            const double next[2] = {1.0 - a * o[0] * o[0] + o[1], b * o[0]};
            o[0] = next[0], o[1] = next[1];
        }
        for (int p = 1; p <= longest; p++) {
            double x[2] = {o[0], o[1]};
            if (!periodic_point(a, b, p, x)) continue;
            const int status = orbits_add(&found, a, b, p, x);
            if (status) return orbits_free(&found), status;
        }
    }
    /* the orbits kept: periods up to period_max, each named one toggled */
    char *keep = calloc(found.count ? found.count : 1, 1);
    if (!keep) return orbits_free(&found), gb_error_set(GB_ENOMEM, "out of memory for the periodic orbits");
    for (size_t k = 0; k < found.count; k++) keep[k] = found.period[k] <= period_max;
    for (size_t t = 0; t < toggles; t++) {
        size_t match = found.count, matches = 0;
        for (size_t k = 0; k < found.count; k++)
            if (found.period[k] == toggle[t].period && fabs(found.least_x[k] - toggle[t].x) <= 1e-6)
                match = k, matches++;
        if (matches != 1) {
            free(keep), orbits_free(&found);
            return gb_error_set(GB_EDOM,
                                "toggle[%zu]: %zu periodic orbits of least period %d have their least x within "
                                "1e-6 of %.9f (allowed: exactly one)",
                                t, matches, toggle[t].period, toggle[t].x);
        }
        keep[match] = !keep[match];
    }
    const long side = 1L << depth;
    uint32_t *list = malloc((found.points ? found.points : 1) * sizeof *list);
    if (!list) return free(keep), orbits_free(&found), gb_error_set(GB_ENOMEM, "out of memory for the seeds");
    for (size_t k = 0; k < found.count; k++) {
        if (!keep[k]) continue;
        for (int q = 0; q < found.period[k]; q++) { /* the orbit's boxes */
            const double *x = found.xy + 2 * (found.first[k] + (size_t)q);
            const long i = (long)floor((x[0] + 2.0) / 4.0 * (double)side),
                       j = (long)floor((x[1] + 1.0) / 2.0 * (double)side);
            if (i > 0 && j > 0 && i < side - 1 && j < side - 1) list[(*count)++] = (uint32_t)(j * side + i);
        }
    }
    free(keep), orbits_free(&found);
    qsort(list, *count, sizeof *list, conley_compare_boxes);
    size_t unique = 0;
    for (size_t k = 0; k < *count; k++)
        if (!unique || list[unique - 1] != list[k]) list[unique++] = list[k];
    *seeds = list, *count = unique;
    return GB_OK;
}
