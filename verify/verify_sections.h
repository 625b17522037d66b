/* One registration function per section file of the harness. */
#ifndef VERIFY_SECTIONS_H
#define VERIFY_SECTIONS_H

#include <CUnit/CUnit.h>

int verify_register_s0_verdicts(void);
int verify_register_s2_surface(void);
int verify_register_s2_massprops(void);
int verify_register_s2_shape(void);
int verify_register_s2_polyhedron(void);
int verify_register_s2_bodies(void);
int verify_register_s2_expression(void);
int verify_register_figures(void);
int verify_register_s4_contact(void);
int verify_register_s4_grid(void);
int verify_register_s4_certify(void);
int verify_register_s4_atlas(void);
int verify_register_s5_dynamics(void);
int verify_register_s5_references(void);
int verify_register_s5_impact(void);
int verify_register_s5_flight(void);
int verify_register_s5_friction_impact(void);
int verify_register_s5_friction(void);
int verify_register_s5_compliant(void);
int verify_register_s5_stepping(void);
int verify_register_s6_estimators(void);
int verify_register_s6_chaos(void);
int verify_register_s6_diagnostics(void);
int verify_register_s7_melnikov(void);
int verify_register_s7_tangle(void);
int verify_register_s7_proofs(void);
int verify_register_s7_proofs_body(void);
int verify_register_s7_proofs_jet(void);
int verify_register_s7_horseshoe(void);
int verify_register_s7_covering(void);
int verify_register_s7_returns(void);
int verify_register_s7_conley(void);
int verify_register_s7_manifold(void);
int verify_register_s8_scan(void);
int verify_register_s8_scan_runs(void);
int verify_register_s8_scan_atlas(void);
int verify_register_s8_ensembles(void);
int verify_register_siconos(void);
int verify_register_command(void);
int verify_register_python(void);
int verify_register_surface(void);
int verify_register_bad_input(void);
int verify_register_bad_input_bodies(void);
int verify_register_bad_input_processes(void);

/* Painlevé's launch of s5_friction.c (Gömböc I, β = 0.12, tilted 0.7 rad about x, ω = 0): the attitude R0, the
 * friction μ* beyond which the rigid law has no consistent normal force, the closed form's two terms (N = g / (d1 −
 * μ d2)) and the launch velocity (0.5 m/s, inertial axes). gb_ status. */
int verify_painleve_launch(double R0[9], double *mu_star, double *d1, double *d2, double v[3]);

/* Register `tests` (NULL-terminated) as one suite whose every test starts the row timer. */
typedef struct verify_test {
    const char *name;
    CU_TestFunc function;
    const char *establishes; /* optional: what holds when every row of the test passes (for the report) */
} verify_test;
int verify_register_suite(const char *name, const verify_test *tests);

#endif
