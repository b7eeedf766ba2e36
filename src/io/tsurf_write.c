/* GoCAD TSurf writer. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_atomic.h"
#include "tsurf_internal.h"
#include "tsurf_lex.h"

/* Lines are assembled by hand in a block buffer: printf-style formatting
 * of millions of numbers would dominate the time of writing a CFM set. */
typedef struct out {
    FILE *fp;
    size_t n;
    int failed; /* errno of the first failed write, 0 if none */
    char buf[1 << 16];
} out;

static void out_flush(out *o)
{
    if (o->n && fwrite(o->buf, 1, o->n, o->fp) != o->n && !o->failed)
        o->failed = errno ? errno : EIO;
    o->n = 0;
}

/* Makes room for n more bytes (n small). */
static char *out_room(out *o, size_t n)
{
    if (o->n + n > sizeof o->buf)
        out_flush(o);
    return o->buf + o->n;
}

static void out_str(out *o, const char *s)
{
    size_t n = strlen(s);
    if (n > sizeof o->buf / 2) { /* long header values: pass through */
        out_flush(o);
        if (fwrite(s, 1, n, o->fp) != n && !o->failed)
            o->failed = errno ? errno : EIO;
        return;
    }
    memcpy(out_room(o, n), s, n);
    o->n += n;
}

static void out_line(out *o, const char *a, const char *b)
{
    out_str(o, a);
    if (b)
        out_str(o, b);
    out_str(o, "\n");
}

static void out_i64(out *o, int64_t v)
{
    char tmp[24];
    int k = 0;
    uint64_t u = v < 0 ? 0 - (uint64_t)v : (uint64_t)v;
    do {
        tmp[k++] = (char)('0' + u % 10);
        u /= 10;
    } while (u);
    char *p = out_room(o, 24);
    size_t n = 0;
    if (v < 0)
        p[n++] = '-';
    while (k)
        p[n++] = tmp[--k];
    o->n += n;
}

static void out_f64(out *o, double x)
{
    o->n += fm_format_double(out_room(o, 40), x);
}

static void out_char(out *o, char c)
{
    *out_room(o, 1) = c;
    o->n++;
}

typedef struct plan {
    size_t nv, nt, nparts, np;
    const double *xyz, *props;
    const int32_t *tri, *tag, *atoms;
    int64_t *ids;      /* id written for each vertex */
    int32_t *home;     /* part each vertex is declared in */
    int32_t *vorder;   /* vertices sorted by home part, then index */
    size_t *vstart;    /* nparts + 1 offsets into vorder */
    int32_t *torder;   /* triangles sorted by part, then index */
    size_t *tstart;    /* nparts + 1 offsets into torder */
    int32_t *as_atom;  /* target index when written as ATOM, else -1 */
    int32_t *stamp;    /* part (+1) for which fresh[v] is valid */
    int64_t *fresh;    /* id of v re-declared as ATOM in the current part */
    int64_t next_id;
} plan;

static void plan_free(plan *pl)
{
    free(pl->ids);
    free(pl->home);
    free(pl->vorder);
    free(pl->vstart);
    free(pl->torder);
    free(pl->tstart);
    free(pl->as_atom);
    free(pl->stamp);
    free(pl->fresh);
}

/* Counting sort of n items by key[i] in [0, nkeys): order and start. */
static void bucket(const int32_t *key, size_t n, size_t nkeys, int32_t *order, size_t *start)
{
    memset(start, 0, (nkeys + 1) * sizeof *start);
    for (size_t i = 0; i < n; i++)
        start[key[i] + 1]++;
    for (size_t k = 0; k < nkeys; k++)
        start[k + 1] += start[k];
    for (size_t i = 0; i < n; i++)
        order[start[key[i]]++] = (int32_t)i;
    for (size_t k = nkeys; k > 0; k--)
        start[k] = start[k - 1];
    start[0] = 0;
}

static fm_status plan_make(plan *pl, const fm_tsurf *ts, const char *name, size_t obj,
                           fm_error *err)
{
    memset(pl, 0, sizeof *pl);
    const fm_mesh *m = ts->mesh;
    pl->nv = fm_mesh_nvertices(m);
    pl->nt = fm_mesh_ntriangles(m);
    pl->xyz = fm_mesh_vertices(m);
    pl->tri = fm_mesh_triangles(m);
    pl->tag = fm_mesh_tags(m);
    pl->atoms = fm_tsurf_atom_targets(ts);
    pl->np = fm_tsurf_nprops(ts);
    pl->props = fm_tsurf_prop_values(ts);
    size_t nv = pl->nv, nt = pl->nt;

    if (pl->np && nv && !pl->props)
        return fm_error_set(err, FM_ERR_INVALID, name, 0,
                            "object %zu: properties cover %zu vertices, the mesh has %zu", obj + 1,
                            ts->nprop_vertices, nv);
    for (size_t i = 0; i < 3 * nv; i++)
        if (!isfinite(pl->xyz[i]))
            return fm_error_set(err, FM_ERR_NUMERIC, name, 0,
                                "object %zu: vertex %zu has a non-finite coordinate", obj + 1,
                                i / 3);
    if (pl->props)
        for (size_t i = 0; i < pl->np * nv; i++)
            if (!isfinite(pl->props[i]))
                return fm_error_set(err, FM_ERR_NUMERIC, name, 0,
                                    "object %zu: vertex %zu has a non-finite property", obj + 1,
                                    i / pl->np);
    size_t nparts = ts->nparts;
    for (size_t t = 0; t < nt; t++) {
        if (pl->tag[t] < 0)
            return fm_error_set(err, FM_ERR_INVALID, name, 0,
                                "object %zu: triangle %zu has a negative part", obj + 1, t);
        if ((size_t)pl->tag[t] >= nparts)
            nparts = (size_t)pl->tag[t] + 1;
        for (int k = 0; k < 3; k++)
            if (pl->tri[3 * t + k] < 0 || (size_t)pl->tri[3 * t + k] >= nv)
                return fm_error_set(err, FM_ERR_INVALID, name, 0,
                                    "object %zu: triangle %zu names vertex %d of %zu", obj + 1, t,
                                    (int)pl->tri[3 * t + k], nv);
    }
    for (size_t i = 0; i < ts->nbstones; i++)
        if (ts->bstones[i] < 0 || (size_t)ts->bstones[i] >= nv)
            return fm_error_set(err, FM_ERR_INVALID, name, 0,
                                "object %zu: BSTONE names vertex %d of %zu", obj + 1,
                                (int)ts->bstones[i], nv);
    for (size_t i = 0; i < ts->nborders; i++)
        for (int k = 1; k < 3; k++)
            if (ts->borders[3 * i + k] < 0 || (size_t)ts->borders[3 * i + k] >= nv)
                return fm_error_set(err, FM_ERR_INVALID, name, 0,
                                    "object %zu: BORDER names vertex %d of %zu", obj + 1,
                                    (int)ts->borders[3 * i + k], nv);
    if (nt == 0)
        return fm_error_set(err, FM_ERR_INVALID, name, 0,
                            "object %zu has no triangles (it would not read back)", obj + 1);
    pl->nparts = nparts;

    size_t nva = nv ? nv : 1, nta = nt ? nt : 1;
    pl->ids = malloc(nva * sizeof *pl->ids);
    pl->home = malloc(nva * sizeof *pl->home);
    pl->vorder = malloc(nva * sizeof *pl->vorder);
    pl->vstart = malloc((nparts + 2) * sizeof *pl->vstart);
    pl->torder = malloc(nta * sizeof *pl->torder);
    pl->tstart = malloc((nparts + 2) * sizeof *pl->tstart);
    pl->as_atom = malloc(nva * sizeof *pl->as_atom);
    pl->stamp = calloc(nva, sizeof *pl->stamp);
    pl->fresh = malloc(nva * sizeof *pl->fresh);
    if (!pl->ids || !pl->home || !pl->vorder || !pl->vstart || !pl->torder || !pl->tstart ||
        !pl->as_atom || !pl->stamp || !pl->fresh)
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");

    const int64_t *fids = fm_tsurf_vertex_ids(ts);
    int64_t maxid = 0;
    for (size_t v = 0; v < nv; v++) {
        pl->ids[v] = fids ? fids[v] : (int64_t)v + 1;
        if (pl->ids[v] > maxid)
            maxid = pl->ids[v];
    }
    if (maxid == INT64_MAX)
        return fm_error_set(err, FM_ERR_INVALID, name, 0, "object %zu: no vertex id left for ATOM",
                            obj + 1);
    pl->next_id = maxid + 1;

    /* Home part: the first part whose triangles use the vertex. */
    for (size_t v = 0; v < nv; v++)
        pl->home[v] = INT32_MAX;
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3; k++) {
            int32_t v = pl->tri[3 * t + k];
            if (pl->tag[t] < pl->home[v])
                pl->home[v] = pl->tag[t];
        }
    int32_t first = INT32_MAX;
    for (size_t t = 0; t < nt; t++)
        if (pl->tag[t] < first)
            first = pl->tag[t];
    for (size_t v = 0; v < nv; v++)
        if (pl->home[v] == INT32_MAX)
            pl->home[v] = v ? pl->home[v - 1] : first;
    bucket(pl->home, nv, nparts, pl->vorder, pl->vstart);
    bucket(pl->tag, nt, nparts, pl->torder, pl->tstart);

    /* An atom is only written as ATOM when that reproduces it exactly:
     * its target declared before it, same coordinates and properties. */
    char *declared = calloc(nva, 1);
    if (!declared)
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
    for (size_t i = 0; i < nv; i++) {
        int32_t v = pl->vorder[i];
        int32_t t = pl->atoms ? pl->atoms[v] : -1;
        pl->as_atom[v] = -1;
        if (t >= 0 && (size_t)t < nv && declared[t] &&
            memcmp(pl->xyz + 3 * (size_t)t, pl->xyz + 3 * (size_t)v, 3 * sizeof(double)) == 0 &&
            (!pl->props || memcmp(pl->props + (size_t)t * pl->np, pl->props + (size_t)v * pl->np,
                                  pl->np * sizeof(double)) == 0))
            pl->as_atom[v] = t;
        declared[v] = 1;
    }
    free(declared);
    return FM_OK;
}

static void write_vertex(out *o, const plan *pl, int32_t v)
{
    if (pl->as_atom[v] >= 0) {
        out_str(o, "ATOM ");
        out_i64(o, pl->ids[v]);
        out_char(o, ' ');
        out_i64(o, pl->ids[pl->as_atom[v]]);
        out_char(o, '\n');
        return;
    }
    out_str(o, pl->props ? "PVRTX " : "VRTX ");
    out_i64(o, pl->ids[v]);
    for (int k = 0; k < 3; k++) {
        out_char(o, ' ');
        out_f64(o, pl->xyz[3 * (size_t)v + k]);
    }
    for (size_t k = 0; pl->props && k < pl->np; k++) {
        out_char(o, ' ');
        out_f64(o, pl->props[(size_t)v * pl->np + k]);
    }
    out_char(o, '\n');
}

/* The id under which vertex v is known inside part p; re-declares it as an
 * ATOM of this part first when it lives in an earlier part. */
static int64_t id_in_part(out *o, plan *pl, int32_t v, int32_t p)
{
    if (pl->home[v] == p)
        return pl->ids[v];
    if (pl->stamp[v] != p + 1) {
        int32_t root = v;
        while (pl->as_atom[root] >= 0)
            root = pl->as_atom[root];
        pl->stamp[v] = p + 1;
        pl->fresh[v] = pl->next_id++;
        out_str(o, "ATOM ");
        out_i64(o, pl->fresh[v]);
        out_char(o, ' ');
        out_i64(o, pl->ids[root]);
        out_char(o, '\n');
    }
    return pl->fresh[v];
}

static void write_parts(out *o, plan *pl)
{
    for (size_t p = 0; p < pl->nparts; p++) {
        if (pl->tstart[p] == pl->tstart[p + 1])
            continue; /* a part without triangles would not read back */
        out_str(o, "TFACE\n");
        for (size_t i = pl->vstart[p]; i < pl->vstart[p + 1]; i++)
            write_vertex(o, pl, pl->vorder[i]);
        /* Atoms for vertices of earlier parts, all before the first TRGL. */
        for (size_t i = pl->tstart[p]; i < pl->tstart[p + 1]; i++)
            for (int k = 0; k < 3; k++)
                (void)id_in_part(o, pl, pl->tri[3 * (size_t)pl->torder[i] + k], (int32_t)p);
        for (size_t i = pl->tstart[p]; i < pl->tstart[p + 1]; i++) {
            const int32_t *t = pl->tri + 3 * (size_t)pl->torder[i];
            out_str(o, "TRGL");
            for (int k = 0; k < 3; k++) {
                out_char(o, ' ');
                out_i64(o, id_in_part(o, pl, t[k], (int32_t)p));
            }
            out_char(o, '\n');
        }
    }
}

static void write_head(out *o, const fm_tsurf *ts)
{
    out_str(o, "GOCAD TSurf 1\nHEADER {\n");
    for (size_t i = 0; i < ts->hkeys.n; i++) {
        out_str(o, ts->hkeys.items[i]);
        out_char(o, ':');
        out_line(o, ts->hvalues.items[i], NULL);
    }
    out_str(o, "}\n");
    if (ts->has_crs) {
        out_str(o, "GOCAD_ORIGINAL_COORDINATE_SYSTEM\n");
        if (ts->crs_name)
            out_line(o, "NAME ", ts->crs_name);
        if (ts->crs_projection)
            out_line(o, "PROJECTION ", ts->crs_projection);
        if (ts->crs_datum)
            out_line(o, "DATUM ", ts->crs_datum);
        for (size_t i = 0; i < ts->crs_extra.n; i++)
            out_line(o, ts->crs_extra.items[i], NULL);
        if (ts->crs_axis_unit)
            out_line(o, "AXIS_UNIT ", ts->crs_axis_unit);
        /* Depth files were converted to elevation on reading. */
        out_str(o, "ZPOSITIVE Elevation\nEND_ORIGINAL_COORDINATE_SYSTEM\n");
    }
    if (ts->prop_names.n) {
        out_str(o, "PROPERTIES");
        for (size_t i = 0; i < ts->prop_names.n; i++) {
            out_char(o, ' ');
            out_str(o, ts->prop_names.items[i]);
        }
        out_char(o, '\n');
    }
    for (size_t i = 0; i < ts->extra.n; i++)
        out_line(o, ts->extra.items[i], NULL);
}

static void write_tail(out *o, const fm_tsurf *ts, const plan *pl)
{
    for (size_t i = 0; i < ts->nbstones; i++) {
        out_str(o, "BSTONE ");
        out_i64(o, pl->ids[ts->bstones[i]]);
        out_char(o, '\n');
    }
    for (size_t i = 0; i < ts->nborders; i++) {
        const int32_t *b = ts->borders + 3 * i;
        out_str(o, "BORDER ");
        out_i64(o, b[0]);
        out_char(o, ' ');
        out_i64(o, pl->ids[b[1]]);
        out_char(o, ' ');
        out_i64(o, pl->ids[b[2]]);
        out_char(o, '\n');
    }
    out_str(o, "END\n");
}

fm_status fm_tsurf_write_stream(FILE *fp, const char *name, fm_tsurf *const *objects,
                                size_t count, fm_error *err)
{
    out *o = malloc(sizeof *o);
    if (!o)
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
    o->fp = fp;
    o->n = 0;
    o->failed = 0;
    fm_status st = FM_OK;
    for (size_t i = 0; i < count && st == FM_OK; i++) {
        plan pl;
        st = plan_make(&pl, objects[i], name, i, err);
        if (st == FM_OK) {
            write_head(o, objects[i]);
            write_parts(o, &pl);
            write_tail(o, objects[i], &pl);
        }
        plan_free(&pl);
    }
    out_flush(o);
    /* a full disk often shows only when the stream's own buffer goes */
    if (st == FM_OK && !o->failed && (ferror(fp) || fflush(fp) != 0))
        o->failed = errno ? errno : EIO;
    if (st == FM_OK && o->failed)
        st = fm_error_set(err, FM_ERR_IO, name, 0, "cannot write: %s", strerror(o->failed));
    free(o);
    return st;
}

fm_status fm_tsurf_write_file(const char *path, fm_tsurf *const *objects, size_t count,
                              fm_error *err)
{
    if (count == 0 || !objects) /* an empty file would not read back */
        return fm_error_set(err, FM_ERR_INVALID, path, 0, "no object to write");
    fm_atomic_file *f = fm_atomic_open(path, err);
    if (!f)
        return err ? err->code : FM_ERR_IO;
    fm_status st = fm_tsurf_write_stream(fm_atomic_stream(f), path, objects, count, err);
    if (st != FM_OK) {
        fm_atomic_abort(f);
        return st;
    }
    return fm_atomic_commit(f, err);
}
