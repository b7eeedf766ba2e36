#include "fit_internal.h"

#include <time.h>

/* Monotonic wall clock for the stats: a fit is single threaded, and the
 * caller wants elapsed time, not CPU time of a process doing other work. */
double fm_fit_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
