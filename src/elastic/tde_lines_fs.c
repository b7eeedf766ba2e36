/* The line terms of Burgers' formula for a triangular loop in a full
 * space: for a straight segment they integrate in closed form, which is
 * the angular-dislocation construction of Nikkhoo & Walter (2015) seen one
 * edge at a time. Their singular half-lines (the artefacts) are the two
 * ways of writing the edge integral, log((r_i+q_i)/(r_j+q_j)) or
 * log((r_j-q_j)/(r_i-q_i)); choosing per observation point the one whose
 * terms do not cancel is their configuration choice, done per edge. */
#include <math.h>

#include "tde_internal.h"

static fm_cx dot(const fm_cx a[3], const fm_cx b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross(const fm_cx a[3], const fm_cx b[3], fm_cx c[3])
{
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
}

/* One edge Pi -> Pj: adds  A (b x e) L + B grad(c L),  L the integral of
 * 1/R along the edge, c = (x - Pi).(e x b) constant along its line. */
static void edge(const fm_cx x[3], const double pi[3], const double pj[3], const double b[3],
                 double nu, fm_cx u[3])
{
    double len = 0;
    fm_cx e[3], ri[3], rj[3], bb[3];
    for (int k = 0; k < 3; k++) {
        e[k] = pj[k] - pi[k];
        len += (pj[k] - pi[k]) * (pj[k] - pi[k]);
    }
    len = sqrt(len);
    for (int k = 0; k < 3; k++) {
        e[k] /= len;
        ri[k] = x[k] - pi[k];
        rj[k] = x[k] - pj[k];
        bb[k] = b[k];
    }
    /* perpendicular offset from the line, and its square h2, without
     * cancellation near the line */
    fm_cx rxe[3], perp[3];
    cross(ri, e, rxe);
    cross(e, rxe, perp);
    fm_cx h2 = dot(rxe, rxe);
    fm_cx qi = dot(ri, e), qj = dot(rj, e);
    fm_cx di = csqrt(dot(ri, ri)), dj = csqrt(dot(rj, rj));
    fm_cx L, gl[3];
    if (creal(qi) + creal(qj) >= 0) {
        /* beyond or alongside: r + q does not cancel at the far end */
        fm_cx pi_ = creal(qi) >= 0 ? di + qi : h2 / (di - qi);
        fm_cx pj_ = creal(qj) >= 0 ? dj + qj : h2 / (dj - qj);
        L = clog(pi_) - clog(pj_);
        for (int k = 0; k < 3; k++)
            gl[k] = (e[k] / di + perp[k] / (di * pi_)) - (e[k] / dj + perp[k] / (dj * pj_));
    } else {
        fm_cx mi = creal(qi) <= 0 ? di - qi : h2 / (di + qi);
        fm_cx mj = creal(qj) <= 0 ? dj - qj : h2 / (dj + qj);
        L = clog(mj) - clog(mi);
        for (int k = 0; k < 3; k++)
            gl[k] = (-e[k] / dj + perp[k] / (dj * mj)) - (-e[k] / di + perp[k] / (di * mi));
    }
    fm_cx bxe[3], exb[3];
    cross(bb, e, bxe);
    for (int k = 0; k < 3; k++)
        exb[k] = -bxe[k];
    fm_cx c = dot(ri, exb);
    const double A = 1 / (4 * FM_TDE_PI), B = 1 / (8 * FM_TDE_PI * (1 - nu));
    for (int k = 0; k < 3; k++)
        u[k] += A * bxe[k] * L + B * (exb[k] * L + c * gl[k]);
}

void fm_tde_lines_fs(const fm_cx x[3], const double tri[3][3], const double b[3], double nu,
                     fm_cx u[3])
{
    u[0] = u[1] = u[2] = 0;
    for (int k = 0; k < 3; k++)
        edge(x, tri[k], tri[(k + 1) % 3], b, nu, u);
}
