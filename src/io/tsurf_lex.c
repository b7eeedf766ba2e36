#include "tsurf_lex.h"

#include <stdlib.h>
#include <string.h>

const char *fm_lines_find(const char *p, const char *end, int c)
{
    const char *q = memchr(p, c, (size_t)(end - p));
    return q ? q : end;
}

void fm_lines_init(fm_lines *L, const char *buf, size_t len)
{
    L->p = buf;
    L->end = buf + len;
    L->nl = fm_lines_find(buf, L->end, '\n');
    L->cr = fm_lines_find(buf, L->end, '\r');
    L->line = 0;
}

/* Powers of ten that are exact in binary64 (5^22 < 2^53). */
static const double exact_pow10[23] = {
    1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
};

#define TWO_POW_53 9007199254740992ULL

#define is_digit fm_lex_is_digit

/* The slow path: strtod needs a NUL-terminated copy. The syntax has
 * already been checked, so strtod sees nothing it could read differently
 * (no hex, no "nan"); the C locale is assumed, as for the whole library. */
static int slow_double(const char *s, const char *e, double *out)
{
    size_t n = (size_t)(e - s);
    char small[128];
    char *buf = n < sizeof small ? small : malloc(n + 1);
    if (!buf)
        return -1;
    memcpy(buf, s, n);
    buf[n] = '\0';
    char *stop;
    *out = strtod(buf, &stop);
    int ok = stop == buf + n;
    if (buf != small)
        free(buf);
    return ok ? 0 : -1;
}

const char *fm_lex_double_slow(const char *p, const char *end, double *out)
{
    const char *start = p;
    int neg = 0;
    if (p < end && (*p == '-' || *p == '+')) {
        neg = *p == '-';
        p++;
    }
    uint64_t m = 0;
    int nd = 0;      /* significant digits held in m */
    int ndigits = 0; /* mantissa digits seen */
    int exp10 = 0;
    int dropped = 0; /* a non-zero digit beyond the 19th was dropped */
    for (; p < end && is_digit(*p); p++, ndigits++) {
        unsigned d = (unsigned)(*p - '0');
        if (nd < 19) {
            if (m || d) {
                m = m * 10 + d;
                nd++;
            }
        } else {
            exp10++;
            dropped |= d != 0;
        }
    }
    if (p < end && *p == '.') {
        for (p++; p < end && is_digit(*p); p++, ndigits++) {
            unsigned d = (unsigned)(*p - '0');
            if (nd < 19) {
                if (m || d) {
                    m = m * 10 + d;
                    nd++;
                }
                exp10--;
            } else {
                dropped |= d != 0;
            }
        }
    }
    if (ndigits == 0)
        return NULL;
    if (p < end && (*p == 'e' || *p == 'E')) {
        p++;
        int eneg = 0;
        if (p < end && (*p == '-' || *p == '+')) {
            eneg = *p == '-';
            p++;
        }
        if (p >= end || !is_digit(*p))
            return NULL;
        int e = 0;
        for (; p < end && is_digit(*p); p++)
            if (e < 100000) /* far beyond any finite double; avoids overflow */
                e = e * 10 + (*p - '0');
        exp10 += eneg ? -e : e;
    }
    if (p < end && *p != ' ' && *p != '\t')
        return NULL;
    if (m == 0) {
        *out = neg ? -0.0 : 0.0;
        return p;
    }
    /* Clinger's fast path: both operands exact, one correctly rounded
     * operation, so the result is the correctly rounded value. */
    if (!dropped && m <= TWO_POW_53 && exp10 >= -22 && exp10 <= 22) {
        double v = (double)m;
        v = exp10 < 0 ? v / exact_pow10[-exp10] : v * exact_pow10[exp10];
        *out = neg ? -v : v;
        return p;
    }
    if (slow_double(start, p, out) != 0)
        return NULL;
    return p;
}

