/* check_connect: radix sort (see cc_sort.h). */
#include "cc_sort.h"

#include <stdlib.h>
#include <string.h>

#define DIGIT 11

int cc_bits(uint64_t max)
{
    int b = 0;
    while (b < 64 && (max >> b) != 0)
        b++;
    return b;
}

int cc_radix_sort(cc_rec *r, size_t n, int bits)
{
    if (n < 2 || bits <= 0)
        return 0;
    cc_rec *tmp = malloc(n * sizeof *tmp);
    size_t *count = malloc(((size_t)1 << DIGIT) * sizeof *count);
    if (!tmp || !count) {
        free(tmp);
        free(count);
        return -1;
    }
    cc_rec *src = r, *dst = tmp;
    for (int shift = 0; shift < bits; shift += DIGIT) {
        memset(count, 0, ((size_t)1 << DIGIT) * sizeof *count);
        uint64_t mask = ((uint64_t)1 << DIGIT) - 1;
        for (size_t i = 0; i < n; i++)
            count[(src[i].key >> shift) & mask]++;
        size_t sum = 0;
        for (size_t d = 0; d <= mask; d++) {
            size_t c = count[d];
            count[d] = sum;
            sum += c;
        }
        for (size_t i = 0; i < n; i++)
            dst[count[(src[i].key >> shift) & mask]++] = src[i];
        cc_rec *t = src;
        src = dst;
        dst = t;
    }
    if (src != r)
        memcpy(r, src, n * sizeof *r);
    free(tmp);
    free(count);
    return 0;
}
