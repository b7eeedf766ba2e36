/* The fit cache's key (fm_model_cache.h): SHA-256 over the format, the
 * code, the input triangulation and the options, each number in a fixed
 * little-endian form so that the key does not depend on the host. */
#include "fm_model_cache.h"

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include <cholmod.h>
#include <lapacke.h>

#include "fm_fit_code.h"
#include "fm_sha256.h"
#include "fm_bytes.h"

/* Raised when the key's layout below changes. */
#define KEY_LAYOUT 1

/* A field added to the options must be added to the key below, or a run
 * with another value of it would read the model of the old one: these
 * sizes are those of the fields hashed (LP64), so a new one stops the
 * build here. */
#if UINTPTR_MAX == UINT64_MAX
_Static_assert(sizeof(fm_repair_options) == 40, "add the new repair option to the key");
_Static_assert(sizeof(fm_fit_frame_options) == 32, "add the new frame option to the key");
_Static_assert(sizeof(fm_fit_options) == 152, "add the new fit option to the key");
_Static_assert(sizeof(fm_trim_options) == 80, "add the new trim option to the key");
_Static_assert(sizeof(fm_model_options) == 240, "add the new model option to the key");
#endif

static char libraries[512];
static pthread_once_t libraries_once = PTHREAD_ONCE_INIT;

/* The numerical libraries as loaded (they may differ from those built
 * against, and OpenBLAS picks its kernels for the CPU): a model fitted
 * with others may differ in its last bits. */
static void find_libraries(void)
{
    int cv[3] = {0, 0, 0};
    cholmod_version(cv);
    lapack_int lv[3] = {0, 0, 0};
    LAPACKE_ilaver(&lv[0], &lv[1], &lv[2]);
    char *(*config)(void), *(*core)(void);
    *(void **)&config = dlsym(RTLD_DEFAULT, "openblas_get_config");
    *(void **)&core = dlsym(RTLD_DEFAULT, "openblas_get_corename");
    snprintf(libraries, sizeof libraries, "CHOLMOD %d.%d.%d; LAPACK %d.%d.%d; %s; %s", cv[0],
             cv[1], cv[2], (int)lv[0], (int)lv[1], (int)lv[2],
             config ? config() : "no OpenBLAS", core ? core() : "");
}

static char code_id[2 * FM_SHA256_BYTES + 1];
static pthread_once_t code_once = PTHREAD_ONCE_INIT;

static void find_code_id(void)
{
    pthread_once(&libraries_once, find_libraries);
    unsigned char d[FM_SHA256_BYTES];
    fm_sha256 c;
    fm_sha256_init(&c);
    fm_sha256_update(&c, FM_FIT_CODE, strlen(FM_FIT_CODE) + 1);
    fm_sha256_update(&c, libraries, strlen(libraries) + 1);
    fm_sha256_final(&c, d);
    fm_sha256_hex(d, code_id);
}

const char *fm_model_code_id(void)
{
    pthread_once(&code_once, find_code_id);
    return code_id;
}

/* The fields go through a fixed little-endian buffer into the hash: it
 * never grows (room flushes it first), so it cannot fail and leave a
 * field out of the key. */
#define SLICE 2048 /* array items per pass */

typedef struct key_state {
    fm_sha256 sha;
    fm_store_out buf;
    unsigned char space[SLICE * sizeof(double)];
} key_state;

static void flush(key_state *k)
{
    if (k->buf.n)
        fm_sha256_update(&k->sha, k->buf.p, k->buf.n);
    k->buf.n = 0;
}

static void room(key_state *k, size_t bytes)
{
    if (k->buf.cap - k->buf.n < bytes)
        flush(k);
}

static void key_f64(key_state *k, double v)
{
    room(k, 8);
    fm_store_f64(&k->buf, v);
}

static void key_int(key_state *k, long long v)
{
    room(k, 8);
    fm_store_i64(&k->buf, (int64_t)v);
}

static void key_size(key_state *k, size_t v)
{
    room(k, 8);
    fm_store_size(&k->buf, v);
}

static void key_string(key_state *k, const char *s)
{
    size_t n = strlen(s);
    key_size(k, n);
    flush(k);
    fm_sha256_update(&k->sha, s, n);
}

static void key_f64s(key_state *k, const double *p, size_t n)
{
    for (size_t i = 0; i < n; i += SLICE) {
        flush(k);
        fm_store_f64s(&k->buf, p + i, n - i < SLICE ? n - i : SLICE);
    }
}

static void key_i32s(key_state *k, const int32_t *p, size_t n)
{
    for (size_t i = 0; i < n; i += SLICE) {
        flush(k);
        fm_store_i32s(&k->buf, p + i, n - i < SLICE ? n - i : SLICE);
    }
}

static void key_repair(key_state *k, const fm_repair_options *r)
{
    key_f64(k, r->weld_tolerance);
    key_size(k, r->min_fragment_triangles);
    key_f64(k, r->min_fragment_area_fraction);
    key_int(k, r->drop_fragments);
    key_int(k, r->split_nonmanifold);
    key_int(k, r->orient);
}

/* fit.name and trim.name are for messages; trim.corner_at is set per loop
 * by the model (model.c, fit_loops) whatever the options hold. */
static void key_model(key_state *k, const fm_model_options *o)
{
    const fm_fit_options *f = &o->fit;
    key_int(k, f->kind);
    for (int i = 0; i < 3; i++)
        key_f64(k, f->frame.direction[i]);
    key_f64(k, f->frame.slack_degrees);
    key_int(k, f->degree);
    key_f64(k, f->extend);
    key_f64(k, f->knot_spacing);
    key_f64(k, f->knot_factor);
    key_size(k, f->max_control_points);
    key_f64(k, f->target_rms);
    key_f64(k, f->target_max);
    key_int(k, f->max_refinements);
    key_f64(k, f->smoothing);
    key_f64(k, f->smoothing_wavelength);
    key_int(k, f->chord_passes);
    key_f64(k, f->chord_weight);
    key_int(k, f->closest_point_stats);
    const fm_trim_options *t = &o->trim;
    key_f64(k, t->tolerance);
    key_f64(k, t->corner_angle);
    key_f64(k, t->corner_window);
    key_f64(k, t->knot_spacing);
    key_f64(k, t->knot_factor);
    key_f64(k, t->smoothing_wavelength);
    key_int(k, t->max_refinements);
    key_f64(k, t->max_deviation);
    key_int(k, o->sample_levels);
    key_int(k, o->measure_samples);
}

void fm_model_key(const fm_mesh *input, const fm_repair_options *repair,
                  const fm_model_options *opt, unsigned char key[FM_MODEL_KEY_BYTES])
{
    fm_repair_options rdef;
    fm_model_options mdef;
    if (!repair) {
        fm_repair_options_default(&rdef);
        repair = &rdef;
    }
    if (!opt) {
        fm_model_options_default(&mdef);
        opt = &mdef;
    }
    key_state k;
    fm_sha256_init(&k.sha);
    k.buf = (fm_store_out){k.space, 0, sizeof k.space, 0};
    key_string(&k, "faultmesh fit cache key");
    key_int(&k, FM_MODEL_FORMAT_VERSION);
    key_int(&k, KEY_LAYOUT);
    key_string(&k, fm_model_code_id());
    key_repair(&k, repair);
    key_model(&k, opt);
    size_t nv = fm_mesh_nvertices(input), nt = fm_mesh_ntriangles(input);
    key_size(&k, nv);
    key_size(&k, nt);
    key_f64s(&k, fm_mesh_vertices(input), 3 * nv);
    key_i32s(&k, fm_mesh_triangles(input), 3 * nt);
    key_i32s(&k, fm_mesh_tags(input), nt);
    flush(&k);
    fm_sha256_final(&k.sha, key);
}
