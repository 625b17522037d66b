/* gomboc scan — a map over two keys of a scene (paper §8.3), parallel over points, resumable. */
#include "gomboc_cli.h"
#include "gb_clock.h"

#include "gb_error.h"
#include "gb_parse.h"
#include "gb_scan_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <inttypes.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#ifdef GOMBOC_MPI
#include <mpi.h>
#endif

static const char *usage_scan =
    "usage: gomboc scan SCAN [--out DIR] [--resume] [--threads N] [--atlas FILE]\n"
    "\n"
    "  SCAN         a scan file (INI; cases/README.md, \"Scan files\"): a base scene, two of its keys with\n"
    "               their ranges and counts, the periods and transient per point, the metrics\n"
    "  --out DIR    where the outputs go (default: the current directory): NAME-scan.csv, one row a\n"
    "               point in index order (row-major, x fastest), every metric; NAME-scan.json, the scan\n"
    "               as read, the environment and the timings. NAME is SCAN without .ini\n"
    "  --resume     finish an interrupted scan from its journal (NAME-scan.journal in DIR): the points\n"
    "               it holds are not run again, and the CSV is byte for byte that of an uninterrupted run;\n"
    "               without a journal, a scan whose NAME-scan.json in DIR this build wrote for this scan\n"
    "               and base scene is complete: nothing is run (said, exit 0); else the scan starts\n"
    "  --threads N  points run in parallel on N threads (1 ... 256; default: one per online processor);\n"
    "               the results do not depend on N\n"
    "  --atlas FILE ([model] certificate = atlas in the base scene, or [scan] atlas = shared) the points\n"
    "               share one atlas of verticals through FILE (built by the first points when FILE is\n"
    "               missing, stale or damaged): each thread keeps it in memory and merges it with FILE every\n"
    "               8 points and at its end; the results are those of the per-vertical certificate, bit for\n"
    "               bit. A scan file with atlas = shared keeps it in NAME-scan.atlas in DIR without this option\n"
    "               (or in the file of DIR its [scan] atlas_file names, which other scans of the body may share)\n"
    "\n"
    "Every finished point is appended to the journal and flushed; the journal is removed when the scan\n"
    "is complete and its outputs are written. Progress goes to standard error.\n"
#ifdef GOMBOC_MPI
    "\n"
    "Built with MPI: `mpirun -n N gomboc-mpi scan ...` shares the points among N ranks (each on its\n"
    "threads). Rank 0 alone reads and writes the journal and the outputs; every rank reads SCAN and its\n"
    "base scene. The CSV does not depend on N.\n"
#endif
    ;

/* On SIGINT, SIGTERM or SIGHUP once the journal exists: say how to continue (a prepared message, written
 * by the async-signal-safe write), then what cli_install_cleanup does (temporaries removed, the signal
 * re-raised). */
static char hint_text[1024];
static size_t hint_length;

static void interrupted(int sig)
{
    if (hint_length && write(STDERR_FILENO, hint_text, hint_length) < 0) hint_length = 0;
    gb_file_remove_temporaries();
    signal(sig, SIG_DFL);
    raise(sig);
}

static void interrupt_hint(const char *scan_path, const char *dir)
{
    const int n = snprintf(hint_text, sizeof hint_text, "\ngomboc scan: interrupted; the finished points are kept in the "
                           "journal: 'gomboc scan %s --out %s --resume' continues from them\n", scan_path, dir);
    hint_length = n > 0 && (size_t)n < sizeof hint_text ? (size_t)n : 0;
    cli_catch_signals(interrupted);
}

/* The running binary's fingerprint (FNV-1a of /proc/self/exe): a journal is resumed by the same build. */
static uint64_t binary_fingerprint(void)
{
    uint64_t hash = 14695981039346656037ull;
    FILE *f = fopen("/proc/self/exe", "rb");
    if (!f) return 0;
    unsigned char buffer[65536];
    size_t n;
    while ((n = fread(buffer, 1, sizeof buffer, f)) > 0)
        for (size_t k = 0; k < n; k++) hash = (hash ^ buffer[k]) * 1099511628211ull;
    fclose(f);
    return hash;
}

/* Is the manifest at `path` that of this scan (the scan file's and base scene's fingerprint) computed by this
 * build? A manifest it cannot read is not. */
static int manifest_is_current(const char *path, const gb_scan *scan)
{
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    char *text = malloc(1 << 20);
    const size_t n = text ? fread(text, 1, (1 << 20) - 1, f) : 0;
    fclose(f);
    if (!text) return 0;
    text[n] = '\0';
    cJSON *root = cJSON_Parse(text);
    free(text);
    char want[17], build[17];
    snprintf(want, sizeof want, "%016" PRIx64, scan->fingerprint);
    snprintf(build, sizeof build, "%016" PRIx64, binary_fingerprint());
    const char *have = cJSON_GetStringValue(cJSON_GetObjectItem(root, "fingerprint"));
    const char *made = cJSON_GetStringValue(cJSON_GetObjectItem(root, "binary"));
    const int current = have && made && !strcmp(have, want) && !strcmp(made, build);
    cJSON_Delete(root);
    return current;
}

typedef struct journal {
    char *path;
    FILE *file;
    char header[160];
} journal;

/* Read an existing journal and verify it line by line (gb_scan_journal_read); only then open it to
 * append, cutting a half-written last line. A journal with any other fault is left as it is. Returns
 * 0, EXIT_INPUT or EXIT_COMPUTE after printing the error. */
static int journal_resume(journal *j, const gb_scan *scan, gb_scan_metrics *results, unsigned char *done, size_t *count)
{
    const size_t points = gb_scan_points(scan), limit = strlen(j->header) + 2 * (points + 1) * (GB_SCAN_JOURNAL_LINE_MAX + 1);
    char *text = NULL;
    size_t size = 0, keep;
    if (gb_file_read(j->path, limit, "journal", "a journal this command wrote", &text, &size) ||
        gb_scan_journal_read(scan, j->path, j->header, text, size, results, done, count, &keep)) {
        free(text);
        fprintf(stderr, "gomboc scan: %s\n", gb_error_message());
        return EXIT_INPUT;
    }
    free(text);
    const int fd = open(j->path, O_WRONLY | O_APPEND | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    struct stat st;
    if (fd < 0 || fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || (size_t)st.st_size != size ||
        (keep < size && ftruncate(fd, (off_t)keep) != 0) || !(j->file = fdopen(fd, "a"))) {
        fprintf(stderr, "gomboc scan: cannot append to the journal '%s': %s\n", j->path,
                fd >= 0 && (size_t)st.st_size != size ? "it changed while it was read" : strerror(errno));
        if (fd >= 0) close(fd);
        return EXIT_COMPUTE;
    }
    /* an empty journal (a kill before its header was written, by an older build) holds no points: its header */
    if (!size && (fputs(j->header, j->file) < 0 || fflush(j->file) != 0)) {
        fprintf(stderr, "gomboc scan: cannot write the journal '%s': %s\n", j->path, strerror(errno));
        return EXIT_COMPUTE;
    }
    return 0;
}

/* A test hook: GOMBOC_TEST_PAUSE_AFTER_POINTS=N stops the process (SIGSTOP) once the journal holds its header and
 * N points of this run, so that a check interrupts the scan at a point the program announces, whatever the
 * machine's load (verify/s8_scan.c). Unset, or not a count, it does nothing. */
static void test_pause(size_t points)
{
    const char *hook = getenv("GOMBOC_TEST_PAUSE_AFTER_POINTS");
    char *end;
    const long after = hook && *hook ? strtol(hook, &end, 10) : -1;
    if (after >= 0 && !*end && (size_t)after == points) raise(SIGSTOP);
}

/* A new journal: its header written whole before its name appears (gb_file_write_new), so that a kill
 * never leaves an empty journal in the way; then opened to append. */
static int journal_create(journal *j)
{
    if (gb_file_write_new(j->path, j->header, strlen(j->header))) {
        fprintf(stderr, "gomboc scan: cannot create the journal: %s\n", gb_error_message());
        return EXIT_COMPUTE;
    }
    const int fd = open(j->path, O_WRONLY | O_APPEND | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0 || !(j->file = fdopen(fd, "a"))) {
        fprintf(stderr, "gomboc scan: cannot open the journal '%s' to append: %s\n", j->path, strerror(errno));
        if (fd >= 0) close(fd);
        return EXIT_COMPUTE;
    }
    test_pause(0);
    return 0;
}

static cJSON *axis_json(const gb_scan_axis *a)
{
    cJSON *o = cJSON_CreateObject();
    char key[72];
    snprintf(key, sizeof key, "%s.%s", a->section, a->key);
    cJSON_AddStringToObject(o, "key", key);
    static const char *const scales[] = {"linear", "pi", "random"};
    cJSON_AddStringToObject(o, "scale", scales[a->scale]);
    if (a->scale == GB_SCAN_RANDOM) {
        cli_json_add(o, "seed", (double)a->seed); /* the column holds k, the k-th attitude drawn */
    } else {
        cli_json_add(o, "from", a->from);
        cli_json_add(o, "to", a->to);
    }
    cli_json_add(o, "count", (double)a->count);
    return o;
}

static int write_outputs(const char *dir, const char *path, const gb_scan *scan, const gb_scan_metrics *results,
                         int ranks, unsigned threads, double seconds, size_t run_here)
{
    gb_file_set set = {0};
    int status = GB_OK;
    char *csv_path = cli_output_name(dir, path, "scan.csv"), *json_path = cli_output_name(dir, path, "scan.json");
    if (!csv_path || !json_path) status = gb_error_set(GB_ENOMEM, "out of memory for an output name");
    FILE *csv = gb_file_set_open(&set, csv_path, &status);
    char row[1024];
    if (csv && !status) status = gb_scan_csv_header(scan, row, sizeof row);
    if (csv && !status && fputs(row, csv) < 0) status = gb_error_set(GB_EIO, "cannot write '%s': %s", csv_path, strerror(errno));
    for (size_t k = 0; !status && k < gb_scan_points(scan); k++) {
        status = gb_scan_csv_row(&results[k], k, row, sizeof row);
        if (!status && fputs(row, csv) < 0) status = gb_error_set(GB_EIO, "cannot write '%s': %s", csv_path, strerror(errno));
    }
    if (csv && !status) status = gb_file_set_seal(&set, 0);
    FILE *json = gb_file_set_open(&set, json_path, &status);
    if (json) {
        cJSON *root = cJSON_CreateObject();
        cJSON_AddStringToObject(root, "scan", scan->path);
        cJSON_AddStringToObject(root, "description", scan->description);
        cJSON_AddStringToObject(root, "base", scan->base);
        cJSON_AddItemToObject(root, "x", axis_json(&scan->axis[0]));
        cJSON_AddItemToObject(root, "y", axis_json(&scan->axis[1]));
        cli_json_add(root, "periods", scan->periods);
        cli_json_add(root, "transient_periods", (double)scan->transient_periods);
        cJSON_AddStringToObject(root, "failed_points", scan->record_failures ? "record" : "stop");
        cli_json_add(root, "points", (double)gb_scan_points(scan));
        const char *names[16];
        const size_t metric_count = gb_scan_metric_names(scan->metrics, names, 16);
        cJSON_AddItemToObject(root, "metrics", cJSON_CreateStringArray(names, (int)metric_count));
        gb_case first;
        if ((scan->metrics & GB_SCAN_CONTACTS) && !gb_scan_point_case(scan, 0, &first) &&
            !gb_dynamics_law_of(first.dynamics.contact_law, first.dynamics.friction)->impacts)
            cJSON_AddStringToObject(cJSON_AddObjectToObject(root, "not_applicable"), "contacts",
                                    "NaN: the base scene's contact law is held, which keeps one contact at all times "
                                    "(no impacts, rest, flight or sliding); the mechanism's columns need contact_law = unilateral");
        cli_manifest_add(cJSON_AddArrayToObject(root, "files"), &set.member[0]);
        char fp[17];
        snprintf(fp, sizeof fp, "%016" PRIx64, scan->fingerprint);
        cJSON_AddStringToObject(root, "fingerprint", fp);
        snprintf(fp, sizeof fp, "%016" PRIx64, binary_fingerprint());
        cJSON_AddStringToObject(root, "binary", fp); /* the build that computed it (--resume: complete for it) */
        cJSON *env = cJSON_AddObjectToObject(root, "environment");
        cJSON_AddStringToObject(env, "parallel", "POSIX threads");
#ifdef GOMBOC_MPI
        cJSON_AddStringToObject(env, "distributed", "MPI");
#else
        cJSON_AddStringToObject(env, "distributed", "none (built without MPI)");
#endif
        cli_json_add(env, "ranks", ranks);
        cli_json_add(env, "threads", threads);
        cJSON *timing = cJSON_AddObjectToObject(root, "timing");
        cli_json_add(timing, "wall_seconds", seconds);
        cli_json_add(timing, "points_run", (double)run_here);
        cli_json_add(timing, "points_per_second", seconds > 0 ? (double)run_here / seconds : 0.0);
        char *text = cJSON_Print(root);
        if (!text || fputs(text, json) < 0 || fputc('\n', json) < 0)
            status = gb_error_set(GB_EIO, "cannot write '%s': %s", json_path, strerror(errno));
        free(text);
        cJSON_Delete(root);
    }
    status = gb_file_set_commit(&set, status);
    free(csv_path);
    free(json_path);
    return status;
}

/* The ranks of the run: one, rank 0, without MPI. Rank 0 alone touches the journal and the outputs. */
typedef struct ranks {
    int rank, size;
    int one_thread; /* MPI without MPI_THREAD_SERIALIZED: the rank's points on one thread */
} ranks;

/* What the callbacks of gb_scan_run share (they run one at a time). */
typedef struct scan_state {
    const gb_scan *scan;
    const ranks *r;
    journal *j;
    gb_scan_metrics *results;
    unsigned char *done;
    size_t points, finished, run_here; /* finished: in the journal; run_here: finished by this run, on any rank */
    double last_report, points_start;   /* points_start: when the points began (the rate's origin) */
    int failed, workers_done;
    char failure[GB_ERROR_MAX];
} scan_state;

/* The first failure is the one reported. */
static void fail_with(scan_state *st, const char *message)
{
    if (st->failed) return;
    snprintf(st->failure, sizeof st->failure, "%s", message);
    st->failed = 1;
}

/* Rank 0: a finished point, as its journal row, appended to the journal and kept. */
static void accept_point(scan_state *st, size_t k, const gb_scan_metrics *m, const char *row)
{
    if (st->failed) return;
    char line[GB_SCAN_JOURNAL_LINE_MAX + 2];
    if (gb_scan_journal_line(st->j->header, row, line, sizeof line) || fputs(line, st->j->file) < 0 ||
        fflush(st->j->file) != 0) {
        char message[sizeof st->failure];
        snprintf(message, sizeof message, "cannot append to the journal '%s': %s (the points before are kept: --resume "
                 "continues from them)", st->j->path, strerror(errno));
        fail_with(st, message);
        return;
    }
    if (!st->done[k]) st->finished++;
    st->results[k] = *m, st->done[k] = 1;
    st->run_here++;
    test_pause(st->run_here);
    const double now = gb_wall_seconds();
    if (now - st->last_report >= 2.0 || st->finished == st->points) {
        const double rate = (double)st->run_here / (now - st->points_start);
        fprintf(stderr, "gomboc scan: %zu of %zu points, %.2f points/s, %.0f s left\n", st->finished, st->points, rate,
                rate > 0 ? (double)(st->points - st->finished) / rate : 0.0);
        st->last_report = now;
    }
}

#ifdef GOMBOC_MPI
/* Messages to rank 0: a point's journal row, a failure's text, the end of a rank's points. */
enum { TAG_ROW = 1, TAG_FAILURE = 2, TAG_DONE = 3 };

/* Rank 0: one message from another rank (waiting for it when `wait`); 1 when one was handled. */
static int receive_one(scan_state *st, int wait)
{
    MPI_Status status;
    int flag = 1;
    if (wait) MPI_Probe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
    else MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
    if (!flag) return 0;
    char text[GB_ERROR_MAX] = "";
    MPI_Recv(text, (int)sizeof text, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    text[sizeof text - 1] = '\0';
    if (status.MPI_TAG == TAG_DONE) st->workers_done++;
    else if (status.MPI_TAG == TAG_FAILURE) fail_with(st, text);
    else {
        size_t index;
        gb_scan_metrics m;
        if (gb_scan_csv_parse(text, &index, &m) || index >= st->points) {
            char message[sizeof st->failure];
            snprintf(message, sizeof message, "rank %d sent a malformed point: %.200s", status.MPI_SOURCE, text);
            fail_with(st, message);
        } else accept_point(st, index, &m, text);
    }
    return 1;
}

static void send_to_root(const char *text, int tag)
{
    MPI_Send(text, (int)strlen(text) + 1, MPI_CHAR, 0, tag, MPI_COMM_WORLD);
}
#endif

/* A status all ranks share: rank 0's. */
static int shared_status(const ranks *r, int status)
{
#ifdef GOMBOC_MPI
    if (r->size > 1) MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
#else
    (void)r;
#endif
    return status;
}

/* gb_scan_run's callbacks: a finished point goes to the journal (rank 0, which then takes the other
 * ranks' messages) or to rank 0; a failure on rank 0's side stops this rank's points. */
static int point_finished(void *user, size_t k, const gb_scan_metrics *m, const char *row)
{
    scan_state *st = user;
    if (st->r->rank == 0) {
        accept_point(st, k, m, row);
#ifdef GOMBOC_MPI
        while (st->r->size > 1 && receive_one(st, 0)) continue;
#endif
        return st->failed ? gb_error_set(GB_EIO, "%s", st->failure) : GB_OK;
    }
#ifdef GOMBOC_MPI
    send_to_root(row, TAG_ROW);
#endif
    return GB_OK;
}

static void point_notice(void *user, const char *message)
{
    (void)user;
    fprintf(stderr, "gomboc scan: %s\n", message);
}

/* Rank 0 reports the Melnikov phase; the points' progress is accept_point's (it counts every rank's). */
static void scan_progress(void *user, const gb_scan_progress *p)
{
    scan_state *st = user;
    if (p->phase == GB_SCAN_PHASE_POINTS) {
        if (!p->done) st->points_start = st->last_report = gb_wall_seconds();
        return;
    }
    if (st->r->rank != 0) return;
    if (!p->done)
        fprintf(stderr, "gomboc scan: the Melnikov margins need %zu reduced model(s) and their integrals at %zu frequency(ies)\n",
                p->models, p->frequencies);
    else if (p->done < p->total)
        fprintf(stderr, "gomboc scan: the Melnikov margins: %zu of %zu models and frequencies, %.0f s\n", p->done, p->total,
                p->seconds);
    else
        fprintf(stderr, "gomboc scan: the Melnikov margins' models and integrals in %.1f s\n", p->seconds);
}

/* Run this rank's share of the points not yet done (gb_scan_run: the i-th of them for i ≡ rank (mod
 * ranks), on `threads` threads); rank 0 journals its own points and those the other ranks send. */
static void run_points(scan_state *st, unsigned threads)
{
    const ranks *r = st->r;
    const gb_scan_runner runner = {.threads = threads, .rank = (size_t)r->rank, .ranks = (size_t)r->size,
                                   .done = st->done, .finished = point_finished, .notice = point_notice,
                                   .progress = scan_progress, .user = st};
    st->points_start = st->last_report = gb_wall_seconds();
    if (gb_scan_run(st->scan, &runner, NULL)) {
#ifdef GOMBOC_MPI
        if (r->rank != 0) send_to_root(gb_error_message(), TAG_FAILURE);
#endif
        fail_with(st, gb_error_message());
    }
#ifdef GOMBOC_MPI
    if (r->rank != 0) send_to_root("", TAG_DONE);
    else
        while (st->workers_done < r->size - 1) receive_one(st, 1);
#endif
}

/* The options of `gomboc scan`, read and checked (--threads as a count, 0 for one per online processor). */
typedef struct scan_options {
    const char *scan_path, *dir, *atlas;
    int resume, threads;
} scan_options;

/* Read the options into *o: -1 to go on, else the exit status (0 for --help). */
static int scan_options_read(int argc, char **argv, scan_options *o)
{
    *o = (scan_options){NULL, ".", NULL, 0, 0};
    const char *threads_text = NULL;
    static const char *const valued[] = {"--out", "--threads", "--atlas", NULL};
    for (int i = 0; i < argc; i++) {
        const char *opt = argv[i], *value = NULL;
        const int positional = cli_positional("scan", opt, &o->scan_path, "scan file", "SCAN");
        if (positional) {
            if (positional == 1) continue;
            return positional;
        }
        if (!strcmp(opt, "--resume")) {
            if (cli_flag("scan", opt, &o->resume)) return EXIT_INPUT;
            continue;
        }
        const int kind = cli_next_option("scan", argc, argv, &i, usage_scan, valued,
                                         " (allowed: --out, --resume, --threads, --atlas, --help)", NULL, NULL, &value);
        if (kind != CLI_VALUE) {
            if (kind == CLI_NEXT) continue;
            return kind == CLI_HELP ? 0 : kind;
        }
        if (!strcmp(opt, "--out")) o->dir = value;
        else if (!strcmp(opt, "--atlas")) o->atlas = value;
        else threads_text = value;
    }
    if (!o->scan_path) return cli_input_error("scan", "missing %s%s", "SCAN", " (allowed: a scan file, e.g. cases/scans/fig10-gomboc-I-omega-A1.ini)");
    if (threads_text) {
        double n;
        if (cli_number("scan", "--threads", threads_text, 1, 256, 0, " (allowed: an integer from 1 to 256)", &n)) return EXIT_INPUT;
        if (n != floor(n)) return cli_input_error("scan", "--threads %s: not an integer (allowed: an integer from 1 to 256)", threads_text);
        o->threads = (int)n;
    }
    return -1;
}

static int scan_command(int argc, char **argv, const ranks *r)
{
    scan_options options;
    const int read = scan_options_read(argc, argv, &options);
    if (read >= 0) return read;
    const char *scan_path = options.scan_path, *dir = options.dir;
    const int resume = options.resume, threads = options.threads;
    /* The outputs are rank 0's: only it checks where they go. */
    journal j = {.path = cli_output_name(dir, scan_path, "scan.journal")};
    int bad = !j.path;
    if (r->rank == 0 && !bad) bad = cli_output_dir_check("scan", "--out", dir);
    if (shared_status(r, bad ? EXIT_INPUT : 0)) {
        free(j.path);
        return EXIT_INPUT;
    }
    gb_scan scan;
    int status = gb_scan_load(scan_path, &scan);
    if (!status && options.atlas) {
        /* as gomboc run --atlas: only for a base scene whose certificate is the atlas */
        gb_case first;
        status = gb_scan_point_case(&scan, 0, &first);
        if (!status && first.dynamics.certificate != GB_CERTIFICATE_ATLAS) {
            gb_scan_free(&scan);
            free(j.path);
            return cli_input_error("scan", "--atlas %s: the base scene %s has no atlas (allowed: a base scene with "
                                   "[model] certificate = atlas)", options.atlas, scan.base);
        }
        scan.atlas_file = options.atlas;
    }
    /* [scan] atlas = shared without --atlas: the atlas beside the outputs (NAME-scan.atlas, or the name
     * [scan] atlas_file gives it), kept for a rerun or --resume */
    char own_atlas[2 * GB_SCAN_PATH_MAX];
    if (!status && scan.atlas_shared && !options.atlas && scan.atlas_name[0]) {
        if ((size_t)snprintf(own_atlas, sizeof own_atlas, "%s/%s", dir, scan.atlas_name) >= sizeof own_atlas)
            status = gb_error_set(GB_EINVAL, "the atlas file's name is too long");
        else
            scan.atlas_file = own_atlas;
    } else if (!status && scan.atlas_shared && !options.atlas) {
        char *name = cli_output_name(dir, scan_path, "scan.atlas");
        if (!name || strlen(name) >= sizeof own_atlas) status = gb_error_set(GB_EINVAL, "the atlas file's name is too long");
        else snprintf(own_atlas, sizeof own_atlas, "%s", name), scan.atlas_file = own_atlas;
        free(name);
    }
    if (!status && r->rank == 0) {
        char *csv_path = cli_output_name(dir, scan_path, "scan.csv"), *json_path = cli_output_name(dir, scan_path, "scan.json");
        char named[GB_SCAN_PATH_MAX + 48]; /* [scan] atlas_file by its line */
        snprintf(named, sizeof named, "%s:%d: [scan] atlas_file", scan_path, scan.atlas_name_line);
        const gb_file_use uses[] = {
            GB_FILE_USE(scan_path, "SCAN", GB_FILE_INPUT), GB_FILE_USE(scan.base, "[scan] base", GB_FILE_INPUT),
            GB_FILE_USE(csv_path, "--out", GB_FILE_OUTPUT), GB_FILE_USE(json_path, "--out", GB_FILE_OUTPUT),
            GB_FILE_USE(j.path, "--out (the journal)", GB_FILE_INPUT | GB_FILE_OUTPUT),
            GB_FILE_CACHE_USE(scan.atlas_file, options.atlas ? "--atlas" : scan.atlas_name[0] ? named : "--out (the atlas)",
                              "an atlas file", GB_ATLAS_FILE_MAGIC, sizeof GB_ATLAS_FILE_MAGIC)};
        bad = !csv_path || !json_path || cli_files_check("scan", uses, sizeof uses / sizeof uses[0]);
        free(csv_path);
        free(json_path);
    }
    if (!status && shared_status(r, bad ? EXIT_INPUT : 0)) {
        gb_scan_free(&scan);
        free(j.path);
        return EXIT_INPUT;
    }
#ifdef GOMBOC_MPI
    int anywhere = status != 0;
    if (r->size > 1) MPI_Allreduce(MPI_IN_PLACE, &anywhere, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (anywhere && !status) {
        gb_scan_free(&scan);
        fprintf(stderr, "gomboc scan: another rank could not read '%s' or its base scene (allowed: paths every rank "
                "can read)\n", scan_path);
        free(j.path);
        return EXIT_INPUT;
    }
#endif
    if (status) {
        free(j.path);
        return cli_failure("scan", status);
    }
    if (cli_parse_only) {
        gb_scan_free(&scan);
        free(j.path);
        return 0;
    }
    /* a directory another process holds locked is reported now, not after the points */
    int held = r->rank == 0 && cli_lock_probe("scan", j.path, "checking that the outputs can be written");
    if (!held && r->rank == 0 && scan.atlas_file)
        held = cli_lock_probe("scan", scan.atlas_file, "checking that the shared atlas can be written");
    if (shared_status(r, held ? EXIT_COMPUTE : 0)) {
        gb_scan_free(&scan);
        free(j.path);
        return EXIT_COMPUTE;
    }
    /* --resume without a journal: a scan whose manifest says it is complete has nothing to resume (said,
     * nothing computed, exit 0); with neither, the scan starts (make scans resumes or starts alike) */
    int nothing = 0;
    if (resume && r->rank == 0) {
        struct stat jst, mst;
        char *json_path = cli_output_name(dir, scan_path, "scan.json");
        if (lstat(j.path, &jst) != 0 && json_path && lstat(json_path, &mst) == 0 && S_ISREG(mst.st_mode)) {
            nothing = manifest_is_current(json_path, &scan);
            if (nothing)
                fprintf(stderr, "gomboc scan: nothing to resume: '%s' holds no journal and the scan is complete ('%s'); "
                        "run it without --resume to compute it again\n", dir, json_path);
            else
                fprintf(stderr, "gomboc scan: '%s' is of another scan file, base scene or build: the scan starts anew\n",
                        json_path);
        }
        free(json_path);
    }
    if (shared_status(r, nothing)) {
        gb_scan_free(&scan);
        free(j.path);
        return 0;
    }
    const size_t points = gb_scan_points(&scan);
    gb_scan_metrics *results = calloc(points, sizeof *results);
    unsigned char *done = calloc(points, 1);
    size_t already = 0;
    int exit_status = 0;
    if (!results || !done) {
        fprintf(stderr, "gomboc scan: out of memory for %zu points\n", points);
        exit_status = EXIT_COMPUTE;
    }
    if (r->rank == 0) {
        gb_scan_journal_header(&scan, binary_fingerprint(), j.header, sizeof j.header);
        struct stat st;
        int exists = lstat(j.path, &st) == 0;
        if (!exit_status && exists && !resume && S_ISREG(st.st_mode) && st.st_size == 0 && unlink(j.path) == 0)
            exists = 0; /* an empty journal holds no points: a fresh start replaces it */
        if (!exit_status && exists && !resume) {
            fprintf(stderr, "gomboc scan: a journal of an unfinished scan exists: '%s' (allowed: --resume to finish it, or "
                    "remove it to start again)\n", j.path);
            exit_status = EXIT_INPUT;
        }
        if (!exit_status) exit_status = exists ? journal_resume(&j, &scan, results, done, &already) : journal_create(&j);
        if (!exit_status) interrupt_hint(scan_path, dir);
    }
#ifdef GOMBOC_MPI
    if (r->size > 1) { /* every rank learns what is done (or that nothing will be) */
        int root_status = exit_status, no_memory = !results || !done;
        MPI_Allreduce(MPI_IN_PLACE, &no_memory, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
        MPI_Bcast(&root_status, 1, MPI_INT, 0, MPI_COMM_WORLD);
        exit_status = root_status ? root_status : no_memory ? EXIT_COMPUTE : 0;
        if (!exit_status) MPI_Bcast(done, (int)points, MPI_UNSIGNED_CHAR, 0, MPI_COMM_WORLD);
    }
#endif

    const unsigned used_threads = r->one_thread ? 1u : gb_scan_threads((unsigned)threads);
    scan_state st = {.scan = &scan, .r = r, .j = &j, .results = results, .done = done, .points = points, .finished = already};
    const double start = gb_wall_seconds();
    if (!exit_status) {
        if (already && r->rank == 0)
            fprintf(stderr, "gomboc scan: %s: resuming, %zu of %zu points in the journal\n", scan_path, already, points);
        run_points(&st, used_threads);
        if (st.failed) {
            fprintf(stderr, "gomboc scan: %s: %s\n", scan_path, st.failure);
            exit_status = EXIT_COMPUTE;
        }
    }
    const double seconds = gb_wall_seconds() - start;
    if (j.file && fclose(j.file) != 0 && !exit_status) {
        fprintf(stderr, "gomboc scan: cannot close the journal '%s': %s\n", j.path, strerror(errno));
        exit_status = EXIT_COMPUTE;
    }
    /* A failed scan keeps the journal only when it holds finished points: one with none would only
     * stand in the way of the next run. */
    if (exit_status == EXIT_COMPUTE && j.file && r->rank == 0) {
        if (st.finished == 0) unlink(j.path);
        else
            fprintf(stderr, "gomboc scan: the %zu finished points are kept in '%s': --resume continues from them while the "
                    "scan file and its base scene are unchanged; remove it to start again\n", st.finished, j.path);
    }
    if (!exit_status && r->rank == 0) {
        status = write_outputs(dir, scan_path, &scan, results, r->size, used_threads, seconds, st.run_here);
        if (status) exit_status = cli_failure("scan", status);
        else if (unlink(j.path) != 0) {
            fprintf(stderr, "gomboc scan: cannot remove the finished journal '%s': %s\n", j.path, strerror(errno));
            exit_status = EXIT_COMPUTE;
        } else {
            fprintf(stderr, "gomboc scan: %s: %zu points (%zu run now) in %.1f s on %d rank(s) of %u thread(s)\n",
                    scan_path, points, st.run_here, seconds, r->size, used_threads);
        }
    }
    free(results);
    free(done);
    free(j.path);
    gb_scan_free(&scan);
    return exit_status;
}

int command_scan(int argc, char **argv)
{
    ranks r = {0, 1, 0};
#ifdef GOMBOC_MPI
    /* The ranks' points run on threads; their messages pass one at a time (the journal's critical section). */
    int provided = 0, initialized = 0;
    MPI_Initialized(&initialized);
    if (!initialized) MPI_Init_thread(NULL, NULL, MPI_THREAD_SERIALIZED, &provided);
    else MPI_Query_thread(&provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &r.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &r.size);
    r.one_thread = provided < MPI_THREAD_SERIALIZED && r.size > 1;
    /* Rank 0 speaks for all: the others' messages would repeat its own, and theirs reach it by message. */
    if (r.rank != 0) {
        FILE *quiet = freopen("/dev/null", "w", stderr);
        (void)quiet;
    }
    const int status = scan_command(argc, argv, &r);
    if (!initialized) MPI_Finalize();
    return status;
#else
    return scan_command(argc, argv, &r);
#endif
}
