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

/* Area of mesh a, and the part of it (by triangle centroids) within tol of
 * the tree. Sample triangles are a few hundred metres at most, far below
 * the kilometres a duplicate shares, so centroids weigh the area well. */
static void near_area(const fm_mesh *a, const fm_closest_tree *tree, double tol, double *area,
                      double *near)
{
    const double *X = fm_mesh_vertices(a);
    const int32_t *T = fm_mesh_triangles(a);
    double sum = 0, in = 0;
    for (size_t t = 0; t < fm_mesh_ntriangles(a); t++) {
        const double *p = X + 3 * (size_t)T[3 * t], *q = X + 3 * (size_t)T[3 * t + 1],
                     *r = X + 3 * (size_t)T[3 * t + 2];
        double ar = fm_triangle_area(p, q, r);
        double c[3] = {(p[0] + q[0] + r[0]) / 3, (p[1] + q[1] + r[1]) / 3, (p[2] + q[2] + r[2]) / 3};
        sum += ar;
        if (fm_closest_query(tree, c, tol, NULL))
            in += ar;
    }
    *area = sum;
    *near = in;
}

fm_status fm_connect_overlap(const fm_model *a, const fm_model *b, double tolerance,
                             double share[2], double area[2], fm_error *err)
{
    fm_mesh *sa = fault_samples(a), *sb = fault_samples(b);
    fm_closest_tree *ta = sa ? fm_closest_tree_create(sa, err) : NULL;
    fm_closest_tree *tb = sb ? fm_closest_tree_create(sb, err) : NULL;
    fm_status st = FM_OK;
    if (!ta || !tb) {
        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory (overlap)");
    } else {
        double near[2];
        near_area(sa, tb, tolerance, &area[0], &near[0]);
        near_area(sb, ta, tolerance, &area[1], &near[1]);
        for (int k = 0; k < 2; k++)
            share[k] = area[k] > 0 ? near[k] / area[k] : 0.0;
    }
    fm_closest_tree_destroy(ta);
    fm_closest_tree_destroy(tb);
    fm_mesh_destroy(sa);
    fm_mesh_destroy(sb);
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
    /* Fault pairs whose trimmed surfaces come within the tolerance: only
     * they can share area at that distance. Pairs are sorted by fault, so
     * repeats (several sheets) are neighbours. */
    size_t np = fm_connect_pairs_count(pairs), cap = 0, nd = 0;
    fm_connect_duplicate *dup = NULL;
    size_t last_a = SIZE_MAX, last_b = SIZE_MAX;
    for (size_t k = 0; k < np; k++) {
        const fm_connect_pair *p = fm_connect_pairs_get(pairs, k);
        if (!(p->trimmed_distance <= opt->tolerance) || p->fault_a >= n || p->fault_b >= n ||
            !models[p->fault_a] || !models[p->fault_b])
            continue;
        if (p->fault_a == last_a && p->fault_b == last_b)
            continue;
        last_a = p->fault_a;
        last_b = p->fault_b;
        double share[2], area[2];
        fm_status st = fm_connect_overlap(models[p->fault_a], models[p->fault_b], opt->tolerance,
                                          share, area, err);
        if (st != FM_OK) {
            free(dup);
            return st;
        }
        if (fmax(share[0], share[1]) < opt->min_share)
            continue;
        if (nd == cap) {
            cap = cap ? 2 * cap : 16;
            fm_connect_duplicate *g = realloc(dup, cap * sizeof *g);
            if (!g) {
                free(dup);
                return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
            }
            dup = g;
        }
        /* share[0] / area[0] belong to the dropped fault */
        int swap = !drop_first(opt, area[0], area[1]);
        fm_connect_duplicate *d = &dup[nd++];
        d->dropped = swap ? p->fault_b : p->fault_a;
        d->kept = swap ? p->fault_a : p->fault_b;
        d->share[0] = share[swap];
        d->share[1] = share[!swap];
        d->area[0] = area[swap];
        d->area[1] = area[!swap];
        d->decided = 0;
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
