/* gb_dynamics_ledger — what every change of contact leaves behind, whatever mode or jump made it: its record
 * (gb_dynamics_impact: points, ω and v before and after, impulses, energies), the ledger's counters and
 * the energy the impacts took (L), and the caller's sink (gb_dynamics_internal.h). */
#include "gb_dynamics_internal.h"
#include "gb_dynamics_protocol_internal.h"

#include "gb_error.h"
#include "gb_vec.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int gb_dyn_book(gb_dynamics *d, const gb_dynamics_impact *e)
{
    d->crease.settled += (size_t)e->settled;
    d->crease.lifts += e->kind == GB_DYNAMICS_IMPACT_LIFT;
    d->crease.third_points += e->kind == GB_DYNAMICS_IMPACT_THIRD;
    d->flight.lift_offs += e->kind == GB_DYNAMICS_IMPACT_LIFT_OFF;
    d->flight.landings += e->kind == GB_DYNAMICS_IMPACT_LANDING;
    d->flight.bounces += e->kind == GB_DYNAMICS_IMPACT_BOUNCE || (e->kind == GB_DYNAMICS_IMPACT_LANDING && e->rebound);
    d->flight.flying_on += e->kind == GB_DYNAMICS_IMPACT_LANDING && !e->rebound && e->contacts_after == 0;
    if (e->kind != GB_DYNAMICS_IMPACT_LIFT && e->kind != GB_DYNAMICS_IMPACT_LIFT_OFF && e->kind != GB_DYNAMICS_IMPACT_CREASE_END) {
        d->impacts++;
        d->impact_loss += e->kinetic_before - e->kinetic_after - e->potential_jump;
        d->impact_friction_max = fmax(d->impact_friction_max, e->friction_needed);
    }
    d->memo_valid = 0; /* ω may have changed */
    return gb_dyn_emit(d, e);
}

int gb_dyn_emit(gb_dynamics *d, const gb_dynamics_impact *e)
{
    if (!d->impact_sink) return GB_OK;
    if (!d->holding) return d->impact_sink(d->impact_context, e);
    if (d->held_count == d->held_capacity) {
        const size_t capacity = d->held_capacity ? 2 * d->held_capacity : 8;
        gb_dynamics_impact *held = realloc(d->held, capacity * sizeof *held);
        if (!held) return gb_error_set(GB_ENOMEM, "out of memory for %zu impact records", capacity);
        d->held = held, d->held_capacity = capacity;
    }
    d->held[d->held_count++] = *e;
    return GB_OK;
}

void gb_dynamics_hold_impacts(gb_dynamics *d, int hold)
{
    d->holding = hold;
}

int gb_dynamics_release_impacts(gb_dynamics *d, int keep)
{
    int status = GB_OK;
    for (size_t k = 0; keep && k < d->held_count && !status; k++) status = d->impact_sink(d->impact_context, &d->held[k]);
    d->held_count = 0;
    return status;
}

/* An impact record from its points and the solver's answer at the new point `k` and the old one `k_old`
 * (−1: none); ω in y takes its value after. */
void gb_dyn_record(gb_dynamics_impact *e, double y[GB_STATE_SIZE], const double old_point[3], const double new_point[3],
                   const double v_before[3], const gb_impact_result *r, int k, int k_old)
{
    double *omega = y + GB_STATE_OMEGA;
    memcpy(e->old_point, old_point, sizeof e->old_point);
    memcpy(e->new_point, new_point, sizeof e->new_point);
    memcpy(e->omega_before, omega, sizeof e->omega_before);
    memcpy(e->v_before, v_before, sizeof e->v_before);
    memcpy(omega, r->omega, sizeof r->omega);
    memcpy(e->omega_after, r->omega, sizeof e->omega_after);
    memcpy(e->v_after, r->v, sizeof e->v_after);
    e->normal_impulse = r->normal_impulse[k], e->tangential_impulse = r->tangential_impulse[k];
    e->old_normal_impulse = k_old >= 0 ? r->normal_impulse[k_old] : 0.0;
    e->friction_needed = r->friction_needed;
    e->kinetic_before = r->energy_before, e->kinetic_after = r->energy_after;
}

/* A change of contact with no impulse (a lift, a lift-off, the end of a crease), the body turning with the ω
 * of y about the point `about` [m]: the centroid's velocity v = ω × (G − P), and the impact's record of
 * nothing changed. */
void gb_dyn_no_impulse(const gb_dynamics *d, const double y[GB_STATE_SIZE], const double about[3], double v[3],
                       gb_impact_result *r)
{
    memset(r, 0, sizeof *r);
    memcpy(r->omega, y + GB_STATE_OMEGA, sizeof r->omega);
    gb_vec_cross(y + GB_STATE_OMEGA, (const double[3]){-about[0], -about[1], -about[2]}, v);
    memcpy(r->v, v, sizeof r->v);
    gb_impact_body body = {d->def.mass, {{0}}};
    memcpy(body.inertia, d->inertia, sizeof body.inertia);
    r->energy_before = r->energy_after = gb_impact_energy(&body, v, r->omega);
}
