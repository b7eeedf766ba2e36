/* The domain as one point list with its loop segments, and its
 * constrained Delaunay triangulation refined under the surface metric,
 * boundary nodes placed on their curves. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "remesh_internal.h"

typedef struct sheet_ctx {
    const fm_fit_surface *s;
    const fm_trim_loop *const *loops;
    double level;
    const dom_seg *segs;  /* per segment id */
    const double *ends;   /* per segment id: its two end points, 4 values */
} sheet_ctx;

static void metric_cb(void *user, const double uv[2], double m[3])
{
    const sheet_ctx *c = user;
    double P[3], du[3], dv[3];
    fm_fit_surface_eval(c->s, uv[0], uv[1], P, du, dv);
    m[0] = du[0] * du[0] + du[1] * du[1] + du[2] * du[2];
    m[1] = du[0] * dv[0] + du[1] * dv[1] + du[2] * dv[2];
    m[2] = dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2];
}

/* Where along the input segment (as a fraction of its chord) a point of
 * one of its sub-segments lies: the chord is a close stand-in for the
 * curve between two nodes at most one size apart. */
double chord_fraction(const double *e, const double p[2])
{
    double d[2] = {e[2] - e[0], e[3] - e[1]};
    double L2 = d[0] * d[0] + d[1] * d[1];
    double f = L2 > 0 ? ((p[0] - e[0]) * d[0] + (p[1] - e[1]) * d[1]) / L2 : 0.5;
    return f < 0 ? 0 : f > 1 ? 1 : f;
}

static void split_cb(void *user, int32_t id, const double a[2], const double b[2], double f,
                     double out[2])
{
    const sheet_ctx *c = user;
    const dom_seg *sg = &c->segs[id];
    const double *e = c->ends + 4 * (size_t)id;
    double straight[2] = {a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])};
    if (sg->kind == SEG_TRIM) {
        double fa = chord_fraction(e, a), fb = chord_fraction(e, b);
        segment_point(c->s, c->loops, c->level, sg, e, e + 2, fa + f * (fb - fa), out);
    } else {
        segment_point(c->s, c->loops, c->level, sg, a, b, f, out);
    }
    /* Between two nodes a size apart a smooth curve stays within a few per
     * cent of its chord; a point far off it means the curve turns back on
     * itself there (a fitted corner that overshoots), and following it
     * would make refinement chase a knot: take the chord's point. */
    double len = hypot(b[0] - a[0], b[1] - a[1]);
    if (!(hypot(out[0] - straight[0], out[1] - straight[1]) <= 0.25 * len)) {
        out[0] = straight[0];
        out[1] = straight[1];
    }
}

void flat_free(flat_domain *f)
{
    free(f->uv);
    free(f->level);
    free(f->seg);
    free(f->segs);
    free(f->ends);
    memset(f, 0, sizeof *f);
}

static fm_status flatten(const remesh_domain *d, flat_domain *f)
{
    size_t n = 0;
    for (size_t l = 0; l < d->n; l++)
        n += d->loops[l].n;
    f->n = n;
    f->uv = malloc(2 * n * sizeof *f->uv + 1);
    f->level = malloc(n * sizeof *f->level + 1);
    f->seg = malloc(2 * n * sizeof *f->seg + 1);
    f->segs = malloc(n * sizeof *f->segs + 1);
    f->ends = malloc(4 * n * sizeof *f->ends + 1);
    if (!f->uv || !f->level || !f->seg || !f->segs || !f->ends)
        return FM_ERR_NOMEM;
    size_t base = 0;
    for (size_t l = 0; l < d->n; l++) {
        const dom_loop *lp = &d->loops[l];
        for (size_t i = 0; i < lp->n; i++) {
            size_t k = base + i, nx = base + (i + 1) % lp->n;
            memcpy(f->uv + 2 * k, lp->uv + 2 * i, 2 * sizeof *f->uv);
            f->level[k] = lp->level[i];
            f->seg[2 * k] = (int32_t)k;
            f->seg[2 * k + 1] = (int32_t)nx;
            f->segs[k] = lp->seg[i];
            memcpy(f->ends + 4 * k, lp->uv + 2 * i, 2 * sizeof *f->ends);
            memcpy(f->ends + 4 * k + 2, lp->uv + 2 * ((i + 1) % lp->n), 2 * sizeof *f->ends);
        }
        base += lp->n;
    }
    return FM_OK;
}

fm_status domain_triangulate(const fm_fit_surface *s, const fm_trim_loop *const *loops,
                             double level, const remesh_domain *dom, double size,
                             size_t max_points, flat_domain *fd, fm_cdt **out, fm_error *err,
                             const char *name)
{
    *out = NULL;
    memset(fd, 0, sizeof *fd);
    if (flatten(dom, fd) != FM_OK) {
        flat_free(fd);
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
    }
    fm_cdt *cdt = NULL;
    fm_error e2;
    fm_error_clear(&e2);
    fm_status rc = fm_cdt_create(fd->uv, fd->n, fd->seg, NULL, fd->n, &cdt, &e2);
    if (rc == FM_OK) {
        sheet_ctx ctx = {s, loops, level, fd->segs, fd->ends};
        fm_cdt_refine_options ro;
        fm_cdt_refine_options_default(&ro);
        ro.size = size;
        ro.metric = metric_cb;
        ro.metric_user = &ctx;
        ro.split = split_cb;
        ro.split_user = &ctx;
        ro.max_points = max_points;
        rc = fm_cdt_refine(cdt, &ro, &e2);
    }
    if (rc != FM_OK) {
        /* The triangulation does not know the file: name it here. */
        fm_error_set(err, rc, name, 0, "%s", e2.message);
        fm_cdt_destroy(cdt);
        flat_free(fd);
        return rc;
    }
    *out = cdt;
    return FM_OK;
}
