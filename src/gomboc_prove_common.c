/* What the proof commands share (gomboc_prove_common.h): Table 1's rolling forcing, written once, and the JSON of an enclosure,
 * a hypothesis and a Gömböc statement's data. */
#include "gomboc_cli.h"
#include "gomboc_prove_common.h"

#include <time.h>

const prove_table1 prove_rolling = {
    .beta = 0.12, .mass = 1.0, .g = 9.81, .damping = 0.02, .A1 = 2.0, .A2 = 1.0, .omega = 18.0};

cJSON *prove_json_interval(gb_proof_interval x)
{
    const double v[2] = {x.lo, x.hi};
    return cli_json_vector(v, 2);
}

void prove_add_hypothesis(cJSON *list, const char *text, const char *status)
{
    cJSON *h = cJSON_CreateObject();
    cJSON_AddStringToObject(h, "hypothesis", text);
    cJSON_AddStringToObject(h, "status", status);
    cJSON_AddItemToArray(list, h);
}

const char *prove_status(int holds) { return holds ? "proved" : "not proved"; }

double prove_thread_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

cJSON *prove_rolling_data(cJSON *statement, const char *morphology, gb_proof_interval psi)
{
    cJSON *data = cJSON_AddObjectToObject(statement, "data");
    cJSON_AddStringToObject(data, "morphology", morphology);
    cli_json_add(data, "beta", prove_rolling.beta);
    cli_json_add(data, "mass", prove_rolling.mass);
    cli_json_add(data, "g", prove_rolling.g);
    cli_json_add(data, "damping", prove_rolling.damping);
    cli_json_add(data, "A1", prove_rolling.A1);
    cli_json_add(data, "A2", prove_rolling.A2);
    cli_json_add(data, "omega", prove_rolling.omega);
    cJSON_AddItemToObject(data, "psi", prove_json_interval(psi));
    return data;
}
