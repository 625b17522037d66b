/* gb_dynamics_stepping_minima — a smooth body's points under time-stepping (docs/stepping.md): the local minima of its
 * height function, tracked from step to step by Newton, the lowest certified global (gb_certify, the atlas), the one a
 * step ahead followed from now. */
#include "gb_dynamics_stepper_internal.h"

#include "gb_error.h"
#include "gb_vec.h"

/* A smooth body's minimum p takes a slot: a free one (the search starting after the last taken, so that a slot just
 * freed, whose node the last step may name, is taken last), else the highest of the minima other than `keep`. */
int gb_dyn_stepping_take_slot(gb_dyn_stepper *s, const gb_contact_point *p, int keep)
{
    int k = -1;
    for (size_t j = 0; j < GB_DYNAMICS_STEPPING_SLOTS && k < 0; j++) {
        const size_t i = (s->next_slot + j) % GB_DYNAMICS_STEPPING_SLOTS;
        if (!s->active[i]) k = (int)i;
    }
    for (int i = 0; k < 0 && i < GB_DYNAMICS_STEPPING_SLOTS; i++) /* all taken: the highest but `keep` gives way */
        if (i != keep && (k < 0 || s->slot[i].height > s->slot[k].height)) k = i;
    s->slot[k] = *p;
    s->active[k] = 1;
    s->next_slot = (size_t)(k + 1) % GB_DYNAMICS_STEPPING_SLOTS;
    return k;
}

/* A smooth body's minima at vertical zb: each tracked one continued by Newton (dropped where it is no longer a
 * minimum, or meets another), the lowest proved global or replaced by the lower one the certificate finds (as the
 * event-driven contact is, gb_dyn_competitor), those other than the global one dropped when they are far above the
 * plane; none tracked (the start): the global minimum from scratch. The lowest's slot in *global. */
int gb_dyn_stepping_track_minima(gb_dynamics *d, gb_dyn_stepper *s, const double y[GB_STATE_SIZE], const double zb[3],
                                 int *global)
{
    int status = GB_OK, low = -1;
    for (int k = 0; k < GB_DYNAMICS_STEPPING_SLOTS && !status; k++) {
        if (!s->active[k]) continue;
        gb_contact_point p;
        status = gb_contact_refine(&d->surface, zb, s->slot[k].phi, s->slot[k].theta, &d->refine, &p);
        if (status == GB_ENOCONV || (!status && !p.is_minimum)) { /* the branch ended in a fold */
            s->active[k] = 0;
            status = GB_OK;
            continue;
        }
        if (status) break;
        s->slot[k] = p;
        for (int j = 0; j < k && s->active[k]; j++)
            if (s->active[j] && gb_dyn_same_point(&s->slot[j], &p)) s->active[k] = 0; /* two branches met */
        if (s->active[k] && (low < 0 || p.height < s->slot[low].height)) low = k;
    }
    if (status) return status;
    if (low < 0) {
        gb_contact_point p;
        status = gb_dyn_global_minimum(d, zb, &p);
        if (status) return status;
        low = gb_dyn_stepping_take_slot(s, &p, -1);
    }
    for (int round = 0; round < 16; round++) {
        gb_certify_result r;
        status = gb_dyn_check_global(d, zb, &s->slot[low], &r);
        if (status) return status;
        if (r.verdict != GB_CERTIFY_LOWER_FOUND) break;
        int same = -1;
        for (int j = 0; j < GB_DYNAMICS_STEPPING_SLOTS && same < 0; j++)
            if (s->active[j] && gb_dyn_same_point(&s->slot[j], &r.lower)) same = j;
        if (same >= 0 && s->slot[same].height < s->slot[low].height) s->slot[same] = r.lower, low = same;
        else if (same < 0) low = gb_dyn_stepping_take_slot(s, &r.lower, low);
        else break;
    }
    /* a step ahead (the vertical turned by ω h, ż_b = z_b × ω in body axes): the minimum that will be the lowest then is
     * followed from now, so that it enters the step that brings it to the plane at its gap, not a step's approach below */
    const double *w = y + GB_STATE_OMEGA;
    double ahead[3], turn[3];
    gb_vec_cross(zb, w, turn);
    for (int k = 0; k < 3; k++) ahead[k] = zb[k] + s->h * turn[k];
    const double size = gb_vec_norm(ahead);
    for (int k = 0; k < 3; k++) ahead[k] /= size;
    gb_certify_result r;
    status = s->h > 0.0 && gb_vec_norm(turn) > 0.0 ? gb_dyn_check_global(d, ahead, &s->slot[low], &r) : GB_OK;
    if (status) return status;
    if (s->h > 0.0 && gb_vec_norm(turn) > 0.0 && r.verdict == GB_CERTIFY_LOWER_FOUND) {
        gb_contact_point p;
        status = gb_contact_refine(&d->surface, zb, r.lower.phi, r.lower.theta, &d->refine, &p);
        int known = status != GB_OK || !p.is_minimum; /* born within the step: the next step meets it */
        for (int j = 0; j < GB_DYNAMICS_STEPPING_SLOTS && !known; j++) known = s->active[j] && gb_dyn_same_point(&s->slot[j], &p);
        if (!known) gb_dyn_stepping_take_slot(s, &p, low);
        if (status == GB_ENOCONV) gb_error_clear();
        else if (status) return status;
    }
    const double far = GB_DYNAMICS_STEPPING_KEEP * d->mean_radius, l = d->def.length, zeta = y[GB_STATE_ZETA];
    for (int k = 0; k < GB_DYNAMICS_STEPPING_SLOTS; k++)
        if (s->active[k] && k != low && zeta + l * s->slot[k].height > far) s->active[k] = 0;
    *global = low;
    return GB_OK;
}

