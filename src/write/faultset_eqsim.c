/* Fault set as an EQSim input geometry file (SCEC simulators' format,
 * spec level 4, version 0.6). */
#include <math.h>
#include <proj.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_atomic.h"
#include "faultset_internal.h"
#include "fm_reproject.h"
#include "fm_sort.h"
#include "fm_sim_write.h"
#include "fs_out.h"
#include "sim_internal.h"

#define PI 3.14159265358979323846
#define DEG2RAD (PI / 180.0)

/* Record descriptors (120) and their fields (121: index, name, type
 * 1 integer / 2 floating / 3 text, description), as the spec lists them. */
typedef struct field_desc {
    const char *name;
    int type;
    const char *text;
} field_desc;

static const field_desc summary_fields[] = {
    {"n_section", 1, "Total number of fault sections in the file"},
    {"n_vertex", 1, "Total number of vertices in the file"},
    {"n_triangle", 1, "Total number of triangles in the file"},
    {"n_rectangle", 1, "Total number of rectangles in the file"},
    {"lat_lo", 2, "Lowest value of latitude (decimal degrees, positive north) or y (meters)"},
    {"lat_hi", 2, "Highest value of latitude (decimal degrees, positive north) or y (meters)"},
    {"lon_lo", 2, "Lowest value of longitude (decimal degrees, positive east) or x (meters)"},
    {"lon_hi", 2, "Highest value of longitude (decimal degrees, positive east) or x (meters)"},
    {"depth_lo", 2, "Lowest value of depth (meters, negative underground)"},
    {"depth_hi", 2, "Highest value of depth (meters, negative underground)"},
    {"coord_sys", 1, "Coordinate system (0 = spherical, 1 = rectangular)"},
};
static const field_desc section_fields[] = {
    {"sid", 1, "Section identification number (positive integer)"},
    {"name", 3, "Section name"},
    {"n_vertex", 1, "Total number of vertices in the section"},
    {"n_triangle", 1, "Total number of triangles in the section"},
    {"n_rectangle", 1, "Total number of rectangles in the section"},
    {"lat_lo", 2, "Lowest value of latitude (decimal degrees, positive north) or y (meters)"},
    {"lat_hi", 2, "Highest value of latitude (decimal degrees, positive north) or y (meters)"},
    {"lon_lo", 2, "Lowest value of longitude (decimal degrees, positive east) or x (meters)"},
    {"lon_hi", 2, "Highest value of longitude (decimal degrees, positive east) or x (meters)"},
    {"depth_lo", 2, "Lowest value of depth in the section (meters, negative underground)"},
    {"depth_hi", 2, "Highest value of depth in the section (meters, negative underground)"},
    {"das_lo", 2, "Lowest value of distance-along-strike in the section (meters)"},
    {"das_hi", 2, "Highest value of distance-along-strike in the section (meters)"},
    {"fault_id", 1, "Fault identification number (positive integer)"},
};
static const field_desc vertex_fields[] = {
    {"index", 1, "Vertex index number (consecutive integers, starting with 1)"},
    {"lat", 2, "Latitude (decimal degrees, positive north) or y (meters)"},
    {"lon", 2, "Longitude (decimal degrees, positive east) or x (meters)"},
    {"depth", 2, "Depth (meters, negative underground)"},
    {"das", 2, "Distance along strike (meters)"},
    {"trace_flag", 1,
     "Trace flag (0 = not on trace, 1 = on trace but not initial or final, 2 = initial point "
     "on trace, 3 = final point on trace)"},
};
static const field_desc triangle_fields[] = {
    {"index", 1, "Element index number (consecutive integers, starting with 1)"},
    {"vertex_1", 1, "Vertex index number for corner #1 (counting counterclockwise as viewed from positive side of element)"},
    {"vertex_2", 1, "Vertex index number for corner #2 (counting counterclockwise as viewed from positive side of element)"},
    {"vertex_3", 1, "Vertex index number for corner #3 (counting counterclockwise as viewed from positive side of element)"},
    {"rake", 2, "Rake angle (decimal degrees)"},
    {"slip_rate", 2, "Element slip rate (meters/second)"},
    {"aseis_factor", 2, "Element aseismicity factor"},
    {"strike", 2, "Strike angle (decimal degrees)"},
    {"dip", 2, "Dip angle (decimal degrees)"},
};

static void put_record_desc(fs_out *o, int kind, const char *name, const char *text,
                            const field_desc *f, size_t n)
{
    fs_out_printf(o, "120 %d %s %zu    %s\n", kind, name, n, text);
    for (size_t i = 0; i < n; i++)
        fs_out_printf(o, "121 %zu %s %d    Field %zu: %s\n", i + 1, f[i].name, f[i].type, i + 1,
                      f[i].text);
}

void sim_put_num(fs_out *o, double v)
{
    fs_out_char(o, ' ');
    fs_out_double(o, v);
}

void sim_put_int(fs_out *o, uint64_t v)
{
    fs_out_char(o, ' ');
    fs_out_u64(o, v);
}

static const field_desc rectangle_fields[] = {
    {"index", 1, "Element index number (consecutive integers, starting with 1)"},
    {"vertex_1", 1, "Vertex index number for corner #1 (counting counterclockwise as viewed from positive side of element)"},
    {"vertex_2", 1, "Vertex index number for corner #2 (counting counterclockwise as viewed from positive side of element)"},
    {"vertex_3", 1, "Vertex index number for corner #3 (counting counterclockwise as viewed from positive side of element)"},
    {"vertex_4", 1, "Vertex index number for corner #4 (counting counterclockwise as viewed from positive side of element)"},
    {"rake", 2, "Rake angle (decimal degrees)"},
    {"slip_rate", 2, "Element slip rate (meters/second)"},
    {"aseis_factor", 2, "Element aseismicity factor"},
    {"strike", 2, "Strike angle (decimal degrees)"},
    {"dip", 2, "Dip angle (decimal degrees)"},
    {"perfect_flag", 1, "Perfect flag (0 = not perfect rectangle, 1 = perfect rectangle)"},
};

void sim_eqsim_head(fs_out *o, const char *title, int sph, const fm_reproject *rp,
                    const char *crs, int rectangles)
{
    fs_out_str(o, "101 EQSim_Input_Geometry_2 4\n");
    fs_out_printf(o, "111 %s\n", title);
    fs_out_printf(o, "112 faultmesh %s\n", FM_VERSION_STRING);
    if (sph) {
        PJ_INFO pi = proj_info();
        fs_out_printf(o, "110 Coordinates: spherical, latitude and longitude in decimal "
                         "degrees on WGS 84 (EPSG:4326), converted with PROJ %s from %.200s\n",
                      pi.version, crs);
        fs_out_printf(o, "110 PROJ operation (one for every vertex): %s, accuracy %s\n",
                      fm_reproject_name(rp), fm_reproject_accuracy(rp));
        fs_out_str(o, "110 PROJ pipeline: ");
        fs_out_str(o, fm_reproject_pipeline(rp));
        fs_out_char(o, '\n');
        fs_out_printf(o, "110 Strike from true north, dip: from the converted corners in "
                         "earth-centred coordinates (depth as height over the ellipsoid), seen "
                         "in the east-north-up frame at each %s\n",
                      rectangles ? "rectangle" : "triangle");
    } else {
        fs_out_printf(o, "110 Coordinates: rectangular, y (north) in the lat fields and x "
                         "(east) in the lon fields, meters, CRS %.200s\n",
                      crs && crs[0] ? crs : "not given");
        fs_out_str(o, "110 Strike from grid north (+y), dip\n");
    }
    fs_out_str(o, "110 Depth: elevation in meters, negative underground; das: meters along "
                  "the section's mean strike in the mesh's own coordinates\n");
    fs_out_str(o, rectangles ? "110 Rectangle corners: top and bottom at the start of the "
                               "strike, then bottom and top at its end, counterclockwise seen "
                               "from above (the upward normal side); rake: Aki & Richards; "
                               "slip rate: meters/second\n"
                             : "110 Triangle corners counterclockwise seen from above (the "
                               "upward normal side); rake: Aki & Richards; slip rate: "
                               "meters/second\n");
    fs_out_str(o, "102 End_Metadata\n");
    put_record_desc(o, 200, "summary", "Record 200: Fault system summary", summary_fields,
                    sizeof summary_fields / sizeof *summary_fields);
    put_record_desc(o, 201, "section", "Record 201: Fault section information",
                    section_fields, sizeof section_fields / sizeof *section_fields);
    put_record_desc(o, 202, "vertex", "Record 202: Vertex", vertex_fields,
                    sizeof vertex_fields / sizeof *vertex_fields);
    if (rectangles)
        put_record_desc(o, 204, "rectangle", "Record 204: Rectangle", rectangle_fields,
                        sizeof rectangle_fields / sizeof *rectangle_fields);
    else
        put_record_desc(o, 203, "triangle", "Record 203: Triangle", triangle_fields,
                        sizeof triangle_fields / sizeof *triangle_fields);
    fs_out_str(o, "103 End_Descriptor\n");
}

void sim_bounds_init(sim_bounds *b)
{
    for (int k = 0; k < 2; k++)
        b->lat[k] = b->lon[k] = b->z[k] = k ? -INFINITY : INFINITY;
}

void sim_bounds_add(sim_bounds *b, double lat, double lon, double z)
{
    b->lat[0] = fmin(b->lat[0], lat);
    b->lat[1] = fmax(b->lat[1], lat);
    b->lon[0] = fmin(b->lon[0], lon);
    b->lon[1] = fmax(b->lon[1], lon);
    b->z[0] = fmin(b->z[0], z);
    b->z[1] = fmax(b->z[1], z);
}

static void put_bounds(fs_out *o, const sim_bounds *b)
{
    int empty = !(b->lat[0] <= b->lat[1]);
    const double *r[3] = {b->lat, b->lon, b->z};
    for (int k = 0; k < 3; k++)
        for (int e = 0; e < 2; e++)
            sim_put_num(o, empty ? 0 : r[k][e]);
}

void sim_eqsim_summary(fs_out *o, size_t nsec, size_t nv, size_t ntri, size_t nrect,
                       const sim_bounds *b, int spherical)
{
    fs_out_str(o, "200");
    sim_put_int(o, nsec);
    sim_put_int(o, nv);
    sim_put_int(o, ntri);
    sim_put_int(o, nrect);
    put_bounds(o, b);
    sim_put_int(o, spherical ? 0 : 1);
    fs_out_char(o, '\n');
}

void sim_eqsim_section(fs_out *o, size_t sid, const char *name, size_t nv, size_t ntri,
                       size_t nrect, const sim_bounds *b, double das_hi)
{
    fs_out_str(o, "201");
    sim_put_int(o, sid);
    fs_out_char(o, ' ');
    fs_out_str(o, name);
    sim_put_int(o, nv);
    sim_put_int(o, ntri);
    sim_put_int(o, nrect);
    put_bounds(o, b);
    sim_put_num(o, 0);
    sim_put_num(o, das_hi);
    sim_put_int(o, sid);
    fs_out_char(o, '\n');
}

fm_status fm_eqsim_check_crs(const char *crs, fm_error *err)
{
    if (!crs || !crs[0])
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                            "spherical EQSim coordinates need a CRS (--crs)");
    return fm_reproject_check(crs, "EPSG:4326", err);
}

fm_status sim_latlon(const double *x, size_t nv, const unsigned char *used, const char *crs,
                     fm_eqsim_coords coords, double *lat, double *lon, fm_reproject **rp,
                     const char *path, fm_error *err)
{
    if (coords == FM_EQSIM_RECTANGULAR) {
        for (size_t v = 0; v < nv; v++) {
            lat[v] = x[3 * v + 1];
            lon[v] = x[3 * v];
        }
        return FM_OK;
    }
    double bb[4] = {INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < nv; v++)
        if (!used || used[v]) {
            bb[0] = fmin(bb[0], x[3 * v]);
            bb[1] = fmin(bb[1], x[3 * v + 1]);
            bb[2] = fmax(bb[2], x[3 * v]);
            bb[3] = fmax(bb[3], x[3 * v + 1]);
        }
    *rp = fm_reproject_create(crs, "EPSG:4326", bb, path, err);
    fm_status st = *rp ? FM_OK : err ? err->code : FM_ERR_INVALID;
    for (size_t v = 0; v < nv && st == FM_OK; v++) {
        if (used && !used[v]) {
            lat[v] = lon[v] = 0;
            continue;
        }
        if (fm_reproject_point(*rp, x[3 * v], x[3 * v + 1], &lon[v], &lat[v]) ||
            fabs(lat[v]) > 90)
            st = fm_error_set(err, FM_ERR_NUMERIC, path, 0,
                              "PROJ cannot convert vertex %zu (%.3f, %.3f) from '%s' to WGS 84",
                              v, x[3 * v], x[3 * v + 1], crs);
    }
    return st;
}

/* Normal of the triangle p0 p1 p2 given as lat, lon (degrees) and
 * elevation z (m, taken as height over the WGS 84 ellipsoid) in the
 * east-north-up frame at their mean latitude and longitude: true north,
 * metres. The corners go through earth-centred coordinates exactly
 * rather than a flat local approximation, whose curvature error (d^2/2R,
 * 2 cm over 500 m) tilts thin triangles by degrees. */
void sim_enu_normal(const double lat[3], const double lon[3], const double z[3], double n[3])
{
    const double a = 6378137.0, f = 1 / 298.257223563, e2 = f * (2 - f);
    double p[3][3], c[3] = {0, 0, 0};
    for (int k = 0; k < 3; k++) {
        double phi = lat[k] * DEG2RAD, lam = lon[k] * DEG2RAD, s = sin(phi);
        double rn = a / sqrt(1 - e2 * s * s);
        p[k][0] = (rn + z[k]) * cos(phi) * cos(lam);
        p[k][1] = (rn + z[k]) * cos(phi) * sin(lam);
        p[k][2] = (rn * (1 - e2) + z[k]) * s;
        for (int d = 0; d < 3; d++)
            c[d] += p[k][d] / 3;
    }
    double phi = (lat[0] + lat[1] + lat[2]) / 3 * DEG2RAD;
    double lam = (lon[0] + lon[1] + lon[2]) / 3 * DEG2RAD;
    double east[3] = {-sin(lam), cos(lam), 0};
    double north[3] = {-sin(phi) * cos(lam), -sin(phi) * sin(lam), cos(phi)};
    double up[3] = {cos(phi) * cos(lam), cos(phi) * sin(lam), sin(phi)};
    double q[3][3];
    for (int k = 0; k < 3; k++) {
        double r[3] = {p[k][0] - c[0], p[k][1] - c[1], p[k][2] - c[2]};
        q[k][0] = r[0] * east[0] + r[1] * east[1] + r[2] * east[2];
        q[k][1] = r[0] * north[0] + r[1] * north[1] + r[2] * north[2];
        q[k][2] = r[0] * up[0] + r[1] * up[1] + r[2] * up[2];
    }
    double e[3], g[3];
    for (int d = 0; d < 3; d++) {
        e[d] = q[1][d] - q[0][d];
        g[d] = q[2][d] - q[0][d];
    }
    n[0] = e[1] * g[2] - e[2] * g[1];
    n[1] = e[2] * g[0] - e[0] * g[2];
    n[2] = e[0] * g[1] - e[1] * g[0];
}

typedef struct edge_rec {
    uint64_t key;
    int32_t opp; /* the triangle's third vertex */
    uint32_t tri; /* position within the section */
} edge_rec;

/* Scratch of one section, sized for the largest. */
typedef struct section_work {
    int32_t (*corner)[3]; /* oriented corners of each triangle */
    edge_rec *edge;
    fm_keyed *order;      /* edges or vertices in sorted order (radix: qsort took a tenth
                             of the writers' time on a whole-CFM set) */
    int32_t *local;       /* per mesh vertex: index within the section, -1 if not in it */
    int32_t *verts;       /* the section's vertices, ascending */
    double *das;
    unsigned char *trace; /* per mesh vertex */
} section_work;

/* The section's mean strike direction (east, north): the area- and
 * sin(dip)-weighted axial mean of its elements' strikes (axial, so that
 * elements of a vertical fault ordered either way agree), pointed the way
 * most of them point. */
static void mean_strike(const double *x, int32_t (*corner)[3], size_t n, double dir[2])
{
    double c2 = 0, s2 = 0;
    for (size_t i = 0; i < n; i++) {
        const double *a = x + 3 * (size_t)corner[i][0], *b = x + 3 * (size_t)corner[i][1],
                     *c = x + 3 * (size_t)corner[i][2];
        double st, dp;
        fm_element_orient(a, b, c, &st, &dp);
        double area = fm_triangle_area(a, b, c) * sin(dp * DEG2RAD);
        c2 += area * cos(2 * st * DEG2RAD);
        s2 += area * sin(2 * st * DEG2RAD);
    }
    double th = (c2 == 0 && s2 == 0) ? 0 : atan2(s2, c2) / 2;
    double sense = 0;
    for (size_t i = 0; i < n; i++) {
        const double *a = x + 3 * (size_t)corner[i][0], *b = x + 3 * (size_t)corner[i][1],
                     *c = x + 3 * (size_t)corner[i][2];
        double st, dp;
        fm_element_orient(a, b, c, &st, &dp);
        sense += fm_triangle_area(a, b, c) * sin(dp * DEG2RAD) * cos(st * DEG2RAD - th);
    }
    if (sense < 0)
        th += PI;
    dir[0] = sin(th);
    dir[1] = cos(th);
}

/* Marks in w->trace the vertices on the section's upper edge (see the
 * header); returns how many. */
static size_t mark_trace(const double *x, section_work *w, size_t n)
{
    size_t ne = 0;
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            int32_t u = w->corner[i][k], v = w->corner[i][(k + 1) % 3];
            int32_t lo = u < v ? u : v, hi = u < v ? v : u;
            w->edge[ne++] = (edge_rec){((uint64_t)(uint32_t)lo << 32) | (uint32_t)hi,
                                       w->corner[i][(k + 2) % 3], (uint32_t)i};
        }
    /* by key, ties in triangle order (the order they were made in) */
    for (size_t i = 0; i < ne; i++)
        w->order[i] = (fm_keyed){w->edge[i].key, i};
    if (fm_sort_keyed(w->order, ne))
        return SIZE_MAX;
    size_t marked = 0;
    const double cos45 = sqrt(0.5);
    for (size_t i = 0; i < ne;) {
        size_t j = i + 1;
        while (j < ne && w->order[j].key == w->order[i].key)
            j++;
        if (j - i == 1) {
            const edge_rec *er = &w->edge[w->order[i].index];
            int32_t u = (int32_t)(er->key >> 32), v = (int32_t)(er->key & 0xffffffffu);
            const int32_t *c = w->corner[er->tri];
            const double *a = x + 3 * (size_t)c[0], *b = x + 3 * (size_t)c[1],
                         *cc = x + 3 * (size_t)c[2];
            double e1[3], e2[3], nrm[3];
            for (int d = 0; d < 3; d++) {
                e1[d] = b[d] - a[d];
                e2[d] = cc[d] - a[d];
            }
            nrm[0] = e1[1] * e2[2] - e1[2] * e2[1];
            nrm[1] = e1[2] * e2[0] - e1[0] * e2[2];
            nrm[2] = e1[0] * e2[1] - e1[1] * e2[0];
            double len = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
            if (len > 0) {
                for (int d = 0; d < 3; d++)
                    nrm[d] /= len;
                /* Up dip within the element: vertical projected onto it. */
                double ud[3] = {-nrm[2] * nrm[0], -nrm[2] * nrm[1], 1 - nrm[2] * nrm[2]};
                double udl = sqrt(ud[0] * ud[0] + ud[1] * ud[1] + ud[2] * ud[2]);
                const double *pu = x + 3 * (size_t)u, *pv = x + 3 * (size_t)v,
                             *pw = x + 3 * (size_t)er->opp;
                double ed[3], o[3], ee = 0, oe = 0;
                for (int d = 0; d < 3; d++) {
                    ed[d] = pv[d] - pu[d];
                    o[d] = (pu[d] + pv[d]) / 2 - pw[d];
                    ee += ed[d] * ed[d];
                    oe += o[d] * ed[d];
                }
                double ol = 0, dot = 0;
                for (int d = 0; d < 3; d++) {
                    o[d] -= ee > 0 ? oe / ee * ed[d] : 0;
                    ol += o[d] * o[d];
                    dot += o[d] * ud[d];
                }
                ol = sqrt(ol);
                if (udl > 1e-6 && ol > 0 && dot > cos45 * ol * udl) {
                    marked += !w->trace[u] + !w->trace[v];
                    w->trace[u] = w->trace[v] = 1;
                }
            }
        }
        i = j;
    }
    return marked;
}

fm_status fm_faultset_write_eqsim(const char *path, const fm_faultset *fs,
                                  const fm_sim_slip *slip, fm_eqsim_coords coords,
                                  fm_error *err)
{
    fm_status st = fm_faultset_validate(fs, path, err);
    if (st == FM_OK)
        st = sim_check_slip(fs, slip, path, err);
    if (st == FM_OK && coords != FM_EQSIM_SPHERICAL && coords != FM_EQSIM_RECTANGULAR)
        st = fm_error_set(err, FM_ERR_INVALID, path, 0, "unknown EQSim coordinate system %d",
                          (int)coords);
    if (st != FM_OK)
        return st;
    size_t nv = fm_mesh_nvertices(fs->mesh), nt = fm_mesh_ntriangles(fs->mesh);
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh);
    size_t *start = NULL, *order = NULL;
    section_work w = {0};
    fm_reproject *rp = NULL;
    double *lat = malloc((nv + 1) * sizeof *lat), *lon = malloc((nv + 1) * sizeof *lon);
    unsigned char *used = calloc(nv + 1, 1);
    size_t *nvsec = calloc(fs->nfaults + 1, sizeof *nvsec);
    char **sect = sim_section_names(fs);
    int bad = !lat || !lon || !used || !nvsec || !sect ||
              fs_group_by(fm_mesh_tags(fs->mesh), nt, fs->nfaults, &start, &order);
    size_t maxt = 0;
    for (size_t f = 0; !bad && f < fs->nfaults; f++) {
        if (start[f + 1] - start[f] > maxt)
            maxt = start[f + 1] - start[f];
    }
    if (!bad) {
        w.corner = malloc((maxt + 1) * sizeof *w.corner);
        w.edge = malloc((3 * maxt + 1) * sizeof *w.edge);
        w.order = malloc((3 * maxt + 1) * sizeof *w.order);
        w.local = malloc((nv + 1) * sizeof *w.local);
        w.verts = malloc((3 * maxt + 1) * sizeof *w.verts);
        w.das = malloc((3 * maxt + 1) * sizeof *w.das);
        w.trace = calloc(nv + 1, 1);
        bad = !w.corner || !w.edge || !w.order || !w.local || !w.verts || !w.das || !w.trace;
    }
    if (bad)
        st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    /* Vertex counts per section (a shared node counts in each) and the
     * file's bounds, which record 200 gives before any section. */
    size_t nvtotal = 0;
    for (size_t v = 0; st == FM_OK && v < nv; v++)
        w.local[v] = -1;
    for (size_t f = 0; st == FM_OK && f < fs->nfaults; f++) {
        for (size_t i = start[f]; i < start[f + 1]; i++)
            for (int k = 0; k < 3; k++) {
                int32_t v = tri[3 * order[i] + (size_t)k];
                used[v] = 1;
                if (w.local[v] != (int32_t)f) {
                    w.local[v] = (int32_t)f;
                    nvsec[f]++;
                }
            }
        nvtotal += nvsec[f];
    }
    if (st == FM_OK)
        st = sim_latlon(fm_mesh_vertices(fs->mesh), nv, used, fs->crs, coords, lat, lon, &rp, path,
                        err);
    sim_bounds all;
    sim_bounds_init(&all);
    for (size_t v = 0; st == FM_OK && v < nv; v++)
        if (used[v]) {
            sim_bounds_add(&all, lat[v], lon[v], x[3 * v + 2]);
        }
    fm_atomic_file *af = NULL;
    fs_out *o = NULL;
    if (st == FM_OK && !(af = fm_atomic_open(path, err)))
        st = err ? err->code : FM_ERR_IO;
    if (st == FM_OK && !(o = fs_out_open(fm_atomic_stream(af)))) {
        fm_atomic_abort(af);
        st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    if (st == FM_OK) {
        int sph = coords == FM_EQSIM_SPHERICAL;
        char title[160];
        snprintf(title, sizeof title, "faultmesh fault set: %zu sections, %zu triangles",
                 fs->nfaults, nt);
        sim_eqsim_head(o, title, sph, rp, fs->crs, 0);
        sim_eqsim_summary(o, fs->nfaults, nvtotal, nt, 0, &all, sph);

        for (size_t v = 0; v < nv; v++)
            w.local[v] = -1;
        size_t vbase = 0, tbase = 0;
        for (size_t f = 0; f < fs->nfaults; f++) {
            size_t n = start[f + 1] - start[f], nsv = 0;
            for (size_t i = 0; i < n; i++) {
                sim_corners(fs, order[start[f] + i], w.corner[i]);
                for (int k = 0; k < 3; k++) {
                    int32_t v = w.corner[i][k];
                    if (w.local[v] < 0) {
                        w.local[v] = 0;
                        w.verts[nsv++] = v;
                    }
                }
            }
            /* Mesh order of vertices within the section. */
            for (size_t k = 0; k < nsv; k++)
                w.order[k] = (fm_keyed){(uint64_t)(uint32_t)w.verts[k], 0};
            if (fm_sort_keyed(w.order, nsv)) {
                st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
                break;
            }
            for (size_t k = 0; k < nsv; k++)
                w.verts[k] = (int32_t)w.order[k].key;
            for (size_t k = 0; k < nsv; k++)
                w.local[w.verts[k]] = (int32_t)k;
            double dir[2];
            mean_strike(x, w.corner, n, dir);
            double das_lo = INFINITY, das_hi = -INFINITY;
            for (size_t k = 0; k < nsv; k++) {
                const double *p = x + 3 * (size_t)w.verts[k];
                w.das[k] = dir[0] * p[0] + dir[1] * p[1];
                das_lo = fmin(das_lo, w.das[k]);
            }
            for (size_t k = 0; k < nsv; k++) {
                w.das[k] -= das_lo;
                das_hi = fmax(das_hi, w.das[k]);
            }
            if (mark_trace(x, &w, n) == SIZE_MAX) {
                st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
                break;
            }
            size_t first = nsv, last = nsv;
            for (size_t k = 0; k < nsv; k++)
                if (w.trace[w.verts[k]]) {
                    if (first == nsv || w.das[k] < w.das[first])
                        first = k;
                    if (last == nsv || w.das[k] > w.das[last])
                        last = k;
                }
            sim_bounds sb;
            sim_bounds_init(&sb);
            for (size_t k = 0; k < nsv; k++) {
                int32_t v = w.verts[k];
                sim_bounds_add(&sb, lat[v], lon[v], x[3 * (size_t)v + 2]);
            }
            sim_eqsim_section(o, f + 1, sect[f], nsv, n, 0, &sb, das_hi);
            for (size_t k = 0; k < nsv; k++) {
                int32_t v = w.verts[k];
                fs_out_str(o, "202");
                sim_put_int(o, vbase + k + 1);
                sim_put_num(o, lat[v]);
                sim_put_num(o, lon[v]);
                sim_put_num(o, x[3 * (size_t)v + 2]);
                sim_put_num(o, w.das[k]);
                int flag = !w.trace[v] ? 0 : k == first ? 2 : k == last ? 3 : 1;
                sim_put_int(o, (uint64_t)flag);
                fs_out_char(o, '\n');
            }
            for (size_t i = 0; i < n; i++) {
                const int32_t *c = w.corner[i];
                double st_deg, dip_deg;
                if (sph) {
                    double la[3], lo[3], z[3], nrm[3];
                    for (int k = 0; k < 3; k++) {
                        la[k] = lat[c[k]];
                        lo[k] = lon[c[k]];
                        z[k] = x[3 * (size_t)c[k] + 2];
                    }
                    sim_enu_normal(la, lo, z, nrm);
                    sim_strike_dip(nrm, &st_deg, &dip_deg);
                } else {
                    fm_element_orient(x + 3 * (size_t)c[0], x + 3 * (size_t)c[1],
                                      x + 3 * (size_t)c[2], &st_deg, &dip_deg);
                }
                fs_out_str(o, "203");
                sim_put_int(o, tbase + i + 1);
                for (int k = 0; k < 3; k++)
                    sim_put_int(o, vbase + (size_t)w.local[c[k]] + 1);
                size_t t = order[start[f] + i];
                sim_put_num(o, slip->rake_t ? slip->rake_t[t] : slip->rake[f]);
                sim_put_num(o, slip->slip_rate_t ? slip->slip_rate_t[t] : slip->slip_rate[f]);
                sim_put_num(o, 0);
                sim_put_num(o, st_deg);
                sim_put_num(o, dip_deg);
                fs_out_char(o, '\n');
            }
            for (size_t k = 0; k < nsv; k++) {
                w.local[w.verts[k]] = -1;
                w.trace[w.verts[k]] = 0;
            }
            vbase += nsv;
            tbase += n;
        }
        if (st == FM_OK) {
            fs_out_str(o, "999 End\n");
            st = fs_out_commit(o, af, path, err);
        } else {
            fs_out_finish(o);
            fm_atomic_abort(af);
        }
    }
    sim_section_names_free(sect, fs->nfaults);
    free(nvsec);
    free(used);
    free(lat);
    free(lon);
    free(start);
    free(order);
    free(w.corner);
    free(w.edge);
    free(w.order);
    free(w.local);
    free(w.verts);
    free(w.das);
    free(w.trace);
    fm_reproject_destroy(rp);
    return st;
}
