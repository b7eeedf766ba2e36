/* The CAD model of a meshed fault set: fitted surfaces trimmed by the
 * meshed domains, as IGES (fm_cad_write.h). */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_cad_write.h"
#include "cad_internal.h"
#include "faultset_internal.h"
#include "fm_iges.h"
#include "fm_reproject.h"

struct fm_cad_face {
    char *name;
    int degree;
    size_t nu, nv;
    double *knots_u, *knots_v, *ctrl;
    double dom[4];
    cad_curves cv; /* the trims */
};

void fm_cad_face_destroy(fm_cad_face *f)
{
    if (!f)
        return;
    free(f->name);
    free(f->knots_u);
    free(f->knots_v);
    free(f->ctrl);
    cad_curves_free(&f->cv);
    free(f);
}

static double *dup_doubles(const double *v, size_t n)
{
    double *d = malloc((n + 1) * sizeof *d);
    if (d && n)
        memcpy(d, v, n * sizeof *d);
    return d;
}

fm_status fm_cad_face_create(const char *name, const fm_fit_surface *s, const double *uv,
                             const size_t *start, size_t nloops, const unsigned char *corner,
                             fm_cad_face **out, fm_error *err)
{
    *out = NULL;
    const char *what = name ? name : "face";
    if (nloops == 0)
        return fm_error_set(err, FM_ERR_INVALID, what, 0, "CAD face without an outline");
    fm_cad_face *f = calloc(1, sizeof *f);
    if (!f)
        return fm_error_set(err, FM_ERR_NOMEM, what, 0, "out of memory");
    size_t nku, nkv;
    const double *ku = fm_fit_surface_knots(s, 0, &nku), *kv = fm_fit_surface_knots(s, 1, &nkv);
    fm_fit_surface_heights(s, &f->nu, &f->nv);
    f->degree = fm_fit_surface_degree(s);
    fm_fit_surface_domain(s, f->dom);
    f->name = malloc(strlen(name ? name : "") + 1);
    f->knots_u = dup_doubles(ku, nku);
    f->knots_v = dup_doubles(kv, nkv);
    f->ctrl = malloc((3 * f->nu * f->nv + 1) * sizeof *f->ctrl);
    size_t npts = start[nloops] - start[0];
    unsigned char *brk = malloc(npts + 1);
    if (!f->name || !f->knots_u || !f->knots_v || !f->ctrl || !brk) {
        free(brk);
        fm_cad_face_destroy(f);
        return fm_error_set(err, FM_ERR_NOMEM, what, 0, "out of memory");
    }
    strcpy(f->name, name ? name : "");
    fm_fit_surface_control_points(s, f->ctrl);
    double tol = 1e-7 * hypot(f->dom[1] - f->dom[0], f->dom[3] - f->dom[2]);
    for (size_t l = 0; l < nloops; l++) {
        size_t a = start[l], n = start[l + 1] - start[l];
        if (n < 3) {
            free(brk);
            fm_cad_face_destroy(f);
            return fm_error_set(err, FM_ERR_INVALID, what, 0, "CAD face loop %zu of %zu points",
                                l, n);
        }
        for (size_t i = a; i < a + n; i++)
            if (!(uv[2 * i] >= f->dom[0] - tol && uv[2 * i] <= f->dom[1] + tol &&
                  uv[2 * i + 1] >= f->dom[2] - tol && uv[2 * i + 1] <= f->dom[3] + tol)) {
                fm_error_set(err, FM_ERR_INVALID, what, 0,
                             "CAD face: trimming point (%.17g, %.17g) outside the surface's "
                             "rectangle [%.17g, %.17g] x [%.17g, %.17g]",
                             uv[2 * i], uv[2 * i + 1], f->dom[0], f->dom[1], f->dom[2], f->dom[3]);
                free(brk);
                fm_cad_face_destroy(f);
                return FM_ERR_INVALID;
            }
        /* the writer's own check (iges_check.c) would refuse the whole
         * file for it: a face too small for its surface's parameters is
         * refused here, alone */
        double area = 0;
        for (size_t i = 0; i < n; i++) {
            const double *p = uv + 2 * (a + i), *q = uv + 2 * (a + (i + 1) % n);
            area += p[0] * q[1] - q[0] * p[1];
        }
        if (!(fabs(0.5 * area) > 1e-12 * (f->dom[1] - f->dom[0]) * (f->dom[3] - f->dom[2]))) {
            free(brk);
            fm_cad_face_destroy(f);
            return fm_error_set(err, FM_ERR_INVALID, what, 0,
                                "CAD face loop %zu encloses no area", l);
        }
        cad_loop_breaks(uv + 2 * a, n, corner ? corner + a : NULL, brk + (a - start[0]));
    }
    fm_status st = cad_curves_make(&f->cv, uv, start, nloops, brk);
    free(brk);
    if (st != FM_OK) {
        fm_cad_face_destroy(f);
        return fm_error_set(err, FM_ERR_NOMEM, what, 0, "out of memory");
    }
    *out = f;
    return FM_OK;
}

fm_status fm_cad_write_iges(const char *path, const fm_cad_face *const *faces, size_t n,
                            const char *crs, fm_error *err)
{
    return fm_cad_write_iges_reprojected(path, faces, n, crs, NULL, err);
}

/* Each face's control points converted by rp: copies, one block. */
static double *converted_ctrl(const fm_cad_face *const *faces, size_t n, const fm_reproject *rp,
                              const char *path, fm_error *err)
{
    size_t total = 0;
    for (size_t i = 0; i < n; i++)
        total += 3 * faces[i]->nu * faces[i]->nv;
    double *c = malloc((total + 1) * sizeof *c);
    if (!c) {
        fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
        return NULL;
    }
    size_t w = 0;
    for (size_t i = 0; i < n; i++) {
        size_t k = 3 * faces[i]->nu * faces[i]->nv;
        memcpy(c + w, faces[i]->ctrl, k * sizeof *c);
        w += k;
    }
    if (fm_reproject_points(rp, c, total / 3, 3, path, err) != FM_OK) {
        free(c);
        return NULL;
    }
    return c;
}

fm_status fm_cad_write_iges_reprojected(const char *path, const fm_cad_face *const *faces,
                                        size_t n, const char *crs, const fm_reproject *rp,
                                        fm_error *err)
{
    double *ctrl = rp ? converted_ctrl(faces, n, rp, path, err) : NULL;
    if (rp && !ctrl)
        return err ? err->code : FM_ERR_NUMERIC;
    size_t ncurves = 0, nloops = 0;
    for (size_t i = 0; i < n; i++) {
        ncurves += faces[i]->cv.ncurves;
        nloops += faces[i]->cv.nloops;
    }
    fm_iges_face *out = calloc(n + 1, sizeof *out);
    fm_iges_curve2d *cv = calloc(ncurves + 1, sizeof *cv);
    fm_iges_loop *lp = calloc(nloops + 1, sizeof *lp);
    if (!out || !cv || !lp) {
        free(out);
        free(cv);
        free(lp);
        free(ctrl);
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    size_t cw = 0, lw = 0, pw = 0;
    for (size_t i = 0; i < n; i++) {
        const fm_cad_face *f = faces[i];
        fm_iges_face *g = &out[i];
        g->name = f->name;
        g->surface.degree_u = g->surface.degree_v = f->degree;
        g->surface.nu = f->nu;
        g->surface.nv = f->nv;
        g->surface.knots_u = f->knots_u;
        g->surface.knots_v = f->knots_v;
        g->surface.ctrl = ctrl ? ctrl + pw : f->ctrl;
        pw += 3 * f->nu * f->nv;
        g->surface.u0 = f->dom[0];
        g->surface.u1 = f->dom[1];
        g->surface.v0 = f->dom[2];
        g->surface.v1 = f->dom[3];
        const cad_curves *fc = &f->cv;
        for (size_t c = 0; c < fc->ncurves; c++) {
            cv[cw + c].degree = fc->degree[c];
            cv[cw + c].n = fc->count[c];
            cv[cw + c].knots = fc->knots + fc->kfirst[c];
            cv[cw + c].ctrl = fc->pts + 2 * fc->first[c];
        }
        for (size_t l = 0; l < fc->nloops; l++) {
            lp[lw + l].curves = cv + cw + fc->loop_first[l];
            lp[lw + l].ncurves = fc->loop_first[l + 1] - fc->loop_first[l];
        }
        g->outer = &lp[lw];
        g->holes = lp + lw + 1;
        g->nholes = fc->nloops - 1;
        cw += fc->ncurves;
        lw += fc->nloops;
    }
    char desc[512];
    snprintf(desc, sizeof desc,
             "faultmesh " FM_VERSION_STRING " model.igs: the fault surfaces as meshed.\n"
             "One trimmed B-spline surface (144) per connected part of each sheet,\n"
             "named after its fault (406 form 15), trimmed at the mesh's outline,\n"
             "the intersection curves it shares with other faults and sea level.\n"
             "Units metres, z up (elevation, negative below sea level).\n"
             "CRS: %.150s",
             crs && *crs ? crs : "not given");
    for (char *p = desc; *p; p++)
        if (*p != '\n' && (*p < 32 || *p > 126))
            *p = '?'; /* IGES text is printable ASCII */
    fm_iges_options opt;
    fm_iges_options_default(&opt);
    opt.description = desc;
    opt.product_id = "faultmesh fault model";
    fm_status rc = fs_source_date(path, &opt.time, err);
    if (rc == FM_OK)
        rc = fm_iges_write(path, out, n, &opt, err);
    free(out);
    free(cv);
    free(lp);
    free(ctrl);
    return rc;
}
