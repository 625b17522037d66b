/* gomboc melnikov — the reduced separatrix-splitting criterion of §7 for one scene's body and forcing. */
#include "gomboc_cli.h"

#include "gb_error.h"
#include "gb_melnikov_body.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *usage_melnikov =
    "usage: gomboc melnikov CASE [--json] [--mass top|variable] [--weight exact|paper]\n"
    "                            [--damping paper|exact] [--curve FILE] [--curve-points N]\n"
    "                            [--tangle SPACING [--tangle-threshold N]]\n"
    "\n"
    "  CASE            a scene file: its body, mass, g, damping and forcing (omega, A1, A2, psi)\n"
    "  --json          print one JSON object: q_u, E_s, D, C1, S1, C2, S2, A1_star, A2_star, mu_D,\n"
    "                  eq93_holds, sign_change, epsilon, threshold_A1 (by eq 93 and exact), the body's\n"
    "                  top, rocking axis and contact ties\n"
    "  --mass          top (default): M frozen at M(q_u), the reading under which the reduced model is\n"
    "                  Hamiltonian; variable: M(q) of the body, which jumps at contact ties\n"
    "  --weight        exact (default): the splitting integral of q_dot G; paper: eq 86 as written (p G)\n"
    "  --damping       paper (default): -mu p with mu = c / M(q_u); exact: -c q_dot = -(c / M(q)) p (the\n"
    "                  same when M is frozen at the top)\n"
    "  --curve FILE    write the threshold A1 against omega as CSV (the scene's A2/A1 and psi), over\n"
    "                  omega +- 33 %% of the scene's in --curve-points points (default 13)\n"
    "  --tangle SPACING  also grow the period map's manifolds at the scene's whole forcing (not its\n"
    "                  first order) with points at most SPACING apart (1e-4 to 0.1; 0.01 is a good start)\n"
    "                  and count the homoclinic orbits a fundamental domain crosses (seconds to a minute;\n"
    "                  with --mass top only: its window is the unperturbed separatrix's passage)\n"
    "  --tangle-threshold N  also bracket the A1 at which the manifolds start to cross (A2 scaled with\n"
    "                  it, the damping kept; A2 when A1 = 0) by N bisections (1 to 30; each a tangle, 5 gives A1 / 32)\n"
    "\n"
    "The reduced model rocks the body about a horizontal axis through its top (docs/melnikov.md).\n";

static int parse_choice(const char *option, const char *value, const char *a, const char *b, int *out)
{
    if (!strcmp(value, a)) return *out = 0, 0;
    if (!strcmp(value, b)) return *out = 1, 0;
    return cli_input_error("melnikov", "%s %s: unknown (allowed: %s, %s)", option, value, a, b);
}

typedef struct melnikov_run {
    gb_melnikov_model model;
    gb_melnikov_orbit orbit;
    gb_melnikov_weight weight;
    double mu;            /* c / M(q_u), or c for the exact damping */
    int damping_exact;
    double psi;           /* of the scene */
    gb_melnikov_tables *tables; /* the separatrix tabulated per octave of omega, as a scan's */
} melnikov_run;

/* The integrals at omega and the critical A1 by both conditions (A2 scaled with it). */
static int threshold_at(melnikov_run *r, double omega, double A1, double A2, gb_melnikov_integrals *I,
                        double *by_eq93, double *exact)
{
    int status = gb_melnikov_tables_prepare(r->tables, omega);
    if (!status) status = gb_melnikov_tables_integrals(r->tables, omega, I);
    if (status) return status;
    *by_eq93 = *exact = NAN; /* no fundamental to scale */
    if (A1 == 0.0) return GB_OK;
    const gb_melnikov_forcing f = {r->mu, A1, A2, omega, r->psi, r->damping_exact};
    double s93, sx;
    gb_melnikov_threshold(I, &f, &s93, &sx);
    *by_eq93 = s93 * A1, *exact = sx * A1;
    return GB_OK;
}

/* The options of `gomboc melnikov`, read and checked. */
typedef struct melnikov_options {
    const char *case_path, *curve;
    int json, variable_mass, paper_weight, damping_exact;
    double points;  /* --curve-points */
    double spacing; /* --tangle; NAN: not asked for */
    double halvings; /* --tangle-threshold; 0: not asked for */
} melnikov_options;

/* Read the options into *o: -1 to go on, else the exit status (0 for --help). */
static int melnikov_options_read(int argc, char **argv, melnikov_options *o)
{
    *o = (melnikov_options){NULL, NULL, 0, 0, 0, 0, 13, NAN, 0};
    const char *points_text = NULL, *spacing_text = NULL, *halvings_text = NULL;
    static const char *const valued[] = {"--mass",   "--weight",           "--damping", "--curve", "--curve-points",
                                         "--tangle", "--tangle-threshold", NULL};
    for (int i = 0; i < argc; i++) {
        const char *opt = argv[i], *value = NULL;
        const int positional = cli_positional("melnikov", opt, &o->case_path, "case file", "CASE");
        if (positional) {
            if (positional == 1) continue;
            return positional;
        }
        const int kind = cli_next_option("melnikov", argc, argv, &i, usage_melnikov, valued,
                                         " (allowed: --json, --mass, --weight, --damping, --curve, --curve-points, --tangle, --tangle-threshold, --help)", NULL,
                                         &o->json, &value);
        if (kind != CLI_VALUE) {
            if (kind == CLI_NEXT) continue;
            return kind == CLI_HELP ? 0 : kind;
        }
        int bad = 0;
        if (!strcmp(opt, "--mass")) bad = parse_choice(opt, value, "top", "variable", &o->variable_mass);
        else if (!strcmp(opt, "--weight")) bad = parse_choice(opt, value, "exact", "paper", &o->paper_weight);
        else if (!strcmp(opt, "--damping")) bad = parse_choice(opt, value, "paper", "exact", &o->damping_exact);
        else if (!strcmp(opt, "--curve")) o->curve = value;
        else if (!strcmp(opt, "--tangle")) spacing_text = value;
        else if (!strcmp(opt, "--tangle-threshold")) halvings_text = value;
        else points_text = value;
        if (bad) return bad;
    }
    if (!o->case_path) return cli_input_error("melnikov", "missing %s%s", "CASE", " (allowed: a scene file, e.g. cases/table1-gomboc-I.ini)");
    if (points_text && !o->curve)
        return cli_input_error("melnikov", "--curve-points %s without --curve (allowed: --curve-points with --curve FILE)",
                               points_text);
    if (points_text && cli_number("melnikov", "--curve-points", points_text, 2, 1000, 0,
                                  " (allowed: an integer from 2 to 1000)", &o->points))
        return EXIT_INPUT;
    if (o->points != floor(o->points))
        return cli_input_error("melnikov", "--curve-points %s: not an integer (allowed: an integer from 2 to 1000)", points_text);
    if (spacing_text && cli_number("melnikov", "--tangle", spacing_text, 1e-4, 0.1, 0, " (allowed: a spacing from 1e-4 to 0.1)",
                                   &o->spacing))
        return EXIT_INPUT;
    if (spacing_text && o->variable_mass) /* the passage that sets the window is the unperturbed separatrix's */
        return cli_input_error("melnikov", "--tangle %s with --mass variable: the tangle's window is the unperturbed "
                               "separatrix's passage, and with M jumping at the ties there is no separatrix "
                               "(allowed: --tangle with --mass top, the default; docs/melnikov.md)", spacing_text);
    if (halvings_text && !spacing_text)
        return cli_input_error("melnikov", "--tangle-threshold %s without --tangle (allowed: --tangle-threshold with --tangle "
                               "SPACING)", halvings_text);
    if (halvings_text && cli_number("melnikov", "--tangle-threshold", halvings_text, 1, 30, 0,
                                    " (allowed: an integer from 1 to 30)", &o->halvings))
        return EXIT_INPUT;
    if (o->halvings != floor(o->halvings))
        return cli_input_error("melnikov", "--tangle-threshold %s: not an integer (allowed: an integer from 1 to 30)",
                               halvings_text);
    const gb_file_use uses[] = {GB_FILE_USE(o->case_path, "CASE", GB_FILE_INPUT), GB_FILE_USE(o->curve, "--curve", GB_FILE_OUTPUT)};
    if (cli_files_check("melnikov", uses, 2)) return EXIT_INPUT;
    return -1;
}

/* The tangle's summary and its confirmed homoclinic points in the window. */
static void tangle_json(cJSON *root, const gb_melnikov_tangle *t, double spacing, const double bracket[2])
{
    cJSON *o = cJSON_AddObjectToObject(root, "tangle");
    cli_json_add(o, "spacing", spacing);
    cJSON_AddItemToObject(o, "saddle", cli_json_vector(t->saddle, 2));
    cJSON_AddItemToObject(o, "multipliers", cli_json_vector(t->multipliers, 2));
    cli_json_add(o, "passage_periods", t->passage);
    cli_json_add(o, "iterates", t->iterates);
    cli_json_add(o, "window", t->window);
    cli_json_add(o, "points", (double)(t->points_unstable + t->points_stable));
    cli_json_add(o, "chord_crossings", (double)t->crossings);
    cli_json_add(o, "widest_gap", t->widest_gap); /* above the spacing: a gap whose parameter could not be split */
    cli_json_add(o, "homoclinic_orbits", (double)t->in_window);
    cli_json_add(o, "smallest_angle_deg", t->in_window ? t->smallest_angle * 180 / M_PI : NAN);
    if (!isnan(bracket[0])) cJSON_AddItemToObject(o, "threshold_A1", cli_json_vector(bracket, 2));
    cJSON *list = cJSON_AddArrayToObject(o, "homoclinic_points");
    for (size_t i = 0; i < t->crossings; i++) {
        const gb_melnikov_crossing *x = &t->crossing[i];
        if (x->confirmed != 1) continue;
        cJSON *row = cJSON_CreateObject();
        cli_json_add(row, "u", x->u);
        cli_json_add(row, "s", x->s);
        cli_json_add(row, "q", x->q);
        cli_json_add(row, "p", x->p);
        cli_json_add(row, "angle_deg", x->angle * 180 / M_PI);
        cJSON_AddItemToArray(list, row);
    }
}

int command_melnikov(int argc, char **argv)
{
    melnikov_options options;
    const int read = melnikov_options_read(argc, argv, &options);
    if (read >= 0) return read;
    const char *case_path = options.case_path, *curve = options.curve;
    const int json = options.json, variable_mass = options.variable_mass, paper_weight = options.paper_weight,
              damping_exact = options.damping_exact;
    const double points = options.points, spacing = options.spacing, halvings = options.halvings;
    double bracket[2] = {NAN, NAN}; /* --tangle-threshold: A1 without and with crossings */
    gb_case scene;
    int status = gb_case_load(case_path, &scene);
    if (status) return cli_failure("melnikov", status);
    const gb_forcing *F = &scene.dynamics.forcing;
    if (!(F->g > 0.0))
        return cli_input_error("melnikov", "%s: [forcing] g = %g: without gravity the reduced potential has no saddle (allowed: g > 0)",
                               case_path, F->g);
    if (cli_parse_only) return 0;

    gb_melnikov_body *body = NULL;
    status = gb_melnikov_body_create(&scene.body, scene.dynamics.mass, F->g, GB_MELNIKOV_BODY_NODES, &body);
    if (status) return cli_failure("melnikov", status);
    melnikov_run r = {.weight = paper_weight ? GB_MELNIKOV_PAPER : GB_MELNIKOV_EXACT, .psi = F->psi,
                      .damping_exact = damping_exact};
    r.model = gb_melnikov_body_model(body, variable_mass ? GB_MELNIKOV_MASS_VARIABLE : GB_MELNIKOV_MASS_AT_TOP);
    status = gb_melnikov_orbit_find(&r.model, &r.orbit);
    gb_melnikov_values top;
    if (!status) status = r.model.eval(r.model.context, r.orbit.q_u, &top);
    if (!status) status = gb_melnikov_tables_create(&r.model, &r.orbit, r.weight, &r.tables);
    gb_melnikov_integrals I;
    double t93 = NAN, tx = NAN;
    gb_melnikov_criterion c = {0};
    gb_melnikov_tangle tangle = {0};
    if (!status) {
        r.mu = damping_exact ? scene.dynamics.damping : scene.dynamics.damping / top.M;
        status = threshold_at(&r, F->omega, F->a1, F->a2, &I, &t93, &tx);
        const gb_melnikov_forcing f = {r.mu, F->a1, F->a2, F->omega, F->psi, damping_exact};
        gb_melnikov_judge(&I, &f, &c);
        if (!status && !isnan(spacing)) {
            gb_melnikov_tangle_def def = gb_melnikov_tangle_default_def();
            def.spacing = spacing;
            status = gb_melnikov_tangle_compute(&r.model, &r.orbit, &f, &def, &tangle);
            if (!status && halvings > 0) {
                status = gb_melnikov_tangle_threshold(&r.model, &r.orbit, &f, &def, (int)halvings, bracket);
                const double unit = F->a1 != 0.0 ? F->a1 : F->a2; /* A1's, or A2's without a fundamental */
                bracket[0] *= unit, bracket[1] *= unit;
            }
            if (status) /* said as the tangle's, not as the integrals' failure below */
                status = gb_error_set(status == GB_ENUMERIC ? GB_ENOCONV : status, "%s: --tangle %g: %s", case_path, spacing,
                                      gb_error_message());
        }
    }
    cJSON *root = NULL;
    FILE *csv = NULL;
    gb_file_set set = {0};
    if (!status && curve) {
        csv = gb_file_set_open(&set, curve, &status);
        if (csv && fputs("omega,threshold_A1_eq93,threshold_A1_exact,D,A1_star,A2_star\n", csv) < 0) status = GB_EIO;
        for (int k = 0; !status && k < (int)points; k++) {
            const double omega = F->omega * (2.0 / 3.0 + (2.0 / 3.0) * k / (points - 1.0));
            gb_melnikov_integrals J;
            double a, b;
            status = threshold_at(&r, omega, F->a1, F->a2, &J, &a, &b);
            if (!status && fprintf(csv, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", omega, a, b, J.D, J.A1, J.A2) < 0)
                status = gb_error_set(GB_EIO, "cannot write '%s'", curve);
        }
        if (status == GB_EIO) status = gb_error_set(GB_EIO, "cannot write '%s'", curve);
    }
    status = gb_file_set_commit(&set, status);
    gb_melnikov_body_info info;
    gb_melnikov_body_get_info(body, &info);
    if (!status) {
        root = cJSON_CreateObject();
        cJSON_AddStringToObject(root, "case", case_path);
        cJSON_AddStringToObject(root, "morphology", scene.body.morphology->name);
        cli_json_add(root, "beta", scene.body.beta);
        cJSON_AddStringToObject(root, "mass_reading", variable_mass ? "variable" : "top");
        cJSON_AddStringToObject(root, "weight", paper_weight ? "paper" : "exact");
        cJSON_AddStringToObject(root, "damping", damping_exact ? "exact: -c q_dot" : "paper: -mu p, mu = c / M(q_u)");
        cli_json_add(root, "D_mass", I.D_mass);
        cli_json_add(root, "q_u", r.orbit.q_u);
        cli_json_add(root, "E_s", r.orbit.E_s);
        cli_json_add(root, "U2", r.orbit.curvature);
        cli_json_add(root, "M_u", top.M);
        cli_json_add(root, "saddle_rate", r.orbit.rate);
        cli_json_add(root, "t0_point", r.orbit.q0);
        cli_json_add(root, "D", I.D);
        cli_json_add(root, "C1", I.C1);
        cli_json_add(root, "S1", I.S1);
        cli_json_add(root, "C2", I.C2);
        cli_json_add(root, "S2", I.S2);
        cli_json_add(root, "A1_star", I.A1);
        cli_json_add(root, "A2_star", I.A2);
        cli_json_add(root, "mu", r.mu);
        cli_json_add(root, "mu_D", r.mu * (damping_exact ? I.D_mass : I.D));
        cli_json_add(root, "nu1_A1_plus_nu2_A2", fabs(F->a1) * I.A1 + fabs(F->a2) * I.A2);
        cli_json_add(root, "oscillatory_max", c.oscillatory_max);
        cJSON_AddBoolToObject(root, "eq93_holds", c.eq93);
        cJSON_AddBoolToObject(root, "sign_change", c.sign_change);
        cJSON *eps = cJSON_AddObjectToObject(root, "epsilon");
        cli_json_add(eps, "forcing", (fabs(F->a1) + fabs(F->a2)) / F->g);
        cli_json_add(eps, "damping", r.mu / r.orbit.rate);
        cJSON *th = cJSON_AddObjectToObject(root, "threshold_A1");
        cli_json_add(th, "eq93", t93);
        cli_json_add(th, "exact", tx);
        if (!isnan(spacing)) tangle_json(root, &tangle, spacing, bracket);
        cJSON *b = cJSON_AddObjectToObject(root, "body");
        cJSON_AddItemToObject(b, "top", cli_json_vector(info.top, 3));
        cli_json_add(b, "r_max", info.r_max);
        cJSON_AddItemToObject(b, "rocking_direction", cli_json_vector(info.rocking, 3));
        cJSON_AddItemToObject(b, "axis", cli_json_vector(info.axis, 3));
        cJSON_AddItemToObject(b, "height_curvatures", cli_json_vector(info.curvatures, 2));
        cli_json_add(b, "contact_ties", (double)info.kinks);
        const size_t shown = info.kinks < 16 ? info.kinks : 16;
        cJSON_AddItemToObject(b, "tie_q", cli_json_vector(info.kink_q, (int)shown));
        cJSON_AddItemToObject(b, "tie_dH_jump", cli_json_vector(info.kink_jump, (int)shown));
    }
    gb_melnikov_tables_free(r.tables);
    gb_melnikov_body_free(body);
    if (status) {
        cJSON_Delete(root);
        gb_melnikov_tangle_free(&tangle);
        if (status == GB_ENUMERIC) /* the integrals at the scene's frequency, or at one of the curve's */
            return cli_failure("melnikov", gb_error_set(status, "%s: [forcing] omega = %.17g%s: the reduced model's integrals: %s",
                                                        case_path, F->omega, curve ? " (and the curve around it)" : "",
                                                        gb_error_message()));
        return cli_failure("melnikov", status);
    }
    if (json) cli_print_json(root);
    else {
        printf("%s: Gomboc %s, beta = %g; the reduced model rocks over the top (r_max = %.6g)\n", case_path,
               scene.body.morphology->name, scene.body.beta, info.r_max);
        printf("  %zu contact ties over one turn (two-point contacts, where U' jumps)\n", info.kinks);
        printf("  saddle q_u = %.3g, U'' = %.6g, M(q_u) = %.6g, rate %.6g 1/s\n", r.orbit.q_u, r.orbit.curvature, top.M, r.orbit.rate);
        printf("  D = %.6g, A1* = %.6g, A2* = %.6g at omega = %g (weight %s, mass %s)\n", I.D, I.A1, I.A2, F->omega,
               paper_weight ? "paper" : "exact", variable_mass ? "variable" : "top");
        printf("  mu D = %.6g; nu1 A1* + nu2 A2* = %.6g (eq 93 %s); largest oscillatory part %.6g (sign change: %s)\n",
               r.mu * (damping_exact ? I.D_mass : I.D), fabs(F->a1) * I.A1 + fabs(F->a2) * I.A2, c.eq93 ? "holds" : "does not hold", c.oscillatory_max,
               c.sign_change ? "yes" : "no");
        printf("  threshold A1: %.6g by eq 93, %.6g exact (m/s2, A2/A1 and psi of the scene)\n", t93, tx);
        if (!isnan(spacing))
            printf("  the period map's manifolds at the scene's forcing (spacing %g): %zu homoclinic orbits a fundamental "
                   "domain crosses%s%.1f deg (multipliers %.6g, %.6g; %zu points)\n", spacing, tangle.in_window,
                   tangle.in_window ? ", the smallest angle " : "", tangle.in_window ? tangle.smallest_angle * 180 / M_PI : 0.0,
                   tangle.multipliers[0], tangle.multipliers[1], tangle.points_unstable + tangle.points_stable);
        if (!isnan(spacing) && tangle.widest_gap > spacing)
            printf("  note: neighbouring points stayed %.3g apart where the parameter could not be split: crossings there "
                   "may be missed\n", tangle.widest_gap);
        if (halvings > 0)
            printf("  the manifolds start to cross between %s = %.6g and %.6g m/s2 (A2/A1 and psi of the scene; first order: "
                   "%.6g)\n", F->a1 != 0.0 ? "A1" : "A2", bracket[0], bracket[1], tx);
    }
    gb_melnikov_tangle_free(&tangle);
    cJSON_Delete(root);
    return 0;
}
