/* Fault set as one GoCAD TSurf per fault, through the io stage's writer. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_atomic.h"
#include "fm_tsurf.h"
#include "faultset_internal.h"

#define STEM_MAX 200

static int keep(unsigned char c)
{
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
           c == '.' || c == '-' || c == '_';
}

static int same_ignoring_case(const char *a, const char *b)
{
    for (; *a && *b; a++, b++) {
        char x = *a >= 'A' && *a <= 'Z' ? (char)(*a + 32) : *a;
        char y = *b >= 'A' && *b <= 'Z' ? (char)(*b + 32) : *b;
        if (x != y)
            return 0;
    }
    return *a == *b;
}

/* The rule of the header, without the suffixes. */
static char *stem(const char *name)
{
    char *s = malloc(STEM_MAX + 1);
    if (!s)
        return NULL;
    size_t n = 0;
    for (const char *c = name; *c && n < STEM_MAX; c++) {
        if (keep((unsigned char)*c))
            s[n++] = *c;
        else if (c == name || keep((unsigned char)c[-1])) /* first of a run */
            s[n++] = '_';
    }
    s[n] = '\0';
    if (s[0] == '.')
        s[0] = '_';
    return s;
}

void fm_faultset_free_file_names(char **names, size_t n)
{
    if (!names)
        return;
    for (size_t i = 0; i < n; i++)
        free(names[i]);
    free(names);
}

fm_status fm_faultset_tsurf_file_names(const fm_faultset *fs, char ***out, fm_error *err)
{
    *out = NULL;
    fm_status st = fm_faultset_validate(fs, NULL, err);
    if (st != FM_OK)
        return st;
    char **names = calloc(fs->nfaults, sizeof *names);
    if (!names)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    for (size_t i = 0; i < fs->nfaults; i++) {
        char *base = stem(fs->names[i]);
        /* base, "-" and a counter (at most 20 digits), ".ts" */
        names[i] = malloc(STEM_MAX + 32);
        if (!base || !names[i]) {
            free(base);
            fm_faultset_free_file_names(names, fs->nfaults);
            return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
        }
        /* Compare stems with their ".ts" so that "a-2" and a renamed "a" meet. */
        snprintf(names[i], STEM_MAX + 32, "%s.ts", base);
        for (size_t k = 2;; k++) {
            size_t j = 0;
            while (j < i && !same_ignoring_case(names[j], names[i]))
                j++;
            if (j == i)
                break;
            snprintf(names[i], STEM_MAX + 32, "%s-%zu.ts", base, k);
        }
        free(base);
    }
    *out = names;
    return FM_OK;
}

/* Fault f alone, vertices renumbered in mesh order; map is scratch of
 * nvertices entries. */
static fm_tsurf *build(const fm_faultset *fs, size_t f, int32_t *map)
{
    fm_tsurf *ts = fm_tsurf_create(fs->names[f]);
    if (!ts || fm_tsurf_add_part(ts) < 0) {
        fm_tsurf_destroy(ts);
        return NULL;
    }
    size_t nv = fm_mesh_nvertices(fs->mesh), nt = fm_mesh_ntriangles(fs->mesh);
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh), *tag = fm_mesh_tags(fs->mesh);
    for (size_t v = 0; v < nv; v++)
        map[v] = -1;
    for (size_t t = 0; t < nt; t++)
        if ((size_t)tag[t] == f)
            for (int k = 0; k < 3; k++)
                map[tri[3 * t + (size_t)k]] = 0;
    fm_mesh *m = fm_tsurf_mesh_mut(ts);
    int ok = 1;
    for (size_t v = 0; v < nv && ok; v++)
        if (map[v] == 0)
            ok = (map[v] = fm_mesh_add_vertex(m, x[3 * v], x[3 * v + 1], x[3 * v + 2])) >= 0;
    for (size_t t = 0; t < nt && ok; t++)
        if ((size_t)tag[t] == f)
            ok = fm_mesh_add_triangle(m, map[tri[3 * t]], map[tri[3 * t + 1]],
                                      map[tri[3 * t + 2]], 0) >= 0;
    if (!ok) {
        fm_tsurf_destroy(ts);
        return NULL;
    }
    return ts;
}

fm_status fm_faultset_write_tsurf(const char *dir, const fm_faultset *fs, fm_error *err)
{
    char **files = NULL;
    fm_status st = fm_faultset_validate(fs, dir, err);
    if (st == FM_OK)
        st = fm_faultset_tsurf_file_names(fs, &files, err);
    if (st != FM_OK)
        return st;
    size_t nv = fm_mesh_nvertices(fs->mesh);
    fm_tsurf **ts = calloc(fs->nfaults, sizeof *ts);
    int32_t *map = malloc((nv ? nv : 1) * sizeof *map);
    char *path = malloc(strlen(dir) + STEM_MAX + 40);
    if (!ts || !map || !path)
        st = fm_error_set(err, FM_ERR_NOMEM, dir, 0, "out of memory");
    /* Every object first: a failure to build one must not leave a
     * partial set on disk. Building them one at a time would need less
     * memory, but a fault set is a copy of one mesh at most. */
    for (size_t f = 0; f < fs->nfaults && st == FM_OK; f++)
        if (!(ts[f] = build(fs, f, map)))
            st = fm_error_set(err, FM_ERR_NOMEM, dir, 0, "out of memory");
    if (st == FM_OK)
        st = fm_mkdir_p(dir, err);
    for (size_t f = 0; f < fs->nfaults && st == FM_OK; f++) {
        sprintf(path, "%s/%s", dir, files[f]);
        st = fm_tsurf_write_file(path, &ts[f], 1, err);
    }
    for (size_t f = 0; ts && f < fs->nfaults; f++)
        fm_tsurf_destroy(ts[f]);
    free(ts);
    free(map);
    free(path);
    fm_faultset_free_file_names(files, fs->nfaults);
    return st;
}
