/* Read -> write -> read on every file of the CFM 500 m and native sets:
 * geometry, ids, parts, header and properties must come back identical.
 * Skips (77) when the CFM folder is absent. */
#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fm_atomic.h"
#include "fm_test.h"
#include "fm_tsurf.h"
#include "test_tsurf_common.h"

static int nfiles;

/* Counts lines starting with kw, independently of the reader. */
static size_t count_lines(const char *path, const char *kw)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    size_t n = 0, k = strlen(kw);
    char line[512];
    while (fgets(line, sizeof line, f))
        if (strncmp(line, kw, k) == 0)
            n++;
    fclose(f);
    return n;
}

static void round_trip(const char *path, const char *tmp)
{
    fm_tsurf **a = NULL, **b = NULL;
    size_t na = 0, nb = 0;
    fm_error err;
    if (fm_tsurf_read_file(path, &a, &na, &err) != FM_OK) {
        fprintf(stderr, "%s\n", err.message);
        CHECK(0);
        return;
    }
    size_t nv = 0, nt = 0;
    for (size_t i = 0; i < na; i++) {
        nv += fm_mesh_nvertices(fm_tsurf_mesh(a[i]));
        nt += fm_mesh_ntriangles(fm_tsurf_mesh(a[i]));
    }
    CHECK_EQ(nv, count_lines(path, "VRTX ") + count_lines(path, "PVRTX ") +
                     count_lines(path, "ATOM ") + count_lines(path, "PATOM "));
    CHECK_EQ(nt, count_lines(path, "TRGL "));
    CHECK_EQ(fm_tsurf_write_file(tmp, a, na, &err), FM_OK);
    if (fm_tsurf_read_file(tmp, &b, &nb, &err) != FM_OK) {
        fprintf(stderr, "re-read of %s: %s\n", path, err.message);
        CHECK(0);
    }
    CHECK_EQ(nb, na);
    for (size_t i = 0; i < na && i < nb; i++)
        if (!same_object(a[i], b[i]))
            fprintf(stderr, "round trip differs: %s object %zu\n", path, i);
    fm_tsurf_free_all(a, na);
    fm_tsurf_free_all(b, nb);
    nfiles++;
}

static int run_folder(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    fm_error err;
    CHECK_EQ(fm_mkdir_p(FM_TMP_DIR, &err), FM_OK);
    char tmp[1024];
    snprintf(tmp, sizeof tmp, "%s/cfm_round_trip.ts", FM_TMP_DIR);
    struct dirent *de;
    int n = 0;
    while ((de = readdir(d)) != NULL) {
        size_t len = strlen(de->d_name);
        if (len < 4 || strcmp(de->d_name + len - 3, ".ts") != 0)
            continue;
        char path[2048];
        snprintf(path, sizeof path, "%s/%s", dir, de->d_name);
        round_trip(path, tmp);
        n++;
    }
    closedir(d);
    unlink(tmp);
    return n;
}

static void test_cfm_500m(void)
{
    int n = run_folder(FM_CFM_DIR "/CFM5.3/500m");
    CHECK(n >= 400);
}

static void test_cfm_native(void)
{
    /* Several TFACE parts per file there; optional. */
    struct stat sb;
    if (stat(FM_CFM_DIR "/CFM5.3/native", &sb) != 0)
        return;
    int n = run_folder(FM_CFM_DIR "/CFM5.3/native");
    CHECK(n >= 400);
}

int main(void)
{
    struct stat sb;
    if (stat(FM_CFM_DIR "/CFM5.3/500m", &sb) != 0 || !S_ISDIR(sb.st_mode)) {
        printf("CFM not found under %s: skipped\n", FM_CFM_DIR);
        return FM_TEST_SKIP;
    }
    static const fm_test_case cases[] = {FM_CASE(test_cfm_500m), FM_CASE(test_cfm_native)};
    int rc = fm_test_run(cases, 2);
    printf("%d files round-tripped\n", nfiles);
    return rc;
}
