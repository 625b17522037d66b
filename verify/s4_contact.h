/* What §4's contact checks share (verify/s4_contact.c, s4_grid.c): the bodies and the sample of verticals. A
 * uniformly random attitude gives a uniformly random vertical z_b (eq 28), so the checks draw z_b directly: 10⁴
 * directions from GSL's mt19937 seeded with 20261122 (gsl_ran_dir_3d), the same for each body and β. */
#ifndef S4_CONTACT_H
#define S4_CONTACT_H

#include <stddef.h>

enum { SAMPLE_SIZE = 10000, CASE_COUNT = 4 };
typedef struct s4_case {
    const char *morphology;
    double beta;
} s4_case;
/* Gömböc I and II at β = 0.12 (Table 1's) and 0.02 (strictly convex) */
extern const s4_case s4_cases[CASE_COUNT];
/* the sample's verticals, drawn by s4_draw_sample (once) */
extern double s4_sample_zb[SAMPLE_SIZE][3];
void s4_draw_sample(void);
/* "morphology M, beta B" of case c */
void s4_case_label(int c, char *out, size_t size);
double s4_distance(const double a[3], const double b[3]);

#endif
