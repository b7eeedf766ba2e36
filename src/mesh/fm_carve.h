/* faultmesh mesh: the last guard of a conforming fault set.
 *
 * The connect stage makes faults that meet share a curve; where it could
 * not (curves in conflict, faults tangent to each other, the ends of a
 * shared curve), two faults' meshes may still cross or touch. A simulator
 * cannot use elements that pass through each other, so the fault set is
 * searched for every pair of triangles of different faults that have a
 * common point other than the corners and sides they share (exact test,
 * fm_triangles_meet_apart), and of each pair of faults that meet so, one
 * gives way: the triangles of it that meet the other are removed, which
 * leaves a notch about one triangle deep where it met the other instead of
 * two surfaces running through each other. The fault that gives way is the
 * one whose triangles there hold no piece of a curve it shares with some
 * fault, when only one is so (a junction is not undone to clear another);
 * else the one that loses the smaller share of its area (on a tie, the
 * later fault), which spares a small fault touching a large one, unless
 * that would cut it in two (more edge-connected pieces) and the other
 * would stay whole: a piece cut off is an island. No
 * fault is emptied: when the one chosen would lose its last triangles the
 * other gives way, and when both would (at sizes near the faults' own
 * extents) the two are left as they are (kept). Removing triangles never
 * makes a new contact, so afterwards no two triangles of different faults
 * meet except at shared nodes and edges, kept pairs aside.
 * Triangles of the same fault (its sheets) are not compared. A triangle
 * under 20 degrees with a corner on a notch goes with it (it was a sliver
 * at the other fault's curve, and would be one on an open edge now). */
#ifndef FM_CARVE_H
#define FM_CARVE_H

#include <stddef.h>
#include <stdint.h>

#include "fm_core.h"
#include "fm_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A pair of faults (triangle tags) whose triangles met. */
typedef struct fm_carve_pair {
    int32_t fault[2];  /* tags, fault[0] < fault[1] */
    size_t contacts;   /* pairs of their triangles that met */
    int yielded;       /* 0 or 1: the fault whose triangles were removed */
    int kept;          /* 1: neither gave way, as either would have lost every
                          triangle it has left (removed and area are 0) */
    size_t removed;    /* its triangles that met the other, all removed */
    double area;       /* their area, m^2 */
} fm_carve_pair;

typedef struct fm_carve_result fm_carve_result;

/* Removes from set the triangles described above, keeping the order of the
 * others (vertices are kept, some then unused). cell: the side of the
 * search grid's cells (about twice the edge length; <= 0 takes twice the
 * mean edge length). beside (may be NULL): a value per triangle that the
 * caller keeps beside the mesh (a sheet index, say), compacted the same
 * way. threads: up to 2 are used (the search beside the facts the
 * decisions read). *out lists the pairs of faults that met, ordered by
 * tags; it is NULL on failure. Deterministic, whatever the threads. */
fm_status fm_carve_crossings(fm_mesh *set, double cell, int threads, int32_t *beside,
                             fm_carve_result **out, fm_error *err);

size_t fm_carve_npairs(const fm_carve_result *r);
const fm_carve_pair *fm_carve_pair_at(const fm_carve_result *r, size_t k);
/* Triangles removed in all (a triangle that met two faults counts once),
 * and of them the slivers removed with a notch (not in any pair's count). */
size_t fm_carve_removed(const fm_carve_result *r);
size_t fm_carve_slivers(const fm_carve_result *r);
void fm_carve_result_destroy(fm_carve_result *r);

#ifdef __cplusplus
}
#endif
#endif
