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
#include <stdlib.h>
#include <string.h>

void fm_connect_duplicate_options_default(fm_connect_duplicate_options *opt)
{
    opt->tolerance = 50.0;
    opt->min_share = 0.5;
    opt->keep = FM_CONNECT_KEEP_SMALLER;
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

/* Area of a fault's sampled trimmed surface (all sheets) and, when tree
 * is given, the part of it (by triangle centroids) within tol of the tree.
 * Sample triangles are a few hundred metres at most, far below the
 * kilometres a duplicate shares, so centroids weigh the area well. */
static double model_area(const fm_model *m, const fm_closest_tree *tree, double tol)
{
    double sum = 0;
    for (size_t s = 0; s < fm_model_nsheets(m); s++) {
        const fm_mesh *a = fm_model_samples(m, s);
        if (!a)
            continue;
        const double *X = fm_mesh_vertices(a);
        const int32_t *T = fm_mesh_triangles(a);
        for (size_t t = 0; t < fm_mesh_ntriangles(a); t++) {
            const double *p = X + 3 * (size_t)T[3 * t], *q = X + 3 * (size_t)T[3 * t + 1],
                         *r = X + 3 * (size_t)T[3 * t + 2];
            double c[3] = {(p[0] + q[0] + r[0]) / 3, (p[1] + q[1] + r[1]) / 3,
                           (p[2] + q[2] + r[2]) / 3};
            if (!tree || fm_closest_query(tree, c, tol, NULL))
                sum += fm_triangle_area(p, q, r);
        }
    }
    return sum;
}

static fm_closest_tree *fault_tree(const fm_model *m, fm_error *err)
{
    fm_mesh *all = fault_samples(m);
    fm_closest_tree *t = all ? fm_closest_tree_create(all, err) : NULL;
    fm_mesh_destroy(all);
    return t;
}

fm_status fm_connect_overlap(const fm_model *a, const fm_model *b, double tolerance,
                             double share[2], double area[2], fm_error *err)
{
    fm_closest_tree *ta = fault_tree(a, err), *tb = ta ? fault_tree(b, err) : NULL;
    fm_status st = FM_OK;
    if (!ta || !tb) {
        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory (overlap)");
    } else {
        area[0] = model_area(a, NULL, 0);
        area[1] = model_area(b, NULL, 0);
        double near[2] = {model_area(a, tb, tolerance), model_area(b, ta, tolerance)};
        for (int k = 0; k < 2; k++)
            share[k] = area[k] > 0 ? near[k] / area[k] : 0.0;
    }
    fm_closest_tree_destroy(ta);
    fm_closest_tree_destroy(tb);
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

/* For every candidate pair, the area of each fault near the other. Each
 * fault's tree is built once, in fault order, and serves every pair the
 * fault is in: its partners' samples are queried against it. */
static fm_status measure_pairs(const fm_model *const *models, size_t n, fpair *fp, size_t m,
                               double tol, double *area, fm_error *err)
{
    unsigned char *in = calloc(n ? n : 1, 1);
    if (!in)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    for (size_t k = 0; k < m; k++)
        in[fp[k].a] = in[fp[k].b] = 1;
    fm_status st = FM_OK;
    for (size_t f = 0; f < n && st == FM_OK; f++) {
        if (!in[f])
            continue;
        area[f] = model_area(models[f], NULL, 0);
        fm_closest_tree *tree = fault_tree(models[f], err);
        if (!tree) {
            st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
            break;
        }
        for (size_t k = 0; k < m; k++) {
            if (fp[k].a == f)
                fp[k].near[1] = model_area(models[fp[k].b], tree, tol);
            else if (fp[k].b == f)
                fp[k].near[0] = model_area(models[fp[k].a], tree, tol);
        }
        fm_closest_tree_destroy(tree);
    }
    free(in);
    return st;
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
    if (!area || candidate_pairs(models, n, pairs, opt->tolerance, &fp, &m) != FM_OK) {
        free(area);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    }
    fm_status st = measure_pairs(models, n, fp, m, opt->tolerance, area, err);
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
        /* index 0 of share and area belongs to the dropped fault */
        int swap = !drop_first(opt, ar[0], ar[1]);
        fm_connect_duplicate *d = &dup[nd++];
        d->dropped = swap ? fp[k].b : fp[k].a;
        d->kept = swap ? fp[k].a : fp[k].b;
        d->share[0] = share[swap];
        d->share[1] = share[!swap];
        d->area[0] = ar[swap];
        d->area[1] = ar[!swap];
        d->decided = 0;
    }
    free(fp);
    free(area);
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
