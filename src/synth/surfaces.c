/* The analytic surfaces.
 *
 * A sheet is swept along strike: at parameter s its dip section is a
 * profile curve, parameterised by arc length w, giving a horizontal offset
 * h(w) along the dip direction and an elevation z(w):
 *
 *   x(s, t) = O + s us + (h(w) + c(s)) ud + z(w) ez,
 *   w       = w_top(s) + t (w_bot - w_top(s)) / width,
 *
 * where w_top(s), w_bot are the arc lengths at which the profile reaches the
 * top elevation (topography or constant) and the bottom elevation, and c(s)
 * is a corrugation. With a constant top, t is exactly the down-dip arc
 * length; under topography it is that length stretched by a few percent so
 * that the parameter domain stays a rectangle. */
#include <math.h>

#include "synth_internal.h"

/* Exact for the vertical case, so that a vertical sheet has no 1e-17
 * lean that would blur the gap and overshoot distances. */
static void sincos_deg(double deg, double *s, double *c)
{
    if (deg == 90.0) {
        *s = 1.0;
        *c = 0.0;
    } else {
        *s = sin(deg * SYNTH_DEG);
        *c = cos(deg * SYNTH_DEG);
    }
}

double synth_topo_z(const synth_topo *tp, double x, double y)
{
    double xi = x * tp->xi[0] + y * tp->xi[1];
    double eta = x * tp->eta[0] + y * tp->eta[1];
    return tp->base + tp->amp_xi * sin(2.0 * SYNTH_PI * xi / tp->wl_xi + tp->phase_xi) +
           tp->amp_eta * cos(2.0 * SYNTH_PI * eta / tp->wl_eta);
}

/* Profile point at arc length w. */
static void profile(const synth_sheet *sh, double w, double *h, double *z)
{
    if (sh->law == SYNTH_CIRCULAR) {
        double d = sh->dip1 - w / sh->radius;
        *h = sh->radius * (sin(sh->dip1) - sin(d));
        *z = sh->z1 + sh->radius * (cos(sh->dip1) - cos(d));
    } else {
        *h = w * sh->cos_dip;
        *z = -w * sh->sin_dip;
    }
}

/* Arc length at which the profile reaches elevation z (inverse of the z
 * part of profile()). Planar profiles pass sea level at w = 0; circular
 * ones have w = 0 where the dip is dip1. */
static double profile_w(const synth_sheet *sh, double z)
{
    if (sh->law == SYNTH_CIRCULAR) {
        double c = cos(sh->dip1) + (sh->z1 - z) / sh->radius;
        c = c < -1.0 ? -1.0 : (c > 1.0 ? 1.0 : c);
        return sh->radius * (sh->dip1 - acos(c));
    }
    return -z / sh->sin_dip;
}

void synth_sheet_prepare(synth_sheet *sh)
{
    double ss, cs;
    sincos_deg(sh->strike_deg, &ss, &cs);
    sh->us[0] = ss;
    sh->us[1] = cs;
    /* Dip direction to the right of strike (Aki-Richards). */
    sh->ud[0] = cs;
    sh->ud[1] = -ss;
    sincos_deg(sh->dip_deg, &sh->sin_dip, &sh->cos_dip);
    if (sh->law == SYNTH_CIRCULAR) {
        sh->dip1 = sh->dip1_deg * SYNTH_DEG;
        sh->radius = (sh->z1 - sh->z2) / (cos(sh->dip2_deg * SYNTH_DEG) - cos(sh->dip1));
    }
    if (sh->law != SYNTH_SPLAY) {
        sh->w_bot = profile_w(sh, sh->bottom_z);
        /* Nominal width: from sea level (or the constant top) to the bottom. */
        sh->width = sh->w_bot - profile_w(sh, sh->top_topo ? 0.0 : sh->top_z);
    }
}

double synth_top_z(const fm_synth *sy, const synth_sheet *sh, double s)
{
    if (!sh->top_topo)
        return sh->top_z;
    /* Topography at the reference trace O + s us: explicit, so that the top
     * edge needs no implicit solve; the dip offset between that trace and
     * the true top is small against the topography's wavelengths. */
    return synth_topo_z(&sy->topo, sh->origin[0] + s * sh->us[0], sh->origin[1] + s * sh->us[1]);
}

static void eval_swept(const fm_synth *sy, const synth_sheet *sh, double s, double t,
                       double out[3])
{
    double wt = profile_w(sh, synth_top_z(sy, sh, s));
    double w = wt + t * (sh->w_bot - wt) / sh->width;
    double h, z;
    profile(sh, w, &h, &z);
    if (sh->corr_amp != 0.0)
        h += sh->corr_amp *
             sin(2.0 * SYNTH_PI * s / sh->corr_wavelength + sh->corr_phase_deg * SYNTH_DEG);
    out[0] = sh->origin[0] + s * sh->us[0] + h * sh->ud[0];
    out[1] = sh->origin[1] + s * sh->us[1] + h * sh->ud[1];
    out[2] = z;
}

/* The splay rises in a straight line (at dip_deg, on side `away` of sheet
 * 0) from the junction point J(s) = x0(s, junction_t) to the elevation of
 * sheet 0's top at the same s; t = 0 at the top, t = width at J. */
static void eval_splay(const fm_synth *sy, const synth_fault *f, const synth_sheet *sh, double s,
                       double t, double out[3])
{
    const synth_sheet *base = &f->sheet[0];
    double j[3];
    eval_swept(sy, base, s, sh->junction_t, j);
    double len = (synth_top_z(sy, base, s) - j[2]) / sh->sin_dip;
    double r = len * (1.0 - t / sh->width);
    double hz = r * sh->cos_dip * sh->away;
    out[0] = j[0] + hz * base->ud[0];
    out[1] = j[1] + hz * base->ud[1];
    out[2] = j[2] + r * sh->sin_dip;
}

void synth_eval_local(const fm_synth *sy, const synth_fault *f, size_t k, double s, double t,
                      double out[3])
{
    const synth_sheet *sh = &f->sheet[k];
    if (sh->law == SYNTH_SPLAY)
        eval_splay(sy, f, sh, s, t, out);
    else
        eval_swept(sy, sh, s, t, out);
}
