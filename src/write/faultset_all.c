/* Every output of a fault set on several threads: one piece of work per
 * file, handed out in a fixed order, so that which thread writes a file
 * never changes its bytes. */
#include <pthread.h>
#include <stdlib.h>

#include "faultset_internal.h"

enum { SINGLE_VTU, SINGLE_MSH, SINGLE_STL, SINGLE_OBJ, SINGLE_EXO, NSINGLE };

typedef struct pool {
    const fm_faultset *fs;
    const fm_faultset_outputs *out;
    int singles[NSINGLE]; /* the single-file outputs asked for, in order */
    size_t nsingles, ntasks;
    fs_tsurf_plan plan;

    pthread_mutex_t mu;
    size_t next;         /* next task to hand out */
    int stop;            /* a task failed: hand out no more */
    size_t failed_task;  /* lowest failing task, ntasks if none */
    fm_error failed_err; /* its error */
} pool;

static fm_status write_single(const pool *p, int kind, fm_error *err)
{
    const fm_faultset_outputs *o = p->out;
    switch (kind) {
    case SINGLE_VTU: return fm_faultset_write_vtu(o->vtu, p->fs, err);
    case SINGLE_MSH: return fm_faultset_write_msh(o->msh, p->fs, o->msh_version, err);
    case SINGLE_STL: return fm_faultset_write_stl(o->stl, p->fs, err);
    case SINGLE_EXO: return fm_faultset_write_exodus(o->exo, p->fs, err);
    default: return fm_faultset_write_obj(o->obj, p->fs, err);
    }
}

static void *worker(void *arg)
{
    pool *p = arg;
    fs_tsurf_scratch sc = {0};
    int have_scratch = 0;
    for (;;) {
        pthread_mutex_lock(&p->mu);
        size_t i = p->stop ? p->ntasks : p->next++;
        pthread_mutex_unlock(&p->mu);
        if (i >= p->ntasks)
            break;
        fm_error e;
        fm_error_clear(&e);
        fm_status st;
        if (i < p->nsingles) {
            st = write_single(p, p->singles[i], &e);
        } else {
            /* Scratch is a vertex map of the whole set: made once per
             * thread, on its first TSurf file. */
            if (!have_scratch && fs_tsurf_scratch_init(&sc, &p->plan) != 0) {
                fs_tsurf_scratch_free(&sc);
                st = fm_error_set(&e, FM_ERR_NOMEM, p->out->tsurf_dir, 0, "out of memory");
            } else {
                have_scratch = 1;
                st = fs_tsurf_write_fault(&p->plan, i - p->nsingles, &sc, &e);
            }
        }
        if (st != FM_OK) {
            e.code = st;
            pthread_mutex_lock(&p->mu);
            p->stop = 1;
            if (i < p->failed_task) {
                p->failed_task = i;
                p->failed_err = e;
            }
            pthread_mutex_unlock(&p->mu);
        }
    }
    fs_tsurf_scratch_free(&sc);
    return NULL;
}

fm_status fm_faultset_write_all(const fm_faultset *fs, const fm_faultset_outputs *out,
                                int nthreads, fm_error *err)
{
    const char *where = out->vtu    ? out->vtu
                        : out->msh  ? out->msh
                        : out->stl  ? out->stl
                        : out->obj  ? out->obj
                        : out->exo  ? out->exo
                                    : out->tsurf_dir;
    fm_status st = fm_faultset_validate(fs, where, err);
    if (st != FM_OK)
        return st;
    if (out->msh && out->msh_version != FM_MSH_41 && out->msh_version != FM_MSH_22)
        return fm_error_set(err, FM_ERR_INVALID, out->msh, 0, "unknown MSH version %d",
                            (int)out->msh_version);
    pool p = {.fs = fs, .out = out, .mu = PTHREAD_MUTEX_INITIALIZER};
    const char *paths[NSINGLE] = {out->vtu, out->msh, out->stl, out->obj, out->exo};
    for (int k = 0; k < NSINGLE; k++)
        if (paths[k])
            p.singles[p.nsingles++] = k;
    p.ntasks = p.nsingles;
    if (out->tsurf_dir) {
        /* Names and directory before any file, so that they cannot fail
         * part way. */
        st = fs_tsurf_plan_make(&p.plan, out->tsurf_dir, fs, err);
        if (st != FM_OK) {
            fs_tsurf_plan_free(&p.plan);
            return st;
        }
        p.ntasks += fs->nfaults;
    }
    p.failed_task = p.ntasks;

    size_t nextra = nthreads > 1 ? (size_t)nthreads - 1 : 0;
    if (nextra > p.ntasks)
        nextra = p.ntasks;
    pthread_t *th = nextra ? malloc(nextra * sizeof *th) : NULL;
    size_t started = 0;
    /* Fewer threads than asked (none at all, even) only take longer. */
    while (th && started < nextra && pthread_create(&th[started], NULL, worker, &p) == 0)
        started++;
    worker(&p);
    for (size_t k = 0; k < started; k++)
        pthread_join(th[k], NULL);
    free(th);
    fs_tsurf_plan_free(&p.plan);
    pthread_mutex_destroy(&p.mu);
    if (p.failed_task < p.ntasks) {
        if (err)
            *err = p.failed_err;
        return p.failed_err.code;
    }
    return FM_OK;
}
