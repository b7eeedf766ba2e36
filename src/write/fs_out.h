/* A block buffer in front of a stream for the writers of src/write (private).
 *
 * Millions of short items (numbers, separators) go through it; one stdio
 * call each, with the stream's lock and checks, was most of the time of
 * writing a fault set. Write errors are remembered and reported once, at
 * fs_out_finish. */
#ifndef FS_OUT_H
#define FS_OUT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "fm_atomic.h"

#define FS_OUT_BLOCK (1 << 16)

typedef struct fs_out {
    FILE *fp;
    size_t n;
    int failed; /* errno of the first failed write, 0 if none */
    char buf[FS_OUT_BLOCK];
} fs_out;

/* A buffer for fp, NULL when memory runs out. */
fs_out *fs_out_open(FILE *fp);
/* Flushes and frees o; 0, or the errno of the first write that failed. */
int fs_out_finish(fs_out *o);
/* The end of every writer: finishes o, then renames af into place, or
 * removes it if any write failed ("write failed: " and the system's
 * reason, naming path). */
fm_status fs_out_commit(fs_out *o, fm_atomic_file *af, const char *path, fm_error *err);
void fs_out_flush(fs_out *o);
void fs_out_bytes(fs_out *o, const void *p, size_t n);
/* For the rare formatted line (headers); at most 512 bytes. */
void fs_out_printf(fs_out *o, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void fs_out_double(fs_out *o, double v);

/* Room for n more bytes (n at most a few hundred). */
static inline char *fs_out_room(fs_out *o, size_t n)
{
    if (o->n + n > FS_OUT_BLOCK)
        fs_out_flush(o);
    return o->buf + o->n;
}

static inline void fs_out_char(fs_out *o, char c)
{
    *fs_out_room(o, 1) = c;
    o->n++;
}

static inline void fs_out_str(fs_out *o, const char *s) { fs_out_bytes(o, s, strlen(s)); }

static inline void fs_out_u64(fs_out *o, uint64_t v)
{
    char tmp[20];
    int k = 0;
    do {
        tmp[k++] = (char)('0' + v % 10);
        v /= 10;
    } while (v);
    char *p = fs_out_room(o, 20);
    for (int i = 0; i < k; i++)
        p[i] = tmp[k - 1 - i];
    o->n += (size_t)k;
}

static inline void fs_out_i64(fs_out *o, int64_t v)
{
    if (v < 0) {
        fs_out_char(o, '-');
        fs_out_u64(o, 0 - (uint64_t)v);
    } else {
        fs_out_u64(o, (uint64_t)v);
    }
}

#endif
