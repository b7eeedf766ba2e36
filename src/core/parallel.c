/* Work items on N threads (fm_parallel.h). */
#include <pthread.h>
#include <stdlib.h>

#include "fm_parallel.h"

typedef struct pool {
    fm_task_fn fn;
    void *user;
    size_t n, next, done;
    fm_told_fn told;
    void *told_user;
    size_t base, total;
    pthread_mutex_t lock;
} pool;

static void *worker(void *arg)
{
    pool *p = arg;
    for (;;) {
        pthread_mutex_lock(&p->lock);
        size_t k = p->next++;
        pthread_mutex_unlock(&p->lock);
        if (k >= p->n)
            return NULL;
        p->fn(p->user, k);
        if (p->told) {
            pthread_mutex_lock(&p->lock);
            p->done++;
            p->told(p->told_user, p->base + p->done, p->total);
            pthread_mutex_unlock(&p->lock);
        }
    }
}

void fm_parallel_for(size_t n, int nthreads, fm_task_fn fn, void *user, fm_told_fn told,
                     void *told_user, size_t base, size_t total)
{
    if (nthreads < 1)
        nthreads = 1;
    if ((size_t)nthreads > n)
        nthreads = n ? (int)n : 1;
    pool p = {fn, user, n, 0, 0, told, told_user, base, total, PTHREAD_MUTEX_INITIALIZER};
    pthread_t *th = nthreads > 1 ? malloc((size_t)(nthreads - 1) * sizeof *th) : NULL;
    int started = 0;
    for (int t = 0; th && t < nthreads - 1; t++) {
        if (pthread_create(&th[t], NULL, worker, &p) != 0)
            break;
        started++;
    }
    /* the calling thread works too; with no thread started it does it all */
    worker(&p);
    for (int t = 0; t < started; t++)
        pthread_join(th[t], NULL);
    free(th);
    pthread_mutex_destroy(&p.lock);
}
