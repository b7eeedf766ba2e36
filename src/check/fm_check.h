/* faultmesh check: what a remeshed fault is worth, measured on the output
 * mesh alone (no knowledge of how it was made), so that the figures in
 * report.json are the ones a user's own tools would find.
 *
 * Quality: the smallest 3D angle of every triangle; triangles under 20
 * degrees are "forced" when that angle sits at a corner of the mesh's own
 * boundary whose interior angle (the sum of the triangle angles there) is
 * below 40 degrees: no triangle at such a corner can have its angles
 * above 20 without cutting the corner off. Size: every edge once, against
 * the target H. Fidelity: every node's distance to the original surface
 * (closest point on its triangles). */
#ifndef FM_CHECK_H
#define FM_CHECK_H

#include <stddef.h>
#include <stdint.h>

#include "fm_closest.h"
#include "fm_core.h"
#include "fm_mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_quality {
    size_t triangles, nodes, edges;
    double angle_min;          /* degrees, smallest angle of any triangle */
    double angle_mean;         /* mean over triangles of their smallest angle */
    size_t below_30;           /* triangles with an angle under 30 degrees */
    size_t below_20;           /* ... under 20 */
    size_t below_20_forced;    /* ... of which at a boundary corner sharper than 40 */
    size_t sharp_corners;      /* boundary nodes with an interior angle under 40 */
    double edge_min, edge_max, edge_median, edge_p05, edge_p95; /* metres */
    size_t edges_in_band;      /* edges within [0.7 H, 1.4 H] */
    double area;               /* m^2 */
    double zmax;               /* highest node */
} fm_quality;

/* Quality of the triangles of m tagged tag (tag < 0: all). H > 0 is the
 * target edge length. */
fm_status fm_check_quality(const fm_mesh *m, int32_t tag, double H, fm_quality *q);

/* Distance (m) a node may lie from the original: the fidelity criterion. */
#define FM_FIDELITY_TOL 100.0

typedef struct fm_fidelity {
    size_t nodes;
    double rms, max;           /* metres */
    /* The node's nearest point on the original (its foot) tells where a
     * node farther than FM_FIDELITY_TOL lies: with its foot within
     * FM_FIDELITY_TOL of the original's outline (its edges used by one
     * triangle) it is past the original's edge, as over a gap a fault was
     * extended across to a neighbour, else over the original's inside.
     * beyond_max: largest distance of the nodes past the edge
     * (beyond_nodes of them; 0 without orig); inside_max: largest of the
     * others, with inside_over of them over FM_FIDELITY_TOL (without
     * orig every node counts as inside). */
    double beyond_max, inside_max;
    size_t beyond_nodes, inside_over;
} fm_fidelity;

/* Distances of the nodes of m used by triangles tagged tag (tag < 0: all)
 * to the surface in tree, built over orig (orig may be NULL: nothing is
 * then known of its outline and beyond_max stays 0). */
fm_status fm_check_fidelity(const fm_mesh *m, int32_t tag, const fm_mesh *orig,
                            const fm_closest_tree *tree, fm_fidelity *f);

/* What connecting faults cost: the measures of the connect issue, taken
 * from the output set and the originals alone, so that a user's own
 * checker finds the same. H is a fault's target size, D its join
 * distance; "original" is the input surface below zcut (sea level when
 * the top is cut).
 *
 * - Unclosed gap of fault A beside B: the length of A's outline edges
 *   (used by one triangle of A) whose midpoint lies within
 *   FM_LOSS_NEAR of B's output but farther than FM_LOSS_TOUCH from it,
 *   leaving out edges within H of a node A and B share. A pair's gap is
 *   the larger of (A, B) and (B, A).
 * - Missing area: the original's area (sampled at about H/4 per
 *   original triangle) farther than H/2 from the fault's own output; it
 *   is "away" where also farther than D from every other fault's output,
 *   a loss no junction can explain.
 * - Interior moved: the largest distance from an output node to the
 *   original, over the nodes whose closest point on the original lies
 *   farther than FM_LOSS_TOUCH from the original's outline; and how many
 *   such nodes are farther than FM_FIDELITY_TOL. A fault of several
 *   sheets is measured sheet by sheet: a sheet's original is the share of
 *   the original whose triangles (by their centroids) lie nearest that
 *   sheet's output, and its outline includes the seams with the other
 *   shares; a node on several sheets counts only over the inside of each.
 *   A gap closed over one strand's extension beside another strand is
 *   then measured from the outline it extends, not from the other
 *   strand's inside.
 * - Islands: edge-connected pieces of a fault's output, each sheet on its
 *   own, beyond one per sheet, or beyond the pieces of its original below
 *   zcut when more (vertices within FM_LOSS_TOUCH welded; a piece counts
 *   when it reaches H/10 below zcut): a sheet the sea level cuts in two
 *   has no island. */
#define FM_LOSS_NEAR 250.0
#define FM_LOSS_TOUCH 1.0

typedef struct fm_loss_input {
    const fm_mesh *set;          /* every fault: triangle tag = fault, 0 .. nfaults-1 */
    const int32_t *sheet;        /* per triangle: its sheet in its fault; NULL: one sheet each */
    size_t nfaults;
    const fm_mesh *const *orig;  /* per fault: its original, NULL when none */
    const double *size;          /* per fault: H (m) */
    const double *join;          /* per fault: D (m) */
    const double *zcut;          /* per fault: the original counts below this z (INFINITY: all) */
    int threads;                 /* results do not depend on it */
} fm_loss_input;

typedef struct fm_loss_fault {
    double orig_area;      /* original below zcut, m^2 */
    double missing_area;   /* of it farther than H/2 from the output, m^2 */
    double missing_away;   /* ... and farther than D from every other fault, m^2 */
    double moved_max;      /* interior moved, m */
    size_t moved_over;     /* nodes moved farther than FM_FIDELITY_TOL */
    double moved_at[3];    /* the node farthest moved (when moved_max > 0) */
    size_t pieces, orig_pieces; /* edge-connected pieces of the output (of each sheet),
                                   of the original */
    size_t sheets;         /* sheets its output has */
    size_t islands;        /* pieces beyond max(sheets, orig_pieces) */
    size_t island_triangles; /* triangles of the smallest `islands` pieces */
    double gap;            /* sum of its unclosed gaps beside every other fault, m */
} fm_loss_fault;

typedef struct fm_loss_pair {
    int32_t a, b;          /* faults, a < b */
    double gap_ab, gap_ba; /* unclosed gap of a beside b, of b beside a (m) */
    double gap;            /* the larger */
    size_t shared_nodes;
} fm_loss_pair;

typedef struct fm_loss fm_loss;

fm_status fm_check_loss(const fm_loss_input *in, fm_loss **out, fm_error *err);
void fm_loss_destroy(fm_loss *l);
const fm_loss_fault *fm_loss_fault_at(const fm_loss *l, size_t f);
/* Pairs with an unclosed gap, sorted by (a, b). */
size_t fm_loss_npairs(const fm_loss *l);
const fm_loss_pair *fm_loss_pair_at(const fm_loss *l, size_t k);

/* The elastic interaction check (docs/guide.md, "Elastic check"): how
 * strongly the elements of different faults load each other, by the
 * field of a triangular dislocation (src/elastic) in a half space.
 *
 * Every element slips in its rake direction (Aki and Richards: hanging
 * wall relative to footwall, measured from strike in the fault plane,
 * with strike and dip from its upward normal); the traction on element i
 * is sampled at its centroid, on its plane, with the normal pointing into
 * its hanging wall. K_ij (Pa/m) is the shear traction on i along i's rake
 * per unit slip of j along j's rake. K_ii must be negative (slip lowers
 * the stress that drives it); an element where it is not is named. Pairs
 * (i, j) of different faults whose centroids lie within radius x the
 * larger element size of each other are evaluated (on a grid, so the
 * cost grows with the elements, not their square), and flagged when
 * their coupling c_ij = sqrt(|K_ij K_ji| / (K_ii K_jj)) exceeds fraction:
 * there the two faults act as one fault counted twice. c_ij is |K_ij| /
 * |K_ii| for elements of one size; for elements of different sizes it is
 * what stays symmetric: reciprocity makes A_i K_ij = A_j K_ji, and c_ij is
 * the off-diagonal of the area-weighted (energy) stiffness matrix over
 * the root of its diagonal, whose 2 x 2 block of the pair loses its
 * determinant as c_ij nears 1 (a small element beside a large one would
 * otherwise read the large one's traction against its own, smaller,
 * self-stiffness).
 *
 * Vertices above the free surface (z > 0: a top kept above sea level)
 * are moved down onto it, which is where a half-space simulator puts
 * them too; an element with no vertex below it is left out (counted). */
typedef struct fm_elastic_options {
    double mu;        /* shear modulus, Pa (default 3e10) */
    double nu;        /* Poisson's ratio (default 0.25) */
    double radius;    /* search radius in element sizes (default 3) */
    double fraction;  /* flag ratio (default 0.5) */
    int full_space;   /* 1: the full-space field everywhere, no free surface: a quick
                         look (K of elements at the surface then off by up to a quarter;
                         default 0: half space) */
    int threads;      /* results do not depend on it */
} fm_elastic_options;

void fm_elastic_options_default(fm_elastic_options *o);

/* A junction of the run, to group flagged pairs by: its two faults (tags
 * of the set) and points along its curve (none for a junction without
 * one). A pair goes to the junction of its two faults whose curve passes
 * nearest the pair (the first such junction when none has a curve), or
 * to no junction (0) when its faults have none. */
typedef struct fm_elastic_junction {
    int32_t fault[2];
    const double *points; /* 3 per point */
    size_t npoints;
} fm_elastic_junction;

typedef struct fm_elastic_input {
    const fm_mesh *set;    /* every fault: triangle tag = fault, 0 .. nfaults-1 */
    size_t nfaults;
    const double *strike, *dip, *rake; /* per triangle, degrees */
    const fm_elastic_junction *junctions; /* numbered from 1 in the output */
    size_t njunctions;
} fm_elastic_input;

/* A flagged pair, i on fault a < fault b of j. */
typedef struct fm_elastic_pair {
    size_t i, j;           /* triangles of the set */
    double k_ij, k_ji;     /* Pa/m */
    double ratio;          /* coupling sqrt(|k_ij k_ji| / (K_ii K_jj)) */
    double distance;       /* between the two elements, m (0: they touch) */
} fm_elastic_pair;

#define FM_ELASTIC_EXAMPLES 5

/* Flagged pairs of one fault pair at one junction. */
typedef struct fm_elastic_group {
    int32_t a, b;          /* faults, a < b */
    size_t junction;       /* 1 .. njunctions; 0: the two faults have no junction */
    size_t pairs;
    double max_ratio, min_distance, max_k; /* max_k: largest |K_ij|, Pa/m */
    size_t example[FM_ELASTIC_EXAMPLES]; /* pairs (indices into the flagged pairs) of
                                            the largest ratio */
    size_t nexamples;
} fm_elastic_group;

typedef struct fm_elastic_summary {
    size_t elements;       /* evaluated */
    size_t above_surface;  /* left out: no vertex below the free surface */
    size_t degenerate;     /* left out: zero area */
    size_t self_wrong_sign; /* K_ii >= 0 (or not finite) */
    size_t pairs_within;   /* pairs of different faults within the radius */
    size_t pairs_evaluated, pairs_singular, pairs_flagged; /* evaluated: of those, the
                                 ones close enough to reach the fraction (elastic.c) */
    double self_min, self_max; /* K_ii range over the elements, Pa/m */
    double max_ratio;      /* over every pair evaluated */
} fm_elastic_summary;

typedef struct fm_elastic fm_elastic;

fm_status fm_check_elastic(const fm_elastic_input *in, const fm_elastic_options *opt,
                           fm_elastic **out, fm_error *err);
void fm_elastic_destroy(fm_elastic *e);
const fm_elastic_summary *fm_elastic_get_summary(const fm_elastic *e);
/* K_ii per triangle of the set (NaN where left out). */
const double *fm_elastic_self(const fm_elastic *e);
/* Triangles whose K_ii has the wrong sign, in order. */
const size_t *fm_elastic_wrong_sign(const fm_elastic *e, size_t *n);
/* Flagged pairs sorted by (fault a, fault b, junction, i, j). */
const fm_elastic_pair *fm_elastic_pairs(const fm_elastic *e, size_t *n);
/* Groups sorted by (a, b, junction). */
const fm_elastic_group *fm_elastic_groups(const fm_elastic *e, size_t *n);

/* The full interaction matrices of a small set, for a user's own
 * simulator, written as a NumPy .npy file (docs/formats.md): float64
 * little-endian, shape (N, N, 4), [i, j, c] the traction on element i
 * per unit rake slip of element j, c = 0 along i's strike, 1 up i's dip
 * (rake 90), 2 along i's rake, 3 normal (positive: tension), Pa/m.
 * Refused above FM_STIFFNESS_MAX_N elements (the file holds 32 N^2
 * bytes). Rows are computed on opt->threads threads, written in order. */
#define FM_STIFFNESS_MAX_N 10000
fm_status fm_elastic_write_matrices(const fm_elastic_input *in, const fm_elastic_options *opt,
                                    const char *path, fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
