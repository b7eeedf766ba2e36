/* faultmesh repair: internal types shared by the repair steps.
 *
 * Conventions used throughout:
 *  - vertex ids are input vertex indices (int32); after welding every
 *    triangle refers to the representative of its group only;
 *  - half-edge h = 3*t + i is the edge of triangle t from corner i to corner
 *    (i+1)%3, as the triangle is stored (before any flip); corner c = 3*t+i
 *    is vertex i of triangle t. Half-edge and corner ids share one number;
 *  - every ordering is derived from indices (never from addresses or hash
 *    layout), so that the same input gives the same output on every run. */
#ifndef FM_REPAIR_INTERNAL_H
#define FM_REPAIR_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "fm_core.h"
#include "fm_mesh.h"
#include "fm_repair.h"

/* Triangles being repaired: vertex ids are representatives (input index
 * space); orig is the input triangle index, tag the input part. */
typedef struct rep_tris {
    size_t n;
    int32_t *v;    /* 3n */
    int32_t *tag;  /* n */
    int32_t *orig; /* n */
} rep_tris;

void rep_tris_free(rep_tris *t);

/* Undirected edges of a rep_tris: half-edges grouped by vertex pair. Edge
 * ids are in increasing (min vertex, max vertex) order, and the half-edges
 * of one edge in increasing id order. */
typedef struct rep_edges {
    size_t ne;
    int32_t *edge_of; /* 3n: edge id of each half-edge */
    int32_t *off;     /* ne+1: edge e owns he[off[e] .. off[e+1]) */
    int32_t *he;      /* 3n: half-edges sorted by edge */
} rep_edges;

fm_status rep_edges_build(const rep_tris *t, size_t nv, rep_edges *e);
void rep_edges_free(rep_edges *e);

/* Union-find whose root is always the smallest element of its set, so the
 * partition and the representatives do not depend on the union order. */
static inline int32_t uf_find(int32_t *parent, int32_t x)
{
    while (parent[x] != x) {
        parent[x] = parent[parent[x]]; /* path halving */
        x = parent[x];
    }
    return x;
}

static inline void uf_union(int32_t *parent, int32_t a, int32_t b)
{
    a = uf_find(parent, a);
    b = uf_find(parent, b);
    if (a < b)
        parent[b] = a;
    else if (b < a)
        parent[a] = b;
}

/* 64-bit finaliser (splitmix64) for the open-addressing tables. */
static inline uint64_t rep_mix64(uint64_t x)
{
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return x;
}

/* Smallest power of two >= 2n (at least 16): table size keeping the load
 * factor at or below one half. 0 on overflow. */
size_t rep_table_size(size_t n);

/* Step 1 (weld.c): rep[v] = lowest input index of v's group. */
fm_status rep_weld_exact(const double *xyz, size_t nv, int32_t *rep, size_t *nwelded);
fm_status rep_weld_tolerance(const double *xyz, size_t nv, double tol, int32_t *rep,
                             size_t *nwelded, fm_error *err);

/* Step 2 (clean.c): triangles of the input remapped through rep, without
 * degenerate or duplicate ones. */
fm_status rep_clean(const fm_mesh *in, const int32_t *rep, rep_tris *out,
                    fm_repair_report *r);
/* Number of representatives no triangle of t uses. */
fm_status rep_count_unused(const rep_tris *t, const int32_t *rep, size_t nv, size_t *unused);

/* Step 3 (fragments.c): drops tiny components from t in place (keeping the
 * order of the others) and fills fragments_* and components. */
fm_status rep_drop_fragments(rep_tris *t, const double *xyz, size_t nv,
                             const fm_repair_options *opt, fm_repair_report *r);

/* Step 4 (pairing.c): nbr[h] = the half-edge across which triangle of h
 * continues in the same sheet, or -1 where h lies on the sheet boundary.
 * With split, triangles around an edge of k > 2 are paired by the flattest
 * dihedral; without, such edges connect nothing. */
fm_status rep_pair_edges(const rep_tris *t, const rep_edges *e, const double *xyz,
                         int split, int32_t *nbr, size_t *nonmanifold_edges);

/* Step 4 (sheets.c): output vertex key of every corner: corners with the
 * same key become one sheet vertex. With split, corners are grouped by the
 * fans that nbr links around their vertex (so pinched vertices come apart;
 * links that would glue a sheet to itself along an edge are cut from nbr
 * first); without, by input vertex (keys are then vertex ids, else corner
 * ids). Runs before rep_sheets, which must see the final links. */
fm_status rep_corner_keys(const rep_tris *t, int32_t *nbr, int split, int32_t *key);
/* Step 4 (sheets.c): sheet id of every triangle, numbered in order of their
 * first triangle. With split, sheets follow nbr; without, they are the
 * edge-connected components. */
fm_status rep_sheets(const rep_tris *t, const rep_edges *e, const int32_t *nbr, int split,
                     int32_t *sheet, size_t *nsheets);

/* Step 5 (orient.c): flip[t] = 1 where triangle t must be reversed; the
 * area-weighted unit normal of each sheet after flipping (zero for a sheet
 * whose area vector vanishes, such as a closed one). */
fm_status rep_orient(const rep_tris *t, const int32_t *nbr, const int32_t *sheet,
                     size_t nsheets, const double *xyz, int orient, uint8_t *flip,
                     double *normals, fm_repair_report *r);

/* The surface object (surface.c). */
typedef struct rep_sheet {
    fm_mesh *mesh;
    int32_t *vorigin; /* input vertex of each sheet vertex */
    int32_t *torigin; /* input triangle of each sheet triangle */
    double normal[3];
    size_t nloops;
    size_t *loop_off; /* nloops+1 */
    int32_t *loop_v;
    long outer;
} rep_sheet;

typedef struct rep_junction {
    size_t npoints;
    double *points;   /* 3 per point */
    int32_t *vorigin; /* input vertex of each point */
    int closed;
    size_t nsheets;
    int32_t *sheets;
} rep_junction;

struct fm_surface {
    fm_repair_report report;
    size_t nsheets;
    rep_sheet *sheets;
    size_t njunctions;
    rep_junction *junctions;
};

fm_surface *rep_surface_create(void);

/* Step 4-5 output (extract.c): one compact mesh per sheet, with its loops;
 * fills vertices_out, triangles_out, nonmanifold_vertices, boundary_loops
 * and holes. */
fm_status rep_extract_sheets(fm_surface *s, const rep_tris *t, const int32_t *sheet,
                             size_t nsheets, const int32_t *key, size_t nkeys,
                             const int32_t *nbr, const uint8_t *flip, const double *normals,
                             const double *xyz, size_t nv);

/* Step 6 (loops.c): boundary loops of a sheet, from the half-edges of its
 * mesh triangles that have no neighbour. bnd[3*i+j] != 0 marks edge j
 * (from corner j to j+1, in the sheet mesh's final orientation) of sheet
 * triangle i as boundary. */
fm_status rep_sheet_loops(rep_sheet *sh, const uint8_t *bnd);

/* Junction curves (junctions.c) along the edges of more than two
 * triangles. */
fm_status rep_junctions(fm_surface *s, const rep_tris *t, const rep_edges *e,
                        const int32_t *sheet, const double *xyz, size_t nv);

#endif
