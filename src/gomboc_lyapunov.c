/* gomboc lyapunov — the maximal Lyapunov exponent of one scene (paper eq 77, Fig 9). */
#include "gomboc_cli.h"

#include "gb_error.h"
#include "gb_run.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static const char *usage_lyapunov =
    "usage: gomboc lyapunov CASE [--json]\n"
    "\n"
    "  CASE    a scene file (INI; cases/README.md); its [lyapunov] section sets delta0,\n"
    "          transient_periods, interval_periods, warmup_intervals, batches and omega_scale (the\n"
    "          warm-up and the batches are chosen from the record unless fixed), and the run's\n"
    "          [integrator] periods set the record: (periods - transient) / interval_periods intervals\n"
    "  --json  print one JSON object: lambda_max [1/s], error_bar (batch-means standard error),\n"
    "          periods, delta0, running (the running lambda_max after each interval),\n"
    "          instantaneous (lambda_inst per interval), converged, late_drift, ...\n"
    "\n"
    "Two trajectories of the scene, the second put back at distance delta0 along their separation\n"
    "after every interval (eq 77). Nothing is written to files.\n";

int command_lyapunov(int argc, char **argv)
{
    const char *case_path = NULL;
    int json = 0;
    static const char *const valued[] = {NULL};
    for (int i = 0; i < argc; i++) {
        const char *opt = argv[i];
        const int positional = cli_positional("lyapunov", opt, &case_path, "case file", "CASE");
        if (positional) {
            if (positional == 1) continue;
            return positional;
        }
        const int kind = cli_next_option("lyapunov", argc, argv, &i, usage_lyapunov, valued, " (allowed: --json, --help)",
                                         NULL, &json, NULL);
        if (kind == CLI_NEXT) continue;
        return kind == CLI_HELP ? 0 : kind;
    }
    if (!case_path)
        return cli_input_error("lyapunov", "missing %s%s", "CASE", " (allowed: a scene file, e.g. cases/table1-gomboc-I.ini)");
    gb_case scene;
    int status = gb_case_load(case_path, &scene);
    if (!status) status = gb_case_lyapunov_check(case_path, &scene);
    if (status) return cli_failure("lyapunov", status);
    if (cli_parse_only) return 0;
    /* The scene's run with λ and nothing else: no monitors, strobe, spectrum or files. */
    scene.lyapunov = 1;
    scene.monitors = scene.strobe = scene.spectrum = 0;
    scene.write_history = scene.write_summary = 0;
    gb_run_result run;
    status = gb_run(&scene, NULL, &run);
    if (status) return cli_failure("lyapunov", status);
    const gb_lyapunov_result r = run.lyapunov;
    const double seconds = run.seconds;
    if (json) {
        cJSON *root = cli_lyapunov_json(&scene, &r, 1);
        cJSON_AddStringToObject(root, "case", case_path);
        cJSON_AddStringToObject(root, "morphology", scene.body.morphology->name);
        cli_json_add(root, "beta", scene.body.beta);
        cJSON_AddStringToObject(root, "equation", gb_dynamics_variant_name(scene.dynamics.variant));
        cJSON_AddStringToObject(root, "contact", gb_contact_model_name(scene.dynamics.contact));
        cli_print_json(root);
        cJSON_Delete(root);
    } else {
        const double T = gb_forcing_period(&scene.dynamics.forcing);
        printf("%s: lambda_max = %.6g +- %.2g 1/s (%.6g +- %.2g per forcing period)\n", case_path, r.lambda_max,
               r.error_bar, r.lambda_max * T, r.error_bar * T);
        printf("  %zu intervals of %zu period(s) after %zu transient period(s); delta0 = %g; omega_scale = %g rad/s\n",
               r.intervals, scene.lyapunov_interval_periods, scene.lyapunov_def.transient, r.delta0, scene.omega_scale);
        printf("  warm-up: %zu intervals left out (%s%s); whole record: %.6g 1/s\n", r.warmup,
               scene.lyapunov_def.warmup == GB_LYAPUNOV_CHOSEN ? "MSER-5" : "fixed",
               r.warmup_found ? "" : ", NOT found: the record did not settle", r.whole_record);
        printf("  error bar: %zu batches (%s), lag-1 correlation of their means %.2f%s\n", r.batches,
               scene.lyapunov_def.batches == GB_LYAPUNOV_CHOSEN ? "chosen" : "fixed", r.batch_correlation,
               r.batches_independent ? "" : ", NOT independent: the error bar is a lower bound");
        printf("  convergence: the running value moved by %.3g over the kept record's last quarter (%s: limit 2 x "
               "error bar = %.3g)\n",
               r.late_drift, r.converged ? "converged" : "NOT converged", 2.0 * r.error_bar);
        printf("  %10s %14s %14s\n", "interval", "lambda_inst", "running");
        const size_t every = r.intervals > 20 ? r.intervals / 20 : 1;
        for (size_t n = 0; n < r.intervals; n++)
            if ((n + 1) % every == 0 || n + 1 == r.intervals)
                printf("  %10zu %14.6g %14.6g\n", n + 1, r.instantaneous[n], r.running[n]);
    }
    fprintf(stderr, "gomboc lyapunov: %s: %.2f s CPU\n", case_path, seconds);
    gb_run_result_free(&run);
    return 0;
}
