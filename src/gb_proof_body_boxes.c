#include "gb_proof_body_boxes_internal.h"

#include <math.h>

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


int gb_proof_body_second(const boxes *kept, const gb_interval v[3], const gb_interval dv[3], gb_interval *out)
{
    *out = (gb_interval){-INFINITY, INFINITY};
    for (size_t k = 0; k < kept->n; k++) {
        const gb_surface_enclosure *e = &kept->at[k].e;
        const gb_interval A = gb_proof_body_dot(e->x_aa, v), B = gb_proof_body_dot(e->x_ab, v), C = gb_proof_body_dot(e->x_bb, v);
        const gb_interval det = gb_interval_sub(gb_interval_mul(A, C), gb_interval_sqr(B));
        if (!(e->smooth && A.hi < 0.0 && det.lo > 0.0)) { /* not C² over the box (I at ±e_z), or not definite */
            *out = (gb_interval){-INFINITY, INFINITY};
            return 0;
        }
        const gb_interval ga = gb_proof_body_dot(e->x_a, dv), gb = gb_proof_body_dot(e->x_b, dv);
        /* gᵀ K⁻¹ g = (C g_a² − 2 B g_a g_b + A g_b²) / det K */
        const gb_interval num = gb_interval_add(gb_interval_sub(gb_interval_mul(C, gb_interval_sqr(ga)),
                                                                gb_interval_scale(2.0, gb_interval_mul(B, gb_interval_mul(ga, gb)))),
                                                gb_interval_mul(A, gb_interval_sqr(gb)));
        const gb_interval term = gb_interval_neg(gb_interval_mul(num, gb_interval_recip(det)));
        *out = k ? gb_interval_hull(*out, term) : term;
    }
    return kept->n > 0;
}
