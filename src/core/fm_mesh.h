/* faultmesh core: an indexed triangle mesh, the currency between stages.
 *
 * Vertices are stored as x,y,z triples of doubles (metres, z up: elevation,
 * negative below sea level), triangles as three 0-based int32 vertex indices
 * plus one int32 tag per triangle (the TSurf part it came from, a sheet id,
 * a fault id: whatever the producing stage documents). Arrays are
 * contiguous so stages can loop over them directly. */
#ifndef FM_MESH_H
#define FM_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "fm_core.h"
#include "fm_sort.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_mesh fm_mesh;

fm_mesh *fm_mesh_create(void);
void fm_mesh_destroy(fm_mesh *m);
/* Deep copy; NULL on allocation failure. */
fm_mesh *fm_mesh_clone(const fm_mesh *m);

/* Grow capacity so that nv vertices and nt triangles fit. */
fm_status fm_mesh_reserve(fm_mesh *m, size_t nv, size_t nt);

/* Append; return the new index, or -1 when memory runs out. Indices of
 * triangles are not checked here (stages validate where input enters). */
int32_t fm_mesh_add_vertex(fm_mesh *m, double x, double y, double z);
int32_t fm_mesh_add_triangle(fm_mesh *m, int32_t a, int32_t b, int32_t c, int32_t tag);

size_t fm_mesh_nvertices(const fm_mesh *m);
size_t fm_mesh_ntriangles(const fm_mesh *m);

/* 3 doubles per vertex. */
const double *fm_mesh_vertices(const fm_mesh *m);
double *fm_mesh_vertices_mut(fm_mesh *m);
/* 3 indices per triangle. */
const int32_t *fm_mesh_triangles(const fm_mesh *m);
int32_t *fm_mesh_triangles_mut(fm_mesh *m);
/* 1 tag per triangle. */
const int32_t *fm_mesh_tags(const fm_mesh *m);
int32_t *fm_mesh_tags_mut(fm_mesh *m);

/* Appends all of src to dst (vertex indices shifted), every appended
 * triangle tagged with tag: the way several sheets or faults become one
 * mesh for output. */
fm_status fm_mesh_append(fm_mesh *dst, const fm_mesh *src, int32_t tag);

/* Shrink counts (keeps capacity); n must not exceed the current count. */
void fm_mesh_truncate(fm_mesh *m, size_t nv, size_t nt);

/* Removes the triangles t with gone[t] != 0, the others kept in order
 * with their tags (vertices are kept); beside (may be NULL), a value per
 * triangle the caller keeps beside the mesh, is compacted the same way.
 * Returns the number removed. */
size_t fm_mesh_drop_triangles(fm_mesh *m, const unsigned char *gone, int32_t *beside);

/* Quality and size figures of a mesh, as reported by `faultmesh info` and
 * later by the check stage. Angles in degrees, lengths in metres, area in
 * square metres. Edges are counted once (shared edges are not doubled). */
typedef struct fm_mesh_stats {
    size_t vertices, triangles, edges;
    size_t boundary_edges, nonmanifold_edges; /* edges with 1 / >2 triangles */
    size_t unused_vertices;                   /* not referenced by a triangle */
    double area;
    double zmin, zmax;                        /* over referenced vertices */
    double edge_min, edge_max, edge_mean, edge_median;
    double angle_min, angle_mean;             /* minimum angle per triangle */
    double angle_min_p01;                     /* 1st percentile of min angle */
    size_t angle_below_20, angle_below_30;    /* triangles whose min angle is below */
} fm_mesh_stats;

fm_status fm_mesh_compute_stats(const fm_mesh *m, fm_mesh_stats *st);

/* Geometry helpers used by several stages. */
double fm_triangle_area(const double *a, const double *b, const double *c);

/* map[v] for the nv vertices: its index among the vertices nt triangles
 * use (in order), or -1 when none uses it; returns how many are used. */
size_t fm_used_vertices(const int32_t *tri, size_t nt, size_t nv, int32_t *map);
/* Smallest interior angle in degrees (0 for a degenerate triangle). */
double fm_triangle_min_angle(const double *a, const double *b, const double *c);
/* Angle at p between q - p and r - p, degrees (atan2 of |cross| and dot:
 * accurate near 0 and 180). */
double fm_angle_at(const double *p, const double *q, const double *r);
/* Which side of a triangle (its 3 vertex indices) joins vertices u and v,
 * either way: k when it runs from corner k to corner k + 1; -1 when none. */
int fm_triangle_side(const int32_t *tri, int32_t u, int32_t v);
/* Distance from p to the segment a-b (a point when a == b). */
double fm_segment_distance3(const double *p, const double *a, const double *b);

/* Every side of every triangle of m, 3 per triangle, keyed fm_edge_key of
 * its two vertices, index the triangle, sorted by key (stably: a side's
 * triangles in triangle order); *n of them (malloc'ed). NULL when out of
 * memory. */
fm_keyed *fm_mesh_sides(const fm_mesh *m, size_t *n);
/* Sine of the smallest angle: the same order as fm_triangle_min_angle (the
 * smallest angle is at most 60 degrees) without its atan2, for code that
 * only compares triangles (mesh optimisation). 0 for a degenerate one. */
double fm_triangle_min_angle_sin(const double *a, const double *b, const double *c);

#ifdef __cplusplus
}
#endif
#endif
