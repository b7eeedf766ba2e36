#include "fm_sort.h"

#include <stdlib.h>
#include <string.h>

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

void fm_sort_doubles(double *v, size_t n)
{
    if (n > 1)
        qsort(v, n, sizeof *v, cmp_double);
}

double fm_median(double *v, size_t n)
{
    if (n == 0)
        return 0.0;
    fm_sort_doubles(v, n);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* 11-bit digits, 2048 counts each staying in cache. Only the bits in which
 * the keys differ are sorted on, each digit starting at the next such bit:
 * an edge key (fm_edge_key) of vertex numbers under 2^22 takes four
 * passes, not the five of digits at fixed places (the high bits of the
 * low number and the low bit of the high one fall in one). */
#define RADIX_BITS 11
#define RADIX_DIGITS 6
#define RADIX_SIZE (1 << RADIX_BITS)

static int lowest_bit(uint64_t x)
{
    int b = 0;
    while (!(x & 1)) {
        x >>= 1;
        b++;
    }
    return b;
}

int fm_sort_keyed(fm_keyed *v, size_t n)
{
    if (n < 2)
        return 0;
    if (n <= 32) { /* insertion sort: stable */
        for (size_t i = 1; i < n; i++) {
            fm_keyed x = v[i];
            size_t j = i;
            while (j > 0 && v[j - 1].key > x.key) {
                v[j] = v[j - 1];
                j--;
            }
            v[j] = x;
        }
        return 0;
    }
    uint64_t differ = 0;
    for (size_t i = 1; i < n; i++)
        differ |= v[i].key ^ v[0].key;
    if (!differ)
        return 0;
    unsigned shift[RADIX_DIGITS];
    int nd = 0;
    for (int at = lowest_bit(differ); nd < RADIX_DIGITS;) {
        shift[nd++] = (unsigned)at;
        at += RADIX_BITS;
        if (at >= 64 || !(differ >> at))
            break;
        at += lowest_bit(differ >> at);
    }
    size_t(*count)[RADIX_SIZE] = calloc((size_t)nd, sizeof *count);
    fm_keyed *tmp = malloc(n * sizeof *tmp);
    if (!count || !tmp) {
        free(count);
        free(tmp);
        return -1;
    }
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < nd; d++)
            count[d][(v[i].key >> shift[d]) & (RADIX_SIZE - 1)]++;
    fm_keyed *src = v, *dst = tmp;
    for (int d = 0; d < nd; d++) {
        size_t *c = count[d];
        if (c[(src[0].key >> shift[d]) & (RADIX_SIZE - 1)] == n)
            continue;
        size_t sum = 0;
        for (size_t b = 0; b < RADIX_SIZE; b++) {
            size_t t = c[b];
            c[b] = sum;
            sum += t;
        }
        for (size_t i = 0; i < n; i++)
            dst[c[(src[i].key >> shift[d]) & (RADIX_SIZE - 1)]++] = src[i];
        fm_keyed *t = src;
        src = dst;
        dst = t;
    }
    if (src != v)
        memcpy(v, src, n * sizeof *v);
    free(count);
    free(tmp);
    return 0;
}

size_t fm_keyed_lower_bound(const fm_keyed *v, size_t n, uint64_t key)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (v[mid].key < key)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

uint64_t fm_edge_key(uint64_t a, uint64_t b)
{
    return a < b ? a << 32 | b : b << 32 | a;
}
