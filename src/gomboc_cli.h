/* gomboc_cli — what the subcommands of the `gomboc` command share: strict option parsing with
 * messages that name the option and its allowed range, atomic output files, exit statuses. */
#ifndef GOMBOC_CLI_H
#define GOMBOC_CLI_H

#include "gb_case.h"
#include "gb_lyapunov.h"

#include <cjson/cJSON.h>

enum { EXIT_INPUT = 2, EXIT_COMPUTE = 1 };

/* Print "gomboc COMMAND: " + fmt (with `what` and `allowed`) and a pointer to --help; returns
 * EXIT_INPUT. */
int cli_input_error(const char *command, const char *fmt, const char *what, const char *allowed);

/* A whole-string finite double, or 0. */
int cli_parse_double(const char *text, double *value);

/* The body every body-level command names: --morphology and --beta. */
typedef struct cli_body {
    const char *morphology;
    double beta;
    int have_beta;
} cli_body;

/* Read the option argv[*i]. Returns CLI_HELP after printing `usage` for --help/-h; CLI_NEXT after
 * consuming --json (sets *json) or a body option (--morphology, --beta, into *body; refused when
 * body is NULL); CLI_VALUE for
 * an option listed in `valued` (NULL-terminated), with its value in *value and *i advanced past it;
 * otherwise EXIT_INPUT after printing an error that lists `allowed`. */
enum { CLI_HELP = 10, CLI_NEXT = 11, CLI_VALUE = 12 };
int cli_next_option(const char *command, int argc, char **argv, int *i, const char *usage,
                    const char *const *valued, const char *allowed, cli_body *body, int *json,
                    const char **value);

/* After parsing: both given? Returns 0 or EXIT_INPUT after printing an error. */
int cli_body_required(const char *command, const cli_body *body);

/* Write `text` to `path` atomically: a temporary file beside it, then rename. gb_ status. */
int cli_write_atomically(const char *path, const char *text);

/* Print a library failure and map its status to the exit status. */
int cli_failure(const char *command, int status);

cJSON *cli_json_vector(const double *v, int n);

/* Print `root` as JSON on stdout. */
void cli_print_json(const cJSON *root);

/* The scene's λ_max by the pair estimator (eq 77) with its [lyapunov] definition; the reference is the
 * scene's run, whose samples (t = 0 included) go to `sample`, observed through *observer (may be NULL).
 * On success *body holds the final states (free it with gb_lyapunov_body_free); *result is filled. */
int cli_scene_lyapunov(const gb_case *scene, gb_integrate_sample sample, void *context, gb_dynamics **observer,
                       gb_lyapunov_body **body, gb_lyapunov_result *result);
/* The JSON of a scene's λ: lambda_max, error_bar, periods, delta0, …; with `with_record`, running and
 * instantaneous. */
cJSON *cli_lyapunov_json(const gb_case *scene, const gb_lyapunov_result *result, int with_record);

int command_shape(int argc, char **argv);
int command_lyapunov(int argc, char **argv);
int command_contact(int argc, char **argv);
int command_run(int argc, char **argv);

#endif
