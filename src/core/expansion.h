/* faultmesh core (internal): floating-point expansion arithmetic.
 *
 * An expansion is an array of doubles e[0..n) whose exact (unrounded) sum is
 * the value it represents, stored in order of increasing magnitude, with no
 * two components overlapping (Shewchuk, "Adaptive Precision Floating-Point
 * Arithmetic and Fast Robust Geometric Predicates", DCG 18 (1997), sec. 2).
 * The routines here keep expansions strongly nonoverlapping and drop zero
 * components, so a value of zero is the empty expansion (n == 0).
 *
 * Correctness of every routine rests on IEEE 754 binary64 arithmetic with
 * round-to-nearest-even, each operation rounded exactly once, and no
 * overflow or underflow in the products formed. Hence the checks below:
 * no -ffast-math (which licenses reassociation) and no excess precision
 * (x87). Contraction of a*b+c into an fma would also break the error-free
 * transformations; fm_core is built with -ffp-contract=off. */
#ifndef FM_EXPANSION_H
#define FM_EXPANSION_H

#include <float.h>
#include <math.h>

#if defined(__FAST_MATH__)
#error "faultmesh predicates need IEEE arithmetic: do not build with -ffast-math"
#endif
#if !defined(FLT_EVAL_METHOD) || FLT_EVAL_METHOD != 0
#error "faultmesh predicates need FLT_EVAL_METHOD == 0 (SSE2, not x87 excess precision)"
#endif

/* 2^-53: half an ulp of 1, the unit roundoff of binary64. */
#define FM_EPSILON 1.1102230246251565404e-16

/* a + b == s + e exactly, s = fl(a + b) (Knuth's TwoSum; any a, b). */
static inline void fm_two_sum(double a, double b, double *s, double *e)
{
    double x = a + b;
    double bv = x - a;
    double av = x - bv;
    *s = x;
    *e = (a - av) + (b - bv);
}

/* a - b == s + e exactly, s = fl(a - b). */
static inline void fm_two_diff(double a, double b, double *s, double *e)
{
    double x = a - b;
    double bv = a - x;
    double av = x + bv;
    *s = x;
    *e = (a - av) + (bv - b);
}

/* a * b == p + e exactly, p = fl(a * b); fma rounds once (C17 7.12.13.1),
 * so e is the exact rounding error as long as it does not underflow. */
static inline void fm_two_product(double a, double b, double *p, double *e)
{
    double x = a * b;
    *p = x;
    *e = fma(a, b, -x);
}

/* h = e + f. h must have room for elen + flen components and must not alias
 * e or f. Returns the length of h (Fast-Expansion-Sum with zero
 * elimination, Shewchuk Theorem 13). */
int fm_exp_sum(int elen, const double *e, int flen, const double *f, double *h);

/* h = e * b. h must have room for 2 * elen components and must not alias e.
 * Returns the length of h (Scale-Expansion with zero elimination, Shewchuk
 * Theorem 19). */
int fm_exp_scale(int elen, const double *e, double b, double *h);

/* e = -e in place. */
void fm_exp_negate(int elen, double *e);

/* Sign of the value of e: that of its largest (last) component. */
static inline int fm_exp_sign(int elen, const double *e)
{
    if (elen == 0)
        return 0;
    return e[elen - 1] > 0.0 ? 1 : (e[elen - 1] < 0.0 ? -1 : 0);
}

/* h = a * b - c * d exactly, at most 4 components. */
int fm_exp_two_two_diff(double a, double b, double c, double d, double *h);

#endif
