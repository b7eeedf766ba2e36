/* The one place that talks to CHOLMOD: factor a sparse SPD matrix once,
 * solve with it as often as needed. */
#define _GNU_SOURCE /* RTLD_DEFAULT */
#include "fit_internal.h"

#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#include <cholmod.h>
#include <omp.h>

struct fm_fit_spd {
    cholmod_common c;
    cholmod_factor *L;
    size_t n;
};

void fm_fit_spd_destroy(fm_fit_spd *f)
{
    if (!f)
        return;
    cholmod_free_factor(&f->L, &f->c);
    cholmod_finish(&f->c);
    free(f);
}

static fm_status cholmod_failure(const cholmod_common *c, const char *what, const char *name,
                                 fm_error *err)
{
    return fm_error_set(err, c->status == CHOLMOD_OUT_OF_MEMORY ? FM_ERR_NOMEM : FM_ERR_NUMERIC,
                        name, 0, "fit: CHOLMOD %s failed (status %d)", what, c->status);
}

/* Debian's OpenBLAS builds are either thread-safe and multi-threaded
 * (libopenblas0-pthread, which setup.sh installs) or single-threaded but
 * unsafe to call from several threads at once (libopenblas0-serial: faults
 * fitted side by side then corrupt each other's buffers). So the
 * thread-safe build is told to use one thread, which also keeps results
 * independent of the machine's core count. Looked up at run time: the
 * reference BLAS, or another, simply has no such function. */
static void one_blas_thread(void)
{
    void (*set)(int);
    *(void **)&set = dlsym(RTLD_DEFAULT, "openblas_set_num_threads");
    if (set)
        set(1);
}

static pthread_once_t blas_once = PTHREAD_ONCE_INIT;

/* Analysis: with a fill-reducing order of the caller's (perm, n entries),
 * or CHOLMOD's own (AMD) without. */
static cholmod_factor *analyze(cholmod_sparse *A, const int *perm, cholmod_common *c)
{
    if (!perm)
        return cholmod_analyze(A, c);
    c->nmethods = 1;
    c->method[0].ordering = CHOLMOD_GIVEN;
    c->postorder = 1;
    return cholmod_analyze_p(A, (int *)perm, NULL, 0, c);
}

fm_status fm_fit_spd_factor(size_t n, const size_t *colptr, const size_t *rowind,
                            const double *values, fm_fit_spd **out, const char *name,
                            fm_error *err)
{
    return fm_fit_spd_factor_ordered(n, colptr, rowind, values, NULL, out, name, err);
}

fm_status fm_fit_spd_factor_ordered(size_t n, const size_t *colptr, const size_t *rowind,
                                    const double *values, const int *perm, fm_fit_spd **out,
                                    const char *name, fm_error *err)
{
    *out = NULL;
    size_t nnz = colptr[n];
    if (n == 0 || n > INT_MAX || nnz > INT_MAX)
        return fm_error_set(err, FM_ERR_INVALID, name, 0,
                            "fit: system of %zu unknowns and %zu entries is out of range", n, nnz);
    fm_fit_spd *f = calloc(1, sizeof *f);
    if (!f)
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (solver)");
    f->n = n;
    cholmod_start(&f->c);
    /* Library code never prints: CHOLMOD reports through c.status only. */
    f->c.print = 0;
    /* Supernodal LL': the dense blocks of a 2D stencil's separators go to
     * BLAS (OpenBLAS on one thread, see one_blas_thread; with it the
     * factorization is about twice as fast as the simplicial one). CHOLMOD
     * would also open an OpenMP team of 4 per supernode: on these systems
     * the team costs more than it saves, it would compete with the threads
     * that fit faults side by side, and one thread per solve keeps the
     * result independent of how many run. No active parallel levels makes
     * every team (of this thread) a team of one. */
    f->c.supernodal = CHOLMOD_SUPERNODAL;
    omp_set_max_active_levels(0);
    pthread_once(&blas_once, one_blas_thread);
    fm_status st = FM_OK;
    cholmod_sparse *A = cholmod_allocate_sparse(n, n, nnz, 1, 1, 1, CHOLMOD_REAL, &f->c);
    if (!A) {
        st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (sparse matrix)");
        goto done;
    }
    int *Ap = A->p, *Ai = A->i;
    double *Ax = A->x;
    for (size_t j = 0; j <= n; j++)
        Ap[j] = (int)colptr[j];
    for (size_t k = 0; k < nnz; k++) {
        Ai[k] = (int)rowind[k];
        Ax[k] = values[k];
    }
    f->L = analyze(A, perm, &f->c);
    if (!f->L || f->c.status < CHOLMOD_OK) {
        st = cholmod_failure(&f->c, "analysis", name, err);
        goto done;
    }
    cholmod_factorize(A, f->L, &f->c);
    if (f->c.status == CHOLMOD_NOT_POSDEF && f->L->is_super) {
        /* Rounding can leave a pivot of a nearly singular system (a margin
         * the smoothing alone holds) just under zero, which LL' refuses;
         * the simplicial LDL' carries such a pivot through, as the whole
         * fit did before the supernodal factorization. */
        cholmod_free_factor(&f->L, &f->c);
        f->c.status = CHOLMOD_OK;
        f->c.supernodal = CHOLMOD_SIMPLICIAL;
        f->L = analyze(A, perm, &f->c);
        if (!f->L || f->c.status < CHOLMOD_OK) {
            st = cholmod_failure(&f->c, "analysis", name, err);
            goto done;
        }
        cholmod_factorize(A, f->L, &f->c);
    }
    if (f->c.status == CHOLMOD_NOT_POSDEF || f->L->minor < n) {
        st = fm_error_set(err, FM_ERR_NUMERIC, name, 0,
                          "fit: normal equations not positive definite (column %zu of %zu); "
                          "is the sheet degenerate in the plane?",
                          (size_t)f->L->minor, n);
        goto done;
    }
    if (f->c.status < CHOLMOD_OK)
        st = cholmod_failure(&f->c, "factorization", name, err);
done:
    cholmod_free_sparse(&A, &f->c);
    if (st != FM_OK)
        fm_fit_spd_destroy(f);
    else
        *out = f;
    return st;
}

fm_status fm_fit_spd_solve(fm_fit_spd *f, const double *b, double *x, const char *name,
                           fm_error *err)
{
    cholmod_dense *B = cholmod_allocate_dense(f->n, 1, f->n, CHOLMOD_REAL, &f->c);
    if (!B)
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (solve)");
    memcpy(B->x, b, f->n * sizeof(double));
    cholmod_dense *X = cholmod_solve(CHOLMOD_A, f->L, B, &f->c);
    fm_status st = FM_OK;
    if (!X || f->c.status < CHOLMOD_OK)
        st = cholmod_failure(&f->c, "solve", name, err);
    else
        memcpy(x, X->x, f->n * sizeof(double));
    cholmod_free_dense(&X, &f->c);
    cholmod_free_dense(&B, &f->c);
    return st;
}
