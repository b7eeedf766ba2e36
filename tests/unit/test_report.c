/* fm_report: report.html of a tiny synthetic set. The pictures are
 * decoded back (cairo reads the PNGs of the data: URIs) and looked at:
 * their sizes, that they are not blank, that the map puts east right and
 * north up; the page holds every fault, junction and reason, problems
 * before the overview, a badge word per kind, junctions numbered from 1,
 * the packed triangles and its own script; the same report gives the
 * same bytes. (The packed triangles are decoded against the mesh by
 * tests/tools/check_report_html.py, the page run in a browser by
 * report_html_browser.sh.) */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <cairo.h>

#include "fm_atomic.h"
#include "fm_report.h"
#include "fm_test.h"

#define TMP FM_TMP_DIR "/report"

/* A rectangle of nu x nv cells from the trace (x0, y0) - (x1, y1) down to
 * depth, its bottom moved (dx, dy) horizontally (a dip), tagged tag. */
static void add_plane(fm_mesh *m, double x0, double y0, double x1, double y1, double depth,
                      double dx, double dy, int nu, int nv, int32_t tag)
{
    int32_t base = (int32_t)fm_mesh_nvertices(m);
    for (int j = 0; j <= nv; j++)
        for (int i = 0; i <= nu; i++) {
            double u = (double)i / nu, v = (double)j / nv;
            fm_mesh_add_vertex(m, x0 + u * (x1 - x0) + v * dx, y0 + u * (y1 - y0) + v * dy,
                               -v * depth);
        }
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            int32_t a = base + j * (nu + 1) + i, b = a + 1, c = a + nu + 1, d = c + 1;
            fm_mesh_add_triangle(m, a, b, d, tag);
            fm_mesh_add_triangle(m, a, d, c, tag);
        }
}

typedef struct fixture {
    fm_mesh *set, *orig[3];
    fm_report *rep;
} fixture;

/* Alpha (meshed) dips north in the south-west, Beta (meshed, with a
 * warning) is vertical in the middle, Gamma (failed) is vertical in the
 * north-east, Epsilon could not be read, Delta (dropped) duplicates
 * Alpha. */
static void make(fixture *fx)
{
    memset(fx, 0, sizeof *fx);
    fx->set = fm_mesh_create();
    add_plane(fx->set, 2000, 2000, 12000, 2000, 8000, 0, 8000, 10, 8, 0);
    add_plane(fx->set, 20000, 15000, 20000, 25000, 8000, 0, 0, 10, 8, 1);
    for (int k = 0; k < 3; k++)
        fx->orig[k] = fm_mesh_create();
    add_plane(fx->orig[0], 2000, 2000, 12000, 2000, 8000, 0, 8000, 40, 32, 0);
    add_plane(fx->orig[1], 20000, 15000, 20000, 25000, 8000, 0, 0, 40, 32, 0);
    add_plane(fx->orig[2], 40000, 40000, 50000, 50000, 8000, 0, 0, 40, 32, 0);
    fm_report_info info = {"test report", "EPSG:26711", 1000};
    fx->rep = fm_report_create(fx->set, &info, NULL);
    CHECK(fx->rep != NULL);
    fm_quality q = {.triangles = 160, .nodes = 99, .edges = 260, .angle_min = 35, .below_30 = 0,
                    .edges_in_band = 250, .area = 8e7};
    fm_fidelity fid = {.nodes = 99, .rms = 3.5, .max = 12};
    const char *warn[1] = {"a <warning> & more"};
    fm_report_fault f[5] = {
        {.name = "Alpha", .file = "alpha.ts", .status = "ok", .tag = 0, .original = fx->orig[0],
         .sheets = 1, .quality = q, .fidelity = fid, .fitted_area = 8.1e7},
        {.name = "Beta", .file = "beta.ts", .status = "ok", .tag = 1, .original = fx->orig[1],
         .warnings = warn, .nwarnings = 1, .sheets = 1, .quality = q, .fidelity = fid,
         .fitted_area = 8e7},
        {.name = "Gamma", .file = "gamma.ts", .status = "error", .reason = "could not fit",
         .tag = -1, .original = fx->orig[2]},
        {.name = "Epsilon", .file = "eps.ts", .status = "error", .reason = "cannot read",
         .tag = -1},
        {.name = "Delta", .file = "delta.ts", .status = "dropped", .reason = "near-duplicate",
         .tag = -1, .original = fx->orig[0]},
    };
    for (int k = 0; k < 5; k++)
        CHECK_EQ(fm_report_add_fault(fx->rep, &f[k], NULL), FM_OK);
    fm_report_junction j[2] = {
        {.fault = {"Alpha", "Beta"}, .type = "T", .gap_closed = 250, .length = 8000,
         .min_angle = 60},
        {.fault = {"Alpha", "Gamma"}, .type = "unjoined", .length = 0, .reason = "too far apart"},
    };
    for (int k = 0; k < 2; k++)
        CHECK_EQ(fm_report_add_junction(fx->rep, &j[k], NULL), FM_OK);
    CHECK_EQ(fm_report_add_fact(fx->rep, "faults", "4 read", NULL), FM_OK);
}

static void release(fixture *fx)
{
    fm_report_destroy(fx->rep);
    fm_mesh_destroy(fx->set);
    for (int k = 0; k < 3; k++)
        fm_mesh_destroy(fx->orig[k]);
}

static int b64(char c)
{
    if (c >= 'A' && c <= 'Z')
        return c - 'A';
    if (c >= 'a' && c <= 'z')
        return c - 'a' + 26;
    if (c >= '0' && c <= '9')
        return c - '0' + 52;
    return c == '+' ? 62 : c == '/' ? 63 : -1;
}

typedef struct bytes {
    unsigned char *d;
    size_t n, at;
} bytes;

/* The base64 text from s up to the closing quote, decoded. */
static bytes decode(const char *s)
{
    bytes b = {malloc(strlen(s)), 0, 0};
    unsigned v = 0;
    int bits = 0;
    for (; *s && *s != '"'; s++) {
        int x = b64(*s);
        if (x < 0)
            continue; /* '=' padding */
        v = v << 6 | (unsigned)x;
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            b.d[b.n++] = (unsigned char)(v >> bits & 255);
        }
    }
    return b;
}

static cairo_status_t read_bytes(void *closure, unsigned char *data, unsigned int length)
{
    bytes *b = closure;
    if (b->at + length > b->n)
        return CAIRO_STATUS_READ_ERROR;
    memcpy(data, b->d + b->at, length);
    b->at += length;
    return CAIRO_STATUS_SUCCESS;
}

/* The n-th embedded picture of html, decoded; NULL when there is none or
 * it does not decode. */
static cairo_surface_t *picture(const char *html, int n)
{
    const char *p = html;
    for (int k = 0; p && k <= n; k++) {
        p = strstr(p, "data:image/png;base64,");
        if (p && k < n)
            p++;
    }
    if (!p)
        return NULL;
    bytes b = decode(p + strlen("data:image/png;base64,"));
    cairo_surface_t *s = cairo_image_surface_create_from_png_stream(read_bytes, &b);
    free(b.d);
    if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(s);
        return NULL;
    }
    return s;
}

static uint32_t pixel(cairo_surface_t *s, int x, int y)
{
    const unsigned char *d = cairo_image_surface_get_data(s);
    return ((const uint32_t *)(d + (size_t)y * (size_t)cairo_image_surface_get_stride(s)))[x] &
           0xffffff;
}

/* Pixels of the histograms' bar colour. */
static size_t bar_pixels(cairo_surface_t *s)
{
    size_t n = 0;
    for (int y = 0; y < cairo_image_surface_get_height(s); y++)
        for (int x = 0; x < cairo_image_surface_get_width(s); x++)
            n += pixel(s, x, y) == (69u << 16 | 120u << 8 | 179u);
    return n;
}

static char *write_and_read(fm_report *rep, const char *name)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", TMP, name);
    fm_error err;
    CHECK_EQ(fm_report_write_html(rep, path, &err), FM_OK);
    return fm_test_read_file(path, NULL);
}

static void test_page(void)
{
    fm_mkdir_p(TMP, NULL);
    fixture fx;
    make(&fx);
    char *html = write_and_read(fx.rep, "a.html");
    CHECK(html != NULL);
    if (!html) {
        release(&fx);
        return;
    }
    const char *want[] = {"<td class=\"fn\">Alpha</td>", "<td class=\"fn\">Beta</td>",
                          "<td class=\"fn\">Gamma</td>", "<td class=\"fn\">Epsilon</td>",
                          "could not fit", "cannot read", "too far apart",
                          "a &lt;warning&gt; &amp; more", "<th>faults</th><td>4 read</td>",
                          "2 junctions: 0 crossing, 1 T, 0 corner, 1 unjoined", "EPSG:26711",
                          /* the badge says what its colour means */
                          ">warnings</span>", ">failed</span>", ">dropped</span>",
                          /* junctions numbered from 1, as in every output */
                          "<tr><td class=\"n\">1</td><td class=\"fn\">Alpha</td>",
                          "<tr><td class=\"n\">2</td><td class=\"fn\">Alpha</td>",
                          "<nav class=\"toc\">", "id=\"fm-mesh\"", "id=\"fm-panel\"",
                          "\"ntags\":2"};
    for (size_t k = 0; k < sizeof want / sizeof *want; k++)
        if (!strstr(html, want[k])) {
            fprintf(stderr, "missing: %s\n", want[k]);
            CHECK(0);
        }
    CHECK(!strstr(html, "a <warning>"));
    /* problems first: before the map and the tables */
    const char *problems = strstr(html, "id=\"problems\""), *map_at = strstr(html, "id=\"map\"");
    const char *faults = strstr(html, "id=\"faults\"");
    CHECK(problems && map_at && faults && problems < map_at && map_at < faults);
    /* no badge of a fault not plainly ok reads "ok" */
    CHECK(!strstr(html, "#e69f00\" title=\"meshed, with warnings\">ok<"));
    /* the map and four histograms; the faults are drawn by the page */
    int n = 0;
    for (const char *p = html; (p = strstr(p, "data:image/png")); p++)
        n++;
    CHECK_EQ(n, 5);
    release(&fx);

    cairo_surface_t *map = picture(html, 0);
    CHECK(map != NULL);
    if (map) {
        /* Alpha (green) in the south-west, Gamma (vermilion) in the
         * north-east: east right, north up */
        int w = cairo_image_surface_get_width(map), h = cairo_image_surface_get_height(map);
        double gx = 0, gy = 0, rx = 0, ry = 0;
        size_t ng = 0, nr = 0, purple = 0;
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                uint32_t c = pixel(map, x, y);
                int r = c >> 16 & 255, g = c >> 8 & 255, b = c & 255;
                if (r < 40 && g > 80 && b > 40 && b < g) {
                    gx += x;
                    gy += y;
                    ng++;
                } else if (abs(r - 204) < 20 && abs(g - 121) < 20 && abs(b - 167) < 20) {
                    purple++;
                } else if (r > 120 && b < r / 5 && g < r * 55 / 100 && g > r / 4) {
                    rx += x;
                    ry += y;
                    nr++;
                }
            }
        CHECK(ng > 100);
        /* Delta lies beneath Alpha, its outline drawn over it */
        CHECK(purple > 100);
        CHECK(nr > 20);
        if (ng && nr) {
            CHECK(rx / (double)nr > gx / (double)ng + w / 3.0);
            CHECK(ry / (double)nr < gy / (double)ng - h / 3.0);
        }
        /* one scale for x and y: the set spans 48 km both ways */
        CHECK(abs(w - h) < 60);
        cairo_surface_destroy(map);
    }
    for (int k = 1; k <= 4; k++) {
        cairo_surface_t *hist = picture(html, k);
        CHECK(hist != NULL);
        if (hist) {
            CHECK_EQ(cairo_image_surface_get_width(hist), 380);
            CHECK_EQ(cairo_image_surface_get_height(hist), 230);
            CHECK(bar_pixels(hist) > 100);
            cairo_surface_destroy(hist);
        }
    }
    free(html);
}

static void test_same_bytes(void)
{
    fm_mkdir_p(TMP, NULL);
    fixture a, b;
    make(&a);
    make(&b);
    char *x = write_and_read(a.rep, "x.html"), *y = write_and_read(b.rep, "y.html");
    CHECK(x && y && strcmp(x, y) == 0);
    free(x);
    free(y);
    release(&a);
    release(&b);
}

static void test_unwritable(void)
{
    fixture fx;
    make(&fx);
    fm_error err;
    CHECK(fm_report_write_html(fx.rep, TMP "/no/such/dir/r.html", &err) != FM_OK);
    CHECK(strstr(err.message, "r.html") != NULL);
    struct stat sb;
    CHECK(stat(TMP "/no/such/dir/r.html", &sb) != 0);
    release(&fx);
}

int main(void)
{
    static const fm_test_case cases[] = {FM_CASE(test_page), FM_CASE(test_same_bytes),
                                         FM_CASE(test_unwritable)};
    int rc = fm_test_run(cases, sizeof cases / sizeof cases[0]);
    fm_report_cleanup(); /* cairo's and fontconfig's caches, for the leak checker */
    return rc;
}
