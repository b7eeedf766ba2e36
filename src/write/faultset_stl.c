/* Fault set as binary STL. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fm_atomic.h"
#include "faultset_internal.h"
#include "fs_out.h"

/* Byte by byte, so the file is little-endian whatever the machine. */
static void put_u32(fs_out *o, uint32_t v)
{
    unsigned char *b = (unsigned char *)fs_out_room(o, 4);
    b[0] = (unsigned char)v;
    b[1] = (unsigned char)(v >> 8);
    b[2] = (unsigned char)(v >> 16);
    b[3] = (unsigned char)(v >> 24);
    o->n += 4;
}

static void put_f32(fs_out *o, double v)
{
    float f = (float)v;
    uint32_t u;
    memcpy(&u, &f, 4);
    put_u32(o, u);
}

/* The normal is computed in double from the exact corners, so it stays
 * right even where float32 corners would make a thin triangle flip. */
static void put_normal(fs_out *o, const double *a, const double *b, const double *c)
{
    double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double g[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {e[1] * g[2] - e[2] * g[1], e[2] * g[0] - e[0] * g[2],
                   e[0] * g[1] - e[1] * g[0]};
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int d = 0; d < 3; d++)
        put_f32(o, len > 0 ? n[d] / len : 0.0);
}

static void put_header(fs_out *o, const fm_faultset *fs, size_t nt)
{
    char h[81];
    memset(h, 0, sizeof h);
    int n = snprintf(h, sizeof h, "faultmesh %s fault set: %zu faults, %zu triangles",
                     FM_VERSION_STRING, fs->nfaults, nt);
    if (fs->crs && fs->crs[0] && n + 6 < 80) {
        memcpy(h + n, ", CRS ", 6);
        size_t room = 80 - (size_t)n - 6, len = strlen(fs->crs);
        /* A CRS too long for the header is cut, but not inside a character. */
        memcpy(h + n + 6, fs->crs, len > room ? fs_utf8_cut(fs->crs, room) : len);
    }
    fs_out_bytes(o, h, 80);
}

fm_status fm_faultset_write_stl(const char *path, const fm_faultset *fs, fm_error *err)
{
    fm_status st = fm_faultset_validate(fs, path, err);
    if (st != FM_OK)
        return st;
    size_t nt = fm_mesh_ntriangles(fs->mesh);
    fm_atomic_file *f = fm_atomic_open(path, err);
    if (!f)
        return err ? err->code : FM_ERR_IO;
    fs_out *o = fs_out_open(fm_atomic_stream(f));
    if (!o) {
        fm_atomic_abort(f);
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh), *tag = fm_mesh_tags(fs->mesh);
    put_header(o, fs, nt);
    put_u32(o, (uint32_t)nt);
    for (size_t t = 0; t < nt; t++) {
        const double *p[3];
        for (int k = 0; k < 3; k++)
            p[k] = x + 3 * (size_t)tri[3 * t + (size_t)k];
        put_normal(o, p[0], p[1], p[2]);
        for (int k = 0; k < 3; k++)
            for (int d = 0; d < 3; d++)
                put_f32(o, p[k][d]);
        unsigned char attr[2] = {(unsigned char)tag[t], (unsigned char)(tag[t] >> 8)};
        fs_out_bytes(o, attr, 2);
    }
    return fs_out_commit(o, f, path, err);
}
