/* realpath */
#define _XOPEN_SOURCE 700

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli.h"
#include "fm_atomic.h"
#include "fm_run_options.h"

/* The run module lists them (fm_run_list_inputs); what it has to say is
 * said here as the command has always said it. */
static void say(void *user, fm_log_level level, const char *message)
{
    (void)user;
    (void)level;
    fprintf(stderr, "faultmesh: %s\n", message);
}

long fm_input_list(char *const *args, size_t nargs, char ***out)
{
    fm_error err;
    long n = fm_run_list_inputs((const char *const *)args, nargs, say, NULL, out, &err);
    if (n < 0)
        fprintf(stderr, "faultmesh: %s\n", err.message);
    return n;
}

void fm_input_list_free(char **list, long n)
{
    fm_run_list_free(list, n);
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
        out = fm_path_join(parent, tail);
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
