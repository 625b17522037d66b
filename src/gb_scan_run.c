/* gb_scan_run — a scan's points on threads (gb_scan.h, "running a scan").
 *
 * POSIX threads rather than OpenMP: the work is one queue of independent points (an atomic counter hands
 * out the next), and a library that starts an OpenMP runtime imposes it on every program linked with it
 * (libgomp beside a program's own libomp or thread pool, and its threads kept alive after the call). The
 * caller's callbacks run one at a time under one mutex, so that a caller may write a journal or pass
 * MPI messages from them (MPI_THREAD_SERIALIZED). */
#include "gb_scan_internal.h"

#include "gb_clock.h"
#include "gb_dynamics_protocol_internal.h"
#include "gb_error.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { THREADS_MAX = 256 };

/* What the threads of one phase share. */
typedef struct runner_state {
    const gb_scan *scan;
    const gb_scan_runner *runner;
    gb_scan_melnikov *plan;
    const size_t *todo;             /* the points this process runs */
    size_t tasks;                   /* the tasks handed out so far in this phase: [next, tasks) */
    size_t total;                   /* this phase's tasks in all, for progress */
    size_t models;                  /* the Melnikov phase: tasks [0, models) are bodies, the rest frequencies */
    atomic_size_t next;             /* the next task to hand out */
    atomic_int stop;                /* 1 after a failure: no task starts */
    pthread_mutex_t lock;           /* the callbacks, the counters and the failure below */
    gb_dynamics_context *atlas;     /* the points' phase with a shared atlas: the one atlas its threads view */
    gb_scan_phase phase;
    size_t done, points_run;
    double start, last_report;
    int status;
    char failure[GB_ERROR_MAX];
} runner_state;

unsigned gb_scan_threads(unsigned threads)
{
    if (threads) return threads;
    const long online = sysconf(_SC_NPROCESSORS_ONLN);
    return online < 1 ? 1u : online > THREADS_MAX ? THREADS_MAX : (unsigned)online;
}

/* Under the lock: the first failure is the one returned; no task starts after it. */
static void fail(runner_state *st, int status, const char *message)
{
    if (!st->status) {
        st->status = status;
        snprintf(st->failure, sizeof st->failure, "%s", message);
    }
    atomic_store(&st->stop, 1);
}

/* Under the lock: a progress report when one is due (every progress_seconds, and the phase's end). */
static void report(runner_state *st, int start)
{
    const gb_scan_runner *r = st->runner;
    if (!r->progress || !st->total) return;
    const double now = gb_wall_seconds(), every = r->progress_seconds > 0.0 ? r->progress_seconds : 2.0;
    if (!start && st->done < st->total && now - st->last_report < every) return;
    const int melnikov = st->phase == GB_SCAN_PHASE_MELNIKOV;
    const gb_scan_progress p = {st->phase, st->done, st->total, melnikov ? st->models : 0,
                                melnikov ? st->total - st->models : 0, now - st->start};
    r->progress(r->user, &p);
    st->last_report = now;
}

static void phase_begin(runner_state *st, gb_scan_phase phase, size_t tasks)
{
    st->phase = phase, st->tasks = st->total = tasks, st->done = 0;
    atomic_store(&st->next, 0);
    st->start = st->last_report = gb_wall_seconds();
    report(st, 1);
}

/* A thread of the Melnikov phase: bodies first, then (after every body, gb_scan_run's second call)
 * frequencies. */
static void *melnikov_worker(void *arg)
{
    runner_state *st = arg;
    for (;;) {
        const size_t k = atomic_fetch_add(&st->next, 1);
        if (k >= st->tasks || atomic_load(&st->stop)) break;
        const int s = k < st->models ? gb_scan_melnikov_body(st->plan, k) : gb_scan_melnikov_frequency(st->plan, k - st->models);
        char message[GB_ERROR_MAX];
        if (s) snprintf(message, sizeof message, "the Melnikov margins' reduced model failed: %s", gb_error_message());
        pthread_mutex_lock(&st->lock);
        if (s) fail(st, s, message);
        st->done++;
        report(st, 0);
        pthread_mutex_unlock(&st->lock);
    }
    return NULL;
}

/* Under the lock: the caller hears `message` (the notice callback). */
static void notice(runner_state *st, const char *message)
{
    if (st->runner->notice) st->runner->notice(st->runner->user, message);
}

/* The process's shared atlas merged with its file and written back (gb_dynamics_context_save_shared): a file
 * that cannot be written costs the sharing, not the scan (the points' results do not depend on the atlas). The
 * writers take turns under the directory's lock, the processes of an MPI run alike. */
static void save_atlas(runner_state *st)
{
    if (!gb_dynamics_context_save_shared(st->atlas)) return;
    char message[GB_ERROR_MAX + 64];
    snprintf(message, sizeof message, "the shared atlas was not written: %s", gb_error_message());
    gb_error_clear();
    pthread_mutex_lock(&st->lock);
    notice(st, message);
    pthread_mutex_unlock(&st->lock);
}

/* The failure of point k's computation, named by its coordinates. */
static void point_message(const gb_scan *scan, size_t k, const char *how, char *out, size_t size)
{
    double x, y;
    gb_scan_coordinates(scan, k, &x, &y);
    snprintf(out, size, "point %zu (%s.%s = %.17g, %s.%s = %.17g) %s: %s", k, scan->axis[0].section, scan->axis[0].key, x,
             scan->axis[1].section, scan->axis[1].key, y, how, gb_error_message());
}

/* A thread of the points' phase, with its own context from point to point, viewing the process's one atlas. */
static void *point_worker(void *arg)
{
    runner_state *st = arg;
    const gb_scan *scan = st->scan;
    gb_dynamics_context *context = NULL;
    if (gb_dynamics_context_create(&context)) gb_error_clear(); /* none: each point builds its own set-up */
    if (context && st->atlas) gb_dynamics_context_share(context, st->atlas);
    for (;;) {
        const size_t i = atomic_fetch_add(&st->next, 1);
        if (i >= st->tasks || atomic_load(&st->stop)) break;
        const size_t k = st->todo[i];
        gb_scan_metrics m;
        int s = gb_scan_point_run_in(scan, st->plan, k, context, &m);
        char message[GB_ERROR_MAX + 160] = "";
        if (s && scan->record_failures && s != GB_ENOMEM && s != GB_EIO && s != GB_EINVAL && s != GB_EDOM) {
            /* failed_points = record: the computation failed (the model cannot follow this point); a row of NaN */
            point_message(scan, k, "failed, recorded with NaN metrics", message, sizeof message);
            gb_scan_failed_metrics(scan, k, &m);
            gb_error_clear();
            s = GB_OK;
        } else if (s) {
            point_message(scan, k, "failed", message, sizeof message);
        }
        char row[1024];
        if (!s) s = gb_scan_csv_row(&m, k, row, sizeof row);
        int checkpoint = 0;
        pthread_mutex_lock(&st->lock);
        if (s) {
            fail(st, s, message[0] ? message : gb_error_message());
        } else if (!atomic_load(&st->stop)) {
            if (message[0]) notice(st, message);
            const int refused = st->runner->finished ? st->runner->finished(st->runner->user, k, &m, row) : GB_OK;
            if (refused) fail(st, refused, gb_error_message());
            else st->done++, st->points_run++, checkpoint = st->done % GB_SCAN_ATLAS_SAVE_POINTS == 0;
            report(st, 0);
        }
        pthread_mutex_unlock(&st->lock);
        if (st->atlas && checkpoint) save_atlas(st); /* every GB_SCAN_ATLAS_SAVE_POINTS points of the process */
    }
    gb_dynamics_context_free(context);
    return NULL;
}

/* The shared atlas's cells, what proving them cost and the views' waits, for the caller (issue 57's measure). */
static void atlas_notice(runner_state *st)
{
    gb_atlas_stats a;
    size_t read;
    if (!gb_dynamics_context_shared_stats(st->atlas, &a, &read)) return;
    char message[512];
    const size_t held = a.cells + a.cells_failed, proved = held + a.cells_split - read;
    snprintf(message, sizeof message, "the shared atlas: %zu cells proved in this process (%.2f a point run; %zu read from "
             "its file), %.2f s proving them; %zu waits for a cell another thread was proving, %.3f s in all", proved,
             st->points_run ? (double)proved / (double)st->points_run : 0.0, read, a.build_seconds, a.waits, a.wait_seconds);
    pthread_mutex_lock(&st->lock);
    notice(st, message);
    pthread_mutex_unlock(&st->lock);
}

/* `worker` on `threads` threads (the calling one among them), until the tasks [next, tasks) are handed out. */
static int run_threads(runner_state *st, unsigned threads, void *(*worker)(void *))
{
    const size_t tasks = st->tasks - atomic_load(&st->next);
    if (threads > tasks) threads = tasks ? (unsigned)tasks : 1u;
    pthread_t id[THREADS_MAX];
    unsigned started = 0;
    for (; started + 1 < threads; started++)
        if (pthread_create(&id[started], NULL, worker, st)) break; /* fewer threads: the same results */
    worker(st);
    for (unsigned k = 0; k < started; k++) pthread_join(id[k], NULL);
    return st->status;
}

int gb_scan_run(const gb_scan *scan, const gb_scan_runner *runner, size_t *points_run)
{
    if (points_run) *points_run = 0;
    const size_t ranks = runner->ranks ? runner->ranks : 1;
    if (runner->threads > THREADS_MAX || runner->rank >= ranks)
        return gb_error_set(GB_EINVAL, "scan runner: %u threads, rank %zu of %zu (allowed: 0 to %d threads, rank < ranks)",
                            runner->threads, runner->rank, ranks, THREADS_MAX);
    const size_t points = gb_scan_points(scan);
    size_t *todo = malloc((points ? points : 1) * sizeof *todo), left = 0, mine = 0;
    if (!todo) return gb_error_set(GB_ENOMEM, "out of memory for the list of %zu points", points);
    for (size_t k = 0; k < points; k++)
        if (!runner->done || !runner->done[k]) {
            if (left++ % ranks == runner->rank) todo[mine++] = k;
        }
    runner_state st = {.scan = scan, .runner = runner, .todo = todo};
    if (pthread_mutex_init(&st.lock, NULL)) {
        free(todo);
        return gb_error_set(GB_ENOMEM, "scan runner: no mutex");
    }
    const unsigned threads = gb_scan_threads(runner->threads);
    int status = gb_scan_melnikov_plan(scan, todo, mine, &st.plan);
    if (!status) {
        /* the bodies, then their frequencies */
        const size_t bodies = gb_scan_melnikov_bodies(st.plan), frequencies = gb_scan_melnikov_frequencies(st.plan);
        st.models = bodies;
        phase_begin(&st, GB_SCAN_PHASE_MELNIKOV, bodies + frequencies);
        st.tasks = bodies;
        status = run_threads(&st, threads, melnikov_worker);
        if (!status) {
            st.tasks = bodies + frequencies;
            atomic_store(&st.next, bodies);
            status = run_threads(&st, threads, melnikov_worker);
        }
        if (status) gb_error_set(status, "%s", st.failure);
    }
    if (!status && scan->atlas_file) { /* one atlas for the process, read from its file by the first point */
        if (gb_dynamics_context_create(&st.atlas) || gb_dynamics_context_files(st.atlas, scan->atlas_file, NULL)) {
            gb_error_clear(); /* none: each point builds its own */
            gb_dynamics_context_free(st.atlas), st.atlas = NULL;
        }
        if (st.atlas) gb_dynamics_context_atlas_bound(st.atlas, GB_SCAN_ATLAS_MEMORY);
    }
    if (!status) {
        phase_begin(&st, GB_SCAN_PHASE_POINTS, mine);
        status = run_threads(&st, threads, point_worker);
        if (status) gb_error_set(status, "%s", st.failure);
        if (st.atlas) {
            const int kept = status;
            char failure[GB_ERROR_MAX];
            snprintf(failure, sizeof failure, "%s", gb_error_message());
            save_atlas(&st), atlas_notice(&st);
            if (kept) gb_error_set(kept, "%s", failure);
        }
    }
    gb_dynamics_context_free(st.atlas);
    if (points_run) *points_run = st.points_run;
    gb_scan_melnikov_free(st.plan);
    pthread_mutex_destroy(&st.lock);
    free(todo);
    return status;
}
