/* The public face of the synth module: building, queries, evaluation. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "synth_internal.h"

void fm_synth_options_default(fm_synth_options *opt)
{
    opt->spacing = 500.0;
    opt->seed = 1;
}

fm_status fm_synth_create(const fm_synth_options *opt, fm_synth **out, fm_error *err)
{
    fm_synth_options o;
    *out = NULL;
    if (opt)
        o = *opt;
    else
        fm_synth_options_default(&o);
    /* Below 20 m the system has millions of triangles; above 20 km a fault
     * would be a handful of cells whatever we do. */
    if (!(o.spacing >= 20.0 && o.spacing <= 20000.0))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                            "synth: spacing must be between 20 and 20000 m (got %g)", o.spacing);
    fm_synth *sy = calloc(1, sizeof *sy);
    if (!sy)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "synth: out of memory");
    sy->opt = o;
    synth_layout(sy);
    for (size_t i = 0; i < sy->nfaults; i++) {
        /* One stream per fault, so that faults do not shift each other's
         * random numbers when one of them changes. */
        uint64_t seed = ((uint64_t)o.seed << 32) ^ (0x243F6A8885A308D3ull * (i + 1));
        fm_status st = synth_triangulate(sy, &sy->fault[i], seed, err);
        if (st != FM_OK) {
            fm_synth_destroy(sy);
            return st;
        }
    }
    *out = sy;
    return FM_OK;
}

void fm_synth_destroy(fm_synth *s)
{
    if (!s)
        return;
    for (size_t i = 0; i < s->nfaults; i++)
        fm_mesh_destroy(s->fault[i].mesh);
    free(s);
}

size_t fm_synth_nfaults(const fm_synth *s) { return s->nfaults; }

const char *fm_synth_fault_name(const fm_synth *s, size_t i)
{
    return i < s->nfaults ? s->fault[i].name : "";
}

const char *fm_synth_fault_description(const fm_synth *s, size_t i)
{
    return i < s->nfaults ? s->fault[i].description : "";
}

long fm_synth_find(const fm_synth *s, const char *name)
{
    for (size_t i = 0; i < s->nfaults; i++)
        if (strcmp(s->fault[i].name, name) == 0)
            return (long)i;
    return -1;
}

const fm_mesh *fm_synth_fault_mesh(const fm_synth *s, size_t i)
{
    return i < s->nfaults ? s->fault[i].mesh : NULL;
}

size_t fm_synth_nsheets(const fm_synth *s, size_t i)
{
    return i < s->nfaults ? s->fault[i].nsheets : 0;
}

void fm_synth_sheet_rect(const fm_synth *s, size_t i, size_t sheet, double rect[4])
{
    const synth_sheet *sh = &s->fault[i].sheet[sheet];
    rect[0] = sh->s0;
    rect[1] = sh->s1;
    rect[2] = 0.0;
    rect[3] = sh->width;
}

static void to_world(double p[3])
{
    p[0] += SYNTH_CENTRE_X;
    p[1] += SYNTH_CENTRE_Y;
}

void fm_synth_eval_sheet(const fm_synth *s, size_t i, size_t sheet, double ps, double pt,
                         double out[3])
{
    synth_eval_local(s, &s->fault[i], sheet, ps, pt, out);
    to_world(out);
}

void fm_synth_eval(const fm_synth *s, size_t i, double ps, double pt, double out[3])
{
    fm_synth_eval_sheet(s, i, 0, ps, pt, out);
}

void fm_synth_normal(const fm_synth *s, size_t i, size_t sheet, double ps, double pt,
                     double n[3])
{
    double x[3], xs[3], xt[3];
    synth_derivatives(s, &s->fault[i], sheet, ps, pt, x, xs, xt);
    n[0] = xs[1] * xt[2] - xs[2] * xt[1];
    n[1] = xs[2] * xt[0] - xs[0] * xt[2];
    n[2] = xs[0] * xt[1] - xs[1] * xt[0];
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++)
        n[k] /= len;
}

double fm_synth_closest(const fm_synth *s, size_t i, const double p[3], size_t *sheet,
                        double *ps, double *pt, double foot[3])
{
    const synth_fault *f = &s->fault[i];
    double q[3] = {p[0] - SYNTH_CENTRE_X, p[1] - SYNTH_CENTRE_Y, p[2]};
    double best = INFINITY, bs = 0.0, bt = 0.0;
    size_t bk = 0;
    for (size_t k = 0; k < f->nsheets; k++) {
        double cs, ct;
        double d = synth_closest_local(s, f, k, q, &cs, &ct);
        if (d < best) {
            best = d;
            bk = k;
            bs = cs;
            bt = ct;
        }
    }
    if (sheet)
        *sheet = bk;
    if (ps)
        *ps = bs;
    if (pt)
        *pt = bt;
    if (foot)
        fm_synth_eval_sheet(s, i, bk, bs, bt, foot);
    return best;
}

double fm_synth_distance(const fm_synth *s, size_t i, const double p[3])
{
    return fm_synth_closest(s, i, p, NULL, NULL, NULL, NULL);
}

void fm_synth_fault_expect(const fm_synth *s, size_t i, fm_synth_expect *e)
{
    const synth_fault *f = &s->fault[i];
    memset(e, 0, sizeof *e);
    e->kind = f->kind;
    e->parts = f->nparts;
    e->seam_vertices = f->seam_vertices;
    e->sheets = f->nsheets;
    e->junctions = f->nsheets - 1;
    e->junction_edges = f->junction_edges;
    e->holes = f->holes;
    e->blind = f->top_zmax < 0.0;
    e->top_zmin = f->top_zmin;
    e->top_zmax = f->top_zmax;
    e->bottom_z = f->sheet[0].bottom_z;
    e->noise = f->noise;
    e->gap_to = f->gap_to;
    e->gap = f->gap;
    e->overshoot_of = f->overshoot_of;
    e->overshoot = f->overshoot;
    e->crosses = f->crosses;
}
