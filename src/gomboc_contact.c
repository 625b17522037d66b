/* gomboc contact — the contact point of one body for one body-frame vertical z_b (paper §4). */
#include "gomboc_cli.h"

#include "gb_contact.h"
#include "gb_error.h"
#include "gb_parse.h"
#include "gb_surface.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *usage_contact =
    "usage: gomboc contact --morphology I|II --beta B --zb X,Y,Z --method grid|fast-grid|continuous\n"
    "                      [--grid NPxNT] [--nodes centred|linspace] [--json]\n"
    "                      [--landscape FILE] [--zoom FILE] [--zoom-halfwidth W]\n"
    "\n"
    "  --morphology I|II  phase function chi (eqs 8, 9)\n"
    "  --beta B           shape parameter, 0 <= B < 0.25\n"
    "  --zb X,Y,Z         the upward vertical in the body frame, z_b = R^T e_z (eq 28); any non-zero\n"
    "                     length (it is normalised; heights are along the unit vertical)\n"
    "  --method M         grid: the lowest node of the N_phi x N_theta grid by brute force, as the\n"
    "                     paper (section 8); fast-grid: the same node by branch and bound;\n"
    "                     continuous: every local minimum polished by Newton (eqs 31-35)\n"
    "  --grid NPxNT       grid size, 2 <= NP, NT and NP*NT <= 67108864 (default 90x180 as Table 1\n"
    "                     for the grid methods; for continuous the seed grid, default 180x360)\n"
    "  --nodes P          node placement: centred (phi_i = (i+1/2) pi/NP, theta_j = 2 pi j/NT; the\n"
    "                     default) or linspace (phi_i = i pi/(NP-1), theta_j = 2 pi j/(NT-1))\n"
    "  --json             print one JSON object: phi, theta, height, rc, index, branches, gap, ...\n"
    "  --landscape FILE   write h(phi, theta) at every node of the grid as CSV (Figure 2)\n"
    "  --zoom FILE        write h on a 201 x 201 window around the contact as CSV\n"
    "  --zoom-halfwidth W half-width of that window in phi and theta [rad], 0 < W <= 1 (default 0.25)\n"
    "\n"
    "Prints the contact (phi*, theta*, h*, r_c; the grid index for the grid methods) and every local\n"
    "minimum of h with its height (branches, from continuous minimisation seeded on the 180x360 grid\n"
    "or, for --method continuous, on --grid), and the gap between the two lowest (eqs 38-39).\n";


/* h at every node of `grid` as CSV, written to the member `file` of the command's output set. */
static int write_landscape(const gb_contact_grid *grid, const double zb[3], FILE *file)
{
    const gb_contact_grid_def *def = gb_contact_grid_get_def(grid);
    const gb_surface *surface = gb_contact_grid_surface(grid);
    const size_t size = gb_contact_grid_size(grid);
    size_t cap = 512 + size * 64, used = 0;
    char *text = malloc(cap);
    if (!text) return gb_error_set(GB_ENOMEM, "out of memory for the landscape");
    used += (size_t)snprintf(text, cap,
                             "# gomboc height landscape: morphology %s, beta %.17g, z_b %.17g %.17g %.17g, grid "
                             "%zux%zu %s\nphi,theta,height\n",
                             surface->morphology->name, surface->beta, zb[0], zb[1], zb[2], def->n_phi,
                             def->n_theta, gb_contact_nodes_name(def->nodes));
    for (size_t k = 0; k < size; k++) {
        double phi, theta, x[3];
        gb_contact_grid_node(grid, k, &phi, &theta, x);
        used += (size_t)snprintf(text + used, cap - used, "%.9g,%.9g,%.12g\n", phi, theta,
                                 zb[0] * x[0] + zb[1] * x[1] + zb[2] * x[2]);
    }
    const int status = fputs(text, file) < 0 ? gb_error_set(GB_EIO, "cannot write the landscape: %s", strerror(errno)) : GB_OK;
    free(text);
    return status;
}

/* h on a 201 × 201 window of half-width w around (φ*, θ*), as CSV. */
static int write_zoom(const gb_surface *surface, const double zb[3], double phi0, double theta0, double w,
                      FILE *file)
{
    enum { N = 201 };
    size_t cap = 512 + (size_t)N * N * 64, used = 0;
    char *text = malloc(cap);
    if (!text) return gb_error_set(GB_ENOMEM, "out of memory for the zoom window");
    used += (size_t)snprintf(text, cap,
                             "# gomboc height zoom: morphology %s, beta %.17g, z_b %.17g %.17g %.17g, centre "
                             "%.17g %.17g, half-width %.17g\nphi,theta,height\n",
                             surface->morphology->name, surface->beta, zb[0], zb[1], zb[2], phi0, theta0, w);
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            const double phi = phi0 + w * (2.0 * i / (N - 1) - 1.0), theta = theta0 + w * (2.0 * j / (N - 1) - 1.0);
            double x[3];
            gb_surface_position(surface, phi, theta, x);
            used += (size_t)snprintf(text + used, cap - used, "%.12g,%.12g,%.12g\n", phi, theta,
                                     zb[0] * x[0] + zb[1] * x[1] + zb[2] * x[2]);
        }
    const int status = fputs(text, file) < 0 ? gb_error_set(GB_EIO, "cannot write the zoom window: %s", strerror(errno)) : GB_OK;
    free(text);
    return status;
}

static cJSON *point_json(const gb_contact_point *p)
{
    cJSON *o = cJSON_CreateObject();
    cli_json_add(o, "phi", p->phi);
    cli_json_add(o, "theta", p->theta);
    cli_json_add(o, "height", p->height);
    cJSON_AddItemToObject(o, "rc", cli_json_vector(p->rc, 3));
    cJSON_AddItemToObject(o, "hessian", cli_json_vector(p->hessian, 3));
    cli_json_add(o, "residual", p->residual);
    return o;
}

/* What `gomboc contact` found, for its JSON and its text. */
typedef struct contact_answer {
    const gb_surface *surface;
    double beta, unit[3];
    gb_contact_model method;
    gb_contact_grid_def grid_def, seed_def;
    gb_contact_node node;       /* the grid methods' node */
    size_t grid_size;           /* the grid methods' node count */
    const gb_contact_branches *branches;
    double phi, theta;          /* the contact's angles by the method asked for */
} contact_answer;

static cJSON *contact_json(const contact_answer *a)
{
    const gb_contact_point *contact = &a->branches->branch[0];
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "morphology", a->surface->morphology->name);
    cli_json_add(root, "beta", a->beta);
    cJSON_AddItemToObject(root, "zb", cli_json_vector(a->unit, 3));
    cJSON_AddStringToObject(root, "method", gb_contact_model_name(a->method));
    if (a->method != GB_CONTACT_MODEL_CONTINUOUS) {
        cJSON_AddItemToObject(root, "grid", cli_json_vector((double[]){(double)a->grid_def.n_phi, (double)a->grid_def.n_theta}, 2));
        cJSON_AddStringToObject(root, "nodes", gb_contact_nodes_name(a->grid_def.nodes));
        cli_json_add(root, "phi", a->node.phi);
        cli_json_add(root, "theta", a->node.theta);
        cli_json_add(root, "height", a->node.height);
        cJSON_AddItemToObject(root, "rc", cli_json_vector(a->node.x, 3));
        cli_json_add(root, "index", (double)a->node.index);
        cli_json_add(root, "nodes_visited", (double)a->node.visited);
    } else {
        cJSON_AddItemToObject(root, "grid", cli_json_vector((double[]){(double)a->seed_def.n_phi, (double)a->seed_def.n_theta}, 2));
        cJSON_AddStringToObject(root, "nodes", gb_contact_nodes_name(a->seed_def.nodes));
        cli_json_add(root, "phi", contact->phi);
        cli_json_add(root, "theta", contact->theta);
        cli_json_add(root, "height", contact->height);
        cJSON_AddItemToObject(root, "rc", cli_json_vector(contact->rc, 3));
        cJSON_AddNullToObject(root, "index");
        cli_json_add(root, "residual", contact->residual);
    }
    cJSON *list = cJSON_AddArrayToObject(root, "branches");
    for (size_t k = 0; k < a->branches->count; k++) cJSON_AddItemToArray(list, point_json(&a->branches->branch[k]));
    if (isfinite(a->branches->gap)) cli_json_add(root, "gap", a->branches->gap);
    else cJSON_AddNullToObject(root, "gap");
    cJSON_AddItemToObject(root, "branch_seed_grid", cli_json_vector((double[]){(double)a->seed_def.n_phi, (double)a->seed_def.n_theta}, 2));
    return root;
}

static void print_contact(const contact_answer *a)
{
    const gb_contact_point *contact = &a->branches->branch[0];
    const int continuous = a->method == GB_CONTACT_MODEL_CONTINUOUS;
    printf("body          morphology %s (chi = %s), beta = %.17g\n", a->surface->morphology->name,
           a->surface->morphology->chi_formula, a->beta);
    printf("z_b (unit)    %.12f %.12f %.12f\n", a->unit[0], a->unit[1], a->unit[2]);
    if (!continuous)
        printf("method        %s on a %zux%zu %s grid: node %zu (%zu of %zu nodes visited)\n", gb_contact_model_name(a->method),
               a->grid_def.n_phi, a->grid_def.n_theta, gb_contact_nodes_name(a->grid_def.nodes), a->node.index,
               a->node.visited, a->grid_size);
    else
        printf("method        continuous (Newton, eqs 31-35) seeded on a %zux%zu grid; |z_b x n| = %.2e\n",
               a->seed_def.n_phi, a->seed_def.n_theta, contact->residual);
    const double *rc = continuous ? contact->rc : a->node.x;
    printf("contact       phi* = %.12f  theta* = %.12f  h* = %.15f\n", a->phi, a->theta,
           continuous ? contact->height : a->node.height);
    printf("r_c           %.12f %.12f %.12f\n", rc[0], rc[1], rc[2]);
    printf("local minima  %zu (seeded on %zux%zu)", a->branches->count, a->seed_def.n_phi, a->seed_def.n_theta);
    if (isfinite(a->branches->gap)) printf(", gap h2 - h1 = %.6e", a->branches->gap);
    printf("\n");
    for (size_t k = 0; k < a->branches->count; k++)
        printf("  %zu  phi = %.12f  theta = %.12f  h = %.15f\n", k + 1, a->branches->branch[k].phi,
               a->branches->branch[k].theta, a->branches->branch[k].height);
}

int command_contact(int argc, char **argv)
{
    const char *landscape = NULL, *zoom = NULL;
    double zb[3] = {0, 0, 0}, zoom_halfwidth = 0.25;
    int json = 0, have_zb = 0, have_grid = 0, have_method = 0;
    gb_contact_model method = GB_CONTACT_MODEL_GRID;
    cli_body body = {NULL, NAN, 0};
    gb_contact_grid_def grid_def = gb_contact_grid_default_def();
    static const char *const valued[] = {"--morphology", "--beta", "--zb", "--method", "--grid", "--nodes",
                                         "--landscape", "--zoom", "--zoom-halfwidth", NULL};
    for (int i = 0; i < argc; i++) {
        const char *opt = argv[i], *value = NULL;
        const int kind = cli_next_option("contact", argc, argv, &i, usage_contact, valued,
                                         " (allowed: --morphology, --beta, --zb, --method, --grid, --nodes, --json, "
                                         "--landscape, --zoom, --zoom-halfwidth, --help)", &body, &json, &value);
        if (kind != CLI_VALUE) {
            if (kind == CLI_NEXT) continue;
            return kind == CLI_HELP ? 0 : kind;
        }
        if (!strcmp(opt, "--zb")) {
            static const char *const zb_allowed = " (allowed: X,Y,Z, each -1e100 <= component <= 1e100, not all zero, of "
                                                  "length at least 1e-100)";
            const gb_parse_result p = gb_parse_list(value, zb, 3);
            if (p == GB_PARSE_OVERFLOW) return cli_input_error("contact", "--zb '%s' is beyond the range of a double%s", value, zb_allowed);
            if (p) return cli_input_error("contact", "--zb '%s' is not three numbers%s", value, zb_allowed);
            if (!(fabs(zb[0]) <= 1e100 && fabs(zb[1]) <= 1e100 && fabs(zb[2]) <= 1e100))
                return cli_input_error("contact", "--zb '%s' is out of range%s", value, zb_allowed);
            if (zb[0] == 0.0 && zb[1] == 0.0 && zb[2] == 0.0)
                return cli_input_error("contact", "--zb '%s' is the zero vector%s", value, zb_allowed);
            /* its square must not underflow: the length from hypot, which does not square */
            if (!(hypot(hypot(zb[0], zb[1]), zb[2]) >= 1e-100))
                return cli_input_error("contact", "--zb '%s' is too short to give a direction%s", value, zb_allowed);
            have_zb = 1;
        } else if (!strcmp(opt, "--method")) {
            if (gb_contact_model_parse(value, &method))
                return cli_input_error("contact", "--method '%s' is unknown %s", value, cli_allowed());
            have_method = 1;
        } else if (!strcmp(opt, "--grid")) {
            unsigned long long np, nt;
            const gb_parse_result p = gb_parse_pair(value, GB_CONTACT_GRID_MAX_NODES, &np, &nt);
            if (p || np < 2 || nt < 3 || np > GB_CONTACT_GRID_MAX_NODES / nt)
                return cli_input_error("contact", "--grid '%s' is %s%s", value, p == GB_PARSE_SYNTAX ? "not a grid" : "out of range",
                                       " (allowed: NPxNT with NP >= 2, NT >= 3, NP*NT <= 67108864)");
            grid_def.n_phi = (size_t)np;
            grid_def.n_theta = (size_t)nt;
            have_grid = 1;
        } else if (!strcmp(opt, "--nodes")) {
            if (gb_contact_nodes_parse(value, &grid_def.nodes))
                return cli_input_error("contact", "--nodes '%s' is unknown %s", value, cli_allowed());
        } else if (!strcmp(opt, "--landscape")) {
            landscape = value;
        } else if (!strcmp(opt, "--zoom")) {
            zoom = value;
        } else {
            if (cli_number("contact", "--zoom-halfwidth", value, 0.0, 1.0, CLI_OPEN_MIN, " (allowed: 0 < W <= 1 rad)",
                           &zoom_halfwidth))
                return EXIT_INPUT;
        }
    }
    if (cli_body_required("contact", &body)) return EXIT_INPUT;
    const char *morphology = body.morphology;
    const double beta = body.beta;
    if (!have_zb) return cli_input_error("contact", "missing %s%s", "--zb", " (allowed: X,Y,Z, not all zero)");
    if (!have_method) {
        gb_contact_model_parse(NULL, &method); /* its message lists the models */
        return cli_input_error("contact", "missing --method %s", cli_allowed());
    }
    const gb_file_use uses[] = {GB_FILE_USE(landscape, "--landscape", GB_FILE_OUTPUT), GB_FILE_USE(zoom, "--zoom", GB_FILE_OUTPUT)};
    if (cli_files_check("contact", uses, 2)) return EXIT_INPUT;
    if (cli_parse_only) return 0;

    gb_surface surface;
    int status = gb_surface_init(&surface, morphology, beta);
    if (status) return cli_failure("contact", status);
    /* The seed grid of the branch search; for --method continuous, --grid replaces it. */
    gb_contact_grid_def seed_def = gb_contact_default_branch_grid();
    if (method == GB_CONTACT_MODEL_CONTINUOUS) {
        if (have_grid) seed_def.n_phi = grid_def.n_phi, seed_def.n_theta = grid_def.n_theta;
        seed_def.nodes = grid_def.nodes;
    }
    gb_contact_grid *grid = NULL, *seeds = NULL;
    gb_contact_node node;
    gb_contact_branches branches;
    gb_contact_refine_def refine = gb_contact_refine_default_def();
    status = gb_contact_grid_create(&surface, &seed_def, &seeds);
    if (!status && method != GB_CONTACT_MODEL_CONTINUOUS) status = gb_contact_grid_create(&surface, &grid_def, &grid);
    if (!status && method == GB_CONTACT_MODEL_GRID) status = gb_contact_grid_brute(grid, zb, &node);
    if (!status && method == GB_CONTACT_MODEL_FAST_GRID) status = gb_contact_grid_fast(grid, zb, &node);
    if (!status) status = gb_contact_branches_find(seeds, zb, &refine, &branches);
    double unit[3];
    if (!status) status = gb_contact_unit_vertical(zb, unit);
    const gb_contact_point *contact = &branches.branch[0];
    double phi = NAN, theta = NAN;
    if (!status) {
        phi = method == GB_CONTACT_MODEL_CONTINUOUS ? contact->phi : node.phi;
        theta = method == GB_CONTACT_MODEL_CONTINUOUS ? contact->theta : node.theta;
    }
    /* The two files are one set: both are written, or neither. */
    gb_file_set files = {0};
    if (landscape) {
        FILE *f = gb_file_set_open(&files, landscape, &status);
        if (f) status = write_landscape(grid ? grid : seeds, unit, f);
    }
    if (zoom) {
        FILE *f = gb_file_set_open(&files, zoom, &status);
        if (f) status = write_zoom(&surface, unit, phi, theta, zoom_halfwidth, f);
    }
    status = gb_file_set_commit(&files, status);
    if (status) {
        gb_contact_grid_free(grid);
        gb_contact_grid_free(seeds);
        return cli_failure("contact", status);
    }

    const contact_answer answer = {&surface, beta, {unit[0], unit[1], unit[2]}, method, grid_def, seed_def, node,
                                   grid ? gb_contact_grid_size(grid) : 0, &branches, phi, theta};
    cJSON *root = contact_json(&answer);
    if (json) cli_print_json(root);
    else print_contact(&answer);
    cJSON_Delete(root);
    gb_contact_grid_free(grid);
    gb_contact_grid_free(seeds);
    return 0;
}
