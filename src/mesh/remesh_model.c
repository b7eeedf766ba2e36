/* Every sheet of a fault model meshed into one mesh. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_remesh.h"

fm_status fm_remesh_model(const fm_model *m, const fm_remesh_options *opt, fm_mesh **out,
                          fm_remesh_stats *stats, fm_error *err)
{
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
        st = fm_remesh_sheet(fm_model_surface(m, i), loops, nl, opt, (int32_t)i, &sheet, NULL, &s,
                             err);
        free(loops);
        if (st != FM_OK)
            break;
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
        return st;
    }
    if (stats)
        *stats = sum;
    *out = all;
    return FM_OK;
}
