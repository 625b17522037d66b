/* gb_proof_flow_internal — what the rigorous integrator's two files share (gb_proof_flow.c: the field, the Taylor step
 * and the C⁰ Lohner update; gb_proof_section.c: the crossings of a plane), and what gb_proof_cover.c and
 * gb_proof_returns.c take from them. Not installed, not exported. */
#ifndef GB_PROOF_FLOW_INTERNAL_H
#define GB_PROOF_FLOW_INTERNAL_H

#include "gb_proof_flow.h"
#include "gb_proof_flow_term_internal.h"

#include <arb.h>
#include <arb_mat.h>

enum { NMAX = GB_PROOF_FIELD_DIMENSION_MAX };
_Static_assert((int)NMAX == (int)GB_PROOF_TERM_DIMENSION_MAX, "the term holds the field's dimensions");

/* The field's coefficients as balls, and which quadratic terms are present. */
typedef struct field_balls {
    int n, order;
    slong prec;
    arb_struct c[NMAX], L[NMAX][NMAX], Q[NMAX][NMAX][NMAX];
    int has_Q[NMAX][NMAX][NMAX], pair_used[NMAX][NMAX];
    field_term term; /* the one non-polynomial term, if any (gb_proof_flow_term_internal.h) */
} field_balls;

/* The set x̂ + A r. */
typedef struct lohner_set {
    arb_struct x[NMAX], r[NMAX];
    arb_mat_t A;
} lohner_set;

/* One step's data: the Taylor coefficients at x̂ (with the remainder's coefficient over B in place p + 1), the
 * variational coefficients over the hull, the hull, B and A r. */
typedef struct step_data {
    int order;
    arb_ptr centre; /* n (order + 2): x_0 … x_p at x̂, then x_{p+1} over B */
    arb_ptr V;      /* (order + 1) n² over the hull */
    arb_struct B[NMAX], Ar[NMAX], hull[NMAX];
    int c1;         /* 1: Vrem is prepared too */
    arb_ptr Vrem;   /* n²: the variational coefficient p + 1 over B and the a-priori enclosure W of DΦ over the step */
} step_data;

/* The state of one integration: the field's balls, the set, a step's data and scratch for the step length. */
typedef struct integration {
    field_balls F;
    lohner_set S;
    step_data D;
    arb_ptr scratch;
} integration;

/* The field's coefficients as balls at prec (order: the Taylor order the balls serve), and their release. */
void gb_proof_flow_field_init(field_balls *F, const gb_proof_field *f, int order, slong prec);
void gb_proof_flow_field_clear(field_balls *F);
/* The new frame: Q of the QR factorisation (Gram–Schmidt in doubles, taken exact) of mid(M) with the columns ordered
 * by |column| times the width of r along it (r NULL: by |column|), the widest first. */
void gb_proof_flow_new_frame(int n, const arb_mat_t M, arb_srcptr r, arb_mat_t Q);
/* Df over the box x (n × n). */
void gb_proof_flow_field_derivative(const field_balls *F, arb_srcptr x, arb_mat_t J);
/* DΦ over the prepared step at every time of the ball t ⊆ [0, h] and every point of the set: the Taylor part over the
 * hull, plus t^(p+1) Vrem when the step was prepared with c1 (else the Taylor part alone: the mean value form's). */
void gb_proof_flow_derivative_at(const field_balls *F, const step_data *D, const arb_t t, arb_mat_t out);
/* f(x) over the box x. */
void gb_proof_flow_field_eval(const field_balls *F, arb_srcptr x, arb_ptr out);
/* The box x̂ + A r. */
void gb_proof_flow_set_hull(const field_balls *F, const lohner_set *S, arb_ptr out);
/* Every solution from the set at every time of the ball t ⊆ [0, h] of the prepared step: a box. */
void gb_proof_flow_enclose_at(const field_balls *F, const step_data *D, const arb_t t, arb_ptr out);
/* Ends the prepared step of length h: S becomes the set at time h. 0 when the new frame cannot be inverted. */
int gb_proof_flow_step_finish(const field_balls *F, lohner_set *S, const step_data *D, double h);
/* Prepares one step from S at time t_now, at most h_cap long (multiples of 2^-30), halved until Picard's test holds. */
int gb_proof_flow_step_take(const field_balls *F, lohner_set *S, step_data *D, const gb_proof_flow_def *def,
                            double h_cap, arb_ptr scratch, double *h_taken, const arb_t t_now);
/* gb_proof_flow_time for the caller's field F (its term too) under def's order, step and time limits (def->field only
 * names the dimension): every solution from the box at time t_end. */
int gb_proof_flow_time_of(const field_balls *F, const gb_proof_flow_def *def, const gb_proof_interval *box,
                          double t_end, gb_proof_interval *image);
/* gb_proof_flow_section_map for the caller's field F (its term too): def's field only names the dimension. The box may
 * also lie wholly off the plane: the first crossing in the stated direction is then crossing 1. */
int gb_proof_flow_section_map_of(const field_balls *F, const gb_proof_flow_def *def, const gb_proof_interval *box,
                                 gb_proof_flow_crossing *out);
/* The integration of the box's set under the caller's field F (A = I, x̂ the box's middle; F borrowed: the release
 * leaves it alone). */
void gb_proof_flow_integration_borrow(integration *I, const field_balls *F, const gb_proof_interval *box);
void gb_proof_flow_integration_release(integration *I);
/* The definition's and the box's ranges (GB_EDOM naming the one out of range). */
int gb_proof_flow_check(const gb_proof_flow_def *def, const gb_proof_interval *box);
/* The definition's ranges alone. */
int gb_proof_flow_def_check(const gb_proof_flow_def *def);
/* f^k of the box x (2 balls) for a quadratic map of the plane, in affine form (the C⁰ Lohner algorithm for maps,
 * gb_proof_cover.c; gb_proof_returns.c uses it too): 0 when the enclosure is not finite. */
int gb_proof_affine_image(const field_balls *F, arb_ptr x, int iterates);
/* f(x) over the box of balls x, the field's formula read as a map (gb_proof_cover.c: Hénon's). */
void gb_proof_field_image(const gb_proof_field *field, arb_srcptr x, arb_ptr out, slong prec);

#endif
