/* Sparse symmetric matrices assembled from element contributions, laid out
 * in the compressed upper columns fm_fit_spd_factor takes. */
#include "fit_internal.h"

#include <stdlib.h>
#include <string.h>

int fm_fit_triplets_add(fm_fit_triplets *q, size_t r, size_t c, double v)
{
    if (r > c)
        return 0; /* symmetric: the caller adds the mirrored entry as well */
    if (q->n == q->cap) {
        size_t cap = q->cap ? 2 * q->cap : 1024;
        fm_fit_triplet *ne = realloc(q->e, cap * sizeof *ne);
        if (!ne)
            return -1;
        q->e = ne;
        q->cap = cap;
    }
    q->e[q->n].row = r;
    q->e[q->n].col = c;
    q->e[q->n].val = v;
    q->n++;
    return 0;
}

void fm_fit_triplets_free(fm_fit_triplets *q)
{
    free(q->e);
    q->e = NULL;
    q->n = q->cap = 0;
}

/* Counting sort by column (it keeps insertion order), insertion sort by
 * row within a column (stable), then equal positions summed in that
 * order: the sums, and so the solution, depend on nothing but the order
 * of the contributions. */
fm_status fm_fit_triplets_compress(const fm_fit_triplets *q, size_t n, size_t **colptr,
                                   size_t **rowind, double **val)
{
    size_t m = q->n ? q->n : 1;
    size_t *cp = calloc(n + 1, sizeof *cp), *next = malloc((n ? n : 1) * sizeof *next);
    fm_fit_triplet *sorted = malloc(m * sizeof *sorted);
    size_t *ri = malloc(m * sizeof *ri);
    double *vv = malloc(m * sizeof *vv);
    if (!cp || !next || !sorted || !ri || !vv) {
        free(cp);
        free(next);
        free(sorted);
        free(ri);
        free(vv);
        return FM_ERR_NOMEM;
    }
    for (size_t k = 0; k < q->n; k++)
        cp[q->e[k].col + 1]++;
    for (size_t c = 0; c < n; c++)
        cp[c + 1] += cp[c];
    memcpy(next, cp, n * sizeof *next);
    for (size_t k = 0; k < q->n; k++)
        sorted[next[q->e[k].col]++] = q->e[k];
    free(next);
    size_t nnz = 0;
    for (size_t c = 0; c < n; c++) {
        fm_fit_triplet *col = sorted + cp[c];
        size_t len = cp[c + 1] - cp[c];
        for (size_t i = 1; i < len; i++) {
            fm_fit_triplet t = col[i];
            size_t j = i;
            while (j > 0 && col[j - 1].row > t.row) {
                col[j] = col[j - 1];
                j--;
            }
            col[j] = t;
        }
        cp[c] = nnz;
        for (size_t i = 0; i < len; i++) {
            if (i > 0 && col[i].row == col[i - 1].row) {
                vv[nnz - 1] += col[i].val;
                continue;
            }
            ri[nnz] = col[i].row;
            vv[nnz] = col[i].val;
            nnz++;
        }
    }
    cp[n] = nnz;
    free(sorted);
    *colptr = cp;
    *rowind = ri;
    *val = vv;
    return FM_OK;
}
