/* Where three faults meet: the curves of two junctions that meet on the
 * sheet they share (A with B, A with C) meet at the point of all three
 * surfaces, and both (and the curve of B with C, when there is one
 * nearby) get that point as one common node. Every place where the two
 * may meet is tried (plan_meet.c): each crossing, and each place where
 * they come within a quarter size, as where one ends against the other. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_predicates.h"
#include "plan_internal.h"

/* Places where two curves may meet that are tried, per pair and sheet. */
#define MAX_SEEDS 8

static double dist3(const double *a, const double *b)
{
    double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* Solves 6x6 J x = r in place (partial pivoting); -1 when singular. */
static int solve6(double J[6][6], double r[6])
{
    for (int c = 0; c < 6; c++) {
        int p = c;
        for (int i = c + 1; i < 6; i++)
            if (fabs(J[i][c]) > fabs(J[p][c]))
                p = i;
        if (!(fabs(J[p][c]) > 1e-300))
            return -1;
        if (p != c) {
            for (int k = 0; k < 6; k++) {
                double t = J[c][k];
                J[c][k] = J[p][k];
                J[p][k] = t;
            }
            double t = r[c];
            r[c] = r[p];
            r[p] = t;
        }
        for (int i = c + 1; i < 6; i++) {
            double f = J[i][c] / J[c][c];
            for (int k = c; k < 6; k++)
                J[i][k] -= f * J[c][k];
            r[i] -= f * r[c];
        }
    }
    for (int c = 5; c >= 0; c--) {
        for (int k = c + 1; k < 6; k++)
            r[c] -= J[c][k] * r[k];
        r[c] /= J[c][c];
    }
    return 0;
}

/* The point on surfaces S[0..2] near p (Newton on S0 = S1 = S2 from the
 * projections of p); its parameters in uv[6]. Returns the largest
 * |S0 - Sk| reached, or INFINITY when it fails or wanders beyond `far`. */
static double triple_point(const fm_fit_surface *const S[3], const double p[3], double far,
                           double uv[6], double out[3])
{
    for (int k = 0; k < 3; k++) {
        double f[3];
        if (fm_fit_project(S[k], p, uv + 2 * k, f, NULL) != FM_OK) {
            return INFINITY;
        }
    }
    double g = INFINITY, x[3][3];
    for (int it = 0; it < 30; it++) {
        double du[3][3], dv[3][3];
        for (int k = 0; k < 3; k++)
            fm_fit_surface_eval(S[k], uv[2 * k], uv[2 * k + 1], x[k], du[k], dv[k]);
        double r[6], J[6][6];
        memset(J, 0, sizeof J);
        g = 0;
        for (int e = 0; e < 2; e++)
            for (int c = 0; c < 3; c++) {
                int row = 3 * e + c;
                r[row] = -(x[0][c] - x[e + 1][c]);
                g = fmax(g, fabs(r[row]));
                J[row][0] = du[0][c];
                J[row][1] = dv[0][c];
                J[row][2 + 2 * e] = -du[e + 1][c];
                J[row][3 + 2 * e] = -dv[e + 1][c];
            }
        if (g < 1e-7)
            break;
        if (solve6(J, r)) {
            return INFINITY;
        }
        for (int k = 0; k < 6; k++)
            uv[k] += r[k];
    }
    for (int c = 0; c < 3; c++)
        out[c] = (x[0][c] + x[1][c] + x[2][c]) / 3;
    if (!(g < 1e-3) || dist3(out, p) > far) {
        return INFINITY;
    }
    return g;
}

/* Inserts a node at position `at` of curve c (before node at). */
static int insert_node(pl_curve *c, size_t at, const double xyz[3], const double uv0[2],
                       const double uv1[2], int64_t key)
{
    size_t n = c->n + 1;
    double *x = realloc(c->xyz, 3 * n * sizeof *x);
    if (!x)
        return -1;
    c->xyz = x;
    double *u0 = realloc(c->uv[0], 2 * n * sizeof *u0);
    if (!u0)
        return -1;
    c->uv[0] = u0;
    double *u1 = realloc(c->uv[1], 2 * n * sizeof *u1);
    if (!u1)
        return -1;
    c->uv[1] = u1;
    int64_t *k = realloc(c->key, n * sizeof *k);
    if (!k)
        return -1;
    c->key = k;
    size_t tail = c->n - at;
    memmove(c->xyz + 3 * (at + 1), c->xyz + 3 * at, 3 * tail * sizeof *x);
    memmove(c->uv[0] + 2 * (at + 1), c->uv[0] + 2 * at, 2 * tail * sizeof *u0);
    memmove(c->uv[1] + 2 * (at + 1), c->uv[1] + 2 * at, 2 * tail * sizeof *u1);
    memmove(c->key + at + 1, c->key + at, tail * sizeof *k);
    memcpy(c->xyz + 3 * at, xyz, 3 * sizeof *x);
    memcpy(c->uv[0] + 2 * at, uv0, 2 * sizeof *u0);
    memcpy(c->uv[1] + 2 * at, uv1, 2 * sizeof *u1);
    c->key[at] = key;
    c->n = n;
    return 0;
}

/* Removes interior nodes of c within `near` of node `keep` (not keyed). */
static void thin_around(pl_curve *c, size_t keep, double near)
{
    size_t w = 0;
    for (size_t i = 0; i < c->n; i++) {
        int drop = i != keep && i > 0 && i + 1 < c->n && c->key[i] < 0 &&
                   dist3(c->xyz + 3 * i, c->xyz + 3 * keep) < near;
        if (drop)
            continue;
        if (w != i) {
            memcpy(c->xyz + 3 * w, c->xyz + 3 * i, 3 * sizeof(double));
            memcpy(c->uv[0] + 2 * w, c->uv[0] + 2 * i, 2 * sizeof(double));
            memcpy(c->uv[1] + 2 * w, c->uv[1] + 2 * i, 2 * sizeof(double));
            c->key[w] = c->key[i];
        }
        w++;
    }
    c->n = w;
}

static int ensure_keys(pl_curve *c)
{
    if (c->key)
        return 0;
    c->key = malloc((c->n + 1) * sizeof *c->key);
    if (!c->key)
        return -1;
    for (size_t i = 0; i < c->n; i++)
        c->key[i] = -1;
    return 0;
}

/* The side (0, 1) of junction j on sheet (f, s), or -1. */
static int side_on(const fm_connect_junction *j, size_t f, size_t s)
{
    for (int k = 0; k < 2; k++)
        if (j->fault[k] == f && j->sheet[k] == s)
            return k;
    return -1;
}

static int find_node(const pl_curve *c, int64_t key)
{
    for (size_t i = 0; i < c->n; i++)
        if (c->key[i] == key)
            return (int)i;
    return -1;
}

/* Keys of points found twice (two pairs of curves meeting at the same
 * triple point) are one: a union-find over keys. */
typedef struct keyset {
    int64_t *parent;
    size_t n, cap;
} keyset;

static int64_t key_new(keyset *ks)
{
    if (ks->n == ks->cap) {
        size_t cap = ks->cap ? 2 * ks->cap : 64;
        int64_t *p = realloc(ks->parent, cap * sizeof *p);
        if (!p)
            return -1;
        ks->parent = p;
        ks->cap = cap;
    }
    ks->parent[ks->n] = (int64_t)ks->n;
    return (int64_t)ks->n++;
}

static int64_t key_find(keyset *ks, int64_t k)
{
    while (ks->parent[k] != k) {
        ks->parent[k] = ks->parent[ks->parent[k]];
        k = ks->parent[k];
    }
    return k;
}

/* -1 (+1) when T lies before the first (after the last) node of c, seen
 * from the end segment nearest to it (segment `seg`); 0 otherwise. */
static int beyond_end(const pl_curve *c, size_t seg, const double T[3])
{
    const double *p = c->xyz + 3 * seg, *q = p + 3;
    double t = 0, dd = 0;
    for (int k = 0; k < 3; k++) {
        t += (q[k] - p[k]) * (T[k] - p[k]);
        dd += (q[k] - p[k]) * (q[k] - p[k]);
    }
    if (seg == 0 && t < 0)
        return -1;
    if (seg + 2 == c->n && t > dd)
        return 1;
    return 0;
}

/* Puts point T (key) on curve c: at the node within `snap` of it (ends
 * first), else into the segment nearest to it, if within `reach`. The
 * uv of T on c's sides come from projecting it, or from uvs[] when the
 * sheet is one of the three (so that one sheet sees one (u, v) for it). */
static int put_point(pl_curve *c, const fm_connect_junction *j, const double T[3], int64_t key,
                     const size_t fs[3][2], const double uvs[6], const fm_model *const *models,
                     double snap, double reach, keyset *ks)
{
    if (find_node(c, key) >= 0)
        return 0;
    /* the same point found before through another pair of curves */
    for (size_t i = 0; i < c->n; i++)
        if (c->key[i] >= 0 && dist3(c->xyz + 3 * i, T) <= 1e-3 * snap) {
            int64_t a = key_find(ks, c->key[i]), b = key_find(ks, key);
            if (a != b)
                ks->parent[b] = a;
            return 0;
        }
    double uv[2][2];
    for (int s = 0; s < 2; s++) {
        int which = -1;
        for (int k = 0; k < 3; k++)
            if (fs[k][0] == j->fault[s] && fs[k][1] == j->sheet[s])
                which = k;
        if (which >= 0) {
            uv[s][0] = uvs[2 * which];
            uv[s][1] = uvs[2 * which + 1];
        } else {
            double f[3];
            fm_fit_project(fm_model_surface(models[j->fault[s]], j->sheet[s]), T, uv[s], f, NULL);
        }
    }
    /* the nearest segment */
    size_t best = 0;
    double bd = INFINITY;
    for (size_t i = 0; i + 1 < c->n; i++) {
        double d = fm_segment_distance3(T, c->xyz + 3 * i, c->xyz + 3 * (i + 1));
        if (d < bd) {
            bd = d;
            best = i;
        }
    }
    if (!(bd <= reach))
        return 1; /* not on this curve */
    double da = dist3(T, c->xyz + 3 * best), db = dist3(T, c->xyz + 3 * (best + 1));
    size_t at;
    int beyond = beyond_end(c, best, T);
    if (beyond && c->key[beyond < 0 ? 0 : c->n - 1] >= 0)
        beyond = 0;
    if (beyond) {
        /* a curve that stops short of the point (or passes it by less than
         * a snap) ends there */
        at = beyond < 0 ? 0 : c->n - 1;
        if (dist3(T, c->xyz + 3 * at) > snap) {
            if (beyond > 0)
                at = c->n;
            if (insert_node(c, at, T, uv[0], uv[1], key))
                return -1;
        } else {
            memcpy(c->xyz + 3 * at, T, 3 * sizeof(double));
            memcpy(c->uv[0] + 2 * at, uv[0], 2 * sizeof(double));
            memcpy(c->uv[1] + 2 * at, uv[1], 2 * sizeof(double));
            c->key[at] = key;
        }
    } else if (fmin(da, db) <= snap && c->key[da <= db ? best : best + 1] < 0) {
        at = da <= db ? best : best + 1;
        memcpy(c->xyz + 3 * at, T, 3 * sizeof(double));
        memcpy(c->uv[0] + 2 * at, uv[0], 2 * sizeof(double));
        memcpy(c->uv[1] + 2 * at, uv[1], 2 * sizeof(double));
        c->key[at] = key;
    } else {
        /* T beyond an end of the curve (its foot on the end segment is
         * that end node) extends the curve: put between the last two
         * nodes it would make the curve run back on itself, a sliver
         * both sheets then have (Big Bear 1992 rupture with the North
         * Frontal thrust, 1 km) */
        const double *A = c->xyz + 3 * best, *B = c->xyz + 3 * (best + 1);
        double ab = 0, at_ = 0;
        for (int k = 0; k < 3; k++) {
            ab += (B[k] - A[k]) * (B[k] - A[k]);
            at_ += (B[k] - A[k]) * (T[k] - A[k]);
        }
        if (best == 0 && at_ <= 0)
            at = 0;
        else if (best + 2 == c->n && at_ >= ab)
            at = c->n;
        else
            at = best + 1;
        if (insert_node(c, at, T, uv[0], uv[1], key))
            return -1;
    }
    thin_around(c, (size_t)find_node(c, key), snap);
    return 0;
}

static int near_curve(const pl_curve *c, const double T[3], double reach)
{
    for (size_t i = 0; i + 1 < c->n; i++)
        if (fm_segment_distance3(T, c->xyz + 3 * i, c->xyz + 3 * i + 3) <= reach)
            return 1;
    return 0;
}

/* Do curves a and b already share a keyed node within r of p? */
static int share_near(const pl_curve *a, const pl_curve *b, const double p[3], double r)
{
    for (size_t i = 0; a->key && b->key && i < a->n; i++)
        if (a->key[i] >= 0 && find_node(b, a->key[i]) >= 0 && dist3(a->xyz + 3 * i, p) < r)
            return 1;
    return 0;
}

/* Curves x and y share sheet side sx of x (sy of y); P is where they may
 * meet. Finds the point of the three surfaces there and puts it, keyed,
 * on both and on the curve of the other two sheets when that passes by.
 * Returns 1 when a point was made, 0 when none, -1 out of memory. */
static int meet_at(const fm_connect_junction *J, pl_curve *C, size_t nj, size_t x, int sx,
                   size_t y, int sy, const double P[3], const fm_model *const *models, double H,
                   const double *level, keyset *ks)
{
    pl_curve *a = &C[x], *b = &C[y];
    if (share_near(a, b, P, 0.5 * H))
        return 0;
    /* the three sheets: the shared one, x's other, y's other */
    size_t fs[3][2] = {{J[x].fault[sx], J[x].sheet[sx]},
                       {J[x].fault[1 - sx], J[x].sheet[1 - sx]},
                       {J[y].fault[1 - sy], J[y].sheet[1 - sy]}};
    const fm_fit_surface *S[3];
    for (int k = 0; k < 3; k++)
        S[k] = fm_model_surface(models[fs[k][0]], fs[k][1]);
    double uvs[6], T[3];
    if (!isfinite(triple_point(S, P, 0.5 * H, uvs, T)) || !near_curve(a, T, 0.5 * H) ||
        !near_curve(b, T, 0.5 * H))
        return 0;
    /* with the top cut, nothing may rise above sea level */
    if (level && T[2] > *level)
        return 0;
    int64_t key = key_new(ks);
    if (key < 0 || ensure_keys(a) || ensure_keys(b))
        return -1;
    if (put_point(a, &J[x], T, key, fs, uvs, models, 0.3 * H, 0.5 * H, ks) < 0 ||
        put_point(b, &J[y], T, key, fs, uvs, models, 0.3 * H, 0.5 * H, ks) < 0)
        return -1;
    /* the curve of the other two, when it passes there */
    for (size_t z = 0; z < nj; z++) {
        if (z == x || z == y || !C[z].n)
            continue;
        if (side_on(&J[z], fs[1][0], fs[1][1]) < 0 || side_on(&J[z], fs[2][0], fs[2][1]) < 0)
            continue;
        if (ensure_keys(&C[z]) ||
            put_point(&C[z], &J[z], T, key, fs, uvs, models, 0.3 * H, 0.5 * H, ks) < 0)
            return -1;
    }
    return 1;
}

int pl_triple_junctions(fm_connect_junction *J, pl_curve *C, size_t nj,
                        const fm_model *const *models, double H, const double *level,
                        size_t *made)
{
    *made = 0;
    keyset ks = {0};
    /* a loop's two ends are one point */
    for (size_t x = 0; x < nj; x++) {
        if (!C[x].n || !C[x].loop)
            continue;
        int64_t key = key_new(&ks);
        if (key < 0 || ensure_keys(&C[x]))
            goto nomem;
        C[x].key[0] = C[x].key[C[x].n - 1] = key;
    }
    for (size_t x = 0; x < nj; x++) {
        if (!C[x].n)
            continue;
        for (size_t y = x + 1; y < nj; y++) {
            if (!C[y].n)
                continue;
            for (int sx = 0; sx < 2; sx++) {
                int sy = side_on(&J[y], J[x].fault[sx], J[x].sheet[sx]);
                if (sy < 0)
                    continue;
                pl_curve *a = &C[x], *b = &C[y];
                double P[MAX_SEEDS][3];
                size_t ns = pl_meet_seeds(a, sx, b, sy, 0.25 * H, 0.5 * H, P, MAX_SEEDS);
                for (size_t q = 0; q < ns; q++) {
                    int r = meet_at(J, C, nj, x, sx, y, sy, P[q], models, H, level, &ks);
                    if (r < 0)
                        goto nomem;
                    *made += (size_t)r;
                }
            }
        }
    }
    /* one key per point */
    for (size_t x = 0; x < nj; x++)
        for (size_t i = 0; C[x].key && i < C[x].n; i++)
            if (C[x].key[i] >= 0)
                C[x].key[i] = key_find(&ks, C[x].key[i]);
    free(ks.parent);
    return 0;
nomem:
    free(ks.parent);
    return -1;
}
