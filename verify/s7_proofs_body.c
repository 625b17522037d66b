/* Proved on Arb's balls: the Gömböcs' reduced models (gb_proof_body, `gomboc prove`'s last two statements).
 *
 * Oracles, none sharing code with what they check:
 * - M and the volume by Arb's quadrature over the sphere against gb_massprops (GSL's nested adaptive quadrature in
 *   doubles, its own error estimate) and gb_melnikov_body's M at the top;
 * - the enclosed reduced model against today's non-rigorous one (gb_melnikov_body: the contact continued by Newton and
 *   certified at table nodes, cubic Hermite tables, GSL quadrature in q): r_max, H''(0) (central differences of the
 *   support function, step 1e-4), the saddle's rate, D, C1, S1, C2, S2 at Table 1's omega, each inside its enclosure
 *   within the float's own error bar; with M moved by 1 % the enclosure of D must exclude the float (teeth);
 * - `gomboc prove --json`'s Gömböc statements computed (enclosures finite, today's estimates inside, the forcing the
 *   case files' values); their verdicts are the report's, not an assertion;
 * - bad definitions refused naming the field and its range. */
#include "gb_case.h"
#include "gb_check.h"
#include "gb_error.h"
#include "gb_massprops.h"
#include "gb_melnikov_body.h"
#include "gb_proof_body.h"
#include "verify_sections.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const char *const bodies[2] = {"I", "II"};

/* Inside the interval within the float's bar. */
static int inside_bar(double x, gb_proof_interval i, double bar) { return x >= i.lo - bar && x <= i.hi + bar; }

static void test_inertia(void)
{
    int inside = 0, teeth = 0, status = GB_OK;
    double widest = 0.0, seconds = 0.0;
    for (int b = 0; b < 2 && !status; b++) {
        gb_surface s;
        gb_melnikov_body *model = NULL;
        status = gb_surface_init(&s, bodies[b], 0.12);
        if (!status) status = gb_melnikov_body_create(&s, 1.0, 9.81, GB_MELNIKOV_BODY_NODES, &model);
        gb_melnikov_body_info info;
        double H, dH, M;
        if (!status) gb_melnikov_body_get_info(model, &info), status = gb_melnikov_body_direct(model, 0.0, &H, &dH, &M);
        gb_massprops_def md = gb_massprops_default_def();
        md.mass = 1.0;
        gb_massprops mp;
        if (!status) status = gb_massprops_compute(&s, &md, &mp);
        gb_proof_interval Mi, Vi;
        const clock_t c0 = clock();
        if (!status) status = gb_proof_body_inertia(&s, 1.0, info.rocking, GB_PROOF_PRECISION_DEFAULT, &Mi, &Vi);
        seconds += (double)(clock() - c0) / CLOCKS_PER_SEC;
        gb_melnikov_body_free(model);
        if (status) break;
        /* the floats' bars: GSL's stated errors (volume_err) and 1e-12 relative for M (its inertia's quadrature) */
        inside += inside_bar(mp.volume, Vi, mp.volume_err + 1e-14) + inside_bar(M, Mi, 1e-12 * M);
        teeth += !inside_bar(M * (1.0 + 1e-9), Mi, 0.0);
        widest = fmax(widest, fmax((Mi.hi - Mi.lo) / M, (Vi.hi - Vi.lo) / mp.volume));
    }
    gb_check c = {"7", "79-80", "M = a^T I_c a + m r_max^2 and the volume of Gomboc I and II (beta = 0.12, m = 1) on Arb's balls",
                  "gb_massprops (GSL nested adaptive quadrature) and gb_melnikov_body's M at the top",
                  "the floats within their stated errors (volume_err; 1e-12 relative for M); enclosures at most 1e-13 wide, "
                  "relative; M moved by 1e-9 lies outside"};
    gb_check_true(&c, !status && inside == 4 && teeth == 2 && widest <= 1e-13, "%d of 4 inside, %d of 2 moved outside, widest "
                  "%.3g relative, %.2f s CPU%s%s", inside, teeth, widest, seconds, status ? ": " : "", status ? gb_error_message() : "");
}

/* H′'s enclosures on a body's cells against the float model's H′, and H″'s against its central differences (step 1e-5)
 * at 199 q of [0, 2π] and at q = 0 against the top's closed form; the naive −H (x*·v″ alone) as the teeth. */
typedef struct second_tally {
    int sampled, inside, naive_out, saddle;
    int first_sampled, first_inside; /* H′ against its cells' enclosures */
    char first_miss[160];
    size_t curved, smooth;
    double widest;
    char first[160];
} second_tally;

static void tally_second(gb_melnikov_body *body, const gb_proof_body_model *m, second_tally *t)
{
    gb_proof_body_cell cell;
    t->curved += m->curved_cells, t->smooth += m->smooth_cells;
    t->widest = fmax(t->widest, m->second_width_max);
    t->saddle += !gb_proof_body_cell_at(m, 0.0, &cell) && cell.curved && m->curvature.lo >= cell.d2H.lo &&
                 m->curvature.hi <= cell.d2H.hi;
    /* H′: at 200 q over the period, and at both ends of the cells holding 100 q within 0.2 rad of each side of the
     * saddle, where the cells are narrow, H″ < −H/2, and an enclosure taken with v′ at a cell's middle misses H′ */
    for (int k = 0; k < 400; k++) {
        const int near = k >= 200;
        const double u = near ? 0.2 * ((k - 200) % 100 + 1) / 100.0 : 0.0;
        const double q = !near ? 2.0 * M_PI * k / 200.0 : k < 300 ? u : 2.0 * M_PI - u;
        if (gb_proof_body_cell_at(m, q, &cell)) continue;
        const gb_proof_body_cell whole = cell;
        for (int end = 0; end < (near ? 2 : 1); end++) {
            const double at = !near ? q : end ? whole.q_hi : whole.q_lo;
            double H, dH, M;
            if (gb_melnikov_body_direct(body, at, &H, &dH, &M)) continue;
            const int in = dH >= whole.dH.lo - 1e-12 && dH <= whole.dH.hi + 1e-12;
            t->first_sampled++, t->first_inside += in;
            if (!in && !t->first_miss[0])
                snprintf(t->first_miss, sizeof t->first_miss, "; H' at q = %.9g: %.12g outside [%.12g, %.12g]", at, dH,
                         whole.dH.lo, whole.dH.hi);
        }
    }
    for (int k = 1; k < 200; k++) {
        const double q = 2.0 * M_PI * k / 200.0, h = 1e-5;
        double H, dH, Hp, dHp, Hm, dHm, M;
        if (gb_proof_body_cell_at(m, q, &cell) || !cell.curved) continue; /* a tie's cell: no H'' */
        const gb_proof_interval I = cell.d2H;
        if (gb_melnikov_body_direct(body, q + h, &Hp, &dHp, &M) || gb_melnikov_body_direct(body, q - h, &Hm, &dHm, &M) ||
            gb_melnikov_body_direct(body, q, &H, &dH, &M))
            continue;
        const double fd = (dHp - dHm) / (2.0 * h);
        const int in = fd >= I.lo - 1e-6 && fd <= I.hi + 1e-6;
        t->sampled++, t->inside += in, t->naive_out += -H < I.lo || -H > I.hi;
        if (!in && !t->first[0]) snprintf(t->first, sizeof t->first, "; at q = %.6g: %.9g outside [%.9g, %.9g]", q, fd, I.lo, I.hi);
    }
}

static void test_enclosures(void)
{
    int inside = 0, total = 0, teeth = 0, status = GB_OK, books = 0, open = 0;
    int ties_found = 0, ties_total = 0, cells_matched = 0, cells_total = 0;
    second_tally second = {0};
    double seconds = 0.0, widest_C = 0.0;
    char first[200] = "";
    for (int b = 0; b < 2 && !status; b++) {
        gb_surface s;
        gb_melnikov_body *body = NULL;
        status = gb_surface_init(&s, bodies[b], 0.12);
        if (!status) status = gb_melnikov_body_create(&s, 1.0, 9.81, GB_MELNIKOV_BODY_NODES, &body);
        if (status) break;
        gb_melnikov_body_info info;
        gb_melnikov_body_get_info(body, &info);
        const gb_melnikov_model model = gb_melnikov_body_model(body, GB_MELNIKOV_MASS_AT_TOP);
        gb_melnikov_orbit orbit;
        gb_melnikov_integrals I;
        double H, dH, M;
        status = gb_melnikov_orbit_find(&model, &orbit);
        if (!status) status = gb_melnikov_integrals_compute(&model, &orbit, 18.0, GB_MELNIKOV_EXACT, &I);
        if (!status) status = gb_melnikov_body_direct(body, 0.0, &H, &dH, &M);
        gb_proof_interval Mi = {0, 0};
        if (!status) status = gb_proof_body_inertia(&s, 1.0, info.rocking, GB_PROOF_PRECISION_DEFAULT, &Mi, NULL);
        gb_proof_body_def def = {.surface = &s, .mass = 1.0, .g = 9.81, .inertia = Mi, .origin = orbit.q0, .cut = 2e-3,
                                 .resolution = 1e-3, .precision = GB_PROOF_PRECISION_DEFAULT};
        memcpy(def.rocking, info.rocking, sizeof def.rocking);
        gb_proof_body_model m = {0}, moved = {0};
        gb_proof_body_integrals J;
        if (!status) status = gb_proof_body_enclose(&def, &m);
        if (!status) status = gb_proof_body_integrals_compute(&def, &m, 18.0, &J);
        gb_proof_body_def heavier = def;
        heavier.inertia = (gb_proof_interval){Mi.lo * 1.01, Mi.hi * 1.01};
        heavier.resolution = 1e-2; /* D's enclosure is 3e-5 wide, relative, even so; the move is 5e-3 */
        if (!status) status = gb_proof_body_enclose(&heavier, &moved);
        if (!status) tally_second(body, &m, &second);
        gb_melnikov_body_free(body);
        if (status) break;
        seconds += m.seconds + J.seconds;
        /* the floats' bars: 1e-9 relative + 1e-12 (the tables' quadrature targets 1e-10, a margin of 10); r_max to
         * 1e-13; H''(0) by central differences at step 1e-4 to 1e-6; the rate from U'' by Brent and differences, 1e-6 */
        const struct {
            double x;
            gb_proof_interval i;
            double bar;
            const char *name;
        } pairs[8] = {{info.r_max, m.r_max, 1e-13, "r_max"},
                      {info.curvatures[0], m.curvature, 1e-6, "H''(0)"},
                      {orbit.rate, m.rate, 1e-6 * orbit.rate, "rate"},
                      {I.D, m.D, 1e-9 * fabs(I.D) + 1e-12, "D"},
                      {I.C1, J.C1, 1e-9 * fabs(I.C1) + 1e-12, "C1"},
                      {I.S1, J.S1, 1e-9 * fabs(I.S1) + 1e-12, "S1"},
                      {I.C2, J.C2, 1e-9 * fabs(I.C2) + 1e-12, "C2"},
                      {I.S2, J.S2, 1e-9 * fabs(I.S2) + 1e-12, "S2"}};
        for (int k = 0; k < 8; k++) {
            const int in = inside_bar(pairs[k].x, pairs[k].i, pairs[k].bar);
            inside += in, total++;
            if (!in && !first[0])
                snprintf(first, sizeof first, "; %s %s: %.12g outside [%.12g, %.12g]", bodies[b], pairs[k].name, pairs[k].x,
                         pairs[k].i.lo, pairs[k].i.hi);
        }
        /* the piecewise structure against the numeric model's ties (bisection on the branches' height gap) */
        books += m.smooth_cells + m.tie_cells + m.open_cells == m.cells + 2;
        open += (int)m.open_cells;
        for (size_t k = 0; k < info.kinks && k < 16; k++) {
            int in = 0;
            for (size_t j = 0; j < m.tie_cells && j < 8; j++) in |= info.kink_q[k] >= m.tie_q[j][0] - 1e-9 && info.kink_q[k] <= m.tie_q[j][1] + 1e-9;
            ties_found += in, ties_total++;
        }
        for (size_t j = 0; j < m.tie_cells && j < 8; j++) {
            int in = 0;
            for (size_t k = 0; k < info.kinks && k < 16; k++) in |= info.kink_q[k] >= m.tie_q[j][0] - 1e-9 && info.kink_q[k] <= m.tie_q[j][1] + 1e-9;
            cells_matched += in, cells_total++;
        }
        widest_C = fmax(widest_C, fmax(fmax(J.C1.hi - J.C1.lo, J.S1.hi - J.S1.lo), fmax(J.C2.hi - J.C2.lo, J.S2.hi - J.S2.lo)));
        teeth += !inside_bar(I.D, moved.D, 1e-9 * fabs(I.D) + 1e-12);
        gb_proof_body_free(&m);
        gb_proof_body_free(&moved);
    }
    gb_check c = {"7", "78-90", "the reduced models of Gomboc I and II enclosed from the body (top reading, resolution 1e-3, cut 2e-3): "
                  "r_max, H''(0), the saddle's rate, D and C1, S1, C2, S2 at omega = 18",
                  "gb_melnikov_body (Newton-continued contact, Hermite tables, GSL quadrature in q)",
                  "each float inside within its own bar: 1e-9 relative + 1e-12 for the integrals (their targets 1e-10), 1e-13 for "
                  "r_max, 1e-6 for H''(0) and the rate (central differences at 1e-4); with M 1 % larger D's enclosure excludes the "
                  "float (2 of 2, at resolution 1e-2); the cells classified (C2, one tie at most, open) account for every "
                  "cell, every tie the numeric model locates lies in a cell proved to hold one, and every such cell holds one "
                  "of them (to 1e-9)"};
    gb_check_true(&c, !status && total == 16 && inside == total && teeth == 2 && books == 2 && ties_found == ties_total &&
                      cells_matched == cells_total && ties_total > 0,
                  "%d of %d inside, %d of 2 excluded with M moved; the oscillatory enclosures at most %.3g wide; ties: %d of %d "
                  "numeric ones in tie cells, %d of %d tie cells holding one, %d cells open; %.2f s CPU%s%s%s", inside, total, teeth,
                  widest_C, ties_found, ties_total, cells_matched, cells_total, open, seconds, first, status ? ": " : "",
                  status ? gb_error_message() : "");
    gb_check c2 = {"7", "78", "H'' of Gomboc I and II on the cells where their contact is unique (resolution 1e-3): "
                   "H'' = -H - g^T K^-1 g over each cell's kept boxes, at 199 q each (those in a tie's cell left out)",
                   "central differences of the float model's H' (step 1e-5); at q = 0 the closed form H''(0) of the top",
                   "each difference inside within 1e-6: its truncation (h^2/6 times H's fourth derivative) is about 1e-10 and "
                   "the floats' 1e-14 over h = 1e-5 gives 1e-9, a margin of 1000; H''(0) inside exactly; "
                   "the naive H'' = x*.v'' = -H (the contact's motion left out) outside at 90 % of the q or more, so the "
                   "enclosures decide; every C2 cell enclosed"};
    gb_check c1 = {"7", "78", "H' of Gomboc I and II on their cells (resolution 1e-3): the hull of x.v' over each cell's kept "
                   "boxes, v' over the whole cell; at 200 q over the period and at both ends of the cells holding 100 q within 0.2 rad "
                   "of each side of the saddle (narrow cells, where H'' < -H/2)",
                   "the float model's H' (Newton-continued contact, gb_melnikov_body_direct)",
                   "inside within 1e-12: the float's contact is Newton's to a step of 1e-14 rad, so its H' is good to about "
                   "1e-14 (|x_a| < 1.1), and 1e-12 leaves a margin of 100; every q, the saddle's narrow cells included"};
    gb_check_true(&c1, !status && second.first_sampled == 2 * 600 && second.first_inside == second.first_sampled,
                  "%d of %d inside%s", second.first_inside, second.first_sampled, second.first_miss);
    gb_check_true(&c2, !status && second.sampled >= 2 * 195 && second.inside == second.sampled && second.saddle == 2 &&
                       10 * second.naive_out >= 9 * second.sampled && second.curved == second.smooth,
                  "%d of %d differences inside; H''(0) inside %d of 2; naive -H outside %d of %d; %zu of %zu C2 cells "
                  "enclosed, the widest %.3g%s", second.inside, second.sampled, second.saddle, second.naive_out, second.sampled,
                  second.curved, second.smooth, second.widest, second.first);
}

static void test_bad_definitions(void)
{
    gb_surface s, sphere;
    gb_surface_init(&s, "II", 0.12);
    gb_surface_init(&sphere, "II", 0.0);
    const gb_proof_body_def good = {.surface = &s, .mass = 1.0, .g = 9.81, .inertia = {1.6, 1.7}, .rocking = {0.0, 0.5, 0.8},
                                    .origin = 2.0, .cut = 2e-3, .resolution = 1e-3, .precision = 128};
    struct {
        gb_proof_body_def def;
        const char *must;
    } bad[7];
    for (int k = 0; k < 7; k++) bad[k].def = good;
    bad[0].def.cut = 0.5, bad[0].must = "cut";
    bad[1].def.resolution = 1.0, bad[1].must = "resolution";
    bad[2].def.inertia = (gb_proof_interval){0.0, 1.0}, bad[2].must = "inertia";
    bad[3].def.origin = 1e-3, bad[3].must = "origin";
    bad[4].def.precision = 10, bad[4].must = "precision";
    bad[5].def.surface = &sphere, bad[5].must = "beta";
    bad[6].def.rocking[1] = bad[6].def.rocking[2] = 0.0, bad[6].def.rocking[0] = 1.0, bad[6].must = "rocking";
    int refused = 0;
    char first[300] = "";
    for (int k = 0; k < 7; k++) {
        gb_proof_body_model m;
        const int st = gb_proof_body_enclose(&bad[k].def, &m);
        const char *msg = st ? gb_error_message() : "";
        const int ok = st == GB_EDOM && strstr(msg, bad[k].must) && strstr(msg, "allowed");
        refused += ok;
        if (!ok && !first[0]) snprintf(first, sizeof first, "; case %d gave %d: %.200s", k, st, msg);
        if (!st) gb_proof_body_free(&m);
    }
    gb_check c = {"-", "-", "gb_proof_body_enclose: definitions out of range (cut, resolution, inertia, origin, precision, a "
                  "sphere, a rocking direction along the top)", "GB_EDOM naming the field and its allowed range", "exact"};
    gb_check_true(&c, refused == 7, "%d of 7 refused so%s", refused, first);
}

static const char *binary(void) { return getenv("GOMBOC_BIN") ? getenv("GOMBOC_BIN") : "build/gomboc"; }

/* The JSON `gomboc prove --json` wrote for the report (verify/s7_proofs.c's check, run just before), or the command's
 * own when it is absent (this suite run alone); *code its exit status (0 when read from the file: written only then). */
static void prove_json(char *out, size_t size, int *code)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/proofs.json", gb_check_data_dir ? gb_check_data_dir : ".");
    FILE *f = fopen(path, "r");
    if (f) {
        const size_t n = fread(out, 1, size - 1, f);
        out[n] = '\0';
        fclose(f);
        *code = 0;
        if (n > 0) return;
    }
    *code = gb_check_command(binary(), "prove --json", out, size);
    char *mark = strstr(out, "@@exit=");
    if (mark) *mark = '\0';
}

/* `gomboc prove --json`'s Gömböc statements: computed, with today's estimates inside and Table 1's rolling scenes' data. */
static void test_command_bodies(void)
{
    static char out[1 << 18];
    int code;
    prove_json(out, sizeof out, &code);
    cJSON *root = code == 0 || code == 1 ? cJSON_Parse(out) : NULL;
    int computed = 0, data_ok = 0, status = GB_OK;
    char verdicts[2][64] = {"", ""};
    const cJSON *item;
    cJSON_ArrayForEach(item, cJSON_GetObjectItem(root, "statements"))
    {
        const cJSON *data = cJSON_GetObjectItem(item, "data");
        if (!data) continue;
        const char *morph = cJSON_GetStringValue(cJSON_GetObjectItem(data, "morphology"));
        const int b = morph && !strcmp(morph, "II");
        const cJSON *enc = cJSON_GetObjectItem(item, "enclosures"), *est = cJSON_GetObjectItem(item, "estimates");
        int finite = enc != NULL;
        const cJSON *e;
        cJSON_ArrayForEach(e, enc) finite &= isfinite(cJSON_GetNumberValue(cJSON_GetArrayItem(e, 0))) &&
                                            isfinite(cJSON_GetNumberValue(cJSON_GetArrayItem(e, 1)));
        computed += finite && cJSON_IsTrue(cJSON_GetObjectItem(est, "inside")) && cJSON_GetObjectItem(item, "verdict");
        snprintf(verdicts[b], sizeof verdicts[b], "%s", cJSON_GetStringValue(cJSON_GetObjectItem(item, "verdict")) ?: "?");
        char path[64];
        snprintf(path, sizeof path, "cases/table1-gomboc-%s-rolling.ini", b ? "II" : "I");
        gb_case scene;
        status = gb_case_load(path, &scene);
        if (status) break;
        const gb_forcing *F = &scene.dynamics.forcing;
        const cJSON *psi = cJSON_GetObjectItem(data, "psi");
        data_ok += scene.body.beta == cJSON_GetNumberValue(cJSON_GetObjectItem(data, "beta")) &&
                   scene.dynamics.mass == cJSON_GetNumberValue(cJSON_GetObjectItem(data, "mass")) &&
                   F->g == cJSON_GetNumberValue(cJSON_GetObjectItem(data, "g")) &&
                   scene.dynamics.damping == cJSON_GetNumberValue(cJSON_GetObjectItem(data, "damping")) &&
                   F->a1 == cJSON_GetNumberValue(cJSON_GetObjectItem(data, "A1")) &&
                   F->a2 == cJSON_GetNumberValue(cJSON_GetObjectItem(data, "A2")) &&
                   F->omega == cJSON_GetNumberValue(cJSON_GetObjectItem(data, "omega")) &&
                   fabs(F->psi - cJSON_GetNumberValue(cJSON_GetArrayItem(psi, 0))) <= 1e-15;
    }
    cJSON_Delete(root);
    gb_check c = {"7", "91", "gomboc prove --json: the Gomboecs' statements (Table 1's rolling forcing)",
                  "enclosures finite with today's estimates inside; the data those of cases/table1-gomboc-{I,II}-rolling.ini",
                  "exact; the verdicts are the report's (section Proved), not asserted here"};
    gb_check_true(&c, !status && (code == 0 || code == 1) && computed == 2 && data_ok == 2, "exit %d, %d of 2 computed, %d of 2 "
                  "with the case files' data; verdicts: I %s, II %s%s%s", code, computed, data_ok, verdicts[0], verdicts[1],
                  status ? ": " : "", status ? gb_error_message() : "");
    int e = gb_check_command(binary(), "prove --resolution 0.5", out, sizeof out);
    gb_check cb = {"-", "-", "gomboc prove --resolution 0.5", "exit 2 naming the option and its allowed range", "exact"};
    gb_check_true(&cb, e == 2 && strstr(out, "--resolution") && strstr(out, "allowed"), "exit %d: %.200s", e, out);
}

int verify_register_s7_proofs_body(void)
{
    static const verify_test tests[] = {
        {"proofs: the Gomboecs' M and volume on Arb's balls", test_inertia,
         "the moment of inertia of the reduced model is enclosed rigorously and holds the quadrature's value"},
        {"proofs: the Gomboecs' reduced models enclosed from the body hold today's estimates", test_enclosures,
         "the rigorous enclosures of the reduced model's integrals hold the non-rigorous Melnikov integrals"},
        {"proofs: bad definitions of a Gomboc's enclosure", test_bad_definitions, NULL},
        {"proofs: gomboc prove's Gomboec statements", test_command_bodies,
         "gomboc prove decides the Melnikov function of each Gomboc's reduced model from enclosures"},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Proved on Arb's balls: the Gomboecs' reduced models (section 7)", tests);
}
