/* gomboc prove --horseshoe — each Gömböc's period map at Table 1's rolling forcing has a horseshoe: covering relations of
 * parallelograms along one homoclinic orbit (N₀ ⇒ N₀ at the saddle, N₀ ⇒ N₁ ⇒ … ⇒ N_m ⇒ N₀ round the excursion), each
 * proved on Arb's balls, the sets proved disjoint on the cylinder, and the graph's entropy bounded below
 * (gb_proof_body_chain_design, gb_proof_body_cover_link; docs/proofs.md). The links are independent: they run on the
 * threads asked. */
#include "gomboc_cli.h"
#include "gomboc_prove_common.h"

#include "gb_error.h"
#include "gb_melnikov_body.h"
#include "gb_proof_body.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The links' first cut across, the halvings allowed and the Taylor order; H's coefficients over cells of q 2^-9 wide
 * shared by all links (gb_proof_body_arcs: a step's H′ for Picard's test and its remainder's coefficients, up to
 * ORDER + 2; docs/proofs.md, item 10, says why and what it saves). */
enum { PIECES = 1, DEPTH = 6, ORDER = 12, CELL_LEVEL = 9 };

typedef struct link_job {
    size_t from, to;
    int turns, tie; /* the target 2π on (the last link); the float model's tie crossed, or −1 */
    gb_proof_body_link result;
    int status;
    char message[300];
} link_job;

typedef struct work {
    const gb_proof_body_def *def;
    const gb_proof_body_forcing *forcing;
    const gb_proof_body_chain *chain;
    const gb_proof_body_tie *ties;
    link_job *jobs;
    size_t count, next;
    pthread_mutex_t lock;
} work;

static void *run_links(void *arg)
{
    work *w = arg;
    for (;;) {
        pthread_mutex_lock(&w->lock);
        const size_t k = w->next++;
        pthread_mutex_unlock(&w->lock);
        if (k >= w->count) return NULL;
        link_job *j = &w->jobs[k];
        j->status = gb_proof_body_cover_link(w->def, w->forcing, j->tie >= 0 ? &w->ties[j->tie] : NULL,
                                             &w->chain->set[j->from], &w->chain->set[j->to], j->turns, PIECES, DEPTH,
                                             ORDER, &j->result);
        if (j->status) snprintf(j->message, sizeof j->message, "%s", gb_error_message());
    }
}

/* The definition of a Gömböc's reduced field (M enclosed, ψ = π/3 enclosed) and its float model's ties. */
static int setup(const char *morphology, gb_surface *surface, gb_proof_body_def *def, gb_proof_body_forcing *forcing,
                 gb_melnikov_body_info *info, long precision)
{
    int status = gb_surface_init(surface, morphology, prove_rolling.beta);
    gb_melnikov_body *body = NULL;
    if (!status)
        status = gb_melnikov_body_create(surface, prove_rolling.mass, prove_rolling.g, GB_MELNIKOV_BODY_NODES, &body);
    if (status) return status;
    gb_melnikov_body_get_info(body, info);
    gb_melnikov_body_free(body);
    *def = (gb_proof_body_def){.surface = surface,
                               .mass = prove_rolling.mass,
                               .g = prove_rolling.g,
                               .origin = 3.0,
                               .cut = 2e-3,
                               .resolution = 1e-3,
                               .precision = precision};
    memcpy(def->rocking, info->rocking, sizeof def->rocking);
    gb_proof_interval psi = {M_PI / 3.0, M_PI / 3.0};
    status = gb_proof_body_inertia(surface, prove_rolling.mass, info->rocking, precision, &def->inertia, NULL);
    if (!status) status = gb_proof_pi_fraction(1, 3, &psi);
    *forcing =
        (gb_proof_body_forcing){prove_rolling.damping, prove_rolling.A1, prove_rolling.A2, prove_rolling.omega, psi, 0};
    return status;
}

cJSON *prove_chain_statement(const char *morphology, long precision, int threads, int *proved, int *status)
{
    *proved = 0;
    gb_surface surface;
    gb_proof_body_def def;
    gb_proof_body_forcing forcing;
    gb_melnikov_body_info info;
    *status = setup(morphology, &surface, &def, &forcing, &info, precision);
    gb_proof_body_chain_def cd = {0};
    if (!*status) *status = gb_proof_body_chain_default(morphology, &cd);
    gb_proof_body_chain chain = {0};
    if (!*status) *status = gb_proof_body_chain_design(&def, &forcing, &cd, &chain);
    gb_proof_body_tie ties[16];
    const size_t kinks = info.kinks < 16 ? info.kinks : 16;
    for (size_t t = 0; t < kinks && !*status; t++)
        *status = gb_proof_body_tie_locate(&def, info.kink_q[t] - 2e-4, info.kink_q[t] + 2e-4, &ties[t]);
    const size_t m = chain.sets ? chain.sets - 1 : 0, count = m + 2;
    gb_proof_body_arcs *arcs = NULL;
    if (!*status) *status = gb_proof_body_arcs_create(&def, CELL_LEVEL, ORDER + 2, &arcs);
    def.arcs = arcs;
    link_job *jobs = *status ? NULL : calloc(count, sizeof *jobs);
    if (!*status && !jobs) *status = gb_error_set(GB_ENOMEM, "the horseshoe's links: no memory");
    if (*status) {
        gb_proof_body_arcs_free(arcs);
        free(jobs);
        gb_proof_body_chain_free(&chain);
        return NULL;
    }
    /* N₀ ⇒ N₀, then N_i ⇒ N_{i+1} for i = 0 … m − 1, then N_m ⇒ N₀ 2π on */
    jobs[0] = (link_job){.from = 0, .to = 0, .tie = -1};
    for (size_t i = 0; i <= m; i++)
        jobs[i + 1] = (link_job){.from = i, .to = i < m ? i + 1 : 0, .turns = i < m ? 0 : 1, .tie = chain.tie[i]};
    work w = {&def, &forcing, &chain, ties, jobs, count, 0, PTHREAD_MUTEX_INITIALIZER};
    const int extra = threads > 1 ? threads - 1 : 0;
    pthread_t *workers = extra ? calloc((size_t)extra, sizeof *workers) : NULL;
    int started = 0;
    for (int k = 0; k < extra && workers; k++) started += !pthread_create(&workers[started], NULL, run_links, &w);
    run_links(&w);
    for (int k = 0; k < started; k++) pthread_join(workers[k], NULL);
    free(workers);
    double seconds = 0.0;
    size_t covered = 0, pairs = 0, apart = 0;
    for (size_t k = 0; k < count && !*status; k++) {
        if (jobs[k].status) *status = gb_error_set(jobs[k].status, "%s", jobs[k].message);
        covered += jobs[k].result.covers, seconds += jobs[k].result.seconds;
    }
    gb_proof_body_arcs_stats cells;
    gb_proof_body_arcs_get_stats(arcs, &cells);
    gb_proof_body_arcs_free(arcs);
    def.arcs = NULL;
    for (size_t i = 0; i < chain.sets && !*status; i++)
        for (size_t j = i + 1; j < chain.sets; j++)
            pairs++, apart += gb_proof_body_hsets_disjoint(&chain.set[i], &chain.set[j], precision);
    double log_rho = 0.0;
    if (!*status) *status = gb_proof_body_chain_entropy((int)chain.sets, &log_rho);
    if (*status) {
        free(jobs);
        gb_proof_body_chain_free(&chain);
        return NULL;
    }
    *proved = covered == count && apart == pairs;
    cJSON *s = cJSON_CreateObject();
    char text[512];
    snprintf(text, sizeof text,
             "Gomboc %s, beta = %g, Table 1's rolling forcing (A1 = %g, A2 = %g m/s2, omega = %g, psi = "
             "pi/3, c = %g), reduced field of section 7 (M at the top, not linearised in eps): its period map has a "
             "horseshoe "
             "of %zu sets along a homoclinic orbit, h_top >= %.5f a period",
             morphology, prove_rolling.beta, prove_rolling.A1, prove_rolling.A2, prove_rolling.omega,
             prove_rolling.damping, chain.sets, floor(log_rho * 1e5) / 1e5);
    cJSON_AddStringToObject(s, "statement", text);
    cJSON_AddStringToObject(s, "system", "q' = P, P' = -(m / M) a(t) H'(q) - (c / M) P, a(t) = g + A1 cos(omega t) + A2 "
                                         "cos(2 omega t + psi), H the support function along the rocking direction; the "
                                         "period map from phase 0 on the cylinder q mod 2 pi");
    cJSON_AddStringToObject(s, "sets", "N0: the saddle's box in its eigenvectors; N1 ... Nm: parallelograms at the points of "
                                       "a homoclinic orbit placed on floats (Newton on the manifolds' meeting), in frames "
                                       "carried along it, their half-widths shrinking across and growing along by rho a "
                                       "period against the linear part");
    cJSON_AddStringToObject(s, "method",
                            "each covering relation by the mean value form on pieces: the period map of each "
                            "piece's middle and its derivative over the piece's box hull (the C1 Taylor-Lohner "
                            "step on Arb's balls, H' from the body's Taylor coefficients, over a step's arc the "
                            "hull of those of fixed cells of q shared by all links; across a tie the "
                            "branches' section maps composed through a sliver crossed with bounds)");
    cJSON_AddStringToObject(s, "theorem", "Zgliczynski and Gidea 2004 (J. Differential Equations 202), Thm 9: a chain of "
                                          "covering relations N0 => N0, N0 => N1 => ... => Nm => N0 gives for every sequence "
                                          "the graph admits an orbit of P visiting the sets in that order; the sets being "
                                          "disjoint, P on the invariant part of their union is semiconjugate to the subshift "
                                          "of the graph, so h_top(P) >= ln rho, rho the root above 1 of x^L = x^(L-1) + 1 "
                                          "(L the cycle's length)");
    cJSON *hyp = cJSON_AddArrayToObject(s, "hypotheses");
    char line[256];
    snprintf(line, sizeof line, "every covering relation of the graph: %zu of %zu proved", covered, count);
    prove_add_hypothesis(hyp, line, prove_status(covered == count));
    snprintf(line, sizeof line, "the sets pairwise disjoint on the cylinder: %zu of %zu pairs proved apart", apart, pairs);
    prove_add_hypothesis(hyp, line, prove_status(apart == pairs));
    prove_add_hypothesis(
        hyp,
        "P continuous on each set: the flow is, and every solution from a set that meets a tie crosses it "
        "moving up within the period (proved by the enclosures: q' > 0 there)",
        prove_status(covered == count));
    cJSON *data = prove_rolling_data(s, morphology, forcing.psi);
    cJSON_AddItemToObject(data, "M", prove_json_interval(def.inertia));
    cli_json_add(data, "unstable_iterates", cd.unstable_iterates);
    cli_json_add(data, "stable_iterates", cd.stable_iterates);
    cli_json_add(data, "first", cd.first);
    cli_json_add(data, "last", cd.last);
    cli_json_add(data, "rho", cd.rho);
    cJSON_AddItemToObject(data, "homoclinic_point", cli_json_vector(chain.homoclinic, 2));
    cli_json_add(data, "newton_residual", chain.residual);
    cJSON *links = cJSON_AddArrayToObject(s, "links");
    for (size_t k = 0; k < count; k++) {
        const gb_proof_body_link *r = &jobs[k].result;
        cJSON *l = cJSON_CreateObject();
        char name[64];
        snprintf(name, sizeof name, "N%zu => N%zu%s", jobs[k].from, jobs[k].to, jobs[k].turns ? " (2 pi on)" : "");
        cJSON_AddStringToObject(l, "link", name);
        if (jobs[k].tie >= 0) cJSON_AddItemToObject(l, "tie", prove_json_interval(ties[jobs[k].tie].q));
        cJSON_AddBoolToObject(l, "covers", r->covers);
        if (r->covers) {
            cli_json_add(l, "strip_margin", r->strip_margin);
            cli_json_add(l, "edge_margin", r->edge_margin);
        } else {
            cJSON_AddStringToObject(l, "failure", r->failure);
        }
        cli_json_add(l, "pieces", (double)r->pieces);
        cli_json_add(l, "seconds", r->seconds);
        cJSON_AddItemToArray(links, l);
    }
    cJSON *c = cJSON_AddObjectToObject(s, "cells");
    cli_json_add(c, "width", ldexp(1.0, -CELL_LEVEL));
    cli_json_add(c, "order", ORDER + 2);
    cli_json_add(c, "enclosed", (double)cells.cells);
    cli_json_add(c, "refused", (double)cells.refused);
    cli_json_add(c, "arcs_served", (double)cells.served);
    cli_json_add(c, "arcs_declined", (double)cells.declined);
    cli_json_add(c, "seconds", cells.seconds);
    cli_json_add(s, "log_rho", log_rho);
    cli_json_add(s, "precision_bits", (double)precision);
    cJSON_AddStringToObject(s, "result", *proved ? "proved" : "not proved: a covering relation or a disjointness not proved "
                                                              "(see links)");
    cli_json_add(s, "seconds", seconds);
    char summary[200];
    snprintf(summary, sizeof summary, "(%zu of %zu covering relations, %zu of %zu pairs apart; ln rho >= %.6f; %.0f s CPU)",
             covered, count, apart, pairs, log_rho, seconds);
    cJSON_AddStringToObject(s, "summary", summary);
    free(jobs);
    gb_proof_body_chain_free(&chain);
    return s;
}
