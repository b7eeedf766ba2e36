/* faultmesh mesh: rectangular elements. Every fault of a fault set (an
 * fm_mesh whose triangle tags are fault indices 0..nfaults-1, vertices
 * shared where faults meet) tiled into planar rectangles of about
 * size x size, for the simulators that read only rectangles (EQSim
 * record 204, RSQSim's rectangular patches, Okada-based codes).
 *
 * Rows follow levels: depth, or, for a fault much of which is flat (a
 * detachment, a low-dip thrust, a ramp running into a flat), distance up
 * the dip of its mean plane. The fault's level range is cut into rows of
 * equal down-dip width (the area-weighted slope of each level band turns
 * levels into distance down dip). Columns follow strike: the fault's
 * contour at a row's middle level is cut into pieces of equal length
 * closest to size, each piece one tile. The contour stops where the
 * fault's triangles stop: at its outline, at the sea-level cut and at
 * every junction with another fault (an edge two faults share), so tiles
 * of two faults end at the curve where they meet instead of running
 * through each other. A tile's plane is fitted to the surface in its
 * columns and row (its strike horizontal), its width makes its area that
 * surface's, and it is centred on that surface. Each fault is tiled both
 * ways (where the plane's levels are worth trying) and with the row
 * count closest to size and up to two fewer and more; the tiling whose
 * area and flatness are closest to the triangles' is kept, each also with
 * its edge tiles cut into a quadtree of rectangles down to a quarter of
 * the size that follows a slanted outline or junction (dropping those
 * standing past it, adding those over a bare wedge). Where a fault
 * reaches a junction only as a strip its rows miss, a tile of half the
 * size on the junction covers it. Given its parts (sheets), a fault whose
 * tiling comes over 3 % from its area is tiled part by part as well.
 * Where the tiles still fall short of a fault's area (the rows' widths
 * average their surface, a slanted junction leaves a staircase), they
 * grow into the bare surface beside them and squares fill its wedges.
 *
 * What rectangles cannot do is measured rather than hidden: where the
 * tiles of two faults still meet (a tile's corner past the other fault's
 * plane), the one losing less area is shrunk (cut back along strike or
 * dip, or scaled about its centre) until no two tiles of different faults
 * meet, by the exact predicates; where that leaves a fault over 3 % short
 * of its area, it and its neighbours are tiled again with its tiles kept
 * where the neighbour's may be cut instead. The area each fault keeps,
 * how far the surface departs from each tile's plane, and the gap left
 * along each junction are given per fault and per junction. */
#ifndef FM_TILE_H
#define FM_TILE_H

#include <stddef.h>
#include <stdint.h>

#include "fm_core.h"
#include "fm_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_tile {
    int32_t fault;     /* fault index (the triangle tag) */
    int32_t triangle;  /* the set's triangle under the centre */
    int32_t row;       /* 0 at the fault's top */
    double centre[3];
    double strike[3];  /* unit, horizontal; the tile dips to its right */
    double dip[3];     /* unit, down dip (upward normal = dip x strike) */
    double length;     /* along strike, m */
    double width;      /* down dip, m */
    double flatness;   /* farthest the fault's surface under the tile lies from its plane, m */
    int shrunk;        /* cut back where it met another fault's tile */
    int32_t part;      /* 0: the fault tiled whole; p + 1: its part p tiled on its own */
} fm_tile;

typedef struct fm_tile_fault {
    size_t ntiles;
    double area_triangles; /* the fault's triangles, m^2 */
    double area_tiles;     /* its tiles, m^2 */
    double area_cut;       /* what its tiles lost where they met other faults' tiles, m^2 */
    double flatness_max;   /* m */
} fm_tile_fault;

/* A junction: the edges faults a < b share, and how far their tiles stay
 * from it. */
typedef struct fm_tile_junction {
    int32_t a, b;
    double length;   /* m */
    double gap_max;  /* over the junction's sample points, the larger distance to a tile of
                        either fault, m */
    double gap_mean; /* length-weighted, m */
    double over_half; /* length of junction where the gap exceeds size / 2, m */
} fm_tile_junction;

typedef struct fm_tile_stats {
    double size;          /* the size asked for, m */
    size_t ntiles;
    size_t shrunk;        /* tiles cut back at another fault */
    size_t dropped;       /* tiles given up (nothing left after cutting back) */
    size_t slivers;       /* tiles left out for a side under a twentieth of the size (after
                             cutting back, or where the surface fills a row only thinly):
                             elements that thin only trouble a simulator */
    size_t meeting;       /* pairs of tiles of different faults that still meet: 0 unless a
                             tile could not be cut back */
    size_t unrowed;       /* faults with triangles that could not be tiled (no level range) */
    double flatness_p99;  /* over tiles, m */
    double flatness_max;  /* m */
    double area_ratio_min, area_ratio_max; /* tiles / triangles over faults with tiles */
} fm_tile_stats;

typedef struct fm_tiles fm_tiles;

/* Tiles of every fault of set at size (m, > 0). FM_ERR_INVALID for a
 * size that is not positive and finite or a tag outside 0..nfaults-1,
 * FM_ERR_NOMEM. The same input gives the same tiles, in fault order, row
 * by row from the top, along each contour. */
fm_status fm_tiles_create(const fm_mesh *set, size_t nfaults, double size, fm_tiles **out,
                          fm_error *err);
/* The same, with part (NULL: none) giving per triangle the part of its
 * fault it belongs to (a sheet: non-negative, small). A fault of several
 * parts whose tiles, tiled whole, fall over 3 % short of or over its area
 * (strands side by side, splays off a branch line, which one set of rows
 * cannot follow) is also tiled part by part, in rows by depth, the parts
 * kept apart as two faults are; whichever comes closer to its area is
 * kept. The faults are tiled on up to jobs threads, with the same tiles
 * for any number. */
fm_status fm_tiles_create_parts(const fm_mesh *set, const int32_t *part, size_t nfaults,
                                double size, int jobs, fm_tiles **out, fm_error *err);
void fm_tiles_destroy(fm_tiles *t);

size_t fm_tiles_count(const fm_tiles *t);
const fm_tile *fm_tiles_get(const fm_tiles *t, size_t i);
size_t fm_tiles_nfaults(const fm_tiles *t);
const fm_tile_fault *fm_tiles_fault(const fm_tiles *t, size_t f);
size_t fm_tiles_njunctions(const fm_tiles *t);
const fm_tile_junction *fm_tiles_junction(const fm_tiles *t, size_t i);
const fm_tile_stats *fm_tiles_stats(const fm_tiles *t);

/* The four corners of a tile in EQSim's order: top at the start of the
 * strike, bottom there, bottom at the end, top at the end
 * (counterclockwise seen from the side its upward normal points to). */
void fm_tile_corners(const fm_tile *t, double c[4][3]);

#ifdef __cplusplus
}
#endif
#endif
