/* One fault's connect measures (fm_check_loss): its unclosed gaps, the
 * area of its original the output misses, and how far the output moved
 * the original's interior. Reads only the shared set; writes only o. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check_internal.h"

/* Sampling of an original triangle: split in four at most this many times,
 * so a huge triangle at a tiny size stays bounded (4^6 leaves). */
#define MAX_DEPTH 6

typedef struct near_fault {
    int32_t fault;
    double d2;
} near_fault;

typedef struct near_query {
    const fm_mesh *set;
    int32_t self;
    double p[3];
    double max2;   /* only triangles this close count */
    int stop_at_first;
    near_fault *near;
    size_t n, cap;
    int nomem;
} near_query;

static double tri_dist2(const fm_mesh *m, int32_t t, const double p[3])
{
    const double *X = fm_mesh_vertices(m);
    const int32_t *T = fm_mesh_triangles(m);
    double a[3], b[3], c[3], o[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++) {
        a[k] = X[3 * T[3 * t] + k] - p[k];
        b[k] = X[3 * T[3 * t + 1] + k] - p[k];
        c[k] = X[3 * T[3 * t + 2] + k] - p[k];
    }
    return fm_closest_on_triangle(o, a, b, c, NULL, NULL);
}

/* Box query callback: the closest distance to every other fault. */
static int near_cb(int32_t t, void *user)
{
    near_query *q = user;
    int32_t g = fm_mesh_tags(q->set)[t];
    if (g == q->self)
        return 0;
    double d2 = tri_dist2(q->set, t, q->p);
    if (d2 > q->max2)
        return 0;
    if (q->stop_at_first)
        return q->n = 1;
    for (size_t i = 0; i < q->n; i++)
        if (q->near[i].fault == g) {
            q->near[i].d2 = fmin(q->near[i].d2, d2);
            return 0;
        }
    if (q->n == q->cap) {
        size_t cap = q->cap ? 2 * q->cap : 8;
        near_fault *nf = realloc(q->near, cap * sizeof *nf);
        if (!nf) {
            q->nomem = 1;
            return 1;
        }
        q->near = nf;
        q->cap = cap;
    }
    q->near[q->n++] = (near_fault){g, d2};
    return 0;
}

static void near_faults(const ck_set *s, near_query *q, const double p[3], double r)
{
    double lo[3], hi[3];
    for (int k = 0; k < 3; k++) {
        q->p[k] = p[k];
        lo[k] = p[k] - r;
        hi[k] = p[k] + r;
    }
    q->max2 = r * r;
    q->n = 0;
    fm_closest_tree_box_query(s->all, lo, hi, near_cb, q);
}

/* Whether faults f and g share a node within r of the segment a-b. */
static int shared_near(const ck_set *s, int32_t f, int32_t g, const double *a, const double *b,
                       double r)
{
    uint64_t lo = (uint64_t)(f < g ? f : g), hi = (uint64_t)(f < g ? g : f);
    uint64_t key = lo << 32 | hi;
    const double *X = fm_mesh_vertices(s->in->set);
    for (size_t i = fm_keyed_lower_bound(s->shared, s->nshared, key);
         i < s->nshared && s->shared[i].key == key; i++)
        if (fm_segment_distance3(X + 3 * s->shared[i].index, a, b) <= r)
            return 1;
    return 0;
}

static int add_gap(ck_fault_out *o, int32_t g, double len)
{
    for (size_t i = 0; i < o->ngaps; i++)
        if (o->gaps[i].other == g) {
            o->gaps[i].length += len;
            return 0;
        }
    ck_gap *ng = realloc(o->gaps, (o->ngaps + 1) * sizeof *ng);
    if (!ng)
        return -1;
    o->gaps = ng;
    o->gaps[o->ngaps++] = (ck_gap){g, len};
    return 0;
}

static int cmp_gap(const void *a, const void *b)
{
    const ck_gap *x = a, *y = b;
    return (x->other > y->other) - (x->other < y->other);
}

static fm_status gaps(const ck_set *s, int32_t f, double H, near_query *q, ck_fault_out *o)
{
    const double *X = fm_mesh_vertices(s->in->set);
    for (size_t e = s->bnd_first[f]; e < s->bnd_first[f + 1]; e++) {
        const double *a = X + 3 * (s->bnd[e] >> 32), *b = X + 3 * (s->bnd[e] & 0xffffffffu);
        double m[3], len = 0;
        for (int k = 0; k < 3; k++) {
            m[k] = 0.5 * (a[k] + b[k]);
            len += (b[k] - a[k]) * (b[k] - a[k]);
        }
        len = sqrt(len);
        near_faults(s, q, m, FM_LOSS_NEAR);
        if (q->nomem)
            return FM_ERR_NOMEM;
        for (size_t i = 0; i < q->n; i++) {
            int32_t g = q->near[i].fault;
            if (q->near[i].d2 <= FM_LOSS_TOUCH * FM_LOSS_TOUCH || shared_near(s, f, g, a, b, H))
                continue;
            if (add_gap(o, g, len))
                return FM_ERR_NOMEM;
        }
    }
    if (o->ngaps)
        qsort(o->gaps, o->ngaps, sizeof *o->gaps, cmp_gap);
    for (size_t i = 0; i < o->ngaps; i++)
        o->m.gap += o->gaps[i].length;
    return FM_OK;
}

/* One sample of the original: its area w counted, and whether the output
 * misses it (farther than H/2 from its own fault), and whether it is away
 * from every other fault too (farther than D). */
static void sample(const ck_set *s, int32_t f, const fm_closest_tree *own, const double p[3],
                   double w, double H, double D, int32_t *hint, near_query *q, fm_loss_fault *m)
{
    if (!(p[2] <= s->in->zcut[f]))
        return;
    m->orig_area += w;
    if (fm_closest_within(own, p, 0.5 * H, hint))
        return;
    m->missing_area += w;
    q->stop_at_first = 1;
    near_faults(s, q, p, D);
    q->stop_at_first = 0;
    if (!q->n)
        m->missing_away += w;
}

typedef struct sampler {
    const ck_set *s;
    int32_t f;
    const fm_closest_tree *own;
    double H, D, zcut;
    int32_t hint;
    near_query *q;
    fm_loss_fault *m;
} sampler;

/* Triangle a, b, c split in four `depth` times, its leaves sampled at
 * their centroids (the k^2 equal sub-triangles of a k = 2^depth grid).
 * A part whose every point is known to lie within H/2 of the output (its
 * centroid closer than H/2 less the part's reach from it) and below zcut
 * counts whole without its leaves: the sum is the leaves' to the last
 * bit of area, at a fraction of the queries. */
static void sample_part(sampler *sp, const double *a, const double *b, const double *c, int depth)
{
    double g[3], reach = 0, ztop = fmax(a[2], fmax(b[2], c[2]));
    for (int k = 0; k < 3; k++)
        g[k] = (a[k] + b[k] + c[k]) / 3;
    reach = sqrt(fmax((a[0] - g[0]) * (a[0] - g[0]) + (a[1] - g[1]) * (a[1] - g[1]) +
                          (a[2] - g[2]) * (a[2] - g[2]),
                      fmax((b[0] - g[0]) * (b[0] - g[0]) + (b[1] - g[1]) * (b[1] - g[1]) +
                               (b[2] - g[2]) * (b[2] - g[2]),
                           (c[0] - g[0]) * (c[0] - g[0]) + (c[1] - g[1]) * (c[1] - g[1]) +
                               (c[2] - g[2]) * (c[2] - g[2]))));
    if (depth > 0 && ztop <= sp->zcut && reach < 0.5 * sp->H &&
        fm_closest_within(sp->own, g, 0.5 * sp->H - reach, &sp->hint)) {
        double w = fm_triangle_area(a, b, c);
        sp->m->orig_area += w;
        return;
    }
    if (depth == 0) {
        sample(sp->s, sp->f, sp->own, g, fm_triangle_area(a, b, c), sp->H, sp->D, &sp->hint,
               sp->q, sp->m);
        return;
    }
    double ab[3], bc[3], ca[3];
    for (int k = 0; k < 3; k++) {
        ab[k] = 0.5 * (a[k] + b[k]);
        bc[k] = 0.5 * (b[k] + c[k]);
        ca[k] = 0.5 * (c[k] + a[k]);
    }
    sample_part(sp, a, ab, ca, depth - 1);
    sample_part(sp, ab, b, bc, depth - 1);
    sample_part(sp, ca, bc, c, depth - 1);
    sample_part(sp, ab, bc, ca, depth - 1);
}

static void missing(const ck_set *s, int32_t f, const fm_closest_tree *own, near_query *q,
                    fm_loss_fault *m)
{
    const fm_mesh *o = s->in->orig[f];
    const double *X = fm_mesh_vertices(o);
    const int32_t *T = fm_mesh_triangles(o);
    size_t nv = fm_mesh_nvertices(o), nt = fm_mesh_ntriangles(o);
    sampler sp = {s, f, own, s->in->size[f], s->in->join[f], s->in->zcut[f], -1, q, m};
    for (size_t t = 0; t < nt; t++) {
        if (T[3 * t] < 0 || T[3 * t + 1] < 0 || T[3 * t + 2] < 0 || (size_t)T[3 * t] >= nv ||
            (size_t)T[3 * t + 1] >= nv || (size_t)T[3 * t + 2] >= nv)
            continue;
        const double *A = X + 3 * T[3 * t], *B = X + 3 * T[3 * t + 1], *C = X + 3 * T[3 * t + 2];
        if (fmin(A[2], fmin(B[2], C[2])) > sp.zcut)
            continue;
        /* leaves at most H/4 long */
        double L = fmax(fm_segment_distance3(A, B, B),
                        fmax(fm_segment_distance3(B, C, C), fm_segment_distance3(C, A, A)));
        int depth = 0;
        while (depth < MAX_DEPTH && L > 0.25 * sp.H) {
            L *= 0.5;
            depth++;
        }
        sample_part(&sp, A, B, C, depth);
    }
}

static int cmp_i32(const void *a, const void *b)
{
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

/* A sheet's share of the original (part: its triangles), the outline of
 * that share and a tree of it. */
typedef struct sheet_part {
    const fm_mesh *m; /* o itself, or copy */
    fm_mesh *copy;
    fm_closest_tree *tree;
    uint64_t *E;
    size_t ne;
} sheet_part;

static void part_free(sheet_part *p)
{
    fm_closest_tree_destroy(p->tree);
    fm_mesh_destroy(p->copy);
    free(p->E);
}

/* The original's triangles part[0 .. n-1] as a mesh of their own (all of
 * o's vertices, so that seams between parts are outline edges of each);
 * part NULL: the whole of o, not copied. */
static fm_status part_build(const fm_mesh *o, const int32_t *part, size_t n, sheet_part *p)
{
    memset(p, 0, sizeof *p);
    int ok = 1;
    p->m = o;
    if (part) {
        const double *X = fm_mesh_vertices(o);
        const int32_t *T = fm_mesh_triangles(o);
        size_t nv = fm_mesh_nvertices(o);
        p->m = p->copy = fm_mesh_create();
        ok = p->copy && fm_mesh_reserve(p->copy, nv, n) == FM_OK;
        for (size_t v = 0; ok && v < nv; v++)
            ok = fm_mesh_add_vertex(p->copy, X[3 * v], X[3 * v + 1], X[3 * v + 2]) >= 0;
        for (size_t i = 0; ok && i < n; i++)
            ok = fm_mesh_add_triangle(p->copy, T[3 * part[i]], T[3 * part[i] + 1],
                                      T[3 * part[i] + 2], 0) >= 0;
    }
    if (ok)
        p->tree = fm_closest_tree_create_quick(p->m, NULL);
    if (!ok || !p->tree || ck_outline_edges(p->m, &p->E, &p->ne) != FM_OK) {
        part_free(p);
        return FM_ERR_NOMEM;
    }
    return FM_OK;
}

/* The output's nodes over the original's inside (sub: the fault's own
 * mesh, its nodes in the set's order, own its tree, sheet[i] the sheet of
 * its triangle i). A fault of several sheets is measured sheet by sheet
 * against the share of its original nearest that sheet's output: a gap a
 * sheet closes over its own extension may pass beside another strand of
 * the fault, whose inside is then the nearest original point, though no
 * node of any inside moved (the design note's I2: fill nodes are measured
 * from the outline they extend). A node on several sheets counts only
 * when it is over the inside of each. */
static fm_status moved(const ck_set *s, int32_t f, const fm_mesh *sub,
                       const fm_closest_tree *own, const int32_t *sheet, fm_loss_fault *m)
{
    const fm_mesh *o = s->in->orig[f];
    const double *X = fm_mesh_vertices(sub);
    const int32_t *ST = fm_mesh_triangles(sub);
    size_t nv = fm_mesh_nvertices(sub), nt = fm_mesh_ntriangles(sub);
    size_t no = fm_mesh_ntriangles(o);
    int32_t nsh = 0;
    for (size_t i = 0; i < nt; i++)
        nsh = sheet[i] + 1 > nsh ? sheet[i] + 1 : nsh;
    /* per original triangle: the sheet of the output nearest its centroid
     * (one sheet: all of it); then the triangles grouped by sheet */
    int32_t *osh = malloc((no + 1) * sizeof *osh);
    int32_t *order = malloc((no + 1) * sizeof *order);
    size_t *first = calloc((size_t)nsh + 2, sizeof *first);
    double *best = malloc((nv + 1) * sizeof *best);
    unsigned char *out = calloc(nv + 1, 1);
    int32_t *stamp = malloc((nv + 1) * sizeof *stamp);
    fm_status st = osh && order && first && best && out && stamp ? FM_OK : FM_ERR_NOMEM;
    const double *OX = fm_mesh_vertices(o);
    const int32_t *OT = fm_mesh_triangles(o);
    for (size_t t = 0; st == FM_OK && t < no; t++) {
        osh[t] = 0;
        if (nsh < 2)
            continue;
        double c[3];
        for (int k = 0; k < 3; k++)
            c[k] = (OX[3 * OT[3 * t] + k] + OX[3 * OT[3 * t + 1] + k] + OX[3 * OT[3 * t + 2] + k]) / 3;
        fm_closest_hit hit;
        if (fm_closest_query(own, c, INFINITY, &hit))
            osh[t] = sheet[hit.triangle];
    }
    if (st == FM_OK) {
        for (size_t t = 0; t < no; t++)
            first[osh[t] + 1]++;
        for (int32_t k = 0; k < nsh; k++)
            first[k + 1] += first[k];
        size_t *at = calloc((size_t)nsh + 1, sizeof *at);
        if (!at)
            st = FM_ERR_NOMEM;
        for (size_t t = 0; at && t < no; t++)
            order[first[osh[t]] + at[osh[t]]++] = (int32_t)t;
        free(at);
    }
    for (size_t v = 0; st == FM_OK && v < nv; v++) {
        best[v] = INFINITY;
        stamp[v] = -1;
    }
    /* the largest distance counted so far (one sheet: a node's own) */
    double counted = 0;
    for (int32_t k = 0; st == FM_OK && k < nsh; k++) {
        sheet_part p;
        /* one sheet, or one nearest to none of the original: the whole of it */
        size_t n = first[k + 1] - first[k];
        int whole = nsh < 2 || n == 0;
        st = part_build(o, whole ? NULL : order + first[k], n, &p);
        for (size_t i = 0; st == FM_OK && i < nt; i++) {
            if (sheet[i] != k)
                continue;
            for (int c = 0; c < 3; c++) {
                int32_t v = ST[3 * i + c];
                if (stamp[v] == k)
                    continue;
                stamp[v] = k;
                fm_closest_hit hit;
                if (out[v] || !fm_closest_query(p.tree, X + 3 * v, INFINITY, &hit))
                    continue;
                /* with one sheet, a node nearer than one counted and within
                 * the tolerance changes no figure: its outline (measured by
                 * brute force) is not needed */
                if (nsh < 2 && hit.dist < counted && hit.dist <= FM_FIDELITY_TOL)
                    continue;
                /* within a metre, or over an outline it may extend */
                if (hit.dist <= FM_LOSS_TOUCH ||
                    ck_outline_distance(p.m, p.E, p.ne, hit.foot) <= FM_LOSS_TOUCH) {
                    out[v] = 1;
                } else {
                    best[v] = fmin(best[v], hit.dist);
                    counted = fmax(counted, best[v]);
                }
            }
        }
        if (st == FM_OK)
            part_free(&p);
    }
    for (size_t v = 0; st == FM_OK && v < nv; v++) {
        if (out[v] || !(best[v] < INFINITY))
            continue;
        if (best[v] > FM_FIDELITY_TOL)
            m->moved_over++;
        if (best[v] > m->moved_max) {
            m->moved_max = best[v];
            memcpy(m->moved_at, X + 3 * v, sizeof m->moved_at);
        }
    }
    free(osh);
    free(order);
    free(first);
    free(best);
    free(out);
    free(stamp);
    return st;
}

/* Fault f's triangles as a mesh of their own: a tree of it costs the
 * fault's size, where one of a part of the whole set would walk all of the
 * set's vertices. */
static fm_mesh *fault_mesh(const ck_set *s, int32_t f)
{
    size_t n = s->tri_first[f + 1] - s->tri_first[f];
    const int32_t *T = fm_mesh_triangles(s->in->set);
    const double *X = fm_mesh_vertices(s->in->set);
    int32_t *v = malloc((3 * n + 1) * sizeof *v);
    fm_mesh *m = v ? fm_mesh_create() : NULL;
    if (!m) {
        free(v);
        return NULL;
    }
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++)
            v[3 * i + k] = T[3 * s->tri[s->tri_first[f] + i] + k];
    qsort(v, 3 * n, sizeof *v, cmp_i32);
    size_t nv = 0;
    for (size_t i = 0; i < 3 * n; i++)
        if (!nv || v[i] != v[nv - 1])
            v[nv++] = v[i];
    int ok = fm_mesh_reserve(m, nv, n) == FM_OK;
    for (size_t i = 0; ok && i < nv; i++)
        ok = fm_mesh_add_vertex(m, X[3 * v[i]], X[3 * v[i] + 1], X[3 * v[i] + 2]) >= 0;
    for (size_t i = 0; ok && i < n; i++) {
        int32_t c[3];
        for (int k = 0; k < 3; k++) {
            int32_t key = T[3 * s->tri[s->tri_first[f] + i] + k];
            c[k] = (int32_t)((const int32_t *)bsearch(&key, v, nv, sizeof *v, cmp_i32) - v);
        }
        ok = fm_mesh_add_triangle(m, c[0], c[1], c[2], f) >= 0;
    }
    free(v);
    if (!ok) {
        fm_mesh_destroy(m);
        return NULL;
    }
    return m;
}

void ck_measure_fault(const ck_set *s, size_t fi, ck_fault_out *o)
{
    int32_t f = (int32_t)fi;
    near_query q = {s->in->set, f, {0, 0, 0}, 0, 0, NULL, 0, 0, 0};
    size_t n = s->tri_first[f + 1] - s->tri_first[f];
    o->st = gaps(s, f, s->in->size[f], &q, o);
    if (o->st == FM_OK && s->in->orig && s->in->orig[f]) {
        fm_mesh *sub = fault_mesh(s, f);
        fm_closest_tree *own = sub ? fm_closest_tree_create_quick(sub, NULL) : NULL;
        int32_t *sheet = malloc((n + 1) * sizeof *sheet);
        for (size_t i = 0; sheet && i < n; i++)
            sheet[i] = s->in->sheet ? s->in->sheet[s->tri[s->tri_first[f] + i]] : 0;
        if (!own || !sheet)
            o->st = FM_ERR_NOMEM;
        else {
            missing(s, f, own, &q, &o->m);
            o->st = q.nomem ? FM_ERR_NOMEM : n ? moved(s, f, sub, own, sheet, &o->m) : FM_OK;
        }
        free(sheet);
        fm_closest_tree_destroy(own);
        fm_mesh_destroy(sub);
    }
    free(q.near);
}
