/* Fitted models on disk (fm_model_save / fm_model_load, model_store.c)
 * and the fit cache (fm_model_cache.h): a model read back is the one
 * written in every field the accessors show, saves again to the same
 * bytes (so no stored field is lost) and meshes to the same mesh bit for
 * bit; a truncated, extended or damaged file, one of another format
 * version or one stored under another key is rejected; the key changes
 * with every option that reaches the fit and with any bit of the input,
 * and with nothing else. Models: faults of the synthetic system (height
 * fields, several sheets) and a ring cut into disks (parametric, cuts). */
#include <math.h>
#include <stdint.h>
#include <string.h>
#include <sys/stat.h>

#include "fm_atomic.h"
#include "fm_fit.h"
#include "fm_model.h"
#include "fm_model_cache.h"
#include "fm_remesh.h"
#include "fm_repair.h"
#include "fm_sha256.h"
#include "fm_synth.h"
#include "fm_test.h"

#define TMP FM_TMP_DIR "/model_store"
#define FM_PI 3.14159265358979323846

/* A vertical cylindrical band: one sheet with two outer rims, which the
 * model cuts into disks (as in test_model_split.c). */
static fm_mesh *ring_mesh(void)
{
    enum { NT = 120, NZ = 10 };
    const double R = 10000.0, H = 5000.0;
    fm_mesh *m = fm_mesh_create();
    for (int j = 0; m && j <= NZ; j++)
        for (int i = 0; i < NT; i++) {
            double t = 2 * FM_PI * i / NT, z = -H * j / NZ;
            double r = R + 300.0 * sin(2 * t) * (1.0 + z / H);
            fm_mesh_add_vertex(m, 400000.0 + r * cos(t), 3700000.0 + r * sin(t), z);
        }
    for (int j = 0; m && j < NZ; j++)
        for (int i = 0; i < NT; i++) {
            int32_t a = j * NT + i, b = j * NT + (i + 1) % NT;
            fm_mesh_add_triangle(m, a, a + NT, b, 0);
            fm_mesh_add_triangle(m, b, a + NT, b + NT, 0);
        }
    return m;
}

static fm_model *fit(const char *name, const fm_mesh *in, const fm_model_options *opt)
{
    fm_surface *s = NULL;
    fm_model *m = NULL;
    fm_error err;
    fm_error_clear(&err);
    if (fm_repair(in, NULL, &s, &err) == FM_OK)
        fm_model_build(name, s, opt, &m, &err);
    fm_surface_destroy(s);
    if (!m)
        fprintf(stderr, "%s: %s\n", name, err.message);
    return m;
}

/* Bitwise equality of doubles (NaN and -0 included). */
static int same_doubles(const double *a, const double *b, size_t n)
{
    return n == 0 || (a && b && memcmp(a, b, n * sizeof *a) == 0);
}

#define SAME(field) CHECK(memcmp(&a->field, &b->field, sizeof a->field) == 0)

static void same_frame(const fm_fit_frame *a, const fm_fit_frame *b)
{
    SAME(origin);
    SAME(u);
    SAME(v);
    SAME(w);
    SAME(min_dot);
    SAME(optimum_dot);
    SAME(mean_dot);
    SAME(folded_area);
    SAME(area);
    SAME(dip_degrees);
    SAME(projectable);
    SAME(strike_axes);
}

static void same_fit_stats(const fm_fit_stats *a, const fm_fit_stats *b)
{
    SAME(kind);
    SAME(passes);
    SAME(overlap);
    SAME(lscm_flipped);
    SAME(convex_map);
    SAME(vertices);
    SAME(triangles);
    SAME(samples);
    SAME(degree);
    SAME(spans_u);
    SAME(spans_v);
    SAME(control_u);
    SAME(control_v);
    SAME(knot_spacing);
    SAME(edge_median);
    SAME(smoothing);
    SAME(rms_w);
    SAME(max_w);
    SAME(rms_dist);
    SAME(max_dist);
    SAME(projection_failures);
    SAME(max_border_offset);
    SAME(stacked);
    SAME(time_frame);
    SAME(time_param);
    SAME(time_assemble);
    SAME(time_solve);
    SAME(time_stats);
    SAME(time_total);
}

static void same_trim_stats(const fm_trim_stats *a, const fm_trim_stats *b)
{
    SAME(points);
    SAME(distinct_points);
    SAME(spacing);
    SAME(corner_window);
    SAME(knot_spacing);
    SAME(corners);
    SAME(pieces);
    SAME(spans);
    SAME(control_points);
    SAME(refinements);
    SAME(max_dev);
    SAME(rms_dev);
    SAME(max_curve_dev);
    SAME(max_systematic);
    SAME(within_tolerance);
    SAME(area);
    SAME(polygon_area);
}

static void same_report(const fm_sheet_report *a, const fm_sheet_report *b)
{
    SAME(vertices);
    SAME(triangles);
    SAME(loops);
    SAME(holes);
    SAME(corners);
    SAME(trim_pieces);
    SAME(to_surface_rms);
    SAME(to_surface_max);
    SAME(from_trimmed_rms);
    SAME(from_trimmed_max);
    SAME(outline_max);
    SAME(outline_rms);
    SAME(samples);
    SAME(repair_sheet);
    SAME(time);
}

static void same_mesh(const fm_mesh *a, const fm_mesh *b)
{
    CHECK((a == NULL) == (b == NULL));
    if (!a || !b)
        return;
    size_t nv = fm_mesh_nvertices(a), nt = fm_mesh_ntriangles(a);
    CHECK_EQ(nv, fm_mesh_nvertices(b));
    CHECK_EQ(nt, fm_mesh_ntriangles(b));
    if (nv != fm_mesh_nvertices(b) || nt != fm_mesh_ntriangles(b))
        return;
    CHECK(same_doubles(fm_mesh_vertices(a), fm_mesh_vertices(b), 3 * nv));
    CHECK(nt == 0 || !memcmp(fm_mesh_triangles(a), fm_mesh_triangles(b), 3 * nt * sizeof(int32_t)));
    CHECK(nt == 0 || !memcmp(fm_mesh_tags(a), fm_mesh_tags(b), nt * sizeof(int32_t)));
}

static void same_surface(const fm_fit_surface *a, const fm_fit_surface *b)
{
    CHECK_EQ(fm_fit_surface_kind(a), fm_fit_surface_kind(b));
    CHECK_EQ(fm_fit_surface_degree(a), fm_fit_surface_degree(b));
    same_frame(fm_fit_surface_frame(a), fm_fit_surface_frame(b));
    same_fit_stats(fm_fit_surface_stats(a), fm_fit_surface_stats(b));
    double da[4], db[4];
    fm_fit_surface_domain(a, da);
    fm_fit_surface_domain(b, db);
    CHECK(same_doubles(da, db, 4));
    for (int dir = 0; dir < 2; dir++) {
        size_t na, nb;
        const double *ka = fm_fit_surface_knots(a, dir, &na), *kb = fm_fit_surface_knots(b, dir, &nb);
        CHECK_EQ(na, nb);
        CHECK(na == nb && same_doubles(ka, kb, na));
    }
    size_t nua, nva, nub, nvb;
    const double *ha = fm_fit_surface_heights(a, &nua, &nva);
    const double *hb = fm_fit_surface_heights(b, &nub, &nvb);
    CHECK(nua == nub && nva == nvb && same_doubles(ha, hb, nua * nva));
    double *ca = malloc(3 * nua * nva * sizeof *ca), *cb = malloc(3 * nua * nva * sizeof *cb);
    if (ca && cb && nua == nub && nva == nvb) {
        fm_fit_surface_control_points(a, ca);
        fm_fit_surface_control_points(b, cb);
        CHECK(same_doubles(ca, cb, 3 * nua * nva));
    }
    free(ca);
    free(cb);
    /* projections start from the stored span centres (parametric) */
    for (int i = 0; i <= 4; i++)
        for (int j = 0; j <= 4; j++) {
            double u = da[0] + (da[1] - da[0]) * i / 4, v = da[2] + (da[3] - da[2]) * j / 4;
            double p[3], pa[3], pb[3], uva[2], uvb[2], sa = 0, sb = 0;
            fm_fit_surface_eval(a, u, v, p, NULL, NULL);
            p[0] += 37.0;
            p[2] -= 11.0;
            fm_status ra = fm_fit_project(a, p, uva, pa, &sa);
            fm_status rb = fm_fit_project(b, p, uvb, pb, &sb);
            CHECK(ra == rb && same_doubles(uva, uvb, 2) && same_doubles(pa, pb, 3) &&
                  same_doubles(&sa, &sb, 1));
        }
}

static void same_loop(const fm_trim_loop *a, const fm_trim_loop *b)
{
    same_trim_stats(fm_trim_loop_stats(a), fm_trim_loop_stats(b));
    size_t na, nb;
    const size_t *ca = fm_trim_loop_corners(a, &na), *cb = fm_trim_loop_corners(b, &nb);
    CHECK(na == nb && (na == 0 || !memcmp(ca, cb, na * sizeof *ca)));
    CHECK_EQ(fm_trim_loop_npieces(a), fm_trim_loop_npieces(b));
    for (size_t i = 0; i < fm_trim_loop_npieces(a) && i < fm_trim_loop_npieces(b); i++) {
        fm_trim_piece pa, pb;
        fm_trim_loop_piece(a, i, &pa);
        fm_trim_loop_piece(b, i, &pb);
        CHECK(pa.degree == pb.degree && pa.periodic == pb.periodic && pa.nknots == pb.nknots &&
              pa.ncontrol == pb.ncontrol && pa.first == pb.first && pa.last == pb.last);
        CHECK(same_doubles(pa.knots, pb.knots, pa.nknots));
        CHECK(same_doubles(pa.control, pb.control, 2 * pa.ncontrol));
        CHECK(same_doubles(&pa.t0, &pb.t0, 1) && same_doubles(&pa.t1, &pb.t1, 1));
    }
    double aa = fm_trim_loop_area(a), ab = fm_trim_loop_area(b);
    CHECK(same_doubles(&aa, &ab, 1));
}

static void same_model(const fm_model *a, const fm_model *b)
{
    CHECK_EQ(fm_model_nsheets(a), fm_model_nsheets(b));
    CHECK_EQ(fm_model_ncuts(a), fm_model_ncuts(b));
    if (fm_model_nsheets(a) != fm_model_nsheets(b) || fm_model_ncuts(a) != fm_model_ncuts(b))
        return;
    for (size_t i = 0; i < fm_model_nsheets(a); i++) {
        same_surface(fm_model_surface(a, i), fm_model_surface(b, i));
        CHECK_EQ(fm_model_nloops(a, i), fm_model_nloops(b, i));
        for (size_t k = 0; k < fm_model_nloops(a, i) && k < fm_model_nloops(b, i); k++)
            same_loop(fm_model_loop(a, i, k), fm_model_loop(b, i, k));
        same_report(fm_model_report(a, i), fm_model_report(b, i));
        same_mesh(fm_model_samples(a, i), fm_model_samples(b, i));
        const double *sa = fm_model_sample_distance(a, i), *sb = fm_model_sample_distance(b, i);
        CHECK((sa == NULL) == (sb == NULL));
        if (sa && sb)
            CHECK(same_doubles(sa, sb, fm_mesh_nvertices(fm_model_samples(a, i))));
    }
    for (size_t c = 0; c < fm_model_ncuts(a); c++) {
        size_t na, nb;
        long sha[2], shb[2];
        const double *pa = fm_model_cut(a, c, &na, sha), *pb = fm_model_cut(b, c, &nb, shb);
        CHECK(na == nb && sha[0] == shb[0] && sha[1] == shb[1] && same_doubles(pa, pb, 3 * na));
    }
}

/* Saves m, loads it, compares, saves the copy again (same bytes), and
 * meshes both (the same mesh). */
static void round_trip(const char *name, const fm_model *m)
{
    char p1[512], p2[512];
    snprintf(p1, sizeof p1, "%s/%s.fmm", TMP, name);
    snprintf(p2, sizeof p2, "%s/%s.again.fmm", TMP, name);
    fm_error err;
    fm_model *back = NULL;
    CHECK_EQ(fm_model_save(m, p1, &err), FM_OK);
    CHECK_EQ(fm_model_load(p1, &back, &err), FM_OK);
    CHECK(back != NULL);
    if (!back)
        return;
    same_model(m, back);
    CHECK_EQ(fm_model_save(back, p2, &err), FM_OK);
    CHECK(fm_test_same_file(p1, p2));
    fm_remesh_options ro;
    fm_remesh_options_default(&ro);
    ro.size = 1500;
    fm_mesh *ma = NULL, *mb = NULL;
    fm_remesh_stats sa, sb;
    fm_status ra = fm_remesh_model(m, &ro, &ma, &sa, &err);
    fm_status rb = fm_remesh_model(back, &ro, &mb, &sb, &err);
    CHECK_EQ(ra, rb);
    CHECK(ra != FM_OK || fm_mesh_ntriangles(ma) > 0);
    same_mesh(ma, mb);
    fm_mesh_destroy(ma);
    fm_mesh_destroy(mb);
    fm_model_destroy(back);
}

static void test_round_trip(void)
{
    CHECK_EQ(fm_mkdir_p(TMP, NULL), FM_OK);
    fm_mesh *ring = ring_mesh();
    fm_model_options mo, ro;
    fm_model_options_default(&mo);          /* samples measured */
    fm_remesh_model_options_default(&ro);   /* as remesh fits: not measured */
    fm_model *m = fit("ring", ring, &mo);
    CHECK(m && fm_model_ncuts(m) >= 2);
    if (m) {
        int parametric = 0;
        for (size_t i = 0; i < fm_model_nsheets(m); i++)
            parametric |= fm_fit_surface_kind(fm_model_surface(m, i)) == FM_FIT_PARAMETRIC;
        CHECK(parametric);
        round_trip("ring", m);
    }
    fm_model_destroy(m);
    fm_mesh_destroy(ring);

    fm_synth *sy = NULL;
    fm_error err;
    CHECK_EQ(fm_synth_create(NULL, &sy, &err), FM_OK);
    size_t multi = 0, tried = 0;
    for (size_t i = 0; sy && i < fm_synth_nfaults(sy); i++) {
        tried++;
        const char *name = fm_synth_fault_name(sy, i);
        m = fit(name, fm_synth_fault_mesh(sy, i), i % 2 ? &mo : &ro);
        CHECK(m != NULL);
        if (m) {
            multi += fm_model_nsheets(m) > 1;
            round_trip(name, m);
        }
        fm_model_destroy(m);
    }
    fm_synth_destroy(sy);
    CHECK(tried >= 10);
    CHECK(multi >= 1); /* a fault of several sheets among them */
}

static void write_bytes(const char *path, const char *buf, size_t n)
{
    FILE *fp = fopen(path, "wb");
    CHECK(fp != NULL);
    if (fp) {
        CHECK(fwrite(buf, 1, n, fp) == n);
        fclose(fp);
    }
}

static void expect_rejected(const char *path, const char *what)
{
    fm_model *m = (fm_model *)&m; /* must come back NULL */
    fm_error err;
    fm_error_clear(&err);
    fm_status st = fm_model_load(path, &m, &err);
    if (st == FM_OK || m != NULL)
        fprintf(stderr, "not rejected: %s\n", what);
    CHECK(st != FM_OK);
    CHECK(m == NULL);
    CHECK(err.message[0] != '\0');
    if (st == FM_OK)
        fm_model_destroy(m);
}

static void test_damaged_files_rejected(void)
{
    CHECK_EQ(fm_mkdir_p(TMP, NULL), FM_OK);
    fm_mesh *ring = ring_mesh();
    fm_model *m = fit("ring", ring, NULL);
    fm_mesh_destroy(ring);
    CHECK(m != NULL);
    if (!m)
        return;
    const char *good = TMP "/good.fmm", *bad = TMP "/bad.fmm";
    fm_error err;
    CHECK_EQ(fm_model_save(m, good, &err), FM_OK);
    fm_model_destroy(m);
    size_t n = 0;
    char *buf = fm_test_read_file(good, &n);
    CHECK(buf && n > 200);
    if (!buf || n <= 200)
        return;
    /* truncated anywhere */
    const size_t cuts[] = {0, 1, 7, 8, 20, 55, 56, 87, 88, n / 3, n / 2, n - 33, n - 32, n - 1};
    for (size_t k = 0; k < sizeof cuts / sizeof cuts[0]; k++) {
        write_bytes(bad, buf, cuts[k]);
        expect_rejected(bad, "truncated");
    }
    /* one byte longer */
    char *longer = malloc(n + 1);
    if (longer) {
        memcpy(longer, buf, n);
        longer[n] = 0;
        write_bytes(bad, longer, n + 1);
        expect_rejected(bad, "extended");
        free(longer);
    }
    /* one bit flipped: magic, version, reserved, key, length, payload,
     * checksum */
    const size_t at[] = {0, 7, 8, 12, 16, 47, 48, 56, 60, n / 4, n / 2, 3 * n / 4, n - 40,
                         n - 32, n - 1};
    for (size_t k = 0; k < sizeof at / sizeof at[0]; k++) {
        buf[at[k]] ^= 0x10;
        write_bytes(bad, buf, n);
        buf[at[k]] ^= 0x10;
        expect_rejected(bad, "bit flipped");
    }
    /* another format version, with its checksum made right: refused for
     * the version, not the checksum */
    char *other = malloc(n);
    if (other) {
        memcpy(other, buf, n);
        other[8] = (char)(FM_MODEL_FORMAT_VERSION + 1);
        fm_sha256_of(other, n - FM_SHA256_BYTES, (unsigned char *)other + n - FM_SHA256_BYTES);
        write_bytes(bad, other, n);
        fm_error_clear(&err);
        m = NULL;
        CHECK(fm_model_load(bad, &m, &err) == FM_ERR_PARSE && m == NULL);
        CHECK(strstr(err.message, "version") != NULL);
        free(other);
    }
    /* a text file, an empty one, a missing one */
    write_bytes(bad, "solid\n", 6);
    expect_rejected(bad, "text");
    expect_rejected(TMP "/missing.fmm", "missing");
    /* and the good one still loads */
    CHECK_EQ(fm_model_load(good, &m, &err), FM_OK);
    fm_model_destroy(m);
    free(buf);
}

static void test_cache(void)
{
    const char *dir = TMP "/cache";
    fm_error err;
    CHECK_EQ(fm_model_cache_open(dir, &err), FM_OK);
    struct stat sb;
    CHECK(stat(TMP "/cache/CACHEDIR.TAG", &sb) == 0);
    fm_mesh *ring = ring_mesh();
    unsigned char key[FM_MODEL_KEY_BYTES], other[FM_MODEL_KEY_BYTES];
    fm_model_key(ring, NULL, NULL, key);
    memcpy(other, key, sizeof other);
    other[5] ^= 1;
    char *path = fm_model_cache_path(dir, key), *opath = fm_model_cache_path(dir, other);
    remove(path);
    remove(opath);
    fm_model *m = (fm_model *)&m;
    CHECK_EQ(fm_model_cache_get(dir, key, &m, &err), FM_OK); /* none yet */
    CHECK(m == NULL);
    m = fit("ring", ring, NULL);
    CHECK(m != NULL);
    if (m)
        CHECK_EQ(fm_model_cache_put(dir, key, m, &err), FM_OK);
    fm_model *back = NULL;
    CHECK_EQ(fm_model_cache_get(dir, key, &back, &err), FM_OK);
    CHECK(back != NULL);
    if (m && back)
        same_model(m, back);
    fm_model_destroy(back);
    /* a file under another key's name is not that key's model */
    size_t n = 0;
    char *buf = fm_test_read_file(path, &n);
    CHECK(buf != NULL);
    char *slash = strrchr(opath, '/');
    *slash = '\0';
    CHECK_EQ(fm_mkdir_p(opath, NULL), FM_OK);
    *slash = '/';
    if (buf)
        write_bytes(opath, buf, n);
    back = (fm_model *)&back;
    CHECK(fm_model_cache_get(dir, other, &back, &err) != FM_OK);
    CHECK(back == NULL);
    /* a damaged entry is an error, which the caller takes as a miss */
    if (buf) {
        buf[n / 2] ^= 1;
        write_bytes(path, buf, n);
    }
    back = (fm_model *)&back;
    CHECK(fm_model_cache_get(dir, key, &back, &err) != FM_OK);
    CHECK(back == NULL);
    /* stored again, it is whole again */
    if (m)
        CHECK_EQ(fm_model_cache_put(dir, key, m, &err), FM_OK);
    CHECK_EQ(fm_model_cache_get(dir, key, &back, &err), FM_OK);
    CHECK(back != NULL);
    fm_model_destroy(back);
    free(buf);
    free(path);
    free(opath);
    fm_model_destroy(m);
    fm_mesh_destroy(ring);
}

static int same_key(const unsigned char *a, const unsigned char *b)
{
    return memcmp(a, b, FM_MODEL_KEY_BYTES) == 0;
}

/* Every option that reaches the fit changes the key; names do not. */
static void test_key(void)
{
    fm_mesh *ring = ring_mesh();
    if (!ring)
        return;
    fm_repair_options r0;
    fm_model_options m0;
    fm_repair_options_default(&r0);
    fm_model_options_default(&m0);
    unsigned char k0[FM_MODEL_KEY_BYTES], k[FM_MODEL_KEY_BYTES];
    fm_model_key(ring, &r0, &m0, k0);
    fm_model_key(ring, NULL, NULL, k);
    CHECK(same_key(k0, k)); /* NULL means the defaults */
    fm_model_key(ring, &r0, &m0, k);
    CHECK(same_key(k0, k)); /* deterministic */
    CHECK(strlen(fm_model_code_id()) == 64);

    fm_model_options mo = m0;
    mo.fit.name = "another name";
    mo.trim.name = "and another";
    fm_model_key(ring, &r0, &mo, k);
    CHECK(same_key(k0, k));

    /* each option changed alone */
    enum { NMUT = 33 };
    for (int i = 0; i < NMUT; i++) {
        fm_repair_options r = r0;
        fm_model_options o = m0;
        switch (i) {
        case 0: r.weld_tolerance = 1; break;
        case 1: r.min_fragment_triangles++; break;
        case 2: r.min_fragment_area_fraction *= 2; break;
        case 3: r.drop_fragments = !r.drop_fragments; break;
        case 4: r.split_nonmanifold = !r.split_nonmanifold; break;
        case 5: r.orient = !r.orient; break;
        case 6: o.fit.kind = FM_FIT_PARAMETRIC; break;
        case 7: o.fit.frame.direction[0] = 1; break;
        case 8: o.fit.frame.direction[2] = 1; break;
        case 9: o.fit.frame.slack_degrees += 1; break;
        case 10: o.fit.degree = 2; break;
        case 11: o.fit.extend += 1; break;
        case 12: o.fit.knot_spacing = 250; break;
        case 13: o.fit.knot_factor *= 1.5; break;
        case 14: o.fit.max_control_points++; break;
        case 15: o.fit.target_rms += 1; break;
        case 16: o.fit.target_max += 1; break;
        case 17: o.fit.max_refinements--; break;
        case 18: o.fit.smoothing = 1e6; break;
        case 19: o.fit.smoothing_wavelength *= 2; break;
        case 20: o.fit.chord_passes++; break;
        case 21: o.fit.chord_weight = 0.5; break;
        case 22: o.fit.closest_point_stats = !o.fit.closest_point_stats; break;
        case 23: o.trim.tolerance += 1; break;
        case 24: o.trim.corner_angle += 1; break;
        case 25: o.trim.corner_window = 100; break;
        case 26: o.trim.knot_spacing = 100; break;
        case 27: o.trim.knot_factor += 1; break;
        case 28: o.trim.smoothing_wavelength += 1; break;
        case 29: o.trim.max_refinements--; break;
        case 30: o.trim.max_deviation += 1; break;
        case 31: o.sample_levels++; break;
        case 32: o.measure_samples = !o.measure_samples; break;
        }
        fm_model_key(ring, &r, &o, k);
        if (same_key(k0, k))
            fprintf(stderr, "option change %d leaves the key\n", i);
        CHECK(!same_key(k0, k));
    }
    /* any bit of the input: a coordinate's last bit, a triangle, a tag */
    double *X = fm_mesh_vertices_mut(ring);
    double x = X[100];
    X[100] = nextafter(x, INFINITY);
    fm_model_key(ring, &r0, &m0, k);
    CHECK(!same_key(k0, k));
    X[100] = x;
    int32_t *T = fm_mesh_triangles_mut(ring);
    int32_t t = T[0];
    T[0] = T[1];
    T[1] = t;
    fm_model_key(ring, &r0, &m0, k);
    CHECK(!same_key(k0, k));
    T[1] = T[0];
    T[0] = t;
    fm_mesh_tags_mut(ring)[7] = 1;
    fm_model_key(ring, &r0, &m0, k);
    CHECK(!same_key(k0, k));
    fm_mesh_tags_mut(ring)[7] = 0;
    fm_model_key(ring, &r0, &m0, k);
    CHECK(same_key(k0, k));
    /* one triangle fewer */
    fm_mesh_truncate(ring, fm_mesh_nvertices(ring), fm_mesh_ntriangles(ring) - 1);
    fm_model_key(ring, &r0, &m0, k);
    CHECK(!same_key(k0, k));
    fm_mesh_destroy(ring);
}

FM_TEST_MAIN(FM_CASE(test_round_trip), FM_CASE(test_damaged_files_rejected), FM_CASE(test_cache),
             FM_CASE(test_key))
