/* faultmesh connect: what the junction plan's files share (fm_connect.h,
 * "The junction plan"). */
#ifndef FM_PLAN_INTERNAL_H
#define FM_PLAN_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "connect_internal.h"
#include "fm_closest.h"
#include "fm_connect.h"

/* A sheet's outline for foot queries: the trimming loops sampled finely,
 * in (u, v) and as 3D segments in a closest-point tree (segment k joins
 * sample a[k] to b[k]). */
typedef struct pl_outline {
    const fm_fit_surface *surf;
    double *uv;
    size_t *start;      /* nloops + 1 */
    size_t nloops;
    int32_t *a, *b;     /* per segment */
    fm_closest_tree *tree;
} pl_outline;

fm_status pl_outline_build(const fm_model *m, size_t sheet, pl_outline *o, fm_error *err);
void pl_outline_free(pl_outline *o);
/* Nearest outline point to p: 3D foot and its (u, v); returns the distance. */
double pl_outline_foot(const pl_outline *o, const double p[3], double foot[3], double uv[2]);
/* Even-odd test on the sampled loops. */
int pl_outline_inside(const pl_outline *o, const double uv[2]);

/* A candidate shared curve: nodes in 3D and in each sheet's (u, v), in
 * curve order; end[s] and keep_left[s] per side. */
typedef struct pl_curve {
    size_t n;
    double *xyz;
    double *uv[2];
    int64_t *key;     /* per node: a point shared with other curves (-1: none); NULL: none */
    int end[2], keep_left[2];
    unsigned char off[2]; /* 1: not given to that side's sheet (a curve only the
                             other sheet ends at, short of this one: plan_clear.c) */
    int loop;             /* a closed curve: node n-1 is node 0 again (both get one
                             key, so one plan node: plan_triple.c) */
} pl_curve;

void pl_curve_free(pl_curve *c);


/* The junctions one pair of sheets makes: one per shared curve, plus one
 * unjoined entry per raw curve that gave none. curve[k].n == 0 when
 * junction k is unjoined. */
typedef struct pl_pair_result {
    fm_connect_junction *junction;
    pl_curve *curve;
    size_t n, cap;
} pl_pair_result;

void pl_pair_result_free(pl_pair_result *r);

/* Where curves a and b, on one sheet (a's side sa, b's side sb), may
 * meet (plan_meet.c): each crossing of their (u, v) polylines, then the
 * closest place of each stretch where they come within `near` of each
 * other in space; at most max points, none within `sep` of another. */
size_t pl_meet_seeds(const pl_curve *a, int sa, const pl_curve *b, int sb, double near,
                     double sep, double (*P)[3], size_t max);

/* Gives the curves of junctions that meet on a common sheet their common
 * point (plan_triple.c): keyed nodes; *made counts the points. */
int pl_triple_junctions(fm_connect_junction *J, pl_curve *C, size_t nj,
                        const fm_model *const *models, double H, const double *level,
                        size_t *made);

/* Accepts curves longest first; one that crosses or nears an accepted
 * curve on a shared sheet, or lies within D beyond one the sheet ends at,
 * is cut to its longest clear stretch, or left unjoined with a reason
 * (plan_conflict.c). -1: out of memory. */
int pl_resolve_conflicts(fm_connect_junction *J, pl_curve *C, size_t nj,
                         const fm_model *const *models, double H, double D, const double *level);

/* Curve c of junction j, in conflict, as a curve of sheet s alone (one
 * that was to end at it): the sheet ends `gap` short of the other surface,
 * over the stretch where both sheets are; with level, no node rises above
 * it and a node on it stays there (plan_clear.c). 1: made into *out (c
 * untouched); 0: not (*out empty); -1: out of memory. */
int pl_clear_curve(const fm_connect_junction *j, const pl_curve *c, int s,
                   const fm_model *const *models, double H, double gap, const double *level,
                   pl_curve *out);

/* A sheet as the plan's pairs share it: sampled once, its outline built
 * once (st and err: how that went; the outline is needed, and a failure
 * reported, only by pairs whose sheets have curves). */
typedef struct pl_sheet {
    const cn_sheet *s;
    pl_outline ol;
    fm_status st;
    fm_error err;
} pl_sheet;

/* Intersects the pair's sheets and decides every curve (plan_decide.c):
 * from the runs kept by an earlier plan when kept is not NULL (the sheets
 * then need only their outlines), else traced now into *traced (the
 * caller frees it; it is what a later plan may keep). */
fm_status pl_decide_pair(const pl_sheet *a, size_t fault_a, size_t sheet_a, const pl_sheet *b,
                         size_t fault_b, size_t sheet_b, const fm_connect_plan_options *opt,
                         const cn_runs *kept, cn_runs *traced, pl_pair_result *out,
                         fm_error *err);

#endif
