/* gomboc prove's statements by the discrete Conley index (gb_proof_conley.h): Hénon's map at a = 6, whose entropy is
 * known exactly, and the classical Hénon map from the boxes of its periodic points. */
#include "gomboc_cli.h"
#include "gomboc_prove_common.h"

#include "gb_proof_conley.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* The statements' claims, fixed before a run: ln 2 for a = 6, rounded down; for the classical map the bound this
 * construction reached when it was written, rounded down to 5 decimals. */
enum { HORSESHOE_DEPTH = 7, CLASSICAL_DEPTH = 12, CLASSICAL_PERIODS = 12 };
static const double horseshoe_claim = 0.69314, classical_claim = 0.43255;

/* The classical map's seeds: the periodic orbits of periods 1 ... 12 with these orbits toggled (least period, least x),
 * chosen once by a search over single orbits of periods 1 ... 16 that kept each toggle raising the bound (docs/proofs.md,
 * item 11). They only place N; nothing proved rests on them. */
static const gb_proof_conley_orbit classical_toggles[] = {
    {8, -1.140785646},  {13, -1.035518622}, {14, -1.177431040}, {14, -1.157644383}, {15, -1.030184236},
    {15, -0.938869971}, {16, -1.246542874}, {16, -1.162764450}, {16, -1.133356880},
};
enum { CLASSICAL_TOGGLE_COUNT = sizeof classical_toggles / sizeof *classical_toggles };

cJSON *prove_conley_statement(long precision, int classical, int *proved, int *status)
{
    const double start = prove_thread_seconds();
    gb_proof_field field;
    gb_proof_conley_def def;
    uint32_t *seeds = NULL, *n_boxes = NULL, *p1 = NULL, *p0 = NULL;
    size_t seed_count = 0, n = 0, p1_count = 0, p0_count = 0;
    *status = classical ? gb_proof_conley_henon_orbits(CLASSICAL_PERIODS, classical_toggles, CLASSICAL_TOGGLE_COUNT,
                                                       CLASSICAL_DEPTH, &field, &def, &seeds, &seed_count)
                        : gb_proof_conley_henon_horseshoe(HORSESHOE_DEPTH, &field, &def, &n_boxes, &n);
    def.precision = precision;
    if (!*status && classical) *status = gb_proof_conley_isolate(&def, seeds, seed_count, 1000000, &n_boxes, &n);
    if (!*status) *status = gb_proof_conley_pair(&def, n_boxes, n, &p1, &p1_count, &p0, &p0_count);
    gb_proof_conley_result r;
    if (!*status) {
        def.p1 = p1, def.p1_count = p1_count, def.p0 = p0, def.p0_count = p0_count;
        *status = gb_proof_conley(&def, &r);
    }
    free(seeds), free(n_boxes), free(p1), free(p0);
    if (*status) return NULL;
    const double claim = classical ? classical_claim : horseshoe_claim;
    cJSON *s = cJSON_CreateObject();
    char text[1200]; /* the sets line: grown (up to 400) and its own words and numbers */
    if (classical)
        snprintf(text, sizeof text, "Henon, a = 1.4, b = 0.3 (classical), by its discrete Conley index: h_top >= %.5f",
                 claim);
    else
        snprintf(text, sizeof text, "Henon, a = 6, b = 0.3, by its discrete Conley index: h_top >= %.5f (ln 2)", claim);
    cJSON_AddStringToObject(s, "statement", text);
    cJSON_AddStringToObject(s, "system",
                            classical ? "(x, y) -> (1 - a x^2 + y, b x), a = 7/5, b = 3/10 exactly"
                                      : "(x, y) -> (1 - a x^2 + y, b x), a = 6, b = 3/10 exactly");
    int left_out = 0, added = 0, longest = 0;
    for (int k = 0; k < CLASSICAL_TOGGLE_COUNT; k++) {
        if (classical_toggles[k].period <= CLASSICAL_PERIODS)
            left_out++;
        else
            added++, longest = classical_toggles[k].period > longest ? classical_toggles[k].period : longest;
    }
    char grown[400], longer[80] = "";
    if (added)
        snprintf(longer, sizeof longer, ", and %d of periods %d ... %d added", added, CLASSICAL_PERIODS + 1, longest);
    snprintf(grown, sizeof grown,
             "N grown from the %zu boxes of the points of periodic orbits (Newton on doubles): those of periods 1 ... "
             "%d, %d of them left out%s (the orbits named in the source), until it isolates its invariant part and "
             "holds P1 \\ P0 in its interior",
             seed_count, CLASSICAL_PERIODS, left_out, longer);
    snprintf(text, sizeof text,
             "a grid of 2^%d x 2^%d boxes over [%g, %g] x [%g, %g]; %s; the index pair built from N (S = Inv(N), "
             "K = S and its neighbours, P1 = what F reaches from K inside N, P0 = the part of P1 that cannot reach K): "
             "%zu boxes in N, %zu in P1, %zu in P0",
             def.depth, def.depth, def.x.lo, def.x.hi, def.y.lo, def.y.hi,
             classical ? grown : "N every box off the grid's edge", n, p1_count, p0_count);
    cJSON_AddStringToObject(s, "sets", text);
    cJSON_AddStringToObject(s, "reproduces",
                            classical
                                ? "Day, Frongillo & Trevino 2008's h_top >= 0.4320 by the same index: "
                                  "reached and passed with an N of our own (theirs is not reproduced)"
                                : "Devaney & Nitecki 1979: a full horseshoe for a > (5 + 2 sqrt 5)(1 + |b|)^2 / 4; "
                                  "Friedland & Milnor 1989: h_top <= ln 2 for every Henon map");
    cJSON_AddStringToObject(s, "method",
                            "F on Arb's balls (every box touching the enclosure of a box's image); the index pair's "
                            "three conditions box by box; H_1(P1, P0; Z2) by tree-cotree and the index map by an "
                            "acyclic-carrier chain selector; regions the components of P1 \\ P0; the sofic graph of "
                            "pairs (region, non-zero class) and Collatz-Wielandt on Arb for its largest component");
    cJSON_AddStringToObject(s, "theorem",
                            "the Conley index of a decomposition (Szymczak 1995; Day, Frongillo & Trevino 2008): a "
                            "cyclic word of regions whose product of index-map blocks is not nilpotent is followed by "
                            "an orbit; the labels of the sofic graph's cycles are such words, so the orbits map onto "
                            "its shift (right-resolving presentation: entropy ln rho, Lind & Marcus Thm 4.3.3)");
    snprintf(
        text, sizeof text,
        classical
            ? "an independent proof of the classical Henon map's chaos, and the highest bound proved here: "
              "%.9f, above Day, Frongillo & Trevino's 0.4320 and the returns' 0.41184 above; below Newhouse, Berz, "
              "Grote & Makino's 0.46469"
            : "the Conley index machinery on a map whose entropy is known exactly: %.12f against ln 2 = 0.693147180560",
        r.entropy);
    cJSON_AddStringToObject(s, "reading", text);
    cJSON *c = cJSON_AddObjectToObject(s, "index_pair");
    cli_json_add(c, "positively_invariant", r.positively_invariant);
    cli_json_add(c, "exit_set", r.exit_set);
    cli_json_add(c, "isolated", r.isolated);
    cli_json_add(c, "invariant_boxes", (double)r.invariant_boxes);
    cli_json_add(s, "h0", (double)r.h0), cli_json_add(s, "h1", (double)r.h1), cli_json_add(s, "h2", (double)r.h2);
    cli_json_add(s, "regions", (double)r.regions), cli_json_add(s, "regions_used", (double)r.regions_used);
    cli_json_add(s, "symbols", (double)r.symbols), cli_json_add(s, "transitions", (double)r.transitions);
    cli_json_add(s, "component", (double)r.component), cli_json_add(s, "rho_lower_bound", r.rho);
    cli_json_add(s, "entropy_lower_bound", r.entropy);
    if (classical) cli_json_add(s, "seeds", (double)seed_count);
    *proved = r.index_pair && r.entropy >= claim;
    char result[320];
    if (*proved)
        snprintf(result, sizeof result, "proved");
    else if (!r.index_pair)
        snprintf(result, sizeof result, "not proved: not an index pair: %s", r.failure);
    else
        snprintf(result, sizeof result, "not proved: h_top >= %.6f only", r.entropy);
    cJSON_AddStringToObject(s, "result", result);
    const double seconds = prove_thread_seconds() - start; /* the construction's and the proof's */
    cli_json_add(s, "seconds", seconds);
    char summary[200];
    snprintf(summary, sizeof summary, "(H_1 of rank %ld on %ld regions, %ld symbols, h_top >= %.6f; %.2g s)", r.h1,
             r.regions, r.symbols, r.entropy, seconds);
    cJSON_AddStringToObject(s, "summary", summary);
    return s;
}
