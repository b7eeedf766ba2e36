/* faultmesh synth: a synthetic fault system with known true surfaces.
 *
 * It is the embedded default for new users and the ground truth for tests:
 * every fault is an analytic surface x(s, t) over a rectangle of parameters
 * (s along strike, t down dip, metres), triangulated in one of several
 * styles and written as TSurf. Tests measure distances to the true surface
 * with fm_synth_distance. Coordinates are UTM-like metres (zone 11 N, near
 * 34 N 117 W, so that outputs look like CFM), z elevation. */
#ifndef FM_SYNTH_H
#define FM_SYNTH_H

#include <stddef.h>

#include "fm_core.h"
#include "fm_mesh.h"
#include "fm_synthetic.h"

#ifdef __cplusplus
extern "C" {
#endif

/* fm_synth and what the installed API does with it: fm_synthetic.h. */

typedef struct fm_synth_options {
    double spacing;    /* nominal triangle size in metres; default 500 */
    unsigned seed;     /* noise and irregular triangulation; default 1 */
} fm_synth_options;

void fm_synth_options_default(fm_synth_options *opt);

/* Builds the fault system in memory (deterministic for given options). */
fm_status fm_synth_create(const fm_synth_options *opt, fm_synth **out, fm_error *err);

/* Distance in metres from p to the true (noise-free, untrimmed within its
 * parameter rectangle) surface of fault i. */
double fm_synth_distance(const fm_synth *s, size_t i, const double p[3]);

/* Point of the true surface of fault i at parameters (s, t). */
void fm_synth_eval(const fm_synth *s, size_t i, double ps, double pt, double out[3]);

/* --- Additions for the tests of later stages (ground truth). ---
 *
 * A fault has one analytic sheet, or two for the branched fault (sheet 0
 * the through-going sheet, sheet 1 the splay); fm_synth_eval is sheet 0.
 * faults.json documents the formulas; the parameters are metres. */
size_t fm_synth_nsheets(const fm_synth *s, size_t i);
/* Parameter rectangle of a sheet: {s_min, s_max, t_min, t_max}. */
void fm_synth_sheet_rect(const fm_synth *s, size_t i, size_t sheet, double rect[4]);
void fm_synth_eval_sheet(const fm_synth *s, size_t i, size_t sheet, double ps, double pt,
                         double out[3]);
/* Unit normal of a sheet at (s, t), along ds x dt. */
void fm_synth_normal(const fm_synth *s, size_t i, size_t sheet, double ps, double pt,
                     double n[3]);
/* Closest point of the true surface (all sheets) to p; returns the
 * distance, as fm_synth_distance. sheet, ps, pt, foot may be NULL. */
double fm_synth_closest(const fm_synth *s, size_t i, const double p[3], size_t *sheet,
                        double *ps, double *pt, double foot[3]);

/* The triangulation as generated and written (tags = TFACE part), world
 * coordinates. */
const fm_mesh *fm_synth_fault_mesh(const fm_synth *s, size_t i);
/* Index of the fault called name, or -1. */
long fm_synth_find(const fm_synth *s, const char *name);

/* What later stages must find in fault i (also in faults.json). */
typedef struct fm_synth_expect {
    const char *kind;         /* "planar", "listric", "corrugated", ... */
    size_t parts;             /* TFACE parts written */
    size_t seam_vertices;     /* duplicated border vertices (repair welds them) */
    size_t sheets;            /* manifold sheets after repair */
    size_t junctions;         /* junction curves after repair */
    size_t junction_edges;    /* edges with 3 triangles in the file */
    size_t holes;             /* interior boundary loops */
    int blind;                /* 1 when the top is below sea level */
    double top_zmin, top_zmax;/* elevation range of the (noise-free) top edge */
    double bottom_z;
    double noise;             /* max perturbation per coordinate, 0 = exact */
    long gap_to;              /* fault its s = 0 end should meet, -1 none */
    double gap;               /* ... and stops this short of (metres) */
    long overshoot_of;        /* fault its s = 0 end crosses, -1 none */
    long crosses;             /* fault it crosses with an end beyond it by a distance that
                                 grows with depth (no fixed overshoot), -1 none */
    double overshoot;         /* ... and sticks out beyond (metres) */
} fm_synth_expect;
void fm_synth_fault_expect(const fm_synth *s, size_t i, fm_synth_expect *e);

#ifdef __cplusplus
}
#endif
#endif
