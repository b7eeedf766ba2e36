/* Helpers shared by the simulator writers (private to src/write). */
#ifndef SIM_INTERNAL_H
#define SIM_INTERNAL_H

#include <stdint.h>

#include "fm_sim_write.h"

/* Strike and dip of a triangle with normal n, taken as pointing up
 * (the sign of n[2] is ignored). */
void sim_strike_dip(const double *n, double *strike, double *dip);
/* Corners of triangle t ordered by the element convention; 1 if swapped. */
int sim_corners(const fm_faultset *fs, size_t t, int32_t v[3]);
/* Every fault's section name (fm_section_name), or NULL when memory runs
 * out; freed with sim_section_names_free. */
char **sim_section_names(const fm_faultset *fs);
void sim_section_names_free(char **sect, size_t n);
/* One finite rake and slip rate >= 0 per fault. */
fm_status sim_check_slip(const fm_faultset *fs, const fm_sim_slip *slip, const char *path,
                         fm_error *err);

/* The EQSim geometry file's metadata and descriptors, up to and with
 * 103 End_Descriptor: records 200-202 and 203 (triangles) or 204
 * (rectangles); rp is the spherical conversion (sph). */
struct fs_out;
struct fm_reproject;
void sim_eqsim_head(struct fs_out *o, const char *title, int sph, const struct fm_reproject *rp,
                    const char *crs, int rectangles);
/* Latitude (or y), longitude (or x) and depth ranges of EQSim records 200
 * and 201: sim_bounds_init, then sim_bounds_add per vertex. */
typedef struct sim_bounds {
    double lat[2], lon[2], z[2];
} sim_bounds;
void sim_bounds_init(sim_bounds *b);
void sim_bounds_add(sim_bounds *b, double lat, double lon, double z);
/* Record 200 (the fault system summary; the bounds 0 when empty) and
 * record 201 (a section, sid also its fault id), each a line. */
void sim_eqsim_summary(struct fs_out *o, size_t nsec, size_t nv, size_t ntri, size_t nrect,
                       const sim_bounds *b, int spherical);
void sim_eqsim_section(struct fs_out *o, size_t sid, const char *name, size_t nv, size_t ntri,
                       size_t nrect, const sim_bounds *b, double das_hi);
/* lat (or y) and lon (or x) of the nv points x (3 doubles each) in the
 * EQSim file's coordinates; spherical: from crs to WGS 84 by one PROJ
 * operation (*rp, for the metadata) chosen for the points' extent. Points
 * not used (used non-NULL and 0) are left out and get 0, 0. */
fm_status sim_latlon(const double *x, size_t nv, const unsigned char *used, const char *crs,
                     fm_eqsim_coords coords, double *lat, double *lon,
                     struct fm_reproject **rp, const char *path, fm_error *err);
/* A space and a number (shortest round-trip text) or a whole number. */
void sim_put_num(struct fs_out *o, double v);
void sim_put_int(struct fs_out *o, uint64_t v);
/* Normal of the triangle of three corners given as lat, lon (degrees) and
 * elevation (m) in the east-north-up frame at their mean position. */
void sim_enu_normal(const double lat[3], const double lon[3], const double z[3], double n[3]);

#endif
