/* IGES 5.3 file of trimmed B-spline surfaces: entity layout and sections. */
#include "iges_internal.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fm_atomic.h"

/* Status numbers (DE field 9): blank status, subordinate switch, entity
 * use, hierarchy. Everything a 144 uses is physically dependent on it, so
 * readers transfer the 144 alone as the face. */
#define STATUS_FACE "00000000"
#define STATUS_DEPENDENT "00010000"
#define STATUS_PARAMETRIC "00010500" /* entity use 05: 2D parametric */

typedef struct iges_entity {
    int type, form;
    const char *status;
    char label[9];
    long pd_first, pd_lines;
} iges_entity;

/* One pass over the faces; the first counts PD lines into ents, the
 * second writes them (the DE section in between needs the counts). */
typedef struct iges_walk {
    const fm_iges_face *faces;
    size_t nfaces;
    const unsigned char *rev; /* per face 1 + nholes flags, faces in order */
    const iges_net *nets;     /* per face: what of its surface is written */
    int digits;               /* of the reals in the Parameter Data */
    iges_entity *ents;
    size_t nents, next;       /* entities, and the next to emit */
    iges_lines pd;
} iges_walk;

static const char *unit_name(int flag)
{
    static const char *const names[] = {NULL, "IN", "MM", NULL, "FT", "MI", "M",
                                        "KM", "MIL", "UM", "CM", "UIN"};
    return flag >= 1 && flag <= 11 ? names[flag] : NULL;
}

void fm_iges_options_default(fm_iges_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->unit_flag = 6;
    opt->model_scale = 1.0;
    opt->time = FM_IGES_TIME_AUTO;
}

static long de_of(size_t entity) { return 2 * (long)entity + 1; }

/* Opens the next entity: its DE number becomes the PD back-pointer. */
static size_t begin(iges_walk *w, int type, int form, const char *status, const char *label)
{
    size_t e = w->next++;
    iges_entity *en = &w->ents[e];
    if (!w->pd.fp) {
        en->type = type;
        en->form = form;
        en->status = status;
        snprintf(en->label, sizeof en->label, "%.8s", label ? label : "");
        en->pd_first = w->pd.seq + 1;
    }
    w->pd.de = de_of(e);
    iges_int(&w->pd, type);
    return e;
}

static void end(iges_walk *w, size_t e)
{
    iges_end(&w->pd);
    if (!w->pd.fp)
        w->ents[e].pd_lines = w->pd.seq + 1 - w->ents[e].pd_first;
}

static void emit_surface(iges_walk *w, const iges_net *net)
{
    size_t e = begin(w, 128, 0, STATUS_DEPENDENT, NULL);
    iges_lines *l = &w->pd;
    iges_int(l, (long long)net->nu - 1);
    iges_int(l, (long long)net->nv - 1);
    iges_int(l, net->pu);
    iges_int(l, net->pv);
    /* Closed and periodic flags 0: readers recompute closure from the
     * data, and fault surfaces are open. */
    iges_int(l, 0);
    iges_int(l, 0);
    iges_int(l, net->weights ? 0 : 1);
    iges_int(l, 0);
    iges_int(l, 0);
    for (size_t i = 0; i < net->nu + (size_t)net->pu + 1; i++)
        iges_real(l, net->knots_u[i]);
    for (size_t j = 0; j < net->nv + (size_t)net->pv + 1; j++)
        iges_real(l, net->knots_v[j]);
    size_t n = net->nu * net->nv;
    for (size_t k = 0; k < n; k++)
        iges_real(l, net->weights ? net->weights[k] : 1.0);
    for (size_t k = 0; k < n; k++)
        for (int d = 0; d < 3; d++) {
            if (net->rounded)
                iges_real_quantum(l, net->ctrl[3 * k + (size_t)d], net->quantum_exp);
            else
                iges_real(l, net->ctrl[3 * k + (size_t)d]);
        }
    for (int i = 0; i < 4; i++)
        iges_real(l, net->r[i]);
    end(w, e);
}

/* A reversed curve has its control points and weights in reverse order
 * and knots t'_i = -t_(m-1-i): the same point set traversed backwards,
 * with no rounding. */
static void emit_curve(iges_walk *w, const fm_iges_curve2d *c, int reversed, int closed)
{
    size_t e = begin(w, 126, 0, STATUS_PARAMETRIC, NULL);
    iges_lines *l = &w->pd;
    size_t m = c->n + (size_t)c->degree + 1;
    iges_int(l, (long long)c->n - 1);
    iges_int(l, c->degree);
    iges_int(l, 1); /* planar: the z = 0 plane of (u, v) */
    iges_int(l, closed);
    iges_int(l, c->weights ? 0 : 1);
    iges_int(l, 0);
    for (size_t i = 0; i < m; i++)
        iges_real(l, reversed ? -c->knots[m - 1 - i] : c->knots[i]);
    for (size_t i = 0; i < c->n; i++) {
        size_t j = reversed ? c->n - 1 - i : i;
        iges_real(l, c->weights ? c->weights[j] : 1.0);
    }
    for (size_t i = 0; i < c->n; i++) {
        size_t j = reversed ? c->n - 1 - i : i;
        iges_real(l, c->ctrl[2 * j]);
        iges_real(l, c->ctrl[2 * j + 1]);
        iges_real(l, 0.0);
    }
    double a = c->knots[c->degree], b = c->knots[c->n];
    iges_real(l, reversed ? -b : a);
    iges_real(l, reversed ? -a : b);
    iges_real(l, 0.0);
    iges_real(l, 0.0);
    iges_real(l, 1.0);
    end(w, e);
}

/* Curves (and their composite) then the 142; returns the 142's entity. */
static size_t emit_loop(iges_walk *w, size_t surf, const fm_iges_loop *lp, int reversed)
{
    size_t first = w->next, nc = lp->ncurves;
    for (size_t k = 0; k < nc; k++)
        emit_curve(w, &lp->curves[reversed ? nc - 1 - k : k], reversed, nc == 1);
    size_t curve = first;
    if (nc > 1) {
        curve = begin(w, 102, 0, STATUS_PARAMETRIC, NULL);
        iges_int(&w->pd, (long long)nc);
        for (size_t k = 0; k < nc; k++)
            iges_int(&w->pd, de_of(first + k));
        end(w, curve);
    }
    size_t e = begin(w, 142, 0, STATUS_DEPENDENT, NULL);
    iges_int(&w->pd, 0); /* created: unspecified */
    iges_int(&w->pd, de_of(surf));
    iges_int(&w->pd, de_of(curve));
    iges_int(&w->pd, 0); /* no model-space curve */
    iges_int(&w->pd, 1); /* the parameter-space curve is the definition */
    end(w, e);
    return e;
}

/* OpenCASCADE reads N1 = 0 as the knot range, so a face whose range is
 * narrower gets its rectangle as an explicit outer loop. */
static int needs_rectangle(const fm_iges_face *f)
{
    const fm_iges_surface *s = &f->surface;
    double r[4];
    iges_face_range(s, r);
    return !f->outer && (r[0] != s->knots_u[s->degree_u] || r[1] != s->knots_u[s->nu] ||
                         r[2] != s->knots_v[s->degree_v] || r[3] != s->knots_v[s->nv]);
}

static size_t entities_of_loop(const fm_iges_loop *lp)
{
    return lp->ncurves + (lp->ncurves > 1) + 1;
}

static size_t entities_of_face(const fm_iges_face *f)
{
    size_t n = 2 + (f->name && *f->name ? 1 : 0);
    if (f->outer)
        n += entities_of_loop(f->outer);
    else if (needs_rectangle(f))
        n += 6;
    for (size_t h = 0; h < f->nholes; h++)
        n += entities_of_loop(&f->holes[h]);
    return n;
}

static void emit_face(iges_walk *w, const fm_iges_face *f, const unsigned char *rev,
                      const iges_net *net)
{
    size_t surf = w->next;
    emit_surface(w, net);
    size_t outer = 0;
    int has_outer = 1;
    if (f->outer) {
        outer = emit_loop(w, surf, f->outer, rev[0]);
    } else if (needs_rectangle(f)) {
        double r[4];
        iges_face_range(&f->surface, r);
        static const double knots[4] = {0, 0, 1, 1};
        double ctrl[4][4] = {{r[0], r[2], r[1], r[2]},
                             {r[1], r[2], r[1], r[3]},
                             {r[1], r[3], r[0], r[3]},
                             {r[0], r[3], r[0], r[2]}};
        fm_iges_curve2d sides[4];
        for (int k = 0; k < 4; k++)
            sides[k] = (fm_iges_curve2d){1, 2, knots, ctrl[k], NULL};
        fm_iges_loop rect = {sides, 4};
        outer = emit_loop(w, surf, &rect, 0);
    } else {
        has_outer = 0;
    }
    /* Each hole's 142 closes its run of entities, so the 144 finds them
     * from where the holes start. */
    size_t hole_first = w->next;
    for (size_t h = 0; h < f->nholes; h++)
        emit_loop(w, surf, &f->holes[h], rev[1 + h]);
    size_t name = 0;
    int has_name = f->name && *f->name;
    if (has_name) {
        name = begin(w, 406, 15, STATUS_DEPENDENT, NULL);
        iges_int(&w->pd, 1);
        iges_str(&w->pd, f->name);
        end(w, name);
    }
    size_t e = begin(w, 144, 0, STATUS_FACE, has_name ? f->name : NULL);
    iges_int(&w->pd, de_of(surf));
    iges_int(&w->pd, has_outer);
    iges_int(&w->pd, (long long)f->nholes);
    iges_int(&w->pd, has_outer ? de_of(outer) : 0);
    size_t at = hole_first;
    for (size_t h = 0; h < f->nholes; h++) {
        at += entities_of_loop(&f->holes[h]);
        iges_int(&w->pd, de_of(at - 1));
    }
    if (has_name) {
        iges_int(&w->pd, 0); /* no associativities */
        iges_int(&w->pd, 1); /* one property: the name */
        iges_int(&w->pd, de_of(name));
    }
    end(w, e);
}

static void walk_faces(iges_walk *w, FILE *fp, long first_seq)
{
    iges_lines_init(&w->pd, fp, 'P', first_seq);
    w->pd.digits = w->digits;
    w->next = 0;
    const unsigned char *rev = w->rev;
    for (size_t i = 0; i < w->nfaces; i++) {
        emit_face(w, &w->faces[i], rev, &w->nets[i]);
        rev += 1 + w->faces[i].nholes;
    }
}

static long long resolve_time(long long t)
{
    if (t != FM_IGES_TIME_AUTO)
        return t;
    const char *env = getenv("SOURCE_DATE_EPOCH");
    if (env && *env) {
        char *endp;
        errno = 0;
        long long v = strtoll(env, &endp, 10);
        if (!*endp && errno == 0 && v >= 0)
            return v;
    }
    return (long long)time(NULL);
}

static void write_start(FILE *fp, const char *text, long *seq)
{
    char line[73];
    size_t len = 0;
    for (const char *p = text;; p++) {
        if (*p == '\n' || *p == '\0' || len == 72) {
            line[len] = '\0';
            iges_put_line(fp, line, 'S', ++*seq);
            len = 0;
            if (!*p)
                break;
            if (*p == '\n')
                continue;
        }
        line[len++] = *p;
    }
}

typedef struct iges_global {
    const char *file_name, *product, *author, *organization;
    char date[40]; /* YYYYMMDD.HHNNSS */
    int unit_flag;
    int digits; /* significant digits of the Parameter Data's reals */
    double scale, resolution, max_coord;
} iges_global;

static long write_global(FILE *fp, const iges_global *g)
{
    iges_lines l;
    iges_lines_init(&l, fp, 'G', 1);
    iges_str(&l, ",");
    iges_str(&l, ";");
    iges_str(&l, g->product);
    iges_str(&l, g->file_name);
    iges_str(&l, "faultmesh");
    iges_str(&l, "faultmesh " FM_VERSION_STRING);
    iges_int(&l, 32);  /* bits of an integer */
    iges_int(&l, 38);  /* single precision: max power of ten, digits */
    iges_int(&l, 6);
    iges_int(&l, 308); /* double precision: max power of ten, digits */
    iges_int(&l, g->digits);
    iges_str(&l, g->product);
    iges_real(&l, g->scale);
    iges_int(&l, g->unit_flag);
    iges_str(&l, unit_name(g->unit_flag));
    iges_int(&l, 1);   /* line weight gradations */
    iges_real(&l, g->resolution); /* width of the thickest line: irrelevant here */
    iges_str(&l, g->date);
    iges_real(&l, g->resolution);
    iges_real(&l, g->max_coord);
    iges_str(&l, g->author);
    iges_str(&l, g->organization);
    iges_int(&l, 11);  /* IGES 5.3 */
    iges_int(&l, 0);   /* no drafting standard */
    iges_str(&l, g->date); /* model created/modified */
    iges_str(&l, NULL);    /* no application protocol */
    iges_end(&l);
    return l.seq;
}

static void write_directory(FILE *fp, const iges_entity *ents, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        const iges_entity *e = &ents[i];
        long seq = de_of(i);
        fprintf(fp, "%8d%8ld%8d%8d%8d%8d%8d%8d%8sD%7ld\n", e->type, e->pd_first, 0, 0, 0, 0, 0,
                0, e->status, seq);
        fprintf(fp, "%8d%8d%8d%8ld%8d%8s%8s%8s%8dD%7ld\n", e->type, 0, 0, e->pd_lines, e->form,
                "", "", e->label, 0, seq + 1);
    }
}

/* Bounds of the control points written. */
static void control_box(const fm_iges_face *faces, const iges_window *win, size_t n,
                        double *max_coord, double *diag)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    *max_coord = 0;
    for (size_t f = 0; f < n; f++) {
        const fm_iges_surface *s = &faces[f].surface;
        const iges_window *w = &win[f];
        for (size_t j = w->j0; j < w->j0 + w->nj; j++)
            for (size_t i = w->i0; i < w->i0 + w->ni; i++)
                for (int d = 0; d < 3; d++) {
                    double x = s->ctrl[3 * (j * s->nu + i) + (size_t)d];
                    lo[d] = fmin(lo[d], x);
                    hi[d] = fmax(hi[d], x);
                    *max_coord = fmax(*max_coord, fabs(x));
                }
    }
    *diag = n ? sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                     (hi[2] - lo[2]) * (hi[2] - lo[2]))
              : 0;
}

/* The fewest significant digits that round no coordinate of magnitude up
 * to max_coord by more than a hundredth of the resolution: every reader
 * takes points closer than the resolution as one, so the rounding is
 * invisible to it, and the file is half the size of exact texts. */
static int auto_digits(double max_coord, double resolution)
{
    if (!(max_coord > 0) || !(resolution > 0))
        return 17;
    /* rounding to d digits moves x by at most 10^(floor(log10 x) + 1 - d) / 2 */
    double e = floor(log10(max_coord)) + 1;
    int d = (int)ceil(e - log10(2 * resolution / 100));
    return d < 6 ? 6 : d > 17 ? 17 : d;
}

/* The largest power of ten (its exponent) whose rounding moves a point by
 * at most half the tolerance: half of a quantum in each of 3 coordinates
 * is sqrt(3) / 2 quanta. */
static int quantum_exp_for(double tol)
{
    double half = 0.5 * sqrt(3.0), want = 0.5 * tol;
    int e = (int)floor(log10(tol / sqrt(3.0)));
    while (e > -22 && pow(10.0, e) * half > want)
        e--;
    while (e < 22 && pow(10.0, e + 1) * half <= want)
        e++;
    return e < -22 ? -22 : e > 22 ? 22 : e;
}

/* What of each face's surface is written: exactly its window when the
 * tolerance is negative; otherwise the window with knots removed within
 * what the rounding leaves of the tolerance (iges_reduce.c), its
 * coordinates rounded to the quantum of quantum_exp_for. */
static fm_status make_nets(const char *path, const fm_iges_face *faces, const iges_window *win,
                           size_t n, double tolerance, double max_coord, iges_net *nets,
                           fm_error *err)
{
    for (size_t i = 0; i < n; i++)
        if (iges_net_copy(&faces[i].surface, &win[i], &nets[i]) != FM_OK)
            return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    if (tolerance < 0)
        return FM_OK;
    int qe = quantum_exp_for(tolerance);
    /* never finer than a double holds the coordinates: below 1e15 quanta */
    while (qe < 22 && max_coord / pow(10.0, qe) >= 1e15)
        qe++;
    double budget = tolerance - 0.5 * sqrt(3.0) * pow(10.0, qe);
    for (size_t i = 0; i < n; i++) {
        nets[i].rounded = 1;
        nets[i].quantum_exp = qe;
        if (iges_reduce(&nets[i], budget) != FM_OK)
            return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    return FM_OK;
}

/* Global 20: the largest coordinate of a control point as written. */
static double nets_max_coord(const iges_net *nets, size_t n)
{
    double m = 0;
    for (size_t i = 0; i < n; i++) {
        const iges_net *net = &nets[i];
        double slack = net->rounded ? 0.5 * pow(10.0, net->quantum_exp) : 0;
        for (size_t k = 0; k < 3 * net->nu * net->nv; k++)
            m = fmax(m, fabs(net->ctrl[k]) + slack);
    }
    return m;
}

static fm_status check_options(const char *path, const fm_iges_options *o, fm_error *err)
{
    if (!unit_name(o->unit_flag))
        return fm_error_set(err, FM_ERR_INVALID, path, 0,
                            "unit flag %d is not one of 1, 2, 4..11", o->unit_flag);
    if (!isfinite(o->model_scale) || !(o->model_scale > 0))
        return fm_error_set(err, FM_ERR_INVALID, path, 0, "model scale must be positive");
    if (!isfinite(o->resolution) || o->resolution < 0)
        return fm_error_set(err, FM_ERR_INVALID, path, 0, "resolution must be >= 0");
    if (!isfinite(o->tolerance))
        return fm_error_set(err, FM_ERR_INVALID, path, 0, "tolerance must be finite");
    if (o->digits < 0 || o->digits > 17)
        return fm_error_set(err, FM_ERR_INVALID, path, 0, "digits must be 0..17");
    if (o->time != FM_IGES_TIME_AUTO && (o->time < 0 || o->time >= 253402300800LL))
        return fm_error_set(err, FM_ERR_INVALID, path, 0, "time outside years 1970..9999");
    const char *texts[] = {o->author, o->organization, o->product_id};
    for (int i = 0; i < 3; i++)
        if (!iges_printable(texts[i]))
            return fm_error_set(err, FM_ERR_INVALID, path, 0,
                                "author, organization and product id must be printable ASCII");
    for (const char *p = o->description; p && *p; p++)
        if (*p != '\n' && ((unsigned char)*p < 0x20 || (unsigned char)*p > 0x7e))
            return fm_error_set(err, FM_ERR_INVALID, path, 0,
                                "the description must be printable ASCII lines");
    return FM_OK;
}

static fm_status write_file(const char *path, iges_walk *w, const iges_global *g,
                            const char *description, fm_error *err)
{
    fm_atomic_file *af = fm_atomic_open(path, err);
    if (!af)
        return err ? err->code : FM_ERR_IO;
    FILE *fp = fm_atomic_stream(af);
    long s_lines = 0;
    write_start(fp, description, &s_lines);
    long g_lines = write_global(fp, g);
    write_directory(fp, w->ents, w->nents);
    walk_faces(w, fp, 1);
    char t[73];
    snprintf(t, sizeof t, "S%7ldG%7ldD%7ldP%7ld", s_lines, g_lines, 2 * (long)w->nents,
             w->pd.seq);
    iges_put_line(fp, t, 'T', 1);
    return fm_atomic_commit(af, err);
}

fm_status fm_iges_write(const char *path, const fm_iges_face *faces, size_t nfaces,
                        const fm_iges_options *opt, fm_error *err)
{
    fm_iges_options defaults;
    if (!opt) {
        fm_iges_options_default(&defaults);
        opt = &defaults;
    }
    if (!path || (nfaces && !faces))
        return fm_error_set(err, FM_ERR_INVALID, path, 0, "no path or no faces");
    fm_status st = check_options(path, opt, err);
    if (st)
        return st;
    size_t nflags = 0, nents = 0;
    for (size_t i = 0; i < nfaces; i++)
        nflags += 1 + faces[i].nholes;
    unsigned char *rev = calloc(nflags ? nflags : 1, 1);
    if (!rev)
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    unsigned char *r = rev;
    for (size_t i = 0; i < nfaces && !st; i++) {
        st = iges_check_face(path, i, &faces[i], r, err);
        r += 1 + faces[i].nholes;
    }
    iges_window *win = NULL;
    if (!st) {
        win = calloc(nfaces ? nfaces : 1, sizeof *win);
        if (!win)
            st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
        for (size_t i = 0; win && i < nfaces; i++)
            iges_face_window(&faces[i], &win[i]);
    }
    iges_global g = {0};
    double diag = 0;
    iges_net *nets = NULL;
    if (!st) {
        control_box(faces, win, nfaces, &g.max_coord, &diag);
        g.resolution = opt->resolution > 0 ? opt->resolution : diag > 0 ? 1e-7 * diag : 1e-7;
        g.digits = opt->digits ? opt->digits : auto_digits(g.max_coord, g.resolution);
        nets = calloc(nfaces ? nfaces : 1, sizeof *nets);
        if (!nets)
            st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    if (!st)
        st = make_nets(path, faces, win, nfaces,
                       opt->tolerance != 0 ? opt->tolerance : g.resolution, g.max_coord, nets,
                       err);
    if (!st) {
        g.max_coord = nets_max_coord(nets, nfaces);
        for (size_t i = 0; i < nfaces; i++)
            nents += entities_of_face(&faces[i]);
    }
    iges_walk w = {faces, nfaces, rev, nets, g.digits, NULL, nents, 0, {0}};
    if (!st && 2 * nents > (size_t)IGES_MAX_SEQ)
        st = fm_error_set(err, FM_ERR_INVALID, path, 0, "too many entities for IGES (%zu)", nents);
    if (!st) {
        w.ents = calloc(nents ? nents : 1, sizeof *w.ents);
        if (!w.ents)
            st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    if (!st) {
        walk_faces(&w, NULL, 1);
        if (w.pd.seq > IGES_MAX_SEQ)
            st = fm_error_set(err, FM_ERR_INVALID, path, 0,
                              "%ld parameter lines exceed the 7 digits IGES numbers them with",
                              w.pd.seq);
    }
    if (!st) {
        const char *base = strrchr(path, '/');
        g.file_name = base ? base + 1 : path;
        char product[256];
        snprintf(product, sizeof product, "%s", g.file_name);
        char *dot = strrchr(product, '.');
        if (dot && dot != product)
            *dot = '\0';
        g.product = opt->product_id ? opt->product_id : product;
        g.author = opt->author;
        g.organization = opt->organization;
        g.unit_flag = opt->unit_flag;
        g.scale = opt->model_scale;
        time_t tt = (time_t)resolve_time(opt->time);
        struct tm tm;
        if (!gmtime_r(&tt, &tm))
            memset(&tm, 0, sizeof tm);
        snprintf(g.date, sizeof g.date, "%04d%02d%02d.%02d%02d%02d", tm.tm_year + 1900,
                 tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec);
        const char *desc = opt->description
                               ? opt->description
                               : "faultmesh " FM_VERSION_STRING " fault surfaces";
        st = write_file(path, &w, &g, desc, err);
    }
    free(w.ents);
    for (size_t i = 0; nets && i < nfaces; i++)
        iges_net_free(&nets[i]);
    free(nets);
    free(win);
    free(rev);
    return st;
}
