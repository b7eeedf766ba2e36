/* The solid-angle (Burgers function) term of a triangular dislocation: the
 * only discontinuous part of the field, so the only one that carries the
 * slip jump across the triangle. */
#include <math.h>

#include "tde_internal.h"

/* atan2 continued analytically in its arguments' imaginary parts (first
 * order is all complex-step differentiation needs): the real branch comes
 * from the real parts, the derivative is (D dN - N dD) / (N^2 + D^2). */
static fm_cx atan2_cx(fm_cx n, fm_cx d)
{
    double nr = creal(n), dr = creal(d);
    double den = nr * nr + dr * dr;
    double im = den > 0 ? (dr * cimag(n) - nr * cimag(d)) / den : 0;
    return atan2(nr, dr) + I * im;
}

void fm_tde_solid_angle_term(const fm_cx x[3], const double tri[3][3], const double b[3],
                             fm_cx u[3])
{
    fm_cx r[3][3], len[3];
    for (int v = 0; v < 3; v++) {
        for (int k = 0; k < 3; k++)
            r[v][k] = tri[v][k] - x[k];
        len[v] = csqrt(r[v][0] * r[v][0] + r[v][1] * r[v][1] + r[v][2] * r[v][2]);
    }
#define DOT(a, c) (r[a][0] * r[c][0] + r[a][1] * r[c][1] + r[a][2] * r[c][2])
    fm_cx num = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) +
                r[0][1] * (r[1][2] * r[2][0] - r[1][0] * r[2][2]) +
                r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
    fm_cx den = len[0] * len[1] * len[2] + DOT(0, 1) * len[2] + DOT(0, 2) * len[1] +
                DOT(1, 2) * len[0];
#undef DOT
    /* On the triangle's plane inside it num is zero but for rounding, and
     * its sign would pick a side at random: take the +n side (num < 0). */
    double scale = creal(len[0] * len[1] * len[2]);
    if (creal(den) < 0 && fabs(creal(num)) <= 1e-13 * scale)
        num = CMPLX(-0.0, cimag(num));
    fm_cx omega = 2 * atan2_cx(num, den);
    for (int k = 0; k < 3; k++)
        u[k] = -b[k] * omega / (4 * FM_TDE_PI);
}
