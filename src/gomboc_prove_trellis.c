/* gomboc prove's statement on the classical Hénon map's topological entropy by a trellis of its fixed point's
 * manifolds (gb_proof_trellis.h; docs/proofs.md, item 13). */
#include "gomboc_cli.h"
#include "gomboc_prove_common.h"

#include "gb_proof_manifold.h"
#include "gb_proof_trellis.h"

#include <stdio.h>

enum { DEPTH = 40 };
/* The claims, fixed before a run: the bound each trellis gave when the statement was written, rounded down. */
#define CLAIM_SMALL 0.4621
#define CLAIM_LARGE 0.46471
#define NBGM 0.46469 /* Newhouse, Berz, Grote & Makino's published bound (2008) */

/* W: the stable pieces R(t), t in each, chosen once in doubles by levels (docs/proofs.md, item 13): the local piece,
 * then the parts of each level's piece times R's eigenvalue that lie in Hénon's trapping quadrilateral, eight levels.
 * The proof checks f(W) ⊂ W itself; the choice only decides how much the bound can give. */
static const gb_proof_interval stable[] = {
    {-1273339.8897936922, -1273335.4857052993}, {-1273311.7461614106, -1273307.3953666999},
    {-1170959.3119095128, -1170955.3011080641}, {-1170954.3819246879, -1170947.6080119316},
    {-1170613.0259559099, -1170601.3284347788}, {-1170098.0582092374, -1170086.9469255297},
    {-1169659.6576607963, -1169653.7327293777}, {-1169650.3532438152, -1169647.3412023191},
    {-294524.87553324807, -294522.99352998554}, {-294520.42683067388, -294516.58883325371},
    {-294464.08823344426, -294457.55811012525}, {-294396.26546748751, -294390.73874723737},
    {-294270.98004650418, -294267.66658411117}, {-292289.82249999687, -292285.80961694708},
    {-292142.15210829128, -292134.43139511102}, {-198572.73530565234, -198567.54788312194},
    {-182606.87463803557, -182604.84478834865}, {-182553.08674105915, -182550.53903649945},
    {-182472.9345266879, -182470.45958971389},  {-182404.26417253926, -182402.1353046521},
    {-45930.112760758202, -45928.680545301024}, {-45921.289952061416, -45908.458691914871},
    {-45890.576741338205, -45889.816695988586}, {-45581.653477024694, -45580.803450935571},
    {-45558.577824044078, -45557.236083039999}, {-30966.844541758852, -30965.706488436961},
    {-28476.899072067579, -28468.023918937462}, {-28456.052374085506, -28444.904753262672},
    {-7162.6591599817557, -7156.3233234748441}, {-7108.3069574037063, -7104.4662534766612},
    {-4829.1705834469149, -4828.9837232895334}, {-4440.9892414261385, -4439.2147138746132},
    {-4437.8851824466037, -4435.7855875337918}, {-1117.046439100239, -1115.9286842459569},
    {-1108.5881546093515, -1107.8263601235958}, {-753.1686530260265, -753.00252302858644},
    {-747.8202981628383, -747.73832058298831},  {-747.2839365444944, -747.15426202606022},
    {-692.56122828831178, -691.73765219172196}, {-174.20759075448657, -172.75506359149324},
    {-117.4768432383007, -116.39099275851208},  {-108.08236074326638, -107.76388840354974},
    {-27.254882044465212, -26.879632751585831}, {-18.493999396626727, -16.772606552201829},
    {-4.2702736984882934, -2.4357763250247597}, {-0.72864709311385778, 0.5},
};

/* The trellises: U = P([−S, S]), W's arcs, the walks' length n, and the claim (the manifolds of
 * prove_henon_manifolds). */
typedef struct trellis_case {
    double u;
    const gb_proof_interval *stable;
    size_t count;
    int power;
    double claim;
} trellis_case;

cJSON *prove_trellis_statement(long precision, int large, int threads, int *proved, int *status)
{
    const trellis_case c =
        large ? (trellis_case){25600.0, prove_trellis_large_arcs, prove_trellis_large_count, 500000, CLAIM_LARGE}
              : (trellis_case){3200.0, stable, sizeof stable / sizeof *stable, 100000, CLAIM_SMALL};
    const double start = prove_thread_seconds();
    gb_proof_manifold *P, *R;
    *status = prove_henon_manifolds(precision, &P, &R);
    const size_t pieces = c.count;
    const double arc_u = c.u;
    const gb_proof_trellis_def td = {arc_u, c.stable, pieces, 0.01, DEPTH, c.power, threads};
    gb_proof_trellis_result t = {0};
    const double before = prove_thread_seconds(); /* this thread's share of t.seconds */
    if (!*status) *status = gb_proof_trellis_entropy(P, R, &td, &t);
    const double others = t.seconds - (prove_thread_seconds() - before);
    gb_proof_manifold_free(P), gb_proof_manifold_free(R);
    if (*status) return NULL;
    cJSON *s = cJSON_CreateObject();
    char text[700];
    snprintf(text, sizeof text,
             "Henon, a = 1.4, b = 0.3 (classical), by a trellis of its fixed point's manifolds: h_top >= %g", c.claim);
    cJSON_AddStringToObject(s, "statement", text);
    cJSON_AddStringToObject(s, "system", "(x, y) -> (1 - a x^2 + y, b x), a = 7/5, b = 3/10 exactly");
    snprintf(text, sizeof text,
             "U = P([-%g, %g]) of the unstable manifold, f(U) = P([-|lambda| %g, |lambda| %g]); W: %zu arcs of the "
             "stable manifold (f(W) in W proved); %zu crossings of f(U) with W, %zu of them on U; %zu rectangles, "
             "%zu strips (%zu four-sided faces in a rectangle not proved strips); closed walks of n = %d strips",
             arc_u, arc_u, arc_u, arc_u, pieces, t.crossings, t.vertices, t.rectangles, t.strips, t.strips_left,
             c.power);
    cJSON_AddStringToObject(s, "sets", text);
    cJSON_AddStringToObject(s, "method",
                            "every crossing of f(U) with W by Krawczyk's operator and no other by bisection, with the "
                            "orientation of its tangents; the faces of U + W and of f(U) + W traced from the order of "
                            "the crossings along each arc; a strip: a face of f(U) + W across a rectangle Q_j from one "
                            "side on W to the other, bounded by the images of both sides on U of a rectangle Q_i; "
                            "a lower bound N of (A^n)_QQ in 63-bit integers rounded down, log ceil(N/2) on Arb");
    cJSON_AddStringToObject(
        s, "theorem",
        "each strip's preimage is stretched along paths across Q_j (Pireddu & Zanolin 2007, SAP); "
        "strips touch only as neighbours, so half the closed walks of n strips from Q give pairwise "
        "disjoint compact sets, each stretched by f^n across Q: f^n is semiconjugate on an "
        "invariant set to the full shift on ceil((A^n)_QQ / 2) symbols, and h_top(f) >= (1/n) log "
        "ceil(N / 2) for any N <= (A^n)_QQ");
    snprintf(text, sizeof text,
             "above Day, Frongillo & Trevino's 0.4320 and this command's 0.43255 by the discrete Conley index; %s "
             "Newhouse, Berz, Grote & Makino's 0.46469. log rho(A) = %.6f (doubles, not proved): longer walks give "
             "at most that",
             t.bound > NBGM ? "above" : "below", t.log_rho);
    cJSON_AddStringToObject(s, "reading", text);
    cli_json_add(s, "bound", t.bound);
    cli_json_add(s, "claim", c.claim);
    cli_json_add(s, "log_rho", t.log_rho);
    cli_json_add(s, "log_walks", t.log_walks);
    cli_json_add(s, "crossing_count", (double)t.crossings);
    cli_json_add(s, "rectangle_count", (double)t.rectangles);
    cli_json_add(s, "strip_count", (double)t.strips);
    *proved = t.proved && t.bound >= c.claim;
    char result[320];
    if (*proved)
        snprintf(result, sizeof result, "proved");
    else if (!t.proved)
        snprintf(result, sizeof result, "not proved: %s", t.failure);
    else
        snprintf(result, sizeof result, "not proved: the bound is %.6f, not %g", t.bound, c.claim);
    cJSON_AddStringToObject(s, "result", result);
    const double seconds = prove_thread_seconds() - start + (others > 0.0 ? others : 0.0);
    cli_json_add(s, "seconds", seconds);
    char summary[200];
    snprintf(summary, sizeof summary, "(h_top >= %.6f; %zu rectangles, %zu strips; %.3g s)", t.bound, t.rectangles,
             t.strips, seconds);
    cJSON_AddStringToObject(s, "summary", summary);
    return s;
}
