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
 * printf and strtod made that cost three formatting and three parsing
 * passes per number. Here it is computed exactly in 128-bit integers: a
 * finite x = m 2^e (m < 2^53) with e < 0 times 10^k (k <= 19) is the
 * integer S = m 10^k over 2^-e, so its P-digit rounding d and whether d
 * reads back as x (d within half a gap between x and its neighbours, ties
 * to the even m, as a correctly rounding reader decides) are integer
 * comparisons. That covers every x in [1e-3, 1e15) and more, coordinates
 * in metres included; other values (and machines without a 128-bit
 * integer type) take the printf route. tests/unit/test_format_double.c
 * holds the two routes to the same bytes. */
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

/* %.{P}g layout of the P-digit integer d (trailing zeros allowed) with
 * decimal exponent X: trailing zeros dropped, plain notation when
 * -4 <= X < P, else d.ddde[+-]XX. */
static size_t emit_g(char *buf, int neg, uint64_t d, int X, int P)
{
    char dig[20];
    int n = 0;
    while (d % 10 == 0 && d) /* d > 0: x != 0 here */
        d /= 10;
    do {
        dig[n++] = (char)('0' + d % 10);
        d /= 10;
    } while (d);
    /* dig holds the n significant digits, last first. */
    size_t k = 0;
    if (neg)
        buf[k++] = '-';
    if (X < -4 || X >= P) {
        buf[k++] = dig[--n];
        if (n) {
            buf[k++] = '.';
            while (n)
                buf[k++] = dig[--n];
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
        while (n)
            buf[k++] = dig[--n];
    } else {
        for (int i = 0; i <= X; i++) /* integer part, zero-padded */
            buf[k++] = n ? dig[--n] : '0';
        if (n) {
            buf[k++] = '.';
            while (n)
                buf[k++] = dig[--n];
        }
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
    /* F <= 120 keeps 2 * (a remainder below 2^F) inside 128 bits. */
    if (F < 1 || F > 120)
        return 0;
    /* At the bottom of a binade the gap below x is half the gap above. */
    int narrow_below = m == UINT64_C(1) << 52 && be > 1;
    int even = (m & 1) == 0;
    /* floor(log10 x) is X0 or X0 + 1, x being in [2^E2, 2^(E2 + 1)). */
    int X0 = (int)floor((double)(52 - F) * 0.30102999566398119521);
    u128 one = 1, unit = one << F, half = one << (F - 1);
    for (int P = 15; P <= 17; P++) {
        for (int X = X0; X <= X0 + 1; X++) {
            int k = P - 1 - X;
            if (k < 0 || k > 19)
                return 0;
            u128 S = (u128)m * pow10_u64[k]; /* x 10^k = S / 2^F */
            uint64_t q = (uint64_t)(S >> F);
            if (q >= pow10_u64[P])
                continue; /* x >= 10^(X + 1): X0 was one short */
            u128 rem = S - ((u128)q << F);
            int up = rem > half || (rem == half && (q & 1));
            u128 dist = up ? unit - rem : rem;
            uint64_t d = q + (uint64_t)up;
            /* |d 10^-k - x| against half the gap on d's side, in units
             * of 10^-k / 2^F; a tie reads back as x only for even m. */
            u128 lim = pow10_u64[k], twice = dist * (!up && narrow_below ? 4 : 2);
            if (twice < lim || (twice == lim && even)) {
                if (d == pow10_u64[P]) { /* rounded up to 10^(X + 1) */
                    d = pow10_u64[P - 1];
                    X++;
                }
                return emit_g(buf, neg, d, X, P);
            }
            break; /* P digits are too few */
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
