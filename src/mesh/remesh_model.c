/* Every sheet of a fault model meshed into one mesh. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_remesh.h"

fm_status fm_remesh_model(const fm_model *m, const fm_remesh_options *opt, fm_mesh **out,
                          fm_remesh_stats *stats, fm_error *err)
{
    return fm_remesh_model_joined(m, NULL, opt, out, NULL, NULL, NULL, stats, err);
}

/* Appends ids (n of them, or n times -1) to *all, which holds *nall. */
static int append_ids(int64_t **all, size_t *nall, const int64_t *ids, size_t n)
{
    int64_t *g = realloc(*all, (*nall + n + 1) * sizeof *g);
    if (!g)
        return -1;
    *all = g;
    for (size_t k = 0; k < n; k++)
        g[*nall + k] = ids ? ids[k] : -1;
    *nall += n;
    return 0;
}

fm_status fm_remesh_model_joined(const fm_model *m, const fm_remesh_sheet_curves *curves,
                                 const fm_remesh_options *opt, fm_mesh **out, int64_t **node_out,
                                 unsigned char *join_failed, fm_error *join_errors,
                                 fm_remesh_stats *stats, fm_error *err)
{
    *out = NULL;
    if (node_out)
        *node_out = NULL;
    int64_t *ids = NULL;
    size_t nids = 0;
    fm_remesh_stats sum;
    memset(&sum, 0, sizeof sum);
    sum.empty = 1;
    fm_mesh *all = fm_mesh_create();
    if (!all)
        return fm_error_set(err, FM_ERR_NOMEM, opt->name, 0, "out of memory");
    fm_status st = FM_OK;
    for (size_t i = 0; i < fm_model_nsheets(m) && st == FM_OK; i++) {
        size_t nl = fm_model_nloops(m, i);
        const fm_trim_loop **loops = malloc((nl ? nl : 1) * sizeof *loops);
        if (!loops) {
            st = fm_error_set(err, FM_ERR_NOMEM, opt->name, 0, "out of memory");
            break;
        }
        for (size_t k = 0; k < nl; k++)
            loops[k] = fm_model_loop(m, i, k);
        fm_mesh *sheet = NULL;
        fm_remesh_stats s;
        int64_t *sid = NULL;
        const fm_remesh_curve *cv = curves ? curves[i].curves : NULL;
        size_t nc = curves ? curves[i].n : 0;
        if (join_failed)
            join_failed[i] = 0;
        st = fm_remesh_sheet_joined(fm_model_surface(m, i), loops, nl, cv, nc, opt, (int32_t)i,
                                    &sheet, NULL, &sid, &s, err);
        if (st != FM_OK && st != FM_ERR_NOMEM && nc > 0) {
            /* Curves that do not fit the domain: the sheet is meshed as
             * it is, and the caller reports the junctions left open. */
            if (join_failed)
                join_failed[i] = 1;
            if (join_errors)
                join_errors[i] = *err;
            st = fm_remesh_sheet_joined(fm_model_surface(m, i), loops, nl, NULL, 0, opt,
                                        (int32_t)i, &sheet, NULL, &sid, &s, err);
        }
        free(loops);
        if (st != FM_OK)
            break;
        if (append_ids(&ids, &nids, sid, fm_mesh_nvertices(sheet))) {
            free(sid);
            fm_mesh_destroy(sheet);
            st = fm_error_set(err, FM_ERR_NOMEM, opt->name, 0, "out of memory");
            break;
        }
        free(sid);
        st = fm_mesh_append(all, sheet, (int32_t)i);
        if (st != FM_OK) {
            fm_mesh_destroy(sheet);
            fm_error_set(err, st, opt->name, 0, "out of memory");
            break;
        }
        fm_mesh_destroy(sheet);
        sum.points += s.points;
        sum.triangles += s.triangles;
        sum.boundary_points += s.boundary_points;
        sum.level_points += s.level_points;
        sum.clamped += s.clamped;
        sum.clamp_max = fmax(sum.clamp_max, s.clamp_max);
        sum.flips += s.flips;
        sum.smoothed += s.smoothed;
        sum.collapsed += s.collapsed;
        sum.cut |= s.cut;
        sum.empty &= s.empty;
        sum.extended = fmax(sum.extended, s.extended);
        sum.time += s.time;
    }
    if (st != FM_OK) {
        fm_mesh_destroy(all);
        free(ids);
        return st;
    }
    if (stats)
        *stats = sum;
    *out = all;
    if (node_out)
        *node_out = ids;
    else
        free(ids);
    return FM_OK;
}
