/* gomboc_cli — what the subcommands of the `gomboc` command share: strict option parsing with
 * messages that name the option and its allowed range, atomic output files, exit statuses. */
#ifndef GOMBOC_CLI_H
#define GOMBOC_CLI_H

#include "gb_case.h"
#include "gb_file.h"
#include "gb_lyapunov.h"

#include <cjson/cJSON.h>
#include <stdio.h>

enum { EXIT_INPUT = 2, EXIT_COMPUTE = 1 };

/* Print "gomboc COMMAND: " + the printf-formatted message and a pointer to --help; returns
 * EXIT_INPUT. The message names the option and its allowed values. */
int cli_input_error(const char *command, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The value of `option` as a number in [min, max] (an end excluded per `open`: CLI_OPEN_MIN,
 * CLI_OPEN_MAX), read by gb_parse_double (one whole token): 0, or EXIT_INPUT after an error that names
 * the option, the value, the reason (not a number, beyond a double, out of range) and `allowed`. */
enum { CLI_OPEN_MIN = 1, CLI_OPEN_MAX = 2 };
int cli_number(const char *command, const char *option, const char *value, double min, double max, int open,
               const char *allowed, double *out);

/* The body every body-level command names: --morphology and --beta. */
typedef struct cli_body {
    const char *morphology;
    double beta;
    int have_beta;
} cli_body;

/* Read the option argv[*i]. Returns CLI_HELP after printing `usage` for --help/-h; CLI_NEXT after
 * consuming --json (sets *json; refused when json is NULL) or a body option (--morphology, --beta, into *body; refused when
 * body is NULL); CLI_VALUE for
 * an option listed in `valued` (NULL-terminated), with its value in *value and *i advanced past it;
 * otherwise EXIT_INPUT after printing an error that lists `allowed`. */
enum { CLI_HELP = 10, CLI_NEXT = 11, CLI_VALUE = 12 };
int cli_next_option(const char *command, int argc, char **argv, int *i, const char *usage,
                    const char *const *valued, const char *allowed, cli_body *body, int *json,
                    const char **value);

/* Options' values: one that starts with "--" is taken only when written --name=value (cli_attached_values
 * records those values for the command's run; gomboc_main calls it). A flag given twice is refused:
 * cli_flag sets *flag, or returns EXIT_INPUT after an error when it is set already. */
void cli_attached_values(const char **values, int count);
int cli_flag(const char *command, const char *opt, int *flag);

/* For the option fuzzer (verify/fuzz): when set, a command returns 0 as soon as all its input (options,
 * output targets, the scene file) has been read and judged, before any computation or output. */
extern int cli_parse_only;

/* The "(allowed: …)" part of the last library error (a name parser's list of names), or "". */
const char *cli_allowed(void);

/* A positional argument (anything but an option; "-" is positional) into *slot, which takes one: 1 when
 * taken, EXIT_INPUT after an error naming `what` and `name` when *slot already holds one, 0 when `opt`
 * is an option. */
int cli_positional(const char *command, const char *opt, const char **slot, const char *what, const char *name);

/* After parsing: both given? Returns 0 or EXIT_INPUT after printing an error. */
int cli_body_required(const char *command, const cli_body *body);

/* Files. Before any work, a command lists every path it reads and writes (gb_file_use) and checks
 * them by gb_file's one rule (cli_files_check), and --out DIR by cli_output_dir_check: both print the
 * error, naming the option, and return EXIT_INPUT, or 0. Outputs are then written as gb_file sets.
 * cli_install_cleanup removes this process's temporaries on SIGINT, SIGTERM and SIGHUP, except for a
 * signal the parent process ignored, which stays ignored (nohup, a background job), and ignores SIGXFSZ
 * (a write past `ulimit -f` then fails like any other); cli_catch_signals(handler) installs `handler`
 * by the same rule. */
int cli_files_check(const char *command, const gb_file_use *uses, size_t count);
int cli_output_dir_check(const char *command, const char *option, const char *dir);
/* Before the work: can the lock of the directory holding `path` be taken (gb_file_lock's bounded wait)?
 * A lock held by another process is reported before the computation rather than after it: 0, or
 * EXIT_COMPUTE after printing the error. */
int cli_lock_probe(const char *command, const char *path, const char *what);
/* "DIR/NAME-suffix", NAME the input file's base name without ".ini" (malloc'd; NULL when out of memory). */
char *cli_output_name(const char *dir, const char *input, const char *suffix);
void cli_install_cleanup(void);
void cli_catch_signals(void (*handler)(int));

/* A sealed member of a set as a manifest entry {name (its base name), bytes, fnv1a64 (16 hex digits)},
 * appended to `list`. The manifest (a run's summary, a scan's JSON) is the set's last member. */
void cli_manifest_add(cJSON *list, const gb_file_member *member);

/* The suffixes of the files `gomboc run` may write beside NAME-summary.json (NULL-terminated). */
extern const char *const cli_run_suffixes[];

/* Write `text` to `path` as a set of one. gb_ status. */
int cli_write_atomically(const char *path, const char *text);

/* Print a library failure and map its status to the exit status. */
int cli_failure(const char *command, int status);

/* JSON numbers that read back to the same double (cJSON's own printing may drop the last bits): a
 * number (null when not finite), a member of `object`, an array. */
cJSON *cli_json_number(double value);
cJSON *cli_json_add(cJSON *object, const char *key, double value);
cJSON *cli_json_vector(const double *v, int n);

/* Print `root` as JSON on stdout. */
void cli_print_json(const cJSON *root);

/* The JSON of a scene's λ: lambda_max, error_bar, periods, delta0, …; with `with_record`, running and
 * instantaneous. */
cJSON *cli_lyapunov_json(const gb_case *scene, const gb_lyapunov_result *result, int with_record);

int gomboc_main(int argc, char **argv);
int command_shape(int argc, char **argv);
int command_lyapunov(int argc, char **argv);
int command_contact(int argc, char **argv);
int command_run(int argc, char **argv);
int command_scan(int argc, char **argv);
int command_melnikov(int argc, char **argv);
int command_check(int argc, char **argv);
int command_prove(int argc, char **argv);
/* The proofs themselves (gomboc_prove.c): linked into gomboc-prove (and the option fuzzer), not into gomboc, whose
 * command_prove runs gomboc-prove (gomboc_prove_exec.c). */
int command_prove_in_process(int argc, char **argv);
/* gomboc prove's statement on Gömböc `which` (0: I, 1: II) at Table 1's rolling forcing (gomboc_prove_body.c); resolution 0:
 * the coarsest that decides. NULL with *status set when a computation fails. */
cJSON *prove_body_statement(size_t which, double resolution, long precision, int depth, int *proved, int *status);
/* gomboc prove --horseshoe's statement on Gömböc `morphology` ("I" or "II", gomboc_prove_chain.c): its horseshoe along a
 * homoclinic orbit, its links on `threads` threads. NULL with *status set when a computation fails. */
cJSON *prove_chain_statement(const char *morphology, long precision, int threads, int *proved, int *status);

/* The user's cache of hulls and mass properties for context: $XDG_CACHE_HOME/gomboc, else $HOME/.cache/gomboc (made,
 * 0700); none when GOMBOC_CACHE=off or it cannot be made. gb_ status (a cache never fails a run: GB_OK but for memory). */
int cli_user_cache(gb_dynamics_context *context);

#endif
