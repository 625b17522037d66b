/* gb_proof_internal — what the proofs' files share: Arb's balls to and from intervals of doubles, the precision's
 * range, the CPU clock. Not exported. */
#ifndef GB_PROOF_INTERNAL_H
#define GB_PROOF_INTERNAL_H

#include "gb_proof.h"

#include <arb.h>

/* The ball x as an interval of doubles rounded outwards. */
gb_proof_interval gb_proof_interval_of(const arb_t x);

/* The interval [lo, hi] of doubles as a ball (exact endpoints). */
void gb_proof_ball_of(arb_t out, gb_proof_interval x, slong prec);

/* GB_EDOM naming the allowed range when precision is outside it. */
int gb_proof_check_precision(long precision);

/* CPU seconds of the process. */
double gb_proof_cpu_seconds(void);

#endif
