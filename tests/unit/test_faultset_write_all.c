/* fm_faultset_write_all: the same bytes as the one-format writers whatever
 * the thread count; on failure every other file still written, each file
 * accounted for in order, the first failing one named, no partial or
 * temporary file; bad input writing nothing, and saying so per file. */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fm_atomic.h"
#include "fm_faultset_write.h"
#include "fm_test.h"

#define NFAULTS 7

static const char *const names[NFAULTS] = {"A fault", "B/fault", "c", "d d", "e", "f#", "g"};

/* NFAULTS strips of triangles side by side in x, each sharing its first
 * column with the strip before it; full-precision coordinates. */
static fm_mesh *sample_mesh(void)
{
    fm_mesh *m = fm_mesh_create();
    const int cols = 4 * NFAULTS + 1, rows = 6;
    for (int j = 0; j < rows; j++)
        for (int i = 0; i < cols; i++)
            fm_mesh_add_vertex(m, 400000.0 + 997.3 * i / 3.0, 3750000.0 + 13.7 * i + 0.1 * j,
                               -1234.5 * j / 7.0);
    for (int j = 0; j + 1 < rows; j++)
        for (int i = 0; i + 1 < cols; i++) {
            int32_t a = j * cols + i, f = i / 4;
            fm_mesh_add_triangle(m, a, a + 1, a + cols, f);
            fm_mesh_add_triangle(m, a + 1, a + cols + 1, a + cols, f);
        }
    return m;
}

/* Entries of dir, and how many look like temporaries. */
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

typedef struct paths {
    char dir[4096], vtu[4200], msh[4200], stl[4200], obj[4200], exo[4200];
} paths;

/* Empties dir (files, and the empty folders a test puts in the way), so
 * that no earlier run's file passes for this run's. */
static void empty_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    char path[8400];
    for (struct dirent *e; (e = readdir(d));) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        if (remove(path) != 0)
            rmdir(path);
    }
    closedir(d);
}

static void make_paths(paths *p, const char *name)
{
    snprintf(p->dir, sizeof p->dir, "%s/%s", FM_TMP_DIR, name);
    snprintf(p->vtu, sizeof p->vtu, "%s/mesh.vtu", p->dir);
    snprintf(p->msh, sizeof p->msh, "%s/mesh.msh", p->dir);
    snprintf(p->stl, sizeof p->stl, "%s/mesh.stl", p->dir);
    snprintf(p->obj, sizeof p->obj, "%s/mesh.obj", p->dir);
    snprintf(p->exo, sizeof p->exo, "%s/mesh.exo", p->dir);
    CHECK_EQ(fm_mkdir_p(p->dir, NULL), FM_OK);
    empty_dir(p->dir);
}

static void test_same_bytes(void)
{
    fm_mesh *m = sample_mesh();
    fm_faultset fs = {.mesh = m, .names = names, .nfaults = NFAULTS, .crs = "EPSG:26711"};
    fm_error err;
    char **files = NULL;
    CHECK_EQ(fm_faultset_tsurf_file_names(&fs, &files, &err), FM_OK);
    for (int v = 0; v < 2; v++) {
        fm_msh_version ver = v ? FM_MSH_22 : FM_MSH_41;
        paths ref;
        make_paths(&ref, "fswa_ref");
        CHECK_EQ(fm_faultset_write_vtu(ref.vtu, &fs, &err), FM_OK);
        CHECK_EQ(fm_faultset_write_msh(ref.msh, &fs, ver, &err), FM_OK);
        CHECK_EQ(fm_faultset_write_stl(ref.stl, &fs, &err), FM_OK);
        CHECK_EQ(fm_faultset_write_obj(ref.obj, &fs, &err), FM_OK);
        CHECK_EQ(fm_faultset_write_tsurf(ref.dir, &fs, &err), FM_OK);
        CHECK_EQ(fm_faultset_write_exodus(ref.exo, &fs, &err), FM_OK);
        for (int threads = 0; threads <= 5; threads++) {
            paths p;
            char name[32];
            snprintf(name, sizeof name, "fswa_%d_%d", v, threads);
            make_paths(&p, name);
            fm_faultset_outputs out = {p.vtu, p.msh, p.stl, p.obj, ver, p.dir, p.exo, NULL, NULL};
            CHECK_EQ(fm_faultset_write_all(&fs, &out, threads, &err), FM_OK);
            CHECK(fm_test_same_file(ref.vtu, p.vtu));
            CHECK(fm_test_same_file(ref.msh, p.msh));
            CHECK(fm_test_same_file(ref.stl, p.stl));
            CHECK(fm_test_same_file(ref.obj, p.obj));
            CHECK(fm_test_same_file(ref.exo, p.exo));
            for (size_t f = 0; f < NFAULTS; f++) {
                char a[4400], b[4400];
                snprintf(a, sizeof a, "%s/%s", ref.dir, files[f]);
                snprintf(b, sizeof b, "%s/%s", p.dir, files[f]);
                CHECK(fm_test_same_file(a, b));
            }
            int tmp;
            CHECK_EQ(count_entries(p.dir, &tmp), 5 + NFAULTS);
            CHECK_EQ(tmp, 0);
        }
    }
    fm_faultset_free_file_names(files, NFAULTS);
    fm_mesh_destroy(m);
}

/* What fm_output_done saw. */
typedef struct tally {
    int calls, failed, out_of_order;
    size_t last_fault, failed_fault;
    char first_failed[FM_ERROR_MESSAGE_MAX];
} tally;

static void count_done(void *ctx, const char *path, size_t fault, const fm_error *err)
{
    tally *t = ctx;
    /* set files first (SIZE_MAX), then TSurf by fault */
    if (t->calls && fault != SIZE_MAX && t->last_fault != SIZE_MAX && fault != t->last_fault + 1)
        t->out_of_order++;
    if (fault == SIZE_MAX && t->calls && t->last_fault != SIZE_MAX)
        t->out_of_order++;
    t->last_fault = fault;
    t->calls++;
    if (err) {
        if (!t->failed++)
            snprintf(t->first_failed, sizeof t->first_failed, "%s", err->message);
        else
            t->failed_fault = fault;
        if (!strstr(err->message, path))
            t->out_of_order++;
    }
}

/* A directory where mesh.msh should go, and one where a TSurf file should:
 * both fail, with the reason, and are named, the error is the same on any
 * thread count, every other file is written, nothing partial is left. */
static void test_blocked(void)
{
    fm_mesh *m = sample_mesh();
    fm_faultset fs = {.mesh = m, .names = names, .nfaults = NFAULTS};
    for (int threads = 1; threads <= 4; threads++) {
        paths p;
        char name[32];
        snprintf(name, sizeof name, "fswa_blocked_%d", threads);
        make_paths(&p, name);
        CHECK_EQ(fm_mkdir_p(p.msh, NULL), FM_OK);
        /* and a directory where the third fault's TSurf should go */
        char **files = NULL;
        CHECK_EQ(fm_faultset_tsurf_file_names(&fs, &files, NULL), FM_OK);
        char ts[8400];
        snprintf(ts, sizeof ts, "%s/%s", p.dir, files[2]);
        CHECK_EQ(fm_mkdir_p(ts, NULL), FM_OK);
        tally t = {0};
        fm_faultset_outputs out = {p.vtu, p.msh, p.stl, p.obj, FM_MSH_41, p.dir, p.exo,
                                   count_done, &t};
        fm_error err;
        fm_error_clear(&err);
        CHECK_EQ(fm_faultset_write_all(&fs, &out, threads, &err), FM_ERR_IO);
        CHECK(strstr(err.message, "mesh.msh") != NULL);
        CHECK(strstr(err.message, "directory") != NULL); /* the reason, not only "failed" */
        /* every file asked for, once, in order; the two failures named */
        CHECK_EQ(t.calls, 5 + NFAULTS);
        CHECK_EQ(t.failed, 2);
        CHECK(strstr(t.first_failed, "mesh.msh") != NULL);
        CHECK_EQ(t.failed_fault, 2);
        CHECK_EQ(t.out_of_order, 0);
        struct stat st;
        CHECK(stat(p.msh, &st) == 0 && S_ISDIR(st.st_mode));
        int tmp;
        /* the 5 set files (mesh.msh the folder) and the TSurf files */
        CHECK_EQ(count_entries(p.dir, &tmp), 5 + NFAULTS);
        CHECK_EQ(tmp, 0);
        /* every file after the failing one was written, whole */
        size_t n;
        char *vtu = fm_test_read_file(p.vtu, &n);
        CHECK(vtu && n > 20 && memcmp(vtu + n - 11, "</VTKFile>\n", 11) == 0);
        free(vtu);
        CHECK(stat(p.exo, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0);
        snprintf(ts, sizeof ts, "%s/%s", p.dir, files[NFAULTS - 1]);
        CHECK(stat(ts, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0);
        fm_faultset_free_file_names(files, NFAULTS);
    }
    fm_mesh_destroy(m);
}

/* Bad input: nothing at all is written. */
static void test_invalid(void)
{
    fm_mesh *m = sample_mesh();
    fm_mesh_vertices_mut(m)[7] = NAN;
    fm_faultset fs = {.mesh = m, .names = names, .nfaults = NFAULTS};
    paths p;
    make_paths(&p, "fswa_invalid");
    tally t = {0};
    fm_faultset_outputs out = {p.vtu, p.msh, p.stl, p.obj, FM_MSH_41, p.dir, p.exo,
                               count_done, &t};
    fm_error err;
    CHECK_EQ(fm_faultset_write_all(&fs, &out, 3, &err), FM_ERR_NUMERIC);
    int tmp;
    CHECK_EQ(count_entries(p.dir, &tmp), 0);
    /* the five files and the TSurf folder, each said to be not written */
    CHECK_EQ(t.calls, 6);
    CHECK_EQ(t.failed, 6);
    fm_mesh_destroy(m);
}

FM_TEST_MAIN(FM_CASE(test_same_bytes), FM_CASE(test_blocked), FM_CASE(test_invalid))
