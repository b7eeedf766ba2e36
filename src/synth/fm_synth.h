/* faultmesh synth: a synthetic fault system with known true surfaces.
 *
 * It is the embedded default for new users and the ground truth for tests:
 * every fault is an analytic surface x(s, t) over a rectangle of parameters
 * (s along strike, t down dip, metres), triangulated in one of several
 * styles and written as TSurf. Tests measure distances to the true surface
 * with fm_synth_distance. Coordinates are UTM-like metres (zone 11 N, near
 * 34 N 117 W, so that outputs look like CFM), z elevation. */
#ifndef FM_SYNTH_H
#define FM_SYNTH_H

#include <stddef.h>

#include "fm_core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_synth fm_synth;

typedef struct fm_synth_options {
    double spacing;    /* nominal triangle size in metres; default 500 */
    unsigned seed;     /* noise and irregular triangulation; default 1 */
} fm_synth_options;

void fm_synth_options_default(fm_synth_options *opt);

/* Builds the fault system in memory (deterministic for given options). */
fm_status fm_synth_create(const fm_synth_options *opt, fm_synth **out, fm_error *err);
void fm_synth_destroy(fm_synth *s);

size_t fm_synth_nfaults(const fm_synth *s);
const char *fm_synth_fault_name(const fm_synth *s, size_t i);
/* One line on what this fault exercises ("gap of 300 m to ...", ...). */
const char *fm_synth_fault_description(const fm_synth *s, size_t i);

/* Writes one <name>.ts per fault and faults.json (the analytic
 * descriptions and the expected relations: gaps, overshoots, holes, seams)
 * into dir, atomically per file. */
fm_status fm_synth_write(const fm_synth *s, const char *dir, fm_error *err);

/* Distance in metres from p to the true (noise-free, untrimmed within its
 * parameter rectangle) surface of fault i. */
double fm_synth_distance(const fm_synth *s, size_t i, const double p[3]);

/* Point of the true surface of fault i at parameters (s, t). */
void fm_synth_eval(const fm_synth *s, size_t i, double ps, double pt, double out[3]);

#ifdef __cplusplus
}
#endif
#endif
