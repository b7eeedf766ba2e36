/* The elastic interaction check (fm_check.h): every element's
 * self-stiffness, and the stiffness between elements of different faults
 * near each other, found on a grid of cells one search radius wide so
 * that the cost follows the elements near other faults, not the square
 * of all of them. Work is handed out in fixed chunks of elements and the
 * chunks' findings joined in chunk order, so the result does not depend
 * on the thread count. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "elastic_internal.h"
#include "fm_parallel.h"
#include "fm_sort.h"

#define CHUNK 256

/* Coupling falls fast with the distance between two elements: for
 * elements facing each other across a gap (the strongest case) it is 0.93
 * at 0.05 element sizes, 0.75 at 0.1, 0.37 at 0.2, 0.20 at 0.3 and 0.10
 * at 0.5 (1 km elements, measured as in tests/unit/test_elastic_check.c);
 * neighbours of one flat fault sharing an edge reach 0.26. Pairs farther
 * apart than SCREEN_SIZES x the larger size cannot then reach a fraction
 * of SCREEN_FRACTION or more, and are not evaluated: most pairs within the
 * search radius are, and near the surface each costs milliseconds. Below
 * that fraction every pair within the radius is evaluated. */
#define SCREEN_SIZES 0.5
#define SCREEN_FRACTION 0.25

struct fm_elastic {
    fm_elastic_summary sum;
    double *self;
    size_t *wrong;
    size_t nwrong;
    fm_elastic_pair *pair;
    size_t npairs;
    fm_elastic_group *group;
    size_t ngroups;
};

void fm_elastic_options_default(fm_elastic_options *o)
{
    o->mu = 3e10;
    o->nu = 0.25;
    o->radius = 3;
    o->fraction = 0.5;
    o->full_space = 0;
    o->threads = 1;
}

/* A cell (ix, iy, iz) as one sort key, CELL_BITS bits an axis, each
 * index shifted by one so that the neighbours of the first cell (-1) have
 * keys too: the grid is then core's keyed sort and lower bound, as in
 * carve.c and tile_grid.c. make_grid widens the cells to keep every index
 * within the bits. */
#define CELL_BITS 21

static uint64_t cell_key(int64_t ix, int64_t iy, int64_t iz)
{
    return (uint64_t)(ix + 1) << (2 * CELL_BITS) | (uint64_t)(iy + 1) << CELL_BITS |
           (uint64_t)(iz + 1);
}

/* One chunk's findings. */
typedef struct chunk_out {
    fm_elastic_pair *pair;
    size_t n, cap;
    size_t within, evaluated, singular;
    double max_ratio;
    int nomem;
} chunk_out;

typedef struct work {
    const fm_elastic_input *in;
    const fm_elastic_options *opt;
    const el_elem *el;
    const int32_t *tag;
    size_t n;
    double *self;
    const fm_keyed *cells; /* cell_key of each usable element, sorted */
    size_t ncells;
    double cell, origin[3];
    chunk_out *out;
} work;

static void self_chunk(void *user, size_t k)
{
    work *w = user;
    size_t end = (k + 1) * CHUNK < w->n ? (k + 1) * CHUNK : w->n;
    for (size_t i = k * CHUNK; i < end; i++) {
        double t[4];
        w->self[i] = w->el[i].state == EL_OK &&
                             el_traction(&w->el[i], &w->el[i], w->opt, t) == 0
                         ? t[2]
                         : NAN;
    }
}

static int64_t cell_of(const work *w, double v, int d)
{
    return (int64_t)floor((v - w->origin[d]) / w->cell);
}

/* The stiffness a self-stiffness stands for in the ratio: none when it
 * is unknown or of the wrong sign (that element is reported as such). */
static double self_scale(double k)
{
    return isfinite(k) && k < 0 ? -k : NAN;
}

static void pair_add(chunk_out *o, const fm_elastic_pair *p)
{
    if (o->n == o->cap) {
        size_t cap = o->cap ? 2 * o->cap : 16;
        fm_elastic_pair *g = realloc(o->pair, cap * sizeof *g);
        if (!g) {
            o->nomem = 1;
            return;
        }
        o->pair = g;
        o->cap = cap;
    }
    o->pair[o->n++] = *p;
}

static void mutual_chunk(void *user, size_t k)
{
    work *w = user;
    chunk_out *o = &w->out[k];
    const el_elem *el = w->el;
    size_t end = (k + 1) * CHUNK < w->n ? (k + 1) * CHUNK : w->n;
    for (size_t i = k * CHUNK; i < end; i++) {
        if (el[i].state != EL_OK)
            continue;
        int64_t c[3];
        for (int d = 0; d < 3; d++)
            c[d] = cell_of(w, el[i].c[d], d);
        for (int64_t dx = -1; dx <= 1; dx++)
            for (int64_t dy = -1; dy <= 1; dy++)
                for (int64_t dz = -1; dz <= 1; dz++) {
                    uint64_t key = cell_key(c[0] + dx, c[1] + dy, c[2] + dz);
                    for (size_t q = fm_keyed_lower_bound(w->cells, w->ncells, key);
                         q < w->ncells && w->cells[q].key == key; q++) {
                        size_t j = w->cells[q].index;
                        if (j <= i || w->tag[j] == w->tag[i] || el[j].state != EL_OK)
                            continue;
                        double r = w->opt->radius * fmax(el[i].h, el[j].h), d2 = 0;
                        for (int d = 0; d < 3; d++)
                            d2 += (el[i].c[d] - el[j].c[d]) * (el[i].c[d] - el[j].c[d]);
                        if (d2 > r * r)
                            continue;
                        o->within++;
                        double dist = el_distance(&el[i], &el[j]);
                        if (w->opt->fraction >= SCREEN_FRACTION &&
                            dist > SCREEN_SIZES * fmax(el[i].h, el[j].h))
                            continue;
                        double tij[4], tji[4];
                        o->evaluated++;
                        if (el_traction(&el[j], &el[i], w->opt, tij) ||
                            el_traction(&el[i], &el[j], w->opt, tji)) {
                            o->singular++;
                            continue;
                        }
                        double ki = self_scale(w->self[i]), kj = self_scale(w->self[j]);
                        if (!(ki > 0 && kj > 0))
                            continue;
                        double ratio = sqrt(fabs(tij[2] * tji[2]) / (ki * kj));
                        o->max_ratio = fmax(o->max_ratio, ratio);
                        if (ratio <= w->opt->fraction)
                            continue;
                        /* i on the fault of the smaller tag, as groups name them */
                        int sw = w->tag[i] > w->tag[j];
                        fm_elastic_pair p = {sw ? j : i, sw ? i : j, sw ? tji[2] : tij[2],
                                             sw ? tij[2] : tji[2], ratio, dist};
                        pair_add(o, &p);
                    }
                }
    }
}

/* The junction of faults a < b nearest point p: 1-based, 0 when none. */
static size_t junction_of(const fm_elastic_input *in, int32_t a, int32_t b, const double p[3])
{
    size_t best = 0;
    double bd = INFINITY;
    for (size_t k = 0; k < in->njunctions; k++) {
        const fm_elastic_junction *jn = &in->junctions[k];
        int32_t x = jn->fault[0] < jn->fault[1] ? jn->fault[0] : jn->fault[1];
        int32_t y = jn->fault[0] < jn->fault[1] ? jn->fault[1] : jn->fault[0];
        if (x != a || y != b)
            continue;
        if (!best)
            best = k + 1;
        for (size_t q = 0; q < jn->npoints; q++) {
            const double *c = jn->points + 3 * q;
            double d = (c[0] - p[0]) * (c[0] - p[0]) + (c[1] - p[1]) * (c[1] - p[1]) +
                       (c[2] - p[2]) * (c[2] - p[2]);
            if (d < bd) {
                bd = d;
                best = k + 1;
            }
        }
    }
    return best;
}

typedef struct keyed_pair {
    int32_t a, b;
    size_t junction;
    fm_elastic_pair p;
} keyed_pair;

static int cmp_keyed(const void *pa, const void *pb)
{
    const keyed_pair *x = pa, *y = pb;
    if (x->a != y->a)
        return x->a < y->a ? -1 : 1;
    if (x->b != y->b)
        return x->b < y->b ? -1 : 1;
    if (x->junction != y->junction)
        return x->junction < y->junction ? -1 : 1;
    if (x->p.i != y->p.i)
        return x->p.i < y->p.i ? -1 : 1;
    return (x->p.j > y->p.j) - (x->p.j < y->p.j);
}

/* Pairs sorted and grouped by (a, b, junction); each group's examples
 * the pairs of largest ratio (ties: the first in order). */
static int make_groups(fm_elastic *e, const fm_elastic_input *in, const el_elem *el,
                       const int32_t *tag)
{
    keyed_pair *kp = malloc((e->npairs + 1) * sizeof *kp);
    e->group = malloc((e->npairs + 1) * sizeof *e->group);
    if (!kp || !e->group) {
        free(kp);
        return -1;
    }
    for (size_t k = 0; k < e->npairs; k++) {
        const fm_elastic_pair *p = &e->pair[k];
        double mid[3];
        for (int d = 0; d < 3; d++)
            mid[d] = (el[p->i].c[d] + el[p->j].c[d]) / 2;
        kp[k] = (keyed_pair){tag[p->i], tag[p->j], 0, *p};
        kp[k].junction = junction_of(in, kp[k].a, kp[k].b, mid);
    }
    qsort(kp, e->npairs, sizeof *kp, cmp_keyed);
    e->ngroups = 0;
    for (size_t k = 0; k < e->npairs; k++) {
        e->pair[k] = kp[k].p;
        fm_elastic_group *g = e->ngroups ? &e->group[e->ngroups - 1] : NULL;
        if (!g || g->a != kp[k].a || g->b != kp[k].b || g->junction != kp[k].junction) {
            g = &e->group[e->ngroups++];
            *g = (fm_elastic_group){.a = kp[k].a, .b = kp[k].b, .junction = kp[k].junction,
                                    .min_distance = INFINITY};
        }
        g->pairs++;
        g->max_ratio = fmax(g->max_ratio, kp[k].p.ratio);
        g->min_distance = fmin(g->min_distance, kp[k].p.distance);
        g->max_k = fmax(g->max_k, fmax(fabs(kp[k].p.k_ij), fabs(kp[k].p.k_ji)));
        /* insertion into the examples, largest ratio first */
        size_t pos = g->nexamples;
        while (pos > 0 && e->pair[g->example[pos - 1]].ratio < kp[k].p.ratio)
            pos--;
        if (pos < FM_ELASTIC_EXAMPLES) {
            size_t last = g->nexamples < FM_ELASTIC_EXAMPLES ? g->nexamples : FM_ELASTIC_EXAMPLES - 1;
            for (size_t q = last; q > pos; q--)
                g->example[q] = g->example[q - 1];
            g->example[pos] = k;
            if (g->nexamples < FM_ELASTIC_EXAMPLES)
                g->nexamples++;
        }
    }
    free(kp);
    return 0;
}

/* The elements, and the sums of their states. */
static el_elem *make_elements(const fm_elastic_input *in, fm_elastic_summary *s)
{
    size_t n = fm_mesh_ntriangles(in->set);
    el_elem *el = malloc((n + 1) * sizeof *el);
    for (size_t t = 0; el && t < n; t++) {
        int st = el_elem_make(in->set, t, in->strike[t], in->dip[t], in->rake[t], &el[t]);
        s->elements += st == EL_OK;
        s->above_surface += st == EL_ABOVE;
        s->degenerate += st == EL_DEGENERATE;
    }
    return el;
}

/* The grid: every usable element under its cell, sorted by cell and
 * within a cell by element (the order pairs are found in). */
static fm_keyed *make_grid(work *w, size_t *ncells)
{
    double hmax = 0, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int d = 0; d < 3; d++)
        w->origin[d] = INFINITY;
    for (size_t t = 0; t < w->n; t++)
        if (w->el[t].state == EL_OK) {
            hmax = fmax(hmax, w->el[t].h);
            for (int d = 0; d < 3; d++) {
                w->origin[d] = fmin(w->origin[d], w->el[t].c[d]);
                hi[d] = fmax(hi[d], w->el[t].c[d]);
            }
        }
    /* cells one search radius wide, wider only when the set spans more
     * cells than a key holds (the radius itself is checked pair by pair) */
    w->cell = fmax(w->opt->radius * hmax, 1e-9);
    for (int d = 0; d < 3; d++)
        if (hi[d] > w->origin[d])
            w->cell = fmax(w->cell, (hi[d] - w->origin[d]) / (double)((1 << CELL_BITS) - 4));
    fm_keyed *cells = malloc((w->n + 1) * sizeof *cells);
    size_t m = 0;
    for (size_t t = 0; cells && t < w->n; t++)
        if (w->el[t].state == EL_OK)
            cells[m++] = (fm_keyed){cell_key(cell_of(w, w->el[t].c[0], 0),
                                             cell_of(w, w->el[t].c[1], 1),
                                             cell_of(w, w->el[t].c[2], 2)),
                                    t};
    if (cells && fm_sort_keyed(cells, m)) {
        free(cells);
        cells = NULL;
    }
    *ncells = m;
    return cells;
}

static fm_status nomem(fm_elastic *e, el_elem *el, fm_keyed *cells, fm_error *err)
{
    free(el);
    free(cells);
    fm_elastic_destroy(e);
    return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "elastic check: out of memory");
}

fm_status fm_check_elastic(const fm_elastic_input *in, const fm_elastic_options *opt,
                           fm_elastic **out, fm_error *err)
{
    *out = NULL;
    if (!(opt->mu > 0) || !(opt->nu > -1 && opt->nu < 0.5) || !(opt->radius > 0) ||
        !(opt->fraction > 0))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                            "elastic check: needs mu > 0, -1 < nu < 0.5, radius > 0 and "
                            "fraction > 0");
    fm_elastic *e = calloc(1, sizeof *e);
    size_t n = fm_mesh_ntriangles(in->set);
    if (!e)
        return nomem(NULL, NULL, NULL, err);
    e->self = malloc((n + 1) * sizeof *e->self);
    el_elem *el = make_elements(in, &e->sum);
    if (!e->self || !el)
        return nomem(e, el, NULL, err);
    work w = {.in = in, .opt = opt, .el = el, .tag = fm_mesh_tags(in->set), .n = n,
              .self = e->self};
    size_t nchunks = (n + CHUNK - 1) / CHUNK;
    fm_parallel_for(nchunks, opt->threads, self_chunk, &w, NULL, NULL, 0, nchunks);
    e->wrong = malloc((n + 1) * sizeof *e->wrong);
    if (!e->wrong)
        return nomem(e, el, NULL, err);
    e->sum.self_min = INFINITY;
    e->sum.self_max = -INFINITY;
    for (size_t t = 0; t < n; t++) {
        if (el[t].state != EL_OK)
            continue;
        if (!(e->self[t] < 0))
            e->wrong[e->nwrong++] = t;
        if (isfinite(e->self[t])) {
            e->sum.self_min = fmin(e->sum.self_min, e->self[t]);
            e->sum.self_max = fmax(e->sum.self_max, e->self[t]);
        }
    }
    e->sum.self_wrong_sign = e->nwrong;
    if (!(e->sum.self_min <= e->sum.self_max))
        e->sum.self_min = e->sum.self_max = 0;
    fm_keyed *cells = make_grid(&w, &w.ncells);
    w.cells = cells;
    w.out = calloc(nchunks + 1, sizeof *w.out);
    if (!cells || !w.out) {
        free(w.out);
        return nomem(e, el, cells, err);
    }
    fm_parallel_for(nchunks, opt->threads, mutual_chunk, &w, NULL, NULL, 0, nchunks);
    int lost = 0;
    size_t total = 0;
    for (size_t k = 0; k < nchunks; k++) {
        lost |= w.out[k].nomem;
        total += w.out[k].n;
        e->sum.pairs_within += w.out[k].within;
        e->sum.pairs_evaluated += w.out[k].evaluated;
        e->sum.pairs_singular += w.out[k].singular;
        e->sum.max_ratio = fmax(e->sum.max_ratio, w.out[k].max_ratio);
    }
    e->pair = lost ? NULL : malloc((total + 1) * sizeof *e->pair);
    for (size_t k = 0; e->pair && k < nchunks; k++) {
        if (w.out[k].n)
            memcpy(e->pair + e->npairs, w.out[k].pair, w.out[k].n * sizeof *e->pair);
        e->npairs += w.out[k].n;
    }
    for (size_t k = 0; k < nchunks; k++)
        free(w.out[k].pair);
    free(w.out);
    e->sum.pairs_flagged = e->npairs;
    if (!e->pair || make_groups(e, in, el, w.tag))
        return nomem(e, el, cells, err);
    free(el);
    free(cells);
    *out = e;
    return FM_OK;
}

void fm_elastic_destroy(fm_elastic *e)
{
    if (!e)
        return;
    free(e->self);
    free(e->wrong);
    free(e->pair);
    free(e->group);
    free(e);
}

const fm_elastic_summary *fm_elastic_get_summary(const fm_elastic *e)
{
    return &e->sum;
}

const double *fm_elastic_self(const fm_elastic *e)
{
    return e->self;
}

const size_t *fm_elastic_wrong_sign(const fm_elastic *e, size_t *n)
{
    *n = e->nwrong;
    return e->wrong;
}

const fm_elastic_pair *fm_elastic_pairs(const fm_elastic *e, size_t *n)
{
    *n = e->npairs;
    return e->pair;
}

const fm_elastic_group *fm_elastic_groups(const fm_elastic *e, size_t *n)
{
    *n = e->ngroups;
    return e->group;
}
