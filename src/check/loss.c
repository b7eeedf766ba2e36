/* What connecting faults cost (fm_check.h, fm_check_loss): the set's
 * topology once (outline edges per fault, nodes shared by two faults,
 * edge-connected pieces) beside its closest-point tree, then every fault
 * measured on its own on any thread, then the pairs gathered. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check_internal.h"
#include "fm_parallel.h"

struct fm_loss {
    fm_loss_fault *fault;
    size_t nfaults;
    fm_loss_pair *pair;
    size_t npairs;
};

/* Triangles per fault, outline edges per fault and pieces, from the sides
 * of the set's triangles. */
static fm_status topology(const fm_mesh *m, const int32_t *sheet, size_t nf, ck_set *s)
{
    size_t nt = fm_mesh_ntriangles(m), ns = 0;
    const int32_t *tag = fm_mesh_tags(m);
    s->tri_first = calloc(nf + 2, sizeof *s->tri_first);
    s->bnd_first = calloc(nf + 2, sizeof *s->bnd_first);
    s->tri = malloc((nt + 1) * sizeof *s->tri);
    s->root = malloc((nt + 1) * sizeof *s->root);
    s->piece_size = calloc(nt + 1, sizeof *s->piece_size);
    fm_keyed *side = fm_mesh_sides(m, &ns);
    fm_keyed *bnd = malloc((ns + 1) * sizeof *bnd);
    if (!s->tri_first || !s->bnd_first || !s->tri || !s->root || !s->piece_size || !side || !bnd) {
        free(side);
        free(bnd);
        return FM_ERR_NOMEM;
    }
    for (size_t t = 0; t < nt; t++) {
        s->tri_first[tag[t] + 1]++;
        s->root[t] = (int32_t)t;
    }
    for (size_t f = 0; f < nf; f++)
        s->tri_first[f + 1] += s->tri_first[f];
    size_t *at = s->bnd_first; /* borrowed as a cursor, reset below */
    for (size_t f = 0; f <= nf; f++)
        at[f] = s->tri_first[f];
    for (size_t t = 0; t < nt; t++)
        s->tri[at[tag[t]]++] = (int32_t)t;
    memset(at, 0, (nf + 2) * sizeof *at);
    size_t nb = 0;
    for (size_t e = 0; e < ns;) {
        size_t r = e + 1;
        while (r < ns && side[r].key == side[e].key)
            r++;
        for (size_t i = e; i < r; i++) {
            int32_t t = (int32_t)side[i].index, same = 0;
            for (size_t j = e; j < r; j++)
                if (tag[side[j].index] == tag[t]) {
                    same++;
                    /* joined to an earlier triangle of its sheet */
                    if (j < i && (!sheet || sheet[side[j].index] == sheet[t])) {
                        ck_unite(s->root, t, (int32_t)side[j].index);
                    }
                }
            if (same == 1)
                bnd[nb++] = (fm_keyed){side[e].key, (size_t)tag[t]};
        }
        e = r;
    }
    free(side);
    s->bnd = malloc((nb + 1) * sizeof *s->bnd);
    if (!s->bnd) {
        free(bnd);
        return FM_ERR_NOMEM;
    }
    for (size_t i = 0; i < nb; i++)
        at[bnd[i].index + 1]++;
    for (size_t f = 0; f < nf; f++)
        at[f + 1] += at[f];
    size_t *cur = malloc((nf + 1) * sizeof *cur);
    if (!cur) {
        free(bnd);
        return FM_ERR_NOMEM;
    }
    memcpy(cur, at, (nf + 1) * sizeof *cur);
    for (size_t i = 0; i < nb; i++) /* stable: each fault's edges in key order */
        s->bnd[cur[bnd[i].index]++] = bnd[i].key;
    free(cur);
    free(bnd);
    for (size_t t = 0; t < nt; t++) {
        s->root[t] = ck_find(s->root, (int32_t)t);
        s->piece_size[s->root[t]]++;
    }
    return FM_OK;
}

/* Nodes used by two faults, keyed by the pair. */
static fm_status shared_nodes(const fm_mesh *m, ck_set *s)
{
    size_t nt = fm_mesh_ntriangles(m), n = 0;
    const int32_t *T = fm_mesh_triangles(m), *tag = fm_mesh_tags(m);
    uint64_t *vf = malloc((3 * nt + 1) * sizeof *vf);
    if (!vf)
        return FM_ERR_NOMEM;
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++)
            vf[n++] = (uint64_t)(uint32_t)T[3 * t + k] << 32 | (uint32_t)tag[t];
    qsort(vf, n, sizeof *vf, ck_cmp_u64);
    size_t u = 0;
    for (size_t i = 0; i < n; i++)
        if (!u || vf[i] != vf[u - 1])
            vf[u++] = vf[i];
    size_t np = 0, cap = 0;
    fm_keyed *sh = NULL;
    for (size_t i = 0; i < u;) {
        size_t r = i + 1;
        while (r < u && vf[r] >> 32 == vf[i] >> 32)
            r++;
        for (size_t a = i; a < r; a++)
            for (size_t b = a + 1; b < r; b++) {
                if (np == cap) {
                    cap = cap ? 2 * cap : 1024;
                    fm_keyed *g = realloc(sh, cap * sizeof *g);
                    if (!g) {
                        free(sh);
                        free(vf);
                        return FM_ERR_NOMEM;
                    }
                    sh = g;
                }
                sh[np++] = (fm_keyed){(vf[a] & 0xffffffffu) << 32 | (vf[b] & 0xffffffffu),
                                      (size_t)(vf[i] >> 32)};
            }
        i = r;
    }
    free(vf);
    if (np && fm_sort_keyed(sh, np)) {
        free(sh);
        return FM_ERR_NOMEM;
    }
    s->shared = sh;
    s->nshared = np;
    return FM_OK;
}

/* The set's topology and its closest-point tree, side by side: neither
 * reads what the other makes. */
typedef struct prep_work {
    const fm_mesh *m;
    const int32_t *sheet;
    size_t nf;
    ck_set *s;
    fm_status st[2];
    fm_closest_tree *all;
    fm_error err;
} prep_work;

static void prep_one(void *user, size_t k)
{
    prep_work *w = user;
    if (k == 0) {
        w->st[0] = topology(w->m, w->sheet, w->nf, w->s);
        if (w->st[0] == FM_OK)
            w->st[0] = shared_nodes(w->m, w->s);
    } else {
        w->all = fm_closest_tree_create_quick(w->m, &w->err);
        w->st[1] = w->all ? FM_OK : w->err.code;
    }
}

typedef struct loss_work {
    const ck_set *s;
    ck_fault_out *out;
} loss_work;

static void measure_one(void *user, size_t f)
{
    loss_work *w = user;
    ck_measure_fault(w->s, f, &w->out[f]);
}

/* The originals' pieces, one fault per task (SIZE_MAX: out of memory). */
typedef struct orig_work {
    const fm_loss_input *in;
    size_t *op;
} orig_work;

static void orig_one(void *user, size_t f)
{
    orig_work *w = user;
    const fm_loss_input *in = w->in;
    const fm_mesh *o = in->orig ? in->orig[f] : NULL;
    w->op[f] = o ? ck_orig_pieces(o, in->zcut[f], in->zcut[f] - 0.1 * in->size[f]) : 0;
}

/* Pieces of each fault's output against those of its original. */
static fm_status pieces(const ck_set *s, fm_loss_fault *F)
{
    const fm_loss_input *in = s->in;
    size_t nf = in->nfaults;
    /* the originals are whole input meshes: counted on every thread */
    size_t *op = malloc((nf + 1) * sizeof *op);
    if (!op)
        return FM_ERR_NOMEM;
    orig_work ow = {in, op};
    fm_parallel_for(nf, in->threads, orig_one, &ow, NULL, NULL, 0, 0);
    for (size_t f = 0; f < nf; f++) {
        size_t n = s->tri_first[f + 1] - s->tri_first[f];
        size_t *sz = malloc((n + 1) * sizeof *sz), k = 0;
        uint64_t *sh = malloc((n + 1) * sizeof *sh);
        if (!sz || !sh) {
            free(sz);
            free(sh);
            free(op);
            return FM_ERR_NOMEM;
        }
        for (size_t i = 0; i < n; i++) {
            int32_t t = s->tri[s->tri_first[f] + i];
            if (s->root[t] == t)
                sz[k++] = s->piece_size[t];
            sh[i] = in->sheet ? (uint64_t)(uint32_t)in->sheet[t] : 0;
        }
        qsort(sh, n, sizeof *sh, ck_cmp_u64);
        size_t nsh = 0;
        for (size_t i = 0; i < n; i++)
            nsh += !i || sh[i] != sh[i - 1];
        free(sh);
        F[f].pieces = k;
        F[f].sheets = nsh;
        size_t expect = nsh;
        const fm_mesh *o = in->orig ? in->orig[f] : NULL;
        if (o) {
            if (op[f] == SIZE_MAX) {
                free(sz);
                free(op);
                return FM_ERR_NOMEM;
            }
            F[f].orig_pieces = op[f];
            expect = op[f] > nsh ? op[f] : nsh;
        }
        if (k > expect) {
            F[f].islands = k - expect;
            qsort(sz, k, sizeof *sz, ck_cmp_u64);
            for (size_t i = 0; i < k - expect; i++)
                F[f].island_triangles += sz[i];
        }
        free(sz);
    }
    free(op);
    return FM_OK;
}

static int cmp_pair(const void *a, const void *b)
{
    const fm_loss_pair *x = a, *y = b;
    if (x->a != y->a)
        return (x->a > y->a) - (x->a < y->a);
    return (x->b > y->b) - (x->b < y->b);
}

/* Every fault's gaps beside others as pairs (a < b). */
static fm_status gather_pairs(const ck_set *s, const ck_fault_out *out, fm_loss *l)
{
    size_t n = 0;
    for (size_t f = 0; f < l->nfaults; f++)
        n += out[f].ngaps;
    fm_loss_pair *p = malloc((n + 1) * sizeof *p);
    if (!p)
        return FM_ERR_NOMEM;
    size_t k = 0;
    for (size_t f = 0; f < l->nfaults; f++)
        for (size_t i = 0; i < out[f].ngaps; i++) {
            int32_t g = out[f].gaps[i].other, a = (int32_t)f < g ? (int32_t)f : g;
            p[k++] = (fm_loss_pair){a, a == g ? (int32_t)f : g, a == (int32_t)f ? out[f].gaps[i].length : 0,
                                    a == (int32_t)f ? 0 : out[f].gaps[i].length, 0, 0};
        }
    qsort(p, k, sizeof *p, cmp_pair);
    size_t u = 0;
    for (size_t i = 0; i < k; i++) {
        if (u && p[u - 1].a == p[i].a && p[u - 1].b == p[i].b) {
            p[u - 1].gap_ab += p[i].gap_ab;
            p[u - 1].gap_ba += p[i].gap_ba;
        } else
            p[u++] = p[i];
    }
    for (size_t i = 0; i < u; i++) {
        p[i].gap = fmax(p[i].gap_ab, p[i].gap_ba);
        uint64_t key = (uint64_t)p[i].a << 32 | (uint64_t)p[i].b;
        for (size_t j = fm_keyed_lower_bound(s->shared, s->nshared, key);
             j < s->nshared && s->shared[j].key == key; j++)
            p[i].shared_nodes++;
    }
    l->pair = p;
    l->npairs = u;
    return FM_OK;
}

fm_status fm_check_loss(const fm_loss_input *in, fm_loss **out, fm_error *err)
{
    *out = NULL;
    const fm_mesh *m = in->set;
    size_t nt = fm_mesh_ntriangles(m), nf = in->nfaults;
    const int32_t *tag = fm_mesh_tags(m);
    for (size_t t = 0; t < nt; t++)
        if (tag[t] < 0 || (size_t)tag[t] >= nf)
            return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                                "triangle %zu is tagged %d, not a fault of %zu", t, tag[t], nf);
    for (size_t f = 0; f < nf; f++)
        if (!(in->size[f] > 0) || !(in->join[f] >= 0))
            return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                                "fault %zu: size %g and join distance %g", f, in->size[f],
                                in->join[f]);
    fm_loss *l = calloc(1, sizeof *l);
    ck_set s = {in, NULL, NULL, NULL, NULL, NULL, NULL, 0, NULL, NULL};
    ck_fault_out *fo = calloc(nf + 1, sizeof *fo);
    fm_status st = l && fo ? FM_OK : FM_ERR_NOMEM;
    prep_work pw = {m, in->sheet, nf, &s, {FM_OK, FM_OK}, NULL, {0}};
    fm_error_clear(&pw.err);
    if (st == FM_OK) {
        fm_parallel_for(2, in->threads, prep_one, &pw, NULL, NULL, 0, 0);
        st = pw.st[0] != FM_OK ? pw.st[0] : pw.st[1];
        if (pw.st[0] == FM_OK && pw.st[1] != FM_OK && err)
            *err = pw.err;
    }
    fm_closest_tree *all = pw.all;
    s.all = all;
    if (st == FM_OK) {
        loss_work w = {&s, fo};
        fm_parallel_for(nf, in->threads, measure_one, &w, NULL, NULL, 0, 0);
        for (size_t f = 0; f < nf && st == FM_OK; f++)
            st = fo[f].st;
    }
    if (st == FM_OK) {
        l->nfaults = nf;
        l->fault = malloc((nf + 1) * sizeof *l->fault);
        st = l->fault ? FM_OK : FM_ERR_NOMEM;
        for (size_t f = 0; f < nf && st == FM_OK; f++)
            l->fault[f] = fo[f].m;
    }
    if (st == FM_OK)
        st = pieces(&s, l->fault);
    if (st == FM_OK)
        st = gather_pairs(&s, fo, l);
    for (size_t f = 0; fo && f < nf; f++)
        free(fo[f].gaps);
    free(fo);
    fm_closest_tree_destroy(all);
    free(s.tri_first);
    free(s.bnd_first);
    free(s.tri);
    free(s.bnd);
    free(s.shared);
    free(s.piece_size);
    free(s.root);
    if (st != FM_OK) {
        fm_loss_destroy(l);
        if (st == FM_ERR_NOMEM)
            fm_error_set(err, st, NULL, 0, "out of memory measuring the connected set");
        return st;
    }
    *out = l;
    return FM_OK;
}

void fm_loss_destroy(fm_loss *l)
{
    if (!l)
        return;
    free(l->fault);
    free(l->pair);
    free(l);
}

const fm_loss_fault *fm_loss_fault_at(const fm_loss *l, size_t f)
{
    return f < l->nfaults ? &l->fault[f] : NULL;
}

size_t fm_loss_npairs(const fm_loss *l)
{
    return l->npairs;
}

const fm_loss_pair *fm_loss_pair_at(const fm_loss *l, size_t k)
{
    return k < l->npairs ? &l->pair[k] : NULL;
}
