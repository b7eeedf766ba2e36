/* faultmesh write: VTK XML UnstructuredGrid (.vtu) for ParaView.
 *
 * Triangles (VTK cell type 5) of an fm_mesh, or quadrilaterals (type 9)
 * over a point array. Arrays are written inline as base64
 * "binary" DataArrays with UInt64 headers, little-endian, which ParaView and
 * meshio both read. Coordinates are Float64, in the input CRS's metres.
 * Strings (fault names) have no portable VTU array type that every reader
 * accepts, so a string list is stored as a UInt8 field-data array holding
 * the UTF-8 names, each terminated by a NUL byte. */
#ifndef FM_VTU_H
#define FM_VTU_H

#include <stddef.h>
#include <stdint.h>

#include "fm_core.h"
#include "fm_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum fm_vtu_type { FM_VTU_FLOAT64, FM_VTU_INT32 } fm_vtu_type;

/* One data array: ncomp values per point or per cell. */
typedef struct fm_vtu_array {
    const char *name;
    fm_vtu_type type;
    int ncomp;
    const void *values; /* double or int32_t, n * ncomp of them */
} fm_vtu_array;

typedef struct fm_vtu_strings {
    const char *name;
    const char *const *items;
    size_t count;
} fm_vtu_strings;

typedef struct fm_vtu_content {
    const fm_mesh *mesh; /* NULL: the quadrilaterals at the end */
    const fm_vtu_array *point_data;
    size_t npoint_data;
    const fm_vtu_array *cell_data;
    size_t ncell_data;
    const fm_vtu_strings *field_strings;
    size_t nfield_strings;
    const double *points; /* without a mesh: 3 per point */
    size_t npoints;
    const int32_t *quads; /* and 4 point indices per cell */
    size_t nquads;
} fm_vtu_content;

/* Writes path atomically. */
fm_status fm_vtu_write(const char *path, const fm_vtu_content *c, fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
