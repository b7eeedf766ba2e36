/* The connect stage's work items on N threads, through fm_parallel_for. */
#include "connect_internal.h"
#include "fm_parallel.h"

void cn_parallel_for(size_t n, int nthreads, cn_task_fn fn, void *user)
{
    fm_parallel_for(n, nthreads, fn, user, NULL, NULL, 0, 0);
}

void cn_parallel_for_told(size_t n, int nthreads, cn_task_fn fn, void *user,
                          fm_connect_progress_fn progress, void *progress_user, size_t base,
                          size_t total)
{
    fm_parallel_for(n, nthreads, fn, user, progress, progress_user, base, total);
}
