/* TSurf reader and writer: unit cases on small files and buffers. */
#include <stdint.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fm_atomic.h"
#include "fm_test.h"
#include "fm_tsurf.h"
#include "tsurf_idmap.h"
#include "tsurf_lex.h"
#include "test_tsurf_common.h"

#define DATA FM_TEST_DATA "/ts/"

static fm_tsurf **read_ok(const char *path, size_t *n)
{
    fm_tsurf **objs = NULL;
    fm_error err;
    fm_error_clear(&err);
    fm_status s = fm_tsurf_read_file(path, &objs, n, &err);
    if (s != FM_OK)
        fprintf(stderr, "read failed: %s\n", err.message);
    CHECK_EQ(s, FM_OK);
    return objs;
}

static fm_tsurf **read_str(const char *text, size_t *n)
{
    fm_tsurf **objs = NULL;
    fm_error err;
    fm_error_clear(&err);
    fm_status s = fm_tsurf_read_buffer("mem", text, strlen(text), &objs, n, &err);
    if (s != FM_OK)
        fprintf(stderr, "read failed: %s\n", err.message);
    CHECK_EQ(s, FM_OK);
    return objs;
}

static void tmp_path(char *buf, size_t n, const char *name)
{
    fm_error err;
    CHECK_EQ(fm_mkdir_p(FM_TMP_DIR, &err), FM_OK);
    snprintf(buf, n, "%s/%s", FM_TMP_DIR, name);
}

static void test_simple(void)
{
    size_t n = 0;
    fm_tsurf **o = read_ok(DATA "simple.ts", &n);
    CHECK_EQ(n, 1);
    if (!o)
        return;
    const fm_mesh *m = fm_tsurf_mesh(o[0]);
    CHECK_EQ(fm_mesh_nvertices(m), 4);
    CHECK_EQ(fm_mesh_ntriangles(m), 2);
    CHECK_EQ(fm_tsurf_nparts(o[0]), 1);
    CHECK_STR(fm_tsurf_name(o[0]), "simple_fault");
    CHECK(fm_mesh_vertices(m)[0] == 521258.67969);
    CHECK(fm_mesh_vertices(m)[11] == 1263.45557);
    const int32_t *t = fm_mesh_triangles(m);
    CHECK(t[0] == 0 && t[1] == 1 && t[2] == 2 && t[3] == 1 && t[4] == 3 && t[5] == 2);
    CHECK_EQ(fm_tsurf_nheader(o[0]), 3);
    CHECK_STR(fm_tsurf_header_key(o[0], 2), "*solid*color");
    CHECK_STR(fm_tsurf_header_value(o[0], 2), "0.566786 0.825007 0.823164 1");
    CHECK_STR(fm_tsurf_header_get(o[0], "*visible"), "true");
    CHECK(fm_tsurf_header_get(o[0], "visible") == NULL);
    fm_tsurf_crs crs;
    fm_tsurf_get_crs(o[0], &crs);
    CHECK_STR(crs.name, "Default");
    CHECK_STR(crs.axis_unit, "\"m\" \"m\" \"m\"");
    CHECK_STR(crs.projection, "");
    CHECK_EQ(crs.z_positive_depth, 0);
    CHECK(fm_tsurf_atom_targets(o[0]) == NULL);
    CHECK(fm_tsurf_prop_values(o[0]) == NULL);
    CHECK_EQ(fm_tsurf_vertex_ids(o[0])[3], 4);
    fm_tsurf_free_all(o, n);
}

/* The same object with LF, CRLF, CR-only and mixed line ends. */
static void test_line_endings(void)
{
    const char *lf = "GOCAD TSurf 1\nHEADER {\nname:le\n}\nTFACE\nVRTX 1 0 0 0\n"
                     "VRTX 2 1 0 0\nVRTX 3 0 1 0\nTRGL 1 2 3\nEND\n";
    char crlf[512], cr[512], mixed[512];
    size_t a = 0, b = 0, c = 0;
    for (const char *p = lf; *p; p++) {
        if (*p == '\n') {
            crlf[a++] = '\r';
            crlf[a++] = '\n';
            cr[b++] = '\r';
            /* one stray CRLF line, as in two CFM files */
            if (p > lf && p[-1] == 'E' && p[-2] == 'C') {
                mixed[c++] = '\r';
            }
            mixed[c++] = '\n';
        } else {
            crlf[a++] = cr[b++] = mixed[c++] = *p;
        }
    }
    crlf[a] = cr[b] = mixed[c] = '\0';
    const char *texts[] = {lf, crlf, cr, mixed};
    size_t n0 = 0;
    fm_tsurf **ref = read_str(lf, &n0);
    CHECK_EQ(n0, 1);
    for (int i = 1; i < 4 && ref; i++) {
        size_t n = 0;
        fm_tsurf **o = read_str(texts[i], &n);
        CHECK_EQ(n, 1);
        if (o)
            CHECK(same_object(ref[0], o[0]));
        fm_tsurf_free_all(o, n);
    }
    /* Line numbers in messages count CR and CRLF as one break. */
    fm_tsurf **o;
    size_t n;
    fm_error err;
    const char *bad = "GOCAD TSurf 1\r\nTFACE\r\nVRTX 1 0 0 0\rTRGL 1 2 3\r\nEND\r\n";
    CHECK(fm_tsurf_read_buffer("x", bad, strlen(bad), &o, &n, &err) != FM_OK);
    CHECK_STR(err.message, "x:4: TRGL names unknown vertex 2");
    fm_tsurf_free_all(ref, n0);
}

static void test_props_atoms_parts(void)
{
    size_t n = 0;
    fm_tsurf **o = read_ok(DATA "parts_atoms_props.ts", &n);
    CHECK_EQ(n, 1);
    if (!o)
        return;
    fm_tsurf *ts = o[0];
    const fm_mesh *m = fm_tsurf_mesh(ts);
    CHECK_EQ(fm_mesh_nvertices(m), 7);
    CHECK_EQ(fm_mesh_ntriangles(m), 3);
    CHECK_EQ(fm_tsurf_nparts(ts), 2);
    const int32_t *tag = fm_mesh_tags(m);
    CHECK(tag[0] == 0 && tag[1] == 0 && tag[2] == 1);
    CHECK_EQ(fm_tsurf_nprops(ts), 2);
    CHECK_STR(fm_tsurf_prop_name(ts, 0), "slip");
    CHECK_STR(fm_tsurf_prop_name(ts, 1), "rake");
    const double *pv = fm_tsurf_prop_values(ts);
    CHECK(pv != NULL);
    if (pv) {
        CHECK(pv[0] == 1.5 && pv[1] == 90);
        CHECK(pv[2] == 2.5 && pv[3] == 91);
        CHECK(pv[4] == 3.5 && pv[5] == 92);
        CHECK(pv[6] == -99999 && pv[7] == -1); /* VRTX: NO_DATA_VALUES */
        CHECK(pv[8] == 2.5 && pv[9] == 91);    /* ATOM copies its target */
        CHECK(pv[10] == -99999 && pv[11] == -1);
        CHECK(pv[12] == 4 && pv[13] == 93);
    }
    const int32_t *at = fm_tsurf_atom_targets(ts);
    CHECK(at != NULL);
    if (at) {
        CHECK(at[0] == -1 && at[3] == -1 && at[6] == -1);
        CHECK_EQ(at[4], 1);
        CHECK_EQ(at[5], 3);
    }
    const double *x = fm_mesh_vertices(m);
    CHECK(x[12] == 1000 && x[13] == 0 && x[14] == 0);
    CHECK(x[15] == 1000 && x[16] == 1000 && x[17] == -250);
    CHECK(x[8] == -500.5);
    const int32_t *t = fm_mesh_triangles(m);
    CHECK(t[6] == 4 && t[7] == 6 && t[8] == 5);
    CHECK_EQ(fm_tsurf_vertex_ids(ts)[6], 70);
    CHECK_EQ(fm_tsurf_nbstones(ts), 2);
    CHECK(fm_tsurf_bstones(ts)[0] == 0 && fm_tsurf_bstones(ts)[1] == 6);
    CHECK_EQ(fm_tsurf_nborders(ts), 2);
    const int32_t *bd = fm_tsurf_borders(ts);
    CHECK(bd[0] == 1 && bd[1] == 0 && bd[2] == 1 && bd[3] == 2 && bd[4] == 6 && bd[5] == 4);
    CHECK_EQ(fm_tsurf_nskipped(ts), 1); /* SUBVSET */
    fm_tsurf_crs crs;
    fm_tsurf_get_crs(ts, &crs);
    CHECK_STR(crs.name, "utm11");
    CHECK_STR(crs.projection, "Universal_Transverse_Mercator");
    CHECK_STR(crs.datum, "NAD27");
    CHECK_EQ(fm_tsurf_nheader(ts), 3);
    CHECK_STR(fm_tsurf_header_get(ts, "*solid*color"), "1 0 0 1");
    fm_tsurf_free_all(o, n);
}

static void test_sparse_ids(void)
{
    /* Dense at first, then out of order: the id map changes mode midway. */
    const char *text = "GOCAD TSurf 1\nTFACE\nVRTX 5 0 0 0\nVRTX 6 1 0 0\nVRTX 7 2 0 0\n"
                       "VRTX 3 0 1 0\nVRTX 9223372036854775807 1 1 0\nVRTX 100 2 1 0\n"
                       "TRGL 100 9223372036854775807 7\nTRGL 3 5 6\nTRGL 6 7 3\nEND\n";
    size_t n = 0;
    fm_tsurf **o = read_str(text, &n);
    if (!o)
        return;
    const int32_t *t = fm_mesh_triangles(fm_tsurf_mesh(o[0]));
    CHECK(t[0] == 5 && t[1] == 4 && t[2] == 2);
    CHECK(t[3] == 3 && t[4] == 0 && t[5] == 1);
    CHECK(t[6] == 1 && t[7] == 2 && t[8] == 3);
    CHECK_EQ(fm_tsurf_vertex_ids(o[0])[4], INT64_MAX);
    fm_tsurf_free_all(o, n);

    /* Many random ids through the hash map. */
    fm_idmap m;
    fm_idmap_init(&m);
    uint64_t s = 12345;
    int64_t keys[5000];
    for (int i = 0; i < 5000; i++) {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        keys[i] = (int64_t)(s >> 2);
        CHECK_EQ(fm_idmap_add(&m, keys[i]), 0);
    }
    CHECK_EQ(fm_idmap_add(&m, keys[1234]), 1);
    for (int i = 0; i < 5000; i++)
        CHECK_EQ(fm_idmap_find(&m, keys[i]), i);
    CHECK_EQ(fm_idmap_find(&m, 7), -1);
    fm_idmap_free(&m);
    /* Dense mode finds duplicates and ids below the base. */
    fm_idmap_init(&m);
    CHECK_EQ(fm_idmap_add(&m, 10), 0);
    CHECK_EQ(fm_idmap_add(&m, 11), 0);
    CHECK_EQ(fm_idmap_add(&m, 10), 1);
    CHECK_EQ(fm_idmap_find(&m, 9), -1);
    CHECK_EQ(fm_idmap_find(&m, 11), 1);
    CHECK_EQ(fm_idmap_add(&m, 2), 0);
    CHECK_EQ(fm_idmap_find(&m, 2), 2);
    CHECK_EQ(fm_idmap_find(&m, 11), 1);
    fm_idmap_free(&m);
}

static void test_two_objects_scientific(void)
{
    size_t n = 0;
    fm_tsurf **o = read_ok(DATA "two_objects.ts", &n);
    CHECK_EQ(n, 2);
    if (!o || n != 2)
        return;
    CHECK_STR(fm_tsurf_name(o[0]), "first");
    CHECK_STR(fm_tsurf_name(o[1]), "second");
    const double *x = fm_mesh_vertices(fm_tsurf_mesh(o[0]));
    CHECK(x[0] == 1500 && x[1] == -0.025 && x[2] == 100);
    CHECK(x[3] == 0.5 && x[4] == 5 && x[5] == 7);
    CHECK(x[6] == 1.0000000000000002 && x[6] != 1.0 && x[7] == 0.1);
    CHECK(x[8] == 0 && signbit(x[8]));
    CHECK_EQ(fm_mesh_ntriangles(fm_tsurf_mesh(o[1])), 2);
    /* ids are per object */
    CHECK_EQ(fm_tsurf_vertex_ids(o[1])[0], 1);
    fm_tsurf_free_all(o, n);
}

static void test_header_forms(void)
{
    const char *text = "GOCAD TSurf 1   \nHEADER {name:one line}\n"
                       "PROPERTY_CLASS_HEADER X {\nkind:X\n}\nUNKNOWN_HEAD stuff\n"
                       "TFACE\nVRTX 1 0 0 0\nVRTX 2 1 0 0\nVRTX 3 0 1 0\n"
                       "MYSTERY 1 2\nTRGL 1 2 3\nEND\n";
    size_t n = 0;
    fm_tsurf **o = read_str(text, &n);
    if (!o)
        return;
    CHECK_STR(fm_tsurf_name(o[0]), "one line");
    CHECK_EQ(fm_tsurf_nheader(o[0]), 1);
    CHECK_EQ(fm_tsurf_nskipped(o[0]), 1);
    fm_tsurf_free_all(o, n);

    const char *t2 = "GOCAD TSurf 1\nHEADER {\n  *solid*color: 1 0 0 1 \n"
                     "name:spaced}\nTFACE\nVRTX 1 0 0 0\nVRTX 2 1 0 0\nVRTX 3 0 1 0\n"
                     "TRGL 1 2 3\nEND\n";
    o = read_str(t2, &n);
    if (!o)
        return;
    CHECK_EQ(fm_tsurf_nheader(o[0]), 2);
    CHECK_STR(fm_tsurf_header_get(o[0], "*solid*color"), "1 0 0 1");
    CHECK_STR(fm_tsurf_name(o[0]), "spaced");
    fm_tsurf_free_all(o, n);
}

static void test_depth(void)
{
    size_t n = 0;
    fm_tsurf **o = read_ok(DATA "depth.ts", &n);
    if (!o)
        return;
    const double *x = fm_mesh_vertices(fm_tsurf_mesh(o[0]));
    CHECK(x[2] == -100 && x[5] == -200.5 && x[8] == 5);
    fm_tsurf_crs crs;
    fm_tsurf_get_crs(o[0], &crs);
    CHECK_EQ(crs.z_positive_depth, 1);
    CHECK_STR(fm_tsurf_name(o[0]), "deep");
    /* Written as elevation: the z values survive, the flag does not. */
    char path[512];
    tmp_path(path, sizeof path, "depth_rt.ts");
    fm_error err;
    CHECK_EQ(fm_tsurf_write_file(path, o, n, &err), FM_OK);
    size_t n2 = 0;
    fm_tsurf **o2 = read_ok(path, &n2);
    if (o2) {
        fm_tsurf_get_crs(o2[0], &crs);
        CHECK_EQ(crs.z_positive_depth, 0);
        CHECK(same_object(o[0], o2[0]));
    }
    fm_tsurf_free_all(o2, n2);
    fm_tsurf_free_all(o, n);
}

static void round_trip_file(const char *src, const char *tmpname)
{
    size_t n = 0, n2 = 0;
    fm_tsurf **o = read_ok(src, &n);
    if (!o)
        return;
    char path[512];
    tmp_path(path, sizeof path, tmpname);
    fm_error err;
    CHECK_EQ(fm_tsurf_write_file(path, o, n, &err), FM_OK);
    fm_tsurf **o2 = read_ok(path, &n2);
    CHECK_EQ(n2, n);
    for (size_t i = 0; o2 && i < n && i < n2; i++)
        CHECK(same_object(o[i], o2[i]));
    /* Writing what was read back gives the same bytes. */
    char path2[512];
    tmp_path(path2, sizeof path2, "again.ts");
    if (o2) {
        CHECK_EQ(fm_tsurf_write_file(path2, o2, n2, &err), FM_OK);
        FILE *a = fopen(path, "rb"), *b = fopen(path2, "rb");
        CHECK(a && b);
        if (a && b) {
            int ca, cb;
            do {
                ca = fgetc(a);
                cb = fgetc(b);
            } while (ca == cb && ca != EOF);
            CHECK(ca == cb);
        }
        if (a)
            fclose(a);
        if (b)
            fclose(b);
    }
    fm_tsurf_free_all(o2, n2);
    fm_tsurf_free_all(o, n);
}

static void test_round_trip(void)
{
    round_trip_file(DATA "simple.ts", "simple_rt.ts");
    round_trip_file(DATA "parts_atoms_props.ts", "parts_rt.ts");
    round_trip_file(DATA "two_objects.ts", "two_rt.ts");
    /* CFM-style values keep their text. */
    size_t n = 0;
    fm_tsurf **o = read_ok(DATA "simple.ts", &n);
    char path[512];
    tmp_path(path, sizeof path, "simple_text.ts");
    fm_error err;
    if (o)
        CHECK_EQ(fm_tsurf_write_file(path, o, n, &err), FM_OK);
    FILE *f = fopen(path, "rb");
    char buf[4096] = {0};
    if (f) {
        CHECK(fread(buf, 1, sizeof buf - 1, f) > 0);
        fclose(f);
    }
    CHECK(strstr(buf, "VRTX 1 521258.67969 3777346.25 -2268.26294\n") != NULL);
    CHECK(strstr(buf, "TFACE\n") != NULL && strstr(buf, "ZPOSITIVE Elevation\n") != NULL);
    CHECK(strstr(buf, "*solid*color:0.566786 0.825007 0.823164 1\n") != NULL);
    fm_tsurf_free_all(o, n);
}

/* A vertex used by two parts: written as VRTX in the first and ATOM in the
 * second; reading back gives an atom vertex at the same place. */
static void test_shared_vertex_writes_atom(void)
{
    fm_tsurf *ts = fm_tsurf_create("built");
    CHECK(ts != NULL);
    if (!ts)
        return;
    fm_mesh *m = fm_tsurf_mesh_mut(ts);
    int p0 = fm_tsurf_add_part(ts), p1 = fm_tsurf_add_part(ts);
    CHECK(p0 == 0 && p1 == 1);
    fm_mesh_add_vertex(m, 0, 0, 0);
    fm_mesh_add_vertex(m, 1, 0, 0);
    fm_mesh_add_vertex(m, 0, 1, 0);
    fm_mesh_add_vertex(m, 1, 1, 0.1);
    fm_mesh_add_triangle(m, 0, 1, 2, p0);
    fm_mesh_add_triangle(m, 1, 3, 2, p1);
    char path[512];
    tmp_path(path, sizeof path, "shared.ts");
    fm_error err;
    CHECK_EQ(fm_tsurf_write_file(path, &ts, 1, &err), FM_OK);
    size_t n = 0;
    fm_tsurf **o = read_ok(path, &n);
    if (o) {
        const fm_mesh *r = fm_tsurf_mesh(o[0]);
        CHECK_EQ(fm_tsurf_nparts(o[0]), 2);
        CHECK_EQ(fm_mesh_nvertices(r), 6); /* 4 + two atoms (vertices 1, 2) */
        const int32_t *at = fm_tsurf_atom_targets(o[0]);
        CHECK(at != NULL);
        const int32_t *t = fm_mesh_triangles(r);
        const double *x = fm_mesh_vertices(r), *x0 = fm_mesh_vertices(m);
        /* Same geometry per triangle corner. */
        for (int c = 0; c < 6; c++)
            for (int k = 0; k < 3; k++)
                CHECK(x[3 * t[c] + k] == x0[3 * fm_mesh_triangles(m)[c] + k]);
        if (at) {
            CHECK(at[t[3]] == 1 && at[t[5]] == 2 && at[t[4]] == -1);
        }
        CHECK_STR(fm_tsurf_name(o[0]), "built");
        fm_tsurf_crs crs;
        fm_tsurf_get_crs(o[0], &crs);
        CHECK_STR(crs.name, "Default");
    }
    fm_tsurf_free_all(o, n);
    fm_tsurf_destroy(ts);
}

static void test_write_failures(void)
{
    fm_tsurf *ts = fm_tsurf_create("bad");
    if (!ts)
        return;
    fm_mesh *m = fm_tsurf_mesh_mut(ts);
    fm_tsurf_add_part(ts);
    fm_mesh_add_vertex(m, 0, 0, 0);
    fm_mesh_add_vertex(m, 1, 0, 0);
    fm_mesh_add_vertex(m, 0, NAN, 0);
    fm_mesh_add_triangle(m, 0, 1, 2, 0);
    char path[512];
    tmp_path(path, sizeof path, "nan_out.ts");
    unlink(path);
    fm_error err;
    CHECK_EQ(fm_tsurf_write_file(path, &ts, 1, &err), FM_ERR_NUMERIC);
    CHECK(access(path, F_OK) != 0); /* nothing left behind */
    fm_mesh_vertices_mut(m)[7] = 1;
    CHECK_EQ(fm_tsurf_write_file(FM_TMP_DIR "/no/such/dir/x.ts", &ts, 1, &err), FM_ERR_IO);
    CHECK_EQ(fm_tsurf_write_file(path, &ts, 1, &err), FM_OK);
    CHECK(access(path, F_OK) == 0);
    /* Properties must cover every vertex. */
    const char *names[] = {"slip"};
    double vals[3] = {1, 2, 3};
    CHECK_EQ(fm_tsurf_set_props(ts, 1, names, vals), FM_OK);
    fm_mesh_add_vertex(m, 5, 5, 5);
    CHECK_EQ(fm_tsurf_write_file(path, &ts, 1, &err), FM_ERR_INVALID);
    fm_tsurf_clear_vertex_data(ts);
    CHECK_EQ(fm_tsurf_write_file(path, &ts, 1, &err), FM_OK);
    CHECK_EQ(fm_tsurf_set_header(ts, "bad:key", "x"), FM_ERR_INVALID);
    CHECK_EQ(fm_tsurf_set_header(ts, "k", "line\nbreak"), FM_ERR_INVALID);
    int64_t dup[4] = {1, 2, 2, 3};
    CHECK_EQ(fm_tsurf_set_vertex_ids(ts, dup, 4), FM_ERR_INVALID);
    dup[2] = 9;
    CHECK_EQ(fm_tsurf_set_vertex_ids(ts, dup, 4), FM_OK);
    CHECK_EQ(fm_tsurf_vertex_ids(ts)[2], 9);
    fm_tsurf_destroy(ts);
}

/* The number parser against strtod, and the formatter's round trip. */
static void test_numbers(void)
{
    static const char *cases[] = {
        "0", "-0", "1", "521258.67969", "3777346.25000", "-2268.26294", "1e23", "8.5e-323",
        "2.2250738585072014e-308", "2.2250738585072011e-308", "9007199254740993",
        "9007199254740992.5", "1.7976931348623157e308", "4.9e-324", "123456789012345678901234",
        "0.000000000000000000000000000001", "1.00000000000000011102230246251565404236316680908203125",
        "1.000000000000000111022302462515654042363166809082031251", "7.", ".7", "+3e+0",
        "0.1", "0.3", "1e22", "1e-22", "12345678901234567890e-10",
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const char *s = cases[i];
        double x = 0;
        const char *e = fm_lex_double(s, s + strlen(s), &x);
        CHECK(e == s + strlen(s));
        double y = strtod(s, NULL);
        if (memcmp(&x, &y, sizeof x) != 0)
            fprintf(stderr, "mismatch on %s: %.17g vs %.17g\n", s, x, y);
        CHECK(memcmp(&x, &y, sizeof x) == 0);
    }
    static const char *bad[] = {"", "-", ".", "1e", "1e+", "nan", "inf", "0x10", "1,5", "1.2.3",
                                "--1", "1e5x"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        double x;
        CHECK(fm_lex_double(bad[i], bad[i] + strlen(bad[i]), &x) == NULL);
    }
    double x;
    const char *big = "1e400";
    CHECK(fm_lex_double(big, big + 5, &x) != NULL && isinf(x));
    /* Random decimals of CFM shape and random bit patterns. */
    uint64_t s = 99;
    char buf[64];
    for (int i = 0; i < 200000; i++) {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        int len;
        if (i & 1)
            len = snprintf(buf, sizeof buf, "%llu.%05llu", (unsigned long long)(s >> 44),
                           (unsigned long long)((s >> 8) % 100000));
        else
            len = snprintf(buf, sizeof buf, "%llue%d", (unsigned long long)(s >> (s & 31)),
                           (int)((s >> 40) % 60) - 40);
        double a = 0, b = strtod(buf, NULL);
        fm_lex_double(buf, buf + len, &a);
        if (a != b) {
            fprintf(stderr, "mismatch on %s\n", buf);
            CHECK(a == b);
            break;
        }
        double r;
        memcpy(&r, &s, sizeof r);
        if (!isfinite(r))
            continue;
        char out[40];
        size_t n = fm_format_double(out, r);
        double back = 0;
        CHECK(fm_lex_double(out, out + n, &back) == out + n);
        if (memcmp(&back, &r, sizeof r) != 0) {
            fprintf(stderr, "format round trip failed: %.17g -> %s\n", r, out);
            CHECK(0);
            break;
        }
    }
    char out[40];
    fm_format_double(out, 521258.67969);
    CHECK_STR(out, "521258.67969");
    fm_format_double(out, -0.0);
    CHECK_STR(out, "-0");
    fm_format_double(out, 0.1);
    CHECK_STR(out, "0.1");
    fm_format_double(out, 1e300);
    CHECK_STR(out, "1e+300");
    fm_format_double(out, -2544.9668);
    CHECK_STR(out, "-2544.9668");
    fm_format_double(out, 0.1 + 0.2);
    CHECK_STR(out, "0.30000000000000004");
    int64_t id;
    const char *ids = "9223372036854775808";
    CHECK(fm_lex_int64(ids, ids + strlen(ids), &id) == NULL);
    CHECK(fm_lex_int64(ids, ids + strlen(ids) - 1, &id) != NULL && id == 922337203685477580);
}

FM_TEST_MAIN(FM_CASE(test_simple), FM_CASE(test_line_endings), FM_CASE(test_props_atoms_parts),
             FM_CASE(test_sparse_ids), FM_CASE(test_two_objects_scientific),
             FM_CASE(test_header_forms), FM_CASE(test_depth), FM_CASE(test_round_trip),
             FM_CASE(test_shared_vertex_writes_atom), FM_CASE(test_write_failures),
             FM_CASE(test_numbers))
