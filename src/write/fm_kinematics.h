/* faultmesh write: slip rate and rake of every element from the fault
 * sections of a deformation model (fm_sections.h, NSHM23).
 *
 * Each section becomes a surface: its trace (converted from WGS 84 to the
 * set's CRS by one PROJ operation, fm_reproject.h), oriented by the
 * right-hand rule (the fault dips to the right of the trace; a trace whose
 * right side is more than 90 degrees from DipDir is reversed), each
 * segment swept down-dip at DipDeg from UpDepth to `depth_max` (the
 * sections' LowDepth, 11 to 17 km, is often shallower than the CFM's
 * surfaces, and rates apply down-dip of it too). A section buried below
 * the surface (UpDepth > 0) is tried both ways the data draw it: the
 * trace as the vertical projection of its upper edge, and the trace as
 * the up-dip extension of the plane to the surface.
 *
 * An element takes the section whose surface (either way) is nearest its
 * centroid, within `max_distance`, among those whose plane is within
 * `max_angle` of its own (a fault crossing a section does not take its
 * rate); ties go to the lower section index. Its rake is the section's
 * slip vector (Aki & Richards: strike, dip, rake of the segment) projected
 * onto the element's plane and expressed for its own strike and dip, the
 * vector reversed when the element's upper side faces the section's lower
 * one. Its rate is the section's PrefRate (mm/yr, on the fault plane). */
#ifndef FM_KINEMATICS_H
#define FM_KINEMATICS_H

#include <stddef.h>
#include <stdint.h>

#include "fm_core.h"
#include "fm_faultset_write.h"
#include "fm_sections.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_kinematics_options {
    double max_distance; /* m (default 3000) */
    double max_angle;    /* degrees between the planes (default 45) */
    double depth_max;    /* km, how deep the section surfaces reach (default 40) */
} fm_kinematics_options;

void fm_kinematics_options_default(fm_kinematics_options *o);

typedef struct fm_element_kinematics {
    int32_t section;  /* index in the sections, -1: none within reach */
    int convention;   /* 0: trace over the upper edge, 1: trace at the surface */
    double distance;  /* m, centroid to the section's surface */
    double rake;      /* degrees, for the element's strike and dip (Aki & Richards) */
} fm_element_kinematics;

/* One result per triangle of fs (out: ntriangles entries); fs->crs names
 * the set's CRS. strike and dip (degrees, per triangle, as
 * fm_faultset_strike_dip gives them) define each element's frame. */
fm_status fm_kinematics_assign(const fm_sections *s, const fm_faultset *fs, const double *strike,
                               const double *dip, const fm_kinematics_options *opt,
                               fm_element_kinematics *out, fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
