/* Rectangular elements: the tiles at a fault's edges made to follow them
 * (tile_internal.h). A rectangle's end is a straight line down dip and its
 * top and bottom are level, so where an outline or a junction crosses a
 * row at a slant the row's end tile stands past the edge on one side and
 * leaves a wedge of surface bare on the other; its width, which makes its
 * area the surface's, only averages the two, and not at all where the
 * wedge is cut off by the other fault's tiles or the tile stands past a
 * sea-floor edge. Such a tile is cut into a quadtree of rectangles on its
 * plane: the box of its row's surface (its columns, and up to twice the
 * size past an end its contour stops at, and above and below it) is cut
 * in a grid of about a quarter of the size aligned on the tile. A cell
 * over the tile stays unless no surface of the fault lies within half the
 * size along the tile's normal from its centre (it stands past the edge);
 * a cell past the tile is added where that line meets the surface of its
 * row within a quarter of the size and no other tile of the fault lies
 * over the point (a wedge), moved along the normal onto the surface. The
 * kept cells are merged back into the largest aligned blocks: the tile
 * itself where all of it is kept. The tiled area then follows the outline
 * cell by cell, as a raster of the surface does, and the cells stay
 * planar and apart. It does not fill the thin gaps between rows that the
 * widths made up for, so the tiling picks, per fault, whether the refined
 * or the unrefined tiles match its area better (tile_fault_best). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tile_internal.h"
#include "fm_vec3.h"

/* Cells of the grid over one tile's box: at most this many a side. */
#define MAXC 24

typedef struct edge_ctx {
    fm_tiles *t;
    tile_walk *w;
    size_t first, n;  /* the fault's tiles as made: t->tile[first .. first + n) */
    fm_tile *orig;    /* their copies */
    double (*band)[4];
    unsigned char *gone; /* replaced by its cells */
    fm_tile *cell;    /* the cells made so far */
    size_t *cnext, ncell, ccap;
    size_t *head;     /* per tile: its first cell, or SIZE_MAX */
    tile_grid g;      /* over orig */
    double reach;
    /* the query of covered_by */
    const double *p;
    size_t self;
    int hit;
} edge_ctx;

static int over(const fm_tile *r, const double p[3], double size)
{
    double wd;
    int inside;
    if (r->length <= 0)
        return 0;
    tile_distance(r, p, &wd, &inside);
    return inside && fabs(wd) <= size / 2;
}

static int covered_fn(size_t j, void *user)
{
    edge_ctx *c = user;
    if (j == c->self)
        return 0;
    if (!c->gone[j]) {
        c->hit = over(&c->orig[j], c->p, c->t->stats.size);
    } else {
        for (size_t k = c->head[j]; k != SIZE_MAX && !c->hit; k = c->cnext[k])
            c->hit = over(&c->cell[k], c->p, c->t->stats.size);
    }
    return c->hit;
}

/* Whether a tile of the fault other than tile self (or its cells) lies
 * over surface point p. */
static int covered_by(edge_ctx *c, size_t self, const double p[3])
{
    c->p = p;
    c->self = self;
    c->hit = 0;
    tile_grid_near(&c->g, p, c->reach, covered_fn, c);
    return c->hit;
}

/* Where the line through q along n meets the surface w found, within lim
 * of q and between levels zbot and ztop: the triangle (-1 for none) and
 * the point in p. */
static int32_t meet(const tile_walk *w, const double *up, const double q[3], const double n[3],
                    double lim, double zbot, double ztop, double p[3])
{
    int32_t best = -1;
    double bs = INFINITY;
    for (size_t i = 0; i < w->n; i++) {
        size_t t = (size_t)w->list[i];
        const double *a = w->x + 3 * (size_t)w->tri[3 * t], *b = w->x + 3 * (size_t)w->tri[3 * t + 1],
                     *c = w->x + 3 * (size_t)w->tri[3 * t + 2];
        double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]}, pv[3], qv[3];
        fm_cross3(n, e2, pv);
        double det = fm_dot3(e1, pv);
        if (fabs(det) < 1e-12 * fm_dot3(e1, e1))
            continue; /* the triangle edge-on to the line */
        double tv[3] = {q[0] - a[0], q[1] - a[1], q[2] - a[2]};
        double u = fm_dot3(tv, pv) / det;
        if (u < 0 || u > 1)
            continue;
        fm_cross3(tv, e1, qv);
        double v = fm_dot3(n, qv) / det;
        if (v < 0 || u + v > 1)
            continue;
        double s = fm_dot3(e2, qv) / det;
        if (fabs(s) > lim || fabs(s) >= fabs(bs))
            continue;
        double h[3] = {q[0] + s * n[0], q[1] + s * n[1], q[2] + s * n[2]};
        double lv = tile_level(up, h);
        if (lv < zbot || lv > ztop)
            continue;
        bs = s;
        best = (int32_t)t;
        memcpy(p, h, sizeof h);
    }
    return best;
}

/* The box (in the tile's strike u and dip v about its centre) of the
 * surface w found between levels zbot and ztop, between u0 and u1; 0 when
 * none of it is there. */
static int surface_box(const tile_walk *w, const fm_tile *tl, const double *up, double zbot,
                       double ztop, double u0, double u1, double box[4])
{
    box[0] = box[2] = INFINITY;
    box[1] = box[3] = -INFINITY;
    for (size_t i = 0; i < w->n; i++) {
        double poly[2][12][3];
        int n = 3, cur = 0;
        for (int k = 0; k < 3; k++)
            memcpy(poly[0][k], w->x + 3 * (size_t)w->tri[3 * (size_t)w->list[i] + (size_t)k],
                   sizeof poly[0][k]);
        for (int plane = 0; plane < 4 && n > 0; plane++) {
            double f[12];
            for (int k = 0; k < n; k++) {
                const double *p = poly[cur][k];
                double r[3] = {p[0] - tl->centre[0], p[1] - tl->centre[1], p[2] - tl->centre[2]};
                double u = fm_dot3(r, tl->strike);
                f[k] = plane == 0   ? u - u0
                       : plane == 1 ? u1 - u
                       : plane == 2 ? tile_level(up, p) - zbot
                                    : ztop - tile_level(up, p);
            }
            int m = 0;
            for (int k = 0; k < n; k++) {
                int j = (k + 1) % n;
                const double *a = poly[cur][k], *b = poly[cur][j];
                if (f[k] >= 0 && m < 12)
                    memcpy(poly[1 - cur][m++], a, 3 * sizeof *a);
                if ((f[k] >= 0) != (f[j] >= 0) && m < 12) {
                    double s = f[k] / (f[k] - f[j]);
                    for (int d = 0; d < 3; d++)
                        poly[1 - cur][m][d] = a[d] + s * (b[d] - a[d]);
                    m++;
                }
            }
            n = m;
            cur = 1 - cur;
        }
        for (int k = 0; k < n; k++) {
            const double *p = poly[cur][k];
            double r[3] = {p[0] - tl->centre[0], p[1] - tl->centre[1], p[2] - tl->centre[2]};
            double u = fm_dot3(r, tl->strike), v = fm_dot3(r, tl->dip);
            box[0] = fmin(box[0], u);
            box[1] = fmax(box[1], u);
            box[2] = fmin(box[2], v);
            box[3] = fmax(box[3], v);
        }
    }
    return box[0] <= box[1];
}

/* The grid over one tile's box, aligned on the tile: cell (i, j) spans u
 * from -L/2 + i cu and v from -W/2 + j cv (tile frame about its centre),
 * i from i0, j from j0; per cell whether it is kept, the triangle under
 * its centre and how far along the tile's normal the surface lies there. */
typedef struct cells {
    const fm_tile *tl;
    long i0, j0, ni, nj;
    double cu, cv;
    unsigned char keep[MAXC * MAXC];
    int32_t tri[MAXC * MAXC];
    double off[MAXC * MAXC];
} cells;

static int push_cell(edge_ctx *c, size_t parent, const fm_tile *cl)
{
    if (c->ncell == c->ccap) {
        size_t cap = c->ccap ? 2 * c->ccap : 64;
        fm_tile *nc = realloc(c->cell, cap * sizeof *nc);
        if (nc)
            c->cell = nc;
        size_t *nx = realloc(c->cnext, cap * sizeof *nx);
        if (nx)
            c->cnext = nx;
        if (!nc || !nx)
            return -1;
        c->ccap = cap;
    }
    /* in the order made, after the parent's earlier cells */
    c->cell[c->ncell] = *cl;
    c->cnext[c->ncell] = SIZE_MAX;
    size_t *at = &c->head[parent];
    while (*at != SIZE_MAX)
        at = &c->cnext[*at];
    *at = c->ncell++;
    return 0;
}

/* The kept cells of block [a0, a1) x [b0, b1) (grid indices) as the fewest
 * aligned rectangles: the block whole where all of it is kept, else its
 * halves (quarters) in turn. Past the tile (moved) a rectangle is moved
 * along the normal onto its surface, its plane parallel to the tile's. */
static int emit(edge_ctx *c, size_t parent, const cells *g, long a0, long a1, long b0, long b1,
                int moved)
{
    long lo_a = a0 > g->i0 ? a0 : g->i0, hi_a = a1 < g->i0 + g->ni ? a1 : g->i0 + g->ni;
    long lo_b = b0 > g->j0 ? b0 : g->j0, hi_b = b1 < g->j0 + g->nj ? b1 : g->j0 + g->nj;
    if (lo_a >= hi_a || lo_b >= hi_b)
        return 0;
    long kept = 0, all = (a1 - a0) * (b1 - b0);
    int32_t tri = -1;
    double bestd = INFINITY, ac = (double)(a0 + a1) / 2, bc = (double)(b0 + b1) / 2, off = 0;
    for (long i = lo_a; i < hi_a; i++)
        for (long j = lo_b; j < hi_b; j++) {
            size_t k = (size_t)((i - g->i0) * g->nj + (j - g->j0));
            if (!g->keep[k])
                continue;
            kept++;
            off += g->off[k];
            /* the triangle under the kept cell nearest the block's centre */
            double d = fabs((double)i + 0.5 - ac) + fabs((double)j + 0.5 - bc);
            if (d < bestd) {
                bestd = d;
                tri = g->tri[k];
            }
        }
    if (!kept)
        return 0;
    if (kept == all) {
        const fm_tile *tl = g->tl;
        fm_tile cl = *tl;
        double n[3];
        tile_normal(tl, n);
        double u0 = -tl->length / 2 + (double)a0 * g->cu, u1 = -tl->length / 2 + (double)a1 * g->cu;
        double v0 = -tl->width / 2 + (double)b0 * g->cv, v1 = -tl->width / 2 + (double)b1 * g->cv;
        double s = moved ? off / (double)kept : 0;
        for (int d = 0; d < 3; d++)
            cl.centre[d] += (u0 + u1) / 2 * tl->strike[d] + (v0 + v1) / 2 * tl->dip[d] + s * n[d];
        cl.length = u1 - u0;
        cl.width = v1 - v0;
        cl.triangle = tri;
        /* the top edge only where the tile's was */
        if (b0 > 0)
            cl.row = tl->row + 1;
        return push_cell(c, parent, &cl);
    }
    if (a1 - a0 <= 1 && b1 - b0 <= 1)
        return 0;
    long am = a1 - a0 > 1 ? (a0 + a1) / 2 : a1, bm = b1 - b0 > 1 ? (b0 + b1) / 2 : b1;
    return emit(c, parent, g, a0, am, b0, bm, moved) || emit(c, parent, g, am, a1, b0, bm, moved) ||
           emit(c, parent, g, a0, am, bm, b1, moved) || emit(c, parent, g, am, a1, bm, b1, moved);
}

static long floor_div(double x, double d) { return (long)floor(x / d + 1e-9); }

/* Tile k of the fault refined where it and its row's surface differ; -1
 * when memory runs out. */
static int refine(edge_ctx *c, size_t k)
{
    const fm_tile *tl = &c->orig[k];
    const double *b = c->band[k];
    double size = c->t->stats.size, L = tl->length, W = tl->width;
    if (L <= 0 || W <= 0)
        return 0;
    tile_walk *w = c->w;
    const double *up = w->up[tl->fault];
    double ztop = b[0], zbot = b[1];
    int open = (int)b[3];
    if (!(ztop > zbot))
        return 0;
    /* Over the tile a cell goes only where no surface at all lies within
     * half the size of it (the tile stood there before); past it a cell
     * must find its row's surface within a quarter of the size (a tile's
     * plane departs from a curving fault as it goes on). */
    double ext = 2 * size, lim = size / 4, limin = size / 2, n[3];
    tile_normal(tl, n);
    w->open = open;
    tile_region(w, tl, zbot - limin, ztop + limin);
    w->open = 0;
    double u0 = -L / 2 - (open & 1 ? ext : 0), u1 = L / 2 + (open & 2 ? ext : 0);
    double box[4];
    if (!surface_box(w, tl, up, zbot, ztop, u0, u1, box)) {
        box[0] = box[1] = box[2] = box[3] = 0;
    }
    cells *g = malloc(sizeof *g);
    if (!g)
        return -1;
    g->tl = tl;
    long kl = lround(L / (size / 4)), kw = lround(W / (size / 4));
    kl = kl < 1 ? 1 : kl;
    kw = kw < 1 ? 1 : kw;
    g->cu = L / (double)kl;
    g->cv = W / (double)kw;
    box[2] = fmax(box[2], -W / 2 - ext);
    box[3] = fmin(box[3], W / 2 + ext);
    /* the grid: the tile's cells and those of the box beside it */
    g->i0 = floor_div(box[0] + L / 2, g->cu);
    long i1 = -floor_div(-(box[1] + L / 2), g->cu);
    g->j0 = floor_div(box[2] + W / 2, g->cv);
    long j1 = -floor_div(-(box[3] + W / 2), g->cv);
    g->i0 = g->i0 > 0 ? 0 : g->i0;
    g->j0 = g->j0 > 0 ? 0 : g->j0;
    i1 = i1 < kl ? kl : i1;
    j1 = j1 < kw ? kw : j1;
    g->ni = i1 - g->i0;
    g->nj = j1 - g->j0;
    if (g->ni > MAXC || g->nj > MAXC) {
        free(g);
        return 0; /* a box far larger than the tile: left as it is */
    }
    int same = 1;
    for (long i = 0; i < g->ni; i++)
        for (long j = 0; j < g->nj; j++) {
            long a = g->i0 + i, bb = g->j0 + j;
            double u = -L / 2 + ((double)a + 0.5) * g->cu, v = -W / 2 + ((double)bb + 0.5) * g->cv;
            double q[3], p[3];
            for (int d = 0; d < 3; d++)
                q[d] = tl->centre[d] + u * tl->strike[d] + v * tl->dip[d];
            size_t m = (size_t)(i * g->nj + j);
            int in = a >= 0 && a < kl && bb >= 0 && bb < kw;
            g->tri[m] = !(u >= u0 && u <= u1) ? -1
                        : in ? meet(w, up, q, n, limin, -INFINITY, INFINITY, p)
                             : meet(w, up, q, n, lim, zbot, ztop, p);
            g->off[m] = g->tri[m] >= 0 ? fm_dot3(n, p) - fm_dot3(n, q) : 0;
            /* past the tile only where no other tile of the fault is (the
             * next row's, a quarter contour's, the next contour's) */
            g->keep[m] = g->tri[m] >= 0 && (in || !covered_by(c, k, p));
            same &= g->keep[m] == in;
        }
    if (same) {
        free(g);
        return 0;
    }
    c->gone[k] = 1;
    /* blocks of the tile's own size, aligned on it */
    int bad = 0;
    for (long a = floor_div((double)g->i0, (double)kl); !bad && a * kl < g->i0 + g->ni; a++)
        for (long bb = floor_div((double)g->j0, (double)kw); !bad && bb * kw < g->j0 + g->nj; bb++)
            bad = emit(c, k, g, a * kl, (a + 1) * kl, bb * kw, (bb + 1) * kw, a || bb);
    free(g);
    return bad ? -1 : 0;
}

int tile_refine_edges(fm_tiles *t, tile_walk *w, size_t first)
{
    size_t n = t->n - first;
    if (!n)
        return 0;
    edge_ctx c = {.t = t, .w = w, .first = first, .n = n};
    c.orig = malloc(n * sizeof *c.orig);
    c.band = malloc(n * sizeof *c.band);
    c.gone = calloc(n, 1);
    c.head = malloc(n * sizeof *c.head);
    int bad = !c.orig || !c.band || !c.gone || !c.head;
    double rmax = 0;
    if (!bad) {
        memcpy(c.orig, t->tile + first, n * sizeof *c.orig);
        memcpy(c.band, t->band + first, n * sizeof *c.band);
        for (size_t i = 0; i < n; i++) {
            c.head[i] = SIZE_MAX;
            rmax = fmax(rmax, 0.5 * hypot(c.orig[i].length, c.orig[i].width));
        }
        /* a cell lies within its tile's box: 2 sizes past its sides */
        c.reach = rmax + 3 * t->stats.size;
        fm_tiles view = {.tile = c.orig, .n = n};
        bad = tile_grid_make(&c.g, &view, c.reach);
    }
    for (size_t i = 0; !bad && i < n; i++)
        bad = refine(&c, i);
    /* the fault's tiles again, each replaced one by its cells where it was */
    if (!bad) {
        t->n = first;
        for (size_t i = 0; !bad && i < n; i++) {
            if (!c.gone[i]) {
                bad = tile_push(t, &c.orig[i], c.band[i][0], c.band[i][1], c.band[i][2],
                                (int)c.band[i][3]);
                continue;
            }
            for (size_t k = c.head[i]; !bad && k != SIZE_MAX; k = c.cnext[k])
                bad = tile_push(t, &c.cell[k], c.band[i][0], c.band[i][1], c.band[i][2],
                                (int)c.band[i][3]);
        }
    }
    free(c.orig);
    free(c.band);
    free(c.gone);
    free(c.head);
    free(c.cell);
    free(c.cnext);
    free(c.g.e);
    return bad ? -1 : 0;
}
