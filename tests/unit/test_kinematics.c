/* Fault sections (fm_sections.h) and element slip from them
 * (fm_kinematics.h): sections written here as GeoJSON, the faults built
 * on them in UTM 11N NAD27, every element checked. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fm_atomic.h"
#include "fm_kinematics.h"
#include "fm_reproject.h"
#include "fm_sections.h"
#include "fm_sim_write.h"
#include "fm_test.h"

#define CRS "EPSG:26711"

static void write_file(const char *path, const char *text)
{
    FILE *fp = fopen(path, "w");
    CHECK(fp != NULL);
    if (fp) {
        fputs(text, fp);
        fclose(fp);
    }
}

/* Three sections: a vertical right-lateral one running north, a blind
 * thrust dipping 30 degrees east from 5 km (its trace drawn southwards:
 * DipDir puts it right) whose rate comes from a second file, and one
 * without depths (left out). */
static const char *fsd =
    "{\"type\":\"FeatureCollection\",\"features\":["
    "{\"type\":\"Feature\",\"properties\":{\"FaultID\":7,\"FaultName\":\"Strike\",\"DipDeg\":90,"
    "\"DipDir\":\"Vertical\",\"Rake\":180,\"UpDepth\":0.0,\"LowDepth\":12.0,\"PrefRate\":10},"
    "\"geometry\":{\"type\":\"LineString\",\"coordinates\":[[-117.0,34.0],[-117.0,34.2]]}},"
    "{\"type\":\"Feature\",\"properties\":{\"FaultID\":9,\"FaultName\":\"Thrust\",\"DipDeg\":30,"
    "\"DipDir\":\"E\",\"Rake\":90,\"UpDepth\":5.0,\"LowDepth\":15.0},"
    "\"geometry\":{\"type\":\"MultiLineString\",\"coordinates\":[[[-116.5,34.2],[-116.5,34.1]],"
    "[[-116.5,34.1],[-116.5,34.0]]]}},"
    "{\"type\":\"Feature\",\"properties\":{\"FaultID\":11,\"FaultName\":\"Broken\",\"DipDeg\":60,"
    "\"Rake\":0},\"geometry\":{\"type\":\"LineString\",\"coordinates\":[[-118,34],[-118,34.1]]}}"
    "]}";
static const char *dm =
    "{\"type\":\"FeatureCollection\",\"features\":["
    "{\"type\":\"Feature\",\"properties\":{\"FaultID\":9,\"PrefRate\":1.5},\"geometry\":null}]}";

/* A grid of points along the horizontal line p0-p1 swept along dir (unit,
 * 3D) from depth z0 to z1 (m, negative), tagged tag. */
static void add_plane(fm_mesh *m, const double p0[2], const double p1[2], double dip_deg,
                      double z0, double z1, int32_t tag)
{
    int nu = 10, nv = 6;
    double dx = p1[0] - p0[0], dy = p1[1] - p0[1], len = hypot(dx, dy);
    double r[2] = {dy / len, -dx / len}; /* right of p0 -> p1 */
    double cot = dip_deg < 90 ? 1 / tan(dip_deg * 3.14159265358979323846 / 180) : 0;
    int32_t base = (int32_t)fm_mesh_nvertices(m);
    for (int j = 0; j <= nv; j++)
        for (int i = 0; i <= nu; i++) {
            double z = z0 + (z1 - z0) * j / nv, off = -z * cot;
            fm_mesh_add_vertex(m, p0[0] + dx * i / nu + off * r[0], p0[1] + dy * i / nu + off * r[1],
                               z);
        }
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            int32_t a = base + j * (nu + 1) + i;
            fm_mesh_add_triangle(m, a, a + 1, a + nu + 1, tag);
            fm_mesh_add_triangle(m, a + 1, a + nu + 2, a + nu + 1, tag);
        }
}

static void test_sections_and_slip(void)
{
    char dir[4096], a[4200], b[4200];
    snprintf(dir, sizeof dir, "%s/kinematics", FM_TMP_DIR);
    CHECK_EQ(fm_mkdir_p(dir, NULL), FM_OK);
    snprintf(a, sizeof a, "%s/fsd.geojson", dir);
    snprintf(b, sizeof b, "%s/dm.geojson", dir);
    write_file(a, fsd);
    write_file(b, dm);
    const char *paths[2] = {a, b};
    fm_sections *s = NULL;
    fm_error err;
    CHECK_EQ(fm_sections_read(paths, 2, &s, &err), FM_OK);
    if (!s)
        return;
    CHECK_EQ(fm_sections_count(s), 2);
    CHECK_EQ(fm_sections_incomplete(s), 1);
    const fm_section *st = fm_sections_get(s, 0), *th = fm_sections_get(s, 1);
    CHECK(st->id == 7 && th->id == 9);
    CHECK(isnan(st->dip_dir) && th->dip_dir == 90);
    CHECK(th->has_rate && th->rate == 1.5); /* merged from the second file */
    CHECK_EQ(th->ntrace, 3);                  /* the parts joined, the shared point once */

    /* the faults, on the sections' own surfaces: the strike-slip one
     * under its trace; the thrust as the plane meeting the surface at its
     * trace, from 5 to 15 km; a vertical east-west fault crossing the
     * strike-slip one, which must take nothing from it */
    double bb[4] = {-118, 33.9, -116, 34.3};
    fm_reproject *rp = fm_reproject_create("EPSG:4326", CRS, bb, "test", &err);
    CHECK(rp != NULL);
    if (!rp) {
        fm_sections_destroy(s);
        return;
    }
    double p[6][2];
    const double ll[6][2] = {{-117.0, 34.0},   {-117.0, 34.2},  {-116.5, 34.0},
                             {-116.5, 34.2},   {-117.05, 34.1}, {-116.95, 34.1}};
    for (int k = 0; k < 6; k++)
        CHECK_EQ(fm_reproject_point(rp, ll[k][0], ll[k][1], &p[k][0], &p[k][1]), 0);
    fm_reproject_destroy(rp);
    fm_mesh *m = fm_mesh_create();
    add_plane(m, p[0], p[1], 90, 0, -12000, 0);
    add_plane(m, p[2], p[3], 30, -5000, -15000, 1);
    add_plane(m, p[4], p[5], 90, -1000, -9000, 2);
    const char *names[3] = {"strike", "thrust", "crossing"};
    fm_faultset fs = {.mesh = m, .names = names, .nfaults = 3, .crs = CRS};
    size_t nt = fm_mesh_ntriangles(m);
    double *strike = malloc(nt * sizeof *strike), *dip = malloc(nt * sizeof *dip);
    fm_element_kinematics *k = malloc(nt * sizeof *k);
    fm_faultset_strike_dip(&fs, strike, dip);
    CHECK_EQ(fm_kinematics_assign(s, &fs, strike, dip, NULL, k, &err), FM_OK);
    const int32_t *tag = fm_mesh_tags(m);
    int bad[3] = {0, 0, 0}, conv1 = 0, n1 = 0;
    double far = 0;
    for (size_t t = 0; t < nt; t++) {
        if (tag[t] == 0)
            bad[0] += k[t].section != 0 || fabs(fabs(k[t].rake) - 180) > 1e-6;
        if (tag[t] == 1) {
            bad[1] += k[t].section != 1 || fabs(k[t].rake - 90) > 0.5;
            conv1 += k[t].convention == 1;
            n1++;
        }
        if (tag[t] == 2)
            bad[2] += k[t].section >= 0;
        if (k[t].section >= 0)
            far = fmax(far, k[t].distance);
    }
    /* the strike-slip: right-lateral on every element; the thrust: reverse
     * (its trace turned by DipDir), found as drawn to the surface */
    CHECK_EQ(bad[0], 0);
    CHECK_EQ(bad[1], 0);
    CHECK_EQ(conv1, n1);
    CHECK_EQ(bad[2], 0);
    CHECK(far < 50); /* on the section surfaces but for the NAD27 -> WGS 84 curvature */
    printf("kinematics: %zu elements, farthest matched %.2f m\n", nt, far);
    free(strike);
    free(dip);
    free(k);
    fm_mesh_destroy(m);
    fm_sections_destroy(s);
}

/* Bad files: named, a clear status. */
static void test_bad_files(void)
{
    char dir[4096], a[4200];
    snprintf(dir, sizeof dir, "%s/kinematics", FM_TMP_DIR);
    CHECK_EQ(fm_mkdir_p(dir, NULL), FM_OK);
    snprintf(a, sizeof a, "%s/bad.geojson", dir);
    write_file(a, "{\"type\":\"Feature\"}");
    const char *paths[1] = {a};
    fm_sections *s = NULL;
    fm_error err;
    CHECK_EQ(fm_sections_read(paths, 1, &s, &err), FM_ERR_PARSE);
    CHECK(strstr(err.message, "bad.geojson") && strstr(err.message, "FeatureCollection"));
    write_file(a, "{\"features\": [1, 2");
    CHECK_EQ(fm_sections_read(paths, 1, &s, &err), FM_ERR_PARSE);
    CHECK(strstr(err.message, "not JSON") != NULL);
    CHECK(s == NULL);
}

FM_TEST_MAIN(FM_CASE(test_sections_and_slip), FM_CASE(test_bad_files))
