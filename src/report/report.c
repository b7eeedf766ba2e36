/* The report builder: copies what the caller hands in, and classifies
 * each fault for its colour. */
#include <stdlib.h>
#include <string.h>

#include "report_internal.h"

/* Colour-blind safe (Okabe-Ito): green ok, orange warned, blue carved,
 * grey empty, vermilion failed, purple dropped, light grey excluded. */
const double rp_kind_rgb[RP_NKINDS][3] = {
    {0.000, 0.620, 0.451}, {0.902, 0.624, 0.000}, {0.337, 0.706, 0.914},
    {0.600, 0.600, 0.600}, {0.835, 0.369, 0.000}, {0.800, 0.475, 0.655},
    {0.780, 0.780, 0.780},
};
const char *const rp_kind_label[RP_NKINDS] = {
    "meshed", "meshed, with warnings", "meshed, cut back where it crossed another",
    "empty (above sea level)", "failed", "dropped (near-duplicate)", "excluded",
};
const char *const rp_kind_badge[RP_NKINDS] = {
    "ok", "warnings", "cut back", "empty", "failed", "dropped", "excluded",
};

static char *dup_or_null(const char *s, int *bad)
{
    if (!s)
        return NULL;
    char *d = strdup(s);
    if (!d)
        *bad = 1;
    return d;
}

fm_report *fm_report_create(const fm_mesh *set, const fm_report_info *info, fm_error *err)
{
    fm_report *r = calloc(1, sizeof *r);
    int bad = !r;
    if (r) {
        r->set = set;
        r->size = info && info->size > 0 ? info->size : 1;
        r->title = dup_or_null(info && info->title ? info->title : "faultmesh report", &bad);
        r->crs = dup_or_null(info && info->crs ? info->crs : "", &bad);
    }
    if (bad) {
        fm_report_destroy(r);
        fm_error_set(err, FM_ERR_NOMEM, "report.html", 0, "out of memory");
        return NULL;
    }
    return r;
}

static void free_fault(rp_fault *f)
{
    free(f->name);
    free(f->file);
    free(f->status);
    free(f->reason);
    free(f->join_error);
    for (size_t i = 0; i < f->nwarnings; i++)
        free(f->warnings[i]);
    free(f->warnings);
}

void fm_report_destroy(fm_report *r)
{
    if (!r)
        return;
    for (size_t i = 0; i < r->nf; i++)
        free_fault(&r->f[i]);
    free(r->f);
    for (size_t i = 0; i < r->nj; i++) {
        free(r->j[i].fault[0]);
        free(r->j[i].fault[1]);
        free(r->j[i].type);
        free(r->j[i].reason);
    }
    free(r->j);
    for (size_t i = 0; i < r->neg; i++) {
        free(r->eg[i].fault[0]);
        free(r->eg[i].fault[1]);
    }
    free(r->eg);
    for (size_t i = 0; i < r->nfact; i++)
        free(r->fact[i]);
    free(r->fact);
    free(r->title);
    free(r->crs);
    free(r);
}

/* Grows *p (of *cap elements of size sz) to hold n + 1. */
static int grow(void *p, size_t *cap, size_t n, size_t sz)
{
    if (n < *cap)
        return 0;
    size_t c = *cap ? 2 * *cap : 16;
    void *g = realloc(*(void **)p, c * sz);
    if (!g)
        return -1;
    *(void **)p = g;
    *cap = c;
    return 0;
}

static rp_kind classify(const rp_fault *f)
{
    if (!strcmp(f->status, "ok"))
        return f->carved ? RP_CARVED : f->nwarnings ? RP_WARNED : RP_OK;
    if (!strcmp(f->status, "empty"))
        return RP_EMPTY;
    if (!strcmp(f->status, "dropped"))
        return RP_DROPPED;
    if (!strcmp(f->status, "excluded"))
        return RP_EXCLUDED;
    return RP_FAILED;
}

fm_status fm_report_add_fault(fm_report *r, const fm_report_fault *in, fm_error *err)
{
    if (grow(&r->f, &r->capf, r->nf, sizeof *r->f))
        return fm_error_set(err, FM_ERR_NOMEM, "report.html", 0, "out of memory");
    rp_fault *f = &r->f[r->nf];
    memset(f, 0, sizeof *f);
    int bad = 0;
    f->name = dup_or_null(in->name ? in->name : in->file ? in->file : "", &bad);
    f->file = dup_or_null(in->file ? in->file : "", &bad);
    f->status = dup_or_null(in->status ? in->status : "error", &bad);
    f->reason = dup_or_null(in->reason, &bad);
    f->join_error = dup_or_null(in->join_error, &bad);
    f->warnings = in->nwarnings ? calloc(in->nwarnings, sizeof *f->warnings) : NULL;
    bad |= in->nwarnings && !f->warnings;
    for (size_t i = 0; f->warnings && i < in->nwarnings; i++, f->nwarnings++)
        f->warnings[i] = dup_or_null(in->warnings[i] ? in->warnings[i] : "", &bad);
    if (bad) {
        free_fault(f);
        return fm_error_set(err, FM_ERR_NOMEM, "report.html", 0, "out of memory");
    }
    f->tag = in->tag;
    f->original = in->original;
    f->sheets = in->sheets;
    f->q = in->quality;
    f->fid = in->fidelity;
    f->fitted_area = in->fitted_area;
    f->carved = in->carved;
    f->carved_area = in->carved_area;
    f->has_loss = in->loss != NULL;
    if (in->loss)
        f->loss = *in->loss;
    f->kind = classify(f);
    r->nf++;
    return FM_OK;
}

fm_status fm_report_add_junction(fm_report *r, const fm_report_junction *in, fm_error *err)
{
    if (grow(&r->j, &r->capj, r->nj, sizeof *r->j))
        return fm_error_set(err, FM_ERR_NOMEM, "report.html", 0, "out of memory");
    rp_junction *j = &r->j[r->nj];
    memset(j, 0, sizeof *j);
    int bad = 0;
    j->fault[0] = dup_or_null(in->fault[0] ? in->fault[0] : "", &bad);
    j->fault[1] = dup_or_null(in->fault[1] ? in->fault[1] : "", &bad);
    j->type = dup_or_null(in->type ? in->type : "", &bad);
    j->reason = dup_or_null(in->reason, &bad);
    if (bad) {
        free(j->fault[0]);
        free(j->fault[1]);
        free(j->type);
        free(j->reason);
        return fm_error_set(err, FM_ERR_NOMEM, "report.html", 0, "out of memory");
    }
    j->gap = in->gap_closed;
    j->overshoot = in->overshoot_trimmed;
    j->length = in->length;
    j->min_angle = in->min_angle;
    r->nj++;
    return FM_OK;
}

void fm_report_set_elastic(fm_report *r, double fraction, size_t wrong_sign)
{
    r->elastic = 1;
    r->elastic_fraction = fraction;
    r->elastic_wrong = wrong_sign;
}

fm_status fm_report_add_elastic_group(fm_report *r, const fm_report_elastic_group *in,
                                      fm_error *err)
{
    if (grow(&r->eg, &r->capeg, r->neg, sizeof *r->eg))
        return fm_error_set(err, FM_ERR_NOMEM, "report.html", 0, "out of memory");
    rp_elastic_group *g = &r->eg[r->neg];
    memset(g, 0, sizeof *g);
    int bad = 0;
    g->fault[0] = dup_or_null(in->fault[0] ? in->fault[0] : "", &bad);
    g->fault[1] = dup_or_null(in->fault[1] ? in->fault[1] : "", &bad);
    if (bad) {
        free(g->fault[0]);
        free(g->fault[1]);
        return fm_error_set(err, FM_ERR_NOMEM, "report.html", 0, "out of memory");
    }
    g->junction = in->junction;
    g->pairs = in->pairs;
    g->max_ratio = in->max_ratio;
    g->min_distance = in->min_distance;
    g->nexamples = in->nexamples < 5 ? in->nexamples : 5;
    memcpy(g->examples, in->examples, 2 * g->nexamples * sizeof *g->examples);
    r->neg++;
    return FM_OK;
}

fm_status fm_report_add_fact(fm_report *r, const char *label, const char *value, fm_error *err)
{
    int bad = 0;
    if (grow(&r->fact, &r->capfact, r->nfact + 1, sizeof *r->fact))
        bad = 1;
    char *l = bad ? NULL : dup_or_null(label ? label : "", &bad);
    char *v = bad ? NULL : dup_or_null(value ? value : "", &bad);
    if (bad) {
        free(l);
        free(v);
        return fm_error_set(err, FM_ERR_NOMEM, "report.html", 0, "out of memory");
    }
    r->fact[r->nfact++] = l;
    r->fact[r->nfact++] = v;
    return FM_OK;
}
