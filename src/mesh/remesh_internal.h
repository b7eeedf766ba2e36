/* Internals of the surface mesher (fm_remesh.h): the domain in (u, v) as
 * closed loops of nodes, each boundary segment knowing the curve it
 * samples, so that refinement can put new boundary nodes on that curve. */
#ifndef FM_REMESH_INTERNAL_H
#define FM_REMESH_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "fm_cdt.h"
#include "fm_remesh.h"

/* What a boundary segment (or node) lies on. */
typedef enum seg_kind {
    SEG_TRIM = 0,  /* a trimming curve piece: loop, piece, t from ta to tb */
    SEG_LEVEL = 1, /* the sea-level curve of the surface */
    SEG_FREE = 2,  /* a straight line in (u, v) (extension sides, connectors) */
    SEG_SHARED = 3 /* a piece of a curve shared with another sheet: never split */
} seg_kind;

typedef struct dom_seg {
    seg_kind kind;
    int loop;     /* trimming loop (SEG_TRIM) */
    size_t piece;
    double ta, tb; /* curve parameters at the segment's two ends (ta < tb) */
} dom_seg;

typedef struct dom_loop {
    double *uv;    /* 2 per node */
    int *level;    /* per node: 1 when it lies on the sea-level curve */
    dom_seg *seg;  /* seg[i] joins node i to node i + 1 (mod n) */
    size_t n, cap;
} dom_loop;

typedef struct remesh_domain {
    dom_loop *loops;
    size_t n, cap;
} remesh_domain;

void domain_free(remesh_domain *d);
dom_loop *domain_add_loop(remesh_domain *d);
/* Adds a node before node `at` (at == n: at the end, as loop_push). */
int loop_insert(dom_loop *l, size_t at, const double uv[2], int level, const dom_seg *seg);
int loop_push(dom_loop *l, const double uv[2], int level, const dom_seg *seg);

/* Height above sea level (z - level) and its (u, v) gradient. */
double surface_z(const fm_fit_surface *s, const double uv[2], double level, double grad[2]);
/* Moves uv along grad z onto z = level (Newton); returns the final |z - level|. */
double level_project(const fm_fit_surface *s, double uv[2], double level);
/* 3D distance between the surface points at two parameters. */
double surface_dist(const fm_fit_surface *s, const double a[2], const double b[2]);

/* The trimming loops sampled at spacing h along their 3D length, every
 * corner a node. */
fm_status domain_sample(const fm_fit_surface *s, const fm_trim_loop *const *loops,
                        size_t nloops, double h, remesh_domain *out, fm_error *err,
                        const char *name);

/* Splits every trimming-curve segment whose curve strays more than a
 * tenth of h from its chord in 3D, at the farthest point (domain_sag.c);
 * -1 when memory ran out. */
int domain_split_sags(const fm_fit_surface *s, const fm_trim_loop *const *loops,
                      remesh_domain *d, double h);

/* 1 if segments (a, b) and (c, d) cross, touch or overlap (exact). */
int segments_cross(const double *a, const double *b, const double *c, const double *d);
/* Whether chord a-b crosses segment c-e that does not end at a or b; box
 * is the chord's {x0, x1, y0, y1}, which a segment wholly beside it misses
 * before any exact test. */
int chord_crosses_segment(const double *a, const double *b, const double box[4],
                          const double *c, const double *e);

/* Removes nodes where a loop turns back on itself (3D angle below
 * min_angle degrees: a trimming curve that overshoots a corner and
 * returns), when the chord that replaces them crosses nothing. */
void domain_despike(const fm_fit_surface *s, remesh_domain *d, double min_angle);

/* Removes one of two consecutive nodes closer than a quarter of h (3D)
 * when that moves the outline by at most 2 % of h and the new chord
 * crosses nothing; sea-level nodes stay. Returns the nodes removed. */
size_t domain_merge_close(const fm_fit_surface *s, remesh_domain *d, double h);

/* in clipped to z <= level; *cut = 1 when anything was above. */
fm_status domain_clip(const fm_fit_surface *s, const fm_trim_loop *const *loops,
                      const remesh_domain *in, double level, double h, remesh_domain *out,
                      int *cut, fm_error *err, const char *name);

/* Moves the top edge of the outer loop up dip past sea level (by at most
 * `reach` metres of depth) when the top lies less than `reach` below it;
 * *moved = largest up-dip move (m), 0 when nothing moved. */
fm_status domain_extend_top(const fm_fit_surface *s, remesh_domain *d, double level,
                            double reach, double h, double *moved, fm_error *err,
                            const char *name);

/* The point of a segment's curve at fraction f of its way from a to b
 * (for a trimming curve: of its parameter range). */
void segment_point(const fm_fit_surface *s, const fm_trim_loop *const *loops, double level,
                   const dom_seg *sg, const double a[2], const double b[2], double f,
                   double out[2]);

/* The domain as one point list: point k is loop node k in loop order,
 * segment k joins it to the next node of its loop (seg[2k], seg[2k+1]),
 * segs[k] is that segment's curve and ends[4k..4k+3] its two end points. */
typedef struct flat_domain {
    double *uv;
    int *level;
    int32_t *seg;
    dom_seg *segs;
    double *ends;
    size_t n;          /* points; the first n segments are the loops' */
    /* With shared curves (domain_join): more points and segments; per
     * point its shared node id (-1: none); per segment the shared curve it
     * belongs to (-1: none) and whether that curve is one the sheet ends
     * at (keeping the left side; 2: a lone curve, fm_remesh_curve.lone). */
    size_t npoints, nseg;
    int64_t *shared;
    int32_t *curve;
    unsigned char *end;
    /* The surface, and the widest flap (m, 0: any) a curve may cut off
     * (fm_remesh_options.flap_max). */
    const fm_fit_surface *surf;
    double flap_max;
    long *partner;     /* per shared curve: fm_remesh_curve.partner */
    size_t flaps_kept; /* set by join_reduce: flaps wider than flap_max kept */
} flat_domain;
void flat_free(flat_domain *f);

/* Puts the shared curves into the domain (domain_join.c): a curve end
 * within a quarter size of a loop becomes a node of it; the open end of a
 * curve the sheet ends at is joined to the nearest point of the loops by a
 * straight connector; fd receives the loops flattened plus the curves and
 * connectors. dom gains the nodes put on its loops. */
fm_status domain_join(const fm_fit_surface *s, remesh_domain *dom, const fm_remesh_curve *cv,
                      size_t nc, double h, double level, flat_domain *fd, fm_error *err,
                      const char *name);

/* Chooses the faces of a joined domain's arrangement (fd from
 * domain_join, cdt from fm_cdt_create_graph on it) and selects them. */
fm_status join_select(fm_cdt *cdt, const flat_domain *fd, fm_error *err);
/* Reduces fd to the chosen domain's boundary (the first fd->n segments,
 * the domain on their left) and the shared curves inside it. */
fm_status join_reduce(fm_cdt *cdt, flat_domain *fd, fm_error *err);

/* Flattens dom (unless fd already holds a joined domain: fd->npoints > 0),
 * triangulates it and refines it at `size` under the surface metric;
 * caller ids of segments are their flat indices. With shared curves the
 * faces between loops, curves and connectors are chosen: inside the loops,
 * less the flaps beyond curves the sheet ends at, plus the closed gaps
 * before them. */
fm_status domain_triangulate(const fm_fit_surface *s, const fm_trim_loop *const *loops,
                             double level, const remesh_domain *dom, double size,
                             size_t max_points, flat_domain *fd, fm_cdt **out, fm_error *err,
                             const char *name);

/* Where along input segment k (as a fraction of its chord) a point lies. */
double chord_fraction(const double *ends, const double p[2]);

/* The curves under the boundary nodes, for moves along them: point k of
 * the triangulation lies on input segment pseg[k] (-1: none), whose curve
 * is segs[pseg[k]] between ends[4 pseg[k] ..]; points below ninput are the
 * domain's own nodes. */
typedef struct opt_curves {
    const fm_trim_loop *const *loops;
    double level;
    const dom_seg *segs;
    const double *ends;
    const int32_t *pseg;
    size_t ninput;
} opt_curves;

/* slivers.c: every triangle with an angle under min_angle_deg (3D) whose
 * widest corner m is not a shared node (shared[v] >= 0 for v < nshared)
 * and lies on a boundary edge m-p: m merged into p when every other
 * triangle of m keeps its orientation in uv (those of both go), round
 * after round. tri compacted; the number of merges. */
size_t mesh_collapse_slivers(const double *uv, const double *xyz, int32_t *tri, size_t *nt,
                             const int64_t *shared, size_t nshared, double min_angle_deg);

/* The optimisation stage: flips and smoothing in 3D with nodes on the
 * surface. fixed[i] != 0: node i does not move freely; constrained edges
 * are the pairs in cons (ncons of them, the domain on their left). With
 * cv (may be NULL), fixed nodes refinement added on a curve slide along it
 * (slide_boundary). */
typedef struct opt_result {
    size_t flips, smoothed, collapsed, slid;
} opt_result;
fm_status optimise_mesh(const fm_fit_surface *s, double *uv, double *xyz, const unsigned char *fixed,
                        size_t np, int32_t *tri, size_t *nt, const int32_t *cons, size_t ncons,
                        const opt_curves *cv, int passes, double size, opt_result *res);

/* One round of moves of the nodes added on curves (v >= cv->ninput, on a
 * curve, with boundary neighbours prev[v] and next[v]) whose triangles
 * have an angle under 30 degrees: each goes to the point of its curve
 * between the neighbours that makes the smallest 3D angle around it
 * largest (slide.c). start/list: the triangles around each node. Returns
 * the nodes moved. */
size_t slide_boundary(const fm_fit_surface *s, const opt_curves *cv, double *uv, double *xyz,
                      size_t np, const int32_t *tri, const size_t *start, const int32_t *list,
                      const int32_t *prev, const int32_t *next, const int32_t *cons,
                      size_t ncons);

/* The constrained edges (pairs of node indices into uv) an edge may cross,
 * looked up through a grid (cons_grid.c): cons_grid_crosses says whether
 * edge (p, q) crosses one not ending at p or q, exactly as a scan of all
 * would; after node v moves, cons_grid_moved(v) before the next query.
 * cons and uv must outlive the grid. NULL only when out of memory. */
typedef struct cons_grid cons_grid;
cons_grid *cons_grid_create(const double *uv, size_t np, const int32_t *cons, size_t ncons);
void cons_grid_destroy(cons_grid *g);
int cons_grid_crosses(cons_grid *g, const double *uv, int32_t p, int32_t q);
void cons_grid_moved(cons_grid *g, const double *uv, int32_t v);

/* One round of collapses of edges shorter than 0.7 size into a free end
 * (collapse.c); tri is compacted and *nt updated. Returns the count;
 * *nomem set when memory ran out (nothing changed then). */
size_t collapse_short(const double *uv, const double *xyz, const unsigned char *fixed, size_t np,
                      int32_t *tri, size_t *nt, double size, int *nomem);

#endif
