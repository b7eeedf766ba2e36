/* Delaunay refinement (Ruppert 1995, Shewchuk 2002) in a metric.
 *
 * Encroached sub-segments are split first, then bad triangles are taken
 * from a priority queue: too long first, longest first (refining from the
 * coarse end keeps sizes even), then too skinny, worst first; ties go to
 * the lower slot, so runs repeat exactly. A bad triangle's new point is
 * tried in its own Bowyer-Watson cavity, grown from the triangle with
 * circle tests in the triangle's metric (so the mesh becomes Delaunay in
 * the metric, where quality is judged): if the point lies beyond a segment
 * (outside the domain or across a hole) or in the diametral circle of a
 * segment on the cavity's rim, the segment is split instead and the
 * triangle queued again; if no split could be made it is given up (counted
 * in the stats), which is what makes frozen segments and unsplittable
 * features end instead of loop. */
#include <math.h>
#include <stdlib.h>

#include "cdt_internal.h"

void fm_cdt_refine_options_default(fm_cdt_refine_options *o)
{
    o->size = 0;
    o->min_angle = 30;
    o->metric = NULL;
    o->metric_user = NULL;
    o->split = NULL;
    o->split_user = NULL;
    o->frozen_ids = NULL;
    o->nfrozen = 0;
    o->max_points = 0;
    o->expected_limit = 0;
    o->max_anisotropy = 0;
    o->min_length = 0;
}

static int heap_less(const cdt_heap_item *a, const cdt_heap_item *b)
{
    /* "a comes after b" */
    if (a->key != b->key)
        return a->key < b->key;
    return a->tri > b->tri;
}

static int heap_push(cdt_refiner *r, double key, int32_t tri)
{
    if (r->nheap == r->heapcap) {
        size_t c = r->heapcap ? 2 * r->heapcap : 1024;
        cdt_heap_item *n = realloc(r->heap, c * sizeof *n);
        if (!n)
            return -1;
        r->heap = n;
        r->heapcap = c;
    }
    size_t i = r->nheap++;
    cdt_heap_item it = {key, tri, r->t->stamp[tri]};
    while (i > 0) {
        size_t p = (i - 1) / 2;
        if (!heap_less(&r->heap[p], &it))
            break;
        r->heap[i] = r->heap[p];
        i = p;
    }
    r->heap[i] = it;
    return 0;
}

static cdt_heap_item heap_pop(cdt_refiner *r)
{
    cdt_heap_item top = r->heap[0], last = r->heap[--r->nheap];
    size_t i = 0, n = r->nheap;
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= n)
            break;
        if (c + 1 < n && heap_less(&r->heap[c], &r->heap[c + 1]))
            c++;
        if (!heap_less(&last, &r->heap[c]))
            break;
        r->heap[i] = r->heap[c];
        i = c;
    }
    if (n)
        r->heap[i] = last;
    return top;
}

static void nomem(cdt_refiner *r)
{
    if (r->st == FM_OK)
        r->st = fm_error_set(r->err, FM_ERR_NOMEM, NULL, 0, "out of memory");
}

/* Every triangle made or changed: queue it when bad, and queue its
 * segments when its apex encroaches them. */
static void touch(struct fm_cdt *t, int32_t tri)
{
    cdt_refiner *r = t->touch_user;
    if (t->region[tri] != 1 || r->st != FM_OK)
        return;
    for (int i = 0; i < 3; i++) {
        int32_t e = 3 * tri + i;
        if (t->tc[e] >= 0 && !cdt_frozen(r, t->tc[e]) &&
            cdt_encroaches(r, cdt_p(t, t->tv[e]), cdt_org(t, e), cdt_dst(t, e)) &&
            cdt_segq_push(r, cdt_org(t, e), cdt_dst(t, e)))
            nomem(r);
    }
    cdt_quality q;
    if (cdt_quality_eval(r, tri, &q) == 0 && q.bad && heap_push(r, q.key, tri))
        nomem(r);
}

static void process_segment(cdt_refiner *r, cdt_seg_item it)
{
    struct fm_cdt *t = r->t;
    int32_t e = cdt_find_edge(t, it.a, it.b);
    if (e < 0 || t->tc[e] < 0)
        return;
    /* Still encroached by an apex on the domain side? */
    int32_t f = t->tn[e];
    int enc = 0;
    if (t->region[e / 3] == 1)
        enc |= cdt_encroaches(r, cdt_p(t, t->tv[e]), it.a, it.b);
    if (!enc && f >= 0 && t->region[f / 3] == 1)
        enc |= cdt_encroaches(r, cdt_p(t, t->tv[f]), it.a, it.b);
    if (enc)
        cdt_split_subsegment(r, it.a, it.b);
}

/* The segment on the cavity's rim that p lies beyond: the one the line
 * from the triangle's centroid to p leaves through. */
static int32_t blocking_segment(const struct fm_cdt *t, const double g[2], const double p[2])
{
    int32_t first = -1;
    for (size_t k = 0; k < t->nbnd; k++) {
        int32_t e = t->bnde[k];
        if (t->tc[e] < 0)
            continue;
        const double *a = cdt_p(t, cdt_org(t, e)), *b = cdt_p(t, cdt_dst(t, e));
        if (fm_orient2d(a, b, p) > 0)
            continue;
        if (first < 0)
            first = e;
        if (fm_orient2d(a, b, g) > 0 && fm_orient2d(g, p, a) * fm_orient2d(g, p, b) <= 0)
            return e;
    }
    return first;
}

/* A cap the caller gave is an error; the automatic one ends refinement
 * where it is (the mesh stays valid, its bad triangles are counted). */
static int32_t max_points_error(cdt_refiner *r)
{
    if (r->auto_cap)
        r->t->stats.capped = 1;
    else if (r->st == FM_OK)
        r->st = fm_error_set(r->err, FM_ERR_INVALID, NULL, 0,
                             "refinement reached max_points (%zu points): the size is too "
                             "small for the domain, or refinement does not end",
                             r->max_points);
    return -1;
}

/* 1 if p lies closer than min_length / 2 (in the metric m) to a vertex of
 * the gathered cavity. Under a metric that is nearly constant over the
 * cavity a new point keeps a circumradius from every vertex; one this
 * close comes from a metric varying faster than the mesh can follow, and
 * inserting it would start a cascade. */
static int too_close(const cdt_refiner *r, const double p[2], const double m[3])
{
    const struct fm_cdt *t = r->t;
    double lim = 0.25 * r->min_len * r->min_len;
    if (!(lim > 0))
        return 0;
    for (size_t k = 0; k < t->nbnd; k++) {
        const double *a = cdt_p(t, cdt_org(t, t->bnde[k]));
        double dx = a[0] - p[0], dy = a[1] - p[1];
        if (m[0] * dx * dx + 2 * m[1] * dx * dy + m[2] * dy * dy < lim)
            return 1;
    }
    return 0;
}

/* Splits the sub-segments in pairs[from ..]; the triangle that asked is
 * queued again when anything was split and it survived, else it is given
 * up (so a refused split cannot loop). */
static void split_for(cdt_refiner *r, int32_t tri, size_t from)
{
    struct fm_cdt *t = r->t;
    uint32_t stamp = t->stamp[tri];
    int done = 0;
    while (t->npairs > from && r->st == FM_OK && !t->stats.capped) {
        cdt_pair pr = t->pairs[--t->npairs];
        if (t->np - CDT_NSUPER >= r->max_points) {
            max_points_error(r);
            break;
        }
        done |= cdt_split_subsegment(r, pr.a, pr.b);
    }
    t->npairs = from;
    if (!done)
        t->stats.rejected++;
    else if (t->region[tri] == 1 && t->stamp[tri] == stamp)
        touch(t, tri);
}

/* The triangles from tri to the one holding p, crossing no segment; 0
 * when the way is longer than cap or blocked. */
static size_t walk_to(const struct fm_cdt *t, int32_t tri, const double p[2], int32_t *out,
                      size_t cap)
{
    size_t n = 0;
    int32_t from = -1;
    while (n < cap) {
        out[n++] = tri;
        int moved = 0;
        for (int i = 0; i < 3 && !moved; i++) {
            int32_t e = 3 * tri + i;
            if (e == from ||
                fm_orient2d(cdt_p(t, cdt_org(t, e)), cdt_p(t, cdt_dst(t, e)), p) >= 0)
                continue;
            if (t->tc[e] >= 0 || t->tn[e] < 0)
                return 0;
            from = t->tn[e];
            tri = from / 3;
            moved = 1;
        }
        if (!moved)
            return n;
    }
    return 0;
}

static void insert_for(cdt_refiner *r, int32_t tri, const cdt_quality *qq, const double p[2],
                       int again);

static void process_triangle(cdt_refiner *r, int32_t tri)
{
    struct fm_cdt *t = r->t;
    cdt_quality q;
    if (cdt_quality_eval(r, tri, &q) || !q.bad)
        return;
    double p[2];
    if (cdt_fix_point(r, tri, &q, p)) {
        t->stats.rejected++;
        return;
    }
    insert_for(r, tri, &q, p, 1);
}

/* Inserts p for bad triangle tri, or splits the segments it encroaches.
 * A point too close to a frozen segment (which cannot be split) is
 * replaced, once (again), by the apex of the equilateral triangle on that
 * segment on tri's side: the point a good triangle there has. */
static void insert_for(cdt_refiner *r, int32_t tri, const cdt_quality *qq, const double p[2],
                       int again)
{
    struct fm_cdt *t = r->t;
    cdt_quality q = *qq;
    cdt_use_metric(r, q.m);
    int32_t bad, seed = tri;
    if (!again) {
        /* the apex lies in some other triangle: start from the one holding it */
        int32_t way[64];
        size_t nw = walk_to(t, tri, p, way, 64);
        if (!nw) {
            t->stats.rejected++;
            return;
        }
        seed = way[nw - 1];
    }
    cdt_cavity_result cr = cdt_cavity(t, p, &seed, 1, -1, &bad);
    if (cr == CDT_CAVITY_NOMEM) {
        nomem(r);
        return;
    }
    size_t from = t->npairs;
    if (cr == CDT_CAVITY_NOT_STAR) {
        const int32_t *v = t->tv + 3 * (size_t)tri;
        double g[2];
        for (int c = 0; c < 2; c++)
            g[c] = (cdt_p(t, v[0])[c] + cdt_p(t, v[1])[c] + cdt_p(t, v[2])[c]) / 3;
        int32_t e = blocking_segment(t, g, p);
        if (e < 0) {
            /* No segment in the way: the triangulation is not quite
             * Delaunay in this triangle's metric (it varies), so the
             * cavity missed p's side. Take the triangles on the way to p
             * as well. */
            int32_t seeds[32];
            size_t ns = walk_to(t, tri, p, seeds, 32);
            if (ns) {
                cr = cdt_cavity(t, p, seeds, ns, -1, &bad);
                if (cr == CDT_CAVITY_NOMEM) {
                    nomem(r);
                    return;
                }
                if (cr == CDT_CAVITY_OK)
                    goto star;
            }
        }
        if (e < 0 || cdt_frozen(r, t->tc[e])) {
            t->stats.rejected++;
            return;
        }
        if (cdt_push_pair(t, cdt_org(t, e), cdt_dst(t, e)))
            nomem(r);
        split_for(r, tri, from);
        return;
    }
star:;
    /* An encroached segment is split instead; a frozen one cannot be, and
     * a point off it by a good part of its length is let in: refusing it
     * would leave the skinny triangles next to a shared curve for good. */
    int any = 0;
    double apex[2];
    int have_apex = 0;
    for (size_t k = 0; k < t->nbnd; k++) {
        int32_t e = t->bnde[k];
        if (t->tc[e] < 0 || !cdt_encroaches(r, p, cdt_org(t, e), cdt_dst(t, e)))
            continue;
        if (cdt_frozen(r, t->tc[e])) {
            const double *a = cdt_p(t, cdt_org(t, e)), *b = cdt_p(t, cdt_dst(t, e));
            double d[2] = {b[0] - a[0], b[1] - a[1]}, L2 = d[0] * d[0] + d[1] * d[1];
            double side = d[0] * (p[1] - a[1]) - d[1] * (p[0] - a[0]);
            /* distance over length, in (u, v): the metric is near constant
             * over one triangle */
            if (L2 > 0 && fabs(side) / L2 >= 0.35)
                continue;
            if (L2 > 0 && !have_apex) {
                double sg = side >= 0 ? 1 : -1, h = 0.866 * sg;
                apex[0] = 0.5 * (a[0] + b[0]) - h * d[1];
                apex[1] = 0.5 * (a[1] + b[1]) + h * d[0];
                have_apex = 1;
            }
        }
        any = 1;
        if (!cdt_frozen(r, t->tc[e]) && cdt_push_pair(t, cdt_org(t, e), cdt_dst(t, e)))
            nomem(r);
    }
    if (any) {
        if (have_apex && again && t->npairs == from) {
            insert_for(r, tri, &q, apex, 0);
            return;
        }
        split_for(r, tri, from);
        return;
    }
    if (too_close(r, p, q.m)) {
        t->stats.rejected++;
        return;
    }
    if (t->np - CDT_NSUPER >= r->max_points) {
        max_points_error(r);
        return;
    }
    int32_t nv = cdt_add_point(t, p, -1);
    if (nv < 0 || cdt_commit(t, nv, -1, -1)) {
        if (nv >= 0)
            t->np--;
        nomem(r);
        return;
    }
    t->stats.inserted_interior++;
}

/* Points the metric area and boundary length call for (in the stats), and
 * the automatic cap: 16 times that, with slack for small domains. */
static size_t auto_max_points(cdt_refiner *r)
{
    const struct fm_cdt *t = r->t;
    double area = 0, perim = 0, m[3];
    for (size_t k = 0; k < t->nt && r->st == FM_OK; k++) {
        if (t->region[k] != 1)
            continue;
        const int32_t *v = t->tv + 3 * k;
        const double *a = cdt_p(t, v[0]), *b = cdt_p(t, v[1]), *c = cdt_p(t, v[2]);
        double g[2] = {(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3};
        if (cdt_metric(r, g, m))
            break;
        double ar = 0.5 * fabs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
        area += ar * sqrt(m[0] * m[2] - m[1] * m[1]);
        for (int i = 0; i < 3; i++) {
            int32_t e = (int32_t)(3 * k) + i;
            if (t->tc[e] < 0)
                continue;
            const double *x = cdt_p(t, cdt_org(t, e)), *y = cdt_p(t, cdt_dst(t, e));
            double mid[2] = {0.5 * (x[0] + y[0]), 0.5 * (x[1] + y[1])};
            if (cdt_metric(r, mid, m))
                break;
            double dx = y[0] - x[0], dy = y[1] - x[1];
            /* An interior segment is met from both sides. */
            int32_t f = t->tn[e];
            double w = f >= 0 && t->region[f / 3] == 1 ? 0.5 : 1;
            perim += w * sqrt(m[0] * dx * dx + 2 * m[1] * dx * dy + m[2] * dy * dy);
        }
    }
    double s = r->size;
    /* An equilateral mesh of side s has 2 / (sqrt 3 s^2) points per area. */
    double called = 1.1547 * area / (s * s) + perim / s;
    r->t->stats.expected_points = called < 1e15 ? (size_t)called : (size_t)1e15;
    double n = (double)(t->np - CDT_NSUPER) + 16 * (area / (s * s) + perim / s) + 10000;
    double lim = (double)(INT32_MAX / 8);
    return n < lim ? (size_t)n : (size_t)lim;
}

static size_t count_bad(cdt_refiner *r)
{
    size_t n = 0;
    for (size_t k = 0; k < r->t->nt; k++) {
        cdt_quality q;
        if (r->t->region[k] == 1 && cdt_quality_eval(r, (int32_t)k, &q) == 0 && q.poor)
            n++;
    }
    return n;
}

fm_status fm_cdt_refine(fm_cdt *t, const fm_cdt_refine_options *opt, fm_error *err)
{
    if (!t || !opt)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "fm_cdt_refine: NULL argument");
    if (!(opt->size > 0) || !isfinite(opt->size))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                            "fm_cdt_refine: size must be positive (%g)", opt->size);
    if (!(opt->min_angle >= 0 && opt->min_angle <= 35))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                            "fm_cdt_refine: min_angle must be within 0 .. 35 degrees (%g)",
                            opt->min_angle);
    cdt_refiner r = {0};
    r.t = t;
    r.o = opt;
    r.err = err;
    r.size = opt->size;
    /* 1.4 rather than 1.3: with the size off-centre it keeps edges
     * between 0.7 and 1.4 size (a 1.3 bound splits triangles just above it
     * into edges of 0.65). */
    r.bad_len = 1.4 * opt->size;
    const double pi = 3.14159265358979323846;
    double ang = (opt->min_angle > 1 ? opt->min_angle : 1) * pi / 180;
    r.cos_min = opt->min_angle > 0 ? cos(opt->min_angle * pi / 180) : 2;
    r.tan_half = tan(0.5 * ang);
    if (!(opt->max_anisotropy >= 0) || !(opt->min_length == opt->min_length))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                            "fm_cdt_refine: max_anisotropy must be >= 0 and min_length a number");
    r.aniso2 = opt->max_anisotropy > 0 ? fmax(opt->max_anisotropy, 1.0) : 0;
    r.aniso2 *= r.aniso2;
    r.min_len = opt->min_length == 0 ? opt->size / 16 : opt->min_length > 0 ? opt->min_length : 0;
    if (!isfinite(r.min_len))
        r.min_len = 0;
    r.auto_cap = opt->max_points == 0;
    t->stats = (fm_cdt_refine_stats){0};
    cdt_graph_refined(t);
    r.st = cdt_apex_init(&r);
    if (r.st == FM_OK) {
        size_t cap = auto_max_points(&r); /* also the stats' expected points */
        r.max_points = opt->max_points ? opt->max_points : cap;
        if (opt->expected_limit && t->stats.expected_points > opt->expected_limit)
            t->stats.capped = 1;
    }
    t->touch = touch;
    t->touch_user = &r;
    for (size_t k = 0; k < t->nt && r.st == FM_OK; k++)
        touch(t, (int32_t)k);
    size_t iter = 0, iter_cap = 16 * r.max_points + 100000;
    while (r.st == FM_OK && !t->stats.capped) {
        if (++iter > iter_cap) {
            if (r.auto_cap)
                t->stats.capped = 1;
            else
                r.st = fm_error_set(err, FM_ERR_NUMERIC, NULL, 0,
                                    "refinement did not end after %zu steps", iter_cap);
            break;
        }
        if (r.nsegq) {
            cdt_seg_item it = r.segq[--r.nsegq];
            if (t->np - CDT_NSUPER >= r.max_points) {
                max_points_error(&r);
                break;
            }
            process_segment(&r, it);
        } else if (r.nheap) {
            cdt_heap_item it = heap_pop(&r);
            if (t->region[it.tri] == 1 && t->stamp[it.tri] == it.stamp)
                process_triangle(&r, it.tri);
        } else {
            break;
        }
    }
    t->touch = NULL;
    t->touch_user = NULL;
    if (r.st == FM_OK)
        t->stats.bad_left = count_bad(&r);
    if (cdt_build_output(t) && r.st == FM_OK)
        r.st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    free(r.heap);
    free(r.segq);
    free(r.adj_off);
    free(r.adj);
    return r.st;
}
