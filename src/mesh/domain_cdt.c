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
    /* How the metric is taken (see domain_triangulate): step > 0, by
     * central differences over that step in (u, v); iso > 0, the constant
     * iso I; else the first fundamental form at the point. */
    double step, iso;
    double dom[4];        /* the spline's rectangle */
} sheet_ctx;

static void metric_cb(void *user, const double uv[2], double m[3])
{
    const sheet_ctx *c = user;
    double du[3], dv[3];
    if (c->iso > 0) {
        m[0] = c->iso, m[1] = 0, m[2] = c->iso;
        return;
    }
    if (c->step > 0) {
        /* Secants over about a size on the surface: wrinkles of the fit
         * shorter than that average out, as they do in the mesh. */
        for (int d = 0; d < 2; d++) {
            double lo[2] = {uv[0], uv[1]}, hi[2] = {uv[0], uv[1]}, a[3], b[3];
            lo[d] = fmax(uv[d] - c->step, c->dom[2 * d]);
            hi[d] = fmin(uv[d] + c->step, c->dom[2 * d + 1]);
            double h = hi[d] - lo[d];
            if (!(h > 0)) {
                lo[d] = uv[d] - c->step;
                hi[d] = uv[d] + c->step;
                h = 2 * c->step;
            }
            fm_fit_surface_eval(c->s, lo[0], lo[1], a, NULL, NULL);
            fm_fit_surface_eval(c->s, hi[0], hi[1], b, NULL, NULL);
            double *o = d ? dv : du;
            for (int k = 0; k < 3; k++)
                o[k] = (b[k] - a[k]) / h;
        }
    } else {
        double P[3];
        fm_fit_surface_eval(c->s, uv[0], uv[1], P, du, dv);
    }
    m[0] = du[0] * du[0] + du[1] * du[1] + du[2] * du[2];
    m[1] = du[0] * dv[0] + du[1] * dv[1] + du[2] * dv[2];
    m[2] = dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2];
}

/* The points a sheet would call for were it stretched everywhere as its
 * boundary is (scale: metres per unit of (u, v) along it): its (u, v) area
 * inside the loops (outer counter-clockwise, holes clockwise) and their
 * length, at that scale. */
static double points_at_scale(const flat_domain *fd, double scale, double size)
{
    double a = 0, len = 0;
    for (size_t k = 0; k < fd->n; k++) {
        const double *p = fd->uv + 2 * (size_t)fd->seg[2 * k];
        const double *q = fd->uv + 2 * (size_t)fd->seg[2 * k + 1];
        a += p[0] * q[1] - p[1] * q[0];
        len += hypot(q[0] - p[0], q[1] - p[1]);
    }
    return 1.1547 * 0.5 * fabs(a) * scale * scale / (size * size) + len * scale / size;
}

/* Metres on the surface per unit of (u, v), along the domain's boundary. */
static double boundary_scale(const fm_fit_surface *s, const flat_domain *fd)
{
    double l3 = 0, l2 = 0;
    for (size_t k = 0; k < fd->n; k++) {
        const double *a = fd->uv + 2 * (size_t)fd->seg[2 * k];
        const double *b = fd->uv + 2 * (size_t)fd->seg[2 * k + 1];
        l3 += surface_dist(s, a, b);
        l2 += hypot(b[0] - a[0], b[1] - a[1]);
    }
    return l2 > 0 && l3 > 0 && isfinite(l3) ? l3 / l2 : 1;
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
    free(f->shared);
    free(f->curve);
    free(f->end);
    free(f->partner);
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
    int joined = fd->npoints > 0;
    if (!joined) {
        memset(fd, 0, sizeof *fd);
        if (flatten(dom, fd) != FM_OK) {
            flat_free(fd);
            return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
        }
    }
    if (joined) {
        fm_error e0;
        fm_cdt *arr = NULL;
        fm_status r0 = fm_cdt_create_graph(fd->uv, fd->npoints, fd->seg, NULL, fd->nseg, &arr, &e0);
        if (r0 == FM_OK)
            r0 = join_reduce(arr, fd, &e0);
        fm_cdt_destroy(arr);
        if (r0 != FM_OK) {
            fm_error_set(err, r0, name, 0, "%s", e0.message);
            flat_free(fd);
            return r0;
        }
    }
    size_t nseg = joined ? fd->nseg : fd->n, npts = joined ? fd->npoints : fd->n;
    unsigned char *frozen = NULL;
    if (joined) {
        frozen = calloc(nseg + 1, 1);
        if (!frozen) {
            flat_free(fd);
            return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
        }
        for (size_t k = 0; k < nseg; k++)
            frozen[k] = fd->segs[k].kind == SEG_SHARED;
    }
    fm_cdt *cdt = NULL;
    fm_error e2;
    fm_error_clear(&e2);
    sheet_ctx ctx = {s, loops, level, fd->segs, fd->ends, 0, 0, {0, 0, 0, 0}};
    fm_fit_surface_domain(s, ctx.dom);
    double scale = boundary_scale(s, fd), plain = points_at_scale(fd, scale, size);
    fm_status rc = FM_OK;
    /* The surface's own metric first. Where the fit is crumpled (wrinkles
     * far below the size, so the surface is much longer than the fault) or
     * folds, refinement under that metric runs into the automatic cap or
     * ends with many triangles it could not fix; then the metric of
     * secants a size long is tried, and last a constant one (a mesh even
     * in (u, v)), which always ends at about the points the area calls
     * for. */
    for (int mode = 0; mode < 3; mode++) {
        fm_cdt_destroy(cdt);
        cdt = NULL;
        if (joined) {
            rc = fm_cdt_create_graph(fd->uv, npts, fd->seg, NULL, nseg, &cdt, &e2);
            if (rc == FM_OK)
                rc = join_select(cdt, fd, &e2);
        } else {
            rc = fm_cdt_create(fd->uv, npts, fd->seg, NULL, nseg, &cdt, &e2);
        }
        if (rc != FM_OK)
            break;
        ctx.step = mode == 1 ? 0.5 * size / scale : 0;
        ctx.iso = mode == 2 ? scale * scale : 0;
        fm_cdt_refine_options ro;
        fm_cdt_refine_options_default(&ro);
        ro.size = size;
        ro.metric = metric_cb;
        ro.metric_user = &ctx;
        ro.split = split_cb;
        ro.split_user = &ctx;
        ro.max_points = max_points;
        /* A fit far more crumpled than a fault is (fuzz_fit_mesh: a sheet
         * whose surface calls for 130,199 points at 4 km where its
         * outline's stretch calls for 14) would be refined to all of them,
         * the automatic cap being higher still: seconds, and 77,488 nodes
         * on a 20 km fault. On the CFM the surface calls for at most 1.4
         * times the points its outline's stretch does; beyond 100 times,
         * only the constant metric is tried. */
        if (mode < 2)
            ro.expected_limit = (size_t)fmin(100 * (plain + 1), 1e15);
        ro.frozen_ids = frozen;
        ro.nfrozen = frozen ? nseg : 0;
        /* A parametrisation (over a conformal or convex map) that nearly
         * folds has a metric close to singular there; beyond this ratio
         * the mesh in (u, v) cannot follow it anyway. */
        ro.max_anisotropy = 10;
        rc = fm_cdt_refine(cdt, &ro, &e2);
        fm_cdt_refine_stats rs;
        fm_cdt_refine_get_stats(cdt, &rs);
        size_t ntri = fm_cdt_ntriangles(cdt);
        /* A metric that varies faster than the size (a steep height field
         * whose fine knots wrinkle its slope) makes the angle refinement
         * cascade: the mesh ends well below the cap but with many times
         * the points the area calls for, nearly all of them removed again
         * by the collapses, which leaves short edges behind. */
        int swollen = ntri > 12 * rs.expected_points + 200;
        /* A metric clamped to max_anisotropy is one the parametrisation
         * nearly folds at (a strip of a few triangles cut off a ring, over
         * its convex map); where triangles are then left bad, the splits
         * chased the fold (a Coronado Bank north piece of 0.6 km2: 49
         * triangles where 4 were called for, 4 of them under 20 degrees
         * at 1 km). */
        int folded = rs.clamped > 0 && rs.bad_left > 0;
        if (rc != FM_OK || (!rs.capped && !swollen && !folded && rs.bad_left <= 8 + ntri / 50))
            break;
    }
    free(frozen);
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
