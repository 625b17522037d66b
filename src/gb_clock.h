/* gb_clock — the monotonic wall clock the library and the command time their work with (internal). */
#ifndef GB_CLOCK_H
#define GB_CLOCK_H

#include <time.h>

/* Seconds on CLOCK_MONOTONIC: differences of two readings are elapsed wall time. */
static inline double gb_wall_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

#endif
