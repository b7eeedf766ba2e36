/* Shortest round-tripping decimal text of a double, for every writer.
 *
 * The text is defined as the shortest of printf's %.15g, %.16g and %.17g
 * that reads back to the same double (%.17g always does). That definition
 * is kept, rather than the shortest digit string of Ryu or Grisu, because
 * the two agree on every number that needs at most 15 digits (a decimal of
 * up to 15 digits read into a double prints back as itself: DBL_DIG) and
 * almost always beyond, and it leaves the files of earlier versions
 * byte-identical.
 *
 * printf and strtod made that cost up to three formatting and three
 * parsing passes per number. Here it is computed exactly in 128-bit
 * integers: a finite x = m 2^e (m < 2^53) with e < 0 times 10^k (k <= 22)
 * is the integer S = m 10^k over 2^-e, so with one multiplication its 17
 * leading digits and the exact rest are known, and for P = 15, 16, 17 the
 * P-digit rounding d and whether d reads back as x (d within half a gap
 * between x and its neighbours, ties to the even m, as a correctly
 * rounding reader decides) are integer comparisons. That covers every x
 * in [1e-6, 2^52), coordinates in metres included; other values (and
 * machines without a 128-bit integer type) take the printf route.
 * tests/unit/test_format_double.c holds the two routes to the same bytes
 * (about 20 times faster on UTM coordinates). */
#include "tsurf_lex.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* printf then strtod: exact for any value, slow. */
static size_t format_slow(char *buf, double x)
{
    for (int prec = 15; prec <= 17; prec++) {
        int n = snprintf(buf, 32, "%.*g", prec, x);
        if (prec == 17 || strtod(buf, NULL) == x)
            return (size_t)n;
    }
    return 0; /* not reached */
}

/* "00" .. "99": two digits per division. */
static const char digit_pairs[201] = "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
                                     "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
                                     "8081828384858687888990919293949596979899";

/* %.{P}g layout of the P-digit integer d (trailing zeros allowed) with
 * decimal exponent X: trailing zeros dropped, plain notation when
 * -4 <= X < P, else d.ddde[+-]XX. */
static size_t emit_g(char *buf, int neg, uint64_t d, int X, int P)
{
    while (d % 10 == 0) /* d > 0: x != 0 here */
        d /= 10;
    char dig[20]; /* the n significant digits, right-aligned */
    int at = 20;
    while (d >= 100) {
        memcpy(dig + (at -= 2), digit_pairs + 2 * (d % 100), 2);
        d /= 100;
    }
    if (d >= 10)
        memcpy(dig + (at -= 2), digit_pairs + 2 * d, 2);
    else
        dig[--at] = (char)('0' + d);
    const char *D = dig + at;
    int n = 20 - at;
    size_t k = 0;
    if (neg)
        buf[k++] = '-';
    if (X < -4 || X >= P) {
        buf[k++] = D[0];
        if (n > 1) {
            buf[k++] = '.';
            memcpy(buf + k, D + 1, (size_t)n - 1);
            k += (size_t)n - 1;
        }
        buf[k++] = 'e';
        buf[k++] = X < 0 ? '-' : '+';
        int a = X < 0 ? -X : X;
        if (a >= 100)
            buf[k++] = (char)('0' + a / 100);
        buf[k++] = (char)('0' + a / 10 % 10);
        buf[k++] = (char)('0' + a % 10);
    } else if (X < 0) {
        buf[k++] = '0';
        buf[k++] = '.';
        for (int i = -1; i > X; i--)
            buf[k++] = '0';
        memcpy(buf + k, D, (size_t)n);
        k += (size_t)n;
    } else if (n <= X + 1) { /* an integer, zero-padded */
        memcpy(buf + k, D, (size_t)n);
        k += (size_t)n;
        for (int i = n; i <= X; i++)
            buf[k++] = '0';
    } else {
        memcpy(buf + k, D, (size_t)X + 1);
        k += (size_t)X + 1;
        buf[k++] = '.';
        memcpy(buf + k, D + X + 1, (size_t)(n - X - 1));
        k += (size_t)(n - X - 1);
    }
    buf[k] = '\0';
    return k;
}

#if defined(__SIZEOF_INT128__)
__extension__ typedef unsigned __int128 u128;

static const uint64_t pow10_u64[20] = {1u,
                                       10u,
                                       100u,
                                       1000u,
                                       10000u,
                                       100000u,
                                       1000000u,
                                       10000000u,
                                       100000000u,
                                       1000000000u,
                                       10000000000u,
                                       100000000000u,
                                       1000000000000u,
                                       10000000000000u,
                                       100000000000000u,
                                       1000000000000000u,
                                       10000000000000000u,
                                       100000000000000000u,
                                       1000000000000000000u,
                                       10000000000000000000u};

/* 10^k for k <= 22: m 10^22 < 2^53 2^73.1 still fits in 128 bits. */
static u128 pow10_u128(int k)
{
    return k <= 19 ? (u128)pow10_u64[k] : (u128)pow10_u64[19] * pow10_u64[k - 19];
}

/* The exact route; 0 when x is outside its range. */
static size_t format_fast(char *buf, double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    int neg = (int)(bits >> 63), be = (int)(bits >> 52 & 0x7ff);
    if (be == 0 || be == 0x7ff)
        return 0; /* zero, subnormal, non-finite */
    uint64_t m = (bits & ((UINT64_C(1) << 52) - 1)) | UINT64_C(1) << 52;
    int F = 1075 - be; /* x = m / 2^F */
    /* F <= 120 keeps 200 2^F, the largest product below, in 128 bits. */
    if (F < 1 || F > 120)
        return 0;
    /* floor(log10 x) = X is X0 or X0 + 1, x being in [2^E2, 2^(E2 + 1)). */
    int X = (int)floor((double)(52 - F) * 0.30102999566398119521);
    /* The 17 leading digits once: x 10^k = S / 2^F = q17 + r / 2^F with
     * 10^16 <= q17 < 10^17. */
    int k = 16 - X;
    if (k < 0 || k > 22)
        return 0;
    u128 S = (u128)m * pow10_u128(k);
    uint64_t q17 = (uint64_t)(S >> F);
    if (q17 >= pow10_u64[17]) { /* X0 was one short */
        X++;
        if (--k < 0)
            return 0;
        S = (u128)m * pow10_u128(k);
        q17 = (uint64_t)(S >> F);
    }
    u128 r = S - ((u128)q17 << F), lim = pow10_u128(k);
    /* At the bottom of a binade the gap below x is half the gap above. */
    int narrow_below = m == UINT64_C(1) << 52 && be > 1, even = (m & 1) == 0;
    /* Constant divisors: the compiler multiplies instead. */
    const uint64_t qs[3] = {q17 / 100, q17 / 10, q17}, rs[3] = {q17 % 100, q17 % 10, 0};
    for (int P = 15; P <= 17; P++) {
        /* x 10^k = (q + rem / D) 10^(17 - P): P digits q, the rest exact. */
        uint64_t p10 = pow10_u64[17 - P], q = qs[P - 15];
        u128 D = (u128)p10 << F, rem = ((u128)rs[P - 15] << F) + r, half = D >> 1;
        int up = rem > half || (rem == half && (q & 1)); /* printf: ties to even */
        u128 dist = up ? D - rem : rem;
        /* |d - x 10^(P-1-X)| in units where the gap between x and its
         * neighbours is lim: within half of it, x reads back; on a tie,
         * only if m is even (a correctly rounding reader's rule). */
        u128 twice = dist * (!up && narrow_below ? 4 : 2);
        if (twice < lim || (twice == lim && even)) {
            uint64_t d = q + (uint64_t)up;
            int XP = X;
            if (d == pow10_u64[P]) { /* rounded up to 10^(X + 1) */
                d = pow10_u64[P - 1];
                XP++;
            }
            return emit_g(buf, neg, d, XP, P);
        }
    }
    return 0;
}
#else
static size_t format_fast(char *buf, double x)
{
    (void)buf;
    (void)x;
    return 0;
}
#endif

size_t fm_format_double(char *buf, double x)
{
    size_t n = format_fast(buf, x);
    return n ? n : format_slow(buf, x);
}
