/* check_connect: stable LSD radix sort of (key, a, b) records by the low
 * `bits` bits of key (the rest must be zero). Records with equal keys keep
 * their order, so sorting by a minor key first and a major one second
 * sorts by both. */
#ifndef CC_SORT_H
#define CC_SORT_H

#include <stddef.h>
#include <stdint.h>

typedef struct cc_rec {
    uint64_t key;
    uint32_t a, b;
} cc_rec;

/* Bits needed for values 0..max. */
int cc_bits(uint64_t max);

/* 0, or -1 when out of memory (r unchanged). */
int cc_radix_sort(cc_rec *r, size_t n, int bits);

#endif
