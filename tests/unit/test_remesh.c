/* The surface mesher (fm_remesh.h) on faults whose true shape is known:
 * planes and a vertical cylinder, triangulated, repaired and fitted as
 * `faultmesh remesh` does (fm_repair, fm_model_build), then meshed.
 * Measured on the output alone: the sea-level cut (every node z <= 0, the
 * top edge exactly on z = 0, the analytic area below sea level), --top keep
 * and --top extend, a sheet wholly above sea level, quality and size in 3D,
 * nodes on the true surface, the (u, v) contract of fm_remesh_sheet, bad
 * arguments, determinism, an outline with bends rounded too wide to be
 * corners, sampled without cutting them off, one with a slit whose
 * sides are metres apart, meshed without slivers, a boundary node slid
 * along its side out of a sliver, and a curve the sheet ends at that runs
 * through a notch beyond the outline (nothing of the notch filled). */
#include "fm_check.h"
#include "fm_mesh.h"
#include "fm_model.h"
#include "fm_remesh.h"
#include "fm_repair.h"
#include "fm_test.h"
#include "fm_test_mesh.h"
#include "fm_trim.h"
#include "remesh_internal.h"

#include <stdint.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)
#define X0 430000.0
#define Y0 3770000.0
#define H 1000.0

/* A fault x(s, t), s along strike over [0, L], t down dip over [0, W]
 * (arc length in metres). */
typedef struct fault {
    double L, W;
    double dip;  /* degrees; plane */
    double ztop; /* elevation of the top edge */
    double R;    /* > 0: vertical cylinder of radius R instead of a plane */
} fault;

static void fault_point(const fault *f, double s, double t, double p[3])
{
    if (f->R > 0) {
        double a = s / f->R;
        p[0] = X0 + f->R * cos(a);
        p[1] = Y0 + f->R * sin(a);
        p[2] = f->ztop - t;
        return;
    }
    /* strike N60E, dipping to the south-east */
    double sa = 60 * DEG, c = cos(f->dip * DEG), d = sin(f->dip * DEG);
    p[0] = X0 + s * sin(sa) + t * c * cos(sa);
    p[1] = Y0 + s * cos(sa) - t * c * sin(sa);
    p[2] = f->ztop - t * d;
}

/* Distance of p to the true surface, extended beyond its rectangle. */
static double fault_distance(const fault *f, const double p[3])
{
    if (f->R > 0)
        return fabs(hypot(p[0] - X0, p[1] - Y0) - f->R);
    double o[3], a[3], b[3];
    fault_point(f, 0, 0, o);
    fault_point(f, 1, 0, a);
    fault_point(f, 0, 1, b);
    double u[3] = {a[0] - o[0], a[1] - o[1], a[2] - o[2]};
    double v[3] = {b[0] - o[0], b[1] - o[1], b[2] - o[2]};
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    return fabs((p[0] - o[0]) * n[0] + (p[1] - o[1]) * n[1] + (p[2] - o[2]) * n[2]) / nn;
}

static void fault_grid_point(const void *ctx, double s, double t, double p[3])
{
    fault_point(ctx, s, t, p);
}

/* Regular triangulation at spacing h. */
static fm_mesh *triangulate(const fault *f, double h)
{
    return fm_test_grid_mesh(f->L, f->W, h, fault_grid_point, f);
}

/* Triangulate, repair, fit: the model `faultmesh remesh` meshes. */
static fm_model *build_model(const fault *f)
{
    fm_mesh *m = triangulate(f, 500);
    fm_surface *surf = NULL;
    fm_model *model = NULL;
    fm_error err;
    fm_error_clear(&err);
    fm_status st = fm_repair(m, NULL, &surf, &err);
    CHECK_EQ(st, FM_OK);
    if (st == FM_OK) {
        fm_model_options mo;
        fm_model_options_default(&mo);
        st = fm_model_build("test_remesh", surf, &mo, &model, &err);
        if (st != FM_OK)
            fprintf(stderr, "model: %s\n", err.message);
        CHECK_EQ(st, FM_OK);
    }
    fm_surface_destroy(surf);
    fm_mesh_destroy(m);
    return model;
}

static fm_mesh *remesh(const fm_model *model, fm_top_mode top, double extend,
                       fm_remesh_stats *stats)
{
    fm_remesh_options opt;
    fm_remesh_options_default(&opt);
    opt.name = "test_remesh";
    opt.size = H;
    opt.top = top;
    if (top == FM_TOP_EXTEND)
        opt.top_extend = extend;
    fm_mesh *out = NULL;
    fm_error err;
    fm_error_clear(&err);
    fm_status st = fm_remesh_model(model, &opt, &out, stats, &err);
    if (st != FM_OK)
        fprintf(stderr, "remesh: %s\n", err.message);
    CHECK_EQ(st, FM_OK);
    return out;
}

/* What the output mesh is, measured on it alone. */
typedef struct measure {
    size_t tris, nodes, below30, below20, edges, in_band, bnodes;
    size_t above;          /* nodes with z > 0 */
    size_t on_level;       /* boundary nodes with z == 0 exactly */
    size_t near_level;     /* boundary nodes within 1 m below 0 but not on it */
    double level_len;      /* boundary edges with both ends z == 0 */
    double area, zmax, min_angle, max_dist;
} measure;

typedef struct edge {
    int32_t a, b;
} edge;

static int by_edge(const void *x, const void *y)
{
    const edge *p = x, *q = y;
    if (p->a != q->a)
        return (p->a > q->a) - (p->a < q->a);
    return (p->b > q->b) - (p->b < q->b);
}

static double dist3(const double *a, const double *b)
{
    return sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                (a[2] - b[2]) * (a[2] - b[2]));
}

static measure measure_mesh(const fm_mesh *m, const fault *f)
{
    measure r;
    memset(&r, 0, sizeof r);
    size_t nv = fm_mesh_nvertices(m), nt = fm_mesh_ntriangles(m);
    const double *X = fm_mesh_vertices(m);
    const int32_t *T = fm_mesh_triangles(m);
    r.tris = nt;
    r.nodes = nv;
    r.zmax = -INFINITY;
    r.min_angle = 180;
    for (size_t i = 0; i < nv; i++) {
        r.zmax = fmax(r.zmax, X[3 * i + 2]);
        r.above += X[3 * i + 2] > 0;
        if (f)
            r.max_dist = fmax(r.max_dist, fault_distance(f, X + 3 * i));
    }
    edge *e = malloc((3 * nt + 1) * sizeof *e);
    for (size_t t = 0; t < nt; t++) {
        const double *a = X + 3 * T[3 * t], *b = X + 3 * T[3 * t + 1], *c = X + 3 * T[3 * t + 2];
        double ang = fm_triangle_min_angle(a, b, c);
        r.min_angle = fmin(r.min_angle, ang);
        r.below30 += ang < 30;
        r.below20 += ang < 20;
        r.area += fm_triangle_area(a, b, c);
        for (int k = 0; k < 3; k++) {
            int32_t p = T[3 * t + k], q = T[3 * t + (k + 1) % 3];
            e[3 * t + k].a = p < q ? p : q;
            e[3 * t + k].b = p < q ? q : p;
        }
    }
    qsort(e, 3 * nt, sizeof *e, by_edge);
    unsigned char *bnd = calloc(nv + 1, 1);
    for (size_t i = 0; i < 3 * nt;) {
        size_t j = i + 1;
        while (j < 3 * nt && e[j].a == e[i].a && e[j].b == e[i].b)
            j++;
        const double *p = X + 3 * e[i].a, *q = X + 3 * e[i].b;
        double len = dist3(p, q);
        r.edges++;
        r.in_band += len >= 0.7 * H && len <= 1.4 * H;
        if (j - i == 1) {
            bnd[e[i].a] = bnd[e[i].b] = 1;
            if (p[2] == 0 && q[2] == 0)
                r.level_len += len;
        }
        i = j;
    }
    for (size_t i = 0; i < nv; i++) {
        if (!bnd[i])
            continue;
        r.bnodes++;
        double z = X[3 * i + 2];
        r.on_level += z == 0;
        r.near_level += z > -1 && z != 0;
    }
    free(bnd);
    free(e);
    return r;
}

/* The bounds (>= 99.5 % of triangles at 30 degrees or more, none
 * under 20, >= 95 % of edges within [0.7 H, 1.4 H]) hold over a whole fault
 * set; on one small fault (500 triangles, a tenth of its edges on the
 * outline) a few outline edges weigh more, so `loose` allows 1 % and 93 %
 * there. */
static void check_quality(const measure *m, int loose)
{
    double max30 = loose ? 0.01 : 0.005, band = loose ? 0.93 : 0.95;
    int ok = m->tris > 0 && (double)m->below30 <= max30 * (double)m->tris && m->below20 == 0 &&
             (double)m->in_band >= band * (double)m->edges;
    CHECK(m->tris > 0);
    CHECK((double)m->below30 <= max30 * (double)m->tris);
    CHECK_EQ(m->below20, 0);
    CHECK((double)m->in_band >= band * (double)m->edges);
    printf("  quality: %zu tri, min %.1f deg, %zu < 30 (%.2f%%), %zu < 20, edges in band %.1f%%%s\n",
           m->tris, m->min_angle, m->below30, 100.0 * (double)m->below30 / (double)(m->tris ? m->tris : 1),
           m->below20, 100.0 * (double)m->in_band / (double)(m->edges ? m->edges : 1),
           ok ? "" : "  OUTSIDE");
}

static const fault DIPPING = {20000, 12000, 60, 2000, 0};

/* Top cut (the default): a 60 degree plane whose top is 2 km above sea
 * level. */
static void test_cut_plane(void)
{
    fm_model *model = build_model(&DIPPING);
    if (!model)
        return;
    fm_remesh_stats st;
    fm_mesh *m = remesh(model, FM_TOP_CUT, 0, &st);
    if (m) {
        measure r = measure_mesh(m, &DIPPING);
        double below = DIPPING.L * (DIPPING.W - DIPPING.ztop / sin(DIPPING.dip * DEG));
        printf("cut plane: %zu tri, area %.4g (analytic %.4g), level %.0f m, max dist %.3g m\n",
               r.tris, r.area, below, r.level_len, r.max_dist);
        CHECK_EQ(r.above, 0);
        CHECK(r.zmax == 0);
        CHECK_EQ(r.near_level, 0);
        CHECK(r.on_level >= (size_t)(DIPPING.L / (1.4 * H)));
        CHECK(fabs(r.level_len - DIPPING.L) <= 0.02 * DIPPING.L);
        CHECK(fabs(r.area - below) <= 0.02 * below);
        CHECK(r.max_dist < 1.0);
        check_quality(&r, 0);
        CHECK_EQ(st.cut, 1);
        CHECK_EQ(st.empty, 0);
        CHECK_EQ(st.triangles, r.tris);
        CHECK_EQ(st.points, r.nodes);
        CHECK(st.level_points >= r.on_level);
    }
    fm_mesh_destroy(m);
    fm_model_destroy(model);
}

/* --top keep: the part above sea level stays. */
static void test_keep(void)
{
    fm_model *model = build_model(&DIPPING);
    if (!model)
        return;
    fm_remesh_stats st;
    fm_mesh *m = remesh(model, FM_TOP_KEEP, 0, &st);
    if (m) {
        measure r = measure_mesh(m, &DIPPING);
        double all = DIPPING.L * DIPPING.W;
        printf("keep: %zu tri, area %.4g (analytic %.4g), z max %.1f\n", r.tris, r.area, all,
               r.zmax);
        CHECK(fabs(r.area - all) <= 0.02 * all);
        CHECK(fabs(r.zmax - DIPPING.ztop) <= 100);
        CHECK_EQ(st.cut, 0);
        CHECK(r.max_dist < 1.0);
        check_quality(&r, 1);
    }
    fm_mesh_destroy(m);
    fm_model_destroy(model);
}

/* --top extend D: a top 300 m below sea level reaches it when D >= 300 and
 * stays blind otherwise; plain cut leaves it blind. */
static void test_extend(void)
{
    const fault f = {20000, 10000, 60, -300, 0};
    fm_model *model = build_model(&f);
    if (!model)
        return;
    double up = -f.ztop / sin(f.dip * DEG); /* 346 m up dip */
    fm_remesh_stats st;
    fm_mesh *m = remesh(model, FM_TOP_EXTEND, 2000, &st);
    if (m) {
        measure r = measure_mesh(m, &f);
        double want = f.L * (f.W + up);
        printf("extend: %zu tri, area %.4g (analytic %.4g), level %.0f m, extended %.0f m\n",
               r.tris, r.area, want, r.level_len, st.extended);
        CHECK(r.zmax == 0);
        CHECK_EQ(r.above, 0);
        CHECK_EQ(r.near_level, 0);
        CHECK(fabs(r.level_len - f.L) <= 0.02 * f.L);
        CHECK(fabs(r.area - want) <= 0.02 * want);
        CHECK(st.extended >= up - 1);
        CHECK(r.max_dist < 1.0);
        check_quality(&r, 1);
    }
    fm_mesh_destroy(m);
    m = remesh(model, FM_TOP_EXTEND, 200, &st);
    if (m) {
        measure r = measure_mesh(m, &f);
        CHECK(fabs(r.zmax - f.ztop) <= 50);
        CHECK(r.level_len == 0);
        CHECK(fabs(r.area - f.L * f.W) <= 0.02 * f.L * f.W);
    }
    fm_mesh_destroy(m);
    m = remesh(model, FM_TOP_CUT, 0, &st);
    if (m) {
        measure r = measure_mesh(m, &f);
        CHECK(fabs(r.zmax - f.ztop) <= 50);
        CHECK_EQ(st.cut, 0);
        CHECK(fabs(r.area - f.L * f.W) <= 0.02 * f.L * f.W);
    }
    fm_mesh_destroy(m);
    fm_model_destroy(model);
}

/* A sheet wholly above sea level: an empty mesh, flagged. */
static void test_above_sea_level(void)
{
    const fault f = {15000, 5000, 45, 4500, 0}; /* z from 4500 down to about 965 m */
    fm_model *model = build_model(&f);
    if (!model)
        return;
    fm_remesh_stats st;
    fm_mesh *m = remesh(model, FM_TOP_CUT, 0, &st);
    if (m) {
        CHECK_EQ(fm_mesh_ntriangles(m), 0);
        CHECK_EQ(st.empty, 1);
        CHECK_EQ(st.triangles, 0);
    }
    fm_mesh_destroy(m);
    /* the same through fm_remesh_sheet */
    fm_remesh_options opt;
    fm_remesh_options_default(&opt);
    size_t nl = fm_model_nloops(model, 0);
    const fm_trim_loop *loops[8];
    for (size_t k = 0; k < nl && k < 8; k++)
        loops[k] = fm_model_loop(model, 0, k);
    fm_error err;
    double *uv = NULL;
    fm_status s = fm_remesh_sheet(fm_model_surface(model, 0), loops, nl, &opt, 0, &m, &uv, &st, &err);
    CHECK_EQ(s, FM_OK);
    if (s == FM_OK) {
        CHECK_EQ(st.empty, 1);
        CHECK_EQ(fm_mesh_ntriangles(m), 0);
    }
    free(uv);
    fm_mesh_destroy(m);
    /* keep meshes it all */
    m = remesh(model, FM_TOP_KEEP, 0, &st);
    if (m) {
        CHECK(fm_mesh_ntriangles(m) > 0);
        CHECK_EQ(st.empty, 0);
    }
    fm_mesh_destroy(m);
    fm_model_destroy(model);
}

/* A curved (vertical cylinder) fault crossing sea level: nodes stay on the
 * true surface, quality holds, the area below sea level is right. */
static void test_cylinder(void)
{
    const fault f = {25000, 10000, 90, 1500, 20000};
    fm_model *model = build_model(&f);
    if (!model)
        return;
    fm_remesh_stats st;
    fm_mesh *m = remesh(model, FM_TOP_CUT, 0, &st);
    if (m) {
        measure r = measure_mesh(m, &f);
        double below = f.L * (f.W - f.ztop);
        printf("cylinder: %zu tri, area %.4g (analytic %.4g), level %.0f m, max dist %.2f m\n",
               r.tris, r.area, below, r.level_len, r.max_dist);
        CHECK_EQ(r.above, 0);
        CHECK_EQ(r.near_level, 0);
        CHECK(fabs(r.level_len - f.L) <= 0.02 * f.L);
        CHECK(fabs(r.area - below) <= 0.02 * below);
        CHECK(r.max_dist < 10.0);
        check_quality(&r, 1);
    }
    fm_mesh_destroy(m);
    fm_model_destroy(model);
}

static double orient2(const double *a, const double *b, const double *c)
{
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/* fm_remesh_sheet: uv_out gives every node's parameters, the node is the
 * surface there (sea-level nodes: but for z), triangles are
 * counter-clockwise in (u, v) and tagged. */
static void test_sheet_uv(void)
{
    fm_model *model = build_model(&DIPPING);
    if (!model)
        return;
    fm_remesh_options opt;
    fm_remesh_options_default(&opt);
    opt.size = H;
    const fm_fit_surface *s = fm_model_surface(model, 0);
    size_t nl = fm_model_nloops(model, 0);
    const fm_trim_loop *loops[8];
    for (size_t k = 0; k < nl && k < 8; k++)
        loops[k] = fm_model_loop(model, 0, k);
    fm_mesh *m = NULL;
    double *uv = NULL;
    fm_remesh_stats st;
    fm_error err;
    fm_status rc = fm_remesh_sheet(s, loops, nl, &opt, 7, &m, &uv, &st, &err);
    CHECK_EQ(rc, FM_OK);
    if (rc == FM_OK && uv) {
        const double *X = fm_mesh_vertices(m);
        const int32_t *T = fm_mesh_triangles(m), *tag = fm_mesh_tags(m);
        size_t off = 0, badtag = 0, cw = 0;
        for (size_t i = 0; i < fm_mesh_nvertices(m); i++) {
            double p[3];
            fm_fit_surface_eval(s, uv[2 * i], uv[2 * i + 1], p, NULL, NULL);
            double dz = X[3 * i + 2] == 0 ? 0 : p[2] - X[3 * i + 2];
            if (fabs(p[0] - X[3 * i]) > 1e-6 || fabs(p[1] - X[3 * i + 1]) > 1e-6 ||
                fabs(dz) > 1e-6 || (X[3 * i + 2] == 0 && fabs(p[2]) > 1e-3))
                off++;
        }
        for (size_t t = 0; t < fm_mesh_ntriangles(m); t++) {
            badtag += tag[t] != 7;
            cw += orient2(uv + 2 * T[3 * t], uv + 2 * T[3 * t + 1], uv + 2 * T[3 * t + 2]) <= 0;
        }
        CHECK_EQ(off, 0);
        CHECK_EQ(badtag, 0);
        CHECK_EQ(cw, 0);
        CHECK_EQ(st.points, fm_mesh_nvertices(m));
    }
    free(uv);
    fm_mesh_destroy(m);
    /* bad arguments */
    opt.size = 0;
    rc = fm_remesh_sheet(s, loops, nl, &opt, 0, &m, NULL, &st, &err);
    CHECK_EQ(rc, FM_ERR_INVALID);
    opt.size = NAN;
    rc = fm_remesh_sheet(s, loops, nl, &opt, 0, &m, NULL, &st, &err);
    CHECK_EQ(rc, FM_ERR_INVALID);
    opt.size = H;
    rc = fm_remesh_sheet(s, loops, 0, &opt, 0, &m, NULL, &st, &err);
    CHECK_EQ(rc, FM_ERR_INVALID);
    fm_model_destroy(model);
}

/* Shoelace area of a domain loop in (u, v). */
static double loop_area(const dom_loop *l)
{
    double a = 0;
    for (size_t i = 0; i < l->n; i++) {
        const double *p = l->uv + 2 * i, *q = l->uv + 2 * ((i + 1) % l->n);
        a += p[0] * q[1] - q[0] * p[1];
    }
    return 0.5 * a;
}

/* A rectangle of 5 x 3 km with corners rounded at 500 m: no corner for
 * the trimming fit, so one periodic piece sampled at equal steps, whose
 * chords cut across some of the rounded corners. After the sag splits
 * (domain_sag.c) the sampled outline keeps the curve's area. The plane's
 * (u, v) is metres on the fault (a height field over its own plane). */
static void test_rounded_outline(void)
{
    fm_model *model = build_model(&DIPPING);
    if (!model)
        return;
    const fm_fit_surface *s = fm_model_surface(model, 0);
    double dom[4];
    fm_fit_surface_domain(s, dom);
    double c[2] = {0.5 * (dom[0] + dom[1]), 0.5 * (dom[2] + dom[3])};
    const double a = 2500, b = 1500, r = 500, step = 50;
    double corner[4][2] = {{a - r, b - r}, {-(a - r), b - r}, {-(a - r), -(b - r)}, {a - r, -(b - r)}};
    double *uv = malloc(2 * 4096 * sizeof *uv);
    size_t n = 0;
    for (int k = 0; k < 4; k++) {
        /* the quarter arc at corner k, then the straight side to corner k + 1 */
        int m = (int)ceil(0.5 * PI * r / step);
        for (int i = 0; i < m; i++) {
            double t = 0.5 * PI * (k + (double)i / m);
            uv[2 * n] = c[0] + corner[k][0] + r * cos(t);
            uv[2 * n + 1] = c[1] + corner[k][1] + r * sin(t);
            n++;
        }
        const double *p = corner[k], *q = corner[(k + 1) % 4];
        double t = 0.5 * PI * (k + 1);
        double s0[2] = {p[0] + r * cos(t), p[1] + r * sin(t)}, s1[2] = {q[0] + r * cos(t), q[1] + r * sin(t)};
        double len = hypot(s1[0] - s0[0], s1[1] - s0[1]);
        int ms = (int)ceil(len / step);
        for (int i = 0; i < ms; i++) {
            uv[2 * n] = c[0] + s0[0] + (s1[0] - s0[0]) * i / ms;
            uv[2 * n + 1] = c[1] + s0[1] + (s1[1] - s0[1]) * i / ms;
            n++;
        }
    }
    fm_trim_loop *loop = NULL;
    fm_error err;
    fm_error_clear(&err);
    CHECK_EQ(fm_trim_fit(uv, n, NULL, &loop, &err), FM_OK);
    free(uv);
    if (!loop) {
        fm_model_destroy(model);
        return;
    }
    CHECK_EQ(fm_trim_loop_npieces(loop), 1);
    const fm_trim_loop *loops[1] = {loop};
    double curve = fm_trim_loop_area(loop);
    remesh_domain d;
    CHECK_EQ(domain_sample(s, loops, 1, H, &d, &err, "rounded"), FM_OK);
    double before = loop_area(&d.loops[0]) / curve;
    CHECK_EQ(domain_split_sags(s, loops, &d, H), 0);
    double after = loop_area(&d.loops[0]) / curve;
    printf("rounded outline: sampled area / curve area %.4f, after sag splits %.4f (%zu nodes)\n",
           before, after, d.loops[0].n);
    /* a chord a size long that keeps within a tenth of a size of a
     * 500 m arc loses at most about 2 % of this outline; without the
     * splits, the phase of the equal steps decides */
    CHECK(after >= 0.98);
    CHECK(after >= before);
    domain_free(&d);
    fm_trim_loop_destroy(loop);
    fm_model_destroy(model);
}

/* Appends the points from a to b (b excluded) at about `step` apart. */
static size_t add_side(double *uv, size_t n, const double a[2], const double b[2], double step)
{
    int m = (int)ceil(hypot(b[0] - a[0], b[1] - a[1]) / step);
    for (int i = 0; i < m; i++) {
        uv[2 * n] = a[0] + (b[0] - a[0]) * i / m;
        uv[2 * n + 1] = a[1] + (b[1] - a[1]) * i / m;
        n++;
    }
    return n;
}

/* A rectangle of 6 x 4 km with a slit 2 km long out of its top side, 3 m
 * wide at its base (a spike of the outline, as on a Rose Canyon sheet,
 * whose despiked base left two corners 3 m apart and a 2.7 degree
 * triangle at 1 km). Despiking takes the slit's tip off and leaves the
 * nodes half way up its sides 1.5 m apart; one of them goes
 * (domain_merge_close), the other is then a tip despiking takes off, and
 * so on down to the base. No outline edge is left shorter than a quarter
 * size, and no 3D angle is under 20 degrees but at the outline's sharp
 * corners (65 triangles were without the merge). */
static void test_close_corners(void)
{
    fm_model *model = build_model(&DIPPING);
    if (!model)
        return;
    const fm_fit_surface *s = fm_model_surface(model, 0);
    double dom[4];
    fm_fit_surface_domain(s, dom);
    double c[2] = {0.5 * (dom[0] + dom[1]), 0.5 * (dom[2] + dom[3])};
    double P[][2] = {{-3000, -2000}, {3000, -2000}, {3000, 2000}, {503, 2000},
                     {300, 4000},    {500, 2000},   {-3000, 2000}};
    size_t np = sizeof P / sizeof P[0];
    double *uv = malloc(2 * 4096 * sizeof *uv);
    unsigned char *corner = calloc(4096, 1);
    size_t n = 0;
    for (size_t k = 0; k < np; k++) {
        double a[2] = {c[0] + P[k][0], c[1] + P[k][1]};
        double b[2] = {c[0] + P[(k + 1) % np][0], c[1] + P[(k + 1) % np][1]};
        corner[n] = 1;
        n = add_side(uv, n, a, b, 50);
    }
    fm_trim_options to;
    fm_trim_options_default(&to);
    to.corner_at = corner;
    fm_trim_loop *loop = NULL;
    fm_error err;
    fm_error_clear(&err);
    CHECK_EQ(fm_trim_fit(uv, n, &to, &loop, &err), FM_OK);
    free(uv);
    free(corner);
    if (!loop) {
        fm_model_destroy(model);
        return;
    }
    const fm_trim_loop *loops[1] = {loop};
    remesh_domain d;
    CHECK_EQ(domain_sample(s, loops, 1, H, &d, &err, "slit"), FM_OK);
    CHECK_EQ(domain_split_sags(s, loops, &d, H), 0);
    domain_despike(s, &d, 30.0);
    double before = INFINITY, after = INFINITY;
    for (size_t i = 0; i < d.loops[0].n; i++)
        before = fmin(before, surface_dist(s, d.loops[0].uv + 2 * i,
                                           d.loops[0].uv + 2 * ((i + 1) % d.loops[0].n)));
    /* as build_domain does: a merge can leave a spike to take off */
    while (domain_merge_close(s, &d, H))
        domain_despike(s, &d, 30.0);
    for (size_t i = 0; i < d.loops[0].n; i++)
        after = fmin(after, surface_dist(s, d.loops[0].uv + 2 * i,
                                         d.loops[0].uv + 2 * ((i + 1) % d.loops[0].n)));
    printf("slit: shortest outline edge %.1f m after despiking, %.1f m after merging\n", before,
           after);
    CHECK(before < 10);
    CHECK(after >= 0.25 * H);
    domain_free(&d);

    fm_remesh_options opt;
    fm_remesh_options_default(&opt);
    opt.size = H;
    opt.top = FM_TOP_KEEP;
    fm_mesh *m = NULL;
    fm_remesh_stats st;
    CHECK_EQ(fm_remesh_sheet(s, loops, 1, &opt, 0, &m, NULL, &st, &err), FM_OK);
    if (m) {
        fm_quality q;
        CHECK_EQ(fm_check_quality(m, -1, H, &q), FM_OK);
        printf("slit: %zu triangles, min angle %.1f deg, %zu under 20 deg (%zu at sharp corners)\n",
               fm_mesh_ntriangles(m), q.angle_min, q.below_20, q.below_20_forced);
        CHECK_EQ(q.below_20, q.below_20_forced);
    }
    fm_mesh_destroy(m);
    fm_trim_loop_destroy(loop);
    fm_model_destroy(model);
}

/* A curve the sheet ends at that leaves the outline through a notch in
 * its bottom side and comes back, as Hosgri's does on Santa Maria Basin
 * thrust A (CFM, 1 km): the curve's piece in the notch has on its kept
 * (left) side the convex hull's pocket beyond the outline, which no curve
 * closes off; taken for a gap and filled, it put the hull's edge across
 * the notch on the boundary, never split (a 21 km edge with a fan of
 * slivers there). The sheet keeps the two parts below the curve's arms
 * and nothing of the notch. */
static void test_curve_through_notch(void)
{
    fm_model *model = build_model(&DIPPING);
    if (!model)
        return;
    const fm_fit_surface *s = fm_model_surface(model, 0);
    double dom[4];
    fm_fit_surface_domain(s, dom);
    double c[2] = {0.5 * (dom[0] + dom[1]), 0.5 * (dom[2] + dom[3])};
    double P[][2] = {{-8000, -5000}, {-2000, -5000}, {-2000, -1000}, {2000, -1000},
                     {2000, -5000},  {8000, -5000},  {8000, 5000},   {-8000, 5000}};
    size_t np = sizeof P / sizeof P[0];
    double *uv = malloc(2 * 4096 * sizeof *uv);
    unsigned char *corner = calloc(4096, 1);
    size_t n = 0;
    for (size_t k = 0; k < np; k++) {
        double a[2] = {c[0] + P[k][0], c[1] + P[k][1]};
        double b[2] = {c[0] + P[(k + 1) % np][0], c[1] + P[(k + 1) % np][1]};
        corner[n] = 1;
        n = add_side(uv, n, a, b, 50);
    }
    fm_trim_options to;
    fm_trim_options_default(&to);
    to.corner_at = corner;
    fm_trim_loop *loop = NULL;
    fm_error err;
    fm_error_clear(&err);
    CHECK_EQ(fm_trim_fit(uv, n, &to, &loop, &err), FM_OK);
    free(corner);
    if (!loop) {
        free(uv);
        fm_model_destroy(model);
        return;
    }
    /* from the top side down into the notch, along under its roof, and
     * back up: the flap between the arms is dropped */
    double Q[][2] = {{3500, 5000}, {1000, -1300}, {-1000, -1300}, {-3500, 5000}};
    size_t nq = 0;
    for (size_t k = 0; k + 1 < sizeof Q / sizeof Q[0]; k++) {
        double a[2] = {c[0] + Q[k][0], c[1] + Q[k][1]};
        double b[2] = {c[0] + Q[k + 1][0], c[1] + Q[k + 1][1]};
        nq = add_side(uv, nq, a, b, 0.9 * H);
    }
    uv[2 * nq] = c[0] + Q[3][0];
    uv[2 * nq + 1] = c[1] + Q[3][1];
    nq++;
    int64_t *ids = malloc(nq * sizeof *ids);
    for (size_t i = 0; i < nq; i++)
        ids[i] = 100 + (int64_t)i;
    fm_remesh_curve cv = {uv, nq, ids, 1, 0, -1};
    const fm_trim_loop *loops[1] = {loop};
    fm_remesh_options opt;
    fm_remesh_options_default(&opt);
    opt.size = H;
    opt.top = FM_TOP_KEEP;
    fm_mesh *m = NULL;
    double *muv = NULL;
    fm_remesh_stats st;
    fm_status rc = fm_remesh_sheet_joined(s, loops, 1, &cv, 1, &opt, 0, &m, &muv, NULL, &st, &err);
    if (rc != FM_OK)
        fprintf(stderr, "notch: %s\n", err.message);
    CHECK_EQ(rc, FM_OK);
    if (m && muv) {
        size_t nt = fm_mesh_ntriangles(m);
        const double *X = fm_mesh_vertices(m);
        const int32_t *T = fm_mesh_triangles(m);
        edge *e = malloc(3 * nt * sizeof *e);
        size_t in_notch = 0;
        for (size_t t = 0; t < nt; t++) {
            double g[2] = {0, 0};
            for (int k = 0; k < 3; k++) {
                int32_t a = T[3 * t + k], b = T[3 * t + (k + 1) % 3];
                e[3 * t + (size_t)k] = (edge){a < b ? a : b, a < b ? b : a};
                g[0] += muv[2 * a] / 3;
                g[1] += muv[2 * a + 1] / 3;
            }
            in_notch += fabs(g[0] - c[0]) < 2000 && g[1] - c[1] < -1000;
        }
        qsort(e, 3 * nt, sizeof *e, by_edge);
        double longest = 0;
        for (size_t i = 0; i < 3 * nt;) {
            size_t j = i;
            while (j < 3 * nt && e[j].a == e[i].a && e[j].b == e[i].b)
                j++;
            if (j - i == 1)
                longest = fmax(longest, dist3(X + 3 * e[i].a, X + 3 * e[i].b));
            i = j;
        }
        free(e);
        printf("notch: %zu triangles, longest boundary edge %.0f m, %zu triangles in the notch\n",
               nt, longest, in_notch);
        CHECK(longest <= 1.5 * H);
        CHECK_EQ(in_notch, 0);
    }
    free(muv);
    free(ids);
    free(uv);
    fm_mesh_destroy(m);
    fm_trim_loop_destroy(loop);
    fm_model_destroy(model);
}

/* Smallest 3D angle (degrees) of the triangles, and whether all are
 * counter-clockwise in (u, v). */
static double min_angle_ccw(const double *uv, const double *xyz, const int32_t *tri, size_t nt,
                            int *ccw)
{
    double a = 180;
    *ccw = 1;
    for (size_t t = 0; t < nt; t++) {
        const int32_t *T = tri + 3 * t;
        *ccw &= orient2(uv + 2 * T[0], uv + 2 * T[1], uv + 2 * T[2]) > 0;
        for (int k = 0; k < 3; k++)
            a = fmin(a, fm_angle_at(xyz + 3 * T[k], xyz + 3 * T[(k + 1) % 3],
                                    xyz + 3 * T[(k + 2) % 3]));
    }
    return a;
}

/* A boundary node refinement put on a side (E on A-B, a tenth of the way)
 * with one inside node F: every node is on the boundary or fixed, so
 * flips alone leave a 6 degree triangle at F. With the curves given
 * (slide_boundary) E moves along A-B towards the middle: the triangles
 * get above 30 degrees, E stays on the side and no other node moves. (As
 * in the wedges where the outline meets sea level at a shallow angle:
 * Big Pine east and West Huasna at 500 m had 18.4 and 19.9 degrees.) */
static void test_slide(void)
{
    fm_model *model = build_model(&DIPPING);
    if (!model)
        return;
    const fm_fit_surface *s = fm_model_surface(model, 0);
    double dom[4];
    fm_fit_surface_domain(s, dom);
    double c[2] = {0.5 * (dom[0] + dom[1]), 0.5 * (dom[2] + dom[3])};
    /* A B C D (the domain's own nodes), E on A-B, F inside */
    const double P[6][2] = {{0, 0}, {1000, 0}, {1000, 800}, {0, 800}, {100, 0}, {500, 400}};
    const int32_t T[5][3] = {{0, 4, 5}, {4, 1, 5}, {1, 2, 5}, {2, 3, 5}, {3, 0, 5}};
    const int32_t cons[5][2] = {{0, 4}, {4, 1}, {1, 2}, {2, 3}, {3, 0}};
    const int32_t pseg[6] = {0, 0, 1, 2, 0, -1};
    dom_seg segs[4];
    double ends[16];
    for (int k = 0; k < 4; k++) {
        segs[k] = (dom_seg){SEG_FREE, 0, 0, 0, 0};
        for (int q = 0; q < 2; q++) {
            ends[4 * k + q] = c[q] + P[k][q];
            ends[4 * k + 2 + q] = c[q] + P[(k + 1) % 4][q];
        }
    }
    const unsigned char fixed[6] = {1, 1, 1, 1, 1, 1};
    double angle[2] = {0, 0}, e_off = 0, moved = 0;
    int ccw[2] = {0, 0};
    for (int with = 0; with < 2; with++) {
        double uv[12], xyz[18];
        int32_t tri[15];
        for (int i = 0; i < 6; i++) {
            uv[2 * i] = c[0] + P[i][0];
            uv[2 * i + 1] = c[1] + P[i][1];
            fm_fit_surface_eval(s, uv[2 * i], uv[2 * i + 1], xyz + 3 * i, NULL, NULL);
        }
        memcpy(tri, T, sizeof tri);
        size_t nt = 5;
        opt_curves cv = {NULL, 0, segs, ends, pseg, 4};
        opt_result res;
        CHECK_EQ(optimise_mesh(s, uv, xyz, fixed, 6, tri, &nt, &cons[0][0], 5, with ? &cv : NULL,
                               2, 600, &res),
                 FM_OK);
        angle[with] = min_angle_ccw(uv, xyz, tri, nt, &ccw[with]);
        if (with) {
            CHECK(res.slid > 0);
            /* E on the line A-B (v unchanged), between a quarter and three quarters */
            e_off = fabs(uv[2 * 4 + 1] - (c[1] + P[0][1]));
            CHECK(uv[2 * 4] - c[0] >= 250 - 1e-9 && uv[2 * 4] - c[0] <= 750 + 1e-9);
            for (int i = 0; i < 6; i++)
                if (i != 4)
                    moved = fmax(moved, hypot(uv[2 * i] - c[0] - P[i][0], uv[2 * i + 1] - c[1] - P[i][1]));
        }
    }
    printf("slide: smallest angle %.1f deg with flips alone, %.1f deg with the boundary node slid\n",
           angle[0], angle[1]);
    CHECK(angle[0] < 20);
    CHECK(angle[1] >= 30);
    CHECK(ccw[0] && ccw[1]);
    CHECK(e_off < 1e-9);
    CHECK(moved == 0);
    fm_model_destroy(model);
}

/* Same input, same output, to the bit (two models built from scratch). */
static void test_determinism(void)
{
    const fault *cases[2] = {&DIPPING, NULL};
    const fault cyl = {25000, 10000, 90, 1500, 20000};
    cases[1] = &cyl;
    for (int c = 0; c < 2; c++) {
        fm_mesh *m[2] = {NULL, NULL};
        for (int k = 0; k < 2; k++) {
            fm_model *model = build_model(cases[c]);
            fm_remesh_stats st;
            if (model)
                m[k] = remesh(model, FM_TOP_CUT, 0, &st);
            fm_model_destroy(model);
        }
        if (m[0] && m[1]) {
            size_t nv = fm_mesh_nvertices(m[0]), nt = fm_mesh_ntriangles(m[0]);
            CHECK_EQ(nv, fm_mesh_nvertices(m[1]));
            CHECK_EQ(nt, fm_mesh_ntriangles(m[1]));
            if (nv == fm_mesh_nvertices(m[1]) && nt == fm_mesh_ntriangles(m[1])) {
                CHECK(!memcmp(fm_mesh_vertices(m[0]), fm_mesh_vertices(m[1]), 3 * nv * sizeof(double)));
                CHECK(!memcmp(fm_mesh_triangles(m[0]), fm_mesh_triangles(m[1]), 3 * nt * sizeof(int32_t)));
                CHECK(!memcmp(fm_mesh_tags(m[0]), fm_mesh_tags(m[1]), nt * sizeof(int32_t)));
            }
        }
        fm_mesh_destroy(m[0]);
        fm_mesh_destroy(m[1]);
    }
}

FM_TEST_MAIN(FM_CASE(test_cut_plane), FM_CASE(test_keep), FM_CASE(test_extend),
             FM_CASE(test_above_sea_level), FM_CASE(test_cylinder), FM_CASE(test_sheet_uv),
             FM_CASE(test_determinism), FM_CASE(test_rounded_outline),
             FM_CASE(test_close_corners), FM_CASE(test_slide),
             FM_CASE(test_curve_through_notch))
