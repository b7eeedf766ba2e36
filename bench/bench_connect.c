/* Neighbours and intersection curves over a whole fault set.
 *
 *   bench_connect [-m SUBSTRING] [FOLDER]   (default: the CFM 500 m set)
 *
 * Fits every fault (repair + model, timed on its own: it dominates), then
 * finds the pairs at D = 1000 and 2000 m and computes the intersection
 * curves of every pair found at 1000 m; lists the near-duplicate fault
 * pairs (fm_connect_find_duplicates, defaults); prints counts, accuracy and
 * times: wall clock, and CPU seconds of the whole process (all threads),
 * which a shared machine disturbs less. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "fm_connect.h"
#include "fm_model.h"
#include "fm_repair.h"
#include "fm_tsurf.h"

static const char *base_name(const char *path)
{
    const char *s = strrchr(path, '/');
    return s ? s + 1 : path;
}

int main(int argc, char **argv)
{
    const char *dir = FM_CFM_DIR "/CFM5.3/500m", *match = NULL;
    setvbuf(stdout, NULL, _IOLBF, 0);
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-m") && i + 1 < argc)
            match = argv[++i];
        else
            dir = argv[i];
    }
    char **paths = NULL;
    size_t np = 0;
    if (bench_list_ts(dir, &paths, &np) != 0 || np == 0) {
        fprintf(stderr, "bench_connect: no .ts files in %s\n", dir);
        return 77;
    }
    fm_model **models = calloc(np, sizeof *models);
    const char **names = calloc(np, sizeof *names); /* per model: its file */
    if (!models || !names)
        return 1;
    size_t nm = 0, failed = 0, sheets = 0;
    double t0 = fm_clock_seconds();
    for (size_t i = 0; i < np; i++) {
        if (match && !strstr(paths[i], match))
            continue;
        fm_tsurf **objs = NULL;
        size_t nobj = 0;
        fm_error err;
        if (fm_tsurf_read_file(paths[i], &objs, &nobj, &err) != FM_OK || nobj < 1) {
            failed++;
            continue;
        }
        fm_surface *s = NULL;
        fm_model *m = NULL;
        if (fm_repair(fm_tsurf_mesh(objs[0]), NULL, &s, &err) == FM_OK &&
            fm_model_build(paths[i], s, NULL, &m, &err) == FM_OK) {
            names[nm] = paths[i];
            models[nm++] = m;
            sheets += fm_model_nsheets(m);
        } else {
            failed++;
        }
        fm_surface_destroy(s);
        fm_tsurf_free_all(objs, nobj);
    }
    double t1 = fm_clock_seconds();
    printf("fit: %zu faults (%zu sheets), %zu failed, %.1f s, %.1f s CPU\n", nm, sheets, failed,
           t1 - t0, bench_cpu_seconds());

    fm_connect_pairs *keep = NULL;
    for (int pass = 0; pass < 2; pass++) {
        fm_connect_options o;
        fm_connect_options_default(&o);
        o.distance = pass ? 2000.0 : 1000.0;
        fm_connect_pairs *pairs = NULL;
        fm_error err;
        double a = fm_clock_seconds(), ca = bench_cpu_seconds();
        if (fm_connect_find_pairs((const fm_model *const *)models, nm, &o, &pairs, &err) != FM_OK) {
            fprintf(stderr, "%s\n", err.message);
            return 1;
        }
        double b = fm_clock_seconds(), cb = bench_cpu_seconds();
        size_t n = fm_connect_pairs_count(pairs), cross = 0, tcross = 0, tnear = 0, fpairs = 0;
        size_t last_a = (size_t)-1, last_b = (size_t)-1;
        for (size_t i = 0; i < n; i++) {
            const fm_connect_pair *p = fm_connect_pairs_get(pairs, i);
            cross += (size_t)p->crosses;
            tcross += (size_t)p->trimmed_crosses;
            tnear += !p->trimmed_crosses && p->trimmed_distance <= o.distance;
            if (p->fault_a != last_a || p->fault_b != last_b)
                fpairs++;
            last_a = p->fault_a;
            last_b = p->fault_b;
        }
        const fm_connect_pairs_stats *st = fm_connect_pairs_get_stats(pairs);
        printf("pairs D = %.0f (reach = D): %zu sheet pairs (%zu fault pairs); grown surfaces "
               "cross %zu; trimmed cross %zu, trimmed within D %zu; candidates %zu, meshed %zu, "
               "cells %zu; %.2f s (sample %.2f, measure %.2f), %.2f s CPU\n",
               o.distance, n, fpairs, cross, tcross, tnear, st->candidates, st->measured, st->cells,
               b - a, st->time_sample, st->time_measure, cb - ca);
        if (pass == 0)
            keep = pairs;
        else
            fm_connect_pairs_destroy(pairs);
    }

    {
        double a = fm_clock_seconds(), ca = bench_cpu_seconds();
        fm_connect_duplicate *d = NULL;
        size_t nd = 0;
        fm_error err;
        if (fm_connect_find_duplicates((const fm_model *const *)models, nm, keep, NULL, &d, &nd,
                                       &err) != FM_OK) {
            fprintf(stderr, "%s\n", err.message);
            return 1;
        }
        size_t decided = 0;
        for (size_t k = 0; k < nd; k++) {
            decided += (size_t)d[k].decided;
            printf("  duplicate%s: %s (%.0f%% of %.0f km2) ~ %s (%.0f%% of %.0f km2)\n",
                   d[k].decided ? "" : " (already decided)", base_name(names[d[k].dropped]),
                   100 * d[k].share[0], d[k].area[0] / 1e6, base_name(names[d[k].kept]),
                   100 * d[k].share[1], d[k].area[1] / 1e6);
        }
        printf("duplicates (50 m, share >= 50%%, keep the smaller): %zu pairs, %zu faults given "
               "up; %.2f s, %.2f s CPU\n",
               nd, decided, fm_clock_seconds() - a, bench_cpu_seconds() - ca);
        free(d);
    }

    double a = fm_clock_seconds(), ca = bench_cpu_seconds();
    size_t ncurves = 0, npoints = 0, fallback = 0, unconverged = 0, closed = 0, with_curve = 0;
    size_t gaps = 0, overshoots = 0;
    double maxd = 0, minang = 90, length = 0;
    for (size_t i = 0; i < fm_connect_pairs_count(keep); i++) {
        const fm_connect_pair *p = fm_connect_pairs_get(keep, i);
        fm_connect_curves *c = NULL;
        fm_error err;
        if (fm_connect_intersect(models[p->fault_a], p->sheet_a, models[p->fault_b], p->sheet_b,
                                 NULL, &c, &err) != FM_OK) {
            fprintf(stderr, "%s\n", err.message);
            continue;
        }
        size_t k = fm_connect_curves_count(c);
        with_curve += k > 0;
        for (size_t j = 0; j < k; j++) {
            const fm_connect_curve_info *in = fm_connect_curve_get_info(c, j);
            ncurves++;
            npoints += in->npoints;
            fallback += in->fallback_points;
            unconverged += in->unconverged;
            closed += (size_t)in->closed;
            length += in->length;
            maxd = fmax(maxd, fmax(in->max_dist[0], in->max_dist[1]));
            minang = fmin(minang, in->min_angle);
            for (int s = 0; s < 2; s++) {
                gaps += in->side[s].role == FM_CONNECT_GAP;
                overshoots += in->side[s].role == FM_CONNECT_OVERSHOOT;
            }
        }
        fm_connect_curves_destroy(c);
    }
    double b = fm_clock_seconds(), cb = bench_cpu_seconds();
    printf("curves (D = 1000): %zu pairs with curves, %zu curves (%zu closed), %zu points, "
           "%.0f km; sides: %zu gap, %zu overshoot; max |S - xyz| %.2e m; smallest angle %.2f "
           "deg; fallback %zu, unconverged %zu; %.2f s, %.2f s CPU\n",
           with_curve, ncurves, closed, npoints, length / 1000, gaps, overshoots, maxd, minang,
           fallback, unconverged, b - a, cb - ca);
    fm_connect_pairs_destroy(keep);
    {
        fm_connect_plan_options po;
        fm_connect_plan_options_default(&po);
        po.nthreads = 2;
        fm_connect_plan *plan = NULL;
        fm_error err;
        double pa = fm_clock_seconds(), cpa = bench_cpu_seconds();
        if (fm_connect_plan_build((const fm_model *const *)models, nm, &po, &plan, &err) != FM_OK) {
            fprintf(stderr, "%s\n", err.message);
            return 1;
        }
        double pb = fm_clock_seconds(), cpb = bench_cpu_seconds();
        const fm_connect_plan_stats *ps = fm_connect_plan_get_stats(plan);
        printf("plan (D = 1000, H = 1000, cut, 2 threads): %zu pairs; crossing %zu, T %zu, corner "
               "%zu, unjoined %zu; %zu shared nodes; %.1f s (pairs + duplicates %.1f, curves "
               "%.1f), %.1f s CPU\n",
               ps->pairs, ps->junctions[0], ps->junctions[1], ps->junctions[2], ps->junctions[3],
               fm_connect_plan_nnodes(plan), pb - pa, ps->time_pairs, ps->time_curves, cpb - cpa);
        /* unjoined reasons, counted */
        const char *reasons[16];
        size_t counts[16], nr = 0;
        for (size_t i = 0; i < fm_connect_plan_njunctions(plan); i++) {
            const fm_connect_junction *j = fm_connect_plan_junction(plan, i);
            if (match)
                printf("  %-9s %s / %s  gap %.0f overshoot %.0f length %.0f angle %.1f%s%s\n",
                       fm_junction_type_name(j->type), base_name(names[j->fault[0]]),
                       base_name(names[j->fault[1]]), j->gap, j->overshoot, j->length,
                       j->min_angle, j->reason ? ": " : "", j->reason ? j->reason : "");
            if (!j->reason)
                continue;
            size_t r = 0;
            while (r < nr && strcmp(reasons[r], j->reason))
                r++;
            if (r == nr && nr < 16) {
                reasons[nr] = j->reason;
                counts[nr++] = 0;
            }
            if (r < nr)
                counts[r]++;
        }
        for (size_t r = 0; r < nr; r++)
            printf("  unjoined %zu: %s\n", counts[r], reasons[r]);
        fm_connect_plan_destroy(plan);
    }
    for (size_t i = 0; i < nm; i++)
        fm_model_destroy(models[i]);
    free(models);
    free(names);
    for (size_t i = 0; i < np; i++)
        free(paths[i]);
    free(paths);
    return 0;
}
