/* libFuzzer target: the mesh reader (gb_mesh_read_buffer) and the hull and mass properties built on what
 * it accepts (gb_polyhedron).
 *
 * The input's first byte picks the name, so the format: .off, .obj or .stl (an .stl is ASCII or binary by
 * its content); the rest is the file. Beyond not crashing (ASan, UBSan): an accepted mesh has finite
 * vertices and triangles of three distinct vertices in range; an accepted hull has vertices of the mesh
 * and a positive, finite volume and inertia; a refused input says why. Seeds: verify/fuzz/mesh/. */
#include "gb_error.h"
#include "gb_mesh.h"
#include "gb_polyhedron.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

static void require(int condition)
{
    if (!condition) abort();
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) return 0;
    static const char *const names[3] = {"fuzz.off", "fuzz.obj", "fuzz.stl"};
    const char *name = names[data[0] % 3];
    gb_mesh mesh;
    int status = gb_mesh_read_buffer(name, data + 1, size - 1, &mesh);
    if (status) {
        require(mesh.vertices == NULL && gb_error_message()[0] != '\0');
        gb_error_clear();
        return 0;
    }
    for (size_t k = 0; k < 3 * mesh.vertex_count; k++) require(isfinite(mesh.vertices[k]));
    for (size_t t = 0; t < mesh.triangle_count; t++) {
        const size_t *v = mesh.triangles + 3 * t;
        require(v[0] < mesh.vertex_count && v[1] < mesh.vertex_count && v[2] < mesh.vertex_count);
        require(v[0] != v[1] && v[1] != v[2] && v[0] != v[2]);
    }
    gb_polyhedron p;
    status = gb_polyhedron_from_mesh(&mesh, name, &p);
    if (!status) {
        require(p.vertex_count >= 4 && p.vertex_count <= mesh.vertex_count && p.triangle_count >= 4);
        for (size_t k = 0; k < p.vertex_count; k++) require(p.mesh_index[k] < mesh.vertex_count);
        gb_massprops m;
        if (gb_polyhedron_massprops(&p, 1.0, &m) == GB_OK) require(m.volume > 0.0 && isfinite(m.inertia[0][0]));
        else gb_error_clear();
        gb_polyhedron_free(&p);
    } else {
        require(gb_error_message()[0] != '\0');
        gb_error_clear();
    }
    gb_mesh_free(&mesh);
    return 0;
}
