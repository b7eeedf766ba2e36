/* Fuzz target: a small fault surface decoded from the bytes goes through
 * repair, fit (fm_model_build) and the surface mesher (with the domain
 * boundaries the CLI asks for), as `faultmesh remesh` runs them, at a mesh
 * size relative to the surface's extent. Small (at most 49 vertices,
 * 96 triangles) so that an input runs in milliseconds. Failures returned
 * as fm_status are fine; what the mesher returns is checked for indices
 * in range and finite coordinates.
 *
 * Byte 0 picks the kind of surface:
 *  0: a perturbed grid of nx x ny points (2..7 each) on a dipping plane at
 *     kilometre scale, one diagonal per cell from a bit, cells dropped by
 *     other bits (holes, pinches, fragments);
 *  1: a triangle soup: points on a coarse lattice (exact collinearity and
 *     coplanarity are common there) and vertex triples from the bytes;
 *  2: the rest of the bytes as TSurf text (its first object, if small). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_model.h"
#include "fm_remesh.h"
#include "fm_repair.h"
#include "fm_tsurf.h"
#include "fuzz.h"

#define FUZZ_PI 3.14159265358979323846

enum { MAX_SIDE = 7, MAX_VERTICES = 49, MAX_TRIANGLES = 96 };

typedef struct bytes {
    const uint8_t *p;
    size_t n;
} bytes;

/* Past the end every byte reads 0, so that any input decodes. */
static unsigned next(bytes *b)
{
    if (b->n == 0)
        return 0;
    b->n--;
    return *b->p++;
}

static int next_s8(bytes *b)
{
    return (int)next(b) - 128;
}

static fm_mesh *decode_grid(bytes *b)
{
    int nx = 2 + (int)(next(b) % (MAX_SIDE - 1)), ny = 2 + (int)(next(b) % (MAX_SIDE - 1));
    double len = 1000.0 * (1 + next(b) % 20), wid = 1000.0 * (1 + next(b) % 15);
    double strike = next(b) * (2 * FUZZ_PI / 256), dip = (5 + next(b) % 86) * (FUZZ_PI / 180);
    double top = 2000.0 - 100.0 * next(b);
    /* in-plane jitter as a share of a cell, out-of-plane bumps in metres */
    double jitter = next(b) / 256.0, bump = 4.0 * next(b);
    int far = next(b) & 1; /* UTM-sized coordinates, as the CFM's */
    double ox = far ? 400000.0 : 0.0, oy = far ? 3700000.0 : 0.0;
    double sx = sin(strike), cx = cos(strike), cd = cos(dip), sd = sin(dip);
    double cell_s = len / (nx - 1), cell_d = wid / (ny - 1);
    fm_mesh *m = fm_mesh_create();
    if (!m)
        return NULL;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            double s = i * cell_s + jitter * cell_s * next_s8(b) / 128.0;
            double d = j * cell_d + jitter * cell_d * next_s8(b) / 128.0;
            double w = bump * next_s8(b) / 128.0;
            /* strike direction (sx, cx, 0); down dip (cx cd, -sx cd, -sd) */
            double x = ox + s * sx + d * cx * cd + w * cx * sd;
            double y = oy + s * cx - d * sx * cd - w * sx * sd;
            double z = top - d * sd + w * cd;
            fm_mesh_add_vertex(m, x, y, z);
        }
    unsigned drop = next(b); /* density of dropped cells, 0: none */
    for (int j = 0; j + 1 < ny; j++)
        for (int i = 0; i + 1 < nx; i++) {
            unsigned c = next(b);
            int32_t a = j * nx + i, bb = a + 1, cc = a + nx, dd = cc + 1;
            if (drop && c % 8 < drop % 4)
                continue;
            if (c & 0x80) {
                fm_mesh_add_triangle(m, a, bb, dd, 0);
                fm_mesh_add_triangle(m, a, dd, cc, 0);
            } else {
                fm_mesh_add_triangle(m, a, bb, cc, 0);
                fm_mesh_add_triangle(m, bb, dd, cc, 0);
            }
        }
    return m;
}

static fm_mesh *decode_soup(bytes *b)
{
    int nv = 3 + (int)(next(b) % (MAX_VERTICES - 2));
    int nt = 1 + (int)(next(b) % MAX_TRIANGLES);
    double step = 50.0 * (1 + next(b)), zstep = 50.0 * (1 + next(b));
    fm_mesh *m = fm_mesh_create();
    if (!m)
        return NULL;
    for (int v = 0; v < nv; v++) {
        double x = step * next_s8(b), y = step * next_s8(b), z = -zstep * (next(b) % 64);
        fm_mesh_add_vertex(m, x, y, z);
    }
    for (int t = 0; t < nt; t++) {
        int32_t a = (int32_t)(next(b) % nv), c = (int32_t)(next(b) % nv);
        int32_t d = (int32_t)(next(b) % nv);
        fm_mesh_add_triangle(m, a, c, d, (int32_t)(next(b) % 3));
    }
    return m;
}

static fm_mesh *decode_tsurf(bytes *b)
{
    fm_tsurf **objs = NULL;
    size_t n = 0;
    fm_error err;
    if (fm_tsurf_read_buffer("fuzz", (const char *)b->p, b->n, &objs, &n, &err) != FM_OK)
        return NULL;
    const fm_mesh *m = fm_tsurf_mesh(objs[0]);
    fm_mesh *copy = NULL;
    if (fm_mesh_nvertices(m) <= 2 * MAX_VERTICES && fm_mesh_ntriangles(m) <= MAX_TRIANGLES)
        copy = fm_mesh_clone(m);
    fm_tsurf_free_all(objs, n);
    return copy;
}

static void check_output(const fm_mesh *out, const int64_t *ids, const fm_model *model,
                         const fm_remesh_boundary *bounds)
{
    size_t nv = fm_mesh_nvertices(out), nt = fm_mesh_ntriangles(out);
    const double *x = fm_mesh_vertices(out);
    const int32_t *t = fm_mesh_triangles(out), *tag = fm_mesh_tags(out);
    for (size_t k = 0; k < 3 * nv; k++)
        if (!isfinite(x[k]))
            abort();
    for (size_t k = 0; k < 3 * nt; k++)
        if (t[k] < 0 || (size_t)t[k] >= nv)
            abort();
    for (size_t k = 0; k < nt; k++)
        if (tag[k] < 0 || (size_t)tag[k] >= fm_model_nsheets(model))
            abort();
    for (size_t v = 0; ids && v < nv; v++)
        if (ids[v] != -1)
            abort(); /* no shared curves were given */
    for (size_t s = 0; s < fm_model_nsheets(model); s++) {
        const fm_remesh_boundary *bd = &bounds[s];
        for (size_t l = 0; l < bd->nloops; l++)
            if (bd->start[l] > bd->start[l + 1] || bd->part[l] >= bd->nparts)
                abort();
        size_t np = bd->nloops ? bd->start[bd->nloops] : 0;
        for (size_t k = 0; k < 2 * np; k++)
            if (!isfinite(bd->uv[k]))
                abort();
    }
}

static void fit_and_mesh(const fm_mesh *in, bytes *b)
{
    fm_repair_options ro;
    fm_repair_options_default(&ro);
    unsigned flags = next(b);
    ro.weld_tolerance = (flags & 1) ? 10.0 * (flags >> 4) : 0.0;
    ro.drop_fragments = !(flags & 2);
    fm_surface *surf = NULL;
    fm_error err;
    if (fm_repair(in, &ro, &surf, &err) != FM_OK)
        return;
    fm_model_options mo;
    fm_remesh_model_options_default(&mo);
    /* fewer knot halvings than the default 3 make most inputs several times
     * faster; every count is still met */
    unsigned fit = next(b);
    mo.fit.max_refinements = (int)(fit % 4);
    fm_model *model = NULL;
    fm_status st = fm_model_build("fuzz", surf, &mo, &model, &err);
    fm_surface_destroy(surf);
    if (st != FM_OK)
        return;

    /* extent of the input, for a size and a sea level relative to it */
    const double *x = fm_mesh_vertices(in);
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < fm_mesh_nvertices(in); v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fmin(lo[k], x[3 * v + k]);
            hi[k] = fmax(hi[k], x[3 * v + k]);
        }
    double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    if (!(diag > 0) || !isfinite(diag)) {
        fm_model_destroy(model);
        return;
    }
    fm_remesh_options opt;
    fm_remesh_options_default(&opt);
    opt.name = "fuzz";
    opt.size = diag / (2 + next(b) % 14);
    unsigned top = next(b);
    opt.top = top % 3 == 0 ? FM_TOP_CUT : top % 3 == 1 ? FM_TOP_KEEP : FM_TOP_EXTEND;
    opt.top_extend = diag * next(b) / 256.0;
    if (top & 4) /* a sea level through the surface rather than at 0 */
        opt.sea_level = lo[2] + (hi[2] - lo[2]) * next(b) / 255.0;
    opt.optimise_passes = (int)(next(b) % 8);

    size_t ns = fm_model_nsheets(model);
    fm_remesh_boundary *bounds = calloc(ns + 1, sizeof *bounds);
    fm_mesh *out = NULL;
    int64_t *ids = NULL;
    fm_remesh_stats stats;
    if (bounds && fm_remesh_model_joined(model, NULL, &opt, &out, &ids, NULL, NULL, &stats,
                                         bounds, &err) == FM_OK) {
        check_output(out, ids, model, bounds);
        fm_mesh_destroy(out);
        free(ids);
    }
    for (size_t s = 0; bounds && s < ns; s++)
        fm_remesh_boundary_free(&bounds[s]);
    free(bounds);
    fm_model_destroy(model);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    bytes b = {data, size};
    unsigned kind = next(&b) % 3;
    /* the options come from the end, so that the TSurf text keeps the rest */
    bytes tail = {data + size, 0};
    if (size > 16) {
        tail.p = data + size - 8;
        tail.n = 8;
        b.n -= 8;
    }
    fm_mesh *m = kind == 0 ? decode_grid(&b) : kind == 1 ? decode_soup(&b) : decode_tsurf(&b);
    if (!m)
        return 0;
    if (fm_mesh_nvertices(m) > 0)
        fit_and_mesh(m, &tail);
    fm_mesh_destroy(m);
    return 0;
}
