/* gb_body — bodies of one's own: a convex polyhedron from a mesh file ([body] mesh), or a smooth star-shaped
 * body given by an expression for r or for χ in φ, θ and β ([body] r, [body] chi).
 *
 * Each is a gb_morphology row made at run time, so that every module that takes a gb_surface takes it: the
 * grid contact models (a polyhedron's nodes are its hull's vertices), the mass properties, the dynamics and
 * its caches (which tell bodies apart by their row). The rows are interned: the same mesh bytes, or the same
 * expression, give the same row, kept until gb_body_release (a scan reads its scene once a point, and a
 * row it made once serves every point).
 *
 * A polyhedron: the convex hull of the file's vertices (gb_polyhedron: a non-convex or flat mesh is refused),
 * translated so that its centroid is the origin (the dynamics take body points relative to the centroid);
 * its mass properties in closed form (the divergence theorem), its length L (eq 53's role: the Lyapunov
 * scale, the body-length tolerances) the radius of the sphere of its volume, (3V/4π)^(1/3).
 *
 * An expression: parsed by GNU libmatheval (its derivatives symbolic), the names φ, θ, β written phi, theta,
 * beta, and pi, e; r = EXPR is the radius of eq 12 itself (the kernel S = r⁴), chi = EXPR the phase of eq 11
 * (S = 1 + 4β sinφ cos χ). The body is checked on a 180 × 360 grid of directions and the poles: every value
 * finite, r > 0, one value at each pole and r periodic in θ; between those directions r (for chi, r⁴) is bounded
 * above 0 on intervals (gb_expression: the user's text read again as a tree, its value checked against
 * libmatheval's at every grid point), and a function that is not smooth (abs, step, delta) is refused. A body that
 * fails is refused. The body is then moved to its centroid: r is measured from the chart's origin, and positions
 * are taken from the centroid (gb_morphology.origin, GB_BODY_CENTRED). Such a body has no certificate (kernel_jet
 * NULL), and only the grid contact models run it. libmatheval keeps its variables in the evaluator: every evaluation holds one lock. */
#ifndef GB_BODY_H
#define GB_BODY_H

#include "gb_export.h"
#include "gb_surface.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A body given by an expression whose centroid lies farther than this, times its size, from its chart's origin is
 * moved to its centroid (gb_morphology.origin); nearer, the centroid is the origin to what the dynamics resolve. */
#define GB_BODY_CENTRED 1e-12

typedef enum gb_body_expression_kind { GB_BODY_RADIUS = 0, GB_BODY_PHASE = 1 } gb_body_expression_kind;

/* The polyhedron of the mesh file at `path` as a body (beta 0). GB_EIO when unreadable; GB_EINVAL naming
 * the file, the line and what is wrong (gb_mesh, gb_polyhedron). */
GB_API int gb_body_mesh(const char *path, gb_surface *out);
/* The body of `text` (r or χ, by kind) at β = beta. GB_EINVAL when it does not parse or names an unknown
 * variable; GB_EDOM when it is not finite, makes r ≤ 0, or is not one surface (poles, period in θ): the
 * message names the expression and the direction where it fails. */
GB_API int gb_body_expression(gb_body_expression_kind kind, const char *text, double beta, gb_surface *out);
/* Is `surface` a body of one's own (mesh or expression)? */
GB_API int gb_body_is_own(const gb_surface *surface);
/* Does the expression of a body of one's own name beta? (0 for a mesh and the paper's bodies) */
GB_API int gb_body_names_beta(const gb_surface *surface);
/* The polyhedron's hull (vertices about the centroid), or NULL for a smooth body. */
GB_API const struct gb_polyhedron *gb_body_polyhedron(const gb_surface *surface);
/* Free every row made; no surface made before may be used after. */
GB_API void gb_body_release(void);

#ifdef __cplusplus
}
#endif

#endif
