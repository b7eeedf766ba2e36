/* faultmesh write: one coordinate operation between two CRSs for a whole
 * fault set (PROJ).
 *
 * proj_create_crs_to_crs would choose per point among the candidate
 * operations whose area of use holds it, so neighbouring nodes on either
 * side of a border (a coastline, a state line) could get datum shifts
 * metres apart. One operation for the whole set keeps the geometry whole:
 * the first that PROJ ranks for the set's extent among those it can run
 * with the grids installed locally (never the network, so results do not
 * depend on what a CDN serves). Axes are in the order of the traditional
 * GIS view: x east (or longitude), y north (or latitude); z passes
 * through. Not for use by two threads at once. */
#ifndef FM_REPROJECT_H
#define FM_REPROJECT_H

#include <stddef.h>

#include "fm_core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_reproject fm_reproject;

/* Whether PROJ knows both CRSs and an operation between them (a quick
 * check before any work; FM_ERR_INVALID naming both otherwise). */
fm_status fm_reproject_check(const char *from, const char *to, fm_error *err);

/* The operation from `from` to `to` for points in the box bb = {x0, y0,
 * x1, y1} (in `from`); NULL with err set (path names the output it was
 * for) when there is none. */
fm_reproject *fm_reproject_create(const char *from, const char *to, const double bb[4],
                                  const char *path, fm_error *err);
void fm_reproject_destroy(fm_reproject *r);

/* Point (x, y) to (*ox, *oy); -1 when PROJ cannot convert it. */
int fm_reproject_point(const fm_reproject *r, double x, double y, double *ox, double *oy);

/* n points of `stride` doubles from xyz, x and y converted in place;
 * FM_ERR_NUMERIC naming the first it cannot convert. */
fm_status fm_reproject_points(const fm_reproject *r, double *xyz, size_t n, size_t stride,
                              const char *path, fm_error *err);

/* The operation's name, its accuracy ("1 m", "unknown") and its PROJ
 * string, for the files' metadata. */
const char *fm_reproject_name(const fm_reproject *r);
const char *fm_reproject_accuracy(const fm_reproject *r);
const char *fm_reproject_pipeline(const fm_reproject *r);

#ifdef __cplusplus
}
#endif
#endif
