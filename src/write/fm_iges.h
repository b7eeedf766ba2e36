/* faultmesh write: IGES 5.3 files of trimmed B-spline surfaces.
 *
 * For CAD tools, Cubit and Gmsh/OpenCASCADE. Takes plain arrays (no
 * dependency on the fit stage), so any tensor-product B-spline surface with
 * trimming loops in its parameter plane can be written.
 *
 * What a face becomes (entity numbers of IGES 5.3):
 *   128  the surface (rational B-spline surface; the polynomial flag is set
 *        when no weights are given), physically dependent on its 144
 *   126  each trimming curve, in the (u, v) plane: z = 0, planar, normal
 *        (0, 0, 1), entity use "2D parametric"
 *   102  a composite curve for a loop of more than one curve
 *   142  one per loop: curve on the surface, pointing to the 128 and to the
 *        126/102; no model-space curve (pointer 0), preference 1 = the
 *        parameter-space curve is the definition
 *   406  form 15 (Name property) with the face name, when there is one
 *   144  the trimmed surface, the only independent entity of the face (what
 *        readers transfer as a face). Without an outer loop: N1 = 0 (the
 *        boundary of the surface's parameter range) when that range is the
 *        knot range; otherwise the rectangle [u0, u1] x [v0, v1] is written
 *        as an outer loop of four lines, because readers (OpenCASCADE) take
 *        the knot range for N1 = 0 and ignore the 128's range fields.
 *
 * Orientation. The outer loop is written counter-clockwise in (u, v), so
 * the face has positive area and its normal is S_u x S_v; holes are written
 * clockwise. The sense of each loop is taken from the signed area of the
 * loop sampled along its curves, and a loop given the other way round is
 * reversed: curves in the opposite order, each with its control points
 * reversed and its knots negated and reversed (t -> -t, exact in floating
 * point), so the geometry is unchanged. The caller's arrays are never
 * modified.
 *
 * Checks (FM_ERR_INVALID with a message naming the face): degrees 1..25
 * (OpenCASCADE's limit), counts > degree, knot vectors non-decreasing with
 * interior multiplicity <= degree, positive weights, finite numbers, a
 * parameter range inside the knot range, consecutive curves of a loop
 * meeting and the loop closing within 1e-7 of the (u, v) range's diagonal,
 * loop samples inside [u0, u1] x [v0, v1] (same tolerance), loops with
 * non-zero area, names and texts of printable ASCII. Nothing is written
 * unless every face passes.
 *
 * What of a surface is written: the knot spans its outer loop reaches.
 * A surface fitted past its outline (an extension margin, the rectangle
 * around a slanting outline) keeps control points that shape only the
 * part trimmed away; the B-spline restricted to the spans the loop's
 * control polygon touches is the same surface there, exactly, and the 128
 * holds only those spans, its range narrowed to match. Untrimmed faces
 * are written whole.
 *
 * How far a written surface may be from the given one: `tolerance` (file
 * units), at every (u, v) of its range, the parameterisation unchanged
 * (the trims need no change). By default the resolution (Global 19, which
 * readers take as the distance below which points are one): 0.09 m for
 * the whole CFM. It is spent in two parts, both exactly bounded:
 *   - the control points' coordinates are rounded to a decimal quantum q,
 *     the largest power of ten with q sqrt(3) / 2 <= tolerance / 2 (1 cm
 *     for the whole CFM; "-1231.09" where 10 significant digits wrote
 *     "-1231.089506"); a surface moves no more than its control points
 *     (its basis functions are non-negative and sum to 1);
 *   - what is left, at least half, bounds knot removal (iges_reduce.c:
 *     Tiller's algorithm, each removal's bound measured and accumulated
 *     per cell of the knot grid; rational surfaces keep their knots).
 * A negative tolerance writes the control points as given, at `digits`.
 * Measured on the whole CFM (remesh --size 1000 of the 500 m set, 534
 * faces, 1,881,227 control points as given; deviation: largest distance
 * to the given surface on a 24 x 24 grid of each face's range):
 *     tolerance     quantum   control points   model.igs   deviation
 *     exact (< 0)   -         1,881,227        106.6 MB    0
 *     0.01 m        1 mm      1,878,868        102.8 MB    0.003 m
 *     0.09 m (res.) 1 cm      1,859,414         90.3 MB    0.034 m
 *     0.5 m         10 cm     1,831,180         80.5 MB    0.17 m
 *     1 m           10 cm     1,810,408         79.6 MB    0.39 m
 * The fitted fault surfaces are rough at their knot spacing (~530 m): a
 * single knot's removal, row by row, moves the row by more than 1 m in
 * half the cases, and a knot goes only where every row lets it, so
 * removal takes 1 to 4 % of the points at these tolerances (9 % at 5 m,
 * 43 % at 50 m: 46.8 MB); the quantum does most of the rest.
 *
 * The file: Start section = the description; Global section with "," and
 * ";" delimiters, native system id "faultmesh", the significant digits of
 * the reals written, version flag 11 (5.3), drafting standard 0 (none),
 * the units, the largest absolute control-point coordinate, a minimum
 * resolution and the date (UTC, 15HYYYYMMDD.HHNNSS). Parameter Data reals
 * other than the rounded control points are written to `digits`
 * significant digits (by default the fewest that move no coordinate by
 * more than 1/100 of the resolution: 10 for the whole CFM, in metres) or,
 * with digits = 17, the shortest text that reads back as the same double;
 * always with a decimal point, E exponent. Byte-for-byte deterministic for
 * a fixed time. Written through fm_atomic.h: the file appears complete or
 * not at all. */
#ifndef FM_IGES_H
#define FM_IGES_H

#include <stddef.h>

#include "fm_core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A tensor-product B-spline surface (rational when weights != NULL). */
typedef struct fm_iges_surface {
    int degree_u, degree_v;           /* 1..25 */
    size_t nu, nv;                    /* control points per direction, > degree */
    const double *knots_u, *knots_v;  /* nu + degree_u + 1 and nv + degree_v + 1 values;
                                         clamped or not */
    const double *ctrl;               /* 3 nu nv: point (i, j) at ctrl[3 (j nu + i)] */
    const double *weights;            /* nu nv (same order) or NULL = polynomial */
    /* Parameter range of the face. u0 == u1 (e.g. both 0) means the knot
     * range knots_u[degree_u] .. knots_u[nu]; the same for v. */
    double u0, u1, v0, v1;
} fm_iges_surface;

/* A B-spline curve in the surface's (u, v) plane, defined over
 * knots[degree] .. knots[n]. */
typedef struct fm_iges_curve2d {
    int degree;             /* 1..25 */
    size_t n;               /* control points, > degree */
    const double *knots;    /* n + degree + 1 values */
    const double *ctrl;     /* 2 n: (u, v) pairs */
    const double *weights;  /* n or NULL = polynomial */
} fm_iges_curve2d;

/* A closed loop: curves joined end to end, the last ending where the first
 * starts. Either sense; see the orientation note above. */
typedef struct fm_iges_loop {
    const fm_iges_curve2d *curves;
    size_t ncurves;         /* >= 1 */
} fm_iges_loop;

typedef struct fm_iges_face {
    /* Written as a 406 form 15 Name property (any length) and, its first
     * 8 characters, as the entity label of the 144. NULL or "" = none. */
    const char *name;
    fm_iges_surface surface;
    const fm_iges_loop *outer;  /* NULL = untrimmed: the whole parameter range */
    const fm_iges_loop *holes;  /* nholes loops inside the outer one */
    size_t nholes;
} fm_iges_face;

/* FM_IGES_TIME_AUTO: SOURCE_DATE_EPOCH from the environment when it is set
 * (reproducible builds convention), else the current time. */
#define FM_IGES_TIME_AUTO (-1LL)

typedef struct fm_iges_options {
    const char *description;   /* Start section; '\n' starts a new line.
                                  NULL = "faultmesh <version> fault surfaces" */
    const char *author;        /* Global 21, NULL = not given */
    const char *organization;  /* Global 22, NULL = not given */
    const char *product_id;    /* Global 3 and 12, NULL = file name without extension */
    int unit_flag;             /* Global 14: 1 in, 2 mm, 4 ft, 5 mi, 6 m (default),
                                  7 km, 8 mil, 9 um, 10 cm, 11 uin (3 not supported) */
    double model_scale;        /* Global 13, model units per real-world unit; default 1 */
    double resolution;         /* Global 19, in file units; 0 = automatic (default):
                                  1e-7 of the control points' bounding-box diagonal.
                                  Readers (OpenCASCADE) use it as their tolerance. */
    int digits;                /* significant digits of the Parameter Data's reals, 1..17
                                  (17: exact round trip); 0 = automatic (default),
                                  see the file note above. Not for the surfaces'
                                  control points unless tolerance < 0 */
    double tolerance;          /* how far, in file units, a written surface may be from
                                  the given one (knot removal and rounding, see the
                                  note above); 0 = automatic (default): the resolution;
                                  < 0: none, the control points as given, at `digits` */
    long long time;            /* seconds since 1970-01-01 UTC for Global 18 and 25;
                                  default FM_IGES_TIME_AUTO */
} fm_iges_options;

void fm_iges_options_default(fm_iges_options *opt);

/* Writes the faces (in this order) to path. opt may be NULL for defaults.
 * nfaces may be 0 (a valid file without entities). */
fm_status fm_iges_write(const char *path, const fm_iges_face *faces, size_t nfaces,
                        const fm_iges_options *opt, fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
