/* gb_proof_parallel — independent tasks of a proof on several threads (gb_proof_internal.h states the contract).
 * Each task writes only its own outputs and reads shared data that no task changes; a task is handed out once, under
 * a lock, to whichever thread is free, so the results do not depend on the threads' number or timing. */
#include "gb_error.h"
#include "gb_proof_internal.h"

#include <flint/flint.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct pool {
    size_t count, next;
    int (*task)(void *ctx, size_t k);
    void *ctx;
    pthread_mutex_t lock;
    int status;                 /* the first failure's */
    char message[GB_ERROR_MAX]; /* and its message, set again on the caller's thread */
    double seconds;
} pool;

static void *worker(void *arg)
{
    pool *P = arg;
    const double start = gb_proof_cpu_seconds();
    for (;;) {
        pthread_mutex_lock(&P->lock);
        const size_t k = P->status ? P->count : P->next;
        if (k < P->count) P->next++;
        pthread_mutex_unlock(&P->lock);
        if (k >= P->count) break;
        const int status = P->task(P->ctx, k);
        if (status) {
            pthread_mutex_lock(&P->lock);
            if (!P->status) P->status = status, snprintf(P->message, sizeof P->message, "%s", gb_error_message());
            pthread_mutex_unlock(&P->lock);
        }
    }
    const double used = gb_proof_cpu_seconds() - start;
    pthread_mutex_lock(&P->lock);
    P->seconds += used;
    pthread_mutex_unlock(&P->lock);
    flint_cleanup(); /* FLINT's caches of this thread */
    return NULL;
}

int gb_proof_for_each(size_t count, int threads, int (*task)(void *ctx, size_t k), void *ctx, double *seconds)
{
    if (seconds) *seconds = 0.0;
    if (threads <= 1 || count <= 1) {
        for (size_t k = 0; k < count; k++) {
            const int status = task(ctx, k);
            if (status) return status;
        }
        return GB_OK;
    }
    if ((size_t)threads > count) threads = (int)count;
    pool P = {.count = count, .task = task, .ctx = ctx};
    pthread_t *id = malloc((size_t)threads * sizeof *id);
    if (!id) return gb_error_set(GB_ENOMEM, "proof: out of memory for %d threads", threads);
    pthread_mutex_init(&P.lock, NULL);
    int made = 0;
    while (made < threads && !pthread_create(&id[made], NULL, worker, &P)) made++;
    if (!made) worker(&P); /* no thread could be made: the caller's does it all */
    for (int i = 0; i < made; i++) pthread_join(id[i], NULL);
    pthread_mutex_destroy(&P.lock);
    free(id);
    if (seconds) *seconds = made ? P.seconds : 0.0;
    if (P.status) return gb_error_set(P.status, "%s", P.message);
    return GB_OK;
}
