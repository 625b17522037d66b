/* What `gomboc run` and `gomboc lyapunov` share: a scene's λ (the pair estimator, eq 77, whose
 * reference is the scene's own run) and its JSON. */
#include "gomboc_cli.h"

#include "gb_error.h"

#include <string.h>

int cli_scene_lyapunov(const gb_case *scene, gb_integrate_sample sample, void *context, gb_dynamics **observer,
                       gb_lyapunov_body **out_body, gb_lyapunov_result *result)
{
    gb_lyapunov_body *body = NULL;
    memset(result, 0, sizeof *result);
    int status = gb_lyapunov_body_create(&scene->body, &scene->dynamics, &scene->integrate,
                                         scene->attitude, scene->omega0, scene->omega_scale, &body);
    if (status) return status;
    if (observer) *observer = gb_lyapunov_body_dynamics(body);
    /* The sample at t = 0 is ours; the reference delivers the rest as a plain run would. */
    if (sample && sample(context, 0.0, gb_lyapunov_body_state(body)))
        status = gb_error_set(GB_EINVAL, "the sampler stopped the run at t = 0");
    gb_lyapunov_body_observe(body, sample, context);
    const gb_lyapunov_pair_system system = gb_lyapunov_body_pair();
    if (!status) status = gb_lyapunov_pair(&system, body, &scene->lyapunov_def, 0.0, NULL, result);
    if (status) {
        gb_lyapunov_body_free(body);
        return status;
    }
    *out_body = body;
    return GB_OK;
}

cJSON *cli_lyapunov_json(const gb_case *scene, const gb_lyapunov_result *r, int with_record)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "lambda_max", r->lambda_max);
    cJSON_AddNumberToObject(o, "error_bar", r->error_bar);
    cJSON_AddStringToObject(o, "units", "1/s");
    cJSON_AddNumberToObject(o, "periods", (double)r->intervals * (double)scene->lyapunov_interval_periods);
    cJSON_AddNumberToObject(o, "intervals", (double)r->intervals);
    cJSON_AddNumberToObject(o, "interval_periods", (double)scene->lyapunov_interval_periods);
    cJSON_AddNumberToObject(o, "transient_periods", (double)scene->lyapunov_def.transient);
    cJSON_AddNumberToObject(o, "delta0", r->delta0);
    cJSON_AddNumberToObject(o, "batches", (double)scene->lyapunov_def.batches);
    cJSON_AddNumberToObject(o, "omega_scale", scene->omega_scale);
    cJSON_AddNumberToObject(o, "late_drift", r->late_drift);
    cJSON_AddBoolToObject(o, "converged", r->converged);
    if (with_record) {
        cJSON_AddItemToObject(o, "running", cJSON_CreateDoubleArray(r->running, (int)r->intervals));
        cJSON_AddItemToObject(o, "instantaneous", cJSON_CreateDoubleArray(r->instantaneous, (int)r->intervals));
    }
    return o;
}
