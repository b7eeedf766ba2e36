/* Triangulating the analytic sheets in their parameter rectangles.
 *
 * Every style starts from a grid of nodes (rows along t, columns along s)
 * and splits each quad into two triangles, or four around a centre node:
 * quads share whole edges, so the result is conforming whatever the split.
 * The features that later stages must cope with are made here: a hole
 * (quads removed), a seam (a column of nodes duplicated for the second
 * TFACE part), a splay (a second grid whose last row reuses a row of the
 * first), noise (vertices moved after the fact). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "synth_internal.h"

static int32_t add_vertex(const fm_synth *sy, synth_fault *f, size_t k, double s, double t)
{
    double x[3];
    synth_eval_local(sy, f, k, s, t, x);
    return fm_mesh_add_vertex(f->mesh, x[0] + SYNTH_CENTRE_X, x[1] + SYNTH_CENTRE_Y, x[2]);
}

/* Vertices for rows [0, rows) and columns [i0, i1], row by row. */
static int add_nodes(const fm_synth *sy, synth_fault *f, size_t k, synth_grid *g, size_t rows,
                     size_t i0, size_t i1)
{
    for (size_t j = 0; j < rows; j++)
        for (size_t i = i0; i <= i1; i++) {
            size_t n = synth_node(g, i, j);
            if ((g->vid[n] = add_vertex(sy, f, k, g->s[n], g->t[n])) < 0)
                return -1;
            if (j == 0) {
                double z = fm_mesh_vertices(f->mesh)[3 * (size_t)g->vid[n] + 2];
                f->top_zmin = fmin(f->top_zmin, z);
                f->top_zmax = fmax(f->top_zmax, z);
            }
        }
    return 0;
}


static int add_quad(fm_mesh *m, int32_t a, int32_t b, int32_t c, int32_t d, int diag,
                    int32_t centre, int32_t tag)
{
    int32_t r = 0;
    if (centre >= 0) {
        r |= fm_mesh_add_triangle(m, a, b, centre, tag);
        r |= fm_mesh_add_triangle(m, b, c, centre, tag);
        r |= fm_mesh_add_triangle(m, c, d, centre, tag);
        r |= fm_mesh_add_triangle(m, d, a, centre, tag);
    } else if (diag == 0) {
        r |= fm_mesh_add_triangle(m, a, b, c, tag);
        r |= fm_mesh_add_triangle(m, a, c, d, tag);
    } else {
        r |= fm_mesh_add_triangle(m, a, b, d, tag);
        r |= fm_mesh_add_triangle(m, b, c, d, tag);
    }
    return r < 0 ? -1 : 0;
}

/* Quads of columns [i0, i1) tagged tag; when dup is given, column i0's
 * nodes are taken from it (the second part's copy of the seam). */
static int add_cells(const fm_synth *sy, synth_fault *f, const synth_grid *g,
                     const unsigned char *removed, size_t i0, size_t i1, int32_t tag,
                     const int32_t *dup, uint64_t *rng)
{
    for (size_t j = 0; j < g->nt; j++) {
        for (size_t i = i0; i < i1; i++) {
            if (removed && removed[j * g->ns + i])
                continue;
            int32_t a = g->vid[synth_node(g, i, j)], b = g->vid[synth_node(g, i + 1, j)];
            int32_t c = g->vid[synth_node(g, i + 1, j + 1)], d = g->vid[synth_node(g, i, j + 1)];
            if (dup && i == i0) {
                a = dup[j];
                d = dup[j + 1];
            }
            int diag = (int)((i + j) & 1), centre = -1;
            if (f->style == SYNTH_GRID_FIXED) {
                diag = 0;
            } else if (f->style == SYNTH_GRID_IRREGULAR) {
                diag = (int)(synth_rng_next(rng) >> 63);
                if (synth_rng_uniform(rng) < 0.15) {
                    double s = 0.0, t = 0.0;
                    const size_t q[4] = {synth_node(g, i, j), synth_node(g, i + 1, j),
                                         synth_node(g, i + 1, j + 1), synth_node(g, i, j + 1)};
                    for (int k = 0; k < 4; k++) {
                        s += 0.25 * g->s[q[k]];
                        t += 0.25 * g->t[q[k]];
                    }
                    if ((centre = add_vertex(sy, f, 0, s, t)) < 0)
                        return -1;
                }
            }
            if (add_quad(f->mesh, a, b, c, d, diag, centre, tag) != 0)
                return -1;
        }
    }
    return 0;
}

/* The splay: columns of sheet 0 between its ends, rows from the top down
 * to the junction row of sheet 0, whose vertices it reuses. */
static int add_splay(const fm_synth *sy, synth_fault *f, const synth_grid *g0, double h,
                     uint64_t *rng)
{
    const synth_sheet *sp = &f->sheet[1];
    size_t ia = 0, ib = 0, jj = 0;
    while (ia < g0->ns && g0->s[synth_node(g0, ia, 0)] != sp->s0)
        ia++;
    while (ib < g0->ns && g0->s[synth_node(g0, ib, 0)] != sp->s1)
        ib++;
    while (jj < g0->nt && g0->t[synth_node(g0, 0, jj)] != sp->junction_t)
        jj++;
    if (ia >= ib || jj == 0 || jj >= g0->nt)
        return -2;
    double br[2] = {0.0, sp->width};
    synth_grid g = {0};
    if (synth_grid_alloc(&g, ib - ia, synth_grid_count_cells(br, 2, h)) != 0) {
        synth_grid_free(&g);
        return -1;
    }
    for (size_t j = 0; j <= g.nt; j++)
        for (size_t i = 0; i <= g.ns; i++) {
            g.s[synth_node(&g, i, j)] = g0->s[synth_node(g0, ia + i, 0)];
            g.t[synth_node(&g, i, j)] = sp->width * (double)j / (double)g.nt;
        }
    int rc = add_nodes(sy, f, 1, &g, g.nt, 0, g.ns);
    for (size_t i = 0; i <= g.ns; i++)
        g.vid[synth_node(&g, i, g.nt)] = g0->vid[synth_node(g0, ia + i, jj)];
    if (rc == 0)
        rc = add_cells(sy, f, &g, NULL, 0, g.ns, 0, NULL, rng);
    f->junction_edges = ib - ia;
    synth_grid_free(&g);
    return rc;
}

/* Drops the vertices a hole left without triangles, keeping the order of
 * the others, so that files carry no stray VRTX. */
static int drop_unused(fm_mesh *m)
{
    size_t nv = fm_mesh_nvertices(m), nt = fm_mesh_ntriangles(m);
    int32_t *map = malloc(nv * sizeof *map);
    if (!map)
        return -1;
    for (size_t k = 0; k < nv; k++)
        map[k] = -1;
    int32_t *t = fm_mesh_triangles_mut(m);
    for (size_t k = 0; k < 3 * nt; k++)
        map[t[k]] = 0;
    double *v = fm_mesh_vertices_mut(m);
    size_t n = 0;
    for (size_t k = 0; k < nv; k++) {
        if (map[k] < 0)
            continue;
        memmove(v + 3 * n, v + 3 * k, 3 * sizeof *v);
        map[k] = (int32_t)n++;
    }
    for (size_t k = 0; k < 3 * nt; k++)
        t[k] = map[t[k]];
    fm_mesh_truncate(m, n, nt);
    free(map);
    return 0;
}

static void add_noise(synth_fault *f, uint64_t *rng)
{
    double *v = fm_mesh_vertices_mut(f->mesh);
    size_t n = 3 * fm_mesh_nvertices(f->mesh);
    for (size_t k = 0; k < n; k++)
        v[k] += (2.0 * synth_rng_uniform(rng) - 1.0) * f->noise;
}

/* Guards the promise that no triangle is degenerate. */
static int check_triangles(const fm_mesh *m)
{
    const double *v = fm_mesh_vertices(m);
    const int32_t *t = fm_mesh_triangles(m);
    for (size_t k = 0; k < fm_mesh_ntriangles(m); k++) {
        const double *a = v + 3 * (size_t)t[3 * k], *b = v + 3 * (size_t)t[3 * k + 1];
        const double *c = v + 3 * (size_t)t[3 * k + 2];
        if (!(fm_triangle_area(a, b, c) > 0.0) || !(fm_triangle_min_angle(a, b, c) > 5.0))
            return -2;
    }
    return 0;
}

/* 0, or -1 when memory ran out, -2 when the geometry came out wrong. */
static int build(const fm_synth *sy, synth_fault *f, uint64_t *rng, double h, synth_grid *g,
                 unsigned char **removed, int32_t **dup)
{
    const synth_sheet *sh = &f->sheet[0];
    double sbr[4] = {sh->s0, sh->s1}, tbr[3] = {0.0, sh->width};
    size_t nsb = 2, ntb = 2;
    if (f->nsheets > 1) {
        const synth_sheet *sp = &f->sheet[1];
        sbr[1] = sp->s0;
        sbr[2] = sp->s1;
        sbr[3] = sh->s1;
        nsb = 4;
        tbr[1] = sp->junction_t;
        tbr[2] = sh->width;
        ntb = 3;
    }
    if (synth_grid_make(sh, f->style, h, sbr, nsb, tbr, ntb, rng, g) != 0)
        return -1;
    /* With a seam, the second part's vertices and triangles come after the
     * first part's, which is the order a TSurf file lists them in: the
     * file then reads back vertex for vertex as generated. */
    size_t seam = f->seam ? g->ns / 2 : g->ns;
    if (add_nodes(sy, f, 0, g, g->nt + 1, 0, seam) != 0)
        return -1;
    if (f->seam) {
        if (!(*dup = malloc((g->nt + 1) * sizeof **dup)))
            return -1;
        /* Copies, not re-evaluations: bitwise identical coordinates. */
        for (size_t j = 0; j <= g->nt; j++) {
            size_t v = (size_t)g->vid[synth_node(g, seam, j)];
            const double *x = fm_mesh_vertices(f->mesh) + 3 * v;
            if (((*dup)[j] = fm_mesh_add_vertex(f->mesh, x[0], x[1], x[2])) < 0)
                return -1;
        }
        if (add_nodes(sy, f, 0, g, g->nt + 1, seam + 1, g->ns) != 0)
            return -1;
        f->seam_vertices = g->nt + 1;
        f->seam_s = g->s[synth_node(g, seam, 0)];
    }
    if (f->hole) {
        if (!(*removed = calloc(g->ns * g->nt, 1)))
            return -1;
        synth_grid_hole_mask(f, g, *removed);
        f->holes = 1;
    }
    f->nparts = f->seam ? 2 : 1;
    if (add_cells(sy, f, g, *removed, 0, seam, 0, NULL, rng) != 0)
        return -1;
    if (f->seam && add_cells(sy, f, g, *removed, seam, g->ns, 1, *dup, rng) != 0)
        return -1;
    int rc = f->nsheets > 1 ? add_splay(sy, f, g, h, rng) : 0;
    if (rc != 0)
        return rc;
    if (f->hole && drop_unused(f->mesh) != 0)
        return -1;
    if (f->noise > 0.0)
        add_noise(f, rng);
    return check_triangles(f->mesh);
}

fm_status synth_triangulate(const fm_synth *sy, synth_fault *f, uint64_t seed, fm_error *err)
{
    uint64_t rng = seed;
    synth_grid g = {0};
    unsigned char *removed = NULL;
    int32_t *dup = NULL;
    f->top_zmin = INFINITY;
    f->top_zmax = -INFINITY;
    if (!(f->mesh = fm_mesh_create()))
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "synth: out of memory");
    int rc = build(sy, f, &rng, sy->opt.spacing, &g, &removed, &dup);
    synth_grid_free(&g);
    free(removed);
    free(dup);
    if (rc == -1)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "synth: out of memory");
    if (rc != 0)
        return fm_error_set(err, FM_ERR_NUMERIC, NULL, 0,
                            "synth: cannot triangulate %s at spacing %g m", f->name,
                            sy->opt.spacing);
    return FM_OK;
}
