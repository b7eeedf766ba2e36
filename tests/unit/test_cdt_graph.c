/* Graph CDTs (fm_cdt_create_graph): arrangements of loops and open chains,
 * their faces and the selection of the domain among them, interior
 * segments through refinement (frozen or not), and determinism. Every
 * result is checked exactly: orientation by fm_orient2d, a manifold whose
 * one-sided edges are exactly the listed boundary edges, interior edges
 * listed once with triangles on both sides, no triangle edge crossing a
 * segment. */
#include <stdint.h>

#include "fm_cdt.h"
#include "fm_predicates.h"
#include "fm_test.h"

#define MAXP 4096

/* Points and segments; chains join consecutive points. */
typedef struct graph {
    double uv[2 * MAXP];
    int32_t seg[2 * MAXP], sid[MAXP];
    size_t np, ns;
} graph;

static int32_t add_point(graph *g, double u, double v)
{
    g->uv[2 * g->np] = u;
    g->uv[2 * g->np + 1] = v;
    return (int32_t)g->np++;
}

static void add_seg(graph *g, int32_t a, int32_t b, int32_t id)
{
    g->seg[2 * g->ns] = a;
    g->seg[2 * g->ns + 1] = b;
    g->sid[g->ns] = id;
    g->ns++;
}

/* A chain through n points (2 per point); returns its first segment. */
static size_t add_chain(graph *g, const double *pts, size_t n, int closed, int32_t id)
{
    size_t first = g->ns;
    int32_t base = (int32_t)g->np;
    for (size_t i = 0; i < n; i++)
        add_point(g, pts[2 * i], pts[2 * i + 1]);
    for (size_t i = 0; i + 1 < n; i++)
        add_seg(g, base + (int32_t)i, base + (int32_t)i + 1, id);
    if (closed)
        add_seg(g, base + (int32_t)n - 1, base, id);
    return first;
}

/* The square [0, s]^2 as a loop with id 100 (4 corners). */
static graph *square(double s)
{
    graph *g = calloc(1, sizeof *g);
    double sq[] = {0, 0, s, 0, s, s, 0, s};
    add_chain(g, sq, 4, 1, 100);
    return g;
}

static fm_cdt *make(const graph *g)
{
    fm_cdt *t = NULL;
    fm_error err;
    if (fm_cdt_create_graph(g->uv, g->np, g->seg, g->sid, g->ns, &t, &err) != FM_OK)
        fprintf(stderr, "create_graph: %s\n", err.message);
    return t;
}

static fm_status refine(fm_cdt *t, double size, const unsigned char *frozen, size_t nfrozen)
{
    fm_cdt_refine_options o;
    fm_cdt_refine_options_default(&o);
    o.size = size;
    o.frozen_ids = frozen;
    o.nfrozen = nfrozen;
    fm_error err;
    fm_status st = fm_cdt_refine(t, &o, &err);
    if (st != FM_OK)
        fprintf(stderr, "refine: %s\n", err.message);
    return st;
}

static double shoelace(const double *pts, size_t n)
{
    double a = 0;
    for (size_t i = 0; i < n; i++) {
        size_t j = (i + 1) % n;
        a += pts[2 * i] * pts[2 * j + 1] - pts[2 * j] * pts[2 * i + 1];
    }
    return 0.5 * a;
}

typedef struct erec {
    int32_t lo, hi, a, b, tri;
} erec;

static int by_erec(const void *x, const void *y)
{
    const erec *p = x, *q = y;
    if (p->lo != q->lo)
        return p->lo < q->lo ? -1 : 1;
    if (p->hi != q->hi)
        return p->hi < q->hi ? -1 : 1;
    return (p->a > q->a) - (p->a < q->a);
}

static erec mk(int32_t a, int32_t b)
{
    return (erec){a < b ? a : b, a < b ? b : a, a, b, -1};
}

/* 1 if segments pq and rs cross at a point interior to both (exact). */
static int proper_cross(const double *p, const double *q, const double *r, const double *s)
{
    int o1 = fm_orient2d(p, q, r), o2 = fm_orient2d(p, q, s);
    int o3 = fm_orient2d(r, s, p), o4 = fm_orient2d(r, s, q);
    return o1 * o2 < 0 && o3 * o4 < 0;
}

/* Exact checks of a graph CDT's results: counter-clockwise triangles, the
 * area, a manifold whose one-sided edges are the listed boundary edges
 * (domain on their left) and whose listed interior edges have a triangle
 * on each side, and the constrained Delaunay property when asked.
 * Returns the number of failed checks. */
static int validate(const fm_cdt *t, double want_area, int delaunay)
{
    int before = fm_test_failed_checks;
    size_t np = fm_cdt_npoints(t), nt = fm_cdt_ntriangles(t), ne = fm_cdt_nedges(t);
    const double *p = fm_cdt_points(t);
    const int32_t *tri = fm_cdt_triangles(t), *ed = fm_cdt_edges(t);
    const unsigned char *ei = fm_cdt_edge_interior(t);
    double area = 0;
    int ccw = 1, range = 1;
    for (size_t k = 0; k < 3 * nt; k++)
        range &= tri[k] >= 0 && (size_t)tri[k] < np;
    CHECK(range);
    if (!range)
        return 1;
    for (size_t k = 0; k < nt; k++) {
        const double *a = p + 2 * tri[3 * k], *b = p + 2 * tri[3 * k + 1], *c = p + 2 * tri[3 * k + 2];
        ccw &= fm_orient2d(a, b, c) > 0;
        area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    }
    CHECK(ccw);
    CHECK_NEAR(area, want_area, 1e-9 * (fabs(want_area) + 1));
    erec *te = malloc((3 * nt + 1) * sizeof *te), *le = malloc((ne + 1) * sizeof *le);
    for (size_t k = 0; k < nt; k++)
        for (int i = 0; i < 3; i++) {
            te[3 * k + i] = mk(tri[3 * k + (i + 1) % 3], tri[3 * k + (i + 2) % 3]);
            te[3 * k + i].tri = (int32_t)k;
        }
    qsort(te, 3 * nt, sizeof *te, by_erec);
    for (size_t m = 0; m < ne; m++)
        le[m] = mk(ed[2 * m], ed[2 * m + 1]);
    qsort(le, ne, sizeof *le, by_erec);
    size_t bad_manifold = 0, bad_listed = 0, bad_delaunay = 0, nbound = 0, ninner = 0;
    for (size_t i = 0; i < 3 * nt;) {
        size_t j = i + 1;
        while (j < 3 * nt && te[j].lo == te[i].lo && te[j].hi == te[i].hi)
            j++;
        erec key = te[i];
        const erec *hit = NULL;
        for (size_t m = 0; m < ne && !hit; m++)
            if (le[m].lo == key.lo && le[m].hi == key.hi)
                hit = le + m;
        if (j - i == 1) {
            nbound++;
            /* listed, in the triangle's direction, as a boundary */
            size_t m;
            for (m = 0; m < ne; m++)
                if (ed[2 * m] == te[i].a && ed[2 * m + 1] == te[i].b)
                    break;
            if (m == ne || ei[m])
                bad_listed++;
        } else if (j - i == 2) {
            if (te[i].a != te[i + 1].b || te[i].b != te[i + 1].a)
                bad_manifold++;
            if (hit) {
                ninner++;
                size_t m;
                for (m = 0; m < ne; m++)
                    if ((ed[2 * m] == key.lo && ed[2 * m + 1] == key.hi) ||
                        (ed[2 * m] == key.hi && ed[2 * m + 1] == key.lo))
                        break;
                if (m == ne || !ei[m])
                    bad_listed++;
            } else if (delaunay) {
                const int32_t *v = tri + 3 * te[i].tri, *w = tri + 3 * te[i + 1].tri;
                int32_t o = w[0] + w[1] + w[2] - key.lo - key.hi;
                if (fm_incircle(p + 2 * v[0], p + 2 * v[1], p + 2 * v[2], p + 2 * o) > 0)
                    bad_delaunay++;
            }
        } else {
            bad_manifold++;
        }
        i = j;
    }
    CHECK_EQ(bad_manifold, 0);
    CHECK_EQ(bad_listed, 0);
    CHECK_EQ(bad_delaunay, 0);
    CHECK_EQ(nbound + ninner, ne);
    free(te);
    free(le);
    return fm_test_failed_checks - before;
}

/* Every input segment of g with an id in ids[] (n of them) as a chain of
 * output edges: the segment's points in order along it, each sub-edge an
 * edge of the triangulation with a triangle on both sides when interior;
 * and no triangle edge crossing any of those segments. Returns the number
 * of sub-edges found. */
static size_t check_chain(const fm_cdt *t, const graph *g, int32_t id, int interior)
{
    size_t np = fm_cdt_npoints(t), nt = fm_cdt_ntriangles(t), ne = fm_cdt_nedges(t);
    const double *p = fm_cdt_points(t);
    const int32_t *tri = fm_cdt_triangles(t), *ed = fm_cdt_edges(t), *eid = fm_cdt_edge_ids(t);
    const unsigned char *ei = fm_cdt_edge_interior(t);
    size_t nsub = 0, crossing = 0, missing = 0, wrong_dir = 0, wrong_kind = 0;
    (void)np;
    for (size_t m = 0; m < ne; m++) {
        if (eid[m] != id)
            continue;
        nsub++;
        wrong_kind += ei[m] != interior;
        int32_t a = ed[2 * m], b = ed[2 * m + 1];
        /* both sides (interior) or the left side (boundary) */
        int left = 0, right = 0;
        for (size_t k = 0; k < nt; k++) {
            const int32_t *v = tri + 3 * k;
            for (int i = 0; i < 3; i++) {
                if (v[(i + 1) % 3] == a && v[(i + 2) % 3] == b) {
                    left++;
                    CHECK(fm_orient2d(p + 2 * a, p + 2 * b, p + 2 * v[i]) > 0);
                }
                if (v[(i + 1) % 3] == b && v[(i + 2) % 3] == a) {
                    right++;
                    CHECK(fm_orient2d(p + 2 * a, p + 2 * b, p + 2 * v[i]) < 0);
                }
            }
        }
        missing += left != 1 || right != (interior ? 1 : 0);
        /* The input segment it belongs to: direction as the input's. */
        int found = 0;
        for (size_t s = 0; s < g->ns && !found; s++) {
            if (g->sid[s] != id)
                continue;
            const double *sa = g->uv + 2 * g->seg[2 * s], *sb = g->uv + 2 * g->seg[2 * s + 1];
            double dx = sb[0] - sa[0], dy = sb[1] - sa[1], L = hypot(dx, dy);
            /* Points refinement put on a segment are on it within
             * rounding (exactly only for axis-parallel ones). */
            double da = fabs((p[2 * a] - sa[0]) * dy - (p[2 * a + 1] - sa[1]) * dx) / L;
            double db = fabs((p[2 * b] - sa[0]) * dy - (p[2 * b + 1] - sa[1]) * dx) / L;
            if (da <= 1e-12 * L && db <= 1e-12 * L) {
                double t0 = (p[2 * a] - sa[0]) * dx + (p[2 * a + 1] - sa[1]) * dy;
                double t1 = (p[2 * b] - sa[0]) * dx + (p[2 * b + 1] - sa[1]) * dy;
                double l2 = dx * dx + dy * dy;
                double tol = 1e-12 * l2;
                if (t0 >= -tol && t1 <= l2 + tol && t0 <= l2 + tol && t1 >= -tol) {
                    found = 1;
                    wrong_dir += interior && !(t1 > t0);
                }
            }
        }
        CHECK(found);
        for (size_t k = 0; k < nt; k++)
            for (int i = 0; i < 3; i++) {
                int32_t x = tri[3 * k + i], y = tri[3 * k + (i + 1) % 3];
                crossing += proper_cross(p + 2 * a, p + 2 * b, p + 2 * x, p + 2 * y);
            }
    }
    CHECK_EQ(crossing, 0);
    CHECK_EQ(missing, 0);
    CHECK_EQ(wrong_dir, 0);
    CHECK_EQ(wrong_kind, 0);
    return nsub;
}

static double tri_min_angle(const double *a, const double *b, const double *c)
{
    const double *p[3] = {a, b, c};
    double best = 180;
    for (int i = 0; i < 3; i++) {
        const double *o = p[i], *x = p[(i + 1) % 3], *y = p[(i + 2) % 3];
        double ux = x[0] - o[0], uy = x[1] - o[1], vx = y[0] - o[0], vy = y[1] - o[1];
        double ang = atan2(fabs(ux * vy - uy * vx), ux * vx + uy * vy) * 180 / 3.14159265358979323846;
        if (ang < best)
            best = ang;
    }
    return best;
}

static void quality(const fm_cdt *t, double *ok30, double *minang)
{
    const double *p = fm_cdt_points(t);
    const int32_t *tri = fm_cdt_triangles(t);
    size_t nt = fm_cdt_ntriangles(t), good = 0;
    *minang = 180;
    for (size_t k = 0; k < nt; k++) {
        double a = tri_min_angle(p + 2 * tri[3 * k], p + 2 * tri[3 * k + 1], p + 2 * tri[3 * k + 2]);
        good += a >= 30 - 1e-9;
        if (a < *minang)
            *minang = a;
    }
    *ok30 = nt ? (double)good / (double)nt : 0;
}

/* A chain dangling inside the square: one face, the chain interior. */
static void test_dangling(void)
{
    graph *g = square(1);
    double ch[] = {0.3, 0.5, 0.5, 0.5, 0.62, 0.63};
    size_t c0 = add_chain(g, ch, 3, 0, 7);
    fm_cdt *t = make(g);
    CHECK(t != NULL);
    if (!t) {
        free(g);
        return;
    }
    CHECK_EQ(fm_cdt_nfaces(t), 1);
    CHECK_NEAR(fm_cdt_face_areas(t)[0], 1, 1e-12);
    int32_t l, r;
    fm_cdt_segment_faces(t, c0, &l, &r);
    CHECK(l == 0 && r == 0);
    fm_cdt_segment_faces(t, 0, &l, &r); /* the square's bottom, CCW */
    CHECK(l == 0 && r == -1);
    fm_cdt_segment_faces(t, 99, &l, &r);
    CHECK(l == -1 && r == -1);
    /* Before any selection the domain is the hull (here the square). */
    validate(t, 1, 1);
    CHECK_EQ(check_chain(t, g, 7, 1), 2);
    unsigned char keep[1] = {1};
    fm_error err;
    CHECK_EQ(fm_cdt_select_faces(t, keep, &err), FM_OK);
    validate(t, 1, 1);
    CHECK_EQ(check_chain(t, g, 7, 1), 2);
    const int32_t *ps = fm_cdt_point_segment(t);
    CHECK_EQ(ps[4], 7);
    CHECK_EQ(ps[6], 7);
    CHECK_EQ(ps[0], 100);
    CHECK_EQ(refine(t, 0.05, NULL, 0), FM_OK);
    validate(t, 1, 1);
    size_t nsub = check_chain(t, g, 7, 1);
    CHECK(nsub >= 6); /* about 0.37 long at size 0.05, split */
    double ok, mn;
    quality(t, &ok, &mn);
    fm_cdt_refine_stats st;
    fm_cdt_refine_get_stats(t, &st);
    printf("dangling chain 0.05: %zu triangles, %zu chain edges, angle>=30 %.4f, min %.2f, "
           "%zu rejected, %zu bad left\n",
           fm_cdt_ntriangles(t), nsub, ok, mn, st.rejected, st.bad_left);
    CHECK(ok >= 0.97);
    CHECK(mn >= 15);
    /* Points on the chain report its id, the rest of the new points none
     * or the square's. */
    ps = fm_cdt_point_segment(t);
    size_t on7 = 0;
    for (size_t i = 0; i < fm_cdt_npoints(t); i++)
        on7 += ps[i] == 7;
    CHECK_EQ(on7, nsub + 1);
    /* Selection is over once refined. */
    CHECK_EQ(fm_cdt_select_faces(t, keep, &err), FM_ERR_INVALID);
    CHECK(strstr(err.message, "before refinement") != NULL);
    fm_cdt_destroy(t);
    free(g);
}

/* A chain across the square: two faces. */
static void test_cut(void)
{
    graph *g = square(1);
    /* (0, 0.4) lies on the left side (3 -> 0) and splits it. */
    double ch[] = {0, 0.4, 0.5, 0.55, 1, 0.6};
    size_t c0 = add_chain(g, ch, 3, 0, 7);
    /* (1, 0.6) must be on the right side too: it is (x == 1). */
    fm_cdt *t = make(g);
    CHECK(t != NULL);
    if (!t) {
        free(g);
        return;
    }
    CHECK_EQ(fm_cdt_nfaces(t), 2);
    double below[] = {0, 0, 1, 0, 1, 0.6, 0.5, 0.55, 0, 0.4};
    double above[] = {0, 0.4, 0.5, 0.55, 1, 0.6, 1, 1, 0, 1};
    double ab = shoelace(below, 5), aa = shoelace(above, 5);
    const double *fa = fm_cdt_face_areas(t), *fp = fm_cdt_face_points(t);
    /* Face 0 holds the smallest directed piece, 0 -> 1: the lower one. */
    CHECK_NEAR(fa[0], ab, 1e-12);
    CHECK_NEAR(fa[1], aa, 1e-12);
    /* Face points lie on the right side of the chain. */
    for (int f = 0; f < 2; f++) {
        const double *q = fp + 2 * f;
        double ychain = q[0] < 0.5 ? 0.4 + 0.3 * q[0] : 0.55 + 0.1 * (q[0] - 0.5);
        CHECK(f == 0 ? q[1] < ychain : q[1] > ychain);
        CHECK(q[0] > 0 && q[0] < 1 && q[1] > 0 && q[1] < 1);
    }
    int32_t l, r;
    fm_cdt_segment_faces(t, c0, &l, &r);
    CHECK(l == 1 && r == 0);
    fm_cdt_segment_faces(t, c0 + 1, &l, &r);
    CHECK(l == 1 && r == 0);
    /* The left side 3 -> 0 runs from (0, 1) down: its first piece, down to
     * (0, 0.4), borders the upper face. */
    fm_cdt_segment_faces(t, 3, &l, &r);
    CHECK(l == 1 && r == -1);

    /* One face: the chain is a boundary. */
    fm_error err;
    unsigned char keep[2] = {1, 0};
    CHECK_EQ(fm_cdt_select_faces(t, keep, &err), FM_OK);
    validate(t, ab, 1);
    CHECK_EQ(check_chain(t, g, 7, 0), 2);
    const int32_t *ed = fm_cdt_edges(t), *eid = fm_cdt_edge_ids(t);
    /* Boundary edges of the chain have the lower face on their left: they
     * run against the chain. */
    for (size_t m = 0; m < fm_cdt_nedges(t); m++)
        if (eid[m] == 7)
            CHECK(fm_cdt_points(t)[2 * ed[2 * m]] > fm_cdt_points(t)[2 * ed[2 * m + 1]]);
    /* The other one. */
    keep[0] = 0, keep[1] = 1;
    CHECK_EQ(fm_cdt_select_faces(t, keep, &err), FM_OK);
    validate(t, aa, 1);
    CHECK_EQ(check_chain(t, g, 7, 0), 2);
    CHECK_EQ(fm_cdt_point_segment(t)[0], -1); /* corner (0,0): no kept segment */
    CHECK_EQ(fm_cdt_ntriangles(t) > 0, 1);
    /* Both: the chain is interior. */
    keep[0] = keep[1] = 1;
    CHECK_EQ(fm_cdt_select_faces(t, keep, &err), FM_OK);
    validate(t, 1, 1);
    CHECK_EQ(check_chain(t, g, 7, 1), 2);
    CHECK_EQ(refine(t, 0.06, NULL, 0), FM_OK);
    validate(t, 1, 1);
    size_t nsub = check_chain(t, g, 7, 1);
    CHECK(nsub >= 12);
    /* Triangles on both sides of the chain, areas as the faces'. */
    const double *p = fm_cdt_points(t);
    const int32_t *tri = fm_cdt_triangles(t);
    double sa = 0, sb = 0;
    for (size_t k = 0; k < fm_cdt_ntriangles(t); k++) {
        const double *a = p + 2 * tri[3 * k], *b = p + 2 * tri[3 * k + 1], *c = p + 2 * tri[3 * k + 2];
        double gx = (a[0] + b[0] + c[0]) / 3, gy = (a[1] + b[1] + c[1]) / 3;
        double ychain = gx < 0.5 ? 0.4 + 0.3 * gx : 0.55 + 0.1 * (gx - 0.5);
        double ar = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
        if (gy < ychain)
            sb += ar;
        else
            sa += ar;
    }
    CHECK_NEAR(sb, ab, 1e-9);
    CHECK_NEAR(sa, aa, 1e-9);
    double ok, mn;
    quality(t, &ok, &mn);
    printf("cut square 0.06: %zu triangles, %zu chain edges, angle>=30 %.4f, min %.2f\n",
           fm_cdt_ntriangles(t), nsub, ok, mn);
    CHECK(ok >= 0.97);
    fm_cdt_destroy(t);

    /* Select none: nothing left. */
    t = make(g);
    keep[0] = keep[1] = 0;
    CHECK_EQ(fm_cdt_select_faces(t, keep, &err), FM_OK);
    CHECK_EQ(fm_cdt_ntriangles(t), 0);
    CHECK_EQ(fm_cdt_nedges(t), 0);
    fm_cdt_destroy(t);
    free(g);
}

/* A chain that leaves the square: the parts outside are discarded. */
static void test_leaving(void)
{
    graph *g = square(1);
    double ch[] = {0.5, 0.5, 1, 0.5, 1.3, 0.7, 1.3, 0.9};
    size_t c0 = add_chain(g, ch, 4, 0, 7);
    fm_cdt *t = make(g);
    CHECK(t != NULL);
    if (!t) {
        free(g);
        return;
    }
    /* The square, and the hull beyond its right side cut in two by the
     * chain. */
    CHECK_EQ(fm_cdt_nfaces(t), 3);
    int32_t l, r, lo, ro;
    fm_cdt_segment_faces(t, c0, &l, &r);
    CHECK(l == r && l >= 0);
    int32_t sq = l;
    CHECK_NEAR(fm_cdt_face_areas(t)[sq], 1, 1e-12);
    fm_cdt_segment_faces(t, c0 + 1, &lo, &ro);
    CHECK(lo >= 0 && ro >= 0 && lo != ro && lo != sq && ro != sq);
    double hull_beyond[] = {1, 0, 1.3, 0.7, 1.3, 0.9, 1, 1};
    CHECK_NEAR(fm_cdt_face_areas(t)[lo] + fm_cdt_face_areas(t)[ro], shoelace(hull_beyond, 4),
               1e-12);
    /* The square is closed by its segments (its sides on the hull are
     * segments); the two pockets beyond it reach hull edges no segment
     * holds. */
    CHECK_EQ(fm_cdt_face_open(t)[sq], 0);
    CHECK_EQ(fm_cdt_face_open(t)[lo], 1);
    CHECK_EQ(fm_cdt_face_open(t)[ro], 1);
    /* Before selection: the whole hull, hull edges listed with id -1. */
    validate(t, 1 + shoelace(hull_beyond, 4), 1);
    size_t nhull = 0;
    for (size_t m = 0; m < fm_cdt_nedges(t); m++)
        nhull += fm_cdt_edge_ids(t)[m] == -1;
    CHECK_EQ(nhull, 2); /* (1,0)-(1.3,0.7) and (1.3,0.9)-(1,1); the chain runs between */
    unsigned char keep[3] = {0, 0, 0};
    keep[sq] = 1;
    fm_error err;
    CHECK_EQ(fm_cdt_select_faces(t, keep, &err), FM_OK);
    validate(t, 1, 1);
    CHECK_EQ(check_chain(t, g, 7, 1), 1); /* (0.5,0.5)-(1,0.5) interior */
    const int32_t *ps = fm_cdt_point_segment(t);
    CHECK_EQ(ps[4], 7);
    CHECK_EQ(ps[5], 100); /* on the chain and on the right side: the lowest index, the side's */
    CHECK_EQ(ps[6], -1); /* outside */
    CHECK_EQ(ps[7], -1);
    for (size_t m = 0; m < fm_cdt_nedges(t); m++)
        CHECK(fm_cdt_edge_ids(t)[m] != -1);
    const int32_t *tri = fm_cdt_triangles(t);
    size_t uses_outside = 0;
    for (size_t k = 0; k < 3 * fm_cdt_ntriangles(t); k++)
        uses_outside += tri[k] == 6 || tri[k] == 7;
    CHECK_EQ(uses_outside, 0);
    CHECK_EQ(refine(t, 0.1, NULL, 0), FM_OK);
    validate(t, 1, 1);
    CHECK(check_chain(t, g, 7, 1) >= 4);
    tri = fm_cdt_triangles(t);
    uses_outside = 0;
    for (size_t k = 0; k < 3 * fm_cdt_ntriangles(t); k++)
        uses_outside += tri[k] == 6 || tri[k] == 7;
    CHECK_EQ(uses_outside, 0);
    const double *p = fm_cdt_points(t);
    size_t beyond = 0;
    for (size_t i = 0; i < fm_cdt_npoints(t); i++)
        beyond += i != 6 && i != 7 && p[2 * i] > 1;
    CHECK_EQ(beyond, 0);
    fm_cdt_destroy(t);
    free(g);
}

/* T-junctions: a chain ending on a chain's vertex, and one ending inside
 * a segment (which splits it). */
static void test_t_junction(void)
{
    for (int variant = 0; variant < 2; variant++) {
        graph *g = square(1);
        /* The sides through (0, 0.5) and (1, 0.5) and (0.5, 1) split. */
        size_t a0, b0;
        if (variant == 0) {
            double a[] = {0, 0.5, 0.5, 0.5, 1, 0.5};
            a0 = add_chain(g, a, 3, 0, 7);
            int32_t mid = 5;
            int32_t top = add_point(g, 0.5, 1);
            b0 = g->ns;
            add_seg(g, mid, top, 8);
        } else {
            double a[] = {0, 0.5, 1, 0.5};
            a0 = add_chain(g, a, 2, 0, 7);
            double b[] = {0.5, 0.5, 0.5, 1};
            b0 = add_chain(g, b, 2, 0, 8);
        }
        fm_cdt *t = make(g);
        CHECK(t != NULL);
        if (!t) {
            free(g);
            continue;
        }
        CHECK_EQ(fm_cdt_nfaces(t), 3);
        int32_t l, r;
        fm_cdt_segment_faces(t, a0, &l, &r);
        int32_t top_left = l, bottom = r;
        fm_cdt_segment_faces(t, b0, &l, &r);
        int32_t top_right = r;
        CHECK_EQ(l, top_left);
        CHECK(top_left != bottom && top_right != bottom && top_left != top_right);
        const double *fa = fm_cdt_face_areas(t), *fp = fm_cdt_face_points(t);
        CHECK_NEAR(fa[bottom], 0.5, 1e-12);
        CHECK_NEAR(fa[top_left], 0.25, 1e-12);
        CHECK_NEAR(fa[top_right], 0.25, 1e-12);
        CHECK(fp[2 * bottom + 1] < 0.5);
        CHECK(fp[2 * top_left] < 0.5 && fp[2 * top_left + 1] > 0.5);
        CHECK(fp[2 * top_right] > 0.5 && fp[2 * top_right + 1] > 0.5);
        /* Keep the bottom and the top right: chain 7 is interior right of
         * the junction only, chain 8 interior. */
        unsigned char keep[3] = {0, 0, 0};
        keep[bottom] = keep[top_right] = 1;
        fm_error err;
        CHECK_EQ(fm_cdt_select_faces(t, keep, &err), FM_OK);
        validate(t, 0.75, 1);
        const int32_t *ed = fm_cdt_edges(t), *eid = fm_cdt_edge_ids(t);
        const unsigned char *ei = fm_cdt_edge_interior(t);
        const double *p = fm_cdt_points(t);
        size_t n7i = 0, n7b = 0, n8 = 0;
        for (size_t m = 0; m < fm_cdt_nedges(t); m++) {
            if (eid[m] == 7) {
                int right = p[2 * ed[2 * m]] >= 0.5 && p[2 * ed[2 * m + 1]] >= 0.5;
                CHECK_EQ(ei[m], right);
                n7i += ei[m];
                n7b += !ei[m];
            }
            if (eid[m] == 8) {
                CHECK_EQ(ei[m], 0);
                n8++;
            }
        }
        CHECK(n7i == 1 && n7b == 1 && n8 == 1);
        /* The junction point reports the lowest segment through it. */
        int32_t jn = variant == 0 ? 5 : 6;
        CHECK_EQ(fm_cdt_point_segment(t)[jn], 7);
        CHECK_EQ(refine(t, 0.05, NULL, 0), FM_OK);
        validate(t, 0.75, 1);
        double ok, mn;
        quality(t, &ok, &mn);
        printf("T-junction %d 0.05: %zu triangles, angle>=30 %.4f, min %.2f\n", variant,
               fm_cdt_ntriangles(t), ok, mn);
        CHECK(ok >= 0.97);
        fm_cdt_destroy(t);
        free(g);
    }
}

/* A polyline from (0, y0) to (s, y1) across the square [0, s]^2, pieces
 * about len long, wiggling, with the given id; its ends split the sides. */
static void wiggly_chain(graph *g, double s, double y0, double y1, double len, int32_t id)
{
    double pts[2 * 512];
    size_t n = (size_t)ceil(hypot(s, y1 - y0) / len);
    for (size_t i = 0; i <= n; i++) {
        double f = (double)i / (double)n;
        pts[2 * i] = f * s;
        pts[2 * i + 1] = y0 + f * (y1 - y0) + (i && i < n ? 0.12 * len * sin(1.7 * (double)i) : 0);
    }
    add_chain(g, pts, n + 1, 0, id);
}

/* A frozen interior chain of pieces about size long: its nodes stay, it
 * is never crossed, and the triangles next to it are decent. The same
 * chain not frozen is split (so frozen is what keeps it). */
static void test_frozen_interior(void)
{
    double s = 10, piece = 1;
    graph *g = square(s);
    size_t first = g->ns;
    wiggly_chain(g, s, 2, 7.3, piece, 5);
    size_t nchain = g->ns - first;
    double sizes[2] = {1, 0.8};
    for (int run = 0; run < 4; run++) {
        double size = sizes[run / 2];
        int freeze = run % 2 == 0;
        fm_cdt *t = make(g);
        CHECK(t != NULL);
        if (!t)
            break;
        CHECK_EQ(fm_cdt_nfaces(t), 2);
        unsigned char keep[2] = {1, 1}, frozen[6] = {0, 0, 0, 0, 0, 1};
        fm_error err;
        CHECK_EQ(fm_cdt_select_faces(t, keep, &err), FM_OK);
        CHECK_EQ(refine(t, size, freeze ? frozen : NULL, freeze ? 6 : 0), FM_OK);
        validate(t, s * s, 1);
        const int32_t *ps = fm_cdt_point_segment(t);
        const double *p = fm_cdt_points(t);
        size_t on5 = 0, added_on5 = 0;
        for (size_t i = 0; i < fm_cdt_npoints(t); i++) {
            on5 += ps[i] == 5;
            added_on5 += ps[i] == 5 && i >= g->np;
        }
        for (size_t i = 0; i < g->np; i++)
            CHECK(p[2 * i] == g->uv[2 * i] && p[2 * i + 1] == g->uv[2 * i + 1]);
        /* Every sub-edge of the chain is an edge with a triangle on each
         * side (exact orient2d), and no triangle edge crosses it. */
        size_t nsub = check_chain(t, g, 5, 1);
        double ok, mn;
        quality(t, &ok, &mn);
        fm_cdt_refine_stats st;
        fm_cdt_refine_get_stats(t, &st);
        printf("interior chain, %s, %zu pieces of %.2f size: %zu triangles, %zu chain edges, "
               "angle>=30 %.4f, min %.2f, %zu rejected, %zu bad left\n",
               freeze ? "frozen" : "free", nchain, hypot(s, 5.3) / (double)nchain / size,
               fm_cdt_ntriangles(t), nsub, ok, mn, st.rejected, st.bad_left);
        if (freeze) {
            /* Nodes on the chain: exactly its input points (its ends are
             * on the square's sides, which come first). */
            CHECK_EQ(added_on5, 0);
            CHECK_EQ(on5, nchain - 1);
            CHECK_EQ(ps[4], 100);
            CHECK_EQ(ps[4 + nchain], 100);
            CHECK_EQ(nsub, nchain);
            CHECK(ok >= 0.95);
            CHECK(mn >= 15);
            CHECK_EQ(st.capped, 0);
        } else if (size < 1) {
            CHECK(added_on5 > 0);
            CHECK_EQ(nsub, nchain + added_on5);
        }
        fm_cdt_destroy(t);
    }
    free(g);
}

static double point_segment_distance(const double *q, const double *a, const double *b)
{
    double dx = b[0] - a[0], dy = b[1] - a[1];
    double f = ((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / (dx * dx + dy * dy);
    f = f < 0 ? 0 : f > 1 ? 1 : f;
    return hypot(q[0] - a[0] - f * dx, q[1] - a[1] - f * dy);
}

/* Face numbers follow the documented key (the smallest directed boundary
 * piece, face on its left) whatever the point numbering; each face's point
 * is the incentre of its triangle with the largest incircle, so at least
 * that radius from every segment. */
static void test_face_numbers(void)
{
    /* The square with the chain's ends as loop points, a chain across and
     * a hole below it: every segment is one piece, the hull the square. */
    double base[] = {0, 0, 1, 0, 1, 0.6, 1, 1, 0, 1, 0, 0.4, 0.5, 0.55,
                     0.6, 0.1, 0.8, 0.1, 0.8, 0.3, 0.6, 0.3};
    int32_t bseg[] = {0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 0, 5, 6, 6, 2, 7, 8, 8, 9, 9, 10, 10, 7};
    size_t np = 11, ns = 12;
    uint64_t r = 5;
    for (int trial = 0; trial < 8; trial++) {
        int32_t perm[11];
        for (size_t i = 0; i < np; i++)
            perm[i] = (int32_t)i;
        for (size_t i = np - 1; i > 0 && trial; i--) {
            r = r * 6364136223846793005ull + 1442695040888963407ull;
            size_t j = (size_t)(r >> 33) % (i + 1);
            int32_t x = perm[i];
            perm[i] = perm[j];
            perm[j] = x;
        }
        double uv[22];
        int32_t seg[24];
        for (size_t i = 0; i < np; i++) {
            uv[2 * perm[i]] = base[2 * i];
            uv[2 * perm[i] + 1] = base[2 * i + 1];
        }
        for (size_t k = 0; k < 2 * ns; k++)
            seg[k] = perm[bseg[k]];
        fm_cdt *t = NULL;
        fm_error err;
        CHECK_EQ(fm_cdt_create_graph(uv, np, seg, NULL, ns, &t, &err), FM_OK);
        if (!t)
            continue;
        size_t nf = fm_cdt_nfaces(t);
        CHECK_EQ(nf, 3);
        if (nf != 3) {
            fm_cdt_destroy(t);
            continue;
        }
        int32_t key[3][2];
        for (int f = 0; f < 3; f++)
            key[f][0] = key[f][1] = INT32_MAX;
        for (size_t k = 0; k < ns; k++) {
            int32_t l, rr, d[2][2] = {{seg[2 * k], seg[2 * k + 1]}, {seg[2 * k + 1], seg[2 * k]}};
            fm_cdt_segment_faces(t, k, &l, &rr);
            int32_t fs[2] = {l, rr};
            for (int side = 0; side < 2; side++) {
                int32_t f = fs[side];
                if (f < 0)
                    continue;
                if (d[side][0] < key[f][0] || (d[side][0] == key[f][0] && d[side][1] < key[f][1])) {
                    key[f][0] = d[side][0];
                    key[f][1] = d[side][1];
                }
            }
        }
        for (int f = 0; f + 1 < 3; f++)
            CHECK(key[f][0] < key[f + 1][0] ||
                  (key[f][0] == key[f + 1][0] && key[f][1] < key[f + 1][1]));
        /* Areas by geometry: above the chain, below it less the hole, the
         * hole. */
        double above[] = {0, 0.4, 0.5, 0.55, 1, 0.6, 1, 1, 0, 1};
        double want[3] = {shoelace(above, 5), 1 - shoelace(above, 5) - 0.04, 0.04};
        const double *fa = fm_cdt_face_areas(t), *fp = fm_cdt_face_points(t);
        const double *p = fm_cdt_points(t);
        const int32_t *tri = fm_cdt_triangles(t);
        double rmax[3] = {0, 0, 0};
        for (int f = 0; f < 3; f++) {
            const double *q = fp + 2 * f;
            int kind = q[0] > 0.6 && q[0] < 0.8 && q[1] > 0.1 && q[1] < 0.3 ? 2
                       : q[1] > (q[0] < 0.5 ? 0.4 + 0.3 * q[0] : 0.55 + 0.1 * (q[0] - 0.5)) ? 0
                                                                                             : 1;
            CHECK_NEAR(fa[f], want[kind], 1e-12);
        }
        /* Before a selection the triangles are the CDT's: the largest
         * incircle in each face (a triangle's face from its centroid). */
        for (size_t k = 0; k < fm_cdt_ntriangles(t); k++) {
            const double *a = p + 2 * tri[3 * k], *b = p + 2 * tri[3 * k + 1], *c = p + 2 * tri[3 * k + 2];
            double g[2] = {(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3};
            double ar = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
            double per = hypot(b[0] - a[0], b[1] - a[1]) + hypot(c[0] - b[0], c[1] - b[1]) +
                         hypot(a[0] - c[0], a[1] - c[1]);
            int kind = g[0] > 0.6 && g[0] < 0.8 && g[1] > 0.1 && g[1] < 0.3 ? 2
                       : g[1] > (g[0] < 0.5 ? 0.4 + 0.3 * g[0] : 0.55 + 0.1 * (g[0] - 0.5)) ? 0
                                                                                             : 1;
            for (int f = 0; f < 3; f++)
                if (fabs(fa[f] - want[kind]) < 1e-12 && 2 * ar / per > rmax[f])
                    rmax[f] = 2 * ar / per;
        }
        for (int f = 0; f < 3; f++) {
            double dmin = 1e300;
            for (size_t k = 0; k < ns; k++)
                dmin = fmin(dmin, point_segment_distance(fp + 2 * f, uv + 2 * seg[2 * k],
                                                         uv + 2 * seg[2 * k + 1]));
            CHECK(rmax[f] > 0 && dmin >= rmax[f] * (1 - 1e-9));
        }
        fm_cdt_destroy(t);
    }
}

static int same_results(const fm_cdt *a, const fm_cdt *b)
{
    int ok = fm_cdt_npoints(a) == fm_cdt_npoints(b) &&
             fm_cdt_ntriangles(a) == fm_cdt_ntriangles(b) && fm_cdt_nedges(a) == fm_cdt_nedges(b) &&
             fm_cdt_nfaces(a) == fm_cdt_nfaces(b);
    if (!ok)
        return 0;
    size_t np = fm_cdt_npoints(a), nt = fm_cdt_ntriangles(a), ne = fm_cdt_nedges(a),
           nf = fm_cdt_nfaces(a);
    return memcmp(fm_cdt_points(a), fm_cdt_points(b), 2 * np * sizeof(double)) == 0 &&
           memcmp(fm_cdt_triangles(a), fm_cdt_triangles(b), 3 * nt * sizeof(int32_t)) == 0 &&
           memcmp(fm_cdt_point_segment(a), fm_cdt_point_segment(b), np * sizeof(int32_t)) == 0 &&
           memcmp(fm_cdt_edges(a), fm_cdt_edges(b), 2 * ne * sizeof(int32_t)) == 0 &&
           memcmp(fm_cdt_edge_ids(a), fm_cdt_edge_ids(b), ne * sizeof(int32_t)) == 0 &&
           memcmp(fm_cdt_edge_interior(a), fm_cdt_edge_interior(b), ne) == 0 &&
           memcmp(fm_cdt_face_areas(a), fm_cdt_face_areas(b), nf * sizeof(double)) == 0 &&
           memcmp(fm_cdt_face_points(a), fm_cdt_face_points(b), 2 * nf * sizeof(double)) == 0;
}

static void test_deterministic(void)
{
    graph *g = square(4);
    wiggly_chain(g, 4, 0.5, 3.1, 0.3, 5);
    double dang[] = {1, 3.5, 2, 3.6, 2.4, 3.2};
    add_chain(g, dang, 3, 0, 6);
    double hole[] = {2.5, 0.5, 3.5, 0.5, 3.5, 1.2, 2.5, 1.2};
    add_chain(g, hole, 4, 1, 9);
    fm_cdt *a = make(g), *b = make(g);
    CHECK(a && b);
    if (!a || !b) {
        free(g);
        return;
    }
    CHECK_EQ(fm_cdt_nfaces(a), 3);
    CHECK(same_results(a, b));
    unsigned char keep[3] = {1, 1, 1}, frozen[7] = {0, 0, 0, 0, 0, 1, 0};
    /* drop the hole's face: the one with the smallest area */
    const double *fa = fm_cdt_face_areas(a);
    int hole_face = 0;
    for (int f = 1; f < 3; f++)
        if (fa[f] < fa[hole_face])
            hole_face = f;
    CHECK_NEAR(fa[hole_face], 0.7, 1e-12);
    keep[hole_face] = 0;
    fm_error err;
    CHECK_EQ(fm_cdt_select_faces(a, keep, &err), FM_OK);
    CHECK_EQ(fm_cdt_select_faces(b, keep, &err), FM_OK);
    CHECK_EQ(refine(a, 0.15, frozen, 7), FM_OK);
    CHECK_EQ(refine(b, 0.15, frozen, 7), FM_OK);
    CHECK(same_results(a, b));
    validate(a, 16 - 0.7, 1);
    check_chain(a, g, 5, 1);
    check_chain(a, g, 6, 1);
    check_chain(a, g, 9, 0);

    /* Face numbers do not depend on the order of the segments (which
     * changes how the triangulation is reached). */
    graph *h = malloc(sizeof *h);
    memcpy(h, g, sizeof *h);
    for (size_t k = 0; k < g->ns; k++) {
        h->seg[2 * k] = g->seg[2 * (g->ns - 1 - k)];
        h->seg[2 * k + 1] = g->seg[2 * (g->ns - 1 - k) + 1];
        h->sid[k] = g->sid[g->ns - 1 - k];
    }
    fm_cdt *c = make(h), *d = make(g);
    CHECK(c && d);
    if (c && d) {
        CHECK_EQ(fm_cdt_nfaces(c), fm_cdt_nfaces(d));
        for (size_t f = 0; f < fm_cdt_nfaces(c) && f < fm_cdt_nfaces(d); f++)
            CHECK_NEAR(fm_cdt_face_areas(c)[f], fm_cdt_face_areas(d)[f], 1e-12);
        for (size_t k = 0; k < g->ns; k++) {
            int32_t l1, r1, l2, r2;
            fm_cdt_segment_faces(d, k, &l1, &r1);
            fm_cdt_segment_faces(c, g->ns - 1 - k, &l2, &r2);
            CHECK(l1 == l2 && r1 == r2);
        }
    }
    fm_cdt_destroy(c);
    fm_cdt_destroy(d);
    free(h);
    fm_cdt_destroy(a);
    fm_cdt_destroy(b);
    free(g);
}

/* Loops given to the graph constructor and a loop CDT: same domain once
 * the inside is selected. */
static void test_loops_as_graph(void)
{
    graph *g = square(1);
    double hole[] = {0.3, 0.3, 0.3, 0.7, 0.7, 0.7, 0.7, 0.3};
    add_chain(g, hole, 4, 1, 101);
    fm_cdt *t = make(g);
    CHECK(t != NULL);
    if (!t) {
        free(g);
        return;
    }
    CHECK_EQ(fm_cdt_nfaces(t), 2);
    const double *fa = fm_cdt_face_areas(t);
    unsigned char keep[2] = {fa[0] > 0.5, fa[1] > 0.5};
    fm_error err;
    CHECK_EQ(fm_cdt_select_faces(t, keep, &err), FM_OK);
    validate(t, 1 - 0.16, 1);
    CHECK_EQ(fm_cdt_nedges(t), 8);
    for (size_t m = 0; m < 8; m++)
        CHECK_EQ(fm_cdt_edge_interior(t)[m], 0);
    CHECK_EQ(refine(t, 0.04, NULL, 0), FM_OK);
    validate(t, 1 - 0.16, 1);
    double ok, mn;
    quality(t, &ok, &mn);
    CHECK(ok >= 0.99);
    /* A loop CDT has no faces and cannot select. */
    fm_cdt *u = NULL;
    CHECK_EQ(fm_cdt_create(g->uv, g->np, g->seg, g->sid, g->ns, &u, &err), FM_OK);
    if (u) {
        CHECK_EQ(fm_cdt_nfaces(u), 0);
        CHECK(fm_cdt_face_areas(u) == NULL);
        CHECK(fm_cdt_face_open(u) == NULL);
        CHECK_EQ(fm_cdt_select_faces(u, keep, &err), FM_ERR_INVALID);
        for (size_t m = 0; m < fm_cdt_nedges(u); m++)
            CHECK_EQ(fm_cdt_edge_interior(u)[m], 0);
        fm_cdt_destroy(u);
    }
    fm_cdt_destroy(t);
    free(g);
}

/* Points only, collinear points, isolated segments, a star of segments. */
static void test_odd_graphs(void)
{
    fm_error err;
    fm_cdt *t = NULL;
    double pts[] = {0, 0, 1, 0, 0.5, 0.8, 0.4, 0.3};
    CHECK_EQ(fm_cdt_create_graph(pts, 4, NULL, NULL, 0, &t, &err), FM_OK);
    if (t) {
        CHECK_EQ(fm_cdt_nfaces(t), 1);
        CHECK_NEAR(fm_cdt_face_areas(t)[0], 0.4, 1e-12);
        validate(t, 0.4, 1);
        CHECK_EQ(fm_cdt_nedges(t), 3); /* the hull, id -1 */
        CHECK_EQ(refine(t, 0.1, NULL, 0), FM_OK);
        validate(t, 0.4, 1);
        CHECK_EQ(fm_cdt_nedges(t), 3); /* never split */
        fm_cdt_destroy(t);
    }
    double line[] = {0, 0, 1, 1, 2, 2, 3, 3};
    int32_t ls[] = {0, 3};
    CHECK_EQ(fm_cdt_create_graph(line, 4, ls, NULL, 1, &t, &err), FM_OK);
    if (t) {
        CHECK_EQ(fm_cdt_nfaces(t), 0);
        CHECK_EQ(fm_cdt_ntriangles(t), 0);
        fm_cdt_destroy(t);
    }
    /* A nearly flat hull: (0.5, -1e-15) is a hull vertex just below the
     * line, and the face must reach it. */
    double flat[] = {0, 0, 0.5, -1e-15, 1, 0, 0.5, 0.5, 0.4, 1e-16};
    CHECK_EQ(fm_cdt_create_graph(flat, 5, NULL, NULL, 0, &t, &err), FM_OK);
    if (t) {
        /* (0.4, 1e-16) lies 9e-16 inside the hull edge below it, whose
         * empty circles are far larger than the super triangle: only a
         * recovered hull keeps the sliver under it. */
        double hull[] = {0, 0, 0.5, -1e-15, 1, 0, 0.5, 0.5};
        CHECK_NEAR(fm_cdt_face_areas(t)[0], shoelace(hull, 4), 1e-15);
        validate(t, shoelace(hull, 4), 1);
        CHECK_EQ(fm_cdt_nedges(t), 4);
        for (size_t m = 0; m < 2 * fm_cdt_nedges(t); m++)
            CHECK(fm_cdt_edges(t)[m] != 4);
        fm_cdt_destroy(t);
    }
    /* A star: 6 segments from the centre of a hexagon to its corners,
     * plus an isolated segment. */
    graph *g = calloc(1, sizeof *g);
    int32_t c = add_point(g, 0, 0);
    for (int i = 0; i < 6; i++) {
        double a = i * 3.14159265358979323846 / 3;
        int32_t v = add_point(g, cos(a), sin(a));
        add_seg(g, c, v, i);
    }
    int32_t x = add_point(g, 0.3, 0.1), y = add_point(g, 0.45, 0.2);
    add_seg(g, x, y, 6);
    t = make(g);
    CHECK(t != NULL);
    if (t) {
        CHECK_EQ(fm_cdt_nfaces(t), 6);
        const double *fa = fm_cdt_face_areas(t);
        for (int f = 0; f < 6; f++)
            CHECK_NEAR(fa[f], sqrt(3) / 4, 1e-12);
        int32_t l, r;
        fm_cdt_segment_faces(t, 6, &l, &r);
        CHECK(l == r && l >= 0);
        validate(t, 6 * sqrt(3) / 4, 1);
        CHECK_EQ(refine(t, 0.1, NULL, 0), FM_OK);
        validate(t, 6 * sqrt(3) / 4, 1);
        for (int k = 0; k < 7; k++)
            check_chain(t, g, k, 1);
        fm_cdt_destroy(t);
    }
    free(g);
}

static void test_bad_input(void)
{
    fm_error err;
    fm_cdt *t = NULL;
    /* Two chains that cross. */
    double x[] = {0, 0, 1, 1, 1, 0, 0, 1};
    int32_t xs[] = {0, 1, 2, 3};
    CHECK_EQ(fm_cdt_create_graph(x, 4, xs, NULL, 2, &t, &err), FM_ERR_TOPOLOGY);
    CHECK(strstr(err.message, "cross") != NULL);
    CHECK(t == NULL);
    /* Overlap along a line. */
    double ov[] = {0, 0, 2, 0, 1, 0, 3, 0, 0, 1};
    int32_t os[] = {0, 1, 2, 3};
    CHECK_EQ(fm_cdt_create_graph(ov, 5, os, NULL, 2, &t, &err), FM_ERR_TOPOLOGY);
    CHECK(strstr(err.message, "overlap") != NULL);
    /* Duplicates, bad indices, repeated and degenerate segments. */
    double dup[] = {0, 0, 1, 0, 0, 0};
    CHECK_EQ(fm_cdt_create_graph(dup, 3, NULL, NULL, 0, &t, &err), FM_ERR_INVALID);
    int32_t oor[] = {0, 5};
    CHECK_EQ(fm_cdt_create_graph(x, 4, oor, NULL, 1, &t, &err), FM_ERR_INVALID);
    int32_t rep[] = {0, 2, 2, 0};
    CHECK_EQ(fm_cdt_create_graph(x, 4, rep, NULL, 2, &t, &err), FM_ERR_INVALID);
    int32_t self[] = {1, 1};
    CHECK_EQ(fm_cdt_create_graph(x, 4, self, NULL, 1, &t, &err), FM_ERR_INVALID);
    CHECK_EQ(fm_cdt_create_graph(x, 4, xs, NULL, 2, NULL, &err), FM_ERR_INVALID);
    /* The loop constructor still wants loops. */
    CHECK_EQ(fm_cdt_create(x, 4, xs, NULL, 1, &t, &err), FM_ERR_TOPOLOGY);
    CHECK(strstr(err.message, "closed loops") != NULL);
}

FM_TEST_MAIN(FM_CASE(test_dangling), FM_CASE(test_cut), FM_CASE(test_leaving),
             FM_CASE(test_t_junction), FM_CASE(test_face_numbers), FM_CASE(test_frozen_interior),
             FM_CASE(test_deterministic), FM_CASE(test_loops_as_graph),
             FM_CASE(test_odd_graphs), FM_CASE(test_bad_input))
