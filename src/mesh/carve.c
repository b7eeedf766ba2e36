/* faultmesh mesh: removing what is left of faults running through each
 * other (fm_carve.h).
 *
 * Candidates come from a uniform grid over the triangles' bounding boxes
 * (the set is a few hundred thousand triangles of about one size): each
 * triangle is listed under every cell its box touches, the list is sorted
 * by cell, and two triangles of different faults in one cell are tested
 * when their boxes overlap and this cell holds the low corner of the
 * overlap, so that each pair is tested once. What the decisions need of
 * the set (areas, triangles on junctions, pieces) is made beside the
 * search, on a second thread. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "carve_pieces.h"
#include "fm_carve.h"
#include "fm_parallel.h"
#include "fm_predicates.h"
#include "fm_sort.h"

struct fm_carve_result {
    fm_carve_pair *pairs;
    size_t n;
    size_t removed;
    size_t slivers; /* removed with the notch they bordered */
};

/* A triangle under this angle (degrees) left at the edge of a notch goes
 * with it: it was acceptable where it met the other fault's curve, and is
 * only a sliver on an open edge once that fault is gone. */
#define NOTCH_SLIVER_DEG 20.0

/* Two triangles of different faults that meet; fault a < fault b. */
typedef struct contact {
    int32_t fa, fb, ta, tb;
} contact;

#define CELL_BITS 21
#define CELL_MAX ((1 << CELL_BITS) - 1)

typedef struct grid {
    double origin[3], cell;
} grid;

static int64_t cell_of(const grid *g, double x, int k)
{
    return (int64_t)floor((x - g->origin[k]) / g->cell);
}

static uint64_t cell_key(int64_t i, int64_t j, int64_t k)
{
    return (uint64_t)i << (2 * CELL_BITS) | (uint64_t)j << CELL_BITS | (uint64_t)k;
}

static int by_faults_then_triangles(const void *pa, const void *pb)
{
    const contact *a = pa, *b = pb;
    if (a->fa != b->fa)
        return a->fa < b->fa ? -1 : 1;
    if (a->fb != b->fb)
        return a->fb < b->fb ? -1 : 1;
    if (a->ta != b->ta)
        return a->ta < b->ta ? -1 : 1;
    return a->tb < b->tb ? -1 : a->tb > b->tb;
}

static int by_value(const void *pa, const void *pb)
{
    int32_t a = *(const int32_t *)pa, b = *(const int32_t *)pb;
    return a < b ? -1 : a > b;
}

/* Distinct values of v (sorted in place), their count. */
static size_t distinct(int32_t *v, size_t n)
{
    qsort(v, n, sizeof *v, by_value);
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (!m || v[m - 1] != v[i])
            v[m++] = v[i];
    return m;
}

/* The grid: cells of side `cell` (twice the mean edge length when <= 0),
 * widened until every coordinate range fits CELL_BITS bits. */
static grid make_grid(const double *box, size_t nt, double cell, const fm_mesh *m)
{
    grid g = {{INFINITY, INFINITY, INFINITY}, cell};
    double hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            g.origin[k] = fmin(g.origin[k], box[6 * t + k]);
            hi[k] = fmax(hi[k], box[6 * t + 3 + k]);
        }
    if (!(g.cell > 0)) {
        fm_mesh_stats st;
        g.cell = fm_mesh_compute_stats(m, &st) == FM_OK && st.edge_mean > 0 ? 2 * st.edge_mean
                                                                              : 1.0;
    }
    for (int k = 0; k < 3; k++)
        while ((hi[k] - g.origin[k]) / g.cell >= CELL_MAX)
            g.cell *= 2;
    return g;
}

static int boxes_overlap(const double *a, const double *b)
{
    for (int k = 0; k < 3; k++)
        if (a[k] > b[3 + k] || b[k] > a[3 + k])
            return 0;
    return 1;
}

/* Every pair of triangles of different faults that meet, sorted; -1 when
 * out of memory. */
static int find_contacts(const fm_mesh *m, double cell, contact **out, size_t *nout)
{
    size_t nt = fm_mesh_ntriangles(m);
    const int32_t *T = fm_mesh_triangles(m), *tag = fm_mesh_tags(m);
    const double *X = fm_mesh_vertices(m);
    *out = NULL;
    *nout = 0;
    double *box = malloc((6 * nt + 1) * sizeof *box);
    if (!box)
        return -1;
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            double a = X[3 * T[3 * t] + k], b = X[3 * T[3 * t + 1] + k], c = X[3 * T[3 * t + 2] + k];
            box[6 * t + k] = fmin(a, fmin(b, c));
            box[6 * t + 3 + k] = fmax(a, fmax(b, c));
        }
    grid g = make_grid(box, nt, cell, m);
    size_t nkeys = 0;
    for (size_t t = 0; t < nt; t++) {
        size_t c = 1;
        for (int k = 0; k < 3; k++)
            c *= (size_t)(cell_of(&g, box[6 * t + 3 + k], k) - cell_of(&g, box[6 * t + k], k) + 1);
        nkeys += c;
    }
    fm_keyed *key = malloc((nkeys + 1) * sizeof *key);
    if (!key) {
        free(box);
        return -1;
    }
    size_t q = 0;
    for (size_t t = 0; t < nt; t++) {
        int64_t lo[3], hi[3];
        for (int k = 0; k < 3; k++) {
            lo[k] = cell_of(&g, box[6 * t + k], k);
            hi[k] = cell_of(&g, box[6 * t + 3 + k], k);
        }
        for (int64_t i = lo[0]; i <= hi[0]; i++)
            for (int64_t j = lo[1]; j <= hi[1]; j++)
                for (int64_t k = lo[2]; k <= hi[2]; k++)
                    key[q++] = (fm_keyed){cell_key(i, j, k), t};
    }
    int rc = fm_sort_keyed(key, nkeys);
    size_t cap = 0;
    for (size_t s = 0, e; rc == 0 && s < nkeys; s = e) {
        for (e = s + 1; e < nkeys && key[e].key == key[s].key; e++)
            ;
        for (size_t i = s; i < e && rc == 0; i++)
            for (size_t j = i + 1; j < e; j++) {
                size_t a = key[i].index, b = key[j].index;
                if (tag[a] == tag[b] || !boxes_overlap(box + 6 * a, box + 6 * b))
                    continue;
                int64_t c[3];
                for (int k = 0; k < 3; k++)
                    c[k] = cell_of(&g, fmax(box[6 * a + k], box[6 * b + k]), k);
                if (cell_key(c[0], c[1], c[2]) != key[s].key ||
                    !fm_triangles_meet_apart(T + 3 * a, T + 3 * b, X))
                    continue;
                if (*nout == cap) {
                    size_t nc = cap ? 2 * cap : 256;
                    contact *grown = realloc(*out, nc * sizeof *grown);
                    if (!grown) {
                        rc = -1;
                        break;
                    }
                    *out = grown;
                    cap = nc;
                }
                int swap = tag[a] > tag[b];
                (*out)[(*nout)++] = (contact){tag[swap ? b : a], tag[swap ? a : b],
                                              (int32_t)(swap ? b : a), (int32_t)(swap ? a : b)};
            }
    }
    free(key);
    free(box);
    if (rc == 0 && *nout)
        qsort(*out, *nout, sizeof **out, by_faults_then_triangles);
    return rc;
}

static double area_of(const fm_mesh *m, const int32_t *t, size_t n)
{
    const int32_t *T = fm_mesh_triangles(m);
    const double *X = fm_mesh_vertices(m);
    double a = 0;
    for (size_t k = 0; k < n; k++) {
        const int32_t *v = T + 3 * (size_t)t[k];
        a += fm_triangle_area(X + 3 * v[0], X + 3 * v[1], X + 3 * v[2]);
    }
    return a;
}

/* One more than the largest tag. */
static size_t fault_count(const fm_mesh *m)
{
    size_t nt = fm_mesh_ntriangles(m), nf = 0;
    const int32_t *tag = fm_mesh_tags(m);
    for (size_t t = 0; t < nt; t++)
        if (tag[t] >= 0 && (size_t)tag[t] + 1 > nf)
            nf = (size_t)tag[t] + 1;
    return nf;
}

/* Area of every fault (by tag); NULL when out of memory. */
static double *fault_areas(const fm_mesh *m, size_t *nf)
{
    size_t nt = fm_mesh_ntriangles(m);
    const int32_t *tag = fm_mesh_tags(m);
    *nf = fault_count(m);
    double *a = calloc(*nf + 1, sizeof *a);
    for (size_t t = 0; a && t < nt; t++) {
        int32_t one = (int32_t)t;
        if (tag[t] >= 0)
            a[tag[t]] += area_of(m, &one, 1);
    }
    return a;
}

/* Per triangle: 1 if a side of it is a side of another fault's triangle
 * (it holds a piece of a curve the two share). NULL when out of memory. */
static unsigned char *on_junction(const fm_mesh *m)
{
    size_t nt = fm_mesh_ntriangles(m), ns;
    const int32_t *tag = fm_mesh_tags(m);
    unsigned char *on = calloc(nt + 1, 1);
    fm_keyed *side = on ? fm_mesh_sides(m, &ns) : NULL;
    if (!side) {
        free(on);
        return NULL;
    }
    for (size_t s = 0, e; s < ns; s = e) {
        int mixed = 0;
        for (e = s + 1; e < ns && side[e].key == side[s].key; e++)
            mixed |= tag[side[e].index] != tag[side[s].index];
        for (size_t i = s; mixed && i < e; i++)
            on[side[i].index] = 1;
    }
    free(side);
    return on;
}

static int any_on(const unsigned char *on, const int32_t *t, size_t n)
{
    for (size_t k = 0; k < n; k++)
        if (on[t[k]])
            return 1;
    return 0;
}

/* Of the n triangles in t, those not yet gone (t is distinct). */
static size_t still_there(const unsigned char *gone, const int32_t *t, size_t n)
{
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        k += !gone[t[i]];
    return k;
}

/* What decide reads of the set: every fault's area, the triangles on a
 * junction (on_junction), the pieces (carve_pieces.h). */
typedef struct set_facts {
    double *total;
    unsigned char *junction;
    cv_pieces *pieces;
} set_facts;

static void set_facts_make(const fm_mesh *m, set_facts *f)
{
    size_t nf;
    f->total = fault_areas(m, &nf);
    f->junction = on_junction(m);
    f->pieces = cv_pieces_create(m);
}

static void set_facts_free(set_facts *f)
{
    free(f->total);
    free(f->junction);
    cv_pieces_destroy(f->pieces);
}

/* Decides each pair of faults in the sorted contacts and marks the
 * triangles to remove; fills r->pairs. The fault that gives way is the one
 * whose triangles there hold no piece of a curve it shares with a fault,
 * when only one of them is so, else the one losing the smaller share of
 * its area, so that a small fault is not eaten by a large one it touches.
 * Neither is emptied: when the one chosen would lose its last triangles
 * the other gives way, and when both would, the pair is kept (at sizes
 * near a fault's own extent, a fault of one triangle meets another's).
 * Nor, by the area rule, is one cut in two when the other need not be:
 * the piece cut off would be an island of a few triangles.
 * left: triangles per fault not (yet) gone. -1 when out of memory. */
static int decide(const fm_mesh *m, const contact *c, size_t n, unsigned char *gone,
                  size_t *left, const set_facts *facts, fm_carve_result *r)
{
    const double *total = facts->total;
    const unsigned char *junction = facts->junction;
    cv_pieces *pieces = facts->pieces;
    int32_t *ta = malloc((n + 1) * sizeof *ta), *tb = malloc((n + 1) * sizeof *tb);
    size_t npairs = 0;
    for (size_t i = 0; i < n; i++)
        npairs += !i || c[i].fa != c[i - 1].fa || c[i].fb != c[i - 1].fb;
    r->pairs = calloc(npairs + 1, sizeof *r->pairs);
    /* with no contact the facts are not read (nor, for an empty set, made) */
    if (!ta || !tb || !r->pairs || (n && (!total || !junction || !pieces))) {
        free(ta);
        free(tb);
        return -1;
    }
    for (size_t s = 0, e; s < n; s = e) {
        for (e = s; e < n && c[e].fa == c[s].fa && c[e].fb == c[s].fb; e++) {
            ta[e - s] = c[e].ta;
            tb[e - s] = c[e].tb;
        }
        size_t na = distinct(ta, e - s), nb = distinct(tb, e - s);
        fm_carve_pair *p = &r->pairs[r->n++];
        p->fault[0] = c[s].fa;
        p->fault[1] = c[s].fb;
        p->contacts = e - s;
        double lost_a = area_of(m, ta, na), lost_b = area_of(m, tb, nb);
        int ja = any_on(junction, ta, na), jb = any_on(junction, tb, nb);
        /* the later fault on a tie */
        p->yielded = ja != jb ? ja : lost_b * total[c[s].fa] <= lost_a * total[c[s].fb];
        int empties[2] = {still_there(gone, ta, na) >= left[c[s].fa],
                          still_there(gone, tb, nb) >= left[c[s].fb]};
        if (ja == jb && !empties[0] && !empties[1]) {
            int y = p->yielded;
            const int32_t *ly = y ? tb : ta, *lo = y ? ta : tb;
            size_t ny = y ? nb : na, no = y ? na : nb;
            int32_t fy = p->fault[y], fo = p->fault[!y];
            /* the other's count only when the one chosen would split */
            if (cv_pieces_count(pieces, fy, gone, ly, ny) >
                    cv_pieces_count(pieces, fy, gone, NULL, 0) &&
                cv_pieces_count(pieces, fo, gone, lo, no) <=
                    cv_pieces_count(pieces, fo, gone, NULL, 0))
                p->yielded = !y;
        }
        if (empties[p->yielded])
            p->yielded = !p->yielded;
        if (empties[p->yielded]) {
            p->kept = 1;
            continue;
        }
        const int32_t *lose = p->yielded ? tb : ta;
        p->removed = p->yielded ? nb : na;
        p->area = p->yielded ? lost_b : lost_a;
        for (size_t k = 0; k < p->removed; k++)
            if (!gone[lose[k]]) {
                gone[lose[k]] = 1;
                left[p->fault[p->yielded]]--;
            }
    }
    free(ta);
    free(tb);
    return 0;
}

/* Marks as gone the slivers of a fault that share a corner with one of its
 * own triangles already gone, short of a fault's last triangle; their
 * count. -1 when out of memory. */
static long tidy_notches(const fm_mesh *m, unsigned char *gone, size_t *left)
{
    size_t nt = fm_mesh_ntriangles(m), ngone = 0;
    const int32_t *T = fm_mesh_triangles(m), *tag = fm_mesh_tags(m);
    const double *X = fm_mesh_vertices(m);
    for (size_t t = 0; t < nt; t++)
        ngone += gone[t];
    if (!ngone)
        return 0;
    fm_keyed *corner = malloc(3 * ngone * sizeof *corner);
    if (!corner)
        return -1;
    size_t q = 0;
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; gone[t] && k < 3; k++)
            corner[q++] = (fm_keyed){(uint64_t)T[3 * t + k] << 32 | (uint32_t)tag[t], t};
    if (fm_sort_keyed(corner, q)) {
        free(corner);
        return -1;
    }
    long more = 0;
    for (size_t t = 0; t < nt; t++) {
        const int32_t *v = T + 3 * t;
        if (gone[t] || tag[t] < 0 || left[tag[t]] < 2 ||
            fm_triangle_min_angle(X + 3 * v[0], X + 3 * v[1], X + 3 * v[2]) >= NOTCH_SLIVER_DEG)
            continue;
        for (int k = 0; k < 3; k++) {
            uint64_t key = (uint64_t)v[k] << 32 | (uint32_t)tag[t];
            size_t i = fm_keyed_lower_bound(corner, q, key);
            if (i < q && corner[i].key == key) {
                gone[t] = 2; /* not a corner of the notch itself: no chain */
                left[tag[t]]--;
                more++;
                break;
            }
        }
    }
    free(corner);
    return more;
}

/* Triangles per fault (tag), an entry for every tag up to the largest. */
static size_t *faults_sizes(const fm_mesh *m)
{
    size_t nt = fm_mesh_ntriangles(m);
    const int32_t *tag = fm_mesh_tags(m);
    size_t *n = calloc(fault_count(m) + 1, sizeof *n);
    for (size_t t = 0; n && t < nt; t++)
        if (tag[t] >= 0)
            n[tag[t]]++;
    return n;
}

typedef struct search_work {
    const fm_mesh *set;
    double cell;
    contact *c;
    size_t n;
    int rc;
    set_facts facts;
} search_work;

static void search_one(void *user, size_t k)
{
    search_work *w = user;
    if (k == 0)
        w->rc = find_contacts(w->set, w->cell, &w->c, &w->n);
    else
        set_facts_make(w->set, &w->facts);
}

fm_status fm_carve_crossings(fm_mesh *set, double cell, int threads, int32_t *beside,
                             fm_carve_result **out, fm_error *err)
{
    *out = NULL;
    fm_carve_result *r = calloc(1, sizeof *r);
    size_t nt = fm_mesh_ntriangles(set);
    unsigned char *gone = calloc(nt + 1, 1);
    size_t *left = faults_sizes(set);
    search_work w = {set, cell, NULL, 0, -1, {NULL, NULL, NULL}};
    if (r && gone && left)
        fm_parallel_for(2, threads, search_one, &w, NULL, NULL, 0, 0);
    long slivers = -1;
    if (!r || !gone || !left || w.rc || decide(set, w.c, w.n, gone, left, &w.facts, r) ||
        (slivers = tidy_notches(set, gone, left)) < 0) {
        free(gone);
        free(left);
        free(w.c);
        set_facts_free(&w.facts);
        fm_carve_result_destroy(r);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    free(w.c);
    set_facts_free(&w.facts);
    r->slivers = (size_t)slivers;
    r->removed = fm_mesh_drop_triangles(set, gone, beside);
    free(gone);
    free(left);
    *out = r;
    return FM_OK;
}

size_t fm_carve_npairs(const fm_carve_result *r)
{
    return r ? r->n : 0;
}

const fm_carve_pair *fm_carve_pair_at(const fm_carve_result *r, size_t k)
{
    return r && k < r->n ? &r->pairs[k] : NULL;
}

size_t fm_carve_removed(const fm_carve_result *r)
{
    return r ? r->removed : 0;
}

size_t fm_carve_slivers(const fm_carve_result *r)
{
    return r ? r->slivers : 0;
}

void fm_carve_result_destroy(fm_carve_result *r)
{
    if (!r)
        return;
    free(r->pairs);
    free(r);
}
