/* Triangles projected and flat shaded: enough to see a fault's shape,
 * its folds and its triangles without a 3D library (raster.c draws
 * them). */
#include <math.h>
#include <stdlib.h>

#include "report_internal.h"
#include "fm_vec3.h"

/* Adds the triangles of m whose colour is known: base (for every tag) or
 * per_tag[tag] (when base is NULL; tags past ntags or with a negative red
 * are left out). */
static int add_triangles(rp_scene *s, const fm_mesh *m, int32_t only, const rp_camera *cam,
                         const double *base, const double (*per_tag)[3], size_t ntags, int edges)
{
    size_t nt = fm_mesh_ntriangles(m);
    const double *X = fm_mesh_vertices(m);
    const int32_t *T = fm_mesh_triangles(m), *tg = fm_mesh_tags(m);
    for (size_t t = 0; t < nt; t++) {
        if (only >= 0 && tg[t] != only)
            continue;
        const double *rgb = base;
        if (!rgb) {
            if (tg[t] < 0 || (size_t)tg[t] >= ntags || per_tag[tg[t]][0] < 0)
                continue;
            rgb = per_tag[tg[t]];
        }
        if (s->n == s->cap) {
            size_t cap = s->cap ? 2 * s->cap : 1024;
            rp_tri *g = realloc(s->t, cap * sizeof *g);
            if (!g)
                return -1;
            s->t = g;
            s->cap = cap;
        }
        const double *v[3] = {X + 3 * T[3 * t], X + 3 * T[3 * t + 1], X + 3 * T[3 * t + 2]};
        rp_tri *o = &s->t[s->n++];
        for (int k = 0; k < 3; k++) {
            o->p[k][0] = fm_dot3(v[k], cam->r);
            o->p[k][1] = fm_dot3(v[k], cam->u);
            o->z[k] = fm_dot3(v[k], cam->d);
        }
        double e1[3], e2[3], n[3];
        for (int k = 0; k < 3; k++) {
            e1[k] = v[1][k] - v[0][k];
            e2[k] = v[2][k] - v[0][k];
        }
        n[0] = e1[1] * e2[2] - e1[2] * e2[1];
        n[1] = e1[2] * e2[0] - e1[0] * e2[2];
        n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        double len = sqrt(fm_dot3(n, n));
        /* two-sided: a fault has no outside */
        double lit = len > 0 ? fabs(fm_dot3(n, cam->light)) / len : 0;
        double b = cam->ambient + (1 - cam->ambient) * lit;
        for (int k = 0; k < 3; k++)
            o->rgb[k] = (float)(rgb[k] * b);
        o->edges = edges;
    }
    return 0;
}

int rp_scene_add(rp_scene *s, const fm_mesh *m, int32_t tag, const rp_camera *cam,
                 const double rgb[3], int edges)
{
    return add_triangles(s, m, tag, cam, rgb, NULL, 0, edges);
}

int rp_scene_add_tagged(rp_scene *s, const fm_mesh *m, const rp_camera *cam,
                        const double (*rgb)[3], size_t ntags, int edges)
{
    return add_triangles(s, m, -1, cam, NULL, rgb, ntags, edges);
}

int rp_scene_bounds(const rp_scene *s, double lo[2], double hi[2])
{
    lo[0] = lo[1] = INFINITY;
    hi[0] = hi[1] = -INFINITY;
    for (size_t i = 0; i < s->n; i++)
        for (int k = 0; k < 3; k++)
            for (int c = 0; c < 2; c++) {
                lo[c] = fmin(lo[c], s->t[i].p[k][c]);
                hi[c] = fmax(hi[c], s->t[i].p[k][c]);
            }
    return s->n > 0;
}

void rp_scene_reset(rp_scene *s)
{
    s->n = 0;
}

void rp_scene_free(rp_scene *s)
{
    free(s->t);
    s->t = NULL;
    s->n = s->cap = 0;
}
