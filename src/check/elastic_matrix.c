/* The full interaction matrices of a small set (fm_check.h), as a NumPy
 * .npy file, which numpy.load reads as it is and whose layout is a
 * public one (the NumPy format's version 1.0): a user's simulator needs
 * no reader of ours. Rows are made a block at a time on the threads and
 * written in order, so memory stays a block and the bytes do not depend
 * on the thread count. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "elastic_internal.h"
#include "fm_atomic.h"
#include "fm_parallel.h"

#define BLOCK 64

typedef struct rows {
    const el_elem *el;
    const fm_elastic_options *opt;
    size_t n, first;
    double *v; /* BLOCK rows of n x 4 */
} rows;

static void row(void *user, size_t k)
{
    rows *r = user;
    size_t i = r->first + k;
    double *o = r->v + k * r->n * 4;
    for (size_t j = 0; j < r->n; j++, o += 4)
        /* NaN: an element left out (above the surface, degenerate), or a
         * receiver on the edge of the source, where the field has no value */
        if (r->el[i].state != EL_OK || r->el[j].state != EL_OK ||
            el_traction(&r->el[j], &r->el[i], r->opt, o))
            o[0] = o[1] = o[2] = o[3] = NAN;
}

/* The .npy header: magic, version 1.0, the dict padded so that the data
 * start on a multiple of 64 bytes, as numpy writes it. */
static void npy_header(FILE *fp, size_t n)
{
    char dict[128];
    int len = snprintf(dict, sizeof dict,
                       "{'descr': '<f8', 'fortran_order': False, 'shape': (%zu, %zu, 4), }", n, n);
    size_t total = 10 + (size_t)len + 1;
    size_t pad = (64 - total % 64) % 64;
    size_t hlen = (size_t)len + pad + 1;
    fwrite("\x93NUMPY\x01\x00", 1, 8, fp);
    fputc((int)(hlen & 0xff), fp);
    fputc((int)(hlen >> 8), fp);
    fwrite(dict, 1, (size_t)len, fp);
    for (size_t k = 0; k < pad; k++)
        fputc(' ', fp);
    fputc('\n', fp);
}

static void put_le(FILE *fp, const double *v, size_t n, unsigned char *buf)
{
    for (size_t k = 0; k < n; k++) {
        uint64_t u;
        memcpy(&u, &v[k], sizeof u);
        for (int b = 0; b < 8; b++)
            buf[8 * k + (size_t)b] = (unsigned char)(u >> (8 * b));
    }
    fwrite(buf, 8, n, fp);
}

fm_status fm_elastic_write_matrices(const fm_elastic_input *in, const fm_elastic_options *opt,
                                    const char *path, fm_error *err)
{
    size_t n = fm_mesh_ntriangles(in->set);
    if (n > FM_STIFFNESS_MAX_N)
        return fm_error_set(err, FM_ERR_INVALID, path, 0,
                            "the stiffness matrices of %zu elements would take %.3g GB; they "
                            "are written for at most %d elements (a larger size, or fewer "
                            "faults)",
                            n, 32.0 * (double)n * (double)n / 1e9, FM_STIFFNESS_MAX_N);
    if (!(opt->mu > 0) || !(opt->nu > -1 && opt->nu < 0.5))
        return fm_error_set(err, FM_ERR_INVALID, path, 0,
                            "stiffness matrices: needs mu > 0 and -1 < nu < 0.5");
    el_elem *el = malloc((n + 1) * sizeof *el);
    double *v = malloc((BLOCK * n * 4 + 1) * sizeof *v);
    unsigned char *buf = malloc(n * 4 * 8 + 1);
    if (!el || !v || !buf) {
        free(el);
        free(v);
        free(buf);
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    for (size_t t = 0; t < n; t++)
        el_elem_make(in->set, t, in->strike[t], in->dip[t], in->rake[t], &el[t]);
    fm_atomic_file *af = fm_atomic_open(path, err);
    fm_status st = af ? FM_OK : FM_ERR_IO;
    if (af) {
        FILE *fp = fm_atomic_stream(af);
        npy_header(fp, n);
        rows r = {el, opt, n, 0, v};
        for (size_t first = 0; first < n; first += BLOCK) {
            size_t m = n - first < BLOCK ? n - first : BLOCK;
            r.first = first;
            fm_parallel_for(m, opt->threads, row, &r, NULL, NULL, 0, m);
            for (size_t k = 0; k < m; k++)
                put_le(fp, v + k * n * 4, n * 4, buf);
        }
        st = fm_atomic_commit(af, err);
    }
    free(el);
    free(v);
    free(buf);
    return st;
}
