/* faultmesh write: the CAD model of a meshed fault set (model.igs).
 *
 * One IGES 5.3 trimmed surface (144) per connected part of each sheet's
 * mesh: the sheet's fitted B-spline surface (128, fm_fit_surface as is:
 * same knots and control net, written over the spans the trim reaches)
 * trimmed by the domain the mesher meshed, given as closed polygons in the
 * surface's (u, v) plane through the mesh's boundary nodes. A polygon is
 * cut into one curve per stretch between corners (where the boundary
 * passes from the outline to a shared intersection curve or the sea-level
 * line, and where it turns sharply), joined by a 102, so that CAD tools
 * see each stretch as an edge of its own and can sew two faces along the
 * curve they share; each stretch is the C2 cubic (126) through its nodes,
 * so two faces' trims pass through the same nodes, each on its own
 * surface.
 *
 * The faces keep copies of what they need (the model may be freed before
 * the file is written). */
#ifndef FM_CAD_WRITE_H
#define FM_CAD_WRITE_H

#include <stddef.h>

#include "fm_core.h"
#include "fm_fit.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_cad_face fm_cad_face;

/* A face of surface s named name (the fault's name: a 406 form 15 Name
 * property). Loop k is the closed polygon uv[2 start[k]] ..
 * uv[2 (start[k + 1] - 1) + 1] (the last point joins the first, not
 * repeated); loop 0 is the outer one, the rest holes; either sense.
 * corner (may be NULL) flags per point where a new curve starts. Fails
 * (FM_ERR_INVALID) on a loop of fewer than 3 points, a point outside
 * the surface's parameter rectangle by more than 1e-7 of its diagonal, or
 * a loop enclosing no more than 1e-12 of that rectangle's area. */
fm_status fm_cad_face_create(const char *name, const fm_fit_surface *s, const double *uv,
                             const size_t *start, size_t nloops, const unsigned char *corner,
                             fm_cad_face **out, fm_error *err);
void fm_cad_face_destroy(fm_cad_face *f);

/* Writes the faces, in this order, to path (atomically). Units metres;
 * crs (may be NULL) is named in the Start section. The file's date is
 * SOURCE_DATE_EPOCH when set, else 1970-01-01 00:00:00 UTC, so that the
 * same meshes give the same bytes. */
fm_status fm_cad_write_iges(const char *path, const fm_cad_face *const *faces, size_t n,
                            const char *crs, fm_error *err);

/* The same, every control point's x and y converted by rp (crs then names
 * the target CRS). A B-spline surface maps to another through its control
 * points exactly only under an affine map; a conversion between projected
 * CRSs is nearly affine over a control cell (a few kilometres), so the
 * surface follows its converted nodes closely, not exactly (the meshes are
 * converted node by node). */
struct fm_reproject;
fm_status fm_cad_write_iges_reprojected(const char *path, const fm_cad_face *const *faces,
                                        size_t n, const char *crs,
                                        const struct fm_reproject *rp, fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
