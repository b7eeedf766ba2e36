/* Private to src/synth: the analytic description of each fault, shared by
 * the surface evaluator, the triangulator, the closest-point search and the
 * writer.
 *
 * All geometry is kept in a local frame whose origin is the system centre
 * (SYNTH_CENTRE_X, SYNTH_CENTRE_Y, 0): coordinates stay below ~50 km there,
 * so finite differences and Newton steps do not lose digits to the
 * 3.76e6 m northing. World = centre + local, added only at the edges. */
#ifndef FM_SYNTH_INTERNAL_H
#define FM_SYNTH_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "fm_mesh.h"
#include "fm_synth.h"

#define SYNTH_PI 3.14159265358979323846
#define SYNTH_DEG (SYNTH_PI / 180.0)

#define SYNTH_CENTRE_X 450000.0
#define SYNTH_CENTRE_Y 3760000.0
#define SYNTH_MAX_FAULTS 12
#define SYNTH_MAX_SHEETS 2

/* Dip law of a sheet. */
enum synth_law {
    SYNTH_PLANAR,   /* constant dip */
    SYNTH_CIRCULAR, /* listric: circular arc in the dip section */
    SYNTH_SPLAY     /* ruled surface rising from a line on sheet 0 */
};

/* How a sheet is triangulated. */
enum synth_style {
    SYNTH_GRID_FIXED,     /* structured grid, every quad split the same way */
    SYNTH_GRID_ALTERNATE, /* structured grid, diagonals alternate */
    SYNTH_GRID_IRREGULAR  /* graded, jittered, random diagonals, some centre splits */
};

/* The topography that tops reach: a function of map position, written in
 * coordinates along (xi) and across (eta) the main fault's strike so that
 * it peaks on the main fault's trace for every xi (see system.c). */
typedef struct synth_topo {
    double xi[2], eta[2];   /* unit vectors of the frame, local x,y */
    double base;            /* mean elevation */
    double amp_xi, wl_xi, phase_xi;
    double amp_eta, wl_eta;
} synth_topo;

/* One analytic sheet: x(s, t) over [s0, s1] x [0, width]. */
typedef struct synth_sheet {
    int law;
    double origin[2];      /* local x,y of the reference trace at s = 0 */
    double strike_deg;     /* azimuth of increasing s, clockwise from north */
    double s0, s1;         /* parameter range along strike */
    double width;          /* parameter range down dip is [0, width] */
    double dip_deg;        /* SYNTH_PLANAR and SYNTH_SPLAY */
    double dip1_deg, z1;   /* SYNTH_CIRCULAR: dip dip1 at elevation z1 ... */
    double dip2_deg, z2;   /* ... and dip2 at z2 */
    double corr_amp, corr_wavelength, corr_phase_deg; /* corrugation */
    int top_topo;          /* 1: top edge on the topography, 0: at top_z */
    double top_z;
    double bottom_z;
    double junction_t;     /* SYNTH_SPLAY: t of the junction line on sheet 0 */
    double away;           /* SYNTH_SPLAY: +1/-1, side of sheet 0 it rises on */
    /* Derived by synth_sheet_prepare. */
    double us[2], ud[2];   /* strike and (horizontal) dip direction */
    double sin_dip, cos_dip;
    double dip1, radius;   /* radians, metres */
    double w_bot;          /* profile arc length at the bottom */
} synth_sheet;

/* What a fault exercises and what later stages must find in it. */
typedef struct synth_fault {
    char name[96];
    const char *description;
    const char *kind;
    int style;
    size_t nsheets;
    synth_sheet sheet[SYNTH_MAX_SHEETS];
    /* features of the triangulation */
    int hole;              /* remove an interior patch of cells */
    double hole_s, hole_t, hole_rs, hole_rt; /* its centre and radii, metres */
    int seam;              /* two parts with duplicated border vertices */
    double noise;          /* max perturbation per coordinate, metres */
    long gap_to;           /* fault index its s = 0 end should meet, or -1 */
    double gap;            /* metres short of it */
    long overshoot_of;     /* fault index its s = 0 end crosses, or -1 */
    double overshoot;      /* metres beyond it */
    long crosses;          /* fault index it crosses with an end beyond by a distance that
                              grows with depth (the wedge), or -1 */
    /* results of the triangulation */
    fm_mesh *mesh;
    size_t nparts;
    size_t holes;
    size_t seam_vertices;  /* vertices duplicated along the seam */
    double seam_s;         /* s of the seam */
    size_t junction_edges; /* edges shared by 3 triangles */
    double top_zmin, top_zmax; /* over the noise-free top-row vertices */
} synth_fault;

struct fm_synth {
    fm_synth_options opt;
    synth_topo topo;
    size_t nfaults;
    synth_fault fault[SYNTH_MAX_FAULTS];
};

/* surfaces.c */
void synth_sheet_prepare(synth_sheet *sh);
double synth_topo_z(const synth_topo *tp, double x, double y);
double synth_top_z(const fm_synth *sy, const synth_sheet *sh, double s);
/* Local coordinates of sheet k of fault f at (s, t). */
void synth_eval_local(const fm_synth *sy, const synth_fault *f, size_t k, double s, double t,
                      double out[3]);

/* closest.c: closest point of sheet k to local point p; returns distance. */
double synth_closest_local(const fm_synth *sy, const synth_fault *f, size_t k, const double p[3],
                           double *ps, double *pt);
void synth_derivatives(const fm_synth *sy, const synth_fault *f, size_t k, double s, double t,
                       double x[3], double xs[3], double xt[3]);

/* grid.c: nodes (rows along t, columns along s) of a sheet's grid. */
typedef struct synth_grid {
    size_t ns, nt;   /* cells along s and t */
    double *s, *t;   /* node parameters, (nt + 1) x (ns + 1), row-major */
    int32_t *vid;    /* mesh vertex of each node */
} synth_grid;

static inline size_t synth_node(const synth_grid *g, size_t i, size_t j)
{
    return j * (g->ns + 1) + i;
}
int synth_grid_alloc(synth_grid *g, size_t ns, size_t nt);
void synth_grid_free(synth_grid *g);
/* Cells over breakpoints br[0..nb) at spacing h (at least a minimum). */
size_t synth_grid_count_cells(const double *br, size_t nb, double h);
/* Node parameters in the style of the fault (enum synth_style). */
int synth_grid_make(const synth_sheet *sh, int style, double h, const double *sbr, size_t nsb,
                    const double *tbr, size_t ntb, uint64_t *rng, synth_grid *g);
/* Marks removed[j * ns + i] for the cells of the fault's hole. */
void synth_grid_hole_mask(const synth_fault *f, const synth_grid *g, unsigned char *removed);

/* triangulate.c */
fm_status synth_triangulate(const fm_synth *sy, synth_fault *f, uint64_t seed, fm_error *err);

/* system.c */
void synth_layout(fm_synth *sy);

/* A small deterministic generator (splitmix64): the output must not depend
 * on the C library's rand(). */
static inline uint64_t synth_rng_next(uint64_t *state)
{
    uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1). */
static inline double synth_rng_uniform(uint64_t *state)
{
    return (double)(synth_rng_next(state) >> 11) * (1.0 / 9007199254740992.0);
}

#endif
