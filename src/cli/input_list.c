/* realpath */
#define _XOPEN_SOURCE 700

#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"

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

static char *join(const char *dir, const char *name)
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

static int walk(const char *dir, strvec *out, seen_dirs *seen)
{
    DIR *d = opendir(dir);
    if (!d) {
        fprintf(stderr, "faultmesh: %s: cannot open folder: %s\n", dir, strerror(errno));
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
        char *path = join(dir, names.v[i]);
        struct stat sb;
        if (!path) {
            rc = -1;
        } else if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode)) {
            int again = seen_before(seen, &sb);
            if (again < 0)
                rc = -1;
            else if (again)
                fprintf(stderr, "faultmesh: %s: a folder read already (a symbolic link loops "
                                "back to it), skipped\n", path);
            else
                rc = walk(path, out, seen);
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

long fm_input_list(char *const *args, size_t nargs, char ***out)
{
    strvec list = {0};
    seen_dirs seen = {0};
    long n = -1;
    for (size_t i = 0; i < nargs; i++) {
        struct stat sb;
        if (stat(args[i], &sb) != 0) {
            fprintf(stderr, "faultmesh: %s: %s\n", args[i], strerror(errno));
            goto done;
        }
        int rc = 0;
        if (!S_ISDIR(sb.st_mode))
            rc = push(&list, args[i]);
        else if ((rc = seen_before(&seen, &sb)) == 0)
            rc = walk(args[i], &list, &seen);
        else if (rc > 0) {
            fprintf(stderr, "faultmesh: %s: a folder read already, skipped\n", args[i]);
            rc = 0;
        }
        if (rc)
            goto done;
    }
    *out = list.v;
    n = list.n;
done:
    if (n < 0)
        fm_input_list_free(list.v, list.n);
    free(seen.dev);
    free(seen.ino);
    return n;
}

void fm_input_list_free(char **list, long n)
{
    for (long i = 0; i < n; i++)
        free(list[i]);
    free(list);
}

/* The absolute, symbolic-link-free form of path, which need not exist
 * yet: its longest existing ancestor resolved, the rest appended
 * (malloc'ed; NULL when nothing of it resolves or out of memory). */
static char *resolve(const char *path)
{
    char *r = realpath(path, NULL);
    if (r)
        return r;
    size_t n = strlen(path);
    char *head = malloc(n + 1);
    if (!head)
        return NULL;
    memcpy(head, path, n + 1);
    while (n > 0 && head[n - 1] == '/')
        head[--n] = '\0';
    char *slash = strrchr(head, '/');
    const char *tail = slash ? slash + 1 : head;
    char *parent = NULL;
    if (!slash)
        parent = realpath(".", NULL);
    else if (slash == head)
        parent = realpath("/", NULL);
    else {
        *slash = '\0';
        parent = resolve(head);
    }
    char *out = NULL;
    if (parent && strcmp(tail, ".") && strcmp(tail, "..") && *tail) {
        out = join(parent, tail);
    } else if (parent && (!strcmp(tail, ".") || !*tail)) {
        out = parent;
        parent = NULL;
    }
    free(parent);
    free(head);
    return out;
}

/* 1 when path is dir or lies inside it (both resolved). */
static int within(const char *path, const char *dir)
{
    size_t n = strlen(dir);
    if (n == 1 && dir[0] == '/')
        return 1;
    return !strncmp(path, dir, n) && (path[n] == '\0' || path[n] == '/');
}

int fm_output_guard(const char *outdir, char *const *args, size_t nargs, char *const *files,
                    long nfiles)
{
    struct stat ob;
    if (stat(outdir, &ob) == 0 && !S_ISDIR(ob.st_mode)) {
        fprintf(stderr, "faultmesh: -o %s is a file, not a folder\n", outdir);
        return -1;
    }
    char *out = resolve(outdir);
    if (!out) {
        fprintf(stderr, "faultmesh: %s: cannot tell where the output folder is: %s\n", outdir,
                strerror(errno));
        return -1;
    }
    int rc = 0;
    for (size_t i = 0; i < nargs && !rc; i++) {
        struct stat sb;
        char *in = stat(args[i], &sb) == 0 && S_ISDIR(sb.st_mode) ? resolve(args[i]) : NULL;
        if (in && within(out, in)) {
            fprintf(stderr,
                    "faultmesh: output folder %s is the input folder %s or lies inside it: the "
                    "outputs could replace inputs and would be read as inputs; choose another "
                    "-o\n",
                    outdir, args[i]);
            rc = -1;
        }
        free(in);
    }
    for (long i = 0; i < nfiles && !rc; i++) {
        /* the folder the path names (a link replaced would be lost too),
         * and the one its target lies in */
        char *dir = malloc(strlen(files[i]) + 3);
        if (!dir) {
            rc = -1;
            break;
        }
        strcpy(dir, files[i]);
        char *slash = strrchr(dir, '/');
        if (slash)
            slash[1] = '\0';
        else
            strcpy(dir, ".");
        char *a = resolve(dir), *t = realpath(files[i], NULL), *b = NULL;
        if (t && (slash = strrchr(t, '/')) != NULL) {
            *slash = '\0';
            b = t[0] ? t : NULL;
        }
        if ((a && !strcmp(a, out)) || (b && !strcmp(b, out)) || (t && !b && !strcmp(out, "/"))) {
            fprintf(stderr,
                    "faultmesh: output folder %s holds the input %s, which an output of the "
                    "same name would replace; choose another -o\n",
                    outdir, files[i]);
            rc = -1;
        }
        free(a);
        free(t);
        free(dir);
    }
    free(out);
    return rc;
}

long fm_input_list_for(const char *cmd, const char *outdir, char *const *args, size_t nargs,
                       char ***out)
{
    long n = fm_input_list(args, nargs, out);
    if (n == 0)
        fprintf(stderr, "faultmesh %s: no .ts files found\n", cmd);
    if (n == 0 || (n > 0 && fm_output_guard(outdir, args, nargs, *out, n))) {
        fm_input_list_free(*out, n);
        *out = NULL;
        return -1;
    }
    return n;
}

int fm_cli_missing(const char *opt)
{
    fprintf(stderr, "faultmesh: %s needs a value\n", opt);
    return -1;
}

/* A decimal number (strtod also takes hexadecimal, inf and nan) in
 * [lo, 1e12] (above lo when open); -1 after saying what it needs. */
static int parse_number(const char *opt, const char *s, double lo, int open, const char *need,
                        double *out)
{
    if (!s)
        return fm_cli_missing(opt);
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    int decimal = s[strspn(s, "0123456789.eE+-")] == '\0';
    if (!decimal || end == s || *end || errno || !(open ? v > lo : v >= lo) || v > 1e12) {
        fprintf(stderr, "faultmesh: %s needs %s, got '%s'\n", opt, need, s);
        return -1;
    }
    *out = v;
    return 0;
}

int fm_parse_double(const char *opt, const char *s, double *out)
{
    return parse_number(opt, s, 0, 0, "a non-negative number", out);
}

int fm_parse_positive(const char *opt, const char *s, double *out)
{
    return parse_number(opt, s, 0, 1, "a positive number", out);
}

int fm_parse_size(const char *opt, const char *s, size_t *out)
{
    if (!s)
        return fm_cli_missing(opt);
    char *end;
    errno = 0;
    unsigned long long v = strtoull(s, &end, 10);
    if (end == s || *end || errno || s[0] == '-') {
        fprintf(stderr, "faultmesh: %s needs a non-negative integer, got '%s'\n", opt, s);
        return -1;
    }
    *out = (size_t)v;
    return 0;
}
