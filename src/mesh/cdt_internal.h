/* Private to the CDT (fm_cdt.h): the triangle structure and the operations
 * the builder and the refiner share.
 *
 * Triangles are counter-clockwise vertex triples in slots; edge i of
 * triangle t lies opposite its vertex i, runs from vertex i+1 to vertex
 * i+2 (mod 3) and is named by the handle 3t+i. Neighbours are stored as the
 * handle of the twin edge, so crossing an edge needs no search. Three
 * super-triangle vertices come first (internal index = caller index + 3):
 * every point is inside, so there is no hull to special-case; triangles
 * outside the domain are kept (flagged) rather than deleted. */
#ifndef CDT_INTERNAL_H
#define CDT_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "fm_cdt.h"
#include "fm_predicates.h"

#define CDT_NSUPER 3
#define CDT_DEAD 0xff

typedef struct cdt_bedge {
    int32_t org, dst, twin, cons;
    uint8_t region;
} cdt_bedge;

typedef struct cdt_pair {
    int32_t a, b;
} cdt_pair;

/* A CDT made by fm_cdt_create_graph (cdt_graph.c): the arrangement as
 * built, kept so that faces can be selected (again) until refinement
 * changes the triangles. Segments there are pieces: one per triangulation
 * edge of an input segment as recovered (an input segment split by points
 * lying on it has several), user pieces in input order first, then the
 * convex hull's edges that lie on no segment. */
typedef struct cdt_graph {
    size_t nin;              /* input segments */
    int32_t *in_sid;         /* their caller ids */
    size_t npc, nuser;       /* pieces, of which user pieces */
    int32_t *pc;             /* internal point indices, 2 per piece */
    int32_t *pc_orig;        /* input segment of a piece, -1 on the hull */
    int32_t *first;          /* per input segment: its first piece */
    int32_t *left, *right;   /* per piece: face on either side, -1 outside */
    size_t nfaces;
    double *area, *point;    /* per face: (u, v) area, a point inside */
    unsigned char *open;     /* per face: 1 when hull pieces bound it */
    int32_t *tface;          /* per triangle slot: face, -1 outside the hull */
    int32_t *tc0;            /* per edge handle: piece */
    size_t nt0;              /* slots tface and tc0 describe; 0: refined */
} cdt_graph;

/* Called for every triangle created or changed, so refinement can queue
 * it; NULL while building. */
typedef void (*cdt_touch_fn)(struct fm_cdt *t, int32_t tri);

struct fm_cdt {
    /* points */
    double *xy;
    int32_t *pseg;   /* input segment a point lies on, or -1 */
    int32_t *vtri;   /* one triangle incident to each point */
    int32_t *vmark;  /* scratch per point (fan stitching) */
    size_t np, pcap, ninput;
    /* triangles */
    int32_t *tv, *tn, *tc; /* vertices, twin handles, constraint (input segment or -1) */
    uint8_t *region;       /* 1 domain, 0 outside, CDT_DEAD free slot */
    uint32_t *stamp;       /* bumped whenever a slot is rewritten */
    uint32_t *tmark;
    uint32_t epoch;
    size_t nt, tcap;
    int32_t *freel;
    size_t nfree, freecap;
    int32_t last;          /* a recent triangle, where walks start */
    /* input segments */
    size_t nseg;
    int32_t *seg;          /* internal point indices, 2 per segment */
    int32_t *sid;          /* caller ids */
    /* Graph CDTs: per segment the input segment it is a piece of (or nin
     * for the hull), for the order of the results; and how many segments
     * come before the hull pieces, which are never split. NULL and nseg
     * for loop CDTs, whose segments are the input segments. */
    int32_t *sorig;
    size_t nuser;
    cdt_graph *graph;
    uint8_t *apex;         /* per input point: small-angle apex */
    /* cavity scratch */
    int32_t *cav, *stack;
    size_t ncav, cavcap, stackcap;
    cdt_bedge *bnd;
    int32_t *bnde;
    size_t nbnd, bndcap;
    int32_t *newt;
    size_t newcap;
    cdt_pair *pairs;
    size_t npairs, paircap;
    /* Delaunay in a metric: circle tests on the plane mapped by R (upper
     * Cholesky factor r11, r12, r22) when use_metric is set. */
    int use_metric;
    double R[3];
    /* refinement hook */
    cdt_touch_fn touch;
    void *touch_user;
    /* results */
    int32_t *out_tri, *out_pseg, *out_edges, *out_eid;
    unsigned char *out_eint;
    size_t out_nt, out_ne;
    fm_cdt_refine_stats stats;
};

static inline int32_t cdt_org(const struct fm_cdt *t, int32_t e)
{
    int32_t tri = e / 3, i = e % 3;
    return t->tv[3 * tri + (i + 1) % 3];
}
static inline int32_t cdt_dst(const struct fm_cdt *t, int32_t e)
{
    int32_t tri = e / 3, i = e % 3;
    return t->tv[3 * tri + (i + 2) % 3];
}
static inline const double *cdt_p(const struct fm_cdt *t, int32_t v) { return t->xy + 2 * (size_t)v; }
static inline int cdt_has_super(const struct fm_cdt *t, int32_t tri)
{
    const int32_t *v = t->tv + 3 * (size_t)tri;
    return v[0] < CDT_NSUPER || v[1] < CDT_NSUPER || v[2] < CDT_NSUPER;
}

/* Is d inside the circle through a, b, c (counter-clockwise)? In the
 * metric when t->use_metric: an empty-circle test there is a matter of
 * quality, not validity (validity is orient2d's, on the true points), so
 * the rounding of the mapping is harmless. */
static inline int cdt_incircle(const struct fm_cdt *t, const double *a, const double *b,
                               const double *c, const double *d)
{
    if (!t->use_metric)
        return fm_incircle(a, b, c, d);
    const double *R = t->R, *p[3] = {a, b, c};
    double m[3][2], o[2] = {0, 0};
    for (int i = 0; i < 3; i++) {
        double dx = p[i][0] - d[0], dy = p[i][1] - d[1];
        m[i][0] = R[0] * dx + R[1] * dy;
        m[i][1] = R[2] * dy;
    }
    return fm_incircle(m[0], m[1], m[2], o);
}

/* cdt_mesh.c: storage */
int cdt_reserve_points(struct fm_cdt *t, size_t n);
int32_t cdt_add_point(struct fm_cdt *t, const double p[2], int32_t pseg);
int cdt_reserve_triangles(struct fm_cdt *t, size_t n);
int32_t cdt_new_triangle(struct fm_cdt *t);
void cdt_free_triangle(struct fm_cdt *t, int32_t tri);
int cdt_push_pair(struct fm_cdt *t, int32_t a, int32_t b);
/* Handle of the edge a -> b (a triangle has it counter-clockwise), or -1. */
int32_t cdt_find_edge(const struct fm_cdt *t, int32_t a, int32_t b);
/* Flips the edge e (its quadrilateral must be strictly convex). */
void cdt_flip(struct fm_cdt *t, int32_t e);
/* Lawson flips until every unconstrained edge among and around the
 * queued pairs is locally Delaunay (pairs consumed from index from). */
void cdt_legalize(struct fm_cdt *t, size_t from);

/* cdt_insert.c: Bowyer-Watson insertion */
typedef enum cdt_cavity_result {
    CDT_CAVITY_OK = 0,
    CDT_CAVITY_NOT_STAR,   /* q does not see every cavity edge: bnde holds a culprit */
    CDT_CAVITY_NOMEM
} cdt_cavity_result;
/* Gathers the cavity of q: seeds and the triangles reached from them across
 * unconstrained edges whose circumcircle holds q (outside the domain only
 * triangles free of super vertices grow, as nothing there needs to stay
 * Delaunay). force_edge >= 0: the constrained edge being split, crossed
 * regardless. Nothing is modified. On NOT_STAR, *bad is the first boundary
 * edge q does not strictly see. */
cdt_cavity_result cdt_cavity(struct fm_cdt *t, const double q[2], const int32_t *seeds,
                             size_t nseeds, int32_t force_edge, int32_t *bad);
/* Replaces the gathered cavity with the fan around the new point q (index
 * v). split_seg >= 0: the fan edges to the ends of the forced edge become
 * that input segment. Returns 0 on success, -1 out of memory. */
int cdt_commit(struct fm_cdt *t, int32_t v, int32_t force_edge, int32_t split_seg);
/* Triangle containing q (possibly on its boundary), walking from t->last.
 * Only valid while the triangulation is Delaunay (no segments yet). */
int32_t cdt_locate(struct fm_cdt *t, const double q[2]);

/* cdt_segment.c: segment recovery. soft (the convex hull of a graph
 * CDT): edges some segment already holds are left to it, and points met on
 * the way do not take k as their segment. */
fm_status cdt_recover_segment(struct fm_cdt *t, int32_t k, int soft, fm_error *err);

/* cdt_graph.c: the arrangement of a graph CDT. After the segments are
 * recovered: the convex hull's edges, the pieces, the faces and the
 * domain (every face). */
fm_status cdt_graph_build(struct fm_cdt *t, fm_error *err);
void cdt_graph_free(cdt_graph *g);
/* Refinement starts: the triangles no longer match the faces' slots. */
void cdt_graph_refined(struct fm_cdt *t);
/* The other end of the constrained edge with segment k at v that does not
 * lead to prev, or -1. */
int32_t cdt_next_on_segment(const struct fm_cdt *t, int32_t v, int32_t prev, int32_t k);

/* cdt_output.c */
int cdt_build_output(struct fm_cdt *t);

/* Refinement state (refine*.c). */
typedef struct cdt_heap_item {
    double key;
    int32_t tri;
    uint32_t stamp;
} cdt_heap_item;

typedef struct cdt_seg_item {
    int32_t a, b;
} cdt_seg_item;

typedef struct cdt_refiner {
    struct fm_cdt *t;
    const fm_cdt_refine_options *o;
    double size, bad_len;     /* target, and the longest edge allowed */
    double cos_min;           /* cosine of the smallest angle allowed */
    double tan_half;          /* tan(min_angle / 2), for off-centres */
    double aniso2;            /* max_anisotropy squared, 0: no clamp */
    double min_len;           /* min_length resolved, 0: none */
    int auto_cap;             /* max_points is the automatic one */
    cdt_heap_item *heap;
    size_t nheap, heapcap;
    cdt_seg_item *segq;
    size_t nsegq, segqcap;
    int32_t *adj_off, *adj;   /* input segments at each input point (CSR) */
    size_t max_points;
    fm_status st;
    fm_error *err;
} cdt_refiner;

/* What the quality test found about one triangle, in the metric. */
typedef struct cdt_quality {
    double lmax, lmin;        /* longest and shortest edge */
    double cos_min;           /* cosine of the smallest angle */
    int shortest;             /* local index of the edge opposite that angle */
    int bad;                  /* 1 size, 2 angle: to be fixed */
    int poor;                 /* bad, or below the angle but under min_length */
    double key;               /* priority: larger first */
    double m[3];              /* the metric used (at the centroid) */
} cdt_quality;

/* refine_quality.c */
/* m = metric at uv; -1 (and r->st set) when it is not positive definite. */
int cdt_metric(cdt_refiner *r, const double uv[2], double m[3]);
int cdt_quality_eval(cdt_refiner *r, int32_t tri, cdt_quality *q);
/* The point that fixes the triangle: metric circumcentre, or the
 * off-centre when the circumcentre lies farther out than needed. */
int cdt_fix_point(cdt_refiner *r, int32_t tri, const cdt_quality *q, double p[2]);
/* Circle tests of the coming insertion in the metric m (when there is a
 * metric at all). */
void cdt_use_metric(cdt_refiner *r, const double m[3]);
/* 1 if p lies in the diametral circle of (a, b) in the metric. */
int cdt_encroaches(cdt_refiner *r, const double p[2], int32_t a, int32_t b);

/* refine_split.c */
int cdt_frozen(const cdt_refiner *r, int32_t k);
fm_status cdt_apex_init(cdt_refiner *r);
/* Splits the sub-segment a-b if it still exists and is not frozen;
 * returns 1 when a point was inserted. */
int cdt_split_subsegment(cdt_refiner *r, int32_t a, int32_t b);
/* Queues a sub-segment an apex encroaches; checked again when taken. */
int cdt_segq_push(cdt_refiner *r, int32_t a, int32_t b);
/* 1 if p and q lie on two different segments that meet at a small-angle
 * apex: an edge whose shortness the input forces. */
int cdt_apex_exempt(cdt_refiner *r, int32_t p, int32_t q);

#endif
