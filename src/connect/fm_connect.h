/* faultmesh connect: neighbouring faults and the intersection curves of
 * their fitted surfaces.
 *
 * Every sheet of a fault model (fm_model.h) is a B-spline surface S(u, v)
 * valid over a rectangle that extends about 2 km beyond the sheet, cut by
 * trimming loops in (u, v). Faults that meet in nature rarely meet in the
 * data: one stops a few hundred metres short of the other (a gap) or runs
 * a few hundred metres past it (an overshoot). So both stages work on each
 * sheet's trimmed surface grown by `reach` metres over its own extension.
 *
 * Sampling. Each sheet is sampled once on the lattice of its knots (one
 * node per knot, over the whole rectangle). Each node carries S and its
 * signed distance to the trimmed outline: negative inside (point-in-loop
 * test in (u, v) on the sampled trimming curves, a crossing count per
 * lattice row), its magnitude the 3D distance to the outline mapped onto
 * the surface. A knot cell is active when the outline distance at one of
 * its corners is within reach + half its diagonal; its box bounds S over it
 * (corners, centre, and a pad for the bulge of the cubic).
 *
 * Neighbours (fm_connect_find_pairs). Sheets of different faults whose
 * active boxes come within `distance` D are candidates (sheet boxes first,
 * then an AABB tree over each sheet's cell boxes). For each candidate the
 * knot cells near the other sheet are subdivided into cells of at most
 * `sample_spacing` and triangulated; the triangles are clipped to the
 * grown region (outline distance <= reach, interpolated linearly) and to
 * the trimmed region (<= 0). Whether two clipped meshes cross is decided
 * with exact orient3d tests; their distance is the smallest vertex-to-mesh
 * distance both ways (closest-point trees), which for these fine, nearly
 * flat samples is within a few metres of the true distance. A pair is
 * reported when its grown surfaces come within D.
 *
 * Intersection curves (fm_connect_intersect). The cells of each sheet
 * whose boxes overlap the other's are subdivided and triangulated on one
 * lattice, so that neighbouring triangles share edges. An intersection
 * point is an edge of one mesh crossing a triangle of the other, decided
 * with exact orient3d on B's vertices moved by a fixed vector of a few
 * ulps (micrometres) off every axis, because fitted planes and lattices
 * put whole rows of one mesh's vertices exactly on the other's planes;
 * remaining exact zeros are broken by rules (a vertex on a plane counts as
 * above it; an edge on a line of the other mesh goes, by vertex ids, to
 * one of the two triangles sharing that edge). So each triangle pair meets
 * in 0 or 2 points (pairs that do not are skipped) and the points chain
 * into open or closed polylines. Each point is then solved for onto both
 * surfaces: Newton (with
 * Levenberg-Marquardt damping, so a small crossing angle slows it but does
 * not break it) on S_A(uA, vA) - S_B(uB, vB) = 0 with the point held on the
 * plane through its start across the curve; a point that does not converge
 * falls back to alternating closest-point projections (fm_fit_project) and
 * is counted. Curves are cut where they leave either sheet's grown region
 * (clip_to_reach) or its rectangle, and resampled at `spacing` (3D arc
 * length), every resampled point solved again. Per point and per sheet the
 * curve records whether it lies inside the trimmed outline, its signed
 * outline distance (> 0: in the extension, the gap the sheet must be
 * extended by to reach the curve), and for inside points the flap: the
 * distance over the surface, at right angles to the curve, to the outline
 * on the nearer side (a flap under D is an overshoot to trim).
 *
 * Everything is deterministic: fixed orders; find_pairs, find_duplicates
 * and the plan may run on threads, but store every result by index, so
 * nothing depends on their number. Nothing prints.
 * Limitations: a lattice cell of the fine sampling that contains a closed
 * curve smaller than itself, or a tangential touch, can be missed; distances
 * between the sampled meshes are vertex-to-mesh (an edge-to-edge closest
 * pair between samples counts at its nearer vertex). */
#ifndef FM_CONNECT_H
#define FM_CONNECT_H

#include <stddef.h>

#include "fm_core.h"
#include "fm_model.h"
#include "fm_model_cache.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_connect_options {
    double distance;       /* D: pairs whose grown surfaces come this close (m); default 1000 */
    double reach;          /* growth beyond the outline over the extension (m); < 0 = distance
                              (default -1) */
    double sample_spacing; /* largest fine cell (m); default 250 */
    double spacing;        /* curve point spacing, 3D arc length (m); default 250 */
    double tolerance;      /* curve points: |S_A - S_B| target (m); default 1e-6 */
    int clip_to_reach;     /* intersect: keep only curve parts within reach of both
                              outlines (1, default) or the whole rectangles (0) */
    int nthreads;          /* find_pairs: sheets sampled and candidates measured on this
                              many threads (default 1); the pairs do not depend on it */
} fm_connect_options;

void fm_connect_options_default(fm_connect_options *opt);

/* ---- Neighbours ---- */

typedef struct fm_connect_pair {
    size_t fault_a, sheet_a;  /* (fault_a, sheet_a) < (fault_b, sheet_b) (indices into the models
                                 array; sheets of one fault pair up too: a branching fault
                                 is rejoined as two faults are) */
    size_t fault_b, sheet_b;
    double distance;          /* grown surfaces: smallest distance found (0: they cross) */
    int crosses;              /* grown surfaces intersect */
    double trimmed_distance;  /* trimmed surfaces: smallest distance, INFINITY when more
                                 than distance + 2 reach */
    int trimmed_crosses;      /* the trimmed surfaces themselves intersect */
    double point_a[3], point_b[3]; /* where the grown surfaces are closest (crossing: a
                                      point near the intersection on each) */
} fm_connect_pair;

typedef struct fm_connect_pairs fm_connect_pairs;

typedef struct fm_connect_pairs_stats {
    size_t sheets;            /* sheets sampled */
    size_t cells;             /* active knot cells */
    size_t candidates;        /* sheet pairs whose boxes came within D */
    size_t measured;          /* of those, pairs with cells near each other (meshed) */
    double time_sample, time_candidates, time_measure; /* seconds (wall clock) */
} fm_connect_pairs_stats;

/* Finds the pairs among the sheets of models[0 .. n-1] (NULL entries are
 * skipped). Sorted by fault_a, sheet_a, fault_b, sheet_b. opt may be NULL. */
fm_status fm_connect_find_pairs(const fm_model *const *models, size_t n,
                                const fm_connect_options *opt, fm_connect_pairs **out,
                                fm_error *err);
void fm_connect_pairs_destroy(fm_connect_pairs *p);
size_t fm_connect_pairs_count(const fm_connect_pairs *p);
const fm_connect_pair *fm_connect_pairs_get(const fm_connect_pairs *p, size_t i);
const fm_connect_pairs_stats *fm_connect_pairs_get_stats(const fm_connect_pairs *p);

/* ---- Intersection curves ---- */

/* How a curve sits on one sheet, by the larger share of its length. */
typedef enum fm_connect_role {
    FM_CONNECT_THROUGH = 0,  /* inside the outline, the sheet continues past it by more
                                than D on both sides */
    FM_CONNECT_OVERSHOOT = 1,/* inside, but the sheet ends within D beyond it (a flap) */
    FM_CONNECT_GAP = 2       /* in the extension: the sheet stops short of it */
} fm_connect_role;

typedef struct fm_connect_side {
    fm_connect_role role;
    double length_inside;    /* m of curve inside the trimmed outline */
    double length_extension; /* m of curve in the extension */
    double max_gap;          /* largest outline distance of points in the extension (0 if none) */
    double median_gap;       /* ... their median (0 if none) */
    double median_flap;      /* inside points whose flap is within D: median flap
                                (INFINITY if none) */
    int end_inside[2];       /* first and last point inside the outline */
} fm_connect_side;

typedef struct fm_connect_curve_info {
    size_t npoints;
    int closed;              /* the last point joins the first (not repeated) */
    double length;           /* 3D polyline length (m) */
    double min_angle, max_angle, mean_angle; /* crossing angle of the surfaces (degrees) */
    double max_dist[2];      /* largest |xyz - S(u, v)| of the points, sheet A and B */
    size_t fallback_points;  /* points solved by alternating projection */
    size_t unconverged;      /* points left above the tolerance */
    fm_connect_side side[2]; /* sheet A, sheet B */
} fm_connect_curve_info;

typedef struct fm_connect_curves fm_connect_curves;

/* Intersection curves of sheet_a of a with sheet_b of b (a and b may be the
 * same model with different sheets). opt may be NULL. Curves are sorted by
 * their first point (x, then y, then z); an open curve runs from its end
 * with the smaller such point. */
fm_status fm_connect_intersect(const fm_model *a, size_t sheet_a, const fm_model *b,
                               size_t sheet_b, const fm_connect_options *opt,
                               fm_connect_curves **out, fm_error *err);
void fm_connect_curves_destroy(fm_connect_curves *c);

size_t fm_connect_curves_count(const fm_connect_curves *c);
const fm_connect_curve_info *fm_connect_curve_get_info(const fm_connect_curves *c, size_t i);
/* Points, 3 doubles each (the mean of S_A and S_B at the solved parameters). */
const double *fm_connect_curve_points(const fm_connect_curves *c, size_t i, size_t *n);
/* Parameters on sheet A (side 0) or B (side 1), 2 doubles per point. */
const double *fm_connect_curve_params(const fm_connect_curves *c, size_t i, int side);
/* Per point: 1 inside the trimmed outline of that side's sheet. */
const unsigned char *fm_connect_curve_inside(const fm_connect_curves *c, size_t i, int side);
/* Per point: signed 3D distance to that sheet's outline (< 0 inside). */
const double *fm_connect_curve_outline_distance(const fm_connect_curves *c, size_t i,
                                                int side);
/* Per point: the flap (see above) for inside points when within D, else INFINITY;
 * NAN for points outside. */
const double *fm_connect_curve_flap(const fm_connect_curves *c, size_t i, int side);
/* Per point: crossing angle of the two surfaces (degrees, 0..90). */
const double *fm_connect_curve_angles(const fm_connect_curves *c, size_t i);

/* ---- Near-duplicates ----
 *
 * A fault that repeats another over much of its area (a historical-rupture
 * composite over its section faults, an alternative representation) is not
 * joined to it: one of the two is kept. Overlap is measured on the sampled
 * trimmed surfaces (fm_model_samples): the share of a fault's area whose
 * sample triangles have their centroid within `tolerance` of the other
 * fault's samples. A pair is a duplicate when the larger of its two shares
 * reaches `min_share`. Rule: FM_CONNECT_KEEP_SMALLER (default) gives up the
 * larger fault of the pair, which keeps the section faults and drops the
 * composites over them; FM_CONNECT_KEEP_LARGER the opposite. Equal areas:
 * the later fault (higher index) goes. Nothing is lost by it: the fault the
 * rule would give up goes only when the faults it is paired with cover
 * (together, within `tolerance`) at least `min_share` of it; otherwise the
 * other of the pair goes (a small patch lying on a large fault is given up,
 * never the large fault). Pairs decide in order of their
 * larger share, strongest first; a pair one of whose faults has already
 * been given up decides nothing (the other stays unless a pair of its own
 * drops it). */
typedef enum fm_connect_keep {
    FM_CONNECT_KEEP_SMALLER = 0,
    FM_CONNECT_KEEP_LARGER = 1
} fm_connect_keep;

typedef struct fm_connect_duplicate_options {
    double tolerance;     /* m; default 50 */
    double min_share;     /* in (0, 1]; default 0.5 */
    fm_connect_keep keep;
    int nthreads;         /* faults measured on this many threads (default 1); the
                             result does not depend on it */
} fm_connect_duplicate_options;

void fm_connect_duplicate_options_default(fm_connect_duplicate_options *opt);

typedef struct fm_connect_duplicate {
    size_t dropped, kept; /* fault indices: the one the rule gives up, the other */
    double share[2];      /* share of the dropped [0] and kept [1] fault's area within
                             the tolerance of the other */
    double area[2];       /* sampled trimmed areas (m^2), dropped [0] and kept [1] */
    double cover;         /* share of the dropped fault's area within the tolerance of
                             any fault it is paired with */
    int decided;          /* 1: this pair gave up `dropped`; 0: an earlier pair had
                             already given up one of the two */
} fm_connect_duplicate;

/* Overlap of two faults (all their sheets): share[0] of a's area lies within
 * tolerance of b, share[1] of b's within tolerance of a; area[] their
 * sampled areas. */
fm_status fm_connect_overlap(const fm_model *a, const fm_model *b, double tolerance,
                             double share[2], double area[2], fm_error *err);

/* The duplicate pairs among the fault pairs of `pairs` (from
 * fm_connect_find_pairs on the same models) whose trimmed surfaces come
 * within the tolerance, in the order they were decided; *out is malloc'ed
 * (free it), NULL when there are none. opt may be NULL. */
fm_status fm_connect_find_duplicates(const fm_model *const *models, size_t n,
                                     const fm_connect_pairs *pairs,
                                     const fm_connect_duplicate_options *opt,
                                     fm_connect_duplicate **out, size_t *nout, fm_error *err);


/* ---- The junction plan ----
 *
 * Everything the mesher needs to make faults that meet share their nodes:
 * for every pair of sheets of different faults within D, the intersection
 * curves of their extended surfaces, each decided as a junction, cut to
 * the part both sheets use, sampled once at the mesh size H and given to
 * both sheets with the very same nodes.
 *
 * Policy, per curve and per side (its role, see fm_connect_side): a side
 * that runs THROUGH the curve keeps both sides of it (the curve is an
 * interior constraint there); a side that stops short of it (GAP) or runs
 * just past it (OVERSHOOT) ENDS at it, keeping the side where the bulk of
 * the sheet lies: the gap is filled over the sheet's own extension, the
 * flap trimmed. Two through sides make a crossing, one a T-junction, none
 * a corner.
 *
 * The part of the curve a sheet that ends uses is found by walking the
 * curve both ways from the middle of its points that matter (inside, or in
 * the extension within D): inside the outline the walk goes on until the
 * curve leaves the outline; in the extension it goes on while the nearest
 * outline point moves along with the curve (the curve faces the edge that
 * ends there) and stops where that point sticks at a corner of the
 * outline (the curve has passed the end of the facing edge). A through
 * side uses the part of the curve inside its outline. The junction's curve
 * is the part both use, clipped at sea level when the top is cut (with a
 * node solved on both surfaces at z = sea level exactly), resampled at H,
 * every node solved onto both surfaces.
 *
 * Where the curves of two junctions on a common sheet cross (or end
 * within H/4 of each other), three faults meet: the point on all three
 * surfaces is solved for (Newton on S_A = S_B = S_C) and becomes one node
 * of both curves, and of the third pair's curve when it passes within H/2.
 * Otherwise junction curves on one sheet must not cross or come within H/4
 * of one another; junctions are accepted longest first and a later one
 * that conflicts is left unjoined with that reason. Near-duplicate faults
 * (fm_connect_find_duplicates) are given up first and join nothing.
 * Deterministic for any thread count. */

/* Told how far the plan's curves are: done of total sheet outlines and
 * pairs measured. Called from worker threads, one call at a time. */
typedef void (*fm_connect_progress_fn)(void *user, size_t done, size_t total);

typedef struct fm_connect_plan_options {
    double distance;   /* D: join tolerance (m); default 1000 */
    double size;       /* H: node spacing along junction curves (m); default 1000 */
    int cut;           /* 1 (default): clip junction curves to z <= sea_level */
    double sea_level;  /* default 0 */
    int nthreads;      /* neighbours, near-duplicates and every pair's curves are found
                          on this many threads (it overrides duplicates.nthreads);
                          default 1 */
    fm_connect_duplicate_options duplicates;
    fm_connect_progress_fn progress; /* NULL (default): not told */
    void *progress_user;
    /* Per fault (indices of the models array), where faults differ; NULL
     * (default): every fault takes the values above. A pair is joined
     * within the larger of its faults' distances (distance above must be
     * the largest: it bounds the neighbour search), its curve sampled at
     * the smaller of their sizes (size above should be the smallest:
     * triple points are merged at it), and cut at sea level unless
     * neither fault is cut. A fault whose joins[f] is 0 joins nobody. */
    const double *fault_distance;
    const double *fault_size;
    const unsigned char *fault_cut;
    const unsigned char *fault_joins;
    /* The pairs, near-duplicates and traced curves found before for the
     * same models and options (fm_connect_neighbours_get, under
     * fm_connect_neighbours_key of them); NULL (default): found now.
     * Borrowed for the call. */
    const struct fm_connect_neighbours *neighbours;
} fm_connect_plan_options;

void fm_connect_plan_options_default(fm_connect_plan_options *opt);

typedef enum fm_junction_type {
    FM_JUNCTION_CROSSING = 0, /* both sheets continue through the curve */
    FM_JUNCTION_T = 1,        /* one ends at the other */
    FM_JUNCTION_CORNER = 2,   /* both end at the curve */
    FM_JUNCTION_UNJOINED = 3  /* left as it is; see reason */
} fm_junction_type;

const char *fm_junction_type_name(fm_junction_type t);

typedef struct fm_connect_junction {
    size_t fault[2], sheet[2];
    fm_junction_type type;
    fm_connect_role role[2];   /* as found by fm_connect_intersect */
    double gap;                /* largest gap closed, m (0: none) */
    double overshoot;          /* largest flap trimmed, m (0: none) */
    double length;             /* of the shared curve, m (unjoined: of the raw curve) */
    double min_angle;          /* smallest crossing angle of the surfaces along it, degrees */
    double distance;           /* smallest distance of the extended surfaces, m (0: they meet) */
    long curve;                /* shared curve index; -1 when unjoined, but for an unjoined
                                  junction one sheet stops short at (clearance > 0): its
                                  curve, on that sheet only */
    double clearance;          /* unjoined: the gap (m) left where sheet short_side was
                                  trimmed to stop short of the other instead of running
                                  through it; 0: none */
    int short_side;            /* 0 or 1, when clearance > 0 */
    const char *reason;        /* unjoined: why (static text); NULL otherwise */
} fm_connect_junction;

/* A shared curve as one sheet sees it. */
typedef struct fm_connect_shared {
    size_t curve;          /* plan curve index */
    size_t n;              /* nodes, >= 2 */
    const double *uv;      /* 2 per node, in this sheet's (u, v) */
    const int64_t *node;   /* plan node index per node */
    int end;               /* 1: the sheet ends at the curve and keeps what lies on the
                              left of it in (u, v), going from node 0 to node n-1
                              (outer loops are counter-clockwise); 0: interior */
} fm_connect_shared;

typedef struct fm_connect_plan_stats {
    size_t pairs, curves, junctions[4]; /* by fm_junction_type */
    size_t duplicates;                  /* faults given up as near-duplicates */
    size_t triple_points;               /* points where junction curves of three faults meet */
    size_t pairs_kept, pairs_traced;    /* pairs whose curves were taken from kept runs
                                           (fm_connect_neighbours) or traced now */
    double time_pairs, time_curves, time_total; /* seconds, wall clock */
} fm_connect_plan_stats;

typedef struct fm_connect_plan fm_connect_plan;

/* Plans the junctions of models[0 .. n-1] (NULL entries skipped). opt may
 * be NULL. */
fm_status fm_connect_plan_build(const fm_model *const *models, size_t n,
                                const fm_connect_plan_options *opt, fm_connect_plan **out,
                                fm_error *err);
void fm_connect_plan_destroy(fm_connect_plan *p);

size_t fm_connect_plan_njunctions(const fm_connect_plan *p);
const fm_connect_junction *fm_connect_plan_junction(const fm_connect_plan *p, size_t i);
/* Shared nodes: 3 coordinates each (the mean of both surfaces' points). */
size_t fm_connect_plan_nnodes(const fm_connect_plan *p);
const double *fm_connect_plan_nodes(const fm_connect_plan *p);
/* The shared curves of one sheet, in plan curve order. */
size_t fm_connect_plan_sheet(const fm_connect_plan *p, size_t fault, size_t sheet,
                             const fm_connect_shared **out);
/* 1 when the fault was given up as a near-duplicate (and the pair that
 * decided it, when dup is not NULL). */
int fm_connect_plan_dropped(const fm_connect_plan *p, size_t fault,
                            const fm_connect_duplicate **dup);
const fm_connect_plan_stats *fm_connect_plan_get_stats(const fm_connect_plan *p);
/* The sheet pairs and near-duplicates the plan was made from (found, or
 * given in its options), for fm_connect_neighbours_put. */
const fm_connect_pairs *fm_connect_plan_pairs(const fm_connect_plan *p);
const fm_connect_duplicate *fm_connect_plan_duplicates(const fm_connect_plan *p, size_t *n);

/* ---- Neighbours kept between runs ----
 *
 * Of a plan's work, finding the sheet pairs within D and the
 * near-duplicates, and tracing each pair's intersection curves (up to
 * their resampling at a spacing that follows H), do not depend on the
 * mesh size, the sea level or the per-fault sizes: a run at another size,
 * or again, may take them from a cache folder (the fit cache's,
 * fm_model_cache.h) instead, and then samples no sheet's lattice; what
 * follows H (resampling, classifying, deciding, clipping at sea level,
 * triple points, conflicts) is made anew, so the plan is the same bit for
 * bit. A pair's curves are kept with the join distance they were traced
 * at (the larger of its faults'); a run whose per-fault join distances
 * give a pair another traces that pair again. They are kept under a key,
 * the SHA-256 of
 *  - the file format and the code that finds them (a digest of the
 *    sources of core, repair, fit and connect and the compiler and flags,
 *    made by the build; and fm_model_code_id()),
 *  - the fit-cache key of every fault's model, in order (all zero bytes
 *    for a fault with none), which stands for the model bit for bit,
 *  - D and the near-duplicate rule (tolerance, min_share, keep).
 * So a key never names stale neighbours. Files are written whole or not
 * at all, and carry a checksum: a damaged, truncated or foreign file is
 * rejected (found again, and stored anew). Layout:
 * DIR/connect/XX/KEY.fmn, XX the first two hexadecimal digits. */
#define FM_CONNECT_KEY_BYTES 32
typedef struct fm_connect_neighbours fm_connect_neighbours;

void fm_connect_neighbours_key(const unsigned char (*model_keys)[FM_MODEL_KEY_BYTES], size_t n,
                               const fm_connect_plan_options *opt,
                               unsigned char key[FM_CONNECT_KEY_BYTES]);
/* FM_OK and *out the neighbours stored under key for nfaults faults, or
 * FM_OK and *out NULL when there are none; an error (err set, *out NULL)
 * when a file is there but rejected or unreadable. */
fm_status fm_connect_neighbours_get(const char *dir, const unsigned char key[FM_CONNECT_KEY_BYTES],
                                    size_t nfaults, fm_connect_neighbours **out, fm_error *err);
/* Stores the pairs, near-duplicates and traced curves of a plan of
 * nfaults faults. */
fm_status fm_connect_neighbours_put(const char *dir, const unsigned char key[FM_CONNECT_KEY_BYTES],
                                    size_t nfaults, const fm_connect_plan *plan, fm_error *err);
void fm_connect_neighbours_destroy(fm_connect_neighbours *nb);

#ifdef __cplusplus
}
#endif
#endif
