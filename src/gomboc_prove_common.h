/* What the proof commands (gomboc_prove.c, gomboc_prove_body.c, gomboc_prove_chain.c, gomboc_prove_conley.c,
 * gomboc_prove_manifold.c) share, defined in
 * gomboc_prove_common.c: Table 1's rolling forcing, written once, and the JSON of an enclosure, a hypothesis and a
 * Gömböc statement's data. Internal to gomboc-prove. */
#ifndef GOMBOC_PROVE_COMMON_H
#define GOMBOC_PROVE_COMMON_H

#include "gb_proof.h"

#include <cJSON.h>

/* Table 1's rolling scenes (cases/table1-gomboc-I-rolling.ini, -II-rolling.ini; verify/s7_proofs_body.c checks that the
 * statements' data are the files' values): β, m, g [m/s²], c, A₁, A₂ [m/s²], ω [1/s]; ψ = π/3 is enclosed where used. */
typedef struct prove_table1 {
    double beta, mass, g, damping, A1, A2, omega;
} prove_table1;
extern const prove_table1 prove_rolling;

/* [lo, hi] as a JSON pair. */
cJSON *prove_json_interval(gb_proof_interval x);
/* Appends {"hypothesis": text, "status": status} to list. */
void prove_add_hypothesis(cJSON *list, const char *text, const char *status);
/* "proved" or "not proved". */
const char *prove_status(int holds);
/* This thread's CPU seconds (gomboc prove runs another statement on a thread beside this one). */
double prove_thread_seconds(void);
/* Adds the statement's "data" object: the body's morphology, Table 1's rolling forcing and ψ's enclosure; returns it. */
cJSON *prove_rolling_data(cJSON *statement, const char *morphology, gb_proof_interval psi);

/* The statement by the discrete Conley index (gomboc_prove_conley.c): Hénon's map at a = 6 (classical 0) or the
 * classical one; NULL with *status set when a computation fails. */
cJSON *prove_conley_statement(long precision, int classical, int *proved, int *status);

/* The statement on the classical Hénon map's fixed point's manifolds and their crossings (gomboc_prove_manifold.c);
 * NULL with *status set when a computation fails. */
cJSON *prove_manifold_statement(long precision, int *proved, int *status);
struct gb_proof_manifold;
/* The classical Hénon map's fixed point's unstable (P) and stable (R) manifolds: order 30, σ = 1, ρ = 1 (NULL both on
 * failure, with the status). */
int prove_henon_manifolds(long precision, struct gb_proof_manifold **P, struct gb_proof_manifold **R);
/* The statement on the classical Hénon map's entropy by a trellis of those manifolds (gomboc_prove_trellis.c): the
 * small one (S = 3200, 46 stable arcs, about a minute) or the large one (S = 25 600, the arcs below), on up to
 * `threads` threads; NULL with *status set when a computation fails. */
cJSON *prove_trellis_statement(long precision, int large, int threads, int *proved, int *status);
/* The large trellis's stable arcs (gomboc_prove_trellis_arcs.c). */
extern const gb_proof_interval prove_trellis_large_arcs[];
extern const size_t prove_trellis_large_count;

#endif
