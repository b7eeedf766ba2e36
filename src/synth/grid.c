/* The grids of parameter nodes that every triangulation style starts from,
 * and the patch of cells a hole removes. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "synth_internal.h"

/* Fewer cells than this along either direction would leave no room for
 * the hole and the splay at a coarse spacing. */
#define MIN_CELLS 6

void synth_grid_free(synth_grid *g)
{
    free(g->s);
    free(g->t);
    free(g->vid);
    memset(g, 0, sizeof *g);
}

int synth_grid_alloc(synth_grid *g, size_t ns, size_t nt)
{
    size_t n = (ns + 1) * (nt + 1);
    g->ns = ns;
    g->nt = nt;
    g->s = malloc(n * sizeof *g->s);
    g->t = malloc(n * sizeof *g->t);
    g->vid = malloc(n * sizeof *g->vid);
    return g->s && g->t && g->vid ? 0 : -1;
}

/* Cells per segment between breakpoints: uniform within each segment so
 * that every breakpoint (splay ends, junction depth) is a grid line. */
static size_t segment_cells(double len, double h)
{
    double n = ceil(len / h - 1e-9);
    return n < 1.0 ? 1 : (size_t)n;
}

size_t synth_grid_count_cells(const double *br, size_t nb, double h)
{
    double total = br[nb - 1] - br[0];
    if (total / h < MIN_CELLS)
        h = total / MIN_CELLS;
    size_t n = 0;
    for (size_t k = 0; k + 1 < nb; k++)
        n += segment_cells(br[k + 1] - br[k], h);
    return n;
}

static void fill_lines(const double *br, size_t nb, double h, double *out)
{
    double total = br[nb - 1] - br[0];
    if (total / h < MIN_CELLS)
        h = total / MIN_CELLS;
    size_t n = 0;
    for (size_t k = 0; k + 1 < nb; k++) {
        size_t m = segment_cells(br[k + 1] - br[k], h);
        for (size_t q = 0; q < m; q++)
            out[n++] = br[k] + (br[k + 1] - br[k]) * (double)q / (double)m;
    }
    out[n] = br[nb - 1];
}

/* Graded lines: x(u) = u + a (sin(2 pi m u + p) - sin p) / (2 pi m) has
 * slope 1 +- a, so with a = 0.45 the spacing varies by (1.45/0.55) = 2.6x
 * while both ends stay fixed. */
static void graded_lines(double lo, double hi, size_t n, int m, double phase, double *out)
{
    const double a = 0.45, w = 2.0 * SYNTH_PI * m;
    for (size_t k = 0; k <= n; k++) {
        double u = (double)k / (double)n;
        out[k] = lo + (hi - lo) * (u + a * (sin(w * u + phase) - sin(phase)) / w);
    }
    out[0] = lo;
    out[n] = hi;
}

int synth_grid_make(const synth_sheet *sh, int style, double h, const double *sbr, size_t nsb,
                     const double *tbr, size_t ntb, uint64_t *rng, synth_grid *g)
{
    size_t ns = synth_grid_count_cells(sbr, nsb, h), nt = synth_grid_count_cells(tbr, ntb, h);
    double *cs = malloc((ns + 1) * sizeof *cs), *rt = malloc((nt + 1) * sizeof *rt);
    if (!cs || !rt || synth_grid_alloc(g, ns, nt) != 0) {
        free(cs);
        free(rt);
        return -1;
    }
    if (style == SYNTH_GRID_IRREGULAR) {
        graded_lines(sh->s0, sh->s1, ns, 2, 0.9, cs);
        graded_lines(0.0, sh->width, nt, 1, 2.1, rt);
    } else {
        fill_lines(sbr, nsb, h, cs);
        fill_lines(tbr, ntb, h, rt);
    }
    for (size_t j = 0; j <= nt; j++) {
        for (size_t i = 0; i <= ns; i++) {
            double s = cs[i], t = rt[j];
            if (style == SYNTH_GRID_IRREGULAR) {
                /* Within +-0.2 of the smaller neighbouring spacing every
                 * quad stays convex (angles within 90 +- 67 deg), so
                 * either diagonal gives proper triangles. Border nodes
                 * only slide along their border. */
                if (i > 0 && i < ns) {
                    double d = fmin(cs[i] - cs[i - 1], cs[i + 1] - cs[i]);
                    s += (synth_rng_uniform(rng) - 0.5) * 0.4 * d;
                }
                if (j > 0 && j < nt) {
                    double d = fmin(rt[j] - rt[j - 1], rt[j + 1] - rt[j]);
                    t += (synth_rng_uniform(rng) - 0.5) * 0.4 * d;
                }
            }
            g->s[synth_node(g, i, j)] = s;
            g->t[synth_node(g, i, j)] = t;
        }
    }
    free(cs);
    free(rt);
    return 0;
}

/* Removes an elliptic patch of cells, row by row, each row an interval
 * around the same centre column: consecutive rows then share cells, so the
 * patch is one hole whose boundary is a simple loop (no pinch vertex). */
void synth_grid_hole_mask(const synth_fault *f, const synth_grid *g, unsigned char *removed)
{
    size_t ci = 0, cj = 0;
    while (ci + 1 < g->ns && g->s[synth_node(g, ci + 1, 0)] <= f->hole_s)
        ci++;
    while (cj + 1 < g->nt && g->t[synth_node(g, 0, cj + 1)] <= f->hole_t)
        cj++;
    /* Two cells of margin to the border on every side. */
    ci = ci < 2 ? 2 : (ci > g->ns - 3 ? g->ns - 3 : ci);
    cj = cj < 2 ? 2 : (cj > g->nt - 3 ? g->nt - 3 : cj);
    const synth_sheet *sh = &f->sheet[0];
    double hs = (sh->s1 - sh->s0) / (double)g->ns, ht = sh->width / (double)g->nt;
    size_t ri = (size_t)floor(f->hole_rs / hs), rj = (size_t)floor(f->hole_rt / ht);
    if (ri > ci - 2) ri = ci - 2;
    if (ri > g->ns - 3 - ci) ri = g->ns - 3 - ci;
    if (rj > cj - 2) rj = cj - 2;
    if (rj > g->nt - 3 - cj) rj = g->nt - 3 - cj;
    for (size_t j = cj - rj; j <= cj + rj; j++) {
        double q = ((double)j - (double)cj) / ((double)rj + 1.0);
        size_t hw = (size_t)floor((double)ri * sqrt(1.0 - q * q) + 0.5);
        for (size_t i = ci - hw; i <= ci + hw; i++)
            removed[j * g->ns + i] = 1;
    }
}
