/* `faultmesh remesh`: the files' faults fitted and meshed on --jobs
 * threads, and meshed again until every curve a mesh took is in its
 * partners' meshes too. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fm_parallel.h"
#include "fm_sort.h"
#include "run_internal.h"

/* Rounds of meshing again at most (settle_curves). */
#define SETTLE_ROUNDS 16

typedef struct pool {
    const remesh_cli *cli;
    const fm_connect_plan *plan;
    int phase;          /* 0: fit, 1: mesh, 2: mesh again those marked */
    const curve_filter *flt; /* phase 2: plan curves (or pieces) left out */
    file_job *jobs;
    const size_t *order; /* the order jobs are handed out in */
} pool;

/* Whether a job has faults to mesh again. */
static int marked(const file_job *job)
{
    for (size_t o = 0; job->redo && o < job->n; o++)
        if (job->redo[o])
            return 1;
    return 0;
}

/* The i-th job handed out. */
static void run_one(void *arg, size_t i)
{
    pool *p = arg;
    size_t at = p->order ? p->order[i] : i;
    file_job *job = &p->jobs[at];
    /* cancelled: the files not begun are left (the run then ends) */
    if (run_cancelled(p->cli->ctl))
        return;
    if (p->phase == 0)
        fit_file(p->cli, job);
    else
        mesh_file(p->plan, p->flt, job, p->phase == 2);
    if (p->phase != 2 || marked(job))
        run_progress_step(p->cli->ctl, 1);
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
static size_t *schedule(const file_job *jobs, size_t n)
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
        /* an in-memory input weighs what its TSurf file would (about 40
         * bytes a triangle: a TRGL line, half a VRTX line) */
        if (jobs[i].given)
            key[i].bytes = 40 * (long long)fm_mesh_ntriangles(jobs[i].given);
        else
            key[i].bytes = stat(jobs[i].path, &sb) == 0 ? (long long)sb.st_size : 0;
        key[i].index = i;
    }
    qsort(key, n, sizeof *key, larger_first);
    for (size_t i = 0; i < n; i++)
        order[i] = key[i].index;
    free(key);
    return order;
}

void run_jobs(const remesh_cli *cli, const fm_connect_plan *plan, int phase,
              const curve_filter *flt, file_job *jobs, size_t n)
{
    run_jobs_open(cli, plan, phase, flt, jobs, n);
    run_progress_end(cli->ctl);
}

void run_jobs_open(const remesh_cli *cli, const fm_connect_plan *plan, int phase,
                   const curve_filter *flt, file_job *jobs, size_t n)
{
    size_t *order = schedule(jobs, n);
    size_t count = 0;
    for (size_t i = 0; i < n; i++)
        count += phase != 2 || marked(&jobs[i]);
    /* Progress counts files done, not their bytes: a share of bytes read
     * as a share of files ("24/438 files, 25%") misleads, and the time a
     * file takes follows its surface more than its size. Later rounds
     * mesh again the files whose shared curves a neighbour dropped; the
     * summary's mesh time includes them. */
    static const char *stage[3] = {"read and fit", "mesh", "mesh again"};
    static const char *unit[3] = {"files", "files", "files whose shared curves changed"};
    run_progress_begin(cli->ctl, stage[phase], count, unit[phase], 0);
    pool p = {cli, plan, phase, flt, jobs, order};
    fm_parallel_for(n, cli->jobs, run_one, &p, NULL, NULL, 0, 0);
    free(order);
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

/* The keys of v (sorted by key) whose index is curve c, each once, into
 * out (room for n); their count. For the edges of c a mesh holds
 * (curve_pieces) or a clip keeps. */
static size_t curve_keys(const fm_keyed *v, size_t n, size_t c, uint64_t *out)
{
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        if (v[i].index == c && (k == 0 || out[k - 1] != v[i].key))
            out[k++] = v[i].key;
    return k;
}

/* The keys in both sorted lists a and b, into out (may be a or b); their
 * count. */
static size_t intersect(const uint64_t *a, size_t na, const uint64_t *b, size_t nb,
                        uint64_t *out)
{
    size_t n = 0;
    for (size_t i = 0, k = 0; i < na && k < nb;) {
        if (a[i] == b[k]) {
            out[n++] = a[i];
            i++;
            k++;
        } else if (a[i] < b[k]) {
            i++;
        } else {
            k++;
        }
    }
    return n;
}

/* The fault result of each plan fault (NULL: none). */
static fault_result **plan_results(file_job *jobs, size_t njobs, size_t *nf)
{
    *nf = 0;
    for (size_t i = 0; i < njobs; i++)
        if (jobs[i].res && jobs[i].model && jobs[i].first + jobs[i].n > *nf)
            *nf = jobs[i].first + jobs[i].n;
    fault_result **of = calloc(*nf + 1, sizeof *of);
    for (size_t i = 0; of && i < njobs; i++)
        for (size_t o = 0; jobs[i].res && jobs[i].model && o < jobs[i].n; o++)
            of[jobs[i].first + o] = &jobs[i].res[o];
    return of;
}

static int marks_redo(file_job *jobs, size_t njobs, const fault_result *r)
{
    for (size_t i = 0; i < njobs; i++)
        if (jobs[i].res && r >= jobs[i].res && r < jobs[i].res + jobs[i].n) {
            size_t o = (size_t)(r - jobs[i].res);
            if (!jobs[i].redo)
                jobs[i].redo = calloc(jobs[i].n, 1);
            if (!jobs[i].redo || jobs[i].redo[o])
                return 0;
            jobs[i].redo[o] = 1;
            return 1;
        }
    return 0;
}

/* A sheet holds only the stretch of a curve its domain and its other
 * curves leave it, and two sheets may keep different stretches of the
 * curve they share: where one holds a stretch the other does not, it ended
 * at (or filled a gap to) a curve nobody else is at (Laguna Salada east
 * branch dipping splay filled 1 km past its edge, 2 km along curves that
 * Yuha Well west steep and Sierra Cucapah NW splay hold only a kilometre
 * of). Each such curve is clipped to the edges both hold, or left out when
 * they hold none in common, and the faults holding more are marked to be
 * meshed again. The curves clipped (or left out). */
static size_t settle_pieces(const fm_connect_plan *plan, file_job *jobs, size_t njobs,
                            curve_filter *flt, size_t *again)
{
    size_t nf, changed = 0, nj = fm_connect_plan_njunctions(plan);
    fault_result **of = plan_results(jobs, njobs, &nf);
    size_t most = 0;
    for (size_t f = 0; of && f < nf; f++)
        most = of[f] && of[f]->npieces > most ? of[f]->npieces : most;
    uint64_t *ha = malloc((most + 1) * sizeof *ha), *hb = malloc((most + 1) * sizeof *hb);
    uint64_t *both = malloc((most + 1) * sizeof *both);
    uint64_t *kc = malloc((flt->nkeep + most + 1) * sizeof *kc);
    for (size_t j = 0; of && ha && hb && both && kc && j < nj; j++) {
        const fm_connect_junction *jn = fm_connect_plan_junction(plan, j);
        if (jn->type == FM_JUNCTION_UNJOINED || jn->curve < 0 || jn->fault[0] == jn->fault[1] ||
            flt->excluded[jn->curve])
            continue;
        fault_result *ra = of[jn->fault[0]], *rb = of[jn->fault[1]];
        if (!ra || !rb || !ra->status || !rb->status || strcmp(ra->status, "ok") ||
            strcmp(rb->status, "ok"))
            continue; /* a failed fault's curves are left out whole */
        size_t c = (size_t)jn->curve;
        size_t na = curve_keys(ra->curve_pieces, ra->npieces, c, ha);
        size_t nb = curve_keys(rb->curve_pieces, rb->npieces, c, hb);
        size_t n = intersect(ha, na, hb, nb, both);
        /* Only a sheet that closed a gap to the curve fills where its
         * partner is not; one trimmed at it or crossed by it loses nothing
         * it should keep. One edge more (a curve node a size past the
         * partner's last) keeps the fill within a size of the shared curve,
         * and clipping it leaves a sliver of a pocket where curves meet at
         * a few degrees (Sierra Cucapah at Borrego, at 500 m). */
        int xa = na >= n + 2 && jn->role[0] == FM_CONNECT_GAP;
        int xb = nb >= n + 2 && jn->role[1] == FM_CONNECT_GAP;
        if (!xa && !xb)
            continue;
        /* what the other holds, or what both do when both filled */
        const uint64_t *to = xa && xb ? both : xa ? hb : ha;
        size_t nto = xa && xb ? n : xa ? nb : na;
        /* A clip only shrinks: the edges of two neighbour nodes that other
         * curves put in a mesh may be there without being asked for, so
         * a clip stands until it would keep fewer. */
        if (flt->clipped[c]) {
            size_t nk = curve_keys(flt->keep, flt->nkeep, c, kc);
            size_t m = intersect(to, nto, kc, nk, kc);
            if (m == nk)
                continue;
            to = kc;
            nto = m;
        }
        size_t w = 0;
        for (size_t i = 0; i < flt->nkeep; i++)
            if (flt->keep[i].index != c)
                flt->keep[w++] = flt->keep[i];
        flt->nkeep = w;
        fm_keyed *grown = nto ? realloc(flt->keep, (flt->nkeep + nto) * sizeof *grown) : flt->keep;
        if (!grown)
            break; /* out of memory: the curve stays as it is */
        flt->keep = grown;
        for (size_t i = 0; i < nto; i++)
            flt->keep[flt->nkeep++] = (fm_keyed){to[i], c};
        if (nto)
            flt->clipped[c] = 1;
        else
            flt->excluded[c] = 1;
        *again += (size_t)(xa && marks_redo(jobs, njobs, ra));
        *again += (size_t)(xb && marks_redo(jobs, njobs, rb));
        changed++;
    }
    if (changed && fm_sort_keyed(flt->keep, flt->nkeep))
        flt->nkeep = 0; /* out of memory: no edge kept, so clipped curves are left out */
    free(ha);
    free(hb);
    free(both);
    free(kc);
    free(of);
    return changed;
}

/* A junction is made only when both sheets take its curve. Faults are
 * meshed each on its own, so a curve one sheet could not fit (or one of a
 * fault that failed) is still in the other's mesh: that sheet trimmed its
 * flap or filled its gap to a curve it shares with nobody (San Pedro
 * Escarpment YngB: filled 1 km past its edge towards a curve F could not
 * take). Those faults are meshed again without such curves; then a sheet
 * that filled a gap along more of a curve than its partner holds is meshed
 * again with the curve clipped (settle_pieces); and so on until nothing
 * changes (what is taken only shrinks, so this ends). */
int settle_curves(const remesh_cli *cli, const fm_connect_plan *plan, file_job *jobs,
                  size_t njobs)
{
    size_t nc = fm_connect_plan_get_stats(plan)->curves;
    curve_filter flt = {calloc(nc + 1, 1), calloc(nc + 1, 1), NULL, 0};
    if (!flt.excluded || !flt.clipped) {
        free(flt.excluded);
        free(flt.clipped);
        return 0;
    }
    unsigned char *excluded = flt.excluded;
    /* Each round only shrinks what is taken, so this ends; the bound keeps
     * a chain of clips from costing more than a few meshings. */
    int rounds = 0;
    for (int round = 0; round < SETTLE_ROUNDS; round++) {
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
        if (!added && !settle_pieces(plan, jobs, njobs, &flt, &again))
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
                again += (size_t)marks_redo(jobs, njobs, r);
            }
        }
        if (!again)
            break;
        run_jobs(cli, plan, 2, &flt, jobs, njobs);
        rounds++;
        for (size_t i = 0; i < njobs; i++)
            if (jobs[i].redo)
                memset(jobs[i].redo, 0, jobs[i].n);
    }
    free(flt.excluded);
    free(flt.clipped);
    free(flt.keep);
    return rounds;
}
