/* Internal pieces of the fault model (fm_model.h). */
#ifndef FM_MODEL_INTERNAL_H
#define FM_MODEL_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "fm_core.h"
#include "fm_fit.h"
#include "fm_mesh.h"
#include "fm_model.h"
#include "fm_repair.h"
#include "fm_trim.h"

/* A bucket grid over 2D segments of closed polylines, for nearest-segment
 * queries in the parameter plane. */
typedef struct fm_seggrid fm_seggrid;

/* Segments i -> i+1 (mod n) of the closed polyline uv[2n]. */
fm_seggrid *fm_seggrid_create(const double *uv, size_t n, double cell);
void fm_seggrid_destroy(fm_seggrid *g);
/* Nearest segment to p: returns its index, writes the foot and the segment
 * parameter in [0, 1]. */
size_t fm_seggrid_nearest(const fm_seggrid *g, const double p[2], double foot[2], double *t);

/* Midpoint subdivision of a planar triangulation: uv (2 per vertex),
 * triangles, and per vertex the boundary loop it lies on (-1 inside).
 * Each level quarters every triangle; midpoints of boundary edges inherit
 * the loop of the edge. Outputs are malloc'ed. */
typedef struct fm_submesh {
    double *uv;
    int32_t *loop;
    size_t nv;
    int32_t *tri;
    size_t nt;
} fm_submesh;

fm_status fm_submesh_refine(fm_submesh *m, int levels);
void fm_submesh_free(fm_submesh *m);

/* --- model_split.c --- */

/* A cut that splits a ring-shaped sheet: a polyline along sheet edges from
 * one rim to the other, and the pieces on its two sides (indices into the
 * split's pieces; -1 when unknown). */
typedef struct fm_split_cut {
    double *xyz;        /* 3 n */
    size_t n;
    long sheets[2];
    size_t repair_sheet; /* the repaired sheet it cuts */
} fm_split_cut;

typedef struct fm_model_split {
    fm_surface **pieces; /* one sheet each */
    /* Per piece (NULL when none), or for the sheet itself when it stays
     * whole: the fit the decision began (fit_internal.h), to be finished. */
    struct fm_fit_pending **fits;
    struct fm_fit_pending *whole;
    size_t npieces;
    fm_split_cut *cuts;
    size_t ncuts;
} fm_model_split;

/* When sheet `sheet` of s is a ring (two or more boundary loops, no
 * one-to-one plane, and a parametric fit that misses the fit targets), cut
 * it into disks; out->npieces = 0 when it stays whole. */
fm_status fm_model_split_sheet(const char *name, const fm_surface *s, size_t sheet,
                               const fm_fit_options *fit, fm_model_split *out, fm_error *err);
void fm_model_split_free(fm_model_split *sp);

/* --- model.c; model_store.c reads and writes them --- */

typedef struct sheet_model {
    fm_fit_surface *surface;
    fm_trim_loop **loops; /* outer first */
    double *loop_scale;   /* per loop: largest 3D length of a unit (u, v) step */
    size_t nloops;
    fm_mesh *samples;
    double *sample_dist;
    fm_sheet_report report;
} sheet_model;

struct fm_model {
    sheet_model *sheets;
    size_t nsheets;
    fm_split_cut *cuts; /* where rings were cut into disks */
    size_t ncuts;
};

#endif
