/* Section 2 for bodies of one's own: a mesh read strictly, its convex hull, and the mass properties of a
 * polyhedron in closed form.
 *
 * - the same cube written as OFF, OBJ, ASCII STL and binary STL reads to the same vertices and hull, and
 *   its volume, centroid and inertia are the closed form's (side 2: V = 8, I = 2m/3 on the diagonal);
 * - a right tetrahedron's inertia about its centroid, with its products, is the closed form's;
 * - the divergence-theorem sums against the quadrature of gb_massprops: the surface of Gömböc I's grid
 *   (its (phi, theta) nodes joined into triangles, the poles added) converges to the smooth body's
 *   volume and inertia at second order in the spacing;
 * - bad meshes are refused with their line: a vertex inside the hull (not convex), a flat mesh, a face
 *   index out of range, a statement the format does not have, a non-finite coordinate, a binary STL whose
 *   size disagrees with its count. */
#include "gb_check.h"
#include "gb_error.h"
#include "gb_massprops.h"
#include "gb_mesh.h"
#include "gb_polyhedron.h"
#include "gb_surface.h"
#include "verify_sections.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double CUBE[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
static const int CUBE_FACES[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};

static size_t cube_off(char *out, size_t cap)
{
    size_t n = (size_t)snprintf(out, cap, "OFF\n# a cube of side 2\n8 6 12\n");
    for (int v = 0; v < 8; v++) n += (size_t)snprintf(out + n, cap - n, "%g %g %g\n", CUBE[v][0], CUBE[v][1], CUBE[v][2]);
    for (int f = 0; f < 6; f++)
        n += (size_t)snprintf(out + n, cap - n, "4 %d %d %d %d\n", CUBE_FACES[f][0], CUBE_FACES[f][1], CUBE_FACES[f][2], CUBE_FACES[f][3]);
    return n;
}

static size_t cube_obj(char *out, size_t cap)
{
    size_t n = (size_t)snprintf(out, cap, "# a cube of side 2\no cube\n");
    for (int v = 0; v < 8; v++) n += (size_t)snprintf(out + n, cap - n, "v %g %g %g\n", CUBE[v][0], CUBE[v][1], CUBE[v][2]);
    n += (size_t)snprintf(out + n, cap - n, "vn 0 0 1\ns off\n");
    for (int f = 0; f < 6; f++)
        n += (size_t)snprintf(out + n, cap - n, "f %d/1 %d//1 %d %d\n", CUBE_FACES[f][0] + 1, CUBE_FACES[f][1] + 1, CUBE_FACES[f][2] + 1,
                              CUBE_FACES[f][3] - 8); /* the last as a relative reference */
    return n;
}

static size_t cube_stl_ascii(char *out, size_t cap)
{
    size_t n = (size_t)snprintf(out, cap, "solid cube\n");
    for (int f = 0; f < 6; f++)
        for (int t = 0; t < 2; t++) {
            const int v[3] = {CUBE_FACES[f][0], CUBE_FACES[f][1 + t], CUBE_FACES[f][2 + t]};
            n += (size_t)snprintf(out + n, cap - n, "  facet normal 0 0 0\n    outer loop\n");
            for (int k = 0; k < 3; k++)
                n += (size_t)snprintf(out + n, cap - n, "      vertex %g %g %g\n", CUBE[v[k]][0], CUBE[v[k]][1], CUBE[v[k]][2]);
            n += (size_t)snprintf(out + n, cap - n, "    endloop\n  endfacet\n");
        }
    return n + (size_t)snprintf(out + n, cap - n, "endsolid cube\n");
}

static size_t cube_stl_binary(unsigned char *out)
{
    memset(out, 0, 84);
    memcpy(out, "binary cube", 11);
    out[80] = 12;
    size_t n = 84;
    for (int f = 0; f < 6; f++)
        for (int t = 0; t < 2; t++) {
            const int v[3] = {CUBE_FACES[f][0], CUBE_FACES[f][1 + t], CUBE_FACES[f][2 + t]};
            memset(out + n, 0, 50);
            for (int k = 0; k < 3; k++)
                for (int i = 0; i < 3; i++) {
                    const float x = (float)CUBE[v[k]][i];
                    uint32_t u;
                    memcpy(&u, &x, sizeof u);
                    for (int b = 0; b < 4; b++) out[n + 12 + 12 * k + 4 * i + b] = (unsigned char)(u >> (8 * b));
                }
            n += 50;
        }
    return n;
}

static void test_cube_formats(void)
{
    static char text[4][8192];
    static unsigned char binary[1024];
    const char *names[4] = {"cube.off", "cube.obj", "cube.stl", "cube.stl"};
    const unsigned char *data[4] = {(unsigned char *)text[0], (unsigned char *)text[1], (unsigned char *)text[2], binary};
    const size_t size[4] = {cube_off(text[0], sizeof text[0]), cube_obj(text[1], sizeof text[1]), cube_stl_ascii(text[2], sizeof text[2]),
                            cube_stl_binary(binary)};
    gb_massprops props[4];
    int ok[4] = {0};
    for (int k = 0; k < 4; k++) {
        gb_mesh mesh;
        gb_polyhedron p;
        int status = gb_mesh_read_buffer(names[k], data[k], size[k], &mesh);
        if (!status) status = gb_polyhedron_from_mesh(&mesh, names[k], &p);
        if (!status) {
            status = gb_polyhedron_massprops(&p, 1.0, &props[k]);
            ok[k] = !status && mesh.vertex_count == 8 && p.vertex_count == 8 && p.triangle_count == 12 && mesh.format == (gb_mesh_format)k;
            gb_polyhedron_free(&p);
            gb_mesh_free(&mesh);
        }
        char quantity[128];
        snprintf(quantity, sizeof quantity, "a cube of side 2 as %s: 8 vertices, a hull of 8 vertices and 12 triangles",
                 gb_mesh_format_name((gb_mesh_format)k));
        gb_check c = {"2", "-", quantity, "the file as written", "exact"};
        gb_check_true(&c, ok[k], "%s", status ? gb_error_message() : "read");
    }
    if (!ok[0]) return;
    gb_check cv = {"2", "-", "the cube's volume (divergence theorem over its hull)", "closed form 2^3", "4 eps"};
    gb_check_close(&cv, props[0].volume, 8.0, 4 * 2.2e-16, 0.0);
    gb_check ci = {"2", "-", "the cube's inertia about its centroid, I_xx (m = 1)", "closed form m (2^2 + 2^2)/12 = 2/3", "8 eps"};
    gb_check_close(&ci, props[0].inertia[0][0], 2.0 / 3.0, 8 * 2.2e-16, 0.0);
    double off = 0.0, spread = 0.0;
    for (int i = 0; i < 3; i++) {
        off = fmax(off, fabs(props[0].centroid[i]));
        for (int k = 0; k < 3; k++) {
            if (i != k) off = fmax(off, fabs(props[0].inertia[i][k]));
            for (int f = 1; f < 4; f++) if (ok[f]) spread = fmax(spread, fabs(props[f].inertia[i][k] - props[0].inertia[i][k]));
        }
    }
    gb_check co = {"2", "-", "the cube's centroid and products of inertia", "closed form 0", "1e-15: rounding of sums of order 1"};
    gb_check_close(&co, off, 0.0, 0.0, 1e-15);
    gb_check cs = {"2", "-", "the cube in four formats: the largest difference of their inertia tensors", "the OFF file's",
                   "exact: the same vertices (exact in binary32 too) give the same sums"};
    gb_check_true(&cs, ok[1] && ok[2] && ok[3] && spread == 0.0, "largest difference %.3g", spread);
}

static void test_tetrahedron(void)
{
    const char *text = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
    gb_mesh mesh;
    gb_polyhedron p;
    gb_massprops m;
    int status = gb_mesh_read_buffer("tetra.off", (const unsigned char *)text, strlen(text), &mesh);
    if (!status) status = gb_polyhedron_from_mesh(&mesh, "tetra.off", &p);
    if (!status) status = gb_polyhedron_massprops(&p, 1.0, &m), gb_polyhedron_free(&p);
    gb_mesh_free(&mesh); /* a failed read leaves it empty */
    gb_check cr = {"2", "-", "the right tetrahedron (0, e_x, e_y, e_z) read and its hull built", "the file", "exact"};
    if (!gb_check_true(&cr, !status, "%s", status ? gb_error_message() : "read")) return;
    /* rho = m/V = 6: about the origin I_xx = rho/30, I_xy = -rho/120; shifted to g = (1/4, 1/4, 1/4) */
    gb_check cv = {"2", "-", "the right tetrahedron's volume", "closed form 1/6", "8 eps"};
    gb_check_close(&cv, m.volume, 1.0 / 6.0, 8 * 2.2e-16, 0.0);
    gb_check cg = {"2", "-", "its centroid, x", "closed form 1/4", "16 eps"};
    gb_check_close(&cg, m.centroid[0], 0.25, 16 * 2.2e-16, 0.0);
    gb_check cxx = {"2", "-", "its inertia about the centroid, I_xx (m = 1)", "closed form rho/80 = 3/40", "64 eps: sums of 4 tetrahedra"};
    gb_check_close(&cxx, m.inertia[0][0], 3.0 / 40.0, 64 * 2.2e-16, 0.0);
    gb_check cxy = {"2", "-", "its product of inertia about the centroid, I_xy (m = 1)", "closed form rho/480 = 1/80",
                    "64 eps: sums of 4 tetrahedra"};
    gb_check_close(&cxy, m.inertia[0][1], 1.0 / 80.0, 64 * 2.2e-16, 0.0);
}

/* The closed surface of a body's (phi, theta) grid: n_phi rings of n_theta nodes (phi midpoints, theta
 * from 0) and the two poles, as triangles; its divergence-theorem mass properties. */
static int grid_surface_massprops(const gb_surface *s, size_t n_phi, size_t n_theta, gb_massprops *out)
{
    const size_t n = n_phi * n_theta + 2;
    double *x = malloc(3 * n * sizeof *x);
    size_t *tri = malloc(3 * 2 * n_theta * n_phi * sizeof *tri);
    if (!x || !tri) {
        free(x), free(tri);
        return GB_ENOMEM;
    }
    for (size_t i = 0; i < n_phi; i++)
        for (size_t j = 0; j < n_theta; j++)
            gb_surface_position(s, (i + 0.5) * M_PI / (double)n_phi, (double)j * 2.0 * M_PI / (double)n_theta, x + 3 * (i * n_theta + j));
    gb_surface_position(s, 0.0, 0.0, x + 3 * (n - 2));
    gb_surface_position(s, M_PI, 0.0, x + 3 * (n - 1));
    size_t t = 0;
    for (size_t j = 0; j < n_theta; j++) {
        const size_t j1 = (j + 1) % n_theta;
        tri[3 * t] = n - 2, tri[3 * t + 1] = j, tri[3 * t + 2] = j1, t++;  /* north cap */
        const size_t last = (n_phi - 1) * n_theta;
        tri[3 * t] = n - 1, tri[3 * t + 1] = last + j1, tri[3 * t + 2] = last + j, t++; /* south cap */
        for (size_t i = 0; i + 1 < n_phi; i++) {
            const size_t a = i * n_theta + j, b = i * n_theta + j1, c = (i + 1) * n_theta + j, d = (i + 1) * n_theta + j1;
            tri[3 * t] = a, tri[3 * t + 1] = c, tri[3 * t + 2] = d, t++;
            tri[3 * t] = a, tri[3 * t + 1] = d, tri[3 * t + 2] = b, t++;
        }
    }
    gb_polyhedron p = {n, x, NULL, t, tri, 1.0};
    const int status = gb_polyhedron_massprops(&p, 1.0, out);
    free(x), free(tri);
    return status;
}

static void test_grid_surface_against_quadrature(void)
{
    const gb_surface *s = gb_check_body("I", 0.12);
    gb_massprops quad, coarse, fine;
    const gb_massprops_def def = gb_massprops_default_def();
    int status = gb_massprops_compute(s, &def, &quad);
    if (!status) status = grid_surface_massprops(s, 90, 180, &coarse);
    if (!status) status = grid_surface_massprops(s, 180, 360, &fine);
    gb_check cr = {"2", "12, 29", "Gomboc I's grid surface (90 x 180 and 180 x 360 nodes, the poles added) as a polyhedron", "runs", "exact"};
    if (!gb_check_true(&cr, !status, "%s", status ? gb_error_message() : "ran")) return;
    const double e1 = fabs(coarse.volume - quad.volume), e2 = fabs(fine.volume - quad.volume);
    gb_check co = {"2", "12, 29", "the polyhedral volume's error against the quadrature, observed order from 90 x 180 to 180 x 360",
                   "gb_massprops (nested GSL quadrature, its error ~1e-12, below both errors)",
                   "2 +- 0.2: a surface interpolated linearly between nodes is second order in the spacing"};
    gb_check_close(&co, gb_check_observed_order(e1, e2, 1.0, 0.5), 2.0, 0.0, 0.2);
    const double i1 = fabs(coarse.inertia[0][0] - quad.inertia[0][0]), i2 = fabs(fine.inertia[0][0] - quad.inertia[0][0]);
    gb_check ci = {"2", "12, 29", "the polyhedral I_xx's error against the quadrature, observed order", "gb_massprops",
                   "2 +- 0.2, as the volume"};
    gb_check_close(&ci, gb_check_observed_order(i1, i2, 1.0, 0.5), 2.0, 0.0, 0.2);
    /* Richardson: the second-order extrapolation of the two is the smooth body's, to the next order */
    gb_check cx = {"2", "12, 29", "the volume extrapolated from the two grids (4 V_fine - V_coarse)/3", "the quadrature",
                   "e2/10: the extrapolation removes the second-order term, leaving a tenth of the fine grid's error at most"};
    gb_check_close(&cx, (4.0 * fine.volume - coarse.volume) / 3.0, quad.volume, 0.0, e2 / 10.0);
}

static void test_bad_meshes(void)
{
    static const struct {
        const char *name, *text, *expect;
    } rows[] = {
        {"inside.off", "OFF\n5 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0.1 0.1 0.1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n", "inside.off:7: this vertex lies"},
        {"flat.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n3 0 1 3\n3 0 2 3\n", "flat.off: the points are flat"},
        {"index.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 4\n3 0 3 2\n3 1 2 3\n", "index.off:8: the vertex index '4'"},
        {"nan.obj", "v 0 0 0\nv 1 0 0\nv 0 1 nan\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n", "nan.obj:3: a coordinate 'nan'"},
        {"huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1 1e999\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n", "huge.obj:3: a coordinate '1e999'"},
        {"curve.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\ncurv 0 1 1 2\nf 1 3 2\n", "curve.obj:5: the statement 'curv'"},
        {"ref.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n", "ref.obj:3: the vertex reference '3'"},
        {"few.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "few.obj: 3 vertices and 1 triangles"},
        {"loop.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n", "loop.stl:6: 'endloop' out of place"},
        {"short.stl", "not a solid", "short.stl: a binary STL of 11 bytes"},
        {"cube.ply", "ply\n", "cube.ply: the mesh format is unknown"},
    };
    const int count = (int)(sizeof rows / sizeof rows[0]);
    for (int k = 0; k < count; k++) {
        gb_mesh mesh;
        gb_polyhedron p;
        int status = gb_mesh_read_buffer(rows[k].name, (const unsigned char *)rows[k].text, strlen(rows[k].text), &mesh);
        if (!status) {
            status = gb_polyhedron_from_mesh(&mesh, rows[k].name, &p);
            if (!status) gb_polyhedron_free(&p);
            gb_mesh_free(&mesh);
        }
        const int ok = status && strstr(gb_error_message(), rows[k].expect) && strstr(gb_error_message(), "allowed");
        char quantity[160];
        snprintf(quantity, sizeof quantity, "a bad mesh '%s' is refused naming its line and what is allowed", rows[k].name);
        gb_check c = {"2", "-", quantity, rows[k].expect, "exact"};
        gb_check_true(&c, ok, "%s", status ? gb_error_message() : "accepted");
    }
}

/* The faces a body rests on: every face of a cube and of a right tetrahedron; of a skew tetrahedron
 * (0, e_x, e_y, (2, 2, 0.2)), whose centroid (0.75, 0.75, 0.05) stands over none of its base z = 0, the
 * three others (worked by hand: the projections onto them have barycentric coordinates (0.0025, 0.37),
 * the same mirrored, and (0.42, 0.17), all inside). */
static void test_rest_faces(void)
{
    static const struct {
        const char *name;
        double v[4][3];
        size_t want;
    } tetras[] = {{"the right tetrahedron", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, 4},
                  {"the skew tetrahedron (0, e_x, e_y, (2, 2, 0.2))", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 2, 0.2}}, 3}};
    gb_polyhedron p;
    gb_massprops m;
    double normals[8][3];
    size_t count = 0;
    int status = gb_polyhedron_from_points(&CUBE[0][0], 8, "cube", &p);
    if (!status) {
        status = gb_polyhedron_massprops(&p, 1.0, &m);
        if (!status) status = gb_polyhedron_rest_faces(&p, m.centroid, normals, 8, &count);
        gb_polyhedron_free(&p);
    }
    gb_check cc = {"2", "-", "a cube's stable rest faces (the centroid over the face, clear of its edges)", "6, every face", "exact"};
    gb_check_true(&cc, !status && count == 6, "%s, %zu faces", status ? gb_error_message() : "ran", count);
    for (int k = 0; k < 2; k++) {
        count = 0;
        status = gb_polyhedron_from_points(&tetras[k].v[0][0], 4, "tetrahedron", &p);
        int base = 0;
        if (!status) {
            status = gb_polyhedron_massprops(&p, 1.0, &m);
            if (!status) status = gb_polyhedron_rest_faces(&p, m.centroid, normals, 8, &count);
            for (size_t f = 0; f < count && f < 8; f++) base |= normals[f][2] < -0.999;
            gb_polyhedron_free(&p);
        }
        char quantity[160];
        snprintf(quantity, sizeof quantity, "%s: its stable rest faces", tetras[k].name);
        gb_check ct = {"2", "-", quantity, k ? "3, not the base z = 0 (worked by hand)" : "4, every face", "exact"};
        gb_check_true(&ct, !status && count == tetras[k].want && (k == 0 || !base), "%s, %zu faces%s",
                      status ? gb_error_message() : "ran", count, base ? ", the base among them" : "");
    }
}

int verify_register_s2_polyhedron(void)
{
    static const verify_test tests[] = {
        {"a cube in four mesh formats", test_cube_formats,
         "OFF, OBJ and STL (ASCII and binary) read the same body, whose mass properties are the closed form's"},
        {"a right tetrahedron's mass properties", test_tetrahedron,
         "the divergence-theorem sums give a polyhedron's volume, centroid and full inertia tensor in closed form"},
        {"a grid surface against the quadrature", test_grid_surface_against_quadrature,
         "the polyhedral sums converge to the smooth body's mass properties at second order in the grid spacing"},
        {"rest faces", test_rest_faces, "a polyhedron rests stably on exactly the faces over which its centroid stands"},
        {"bad meshes", test_bad_meshes, "a mesh that is not a convex body, or not well formed, is refused naming its line"},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Section 2: bodies of one's own, polyhedra from mesh files", tests);
}
