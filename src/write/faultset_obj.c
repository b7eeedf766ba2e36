/* Fault set as Wavefront OBJ: shared vertices, one group per fault. */
#include <stdio.h>
#include <stdlib.h>

#include "fm_atomic.h"
#include "faultset_internal.h"

static void put_name(FILE *fp, const char *key, const char *name)
{
    fputs(key, fp);
    for (const char *c = name; *c; c++)
        fputc(*c == ' ' || *c == '#' ? '_' : *c, fp); /* other whitespace is refused */
    fputc('\n', fp);
}

static void put_body(FILE *fp, const fm_faultset *fs, const size_t *tstart, const size_t *torder)
{
    size_t nv = fm_mesh_nvertices(fs->mesh), nt = fm_mesh_ntriangles(fs->mesh);
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh);
    fprintf(fp, "# faultmesh %s fault set: %zu faults, %zu vertices, %zu triangles\n",
            FM_VERSION_STRING, fs->nfaults, nv, nt);
    if (fs->crs && fs->crs[0])
        fprintf(fp, "# CRS %s\n", fs->crs);
    for (size_t v = 0; v < nv; v++) {
        char buf[32];
        fputc('v', fp);
        for (int d = 0; d < 3; d++) {
            fputc(' ', fp);
            fwrite(buf, 1, fs_format_double(buf, x[3 * v + (size_t)d]), fp);
        }
        fputc('\n', fp);
    }
    for (size_t f = 0; f < fs->nfaults; f++) {
        put_name(fp, "o ", fs->names[f]);
        put_name(fp, "g ", fs->names[f]);
        for (size_t i = tstart[f]; i < tstart[f + 1]; i++) {
            const int32_t *t = tri + 3 * torder[i];
            fprintf(fp, "f %ld %ld %ld\n", (long)t[0] + 1, (long)t[1] + 1, (long)t[2] + 1);
        }
    }
}

fm_status fm_faultset_write_obj(const char *path, const fm_faultset *fs, fm_error *err)
{
    fm_status st = fm_faultset_validate(fs, path, err);
    if (st != FM_OK)
        return st;
    size_t *tstart = NULL, *torder = NULL;
    fm_atomic_file *f = NULL;
    if (fs_group_by(fm_mesh_tags(fs->mesh), fm_mesh_ntriangles(fs->mesh), fs->nfaults, &tstart,
                    &torder))
        st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    else if (!(f = fm_atomic_open(path, err)))
        st = err ? err->code : FM_ERR_IO;
    if (st == FM_OK) {
        FILE *fp = fm_atomic_stream(f);
        put_body(fp, fs, tstart, torder);
        if (ferror(fp)) {
            fm_atomic_abort(f);
            st = fm_error_set(err, FM_ERR_IO, path, 0, "write failed");
        } else {
            st = fm_atomic_commit(f, err);
        }
    }
    free(tstart);
    free(torder);
    return st;
}
