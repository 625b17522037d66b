/* What the friction checks share (verify/s5_friction.c, s5_friction_impact.c): the plane's normal, small vector
 * algebra, and the kinetic energy computed apart from the library's. */
#ifndef S5_FRICTION_H
#define S5_FRICTION_H

#include "gb_impact.h"

#include <math.h>

static const double UP[3] = {0.0, 0.0, 1.0};

static inline void cross(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1], out[1] = a[2] * b[0] - a[0] * b[2], out[2] = a[0] * b[1] - a[1] * b[0];
}

static inline double dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline double norm(const double a[3]) { return sqrt(dot(a, a)); }

/* The kinetic energy, apart from the library's. */
static inline double energy(const gb_impact_body *b, const double v[3], const double w[3])
{
    double spin = 0.0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) spin += w[i] * b->inertia[i][j] * w[j];
    return 0.5 * b->mass * dot(v, v) + 0.5 * spin;
}

#endif
