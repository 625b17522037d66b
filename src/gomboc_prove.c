/* gomboc prove — the statements gb_proof proves on Arb's balls, each with its hypotheses, the theorem it rests on,
 * the enclosures and its CPU time (docs/proofs.md). What is proved today: the oracles of the separatrix splitting
 * (the pendulum's and Duffing's Melnikov integrals enclosed, their closed forms met, and the zeros of their Melnikov
 * functions decided for stated forcings), Rössler's horseshoe (Zgliczyński 1997) by covering relations on the
 * rigorous integrator, Hénon's full horseshoe at a = 6 and a horseshoe of the classical Hénon map's 7th iterate on five
 * parallelograms, the classical map's renewal bound from strips of a band that return across it, and the
 * Gömböcs' reduced models (§7) at Table 1's rolling forcing:
 * their Melnikov functions enclosed from the body and their zeros decided (gomboc_prove_body.c); with --horseshoe,
 * instead, Gömböc II's period map at that forcing has a horseshoe, or Gömböc I's is attempted with --morphology I (not
 * proved: docs/proofs.md) (gomboc_prove_chain.c). */
#include "gomboc_cli.h"
#include "gomboc_prove_common.h"

#include "gb_error.h"
#include "gb_proof.h"
#include "gb_proof_body.h"
#include "gb_proof_cover.h"
#include "gb_proof_returns.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const char *usage_prove =
    "usage: gomboc prove [--precision BITS] [--depth N] [--resolution R] [--threads N] [--large-trellis] [--json]\n"
    "       gomboc prove --horseshoe [--morphology I|II] [--precision BITS] [--threads N] [--json]\n"
    "\n"
    "Proves, on Arb's ball arithmetic, the statements docs/proofs.md lists, and prints each with its\n"
    "hypotheses, the theorem it rests on, the enclosures (intervals rounded outwards) and its CPU time:\n"
    "  - the Melnikov integrals of the pendulum and of Duffing's oscillator at omega = 0.5, 1, 3, enclosed\n"
    "    by rigorous quadrature along their homoclinic orbits and met by their closed forms;\n"
    "  - the zeros of their Melnikov functions M(t0) for stated forcings: simple zeros proved, or M != 0;\n"
    "  - Roessler's horseshoe (Zgliczynski 1997; the sets of CAPD's example): covering relations of the\n"
    "    second return map to x = 0 on a rigorous Taylor-Lohner integrator, h_top(P^2) >= ln 2;\n"
    "  - Roessler's period-1 orbit: Krawczyk's operator on the return map and its derivative (the\n"
    "    integrator's C1 step), the orbit unique in a box and its period enclosed;\n"
    "  - Henon's map at a = 6, b = 0.3: a full horseshoe by covering relations, h_top >= ln 2;\n"
    "  - Henon's map at the classical a = 1.4, b = 0.3: its 7th iterate crosses five parallelograms\n"
    "    (a frame near the fixed point's eigenvectors), a full horseshoe, h_top >= ln 5 / 7;\n"
    "  - the same map: 21 strips of a band along the fixed point's unstable direction return across it,\n"
    "    each in its own number of iterates, h_top >= ln x with sum x^-m = 1 (0.39926); and with 9 more\n"
    "    that return across part of it, the graph's bound h_top >= ln x0, M(x0) v >= v (0.41184);\n"
    "  - both Henon maps by their discrete Conley index: an index pair of boxes, H_1(P1, P0; Z2) and the\n"
    "    index map's blocks on its regions, the entropy of the sofic shift they force: ln 2 at a = 6,\n"
    "    0.43255 for the classical map (a grid of 2^12 boxes a side grown from its periodic points);\n"
    "  - the classical Henon map's fixed point: its unstable and stable manifolds parametrised with\n"
    "    proved tails, and their 19 crossings over two arcs, each transverse, and no other;\n"
    "  - the same manifolds' trellis: the rectangles their arcs bound and the strips the map carries\n"
    "    across them, h_top >= 0.4621 from the graph's closed walks (Newhouse, Berz, Grote & Makino\n"
    "    proved 0.46469 from pieces of these manifolds);\n"
    "  - the Gomboecs' reduced models (section 7) at Table 1's rolling forcing: their Melnikov integrals\n"
    "    enclosed from the body, M(t0) != 0 for Gomboc I, simple zeros for Gomboc II.\n"
    "\n"
    "  --precision BITS  Arb's working precision, 64 to 4096 (default 128)\n"
    "  --depth N         the most halvings of a piece of the period of t0, 1 to 40 (default 24)\n"
    "  --resolution R    the Gomboecs' cells of q: width over distance to the saddle, 1e-5 to 0.1\n"
    "                    (default: 1e-3, then 3e-4 with at most 12 halvings, then 1e-4 at --depth,\n"
    "                    until the verdict is decided)\n"
    "  --threads N       1: every statement in turn; 2: the trellis's statement (the longest) on a thread\n"
    "                    of its own beside the others, 3 or more: Gomboc I's too (1 to 256; default 2\n"
    "                    where the machine has two processors or more, else 1); the statements and their\n"
    "                    order are the same either way;\n"
    "                    with --horseshoe, its covering relations on N threads\n"
    "  --large-trellis   the trellis's statement on the large trellis (S = 25600, 341 stable arcs,\n"
    "                    h_top >= 0.46471, above the published 0.46469; 37 min of CPU, 25 on two\n"
    "                    threads; make prove)\n"
    "  --horseshoe       instead, Gomboc II's horseshoe at Table 1's rolling forcing: covering relations of\n"
    "                    its period map along a homoclinic orbit, h_top >= ln rho (minutes; make prove;\n"
    "                    --precision and --threads apply)\n"
    "  --morphology M    with --horseshoe, Gomboc M's (I or II; default II). Gomboc I's: 30 of its 36 links\n"
    "                    are proved, five through its stretches of large Taylor coefficients are not and one\n"
    "                    runs for more than 25 minutes (docs/proofs.md, What is open): exit 1\n"
    "  --json            the statements as JSON on standard output\n"
    "\n"
    "Exit 0 when every statement attempted is proved, 1 when one is not (it says which and why), 2 for bad\n"
    "input. Nothing estimated is called proved.\n";

/* One forcing of an oracle whose Melnikov function's zeros are decided. */
typedef struct forcing {
    gb_proof_system system;
    double mu, nu1, nu2, omega;
    long psi_num, psi_den; /* ψ = π num/den */
    gb_proof_verdict expected;
    const char *reading;
} forcing;

static const forcing forcings[] = {
    {GB_PROOF_PENDULUM, 0.1, 1.0, 0.5, 1.0, 1, 3, GB_PROOF_SIMPLE_ZEROS,
     "transversal homoclinic points of the period map for all small enough eps (Melnikov's theorem)"},
    {GB_PROOF_PENDULUM, 0.5, 1.0, 0.0, 1.0, 0, 1, GB_PROOF_NO_ZERO,
     "no transversal homoclinic point near the unperturbed separatrix for all small enough eps (first order)"},
    {GB_PROOF_DUFFING, 0.25, 0.3, 0.0, 1.0, 0, 1, GB_PROOF_SIMPLE_ZEROS,
     "transversal homoclinic points of the period map for all small enough eps (Melnikov's theorem)"},
};
enum { FORCINGS = sizeof forcings / sizeof forcings[0] };

static const double omegas[] = {0.5, 1.0, 3.0};
enum { OMEGAS = sizeof omegas / sizeof omegas[0] };

static const char *const integral_names[5] = {"D", "C1", "S1", "C2", "S2"};

/* The integrals' statement: the quadrature's five enclosures meet the closed forms'. */
static cJSON *integrals_statement(const gb_proof_integrals *I, int *proved)
{
    cJSON *s = cJSON_CreateObject();
    char name[128];
    snprintf(name, sizeof name, "%s: Melnikov integrals at omega = %g", gb_proof_system_name(I->system), I->omega);
    cJSON_AddStringToObject(s, "statement", name);
    cJSON_AddStringToObject(s, "claim", I->system == GB_PROOF_PENDULUM
                                            ? "int p_h^2 dt = 8, int p_h cos(k w t) dt = 2 pi sech(k pi w / 2), int p_h sin(k w t) dt = 0 "
                                              "(k = 1, 2; p_h = 2 sech t)"
                                            : "int p_h^2 dt = 4/3, int p_h cos(k w t) dt = 0, int p_h sin(k w t) dt = -sqrt 2 pi k w "
                                              "sech(k pi w / 2) (k = 1, 2; p_h = -sqrt 2 sech t tanh t)");
    cJSON_AddStringToObject(s, "method", "Arb's rigorous Gauss-Legendre quadrature (acb_calc_integrate) on [-T, T]; the tails "
                                         "bounded by |p_h| <= c e^-|t|; the closed forms enclosed apart");
    cli_json_add(s, "T", I->horizon);
    cli_json_add(s, "precision_bits", (double)I->precision);
    const gb_proof_interval *q[5] = {&I->D, &I->C1, &I->S1, &I->C2, &I->S2};
    cJSON *enc = cJSON_AddObjectToObject(s, "enclosures");
    for (int k = 0; k < 5; k++) {
        cJSON *e = cJSON_AddObjectToObject(enc, integral_names[k]);
        cJSON_AddItemToObject(e, "quadrature", prove_json_interval(*q[k]));
        cJSON_AddItemToObject(e, "closed_form", prove_json_interval(I->closed[k]));
    }
    *proved = I->consistent;
    cJSON_AddStringToObject(s, "result", I->consistent ? "proved" : "not proved: a quadrature enclosure misses its closed form");
    cli_json_add(s, "seconds", I->seconds);
    char summary[200];
    snprintf(summary, sizeof summary, "(the five quadrature enclosures, at most %.2g wide as doubles, each meet their closed "
             "forms; %.2g s)",
             fmax(fmax(I->D.hi - I->D.lo, I->C1.hi - I->C1.lo), fmax(I->C2.hi - I->C2.lo, I->S1.hi - I->S1.lo)), I->seconds);
    cJSON_AddStringToObject(s, "summary", summary);
    return s;
}

static cJSON *zeros_statement(const forcing *f, const gb_proof_integrals *I, const gb_proof_zeros *z, gb_proof_interval psi,
                              int *proved)
{
    cJSON *s = cJSON_CreateObject();
    char text[512];
    const char *system = gb_proof_system_name(f->system);
    snprintf(text, sizeof text, "%s, mu = %g, nu1 = %g, nu2 = %g, psi = pi %ld/%ld, omega = %g: %s", system, f->mu, f->nu1, f->nu2,
             f->psi_num, f->psi_den, f->omega, f->expected == GB_PROOF_SIMPLE_ZEROS ? "M(t0) has simple zeros only" : "M(t0) != 0");
    cJSON_AddStringToObject(s, "statement", text);
    cJSON_AddStringToObject(s, "system", f->system == GB_PROOF_PENDULUM
                                             ? "q'' = -sin q + eps (-mu q' + nu1 cos(omega t) + nu2 cos(2 omega t + psi))"
                                             : "x'' = x - x^3 + eps (-mu x' + nu1 cos(omega t) + nu2 cos(2 omega t + psi))");
    cJSON_AddStringToObject(s, "function", "M(t0) = -mu D + nu1 (C1 cos w t0 - S1 sin w t0) + nu2 (C2 cos(2 w t0 + psi) - S2 sin(2 w t0 "
                                           "+ psi)) (eq 91), its integrals the enclosures above");
    cJSON_AddStringToObject(s, "method", "the period cut in 64 pieces, each halved until M is bounded away from 0 (mean value form) or "
                                         "M' is (then strict signs at its ends: one simple zero, or none)");
    cJSON_AddStringToObject(s, "theorem", "Melnikov (Guckenheimer & Holmes 1983, Thm 4.5.3): H0 analytic with a hyperbolic saddle "
                                          "joined to itself by a homoclinic orbit, the perturbation smooth and periodic in t; a "
                                          "simple zero of M gives, for 0 < eps small enough, a transversal intersection of the "
                                          "stable and unstable manifolds of the period map's saddle (Smale-Birkhoff: a horseshoe)");
    cJSON_AddStringToObject(s, "hypotheses", f->system == GB_PROOF_PENDULUM
                                                 ? "hold: analytic, saddle q = pi (eigenvalues +-1), the rotation orbit p = 2 cos(q/2)"
                                                 : "hold: analytic, saddle x = 0 (eigenvalues +-1), the loop x = sqrt 2 sech t");
    cJSON_AddStringToObject(s, "reading", f->reading);
    cJSON_AddItemToObject(s, "psi", prove_json_interval(psi));
    cJSON_AddStringToObject(s, "verdict", gb_proof_verdict_name(z->verdict));
    cli_json_add(s, "zeros", (double)z->zeros);
    cJSON *where = cJSON_AddArrayToObject(s, "zero_t0");
    for (size_t k = 0; k < z->zeros && k < GB_PROOF_ZEROS_MAX; k++)
        cJSON_AddItemToArray(where, prove_json_interval(z->where[k]));
    cli_json_add(s, "slope_min", z->slope_min);
    cli_json_add(s, "margin", z->margin);
    cli_json_add(s, "pieces", (double)z->boxes);
    cli_json_add(s, "undecided_pieces", (double)z->undecided);
    *proved = I->consistent && z->verdict == f->expected;
    cJSON_AddStringToObject(s, "result", *proved ? "proved" : !I->consistent ? "not proved: the integrals' enclosures are not consistent"
                                                               : "not proved: the prover's verdict differs");
    cli_json_add(s, "seconds", I->seconds + z->seconds);
    char summary[200];
    if (z->verdict == GB_PROOF_SIMPLE_ZEROS)
        snprintf(summary, sizeof summary, "(%zu simple zeros a period, |dM/dt0| >= %.3g on their intervals; %.2g s)", z->zeros,
                 z->slope_min, I->seconds + z->seconds);
    else if (z->verdict == GB_PROOF_NO_ZERO)
        snprintf(summary, sizeof summary, "(|M| >= %.3g over the period; %.2g s)", z->margin, I->seconds + z->seconds);
    else
        snprintf(summary, sizeof summary, "(%zu of %zu pieces undecided at the deepest halving; %.2g s)", z->undecided, z->boxes,
                 I->seconds + z->seconds);
    cJSON_AddStringToObject(s, "summary", summary);
    return s;
}

/* A horseshoe by covering relations. */
typedef struct horseshoe {
    const char *statement, *system, *sets, *theorem, *reading, *source;
    gb_proof_cover_def def;
    gb_proof_field field;
    int status; /* GB_OK, or why the definition could not be built */
} horseshoe;

static void horseshoe_rossler(horseshoe *h)
{
    memset(h, 0, sizeof *h);
    h->statement = "Roessler, a = b = 0.2, c = 5.7: the second return map to x = 0 (x' > 0) has a horseshoe, h_top(P^2) >= ln 2";
    h->system = "x' = -y - z, y' = x + a y, z' = b + z (x - c), a = 1/5, b = 1/5, c = 57/10 exactly";
    h->sets = "on the plane x = 0 (u = y, s = z): R = [-10.7, -2.3] x [0.028, 0.034] with P(R) in int R (200 pieces); "
              "M = [-8.4, -7.6] x [0.028, 0.034], N = [-5.7, -4.6] x [0.028, 0.034]";
    h->source = "Zgliczynski 1997 (Nonlinearity 10, 243-252): a horseshoe for P^2; the sets of CAPD's example "
                "RosslerChaoticDynamics";
    h->theorem = "covering relations (Zgliczynski 1997; Gidea & Zgliczynski 2004, Thm 9): for every sequence the transition "
                 "matrix admits there is an orbit of P^2 visiting the sets in that order; the sets disjoint, P^2 on the invariant "
                 "part of M u N is semiconjugate to the shift, so h_top >= ln rho(A)";
    h->reading = "chaos of the Roessler flow proved: a compact invariant set of P^2 semiconjugate to the full shift on 2 "
                 "symbols (the cone condition, which would make it a conjugacy, is not checked)";
    h->field = gb_proof_flow_rossler(1, 5, 1, 5, 57, 10);
    gb_proof_cover_def *d = &h->def;
    *d = gb_proof_cover_def_default();
    d->section = gb_proof_flow_def_default(&h->field);
    d->u = 1, d->s = 2, d->iterates = 2, d->trap = 1;
    d->region_u = (gb_proof_interval){-10.7, -2.3}, d->strip = (gb_proof_interval){0.028, 0.034};
    d->sets = 2, d->set_u[0] = (gb_proof_interval){-8.4, -7.6}, d->set_u[1] = (gb_proof_interval){-5.7, -4.6};
    d->pieces = 200, d->depth = 4;
}

static void horseshoe_henon(horseshoe *h)
{
    memset(h, 0, sizeof *h);
    h->statement = "Henon, a = 6, b = 0.3: a full horseshoe, h_top = ln 2";
    h->system = "(x, y) -> (1 - a x^2 + y, b x), a = 6, b = 3/10 exactly";
    h->sets = "u = x, s = y: N0 = [-0.7, -0.1] x [-0.22, 0.22], N1 = [0.1, 0.7] x [-0.22, 0.22] (16 pieces each)";
    h->source = "Devaney & Nitecki 1979: for a > (5 + 2 sqrt 5)(1 + |b|)^2 / 4 (4.0 at b = 0.3) the non-wandering set is a "
                "full horseshoe; Friedland & Milnor 1989: h_top <= ln 2 for every Henon map";
    h->theorem = "covering relations (Gidea & Zgliczynski 2004, Thm 9) for the lower bound; Friedland-Milnor for the upper";
    h->reading = "the covering relations' machinery on a map whose entropy is known exactly: h_top = ln 2";
    h->field = gb_proof_cover_henon(6, 1, 3, 10);
    gb_proof_cover_def *d = &h->def;
    *d = gb_proof_cover_def_default();
    d->kind = GB_PROOF_MAP_QUADRATIC, d->map = &h->field;
    d->u = 0, d->s = 1, d->iterates = 1;
    d->strip = (gb_proof_interval){-0.22, 0.22};
    d->sets = 2, d->set_u[0] = (gb_proof_interval){-0.7, -0.1}, d->set_u[1] = (gb_proof_interval){0.1, 0.7};
    d->pieces = 16;
}

/* The classical Hénon map in the frame of its fixed point's eigenvectors (rounded to small rationals): five
 * parallelograms crossed by the 7th iterate, found by a search on floats and proved here. */
static void horseshoe_henon_classical(horseshoe *h)
{
    memset(h, 0, sizeof *h);
    h->statement = "Henon, a = 1.4, b = 0.3 (classical): the 7th iterate has a full horseshoe on 5 symbols, h_top >= ln 5 / 7";
    h->system = "(x, y) -> (1 - a x^2 + y, b x), a = 7/5, b = 3/10 exactly, read in the frame (x, y) = o + F (u, s), "
                "o = (3157/5000, 947/5000) (near the fixed point), F = [[-1, -13/25], [39/250, -1]] (columns near its unstable "
                "and stable eigenvectors): the conjugate map's coefficients exact";
    h->sets = "in the frame, S = [-0.045, 0.045] and U = [-0.41079, -0.3875], [-0.38371, -0.3596], [-0.24016, -0.20567], "
              "[-0.20529, -0.17745], [-0.00009, 0.00564]: five parallelograms in the plane (8 pieces across, halved across and "
              "along where an inclusion is not proved)";
    h->source = "not a published set (ours, found by a search on floats); published lower bounds at these parameters: "
                "0.4320 (Day, Frongillo & Trevino 2008, discrete Conley index) and 0.46469 (Newhouse, Berz, Grote & Makino "
                "2008, pieces of stable and unstable manifolds); Zgliczynski 1997 proved symbolic dynamics on two symbols for "
                "an iterate of this map by covering relations";
    h->theorem = "covering relations (Gidea & Zgliczynski 2004, Thm 9) of the conjugate map g = A^-1 H A, A the frame's affine "
                 "map: h_top(H) = h_top(g) = h_top(g^7) / 7 >= ln rho(A) / 7; Friedland & Milnor 1989: h_top <= ln 2";
    h->reading = "chaos of the classical Henon map proved: a compact invariant set of H^7 semiconjugate to the full shift on 5 "
                 "symbols; the bound is below the published ones, as a lower bound may be (they use thousands of boxes or "
                 "manifold trellises)";
    h->status = gb_proof_cover_henon_classical(&h->field, &h->def);
}

static cJSON *horseshoe_statement(const horseshoe *h, const gb_proof_cover_result *r, int *proved)
{
    cJSON *s = cJSON_CreateObject();
    cJSON_AddStringToObject(s, "statement", h->statement);
    cJSON_AddStringToObject(s, "system", h->system);
    cJSON_AddStringToObject(s, "sets", h->sets);
    cJSON_AddStringToObject(s, "reproduces", h->source);
    cJSON_AddStringToObject(s, "method", h->def.kind == GB_PROOF_MAP_RETURN
                                             ? "the return map by Taylor's method of order 20 with the C0 Lohner algorithm on Arb "
                                               "(128 bits), crossings proved transversal; each piece halved up to 4 times where "
                                               "its inclusion is not proved"
                                             : "the map's iterates on Arb's balls in affine form (the C0 Lohner algorithm "
                                               "for maps: centre, exact linear part, remainder box) over pieces of each set");
    cJSON_AddStringToObject(s, "theorem", h->theorem);
    cJSON_AddStringToObject(s, "reading", h->reading);
    if (h->def.trap) {
        cli_json_add(s, "trapped", r->trapped);
        cJSON_AddItemToObject(s, "trap_image_u", prove_json_interval(r->trap_image_u));
        cJSON_AddItemToObject(s, "trap_image_s", prove_json_interval(r->trap_image_s));
    }
    cJSON *sets = cJSON_AddArrayToObject(s, "h_sets");
    int relations = 0;
    for (size_t i = 0; i < h->def.sets; i++) {
        cJSON *e = cJSON_CreateObject();
        cJSON_AddItemToObject(e, "u", prove_json_interval(h->def.set_u[i]));
        cli_json_add(e, "strip", r->strip[i]);
        cJSON_AddItemToObject(e, "image_of_low_edge_u", prove_json_interval(r->edge[i][0]));
        cJSON_AddItemToObject(e, "image_of_high_edge_u", prove_json_interval(r->edge[i][1]));
        cJSON *row = cJSON_AddArrayToObject(e, "covers");
        for (size_t j = 0; j < h->def.sets; j++) cJSON_AddItemToArray(row, cJSON_CreateNumber(r->covers[i][j])), relations += r->covers[i][j];
        cJSON_AddItemToArray(sets, e);
    }
    cli_json_add(s, "entropy_lower_bound", r->entropy);
    cli_json_add(s, "iterates", h->def.iterates);
    cli_json_add(s, "entropy_lower_bound_map", r->entropy_map);
    cli_json_add(s, "pieces", (double)r->pieces);
    *proved = relations == (int)(h->def.sets * h->def.sets); /* the full shift: rho(A) = 2 for two sets, h_top >= ln 2 */
    char result[300];
    if (*proved)
        snprintf(result, sizeof result, "proved");
    else
        snprintf(result, sizeof result, "not proved: %d of %zu covering relations proved%s%s", relations, h->def.sets * h->def.sets,
                 r->failure[0] ? "; " : "", r->failure);
    cJSON_AddStringToObject(s, "result", result);
    cli_json_add(s, "seconds", r->seconds);
    char summary[200];
    char bound[80];
    if (h->def.iterates > 1 && h->def.kind == GB_PROOF_MAP_QUADRATIC)
        snprintf(bound, sizeof bound, "h_top(H^%d) >= %.6f, h_top(H) >= %.6f", h->def.iterates, r->entropy, r->entropy_map);
    else
        snprintf(bound, sizeof bound, "h_top >= %.6f", r->entropy);
    snprintf(summary, sizeof summary, "(%d of %zu covering relations, %s, %ld pieces enclosed; %.2g s)", relations,
             h->def.sets * h->def.sets, bound, r->pieces, r->seconds);
    cJSON_AddStringToObject(s, "summary", summary);
    return s;
}

/* The classical Hénon map's strips returning across a band, and the renewal bound of entropy they prove; with
 * `partial`, also the strips returning across part of it, and their graph's bound. */
static cJSON *returns_statement(long precision, int partial, int *proved, int *status)
{
    gb_proof_field field;
    gb_proof_returns_def def;
    gb_proof_returns_result r;
    *status = partial ? gb_proof_returns_henon_partial(&field, &def) : gb_proof_returns_henon_classical(&field, &def);
    if (*status) return NULL;
    def.precision = precision;
    /* the statement: the bound the table gives when every strip returns, rounded down to 5 decimals (computed from the
     * table before the returns are proved; proved when all of them are) */
    double table_root = 0.0;
    *status = gb_proof_returns_table_bound(&def, &table_root);
    if (*status) return NULL;
    const double claimed = floor(table_root * 1e5) / 1e5;
    *status = gb_proof_returns(&def, &r);
    if (*status) return NULL;
    size_t across = 0;
    for (size_t i = 0; i < def.sets; i++) across += def.reach[i].lo == 0.0 && def.reach[i].hi == 0.0;
    cJSON *s = cJSON_CreateObject();
    char text[400];
    if (partial)
        snprintf(
            text, sizeof text,
            "Henon, a = 1.4, b = 0.3 (classical): %zu strips of a band return across it and %zu across part of it, "
            "h_top >= %.5f",
            across, def.sets - across, claimed);
    else
        snprintf(text, sizeof text,
                 "Henon, a = 1.4, b = 0.3 (classical): %zu strips of a band return across it, h_top >= %.5f", def.sets,
                 claimed);
    cJSON_AddStringToObject(s, "statement", text);
    cJSON_AddStringToObject(s, "system",
                            "(x, y) -> (1 - a x^2 + y, b x), a = 7/5, b = 3/10 exactly, read in the horseshoe's frame "
                            "(x, y) = o + F (u, s), o = (3157/5000, 947/5000), F = [[-1, -13/25], [39/250, -1]]");
    snprintf(text, sizeof text,
             "in the frame's chart (u, s - %g (u - %g)^2) (a band bent along the attractor's layers near the fixed "
             "point), R = W x S with W = [%g, %g], S = [%g, %g]; %zu strips U_i x S with return times m_i%s (listed), "
             "found by scripts/henon_returns_search.py%s",
             def.curvature, def.vertex, def.window.lo, def.window.hi, def.strip.lo, def.strip.hi, def.sets,
             partial ? " and reaches T_i (W where not listed)" : "", partial ? " --partial" : "");
    cJSON_AddStringToObject(s, "sets", text);
    cJSON_AddStringToObject(s, "reproduces",
                            "not a published set (ours); published lower bounds at these parameters: 0.4320 (Day, "
                            "Frongillo & Trevino 2008) and 0.46469 (Newhouse, Berz, Grote & Makino 2008)");
    cJSON_AddStringToObject(
        s, "method",
        partial ? "each strip's m-th iterate on Arb's balls in affine form (the C0 Lohner algorithm for maps) over "
                  "pieces, halved across and along where a piece decides nothing; the edges' images beyond its reach "
                  "T, the images that land in T inside S; M(x0) v >= v on Arb's balls for a positive v"
                : "each strip's m-th iterate on Arb's balls in affine form (the C0 Lohner algorithm for maps) "
                  "over pieces, halved across and along where a piece decides nothing; the edges' images "
                  "beyond W, the images that land in W inside S");
    cJSON_AddStringToObject(
        s, "theorem",
        partial
            ? "a strip whose m-th image runs across its reach T covers every strip inside T for that iterate (Gidea "
              "& Zgliczynski 2004, Def. 6, by a two-stage homotopy: docs/proofs.md); chains of such relations have "
              "orbits (their Thm 9), and sequences that first differ do so at the same time in disjoint strips, so "
              "h_top >= ln x0 where M(x0) v >= v for a positive v, M(x)_ij = x^-m_i when strip j lies in strip "
              "i's reach (the paths of total time T from i number at least c v_i x0^T)"
            : "a strip whose m-th image runs across R covers every strip for that iterate (Gidea & "
              "Zgliczynski 2004, Def. 6, by a two-stage homotopy: docs/proofs.md); chains of such "
              "relations have orbits (their Thm 9), and sequences that first differ do so at the same "
              "time in disjoint strips, so h_top >= ln x, sum_i x^-m_i = 1");
    snprintf(text, sizeof text,
             partial
                 ? "the classical Henon map's entropy bound raised from the band's returns across it to %.5f by "
                   "returns across part of it; still below the published 0.4320 and 0.46469"
                 : "the classical Henon map's entropy bound raised from ln 5 / 7 = 0.22992 (the horseshoe above) to "
                   "%.5f on one band; still below the published 0.4320 and 0.46469",
             claimed);
    cJSON_AddStringToObject(s, "reading", text);
    cJSON *list = cJSON_AddArrayToObject(s, "strips");
    for (size_t i = 0; i < def.sets; i++) {
        cJSON *e = cJSON_CreateObject();
        cJSON_AddItemToObject(e, "u", prove_json_interval(def.set_u[i]));
        cli_json_add(e, "returns", def.returns[i]);
        if (def.reach[i].lo != 0.0 || def.reach[i].hi != 0.0)
            cJSON_AddItemToObject(e, "reach", prove_json_interval(def.reach[i]));
        cli_json_add(e, "across", r.across[i]);
        cli_json_add(e, "targets", (double)r.targets[i]);
        cJSON_AddItemToObject(e, "image_of_low_edge_u", prove_json_interval(r.edge[i][0]));
        cJSON_AddItemToObject(e, "image_of_high_edge_u", prove_json_interval(r.edge[i][1]));
        cJSON_AddItemToArray(list, e);
    }
    cli_json_add(s, "entropy_lower_bound", r.entropy);
    cli_json_add(s, "pieces", (double)r.pieces);
    *proved = r.proved == def.sets && r.entropy >= claimed;
    char result[520];
    if (*proved)
        snprintf(result, sizeof result, "proved");
    else
        snprintf(result, sizeof result, "not proved: %zu of %zu returns proved, h_top >= %.6f%s%s", r.proved, def.sets,
                 r.entropy, r.failure[0] ? "; " : "", r.failure);
    cJSON_AddStringToObject(s, "result", result);
    cli_json_add(s, "seconds", r.seconds);
    char summary[200];
    snprintf(summary, sizeof summary, "(%zu of %zu returns, h_top >= %.6f, %ld pieces enclosed; %.2g s)", r.proved,
             def.sets, r.entropy, r.pieces, r.seconds);
    cJSON_AddStringToObject(s, "summary", summary);
    return s;
}

/* Rössler's period-1 orbit: Krawczyk's operator on the return map to x = 0 over a box 2e-3 wide (uniqueness there),
 * then over a box 2e-7 wide about the same middle (its K, and the period over K, pin the orbit down). The middle, to 8
 * decimals, is where Newton on a floating-point return map lands (verify/s7_covering.c finds it again with GSL's rk8pd
 * and checks that it lies in both K); it only places the boxes: what is proved is read from K. */
static cJSON *orbit_statement(long precision, int *proved, int *status)
{
    static const double y0 = -8.38094174, z0 = 0.02959006, wide = 1e-3, narrow = 1e-7;
    gb_proof_field field = gb_proof_flow_rossler(1, 5, 1, 5, 57, 10);
    gb_proof_flow_def def = gb_proof_flow_def_default(&field);
    def.precision = precision;
    gb_proof_interval big[3] = {{0, 0}, {y0 - wide, y0 + wide}, {z0 - wide, z0 + wide}};
    gb_proof_interval small[3] = {{0, 0}, {y0 - narrow, y0 + narrow}, {z0 - narrow, z0 + narrow}};
    gb_proof_flow_orbit unique, tight;
    *status = gb_proof_flow_periodic_orbit(&def, big, &unique);
    if (!*status) *status = gb_proof_flow_periodic_orbit(&def, small, &tight);
    if (*status) return NULL;
    *proved = unique.proved && tight.proved;
    cJSON *s = cJSON_CreateObject();
    cJSON_AddStringToObject(s, "statement", "Roessler, a = b = 0.2, c = 5.7: a periodic orbit crossing x = 0 once a turn, the only one "
                                            "through the box (y, z) in [-8.38194, -8.37994] x [0.02859, 0.03059]");
    cJSON_AddStringToObject(s, "system", "x' = -y - z, y' = x + a y, z' = b + z (x - c), a = 1/5, b = 1/5, c = 57/10 exactly; "
                                         "P the return map to x = 0 crossed with x' > 0");
    cJSON_AddStringToObject(s, "method", "P and DP enclosed over the box by the rigorous integrator's C1 step (the variational "
                                         "equations with their own a-priori enclosure and remainder, DP = (I - f e^T / f_x) DPhi at "
                                         "the crossing), Krawczyk's operator on P - id on Arb's balls");
    cJSON_AddStringToObject(s, "theorem", "Krawczyk 1969 (Neumaier 1990, Thm 5.1.7): K = x - C F(x) + (I - C F'(X))(X - x) inside "
                                          "the interior of X gives exactly one zero of F = P - id in X, and it lies in K");
    cJSON_AddStringToObject(s, "reproduces", "the period-1 orbit of the Roessler attractor at the standard parameters (period "
                                             "5.8811), found here by Newton on a floating-point return map and proved");
    cJSON *boxes = cJSON_AddArrayToObject(s, "boxes");
    const gb_proof_flow_orbit *o[2] = {&unique, &tight};
    for (int k = 0; k < 2; k++) {
        cJSON *b = cJSON_CreateObject();
        cJSON_AddItemToObject(b, "y", prove_json_interval(k ? small[1] : big[1]));
        cJSON_AddItemToObject(b, "z", prove_json_interval(k ? small[2] : big[2]));
        cJSON_AddItemToObject(b, "K_y", prove_json_interval(o[k]->krawczyk[1]));
        cJSON_AddItemToObject(b, "K_z", prove_json_interval(o[k]->krawczyk[2]));
        cli_json_add(b, "proved", o[k]->proved);
        cJSON_AddItemToArray(boxes, b);
    }
    cJSON_AddItemToObject(s, "period", prove_json_interval(tight.period));
    cJSON *dp = cJSON_AddArrayToObject(s, "DP_over_wide_box"); /* rows y, z; columns y, z */
    for (int a = 1; a < 3; a++)
        for (int b = 1; b < 3; b++) cJSON_AddItemToArray(dp, prove_json_interval(unique.jacobian[a][b]));
    char result[200];
    snprintf(result, sizeof result, *proved ? "proved" : "not proved: K is not inside the box%s",
             unique.excluded || tight.excluded ? " (it misses it: no fixed point there)" : "");
    cJSON_AddStringToObject(s, "result", result);
    cli_json_add(s, "seconds", unique.seconds + tight.seconds);
    char summary[200];
    snprintf(summary, sizeof summary, "(period in [%.10f, %.10f], y in [%.10f, %.10f]; %.2g s)", tight.period.lo, tight.period.hi,
             tight.krawczyk[1].lo, tight.krawczyk[1].hi, unique.seconds + tight.seconds);
    cJSON_AddStringToObject(s, "summary", summary);
    return s;
}

/* A Gömböc's statement, on a thread of its own (or in the caller's): what it needs and what it gives. */
typedef struct body_job {
    size_t which; /* 0: Gömböc I, 1: Gömböc II; for the trellis, 1: the large one */
    double resolution;
    long precision;
    int depth, threaded, threads;
    cJSON *statement;
    int proved, status;
    char message[512]; /* the error's message, read in the thread that failed (gb_error's is per thread) */
} body_job;

static void *body_statement(void *arg)
{
    body_job *j = arg;
    j->statement = prove_body_statement(j->which, j->resolution, j->precision, j->depth, &j->proved, &j->status);
    if (j->status) snprintf(j->message, sizeof j->message, "%s", gb_error_message());
    if (j->threaded) gb_proof_thread_done();
    return NULL;
}

/* The trellis's statement (the longest), in a body_job's frame (resolution unused; the large one on `threads`). */
static void *trellis_statement(void *arg)
{
    body_job *j = arg;
    j->statement =
        prove_trellis_statement(j->precision, (int)j->which, j->which ? j->threads : 1, &j->proved, &j->status);
    if (j->status) snprintf(j->message, sizeof j->message, "%s", gb_error_message());
    if (j->threaded) gb_proof_thread_done();
    return NULL;
}

/* Each statement on a line with its result and summary, then the count. */
static void print_statements(const cJSON *list, int proved_count, int attempted, double precision)
{
    const cJSON *item;
    cJSON_ArrayForEach(item, list)
    {
        const cJSON *st = cJSON_GetObjectItemCaseSensitive(item, "statement"),
                    *res = cJSON_GetObjectItemCaseSensitive(item, "result");
        const cJSON *summary = cJSON_GetObjectItemCaseSensitive(item, "summary");
        printf("%s: %s%s%s\n", st->valuestring, res->valuestring, cJSON_IsString(summary) ? " " : "",
               cJSON_IsString(summary) ? summary->valuestring : "");
    }
    printf("%d of %d statements attempted proved at %.0f bits (gomboc prove --json: the enclosures)\n", proved_count,
           attempted, precision);
}

/* gomboc prove --horseshoe: that statement alone, for the body named (NULL: Gömböc II, the one make prove proves;
 * gomboc_prove_chain.c). Gömböc I's is not proved (five of its links fail): docs/proofs.md, "What is open". */
static int prove_horseshoe(const char *morphology, long precision, int threads, int json)
{
    cJSON *root = cJSON_CreateObject(), *list = cJSON_AddArrayToObject(root, "statements");
    cli_json_add(root, "precision_bits", (double)precision);
    int proved = 0, status = GB_OK;
    cJSON *statement = prove_chain_statement(morphology ? morphology : "II", precision, threads, &proved, &status);
    if (statement) cJSON_AddItemToArray(list, statement);
    if (status) {
        cJSON_Delete(root);
        return cli_failure("prove", status);
    }
    cli_json_add(root, "attempted", 1);
    cli_json_add(root, "proved", proved);
    if (json)
        cli_print_json(root);
    else
        print_statements(list, proved, 1, (double)precision);
    cJSON_Delete(root);
    if (!proved) {
        fprintf(stderr, "gomboc prove: the horseshoe is not proved (its links say why)\n");
        return EXIT_COMPUTE;
    }
    return 0;
}

int command_prove_in_process(int argc, char **argv)
{
    const char *precision_text = NULL, *depth_text = NULL, *resolution_text = NULL, *threads_text = NULL,
               *morphology = NULL;
    int json = 0, chain = 0, large = 0;
    for (int i = 0; i < argc; i++) {
        if (!strcmp(argv[i], "--horseshoe") || !strcmp(argv[i], "--large-trellis")) {
            if (cli_flag("prove", argv[i], argv[i][2] == 'h' ? &chain : &large)) return EXIT_INPUT;
            continue;
        }
        const char *value = NULL;
        const int kind = cli_next_option(
            "prove", argc, argv, &i, usage_prove,
            (const char *const[]){"--precision", "--depth", "--resolution", "--threads", "--morphology", NULL},
            " (allowed: --precision BITS, --depth N, --resolution R, --threads N, --horseshoe, --morphology I|II, "
            "--large-trellis, --json, --help)",
            NULL, &json, &value);
        if (kind == CLI_HELP) return 0;
        if (kind == CLI_NEXT) continue;
        if (kind != CLI_VALUE) return kind;
        const char **slot = !strcmp(argv[i - 1], "--precision")    ? &precision_text
                            : !strcmp(argv[i - 1], "--depth")      ? &depth_text
                            : !strcmp(argv[i - 1], "--threads")    ? &threads_text
                            : !strcmp(argv[i - 1], "--morphology") ? &morphology
                                                                   : &resolution_text;
        if (*slot) return cli_input_error("prove", "%s given twice (allowed: once)", argv[i - 1]);
        *slot = value;
    }
    double precision = GB_PROOF_PRECISION_DEFAULT, depth = 24;
    if (precision_text && cli_number("prove", "--precision", precision_text, GB_PROOF_PRECISION_MIN, GB_PROOF_PRECISION_MAX, 0,
                                     " (allowed: an integer from 64 to 4096)", &precision))
        return EXIT_INPUT;
    if (precision != floor(precision))
        return cli_input_error("prove", "--precision %s: not an integer (allowed: an integer from 64 to 4096)", precision_text);
    if (depth_text && cli_number("prove", "--depth", depth_text, 1, 40, 0, " (allowed: an integer from 1 to 40)", &depth))
        return EXIT_INPUT;
    if (depth != floor(depth)) return cli_input_error("prove", "--depth %s: not an integer (allowed: an integer from 1 to 40)", depth_text);
    double resolution = 0.0;
    if (resolution_text && cli_number("prove", "--resolution", resolution_text, GB_PROOF_BODY_RESOLUTION_MIN,
                                      GB_PROOF_BODY_RESOLUTION_MAX, 0, " (allowed: 1e-5 to 0.1)", &resolution))
        return EXIT_INPUT;
    double threads = sysconf(_SC_NPROCESSORS_ONLN) >= 2 ? 2 : 1;
    if (threads_text &&
        cli_number("prove", "--threads", threads_text, 1, 256, 0, " (allowed: an integer from 1 to 256)", &threads))
        return EXIT_INPUT;
    if (threads != floor(threads))
        return cli_input_error("prove", "--threads %s: not an integer (allowed: an integer from 1 to 256)",
                               threads_text);
    if (morphology && !chain)
        return cli_input_error("prove",
                               "--morphology %s without --horseshoe (allowed: --morphology with --horseshoe only; "
                               "the Melnikov statements are made for both bodies)",
                               morphology);
    if (morphology && strcmp(morphology, "I") && strcmp(morphology, "II"))
        return cli_input_error("prove", "--morphology %s: no horseshoe for it (allowed: I or II, Table 1's bodies)",
                               morphology);
    if (large && chain)
        return cli_input_error("prove", "--large-trellis with --horseshoe (allowed: one of them; the horseshoe's "
                                        "statement has no trellis)");
    if (cli_parse_only) return 0;
    if (chain) return prove_horseshoe(morphology, (long)precision, (int)threads, json);

    /* The trellis's statement (the longest) starts first, on a thread of its own when there are two, and Gömböc I's
     * (the next) on another when there are three; the rest follow on this thread. The list's order is the same
     * whatever the threads. */
    body_job job[2],
        trellis = {(size_t)large, resolution, (long)precision, (int)depth, 0, (int)threads, NULL, 0, GB_OK, ""};
    for (size_t k = 0; k < 2; k++)
        job[k] = (body_job){k, resolution, (long)precision, (int)depth, 0, 1, NULL, 0, GB_OK, ""};
    trellis.threaded = threads >= 2, job[0].threaded = threads >= 3;
    pthread_t worker, trellis_worker;
    if (trellis.threaded && pthread_create(&trellis_worker, NULL, trellis_statement, &trellis)) trellis.threaded = 0;
    if (job[0].threaded && pthread_create(&worker, NULL, body_statement, &job[0])) job[0].threaded = 0;
    cJSON *root = cJSON_CreateObject(), *list = cJSON_AddArrayToObject(root, "statements");
    cli_json_add(root, "precision_bits", precision);
    int attempted = 0, proved_count = 0, status = GB_OK;
    for (int s = 0; s < 2 && !status; s++)
        for (int k = 0; k < OMEGAS && !status; k++) {
            gb_proof_integrals I;
            status = gb_proof_oracle_integrals((gb_proof_system)s, omegas[k], (long)precision, &I);
            if (status) break;
            int proved;
            cJSON_AddItemToArray(list, integrals_statement(&I, &proved));
            attempted++, proved_count += proved;
        }
    for (int k = 0; k < FORCINGS && !status; k++) {
        const forcing *f = &forcings[k];
        gb_proof_integrals I;
        gb_proof_interval psi = {0}; /* read only once made (the struct below is built before the status is tested) */
        status = gb_proof_oracle_integrals(f->system, f->omega, (long)precision, &I);
        if (!status) status = gb_proof_pi_fraction(f->psi_num, f->psi_den, &psi);
        gb_proof_zeros z;
        const gb_proof_melnikov m = {I.D, I.C1, I.S1, I.C2, I.S2, f->mu, f->nu1, f->nu2, f->omega, psi, (long)precision, (int)depth};
        if (!status) status = gb_proof_melnikov_zeros(&m, &z);
        if (status) break;
        int proved;
        cJSON_AddItemToArray(list, zeros_statement(f, &I, &z, psi, &proved));
        attempted++, proved_count += proved;
    }
    void (*const horseshoes[3])(horseshoe *) = {horseshoe_rossler, horseshoe_henon, horseshoe_henon_classical};
    for (int k = 0; k < 3 && !status; k++) {
        horseshoe h;
        horseshoes[k](&h);
        h.def.section.precision = (long)precision, h.def.precision = (long)precision;
        gb_proof_cover_result r;
        status = h.status ? h.status : gb_proof_cover(&h.def, &r);
        if (status) break;
        int proved;
        cJSON_AddItemToArray(list, horseshoe_statement(&h, &r, &proved));
        attempted++, proved_count += proved;
    }
    if (!status) {
        int proved;
        cJSON *statement = returns_statement((long)precision, 0, &proved, &status);
        if (statement) cJSON_AddItemToArray(list, statement), attempted++, proved_count += proved;
    }
    if (!status) {
        int proved;
        cJSON *statement = returns_statement((long)precision, 1, &proved, &status);
        if (statement) cJSON_AddItemToArray(list, statement), attempted++, proved_count += proved;
    }
    for (int classical = 0; classical < 2 && !status; classical++) {
        int proved;
        cJSON *statement = prove_conley_statement((long)precision, classical, &proved, &status);
        if (statement) cJSON_AddItemToArray(list, statement), attempted++, proved_count += proved;
    }
    if (!status) {
        int proved;
        cJSON *statement = prove_manifold_statement((long)precision, &proved, &status);
        if (statement) cJSON_AddItemToArray(list, statement), attempted++, proved_count += proved;
    }
    /* the trellis's place, held by a null until it is done (cJSON 1.7.15's insertion inside an array does nothing) */
    const int trellis_at = cJSON_GetArraySize(list);
    cJSON_AddItemToArray(list, cJSON_CreateNull());
    if (!status) {
        int proved;
        cJSON *statement = orbit_statement((long)precision, &proved, &status);
        if (statement) cJSON_AddItemToArray(list, statement), attempted++, proved_count += proved;
    }
    if (!status) body_statement(&job[1]);
    if (job[0].threaded)
        pthread_join(worker, NULL);
    else if (!status && !job[1].status)
        body_statement(&job[0]);
    if (trellis.threaded)
        pthread_join(trellis_worker, NULL);
    else if (!status && !job[0].status && !job[1].status)
        trellis_statement(&trellis);
    if (!status && trellis.status) status = gb_error_set(trellis.status, "%s", trellis.message);
    for (size_t k = 0; k < 2; k++)
        if (!status && job[k].status) status = gb_error_set(job[k].status, "%s", job[k].message);
    if (trellis.statement && !status && cJSON_ReplaceItemInArray(list, trellis_at, trellis.statement)) {
        attempted++, proved_count += trellis.proved;
    } else {
        cJSON_Delete(trellis.statement);
        cJSON_DeleteItemFromArray(list, trellis_at);
    }
    for (size_t k = 0; k < 2; k++) {
        if (!job[k].statement) continue;
        if (status) { /* a failure elsewhere: the statement is not listed */
            cJSON_Delete(job[k].statement);
            continue;
        }
        cJSON_AddItemToArray(list, job[k].statement);
        attempted++, proved_count += job[k].proved;
    }
    if (status) {
        cJSON_Delete(root);
        return cli_failure("prove", status);
    }
    cli_json_add(root, "attempted", attempted);
    cli_json_add(root, "proved", proved_count);
    if (json) {
        cli_print_json(root);
    } else {
        print_statements(list, proved_count, attempted, precision);
    }
    cJSON_Delete(root);
    if (proved_count < attempted) {
        fprintf(stderr, "gomboc prove: %d of %d statements not proved (each says why)\n", attempted - proved_count, attempted);
        return EXIT_COMPUTE;
    }
    return 0;
}
