/* The Melnikov oracles' analytic models (verify/s7_melnikov.c, verify/s7_proofs.c): the pendulum U = cos q (its
 * rotation orbit over the saddle q = 0), Duffing's U = −q²/2 + q⁴/4 (the right loop), and the pendulum with a mass
 * that varies along the orbit and an odd coupling. */
#ifndef S7_MODELS_H
#define S7_MODELS_H

#include "gb_melnikov.h"

#include <math.h>

static inline int pendulum(void *c, double q, gb_melnikov_values *v)
{
    (void)c;
    *v = (gb_melnikov_values){1.0, 0.0, cos(q), -sin(q), 1.0};
    return 0;
}

static inline int duffing(void *c, double q, gb_melnikov_values *v)
{
    (void)c;
    *v = (gb_melnikov_values){1.0, 0.0, -q * q / 2 + q * q * q * q / 4, -q + q * q * q, 1.0};
    return 0;
}

/* The pendulum with a mass that varies along the orbit and an odd coupling: no closed form, but even M
 * and odd S about q = π make every cosine integral vanish. */
static inline int varying(void *c, double q, gb_melnikov_values *v)
{
    (void)c;
    *v = (gb_melnikov_values){1.0 + 0.3 * cos(q), -0.3 * sin(q), cos(q), -sin(q), sin(q)};
    return 0;
}

static const gb_melnikov_model PENDULUM = {pendulum, NULL, -0.5, 0.5, 1, 2 * M_PI, 0.0, NAN, NULL, 0};
static const gb_melnikov_model DUFFING = {duffing, NULL, -0.5, 0.5, 1, 0.0, 3.0, NAN, NULL, 0};
static const gb_melnikov_model VARYING = {varying, NULL, -0.5, 0.5, 1, 2 * M_PI, 0.0, NAN, NULL, 0};

#endif
