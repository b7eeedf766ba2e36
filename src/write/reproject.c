/* One coordinate operation for a whole fault set (fm_reproject.h). */
#include <math.h>
#include <proj.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_reproject.h"

struct fm_reproject {
    PJ_CONTEXT *ctx;
    PJ *op;         /* normalised: x east / longitude, y north / latitude */
    char name[256]; /* the operation's name */
    char accuracy[32];
    char *pipeline; /* its PROJ string */
};

void fm_reproject_destroy(fm_reproject *r)
{
    if (!r)
        return;
    proj_destroy(r->op);
    if (r->ctx)
        proj_context_destroy(r->ctx);
    free(r->pipeline);
    free(r);
}

static PJ_CONTEXT *quiet_context(void)
{
    PJ_CONTEXT *ctx = proj_context_create();
    if (ctx) {
        proj_context_set_enable_network(ctx, 0);
        proj_log_level(ctx, PJ_LOG_NONE);
    }
    return ctx;
}

fm_status fm_reproject_check(const char *from, const char *to, fm_error *err)
{
    PJ_CONTEXT *ctx = quiet_context();
    if (!ctx)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "PROJ: cannot create a context");
    PJ *P = from && to && from[0] && to[0] ? proj_create_crs_to_crs(ctx, from, to, NULL) : NULL;
    fm_status st = FM_OK;
    if (!P)
        st = fm_error_set(err, FM_ERR_INVALID, NULL, 0, "PROJ cannot convert from CRS '%s' to '%s'",
                          from ? from : "", to ? to : "");
    proj_destroy(P);
    proj_context_destroy(ctx);
    return st;
}

/* Longitude/latitude box of the x/y box bb through the source CRS's own
 * geographic CRS (no datum change: only to rank operations). */
static int extent_lonlat(PJ_CONTEXT *ctx, PJ *src, const double bb[4], double ll[4])
{
    PJ *geo = proj_crs_get_geodetic_crs(ctx, src);
    PJ *P = geo ? proj_create_crs_to_crs_from_pj(ctx, src, geo, NULL, NULL) : NULL;
    PJ *N = P ? proj_normalize_for_visualization(ctx, P) : NULL;
    int ok = N != NULL;
    ll[0] = ll[1] = INFINITY;
    ll[2] = ll[3] = -INFINITY;
    for (int i = 0; ok && i <= 4; i++)
        for (int j = 0; ok && j <= 4; j++) {
            double x = bb[0] + (bb[2] - bb[0]) * i / 4, y = bb[1] + (bb[3] - bb[1]) * j / 4;
            PJ_COORD c = proj_trans(N, PJ_FWD, proj_coord(x, y, 0, HUGE_VAL));
            if (!isfinite(c.xy.x) || !isfinite(c.xy.y) || c.xy.x == HUGE_VAL) {
                ok = 0;
                break;
            }
            ll[0] = fmin(ll[0], c.xy.x);
            ll[1] = fmin(ll[1], c.xy.y);
            ll[2] = fmax(ll[2], c.xy.x);
            ll[3] = fmax(ll[3], c.xy.y);
        }
    proj_destroy(N);
    proj_destroy(P);
    proj_destroy(geo);
    return ok ? 0 : -1;
}

fm_reproject *fm_reproject_create(const char *from, const char *to, const double bb[4],
                                  const char *path, fm_error *err)
{
    if (!from || !from[0]) {
        fm_error_set(err, FM_ERR_INVALID, path, 0,
                     "converting to '%s' needs the mesh's CRS (none given)", to ? to : "");
        return NULL;
    }
    fm_reproject *r = calloc(1, sizeof *r);
    if (!r || !(r->ctx = quiet_context())) {
        fm_reproject_destroy(r);
        fm_error_set(err, FM_ERR_NOMEM, path, 0, "PROJ: cannot create a context");
        return NULL;
    }
    PJ *src = proj_create(r->ctx, from), *dst = to ? proj_create(r->ctx, to) : NULL;
    PJ_OPERATION_FACTORY_CONTEXT *fc = NULL;
    PJ_OBJ_LIST *ops = NULL;
    double ll[4];
    if (src && dst && extent_lonlat(r->ctx, src, bb, ll) == 0 &&
        (fc = proj_create_operation_factory_context(r->ctx, NULL))) {
        proj_operation_factory_context_set_grid_availability_use(
            r->ctx, fc, PROJ_GRID_AVAILABILITY_DISCARD_OPERATION_IF_MISSING_GRID);
        proj_operation_factory_context_set_spatial_criterion(
            r->ctx, fc, PROJ_SPATIAL_CRITERION_PARTIAL_INTERSECTION);
        proj_operation_factory_context_set_area_of_interest(r->ctx, fc, ll[0], ll[1], ll[2],
                                                            ll[3]);
        ops = proj_create_operations(r->ctx, src, dst, fc);
    }
    int n = ops ? proj_list_get_count(ops) : 0;
    for (int i = 0; i < n && !r->op; i++) {
        PJ *op = proj_list_get(r->ctx, ops, i);
        if (op && proj_coordoperation_is_instantiable(r->ctx, op)) {
            r->op = proj_normalize_for_visualization(r->ctx, op);
            const char *nm = proj_get_name(op);
            snprintf(r->name, sizeof r->name, "%s", nm ? nm : "unnamed");
            double acc = proj_coordoperation_get_accuracy(r->ctx, op);
            if (acc >= 0)
                snprintf(r->accuracy, sizeof r->accuracy, "%g m", acc);
            else
                snprintf(r->accuracy, sizeof r->accuracy, "unknown");
        }
        proj_destroy(op);
    }
    proj_list_destroy(ops);
    proj_operation_factory_context_destroy(fc);
    proj_destroy(src);
    proj_destroy(dst);
    const char *ps = r->op ? proj_as_proj_string(r->ctx, r->op, PJ_PROJ_5, NULL) : NULL;
    if (ps && (r->pipeline = malloc(strlen(ps) + 1)))
        strcpy(r->pipeline, ps);
    if (!r->op || !r->pipeline) {
        int e = proj_context_errno(r->ctx);
        fm_error_set(err, FM_ERR_INVALID, path, 0, "PROJ cannot convert from CRS '%s' to '%s'%s%s",
                     from, to ? to : "", e ? ": " : "",
                     e ? proj_context_errno_string(r->ctx, e) : "");
        fm_reproject_destroy(r);
        return NULL;
    }
    return r;
}

int fm_reproject_point(const fm_reproject *r, double x, double y, double *ox, double *oy)
{
    PJ_COORD c = proj_trans(r->op, PJ_FWD, proj_coord(x, y, 0, HUGE_VAL));
    *ox = c.xy.x;
    *oy = c.xy.y;
    return isfinite(*ox) && isfinite(*oy) && *ox != HUGE_VAL ? 0 : -1;
}

fm_status fm_reproject_points(const fm_reproject *r, double *xyz, size_t n, size_t stride,
                              const char *path, fm_error *err)
{
    for (size_t i = 0; i < n; i++) {
        double *p = xyz + i * stride;
        double x, y;
        if (fm_reproject_point(r, p[0], p[1], &x, &y))
            return fm_error_set(err, FM_ERR_NUMERIC, path, 0,
                                "PROJ cannot convert point %zu (%.3f, %.3f) by '%s'", i, p[0],
                                p[1], r->name);
        p[0] = x;
        p[1] = y;
    }
    return FM_OK;
}

const char *fm_reproject_name(const fm_reproject *r) { return r->name; }
const char *fm_reproject_accuracy(const fm_reproject *r) { return r->accuracy; }
const char *fm_reproject_pipeline(const fm_reproject *r) { return r->pipeline; }
