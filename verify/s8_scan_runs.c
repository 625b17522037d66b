/* Section 8.3: a scan that survives its machine: the library's parallel runner on threads and ranks, a kill -9 and
 * --resume, a journal verified line by line and never trusted, a disk that fills, a point out of its key's range,
 * and MPI ranks where an MPI build exists. The CSV of a scan must not depend on any of them. The binary comes from
 * $GOMBOC_BIN (the MPI one from $GOMBOC_MPI_BIN, launched by $GOMBOC_MPIRUN). */
#include "gb_check.h"
#include "gb_error.h"
#include "gb_run.h"
#include "gb_scan_internal.h"
#include "gb_seal.h"
#include "s8_scan.h"
#include "verify_sections.h"

#include <cjson/cJSON.h>
#include <dirent.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

/* ---- the library's runner ------------------------------------------------------------------------ */

enum { RUNNER_POINTS = 6 };

/* What a runner's callbacks saw: each point's row and how often it came, the progress reports. */
typedef struct runner_seen {
    char row[RUNNER_POINTS][1024];
    int calls[RUNNER_POINTS];
    size_t finished, progress_calls, progress_bad, last_done, stop_after;
    int points_started, points_ended;
} runner_seen;

static int seen_finished(void *user, size_t index, const gb_scan_metrics *metrics, const char *row)
{
    (void)metrics;
    runner_seen *seen = user;
    if (index < RUNNER_POINTS) snprintf(seen->row[index], sizeof seen->row[index], "%s", row), seen->calls[index]++;
    if (++seen->finished == seen->stop_after) return gb_error_set(GB_EIO, "the caller stops the scan here");
    return GB_OK;
}

static void seen_progress(void *user, const gb_scan_progress *p)
{
    runner_seen *seen = user;
    seen->progress_calls++;
    if (p->phase != GB_SCAN_PHASE_POINTS || p->done > p->total || (p->done && p->done < seen->last_done)) seen->progress_bad++;
    if (!p->done) seen->points_started++;
    if (p->done == p->total) seen->points_ended++;
    seen->last_done = p->done;
}

static int runner_run(const gb_scan *scan, unsigned threads, size_t rank, size_t ranks, const unsigned char *done,
                      runner_seen *seen, size_t *points_run)
{
    const gb_scan_runner runner = {.threads = threads, .rank = rank, .ranks = ranks, .done = done,
                                   .finished = seen_finished, .progress = seen_progress, .user = seen};
    return gb_scan_run(scan, &runner, points_run);
}

/* gb_scan_run, the library's runner, against each point run alone (gb_scan_point_run, then its CSV row): on
 * 1 and 2 threads, as rank 0 and rank 1 of 2 (which share the points, each once), with points already
 * done left out, stopped by its caller, and refusing a runner out of range. */
static void test_library_runner(void)
{
    s8_scan_dir d;
    gb_check c = {"8.3", "-", "gb_scan_run on 1 and 2 threads: 3 x 2 points (omega, A2), 4 periods, every row",
                  "each point run alone (gb_scan_point_run), its CSV row", "exact (byte for byte), each point once"};
    if (s8_make_scan_dir(&d, &c)) return;
    static const char text[] = "[scan]\ndescription = the runner's scan\nbase = base.ini\nperiods = 4\n"
                               "transient_periods = 1\nmetrics = omega_rms, switch_rate, strobe_sd\n"
                               "[x]\nkey = forcing.omega\nfrom = 16\nto = 20\ncount = 3\n"
                               "[y]\nkey = forcing.A2\nfrom = 0.5\nto = 1.5\ncount = 2\n";
    gb_scan scan;
    if (s8_spill(d.scan, text) || gb_scan_load(d.scan, &scan)) {
        gb_check_true(&c, 0, "cannot load the scan: %s", gb_error_message());
        s8_remove_scan_dir(&d);
        return;
    }
    char alone[RUNNER_POINTS][1024];
    int status = gb_scan_points(&scan) == RUNNER_POINTS ? GB_OK : GB_EINVAL;
    for (size_t k = 0; k < RUNNER_POINTS && !status; k++) {
        gb_scan_metrics m;
        status = gb_scan_point_run(&scan, k, &m);
        if (!status) status = gb_scan_csv_row(&m, k, alone[k], sizeof alone[k]);
    }
    static runner_seen one, two, rank0, rank1, partial, stopped;
    size_t run_one = 0, run_two = 0, run0 = 0, run1 = 0, run_partial = 0, run_stopped = 0;
    const int s1 = status ? status : runner_run(&scan, 1, 0, 1, NULL, &one, &run_one);
    const int s2 = status ? status : runner_run(&scan, 2, 0, 1, NULL, &two, &run_two);
    int same = 0, once = 0;
    for (int k = 0; k < RUNNER_POINTS; k++) {
        same += !strcmp(one.row[k], alone[k]) && !strcmp(two.row[k], alone[k]);
        once += one.calls[k] == 1 && two.calls[k] == 1;
    }
    gb_check_true(&c, !status && !s1 && !s2 && same == RUNNER_POINTS && once == RUNNER_POINTS && run_one == RUNNER_POINTS &&
                  run_two == RUNNER_POINTS, "%s; statuses %d, %d; %d of %d rows the same, %d each once; %zu and %zu run",
                  status ? gb_error_message() : "alone ran", s1, s2, same, RUNNER_POINTS, once, run_one, run_two);
    gb_check cp = {"8.3", "-", "gb_scan_run's progress reports (points phase)",
                   "one at the start (done 0), one at the end (done = total), done never decreasing", "exact"};
    gb_check_true(&cp, one.progress_bad == 0 && one.points_started == 1 && one.points_ended == 1 && one.last_done == RUNNER_POINTS &&
                  two.progress_bad == 0 && two.points_started == 1 && two.points_ended == 1,
                  "%zu and %zu reports, %zu and %zu out of order, starts %d, %d, ends %d, %d", one.progress_calls,
                  two.progress_calls, one.progress_bad, two.progress_bad, one.points_started, two.points_started,
                  one.points_ended, two.points_ended);

    const int r0 = status ? status : runner_run(&scan, 2, 0, 2, NULL, &rank0, &run0);
    const int r1 = status ? status : runner_run(&scan, 2, 1, 2, NULL, &rank1, &run1);
    int shared = 0;
    for (int k = 0; k < RUNNER_POINTS; k++)
        shared += rank0.calls[k] + rank1.calls[k] == 1 && !strcmp(rank0.calls[k] ? rank0.row[k] : rank1.row[k], alone[k]);
    gb_check cr = {"8.3", "-", "gb_scan_run as rank 0 and as rank 1 of 2 (2 threads each)",
                   "every point once, on one rank, its row the point's own", "exact"};
    gb_check_true(&cr, !r0 && !r1 && shared == RUNNER_POINTS && run0 + run1 == RUNNER_POINTS && run0 == RUNNER_POINTS / 2,
                  "statuses %d, %d; %d of %d points once and the same; %zu + %zu run", r0, r1, shared, RUNNER_POINTS, run0, run1);

    const unsigned char done[RUNNER_POINTS] = {1, 0, 1, 0, 0, 1};
    const int sp = status ? status : runner_run(&scan, 2, 0, 1, done, &partial, &run_partial);
    int left_out = 0;
    for (int k = 0; k < RUNNER_POINTS; k++)
        left_out += done[k] ? partial.calls[k] == 0 : partial.calls[k] == 1 && !strcmp(partial.row[k], alone[k]);
    gb_check cd = {"8.3", "-", "gb_scan_run with points 0, 2 and 5 done already (a journal's)",
                   "those never run, the others once with their own rows", "exact"};
    gb_check_true(&cd, !sp && left_out == RUNNER_POINTS && run_partial == 3, "status %d; %d of %d as they should; %zu run", sp,
                  left_out, RUNNER_POINTS, run_partial);

    stopped.stop_after = 2;
    const int ss = status ? status : runner_run(&scan, 1, 0, 1, NULL, &stopped, &run_stopped);
    const unsigned char none[RUNNER_POINTS] = {0};
    const gb_scan_runner wide = {.threads = 257, .done = none}, beyond = {.rank = 2, .ranks = 2};
    const int sw = gb_scan_run(&scan, &wide, NULL), sb = gb_scan_run(&scan, &beyond, NULL);
    gb_check cs = {"8.3", "-", "gb_scan_run stopped by its caller's second finished point; 257 threads; rank 2 of 2",
                   "the caller's status and message, no point after; GB_EINVAL twice", "exact"};
    gb_check_true(&cs, ss == GB_EIO && stopped.finished == 2 && run_stopped == 1 && sw == GB_EINVAL && sb == GB_EINVAL,
                  "status %d (%s), %zu finished, %zu counted; %d, %d", ss, ss ? gb_error_message() : "", stopped.finished,
                  run_stopped, sw, sb);
    gb_error_clear();
    gb_scan_free(&scan);
    s8_remove_scan_dir(&d);
}

/* ---- threads, interruption and resume ----------------------------------------------------------- */

static size_t lines_of(const char *path)
{
    FILE *f = fopen(path, "r");
    size_t n = 0;
    for (int ch; f && (ch = fgetc(f)) != EOF;) n += ch == '\n';
    if (f) fclose(f);
    return n;
}

/* Start `gomboc scan` on one thread, its standard error into `err` (a file of the test's directory), with SIGINT
 * at `sigint` (SIG_DFL, or SIG_IGN as a background job's) whatever this harness inherited, and the program's own
 * test hook (GOMBOC_TEST_PAUSE_AFTER_POINTS) stopping it once its journal holds `lines` lines (the header and
 * lines − 1 points); then send it `sig` and let it continue. The wait status. No polling and no timing: the
 * same under any load and any parent. */
static int signalled_scan_with(const s8_scan_dir *d, size_t lines, int sig, const char *err, void (*sigint)(int))
{
    char points[32];
    snprintf(points, sizeof points, "%zu", lines - 1);
    const pid_t pid = fork();
    if (pid == 0) {
        signal(SIGINT, sigint);
        signal(SIGTERM, SIG_DFL);
        sigset_t none;
        sigemptyset(&none);
        sigprocmask(SIG_SETMASK, &none, NULL);
        setenv("GOMBOC_TEST_PAUSE_AFTER_POINTS", points, 1);
        if (!freopen(err, "w", stderr)) _exit(127);
        execl(s8_binary(), s8_binary(), "scan", d->scan, "--out", d->path, "--threads", "1", (char *)NULL);
        _exit(127);
    }
    int wstatus = 0;
    waitpid(pid, &wstatus, WUNTRACED); /* stopped by the hook, or ended before it (a failure the caller sees) */
    if (WIFSTOPPED(wstatus)) {
        kill(pid, sig);
        kill(pid, SIGCONT);
        waitpid(pid, &wstatus, 0);
    }
    return wstatus;
}

static int signalled_scan(const s8_scan_dir *d, size_t lines, int sig, const char *err)
{
    return signalled_scan_with(d, lines, sig, err, SIG_DFL);
}

/* kill -9 once the journal holds `lines` lines. */
static int killed_scan(const s8_scan_dir *d, size_t lines)
{
    char err[320];
    snprintf(err, sizeof err, "%s/killed.txt", d->path);
    const int wstatus = signalled_scan(d, lines, SIGKILL, err);
    remove(err);
    return wstatus;
}

static void test_threads_and_resume(void)
{
    s8_scan_dir d;
    char out[1 << 14];
    gb_check ct = {"8.3", "-", "scan CSV on 1 and on 2 threads", "byte for byte", "exact"};
    if (s8_make_scan_dir(&d, &ct)) return;
    const int c1 = s8_scan_run(&d, "--threads 1", out, sizeof out);
    char *one = gb_check_read_file(d.csv);
    const int c2 = s8_scan_run(&d, "--threads 2", out, sizeof out);
    char *two = gb_check_read_file(d.csv);
    gb_check_true(&ct, c1 == 0 && c2 == 0 && one && two && !strcmp(one, two), "exits %d, %d; %s", c1, c2,
                  one && two && !strcmp(one, two) ? "identical" : "different");
    free(two);

    /* Kill the scan once its journal holds two points, leave half a line behind, resume. */
    remove(d.csv);
    const int wstatus = killed_scan(&d, 3);
    const size_t kept = lines_of(d.journal);
    FILE *j = fopen(d.journal, "a");
    if (j) fputs("7,18.5,0.7", j), fclose(j); /* a line cut off by the kill */
    const int cr = s8_scan_run(&d, "--resume", out, sizeof out);
    char *resumed = gb_check_read_file(d.csv);
    gb_check ck = {"8.3", "-", "scan CSV after a kill -9 with 2 or more points in the journal, a half-written line, and --resume",
                   "the uninterrupted run's CSV, byte for byte", "exact"};
    gb_check_true(&ck, WIFSIGNALED(wstatus) && kept >= 3 && kept < 1 + SCAN_POINTS && cr == 0 && resumed && one &&
                  !strcmp(one, resumed) && access(d.journal, F_OK) != 0,
                  "killed with %zu journal lines; resume exit %d; %s; journal %s", kept, cr,
                  resumed && one && !strcmp(one, resumed) ? "identical" : "different",
                  access(d.journal, F_OK) ? "removed" : "left");
    free(resumed);

    /* Ctrl-C: the scan says how to continue, and --resume does. */
    remove(d.csv);
    char err[320];
    snprintf(err, sizeof err, "%s/interrupted.txt", d.path);
    const int istatus = signalled_scan(&d, 3, SIGINT, err);
    char *said = gb_check_read_file(err);
    const int ci = s8_scan_run(&d, "--resume", out, sizeof out);
    char *continued = gb_check_read_file(d.csv);
    gb_check cint = {"8.3", "-", "scan interrupted by SIGINT (Ctrl-C) with 2 or more points in the journal",
                     "says how to resume (the scan file, --out and --resume on standard error), and --resume gives the "
                     "uninterrupted run's CSV", "exact"};
    gb_check_true(&cint, WIFSIGNALED(istatus) && WTERMSIG(istatus) == SIGINT && said && strstr(said, "--resume") &&
                  strstr(said, d.scan) && ci == 0 && continued && one && !strcmp(one, continued),
                  "signal %d; said: %.200s; resume exit %d; %s", WIFSIGNALED(istatus) ? WTERMSIG(istatus) : 0,
                  said ? said : "(nothing)", ci, continued && one && !strcmp(one, continued) ? "identical" : "different");
    free(said);
    free(continued);
    remove(err);

    /* SIGINT ignored by the scan's parent (a background job, nohup): it stays ignored, the scan runs to its end. */
    remove(d.csv);
    const int gstatus = signalled_scan_with(&d, 3, SIGINT, err, SIG_IGN);
    char *whole = gb_check_read_file(d.csv);
    gb_check cg = {"8.3", "-", "scan started with SIGINT ignored (as by a background job), sent SIGINT with 2 points in the journal",
                   "the signal stays ignored: exit 0 with the uninterrupted run's CSV", "exact"};
    gb_check_true(&cg, WIFEXITED(gstatus) && WEXITSTATUS(gstatus) == 0 && whole && one && !strcmp(one, whole),
                  "wait status %d; %s", gstatus, whole && one && !strcmp(one, whole) ? "identical" : "different");
    free(whole);
    remove(err);

    /* A journal of another scan (another header), and a malformed line: refused, the journal kept. */
    s8_spill(d.journal, "gomboc scan journal 1: scan 0000000000000000, binary 0000000000000000, 9 points\n");
    const int cm = s8_scan_run(&d, "--resume", out, sizeof out);
    gb_check cj = {"8.3", "-", "--resume with the journal of another scan", "refused (exit 2), the journal kept", "exact"};
    gb_check_true(&cj, cm == 2 && strstr(out, "not this scan's journal") && access(d.journal, F_OK) == 0, "exit %d: %.200s", cm, out);
    remove(d.journal);
    const int first = s8_scan_run(&d, "--threads 1", out, sizeof out); /* a complete run: no journal left */
    /* The header this binary writes, from a run killed at once (the header is written first). */
    char header[256] = "";
    killed_scan(&d, 1);
    FILE *h = fopen(d.journal, "r");
    if (h && !fgets(header, sizeof header, h)) header[0] = '\0';
    if (h) fclose(h);
    char bad[512];
    snprintf(bad, sizeof bad, "%s0,not a number\n", header);
    s8_spill(d.journal, bad);
    const int cb = s8_scan_run(&d, "--resume", out, sizeof out);
    gb_check cb2 = {"8.3", "-", "--resume with a malformed journal line", "refused (exit 2) naming the line, the journal kept", "exact"};
    gb_check_true(&cb2, first == 0 && header[0] && cb == 2 && strstr(out, "map-scan.journal:2: no seal at its end") &&
                       access(d.journal, F_OK) == 0,
                  "exit %d: %.200s", cb, out);
    /* An empty journal (a kill before the header of an older build's journal was written) holds no points: it
     * neither blocks --resume nor a fresh start, and both give the uninterrupted CSV. */
    int empty_codes[2];
    char *empty_csv[2];
    for (int k = 0; k < 2; k++) {
        remove(d.csv);
        s8_spill(d.journal, "");
        empty_codes[k] = s8_scan_run(&d, k ? "--threads 1" : "--resume --threads 1", out, sizeof out);
        empty_csv[k] = gb_check_read_file(d.csv);
    }
    gb_check ce = {"8.3", "-", "an empty journal, then --resume, and then a fresh start", "both exit 0 with the uninterrupted "
                   "run's CSV, byte for byte; no journal left", "exact"};
    gb_check_true(&ce, empty_codes[0] == 0 && empty_codes[1] == 0 && one && empty_csv[0] && empty_csv[1] &&
                       !strcmp(one, empty_csv[0]) && !strcmp(one, empty_csv[1]) && access(d.journal, F_OK) != 0,
                  "exits %d, %d: %.200s", empty_codes[0], empty_codes[1], out);
    free(empty_csv[0]), free(empty_csv[1]);
    /* The scan is complete now (its manifest beside the CSV, no journal): --resume has nothing to resume, says
     * so and runs no point, leaving the CSV as it was; a CSV whose point it ran again would be rewritten. */
    struct stat before, after;
    const int had = stat(d.csv, &before);
    const int cr2 = s8_scan_run(&d, "--resume", out, sizeof out);
    char *csv_after = gb_check_read_file(d.csv);
    const int same = had == 0 && stat(d.csv, &after) == 0 && before.st_mtim.tv_sec == after.st_mtim.tv_sec &&
                     before.st_mtim.tv_nsec == after.st_mtim.tv_nsec && csv_after && one && !strcmp(csv_after, one);
    gb_check cn = {"8.3", "-", "--resume on a complete scan", "exit 0, 'nothing to resume' on standard error, no point run, "
                   "the CSV untouched (same bytes and modification time)", "exact"};
    gb_check_true(&cn, cr2 == 0 && strstr(out, "nothing to resume") && !strstr(out, "points (") && same, "exit %d: %.200s", cr2, out);
    free(csv_after);
    /* the same outputs, the scan file changed (a comment appended): they are another scan's, and it starts anew */
    FILE *edit = fopen(d.scan, "a");
    if (edit) fputs("; changed\n", edit), fclose(edit);
    const int cr3 = s8_scan_run(&d, "--resume", out, sizeof out);
    gb_check cs = {"8.3", "-", "--resume beside the outputs of another scan file (the same one with a comment added)",
                   "exit 0, the scan run anew", "exact"};
    gb_check_true(&cs, cr3 == 0 && strstr(out, "starts anew") && strstr(out, "points ("), "exit %d: %.200s", cr3, out);
    free(one);
    s8_remove_scan_dir(&d);
}

/* ---- a journal is verified, never trusted ----------------------------------------------------------- */

/* The journal's lines (the header first) as a NULL-terminated array of malloc'd strings, each with its
 * '\n'; NULL when there is none. */
static char **journal_lines(const char *path, size_t *count)
{
    char *text = gb_check_read_file(path);
    *count = 0;
    if (!text) return NULL;
    char **lines = calloc(strlen(text) + 2, sizeof *lines);
    for (char *p = text; lines && *p;) {
        char *end = strchr(p, '\n');
        const size_t n = end ? (size_t)(end - p) + 1 : strlen(p);
        lines[(*count)++] = strndup(p, n);
        p += n;
    }
    free(text);
    return lines;
}

static void free_lines(char **lines)
{
    for (size_t k = 0; lines && lines[k]; k++) free(lines[k]);
    free(lines);
}

/* A journal made of `lines` with line `which` replaced by `replacement` (or the lines as they are). */
static int spill_lines(const char *path, char *const *lines, size_t count, size_t which, const char *replacement,
                       size_t replacement_size)
{
    FILE *f = fopen(path, "wb");
    if (!f) return 1;
    for (size_t k = 0; k < count; k++) {
        if (k == which) fwrite(replacement, 1, replacement_size, f);
        else fputs(lines[k], f);
    }
    return fclose(f) != 0;
}

/* Line `line` (a point's) with its `field`-th comma-separated field replaced by `value`, and its seal:
 * SEAL_KEPT, the old one; SEAL_KEYED, recomputed with this user's key (a row this program would write,
 * for the checks behind the seal); SEAL_FORGED, recomputed as a forger without the key can (an unkeyed
 * BLAKE2b-256 of the same bytes, as a checksum would be recomputed). */
enum { SEAL_KEPT = 0, SEAL_KEYED = 1, SEAL_FORGED = 2 };
static void edited_line(const char *header, const char *line, int field, const char *value, int sign, char *out, size_t cap)
{
    char row[2048];
    size_t n = 0;
    int at = 0;
    const char *p = line;
    const size_t body = strlen(line) - (2 * GB_SEAL_BYTES + 2); /* without ",<64 hex>\n" */
    while ((size_t)(p - line) < body) {
        const char *comma = memchr(p, ',', body - (size_t)(p - line));
        const size_t len = comma ? (size_t)(comma - p) : body - (size_t)(p - line);
        n += (size_t)snprintf(row + n, sizeof row - n, "%s%.*s", at ? "," : "", (int)(at == field ? strlen(value) : len),
                              at == field ? value : p);
        at++;
        p += len + (comma != NULL);
        if (!comma) break;
    }
    snprintf(row + n, sizeof row - n, "\n");
    if (sign == SEAL_KEYED) {
        gb_scan_journal_line(header, row, out, cap);
    } else if (sign == SEAL_FORGED) {
        unsigned char digest[GB_SEAL_BYTES];
        char hex[GB_SEAL_HEX];
        const gb_seal_piece pieces[2] = {{header, strlen(header)}, {row, strlen(row) - 1}};
        gb_seal_digest(pieces, 2, digest);
        gb_seal_hex(digest, hex);
        snprintf(out, cap, "%.*s,%s\n", (int)(strlen(row) - 1), row, hex);
    } else {
        snprintf(out, cap, "%.*s%s", (int)(strlen(row) - 1), row, line + body);
    }
}

static void test_journal_verified(void)
{
    s8_scan_dir d;
    char out[1 << 14];
    gb_check c = {"8.3", "-", "--resume with a journal edited or damaged in its middle, one way a row",
                  "refused with exit 2 naming the line and the fault, the journal byte for byte as it was", "exact"};
    if (s8_make_scan_dir(&d, &c)) return;
    const int wstatus = killed_scan(&d, 5); /* the header and at least 4 points */
    size_t count = 0;
    char **lines = journal_lines(d.journal, &count);
    if (!WIFSIGNALED(wstatus) || !lines || count < 5 || count >= 1 + SCAN_POINTS) {
        gb_check_true(&c, 0, "the killed scan left %zu journal lines", count);
        free_lines(lines);
        s8_remove_scan_dir(&d);
        return;
    }
    const char *header = lines[0];
    char nan_line[2048], metric[2048], forged[2048], fingerprint[2048], coordinate[2048], duplicate[2048], too_long[2048],
        negative[2048];
    edited_line(header, lines[2], 0, "-1", SEAL_KEYED, negative, sizeof negative); /* a point index of -1, re-sealed */
    edited_line(header, lines[2], 1, "17", SEAL_KEYED, coordinate, sizeof coordinate); /* x of another point, re-sealed */
    edited_line(header, lines[2], 3, "0.25", SEAL_KEPT, metric, sizeof metric);       /* omega_rms edited */
    edited_line(header, lines[2], 3, "0.5", SEAL_FORGED, forged, sizeof forged);      /* ... and its digest recomputed */
    edited_line(header, lines[2], 17, "0123456789abcdef", SEAL_KEPT, fingerprint, sizeof fingerprint);
    const char *nan_at = strstr(lines[2], ",nan,");
    snprintf(nan_line, sizeof nan_line, "%s", lines[2]);
    if (nan_at) memcpy(nan_line + (nan_at - lines[2]) + 1, "0.5", 3); /* a NaN made a number (none: the row stays, and fails) */
    edited_line(header, lines[2], 3, "0.25", SEAL_KEYED, duplicate, sizeof duplicate); /* line 2's point again, re-sealed */
    memset(too_long, '7', 1500);
    snprintf(too_long + 1500, sizeof too_long - 1500, "\n");
    char with_nul[2048];
    const size_t nul_size = strlen(lines[2]);
    memcpy(with_nul, lines[2], nul_size);
    with_nul[5] = '\0';
    char garbage[256];
    snprintf(garbage, sizeof garbage, "gomboc scan journal 3: \x1b[31mred\x07 %0180d\n", 7);
    const struct {
        const char *what;
        size_t line;
        const char *text;
        size_t size;
        const char *must;
    } faults[] = {
        {"a coordinate edited (x = 17), re-sealed with the key", 2, coordinate, strlen(coordinate), "do not read back to the same row"},
        {"a metric edited", 2, metric, strlen(metric), "seal does not verify"},
        {"a metric edited (0.5), its digest recomputed without the key", 2, forged, strlen(forged), "seal does not verify"},
        {"a NaN made a number", 2, nan_line, strlen(nan_line), "seal does not verify"},
        {"a fingerprint edited", 2, fingerprint, strlen(fingerprint), "seal does not verify"},
        {"line 2's point again with another value, re-sealed", 3, duplicate, strlen(duplicate), "a second time, with other values"},
        {"a NUL byte", 2, with_nul, nul_size, "a NUL byte"},
        {"a point index of -1, re-sealed", 2, negative, strlen(negative), "not a row of this command"},
        {"a line of 1500 bytes", 2, too_long, strlen(too_long), "1500 bytes long"},
        {"a header with escape and bell characters", 0, garbage, strlen(garbage), "its header: 'gomboc scan journal 3: ?[31mred? 000"},
    };
    size_t refused = 0;
    const size_t total = sizeof faults / sizeof faults[0];
    char report[4096] = "";
    for (size_t k = 0; k < total; k++) {
        spill_lines(d.journal, lines, count, faults[k].line, faults[k].text, faults[k].size);
        char *before = gb_check_read_file(d.journal);
        const int code = s8_scan_run(&d, "--resume --threads 1", out, sizeof out);
        char *after = gb_check_read_file(d.journal);
        char where[64];
        snprintf(where, sizeof where, "map-scan.journal:%zu: ", faults[k].line + 1);
        const int ok = code == 2 && strstr(out, faults[k].must) && (faults[k].line == 0 || strstr(out, where)) &&
                       strstr(out, "remove it to start again") && before && after && !memcmp(before, after, strlen(before)) &&
                       access(d.csv, F_OK) != 0 && !strchr(out, '\x1b');
        refused += ok;
        if (!ok && strlen(report) < 3000)
            snprintf(report + strlen(report), sizeof report - strlen(report), "[%s: exit %d: %.300s] ", faults[k].what, code, out);
        free(before), free(after);
    }
    gb_check_true(&c, refused == total, "%zu of %zu faults refused as stated%s%s", refused, total, report[0] ? ": " : "", report);

    /* The same point twice with the same values is no fault; a half-written last line is dropped. */
    FILE *f = fopen(d.journal, "wb");
    for (size_t k = 0; f && k < count; k++) fputs(lines[k], f);
    if (f) fputs(lines[2], f), fputs("5,18,", f), fclose(f);
    const int resumed = s8_scan_run(&d, "--resume --threads 1", out, sizeof out);
    char *csv = gb_check_read_file(d.csv);
    const int whole = s8_scan_run(&d, "--threads 1", out, sizeof out); /* the uninterrupted CSV */
    char *reference = gb_check_read_file(d.csv);
    gb_check ci = {"8.3", "-", "--resume with a point twice, identical, and a half-written last line",
                   "accepted; the CSV of an uninterrupted run, byte for byte", "exact"};
    gb_check_true(&ci, resumed == 0 && whole == 0 && csv && reference && !strcmp(csv, reference), "resume exit %d, run exit %d, %s",
                  resumed, whole, csv && reference && !strcmp(csv, reference) ? "identical" : "different");
    free(csv), free(reference);

    /* The scan's JSON is the set's manifest and records what the scan was: gomboc check finds it whole. */
    char json_path[200], args[512];
    snprintf(json_path, sizeof json_path, "%s/map-scan.json", d.path);
    snprintf(args, sizeof args, "check '%s'", json_path);
    const int checked = s8_run(args, out, sizeof out);
    char *json_text = gb_check_read_file(json_path);
    cJSON *root = json_text ? cJSON_Parse(json_text) : NULL;
    const cJSON *metrics = cJSON_GetObjectItem(root, "metrics");
    gb_check cm = {"8.3", "-", "a scan's JSON lists its CSV with size and checksum, and the metrics it computed",
                   "gomboc check exit 0; 8 metrics, omega_rms first, contacts last", "exact"};
    gb_check_true(&cm, checked == 0 && cJSON_GetArraySize(metrics) == 8 &&
                       !strcmp(cJSON_GetArrayItem(metrics, 0)->valuestring, "omega_rms") &&
                       !strcmp(cJSON_GetArrayItem(metrics, 7)->valuestring, "contacts"),
                  "check exit %d: %.200s", checked, out);
    cJSON_Delete(root);
    free(json_text);
    free_lines(lines);

    /* A scan that fails before any point is finished leaves no journal to stand in the way of the next
     * run (RK4 at one step a period diverges under a damping rate c/I of ~1e9 /s: "the state is no longer
     * finite", a computation that failed). */
    char path[200];
    snprintf(path, sizeof path, "%s/base.ini", d.path);
    s8_spill(path, "[body]\nbeta = 0.12\nmass = 1e-6\n[model]\nequation = rolling\ncontact = continuous\ndamping = 1000\n"
                "[integrator]\nperiods = 1\nsteps_per_period = 1\n[initial]\nomega = 1,0,0\n");
    s8_spill(d.scan, "[scan]\nbase = base.ini\nperiods = 2\ntransient_periods = 1\n[x]\nkey = body.mass\nfrom = 1\nto = 2\n"
                  "count = 2\n[y]\nkey = forcing.A1\nfrom = 1\nto = 1\ncount = 1\n");
    const int failed = s8_scan_run(&d, "--threads 1", out, sizeof out);
    const int again = s8_scan_run(&d, "--threads 1", out, sizeof out);
    gb_check cf = {"8.3", "-", "a scan whose every point fails, run twice", "exit 1 both times (never 2 for a journal left behind), "
                   "no journal", "exact"};
    gb_check_true(&cf, failed == 1 && again == 1 && access(d.journal, F_OK) != 0, "exits %d, %d; journal %s: %.200s", failed, again,
                  access(d.journal, F_OK) ? "none" : "LEFT", out);

    /* The same scan with failed_points = record: it finishes, each failed point a row of NaN metrics. */
    s8_spill(d.scan, "[scan]\nbase = base.ini\nperiods = 2\ntransient_periods = 1\nfailed_points = record\n[x]\nkey = body.mass\n"
                  "from = 1\nto = 2\ncount = 2\n[y]\nkey = forcing.A1\nfrom = 1\nto = 1\ncount = 1\n");
    const int recorded = s8_scan_run(&d, "--threads 1", out, sizeof out);
    char *csv_text = gb_check_read_file(d.csv);
    json_text = gb_check_read_file(json_path);
    root = json_text ? cJSON_Parse(json_text) : NULL;
    const cJSON *mode = cJSON_GetObjectItem(root, "failed_points");
    size_t nan_rows = 0;
    /* the rows after the header: each must hold ",nan," and end in two zero fingerprints */
    for (char *line = csv_text ? strchr(csv_text, '\n') : NULL; line && line[1]; line = strchr(line + 1, '\n')) {
        char *end = strchr(line + 1, '\n');
        if (end) *end = '\0';
        const size_t n = strlen(line + 1);
        nan_rows += strstr(line + 1, ",nan,") && n > 34 && !strcmp(line + 1 + n - 34, ",0000000000000000,0000000000000000");
        if (end) *end = '\n';
    }
    gb_check cg = {"8.3", "-", "that scan with failed_points = record", "exit 0; 2 rows of NaN metrics with zero fingerprints; "
                   "the JSON says record; the message names each failed point", "exact"};
    gb_check_true(&cg, recorded == 0 && nan_rows == 2 && cJSON_IsString(mode) && !strcmp(mode->valuestring, "record") &&
                       strstr(out, "recorded with NaN metrics"),
                  "exit %d, %zu NaN rows: %.300s", recorded, nan_rows, csv_text ? csv_text : out);
    cJSON_Delete(root);
    free(json_text);
    free(csv_text);

    /* A random axis is recorded as such: its seed and count, no range. */
    s8_spill(path, "[integrator]\nperiods = 2\n[model]\ncontact = fast-grid\n");
    s8_spill(d.scan, "[scan]\nbase = base.ini\nperiods = 2\ntransient_periods = 1\nmetrics = omega_rms\n[x]\nkey = initial.attitude\n"
                  "scale = random\ncount = 2\nseed = 5\n[y]\nkey = forcing.A1\nfrom = 1\nto = 1\ncount = 1\n");
    const int random_run = s8_scan_run(&d, "--threads 1", out, sizeof out);
    json_text = gb_check_read_file(json_path);
    root = json_text ? cJSON_Parse(json_text) : NULL;
    const cJSON *x = cJSON_GetObjectItem(root, "x");
    const cJSON *scale = cJSON_GetObjectItem(x, "scale"), *seed = cJSON_GetObjectItem(x, "seed");
    gb_check cr = {"8.3", "-", "the JSON of a scan over random attitudes (seed 5, 2 points)",
                   "x.scale = random, x.seed = 5, x.count = 2, no from or to; metrics = [omega_rms]", "exact"};
    gb_check_true(&cr, random_run == 0 && cJSON_IsString(scale) && !strcmp(scale->valuestring, "random") && cJSON_IsNumber(seed) &&
                       seed->valuedouble == 5 && s8_number_at(x, "count", NULL) == 2 && !cJSON_GetObjectItem(x, "from") &&
                       !cJSON_GetObjectItem(x, "to") && cJSON_GetArraySize(cJSON_GetObjectItem(root, "metrics")) == 1,
                  "exit %d: %.300s", random_run, json_text ? json_text : out);
    cJSON_Delete(root);
    free(json_text);
    s8_remove_scan_dir(&d);
}

/* ---- MPI ranks (where an MPI build exists: $GOMBOC_MPI_BIN, launched by $GOMBOC_MPIRUN) ----------- */

static const char *mpi_binary(void) { return getenv("GOMBOC_MPI_BIN"); }

/* `LAUNCHER -n RANKS MPI-BINARY scan ...` into the scan directory; the exit status. */
static int mpi_scan_run(const s8_scan_dir *d, int ranks, const char *extra, char *out, size_t cap)
{
    char command[1024], args[1024];
    snprintf(command, sizeof command, "%s -n %d '%s'", getenv("GOMBOC_MPIRUN"), ranks, mpi_binary());
    snprintf(args, sizeof args, "scan '%s' --out '%s' %s", d->scan, d->path, extra);
    return gb_check_command(command, args, out, cap);
}

/* The ranks the scan's JSON says it ran on. */
static int ranks_of(const s8_scan_dir *d)
{
    char path[200];
    snprintf(path, sizeof path, "%s/map-scan.json", d->path);
    char *text = gb_check_read_file(path);
    cJSON *root = text ? cJSON_Parse(text) : NULL;
    free(text);
    const double ranks = s8_number_at(root, "environment", "ranks");
    cJSON_Delete(root);
    return isfinite(ranks) ? (int)ranks : -1;
}

/* SIGKILL to every process of session `sid` (mpirun and its ranks, which OpenMPI puts in process groups
 * of their own) until none is left; the number killed. */
static int kill_session(pid_t sid)
{
    int killed = 0;
    for (int round = 0; round < 100; round++) {
        int found = 0;
        DIR *proc = opendir("/proc");
        for (struct dirent *e; proc && (e = readdir(proc));) {
            const long pid = strtol(e->d_name, NULL, 10);
            if (pid <= 0) continue;
            char path[64], stat[512];
            snprintf(path, sizeof path, "/proc/%ld/stat", pid);
            FILE *f = fopen(path, "r");
            if (!f) continue;
            const size_t n = fread(stat, 1, sizeof stat - 1, f);
            fclose(f);
            stat[n] = '\0';
            const char *after = strrchr(stat, ')'); /* after the command's name: state, ppid, pgrp, session */
            char state;
            long ppid, pgrp, session;
            if (!after || sscanf(after + 1, " %c %ld %ld %ld", &state, &ppid, &pgrp, &session) != 4) continue;
            if (session != (long)sid || state == 'Z') continue;
            found++;
            if (kill((pid_t)pid, SIGKILL) == 0) killed++;
        }
        if (proc) closedir(proc);
        if (!found) break;
        const struct timespec pause = {0, 10000000};
        nanosleep(&pause, NULL);
    }
    return killed;
}

static void test_mpi_ranks(void)
{
    s8_scan_dir d;
    char out[1 << 14];
    gb_check c1 = {"8.3", "-", "scan CSV of the MPI build on 1 rank against the plain build on 1 thread", "byte for byte", "exact"};
    if (s8_make_scan_dir(&d, &c1)) return;
    const int plain = s8_scan_run(&d, "--threads 1", out, sizeof out);
    char *reference = gb_check_read_file(d.csv);
    remove(d.csv);
    const int one = mpi_scan_run(&d, 1, "--threads 1", out, sizeof out);
    char *csv = gb_check_read_file(d.csv);
    const int same1 = plain == 0 && one == 0 && reference && csv && !strcmp(reference, csv) && ranks_of(&d) == 1;
    gb_check_true(&c1, same1, "exits %d, %d; %d rank(s); %s%s%.200s", plain, one, ranks_of(&d),
                  reference && csv && !strcmp(reference, csv) ? "identical" : "different", same1 ? "" : ": ", same1 ? "" : out);
    free(csv);

    static const struct {
        int ranks;
        const char *threads;
    } runs[] = {{2, "--threads 1"}, {2, "--threads 2"}, {3, "--threads 1"}};
    for (size_t k = 0; k < sizeof runs / sizeof runs[0]; k++) {
        remove(d.csv);
        const int code = mpi_scan_run(&d, runs[k].ranks, runs[k].threads, out, sizeof out);
        csv = gb_check_read_file(d.csv);
        char quantity[160];
        snprintf(quantity, sizeof quantity, "scan CSV on %d MPI ranks (%s) against the plain build on 1 thread",
                 runs[k].ranks, runs[k].threads);
        gb_check c = {"8.3", "-", quantity, "byte for byte; the JSON names the ranks", "exact"};
        const int same = code == 0 && csv && reference && !strcmp(reference, csv) && ranks_of(&d) == runs[k].ranks;
        gb_check_true(&c, same, "exit %d; %d rank(s); %s%s%.200s", code, ranks_of(&d),
                      reference && csv && !strcmp(reference, csv) ? "identical" : "different", same ? "" : ": ", same ? "" : out);
        free(csv);
    }

    /* The whole launch (mpirun and its ranks, one session) killed once the journal holds two points; a
     * half-written line left behind; resumed on 2 ranks. Rank 0 stops itself there (the program's test hook,
     * GOMBOC_TEST_PAUSE_AFTER_POINTS, forwarded by mpirun -x), so the journal holds exactly 3 lines when it is
     * killed, whatever the load. */
    remove(d.csv);
    const pid_t pid = fork();
    if (pid == 0) {
        setsid();
        signal(SIGINT, SIG_DFL), signal(SIGTERM, SIG_DFL);
        char log[600];
        snprintf(log, sizeof log, "%s/mpi-killed.log", d.path);
        if (!freopen(log, "w", stdout) || !freopen(log, "a", stderr)) _exit(127);
        setenv("GOMBOC_TEST_PAUSE_AFTER_POINTS", "2", 1);
        char command[1024];
        snprintf(command, sizeof command, "exec %s -x GOMBOC_TEST_PAUSE_AFTER_POINTS -n 2 '%s' scan '%s' --out '%s' --threads 1",
                 getenv("GOMBOC_MPIRUN"), mpi_binary(), d.scan, d.path);
        execl("/bin/sh", "sh", "-c", command, (char *)NULL);
        _exit(127);
    }
    const struct timespec ms = {0, 1000000};
    for (int k = 0; k < 60000 && lines_of(d.journal) < 3; k++) nanosleep(&ms, NULL);
    const int killed = kill_session(pid);
    int wstatus = 0;
    waitpid(pid, &wstatus, 0);
    const size_t kept = lines_of(d.journal);
    FILE *j = fopen(d.journal, "a");
    if (j) fputs("5,18,1.", j), fclose(j);
    const int resumed = mpi_scan_run(&d, 2, "--resume --threads 1", out, sizeof out);
    csv = gb_check_read_file(d.csv);
    gb_check ck = {"8.3", "-", "scan CSV after a kill -9 of every rank with 2 or more points journaled, a half-written line, "
                   "and --resume on 2 ranks", "the plain build's uninterrupted CSV, byte for byte", "exact"};
    size_t journaled = SCAN_POINTS; /* what the resumed run found in the journal */
    const char *said = strstr(out, "resuming, ");
    if (!said || sscanf(said, "resuming, %zu of", &journaled) != 1) journaled = SCAN_POINTS;
    const int resumed_same = WIFSIGNALED(wstatus) && killed >= 3 && kept == 3 && journaled == kept - 1 &&
                             journaled < SCAN_POINTS && resumed == 0 && csv && reference && !strcmp(reference, csv) &&
                             access(d.journal, F_OK) != 0;
    gb_check_true(&ck, resumed_same,
                  "%d processes killed with %zu journal lines (%zu points found on resuming); resume exit %d; %s%s%.200s",
                  killed, kept, journaled, resumed, reference && csv && !strcmp(reference, csv) ? "identical" : "different",
                  resumed_same ? "" : ": ", resumed_same ? "" : out);
    free(csv);
    free(reference);
    s8_remove_scan_dir(&d);
}

/* A disk that fills: the scan's files limited to 700 bytes (RLIMIT_FSIZE: every write past it fails with
 * EFBIG, as on a full disk with ENOSPC). The scan must stop with exit 1 naming the journal, leave no
 * CSV, keep the points it journaled, and finish them with --resume once there is room, byte for byte. */
static void test_disk_full(void)
{
    s8_scan_dir d;
    char out[1 << 14];
    gb_check c = {"8.3", "-", "a scan whose journal cannot grow (file size limit of 700 bytes: a full disk)",
                  "exit 1 naming the journal, no CSV; --resume with room gives the uninterrupted CSV byte for byte",
                  "exact"};
    if (s8_make_scan_dir(&d, &c)) return;
    const int plain = s8_scan_run(&d, "--threads 1", out, sizeof out);
    char *reference = gb_check_read_file(d.csv);
    remove(d.csv);
    char log[200];
    snprintf(log, sizeof log, "%s/full.log", d.path);
    const pid_t pid = fork();
    if (pid == 0) {
        const struct rlimit limit = {700, 700};
        signal(SIGXFSZ, SIG_IGN);
        if (setrlimit(RLIMIT_FSIZE, &limit) || !freopen(log, "w", stderr)) _exit(127);
        execl(s8_binary(), s8_binary(), "scan", d.scan, "--out", d.path, "--threads", "1", (char *)NULL);
        _exit(127);
    }
    int wstatus = 0;
    waitpid(pid, &wstatus, 0);
    char *message = gb_check_read_file(log);
    const size_t kept = lines_of(d.journal);
    const int no_csv = access(d.csv, F_OK) != 0;
    const int resumed = s8_scan_run(&d, "--resume --threads 1", out, sizeof out);
    char *csv = gb_check_read_file(d.csv);
    const int ok = plain == 0 && WIFEXITED(wstatus) && WEXITSTATUS(wstatus) == 1 && message &&
                   strstr(message, "cannot append to the journal") && no_csv && kept >= 2 && kept < 1 + SCAN_POINTS &&
                   resumed == 0 && csv && reference && !strcmp(csv, reference);
    gb_check_true(&c, ok, "exit %d, %zu journal lines kept, %s; resume exit %d, %s; message: %.160s",
                  WIFEXITED(wstatus) ? WEXITSTATUS(wstatus) : -1, kept, no_csv ? "no CSV" : "a CSV left", resumed,
                  csv && reference && !strcmp(csv, reference) ? "identical" : "different", message ? message : "(none)");
    free(message), free(csv), free(reference);
    s8_remove_scan_dir(&d);
}

/* A point whose coordinate is outside its key's range is refused before any run, naming the scan
 * file's line, the point and the range; nothing is written. */
static void test_point_out_of_range(void)
{
    s8_scan_dir d;
    char out[1 << 14];
    gb_check c = {"8.3", "-", "a scan whose last point has beta = 0.3", "refused (exit 2) before any run, naming line, point, range",
                  "exact"};
    if (s8_make_scan_dir(&d, &c)) return;
    s8_spill(d.scan, "[scan]\nbase = base.ini\nperiods = 12\ntransient_periods = 4\n"
                  "[x]\nkey = body.beta\nfrom = 0.1\nto = 0.3\ncount = 3\n[y]\nkey = forcing.A2\nfrom = 0.5\nto = 1.5\ncount = 2\n");
    const int code = s8_scan_run(&d, "", out, sizeof out);
    gb_check_true(&c, code == 2 && strstr(out, "map.ini:6 (point 2): [body] beta = 0.2999") && strstr(out, "beta < 0.25") &&
                  access(d.csv, F_OK) != 0 && access(d.journal, F_OK) != 0,
                  "exit %d: %.300s", code, out);
    s8_remove_scan_dir(&d);
}

int verify_register_s8_scan_runs(void)
{
    static const verify_test tests[] = {
        {"section 8.3: the library's runner: threads, ranks and points done give each point's own row", test_library_runner,
         "gb_scan_run, the library's parallel runner, gives each point's own run on any threads and ranks"},
        {"section 8.3: threads, kill -9 and --resume give the same bytes", test_threads_and_resume,
         "a scan's CSV does not depend on the thread count or on an interruption"},
        {"section 8.3: a journal is verified line by line, never trusted", test_journal_verified,
         "a resumed scan takes from its journal only rows it can verify"},
        {"section 8.3: a point out of its key's range is refused before any run", test_point_out_of_range, NULL},
        {"section 8.3: a disk that fills stops the scan, and --resume finishes it", test_disk_full,
         "a scan that cannot write its journal stops, names it, and loses none of the points it wrote"},
        {NULL, NULL, NULL},
    };
    static const verify_test mpi_tests[] = {
        {"section 8.3: 1, 2 and 3 MPI ranks, kill -9 and --resume give the same bytes", test_mpi_ranks,
         "a scan's CSV does not depend on the number of MPI ranks or on an interruption of all of them"},
        {NULL, NULL, NULL},
    };
    /* The ranks' checks need an MPI build (make mpi; make verify builds one where mpicc is). */
    return verify_register_suite("Section 8.3: scans that survive threads, kills, journals and full disks", tests) ||
           (mpi_binary() && getenv("GOMBOC_MPIRUN") && verify_register_suite("Section 8.3: scans on MPI ranks", mpi_tests));
}
