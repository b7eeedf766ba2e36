/* Fault set as Wavefront OBJ: shared vertices, one group per fault. */
#include <stdio.h>
#include <stdlib.h>

#include "fm_atomic.h"
#include "faultset_internal.h"
#include "fs_out.h"

static void put_name(fs_out *o, const char *key, const char *name)
{
    fs_out_str(o, key);
    for (const char *c = name; *c; c++)
        fs_out_char(o, *c == ' ' || *c == '#' ? '_' : *c); /* other whitespace is refused */
    fs_out_char(o, '\n');
}

static void put_body(fs_out *o, const fm_faultset *fs, const size_t *tstart, const size_t *torder)
{
    size_t nv = fm_mesh_nvertices(fs->mesh), nt = fm_mesh_ntriangles(fs->mesh);
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh);
    fs_out_printf(o, "# faultmesh %s fault set: %zu faults, %zu vertices, %zu triangles\n",
                  FM_VERSION_STRING, fs->nfaults, nv, nt);
    if (fs->crs && fs->crs[0]) {
        fs_out_str(o, "# CRS ");
        fs_out_str(o, fs->crs);
        fs_out_char(o, '\n');
    }
    for (size_t v = 0; v < nv; v++) {
        fs_out_char(o, 'v');
        for (int d = 0; d < 3; d++) {
            fs_out_char(o, ' ');
            fs_out_double(o, x[3 * v + (size_t)d]);
        }
        fs_out_char(o, '\n');
    }
    for (size_t f = 0; f < fs->nfaults; f++) {
        put_name(o, "o ", fs->names[f]);
        put_name(o, "g ", fs->names[f]);
        for (size_t i = tstart[f]; i < tstart[f + 1]; i++) {
            const int32_t *t = tri + 3 * torder[i];
            fs_out_char(o, 'f');
            for (int k = 0; k < 3; k++) {
                fs_out_char(o, ' ');
                fs_out_i64(o, (int64_t)t[k] + 1);
            }
            fs_out_char(o, '\n');
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
    fs_out *o = NULL;
    if (st == FM_OK && !(o = fs_out_open(fm_atomic_stream(f)))) {
        fm_atomic_abort(f);
        st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    if (st == FM_OK) {
        put_body(o, fs, tstart, torder);
        st = fs_out_commit(o, f, path, err);
    }
    free(tstart);
    free(torder);
    return st;
}
