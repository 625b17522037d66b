/* gb_dynamics_rest — the mode "at rest on three points": three points stop the body (ω = 0), and with the
 * vertical forcing alone it stays while its weight falls inside their triangle; it lifts off them all where
 * g_eff reaches 0 (gb_dynamics_events.c, gb_dynamics_jumps.c). */
#include "gb_dynamics_internal.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <string.h>

/* Nothing turns, whatever rounding is left in the state's ω. */
int gb_dyn_rest_field(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], const double omega[3], const double zb[3],
                      double geff, double omega_dot[3], double *zeta, gb_dyn_rates *rates)
{
    (void)y, (void)geff, (void)rates; /* at rest nothing moves: the rates stay 0 */
    gb_dyn_contact c;
    const int status = gb_dyn_contact_at(d, t, zb, omega, &c);
    if (status) return status;
    memset(omega_dot, 0, 3 * sizeof *omega_dot);
    *zeta = -gb_vec_dot(zb, c.rc);
    return GB_OK;
}

int gb_dyn_rest_accept(gb_dynamics *d, double t, double y[GB_STATE_SIZE])
{
    (void)y;
    if (gb_forcing_geff(&d->def.forcing, t) < 0.0)
        return gb_error_set(GB_ENUMERIC, "unilateral contact at t = %.9g: g_eff < 0 on three points, a lift-off that "
                            "the step's event location did not find", t);
    return GB_OK;
}

int gb_dyn_rest_observe(gb_dynamics *d, double t, const double y[GB_STATE_SIZE], gb_dynamics_observables *o)
{
    gb_dyn_contact c;
    const int status = gb_dyn_contact_at(d, t, o->zb, o->omega, &c); /* ω̇ = 0 */
    if (!status) gb_dyn_observe_on_plane(d, t, y, &c, 3, o);
    return status;
}

/* At rest: the height on the three points, and no velocity. */
void gb_dyn_rest_translate(const gb_dynamics *d, double t, double y[GB_STATE_SIZE])
{
    gb_dyn_translate_on_plane(d, t, y);
    memset(y + GB_STATE_VELOCITY, 0, 3 * sizeof *y);
}
