/* Deformation-model fault sections from GeoJSON (fm_sections.h). */
#include <json-c/json.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_sections.h"

/* A section as the files have given it so far. */
typedef struct partial {
    long id;
    char *name;
    double v[6]; /* dip, dip_dir, rake, up, low, rate */
    unsigned char has[6];
    double *trace;
    size_t ntrace;
} partial;

enum { K_DIP, K_DIPDIR, K_RAKE, K_UP, K_LOW, K_RATE };

struct fm_sections {
    partial *p;
    size_t n, cap;
    fm_section *sec; /* the complete ones, by FaultID */
    size_t nsec, incomplete;
};

void fm_sections_destroy(fm_sections *s)
{
    if (!s)
        return;
    for (size_t i = 0; i < s->n; i++) {
        free(s->p[i].name);
        free(s->p[i].trace);
    }
    free(s->p);
    free(s->sec);
    free(s);
}

size_t fm_sections_count(const fm_sections *s) { return s->nsec; }
const fm_section *fm_sections_get(const fm_sections *s, size_t i) { return &s->sec[i]; }
size_t fm_sections_incomplete(const fm_sections *s) { return s->incomplete; }

/* The compass direction of DipDir as an azimuth; NAN for Vertical or an
 * unknown word. */
static double compass(const char *s)
{
    static const char *const name[8] = {"N", "NE", "E", "SE", "S", "SW", "W", "NW"};
    for (int k = 0; k < 8; k++)
        if (!strcmp(s, name[k]))
            return 45.0 * k;
    return NAN;
}

static int number(json_object *o, double *v)
{
    if (!o || !(json_object_is_type(o, json_type_double) || json_object_is_type(o, json_type_int)))
        return 0;
    *v = json_object_get_double(o);
    return isfinite(*v);
}

static partial *entry(fm_sections *s, long id)
{
    for (size_t i = 0; i < s->n; i++)
        if (s->p[i].id == id)
            return &s->p[i];
    if (s->n == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 256;
        partial *p = realloc(s->p, cap * sizeof *p);
        if (!p)
            return NULL;
        s->p = p;
        s->cap = cap;
    }
    partial *e = &s->p[s->n++];
    memset(e, 0, sizeof *e);
    e->id = id;
    return e;
}

/* The trace of a LineString or MultiLineString, its parts end to end;
 * 0 when there is none, -1 when memory runs out. */
static int trace_of(json_object *geom, partial *e)
{
    json_object *type, *coords;
    if (!geom || !json_object_object_get_ex(geom, "type", &type) ||
        !json_object_object_get_ex(geom, "coordinates", &coords) ||
        !json_object_is_type(coords, json_type_array))
        return 0;
    const char *t = json_object_get_string(type);
    int multi = t && !strcmp(t, "MultiLineString");
    if (!multi && !(t && !strcmp(t, "LineString")))
        return 0;
    size_t nparts = multi ? json_object_array_length(coords) : 1, total = 0;
    for (size_t k = 0; k < nparts; k++) {
        json_object *part = multi ? json_object_array_get_idx(coords, k) : coords;
        if (json_object_is_type(part, json_type_array))
            total += json_object_array_length(part);
    }
    double *xy = malloc((2 * total + 1) * sizeof *xy);
    if (!xy)
        return -1;
    size_t n = 0;
    for (size_t k = 0; k < nparts; k++) {
        json_object *part = multi ? json_object_array_get_idx(coords, k) : coords;
        if (!json_object_is_type(part, json_type_array))
            continue;
        for (size_t i = 0; i < json_object_array_length(part); i++) {
            json_object *pt = json_object_array_get_idx(part, i);
            double lon, lat;
            if (!json_object_is_type(pt, json_type_array) || json_object_array_length(pt) < 2 ||
                !number(json_object_array_get_idx(pt, 0), &lon) ||
                !number(json_object_array_get_idx(pt, 1), &lat))
                continue;
            /* a part starting where the last ended does not repeat the point */
            if (n && xy[2 * n - 2] == lon && xy[2 * n - 1] == lat)
                continue;
            xy[2 * n] = lon;
            xy[2 * n + 1] = lat;
            n++;
        }
    }
    if (n < 2) {
        free(xy);
        return 0;
    }
    free(e->trace);
    e->trace = xy;
    e->ntrace = n;
    return 1;
}

static fm_status read_one(fm_sections *s, const char *path, fm_error *err)
{
    json_object *root = json_object_from_file(path);
    if (!root)
        return fm_error_set(err, FM_ERR_PARSE, path, 0, "not JSON: %s", json_util_get_last_err());
    json_object *features;
    fm_status st = FM_OK;
    if (!json_object_object_get_ex(root, "features", &features) ||
        !json_object_is_type(features, json_type_array)) {
        st = fm_error_set(err, FM_ERR_PARSE, path, 0,
                          "not a GeoJSON FeatureCollection (no \"features\" array)");
        json_object_put(root);
        return st;
    }
    static const char *const key[6] = {"DipDeg", "DipDir", "Rake", "UpDepth", "LowDepth",
                                       "PrefRate"};
    for (size_t i = 0; i < json_object_array_length(features) && st == FM_OK; i++) {
        json_object *f = json_object_array_get_idx(features, i), *props, *idv, *geom = NULL;
        double id;
        if (!json_object_object_get_ex(f, "properties", &props) ||
            !json_object_object_get_ex(props, "FaultID", &idv) || !number(idv, &id))
            continue;
        partial *e = entry(s, (long)id);
        if (!e) {
            st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
            break;
        }
        json_object *v;
        if (json_object_object_get_ex(props, "FaultName", &v) &&
            json_object_is_type(v, json_type_string)) {
            char *nm = strdup(json_object_get_string(v));
            if (!nm) {
                st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
                break;
            }
            free(e->name);
            e->name = nm;
        }
        for (int k = 0; k < 6; k++) {
            if (!json_object_object_get_ex(props, key[k], &v))
                continue;
            double x;
            if (k == K_DIPDIR && json_object_is_type(v, json_type_string)) {
                e->v[k] = compass(json_object_get_string(v));
                e->has[k] = 1;
            } else if (number(v, &x)) {
                e->v[k] = x;
                e->has[k] = 1;
            }
        }
        json_object_object_get_ex(f, "geometry", &geom);
        if (trace_of(geom, e) < 0)
            st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    json_object_put(root);
    return st;
}

static int by_id(const void *a, const void *b)
{
    long x = ((const fm_section *)a)->id, y = ((const fm_section *)b)->id;
    return (x > y) - (x < y);
}

fm_status fm_sections_read(const char *const *paths, size_t n, fm_sections **out, fm_error *err)
{
    *out = NULL;
    fm_sections *s = calloc(1, sizeof *s);
    if (!s)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    for (size_t i = 0; i < n; i++) {
        fm_status st = read_one(s, paths[i], err);
        if (st != FM_OK) {
            fm_sections_destroy(s);
            return st;
        }
    }
    s->sec = calloc(s->n + 1, sizeof *s->sec);
    if (!s->sec) {
        fm_sections_destroy(s);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    for (size_t i = 0; i < s->n; i++) {
        const partial *e = &s->p[i];
        double dip = e->v[K_DIP];
        if (!e->trace || !e->has[K_DIP] || !e->has[K_RAKE] || !e->has[K_UP] || !e->has[K_LOW] ||
            !(dip > 0 && dip <= 90) || !(e->v[K_LOW] > e->v[K_UP])) {
            s->incomplete++;
            continue;
        }
        double rake = fmod(e->v[K_RAKE], 360);
        rake = rake > 180 ? rake - 360 : rake <= -180 ? rake + 360 : rake;
        s->sec[s->nsec++] = (fm_section){e->id,
                                         e->name ? e->name : "",
                                         dip,
                                         e->has[K_DIPDIR] ? e->v[K_DIPDIR] : NAN,
                                         rake,
                                         e->v[K_UP],
                                         e->v[K_LOW],
                                         e->has[K_RATE] ? e->v[K_RATE] : 0,
                                         e->has[K_RATE],
                                         e->trace,
                                         e->ntrace};
    }
    qsort(s->sec, s->nsec, sizeof *s->sec, by_id);
    *out = s;
    return FM_OK;
}
