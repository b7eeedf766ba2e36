/* fm_run_check_output_dir: an output folder that would put the inputs at
 * risk is refused before anything is written. */
/* realpath */
#define _XOPEN_SOURCE 700

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fm_atomic.h"
#include "run_internal.h"

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

/* 1 (err set) when the folder file lies in, or its target's, is out. */
static int holds(const char *outdir, const char *out, const char *file, fm_error *err)
{
    /* the folder the path names (a link replaced would be lost too), and
     * the one its target lies in */
    char *dir = malloc(strlen(file) + 3);
    if (!dir) {
        fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
        return 1;
    }
    strcpy(dir, file);
    char *slash = strrchr(dir, '/');
    if (slash)
        slash[1] = '\0';
    else
        strcpy(dir, ".");
    char *a = resolve(dir), *t = realpath(file, NULL), *b = NULL;
    if (t && (slash = strrchr(t, '/')) != NULL) {
        *slash = '\0';
        b = t[0] ? t : NULL;
    }
    int bad = (a && !strcmp(a, out)) || (b && !strcmp(b, out)) || (t && !b && !strcmp(out, "/"));
    if (bad)
        fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                     "output folder %s holds the input %s, which an output of the same name "
                     "would replace; choose another -o",
                     outdir, file);
    free(a);
    free(t);
    free(dir);
    return bad;
}

fm_status fm_run_check_output_dir(const char *outdir, const char *const *args, size_t nargs,
                                  const char *const *files, size_t nfiles, fm_error *err)
{
    struct stat ob;
    if (stat(outdir, &ob) == 0 && !S_ISDIR(ob.st_mode))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "-o %s is a file, not a folder",
                            outdir);
    char *out = resolve(outdir);
    if (!out)
        return fm_error_set(err, FM_ERR_IO, NULL, 0,
                            "%s: cannot tell where the output folder is: %s", outdir,
                            strerror(errno));
    fm_status st = FM_OK;
    for (size_t i = 0; i < nargs && st == FM_OK; i++) {
        struct stat sb;
        char *in = stat(args[i], &sb) == 0 && S_ISDIR(sb.st_mode) ? resolve(args[i]) : NULL;
        if (in && within(out, in))
            st = fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                              "output folder %s is the input folder %s or lies inside it: the "
                              "outputs could replace inputs and would be read as inputs; "
                              "choose another -o",
                              outdir, args[i]);
        free(in);
    }
    for (size_t i = 0; i < nfiles && st == FM_OK; i++)
        if (holds(outdir, out, files[i], err))
            st = err && err->code != FM_OK ? err->code : FM_ERR_INVALID;
    free(out);
    return st;
}
