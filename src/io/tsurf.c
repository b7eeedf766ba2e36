/* fm_tsurf objects: construction, accessors and the small helpers the
 * reader and writer share. */
#include "tsurf_idmap.h"
#include "tsurf_internal.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

int fm_io_grow(void **p, size_t *cap, size_t need, size_t elsize)
{
    if (need <= *cap)
        return 0;
    size_t n = *cap ? *cap : 16;
    while (n < need) {
        if (n > SIZE_MAX / 2 / elsize)
            return -1;
        n *= 2;
    }
    void *q = realloc(*p, n * elsize);
    if (!q)
        return -1;
    *p = q;
    *cap = n;
    return 0;
}

char *fm_io_strndup(const char *s, size_t n)
{
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, s, n);
        d[n] = '\0';
    }
    return d;
}

int fm_strlist_push(fm_strlist *l, const char *s, size_t n)
{
    if (fm_io_grow((void **)&l->items, &l->cap, l->n + 1, sizeof *l->items))
        return -1;
    char *d = fm_io_strndup(s, n);
    if (!d)
        return -1;
    l->items[l->n++] = d;
    return 0;
}

void fm_strlist_free(fm_strlist *l)
{
    for (size_t i = 0; i < l->n; i++)
        free(l->items[i]);
    free(l->items);
    l->items = NULL;
    l->n = l->cap = 0;
}

fm_tsurf *fm_tsurf_alloc(void)
{
    fm_tsurf *ts = calloc(1, sizeof *ts);
    if (!ts)
        return NULL;
    ts->mesh = fm_mesh_create();
    if (!ts->mesh) {
        free(ts);
        return NULL;
    }
    return ts;
}

static int set_str(char **dst, const char *s)
{
    char *d = fm_io_strndup(s, strlen(s));
    if (!d)
        return -1;
    free(*dst);
    *dst = d;
    return 0;
}

fm_tsurf *fm_tsurf_create(const char *name)
{
    fm_tsurf *ts = fm_tsurf_alloc();
    if (!ts)
        return NULL;
    /* New objects get the coordinate system of the CFM, so that what the
     * tool writes opens in the same frame as its inputs. */
    ts->has_crs = 1;
    if (set_str(&ts->crs_name, "Default") || set_str(&ts->crs_axis_unit, "\"m\" \"m\" \"m\"") ||
        fm_strlist_push(&ts->crs_extra, "AXIS_NAME \"X\" \"Y\" \"Z\"", 22) ||
        (name && name[0] && fm_tsurf_set_header(ts, "name", name) != FM_OK)) {
        fm_tsurf_destroy(ts);
        return NULL;
    }
    return ts;
}

void fm_tsurf_destroy(fm_tsurf *ts)
{
    if (!ts)
        return;
    fm_mesh_destroy(ts->mesh);
    free(ts->ids);
    free(ts->atoms);
    fm_strlist_free(&ts->hkeys);
    fm_strlist_free(&ts->hvalues);
    free(ts->crs_name);
    free(ts->crs_projection);
    free(ts->crs_datum);
    free(ts->crs_axis_unit);
    fm_strlist_free(&ts->crs_extra);
    fm_strlist_free(&ts->prop_names);
    free(ts->props);
    fm_strlist_free(&ts->extra);
    free(ts->bstones);
    free(ts->borders);
    free(ts);
}

void fm_tsurf_free_all(fm_tsurf **objects, size_t count)
{
    if (!objects)
        return;
    for (size_t i = 0; i < count; i++)
        fm_tsurf_destroy(objects[i]);
    free(objects);
}

int fm_tsurf_add_part(fm_tsurf *ts)
{
    if (ts->nparts >= (size_t)INT32_MAX)
        return -1;
    return (int)ts->nparts++;
}

fm_status fm_tsurf_set_header(fm_tsurf *ts, const char *key, const char *value)
{
    /* Anything that would break the "key:value" line on writing. */
    if (!key[0] || strpbrk(key, ":}\r\n") || strpbrk(value, "}\r\n"))
        return FM_ERR_INVALID;
    for (size_t i = 0; i < ts->hkeys.n; i++) {
        if (strcmp(ts->hkeys.items[i], key) == 0)
            return set_str(&ts->hvalues.items[i], value) ? FM_ERR_NOMEM : FM_OK;
    }
    if (fm_strlist_push(&ts->hkeys, key, strlen(key)))
        return FM_ERR_NOMEM;
    if (fm_strlist_push(&ts->hvalues, value, strlen(value))) {
        free(ts->hkeys.items[--ts->hkeys.n]);
        return FM_ERR_NOMEM;
    }
    return FM_OK;
}

const char *fm_tsurf_name(const fm_tsurf *ts)
{
    const char *n = fm_tsurf_header_get(ts, "name");
    return n ? n : "";
}

const fm_mesh *fm_tsurf_mesh(const fm_tsurf *ts) { return ts->mesh; }
fm_mesh *fm_tsurf_mesh_mut(fm_tsurf *ts) { return ts->mesh; }
size_t fm_tsurf_nparts(const fm_tsurf *ts) { return ts->nparts; }
size_t fm_tsurf_nskipped(const fm_tsurf *ts) { return ts->nskipped; }

const int64_t *fm_tsurf_vertex_ids(const fm_tsurf *ts)
{
    size_t nv = fm_mesh_nvertices(ts->mesh);
    return nv && ts->nids == nv ? ts->ids : NULL;
}

const int32_t *fm_tsurf_atom_targets(const fm_tsurf *ts)
{
    size_t nv = fm_mesh_nvertices(ts->mesh);
    return ts->atoms && ts->natoms == nv ? ts->atoms : NULL;
}

fm_status fm_tsurf_set_vertex_ids(fm_tsurf *ts, const int64_t *ids, size_t n)
{
    if (!ids) {
        ts->nids = 0;
        return FM_OK;
    }
    if (n != fm_mesh_nvertices(ts->mesh))
        return FM_ERR_INVALID;
    fm_idmap seen;
    fm_idmap_init(&seen);
    for (size_t i = 0; i < n; i++) {
        int k = ids[i] < 0 ? 1 : fm_idmap_add(&seen, ids[i]);
        if (k != 0) {
            fm_idmap_free(&seen);
            return k > 0 ? FM_ERR_INVALID : FM_ERR_NOMEM;
        }
    }
    fm_idmap_free(&seen);
    if (fm_io_grow((void **)&ts->ids, &ts->cap_ids, n, sizeof *ts->ids))
        return FM_ERR_NOMEM;
    if (n)
        memcpy(ts->ids, ids, n * sizeof *ids);
    ts->nids = n;
    return FM_OK;
}

void fm_tsurf_clear_vertex_data(fm_tsurf *ts)
{
    ts->nids = 0;
    free(ts->atoms);
    ts->atoms = NULL;
    ts->natoms = ts->cap_atoms = 0;
    fm_strlist_free(&ts->prop_names);
    free(ts->props);
    ts->props = NULL;
    ts->nprop_vertices = ts->cap_prop_vertices = 0;
    ts->nbstones = 0;
    ts->nborders = 0;
}

size_t fm_tsurf_nheader(const fm_tsurf *ts) { return ts->hkeys.n; }
const char *fm_tsurf_header_key(const fm_tsurf *ts, size_t i) { return ts->hkeys.items[i]; }
const char *fm_tsurf_header_value(const fm_tsurf *ts, size_t i) { return ts->hvalues.items[i]; }

const char *fm_tsurf_header_get(const fm_tsurf *ts, const char *key)
{
    for (size_t i = 0; i < ts->hkeys.n; i++)
        if (strcmp(ts->hkeys.items[i], key) == 0)
            return ts->hvalues.items[i];
    return NULL;
}

fm_status fm_tsurf_set_crs_name(fm_tsurf *ts, const char *name)
{
    if (!name || !name[0])
        return FM_ERR_INVALID;
    for (const unsigned char *p = (const unsigned char *)name; *p; p++)
        if (*p < 0x20 || *p == 0x7f)
            return FM_ERR_INVALID;
    if (set_str(&ts->crs_name, name))
        return FM_ERR_NOMEM;
    ts->has_crs = 1;
    return FM_OK;
}

const char *fm_tsurf_crs_code(const fm_tsurf *ts)
{
    const char *s = ts->has_crs ? ts->crs_name : NULL;
    if (!s)
        return NULL;
    size_t i = 0;
    while (isalpha((unsigned char)s[i]))
        i++;
    if (i == 0 || s[i] != ':' || !s[i + 1])
        return NULL;
    for (i++; s[i]; i++)
        if (!isalnum((unsigned char)s[i]) && !strchr(".-_", s[i]))
            return NULL;
    return s;
}

void fm_tsurf_get_crs(const fm_tsurf *ts, fm_tsurf_crs *crs)
{
    crs->name = ts->crs_name ? ts->crs_name : "";
    crs->projection = ts->crs_projection ? ts->crs_projection : "";
    crs->datum = ts->crs_datum ? ts->crs_datum : "";
    crs->axis_unit = ts->crs_axis_unit ? ts->crs_axis_unit : "";
    crs->z_positive_depth = ts->z_depth;
}

size_t fm_tsurf_nprops(const fm_tsurf *ts) { return ts->prop_names.n; }
const char *fm_tsurf_prop_name(const fm_tsurf *ts, size_t i) { return ts->prop_names.items[i]; }

const double *fm_tsurf_prop_values(const fm_tsurf *ts)
{
    size_t nv = fm_mesh_nvertices(ts->mesh);
    return ts->prop_names.n && nv && ts->nprop_vertices == nv ? ts->props : NULL;
}

fm_status fm_tsurf_set_props(fm_tsurf *ts, size_t nprops, const char *const *names,
                             const double *values)
{
    size_t nv = fm_mesh_nvertices(ts->mesh);
    fm_strlist names_new = {0};
    double *vals = NULL;
    for (size_t i = 0; i < nprops; i++) {
        size_t len = strlen(names[i]);
        if (len == 0 || strpbrk(names[i], " \t\r\n")) {
            fm_strlist_free(&names_new);
            return FM_ERR_INVALID;
        }
        if (fm_strlist_push(&names_new, names[i], len)) {
            fm_strlist_free(&names_new);
            return FM_ERR_NOMEM;
        }
    }
    if (nprops && nv) {
        vals = malloc(nv * nprops * sizeof *vals);
        if (!vals) {
            fm_strlist_free(&names_new);
            return FM_ERR_NOMEM;
        }
        memcpy(vals, values, nv * nprops * sizeof *vals);
    }
    fm_strlist_free(&ts->prop_names);
    free(ts->props);
    ts->prop_names = names_new;
    ts->props = vals;
    ts->nprop_vertices = nprops ? nv : 0;
    ts->cap_prop_vertices = ts->nprop_vertices;
    return FM_OK;
}

size_t fm_tsurf_nbstones(const fm_tsurf *ts) { return ts->nbstones; }
const int32_t *fm_tsurf_bstones(const fm_tsurf *ts) { return ts->bstones; }
size_t fm_tsurf_nborders(const fm_tsurf *ts) { return ts->nborders; }
const int32_t *fm_tsurf_borders(const fm_tsurf *ts) { return ts->borders; }
