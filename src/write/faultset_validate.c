/* What every fault-set writer requires of its input, checked before any
 * byte is written so that bad input never leaves a file behind. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "faultset_internal.h"

int32_t fs_physical_tag(const fm_faultset *fs, size_t i)
{
    return fs->physical_tags ? fs->physical_tags[i] : (int32_t)(i + 1);
}

const char *fs_physical_name(const fm_faultset *fs, size_t i)
{
    return fs->physical_names ? fs->physical_names[i] : fs->names[i];
}

int32_t *fs_vertex_owner(const fm_faultset *fs)
{
    size_t nv = fm_mesh_nvertices(fs->mesh), nt = fm_mesh_ntriangles(fs->mesh);
    int32_t *owner = malloc((nv ? nv : 1) * sizeof *owner);
    if (!owner)
        return NULL;
    for (size_t v = 0; v < nv; v++)
        owner[v] = -1;
    const int32_t *tri = fm_mesh_triangles(fs->mesh), *tag = fm_mesh_tags(fs->mesh);
    for (size_t t = 0; t < 3 * nt; t++) {
        int32_t *o = &owner[tri[t]];
        if (*o < 0 || tag[t / 3] < *o)
            *o = tag[t / 3];
    }
    return owner;
}

size_t *fs_fault_counts(const fm_faultset *fs)
{
    size_t *count = calloc(fs->nfaults ? fs->nfaults : 1, sizeof *count);
    if (!count)
        return NULL;
    const int32_t *tag = fm_mesh_tags(fs->mesh);
    for (size_t t = 0; t < fm_mesh_ntriangles(fs->mesh); t++)
        count[tag[t]]++;
    return count;
}

/* Indices 0..n-1 grouped by key (0..nkeys-1; negative keys dropped),
 * ascending within a group: start[k]..start[k+1] indexes order. */
int fs_group_by(const int32_t *key, size_t n, size_t nkeys, size_t **start,
                    size_t **order)
{
    *start = calloc(nkeys + 1, sizeof **start);
    *order = malloc((n ? n : 1) * sizeof **order);
    if (!*start || !*order)
        return -1;
    for (size_t i = 0; i < n; i++)
        if (key[i] >= 0)
            (*start)[key[i] + 1]++;
    for (size_t k = 0; k < nkeys; k++)
        (*start)[k + 1] += (*start)[k];
    size_t *fill = malloc((nkeys ? nkeys : 1) * sizeof *fill);
    if (!fill)
        return -1;
    memcpy(fill, *start, nkeys * sizeof *fill);
    for (size_t i = 0; i < n; i++)
        if (key[i] >= 0)
            (*order)[fill[key[i]]++] = i;
    free(fill);
    return 0;
}

size_t fs_utf8_cut(const char *s, size_t n)
{
    while (n > 0 && ((unsigned char)s[n] & 0xC0) == 0x80)
        n--;
    return n;
}

/* 0 when s is UTF-8 without control characters (names and the CRS go on
 * one text line in every format), else the offending byte offset + 1. */
static size_t bad_text(const char *s)
{
    const unsigned char *p = (const unsigned char *)s;
    size_t i = 0;
    while (p[i]) {
        unsigned c = p[i];
        size_t len = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
        if (c < 0x20 || c == 0x7f || len == 0)
            return i + 1;
        unsigned long cp = len == 1 ? c : c & (0x7Fu >> len);
        for (size_t k = 1; k < len; k++) {
            if ((p[i + k] & 0xC0) != 0x80)
                return i + 1;
            cp = (cp << 6) | (p[i + k] & 0x3F);
        }
        /* Overlong forms, surrogates and values past U+10FFFF are not UTF-8. */
        static const unsigned long least[5] = {0, 0, 0x80, 0x800, 0x10000};
        if (len > 1 && (cp < least[len] || (cp >= 0xD800 && cp <= 0xDFFF) || cp > 0x10FFFF))
            return i + 1;
        i += len;
    }
    return 0;
}

static fm_status check_names(const fm_faultset *fs, const char *path, fm_error *err)
{
    for (size_t i = 0; i < fs->nfaults; i++) {
        const char *n = fs->names[i];
        if (!n || !n[0])
            return fm_error_set(err, FM_ERR_INVALID, path, 0, "fault %zu has no name", i);
        size_t bad = bad_text(n);
        if (bad)
            return fm_error_set(err, FM_ERR_INVALID, path, 0,
                                "name of fault %zu: byte %zu is a control character or not "
                                "UTF-8",
                                i, bad);
    }
    if (fs->crs && bad_text(fs->crs))
        return fm_error_set(err, FM_ERR_INVALID, path, 0,
                            "CRS: a control character or not UTF-8");
    for (size_t i = 0; fs->physical_names && i < fs->nfaults; i++) {
        const char *n = fs->physical_names[i];
        if (!n || !n[0] || bad_text(n))
            return fm_error_set(err, FM_ERR_INVALID, path, 0,
                                "physical name of fault %zu: empty, a control character or "
                                "not UTF-8",
                                i);
    }
    if (fs->physical_tags)
        for (size_t i = 0; i < fs->nfaults; i++) {
            if (fs->physical_tags[i] <= 0)
                return fm_error_set(err, FM_ERR_INVALID, path, 0,
                                    "physical tag %d of fault %zu is not positive",
                                    (int)fs->physical_tags[i], i);
            /* one group, one name */
            for (size_t k = 0; k < i; k++)
                if (fs->physical_tags[k] == fs->physical_tags[i] &&
                    strcmp(fs_physical_name(fs, k), fs_physical_name(fs, i)) != 0)
                    return fm_error_set(err, FM_ERR_INVALID, path, 0,
                                        "faults %zu and %zu share physical tag %d under "
                                        "different names",
                                        k, i, (int)fs->physical_tags[i]);
        }
    for (size_t i = 0; i < fs->nnodesets; i++) {
        const fm_faultset_nodeset *ns = &fs->nodesets[i];
        if (!ns->name || !ns->name[0] || bad_text(ns->name) || (ns->n && !ns->vertices))
            return fm_error_set(err, FM_ERR_INVALID, path, 0,
                                "node set %zu: needs a UTF-8 name without control "
                                "characters and its vertices",
                                i);
    }
    for (size_t i = 0; i < fs->ncell_data; i++) {
        const fm_vtu_array *a = &fs->cell_data[i];
        if (!a->name || !a->name[0] || strcmp(a->name, "fault_id") == 0 || a->ncomp < 1 ||
            !a->values || (a->type != FM_VTU_FLOAT64 && a->type != FM_VTU_INT32))
            return fm_error_set(err, FM_ERR_INVALID, path, 0,
                                "cell array %zu: needs a name other than fault_id, values, "
                                "ncomp >= 1 and type double or int32",
                                i);
        /* The name lands in an XML attribute unescaped. */
        if (strpbrk(a->name, "<>&\"") || bad_text(a->name))
            return fm_error_set(err, FM_ERR_INVALID, path, 0,
                                "cell array %zu: name \"%s\" has characters XML needs escaped",
                                i, a->name);
    }
    return FM_OK;
}

fm_status fm_faultset_validate(const fm_faultset *fs, const char *path, fm_error *err)
{
    if (!fs || !fs->mesh || !fs->names || fs->nfaults == 0)
        return fm_error_set(err, FM_ERR_INVALID, path, 0,
                            "a fault set needs a mesh and at least one named fault");
    if (fs->nfaults > (size_t)INT32_MAX)
        return fm_error_set(err, FM_ERR_INVALID, path, 0, "too many faults");
    fm_status st = check_names(fs, path, err);
    if (st != FM_OK)
        return st;
    size_t nv = fm_mesh_nvertices(fs->mesh), nt = fm_mesh_ntriangles(fs->mesh);
    if (nv >= (size_t)INT32_MAX || nt >= (size_t)INT32_MAX)
        return fm_error_set(err, FM_ERR_INVALID, path, 0, "mesh too large for int32 indices");
    const double *x = fm_mesh_vertices(fs->mesh);
    for (size_t i = 0; i < 3 * nv; i++)
        if (!isfinite(x[i]))
            return fm_error_set(err, FM_ERR_NUMERIC, path, 0,
                                "vertex %zu has a non-finite coordinate", i / 3);
    const int32_t *tri = fm_mesh_triangles(fs->mesh), *tag = fm_mesh_tags(fs->mesh);
    for (size_t t = 0; t < nt; t++) {
        if (tag[t] < 0 || (size_t)tag[t] >= fs->nfaults)
            return fm_error_set(err, FM_ERR_INVALID, path, 0,
                                "triangle %zu has tag %d, not a fault index 0..%zu", t,
                                (int)tag[t], fs->nfaults - 1);
        for (int k = 0; k < 3; k++)
            if (tri[3 * t + (size_t)k] < 0 || (size_t)tri[3 * t + (size_t)k] >= nv)
                return fm_error_set(err, FM_ERR_INVALID, path, 0,
                                    "triangle %zu names vertex %d of %zu", t,
                                    (int)tri[3 * t + (size_t)k], nv);
    }
    for (size_t i = 0; i < fs->nnodesets; i++)
        for (size_t k = 0; k < fs->nodesets[i].n; k++)
            if (fs->nodesets[i].vertices[k] < 0 || (size_t)fs->nodesets[i].vertices[k] >= nv)
                return fm_error_set(err, FM_ERR_INVALID, path, 0,
                                    "node set %zu (%s) names vertex %d of %zu", i,
                                    fs->nodesets[i].name, (int)fs->nodesets[i].vertices[k], nv);
    size_t *count = fs_fault_counts(fs);
    if (!count)
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    for (size_t i = 0; i < fs->nfaults && st == FM_OK; i++)
        if (count[i] == 0)
            st = fm_error_set(err, FM_ERR_INVALID, path, 0, "fault %zu (%s) has no triangles", i,
                              fs->names[i]);
    free(count);
    return st;
}
