/* Building the CDT: input checks, the Delaunay triangulation of the points
 * inside a super triangle (inserted in Morton order so that walks stay
 * short), segment recovery, and the domain: by parity flood fill for
 * loops (fm_cdt_create), the arrangement's faces for a graph
 * (fm_cdt_create_graph, cdt_graph.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cdt_internal.h"

typedef struct sort_key {
    uint64_t key;
    int32_t a, b;
} sort_key;

static int by_key(const void *x, const void *y)
{
    const sort_key *p = x, *q = y;
    if (p->key != q->key)
        return p->key < q->key ? -1 : 1;
    if (p->a != q->a)
        return p->a < q->a ? -1 : 1;
    return (p->b > q->b) - (p->b < q->b);
}

static int by_point(const void *x, const void *y)
{
    const double *p = *(const double *const *)x, *q = *(const double *const *)y;
    if (p[0] != q[0])
        return p[0] < q[0] ? -1 : 1;
    if (p[1] != q[1])
        return p[1] < q[1] ? -1 : 1;
    return (p > q) - (p < q);
}

static uint64_t spread(uint32_t x)
{
    uint64_t v = x;
    v = (v | (v << 16)) & 0x0000FFFF0000FFFFull;
    v = (v | (v << 8)) & 0x00FF00FF00FF00FFull;
    v = (v | (v << 4)) & 0x0F0F0F0F0F0F0F0Full;
    v = (v | (v << 2)) & 0x3333333333333333ull;
    v = (v | (v << 1)) & 0x5555555555555555ull;
    return v;
}

static fm_status check_input(const double *uv, size_t np, const int32_t *seg, size_t nseg,
                             int loops, fm_error *err)
{
    for (size_t i = 0; i < np; i++)
        if (!isfinite(uv[2 * i]) || !isfinite(uv[2 * i + 1]))
            return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "point %zu is not finite", i);
    fm_status st = FM_OK;
    if (np > 1) {
        const double **ord = malloc(np * sizeof *ord);
        if (!ord)
            return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
        for (size_t i = 0; i < np; i++)
            ord[i] = uv + 2 * i;
        qsort(ord, np, sizeof *ord, by_point);
        for (size_t i = 1; i < np && st == FM_OK; i++)
            if (ord[i][0] == ord[i - 1][0] && ord[i][1] == ord[i - 1][1])
                st = fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                                  "points %td and %td coincide at (%.17g, %.17g)",
                                  (ord[i - 1] - uv) / 2, (ord[i] - uv) / 2, ord[i][0], ord[i][1]);
        free(ord);
        if (st != FM_OK)
            return st;
    }
    for (size_t k = 0; k < nseg; k++) {
        int32_t a = seg[2 * k], b = seg[2 * k + 1];
        if (a < 0 || b < 0 || (size_t)a >= np || (size_t)b >= np)
            return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                                "segment %zu: point index out of range (%d, %d; %zu points)", k,
                                a, b, np);
        if (a == b)
            return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                                "segment %zu joins point %d to itself", k, a);
    }
    if (nseg == 0)
        return FM_OK;
    sort_key *keys = malloc(nseg * sizeof *keys);
    int32_t *deg = calloc(np, sizeof *deg);
    if (!keys || !deg) {
        free(keys);
        free(deg);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    for (size_t k = 0; k < nseg; k++) {
        int32_t a = seg[2 * k], b = seg[2 * k + 1];
        keys[k].key = ((uint64_t)(uint32_t)(a < b ? a : b) << 32) | (uint32_t)(a < b ? b : a);
        keys[k].a = (int32_t)k;
        keys[k].b = 0;
        deg[a]++;
        deg[b]++;
    }
    qsort(keys, nseg, sizeof *keys, by_key);
    for (size_t k = 1; k < nseg && st == FM_OK; k++)
        if (keys[k].key == keys[k - 1].key)
            st = fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                              "segments %d and %d join the same points (%d, %d)", keys[k - 1].a,
                              keys[k].a, seg[2 * keys[k].a], seg[2 * keys[k].a + 1]);
    for (size_t i = 0; i < np && st == FM_OK && loops; i++)
        if (deg[i] % 2)
            st = fm_error_set(err, FM_ERR_TOPOLOGY, NULL, 0,
                              "point %zu ends %d segments: the segments do not form closed loops",
                              i, deg[i]);
    free(keys);
    free(deg);
    return st;
}

static fm_status build_delaunay(struct fm_cdt *t, fm_error *err)
{
    size_t n = t->ninput;
    double lo[2] = {0, 0}, hi[2] = {0, 0};
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 2; c++) {
            double x = t->xy[2 * (i + CDT_NSUPER) + c];
            if (i == 0 || x < lo[c])
                lo[c] = x;
            if (i == 0 || x > hi[c])
                hi[c] = x;
        }
    double cx = 0.5 * (lo[0] + hi[0]), cy = 0.5 * (lo[1] + hi[1]);
    double r = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(r > 0))
        r = fmax(1.0, fabs(cx) + fabs(cy));
    /* Far enough that the super vertices never matter inside the domain,
     * which segments enclose; the predicates are exact at any distance. */
    double sx[3] = {cx - 40 * r, cx + 40 * r, cx}, sy[3] = {cy - 30 * r, cy - 30 * r, cy + 40 * r};
    for (int k = 0; k < 3; k++) {
        t->xy[2 * k] = sx[k];
        t->xy[2 * k + 1] = sy[k];
        t->pseg[k] = -1;
    }
    int32_t t0 = cdt_new_triangle(t);
    if (t0 < 0)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    for (int k = 0; k < 3; k++) {
        t->tv[3 * t0 + k] = k;
        t->vtri[k] = t0;
    }
    t->last = t0;
    sort_key *ord = malloc((n ? n : 1) * sizeof *ord);
    if (!ord)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    double sxr = hi[0] > lo[0] ? 65535.0 / (hi[0] - lo[0]) : 0;
    double syr = hi[1] > lo[1] ? 65535.0 / (hi[1] - lo[1]) : 0;
    for (size_t i = 0; i < n; i++) {
        const double *p = t->xy + 2 * (i + CDT_NSUPER);
        uint32_t qx = (uint32_t)((p[0] - lo[0]) * sxr), qy = (uint32_t)((p[1] - lo[1]) * syr);
        ord[i].key = spread(qx) | (spread(qy) << 1);
        ord[i].a = (int32_t)(i + CDT_NSUPER);
        ord[i].b = 0;
    }
    qsort(ord, n, sizeof *ord, by_key);
    fm_status st = FM_OK;
    for (size_t i = 0; i < n && st == FM_OK; i++) {
        int32_t v = ord[i].a;
        const double *q = cdt_p(t, v);
        int32_t tri = cdt_locate(t, q), bad;
        if (tri < 0)
            st = fm_error_set(err, FM_ERR_NUMERIC, NULL, 0, "point %d: location failed",
                              v - CDT_NSUPER);
        else {
            cdt_cavity_result cr = cdt_cavity(t, q, &tri, 1, -1, &bad);
            if (cr == CDT_CAVITY_NOMEM || (cr == CDT_CAVITY_OK && cdt_commit(t, v, -1, -1)))
                st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
            else if (cr != CDT_CAVITY_OK)
                st = fm_error_set(err, FM_ERR_NUMERIC, NULL, 0,
                                  "point %d: insertion cavity is not star-shaped",
                                  v - CDT_NSUPER);
        }
    }
    free(ord);
    return st;
}

/* Outside is what touches the super triangle; every segment crossed
 * toggles inside and outside. */
static fm_status flood_domain(struct fm_cdt *t, fm_error *err)
{
    int32_t *queue = malloc((t->nt ? t->nt : 1) * sizeof *queue);
    if (!queue)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    uint8_t *seen = calloc(t->nt ? t->nt : 1, 1);
    if (!seen) {
        free(queue);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    size_t head = 0, tail = 0;
    for (size_t k = 0; k < t->nt; k++)
        if (t->region[k] != CDT_DEAD && cdt_has_super(t, (int32_t)k)) {
            t->region[k] = 0;
            seen[k] = 1;
            queue[tail++] = (int32_t)k;
        }
    while (head < tail) {
        int32_t tri = queue[head++];
        for (int i = 0; i < 3; i++) {
            int32_t n = t->tn[3 * tri + i];
            if (n < 0 || seen[n / 3])
                continue;
            seen[n / 3] = 1;
            t->region[n / 3] = (uint8_t)(t->region[tri] ^ (t->tc[3 * tri + i] >= 0));
            queue[tail++] = n / 3;
        }
    }
    free(queue);
    free(seen);
    return FM_OK;
}

/* The two ways in differ only in the parity check of the input and in how
 * the domain is found; loops keep their own path (no hull, no pieces) so
 * that their results stay exactly what they were. */
static fm_status create(const double *uv, size_t npoints, const int32_t *seg,
                        const int32_t *seg_id, size_t nseg, int graph, fm_cdt **out,
                        fm_error *err)
{
    const char *fn = graph ? "fm_cdt_create_graph" : "fm_cdt_create";
    if (!out || (npoints && !uv) || (nseg && !seg))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "%s: NULL argument", fn);
    *out = NULL;
    if (npoints > (size_t)INT32_MAX / 8 || nseg > (size_t)INT32_MAX / 8)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "%s: too many points or segments", fn);
    fm_status st = check_input(uv, npoints, seg, nseg, !graph, err);
    if (st != FM_OK)
        return st;
    struct fm_cdt *t = calloc(1, sizeof *t);
    if (!t)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    t->last = -1;
    t->ninput = npoints;
    t->nseg = nseg;
    t->nuser = nseg;
    t->seg = malloc((nseg ? 2 * nseg : 1) * sizeof *t->seg);
    t->sid = malloc((nseg ? nseg : 1) * sizeof *t->sid);
    if (!t->seg || !t->sid || cdt_reserve_points(t, npoints + CDT_NSUPER) ||
        cdt_reserve_triangles(t, 2 * npoints + 8)) {
        fm_cdt_destroy(t);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    t->np = npoints + CDT_NSUPER;
    for (size_t i = 0; i < t->np; i++) {
        t->pseg[i] = -1;
        t->vtri[i] = -1;
        t->vmark[i] = -1;
    }
    if (npoints)
        memcpy(t->xy + 2 * CDT_NSUPER, uv, 2 * npoints * sizeof *uv);
    for (size_t k = 0; k < nseg; k++) {
        t->seg[2 * k] = seg[2 * k] + CDT_NSUPER;
        t->seg[2 * k + 1] = seg[2 * k + 1] + CDT_NSUPER;
        t->sid[k] = seg_id ? seg_id[k] : (int32_t)k;
        for (int s = 0; s < 2; s++)
            if (t->pseg[t->seg[2 * k + s]] < 0)
                t->pseg[t->seg[2 * k + s]] = (int32_t)k;
    }
    st = build_delaunay(t, err);
    for (size_t k = 0; k < nseg && st == FM_OK; k++)
        st = cdt_recover_segment(t, (int32_t)k, 0, err);
    if (st == FM_OK)
        st = graph ? cdt_graph_build(t, err) : flood_domain(t, err);
    if (st == FM_OK && cdt_build_output(t))
        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    if (st != FM_OK) {
        fm_cdt_destroy(t);
        return st;
    }
    *out = t;
    return FM_OK;
}

fm_status fm_cdt_create(const double *uv, size_t npoints, const int32_t *seg,
                        const int32_t *seg_id, size_t nseg, fm_cdt **out, fm_error *err)
{
    return create(uv, npoints, seg, seg_id, nseg, 0, out, err);
}

fm_status fm_cdt_create_graph(const double *uv, size_t npoints, const int32_t *seg,
                              const int32_t *seg_id, size_t nseg, fm_cdt **out, fm_error *err)
{
    return create(uv, npoints, seg, seg_id, nseg, 1, out, err);
}

void fm_cdt_destroy(fm_cdt *t)
{
    if (!t)
        return;
    void *arrs[] = {t->xy,    t->pseg,      t->vtri,     t->vmark,   t->tv,     t->tn,
                    t->tc,    t->region,    t->stamp,    t->tmark,   t->freel,  t->seg,
                    t->sid,   t->apex,      t->cav,      t->stack,   t->bnd,    t->bnde,
                    t->newt,  t->pairs,     t->out_tri,  t->out_pseg, t->out_edges, t->out_eid,
                    t->out_eint, t->sorig};
    for (size_t i = 0; i < sizeof arrs / sizeof arrs[0]; i++)
        free(arrs[i]);
    cdt_graph_free(t->graph);
    free(t);
}

size_t fm_cdt_ninput(const fm_cdt *t) { return t->ninput; }
size_t fm_cdt_npoints(const fm_cdt *t) { return t->np - CDT_NSUPER; }
const double *fm_cdt_points(const fm_cdt *t) { return t->xy + 2 * CDT_NSUPER; }
size_t fm_cdt_ntriangles(const fm_cdt *t) { return t->out_nt; }
const int32_t *fm_cdt_triangles(const fm_cdt *t) { return t->out_tri; }
const int32_t *fm_cdt_point_segment(const fm_cdt *t) { return t->out_pseg; }
size_t fm_cdt_nedges(const fm_cdt *t) { return t->out_ne; }
const int32_t *fm_cdt_edges(const fm_cdt *t) { return t->out_edges; }
const int32_t *fm_cdt_edge_ids(const fm_cdt *t) { return t->out_eid; }
const unsigned char *fm_cdt_edge_interior(const fm_cdt *t) { return t->out_eint; }
void fm_cdt_refine_get_stats(const fm_cdt *t, fm_cdt_refine_stats *st) { *st = t->stats; }
