/* faultmesh connect: what the files of the stage share. */
#ifndef FM_CONNECT_INTERNAL_H
#define FM_CONNECT_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "fm_clock.h"
#include "fm_closest.h"
#include "fm_connect.h"

/* One sheet sampled on its knot lattice (see fm_connect.h). */
typedef struct cn_sheet {
    const fm_fit_surface *surf;
    size_t fault, sheet;
    double u0, v0, hs;       /* lattice origin and knot spacing */
    size_t nsu, nsv;         /* spans; nodes (nsu + 1) x (nsv + 1), u fastest */
    double *xyz;             /* per node */
    double *sd;              /* per node: signed outline distance (< 0 inside) */
    double *box;             /* per cell (nsu x nsv): lo[3], hi[3], padded for the bulge */
    unsigned char *active;   /* per cell */
    size_t nactive;
    double lo[3], hi[3];     /* box of the active cells */
    /* sampled trimming loops, (u, v), all loops one after the other */
    double *loop_uv;
    size_t *loop_start;      /* nloops + 1 */
    size_t nloops;
    /* the loops' segments by band of v (point-in-loop tests): segment k
     * joins points seg[2k] and seg[2k + 1]; band j lists band_seg[band_start[j]
     * .. band_start[j + 1] - 1], the segments whose v range meets it */
    uint32_t *seg, *band_seg;
    size_t *band_start, nband;
    double band_v0, band_h;
    fm_closest_tree *outline;  /* outline segments in 3D (degenerate triangles) */
    fm_closest_tree *cells;    /* active cell boxes (degenerate triangles lo, hi, lo) */
    int32_t *cell_id;          /* tree triangle -> cell */
} cn_sheet;

fm_status cn_sheet_build(const fm_model *m, size_t fault, size_t sheet, double reach,
                         cn_sheet *out, fm_error *err);
/* Only the sheet's trimming loops, bands and outline tree (what
 * cn_sheet_inside, cn_sheet_outline_distance, cn_sheet_ray_exit and
 * cn_intersect_emit use), no lattice: the same as cn_sheet_build's. */
fm_status cn_sheet_build_outline(const fm_model *m, size_t fault, size_t sheet, cn_sheet *out,
                                 fm_error *err);
void cn_sheet_free(cn_sheet *s);

/* Every sheet of models[0 .. n-1] (NULL entries skipped), in model then
 * sheet order, built on nthreads threads; the first that fails, in that
 * order, gives the error. */
fm_status cn_sheets_build(const fm_model *const *models, size_t n, double reach, int nthreads,
                          cn_sheet **out, size_t *nout, fm_error *err);
/* The same, but global sheet g only as far as level[g] asks: 0 not at all
 * (left zeroed), 1 its outline (cn_sheet_build_outline), 2 whole; level
 * NULL: all whole. */
fm_status cn_sheets_build_some(const fm_model *const *models, size_t n, double reach,
                               const unsigned char *level, int nthreads, cn_sheet **out,
                               size_t *nout, fm_error *err);
void cn_sheets_free(cn_sheet *s, size_t n);

/* fm_connect_find_pairs on sheets built by cn_sheets_build at the reach
 * of opt (not NULL, checked); stats.time_sample is left 0. */
fm_status cn_find_pairs(const cn_sheet *sh, size_t ns, const fm_connect_options *opt,
                        fm_connect_pairs **out, fm_error *err);
void cn_pairs_set_time_sample(fm_connect_pairs *p, double seconds);
/* Pairs made of pair[0 .. n-1] (copied; sorted as found); NULL when out of
 * memory. */
fm_connect_pairs *cn_pairs_copy(const fm_connect_pair *pair, size_t n);

/* What kept neighbours hold (neighbours.c). */
void cn_neighbours_view(const fm_connect_neighbours *nb, const fm_connect_pair **pair,
                        size_t *npairs, const fm_connect_duplicate **dup, size_t *ndup);
size_t cn_neighbours_nfaults(const fm_connect_neighbours *nb);
/* The runs kept for pair k, when they were traced at join distance
 * `distance` (per-fault distances may differ from run to run under one
 * key); NULL: none such, the pair is traced again. */
const struct cn_runs *cn_neighbours_runs(const fm_connect_neighbours *nb, size_t k,
                                         double distance);
/* The runs plan p traced for pair k and the distance they were traced
 * at; NULL for a pair it did not trace (kept runs, or not decided). */
const struct cn_runs *cn_plan_runs(const fm_connect_plan *p, size_t k, double *distance);

/* fm_connect_intersect on sheets built at the reach of opt (INFINITY when
 * opt->clip_to_reach is 0); opt not NULL, checked. */
fm_status cn_intersect(const cn_sheet *sa, const cn_sheet *sb, const fm_connect_options *opt,
                       fm_connect_curves **out, fm_error *err);

/* fm_connect_intersect in two steps. The trace (sampling, mesh-mesh
 * intersection, chaining, solving, cutting at the reach) gives runs: the
 * solved points (x = uA, vA, uB, vB; p in 3D) of each curve before it is
 * resampled. It depends on the sheets, D (reach) and sample_spacing but
 * not on `spacing` (the plan's, which follows H), so the plan keeps the
 * runs between runs (neighbours.c). The emit resamples the runs at
 * `spacing` and classifies them; it needs of the sheets only what
 * cn_sheet_build_outline makes. cn_intersect is the trace then the emit. */
typedef struct cn_run {
    int closed;
    size_t n;
    double *x, *p; /* 4 and 3 per point */
} cn_run;

typedef struct cn_runs {
    cn_run *r;
    size_t n, cap;
} cn_runs;

void cn_runs_free(cn_runs *rs);
/* Appends a run of n points, copied from x and p (both NULL: left for
 * the caller to fill); -1: out of memory. */
int cn_runs_push(cn_runs *rs, int closed, size_t n, const double *x, const double *p);
fm_status cn_intersect_trace(const cn_sheet *sa, const cn_sheet *sb, const fm_connect_options *opt,
                             cn_runs *rs, fm_error *err);
fm_status cn_intersect_emit(const cn_sheet *sa, const cn_sheet *sb, const fm_connect_options *opt,
                            const cn_runs *rs, fm_connect_curves **out, fm_error *err);

/* 1 when (u, v) lies inside the sampled trimming loops (even-odd). */
int cn_sheet_inside(const cn_sheet *s, double u, double v);
/* Signed distance of S(u, v) = xyz to the outline (< 0 inside). */
double cn_sheet_outline_distance(const cn_sheet *s, double u, double v, const double xyz[3]);
/* Distance along the straight (u, v) ray from (u, v) in direction d (uv per
 * metre of 3D length) to where it first leaves the loops, or INFINITY when
 * that is beyond limit metres. */
double cn_sheet_ray_exit(const cn_sheet *s, const double uv[2], const double d[2], double limit);

/* Marks the active cells of a that have an active cell of b within margin
 * (box distance); returns their number. sel has nsu x nsv entries. */
size_t cn_select_cells(const cn_sheet *a, const cn_sheet *b, double margin, unsigned char *sel);

/* The selected cells subdivided sub x sub and triangulated on one lattice
 * (shared vertices, shared edges). Edge k of triangle t joins tri[3t + k]
 * and tri[3t + (k + 1) % 3]; edges numbered (tedge, ev) only when asked
 * for (the intersection chains through them, distances do not). */
typedef struct cn_zone {
    size_t nv, nt, ne;
    double *xyz, *uv, *sd;   /* per vertex */
    int32_t *tri;            /* 3 per triangle */
    int32_t *tedge;          /* 3 per triangle: edge ids */
    int32_t *ev;             /* 2 per edge, lower vertex id first */
} cn_zone;

fm_status cn_zone_build(const cn_sheet *s, const unsigned char *sel, int sub, int edges,
                        cn_zone *z);
void cn_zone_free(cn_zone *z);
int cn_subdivision(const cn_sheet *s, double sample_spacing);

/* The zone's triangles clipped to sd <= level, as a triangle soup. */
fm_mesh *cn_zone_clip(const cn_zone *z, double level);

/* Exact tests with the perturbation rules of fm_connect.h. ids are global
 * vertex ids that order the vertices (A's below B's). */
int cn_plane_side(const double *a, const double *b, const double *c, const double *p);
int cn_edge_crosses_triangle(const double *p, const double *q, int64_t ip, int64_t iq,
                             const double *const t[3], const int64_t it[3]);

/* Calls fn(user, k) once for every k in [0, n), on nthreads threads (the
 * caller's among them), in no fixed order: fn stores its results by k. */
typedef void (*cn_task_fn)(void *user, size_t k);
void cn_parallel_for(size_t n, int nthreads, cn_task_fn fn, void *user);
/* The same, telling progress(progress_user, base + items done, total)
 * after each item (progress may be NULL); calls to it are serialised. */
void cn_parallel_for_told(size_t n, int nthreads, cn_task_fn fn, void *user,
                          fm_connect_progress_fn progress, void *progress_user, size_t base,
                          size_t total);

#endif
