#include "gb_proof_body_boxes.h"

gb_interval gb_proof_body_dot(const gb_interval a[3], const gb_interval b[3])
{
    gb_interval s = gb_interval_mul(a[0], b[0]);
    s = gb_interval_add(s, gb_interval_mul(a[1], b[1]));
    return gb_interval_add(s, gb_interval_mul(a[2], b[2]));
}

void gb_proof_body_directions(const gb_proof_axes *axes, double q_lo, double q_hi, gb_interval v[3], gb_interval dv[3])
{
    const gb_interval Q = gb_interval_make(q_lo, q_hi), c = gb_interval_cos(Q), s = gb_interval_sin(Q);
    for (int k = 0; k < 3; k++) {
        const gb_interval s0 = gb_interval_point(axes->s0[k]);
        v[k] = gb_interval_sub(gb_interval_mul(c, s0), gb_interval_mul(s, axes->e[k]));
        dv[k] = gb_interval_neg(gb_interval_add(gb_interval_mul(s, s0), gb_interval_mul(c, axes->e[k])));
    }
}

