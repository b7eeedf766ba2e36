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

static int walk(const char *dir, strvec *out)
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
    qsort(names.v, (size_t)names.n, sizeof *names.v, cmp_str);
    for (long i = 0; i < names.n && rc == 0; i++) {
        char *path = join(dir, names.v[i]);
        struct stat sb;
        if (!path) {
            rc = -1;
        } else if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode)) {
            rc = walk(path, out);
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
    for (size_t i = 0; i < nargs; i++) {
        struct stat sb;
        if (stat(args[i], &sb) != 0) {
            fprintf(stderr, "faultmesh: %s: %s\n", args[i], strerror(errno));
            fm_input_list_free(list.v, list.n);
            return -1;
        }
        int rc = S_ISDIR(sb.st_mode) ? walk(args[i], &list) : push(&list, args[i]);
        if (rc) {
            fm_input_list_free(list.v, list.n);
            return -1;
        }
    }
    *out = list.v;
    return list.n;
}

void fm_input_list_free(char **list, long n)
{
    for (long i = 0; i < n; i++)
        free(list[i]);
    free(list);
}

int fm_parse_double(const char *opt, const char *s, double *out)
{
    char *end;
    errno = 0;
    double v = s ? strtod(s, &end) : 0.0;
    if (!s || end == s || *end || errno || !(v >= 0.0) || v > 1e12) {
        fprintf(stderr, "faultmesh: %s needs a non-negative number, got '%s'\n", opt,
                s ? s : "");
        return -1;
    }
    *out = v;
    return 0;
}

int fm_parse_size(const char *opt, const char *s, size_t *out)
{
    char *end;
    errno = 0;
    unsigned long long v = s ? strtoull(s, &end, 10) : 0;
    if (!s || end == s || *end || errno || s[0] == '-') {
        fprintf(stderr, "faultmesh: %s needs a non-negative integer, got '%s'\n", opt,
                s ? s : "");
        return -1;
    }
    *out = (size_t)v;
    return 0;
}
