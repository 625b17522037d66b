/* Maps and flows with known Lyapunov exponents, as gb_lyapunov systems (the estimator's oracles):
 *  logistic x → a x(1 − x);  Hénon (x, y) → (1 − a x² + y, b x);
 *  Lorenz ẋ = σ(y − x), ẏ = x(ρ − z) − y, ż = xy − βz;  Ueda ẍ + k ẋ + x³ = B cos t.
 * Flows are integrated with GSL rk8pd in fixed steps (`step`); tangent vectors with the exact Jacobian. */
#ifndef KNOWN_SYSTEMS_H
#define KNOWN_SYSTEMS_H

#include "gb_lyapunov.h"

#include <stddef.h>

/* Trajectory 0 (the reference) and 1 (the perturbed one); the first member of every system. */
typedef struct known_pair {
    size_t dimension;
    double x[2][3];
} known_pair;

typedef enum { KNOWN_LOGISTIC, KNOWN_HENON } known_map_kind;

typedef struct known_map {
    known_pair pair; /* dimension 1 (logistic) or 2 (Hénon) */
    known_map_kind kind;
    double a, b;
} known_map;

known_map known_logistic(double r, double x0);
known_map known_henon(double a, double b, double x0, double y0);
size_t known_map_dimension(const known_map *m);
gb_lyapunov_pair_system known_map_pair(const known_map *m);
gb_lyapunov_tangent_system known_map_tangent(const known_map *m);

typedef enum { KNOWN_LORENZ, KNOWN_UEDA } known_flow_kind;

typedef struct known_flow {
    known_pair pair; /* dimension 3 (Lorenz) or 2 (Ueda) */
    known_flow_kind kind;
    double sigma, rho, beta;   /* Lorenz */
    double damping, forcing;   /* Ueda */
    double step;               /* fixed rk8pd step */
    size_t vectors;            /* tangent vectors carried (internal) */
} known_flow;

/* step 0.005 (Lorenz), 2π/400 (Ueda) */
known_flow known_lorenz(double sigma, double rho, double beta, const double x0[3]);
known_flow known_ueda(double damping, double forcing, double x0, double v0);
size_t known_flow_dimension(const known_flow *f);
gb_lyapunov_pair_system known_flow_pair(const known_flow *f);
gb_lyapunov_tangent_system known_flow_tangent(const known_flow *f);

#endif
