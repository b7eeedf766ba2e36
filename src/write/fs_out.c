#include "fs_out.h"

#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>

#include "fm_dtoa.h"

fs_out *fs_out_open(FILE *fp)
{
    fs_out *o = malloc(sizeof *o);
    if (o) {
        o->fp = fp;
        o->n = 0;
        o->failed = 0;
    }
    return o;
}

void fs_out_flush(fs_out *o)
{
    if (o->n && fwrite(o->buf, 1, o->n, o->fp) != o->n && !o->failed)
        o->failed = errno ? errno : EIO;
    o->n = 0;
}

int fs_out_finish(fs_out *o)
{
    fs_out_flush(o);
    /* the buffered bytes reach the device only now: a full disk shows here */
    if (!o->failed && (ferror(o->fp) || fflush(o->fp) != 0))
        o->failed = errno ? errno : EIO;
    int failed = o->failed;
    free(o);
    return failed;
}

fm_status fs_out_commit(fs_out *o, fm_atomic_file *af, const char *path, fm_error *err)
{
    int failed = fs_out_finish(o);
    if (failed) {
        fm_atomic_abort(af);
        return fm_error_set(err, FM_ERR_IO, path, 0, "write failed: %s", strerror(failed));
    }
    return fm_atomic_commit(af, err);
}

void fs_out_bytes(fs_out *o, const void *p, size_t n)
{
    if (n > FS_OUT_BLOCK / 2) { /* large blocks go straight through */
        fs_out_flush(o);
        if (fwrite(p, 1, n, o->fp) != n && !o->failed)
            o->failed = errno ? errno : EIO;
        return;
    }
    memcpy(fs_out_room(o, n), p, n);
    o->n += n;
}

void fs_out_printf(fs_out *o, const char *fmt, ...)
{
    char *p = fs_out_room(o, 512);
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(p, 512, fmt, ap);
    va_end(ap);
    if (k > 0)
        o->n += (size_t)k < 512 ? (size_t)k : 511;
}

void fs_out_double(fs_out *o, double v) { o->n += fm_format_double(fs_out_room(o, 32), v); }
