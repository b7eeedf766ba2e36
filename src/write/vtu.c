#include "fm_vtu.h"

#include <stdio.h>
#include <string.h>

#include "fm_atomic.h"

/* Base64 of a byte stream, written as it is produced so that large
 * arrays need no second buffer. */
typedef struct {
    FILE *fp;
    unsigned char pending[3];
    int npending;
} b64;

static const char B64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

static void b64_emit(b64 *b)
{
    unsigned char *p = b->pending;
    char out[4];
    out[0] = B64[p[0] >> 2];
    out[1] = B64[((p[0] & 3) << 4) | (b->npending > 1 ? p[1] >> 4 : 0)];
    out[2] = b->npending > 1 ? B64[((p[1] & 15) << 2) | (b->npending > 2 ? p[2] >> 6 : 0)] : '=';
    out[3] = b->npending > 2 ? B64[p[2] & 63] : '=';
    fwrite(out, 1, 4, b->fp);
    b->npending = 0;
}

static void b64_put(b64 *b, const void *data, size_t n)
{
    const unsigned char *s = data;
    for (size_t i = 0; i < n; i++) {
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
static void write_binary(FILE *fp, const void *data, size_t nbytes)
{
    b64 b = {fp, {0}, 0};
    uint64_t header = nbytes;
    b64_put(&b, &header, sizeof header);
    b64_put(&b, data, nbytes);
    b64_finish(&b);
}

static void array_open(FILE *fp, const char *type, const char *name, int ncomp)
{
    fprintf(fp, "        <DataArray type=\"%s\"", type);
    if (name)
        fprintf(fp, " Name=\"%s\"", name);
    if (ncomp > 1)
        fprintf(fp, " NumberOfComponents=\"%d\"", ncomp);
    fputs(" format=\"binary\">\n          ", fp);
}

static void array_close(FILE *fp) { fputs("\n        </DataArray>\n", fp); }

static void write_arrays(FILE *fp, const fm_vtu_array *a, size_t na, size_t n)
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

static fm_status write_body(FILE *fp, const fm_vtu_content *c, fm_error *err, const char *path)
{
    size_t nv = fm_mesh_nvertices(c->mesh), nt = fm_mesh_ntriangles(c->mesh);
    fputs("<?xml version=\"1.0\"?>\n"
          "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
          "header_type=\"UInt64\">\n  <UnstructuredGrid>\n",
          fp);
    if (c->nfield_strings) {
        fputs("    <FieldData>\n", fp);
        for (size_t i = 0; i < c->nfield_strings; i++) {
            const fm_vtu_strings *s = &c->field_strings[i];
            size_t total = 0;
            for (size_t k = 0; k < s->count; k++)
                total += strlen(s->items[k]) + 1;
            fprintf(fp,
                    "      <DataArray type=\"UInt8\" Name=\"%s\" NumberOfTuples=\"%zu\" "
                    "format=\"binary\">\n          ",
                    s->name, total);
            b64 b = {fp, {0}, 0};
            uint64_t header = total;
            b64_put(&b, &header, sizeof header);
            for (size_t k = 0; k < s->count; k++)
                b64_put(&b, s->items[k], strlen(s->items[k]) + 1);
            b64_finish(&b);
            fputs("\n      </DataArray>\n", fp);
        }
        fputs("    </FieldData>\n", fp);
    }
    fprintf(fp, "    <Piece NumberOfPoints=\"%zu\" NumberOfCells=\"%zu\">\n", nv, nt);
    fputs("      <Points>\n", fp);
    array_open(fp, "Float64", "Points", 3);
    write_binary(fp, fm_mesh_vertices(c->mesh), nv * 3 * sizeof(double));
    array_close(fp);
    fputs("      </Points>\n      <Cells>\n", fp);
    array_open(fp, "Int32", "connectivity", 1);
    write_binary(fp, fm_mesh_triangles(c->mesh), nt * 3 * sizeof(int32_t));
    array_close(fp);

    /* offsets and types, streamed in chunks to stay small in memory */
    array_open(fp, "Int32", "offsets", 1);
    {
        b64 b = {fp, {0}, 0};
        uint64_t header = nt * sizeof(int32_t);
        b64_put(&b, &header, sizeof header);
        for (size_t t = 0; t < nt; t++) {
            int32_t off = (int32_t)(3 * (t + 1));
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
        const unsigned char tri = 5; /* VTK_TRIANGLE */
        for (size_t t = 0; t < nt; t++)
            b64_put(&b, &tri, 1);
        b64_finish(&b);
    }
    array_close(fp);
    fputs("      </Cells>\n", fp);
    if (c->npoint_data) {
        fputs("      <PointData>\n", fp);
        write_arrays(fp, c->point_data, c->npoint_data, nv);
        fputs("      </PointData>\n", fp);
    }
    if (c->ncell_data) {
        fputs("      <CellData>\n", fp);
        write_arrays(fp, c->cell_data, c->ncell_data, nt);
        fputs("      </CellData>\n", fp);
    }
    fputs("    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n", fp);
    if (ferror(fp))
        return fm_error_set(err, FM_ERR_IO, path, 0, "write failed");
    return FM_OK;
}

fm_status fm_vtu_write(const char *path, const fm_vtu_content *c, fm_error *err)
{
    if (!little_endian())
        return fm_error_set(err, FM_ERR_INVALID, path, 0,
                            "VTU output needs a little-endian machine");
    fm_atomic_file *f = fm_atomic_open(path, err);
    if (!f)
        return err ? err->code : FM_ERR_IO;
    fm_status s = write_body(fm_atomic_stream(f), c, err, path);
    if (s != FM_OK) {
        fm_atomic_abort(f);
        return s;
    }
    return fm_atomic_commit(f, err);
}
