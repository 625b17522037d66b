/* gb_dynamics_faces — a face of a polyhedron meeting the plane: several nodes reaching it at once.
 *
 * A body rolling on an edge PQ of a polyhedron turns about PQ, so the face through PQ that lands next lands
 * flat: all its vertices reach the plane at the same instant (Housner's block rocking onto its other edge, a
 * die falling onto a face, a coin onto its flat side). The third-point event locates the first of them, R;
 * the others are found here (heights within GB_DYN_FACE_TIE body lengths of R's, far below any length of
 * a mesh and far above the rounding of a located event). Only a mesh's polyhedron has faces made flat: the
 * grid of a smooth body samples a curved surface, whose nodes near a pole can lie within 1e-14 of one plane
 * without being a face (Gömböc I at β = 0.02 rolls onto twelve such nodes of its pole ring); there every
 * node that reaches the plane is an impact of its own, in the order they come (gb_dynamics_jumps.c),
 * unchanged.
 *
 * The impact over the whole face is Moreau's law at P, Q and the two vertices R', S' of the landed face
 * farthest from the line PQ (its far edge; for a single farthest vertex, it and the tied vertex farthest from
 * it): the normal velocity after is affine over the face, so where it is ≥ 0 at the face's extreme vertices
 * it is ≥ 0 at all of them — which is checked at every tied vertex after the impact. Its outcomes:
 * R' and S' hold while P and Q lift: the body rolls on the far edge (two points); all hold, or P and Q would
 * fall back within the settle time: the body stops on the face, at rest where the centroid's foot is inside
 * it. Any other outcome is not followed: the run stops saying so (exit 1). On a plane of finite friction a face
 * landing is not followed either (gb_dyn_face_ties lets the friction path stop): its impact law (gb_impact_coulomb
 * through gb_dyn_friction_impact) takes three points, and one vertex of the landing edge alone would break the
 * face's symmetry (Housner's block at mu = 0.6 chattered through 233 impacts where the rough plane has 12). */
#include "gb_dynamics_internal.h"

#include "gb_contact.h"
#include "gb_error.h"
#include "gb_impact.h"
#include "gb_vec.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

/* Nodes this close to R's height [body lengths] land with it. */
#define GB_DYN_FACE_TIE 1e-10

enum { FACE_MAX = 4 };

static double dist_to_line(const double p[3], const double a[3], const double b[3])
{
    double ab[3], ap[3], c[3];
    for (int k = 0; k < 3; k++) ab[k] = b[k] - a[k], ap[k] = p[k] - a[k];
    gb_vec_cross(ab, ap, c);
    return gb_vec_norm(c) / gb_vec_norm(ab);
}

static double dist2(const double a[3], const double b[3])
{
    double s = 0.0;
    for (int k = 0; k < 3; k++) s += (a[k] - b[k]) * (a[k] - b[k]);
    return s;
}

/* Is the centroid's foot (the origin projected along zb) inside the convex polygon of the n points [m] on
 * the plane, to `tol` [m]? The points are in any order: the foot is inside when no line through two of them
 * has every point on one side and the foot beyond it. */
static int foot_inside(const double zb[3], const double (*pts)[3], int n, double tol)
{
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            if (i == j) continue;
            double e[3], c[3], side = 0.0;
            for (int k = 0; k < 3; k++) e[k] = pts[j][k] - pts[i][k];
            int all = 1;
            for (int m = 0; m < n && all; m++) {
                double w[3];
                for (int k = 0; k < 3; k++) w[k] = pts[m][k] - pts[i][k];
                gb_vec_cross(e, w, c);
                if (gb_vec_dot(zb, c) < -tol * gb_vec_norm(e)) all = 0;
            }
            if (!all) continue; /* not an edge with the polygon on its left */
            const double g[3] = {-pts[i][0], -pts[i][1], -pts[i][2]};
            gb_vec_cross(e, g, c);
            side = gb_vec_dot(zb, c);
            if (side < -tol * gb_vec_norm(e)) return 0;
        }
    return 1;
}

/* Does node i reach the plane with R (its height within GB_DYN_FACE_TIE of R's, h_r)? Its position [m] into x. */
static int tied(const gb_dynamics *d, const double zb[3], double h_r, size_t i, double x[3])
{
    gb_contact_grid_node(d->grid, i, NULL, NULL, x);
    const int tie = gb_vec_dot(zb, x) - h_r <= GB_DYN_FACE_TIE;
    for (int k = 0; k < 3; k++) x[k] *= d->def.length;
    return tie;
}

int gb_dyn_face_ties(const gb_dynamics *d, const double zb[3], const gb_contact_point *p, const gb_contact_point *q,
                     const gb_contact_point *third)
{
    if (!gb_surface_is_polyhedron(&d->surface) || !d->grid) return 0;
    const double h_r = gb_vec_dot(zb, third->rc);
    const size_t n = gb_contact_grid_size(d->grid);
    int ties = 0;
    double x[3];
    for (size_t i = 0; i < n; i++) ties += i != third->node && i != p->node && i != q->node && tied(d, zb, h_r, i, x);
    return ties;
}

int gb_dyn_face_landing(gb_dynamics *d, double t, double y[GB_STATE_SIZE], const gb_dyn_two_point *tp,
                        const gb_contact_point *third, int *handled)
{
    *handled = 0;
    if (!gb_surface_is_polyhedron(&d->surface) || !d->grid) return GB_OK;
    const double L = d->def.length;
    double zb[3];
    gb_dyn_vertical(y, zb);
    const double h_r = gb_vec_dot(zb, third->rc);
    const size_t n = gb_contact_grid_size(d->grid), stands[2] = {tp->p.point.node, tp->q.node};
    /* the tied nodes, R first; the far edge among them */
    size_t far[2] = {third->node, SIZE_MAX}, ties = 0;
    double rr[3], best = 0.0;
    for (int k = 0; k < 3; k++) rr[k] = L * third->rc[k];
    best = dist_to_line(rr, tp->rp, tp->rq);
    for (size_t i = 0; i < n; i++) {
        double x[3], a[3], b[3];
        if (i == third->node || i == stands[0] || i == stands[1] || !tied(d, zb, h_r, i, x)) continue;
        ties++;
        const double dl = dist_to_line(x, tp->rp, tp->rq);
        if (dl > best * (1.0 + 1e-9)) best = dl, far[0] = i, far[1] = SIZE_MAX;
        else if (dl >= best * (1.0 - 1e-9)) { /* on the far edge too: keep the two farthest apart */
            tied(d, zb, h_r, far[0], a);
            if (far[1] == SIZE_MAX) far[1] = i;
            else if (tied(d, zb, h_r, far[1], b), dist2(x, a) > dist2(a, b)) far[1] = i;
        }
    }
    if (!ties) return GB_OK;
    *handled = 1;
    if (far[1] == SIZE_MAX) { /* one farthest vertex: the tied vertex farthest from it beside it */
        double a[3], x[3], most = -1.0;
        tied(d, zb, h_r, far[0], a);
        for (size_t i = 0; i < n; i++)
            if (i != far[0] && i != stands[0] && i != stands[1] && tied(d, zb, h_r, i, x) && dist2(x, a) > most)
                most = dist2(x, a), far[1] = i;
    }
    gb_contact_point r_pt, s_pt;
    gb_dyn_grid_point(d, far[0], zb, &r_pt);
    gb_dyn_grid_point(d, far[1], zb, &s_pt);
    double pts[FACE_MAX][3];
    for (int k = 0; k < 3; k++)
        pts[0][k] = tp->rp[k], pts[1][k] = tp->rq[k], pts[2][k] = L * r_pt.rc[k], pts[3][k] = L * s_pt.rc[k];
    gb_impact_body body = {d->def.mass, {{0}}};
    memcpy(body.inertia, d->inertia, sizeof body.inertia);
    double v[3];
    const double arm[3] = {-tp->rp[0], -tp->rp[1], -tp->rp[2]}; /* G − P: the body turns about PQ */
    gb_vec_cross(y + GB_STATE_OMEGA, arm, v);
    gb_impact_result r;
    int status = gb_impact_solve(&body, zb, 0.0, (const double(*)[3])pts, FACE_MAX, v, y + GB_STATE_OMEGA, &r);
    if (status)
        return gb_error_set(GB_ENUMERIC, "a face of %zu vertices lands at t = %.9g: %s", ties + 3, t, gb_error_message());
    /* by the points' normal velocities after (a set of three may already stop the body, the fourth held
     * with no impulse: Moreau's smallest set) */
    const double vscale = 1e-9 * sqrt(fabs(gb_forcing_geff(&d->def.forcing, t)) * L + gb_vec_dot(v, v));
    int still[FACE_MAX];
    for (int k = 0; k < FACE_MAX; k++) {
        double u[3];
        gb_vec_cross(r.omega, pts[k], u);
        still[k] = fabs(gb_vec_dot(zb, r.v) + gb_vec_dot(zb, u)) <= vscale;
    }
    int settled = 0, on_face = still[0] && still[1] && still[2] && still[3];
    const int far_edge = !still[0] && !still[1] && still[2] && still[3];
    double back = INFINITY;
    if (far_edge) { /* the settle rule: P or Q falling back within the settle time stops the body on the face */
        double yafter[GB_STATE_SIZE];
        memcpy(yafter, y, sizeof yafter);
        memcpy(yafter + GB_STATE_OMEGA, r.omega, sizeof r.omega);
        back = fmin(gb_dyn_return_time(d, t, yafter, &r_pt, r.v, pts[0]), gb_dyn_return_time(d, t, yafter, &r_pt, r.v, pts[1]));
        if (back < d->settle_time) {
            status = gb_impact_hold_all(&body, zb, (const double(*)[3])pts, FACE_MAX, v, y + GB_STATE_OMEGA, &r);
            if (status) return status;
            on_face = settled = 1;
        }
    }
    if (!far_edge && !on_face)
        return gb_error_set_limit(GB_ENUMERIC, "a face of %zu vertices lands at t = %.9g and the impact holds neither the whole face "
                                  "nor its far edge, which is not followed (the body would pivot on one vertex of a flat face)",
                                  ties + 3, t);
    /* every tied vertex leaves the plane or stays on it after the impact */
    for (size_t i = 0; i < n; i++) {
        double x[3], u[3];
        if (!tied(d, zb, h_r, i, x)) continue;
        gb_vec_cross(r.omega, x, u);
        const double un = gb_vec_dot(zb, r.v) + gb_vec_dot(zb, u);
        if (un < -vscale)
            return gb_error_set_limit(GB_ENUMERIC, "a face of %zu vertices lands at t = %.9g: after the impact at its extreme "
                                      "vertices, vertex (%.6g, %.6g, %.6g) m moves into the plane at %.3g m/s (not followed)",
                                      ties + 3, t, x[0], x[1], x[2], un);
    }
    if (!settled) status = gb_dyn_plane_pushes(d, t, &r, (const double(*)[3])pts, FACE_MAX, 2, 0, v, y + GB_STATE_OMEGA);
    if (status) return status;
    gb_dynamics_impact e = {.t = t, .located = 1, .kind = GB_DYNAMICS_IMPACT_THIRD, .contacts_after = on_face ? 3 : 2,
                            .settled = settled, .return_time = back};
    gb_dyn_record(&e, y, pts[0], pts[2], v, &r, 2, 0);
    if (on_face) {
        if (!foot_inside(zb, (const double(*)[3])pts, FACE_MAX, 1e-9 * L))
            return gb_error_set_limit(GB_ENUMERIC, "a face lands at t = %.9g and stops the body with its centroid's foot outside "
                                      "it: the tip over the face's edge from rest is not followed", t);
        gb_dyn_set_mode(d, GB_DYN_REST, t);
        gb_dyn_set_contact(d, &r_pt);
        d->contact2 = s_pt;
    } else {
        gb_dyn_set_contact(d, &r_pt);
        d->contact2 = s_pt;
        d->crease.q_valid = 0;
        d->crease.entries++;
    }
    return gb_dyn_book(d, &e);
}
