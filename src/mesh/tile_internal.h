/* Rectangular elements (fm_tile.h), private to tile*.c. */
#ifndef FM_TILE_INTERNAL_H
#define FM_TILE_INTERNAL_H

#include <math.h>

#include "fm_sort.h"
#include "fm_tile.h"
#include "fm_vec3.h"

struct fm_tiles {
    fm_tile *tile;
    size_t n, cap;
    fm_tile_fault *fault;
    size_t nfaults;
    fm_tile_junction *junction;
    size_t njunctions;
    fm_tile_stats stats;
    double (*up)[3];     /* per fault, the direction its rows are levels of (tile_up) */
    double (*band)[4];   /* while tiling: each tile's row, its top and bottom level and its
                            width down dip at the fault's mean dip in that band; and
                            whether its columns are open at the start (1) or the end (2)
                            of the strike: it ends its contour there */
    size_t (*left_out)[2]; /* per fault, tiles tile_separate left out: as slivers, and
                              given up with nothing left */
    unsigned char *favour; /* per fault, while tile_settle tiles again: whether its tiles
                              keep their area where they meet another's (NULL: none do) */
    unsigned char *active; /* per fault, while tile_settle tiles again: whether its tiles
                              are cut and grown again (NULL: all are) */
};

/* Whether fault f's tiles are being cut and grown. */
static inline int tile_active(const struct fm_tiles *t, int32_t f)
{
    return !t->active || t->active[f];
}

/* The set's triangle sides (fm_mesh_sides) with, per run of one key,
 * whether triangles of two faults hold it (a junction edge). */
typedef struct tile_sides {
    fm_keyed *side;
    size_t n;
    unsigned char *junction; /* per entry of side, the same for a whole run */
} tile_sides;

/* Tiles of different faults that meet cut back until none does, the one
 * tile_a_gives_way names each time (only the active faults' tiles are
 * split and cut, while tile_settle tiles again); the tiles left too thin
 * counted per fault in left_out; -1 when memory runs out (tile_apart.c). */
int tile_separate(fm_tiles *t);
/* Whether two tiles belong to one surface: of one fault, and of one
 * part of it or tiled with it whole (part 0); tiles of different ones are
 * kept apart. */
static inline int tile_same_unit(const fm_tile *a, const fm_tile *b)
{
    return a->fault == b->fault && (a->part == b->part || !a->part || !b->part);
}

struct tile_walk;
/* The tiles in fault order, each fault's in the order they were made (a
 * split tile's second half comes after the others); -1 when memory runs
 * out (tile_settle.c). */
int tile_by_fault(fm_tiles *t);
/* The tiles as made cut apart (tile_separate) and grown (tile_grow), in
 * fault order; then, where that leaves faults over 3 % short of their
 * area, again with those faults' tiles favoured where they meet others',
 * the second tiling kept if fewer faults end up outside 3 %; -1 when
 * memory runs out (tile_settle.c). */
int tile_settle(fm_tiles *t, const fm_mesh *set, struct tile_walk *w, const size_t *order,
                const size_t *start);
/* Whether tile a, rather than b, is cut where they meet, given what each
 * cut loses: a favoured fault's tile is kept while the other may be cut,
 * otherwise the one losing less goes (tile_apart.c). */
int tile_a_gives_way(const fm_tiles *t, const fm_tile *a, const fm_tile *b, double la, double lb);
/* Whether two tiles meet, by the exact predicates on their triangles
 * (tile_apart.c). */
int tile_meet(const fm_tile *a, const fm_tile *b);
/* Each tile's sides pushed out over the bare surface of its fault beside
 * it, clear of other faults' tiles; the tiles in fault order (tile_by_fault),
 * fault f's triangles order[start[f] .. start[f + 1]) and their area in
 * t->fault[f].area_triangles; -1 when memory runs out (tile_grow.c). */
int tile_grow(fm_tiles *t, const fm_mesh *set, struct tile_walk *w, const size_t *order,
              const size_t *start);
/* A square tile of fault f, side s, centred at c in the plane of
 * triangle k, its strike level (along level[] on a level triangle); 0
 * when the triangle has no plane (tile_fill.c). */
int tile_square(const double *x, const int32_t *tri, size_t k, int32_t f, const double c[3],
                double s, const double level[3], fm_tile *out);
/* Tiles added for each fault at the junction points (where tile_measure
 * measures gaps) that none of its tiles comes within 0.4 of the size of;
 * -1 when memory runs out (tile_fill.c). */
int tile_fill_junctions(fm_tiles *t, const fm_mesh *set, const tile_sides *sd);
/* The surface a tile stands for: the triangles joined to the one under its
 * centre (across the sides nbr joins: not across an outline, a junction
 * or a branch line) that reach into its columns between levels zlo and
 * zhi (tile_level). Found by walking out from that triangle (tile_plane.c). */
typedef struct tile_walk {
    const double *x;
    const double (*up)[3]; /* per fault, as fm_tiles' */
    const int32_t *tri, *nbr;
    uint32_t *stamp; /* per triangle */
    uint32_t cur;
    int32_t *list;   /* the triangles found */
    size_t n;
    int open;        /* the columns run on past the start (1) or the end (2) of the tile */
} tile_walk;
void tile_region(tile_walk *w, const fm_tile *tl, double zlo, double zhi);

/* Each tile's plane (from first on) fitted to the surface it stands for, then a tile over
 * 1.5 times the size wide halved down dip until it is not, and one the
 * surface departs from by more than a 25th of the size split in two
 * (along strike or down dip, whichever leaves it flatter) while its sides
 * stay above an eighth of the size; -1 when memory runs out
 * (tile_plane.c). */
int tile_fit_planes(fm_tiles *t, tile_walk *w, size_t first);
/* Fault's tiles from first on that stand past its outline or a junction,
 * or leave a wedge of their row's surface bare, cut into a quadtree of
 * rectangles on their planes of about a quarter of the size, over the
 * tile those with surface under their centre, past it those over surface
 * of its row that no other tile of the fault covers; -1 when memory runs
 * out (tile_edges.c). */
int tile_refine_edges(fm_tiles *t, tile_walk *w, size_t first);
/* How far the surface w found for tl lies from tl's plane where it lies
 * under tl (tile_region first). */
double tile_flatness(const tile_walk *w, const fm_tile *tl);
/* Where p lies along up: the "depth" a fault's rows are cut by. With up
 * straight up (0, 0, 1) it is p's z exactly. */
static inline double tile_level(const double up[3], const double p[3])
{
    return up[0] * p[0] + up[1] * p[1] + up[2] * p[2];
}

/* The flatness of a tile as it stands, over the surface its level span
 * reaches (tile_plane.c). */
double tile_flat_as_is(tile_walk *w, const fm_tile *tl);
/* Appends a tile of the row ztop..zbot, dw wide down dip (tile.c). */
int tile_push(fm_tiles *t, const fm_tile *tile, double ztop, double zbot, double dw, int open);

/* Below about 2 degrees a depth row no longer says where a tile ends down
 * dip (sin 2 deg). */
#define TILE_MIN_SIN 0.0348994967025

/* The least sine of dip a tile of a row dz deep and dw wide down dip (at
 * the fault's mean dip there) takes: a surface locally flatter than that
 * (or a dip of under 2 degrees) would give a tile reaching far beyond its
 * row, over its neighbours; 1.5 dw at most. */
static inline double tile_min_sin(double dz, double dw)
{
    double s = dw > 0 ? dz / (1.5 * dw) : 0;
    return s > TILE_MIN_SIN ? s : TILE_MIN_SIN;
}

/* A tile's upward normal, dip x strike. */
static inline void tile_normal(const fm_tile *t, double n[3])
{
    fm_cross3(t->dip, t->strike, n);
}

/* A tile's frame by the element convention of the simulator writers,
 * from a horizontal unit strike st and a unit normal n across it (either
 * way up): n made to point up, st turned round if the tile would dip to
 * its left, a vertical tile's strike put in [0, 180); dip = st x n. */
static inline void tile_frame(double st[3], double n[3], double dip[3])
{
    if (n[2] < 0)
        for (int d = 0; d < 3; d++)
            n[d] = -n[d];
    if (n[0] * st[1] - n[1] * st[0] < 0) {
        st[0] = -st[0];
        st[1] = -st[1];
    }
    if (fabs(n[2]) < 1e-12) {
        double az = atan2(st[0], st[1]);
        if (az < 0 || az >= 3.14159265358979323846) {
            st[0] = -st[0];
            st[1] = -st[1];
            n[0] = -n[0];
            n[1] = -n[1];
        }
    }
    fm_cross3(st, n, dip);
}
/* The measures of fm_tile_fault (but its triangles' area, set when the
 * tiling starts), fm_tile_junction and fm_tile_stats; -1 when memory runs
 * out (tile_apart.c). */
int tile_measure(fm_tiles *t, const fm_mesh *set, const tile_sides *sd, struct tile_walk *w);

/* Distance from p to the tile's rectangle, and from p to its plane in
 * *plane (signed, along the upward normal) when plane is not NULL; *inside
 * whether p projects into the rectangle. */
double tile_distance(const fm_tile *t, const double p[3], double *plane, int *inside);

/* Tile centres in cubic cells, for the pairs and points near each other
 * (tile_grid.c). */
typedef struct tile_grid {
    double lo[3], cell;
    fm_keyed *e; /* key: cell, index: tile */
    size_t n;
} tile_grid;
/* Cells of about reach over t's tiles as they are now; -1 when memory runs
 * out (free g->e either way). */
int tile_grid_make(tile_grid *g, const fm_tiles *t, double reach);
/* The same over n points, the i-th at base + i * stride bytes. */
int tile_grid_make_points(tile_grid *g, const void *base, size_t stride, size_t n, double reach);
/* Calls fn for every tile whose centre lies in a cell within reach of p,
 * until it returns non-zero. */
typedef int (*tile_grid_fn)(size_t tile, void *user);
void tile_grid_near(const tile_grid *g, const double p[3], double reach, tile_grid_fn fn,
                    void *user);
/* The distance from p to the nearest tile of fault among those the grid
 * lists within reach of it (tile_apart.c); none when there is none. */
double tile_nearest_of_fault(const tile_grid *g, const fm_tiles *t, const double p[3],
                             double reach, int32_t fault, double none);

#endif
