/* gb_scan_plan — the Melnikov margins of a scan's points (paper §7, eqs 91–93): the reduced models and
 * integrals the points need, planned and computed once for all of them (gb_scan_internal.h). */
#include "gb_scan_internal.h"

#include "gb_error.h"
#include "gb_melnikov_body.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* A reduced model: the key (what gb_melnikov_body_create reads) and what it yields. */
typedef struct melnikov_body {
    const gb_morphology *morphology;
    double beta, mass, g;
    int computed, status;       /* status GB_EDOM: not defined here (margins NAN) */
    gb_melnikov_body *body;
    gb_melnikov_model model;
    gb_melnikov_orbit orbit;
    double M_u;                 /* M(q_u): μ = c / M_u */
    gb_melnikov_tables *tables; /* its separatrix tabulated once for the planned ω */
} melnikov_body;

/* The integrals of one body at one ω. */
typedef struct melnikov_frequency {
    size_t body;
    double omega;
    int computed, status;
    gb_melnikov_integrals integrals;
} melnikov_frequency;

struct gb_scan_melnikov {
    melnikov_body *bodies;
    size_t n_bodies;
    melnikov_frequency *frequencies;
    size_t n_frequencies;
};

static int same_bits(double a, double b) { return !memcmp(&a, &b, sizeof a); }

static int body_matches(const melnikov_body *b, const gb_case *scene)
{
    return b->morphology == scene->body.morphology && same_bits(b->beta, scene->body.beta) &&
           same_bits(b->mass, scene->dynamics.mass) && same_bits(b->g, scene->dynamics.forcing.g);
}

/* Where the scene's body and ω sit in the plan (SIZE_MAX: not planned). */
static void plan_find(const gb_scan_melnikov *p, const gb_case *scene, size_t *body, size_t *frequency)
{
    *body = *frequency = SIZE_MAX;
    for (size_t k = 0; k < p->n_bodies && *body == SIZE_MAX; k++)
        if (body_matches(&p->bodies[k], scene)) *body = k;
    for (size_t k = 0; *body != SIZE_MAX && k < p->n_frequencies && *frequency == SIZE_MAX; k++)
        if (p->frequencies[k].body == *body && same_bits(p->frequencies[k].omega, scene->dynamics.forcing.omega))
            *frequency = k;
}

/* Add the scene's body and ω to the plan unless there (the reduced model needs g > 0). */
static int plan_add(gb_scan_melnikov *p, const gb_case *scene)
{
    if (!(scene->dynamics.forcing.g > 0.0)) return GB_OK;
    size_t b, f;
    plan_find(p, scene, &b, &f);
    if (b == SIZE_MAX) {
        melnikov_body *grown = realloc(p->bodies, (p->n_bodies + 1) * sizeof *grown);
        if (!grown) return gb_error_set(GB_ENOMEM, "out of memory for the reduced models of a scan");
        p->bodies = grown;
        b = p->n_bodies++;
        p->bodies[b] = (melnikov_body){.morphology = scene->body.morphology, .beta = scene->body.beta,
                                       .mass = scene->dynamics.mass, .g = scene->dynamics.forcing.g};
    }
    if (f == SIZE_MAX) {
        melnikov_frequency *grown = realloc(p->frequencies, (p->n_frequencies + 1) * sizeof *grown);
        if (!grown) return gb_error_set(GB_ENOMEM, "out of memory for the Melnikov integrals of a scan");
        p->frequencies = grown;
        p->frequencies[p->n_frequencies++] = (melnikov_frequency){.body = b, .omega = scene->dynamics.forcing.omega};
    }
    return GB_OK;
}

int gb_scan_melnikov_plan(const gb_scan *scan, const size_t *points, size_t count, gb_scan_melnikov **out)
{
    *out = NULL;
    gb_scan_melnikov *p = calloc(1, sizeof *p);
    if (!p) return gb_error_set(GB_ENOMEM, "out of memory for a scan's reduced models");
    int status = GB_OK;
    for (size_t k = 0; k < count && !status && (scan->metrics & GB_SCAN_MELNIKOV); k++) {
        gb_case scene;
        status = gb_scan_point_case(scan, points[k], &scene);
        if (!status) status = plan_add(p, &scene);
    }
    if (status) {
        gb_scan_melnikov_free(p);
        return status;
    }
    *out = p;
    return GB_OK;
}

size_t gb_scan_melnikov_bodies(const gb_scan_melnikov *plan) { return plan->n_bodies; }
size_t gb_scan_melnikov_frequencies(const gb_scan_melnikov *plan) { return plan->n_frequencies; }

int gb_scan_melnikov_body(gb_scan_melnikov *plan, size_t i)
{
    melnikov_body *b = &plan->bodies[i];
    const gb_surface surface = {b->morphology, b->beta};
    int status = gb_melnikov_body_create(&surface, b->mass, b->g, GB_MELNIKOV_BODY_NODES, &b->body);
    if (!status) {
        b->model = gb_melnikov_body_model(b->body, GB_MELNIKOV_MASS_AT_TOP);
        status = gb_melnikov_orbit_find(&b->model, &b->orbit);
    }
    gb_melnikov_values top;
    if (!status) status = b->model.eval(b->model.context, b->orbit.q_u, &top);
    if (!status) b->M_u = top.M;
    if (!status) status = gb_melnikov_tables_create(&b->model, &b->orbit, GB_MELNIKOV_EXACT, &b->tables);
    for (size_t k = 0; !status && k < plan->n_frequencies; k++)
        if (plan->frequencies[k].body == i) status = gb_melnikov_tables_prepare(b->tables, plan->frequencies[k].omega);
    b->status = status, b->computed = 1;
    return status == GB_EDOM ? GB_OK : status; /* not defined for this body: its margins are NAN */
}

int gb_scan_melnikov_frequency(gb_scan_melnikov *plan, size_t i)
{
    melnikov_frequency *f = &plan->frequencies[i];
    const melnikov_body *b = &plan->bodies[f->body];
    if (!b->computed) return gb_error_set(GB_EINVAL, "the Melnikov integrals at omega = %g before their body", f->omega);
    f->status = b->status ? b->status : gb_melnikov_tables_integrals(b->tables, f->omega, &f->integrals);
    f->computed = 1;
    return f->status == GB_EDOM ? GB_OK : f->status;
}

void gb_scan_melnikov_free(gb_scan_melnikov *plan)
{
    if (!plan) return;
    for (size_t k = 0; k < plan->n_bodies; k++) {
        gb_melnikov_tables_free(plan->bodies[k].tables);
        gb_melnikov_body_free(plan->bodies[k].body);
    }
    free(plan->bodies);
    free(plan->frequencies);
    free(plan);
}

int gb_scan_melnikov_planned(const gb_scan_melnikov *p, const gb_case *scene, double *margin, double *margin_eq93)
{
    *margin = *margin_eq93 = NAN;
    if (!(scene->dynamics.forcing.g > 0.0)) return GB_OK;
    size_t b, f;
    plan_find(p, scene, &b, &f);
    if (f == SIZE_MAX || !p->frequencies[f].computed)
        return gb_error_set(GB_EINVAL, "the Melnikov margins of a point the scan did not plan (omega = %g)",
                            scene->dynamics.forcing.omega);
    const melnikov_frequency *w = &p->frequencies[f];
    if (w->status) return GB_OK;
    const gb_forcing *F = &scene->dynamics.forcing;
    const double mu = scene->dynamics.damping / p->bodies[b].M_u, damping = mu * w->integrals.D;
    const gb_melnikov_forcing forcing = {mu, F->a1, F->a2, F->omega, F->psi, 0};
    gb_melnikov_criterion c;
    gb_melnikov_judge(&w->integrals, &forcing, &c);
    *margin = c.oscillatory_max / damping;
    *margin_eq93 = (fabs(F->a1) * w->integrals.A1 + fabs(F->a2) * w->integrals.A2) / damping;
    return GB_OK;
}

int gb_scan_melnikov_margins(const gb_case *scene, double *margin, double *margin_eq93)
{
    gb_scan_melnikov p = {0};
    int status = plan_add(&p, scene);
    for (size_t k = 0; !status && k < p.n_bodies; k++) status = gb_scan_melnikov_body(&p, k);
    for (size_t k = 0; !status && k < p.n_frequencies; k++) status = gb_scan_melnikov_frequency(&p, k);
    if (!status) status = gb_scan_melnikov_planned(&p, scene, margin, margin_eq93);
    for (size_t k = 0; k < p.n_bodies; k++) {
        gb_melnikov_tables_free(p.bodies[k].tables);
        gb_melnikov_body_free(p.bodies[k].body);
    }
    free(p.bodies);
    free(p.frequencies);
    return status;
}
