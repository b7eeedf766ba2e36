/* Simulator attributes and formats: the metadata and --slip CSV readers
 * (quoting, CRLF, title rows, errors with file:line), the rake of each
 * slip-sense code, which rule gives a fault its slip, the per-element
 * strike/dip convention, and the RSQSim and EQSim writers (content,
 * atomic failure, PROJ conversion of a fixed point). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fm_atomic.h"
#include "fm_metadata.h"
#include "fm_names.h"
#include "fm_sim_write.h"
#include "fm_test.h"

static void tmp_path(char *buf, size_t n, const char *name)
{
    snprintf(buf, n, "%s/sim", FM_TMP_DIR);
    CHECK_EQ(fm_mkdir_p(buf, NULL), FM_OK);
    snprintf(buf, n, "%s/sim/%s", FM_TMP_DIR, name);
}

static void put_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    CHECK(f != NULL);
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

static int exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* ---- CSV readers ---- */

static const char METADATA[] =
    "\xEF\xBB\xBF"
    "CFM5.3 Fault Object Name,Num,Avg Strike,Slip Sense,References\r\n"
    "SAN ANDREAS FAULT SYSTEM,,,,\r\n"
    "SAFS-SAFZ-MULT-Banning_fault_strand-CFM4,1,294,rlss,\"Bryant, 2005; \"\"quoted\"\"\"\r\n"
    "WTRA-ORFZ-SFNV-Northridge_Frew_fault-CFM2,5,107,t,\"two\r\nlines\"\r\n"
    "\r\n"
    "PNRA-X-Y-Oblique_fault-CFM5,2,300,orln,\r\n"
    "PNRA-X-Y-Unknown_sense_fault-CFM5,2,300,,\r\n"
    "PNRA-X-Y-Odd_sense_fault-CFM5,2,300,weird,\r\n";

static void test_metadata_read(void)
{
    char path[512];
    tmp_path(path, sizeof path, "meta.csv");
    put_file(path, METADATA);
    fm_metadata *m = NULL;
    fm_error err;
    CHECK_EQ(fm_metadata_read(path, &m, &err), FM_OK);
    CHECK_EQ(fm_metadata_count(m), 5);
    CHECK_STR(fm_metadata_slip_sense(m, "SAFS-SAFZ-MULT-Banning_fault_strand-CFM4"), "rlss");
    /* The regularised files' resolution suffix is dropped to match. */
    CHECK_STR(fm_metadata_slip_sense(m, "WTRA-ORFZ-SFNV-Northridge_Frew_fault-CFM2_500m"), "t");
    CHECK_STR(fm_metadata_slip_sense(m, "PNRA-X-Y-Oblique_fault-CFM5"), "orln");
    CHECK_STR(fm_metadata_slip_sense(m, "PNRA-X-Y-Unknown_sense_fault-CFM5"), "");
    CHECK(fm_metadata_slip_sense(m, "SAN ANDREAS FAULT SYSTEM") == NULL);
    CHECK(fm_metadata_slip_sense(m, "Not_there") == NULL);
    CHECK(fm_metadata_slip_sense(m, "SAFS-SAFZ-MULT-Banning_fault_strand-CFM4_m") == NULL);
    fm_metadata_destroy(m);
}

static void expect_error(int metadata, const char *text, const char *what)
{
    char path[512];
    tmp_path(path, sizeof path, "bad.csv");
    put_file(path, text);
    fm_error err;
    fm_error_clear(&err);
    fm_status st;
    if (metadata) {
        fm_metadata *m = NULL;
        st = fm_metadata_read(path, &m, &err);
        CHECK(m == NULL);
    } else {
        fm_slip_table *t = NULL;
        st = fm_slip_table_read(path, &t, &err);
        CHECK(t == NULL);
    }
    CHECK_EQ(st, FM_ERR_PARSE);
    if (!strstr(err.message, what) || !strstr(err.message, path)) {
        fprintf(stderr, "message '%s' lacks '%s' or the path\n", err.message, what);
        fm_test_failed_checks++;
    }
}

static void test_csv_errors(void)
{
    expect_error(1, "Fault Object Name,Slip Sense\nA,rlss\nB,\"open\n", "bad.csv:3: quoted field never closed");
    expect_error(1, "Name,Num\nA,1\n", "no 'Fault Object Name'");
    expect_error(1, "Fault Object Name,Num\nA,1\n", "no 'Slip Sense'");
    expect_error(1, "Fault Object Name,Slip Sense,X\nA,rlss,1\nB,n\n", "bad.csv:3: 2 fields");
    expect_error(1, "Fault Object Name,Slip Sense\nA,\"rl\"ss\n", "bad.csv:2: text after the closing");
    expect_error(1, "Fault Object Name,Slip Sense\nA,rlss\nA,n\n", "listed twice");
    expect_error(0, "name,rake,rate\nA,90\n", "bad.csv:2: 2 fields");
    expect_error(0, "name,rake,rate\r\nA,90,1\r\nB,ninety,1\r\n", "bad.csv:3: rake 'ninety'");
    expect_error(0, "A,90,-1\n", "bad.csv:1: slip rate '-1'");
    expect_error(0, "A,90,1\n,90,1\n", "bad.csv:2: empty fault name");
    fm_slip_table *t = NULL;
    fm_error err;
    CHECK_EQ(fm_slip_table_read(FM_TMP_DIR "/sim/none/missing.csv", &t, &err), FM_ERR_IO);
}

static void test_sense_rake(void)
{
    static const struct {
        const char *code;
        double rake;
    } want[] = {{"rlss", 180}, {"llss", 0},     {"r", 90},     {"t", 90},
                {"n", -90},    {"orlr", 135},   {"ollr", 45},  {"orln", -135},
                {"olln", -45}, {"Thrust", 90},  {" n ", -90},  {"Normal", -90}};
    for (size_t i = 0; i < sizeof want / sizeof *want; i++) {
        double r = 1e9;
        CHECK_EQ(fm_slip_sense_rake(want[i].code, &r), 0);
        CHECK_NEAR(r, want[i].rake, 0);
    }
    double r;
    CHECK_EQ(fm_slip_sense_rake("", &r), -1);
    CHECK_EQ(fm_slip_sense_rake("rl", &r), -1);
    CHECK_EQ(fm_slip_sense_rake(NULL, &r), -1);
}

static void test_slip_assign(void)
{
    char mpath[512], spath[512];
    tmp_path(mpath, sizeof mpath, "meta2.csv");
    put_file(mpath, METADATA);
    tmp_path(spath, sizeof spath, "slip.csv");
    put_file(spath, "# rules\n"
                    "fault,rake (deg),slip rate (mm/yr)\n"
                    "SAFS-*,,20\n"
                    "\"SAFS-SAFZ-MULT-Banning_fault_strand-CFM4\",170,\n"
                    "PNRA-X-Y-?nknown_sense_fault-CFM5,-100,0.5,,\n"
                    "*,,1\r\n");
    fm_metadata *m = NULL;
    fm_slip_table *t = NULL;
    fm_error err;
    CHECK_EQ(fm_metadata_read(mpath, &m, &err), FM_OK);
    CHECK_EQ(fm_slip_table_read(spath, &t, &err), FM_OK);
    const char *names[] = {"SAFS-SAFZ-MULT-Banning_fault_strand-CFM4_500m",
                           "WTRA-ORFZ-SFNV-Northridge_Frew_fault-CFM2",
                           "PNRA-X-Y-Unknown_sense_fault-CFM5", "PNRA-X-Y-Odd_sense_fault-CFM5",
                           "PNRA-X-Y-Oblique_fault-CFM5_1000m"};
    fm_fault_slip s[5];
    fm_slip_assign(names, 5, m, t, s);
    /* Exact rule (rake 170) wins over the earlier glob; its empty rate
     * leaves the default, not the glob's 20. */
    CHECK_NEAR(s[0].rake, 170, 0);
    CHECK_EQ(s[0].rake_from, FM_SLIP_FROM_CSV);
    CHECK_NEAR(s[0].slip_rate_mm_yr, 0, 0);
    CHECK_EQ(s[0].rate_from, FM_SLIP_FROM_DEFAULT);
    CHECK_EQ(s[0].csv_line, 4);
    CHECK_STR(s[0].slip_sense, "rlss");
    /* Catch-all: rate 1, rake from the metadata's thrust. */
    CHECK_NEAR(s[1].rake, 90, 0);
    CHECK_EQ(s[1].rake_from, FM_SLIP_FROM_METADATA);
    CHECK_NEAR(s[1].slip_rate_mm_yr, 1, 0);
    CHECK_EQ(s[1].csv_line, 6);
    /* Glob with '?' (first matching glob in file order). */
    CHECK_NEAR(s[2].rake, -100, 0);
    CHECK_NEAR(s[2].slip_rate_mm_yr, 0.5, 0);
    /* Unknown code: default rake. */
    CHECK_NEAR(s[3].rake, FM_SLIP_DEFAULT_RAKE, 0);
    CHECK_EQ(s[3].rake_from, FM_SLIP_FROM_DEFAULT);
    CHECK_STR(s[3].slip_sense, "weird");
    CHECK_NEAR(s[4].rake, -135, 0);
    CHECK_EQ(s[4].rake_from, FM_SLIP_FROM_METADATA);
    /* Nothing at all: defaults; rakes normalised into (-180, 180]. */
    fm_slip_assign(names, 1, NULL, NULL, s);
    CHECK_NEAR(s[0].rake, FM_SLIP_DEFAULT_RAKE, 0);
    CHECK(s[0].slip_sense == NULL);
    put_file(spath, "*,-180,2\n");
    fm_slip_table_destroy(t);
    CHECK_EQ(fm_slip_table_read(spath, &t, &err), FM_OK);
    fm_slip_assign(names, 1, NULL, t, s);
    CHECK_NEAR(s[0].rake, 180, 0);
    CHECK_NEAR(s[0].slip_rate_mm_yr * FM_MM_PER_YEAR_TO_M_PER_S, 2e-3 / 31557600.0, 1e-24);
    fm_slip_table_destroy(t);
    fm_metadata_destroy(m);
}

/* ---- element convention ---- */

static void test_orient(void)
{
    double s, d;
    /* Plane dipping 30 degrees to the east (z = -x tan 30): strike 0. */
    double t = tan(30 * 3.14159265358979323846 / 180);
    double a[3] = {0, 0, 0}, b[3] = {1000, 0, -1000 * t}, c[3] = {0, 1000, 0};
    CHECK_EQ(fm_element_orient(a, b, c, &s, &d), 0); /* (b-a)x(c-a) has z > 0 */
    CHECK_NEAR(s, 0, 1e-9);
    CHECK_NEAR(d, 30, 1e-9);
    CHECK_EQ(fm_element_orient(a, c, b, &s, &d), 1);
    CHECK_NEAR(s, 0, 1e-9);
    CHECK_NEAR(d, 30, 1e-9);
    /* Dipping 60 degrees to the north-west: dip direction 315, strike 225. */
    double u[3] = {-sqrt(0.5), sqrt(0.5), 0}, v[3] = {sqrt(0.5), sqrt(0.5), 0};
    double tn = tan(60 * 3.14159265358979323846 / 180);
    double p1[3] = {1000 * u[0], 1000 * u[1], -1000 * tn}, p2[3] = {1000 * v[0], 1000 * v[1], 0};
    fm_element_orient(a, p1, p2, &s, &d);
    CHECK_NEAR(s, 225, 1e-9);
    CHECK_NEAR(d, 60, 1e-9);
    /* Vertical plane x = 0: strike 0 (not 180) whichever way wound. */
    double q1[3] = {0, 1000, 0}, q2[3] = {0, 0, -1000};
    int f1 = fm_element_orient(a, q1, q2, &s, &d);
    CHECK_NEAR(s, 0, 1e-9);
    CHECK_NEAR(d, 90, 0);
    int f2 = fm_element_orient(a, q2, q1, &s, &d);
    CHECK_NEAR(s, 0, 1e-9);
    CHECK_EQ(f1 + f2, 1);
    /* Vertical striking 120 or 300: 120. */
    double r1[3] = {866.0254037844386, -500, 0};
    fm_element_orient(a, r1, q2, &s, &d);
    CHECK_NEAR(s, 120, 1e-9);
    fm_element_orient(a, q2, r1, &s, &d);
    CHECK_NEAR(s, 120, 1e-9);
    /* Horizontal: strike 0, dip 0; degenerate likewise. */
    double h1[3] = {1000, 0, 0}, h2[3] = {0, 1000, 0};
    CHECK_EQ(fm_element_orient(a, h2, h1, &s, &d), 1);
    CHECK_NEAR(s, 0, 0);
    CHECK_NEAR(d, 0, 0);
    CHECK_EQ(fm_element_orient(a, h1, h1, &s, &d), 0);
    CHECK_NEAR(d, 0, 0);
    char *n = fm_section_name("San Andreas (Mojave) \"1857\"\tx");
    CHECK_STR(n, "San_Andreas_Mojave_1857_x");
    free(n);
    n = fm_section_name("  ");
    CHECK_STR(n, "_");
    free(n);
}

/* Short names: at most max bytes, unique, the same for a long name
 * whatever its neighbours (unless they collide), one token. */
static void test_short_names(void)
{
    const char *names[] = {
        "SAFS-SAFZ-MULT-San_Andreas_fault_Coachella_Valley_strand-CFM5_500m", /* 66 */
        "SAFS-SAFZ-MULT-San_Andreas_fault_Coachella_Valley_strand-CFM4_500m", /* same 45 */
        "short name",
        "short_name", /* the same token */
        "exactly_fifty_characters_long_name_xxxxxxxxxxxxxxx"};
    CHECK_EQ(strlen(names[4]), 50);
    char **s = fm_short_names(names, 5, FM_SECTION_NAME_MAX);
    CHECK(s != NULL);
    if (!s)
        return;
    for (int i = 0; i < 5; i++) {
        CHECK(strlen(s[i]) <= FM_SECTION_NAME_MAX);
        CHECK(strpbrk(s[i], " \t\"") == NULL);
        for (int j = 0; j < i; j++)
            CHECK(strcmp(s[i], s[j]) != 0);
    }
    CHECK_EQ(strlen(s[0]), 50);
    CHECK(strncmp(s[0], names[0], 45) == 0 && s[0][45] == '~');
    CHECK(strncmp(s[1], names[1], 45) == 0 && s[1][45] == '~');
    CHECK_STR(s[2], "short_name");
    CHECK(strncmp(s[3], "short_name~", 11) == 0 && strlen(s[3]) == 15);
    CHECK_STR(s[4], names[4]);
    /* a long name's short form alone is the same as among the others */
    char **one = fm_short_names(&names[1], 1, FM_SECTION_NAME_MAX);
    CHECK(one && strcmp(one[0], s[1]) == 0);
    fm_short_names_free(one, 1);
    /* Exodus: 32 */
    char **e = fm_short_names(names, 5, FM_EXODUS_NAME_MAX);
    for (int i = 0; e && i < 5; i++) {
        CHECK(strlen(e[i]) <= FM_EXODUS_NAME_MAX);
        for (int j = 0; j < i; j++)
            CHECK(strcmp(e[i], e[j]) != 0);
    }
    fm_short_names_free(e, 5);
    fm_short_names_free(s, 5);
    CHECK(fm_short_names(names, 5, 5) == NULL);
}

/* ---- writers ---- */

/* Two faults: a plane dipping 45 degrees to the south with triangles of
 * both windings, and a vertical one sharing its top-left vertex. */
static fm_mesh *two_faults(void)
{
    fm_mesh *m = fm_mesh_create();
    double x0 = 400000, y0 = 3800000;
    fm_mesh_add_vertex(m, x0, y0, 0);                   /* 0 */
    fm_mesh_add_vertex(m, x0 + 2000, y0, 0);            /* 1 */
    fm_mesh_add_vertex(m, x0, y0 - 1000, -1000);        /* 2 */
    fm_mesh_add_vertex(m, x0 + 2000, y0 - 1000, -1000); /* 3 */
    fm_mesh_add_vertex(m, x0, y0 + 1500, 0);            /* 4 */
    fm_mesh_add_vertex(m, x0, y0 + 1500, -1500);        /* 5 */
    fm_mesh_add_vertex(m, x0, y0, -1500);               /* 6 */
    fm_mesh_add_triangle(m, 0, 2, 1, 0);
    fm_mesh_add_triangle(m, 1, 3, 2, 0); /* wound the other way */
    fm_mesh_add_triangle(m, 0, 4, 5, 1);
    fm_mesh_add_triangle(m, 0, 6, 5, 1);
    return m;
}

static void test_rsqsim(void)
{
    fm_mesh *m = two_faults();
    const char *names[] = {"South dipping", "Vertical/one"};
    fm_faultset fs = {.mesh = m, .names = names, .nfaults = 2, .crs = "EPSG:26711"};
    double rake[2] = {90, 180}, rate[2] = {1e-10, 2.5e-10};
    fm_sim_slip slip = {rake, rate, NULL, NULL};
    char path[512];
    tmp_path(path, sizeof path, "set.rsqsim");
    fm_error err;
    CHECK_EQ(fm_faultset_write_rsqsim(path, &fs, &slip, &err), FM_OK);
    char *text = fm_test_read_file(path, NULL);
    CHECK(text != NULL);
    if (text) {
        /* The dipping fault's second triangle is wound down: swapped to
         * 1 2 3; the vertical one's first has strike 180: swapped to 0 5 4. */
        const char *want =
            "400000 3800000 0 400000 3799000 -1000 402000 3800000 0 90 1e-10 1 South_dipping\n"
            "402000 3800000 0 400000 3799000 -1000 402000 3799000 -1000 90 1e-10 1 South_dipping\n"
            "400000 3800000 0 400000 3801500 -1500 400000 3801500 0 180 2.5e-10 2 Vertical_one\n"
            "400000 3800000 0 400000 3800000 -1500 400000 3801500 -1500 180 2.5e-10 2 "
            "Vertical_one\n";
        CHECK_STR(text, want);
        free(text);
    }
    /* Bad slip: nothing written. */
    rate[1] = NAN;
    tmp_path(path, sizeof path, "bad.rsqsim");
    CHECK_EQ(fm_faultset_write_rsqsim(path, &fs, &slip, &err), FM_ERR_NUMERIC);
    CHECK(!exists(path));
    fm_mesh_destroy(m);
}

static void test_eqsim(void)
{
    fm_mesh *m = two_faults();
    const char *names[] = {"South dipping", "Vertical"};
    fm_faultset fs = {.mesh = m, .names = names, .nfaults = 2, .crs = "EPSG:26711"};
    double rake[2] = {90, 180}, rate[2] = {1e-10, 2e-10};
    fm_sim_slip slip = {rake, rate, NULL, NULL};
    char path[512];
    fm_error err;
    tmp_path(path, sizeof path, "set.eqsim");
    CHECK_EQ(fm_faultset_write_eqsim(path, &fs, &slip, FM_EQSIM_RECTANGULAR, &err), FM_OK);
    char *text = fm_test_read_file(path, NULL);
    CHECK(text != NULL);
    if (text) {
        CHECK(!strncmp(text, "101 EQSim_Input_Geometry_2 4\n", 29));
        CHECK(strstr(text, "\n200 2 8 4 0 3799000 3801500 400000 402000 -1500 0 1\n") != NULL);
        /* Dipping fault: strike 90 (east), das = x - 400000; its top edge
         * (z = 0) is the trace, west end initial. */
        CHECK(strstr(text, "\n201 1 South_dipping 4 2 0 3799000 3800000 400000 402000 -1000 0 0 "
                           "2000 1\n202 1 3800000 400000 0 0 2\n202 2 3800000 402000 0 2000 3\n"
                           "202 3 3799000 400000 -1000 0 0\n202 4 3799000 402000 -1000 2000 0\n"
                           "203 1 1 3 2 90 1e-10 0 90 45\n203 2 2 3 4 90 1e-10 0 90 45\n") != NULL);
        /* Vertical fault x = 400000: strike 0, das = y - y0, vertices
         * numbered on from 5; the shared node is listed again. */
        CHECK(strstr(text, "\n201 2 Vertical 4 2 0 3800000 3801500 400000 400000 -1500 0 0 1500 2\n"
                           "202 5 3800000 400000 0 0 2\n202 6 3801500 400000 0 1500 3\n"
                           "202 7 3801500 400000 -1500 1500 0\n202 8 3800000 400000 -1500 0 0\n"
                           "203 3 5 7 6 180 2e-10 0 0 90\n203 4 5 8 7 180 2e-10 0 0 90\n"
                           "999 End\n") != NULL);
        free(text);
    }
    /* Spherical: the shared corner through PROJ (EPSG:26711 to WGS 84,
     * what cs2cs gives with Debian's proj-data), strike from true north:
     * along the grid's east line the geodesic azimuth is 89.386 degrees
     * here (pyproj's Geod between the two converted top corners). */
    tmp_path(path, sizeof path, "sph.eqsim");
    CHECK_EQ(fm_faultset_write_eqsim(path, &fs, &slip, FM_EQSIM_SPHERICAL, &err), FM_OK);
    text = fm_test_read_file(path, NULL);
    CHECK(text != NULL);
    if (text) {
        const char *v = strstr(text, "\n202 1 ");
        double lat = 0, lon = 0, z = 1;
        CHECK(v && sscanf(v, "\n202 1 %lf %lf %lf", &lat, &lon, &z) == 3);
        CHECK_NEAR(lat, 34.338240881, 1e-9);
        CHECK_NEAR(lon, -118.088032129, 1e-9);
        CHECK_NEAR(z, 0, 0);
        const char *t = strstr(text, "\n203 1 ");
        double r, sr, as, st, dp;
        int i1, i2, i3;
        CHECK(t && sscanf(t, "\n203 1 %d %d %d %lf %lf %lf %lf %lf", &i1, &i2, &i3, &r, &sr, &as,
                          &st, &dp) == 8);
        CHECK_NEAR(st, 89.386, 0.005);
        CHECK_NEAR(dp, 45, 0.05);
        CHECK(strstr(text, "converted with PROJ") != NULL);
        free(text);
    }
    /* A CRS PROJ does not know: an error naming it, no file. */
    fs.crs = "local metres (synthetic)";
    tmp_path(path, sizeof path, "bad.eqsim");
    CHECK_EQ(fm_faultset_write_eqsim(path, &fs, &slip, FM_EQSIM_SPHERICAL, &err), FM_ERR_INVALID);
    CHECK(strstr(err.message, "local metres (synthetic)") != NULL);
    CHECK(!exists(path));
    fm_mesh_destroy(m);
}

FM_TEST_MAIN(FM_CASE(test_metadata_read), FM_CASE(test_csv_errors), FM_CASE(test_sense_rake),
             FM_CASE(test_slip_assign), FM_CASE(test_orient), FM_CASE(test_short_names),
             FM_CASE(test_rsqsim),
             FM_CASE(test_eqsim))
