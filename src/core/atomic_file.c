#include "fm_atomic.h"

#include <errno.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

struct fm_atomic_file {
    FILE *fp;
    char *path;
    char *tmp;
};

/* umask can only be read by setting it, which would race with a thread
 * creating a file at that moment: it is read once, and every later call
 * (from any thread) uses the copy. */
static mode_t process_umask;
static pthread_once_t umask_once = PTHREAD_ONCE_INIT;

static void read_umask(void)
{
    process_umask = umask(0);
    umask(process_umask);
}

fm_atomic_file *fm_atomic_open(const char *path, fm_error *err)
{
    pthread_once(&umask_once, read_umask);
    fm_atomic_file *f = calloc(1, sizeof *f);
    size_t n = strlen(path);
    if (f) {
        f->path = malloc(n + 1);
        f->tmp = malloc(n + 16);
    }
    if (!f || !f->path || !f->tmp) {
        if (f) {
            free(f->path);
            free(f->tmp);
        }
        free(f);
        fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
        return NULL;
    }
    memcpy(f->path, path, n + 1);
    /* Same directory as the target so that rename() is atomic; the name
     * is hidden-ish and clearly temporary. */
    snprintf(f->tmp, n + 16, "%s.tmp.XXXXXX", path);
    int fd = mkstemp(f->tmp);
    if (fd < 0) {
        fm_error_set(err, FM_ERR_IO, path, 0, "cannot create file: %s", strerror(errno));
        free(f->path);
        free(f->tmp);
        free(f);
        return NULL;
    }
    /* mkstemp creates 0600; outputs are ordinary files for the user. */
    (void)fchmod(fd, 0666 & ~process_umask);
    f->fp = fdopen(fd, "wb");
    if (!f->fp) {
        fm_error_set(err, FM_ERR_IO, path, 0, "cannot open stream: %s", strerror(errno));
        close(fd);
        unlink(f->tmp);
        free(f->path);
        free(f->tmp);
        free(f);
        return NULL;
    }
    return f;
}

FILE *fm_atomic_stream(fm_atomic_file *f) { return f->fp; }

static void release(fm_atomic_file *f)
{
    free(f->path);
    free(f->tmp);
    free(f);
}

fm_status fm_atomic_commit(fm_atomic_file *f, fm_error *err)
{
    int bad = ferror(f->fp) || fflush(f->fp) != 0;
    if (!bad)
        bad = fsync(fileno(f->fp)) != 0 && errno != EINVAL;
    int saved = errno;
    if (fclose(f->fp) != 0 && !bad) {
        bad = 1;
        saved = errno;
    }
    f->fp = NULL;
    if (!bad && rename(f->tmp, f->path) != 0) {
        bad = 1;
        saved = errno;
    }
    if (bad) {
        unlink(f->tmp);
        fm_error_set(err, FM_ERR_IO, f->path, 0, "cannot write file: %s", strerror(saved));
        release(f);
        return FM_ERR_IO;
    }
    release(f);
    return FM_OK;
}

void fm_atomic_abort(fm_atomic_file *f)
{
    if (!f)
        return;
    if (f->fp)
        fclose(f->fp);
    unlink(f->tmp);
    release(f);
}

fm_status fm_mkdir_p(const char *path, fm_error *err)
{
    size_t n = strlen(path);
    char *buf = malloc(n + 1);
    if (!buf)
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    memcpy(buf, path, n + 1);
    for (size_t i = 1; i <= n; i++) {
        if (buf[i] != '/' && buf[i] != '\0')
            continue;
        char c = buf[i];
        buf[i] = '\0';
        if (mkdir(buf, 0777) != 0 && errno != EEXIST) {
            fm_status s = fm_error_set(err, FM_ERR_IO, buf, 0, "cannot create directory: %s",
                                       strerror(errno));
            free(buf);
            return s;
        }
        buf[i] = c;
    }
    struct stat sb;
    int ok = stat(path, &sb) == 0 && S_ISDIR(sb.st_mode);
    free(buf);
    if (!ok)
        return fm_error_set(err, FM_ERR_IO, path, 0, "not a directory");
    return FM_OK;
}
