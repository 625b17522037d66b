/* gb_polyhedron — the convex hull of a mesh as a body, and its mass properties in closed form
 * (see gb_polyhedron.h). */
#include "gb_polyhedron.h"

#include "gb_error.h"

#include <libqhull_r/qhull_ra.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void gb_polyhedron_free(gb_polyhedron *p)
{
    if (!p) return;
    free(p->vertices);
    free(p->mesh_index);
    free(p->triangles);
    memset(p, 0, sizeof *p);
}

/* The hull of `points`; with `lines` (a mesh's), a point strictly inside it is a non-convex mesh. */
static int hull(const double *points, size_t count, const size_t *lines, const char *name, gb_polyhedron *out)
{
    memset(out, 0, sizeof *out);
    if (count < 4) return gb_error_set(GB_EINVAL, "%s: %zu points (allowed: at least 4, not in one plane)", name, count);
    double mean[3] = {0, 0, 0}, size = 0.0;
    for (size_t k = 0; k < count; k++)
        for (int i = 0; i < 3; i++) mean[i] += points[3 * k + i] / (double)count;
    for (size_t k = 0; k < count; k++) {
        const double d[3] = {points[3 * k] - mean[0], points[3 * k + 1] - mean[1], points[3 * k + 2] - mean[2]};
        size = fmax(size, sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    }
    if (!(size > 0.0) || !isfinite(size)) return gb_error_set(GB_EINVAL, "%s: every point is the same point (allowed: a body)", name);
    const double tol = GB_POLYHEDRON_FLAT * size;
    double *copy = malloc(3 * count * sizeof *copy);
    unsigned char *seen = calloc(count, 1);
    if (!copy || !seen) {
        free(copy), free(seen);
        return gb_error_set(GB_ENOMEM, "%s: out of memory for the hull", name);
    }
    memcpy(copy, points, 3 * count * sizeof *copy);
    FILE *errors = tmpfile();
    qhT qh_storage, *qh = &qh_storage;
    qh_zero(qh, errors);
    char command[64];
    snprintf(command, sizeof command, "qhull Qt Qc U%g", tol);
    const int exitcode = qh_new_qhull(qh, 3, (int)count, copy, False, command, NULL, errors);
    int status = GB_OK;
    if (exitcode == qh_ERRsingular || exitcode == qh_ERRprec)
        status = gb_error_set(GB_EINVAL, "%s: the points are flat, all within %.3g m of one plane (allowed: a body with volume)", name, tol);
    else if (exitcode)
        status = gb_error_set(GB_ENUMERIC, "%s: Qhull could not build the hull (code %d)", name, exitcode);
    size_t *vertex_of = NULL;
    if (!status) {
        vertex_of = malloc(count * sizeof *vertex_of);
        out->vertices = malloc(3 * (size_t)qh->num_vertices * sizeof *out->vertices);
        out->mesh_index = malloc((size_t)qh->num_vertices * sizeof *out->mesh_index);
        out->triangles = malloc(3 * (size_t)qh->num_facets * sizeof *out->triangles);
        if (!vertex_of || !out->vertices || !out->mesh_index || !out->triangles)
            status = gb_error_set(GB_ENOMEM, "%s: out of memory for the hull", name);
    }
    if (!status) {
        vertexT *vertex, **vertexp;
        facetT *facet;
        pointT *point, **pointp;
        /* the hull's vertices in the points' order */
        FORALLvertices seen[qh_pointid(qh, vertex->point)] = 1;
        for (size_t k = 0; k < count; k++) {
            if (!seen[k]) continue;
            vertex_of[k] = out->vertex_count;
            memcpy(out->vertices + 3 * out->vertex_count, points + 3 * k, 3 * sizeof *points);
            out->mesh_index[out->vertex_count++] = k;
        }
        FORALLfacets {
            size_t v[3];
            int nv = 0;
            FOREACHvertex_(facet->vertices) if (nv < 3) v[nv++] = vertex_of[qh_pointid(qh, vertex->point)];
            if (nv != 3 || qh_setsize(qh, facet->vertices) != 3) {
                status = gb_error_set(GB_ENUMERIC, "%s: Qhull returned a face that is not a triangle", name);
                break;
            }
            /* counter-clockwise seen from outside: along Qhull's outward normal */
            const double *a = out->vertices + 3 * v[0], *b = out->vertices + 3 * v[1], *c = out->vertices + 3 * v[2];
            const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
            if (n[0] * facet->normal[0] + n[1] * facet->normal[1] + n[2] * facet->normal[2] < 0.0) {
                const size_t swap = v[1];
                v[1] = v[2], v[2] = swap;
            }
            memcpy(out->triangles + 3 * out->triangle_count++, v, sizeof v);
            FOREACHpoint_(facet->coplanarset) seen[qh_pointid(qh, point)] = 2; /* on the hull's surface */
        }
        /* a mesh's point that is neither a vertex nor on a face lies inside: the mesh is not convex */
        for (size_t k = 0; !status && lines && k < count; k++)
            if (!seen[k]) {
                /* a point within tol of the surface that Qhull left out of every coplanar set is on the surface too */
                double depth = -INFINITY;
                FORALLfacets depth = fmax(depth, facet->normal[0] * points[3 * k] + facet->normal[1] * points[3 * k + 1] +
                                                     facet->normal[2] * points[3 * k + 2] + facet->offset);
                if (depth < -tol)
                    status = gb_error_set(GB_EINVAL, "%s:%zu: this vertex lies %.3g m inside the convex hull of the others: the mesh "
                                          "is not convex (allowed: a convex polyhedron; its contact with a plane is its hull's, so "
                                          "give the hull)", name, lines[k], -depth);
            }
    }
    out->size = size;
    free(vertex_of), free(copy), free(seen);
    qh_freeqhull(qh, !qh_ALL);
    int curlong, totlong;
    qh_memfreeshort(qh, &curlong, &totlong);
    if (errors) fclose(errors);
    if (status) gb_polyhedron_free(out);
    return status;
}

int gb_polyhedron_from_mesh(const gb_mesh *mesh, const char *name, gb_polyhedron *out)
{
    return hull(mesh->vertices, mesh->vertex_count, mesh->vertex_line, name, out);
}

int gb_polyhedron_from_points(const double *points, size_t count, const char *name, gb_polyhedron *out)
{
    return hull(points, count, NULL, name, out);
}

int gb_polyhedron_massprops(const gb_polyhedron *p, double mass, gb_massprops *out)
{
    memset(out, 0, sizeof *out);
    if (!(mass >= 1e-6 && mass <= 1e6)) return gb_error_set(GB_EDOM, "mass %g (allowed: 1e-06 <= mass <= 1000000 [kg])", mass);
    /* the apex: the vertices' mean, inside a convex body, so that the tetrahedra's sums cancel little */
    double o[3] = {0, 0, 0};
    for (size_t k = 0; k < p->vertex_count; k++)
        for (int i = 0; i < 3; i++) o[i] += p->vertices[3 * k + i] / (double)p->vertex_count;
    double volume = 0.0, first[3] = {0, 0, 0}, C[3][3] = {{0}}, scale = 0.0;
    for (size_t t = 0; t < p->triangle_count; t++) {
        double A[3][3]; /* columns a, b, c relative to the apex */
        for (int j = 0; j < 3; j++)
            for (int i = 0; i < 3; i++) A[i][j] = p->vertices[3 * p->triangles[3 * t + j] + i] - o[i];
        const double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) - A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                           A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
        volume += det / 6.0;
        scale += fabs(det) / 6.0;
        for (int i = 0; i < 3; i++) first[i] += det * (A[i][0] + A[i][1] + A[i][2]) / 24.0;
        /* det · A C₀ Aᵀ with C₀ = (1 + δ)/120: (Σ_j a_ij a_kj + (Σ_j a_ij)(Σ_j a_kj)) det / 120 */
        for (int i = 0; i < 3; i++)
            for (int k = 0; k < 3; k++)
                C[i][k] += det * (A[i][0] * A[k][0] + A[i][1] * A[k][1] + A[i][2] * A[k][2] +
                                  (A[i][0] + A[i][1] + A[i][2]) * (A[k][0] + A[k][1] + A[k][2])) / 120.0;
    }
    if (!(volume > 0.0)) return gb_error_set(GB_EINVAL, "the polyhedron's volume is %g (allowed: positive, faces turned outward)", volume);
    const double density = mass / volume, eps = 64.0 * DBL_EPSILON;
    double g[3];
    for (int i = 0; i < 3; i++) g[i] = first[i] / volume; /* the centroid relative to the apex */
    double Cg[3][3];
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++) Cg[i][k] = C[i][k] - volume * g[i] * g[k]; /* the covariance about the centroid */
    const double trace = Cg[0][0] + Cg[1][1] + Cg[2][2];
    out->mass = mass, out->density = density, out->volume = volume, out->volume_err = eps * scale;
    for (int i = 0; i < 3; i++) {
        out->centroid[i] = o[i] + g[i];
        out->centroid_err[i] = eps * p->size;
        for (int k = 0; k < 3; k++) {
            out->inertia[i][k] = density * ((i == k ? trace : 0.0) - Cg[i][k]);
            out->inertia_err[i][k] = eps * mass * p->size * p->size;
        }
    }
    return GB_OK;
}

/* The triangle's outward unit normal and whether the centroid's projection onto its plane lies in it
 * (barycentric coordinates all >= -tol). */
static int projects_inside(const gb_polyhedron *p, size_t t, const double c[3], double tol, double n[3])
{
    const double *a = p->vertices + 3 * p->triangles[3 * t], *b = p->vertices + 3 * p->triangles[3 * t + 1],
                 *d = p->vertices + 3 * p->triangles[3 * t + 2];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
    double m[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    const double len = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    if (!(len > 0.0)) return 0;
    for (int i = 0; i < 3; i++) n[i] = m[i] / len;
    const double e[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double depth = e[0] * n[0] + e[1] * n[1] + e[2] * n[2];
    const double q[3] = {e[0] - depth * n[0], e[1] - depth * n[1], e[2] - depth * n[2]}; /* the projection, from a */
    /* barycentric coordinates of q in (u, w), through the Gram matrix */
    const double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2], ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    const double uw = u[0] * w[0] + u[1] * w[1] + u[2] * w[2], qu = q[0] * u[0] + q[1] * u[1] + q[2] * u[2];
    const double qw = q[0] * w[0] + q[1] * w[1] + q[2] * w[2], det = uu * ww - uw * uw;
    const double s = (qu * ww - qw * uw) / det, r = (qw * uu - qu * uw) / det;
    /* tolerances as distances: a coordinate times the triangle's height over that edge */
    const double scale = tol / sqrt(fmax(uu, ww));
    return s >= -scale && r >= -scale && 1.0 - s - r >= -scale;
}

/* The distance from point q to the segment a–b. */
static double segment_distance(const double q[3], const double a[3], const double b[3])
{
    const double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e[3] = {q[0] - a[0], q[1] - a[1], q[2] - a[2]};
    const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    const double s = dd > 0.0 ? fmin(1.0, fmax(0.0, (e[0] * d[0] + e[1] * d[1] + e[2] * d[2]) / dd)) : 0.0;
    const double f[3] = {e[0] - s * d[0], e[1] - s * d[1], e[2] - s * d[2]};
    return sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
}

/* Is the centroid's projection onto the face of triangle t (the triangles of its normal) farther than tol
 * from the face's boundary, the edges that only one of those triangles has? */
static int clear_of_boundary(const gb_polyhedron *p, const double n[3], const double c[3], double tol)
{
    for (size_t t = 0; t < p->triangle_count; t++) {
        double m[3];
        projects_inside(p, t, c, 0.0, m);
        if (fabs(m[0] - n[0]) + fabs(m[1] - n[1]) + fabs(m[2] - n[2]) > 1e-9) continue;
        for (int k = 0; k < 3; k++) {
            const size_t va = p->triangles[3 * t + k], vb = p->triangles[3 * t + (k + 1) % 3];
            int shared = 0; /* the same edge, reversed, in another triangle of the face */
            for (size_t u = 0; u < p->triangle_count && !shared; u++) {
                if (u == t) continue;
                double mu[3];
                projects_inside(p, u, c, 0.0, mu);
                if (fabs(mu[0] - n[0]) + fabs(mu[1] - n[1]) + fabs(mu[2] - n[2]) > 1e-9) continue;
                for (int j = 0; j < 3 && !shared; j++)
                    shared = p->triangles[3 * u + j] == vb && p->triangles[3 * u + (j + 1) % 3] == va;
            }
            if (shared) continue;
            const double *a = p->vertices + 3 * va, *b = p->vertices + 3 * vb;
            const double e[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]}, depth = e[0] * n[0] + e[1] * n[1] + e[2] * n[2];
            const double q[3] = {c[0] - depth * n[0], c[1] - depth * n[1], c[2] - depth * n[2]};
            if (segment_distance(q, a, b) <= tol) return 0;
        }
    }
    return 1;
}

int gb_polyhedron_rest_faces(const gb_polyhedron *p, const double centroid[3], double (*normals)[3], size_t cap, size_t *count)
{
    *count = 0;
    const double tol = GB_POLYHEDRON_FLAT * p->size;
    double *found = malloc(3 * (p->triangle_count ? p->triangle_count : 1) * sizeof *found);
    if (!found) return gb_error_set(GB_ENOMEM, "out of memory for the rest faces");
    size_t n_found = 0;
    for (size_t t = 0; t < p->triangle_count; t++) {
        double n[3];
        if (!projects_inside(p, t, centroid, tol, n)) continue;
        int known = 0; /* a face of several coplanar triangles counts once */
        for (size_t k = 0; k < n_found && !known; k++)
            known = fabs(found[3 * k] - n[0]) + fabs(found[3 * k + 1] - n[1]) + fabs(found[3 * k + 2] - n[2]) <= 1e-9;
        if (known || !clear_of_boundary(p, n, centroid, tol)) continue; /* on an edge of the face: not a stable rest */
        memcpy(found + 3 * n_found++, n, sizeof n);
    }
    for (size_t k = 0; k < n_found && k < cap; k++) memcpy(normals[k], found + 3 * k, 3 * sizeof(double));
    *count = n_found;
    free(found);
    return GB_OK;
}
