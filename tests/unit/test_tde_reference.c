/* The TDE module against the reference values of ../shared/elastic
 * (Nikkhoo & Walter's MATLAB functions; see that folder's README.md):
 * five cases of 1331 points each, displacement (nu = 0.25), stress and
 * strain (mu = lambda = 1).
 *
 * Error norm: for each case and field (u, stress, strain), the largest
 * |ours - reference| over every row and component, divided by the largest
 * |reference| of that field in that case; it must be <= 1e-8. Rows that
 * are NaN in the reference (points on a vertex or an edge) must be NaN in
 * ours, and no other row may be. Skips (77) when the folder is absent. */
#include <stdio.h>
#include <stdlib.h>

#include "fm_elastic.h"
#include "fm_test.h"

enum { ROWS = 1331, COLS = 18 };

typedef struct ref_case {
    const char *file;
    int half_space;
    double tri[3][3], slip[3];
} ref_case;

static const ref_case cases[] = {
    {"simple", 0, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {1, 0, 0}},
    {"complex", 0, {{0, 0.1, 0.1}, {1, -0.2, -0.2}, {1, 1, 0.3}}, {1.3, 1.4, 1.5}},
    {"fullspace_horizontal", 0, {{-1, 0, -1}, {1, 0, -1}, {0, 1, -1}}, {1, 0.5, -0.3}},
    {"halfspace", 1, {{0, 0.1, -0.1}, {1, -0.2, -0.2}, {1, 1, -0.3}}, {1.3, 1.4, 1.5}},
    {"halfspace_horizontal", 1, {{-1, 0, -1}, {1, 0, -1}, {0, 1, -1}}, {1, 0.5, -0.3}},
};

/* rows x COLS values (header skipped); NULL if the file cannot be read */
static double *read_csv(const char *path, int *nrows)
{
    char *text = fm_test_read_file(path, NULL);
    if (!text)
        return NULL;
    double *v = malloc(sizeof(double) * ROWS * COLS);
    char *p = strchr(text, '\n');
    int n = 0;
    while (v && p && n < ROWS) {
        p++;
        if (*p == '\0')
            break;
        for (int k = 0; k < COLS; k++) {
            char *end;
            v[n * COLS + k] = strtod(p, &end);
            p = end;
            if (*p == ',')
                p++;
        }
        n++;
        p = strchr(p, '\n');
    }
    free(text);
    *nrows = n;
    return v;
}

static int data_present(void)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/simple.csv", FM_ELASTIC_DIR);
    FILE *fp = fopen(path, "rb");
    if (fp)
        fclose(fp);
    return fp != NULL;
}

static void run_case(const ref_case *c)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.csv", FM_ELASTIC_DIR, c->file);
    int n = 0;
    double *ref = read_csv(path, &n);
    CHECK(ref != NULL);
    CHECK_EQ(n, ROWS);
    if (!ref || n != ROWS) {
        free(ref);
        return;
    }
    /* ours: 15 values per row in the reference's column order */
    double *got = malloc(sizeof(double) * ROWS * 15);
    CHECK(got != NULL);
    if (!got) {
        free(ref);
        return;
    }
    for (int r = 0; r < ROWS; r++) {
        const double *x = ref + r * COLS;
        double *g = got + r * 15, eps[6];
        int rc1 = c->half_space ? fm_tde_disp_hs(x, c->tri, c->slip, 0.25, g)
                                : fm_tde_disp_fs(x, c->tri, c->slip, 0.25, g);
        int rc2 = c->half_space ? fm_tde_strain_hs(x, c->tri, c->slip, 0.25, eps)
                                : fm_tde_strain_fs(x, c->tri, c->slip, 0.25, eps);
        CHECK_EQ(rc1, 0);
        CHECK_EQ(rc2, 0);
        fm_tde_stress_from_strain(eps, 1, 1, g + 3);
        memcpy(g + 9, eps, sizeof eps);
    }
    static const char *field[3] = {"u", "stress", "strain"};
    double maxref[3] = {0, 0, 0}, maxerr[3] = {0, 0, 0};
    int nan_rows = 0, nan_bad = 0;
    for (int r = 0; r < ROWS; r++)
        for (int k = 0; k < 15; k++) {
            double v = ref[r * COLS + 3 + k];
            int f = k < 3 ? 0 : k < 9 ? 1 : 2;
            if (!isnan(v) && fabs(v) > maxref[f])
                maxref[f] = fabs(v);
        }
    for (int r = 0; r < ROWS; r++) {
        nan_rows += isnan(ref[r * COLS + 3]);
        for (int k = 0; k < 15; k++) {
            double v = ref[r * COLS + 3 + k], w = got[r * 15 + k];
            int f = k < 3 ? 0 : k < 9 ? 1 : 2;
            if (isnan(v) || isnan(w)) {
                if (isnan(v) != isnan(w)) {
                    nan_bad++;
                    fprintf(stderr, "%s row %d (%g,%g,%g): NaN in one only\n", c->file, r,
                            ref[r * COLS], ref[r * COLS + 1], ref[r * COLS + 2]);
                }
                continue;
            }
            double e = fabs(w - v) / maxref[f];
            if (e > maxerr[f])
                maxerr[f] = e;
        }
    }
    CHECK_EQ(nan_bad, 0);
    printf("%-22s", c->file);
    for (int f = 0; f < 3; f++) {
        printf("  %s %.2e", field[f], maxerr[f]);
        CHECK(maxerr[f] <= 1e-8);
    }
    printf("  (NaN rows %d)\n", nan_rows);
    free(ref);
    free(got);
}

static void test_fullspace(void)
{
    for (int i = 0; i < 3; i++)
        run_case(&cases[i]);
}

static void test_halfspace(void)
{
    for (int i = 3; i < 5; i++)
        run_case(&cases[i]);
}

int main(void)
{
    if (!data_present()) {
        printf("skipped: no reference values in %s\n", FM_ELASTIC_DIR);
        return FM_TEST_SKIP;
    }
    static const fm_test_case list[] = {FM_CASE(test_fullspace), FM_CASE(test_halfspace)};
    return fm_test_run(list, sizeof list / sizeof list[0]);
}
