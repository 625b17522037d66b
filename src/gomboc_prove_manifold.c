/* gomboc prove's statement on the classical Hénon map's invariant manifolds (gb_proof_manifold.h): the fixed point's
 * unstable and stable manifolds parametrised with proved tails, and their crossings over two arcs, each proved
 * transverse, and no other. */
#include "gomboc_cli.h"
#include "gomboc_prove_common.h"

#include "gb_proof_manifold.h"

#include <stdio.h>

/* The claim, fixed before a run: the number of crossings of the arcs below when the statement was written (the fixed
 * point among them); the arcs, the parametrisations' order 30, σ = 1 and ρ = 1, and the pieces' width 0.01. */
enum { CLAIM_CROSSINGS = 19, ORDER = 30, DEPTH = 40 };
static const gb_proof_interval arc_s = {-26.0, 26.0}, arc_t = {-3.0, 3.0};

int prove_henon_manifolds(long precision, gb_proof_manifold **P, gb_proof_manifold **R)
{
    gb_proof_field map, inverse;
    *P = *R = NULL;
    int status = gb_proof_manifold_henon(7, 5, 3, 10, &map, &inverse);
    gb_proof_manifold_def def = gb_proof_manifold_def_default();
    def.fixed[0] = 0.63, def.fixed[1] = 0.19, def.order = ORDER, def.precision = precision;
    def.map = &map;
    if (!status) status = gb_proof_manifold_create(&def, P);
    def.map = &inverse;
    if (!status) status = gb_proof_manifold_create(&def, R);
    return status;
}

cJSON *prove_manifold_statement(long precision, int *proved, int *status)
{
    const double start = prove_thread_seconds();
    gb_proof_manifold *P, *R;
    *status = prove_henon_manifolds(precision, &P, &R);
    gb_proof_manifold_crossings_result x = {0};
    const gb_proof_manifold_crossings_def cd = {arc_s, arc_t, 0.01, DEPTH};
    if (!*status) *status = gb_proof_manifold_crossings(P, R, &cd, &x);
    if (*status) {
        gb_proof_manifold_free(P), gb_proof_manifold_free(R);
        return NULL;
    }
    gb_proof_manifold_info ip, ir;
    gb_proof_manifold_info_of(P, &ip), gb_proof_manifold_info_of(R, &ir);
    gb_proof_manifold_free(P), gb_proof_manifold_free(R);
    cJSON *s = cJSON_CreateObject();
    char text[700];
    snprintf(text, sizeof text,
             "Henon, a = 1.4, b = 0.3 (classical): the fixed point's unstable arc P([%g, %g]) and stable arc "
             "R([%g, %g]) cross exactly %d times, each transversally (the fixed point and %d homoclinic points)",
             arc_s.lo, arc_s.hi, arc_t.lo, arc_t.hi, CLAIM_CROSSINGS, CLAIM_CROSSINGS - 1);
    cJSON_AddStringToObject(s, "statement", text);
    cJSON_AddStringToObject(s, "system",
                            "(x, y) -> (1 - a x^2 + y, b x), a = 7/5, b = 3/10 exactly; its inverse "
                            "(x, y) -> (y/b, x - 1 + (a/b^2) y^2)");
    snprintf(text, sizeof text,
             "P(lambda s) = H(P(s)), P(0) = z*, |P'(0)| = 1 (the unstable manifold); R likewise for the inverse (the "
             "stable manifold); each of order %d on the disc |s| <= 1 with its tail, beyond it by iterates; pieces of "
             "the arcs until their enclosures are 0.01 wide: %zu of P, %zu of R, %zu pairs whose enclosures meet",
             ORDER, x.pieces_s, x.pieces_t, x.pairs);
    cJSON_AddStringToObject(s, "sets", text);
    cJSON_AddStringToObject(s, "method",
                            "the fixed point by Krawczyk's operator; the eigenvalues proved real, |lambda| > 1 > |mu|; "
                            "the parametrisation method's coefficients on Arb and the tail h = P - P_N as the fixed "
                            "point of a contraction (Schwarz's lemma; bounds r (|s|/rho)^(N+1) and, by Cauchy, on P'); "
                            "each crossing by Krawczyk's operator on P(s) - R(t), the rest of the arcs excluded by "
                            "bisection (enclosures apart, or Krawczyk's image outside the box)");
    cJSON_AddStringToObject(s, "theorem",
                            "the parametrisation method (Cabre, Fontich & de la Llave 2003): the solution of the "
                            "conjugacy is the unstable manifold; Krawczyk's operator inside the box: exactly one zero "
                            "and every matrix of [P', -R'] over the box regular, so the crossing is transverse; "
                            "Smale-Birkhoff: a transverse homoclinic point gives a horseshoe of an iterate");
    snprintf(text, sizeof text,
             "the first pieces of a trellis (Newhouse, Berz, Grote & Makino 2008's route to h_top >= 0.46469): the "
             "manifolds and their crossings; no entropy bound comes from them yet. Tails: P %.2g, R %.2g; "
             "eigenvalues [%.15g, %.15g] and [%.9g, %.9g]",
             ip.tail, ir.tail, ip.lambda.lo, ip.lambda.hi, ip.other.lo, ip.other.hi);
    cJSON_AddStringToObject(s, "reading", text);
    cJSON *points = cJSON_AddArrayToObject(s, "crossings");
    for (size_t k = 0; k < x.count; k++) {
        cJSON *p = cJSON_CreateObject();
        cJSON_AddItemToObject(p, "s", prove_json_interval(x.crossings[k].s));
        cJSON_AddItemToObject(p, "t", prove_json_interval(x.crossings[k].t));
        cJSON_AddItemToObject(p, "x", prove_json_interval(x.crossings[k].point[0]));
        cJSON_AddItemToObject(p, "y", prove_json_interval(x.crossings[k].point[1]));
        cJSON_AddItemToArray(points, p);
    }
    cJSON_AddItemToObject(s, "fixed_point_x", prove_json_interval(ip.fixed[0]));
    cJSON_AddItemToObject(s, "fixed_point_y", prove_json_interval(ip.fixed[1]));
    cli_json_add(s, "count", (double)x.count);
    cli_json_add(s, "complete", x.proved);
    *proved = x.proved && x.count == CLAIM_CROSSINGS;
    char result[320];
    if (*proved)
        snprintf(result, sizeof result, "proved");
    else if (!x.proved)
        snprintf(result, sizeof result, "not proved: %s", x.failure);
    else
        snprintf(result, sizeof result, "not proved: %zu crossings, not %d", x.count, CLAIM_CROSSINGS);
    cJSON_AddStringToObject(s, "result", result);
    const size_t count = x.count;
    gb_proof_manifold_crossings_free(&x);
    const double seconds = prove_thread_seconds() - start;
    cli_json_add(s, "seconds", seconds);
    char summary[200];
    snprintf(summary, sizeof summary, "(%zu crossings%s; tails %.1g and %.1g; %.2g s)", count,
             *proved ? ", complete" : "", ip.tail, ir.tail, seconds);
    cJSON_AddStringToObject(s, "summary", summary);
    return s;
}
