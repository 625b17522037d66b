/* gb_expression — an expression of a body of one's own as a tree that can be bounded on intervals (internal).
 *
 * libmatheval evaluates a body's expression and differentiates it symbolically, but gives no tree to evaluate on
 * intervals (its printed form rounds constants to six digits, so bounding that would not bound the expression).
 * This module reads the user's text with libmatheval's grammar — numbers, the variables phi, theta, beta, the
 * constants pi and e, + − * / ^, unary minus, f(x) — with its precedences (^ left-associative and above unary
 * minus, unary minus above * and /), evaluates it at a point (gb_body checks that value against libmatheval's on
 * every grid point, so the tree bounded is the expression run), and encloses it over a box of (phi, theta) with
 * gb_interval's outward-widened arithmetic.
 *
 * Functions: exp, log, sqrt, sin, cos, sinh, cosh, tanh, atan, asinh and erf are enclosed; abs, step, delta and
 * nandelta are not smooth and are named as such (a body's normal and curvature need derivatives); libmatheval's
 * other functions have no enclosure here and are named as such. */
#ifndef GB_EXPRESSION_H
#define GB_EXPRESSION_H

#include "gb_interval.h"

#include <stddef.h>

typedef struct gb_expression gb_expression;

/* What stands in the way of bounding an expression: */
typedef enum gb_expression_fault {
    GB_EXPRESSION_OK = 0,
    GB_EXPRESSION_SYNTAX = 1,      /* not read (libmatheval may read it; the message says where this reader stopped) */
    GB_EXPRESSION_NOT_SMOOTH = 2,  /* names abs, step, delta or nandelta */
    GB_EXPRESSION_NO_ENCLOSURE = 3 /* names a function without an interval enclosure here */
} gb_expression_fault;

/* Read `text`; *fault says why when NULL is returned, `detail` (of `cap` bytes) names the place or function. */
gb_expression *gb_expression_parse(const char *text, gb_expression_fault *fault, char *detail, size_t cap);
void gb_expression_free(gb_expression *e);

/* The value at a point, and an enclosure over a box (beta a point). */
double gb_expression_eval(const gb_expression *e, double phi, double theta, double beta);
gb_interval gb_expression_enclose(const gb_expression *e, gb_interval phi, gb_interval theta, double beta);

#endif
