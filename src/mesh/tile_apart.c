/* Rectangular elements: tiles of different faults kept apart, and the
 * measures of fm_tile.h (flatness, area, junction gaps). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_predicates.h"
#include "tile_internal.h"
#include "fm_vec3.h"

/* Clearance a cut leaves between a tile and the other tile's plane: far
 * above the rounding of UTM coordinates (1e-9 m), far below anything a
 * simulator resolves. */
#define CLEARANCE 1e-3

double tile_distance(const fm_tile *t, const double p[3], double *plane, int *inside)
{
    double r[3] = {p[0] - t->centre[0], p[1] - t->centre[1], p[2] - t->centre[2]}, n[3];
    tile_normal(t, n);
    double u = fm_dot3(r, t->strike), v = fm_dot3(r, t->dip), w = fm_dot3(r, n);
    double cu = fmin(fmax(u, -t->length / 2), t->length / 2);
    double cv = fmin(fmax(v, -t->width / 2), t->width / 2);
    if (plane)
        *plane = w;
    if (inside)
        *inside = cu == u && cv == v;
    return sqrt((u - cu) * (u - cu) + (v - cv) * (v - cv) + w * w);
}

static double radius(const fm_tile *t) { return 0.5 * hypot(t->length, t->width); }

static double max_radius(const fm_tiles *t)
{
    double r = 0;
    for (size_t i = 0; i < t->n; i++)
        r = fmax(r, radius(&t->tile[i]));
    return r;
}

int tile_meet(const fm_tile *a, const fm_tile *b)
{
    if (a->length <= 0 || b->length <= 0)
        return 0;
    double ca[4][3], cb[4][3];
    fm_tile_corners(a, ca);
    fm_tile_corners(b, cb);
    const double *ta[2][3] = {{ca[0], ca[1], ca[2]}, {ca[0], ca[2], ca[3]}};
    const double *tb[2][3] = {{cb[0], cb[1], cb[2]}, {cb[0], cb[2], cb[3]}};
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 2; j++)
            if (fm_triangles_meet(ta[i], tb[j]))
                return 1;
    return 0;
}

/* The largest part of a on its centre's side of the plane of b, clear of
 * it: cut back along strike, or down dip, or scaled about its centre,
 * whichever keeps most. Returns the area lost (INFINITY when a's centre
 * is on b's plane) and the cut tile in *out. */
static double cut(const fm_tile *a, const fm_tile *b, fm_tile *out)
{
    double n[3];
    tile_normal(b, n);
    double r[3] = {a->centre[0] - b->centre[0], a->centre[1] - b->centre[1],
                   a->centre[2] - b->centre[2]};
    double g0 = fm_dot3(n, r);
    if (fabs(g0) <= CLEARANCE)
        return INFINITY;
    double sg = g0 > 0 ? 1 : -1, h0 = fabs(g0);
    double hu = sg * fm_dot3(n, a->strike), hv = sg * fm_dot3(n, a->dip);
    double L = a->length, W = a->width;
    double best = INFINITY, bu[2] = {0, 0}, bv[2] = {0, 0};
    /* along strike: every v of the tile, u restricted */
    double k = h0 - fabs(hv) * W / 2 - CLEARANCE;
    if (k > 0) {
        double u0 = -L / 2, u1 = L / 2;
        if (hu > 0)
            u0 = fmax(u0, -k / hu);
        else if (hu < 0)
            u1 = fmin(u1, k / -hu);
        if (u1 > u0 && (L - (u1 - u0)) * W < best) {
            best = (L - (u1 - u0)) * W;
            bu[0] = u0, bu[1] = u1, bv[0] = -W / 2, bv[1] = W / 2;
        }
    }
    k = h0 - fabs(hu) * L / 2 - CLEARANCE;
    if (k > 0) {
        double v0 = -W / 2, v1 = W / 2;
        if (hv > 0)
            v0 = fmax(v0, -k / hv);
        else if (hv < 0)
            v1 = fmin(v1, k / -hv);
        if (v1 > v0 && (W - (v1 - v0)) * L < best) {
            best = (W - (v1 - v0)) * L;
            bu[0] = -L / 2, bu[1] = L / 2, bv[0] = v0, bv[1] = v1;
        }
    }
    double den = fabs(hu) * L / 2 + fabs(hv) * W / 2;
    double s = den > 0 ? (h0 - CLEARANCE) / den : 1;
    if (s > 0 && s < 1 && L * W * (1 - s * s) < best) {
        best = L * W * (1 - s * s);
        bu[0] = -s * L / 2, bu[1] = s * L / 2, bv[0] = -s * W / 2, bv[1] = s * W / 2;
    }
    if (best == INFINITY)
        return INFINITY;
    *out = *a;
    double du = (bu[0] + bu[1]) / 2, dv = (bv[0] + bv[1]) / 2;
    for (int d = 0; d < 3; d++)
        out->centre[d] = a->centre[d] + du * a->strike[d] + dv * a->dip[d];
    out->length = bu[1] - bu[0];
    out->width = bv[1] - bv[0];
    out->shrunk = 1;
    return best;
}

int tile_a_gives_way(const fm_tiles *t, const fm_tile *a, const fm_tile *b, double la, double lb)
{
    int fa = t->favour && t->favour[a->fault], fb = t->favour && t->favour[b->fault];
    if (fa != fb && (fa ? lb : la) < INFINITY)
        return fb;
    return la <= lb;
}

typedef struct sep_ctx {
    fm_tiles *t;
    const double *rad; /* radius of each tile as made */
    const double (*c0)[3]; /* centre of each tile as made */
    size_t i;
} sep_ctx;

static int separate_pair(size_t j, void *user)
{
    sep_ctx *c = user;
    fm_tile *a = &c->t->tile[c->i], *b = &c->t->tile[j];
    /* a pair of tiles both cut here is taken once; a tile that stays is
     * taken from the other's side */
    if ((j <= c->i && tile_active(c->t, b->fault)) || tile_same_unit(a, b))
        return 0;
    double r[3] = {c->c0[c->i][0] - c->c0[j][0], c->c0[c->i][1] - c->c0[j][1],
                   c->c0[c->i][2] - c->c0[j][2]};
    if (sqrt(fm_dot3(r, r)) > c->rad[c->i] + c->rad[j])
        return 0;
    for (int round = 0; round < 8 && tile_meet(a, b); round++) {
        fm_tile ca, cb;
        double la = cut(a, b, &ca), lb = cut(b, a, &cb);
        if (la == INFINITY && lb == INFINITY)
            break;
        if (tile_a_gives_way(c->t, a, b, la, lb))
            *a = ca;
        else
            *b = cb;
    }
    if (tile_meet(a, b)) {
        /* nothing cuts them apart (one lies across the other's plane at
         * its centre): the smaller goes */
        fm_tile *gone = a->length * a->width <= b->length * b->width ? a : b;
        gone->length = gone->width = 0;
    }
    return a->length <= 0; /* nothing left of a to test */
}

typedef struct split_ctx {
    fm_tiles *t;
    unsigned char *mark; /* 1: split along strike, 2: down dip */
    size_t i;
} split_ctx;

/* Halves of a tile (along strike, or down dip: then the lower one is no
 * longer on the top row). */
static void halve(const fm_tile *a, int dip, fm_tile h[2])
{
    for (int k = 0; k < 2; k++) {
        double sg = k ? 0.25 : -0.25;
        h[k] = *a;
        if (dip) {
            h[k].width = a->width / 2;
            for (int d = 0; d < 3; d++)
                h[k].centre[d] += sg * a->width * a->dip[d];
            h[k].row = a->row + k;
        } else {
            h[k].length = a->length / 2;
            for (int d = 0; d < 3; d++)
                h[k].centre[d] += sg * a->length * a->strike[d];
        }
    }
}

/* What cutting a (or its halves) clear of b's plane loses. */
static double cut_loss(const fm_tile *a, const fm_tile *b, int halves_dip)
{
    fm_tile o, h[2];
    if (halves_dip < 0)
        return cut(a, b, &o);
    halve(a, halves_dip, h);
    double l = 0;
    for (int k = 0; k < 2; k++)
        l += tile_meet(&h[k], b) ? cut(&h[k], b, &o) : 0;
    return l;
}

static int mark_pair(size_t j, void *user)
{
    split_ctx *c = user;
    fm_tile *a = &c->t->tile[c->i], *b = &c->t->tile[j];
    if (j == c->i || tile_same_unit(a, b) || c->mark[c->i] || !tile_meet(a, b))
        return 0;
    double la = cut_loss(a, b, -1), lb = cut_loss(b, a, -1);
    if (!tile_a_gives_way(c->t, a, b, la, lb))
        return 0; /* b is the one cut: its own turn decides */
    double area = a->length * a->width, least = c->t->stats.size / 8;
    if (!(la > 0.05 * area))
        return 0;
    double ls = a->length / 2 >= least ? cut_loss(a, b, 0) : INFINITY;
    double ld = a->width / 2 >= least ? cut_loss(a, b, 1) : INFINITY;
    if (fmin(ls, ld) < 0.75 * la)
        c->mark[c->i] = ls <= ld ? 1 : 2;
    return 0;
}

/* Tiles that would lose more than a twentieth of their area where they
 * meet another fault's tile (a junction crossing a row at a slant) split
 * in two first, down to an eighth of the size, so that the cut takes
 * less: over rounds the tiles follow the junction as a staircase (on the
 * whole CFM at 2 km, 64 faults outside 3 % of their area instead of 78
 * with two rounds, a tenth and a quarter of the size); -1 when memory
 * runs out. */
static int split_for_cuts(fm_tiles *t)
{
    double rmax = max_radius(t);
    unsigned char *mark = calloc(t->n + 1, 1);
    tile_grid g = {0};
    if (!mark || tile_grid_make(&g, t, rmax)) {
        free(mark);
        free(g.e);
        return -1;
    }
    split_ctx c = {t, mark, 0};
    for (size_t i = 0; i < t->n; i++) {
        c.i = i;
        if (tile_active(t, t->tile[i].fault))
            tile_grid_near(&g, t->tile[i].centre, 2 * rmax, mark_pair, &c);
    }
    free(g.e);
    size_t n = t->n;
    for (size_t i = 0; i < n; i++) {
        if (!mark[i])
            continue;
        fm_tile h[2];
        halve(&t->tile[i], mark[i] == 2, h);
        t->tile[i] = h[0];
        if (tile_push(t, &h[1], 0, 0, 0, 0)) {
            free(mark);
            return -1;
        }
    }
    free(mark);
    return 0;
}

int tile_separate(fm_tiles *t)
{
    if (!t->n)
        return 0;
    for (int round = 0; round < 4; round++)
        if (split_for_cuts(t))
            return -1;
    double *rad = malloc(t->n * sizeof *rad), rmax = 0;
    double (*c0)[3] = malloc(t->n * sizeof *c0), *a0 = malloc(t->n * sizeof *a0);
    tile_grid g = {0};
    if (!rad || !c0 || !a0) {
        free(rad);
        free(c0);
        free(a0);
        return -1;
    }
    for (size_t i = 0; i < t->n; i++) {
        rad[i] = radius(&t->tile[i]);
        a0[i] = t->tile[i].length * t->tile[i].width;
        rmax = fmax(rmax, rad[i]);
        memcpy(c0[i], t->tile[i].centre, sizeof c0[i]);
    }
    if (tile_grid_make(&g, t, rmax)) {
        free(rad);
        free(c0);
        free(a0);
        free(g.e);
        return -1;
    }
    sep_ctx ctx = {t, rad, (const double(*)[3])c0, 0};
    for (size_t i = 0; i < t->n; i++) {
        ctx.i = i;
        if (t->tile[i].length > 0 && tile_active(t, t->tile[i].fault))
            tile_grid_near(&g, c0[i], rad[i] + rmax, separate_pair, &ctx);
    }
    /* the tiles given up leave the list */
    size_t m = 0;
    for (size_t i = 0; i < t->n; i++) {
        t->fault[t->tile[i].fault].area_cut +=
            a0[i] - t->tile[i].length * t->tile[i].width;
        double least = fmin(t->tile[i].length, t->tile[i].width);
        if (least >= t->stats.size / 20)
            t->tile[m++] = t->tile[i];
        else
            t->left_out[t->tile[i].fault][least > 0 ? 0 : 1]++;
    }
    t->n = m;
    free(rad);
    free(c0);
    free(a0);
    free(g.e);
    return 0;
}

typedef struct near_ctx {
    const fm_tiles *t;
    const double *p;
    int32_t fault;
    double best;    /* nearest tile of fault (measure_gap) */
    size_t count;   /* meeting pairs (count_meeting) */
    size_t i;
} near_ctx;

static int nearest_of_fault(size_t j, void *user)
{
    near_ctx *c = user;
    const fm_tile *b = &c->t->tile[j];
    if (b->fault == c->fault)
        c->best = fmin(c->best, tile_distance(b, c->p, NULL, NULL));
    return 0;
}

double tile_nearest_of_fault(const tile_grid *g, const fm_tiles *t, const double p[3],
                             double reach, int32_t fault, double none)
{
    near_ctx c = {t, p, fault, none, 0, 0};
    tile_grid_near(g, p, reach, nearest_of_fault, &c);
    return c.best;
}

static int count_meeting(size_t j, void *user)
{
    near_ctx *c = user;
    const fm_tile *a = &c->t->tile[c->i], *b = &c->t->tile[j];
    if (j > c->i && !tile_same_unit(a, b) && tile_meet(a, b))
        c->count++;
    return 0;
}

static int dbl_cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

typedef struct gap_rec {
    uint64_t pair; /* a << 32 | b */
    double len, gmax, gsum, over;
} gap_rec;

static int gap_cmp(const void *a, const void *b)
{
    const gap_rec *x = a, *y = b;
    return (x->pair > y->pair) - (x->pair < y->pair);
}

/* The per-junction gaps: each edge two faults share sampled at its
 * quarter points, each sample the larger distance to a tile of either. */
static int measure_gaps(fm_tiles *t, const fm_mesh *set, const tile_sides *sd, const tile_grid *g,
                        double reach)
{
    const double *x = fm_mesh_vertices(set);
    const int32_t *tag = fm_mesh_tags(set);
    gap_rec *rec = NULL;
    size_t nrec = 0, cap = 0;
    for (size_t i = 0; i < sd->n;) {
        size_t j = i + 1;
        while (j < sd->n && sd->side[j].key == sd->side[i].key)
            j++;
        if (!sd->junction[i]) {
            i = j;
            continue;
        }
        const double *a = x + 3 * (size_t)(sd->side[i].key >> 32),
                     *b = x + 3 * (size_t)(sd->side[i].key & 0xffffffffu);
        double len = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
                          (b[2] - a[2]) * (b[2] - a[2]));
        /* the distinct faults holding the edge */
        int32_t fl[8];
        int nf = 0;
        for (size_t p = i; p < j && nf < 8; p++) {
            int32_t f = tag[sd->side[p].index], k = nf;
            for (int q = 0; q < nf; q++)
                if (fl[q] == f)
                    k = -1;
            if (k < 0)
                continue;
            while (k > 0 && fl[k - 1] > f) {
                fl[k] = fl[k - 1];
                k--;
            }
            fl[k] = f;
            nf++;
        }
        for (int p = 0; p < nf; p++)
            for (int q = p + 1; q < nf; q++) {
                int32_t fa = fl[p], fb = fl[q];
                if (nrec == cap) {
                    cap = cap ? 2 * cap : 1024;
                    gap_rec *nr = realloc(rec, cap * sizeof *nr);
                    if (!nr) {
                        free(rec);
                        return -1;
                    }
                    rec = nr;
                }
                gap_rec gr = {(uint64_t)(uint32_t)fa << 32 | (uint32_t)fb, len, 0, 0, 0};
                for (int k = 1; k <= 3; k++) {
                    double pt[3];
                    for (int d = 0; d < 3; d++)
                        pt[d] = a[d] + (b[d] - a[d]) * k / 4.0;
                    double gap = fmax(tile_nearest_of_fault(g, t, pt, reach, fa, reach),
                                      tile_nearest_of_fault(g, t, pt, reach, fb, reach));
                    gr.gmax = fmax(gr.gmax, gap);
                    gr.gsum += gap * len / 3;
                    if (gap > t->stats.size / 2)
                        gr.over += len / 3;
                }
                rec[nrec++] = gr;
            }
        i = j;
    }
    if (nrec)
        qsort(rec, nrec, sizeof *rec, gap_cmp);
    size_t m = 0;
    for (size_t i = 0; i < nrec; i++) {
        if (m && rec[m - 1].pair == rec[i].pair) {
            rec[m - 1].len += rec[i].len;
            rec[m - 1].gmax = fmax(rec[m - 1].gmax, rec[i].gmax);
            rec[m - 1].gsum += rec[i].gsum;
            rec[m - 1].over += rec[i].over;
        } else {
            rec[m++] = rec[i];
        }
    }
    t->junction = malloc((m + 1) * sizeof *t->junction);
    if (!t->junction) {
        free(rec);
        return -1;
    }
    for (size_t i = 0; i < m; i++)
        t->junction[i] = (fm_tile_junction){(int32_t)(rec[i].pair >> 32),
                                            (int32_t)(rec[i].pair & 0xffffffffu), rec[i].len,
                                            rec[i].gmax, rec[i].len > 0 ? rec[i].gsum / rec[i].len : 0,
                                            rec[i].over};
    t->njunctions = m;
    free(rec);
    return 0;
}

int tile_measure(fm_tiles *t, const fm_mesh *set, const tile_sides *sd, tile_walk *w)
{
    double rmax = max_radius(t);
    tile_grid g = {0};
    if (t->n && tile_grid_make(&g, t, rmax)) {
        free(g.e);
        return -1;
    }
    /* flatness: the surface each tile stands for, sampled at its
     * triangles' corners, side midpoints and centroids, where it lies
     * under the tile */
    for (size_t i = 0; i < t->n; i++) {
        fm_tile *tl = &t->tile[i];
        double c[4][3];
        fm_tile_corners(tl, c);
        double zlo = INFINITY, zhi = -INFINITY;
        for (int k = 0; k < 4; k++) {
            double z = tile_level(t->up[tl->fault], c[k]);
            zlo = fmin(zlo, z);
            zhi = fmax(zhi, z);
        }
        tile_region(w, tl, zlo, zhi);
        tl->flatness = tile_flatness(w, tl);
    }
    double *flat = malloc((t->n + 1) * sizeof *flat);
    if (!flat) {
        free(g.e);
        return -1;
    }
    for (size_t i = 0; i < t->n; i++) {
        fm_tile *tl = &t->tile[i];
        fm_tile_fault *f = &t->fault[tl->fault];
        f->ntiles++;
        f->area_tiles += tl->length * tl->width;
        f->flatness_max = fmax(f->flatness_max, tl->flatness);
        t->stats.shrunk += tl->shrunk != 0;
        flat[i] = tl->flatness;
    }
    t->stats.ntiles = t->n;
    for (size_t f = 0; f < t->nfaults; f++) {
        t->stats.slivers += t->left_out[f][0];
        t->stats.dropped += t->left_out[f][1];
    }
    if (t->n) {
        qsort(flat, t->n, sizeof *flat, dbl_cmp);
        t->stats.flatness_p99 = flat[(size_t)floor(0.99 * (double)(t->n - 1))];
        t->stats.flatness_max = flat[t->n - 1];
    }
    free(flat);
    t->stats.area_ratio_min = INFINITY;
    t->stats.area_ratio_max = 0;
    for (size_t f = 0; f < t->nfaults; f++)
        if (t->fault[f].ntiles && t->fault[f].area_triangles > 0) {
            double r = t->fault[f].area_tiles / t->fault[f].area_triangles;
            t->stats.area_ratio_min = fmin(t->stats.area_ratio_min, r);
            t->stats.area_ratio_max = fmax(t->stats.area_ratio_max, r);
        }
    if (t->stats.area_ratio_min == INFINITY)
        t->stats.area_ratio_min = 0;
    /* what still meets, counted by the same exact test */
    for (size_t i = 0; i < t->n; i++) {
        near_ctx nc = {t, NULL, 0, 0, 0, i};
        tile_grid_near(&g, t->tile[i].centre, 2 * rmax, count_meeting, &nc);
        t->stats.meeting += nc.count;
    }
    int st = t->n ? measure_gaps(t, set, sd, &g, 2 * rmax + t->stats.size) : 0;
    if (!t->n)
        t->junction = malloc(1);
    free(g.e);
    return st || !t->junction ? -1 : 0;
}
