#include "fm_atomic.h"

#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

/* The temporary names of writes in progress, for fm_atomic_remove_pending,
 * which runs in a signal handler while other threads go on: it may take no
 * lock and touch no memory another thread frees or rewrites. So the names
 * live in preallocated slots owned through one atomic state each, changed
 * only by compare-and-swap: a slot's name is written while the slot is
 * CLAIMED (invisible to the handler), read by the handler only once it
 * has moved the slot from ARMED to REMOVING, and a writer gives back only
 * a slot still ARMED (one the handler took stays taken: the process is
 * ending).
 *
 * The file itself is created while its slot is CREATING, with every signal
 * blocked in the creating thread, and the handler (in another thread, then)
 * waits for such a slot to be ARMED again before removing it: otherwise a
 * file created just after the handler passed would outlive the process,
 * which a thread on another core can still do between the handler's return
 * and the end of the process. A writer that sees the handler has run does
 * not create its file at all.
 *
 * A write whose name finds no slot (all busy, or a path longer than a
 * slot) is still atomic, only not removed on a signal. */
enum { SLOT_FREE, SLOT_CLAIMED, SLOT_ARMED, SLOT_CREATING, SLOT_REMOVING };
#define NSLOTS 128
#define SLOT_BYTES 4096

_Static_assert(ATOMIC_INT_LOCK_FREE == 2, "a signal handler may only use lock-free atomics");

static atomic_int slot_state[NSLOTS];
static char slot_name[NSLOTS][SLOT_BYTES];
static atomic_int removing;   /* set once fm_atomic_remove_pending ran */
static atomic_uint name_count; /* makes each temporary name of the process new */

struct fm_atomic_name {
    char *path;
    char *tmp;
    int slot; /* -1: not registered */
    sigset_t held; /* the creating thread's signal mask, while it creates */
};

struct fm_atomic_file {
    FILE *fp;
    fm_atomic_name *name;
};

static int slot_take(const char *tmp)
{
    size_t n = strlen(tmp);
    if (n >= SLOT_BYTES)
        return -1;
    for (int i = 0; i < NSLOTS; i++) {
        int expect = SLOT_FREE;
        if (!atomic_compare_exchange_strong(&slot_state[i], &expect, SLOT_CLAIMED))
            continue;
        memcpy(slot_name[i], tmp, n + 1);
        atomic_store(&slot_state[i], SLOT_ARMED);
        return i;
    }
    return -1;
}

static void slot_give_back(int i)
{
    if (i < 0)
        return;
    int expect = SLOT_ARMED;
    atomic_compare_exchange_strong(&slot_state[i], &expect, SLOT_FREE);
}

void fm_atomic_remove_pending(void)
{
    atomic_store(&removing, 1);
    for (int i = 0; i < NSLOTS; i++) {
        int expect = SLOT_ARMED;
        /* a CREATING slot belongs to a thread with signals blocked, so not
         * this one: it is running, and hands the slot back shortly */
        while (!atomic_compare_exchange_strong(&slot_state[i], &expect, SLOT_REMOVING)) {
            if (expect != SLOT_CREATING)
                break;
            expect = SLOT_ARMED;
        }
        if (expect == SLOT_ARMED)
            unlink(slot_name[i]);
    }
}

fm_status fm_atomic_name_creating(fm_atomic_name *n, fm_error *err)
{
    sigset_t all;
    sigfillset(&all);
    pthread_sigmask(SIG_BLOCK, &all, &n->held);
    int expect = SLOT_ARMED;
    if (n->slot >= 0 &&
        !atomic_compare_exchange_strong(&slot_state[n->slot], &expect, SLOT_CREATING))
        expect = -1; /* the handler took the slot */
    /* read after the slot became CREATING: a handler that has not yet set
     * the flag will find the slot, and wait for it */
    if (expect == -1 || atomic_load(&removing)) {
        fm_atomic_name_created(n);
        return fm_error_set(err, FM_ERR_IO, n->path, 0, "interrupted");
    }
    return FM_OK;
}

void fm_atomic_name_created(fm_atomic_name *n)
{
    if (n->slot >= 0) {
        int expect = SLOT_CREATING;
        atomic_compare_exchange_strong(&slot_state[n->slot], &expect, SLOT_ARMED);
    }
    pthread_sigmask(SIG_SETMASK, &n->held, NULL);
}

static void name_free(fm_atomic_name *n)
{
    if (!n)
        return;
    slot_give_back(n->slot);
    free(n->path);
    free(n->tmp);
    free(n);
}

fm_atomic_name *fm_atomic_name_create(const char *path, fm_error *err)
{
    fm_atomic_name *n = calloc(1, sizeof *n);
    size_t len = strlen(path);
    if (n) {
        n->slot = -1;
        n->path = malloc(len + 1);
        n->tmp = malloc(len + 48);
    }
    if (!n || !n->path || !n->tmp) {
        name_free(n);
        fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
        return NULL;
    }
    memcpy(n->path, path, len + 1);
    /* Same folder as the target so that rename() is atomic; a hidden name
     * that says what it was to become, should a killed run leave it. */
    const char *slash = strrchr(path, '/');
    size_t dir = slash ? (size_t)(slash - path) + 1 : 0;
    snprintf(n->tmp, len + 48, "%.*s.%s.tmp.%ld.%u", (int)dir, path, path + dir, (long)getpid(),
             atomic_fetch_add(&name_count, 1u));
    /* registered before anything exists under the name; the file is made
     * between fm_atomic_name_creating and _created */
    n->slot = slot_take(n->tmp);
    return n;
}

const char *fm_atomic_name_tmp(const fm_atomic_name *n) { return n->tmp; }

int fm_atomic_interrupted(void) { return atomic_load(&removing); }

fm_status fm_atomic_name_commit(fm_atomic_name *n, int synced, fm_error *err)
{
    int bad = 0, saved = 0;
    if (!synced) {
        int fd = open(n->tmp, O_RDONLY);
        bad = fd < 0 || (fsync(fd) != 0 && errno != EINVAL);
        saved = errno;
        if (fd >= 0)
            close(fd);
    }
    if (!bad && rename(n->tmp, n->path) != 0) {
        bad = 1;
        saved = errno;
    }
    if (bad) {
        unlink(n->tmp);
        fm_error_set(err, FM_ERR_IO, n->path, 0, "cannot write file: %s", strerror(saved));
    }
    name_free(n);
    return bad ? FM_ERR_IO : FM_OK;
}

void fm_atomic_name_abort(fm_atomic_name *n)
{
    if (!n)
        return;
    unlink(n->tmp);
    name_free(n);
}

fm_atomic_file *fm_atomic_open(const char *path, fm_error *err)
{
    fm_atomic_file *f = calloc(1, sizeof *f);
    if (!f) {
        fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
        return NULL;
    }
    int fd = -1;
    /* a name left by an earlier run of a process with the same id is
     * skipped, never overwritten */
    for (int attempt = 0; fd < 0 && attempt < 100; attempt++) {
        name_free(f->name);
        f->name = NULL;
        if (!(f->name = fm_atomic_name_create(path, err))) {
            free(f);
            return NULL;
        }
        if (fm_atomic_name_creating(f->name, err) != FM_OK) {
            name_free(f->name);
            free(f);
            return NULL;
        }
        /* open() applies the umask: outputs are ordinary files for the user */
        fd = open(f->name->tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        int saved = errno;
        fm_atomic_name_created(f->name);
        errno = saved;
        if (fd < 0 && errno != EEXIST)
            break;
    }
    if (fd < 0) {
        fm_error_set(err, FM_ERR_IO, path, 0, "cannot create file: %s", strerror(errno));
        name_free(f->name);
        free(f);
        return NULL;
    }
    f->fp = fdopen(fd, "wb");
    if (!f->fp) {
        fm_error_set(err, FM_ERR_IO, path, 0, "cannot open stream: %s", strerror(errno));
        close(fd);
        fm_atomic_name_abort(f->name);
        free(f);
        return NULL;
    }
    return f;
}

FILE *fm_atomic_stream(fm_atomic_file *f) { return f->fp; }

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
    fm_atomic_name *n = f->name;
    free(f);
    if (bad) {
        fm_error_set(err, FM_ERR_IO, n->path, 0, "cannot write file: %s", strerror(saved));
        fm_atomic_name_abort(n);
        return FM_ERR_IO;
    }
    return fm_atomic_name_commit(n, 1, err);
}

void fm_atomic_abort(fm_atomic_file *f)
{
    if (!f)
        return;
    if (f->fp)
        fclose(f->fp);
    fm_atomic_name_abort(f->name);
    free(f);
}

char *fm_path_join(const char *dir, const char *name)
{
    size_t a = strlen(dir), b = strlen(name);
    char *p = malloc(a + b + 2);
    if (!p)
        return NULL;
    memcpy(p, dir, a);
    size_t k = a;
    if (a == 0 || dir[a - 1] != '/')
        p[k++] = '/';
    memcpy(p + k, name, b + 1);
    return p;
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
