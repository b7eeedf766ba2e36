/* A sheet sampled on its knot lattice: points, outline distances, active
 * cells and their boxes, and the sampled trimming loops. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "connect_internal.h"

void cn_sheet_free(cn_sheet *s)
{
    if (!s)
        return;
    free(s->xyz);
    free(s->sd);
    free(s->box);
    free(s->active);
    free(s->loop_uv);
    free(s->loop_start);
    free(s->seg);
    free(s->band_seg);
    free(s->band_start);
    fm_closest_tree_destroy(s->outline);
    fm_closest_tree_destroy(s->cells);
    free(s->cell_id);
    memset(s, 0, sizeof *s);
}

/* Band of v (NaN and values outside the loops' v range: none). */
static int band_of(const cn_sheet *s, double v, size_t *j)
{
    double f = (v - s->band_v0) / s->band_h;
    if (!(f >= 0) || !(f < (double)s->nband + 1))
        return 0;
    *j = f >= (double)(s->nband - 1) ? s->nband - 1 : (size_t)f;
    return 1;
}

/* Even-odd over the segments of v's band: the segments that can cross
 * the horizontal through v, each tested as a scan of all would test it. */
int cn_sheet_inside(const cn_sheet *s, double u, double v)
{
    size_t j;
    if (!s->nband || !band_of(s, v, &j))
        return 0;
    int in = 0;
    for (size_t k = s->band_start[j]; k < s->band_start[j + 1]; k++) {
        const uint32_t *e = s->seg + 2 * (size_t)s->band_seg[k];
        const double *a = s->loop_uv + 2 * (size_t)e[0], *b = s->loop_uv + 2 * (size_t)e[1];
        if ((a[1] > v) != (b[1] > v)) {
            double x = a[0] + (v - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
            if (x > u)
                in ^= 1;
        }
    }
    return in;
}

/* The segments binned by v: about 8 per band, each in every band its v
 * range meets (band_of is monotone, so a v inside the range lands in one
 * of them). */
static fm_status build_bands(cn_sheet *s)
{
    size_t total = s->loop_start[s->nloops];
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < total; i++) {
        lo = fmin(lo, s->loop_uv[2 * i + 1]);
        hi = fmax(hi, s->loop_uv[2 * i + 1]);
    }
    if (total == 0 || !(hi >= lo))
        return FM_OK;
    s->nband = total / 8 + 1;
    if (s->nband > 4096)
        s->nband = 4096;
    s->band_v0 = lo;
    s->band_h = hi > lo ? (hi - lo) / (double)s->nband : 1.0;
    s->seg = malloc(2 * total * sizeof *s->seg);
    s->band_start = calloc(s->nband + 1, sizeof *s->band_start);
    if (!s->seg || !s->band_start)
        return FM_ERR_NOMEM;
    size_t k = 0;
    for (size_t l = 0; l < s->nloops; l++) {
        size_t a0 = s->loop_start[l], n = s->loop_start[l + 1] - a0;
        for (size_t i = 0; i < n; i++, k++) {
            s->seg[2 * k] = (uint32_t)(a0 + i);
            s->seg[2 * k + 1] = (uint32_t)(a0 + (i + 1) % n);
        }
    }
    for (int pass = 0; pass < 2; pass++) {
        size_t *fill = pass ? malloc((s->nband + 1) * sizeof *fill) : NULL;
        if (pass) {
            if (!fill)
                return FM_ERR_NOMEM;
            for (size_t j = 0; j < s->nband; j++)
                s->band_start[j + 1] += s->band_start[j];
            memcpy(fill, s->band_start, (s->nband + 1) * sizeof *fill);
            s->band_seg = malloc((s->band_start[s->nband] + 1) * sizeof *s->band_seg);
            if (!s->band_seg) {
                free(fill);
                return FM_ERR_NOMEM;
            }
        }
        for (k = 0; k < total; k++) {
            double va = s->loop_uv[2 * (size_t)s->seg[2 * k] + 1];
            double vb = s->loop_uv[2 * (size_t)s->seg[2 * k + 1] + 1];
            size_t j0 = 0, j1 = s->nband - 1; /* all bands if unsure */
            if (!band_of(s, fmin(va, vb), &j0) || !band_of(s, fmax(va, vb), &j1)) {
                j0 = 0;
                j1 = s->nband - 1;
            }
            for (size_t j = j0; j <= j1; j++) {
                if (pass)
                    s->band_seg[fill[j]++] = (uint32_t)k;
                else
                    s->band_start[j + 1]++;
            }
        }
        free(fill);
    }
    return FM_OK;
}

double cn_sheet_outline_distance(const cn_sheet *s, double u, double v, const double xyz[3])
{
    fm_closest_hit h;
    double d = fm_closest_query(s->outline, xyz, INFINITY, &h) ? h.dist : INFINITY;
    return cn_sheet_inside(s, u, v) ? -d : d;
}

double cn_sheet_ray_exit(const cn_sheet *s, const double uv[2], const double d[2], double limit)
{
    double best = INFINITY;
    for (size_t l = 0; l < s->nloops; l++) {
        size_t a0 = s->loop_start[l], n = s->loop_start[l + 1] - a0;
        for (size_t i = 0; i < n; i++) {
            const double *a = s->loop_uv + 2 * (a0 + i), *b = s->loop_uv + 2 * (a0 + (i + 1) % n);
            /* uv + t d = a + r (b - a), t >= 0, 0 <= r <= 1 */
            double ex = b[0] - a[0], ey = b[1] - a[1];
            double den = d[0] * (-ey) - d[1] * (-ex);
            if (den == 0)
                continue;
            double rx = a[0] - uv[0], ry = a[1] - uv[1];
            double t = (rx * (-ey) - ry * (-ex)) / den;
            double r = (d[0] * ry - d[1] * rx) / den;
            if (t > 0 && t < best && r >= 0 && r <= 1)
                best = t;
        }
    }
    return best <= limit ? best : INFINITY;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Inside flags of the lattice nodes: one crossing list per row. */
static fm_status lattice_inside(cn_sheet *s, unsigned char *in)
{
    size_t total = s->loop_start[s->nloops];
    double *x = malloc((total + 1) * sizeof *x);
    if (!x)
        return FM_ERR_NOMEM;
    for (size_t j = 0; j <= s->nsv; j++) {
        double v = s->v0 + (double)j * s->hs;
        size_t nx = 0;
        for (size_t l = 0; l < s->nloops; l++) {
            size_t a0 = s->loop_start[l], n = s->loop_start[l + 1] - a0;
            for (size_t i = 0; i < n; i++) {
                const double *a = s->loop_uv + 2 * (a0 + i);
                const double *b = s->loop_uv + 2 * (a0 + (i + 1) % n);
                if ((a[1] > v) != (b[1] > v))
                    x[nx++] = a[0] + (v - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
            }
        }
        qsort(x, nx, sizeof *x, cmp_double);
        /* inside when an odd number of crossings lie beyond u */
        size_t k = 0;
        for (size_t i = 0; i <= s->nsu; i++) {
            double u = s->u0 + (double)i * s->hs;
            while (k < nx && x[k] <= u)
                k++;
            in[j * (s->nsu + 1) + i] = (unsigned char)((nx - k) & 1);
        }
    }
    free(x);
    return FM_OK;
}

static fm_status sample_loops(cn_sheet *s, const fm_model *m, size_t sheet, fm_error *err)
{
    size_t nl = fm_model_nloops(m, sheet);
    double spacing = fmax(20.0, fmin(100.0, 0.25 * s->hs));
    s->loop_start = calloc(nl + 1, sizeof *s->loop_start);
    if (!s->loop_start)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    size_t total = 0;
    for (size_t l = 0; l < nl; l++) {
        double *uv = NULL;
        size_t n = 0;
        fm_status st = fm_trim_loop_sample(fm_model_loop(m, sheet, l), spacing, &uv, &n, NULL, err);
        if (st != FM_OK)
            return st;
        double *grown = realloc(s->loop_uv, 2 * (total + n) * sizeof *grown);
        if (!grown) {
            free(uv);
            return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
        }
        s->loop_uv = grown;
        memcpy(s->loop_uv + 2 * total, uv, 2 * n * sizeof *uv);
        free(uv);
        total += n;
        s->loop_start[l + 1] = total;
        s->nloops = l + 1;
    }
    if (build_bands(s) != FM_OK)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    /* The outline in 3D as segments (degenerate triangles a, b, b). */
    fm_mesh *om = fm_mesh_create();
    if (!om || fm_mesh_reserve(om, total, total) != FM_OK) {
        fm_mesh_destroy(om);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    for (size_t i = 0; i < total; i++) {
        double p[3];
        fm_fit_surface_eval(s->surf, s->loop_uv[2 * i], s->loop_uv[2 * i + 1], p, NULL, NULL);
        fm_mesh_add_vertex(om, p[0], p[1], p[2]);
    }
    for (size_t l = 0; l < s->nloops; l++) {
        size_t a0 = s->loop_start[l], n = s->loop_start[l + 1] - a0;
        for (size_t i = 0; i < n; i++) {
            int32_t a = (int32_t)(a0 + i), b = (int32_t)(a0 + (i + 1) % n);
            fm_mesh_add_triangle(om, a, b, b, 0);
        }
    }
    s->outline = fm_closest_tree_create_quick(om, err);
    fm_mesh_destroy(om);
    return s->outline ? FM_OK : (err ? err->code : FM_ERR_NOMEM);
}

static double dist3(const double *a, const double *b)
{
    double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

fm_status cn_sheet_build_outline(const fm_model *m, size_t fault, size_t sheet, cn_sheet *s,
                                 fm_error *err)
{
    memset(s, 0, sizeof *s);
    s->surf = fm_model_surface(m, sheet);
    s->fault = fault;
    s->sheet = sheet;
    if (!s->surf)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "connect: sheet %zu has no surface",
                            sheet);
    double dom[4];
    fm_fit_surface_domain(s->surf, dom);
    size_t nk;
    int p = fm_fit_surface_degree(s->surf);
    fm_fit_surface_knots(s->surf, 0, &nk);
    s->nsu = nk - 2 * (size_t)p - 1;
    fm_fit_surface_knots(s->surf, 1, &nk);
    s->nsv = nk - 2 * (size_t)p - 1;
    s->u0 = dom[0];
    s->v0 = dom[2];
    s->hs = (dom[1] - dom[0]) / (double)s->nsu;
    fm_status st = sample_loops(s, m, sheet, err);
    if (st != FM_OK)
        cn_sheet_free(s);
    return st;
}

fm_status cn_sheet_build(const fm_model *m, size_t fault, size_t sheet, double reach,
                         cn_sheet *s, fm_error *err)
{
    fm_status st = cn_sheet_build_outline(m, fault, sheet, s, err);
    if (st != FM_OK)
        return st;
    size_t nu = s->nsu + 1, nn = nu * (s->nsv + 1), nc = s->nsu * s->nsv;
    s->xyz = malloc(3 * nn * sizeof *s->xyz);
    s->sd = malloc(nn * sizeof *s->sd);
    s->box = malloc(6 * nc * sizeof *s->box);
    s->active = calloc(nc ? nc : 1, 1);
    unsigned char *in = malloc(nn);
    if (!s->xyz || !s->sd || !s->box || !s->active || !in ||
        lattice_inside(s, in) != FM_OK) {
        free(in);
        cn_sheet_free(s);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    for (size_t j = 0; j <= s->nsv; j++)
        for (size_t i = 0; i < nu; i++) {
            size_t k = j * nu + i;
            double *x = s->xyz + 3 * k;
            fm_fit_surface_eval(s->surf, s->u0 + (double)i * s->hs, s->v0 + (double)j * s->hs, x,
                                NULL, NULL);
            fm_closest_hit h;
            double d = fm_closest_query(s->outline, x, INFINITY, &h) ? h.dist : INFINITY;
            s->sd[k] = in[k] ? -d : d;
        }
    free(in);
    fm_mesh *bm = fm_mesh_create();
    s->cell_id = malloc((nc ? nc : 1) * sizeof *s->cell_id);
    if (!bm || !s->cell_id) {
        fm_mesh_destroy(bm);
        cn_sheet_free(s);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    for (int k = 0; k < 3; k++) {
        s->lo[k] = INFINITY;
        s->hi[k] = -INFINITY;
    }
    for (size_t j = 0; j < s->nsv; j++)
        for (size_t i = 0; i < s->nsu; i++) {
            size_t c = j * s->nsu + i;
            size_t n00 = j * nu + i, n10 = n00 + 1, n01 = n00 + nu, n11 = n01 + 1;
            const double *P[4] = {s->xyz + 3 * n00, s->xyz + 3 * n10, s->xyz + 3 * n01,
                                  s->xyz + 3 * n11};
            double ctr[3];
            fm_fit_surface_eval(s->surf, s->u0 + ((double)i + 0.5) * s->hs,
                                s->v0 + ((double)j + 0.5) * s->hs, ctr, NULL, NULL);
            double mean[3], *lo = s->box + 6 * c, *hi = lo + 3;
            for (int k = 0; k < 3; k++) {
                mean[k] = 0.25 * (P[0][k] + P[1][k] + P[2][k] + P[3][k]);
                lo[k] = fmin(fmin(fmin(P[0][k], P[1][k]), fmin(P[2][k], P[3][k])), ctr[k]);
                hi[k] = fmax(fmax(fmax(P[0][k], P[1][k]), fmax(P[2][k], P[3][k])), ctr[k]);
            }
            double pad = 2.0 * dist3(ctr, mean) + 0.02 * s->hs + 1.0;
            for (int k = 0; k < 3; k++) {
                lo[k] -= pad;
                hi[k] += pad;
            }
            double smin = fmin(fmin(s->sd[n00], s->sd[n10]), fmin(s->sd[n01], s->sd[n11]));
            double diag = fmax(dist3(P[0], P[3]), dist3(P[1], P[2]));
            if (!(smin <= reach + 0.5 * diag))
                continue;
            s->active[c] = 1;
            int32_t a = fm_mesh_add_vertex(bm, lo[0], lo[1], lo[2]);
            int32_t b = fm_mesh_add_vertex(bm, hi[0], hi[1], hi[2]);
            fm_mesh_add_triangle(bm, a, b, a, 0);
            s->cell_id[s->nactive++] = (int32_t)c;
            for (int k = 0; k < 3; k++) {
                s->lo[k] = fmin(s->lo[k], lo[k]);
                s->hi[k] = fmax(s->hi[k], hi[k]);
            }
        }
    if (fm_mesh_ntriangles(bm) != s->nactive) {
        fm_mesh_destroy(bm);
        cn_sheet_free(s);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    }
    s->cells = fm_closest_tree_create_quick(bm, err);
    fm_mesh_destroy(bm);
    if (!s->cells) {
        cn_sheet_free(s);
        return err ? err->code : FM_ERR_NOMEM;
    }
    return FM_OK;
}

static int stop_at_first(int32_t t, void *user)
{
    (void)t;
    *(int *)user = 1;
    return 1;
}

size_t cn_select_cells(const cn_sheet *a, const cn_sheet *b, double margin, unsigned char *sel)
{
    size_t n = 0;
    memset(sel, 0, a->nsu * a->nsv);
    for (size_t k = 0; k < a->nactive; k++) {
        size_t c = (size_t)a->cell_id[k];
        const double *box = a->box + 6 * c;
        double lo[3], hi[3];
        int out = 0;
        for (int i = 0; i < 3; i++) {
            lo[i] = box[i] - margin;
            hi[i] = box[3 + i] + margin;
            if (lo[i] > b->hi[i] || hi[i] < b->lo[i])
                out = 1;
        }
        if (out)
            continue;
        int hit = 0;
        fm_closest_tree_box_query(b->cells, lo, hi, stop_at_first, &hit);
        if (hit) {
            sel[c] = 1;
            n++;
        }
    }
    return n;
}

/* Sheets sampled on N threads: slot k is model sheet ref[k]. */
typedef struct sample_work {
    const fm_model *const *models;
    const size_t (*ref)[2];
    double reach;
    const unsigned char *level;
    cn_sheet *sh;
    fm_status *st;
    fm_error *err;
} sample_work;

static void sample_task(void *user, size_t k)
{
    sample_work *w = user;
    size_t f = w->ref[k][0], s = w->ref[k][1];
    int level = w->level ? w->level[k] : 2;
    if (level == 2)
        w->st[k] = cn_sheet_build(w->models[f], f, s, w->reach, &w->sh[k], &w->err[k]);
    else if (level == 1)
        w->st[k] = cn_sheet_build_outline(w->models[f], f, s, &w->sh[k], &w->err[k]);
}

fm_status cn_sheets_build(const fm_model *const *models, size_t n, double reach, int nthreads,
                          cn_sheet **out, size_t *nout, fm_error *err)
{
    return cn_sheets_build_some(models, n, reach, NULL, nthreads, out, nout, err);
}

fm_status cn_sheets_build_some(const fm_model *const *models, size_t n, double reach,
                               const unsigned char *level, int nthreads, cn_sheet **out,
                               size_t *nout, fm_error *err)
{
    *out = NULL;
    *nout = 0;
    size_t ns = 0;
    for (size_t i = 0; i < n; i++)
        ns += models && models[i] ? fm_model_nsheets(models[i]) : 0;
    cn_sheet *sh = calloc(ns ? ns : 1, sizeof *sh);
    size_t(*ref)[2] = malloc((ns ? ns : 1) * sizeof *ref);
    fm_status *sst = calloc(ns ? ns : 1, sizeof *sst);
    fm_error *serr = calloc(ns ? ns : 1, sizeof *serr);
    if (!sh || !ref || !sst || !serr) {
        free(sh);
        free(ref);
        free(sst);
        free(serr);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "connect: out of memory");
    }
    size_t k = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t s = 0; models[i] && s < fm_model_nsheets(models[i]); s++, k++) {
            ref[k][0] = i;
            ref[k][1] = s;
        }
    sample_work w = {models, (const size_t(*)[2])ref, reach, level, sh, sst, serr};
    cn_parallel_for(ns, nthreads, sample_task, &w);
    /* the first sheet in order that failed decides the error, as on one thread */
    fm_status st = FM_OK;
    for (k = 0; k < ns; k++)
        if (sst[k] != FM_OK) {
            st = sst[k];
            if (err)
                *err = serr[k];
            break;
        }
    free(ref);
    free(sst);
    free(serr);
    if (st != FM_OK) {
        cn_sheets_free(sh, ns);
        return st;
    }
    *out = sh;
    *nout = ns;
    return FM_OK;
}

void cn_sheets_free(cn_sheet *s, size_t n)
{
    for (size_t k = 0; s && k < n; k++)
        cn_sheet_free(&s[k]);
    free(s);
}
