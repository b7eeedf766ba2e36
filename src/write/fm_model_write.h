/* faultmesh write: the files of a fitted fault model (fm_model.h).
 *
 *  - JSON (*.model.json): the complete model, documented in docs/guide.md (fit):
 *    per sheet the reference frame, the B-spline surface (degree, knots,
 *    3D control points), the trimming loops (B-spline pieces in (u, v)),
 *    and the fit report. Coordinates in full precision.
 *  - IGES 5.3 (*.igs): one trimmed surface (entity 144) per sheet.
 *  - VTU (*.vtu): the trimmed surface sampled finely, with its distance to
 *    the original triangulation per point and the sheet per triangle. */
#ifndef FM_MODEL_WRITE_H
#define FM_MODEL_WRITE_H

#include <stddef.h>

#include "fm_core.h"
#include "fm_json.h"
#include "fm_model.h"

#ifdef __cplusplus
extern "C" {
#endif

fm_status fm_model_write_json(const char *path, const char *name, const fm_model *m,
                              fm_error *err);
fm_status fm_model_write_iges(const char *path, const char *name, const fm_model *m,
                              fm_error *err);
fm_status fm_model_write_vtu(const char *path, const char *name, const fm_model *m,
                             fm_error *err);

/* The fit report of sheet i as a JSON object (shared by the model file and
 * fit_report.json). Times are not deterministic, so only the run report
 * includes them (with_time). */
void fm_model_write_sheet_report(fm_json *j, const fm_model *m, size_t i, int with_time);

/* The files of a fitted fault (model_files.c): DIR/BASE.EXT for each
 * fm_model_file_ext, each tried whatever became of the others; bit k of
 * *missing and errs[k] for each one not written. FM_OK, or the first
 * failure's status. */
#define FM_MODEL_NFILES 3
extern const char *const fm_model_file_ext[FM_MODEL_NFILES]; /* model.json, igs, vtu */
fm_status fm_model_write_files(const char *dir, const char *base, const char *name,
                               const fm_model *m, unsigned *missing,
                               fm_error errs[FM_MODEL_NFILES]);

/* A fault's figures over its sheets, each sheet weighted by its point
 * counts: RMS and largest distance, original vertices to the surface and
 * trimmed surface to the original, and the largest outline deviation (m). */
typedef struct fm_fault_figures {
    double to_rms, to_max, from_rms, from_max, outline_max;
} fm_fault_figures;
void fm_model_fault_figures(const fm_model *m, fm_fault_figures *f);

#ifdef __cplusplus
}
#endif
#endif
