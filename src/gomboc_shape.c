/* gomboc shape — the body-level facts of paper §2 for one morphology and β, a mesh, or a scene's body. */
#include "gomboc_cli.h"

#include "gb_body.h"
#include "gb_case.h"
#include "gb_contact.h"
#include "gb_error.h"
#include "gb_massprops.h"
#include "gb_mesh.h"
#include "gb_polyhedron.h"
#include "gb_shape.h"
#include "gb_surface.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *usage_shape =
    "usage: gomboc shape --morphology I|II --beta B [--mass M] [--json] [--radial-map FILE]\n"
    "                    [--grid-nodes FILE]\n"
    "       gomboc shape --mesh FILE [--mass M] [--json] [--faces FILE]\n"
    "       gomboc shape --scene FILE [--json] [--radial-map FILE] [--grid-nodes FILE] [--faces FILE]\n"
    "\n"
    "  --morphology I|II  phase function chi: I is theta - 5 phi (eq 8), II is\n"
    "                     theta - (3 pi/2)(cos phi - cos^3 phi/3) (eq 9)\n"
    "  --beta B           shape parameter, 0 <= B < 0.25 (r^4 = 1 + 4 B sin phi cos chi > 0)\n"
    "  --mass M           mass of the homogeneous body, 1e-6 <= M <= 1e6 kg (default 1, as Table 1)\n"
    "  --json             print one JSON object instead of text\n"
    "  --radial-map FILE  also write r(phi, theta) and x on a 90 x 180 midpoint grid as CSV\n"
    "                     (columns phi, theta, r, x, y, z), for Figure 1\n"
    "  --mesh FILE        instead of a morphology: a convex polyhedron from a mesh file (.off, .obj,\n"
    "                     .stl ASCII or binary), the hull of its vertices; prints its vertices and\n"
    "                     faces, volume, centroid, inertia and the faces it rests on stably\n"
    "  --scene FILE       the body of a scene file ([body] morphology and beta, mesh, r or chi, and\n"
    "                     mass): the study above for a smooth body, the --mesh study for a mesh\n"
    "  --grid-nodes FILE  also write the nodes of the scenes' default contact grid (90 x 180,\n"
    "                     nodes = centred) to the last bit, as CSV (columns index, phi, theta,\n"
    "                     x, y, z; body axes about the origin): the vertices of the grid\n"
    "                     polyhedron, for another engine to run the same body\n"
    "  --faces FILE       a mesh body: write its hull's triangles in body axes about the centroid\n"
    "                     (the axes the dynamics use), as CSV (columns triangle, x0, y0, z0, x1,\n"
    "                     y1, z1, x2, y2, z2; counter-clockwise seen from outside), for animate.py\n"
    "\n"
    "Prints: volume, centroid, inertia about the centroid (3x3), L (eq 53), the minimum Gaussian\n"
    "curvature and where, the area fraction of negative curvature, the largest beta at which the\n"
    "morphology is strictly convex, the critical points of r (type, phi, theta, r), the static\n"
    "equilibria of the convex hull, and the verdicts convex and mono_monostatic.\n";

static int write_radial_map(const gb_surface *surface, const char *path)
{
    const size_t nphi = 90, ntheta = 180;
    size_t cap = 64 + nphi * ntheta * 120, used = 0;
    char *text = malloc(cap);
    if (!text) return gb_error_set(GB_ENOMEM, "out of memory for the radial map");
    used += (size_t)snprintf(text, cap, "# gomboc radial map: morphology %s, beta %.17g\nphi,theta,r,x,y,z\n",
                             surface->morphology->name, surface->beta);
    for (size_t i = 0; i < nphi; i++)
        for (size_t j = 0; j < ntheta; j++) {
            const double phi = (i + 0.5) * M_PI / nphi, theta = (j + 0.5) * 2.0 * M_PI / ntheta;
            double x[3];
            gb_surface_position(surface, phi, theta, x);
            used += (size_t)snprintf(text + used, cap - used, "%.9g,%.9g,%.12g,%.12g,%.12g,%.12g\n",
                                     phi, theta, gb_surface_radius(surface, phi, theta), x[0], x[1], x[2]);
        }
    int status = cli_write_atomically(path, text);
    free(text);
    return status;
}

/* The default contact grid's nodes, %.17g so that a reader rebuilds every vertex bit for bit. */
static int write_grid_nodes(const gb_surface *surface, const char *path)
{
    const gb_contact_grid_def def = gb_contact_grid_default_def();
    gb_contact_grid *grid = NULL;
    int status = gb_contact_grid_create(surface, &def, &grid);
    if (status) return status;
    const size_t count = gb_contact_grid_size(grid);
    size_t cap = 256 + count * 128, used = 0;
    char *text = malloc(cap);
    if (!text) {
        gb_contact_grid_free(grid);
        return gb_error_set(GB_ENOMEM, "out of memory for the grid nodes");
    }
    used += (size_t)snprintf(text, cap, "# gomboc grid nodes: morphology %s, beta %.17g, grid %zux%zu, nodes centred\n"
                             "index,phi,theta,x,y,z\n", surface->morphology->name, surface->beta, def.n_phi, def.n_theta);
    for (size_t k = 0; k < count; k++) {
        double phi, theta, x[3];
        gb_contact_grid_node(grid, k, &phi, &theta, x);
        used += (size_t)snprintf(text + used, cap - used, "%zu,%.17g,%.17g,%.17g,%.17g,%.17g\n", k, phi, theta, x[0], x[1],
                                 x[2]);
    }
    gb_contact_grid_free(grid);
    status = cli_write_atomically(path, text);
    free(text);
    return status;
}

/* Everything `gomboc shape` computes for one body, for its JSON and its text. */
typedef struct shape_study {
    gb_surface surface;
    double beta, mass;
    gb_massprops props;
    gb_shape_def sdef;
    gb_curvature_survey survey;
    gb_equilibria equilibria;
    gb_hull_equilibria hull;
    double beta_limit, limit_phi, limit_theta;
    char limit_note[200]; /* why beta_limit is NaN */
    int convex, mono;
} shape_study;

static cJSON *shape_json(const shape_study *st)
{
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "morphology", st->surface.morphology->name);
    cli_json_add(root, "beta", st->beta);
    cli_json_add(root, "mass", st->mass);
    cli_json_add(root, "volume", st->props.volume);
    cli_json_add(root, "volume_error", st->props.volume_err);
    cJSON_AddItemToObject(root, "centroid", cli_json_vector(st->props.centroid, 3));
    cJSON_AddItemToObject(root, "centroid_error", cli_json_vector(st->props.centroid_err, 3));
    /* a body given by an expression is moved to its centroid: where its chart's origin (r's) lies from it */
    const double none[3] = {0.0, 0.0, 0.0};
    const double *origin = st->surface.morphology->moved ? st->surface.morphology->origin : none;
    cJSON_AddItemToObject(root, "chart_origin", cli_json_vector(origin, 3));
    cJSON *inertia = cJSON_AddArrayToObject(root, "inertia");
    for (int i = 0; i < 3; i++) cJSON_AddItemToArray(inertia, cli_json_vector(st->props.inertia[i], 3));
    cli_json_add(root, "L", st->props.L);
    cli_json_add(root, "L_error", st->props.L_err);
    cli_json_add(root, "curvature_min", st->survey.K_min);
    cJSON_AddItemToObject(root, "curvature_min_at", cli_json_vector((double[]){st->survey.K_min_phi, st->survey.K_min_theta}, 2));
    cli_json_add(root, "principal_curvature_min", st->survey.kappa_min);
    cJSON_AddItemToObject(root, "principal_curvature_min_at",
                          cli_json_vector((double[]){st->survey.kappa_min_phi, st->survey.kappa_min_theta}, 2));
    cli_json_add(root, "negative_curvature_fraction", st->survey.negative_fraction);
    cli_json_add(root, "convexity_beta_limit", st->beta_limit);
    if (isnan(st->beta_limit)) cJSON_AddStringToObject(root, "convexity_beta_limit_note", st->limit_note);
    cJSON_AddItemToObject(root, "convexity_lost_at", cli_json_vector((double[]){st->limit_phi, st->limit_theta}, 2));
    cJSON_AddBoolToObject(root, "convex", st->convex);
    cJSON *eqs = cJSON_AddArrayToObject(root, "equilibria");
    for (size_t k = 0; k < st->equilibria.count; k++) {
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "type", gb_shape_equilibrium_name(st->equilibria.points[k].type));
        cli_json_add(e, "phi", st->equilibria.points[k].phi);
        cli_json_add(e, "theta", st->equilibria.points[k].theta);
        cli_json_add(e, "r", st->equilibria.points[k].r);
        cJSON_AddItemToArray(eqs, e);
    }
    cli_json_add(root, "polar_cap_gradient_min", st->equilibria.polar_gradient_min);
    cJSON *h = cJSON_AddObjectToObject(root, "hull_equilibria");
    cJSON_AddItemToObject(h, "sample", cli_json_vector((double[]){(double)st->sdef.hull_phi, (double)st->sdef.hull_theta}, 2));
    cli_json_add(h, "neighbourhood_rad", st->sdef.hull_neighbourhood);
    cli_json_add(h, "vertices", (double)st->hull.vertices);
    cli_json_add(h, "sampled_fraction_on_hull", st->hull.sampled_fraction_on_hull);
    cli_json_add(h, "raw_stable", (double)st->hull.raw_stable);
    cli_json_add(h, "raw_unstable", (double)st->hull.raw_unstable);
    cli_json_add(h, "stable", (double)st->hull.stable);
    cli_json_add(h, "unstable", (double)st->hull.unstable);
    cJSON *rests = cJSON_AddArrayToObject(h, "rests");
    for (size_t k = 0; k < st->hull.stable; k++) {
        cJSON *r = cJSON_CreateObject();
        cJSON_AddItemToObject(r, "normal", cli_json_vector(st->hull.rests[k].normal, 3));
        cli_json_add(r, "height", st->hull.rests[k].height);
        cJSON_AddItemToArray(rests, r);
    }
    cJSON *tops = cJSON_AddArrayToObject(h, "unstable_points");
    for (size_t k = 0; k < st->hull.unstable; k++) cJSON_AddItemToArray(tops, cli_json_vector(st->hull.unstable_points[k], 3));
    cJSON_AddBoolToObject(root, "mono_monostatic", st->mono);

    return root;
}

static void print_shape(const shape_study *st)
{
    /* beta is the body's only where it enters it: the paper's morphologies, and a body of one's own that names it */
    const int beta_used = !gb_body_is_own(&st->surface) || gb_body_names_beta(&st->surface);
    if (beta_used)
        printf("body             morphology %s (chi = %s), beta = %.17g, mass = %g\n", st->surface.morphology->name,
               st->surface.morphology->chi_formula, st->beta, st->mass);
    else
        printf("body             %s (chi = %s; beta not used), mass = %g\n", st->surface.morphology->name,
               st->surface.morphology->chi_formula, st->mass);
    printf("volume           %.15g  (+- %.1e)\n", st->props.volume, st->props.volume_err);
    printf("centroid         %.3e %.3e %.3e  (+- %.1e)\n", st->props.centroid[0], st->props.centroid[1],
           st->props.centroid[2], st->props.centroid_err[0]);
    if (st->surface.morphology->moved)
        printf("moved            to its centroid: r is measured from (%.10g, %.10g, %.10g), the chart's origin\n",
               st->surface.morphology->origin[0], st->surface.morphology->origin[1], st->surface.morphology->origin[2]);
    for (int i = 0; i < 3; i++)
        printf("%s %15.12f %15.12f %15.12f\n", i ? "                " : "inertia (I_C)   ",
               st->props.inertia[i][0], st->props.inertia[i][1], st->props.inertia[i][2]);
    printf("L (eq 53)        %.15g  (+- %.1e)\n", st->props.L, st->props.L_err);
    printf("curvature min    K = %.10g at (phi, theta) = (%.8f, %.8f)\n", st->survey.K_min, st->survey.K_min_phi, st->survey.K_min_theta);
    printf("                 kappa_1 = %.10g at (%.8f, %.8f)\n", st->survey.kappa_min, st->survey.kappa_min_phi, st->survey.kappa_min_theta);
    printf("negative K       %.6f of the area\n", st->survey.negative_fraction);
    if (isnan(st->beta_limit)) printf("convex up to     (not computed: %s)\n", st->limit_note);
    else printf("convex up to     beta = %.12g (lost at phi = %.8f, theta = %.8f)\n", st->beta_limit, st->limit_phi, st->limit_theta);
    printf("convex           %s\n", st->convex ? "yes" : "no");
    printf("critical points of r: %d stable, %d saddle, %d unstable (min |grad r| in polar caps %.3g)\n",
           st->equilibria.stable, st->equilibria.saddle, st->equilibria.unstable, st->equilibria.polar_gradient_min);
    for (size_t k = 0; k < st->equilibria.count; k++)
        printf("  %-8s phi = %.10f theta = %.10f r = %.12f\n", gb_shape_equilibrium_name(st->equilibria.points[k].type),
               st->equilibria.points[k].phi, st->equilibria.points[k].theta, st->equilibria.points[k].r);
    printf("convex hull      %zux%zu sample, %zu vertices (%.4f of the sample)\n", st->sdef.hull_phi, st->sdef.hull_theta,
           st->hull.vertices, st->hull.sampled_fraction_on_hull);
    printf("  raw polyhedral equilibria: %zu resting faces, %zu unstable vertices\n", st->hull.raw_stable, st->hull.raw_unstable);
    printf("  robust within %.2f rad:    %zu resting faces, %zu unstable vertices\n", st->sdef.hull_neighbourhood,
           st->hull.stable, st->hull.unstable);
    for (size_t k = 0; k < st->hull.stable; k++)
        printf("    rest on normal (%.5f, %.5f, %.5f), centroid height %.8f\n", st->hull.rests[k].normal[0],
               st->hull.rests[k].normal[1], st->hull.rests[k].normal[2], st->hull.rests[k].height);
    printf("mono-monostatic  %s\n", st->mono ? "yes" : "no");
}

/* The hull's triangles about the centroid, %.17g. */
static int write_faces(const gb_polyhedron *p, const double centroid[3], const char *path)
{
    size_t cap = 128 + p->triangle_count * 260, used = 0;
    char *text = malloc(cap);
    if (!text) return gb_error_set(GB_ENOMEM, "out of memory for the faces");
    used += (size_t)snprintf(text, cap, "# gomboc hull triangles: body axes about the centroid [m]\ntriangle,x0,y0,z0,x1,y1,z1,x2,y2,z2\n");
    for (size_t k = 0; k < p->triangle_count; k++) {
        used += (size_t)snprintf(text + used, cap - used, "%zu", k);
        for (int c = 0; c < 3; c++)
            for (int i = 0; i < 3; i++)
                used += (size_t)snprintf(text + used, cap - used, ",%.17g", p->vertices[3 * p->triangles[3 * k + c] + i] - centroid[i]);
        used += (size_t)snprintf(text + used, cap - used, "\n");
    }
    const int status = cli_write_atomically(path, text);
    free(text);
    return status;
}

/* gomboc shape --mesh: the polyhedron of a mesh file. */
static int shape_mesh(const char *path, double mass, int json, const char *faces_path)
{
    gb_mesh mesh;
    gb_polyhedron p;
    gb_massprops props;
    double normals[64][3];
    size_t rests = 0;
    int status = gb_mesh_read(path, &mesh);
    if (status == GB_EIO || status == GB_EINVAL) /* unreadable, no regular file, or not a mesh: bad input */
        return cli_input_error("shape", "--mesh %s%s", gb_error_message(),
                               strstr(gb_error_message(), "allowed") ? "" : " (allowed: a readable mesh file)");
    if (status) return cli_failure("shape", status);
    status = gb_polyhedron_from_mesh(&mesh, path, &p);
    if (!status) {
        status = gb_polyhedron_massprops(&p, mass, &props);
        if (!status) status = gb_polyhedron_rest_faces(&p, props.centroid, normals, 64, &rests);
        if (status) gb_polyhedron_free(&p);
    }
    if (!status && faces_path) {
        status = write_faces(&p, props.centroid, faces_path);
        if (status) gb_polyhedron_free(&p);
    }
    if (status) {
        gb_mesh_free(&mesh);
        return cli_failure("shape", status);
    }
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "mesh", path);
    cJSON_AddStringToObject(root, "format", gb_mesh_format_name(mesh.format));
    cli_json_add(root, "mesh_vertices", (double)mesh.vertex_count);
    cli_json_add(root, "hull_vertices", (double)p.vertex_count);
    cli_json_add(root, "hull_triangles", (double)p.triangle_count);
    cli_json_add(root, "mass", mass);
    cli_json_add(root, "volume", props.volume);
    cJSON_AddItemToObject(root, "centroid", cli_json_vector(props.centroid, 3));
    cJSON *inertia = cJSON_AddArrayToObject(root, "inertia");
    for (int i = 0; i < 3; i++) cJSON_AddItemToArray(inertia, cli_json_vector(props.inertia[i], 3));
    cJSON *faces = cJSON_AddArrayToObject(root, "rest_faces");
    for (size_t k = 0; k < rests && k < 64; k++) cJSON_AddItemToArray(faces, cli_json_vector(normals[k], 3));
    cli_json_add(root, "rest_face_count", (double)rests);
    if (json) {
        cli_print_json(root);
    } else {
        printf("mesh             %s (%s): %zu vertices; convex hull %zu vertices, %zu triangles\n", path,
               gb_mesh_format_name(mesh.format), mesh.vertex_count, p.vertex_count, p.triangle_count);
        printf("mass             %.10g kg\nvolume           %.10g m^3\n", mass, props.volume);
        printf("centroid         %.10g %.10g %.10g\n", props.centroid[0], props.centroid[1], props.centroid[2]);
        for (int i = 0; i < 3; i++)
            printf("%s %.10g %.10g %.10g\n", i ? "                " : "inertia about G ", props.inertia[i][0] + 0.0,
                   props.inertia[i][1] + 0.0, props.inertia[i][2] + 0.0);
        printf("rests stably on  %zu faces (outward normals):\n", rests);
        for (size_t k = 0; k < rests && k < 64; k++) /* + 0.0: no "-0.000000" */
            printf("    %.6f %.6f %.6f\n", normals[k][0] + 0.0, normals[k][1] + 0.0, normals[k][2] + 0.0);
    }
    cJSON_Delete(root);
    gb_polyhedron_free(&p);
    gb_mesh_free(&mesh);
    return 0;
}

int command_shape(int argc, char **argv)
{
    const char *radial_map = NULL, *grid_nodes = NULL, *mesh = NULL, *scene_path = NULL, *faces = NULL;
    double mass = 1.0;
    int json = 0, mass_given = 0;
    cli_body body = {NULL, NAN, 0};
    static const char *const valued[] = {"--morphology", "--beta", "--mass", "--radial-map", "--grid-nodes", "--mesh", "--scene",
                                         "--faces", NULL};
    for (int i = 0; i < argc; i++) {
        const char *opt = argv[i], *value = NULL;
        const int kind = cli_next_option("shape", argc, argv, &i, usage_shape, valued,
                                         " (allowed: --morphology, --beta, --mass, --json, --radial-map, --grid-nodes, --mesh, --scene, --faces, --help)", &body, &json, &value);
        if (kind != CLI_VALUE) {
            if (kind == CLI_NEXT) continue;
            return kind == CLI_HELP ? 0 : kind;
        }
        if (!strcmp(opt, "--mass")) {
            mass_given = 1;
            if (cli_number("shape", "--mass", value, 1e-6, 1e6, 0, " (allowed: 1e-06 <= mass <= 1000000 [kg])", &mass))
                return EXIT_INPUT;
        } else if (!strcmp(opt, "--radial-map")) {
            radial_map = value;
        } else if (!strcmp(opt, "--grid-nodes")) {
            grid_nodes = value;
        } else if (!strcmp(opt, "--scene")) {
            scene_path = value;
        } else if (!strcmp(opt, "--faces")) {
            faces = value;
        } else {
            mesh = value;
        }
    }
    if (mesh) {
        if (body.morphology || body.have_beta || radial_map || grid_nodes || scene_path)
            return cli_input_error("shape", "--mesh names the body: not with --morphology, --beta, --radial-map or --grid-nodes "
                                   "(allowed: --mesh FILE [--mass M] [--json] [--faces FILE])");
        const gb_file_use in[] = {GB_FILE_USE(mesh, "--mesh", GB_FILE_INPUT), GB_FILE_USE(faces, "--faces", GB_FILE_OUTPUT)};
        if (cli_files_check("shape", in, 2)) return EXIT_INPUT;
        if (cli_parse_only) return 0;
        return shape_mesh(mesh, mass, json, faces);
    }
    gb_surface surface;
    gb_case scene;
    if (scene_path) {
        if (body.morphology || body.have_beta || mass_given)
            return cli_input_error("shape", "--scene names the body and its mass: not with --morphology, --beta, --mass or --mesh "
                                   "(allowed: --scene FILE [--json] [--radial-map FILE] [--grid-nodes FILE] [--faces FILE])");
        const gb_file_use in[] = {GB_FILE_USE(scene_path, "--scene", GB_FILE_INPUT), GB_FILE_USE(faces, "--faces", GB_FILE_OUTPUT)};
        if (cli_files_check("shape", in, 2)) return EXIT_INPUT;
        if (gb_case_load(scene_path, &scene)) return cli_input_error("shape", "--scene %s", gb_error_message());
        mass = scene.dynamics.mass;
        if (gb_surface_is_polyhedron(&scene.body)) {
            if (radial_map || grid_nodes)
                return cli_input_error("shape", "--scene %s has a mesh body: --radial-map and --grid-nodes are for a smooth "
                                       "body (allowed: --scene FILE [--json] with a mesh)", scene_path);
            if (cli_parse_only) return 0;
            char file[PATH_MAX];
            if (gb_case_mesh_path(scene_path, &scene, file, sizeof file)) return cli_input_error("shape", "--scene %s", gb_error_message());
            return shape_mesh(file, mass, json, faces);
        }
        if (faces)
            return cli_input_error("shape", "--scene %s has a smooth body: --faces is for a mesh body (allowed: --radial-map FILE "
                                   "for a smooth one)", scene_path);
        surface = scene.body;
    } else if (faces) {
        return cli_input_error("shape", "--faces is for a mesh body (allowed: --mesh FILE or --scene FILE with a mesh)");
    } else if (cli_body_required("shape", &body)) {
        return EXIT_INPUT;
    }
    /* no output may be an input: the scene is named beside the outputs (its mesh, if any, was refused above) */
    const gb_file_use uses[] = {GB_FILE_USE(scene_path, "--scene", GB_FILE_INPUT),
                                GB_FILE_USE(radial_map, "--radial-map", GB_FILE_OUTPUT),
                                GB_FILE_USE(grid_nodes, "--grid-nodes", GB_FILE_OUTPUT)};
    if (cli_files_check("shape", uses, 3)) return EXIT_INPUT;
    if (cli_parse_only) return 0;
    const double beta = scene_path ? surface.beta : body.beta;

    gb_massprops props;
    gb_massprops_def mdef = gb_massprops_default_def();
    gb_shape_def sdef = gb_shape_default_def();
    gb_curvature_survey survey;
    gb_equilibria equilibria;
    gb_hull_equilibria hull;
    double beta_limit, limit_phi, limit_theta;
    mdef.mass = mass;
    char limit_note[200] = "";
    int status = scene_path ? GB_OK : gb_surface_init(&surface, body.morphology, beta);
    if (!status) status = gb_massprops_compute(&surface, &mdef, &props);
    if (!status) status = gb_shape_curvature_survey(&surface, &sdef, &survey);
    if (!status && gb_body_is_own(&surface) && gb_body_names_beta(&surface) && surface.morphology->phase) {
        /* chi(beta) is fixed at the scene's beta in its row: the family in beta is not the one chi names */
        beta_limit = limit_phi = limit_theta = NAN;
        snprintf(limit_note, sizeof limit_note, "chi names beta, so the family in beta is not r^4 = 1 + 4 beta sin(phi) cos(chi)");
    } else if (!status) {
        status = gb_shape_convexity_limit(surface.morphology, &sdef, &beta_limit, &limit_phi, &limit_theta);
        if (status && gb_body_is_own(&surface)) { /* a body of one's own need not lose convexity in [0, 1/4) */
            snprintf(limit_note, sizeof limit_note, "%s", gb_error_message());
            gb_error_clear();
            beta_limit = limit_phi = limit_theta = NAN;
            status = GB_OK;
        }
    }
    if (!status) status = gb_shape_equilibria(&surface, &sdef, &equilibria);
    if (!status) status = gb_shape_hull_equilibria(&surface, &sdef, &hull);
    if (!status && radial_map) status = write_radial_map(&surface, radial_map);
    if (!status && grid_nodes) status = write_grid_nodes(&surface, grid_nodes);
    if (status) return cli_failure("shape", status);
    shape_study study = {.surface = surface, .beta = beta, .mass = mass, .props = props, .sdef = sdef, .survey = survey,
                         .equilibria = equilibria, .hull = hull, .beta_limit = beta_limit, .limit_phi = limit_phi,
                         .limit_theta = limit_theta};
    snprintf(study.limit_note, sizeof study.limit_note, "%s", limit_note);
    study.convex = survey.kappa_min > 0.0;
    study.mono = study.convex ? equilibria.stable == 1 && equilibria.unstable == 1 : hull.stable == 1 && hull.unstable == 1;
    cJSON *root = shape_json(&study);
    if (json) cli_print_json(root);
    else print_shape(&study);
    cJSON_Delete(root);
    return 0;
}

