/* Angles, edge lengths and boundary corners of a triangle mesh. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_check.h"
#include "fm_sort.h"

static double angle_at(const double *p, const double *a, const double *b)
{
    double u[3] = {a[0] - p[0], a[1] - p[1], a[2] - p[2]};
    double v[3] = {b[0] - p[0], b[1] - p[1], b[2] - p[2]};
    double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    /* atan2 of |u x v| and u.v stays accurate for angles near 0 and 180. */
    return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
                 u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) * (180.0 / 3.14159265358979323846);
}

fm_status fm_check_quality(const fm_mesh *m, int32_t tag, double H, fm_quality *q)
{
    memset(q, 0, sizeof *q);
    size_t nv = fm_mesh_nvertices(m), nt = fm_mesh_ntriangles(m);
    const double *X = fm_mesh_vertices(m);
    const int32_t *T = fm_mesh_triangles(m), *tags = fm_mesh_tags(m);
    double *angle_sum = calloc(nv ? nv : 1, sizeof *angle_sum);
    unsigned char *used = calloc(nv ? nv : 1, 1);
    fm_keyed *e = malloc(3 * nt * sizeof *e + 1);
    double *len = NULL;
    if (!angle_sum || !used || !e) {
        free(angle_sum);
        free(used);
        free(e);
        return FM_ERR_NOMEM;
    }
    /* first pass: angles, edges */
    size_t ne = 0;
    double sum_min = 0;
    q->angle_min = 180;
    q->zmax = -INFINITY;
    for (size_t t = 0; t < nt; t++) {
        if (tag >= 0 && tags[t] != tag)
            continue;
        const int32_t *v = T + 3 * t;
        double ang[3];
        for (int i = 0; i < 3; i++) {
            ang[i] = angle_at(X + 3 * v[i], X + 3 * v[(i + 1) % 3], X + 3 * v[(i + 2) % 3]);
            angle_sum[v[i]] += ang[i];
            used[v[i]] = 1;
            uint32_t a = (uint32_t)v[(i + 1) % 3], b = (uint32_t)v[(i + 2) % 3];
            e[ne].key = a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
            e[ne].index = ne;
            ne++;
        }
        double mn = fmin(ang[0], fmin(ang[1], ang[2]));
        q->angle_min = fmin(q->angle_min, mn);
        sum_min += mn;
        q->below_30 += mn < 30;
        q->below_20 += mn < 20;
        q->area += fm_triangle_area(X + 3 * v[0], X + 3 * v[1], X + 3 * v[2]);
        q->triangles++;
    }
    q->angle_mean = q->triangles ? sum_min / (double)q->triangles : 0;
    if (!q->triangles)
        q->angle_min = 0;
    int sorted = fm_sort_keyed(e, ne) == 0;
    unsigned char *boundary = calloc(nv ? nv : 1, 1);
    len = malloc((ne ? ne : 1) * sizeof *len);
    if (!sorted || !boundary || !len) {
        free(angle_sum);
        free(used);
        free(e);
        free(boundary);
        free(len);
        return FM_ERR_NOMEM;
    }
    size_t nl = 0, in_band = 0;
    for (size_t k = 0; k < ne;) {
        size_t j = k + 1;
        while (j < ne && e[j].key == e[k].key)
            j++;
        size_t ea = (size_t)(e[k].key >> 32), eb = (size_t)(e[k].key & 0xffffffffu);
        if (j - k == 1)
            boundary[ea] = boundary[eb] = 1;
        const double *a = X + 3 * ea, *b = X + 3 * eb;
        double l = sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                        (a[2] - b[2]) * (a[2] - b[2]));
        len[nl++] = l;
        in_band += l >= 0.7 * H && l <= 1.4 * H;
        k = j;
    }
    q->edges = nl;
    q->edges_in_band = in_band;
    if (nl) {
        fm_sort_doubles(len, nl);
        q->edge_min = len[0];
        q->edge_max = len[nl - 1];
        q->edge_median = len[nl / 2];
        q->edge_p05 = len[(size_t)(0.05 * (double)(nl - 1))];
        q->edge_p95 = len[(size_t)(0.95 * (double)(nl - 1))];
    }
    for (size_t v = 0; v < nv; v++) {
        if (!used[v])
            continue;
        q->nodes++;
        q->zmax = fmax(q->zmax, X[3 * v + 2]);
        q->sharp_corners += boundary[v] && angle_sum[v] < 40;
    }
    if (!q->nodes)
        q->zmax = 0;
    /* second pass: which small angles sit at sharp corners */
    for (size_t t = 0; t < nt; t++) {
        if (tag >= 0 && tags[t] != tag)
            continue;
        const int32_t *v = T + 3 * t;
        double best = 180;
        int at = 0;
        for (int i = 0; i < 3; i++) {
            double a = angle_at(X + 3 * v[i], X + 3 * v[(i + 1) % 3], X + 3 * v[(i + 2) % 3]);
            if (a < best) {
                best = a;
                at = i;
            }
        }
        if (best < 20 && boundary[v[at]] && angle_sum[v[at]] < 40)
            q->below_20_forced++;
    }
    free(angle_sum);
    free(used);
    free(e);
    free(boundary);
    free(len);
    return FM_OK;
}
