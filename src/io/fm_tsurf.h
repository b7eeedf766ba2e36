/* faultmesh io: GoCAD TSurf (.ts) reading and writing.
 *
 * A TSurf object is kept as faithfully as the file gives it, so that the
 * writer can reproduce it and the repair stage can report what it changed:
 *  - every VRTX, PVRTX, ATOM and PATOM line becomes one vertex of the mesh,
 *    in file order; an ATOM/PATOM vertex copies the coordinates (and
 *    properties) of the vertex it names and records that vertex in
 *    fm_tsurf_atom_targets() (-1 for an ordinary vertex). Nothing is welded
 *    here: the repair stage welds.
 *  - every TRGL becomes one triangle, tagged with its 0-based TFACE part.
 *  - the original vertex ids are kept (they need not be 1..n).
 *  - the HEADER block, the coordinate-system block, the property names
 *    and the other header lines are kept for the writer.
 * A file may hold several objects ("GOCAD TSurf 1" ... "END" repeated).
 *
 * Coordinates are as in the file: for CFM, UTM metres with z elevation
 * (ZPOSITIVE Elevation). A file whose ZPOSITIVE is Depth is converted on
 * reading to elevation (z negated) and the writer writes Elevation, so that
 * every later stage sees z up. */
#ifndef FM_TSURF_H
#define FM_TSURF_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "fm_core.h"
#include "fm_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_tsurf fm_tsurf;

/* Reads every TSurf object of a file. On success *objects is a malloc'ed
 * array of *count (>= 1) objects, to be freed with fm_tsurf_free_all().
 * On failure nothing is returned and err reads "FILE:LINE: what". */
fm_status fm_tsurf_read_file(const char *path, fm_tsurf ***objects, size_t *count,
                             fm_error *err);
/* Same from memory; name is used in messages. buf need not be
 * NUL-terminated. */
fm_status fm_tsurf_read_buffer(const char *name, const char *buf, size_t len,
                               fm_tsurf ***objects, size_t *count, fm_error *err);
void fm_tsurf_free_all(fm_tsurf **objects, size_t count);

/* Writes objects to path atomically (temporary file, then rename).
 *
 * Output: "GOCAD TSurf 1", the HEADER block, the coordinate-system block
 * (when the object has one: read from a file, or set by fm_tsurf_create),
 * PROPERTIES and the other kept header lines, then one TFACE per part with
 * its vertices (VRTX, or PVRTX when there are properties; ATOM for an atom
 * vertex whose coordinates still equal its target's) and its TRGL lines,
 * then BSTONE/BORDER, END. Coordinates are written in the shortest text
 * that reads back to the same double. Parts without triangles are left out.
 *
 * A vertex is written in the first part whose triangles use it (unused
 * vertices stay with the part before them). GoCAD wants every vertex a
 * part's triangles use declared in that TFACE, so a vertex also used by a
 * later part is declared there again as "ATOM newid id" with a fresh id:
 * reading such output back gives one extra (atom) vertex per such use.
 * Files read from disk already follow that rule and read back identical.
 *
 * Vertex ids are the file's ids when fm_tsurf_vertex_ids() is not NULL,
 * else 1..n. Properties whose values do not cover every vertex make the
 * call fail with FM_ERR_INVALID; a non-finite coordinate with
 * FM_ERR_NUMERIC. Nothing is left under path on failure. */
fm_status fm_tsurf_write_file(const char *path, fm_tsurf *const *objects, size_t count,
                              fm_error *err);
/* Same to an open stream (e.g. stdout); name is used in messages. Not
 * atomic. */
fm_status fm_tsurf_write_stream(FILE *fp, const char *name, fm_tsurf *const *objects,
                                size_t count, fm_error *err);

/* Building an object from scratch (synthetic faults, remeshed output). */
fm_tsurf *fm_tsurf_create(const char *name);
void fm_tsurf_destroy(fm_tsurf *ts);
/* Adds a part; triangles added to the mesh afterwards carry its index as
 * tag. Returns the part index, -1 on allocation failure. */
int fm_tsurf_add_part(fm_tsurf *ts);
/* Sets a HEADER key (replacing an existing one). */
fm_status fm_tsurf_set_header(fm_tsurf *ts, const char *key, const char *value);

/* Names the coordinate system (the NAME line of the
 * GOCAD_ORIGINAL_COORDINATE_SYSTEM block, which the object then has):
 * GoCAD takes any text there, and fm_tsurf_crs_code() reads an
 * authority code such as "EPSG:26711" back from it. FM_ERR_INVALID for a
 * name empty or with a control character, FM_ERR_NOMEM. */
fm_status fm_tsurf_set_crs_name(fm_tsurf *ts, const char *name);

/* The CRS the object's coordinate-system block names unambiguously, as
 * PROJ reads it: its NAME when that is an authority code
 * (letters, ':', then letters, digits, '.', '-' or '_', e.g.
 * "EPSG:26711"), else NULL. The CFM's files say "NAME Default", which
 * names none. The string lives as long as ts. */
const char *fm_tsurf_crs_code(const fm_tsurf *ts);

/* Name from the HEADER (name:...), or "" if none. */
const char *fm_tsurf_name(const fm_tsurf *ts);
/* The geometry: all vertices, triangles tagged by part. */
const fm_mesh *fm_tsurf_mesh(const fm_tsurf *ts);
fm_mesh *fm_tsurf_mesh_mut(fm_tsurf *ts);
size_t fm_tsurf_nparts(const fm_tsurf *ts);

/* Per vertex: the id written in the file (VRTX id). When a tsurf is built
 * with fm_tsurf_create, ids are NULL until written; the writer then uses
 * 1..n. */
const int64_t *fm_tsurf_vertex_ids(const fm_tsurf *ts);
/* Per vertex: index of the vertex an ATOM/PATOM refers to, or -1. NULL when
 * the object has no atoms. */
const int32_t *fm_tsurf_atom_targets(const fm_tsurf *ts);

/* HEADER block entries, in file order ("*solid*color" keys keep their '*'). */
size_t fm_tsurf_nheader(const fm_tsurf *ts);
const char *fm_tsurf_header_key(const fm_tsurf *ts, size_t i);
const char *fm_tsurf_header_value(const fm_tsurf *ts, size_t i);
/* Value for key, or NULL. */
const char *fm_tsurf_header_get(const fm_tsurf *ts, const char *key);

/* Coordinate system (GOCAD_ORIGINAL_COORDINATE_SYSTEM block); fields are ""
 * when absent. */
typedef struct fm_tsurf_crs {
    const char *name;       /* NAME */
    const char *projection; /* PROJECTION, if any */
    const char *datum;      /* DATUM, if any */
    const char *axis_unit;  /* AXIS_UNIT line, as written */
    int z_positive_depth;   /* 1 if ZPOSITIVE Depth (already converted) */
} fm_tsurf_crs;
void fm_tsurf_get_crs(const fm_tsurf *ts, fm_tsurf_crs *crs);

/* Vertex properties (PROPERTIES line + PVRTX columns): nprops names, and
 * nprops values per vertex (row-major), NULL when there are none. */
size_t fm_tsurf_nprops(const fm_tsurf *ts);
const char *fm_tsurf_prop_name(const fm_tsurf *ts, size_t i);
const double *fm_tsurf_prop_values(const fm_tsurf *ts);

/* BSTONE lines (vertex indices) and BORDER lines (id, two vertex indices). */
size_t fm_tsurf_nbstones(const fm_tsurf *ts);
const int32_t *fm_tsurf_bstones(const fm_tsurf *ts);
size_t fm_tsurf_nborders(const fm_tsurf *ts);
const int32_t *fm_tsurf_borders(const fm_tsurf *ts); /* 3 per border: id, v1, v2 */

/* Body lines with a keyword the reader does not know (skipped). */
size_t fm_tsurf_nskipped(const fm_tsurf *ts);

/* Sets the per-vertex ids (n must be the vertex count, ids >= 0 and
 * distinct); ids NULL drops them, so that the writer numbers 1..n. */
fm_status fm_tsurf_set_vertex_ids(fm_tsurf *ts, const int64_t *ids, size_t n);
/* Sets nprops properties (names without blanks) with nprops values per
 * current vertex, row-major; replaces any previous ones. */
fm_status fm_tsurf_set_props(fm_tsurf *ts, size_t nprops, const char *const *names,
                             const double *values);
/* Drops ids, atoms, properties, BSTONE and BORDER lines: for stages that
 * rebuild the vertex set and keep only the header of the object. */
void fm_tsurf_clear_vertex_data(fm_tsurf *ts);

#ifdef __cplusplus
}
#endif
#endif
