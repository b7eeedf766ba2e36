/* Quality, size and new points of triangles in the metric. Each triangle
 * is judged in the metric taken at its centroid, where the surface is
 * treated as its tangent plane: lengths and angles are those of the plane
 * mapped by the Cholesky factor R of M (M = R^T R, R upper triangular with
 * positive diagonal, so orientation is kept). */
#include <math.h>

#include "cdt_internal.h"

/* Raises the small eigenvalue of m to at least the large one / a2. m must
 * be finite with a positive trace; 0 when nothing changed. */
static int clamp_anisotropy(double m[3], double a2)
{
    double E = m[0], F = m[1], G = m[2];
    double h = 0.5 * (E + G), d = hypot(0.5 * (E - G), F);
    double l1 = h + d;
    /* The small eigenvalue from the determinant where that keeps digits. */
    double det = E * G - F * F;
    double l2 = det > 0 ? det / l1 : h - d;
    double want = l1 / a2;
    if (l2 >= want)
        return 0;
    /* Unit eigenvector of l2: perpendicular to that of l1, taken from the
     * better conditioned row of M - l1 I. */
    double vx, vy;
    if (fabs(E - l1) >= fabs(G - l1))
        vx = E - l1, vy = F;
    else
        vx = F, vy = G - l1;
    double n = hypot(vx, vy);
    if (!(n > 0))
        return 0; /* m a multiple of I: l2 == l1, not here */
    vx /= n, vy /= n;
    double dl = want - l2;
    m[0] = E + dl * vx * vx;
    m[1] = F + dl * vx * vy;
    m[2] = G + dl * vy * vy;
    return 1;
}

int cdt_metric(cdt_refiner *r, const double uv[2], double m[3])
{
    if (!r->o->metric) {
        m[0] = 1, m[1] = 0, m[2] = 1;
        return 0;
    }
    r->o->metric(r->o->metric_user, uv, m);
    /* Semi-definite within rounding (a Gram matrix of nearly parallel
     * derivatives) can be clamped; indefinite cannot. */
    double tr = m[0] + m[2];
    if (r->aniso2 > 0 && isfinite(m[0]) && isfinite(m[1]) && isfinite(m[2]) && tr > 0 &&
        m[0] >= 0 && m[2] >= 0 && m[0] * m[2] - m[1] * m[1] >= -1e-12 * tr * tr &&
        clamp_anisotropy(m, r->aniso2))
        r->t->stats.clamped++;
    if (isfinite(m[0]) && isfinite(m[1]) && isfinite(m[2]) && m[0] > 0 && m[2] > 0 &&
        m[0] * m[2] - m[1] * m[1] > 0)
        return 0;
    if (r->st == FM_OK)
        r->st = fm_error_set(r->err, FM_ERR_NUMERIC, NULL, 0,
                             "metric at (%.17g, %.17g) is not positive definite (E %g, F %g, G %g)",
                             uv[0], uv[1], m[0], m[1], m[2]);
    return -1;
}

static double len2(const double m[3], double dx, double dy)
{
    return m[0] * dx * dx + 2 * m[1] * dx * dy + m[2] * dy * dy;
}

int cdt_quality_eval(cdt_refiner *r, int32_t tri, cdt_quality *q)
{
    const struct fm_cdt *t = r->t;
    const int32_t *v = t->tv + 3 * (size_t)tri;
    const double *p[3] = {cdt_p(t, v[0]), cdt_p(t, v[1]), cdt_p(t, v[2])};
    double g[2] = {(p[0][0] + p[1][0] + p[2][0]) / 3, (p[0][1] + p[1][1] + p[2][1]) / 3};
    if (cdt_metric(r, g, q->m))
        return -1;
    double l2[3];
    for (int i = 0; i < 3; i++) {
        const double *a = p[(i + 1) % 3], *b = p[(i + 2) % 3];
        l2[i] = len2(q->m, b[0] - a[0], b[1] - a[1]);
    }
    int s = 0, L = 0;
    for (int i = 1; i < 3; i++) {
        if (l2[i] < l2[s])
            s = i;
        if (l2[i] > l2[L])
            L = i;
    }
    double lj = l2[(s + 1) % 3], lk = l2[(s + 2) % 3];
    q->lmax = sqrt(l2[L]);
    q->lmin = sqrt(l2[s]);
    q->shortest = s;
    q->cos_min = (lj + lk - l2[s]) / (2 * sqrt(lj * lk));
    q->bad = 0;
    q->poor = 0;
    q->key = 0;
    if (q->lmax > r->bad_len) {
        q->bad = q->poor = 1;
        q->key = 2 + q->lmax / r->size;
    } else if (q->cos_min > r->cos_min && q->lmax > 1e-3 * r->size &&
               !cdt_apex_exempt(r, v[(s + 1) % 3], v[(s + 2) % 3])) {
        /* Below min_length the angle is left: what makes a triangle that
         * small is a feature of the input or of the metric, and chasing
         * its angle is how refinement fails to end. */
        q->poor = 2;
        if (!(q->lmax < r->min_len)) {
            q->bad = 2;
            q->key = 1 + q->cos_min;
        }
    }
    return 0;
}

int cdt_fix_point(cdt_refiner *r, int32_t tri, const cdt_quality *q, double out[2])
{
    const struct fm_cdt *t = r->t;
    const int32_t *v = t->tv + 3 * (size_t)tri;
    const double *a = cdt_p(t, v[0]);
    double r11 = sqrt(q->m[0]), r12 = q->m[1] / r11;
    double r22 = sqrt(q->m[2] - r12 * r12);
    if (!(r22 > 0))
        return -1;
    /* Mapped vertices, relative to vertex 0 to keep digits. */
    double P[3][2] = {{0, 0}};
    for (int i = 1; i < 3; i++) {
        const double *b = cdt_p(t, v[i]);
        double dx = b[0] - a[0], dy = b[1] - a[1];
        P[i][0] = r11 * dx + r12 * dy;
        P[i][1] = r22 * dy;
    }
    double bx = P[1][0], by = P[1][1], cx = P[2][0], cy = P[2][1];
    double d = 2 * (bx * cy - by * cx);
    if (!(d != 0))
        return -1;
    double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    double ux = (cy * b2 - by * c2) / d, uy = (bx * c2 - cx * b2) / d;
    /* Off-centre (Ungor 2004): when the circumcentre lies farther from the
     * shortest edge than the apex of the triangle on that edge with exactly
     * the angle aimed at, take that apex: the new triangle on the short
     * edge is then just good, and fewer points are needed. The point stays
     * inside the circumcircle, so the cavity still holds the triangle. */
    const double *e0 = P[(q->shortest + 1) % 3], *e1 = P[(q->shortest + 2) % 3];
    double mx = 0.5 * (e0[0] + e1[0]), my = 0.5 * (e0[1] + e1[1]);
    double l = hypot(e1[0] - e0[0], e1[1] - e0[1]);
    double dist = hypot(ux - mx, uy - my);
    double h = 0.5 * l / r->tan_half;
    /* For size, the apex that makes the two new edges on a short edge
     * exactly the target: edges come out near size rather than at the
     * circumradius, which is what narrows their spread. */
    if (q->bad == 1 && l < 1.2 * r->size) {
        double hs = sqrt(r->size * r->size - 0.25 * l * l);
        if (hs < h)
            h = hs;
    }
    if (dist > h && dist > 0) {
        ux = mx + (ux - mx) * (h / dist);
        uy = my + (uy - my) * (h / dist);
    }
    double y = uy / r22, x = (ux - r12 * y) / r11;
    out[0] = a[0] + x;
    out[1] = a[1] + y;
    return isfinite(out[0]) && isfinite(out[1]) ? 0 : -1;
}

void cdt_use_metric(cdt_refiner *r, const double m[3])
{
    struct fm_cdt *t = r->t;
    t->use_metric = r->o->metric != NULL;
    if (!t->use_metric)
        return;
    t->R[0] = sqrt(m[0]);
    t->R[1] = m[1] / t->R[0];
    t->R[2] = sqrt(m[2] - t->R[1] * t->R[1]);
}

int cdt_encroaches(cdt_refiner *r, const double p[2], int32_t a, int32_t b)
{
    const double *pa = cdt_p(r->t, a), *pb = cdt_p(r->t, b);
    double mid[2] = {0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])}, m[3];
    if (cdt_metric(r, mid, m))
        return 0;
    double ax = pa[0] - p[0], ay = pa[1] - p[1], bx = pb[0] - p[0], by = pb[1] - p[1];
    return m[0] * ax * bx + m[1] * (ax * by + ay * bx) + m[2] * ay * by < 0;
}
