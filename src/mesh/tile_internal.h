/* Rectangular elements (fm_tile.h), private to tile*.c. */
#ifndef FM_TILE_INTERNAL_H
#define FM_TILE_INTERNAL_H

#include "fm_sort.h"
#include "fm_tile.h"

struct fm_tiles {
    fm_tile *tile;
    size_t n, cap;
    fm_tile_fault *fault;
    size_t nfaults;
    fm_tile_junction *junction;
    size_t njunctions;
    fm_tile_stats stats;
};

/* The set's triangle sides (fm_mesh_sides) with, per run of one key,
 * whether triangles of two faults hold it (a junction edge). */
typedef struct tile_sides {
    fm_keyed *side;
    size_t n;
    unsigned char *junction; /* per entry of side, the same for a whole run */
} tile_sides;

/* Tiles of different faults that meet cut back until none does, then the
 * measures of fm_tile_fault, fm_tile_junction and fm_tile_stats; -1 when
 * memory runs out (tile_apart.c). */
int tile_separate(fm_tiles *t);
int tile_measure(fm_tiles *t, const fm_mesh *set, const tile_sides *sd);

/* Distance from p to the tile's rectangle, and from p to its plane in
 * *plane (signed, along the upward normal) when plane is not NULL; *inside
 * whether p projects into the rectangle. */
double tile_distance(const fm_tile *t, const double p[3], double *plane, int *inside);

#endif
