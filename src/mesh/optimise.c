/* Optimisation of a surface mesh in 3D with nodes kept on the surface.
 *
 * The refinement in (u, v) sees the surface only through a metric frozen
 * per triangle; the shapes that count are those in 3D. Two moves fix what
 * that approximation leaves:
 *  - flips of an edge when the two triangles' smallest 3D angle grows
 *    (max-min angle, the 3D analogue of Delaunay flips);
 *  - tangential smoothing: a free node goes towards the mean of its
 *    neighbours in 3D, brought back onto the surface by Gauss-Newton steps
 *    in (u, v) through the surface's Jacobian. Accepted when the worst
 *    angle around it does not get worse than it was (or stays above
 *    35 degrees), so smoothing never trades quality for evenness.
 * Both keep every triangle counter-clockwise in (u, v) by the exact
 * orient2d: the map to 3D is one-to-one, so the mesh cannot fold. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_predicates.h"
#include "fm_sort.h"
#include "remesh_internal.h"

typedef struct opt_mesh {
    const fm_fit_surface *s;
    double *uv, *xyz;
    const unsigned char *fixed;
    size_t np, nt;
    int32_t *tri;
    int32_t *nbr;         /* 3 per triangle: across the edge opposite corner i */
    unsigned char *cons;  /* 3 per triangle: that edge is constrained */
    /* What the flips and the smoothing would otherwise compute again, each
     * value exactly what it stands for (so the mesh is the same):
     *  - sine[3 t + r]: min_sin of t's corners taken from corner r on
     *    (rotations may differ in the last bit where sides tie), -1 when
     *    not known;
     *  - changed[t]: the clock when t's corners, neighbours, constraints or
     *    node positions last changed; declined[3 t + i]: the clock when the
     *    flip of t's edge i was last found not to pay. A flip declined
     *    after the last change of both its triangles is declined again. */
    double *sine;
    uint64_t *changed, *declined, clock;
} opt_mesh;

static int cmp_pair(const void *pa, const void *pb)
{
    const int32_t *a = pa, *b = pb;
    if (a[0] != b[0])
        return a[0] < b[0] ? -1 : 1;
    return (a[1] > b[1]) - (a[1] < b[1]);
}

static fm_status build_adjacency(opt_mesh *m, const int32_t *cons, size_t ncons)
{
    /* Half-edges by (lo, hi, triangle, corner): made in triangle order and
     * sorted stably by the edge. */
    fm_keyed *h = malloc(3 * m->nt * sizeof *h + 1);
    int32_t *ck = malloc(2 * ncons * sizeof *ck + 1);
    if (!h || !ck) {
        free(h);
        free(ck);
        return FM_ERR_NOMEM;
    }
    for (size_t t = 0; t < m->nt; t++)
        for (int i = 0; i < 3; i++) {
            int32_t a = m->tri[3 * t + (i + 1) % 3], b = m->tri[3 * t + (i + 2) % 3];
            uint32_t lo = (uint32_t)(a < b ? a : b), hi = (uint32_t)(a < b ? b : a);
            h[3 * t + (size_t)i].key = (uint64_t)lo << 32 | hi;
            h[3 * t + (size_t)i].index = 3 * t + (size_t)i;
            m->nbr[3 * t + (size_t)i] = -1;
            m->cons[3 * t + (size_t)i] = 1; /* boundary until a twin is found */
        }
    for (size_t k = 0; k < ncons; k++) {
        int32_t a = cons[2 * k], b = cons[2 * k + 1];
        ck[2 * k] = a < b ? a : b;
        ck[2 * k + 1] = a < b ? b : a;
    }
    if (fm_sort_keyed(h, 3 * m->nt) != 0) {
        free(h);
        free(ck);
        return FM_ERR_NOMEM;
    }
    qsort(ck, ncons, 2 * sizeof *ck, cmp_pair);
    for (size_t k = 0; k + 1 < 3 * m->nt; k++) {
        if (h[k].key != h[k + 1].key)
            continue;
        int32_t key[2] = {(int32_t)(h[k].key >> 32), (int32_t)(h[k].key & 0xffffffffu)};
        int c = ncons && bsearch(key, ck, ncons, 2 * sizeof *ck, cmp_pair) != NULL;
        size_t a = h[k].index, b = h[k + 1].index;
        m->nbr[a] = (int32_t)(b / 3);
        m->nbr[b] = (int32_t)(a / 3);
        m->cons[a] = m->cons[b] = (unsigned char)c;
        k++;
    }
    free(h);
    free(ck);
    return FM_OK;
}

/* Triangles are compared by the sine of their smallest angle (the same
 * order as the angle, without an atan2 per triangle considered). */
#define SIN35 0.573576436351046

static double min_sin(const opt_mesh *m, int32_t a, int32_t b, int32_t c)
{
    return fm_triangle_min_angle_sin(m->xyz + 3 * a, m->xyz + 3 * b, m->xyz + 3 * c);
}

/* Forgets all that is known of the triangles (their numbers changed). */
static void forget_all(opt_mesh *m)
{
    m->clock++;
    for (size_t t = 0; t < m->nt; t++) {
        m->sine[3 * t] = m->sine[3 * t + 1] = m->sine[3 * t + 2] = -1;
        m->changed[t] = m->clock;
    }
}

/* Triangle t changed; its sine from corner 0 is s0 (-1: unknown). */
static void changed(opt_mesh *m, int32_t t, double s0)
{
    m->sine[3 * t] = s0;
    m->sine[3 * t + 1] = m->sine[3 * t + 2] = -1;
    m->changed[t] = ++m->clock;
}

static double rot_sin(opt_mesh *m, int32_t t, int r)
{
    double *q = &m->sine[3 * t + r];
    if (*q < 0) {
        const int32_t *T = m->tri + 3 * t;
        *q = min_sin(m, T[r], T[(r + 1) % 3], T[(r + 2) % 3]);
    }
    return *q;
}

static void set_back(opt_mesh *m, int32_t t, int32_t from, int32_t to)
{
    if (t < 0)
        return;
    m->changed[t] = ++m->clock;
    for (int k = 0; k < 3; k++)
        if (m->nbr[3 * t + k] == from) {
            m->nbr[3 * t + k] = to;
            return;
        }
}

/* Flips the edge opposite corner i of triangle t if that raises the
 * smallest 3D angle of the pair. Returns 1 when flipped. */
static int try_flip(opt_mesh *m, int32_t t, int i)
{
    int32_t u = m->nbr[3 * t + i];
    if (u < 0 || m->cons[3 * t + i])
        return 0;
    uint64_t *seen = &m->declined[3 * t + i];
    if (*seen >= m->changed[t] && *seen >= m->changed[u])
        return 0;
    *seen = m->clock;
    int32_t *T = m->tri + 3 * t, *U = m->tri + 3 * u;
    int j = 0;
    while (j < 3 && m->nbr[3 * u + j] != t)
        j++;
    if (j == 3)
        return 0;
    int32_t a = T[i], b = T[(i + 1) % 3], c = T[(i + 2) % 3], d = U[j];
    const double *A = m->uv + 2 * a, *B = m->uv + 2 * b, *C = m->uv + 2 * c, *D = m->uv + 2 * d;
    if (fm_orient2d(A, B, D) <= 0 || fm_orient2d(A, D, C) <= 0)
        return 0;
    /* (d, c, b) is u from corner j when u runs the shared edge backwards,
     * as in a mesh oriented throughout. */
    double su = U[(j + 1) % 3] == c && U[(j + 2) % 3] == b ? rot_sin(m, u, j) : min_sin(m, d, c, b);
    double before = fmin(rot_sin(m, t, i), su);
    double sabd = min_sin(m, a, b, d), sadc = min_sin(m, a, d, c);
    double after = fmin(sabd, sadc);
    if (!(after > before + 1e-8))
        return 0;
    int32_t N1 = m->nbr[3 * t + (i + 1) % 3], N2 = m->nbr[3 * t + (i + 2) % 3];
    unsigned char cN1 = m->cons[3 * t + (i + 1) % 3], cN2 = m->cons[3 * t + (i + 2) % 3];
    int32_t M1 = m->nbr[3 * u + (j + 1) % 3], M2 = m->nbr[3 * u + (j + 2) % 3];
    unsigned char cM1 = m->cons[3 * u + (j + 1) % 3], cM2 = m->cons[3 * u + (j + 2) % 3];
    T[0] = a, T[1] = b, T[2] = d;
    U[0] = a, U[1] = d, U[2] = c;
    int32_t *nt = m->nbr + 3 * t, *nu = m->nbr + 3 * u;
    unsigned char *ct = m->cons + 3 * t, *cu = m->cons + 3 * u;
    nt[0] = M1, nt[1] = u, nt[2] = N2;
    ct[0] = cM1, ct[1] = 0, ct[2] = cN2;
    nu[0] = M2, nu[1] = N1, nu[2] = t;
    cu[0] = cM2, cu[1] = cN1, cu[2] = 0;
    set_back(m, M1, u, t);
    set_back(m, N1, t, u);
    changed(m, t, sabd);
    changed(m, u, sadc);
    return 1;
}

static size_t flip_pass(opt_mesh *m)
{
    size_t flips = 0;
    for (int round = 0; round < 8; round++) {
        size_t f = 0;
        for (size_t t = 0; t < m->nt; t++)
            for (int i = 0; i < 3; i++)
                f += (size_t)try_flip(m, (int32_t)t, i);
        flips += f;
        if (!f)
            break;
    }
    return flips;
}

/* Triangles around every node, as compressed rows. */
static fm_status incidence(const opt_mesh *m, size_t **start, int32_t **list)
{
    size_t *st = calloc(m->np + 1, sizeof *st);
    int32_t *li = malloc(3 * m->nt * sizeof *li + 1);
    if (!st || !li) {
        free(st);
        free(li);
        return FM_ERR_NOMEM;
    }
    for (size_t k = 0; k < 3 * m->nt; k++)
        st[m->tri[k] + 1]++;
    for (size_t v = 0; v < m->np; v++)
        st[v + 1] += st[v];
    size_t *fill = malloc((m->np + 1) * sizeof *fill);
    if (!fill) {
        free(st);
        free(li);
        return FM_ERR_NOMEM;
    }
    memcpy(fill, st, (m->np + 1) * sizeof *fill);
    for (size_t t = 0; t < m->nt; t++)
        for (int i = 0; i < 3; i++)
            li[fill[m->tri[3 * t + i]]++] = (int32_t)t;
    free(fill);
    *start = st;
    *list = li;
    return FM_OK;
}

/* Smallest 3D angle (its sine) of the triangles around v, and whether all
 * are counter-clockwise in (u, v): from what is known of them (fresh ==
 * NULL), or computed anew into fresh (one per triangle) after v moved. */
static double ring_quality(opt_mesh *m, const int32_t *ring, size_t n, int *valid, double *fresh)
{
    double q = 1;
    *valid = 1;
    for (size_t k = 0; k < n; k++) {
        const int32_t *T = m->tri + 3 * ring[k];
        if (fm_orient2d(m->uv + 2 * T[0], m->uv + 2 * T[1], m->uv + 2 * T[2]) <= 0)
            *valid = 0;
        if (fresh)
            q = fmin(q, fresh[k] = min_sin(m, T[0], T[1], T[2]));
        else
            q = fmin(q, rot_sin(m, ring[k], 0));
    }
    return q;
}

static size_t smooth_pass(opt_mesh *m, const size_t *start, const int32_t *list, double *fresh)
{
    size_t moved = 0;
    for (size_t v = 0; v < m->np; v++) {
        if (m->fixed[v] || start[v + 1] == start[v])
            continue;
        const int32_t *ring = list + start[v];
        size_t n = start[v + 1] - start[v];
        double target[3] = {0, 0, 0}, w = 0;
        /* Area-weighted centroid of the ring's triangles: stays near the
         * node where the ring is uneven, unlike the plain neighbour mean. */
        for (size_t k = 0; k < n; k++) {
            const int32_t *T = m->tri + 3 * ring[k];
            const double *a = m->xyz + 3 * T[0], *b = m->xyz + 3 * T[1], *c = m->xyz + 3 * T[2];
            double ar = fm_triangle_area(a, b, c);
            for (int q = 0; q < 3; q++)
                target[q] += ar * (a[q] + b[q] + c[q]) / 3.0;
            w += ar;
        }
        if (!(w > 0))
            continue;
        for (int q = 0; q < 3; q++)
            target[q] /= w;
        int valid;
        double before = ring_quality(m, ring, n, &valid, NULL);
        double old_uv[2] = {m->uv[2 * v], m->uv[2 * v + 1]};
        double old_xyz[3] = {m->xyz[3 * v], m->xyz[3 * v + 1], m->xyz[3 * v + 2]};
        double uv[2] = {old_uv[0], old_uv[1]};
        for (int it = 0; it < 3; it++) {
            double P[3], du[3], dv[3];
            fm_fit_surface_eval(m->s, uv[0], uv[1], P, du, dv);
            double d[3] = {target[0] - P[0], target[1] - P[1], target[2] - P[2]};
            double E = du[0] * du[0] + du[1] * du[1] + du[2] * du[2];
            double F = du[0] * dv[0] + du[1] * dv[1] + du[2] * dv[2];
            double G = dv[0] * dv[0] + dv[1] * dv[1] + dv[2] * dv[2];
            double r0 = du[0] * d[0] + du[1] * d[1] + du[2] * d[2];
            double r1 = dv[0] * d[0] + dv[1] * d[1] + dv[2] * d[2];
            double det = E * G - F * F;
            if (!(det > 0))
                break;
            uv[0] += (G * r0 - F * r1) / det;
            uv[1] += (E * r1 - F * r0) / det;
        }
        m->uv[2 * v] = uv[0];
        m->uv[2 * v + 1] = uv[1];
        fm_fit_surface_eval(m->s, uv[0], uv[1], m->xyz + 3 * v, NULL, NULL);
        double after = ring_quality(m, ring, n, &valid, fresh);
        if (valid && (after >= before - 1e-11 || after >= SIN35)) {
            moved++;
            for (size_t k = 0; k < n; k++)
                changed(m, ring[k], fresh[k]);
        } else {
            memcpy(m->uv + 2 * v, old_uv, sizeof old_uv);
            memcpy(m->xyz + 3 * v, old_xyz, sizeof old_xyz);
        }
    }
    return moved;
}

fm_status optimise_mesh(const fm_fit_surface *s, double *uv, double *xyz, const unsigned char *fixed,
                        size_t np, int32_t *tri, size_t *nt, const int32_t *cons, size_t ncons,
                        const opt_curves *cv, int passes, double size, opt_result *res)
{
    memset(res, 0, sizeof *res);
    opt_mesh m = {s, uv, xyz, fixed, np, *nt, tri, NULL, NULL, NULL, NULL, NULL, 0};
    m.nbr = malloc(3 * m.nt * sizeof *m.nbr + 1);
    m.cons = malloc(3 * m.nt + 1);
    m.sine = malloc(3 * m.nt * sizeof *m.sine + 1);
    m.changed = malloc(m.nt * sizeof *m.changed + 1);
    m.declined = calloc(3 * m.nt + 1, sizeof *m.declined);
    /* A node's ring is at most every triangle. */
    double *fresh = malloc(m.nt * sizeof *fresh + 1);
    /* boundary neighbours along the constrained edges (domain on the left) */
    int32_t *prev = cv ? malloc(2 * np * sizeof *prev + 1) : NULL, *next = prev ? prev + np : NULL;
    fm_status st = FM_OK;
    if (!m.nbr || !m.cons || !m.sine || !m.changed || !m.declined || !fresh || (cv && !prev))
        st = FM_ERR_NOMEM;
    if (st == FM_OK && prev) {
        for (size_t v = 0; v < 2 * np; v++)
            prev[v] = -1;
        for (size_t k = 0; k < ncons; k++) {
            next[cons[2 * k]] = cons[2 * k + 1];
            prev[cons[2 * k + 1]] = cons[2 * k];
        }
    }
    if (st == FM_OK) {
        forget_all(&m);
        st = build_adjacency(&m, cons, ncons);
    }
    for (int p = 0; st == FM_OK && p < passes; p++) {
        /* Collapses first, while the short edges are still short: flips
         * and smoothing would spread them into slivers. */
        int nomem = 0;
        size_t c = collapse_short(uv, xyz, fixed, np, tri, &m.nt, size, &nomem);
        if (nomem) {
            st = FM_ERR_NOMEM;
            break;
        }
        res->collapsed += c;
        if (c) {
            forget_all(&m);
            st = build_adjacency(&m, cons, ncons);
        }
        if (st != FM_OK)
            break;
        res->flips += flip_pass(&m);
        size_t *start = NULL;
        int32_t *list = NULL;
        st = incidence(&m, &start, &list);
        if (st != FM_OK)
            break;
        size_t moved = smooth_pass(&m, start, list, fresh);
        res->smoothed += moved;
        free(start);
        free(list);
    }
    if (st == FM_OK)
        res->flips += flip_pass(&m);
    /* Boundary nodes slide last, where the passes left angles under 30
     * degrees: each move and flip raises the smallest angle of the
     * triangles it changes and nothing else moves, so the mesh differs
     * from the passes' own only there. */
    for (int round = 0; prev && st == FM_OK && round < passes; round++) {
        size_t *start = NULL;
        int32_t *list = NULL;
        st = incidence(&m, &start, &list);
        if (st != FM_OK)
            break;
        size_t slid = slide_boundary(s, cv, uv, xyz, np, m.tri, start, list, prev, next, cons,
                                     ncons);
        free(start);
        free(list);
        res->slid += slid;
        if (!slid)
            break;
        /* slid nodes changed their triangles: no remembered angle holds */
        forget_all(&m);
        res->flips += flip_pass(&m);
    }
    *nt = m.nt;
    free(m.nbr);
    free(m.cons);
    free(prev);
    free(m.sine);
    free(m.changed);
    free(m.declined);
    free(fresh);
    return st;
}
