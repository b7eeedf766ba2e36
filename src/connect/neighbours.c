/* The neighbours of a plan kept between runs (fm_connect.h): the sheet
 * pairs and near-duplicates, and every decided pair's intersection runs
 * as traced (connect_internal.h, cn_intersect_trace), which depend on the
 * models, D and the near-duplicate rule but not on H, stored by a key
 * over all of those.
 *
 * File layout (every number little-endian): "FMNB" and the format
 * version (u32); the key (32 bytes); the number of faults, pairs and
 * near-duplicates (u64 each); each pair's indices (u64) and values (f64,
 * their bits), each near-duplicate's likewise; then per pair, in order,
 * whether its runs are kept (u64 0 or 1) and if so the join distance they
 * were traced at (f64), their number (u64) and each run's closed flag and
 * point count (u64) and points (x then p, 7 f64 each); and the SHA-256 of
 * all that precedes it, so that a damaged or truncated file is
 * rejected. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "connect_internal.h"
#include "fm_atomic.h"
#include "fm_bytes.h"
#include "fm_connect_code.h"
#include "fm_model_cache.h"
#include "fm_sha256.h"

#define NB_MAGIC "FMNB"
#define NB_VERSION 2u

struct fm_connect_neighbours {
    size_t nfaults;
    fm_connect_pair *pair;
    size_t npairs;
    fm_connect_duplicate *dup;
    size_t ndup;
    cn_runs *runs;            /* per pair */
    double *run_distance;     /* per pair */
    unsigned char *has_runs;  /* per pair */
};

void fm_connect_neighbours_destroy(fm_connect_neighbours *nb)
{
    if (!nb)
        return;
    for (size_t k = 0; nb->runs && k < nb->npairs; k++)
        cn_runs_free(&nb->runs[k]);
    free(nb->runs);
    free(nb->run_distance);
    free(nb->has_runs);
    free(nb->pair);
    free(nb->dup);
    free(nb);
}

void cn_neighbours_view(const fm_connect_neighbours *nb, const fm_connect_pair **pair,
                        size_t *npairs, const fm_connect_duplicate **dup, size_t *ndup)
{
    *pair = nb->pair;
    *npairs = nb->npairs;
    *dup = nb->dup;
    *ndup = nb->ndup;
}

size_t cn_neighbours_nfaults(const fm_connect_neighbours *nb) { return nb->nfaults; }

const cn_runs *cn_neighbours_runs(const fm_connect_neighbours *nb, size_t k, double distance)
{
    /* the bits, as the key compares D */
    if (k >= nb->npairs || !nb->has_runs[k] ||
        memcmp(&nb->run_distance[k], &distance, sizeof distance) != 0)
        return NULL;
    return &nb->runs[k];
}

/* ---- key ---- */

void fm_connect_neighbours_key(const unsigned char (*model_keys)[FM_MODEL_KEY_BYTES], size_t n,
                               const fm_connect_plan_options *opt,
                               unsigned char key[FM_CONNECT_KEY_BYTES])
{
    fm_connect_plan_options o;
    if (opt)
        o = *opt;
    else
        fm_connect_plan_options_default(&o);
    fm_store_out b = {0};
    fm_store_raw(&b, NB_MAGIC, 4);
    fm_store_u64(&b, NB_VERSION);
    /* the code that finds them: connect and what it calls (core, fit) */
    fm_store_raw(&b, FM_CONNECT_CODE, strlen(FM_CONNECT_CODE) + 1);
    fm_store_raw(&b, fm_model_code_id(), strlen(fm_model_code_id()) + 1);
    fm_store_u64(&b, n);
    for (size_t f = 0; f < n; f++)
        fm_store_raw(&b, model_keys[f], FM_MODEL_KEY_BYTES);
    /* what they depend on: D bounds the search; the near-duplicate rule */
    fm_store_f64(&b, o.distance);
    fm_store_f64(&b, o.duplicates.tolerance);
    fm_store_f64(&b, o.duplicates.min_share);
    fm_store_u64(&b, (uint64_t)o.duplicates.keep);
    if (b.failed) {
        /* a key nobody stored: the neighbours are found again */
        memset(key, 0, FM_CONNECT_KEY_BYTES);
        key[0] = 1;
    } else {
        fm_sha256_of(b.p, b.n, key);
    }
    free(b.p);
}

/* ---- files ---- */

static char *nb_path(const char *dir, const unsigned char key[FM_CONNECT_KEY_BYTES])
{
    return fm_cache_key_path(dir, "connect", key, ".fmn");
}

fm_status fm_connect_neighbours_put(const char *dir, const unsigned char key[FM_CONNECT_KEY_BYTES],
                                    size_t nfaults, const fm_connect_plan *plan, fm_error *err)
{
    const fm_connect_pairs *pairs = fm_connect_plan_pairs(plan);
    size_t ndup;
    const fm_connect_duplicate *dup = fm_connect_plan_duplicates(plan, &ndup);
    fm_store_out b = {0};
    fm_store_raw(&b, NB_MAGIC, 4);
    fm_store_u32(&b, NB_VERSION);
    fm_store_raw(&b, key, FM_CONNECT_KEY_BYTES);
    size_t np = fm_connect_pairs_count(pairs);
    fm_store_u64(&b, nfaults);
    fm_store_u64(&b, np);
    fm_store_u64(&b, ndup);
    for (size_t i = 0; i < np; i++) {
        const fm_connect_pair *p = fm_connect_pairs_get(pairs, i);
        fm_store_u64(&b, p->fault_a);
        fm_store_u64(&b, p->sheet_a);
        fm_store_u64(&b, p->fault_b);
        fm_store_u64(&b, p->sheet_b);
        fm_store_f64(&b, p->distance);
        fm_store_u64(&b, (uint64_t)p->crosses);
        fm_store_f64(&b, p->trimmed_distance);
        fm_store_u64(&b, (uint64_t)p->trimmed_crosses);
        for (int k = 0; k < 3; k++)
            fm_store_f64(&b, p->point_a[k]);
        for (int k = 0; k < 3; k++)
            fm_store_f64(&b, p->point_b[k]);
    }
    for (size_t i = 0; i < ndup; i++) {
        const fm_connect_duplicate *d = &dup[i];
        fm_store_u64(&b, d->dropped);
        fm_store_u64(&b, d->kept);
        for (int k = 0; k < 2; k++)
            fm_store_f64(&b, d->share[k]);
        for (int k = 0; k < 2; k++)
            fm_store_f64(&b, d->area[k]);
        fm_store_f64(&b, d->cover);
        fm_store_u64(&b, (uint64_t)d->decided);
    }
    for (size_t k = 0; k < np; k++) {
        double dist = 0;
        const cn_runs *rs = cn_plan_runs(plan, k, &dist);
        fm_store_u64(&b, rs != NULL);
        if (!rs)
            continue;
        fm_store_f64(&b, dist);
        fm_store_u64(&b, rs->n);
        for (size_t i = 0; i < rs->n; i++) {
            const cn_run *q = &rs->r[i];
            fm_store_u64(&b, (uint64_t)q->closed);
            fm_store_u64(&b, q->n);
            for (size_t e = 0; e < 4 * q->n; e++)
                fm_store_f64(&b, q->x[e]);
            for (size_t e = 0; e < 3 * q->n; e++)
                fm_store_f64(&b, q->p[e]);
        }
    }
    unsigned char sum[FM_SHA256_BYTES];
    if (!b.failed) {
        fm_sha256_of(b.p, b.n, sum);
        fm_store_raw(&b, sum, sizeof sum);
    }
    char *path = b.failed ? NULL : nb_path(dir, key);
    if (!path) {
        free(b.p);
        return fm_error_set(err, FM_ERR_NOMEM, dir, 0, "out of memory");
    }
    fm_status st = fm_cache_key_folder(path, err);
    fm_atomic_file *af = st == FM_OK ? fm_atomic_open(path, err) : NULL;
    if (st == FM_OK && !af)
        st = err ? err->code : FM_ERR_IO;
    if (af) {
        if (fwrite(b.p, 1, b.n, fm_atomic_stream(af)) != b.n) {
            fm_atomic_abort(af);
            st = fm_error_set(err, FM_ERR_IO, path, 0, "cannot write");
        } else {
            st = fm_atomic_commit(af, err);
        }
    }
    free(path);
    free(b.p);
    return st;
}

static fm_status rejected(const char *path, fm_error *err, const char *why)
{
    return fm_error_set(err, FM_ERR_PARSE, path, 0, "connect cache: %s", why);
}

/* Every pair's runs, after the near-duplicates; 1 when they do not fit
 * the file (or memory ran out: then too the file goes unused). */
static int parse_runs(fm_store_in *r, fm_connect_neighbours *nb)
{
    size_t np = nb->npairs;
    nb->runs = calloc(np + 1, sizeof *nb->runs);
    nb->run_distance = calloc(np + 1, sizeof *nb->run_distance);
    nb->has_runs = calloc(np + 1, 1);
    if (!nb->runs || !nb->run_distance || !nb->has_runs)
        return 1;
    for (size_t k = 0; k < np; k++) {
        uint64_t has = fm_load_u64(r);
        if (r->failed || has > 1)
            return 1;
        if (!has)
            continue;
        nb->has_runs[k] = 1;
        nb->run_distance[k] = fm_load_f64(r);
        uint64_t nr = fm_load_u64(r);
        /* each run takes at least 2 numbers */
        if (r->failed || nr > (r->n - r->at) / 16)
            return 1;
        for (uint64_t i = 0; i < nr; i++) {
            uint64_t closed = fm_load_u64(r), n = fm_load_u64(r);
            if (r->failed || closed > 1 || n > (r->n - r->at) / 56)
                return 1;
            if (cn_runs_push(&nb->runs[k], (int)closed, n, NULL, NULL))
                return 1;
            cn_run *q = &nb->runs[k].r[nb->runs[k].n - 1];
            for (size_t e = 0; e < 4 * n; e++)
                q->x[e] = fm_load_f64(r);
            for (size_t e = 0; e < 3 * n; e++)
                q->p[e] = fm_load_f64(r);
        }
    }
    return r->failed;
}

/* The neighbours in bytes p[0 .. n-1], read back as stored under key. */
static fm_status parse(const char *path, const unsigned char *p, size_t n,
                       const unsigned char key[FM_CONNECT_KEY_BYTES], size_t nfaults,
                       fm_connect_neighbours **out, fm_error *err)
{
    if (n < 8 + FM_CONNECT_KEY_BYTES + 24 + FM_SHA256_BYTES || memcmp(p, NB_MAGIC, 4) != 0)
        return rejected(path, err, "not a neighbours file");
    unsigned char sum[FM_SHA256_BYTES];
    fm_sha256_of(p, n - FM_SHA256_BYTES, sum);
    if (memcmp(sum, p + n - FM_SHA256_BYTES, FM_SHA256_BYTES) != 0)
        return rejected(path, err, "damaged or truncated (checksum)");
    if (p[4] != NB_VERSION || p[5] || p[6] || p[7])
        return rejected(path, err, "another format version");
    if (memcmp(p + 8, key, FM_CONNECT_KEY_BYTES) != 0)
        return rejected(path, err, "stored under another key");
    fm_store_in r = {p, n - FM_SHA256_BYTES, 8 + FM_CONNECT_KEY_BYTES, 0};
    uint64_t nf = fm_load_u64(&r), np = fm_load_u64(&r), nd = fm_load_u64(&r);
    /* each pair takes 14 numbers, each near-duplicate 8 */
    if (r.failed || nf != nfaults || np > (r.n - r.at) / (14 * 8) ||
        nd > (r.n - r.at - np * 14 * 8) / (8 * 8))
        return rejected(path, err, "counts do not fit the file");
    fm_connect_neighbours *nb = calloc(1, sizeof *nb);
    if (nb) {
        nb->pair = malloc((np + 1) * sizeof *nb->pair);
        nb->dup = malloc((nd + 1) * sizeof *nb->dup);
    }
    if (!nb || !nb->pair || !nb->dup) {
        fm_connect_neighbours_destroy(nb);
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    nb->nfaults = nf;
    nb->npairs = np;
    nb->ndup = nd;
    int bad = 0;
    for (size_t i = 0; i < np; i++) {
        fm_connect_pair *q = &nb->pair[i];
        memset(q, 0, sizeof *q);
        q->fault_a = fm_load_u64(&r);
        q->sheet_a = fm_load_u64(&r);
        q->fault_b = fm_load_u64(&r);
        q->sheet_b = fm_load_u64(&r);
        q->distance = fm_load_f64(&r);
        q->crosses = (int)fm_load_u64(&r);
        q->trimmed_distance = fm_load_f64(&r);
        q->trimmed_crosses = (int)fm_load_u64(&r);
        for (int k = 0; k < 3; k++)
            q->point_a[k] = fm_load_f64(&r);
        for (int k = 0; k < 3; k++)
            q->point_b[k] = fm_load_f64(&r);
        bad |= q->fault_a >= nf || q->fault_b >= nf;
    }
    for (size_t i = 0; i < nd; i++) {
        fm_connect_duplicate *d = &nb->dup[i];
        memset(d, 0, sizeof *d);
        d->dropped = fm_load_u64(&r);
        d->kept = fm_load_u64(&r);
        for (int k = 0; k < 2; k++)
            d->share[k] = fm_load_f64(&r);
        for (int k = 0; k < 2; k++)
            d->area[k] = fm_load_f64(&r);
        d->cover = fm_load_f64(&r);
        d->decided = (int)fm_load_u64(&r);
        bad |= d->dropped >= nf || d->kept >= nf;
    }
    bad = bad || r.failed || parse_runs(&r, nb);
    if (r.failed || bad || r.at != r.n) {
        fm_connect_neighbours_destroy(nb);
        return rejected(path, err, "fault indices or length do not fit");
    }
    *out = nb;
    return FM_OK;
}

fm_status fm_connect_neighbours_get(const char *dir, const unsigned char key[FM_CONNECT_KEY_BYTES],
                                    size_t nfaults, fm_connect_neighbours **out, fm_error *err)
{
    *out = NULL;
    char *path = nb_path(dir, key);
    if (!path)
        return fm_error_set(err, FM_ERR_NOMEM, dir, 0, "out of memory");
    fm_status st = FM_OK;
    if (access(path, F_OK) == 0) { /* none stored yet: no error */
        size_t n = 0;
        unsigned char *p = fm_read_file(path, &n, err);
        st = p ? parse(path, p, n, key, nfaults, out, err) : err ? err->code : FM_ERR_IO;
        free(p);
    }
    free(path);
    return st;
}
