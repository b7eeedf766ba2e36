/* Fit fidelity and speed on a folder of .ts files: the measuring tool of
 * the fit stage's acceptance criteria.
 *
 *   bench_fit [-q] [-s] [-m SUBSTRING] [-e EVERY] [FOLDER]  (default: the CFM 500 m set)
 *
 * -m keeps the files whose path contains SUBSTRING, -e every EVERY-th file;
 * -k, -b, -r, -t, -x, -K set the fit options knot_factor,
 * smoothing_wavelength, max_refinements, target_rms, target_max and kind
 * (0 auto, 1 height field, 2 parametric) for experiments; the acceptance
 * figures are those with none of them.
 *
 * Every file is read, repaired (fm_repair defaults, each TSurf object on
 * its own) and every sheet fitted with fm_fit defaults. A fault is a file;
 * its RMS and max are over the vertices of all its sheets (the distance of
 * each vertex to its sheet's surface). Prints one line per fault (-q: only
 * the outliers), with -s one line per sheet, then the distribution, the
 * outliers and failures with their sheets, the sheets that needed the
 * parametric fallback, the time per stage, and last
 *     faults N, within 10/100 m: K (P%), median RMS X m, failures F
 * Exit status 1 if any sheet failed to fit, 2 on bad usage or unreadable
 * input. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_common.h"
#include "fm_fit.h"
#include "fm_repair.h"
#include "fm_tsurf.h"

#define RMS_LIMIT 10.0
#define MAX_LIMIT 100.0

typedef struct fault {
    char *name;
    size_t sheets, vertices, triangles, failed, parametric;
    double sum2, max, rms, time;
    /* The sheet with the largest error, to say why a fault is an outlier. */
    size_t worst_sheet, worst_tris;
    double worst_rms, worst_max, worst_min_dot, worst_dip, worst_spacing;
    int worst_kind, worst_passes;
} fault;

static int by_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

typedef struct totals {
    double read, repair, frame, param, assemble, solve, stats, fit;
    size_t sheets, nonprojectable, parametric, passes_hist[8];
} totals;

static void print_fault(const fault *f)
{
    printf("%-64s %3zu sh %6zu v  rms %7.2f  max %7.1f  %6.3f s%s%s\n", f->name, f->sheets,
           f->vertices, f->rms, f->max, f->time, f->parametric ? "  [parametric]" : "",
           f->failed ? "  FAILED" : "");
}

static void print_worst(const fault *f)
{
    printf("    worst sheet %zu: %zu tri, %s, passes %d, spacing %.0f m, min n.w %.3f, dip %.1f, "
           "rms %.2f max %.1f\n",
           f->worst_sheet, f->worst_tris, f->worst_kind == FM_FIT_PARAMETRIC ? "parametric" : "height", f->worst_passes,
           f->worst_spacing, f->worst_min_dot, f->worst_dip, f->worst_rms, f->worst_max);
}

/* Reads, repairs and fits one file into *f; returns 0, or -1 when the file
 * cannot be read or repaired (a fit failure is counted, not an error). */
static int run_file(const char *path, fault *f, totals *tot, int per_sheet,
                    const fm_fit_options *base_opt)
{
    fm_tsurf **objs = NULL;
    size_t nobj = 0;
    fm_error err;
    double t0 = fm_clock_seconds();
    if (fm_tsurf_read_file(path, &objs, &nobj, &err) != FM_OK) {
        fprintf(stderr, "bench_fit: %s\n", err.message);
        return -1;
    }
    double t1 = fm_clock_seconds();
    tot->read += t1 - t0;
    const char *base = strrchr(path, '/');
    f->name = strdup(base ? base + 1 : path);
    size_t sheet_no = 0;
    for (size_t o = 0; o < nobj; o++) {
        double ta = fm_clock_seconds();
        fm_surface *surf = NULL;
        if (fm_repair(fm_tsurf_mesh(objs[o]), NULL, &surf, &err) != FM_OK) {
            fprintf(stderr, "bench_fit: %s: repair: %s\n", path, err.message);
            fm_tsurf_free_all(objs, nobj);
            return -1;
        }
        tot->repair += fm_clock_seconds() - ta;
        for (size_t k = 0; k < fm_surface_nsheets(surf); k++, sheet_no++) {
            const fm_mesh *sheet = fm_surface_sheet_mesh(surf, k);
            fm_fit_options opt = *base_opt;
            opt.name = f->name;
            fm_fit_surface *fs = NULL;
            double tb = fm_clock_seconds();
            fm_status st = fm_fit_sheet(sheet, &opt, &fs, &err);
            double dt = fm_clock_seconds() - tb;
            tot->fit += dt;
            f->time += dt;
            f->sheets++;
            tot->sheets++;
            f->triangles += fm_mesh_ntriangles(sheet);
            if (st != FM_OK) {
                fprintf(stderr, "bench_fit: sheet %zu (%zu triangles): %s\n", sheet_no,
                        fm_mesh_ntriangles(sheet), err.message);
                f->failed++;
                continue;
            }
            const fm_fit_stats *s = fm_fit_surface_stats(fs);
            const fm_fit_frame *fr = fm_fit_surface_frame(fs);
            int kind = (int)fm_fit_surface_kind(fs);
            tot->frame += s->time_frame;
            tot->param += s->time_param;
            tot->assemble += s->time_assemble;
            tot->solve += s->time_solve;
            tot->stats += s->time_stats;
            if (!fr->projectable || s->overlap > 0)
                tot->nonprojectable++;
            if (kind == FM_FIT_PARAMETRIC) {
                tot->parametric++;
                f->parametric++;
            }
            tot->passes_hist[s->passes < 7 ? s->passes : 7]++;
            f->vertices += s->vertices;
            f->sum2 += s->rms_dist * s->rms_dist * (double)s->vertices;
            if (s->max_dist > f->max)
                f->max = s->max_dist;
            if (per_sheet)
                printf("  %-40.40s sheet %3zu %6zu tri %s min_dot %6.3f overlap %.3f dip %5.1f "
                       "flipped %zu convex %d passes %d s %5.0f m grid %zux%zu  rms %7.2f max %7.1f  %.3f s\n",
                       f->name, sheet_no, s->triangles, kind == FM_FIT_PARAMETRIC ? "param " : "height", fr->min_dot,
                       s->overlap, fr->dip_degrees, s->lscm_flipped, s->convex_map, s->passes, s->knot_spacing, s->control_u,
                       s->control_v, s->rms_dist, s->max_dist, s->time_total);
            if (s->max_dist >= f->worst_max) {
                f->worst_sheet = sheet_no;
                f->worst_tris = s->triangles;
                f->worst_rms = s->rms_dist;
                f->worst_max = s->max_dist;
                f->worst_min_dot = fr->min_dot;
                f->worst_dip = fr->dip_degrees;
                f->worst_spacing = s->knot_spacing;
                f->worst_kind = kind;
                f->worst_passes = s->passes;
            }
            fm_fit_surface_destroy(fs);
        }
        fm_surface_destroy(surf);
    }
    fm_tsurf_free_all(objs, nobj);
    f->rms = f->vertices ? sqrt(f->sum2 / (double)f->vertices) : 0;
    return 0;
}

int main(int argc, char **argv)
{
    const char *dir = FM_CFM_DIR "/CFM5.3/500m";
    const char *match = NULL;
    int quiet = 0, per_sheet = 0, every = 1;
    fm_fit_options opt;
    fm_fit_options_default(&opt);
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-k") == 0 && i + 1 < argc)
            opt.knot_factor = atof(argv[++i]);
        else if (strcmp(argv[i], "-b") == 0 && i + 1 < argc)
            opt.smoothing_wavelength = atof(argv[++i]);
        else if (strcmp(argv[i], "-r") == 0 && i + 1 < argc)
            opt.max_refinements = atoi(argv[++i]);
        else if (strcmp(argv[i], "-t") == 0 && i + 1 < argc)
            opt.target_rms = atof(argv[++i]);
        else if (strcmp(argv[i], "-x") == 0 && i + 1 < argc)
            opt.target_max = atof(argv[++i]);
        else if (strcmp(argv[i], "-K") == 0 && i + 1 < argc)
            opt.kind = (fm_fit_kind)atoi(argv[++i]);
        else if (strcmp(argv[i], "-e") == 0 && i + 1 < argc)
            every = atoi(argv[++i]);
        else if (strcmp(argv[i], "-q") == 0)
            quiet = 1;
        else if (strcmp(argv[i], "-s") == 0)
            per_sheet = 1;
        else if (strcmp(argv[i], "-m") == 0 && i + 1 < argc)
            match = argv[++i];
        else if (argv[i][0] == '-') {
            fprintf(stderr, "usage: bench_fit [-q] [-s] [-m SUBSTRING] [-e EVERY] [-k KNOT_FACTOR] "
                            "[-b BETA] [-r REFINEMENTS] [-t TARGET_RMS] [-x TARGET_MAX] "
                            "[-K KIND] [FOLDER]\n");
            return 2;
        } else
            dir = argv[i];
    }
    char **paths;
    size_t n;
    if (bench_list_ts(dir, &paths, &n) != 0) {
        fprintf(stderr, "bench_fit: cannot open folder %s\n", dir);
        return 2;
    }
    fault *faults = calloc(n ? n : 1, sizeof *faults);
    totals tot;
    memset(&tot, 0, sizeof tot);
    size_t nf = 0, failures = 0;
    double t_start = fm_clock_seconds();
    for (size_t i = 0; i < n; i++) {
        if ((match && !strstr(paths[i], match)) || (every > 1 && i % (size_t)every != 0))
            continue;
        if (run_file(paths[i], &faults[nf], &tot, per_sheet, &opt) != 0) {
            free(faults[nf].name);
            return 2;
        }
        if (!quiet)
            print_fault(&faults[nf]);
        failures += faults[nf].failed;
        nf++;
    }
    double t_all = fm_clock_seconds() - t_start;

    size_t within = 0;
    double *rms = malloc((nf ? nf : 1) * sizeof *rms), *mx = malloc((nf ? nf : 1) * sizeof *mx);
    for (size_t i = 0; i < nf; i++) {
        rms[i] = faults[i].rms;
        mx[i] = faults[i].max;
        if (!faults[i].failed && faults[i].rms <= RMS_LIMIT && faults[i].max <= MAX_LIMIT)
            within++;
    }
    qsort(rms, nf, sizeof *rms, by_double);
    qsort(mx, nf, sizeof *mx, by_double);
    double median = nf ? (nf % 2 ? rms[nf / 2] : 0.5 * (rms[nf / 2 - 1] + rms[nf / 2])) : 0;
    double median_max = nf ? (nf % 2 ? mx[nf / 2] : 0.5 * (mx[nf / 2 - 1] + mx[nf / 2])) : 0;

    printf("\noutliers (rms > %.0f m or max > %.0f m) and failures:\n", RMS_LIMIT, MAX_LIMIT);
    for (size_t i = 0; i < nf; i++)
        if (faults[i].failed || faults[i].rms > RMS_LIMIT || faults[i].max > MAX_LIMIT) {
            print_fault(&faults[i]);
            print_worst(&faults[i]);
        }
    printf("\nfaults with parametric (fallback) sheets:\n");
    for (size_t i = 0; i < nf; i++)
        if (faults[i].parametric) {
            print_fault(&faults[i]);
            print_worst(&faults[i]);
        }
    printf("\nper-fault rms: p10 %.2f  p50 %.2f  p90 %.2f  p98 %.2f  max %.2f m\n",
           nf ? rms[nf / 10] : 0, median, nf ? rms[nf * 9 / 10] : 0, nf ? rms[nf * 98 / 100] : 0,
           nf ? rms[nf - 1] : 0);
    printf("per-fault max: p10 %.1f  p50 %.1f  p90 %.1f  p98 %.1f  max %.1f m\n",
           nf ? mx[nf / 10] : 0, median_max, nf ? mx[nf * 9 / 10] : 0, nf ? mx[nf * 98 / 100] : 0,
           nf ? mx[nf - 1] : 0);
    printf("sheets %zu: not projectable as a height field %zu, parametric fits %zu\n", tot.sheets,
           tot.nonprojectable, tot.parametric);
    printf("refinement passes per sheet:");
    for (int k = 0; k < 8; k++)
        if (tot.passes_hist[k])
            printf("  %d%s: %zu", k, k == 7 ? "+" : "", tot.passes_hist[k]);
    printf("\ntime %.2f s: read %.2f, repair %.2f, fit %.2f (frame %.2f, parameterization %.2f, "
           "assemble %.2f, solve %.2f, stats %.2f)\n",
           t_all, tot.read, tot.repair, tot.fit, tot.frame, tot.param, tot.assemble, tot.solve,
           tot.stats);
    printf("faults %zu, within %.0f/%.0f m: %zu (%.1f%%), median RMS %.2f m, failures %zu\n", nf,
           RMS_LIMIT, MAX_LIMIT, within, nf ? 100.0 * (double)within / (double)nf : 0.0, median,
           failures);
    for (size_t i = 0; i < nf; i++)
        free(faults[i].name);
    for (size_t i = 0; i < n; i++)
        free(paths[i]);
    free(paths);
    free(faults);
    free(rms);
    free(mx);
    return failures ? 1 : 0;
}
