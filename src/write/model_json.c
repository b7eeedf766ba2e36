/* The fault model as JSON: the documented exchange form of a fit. */
#include <stdlib.h>

#include "fm_atomic.h"
#include "fm_json.h"
#include "fm_model_write.h"

static void vec3(fm_json *j, const char *key, const double *v)
{
    fm_json_key(j, key);
    fm_json_begin_array(j);
    for (int k = 0; k < 3; k++)
        fm_json_number_exact(j, v[k]);
    fm_json_end_array(j);
}

static void numbers(fm_json *j, const char *key, const double *v, size_t n)
{
    fm_json_key(j, key);
    fm_json_begin_array(j);
    for (size_t i = 0; i < n; i++)
        fm_json_number_exact(j, v[i]);
    fm_json_end_array(j);
}

static void write_frame(fm_json *j, const fm_fit_frame *f)
{
    fm_json_key(j, "frame");
    fm_json_begin_object(j);
    vec3(j, "origin", f->origin);
    vec3(j, "u", f->u);
    vec3(j, "v", f->v);
    vec3(j, "w", f->w);
    fm_json_kv_number(j, "min_dot", f->min_dot);
    fm_json_kv_number(j, "dip_degrees", f->dip_degrees);
    fm_json_kv_bool(j, "projectable", f->projectable);
    fm_json_end_object(j);
}

static int write_surface(fm_json *j, const fm_fit_surface *s)
{
    size_t nu, nv, nku, nkv;
    fm_fit_surface_heights(s, &nu, &nv);
    double *xyz = malloc(3 * nu * nv * sizeof *xyz);
    if (!xyz)
        return -1;
    fm_fit_surface_control_points(s, xyz);
    double dom[4];
    fm_fit_surface_domain(s, dom);
    const double *ku = fm_fit_surface_knots(s, 0, &nku), *kv = fm_fit_surface_knots(s, 1, &nkv);
    fm_json_key(j, "surface");
    fm_json_begin_object(j);
    fm_json_kv_string(j, "kind", fm_fit_surface_kind(s) == FM_FIT_PARAMETRIC ? "parametric"
                                                                              : "height_field");
    fm_json_kv_int(j, "degree", fm_fit_surface_degree(s));
    numbers(j, "domain", dom, 4);
    fm_json_kv_int(j, "nu", (int64_t)nu);
    fm_json_kv_int(j, "nv", (int64_t)nv);
    numbers(j, "knots_u", ku, nku);
    numbers(j, "knots_v", kv, nkv);
    fm_json_key(j, "control_points");
    fm_json_begin_array(j);
    for (size_t i = 0; i < nu * nv; i++) {
        fm_json_begin_array(j);
        for (int k = 0; k < 3; k++)
            fm_json_number_exact(j, xyz[3 * i + k]);
        fm_json_end_array(j);
    }
    fm_json_end_array(j);
    fm_json_end_object(j);
    free(xyz);
    return 0;
}

static void write_loop(fm_json *j, const fm_trim_loop *l, int outer)
{
    const fm_trim_stats *st = fm_trim_loop_stats(l);
    fm_json_begin_object(j);
    fm_json_kv_string(j, "role", outer ? "outer" : "hole");
    fm_json_kv_number(j, "area_m2", fm_trim_loop_area(l));
    fm_json_kv_int(j, "corners", (int64_t)st->corners);
    fm_json_kv_number(j, "max_deviation_m", st->max_dev);
    fm_json_kv_number(j, "rms_deviation_m", st->rms_dev);
    fm_json_kv_number(j, "systematic_deviation_m", st->max_systematic);
    fm_json_key(j, "pieces");
    fm_json_begin_array(j);
    for (size_t p = 0; p < fm_trim_loop_npieces(l); p++) {
        fm_trim_piece pc;
        fm_trim_loop_piece(l, p, &pc);
        fm_json_begin_object(j);
        fm_json_kv_int(j, "degree", pc.degree);
        fm_json_kv_bool(j, "periodic", pc.periodic);
        fm_json_kv_number(j, "t0", pc.t0);
        fm_json_kv_number(j, "t1", pc.t1);
        numbers(j, "knots", pc.knots, pc.nknots);
        fm_json_key(j, "control_points");
        fm_json_begin_array(j);
        for (size_t i = 0; i < pc.ncontrol; i++) {
            fm_json_begin_array(j);
            fm_json_number_exact(j, pc.control[2 * i]);
            fm_json_number_exact(j, pc.control[2 * i + 1]);
            fm_json_end_array(j);
        }
        fm_json_end_array(j);
        fm_json_end_object(j);
    }
    fm_json_end_array(j);
    fm_json_end_object(j);
}

void fm_model_write_sheet_report(fm_json *j, const fm_model *m, size_t i, int with_time)
{
    const fm_sheet_report *r = fm_model_report(m, i);
    const fm_fit_stats *fs = fm_fit_surface_stats(fm_model_surface(m, i));
    const fm_fit_frame *fr = fm_fit_surface_frame(fm_model_surface(m, i));
    fm_json_begin_object(j);
    fm_json_kv_int(j, "index", (int64_t)i + 1); /* sheets count from 1 */
    fm_json_kv_int(j, "vertices", (int64_t)r->vertices);
    fm_json_kv_int(j, "triangles", (int64_t)r->triangles);
    fm_json_kv_string(j, "kind", fs->kind == FM_FIT_PARAMETRIC ? "parametric" : "height_field");
    fm_json_kv_number(j, "min_dot", fr->min_dot);
    fm_json_kv_number(j, "to_surface_rms_m", r->to_surface_rms);
    fm_json_kv_number(j, "to_surface_max_m", r->to_surface_max);
    fm_json_kv_number(j, "from_trimmed_rms_m", r->from_trimmed_rms);
    fm_json_kv_number(j, "from_trimmed_max_m", r->from_trimmed_max);
    fm_json_kv_number(j, "outline_max_m", r->outline_max);
    fm_json_kv_number(j, "outline_rms_m", r->outline_rms);
    fm_json_kv_int(j, "loops", (int64_t)r->loops);
    fm_json_kv_int(j, "holes", (int64_t)r->holes);
    fm_json_kv_int(j, "corners", (int64_t)r->corners);
    fm_json_kv_int(j, "knots_u", (int64_t)fs->spans_u);
    fm_json_kv_int(j, "knots_v", (int64_t)fs->spans_v);
    fm_json_kv_number(j, "knot_spacing_m", fs->knot_spacing);
    fm_json_kv_number(j, "smoothing", fs->smoothing);
    fm_json_kv_int(j, "refinement_passes", fs->passes);
    fm_json_kv_int(j, "repair_sheet", (int64_t)r->repair_sheet);
    if (with_time)
        fm_json_kv_number(j, "time_s", r->time);
    fm_json_end_object(j);
}

fm_status fm_model_write_json(const char *path, const char *name, const fm_model *m,
                              fm_error *err)
{
    fm_atomic_file *f = fm_atomic_open(path, err);
    if (!f)
        return err ? err->code : FM_ERR_IO;
    fm_json j;
    fm_json_init(&j, fm_atomic_stream(f));
    fm_json_begin_object(&j);
    fm_json_kv_string(&j, "format", "faultmesh-model");
    fm_json_kv_int(&j, "format_version", 1);
    fm_json_kv_string(&j, "name", name);
    fm_json_kv_string(&j, "units", "m");
    fm_json_key(&j, "sheets");
    fm_json_begin_array(&j);
    int bad = 0;
    for (size_t i = 0; i < fm_model_nsheets(m) && !bad; i++) {
        const fm_fit_surface *s = fm_model_surface(m, i);
        fm_json_begin_object(&j);
        fm_json_kv_int(&j, "index", (int64_t)i + 1);
        write_frame(&j, fm_fit_surface_frame(s));
        bad = write_surface(&j, s);
        fm_json_key(&j, "trimming_loops");
        fm_json_begin_array(&j);
        for (size_t k = 0; k < fm_model_nloops(m, i); k++)
            write_loop(&j, fm_model_loop(m, i, k), k == 0);
        fm_json_end_array(&j);
        fm_json_key(&j, "report");
        fm_model_write_sheet_report(&j, m, i, 0);
        fm_json_end_object(&j);
    }
    fm_json_end_array(&j);
    /* Where a ring-shaped sheet was cut into disks: the remeshed pieces must
     * meet again along these polylines. */
    fm_json_key(&j, "cuts");
    fm_json_begin_array(&j);
    for (size_t c = 0; c < fm_model_ncuts(m); c++) {
        size_t np;
        long sh[2];
        const double *p = fm_model_cut(m, c, &np, sh);
        fm_json_begin_object(&j);
        fm_json_key(&j, "sheets");
        fm_json_begin_array(&j);
        fm_json_int(&j, sh[0]);
        fm_json_int(&j, sh[1]);
        fm_json_end_array(&j);
        fm_json_key(&j, "points");
        fm_json_begin_array(&j);
        for (size_t q = 0; q < np; q++) {
            fm_json_begin_array(&j);
            for (int k = 0; k < 3; k++)
                fm_json_number_exact(&j, p[3 * q + k]);
            fm_json_end_array(&j);
        }
        fm_json_end_array(&j);
        fm_json_end_object(&j);
    }
    fm_json_end_array(&j);
    fm_json_end_object(&j);
    if (bad) {
        fm_atomic_abort(f);
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    return fm_atomic_commit(f, err);
}
