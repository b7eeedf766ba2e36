/* model.igs and the simulator files written beside the fault-set formats
 * (remesh_set.c), each on a thread of its own: they are single files made
 * by one thread each, and one after the other they were most of the
 * write stage at fine sizes. What each file became is noted in the run's
 * output log only after they are joined, in the order a run writing them
 * one after the other notes them, so report.json does not depend on which
 * finished first; every file is the same bytes either way. */
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include "run_internal.h"

static void *igs_main(void *p)
{
    side_write *w = p;
    w->st = fm_cad_write_iges_reprojected(w->path, w->cad, w->ncad, w->crs, w->rp, &w->err);
    return NULL;
}

/* Keeps what sim_write says of each file for side_join. */
static void keep_done(void *ctx, const char *path, size_t fault, const fm_error *err)
{
    side_write *w = ctx;
    if (w->ndone == sizeof w->done / sizeof *w->done)
        return; /* sim_write writes two files at most */
    side_done *d = &w->done[w->ndone++];
    d->path = strdup(path);
    d->fault = fault;
    d->failed = err != NULL;
    if (err)
        d->err = *err;
}

static void *sim_main(void *p)
{
    side_write *w = p;
    w->st = sim_write(w->sc, w->fs, w->sa, w->dir, w->rsqsim, w->eqsim, keep_done, w);
    return NULL;
}

void side_start(side_write *w)
{
    fm_error_clear(&w->err);
    void *(*fn)(void *) = w->kind == SIDE_IGES ? igs_main : sim_main;
    w->threaded = pthread_create(&w->thread, NULL, fn, w) == 0;
    if (!w->threaded)
        fn(w); /* no thread to be had: in turn, as before */
}

fm_status side_join(side_write *w, output_log *log)
{
    if (w->threaded)
        pthread_join(w->thread, NULL);
    w->threaded = 0;
    if (w->kind == SIDE_IGES)
        outputs_note(log, w->path, SIZE_MAX, OUTPUT_SET, w->st == FM_OK ? NULL : &w->err);
    for (size_t i = 0; i < w->ndone; i++) {
        side_done *d = &w->done[i];
        fm_error e;
        if (!d->path) { /* out of memory while noting: say so for that file */
            fm_error_set(&e, FM_ERR_NOMEM, w->dir, 0, "out of memory");
            outputs_done(log, w->dir, d->fault, &e);
        } else {
            outputs_done(log, d->path, d->fault, d->failed ? &d->err : NULL);
        }
        free(d->path);
        d->path = NULL;
    }
    w->ndone = 0;
    return w->st;
}
