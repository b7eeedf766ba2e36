/* CDT and Delaunay refinement (fm_cdt.h): triangles made per second.
 *
 *   bench_cdt [-n DIV] [-r REPEAT]    (defaults: 500, 3)
 *
 * Cases, each built from its boundary (fm_cdt_create) and refined
 * (fm_cdt_refine, min angle 30):
 *   square   the unit square at size 1/DIV, identity metric
 *   holes    the unit square with 16 square holes, size 1/DIV
 *   stretch  the unit square under E 1, F 0, G 9 at size 3/DIV (lengths in
 *            v three times those in u: a like number of triangles)
 *   varying  the unit square under a sheared, varying metric (a callback
 *            per evaluation, as a spline surface's would be)
 * Prints the best of REPEAT runs on the monotonic clock (one thread):
 * seconds, triangles, triangles per second, and the share of triangles
 * with smallest angle >= 30 degrees and of edges within [0.7, 1.4] size,
 * both in the metric. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_common.h"
#include "fm_cdt.h"

static void metric_stretch(void *user, const double uv[2], double m[3])
{
    (void)user;
    (void)uv;
    m[0] = 1, m[1] = 0, m[2] = 9;
}

static void metric_varying(void *user, const double uv[2], double m[3])
{
    (void)user;
    double s = 1.5 + 0.5 * sin(3 * uv[0]);
    m[0] = s * s, m[1] = 0.3 * s, m[2] = 1 + 0.5 * uv[1] * uv[1];
}

typedef struct bench_case {
    const char *name;
    fm_cdt_metric_fn metric;
    int holes;
    double size_factor;
} bench_case;

static void metric_at(fm_cdt_metric_fn f, const double *uv, double m[3])
{
    if (f)
        f(NULL, uv, m);
    else
        m[0] = 1, m[1] = 0, m[2] = 1;
}

static void quality(const fm_cdt *t, fm_cdt_metric_fn f, double size, double *angle_ok,
                    double *len_ok)
{
    const double *p = fm_cdt_points(t);
    const int32_t *tri = fm_cdt_triangles(t);
    size_t nt = fm_cdt_ntriangles(t), good = 0, lgood = 0;
    for (size_t k = 0; k < nt; k++) {
        const double *v[3] = {p + 2 * tri[3 * k], p + 2 * tri[3 * k + 1], p + 2 * tri[3 * k + 2]};
        double g[2] = {(v[0][0] + v[1][0] + v[2][0]) / 3, (v[0][1] + v[1][1] + v[2][1]) / 3}, m[3];
        metric_at(f, g, m);
        double l2[3];
        for (int i = 0; i < 3; i++) {
            double dx = v[(i + 2) % 3][0] - v[(i + 1) % 3][0];
            double dy = v[(i + 2) % 3][1] - v[(i + 1) % 3][1];
            l2[i] = m[0] * dx * dx + 2 * m[1] * dx * dy + m[2] * dy * dy;
            double l = sqrt(l2[i]);
            lgood += l >= 0.7 * size && l <= 1.4 * size;
        }
        double cmax = -1;
        for (int i = 0; i < 3; i++) {
            double lj = l2[(i + 1) % 3], lk = l2[(i + 2) % 3];
            double c = (lj + lk - l2[i]) / (2 * sqrt(lj * lk));
            if (c > cmax)
                cmax = c;
        }
        good += cmax <= cos(30 * 3.14159265358979323846 / 180) + 1e-12;
    }
    *angle_ok = nt ? (double)good / (double)nt : 0;
    *len_ok = nt ? (double)lgood / (3.0 * (double)nt) : 0;
}

int main(int argc, char **argv)
{
    int div = 500, repeat = 3;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "-n"))
            div = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "-r"))
            repeat = atoi(argv[i + 1]);
    }
    if (div < 2 || repeat < 1) {
        fprintf(stderr, "usage: bench_cdt [-n DIV] [-r REPEAT]\n");
        return 2;
    }
    const bench_case cases[] = {{"square", NULL, 0, 1},
                                {"holes", NULL, 1, 1},
                                {"stretch", metric_stretch, 0, 3},
                                {"varying", metric_varying, 0, 1.5}};
    double uv[2 * (4 + 16 * 4)];
    int32_t seg[2 * (4 + 16 * 4)];
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        const bench_case *bc = &cases[c];
        size_t np = 0;
        double sq[] = {0, 0, 1, 0, 1, 1, 0, 1};
        for (int i = 0; i < 4; i++) {
            uv[2 * np] = sq[2 * i], uv[2 * np + 1] = sq[2 * i + 1];
            seg[2 * np] = (int32_t)np, seg[2 * np + 1] = (int32_t)(i == 3 ? 0 : np + 1);
            np++;
        }
        if (bc->holes)
            for (int h = 0; h < 16; h++) {
                double x0 = 0.1 + 0.22 * (h % 4), y0 = 0.1 + 0.22 * (h / 4), w = 0.08;
                double hp[] = {x0, y0, x0, y0 + w, x0 + w, y0 + w, x0 + w, y0};
                size_t base = np;
                for (int i = 0; i < 4; i++) {
                    uv[2 * np] = hp[2 * i], uv[2 * np + 1] = hp[2 * i + 1];
                    seg[2 * np] = (int32_t)np;
                    seg[2 * np + 1] = (int32_t)(i == 3 ? base : np + 1);
                    np++;
                }
            }
        double best = 1e300, size = bc->size_factor / div, aok = 0, lok = 0;
        size_t nt = 0;
        for (int r = 0; r < repeat; r++) {
            fm_cdt *t = NULL;
            fm_error err;
            double t0 = fm_clock_seconds();
            fm_status st = fm_cdt_create(uv, np, seg, NULL, np, &t, &err);
            fm_cdt_refine_options o;
            fm_cdt_refine_options_default(&o);
            o.size = size;
            o.metric = bc->metric;
            if (st == FM_OK)
                st = fm_cdt_refine(t, &o, &err);
            double dt = fm_clock_seconds() - t0;
            if (st != FM_OK) {
                fprintf(stderr, "%s: %s\n", bc->name, err.message);
                fm_cdt_destroy(t);
                return 1;
            }
            if (dt < best)
                best = dt;
            nt = fm_cdt_ntriangles(t);
            if (r == 0)
                quality(t, bc->metric, size, &aok, &lok);
            fm_cdt_destroy(t);
        }
        printf("%-8s size %-10.4g %9zu triangles %7.3f s %9.0f triangles/s  angle>=30 %.4f  "
               "edges in [0.7,1.4] %.4f\n",
               bc->name, size, nt, best, (double)nt / best, aok, lok);
    }
    return 0;
}
