/* gb_mesh — a body given as a mesh file: OFF, Wavefront OBJ, or STL (ASCII or binary), read strictly.
 *
 * Our own reader, not a library's: Debian's Assimp reads all three but repairs what it reads (joins,
 * triangulates, skips statements it does not know) and reports no line, where a scene's bad input must
 * be refused naming the file, the line and what is wrong. The formats are small; the reader is fuzzed
 * (verify/fuzz/fuzz_mesh.c).
 *
 * What is read: the vertices (every one finite), and the faces as triangles (a polygon is fanned from its
 * first vertex), each index in range; anything else a format allows is refused with its line but for the
 * statements listed (OBJ: comments, `o`, `g`, `s`, `usemtl`, `mtllib`, `vt`, `vn`; STL: `facet normal`,
 * whose normal is recomputed from the vertices). STL gives vertices per triangle: equal positions (bit for
 * bit) are merged, so a vertex is one point of the body. The body itself, the convex hull, is
 * gb_polyhedron's. */
#ifndef GB_MESH_H
#define GB_MESH_H

#include "gb_export.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define GB_MESH_MAX_VERTICES 1000000 /* a larger mesh is refused (the hull and the contact search scale with it) */
#define GB_MESH_FILE_MAX ((size_t)1 << 30) /* bytes: a binary STL of GB_MESH_MAX_VERTICES vertices is far below it */

typedef enum gb_mesh_format { GB_MESH_OFF = 0, GB_MESH_OBJ = 1, GB_MESH_STL_ASCII = 2, GB_MESH_STL_BINARY = 3 } gb_mesh_format;

typedef struct gb_mesh {
    gb_mesh_format format;
    size_t vertex_count;
    double *vertices;      /* [3 * vertex_count] */
    size_t *vertex_line;   /* the line each vertex was first read from (binary STL: the triangle's number) */
    size_t triangle_count;
    size_t *triangles;     /* [3 * triangle_count], indices into vertices */
} gb_mesh;


/* Read `path` (a regular file of at most GB_MESH_FILE_MAX bytes, read as gb_file_read reads: GB_EINVAL for a
 * path that is no such file, GB_EIO for a failed read) or a buffer named `name` (for messages). On failure
 * nothing is left to free, and the message reads "NAME:LINE: what is wrong (allowed: ...)". */
GB_API int gb_mesh_read(const char *path, gb_mesh *out);
GB_API int gb_mesh_read_buffer(const char *name, const unsigned char *data, size_t size, gb_mesh *out);
GB_API void gb_mesh_free(gb_mesh *mesh);

GB_API const char *gb_mesh_format_name(gb_mesh_format format);

#ifdef __cplusplus
}
#endif

#endif
