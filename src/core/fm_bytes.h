/* faultmesh core: the little-endian byte stream of the files a run keeps
 * in its cache (fitted models, src/fit/model_store.c; the junction plan's
 * neighbours, src/connect/neighbours.c). Numbers are written in a fixed
 * order and width whatever the host (doubles as their IEEE-754 bits), so
 * what is stored reads back bit for bit. Errors are sticky: after a failed
 * allocation or a read past the end every call does nothing and the
 * caller checks `failed` once. */
#ifndef FM_BYTES_H
#define FM_BYTES_H

#include <stddef.h>
#include <stdint.h>

#include "fm_core.h"

typedef struct fm_store_out {
    unsigned char *p;
    size_t n, cap;
    int failed; /* out of memory */
} fm_store_out;

void fm_store_u32(fm_store_out *o, uint32_t v);
void fm_store_u64(fm_store_out *o, uint64_t v);
void fm_store_i32(fm_store_out *o, int32_t v);
void fm_store_i64(fm_store_out *o, int64_t v);
void fm_store_f64(fm_store_out *o, double v);
void fm_store_size(fm_store_out *o, size_t v);
/* n values (nothing when n is 0; p may then be NULL). */
void fm_store_f64s(fm_store_out *o, const double *p, size_t n);
void fm_store_i32s(fm_store_out *o, const int32_t *p, size_t n);
void fm_store_sizes(fm_store_out *o, const size_t *p, size_t n);
void fm_store_raw(fm_store_out *o, const void *p, size_t n);

typedef struct fm_store_in {
    const unsigned char *p;
    size_t n, at;
    int failed; /* truncated, or a count that cannot be right */
} fm_store_in;

uint32_t fm_load_u32(fm_store_in *in);
uint64_t fm_load_u64(fm_store_in *in);
int32_t fm_load_i32(fm_store_in *in);
int64_t fm_load_i64(fm_store_in *in);
double fm_load_f64(fm_store_in *in);
/* A size_t (fails if it does not fit one). */
size_t fm_load_size(fm_store_in *in);
/* A count of items of `bytes` bytes each that must still be in the
 * stream: so that a damaged count fails here instead of asking for
 * gigabytes. */
size_t fm_load_count(fm_store_in *in, size_t bytes);
/* n values into a new array (malloc'ed; NULL for n = 0 or on failure). */
double *fm_load_f64s(fm_store_in *in, size_t n);
int32_t *fm_load_i32s(fm_store_in *in, size_t n);
size_t *fm_load_sizes(fm_store_in *in, size_t n);
void fm_load_raw(fm_store_in *in, void *p, size_t n);

/* The whole file at path (malloc'ed, its length in *n); NULL (err set)
 * when it cannot be opened or read. */
unsigned char *fm_read_file(const char *path, size_t *n, fm_error *err);

#endif
