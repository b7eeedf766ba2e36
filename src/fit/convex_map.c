/* A parameterization that is one-to-one by construction, for the few
 * sheets whose conformal map overlaps itself (a sheet that, unrolled,
 * laps over itself cannot lie flat without distortion).
 *
 * Tutte's theorem as Floater extended it: with the outer boundary on a
 * convex curve and every inner vertex a convex combination (positive
 * weights) of its neighbours, the map of a disk-like sheet is an embedding.
 * The weights are Floater's mean-value weights tan(a/2) / |edge| (positive
 * for any triangle) symmetrized, w_ij + w_ji, so that the system is SPD and
 * CHOLMOD solves it. The ellipse takes the axes and aspect of the conformal
 * layout and the sheet's area, and the boundary vertices are spaced by arc
 * length, which keeps the distortion moderate for the rectangle-like
 * outlines faults have. Hole boundaries stay free (the theorem does not
 * cover them; they rarely fold). */
#include "fit_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define FM_PI 3.14159265358979323846

typedef struct dedge {
    int32_t a, b; /* directed as in its triangle */
} dedge;

static int cmp_undirected(const void *x, const void *y)
{
    const dedge *p = x, *q = y;
    int32_t pa = p->a < p->b ? p->a : p->b, pb = p->a < p->b ? p->b : p->a;
    int32_t qa = q->a < q->b ? q->a : q->b, qb = q->a < q->b ? q->b : q->a;
    if (pa != qa)
        return pa < qa ? -1 : 1;
    if (pb != qb)
        return pb < qb ? -1 : 1;
    if (p->a != q->a)
        return p->a < q->a ? -1 : 1;
    return 0;
}

static double dist3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

/* The outer boundary: the longest loop of boundary edges, in the sheet's
 * orientation. Returns its length in *n (0 when the sheet is closed); the
 * vertices of the other loops go to holes (each loop ended by -1, *nh
 * values in all, malloc'ed). */
static int32_t *outer_loop(const fm_mesh *sheet, size_t *n, int32_t **holes, size_t *nh)
{
    const double *X = fm_mesh_vertices(sheet);
    const int32_t *T = fm_mesh_triangles(sheet);
    size_t nt = fm_mesh_ntriangles(sheet), nv = fm_mesh_nvertices(sheet);
    *n = 0;
    dedge *e = malloc((nt ? 3 * nt : 1) * sizeof *e);
    int32_t *next = malloc((nv ? nv : 1) * sizeof *next);
    unsigned char *seen = calloc(nv ? nv : 1, 1);
    int32_t *best = NULL, *all = malloc((nv + 1) * 2 * sizeof *all);
    size_t nall = 0;
    *holes = NULL;
    *nh = 0;
    if (!e || !next || !seen || !all)
        goto done;
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            e[3 * t + (size_t)k].a = T[3 * t + (size_t)k];
            e[3 * t + (size_t)k].b = T[3 * t + (size_t)(k + 1) % 3];
        }
    qsort(e, 3 * nt, sizeof *e, cmp_undirected);
    for (size_t i = 0; i < nv; i++)
        next[i] = -1;
    for (size_t i = 0; i < 3 * nt;) {
        size_t j = i + 1;
        while (j < 3 * nt && cmp_undirected(&e[i], &e[j]) == 0)
            j++;
        /* Same undirected edge, any direction. */
        while (j < 3 * nt && ((e[j].a == e[i].a && e[j].b == e[i].b) ||
                              (e[j].a == e[i].b && e[j].b == e[i].a)))
            j++;
        if (j - i == 1)
            next[e[i].a] = e[i].b;
        i = j;
    }
    double best_len = -1;
    size_t best_n = 0, start_best = 0;
    for (size_t s = 0; s < nv; s++) {
        if (next[s] < 0 || seen[s])
            continue;
        size_t len = 0;
        double L = 0;
        int32_t v = (int32_t)s;
        while (v >= 0 && !seen[v] && len <= nv) {
            seen[v] = 1;
            len++;
            if (next[v] >= 0)
                L += dist3(X + 3 * (size_t)v, X + 3 * (size_t)next[v]);
            v = next[v];
        }
        if (v != (int32_t)s)
            continue;
        v = (int32_t)s;
        for (size_t k = 0; k < len; k++, v = next[v])
            all[nall + k] = v;
        all[nall + len] = -1;
        if (L > best_len) {
            best_len = L;
            best_n = len;
            start_best = nall;
        }
        nall += len + 1;
    }
    if (best_n > 0) {
        best = malloc(best_n * sizeof *best);
        *holes = malloc((nall ? nall : 1) * sizeof **holes);
        if (!best || !*holes) {
            free(best);
            free(*holes);
            *holes = NULL;
            best = NULL;
            goto done;
        }
        memcpy(best, all + start_best, best_n * sizeof *best);
        for (size_t k = 0; k < nall; k++)
            if (k < start_best || k > start_best + best_n)
                (*holes)[(*nh)++] = all[k];
    }
    *n = best_n;
done:
    free(all);
    free(e);
    free(next);
    free(seen);
    return best;
}

/* Mean-value weight of edge (i, j) seen from i, in the triangle (i, j, k). */
static double mv_weight(const double *xi, const double *xj, const double *xk)
{
    double a[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
    double b[3] = {xk[0] - xi[0], xk[1] - xi[1], xk[2] - xi[2]};
    double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    double lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    double c = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb);
    double ang = acos(fmax(-1.0, fmin(1.0, c)));
    return tan(0.5 * ang) / la;
}

fm_status fm_fit_convex_map(const fm_mesh *sheet, double *uv, const char *name, fm_error *err)
{
    const double *X = fm_mesh_vertices(sheet);
    const int32_t *T = fm_mesh_triangles(sheet);
    size_t nt = fm_mesh_ntriangles(sheet), nv = fm_mesh_nvertices(sheet), nb;
    int32_t *holes = NULL;
    size_t nh = 0;
    int32_t *loop = outer_loop(sheet, &nb, &holes, &nh);
    size_t *idx = malloc((nv ? nv : 1) * sizeof *idx);
    double *fixed = calloc(2 * (nv ? nv : 1), sizeof *fixed);
    unsigned char *onb = calloc(nv ? nv : 1, 1), *active = calloc(nv ? nv : 1, 1);
    fm_fit_triplets q;
    memset(&q, 0, sizeof q);
    double *rhs = NULL, *sol = NULL, *val = NULL;
    size_t *colptr = NULL, *rowind = NULL;
    fm_fit_spd *spd = NULL;
    fm_status st = FM_OK;
    if (!idx || !fixed || !onb || !active) {
        st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (convex map)");
        goto done;
    }
    if (!loop || nb < 3) {
        st = fm_error_set(err, FM_ERR_INVALID, name, 0, "fit: sheet has no outer boundary");
        goto done;
    }
    double area = 0;
    for (size_t t = 0; t < nt; t++) {
        const double *p0 = X + 3 * (size_t)T[3 * t], *p1 = X + 3 * (size_t)T[3 * t + 1];
        const double *p2 = X + 3 * (size_t)T[3 * t + 2];
        double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
        double a2 = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        if (a2 > 0) {
            area += 0.5 * a2;
            for (int k = 0; k < 3; k++)
                active[T[3 * t + k]] = 1;
        }
    }
    /* Ellipse after the conformal layout: its principal axes, their ratio,
     * the sheet's area. */
    double n = 0, mu = 0, mv = 0;
    for (size_t i = 0; i < nv; i++)
        if (active[i]) {
            n++;
            mu += uv[2 * i];
            mv += uv[2 * i + 1];
        }
    mu /= n;
    mv /= n;
    double suu = 0, suv = 0, svv = 0;
    for (size_t i = 0; i < nv; i++)
        if (active[i]) {
            double a = uv[2 * i] - mu, b = uv[2 * i + 1] - mv;
            suu += a * a;
            suv += a * b;
            svv += b * b;
        }
    double phi = 0.5 * atan2(2 * suv, suu - svv);
    double e1[2] = {cos(phi), sin(phi)}, e2[2] = {-sin(phi), cos(phi)};
    double l1 = 0, l2 = 0;
    for (size_t i = 0; i < nv; i++)
        if (active[i]) {
            double a = uv[2 * i] - mu, b = uv[2 * i + 1] - mv;
            double x = a * e1[0] + b * e1[1], y = a * e2[0] + b * e2[1];
            l1 += x * x;
            l2 += y * y;
        }
    double ratio = l2 > 0 ? sqrt(l1 / l2) : 1.0;
    double rb = sqrt(area / (FM_PI * ratio)), ra = ratio * rb;
    /* Boundary by arc length, starting at the vertex farthest along the
     * major axis so that the ellipse sits like the layout. */
    double L = 0, far = -INFINITY;
    size_t k0 = 0;
    for (size_t k = 0; k < nb; k++) {
        L += dist3(X + 3 * (size_t)loop[k], X + 3 * (size_t)loop[(k + 1) % nb]);
        const double *p = uv + 2 * (size_t)loop[k];
        double x = (p[0] - mu) * e1[0] + (p[1] - mv) * e1[1];
        if (x > far) {
            far = x;
            k0 = k;
        }
    }
    double s = 0;
    for (size_t m = 0; m < nb; m++) {
        size_t k = (k0 + m) % nb;
        int32_t v = loop[k];
        double th = 2 * FM_PI * s / L;
        onb[v] = 1;
        fixed[2 * (size_t)v] = ra * cos(th) * e1[0] + rb * sin(th) * e2[0];
        fixed[2 * (size_t)v + 1] = ra * cos(th) * e1[1] + rb * sin(th) * e2[1];
        s += dist3(X + 3 * (size_t)v, X + 3 * (size_t)loop[(k + 1) % nb]);
    }
    size_t nfree = 0, nholes = 0;
    for (size_t i = 0; i < nv; i++)
        idx[i] = (active[i] && !onb[i]) ? nfree++ : (size_t)-1;
    for (size_t k = 0; k < nh; k++)
        nholes += holes[k] < 0;
    /* Each hole gets a virtual centre joined to its loop, which makes the
     * sheet a disk as far as the theorem is concerned: then holes cannot
     * fold either. Centres are the last unknowns. */
    size_t nreal = nfree;
    nfree += nholes;
    rhs = calloc(2 * (nfree ? nfree : 1), sizeof *rhs);
    sol = malloc(2 * (nfree ? nfree : 1) * sizeof *sol);
    if (!rhs || !sol) {
        st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (convex map)");
        goto done;
    }
    for (size_t t = 0; t < nt; t++)
        for (int c = 0; c < 3; c++) {
            size_t i = (size_t)T[3 * t + c], j = (size_t)T[3 * t + (c + 1) % 3];
            size_t k = (size_t)T[3 * t + (c + 2) % 3];
            if (!active[i] || !active[j] || !active[k])
                continue;
            /* Edge (i, j): i's angle and j's angle in this triangle. */
            double w = mv_weight(X + 3 * i, X + 3 * j, X + 3 * k) +
                       mv_weight(X + 3 * j, X + 3 * i, X + 3 * k);
            if (!(w > 0) || !isfinite(w))
                continue;
            size_t a = idx[i], b = idx[j];
            int bad = 0;
            if (a != (size_t)-1)
                bad |= fm_fit_triplets_add(&q, a, a, w);
            if (b != (size_t)-1)
                bad |= fm_fit_triplets_add(&q, b, b, w);
            if (a != (size_t)-1 && b != (size_t)-1) {
                bad |= fm_fit_triplets_add(&q, a < b ? a : b, a < b ? b : a, -w);
            } else if (a != (size_t)-1) {
                rhs[2 * a] += w * fixed[2 * j];
                rhs[2 * a + 1] += w * fixed[2 * j + 1];
            } else if (b != (size_t)-1) {
                rhs[2 * b] += w * fixed[2 * i];
                rhs[2 * b + 1] += w * fixed[2 * i + 1];
            }
            if (bad) {
                st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (convex map)");
                goto done;
            }
        }
    for (size_t k = 0, h = nreal; k < nh; h++) {
        size_t first = k;
        double c[3] = {0, 0, 0}, m = 0;
        for (; holes[k] >= 0; k++, m++)
            for (int d = 0; d < 3; d++)
                c[d] += X[3 * (size_t)holes[k] + (size_t)d];
        for (int d = 0; d < 3; d++)
            c[d] /= m;
        for (size_t j = first; j < k; j++) {
            size_t a = idx[holes[j]];
            double w = 1.0 / fmax(dist3(X + 3 * (size_t)holes[j], c), 1e-9);
            if (a == (size_t)-1)
                continue;
            if (fm_fit_triplets_add(&q, a, a, w) || fm_fit_triplets_add(&q, h, h, w) ||
                fm_fit_triplets_add(&q, a, h, -w)) {
                st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (convex map)");
                goto done;
            }
        }
        k++; /* the -1 */
    }
    if (nfree > 0) {
        if (fm_fit_triplets_compress(&q, nfree, &colptr, &rowind, &val) != FM_OK) {
            st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (convex map)");
            goto done;
        }
        fm_fit_triplets_free(&q);
        st = fm_fit_spd_factor(nfree, colptr, rowind, val, &spd, name, err);
        /* The two coordinates: one factor, two right-hand sides. */
        double *b = sol + nfree;
        for (size_t i = 0; i < nfree && st == FM_OK; i++) {
            sol[i] = rhs[2 * i];
            b[i] = rhs[2 * i + 1];
        }
        if (st == FM_OK)
            st = fm_fit_spd_solve(spd, sol, sol, name, err);
        if (st == FM_OK)
            st = fm_fit_spd_solve(spd, b, b, name, err);
        if (st != FM_OK)
            goto done;
    }
    for (size_t i = 0; i < nv; i++) {
        if (idx[i] != (size_t)-1) {
            uv[2 * i] = sol[idx[i]];
            uv[2 * i + 1] = sol[nfree + idx[i]];
        } else if (onb[i]) {
            uv[2 * i] = fixed[2 * i];
            uv[2 * i + 1] = fixed[2 * i + 1];
        } else {
            uv[2 * i] = uv[2 * i + 1] = 0;
        }
    }
done:
    fm_fit_spd_destroy(spd);
    fm_fit_triplets_free(&q);
    free(loop);
    free(holes);
    free(idx);
    free(fixed);
    free(onb);
    free(active);
    free(rhs);
    free(sol);
    free(colptr);
    free(rowind);
    free(val);
    return st;
}
