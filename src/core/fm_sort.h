/* faultmesh core: sorting and medians of doubles, as every report uses
 * them (one definition of "median" across the project). */
#ifndef FM_SORT_H
#define FM_SORT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Sorts v ascending in place (NaN-free input). */
void fm_sort_doubles(double *v, size_t n);

/* Sorts v in place and returns its median: the middle value, or the mean
 * of the two middle values for an even count; 0 for n == 0. */
double fm_median(double *v, size_t n);

/* A sort key and the index of what it stands for (an edge a-b as
 * a << 32 | b, and the half-edge or triangle it came from). */
typedef struct fm_keyed {
    uint64_t key;
    size_t index;
} fm_keyed;

/* Sorts v by key, stably (equal keys keep their order; entries made in
 * index order come out in (key, index) order), by radix in linear time:
 * what qsort took with a comparator for every mesh's edge list. -1 when
 * out of memory (v unchanged). */
int fm_sort_keyed(fm_keyed *v, size_t n);

/* The first entry of v (sorted by key) whose key is not below key: n when
 * there is none. */
size_t fm_keyed_lower_bound(const fm_keyed *v, size_t n, uint64_t key);

/* The key of the edge between vertices (or nodes) a and b, either way
 * round: the smaller << 32 | the larger (both below 2^32). */
uint64_t fm_edge_key(uint64_t a, uint64_t b);

#ifdef __cplusplus
}
#endif
#endif
