#include "fm_vtu.h"

#include <stdio.h>
#include <string.h>

#include "fm_atomic.h"
#include "fs_out.h"

/* Base64 of a byte stream, written as it is produced so that large
 * arrays need no second buffer. */
typedef struct {
    fs_out *o;
    unsigned char pending[3];
    int npending;
} b64;

static const char B64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

static void b64_emit(b64 *b)
{
    unsigned char *p = b->pending;
    char *out = fs_out_room(b->o, 4);
    out[0] = B64[p[0] >> 2];
    out[1] = B64[((p[0] & 3) << 4) | (b->npending > 1 ? p[1] >> 4 : 0)];
    out[2] = b->npending > 1 ? B64[((p[1] & 15) << 2) | (b->npending > 2 ? p[2] >> 6 : 0)] : '=';
    out[3] = b->npending > 2 ? B64[p[2] & 63] : '=';
    b->o->n += 4;
    b->npending = 0;
}

static void b64_put(b64 *b, const void *data, size_t n)
{
    const unsigned char *s = data;
    size_t i = 0;
    while (b->npending && i < n) { /* complete the pending group first */
        b->pending[b->npending++] = s[i++];
        if (b->npending == 3)
            b64_emit(b);
    }
    /* Whole groups straight from the data. */
    for (; i + 3 <= n; i += 3) {
        char *out = fs_out_room(b->o, 4);
        out[0] = B64[s[i] >> 2];
        out[1] = B64[((s[i] & 3) << 4) | s[i + 1] >> 4];
        out[2] = B64[((s[i + 1] & 15) << 2) | s[i + 2] >> 6];
        out[3] = B64[s[i + 2] & 63];
        b->o->n += 4;
    }
    for (; i < n; i++) {
        b->pending[b->npending++] = s[i];
        if (b->npending == 3)
            b64_emit(b);
    }
}

static void b64_finish(b64 *b)
{
    if (b->npending) {
        for (int i = b->npending; i < 3; i++)
            b->pending[i] = 0;
        b64_emit(b);
    }
}

/* VTK's binary layout: one UInt64 byte count, then the raw array; the
 * project only targets little-endian machines (checked at run time). */
static void write_binary(fs_out *fp, const void *data, size_t nbytes)
{
    b64 b = {fp, {0}, 0};
    uint64_t header = nbytes;
    b64_put(&b, &header, sizeof header);
    b64_put(&b, data, nbytes);
    b64_finish(&b);
}

static void array_open(fs_out *fp, const char *type, const char *name, int ncomp)
{
    fs_out_str(fp, "        <DataArray type=\"");
    fs_out_str(fp, type);
    fs_out_char(fp, '"');
    if (name) {
        fs_out_str(fp, " Name=\"");
        fs_out_str(fp, name);
        fs_out_char(fp, '"');
    }
    if (ncomp > 1)
        fs_out_printf(fp, " NumberOfComponents=\"%d\"", ncomp);
    fs_out_str(fp, " format=\"binary\">\n          ");
}

static void array_close(fs_out *fp) { fs_out_str(fp, "\n        </DataArray>\n"); }

static void write_arrays(fs_out *fp, const fm_vtu_array *a, size_t na, size_t n)
{
    for (size_t i = 0; i < na; i++) {
        int f64 = a[i].type == FM_VTU_FLOAT64;
        array_open(fp, f64 ? "Float64" : "Int32", a[i].name, a[i].ncomp);
        write_binary(fp, a[i].values, n * (size_t)a[i].ncomp * (f64 ? 8 : 4));
        array_close(fp);
    }
}

static int little_endian(void)
{
    const uint16_t one = 1;
    unsigned char c;
    memcpy(&c, &one, 1);
    return c == 1;
}

static void write_body(fs_out *fp, const fm_vtu_content *c)
{
    size_t nv = c->mesh ? fm_mesh_nvertices(c->mesh) : c->npoints;
    size_t nt = c->mesh ? fm_mesh_ntriangles(c->mesh) : c->nquads;
    int corners = c->mesh ? 3 : 4;
    fs_out_str(fp, "<?xml version=\"1.0\"?>\n"
          "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
          "header_type=\"UInt64\">\n  <UnstructuredGrid>\n");
    if (c->nfield_strings) {
        fs_out_str(fp, "    <FieldData>\n");
        for (size_t i = 0; i < c->nfield_strings; i++) {
            const fm_vtu_strings *s = &c->field_strings[i];
            size_t total = 0;
            for (size_t k = 0; k < s->count; k++)
                total += strlen(s->items[k]) + 1;
            fs_out_str(fp, "      <DataArray type=\"UInt8\" Name=\"");
            fs_out_str(fp, s->name);
            fs_out_printf(fp, "\" NumberOfTuples=\"%zu\" format=\"binary\">\n          ", total);
            b64 b = {fp, {0}, 0};
            uint64_t header = total;
            b64_put(&b, &header, sizeof header);
            for (size_t k = 0; k < s->count; k++)
                b64_put(&b, s->items[k], strlen(s->items[k]) + 1);
            b64_finish(&b);
            fs_out_str(fp, "\n      </DataArray>\n");
        }
        fs_out_str(fp, "    </FieldData>\n");
    }
    fs_out_printf(fp, "    <Piece NumberOfPoints=\"%zu\" NumberOfCells=\"%zu\">\n", nv, nt);
    fs_out_str(fp, "      <Points>\n");
    array_open(fp, "Float64", "Points", 3);
    write_binary(fp, c->mesh ? fm_mesh_vertices(c->mesh) : c->points, nv * 3 * sizeof(double));
    array_close(fp);
    fs_out_str(fp, "      </Points>\n      <Cells>\n");
    array_open(fp, "Int32", "connectivity", 1);
    write_binary(fp, c->mesh ? fm_mesh_triangles(c->mesh) : c->quads,
                 nt * (size_t)corners * sizeof(int32_t));
    array_close(fp);

    /* offsets and types, streamed in chunks to stay small in memory */
    array_open(fp, "Int32", "offsets", 1);
    {
        b64 b = {fp, {0}, 0};
        uint64_t header = nt * sizeof(int32_t);
        b64_put(&b, &header, sizeof header);
        for (size_t t = 0; t < nt; t++) {
            int32_t off = (int32_t)((size_t)corners * (t + 1));
            b64_put(&b, &off, sizeof off);
        }
        b64_finish(&b);
    }
    array_close(fp);
    array_open(fp, "UInt8", "types", 1);
    {
        b64 b = {fp, {0}, 0};
        uint64_t header = nt;
        b64_put(&b, &header, sizeof header);
        const unsigned char tri = c->mesh ? 5 : 9; /* VTK_TRIANGLE, VTK_QUAD */
        for (size_t t = 0; t < nt; t++)
            b64_put(&b, &tri, 1);
        b64_finish(&b);
    }
    array_close(fp);
    fs_out_str(fp, "      </Cells>\n");
    if (c->npoint_data) {
        fs_out_str(fp, "      <PointData>\n");
        write_arrays(fp, c->point_data, c->npoint_data, nv);
        fs_out_str(fp, "      </PointData>\n");
    }
    if (c->ncell_data) {
        fs_out_str(fp, "      <CellData>\n");
        write_arrays(fp, c->cell_data, c->ncell_data, nt);
        fs_out_str(fp, "      </CellData>\n");
    }
    fs_out_str(fp, "    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
}

fm_status fm_vtu_write(const char *path, const fm_vtu_content *c, fm_error *err)
{
    if (!little_endian())
        return fm_error_set(err, FM_ERR_INVALID, path, 0,
                            "VTU output needs a little-endian machine");
    fm_atomic_file *f = fm_atomic_open(path, err);
    if (!f)
        return err ? err->code : FM_ERR_IO;
    fs_out *o = fs_out_open(fm_atomic_stream(f));
    if (!o) {
        fm_atomic_abort(f);
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    write_body(o, c);
    return fs_out_commit(o, f, path, err);
}
