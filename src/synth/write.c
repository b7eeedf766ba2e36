/* Writing the system: one TSurf per fault and faults.json, the record of
 * the analytic surfaces and of what later stages must find. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_atomic.h"
#include "fm_json.h"
#include "fm_tsurf.h"
#include "synth_internal.h"

static const char *style_name(int style)
{
    switch (style) {
    case SYNTH_GRID_FIXED: return "regular grid, fixed diagonal";
    case SYNTH_GRID_ALTERNATE: return "regular grid, alternating diagonals";
    default: return "irregular: graded 2.6x, jittered, random diagonals, centre splits";
    }
}

static fm_status write_tsurf(const synth_fault *f, size_t index, const char *dir, fm_error *err)
{
    size_t n = strlen(dir) + strlen(f->name) + 8;
    char *path = malloc(n);
    fm_tsurf *ts = fm_tsurf_create(f->name);
    if (!path || !ts) {
        free(path);
        fm_tsurf_destroy(ts);
        return fm_error_set(err, FM_ERR_NOMEM, dir, 0, "out of memory");
    }
    snprintf(path, n, "%s/%s.ts", dir, f->name);
    fm_status st = FM_OK;
    for (size_t p = 0; p < f->nparts && st == FM_OK; p++)
        if (fm_tsurf_add_part(ts) < 0)
            st = FM_ERR_NOMEM;
    /* A distinct, stable colour per fault, as CFM headers carry one. */
    char colour[64];
    snprintf(colour, sizeof colour, "%.6f %.6f %.6f 1", 0.3 + 0.07 * (double)(index % 10),
             0.8 - 0.05 * (double)(index % 7), 0.2 + 0.09 * (double)(index % 8));
    if (st == FM_OK)
        st = fm_tsurf_set_header(ts, "name", f->name);
    if (st == FM_OK)
        st = fm_tsurf_set_header(ts, "*visible", "true");
    if (st == FM_OK)
        st = fm_tsurf_set_header(ts, "*solid*color", colour);
    fm_mesh *m = fm_tsurf_mesh_mut(ts);
    const fm_mesh *src = f->mesh;
    size_t nv = fm_mesh_nvertices(src), nt = fm_mesh_ntriangles(src);
    if (st == FM_OK)
        st = fm_mesh_reserve(m, nv, nt);
    const double *v = fm_mesh_vertices(src);
    const int32_t *t = fm_mesh_triangles(src), *tag = fm_mesh_tags(src);
    for (size_t k = 0; k < nv && st == FM_OK; k++)
        if (fm_mesh_add_vertex(m, v[3 * k], v[3 * k + 1], v[3 * k + 2]) < 0)
            st = FM_ERR_NOMEM;
    for (size_t k = 0; k < nt && st == FM_OK; k++)
        if (fm_mesh_add_triangle(m, t[3 * k], t[3 * k + 1], t[3 * k + 2], tag[k]) < 0)
            st = FM_ERR_NOMEM;
    if (st != FM_OK)
        fm_error_set(err, st, path, 0, "cannot build the TSurf object: %s", fm_status_string(st));
    else
        st = fm_tsurf_write_file(path, &ts, 1, err);
    fm_tsurf_destroy(ts);
    free(path);
    return st;
}

static void kv_pair(fm_json *j, const char *key, double a, double b)
{
    fm_json_key(j, key);
    fm_json_begin_array(j);
    fm_json_number_exact(j, a);
    fm_json_number_exact(j, b);
    fm_json_end_array(j);
}

static void json_sheet(fm_json *j, const synth_fault *f, size_t k)
{
    const synth_sheet *sh = &f->sheet[k];
    fm_json_begin_object(j);
    fm_json_kv_string(j, "role", sh->law == SYNTH_SPLAY ? "splay" : "sheet");
    if (sh->law == SYNTH_SPLAY) {
        fm_json_kv_string(j, "law", "splay");
        fm_json_kv_string(j, "formula",
                          "x(s,t) = J(s) + (1 - t/W)*l(s)*(side*cos(dip)*ud0 + sin(dip)*ez), "
                          "J(s) = x0(s, junction_t), l(s) = (top0(s) - J_z(s))/sin(dip)");
        fm_json_kv_number(j, "dip_deg", sh->dip_deg);
        fm_json_kv_number(j, "side", sh->away);
        fm_json_kv_number(j, "junction_t", sh->junction_t);
        kv_pair(j, "junction_s_range", sh->s0, sh->s1);
    } else {
        fm_json_kv_string(j, "law", sh->law == SYNTH_CIRCULAR ? "circular" : "planar");
        kv_pair(j, "origin", sh->origin[0] + SYNTH_CENTRE_X, sh->origin[1] + SYNTH_CENTRE_Y);
        fm_json_kv_number(j, "strike_deg", sh->strike_deg);
        kv_pair(j, "us", sh->us[0], sh->us[1]);
        kv_pair(j, "ud", sh->ud[0], sh->ud[1]);
        if (sh->law == SYNTH_CIRCULAR) {
            fm_json_kv_number(j, "dip_top_deg", sh->dip1_deg);
            fm_json_kv_number(j, "z_dip_top", sh->z1);
            fm_json_kv_number(j, "dip_bottom_deg", sh->dip2_deg);
            fm_json_kv_number(j, "z_dip_bottom", sh->z2);
            fm_json_key(j, "radius");
            fm_json_number_exact(j, sh->radius);
        } else {
            fm_json_kv_number(j, "dip_deg", sh->dip_deg);
        }
        fm_json_key(j, "corrugation");
        if (sh->corr_amp != 0.0) {
            fm_json_begin_object(j);
            fm_json_kv_number(j, "amplitude", sh->corr_amp);
            fm_json_kv_number(j, "wavelength", sh->corr_wavelength);
            fm_json_kv_number(j, "phase_deg", sh->corr_phase_deg);
            fm_json_end_object(j);
        } else {
            fm_json_null(j);
        }
        fm_json_key(j, "top");
        fm_json_begin_object(j);
        fm_json_kv_string(j, "type", sh->top_topo ? "topography" : "constant");
        if (!sh->top_topo)
            fm_json_kv_number(j, "z", sh->top_z);
        fm_json_end_object(j);
        fm_json_kv_number(j, "bottom_z", sh->bottom_z);
    }
    kv_pair(j, "s_range", sh->s0, sh->s1);
    kv_pair(j, "t_range", 0.0, sh->width);
    fm_json_end_object(j);
}

static void json_expected(fm_json *j, const fm_synth *sy, const synth_fault *f)
{
    fm_json_key(j, "expected");
    fm_json_begin_object(j);
    fm_json_kv_int(j, "parts", (int64_t)f->nparts);
    fm_json_kv_int(j, "seam_duplicated_vertices", (int64_t)f->seam_vertices);
    if (f->seam)
        fm_json_kv_number(j, "seam_s", f->seam_s);
    fm_json_kv_int(j, "sheets_after_repair", (int64_t)f->nsheets);
    fm_json_kv_int(j, "junctions", (int64_t)f->nsheets - 1);
    fm_json_kv_int(j, "junction_edges", (int64_t)f->junction_edges);
    fm_json_kv_int(j, "holes", (int64_t)f->holes);
    if (f->hole) {
        kv_pair(j, "hole_centre_st", f->hole_s, f->hole_t);
        kv_pair(j, "hole_radii_st", f->hole_rs, f->hole_rt);
    }
    fm_json_kv_bool(j, "top_above_sea_level", f->top_zmin > 0.0);
    fm_json_kv_bool(j, "blind", f->top_zmax < 0.0);
    kv_pair(j, "top_z_range", f->top_zmin, f->top_zmax);
    fm_json_kv_number(j, "bottom_z", f->sheet[0].bottom_z);
    fm_json_kv_number(j, "noise_max_per_coordinate", f->noise);
    fm_json_kv_number(j, "noise_max_distance", f->noise * sqrt(3.0));
    fm_json_key(j, "gap");
    if (f->gap_to >= 0) {
        fm_json_begin_object(j);
        fm_json_kv_string(j, "to", sy->fault[f->gap_to].name);
        fm_json_kv_number(j, "distance_m", f->gap);
        fm_json_kv_string(j, "end", "s = 0 (every vertex of that edge, at every depth)");
        fm_json_end_object(j);
    } else {
        fm_json_null(j);
    }
    fm_json_key(j, "overshoot");
    if (f->overshoot_of >= 0) {
        fm_json_begin_object(j);
        fm_json_kv_string(j, "of", sy->fault[f->overshoot_of].name);
        fm_json_kv_number(j, "distance_m", f->overshoot);
        fm_json_kv_string(j, "end", "s = 0 (every vertex of that edge, at every depth)");
        fm_json_end_object(j);
    } else {
        fm_json_null(j);
    }
    fm_json_key(j, "crosses");
    if (f->crosses >= 0)
        fm_json_string(j, sy->fault[f->crosses].name);
    else
        fm_json_null(j);
    fm_json_end_object(j);
}

static void json_system(fm_json *j, const fm_synth *sy)
{
    const synth_topo *tp = &sy->topo;
    fm_json_kv_string(j, "generator", "faultmesh synth " FM_VERSION_STRING);
    fm_json_key(j, "options");
    fm_json_begin_object(j);
    fm_json_kv_number(j, "spacing", sy->opt.spacing);
    fm_json_kv_int(j, "seed", (int64_t)sy->opt.seed);
    fm_json_end_object(j);
    fm_json_key(j, "coordinate_system");
    fm_json_begin_object(j);
    fm_json_kv_string(j, "description",
                      "UTM zone 11N-like metres (as CFM), z elevation positive up; GOCAD NAME "
                      "Default, AXIS_UNIT m m m, ZPOSITIVE Elevation");
    kv_pair(j, "centre", SYNTH_CENTRE_X, SYNTH_CENTRE_Y);
    fm_json_end_object(j);
    fm_json_key(j, "topography");
    fm_json_begin_object(j);
    fm_json_kv_string(j, "formula",
                      "z = base + a_xi*sin(2*pi*xi/l_xi + phase_xi) + a_eta*cos(2*pi*eta/l_eta), "
                      "xi = (X - Xc, Y - Yc).xi_dir, eta = (X - Xc, Y - Yc).eta_dir");
    kv_pair(j, "xi_dir", tp->xi[0], tp->xi[1]);
    kv_pair(j, "eta_dir", tp->eta[0], tp->eta[1]);
    fm_json_kv_number(j, "base", tp->base);
    fm_json_kv_number(j, "a_xi", tp->amp_xi);
    fm_json_kv_number(j, "l_xi", tp->wl_xi);
    fm_json_kv_number(j, "phase_xi", tp->phase_xi);
    fm_json_kv_number(j, "a_eta", tp->amp_eta);
    fm_json_kv_number(j, "l_eta", tp->wl_eta);
    fm_json_end_object(j);
    fm_json_kv_string(
        j, "parameterization",
        "x(s,t) = O + s*us + (h(w) + c(s))*ud + z(w)*ez; us = (sin strike, cos strike), ud = "
        "(cos strike, -sin strike) (dip direction, right of strike); c(s) = "
        "A*sin(2*pi*s/lambda + phase) with A, lambda = corrugation amplitude, wavelength; w ="
        " w_top(s) + t*(w_bot - w_top(s))/W, w_top/w_bot the arc lengths where z(w) reaches "
        "the top/bottom elevation. planar: h = w*cos(dip), z = -w*sin(dip). circular: d = "
        "dip_top - w/R, h = R*(sin dip_top - sin d), z = z_dip_top + R*(cos dip_top - cos d),"
        " R = (z_dip_top - z_dip_bottom)/(cos dip_bottom - cos dip_top). W = w(bottom) - "
        "w(0), or w(bottom) - w(top z) for a constant top, so t is the down-dip arc length "
        "(stretched by a few percent under topography). Top under topography: the topography "
        "at the reference trace O + s*us. Distances are to the noise-free surface over the "
        "whole parameter rectangle (holes are not part of the analytic surface).");
}

static fm_status write_json(const fm_synth *sy, const char *dir, fm_error *err)
{
    size_t n = strlen(dir) + 16;
    char *path = malloc(n);
    if (!path)
        return fm_error_set(err, FM_ERR_NOMEM, dir, 0, "out of memory");
    snprintf(path, n, "%s/faults.json", dir);
    fm_atomic_file *af = fm_atomic_open(path, err);
    free(path);
    if (!af)
        return err ? err->code : FM_ERR_IO;
    fm_json j;
    fm_json_init(&j, fm_atomic_stream(af));
    fm_json_begin_object(&j);
    json_system(&j, sy);
    fm_json_key(&j, "faults");
    fm_json_begin_array(&j);
    for (size_t i = 0; i < sy->nfaults; i++) {
        const synth_fault *f = &sy->fault[i];
        fm_json_begin_object(&j);
        fm_json_kv_string(&j, "name", f->name);
        char file[sizeof f->name + 4];
        snprintf(file, sizeof file, "%s.ts", f->name);
        fm_json_kv_string(&j, "file", file);
        fm_json_kv_string(&j, "kind", f->kind);
        fm_json_kv_string(&j, "description", f->description);
        fm_json_key(&j, "triangulation");
        fm_json_begin_object(&j);
        fm_json_kv_string(&j, "style", style_name(f->style));
        fm_json_kv_int(&j, "vertices", (int64_t)fm_mesh_nvertices(f->mesh));
        fm_json_kv_int(&j, "triangles", (int64_t)fm_mesh_ntriangles(f->mesh));
        fm_json_end_object(&j);
        fm_json_key(&j, "sheets");
        fm_json_begin_array(&j);
        for (size_t k = 0; k < f->nsheets; k++)
            json_sheet(&j, f, k);
        fm_json_end_array(&j);
        json_expected(&j, sy, f);
        fm_json_end_object(&j);
    }
    fm_json_end_array(&j);
    fm_json_end_object(&j);
    return fm_atomic_commit(af, err);
}

fm_status fm_synth_write(const fm_synth *s, const char *dir, fm_error *err)
{
    fm_status st = fm_mkdir_p(dir, err);
    for (size_t i = 0; i < s->nfaults && st == FM_OK; i++)
        st = write_tsurf(&s->fault[i], i, dir, err);
    if (st == FM_OK)
        st = write_json(s, dir, err);
    return st;
}
