/* Private to src/fit: the little-endian byte stream a fitted model is
 * stored as (model_store.c, store_parts.c). Numbers are written in a fixed
 * order and width whatever the host (doubles as their IEEE-754 bits), so
 * a model reads back bit for bit. Errors are sticky: after a failed
 * allocation or a read past the end every call does nothing and the
 * caller checks `failed` once. */
#ifndef FM_STORE_BYTES_H
#define FM_STORE_BYTES_H

#include <stddef.h>
#include <stdint.h>

typedef struct store_out {
    unsigned char *p;
    size_t n, cap;
    int failed; /* out of memory */
} store_out;

void store_u32(store_out *o, uint32_t v);
void store_u64(store_out *o, uint64_t v);
void store_i32(store_out *o, int32_t v);
void store_i64(store_out *o, int64_t v);
void store_f64(store_out *o, double v);
void store_size(store_out *o, size_t v);
/* n values (nothing when n is 0; p may then be NULL). */
void store_f64s(store_out *o, const double *p, size_t n);
void store_i32s(store_out *o, const int32_t *p, size_t n);
void store_sizes(store_out *o, const size_t *p, size_t n);
void store_raw(store_out *o, const void *p, size_t n);

typedef struct store_in {
    const unsigned char *p;
    size_t n, at;
    int failed; /* truncated, or a count that cannot be right */
} store_in;

uint32_t load_u32(store_in *in);
uint64_t load_u64(store_in *in);
int32_t load_i32(store_in *in);
int64_t load_i64(store_in *in);
double load_f64(store_in *in);
/* A size_t (fails if it does not fit one). */
size_t load_size(store_in *in);
/* A count of items of `bytes` bytes each that must still be in the
 * stream: so that a damaged count fails here instead of asking for
 * gigabytes. */
size_t load_count(store_in *in, size_t bytes);
/* n values into a new array (malloc'ed; NULL for n = 0 or on failure). */
double *load_f64s(store_in *in, size_t n);
int32_t *load_i32s(store_in *in, size_t n);
size_t *load_sizes(store_in *in, size_t n);
void load_raw(store_in *in, void *p, size_t n);

#endif
