/* Rings cut into disks before fitting (see model_internal.h).
 *
 * A sheet whose strands part and rejoin is an annulus whose two rims are
 * both "outer": no plane sees it one-to-one, and its conformal map is
 * either folded (then the convex map squeezes one rim to a sliver) or so
 * distorted that a B-spline over it cannot follow the sheet. Two cuts
 * between the rims make two disks; each is fitted on its own and the cuts
 * are kept, like junctions, for the stages that must make the parts meet
 * again. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fit_internal.h"
#include "model_internal.h"

/* Nested ring splits, at most: a ring of rings is rarer than a bad sheet. */
#define SPLIT_MAX_DEPTH 4

typedef struct graph {
    size_t nv, nt;
    const double *X;
    const int32_t *T;
    size_t *off;     /* CSR vertex -> neighbours */
    int32_t *adj;
    int32_t *loop;   /* loop of each vertex, -1 inside */
} graph;

static void graph_free(graph *g)
{
    free(g->off);
    free(g->adj);
    free(g->loop);
}

static int cmp_i32(const void *a, const void *b)
{
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

static fm_status graph_make(const fm_mesh *mesh, graph *g)
{
    memset(g, 0, sizeof *g);
    g->nv = fm_mesh_nvertices(mesh);
    g->nt = fm_mesh_ntriangles(mesh);
    g->X = fm_mesh_vertices(mesh);
    g->T = fm_mesh_triangles(mesh);
    g->off = calloc(g->nv + 1, sizeof *g->off);
    g->adj = malloc((6 * g->nt + 1) * sizeof *g->adj);
    g->loop = malloc((g->nv + 1) * sizeof *g->loop);
    if (!g->off || !g->adj || !g->loop)
        return FM_ERR_NOMEM;
    for (size_t i = 0; i < 3 * g->nt; i++)
        g->off[g->T[i] + 1] += 2;
    for (size_t v = 0; v < g->nv; v++)
        g->off[v + 1] += g->off[v];
    size_t *fill = malloc((g->nv + 1) * sizeof *fill);
    if (!fill)
        return FM_ERR_NOMEM;
    memcpy(fill, g->off, g->nv * sizeof *fill);
    for (size_t t = 0; t < g->nt; t++)
        for (int k = 0; k < 3; k++) {
            int32_t a = g->T[3 * t + k], b = g->T[3 * t + (k + 1) % 3];
            g->adj[fill[a]++] = b;
            g->adj[fill[b]++] = a;
        }
    free(fill);
    /* Sorted and unique: deterministic order, one entry per edge. */
    size_t w = 0;
    for (size_t v = 0; v < g->nv; v++) {
        size_t a = g->off[v], b = g->off[v + 1];
        qsort(g->adj + a, b - a, sizeof *g->adj, cmp_i32);
        g->off[v] = w;
        for (size_t i = a; i < b; i++)
            if (i == a || g->adj[i] != g->adj[i - 1])
                g->adj[w++] = g->adj[i];
    }
    g->off[g->nv] = w;
    for (size_t v = 0; v < g->nv; v++)
        g->loop[v] = -1;
    return FM_OK;
}

static double edge_len(const graph *g, int32_t a, int32_t b)
{
    const double *p = g->X + 3 * a, *q = g->X + 3 * b;
    return sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                (p[2] - q[2]) * (p[2] - q[2]));
}

/* Binary heap of (distance, vertex), ties broken by vertex index. */
typedef struct heap {
    double *d;
    int32_t *v;
    size_t n;
} heap;

static int heap_less(const heap *h, size_t i, size_t j)
{
    return h->d[i] < h->d[j] || (h->d[i] == h->d[j] && h->v[i] < h->v[j]);
}

static void heap_swap(heap *h, size_t i, size_t j)
{
    double d = h->d[i];
    int32_t v = h->v[i];
    h->d[i] = h->d[j];
    h->v[i] = h->v[j];
    h->d[j] = d;
    h->v[j] = v;
}

static void heap_push(heap *h, double d, int32_t v)
{
    size_t i = h->n++;
    h->d[i] = d;
    h->v[i] = v;
    while (i > 0 && heap_less(h, i, (i - 1) / 2)) {
        heap_swap(h, i, (i - 1) / 2);
        i = (i - 1) / 2;
    }
}

static int32_t heap_pop(heap *h, double *d)
{
    int32_t v = h->v[0];
    *d = h->d[0];
    h->n--;
    h->d[0] = h->d[h->n];
    h->v[0] = h->v[h->n];
    for (size_t i = 0;;) {
        size_t l = 2 * i + 1, r = l + 1, m = i;
        if (l < h->n && heap_less(h, l, m))
            m = l;
        if (r < h->n && heap_less(h, r, m))
            m = r;
        if (m == i)
            break;
        heap_swap(h, i, m);
        i = m;
    }
    return v;
}

/* Is a-b a boundary edge (consecutive on a loop)? Boundary edges bound one
 * triangle; counting triangles through the CSR would cost more than this
 * check on the loop tables. */
typedef struct bedges {
    uint64_t *key;
    size_t n;
} bedges;

static uint64_t ekey(int32_t a, int32_t b)
{
    uint32_t x = (uint32_t)a, y = (uint32_t)b;
    return x < y ? ((uint64_t)x << 32 | y) : ((uint64_t)y << 32 | x);
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

static int is_bedge(const bedges *be, int32_t a, int32_t b)
{
    return bsearch(&(uint64_t){ekey(a, b)}, be->key, be->n, sizeof *be->key, cmp_u64) != NULL;
}

/* Dijkstra from the sources (dist 0) to the first vertex of loop `target`,
 * through inside vertices only (not on any loop, not blocked) and not along
 * boundary edges. Fills the path (target first), or *npath = 0. With
 * target < 0 it only computes distances (everything allowed). */
static fm_status dijkstra(const graph *g, const bedges *be, const int32_t *src, size_t nsrc,
                          int32_t target, const unsigned char *blocked, double *dist,
                          int32_t **path, size_t *npath)
{
    int32_t *prev = malloc((g->nv + 1) * sizeof *prev);
    unsigned char *done = calloc(g->nv + 1, 1);
    heap h = {malloc((g->off[g->nv] + nsrc + 1) * sizeof(double)),
              malloc((g->off[g->nv] + nsrc + 1) * sizeof(int32_t)), 0};
    if (!prev || !done || !h.d || !h.v) {
        free(prev);
        free(done);
        free(h.d);
        free(h.v);
        return FM_ERR_NOMEM;
    }
    for (size_t v = 0; v < g->nv; v++) {
        dist[v] = INFINITY;
        prev[v] = -1;
    }
    for (size_t i = 0; i < nsrc; i++) {
        dist[src[i]] = 0;
        heap_push(&h, 0, src[i]);
    }
    int32_t hit = -1;
    while (h.n) {
        double d;
        int32_t x = heap_pop(&h, &d);
        if (done[x])
            continue;
        done[x] = 1;
        if (target >= 0 && g->loop[x] == target && prev[x] >= 0) {
            hit = x;
            break;
        }
        /* Only sources and inside vertices are passed through. */
        if (target >= 0 && prev[x] >= 0 && g->loop[x] >= 0)
            continue;
        for (size_t k = g->off[x]; k < g->off[x + 1]; k++) {
            int32_t y = g->adj[k];
            if (done[y])
                continue;
            if (target >= 0) {
                if (blocked && blocked[y])
                    continue;
                if (g->loop[y] >= 0 && g->loop[y] != target)
                    continue;
                if (g->loop[x] >= 0 && g->loop[y] >= 0 && is_bedge(be, x, y))
                    continue;
            }
            double nd = d + edge_len(g, x, y);
            if (nd < dist[y]) {
                dist[y] = nd;
                prev[y] = x;
                heap_push(&h, nd, y);
            }
        }
    }
    fm_status st = FM_OK;
    if (path) {
        *npath = 0;
        *path = NULL;
        if (hit >= 0) {
            size_t n = 0;
            for (int32_t x = hit; x >= 0; x = prev[x])
                n++;
            *path = malloc(n * sizeof **path);
            if (!*path) {
                st = FM_ERR_NOMEM;
            } else {
                for (int32_t x = hit; x >= 0; x = prev[x])
                    (*path)[(*npath)++] = x;
            }
        }
    }
    free(prev);
    free(done);
    free(h.d);
    free(h.v);
    return st;
}

/* The two rims: the outer loop and the longest other loop (3D length). */
static void pick_rims(const fm_surface *s, size_t sheet, graph *g, size_t *ra, size_t *rb)
{
    size_t nl = fm_surface_sheet_nloops(s, sheet);
    long outer = fm_surface_sheet_outer_loop(s, sheet);
    *ra = outer >= 0 ? (size_t)outer : 0;
    double best = -1;
    *rb = *ra;
    for (size_t k = 0; k < nl; k++) {
        if (k == *ra)
            continue;
        size_t n;
        const int32_t *lv = fm_surface_sheet_loop(s, sheet, k, &n);
        double len = 0;
        for (size_t q = 0; q < n; q++)
            len += edge_len(g, lv[q], lv[(q + 1) % n]);
        if (len > best) {
            best = len;
            *rb = k;
        }
    }
}

/* What a parametric fit must reach for its sheet to stay whole: the fit
 * stage's acceptance figures (10 m RMS, 100 m max) with some margin. Fixed
 * rather than tied to the knot-refinement targets, which are stricter by
 * design: a sheet that misses those is refined, not cut (cutting makes
 * small pieces whose maps are no better). */
#define SPLIT_RMS 8.0
#define SPLIT_MAX 80.0
#define SPLIT_MIN_TRIANGLES 20

/* A sheet is cut when the fit it would get is not good: no one-to-one
 * plane and a parametric fit that needs the convex map or misses the
 * figures above. The fit is begun here and, when the sheet stays whole,
 * handed on in *keep for the model to finish (no second fit). */
static int needs_split(const char *name, const fm_mesh *mesh, size_t nloops,
                       const fm_fit_options *fit, fm_fit_pending **keep)
{
    *keep = NULL;
    /* A sheet of a few triangles has no neck worth a cut: its pieces would
     * be a triangle or two each, fitted no better (a 6-vertex sheet of
     * Coronado Bank north went from 54 to 121 m off its outline cut). */
    if (nloops < 1 || fm_mesh_ntriangles(mesh) < SPLIT_MIN_TRIANGLES)
        return 0;
    fm_fit_frame fr;
    fm_error e;
    if (fm_fit_reference_frame(mesh, &fit->frame, &fr, &e) != FM_OK)
        return 0;
    fm_fit_options o = *fit;
    o.name = name;
    fm_fit_pending *pf = NULL;
    if (fm_fit_pending_begin(mesh, &o, &fr, &pf, &e) != FM_OK)
        return 1;
    const fm_fit_stats *st = fm_fit_pending_stats(pf);
    int bad;
    if (st->kind == FM_FIT_HEIGHT_FIELD && fr.min_dot >= FM_FIT_STEEP_DOT && st->stacked == 0) {
        /* A height field serves: nothing to decide. Not a steep or
         * stacked one, though: missing its targets, it is fitted parametric
         * (fm_fit.h), and such a sheet can be as far from one smooth map as
         * a folded one (Clark north: strands stacked 30 m apart, 101 m off
         * its outline whole, 47 m as two disks). */
        bad = 0;
    } else if (st->kind == FM_FIT_PARAMETRIC && st->convex_map) {
        bad = 1; /* known before any solve */
    } else {
        /* The decision needs the fit at the usual grid, not the best a
         * ring would get from the further halvings (on the whole ring, at
         * every level of the recursion). */
        fm_fit_stats t;
        bad = fm_fit_pending_trial(pf, 1, &t) != FM_OK ||
              (t.kind == FM_FIT_PARAMETRIC &&
               (t.convex_map || t.rms_w > SPLIT_RMS || t.max_w > SPLIT_MAX));
    }
    if (bad)
        fm_fit_pending_destroy(pf);
    else
        *keep = pf;
    return bad;
}

/* The cut of a disk at its narrowest neck: the path between two vertices
 * a, b of its loop (through inside vertices, not along the loop) with the
 * smallest ratio of its length to the shorter loop arc between a and b.
 * A strand bent round on itself is cut across its middle (a cut of about
 * its width against half its perimeter); a part that hangs on the rest by
 * a narrow strip (a splay folded under its strand, a flap lapping over the
 * sheet) is cut off at that strip, wherever it lies. Cutting between the
 * farthest apart vertices instead finds no path where the strip has no
 * inside vertex, and halving leaves the flap on one of the halves. Every
 * loop vertex is a source; a search stops once no shorter ratio can come
 * (the ratio is at least the length over half the perimeter). Fills the
 * path (from b back to a), or *npath = 0. */
static fm_status disk_neck(const fm_surface *s, size_t sheet, const graph *g, const bedges *be,
                           double *dist, int32_t **path, size_t *npath)
{
    size_t n;
    const int32_t *lv = fm_surface_sheet_loop(s, sheet, 0, &n);
    *path = NULL;
    *npath = 0;
    if (n < 4)
        return FM_OK;
    double *cum = malloc((n + 1) * sizeof *cum);
    size_t *pos = malloc((g->nv + 1) * sizeof *pos);
    int32_t *prev = malloc((g->nv + 1) * sizeof *prev);
    unsigned char *done = calloc(g->nv + 1, 1);
    int32_t *touched = malloc((g->nv + 1) * sizeof *touched);
    heap h = {malloc((g->off[g->nv] + 1) * sizeof(double)),
              malloc((g->off[g->nv] + 1) * sizeof(int32_t)), 0};
    fm_status st = FM_OK;
    if (!cum || !pos || !prev || !done || !touched || !h.d || !h.v) {
        st = FM_ERR_NOMEM;
        goto out;
    }
    cum[0] = 0;
    for (size_t q = 0; q < n; q++)
        cum[q + 1] = cum[q] + edge_len(g, lv[q], lv[(q + 1) % n]);
    for (size_t v = 0; v < g->nv; v++) {
        dist[v] = INFINITY;
        prev[v] = -1;
    }
    for (size_t q = 0; q < n; q++)
        pos[lv[q]] = q;
    double total = cum[n], best = INFINITY;
    size_t best_a = 0;
    int32_t best_b = -1;
    for (int pass = 0; pass < 2; pass++) {
        /* pass 0 finds the best pair; pass 1 reruns its source for the path */
        for (size_t qa = pass ? best_a : 0; qa < (pass ? best_a + 1 : n); qa++) {
            int32_t a = lv[qa];
            size_t nt = 0;
            dist[a] = 0;
            touched[nt++] = a;
            h.n = 0;
            heap_push(&h, 0, a);
            while (h.n) {
                double d;
                int32_t x = heap_pop(&h, &d);
                if (done[x])
                    continue;
                done[x] = 1;
                if (!pass && d >= best * 0.5 * total)
                    break;
                if (x != a && g->loop[x] >= 0) {
                    if (!pass && g->loop[x] == 0) {
                        double arc = fabs(cum[pos[x]] - cum[qa]);
                        arc = fmin(arc, total - arc);
                        if (arc > 0 && d / arc < best) {
                            best = d / arc;
                            best_a = qa;
                            best_b = x;
                        }
                    }
                    continue; /* a cut ends at the loop */
                }
                for (size_t k = g->off[x]; k < g->off[x + 1]; k++) {
                    int32_t y = g->adj[k];
                    if (done[y] || (g->loop[y] >= 0 && g->loop[y] != 0))
                        continue;
                    if (g->loop[x] >= 0 && g->loop[y] >= 0 && is_bedge(be, x, y))
                        continue;
                    double nd = d + edge_len(g, x, y);
                    if (nd < dist[y]) {
                        if (!isfinite(dist[y]))
                            touched[nt++] = y;
                        dist[y] = nd;
                        prev[y] = x;
                        heap_push(&h, nd, y);
                    }
                }
            }
            if (pass && best_b >= 0 && isfinite(dist[best_b])) {
                size_t m = 0;
                for (int32_t x = best_b; x >= 0; x = prev[x])
                    m++;
                *path = malloc(m * sizeof **path);
                if (!*path) {
                    st = FM_ERR_NOMEM;
                    goto out;
                }
                for (int32_t x = best_b; x >= 0; x = prev[x])
                    (*path)[(*npath)++] = x;
            }
            /* reset only what this search touched: n searches stay cheap */
            for (size_t i = 0; i < nt; i++) {
                dist[touched[i]] = INFINITY;
                prev[touched[i]] = -1;
                done[touched[i]] = 0;
            }
        }
        if (best_b < 0)
            break;
    }
out:
    free(cum);
    free(pos);
    free(prev);
    free(done);
    free(touched);
    free(h.d);
    free(h.v);
    return st;
}

static fm_status add_cut(fm_model_split *sp, const graph *g, const int32_t *path, size_t n,
                         const int32_t side_tri[2], size_t repair_sheet)
{
    fm_split_cut *c = realloc(sp->cuts, (sp->ncuts + 1) * sizeof *c);
    if (!c)
        return FM_ERR_NOMEM;
    sp->cuts = c;
    c = &sp->cuts[sp->ncuts];
    memset(c, 0, sizeof *c);
    c->xyz = malloc(3 * n * sizeof *c->xyz);
    if (!c->xyz)
        return FM_ERR_NOMEM;
    sp->ncuts++;
    /* Cuts run from the outer rim to the other one. */
    for (size_t i = 0; i < n; i++)
        memcpy(c->xyz + 3 * i, g->X + 3 * path[n - 1 - i], 3 * sizeof *c->xyz);
    c->n = n;
    c->sheets[0] = side_tri[0];
    c->sheets[1] = side_tri[1];
    c->repair_sheet = repair_sheet;
    return FM_OK;
}

/* The two triangles along edge a-b (from the vertex -> triangle lists). */
static void edge_tris(const graph *g, const size_t *toff, const int32_t *tlist, int32_t a,
                      int32_t b, int32_t out[2])
{
    out[0] = out[1] = -1;
    int n = 0;
    for (size_t k = toff[a]; k < toff[a + 1] && n < 2; k++) {
        const int32_t *t = g->T + 3 * tlist[k];
        if (t[0] == b || t[1] == b || t[2] == b)
            out[n++] = tlist[k];
    }
}

typedef struct cutter {
    graph g;
    bedges be;
    double *dist;
    int32_t *p1, *p2;
    size_t n1, n2;
    size_t *toff;
    int32_t *tlist, *comp;
    uint64_t *cutkeys;
} cutter;

static void cutter_free(cutter *c)
{
    graph_free(&c->g);
    free(c->be.key);
    free(c->dist);
    free(c->p1);
    free(c->p2);
    free(c->toff);
    free(c->tlist);
    free(c->comp);
    free(c->cutkeys);
}

/* The triangles of component `id`, as a mesh repaired into sheets. */
static fm_status piece_surface(const graph *g, const fm_mesh *mesh, const int32_t *comp,
                               int32_t id, fm_surface **out, fm_error *err)
{
    int32_t *map = malloc((g->nv + 1) * sizeof *map);
    fm_mesh *pm = fm_mesh_create();
    if (!map || !pm) {
        free(map);
        fm_mesh_destroy(pm);
        return FM_ERR_NOMEM;
    }
    for (size_t v = 0; v < g->nv; v++)
        map[v] = -1;
    const int32_t *tags = fm_mesh_tags(mesh);
    for (size_t t = 0; t < g->nt; t++) {
        if (comp[t] != id)
            continue;
        int32_t q[3];
        for (int k = 0; k < 3; k++) {
            int32_t v = g->T[3 * t + k];
            if (map[v] < 0)
                map[v] = fm_mesh_add_vertex(pm, g->X[3 * v], g->X[3 * v + 1], g->X[3 * v + 2]);
            q[k] = map[v];
        }
        fm_mesh_add_triangle(pm, q[0], q[1], q[2], tags ? tags[t] : 0);
    }
    free(map);
    fm_repair_options ro;
    fm_repair_options_default(&ro);
    ro.drop_fragments = 0;
    fm_status st = fm_repair(pm, &ro, out, err);
    fm_mesh_destroy(pm);
    return st;
}

/* Cuts the sheet's mesh into disks; fills sp->pieces (one sheet each) and
 * sp->cuts (their sheets: the pieces on either side). Returns FM_OK with no
 * pieces when no two disjoint cuts exist. */
static fm_status cut_ring(const fm_surface *s, size_t sheet, size_t repair_sheet,
                          fm_model_split *sp, fm_error *err, const char *name)
{
    const fm_mesh *mesh = fm_surface_sheet_mesh(s, sheet);
    cutter c;
    memset(&c, 0, sizeof c);
    fm_status st = graph_make(mesh, &c.g);
    graph *g = &c.g;
    size_t nl = fm_surface_sheet_nloops(s, sheet), nb = 0;
    for (size_t k = 0; k < nl; k++) {
        size_t n;
        fm_surface_sheet_loop(s, sheet, k, &n);
        nb += n;
    }
    c.be.key = malloc((nb + 1) * sizeof *c.be.key);
    c.dist = malloc((g->nv + 1) * sizeof *c.dist);
    if (st != FM_OK || !c.be.key || !c.dist) {
        cutter_free(&c);
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
    }
    for (size_t k = 0; k < nl; k++) {
        size_t n;
        const int32_t *lv = fm_surface_sheet_loop(s, sheet, k, &n);
        for (size_t q = 0; q < n; q++) {
            if (g->loop[lv[q]] < 0)
                g->loop[lv[q]] = (int32_t)k;
            c.be.key[c.be.n++] = ekey(lv[q], lv[(q + 1) % n]);
        }
    }
    qsort(c.be.key, c.be.n, sizeof *c.be.key, cmp_u64);
    size_t ra, rb;
    int32_t *src = malloc((nb + 1) * sizeof *src), target;
    size_t nsrc = 0;
    int ring = nl >= 2;
    if (!src) {
        cutter_free(&c);
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
    }
    if (ring) {
        /* A ring: two cuts between its rims. */
        pick_rims(s, sheet, g, &ra, &rb);
        const int32_t *A = fm_surface_sheet_loop(s, sheet, ra, &nsrc);
        memcpy(src, A, nsrc * sizeof *src);
        target = (int32_t)rb;
    } else {
        target = -1;
        ra = rb = 0;
    }

    /* First cut: the shortest path between the rims, or the neck of a
     * disk no map serves (disk_neck). */
    fm_status st2 = ring ? dijkstra(g, &c.be, src, nsrc, target, NULL, c.dist, &c.p1, &c.n1)
                         : disk_neck(s, sheet, g, &c.be, c.dist, &c.p1, &c.n1);
    /* Second cut: from the half of rim A away from the first cut to rim B,
     * not touching the first cut. */
    unsigned char *blocked = NULL;
    if (st2 == FM_OK && ring && c.n1 >= 2) {
        st2 = dijkstra(g, &c.be, c.p1, c.n1, -1, NULL, c.dist, NULL, NULL);
        blocked = calloc(g->nv + 1, 1);
        if (!blocked)
            st2 = FM_ERR_NOMEM;
    }
    if (st2 == FM_OK && blocked) {
        double far = 0;
        for (size_t q = 0; q < nsrc; q++)
            if (isfinite(c.dist[src[q]]))
                far = fmax(far, c.dist[src[q]]);
        for (size_t i = 0; i < c.n1; i++)
            blocked[c.p1[i]] = 1;
        size_t n2 = 0;
        for (size_t q = 0; q < nsrc; q++)
            if (isfinite(c.dist[src[q]]) && c.dist[src[q]] >= 0.5 * far && !blocked[src[q]])
                src[n2++] = src[q];
        if (n2)
            st2 = dijkstra(g, &c.be, src, n2, target, blocked, c.dist, &c.p2, &c.n2);
    }
    free(blocked);
    free(src);
    st = st2;
    if (st != FM_OK || c.n1 < 2 || (ring && c.n2 < 2)) {
        cutter_free(&c);
        return st == FM_OK ? FM_OK : fm_error_set(err, st, name, 0, "out of memory");
    }

    /* Triangles flooded across every inside edge but the cuts. */
    c.toff = calloc(g->nv + 1, sizeof *c.toff);
    c.tlist = malloc((3 * g->nt + 1) * sizeof *c.tlist);
    c.comp = malloc((g->nt + 1) * sizeof *c.comp);
    c.cutkeys = malloc((c.n1 + c.n2 + 1) * sizeof *c.cutkeys);
    int32_t *stack = malloc((g->nt + 1) * sizeof *stack);
    if (!c.toff || !c.tlist || !c.comp || !c.cutkeys || !stack) {
        free(stack);
        cutter_free(&c);
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
    }
    for (size_t i = 0; i < 3 * g->nt; i++)
        c.toff[g->T[i] + 1]++;
    for (size_t v = 0; v < g->nv; v++)
        c.toff[v + 1] += c.toff[v];
    {
        size_t *fill = malloc((g->nv + 1) * sizeof *fill);
        if (!fill) {
            free(stack);
            cutter_free(&c);
            return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
        }
        memcpy(fill, c.toff, g->nv * sizeof *fill);
        for (size_t t = 0; t < g->nt; t++)
            for (int k = 0; k < 3; k++)
                c.tlist[fill[g->T[3 * t + k]]++] = (int32_t)t;
        free(fill);
    }
    size_t nk = 0;
    for (size_t i = 0; i + 1 < c.n1; i++)
        c.cutkeys[nk++] = ekey(c.p1[i], c.p1[i + 1]);
    for (size_t i = 0; i + 1 < c.n2; i++)
        c.cutkeys[nk++] = ekey(c.p2[i], c.p2[i + 1]);
    qsort(c.cutkeys, nk, sizeof *c.cutkeys, cmp_u64);
    for (size_t t = 0; t < g->nt; t++)
        c.comp[t] = -1;
    int32_t nc = 0;
    for (size_t t0 = 0; t0 < g->nt; t0++) {
        if (c.comp[t0] >= 0)
            continue;
        size_t top = 0;
        stack[top++] = (int32_t)t0;
        c.comp[t0] = nc;
        while (top) {
            int32_t t = stack[--top];
            for (int k = 0; k < 3; k++) {
                int32_t a = g->T[3 * t + k], b = g->T[3 * t + (k + 1) % 3];
                if (bsearch(&(uint64_t){ekey(a, b)}, c.cutkeys, nk, sizeof *c.cutkeys, cmp_u64))
                    continue;
                int32_t two[2];
                edge_tris(g, c.toff, c.tlist, a, b, two);
                for (int m = 0; m < 2; m++)
                    if (two[m] >= 0 && c.comp[two[m]] < 0) {
                        c.comp[two[m]] = nc;
                        stack[top++] = two[m];
                    }
            }
        }
        nc++;
    }
    free(stack);
    if (nc < 2) { /* the cuts did not separate anything: leave the sheet */
        cutter_free(&c);
        return FM_OK;
    }
    sp->pieces = calloc((size_t)nc, sizeof *sp->pieces);
    if (!sp->pieces) {
        cutter_free(&c);
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
    }
    for (int32_t id = 0; id < nc; id++) {
        st = piece_surface(g, mesh, c.comp, id, &sp->pieces[id], err);
        if (st != FM_OK) {
            cutter_free(&c);
            return st;
        }
        sp->npieces = (size_t)id + 1;
        /* a component is edge-connected and manifold: one sheet */
        if (fm_surface_nsheets(sp->pieces[id]) != 1) {
            cutter_free(&c);
            fm_model_split_free(sp);
            return FM_OK;
        }
    }
    /* Each cut joins the pieces on its two sides (taken at its first edge
     * inside the sheet; a cut is one edge at least). */
    for (int which = 0; which < 1 + ring && st == FM_OK; which++) {
        const int32_t *p = which ? c.p2 : c.p1;
        size_t n = which ? c.n2 : c.n1;
        int32_t two[2];
        edge_tris(g, c.toff, c.tlist, p[0], p[1], two);
        int32_t side[2] = {two[0] >= 0 ? c.comp[two[0]] : -1, two[1] >= 0 ? c.comp[two[1]] : -1};
        st = add_cut(sp, g, p, n, side, repair_sheet);
    }
    cutter_free(&c);
    return st == FM_OK ? FM_OK : fm_error_set(err, st, name, 0, "out of memory");
}

void fm_model_split_free(fm_model_split *sp)
{
    for (size_t i = 0; i < sp->npieces; i++) {
        fm_surface_destroy(sp->pieces[i]);
        if (sp->fits)
            fm_fit_pending_destroy(sp->fits[i]);
    }
    free(sp->pieces);
    free(sp->fits);
    fm_fit_pending_destroy(sp->whole);
    for (size_t i = 0; i < sp->ncuts; i++)
        free(sp->cuts[i].xyz);
    free(sp->cuts);
    memset(sp, 0, sizeof *sp);
}

/* Index in [from, to) of the piece whose sheet has the edge a-b (exact
 * coordinates: pieces copy them), or -1. */
static long piece_with_edge(fm_surface *const *pieces, size_t from, size_t to, const double a[3],
                            const double b[3])
{
    for (size_t i = from; i < to; i++) {
        const fm_mesh *m = fm_surface_sheet_mesh(pieces[i], 0);
        const double *X = fm_mesh_vertices(m);
        const int32_t *T = fm_mesh_triangles(m);
        for (size_t t = 0; t < fm_mesh_ntriangles(m); t++) {
            int has_a = 0, has_b = 0;
            for (int k = 0; k < 3; k++) {
                const double *p = X + 3 * T[3 * t + k];
                has_a |= memcmp(p, a, 3 * sizeof *p) == 0;
                has_b |= memcmp(p, b, 3 * sizeof *p) == 0;
            }
            if (has_a && has_b)
                return (long)i;
        }
    }
    return -1;
}

static fm_status append(fm_model_split *acc, fm_surface *piece, fm_fit_pending *fit,
                        const fm_split_cut *cut)
{
    if (piece) {
        fm_surface **p = realloc(acc->pieces, (acc->npieces + 1) * sizeof *p);
        if (p)
            acc->pieces = p;
        fm_fit_pending **f = realloc(acc->fits, (acc->npieces + 1) * sizeof *f);
        if (f)
            acc->fits = f;
        if (!p || !f)
            return FM_ERR_NOMEM;
        acc->fits[acc->npieces] = fit;
        acc->pieces[acc->npieces++] = piece;
    }
    if (cut) {
        fm_split_cut *c = realloc(acc->cuts, (acc->ncuts + 1) * sizeof *c);
        if (!c)
            return FM_ERR_NOMEM;
        acc->cuts = c;
        acc->cuts[acc->ncuts++] = *cut;
    }
    return FM_OK;
}

/* Splits recursively: pieces that are rings themselves are cut again. */
static fm_status split_rec(const char *name, const fm_surface *s, size_t sheet,
                           size_t repair_sheet, const fm_fit_options *fit, int depth,
                           fm_model_split *out, fm_error *err)
{
    memset(out, 0, sizeof *out);
    if (depth >= SPLIT_MAX_DEPTH || !needs_split(name, fm_surface_sheet_mesh(s, sheet),
                                                 fm_surface_sheet_nloops(s, sheet), fit, &out->whole))
        return FM_OK;
    fm_model_split sp;
    memset(&sp, 0, sizeof sp);
    fm_status st = cut_ring(s, sheet, repair_sheet, &sp, err, name);
    if (st != FM_OK || sp.npieces == 0) {
        fm_model_split_free(&sp);
        return st;
    }
    fm_model_split acc;
    memset(&acc, 0, sizeof acc);
    size_t *first = malloc((sp.npieces + 1) * sizeof *first);
    if (!first)
        st = FM_ERR_NOMEM;
    for (size_t i = 0; st == FM_OK && i < sp.npieces; i++) {
        first[i] = acc.npieces;
        fm_model_split sub;
        st = split_rec(name, sp.pieces[i], 0, repair_sheet, fit, depth + 1, &sub, err);
        if (st != FM_OK)
            break;
        if (!sub.npieces) {
            st = append(&acc, sp.pieces[i], sub.whole, NULL);
            if (st == FM_OK) {
                sp.pieces[i] = NULL;
                sub.whole = NULL;
            }
            fm_model_split_free(&sub);
            continue;
        }
        for (size_t q = 0; st == FM_OK && q < sub.npieces; q++) {
            st = append(&acc, sub.pieces[q], sub.fits[q], NULL);
            if (st == FM_OK) {
                sub.pieces[q] = NULL;
                sub.fits[q] = NULL;
            }
        }
        for (size_t q = 0; st == FM_OK && q < sub.ncuts; q++) {
            fm_split_cut cq = sub.cuts[q];
            for (int k = 0; k < 2; k++)
                if (cq.sheets[k] >= 0)
                    cq.sheets[k] += (long)first[i];
            st = append(&acc, NULL, NULL, &cq);
            if (st == FM_OK)
                sub.cuts[q].xyz = NULL;
        }
        fm_model_split_free(&sub);
    }
    if (first)
        first[sp.npieces] = acc.npieces;
    for (size_t i = 0; st == FM_OK && i < sp.ncuts; i++) {
        fm_split_cut cq = sp.cuts[i];
        for (int k = 0; k < 2; k++)
            if (cq.sheets[k] >= 0) {
                size_t c = (size_t)cq.sheets[k];
                cq.sheets[k] = piece_with_edge(acc.pieces, first[c], first[c + 1], cq.xyz,
                                               cq.xyz + 3);
            }
        st = append(&acc, NULL, NULL, &cq);
        if (st == FM_OK)
            sp.cuts[i].xyz = NULL;
    }
    free(first);
    fm_model_split_free(&sp);
    if (st != FM_OK) {
        fm_model_split_free(&acc);
        return err && st == FM_ERR_NOMEM ? fm_error_set(err, st, name, 0, "out of memory") : st;
    }
    *out = acc;
    return FM_OK;
}

fm_status fm_model_split_sheet(const char *name, const fm_surface *s, size_t sheet,
                               const fm_fit_options *fit, fm_model_split *out, fm_error *err)
{
    return split_rec(name, s, sheet, sheet, fit, 0, out, err);
}
