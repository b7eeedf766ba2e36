/* faultmesh core: work items on N threads. Each index is handed out once,
 * from a shared counter; callers store results by index, so what they
 * compute does not depend on the number of threads or on which thread did
 * what. */
#ifndef FM_PARALLEL_H
#define FM_PARALLEL_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef void (*fm_task_fn)(void *user, size_t k);
/* Told after each item: done of total (base counts items done before). */
typedef void (*fm_told_fn)(void *user, size_t done, size_t total);

/* fn(user, k) for every k in [0, n), on up to nthreads threads (the
 * caller's among them; one when no thread can be started). told may be
 * NULL; it is called under a lock. */
void fm_parallel_for(size_t n, int nthreads, fm_task_fn fn, void *user, fm_told_fn told,
                     void *told_user, size_t base, size_t total);

#ifdef __cplusplus
}
#endif
#endif
