/* check_connect: OBJ reader (see cc_obj.h). */
#include "cc_obj.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>

static int grow(void **p, size_t *cap, size_t need, size_t size)
{
    if (need <= *cap)
        return 0;
    size_t n = *cap ? *cap : 1024;
    while (n < need)
        n *= 2;
    void *q = realloc(*p, n * size);
    if (!q)
        return -1;
    *p = q;
    *cap = n;
    return 0;
}

static int fail(char *err, size_t errlen, const char *path, unsigned long line, const char *fmt,
                ...)
{
    int k =
        line ? snprintf(err, errlen, "%s:%lu: ", path, line) : snprintf(err, errlen, "%s: ", path);
    size_t n = k < 0 ? 0 : (size_t)k < errlen ? (size_t)k : errlen - 1;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err + n, errlen - n, fmt, ap);
    va_end(ap);
    return -1;
}

static int is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

/* The rest of the line without surrounding white space (modifies s). */
static char *trimmed(char *s)
{
    while (is_space(*s))
        s++;
    size_t n = strlen(s);
    while (n > 0 && is_space(s[n - 1]))
        s[--n] = '\0';
    return s;
}

typedef struct reader {
    cc_mesh *m;
    size_t cap_v, cap_t, cap_f;
    char *name; /* current o/g name (malloc'ed) */
    long cur;   /* its fault, or -1 when not looked up yet */
} reader;

static long fault_of(reader *r)
{
    if (r->cur >= 0)
        return r->cur;
    const char *name = r->name ? r->name : "(unnamed)";
    cc_mesh *m = r->m;
    for (size_t f = 0; f < m->nfaults; f++)
        if (strcmp(m->names[f], name) == 0)
            return r->cur = (long)f;
    if (m->nfaults >= CC_MAX_FAULTS ||
        grow((void **)&m->names, &r->cap_f, m->nfaults + 1, sizeof *m->names))
        return -1;
    if (!(m->names[m->nfaults] = malloc(strlen(name) + 1)))
        return -1;
    strcpy(m->names[m->nfaults], name);
    return r->cur = (long)m->nfaults++;
}

int cc_obj_read(const char *path, cc_mesh *m, char *err, size_t errlen)
{
    memset(m, 0, sizeof *m);
    FILE *fp = fopen(path, "r");
    if (!fp)
        return fail(err, errlen, path, 0, "cannot open: %s", strerror(errno));
    reader r = {.m = m, .cur = -1};
    char *buf = NULL;
    size_t cap = 0;
    unsigned long line = 0;
    int rc = 0;
    ssize_t len;
    while ((len = getline(&buf, &cap, fp)) >= 0) {
        line++;
        if ((size_t)len != strlen(buf)) {
            rc = fail(err, errlen, path, line, "NUL byte in line");
            break;
        }
        char *s = buf;
        while (is_space(*s))
            s++;
        if (*s == '\0' || *s == '#')
            continue;
        size_t kw = 0;
        while (s[kw] && !is_space(s[kw]))
            kw++;
        if (kw == 1 && s[0] == 'v') {
            if (grow((void **)&m->x, &r.cap_v, 3 * (m->nv + 1), sizeof *m->x)) {
                rc = fail(err, errlen, path, line, "out of memory");
                break;
            }
            char *p = s + 1;
            for (int k = 0; k < 3 && rc == 0; k++) {
                char *end;
                errno = 0;
                double v = strtod(p, &end);
                if (end == p || (*end && !is_space(*end)))
                    rc = fail(err, errlen, path, line, "vertex needs three numbers");
                else if (!isfinite(v))
                    rc = fail(err, errlen, path, line, "coordinate is not finite");
                m->x[3 * m->nv + (size_t)k] = v;
                p = end;
            }
            if (rc)
                break;
            if (m->nv >= UINT32_MAX - 1) {
                rc = fail(err, errlen, path, line, "too many vertices");
                break;
            }
            m->nv++;
        } else if (kw == 1 && s[0] == 'f') {
            uint32_t idx[3];
            int n = 0;
            char *p = s + 1;
            for (;;) {
                while (is_space(*p))
                    p++;
                if (!*p)
                    break;
                char *end;
                errno = 0;
                long long v = strtoll(p, &end, 10);
                if (end == p || (*end && *end != '/' && !is_space(*end))) {
                    rc = fail(err, errlen, path, line, "bad vertex index");
                    break;
                }
                while (*end && !is_space(*end))
                    end++; /* texture / normal indices */
                long long at = v > 0 ? v - 1 : (long long)m->nv + v;
                if (v == 0 || errno == ERANGE || at < 0 || at >= (long long)m->nv) {
                    rc = fail(err, errlen, path, line,
                              "vertex index %lld not defined (%zu vertices so far)", v, m->nv);
                    break;
                }
                if (n < 3)
                    idx[n] = (uint32_t)at;
                n++;
                p = end;
            }
            if (rc)
                break;
            if (n != 3) {
                rc = fail(err, errlen, path, line,
                          "face with %d corners; only triangles are checked", n);
                break;
            }
            long f = fault_of(&r);
            size_t old_cap = r.cap_t;
            if (f < 0 || grow((void **)&m->tri, &r.cap_t, m->nt + 1, 3 * sizeof *m->tri)) {
                rc = fail(err, errlen, path, line,
                          m->nfaults >= CC_MAX_FAULTS ? "too many faults" : "out of memory");
                break;
            }
            if (r.cap_t != old_cap) {
                void *fa = realloc(m->fault, r.cap_t * sizeof *m->fault);
                if (fa)
                    m->fault = fa;
                void *la = fa ? realloc(m->line, r.cap_t * sizeof *m->line) : NULL;
                if (la)
                    m->line = la;
                if (!fa || !la) {
                    rc = fail(err, errlen, path, line, "out of memory");
                    break;
                }
            }
            if (m->nt >= UINT32_MAX - 1 || line > UINT32_MAX) {
                rc = fail(err, errlen, path, line, "too many triangles");
                break;
            }
            memcpy(m->tri + 3 * m->nt, idx, sizeof idx);
            m->fault[m->nt] = (uint32_t)f;
            m->line[m->nt] = (uint32_t)line;
            m->nt++;
        } else if (kw == 1 && (s[0] == 'o' || s[0] == 'g')) {
            const char *name = trimmed(s + 1);
            if (!*name)
                name = "(unnamed)";
            if (!r.name || strcmp(r.name, name) != 0) {
                free(r.name);
                if (!(r.name = malloc(strlen(name) + 1))) {
                    rc = fail(err, errlen, path, line, "out of memory");
                    break;
                }
                strcpy(r.name, name);
                r.cur = -1;
            }
        }
    }
    if (rc == 0 && ferror(fp))
        rc = fail(err, errlen, path, line + 1, "read error");
    if (rc == 0 && m->nt == 0)
        rc = fail(err, errlen, path, 0, "no triangles");
    free(buf);
    free(r.name);
    fclose(fp);
    if (rc)
        cc_mesh_free(m);
    return rc;
}

void cc_mesh_free(cc_mesh *m)
{
    for (size_t f = 0; f < m->nfaults; f++)
        free(m->names[f]);
    free(m->names);
    free(m->x);
    free(m->tri);
    free(m->fault);
    free(m->line);
    memset(m, 0, sizeof *m);
}
