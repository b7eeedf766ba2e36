/* Remeshes two faults with libfaultmesh and prints the nodes they share:
 * where two faults meet, their meshes are joined, so the nodes along the
 * junction belong to both.
 *
 *   shared_nodes [--size M] [A.ts B.ts]
 *
 * Without files: two faults of the SCEC CFM 5.3 (500 m set) that meet,
 * read from ../shared/cfm as seen from the repository's root.
 *
 * Build against an installed faultmesh:
 *   cc -std=c17 shared_nodes.c $(pkg-config --cflags --libs faultmesh)
 * or in CMake: find_package(faultmesh) and faultmesh::faultmesh. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <faultmesh/faultmesh.h>

#define CFM "../shared/cfm/CFM5.3/500m/"

static void say(void *user, fm_log_level level, const char *message)
{
    (void)user;
    if (level <= FM_LOG_WARN)
        fprintf(stderr, "faultmesh: %s\n", message);
}

int main(int argc, char **argv)
{
    const char *paths[2] = {CFM "OCBA-CBFZ-NCBF-Coronado_Bank_fault_north-CFM5_500m.ts",
                            CFM "OCBA-CBFZ-WEST-Coronado_Bank_west_splay-CFM5_500m.ts"};
    double size = 1000;
    int a = 1;
    if (a + 1 < argc && strcmp(argv[a], "--size") == 0) {
        size = atof(argv[a + 1]);
        a += 2;
    }
    if (argc - a == 2) {
        paths[0] = argv[a];
        paths[1] = argv[a + 1];
    } else if (argc != a) {
        fprintf(stderr, "usage: %s [--size M] [A.ts B.ts]\n", argv[0]);
        return 2;
    }
    if (fm_version_number() / 100 != FM_VERSION_NUMBER / 100) {
        fprintf(stderr, "libfaultmesh %s, built for %s\n", fm_version_string(),
                FM_VERSION_STRING);
        return 1;
    }

    fm_error err;
    fm_error_clear(&err);
    fm_run *run = fm_run_create(NULL);
    if (!run)
        return 1;
    fm_run_set_log(run, FM_LOG_WARN, say, NULL);
    fm_run_result *res = NULL;
    fm_status st = fm_run_set_double(run, FM_OPT_SIZE, size, &err);
    for (int i = 0; st == FM_OK && i < 2; i++)
        st = fm_run_add_path(run, paths[i], &err);
    if (st == FM_OK)
        st = fm_run_execute(run, &res, &err);
    if (st != FM_OK) {
        fprintf(stderr, "faultmesh: %s (%s)\n", err.message, fm_status_string(st));
        fm_run_destroy(run);
        return 1;
    }

    for (size_t i = 0; i < fm_run_result_nfaults(res); i++) {
        const char *why;
        const char *status = fm_run_result_fault_status(res, i, &why);
        printf("fault %zu: %s: %s%s%s\n", i, fm_run_result_fault_name(res, i), status,
               why ? ": " : "", why ? why : "");
    }

    /* The faults as one mesh: a node two faults share is one vertex, used
     * by triangles of both. */
    size_t nv = fm_run_result_nvertices(res), nt = fm_run_result_ntriangles(res);
    double *xyz = malloc((3 * nv + 1) * sizeof *xyz);
    int32_t *tri = malloc((3 * nt + 1) * sizeof *tri);
    int32_t *fault = malloc((nt + 1) * sizeof *fault);
    unsigned char *seen = calloc(nv + 1, 1);
    int rc = 1;
    if (xyz && tri && fault && seen &&
        fm_run_result_copy_mesh(res, xyz, tri, fault, &err) == FM_OK) {
        for (size_t t = 0; t < nt; t++)
            if (fault[t] == 0 || fault[t] == 1)
                for (int k = 0; k < 3; k++)
                    seen[tri[3 * t + k]] |= (unsigned char)(1u << fault[t]);
        size_t shared = 0;
        for (size_t v = 0; v < nv; v++)
            shared += seen[v] == 3;
        printf("shared nodes: %zu\n", shared);
        for (size_t v = 0; v < nv; v++)
            if (seen[v] == 3)
                printf("  %.3f %.3f %.3f\n", xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
        rc = 0;
    } else {
        fprintf(stderr, "faultmesh: %s\n", err.message[0] ? err.message : "out of memory");
    }
    free(xyz);
    free(tri);
    free(fault);
    free(seen);
    fm_run_result_destroy(res);
    fm_run_destroy(run);
    return rc;
}
