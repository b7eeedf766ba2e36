/* The surface mesher on the CFM 5.3 faults (500 m set) that once kept
 * triangles under 20 degrees away from sharp outline corners, remeshed as
 * `faultmesh remesh` does (repair, fm_remesh_model_options_default, top
 * cut) at 1 km and 500 m: now none may.
 *  - Coronado Bank north: a piece of 11 triangles cut off its ring, whose
 *    map nearly folds (4 at 1 km: the refinement chased the fold);
 *  - Rose Canyon: a despiked slit left two outline corners 3 m apart
 *    (2.7 degrees at 1 km, 9.8 at 500 m);
 *  - Big Pine east, West Huasna: thin wedges where the outline meets sea
 *    level at a shallow angle (18.4 and 19.9 degrees at 500 m).
 * Skips (77) without the CFM. */
#include "fm_check.h"
#include "fm_model.h"
#include "fm_remesh.h"
#include "fm_repair.h"
#include "fm_test.h"
#include "fm_tsurf.h"

#include <unistd.h>

#define DIR500 FM_CFM_DIR "/CFM5.3/500m/"

static const char *const FAULTS[] = {
    "OCBA-CBFZ-NCBF-Coronado_Bank_fault_north-CFM5_500m.ts",
    "OCBA-NIRC-RSCN-Rose_Canyon_fault-CFM5_500m.ts",
    "CRFA-BPPM-EAST-Big_Pine_fault-CFM4_500m.ts",
    "CRFA-OCNZ-HSNV-West_Huasna_fault-CFM5_500m.ts",
};

static void run(const char *file)
{
    char path[1024];
    snprintf(path, sizeof path, "%s%s", DIR500, file);
    fm_tsurf **objs = NULL;
    size_t nobj = 0;
    fm_error err;
    fm_status st = fm_tsurf_read_file(path, &objs, &nobj, &err);
    CHECK(st == FM_OK);
    if (st != FM_OK) {
        fprintf(stderr, "%s\n", err.message);
        return;
    }
    fm_surface *surf = NULL;
    fm_model *model = NULL;
    fm_model_options mo;
    fm_remesh_model_options_default(&mo);
    st = fm_repair(fm_tsurf_mesh(objs[0]), NULL, &surf, &err);
    if (st == FM_OK)
        st = fm_model_build(path, surf, &mo, &model, &err);
    CHECK(st == FM_OK);
    if (st != FM_OK)
        fprintf(stderr, "%s\n", err.message);
    for (int k = 0; model && k < 2; k++) {
        fm_remesh_options opt;
        fm_remesh_options_default(&opt);
        opt.name = path;
        opt.size = k ? 500 : 1000;
        fm_mesh *m = NULL;
        fm_remesh_stats rs;
        st = fm_remesh_model(model, &opt, &m, &rs, &err);
        CHECK(st == FM_OK);
        if (st != FM_OK) {
            fprintf(stderr, "%s\n", err.message);
            continue;
        }
        fm_quality q;
        CHECK_EQ(fm_check_quality(m, -1, opt.size, &q), FM_OK);
        printf("%-56s H %4.0f: %5zu triangles, min angle %4.1f deg, under 30: %zu, under 20: "
               "%zu (%zu at sharp corners)\n",
               file, opt.size, q.triangles, q.angle_min, q.below_30, q.below_20, q.below_20_forced);
        CHECK_EQ(q.below_20, q.below_20_forced);
        fm_mesh_destroy(m);
    }
    fm_model_destroy(model);
    fm_surface_destroy(surf);
    fm_tsurf_free_all(objs, nobj);
}

int main(void)
{
    if (access(DIR500 "OCBA-NIRC-RSCN-Rose_Canyon_fault-CFM5_500m.ts", R_OK) != 0) {
        printf("skipped: no CFM at %s\n", DIR500);
        return FM_TEST_SKIP;
    }
    for (size_t i = 0; i < sizeof FAULTS / sizeof FAULTS[0]; i++)
        run(FAULTS[i]);
    printf("%s\n", fm_test_failed_checks ? "FAILED" : "passed");
    return fm_test_failed_checks ? 1 : 0;
}
