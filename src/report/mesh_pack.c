/* The set's triangles packed for the page's own drawing. A picture per
 * fault made report.html 10 MB for the CFM; the browser draws each fault
 * and its neighbours from these bytes instead, when a fault is opened.
 *
 * Per tag, in tag order: the count of its triangles, then its triangles in
 * breadth-first order over shared edges. The first of each piece is
 * symbol 0 and its three vertices; every other names its parent's edge,
 * symbol 1 + 3 (parent - previous parent) + edge (parents come in
 * order, so the step is small), and its third vertex. A vertex is either
 * 0 and, new, its grid coordinates less a prediction (the parallelogram
 * over the parent's edge, or for a piece's first vertices the last new
 * vertex of the tag, the grid's origin at first), or k > 0, the vertex k
 * back from the next new one. A triangle's vertices, and so its edges
 * 0..2, are in the order decoded: a piece's first as written, a child
 * across its parent's edge (a, b) as (b, a, third), the parent's
 * orientation carried over. Then the
 * count of its junction edges (sides it shares with a triangle of another
 * tag) and their local vertices; then the outline of the fault's
 * original (none when it has none): the count of its chains, and per
 * chain its count of points and each point less the one before (the
 * grid's origin at first). All numbers are LEB128 varints, signed
 * ones zigzagged. One grid of step H / 16 over the whole set, so that the
 * nodes two faults share coincide on the page; at 1 km a node moves at
 * most 55 m, a twentieth of a triangle. The stream is deflated (zlib
 * format, which the browser's DecompressionStream("deflate") reads):
 * the CFM's 470,172 triangles at 1 km and its outlines take 0.87 MB. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <zlib.h>

#include "fm_sort.h"
#include "report_internal.h"

typedef struct buf {
    unsigned char *d;
    size_t n, cap;
    int bad;
} buf;

/* Room for n more bytes; 0 when memory ran out (b->bad then). */
static int reserve(buf *b, size_t n)
{
    if (b->bad)
        return 0;
    if (b->n + n > b->cap) {
        size_t c = b->cap ? 2 * b->cap : 1 << 16;
        while (c < b->n + n)
            c *= 2;
        unsigned char *g = realloc(b->d, c);
        if (!g) {
            b->bad = 1;
            return 0;
        }
        b->d = g;
        b->cap = c;
    }
    return 1;
}

static void put(buf *b, uint64_t u)
{
    if (!reserve(b, 10))
        return;
    for (; u >= 128; u >>= 7)
        b->d[b->n++] = (unsigned char)(u | 128);
    b->d[b->n++] = (unsigned char)u;
}

static void put_bytes(buf *b, const buf *more)
{
    b->bad |= more->bad;
    if (more->n && reserve(b, more->n)) {
        memcpy(b->d + b->n, more->d, more->n);
        b->n += more->n;
    }
}

static void put_signed(buf *b, int64_t v)
{
    put(b, v >= 0 ? (uint64_t)v << 1 : ((uint64_t)(-(v + 1)) << 1) | 1);
}

typedef struct packer {
    const int32_t *T, *tag;
    const int64_t *q;     /* grid coordinates per vertex */
    const fm_keyed *side; /* the set's sides by key */
    const size_t *group;  /* per triangle side 3t + e: where its key starts in side */
    size_t nsides;
    size_t *local;   /* per vertex: its local index + 1 within the tag, stamped */
    size_t *stamp;   /* per vertex: tag + 1 when local holds this tag's index */
    size_t *queue;   /* triangles in the order written */
    int32_t *qv;     /* their vertices as the decoder orders them */
    char *done;      /* per triangle */
    size_t nlocal;
    int64_t last[3]; /* the last new vertex's coordinates */
    buf *out;
} packer;

/* One vertex reference; pred (NULL: the last new vertex) predicts a new
 * one. */
static void vertex(packer *p, int32_t v, size_t g, const int64_t *pred)
{
    if (p->stamp[v] == g + 1) {
        put(p->out, p->nlocal - p->local[v]);
        return;
    }
    put(p->out, 0);
    p->stamp[v] = g + 1;
    p->local[v] = p->nlocal;
    p->nlocal++;
    const int64_t *x = p->q + 3 * (size_t)v;
    for (int k = 0; k < 3; k++) {
        put_signed(p->out, x[k] - (pred ? pred[k] : p->last[k]));
        p->last[k] = x[k];
    }
}

/* The triangles of tag g, tris[0..n), breadth first. */
static void pack_tag(packer *p, size_t g, const size_t *tris, size_t n)
{
    put(p->out, n);
    p->nlocal = 0;
    memset(p->last, 0, sizeof p->last); /* each tag decodes on its own */
    size_t nq = 0, head = 0, last_parent = 0;
    for (size_t s = 0; s < n; s++) {
        if (p->done[tris[s]])
            continue;
        p->done[tris[s]] = 1;
        p->queue[nq++] = tris[s];
        put(p->out, 0);
        for (int c = 0; c < 3; c++)
            vertex(p, p->T[3 * tris[s] + c], g, NULL);
        memcpy(p->qv + 3 * (nq - 1), p->T + 3 * tris[s], 3 * sizeof *p->qv);
        for (; head < nq; head++) {
            size_t t = p->queue[head];
            /* the parent's vertices in the order the decoder holds them */
            const int32_t *pv = p->qv + 3 * head;
            for (int e = 0; e < 3; e++) {
                int32_t a = pv[e], b = pv[(e + 1) % 3], o = pv[(e + 2) % 3];
                uint64_t key = fm_edge_key((uint64_t)a, (uint64_t)b);
                size_t at = 0;
                for (int k = 0; k < 3; k++)
                    if (p->side[p->group[3 * t + k]].key == key)
                        at = p->group[3 * t + k];
                for (size_t i = at; i < p->nsides && p->side[i].key == key; i++) {
                    size_t c = p->side[i].index;
                    if (p->done[c] || p->tag[c] != (int32_t)g)
                        continue;
                    int32_t third = -1, others = 0;
                    for (int k = 0; k < 3; k++)
                        if (p->T[3 * c + k] != a && p->T[3 * c + k] != b) {
                            third = p->T[3 * c + k];
                            others++;
                        }
                    if (others != 1) /* degenerate: it starts a piece of its own */
                        continue;
                    p->done[c] = 1;
                    /* (b, a, third): the parent's orientation carried over */
                    int32_t *cv = p->qv + 3 * nq;
                    cv[0] = b;
                    cv[1] = a;
                    cv[2] = third;
                    p->queue[nq++] = c;
                    put(p->out, 1 + 3 * (uint64_t)(head - last_parent) + (uint64_t)e);
                    last_parent = head;
                    int64_t pred[3];
                    const int64_t *xa = p->q + 3 * (size_t)a, *xb = p->q + 3 * (size_t)b,
                                  *xo = p->q + 3 * (size_t)o;
                    for (int k = 0; k < 3; k++)
                        pred[k] = xa[k] + xb[k] - xo[k];
                    vertex(p, third, g, pred);
                }
            }
        }
    }
}

/* Sides of tag g's triangles that a triangle of another tag has too, as
 * local vertex pairs. */
static void pack_junctions(packer *p, size_t g, const size_t *tris, size_t n, buf *tmp)
{
    tmp->n = 0;
    size_t count = 0;
    for (size_t s = 0; s < n; s++) {
        size_t t = tris[s];
        for (int e = 0; e < 3; e++) {
            size_t at = p->group[3 * t + e];
            uint64_t key = p->side[at].key;
            int mine_first = 0, other = 0;
            for (size_t i = at; i < p->nsides && p->side[i].key == key; i++) {
                size_t c = p->side[i].index;
                if (p->tag[c] != (int32_t)g)
                    other = 1;
                else if (!mine_first)
                    mine_first = c == t ? 1 : -1; /* the first of this tag writes it */
            }
            if (!other || mine_first != 1)
                continue;
            int32_t a = p->T[3 * t + e], b = p->T[3 * t + (e + 1) % 3];
            put(tmp, p->local[a]);
            put(tmp, p->local[b]);
            count++;
        }
    }
    put(p->out, count);
    put_bytes(p->out, tmp);
}

/* The outline of the original m (NULL: none) on the grid. */
static fm_status pack_outline(packer *p, const fm_mesh *m, const double origin[3], double step)
{
    rp_chains c = {0};
    fm_status st = m ? rp_outline(m, &c) : FM_OK;
    if (st != FM_OK)
        return st;
    put(p->out, c.n);
    const double *X = m ? fm_mesh_vertices(m) : NULL;
    int64_t last[3] = {0, 0, 0};
    for (size_t k = 0; k < c.n; k++) {
        put(p->out, c.start[k + 1] - c.start[k]);
        for (size_t i = c.start[k]; i < c.start[k + 1]; i++)
            for (int d = 0; d < 3; d++) {
                int64_t q = llround((X[3 * (size_t)c.v[i] + d] - origin[d]) / step);
                put_signed(p->out, q - last[d]);
                last[d] = q;
            }
    }
    rp_chains_free(&c);
    return FM_OK;
}

/* For each side 3t + e, where its key's run starts in side. */
static size_t *side_groups(const fm_mesh *m, const fm_keyed *side, size_t ns)
{
    const int32_t *T = fm_mesh_triangles(m);
    size_t *group = malloc((ns + 1) * sizeof *group);
    if (!group)
        return NULL;
    for (size_t i = 0, start = 0; i < ns; i++) {
        if (i > 0 && side[i].key != side[i - 1].key)
            start = i;
        size_t t = side[i].index;
        for (int e = 0; e < 3; e++)
            if (fm_edge_key((uint64_t)T[3 * t + e], (uint64_t)T[3 * t + (e + 1) % 3]) ==
                side[i].key)
                group[3 * t + e] = start;
    }
    return group;
}

fm_status rp_pack_set(const fm_report *r, size_t ntags, rp_pack *out)
{
    memset(out, 0, sizeof *out);
    const fm_mesh *m = r->set;
    size_t nt = m ? fm_mesh_ntriangles(m) : 0, nv = m ? fm_mesh_nvertices(m) : 0, ns = 0;
    const double *X = m ? fm_mesh_vertices(m) : NULL;
    out->step = r->size / 16;
    for (size_t v = 0; v < nv; v++)
        for (int k = 0; k < 3; k++)
            out->origin[k] = v ? fmin(out->origin[k], X[3 * v + k]) : X[3 * v + k];
    for (int k = 0; k < 3; k++)
        out->origin[k] = floor(out->origin[k]);
    fm_keyed *side = nt ? fm_mesh_sides(m, &ns) : NULL;
    size_t *group = side ? side_groups(m, side, ns) : NULL;
    int64_t *q = malloc((3 * nv + 1) * sizeof *q);
    size_t *start = calloc(ntags + 2, sizeof *start), *order = malloc((nt + 1) * sizeof *order);
    size_t *local = malloc((nv + 1) * sizeof *local), *stamp = calloc(nv + 1, sizeof *stamp);
    size_t *queue = malloc((nt + 1) * sizeof *queue);
    int32_t *qv = malloc((3 * nt + 3) * sizeof *qv);
    char *done = calloc(nt + 1, 1);
    buf b = {0}, tmp = {0};
    fm_status st = q && start && order && local && stamp && queue && qv && done &&
                           (!nt || (side && group))
                       ? FM_OK
                       : FM_ERR_NOMEM;
    const int32_t *tag = m ? fm_mesh_tags(m) : NULL;
    if (st == FM_OK) {
        for (size_t v = 0; v < nv; v++)
            for (int k = 0; k < 3; k++)
                q[3 * v + k] = llround((X[3 * v + k] - out->origin[k]) / out->step);
        /* triangles by tag, in triangle order (counting sort) */
        for (size_t t = 0; t < nt; t++)
            if (tag[t] >= 0 && (size_t)tag[t] < ntags)
                start[tag[t] + 1]++;
        for (size_t g = 0; g < ntags; g++)
            start[g + 1] += start[g];
        for (size_t t = 0; t < nt; t++)
            if (tag[t] >= 0 && (size_t)tag[t] < ntags)
                order[start[tag[t]]++] = t;
        for (size_t g = ntags; g > 0; g--)
            start[g] = start[g - 1];
        start[0] = 0;
        packer p = {fm_mesh_triangles(m), tag, q, side, group, ns, local, stamp, queue, qv, done, 0, {0, 0, 0}, &b};
        for (size_t g = 0; g < ntags && !b.bad && st == FM_OK; g++) {
            pack_tag(&p, g, order + start[g], start[g + 1] - start[g]);
            pack_junctions(&p, g, order + start[g], start[g + 1] - start[g], &tmp);
            const fm_mesh *orig = NULL;
            for (size_t i = 0; i < r->nf && !orig; i++)
                if (r->f[i].tag == (int32_t)g)
                    orig = r->f[i].original;
            st = pack_outline(&p, orig, out->origin, out->step);
        }
        if (st == FM_OK && b.bad)
            st = FM_ERR_NOMEM;
    }
    if (st == FM_OK) {
        uLongf n = compressBound((uLong)b.n);
        out->data = malloc(n + 1);
        /* zlib's default level: the best level took 0.17 s more of the
         * whole CFM's report at 1 km to save 8 KB of its 2.4 MB */
        if (!out->data || compress2(out->data, &n, b.d, (uLong)b.n, Z_DEFAULT_COMPRESSION) != Z_OK)
            st = FM_ERR_NOMEM;
        out->n = n;
        out->raw = b.n;
    }
    if (st != FM_OK) {
        free(out->data);
        out->data = NULL;
        out->n = 0;
    }
    free(b.d);
    free(tmp.d);
    free(side);
    free(group);
    free(q);
    free(start);
    free(order);
    free(local);
    free(stamp);
    free(queue);
    free(qv);
    free(done);
    return st;
}
