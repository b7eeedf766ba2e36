/* faultmesh core: the few 3-vector operations every stage uses, inline. */
#ifndef FM_VEC3_H
#define FM_VEC3_H

static inline double fm_dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* c = a x b (c may not alias a or b). */
static inline void fm_cross3(const double *a, const double *b, double *c)
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

#endif
