/* Element slip from deformation-model fault sections (fm_kinematics.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_closest.h"
#include "fm_kinematics.h"
#include "fm_reproject.h"
#include "fm_sim_write.h"

#define DEG (3.14159265358979323846 / 180.0)
/* Grid cells of the quads' reach (m). */
#define CELL 5000.0

void fm_kinematics_options_default(fm_kinematics_options *o)
{
    o->max_distance = 3000;
    o->max_angle = 45;
    o->depth_max = 40;
}

/* One segment of a section, swept down dip, one way of drawing it. */
typedef struct quad {
    double p[4][3];   /* top a, top b, bottom b, bottom a */
    double n[3];      /* normal towards the hanging wall (up, or right of strike) */
    double slip[3];   /* slip of the hanging wall, x east, y north, z up */
    int32_t section;
    int convention;
    double lo[2], hi[2]; /* horizontal box */
} quad;

typedef struct grid {
    double lo[2];
    size_t nx, ny;
    size_t *start, *item; /* per cell: quads (CSR) */
} grid;

/* Slip vector (x east, y north, z up) of strike phi, dip delta, rake
 * lambda (Aki & Richards), and the normal towards the hanging wall. */
static void frame(double phi, double delta, double lambda, double slip[3], double n[3])
{
    double sp = sin(phi * DEG), cp = cos(phi * DEG), sd = sin(delta * DEG),
           cd = cos(delta * DEG), sl = sin(lambda * DEG), cl = cos(lambda * DEG);
    /* north, east, down of Aki & Richards (4.83) */
    double un = cl * cp + sl * cd * sp, ue = cl * sp - sl * cd * cp, ud = -sl * sd;
    slip[0] = ue;
    slip[1] = un;
    slip[2] = -ud;
    /* the dip direction is strike + 90: (east, north) = (cos phi, -sin phi) */
    n[0] = sd * cp;
    n[1] = -sd * sp;
    n[2] = cd;
}

/* The trace in the set's CRS, in the right-hand order. */
static double *section_trace(const fm_section *sc, const fm_reproject *rp, size_t *n)
{
    double *xy = malloc((2 * sc->ntrace + 1) * sizeof *xy);
    if (!xy)
        return NULL;
    for (size_t i = 0; i < sc->ntrace; i++)
        if (fm_reproject_point(rp, sc->trace[2 * i], sc->trace[2 * i + 1], &xy[2 * i],
                               &xy[2 * i + 1])) {
            free(xy);
            return NULL;
        }
    *n = sc->ntrace;
    if (isfinite(sc->dip_dir) && sc->dip < 90) {
        double dx = xy[2 * (*n - 1)] - xy[0], dy = xy[2 * (*n - 1) + 1] - xy[1];
        double right = atan2(dx, dy) / DEG + 90; /* azimuth of the right side */
        double diff = fmod(fabs(right - sc->dip_dir), 360);
        if (diff > 180)
            diff = 360 - diff;
        if (diff > 90) /* drawn the other way */
            for (size_t i = 0; i < *n / 2; i++)
                for (int k = 0; k < 2; k++) {
                    double t = xy[2 * i + k];
                    xy[2 * i + k] = xy[2 * (*n - 1 - i) + k];
                    xy[2 * (*n - 1 - i) + k] = t;
                }
    }
    return xy;
}

/* The quads of section k (both drawings if buried) appended to *q. */
static int section_quads(const fm_section *sc, int32_t k, const fm_reproject *rp,
                         const fm_kinematics_options *o, quad **q, size_t *nq, size_t *cap)
{
    size_t n;
    double *xy = section_trace(sc, rp, &n);
    if (!xy)
        return -1;
    int ways = sc->up_depth > 0 && sc->dip < 90 ? 2 : 1;
    double ztop = -1000 * sc->up_depth, zbot = -1000 * fmax(o->depth_max, sc->low_depth);
    for (int w = 0; w < ways; w++)
        for (size_t i = 0; i + 1 < n; i++) {
            const double *a = xy + 2 * i, *b = xy + 2 * i + 2;
            double dx = b[0] - a[0], dy = b[1] - a[1], len = hypot(dx, dy);
            if (!(len > 0))
                continue;
            if (*nq == *cap) {
                size_t c = *cap ? 2 * *cap : 1024;
                quad *g = realloc(*q, c * sizeof *g);
                if (!g) {
                    free(xy);
                    return -1;
                }
                *q = g;
                *cap = c;
            }
            quad *u = &(*q)[(*nq)++];
            double phi = atan2(dx, dy) / DEG;
            frame(phi, sc->dip, sc->rake, u->slip, u->n);
            /* horizontal unit towards the dip, and down-dip unit */
            double r[2] = {dy / len, -dx / len};
            double cot = sc->dip < 90 ? cos(sc->dip * DEG) / sin(sc->dip * DEG) : 0;
            /* way 1: the trace is where the plane meets the surface */
            double shift = w == 1 ? -ztop * cot : 0;
            double down = (ztop - zbot) * cot;
            for (int c = 0; c < 2; c++) {
                const double *p = c ? b : a;
                double *top = u->p[c ? 1 : 0], *bot = u->p[c ? 2 : 3];
                top[0] = p[0] + shift * r[0];
                top[1] = p[1] + shift * r[1];
                top[2] = ztop;
                bot[0] = top[0] + down * r[0];
                bot[1] = top[1] + down * r[1];
                bot[2] = zbot;
            }
            u->section = k;
            u->convention = w;
            u->lo[0] = u->lo[1] = INFINITY;
            u->hi[0] = u->hi[1] = -INFINITY;
            for (int c = 0; c < 4; c++)
                for (int d = 0; d < 2; d++) {
                    u->lo[d] = fmin(u->lo[d], u->p[c][d] - o->max_distance);
                    u->hi[d] = fmax(u->hi[d], u->p[c][d] + o->max_distance);
                }
        }
    free(xy);
    return 0;
}

static size_t cell_of(const grid *g, double v, int axis)
{
    double t = floor((v - g->lo[axis]) / CELL);
    size_t n = axis ? g->ny : g->nx;
    return !(t > 0) ? 0 : t >= (double)n ? n - 1 : (size_t)t;
}

/* Quads by the cells their reach covers, over the set's box. */
static int grid_make(grid *g, const quad *q, size_t nq, const double box[4])
{
    memset(g, 0, sizeof *g);
    g->lo[0] = box[0];
    g->lo[1] = box[1];
    g->nx = (size_t)fmin((box[2] - box[0]) / CELL + 1, 4096);
    g->ny = (size_t)fmin((box[3] - box[1]) / CELL + 1, 4096);
    size_t nc = g->nx * g->ny;
    g->start = calloc(nc + 1, sizeof *g->start);
    if (!g->start)
        return -1;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t k = 0; k < nq; k++) {
            if (q[k].hi[0] < box[0] || q[k].lo[0] > box[2] || q[k].hi[1] < box[1] ||
                q[k].lo[1] > box[3])
                continue;
            size_t i0 = cell_of(g, q[k].lo[0], 0), i1 = cell_of(g, q[k].hi[0], 0);
            size_t j0 = cell_of(g, q[k].lo[1], 1), j1 = cell_of(g, q[k].hi[1], 1);
            for (size_t j = j0; j <= j1; j++)
                for (size_t i = i0; i <= i1; i++) {
                    if (pass == 0)
                        g->start[j * g->nx + i + 1]++;
                    else
                        g->item[g->start[j * g->nx + i]++] = k;
                }
        }
        if (pass == 0) {
            for (size_t c = 0; c < nc; c++)
                g->start[c + 1] += g->start[c];
            if (!(g->item = malloc((g->start[nc] + 1) * sizeof *g->item)))
                return -1;
        } else {
            for (size_t c = nc; c > 0; c--)
                g->start[c] = g->start[c - 1];
            g->start[0] = 0;
        }
    }
    return 0;
}

/* Distance from p to quad u (two triangles), coordinates taken about p. */
static double quad_distance(const quad *u, const double p[3])
{
    double c[4][3], o[3] = {0, 0, 0};
    for (int k = 0; k < 4; k++)
        for (int d = 0; d < 3; d++)
            c[k][d] = u->p[k][d] - p[d];
    double d1 = fm_closest_on_triangle(o, c[0], c[1], c[2], NULL, NULL);
    double d2 = fm_closest_on_triangle(o, c[0], c[2], c[3], NULL, NULL);
    return sqrt(fmin(d1, d2));
}

fm_status fm_kinematics_assign(const fm_sections *s, const fm_faultset *fs, const double *strike,
                               const double *dip, const fm_kinematics_options *opt,
                               fm_element_kinematics *out, fm_error *err)
{
    fm_kinematics_options o;
    if (!opt)
        fm_kinematics_options_default(&o);
    else
        o = *opt;
    size_t nt = fm_mesh_ntriangles(fs->mesh), ns = fm_sections_count(s);
    for (size_t t = 0; t < nt; t++)
        out[t] = (fm_element_kinematics){-1, 0, INFINITY, 0};
    if (!ns || !nt)
        return FM_OK;
    /* one operation from WGS 84 for every trace: over their extent */
    double ll[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (size_t k = 0; k < ns; k++) {
        const fm_section *sc = fm_sections_get(s, k);
        for (size_t i = 0; i < sc->ntrace; i++) {
            ll[0] = fmin(ll[0], sc->trace[2 * i]);
            ll[1] = fmin(ll[1], sc->trace[2 * i + 1]);
            ll[2] = fmax(ll[2], sc->trace[2 * i]);
            ll[3] = fmax(ll[3], sc->trace[2 * i + 1]);
        }
    }
    fm_reproject *rp = fm_reproject_create("EPSG:4326", fs->crs, ll, "kinematics", err);
    if (!rp)
        return err ? err->code : FM_ERR_INVALID;
    quad *q = NULL;
    size_t nq = 0, cap = 0;
    fm_status st = FM_OK;
    for (size_t k = 0; k < ns && st == FM_OK; k++)
        if (section_quads(fm_sections_get(s, k), (int32_t)k, rp, &o, &q, &nq, &cap))
            st = fm_error_set(err, FM_ERR_NUMERIC, "kinematics", 0,
                              "section %ld (%s): its trace cannot be converted to %s, or out "
                              "of memory",
                              fm_sections_get(s, k)->id, fm_sections_get(s, k)->name, fs->crs);
    fm_reproject_destroy(rp);
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh);
    double box[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < fm_mesh_nvertices(fs->mesh); v++) {
        box[0] = fmin(box[0], x[3 * v]);
        box[1] = fmin(box[1], x[3 * v + 1]);
        box[2] = fmax(box[2], x[3 * v]);
        box[3] = fmax(box[3], x[3 * v + 1]);
    }
    grid g = {0};
    if (st == FM_OK && grid_make(&g, q, nq, box))
        st = fm_error_set(err, FM_ERR_NOMEM, "kinematics", 0, "out of memory");
    double cosmax = cos(o.max_angle * DEG);
    for (size_t t = 0; t < nt && st == FM_OK; t++) {
        double c[3];
        for (int d = 0; d < 3; d++)
            c[d] = (x[3 * (size_t)tri[3 * t] + d] + x[3 * (size_t)tri[3 * t + 1] + d] +
                    x[3 * (size_t)tri[3 * t + 2] + d]) / 3;
        double es[3], en[3];
        frame(strike[t], dip[t], 0, es, en);
        size_t cell = cell_of(&g, c[1], 1) * g.nx + cell_of(&g, c[0], 0);
        const quad *best = NULL;
        double bd = INFINITY;
        for (size_t i = g.start[cell]; i < g.start[cell + 1]; i++) {
            const quad *u = &q[g.item[i]];
            if (c[0] < u->lo[0] || c[0] > u->hi[0] || c[1] < u->lo[1] || c[1] > u->hi[1])
                continue;
            double cosang = fabs(u->n[0] * en[0] + u->n[1] * en[1] + u->n[2] * en[2]);
            if (cosang < cosmax)
                continue;
            double dist = quad_distance(u, c);
            if (dist <= o.max_distance &&
                (dist < bd || (dist == bd && best && u->section < best->section))) {
                bd = dist;
                best = u;
            }
        }
        if (!best)
            continue;
        /* the slip of the element's upper (hanging-wall) side */
        double sgn = best->n[0] * en[0] + best->n[1] * en[1] + best->n[2] * en[2] < 0 ? -1 : 1;
        double u[3] = {sgn * best->slip[0], sgn * best->slip[1], sgn * best->slip[2]};
        double h[3], dummy[3];
        frame(strike[t], dip[t], 90, h, dummy); /* the element's rake-90 direction */
        double along = u[0] * es[0] + u[1] * es[1] + u[2] * es[2];
        double updip = u[0] * h[0] + u[1] * h[1] + u[2] * h[2];
        double rake = atan2(updip, along) / DEG;
        out[t] = (fm_element_kinematics){best->section, best->convention, bd,
                                         rake <= -180 ? rake + 360 : rake};
    }
    free(g.start);
    free(g.item);
    free(q);
    return st;
}
