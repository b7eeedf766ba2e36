/* Step 4a: which triangle continues which across every edge.
 *
 * Around a non-manifold edge (k > 2 triangles) each triangle is a half-plane
 * hinged on the edge, at some angle around it. Two half-planes 180 degrees
 * apart form a flat continuation, so pairs are taken greedily from the one
 * closest to 180 degrees: a through-going fault keeps its two sides
 * together and a splay meeting it is left over, its triangle seeing the
 * edge as boundary. Ties go to the lower positions in angle order (angles
 * measured from the lowest half-edge), which only depend on the input. */
#include "repair_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "fm_vec3.h"

/* An edge with more triangles than this is not a junction of a few
 * surfaces but garbage (k^2 pairs would be tried): it is left unpaired. */
#define MAX_PAIRED_FAN 512

#define REP_PI 3.14159265358979323846

typedef struct fan_item {
    double angle;
    int32_t he;
} fan_item;

typedef struct fan_pair {
    double bend; /* how far from flat, radians */
    int32_t i, j;
} fan_pair;

static int cmp_item(const void *pa, const void *pb)
{
    const fan_item *a = pa, *b = pb;
    if (a->angle != b->angle)
        return a->angle < b->angle ? -1 : 1;
    return (a->he > b->he) - (a->he < b->he);
}

static int cmp_pair(const void *pa, const void *pb)
{
    const fan_pair *a = pa, *b = pb;
    if (a->bend != b->bend)
        return a->bend < b->bend ? -1 : 1;
    if (a->i != b->i)
        return a->i < b->i ? -1 : 1;
    return (a->j > b->j) - (a->j < b->j);
}

/* Angles around the edge of the k half-edges hs, into items. */
static void fan_angles(const rep_tris *t, const double *xyz, const int32_t *hs, int32_t k,
                       fan_item *items)
{
    int32_t h0 = hs[0], t0 = h0 / 3, i0 = h0 % 3;
    int32_t va = t->v[3 * t0 + i0], vb = t->v[3 * t0 + (i0 + 1) % 3];
    const double *a = xyz + 3 * (size_t)(va < vb ? va : vb);
    const double *b = xyz + 3 * (size_t)(va < vb ? vb : va);
    double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double ee = fm_dot3(e, e);
    double u[3] = {0, 0, 0}, w[3] = {0, 0, 0};
    for (int32_t m = 0; m < k; m++) {
        int32_t h = hs[m], tr = h / 3, i = h % 3;
        const double *c = xyz + 3 * (size_t)t->v[3 * tr + (i + 2) % 3];
        double p[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double s = ee > 0 ? fm_dot3(p, e) / ee : 0;
        for (int d = 0; d < 3; d++)
            p[d] -= s * e[d]; /* component of the apex across the edge */
        if (m == 0) {
            double len = sqrt(fm_dot3(p, p)), el = sqrt(ee);
            if (len > 0 && el > 0) {
                for (int d = 0; d < 3; d++)
                    u[d] = p[d] / len;
                w[0] = (e[1] * u[2] - e[2] * u[1]) / el;
                w[1] = (e[2] * u[0] - e[0] * u[2]) / el;
                w[2] = (e[0] * u[1] - e[1] * u[0]) / el;
            }
        }
        items[m].angle = atan2(fm_dot3(p, w), fm_dot3(p, u));
        items[m].he = h;
    }
}

static void pair_fan(const rep_tris *t, const double *xyz, const int32_t *hs, int32_t k,
                     fan_item *items, fan_pair *pairs, uint8_t *used, int32_t *nbr)
{
    fan_angles(t, xyz, hs, k, items);
    qsort(items, (size_t)k, sizeof *items, cmp_item);
    size_t np = 0;
    for (int32_t i = 0; i < k; i++)
        for (int32_t j = i + 1; j < k; j++) {
            double d = fabs(items[j].angle - items[i].angle);
            if (d > REP_PI)
                d = 2 * REP_PI - d;
            pairs[np].bend = REP_PI - d;
            pairs[np].i = i;
            pairs[np].j = j;
            np++;
        }
    qsort(pairs, np, sizeof *pairs, cmp_pair);
    memset(used, 0, (size_t)k);
    for (size_t p = 0; p < np; p++) {
        int32_t i = pairs[p].i, j = pairs[p].j;
        if (used[i] || used[j])
            continue;
        used[i] = used[j] = 1;
        nbr[items[i].he] = items[j].he;
        nbr[items[j].he] = items[i].he;
    }
}

fm_status rep_pair_edges(const rep_tris *t, const rep_edges *e, const double *xyz,
                         int split, int32_t *nbr, size_t *nonmanifold_edges)
{
    *nonmanifold_edges = 0;
    int32_t kmax = 0;
    for (size_t h = 0; h < 3 * t->n; h++)
        nbr[h] = -1;
    for (size_t k = 0; k < e->ne; k++) {
        int32_t first = e->off[k], cnt = e->off[k + 1] - first;
        if (cnt == 2) {
            nbr[e->he[first]] = e->he[first + 1];
            nbr[e->he[first + 1]] = e->he[first];
        } else if (cnt > 2) {
            (*nonmanifold_edges)++;
            if (cnt <= MAX_PAIRED_FAN && cnt > kmax)
                kmax = cnt;
        }
    }
    if (!split || kmax == 0)
        return FM_OK;
    fan_item *items = malloc((size_t)kmax * sizeof *items);
    fan_pair *pairs = malloc((size_t)kmax * (size_t)(kmax - 1) / 2 * sizeof *pairs);
    uint8_t *used = malloc((size_t)kmax);
    if (!items || !pairs || !used) {
        free(items);
        free(pairs);
        free(used);
        return FM_ERR_NOMEM;
    }
    for (size_t k = 0; k < e->ne; k++) {
        int32_t first = e->off[k], cnt = e->off[k + 1] - first;
        if (cnt > 2 && cnt <= MAX_PAIRED_FAN)
            pair_fan(t, xyz, e->he + first, cnt, items, pairs, used, nbr);
    }
    free(items);
    free(pairs);
    free(used);
    return FM_OK;
}
