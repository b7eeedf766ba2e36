#include "fm_mesh.h"
#include "fm_sort.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define RAD2DEG 57.29577951308232

static void sub3(const double *a, const double *b, double *r)
{
    r[0] = a[0] - b[0];
    r[1] = a[1] - b[1];
    r[2] = a[2] - b[2];
}

static double norm3(const double *v) { return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

double fm_triangle_area(const double *a, const double *b, const double *c)
{
    double u[3], v[3];
    sub3(b, a, u);
    sub3(c, a, v);
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    return 0.5 * norm3(n);
}

/* atan2(|cross|, dot): accurate for the tiny and near-180 degree angles
 * that acos would round badly. */
double fm_angle_at(const double *p, const double *q, const double *r)
{
    double u[3], v[3];
    sub3(q, p, u);
    sub3(r, p, v);
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double d = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    return atan2(norm3(n), d) * RAD2DEG;
}

double fm_segment_distance3(const double *p, const double *a, const double *b)
{
    double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    double s = len2 > 0 ? ((p[0] - a[0]) * d[0] + (p[1] - a[1]) * d[1] + (p[2] - a[2]) * d[2]) / len2
                        : 0.0;
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    double e[3] = {a[0] + s * d[0] - p[0], a[1] + s * d[1] - p[1], a[2] + s * d[2] - p[2]};
    return sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
}

/* The smallest angle faces the shortest side: one atan2, not three (the
 * mesh optimiser calls this for every flip and collapse it considers). */
double fm_triangle_min_angle(const double *a, const double *b, const double *c)
{
    double u[3], v[3], w[3];
    sub3(b, c, u); /* opposite a */
    sub3(c, a, v); /* opposite b */
    sub3(a, b, w); /* opposite c */
    double la = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
    double lb = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    double lc = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    double m;
    if (la <= lb && la <= lc)
        m = fm_angle_at(a, b, c);
    else if (lb <= lc)
        m = fm_angle_at(b, c, a);
    else
        m = fm_angle_at(c, a, b);
    return isfinite(m) ? m : 0.0;
}

double fm_triangle_min_angle_sin(const double *a, const double *b, const double *c)
{
    const double *P[3] = {a, b, c};
    double e[3][3], l[3];
    for (int i = 0; i < 3; i++) { /* e[i]: the side opposite corner i */
        sub3(P[(i + 2) % 3], P[(i + 1) % 3], e[i]);
        l[i] = e[i][0] * e[i][0] + e[i][1] * e[i][1] + e[i][2] * e[i][2];
    }
    int k = l[0] <= l[1] && l[0] <= l[2] ? 0 : l[1] <= l[2] ? 1 : 2;
    /* the angle at corner k lies between the two other sides */
    const double *u = e[(k + 1) % 3], *v = e[(k + 2) % 3];
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double den = l[(k + 1) % 3] * l[(k + 2) % 3];
    double s = den > 0 ? sqrt((n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) / den) : 0.0;
    return isfinite(s) ? fmin(s, 1.0) : 0.0;
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

fm_status fm_mesh_compute_stats(const fm_mesh *m, fm_mesh_stats *st)
{
    memset(st, 0, sizeof *st);
    size_t nv = fm_mesh_nvertices(m), nt = fm_mesh_ntriangles(m);
    const double *X = fm_mesh_vertices(m);
    const int32_t *T = fm_mesh_triangles(m);
    st->vertices = nv;
    st->triangles = nt;
    st->zmin = st->zmax = 0.0;
    if (nt == 0) {
        st->unused_vertices = nv;
        return FM_OK;
    }

    uint64_t *keys = malloc(3 * nt * sizeof *keys);
    double *angles = malloc(nt * sizeof *angles);
    unsigned char *used = calloc(nv ? nv : 1, 1);
    if (!keys || !angles || !used) {
        free(keys);
        free(angles);
        free(used);
        return FM_ERR_NOMEM;
    }

    double angle_sum = 0.0;
    st->angle_min = 180.0;
    for (size_t t = 0; t < nt; t++) {
        const int32_t *v = T + 3 * t;
        for (int k = 0; k < 3; k++) {
            uint32_t a = (uint32_t)v[k], b = (uint32_t)v[(k + 1) % 3];
            keys[3 * t + k] = a < b ? ((uint64_t)a << 32 | b) : ((uint64_t)b << 32 | a);
            used[v[k]] = 1;
        }
        const double *p = X + 3 * v[0], *q = X + 3 * v[1], *r = X + 3 * v[2];
        st->area += fm_triangle_area(p, q, r);
        double ang = fm_triangle_min_angle(p, q, r);
        angles[t] = ang;
        angle_sum += ang;
        if (ang < st->angle_min)
            st->angle_min = ang;
        if (ang < 20.0)
            st->angle_below_20++;
        if (ang < 30.0)
            st->angle_below_30++;
    }
    st->angle_mean = angle_sum / (double)nt;
    fm_sort_doubles(angles, nt);
    st->angle_min_p01 = angles[(size_t)floor(0.01 * (double)(nt - 1))];

    int first = 1;
    for (size_t i = 0; i < nv; i++) {
        if (!used[i]) {
            st->unused_vertices++;
            continue;
        }
        double z = X[3 * i + 2];
        if (first || z < st->zmin)
            st->zmin = z;
        if (first || z > st->zmax)
            st->zmax = z;
        first = 0;
    }

    qsort(keys, 3 * nt, sizeof *keys, cmp_u64);
    /* Reuse the angle buffer for edge lengths: there are at most 3nt edges,
     * so allocate anew only if needed. */
    double *len = realloc(angles, 3 * nt * sizeof *len);
    if (!len) {
        free(angles);
        free(keys);
        free(used);
        return FM_ERR_NOMEM;
    }
    size_t ne = 0;
    double len_sum = 0.0;
    for (size_t i = 0; i < 3 * nt;) {
        size_t j = i + 1;
        while (j < 3 * nt && keys[j] == keys[i])
            j++;
        size_t mult = j - i;
        if (mult == 1)
            st->boundary_edges++;
        else if (mult > 2)
            st->nonmanifold_edges++;
        uint32_t a = (uint32_t)(keys[i] >> 32), b = (uint32_t)(keys[i] & 0xffffffffu);
        double d[3];
        sub3(X + 3 * (size_t)a, X + 3 * (size_t)b, d);
        double l = norm3(d);
        len[ne++] = l;
        len_sum += l;
        i = j;
    }
    st->edges = ne;
    st->edge_median = fm_median(len, ne); /* sorts len */
    st->edge_min = len[0];
    st->edge_max = len[ne - 1];
    st->edge_mean = len_sum / (double)ne;

    free(len);
    free(keys);
    free(used);
    return FM_OK;
}
