/* The synthetic fault system: deterministic, on its analytic surfaces, with
 * the features it promises, and readable by io + repair as documented. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_atomic.h"
#include "fm_mesh.h"
#include "fm_repair.h"
#include "fm_synth.h"
#include "fm_test.h"
#include "fm_tsurf.h"

static fm_synth *make(double spacing, unsigned seed)
{
    fm_synth_options opt;
    fm_synth_options_default(&opt);
    opt.spacing = spacing;
    opt.seed = seed;
    fm_synth *s = NULL;
    fm_error err;
    fm_status st = fm_synth_create(&opt, &s, &err);
    if (st != FM_OK)
        fprintf(stderr, "fm_synth_create: %s\n", err.message);
    return s;
}

static long find_kind(const fm_synth *s, const char *fragment)
{
    for (size_t i = 0; i < fm_synth_nfaults(s); i++)
        if (strstr(fm_synth_fault_name(s, i), fragment))
            return (long)i;
    return -1;
}

/* ---- edge topology of a triangle soup ---------------------------------- */

typedef struct edge_counts {
    size_t edges, boundary, interior, triple, more;
    size_t used_vertices;
    long euler;              /* V - E + F over used vertices */
    size_t boundary_parts;   /* connected components of the boundary edges */
} edge_counts;

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

static size_t uf_find(size_t *p, size_t i)
{
    while (p[i] != i)
        i = p[i] = p[p[i]];
    return i;
}

static edge_counts count_edges(const fm_mesh *m)
{
    edge_counts c = {0};
    size_t nt = fm_mesh_ntriangles(m), nv = fm_mesh_nvertices(m);
    const int32_t *t = fm_mesh_triangles(m);
    uint64_t *e = malloc(3 * nt * sizeof *e);
    size_t *parent = malloc(nv * sizeof *parent);
    unsigned char *used = calloc(nv, 1), *onb = calloc(nv, 1);
    for (size_t k = 0; k < nt; k++)
        for (int q = 0; q < 3; q++) {
            uint64_t a = (uint64_t)t[3 * k + q], b = (uint64_t)t[3 * k + (q + 1) % 3];
            e[3 * k + q] = a < b ? (a << 32 | b) : (b << 32 | a);
            used[a] = 1;
        }
    qsort(e, 3 * nt, sizeof *e, cmp_u64);
    for (size_t i = 0; i < nv; i++) {
        parent[i] = i;
        c.used_vertices += used[i];
    }
    for (size_t i = 0; i < 3 * nt;) {
        size_t j = i;
        while (j < 3 * nt && e[j] == e[i])
            j++;
        size_t n = j - i;
        c.edges++;
        if (n == 1) {
            size_t a = (size_t)(e[i] >> 32), b = (size_t)(e[i] & 0xffffffffu);
            c.boundary++;
            onb[a] = onb[b] = 1;
            parent[uf_find(parent, a)] = uf_find(parent, b);
        }
        c.interior += n == 2;
        c.triple += n == 3;
        c.more += n > 3;
        i = j;
    }
    for (size_t i = 0; i < nv; i++)
        c.boundary_parts += onb[i] && uf_find(parent, i) == i;
    c.euler = (long)c.used_vertices - (long)c.edges + (long)nt;
    free(e);
    free(parent);
    free(used);
    free(onb);
    return c;
}

/* ---- tests on the in-memory system -------------------------------------- */

static void test_determinism(void)
{
    fm_synth *a = make(500.0, 1), *b = make(500.0, 1), *c = make(500.0, 2);
    CHECK(a && b && c);
    if (!a || !b || !c)
        goto done;
    CHECK_EQ(fm_synth_nfaults(a), fm_synth_nfaults(b));
    int seed_matters = 0;
    for (size_t i = 0; i < fm_synth_nfaults(a); i++) {
        const fm_mesh *ma = fm_synth_fault_mesh(a, i), *mb = fm_synth_fault_mesh(b, i);
        const fm_mesh *mc = fm_synth_fault_mesh(c, i);
        CHECK_STR(fm_synth_fault_name(a, i), fm_synth_fault_name(b, i));
        CHECK_EQ(fm_mesh_nvertices(ma), fm_mesh_nvertices(mb));
        CHECK_EQ(fm_mesh_ntriangles(ma), fm_mesh_ntriangles(mb));
        if (fm_mesh_nvertices(ma) != fm_mesh_nvertices(mb) ||
            fm_mesh_ntriangles(ma) != fm_mesh_ntriangles(mb))
            continue;
        CHECK(memcmp(fm_mesh_vertices(ma), fm_mesh_vertices(mb),
                     3 * fm_mesh_nvertices(ma) * sizeof(double)) == 0);
        CHECK(memcmp(fm_mesh_triangles(ma), fm_mesh_triangles(mb),
                     3 * fm_mesh_ntriangles(ma) * sizeof(int32_t)) == 0);
        CHECK(memcmp(fm_mesh_tags(ma), fm_mesh_tags(mb),
                     fm_mesh_ntriangles(ma) * sizeof(int32_t)) == 0);
        fm_synth_expect e;
        fm_synth_fault_expect(a, i, &e);
        int same = fm_mesh_nvertices(ma) == fm_mesh_nvertices(mc) &&
                   memcmp(fm_mesh_vertices(ma), fm_mesh_vertices(mc),
                          3 * fm_mesh_nvertices(ma) * sizeof(double)) == 0;
        /* The seed only drives the noisy, irregular fault. */
        if (e.noise == 0.0)
            CHECK(same);
        seed_matters |= !same;
    }
    CHECK(seed_matters);
    double p[3], q[3];
    fm_synth_eval(a, 1, 1234.5, 2345.6, p);
    fm_synth_eval(b, 1, 1234.5, 2345.6, q);
    CHECK(memcmp(p, q, sizeof p) == 0);
done:
    fm_synth_destroy(a);
    fm_synth_destroy(b);
    fm_synth_destroy(c);
}

static void test_options(void)
{
    fm_synth_options opt;
    fm_synth_options_default(&opt);
    CHECK_NEAR(opt.spacing, 500.0, 0.0);
    CHECK_EQ(opt.seed, 1);
    fm_synth *s = NULL;
    fm_error err;
    opt.spacing = 0.0;
    CHECK_EQ(fm_synth_create(&opt, &s, &err), FM_ERR_INVALID);
    CHECK(s == NULL);
    opt.spacing = NAN;
    CHECK_EQ(fm_synth_create(&opt, &s, &err), FM_ERR_INVALID);
    /* Every feature survives a coarse and a fine spacing. */
    const double spacings[] = {2500.0, 250.0};
    for (size_t k = 0; k < 2; k++) {
        s = make(spacings[k], 7);
        CHECK(s != NULL);
        if (!s)
            continue;
        for (size_t i = 0; i < fm_synth_nfaults(s); i++) {
            fm_synth_expect e;
            fm_synth_fault_expect(s, i, &e);
            edge_counts c = count_edges(fm_synth_fault_mesh(s, i));
            CHECK_EQ(c.triple, e.junction_edges);
            CHECK_EQ(c.euler, (long)e.parts - (long)e.holes);
        }
        fm_synth_destroy(s);
    }
}

static void test_layout(void)
{
    fm_synth *s = make(500.0, 1);
    CHECK(s != NULL);
    if (!s)
        return;
    size_t n = fm_synth_nfaults(s), total = 0;
    CHECK(n >= 9);
    int seen_hole = 0, seen_seam = 0, seen_branch = 0, seen_blind = 0, seen_noise = 0;
    int seen_gap = 0, seen_overshoot = 0;
    for (size_t i = 0; i < n; i++) {
        const char *name = fm_synth_fault_name(s, i);
        /* AREA-ZONE-SECTION-Name-version, as in CFM. */
        int dashes = 0;
        for (const char *p = name; *p; p++)
            dashes += *p == '-';
        CHECK_EQ(dashes, 4);
        CHECK(strncmp(name, "SYNT-", 5) == 0);
        CHECK(strlen(fm_synth_fault_description(s, i)) > 10);
        CHECK_EQ(fm_synth_find(s, name), (long)i);

        const fm_mesh *m = fm_synth_fault_mesh(s, i);
        fm_synth_expect e;
        fm_synth_fault_expect(s, i, &e);
        total += fm_mesh_ntriangles(m);
        edge_counts c = count_edges(m);
        CHECK_EQ(c.more, 0);
        CHECK_EQ(c.used_vertices, fm_mesh_nvertices(m));
        /* Conforming discs: each part a disc, minus a hole, plus a splay
         * glued along a path (which leaves the Euler number unchanged). */
        CHECK_EQ(c.euler, (long)e.parts - (long)e.holes);
        CHECK_EQ(c.triple, e.junction_edges);
        CHECK_EQ(c.boundary_parts, e.parts + e.holes + e.junctions);

        const double *v = fm_mesh_vertices(m);
        const int32_t *t = fm_mesh_triangles(m), *tag = fm_mesh_tags(m);
        double amin = 180.0, zmax = -1e30;
        for (size_t k = 0; k < fm_mesh_ntriangles(m); k++) {
            double a = fm_triangle_min_angle(v + 3 * t[3 * k], v + 3 * t[3 * k + 1],
                                             v + 3 * t[3 * k + 2]);
            amin = a < amin ? a : amin;
            CHECK(tag[k] >= 0 && (size_t)tag[k] < e.parts);
        }
        for (size_t k = 0; k < fm_mesh_nvertices(m); k++)
            zmax = v[3 * k + 2] > zmax ? v[3 * k + 2] : zmax;
        CHECK(amin > 10.0);
        if (e.blind) {
            CHECK_NEAR(zmax, -2000.0, 1e-6);
        } else {
            CHECK(e.top_zmin >= 200.0 - 1e-9 && e.top_zmax <= 800.0 + 1e-9);
            CHECK(e.top_zmax - e.top_zmin > 20.0); /* follows the topography */
            CHECK(zmax <= e.top_zmax + e.noise + 1e-9);
            CHECK(zmax >= e.top_zmin);
        }
        seen_hole += e.holes == 1;
        seen_seam += e.parts == 2 && e.seam_vertices > 2;
        seen_branch += e.sheets == 2 && e.junctions == 1 && e.junction_edges > 5;
        seen_blind += e.blind;
        seen_noise += e.noise > 0.0;
        seen_gap += e.gap_to >= 0 && e.gap > 250.0 && e.gap < 350.0;
        seen_overshoot += e.overshoot_of >= 0 && e.overshoot > 350.0 && e.overshoot < 450.0;
    }
    CHECK(total < 50000);
    CHECK(seen_hole && seen_seam && seen_branch && seen_blind && seen_noise && seen_gap &&
          seen_overshoot);
    printf("synth: %zu faults, %zu triangles at 500 m\n", n, total);
    fm_synth_destroy(s);
}

static void test_vertices_on_surface(void)
{
    fm_synth *s = make(500.0, 1);
    CHECK(s != NULL);
    if (!s)
        return;
    for (size_t i = 0; i < fm_synth_nfaults(s); i++) {
        const fm_mesh *m = fm_synth_fault_mesh(s, i);
        fm_synth_expect e;
        fm_synth_fault_expect(s, i, &e);
        double bound = e.noise > 0.0 ? e.noise * sqrt(3.0) + 1e-6 : 1e-6, dmax = 0.0;
        const double *v = fm_mesh_vertices(m);
        for (size_t k = 0; k < fm_mesh_nvertices(m); k++) {
            double d = fm_synth_distance(s, i, v + 3 * k);
            dmax = d > dmax ? d : dmax;
        }
        if (!(dmax <= bound))
            fprintf(stderr, "%s: vertex %.3g m off its surface\n", fm_synth_fault_name(s, i),
                    dmax);
        CHECK(dmax <= bound);
        if (e.noise > 0.0)
            CHECK(dmax > 0.3 * e.noise);
    }
    fm_synth_destroy(s);
}

static void test_distance_offsets(void)
{
    fm_synth *s = make(500.0, 1);
    CHECK(s != NULL);
    if (!s)
        return;
    const double offsets[] = {-1200.0, -400.0, -25.0, -0.01, 0.003, 7.0, 150.0, 900.0, 1400.0};
    for (size_t i = 0; i < fm_synth_nfaults(s); i++) {
        for (size_t k = 0; k < fm_synth_nsheets(s, i); k++) {
            double r[4];
            fm_synth_sheet_rect(s, i, k, r);
            for (int a = 1; a <= 5; a++) {
                for (int b = 1; b <= 4; b++) {
                    double ps = r[0] + (r[1] - r[0]) * (0.03 + 0.94 * a / 6.0);
                    double pt = r[2] + (r[3] - r[2]) * b / 5.0;
                    double x[3], nrm[3];
                    fm_synth_eval_sheet(s, i, k, ps, pt, x);
                    fm_synth_normal(s, i, k, ps, pt, nrm);
                    CHECK_NEAR(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2], 1.0, 1e-12);
                    for (size_t o = 0; o < sizeof offsets / sizeof offsets[0]; o++) {
                        double p[3], cs, ct;
                        size_t sheet;
                        for (int q = 0; q < 3; q++)
                            p[q] = x[q] + offsets[o] * nrm[q];
                        double d = fm_synth_closest(s, i, p, &sheet, &cs, &ct, NULL);
                        double want = fabs(offsets[o]);
                        if (fm_synth_nsheets(s, i) > 1 && sheet != k) {
                            /* The other sheet of the branch is nearer. */
                            CHECK(d <= want + 1e-3);
                            continue;
                        }
                        if (fabs(d - want) > 1e-3)
                            fprintf(stderr, "%s sheet %zu (%g, %g) offset %g: distance %.9g\n",
                                    fm_synth_fault_name(s, i), k, ps, pt, offsets[o], d);
                        CHECK_NEAR(d, want, 1e-3);
                        if (want <= 150.0) {
                            CHECK_NEAR(cs, ps, 1e-3);
                            CHECK_NEAR(ct, pt, 1e-3);
                        }
                    }
                }
            }
        }
    }
    fm_synth_destroy(s);
}

static void test_distance_clamped(void)
{
    fm_synth *s = make(500.0, 1);
    CHECK(s != NULL);
    if (!s)
        return;
    double r[4], x[3], n[3], p[3], u[3];
    fm_synth_sheet_rect(s, 0, 0, r);
    /* Straight below the bottom edge of the vertical main fault. */
    fm_synth_eval(s, 0, 0.5 * (r[0] + r[1]), r[3], x);
    p[0] = x[0];
    p[1] = x[1];
    p[2] = x[2] - 1000.0;
    CHECK_NEAR(fm_synth_distance(s, 0, p), 1000.0, 1e-3);
    /* Beyond its s = max end, 700 m along strike and 300 m off the plane. */
    double y[3];
    fm_synth_eval(s, 0, r[1], 0.5 * r[3], x);
    fm_synth_eval(s, 0, r[1] - 1000.0, 0.5 * r[3], y);
    fm_synth_normal(s, 0, 0, r[1], 0.5 * r[3], n);
    for (int q = 0; q < 3; q++) {
        u[q] = (x[q] - y[q]) / 1000.0;
        p[q] = x[q] + 700.0 * u[q] + 300.0 * n[q];
    }
    double cs, ct;
    CHECK_NEAR(fm_synth_closest(s, 0, p, NULL, &cs, &ct, NULL), sqrt(700.0 * 700.0 + 300.0 * 300.0),
               1e-3);
    CHECK_NEAR(cs, r[1], 1e-9);
    /* Far away (tens of km) still gives a sensible, finite answer. */
    p[0] = 450000.0;
    p[1] = 3700000.0;
    p[2] = 5000.0;
    double d = fm_synth_distance(s, 0, p);
    CHECK(d > 1000.0 && d < 200000.0);
    fm_synth_destroy(s);
}

static void test_relations(void)
{
    fm_synth *s = make(500.0, 1);
    CHECK(s != NULL);
    if (!s)
        return;
    for (size_t i = 0; i < fm_synth_nfaults(s); i++) {
        fm_synth_expect e;
        fm_synth_fault_expect(s, i, &e);
        long target = e.gap_to >= 0 ? e.gap_to : e.overshoot_of;
        if (target < 0)
            continue;
        double want = e.gap_to >= 0 ? e.gap : e.overshoot;
        const fm_mesh *m = fm_synth_fault_mesh(s, i);
        const double *v = fm_mesh_vertices(m);
        size_t nend = 0, neg = 0, pos = 0;
        double dmin = 1e30;
        for (size_t k = 0; k < fm_mesh_nvertices(m); k++) {
            double cs, foot[3], nrm[3], ps, pt;
            size_t sh;
            fm_synth_closest(s, i, v + 3 * k, NULL, &cs, NULL, NULL);
            double d = fm_synth_closest(s, (size_t)target, v + 3 * k, &sh, &ps, &pt, foot);
            dmin = d < dmin ? d : dmin;
            fm_synth_normal(s, (size_t)target, sh, ps, pt, nrm);
            double side = 0.0;
            for (int q = 0; q < 3; q++)
                side += (v[3 * k + q] - foot[q]) * nrm[q];
            pos += side > 1.0;
            neg += side < -1.0;
            if (cs < 1e-6) {
                nend++;
                CHECK_NEAR(d, want, 1e-6);
            }
        }
        CHECK(nend >= 7);
        if (e.gap_to >= 0) {
            CHECK_NEAR(dmin, want, 1e-6); /* nothing closer than the end */
            CHECK(pos == 0 || neg == 0);  /* stays on one side */
        } else {
            CHECK(pos > 0 && neg > 0); /* crosses */
        }
    }
    /* The listric thrust: 60 deg near the top, 20 deg at its bottom. */
    long th = find_kind(s, "Listric");
    CHECK(th >= 0);
    if (th >= 0) {
        double r[4], n[3];
        fm_synth_sheet_rect(s, (size_t)th, 0, r);
        fm_synth_normal(s, (size_t)th, 0, 0.5 * r[1], r[3], n);
        CHECK_NEAR(acos(fabs(n[2])) * 180.0 / 3.14159265358979323846, 20.0, 1e-4);
        fm_synth_normal(s, (size_t)th, 0, 0.5 * r[1], 0.0, n);
        CHECK_NEAR(acos(fabs(n[2])) * 180.0 / 3.14159265358979323846, 60.0, 1.0);
    }
    /* The corrugated fault: 250 m sine along strike. */
    long co = find_kind(s, "Corrugated");
    CHECK(co >= 0);
    if (co >= 0) {
        /* Crest and trough (s = 1, 3 km) face the same way; half-way the
         * slope 2 pi A / L = 0.39 turns the normal by about 21 deg. */
        double a[3], b[3], c[3];
        fm_synth_normal(s, (size_t)co, 0, 1000.0, 3000.0, a);
        fm_synth_normal(s, (size_t)co, 0, 2000.0, 3000.0, b);
        fm_synth_normal(s, (size_t)co, 0, 3000.0, 3000.0, c);
        double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        double ac = a[0] * c[0] + a[1] * c[1] + a[2] * c[2];
        double turn = acos(ab) * 180.0 / 3.14159265358979323846;
        CHECK(ac > 0.999);
        CHECK(turn > 18.0 && turn < 24.0);
    }
    fm_synth_destroy(s);
}

/* Apart from the gap and the overshoot, faults keep kilometres apart, so
 * that a later stage finding another contact has a bug. */
static void test_separation(void)
{
    fm_synth *s = make(1000.0, 1);
    CHECK(s != NULL);
    if (!s)
        return;
    size_t n = fm_synth_nfaults(s);
    for (size_t i = 0; i < n; i++) {
        fm_synth_expect e;
        fm_synth_fault_expect(s, i, &e);
        for (size_t j = 0; j < n; j++) {
            fm_synth_expect ej;
            fm_synth_fault_expect(s, j, &ej);
            if (j == i || e.gap_to == (long)j || e.overshoot_of == (long)j ||
                ej.gap_to == (long)i || ej.overshoot_of == (long)i || e.crosses == (long)j ||
                ej.crosses == (long)i)
                continue;
            const fm_mesh *m = fm_synth_fault_mesh(s, i);
            double dmin = 1e30;
            for (size_t k = 0; k < fm_mesh_nvertices(m); k++)
                dmin = fmin(dmin, fm_synth_distance(s, j, fm_mesh_vertices(m) + 3 * k));
            if (!(dmin > 1500.0))
                fprintf(stderr, "%s to %s: %.0f m\n", fm_synth_fault_name(s, i),
                        fm_synth_fault_name(s, j), dmin);
            CHECK(dmin > 1500.0);
        }
    }
    fm_synth_destroy(s);
}

/* ---- written files, read back through io and repair ---------------------- */

static void test_write_read_repair(void)
{
    fm_synth *s = make(500.0, 1);
    CHECK(s != NULL);
    if (!s)
        return;
    fm_error err;
    const char *dir = FM_TMP_DIR "/synth";
    CHECK_EQ(fm_mkdir_p(FM_TMP_DIR, &err), FM_OK);
    fm_status st = fm_synth_write(s, dir, &err);
    if (st != FM_OK)
        fprintf(stderr, "fm_synth_write: %s\n", err.message);
    CHECK_EQ(st, FM_OK);

    char path[1024];
    snprintf(path, sizeof path, "%s/faults.json", dir);
    FILE *fp = fopen(path, "rb");
    CHECK(fp != NULL);
    char *json = NULL;
    if (fp) {
        fseek(fp, 0, SEEK_END);
        long len = ftell(fp);
        fseek(fp, 0, SEEK_SET);
        json = calloc((size_t)len + 1, 1);
        CHECK(fread(json, 1, (size_t)len, fp) == (size_t)len);
        fclose(fp);
    }

    for (size_t i = 0; i < fm_synth_nfaults(s); i++) {
        const char *name = fm_synth_fault_name(s, i);
        if (json)
            CHECK(strstr(json, name) != NULL);
        fm_synth_expect e;
        fm_synth_fault_expect(s, i, &e);
        const fm_mesh *mem = fm_synth_fault_mesh(s, i);

        snprintf(path, sizeof path, "%s/%s.ts", dir, name);
        fm_tsurf **objs = NULL;
        size_t nobj = 0;
        st = fm_tsurf_read_file(path, &objs, &nobj, &err);
        if (st != FM_OK)
            fprintf(stderr, "read %s: %s\n", path, err.message);
        CHECK_EQ(st, FM_OK);
        if (st != FM_OK)
            continue;
        CHECK_EQ(nobj, 1);
        CHECK_STR(fm_tsurf_name(objs[0]), name);
        CHECK_EQ(fm_tsurf_nparts(objs[0]), e.parts);
        fm_tsurf_crs crs;
        fm_tsurf_get_crs(objs[0], &crs);
        CHECK(crs.z_positive_depth == 0);
        const fm_mesh *m = fm_tsurf_mesh(objs[0]);
        CHECK_EQ(fm_mesh_nvertices(m), fm_mesh_nvertices(mem));
        CHECK_EQ(fm_mesh_ntriangles(m), fm_mesh_ntriangles(mem));
        CHECK_STR(crs.name, "Default");
        /* Parts are written in order and coordinates round-trip, so the
         * file reads back exactly as generated. */
        if (fm_mesh_nvertices(m) == fm_mesh_nvertices(mem))
            CHECK(memcmp(fm_mesh_vertices(m), fm_mesh_vertices(mem),
                         3 * fm_mesh_nvertices(m) * sizeof(double)) == 0);
        if (fm_mesh_ntriangles(m) == fm_mesh_ntriangles(mem)) {
            CHECK(memcmp(fm_mesh_triangles(m), fm_mesh_triangles(mem),
                         3 * fm_mesh_ntriangles(m) * sizeof(int32_t)) == 0);
            CHECK(memcmp(fm_mesh_tags(m), fm_mesh_tags(mem),
                         fm_mesh_ntriangles(m) * sizeof(int32_t)) == 0);
        }

        fm_repair_options ro;
        fm_repair_options_default(&ro);
        fm_surface *surf = NULL;
        st = fm_repair(m, &ro, &surf, &err);
        if (st != FM_OK)
            fprintf(stderr, "repair %s: %s\n", name, err.message);
        CHECK_EQ(st, FM_OK);
        if (st == FM_OK) {
            const fm_repair_report *rep = fm_surface_report(surf);
            if (rep->sheets != e.sheets || rep->holes != e.holes || rep->junctions != e.junctions)
                fprintf(stderr, "%s: sheets %zu holes %zu junctions %zu\n", name, rep->sheets,
                        rep->holes, rep->junctions);
            CHECK_EQ(rep->sheets, e.sheets);
            CHECK_EQ(fm_surface_nsheets(surf), e.sheets);
            CHECK_EQ(rep->holes, e.holes);
            CHECK_EQ(rep->junctions, e.junctions);
            CHECK_EQ(fm_surface_njunctions(surf), e.junctions);
            CHECK_EQ(rep->nonmanifold_edges, e.junction_edges);
            CHECK_EQ(rep->welded_exact, e.seam_vertices);
            CHECK_EQ(rep->degenerate_removed, 0);
            CHECK_EQ(rep->duplicates_removed, 0);
            CHECK_EQ(rep->fragments_dropped, 0);
            CHECK_EQ(rep->triangles_out, fm_mesh_ntriangles(mem));
            /* Tops: above sea level unless blind, on every sheet. */
            for (size_t k = 0; k < fm_surface_nsheets(surf); k++) {
                const fm_mesh *sm = fm_surface_sheet_mesh(surf, k);
                double zmax = -1e30;
                for (size_t q = 0; q < fm_mesh_nvertices(sm); q++)
                    zmax = fmax(zmax, fm_mesh_vertices(sm)[3 * q + 2]);
                if (e.blind)
                    CHECK_NEAR(zmax, -2000.0, 1e-3);
                else
                    CHECK(zmax > 150.0);
            }
            if (e.junctions == 1 && fm_surface_njunctions(surf) == 1) {
                size_t np = 0, ns = 0;
                fm_surface_junction_points(surf, 0, &np);
                fm_surface_junction_sheets(surf, 0, &ns);
                CHECK_EQ(np, e.junction_edges + 1);
                CHECK_EQ(ns, 2);
                CHECK(!fm_surface_junction_closed(surf, 0));
            }
            fm_surface_destroy(surf);
        }

        /* Gap and overshoot, measured from the file's end vertices. */
        long target = e.gap_to >= 0 ? e.gap_to : e.overshoot_of;
        if (target >= 0) {
            double want = e.gap_to >= 0 ? e.gap : e.overshoot;
            size_t nend = 0;
            for (size_t k = 0; k < fm_mesh_nvertices(m); k++) {
                const double *p = fm_mesh_vertices(m) + 3 * k;
                double cs;
                fm_synth_closest(s, i, p, NULL, &cs, NULL, NULL);
                if (cs > 1e-3)
                    continue;
                nend++;
                CHECK_NEAR(fm_synth_distance(s, (size_t)target, p), want, 1e-3);
            }
            CHECK(nend >= 7);
        }
        fm_tsurf_free_all(objs, nobj);
    }
    free(json);
    fm_synth_destroy(s);
}

FM_TEST_MAIN(FM_CASE(test_determinism), FM_CASE(test_options), FM_CASE(test_layout),
             FM_CASE(test_vertices_on_surface), FM_CASE(test_distance_offsets),
             FM_CASE(test_distance_clamped), FM_CASE(test_relations), FM_CASE(test_separation),
             FM_CASE(test_write_read_repair))
