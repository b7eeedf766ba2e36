/* The fault model as IGES trimmed surfaces: one 144 per sheet. */
#include <stdio.h>
#include <stdlib.h>

#include "fm_iges.h"
#include "fm_model_write.h"

typedef struct {
    double *ctrl;
    fm_iges_curve2d *curves;
    fm_iges_loop *loops;
} face_store;

static void store_free(face_store *st, size_t n)
{
    for (size_t i = 0; st && i < n; i++) {
        free(st[i].ctrl);
        free(st[i].curves);
        free(st[i].loops);
    }
    free(st);
}

/* fm_trim pieces are B-splines over [t0, t1] = [knots[degree],
 * knots[ncontrol]] (clamped or periodically extended), which is exactly
 * IGES 126's form; the check guards that assumption. */
static int fill_loop(const fm_trim_loop *l, fm_iges_curve2d *c, fm_iges_loop *loop)
{
    size_t n = fm_trim_loop_npieces(l);
    for (size_t p = 0; p < n; p++) {
        fm_trim_piece pc;
        fm_trim_loop_piece(l, p, &pc);
        if (pc.knots[pc.degree] != pc.t0 || pc.knots[pc.ncontrol] != pc.t1)
            return -1;
        c[p].degree = pc.degree;
        c[p].n = pc.ncontrol;
        c[p].knots = pc.knots;
        c[p].ctrl = pc.control;
        c[p].weights = NULL;
    }
    loop->curves = c;
    loop->ncurves = n;
    return 0;
}

fm_status fm_model_write_iges(const char *path, const char *name, const fm_model *m,
                              fm_error *err)
{
    size_t ns = fm_model_nsheets(m);
    face_store *st = calloc(ns ? ns : 1, sizeof *st);
    fm_iges_face *faces = calloc(ns ? ns : 1, sizeof *faces);
    char **names = calloc(ns ? ns : 1, sizeof *names);
    fm_status rc = FM_OK;
    if (!st || !faces || !names)
        rc = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    for (size_t i = 0; i < ns && rc == FM_OK; i++) {
        const fm_fit_surface *s = fm_model_surface(m, i);
        size_t nu, nv, nku, nkv;
        fm_fit_surface_heights(s, &nu, &nv);
        st[i].ctrl = malloc(3 * nu * nv * sizeof *st[i].ctrl);
        size_t nloops = fm_model_nloops(m, i), ncurves = 0;
        for (size_t k = 0; k < nloops; k++)
            ncurves += fm_trim_loop_npieces(fm_model_loop(m, i, k));
        st[i].curves = calloc(ncurves ? ncurves : 1, sizeof *st[i].curves);
        st[i].loops = calloc(nloops ? nloops : 1, sizeof *st[i].loops);
        size_t len = snprintf(NULL, 0, "%s sheet %zu", name, i) + 1;
        names[i] = malloc(len);
        if (!st[i].ctrl || !st[i].curves || !st[i].loops || !names[i]) {
            rc = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
            break;
        }
        /* A single-sheet fault keeps its plain name. */
        if (ns == 1)
            snprintf(names[i], len, "%s", name);
        else
            snprintf(names[i], len, "%s sheet %zu", name, i);
        fm_fit_surface_control_points(s, st[i].ctrl);
        fm_iges_face *f = &faces[i];
        f->name = names[i];
        f->surface.degree_u = f->surface.degree_v = fm_fit_surface_degree(s);
        f->surface.nu = nu;
        f->surface.nv = nv;
        f->surface.knots_u = fm_fit_surface_knots(s, 0, &nku);
        f->surface.knots_v = fm_fit_surface_knots(s, 1, &nkv);
        f->surface.ctrl = st[i].ctrl;
        double dom[4];
        fm_fit_surface_domain(s, dom);
        f->surface.u0 = dom[0];
        f->surface.u1 = dom[1];
        f->surface.v0 = dom[2];
        f->surface.v1 = dom[3];
        size_t used = 0;
        for (size_t k = 0; k < nloops; k++) {
            const fm_trim_loop *l = fm_model_loop(m, i, k);
            if (fill_loop(l, st[i].curves + used, &st[i].loops[k])) {
                rc = fm_error_set(err, FM_ERR_INVALID, path, 0,
                                  "sheet %zu: trimming curve outside its knot range", i);
                break;
            }
            used += fm_trim_loop_npieces(l);
        }
        if (nloops) {
            f->outer = &st[i].loops[0];
            f->holes = st[i].loops + 1;
            f->nholes = nloops - 1;
        }
    }
    if (rc == FM_OK) {
        fm_iges_options opt;
        fm_iges_options_default(&opt);
        rc = fm_iges_write(path, faces, ns, &opt, err);
    }
    for (size_t i = 0; names && i < ns; i++)
        free(names[i]);
    free(names);
    free(faces);
    store_free(st, ns);
    return rc;
}
