/* Fault set as one GoCAD TSurf per fault, through the io stage's writer:
 * what all faults share is prepared once (fs_tsurf_plan), then each file
 * is built and written on its own, on whichever thread takes it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_atomic.h"
#include "fm_names.h"
#include "fm_tsurf.h"
#include "faultset_internal.h"

void fm_faultset_free_file_names(char **names, size_t n)
{
    if (!names)
        return;
    for (size_t i = 0; i < n; i++)
        free(names[i]);
    free(names);
}

/* The file names of a validated set. */
static fm_status file_names(const fm_faultset *fs, char ***out, fm_error *err)
{
    *out = NULL;
    char **names = calloc(fs->nfaults, sizeof *names);
    fm_namer *nm = fm_namer_create();
    for (size_t i = 0; names && nm && i < fs->nfaults; i++) {
        const char *stem = fm_namer_next(nm, fs->names[i]);
        size_t len = stem ? strlen(stem) + 4 : 0;
        names[i] = stem ? malloc(len) : NULL;
        if (!names[i])
            break;
        snprintf(names[i], len, "%s.ts", stem);
    }
    int ok = names && nm && (fs->nfaults == 0 || names[fs->nfaults - 1]);
    fm_namer_destroy(nm);
    if (!ok) {
        fm_faultset_free_file_names(names, names ? fs->nfaults : 0);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    *out = names;
    return FM_OK;
}

fm_status fm_faultset_tsurf_file_names(const fm_faultset *fs, char ***out, fm_error *err)
{
    *out = NULL;
    fm_status st = fm_faultset_validate(fs, NULL, err);
    return st == FM_OK ? file_names(fs, out, err) : st;
}

static int by_index(const void *a, const void *b)
{
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

/* Fault f alone: its triangles (tri[3 * order[i]], i in [t0, t1)) in mesh
 * order, its vertices renumbered in mesh order. */
static fm_tsurf *build(const fm_faultset *fs, size_t f, const size_t *order, size_t t0, size_t t1,
                       fs_tsurf_scratch *sc)
{
    fm_tsurf *ts = fm_tsurf_create(fs->names[f]);
    /* the CRS as the block's NAME, which GoCAD shows and our reader takes
     * back as the input CRS (fm_tsurf_crs_code) */
    if (!ts || fm_tsurf_add_part(ts) < 0 ||
        (fs->crs && fs->crs[0] && fm_tsurf_set_crs_name(ts, fs->crs) != FM_OK)) {
        fm_tsurf_destroy(ts);
        return NULL;
    }
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh);
    size_t nused = 0;
    for (size_t i = t0; i < t1; i++)
        for (int k = 0; k < 3; k++) {
            int32_t v = tri[3 * order[i] + (size_t)k];
            if (sc->map[v] < 0) {
                sc->map[v] = 0;
                sc->used[nused++] = v;
            }
        }
    qsort(sc->used, nused, sizeof *sc->used, by_index);
    fm_mesh *m = fm_tsurf_mesh_mut(ts);
    int ok = fm_mesh_reserve(m, nused, t1 - t0) == FM_OK;
    for (size_t i = 0; i < nused && ok; i++) {
        const double *p = x + 3 * (size_t)sc->used[i];
        ok = (sc->map[sc->used[i]] = fm_mesh_add_vertex(m, p[0], p[1], p[2])) >= 0;
    }
    for (size_t i = t0; i < t1 && ok; i++) {
        const int32_t *t = tri + 3 * order[i];
        ok = fm_mesh_add_triangle(m, sc->map[t[0]], sc->map[t[1]], sc->map[t[2]], 0) >= 0;
    }
    for (size_t i = 0; i < nused; i++) /* clean for the next fault */
        sc->map[sc->used[i]] = -1;
    if (!ok) {
        fm_tsurf_destroy(ts);
        return NULL;
    }
    return ts;
}

fm_status fs_tsurf_plan_make(fs_tsurf_plan *pl, const char *dir, const fm_faultset *fs,
                             fm_error *err)
{
    memset(pl, 0, sizeof *pl);
    pl->fs = fs;
    pl->dir = dir;
    fm_status st = file_names(fs, &pl->files, err);
    if (st != FM_OK)
        return st;
    if (fs_group_by(fm_mesh_tags(fs->mesh), fm_mesh_ntriangles(fs->mesh), fs->nfaults,
                    &pl->tstart, &pl->torder))
        return fm_error_set(err, FM_ERR_NOMEM, dir, 0, "out of memory");
    for (size_t f = 0; f < fs->nfaults; f++) {
        size_t uses = 3 * (pl->tstart[f + 1] - pl->tstart[f]);
        pl->max_uses = uses > pl->max_uses ? uses : pl->max_uses;
    }
    return fm_mkdir_p(dir, err);
}

void fs_tsurf_plan_free(fs_tsurf_plan *pl)
{
    fm_faultset_free_file_names(pl->files, pl->fs ? pl->fs->nfaults : 0);
    free(pl->tstart);
    free(pl->torder);
    memset(pl, 0, sizeof *pl);
}

int fs_tsurf_scratch_init(fs_tsurf_scratch *sc, const fs_tsurf_plan *pl)
{
    size_t nv = fm_mesh_nvertices(pl->fs->mesh);
    sc->map = malloc((nv ? nv : 1) * sizeof *sc->map);
    sc->used = malloc((pl->max_uses ? pl->max_uses : 1) * sizeof *sc->used);
    sc->path = malloc(strlen(pl->dir) + FM_STEM_MAX + 40);
    if (!sc->map || !sc->used || !sc->path)
        return -1;
    for (size_t v = 0; v < nv; v++)
        sc->map[v] = -1;
    return 0;
}

void fs_tsurf_scratch_free(fs_tsurf_scratch *sc)
{
    free(sc->map);
    free(sc->used);
    free(sc->path);
    memset(sc, 0, sizeof *sc);
}

fm_status fs_tsurf_write_fault(const fs_tsurf_plan *pl, size_t f, fs_tsurf_scratch *sc,
                               fm_error *err)
{
    sprintf(sc->path, "%s/%s", pl->dir, pl->files[f]);
    fm_tsurf *ts = build(pl->fs, f, pl->torder, pl->tstart[f], pl->tstart[f + 1], sc);
    if (!ts)
        return fm_error_set(err, FM_ERR_NOMEM, sc->path, 0, "out of memory");
    fm_atomic_file *af = fm_atomic_open(sc->path, err);
    fm_status st = af ? FM_OK : err ? err->code : FM_ERR_IO;
    if (st == FM_OK)
        st = fm_tsurf_write_stream(fm_atomic_stream(af), sc->path, &ts, 1, err);
    if (st == FM_OK)
        st = fm_atomic_commit(af, err);
    else
        fm_atomic_abort(af);
    fm_tsurf_destroy(ts);
    return st;
}

fm_status fm_faultset_write_tsurf(const char *dir, const fm_faultset *fs, fm_error *err)
{
    fm_faultset_outputs out = {0};
    out.tsurf_dir = dir;
    return fm_faultset_write_all(fs, &out, 1, err);
}
