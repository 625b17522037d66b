/* What `gomboc run` and `gomboc lyapunov` share: the JSON of a scene's λ (gb_run computes it). */
#include "gomboc_cli.h"

#include "gb_error.h"

#include <string.h>

cJSON *cli_lyapunov_json(const gb_case *scene, const gb_lyapunov_result *r, int with_record)
{
    cJSON *o = cJSON_CreateObject();
    cli_json_add(o, "lambda_max", r->lambda_max);
    cli_json_add(o, "error_bar", r->error_bar);
    cJSON_AddStringToObject(o, "units", "1/s");
    cli_json_add(o, "periods", (double)r->intervals * (double)scene->lyapunov_interval_periods);
    cli_json_add(o, "intervals", (double)r->intervals);
    cli_json_add(o, "interval_periods", (double)scene->lyapunov_interval_periods);
    cli_json_add(o, "transient_periods", (double)scene->lyapunov_def.transient);
    cli_json_add(o, "delta0", r->delta0);
    /* What the record chose (or the case fixed), and how. */
    cli_json_add(o, "warmup_intervals", (double)r->warmup);
    cJSON_AddStringToObject(o, "warmup_rule", scene->lyapunov_def.warmup == GB_LYAPUNOV_CHOSEN ? "MSER-5" : "fixed");
    cJSON_AddBoolToObject(o, "warmup_found", r->warmup_found);
    cli_json_add(o, "batches", (double)r->batches);
    cJSON_AddStringToObject(o, "batches_rule",
                            scene->lyapunov_def.batches == GB_LYAPUNOV_CHOSEN ? "lag-1 autocorrelation within 2/sqrt(B)" : "fixed");
    cli_json_add(o, "batch_correlation", r->batch_correlation);
    cJSON_AddBoolToObject(o, "batches_independent", r->batches_independent);
    cli_json_add(o, "whole_record_mean", r->whole_record);
    cli_json_add(o, "omega_scale", scene->omega_scale);
    cli_json_add(o, "late_drift", r->late_drift);
    cJSON_AddBoolToObject(o, "converged", r->converged);
    if (with_record) {
        cJSON_AddItemToObject(o, "running", cli_json_vector(r->running, (int)r->intervals));
        cJSON_AddItemToObject(o, "instantaneous", cli_json_vector(r->instantaneous, (int)r->intervals));
    }
    return o;
}
