/* A program using libgomboc: the contact of Gömböc I (β = 0.12) for one vertical, then a scene integrated
 * to its end: the scene file named on the command line, or without one a scene written here (Table 1's
 * forcing, 20 periods), so that it runs from any directory.
 * Build: cc contact_and_scene.c $(pkg-config --cflags --libs gomboc) */
#include <gomboc.h>
#include <stdio.h>
#include <string.h>

static const char scene_text[] = "[body]\nmorphology = I\nbeta = 0.12\n"
                                 "[forcing]\nA1 = 2.0\nA2 = 1.0\nomega = 18\npsi = pi/3\n"
                                 "[model]\nequation = rolling\ncontact = continuous\ndamping = 0.02\n"
                                 "[integrator]\nmethod = rk4\nsteps_per_period = 160\nperiods = 20\nlocate_switches = yes\n";

int main(int argc, char **argv)
{
    gb_error_init_gsl();
    gb_surface body;
    gb_contact_grid *seeds = NULL;
    gb_contact_branches contact;
    const gb_contact_grid_def seed_grid = gb_contact_default_branch_grid();
    const gb_contact_refine_def refine = gb_contact_refine_default_def();
    const double zb[3] = {0.6, 0.6, -0.5}; /* the body-frame vertical */
    int status = gb_surface_init(&body, "I", 0.12);
    if (!status) status = gb_contact_grid_create(&body, &seed_grid, &seeds);
    if (!status) status = gb_contact_branches_find(seeds, zb, &refine, &contact);
    gb_contact_grid_free(seeds);
    if (status) return fprintf(stderr, "contact: %s\n", gb_error_message()), 1;
    printf("contact: phi* = %.12f, theta* = %.12f, h* = %.15f (%zu local minima)\n", contact.branch[0].phi,
           contact.branch[0].theta, contact.branch[0].height, contact.count);

    gb_case scene;
    gb_dynamics *dynamics = NULL;
    gb_integrate_stats stats;
    double y[GB_STATE_SIZE];
    status = argc > 1 ? gb_case_load(argv[1], &scene) : gb_case_load_text("built-in", scene_text, strlen(scene_text), &scene);
    if (!status) status = gb_dynamics_start(&scene.body, &scene.dynamics, scene.attitude, scene.omega0, &dynamics, y);
    if (!status) status = gb_integrate_run(dynamics, &scene.integrate, 0.0, y, NULL, NULL, &stats);
    gb_dynamics_free(dynamics);
    if (status) return fprintf(stderr, "scene: %s\n", gb_error_message()), status == GB_EINVAL || status == GB_EDOM ? 2 : 1;
    printf("scene:   %zu steps, omega(t_end) = (%.9f, %.9f, %.9f) rad/s\n", stats.steps, y[GB_STATE_OMEGA],
           y[GB_STATE_OMEGA + 1], y[GB_STATE_OMEGA + 2]);
    return 0;
}
