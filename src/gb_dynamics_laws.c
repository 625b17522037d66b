/* gb_dynamics_laws — the contact laws, as a table of what each one does (gb_dynamics_internal.h): the one
 * file that tells one law from another. A new law is a row here, the modes and jumps it adds, a key of the
 * scene table (gb_case) and its pages in the docs. */
#include "gb_dynamics_internal.h"

#include "gb_error.h"

#include <math.h>

static const gb_dyn_law laws[] = {
    [GB_CONTACT_LAW_HELD] = {"held", 0},
    [GB_CONTACT_LAW_UNILATERAL] = {"unilateral", 1},
};
enum { LAW_COUNT = sizeof laws / sizeof laws[0] };

const char *gb_dynamics_contact_law_name(gb_contact_law l) { return (unsigned)l < LAW_COUNT ? laws[l].name : NULL; }

int gb_dynamics_contact_law_parse(const char *name, gb_contact_law *law)
{
    const char *names[LAW_COUNT];
    for (int k = 0; k < LAW_COUNT; k++) names[k] = laws[k].name;
    int k = 0;
    const int status = gb_error_parse_name(name, names, LAW_COUNT, "contact law", &k);
    if (!status) *law = (gb_contact_law)k;
    return status;
}

const gb_dyn_law *gb_dyn_law_of(gb_contact_law law) { return (unsigned)law < LAW_COUNT ? &laws[law] : NULL; }

int gb_dynamics_contact_law_impacts(gb_contact_law law) { return (unsigned)law < LAW_COUNT && laws[law].impacts; }

int gb_dyn_law_check(const gb_dynamics_def *def)
{
    const gb_dyn_law *law = gb_dyn_law_of(def->contact_law);
    if (isfinite(def->friction) && law && !law->impacts) /* a held contact never slips: its plane is rough */
        return gb_error_set(GB_EINVAL, "friction mu = %g with the held law (allowed: a finite mu with the unilateral law; "
                            "rough with either)", def->friction);
    if (law && !law->impacts &&
        (def->restitution != 0.0 || def->height0 != 0.0 || def->velocity0[0] != 0.0 || def->velocity0[1] != 0.0 ||
         def->velocity0[2] != 0.0))
        return gb_error_set(GB_EINVAL, "restitution, an initial height and an initial velocity need the unilateral "
                            "law (allowed with held: e = 0, height 0, velocity 0)");
    /* With impacts a grid body is a polyhedron pivoting about a vertex between impacts: ṙ_c = 0, where eq 44 and
     * the rolling equation are the same equation. Continuous contact moves the contact along the surface,
     * where only the rolling equation conserves energy (docs/rolling.md). */
    if (!law || (law->impacts && def->contact == GB_CONTACT_MODEL_CONTINUOUS && def->variant != GB_VARIANT_ROLLING))
        return gb_error_set(GB_EINVAL, "contact law %d with contact model %s and equation %s (allowed: held with any; "
                            "unilateral with a grid model and either equation, or with continuous contact and the "
                            "rolling equation)", (int)def->contact_law, gb_contact_model_name(def->contact),
                            gb_dynamics_variant_name(def->variant));
    return GB_OK;
}
