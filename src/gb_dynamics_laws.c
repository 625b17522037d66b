/* gb_dynamics_laws — the contact laws, as a table of what each one does (gb_dynamics.h): the one file that tells
 * one law from another. A law of its own (one smooth mode, as the compliant law) is one file holding its row, mode
 * and keys, named here; a law that adds to the hybrid system is a row here with the modes and jumps it adds. The
 * scene table reads every law's keys from its row; the docs give each its page. */
#include "gb_dynamics_internal.h"

#include "gb_error.h"

#include <math.h>

/* The scene's contact_law names; a unilateral contact on a plane of finite friction is Coulomb's law, a row of its
 * own. */
static const char *const law_names[] = {[GB_CONTACT_LAW_HELD] = "held", [GB_CONTACT_LAW_UNILATERAL] = "unilateral",
                                        [GB_CONTACT_LAW_COMPLIANT] = "compliant"};
enum { LAW_COUNT = sizeof law_names / sizeof law_names[0] };

/* The traits in gb_dynamics_law's order: impacts, translates, pivots, several events per step, slips, free centroid,
 * needs friction, pushes every vertex, time steps; then its impact map (gb_dynamics_jumps.c: what a change of contact
 * does), the law's own mode and keys (none: the hybrid system's). The compliant
 * law's row is its own file's (gb_dynamics_compliant.c). */
static const gb_dynamics_law held = {"held", GB_CONTACT_LAW_HELD, 0, 0, 0, 0, 0, 0, 0, 0, 0, &gb_dyn_held_impacts,
                                     NULL, NULL, 0};
static const gb_dynamics_law unilateral_rough = {"unilateral", GB_CONTACT_LAW_UNILATERAL, 1, 1, 1, 1, 0, 0, 0, 0, 0,
                                                 &gb_dyn_rough_impacts, NULL, NULL, 0};
static const gb_dynamics_law unilateral_coulomb = {"unilateral with Coulomb friction", GB_CONTACT_LAW_UNILATERAL, 1, 1, 1, 1, 1, 1,
                                                   0, 0, 1, &gb_dyn_coulomb_impacts, NULL, NULL, 0};
/* Every law with keys of its own, in the order their keys are listed (NULL ends the list). */
static const gb_dynamics_law *const keyed[] = {&gb_dyn_compliant_law, NULL};

const char *gb_dynamics_contact_law_name(gb_contact_law l) { return (unsigned)l < LAW_COUNT ? law_names[l] : NULL; }

int gb_dynamics_contact_law_parse(const char *name, gb_contact_law *law)
{
    int k = 0;
    const int status = gb_error_parse_name(name, law_names, LAW_COUNT, "contact law", &k);
    if (!status) *law = (gb_contact_law)k;
    return status;
}

const gb_dynamics_law *gb_dynamics_law_of(gb_contact_law contact_law, double friction)
{
    const int rough = !isfinite(friction);
    if (contact_law == GB_CONTACT_LAW_HELD) return rough ? &held : NULL; /* a held contact never slips */
    if (contact_law == GB_CONTACT_LAW_UNILATERAL) return rough ? &unilateral_rough : &unilateral_coulomb;
    if (contact_law == GB_CONTACT_LAW_COMPLIANT) return &gb_dyn_compliant_law; /* needs a finite μ (gb_dyn_law_check) */
    return NULL;
}

size_t gb_dynamics_law_key_count(void)
{
    size_t n = 0;
    for (size_t l = 0; keyed[l]; l++) n += keyed[l]->key_count;
    return n;
}

const gb_dynamics_law_key *gb_dynamics_law_key_at(size_t i, const gb_dynamics_law **law)
{
    for (size_t l = 0; keyed[l]; l++) {
        if (i < keyed[l]->key_count) {
            if (law) *law = keyed[l];
            return &keyed[l]->keys[i];
        }
        i -= keyed[l]->key_count;
    }
    return NULL;
}

int gb_dyn_law_check(const gb_dynamics_def *def)
{
    const gb_dynamics_law *law = gb_dynamics_law_of(def->contact_law, def->friction);
    for (size_t k = 0; law && k < law->key_count; k++) {
        const gb_dynamics_law_key *key = &law->keys[k];
        const double x = def->law_coefficients[key->slot];
        if (!isnan(x) && !((key->open_min ? x > key->min : x >= key->min) && x <= key->max))
            return gb_error_set(GB_EDOM, "%s = %g is out of range (allowed: %.15g %s %s <= %.15g %s)", key->name, x,
                                key->min, key->open_min ? "<" : "<=", key->name, key->max, key->meaning);
    }
    if (law && law->needs_friction && !isfinite(def->friction))
        return gb_error_set(GB_EINVAL, "friction mu = %g with the %s law (allowed: a finite mu: its friction is Coulomb's, "
                            "regularised)", def->friction, law->name);
    if (!law && def->contact_law == GB_CONTACT_LAW_HELD) /* a held contact never slips: its plane is rough */
        return gb_error_set(GB_EINVAL, "friction mu = %g with the held law (allowed: a finite mu with the unilateral law; "
                            "rough with either)", def->friction);
    if (law && !law->impacts && def->restitution != 0.0)
        return gb_error_set(GB_EINVAL, "restitution e = %g with the %s law, which has no impacts (allowed: e = 0; Newton's e "
                            "with the unilateral law)", def->restitution, law->name);
    if (law && !law->translates &&
        (def->height0 != 0.0 || def->velocity0[0] != 0.0 || def->velocity0[1] != 0.0 || def->velocity0[2] != 0.0))
        return gb_error_set(GB_EINVAL, "an initial height and an initial velocity need a law under which the body leaves "
                            "the plane (allowed with %s: height 0, velocity 0)", law->name);
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
