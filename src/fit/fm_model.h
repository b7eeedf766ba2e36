/* faultmesh fit: the trimmed surface model of a whole fault.
 *
 * For every sheet of a repaired fault (fm_repair.h) the model holds the
 * fitted B-spline surface (fm_fit.h), its boundary loops fitted as trimming
 * curves in the surface's (u, v) plane (fm_trim.h; loop 0 is the outer
 * boundary, counter-clockwise in (u, v); holes follow, clockwise), a fine
 * sampling of the trimmed surface (for viewing and measuring) and the fit
 * report: distances both ways between the model and the original
 * triangulation, and the deviation of the trimmed outline from the
 * original one.
 *
 * The trimming curves run through the parameters of the surface points
 * closest to the boundary vertices, not through the vertices' own
 * parameters (fm_fit_sheet_vertex_params): where a height field is steep
 * or a parametric map distorted, the surface point at a vertex's own
 * parameters lies hundreds of metres from it although the surface passes
 * within metres, and the outline would follow that offset. */
#ifndef FM_MODEL_H
#define FM_MODEL_H

#include <stddef.h>

#include "fm_core.h"
#include "fm_fit.h"
#include "fm_mesh.h"
#include "fm_repair.h"
#include "fm_trim.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_model_options {
    fm_fit_options fit;
    fm_trim_options trim;
    /* Midpoint subdivisions of the sheet's triangles that sample the trimmed
     * surface (each level quarters the triangles); default 2. */
    int sample_levels;
    /* 1 (default): each sample's distance to the original triangulation is
     * measured (fm_model_sample_distance, report.from_trimmed_*); 0: not
     * (NULL and 0 then), for callers that measure their own output. */
    int measure_samples;
} fm_model_options;

void fm_model_options_default(fm_model_options *opt);

/* What the fit of one sheet achieved. Distances in metres. */
typedef struct fm_sheet_report {
    size_t vertices, triangles;   /* of the original sheet */
    size_t loops, holes, corners, trim_pieces;
    /* original vertices -> fitted surface (closest point) */
    double to_surface_rms, to_surface_max;
    /* samples of the trimmed fitted surface -> original triangulation
     * (the samples on the trimming curves excepted: their offset from the
     * original outline is the outline deviation below) */
    double from_trimmed_rms, from_trimmed_max;
    /* trimmed outline <-> original boundary, both ways, in 3D: the largest
     * distance either way, and the RMS of original boundary vertices to
     * the trimmed outline */
    double outline_max, outline_rms;
    size_t samples;               /* points of the sampled trimmed surface */
    size_t repair_sheet;          /* the repaired sheet this model sheet is (a part of) */
    double time;                  /* seconds, whole sheet */
} fm_sheet_report;

typedef struct fm_model fm_model;

/* Fits every sheet of s. name is used in messages (FILE: ...). A sheet
 * that cannot be fitted fails the whole fault with a message naming it. */
fm_status fm_model_build(const char *name, const fm_surface *s, const fm_model_options *opt,
                         fm_model **out, fm_error *err);
void fm_model_destroy(fm_model *m);

size_t fm_model_nsheets(const fm_model *m);
const fm_fit_surface *fm_model_surface(const fm_model *m, size_t sheet);
size_t fm_model_nloops(const fm_model *m, size_t sheet);
const fm_trim_loop *fm_model_loop(const fm_model *m, size_t sheet, size_t loop);
const fm_sheet_report *fm_model_report(const fm_model *m, size_t sheet);

/* The sampled trimmed surface in 3D (triangle tags: the sheet index) and,
 * per sample point, its distance to the original triangulation. */
const fm_mesh *fm_model_samples(const fm_model *m, size_t sheet);
const double *fm_model_sample_distance(const fm_model *m, size_t sheet);

/* Cuts: a repaired sheet that is a ring (strands that part and rejoin, so
 * that two boundary loops are both outer and no map of it is usable) is
 * cut into disks along polylines of its edges between the two rims (a
 * disk that still needs it is cut again at its narrowest neck), and
 * each disk is a model sheet of its own (report.repair_sheet names the
 * sheet it came from). Like junctions, the cuts are where the remeshed
 * parts must meet again: each is a 3D polyline (n points, 3 doubles each,
 * from the outer rim to the other) with the model sheets on its two sides
 * (-1 if not found). */
size_t fm_model_ncuts(const fm_model *m);
const double *fm_model_cut(const fm_model *m, size_t cut, size_t *npoints, long sheets[2]);

/* A fitted model on disk, for the fit cache (fm_model_cache.h): fitting
 * is most of a run and does not depend on the mesh size, so a later run
 * reads the model instead of fitting again. What it reads is the model
 * written, bit for bit: every field of every sheet (surface, trimming
 * loops, samples, report, statistics and times included) and the cuts,
 * so whatever is made of it is what would be made of the fit.
 *
 * Format (all numbers little-endian; doubles as their IEEE-754 bits):
 *   8 bytes   magic "FMMODEL" 0x1a
 *   u32       format version, FM_MODEL_FORMAT_VERSION
 *   u32       0 (reserved)
 *   32 bytes  the cache key (fm_model_cache.h; zeros from fm_model_save)
 *   u64       payload length L
 *   L bytes   payload: the sheets, then the cuts, field by field
 *             (model_store.c, store_parts.c); counts as u64, ints as
 *             32 bits, arrays preceded by a flag saying whether present
 *   32 bytes  SHA-256 of everything before it
 * so that a truncated, extended or damaged file is detected and rejected
 * (then the caller fits again). The version is raised whenever the
 * payload's layout changes (the build stops on a new field of a stored
 * structure until it is stored). Written through fm_atomic.h: the file
 * appears whole or not at all. */
#define FM_MODEL_FORMAT_VERSION 1

fm_status fm_model_save(const fm_model *m, const char *path, fm_error *err);
/* Fails (FM_ERR_IO, or FM_ERR_PARSE for a file that is not a whole model
 * of this format version) with *out NULL. */
fm_status fm_model_load(const char *path, fm_model **out, fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
