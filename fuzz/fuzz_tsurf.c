/* Fuzz target: the TSurf reader on arbitrary bytes, then what a reader's
 * output meets next: repair of every object read (default options and a
 * tolerance weld), and the writer, whose output must read back and write
 * again to the same bytes (the writer's contract for files it wrote). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_repair.h"
#include "fm_tsurf.h"
#include "fuzz.h"

/* Repaired surfaces are walked so that every accessor's array is read
 * (ASan then sees an undersized one). */
static void touch_surface(const fm_surface *s)
{
    volatile double sink = 0;
    for (size_t i = 0; i < fm_surface_nsheets(s); i++) {
        const fm_mesh *m = fm_surface_sheet_mesh(s, i);
        const int32_t *t = fm_mesh_triangles(m);
        const int32_t *vo = fm_surface_sheet_vertex_origin(s, i);
        const int32_t *to = fm_surface_sheet_triangle_origin(s, i);
        for (size_t k = 0; k < 3 * fm_mesh_ntriangles(m); k++)
            if (t[k] < 0 || (size_t)t[k] >= fm_mesh_nvertices(m))
                abort();
        for (size_t v = 0; v < fm_mesh_nvertices(m); v++)
            sink += vo[v];
        for (size_t k = 0; k < fm_mesh_ntriangles(m); k++)
            sink += to[k];
        for (size_t l = 0; l < fm_surface_sheet_nloops(s, i); l++) {
            size_t n = 0;
            const int32_t *loop = fm_surface_sheet_loop(s, i, l, &n);
            for (size_t k = 0; k < n; k++)
                if (loop[k] < 0 || (size_t)loop[k] >= fm_mesh_nvertices(m))
                    abort();
        }
        double nrm[3];
        fm_surface_sheet_normal(s, i, nrm);
        sink += nrm[0];
    }
    for (size_t j = 0; j < fm_surface_njunctions(s); j++) {
        size_t np = 0, ns = 0;
        const double *p = fm_surface_junction_points(s, j, &np);
        const int32_t *sh = fm_surface_junction_sheets(s, j, &ns);
        for (size_t k = 0; k < 3 * np; k++)
            sink += p[k];
        for (size_t k = 0; k < ns; k++)
            if (sh[k] < 0 || (size_t)sh[k] >= fm_surface_nsheets(s))
                abort();
    }
    (void)sink;
}

static void repair_all(fm_tsurf **objs, size_t n)
{
    fm_repair_options opt;
    fm_repair_options_default(&opt);
    for (size_t i = 0; i < n; i++) {
        for (int pass = 0; pass < 2; pass++) {
            opt.weld_tolerance = pass ? 1.0 : 0.0;
            fm_surface *s = NULL;
            fm_error err;
            if (fm_repair(fm_tsurf_mesh(objs[i]), &opt, &s, &err) == FM_OK) {
                touch_surface(s);
                fm_surface_destroy(s);
            }
        }
    }
}

/* The objects written to memory; NULL when the writer refuses them. */
static char *write_all(fm_tsurf **objs, size_t n, size_t *len)
{
    char *buf = NULL;
    FILE *fp = open_memstream(&buf, len);
    if (!fp)
        abort();
    fm_error err;
    fm_status st = fm_tsurf_write_stream(fp, "fuzz", objs, n, &err);
    fclose(fp);
    if (st != FM_OK) {
        free(buf);
        return NULL;
    }
    return buf;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fm_tsurf **objs = NULL;
    size_t n = 0;
    fm_error err;
    if (fm_tsurf_read_buffer("fuzz", (const char *)data, size, &objs, &n, &err) != FM_OK)
        return 0;
    repair_all(objs, n);

    size_t len1 = 0;
    char *out1 = write_all(objs, n, &len1);
    fm_tsurf_free_all(objs, n);
    if (!out1)
        return 0;
    /* what the writer wrote, the reader must read, and write the same */
    fm_tsurf **again = NULL;
    size_t n2 = 0;
    if (fm_tsurf_read_buffer("fuzz-again", out1, len1, &again, &n2, &err) != FM_OK) {
        fprintf(stderr, "written TSurf does not read back: %s\n", err.message);
        abort();
    }
    size_t len2 = 0;
    char *out2 = write_all(again, n2, &len2);
    fm_tsurf_free_all(again, n2);
    if (!out2 || len1 != len2 || memcmp(out1, out2, len1) != 0) {
        fprintf(stderr, "written TSurf changes when read and written again\n");
        abort();
    }
    free(out1);
    free(out2);
    return 0;
}
