/* faultmesh run: the CAD faces of a meshed fault (remesh_cad.c). */
#ifndef FM_REMESH_CAD_H
#define FM_REMESH_CAD_H

#include <stddef.h>

#include "fm_cad_write.h"
#include "fm_model.h"
#include "fm_remesh.h"

struct run_ctl;

/* One face per connected part of each sheet's mesh (bounds: one per
 * sheet of m, as fm_remesh_model_joined gives them), all named name, in
 * sheet order; *faces (n of them) to be destroyed by the caller. cut and
 * level: whether the top was cut at sea level, and its z. A face that
 * cannot be made (a meshed sheet, sheet_meshed[s] != 0, without a traced
 * boundary; a trim off the surface's rectangle) is left out with a line
 * to the log and counted in *skipped: the meshes do not depend on the CAD
 * model. Fails only when out of memory. */
fm_status run_cad_faces(const fm_model *m, const fm_remesh_boundary *bounds,
                           const unsigned char *sheet_meshed, const char *name, int cut,
                           double level, fm_cad_face ***faces, size_t *nfaces, size_t *skipped,
                           struct run_ctl *ctl, fm_error *err);

#endif
