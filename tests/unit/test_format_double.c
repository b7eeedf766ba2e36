/* fm_format_double (src/io/tsurf_dtoa.c) against its definition: the
 * shortest of printf's %.15g, %.16g, %.17g that strtod reads back to the
 * same double, byte for byte, on values chosen to hit every branch of the
 * exact integer route (ties, binade bottoms, powers of ten, rounding up to
 * the next power of ten) and on random ones. */
#include <float.h>
#include <stdint.h>

#include "fm_test.h"
#include "tsurf_lex.h"

static size_t reference(char *buf, double x)
{
    for (int prec = 15; prec <= 17; prec++) {
        int n = snprintf(buf, 40, "%.*g", prec, x);
        if (prec == 17 || strtod(buf, NULL) == x)
            return (size_t)n;
    }
    return 0;
}

static long long checked, failures;

static void check(double x)
{
    char a[40], b[40];
    size_t na = fm_format_double(a, x), nb = reference(b, x);
    checked++;
    if (na != nb || strcmp(a, b) != 0 || strlen(a) != na) {
        if (failures++ < 20)
            fprintf(stderr, "%a (%.17g): got %s, want %s\n", x, x, a, b);
    }
}

static void check_around(double x)
{
    double lo = x, hi = x;
    check(x);
    check(-x);
    for (int i = 0; i < 3; i++) {
        lo = nextafter(lo, 0);
        hi = nextafter(hi, INFINITY);
        check(lo);
        check(hi);
    }
}

static uint64_t rng_state = 0x9E3779B97F4A7C15u;
static uint64_t next_random(void)
{
    /* xorshift64*: deterministic across runs and machines */
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return rng_state * 0x2545F4914F6CDD1Du;
}

static void test_against_printf(void)
{
    check(0.0);
    check(-0.0);
    check(1e300);
    check(DBL_MIN);
    check(DBL_MAX);
    check(5e-324);
    check(0.1 + 0.2);
    check(521258.67969);
    check(999999999999999.9);
    check(99999999999999.99);
    check(9999999999999999.0);
    check(0.00099999999999999999);
    /* Powers of ten and of two, and their neighbours (binade bottoms). */
    for (int e = -30; e <= 30; e++) {
        char s[16];
        snprintf(s, sizeof s, "1e%d", e);
        check_around(strtod(s, NULL));
    }
    for (int e = -80; e <= 60; e++)
        check_around(ldexp(1.0, e));
    /* Decimals of every length near the boundary of 15/16/17 digits, ties
     * included (digit strings ending in 5). */
    for (int i = 0; i < 100000; i++) {
        uint64_t r = next_random();
        int ndig = 1 + (int)(r % 18), exp10 = (int)((r >> 8) % 24) - 8;
        char s[48];
        int k = 0;
        uint64_t digits = next_random();
        for (int j = 0; j < ndig; j++) {
            s[k++] = (char)('0' + (j == 0 ? 1 + digits % 9 : digits % 10));
            digits /= 10;
            if (!digits)
                digits = next_random();
        }
        if (r >> 40 & 1)
            s[k - 1] = '5';
        snprintf(s + k, sizeof s - (size_t)k, "e%d", exp10 - ndig);
        check_around(strtod(s, NULL));
    }
    /* UTM-like coordinates with full-precision fractions. */
    for (int i = 0; i < 200000; i++) {
        uint64_t r = next_random();
        double base = (double)(r % 4000000) + (double)(next_random() >> 11) * 0x1p-53;
        check(base);
        check(-base / 1000.0);
    }
    /* Random bit patterns over the whole exponent range. */
    for (int i = 0; i < 300000; i++) {
        uint64_t r = next_random();
        double x;
        memcpy(&x, &r, sizeof x);
        if (isfinite(x))
            check(x);
    }
    printf("%lld values, %lld differ from printf + strtod\n", checked, failures);
    CHECK_EQ(failures, 0);
}

FM_TEST_MAIN(FM_CASE(test_against_printf))
