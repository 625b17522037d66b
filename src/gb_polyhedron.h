/* gb_polyhedron — a convex polyhedron as a body: the convex hull of a mesh's vertices (Qhull) and its mass
 * properties in closed form.
 *
 * The body is the hull. A mesh some vertex of which lies inside the hull (farther than GB_POLYHEDRON_FLAT
 * times the body's size below every face through it) is not convex, and is refused naming that vertex's
 * line: a rocking body's contact with a plane is its hull's, so a non-convex mesh would silently be
 * another body than the file shows. So is a mesh whose own faces are not its hull's surface: it must be
 * closed and consistently oriented (each edge in two faces, taken in opposite senses) and enclose the hull's
 * volume to GB_POLYHEDRON_FLAT × size × the hull's area (Schönhardt's prism, all of whose vertices lie on
 * its hull, encloses less). A flat mesh (its hull's mean thickness 2V/A within that distance) has no
 * volume and is refused too. Qhull's precision failures on valid input are retried with wide facets
 * allowed, then with joggled input, and named as precision failures (with the input's scale) if all fail.
 *
 * Mass properties of a homogeneous body by the divergence theorem over the hull's triangles, each with
 * the centroid of the vertices as apex (a sum of tetrahedra, exact for a polyhedron but for rounding):
 * volume V = Σ det(a, b, c)/6; first moment Σ det (a + b + c)/24; second moment (covariance about the
 * apex) C = Σ det · A C₀ Aᵀ with A = [a b c] and C₀ = (1 + δᵢⱼ)/120; the inertia tensor about the
 * centroid I = tr(C') E − C' with C' the covariance shifted to the centroid, times the density m/V. */
#ifndef GB_POLYHEDRON_H
#define GB_POLYHEDRON_H

#include "gb_export.h"
#include "gb_massprops.h"
#include "gb_mesh.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define GB_POLYHEDRON_FLAT 1e-9 /* relative to the body's size (its largest vertex distance from the centre of the vertices) */
/* The scale rules [m]: a body's size, and how far from its file's origin it may lie, in sizes. Below 1e-6 m the
 * dynamics' absolute tolerances (1e-12 m a contact) are the body's own scale; above 1e6 m, or 1e6 sizes from
 * the origin, the doubles of the coordinates no longer hold the body's shape to GB_POLYHEDRON_FLAT. */
#define GB_POLYHEDRON_SIZE_MIN 1e-6
#define GB_POLYHEDRON_SIZE_MAX 1e6
#define GB_POLYHEDRON_OFFSET_MAX 1e6

typedef struct gb_polyhedron {
    size_t vertex_count;
    double *vertices;        /* the hull's vertices [3 * vertex_count], in the mesh's order */
    size_t *mesh_index;      /* each one's index in the mesh */
    size_t triangle_count;
    size_t *triangles;       /* the hull's faces as triangles [3 * triangle_count], counter-clockwise seen from outside */
    double size;             /* the largest distance of a vertex from the vertices' mean [m] */
} gb_polyhedron;

/* The hull of `mesh`; `name` for messages ("NAME:LINE: ..."). GB_EINVAL for a flat or non-convex mesh,
 * GB_ENUMERIC when Qhull fails. On failure nothing is left to free. */
GB_API int gb_polyhedron_from_mesh(const gb_mesh *mesh, const char *name, gb_polyhedron *out);
/* The hull of `count` points [3 * count] (a grid's nodes, a test's cube): the same, without lines. */
GB_API int gb_polyhedron_from_points(const double *points, size_t count, const char *name, gb_polyhedron *out);
GB_API void gb_polyhedron_free(gb_polyhedron *polyhedron);

/* Volume, centroid, inertia about the centroid (body axes) of the homogeneous body of `mass` [kg]; the
 * error fields hold a bound on rounding (64 eps times the sums' magnitudes); L and evaluations are 0.
 * GB_EDOM for a mass outside [1e-6, 1e6]. */
GB_API int gb_polyhedron_massprops(const gb_polyhedron *polyhedron, double mass, gb_massprops *out);

/* The faces the body rests on, stably, on a still plane: those whose plane the vertical through the
 * centroid meets inside the face (the projection of `centroid` along the face's normal lies inside one of
 * its triangles, beyond `GB_POLYHEDRON_FLAT` times the size from every edge of the face). Writes up to
 * `cap` outward unit normals, one per face (coplanar triangles are one face), and their count to *count
 * (which may exceed cap). */
GB_API int gb_polyhedron_rest_faces(const gb_polyhedron *polyhedron, const double centroid[3], double (*normals)[3], size_t cap,
                                    size_t *count);

#ifdef __cplusplus
}
#endif

#endif
