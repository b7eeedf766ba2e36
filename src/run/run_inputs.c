/* The .ts files that paths name: files as given, folders searched
 * recursively, each folder's entries in byte order so that runs are
 * reproducible (fm_run_add_path; the CLI lists its inputs with it too). */
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fm_atomic.h"
#include "run_internal.h"

typedef struct {
    char **v;
    long n, cap;
} strvec;

static int push(strvec *s, const char *str)
{
    if (s->n == s->cap) {
        long cap = s->cap ? 2 * s->cap : 64;
        char **p = realloc(s->v, (size_t)cap * sizeof *p);
        if (!p)
            return -1;
        s->v = p;
        s->cap = cap;
    }
    size_t len = strlen(str) + 1;
    char *copy = malloc(len);
    if (!copy)
        return -1;
    memcpy(copy, str, len);
    s->v[s->n++] = copy;
    return 0;
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static int has_ts_suffix(const char *name)
{
    size_t n = strlen(name);
    return n > 3 && (!strcmp(name + n - 3, ".ts") || !strcmp(name + n - 3, ".TS"));
}

/* Folders read so far, by device and inode: a symbolic link back up the
 * tree (ln -s . x) would otherwise have the walk read everything again,
 * or for ever with two such links. */
typedef struct seen_dirs {
    dev_t *dev;
    ino_t *ino;
    size_t n, cap;
} seen_dirs;

/* 1 when dir (stat sb) was read already, 0 after noting it, -1 when out
 * of memory. */
static int seen_before(seen_dirs *s, const struct stat *sb)
{
    for (size_t i = 0; i < s->n; i++)
        if (s->dev[i] == sb->st_dev && s->ino[i] == sb->st_ino)
            return 1;
    if (s->n == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 64;
        dev_t *d = realloc(s->dev, cap * sizeof *d);
        if (d)
            s->dev = d;
        ino_t *i = d ? realloc(s->ino, cap * sizeof *i) : NULL;
        if (!d || !i)
            return -1;
        s->ino = i;
        s->cap = cap;
    }
    s->dev[s->n] = sb->st_dev;
    s->ino[s->n++] = sb->st_ino;
    return 0;
}

static int walk(const char *dir, strvec *out, seen_dirs *seen, run_ctl *log, fm_error *err)
{
    DIR *d = opendir(dir);
    if (!d) {
        fm_error_set(err, FM_ERR_IO, dir, 0, "cannot open folder: %s", strerror(errno));
        return -1;
    }
    strvec names = {0};
    struct dirent *e;
    int rc = 0;
    while ((e = readdir(d)) != NULL) {
        if (e->d_name[0] == '.')
            continue; /* hidden files, temporary outputs, . and .. */
        if (push(&names, e->d_name)) {
            rc = -1;
            break;
        }
    }
    closedir(d);
    if (names.n > 1) /* qsort is not to be given the NULL of an empty folder */
        qsort(names.v, (size_t)names.n, sizeof *names.v, cmp_str);
    for (long i = 0; i < names.n && rc == 0; i++) {
        char *path = fm_path_join(dir, names.v[i]);
        struct stat sb;
        if (!path) {
            rc = -1;
        } else if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode)) {
            int again = seen_before(seen, &sb);
            if (again < 0)
                rc = -1;
            else if (again)
                run_log(log, FM_LOG_WARN, "%s: a folder read already (a symbolic link loops "
                                          "back to it), skipped", path);
            else
                rc = walk(path, out, seen, log, err);
        } else if (has_ts_suffix(names.v[i])) {
            rc = push(out, path);
        }
        free(path);
    }
    for (long i = 0; i < names.n; i++)
        free(names.v[i]);
    free(names.v);
    return rc;
}

long run_list_inputs(const char *const *args, size_t nargs, run_ctl *log, char ***out,
                     fm_error *err)
{
    fm_error_clear(err);
    strvec list = {0};
    seen_dirs seen = {0};
    long n = -1;
    for (size_t i = 0; i < nargs; i++) {
        struct stat sb;
        if (stat(args[i], &sb) != 0) {
            fm_error_set(err, FM_ERR_IO, args[i], 0, "%s", strerror(errno));
            goto done;
        }
        int rc = 0;
        if (!S_ISDIR(sb.st_mode))
            rc = push(&list, args[i]);
        else if ((rc = seen_before(&seen, &sb)) == 0)
            rc = walk(args[i], &list, &seen, log, err);
        else if (rc > 0) {
            run_log(log, FM_LOG_WARN, "%s: a folder read already, skipped", args[i]);
            rc = 0;
        }
        if (rc)
            goto done;
    }
    *out = list.v;
    n = list.n;
done:
    if (n < 0) {
        if (err && err->code == FM_OK)
            fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
        run_list_free(list.v, list.n);
    }
    free(seen.dev);
    free(seen.ino);
    return n;
}

void run_list_free(char **list, long n)
{
    for (long i = 0; i < n; i++)
        free(list[i]);
    free(list);
}

long fm_run_list_inputs(const char *const *paths, size_t npaths, fm_log_fn log, void *user,
                        char ***out, fm_error *err)
{
    run_ctl *c = log ? run_ctl_create() : NULL;
    if (log && !c)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory"), -1;
    if (c) {
        c->log = log;
        c->log_user = user;
        c->log_max = FM_LOG_DETAIL;
    }
    long n = run_list_inputs(paths, npaths, c, out, err);
    run_ctl_destroy(c);
    return n;
}

void fm_run_list_free(char **list, long n)
{
    run_list_free(list, n);
}
