/* The piecewise structure of H on one cell of q, proved from the cell's kept boxes (docs/proofs.md).
 *
 * Every maximiser of x·v(q), q in the cell, lies in a kept box of every chart region that holds it (a box holding one is
 * never dropped). The kept boxes are first brought into one chart: cap boxes whose directions all lie in the equator's
 * region are dropped (the equator's boxes hold their maximisers), or else equator boxes lying in one cap's region; if
 * two regions remain, nothing is proved. Within the chart the boxes fall into components (boxes that touch); on each
 * component's hull box the interval Hessian of x·v over the cell's directions must be negative definite (x·v strictly
 * concave there: at most one critical point, and the surface C² on it). Two regions that cannot be brought into one keep
 * their own boxes, components formed within each:
 * - one component: the maximiser is unique for every q, a nondegenerate critical point, so by the implicit function
 *   theorem it moves smoothly and H is C² on the cell;
 * - two: H = max(h_A, h_B), h_X the largest x·v over component X, each C² where it is the larger (its maximiser is then
 *   the global one, unique in X), and h_A − h_B has its derivative in (x(A) − x(B))·v′ wherever it exists; when that
 *   interval excludes 0 the difference is strictly monotone: at most one tie in the cell, where only H′ jumps (H is a
 *   support function: continuous);
 * - otherwise: not proved. */
#include "gb_proof_body_ties_internal.h"

#include "gb_certify_internal.h"

#include <math.h>
#include <stdlib.h>

/* cos 0.8 and cos 0.75 rounded down: the equator's region is |u_z| ≤ cos 0.8, a cap's |u_x| ≤ cos 0.75 and
 * |u_y| ≤ cos 0.75 sin α with u_z of the cap's sign (gb_certify_internal.h's cover). */
#define EQUATOR_BOUND 0.6967067
#define CAP_BOUND 0.7316888

enum { COMPONENTS_MAX = 2 };

/* u over a box of its chart. */
static void box_direction(const pbox *b, gb_interval u[3])
{
    const gb_interval A = gb_interval_make(b->a_lo, b->a_hi), B = gb_interval_make(b->b_lo, b->b_hi);
    const gb_interval sa = gb_interval_sin(A), ca = gb_interval_cos(A), sb = gb_interval_sin(B), cb = gb_interval_cos(B);
    if (b->region == GB_REGION_EQUATOR) {
        u[0] = gb_interval_mul(sa, cb), u[1] = gb_interval_mul(sa, sb), u[2] = ca;
    } else {
        u[0] = ca, u[1] = gb_interval_mul(sa, cb), u[2] = gb_interval_mul(sa, sb);
    }
}

/* The region other than the box's own whose range holds every direction of the box: the equator's for a cap box, a
 * cap's for an equator box; −1 when none is proved. */
static int also_in(const pbox *b)
{
    gb_interval u[3];
    box_direction(b, u);
    if (b->region != GB_REGION_EQUATOR) return gb_interval_mag(u[2]) <= EQUATOR_BOUND ? GB_REGION_EQUATOR : -1;
    const gb_interval sin_alpha = gb_interval_sqrt(gb_interval_sub(gb_interval_point(1.0), gb_interval_sqr(u[0])));
    if (!(gb_interval_mag(u[0]) <= CAP_BOUND && gb_interval_mag(u[1]) <= gb_interval_down(CAP_BOUND * sin_alpha.lo))) return -1;
    return u[2].lo > 0.0 ? GB_REGION_NORTH : u[2].hi < 0.0 ? GB_REGION_SOUTH : -1;
}

/* The kept boxes of one region that hold every maximiser (indices in `pick`), or 0 when two regions remain. */
static size_t one_chart(const boxes *kept, size_t *pick, int *region)
{
    for (int option = 0; option < 2; option++) {
        size_t n = 0;
        int seen = -1, mixed = 0;
        for (size_t k = 0; k < kept->n; k++) {
            const pbox *b = &kept->at[k];
            const int equator = b->region == GB_REGION_EQUATOR;
            /* option 0 prefers the equator: a cap box in its region goes; option 1 prefers a cap */
            if (option == 0 ? !equator && also_in(b) == GB_REGION_EQUATOR : equator && also_in(b) >= 0) continue;
            if (seen >= 0 && seen != b->region) mixed = 1;
            seen = b->region;
            pick[n++] = k;
        }
        if (!mixed && n > 0) {
            *region = seen;
            return n;
        }
    }
    return 0;
}

static size_t find(size_t *parent, size_t k)
{
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
}

static int touch(const double x[4], const double y[4])
{
    return x[0] <= y[1] && y[0] <= x[1] && x[2] <= y[3] && y[2] <= x[3];
}

gb_proof_body_piece gb_proof_body_structure(const gb_surface *surface, const gb_proof_axes *axes, const boxes *kept,
                                            double q_lo, double q_hi, gb_proof_body_hull hulls[2])
{
    size_t *pick = malloc(kept->n * sizeof *pick), *parent = malloc(kept->n * sizeof *parent);
    double (*box)[4] = malloc(kept->n * sizeof *box);
    gb_proof_body_piece result = GB_PROOF_BODY_OPEN;
    int region = -1;
    size_t n = pick && parent && box ? one_chart(kept, pick, &region) : 0;
    if (n == 0 && pick && parent && box) /* two regions: each keeps its boxes (two contacts, one in each, may be a tie) */
        for (n = 0; n < kept->n; n++) pick[n] = n;
    if (n == 0) goto done;
    /* the equator's longitude is periodic: a component across b = 0 is moved to one side */
    int low = 0, high = 0;
    for (size_t i = 0; i < n; i++) {
        const pbox *b = &kept->at[pick[i]];
        if (b->region == GB_REGION_EQUATOR) low |= b->b_lo <= 0.0, high |= b->b_hi >= 2.0 * GB_INTERVAL_PI;
    }
    for (size_t i = 0; i < n; i++) {
        const pbox *b = &kept->at[pick[i]];
        const double shift = b->region == GB_REGION_EQUATOR && low && high && b->b_lo >= GB_INTERVAL_PI ? 2.0 * GB_INTERVAL_PI : 0.0;
        box[i][0] = b->a_lo, box[i][1] = b->a_hi, box[i][2] = b->b_lo - shift, box[i][3] = b->b_hi - shift;
        parent[i] = i;
    }
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++)
            if (kept->at[pick[i]].region == kept->at[pick[j]].region && touch(box[i], box[j])) parent[find(parent, i)] = find(parent, j);
    /* the components' hulls */
    double hull[COMPONENTS_MAX][4];
    size_t roots[COMPONENTS_MAX], count = 0;
    int regions[COMPONENTS_MAX];
    for (size_t i = 0; i < n; i++) {
        const size_t root = find(parent, i);
        size_t c = 0;
        while (c < count && roots[c] != root) c++;
        if (c == count) {
            if (count == COMPONENTS_MAX) goto done;
            roots[count] = root;
            regions[count] = kept->at[pick[i]].region;
            for (int k = 0; k < 4; k++) hull[count][k] = box[i][k];
            count++;
            continue;
        }
        hull[c][0] = fmin(hull[c][0], box[i][0]), hull[c][1] = fmax(hull[c][1], box[i][1]);
        hull[c][2] = fmin(hull[c][2], box[i][2]), hull[c][3] = fmax(hull[c][3], box[i][3]);
    }
    gb_interval v[3], dv[3];
    gb_proof_body_directions(axes, q_lo, q_hi, v, dv);
    gb_surface_enclosure e[COMPONENTS_MAX];
    for (size_t c = 0; c < count; c++) {
        gb_surface_enclose(surface, gb_region_chart(regions[c]), hull[c][0], hull[c][1], hull[c][2], hull[c][3], &e[c]);
        const gb_interval haa = gb_proof_body_dot(e[c].x_aa, v), hab = gb_proof_body_dot(e[c].x_ab, v),
                          hbb = gb_proof_body_dot(e[c].x_bb, v);
        const gb_interval det = gb_interval_sub(gb_interval_mul(haa, hbb), gb_interval_sqr(hab));
        if (!(e[c].smooth && haa.hi < 0.0 && det.lo > 0.0)) goto done;
    }
    for (size_t c = 0; c < count && hulls; c++) {
        hulls[c].region = regions[c];
        for (int k = 0; k < 4; k++) hulls[c].box[k] = hull[c][k];
    }
    if (count == 1) {
        result = GB_PROOF_BODY_SMOOTH;
    } else {
        gb_interval d[3];
        for (int k = 0; k < 3; k++) d[k] = gb_interval_sub(e[0].x[k], e[1].x[k]);
        const gb_interval slope = gb_proof_body_dot(d, dv);
        if (slope.lo > 0.0 || slope.hi < 0.0) result = GB_PROOF_BODY_TIE;
    }
done:
    free(pick), free(parent), free(box);
    return result;
}
