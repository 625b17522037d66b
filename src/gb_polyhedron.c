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

/* A directed edge of a mesh's triangle, and the triangle's number. */
typedef struct directed_edge {
    size_t from, to, triangle;
} directed_edge;

static int edge_order(const void *a, const void *b)
{
    const directed_edge *x = a, *y = b;
    if (x->from != y->from) return x->from < y->from ? -1 : 1;
    return x->to < y->to ? -1 : x->to > y->to;
}

/* The signed volume and the area of the closed surface of `count` triangles [3 * count] over `vertices`, the
 * tetrahedra's apex at `apex` (inside, so that their sums cancel little). */
static void surface_sums(const double *vertices, const size_t *triangles, size_t count, const double apex[3], double *volume,
                         double *area)
{
    double v = 0.0, s = 0.0;
    for (size_t t = 0; t < count; t++) {
        const double *a = vertices + 3 * triangles[3 * t], *b = vertices + 3 * triangles[3 * t + 1],
                     *c = vertices + 3 * triangles[3 * t + 2];
        const double p[3] = {a[0] - apex[0], a[1] - apex[1], a[2] - apex[2]}, q[3] = {b[0] - apex[0], b[1] - apex[1], b[2] - apex[2]},
                     r[3] = {c[0] - apex[0], c[1] - apex[1], c[2] - apex[2]};
        v += (p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) + p[2] * (q[0] * r[1] - q[1] * r[0])) / 6.0;
        const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, w[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
        const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
        s += 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    *volume = v, *area = s;
}

/* Qhull's options, in the order tried: merged facets triangulated (Qt), coplanar points kept (Qc), points within
 * tol of a facet coplanar (U); then the same allowing the wide facets that merging nearly coplanar points makes
 * (Q12: a die written to 10 digits, a box with a corner raised 1e-11 m); then joggled input (QJ: simplicial
 * facets, never a precision error; the vertices we keep are the file's own, unjoggled). */
static const char *const qhull_options[] = {"qhull Qt Qc U%g", "qhull Qt Qc Q12 U%g", "qhull QJ Qc"};

static int precision_failure(int exitcode)
{
    return exitcode == qh_ERRprec || exitcode == qh_ERRwide || exitcode == qh_ERRtopology || exitcode == qh_ERRqhull;
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
        size = fmax(size, hypot(hypot(d[0], d[1]), d[2])); /* without overflow, for a mesh of 1e300 m */
    }
    const double offset = hypot(hypot(mean[0], mean[1]), mean[2]); /* without overflow, for a mesh 1e300 m away */
    if (!isfinite(offset) || !isfinite(size))
        return gb_error_set(GB_EDOM, "%s: the vertices lie beyond the range of a double from the origin (allowed: %g <= size <= %g m)",
                            name, GB_POLYHEDRON_SIZE_MIN, GB_POLYHEDRON_SIZE_MAX);
    if (!(size > 0.0))
        return gb_error_set(GB_EINVAL, "%s: every point is the same point%s (allowed: a body)", name,
                            offset > 0.0 ? ", as written so far from the origin: a double cannot hold a body's shape there" : "");
    /* the scale rules: a body whose size the dynamics' tolerances and the mass properties' powers (size^5) hold, and
     * coordinates that hold its shape (an offset of 1e6 sizes keeps 1e-10 of the size in a double) */
    if (size < GB_POLYHEDRON_SIZE_MIN || size > GB_POLYHEDRON_SIZE_MAX)
        return gb_error_set(GB_EDOM, "%s: the body's size (its largest vertex distance from the vertices' mean) is %.3g m (allowed: "
                            "%g <= size <= %g m; scale the mesh, in metres)", name, size, GB_POLYHEDRON_SIZE_MIN, GB_POLYHEDRON_SIZE_MAX);
    if (offset > GB_POLYHEDRON_OFFSET_MAX * size)
        return gb_error_set(GB_EDOM, "%s: the body lies %.3g m from the mesh's origin, %.3g times its size of %.3g m: its coordinates "
                            "cannot hold its shape (allowed: the vertices' mean within %g sizes of the origin; move the mesh nearer)",
                            name, offset, offset / size, size, GB_POLYHEDRON_OFFSET_MAX);
    const double tol = GB_POLYHEDRON_FLAT * size;
    double *copy = malloc(3 * count * sizeof *copy);
    unsigned char *seen = calloc(count, 1);
    if (!copy || !seen) {
        free(copy), free(seen);
        return gb_error_set(GB_ENOMEM, "%s: out of memory for the hull", name);
    }
    FILE *errors = tmpfile();
    qhT qh_storage, *qh = &qh_storage;
    int exitcode = 0, status = GB_OK;
    const size_t tries = sizeof qhull_options / sizeof qhull_options[0];
    for (size_t attempt = 0; attempt < tries; attempt++) {
        if (attempt) { /* the previous attempt's structures go before the next */
            qh_freeqhull(qh, !qh_ALL);
            int curlong, totlong;
            qh_memfreeshort(qh, &curlong, &totlong);
        }
        memcpy(copy, points, 3 * count * sizeof *copy);
        qh_zero(qh, errors);
        char command[64];
        snprintf(command, sizeof command, qhull_options[attempt], tol);
        exitcode = qh_new_qhull(qh, 3, (int)count, copy, False, command, NULL, errors);
        if (!precision_failure(exitcode)) break;
    }
    if (exitcode == qh_ERRsingular)
        status = gb_error_set(GB_EINVAL, "%s: the points are flat, all within %.3g m of one plane (allowed: a body with volume)", name, tol);
    else if (exitcode && precision_failure(exitcode))
        status = gb_error_set(GB_ENUMERIC, "%s: Qhull's precision failed on these %zu points (code %d) with every option tried "
                              "(%s; %s; %s), at a size of %.3g m %.3g m from the origin: not a malformed file, a hull Qhull "
                              "cannot resolve at this precision", name, count, exitcode, qhull_options[0], qhull_options[1],
                              qhull_options[2], size, offset);
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
    if (!status) { /* flat: the hull's mean thickness 2V/A (a slab's thickness) within tol */
        double volume, area;
        surface_sums(out->vertices, out->triangles, out->triangle_count, mean, &volume, &area);
        if (!(2.0 * volume > tol * area))
            status = gb_error_set(GB_EINVAL, "%s: the points are flat: the hull's mean thickness 2V/A = %.3g m is within %.3g m, %g of "
                                  "the body's size (allowed: a body with volume)", name, 2.0 * volume / area, tol, GB_POLYHEDRON_FLAT);
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

/* The mesh's own surface against its hull: closed (every edge in two triangles), consistently oriented (each
 * directed edge once, its reverse once), and enclosing the hull's volume to within tol times the hull's area
 * (what vertices within tol of the hull's surface can change); else it is not the convex body its hull is. */
static int mesh_is_its_hull(const gb_mesh *mesh, const gb_polyhedron *hull_body, const char *name)
{
    const size_t count = 3 * mesh->triangle_count;
    directed_edge *edges = malloc(count * sizeof *edges);
    if (!edges) return gb_error_set(GB_ENOMEM, "%s: out of memory for the mesh's edges", name);
    for (size_t t = 0; t < mesh->triangle_count; t++)
        for (int k = 0; k < 3; k++)
            edges[3 * t + k] = (directed_edge){mesh->triangles[3 * t + k], mesh->triangles[3 * t + (k + 1) % 3], t};
    qsort(edges, count, sizeof *edges, edge_order);
    int status = GB_OK;
    for (size_t k = 0; k < count && !status; k++) {
        const directed_edge *e = &edges[k];
        const size_t line_a = mesh->vertex_line[e->from], line_b = mesh->vertex_line[e->to];
        if (e->from == e->to)
            status = gb_error_set(GB_EINVAL, "%s:%zu: a face names this vertex twice in a row (allowed: a closed, consistently oriented "
                                  "surface of faces with distinct vertices)", name, line_a);
        else if (k + 1 < count && !edge_order(e, &edges[k + 1]))
            status = gb_error_set(GB_EINVAL, "%s:%zu: the edge from this vertex to the one of line %zu is in two faces taken the same way "
                                  "round: the faces are not consistently oriented, or the surface not a simple one (allowed: a "
                                  "closed surface, each edge in two faces, taken in opposite senses)", name, line_a, line_b);
        else {
            const directed_edge reverse = {e->to, e->from, 0};
            if (!bsearch(&reverse, edges, count, sizeof *edges, edge_order))
                status = gb_error_set(GB_EINVAL, "%s:%zu: the edge from this vertex to the one of line %zu belongs to one face, or to "
                                      "faces taken the same way round: the mesh is not closed (allowed: a closed surface, each "
                                      "edge in two faces, taken in opposite senses)", name, line_a, line_b);
        }
    }
    free(edges);
    if (status) return status;
    double apex[3] = {0, 0, 0}, own, own_area, hull_volume, hull_area;
    for (size_t k = 0; k < hull_body->vertex_count; k++)
        for (int i = 0; i < 3; i++) apex[i] += hull_body->vertices[3 * k + i] / (double)hull_body->vertex_count;
    surface_sums(mesh->vertices, mesh->triangles, mesh->triangle_count, apex, &own, &own_area);
    surface_sums(hull_body->vertices, hull_body->triangles, hull_body->triangle_count, apex, &hull_volume, &hull_area);
    const double tol = GB_POLYHEDRON_FLAT * hull_body->size * hull_area + 64.0 * DBL_EPSILON * hull_body->size * hull_area;
    if (!(fabs(fabs(own) - hull_volume) <= tol))
        return gb_error_set(GB_EINVAL, "%s: the mesh's faces enclose %.10g m^3 but its convex hull %.10g m^3: the mesh is not convex "
                            "(allowed: a convex polyhedron, its volume its hull's to %.3g m^3; its contact with a plane is its "
                            "hull's, so give the hull)", name, fabs(own), hull_volume, tol);
    return GB_OK;
}

int gb_polyhedron_from_mesh(const gb_mesh *mesh, const char *name, gb_polyhedron *out)
{
    int status = hull(mesh->vertices, mesh->vertex_count, mesh->vertex_line, name, out);
    if (!status && (status = mesh_is_its_hull(mesh, out, name))) gb_polyhedron_free(out);
    return status;
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

/* Union–find over triangles: a face is the triangles joined by edges whose two triangles share the normal. */
static size_t face_root(size_t *parent, size_t t)
{
    while (parent[t] != t) t = parent[t] = parent[parent[t]];
    return t;
}

static int same_normal(const double *a, const double *b)
{
    return fabs(a[0] - b[0]) + fabs(a[1] - b[1]) + fabs(a[2] - b[2]) <= 1e-9;
}

/* A face (the coplanar triangles of one normal) is a stable rest when the centroid's projection lies inside one of
 * its triangles and farther than tol from the face's boundary (the edges whose other triangle is of another face).
 * The faces and their boundaries come from one sort of the directed edges: O(T log T) in the triangles. */
int gb_polyhedron_rest_faces(const gb_polyhedron *p, const double centroid[3], double (*normals)[3], size_t cap, size_t *count)
{
    *count = 0;
    const size_t nt = p->triangle_count, ne = 3 * nt;
    const double tol = GB_POLYHEDRON_FLAT * p->size;
    double *normal = malloc(3 * (nt ? nt : 1) * sizeof *normal);
    unsigned char *inside = malloc(nt ? nt : 1), *face_done = calloc(nt ? nt : 1, 1), *clear = malloc(nt ? nt : 1);
    size_t *parent = malloc((nt ? nt : 1) * sizeof *parent);
    directed_edge *edges = malloc((ne ? ne : 1) * sizeof *edges);
    int status = GB_OK;
    if (!normal || !inside || !face_done || !clear || !parent || !edges) {
        status = gb_error_set(GB_ENOMEM, "out of memory for the rest faces");
        goto done;
    }
    for (size_t t = 0; t < nt; t++) {
        inside[t] = (unsigned char)projects_inside(p, t, centroid, tol, normal + 3 * t);
        if (!inside[t]) projects_inside(p, t, centroid, 0.0, normal + 3 * t); /* the normal in any case */
        parent[t] = t, clear[t] = 1;
        for (int k = 0; k < 3; k++) edges[3 * t + k] = (directed_edge){p->triangles[3 * t + k], p->triangles[3 * t + (k + 1) % 3], t};
    }
    qsort(edges, ne, sizeof *edges, edge_order);
    /* join the triangles across edges of one normal */
    for (size_t k = 0; k < ne; k++) {
        const directed_edge reverse = {edges[k].to, edges[k].from, 0};
        const directed_edge *twin = bsearch(&reverse, edges, ne, sizeof *edges, edge_order);
        if (twin && same_normal(normal + 3 * edges[k].triangle, normal + 3 * twin->triangle)) {
            const size_t a = face_root(parent, edges[k].triangle), b = face_root(parent, twin->triangle);
            if (a != b) parent[a < b ? b : a] = a < b ? a : b;
        }
    }
    /* a boundary edge of a face within tol of the centroid's projection makes the face no stable rest */
    for (size_t k = 0; k < ne; k++) {
        const directed_edge reverse = {edges[k].to, edges[k].from, 0};
        const directed_edge *twin = bsearch(&reverse, edges, ne, sizeof *edges, edge_order);
        const size_t root = face_root(parent, edges[k].triangle);
        if (twin && face_root(parent, twin->triangle) == root) continue; /* inside the face */
        const double *n = normal + 3 * edges[k].triangle;
        const double *a = p->vertices + 3 * edges[k].from, *b = p->vertices + 3 * edges[k].to;
        const double e[3] = {centroid[0] - a[0], centroid[1] - a[1], centroid[2] - a[2]},
                     depth = e[0] * n[0] + e[1] * n[1] + e[2] * n[2];
        const double q[3] = {centroid[0] - depth * n[0], centroid[1] - depth * n[1], centroid[2] - depth * n[2]};
        if (segment_distance(q, a, b) <= tol) clear[root] = 0;
    }
    /* the faces in the order of their first triangle whose projection test passes */
    double *found = malloc(3 * (nt ? nt : 1) * sizeof *found);
    size_t n_found = 0;
    if (!found) {
        status = gb_error_set(GB_ENOMEM, "out of memory for the rest faces");
        goto done;
    }
    for (size_t t = 0; t < nt; t++) {
        if (!inside[t]) continue;
        const size_t root = face_root(parent, t);
        if (face_done[root]) continue;
        face_done[root] = 1;
        if (clear[root]) memcpy(found + 3 * n_found++, normal + 3 * t, 3 * sizeof *found);
    }
    for (size_t k = 0; k < n_found && k < cap; k++) memcpy(normals[k], found + 3 * k, 3 * sizeof(double));
    *count = n_found;
    free(found);
done:
    free(normal), free(inside), free(face_done), free(clear), free(parent), free(edges);
    return status;
}
