/* Near-duplicate faults: how much of each fault of a pair lies within a
 * tolerance of the other, and which of a duplicate pair to keep.
 *
 * The CFM carries historical-rupture composites (the 1857 and 1812 San
 * Andreas ruptures, Landers, ...) and alternative representations (_alt1,
 * _alt2) next to the section faults they repeat. Their surfaces lie within
 * tens of metres of each other over kilometres, where the intersection of
 * two fitted surfaces is a tangle of closed loops, not a junction: such a
 * pair must be recognised before it is joined. */
#include "connect_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

void fm_connect_duplicate_options_default(fm_connect_duplicate_options *opt)
{
    opt->tolerance = 50.0;
    opt->min_share = 0.5;
    opt->keep = FM_CONNECT_KEEP_SMALLER;
    opt->nthreads = 1;
}

/* All sheets' samples of the trimmed surface, as one mesh. */
static fm_mesh *fault_samples(const fm_model *m)
{
    fm_mesh *all = fm_mesh_create();
    if (!all)
        return NULL;
    for (size_t s = 0; s < fm_model_nsheets(m); s++) {
        const fm_mesh *sm = fm_model_samples(m, s);
        if (sm && fm_mesh_append(all, sm, (int32_t)s) != FM_OK) {
            fm_mesh_destroy(all);
            return NULL;
        }
    }
    return all;
}

static int stop_at_first(int32_t t, void *user)
{
    (void)t;
    *(int *)user = 1;
    return 1;
}

static void centroid(const double *p, const double *q, const double *r, double c[3])
{
    for (int k = 0; k < 3; k++)
        c[k] = (p[k] + q[k] + r[k]) / 3;
}

/* A fault's sample triangles in runs of consecutive ones (about a sheet
 * triangle's worth: each is subdivided into 16, so a few hundred metres
 * across), with the box of each run's vertices and a tree of those boxes:
 * a run whose box stays more than the tolerance from another fault's
 * samples is done with at once. */
#define RUN 16

typedef struct fault_runs {
    size_t n;
    size_t *sheet, *t0;    /* per run: sheet and first triangle; it ends at t0 + RUN or
                              at the end of the sheet */
    double *box;           /* per run: lo[3], hi[3] */
    double lo[3], hi[3];   /* of all runs */
    double area;           /* of all triangles, summed in order */
    fm_closest_tree *tree; /* run boxes as degenerate triangles (lo, hi, lo) */
} fault_runs;

static void runs_free(fault_runs *r)
{
    free(r->sheet);
    free(r->t0);
    free(r->box);
    fm_closest_tree_destroy(r->tree);
    memset(r, 0, sizeof *r);
}

static fm_status runs_build(const fm_model *m, fault_runs *r, fm_error *err)
{
    memset(r, 0, sizeof *r);
    size_t n = 0;
    for (size_t s = 0; s < fm_model_nsheets(m); s++) {
        const fm_mesh *a = fm_model_samples(m, s);
        n += a ? (fm_mesh_ntriangles(a) + RUN - 1) / RUN : 0;
    }
    r->sheet = malloc((n + 1) * sizeof *r->sheet);
    r->t0 = malloc((n + 1) * sizeof *r->t0);
    r->box = malloc(6 * (n + 1) * sizeof *r->box);
    fm_mesh *bm = fm_mesh_create();
    if (!r->sheet || !r->t0 || !r->box || !bm || fm_mesh_reserve(bm, 2 * n, n) != FM_OK) {
        fm_mesh_destroy(bm);
        runs_free(r);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    }
    for (int k = 0; k < 3; k++) {
        r->lo[k] = INFINITY;
        r->hi[k] = -INFINITY;
    }
    for (size_t s = 0; s < fm_model_nsheets(m); s++) {
        const fm_mesh *a = fm_model_samples(m, s);
        if (!a)
            continue;
        const double *X = fm_mesh_vertices(a);
        const int32_t *T = fm_mesh_triangles(a);
        size_t nt = fm_mesh_ntriangles(a);
        for (size_t t0 = 0; t0 < nt; t0 += RUN) {
            double *lo = r->box + 6 * r->n, *hi = lo + 3;
            for (int k = 0; k < 3; k++) {
                lo[k] = INFINITY;
                hi[k] = -INFINITY;
            }
            for (size_t t = t0; t < t0 + RUN && t < nt; t++) {
                const double *P[3] = {X + 3 * (size_t)T[3 * t], X + 3 * (size_t)T[3 * t + 1],
                                      X + 3 * (size_t)T[3 * t + 2]};
                r->area += fm_triangle_area(P[0], P[1], P[2]);
                for (int c = 0; c < 3; c++)
                    for (int k = 0; k < 3; k++) {
                        lo[k] = P[c][k] < lo[k] ? P[c][k] : lo[k];
                        hi[k] = P[c][k] > hi[k] ? P[c][k] : hi[k];
                    }
            }
            for (int k = 0; k < 3; k++) {
                r->lo[k] = fmin(r->lo[k], lo[k]);
                r->hi[k] = fmax(r->hi[k], hi[k]);
            }
            int32_t v = fm_mesh_add_vertex(bm, lo[0], lo[1], lo[2]);
            fm_mesh_add_vertex(bm, hi[0], hi[1], hi[2]);
            fm_mesh_add_triangle(bm, v, v + 1, v, 0);
            r->sheet[r->n] = s;
            r->t0[r->n] = t0;
            r->n++;
        }
    }
    r->tree = fm_closest_tree_create_quick(bm, err);
    fm_mesh_destroy(bm);
    if (!r->tree) {
        runs_free(r);
        return err ? err->code : FM_ERR_NOMEM;
    }
    return FM_OK;
}

/* Whether the box [lo - d, hi + d] meets a triangle (box) of the tree. */
static int box_meets(const fm_closest_tree *t, const double *lo, const double *hi, double d)
{
    double a[3], b[3];
    for (int k = 0; k < 3; k++) {
        a[k] = lo[k] - d;
        b[k] = hi[k] + d;
    }
    int hit = 0;
    fm_closest_tree_box_query(t, a, b, stop_at_first, &hit);
    return hit;
}

/* Rounding allowance (m) on top of the tolerance when boxes decide that
 * nothing can lie within it. */
#define PAD 1e-3

/* The tree of the part of fault m's samples (one mesh, all sheets, as one
 * tree of them would see it) whose runs come within tol of a run of one
 * of the other faults: the only triangles that can lie within tol of the
 * others' samples. */
static fm_closest_tree *near_part(const fm_model *m, const fault_runs *own,
                                  const fault_runs *const *other, size_t nother, double tol,
                                  fm_error *err)
{
    unsigned char *mark = calloc(own->n + 1, 1);
    fm_mesh *all = fault_samples(m);
    size_t ns = fm_model_nsheets(m);
    size_t *base = calloc(ns + 1, sizeof *base);
    int32_t *part = NULL;
    fm_closest_tree *tree = NULL;
    if (!mark || !all || !base)
        goto done;
    for (size_t o = 0; o < nother; o++) {
        const fault_runs *q = other[o];
        for (size_t r = 0; r < own->n; r++) {
            const double *lo = own->box + 6 * r, *hi = lo + 3;
            int apart = 0;
            for (int k = 0; k < 3; k++)
                apart |= lo[k] - tol - PAD > q->hi[k] || hi[k] + tol + PAD < q->lo[k];
            if (!mark[r] && !apart)
                mark[r] = (unsigned char)box_meets(q->tree, lo, hi, tol + PAD);
        }
    }
    /* triangle numbers in the one mesh of all sheets (fault_samples) */
    for (size_t s = 0; s < ns; s++) {
        const fm_mesh *a = fm_model_samples(m, s);
        base[s + 1] = base[s] + (a ? fm_mesh_ntriangles(a) : 0);
    }
    part = malloc((base[ns] + 1) * sizeof *part);
    if (!part)
        goto done;
    size_t np = 0;
    for (size_t r = 0; r < own->n; r++) {
        if (!mark[r])
            continue;
        size_t s = own->sheet[r], nt = base[s + 1] - base[s];
        for (size_t t = own->t0[r]; t < own->t0[r] + RUN && t < nt; t++)
            part[np++] = (int32_t)(base[s] + t);
    }
    tree = fm_closest_tree_create_part(all, part, np, NULL);
done:
    if (!tree)
        fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    free(mark);
    free(base);
    free(part);
    fm_mesh_destroy(all);
    return tree;
}

/* The part of fault m's sampled area (by triangle centroids) within tol of
 * any of the trees, summed triangle by triangle in order. Sample triangles
 * are a few hundred metres at most, far below the kilometres a duplicate
 * shares, so centroids weigh the area well. A run whose box stays more
 * than tol from every tree adds nothing and is passed over whole. NAN when
 * memory runs out. */
static double near_area(const fm_model *m, const fault_runs *runs,
                        const fm_closest_tree *const *trees, size_t ntrees, double tol)
{
    double sum = 0;
    int32_t *hint = malloc((ntrees + 1) * sizeof *hint);
    unsigned char *meets = malloc(ntrees + 1);
    if (!hint || !meets) {
        free(hint);
        free(meets);
        return NAN;
    }
    for (size_t k = 0; k < ntrees; k++)
        hint[k] = -1;
    for (size_t r = 0; r < runs->n; r++) {
        const double *lo = runs->box + 6 * r, *hi = lo + 3;
        int any = 0;
        for (size_t k = 0; k < ntrees; k++)
            any |= meets[k] = (unsigned char)box_meets(trees[k], lo, hi, tol + PAD);
        if (!any)
            continue;
        const fm_mesh *a = fm_model_samples(m, runs->sheet[r]);
        const double *X = fm_mesh_vertices(a);
        const int32_t *T = fm_mesh_triangles(a);
        size_t nt = fm_mesh_ntriangles(a);
        for (size_t t = runs->t0[r]; t < runs->t0[r] + RUN && t < nt; t++) {
            const double *p = X + 3 * (size_t)T[3 * t], *q = X + 3 * (size_t)T[3 * t + 1],
                         *w = X + 3 * (size_t)T[3 * t + 2];
            double c[3];
            centroid(p, q, w, c);
            int near = 0;
            for (size_t k = 0; k < ntrees && !near; k++)
                near = meets[k] && fm_closest_within(trees[k], c, tol, &hint[k]);
            if (near)
                sum += fm_triangle_area(p, q, w);
        }
    }
    free(hint);
    free(meets);
    return sum;
}

fm_status fm_connect_overlap(const fm_model *a, const fm_model *b, double tolerance,
                             double share[2], double area[2], fm_error *err)
{
    fault_runs ra, rb;
    fm_status st = runs_build(a, &ra, err);
    if (st != FM_OK)
        return st;
    if ((st = runs_build(b, &rb, err)) != FM_OK) {
        runs_free(&ra);
        return st;
    }
    const fault_runs *pa = &ra, *pb = &rb;
    fm_closest_tree *ta = near_part(a, &ra, &pb, 1, tolerance, err);
    fm_closest_tree *tb = ta ? near_part(b, &rb, &pa, 1, tolerance, err) : NULL;
    if (!ta || !tb) {
        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory (overlap)");
    } else {
        area[0] = ra.area;
        area[1] = rb.area;
        const fm_closest_tree *tree_a = ta, *tree_b = tb;
        double near[2] = {near_area(a, &ra, &tree_b, 1, tolerance),
                          near_area(b, &rb, &tree_a, 1, tolerance)};
        if (isnan(near[0]) || isnan(near[1]))
            st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory (overlap)");
        for (int k = 0; k < 2; k++)
            share[k] = area[k] > 0 ? near[k] / area[k] : 0.0;
    }
    fm_closest_tree_destroy(ta);
    fm_closest_tree_destroy(tb);
    runs_free(&ra);
    runs_free(&rb);
    return st;
}

static int by_share(const void *x, const void *y)
{
    const fm_connect_duplicate *a = x, *b = y;
    double sa = fmax(a->share[0], a->share[1]), sb = fmax(b->share[0], b->share[1]);
    if (sa != sb)
        return sa < sb ? 1 : -1;
    if (a->kept != b->kept)
        return a->kept < b->kept ? -1 : 1;
    return (a->dropped > b->dropped) - (a->dropped < b->dropped);
}

/* Which of faults i and j a pair with these areas gives up. */
static int drop_first(const fm_connect_duplicate_options *opt, double area_i, double area_j)
{
    if (area_i == area_j)
        return 0; /* the later fault goes: any fixed rule keeps runs repeatable */
    int i_larger = area_i > area_j;
    return opt->keep == FM_CONNECT_KEEP_SMALLER ? i_larger : !i_larger;
}

typedef struct fpair {
    size_t a, b;       /* fault indices, a < b */
    double near[2];    /* area of a near b, of b near a */
} fpair;

static int by_faults(const void *x, const void *y)
{
    const fpair *p = x, *q = y;
    if (p->a != q->a)
        return p->a < q->a ? -1 : 1;
    return (p->b > q->b) - (p->b < q->b);
}

/* Unique fault pairs (a < b) among the sheet pairs whose trimmed surfaces
 * come within tol: only they can share area at that distance. */
static fm_status candidate_pairs(const fm_model *const *models, size_t n,
                                 const fm_connect_pairs *pairs, double tol, fpair **out,
                                 size_t *nout)
{
    size_t np = fm_connect_pairs_count(pairs), m = 0;
    fpair *fp = malloc((np ? np : 1) * sizeof *fp);
    if (!fp)
        return FM_ERR_NOMEM;
    for (size_t k = 0; k < np; k++) {
        const fm_connect_pair *p = fm_connect_pairs_get(pairs, k);
        if (!(p->trimmed_distance <= tol) || p->fault_a >= n || p->fault_b >= n ||
            p->fault_a == p->fault_b || !models[p->fault_a] || !models[p->fault_b])
            continue;
        fp[m].a = p->fault_a < p->fault_b ? p->fault_a : p->fault_b;
        fp[m].b = p->fault_a < p->fault_b ? p->fault_b : p->fault_a;
        fp[m].near[0] = fp[m].near[1] = 0;
        m++;
    }
    qsort(fp, m, sizeof *fp, by_faults);
    size_t u = 0;
    for (size_t k = 0; k < m; k++)
        if (u == 0 || fp[k].a != fp[u - 1].a || fp[k].b != fp[u - 1].b)
            fp[u++] = fp[k];
    *out = fp;
    *nout = u;
    return FM_OK;
}

/* The faults of the candidate pairs: first each fault's area and runs, then
 * per fault the tree of its part near its partners, and each partner's
 * area near it; last each fault's area near any of its partners. Tasks run
 * on N threads; every result has its own slot. */
typedef struct measure_work {
    const fm_model *const *models;
    fpair *fp;
    size_t m;
    const size_t *fault;  /* the faults in some pair, ascending */
    const size_t *slot;   /* per fault index: its place in fault[] */
    fault_runs *runs;     /* per place */
    fm_closest_tree **tree; /* per place: its part near its partners */
    double tol;
    double *area, *cover; /* per fault index */
    fm_status *st;
    fm_error *err;
} measure_work;

static void runs_task(void *user, size_t i)
{
    measure_work *w = user;
    size_t f = w->fault[i];
    w->st[i] = runs_build(w->models[f], &w->runs[i], &w->err[i]);
    w->area[f] = w->runs[i].area;
}

/* The places of fault f's partners, in pair order; NULL when out of memory. */
static size_t *partners(const measure_work *w, size_t f, size_t *n)
{
    size_t *p = malloc((w->m + 1) * sizeof *p);
    *n = 0;
    for (size_t k = 0; p && k < w->m; k++)
        if (w->fp[k].a == f || w->fp[k].b == f)
            p[(*n)++] = w->slot[w->fp[k].a == f ? w->fp[k].b : w->fp[k].a];
    return p;
}

static void near_task(void *user, size_t i)
{
    measure_work *w = user;
    size_t f = w->fault[i], no;
    size_t *place = partners(w, f, &no);
    const fault_runs **other = malloc((no + 1) * sizeof *other);
    for (size_t k = 0; place && other && k < no; k++)
        other[k] = &w->runs[place[k]];
    fm_closest_tree *tree =
        place && other ? near_part(w->models[f], &w->runs[i], other, no, w->tol, &w->err[i])
                       : NULL;
    free(place);
    free(other);
    if (!tree) {
        w->st[i] = fm_error_set(&w->err[i], FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
        return;
    }
    w->tree[i] = tree;
    const fm_closest_tree *one = tree;
    for (size_t k = 0; k < w->m; k++) {
        fpair *q = &w->fp[k];
        if (q->a == f)
            q->near[1] = near_area(w->models[q->b], &w->runs[w->slot[q->b]], &one, 1, w->tol);
        else if (q->b == f)
            q->near[0] = near_area(w->models[q->a], &w->runs[w->slot[q->a]], &one, 1, w->tol);
    }
}

static void cover_task(void *user, size_t i)
{
    measure_work *w = user;
    size_t f = w->fault[i], no;
    size_t *place = partners(w, f, &no);
    const fm_closest_tree **trees = malloc((no + 1) * sizeof *trees);
    for (size_t k = 0; place && trees && k < no; k++)
        trees[k] = w->tree[place[k]];
    double a = place && trees ? near_area(w->models[f], &w->runs[i], trees, no, w->tol) : NAN;
    free(place);
    free(trees);
    w->cover[f] = a;
    if (isnan(a))
        w->st[i] = fm_error_set(&w->err[i], FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
}

/* One round of tasks; the first fault in order that failed reports. */
static fm_status round_of(size_t nf, int nthreads, void (*task)(void *, size_t),
                          measure_work *w, fm_error *err)
{
    cn_parallel_for(nf, nthreads, task, w);
    for (size_t i = 0; i < nf; i++)
        if (w->st[i] != FM_OK) {
            if (err)
                *err = w->err[i];
            return w->st[i];
        }
    return FM_OK;
}

static fm_status measure_pairs(const fm_model *const *models, size_t n, fpair *fp, size_t m,
                               double tol, int nthreads, double *area, double *cover,
                               fm_error *err)
{
    size_t *slot = malloc((n ? n : 1) * sizeof *slot);
    size_t *fault = malloc((n ? n : 1) * sizeof *fault), nf = 0;
    fm_status *st = calloc(n ? n : 1, sizeof *st);
    fm_error *errs = calloc(n ? n : 1, sizeof *errs);
    fault_runs *runs = calloc(n ? n : 1, sizeof *runs);
    fm_closest_tree **tree = calloc(n ? n : 1, sizeof *tree);
    fm_status rc = FM_OK;
    if (!slot || !fault || !st || !errs || !runs || !tree) {
        rc = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
        goto done;
    }
    for (size_t f = 0; f < n; f++)
        slot[f] = SIZE_MAX;
    for (size_t k = 0; k < m; k++)
        slot[fp[k].a] = slot[fp[k].b] = 0;
    for (size_t f = 0; f < n; f++)
        if (slot[f] == 0) {
            slot[f] = nf;
            fault[nf++] = f;
        }
    measure_work w = {models, fp, m, fault, slot, runs, tree, tol, area, cover, st, errs};
    rc = round_of(nf, nthreads, runs_task, &w, err);
    if (rc == FM_OK)
        rc = round_of(nf, nthreads, near_task, &w, err);
    if (rc == FM_OK)
        rc = round_of(nf, nthreads, cover_task, &w, err);
done:
    for (size_t i = 0; runs && i < nf; i++)
        runs_free(&runs[i]);
    for (size_t i = 0; tree && i < nf; i++)
        fm_closest_tree_destroy(tree[i]);
    free(tree);
    free(runs);
    free(slot);
    free(fault);
    free(st);
    free(errs);
    return rc;
}

fm_status fm_connect_find_duplicates(const fm_model *const *models, size_t n,
                                     const fm_connect_pairs *pairs,
                                     const fm_connect_duplicate_options *opt,
                                     fm_connect_duplicate **out, size_t *nout, fm_error *err)
{
    fm_connect_duplicate_options defaults;
    if (!opt) {
        fm_connect_duplicate_options_default(&defaults);
        opt = &defaults;
    }
    *out = NULL;
    *nout = 0;
    if (!(opt->tolerance >= 0) || !(opt->min_share > 0 && opt->min_share <= 1))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                            "connect: duplicate tolerance must be >= 0 and share in (0, 1]");
    fpair *fp = NULL;
    size_t m = 0;
    double *area = calloc(n ? n : 1, sizeof *area);
    double *cover = calloc(n ? n : 1, sizeof *cover);
    if (!area || !cover ||
        candidate_pairs(models, n, pairs, opt->tolerance, &fp, &m) != FM_OK) {
        free(area);
        free(cover);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    }
    fm_status st =
        measure_pairs(models, n, fp, m, opt->tolerance, opt->nthreads, area, cover, err);
    fm_connect_duplicate *dup = st == FM_OK ? malloc((m ? m : 1) * sizeof *dup) : NULL;
    if (st == FM_OK && !dup)
        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    size_t nd = 0;
    for (size_t k = 0; k < m && st == FM_OK; k++) {
        double ar[2] = {area[fp[k].a], area[fp[k].b]};
        double share[2] = {ar[0] > 0 ? fp[k].near[0] / ar[0] : 0,
                           ar[1] > 0 ? fp[k].near[1] / ar[1] : 0};
        if (fmax(share[0], share[1]) < opt->min_share)
            continue;
        /* index 0 of share and area belongs to the dropped fault; the
         * rule's choice stands only if what its partners together cover of
         * it reaches the share (a section under a composite, not a small
         * patch lying on a large fault, which would lose the large one) */
        int swap = !drop_first(opt, ar[0], ar[1]);
        size_t drop = swap ? fp[k].b : fp[k].a;
        if (!(cover[drop] >= opt->min_share * area[drop]))
            swap = !swap;
        fm_connect_duplicate *d = &dup[nd++];
        d->dropped = swap ? fp[k].b : fp[k].a;
        d->kept = swap ? fp[k].a : fp[k].b;
        d->share[0] = share[swap];
        d->share[1] = share[!swap];
        d->area[0] = ar[swap];
        d->area[1] = ar[!swap];
        d->cover = ar[swap] > 0 ? cover[swap ? fp[k].b : fp[k].a] / ar[swap] : 0;
        d->decided = 0;
    }
    free(fp);
    free(area);
    free(cover);
    if (st != FM_OK) {
        free(dup);
        return st;
    }
    /* Strongest overlaps decide first; a pair whose fault to keep has
     * already gone to another pair changes nothing more (its other fault
     * stays, unless a pair of its own drops it). */
    qsort(dup, nd, sizeof *dup, by_share);
    unsigned char *gone = calloc(n ? n : 1, 1);
    if (!gone) {
        free(dup);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    }
    for (size_t k = 0; k < nd; k++) {
        fm_connect_duplicate *d = &dup[k];
        if (gone[d->dropped] || gone[d->kept])
            continue;
        gone[d->dropped] = 1;
        d->decided = 1;
    }
    free(gone);
    *out = dup;
    *nout = nd;
    return FM_OK;
}
