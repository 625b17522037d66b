/* Proved on Arb's balls (gb_proof, `gomboc prove`): the Melnikov oracles' enclosures and the zero prover.
 *
 * Oracles, none sharing code with what they check:
 * - the pendulum's and Duffing's Melnikov integrals by Arb's rigorous quadrature along their homoclinic orbits
 *   (in t) against their closed forms by residues, each enclosed apart: the two must meet; a closed form moved by
 *   1e-9 of its frequency must not (the meeting has teeth);
 * - today's non-rigorous tables (gb_melnikov: GSL quadrature in q, targets 1e-10) must lie within their stated
 *   tolerance of the enclosures;
 * - the zero prover on M(t₀) = −8μ + ν C₁ cos ωt₀, whose zeros are ±acos(8μ/(νC₁))/ω in closed form: proved
 *   intervals hold them; a forcing far from the threshold proves M ≠ 0 with a margin below the exact min |M|; at
 *   the threshold (a double zero, to rounding) it must say undecided — a prover that called that proved would lie;
 *   with a second harmonic, the count of zeros against a dense sampling's sign changes;
 * - gb_interval.h (the certificate's arithmetic) against Arb: each operation's interval holds Arb's enclosure of
 *   the exact result, at random and at awkward doubles;
 * - the command: `gomboc prove --json` proves every oracle statement it attempts (its JSON is the report's section
 *   "Proved"; the Gömböcs' statements are checked in verify/s7_proofs_body.c); bad input exits 2 naming the option and
 *   its range. */
#include "gb_check.h"
#include "gb_error.h"
#include "gb_interval.h"
#include "gb_melnikov.h"
#include "gb_proof.h"
#include "s7_models.h"
#include "verify_sections.h"

#include <cjson/cJSON.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int meets(gb_proof_interval a, gb_proof_interval b) { return a.lo <= b.hi && b.lo <= a.hi; }
static int holds(gb_proof_interval a, double x) { return a.lo <= x && x <= a.hi; }
static double width(gb_proof_interval a) { return a.hi - a.lo; }

static const double omegas[3] = {0.5, 1.0, 3.0};

static void test_oracle_integrals(void)
{
    for (int s = 0; s < 2; s++) {
        int met = 0, teeth = 0, status = GB_OK;
        double widest = 0.0, seconds = 0.0;
        for (int k = 0; k < 3 && !status; k++) {
            gb_proof_integrals I;
            status = gb_proof_oracle_integrals((gb_proof_system)s, omegas[k], GB_PROOF_PRECISION_DEFAULT, &I);
            if (status) break;
            const gb_proof_interval *q[5] = {&I.D, &I.C1, &I.S1, &I.C2, &I.S2};
            for (int j = 0; j < 5; j++) {
                met += meets(*q[j], I.closed[j]);
                widest = fmax(widest, width(*q[j]) / fmax(1.0, fabs(q[j]->hi)));
            }
            /* the closed form of the first-harmonic integral that is not 0, at a frequency moved by 1e-9 */
            const double w = omegas[k] * (1.0 + 1e-9);
            const double moved = s == GB_PROOF_PENDULUM ? 2 * M_PI / cosh(M_PI * w / 2) : -sqrt(2.0) * M_PI * w / cosh(M_PI * w / 2);
            teeth += !holds(s == GB_PROOF_PENDULUM ? I.C1 : I.S1, moved);
            seconds += I.seconds;
        }
        char q[160];
        snprintf(q, sizeof q, "%s: the Melnikov integrals D, C1, S1, C2, S2 enclosed on Arb's balls at omega = 0.5, 1, 3",
                 gb_proof_system_name((gb_proof_system)s));
        gb_check c = {"7", "88-90", q, s == GB_PROOF_PENDULUM ? "8; 2 pi sech(k pi omega / 2); 0 (residues), enclosed apart"
                                                              : "4/3; 0; -sqrt 2 pi k omega sech(k pi omega / 2), enclosed apart",
                      "proof: the quadrature's enclosure meets the closed form's (15 of 15); a closed form at 1e-9 of the "
                      "frequency away lies outside (3 of 3); enclosures 1e-14 wide at most, relative (128 bits, rounded to doubles)"};
        gb_check_true(&c, !status && met == 15 && teeth == 3 && widest <= 1e-14, "%d of 15 meet, %d of 3 moved closed forms "
                      "outside, widest %.3g relative, %.3g s CPU%s%s", met, teeth, widest, seconds, status ? ": " : "",
                      status ? gb_error_message() : "");
    }
}

static void test_tables_inside(void)
{
    const gb_melnikov_model *models[2] = {&PENDULUM, &DUFFING};
    int inside = 0, total = 0, status = GB_OK;
    double worst = 0.0;
    for (int s = 0; s < 2 && !status; s++) {
        gb_melnikov_orbit o;
        status = gb_melnikov_orbit_find(models[s], &o);
        for (int k = 0; k < 3 && !status; k++) {
            gb_melnikov_integrals F;
            gb_proof_integrals I;
            status = gb_melnikov_integrals_compute(models[s], &o, omegas[k], GB_MELNIKOV_EXACT, &F);
            if (!status) status = gb_proof_oracle_integrals((gb_proof_system)s, omegas[k], GB_PROOF_PRECISION_DEFAULT, &I);
            if (status) break;
            const double floats[5] = {F.D, F.C1, F.S1, F.C2, F.S2};
            const gb_proof_interval *q[5] = {&I.D, &I.C1, &I.S1, &I.C2, &I.S2};
            for (int j = 0; j < 5; j++) {
                /* the float's own error bar: 1e-9 relative (its quadratures' targets, with a margin of 10), 1e-12
                 * absolute where the integral is 0 by parity */
                const double bar = 1e-9 * fabs(floats[j]) + 1e-12;
                const double gap = floats[j] < q[j]->lo ? q[j]->lo - floats[j] : floats[j] > q[j]->hi ? floats[j] - q[j]->hi : 0.0;
                inside += gap <= bar, total++;
                worst = fmax(worst, gap / bar);
            }
        }
    }
    gb_check c = {"7", "88-90", "today's tables (gb_melnikov, GSL quadrature in q) against the enclosures: pendulum and Duffing, "
                  "omega = 0.5, 1, 3, five integrals each",
                  "each float within its own error bar of the Arb enclosure",
                  "1e-9 relative + 1e-12 absolute: the tables' quadrature targets (1e-10) with a margin of 10, and the parity zeros' "
                  "rounding"};
    gb_check_true(&c, !status && total == 30 && inside == total, "%d of %d inside their error bar of the enclosure; the largest gap "
                  "%.3g of its bar%s%s", inside, total, worst, status ? ": " : "", status ? gb_error_message() : "");
}

/* The pendulum's M(t₀) with one harmonic, its integrals enclosed at ω = 1. */
static int pendulum_zeros(double mu, double nu1, double nu2, gb_proof_interval psi, gb_proof_integrals *I, gb_proof_zeros *z)
{
    int status = gb_proof_oracle_integrals(GB_PROOF_PENDULUM, 1.0, GB_PROOF_PRECISION_DEFAULT, I);
    const gb_proof_melnikov m = {I->D, I->C1, I->S1, I->C2, I->S2, mu, nu1, nu2, 1.0, psi, GB_PROOF_PRECISION_DEFAULT, 24};
    if (!status) status = gb_proof_melnikov_zeros(&m, z);
    return status;
}

static void test_zero_prover(void)
{
    const gb_proof_interval none = {0.0, 0.0};
    gb_proof_integrals I;
    gb_proof_zeros z;
    /* two simple zeros at ±acos(8μ/C₁) */
    int status = pendulum_zeros(0.1, 1.0, 0.0, none, &I, &z);
    const double C1 = 2 * M_PI / cosh(M_PI / 2), s0 = acos(0.8 / C1), exact[2] = {s0, 2 * M_PI - s0};
    int held = 0;
    for (size_t k = 0; !status && k < z.zeros && k < 2; k++)
        for (int j = 0; j < 2; j++) held += holds((gb_proof_interval){z.where[k].lo - 1e-12, z.where[k].hi + 1e-12}, exact[j]);
    gb_check cz = {"7", "91", "the zero prover: pendulum, mu = 0.1, nu1 = 1, omega = 1 (M = -0.8 + C1 cos t0)",
                   "two zeros at +-acos(0.8 / C1), simple (M' = -C1 sin, |sin| = 0.95)",
                   "proof: exactly two proved, each interval holding its closed form (to 1e-12: acos in double)"};
    gb_check_true(&cz, !status && z.verdict == GB_PROOF_SIMPLE_ZEROS && z.zeros == 2 && held == 2 && z.slope_min > 0.0 &&
                  z.slope_min <= C1 * sin(s0) * (1 + 1e-12), "%s, %zu zeros, %d of 2 hold the closed form, |M'| >= %.6g "
                  "(exact |M'| there %.6g), widest %.3g", gb_proof_verdict_name(z.verdict), z.zeros, held, z.slope_min, C1 * sin(s0),
                  fmax(width(z.where[0]), width(z.where[1])));
    /* no zero: |M| ≥ 4 − C1 */
    status = pendulum_zeros(0.5, 1.0, 0.0, none, &I, &z);
    gb_check cn = {"7", "91", "the zero prover: pendulum, mu = 0.5 (M = -4 + C1 cos t0 < 0)", "no zero; min |M| = 4 - C1 = 1.496",
                   "proof: no zero proved, its margin a true lower bound (0 < margin <= 4 - C1)"};
    gb_check_true(&cn, !status && z.verdict == GB_PROOF_NO_ZERO && z.margin > 0.0 && z.margin <= 4.0 - C1, "%s, margin %.6g (exact "
                  "%.6g)", gb_proof_verdict_name(z.verdict), z.margin, 4.0 - C1);
    /* the threshold: μ = C₁/8 as a double, a double zero to rounding: undecided */
    status = pendulum_zeros(C1 / 8.0, 1.0, 0.0, none, &I, &z);
    gb_check ct = {"7", "91", "the zero prover at the threshold: pendulum, mu = C1/8 (a double zero of M at t0 = 0, to rounding)",
                   "neither simple zeros nor M != 0 can be proved", "a negative control: the verdict must be undecided"};
    gb_check_true(&ct, !status && z.verdict == GB_PROOF_UNDECIDED, "%s (%zu of %zu pieces undecided)", gb_proof_verdict_name(z.verdict),
                  z.undecided, z.boxes);
    /* a second harmonic at ψ = π/3: the proved count against a dense sampling's sign changes */
    gb_proof_interval psi;
    status = gb_proof_pi_fraction(1, 3, &psi);
    if (!status) status = pendulum_zeros(0.1, 1.0, 0.5, psi, &I, &z);
    const double C2 = 2 * M_PI / cosh(M_PI);
    int changes = 0;
    enum { SAMPLES = 100000 };
    double prev = NAN;
    for (int k = 0; k <= SAMPLES; k++) {
        const double t = 2 * M_PI * k / SAMPLES, M = -0.8 + C1 * cos(t) + 0.5 * C2 * cos(2 * t + M_PI / 3);
        if (k && (M > 0) != (prev > 0)) changes++;
        prev = M;
    }
    gb_check c2 = {"7", "91", "the zero prover with two harmonics: pendulum, mu = 0.1, nu1 = 1, nu2 = 0.5, psi = pi/3",
                   "the sign changes of M sampled at 1e5 points", "proof: as many simple zeros proved as sign changes"};
    gb_check_true(&c2, !status && z.verdict == GB_PROOF_SIMPLE_ZEROS && (int)z.zeros == changes, "%s, %zu zeros proved, %d sign "
                  "changes sampled", gb_proof_verdict_name(z.verdict), z.zeros, changes);
}

/* The doubles the interval arithmetic is tried at: random over many scales, and awkward ones. */
static double draw(unsigned long long *s)
{
    *s ^= *s >> 12, *s ^= *s << 25, *s ^= *s >> 27;
    const double u = (double)((*s * 2685821657736338717ull) >> 11) / 9007199254740992.0; /* [0, 1) */
    const double scale = ldexp(1.0, (int)(u * 80.0) - 40);
    *s ^= *s >> 12, *s ^= *s << 25, *s ^= *s >> 27;
    const double v = (double)((*s * 2685821657736338717ull) >> 11) / 9007199254740992.0;
    return (v < 0.5 ? -1.0 : 1.0) * scale * (1.0 + v);
}

static void test_interval_against_arb(void)
{
    static const char *const ops[] = {"add", "sub", "mul", "recip", "sqrt", "sin", "cos", "root4"};
    static const double awkward[] = {1.0, 0.1, 1e-300, 3.0, M_PI, M_PI / 2, 1e10, 1e-10, 2.0 / 3.0, 0.7853981633974483};
    unsigned long long s = 0x51ed2701abcdef01ull;
    int tried = 0, enclosed = 0, controls = 0, rejected = 0, status = GB_OK;
    char first[200] = "";
    for (int op = 0; op < 8 && !status; op++)
        for (int k = 0; k < 4000 + 10 && !status; k++) {
            double x = k < 10 ? awkward[k] : draw(&s), y = draw(&s);
            if (op >= 4 || op == 3) x = fabs(x); /* the certificate takes sqrt and x^(1/4) of positives; 1/x of either sign */
            if ((op == 5 || op == 6) && fabs(x) > 1e6) x = fmod(x, 1e6);
            if (op == 3 && k % 2) x = -x;
            gb_interval r, a = gb_interval_point(x), b = gb_interval_point(y);
            switch (op) {
            case 0: r = gb_interval_add(a, b); break;
            case 1: r = gb_interval_sub(a, b); break;
            case 2: r = gb_interval_mul(a, b); break;
            case 3: r = gb_interval_recip(a); break;
            case 4: r = gb_interval_sqrt(a); break;
            case 5: r = gb_interval_sin(a); break;
            case 6: r = gb_interval_cos(a); break;
            default: r = gb_interval_sqrt(gb_interval_sqrt(a)); break;
            }
            int inside;
            status = gb_proof_encloses(ops[op], x, y, r.lo, r.hi, &inside);
            if (status) break;
            tried++, enclosed += inside == 1;
            if (k < 100) { /* a negative control: the interval just above ours holds no exact result ours holds */
                const double above = nextafter(r.hi, INFINITY);
                int wrong;
                status = gb_proof_encloses(ops[op], x, y, above, nextafter(above, INFINITY), &wrong);
                controls++, rejected += wrong == 0;
            }
            if (inside != 1 && !first[0])
                snprintf(first, sizeof first, "; first miss: %s(%.17g, %.17g) = [%.17g, %.17g] %s", ops[op], x, y, r.lo, r.hi,
                         inside ? "undecided at 4096 bits" : "does not hold the exact result");
        }
    gb_check c = {"4", "-", "gb_interval.h (the certificate's arithmetic) against Arb: add, sub, mul, 1/x, sqrt, sin, cos, x^(1/4) "
                  "at 4010 doubles each (random over 2^-40 ... 2^40, and awkward ones)",
                  "the exact result, placed by Arb at 256 to 4096 bits",
                  "proof: every interval holds the exact result (its outward widening by 2 eps + DBL_MIN covers the rounding); "
                  "a negative control: the two-ulp interval just above each of the first 100 a function holds none (800 of 800)"};
    gb_check_true(&c, !status && tried == 8 * 4010 && enclosed == tried && controls == 800 && rejected == controls,
                  "%d of %d hold the exact result; %d of %d intervals just above rejected%s%s%s", enclosed, tried, rejected, controls,
                  first, status ? ": " : "", status ? gb_error_message() : "");
}

static const char *binary(void) { return getenv("GOMBOC_BIN") ? getenv("GOMBOC_BIN") : "build/gomboc"; }

static void test_command(void)
{
    static char out[1 << 18];
    char path[4096];
    snprintf(path, sizeof path, "%s/proofs.json", gb_check_data_dir ? gb_check_data_dir : ".");
    remove(path); /* written again below only from this run's output (verify/s7_proofs_body.c reads it) */
    const int code = gb_check_command(binary(), "prove --json", out, sizeof out);
    char *mark = strstr(out, "@@exit=");
    if (mark) *mark = '\0'; /* the command's own output, without the harness's exit mark */
    cJSON *root = code == 0 || code == 1 ? cJSON_Parse(out) : NULL;
    const double attempted = cJSON_GetNumberValue(cJSON_GetObjectItem(root, "attempted"));
    int oracles = 0, oracles_proved = 0, listed = 0;
    const cJSON *item;
    cJSON_ArrayForEach(item, cJSON_GetObjectItem(root, "statements"))
    {
        const char *result = cJSON_GetStringValue(cJSON_GetObjectItem(item, "result"));
        listed++;
        if (cJSON_GetObjectItem(item, "data")) continue; /* a Gömböc's: verify/s7_proofs_body.c */
        oracles++, oracles_proved += result && !strncmp(result, "proved", 6);
    }
    const int written = root && gb_check_write_text("proofs.json", out) == 0;
    gb_check c = {
        "7", "91", "gomboc prove --json: the oracles' statements", "each oracle statement, proved",
        "exact: 21 attempted (the Melnikov oracles' 9, Roessler's and Henon's two horseshoes, the classical Henon "
        "map's returns across the band and across part of it, both Henon maps by their Conley index, the classical "
        "map's manifolds' crossings and its trellis, Roessler's orbit, the Gomboecs' 2), the 19 oracles' proved; "
        "written for the report"};
    gb_check_true(&c,
                  (code == 0 || code == 1) && attempted == 21 && oracles == 19 && oracles_proved == 19 &&
                      listed == 21 && written,
                  "exit %d, %d of %d oracle statements proved, %d listed, report data %s", code, oracles_proved,
                  oracles, listed, written ? "written" : "not written");
    cJSON_Delete(root);
    static const struct {
        const char *args, *must;
    } bad[] = {{"prove --precision 10", "--precision"}, {"prove --precision 100.5", "integer"},
               {"prove --depth 41", "--depth"},         {"prove --depth=41", "1 to 40"},
               {"prove --frobnicate", "--frobnicate"},  {"prove --precision 128 --precision 256", "twice"},
               {"prove --threads 0", "--threads"},      {"prove --threads 2.5", "integer"}};
    int refused = 0;
    char first[300] = "";
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        const int e = gb_check_command(binary(), bad[k].args, out, sizeof out);
        const int ok = e == 2 && strstr(out, bad[k].must) && strstr(out, "allowed");
        refused += ok;
        if (!ok && !first[0]) snprintf(first, sizeof first, "; '%s' gave exit %d: %.200s", bad[k].args, e, out);
    }
    gb_check cb = {"-", "-", "gomboc prove: bad options", "exit 2 naming the option and its allowed range", "exact"};
    gb_check_true(&cb, refused == (int)(sizeof bad / sizeof bad[0]), "%d of %d refused so%s", refused,
                  (int)(sizeof bad / sizeof bad[0]), first);
}

/* Equal JSON trees, except for the keys whose values are times (seconds, and the summaries that quote them). */
static int same_apart_from_times(const cJSON *a, const cJSON *b)
{
    if (!a || !b || a->type != b->type) return 0;
    if (cJSON_IsNumber(a)) return a->valuedouble == b->valuedouble;
    if (cJSON_IsString(a)) return !strcmp(a->valuestring, b->valuestring);
    if (!cJSON_IsArray(a) && !cJSON_IsObject(a)) return 1;
    if (cJSON_GetArraySize(a) != cJSON_GetArraySize(b)) return 0;
    for (const cJSON *x = a->child, *y = b->child; x && y; x = x->next, y = y->next) {
        if (cJSON_IsObject(a) && strcmp(x->string, y->string)) return 0;
        if (cJSON_IsObject(a) && (!strcmp(x->string, "seconds") || !strcmp(x->string, "summary"))) continue;
        if (!same_apart_from_times(x, y)) return 0;
    }
    return 1;
}

/* verify-full: `gomboc prove --threads 1` states what the default (two threads on two cores) states. */
static void test_command_threads(void)
{
    if (!gb_check_full) return;
    static char one[1 << 18], two[1 << 18];
    const int c1 = gb_check_command(binary(), "prove --json --threads 1", one, sizeof one);
    const int c2 = gb_check_command(binary(), "prove --json --threads 2", two, sizeof two);
    for (char *out[2] = {one, two}, **o = out; o < out + 2; o++) {
        char *mark = strstr(*o, "@@exit=");
        if (mark) *mark = '\0';
    }
    cJSON *r1 = cJSON_Parse(one), *r2 = cJSON_Parse(two);
    const int same = r1 && r2 && same_apart_from_times(r1, r2);
    const double listed = cJSON_GetArraySize(cJSON_GetObjectItem(r2, "statements"));
    /* teeth: one number of one enclosure moved by an ulp must be told apart */
    cJSON *moved = cJSON_Duplicate(r2, 1);
    cJSON *last = cJSON_GetArrayItem(cJSON_GetObjectItem(moved, "statements"), (int)listed - 1);
    cJSON *bound = cJSON_GetArrayItem(cJSON_GetObjectItem(cJSON_GetObjectItem(last, "enclosures"), "M"), 0);
    if (bound) cJSON_SetNumberValue(bound, nextafter(bound->valuedouble, INFINITY));
    const int told = bound && !same_apart_from_times(r2, moved);
    cJSON_Delete(moved), cJSON_Delete(r1), cJSON_Delete(r2);
    gb_check c = {
        "-", "-", "gomboc prove --threads 1 against --threads 2 (verify-full)",
        "every statement, enclosure and verdict the same; only the CPU seconds (and the summaries quoting them) "
        "differ; the comparison tells an enclosure moved by one ulp apart",
        "exact"};
    gb_check_true(&c, c1 == c2 && (c1 == 0 || c1 == 1) && same && told && listed == 21,
                  "exits %d and %d, %g statements, %s; Gomboc II's M moved by an ulp %s", c1, c2, listed,
                  same ? "the same apart from times" : "THEY DIFFER", told ? "told apart" : "NOT told apart");
}

int verify_register_s7_proofs(void)
{
    static const verify_test tests[] = {
        {"proofs: the pendulum's and Duffing's Melnikov integrals enclosed, their closed forms met",
         test_oracle_integrals,
         "the Melnikov integrals of the pendulum and of Duffing's oscillator are enclosed rigorously and hold their "
         "closed forms"},
        {"proofs: today's Melnikov tables lie within their error bars of the enclosures", test_tables_inside,
         "the non-rigorous Melnikov integrals are within their stated error of the rigorous enclosures"},
        {"proofs: the zero prover against closed forms, with a negative control at the threshold", test_zero_prover,
         "simple zeros of M(t0) are proved, M != 0 is proved, and a double zero is left undecided"},
        {"proofs: gb_interval.h against Arb", test_interval_against_arb,
         "the certificate's interval arithmetic encloses the exact results Arb encloses"},
        {"proofs: gomboc prove", test_command, NULL},
        {"proofs: gomboc prove on one thread and on two (verify-full)", test_command_threads,
         "gomboc prove states the same on one thread and on two"},
        {NULL, NULL, NULL},
    };
    return verify_register_suite("Proved on Arb's balls: the Melnikov oracles (section 7)", tests);
}
