/* gb_proof_manifold_internal — what gb_proof_manifold.c gives gb_proof_manifold_cross.c: Krawczyk's operator in the
 * plane and P over a ball. Not installed, not exported. */
#ifndef GB_PROOF_MANIFOLD_INTERNAL_H
#define GB_PROOF_MANIFOLD_INTERNAL_H

#include "gb_proof_manifold.h"

#include <arb.h>
#include <arb_mat.h>

/* Krawczyk's operator K = m − C g + (I − C A)(X − m) for a zero of a map G of R² in the box X, g = G(m) at the
 * middle m (thin), A ⊇ DG(X), C the middle of A inverted in doubles: 1 when K ⊂ int X (exactly one zero in X, in K,
 * and every matrix of A regular: Krawczyk 1969, Neumaier 1990 Thm 5.1.7), −1 when K misses X in a coordinate (no zero
 * in X), 0 otherwise. K written to k. */
int gb_proof_krawczyk2(arb_srcptr X, arb_srcptr m, arb_srcptr g, const arb_mat_t A, arb_ptr k, slong prec);

/* P over the ball S in mean value form P(s_c) + P'(S)(S − s_c), met with the plain enclosure; P'(S) in d (2 balls
 * each). GB_ENUMERIC when not finite. */
int gb_proof_manifold_ball(const gb_proof_manifold *m, const arb_t S, arb_ptr z, arb_ptr d);

/* P (and P' into d unless d is NULL) over the ball S by the plain enclosure alone: for thin S, where the mean value
 * form adds nothing. GB_ENUMERIC when not finite. */
int gb_proof_manifold_point(const gb_proof_manifold *m, const arb_t S, arb_ptr z, arb_ptr d);

/* gb_proof_manifold_crossings for several arcs of R against one arc of P (defs[k].s and the widths the same), the
 * pieces of P's arc made once; out[k] for defs[k]. R's arc k is t_origin[k] + defs[k].t (t_origin NULL: 0), and its
 * crossings' t are relative to t_origin[k] too: far along R the parameter's doubles cannot tell near crossings apart,
 * its offset from a nearby origin can. The arcs run on up to `threads` threads (gb_proof_for_each), the results the
 * same; *worker_seconds (NULL: not wanted) the CPU time of those threads, 0 when the caller's ran the arcs. */
int gb_proof_manifold_crossings_arcs(const gb_proof_manifold *p, const gb_proof_manifold *r,
                                     const gb_proof_manifold_crossings_def *defs, const double *t_origin, size_t count,
                                     int threads, gb_proof_manifold_crossings_result *out, double *worker_seconds);

/* Arb's bits the manifold was made with. */
long gb_proof_manifold_precision(const gb_proof_manifold *m);

/* The map's coefficients as balls (gb_proof_flow_field_derivative gives Df from them). */
const struct field_balls *gb_proof_manifold_field(const gb_proof_manifold *m);

#endif
