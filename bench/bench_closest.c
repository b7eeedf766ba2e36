/* Closest-point tree (fm_closest.h): build time and query throughput.
 *
 *   bench_closest [-n GRID] [-q QUERIES]    (defaults: 708, 1000000)
 *
 * The mesh is a synthetic wavy, dipping sheet on a GRID x GRID vertex grid
 * at 50 m spacing and UTM offsets (708 gives 999,698 triangles), jittered so
 * that no two triangles are alike. Query points lie near the surface: a
 * random point of a triangle moved 0 .. 100 m in a random direction. They
 * run on one thread, first from random triangles (the worst case: nearly
 * every node visited is a cache miss), then from the triangles in mesh
 * order (as a check stage walking output nodes would ask), each unbounded
 * and with max_dist 10 m. Prints the build time and queries per second on
 * the monotonic clock, and a checksum of the distances so that the work
 * cannot be optimised away. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_common.h"
#include "fm_closest.h"

static uint64_t rng_state = 12345;

static uint64_t splitmix64(void)
{
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static double rnd_unit(void) { return (double)(splitmix64() >> 11) * 0x1p-53; }

static fm_mesh *wavy(int n)
{
    fm_mesh *m = fm_mesh_create();
    if (!m || fm_mesh_reserve(m, (size_t)n * n, 2 * (size_t)(n - 1) * (n - 1)) != FM_OK)
        return NULL;
    const double step = 50;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double u = (i + 0.6 * rnd_unit() - 0.3) * step;
            double w = (j + 0.6 * rnd_unit() - 0.3) * step;
            fm_mesh_add_vertex(m, 450000 + u + 80 * sin(w / 700),
                               3750000 + 0.5 * w + 300 * sin(u / 900),
                               -0.8 * w + 50 * cos(u / 400 + w / 300));
        }
    for (int j = 0; j + 1 < n; j++)
        for (int i = 0; i + 1 < n; i++) {
            int32_t v0 = j * n + i, v1 = v0 + 1, v2 = v0 + n, v3 = v2 + 1;
            fm_mesh_add_triangle(m, v0, v1, v3, 0);
            fm_mesh_add_triangle(m, v0, v3, v2, 0);
        }
    return m;
}

static void near_point(const fm_mesh *m, size_t tri, double p[3])
{
    const double *v = fm_mesh_vertices(m);
    const int32_t *t = fm_mesh_triangles(m) + 3 * tri;
    double a = rnd_unit(), b = rnd_unit();
    if (a + b > 1) {
        a = 1 - a;
        b = 1 - b;
    }
    double dir[3], len;
    do {
        for (int k = 0; k < 3; k++)
            dir[k] = 2 * rnd_unit() - 1;
        len = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    } while (len > 1 || len < 1e-3);
    double off = 100 * rnd_unit() / len;
    for (int k = 0; k < 3; k++)
        p[k] = (1 - a - b) * v[3 * t[0] + k] + a * v[3 * t[1] + k] + b * v[3 * t[2] + k] +
               off * dir[k];
}

static void run(const fm_closest_tree *t, const double *pts, size_t nq, double max_dist,
                const char *order)
{
    double t0 = fm_clock_seconds(), sum = 0;
    size_t found = 0;
    for (size_t i = 0; i < nq; i++) {
        fm_closest_hit h;
        if (fm_closest_query(t, pts + 3 * i, max_dist, &h)) {
            found++;
            sum += h.dist;
        }
    }
    double dt = fm_clock_seconds() - t0;
    printf("%s, max_dist %g: %zu queries in %.3f s = %.0f queries/s, %zu found, checksum %.6f\n",
           order, max_dist, nq, dt, (double)nq / dt, found, sum);
}

int main(int argc, char **argv)
{
    int grid = 708;
    size_t nq = 1000000;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-n") == 0 && i + 1 < argc)
            grid = atoi(argv[++i]);
        else if (strcmp(argv[i], "-q") == 0 && i + 1 < argc)
            nq = (size_t)atol(argv[++i]);
        else {
            fprintf(stderr, "usage: bench_closest [-n GRID] [-q QUERIES]\n");
            return 2;
        }
    }
    if (grid < 2 || nq < 1) {
        fprintf(stderr, "bench_closest: GRID must be >= 2 and QUERIES >= 1\n");
        return 2;
    }
    fm_mesh *m = wavy(grid);
    double *pts = malloc(3 * nq * sizeof *pts), *seq = malloc(3 * nq * sizeof *seq);
    if (!m || !pts || !seq) {
        fprintf(stderr, "bench_closest: out of memory\n");
        return 1;
    }
    size_t nt = fm_mesh_ntriangles(m);
    for (size_t i = 0; i < nq; i++) {
        near_point(m, splitmix64() % nt, pts + 3 * i);
        near_point(m, (size_t)((double)i / (double)nq * (double)nt), seq + 3 * i);
    }
    printf("mesh: %zu vertices, %zu triangles\n", fm_mesh_nvertices(m), fm_mesh_ntriangles(m));

    for (int quick = 0; quick < 2; quick++) {
        fm_error err;
        double t0 = fm_clock_seconds(), c0 = bench_cpu_seconds();
        fm_closest_tree *t = quick ? fm_closest_tree_create_quick(m, &err)
                                   : fm_closest_tree_create(m, &err);
        double dt = fm_clock_seconds() - t0, dc = bench_cpu_seconds() - c0;
        if (!t) {
            fprintf(stderr, "bench_closest: %s\n", err.message);
            return 1;
        }
        printf("%s build: %.3f s, %.3f s CPU (%.0f triangles/s)\n", quick ? "quick" : "SAH",
               dt, dc, (double)fm_mesh_ntriangles(m) / dt);
        run(t, pts, nq, INFINITY, "random order");
        run(t, pts, nq, 10.0, "random order");
        run(t, seq, nq, INFINITY, "mesh order");
        run(t, seq, nq, 10.0, "mesh order");
        fm_closest_tree_destroy(t);
    }
    fm_mesh_destroy(m);
    free(pts);
    free(seq);
    return 0;
}
