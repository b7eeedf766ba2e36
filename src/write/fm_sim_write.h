/* faultmesh write: element attributes and the earthquake-simulator formats
 * of a fault set (fm_faultset_write.h): RSQSim fault files and the SCEC
 * simulators' EQSim input geometry.
 *
 * Element orientation. The finite-element formats (MSH, VTU, OBJ, STL,
 * TSurf, Exodus) keep the mesh's winding, consistent within a fault sheet.
 * The element-wise formats here treat each triangle on its own, so each
 * is ordered by this convention: its normal (b - a) x (c - a) points up
 * (z > 0); a vertical one (|n_z| <= 1e-9 |n|, dip within 6e-8 degrees of
 * 90) is ordered so that its strike lies in [0, 180). Strike and dip then
 * follow the right-hand rule: strike in degrees clockwise from north in
 * [0, 360), the fault dipping to the right when looking along strike, dip
 * in [0, 90] from the horizontal; the upward normal's horizontal part
 * points down dip. North is grid north (+y) of the mesh's coordinates
 * (UTM grid north for the CFM, which differs from true north by the
 * meridian convergence, up to about 2.5 degrees across zone 11); a
 * horizontal element has strike 0, a degenerate one strike 0 and dip 0.
 *
 * Section = fault: section number = fault index + 1 (EQSim wants positive
 * ids; the same number as the default MSH physical tag), section name =
 * the fault's short name (fm_names.h: one token of at most 50 bytes,
 * unique, safe for Fortran list-directed reads and rsqsim-python-tools). */
#ifndef FM_SIM_WRITE_H
#define FM_SIM_WRITE_H

#include <stddef.h>

#include "fm_faultset_write.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Strike and dip (degrees) of triangle a, b, c by the convention above;
 * returns 1 when b and c must be swapped to follow it, 0 otherwise. */
int fm_element_orient(const double *a, const double *b, const double *c, double *strike,
                      double *dip);

/* Strike and dip of every triangle of the set (arrays of ntriangles). */
void fm_faultset_strike_dip(const fm_faultset *fs, double *strike, double *dip);

/* Slip of each fault: rake in degrees (Aki & Richards: 0 left-lateral,
 * 180 right-lateral, 90 reverse, -90 normal) and slip rate in m/s, one
 * value per fault (nfaults). */
typedef struct fm_sim_slip {
    const double *rake;
    const double *slip_rate; /* m/s */
    /* Per triangle of the set, in place of its fault's values (a
     * deformation model gives each element its own); NULL: the fault's. */
    const double *rake_t, *slip_rate_t;
} fm_sim_slip;

/* RSQSim triangular fault file: per triangle, faults in index order and
 * mesh order within a fault, one line
 *   x1 y1 z1 x2 y2 z2 x3 y3 z3 rake slip_rate sect_num sect_name
 * in the mesh's coordinates (metres; z elevation, negative below sea
 * level), corners ordered by the element convention, rake in degrees,
 * slip rate in m/s; numbers as the shortest text that reads back to the
 * same double, so a node shared by several triangles is written
 * identically each time. Atomic; validated as every fault-set writer. */
fm_status fm_faultset_write_rsqsim(const char *path, const fm_faultset *fs,
                                   const fm_sim_slip *slip, fm_error *err);

typedef enum fm_eqsim_coords {
    FM_EQSIM_SPHERICAL = 0, /* lat/lon on WGS 84 (EPSG:4326), converted with PROJ */
    FM_EQSIM_RECTANGULAR    /* the mesh's own x (east), y (north), metres */
} fm_eqsim_coords;

/* EQSim input geometry file, spec level 4 (signature EQSim_Input_Geometry_2,
 * format version 0.6, with the coordinate-system field of record 200):
 * metadata (101, 111, 112, 110, 102), descriptors of records 200-203
 * (120, 121, 103), one 200 fault-system summary, then per fault one 201
 * section, its 202 vertices and 203 triangles, and 999 End.
 *
 * Vertices: every vertex of a section's triangles once per section (a
 * node shared by two faults appears in both), numbered 1.. through the
 * file in mesh order within a section. Spherical: lat, lon in decimal
 * degrees (WGS 84), converted from fs->crs by PROJ with one operation for
 * every vertex: the first PROJ ranks for the set's extent among those it
 * can run with the grids installed, network off (per-point choice, as
 * proj_create_crs_to_crs does, could shift neighbouring nodes on either
 * side of an area-of-use border by metres); its name, accuracy and
 * pipeline go into 110 records. For the CFM with Debian's proj-data:
 * "Inverse of UTM zone 11N + NAD27 to WGS 84 (6)", a Helmert shift good
 * to 7 m. Rectangular: y and x in metres in the lat and lon fields. Depth =
 * elevation z in metres, negative underground, unchanged. das = distance
 * along the section's mean strike (metres, in the mesh's coordinates,
 * 0 at the section's first point along strike). trace_flag marks the
 * section's upper edge: boundary edges whose outward direction within
 * their triangle is within 45 degrees of up dip; 2 and 3 the lowest and
 * highest das among them, 1 the others, 0 off the trace.
 *
 * Triangles: corners ordered by the element convention (counterclockwise
 * seen from above, the side the upward normal points to), rake, slip rate
 * (m/s), aseismic factor 0, strike and dip (degrees). Spherical: strike
 * from true north and dip, both recomputed from the converted corners
 * (z taken as height over the WGS 84 ellipsoid) in earth-centred
 * coordinates, seen in the east-north-up frame at the triangle's mean
 * latitude and longitude; rectangular: from grid north.
 *
 * Numbers are the shortest round-trip text; no date, so the file is
 * byte-identical for identical input. */
fm_status fm_faultset_write_eqsim(const char *path, const fm_faultset *fs,
                                  const fm_sim_slip *slip, fm_eqsim_coords coords,
                                  fm_error *err);

/* FM_OK if PROJ knows crs and a way from it to WGS 84: what the
 * spherical EQSim file needs, checked before a long run. */
fm_status fm_eqsim_check_crs(const char *crs, fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
