/* Rectangular elements: tiles grown into the bare surface beside them
 * (tile_internal.h). The rows' widths only average a row's surface, the
 * staircase of cuts where a junction crosses rows at a slant stops each
 * tile short of the junction, and the cut that keeps two faults' tiles
 * apart (tile_separate) takes a whole strip off the tile that loses less:
 * between them they leave strips of surface, tens to hundreds of metres
 * wide, that no tile covers (on the whole CFM at 2 km, 31 faults lost over
 * 3 % of their area to them). Each fault's surface is sampled on a
 * triangular grid of about a sixth of the size; the samples no tile of the
 * fault stands over are the bare surface. While the fault's tiles cover
 * less than its area, each tile in turn pushes each of its four sides out
 * as far as the bare surface beyond it reaches (up to half the size, the
 * tile staying under 1.5 times the size), where that surface lies within
 * the flatness bound of the tile's plane and fills half the strip or
 * more, the surface the grown tile stands for lies no farther from its
 * plane than before, and it runs into no other fault's tile (by the same
 * exact test as tile_separate; halved until it does not). Then squares
 * fill the wedges no side could grow into. The samples a grown tile or a
 * square stands over are no longer bare, so two never take the same
 * strip; and no fault's tiles grow past its area, since where tiles lean
 * away from a bending surface the samples under them count as bare. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tile_internal.h"
#include "fm_vec3.h"

/* Sample spacing, as a fraction of the size. */
#define SPACING (1.0 / 6)
/* Share of a strip (or a square) the bare samples under it must fill:
 * half, so that a side grown across a wedge of bare surface (an outline
 * or junction running at a slant to it) stands past the edge by as much
 * as it covers, as a row's width averages its surface (tile.c). */
#define FILL 0.5
/* Normal distance within which a sample lies under a tile (as covering
 * it) and, for growing, within the flatness bound of tile_fit_planes. */
#define COVER (1.0 / 4)
#define FLAT (1.0 / 25)

typedef struct sample {
    double p[3];
    double area;
    int32_t tri;
    int taken; /* under a tile */
} sample;

typedef struct grow_ctx {
    fm_tiles *t;
    size_t first, last; /* the fault's tiles */
    sample *s;
    size_t ns, cap;
    tile_grid own;   /* while filling: the fault's tiles, as grown */
    double own_r;    /* their largest radius: the grid's cell and reach */
    tile_grid samp;  /* its samples */
    tile_grid all;   /* every tile, as separated */
    double reach;    /* for all */
    /* one query's findings */
    const fm_tile *tl;
    size_t *cand;
    size_t nc, ccap;
    int hit;
    double pt[3];
    tile_walk *w;
    fm_tile *fill;   /* squares added, every fault's so far */
    size_t nfill, fcap, fill_first; /* this fault's from fill_first on */
} grow_ctx;

/* Whether tile b stands over point p: p projects into it, within the
 * normal distance a sample counts as covered at. */
static int stands_over(const grow_ctx *c, const fm_tile *b, const double p[3])
{
    double w;
    int inside;
    tile_distance(b, p, &w, &inside);
    return inside && fabs(w) <= COVER * c->t->stats.size;
}

/* Grid callbacks over the fault's tiles (j from c->first): whether one
 * stands over c->pt. */
static int over_point(size_t j, void *user)
{
    grow_ctx *c = user;
    c->hit = stands_over(c, &c->t->tile[c->first + j], c->pt);
    return c->hit;
}

static int take(size_t j, void *user)
{
    grow_ctx *c = user;
    if (stands_over(c, c->tl, c->s[j].p))
        c->s[j].taken = 1;
    return 0;
}

/* The fault's surface sampled, the samples a tile of it covers dropped. */
static int sample_fault(grow_ctx *c, const fm_mesh *set, const size_t *tris, size_t n)
{
    const double *x = fm_mesh_vertices(set);
    const int32_t *tri = fm_mesh_triangles(set);
    double h = SPACING * c->t->stats.size;
    c->ns = 0;
    for (size_t i = 0; i < n; i++) {
        const double *v[3];
        for (int k = 0; k < 3; k++)
            v[k] = x + 3 * (size_t)tri[3 * tris[i] + (size_t)k];
        double e = 0;
        for (int k = 0; k < 3; k++)
        {
            const double *a = v[k], *b = v[(k + 1) % 3];
            double r[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            e = fmax(e, sqrt(fm_dot3(r, r)));
        }
        int m = (int)fmin(64, ceil(e / h));
        m = m < 1 ? 1 : m;
        double w = fm_triangle_area(v[0], v[1], v[2]) / ((double)m * m);
        for (int a = 0; a < m; a++)
            for (int b = 0; a + b < m; b++)
                for (int up = 0; up < 2; up++) {
                    if (up && a + b > m - 2)
                        continue;
                    double la = (a + (up ? 2.0 : 1.0) / 3) / m, lb = (b + (up ? 2.0 : 1.0) / 3) / m;
                    if (c->ns == c->cap) {
                        c->cap = c->cap ? 2 * c->cap : 4096;
                        sample *ns = realloc(c->s, c->cap * sizeof *ns);
                        if (!ns)
                            return -1;
                        c->s = ns;
                    }
                    sample *sp = &c->s[c->ns];
                    for (int d = 0; d < 3; d++)
                        sp->p[d] = v[0][d] + la * (v[1][d] - v[0][d]) + lb * (v[2][d] - v[0][d]);
                    sp->area = w;
                    sp->tri = (int32_t)tris[i];
                    sp->taken = 0;
                    c->ns++;
                }
    }
    /* each tile marks the samples it stands over (a point a tile stands
     * over lies within its radius of its centre), which leave */
    if (!c->ns)
        return 0;
    if (tile_grid_make_points(&c->samp, c->s[0].p, sizeof *c->s, c->ns, c->t->stats.size))
        return -1;
    for (size_t i = c->first; i < c->last; i++) {
        c->tl = &c->t->tile[i];
        tile_grid_near(&c->samp, c->tl->centre, 0.5 * hypot(c->tl->length, c->tl->width), take,
                       c);
    }
    free(c->samp.e);
    c->samp.e = NULL;
    size_t m = 0;
    for (size_t i = 0; i < c->ns; i++)
        if (!c->s[i].taken)
            c->s[m++] = c->s[i];
    c->ns = m;
    return 0;
}

static int gather(size_t j, void *user)
{
    grow_ctx *c = user;
    if (c->nc == c->ccap) {
        c->ccap = c->ccap ? 2 * c->ccap : 256;
        size_t *nc = realloc(c->cand, c->ccap * sizeof *nc);
        if (!nc) {
            c->hit = -1;
            return 1;
        }
        c->cand = nc;
    }
    c->cand[c->nc++] = j;
    return 0;
}

static int meets_other(size_t j, void *user)
{
    grow_ctx *c = user;
    const fm_tile *a = c->tl, *b = &c->t->tile[j];
    if (tile_same_unit(a, b))
        return 0;
    double r[3] = {a->centre[0] - b->centre[0], a->centre[1] - b->centre[1],
                   a->centre[2] - b->centre[2]};
    if (sqrt(fm_dot3(r, r)) > 0.5 * (hypot(a->length, a->width) + hypot(b->length, b->width)))
        return 0;
    if (tile_meet(a, b)) {
        c->hit = 1;
        return 1;
    }
    return 0;
}

static int meets_fill(grow_ctx *c, const fm_tile *a)
{
    for (size_t j = 0; j < c->fill_first; j++) {
        const fm_tile *b = &c->fill[j];
        double r[3] = {a->centre[0] - b->centre[0], a->centre[1] - b->centre[1],
                       a->centre[2] - b->centre[2]};
        if (sqrt(fm_dot3(r, r)) <= 0.5 * (hypot(a->length, a->width) + hypot(b->length, b->width)) &&
            tile_meet(a, b))
            return 1;
    }
    return 0;
}

/* Where a sample lies in a tile's frame: along strike, down dip, along
 * the normal from its centre. */
static void frame(const fm_tile *tl, const double p[3], double uvw[3])
{
    double r[3] = {p[0] - tl->centre[0], p[1] - tl->centre[1], p[2] - tl->centre[2]}, n[3];
    tile_normal(tl, n);
    uvw[0] = fm_dot3(r, tl->strike);
    uvw[1] = fm_dot3(r, tl->dip);
    uvw[2] = fm_dot3(r, n);
}

typedef struct reach_at {
    double depth, area;
} reach_at;

static int by_depth(const void *a, const void *b)
{
    double x = ((const reach_at *)a)->depth, y = ((const reach_at *)b)->depth;
    return (x > y) - (x < y);
}

/* The tile grown by e on side k (0, 1: the end and the start of its
 * strike; 2, 3: its bottom and top). */
static fm_tile grown(const fm_tile *a, int k, double e)
{
    fm_tile g = *a;
    const double *dir = k < 2 ? a->strike : a->dip;
    double sg = k % 2 ? -0.5 : 0.5;
    for (int d = 0; d < 3; d++)
        g.centre[d] += sg * e * dir[d];
    if (k < 2)
        g.length += e;
    else
        g.width += e;
    return g;
}

/* Whether any of a 3 x 3 grid of points over square q lies over a tile
 * of the fault or a square added to it before (within the normal distance
 * a sample counts as covered at: a strand a few hundred metres beside
 * this one does not hold it off). */
static int over_own(grow_ctx *c, const fm_tile *q)
{
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            double da = q->length * (a - 1) / 3, db = q->width * (b - 1) / 3;
            for (int d = 0; d < 3; d++)
                c->pt[d] = q->centre[d] + da * q->strike[d] + db * q->dip[d];
            c->hit = 0;
            tile_grid_near(&c->own, c->pt, c->own_r, over_point, c);
            for (size_t j = c->fill_first; j < c->nfill && !c->hit; j++)
                c->hit = stands_over(c, &c->fill[j], c->pt);
            if (c->hit)
                return 1;
        }
    return 0;
}

/* Whether side k of tile tl may grow by e: it runs into no other fault's
 * tile or square, and the surface the grown tile stands for (a strand
 * beside this one, a bend beyond the strip) lies no farther from its
 * plane than from the tile's as it was, or the flatness bound. */
static int grow_passes(grow_ctx *c, const fm_tile *tl, int k, double e)
{
    fm_tile g = grown(tl, k, e);
    c->tl = &g;
    c->hit = 0;
    tile_grid_near(&c->all, g.centre, c->reach, meets_other, c);
    if (c->hit || meets_fill(c, &g))
        return 0;
    double H = c->t->stats.size;
    return tile_flat_as_is(c->w, &g) <= fmax(tile_flat_as_is(c->w, tl), FLAT * H);
}

/* How far side k of tile i grows: 0 when it does not. */
static double grow_side(grow_ctx *c, size_t i, int k, reach_at **buf, size_t *bcap)
{
    fm_tile *tl = &c->t->tile[i];
    double H = c->t->stats.size;
    double along = k < 2 ? tl->length : tl->width, across = k < 2 ? tl->width : tl->length;
    double emax = fmin(H / 2, 1.5 * H - along);
    if (!(emax > H / 40))
        return 0;
    if (*bcap < c->nc + 1) {
        reach_at *nb = realloc(*buf, (c->nc + 1) * sizeof *nb);
        if (!nb)
            return -1;
        *buf = nb;
        *bcap = c->nc + 1;
    }
    size_t m = 0;
    for (size_t q = 0; q < c->nc; q++) {
        if (c->s[c->cand[q]].taken)
            continue;
        double uvw[3];
        frame(tl, c->s[c->cand[q]].p, uvw);
        double a = k < 2 ? uvw[0] : uvw[1], b = k < 2 ? uvw[1] : uvw[0];
        double d = (k % 2 ? -a : a) - along / 2;
        if (d >= 0 && d <= emax && fabs(b) <= across / 2 && fabs(uvw[2]) <= FLAT * H)
            (*buf)[m++] = (reach_at){d, c->s[c->cand[q]].area};
    }
    if (!m)
        return 0;
    qsort(*buf, m, sizeof **buf, by_depth);
    double e = 0, sum = 0;
    for (size_t q = 0; q < m; q++) {
        sum += (*buf)[q].area;
        double ek = fmin(emax, (*buf)[q].depth + 0.5 * sqrt((*buf)[q].area));
        if (sum >= FILL * ek * across)
            e = ek;
    }
    /* the longest growth up to e that passes: halved until one does,
     * then bisected towards the one that failed, so that a side grown
     * towards another fault's tiles stops within a thirty-second of its
     * growth of them rather than up to half of it short */
    double ok = 0, fail = 0;
    for (; e >= H / 40 && !ok; e /= 2) {
        if (grow_passes(c, tl, k, e))
            ok = e;
        else
            fail = e;
    }
    for (int b = 0; ok > 0 && fail > 0 && b < 5; b++) {
        double mid = 0.5 * (ok + fail);
        if (grow_passes(c, tl, k, mid))
            ok = mid;
        else
            fail = mid;
    }
    return ok;
}


/* Squares of half, a quarter and an eighth of the size, on bare samples
 * in turn while the fault's tiles fall short of its area: where a
 * junction crosses the rows at a slant the wedges between the staircase
 * of tiles and the other fault's tiles stay bare, and no side of a whole
 * tile can grow into them. */
static int fill_bare(grow_ctx *c, const fm_mesh *set, double atri, double atiles)
{
    const double *x = fm_mesh_vertices(set);
    const int32_t *tri = fm_mesh_triangles(set);
    double H = c->t->stats.size;
    static const double level[3] = {1, 0, 0};
    /* a point a tile stands over lies within its radius of its centre */
    c->own_r = H / 4;
    for (size_t i = c->first; i < c->last; i++)
        c->own_r = fmax(c->own_r, 0.5 * hypot(c->t->tile[i].length, c->t->tile[i].width));
    if (tile_grid_make_points(&c->own, c->t->tile[c->first].centre, sizeof *c->t->tile,
                              c->last - c->first, c->own_r))
        return -1;
    for (size_t q = 0; q < c->ns && atiles < atri; q++) {
        if (c->s[q].taken)
            continue;
        for (double sz = H / 2; sz >= H / 8; sz /= 2) {
            fm_tile sq;
            if (!tile_square(x, tri, (size_t)c->s[q].tri, c->t->tile[c->first].fault, c->s[q].p,
                             sz, level, &sq))
                break;
            c->nc = 0;
            c->hit = 0;
            tile_grid_near(&c->samp, sq.centre, sz, gather, c);
            if (c->hit < 0)
                return -1;
            double bare = 0;
            for (size_t r = 0; r < c->nc; r++) {
                const sample *sp = &c->s[c->cand[r]];
                double w;
                int inside;
                tile_distance(&sq, sp->p, &w, &inside);
                if (!sp->taken && inside && fabs(w) <= FLAT * H)
                    bare += sp->area;
            }
            if (bare < FILL * sz * sz || over_own(c, &sq) ||
                tile_flat_as_is(c->w, &sq) > FLAT * H)
                continue;
            c->tl = &sq;
            c->hit = 0;
            tile_grid_near(&c->all, sq.centre, c->reach, meets_other, c);
            if (c->hit || meets_fill(c, &sq))
                continue;
            if (c->nfill == c->fcap) {
                c->fcap = c->fcap ? 2 * c->fcap : 256;
                fm_tile *nf = realloc(c->fill, c->fcap * sizeof *nf);
                if (!nf)
                    return -1;
                c->fill = nf;
            }
            c->fill[c->nfill++] = sq;
            atiles += sz * sz;
            c->tl = &sq;
            tile_grid_near(&c->samp, sq.centre, sz + H / 8, take, c);
            break;
        }
    }
    return 0;
}

static int grow_fault(grow_ctx *c, const fm_mesh *set, const size_t *tris, size_t n)
{
    double H = c->t->stats.size;
    c->fill_first = c->nfill;
    c->own.e = c->samp.e = NULL;
    int bad = sample_fault(c, set, tris, n);
    if (!bad && c->ns)
        bad = tile_grid_make_points(&c->samp, c->s[0].p, sizeof *c->s, c->ns, H);
    /* the tiles grow while their area falls short of the surface's: where
     * tiles lean away from a surface that bends (a ramp into a flat) the
     * samples under them count as bare */
    double atri = c->t->fault[c->t->tile[c->first].fault].area_triangles, atiles = 0;
    for (size_t i = c->first; i < c->last; i++)
        atiles += c->t->tile[i].length * c->t->tile[i].width;
    reach_at *buf = NULL;
    size_t bcap = 0;
    for (int round = 0; round < 2 && !bad && c->ns; round++)
        for (size_t i = c->first; i < c->last && !bad && atiles < atri; i++) {
            /* the samples any growth of this round may reach: each side
             * grows by at most half the size */
            const fm_tile *t0 = &c->t->tile[i];
            c->nc = 0;
            c->hit = 0;
            tile_grid_near(&c->samp, t0->centre,
                           0.5 * hypot(t0->length + H, t0->width + H) + H / 8, gather, c);
            bad = c->hit < 0;
            for (int k = 0; k < 4 && !bad; k++) {
                double e = grow_side(c, i, k, &buf, &bcap);
                if (e < 0)
                    bad = 1;
                else if (e > 0) {
                    fm_tile *tl = &c->t->tile[i];
                    atiles -= tl->length * tl->width;
                    *tl = grown(tl, k, e);
                    atiles += tl->length * tl->width;
                    c->tl = tl;
                    tile_grid_near(&c->samp, tl->centre,
                                   0.5 * hypot(tl->length, tl->width) + H, take, c);
                }
            }
        }
    if (!bad && atiles < atri)
        bad = fill_bare(c, set, atri, atiles);
    free(buf);
    free(c->own.e);
    free(c->samp.e);
    c->own.e = c->samp.e = NULL;
    return bad ? -1 : 0;
}

int tile_grow(fm_tiles *t, const fm_mesh *set, tile_walk *w, const size_t *order,
              const size_t *start)
{
    if (!t->n)
        return 0;
    grow_ctx c = {.t = t, .w = w};
    double rmax = 0;
    for (size_t i = 0; i < t->n; i++)
        rmax = fmax(rmax, 0.5 * hypot(t->tile[i].length, t->tile[i].width));
    /* a grown tile stays under 1.5 times the size a side, and its centre
     * moves by under the size: the pairs that may meet lie within reach
     * of each other's centres as separated */
    c.reach = 2 * fmax(rmax, 1.1 * t->stats.size) + 2 * t->stats.size;
    int bad = tile_grid_make(&c.all, t, c.reach);
    /* the tiles are in fault order (tile_by_fault) */
    for (size_t i = 0; !bad && i < t->n;) {
        size_t j = i;
        while (j < t->n && t->tile[j].fault == t->tile[i].fault)
            j++;
        int32_t f = t->tile[i].fault;
        c.first = i;
        c.last = j;
        if (tile_active(t, f))
            bad = grow_fault(&c, set, order + start[f], start[f + 1] - start[f]) != 0;
        i = j;
    }
    for (size_t i = 0; !bad && i < c.nfill; i++)
        bad = tile_push(t, &c.fill[i], 0, 0, 0, 0) != 0;
    free(c.fill);
    free(c.all.e);
    free(c.s);
    free(c.cand);
    return bad ? -1 : 0;
}
