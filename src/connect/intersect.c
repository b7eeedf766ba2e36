/* Intersection curves of two sheets (see fm_connect.h): exact mesh-mesh
 * intersection of fine samples, chained, solved onto both surfaces, cut
 * to the grown regions, resampled and classified. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "connect_internal.h"
#include "connect_solve.h"
#include "fm_sort.h"

typedef struct curve {
    fm_connect_curve_info info;
    double *xyz, *uv[2], *sd[2], *flap[2], *angle;
    unsigned char *inside[2];
} curve;

struct fm_connect_curves {
    curve *c;
    size_t n, cap;
};

static void curve_free(curve *c)
{
    free(c->xyz);
    free(c->angle);
    for (int s = 0; s < 2; s++) {
        free(c->uv[s]);
        free(c->sd[s]);
        free(c->flap[s]);
        free(c->inside[s]);
    }
}

void fm_connect_curves_destroy(fm_connect_curves *c)
{
    if (!c)
        return;
    for (size_t i = 0; i < c->n; i++)
        curve_free(&c->c[i]);
    free(c->c);
    free(c);
}

size_t fm_connect_curves_count(const fm_connect_curves *c) { return c ? c->n : 0; }
const fm_connect_curve_info *fm_connect_curve_get_info(const fm_connect_curves *c, size_t i)
{
    return &c->c[i].info;
}
const double *fm_connect_curve_points(const fm_connect_curves *c, size_t i, size_t *n)
{
    if (n)
        *n = c->c[i].info.npoints;
    return c->c[i].xyz;
}
const double *fm_connect_curve_params(const fm_connect_curves *c, size_t i, int side)
{
    return c->c[i].uv[side != 0];
}
const unsigned char *fm_connect_curve_inside(const fm_connect_curves *c, size_t i, int side)
{
    return c->c[i].inside[side != 0];
}
const double *fm_connect_curve_outline_distance(const fm_connect_curves *c, size_t i, int side)
{
    return c->c[i].sd[side != 0];
}
const double *fm_connect_curve_flap(const fm_connect_curves *c, size_t i, int side)
{
    return c->c[i].flap[side != 0];
}
const double *fm_connect_curve_angles(const fm_connect_curves *c, size_t i)
{
    return c->c[i].angle;
}

/* ---- A growable list of curve points: x = (uA, vA, uB, vB) ---- */

typedef struct plist {
    double *x;   /* 4 per point */
    double *p;   /* 3 per point: position (raw, then solved) */
    size_t n, cap;
} plist;

static int plist_push(plist *l, const double x[4], const double p[3])
{
    if (l->n == l->cap) {
        size_t cap = l->cap ? 2 * l->cap : 64;
        double *nx = realloc(l->x, 4 * cap * sizeof *nx);
        if (!nx)
            return -1;
        l->x = nx;
        double *np = realloc(l->p, 3 * cap * sizeof *np);
        if (!np)
            return -1;
        l->p = np;
        l->cap = cap;
    }
    memcpy(l->x + 4 * l->n, x, 4 * sizeof *x);
    memcpy(l->p + 3 * l->n, p, 3 * sizeof *p);
    l->n++;
    return 0;
}

static void plist_free(plist *l)
{
    free(l->x);
    free(l->p);
    memset(l, 0, sizeof *l);
}

static double dist3(const double *a, const double *b)
{
    double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* ---- The intersection graph of the two zone meshes ---- */

typedef struct graph {
    uint64_t *key;       /* sorted node keys: kind << 62 | edge << 31 | triangle */
    size_t nnode;
    int32_t (*seg)[2];   /* node pairs */
    size_t nseg, cap;
    size_t *start;       /* CSR adjacency: segments per node */
    int32_t *adj;
} graph;

#define KEY(kind, e, t) (((uint64_t)(kind) << 62) | ((uint64_t)(e) << 31) | (uint64_t)(t))

typedef struct ctx {
    const cn_sheet *sa, *sb;
    const cn_zone *za, *zb;
    const double *xb;    /* B's vertices, shifted (see build_graph) */
    uint64_t (*raw)[2];
    size_t nraw, cap;
} ctx;

static void tri_points(const int32_t *tri, const double *xyz, size_t t, const double *P[3],
                       int64_t id[3], int64_t off)
{
    for (int k = 0; k < 3; k++) {
        int32_t v = tri[3 * t + (size_t)k];
        P[k] = xyz + 3 * (size_t)v;
        id[k] = off + v;
    }
}

/* Intersection points of triangle ta (of A) and tb (of B), as keys. */
static int pair_points(const ctx *c, size_t ta, size_t tb, uint64_t keys[6])
{
    const double *PA[3], *PB[3];
    int64_t IA[3], IB[3], offb = (int64_t)c->za->nv;
    tri_points(c->za->tri, c->za->xyz, ta, PA, IA, 0);
    tri_points(c->zb->tri, c->xb, tb, PB, IB, offb);
    int n = 0;
    for (int k = 0; k < 3; k++) {
        int32_t e = c->za->tedge[3 * ta + (size_t)k];
        int32_t p = c->za->ev[2 * e], q = c->za->ev[2 * e + 1];
        if (cn_edge_crosses_triangle(c->za->xyz + 3 * p, c->za->xyz + 3 * q, p, q, PB, IB))
            keys[n++] = KEY(0, e, tb);
    }
    for (int k = 0; k < 3; k++) {
        int32_t e = c->zb->tedge[3 * tb + (size_t)k];
        int32_t p = c->zb->ev[2 * e], q = c->zb->ev[2 * e + 1];
        if (cn_edge_crosses_triangle(c->xb + 3 * p, c->xb + 3 * q, offb + p, offb + q,
                                     PA, IA))
            keys[n++] = KEY(1, e, ta);
    }
    return n;
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

static int32_t find_key(const graph *g, uint64_t k)
{
    size_t lo = 0, hi = g->nnode;
    while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        if (g->key[mid] < k)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < g->nnode && g->key[lo] == k ? (int32_t)lo : -1;
}

static void graph_free(graph *g)
{
    free(g->key);
    free(g->seg);
    free(g->start);
    free(g->adj);
    memset(g, 0, sizeof *g);
}

static fm_status build_graph(const cn_zone *za, const cn_zone *zb, graph *g, fm_error *err)
{
    memset(g, 0, sizeof *g);
    ctx c = {0};
    c.za = za;
    c.zb = zb;
    /* Fitted planes and lattices put many vertices of one mesh exactly on
     * the planes and lines of the other (coordinates snap to the same
     * doubles), and the tie rules alone do not keep such a pile of
     * degeneracies consistent. B's vertices are therefore moved by a fixed
     * vector of a few ulps of the coordinates (micrometres in UTM) along no
     * axis or lattice direction for the topological decisions only: exact
     * zeros then need a coincidence of general-position coordinates. */
    double big = 0;
    for (size_t v = 0; v < 3 * zb->nv; v++)
        big = fmax(big, fabs(zb->xyz[v]));
    double scale = 1e-12 * big + 1e-9;
    const double shift[3] = {0.7548776662466927 * scale, 0.5698402909980532 * scale,
                             0.4301597090019468 * scale};
    double *xb = malloc((3 * zb->nv + 1) * sizeof *xb);
    fm_mesh *mb = fm_mesh_create();
    if (!xb || !mb || fm_mesh_reserve(mb, zb->nv, zb->nt) != FM_OK) {
        free(xb);
        fm_mesh_destroy(mb);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    }
    for (size_t v = 0; v < zb->nv; v++) {
        for (int k = 0; k < 3; k++)
            xb[3 * v + (size_t)k] = zb->xyz[3 * v + (size_t)k] + shift[k];
        fm_mesh_add_vertex(mb, xb[3 * v], xb[3 * v + 1], xb[3 * v + 2]);
    }
    c.xb = xb;
    for (size_t t = 0; t < zb->nt; t++)
        fm_mesh_add_triangle(mb, zb->tri[3 * t], zb->tri[3 * t + 1], zb->tri[3 * t + 2], 0);
    fm_closest_tree *tree = fm_closest_tree_create_quick(mb, err);
    fm_mesh_destroy(mb);
    if (!tree) {
        free(xb);
        return err ? err->code : FM_ERR_NOMEM;
    }
    fm_status st = FM_OK;
    for (size_t ta = 0; ta < za->nt && st == FM_OK; ta++) {
        double lo[3], hi[3];
        for (int k = 0; k < 3; k++) {
            lo[k] = INFINITY;
            hi[k] = -INFINITY;
            for (int j = 0; j < 3; j++) {
                double x = za->xyz[3 * (size_t)za->tri[3 * ta + (size_t)j] + (size_t)k];
                lo[k] = fmin(lo[k], x);
                hi[k] = fmax(hi[k], x);
            }
        }
        int32_t *cand = NULL;
        size_t nc = 0;
        st = fm_closest_tree_box_collect(tree, lo, hi, &cand, &nc, err);
        for (size_t i = 0; i < nc && st == FM_OK; i++) {
            uint64_t keys[6];
            if (pair_points(&c, ta, (size_t)cand[i], keys) != 2)
                continue; /* 0, or an inconsistent degenerate case: skipped */
            if (c.nraw == c.cap) {
                size_t cap = c.cap ? 2 * c.cap : 256;
                uint64_t(*nr)[2] = realloc(c.raw, cap * sizeof *nr);
                if (!nr) {
                    st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
                    break;
                }
                c.raw = nr;
                c.cap = cap;
            }
            c.raw[c.nraw][0] = keys[0];
            c.raw[c.nraw][1] = keys[1];
            c.nraw++;
        }
        free(cand);
    }
    fm_closest_tree_destroy(tree);
    free(xb);
    if (st != FM_OK) {
        free(c.raw);
        return st;
    }
    /* nodes */
    g->key = malloc((2 * c.nraw + 1) * sizeof *g->key);
    g->seg = malloc((c.nraw + 1) * sizeof *g->seg);
    if (!g->key || !g->seg) {
        free(c.raw);
        graph_free(g);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    }
    for (size_t i = 0; i < c.nraw; i++) {
        g->key[2 * i] = c.raw[i][0];
        g->key[2 * i + 1] = c.raw[i][1];
    }
    qsort(g->key, 2 * c.nraw, sizeof *g->key, cmp_u64);
    for (size_t i = 0; i < 2 * c.nraw; i++)
        if (g->nnode == 0 || g->key[g->nnode - 1] != g->key[i])
            g->key[g->nnode++] = g->key[i];
    for (size_t i = 0; i < c.nraw; i++) {
        g->seg[i][0] = find_key(g, c.raw[i][0]);
        g->seg[i][1] = find_key(g, c.raw[i][1]);
    }
    g->nseg = c.nraw;
    free(c.raw);
    g->start = calloc(g->nnode + 1, sizeof *g->start);
    g->adj = malloc((2 * g->nseg + 1) * sizeof *g->adj);
    if (!g->start || !g->adj) {
        graph_free(g);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    }
    for (size_t s = 0; s < g->nseg; s++) {
        g->start[g->seg[s][0] + 1]++;
        g->start[g->seg[s][1] + 1]++;
    }
    for (size_t i = 0; i < g->nnode; i++)
        g->start[i + 1] += g->start[i];
    size_t *fill = malloc((g->nnode + 1) * sizeof *fill);
    if (!fill) {
        graph_free(g);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    }
    memcpy(fill, g->start, (g->nnode + 1) * sizeof *fill);
    for (size_t s = 0; s < g->nseg; s++) {
        g->adj[fill[g->seg[s][0]]++] = (int32_t)s;
        g->adj[fill[g->seg[s][1]]++] = (int32_t)s;
    }
    free(fill);
    return FM_OK;
}

/* Position and parameters of graph node k. */
static void node_point(const cn_zone *za, const cn_zone *zb, uint64_t key, double x[4], double p[3])
{
    int kind = (int)(key >> 62);
    size_t e = (size_t)((key >> 31) & 0x7fffffffu), t = (size_t)(key & 0x7fffffffu);
    const cn_zone *ze = kind ? zb : za, *zt = kind ? za : zb;
    int32_t a = ze->ev[2 * e], b = ze->ev[2 * e + 1];
    const double *P = ze->xyz + 3 * a, *Q = ze->xyz + 3 * b;
    const int32_t *T = zt->tri + 3 * t;
    const double *t0 = zt->xyz + 3 * T[0], *t1 = zt->xyz + 3 * T[1], *t2 = zt->xyz + 3 * T[2];
    /* relative to t0 for precision */
    double e1[3], e2[3], n[3], dp = 0, dq = 0;
    for (int k = 0; k < 3; k++) {
        e1[k] = t1[k] - t0[k];
        e2[k] = t2[k] - t0[k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    for (int k = 0; k < 3; k++) {
        dp += n[k] * (P[k] - t0[k]);
        dq += n[k] * (Q[k] - t0[k]);
    }
    double r = dp != dq ? dp / (dp - dq) : 0.5;
    r = r < 0 ? 0 : (r > 1 ? 1 : r);
    double rel[3], zero[3] = {0, 0, 0}, bary[3];
    for (int k = 0; k < 3; k++) {
        p[k] = P[k] + r * (Q[k] - P[k]);
        rel[k] = p[k] - t0[k];
    }
    fm_closest_on_triangle(rel, zero, e1, e2, NULL, bary);
    double uve[2], uvt[2];
    for (int k = 0; k < 2; k++) {
        uve[k] = ze->uv[2 * a + k] + r * (ze->uv[2 * b + k] - ze->uv[2 * a + k]);
        uvt[k] = bary[0] * zt->uv[2 * T[0] + k] + bary[1] * zt->uv[2 * T[1] + k] +
                 bary[2] * zt->uv[2 * T[2] + k];
    }
    const double *uva = kind ? uvt : uve, *uvb = kind ? uve : uvt;
    x[0] = uva[0];
    x[1] = uva[1];
    x[2] = uvb[0];
    x[3] = uvb[1];
}

/* Chains the graph into polylines of node indices. closed[i] marks cycles. */
typedef struct chains {
    int32_t *node;      /* all chains one after the other */
    size_t *start;      /* nchain + 1 */
    int *closed;
    size_t nchain, n, capc;
} chains;

static void chains_free(chains *c)
{
    free(c->node);
    free(c->start);
    free(c->closed);
}

static fm_status make_chains(const graph *g, chains *ch)
{
    memset(ch, 0, sizeof *ch);
    unsigned char *used = calloc(g->nseg + 1, 1);
    ch->node = malloc((2 * g->nseg + 2) * sizeof *ch->node);
    ch->start = malloc((g->nseg + 2) * sizeof *ch->start);
    ch->closed = malloc((g->nseg + 2) * sizeof *ch->closed);
    if (!used || !ch->node || !ch->start || !ch->closed) {
        free(used);
        chains_free(ch);
        return FM_ERR_NOMEM;
    }
    ch->start[0] = 0;
    for (int pass = 0; pass < 2; pass++)
        for (size_t v0 = 0; v0 < g->nnode; v0++) {
            size_t deg = g->start[v0 + 1] - g->start[v0];
            if (pass == 0 && deg == 2)
                continue; /* ends and branch points first, cycles after */
            for (size_t a = g->start[v0]; a < g->start[v0 + 1]; a++) {
                int32_t s = g->adj[a];
                if (used[s])
                    continue;
                size_t first = ch->n;
                ch->node[ch->n++] = (int32_t)v0;
                int32_t v = (int32_t)v0;
                int closed = 0;
                while (s >= 0) {
                    used[s] = 1;
                    int32_t w = g->seg[s][0] == v ? g->seg[s][1] : g->seg[s][0];
                    if (w == (int32_t)v0 && pass == 1) {
                        closed = 1;
                        break;
                    }
                    ch->node[ch->n++] = w;
                    v = w;
                    s = -1;
                    if (g->start[v + 1] - g->start[v] == 2)
                        for (size_t b = g->start[v]; b < g->start[v + 1]; b++)
                            if (!used[g->adj[b]])
                                s = g->adj[b];
                }
                if (ch->n - first < 2) {
                    ch->n = first;
                    continue;
                }
                ch->closed[ch->nchain] = closed;
                ch->start[++ch->nchain] = ch->n;
            }
        }
    free(used);
    return FM_OK;
}

/* ---- Solving, cutting, resampling ---- */

typedef struct job {
    const fm_fit_surface *A, *B;
    const cn_sheet *sa, *sb;
    fm_connect_options o;
    double reach;
    size_t fallback, unconverged;
} job;

static void tangent_at(const double *P, size_t n, size_t i, int closed, double T[3])
{
    size_t a = i, b = i;
    if (closed) {
        a = (i + n - 1) % n;
        b = (i + 1) % n;
    } else {
        a = i ? i - 1 : 0;
        b = i + 1 < n ? i + 1 : n - 1;
    }
    double l = 0;
    for (int k = 0; k < 3; k++) {
        T[k] = P[3 * b + k] - P[3 * a + k];
        l += T[k] * T[k];
    }
    l = sqrt(l);
    for (int k = 0; k < 3; k++)
        T[k] = l > 0 ? T[k] / l : (k == 0);
}

static void solve_into(job *j, double x[4], const double p0[3], const double T[3], double out[3])
{
    int fb;
    double g = cn_solve_point(j->A, j->B, x, p0, T, j->o.tolerance, &fb);
    j->fallback += (size_t)fb;
    j->unconverged += g > j->o.tolerance;
    double sa[3], sb[3];
    fm_fit_surface_eval(j->A, x[0], x[1], sa, NULL, NULL);
    fm_fit_surface_eval(j->B, x[2], x[3], sb, NULL, NULL);
    for (int k = 0; k < 3; k++)
        out[k] = 0.5 * (sa[k] + sb[k]);
}

/* Largest of the two signed outline distances minus reach (> 0: cut). */
static double excess(const job *j, const double x[4], const double p[3])
{
    if (!j->o.clip_to_reach)
        return -1;
    double da = cn_sheet_outline_distance(j->sa, x[0], x[1], p);
    double db = cn_sheet_outline_distance(j->sb, x[2], x[3], p);
    return fmax(da, db) - j->reach;
}

static int lerp_point(job *j, const double *xa, const double *xb, const double *pa,
                      const double *pb, double r, double x[4], double p[3])
{
    double p0[3], T[3], l = 0;
    for (int k = 0; k < 4; k++)
        x[k] = xa[k] + r * (xb[k] - xa[k]);
    for (int k = 0; k < 3; k++) {
        p0[k] = pa[k] + r * (pb[k] - pa[k]);
        T[k] = pb[k] - pa[k];
        l += T[k] * T[k];
    }
    l = sqrt(l);
    for (int k = 0; k < 3; k++)
        T[k] = l > 0 ? T[k] / l : (k == 0);
    solve_into(j, x, p0, T, p);
    return 0;
}

/* Resamples the solved run (n points, closed or not) at the spacing. */
static int resample(job *j, const plist *run, int closed, plist *out)
{
    size_t n = run->n, m = closed ? n + 1 : n;
    double *s = malloc(m * sizeof *s);
    if (!s)
        return -1;
    s[0] = 0;
    for (size_t i = 1; i < m; i++)
        s[i] = s[i - 1] + dist3(run->p + 3 * (i - 1), run->p + 3 * (i % n));
    double L = s[m - 1];
    size_t nseg = (size_t)ceil(L / j->o.spacing - 1e-9);
    if (nseg < 1)
        nseg = 1;
    if (closed && nseg < 3)
        nseg = 3;
    size_t npts = closed ? nseg : nseg + 1;
    size_t k = 0;
    for (size_t q = 0; q < npts; q++) {
        double at = L * (double)q / (double)nseg;
        if (!closed && (q == 0 || q == nseg)) {
            size_t i = q ? n - 1 : 0;
            if (plist_push(out, run->x + 4 * i, run->p + 3 * i)) {
                free(s);
                return -1;
            }
            continue;
        }
        while (k + 2 < m && s[k + 1] < at)
            k++;
        double len = s[k + 1] - s[k], r = len > 0 ? (at - s[k]) / len : 0;
        double x[4], p[3];
        lerp_point(j, run->x + 4 * k, run->x + 4 * ((k + 1) % n), run->p + 3 * k,
                   run->p + 3 * ((k + 1) % n), r, x, p);
        if (plist_push(out, x, p)) {
            free(s);
            return -1;
        }
    }
    free(s);
    return 0;
}

/* Fills the per-point data and summary of a finished curve. */
static int finish_curve(job *j, const plist *pts, int closed, curve *c)
{
    size_t n = pts->n;
    memset(c, 0, sizeof *c);
    c->xyz = malloc(3 * n * sizeof *c->xyz);
    c->angle = malloc(n * sizeof *c->angle);
    for (int s = 0; s < 2; s++) {
        c->uv[s] = malloc(2 * n * sizeof *c->uv[s]);
        c->sd[s] = malloc(n * sizeof *c->sd[s]);
        c->flap[s] = malloc(n * sizeof *c->flap[s]);
        c->inside[s] = malloc(n);
        if (!c->uv[s] || !c->sd[s] || !c->flap[s] || !c->inside[s])
            return -1;
    }
    if (!c->xyz || !c->angle)
        return -1;
    fm_connect_curve_info *in = &c->info;
    in->npoints = n;
    in->closed = closed;
    in->min_angle = INFINITY;
    in->max_angle = 0;
    memcpy(c->xyz, pts->p, 3 * n * sizeof(double));
    double D = j->o.distance;
    for (size_t i = 0; i < n; i++) {
        const double *x = pts->x + 4 * i, *p = pts->p + 3 * i;
        c->angle[i] = cn_crossing_angle(j->A, j->B, x);
        in->min_angle = fmin(in->min_angle, c->angle[i]);
        in->max_angle = fmax(in->max_angle, c->angle[i]);
        in->mean_angle += c->angle[i] / (double)n;
        double T[3];
        tangent_at(pts->p, n, i, closed, T);
        for (int s = 0; s < 2; s++) {
            const fm_fit_surface *S = s ? j->B : j->A;
            const cn_sheet *sh = s ? j->sb : j->sa;
            double uv[2] = {x[2 * s], x[2 * s + 1]}, q[3], du[3], dv[3];
            fm_fit_surface_eval(S, uv[0], uv[1], q, du, dv);
            in->max_dist[s] = fmax(in->max_dist[s], dist3(q, p));
            c->uv[s][2 * i] = uv[0];
            c->uv[s][2 * i + 1] = uv[1];
            c->sd[s][i] = cn_sheet_outline_distance(sh, uv[0], uv[1], p);
            c->inside[s][i] = c->sd[s][i] <= 0 && cn_sheet_inside(sh, uv[0], uv[1]);
            c->flap[s][i] = NAN;
            if (!c->inside[s][i])
                continue;
            /* the direction in (u, v) at right angles (in 3D) to the curve */
            double E = du[0] * du[0] + du[1] * du[1] + du[2] * du[2];
            double F = du[0] * dv[0] + du[1] * dv[1] + du[2] * dv[2];
            double G = dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2];
            double tu = T[0] * du[0] + T[1] * du[1] + T[2] * du[2];
            double tv = T[0] * dv[0] + T[1] * dv[1] + T[2] * dv[2];
            /* d with (du d0 + dv d1) . T = 0: d = (tv, -tu), then unit length in 3D */
            double d[2] = {tv, -tu};
            double l2 = E * d[0] * d[0] + 2 * F * d[0] * d[1] + G * d[1] * d[1];
            if (!(l2 > 0)) {
                c->flap[s][i] = INFINITY;
                continue;
            }
            d[0] /= sqrt(l2);
            d[1] /= sqrt(l2);
            double md[2] = {-d[0], -d[1]};
            double e1 = cn_sheet_ray_exit(sh, uv, d, D), e2 = cn_sheet_ray_exit(sh, uv, md, D);
            c->flap[s][i] = fmin(e1, e2);
        }
    }
    /* lengths and roles */
    size_t nseg = closed ? n : n - 1;
    double *gaps[2];
    size_t ngap[2] = {0, 0};
    double *flaps[2];
    size_t nflap[2] = {0, 0};
    for (int s = 0; s < 2; s++) {
        gaps[s] = malloc((n + 1) * sizeof(double));
        flaps[s] = malloc((n + 1) * sizeof(double));
        if (!gaps[s] || !flaps[s]) {
            free(gaps[0]);
            free(flaps[0]);
            return -1;
        }
    }
    double flap_len[2] = {0, 0};
    for (size_t i = 0; i < nseg; i++) {
        size_t a = i, b = (i + 1) % n;
        double l = dist3(c->xyz + 3 * a, c->xyz + 3 * b);
        in->length += l;
        for (int s = 0; s < 2; s++)
            for (int e = 0; e < 2; e++) {
                size_t k = e ? b : a;
                if (c->inside[s][k]) {
                    in->side[s].length_inside += 0.5 * l;
                    if (isfinite(c->flap[s][k]))
                        flap_len[s] += 0.5 * l;
                } else {
                    in->side[s].length_extension += 0.5 * l;
                }
            }
    }
    for (int s = 0; s < 2; s++) {
        fm_connect_side *sd = &in->side[s];
        for (size_t i = 0; i < n; i++) {
            if (!c->inside[s][i]) {
                double g = fmax(c->sd[s][i], 0);
                gaps[s][ngap[s]++] = g;
                sd->max_gap = fmax(sd->max_gap, g);
            } else if (isfinite(c->flap[s][i])) {
                flaps[s][nflap[s]++] = c->flap[s][i];
            }
        }
        sd->median_gap = ngap[s] ? fm_median(gaps[s], ngap[s]) : 0;
        sd->median_flap = nflap[s] ? fm_median(flaps[s], nflap[s]) : INFINITY;
        sd->end_inside[0] = c->inside[s][0];
        sd->end_inside[1] = c->inside[s][n - 1];
        if (sd->length_extension > sd->length_inside || (n == 1 && !c->inside[s][0]))
            sd->role = FM_CONNECT_GAP;
        else if (flap_len[s] > 0.5 * sd->length_inside)
            sd->role = FM_CONNECT_OVERSHOOT;
        else
            sd->role = FM_CONNECT_THROUGH;
        free(gaps[s]);
        free(flaps[s]);
    }
    return 0;
}

static int push_curve(fm_connect_curves *cs, const curve *c)
{
    if (cs->n == cs->cap) {
        size_t cap = cs->cap ? 2 * cs->cap : 8;
        curve *nc = realloc(cs->c, cap * sizeof *nc);
        if (!nc)
            return -1;
        cs->c = nc;
        cs->cap = cap;
    }
    cs->c[cs->n++] = *c;
    return 0;
}

static int lex_less(const double *a, const double *b)
{
    for (int k = 0; k < 3; k++)
        if (a[k] != b[k])
            return a[k] < b[k];
    return 0;
}

static void reverse_run(plist *r)
{
    for (size_t i = 0, k = r->n - 1; i < k; i++, k--) {
        double t[4];
        memcpy(t, r->x + 4 * i, sizeof t);
        memcpy(r->x + 4 * i, r->x + 4 * k, sizeof t);
        memcpy(r->x + 4 * k, t, sizeof t);
        memcpy(t, r->p + 3 * i, 3 * sizeof(double));
        memcpy(r->p + 3 * i, r->p + 3 * k, 3 * sizeof(double));
        memcpy(r->p + 3 * k, t, 3 * sizeof(double));
    }
}

/* One solved run -> resampled, classified curve. */
static int emit_run(job *j, plist *run, int closed, fm_connect_curves *cs)
{
    if (run->n < 2)
        return 0;
    if (!closed && lex_less(run->p + 3 * (run->n - 1), run->p))
        reverse_run(run);
    plist rs = {0};
    curve c;
    size_t fb0 = j->fallback, un0 = j->unconverged;
    memset(&c, 0, sizeof c);
    if (resample(j, run, closed, &rs) || finish_curve(j, &rs, closed, &c)) {
        curve_free(&c);
        plist_free(&rs);
        return -1;
    }
    c.info.fallback_points = j->fallback - fb0;
    c.info.unconverged = j->unconverged - un0;
    plist_free(&rs);
    return push_curve(cs, &c);
}

/* ---- Runs: the solved, cut curves before resampling ---- */

void cn_runs_free(cn_runs *rs)
{
    if (!rs)
        return;
    for (size_t i = 0; i < rs->n; i++) {
        free(rs->r[i].x);
        free(rs->r[i].p);
    }
    free(rs->r);
    memset(rs, 0, sizeof *rs);
}

int cn_runs_push(cn_runs *rs, int closed, size_t n, const double *x, const double *p)
{
    if (rs->n == rs->cap) {
        size_t cap = rs->cap ? 2 * rs->cap : 4;
        cn_run *nr = realloc(rs->r, cap * sizeof *nr);
        if (!nr)
            return -1;
        rs->r = nr;
        rs->cap = cap;
    }
    cn_run *r = &rs->r[rs->n];
    r->closed = closed;
    r->n = n;
    r->x = malloc((4 * n + 1) * sizeof *r->x);
    r->p = malloc((3 * n + 1) * sizeof *r->p);
    if (!r->x || !r->p) {
        free(r->x);
        free(r->p);
        return -1;
    }
    if (n && x && p) { /* NULL: filled by the caller */
        memcpy(r->x, x, 4 * n * sizeof *x);
        memcpy(r->p, p, 3 * n * sizeof *p);
    }
    rs->n++;
    return 0;
}

/* A run kept as it is; emit_run makes the curve of it (a run of fewer
 * than two points makes none, and is not kept). */
static int keep_run(cn_runs *rs, const plist *run, int closed)
{
    return run->n < 2 ? 0 : cn_runs_push(rs, closed, run->n, run->x, run->p);
}

/* Solves a raw chain, cuts it where it leaves the grown regions, keeps
 * the runs. */
static int process_chain(job *j, plist *raw, int closed, cn_runs *rs)
{
    size_t n = raw->n;
    double *sol = malloc(3 * n * sizeof *sol), *ex = malloc(n * sizeof *ex);
    if (!sol || !ex) {
        free(sol);
        free(ex);
        return -1;
    }
    for (size_t i = 0; i < n; i++) {
        double T[3];
        tangent_at(raw->p, n, i, closed, T);
        solve_into(j, raw->x + 4 * i, raw->p + 3 * i, T, sol + 3 * i);
    }
    memcpy(raw->p, sol, 3 * n * sizeof *sol);
    free(sol);
    for (size_t i = 0; i < n; i++)
        ex[i] = excess(j, raw->x + 4 * i, raw->p + 3 * i);
    /* closed and all kept: one closed curve */
    size_t first_out = n;
    for (size_t i = 0; i < n; i++)
        if (ex[i] > 0) {
            first_out = i;
            break;
        }
    int rc = 0;
    if (closed && first_out == n) {
        free(ex);
        return keep_run(rs, raw, 1);
    }
    /* walk from a cut point (closed) or from the start (open) */
    size_t m = closed ? n + 1 : n, s0 = closed ? first_out : 0;
    plist run = {0};
    for (size_t q = 0; q < m && rc == 0; q++) {
        size_t i = (s0 + q) % n;
        int in = ex[i] <= 0;
        if (q > 0) {
            size_t h = (s0 + q - 1) % n;
            int hin = ex[h] <= 0;
            if (hin != in) {
                double r = ex[h] / (ex[h] - ex[i]), x[4], p[3];
                lerp_point(j, raw->x + 4 * h, raw->x + 4 * i, raw->p + 3 * h, raw->p + 3 * i, r,
                           x, p);
                rc |= plist_push(&run, x, p);
                if (hin) {
                    rc |= keep_run(rs, &run, 0);
                    run.n = 0;
                }
            }
        }
        if (in && !(closed && q == n))
            rc |= plist_push(&run, raw->x + 4 * i, raw->p + 3 * i);
    }
    if (rc == 0 && run.n)
        rc = keep_run(rs, &run, 0);
    plist_free(&run);
    free(ex);
    return rc;
}

static int cmp_curve(const void *a, const void *b)
{
    const curve *x = a, *y = b;
    for (int k = 0; k < 3; k++)
        if (x->xyz[k] != y->xyz[k])
            return x->xyz[k] < y->xyz[k] ? -1 : 1;
    return (x->info.npoints > y->info.npoints) - (x->info.npoints < y->info.npoints);
}

static void job_init(job *j, const cn_sheet *sa, const cn_sheet *sb, const fm_connect_options *opt)
{
    memset(j, 0, sizeof *j);
    j->o = *opt;
    j->reach = j->o.reach < 0 ? j->o.distance : j->o.reach;
    j->A = sa->surf;
    j->B = sb->surf;
    j->sa = sa;
    j->sb = sb;
}

fm_status cn_intersect_trace(const cn_sheet *sa, const cn_sheet *sb, const fm_connect_options *opt,
                             cn_runs *rs, fm_error *err)
{
    memset(rs, 0, sizeof *rs);
    job j;
    job_init(&j, sa, sb, opt);
    fm_status st = FM_OK;
    unsigned char *sel_a = malloc(sa->nsu * sa->nsv + 1), *sel_b = malloc(sb->nsu * sb->nsv + 1);
    cn_zone za = {0}, zb = {0};
    graph g = {0};
    chains ch = {0};
    if (!sel_a || !sel_b) {
        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
        goto done;
    }
    if (!cn_select_cells(sa, sb, 0.0, sel_a) || !cn_select_cells(sb, sa, 0.0, sel_b))
        goto done;
    if (cn_zone_build(sa, sel_a, cn_subdivision(sa, j.o.sample_spacing), 1, &za) != FM_OK ||
        cn_zone_build(sb, sel_b, cn_subdivision(sb, j.o.sample_spacing), 1, &zb) != FM_OK) {
        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
        goto done;
    }
    if ((st = build_graph(&za, &zb, &g, err)) != FM_OK)
        goto done;
    if (make_chains(&g, &ch) != FM_OK) {
        st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
        goto done;
    }
    for (size_t c = 0; c < ch.nchain && st == FM_OK; c++) {
        plist raw = {0};
        int bad = 0;
        for (size_t i = ch.start[c]; i < ch.start[c + 1]; i++) {
            double x[4], p[3];
            node_point(&za, &zb, g.key[ch.node[i]], x, p);
            bad |= plist_push(&raw, x, p);
        }
        if (bad || process_chain(&j, &raw, ch.closed[c], rs))
            st = fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
        plist_free(&raw);
    }
done:
    chains_free(&ch);
    graph_free(&g);
    cn_zone_free(&za);
    cn_zone_free(&zb);
    free(sel_a);
    free(sel_b);
    if (st != FM_OK)
        cn_runs_free(rs);
    return st;
}

fm_status cn_intersect_emit(const cn_sheet *sa, const cn_sheet *sb, const fm_connect_options *opt,
                            const cn_runs *rs, fm_connect_curves **out, fm_error *err)
{
    *out = NULL;
    job j;
    job_init(&j, sa, sb, opt);
    fm_connect_curves *cs = calloc(1, sizeof *cs);
    if (!cs)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    for (size_t i = 0; i < rs->n; i++) {
        /* emit_run may turn the run round: a copy, the kept one untouched */
        const cn_run *r = &rs->r[i];
        plist run = {0};
        int bad = 0;
        for (size_t k = 0; k < r->n; k++)
            bad |= plist_push(&run, r->x + 4 * k, r->p + 3 * k);
        bad = bad || emit_run(&j, &run, r->closed, cs);
        plist_free(&run);
        if (bad) {
            fm_connect_curves_destroy(cs);
            return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
        }
    }
    if (cs->n > 1)
        qsort(cs->c, cs->n, sizeof *cs->c, cmp_curve);
    *out = cs;
    return FM_OK;
}

fm_status cn_intersect(const cn_sheet *sa, const cn_sheet *sb, const fm_connect_options *opt,
                       fm_connect_curves **out, fm_error *err)
{
    *out = NULL;
    cn_runs rs;
    fm_status st = cn_intersect_trace(sa, sb, opt, &rs, err);
    if (st == FM_OK)
        st = cn_intersect_emit(sa, sb, opt, &rs, out, err);
    cn_runs_free(&rs);
    return st;
}

fm_status fm_connect_intersect(const fm_model *a, size_t sheet_a, const fm_model *b,
                               size_t sheet_b, const fm_connect_options *opt,
                               fm_connect_curves **out, fm_error *err)
{
    *out = NULL;
    fm_connect_options o;
    if (opt)
        o = *opt;
    else
        fm_connect_options_default(&o);
    if (!a || !b || sheet_a >= fm_model_nsheets(a) || sheet_b >= fm_model_nsheets(b))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "connect: no such sheet");
    if (!(o.spacing > 0) || !(o.tolerance > 0) || !(o.distance >= 0))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "connect: bad options");
    double reach = o.reach < 0 ? o.distance : o.reach;
    double build_reach = o.clip_to_reach ? reach : INFINITY;
    cn_sheet sa, sb;
    fm_status st = cn_sheet_build(a, 0, sheet_a, build_reach, &sa, err);
    if (st != FM_OK)
        return st;
    if ((st = cn_sheet_build(b, 1, sheet_b, build_reach, &sb, err)) != FM_OK) {
        cn_sheet_free(&sa);
        return st;
    }
    st = cn_intersect(&sa, &sb, &o, out, err);
    cn_sheet_free(&sa);
    cn_sheet_free(&sb);
    return st;
}
