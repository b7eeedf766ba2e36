/* faultmesh io: the inside of an fm_tsurf, shared by the reader, the writer
 * and the accessors. Not installed; other modules use fm_tsurf.h only. */
#ifndef FM_TSURF_INTERNAL_H
#define FM_TSURF_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "fm_tsurf.h"

/* A growable list of owned strings. */
typedef struct fm_strlist {
    char **items;
    size_t n, cap;
} fm_strlist;

struct fm_tsurf {
    fm_mesh *mesh;
    size_t nparts;

    /* Per-vertex arrays run alongside the mesh while reading. Later stages
     * may grow or shrink the mesh through fm_tsurf_mesh_mut(); an array
     * whose length no longer matches the vertex count is then treated as
     * absent (see the accessors and the writer). */
    int64_t *ids;
    size_t nids, cap_ids;
    int32_t *atoms; /* NULL until the first ATOM/PATOM */
    size_t natoms, cap_atoms;

    /* HEADER block: keys[i]:values[i] in file order. */
    fm_strlist hkeys, hvalues;

    /* Coordinate system block. Lines other than NAME, PROJECTION, DATUM,
     * AXIS_UNIT and ZPOSITIVE (e.g. AXIS_NAME) are kept verbatim in
     * crs_extra so that the writer reproduces them. */
    int has_crs;
    char *crs_name, *crs_projection, *crs_datum, *crs_axis_unit;
    int z_depth;
    fm_strlist crs_extra;

    /* Vertex properties: nprops names, nprops doubles per vertex. */
    fm_strlist prop_names;
    double *props;
    size_t nprop_vertices, cap_prop_vertices;

    /* Header-section lines the reader does not interpret (PROPERTY_CLASS_HEADER
     * blocks, UNITS, ESIZES, ...), verbatim, written back after PROPERTIES. */
    fm_strlist extra;

    int32_t *bstones;
    size_t nbstones, cap_bstones;
    int32_t *borders; /* id, v1, v2 */
    size_t nborders, cap_borders;

    size_t nskipped; /* body lines with an unknown keyword */
};

/* Ensures *p has room for need elements of size elsize; grows by doubling.
 * Returns 0, or -1 when memory runs out (then *p is unchanged). */
int fm_io_grow(void **p, size_t *cap, size_t need, size_t elsize);

/* Copies [s, s+n) into a new NUL-terminated string, NULL on failure. */
char *fm_io_strndup(const char *s, size_t n);

int fm_strlist_push(fm_strlist *l, const char *s, size_t n);
void fm_strlist_free(fm_strlist *l);

/* An empty object (no parts, no crs block). NULL on failure. */
fm_tsurf *fm_tsurf_alloc(void);

#endif
