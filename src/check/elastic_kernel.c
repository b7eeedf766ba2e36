/* The elastic check's kernel: an element's frame from its strike, dip
 * and rake, and the traction a unit rake slip of one element puts on
 * another through the half-space dislocation (src/elastic). */
#include <math.h>
#include <string.h>

#include "elastic_internal.h"
#include "fm_closest.h"
#include "fm_elastic.h"
#include "fm_vec3.h"

#define DEG (3.14159265358979323846 / 180.0)

int el_elem_make(const fm_mesh *m, size_t t, double strike, double dip, double rake,
                 el_elem *e)
{
    memset(e, 0, sizeof *e);
    const double *x = fm_mesh_vertices(m);
    const int32_t *tri = fm_mesh_triangles(m);
    int below = 0;
    for (int k = 0; k < 3; k++) {
        const double *p = x + 3 * (size_t)tri[3 * t + k];
        for (int d = 0; d < 3; d++)
            e->tri[k][d] = p[d];
        /* a top kept above sea level: onto the free surface, where a
         * half-space code has it */
        if (e->tri[k][2] > 0)
            e->tri[k][2] = 0;
        below += e->tri[k][2] < 0;
    }
    for (int d = 0; d < 3; d++)
        e->c[d] = (e->tri[0][d] + e->tri[1][d] + e->tri[2][d]) / 3;
    e->top = -fmax(e->tri[0][2], fmax(e->tri[1][2], e->tri[2][2]));
    double ab[3], ac[3], nn[3];
    for (int d = 0; d < 3; d++) {
        ab[d] = e->tri[1][d] - e->tri[0][d];
        ac[d] = e->tri[2][d] - e->tri[0][d];
    }
    fm_cross3(ab, ac, nn);
    double area = sqrt(fm_dot3(nn, nn)) / 2;
    e->h = sqrt(area * 4 / sqrt(3.0));
    if (!below)
        return e->state = EL_ABOVE;
    if (!(area > 0))
        return e->state = EL_DEGENERATE;
    /* Aki and Richards: strike clockwise from north with the dip to its
     * right; rake from strike in the plane, 90 = hanging wall up dip */
    double ps = strike * DEG, pd = dip * DEG, pr = rake * DEG;
    double right[3] = {cos(ps), -sin(ps), 0}, down[3];
    e->s[0] = sin(ps);
    e->s[1] = cos(ps);
    e->s[2] = 0;
    for (int d = 0; d < 3; d++)
        down[d] = cos(pd) * right[d];
    down[2] = -sin(pd);
    for (int d = 0; d < 3; d++) {
        e->u[d] = -down[d];
        e->r[d] = cos(pr) * e->s[d] + sin(pr) * e->u[d];
    }
    fm_cross3(down, e->s, e->n);
    /* The dislocation's slip is the displacement of its +n side relative
     * to the -n side; the rake's is the hanging wall's relative to the
     * footwall: the same vector when its n points into the hanging wall. */
    double tn[3], ts[3], td[3];
    if (fm_tde_frame((const double(*)[3])e->tri, tn, ts, td) != 0)
        return e->state = EL_DEGENERATE;
    double sign = fm_dot3(tn, e->n) >= 0 ? 1 : -1;
    e->b[0] = sign * fm_dot3(e->r, ts);
    e->b[1] = sign * fm_dot3(e->r, td);
    e->b[2] = 0;
    return e->state = EL_OK;
}

static int traction(const el_elem *src, const el_elem *rcv, double mu, double nu, int half,
                    double out[4])
{
    /* horizontally about the receiver, so that UTM magnitudes do not eat
     * the digits; z stays, the free surface being at z = 0 */
    double tri[3][3], obs[3] = {0, 0, rcv->c[2]};
    for (int k = 0; k < 3; k++) {
        tri[k][0] = src->tri[k][0] - rcv->c[0];
        tri[k][1] = src->tri[k][1] - rcv->c[1];
        tri[k][2] = src->tri[k][2];
    }
    double eps[6], sig[6];
    if ((half ? fm_tde_strain_hs : fm_tde_strain_fs)(obs, (const double(*)[3])tri, src->b, nu,
                                                     eps) != 0)
        return -1;
    fm_tde_stress_from_strain(eps, mu, 2 * mu * nu / (1 - 2 * nu), sig);
    const double *n = rcv->n;
    double t[3] = {sig[0] * n[0] + sig[3] * n[1] + sig[4] * n[2],
                   sig[3] * n[0] + sig[1] * n[1] + sig[5] * n[2],
                   sig[4] * n[0] + sig[5] * n[1] + sig[2] * n[2]};
    out[0] = fm_dot3(t, rcv->s);
    out[1] = fm_dot3(t, rcv->u);
    out[2] = fm_dot3(t, rcv->r);
    out[3] = fm_dot3(t, n);
    for (int k = 0; k < 4; k++)
        if (!isfinite(out[k]))
            return -1;
    return 0;
}

int el_traction(const el_elem *src, const el_elem *rcv, const fm_elastic_options *o,
                double out[4])
{
    int half = !o->full_space && src->top - rcv->c[2] < EL_IMAGE_SIZES * src->h;
    return traction(src, rcv, o->mu, o->nu, half, out);
}

int el_traction_hs(const el_elem *src, const el_elem *rcv, double mu, double nu, double out[4])
{
    return traction(src, rcv, mu, nu, 1, out);
}

/* Squared distance of segments p0-p1 and q0-q1 (clamped parameters). */
static double seg_seg2(const double p0[3], const double p1[3], const double q0[3],
                       const double q1[3])
{
    double d1[3], d2[3], r[3];
    for (int k = 0; k < 3; k++) {
        d1[k] = p1[k] - p0[k];
        d2[k] = q1[k] - q0[k];
        r[k] = p0[k] - q0[k];
    }
    double a = fm_dot3(d1, d1), e = fm_dot3(d2, d2), f = fm_dot3(d2, r), c = fm_dot3(d1, r);
    double b = fm_dot3(d1, d2), den = a * e - b * b;
    double s = den > 1e-12 * a * e ? (b * f - c * e) / den : 0;
    s = s < 0 ? 0 : s > 1 ? 1 : s;
    double t = e > 0 ? (b * s + f) / e : 0;
    if (t < 0 || t > 1) {
        t = t < 0 ? 0 : 1;
        s = a > 0 ? (b * t - c) / a : 0;
        s = s < 0 ? 0 : s > 1 ? 1 : s;
    }
    double d = 0;
    for (int k = 0; k < 3; k++) {
        double w = r[k] + s * d1[k] - t * d2[k];
        d += w * w;
    }
    return d;
}

double el_distance(const el_elem *a, const el_elem *b)
{
    /* about a's centroid, for the digits */
    double pa[3][3], pb[3][3];
    for (int k = 0; k < 3; k++)
        for (int d = 0; d < 3; d++) {
            pa[k][d] = a->tri[k][d] - a->c[d];
            pb[k][d] = b->tri[k][d] - a->c[d];
        }
    double best = INFINITY;
    for (int k = 0; k < 3; k++) {
        double d = fm_closest_on_triangle(pa[k], pb[0], pb[1], pb[2], NULL, NULL);
        best = d < best ? d : best;
        d = fm_closest_on_triangle(pb[k], pa[0], pa[1], pa[2], NULL, NULL);
        best = d < best ? d : best;
        for (int l = 0; l < 3; l++) {
            d = seg_seg2(pa[k], pa[(k + 1) % 3], pb[l], pb[(l + 1) % 3]);
            best = d < best ? d : best;
        }
    }
    return sqrt(best);
}
