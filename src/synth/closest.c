/* Closest point of a sheet to a point, over its parameter rectangle.
 *
 * A coarse sampling of the rectangle picks a few starting points (local
 * minima of the squared distance), then a projected Newton iteration in
 * (s, t) converges from each. Full Newton rather than Gauss-Newton: at a
 * few km from a corrugated or listric sheet the distance times the
 * curvature approaches 1, where Gauss-Newton stalls or diverges. The
 * Hessian is made positive definite when it is not and steps are
 * backtracked, so every accepted step decreases the distance. Parameters
 * at a bound whose gradient points outward are held there, which gives the
 * clamped (edge or corner) foot points.
 *
 * Derivatives are central differences of the analytic map with a 0.5 m
 * step: the map is smooth on the scale of kilometres, so the truncation
 * error is ~1e-11 and, since the converged point only depends on the
 * gradient, errors in the Hessian merely slow convergence. */
#include <math.h>

#include "synth_internal.h"

#define FD_STEP 0.5
#define MAX_CANDIDATES 6
#define MAX_SAMPLES_S 96
#define MAX_SAMPLES_T 32

typedef struct sheet_ctx {
    const fm_synth *sy;
    const synth_fault *f;
    size_t k;
    const synth_sheet *sh;
    const double *p;
} sheet_ctx;

static double half_sq(const sheet_ctx *c, double s, double t)
{
    double x[3];
    synth_eval_local(c->sy, c->f, c->k, s, t, x);
    double dx = x[0] - c->p[0], dy = x[1] - c->p[1], dz = x[2] - c->p[2];
    return 0.5 * (dx * dx + dy * dy + dz * dz);
}

void synth_derivatives(const fm_synth *sy, const synth_fault *f, size_t k, double s, double t,
                       double x[3], double xs[3], double xt[3])
{
    double a[3], b[3], c[3], d[3];
    synth_eval_local(sy, f, k, s, t, x);
    synth_eval_local(sy, f, k, s + FD_STEP, t, a);
    synth_eval_local(sy, f, k, s - FD_STEP, t, b);
    synth_eval_local(sy, f, k, s, t + FD_STEP, c);
    synth_eval_local(sy, f, k, s, t - FD_STEP, d);
    for (int i = 0; i < 3; i++) {
        xs[i] = (a[i] - b[i]) / (2.0 * FD_STEP);
        xt[i] = (c[i] - d[i]) / (2.0 * FD_STEP);
    }
}

/* Gradient and Hessian of half the squared distance at (s, t). */
static double gradient_hessian(const sheet_ctx *c, double s, double t, double g[2], double H[3])
{
    const double h = FD_STEP;
    double x[3], pp[3], pm[3], mp[3], mm[3], sp[3], sm[3], tp[3], tm[3];
    synth_eval_local(c->sy, c->f, c->k, s, t, x);
    synth_eval_local(c->sy, c->f, c->k, s + h, t, sp);
    synth_eval_local(c->sy, c->f, c->k, s - h, t, sm);
    synth_eval_local(c->sy, c->f, c->k, s, t + h, tp);
    synth_eval_local(c->sy, c->f, c->k, s, t - h, tm);
    synth_eval_local(c->sy, c->f, c->k, s + h, t + h, pp);
    synth_eval_local(c->sy, c->f, c->k, s + h, t - h, pm);
    synth_eval_local(c->sy, c->f, c->k, s - h, t + h, mp);
    synth_eval_local(c->sy, c->f, c->k, s - h, t - h, mm);
    double f = 0.0;
    g[0] = g[1] = H[0] = H[1] = H[2] = 0.0;
    for (int i = 0; i < 3; i++) {
        double r = x[i] - c->p[i];
        double xs = (sp[i] - sm[i]) / (2.0 * h), xt = (tp[i] - tm[i]) / (2.0 * h);
        double xss = (sp[i] - 2.0 * x[i] + sm[i]) / (h * h);
        double xtt = (tp[i] - 2.0 * x[i] + tm[i]) / (h * h);
        double xst = (pp[i] - pm[i] - mp[i] + mm[i]) / (4.0 * h * h);
        f += 0.5 * r * r;
        g[0] += r * xs;
        g[1] += r * xt;
        H[0] += xs * xs + r * xss;
        H[1] += xs * xt + r * xst;
        H[2] += xt * xt + r * xtt;
    }
    return f;
}

static double clampd(double v, double lo, double hi) { return v < lo ? lo : (v > hi ? hi : v); }

/* Newton step on the free parameters; returns 0 when both are held. */
static int newton_step(const double g[2], const double H[3], const int freev[2], double d[2])
{
    /* Shift to keep the model convex; the Gauss-Newton part has unit scale
     * (|x_s|, |x_t| ~ 1), so 1e-2 is a mild floor. */
    const double floor_eig = 1e-2;
    d[0] = d[1] = 0.0;
    if (freev[0] && freev[1]) {
        double a = H[0], b = H[1], c = H[2];
        double mean = 0.5 * (a + c), dev = sqrt(0.25 * (a - c) * (a - c) + b * b);
        double lmin = mean - dev;
        if (lmin < floor_eig) {
            a += floor_eig - lmin;
            c += floor_eig - lmin;
        }
        double det = a * c - b * b;
        d[0] = -(c * g[0] - b * g[1]) / det;
        d[1] = -(a * g[1] - b * g[0]) / det;
        return 1;
    }
    for (int i = 0; i < 2; i++) {
        if (!freev[i])
            continue;
        double a = H[i == 0 ? 0 : 2];
        if (a < floor_eig)
            a = floor_eig;
        d[i] = -g[i] / a;
        return 1;
    }
    return 0;
}

static double newton(const sheet_ctx *c, double *ps, double *pt)
{
    const synth_sheet *sh = c->sh;
    double lo[2] = {sh->s0, 0.0}, hi[2] = {sh->s1, sh->width};
    double u[2] = {*ps, *pt};
    double f = half_sq(c, u[0], u[1]);
    for (int it = 0; it < 100; it++) {
        double g[2], H[3], d[2];
        f = gradient_hessian(c, u[0], u[1], g, H);
        int freev[2];
        for (int i = 0; i < 2; i++)
            freev[i] = !((u[i] <= lo[i] && g[i] > 0.0) || (u[i] >= hi[i] && g[i] < 0.0));
        if (!newton_step(g, H, freev, d))
            break;
        /* A trust radius keeps a poor model from jumping across the sheet. */
        double len = sqrt(d[0] * d[0] + d[1] * d[1]);
        if (len > 4000.0) {
            d[0] *= 4000.0 / len;
            d[1] *= 4000.0 / len;
        }
        double alpha = 1.0, v[2] = {u[0], u[1]}, fv = f;
        int accepted = 0;
        for (int ls = 0; ls < 40; ls++, alpha *= 0.5) {
            v[0] = clampd(u[0] + alpha * d[0], lo[0], hi[0]);
            v[1] = clampd(u[1] + alpha * d[1], lo[1], hi[1]);
            fv = half_sq(c, v[0], v[1]);
            if (fv <= f) {
                accepted = 1;
                break;
            }
        }
        if (!accepted)
            break;
        double moved = fabs(v[0] - u[0]) + fabs(v[1] - u[1]);
        u[0] = v[0];
        u[1] = v[1];
        f = fv;
        if (moved < 1e-10)
            break;
    }
    *ps = u[0];
    *pt = u[1];
    return sqrt(2.0 * half_sq(c, u[0], u[1]));
}

double synth_closest_local(const fm_synth *sy, const synth_fault *f, size_t k, const double p[3],
                           double *ps, double *pt)
{
    const synth_sheet *sh = &f->sheet[k];
    sheet_ctx c = {sy, f, k, sh, p};
    /* Sampling fine enough to see each corrugation separately. */
    double step = 1000.0;
    if (sh->corr_amp != 0.0 && sh->corr_wavelength / 8.0 < step)
        step = sh->corr_wavelength / 8.0;
    int ns = (int)ceil((sh->s1 - sh->s0) / step), nt = (int)ceil(sh->width / 1000.0);
    ns = ns < 2 ? 2 : (ns > MAX_SAMPLES_S ? MAX_SAMPLES_S : ns);
    nt = nt < 2 ? 2 : (nt > MAX_SAMPLES_T ? MAX_SAMPLES_T : nt);
    double val[(MAX_SAMPLES_S + 1) * (MAX_SAMPLES_T + 1)];
    for (int j = 0; j <= nt; j++)
        for (int i = 0; i <= ns; i++)
            val[j * (ns + 1) + i] = half_sq(&c, sh->s0 + (sh->s1 - sh->s0) * i / ns,
                                            sh->width * j / nt);
    /* The best few local minima of the samples (4-neighbourhood). */
    int cand[MAX_CANDIDATES], nc = 0;
    for (int j = 0; j <= nt; j++) {
        for (int i = 0; i <= ns; i++) {
            const double *at = val + j * (ns + 1) + i, v = *at;
            if ((i > 0 && at[-1] < v) || (i < ns && at[1] < v) || (j > 0 && at[-(ns + 1)] < v) ||
                (j < nt && at[ns + 1] < v))
                continue;
            int pos = nc < MAX_CANDIDATES ? nc++ : MAX_CANDIDATES;
            while (pos > 0 && val[cand[pos - 1]] > v) {
                if (pos < MAX_CANDIDATES)
                    cand[pos] = cand[pos - 1];
                pos--;
            }
            if (pos < MAX_CANDIDATES)
                cand[pos] = j * (ns + 1) + i;
        }
    }
    double best = INFINITY;
    for (int q = 0; q < nc; q++) {
        int i = cand[q] % (ns + 1), j = cand[q] / (ns + 1);
        double s = sh->s0 + (sh->s1 - sh->s0) * i / ns, t = sh->width * j / nt;
        double d = newton(&c, &s, &t);
        if (d < best) {
            best = d;
            *ps = s;
            *pt = t;
        }
    }
    return best;
}
