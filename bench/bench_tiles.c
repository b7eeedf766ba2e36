/* Rectangular elements alone (fm_tiles_create) on a fault set already
 * meshed: the OBJ a `faultmesh remesh --formats obj` run wrote, tiled at
 * SIZE, with the time it takes and the figures (and how many
 * tiles' centres lie over 3 km from every vertex of their fault), and with
 * -v every fault outside 3 % of its area, with tiles the surface departs
 * from by over SIZE/20, every tile over 3 km off and every junction with
 * a gap over SIZE/2. BENCH_TILES_DUMP=TEXT writes the triangles and tile
 * corners of each fault whose name contains TEXT to /tmp/dump_INDEX.txt
 * ("T" and "Q" lines), to look at.
 * The tiling is a few seconds of a whole run (bench/bench_quads.sh), so
 * this is the quick loop for work on src/mesh/tile*.c.
 *
 *   build/bench/bench_tiles [-v] OUT/mesh.obj [SIZE]
 *
 * The OBJ is read as faultmesh writes it: "v x y z", "o NAME" starting a
 * fault (a "g" of the same name continues it), "f a b c" 1-based. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_clock.h"
#include "fm_mesh.h"
#include "fm_tile.h"

typedef struct names {
    char **v;
    size_t n, cap;
} names;

static int name_push(names *nm, const char *s)
{
    if (nm->n == nm->cap) {
        size_t c = nm->cap ? 2 * nm->cap : 64;
        char **v = realloc(nm->v, c * sizeof *v);
        if (!v)
            return -1;
        nm->v = v;
        nm->cap = c;
    }
    size_t l = strlen(s);
    while (l && (s[l - 1] == '\n' || s[l - 1] == '\r'))
        l--;
    nm->v[nm->n] = malloc(l + 1);
    if (!nm->v[nm->n])
        return -1;
    memcpy(nm->v[nm->n], s, l);
    nm->v[nm->n][l] = 0;
    nm->n++;
    return 0;
}

static fm_mesh *read_obj(const char *path, names *nm)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return NULL;
    fm_mesh *m = fm_mesh_create();
    char line[4096];
    int32_t fault = -1;
    while (m && fgets(line, sizeof line, f)) {
        if (line[0] == 'v' && line[1] == ' ') {
            double x, y, z;
            if (sscanf(line + 2, "%lf %lf %lf", &x, &y, &z) == 3)
                fm_mesh_add_vertex(m, x, y, z);
        } else if (line[0] == 'o' && line[1] == ' ') {
            if (name_push(nm, line + 2))
                break;
            fault = (int32_t)nm->n - 1;
        } else if (line[0] == 'f' && line[1] == ' ' && fault >= 0) {
            long a, b, c;
            if (sscanf(line + 2, "%ld %ld %ld", &a, &b, &c) == 3)
                fm_mesh_add_triangle(m, (int32_t)a - 1, (int32_t)b - 1, (int32_t)c - 1, fault);
        }
    }
    fclose(f);
    return m;
}

int main(int argc, char **argv)
{
    int verbose = argc > 1 && strcmp(argv[1], "-v") == 0;
    if (argc < 2 + verbose) {
        fprintf(stderr, "usage: bench_tiles [-v] OUT/mesh.obj [SIZE]\n");
        return 2;
    }
    names nm = {0};
    fm_mesh *m = read_obj(argv[1 + verbose], &nm);
    double size = argc > 2 + verbose ? atof(argv[2 + verbose]) : 2000;
    if (!m || !nm.n) {
        fprintf(stderr, "bench_tiles: cannot read %s\n", argv[1 + verbose]);
        return 1;
    }
    fm_tiles *t = NULL;
    fm_error err;
    fm_error_clear(&err);
    double t0 = fm_clock_seconds();
    if (fm_tiles_create(m, nm.n, size, &t, &err) != FM_OK) {
        fprintf(stderr, "bench_tiles: %s\n", err.message);
        return 1;
    }
    double dt = fm_clock_seconds() - t0;
    const fm_tile_stats *s = fm_tiles_stats(t);
    size_t out3 = 0, tiled = 0, over = 0;
    double tri = 0, til = 0;
    for (size_t f = 0; f < nm.n; f++) {
        const fm_tile_fault *tf = fm_tiles_fault(t, f);
        if (!tf->ntiles)
            continue;
        tiled++;
        tri += tf->area_triangles;
        til += tf->area_tiles;
        double r = tf->area_tiles / tf->area_triangles;
        if (fabs(r - 1) > 0.03) {
            out3++;
            if (verbose)
                printf("area %.4f  %5zu tiles  %8.1f km2  cut %.1f km2  %s\n", r, tf->ntiles,
                       tf->area_triangles / 1e6, tf->area_cut / 1e6, nm.v[f]);
        }
    }
    if (verbose) {
        size_t *nf = calloc(nm.n, sizeof *nf);
        for (size_t i = 0; nf && i < fm_tiles_count(t); i++)
            nf[fm_tiles_get(t, i)->fault] += fm_tiles_get(t, i)->flatness > size / 20;
        for (size_t f = 0; nf && f < nm.n; f++)
            if (nf[f])
                printf("flat %zu of %zu tiles over H/20  %s\n", nf[f], fm_tiles_fault(t, f)->ntiles,
                       nm.v[f]);
        free(nf);
    }
    /* how far tiles sit from their fault: each centre's distance to the
     * nearest vertex of its fault's triangles */
    size_t off3 = 0;
    double offmax = 0;
    {
        const double *x = fm_mesh_vertices(m);
        const int32_t *tr = fm_mesh_triangles(m), *tg = fm_mesh_tags(m);
        for (size_t i = 0; i < fm_tiles_count(t); i++) {
            const fm_tile *tl = fm_tiles_get(t, i);
            double best = INFINITY;
            for (size_t k = 0; k < fm_mesh_ntriangles(m); k++) {
                if (tg[k] != tl->fault)
                    continue;
                for (int q = 0; q < 3; q++) {
                    const double *p = x + 3 * (size_t)tr[3 * k + q];
                    double d = hypot(hypot(p[0] - tl->centre[0], p[1] - tl->centre[1]),
                                     p[2] - tl->centre[2]);
                    best = fmin(best, d);
                }
            }
            offmax = fmax(offmax, best);
            if (best > 3000) {
                off3++;
                if (verbose)
                    printf("off %.0f m  %s at %.0f,%.0f,%.0f %.0fx%.0f row %d\n", best,
                           nm.v[tl->fault], tl->centre[0], tl->centre[1], tl->centre[2],
                           tl->length, tl->width, tl->row);
            }
        }
    }
    printf("tiles over 3 km from a vertex of their fault: %zu (farthest %.0f m)\n", off3, offmax);
    for (size_t i = 0; i < fm_tiles_njunctions(t); i++) {
        const fm_tile_junction *j = fm_tiles_junction(t, i);
        if (j->gap_max > size / 2) {
            over++;
            if (verbose)
                printf("gap %.0f m over %.0f of %.0f m  %s / %s\n", j->gap_max, j->over_half,
                       j->length, nm.v[j->a], nm.v[j->b]);
        }
    }
    printf("%.2f s: %zu tiles, area %.4f, %zu of %zu faults outside 3 %%, ratio %.3f-%.3f, "
           "flatness p99 %.1f m (%.3f H) max %.0f, %zu of %zu junctions over H/2, %zu meeting, "
           "%zu shrunk, %zu dropped, %zu slivers\n",
           dt, s->ntiles, tri > 0 ? til / tri : 0, out3, tiled, s->area_ratio_min,
           s->area_ratio_max, s->flatness_p99, s->flatness_p99 / size, s->flatness_max, over,
           fm_tiles_njunctions(t), s->meeting, s->shrunk, s->dropped, s->slivers);
    const char *dump = getenv("BENCH_TILES_DUMP");
    for (size_t f = 0; dump && f < nm.n; f++) {
        if (!strstr(nm.v[f], dump))
            continue;
        char fn[512];
        snprintf(fn, sizeof fn, "/tmp/dump_%zu.txt", f);
        FILE *o = fopen(fn, "w");
        if (!o)
            continue;
        fprintf(o, "N %s\n", nm.v[f]);
        const double *x = fm_mesh_vertices(m);
        const int32_t *tr = fm_mesh_triangles(m), *tg = fm_mesh_tags(m);
        for (size_t i = 0; i < fm_mesh_ntriangles(m); i++)
            if ((size_t)tg[i] == f) {
                fprintf(o, "T");
                for (int k = 0; k < 3; k++)
                    fprintf(o, " %.3f %.3f %.3f", x[3 * tr[3 * i + k]], x[3 * tr[3 * i + k] + 1],
                            x[3 * tr[3 * i + k] + 2]);
                fprintf(o, "\n");
            }
        for (size_t i = 0; i < fm_tiles_count(t); i++) {
            const fm_tile *tl = fm_tiles_get(t, i);
            if ((size_t)tl->fault != f)
                continue;
            double c[4][3];
            fm_tile_corners(tl, c);
            fprintf(o, "Q %d %d", tl->row, tl->shrunk);
            for (int k = 0; k < 4; k++)
                fprintf(o, " %.3f %.3f %.3f", c[k][0], c[k][1], c[k][2]);
            fprintf(o, "\n");
        }
        fclose(o);
    }
    fm_tiles_destroy(t);
    fm_mesh_destroy(m);
    for (size_t i = 0; i < nm.n; i++)
        free(nm.v[i]);
    free(nm.v);
    return 0;
}
