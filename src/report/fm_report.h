/* faultmesh report: DIR/report.html, one self-contained page a person
 * reads to judge a remeshed fault set: problems first, sortable and
 * filterable tables, the overview pictures drawn here (cairo, to PNG,
 * embedded as data: URIs), and every fault's triangles packed for the
 * page's own script, which draws a fault and its neighbours when it is
 * opened (so that no browser or Python is needed to make the page, and
 * no network to read it).
 *
 * The caller fills it with plain data: the fault set written (its
 * triangles tagged with the fault's index in the set), then every fault
 * of the run in the order of report.json with its status, figures and
 * original, the junctions, and summary facts. Nothing is drawn until
 * fm_report_write_html, so the meshes handed in are borrowed and must
 * stay alive until then. The page holds no times: the same run gives the
 * same bytes whatever the thread count. */
#ifndef FM_REPORT_H
#define FM_REPORT_H

#include <stddef.h>
#include <stdint.h>

#include "fm_check.h"
#include "fm_core.h"
#include "fm_mesh.h"
#include "fm_process.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fm_report fm_report;

typedef struct fm_report_info {
    const char *title;   /* page heading */
    const char *crs;     /* coordinate reference system of the set (x east, y north, metres) */
    double size;         /* target edge length H, m */
} fm_report_info;

/* set: the fault set written, tag = the fault's index in it; borrowed.
 * NULL on allocation failure (err set). */
fm_report *fm_report_create(const fm_mesh *set, const fm_report_info *info, fm_error *err);
void fm_report_destroy(fm_report *r);

/* One fault of the run. Strings are copied; meshes are borrowed. */
typedef struct fm_report_fault {
    const char *name;
    const char *file;
    const char *status;        /* "ok", "empty", "error", "dropped" or "excluded" */
    const char *reason;        /* why it is not ok; NULL when ok */
    const char *const *warnings; /* what to look at before trusting it */
    size_t nwarnings;
    const char *join_error;    /* why some shared curves were left out, or NULL */
    int32_t tag;               /* its triangles in the set, -1 when it has none */
    const fm_mesh *original;   /* as read; NULL when the file could not be read */
    size_t sheets;
    fm_quality quality;        /* ok faults: of its triangles in the set */
    fm_fidelity fidelity;
    double fitted_area;        /* m^2, of the trimmed fitted surface */
    size_t carved;             /* triangles it gave up where it ran through another */
    double carved_area;        /* m^2 */
    const fm_loss_fault *loss; /* what connecting cost it (copied); NULL when not measured */
} fm_report_fault;

fm_status fm_report_add_fault(fm_report *r, const fm_report_fault *f, fm_error *err);

/* One junction of the plan as meshed. */
typedef struct fm_report_junction {
    const char *fault[2];
    const char *type;          /* "crossing", "T", "corner" or "unjoined" */
    double gap_closed;         /* m */
    double overshoot_trimmed;  /* m */
    double length;             /* of the curve, m */
    double min_angle;          /* smallest crossing angle, degrees */
    const char *reason;        /* why it is as it is (NULL when there is nothing to say) */
} fm_report_junction;

fm_status fm_report_add_junction(fm_report *r, const fm_report_junction *j, fm_error *err);

/* The elastic check (fm_check.h), when it ran: its flag ratio, the
 * elements whose self-stiffness has the wrong sign, and its groups of
 * flagged pairs (one fault pair at one junction each). */
typedef struct fm_report_elastic_group {
    const char *fault[2];
    size_t junction;           /* as the junction table numbers it; 0: the faults have none */
    size_t pairs;
    double max_ratio;          /* mutual to the smaller self-stiffness */
    double min_distance;       /* m */
    const size_t *examples;    /* element numbers (from 1), two per pair */
    size_t nexamples;          /* pairs, at most 5 */
} fm_report_elastic_group;

void fm_report_set_elastic(fm_report *r, double fraction, size_t wrong_sign);
fm_status fm_report_add_elastic_group(fm_report *r, const fm_report_elastic_group *g,
                                      fm_error *err);

/* A line of the summary table (label, value), in the order added. */
fm_status fm_report_add_fact(fm_report *r, const char *label, const char *value, fm_error *err);

/* Draws the pictures and writes the page atomically to path. */
fm_status fm_report_write_html(fm_report *r, const char *path, fm_error *err);

/* fm_report_cleanup: fm_process.h (installed). */

#ifdef __cplusplus
}
#endif
#endif
