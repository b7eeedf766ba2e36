/* Time of the fault-set writers (fm_faultset_write.h) on a large set.
 *
 *   bench_write [-n REPEATS] [-j THREADS] [-o OUTDIR] [FOLDER]
 *
 * Every .ts file of FOLDER (default: the CFM 500 m set) becomes one fault
 * of one set, its objects and parts merged, and vertices with bit-identical
 * coordinates are shared across faults, as in the set `faultmesh remesh`
 * writes. The CFM's own coordinates carry few decimals; to time what a
 * remesh run writes (coordinates needing 15 to 17 digits), pass the output
 * folder of one, e.g. `faultmesh remesh --size 1000 -o /tmp/w_out ...` then
 * `bench_write /tmp/w_out`. OUTDIR (default /tmp/bench_write) receives
 * mesh.vtu, mesh.msh (4.1), mesh.stl, mesh.obj, ts/NAME.ts, and the
 * simulator files mesh.rsqsim and mesh.eqsim (spherical, through PROJ;
 * rake 180, 1e-9 m/s on every fault).
 *
 * Prints the best wall and CPU time of each writer over REPEATS passes
 * (default 3), of all of them in a row, and of fm_faultset_write_all on
 * 1, 2 and 4 threads (-j N: on N only), with the set's size. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_common.h"
#include "fm_atomic.h"
#include "fm_faultset_write.h"
#include "fm_sim_write.h"
#include "fm_tsurf.h"

typedef struct set {
    fm_mesh *mesh;
    char **names;
    size_t nfaults;
} set;

static const double *g_xyz;

/* Coordinates, then index: equal points end up side by side, first first. */
static int by_point(const void *a, const void *b)
{
    int32_t i = *(const int32_t *)a, j = *(const int32_t *)b;
    const double *p = g_xyz + 3 * (size_t)i, *q = g_xyz + 3 * (size_t)j;
    for (int d = 0; d < 3; d++)
        if (p[d] != q[d])
            return p[d] < q[d] ? -1 : 1;
    return (i > j) - (i < j);
}

/* The raw set (every file's vertices) welded where coordinates are equal;
 * a vertex keeps the position of its first copy. */
static fm_mesh *weld(const fm_mesh *raw)
{
    size_t nv = fm_mesh_nvertices(raw), nt = fm_mesh_ntriangles(raw);
    int32_t *order = malloc((nv ? nv : 1) * sizeof *order);
    int32_t *rep = malloc((nv ? nv : 1) * sizeof *rep);
    int32_t *id = malloc((nv ? nv : 1) * sizeof *id);
    fm_mesh *m = fm_mesh_create();
    if (!order || !rep || !id || !m) {
        free(order), free(rep), free(id), fm_mesh_destroy(m);
        return NULL;
    }
    for (size_t v = 0; v < nv; v++)
        order[v] = (int32_t)v;
    g_xyz = fm_mesh_vertices(raw);
    qsort(order, nv, sizeof *order, by_point);
    for (size_t i = 0; i < nv; i++)
        rep[order[i]] = i && memcmp(g_xyz + 3 * (size_t)order[i - 1], g_xyz + 3 * (size_t)order[i],
                                    3 * sizeof(double)) == 0
                            ? rep[order[i - 1]]
                            : order[i];
    const double *x = fm_mesh_vertices(raw);
    for (size_t v = 0; v < nv; v++)
        id[v] = rep[v] == (int32_t)v ? fm_mesh_add_vertex(m, x[3 * v], x[3 * v + 1], x[3 * v + 2])
                                     : id[rep[v]];
    const int32_t *t = fm_mesh_triangles(raw), *tag = fm_mesh_tags(raw);
    for (size_t k = 0; k < nt; k++)
        fm_mesh_add_triangle(m, id[t[3 * k]], id[t[3 * k + 1]], id[t[3 * k + 2]], tag[k]);
    free(order), free(rep), free(id);
    return m;
}

static int load(const char *dir, set *s)
{
    char **paths = NULL;
    size_t n = 0;
    if (bench_list_ts(dir, &paths, &n) != 0 || n == 0) {
        fprintf(stderr, "bench_write: no .ts file in %s\n", dir);
        return -1;
    }
    fm_mesh *raw = fm_mesh_create();
    s->names = calloc(n, sizeof *s->names);
    for (size_t i = 0; i < n; i++) {
        fm_tsurf **objs;
        size_t nobj;
        fm_error err;
        if (fm_tsurf_read_file(paths[i], &objs, &nobj, &err) != FM_OK) {
            fprintf(stderr, "bench_write: %s\n", err.message);
            return -1;
        }
        const char *nm = fm_tsurf_name(objs[0]);
        const char *base = strrchr(paths[i], '/');
        s->names[i] = strdup(nm[0] ? nm : base ? base + 1 : paths[i]);
        for (size_t k = 0; k < nobj; k++)
            fm_mesh_append(raw, fm_tsurf_mesh(objs[k]), (int32_t)i);
        fm_tsurf_free_all(objs, nobj);
        free(paths[i]);
    }
    free(paths);
    s->nfaults = n;
    s->mesh = weld(raw);
    fm_mesh_destroy(raw);
    return s->mesh ? 0 : -1;
}

typedef fm_status (*writer)(const char *out, const fm_faultset *fs, fm_error *err);

static fm_status w_vtu(const char *o, const fm_faultset *fs, fm_error *e)
{
    char p[4096];
    snprintf(p, sizeof p, "%s/mesh.vtu", o);
    return fm_faultset_write_vtu(p, fs, e);
}
static fm_status w_msh(const char *o, const fm_faultset *fs, fm_error *e)
{
    char p[4096];
    snprintf(p, sizeof p, "%s/mesh.msh", o);
    return fm_faultset_write_msh(p, fs, FM_MSH_41, e);
}
static fm_status w_stl(const char *o, const fm_faultset *fs, fm_error *e)
{
    char p[4096];
    snprintf(p, sizeof p, "%s/mesh.stl", o);
    return fm_faultset_write_stl(p, fs, e);
}
static fm_status w_obj(const char *o, const fm_faultset *fs, fm_error *e)
{
    char p[4096];
    snprintf(p, sizeof p, "%s/mesh.obj", o);
    return fm_faultset_write_obj(p, fs, e);
}
static fm_status w_ts(const char *o, const fm_faultset *fs, fm_error *e)
{
    char p[4096];
    snprintf(p, sizeof p, "%s/ts", o);
    return fm_faultset_write_tsurf(p, fs, e);
}

static fm_sim_slip g_slip;

static fm_status w_rsqsim(const char *o, const fm_faultset *fs, fm_error *e)
{
    char p[4096];
    snprintf(p, sizeof p, "%s/mesh.rsqsim", o);
    return fm_faultset_write_rsqsim(p, fs, &g_slip, e);
}
static fm_status w_eqsim(const char *o, const fm_faultset *fs, fm_error *e)
{
    char p[4096];
    snprintf(p, sizeof p, "%s/mesh.eqsim", o);
    return fm_faultset_write_eqsim(p, fs, &g_slip, FM_EQSIM_SPHERICAL, e);
}

static const struct {
    const char *name;
    writer fn;
} writers[] = {{"vtu", w_vtu},       {"msh", w_msh},      {"stl", w_stl},
               {"obj", w_obj},       {"tsurf", w_ts},     {"rsqsim", w_rsqsim},
               {"eqsim", w_eqsim}};
#define NWRITERS (sizeof writers / sizeof writers[0])

int main(int argc, char **argv)
{
    const char *dir = FM_CFM_DIR "/CFM5.3/500m", *out = "/tmp/bench_write";
    int repeats = 3, jobs = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-n") == 0 && i + 1 < argc)
            repeats = atoi(argv[++i]);
        else if (strcmp(argv[i], "-j") == 0 && i + 1 < argc)
            jobs = atoi(argv[++i]);
        else if (strcmp(argv[i], "-o") == 0 && i + 1 < argc)
            out = argv[++i];
        else if (argv[i][0] == '-') {
            fprintf(stderr, "usage: bench_write [-n REPEATS] [-j THREADS] [-o OUTDIR] [FOLDER]\n");
            return 2;
        } else
            dir = argv[i];
    }
    if (repeats < 1)
        repeats = 1;
    set s = {0};
    double t0 = fm_clock_seconds();
    if (load(dir, &s) != 0)
        return 1;
    printf("folder      %s (loaded in %.2f s)\n", dir, fm_clock_seconds() - t0);
    printf("set         %zu faults, %zu vertices, %zu triangles\n", s.nfaults,
           fm_mesh_nvertices(s.mesh), fm_mesh_ntriangles(s.mesh));
    fm_faultset fs = {.mesh = s.mesh,
                      .names = (const char *const *)s.names,
                      .nfaults = s.nfaults,
                      .crs = "EPSG:26711"};
    double *rake = malloc((s.nfaults + 1) * sizeof *rake), *rate = malloc((s.nfaults + 1) * sizeof *rate);
    if (!rake || !rate)
        return 1;
    for (size_t f = 0; f < s.nfaults; f++) {
        rake[f] = 180;
        rate[f] = 1e-9;
    }
    g_slip = (fm_sim_slip){rake, rate, NULL, NULL};
    fm_error err;
    if (fm_mkdir_p(out, &err) != FM_OK) {
        fprintf(stderr, "bench_write: %s\n", err.message);
        return 1;
    }
    double best[NWRITERS], cpu[NWRITERS], best_all = 1e300, cpu_all = 1e300;
    for (size_t w = 0; w < NWRITERS; w++)
        best[w] = cpu[w] = 1e300;
    for (int r = 0; r < repeats; r++) {
        double all = 0, all_cpu = 0;
        for (size_t w = 0; w < NWRITERS; w++) {
            double t = fm_clock_seconds(), c = bench_cpu_seconds();
            if (writers[w].fn(out, &fs, &err) != FM_OK) {
                fprintf(stderr, "bench_write: %s\n", err.message);
                return 1;
            }
            t = fm_clock_seconds() - t;
            c = bench_cpu_seconds() - c;
            all += t;
            all_cpu += c;
            best[w] = t < best[w] ? t : best[w];
            cpu[w] = c < cpu[w] ? c : cpu[w];
        }
        best_all = all < best_all ? all : best_all;
        cpu_all = all_cpu < cpu_all ? all_cpu : cpu_all;
    }
    printf("writer      wall s   cpu s (best of %d)\n", repeats);
    for (size_t w = 0; w < NWRITERS; w++)
        printf("%-11s %6.3f  %6.3f\n", writers[w].name, best[w], cpu[w]);
    printf("all, serial %6.3f  %6.3f\n", best_all, cpu_all);

    char p[5][4096];
    const char *ext[4] = {"vtu", "msh", "stl", "obj"};
    for (int k = 0; k < 4; k++)
        snprintf(p[k], sizeof p[k], "%s/all/mesh.%s", out, ext[k]);
    snprintf(p[4], sizeof p[4], "%s/all", out);
    fm_faultset_outputs o = {p[0], p[1], p[2], p[3], FM_MSH_41, p[4], NULL, NULL, NULL};
    int threads[3] = {1, 2, 4}, nthreads = 3;
    if (jobs > 0) {
        threads[0] = jobs;
        nthreads = 1;
    }
    for (int k = 0; k < nthreads; k++) {
        double wall = 1e300, c_best = 1e300;
        for (int r = 0; r < repeats; r++) {
            double t = fm_clock_seconds(), c = bench_cpu_seconds();
            if (fm_faultset_write_all(&fs, &o, threads[k], &err) != FM_OK) {
                fprintf(stderr, "bench_write: %s\n", err.message);
                return 1;
            }
            t = fm_clock_seconds() - t;
            c = bench_cpu_seconds() - c;
            wall = t < wall ? t : wall;
            c_best = c < c_best ? c : c_best;
        }
        printf("all, %d thr  %6.3f  %6.3f\n", threads[k], wall, c_best);
    }
    for (size_t i = 0; i < s.nfaults; i++)
        free(s.names[i]);
    free(s.names);
    free(rake);
    free(rate);
    fm_mesh_destroy(s.mesh);
    return 0;
}
