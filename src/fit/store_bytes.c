/* The little-endian byte stream of stored models (store_bytes.h). */
#include "store_bytes.h"

#include <stdlib.h>
#include <string.h>

static int host_little_endian(void)
{
    const uint16_t one = 1;
    unsigned char b;
    memcpy(&b, &one, 1);
    return b == 1;
}

static unsigned char *room(store_out *o, size_t n)
{
    if (o->failed)
        return NULL;
    if (n > SIZE_MAX - o->n) {
        o->failed = 1;
        return NULL;
    }
    if (o->n + n > o->cap) {
        size_t cap = o->cap ? o->cap : 4096;
        while (cap < o->n + n)
            cap = cap > SIZE_MAX / 2 ? o->n + n : 2 * cap;
        unsigned char *g = realloc(o->p, cap);
        if (!g) {
            o->failed = 1;
            return NULL;
        }
        o->p = g;
        o->cap = cap;
    }
    unsigned char *at = o->p + o->n;
    o->n += n;
    return at;
}

static void put_le(unsigned char *d, uint64_t v, int bytes)
{
    for (int i = 0; i < bytes; i++)
        d[i] = (unsigned char)(v >> (8 * i));
}

static uint64_t get_le(const unsigned char *s, int bytes)
{
    uint64_t v = 0;
    for (int i = 0; i < bytes; i++)
        v |= (uint64_t)s[i] << (8 * i);
    return v;
}

void store_u32(store_out *o, uint32_t v)
{
    unsigned char *d = room(o, 4);
    if (d)
        put_le(d, v, 4);
}

void store_u64(store_out *o, uint64_t v)
{
    unsigned char *d = room(o, 8);
    if (d)
        put_le(d, v, 8);
}

void store_i32(store_out *o, int32_t v) { store_u32(o, (uint32_t)v); }
void store_i64(store_out *o, int64_t v) { store_u64(o, (uint64_t)v); }
void store_size(store_out *o, size_t v) { store_u64(o, (uint64_t)v); }

void store_f64(store_out *o, double v)
{
    uint64_t bits;
    memcpy(&bits, &v, sizeof bits);
    store_u64(o, bits);
}

/* n items of `bytes` bytes at p, each as `bytes` little-endian bytes of
 * the unsigned integer with the same bits. */
static void store_items(store_out *o, const void *p, size_t n, size_t bytes)
{
    if (!n)
        return;
    if (n > SIZE_MAX / bytes) {
        o->failed = 1;
        return;
    }
    unsigned char *d = room(o, n * bytes);
    if (!d)
        return;
    if (host_little_endian()) {
        memcpy(d, p, n * bytes);
        return;
    }
    const unsigned char *s = p;
    for (size_t i = 0; i < n; i++, s += bytes, d += bytes) {
        uint64_t v = 0;
        if (bytes == 8) {
            memcpy(&v, s, 8);
        } else {
            uint32_t w;
            memcpy(&w, s, 4);
            v = w;
        }
        put_le(d, v, (int)bytes);
    }
}

void store_f64s(store_out *o, const double *p, size_t n) { store_items(o, p, n, 8); }
void store_i32s(store_out *o, const int32_t *p, size_t n) { store_items(o, p, n, 4); }

void store_sizes(store_out *o, const size_t *p, size_t n)
{
    for (size_t i = 0; i < n; i++)
        store_size(o, p[i]);
}

void store_raw(store_out *o, const void *p, size_t n)
{
    unsigned char *d = room(o, n);
    if (d && n)
        memcpy(d, p, n);
}

/* The next n bytes, or NULL (and failed) when fewer are left. */
static const unsigned char *take(store_in *in, size_t n)
{
    if (in->failed || n > in->n - in->at) {
        in->failed = 1;
        return NULL;
    }
    const unsigned char *s = in->p + in->at;
    in->at += n;
    return s;
}

uint32_t load_u32(store_in *in)
{
    const unsigned char *s = take(in, 4);
    return s ? (uint32_t)get_le(s, 4) : 0;
}

uint64_t load_u64(store_in *in)
{
    const unsigned char *s = take(in, 8);
    return s ? get_le(s, 8) : 0;
}

int32_t load_i32(store_in *in)
{
    uint32_t u = load_u32(in);
    int32_t v;
    memcpy(&v, &u, sizeof v);
    return v;
}

int64_t load_i64(store_in *in)
{
    uint64_t u = load_u64(in);
    int64_t v;
    memcpy(&v, &u, sizeof v);
    return v;
}

double load_f64(store_in *in)
{
    uint64_t bits = load_u64(in);
    double v;
    memcpy(&v, &bits, sizeof v);
    return v;
}

size_t load_size(store_in *in)
{
    uint64_t v = load_u64(in);
    if (v > SIZE_MAX) {
        in->failed = 1;
        return 0;
    }
    return (size_t)v;
}

size_t load_count(store_in *in, size_t bytes)
{
    size_t v = load_size(in);
    if (!in->failed && bytes && v > (in->n - in->at) / bytes) {
        in->failed = 1;
        return 0;
    }
    return in->failed ? 0 : v;
}

static void *load_items(store_in *in, size_t n, size_t bytes)
{
    if (!n || in->failed)
        return NULL;
    if (n > SIZE_MAX / bytes) {
        in->failed = 1;
        return NULL;
    }
    const unsigned char *s = take(in, n * bytes);
    void *p = s ? malloc(n * bytes) : NULL;
    if (!p) {
        in->failed = 1;
        return NULL;
    }
    if (host_little_endian()) {
        memcpy(p, s, n * bytes);
        return p;
    }
    unsigned char *d = p;
    for (size_t i = 0; i < n; i++, s += bytes, d += bytes) {
        uint64_t v = get_le(s, (int)bytes);
        if (bytes == 8) {
            memcpy(d, &v, 8);
        } else {
            uint32_t w = (uint32_t)v;
            memcpy(d, &w, 4);
        }
    }
    return p;
}

double *load_f64s(store_in *in, size_t n) { return load_items(in, n, 8); }
int32_t *load_i32s(store_in *in, size_t n) { return load_items(in, n, 4); }

size_t *load_sizes(store_in *in, size_t n)
{
    if (!n || in->failed)
        return NULL;
    if (n > (in->n - in->at) / 8) {
        in->failed = 1;
        return NULL;
    }
    size_t *p = malloc(n * sizeof *p);
    if (!p) {
        in->failed = 1;
        return NULL;
    }
    for (size_t i = 0; i < n; i++)
        p[i] = load_size(in);
    return p;
}

void load_raw(store_in *in, void *p, size_t n)
{
    const unsigned char *s = take(in, n);
    if (s && n)
        memcpy(p, s, n);
}
