/* check_connect: exact triangle-triangle contact and floating-point
 * distances, for the independent check of conforming fault meshes.
 *
 * Every contact decision is a combination of signs of fm_orient3d and
 * fm_orient2d (adaptively exact), so touching at a single point or along
 * an edge is found exactly, whatever the coordinates. Nothing else of the
 * faultmesh library is used.
 *
 * Triangles are closed point sets. A triangle is degenerate when two of its
 * vertex indices are equal or its corners are exactly collinear; then it is
 * the segment between its two extreme corners (or a point). */
#ifndef CC_GEOM_H
#define CC_GEOM_H

#include <stdint.h>

/* 1 if the corners are exactly collinear (including coincident). */
int cc_degenerate(const double *a, const double *b, const double *c);

/* 1 if the closed segment ab meets the closed triangle uvw (uvw not
 * degenerate). */
int cc_seg_tri(const double *a, const double *b, const double *u, const double *v, const double *w);

/* 1 if the closed segments ab and cd (in 3D) meet. */
int cc_seg_seg(const double *a, const double *b, const double *c, const double *d);

/* 1 if the closed triangles meet anywhere (touching counts); either may be
 * degenerate. */
int cc_tri_tri(const double *const p[3], const double *const q[3]);

typedef enum cc_contact {
    CC_APART = 0, /* no contact beyond the shared vertices / edge */
    CC_VIOLATION, /* they meet somewhere else (cross, touch, overlap) */
    CC_SKIPPED    /* a degenerate triangle that shares a vertex index */
} cc_contact;

/* Classifies two triangles given by vertex indices (ia, ib) and the
 * coordinate array x (3 doubles per vertex). Sharing is by index only:
 * - no index shared: any contact is a violation;
 * - one index shared: a violation if they meet anywhere but that vertex;
 * - two shared (an edge): a violation if they overlap beyond it (only
 *   possible when coplanar, third corners on the same side);
 * - three shared: the same triangle twice, a violation. */
cc_contact cc_classify(const uint32_t ia[3], const uint32_t ib[3], const double *x);

/* Euclidean distances in floating point (not exact; 0 when the exact test
 * says the sets meet). Coordinates are taken relative to a nearby point,
 * so UTM magnitudes lose nothing that matters at metre scale. */
double cc_dist_seg_tri(const double *a, const double *b, const double *const t[3]);
double cc_dist_tri_tri(const double *const p[3], const double *const q[3]);

#endif
