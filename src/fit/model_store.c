/* A fitted model on disk and back (fm_model_save, fm_model_load; the
 * format is described in fm_model.h): the framing (magic, version, key,
 * length, checksum) and the model's sheets, samples and cuts; the
 * surfaces and trimming loops are in store_parts.c. */
#include "fm_model.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_atomic.h"
#include "fm_sha256.h"
#include "model_internal.h"
#include "model_store.h"
#include "store_parts.h"

#if UINTPTR_MAX == UINT64_MAX
_Static_assert(sizeof(fm_sheet_report) == 120, "store the new fm_sheet_report field");
_Static_assert(sizeof(sheet_model) == 168, "store the new sheet_model field");
_Static_assert(sizeof(fm_split_cut) == 40, "store the new fm_split_cut field");
_Static_assert(sizeof(struct fm_model) == 32, "store the new fm_model field");
#endif

static const unsigned char MAGIC[8] = {'F', 'M', 'M', 'O', 'D', 'E', 'L', 0x1a};
/* magic, version, reserved, key, payload length */
#define HEADER_BYTES (8 + 4 + 4 + FM_SHA256_BYTES + 8)

static void store_report(fm_store_out *o, const fm_sheet_report *r)
{
    fm_store_size(o, r->vertices);
    fm_store_size(o, r->triangles);
    fm_store_size(o, r->loops);
    fm_store_size(o, r->holes);
    fm_store_size(o, r->corners);
    fm_store_size(o, r->trim_pieces);
    fm_store_f64(o, r->to_surface_rms);
    fm_store_f64(o, r->to_surface_max);
    fm_store_f64(o, r->from_trimmed_rms);
    fm_store_f64(o, r->from_trimmed_max);
    fm_store_f64(o, r->outline_max);
    fm_store_f64(o, r->outline_rms);
    fm_store_size(o, r->samples);
    fm_store_size(o, r->repair_sheet);
    fm_store_f64(o, r->time);
}

static void load_report(fm_store_in *in, fm_sheet_report *r)
{
    r->vertices = fm_load_size(in);
    r->triangles = fm_load_size(in);
    r->loops = fm_load_size(in);
    r->holes = fm_load_size(in);
    r->corners = fm_load_size(in);
    r->trim_pieces = fm_load_size(in);
    r->to_surface_rms = fm_load_f64(in);
    r->to_surface_max = fm_load_f64(in);
    r->from_trimmed_rms = fm_load_f64(in);
    r->from_trimmed_max = fm_load_f64(in);
    r->outline_max = fm_load_f64(in);
    r->outline_rms = fm_load_f64(in);
    r->samples = fm_load_size(in);
    r->repair_sheet = fm_load_size(in);
    r->time = fm_load_f64(in);
}

/* A mesh (vertices, triangles, tags), or its absence. */
static void store_mesh(fm_store_out *o, const fm_mesh *m)
{
    fm_store_u32(o, m != NULL);
    if (!m)
        return;
    size_t nv = fm_mesh_nvertices(m), nt = fm_mesh_ntriangles(m);
    fm_store_size(o, nv);
    fm_store_size(o, nt);
    fm_store_f64s(o, fm_mesh_vertices(m), 3 * nv);
    fm_store_i32s(o, fm_mesh_triangles(m), 3 * nt);
    fm_store_i32s(o, fm_mesh_tags(m), nt);
}

static fm_mesh *load_mesh(fm_store_in *in, int *present)
{
    uint32_t flag = fm_load_u32(in);
    *present = flag == 1;
    if (flag > 1)
        in->failed = 1;
    if (flag != 1 || in->failed)
        return NULL;
    size_t nv = fm_load_count(in, 24), nt = fm_load_count(in, 16);
    double *X = fm_load_f64s(in, 3 * nv);
    int32_t *T = fm_load_i32s(in, 3 * nt), *tag = fm_load_i32s(in, nt);
    fm_mesh *m = in->failed ? NULL : fm_mesh_create();
    if (m && fm_mesh_reserve(m, nv, nt) != FM_OK) {
        fm_mesh_destroy(m);
        m = NULL;
    }
    for (size_t t = 0; m && t < 3 * nt; t++)
        if (T[t] < 0 || (size_t)T[t] >= nv) {
            fm_mesh_destroy(m);
            m = NULL;
        }
    for (size_t v = 0; m && v < nv; v++)
        fm_mesh_add_vertex(m, X[3 * v], X[3 * v + 1], X[3 * v + 2]);
    for (size_t t = 0; m && t < nt; t++)
        fm_mesh_add_triangle(m, T[3 * t], T[3 * t + 1], T[3 * t + 2], tag[t]);
    free(X);
    free(T);
    free(tag);
    if (!m)
        in->failed = 1;
    return m;
}

static void store_sheet(fm_store_out *o, const sheet_model *sm)
{
    store_surface(o, sm->surface);
    fm_store_size(o, sm->nloops);
    fm_store_u32(o, sm->loop_scale != NULL);
    if (sm->loop_scale)
        fm_store_f64s(o, sm->loop_scale, sm->nloops);
    for (size_t k = 0; k < sm->nloops; k++)
        store_loop(o, sm->loops[k]);
    store_mesh(o, sm->samples);
    size_t ns = sm->samples ? fm_mesh_nvertices(sm->samples) : 0;
    fm_store_u32(o, sm->sample_dist != NULL);
    if (sm->sample_dist)
        fm_store_f64s(o, sm->sample_dist, ns);
    store_report(o, &sm->report);
}

/* Into a zeroed sm; what it holds is freed with the model on failure. */
static void load_sheet(fm_store_in *in, sheet_model *sm)
{
    sm->surface = load_surface(in);
    size_t nl = fm_load_count(in, 100);
    uint32_t scaled = fm_load_u32(in);
    if (scaled > 1)
        in->failed = 1;
    if (scaled == 1)
        sm->loop_scale = nl ? fm_load_f64s(in, nl) : calloc(1, sizeof *sm->loop_scale);
    if (scaled == 1 && !sm->loop_scale)
        in->failed = 1;
    sm->loops = in->failed ? NULL : calloc(nl ? nl : 1, sizeof *sm->loops);
    if (!sm->loops)
        in->failed = 1;
    else
        sm->nloops = nl;
    for (size_t k = 0; k < sm->nloops && !in->failed; k++)
        sm->loops[k] = load_loop(in);
    int present;
    sm->samples = load_mesh(in, &present);
    size_t ns = sm->samples ? fm_mesh_nvertices(sm->samples) : 0;
    uint32_t measured = fm_load_u32(in);
    if (measured > 1 || (measured && !present))
        in->failed = 1;
    if (measured == 1 && ns)
        sm->sample_dist = fm_load_f64s(in, ns);
    else if (measured == 1)
        sm->sample_dist = calloc(1, sizeof *sm->sample_dist); /* as the fit leaves it */
    if (measured == 1 && !sm->sample_dist)
        in->failed = 1;
    load_report(in, &sm->report);
}

static void store_model(fm_store_out *o, const fm_model *m)
{
    fm_store_size(o, m->nsheets);
    for (size_t i = 0; i < m->nsheets; i++)
        store_sheet(o, &m->sheets[i]);
    fm_store_size(o, m->ncuts);
    for (size_t c = 0; c < m->ncuts; c++) {
        const fm_split_cut *cu = &m->cuts[c];
        fm_store_size(o, cu->n);
        fm_store_f64s(o, cu->xyz, 3 * cu->n);
        fm_store_i64(o, cu->sheets[0]);
        fm_store_i64(o, cu->sheets[1]);
        fm_store_size(o, cu->repair_sheet);
    }
}

static fm_model *load_model(fm_store_in *in)
{
    fm_model *m = calloc(1, sizeof *m);
    if (!m) {
        in->failed = 1;
        return NULL;
    }
    /* a sheet takes well over 500 bytes, a cut over 30 */
    size_t ns = fm_load_count(in, 500);
    m->sheets = in->failed ? NULL : calloc(ns ? ns : 1, sizeof *m->sheets);
    if (!m->sheets)
        in->failed = 1;
    else
        m->nsheets = ns;
    for (size_t i = 0; i < m->nsheets && !in->failed; i++)
        load_sheet(in, &m->sheets[i]);
    size_t nc = fm_load_count(in, 30);
    m->cuts = in->failed ? NULL : calloc(nc ? nc : 1, sizeof *m->cuts);
    if (!m->cuts)
        in->failed = 1;
    else
        m->ncuts = nc;
    for (size_t c = 0; c < m->ncuts && !in->failed; c++) {
        fm_split_cut *cu = &m->cuts[c];
        cu->n = fm_load_count(in, 24);
        cu->xyz = fm_load_f64s(in, 3 * cu->n);
        cu->sheets[0] = (long)fm_load_i64(in);
        cu->sheets[1] = (long)fm_load_i64(in);
        cu->repair_sheet = fm_load_size(in);
        if (!cu->xyz || cu->sheets[0] < -1 || cu->sheets[1] < -1 ||
            cu->sheets[0] >= (long)m->nsheets || cu->sheets[1] >= (long)m->nsheets)
            in->failed = 1;
    }
    /* every sheet whole: a surface and an outer loop */
    for (size_t i = 0; i < m->nsheets && !in->failed; i++) {
        const sheet_model *sm = &m->sheets[i];
        if (!sm->surface || !sm->nloops)
            in->failed = 1;
        for (size_t k = 0; k < sm->nloops && !in->failed; k++)
            if (!sm->loops[k])
                in->failed = 1;
    }
    if (!in->failed && in->at != in->n)
        in->failed = 1; /* bytes left over: not what was written */
    if (in->failed) {
        fm_model_destroy(m);
        return NULL;
    }
    return m;
}

fm_status model_store_write(const fm_model *m, const unsigned char *key, const char *path,
                            fm_error *err)
{
    fm_store_out o = {0};
    fm_store_raw(&o, MAGIC, sizeof MAGIC);
    fm_store_u32(&o, FM_MODEL_FORMAT_VERSION);
    fm_store_u32(&o, 0);
    unsigned char nokey[FM_SHA256_BYTES] = {0};
    fm_store_raw(&o, key ? key : nokey, FM_SHA256_BYTES);
    fm_store_u64(&o, 0); /* the payload's length, once known */
    store_model(&o, m);
    if (o.failed) {
        free(o.p);
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    uint64_t len = (uint64_t)(o.n - HEADER_BYTES);
    for (int i = 0; i < 8; i++)
        o.p[HEADER_BYTES - 8 + i] = (unsigned char)(len >> (8 * i));
    unsigned char digest[FM_SHA256_BYTES];
    fm_sha256_of(o.p, o.n, digest);
    fm_atomic_file *af = fm_atomic_open(path, err);
    if (!af) {
        free(o.p);
        return err ? err->code : FM_ERR_IO;
    }
    FILE *fp = fm_atomic_stream(af);
    int ok = fwrite(o.p, 1, o.n, fp) == o.n && fwrite(digest, 1, sizeof digest, fp) == sizeof digest;
    free(o.p);
    if (!ok) {
        fm_status st = fm_error_set(err, FM_ERR_IO, path, 0, "cannot write: %s", strerror(errno));
        fm_atomic_abort(af);
        return st;
    }
    return fm_atomic_commit(af, err);
}

/* The framing of buf (n bytes) checked: FM_OK when the payload can be
 * read. */
static fm_status check_frame(const unsigned char *buf, size_t n, const unsigned char *key,
                             const char *path, fm_error *err)
{
    if (n < sizeof MAGIC || memcmp(buf, MAGIC, sizeof MAGIC) != 0)
        return fm_error_set(err, FM_ERR_PARSE, path, 0, "not a faultmesh model");
    if (n < HEADER_BYTES + FM_SHA256_BYTES)
        return fm_error_set(err, FM_ERR_PARSE, path, 0, "truncated model (%zu bytes)", n);
    fm_store_in in = {buf, n, sizeof MAGIC, 0};
    uint32_t version = fm_load_u32(&in);
    fm_load_u32(&in);
    const unsigned char *stored_key = buf + in.at;
    in.at += FM_SHA256_BYTES;
    uint64_t len = fm_load_u64(&in);
    if (version != FM_MODEL_FORMAT_VERSION)
        return fm_error_set(err, FM_ERR_PARSE, path, 0,
                            "model format version %u, this faultmesh reads %d", version,
                            FM_MODEL_FORMAT_VERSION);
    if (len != (uint64_t)(n - HEADER_BYTES - FM_SHA256_BYTES))
        return fm_error_set(err, FM_ERR_PARSE, path, 0,
                            "truncated or extended model (%zu bytes, the header says %llu)", n,
                            (unsigned long long)len + HEADER_BYTES + FM_SHA256_BYTES);
    unsigned char digest[FM_SHA256_BYTES];
    fm_sha256_of(buf, n - FM_SHA256_BYTES, digest);
    if (memcmp(digest, buf + n - FM_SHA256_BYTES, FM_SHA256_BYTES) != 0)
        return fm_error_set(err, FM_ERR_PARSE, path, 0, "damaged model (checksum differs)");
    if (key && memcmp(key, stored_key, FM_SHA256_BYTES) != 0)
        return fm_error_set(err, FM_ERR_PARSE, path, 0,
                            "holds the model of another input or options (key differs)");
    return FM_OK;
}

fm_status model_store_read(const char *path, const unsigned char *key, fm_model **out,
                           fm_error *err)
{
    *out = NULL;
    size_t n = 0;
    unsigned char *buf = fm_read_file(path, &n, err);
    if (!buf)
        return err ? err->code : FM_ERR_IO;
    fm_status st = check_frame(buf, n, key, path, err);
    if (st == FM_OK) {
        fm_store_in in = {buf, n - FM_SHA256_BYTES, HEADER_BYTES, 0};
        *out = load_model(&in);
        if (!*out)
            st = fm_error_set(err, FM_ERR_PARSE, path, 0,
                              "damaged model (its contents do not add up)");
    }
    free(buf);
    return st;
}

fm_status fm_model_save(const fm_model *m, const char *path, fm_error *err)
{
    return model_store_write(m, NULL, path, err);
}

fm_status fm_model_load(const char *path, fm_model **out, fm_error *err)
{
    return model_store_read(path, NULL, out, err);
}
