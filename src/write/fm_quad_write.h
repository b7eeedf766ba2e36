/* faultmesh write: a fault set of rectangular elements (fm_tile.h's tiles,
 * or anyone's planar quadrilaterals) for the simulators and codes that
 * read only rectangles: EQSim geometry with record 204, RSQSim's
 * rectangular fault file, and VTU and Gmsh MSH 4.1 with quadrilaterals.
 *
 * Corners: four per element, in EQSim's order: top at the start of the
 * strike, bottom there, bottom at the end, top at the end, so that they
 * run counterclockwise seen from the side the upward normal
 * (c1 - c0) x (c3 - c0) points to, and the element dips to the right of
 * its strike (c3 - c0). Strike and dip follow fm_sim_write.h's convention;
 * rake (Aki & Richards) and slip rate (m/s) are given per element.
 * Elements of one fault are consecutive, faults in ascending order; a
 * fault without elements is left out of the element-wise files. Every
 * file is atomic and byte-identical for identical input. */
#ifndef FM_QUAD_WRITE_H
#define FM_QUAD_WRITE_H

#include <stddef.h>
#include <stdint.h>

#include "fm_core.h"
#include "fm_sim_write.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_quadset {
    const double *corners;     /* 12 per element */
    const int32_t *fault;      /* per element: 0..nfaults-1, ascending */
    const unsigned char *top;  /* per element: 1 on its fault's top row (its upper corners make
                                  the EQSim trace); NULL: none */
    size_t nquads;
    const char *const *names;  /* nfaults UTF-8 names */
    size_t nfaults;
    const char *crs;           /* as fm_faultset's */
    const double *rake;        /* per element, degrees */
    const double *slip_rate;   /* per element, m/s */
    const double *flatness;    /* per element: how far the surface departs from it, m
                                  (VTU cell data); NULL: none */
} fm_quadset;

/* Strike and dip (degrees) of an element's corners by the convention. */
void fm_quad_strike_dip(const double c[12], double *strike, double *dip);

/* VTU: VTK_QUAD cells (type 9), 4 points each in element order; Int32
 * cell data fault_id (the fault number, index + 1), Float64 strike, dip, rake,
 * slip_rate, length, width and flatness (when given); field data
 * fault_names and crs. */
fm_status fm_quadset_write_vtu(const char *path, const fm_quadset *qs, fm_error *err);

/* Gmsh MSH 4.1 ASCII: one surface entity and one physical surface per
 * fault with elements (tag = fault index + 1, name = the fault name as
 * fm_faultset_write_msh writes it), 4-node quadrangles (type 3), node and
 * element tags 1.. in element order. */
fm_status fm_quadset_write_msh(const char *path, const fm_quadset *qs, fm_error *err);

/* RSQSim rectangular fault file: per element one line of 10 columns
 *   x y z L W strike dip rake slip_rate sect_num
 * the centre (metres; z elevation, negative below sea level), length
 * along strike and width down dip (m), strike and dip (degrees), rake
 * (degrees) and slip rate (m/s), section number = fault index + 1. RSQSim
 * tells this file from a triangle file (13 columns) by the column count. */
fm_status fm_quadset_write_rsqsim(const char *path, const fm_quadset *qs, fm_error *err);

/* EQSim input geometry, as fm_faultset_write_eqsim but with rectangles:
 * descriptors of records 200, 201, 202 and 204; per fault with elements
 * one 201 section (no triangles), its 202 vertices (the 4 corners of each
 * element, numbered through the file) and its 204 rectangles (index,
 * vertices 1-4, rake, slip rate, aseismicity 0, strike, dip, perfect
 * flag 1: each element is an exact rectangle in the mesh's coordinates). */
fm_status fm_quadset_write_eqsim(const char *path, const fm_quadset *qs, fm_eqsim_coords coords,
                                 fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
