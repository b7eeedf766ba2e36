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

#ifdef __cplusplus
}
#endif
#endif
