/* The fit stage on real CFM 5.3 faults at 500 m: a few named files through
 * repair and fit with default options, against the acceptance criteria per
 * fault (vertex RMS <= 10 m, max <= 100 m over all its sheets), including
 * sheets no plane sees one-to-one (the parametric fallback; the conformal
 * map of the Puente Hills and Santa Monica thrusts laps over itself, so
 * they take the convex-boundary map). Skips (77) without the CFM. */
#include "fm_fit.h"
#include "fm_repair.h"
#include "fm_test.h"
#include "fm_tsurf.h"

#include <unistd.h>

#define DIR500 FM_CFM_DIR "/CFM5.3/500m/"

typedef struct named {
    const char *file;
    int parametric; /* 1: some sheet must take the fallback; 2: the convex map */
    size_t flips;   /* reversed triangles tolerated in the parameters (known defect) */
} named;

static const named FAULTS[] = {
    {"WTRA-SSFZ-MULT-Santa_Susana_fault-CFM5_500m.ts", 0, 0},
    {"GRFS-GRFZ-WEST-Garlock_fault-CFM5_500m.ts", 0, 0},
    {"OCBA-IBFS-SCTI-Catalina_Island_detachment_upper_alt1-CFM5_500m.ts", 1, 0},
    {"SNFA-LLFZ-EAST-Eastern_Little_Lake_south_west_branch-CFM5_500m.ts", 1, 0},
    /* A folded triangle beside a four-vertex hole: 3 triangles there stay
     * reversed even in the convex map (open issue). */
    {"OCBA-OCSD-OCNS-Oceanside_fault_north-CFM5_500m.ts", 1, 3},
    {"WTRA-PHTS-COYT-Puente_Hills_Thrust_fault-CFM2_500m.ts", 2, 0},
    {"WTRA-SBTS-SMNB-Santa_Monica_thrust_fault-CFM1_500m.ts", 2, 0},
};

static void run(const named *nf)
{
    char path[1024];
    snprintf(path, sizeof path, "%s%s", DIR500, nf->file);
    fm_tsurf **objs = NULL;
    size_t nobj = 0;
    fm_error err;
    fm_status st = fm_tsurf_read_file(path, &objs, &nobj, &err);
    CHECK(st == FM_OK);
    if (st != FM_OK) {
        fprintf(stderr, "%s\n", err.message);
        return;
    }
    double sum2 = 0, max = 0;
    size_t nv = 0, param = 0, convex = 0, sheets = 0;
    for (size_t o = 0; o < nobj; o++) {
        fm_surface *surf = NULL;
        CHECK(fm_repair(fm_tsurf_mesh(objs[o]), NULL, &surf, &err) == FM_OK);
        for (size_t k = 0; surf && k < fm_surface_nsheets(surf); k++, sheets++) {
            const fm_mesh *sheet = fm_surface_sheet_mesh(surf, k);
            fm_fit_surface *fs = NULL;
            st = fm_fit_sheet(sheet, NULL, &fs, &err);
            CHECK(st == FM_OK);
            if (st != FM_OK) {
                fprintf(stderr, "%s\n", err.message);
                continue;
            }
            const fm_fit_stats *s = fm_fit_surface_stats(fs);
            sum2 += s->rms_dist * s->rms_dist * (double)s->vertices;
            nv += s->vertices;
            max = fmax(max, s->max_dist);
            CHECK_EQ(s->projection_failures, 0);
            if (fm_fit_surface_kind(fs) == FM_FIT_PARAMETRIC) {
                param++;
                convex += (size_t)s->convex_map;
                /* The trimming curves need one-to-one boundary parameters:
                 * no triangle of the sheet reversed. */
                size_t n = fm_mesh_nvertices(sheet), bad = 0;
                double *uv = malloc(2 * n * sizeof *uv);
                CHECK(fm_fit_sheet_vertex_params(fs, sheet, uv, &err) == FM_OK);
                const int32_t *T = fm_mesh_triangles(sheet);
                for (size_t t = 0; t < fm_mesh_ntriangles(sheet); t++) {
                    const double *a = uv + 2 * T[3 * t], *b = uv + 2 * T[3 * t + 1];
                    const double *c = uv + 2 * T[3 * t + 2];
                    if (!((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]) > 0))
                        bad++;
                }
                /* LSCM is one-to-one in practice (checked); the convex
                 * map by construction. */
                CHECK(bad <= nf->flips);
                free(uv);
            }
            fm_fit_surface_destroy(fs);
        }
        fm_surface_destroy(surf);
    }
    fm_tsurf_free_all(objs, nobj);
    double rms = nv ? sqrt(sum2 / (double)nv) : 0;
    printf("%-66s %zu sheets (%zu parametric, %zu convex map): rms %.2f m, max %.1f m\n",
           nf->file, sheets, param, convex, rms, max);
    CHECK(rms <= 10.0);
    CHECK(max <= 100.0);
    if (nf->parametric)
        CHECK(param > 0);
    if (nf->parametric == 2)
        CHECK(convex > 0);
}

int main(void)
{
    if (access(DIR500 "GRFS-GRFZ-WEST-Garlock_fault-CFM5_500m.ts", R_OK) != 0) {
        printf("skipped: no CFM at %s\n", DIR500);
        return FM_TEST_SKIP;
    }
    for (size_t i = 0; i < sizeof FAULTS / sizeof FAULTS[0]; i++)
        run(&FAULTS[i]);
    printf("%s\n", fm_test_failed_checks ? "FAILED" : "passed");
    return fm_test_failed_checks ? 1 : 0;
}
