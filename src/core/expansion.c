/* faultmesh core: floating-point expansion arithmetic (see expansion.h). */
#include "expansion.h"

int fm_exp_sum(int elen, const double *e, int flen, const double *f, double *h)
{
    /* Merge the components of e and f by increasing magnitude into the
     * sequence g, then sweep: Q <- g1; for each further g_i,
     * (Q, h) <- TwoSum(Q, g_i), emitting every nonzero h; finally emit Q.
     * (The paper uses FastTwoSum for the first step; TwoSum gives the same
     * two results whenever FastTwoSum's precondition holds.) */
    int i = 0, j = 0, k = 0;
    int have_q = 0;
    double q = 0.0;
    while (i < elen || j < flen) {
        double g;
        if (j >= flen || (i < elen && fabs(e[i]) < fabs(f[j])))
            g = e[i++];
        else
            g = f[j++];
        if (!have_q) {
            q = g;
            have_q = 1;
            continue;
        }
        double s, t;
        fm_two_sum(q, g, &s, &t);
        if (t != 0.0)
            h[k++] = t;
        q = s;
    }
    if (q != 0.0)
        h[k++] = q;
    return k;
}

int fm_exp_scale(int elen, const double *e, double b, double *h)
{
    /* (Q, h1) <- TwoProduct(e1, b); for each further e_i:
     * (T, t) <- TwoProduct(e_i, b); (Q', h) <- TwoSum(Q, t);
     * (Q, h') <- TwoSum(T, Q') (FastTwoSum in the paper, same results);
     * emit nonzero h, h' in that order; finally emit Q. */
    if (elen == 0)
        return 0;
    int k = 0;
    double q, hh;
    fm_two_product(e[0], b, &q, &hh);
    if (hh != 0.0)
        h[k++] = hh;
    for (int i = 1; i < elen; i++) {
        double pt, pe, s;
        fm_two_product(e[i], b, &pt, &pe);
        fm_two_sum(q, pe, &s, &hh);
        if (hh != 0.0)
            h[k++] = hh;
        fm_two_sum(pt, s, &q, &hh);
        if (hh != 0.0)
            h[k++] = hh;
    }
    if (q != 0.0)
        h[k++] = q;
    return k;
}

void fm_exp_negate(int elen, double *e)
{
    for (int i = 0; i < elen; i++)
        e[i] = -e[i];
}

int fm_exp_two_two_diff(double a, double b, double c, double d, double *h)
{
    double p[2], q[2];
    int np = 0, nq = 0;
    double x, y;
    fm_two_product(a, b, &x, &y);
    if (y != 0.0)
        p[np++] = y;
    if (x != 0.0)
        p[np++] = x;
    fm_two_product(-c, d, &x, &y);
    if (y != 0.0)
        q[nq++] = y;
    if (x != 0.0)
        q[nq++] = x;
    return fm_exp_sum(np, p, nq, q, h);
}
