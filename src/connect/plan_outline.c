/* A sheet's trimmed outline for the junction plan: where the nearest point
 * of the outline is (in 3D and in (u, v)), and what lies inside. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "plan_internal.h"

void pl_outline_free(pl_outline *o)
{
    if (!o)
        return;
    free(o->uv);
    free(o->start);
    free(o->a);
    free(o->b);
    fm_closest_tree_destroy(o->tree);
    memset(o, 0, sizeof *o);
}

/* Fine enough that a foot is within metres of the true trimming curve,
 * coarse enough to be cheap on a 100 km fault. */
#define OUTLINE_SPACING 50.0

fm_status pl_outline_build(const fm_model *m, size_t sheet, pl_outline *o, fm_error *err)
{
    memset(o, 0, sizeof *o);
    o->surf = fm_model_surface(m, sheet);
    size_t nl = fm_model_nloops(m, sheet), total = 0;
    o->start = calloc(nl + 1, sizeof *o->start);
    if (!o->start)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    for (size_t l = 0; l < nl; l++) {
        double *uv = NULL;
        size_t n = 0;
        fm_status st = fm_trim_loop_sample(fm_model_loop(m, sheet, l), OUTLINE_SPACING, &uv, &n,
                                           NULL, err);
        if (st != FM_OK) {
            pl_outline_free(o);
            return st;
        }
        double *grown = realloc(o->uv, 2 * (total + n) * sizeof *grown + 1);
        if (!grown) {
            free(uv);
            pl_outline_free(o);
            return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
        }
        o->uv = grown;
        memcpy(o->uv + 2 * total, uv, 2 * n * sizeof *uv);
        free(uv);
        total += n;
        o->start[l + 1] = total;
        o->nloops = l + 1;
    }
    fm_mesh *om = fm_mesh_create();
    o->a = malloc(total * sizeof *o->a + 1);
    o->b = malloc(total * sizeof *o->b + 1);
    if (!om || !o->a || !o->b || fm_mesh_reserve(om, total, total) != FM_OK) {
        fm_mesh_destroy(om);
        pl_outline_free(o);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    for (size_t i = 0; i < total; i++) {
        double p[3];
        fm_fit_surface_eval(o->surf, o->uv[2 * i], o->uv[2 * i + 1], p, NULL, NULL);
        fm_mesh_add_vertex(om, p[0], p[1], p[2]);
    }
    size_t k = 0;
    for (size_t l = 0; l < o->nloops; l++) {
        size_t a0 = o->start[l], n = o->start[l + 1] - a0;
        for (size_t i = 0; i < n; i++, k++) {
            o->a[k] = (int32_t)(a0 + i);
            o->b[k] = (int32_t)(a0 + (i + 1) % n);
            /* a segment as the degenerate triangle a, b, b */
            fm_mesh_add_triangle(om, o->a[k], o->b[k], o->b[k], 0);
        }
    }
    o->tree = fm_closest_tree_create_quick(om, err);
    fm_mesh_destroy(om);
    if (!o->tree) {
        pl_outline_free(o);
        return err ? err->code : FM_ERR_NOMEM;
    }
    return FM_OK;
}

double pl_outline_foot(const pl_outline *o, const double p[3], double foot[3], double uv[2])
{
    fm_closest_hit h;
    if (!fm_closest_query(o->tree, p, INFINITY, &h)) {
        memcpy(foot, p, 3 * sizeof *foot);
        uv[0] = uv[1] = NAN;
        return INFINITY;
    }
    memcpy(foot, h.foot, 3 * sizeof *foot);
    const double *a = o->uv + 2 * o->a[h.triangle], *b = o->uv + 2 * o->b[h.triangle];
    double wb = h.bary[1] + h.bary[2];
    uv[0] = h.bary[0] * a[0] + wb * b[0];
    uv[1] = h.bary[0] * a[1] + wb * b[1];
    return h.dist;
}

int pl_outline_inside(const pl_outline *o, const double uv[2])
{
    int in = 0;
    for (size_t l = 0; l < o->nloops; l++) {
        size_t a0 = o->start[l], n = o->start[l + 1] - a0;
        for (size_t i = 0; i < n; i++) {
            const double *a = o->uv + 2 * (a0 + i), *b = o->uv + 2 * (a0 + (i + 1) % n);
            if ((a[1] > uv[1]) != (b[1] > uv[1])) {
                double x = a[0] + (uv[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
                if (x > uv[0])
                    in ^= 1;
            }
        }
    }
    return in;
}
