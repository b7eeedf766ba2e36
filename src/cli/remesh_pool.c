/* `faultmesh remesh`: the files' faults fitted and meshed on --jobs
 * threads, and meshed again until every curve a mesh took is in its
 * partners' meshes too. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <pthread.h>
#include <sys/stat.h>

#include "remesh_run.h"

typedef struct pool {
    const remesh_cli *cli;
    const fm_connect_plan *plan;
    int phase;          /* 0: fit, 1: mesh, 2: mesh again those marked */
    const unsigned char *excluded; /* phase 2: plan curves left out */
    file_job *jobs;
    const size_t *order; /* the order jobs are handed out in */
    const double *bytes;  /* per job: its file's size, the progress weight */
    size_t n, next;
    pthread_mutex_t mu;
} pool;

/* Whether a job has faults to mesh again. */
static int marked(const file_job *job)
{
    for (size_t o = 0; job->redo && o < job->n; o++)
        if (job->redo[o])
            return 1;
    return 0;
}

static void *worker(void *arg)
{
    pool *p = arg;
    for (;;) {
        pthread_mutex_lock(&p->mu);
        size_t i = p->next++;
        pthread_mutex_unlock(&p->mu);
        if (i >= p->n)
            return NULL;
        size_t at = p->order ? p->order[i] : i;
        file_job *job = &p->jobs[at];
        if (p->phase == 0)
            fit_file(p->cli, job);
        else
            mesh_file(p->plan, p->excluded, job, p->phase == 2);
        if (p->phase != 2 || marked(job))
            progress_step(p->cli->prog, p->bytes ? p->bytes[at] : 1);
    }
}

typedef struct job_key {
    long long bytes;
    size_t index;
} job_key;

static int larger_first(const void *a, const void *b)
{
    const job_key *x = a, *y = b;
    if (x->bytes != y->bytes)
        return x->bytes < y->bytes ? 1 : -1;
    return (x->index > y->index) - (x->index < y->index);
}

/* Largest files first: a large fault started last would keep one thread
 * busy while the others idle (longest-processing-time-first scheduling).
 * Which thread meshes a fault never changes its result, and results are
 * merged in input order, so the order is free. */
static size_t *schedule(const file_job *jobs, size_t n, double *bytes)
{
    size_t *order = malloc((n ? n : 1) * sizeof *order);
    job_key *key = malloc((n ? n : 1) * sizeof *key);
    if (!order || !key) {
        free(key);
        free(order);
        return NULL; /* input order then */
    }
    for (size_t i = 0; i < n; i++) {
        struct stat sb;
        key[i].bytes = stat(jobs[i].path, &sb) == 0 ? (long long)sb.st_size : 0;
        key[i].index = i;
        if (bytes)
            bytes[i] = (double)key[i].bytes;
    }
    qsort(key, n, sizeof *key, larger_first);
    for (size_t i = 0; i < n; i++)
        order[i] = key[i].index;
    free(key);
    return order;
}

/* Runs one phase of the jobs on cli->jobs threads (the calling one
 * included). */
void run_jobs(const remesh_cli *cli, const fm_connect_plan *plan, int phase,
              const unsigned char *excluded, file_job *jobs, size_t n)
{
    double *bytes = malloc((n ? n : 1) * sizeof *bytes);
    size_t *order = schedule(jobs, n, bytes);
    size_t count = 0;
    double weight = 0;
    for (size_t i = 0; i < n; i++)
        if (phase != 2 || marked(&jobs[i])) {
            count++;
            weight += bytes ? bytes[i] : 1;
        }
    static const char *stage[3] = {"read and fit", "mesh", "mesh again"};
    progress_begin(cli->prog, stage[phase], count, "files", weight);
    pool p = {cli, plan, phase, excluded, jobs, order, bytes, n, 0, PTHREAD_MUTEX_INITIALIZER};
    size_t nt = cli->jobs > 1 ? (size_t)cli->jobs - 1 : 0;
    pthread_t *th = nt ? calloc(nt, sizeof *th) : NULL;
    size_t started = 0;
    for (size_t k = 0; th && k < nt; k++)
        if (pthread_create(&th[k], NULL, worker, &p) == 0)
            started++;
        else
            break;
    worker(&p);
    for (size_t k = 0; k < started; k++)
        pthread_join(th[k], NULL);
    free(th);
    free(order);
    free(bytes);
    progress_end(cli->prog);
}

/* A fault that failed in meshing or came out empty took none of the plan
 * curves it was given: they count as dropped, so that its neighbours are
 * meshed again without them rather than end at (or fill a gap to) a curve
 * nobody shares. The number newly excluded. */
static size_t exclude_failed(const fm_connect_plan *plan, const file_job *job, size_t o,
                             unsigned char *excluded, size_t nc)
{
    const fault_result *r = &job->res[o];
    if (!job->model || !job->model[o] || !r->status ||
        (strcmp(r->status, "error") && strcmp(r->status, "empty")))
        return 0;
    size_t added = 0;
    for (size_t s = 0; s < fm_model_nsheets(job->model[o]); s++) {
        const fm_connect_shared *sh;
        size_t n = fm_connect_plan_sheet(plan, job->first + o, s, &sh);
        for (size_t c = 0; c < n; c++)
            if (sh[c].curve < nc && !excluded[sh[c].curve]) {
                excluded[sh[c].curve] = 1;
                added++;
            }
    }
    return added;
}

/* A junction is made only when both sheets take its curve. Faults are
 * meshed each on its own, so a curve one sheet could not fit (or one of a
 * fault that failed) is still in the other's mesh: that sheet trimmed its
 * flap or filled its gap to a curve it shares with nobody (San Pedro
 * Escarpment YngB: filled 1 km past its edge towards a curve F could not
 * take). Those faults are meshed again without such curves, until no
 * curve a mesh took was dropped by another (the set of dropped curves
 * only grows, so this ends). */
void settle_curves(const remesh_cli *cli, const fm_connect_plan *plan, file_job *jobs,
                   size_t njobs)
{
    size_t nc = fm_connect_plan_get_stats(plan)->curves;
    unsigned char *excluded = calloc(nc + 1, 1);
    if (!excluded)
        return;
    for (;;) {
        size_t added = 0, again = 0;
        for (size_t i = 0; i < njobs; i++)
            for (size_t o = 0; jobs[i].res && o < jobs[i].n; o++) {
                const fault_result *r = &jobs[i].res[o];
                added += exclude_failed(plan, &jobs[i], o, excluded, nc);
                for (size_t k = 0; k < r->ndropped; k++)
                    if (r->dropped_curves[k] < nc && !excluded[r->dropped_curves[k]]) {
                        excluded[r->dropped_curves[k]] = 1;
                        added++;
                    }
            }
        if (!added)
            break;
        for (size_t i = 0; i < njobs; i++) {
            file_job *job = &jobs[i];
            if (!job->res || !job->model)
                continue;
            for (size_t o = 0; o < job->n; o++) {
                const fault_result *r = &job->res[o];
                int redo = 0;
                for (size_t k = 0; k < r->nused && !redo; k++)
                    redo = r->used_curves[k] < nc && excluded[r->used_curves[k]];
                if (!redo || !job->model[o] || !r->status || strcmp(r->status, "ok"))
                    continue;
                if (!job->redo)
                    job->redo = calloc(job->n, 1);
                if (!job->redo)
                    continue;
                job->redo[o] = 1;
                again++;
            }
        }
        if (!again)
            break;
        run_jobs(cli, plan, 2, excluded, jobs, njobs);
        for (size_t i = 0; i < njobs; i++)
            if (jobs[i].redo)
                memset(jobs[i].redo, 0, jobs[i].n);
    }
    free(excluded);
}
