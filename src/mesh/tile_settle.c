/* Rectangular elements: the tiles of different faults cut apart and grown
 * back over the bare surface (tile_internal.h), again where that leaves a
 * fault short. The cut goes to the tile that loses less area
 * (tile_separate), meeting by meeting: a fault crossed by several others
 * at small angles, or wedged between two that meet it at a slant, loses a
 * strip at each and may end up more than 3 % short of its area while its
 * neighbours keep theirs whole (on the whole CFM 5.3 at 2 km, the Laguna
 * Salada east branch at 0.956 and Icehouse Canyon at 0.968). Then those
 * faults and their neighbours are tiled again from their tiles as made,
 * the short faults' tiles kept where a neighbour's may be cut instead, the
 * other faults' tiles left as they were (0.990 and 0.991). A neighbour
 * that this cuts short in turn (a fault of 0.87 km^2 crossing the Laguna
 * Salada east branch fell to 0.918) is favoured too in the next round.
 * The tiling with the fewest faults outside 3 % of their area is kept. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "tile_internal.h"

/* A tiling off its fault's area by more than this is short (or over). */
#define OFF 0.03

int tile_by_fault(fm_tiles *t)
{
    size_t *start = calloc(t->nfaults + 1, sizeof *start);
    fm_tile *sorted = malloc((t->n + 1) * sizeof *sorted);
    /* the rows' bands serve only while the faults are tiled; tile_push
     * still writes them, so they stay as long as the tiles */
    double(*band)[4] = sorted ? realloc(t->band, (t->n + 1) * sizeof *band) : NULL;
    if (band)
        t->band = band;
    if (!start || !sorted || !band) {
        free(start);
        free(sorted);
        return -1;
    }
    for (size_t i = 0; i < t->n; i++)
        if ((size_t)t->tile[i].fault + 1 < t->nfaults)
            start[t->tile[i].fault + 1]++;
    for (size_t f = 1; f < t->nfaults; f++)
        start[f] += start[f - 1];
    for (size_t i = 0; i < t->n; i++)
        sorted[start[t->tile[i].fault]++] = t->tile[i];
    free(t->tile);
    t->tile = sorted;
    t->cap = t->n + 1;
    free(start);
    return 0;
}

static int cut_and_grow(fm_tiles *t, const fm_mesh *set, tile_walk *w, const size_t *order,
                        const size_t *start)
{
    return tile_separate(t) || tile_by_fault(t) || tile_grow(t, set, w, order, start) ||
           tile_by_fault(t);
}

/* The number of faults whose tiles' area is off their triangles' by more
 * than OFF (area: per fault, the tiles' area); those short flagged in
 * shortf when given. */
static size_t outside(const fm_tiles *t, double *area, unsigned char *shortf)
{
    memset(area, 0, t->nfaults * sizeof *area);
    for (size_t i = 0; i < t->n; i++)
        area[t->tile[i].fault] += t->tile[i].length * t->tile[i].width;
    size_t n = 0;
    for (size_t f = 0; f < t->nfaults; f++) {
        double at = t->fault[f].area_triangles;
        if (!(at > 0))
            continue; /* a fault with surface but no tile left is short too */
        double r = area[f] / at;
        n += r < 1 - OFF || r > 1 + OFF;
        if (shortf)
            shortf[f] = r < 1 - OFF;
    }
    return n;
}

/* A tiling set aside: its tiles, and per fault the area they lost to
 * cuts and the tiles left out. */
typedef struct tiling {
    fm_tile *tile;
    size_t n;
    double *cut;
    size_t (*left_out)[2];
} tiling;

static void tiling_free(tiling *k)
{
    free(k->tile);
    free(k->cut);
    free(k->left_out);
    *k = (tiling){0};
}

static int tiling_take(const fm_tiles *t, tiling *k)
{
    tiling_free(k);
    k->tile = malloc((t->n + 1) * sizeof *k->tile);
    k->cut = malloc((t->nfaults + 1) * sizeof *k->cut);
    k->left_out = malloc((t->nfaults + 1) * sizeof *k->left_out);
    if (!k->tile || !k->cut || !k->left_out)
        return -1;
    k->n = t->n;
    memcpy(k->tile, t->tile, t->n * sizeof *k->tile);
    memcpy(k->left_out, t->left_out, t->nfaults * sizeof *k->left_out);
    for (size_t f = 0; f < t->nfaults; f++)
        k->cut[f] = t->fault[f].area_cut;
    return 0;
}

/* t's tiles: those of k's faults that active leaves out (all, when
 * active is NULL), then those of made (of n) of the faults it takes in. */
static int tiling_put(fm_tiles *t, const tiling *k, const unsigned char *active,
                      const fm_tile *made, size_t n)
{
    t->n = 0;
    for (size_t i = 0; i < k->n; i++)
        if ((!active || !active[k->tile[i].fault]) && tile_push(t, &k->tile[i], 0, 0, 0, 0))
            return -1;
    for (size_t i = 0; active && i < n; i++)
        if (active[made[i].fault] && tile_push(t, &made[i], 0, 0, 0, 0))
            return -1;
    for (size_t f = 0; f < t->nfaults; f++) {
        int in = active && active[f];
        t->fault[f].area_cut = in ? 0 : k->cut[f];
        t->left_out[f][0] = in ? 0 : k->left_out[f][0];
        t->left_out[f][1] = in ? 0 : k->left_out[f][1];
    }
    return 0;
}

typedef struct near_ctx {
    const fm_tile *made;
    const double *rad;
    const fm_tile *a;
    double ra, reach;
    unsigned char *active;
} near_ctx;

static int mark_near(size_t j, void *user)
{
    near_ctx *c = user;
    const fm_tile *b = &c->made[j];
    double r[3] = {c->a->centre[0] - b->centre[0], c->a->centre[1] - b->centre[1],
                   c->a->centre[2] - b->centre[2]};
    if (sqrt(fm_dot3(r, r)) <= c->ra + c->rad[j] + c->reach)
        c->active[b->fault] = 1;
    return 0;
}

/* The faults cut and grown again: the favoured ones and those whose tiles,
 * as made, come within the size of theirs (grown tiles reach up to half
 * the size past their sides). */
static void mark_active(const fm_tiles *t, const fm_tile *made, size_t n, const double *rad,
                        double rmax, const tile_grid *g, const unsigned char *favour,
                        unsigned char *active)
{
    memcpy(active, favour, t->nfaults);
    near_ctx c = {made, rad, NULL, 0, t->stats.size, active};
    for (size_t i = 0; i < n; i++)
        if (favour[made[i].fault]) {
            c.a = &made[i];
            c.ra = rad[i];
            tile_grid_near(g, made[i].centre, rad[i] + rmax + c.reach, mark_near, &c);
        }
}

/* Rounds of tiling again, each favouring every fault short in a round
 * before: a fault a favoured one cuts short (a small fault crossing it)
 * is favoured in the next, and where two favoured faults meet the one
 * losing less goes as at first. */
#define ROUNDS 3

int tile_settle(fm_tiles *t, const fm_mesh *set, tile_walk *w, const size_t *order,
                const size_t *start)
{
    size_t nf = t->nfaults, nmade = t->n;
    fm_tile *made = malloc((nmade + 1) * sizeof *made);
    double *area = malloc((nf + 1) * sizeof *area), *rad = malloc((nmade + 1) * sizeof *rad);
    unsigned char *favour = calloc(nf + 1, 1), *shortf = calloc(nf + 1, 1),
                  *active = calloc(nf + 1, 1);
    tiling one = {0}, best = {0};
    tile_grid g = {0};
    double rmax = 0;
    int bad = !made || !area || !rad || !favour || !shortf || !active;
    if (!bad) {
        memcpy(made, t->tile, nmade * sizeof *made);
        for (size_t i = 0; i < nmade; i++) {
            rad[i] = 0.5 * hypot(made[i].length, made[i].width);
            rmax = fmax(rmax, rad[i]);
        }
        bad = cut_and_grow(t, set, w, order, start);
    }
    size_t nbest = bad ? 0 : outside(t, area, shortf);
    int improved = 0;
    for (int round = 0; !bad && nbest && round < ROUNDS; round++) {
        int more = 0;
        for (size_t f = 0; f < nf; f++) {
            more |= shortf[f] && !favour[f];
            favour[f] |= shortf[f];
        }
        if (!more)
            break;
        if (!round)
            bad = tiling_take(t, &one) ||
                  tile_grid_make_points(&g, made->centre, sizeof *made, nmade, rmax);
        if (bad)
            break;
        /* the faults near the favoured ones from their tiles as made, the
         * others' as the first round left them */
        mark_active(t, made, nmade, rad, rmax, &g, favour, active);
        bad = tiling_put(t, &one, active, made, nmade);
        t->favour = favour;
        t->active = active;
        bad = bad || cut_and_grow(t, set, w, order, start);
        t->favour = t->active = NULL;
        size_t n = bad ? 0 : outside(t, area, shortf);
        if (!bad && n < nbest) {
            nbest = n;
            improved = 1;
            bad = tiling_take(t, &best);
        }
    }
    if (!bad && one.tile)
        bad = tiling_put(t, improved ? &best : &one, NULL, NULL, 0);
    tiling_free(&one);
    tiling_free(&best);
    free(g.e);
    free(made);
    free(rad);
    free(area);
    free(favour);
    free(shortf);
    free(active);
    return bad ? -1 : 0;
}
