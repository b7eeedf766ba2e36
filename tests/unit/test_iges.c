/* IGES writer: file structure re-read by an independent parser here, and
 * the sample files for tests/tools/check_iges.py (Gmsh / OpenCASCADE).
 *
 * Usage: test_iges            run the checks
 *        test_iges --write DIR write a.igs, b.igs, both.igs into DIR */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fm_atomic.h"
#include "fm_iges.h"
#include "fm_test.h"
#include "fm_test_bspline.h"
#include "iges_internal.h"

/* ---- sample geometry (check_iges.py knows the same numbers) ---- */

/* (a) a plane dipping 60 degrees, striking N60E: S(u, v) = O + u U + v V
 * over [0, 10000] x [0, 8000], bicubic with clamped knots; trimmed by the
 * circle of radius 3500 about (5000, 4000) (exact: rational quadratic),
 * with a 2000 x 2000 square hole about the same centre made of 4 lines.
 * Both loops are given in the wrong sense, so the writer must reverse
 * them. Area pi 3500^2 - 2000^2. */
#define A_R 3500.0
#define A_SIDE 2000.0
static const double a_origin[3] = {400000, 3750000, -500};
static const double a_ku[] = {0, 0, 0, 0, 2500, 5000, 7500, 10000, 10000, 10000, 10000};
static const double a_kv[] = {0, 0, 0, 0, 4000, 8000, 8000, 8000, 8000};
static double a_ctrl[7 * 5 * 3];
static const double circle_knots[] = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
static double circle_ctrl[18], circle_w[9];
static const double line_knots[] = {0, 0, 1, 1};
static double square_ctrl[4][4];
static fm_iges_curve2d circle, square[4];
static fm_iges_loop a_outer, a_hole;

/* (b) z = -3000 + 5e-5 ((u - 5000)^2 + (v - 4000)^2) above (380000 + u,
 * 3760000 + v) over [0, 10000] x [0, 8000]: bicubic, uniform unclamped
 * knots of spacing 1000 as the fit stage makes them, untrimmed. Exact:
 * control points from the blossoms of the quadratics. */
#define B_A 5e-5
static double b_ku[17], b_kv[15], b_ctrl[13 * 11 * 3];

static double greville(const double *k, size_t i) { return (k[i + 1] + k[i + 2] + k[i + 3]) / 3; }

/* Blossom of (x - c)^2 for a cubic at the knots k[i+1..i+3]. */
static double blossom_sq(const double *k, size_t i, double c)
{
    double a = k[i + 1] - c, b = k[i + 2] - c, d = k[i + 3] - c;
    return (a * b + a * d + b * d) / 3;
}

static void build_samples(void)
{
    const double pi = 3.14159265358979323846;
    double U[3] = {cos(pi / 6), sin(pi / 6), 0};
    double V[3] = {-sin(pi / 6) * cos(pi / 3), cos(pi / 6) * cos(pi / 3), -sin(pi / 3)};
    for (size_t j = 0; j < 5; j++)
        for (size_t i = 0; i < 7; i++) {
            double u = greville(a_ku, i), v = greville(a_kv, j);
            for (int d = 0; d < 3; d++)
                a_ctrl[3 * (j * 7 + i) + (size_t)d] = a_origin[d] + u * U[d] + v * V[d];
        }
    /* The circle clockwise: corners and mid-sides of its square, from
     * angle 0 going negative. */
    static const int dir[9][2] = {{1, 0}, {1, -1}, {0, -1}, {-1, -1}, {-1, 0},
                                  {-1, 1}, {0, 1},  {1, 1},   {1, 0}};
    for (int k = 0; k < 9; k++) {
        circle_ctrl[2 * k] = 5000 + A_R * dir[k][0];
        circle_ctrl[2 * k + 1] = 4000 + A_R * dir[k][1];
        circle_w[k] = (k % 2) ? sqrt(0.5) : 1.0;
    }
    circle = (fm_iges_curve2d){2, 9, circle_knots, circle_ctrl, circle_w};
    a_outer = (fm_iges_loop){&circle, 1};
    /* The square counter-clockwise. */
    double h = A_SIDE / 2, c[5][2] = {{5000 - h, 4000 - h}, {5000 + h, 4000 - h},
                                      {5000 + h, 4000 + h}, {5000 - h, 4000 + h},
                                      {5000 - h, 4000 - h}};
    for (int k = 0; k < 4; k++) {
        square_ctrl[k][0] = c[k][0];
        square_ctrl[k][1] = c[k][1];
        square_ctrl[k][2] = c[k + 1][0];
        square_ctrl[k][3] = c[k + 1][1];
        square[k] = (fm_iges_curve2d){1, 2, line_knots, square_ctrl[k], NULL};
    }
    a_hole = (fm_iges_loop){square, 4};

    for (size_t i = 0; i < 17; i++)
        b_ku[i] = ((double)i - 3) * 1000;
    for (size_t i = 0; i < 15; i++)
        b_kv[i] = ((double)i - 3) * 1000;
    for (size_t j = 0; j < 11; j++)
        for (size_t i = 0; i < 13; i++) {
            double *p = &b_ctrl[3 * (j * 13 + i)];
            p[0] = 380000 + greville(b_ku, i);
            p[1] = 3760000 + greville(b_kv, j);
            p[2] = -3000 + B_A * (blossom_sq(b_ku, i, 5000) + blossom_sq(b_kv, j, 4000));
        }
}

static const char *const B_NAME =
    "TEST-BOWL-DOUBLY_CURVED-untrimmed_unclamped_bicubic_patch-with_a_name_"
    "longer_than_one_parameter_line";

static fm_iges_face face_a(void)
{
    fm_iges_face f = {0};
    f.name = "WTRA-TEST-PLANE-Trimmed_disk_with_square_hole";
    f.surface = (fm_iges_surface){3, 3, 7, 5, a_ku, a_kv, a_ctrl, NULL, 0, 0, 0, 0};
    f.outer = &a_outer;
    f.holes = &a_hole;
    f.nholes = 1;
    return f;
}

static fm_iges_face face_b(void)
{
    fm_iges_face f = {0};
    f.name = B_NAME;
    f.surface = (fm_iges_surface){3, 3, 13, 11, b_ku, b_kv, b_ctrl, NULL, 0, 0, 0, 0};
    return f;
}

static void options(fm_iges_options *o)
{
    fm_iges_options_default(o);
    o->author = "faultmesh tests";
    o->organization = "faultmesh";
    o->time = 1700000000; /* 2023-11-14 22:13:20 UTC */
    o->digits = 17; /* exact texts, so that the reals can be compared bit for bit */
    o->tolerance = -1; /* the control points as given */
}

static int write_samples(const char *dir, fm_error *err)
{
    fm_iges_options o;
    options(&o);
    fm_iges_face both[2] = {face_a(), face_b()};
    char path[4096];
    const char *names[3] = {"a.igs", "b.igs", "both.igs"};
    const fm_iges_face *faces[3] = {&both[0], &both[1], both};
    size_t counts[3] = {1, 1, 2};
    if (fm_mkdir_p(dir, err))
        return 1;
    for (int k = 0; k < 3; k++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[k]);
        if (fm_iges_write(path, faces[k], counts[k], &o, err))
            return 1;
    }
    return 0;
}

/* ---- an independent reader ---- */

typedef struct {
    int type, form, pd_first, pd_lines;
    char status[9], label[9];
    char **par; /* parameters as text, strings decoded */
    int npar;
} ent;

typedef struct {
    int nS, nG, nD, nP;
    int tS, tG, tD, tP; /* from the Terminate line */
    char **gpar;
    int ngpar;
    ent *e;
    int ne;
    int ok;
} igs;

static char *dupn(const char *s, size_t n)
{
    char *t = malloc(n + 1);
    memcpy(t, s, n);
    t[n] = '\0';
    return t;
}

/* Splits free-format text at ',' and ';' (strings as nH...). */
static char **split_params(const char *s, int *count)
{
    char **out = NULL;
    int n = 0;
    const char *p = s;
    while (*p) {
        const char *q = p;
        while (*q == ' ')
            q++;
        char *val;
        const char *digits = q;
        while (*q >= '0' && *q <= '9')
            q++;
        if (*q == 'H' && q > digits) {
            size_t len = (size_t)strtoul(digits, NULL, 10);
            val = dupn(q + 1, len);
            q = q + 1 + len;
        } else {
            q = p;
            while (*q && *q != ',' && *q != ';')
                q++;
            val = dupn(p, (size_t)(q - p));
        }
        out = realloc(out, sizeof *out * (size_t)(n + 1));
        out[n++] = val;
        if (*q == ';' || !*q)
            break;
        p = q + 1;
    }
    *count = n;
    return out;
}

static int field(const char *line, int k) /* 8-column integer field k (1-based) */
{
    char t[9];
    memcpy(t, line + 8 * (k - 1), 8);
    t[8] = '\0';
    return atoi(t);
}

static void read_igs(const char *path, igs *f)
{
    memset(f, 0, sizeof *f);
    FILE *fp = fopen(path, "rb");
    CHECK(fp != NULL);
    if (!fp)
        return;
    char **lines = NULL;
    int n = 0, bad = 0;
    char buf[256];
    while (fgets(buf, sizeof buf, fp)) {
        size_t len = strlen(buf);
        if (len != 81 || buf[80] != '\n')
            bad++;
        lines = realloc(lines, sizeof *lines * (size_t)(n + 1));
        lines[n++] = dupn(buf, 80);
    }
    fclose(fp);
    CHECK_EQ(bad, 0);
    /* Sections in order, sequence numbers 1.. within each. */
    const char *order = "SGDPT";
    int sec = 0, count[5] = {0};
    for (int i = 0; i < n; i++) {
        char c = lines[i][72];
        while (sec < 5 && order[sec] != c)
            sec++;
        CHECK(sec < 5);
        if (sec >= 5)
            break;
        count[sec]++;
        CHECK_EQ(atoi(lines[i] + 73), count[sec]);
    }
    f->nS = count[0];
    f->nG = count[1];
    f->nD = count[2];
    f->nP = count[3];
    CHECK_EQ(count[4], 1);
    CHECK(f->nS >= 1 && f->nG >= 1 && f->nD % 2 == 0);
    const char *t = lines[n - 1];
    CHECK(t[0] == 'S' && t[8] == 'G' && t[16] == 'D' && t[24] == 'P');
    f->tS = atoi(t + 1);
    f->tG = atoi(t + 9);
    f->tD = atoi(t + 17);
    f->tP = atoi(t + 25);

    /* Global: columns 1-72 joined. */
    size_t glen = (size_t)f->nG * 72;
    char *g = calloc(glen + 1, 1);
    for (int i = 0; i < f->nG; i++)
        memcpy(g + 72 * i, lines[f->nS + i], 72);
    f->gpar = split_params(g, &f->ngpar);
    free(g);

    int d0 = f->nS + f->nG, p0 = d0 + f->nD;
    f->ne = f->nD / 2;
    f->e = calloc((size_t)f->ne + 1, sizeof *f->e);
    int next_pd = 1;
    for (int k = 0; k < f->ne; k++) {
        const char *l1 = lines[d0 + 2 * k], *l2 = lines[d0 + 2 * k + 1];
        ent *e = &f->e[k];
        e->type = field(l1, 1);
        e->pd_first = field(l1, 2);
        memcpy(e->status, l1 + 64, 8);
        CHECK_EQ(field(l2, 1), e->type);
        e->pd_lines = field(l2, 4);
        e->form = field(l2, 5);
        memcpy(e->label, l2 + 56, 8);
        /* PD contiguous, in DE order, each line pointing back to its DE. */
        CHECK_EQ(e->pd_first, next_pd);
        CHECK(e->pd_lines >= 1);
        next_pd = e->pd_first + e->pd_lines;
        char *pd = calloc((size_t)e->pd_lines * 64 + 1, 1);
        for (int i = 0; i < e->pd_lines && p0 + e->pd_first - 1 + i < n - 1; i++) {
            const char *pl = lines[p0 + e->pd_first - 1 + i];
            memcpy(pd + 64 * i, pl, 64);
            CHECK_EQ(atoi(pl + 64), 2 * k + 1);
            CHECK(pl[64] == ' ');
        }
        e->par = split_params(pd, &e->npar);
        free(pd);
        CHECK(e->npar >= 1 && atoi(e->par[0]) == e->type);
    }
    CHECK_EQ(next_pd - 1, f->nP);
    CHECK_EQ(f->tS, f->nS);
    CHECK_EQ(f->tG, f->nG);
    CHECK_EQ(f->tD, f->nD);
    CHECK_EQ(f->tP, f->nP);
    for (int i = 0; i < n; i++)
        free(lines[i]);
    free(lines);
    f->ok = 1;
}

static void free_igs(igs *f)
{
    for (int i = 0; i < f->ngpar; i++)
        free(f->gpar[i]);
    free(f->gpar);
    for (int k = 0; k < f->ne; k++) {
        for (int i = 0; i < f->e[k].npar; i++)
            free(f->e[k].par[i]);
        free(f->e[k].par);
    }
    free(f->e);
}

/* The entity a DE pointer names, checked to be of the given type. */
static ent *deref(igs *f, const char *ptr, int type)
{
    int de = atoi(ptr);
    CHECK(de >= 1 && de % 2 == 1 && (de + 1) / 2 <= f->ne);
    if (!(de >= 1 && de % 2 == 1 && (de + 1) / 2 <= f->ne))
        return NULL;
    ent *e = &f->e[(de - 1) / 2];
    CHECK_EQ(e->type, type);
    return e->type == type ? e : NULL;
}

static double par(const ent *e, int i) { return i < e->npar ? strtod(e->par[i], NULL) : NAN; }

/* Twice the signed area of the control polygons of a 142's curve(s). */
static double loop_polygon_area(igs *f, const ent *c142)
{
    const ent *b = &f->e[(atoi(c142->par[3]) - 1) / 2];
    const ent *parts[64];
    int np = 0;
    if (b->type == 102) {
        for (int i = 0; i < atoi(b->par[1]) && np < 64; i++)
            parts[np++] = deref(f, b->par[2 + i], 126);
    } else {
        CHECK_EQ(b->type, 126);
        parts[np++] = b;
    }
    double a = 0, first[2] = {0, 0}, prev[2] = {0, 0};
    int have = 0;
    for (int k = 0; k < np; k++) {
        const ent *c = parts[k];
        if (!c)
            return 0;
        int K = atoi(c->par[1]), M = atoi(c->par[2]);
        int at = 7 + (K + M + 2) + (K + 1);
        CHECK_EQ(atoi(c->par[3]), 1); /* planar */
        CHECK_EQ(c->npar, at + 3 * (K + 1) + 5);
        CHECK_EQ(par(c, c->npar - 1), 1.0); /* normal z */
        for (int i = 0; i <= K; i++) {
            double p[2] = {par(c, at + 3 * i), par(c, at + 3 * i + 1)};
            CHECK_EQ(par(c, at + 3 * i + 2), 0.0);
            if (have)
                a += prev[0] * p[1] - p[0] * prev[1];
            else
                memcpy(first, p, sizeof first);
            memcpy(prev, p, sizeof prev);
            have = 1;
        }
    }
    return a + prev[0] * first[1] - first[0] * prev[1];
}

/* ---- checks ---- */

static void tmp_path(char *buf, size_t n, const char *name)
{
    CHECK_EQ(fm_mkdir_p(FM_TMP_DIR, NULL), FM_OK);
    snprintf(buf, n, "%s/%s", FM_TMP_DIR, name);
}

static void check_surface_exact(const ent *s, const fm_iges_surface *in)
{
    int K1 = atoi(s->par[1]), K2 = atoi(s->par[2]), M1 = atoi(s->par[3]), M2 = atoi(s->par[4]);
    CHECK_EQ(K1 + 1, in->nu);
    CHECK_EQ(K2 + 1, in->nv);
    CHECK_EQ(M1, in->degree_u);
    CHECK_EQ(M2, in->degree_v);
    CHECK_EQ(atoi(s->par[7]), in->weights ? 0 : 1);
    int at = 10;
    for (int i = 0; i < K1 + M1 + 2; i++)
        CHECK(par(s, at++) == in->knots_u[i]);
    for (int i = 0; i < K2 + M2 + 2; i++)
        CHECK(par(s, at++) == in->knots_v[i]);
    int n = (K1 + 1) * (K2 + 1);
    for (int i = 0; i < n; i++)
        CHECK(par(s, at++) == 1.0);
    int exact = 1;
    for (int i = 0; i < 3 * n; i++)
        exact &= par(s, at++) == in->ctrl[i];
    CHECK(exact); /* shortest round-trip text reads back bit for bit */
    CHECK_EQ(s->npar, at + 4);
}

static void test_trimmed_face(void)
{
    char path[1024];
    tmp_path(path, sizeof path, "iges_a.igs");
    fm_iges_options o;
    options(&o);
    fm_iges_face f = face_a();
    fm_error err;
    CHECK_EQ(fm_iges_write(path, &f, 1, &o, &err), FM_OK);
    igs g;
    read_igs(path, &g);
    if (!g.ok)
        return;
    /* 128, circle 126 + 142, 4 lines 126 + 102 + 142, 406, 144. */
    CHECK_EQ(g.ne, 11);
    int types[11] = {128, 126, 142, 126, 126, 126, 126, 102, 142, 406, 144};
    for (int k = 0; k < g.ne && k < 11; k++)
        CHECK_EQ(g.e[k].type, types[k]);
    ent *t = &g.e[g.ne - 1];
    CHECK(memcmp(t->status, "00000000", 8) == 0);
    CHECK(memcmp(t->label, "WTRA-TES", 8) == 0);
    for (int k = 0; k < g.ne - 1; k++)
        CHECK(g.e[k].status[3] == '1'); /* physically dependent */
    CHECK(memcmp(g.e[1].status + 4, "05", 2) == 0);
    CHECK_EQ(g.e[9].form, 15);
    CHECK_STR(g.e[9].par[2], f.name);
    /* 144: PTS, N1 = 1, N2 = 1, PTO, PTI, no associativities, 1 property. */
    CHECK_EQ(t->npar, 9);
    ent *s = deref(&g, t->par[1], 128);
    CHECK_EQ(atoi(t->par[2]), 1);
    CHECK_EQ(atoi(t->par[3]), 1);
    ent *outer = deref(&g, t->par[4], 142);
    ent *hole = deref(&g, t->par[5], 142);
    CHECK_EQ(atoi(t->par[6]), 0);
    CHECK_EQ(atoi(t->par[7]), 1);
    deref(&g, t->par[8], 406);
    if (s)
        check_surface_exact(s, &f.surface);
    if (outer && hole) {
        CHECK_EQ(atoi(outer->par[2]), atoi(t->par[1]));
        CHECK_EQ(atoi(outer->par[4]), 0);
        CHECK_EQ(atoi(outer->par[5]), 1);
        deref(&g, outer->par[3], 126);
        deref(&g, hole->par[3], 102);
        /* Given clockwise and counter-clockwise, written the other way. */
        CHECK(loop_polygon_area(&g, outer) > 0);
        CHECK(loop_polygon_area(&g, hole) < 0);
        /* The circle reversed: knots negated, range [-1, 0]. */
        ent *c = &g.e[1];
        CHECK_EQ(par(c, c->npar - 5), -1.0);
        CHECK_EQ(par(c, c->npar - 4), 0.0);
        CHECK_EQ(atoi(c->par[4]), 1); /* closed */
        CHECK_EQ(atoi(c->par[5]), 0); /* rational */
    }
    /* Global section. */
    CHECK_EQ(g.ngpar, 26);
    if (g.ngpar == 26) {
        CHECK_STR(g.gpar[0], ",");
        CHECK_STR(g.gpar[1], ";");
        CHECK_STR(g.gpar[3], "iges_a.igs");
        CHECK_STR(g.gpar[4], "faultmesh");
        CHECK_EQ(atoi(g.gpar[13]), 6);
        CHECK_STR(g.gpar[14], "M");
        CHECK_STR(g.gpar[17], "20231114.221320");
        /* Largest |coordinate|: y of the corner u = 10000, v = 8000. */
        CHECK_NEAR(strtod(g.gpar[19], NULL), 3750000 + 5000 + 8000 * 0.5 * sqrt(3) / 2, 1e-6);
        CHECK_STR(g.gpar[20], "faultmesh tests");
        CHECK_EQ(atoi(g.gpar[22]), 11);
        CHECK_EQ(atoi(g.gpar[23]), 0);
        CHECK_STR(g.gpar[25], "");
    }
    free_igs(&g);
}

static void test_untrimmed_face(void)
{
    char path[1024];
    tmp_path(path, sizeof path, "iges_b.igs");
    fm_iges_options o;
    options(&o);
    fm_iges_face f = face_b();
    fm_error err;
    CHECK_EQ(fm_iges_write(path, &f, 1, &o, &err), FM_OK);
    igs g;
    read_igs(path, &g);
    if (!g.ok)
        return;
    CHECK_EQ(g.ne, 3);
    ent *t = &g.e[2];
    CHECK_EQ(t->type, 144);
    /* Range = knot range: N1 = 0, no loops. */
    CHECK_EQ(t->npar, 8);
    CHECK_EQ(atoi(t->par[2]), 0);
    CHECK_EQ(atoi(t->par[3]), 0);
    CHECK_EQ(atoi(t->par[4]), 0);
    CHECK_STR(g.e[1].par[2], B_NAME); /* a string across PD lines */
    CHECK(g.e[1].pd_lines >= 2);
    ent *s = deref(&g, t->par[1], 128);
    if (s) {
        check_surface_exact(s, &f.surface);
        CHECK_EQ(par(s, s->npar - 4), 0.0);
        CHECK_EQ(par(s, s->npar - 3), 10000.0);
        CHECK_EQ(par(s, s->npar - 1), 8000.0);
    }
    free_igs(&g);

    /* A narrower range than the knots: an explicit rectangle. */
    f.surface.u0 = 1000;
    f.surface.u1 = 9000;
    f.name = NULL;
    CHECK_EQ(fm_iges_write(path, &f, 1, &o, &err), FM_OK);
    read_igs(path, &g);
    if (!g.ok)
        return;
    CHECK_EQ(g.ne, 8);
    t = &g.e[g.ne - 1];
    CHECK_EQ(t->npar, 5);
    CHECK_EQ(atoi(t->par[2]), 1);
    ent *outer = deref(&g, t->par[4], 142);
    if (outer)
        CHECK_NEAR(loop_polygon_area(&g, outer), 2 * 8000.0 * 8000.0, 1e-6);
    CHECK(memcmp(t->label, "        ", 8) == 0);
    free_igs(&g);
}

static void test_deterministic(void)
{
    char p1[1024], p2[1024];
    tmp_path(p1, sizeof p1, "iges_d1.igs");
    tmp_path(p2, sizeof p2, "iges_d2.igs");
    fm_iges_face faces[2] = {face_a(), face_b()};
    fm_iges_options o;
    fm_iges_options_default(&o);
    fm_error err;
    /* SOURCE_DATE_EPOCH stands in for the clock. */
    CHECK_EQ(setenv("SOURCE_DATE_EPOCH", "86399", 1), 0);
    CHECK_EQ(fm_iges_write(p1, faces, 2, &o, &err), FM_OK);
    CHECK_EQ(fm_iges_write(p2, faces, 2, NULL, &err), FM_OK);
    unsetenv("SOURCE_DATE_EPOCH");
    size_t n1 = 0, n2 = 0;
    char *a = fm_test_read_file(p1, &n1), *b = fm_test_read_file(p2, &n2);
    CHECK(a && b && n1 == n2 && n1 > 0);
    /* Identical but for the file name and the product ids taken from it. */
    if (a && b && n1 == n2) {
        size_t diff = 0;
        for (size_t i = 0; i < n1; i++)
            diff += a[i] != b[i];
        CHECK_EQ(diff, 3);
    }
    CHECK(a && strstr(a, "15H19700101.235959") != NULL);
    free(a);
    free(b);
    igs g;
    read_igs(p1, &g);
    if (g.ok) {
        CHECK_EQ(g.ne, 14);
        CHECK_STR(g.gpar[24], "19700101.235959");
        CHECK_STR(g.gpar[2], "iges_d1");
        CHECK_STR(g.gpar[5], "faultmesh " FM_VERSION_STRING);
    }
    free_igs(&g);

    /* No faces: still a valid file. */
    CHECK_EQ(fm_iges_write(p1, NULL, 0, &o, &err), FM_OK);
    read_igs(p1, &g);
    CHECK(g.ok && g.ne == 0 && g.nP == 0);
    free_igs(&g);
}

/* A loop in a corner of face B: only the knot spans it reaches are
 * written, and with the tolerance off and digits automatic the reals are
 * rounded within 1/100 of the resolution. */
static void test_window_and_digits(void)
{
    char path[1024];
    tmp_path(path, sizeof path, "iges_w.igs");
    static const double sq[5][2] = {{1200, 1500}, {2800, 1500}, {2800, 3300}, {1200, 3300},
                                    {1200, 1500}};
    double ctrl[4][4];
    fm_iges_curve2d sides[4];
    for (int k = 0; k < 4; k++) {
        double c[4] = {sq[k][0], sq[k][1], sq[k + 1][0], sq[k + 1][1]};
        memcpy(ctrl[k], c, sizeof c);
        sides[k] = (fm_iges_curve2d){1, 2, line_knots, ctrl[k], NULL};
    }
    fm_iges_loop loop = {sides, 4};
    fm_iges_face f = face_b();
    f.outer = &loop;
    fm_iges_options o;
    options(&o);
    o.digits = 0;
    fm_error err;
    CHECK_EQ(fm_iges_write(path, &f, 1, &o, &err), FM_OK);
    igs g;
    read_igs(path, &g);
    if (!g.ok)
        return;
    ent *s = NULL;
    for (int k = 0; k < g.ne; k++)
        if (g.e[k].type == 128)
            s = &g.e[k];
    CHECK(s != NULL);
    CHECK_EQ(g.ngpar, 26);
    if (!s || g.ngpar != 26) {
        free_igs(&g);
        return;
    }
    /* u: spans [1000, 2000] and [2000, 3000] -> control points 1..5;
     * v: spans [1000, 4000] -> 1..6. */
    CHECK_EQ(atoi(s->par[1]) + 1, 5);
    CHECK_EQ(atoi(s->par[2]) + 1, 6);
    int at = 10;
    for (int i = 0; i < 5 + 4; i++)
        CHECK(par(s, at++) == b_ku[1 + i]);
    for (int j = 0; j < 6 + 4; j++)
        CHECK(par(s, at++) == b_kv[1 + j]);
    at += 5 * 6; /* weights */
    double res = strtod(g.gpar[18], NULL), worst = 0;
    int digits = atoi(g.gpar[10]);
    CHECK(digits >= 6 && digits < 17);
    for (int j = 0; j < 6; j++)
        for (int i = 0; i < 5; i++)
            for (int d = 0; d < 3; d++)
                worst = fmax(worst, fabs(par(s, at++) - b_ctrl[3 * ((size_t)(1 + j) * 13 +
                                                                     (size_t)(1 + i)) +
                                                                (size_t)d]));
    CHECK(res > 0 && worst <= res / 100);
    CHECK(worst > 0); /* rounded, not exact: the default is not 17 digits */
    CHECK_EQ(par(s, at), 1000.0);
    CHECK_EQ(par(s, at + 1), 3000.0);
    CHECK_EQ(par(s, at + 2), 1000.0);
    CHECK_EQ(par(s, at + 3), 4000.0);
    CHECK_EQ(s->npar, at + 4);
    free_igs(&g);
}

/* By default (tolerance automatic: the resolution) the bowl, a single
 * quadratic, loses every interior knot: one span, 4 x 4 control points
 * instead of 13 x 11, each coordinate on the decimal quantum; read back,
 * it stays within the tolerance of the analytic bowl. */
static void test_default_reduces(void)
{
    char path[1024];
    tmp_path(path, sizeof path, "iges_r.igs");
    fm_iges_options o;
    fm_iges_options_default(&o);
    o.time = 1700000000;
    fm_iges_face f = face_b();
    fm_error err;
    CHECK_EQ(fm_iges_write(path, &f, 1, &o, &err), FM_OK);
    igs g;
    read_igs(path, &g);
    if (!g.ok)
        return;
    ent *s = &g.e[0];
    CHECK_EQ(s->type, 128);
    int nu = atoi(s->par[1]) + 1, nv = atoi(s->par[2]) + 1;
    CHECK_EQ(nu, 4);
    CHECK_EQ(nv, 4);
    CHECK_EQ(s->npar, 10 + (nu + 4) + (nv + 4) + 4 * nu * nv + 4);
    if (nu != 4 || nv != 4 || s->npar != 10 + 8 + 8 + 64 + 4) {
        free_igs(&g);
        return;
    }
    double ku[8], kv[8], c[48];
    for (int i = 0; i < 8; i++) {
        ku[i] = par(s, 10 + i);
        kv[i] = par(s, 18 + i);
    }
    CHECK_EQ(ku[3], 0.0);
    CHECK_EQ(ku[4], 10000.0);
    CHECK_EQ(kv[3], 0.0);
    CHECK_EQ(kv[4], 8000.0);
    double res = strtod(g.gpar[18], NULL);
    for (int k = 0; k < 48; k++) {
        const char *t = s->par[10 + 16 + 16 + k];
        c[k] = par(s, 10 + 16 + 16 + k);
        /* the quantum for this resolution: 1e-4 (1e-4 sqrt(3) / 2 <= res / 2 < 1e-3 sqrt(3) / 2) */
        const char *dot = strchr(t, '.');
        CHECK(dot != NULL && strlen(dot + 1) <= 4);
    }
    CHECK(res > 1e-4 * sqrt(3.0) && res < 1e-3 * sqrt(3.0));
    double worst = 0;
    for (int b = 0; b <= 80; b++)
        for (int a = 0; a <= 100; a++) {
            double u = 100.0 * a, v = 100.0 * b, Nu[4], Nv[4], x[3] = {0, 0, 0};
            size_t iu = fm_test_cubic_basis(ku, 4, u, Nu), iv = fm_test_cubic_basis(kv, 4, v, Nv);
            for (size_t j = 0; j < 4; j++)
                for (size_t i = 0; i < 4; i++)
                    for (size_t d = 0; d < 3; d++)
                        x[d] += Nu[i] * Nv[j] * c[3 * ((iv + j) * 4 + iu + i) + d];
            double z = -3000 + B_A * ((u - 5000) * (u - 5000) + (v - 4000) * (v - 4000));
            worst = fmax(worst, sqrt((x[0] - 380000 - u) * (x[0] - 380000 - u) +
                                     (x[1] - 3760000 - v) * (x[1] - 3760000 - v) +
                                     (x[2] - z) * (x[2] - z)));
        }
    printf("bowl read back: within %.2g m of the analytic one (tolerance %.2g m)\n", worst, res);
    CHECK(worst <= res);
    free_igs(&g);

    /* A tolerance of its own: the quantum follows it (0.1 for 0.5). */
    o.tolerance = 0.5;
    CHECK_EQ(fm_iges_write(path, &f, 1, &o, &err), FM_OK);
    read_igs(path, &g);
    if (g.ok && g.e[0].npar > 42) {
        const char *t = g.e[0].par[42];
        CHECK(strchr(t, '.') && strlen(strchr(t, '.') + 1) <= 1);
    }
    free_igs(&g);
    o.tolerance = NAN;
    CHECK_EQ(fm_iges_write(path, &f, 1, &o, &err), FM_ERR_INVALID);
}

/* Reals on a decimal quantum: as many places as the quantum has, the
 * zeros at the end dropped. */
static void test_quantum_text(void)
{
    char b[48];
    iges_format_quantum(-1231.089506, -2, b);
    CHECK_STR(b, "-1231.09");
    iges_format_quantum(4017812.806, -3, b);
    CHECK_STR(b, "4017812.806");
    iges_format_quantum(515673.3773, -1, b);
    CHECK_STR(b, "515673.4");
    iges_format_quantum(0.004, -2, b);
    CHECK_STR(b, "0.");
    iges_format_quantum(-0.004, -2, b);
    CHECK_STR(b, "0.");
    iges_format_quantum(-0.25, -3, b);
    CHECK_STR(b, "-0.25");
    iges_format_quantum(0.0503, -4, b);
    CHECK_STR(b, "0.0503");
    iges_format_quantum(12345.6, 1, b);
    CHECK_STR(b, "12350.");
    iges_format_quantum(-7.0, 0, b);
    CHECK_STR(b, "-7.");
    iges_format_quantum(3.5, -2, b);
    CHECK_STR(b, "3.5");
}

static void test_rejects(void)
{
    char path[1024];
    tmp_path(path, sizeof path, "iges_bad.igs");
    remove(path);
    fm_iges_options o;
    options(&o);
    fm_error err;
    fm_iges_face f = face_a();

    /* An open loop: three sides of the square. */
    fm_iges_loop open = {square, 3};
    f.holes = &open;
    CHECK_EQ(fm_iges_write(path, &f, 1, &o, &err), FM_ERR_INVALID);
    CHECK(strstr(err.message, "not closed") != NULL);
    CHECK(strstr(err.message, "hole 0") != NULL);
    f = face_a();

    /* A loop outside the parameter range. */
    double far_ctrl[18];
    memcpy(far_ctrl, circle_ctrl, sizeof far_ctrl);
    for (int k = 0; k < 9; k++)
        far_ctrl[2 * k] += 3000;
    fm_iges_curve2d far = circle;
    far.ctrl = far_ctrl;
    fm_iges_loop far_loop = {&far, 1};
    f.outer = &far_loop;
    CHECK_EQ(fm_iges_write(path, &f, 1, &o, &err), FM_ERR_INVALID);
    CHECK(strstr(err.message, "leaves") != NULL);
    f = face_a();

    /* Decreasing knots, bad weights, a non-finite point, a bad name. */
    double ku[11];
    memcpy(ku, a_ku, sizeof ku);
    ku[5] = 1000;
    f.surface.knots_u = ku;
    CHECK_EQ(fm_iges_write(path, &f, 1, &o, &err), FM_ERR_INVALID);
    CHECK(strstr(err.message, "knots decrease") != NULL);
    f = face_a();
    double w[9] = {1, 1, 1, 1, 0, 1, 1, 1, 1};
    fm_iges_curve2d cw = circle;
    cw.weights = w;
    fm_iges_loop wl = {&cw, 1};
    f.outer = &wl;
    CHECK_EQ(fm_iges_write(path, &f, 1, &o, &err), FM_ERR_INVALID);
    f = face_a();
    double ctrl[7 * 5 * 3];
    memcpy(ctrl, a_ctrl, sizeof ctrl);
    ctrl[7] = NAN;
    f.surface.ctrl = ctrl;
    CHECK_EQ(fm_iges_write(path, &f, 1, &o, &err), FM_ERR_INVALID);
    f = face_a();
    f.name = "tab\there";
    CHECK_EQ(fm_iges_write(path, &f, 1, &o, &err), FM_ERR_INVALID);
    f = face_a();
    f.surface.u0 = -1;
    f.surface.u1 = 5000;
    CHECK_EQ(fm_iges_write(path, &f, 1, &o, &err), FM_ERR_INVALID);
    f = face_a();
    o.unit_flag = 3;
    CHECK_EQ(fm_iges_write(path, &f, 1, &o, &err), FM_ERR_INVALID);
    options(&o);
    struct stat st;
    CHECK(stat(path, &st) != 0); /* nothing written by a failed call */

    CHECK_EQ(fm_iges_write(FM_TMP_DIR "/no/such/dir/x.igs", &f, 1, &o, &err), FM_ERR_IO);
}

int main(int argc, char **argv)
{
    build_samples();
    if (argc == 3 && strcmp(argv[1], "--write") == 0) {
        fm_error err;
        if (write_samples(argv[2], &err)) {
            fprintf(stderr, "%s\n", err.message);
            return 1;
        }
        return 0;
    }
    static const fm_test_case cases[] = {
        FM_CASE(test_trimmed_face),
        FM_CASE(test_untrimmed_face),
        FM_CASE(test_deterministic),
        FM_CASE(test_window_and_digits),
        FM_CASE(test_default_reduces),
        FM_CASE(test_quantum_text),
        FM_CASE(test_rejects),
    };
    return fm_test_run(cases, sizeof cases / sizeof cases[0]);
}
