/* The little-endian byte stream of cached files, and a file read whole
 * (fm_bytes.h). */
#include "fm_bytes.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static int host_little_endian(void)
{
    const uint16_t one = 1;
    unsigned char b;
    memcpy(&b, &one, 1);
    return b == 1;
}

static unsigned char *room(fm_store_out *o, size_t n)
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

void fm_store_u32(fm_store_out *o, uint32_t v)
{
    unsigned char *d = room(o, 4);
    if (d)
        put_le(d, v, 4);
}

void fm_store_u64(fm_store_out *o, uint64_t v)
{
    unsigned char *d = room(o, 8);
    if (d)
        put_le(d, v, 8);
}

void fm_store_i32(fm_store_out *o, int32_t v) { fm_store_u32(o, (uint32_t)v); }
void fm_store_i64(fm_store_out *o, int64_t v) { fm_store_u64(o, (uint64_t)v); }
void fm_store_size(fm_store_out *o, size_t v) { fm_store_u64(o, (uint64_t)v); }

void fm_store_f64(fm_store_out *o, double v)
{
    uint64_t bits;
    memcpy(&bits, &v, sizeof bits);
    fm_store_u64(o, bits);
}

/* n items of `bytes` bytes at p, each as `bytes` little-endian bytes of
 * the unsigned integer with the same bits. */
static void store_items(fm_store_out *o, const void *p, size_t n, size_t bytes)
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

void fm_store_f64s(fm_store_out *o, const double *p, size_t n) { store_items(o, p, n, 8); }
void fm_store_i32s(fm_store_out *o, const int32_t *p, size_t n) { store_items(o, p, n, 4); }

void fm_store_sizes(fm_store_out *o, const size_t *p, size_t n)
{
    for (size_t i = 0; i < n; i++)
        fm_store_size(o, p[i]);
}

void fm_store_raw(fm_store_out *o, const void *p, size_t n)
{
    unsigned char *d = room(o, n);
    if (d && n)
        memcpy(d, p, n);
}

/* The next n bytes, or NULL (and failed) when fewer are left. */
static const unsigned char *take(fm_store_in *in, size_t n)
{
    if (in->failed || n > in->n - in->at) {
        in->failed = 1;
        return NULL;
    }
    const unsigned char *s = in->p + in->at;
    in->at += n;
    return s;
}

uint32_t fm_load_u32(fm_store_in *in)
{
    const unsigned char *s = take(in, 4);
    return s ? (uint32_t)get_le(s, 4) : 0;
}

uint64_t fm_load_u64(fm_store_in *in)
{
    const unsigned char *s = take(in, 8);
    return s ? get_le(s, 8) : 0;
}

int32_t fm_load_i32(fm_store_in *in)
{
    uint32_t u = fm_load_u32(in);
    int32_t v;
    memcpy(&v, &u, sizeof v);
    return v;
}

int64_t fm_load_i64(fm_store_in *in)
{
    uint64_t u = fm_load_u64(in);
    int64_t v;
    memcpy(&v, &u, sizeof v);
    return v;
}

double fm_load_f64(fm_store_in *in)
{
    uint64_t bits = fm_load_u64(in);
    double v;
    memcpy(&v, &bits, sizeof v);
    return v;
}

size_t fm_load_size(fm_store_in *in)
{
    uint64_t v = fm_load_u64(in);
    if (v > SIZE_MAX) {
        in->failed = 1;
        return 0;
    }
    return (size_t)v;
}

size_t fm_load_count(fm_store_in *in, size_t bytes)
{
    size_t v = fm_load_size(in);
    if (!in->failed && bytes && v > (in->n - in->at) / bytes) {
        in->failed = 1;
        return 0;
    }
    return in->failed ? 0 : v;
}

static void *load_items(fm_store_in *in, size_t n, size_t bytes)
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

double *fm_load_f64s(fm_store_in *in, size_t n) { return load_items(in, n, 8); }
int32_t *fm_load_i32s(fm_store_in *in, size_t n) { return load_items(in, n, 4); }

size_t *fm_load_sizes(fm_store_in *in, size_t n)
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
        p[i] = fm_load_size(in);
    return p;
}

void fm_load_raw(fm_store_in *in, void *p, size_t n)
{
    const unsigned char *s = take(in, n);
    if (s && n)
        memcpy(p, s, n);
}

unsigned char *fm_read_file(const char *path, size_t *n, fm_error *err)
{
    FILE *fp = fopen(path, "rb");
    if (!fp) {
        fm_error_set(err, FM_ERR_IO, path, 0, "cannot open: %s", strerror(errno));
        return NULL;
    }
    struct stat sb;
    unsigned char *buf = NULL;
    if (fstat(fileno(fp), &sb) == 0 && sb.st_size >= 0 && (uint64_t)sb.st_size < SIZE_MAX) {
        *n = (size_t)sb.st_size;
        buf = malloc(*n ? *n : 1);
        if (!buf)
            fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
        else if (fread(buf, 1, *n, fp) != *n) {
            fm_error_set(err, FM_ERR_IO, path, 0, "cannot read: %s",
                         ferror(fp) ? strerror(errno) : "shorter than it was");
            free(buf);
            buf = NULL;
        }
    } else {
        fm_error_set(err, FM_ERR_IO, path, 0, "cannot read: %s", strerror(errno));
    }
    fclose(fp);
    return buf;
}
