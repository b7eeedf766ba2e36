/* faultmesh core: adaptively exact geometric predicates (see fm_predicates.h).
 *
 * Each predicate runs in up to three stages:
 *
 *  A. Floating-point filter. The determinant is evaluated from rounded
 *     coordinate differences in a fixed order, together with a bound on its
 *     forward error proportional to the "permanent" (the same expression
 *     with every term made nonnegative). The bounds are those derived in
 *     Shewchuk (1997), sec. 4.2-4.3, for exactly this evaluation order:
 *       orient2d  (3 + 16 eps) eps * permanent
 *       orient3d  (7 + 56 eps) eps * permanent
 *       incircle (10 + 96 eps) eps * permanent
 *     with eps = 2^-53; the eps^2 terms also cover the rounding of the
 *     permanent and of the final multiplication. If |det| exceeds the bound
 *     its sign is certain.
 *
 *  B. Exact determinant of the differences. The differences are recomputed
 *     with TwoDiff; when all of them were exact (always the case when the
 *     points are within a factor 2 of each other per coordinate, by
 *     Sterbenz's lemma, which covers local patches of UTM coordinates) the
 *     determinant of the differences is the determinant of the points and is
 *     evaluated exactly with short expansions.
 *
 *  C. Exact determinant of the raw coordinates. Otherwise the determinant is
 *     expanded into sums of products of raw coordinates (no rounded
 *     difference enters), every product is formed exactly as an expansion
 *     and everything is summed exactly.
 *
 * Stages B and C are exact as long as no product overflows and every
 * product of coordinate "last bits" stays above 2^-1074 (no underflow):
 * for orient2d/orient3d, nonzero coordinates of magnitude between about
 * 1e-90 and 1e90; for incircle (degree 4) between about 1e-65 and 1e75.
 *
 * All determinants below are written with the 2x2 minors
 *     m(p, q) = px*qy - py*qx
 * and O(p, q, r) = m(p, q) + m(q, r) - m(p, r), which is twice the signed
 * area of the triangle pqr. Expanding the 4x4 determinants
 *     orient3d = det [ax ay az 1; bx by bz 1; cx cy cz 1; dx dy dz 1]
 *     incircle = det [ax ay la 1; ...; dx dy ld 1], lp = px^2 + py^2
 * along their third column gives
 *     z_a O(b,c,d) - z_b O(a,c,d) + z_c O(a,b,d) - z_d O(a,b,c)
 * with z = coordinate z or lift l respectively. Subtracting row d from the
 * others shows these equal Shewchuk's 3x3 forms in the differences a-d,
 * b-d, c-d (for incircle the lift column changes only by multiples of the
 * first two columns). */
#include "fm_predicates.h"

#include "expansion.h"

#include <math.h>

#define CCW_ERRBOUND ((3.0 + 16.0 * FM_EPSILON) * FM_EPSILON)
#define O3D_ERRBOUND ((7.0 + 56.0 * FM_EPSILON) * FM_EPSILON)
#define ICC_ERRBOUND ((10.0 + 96.0 * FM_EPSILON) * FM_EPSILON)

/* ---- shared pieces of the exact stages ---------------------------------- */

/* m(p, q) as an expansion of at most 4 components. */
static int minor2(const double *p, const double *q, double *h)
{
    return fm_exp_two_two_diff(p[0], q[1], p[1], q[0], h);
}

/* h = x + y - z for expansions of at most 4 components each; at most 12. */
static int add_add_sub(int nx, const double *x, int ny, const double *y, int nz,
                       const double *z, double *h)
{
    double xy[8], negz[4];
    int nxy = fm_exp_sum(nx, x, ny, y, xy);
    for (int i = 0; i < nz; i++)
        negz[i] = -z[i];
    return fm_exp_sum(nxy, xy, nz, negz, h);
}

/* The four triangle areas O(b,c,d), O(a,c,d), O(a,b,d), O(a,b,c) of the
 * raw coordinates, each at most 12 components. */
struct areas {
    double o[4][12];
    int n[4];
};

static void raw_areas(const double *a, const double *b, const double *c, const double *d,
                      struct areas *ar)
{
    double ab[4], ac[4], ad[4], bc[4], bd[4], cd[4];
    int nab = minor2(a, b, ab), nac = minor2(a, c, ac), nad = minor2(a, d, ad);
    int nbc = minor2(b, c, bc), nbd = minor2(b, d, bd), ncd = minor2(c, d, cd);
    ar->n[0] = add_add_sub(nbc, bc, ncd, cd, nbd, bd, ar->o[0]); /* O(b,c,d) */
    ar->n[1] = add_add_sub(nac, ac, ncd, cd, nad, ad, ar->o[1]); /* O(a,c,d) */
    ar->n[2] = add_add_sub(nab, ab, nbd, bd, nad, ad, ar->o[2]); /* O(a,b,d) */
    ar->n[3] = add_add_sub(nab, ab, nbc, bc, nac, ac, ar->o[3]); /* O(a,b,c) */
}

/* ---- orient2d ----------------------------------------------------------- */

static int orient2d_exact(const double *a, const double *b, const double *c)
{
    double acx, acy, bcx, bcy, t[4];
    fm_two_diff(a[0], c[0], &acx, &t[0]);
    fm_two_diff(a[1], c[1], &acy, &t[1]);
    fm_two_diff(b[0], c[0], &bcx, &t[2]);
    fm_two_diff(b[1], c[1], &bcy, &t[3]);
    if (t[0] == 0.0 && t[1] == 0.0 && t[2] == 0.0 && t[3] == 0.0) {
        double h[4];
        return fm_exp_sign(fm_exp_two_two_diff(acx, bcy, acy, bcx, h), h);
    }
    /* O(a, b, c) from raw coordinates. */
    double ab[4], bc[4], ac[4], h[12];
    int nab = minor2(a, b, ab), nbc = minor2(b, c, bc), nac = minor2(a, c, ac);
    int n = add_add_sub(nab, ab, nbc, bc, nac, ac, h);
    return fm_exp_sign(n, h);
}

int fm_orient2d(const double *a, const double *b, const double *c)
{
    double l = (a[0] - c[0]) * (b[1] - c[1]);
    double r = (a[1] - c[1]) * (b[0] - c[0]);
    double det = l - r;
    double bound = CCW_ERRBOUND * (fabs(l) + fabs(r));
    if (det > bound)
        return 1;
    if (-det > bound)
        return -1;
    return orient2d_exact(a, b, c);
}

/* ---- orient3d ----------------------------------------------------------- */

static int orient3d_exact(const double *a, const double *b, const double *c, const double *d)
{
    double v[9], t[9];
    const double *p[3] = {a, b, c};
    int exact = 1;
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 3; k++) {
            fm_two_diff(p[i][k], d[k], &v[3 * i + k], &t[3 * i + k]);
            exact &= t[3 * i + k] == 0.0;
        }

    if (exact) {
        /* det = adz m(bd, cd) + bdz m(cd, ad) + cdz m(ad, bd) with exact
         * differences: each minor <= 4, scaled <= 8, total <= 24. */
        const double *ad = v, *bd = v + 3, *cd = v + 6;
        double m[4], s[3][8], ab[16], h[24];
        int ns[3];
        const double *rows[3][3] = {{bd, cd, ad}, {cd, ad, bd}, {ad, bd, cd}};
        for (int i = 0; i < 3; i++) {
            int nm = minor2(rows[i][0], rows[i][1], m);
            ns[i] = fm_exp_scale(nm, m, rows[i][2][2], s[i]);
        }
        int nab = fm_exp_sum(ns[0], s[0], ns[1], s[1], ab);
        int n = fm_exp_sum(nab, ab, ns[2], s[2], h);
        return fm_exp_sign(n, h);
    }

    /* det = az O(b,c,d) - bz O(a,c,d) + cz O(a,b,d) - dz O(a,b,c):
     * each term <= 24 components, total <= 96. */
    struct areas ar;
    raw_areas(a, b, c, d, &ar);
    const double z[4] = {a[2], -b[2], c[2], -d[2]};
    double s[4][24], s01[48], s23[48], h[96];
    int ns[4];
    for (int i = 0; i < 4; i++)
        ns[i] = fm_exp_scale(ar.n[i], ar.o[i], z[i], s[i]);
    int n01 = fm_exp_sum(ns[0], s[0], ns[1], s[1], s01);
    int n23 = fm_exp_sum(ns[2], s[2], ns[3], s[3], s23);
    int n = fm_exp_sum(n01, s01, n23, s23, h);
    return fm_exp_sign(n, h);
}

int fm_orient3d(const double *a, const double *b, const double *c, const double *d)
{
    double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
    double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
    double adz = a[2] - d[2], bdz = b[2] - d[2], cdz = c[2] - d[2];

    double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
    double cdxady = cdx * ady, adxcdy = adx * cdy;
    double adxbdy = adx * bdy, bdxady = bdx * ady;

    double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
    double permanent = (fabs(bdxcdy) + fabs(cdxbdy)) * fabs(adz) +
                       (fabs(cdxady) + fabs(adxcdy)) * fabs(bdz) +
                       (fabs(adxbdy) + fabs(bdxady)) * fabs(cdz);
    double bound = O3D_ERRBOUND * permanent;
    if (det > bound)
        return 1;
    if (-det > bound)
        return -1;
    return orient3d_exact(a, b, c, d);
}

/* ---- incircle ----------------------------------------------------------- */

/* h = e * (x^2 + y^2) exactly; e has at most 12 components, h at most 96. */
static int scale_by_lift(int ne, const double *e, double x, double y, double *h)
{
    double ex[24], exx[48], ey[24], eyy[48];
    int nex = fm_exp_scale(ne, e, x, ex);
    int nexx = fm_exp_scale(nex, ex, x, exx);
    int ney = fm_exp_scale(ne, e, y, ey);
    int neyy = fm_exp_scale(ney, ey, y, eyy);
    return fm_exp_sum(nexx, exx, neyy, eyy, h);
}

static int incircle_exact(const double *a, const double *b, const double *c, const double *d)
{
    double v[6], t[6];
    const double *p[3] = {a, b, c};
    int exact = 1;
    for (int i = 0; i < 3; i++)
        for (int k = 0; k < 2; k++) {
            fm_two_diff(p[i][k], d[k], &v[2 * i + k], &t[2 * i + k]);
            exact &= t[2 * i + k] == 0.0;
        }

    if (exact) {
        /* det = alift m(bd, cd) + blift m(cd, ad) + clift m(ad, bd) with
         * exact differences: each term <= 32 components, total <= 96. */
        const double *ad = v, *bd = v + 2, *cd = v + 4;
        const double *rows[3][3] = {{bd, cd, ad}, {cd, ad, bd}, {ad, bd, cd}};
        double m[4], s[3][32], s01[64], h[96];
        int ns[3];
        for (int i = 0; i < 3; i++) {
            int nm = minor2(rows[i][0], rows[i][1], m);
            ns[i] = scale_by_lift(nm, m, rows[i][2][0], rows[i][2][1], s[i]);
        }
        int n01 = fm_exp_sum(ns[0], s[0], ns[1], s[1], s01);
        int n = fm_exp_sum(n01, s01, ns[2], s[2], h);
        return fm_exp_sign(n, h);
    }

    /* det = la O(b,c,d) - lb O(a,c,d) + lc O(a,b,d) - ld O(a,b,c):
     * each term <= 96 components, total <= 384. */
    struct areas ar;
    raw_areas(a, b, c, d, &ar);
    fm_exp_negate(ar.n[1], ar.o[1]);
    fm_exp_negate(ar.n[3], ar.o[3]);
    const double *q[4] = {a, b, c, d};
    double s[4][96], s01[192], s23[192], h[384];
    int ns[4];
    for (int i = 0; i < 4; i++)
        ns[i] = scale_by_lift(ar.n[i], ar.o[i], q[i][0], q[i][1], s[i]);
    int n01 = fm_exp_sum(ns[0], s[0], ns[1], s[1], s01);
    int n23 = fm_exp_sum(ns[2], s[2], ns[3], s[3], s23);
    int n = fm_exp_sum(n01, s01, n23, s23, h);
    return fm_exp_sign(n, h);
}

int fm_incircle(const double *a, const double *b, const double *c, const double *d)
{
    double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
    double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];

    double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
    double alift = adx * adx + ady * ady;
    double cdxady = cdx * ady, adxcdy = adx * cdy;
    double blift = bdx * bdx + bdy * bdy;
    double adxbdy = adx * bdy, bdxady = bdx * ady;
    double clift = cdx * cdx + cdy * cdy;

    double det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
    double permanent = (fabs(bdxcdy) + fabs(cdxbdy)) * alift +
                       (fabs(cdxady) + fabs(adxcdy)) * blift +
                       (fabs(adxbdy) + fabs(bdxady)) * clift;
    double bound = ICC_ERRBOUND * permanent;
    if (det > bound)
        return 1;
    if (-det > bound)
        return -1;
    return incircle_exact(a, b, c, d);
}

/* ---- collinear3d -------------------------------------------------------- */

int fm_collinear3d(const double *a, const double *b, const double *c)
{
    /* The cross product (b-a)x(c-a) has components equal to the orient2d
     * determinants of the projections onto the yz, zx and xy planes, so it
     * is zero iff all three projections are collinear. */
    for (int k = 0; k < 3; k++) {
        int i = k, j = (k + 1) % 3;
        double pa[2] = {a[i], a[j]}, pb[2] = {b[i], b[j]}, pc[2] = {c[i], c[j]};
        if (fm_orient2d(pa, pb, pc) != 0)
            return 0;
    }
    return 1;
}
