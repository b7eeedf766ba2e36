/* faultmesh core: sorting and medians of doubles, as every report uses
 * them (one definition of "median" across the project). */
#ifndef FM_SORT_H
#define FM_SORT_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Sorts v ascending in place (NaN-free input). */
void fm_sort_doubles(double *v, size_t n);

/* Sorts v in place and returns its median: the middle value, or the mean
 * of the two middle values for an even count; 0 for n == 0. */
double fm_median(double *v, size_t n);

#ifdef __cplusplus
}
#endif
#endif
