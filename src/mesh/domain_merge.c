/* Outline nodes closer than a quarter size merged (domain_merge_close).
 *
 * Each merge may not let the new chord cross any segment of the domain.
 * Asking every segment made the pass quadratic in the outline's nodes: a
 * crumpled fit whose outline runs 20,000 km at 463 m (43,449 nodes, found
 * by fuzz_fit_mesh) took 5 s. The segments are therefore kept in a uniform
 * grid over (u, v), and a loop's nodes in a linked list while it is
 * merged, so that a removal changes one segment (its predecessor's, which
 * is entered again for the cells of its new extent; stale entries are
 * passed over by their current ends). Decisions and their order are those
 * of the plain pass: the same domain comes out. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "remesh_internal.h"

/* Two outline nodes closer than this fraction of the size leave an edge
 * the mesh cannot grow away from: triangles of the size meet it at slivers
 * (two corners of a trimming curve 3 m apart where a spike was taken off
 * Rose Canyon made a 2.7 degree triangle at 1 km). */
#define MERGE_FRACTION 0.25
/* ... and one of them goes when that moves the outline by at most this
 * fraction of the size (in 3D, from the node to its neighbours' chord):
 * 20 m at 1 km, within the trimming curves' own 25 m. */
#define MERGE_DEVIATION 0.02
/* A segment over more cells than this goes to a list looked at always. */
#define WIDE_CELLS 16

typedef struct entry {
    uint32_t loop, node; /* the segment from this node to the next */
    int32_t next;        /* next entry of the cell, -1: none */
} entry;

/* The loop being merged: its nodes as a cyclic list over their indices. */
typedef struct live_loop {
    size_t l;
    size_t *nxt, *prv;
    unsigned char *alive;
    size_t n; /* alive */
} live_loop;

typedef struct seg_grid {
    double lo[2], cell;
    size_t nx, ny;
    int32_t *head;      /* per cell */
    entry *e;           /* pool */
    size_t ne, cap;
    int32_t wide;       /* list of wide segments */
    const remesh_domain *d;
    const live_loop *live;
} seg_grid;

/* Segment (loop, node) as it is now: its two ends; 0 if it is gone. */
static int segment(const seg_grid *g, uint32_t loop, uint32_t node, const double **a,
                   const double **b)
{
    const dom_loop *lp = &g->d->loops[loop];
    size_t to;
    if (loop == g->live->l) {
        if (!g->live->alive[node])
            return 0;
        to = g->live->nxt[node];
    } else {
        to = (node + 1) % lp->n;
    }
    *a = lp->uv + 2 * (size_t)node;
    *b = lp->uv + 2 * to;
    return 1;
}

static size_t cell_of(const seg_grid *g, double x, int axis)
{
    double t = floor((x - g->lo[axis]) / g->cell);
    size_t n = axis ? g->ny : g->nx;
    if (!(t > 0))
        return 0;
    return t >= (double)n ? n - 1 : (size_t)t;
}

static int push(seg_grid *g, int32_t *list, uint32_t loop, uint32_t node)
{
    if (g->ne == g->cap) {
        size_t cap = g->cap ? 2 * g->cap : 1024;
        entry *e = realloc(g->e, cap * sizeof *e);
        if (!e)
            return -1;
        g->e = e;
        g->cap = cap;
    }
    g->e[g->ne] = (entry){loop, node, *list};
    *list = (int32_t)g->ne++;
    return 0;
}

/* Enters segment (loop, node) as it is now into the cells its box meets. */
static int enter(seg_grid *g, uint32_t loop, uint32_t node)
{
    const double *a, *b;
    if (!segment(g, loop, node, &a, &b))
        return 0;
    size_t i0 = cell_of(g, fmin(a[0], b[0]), 0), i1 = cell_of(g, fmax(a[0], b[0]), 0);
    size_t j0 = cell_of(g, fmin(a[1], b[1]), 1), j1 = cell_of(g, fmax(a[1], b[1]), 1);
    if ((i1 - i0 + 1) * (j1 - j0 + 1) > WIDE_CELLS)
        return push(g, &g->wide, loop, node);
    for (size_t j = j0; j <= j1; j++)
        for (size_t i = i0; i <= i1; i++)
            if (push(g, &g->head[j * g->nx + i], loop, node))
                return -1;
    return 0;
}

static void grid_free(seg_grid *g)
{
    free(g->head);
    free(g->e);
    memset(g, 0, sizeof *g);
}

/* Every segment of d (loop live->l through its list). -1: out of memory. */
static int grid_build(seg_grid *g, const remesh_domain *d, const live_loop *live)
{
    memset(g, 0, sizeof *g);
    g->d = d;
    g->live = live;
    g->wide = -1;
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    size_t total = 0;
    for (size_t l = 0; l < d->n; l++)
        for (size_t i = 0; i < d->loops[l].n; i++, total++)
            for (int k = 0; k < 2; k++) {
                lo[k] = fmin(lo[k], d->loops[l].uv[2 * i + k]);
                hi[k] = fmax(hi[k], d->loops[l].uv[2 * i + k]);
            }
    double w = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(w > 0) || !isfinite(w))
        w = 1;
    /* about one segment per cell along the outline */
    g->cell = w / fmax(1.0, sqrt((double)total));
    g->nx = (size_t)fmin((hi[0] - lo[0]) / g->cell + 1, 4096.0);
    g->ny = (size_t)fmin((hi[1] - lo[1]) / g->cell + 1, 4096.0);
    g->nx = g->nx ? g->nx : 1;
    g->ny = g->ny ? g->ny : 1;
    g->lo[0] = lo[0];
    g->lo[1] = lo[1];
    g->head = malloc(g->nx * g->ny * sizeof *g->head);
    if (!g->head)
        return -1;
    for (size_t c = 0; c < g->nx * g->ny; c++)
        g->head[c] = -1;
    for (size_t l = 0; l < d->n; l++)
        for (size_t i = 0; i < d->loops[l].n; i++)
            if (enter(g, (uint32_t)l, (uint32_t)i))
                return -1;
    return 0;
}

static int crosses_list(const seg_grid *g, int32_t k, const double *a, const double *b,
                        const double box[4])
{
    for (; k >= 0; k = g->e[k].next) {
        const double *c, *e;
        if (segment(g, g->e[k].loop, g->e[k].node, &c, &e) &&
            chord_crosses_segment(a, b, box, c, e))
            return 1;
    }
    return 0;
}

/* 1 if the chord (a, b) crosses a segment of the domain not ending at a or b. */
static int chord_crosses(const seg_grid *g, const double *a, const double *b)
{
    double box[4] = {fmin(a[0], b[0]), fmax(a[0], b[0]), fmin(a[1], b[1]), fmax(a[1], b[1])};
    if (crosses_list(g, g->wide, a, b, box))
        return 1;
    size_t i0 = cell_of(g, box[0], 0), i1 = cell_of(g, box[1], 0);
    size_t j0 = cell_of(g, box[2], 1), j1 = cell_of(g, box[3], 1);
    for (size_t j = j0; j <= j1; j++)
        for (size_t i = i0; i <= i1; i++)
            if (crosses_list(g, g->head[j * g->nx + i], a, b, box))
                return 1;
    return 0;
}

/* How far (3D) the outline moves when node r goes: its distance to the
 * chord of its neighbours; INFINITY when it may not go (a sea-level node,
 * or a chord that would cross the domain's other segments). */
static double removal_cost(const fm_fit_surface *s, const seg_grid *g, const dom_loop *lp,
                           const live_loop *lv, size_t r)
{
    size_t p = lv->prv[r], nx = lv->nxt[r];
    if (lp->level[r] || chord_crosses(g, lp->uv + 2 * p, lp->uv + 2 * nx))
        return INFINITY;
    double a[3], b[3], c[3];
    fm_fit_surface_eval(s, lp->uv[2 * p], lp->uv[2 * p + 1], a, NULL, NULL);
    fm_fit_surface_eval(s, lp->uv[2 * r], lp->uv[2 * r + 1], b, NULL, NULL);
    fm_fit_surface_eval(s, lp->uv[2 * nx], lp->uv[2 * nx + 1], c, NULL, NULL);
    return fm_segment_distance3(b, a, c);
}

/* Removes node r: the segment that ends at r takes over up to r's
 * successor. Of two pieces of one trimming curve the parameter ranges
 * join; otherwise the longer segment's curve serves the whole (the other
 * is short: its end moves by its length at most). */
static void live_remove(const fm_fit_surface *s, dom_loop *lp, live_loop *lv, size_t r)
{
    size_t p = lv->prv[r], nx = lv->nxt[r];
    dom_seg *sp = &lp->seg[p], *sr = &lp->seg[r];
    if (sp->kind == SEG_TRIM && sr->kind == SEG_TRIM && sp->loop == sr->loop &&
        sp->piece == sr->piece && sp->tb == sr->ta)
        sp->tb = sr->tb;
    else if (surface_dist(s, lp->uv + 2 * r, lp->uv + 2 * nx) >
             surface_dist(s, lp->uv + 2 * p, lp->uv + 2 * r))
        *sp = *sr;
    lv->nxt[p] = nx;
    lv->prv[nx] = p;
    lv->alive[r] = 0;
    lv->n--;
}

/* The alive nodes moved to the front, in order. */
static void compact(dom_loop *lp, const live_loop *lv)
{
    size_t w = 0;
    for (size_t i = 0; i < lp->n; i++) {
        if (!lv->alive[i])
            continue;
        memmove(lp->uv + 2 * w, lp->uv + 2 * i, 2 * sizeof *lp->uv);
        lp->level[w] = lp->level[i];
        lp->seg[w] = lp->seg[i];
        w++;
    }
    lp->n = w;
}

/* Merges along loop l; the nodes removed, or SIZE_MAX when out of memory
 * (the loop unchanged then). */
static size_t merge_loop(const fm_fit_surface *s, remesh_domain *d, size_t l, double h)
{
    dom_loop *lp = &d->loops[l];
    size_t n = lp->n;
    live_loop lv = {l, malloc(n * sizeof(size_t)), malloc(n * sizeof(size_t)), calloc(n, 1), n};
    seg_grid g = {0};
    /* the list before the grid, which enters the loop's segments through it */
    for (size_t i = 0; lv.nxt && lv.prv && lv.alive && i < n; i++) {
        lv.nxt[i] = (i + 1) % n;
        lv.prv[i] = (i + n - 1) % n;
        lv.alive[i] = 1;
    }
    if (!lv.nxt || !lv.prv || !lv.alive || grid_build(&g, d, &lv)) {
        free(lv.nxt);
        free(lv.prv);
        free(lv.alive);
        grid_free(&g);
        return SIZE_MAX;
    }
    size_t removed = 0, c = 0;
    int oom = 0;
    /* c walks the nodes in order; "first" is the lowest alive index */
    while (lv.n > 3 && !oom) {
        size_t j = lv.nxt[c];
        double ci = INFINITY, cj = INFINITY;
        int close = surface_dist(s, lp->uv + 2 * c, lp->uv + 2 * j) < MERGE_FRACTION * h;
        if (close) {
            ci = removal_cost(s, &g, lp, &lv, c);
            cj = removal_cost(s, &g, lp, &lv, j);
        }
        if (!close || !(fmin(ci, cj) <= MERGE_DEVIATION * h)) {
            if (lv.nxt[c] <= c) /* past the last node */
                break;
            c = lv.nxt[c];
            continue;
        }
        /* the node whose removal moves the outline less; the segment that
         * now ends where it did is looked at again */
        size_t r = cj < ci ? j : c;
        size_t p = lv.prv[r];
        int c_first = lv.prv[c] > c;
        live_remove(s, lp, &lv, r);
        removed++;
        oom = enter(&g, (uint32_t)l, (uint32_t)p) != 0;
        if (r == c)
            c = c_first ? lv.nxt[p] : p;
    }
    /* out of memory entering a segment, the grid is incomplete: what was
     * merged stands (each merge was checked), the rest waits */
    grid_free(&g);
    compact(lp, &lv);
    free(lv.nxt);
    free(lv.prv);
    free(lv.alive);
    return removed;
}

size_t domain_merge_close(const fm_fit_surface *s, remesh_domain *d, double h)
{
    size_t removed = 0;
    for (size_t l = 0; l < d->n; l++) {
        if (d->loops[l].n <= 3)
            continue;
        size_t k = merge_loop(s, d, l, h);
        if (k != SIZE_MAX)
            removed += k;
    }
    return removed;
}
