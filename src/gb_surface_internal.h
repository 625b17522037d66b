/* gb_surface_internal — interval enclosures of the surface over boxes of a chart, for the certificate
 * of the global contact (gb_certify) and its checks; internal to the library and the harness. */
#ifndef GB_SURFACE_INTERNAL_H
#define GB_SURFACE_INTERNAL_H

#include "gb_interval.h"
#include "gb_surface.h"

/* Intervals that hold x and its first and second chart derivatives at every point of the box
 * [a_lo, a_hi] × [b_lo, b_hi] (interval arithmetic with outward widening, see gb_interval.h; value and
 * tangents also by Taylor forms about the centre, met with the direct enclosure). `smooth` is 0 when the
 * box may hold a point where the surface is not C² (morphology I at ±e_z); the second-derivative
 * intervals then hold the Hessian wherever it exists (the surface is C¹,¹ there). */
typedef struct gb_surface_enclosure {
    gb_interval x[3], x_a[3], x_b[3], x_aa[3], x_ab[3], x_bb[3];
    /* At the box centre (a_c, b_c) = midpoints: x, x_a, x_b (narrow intervals), and the offsets of the
     * box from it, a − a_c ∈ da and b − b_c ∈ db. A caller that contracts x with a vector d first can
     * bound d·x over the box by the Taylor form d·x_c + (d·x_a,c) da + (d·x_b,c) db + ½ d·x''(da, db),
     * whose first-order term keeps the cancellation in d·x_a (small near a critical point). */
    gb_interval x_c[3], x_a_c[3], x_b_c[3];
    gb_interval da, db;
    int smooth;
} gb_surface_enclosure;

/* gb_surface_eval in two parts, for Newton's iterations (which need no normal until the last point):
 * everything but n and n̂, then n and n̂ from the tangents. */
void gb_surface_eval_jet(const gb_surface *surface, double phi, double theta, gb_surface_point *point);
void gb_surface_normal(gb_surface_point *point);

/* x and its first and second derivatives in the coordinates (a, b) of `chart` at one point, with u, r and the
 * point's (φ, θ); the fields named after φ and θ then hold the derivatives by a and b, and the kernel's
 * fields are left 0. Point intervals through the jets of gb_surface_enclose, each value the centre of its
 * enclosure (a few ulps). The contact's Newton uses it in the POLAR_X chart near the (φ, θ) poles. */
void gb_surface_eval_chart(const gb_surface *surface, gb_surface_chart chart, double a, double b, gb_surface_point *point);

void gb_surface_enclose(const gb_surface *surface, gb_surface_chart chart, double a_lo, double a_hi, double b_lo,
                        double b_hi, gb_surface_enclosure *out);

#endif
