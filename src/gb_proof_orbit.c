/* Periodic orbits of a flow proved by Krawczyk's operator on its return map (gb_proof_flow.h): the map and its
 * derivative enclosed by the C¹ step of the rigorous integrator, the operator on Arb's balls. */
#include "gb_proof_flow.h"

#include "gb_error.h"
#include "gb_proof_internal.h"

#include <math.h>
#include <string.h>

#include <arb.h>
#include <arb_mat.h>

int gb_proof_flow_periodic_orbit(const gb_proof_flow_def *def, const gb_proof_interval *box, gb_proof_flow_orbit *out)
{
    if (!def || !def->field || !box || !out) return gb_error_set(GB_EINVAL, "a periodic orbit needs a definition, a box and a result");
    memset(out, 0, sizeof *out);
    const double start = gb_proof_cpu_seconds();
    const int n = def->field->dimension, c = def->coordinate, m = n - 1;
    gb_proof_flow_def map = *def, with_derivative = *def;
    map.derivative = 0, with_derivative.derivative = 1;
    /* x̂: the box's middle (a point of the section), its return; the box's return map and derivative */
    gb_proof_interval centre[GB_PROOF_FIELD_DIMENSION_MAX];
    for (int i = 0; i < n; i++) {
        const double mid = i == c ? 0.0 : 0.5 * (box[i].lo + box[i].hi);
        centre[i] = (gb_proof_interval){mid, mid};
    }
    gb_proof_flow_crossing at_centre, over_box;
    int status = gb_proof_flow_section_map(&map, centre, &at_centre);
    if (!status) status = gb_proof_flow_section_map(&with_derivative, box, &over_box);
    if (status) return status;
    const slong prec = def->precision;
    int plane[GB_PROOF_FIELD_DIMENSION_MAX]; /* the plane's coordinates in the state */
    for (int i = 0, k = 0; i < n; i++)
        if (i != c) plane[k++] = i;
    arb_mat_t J, Cm, Mid, K1;
    arb_mat_init(J, m, m), arb_mat_init(Cm, m, m), arb_mat_init(Mid, m, m), arb_mat_init(K1, m, m);
    arb_struct F0[GB_PROOF_FIELD_DIMENSION_MAX], dX[GB_PROOF_FIELD_DIMENSION_MAX], K[GB_PROOF_FIELD_DIMENSION_MAX],
        X[GB_PROOF_FIELD_DIMENSION_MAX], xh[GB_PROOF_FIELD_DIMENSION_MAX];
    for (int k = 0; k < m; k++) arb_init(&F0[k]), arb_init(&dX[k]), arb_init(&K[k]), arb_init(&X[k]), arb_init(&xh[k]);
    for (int a = 0; a < m; a++) {
        gb_proof_ball_of(&X[a], box[plane[a]], prec);
        gb_proof_ball_of(&xh[a], centre[plane[a]], prec);
        arb_sub(&dX[a], &X[a], &xh[a], prec);
        gb_proof_ball_of(&F0[a], at_centre.image[plane[a]], prec); /* F(x̂) = P(x̂) − x̂ */
        arb_sub(&F0[a], &F0[a], &xh[a], prec);
        for (int b = 0; b < m; b++) { /* J = DP(X) − I, its middle for C */
            gb_proof_ball_of(arb_mat_entry(J, a, b), over_box.jacobian[plane[a]][plane[b]], prec);
            if (a == b) arb_sub_ui(arb_mat_entry(J, a, b), arb_mat_entry(J, a, b), 1, prec);
            arb_get_mid_arb(arb_mat_entry(Mid, a, b), arb_mat_entry(J, a, b));
        }
    }
    /* C ≈ mid(J)⁻¹ in doubles (any matrix will do: it is taken exact) */
    if (!arb_mat_approx_inv(Cm, Mid, prec)) {
        status = gb_error_set(GB_ENUMERIC, "the return map's derivative minus the identity is singular at the box's middle");
    } else {
        for (int a = 0; a < m; a++)
            for (int b = 0; b < m; b++) arb_get_mid_arb(arb_mat_entry(Cm, a, b), arb_mat_entry(Cm, a, b));
        /* K = x̂ − C F(x̂) + (I − C J)(X − x̂) */
        arb_mat_mul(K1, Cm, J, prec);
        arb_mat_neg(K1, K1);
        for (int a = 0; a < m; a++) arb_add_ui(arb_mat_entry(K1, a, a), arb_mat_entry(K1, a, a), 1, prec);
        out->proved = 1;
        for (int a = 0; a < m; a++) {
            arb_set(&K[a], &xh[a]);
            for (int b = 0; b < m; b++) {
                arb_submul(&K[a], arb_mat_entry(Cm, a, b), &F0[b], prec);
                arb_addmul(&K[a], arb_mat_entry(K1, a, b), &dX[b], prec);
            }
            out->krawczyk[plane[a]] = gb_proof_interval_of(&K[a]);
            const gb_proof_interval k = out->krawczyk[plane[a]], x = box[plane[a]];
            out->proved &= k.lo > x.lo && k.hi < x.hi;
            out->excluded |= k.hi < x.lo || k.lo > x.hi;
        }
        out->krawczyk[c] = (gb_proof_interval){0.0, 0.0};
        out->time = over_box.time;
        out->period = (gb_proof_interval){NAN, NAN};
        gb_proof_flow_crossing over_k;
        if (out->proved && !gb_proof_flow_section_map(&map, out->krawczyk, &over_k)) out->period = over_k.time;
        for (int a = 0; a < n; a++)
            for (int b = 0; b < n; b++) out->jacobian[a][b] = over_box.jacobian[a][b];
    }
    arb_mat_clear(J), arb_mat_clear(Cm), arb_mat_clear(Mid), arb_mat_clear(K1);
    for (int k = 0; k < m; k++) arb_clear(&F0[k]), arb_clear(&dX[k]), arb_clear(&K[k]), arb_clear(&X[k]), arb_clear(&xh[k]);
    out->seconds = gb_proof_cpu_seconds() - start;
    return status;
}
