/* Least-squares conformal map (Levy, Petitjean, Ray, Maillot 2002): the
 * parameters of a sheet that no plane sees one-to-one.
 *
 * A linear map of a triangle to the complex parameter plane, written in the
 * triangle's own orthonormal coordinates z, is U = alpha z + beta conj(z) +
 * gamma; it is conformal when beta = 0, and for corners z_j
 *     sum_j W_j U_j = beta sum_j W_j conj(z_j),  W_j = z_{j+2} - z_{j+1},
 * so |sum_j W_j U_j|^2 / (2 area) is the area times |beta|^2 (up to a
 * constant). Summed over the triangles and with two vertices pinned this is
 * a sparse positive definite least-squares problem; it maps a disk-like or
 * holed sheet without folds in practice (not provably: the count of
 * reversed triangles is reported), with near-uniform scale on the nearly
 * developable surfaces faults are. */
#include "fit_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "fm_vec3.h"

/* Turns and scales the map: v along the steepest descent of z over the
 * parameters (the height-field convention), or u along the long axis when
 * z hardly changes; area equal to the sheet's so parameters are metres. */
static void normalise(const fm_mesh *sheet, const unsigned char *active, double area3,
                      double *uv)
{
    const double *X = fm_mesh_vertices(sheet);
    size_t nv = fm_mesh_nvertices(sheet);
    const int32_t *T = fm_mesh_triangles(sheet);
    size_t nt = fm_mesh_ntriangles(sheet);
    double n = 0, mu = 0, mv = 0, mz = 0;
    for (size_t i = 0; i < nv; i++)
        if (active[i]) {
            n++;
            mu += uv[2 * i];
            mv += uv[2 * i + 1];
            mz += X[3 * i + 2];
        }
    mu /= n;
    mv /= n;
    mz /= n;
    double suu = 0, suv = 0, svv = 0, suz = 0, svz = 0;
    for (size_t i = 0; i < nv; i++)
        if (active[i]) {
            double a = uv[2 * i] - mu, b = uv[2 * i + 1] - mv, z = X[3 * i + 2] - mz;
            suu += a * a;
            suv += a * b;
            svv += b * b;
            suz += a * z;
            svz += b * z;
        }
    double pa = 0;
    for (size_t t = 0; t < nt; t++) {
        const double *a = uv + 2 * (size_t)T[3 * t], *b = uv + 2 * (size_t)T[3 * t + 1];
        const double *c = uv + 2 * (size_t)T[3 * t + 2];
        pa += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
    }
    double k = pa > 0 ? sqrt(area3 / pa) : 1.0;
    double det = suu * svv - suv * suv;
    double gu = det > 0 ? (svv * suz - suv * svz) / det : 0;
    double gv = det > 0 ? (suu * svz - suv * suz) / det : 0;
    double g = hypot(gu, gv), eu[2], ev[2];
    /* |grad z| over metres of parameter below tan 10 degrees: as flat as
     * the frame's long-axis rule. */
    if (g * k > 0 && g / k > tan(10.0 * 3.14159265358979323846 / 180.0)) {
        ev[0] = -gu / g;
        ev[1] = -gv / g;
        eu[0] = ev[1];
        eu[1] = -ev[0];
    } else {
        double phi = 0.5 * atan2(2 * suv, suu - svv);
        eu[0] = cos(phi);
        eu[1] = sin(phi);
        ev[0] = -eu[1];
        ev[1] = eu[0];
    }
    for (size_t i = 0; i < nv; i++) {
        double a = active[i] ? uv[2 * i] - mu : 0, b = active[i] ? uv[2 * i + 1] - mv : 0;
        uv[2 * i] = k * (a * eu[0] + b * eu[1]);
        uv[2 * i + 1] = k * (a * ev[0] + b * ev[1]);
    }
}

fm_status fm_fit_lscm(const fm_mesh *sheet, double *uv, size_t *flipped, const char *name,
                      fm_error *err)
{
    const double *X = fm_mesh_vertices(sheet);
    const int32_t *T = fm_mesh_triangles(sheet);
    size_t nv = fm_mesh_nvertices(sheet), nt = fm_mesh_ntriangles(sheet);
    unsigned char *active = calloc(nv ? nv : 1, 1);
    size_t *idx = malloc((nv ? nv : 1) * sizeof *idx);
    fm_fit_triplets q;
    memset(&q, 0, sizeof q);
    double *rhs = NULL;
    size_t *colptr = NULL, *rowind = NULL;
    double *val = NULL, *sol = NULL;
    fm_fit_spd *spd = NULL;
    fm_status st = FM_OK;
    if (!active || !idx) {
        st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (LSCM)");
        goto done;
    }
    double area3 = 0, cen[3] = {0, 0, 0};
    for (size_t t = 0; t < nt; t++) {
        const double *p0 = X + 3 * (size_t)T[3 * t], *p1 = X + 3 * (size_t)T[3 * t + 1];
        const double *p2 = X + 3 * (size_t)T[3 * t + 2];
        double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]}, c[3];
        fm_cross3(e1, e2, c);
        double a2 = sqrt(fm_dot3(c, c));
        if (!(a2 > 0))
            continue;
        area3 += 0.5 * a2;
        for (int k = 0; k < 3; k++) {
            active[T[3 * t + k]] = 1;
            cen[k] += a2 * (p0[k] + p1[k] + p2[k]);
        }
    }
    if (!(area3 > 0)) {
        st = fm_error_set(err, FM_ERR_INVALID, name, 0, "fit: sheet has no area");
        goto done;
    }
    for (int k = 0; k < 3; k++)
        cen[k] /= 6 * area3;
    /* Pins: the vertex farthest from the centroid, and the one farthest
     * from it; far apart, so the map's scale and turn are well determined. */
    size_t pa = 0, pb = 0;
    double best = -1;
    for (size_t i = 0; i < nv; i++) {
        if (!active[i])
            continue;
        double d[3] = {X[3 * i] - cen[0], X[3 * i + 1] - cen[1], X[3 * i + 2] - cen[2]};
        if (fm_dot3(d, d) > best) {
            best = fm_dot3(d, d);
            pa = i;
        }
    }
    best = -1;
    for (size_t i = 0; i < nv; i++) {
        if (!active[i])
            continue;
        double d[3] = {X[3 * i] - X[3 * pa], X[3 * i + 1] - X[3 * pa + 1], X[3 * i + 2] - X[3 * pa + 2]};
        if (fm_dot3(d, d) > best) {
            best = fm_dot3(d, d);
            pb = i;
        }
    }
    double pin_u = sqrt(best);
    if (pa == pb || !(pin_u > 0)) {
        st = fm_error_set(err, FM_ERR_INVALID, name, 0, "fit: sheet has no extent");
        goto done;
    }
    size_t nfree = 0;
    for (size_t i = 0; i < nv; i++)
        idx[i] = (active[i] && i != pa && i != pb) ? nfree++ : (size_t)-1;
    size_t n = 2 * nfree;
    rhs = calloc(n ? n : 1, sizeof *rhs);
    if (!rhs) {
        st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (LSCM)");
        goto done;
    }
    double diag_sum = 0;
    for (size_t t = 0; t < nt; t++) {
        const double *p[3];
        for (int k = 0; k < 3; k++)
            p[k] = X + 3 * (size_t)T[3 * t + k];
        double e1[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
        double e2[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]}, nrm[3];
        fm_cross3(e1, e2, nrm);
        double a2 = sqrt(fm_dot3(nrm, nrm)), L = sqrt(fm_dot3(e1, e1));
        if (!(a2 > 0))
            continue;
        /* The triangle's own frame: x along e1, y = n x x, so the corners
         * run counter-clockwise and the map keeps the sheet's orientation. */
        double xh[3] = {e1[0] / L, e1[1] / L, e1[2] / L}, yh[3];
        fm_cross3(nrm, xh, yh);
        for (int k = 0; k < 3; k++)
            yh[k] /= a2;
        double z[3][2] = {{0, 0}, {L, 0}, {fm_dot3(e2, xh), fm_dot3(e2, yh)}};
        double a[3], b[3];
        for (int j = 0; j < 3; j++) {
            a[j] = z[(j + 2) % 3][0] - z[(j + 1) % 3][0];
            b[j] = z[(j + 2) % 3][1] - z[(j + 1) % 3][1];
        }
        double w = 1.0 / a2;
        for (int j = 0; j < 3; j++) {
            size_t vj = (size_t)T[3 * t + j];
            for (int k = 0; k < 3; k++) {
                size_t vk = (size_t)T[3 * t + k];
                double huu = w * (a[j] * a[k] + b[j] * b[k]);
                double huv = w * (b[j] * a[k] - a[j] * b[k]); /* (u_j, v_k) */
                if (idx[vj] == (size_t)-1)
                    continue;
                size_t ru = 2 * idx[vj], rv = ru + 1;
                if (idx[vk] == (size_t)-1) {
                    /* Pinned: U_a = 0, U_b = pin_u (real) moves to the right. */
                    if (vk == pb) {
                        rhs[ru] -= huu * pin_u;
                        rhs[rv] -= -huv * pin_u; /* (v_j, u_k) = -(u_j, v_k) swapped */
                    }
                    continue;
                }
                size_t cu = 2 * idx[vk], cv = cu + 1;
                if (j == k)
                    diag_sum += 2 * huu;
                if (fm_fit_triplets_add(&q, ru, cu, huu) || fm_fit_triplets_add(&q, ru, cv, huv) ||
                    fm_fit_triplets_add(&q, rv, cu, -huv) || fm_fit_triplets_add(&q, rv, cv, huu)) {
                    st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (LSCM)");
                    goto done;
                }
            }
        }
    }
    /* A whisker of Tikhonov keeps a sheet in several pieces (only a caller
     * other than repair makes those) positive definite; it moves nothing
     * measurable otherwise. */
    for (size_t r = 0; r < n; r++)
        if (fm_fit_triplets_add(&q, r, r, 1e-12 * diag_sum / (double)(n ? n : 1))) {
            st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (LSCM)");
            goto done;
        }
    if (fm_fit_triplets_compress(&q, n, &colptr, &rowind, &val) != FM_OK) {
        st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (LSCM)");
        goto done;
    }
    fm_fit_triplets_free(&q);
    sol = malloc((n ? n : 1) * sizeof *sol);
    if (!sol) {
        st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "fit: out of memory (LSCM)");
        goto done;
    }
    st = fm_fit_spd_factor(n, colptr, rowind, val, &spd, name, err);
    if (st == FM_OK)
        st = fm_fit_spd_solve(spd, rhs, sol, name, err);
    if (st != FM_OK)
        goto done;
    for (size_t i = 0; i < nv; i++) {
        if (idx[i] != (size_t)-1) {
            uv[2 * i] = sol[2 * idx[i]];
            uv[2 * i + 1] = sol[2 * idx[i] + 1];
        } else {
            uv[2 * i] = i == pb ? pin_u : 0;
            uv[2 * i + 1] = 0;
        }
        if (!isfinite(uv[2 * i]) || !isfinite(uv[2 * i + 1])) {
            st = fm_error_set(err, FM_ERR_NUMERIC, name, 0, "fit: LSCM solution is not finite");
            goto done;
        }
    }
    normalise(sheet, active, area3, uv);
    size_t nflip = 0;
    for (size_t t = 0; t < nt; t++) {
        const double *a = uv + 2 * (size_t)T[3 * t], *b = uv + 2 * (size_t)T[3 * t + 1];
        const double *c = uv + 2 * (size_t)T[3 * t + 2];
        double sa = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
        if (sa > 0)
            continue;
        const double *p0 = X + 3 * (size_t)T[3 * t], *p1 = X + 3 * (size_t)T[3 * t + 1];
        const double *p2 = X + 3 * (size_t)T[3 * t + 2];
        double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]}, cr[3];
        fm_cross3(e1, e2, cr);
        if (fm_dot3(cr, cr) > 0) /* a triangle without area has no orientation to lose */
            nflip++;
    }
    *flipped = nflip;
done:
    fm_fit_spd_destroy(spd);
    free(active);
    free(idx);
    fm_fit_triplets_free(&q);
    free(rhs);
    free(colptr);
    free(rowind);
    free(val);
    free(sol);
    return st;
}
