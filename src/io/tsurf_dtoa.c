/* Shortest round-tripping decimal text of a double, for the writer. */
#include "tsurf_lex.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double pow10_small[10] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};

/* Plain notation with d decimals of the integer r (|r| < 2^53). */
static size_t emit_fixed(char *buf, int neg, uint64_t r, int d)
{
    char digits[24];
    int n = 0;
    do {
        digits[n++] = (char)('0' + r % 10);
        r /= 10;
    } while (r);
    size_t k = 0;
    if (neg)
        buf[k++] = '-';
    if (n <= d) {
        buf[k++] = '0';
        buf[k++] = '.';
        for (int i = 0; i < d - n; i++)
            buf[k++] = '0';
        while (n)
            buf[k++] = digits[--n];
    } else {
        while (n) {
            if (n == d)
                buf[k++] = '.';
            buf[k++] = digits[--n];
        }
    }
    buf[k] = '\0';
    return k;
}

size_t fm_format_double(char *buf, double x)
{
    if (x == 0) {
        strcpy(buf, signbit(x) ? "-0" : "0");
        return strlen(buf);
    }
    /* Most coordinates carry a handful of decimals (CFM: 5). The fewest
     * decimals d for which round(x * 10^d) / 10^d gives x back is the
     * shortest text; that division is exactly what a correctly rounding
     * reader computes for the text, so it reads back as x. */
    double ax = fabs(x);
    if (ax >= 1e-3 && ax < 1e15) {
        for (int d = 0; d < 10; d++) {
            double s = ax * pow10_small[d];
            if (s >= 9007199254740992.0)
                break;
            double r = round(s);
            if (r / pow10_small[d] == ax)
                return emit_fixed(buf, x < 0, (uint64_t)r, d);
        }
    }
    for (int prec = 15; prec <= 17; prec++) {
        int n = snprintf(buf, 32, "%.*g", prec, x);
        if (prec == 17 || strtod(buf, NULL) == x)
            return (size_t)n;
    }
    return 0; /* not reached */
}
