/* Remesh speed and memory on a folder of .ts files: the measuring tool of
 * the mesh issue's performance targets (whole CFM 500 m set, top cut:
 * <= 20 s wall at H = 1 km, <= 40 s at 500 m, peak memory <= 2 GB).
 *
 *   bench_remesh [-q] [-s H]... [-m SUBSTRING] [-e EVERY] [FOLDER]
 *
 * Default: the CFM 500 m set (FM_CFM_DIR; skipped, exit 0, when absent) at
 * H = 1000 and 500 m. -s H (repeatable) sets the sizes, -m keeps the files
 * whose path contains SUBSTRING, -e every EVERY-th file, -q prints no line
 * per fault.
 *
 * Every file goes through what `faultmesh remesh` does, single-threaded:
 * read (fm_tsurf_read_file) and repair (fm_repair) each object, fit
 * (fm_model_build), then for each size mesh (fm_remesh_model, top cut) and
 * check (closest-point tree of the original, fm_check_quality,
 * fm_check_fidelity). Read, repair and fit are done once and shared by the
 * sizes; a size's pipeline time is read + repair + fit + its mesh + its
 * check. Printed per size: faults meshed and failed, triangles, mesh time
 * and triangles per second, check time, pipeline time (every stage also in
 * CPU time of the thread, which other load on the machine hardly moves);
 * how mesh time grows with a fault's triangle count (least-squares slope
 * of log time over log triangles across faults, and time per triangle by
 * size class); the slowest faults; and the wall and CPU time of the whole run and its peak RSS
 * (getrusage; with several sizes it covers all of them: run with one -s
 * for a size's own peak). Exit 1 if any fault failed, 2 on bad usage or
 * unreadable input. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "bench_common.h"
#include "fm_check.h"
#include "fm_closest.h"
#include "fm_model.h"
#include "fm_remesh.h"
#include "fm_repair.h"
#include "fm_tsurf.h"

#define MAX_SIZES 8

typedef struct fault_run {
    char *name;
    size_t in_triangles;
    size_t tris[MAX_SIZES];
    double t_mesh[MAX_SIZES];
    int failed[MAX_SIZES];
} fault_run;

typedef struct size_totals {
    double H;
    size_t tris, nodes, meshed, empty, failed;
    size_t below30, edges, band;
    double mesh, check, worst_dist;
    double cpu_mesh, cpu_check;
} size_totals;

typedef struct totals {
    double read, repair, fit;
    double cpu_read, cpu_repair, cpu_fit;
    size_t objects, fit_failed, in_triangles;
} totals;

static double peak_rss_mb(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_maxrss / 1024.0; /* Linux: kilobytes */
}

/* Meshes and checks one fitted fault at every size. */
static void mesh_sizes(const fm_model *model, const fm_mesh *orig, const char *name,
                       size_totals *st, size_t nsizes, fault_run *fr)
{
    for (size_t k = 0; k < nsizes; k++) {
        fm_remesh_options mo;
        fm_remesh_options_default(&mo);
        mo.name = name;
        mo.size = st[k].H;
        fm_mesh *mesh = NULL;
        fm_remesh_stats ms;
        fm_error err;
        fm_error_clear(&err);
        double t0 = fm_clock_seconds(), c0 = bench_thread_cpu_seconds();
        fm_status rc = fm_remesh_model(model, &mo, &mesh, &ms, &err);
        double t1 = fm_clock_seconds(), c1 = bench_thread_cpu_seconds();
        st[k].mesh += t1 - t0;
        st[k].cpu_mesh += c1 - c0;
        fr->t_mesh[k] += t1 - t0;
        if (rc != FM_OK) {
            fprintf(stderr, "bench_remesh: H %g: %s\n", st[k].H, err.message);
            st[k].failed++;
            fr->failed[k] = 1;
            continue;
        }
        size_t nt = fm_mesh_ntriangles(mesh);
        fr->tris[k] += nt;
        if (nt == 0) {
            st[k].empty++;
            fm_mesh_destroy(mesh);
            continue;
        }
        st[k].meshed++;
        st[k].tris += nt;
        fm_closest_tree *tree = fm_closest_tree_create(orig, &err);
        fm_quality q;
        fm_fidelity fid;
        if (tree && fm_check_quality(mesh, -1, st[k].H, &q) == FM_OK &&
            fm_check_fidelity(mesh, -1, orig, tree, &fid) == FM_OK) {
            st[k].nodes += q.nodes;
            st[k].below30 += q.below_30;
            st[k].edges += q.edges;
            st[k].band += q.edges_in_band;
            st[k].worst_dist = fmax(st[k].worst_dist, fid.max);
        } else {
            fprintf(stderr, "bench_remesh: %s: check failed\n", name);
        }
        fm_closest_tree_destroy(tree);
        st[k].check += fm_clock_seconds() - t1;
        st[k].cpu_check += bench_thread_cpu_seconds() - c1;
        fm_mesh_destroy(mesh);
    }
}

static int run_file(const char *path, fault_run *fr, totals *tot, size_totals *st,
                    size_t nsizes)
{
    fm_tsurf **objs = NULL;
    size_t nobj = 0;
    fm_error err;
    fm_error_clear(&err);
    double t0 = fm_clock_seconds(), c0 = bench_thread_cpu_seconds();
    if (fm_tsurf_read_file(path, &objs, &nobj, &err) != FM_OK) {
        fprintf(stderr, "bench_remesh: %s\n", err.message);
        return -1;
    }
    tot->read += fm_clock_seconds() - t0;
    tot->cpu_read += bench_thread_cpu_seconds() - c0;
    const char *base = strrchr(path, '/');
    fr->name = strdup(base ? base + 1 : path);
    for (size_t o = 0; o < nobj; o++) {
        const fm_mesh *orig = fm_tsurf_mesh(objs[o]);
        fr->in_triangles += fm_mesh_ntriangles(orig);
        tot->in_triangles += fm_mesh_ntriangles(orig);
        tot->objects++;
        double ta = fm_clock_seconds(), ca = bench_thread_cpu_seconds();
        fm_surface *surf = NULL;
        fm_status rc = fm_repair(orig, NULL, &surf, &err);
        double tb = fm_clock_seconds(), cb = bench_thread_cpu_seconds();
        tot->repair += tb - ta;
        tot->cpu_repair += cb - ca;
        fm_model *model = NULL;
        if (rc == FM_OK) {
            fm_model_options mo;
            fm_remesh_model_options_default(&mo); /* as `faultmesh remesh` */
            rc = fm_model_build(path, surf, &mo, &model, &err);
        }
        tot->fit += fm_clock_seconds() - tb;
        tot->cpu_fit += bench_thread_cpu_seconds() - cb;
        if (rc != FM_OK) {
            fprintf(stderr, "bench_remesh: %s\n", err.message);
            tot->fit_failed++;
            for (size_t k = 0; k < nsizes; k++) {
                st[k].failed++;
                fr->failed[k] = 1;
            }
        } else {
            mesh_sizes(model, orig, path, st, nsizes, fr);
        }
        fm_model_destroy(model);
        fm_surface_destroy(surf);
    }
    fm_tsurf_free_all(objs, nobj);
    return 0;
}

/* Slope of log(time) over log(triangles) across the faults meshed at
 * size k (faults under 20 triangles or 1 ms are dominated by fixed costs
 * and left out). */
static double growth_slope(const fault_run *f, size_t nf, size_t k, size_t *used)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    size_t n = 0;
    for (size_t i = 0; i < nf; i++) {
        if (f[i].failed[k] || f[i].tris[k] < 20 || f[i].t_mesh[k] < 1e-3)
            continue;
        double x = log((double)f[i].tris[k]), y = log(f[i].t_mesh[k]);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
        n++;
    }
    *used = n;
    double d = (double)n * sxx - sx * sx;
    return n > 2 && d > 0 ? ((double)n * sxy - sx * sy) / d : NAN;
}

static void size_classes(const fault_run *f, size_t nf, size_t k)
{
    static const size_t lim[] = {0, 100, 300, 1000, 3000, 10000, 30000, (size_t)-1};
    printf("  mesh time per triangle by fault size (triangles: faults, us/triangle):");
    for (int c = 0; c < 7; c++) {
        double t = 0;
        size_t n = 0, tris = 0;
        for (size_t i = 0; i < nf; i++)
            if (!f[i].failed[k] && f[i].tris[k] > 0 && f[i].tris[k] >= lim[c] &&
                f[i].tris[k] < lim[c + 1]) {
                t += f[i].t_mesh[k];
                tris += f[i].tris[k];
                n++;
            }
        if (!n)
            continue;
        if (c == 6)
            printf("\n    >= %zu: %zu, %.1f", lim[c], n, 1e6 * t / (double)tris);
        else
            printf("\n    %zu-%zu: %zu, %.1f", lim[c], lim[c + 1] - 1, n, 1e6 * t / (double)tris);
    }
    printf("\n");
}

static int by_time_desc(const void *a, const void *b, size_t k)
{
    const fault_run *x = a, *y = b;
    return (x->t_mesh[k] < y->t_mesh[k]) - (x->t_mesh[k] > y->t_mesh[k]);
}

static size_t sort_k;
static int cmp_time(const void *a, const void *b)
{
    return by_time_desc(a, b, sort_k);
}

int main(int argc, char **argv)
{
    const char *dir = FM_CFM_DIR "/CFM5.3/500m";
    const char *match = NULL;
    int quiet = 0, every = 1, dir_given = 0;
    size_totals st[MAX_SIZES];
    size_t nsizes = 0;
    memset(st, 0, sizeof st);
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-s") == 0 && i + 1 < argc && nsizes < MAX_SIZES) {
            st[nsizes++].H = atof(argv[++i]);
            if (!(st[nsizes - 1].H > 0)) {
                fprintf(stderr, "bench_remesh: -s needs a positive size\n");
                return 2;
            }
        } else if (strcmp(argv[i], "-m") == 0 && i + 1 < argc)
            match = argv[++i];
        else if (strcmp(argv[i], "-e") == 0 && i + 1 < argc)
            every = atoi(argv[++i]);
        else if (strcmp(argv[i], "-q") == 0)
            quiet = 1;
        else if (argv[i][0] == '-') {
            fprintf(stderr, "usage: bench_remesh [-q] [-s H]... [-m SUBSTRING] [-e EVERY] [FOLDER]\n");
            return 2;
        } else {
            dir = argv[i];
            dir_given = 1;
        }
    }
    if (nsizes == 0) {
        st[0].H = 1000;
        st[1].H = 500;
        nsizes = 2;
    }
    char **paths;
    size_t n;
    if (bench_list_ts(dir, &paths, &n) != 0) {
        if (!dir_given) {
            printf("bench_remesh: skipped: no CFM at %s\n", dir);
            return 0;
        }
        fprintf(stderr, "bench_remesh: cannot open folder %s\n", dir);
        return 2;
    }
    fault_run *faults = calloc(n ? n : 1, sizeof *faults);
    totals tot;
    memset(&tot, 0, sizeof tot);
    size_t nf = 0;
    double t_start = fm_clock_seconds();
    for (size_t i = 0; i < n; i++) {
        if ((match && !strstr(paths[i], match)) || (every > 1 && i % (size_t)every != 0))
            continue;
        if (run_file(paths[i], &faults[nf], &tot, st, nsizes) != 0)
            return 2;
        if (!quiet) {
            printf("%-64s %7zu in", faults[nf].name, faults[nf].in_triangles);
            for (size_t k = 0; k < nsizes; k++)
                printf("  H %4.0f: %7zu tri %7.3f s%s", st[k].H, faults[nf].tris[k],
                       faults[nf].t_mesh[k], faults[nf].failed[k] ? " FAILED" : "");
            printf("\n");
        }
        nf++;
    }
    double wall = fm_clock_seconds() - t_start;
    double shared = tot.read + tot.repair + tot.fit;

    printf("\nfolder %s: %zu files, %zu objects, %zu input triangles\n", dir, nf, tot.objects,
           tot.in_triangles);
    printf("shared stages: read %.2f s, repair %.2f s, fit %.2f s (%zu fit failures)\n",
           tot.read, tot.repair, tot.fit, tot.fit_failed);
    printf("  CPU: read %.2f s, repair %.2f s, fit %.2f s\n", tot.cpu_read, tot.cpu_repair,
           tot.cpu_fit);
    size_t failed = 0;
    for (size_t k = 0; k < nsizes; k++) {
        size_totals *s = &st[k];
        failed += s->failed;
        size_t used;
        double slope = growth_slope(faults, nf, k, &used);
        printf("\nH = %.0f m, top cut: %zu meshed, %zu empty, %zu failed; %zu triangles, %zu nodes\n",
               s->H, s->meshed, s->empty, s->failed, s->tris, s->nodes);
        printf("  mesh %.2f s (%.0f triangles/s), check %.2f s; pipeline read + repair + fit + "
               "mesh + check %.2f s\n",
               s->mesh, s->mesh > 0 ? (double)s->tris / s->mesh : 0, s->check,
               shared + s->mesh + s->check);
        printf("  CPU: mesh %.2f s, check %.2f s; pipeline %.2f s\n", s->cpu_mesh, s->cpu_check,
               tot.cpu_read + tot.cpu_repair + tot.cpu_fit + s->cpu_mesh + s->cpu_check);
        printf("  quality: below 30 deg %.3f%%, edges in band %.2f%%, worst node distance %.1f m\n",
               s->tris ? 100.0 * (double)s->below30 / (double)s->tris : 0,
               s->edges ? 100.0 * (double)s->band / (double)s->edges : 0, s->worst_dist);
        printf("  mesh time ~ triangles^%.2f (least squares over %zu faults, log-log)\n", slope,
               used);
        size_classes(faults, nf, k);
        fault_run *sorted = malloc((nf ? nf : 1) * sizeof *sorted);
        memcpy(sorted, faults, nf * sizeof *sorted);
        sort_k = k;
        qsort(sorted, nf, sizeof *sorted, cmp_time);
        printf("  slowest:");
        for (size_t i = 0; i < nf && i < 5; i++)
            printf("%s %s (%zu tri, %.2f s)", i ? "," : "", sorted[i].name, sorted[i].tris[k],
                   sorted[i].t_mesh[k]);
        printf("\n");
        free(sorted);
    }
    printf("\nwall %.2f s (CPU %.2f s) for the whole run (shared stages once, %zu size%s), "
           "peak RSS %.0f MB\n",
           wall, bench_cpu_seconds(), nsizes, nsizes > 1 ? "s" : "", peak_rss_mb());
    for (size_t i = 0; i < nf; i++)
        free(faults[i].name);
    for (size_t i = 0; i < n; i++)
        free(paths[i]);
    free(paths);
    free(faults);
    return failed ? 1 : 0;
}
