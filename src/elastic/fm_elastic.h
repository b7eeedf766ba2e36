/* faultmesh elastic: displacement and strain of a triangular dislocation
 * element (TDE) in a homogeneous isotropic elastic full space and half
 * space, after Nikkhoo & Walter (2015, GJI 201:1117, doi:10.1093/gji/ggv035).
 *
 * Used to check a remeshed fault against the original one by the field
 * its slip produces, so the conventions follow the reference values in
 * ../shared/elastic (Nikkhoo's TDdispFS/TDdispHS/TDstress*), not Okada's:
 *
 * Coordinates x = East, y = North, z = Up; the half-space solid is z <= 0
 * (free surface z = 0). tri: vertices P1, P2, P3 (row-major [3][3]);
 * slip[3] = {strike-slip, dip-slip, tensile} in the TD frame:
 *   n = (P2-P1)x(P3-P1) normalised (vertex order matters),
 *   s = z x n normalised (s = y*sign(nz) when the triangle is horizontal),
 *   d = n x s,
 * so that u(+n side) - u(-n side) = Ss*s + Ds*d + Ts*n (Ts > 0 opens).
 * Displacements are in the units of the slip; strains are tensor strains
 * (exy = (dux/dy + duy/dx)/2), order xx yy zz xy xz yz.
 *
 * Points on a vertex or an edge of the triangle (within 1e-12 of its
 * longest edge; the field is singular there) give NaN, as the reference
 * does; every other point, including points on the triangle's plane and on
 * the extensions of its edges, and triangles touching the free surface,
 * gives a finite value: being free of the artefacts of the classical
 * angular-dislocation formulas there is what this module is for. Exactly
 * on the triangle, where u jumps, the value is the +n side's.
 *
 * The full space is closed-form; the half space adds Mindlin's image terms
 * by quadrature (docs/elastic.md), so it costs more near the surface. */
#ifndef FM_ELASTIC_H
#define FM_ELASTIC_H

#ifdef __cplusplus
extern "C" {
#endif

/* Returned when an observation point (or, in the half space, a vertex)
 * lies above the free surface: the half-space solution does not exist
 * there, and silently mirroring it would hide a caller's sign error. */
#define FM_ELASTIC_EOUTSIDE (-1)
/* Returned for a degenerate triangle (zero area) or bad nu. */
#define FM_ELASTIC_EDEGENERATE (-2)

/* The TD frame vectors n, s, d (unit, EFCS) defined above; returns 0 or
 * FM_ELASTIC_EDEGENERATE. The elastic check uses it to express slip given
 * in another frame. */
int fm_tde_frame(const double tri[3][3], double n[3], double s[3], double d[3]);

/* Full space. */
int fm_tde_disp_fs(const double obs[3], const double tri[3][3], const double slip[3], double nu,
                   double u[3]);
int fm_tde_strain_fs(const double obs[3], const double tri[3][3], const double slip[3], double nu,
                     double eps[6]); /* xx yy zz xy xz yz, tensor strain */

/* Half space z <= 0; FM_ELASTIC_EOUTSIDE if obs z > 0 or a vertex z > 0. */
int fm_tde_disp_hs(const double obs[3], const double tri[3][3], const double slip[3], double nu,
                   double u[3]);
int fm_tde_strain_hs(const double obs[3], const double tri[3][3], const double slip[3], double nu,
                     double eps[6]);

/* Hooke's law: sig = 2 mu eps + lambda tr(eps) I, same component order. */
void fm_tde_stress_from_strain(const double eps[6], double mu, double lambda, double sig[6]);

#ifdef __cplusplus
}
#endif
#endif
