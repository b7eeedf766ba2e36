/* The reference frame of a sheet: the max-min direction over the triangle
 * normals, nudged towards the mean normal within a slack, and in-plane axes
 * along strike and down dip. */
#include "fit_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "fm_vec3.h"

#define FM_PI 3.14159265358979323846
#define DEG2RAD (FM_PI / 180.0)

static double normalize3(double *a)
{
    double n = sqrt(fm_dot3(a, a));
    if (n > 0) {
        a[0] /= n;
        a[1] /= n;
        a[2] /= n;
    }
    return n;
}

void fm_fit_frame_options_default(fm_fit_frame_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->slack_degrees = 5.0;
}

void fm_fit_frame_to_local(const fm_fit_frame *f, const double xyz[3], double uvw[3])
{
    double d[3] = {xyz[0] - f->origin[0], xyz[1] - f->origin[1], xyz[2] - f->origin[2]};
    uvw[0] = fm_dot3(d, f->u);
    uvw[1] = fm_dot3(d, f->v);
    uvw[2] = fm_dot3(d, f->w);
}

void fm_fit_frame_to_world(const fm_fit_frame *f, const double uvw[3], double xyz[3])
{
    for (int k = 0; k < 3; k++)
        xyz[k] = f->origin[k] + uvw[0] * f->u[k] + uvw[1] * f->v[k] + uvw[2] * f->w[k];
}

/* Solves the (m+1) x (m+1) system of the affine minimum-norm point of m
 * points (m <= 4) by Gaussian elimination with partial pivoting; returns 0
 * when it is singular. */
static int affine_min_norm(const double (*P)[3], int m, double *alpha)
{
    double A[5][6];
    int n = m + 1;
    for (int i = 0; i < m; i++) {
        for (int j = 0; j < m; j++)
            A[i][j] = fm_dot3(P[i], P[j]);
        A[i][m] = 1.0;
        A[i][n] = 0.0;
    }
    for (int j = 0; j < m; j++)
        A[m][j] = 1.0;
    A[m][m] = 0.0;
    A[m][n] = 1.0;
    for (int c = 0; c < n; c++) {
        int piv = c;
        for (int r = c + 1; r < n; r++)
            if (fabs(A[r][c]) > fabs(A[piv][c]))
                piv = r;
        if (fabs(A[piv][c]) < 1e-14)
            return 0;
        if (piv != c)
            for (int k = 0; k <= n; k++) {
                double t = A[c][k];
                A[c][k] = A[piv][k];
                A[piv][k] = t;
            }
        for (int r = 0; r < n; r++) {
            if (r == c)
                continue;
            double f = A[r][c] / A[c][c];
            for (int k = c; k <= n; k++)
                A[r][k] -= f * A[c][k];
        }
    }
    for (int i = 0; i < m; i++)
        alpha[i] = A[i][n] / A[i][i];
    return 1;
}

/* Wolfe's algorithm for the point of smallest norm in the convex hull of
 * the unit normals. By minimax duality its norm is the largest achievable
 * min n.d, and its direction achieves it; a (near) zero result means the
 * origin is in the hull and no direction sees every normal from the front.
 * Returns that norm; x gets the point. */
static double min_norm_point(const double *nrm, size_t n, double x[3])
{
    double S[4][3], lam[4];
    int m = 1;
    memcpy(S[0], nrm, sizeof S[0]);
    lam[0] = 1.0;
    memcpy(x, nrm, 3 * sizeof(double));
    for (int major = 0; major < 1000; major++) {
        double xx = fm_dot3(x, x);
        if (xx < 1e-24)
            return 0.0;
        size_t best = 0;
        double bd = INFINITY;
        for (size_t i = 0; i < n; i++) {
            double d = fm_dot3(x, nrm + 3 * i);
            if (d < bd) {
                bd = d;
                best = i;
            }
        }
        /* Optimal when no normal lies beyond the plane through x. */
        if (bd >= xx - 1e-13)
            break;
        memcpy(S[m], nrm + 3 * best, sizeof S[m]);
        lam[m] = 0.0;
        m++;
        for (int minor = 0; minor < 8; minor++) {
            double alpha[4];
            if (!affine_min_norm((const double (*)[3])S, m, alpha)) {
                /* Dependent points: drop the newest, x stays optimal for the rest. */
                m--;
                break;
            }
            int inside = 1;
            for (int i = 0; i < m; i++)
                if (alpha[i] <= 0)
                    inside = 0;
            if (inside) {
                memcpy(lam, alpha, (size_t)m * sizeof(double));
                break;
            }
            double theta = 1.0;
            for (int i = 0; i < m; i++)
                if (alpha[i] <= 0 && lam[i] - alpha[i] > 0) {
                    double t = lam[i] / (lam[i] - alpha[i]);
                    if (t < theta)
                        theta = t;
                }
            int k = 0;
            for (int i = 0; i < m; i++) {
                double l = theta * alpha[i] + (1 - theta) * lam[i];
                if (l > 1e-15) {
                    lam[k] = l;
                    memmove(S[k], S[i], sizeof S[k]);
                    k++;
                }
            }
            m = k > 0 ? k : 1;
            if (k == 0)
                lam[0] = 1.0;
        }
        double sum = 0;
        for (int i = 0; i < m; i++)
            sum += lam[i];
        x[0] = x[1] = x[2] = 0;
        for (int i = 0; i < m; i++)
            for (int k = 0; k < 3; k++)
                x[k] += lam[i] / sum * S[i][k];
        if (m == 4) /* four affinely independent points with positive weights enclose the origin */
            return 0.0;
        /* Rounding can undo the step that theory guarantees; stop then. */
        if (!(fm_dot3(x, x) < xx * (1 - 1e-15)))
            break;
    }
    return sqrt(fm_dot3(x, x));
}

static double min_dot(const double *nrm, size_t n, const double d[3])
{
    double md = INFINITY;
    for (size_t i = 0; i < n; i++) {
        double t = fm_dot3(nrm + 3 * i, d);
        if (t < md)
            md = t;
    }
    return md;
}

/* Long axis of the sheet projected onto the plane normal to w: the
 * principal direction of the area second moment (exact per triangle). */
static void long_axis(const fm_mesh *m, const fm_fit_frame *f, double axis[3])
{
    double a[3], b[3];
    double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0};
    const double *ref = fabs(f->w[0]) < 0.9 ? ex : ey;
    double t = fm_dot3(ref, f->w);
    for (int k = 0; k < 3; k++)
        a[k] = ref[k] - t * f->w[k];
    normalize3(a);
    fm_cross3(f->w, a, b);
    const double *X = fm_mesh_vertices(m);
    const int32_t *T = fm_mesh_triangles(m);
    size_t nt = fm_mesh_ntriangles(m);
    double A = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
    for (size_t i = 0; i < nt; i++) {
        double px[3], py[3];
        for (int c = 0; c < 3; c++) {
            const double *q = X + 3 * (size_t)T[3 * i + c];
            double d[3] = {q[0] - f->origin[0], q[1] - f->origin[1], q[2] - f->origin[2]};
            px[c] = fm_dot3(d, a);
            py[c] = fm_dot3(d, b);
        }
        double ar = 0.5 * fabs((px[1] - px[0]) * (py[2] - py[0]) - (px[2] - px[0]) * (py[1] - py[0]));
        double cx = px[0] + px[1] + px[2], cy = py[0] + py[1] + py[2];
        A += ar;
        sx += ar * cx / 3;
        sy += ar * cy / 3;
        /* integral of x x^T over a triangle = area/12 (sum p p^T + c c^T), c = sum p */
        sxx += ar / 12 * (px[0] * px[0] + px[1] * px[1] + px[2] * px[2] + cx * cx);
        sxy += ar / 12 * (px[0] * py[0] + px[1] * py[1] + px[2] * py[2] + cx * cy);
        syy += ar / 12 * (py[0] * py[0] + py[1] * py[1] + py[2] * py[2] + cy * cy);
    }
    double cxx = 0, cxy = 0, cyy = 0;
    if (A > 0) {
        double mx = sx / A, my = sy / A;
        cxx = sxx / A - mx * mx;
        cxy = sxy / A - mx * my;
        cyy = syy / A - my * my;
    }
    double phi = 0.5 * atan2(2 * cxy, cxx - cyy); /* angle of the largest eigenvector */
    for (int k = 0; k < 3; k++)
        axis[k] = cos(phi) * a[k] + sin(phi) * b[k];
    if (axis[0] < -1e-12 || (fabs(axis[0]) <= 1e-12 && axis[1] < 0))
        for (int k = 0; k < 3; k++)
            axis[k] = -axis[k];
}

fm_status fm_fit_reference_frame(const fm_mesh *sheet, const fm_fit_frame_options *opt,
                                 fm_fit_frame *out, fm_error *err)
{
    fm_fit_frame_options defaults;
    if (!opt) {
        fm_fit_frame_options_default(&defaults);
        opt = &defaults;
    }
    memset(out, 0, sizeof *out);
    if (!sheet)
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "fit: no sheet");
    if (!(opt->slack_degrees >= 0 && opt->slack_degrees < 90))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                            "fit: slack_degrees must be in [0, 90), not %g", opt->slack_degrees);
    const double *X = fm_mesh_vertices(sheet);
    const int32_t *T = fm_mesh_triangles(sheet);
    size_t nt = fm_mesh_ntriangles(sheet), nv = fm_mesh_nvertices(sheet);
    double *nrm = malloc((nt ? nt : 1) * 3 * sizeof *nrm);
    double *area = malloc((nt ? nt : 1) * sizeof *area);
    if (!nrm || !area) {
        free(nrm);
        free(area);
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "fit: out of memory (frame)");
    }
    size_t n = 0;
    double total = 0, mean[3] = {0, 0, 0}, cen[3] = {0, 0, 0};
    for (size_t i = 0; i < nt; i++) {
        const double *p[3] = {X, X, X};
        int bad = 0;
        for (int c = 0; c < 3; c++) {
            int32_t vi = T[3 * i + c];
            if (vi < 0 || (size_t)vi >= nv)
                bad = 1;
            else
                p[c] = X + 3 * (size_t)vi;
        }
        if (bad) {
            free(nrm);
            free(area);
            return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                                "fit: triangle %zu has a vertex index out of range", i);
        }
        double e1[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
        double e2[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
        double c3[3];
        fm_cross3(e1, e2, c3);
        double a2 = sqrt(fm_dot3(c3, c3));
        if (!isfinite(a2)) {
            free(nrm);
            free(area);
            return fm_error_set(err, FM_ERR_NUMERIC, NULL, 0,
                                "fit: triangle %zu has non-finite coordinates", i);
        }
        if (a2 == 0)
            continue;
        for (int k = 0; k < 3; k++) {
            nrm[3 * n + k] = c3[k] / a2;
            mean[k] += 0.5 * c3[k];
            cen[k] += 0.5 * a2 * (p[0][k] + p[1][k] + p[2][k]) / 3;
        }
        area[n] = 0.5 * a2;
        total += 0.5 * a2;
        n++;
    }
    if (n == 0 || !(total > 0)) {
        free(nrm);
        free(area);
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "fit: sheet has no area");
    }
    for (int k = 0; k < 3; k++)
        out->origin[k] = cen[k] / total;
    out->area = total;

    double w[3], x[3];
    double opt_dot = min_norm_point(nrm, n, x);
    double m[3] = {mean[0], mean[1], mean[2]};
    int have_mean = normalize3(m) > 1e-12 * total;
    int given = opt->direction[0] != 0 || opt->direction[1] != 0 || opt->direction[2] != 0;
    if (opt_dot > 1e-9) {
        memcpy(w, x, sizeof w);
        normalize3(w);
        out->optimum_dot = min_dot(nrm, n, w);
    } else {
        out->optimum_dot = opt_dot;
    }
    if (given) {
        memcpy(w, opt->direction, sizeof w);
        if (!(normalize3(w) > 0) || !isfinite(w[0] + w[1] + w[2])) {
            free(nrm);
            free(area);
            return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "fit: bad reference direction");
        }
    } else if (opt_dot > 1e-9) {
        /* Walk along the great circle towards the mean normal as far as the
         * slack allows; the feasible part of that arc is one piece (caps
         * intersect in a spherically convex set), so bisect. */
        double target = cos(fmin(acos(fmin(1.0, out->optimum_dot)) +
                                 opt->slack_degrees * DEG2RAD, 0.5 * FM_PI));
        if (have_mean && opt->slack_degrees > 0) {
            double lo = 0, hi = 1, d[3];
            if (min_dot(nrm, n, m) < target) {
                for (int it = 0; it < 40; it++) {
                    double mid = 0.5 * (lo + hi);
                    for (int k = 0; k < 3; k++)
                        d[k] = (1 - mid) * w[k] + mid * m[k];
                    normalize3(d);
                    if (min_dot(nrm, n, d) >= target)
                        lo = mid;
                    else
                        hi = mid;
                }
            } else {
                lo = 1;
            }
            for (int k = 0; k < 3; k++)
                d[k] = (1 - lo) * w[k] + lo * m[k];
            normalize3(d);
            memcpy(w, d, sizeof w);
        }
    } else if (have_mean) {
        /* No direction works: the mean normal is the least bad frame for
         * the parametric fit that such a sheet gets. */
        memcpy(w, m, sizeof w);
    } else {
        w[0] = 0, w[1] = 0, w[2] = 1;
    }
    out->min_dot = min_dot(nrm, n, w);
    double md = 0, folded = 0;
    for (size_t i = 0; i < n; i++) {
        double t = fm_dot3(nrm + 3 * i, w);
        md += area[i] * t;
        if (t <= 0)
            folded += area[i];
    }
    out->mean_dot = md / total;
    out->folded_area = folded;
    out->projectable = out->min_dot > 0;
    free(nrm);
    free(area);

    memcpy(out->w, w, sizeof w);
    out->dip_degrees = acos(fmin(1.0, fabs(w[2]))) / DEG2RAD;
    if (out->dip_degrees >= 10.0) {
        double ez[3] = {0, 0, 1}, v[3];
        double t = fm_dot3(ez, w);
        for (int k = 0; k < 3; k++)
            v[k] = -(ez[k] - t * w[k]);
        normalize3(v);
        memcpy(out->v, v, sizeof v);
        fm_cross3(out->v, out->w, out->u);
        normalize3(out->u);
        out->strike_axes = 1;
    } else {
        long_axis(sheet, out, out->u);
        fm_cross3(out->w, out->u, out->v);
        normalize3(out->v);
        out->strike_axes = 0;
    }
    return FM_OK;
}
