/* check_connect: the analysis (see cc_check.h). */
#include "cc_check.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cc_geom.h"
#include "cc_grid.h"
#include "cc_sort.h"

/* ---- open-addressing map from a 64-bit key to a 32-bit index */

#define EMPTY UINT64_MAX

typedef struct map {
    uint64_t *keys;
    uint32_t *vals;
    size_t cap, n;
} map;

static uint64_t mix(uint64_t k)
{
    k ^= k >> 30;
    k *= 0xbf58476d1ce4e5b9ull;
    k ^= k >> 27;
    k *= 0x94d049bb133111ebull;
    return k ^ (k >> 31);
}

static int map_grow(map *m)
{
    size_t cap = m->cap ? 2 * m->cap : 1024;
    uint64_t *keys = malloc(cap * sizeof *keys);
    uint32_t *vals = malloc(cap * sizeof *vals);
    if (!keys || !vals) {
        free(keys);
        free(vals);
        return -1;
    }
    memset(keys, 0xff, cap * sizeof *keys);
    for (size_t i = 0; i < m->cap; i++) {
        if (m->keys[i] == EMPTY)
            continue;
        size_t s = (size_t)mix(m->keys[i]) & (cap - 1);
        while (keys[s] != EMPTY)
            s = (s + 1) & (cap - 1);
        keys[s] = m->keys[i];
        vals[s] = m->vals[i];
    }
    free(m->keys);
    free(m->vals);
    m->keys = keys;
    m->vals = vals;
    m->cap = cap;
    return 0;
}

/* The value slot of key; a new key gets value n (the count before it), so
 * values number the keys in order of insertion. NULL when out of memory. */
static uint32_t *map_slot(map *m, uint64_t key, int *fresh)
{
    if (2 * (m->n + 1) > m->cap && map_grow(m))
        return NULL;
    size_t s = (size_t)mix(key) & (m->cap - 1);
    while (m->keys[s] != EMPTY && m->keys[s] != key)
        s = (s + 1) & (m->cap - 1);
    *fresh = m->keys[s] == EMPTY;
    if (*fresh) {
        m->keys[s] = key;
        m->vals[s] = (uint32_t)m->n++;
    }
    return &m->vals[s];
}

static void map_free(map *m)
{
    free(m->keys);
    free(m->vals);
}

/* ---- analysis state */

typedef struct ctx {
    const cc_mesh *m;
    const cc_options *opt;
    map pmap; /* (a << 32 | b) -> pairs[] */
    cc_pair *pairs;
    size_t cap_pairs;
    cc_self *self;
    uint32_t *vf_start, *vf; /* faults using each vertex (CSR, ascending) */
    uint8_t *bflag;          /* bit k: edge k of the triangle is a boundary edge of its fault */
    double *box;             /* tight boxes, 6 per triangle */
    map emap;                /* near edge (edge << 30 | other fault) -> edist[] */
    double *edist;
    size_t cap_edist;
    uint64_t skipped;
    int oom;
} ctx;

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static cc_pair *get_pair(ctx *c, uint32_t fa, uint32_t fb)
{
    uint32_t a = fa < fb ? fa : fb, b = fa < fb ? fb : fa;
    int fresh;
    uint32_t *slot = map_slot(&c->pmap, (uint64_t)a << 32 | b, &fresh);
    if (!slot) {
        c->oom = 1;
        return NULL;
    }
    if (fresh) {
        if (*slot >= c->cap_pairs) {
            size_t cap = c->cap_pairs ? 2 * c->cap_pairs : 256;
            cc_pair *p = realloc(c->pairs, cap * sizeof *p);
            if (!p) {
                c->oom = 1;
                return NULL;
            }
            c->pairs = p;
            c->cap_pairs = cap;
        }
        cc_pair *p = &c->pairs[*slot];
        memset(p, 0, sizeof *p);
        p->a = a;
        p->b = b;
        p->distance = INFINITY;
        p->near_min = INFINITY;
    }
    return &c->pairs[*slot];
}

/* Keeps the CC_EXAMPLES smallest (x, y) in ascending order. */
static void add_example(uint32_t ex[][2], int *n, uint32_t x, uint32_t y)
{
    int i = *n;
    while (i > 0 && (ex[i - 1][0] > x || (ex[i - 1][0] == x && ex[i - 1][1] > y)))
        i--;
    if (i >= CC_EXAMPLES)
        return;
    int last = *n < CC_EXAMPLES ? *n : CC_EXAMPLES - 1;
    for (int k = last; k > i; k--) {
        ex[k][0] = ex[k - 1][0];
        ex[k][1] = ex[k - 1][1];
    }
    ex[i][0] = x;
    ex[i][1] = y;
    if (*n < CC_EXAMPLES)
        (*n)++;
}

static int uses(const ctx *c, uint32_t v, uint32_t f)
{
    for (uint32_t i = c->vf_start[v]; i < c->vf_start[v + 1]; i++)
        if (c->vf[i] == f)
            return 1;
    return 0;
}

/* Faults per vertex, shared vertices per pair; edges: boundary flags,
 * non-manifold count, shared edges per pair. */
static int topology(ctx *c, cc_result *r)
{
    const cc_mesh *m = c->m;
    size_t n3 = 3 * m->nt, nv = m->nv, nf = m->nfaults;
    cc_rec *rec = malloc((n3 ? n3 : 1) * sizeof *rec);
    c->vf_start = calloc(nv + 1, sizeof *c->vf_start);
    c->vf = malloc((n3 ? n3 : 1) * sizeof *c->vf);
    if (!rec || !c->vf_start || !c->vf)
        goto fail;
    for (size_t i = 0; i < n3; i++)
        rec[i] = (cc_rec){(uint64_t)m->tri[i] * nf + m->fault[i / 3], 0, 0};
    if (cc_radix_sort(rec, n3, cc_bits((uint64_t)nv * nf)))
        goto fail;
    size_t nu = 0;
    for (size_t i = 0; i < n3; i++)
        if (i == 0 || rec[i].key != rec[i - 1].key) {
            c->vf[nu++] = (uint32_t)(rec[i].key % nf);
            c->vf_start[rec[i].key / nf + 1]++;
        }
    for (size_t v = 0; v < nv; v++)
        c->vf_start[v + 1] += c->vf_start[v];
    for (size_t v = 0; v < nv; v++)
        for (uint32_t i = c->vf_start[v]; i < c->vf_start[v + 1]; i++)
            for (uint32_t j = i + 1; j < c->vf_start[v + 1]; j++) {
                cc_pair *p = get_pair(c, c->vf[i], c->vf[j]);
                if (!p)
                    goto fail;
                p->shared_vertices++;
            }

    /* Edges (v0 < v1) of every triangle in triangle order, sorted by fault
     * and then (stably) by edge: grouped by edge, then fault. */
    size_t ne = 0;
    for (size_t t = 0; t < m->nt; t++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = m->tri[3 * t + (size_t)k], b = m->tri[3 * t + (size_t)(k + 1) % 3];
            if (a != b)
                rec[ne++] = (cc_rec){m->fault[t], (uint32_t)(3 * t + (size_t)k), m->fault[t]};
        }
    if (cc_radix_sort(rec, ne, cc_bits(nf)))
        goto fail;
    for (size_t i = 0; i < ne; i++) {
        uint32_t te = rec[i].a, a = m->tri[te], b = m->tri[te - te % 3 + (te % 3 + 1) % 3];
        rec[i].key = (uint64_t)(a < b ? a : b) * nv + (a < b ? b : a);
    }
    if (cc_radix_sort(rec, ne, cc_bits((uint64_t)nv * nv)))
        goto fail;
    for (size_t s = 0; s < ne;) {
        size_t end = s;
        while (end < ne && rec[end].key == rec[s].key)
            end++;
        /* runs of one fault inside the edge's group */
        for (size_t i = s; i < end;) {
            size_t j = i;
            while (j < end && rec[j].b == rec[i].b)
                j++;
            if (j - i == 1) {
                c->bflag[rec[i].a / 3] |= (uint8_t)(1u << (rec[i].a % 3));
                r->boundary_edges++;
            } else if (j - i > 2) {
                r->nonmanifold_edges++;
            }
            for (size_t k = j; k < end;) { /* every later fault of the group */
                size_t l = k;
                while (l < end && rec[l].b == rec[k].b)
                    l++;
                cc_pair *p = get_pair(c, rec[i].b, rec[k].b);
                if (!p)
                    goto fail;
                p->shared_edges++;
                k = l;
            }
            i = j;
        }
        s = end;
    }
    free(rec);
    for (size_t t = 0; t < m->nt; t++) {
        const uint32_t *v = m->tri + 3 * t;
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2] ||
            cc_degenerate(m->x + 3 * (size_t)v[0], m->x + 3 * (size_t)v[1],
                          m->x + 3 * (size_t)v[2]))
            r->degenerate_triangles++;
    }
    return 0;
fail:
    free(rec);
    return -1;
}

static void on_overlap(void *vc, uint32_t i, uint32_t j)
{
    ctx *c = vc;
    const cc_mesh *m = c->m;
    uint32_t fi = m->fault[i], fj = m->fault[j];
    if ((fi == fj && !c->opt->self) || c->oom)
        return;
    cc_contact k = cc_classify(m->tri + 3 * (size_t)i, m->tri + 3 * (size_t)j, m->x);
    if (k == CC_SKIPPED)
        c->skipped++;
    if (k != CC_VIOLATION)
        return;
    if (fi == fj) {
        cc_self *s = &c->self[fi];
        s->intersections++;
        add_example(s->examples, &s->nexamples, i, j);
        return;
    }
    cc_pair *p = get_pair(c, fi, fj);
    if (!p)
        return;
    p->intersections++;
    if (fi < fj)
        add_example(p->examples, &p->nexamples, i, j);
    else
        add_example(p->examples, &p->nexamples, j, i);
}

static double box_gap(const double *a, const double *b)
{
    double s = 0;
    for (int k = 0; k < 3; k++) {
        double g = fmax(0, fmax(b[k] - a[3 + k], a[k] - b[3 + k]));
        s += g * g;
    }
    return sqrt(s);
}

/* Boundary edges of triangle i against triangle j of another fault. */
static void near_edges(ctx *c, uint32_t i, uint32_t j)
{
    const cc_mesh *m = c->m;
    if (!c->bflag[i])
        return;
    uint32_t fj = m->fault[j];
    const double *tj[3];
    for (int k = 0; k < 3; k++)
        tj[k] = m->x + 3 * (size_t)m->tri[3 * (size_t)j + (size_t)k];
    for (int k = 0; k < 3; k++) {
        if (!(c->bflag[i] >> k & 1))
            continue;
        uint32_t v0 = m->tri[3 * (size_t)i + (size_t)k],
                 v1 = m->tri[3 * (size_t)i + (size_t)(k + 1) % 3];
        if (uses(c, v0, fj) || uses(c, v1, fj))
            continue;
        const double *a = m->x + 3 * (size_t)v0, *b = m->x + 3 * (size_t)v1;
        double eb[6];
        for (int d = 0; d < 3; d++) {
            eb[d] = fmin(a[d], b[d]);
            eb[3 + d] = fmax(a[d], b[d]);
        }
        if (box_gap(eb, c->box + 6 * (size_t)j) > c->opt->distance)
            continue;
        double dist = cc_dist_seg_tri(a, b, tj);
        if (dist > c->opt->distance)
            continue;
        int fresh;
        uint32_t *slot =
            map_slot(&c->emap, (uint64_t)(3 * (size_t)i + (size_t)k) << 30 | fj, &fresh);
        if (!slot) {
            c->oom = 1;
            return;
        }
        if (fresh) {
            if (*slot >= c->cap_edist) {
                size_t cap = c->cap_edist ? 2 * c->cap_edist : 1024;
                double *d = realloc(c->edist, cap * sizeof *d);
                if (!d) {
                    c->oom = 1;
                    return;
                }
                c->edist = d;
                c->cap_edist = cap;
            }
            c->edist[*slot] = dist;
        } else if (dist < c->edist[*slot]) {
            c->edist[*slot] = dist;
        }
    }
}

static void on_near(void *vc, uint32_t i, uint32_t j)
{
    ctx *c = vc;
    const cc_mesh *m = c->m;
    if (c->oom)
        return;
    cc_pair *p = get_pair(c, m->fault[i], m->fault[j]);
    if (!p)
        return;
    if (p->shared_vertices == 0 && p->distance > 0) {
        double lb = box_gap(c->box + 6 * (size_t)i, c->box + 6 * (size_t)j);
        if (lb <= c->opt->distance && lb < p->distance) {
            const double *ti[3], *tj[3];
            for (int k = 0; k < 3; k++) {
                ti[k] = m->x + 3 * (size_t)m->tri[3 * (size_t)i + (size_t)k];
                tj[k] = m->x + 3 * (size_t)m->tri[3 * (size_t)j + (size_t)k];
            }
            double d = cc_dist_tri_tri(ti, tj);
            if (d < p->distance)
                p->distance = d;
        }
    }
    near_edges(c, i, j);
    near_edges(c, j, i);
}

typedef struct near_rec {
    uint64_t key;
    double dist;
} near_rec;

static int cmp_near(const void *pa, const void *pb)
{
    const near_rec *a = pa, *b = pb;
    return (a->key > b->key) - (a->key < b->key);
}

/* Near edges into the pairs, in key order (sums do not depend on the
 * map's layout). */
static int collect_near(ctx *c)
{
    const cc_mesh *m = c->m;
    size_t n = c->emap.n;
    near_rec *rec = malloc((n ? n : 1) * sizeof *rec);
    if (!rec)
        return -1;
    size_t k = 0;
    for (size_t s = 0; s < c->emap.cap; s++)
        if (c->emap.keys[s] != EMPTY)
            rec[k++] = (near_rec){c->emap.keys[s], c->edist[c->emap.vals[s]]};
    qsort(rec, n, sizeof *rec, cmp_near);
    for (size_t i = 0; i < n; i++) {
        uint64_t te = rec[i].key >> 30;
        uint32_t fb = (uint32_t)(rec[i].key & ((1u << 30) - 1));
        size_t t = (size_t)(te / 3);
        uint32_t fa = m->fault[t];
        cc_pair *p = get_pair(c, fa, fb);
        if (!p) {
            free(rec);
            return -1;
        }
        const double *a = m->x + 3 * (size_t)m->tri[te],
                     *b = m->x + 3 * (size_t)m->tri[3 * t + (te % 3 + 1) % 3];
        double len = sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
                          (b[2] - a[2]) * (b[2] - a[2]));
        int side = fa < fb ? 0 : 1;
        p->near_edges[side]++;
        p->near_length[side] += len;
        p->near_min = fmin(p->near_min, rec[i].dist);
    }
    free(rec);
    return 0;
}

static int cmp_pair(const void *pa, const void *pb)
{
    const cc_pair *a = pa, *b = pb;
    if (a->a != b->a)
        return a->a < b->a ? -1 : 1;
    return (a->b > b->b) - (a->b < b->b);
}

int cc_analyse(const cc_mesh *m, const cc_options *opt, cc_result *r)
{
    memset(r, 0, sizeof *r);
    ctx c = {.m = m, .opt = opt};
    int rc = -1;
    double t0 = now();
    c.self = calloc(m->nfaults ? m->nfaults : 1, sizeof *c.self);
    c.bflag = calloc(m->nt ? m->nt : 1, 1);
    c.box = malloc((m->nt ? m->nt : 1) * 6 * sizeof *c.box);
    double *wide = malloc((m->nt ? m->nt : 1) * 6 * sizeof *wide);
    if (!c.self || !c.bflag || !c.box || !wide || topology(&c, r))
        goto done;
    double t1 = now();

    for (size_t t = 0; t < m->nt; t++) {
        double *b = c.box + 6 * t;
        for (int k = 0; k < 3; k++) {
            b[k] = INFINITY;
            b[3 + k] = -INFINITY;
        }
        for (int v = 0; v < 3; v++) {
            const double *p = m->x + 3 * (size_t)m->tri[3 * t + (size_t)v];
            for (int k = 0; k < 3; k++) {
                b[k] = fmin(b[k], p[k]);
                b[3 + k] = fmax(b[3 + k], p[k]);
            }
        }
    }
    if (cc_grid_pairs(c.box, m->nt, NULL, on_overlap, &c) || c.oom)
        goto done;
    r->skipped_pairs = c.skipped;
    double t2 = now();

    /* Boxes grown by D/2 each overlap whenever the triangles are within D. */
    double h = opt->distance / 2;
    for (size_t i = 0; i < 6 * m->nt; i++)
        wide[i] = c.box[i] + (i % 6 < 3 ? -h : h);
    if (cc_grid_pairs(wide, m->nt, m->fault, on_near, &c) || c.oom || collect_near(&c))
        goto done;
    double t3 = now();

    size_t n = 0;
    for (size_t i = 0; i < c.pmap.n; i++) {
        cc_pair *p = &c.pairs[i];
        if (p->shared_vertices)
            p->distance = 0;
        else if (p->distance > opt->distance)
            p->distance = INFINITY;
        if (p->shared_vertices || p->shared_edges || p->intersections || isfinite(p->distance) ||
            p->near_edges[0] || p->near_edges[1]) {
            if (n != i)
                c.pairs[n] = *p;
            n++;
        }
    }
    if (n)
        qsort(c.pairs, n, sizeof *c.pairs, cmp_pair);
    r->pairs = c.pairs;
    r->npairs = n;
    r->self = c.self;
    c.pairs = NULL;
    c.self = NULL;
    r->seconds[0] = t1 - t0;
    r->seconds[1] = t2 - t1;
    r->seconds[2] = t3 - t2;
    rc = 0;
done:
    map_free(&c.pmap);
    map_free(&c.emap);
    free(c.pairs);
    free(c.self);
    free(c.vf_start);
    free(c.vf);
    free(c.bflag);
    free(c.box);
    free(c.edist);
    free(wide);
    return rc;
}

void cc_result_free(cc_result *r)
{
    free(r->pairs);
    free(r->self);
    memset(r, 0, sizeof *r);
}
