/* Every output of a fault set on several threads: one piece of work per
 * file, handed out in a fixed order, so that which thread writes a file
 * never changes its bytes. */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "faultset_internal.h"
#include "fm_names.h"

enum { SINGLE_VTU, SINGLE_MSH, SINGLE_STL, SINGLE_OBJ, SINGLE_EXO, NSINGLE };

typedef struct pool {
    const fm_faultset *fs;
    const fm_faultset_outputs *out;
    int singles[NSINGLE]; /* the single-file outputs asked for, in order */
    size_t nsingles, ntasks;
    fs_tsurf_plan plan;
    const fm_error *plan_err; /* the TSurf files cannot be written: why */
    fm_error *errs;           /* per task: code FM_OK when written, else why not */

    pthread_mutex_t mu;
    size_t next; /* next task to hand out */
} pool;

static const char *single_path(const fm_faultset_outputs *o, int kind)
{
    const char *paths[NSINGLE] = {o->vtu, o->msh, o->stl, o->obj, o->exo};
    return paths[kind];
}

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

static fm_status run_task(pool *p, size_t i, fs_tsurf_scratch *sc, int *have_scratch,
                          fm_error *e)
{
    if (i < p->nsingles)
        return write_single(p, p->singles[i], e);
    if (p->plan_err) {
        *e = *p->plan_err;
        return e->code;
    }
    /* Scratch is a vertex map of the whole set: made once per thread, on
     * its first TSurf file. */
    if (!*have_scratch) {
        if (fs_tsurf_scratch_init(sc, &p->plan) != 0) {
            fs_tsurf_scratch_free(sc);
            return fm_error_set(e, FM_ERR_NOMEM, p->out->tsurf_dir, 0, "out of memory");
        }
        *have_scratch = 1;
    }
    return fs_tsurf_write_fault(&p->plan, i - p->nsingles, sc, e);
}

static void *worker(void *arg)
{
    pool *p = arg;
    fs_tsurf_scratch sc = {0};
    int have_scratch = 0;
    for (;;) {
        pthread_mutex_lock(&p->mu);
        size_t i = p->next++;
        pthread_mutex_unlock(&p->mu);
        if (i >= p->ntasks)
            break;
        fm_error e;
        fm_error_clear(&e);
        fm_status st = run_task(p, i, &sc, &have_scratch, &e);
        e.code = st;
        p->errs[i] = e; /* each task has a slot of its own: no lock */
    }
    fs_tsurf_scratch_free(&sc);
    return NULL;
}

/* Every file asked for, as not written, for why (the set could not be
 * written at all). */
static fm_status all_failed(const fm_faultset_outputs *out, const fm_error *why)
{
    for (int k = 0; k < NSINGLE && out->done; k++)
        if (single_path(out, k))
            out->done(out->done_ctx, single_path(out, k), SIZE_MAX, why);
    if (out->tsurf_dir && out->done)
        out->done(out->done_ctx, out->tsurf_dir, SIZE_MAX, why);
    return why->code;
}

/* out->done for each task, in order; the first failure into err. */
static fm_status account(pool *p, fm_error *err)
{
    fm_status first = FM_OK;
    char *path = NULL;
    if (p->ntasks > p->nsingles)
        path = malloc(strlen(p->out->tsurf_dir) + FM_STEM_MAX + 40);
    for (size_t i = 0; i < p->ntasks; i++) {
        const fm_error *e = p->errs[i].code != FM_OK ? &p->errs[i] : NULL;
        const char *where;
        size_t fault = SIZE_MAX;
        if (i < p->nsingles) {
            where = single_path(p->out, p->singles[i]);
        } else {
            fault = i - p->nsingles;
            if (path)
                sprintf(path, "%s/%s", p->out->tsurf_dir, p->plan.files[fault]);
            where = path ? path : p->out->tsurf_dir;
        }
        if (e && first == FM_OK) {
            first = e->code;
            if (err)
                *err = *e;
        }
        if (p->out->done)
            p->out->done(p->out->done_ctx, where, fault, e);
    }
    free(path);
    return first;
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
    fm_error e;
    fm_error_clear(&e);
    fm_status st = fm_faultset_validate(fs, where, &e);
    if (st == FM_OK && out->msh && out->msh_version != FM_MSH_41 &&
        out->msh_version != FM_MSH_22)
        st = fm_error_set(&e, FM_ERR_INVALID, out->msh, 0, "unknown MSH version %d",
                          (int)out->msh_version);
    if (st != FM_OK) {
        if (err)
            *err = e;
        return all_failed(out, &e);
    }
    pool p = {.fs = fs, .out = out, .mu = PTHREAD_MUTEX_INITIALIZER};
    for (int k = 0; k < NSINGLE; k++)
        if (single_path(out, k))
            p.singles[p.nsingles++] = k;
    p.ntasks = p.nsingles;
    fm_error plan_err;
    fm_error_clear(&plan_err);
    if (out->tsurf_dir) {
        /* Names and directory before any file, so that they cannot fail
         * part way; when they fail the other files are still written. */
        if (fs_tsurf_plan_make(&p.plan, out->tsurf_dir, fs, &plan_err) != FM_OK) {
            plan_err.code = plan_err.code ? plan_err.code : FM_ERR_IO;
            p.plan_err = &plan_err;
        }
        if (p.plan.files)
            p.ntasks += fs->nfaults;
    }
    p.errs = calloc(p.ntasks + 1, sizeof *p.errs);
    if (!p.errs) {
        fs_tsurf_plan_free(&p.plan);
        fm_error_set(&e, FM_ERR_NOMEM, where, 0, "out of memory");
        if (err)
            *err = e;
        return all_failed(out, &e);
    }

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
    st = account(&p, err);
    if (p.plan_err && !p.plan.files) {
        /* the names themselves could not be made */
        if (out->done)
            out->done(out->done_ctx, out->tsurf_dir, SIZE_MAX, p.plan_err);
        if (st == FM_OK) {
            st = p.plan_err->code;
            if (err)
                *err = *p.plan_err;
        }
    }
    free(p.errs);
    fs_tsurf_plan_free(&p.plan);
    pthread_mutex_destroy(&p.mu);
    return st;
}
