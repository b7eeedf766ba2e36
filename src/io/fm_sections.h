/* faultmesh io: fault sections of a deformation model (USGS NSHM23, as the
 * USGS and OpenSHA distribute it): GeoJSON FeatureCollections whose
 * features are sections keyed by `FaultID`.
 *
 * The fault sections database (NSHM23_FSD_v3.geojson) gives each section's
 * trace (LineString or MultiLineString, WGS 84 lon/lat, the fault dipping
 * to the right of the trace direction), `DipDeg`, `DipDir` (N, NE, ... W,
 * NW or Vertical), `Rake` (Aki & Richards), `UpDepth` and `LowDepth` (km,
 * positive down) and `FaultName`; the geologic deformation model
 * (NSHM23_GeologicDeformationModel.geojson) its `PrefRate` (mm/yr, on the
 * fault plane). Several files are read as one: the properties of features
 * with the same `FaultID` are merged (a later file's value of a key wins),
 * so the two files, or one file that already joins them, give the same
 * sections. A section lacking a trace, a dip, a rake or depths is left out
 * (counted); one lacking a rate keeps has_rate = 0. */
#ifndef FM_SECTIONS_H
#define FM_SECTIONS_H

#include <stddef.h>

#include "fm_core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_section {
    long id;              /* FaultID */
    const char *name;     /* FaultName ("" if none) */
    double dip;           /* degrees, (0, 90] */
    double dip_dir;       /* azimuth (degrees clockwise from north) of DipDir; NAN: Vertical
                             or not given */
    double rake;          /* degrees, (-180, 180] */
    double up_depth, low_depth; /* km, positive down */
    double rate;          /* PrefRate, mm/yr */
    int has_rate;
    const double *trace;  /* lon, lat pairs, in trace order (parts joined end to end) */
    size_t ntrace;
} fm_section;

typedef struct fm_sections fm_sections;

/* Reads and merges the n files; FM_ERR_PARSE naming the file (and what is
 * wrong) for one that is not a GeoJSON FeatureCollection. */
fm_status fm_sections_read(const char *const *paths, size_t n, fm_sections **out,
                           fm_error *err);
void fm_sections_destroy(fm_sections *s);
size_t fm_sections_count(const fm_sections *s);
const fm_section *fm_sections_get(const fm_sections *s, size_t i);
/* Features left out for lacking a trace, a dip, a rake or depths. */
size_t fm_sections_incomplete(const fm_sections *s);

#ifdef __cplusplus
}
#endif
#endif
