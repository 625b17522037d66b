/* gb_proof_body_boxes — what the Gömböcs' enclosure (gb_proof_body.c) and the proof of its piecewise structure
 * (gb_proof_body_ties.c) share: the surface's chart boxes with their enclosures, the rocking's axes and the directions
 * of an arc of q. Internal to the library. */
#ifndef GB_PROOF_BODY_BOXES_INTERNAL_H
#define GB_PROOF_BODY_BOXES_INTERNAL_H

#include "gb_proof_body.h"
#include "gb_surface_internal.h"

/* A box of a chart of the surface with its enclosure. */
typedef struct pbox {
    double a_lo, a_hi, b_lo, b_hi;
    int region;
    gb_surface_enclosure e;
} pbox;

typedef struct boxes {
    pbox *at;
    size_t n, cap;
} boxes;

/* The rocking: s₀ (the top's direction, a coordinate axis) and e (unit, ⊥ s₀) as intervals. */
typedef struct gb_proof_axes {
    double s0[3];
    gb_interval e[3];
} gb_proof_axes;

/* Σ a_k b_k, outwards. */
gb_interval gb_proof_body_dot(const gb_interval a[3], const gb_interval b[3]);

/* v(Q) = cos Q s₀ − sin Q e and v′(Q) = −sin Q s₀ − cos Q e over the arc [q_lo, q_hi]. */
void gb_proof_body_directions(const gb_proof_axes *axes, double q_lo, double q_hi, gb_interval v[3], gb_interval dv[3]);

/* H″ − (−H) = −gᵀ K⁻¹ g over the arc whose directions are v, v′, on its kept boxes: K = [x_ab·v] the chart Hessian of
 * x·v and g = (x_a·v′, x_b·v′). At the maximiser x* of x·v(q) the implicit function theorem gives x*′ = −J K⁻¹ g, so
 * H″ = x*·v″ + x*′·v′ = −H − gᵀ K⁻¹ g where the maximiser is unique and K definite. *out: the hull over the boxes;
 * returns 1 when every box is C² (gb_surface_enclosure.smooth) and its K proved negative definite (K_aa < 0 and
 * det K > 0 over it), else 0 (*out the line). */
int gb_proof_body_second(const boxes *kept, const gb_interval v[3], const gb_interval dv[3], gb_interval *out);

/* The boxes of the certificate's root cover, and their quarters split while wider than `size`, that may hold the
 * maximiser of x·v(q) for some q of [q_lo, q_hi] (the branch-and-bound of gb_proof_body_enclose's cells), and the
 * rocking's axes. *out is the caller's to free (out->at). GB_EDOM for a definition out of range. */
int gb_proof_body_arc_boxes(const gb_proof_body_def *def, double q_lo, double q_hi, double size, gb_proof_axes *axes,
                            boxes *out);

/* H's coefficients over an arc for one branch at a tie q_s (gb_proof_body_jet.c): the branch that is the maximiser
 * below q_s (above = 0) or above it, on an arc wholly on its side (its existence proved by Krawczyk's test where the
 * arc's structure still sees both contacts). GB_ENUMERIC for an arc reaching q_s. */
int gb_proof_body_jet_branch(const gb_proof_body_def *def, double q_lo, double q_hi, int order, double q_s, int above,
                             gb_proof_body_jet *out);

/* Both contacts' coefficients over a tie's arc (each proved over the whole arc by Krawczyk's test). */
int gb_proof_body_jet_components(const gb_proof_body_def *def, double q_lo, double q_hi, int order,
                                 gb_proof_body_jet out[2]);

#endif
