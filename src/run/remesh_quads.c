/* --elements quad: the fault set tiled into rectangles (fm_tile.h), each
 * taking the rake and slip rate of the triangle under its centre, the
 * slip turned into the rectangle's own plane; written as VTU, MSH, RSQSim
 * and EQSim; report.json's "rectangles". */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_quad_write.h"
#include "fm_tile.h"
#include "run_internal.h"
#include "remesh_quads.h"
#include "fm_vec3.h"

#define D2R (3.14159265358979323846 / 180)

double quad_rake_from(const fm_tile *tl, const double *a, const double *b, const double *c,
                      double rake)
{
    double st, dp;
    fm_element_orient(a, b, c, &st, &dp);
    st *= D2R;
    dp *= D2R;
    /* the triangle's slip (hanging wall against foot wall) in space */
    double s[3] = {sin(st), cos(st), 0}, n[3] = {sin(dp) * cos(st), -sin(dp) * sin(st), cos(dp)};
    double u[3], v[3], np[3], up[3];
    fm_cross3(n, s, u); /* up dip */
    for (int d = 0; d < 3; d++)
        v[d] = cos(rake * D2R) * s[d] + sin(rake * D2R) * u[d];
    fm_cross3(tl->dip, tl->strike, np);
    /* the rectangle's hanging wall is the triangle's other side */
    if (fm_dot3(np, n) < 0)
        for (int d = 0; d < 3; d++)
            v[d] = -v[d];
    fm_cross3(np, tl->strike, up);
    double r = atan2(fm_dot3(v, up), fm_dot3(v, tl->strike)) / D2R;
    return r <= -180 ? r + 360 : r;
}

fm_status write_quads(const remesh_cli *cli, const fm_faultset *fs, const int32_t *sheet,
                      sim_attrs *sa,
                      output_log *log, fm_error *err)
{
    fm_status st =
        fm_tiles_create_parts(fs->mesh, sheet, fs->nfaults, cli->mesh.size, cli->jobs,
                              &sa->tiles, err);
    if (st != FM_OK)
        return st;
    const fm_tiles *t = sa->tiles;
    size_t n = fm_tiles_count(t);
    double *corners = malloc((12 * n + 1) * sizeof *corners);
    double *rake = malloc((n + 1) * sizeof *rake), *rate = malloc((n + 1) * sizeof *rate);
    int32_t *fault = malloc((n + 1) * sizeof *fault);
    unsigned char *top = malloc(n + 1);
    double *flat = malloc((n + 1) * sizeof *flat);
    size_t plen = strlen(cli->dir) + 32;
    char *path = malloc(plen);
    if (!corners || !rake || !rate || !fault || !top || !flat || !path) {
        st = fm_error_set(err, FM_ERR_NOMEM, cli->dir, 0, "out of memory");
    } else {
        const double *x = fm_mesh_vertices(fs->mesh);
        const int32_t *tri = fm_mesh_triangles(fs->mesh);
        for (size_t i = 0; i < n; i++) {
            const fm_tile *tl = fm_tiles_get(t, i);
            fm_tile_corners(tl, (double(*)[3])(corners + 12 * i));
            size_t k = (size_t)tl->triangle;
            rake[i] = quad_rake_from(tl, x + 3 * (size_t)tri[3 * k], x + 3 * (size_t)tri[3 * k + 1],
                                     x + 3 * (size_t)tri[3 * k + 2], sa->rake_t[k]);
            rate[i] = sa->rate_t[k];
            fault[i] = tl->fault;
            top[i] = tl->row == 0;
            flat[i] = tl->flatness;
        }
        fm_quadset qs = {corners, fault, top, n, fs->names, fs->nfaults, fs->crs, rake, rate, flat};
        static const char *const file[4] = {"mesh.vtu", "mesh.msh", "mesh.rsqsim", "mesh.eqsim"};
        static const unsigned bit[4] = {FMT_VTU, FMT_MSH, FMT_RSQSIM, FMT_EQSIM};
        for (int k = 0; k < 4; k++) {
            if (!(cli->formats & bit[k]))
                continue;
            snprintf(path, plen, "%s/%s", cli->dir, file[k]);
            fm_error e;
            fm_error_clear(&e);
            fm_status s = k == 0   ? fm_quadset_write_vtu(path, &qs, &e)
                          : k == 1 ? fm_quadset_write_msh(path, &qs, &e)
                          : k == 2 ? fm_quadset_write_rsqsim(path, &qs, &e)
                                   : fm_quadset_write_eqsim(path, &qs, cli->sim.eqsim, &e);
            outputs_note(log, path, SIZE_MAX, OUTPUT_SET, s == FM_OK ? NULL : &e);
            if (s != FM_OK && st == FM_OK) {
                st = s;
                if (err)
                    *err = e;
            }
        }
    }
    free(corners);
    free(rake);
    free(rate);
    free(fault);
    free(top);
    free(flat);
    free(path);
    return st;
}

void quads_json(fm_json *j, const sim_attrs *sa, const char *const *names)
{
    const fm_tiles *t = sa->tiles;
    const fm_tile_stats *s = fm_tiles_stats(t);
    fm_json_key(j, "rectangles");
    fm_json_begin_object(j);
    fm_json_kv_number(j, "size_m", s->size);
    fm_json_kv_int(j, "elements", (int64_t)s->ntiles);
    fm_json_kv_int(j, "cut_back_at_other_faults", (int64_t)s->shrunk);
    fm_json_kv_int(j, "given_up", (int64_t)s->dropped);
    fm_json_kv_int(j, "slivers_left_out", (int64_t)s->slivers);
    /* pairs of rectangles of different faults that meet (exact test) */
    fm_json_kv_int(j, "meeting_pairs", (int64_t)s->meeting);
    fm_json_kv_int(j, "faults_not_tiled", (int64_t)s->unrowed);
    fm_json_kv_number(j, "flatness_p99_m", s->flatness_p99);
    fm_json_kv_number(j, "flatness_max_m", s->flatness_max);
    fm_json_kv_number(j, "flatness_p99_of_size", s->size > 0 ? s->flatness_p99 / s->size : 0);
    fm_json_kv_number(j, "area_ratio_min", s->area_ratio_min);
    fm_json_kv_number(j, "area_ratio_max", s->area_ratio_max);
    size_t nj = fm_tiles_njunctions(t), over = 0;
    double gmax = 0;
    for (size_t i = 0; i < nj; i++) {
        const fm_tile_junction *jn = fm_tiles_junction(t, i);
        gmax = fmax(gmax, jn->gap_max);
        over += jn->gap_max > s->size / 2;
    }
    fm_json_kv_number(j, "junction_gap_max_m", gmax);
    fm_json_kv_int(j, "junctions", (int64_t)nj);
    fm_json_kv_int(j, "junctions_with_gap_over_half_size", (int64_t)over);
    fm_json_key(j, "faults");
    fm_json_begin_array(j);
    for (size_t f = 0; f < fm_tiles_nfaults(t); f++) {
        const fm_tile_fault *tf = fm_tiles_fault(t, f);
        fm_json_begin_object(j);
        fm_json_kv_string(j, "name", names[f]);
        fm_json_kv_int(j, "elements", (int64_t)tf->ntiles);
        fm_json_kv_number(j, "area_triangles_m2", tf->area_triangles);
        fm_json_kv_number(j, "area_rectangles_m2", tf->area_tiles);
        fm_json_kv_number(j, "area_ratio",
                          tf->area_triangles > 0 ? tf->area_tiles / tf->area_triangles : 0);
        fm_json_kv_number(j, "area_cut_at_other_faults_m2", tf->area_cut);
        fm_json_kv_number(j, "flatness_max_m", tf->flatness_max);
        fm_json_end_object(j);
    }
    fm_json_end_array(j);
    fm_json_key(j, "junctions");
    fm_json_begin_array(j);
    for (size_t i = 0; i < nj; i++) {
        const fm_tile_junction *jn = fm_tiles_junction(t, i);
        fm_json_begin_object(j);
        fm_json_kv_string(j, "a", names[jn->a]);
        fm_json_kv_string(j, "b", names[jn->b]);
        fm_json_kv_number(j, "length_m", jn->length);
        fm_json_kv_number(j, "gap_max_m", jn->gap_max);
        fm_json_kv_number(j, "gap_mean_m", jn->gap_mean);
        fm_json_kv_number(j, "length_gap_over_half_size_m", jn->over_half);
        fm_json_end_object(j);
    }
    fm_json_end_array(j);
    fm_json_end_object(j);
}
