/* GoCAD TSurf reader.
 *
 * The file is read into one buffer and scanned line by line in place; the
 * body lines (VRTX, TRGL: millions per CFM set) are parsed without any
 * allocation beyond the amortised growth of the output arrays. Header lines
 * are few and simply copied. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "tsurf_idmap.h"
#include "tsurf_internal.h"
#include "tsurf_lex.h"

/* GoCAD's own no-data value, used for vertices given without properties
 * in an object that has some, unless NO_DATA_VALUES says otherwise. */
#define GOCAD_NO_DATA (-99999.0)

typedef enum state {
    S_TOP,    /* between objects: expecting "GOCAD TSurf 1" */
    S_HEAD,   /* after the GOCAD line, before the first body line */
    S_BODY,   /* TFACE, VRTX, TRGL, ... */
    S_HEADER, /* inside HEADER { ... } */
    S_CRS,    /* inside GOCAD_ORIGINAL_COORDINATE_SYSTEM ... END_... */
    S_CLASS   /* inside PROPERTY_CLASS_HEADER ... { ... } */
} state;

typedef struct reader {
    const char *name;
    fm_error *err;
    fm_lines L;
    state st;
    long block_line; /* where the open block started */

    fm_tsurf **objs;
    size_t nobjs, cap_objs;

    fm_tsurf *ts; /* object being read */
    fm_idmap ids;
    long obj_line;
    int in_part;
    long part_line;
    size_t part_first_tri;
    double *nodata;
    size_t nnodata, cap_nodata;
} reader;

static fm_status fail(reader *r, long line, fm_status code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

static fm_status fail(reader *r, long line, fm_status code, const char *fmt, ...)
{
    char msg[FM_ERROR_MESSAGE_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return fm_error_set(r->err, code, r->name, line, "%s", msg);
}

static fm_status nomem(reader *r) { return fail(r, r->L.line, FM_ERR_NOMEM, "out of memory"); }

/* Copies a token for a message: at most 40 bytes, non-printable bytes as
 * '?', so that a message about garbage stays one readable line. */
static const char *quote(char *buf, const char *s, const char *e)
{
    size_t n = 0;
    for (; s < e && n < 40; s++)
        buf[n++] = (unsigned char)*s < 0x20 || *s == 0x7f ? '?' : *s;
    if (s < e) {
        memcpy(buf + n, "...", 3);
        n += 3;
    }
    buf[n] = '\0';
    return buf;
}

static int is_kw(const char *s, const char *e, const char *kw)
{
    size_t n = strlen(kw);
    return (size_t)(e - s) == n && memcmp(s, kw, n) == 0;
}

/* Keywords that cannot appear inside a header block: seeing one there means
 * the block was never closed. */
static int is_structural(const char *s, const char *e)
{
    static const char *const kws[] = {"TFACE", "VRTX", "PVRTX", "ATOM", "PATOM", "TRGL",
                                      "END", "GOCAD", "GOCAD_ORIGINAL_COORDINATE_SYSTEM"};
    for (size_t i = 0; i < sizeof kws / sizeof kws[0]; i++)
        if (is_kw(s, e, kws[i]))
            return 1;
    return 0;
}

/* Lines kept or skipped without being parsed must at least be text. */
static fm_status check_text(reader *r, const char *s, const char *e)
{
    for (; s < e; s++) {
        unsigned char c = (unsigned char)*s;
        if ((c < 0x20 && c != '\t') || c == 0x7f)
            return fail(r, r->L.line, FM_ERR_PARSE, "binary (non-text) data");
    }
    return FM_OK;
}

static void object_label(const reader *r, char *buf, size_t n)
{
    const char *nm = r->ts ? fm_tsurf_name(r->ts) : "";
    if (nm[0])
        snprintf(buf, n, "%s", nm);
    else
        snprintf(buf, n, "#%zu", r->nobjs + 1);
}

/* ---- numbers in body lines ------------------------------------------- */

/* parsed: the token is a valid literal whose value overflowed. */
static fm_status bad_number(reader *r, const char *what, const char *p, const char *e,
                            int parsed)
{
    char q[48];
    const char *t = fm_lex_token_end(p, e);
    const char *u = p + (p < t && (*p == '-' || *p == '+'));
    if (parsed || (u < t && (*u == 'n' || *u == 'N' || *u == 'i' || *u == 'I')))
        return fail(r, r->L.line, FM_ERR_NUMERIC, "%s is not finite: %s", what,
                    quote(q, p, t));
    return fail(r, r->L.line, FM_ERR_PARSE, "%s is not a number: '%s'", what, quote(q, p, t));
}

/* Reads a vertex id at *pp (after blanks). */
static fm_status read_id(reader *r, const char **pp, const char *e, const char *kw,
                         int64_t *id)
{
    const char *p = fm_lex_skip_ws(*pp, e);
    if (p == e)
        return fail(r, r->L.line, FM_ERR_PARSE, "%s has too few fields", kw);
    const char *q = fm_lex_int64(p, e, id);
    if (!q) {
        char buf[48];
        return fail(r, r->L.line, FM_ERR_PARSE, "%s: bad vertex id '%s'", kw,
                    quote(buf, p, fm_lex_token_end(p, e)));
    }
    *pp = q;
    return FM_OK;
}

/* Reads a known vertex id and returns its index in *v. */
static fm_status read_ref(reader *r, const char **pp, const char *e, const char *kw,
                          int32_t *v)
{
    int64_t id;
    fm_status s = read_id(r, pp, e, kw, &id);
    if (s != FM_OK)
        return s;
    *v = fm_idmap_find(&r->ids, id);
    if (*v < 0)
        return fail(r, r->L.line, FM_ERR_PARSE, "%s names unknown vertex %lld", kw,
                    (long long)id);
    return FM_OK;
}

static fm_status read_double(reader *r, const char **pp, const char *e, const char *kw,
                             const char *what, double *x)
{
    const char *p = fm_lex_skip_ws(*pp, e);
    if (p == e)
        return fail(r, r->L.line, FM_ERR_PARSE, "%s has too few fields", kw);
    const char *q = fm_lex_double(p, e, x);
    if (!q || !isfinite(*x))
        return bad_number(r, what, p, e, q != NULL);
    *pp = q;
    return FM_OK;
}

/* ---- vertices and triangles ------------------------------------------ */

static void open_part_if_needed(reader *r)
{
    /* Vertices before any TFACE: be lenient and open the first part. */
    if (!r->in_part) {
        r->in_part = 1;
        r->part_line = r->L.line;
        r->part_first_tri = fm_mesh_ntriangles(r->ts->mesh);
        r->ts->nparts++;
    }
}

/* Registers a new vertex (coordinates xyz, properties props or NULL for
 * no-data, atom target or -1). */
static fm_status add_vertex(reader *r, int64_t id, const double *xyz, const double *props,
                            int32_t atom)
{
    fm_tsurf *ts = r->ts;
    int dup = fm_idmap_add(&r->ids, id);
    if (dup > 0)
        return fail(r, r->L.line, FM_ERR_PARSE, "duplicate vertex id %lld", (long long)id);
    if (dup < 0 || fm_mesh_add_vertex(ts->mesh, xyz[0], xyz[1], xyz[2]) < 0)
        return nomem(r);
    size_t nv = ts->nids + 1;
    if (fm_io_grow((void **)&ts->ids, &ts->cap_ids, nv, sizeof *ts->ids))
        return nomem(r);
    ts->ids[ts->nids++] = id;
    if (atom >= 0 && !ts->atoms) {
        if (fm_io_grow((void **)&ts->atoms, &ts->cap_atoms, nv, sizeof *ts->atoms))
            return nomem(r);
        for (size_t i = 0; i + 1 < nv; i++)
            ts->atoms[i] = -1;
        ts->natoms = nv - 1;
    }
    if (ts->atoms) {
        if (fm_io_grow((void **)&ts->atoms, &ts->cap_atoms, nv, sizeof *ts->atoms))
            return nomem(r);
        ts->atoms[ts->natoms++] = atom;
    }
    size_t np = ts->prop_names.n;
    if (np) {
        if (fm_io_grow((void **)&ts->props, &ts->cap_prop_vertices, nv, np * sizeof(double)))
            return nomem(r);
        double *dst = ts->props + ts->nprop_vertices * np;
        for (size_t k = 0; k < np; k++)
            dst[k] = props ? props[k] : k < r->nnodata ? r->nodata[k] : GOCAD_NO_DATA;
        ts->nprop_vertices++;
    }
    return FM_OK;
}

/* VRTX id x y z / PVRTX id x y z p1 ... pn [extra tokens ignored]. */
static fm_status do_vrtx(reader *r, const char *p, const char *e, int pvrtx)
{
    const char *kw = pvrtx ? "PVRTX" : "VRTX";
    int64_t id;
    double xyz[3];
    fm_status s = read_id(r, &p, e, kw, &id);
    for (int k = 0; s == FM_OK && k < 3; k++)
        s = read_double(r, &p, e, kw, "coordinate", &xyz[k]);
    if (s != FM_OK)
        return s;
    if (r->ts->z_depth)
        xyz[2] = -xyz[2];
    size_t np = r->ts->prop_names.n;
    double small[16];
    double *props = NULL;
    if (pvrtx && np) {
        props = np <= 16 ? small : malloc(np * sizeof *props);
        if (!props)
            return nomem(r);
        for (size_t k = 0; s == FM_OK && k < np; k++) {
            const char *q = fm_lex_skip_ws(p, e);
            if (q == e)
                s = fail(r, r->L.line, FM_ERR_PARSE,
                         "PVRTX has %zu property values, PROPERTIES names %zu", k, np);
            else
                s = read_double(r, &p, e, kw, "property value", &props[k]);
        }
    }
    open_part_if_needed(r);
    if (s == FM_OK)
        s = add_vertex(r, id, xyz, props, -1);
    if (props != small)
        free(props);
    return s;
}

/* ATOM id ref / PATOM id ref [...]: a new vertex sharing ref's position
 * (and properties). */
static fm_status do_atom(reader *r, const char *p, const char *e, int patom)
{
    const char *kw = patom ? "PATOM" : "ATOM";
    int64_t id;
    int32_t t;
    fm_status s = read_id(r, &p, e, kw, &id);
    if (s == FM_OK)
        s = read_ref(r, &p, e, kw, &t);
    if (s != FM_OK)
        return s;
    const double *v = fm_mesh_vertices(r->ts->mesh) + 3 * (size_t)t;
    double xyz[3] = {v[0], v[1], v[2]};
    size_t np = r->ts->prop_names.n;
    double small[16];
    double *props = NULL;
    if (np) {
        props = np <= 16 ? small : malloc(np * sizeof *props);
        if (!props)
            return nomem(r);
        memcpy(props, r->ts->props + (size_t)t * np, np * sizeof *props);
    }
    open_part_if_needed(r);
    s = add_vertex(r, id, xyz, props, t);
    if (props != small)
        free(props);
    return s;
}

static fm_status do_trgl(reader *r, const char *p, const char *e)
{
    int32_t v[3];
    for (int k = 0; k < 3; k++) {
        fm_status s = read_ref(r, &p, e, "TRGL", &v[k]);
        if (s != FM_OK)
            return s;
    }
    /* a fourth index is no triangle: dropping it would mesh a surface the
     * file does not describe */
    if (fm_lex_skip_ws(p, e) != e)
        return fail(r, r->L.line, FM_ERR_PARSE, "TRGL has more than three vertex ids");
    open_part_if_needed(r);
    if (fm_mesh_add_triangle(r->ts->mesh, v[0], v[1], v[2], (int32_t)(r->ts->nparts - 1)) < 0)
        return nomem(r);
    return FM_OK;
}

static fm_status do_bstone(reader *r, const char *p, const char *e)
{
    int32_t v;
    fm_status s = read_ref(r, &p, e, "BSTONE", &v);
    if (s != FM_OK)
        return s;
    fm_tsurf *ts = r->ts;
    if (fm_io_grow((void **)&ts->bstones, &ts->cap_bstones, ts->nbstones + 1, sizeof(int32_t)))
        return nomem(r);
    ts->bstones[ts->nbstones++] = v;
    return FM_OK;
}

static fm_status do_border(reader *r, const char *p, const char *e)
{
    int64_t id;
    int32_t v1, v2;
    fm_status s = read_id(r, &p, e, "BORDER", &id);
    if (s == FM_OK && id > INT32_MAX)
        s = fail(r, r->L.line, FM_ERR_PARSE, "BORDER id %lld is too large", (long long)id);
    if (s == FM_OK)
        s = read_ref(r, &p, e, "BORDER", &v1);
    if (s == FM_OK)
        s = read_ref(r, &p, e, "BORDER", &v2);
    if (s != FM_OK)
        return s;
    fm_tsurf *ts = r->ts;
    if (fm_io_grow((void **)&ts->borders, &ts->cap_borders, 3 * (ts->nborders + 1),
                   sizeof(int32_t)))
        return nomem(r);
    int32_t *b = ts->borders + 3 * ts->nborders++;
    b[0] = (int32_t)id;
    b[1] = v1;
    b[2] = v2;
    return FM_OK;
}

/* Closes the open part at a TFACE or END line. */
static fm_status close_part(reader *r, int at_end)
{
    if (!r->in_part || fm_mesh_ntriangles(r->ts->mesh) > r->part_first_tri)
        return FM_OK;
    if (at_end && r->ts->nparts == 1)
        return FM_OK; /* reported as an object without triangles */
    return fail(r, r->part_line, FM_ERR_PARSE, "empty TFACE part (no triangles)");
}

static fm_status do_tface(reader *r)
{
    fm_status s = close_part(r, 0);
    if (s != FM_OK)
        return s;
    if (fm_tsurf_add_part(r->ts) < 0)
        return nomem(r);
    r->in_part = 1;
    r->part_line = r->L.line;
    r->part_first_tri = fm_mesh_ntriangles(r->ts->mesh);
    return FM_OK;
}

static fm_status finish_object(reader *r)
{
    fm_status s = close_part(r, 1);
    if (s != FM_OK)
        return s;
    if (fm_mesh_ntriangles(r->ts->mesh) == 0) {
        char label[256];
        object_label(r, label, sizeof label);
        return fail(r, r->L.line, FM_ERR_PARSE, "object %s has no triangles", label);
    }
    if (fm_io_grow((void **)&r->objs, &r->cap_objs, r->nobjs + 1, sizeof *r->objs))
        return nomem(r);
    r->objs[r->nobjs++] = r->ts;
    r->ts = NULL;
    fm_idmap_free(&r->ids);
    r->st = S_TOP;
    return FM_OK;
}

/* ---- header section --------------------------------------------------- */

static void trim(const char **s, const char **e)
{
    *s = fm_lex_skip_ws(*s, *e);
    fm_lex_rtrim(*s, e);
}

/* One "key:value" entry of the HEADER block, [s, e) trimmed. */
static fm_status header_entry(reader *r, const char *s, const char *e)
{
    if (s == e)
        return FM_OK;
    fm_status st = check_text(r, s, e);
    if (st != FM_OK)
        return st;
    const char *colon = memchr(s, ':', (size_t)(e - s));
    const char *ke = colon ? colon : e, *vs = colon ? colon + 1 : e, *ve = e;
    trim(&s, &ke);
    trim(&vs, &ve);
    fm_tsurf *ts = r->ts;
    if (fm_strlist_push(&ts->hkeys, s, (size_t)(ke - s)))
        return nomem(r);
    if (fm_strlist_push(&ts->hvalues, vs, (size_t)(ve - vs))) {
        /* The two lists must stay the same length. */
        free(ts->hkeys.items[--ts->hkeys.n]);
        return nomem(r);
    }
    return FM_OK;
}

/* Text after "HEADER": "{", "{name:x}", "{ name:x", or nothing. The
 * writer puts every entry on a line of its own, so an entry here must be
 * one that such a line would give back: not a comment, and not starting
 * with a keyword that ends the block. */
static fm_status do_header_open(reader *r, const char *p, const char *e)
{
    r->block_line = r->L.line;
    r->st = S_HEADER;
    const char *b = memchr(p, '{', (size_t)(e - p));
    if (b)
        p = b + 1;
    const char *c = memchr(p, '}', (size_t)(e - p));
    if (c) {
        r->st = S_HEAD;
        e = c;
    }
    trim(&p, &e);
    if (p < e && *p == '#')
        return FM_OK;
    if (is_structural(p, fm_lex_token_end(p, e)))
        return fail(r, r->L.line, FM_ERR_PARSE, "HEADER entry starts with a TSurf keyword");
    return header_entry(r, p, e);
}

static fm_status do_header_line(reader *r, const char *s, const char *e, const char *t)
{
    if (is_structural(s, t))
        return fail(r, r->block_line, FM_ERR_PARSE, "HEADER block is never closed");
    if (e - s == 1 && *s == '{')
        return FM_OK;
    /* every closing brace goes: a value ending in one would close the
     * block early when written back */
    while (e > s && e[-1] == '}') {
        r->st = S_HEAD;
        e--;
        fm_lex_rtrim(s, &e);
    }
    return header_entry(r, s, e);
}

static fm_status set_field(reader *r, char **dst, const char *s, const char *e)
{
    char *d = fm_io_strndup(s, (size_t)(e - s));
    if (!d)
        return nomem(r);
    free(*dst);
    *dst = d;
    return FM_OK;
}

static fm_status do_crs_line(reader *r, const char *s, const char *e, const char *t)
{
    fm_tsurf *ts = r->ts;
    const char *v = fm_lex_skip_ws(t, e);
    fm_status st = check_text(r, s, e);
    if (st != FM_OK)
        return st;
    if (is_kw(s, t, "END_ORIGINAL_COORDINATE_SYSTEM")) {
        r->st = S_HEAD;
        return FM_OK;
    }
    if (is_structural(s, t) || is_kw(s, t, "HEADER"))
        return fail(r, r->block_line, FM_ERR_PARSE,
                    "GOCAD_ORIGINAL_COORDINATE_SYSTEM block is never closed");
    if (is_kw(s, t, "NAME"))
        return set_field(r, &ts->crs_name, v, e);
    if (is_kw(s, t, "PROJECTION"))
        return set_field(r, &ts->crs_projection, v, e);
    if (is_kw(s, t, "DATUM"))
        return set_field(r, &ts->crs_datum, v, e);
    if (is_kw(s, t, "AXIS_UNIT"))
        return set_field(r, &ts->crs_axis_unit, v, e);
    if (is_kw(s, t, "ZPOSITIVE")) {
        if (is_kw(v, e, "Depth"))
            ts->z_depth = 1;
        else if (is_kw(v, e, "Elevation"))
            ts->z_depth = 0;
        else
            return fail(r, r->L.line, FM_ERR_PARSE, "ZPOSITIVE must be Elevation or Depth");
        return FM_OK;
    }
    return fm_strlist_push(&ts->crs_extra, s, (size_t)(e - s)) ? nomem(r) : FM_OK;
}

static fm_status do_class_line(reader *r, const char *s, const char *e, const char *t)
{
    fm_status st = check_text(r, s, e);
    if (st != FM_OK)
        return st;
    if (is_structural(s, t))
        return fail(r, r->block_line, FM_ERR_PARSE, "PROPERTY_CLASS_HEADER block is never closed");
    if (memchr(s, '}', (size_t)(e - s)))
        r->st = S_HEAD;
    return fm_strlist_push(&r->ts->extra, s, (size_t)(e - s)) ? nomem(r) : FM_OK;
}

static fm_status do_properties(reader *r, const char *p, const char *e)
{
    fm_tsurf *ts = r->ts;
    fm_strlist_free(&ts->prop_names);
    for (p = fm_lex_skip_ws(p, e); p < e; p = fm_lex_skip_ws(p, e)) {
        const char *t = fm_lex_token_end(p, e);
        if (fm_strlist_push(&ts->prop_names, p, (size_t)(t - p)))
            return nomem(r);
        p = t;
    }
    return FM_OK;
}

/* NO_DATA_VALUES: used to fill properties of plain VRTX lines; values that
 * do not parse are left at GoCAD's default (a header line is never fatal). */
static fm_status do_nodata(reader *r, const char *p, const char *e)
{
    r->nnodata = 0;
    for (p = fm_lex_skip_ws(p, e); p < e; p = fm_lex_skip_ws(p, e)) {
        double x;
        const char *q = fm_lex_double(p, e, &x);
        if (!q || !isfinite(x)) {
            x = GOCAD_NO_DATA;
            q = fm_lex_token_end(p, e);
        }
        if (fm_io_grow((void **)&r->nodata, &r->cap_nodata, r->nnodata + 1, sizeof(double)))
            return nomem(r);
        r->nodata[r->nnodata++] = x;
        p = q;
    }
    return FM_OK;
}

/* A header-section line that is not a body line. Returns FM_OK with
 * *is_body set when the line belongs to the body instead. */
static fm_status do_head_line(reader *r, const char *s, const char *e, const char *t,
                              int *is_body)
{
    *is_body = 0;
    if (is_kw(s, t, "HEADER"))
        return do_header_open(r, t, e);
    if (is_kw(s, t, "GOCAD_ORIGINAL_COORDINATE_SYSTEM")) {
        r->ts->has_crs = 1;
        r->block_line = r->L.line;
        r->st = S_CRS;
        return FM_OK;
    }
    if (is_kw(s, t, "GOCAD"))
        return fail(r, r->L.line, FM_ERR_PARSE, "GOCAD line before the END of the object at line %ld",
                    r->obj_line);
    if (is_structural(s, t) || is_kw(s, t, "BSTONE") || is_kw(s, t, "BORDER")) {
        *is_body = 1;
        r->st = S_BODY;
        return FM_OK;
    }
    fm_status st = check_text(r, s, e);
    if (st != FM_OK)
        return st;
    if (is_kw(s, t, "PROPERTIES"))
        return do_properties(r, t, e);
    if (is_kw(s, t, "NO_DATA_VALUES")) {
        st = do_nodata(r, t, e);
        if (st != FM_OK)
            return st;
    }
    if (is_kw(s, t, "PROPERTY_CLASS_HEADER")) {
        const char *b = memchr(s, '{', (size_t)(e - s));
        if (!b || !memchr(b, '}', (size_t)(e - b))) {
            r->block_line = r->L.line;
            r->st = S_CLASS;
        }
    }
    return fm_strlist_push(&r->ts->extra, s, (size_t)(e - s)) ? nomem(r) : FM_OK;
}

/* ---- lines ------------------------------------------------------------ */

static fm_status do_body_line(reader *r, const char *s, const char *e, const char *t)
{
    size_t n = (size_t)(t - s);
    /* By frequency: TRGL and VRTX are nearly all of a file. */
    if (n == 4 && memcmp(s, "TRGL", 4) == 0)
        return do_trgl(r, t, e);
    if (n == 4 && memcmp(s, "VRTX", 4) == 0)
        return do_vrtx(r, t, e, 0);
    if (is_kw(s, t, "PVRTX"))
        return do_vrtx(r, t, e, 1);
    if (is_kw(s, t, "ATOM"))
        return do_atom(r, t, e, 0);
    if (is_kw(s, t, "PATOM"))
        return do_atom(r, t, e, 1);
    if (is_kw(s, t, "TFACE"))
        return do_tface(r);
    if (is_kw(s, t, "BSTONE"))
        return do_bstone(r, t, e);
    if (is_kw(s, t, "BORDER"))
        return do_border(r, t, e);
    if (is_kw(s, t, "END"))
        return finish_object(r);
    if (is_kw(s, t, "GOCAD"))
        return fail(r, r->L.line, FM_ERR_PARSE, "GOCAD line before the END of the object at line %ld",
                    r->obj_line);
    fm_status st = check_text(r, s, e);
    if (st == FM_OK)
        r->ts->nskipped++;
    return st;
}

static fm_status do_top_line(reader *r, const char *s, const char *e, const char *t)
{
    const char *p = fm_lex_skip_ws(t, e);
    const char *u = fm_lex_token_end(p, e);
    if (!is_kw(s, t, "GOCAD") || !is_kw(p, u, "TSurf")) {
        char q[48];
        if (is_kw(s, t, "GOCAD") && p < u)
            return fail(r, r->L.line, FM_ERR_PARSE, "GOCAD %s objects are not supported, only TSurf",
                        quote(q, p, u));
        if (r->nobjs == 0)
            return fail(r, r->L.line, FM_ERR_PARSE, "not a GOCAD TSurf file (first line '%s')",
                        quote(q, s, e));
        return fail(r, r->L.line, FM_ERR_PARSE, "expected 'GOCAD TSurf 1' after END, found '%s'",
                    quote(q, s, e));
    }
    r->ts = fm_tsurf_alloc();
    if (!r->ts)
        return nomem(r);
    fm_idmap_init(&r->ids);
    r->obj_line = r->L.line;
    r->in_part = 0;
    r->nnodata = 0;
    r->st = S_HEAD;
    return FM_OK;
}

static fm_status do_line(reader *r, const char *s, const char *e)
{
    s = fm_lex_skip_ws(s, e);
    if (s == e || *s == '#')
        return FM_OK;
    fm_lex_rtrim(s, &e);
    const char *t = fm_lex_token_end(s, e);
    switch (r->st) {
    case S_BODY:
        return do_body_line(r, s, e, t);
    case S_TOP:
        return do_top_line(r, s, e, t);
    case S_HEAD: {
        int is_body;
        fm_status st = do_head_line(r, s, e, t, &is_body);
        if (st == FM_OK && is_body)
            st = do_body_line(r, s, e, t);
        return st;
    }
    case S_HEADER:
        return do_header_line(r, s, e, t);
    case S_CRS:
        return do_crs_line(r, s, e, t);
    case S_CLASS:
        return do_class_line(r, s, e, t);
    }
    return FM_OK;
}

static fm_status at_eof(reader *r)
{
    char label[256];
    switch (r->st) {
    case S_TOP:
        if (r->nobjs == 0)
            return fail(r, r->L.line > 0 ? r->L.line : 1, FM_ERR_PARSE, "empty file");
        return FM_OK;
    case S_HEAD:
    case S_BODY:
        object_label(r, label, sizeof label);
        return fail(r, r->L.line, FM_ERR_PARSE,
                    "unexpected end of file: object %s (line %ld) has no END", label, r->obj_line);
    case S_HEADER:
        return fail(r, r->block_line, FM_ERR_PARSE, "HEADER block is never closed");
    case S_CRS:
        return fail(r, r->block_line, FM_ERR_PARSE,
                    "GOCAD_ORIGINAL_COORDINATE_SYSTEM block is never closed");
    case S_CLASS:
        return fail(r, r->block_line, FM_ERR_PARSE, "PROPERTY_CLASS_HEADER block is never closed");
    }
    return FM_OK;
}

/* Line number of offset off, counting LF, CRLF and lone CR as one break. */
static long line_of(const char *buf, size_t off)
{
    long line = 1;
    for (size_t i = 0; i < off; i++) {
        if (buf[i] == '\n' || (buf[i] == '\r' && (i + 1 >= off || buf[i + 1] != '\n')))
            line++;
    }
    return line;
}

fm_status fm_tsurf_read_buffer(const char *name, const char *buf, size_t len,
                               fm_tsurf ***objects, size_t *count, fm_error *err)
{
    *objects = NULL;
    *count = 0;
    reader r;
    memset(&r, 0, sizeof r);
    r.name = name;
    r.err = err;
    r.st = S_TOP;
    fm_idmap_init(&r.ids);

    /* UTF-16 (Windows editors save it so) holds NUL bytes too: named for
     * what it is, so the user knows to convert it. */
    if (len >= 2 && (memcmp(buf, "\xFF\xFE", 2) == 0 || memcmp(buf, "\xFE\xFF", 2) == 0))
        return fm_error_set(err, FM_ERR_PARSE, name, 1,
                            "UTF-16 text (byte order mark %s): save it as UTF-8 or ASCII",
                            buf[0] == '\xFF' ? "FF FE" : "FE FF");
    /* A NUL byte never occurs in text; one scan of the buffer settles it
     * before any line is looked at. */
    const char *nul = len ? memchr(buf, '\0', len) : NULL;
    if (nul)
        return fm_error_set(err, FM_ERR_PARSE, name, line_of(buf, (size_t)(nul - buf)),
                            "binary data (NUL byte), not a text file");
    /* A UTF-8 byte order mark is not part of the first line. */
    if (len >= 3 && memcmp(buf, "\xEF\xBB\xBF", 3) == 0) {
        buf += 3;
        len -= 3;
    }
    fm_lines_init(&r.L, buf, len);
    fm_status st = FM_OK;
    const char *s, *e;
    int k;
    while (st == FM_OK && (k = fm_lines_next(&r.L, &s, &e)) != 0) {
        if (k < 0)
            st = fail(&r, r.L.line, FM_ERR_PARSE, "line longer than %d bytes", FM_TSURF_MAX_LINE);
        else
            st = do_line(&r, s, e);
    }
    if (st == FM_OK)
        st = at_eof(&r);
    fm_tsurf_destroy(r.ts);
    fm_idmap_free(&r.ids);
    free(r.nodata);
    if (st != FM_OK) {
        fm_tsurf_free_all(r.objs, r.nobjs);
        return st;
    }
    *objects = r.objs;
    *count = r.nobjs;
    return FM_OK;
}

fm_status fm_tsurf_read_file(const char *path, fm_tsurf ***objects, size_t *count,
                             fm_error *err)
{
    *objects = NULL;
    *count = 0;
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return fm_error_set(err, FM_ERR_IO, path, 0, "cannot open: %s", strerror(errno));
    struct stat sb;
    if (fstat(fileno(fp), &sb) != 0 || !S_ISREG(sb.st_mode)) {
        fclose(fp);
        return fm_error_set(err, FM_ERR_IO, path, 0, "not a regular file");
    }
    size_t size = (size_t)sb.st_size;
    char *buf = malloc(size ? size : 1);
    if (!buf) {
        fclose(fp);
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory (%zu bytes)", size);
    }
    /* One read of the whole file: the parser then never waits on I/O and
     * scans with memchr over contiguous memory. */
    size_t got = size ? fread(buf, 1, size, fp) : 0;
    int bad = ferror(fp);
    fclose(fp);
    if (bad || got != size) {
        free(buf);
        return fm_error_set(err, FM_ERR_IO, path, 0, "cannot read: %s",
                            bad ? strerror(errno) : "file changed size while reading");
    }
    fm_status st = fm_tsurf_read_buffer(path, buf, size, objects, count, err);
    free(buf);
    return st;
}
