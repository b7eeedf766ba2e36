/* Edge collapses: free nodes that end an edge much shorter than the
 * target merge into their neighbour.
 *
 * Refinement in (u, v) measures length with the metric at one point of a
 * triangle; where the surface bends sharply within a triangle (a tight
 * fold of a fitted surface, a steep flank of a height field) that point
 * overstates the 3D length, and the triangles come out too small. A
 * collapse removes such an edge, shortest first, when the result keeps
 * every triangle counter-clockwise in (u, v) (exact orient2d), no new edge
 * above 1.4 sizes, no angle worse than what was there or below 25
 * degrees, and the mesh a manifold (the link condition: the edge's ends
 * share exactly the two opposite nodes). Nodes on constrained edges never
 * move, so the outline and every curve stay as they are. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_predicates.h"
#include "remesh_internal.h"

typedef struct cand {
    double len;
    int32_t b, a; /* b (free) goes into a */
} cand;

static int cmp_cand(const void *pa, const void *pb)
{
    const cand *x = pa, *y = pb;
    if (x->len != y->len)
        return x->len < y->len ? -1 : 1;
    if (x->b != y->b)
        return x->b < y->b ? -1 : 1;
    return (x->a > y->a) - (x->a < y->a);
}

static double dist3(const double *p, const double *q)
{
    return sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                (p[2] - q[2]) * (p[2] - q[2]));
}

static int has(const int32_t *t, int32_t v) { return t[0] == v || t[1] == v || t[2] == v; }

size_t collapse_short(const double *uv, const double *xyz, const unsigned char *fixed, size_t np,
                      int32_t *tri, size_t *ntp, double H, int *nomem)
{
    size_t nt = *ntp, done = 0;
    *nomem = 0;
    size_t *start = calloc(np + 1, sizeof *start);
    int32_t *list = malloc(3 * nt * sizeof *list + 1);
    cand *c = malloc(6 * nt * sizeof *c + 1);
    unsigned char *touched = calloc(np + 1, 1), *dead = calloc(nt + 1, 1);
    if (!start || !list || !c || !touched || !dead) {
        *nomem = 1;
        goto out;
    }
    for (size_t k = 0; k < 3 * nt; k++)
        start[tri[k] + 1]++;
    for (size_t v = 0; v < np; v++)
        start[v + 1] += start[v];
    {
        size_t *fill = malloc((np + 1) * sizeof *fill);
        if (!fill) {
            *nomem = 1;
            goto out;
        }
        memcpy(fill, start, (np + 1) * sizeof *fill);
        for (size_t t = 0; t < nt; t++)
            for (int i = 0; i < 3; i++)
                list[fill[tri[3 * t + i]]++] = (int32_t)t;
        free(fill);
    }
    size_t ncand = 0;
    for (size_t t = 0; t < nt; t++)
        for (int i = 0; i < 3; i++) {
            int32_t p = tri[3 * t + i], q = tri[3 * t + (i + 1) % 3];
            double len = dist3(xyz + 3 * p, xyz + 3 * q);
            if (!(len < 0.7 * H))
                continue;
            if (!fixed[p])
                c[ncand++] = (cand){len, p, q};
            if (!fixed[q])
                c[ncand++] = (cand){len, q, p};
        }
    qsort(c, ncand, sizeof *c, cmp_cand);
    for (size_t k = 0; k < ncand; k++) {
        int32_t a = c[k].a, b = c[k].b;
        if (touched[a] || touched[b])
            continue;
        const int32_t *rb = list + start[b];
        size_t nb = start[b + 1] - start[b];
        /* the edge's two triangles, their opposite nodes */
        int32_t opp[2];
        int nopp = 0, ok = 1;
        for (size_t i = 0; i < nb && ok; i++) {
            const int32_t *T = tri + 3 * rb[i];
            if (!has(T, a))
                continue;
            if (nopp == 2)
                ok = 0;
            else
                opp[nopp++] = T[0] != a && T[0] != b ? T[0] : T[1] != a && T[1] != b ? T[1] : T[2];
        }
        if (!ok || nopp != 2)
            continue;
        /* link condition: a and b share no neighbour but the two */
        const int32_t *ra = list + start[a];
        size_t na = start[a + 1] - start[a];
        for (size_t i = 0; i < nb && ok; i++)
            for (int j = 0; j < 3 && ok; j++) {
                int32_t v = tri[3 * rb[i] + j];
                if (v == a || v == b || v == opp[0] || v == opp[1])
                    continue;
                for (size_t m = 0; m < na && ok; m++)
                    if (has(tri + 3 * ra[m], v))
                        ok = 0;
            }
        if (!ok)
            continue;
        /* the triangles of b that stay, with a in place of b */
        /* smallest angles compared by their sines (see optimise.c) */
        double before = 1, after = 1;
        for (size_t i = 0; i < nb; i++)
            before = fmin(before, fm_triangle_min_angle_sin(xyz + 3 * tri[3 * rb[i]],
                                                        xyz + 3 * tri[3 * rb[i] + 1],
                                                        xyz + 3 * tri[3 * rb[i] + 2]));
        for (size_t i = 0; i < nb && ok; i++) {
            const int32_t *T = tri + 3 * rb[i];
            if (has(T, a))
                continue;
            int32_t n[3];
            for (int j = 0; j < 3; j++)
                n[j] = T[j] == b ? a : T[j];
            if (fm_orient2d(uv + 2 * n[0], uv + 2 * n[1], uv + 2 * n[2]) <= 0)
                ok = 0;
            for (int j = 0; j < 3 && ok; j++)
                if (n[j] != a && dist3(xyz + 3 * a, xyz + 3 * n[j]) > 1.4 * H)
                    ok = 0;
            after = fmin(after, fm_triangle_min_angle_sin(xyz + 3 * n[0], xyz + 3 * n[1], xyz + 3 * n[2]));
        }
        if (!ok || !(after >= fmin(before, 0.422618261740699))) /* sin 25 deg */
            continue;
        for (size_t i = 0; i < nb; i++) {
            int32_t *T = tri + 3 * rb[i];
            if (has(T, a)) {
                dead[rb[i]] = 1;
                continue;
            }
            for (int j = 0; j < 3; j++) {
                touched[T[j]] = 1;
                if (T[j] == b)
                    T[j] = a;
            }
        }
        touched[a] = touched[b] = 1;
        touched[opp[0]] = touched[opp[1]] = 1;
        done++;
    }
    {
        size_t w = 0;
        for (size_t t = 0; t < nt; t++)
            if (!dead[t]) {
                memmove(tri + 3 * w, tri + 3 * t, 3 * sizeof *tri);
                w++;
            }
        *ntp = w;
    }
out:
    free(start);
    free(list);
    free(c);
    free(touched);
    free(dead);
    return done;
}
