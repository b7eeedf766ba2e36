/* Fault-set writers: structure of each format read back here, byte
 * identity, atomicity, and the sample files for tests/tools/check_faultset.py
 * (meshio and Gmsh read them independently).
 *
 * Usage: test_faultset_write            run the checks
 *        test_faultset_write --write DIR write the samples into DIR:
 *          set.vtu, set41.msh, set22.msh, tags41.msh (physical tags
 *          101, 7, 55), set.stl, set.obj, ts/<file name>.ts */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fm_atomic.h"
#include "fm_faultset_write.h"
#include "fm_names.h"
#include "fm_test.h"
#include "fm_tsurf.h"

/* ---- the sample (check_faultset.py builds the same numbers) ----
 *
 * Three vertical faults meeting on one vertical line (a Y junction):
 * fault 0 a 5 x 4 grid of vertices along x, faults 1 and 2 branch off its
 * last column (column 4), which all three share. Rows go down 1234.5 m
 * from 250.25 m above sea level.
 * Triangles are added row by row across all faults, so the tags are
 * interleaved and the MSH 4.1 writer must group them. Coordinates are
 * UTM-sized with decimals that are not binary fractions. */
#define NV 40
#define NT 54
static const int32_t fault_ntri[3] = {24, 18, 12};
static const char *const names[3] = {
    "CRFA-BPPM-WEST-Big_Pine_fault-CFM4",
    "San Andreas fault (Mojave, \"south\") 1857",
    "Falla de San Andr\xc3\xa9s / Ca\xc3\xb1\xc3\xb3n",
};
static const char *const ts_files[3] = {
    "CRFA-BPPM-WEST-Big_Pine_fault-CFM4.ts",
    "San_Andreas_fault_Mojave_south_1857.ts",
    "Falla_de_San_Andr_s_Ca_n.ts",
};
static const int32_t custom_tags[3] = {101, 7, 55};

static double sx(int i) { return 400000.1 + 997.3 * i; }
static double sy(int i) { return 3750000.3 + 13.7 * i; }

/* Vertex index of column c of fault f in row j. */
static int32_t col(int f, int c, int j)
{
    if (f == 0 || c == 0)
        return (int32_t)(j * 5 + (f == 0 ? c : 4));
    return f == 1 ? (int32_t)(20 + j * 3 + c - 1) : (int32_t)(32 + j * 2 + c - 1);
}

static fm_mesh *sample_mesh(void)
{
    fm_mesh *m = fm_mesh_create();
    for (int j = 0; j < 4; j++)
        for (int i = 0; i < 5; i++)
            fm_mesh_add_vertex(m, sx(i), sy(i), 250.25 - 1234.5 * j);
    for (int j = 0; j < 4; j++)
        for (int k = 1; k <= 3; k++)
            fm_mesh_add_vertex(m, sx(4) + 500.7 * k, sy(4) + 811.1 * k, 250.25 - 1234.5 * j);
    for (int j = 0; j < 4; j++)
        for (int k = 1; k <= 2; k++)
            fm_mesh_add_vertex(m, sx(4) + 600.2 * k, sy(4) - 700.9 * k, 250.25 - 1234.5 * j);
    static const int ncols[3] = {5, 4, 3};
    for (int j = 0; j < 3; j++)
        for (int f = 0; f < 3; f++)
            for (int c = 0; c + 1 < ncols[f]; c++) {
                int32_t a = col(f, c, j), b = col(f, c + 1, j), cc = col(f, c + 1, j + 1),
                        d = col(f, c, j + 1);
                if ((c + j) % 2 == 0) {
                    fm_mesh_add_triangle(m, a, b, cc, f);
                    fm_mesh_add_triangle(m, a, cc, d, f);
                } else {
                    fm_mesh_add_triangle(m, a, b, d, f);
                    fm_mesh_add_triangle(m, b, cc, d, f);
                }
            }
    return m;
}

static double area_data[NT];
static const fm_vtu_array extra = {"area", FM_VTU_FLOAT64, 1, area_data};

static fm_faultset sample_set(const fm_mesh *m)
{
    const double *x = fm_mesh_vertices(m);
    const int32_t *t = fm_mesh_triangles(m);
    for (size_t i = 0; i < NT; i++)
        area_data[i] =
            fm_triangle_area(x + 3 * t[3 * i], x + 3 * t[3 * i + 1], x + 3 * t[3 * i + 2]);
    fm_faultset fs = {
        .mesh = m, .names = names, .nfaults = 3, .cell_data = &extra, .ncell_data = 1, .crs = "EPSG:26711"};
    return fs;
}

static fm_status write_all(const char *dir, const fm_faultset *fs, fm_error *err)
{
    char path[4096];
    fm_status st = fm_mkdir_p(dir, err);
    fm_faultset tagged = *fs;
    tagged.physical_tags = custom_tags;
#define W(name, call)                                    \
    if (st == FM_OK) {                                   \
        snprintf(path, sizeof path, "%s/%s", dir, name); \
        st = call;                                       \
    }
    W("set.vtu", fm_faultset_write_vtu(path, fs, err));
    W("set41.msh", fm_faultset_write_msh(path, fs, FM_MSH_41, err));
    W("set22.msh", fm_faultset_write_msh(path, fs, FM_MSH_22, err));
    W("tags41.msh", fm_faultset_write_msh(path, &tagged, FM_MSH_41, err));
    W("set.stl", fm_faultset_write_stl(path, fs, err));
    W("set.obj", fm_faultset_write_obj(path, fs, err));
    W("ts", fm_faultset_write_tsurf(path, fs, err));
#undef W
    return st;
}

/* ---- helpers ---- */

static void tmp_dir(char *buf, size_t n, const char *name)
{
    snprintf(buf, n, "%s/%s", FM_TMP_DIR, name);
    CHECK_EQ(fm_mkdir_p(buf, NULL), FM_OK);
}

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* Entries of dir other than . and .., and how many look like temporaries. */
static int count_entries(const char *dir, int *temporaries)
{
    DIR *d = opendir(dir);
    int n = 0;
    *temporaries = 0;
    if (!d)
        return -1;
    for (struct dirent *e; (e = readdir(d));) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        n++;
        *temporaries += strstr(e->d_name, ".tmp.") != NULL;
    }
    closedir(d);
    return n;
}

/* Next line of a text buffer (NUL-terminated); advances *p. */
static char *next_line(char **p)
{
    char *s = *p;
    if (!*s)
        return NULL;
    char *e = strchr(s, '\n');
    if (e) {
        *e = '\0';
        *p = e + 1;
    } else {
        *p = s + strlen(s);
    }
    return s;
}

/* ---- checks ---- */

static void test_msh41(void)
{
    fm_mesh *m = sample_mesh();
    fm_faultset fs = sample_set(m);
    char dir[4096], path[4200];
    fm_error err;
    tmp_dir(dir, sizeof dir, "fsw_msh41");
    snprintf(path, sizeof path, "%s/a.msh", dir);
    CHECK_EQ(fm_faultset_write_msh(path, &fs, FM_MSH_41, &err), FM_OK);
    char *buf = fm_test_read_file(path, NULL), *p = buf, *line;
    CHECK(buf != NULL);
    if (!buf) {
        fm_mesh_destroy(m);
        return;
    }
    CHECK(strncmp(buf,
                  "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Comments\n\"written by faultmesh " FM_VERSION_STRING
                  "\"\n\"crs EPSG:26711\"\n\"units metres, z up (negative below sea level)\"\n"
                  "$EndComments\n$PhysicalNames\n",
                  strlen("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Comments\n\"written by faultmesh " FM_VERSION_STRING
                  "\"\n\"crs EPSG:26711\"\n\"units metres, z up (negative below sea level)\"\n"
                  "$EndComments\n$PhysicalNames\n")) == 0);
    CHECK(strstr(buf, "\n1 1 \"CRFA-BPPM-WEST-Big_Pine_fault-CFM4: top\"\n") != NULL);
    CHECK(strstr(buf, "\n2 2 \"San Andreas fault (Mojave, 'south') 1857\"\n") != NULL);
    CHECK(strstr(buf, "\n2 3 \"Falla de San Andr\xc3\xa9s / Ca\xc3\xb1\xc3\xb3n\"\n") != NULL);
    /* An independent pass over $Nodes and $Elements: every node declared
     * once, in the entity of the lowest fault using it; every element's
     * nodes declared; per entity the triangles of that fault in mesh
     * order, with tag = mesh index + 1 and the mesh's corners. */
    int declared[NV] = {0}, owner[NV];
    for (int v = 0; v < NV; v++)
        owner[v] = 99;
    const int32_t *tri = fm_mesh_triangles(m), *tag = fm_mesh_tags(m);
    for (int t = 0; t < NT; t++)
        for (int k = 0; k < 3; k++)
            if (tag[t] < owner[tri[3 * t + k]])
                owner[tri[3 * t + k]] = tag[t];
    while ((line = next_line(&p)) && strcmp(line, "$Nodes") != 0)
        ;
    size_t nblocks = 0, nnodes = 0, lo = 0, hi = 0;
    CHECK(sscanf(next_line(&p), "%zu %zu %zu %zu", &nblocks, &nnodes, &lo, &hi) == 4);
    CHECK_EQ(nblocks, 3);
    CHECK_EQ(nnodes, NV);
    CHECK_EQ(lo, 1);
    CHECK_EQ(hi, NV);
    const double *x = fm_mesh_vertices(m);
    for (size_t b = 0; b < nblocks; b++) {
        int dim = 0, ent = 0, par = 1;
        size_t n = 0;
        CHECK(sscanf(next_line(&p), "%d %d %d %zu", &dim, &ent, &par, &n) == 4);
        CHECK_EQ(dim, 2);
        CHECK_EQ(par, 0);
        int tags[NV];
        for (size_t i = 0; i < n && i < NV; i++) {
            tags[i] = atoi(next_line(&p));
            CHECK(tags[i] >= 1 && tags[i] <= NV);
            if (tags[i] < 1 || tags[i] > NV)
                continue;
            declared[tags[i] - 1]++;
            CHECK_EQ(owner[tags[i] - 1] + 1, ent);
        }
        for (size_t i = 0; i < n && i < NV; i++) {
            double c[3];
            CHECK(sscanf(next_line(&p), "%lf %lf %lf", &c[0], &c[1], &c[2]) == 3);
            if (tags[i] >= 1 && tags[i] <= NV)
                for (int d = 0; d < 3; d++)
                    CHECK(c[d] == x[3 * (tags[i] - 1) + d]); /* round trip exact */
        }
    }
    for (int v = 0; v < NV; v++)
        CHECK_EQ(declared[v], 1);
    CHECK_STR(next_line(&p), "$EndNodes");
    CHECK_STR(next_line(&p), "$Elements");
    CHECK(sscanf(next_line(&p), "%zu %zu %zu %zu", &nblocks, &nnodes, &lo, &hi) == 4);
    CHECK(nblocks > 3); /* the faults' triangles, then their outline and junction curves */
    CHECK(nnodes > NT);
    for (int f = 0; f < 3; f++) {
        int dim = 0, ent = 0, type = 0;
        size_t n = 0;
        CHECK(sscanf(next_line(&p), "%d %d %d %zu", &dim, &ent, &type, &n) == 4);
        CHECK_EQ(ent, f + 1);
        CHECK_EQ(type, 2);
        CHECK_EQ(n, fault_ntri[f]);
        int last = 0;
        for (size_t i = 0; i < n; i++) {
            int e = 0, a = 0, b = 0, c = 0;
            CHECK(sscanf(next_line(&p), "%d %d %d %d", &e, &a, &b, &c) == 4);
            CHECK(e > last && e >= 1 && e <= NT);
            last = e;
            if (e < 1 || e > NT)
                continue;
            CHECK_EQ(tag[e - 1], f);
            CHECK(a == tri[3 * (e - 1)] + 1 && b == tri[3 * (e - 1) + 1] + 1 &&
                  c == tri[3 * (e - 1) + 2] + 1);
        }
    }
    /* The curves: 2-node lines tagged after the triangles; every outline
     * edge of a fault (a side of one of its triangles and of no other
     * triangle) in exactly one of them, and nothing else but sides two
     * faults share. */
    int outline_seen[NT][3];
    memset(outline_seen, 0, sizeof outline_seen);
    size_t nlines = 0, bad_lines = 0;
    for (size_t bl = 3; bl < nblocks; bl++) {
        int dim = 0, ent = 0, type = 0;
        size_t n = 0;
        CHECK(sscanf(next_line(&p), "%d %d %d %zu", &dim, &ent, &type, &n) == 4);
        CHECK(dim == 1 && type == 1);
        for (size_t i = 0; i < n; i++) {
            int e = 0, a = 0, b = 0;
            CHECK(sscanf(next_line(&p), "%d %d %d", &e, &a, &b) == 3);
            CHECK(e > NT);
            nlines++;
            int holders = 0, ht = -1, hk = -1, faults_mask = 0;
            for (int t = 0; t < NT; t++)
                for (int k = 0; k < 3; k++) {
                    int u = tri[3 * t + k] + 1, v = tri[3 * t + (k + 1) % 3] + 1;
                    if ((u == a && v == b) || (u == b && v == a)) {
                        holders++;
                        ht = t;
                        hk = k;
                        faults_mask |= 1 << tag[t];
                    }
                }
            if (holders == 1)
                outline_seen[ht][hk]++;
            else if (!(faults_mask & (faults_mask - 1)))
                bad_lines++; /* neither an outline edge nor one two faults share */
        }
    }
    CHECK_EQ(bad_lines, 0);
    CHECK(nlines + NT == nnodes);
    for (int t = 0; t < NT; t++)
        for (int k = 0; k < 3; k++) {
            int u = tri[3 * t + k], v = tri[3 * t + (k + 1) % 3], holders = 0;
            for (int s = 0; s < NT; s++)
                for (int q = 0; q < 3; q++) {
                    int a = tri[3 * s + q], b = tri[3 * s + (q + 1) % 3];
                    holders += (a == u && b == v) || (a == v && b == u);
                }
            if (holders == 1)
                CHECK_EQ(outline_seen[t][k], 1);
        }
    CHECK_STR(next_line(&p), "$EndElements");
    free(buf);
    fm_mesh_destroy(m);
}

static void test_msh22_and_unused_vertex(void)
{
    fm_mesh *m = sample_mesh();
    fm_mesh_add_vertex(m, 1, 2, 3); /* used by no triangle: index 40 */
    fm_faultset fs = sample_set(m);
    char dir[4096], path[4200];
    fm_error err;
    tmp_dir(dir, sizeof dir, "fsw_msh22");
    snprintf(path, sizeof path, "%s/a.msh", dir);
    CHECK_EQ(fm_faultset_write_msh(path, &fs, FM_MSH_22, &err), FM_OK);
    char *buf = fm_test_read_file(path, NULL);
    CHECK(buf && strstr(buf, "$MeshFormat\n2.2 0 8\n") == buf);
    CHECK(buf && strstr(buf, "$Nodes\n40\n1 400000.1 3750000.3 250.25\n") != NULL);
    CHECK(buf && strstr(buf, "\n41 1 2 3\n") == NULL); /* the unused vertex is left out */
    /* first triangle: fault 0, physical 1, entity 1; the 4th is fault 1 */
    /* then the curves' lines, as 2.2 lines (type 1) */
    CHECK(buf && strstr(buf, "$Elements\n") && strstr(strstr(buf, "$Elements\n"), "\n1 2 2 1 1 1 2 7\n"));
    CHECK(buf && strstr(buf, "\n55 1 2 ") != NULL);
    CHECK(buf && strstr(buf, "\n9 2 2 2 2 5 21 24\n") != NULL);
    free(buf);
    snprintf(path, sizeof path, "%s/b.msh", dir);
    CHECK_EQ(fm_faultset_write_msh(path, &fs, FM_MSH_41, &err), FM_OK);
    buf = fm_test_read_file(path, NULL);
    CHECK(buf && strstr(buf, "$Nodes\n3 40 1 40\n") != NULL);
    free(buf);
    snprintf(path, sizeof path, "%s/a.obj", dir);
    CHECK_EQ(fm_faultset_write_obj(path, &fs, &err), FM_OK);
    buf = fm_test_read_file(path, NULL);
    CHECK(buf && strstr(buf, "\nv 1 2 3\n") != NULL); /* OBJ keeps every vertex */
    free(buf);
    fm_mesh_destroy(m);
}

static void test_msh_names(void)
{
    /* A long name is cut at a character boundary; '\\' and '"' replaced. */
    char longname[400];
    size_t n = 0;
    longname[n++] = 'a';
    while (n + 2 < 300) {
        longname[n++] = '\xc3';
        longname[n++] = '\xa9';
    }
    longname[n] = '\0';
    const char *nm[2] = {longname, "back\\slash \"quoted\""};
    fm_mesh *m = fm_mesh_create();
    fm_mesh_add_vertex(m, 0, 0, 0);
    fm_mesh_add_vertex(m, 1, 0, 0);
    fm_mesh_add_vertex(m, 0, 0, -1);
    fm_mesh_add_triangle(m, 0, 1, 2, 0);
    fm_mesh_add_triangle(m, 0, 2, 1, 1);
    fm_faultset fs = {.mesh = m, .names = nm, .nfaults = 2};
    char dir[4096], path[4200];
    fm_error err;
    tmp_dir(dir, sizeof dir, "fsw_names");
    snprintf(path, sizeof path, "%s/a.msh", dir);
    CHECK_EQ(fm_faultset_write_msh(path, &fs, FM_MSH_22, &err), FM_OK);
    char *buf = fm_test_read_file(path, NULL);
    CHECK(buf && strstr(buf, "\n2 2 \"back/slash 'quoted'\"\n") != NULL);
    char expect[400];
    snprintf(expect, sizeof expect, "\n2 1 \"%.199s\"\n", longname); /* 'a' + 99 x 2 bytes */
    CHECK(buf && strstr(buf, expect) != NULL);
    free(buf);
    fm_mesh_destroy(m);
}

static void test_stl(void)
{
    fm_mesh *m = sample_mesh();
    fm_faultset fs = sample_set(m);
    char dir[4096], path[4200];
    fm_error err;
    tmp_dir(dir, sizeof dir, "fsw_stl");
    snprintf(path, sizeof path, "%s/a.stl", dir);
    CHECK_EQ(fm_faultset_write_stl(path, &fs, &err), FM_OK);
    size_t len = 0;
    unsigned char *b = (unsigned char *)fm_test_read_file(path, &len);
    CHECK_EQ(len, 84 + 50 * NT);
    if (!b || len != 84 + 50 * NT) {
        free(b);
        fm_mesh_destroy(m);
        return;
    }
    CHECK(memcmp(b, "faultmesh ", 10) == 0);
    char header[81];
    memcpy(header, b, 80);
    header[80] = '\0';
    CHECK(strstr(header, ", CRS EPSG:26711") != NULL);
    uint32_t count = (uint32_t)b[80] | (uint32_t)b[81] << 8 | (uint32_t)b[82] << 16 |
                     (uint32_t)b[83] << 24;
    CHECK_EQ(count, NT);
    const double *x = fm_mesh_vertices(m);
    const int32_t *tri = fm_mesh_triangles(m), *tag = fm_mesh_tags(m);
    for (size_t t = 0; t < NT; t++) {
        const unsigned char *r = b + 84 + 50 * t;
        float v[12];
        memcpy(v, r, 48); /* the test machine is little-endian, as VTU requires */
        for (int k = 0; k < 3; k++)
            for (int d = 0; d < 3; d++)
                CHECK(v[3 + 3 * k + d] == (float)x[3 * tri[3 * t + (size_t)k] + (size_t)d]);
        CHECK_NEAR(v[0] * v[0] + v[1] * v[1] + v[2] * v[2], 1.0, 1e-6);
        CHECK(fabs(v[2]) < 1e-6); /* vertical faults: horizontal normals */
        CHECK_EQ(r[48] | r[49] << 8, tag[t]);
    }
    free(b);
    fm_mesh_destroy(m);
}

static void test_obj(void)
{
    fm_mesh *m = sample_mesh();
    fm_faultset fs = sample_set(m);
    char dir[4096], path[4200];
    fm_error err;
    tmp_dir(dir, sizeof dir, "fsw_obj");
    snprintf(path, sizeof path, "%s/a.obj", dir);
    CHECK_EQ(fm_faultset_write_obj(path, &fs, &err), FM_OK);
    char *buf = fm_test_read_file(path, NULL), *p = buf, *line;
    int nv = 0, nf = 0, group = -1, counts[3] = {0, 0, 0};
    CHECK(buf && strstr(buf, "# CRS EPSG:26711\n") != NULL);
    CHECK(buf && strstr(buf, "\ng San_Andreas_fault_(Mojave,_\"south\")_1857\n") != NULL);
    while (buf && (line = next_line(&p))) {
        if (line[0] == 'v')
            nv++;
        if (line[0] == 'g')
            group++;
        if (line[0] == 'f' && group >= 0 && group < 3) {
            nf++;
            counts[group]++;
        }
    }
    CHECK_EQ(nv, NV);
    CHECK_EQ(nf, NT);
    for (int f = 0; f < 3; f++)
        CHECK_EQ(counts[f], fault_ntri[f]);
    free(buf);
    fm_mesh_destroy(m);
}

static void test_tsurf(void)
{
    fm_mesh *m = sample_mesh();
    fm_faultset fs = sample_set(m);
    char dir[4096], path[4300];
    fm_error err;
    tmp_dir(dir, sizeof dir, "fsw_ts");
    snprintf(path, sizeof path, "%s/sub/dir", dir);
    CHECK_EQ(fm_faultset_write_tsurf(path, &fs, &err), FM_OK);
    char **files = NULL;
    CHECK_EQ(fm_faultset_tsurf_file_names(&fs, &files, &err), FM_OK);
    static const int nverts[3] = {20, 16, 12};
    for (int f = 0; files && f < 3; f++) {
        CHECK_STR(files[f], ts_files[f]);
        snprintf(path, sizeof path, "%s/sub/dir/%s", dir, ts_files[f]);
        fm_tsurf **obj = NULL;
        size_t nobj = 0;
        CHECK_EQ(fm_tsurf_read_file(path, &obj, &nobj, &err), FM_OK);
        if (!obj)
            continue;
        CHECK_EQ(nobj, 1);
        CHECK_STR(fm_tsurf_name(obj[0]), names[f]);
        const fm_mesh *tm = fm_tsurf_mesh(obj[0]);
        CHECK_EQ(fm_mesh_nvertices(tm), nverts[f]);
        CHECK_EQ(fm_mesh_ntriangles(tm), fault_ntri[f]);
        /* Same triangles, same winding, in mesh order. */
        const double *x = fm_mesh_vertices(m), *tx = fm_mesh_vertices(tm);
        const int32_t *tri = fm_mesh_triangles(m), *tag = fm_mesh_tags(m);
        const int32_t *ttri = fm_mesh_triangles(tm);
        size_t k = 0;
        for (size_t t = 0; t < NT; t++) {
            if (tag[t] != f)
                continue;
            for (int c = 0; c < 3; c++)
                for (int d = 0; d < 3; d++)
                    CHECK(tx[3 * ttri[3 * k + (size_t)c] + (size_t)d] ==
                          x[3 * tri[3 * t + (size_t)c] + (size_t)d]);
            k++;
        }
        fm_tsurf_free_all(obj, nobj);
    }
    fm_faultset_free_file_names(files, 3);
    fm_mesh_destroy(m);
}

static void test_file_names(void)
{
    const char *nm[8] = {"a b", "A_B", "a-b", ".hidden", "x/../y",
                         "Falla de San Andr\xc3\xa9s / Ca\xc3\xb1\xc3\xb3n", "a_b-2", "  #"};
    const char *expect[8] = {"a_b.ts",    "A_B-2.ts", "a-b.ts",     "_hidden.ts",
                             "x_.._y.ts", "Falla_de_San_Andr_s_Ca_n.ts", "a_b-2-2.ts", "_.ts"};
    fm_mesh *m = fm_mesh_create();
    fm_mesh_add_vertex(m, 0, 0, 0);
    fm_mesh_add_vertex(m, 1, 0, 0);
    fm_mesh_add_vertex(m, 0, 0, -1);
    for (int f = 0; f < 8; f++)
        fm_mesh_add_triangle(m, 0, 1, 2, f);
    fm_faultset fs = {.mesh = m, .names = nm, .nfaults = 8};
    char **files = NULL;
    fm_error err;
    CHECK_EQ(fm_faultset_tsurf_file_names(&fs, &files, &err), FM_OK);
    for (int f = 0; files && f < 8; f++)
        CHECK_STR(files[f], expect[f]);
    fm_faultset_free_file_names(files, 8);
    fm_mesh_destroy(m);
}

static void test_deterministic(void)
{
    fm_mesh *m = sample_mesh();
    fm_faultset fs = sample_set(m);
    char d1[4096], d2[4096], a[4200], b[4200];
    fm_error err;
    tmp_dir(d1, sizeof d1, "fsw_det1");
    tmp_dir(d2, sizeof d2, "fsw_det2");
    CHECK_EQ(write_all(d1, &fs, &err), FM_OK);
    /* A copy of the mesh at other addresses must not change a byte. */
    fm_mesh *m2 = fm_mesh_clone(m);
    fs.mesh = m2;
    CHECK_EQ(write_all(d2, &fs, &err), FM_OK);
    static const char *files[] = {"set.vtu",
                                  "set41.msh",
                                  "set22.msh",
                                  "tags41.msh",
                                  "set.stl",
                                  "set.obj",
                                  "ts/CRFA-BPPM-WEST-Big_Pine_fault-CFM4.ts",
                                  "ts/San_Andreas_fault_Mojave_south_1857.ts",
                                  "ts/Falla_de_San_Andr_s_Ca_n.ts"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        snprintf(a, sizeof a, "%s/%s", d1, files[i]);
        snprintf(b, sizeof b, "%s/%s", d2, files[i]);
        CHECK(fm_test_same_file(a, b));
    }
    int tmp = 0;
    CHECK_EQ(count_entries(d1, &tmp), 7); /* 6 files and ts/ */
    CHECK_EQ(tmp, 0);
    snprintf(a, sizeof a, "%s/ts", d1);
    CHECK_EQ(count_entries(a, &tmp), 3);
    CHECK_EQ(tmp, 0);
    fm_mesh_destroy(m);
    fm_mesh_destroy(m2);
}

static const void *find_bytes(const char *hay, size_t n, const char *needle, size_t k)
{
    for (size_t i = 0; i + k <= n; i++)
        if (memcmp(hay + i, needle, k) == 0)
            return hay + i;
    return NULL;
}

static void test_exodus(void)
{
    fm_mesh *m = sample_mesh();
    fm_mesh_add_vertex(m, 1, 2, 3); /* used by no triangle */
    fm_faultset fs = sample_set(m);
    /* the Y junction: the shared column 4 (rows 0..3) */
    int32_t column[4];
    for (int r = 0; r < 4; r++)
        column[r] = col(0, 4, r);
    fm_faultset_nodeset ns = {"junction 1: a / b", column, 4};
    fs.nodesets = &ns;
    fs.nnodesets = 1;
    char dir[4096], a[4200], b[4200];
    fm_error err;
    tmp_dir(dir, sizeof dir, "fsw_exo");
    snprintf(a, sizeof a, "%s/a.exo", dir);
    snprintf(b, sizeof b, "%s/b.exo", dir);
    CHECK_EQ(fm_faultset_write_exodus(a, &fs, &err), FM_OK);
    CHECK_EQ(fm_faultset_write_exodus(b, &fs, &err), FM_OK);
    CHECK(fm_test_same_file(a, b)); /* no date, no time: same bytes */
    size_t n = 0;
    char *buf = fm_test_read_file(a, &n);
    CHECK(buf && n > 4 && memcmp(buf, "CDF", 3) == 0); /* a netCDF file */
    /* the names (short: fm_names.h) and the CRS are in it */
    char **sn = fm_short_names(fs.names, fs.nfaults, FM_EXODUS_NAME_MAX);
    CHECK(sn && buf && find_bytes(buf, n, sn[1], strlen(sn[1])) != NULL);
    fm_short_names_free(sn, fs.nfaults);
    CHECK(buf && find_bytes(buf, n, "crs: EPSG:26711", 15) != NULL);
    CHECK(buf && find_bytes(buf, n, "junction_1_a_b", 14) != NULL);
    free(buf);
    int tmp = 0;
    CHECK_EQ(count_entries(dir, &tmp), 2);
    CHECK_EQ(tmp, 0);
    /* a node set with a vertex of no triangle: refused, nothing written */
    int32_t unused = NV;
    ns = (fm_faultset_nodeset){"loose", &unused, 1};
    snprintf(a, sizeof a, "%s/c.exo", dir);
    CHECK_EQ(fm_faultset_write_exodus(a, &fs, &err), FM_ERR_INVALID);
    CHECK(!exists(a));
    CHECK_EQ(count_entries(dir, &tmp), 2);
    CHECK_EQ(tmp, 0);
    fm_mesh_destroy(m);
}

static void test_msh_conventions(void)
{
    const char *nm[5] = {"San Andreas (Mojave) 1857", "1992 Landers", "a--b", "a  b",
                         "Ca\xc3\xb1\xc3\xb3n"};
    int32_t tags[5];
    char **pn = NULL;
    fm_error err;
    CHECK_EQ(fm_msh_tags_make(FM_MSH_TAGS_PYLITH, nm, 5, tags, &pn, &err), FM_OK);
    static const char *labels[5] = {"San_Andreas_Mojave_1857", "fault_1992_Landers", "a_b", "a_b_2",
                                    "Ca_n"};
    for (int i = 0; pn && i < 5; i++) {
        CHECK_STR(pn[i], labels[i]);
        CHECK_EQ(tags[i], i + 1);
    }
    fm_faultset_free_file_names(pn, 5);
    CHECK_EQ(fm_msh_tags_make(FM_MSH_TAGS_SEISSOL, nm, 5, tags, &pn, &err), FM_OK);
    for (int i = 0; pn && i < 5; i++) {
        CHECK_STR(pn[i], "fault");
        CHECK_EQ(tags[i], 103);
    }
    fm_faultset_free_file_names(pn, 5);
    CHECK_EQ(fm_msh_tags_make((fm_msh_tags)9, nm, 5, tags, &pn, &err), FM_ERR_INVALID);

    /* Tandem: one group, MSH 2.2, node tags 1..n although vertex 0 is
     * used by no triangle */
    fm_mesh *m = fm_mesh_create();
    fm_mesh_add_vertex(m, 9, 9, 9);
    for (int i = 0; i < 4; i++)
        fm_mesh_add_vertex(m, i % 2, i / 2, -1.5);
    fm_mesh_add_triangle(m, 1, 2, 3, 0);
    fm_mesh_add_triangle(m, 2, 4, 3, 1);
    const char *two[2] = {"north", "south"};
    CHECK_EQ(fm_msh_tags_make(FM_MSH_TAGS_TANDEM, two, 2, tags, &pn, &err), FM_OK);
    fm_faultset fs = {.mesh = m, .names = two, .nfaults = 2, .physical_tags = tags,
                      .physical_names = (const char *const *)pn, .msh_dense_nodes = 1,
                      .msh_no_curves = 1,
                      .crs = "say \"x\""};
    char dir[4096], path[4200];
    tmp_dir(dir, sizeof dir, "fsw_conv");
    snprintf(path, sizeof path, "%s/t.msh", dir);
    CHECK_EQ(fm_faultset_write_msh(path, &fs, FM_MSH_22, &err), FM_OK);
    char *buf = fm_test_read_file(path, NULL);
    CHECK(buf && strstr(buf, "\"crs say 'x'\"\n") != NULL);
    CHECK(buf && strstr(buf, "$PhysicalNames\n1\n2 3 \"fault\"\n$EndPhysicalNames\n") != NULL);
    CHECK(buf && strstr(buf, "$Nodes\n4\n1 0 0 -1.5\n2 1 0 -1.5\n3 0 1 -1.5\n4 1 1 -1.5\n") != NULL);
    CHECK(buf && strstr(buf, "$Elements\n2\n1 2 2 3 1 1 2 3\n2 2 2 3 2 2 4 3\n") != NULL);
    free(buf);
    /* without dense numbering the tags keep the gap */
    fs.msh_dense_nodes = 0;
    CHECK_EQ(fm_faultset_write_msh(path, &fs, FM_MSH_22, &err), FM_OK);
    buf = fm_test_read_file(path, NULL);
    CHECK(buf && strstr(buf, "$Nodes\n4\n2 0 0 -1.5\n") != NULL);
    free(buf);
    /* shared tag, different names: refused */
    const char *other[2] = {"fault", "not fault"};
    fs.physical_names = other;
    CHECK_EQ(fm_faultset_write_msh(path, &fs, FM_MSH_22, &err), FM_ERR_INVALID);
    fm_faultset_free_file_names(pn, 2);
    fm_mesh_destroy(m);
}

/* Each writer on bad input or an unwritable place: the error, and nothing
 * on disk. */
typedef fm_status (*writer)(const char *, const fm_faultset *, fm_error *);
static fm_status w_vtu(const char *p, const fm_faultset *s, fm_error *e)
{
    return fm_faultset_write_vtu(p, s, e);
}
static fm_status w_msh41(const char *p, const fm_faultset *s, fm_error *e)
{
    return fm_faultset_write_msh(p, s, FM_MSH_41, e);
}
static fm_status w_msh22(const char *p, const fm_faultset *s, fm_error *e)
{
    return fm_faultset_write_msh(p, s, FM_MSH_22, e);
}
static fm_status w_stl(const char *p, const fm_faultset *s, fm_error *e)
{
    return fm_faultset_write_stl(p, s, e);
}
static fm_status w_obj(const char *p, const fm_faultset *s, fm_error *e)
{
    return fm_faultset_write_obj(p, s, e);
}
static fm_status w_ts(const char *p, const fm_faultset *s, fm_error *e)
{
    return fm_faultset_write_tsurf(p, s, e);
}
static fm_status w_exo(const char *p, const fm_faultset *s, fm_error *e)
{
    return fm_faultset_write_exodus(p, s, e);
}
/* the TSurf writer last: it makes a directory, the read-only test skips it */
#define NWRITERS 7
static const writer writers[NWRITERS] = {w_vtu, w_msh41, w_msh22, w_stl, w_obj, w_exo, w_ts};

static void expect_failure(const char *dir, const fm_faultset *fs, fm_status code)
{
    char path[4200];
    for (int w = 0; w < NWRITERS; w++) {
        fm_error err;
        fm_error_clear(&err);
        snprintf(path, sizeof path, "%s/out%d", dir, w);
        CHECK_EQ(writers[w](path, fs, &err), code);
        CHECK(strstr(err.message, path) == err.message); /* "PATH: what" */
        CHECK(!exists(path));
    }
    int tmp = 0;
    CHECK_EQ(count_entries(dir, &tmp), 0);
}

static void test_rejects(void)
{
    fm_mesh *m = sample_mesh();
    fm_faultset good = sample_set(m), fs;
    char dir[4096];
    tmp_dir(dir, sizeof dir, "fsw_rejects");
    fs = good;
    fs.nfaults = 2; /* fault 2's triangles now have a tag out of range */
    expect_failure(dir, &fs, FM_ERR_INVALID);
    const char *bad_names[4][3] = {
        {names[0], "new\nline", names[2]},
        {names[0], "bad \xc3 utf-8", names[2]},
        {names[0], "", names[2]},
        {names[0], "overlong \xc0\xaf", names[2]},
    };
    for (int i = 0; i < 4; i++) {
        fs = good;
        fs.names = bad_names[i];
        expect_failure(dir, &fs, FM_ERR_INVALID);
    }
    /* faults sharing a physical group under different names */
    static const int32_t dup_tags[3] = {1, 2, 1}, zero_tag[3] = {1, 0, 2};
    fs = good;
    fs.physical_tags = dup_tags;
    expect_failure(dir, &fs, FM_ERR_INVALID);
    /* a junction node set naming a vertex out of range, or without name */
    static const int32_t out_of_range[2] = {3, NV};
    fm_faultset_nodeset ns = {"junction", out_of_range, 2};
    fs = good;
    fs.nodesets = &ns;
    fs.nnodesets = 1;
    expect_failure(dir, &fs, FM_ERR_INVALID);
    ns = (fm_faultset_nodeset){"", out_of_range, 1};
    expect_failure(dir, &fs, FM_ERR_INVALID);
    fs.physical_tags = zero_tag;
    expect_failure(dir, &fs, FM_ERR_INVALID);
    fm_vtu_array taken = {"fault_id", FM_VTU_INT32, 1, fm_mesh_tags(m)};
    fs = good;
    fs.cell_data = &taken;
    expect_failure(dir, &fs, FM_ERR_INVALID);
    /* A fault without triangles. */
    const char *four[4] = {names[0], names[1], names[2], "empty"};
    fs = good;
    fs.names = four;
    fs.nfaults = 4;
    expect_failure(dir, &fs, FM_ERR_INVALID);
    /* A NaN coordinate. */
    fm_mesh *m2 = fm_mesh_clone(m);
    fm_mesh_vertices_mut(m2)[7] = NAN;
    fs = good;
    fs.mesh = m2;
    expect_failure(dir, &fs, FM_ERR_NUMERIC);
    fm_mesh_destroy(m2);

    /* The parent is a regular file: no directory can be made, even by root. */
    char file[4200], under[4300];
    snprintf(file, sizeof file, "%s/plain", dir);
    FILE *fp = fopen(file, "w");
    CHECK(fp != NULL);
    if (fp)
        fclose(fp);
    snprintf(under, sizeof under, "%s/x", file);
    for (int w = 0; w < NWRITERS; w++) {
        fm_error err;
        CHECK_EQ(writers[w](under, &good, &err), FM_ERR_IO);
        CHECK(strstr(err.message, under) != NULL);
    }
    int tmp = 0;
    CHECK_EQ(count_entries(dir, &tmp), 1);
    unlink(file);
    /* A read-only directory (root ignores permissions, so only as a user). */
    if (geteuid() != 0) {
        char ro[4200];
        snprintf(ro, sizeof ro, "%s/ro", dir);
        CHECK_EQ(fm_mkdir_p(ro, NULL), FM_OK);
        chmod(ro, 0555);
        for (int w = 0; w < NWRITERS - 1; w++) {
            fm_error err;
            snprintf(under, sizeof under, "%s/out", ro);
            CHECK_EQ(writers[w](under, &good, &err), FM_ERR_IO);
        }
        CHECK_EQ(count_entries(ro, &tmp), 0);
        chmod(ro, 0755);
        rmdir(ro);
    }
    fm_mesh_destroy(m);
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "--write") == 0) {
        fm_mesh *m = sample_mesh();
        fm_faultset fs = sample_set(m);
        fm_error err;
        fm_status st = write_all(argv[2], &fs, &err);
        fm_mesh_destroy(m);
        if (st != FM_OK) {
            fprintf(stderr, "%s\n", err.message);
            return 1;
        }
        return 0;
    }
    static const fm_test_case cases[] = {
        FM_CASE(test_msh41),      FM_CASE(test_msh22_and_unused_vertex),
        FM_CASE(test_msh_names),  FM_CASE(test_stl),
        FM_CASE(test_obj),        FM_CASE(test_tsurf),
        FM_CASE(test_file_names), FM_CASE(test_deterministic),
        FM_CASE(test_rejects),    FM_CASE(test_exodus),
        FM_CASE(test_msh_conventions),
    };
    return fm_test_run(cases, sizeof cases / sizeof cases[0]);
}
