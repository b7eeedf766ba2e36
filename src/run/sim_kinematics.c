/* The simulator side of remesh: each element's slip rate and rake from a
 * deformation model's fault sections (--kinematics), under the --slip
 * rules and the settings file, over the fallback; and what report.json
 * says of it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_kinematics.h"
#include "run_internal.h"
#include "sim_attrs.h"

/* An element whose section rake differs from its fault's CFM slip sense
 * by more than this (degrees) is counted as disagreeing. */
#define SENSE_DISAGREES 60.0

static double angle_between(double a, double b)
{
    double d = fmod(fabs(a - b), 360);
    return d > 180 ? 360 - d : d;
}

typedef struct sec_area {
    int32_t section;
    size_t t; /* the triangle: equal sections sum in mesh order */
    double area;
} sec_area;

static int by_section(const void *x, const void *y)
{
    const sec_area *a = x, *b = y;
    if (a->section != b->section)
        return (a->section > b->section) - (a->section < b->section);
    return (a->t > b->t) - (a->t < b->t);
}

/* Per fault, the sections its elements took with their areas (CSR). */
static int fault_sections(const fm_faultset *fs, sim_attrs *a, const double *area)
{
    size_t nf = fs->nfaults, nt = a->ntriangles;
    const int32_t *tag = fm_mesh_tags(fs->mesh);
    size_t *count = calloc(nf + 1, sizeof *count);
    sec_area *all = malloc((nt + 1) * sizeof *all);
    a->ksec_start = calloc(nf + 1, sizeof *a->ksec_start);
    if (!count || !all || !a->ksec_start) {
        free(count);
        free(all);
        return -1;
    }
    for (size_t t = 0; t < nt; t++)
        count[tag[t] + 1]++;
    for (size_t f = 0; f < nf; f++)
        count[f + 1] += count[f];
    for (size_t t = 0; t < nt; t++)
        all[count[tag[t]]++] = (sec_area){a->kin[t].section, t, area[t]};
    /* count[f] is now the end of fault f's run */
    size_t w = 0, begin = 0;
    for (size_t f = 0; f < nf; f++) {
        size_t end = count[f];
        qsort(all + begin, end - begin, sizeof *all, by_section);
        a->ksec_start[f] = w;
        for (size_t i = begin; i < end; i++) {
            if (all[i].section < 0)
                continue;
            if (w > a->ksec_start[f] && all[w - 1].section == all[i].section)
                all[w - 1].area += all[i].area;
            else
                all[w++] = all[i];
        }
        begin = end;
    }
    a->ksec_start[nf] = w;
    free(count);
    a->ksec_id = malloc((w + 1) * sizeof *a->ksec_id);
    a->ksec_area = malloc((w + 1) * sizeof *a->ksec_area);
    if (!a->ksec_id || !a->ksec_area) {
        free(all);
        return -1;
    }
    for (size_t i = 0; i < w; i++) {
        a->ksec_id[i] = all[i].section;
        a->ksec_area[i] = all[i].area;
    }
    free(all);
    return 0;
}

int sim_kinematics_apply(const sim_cli *sc, const fm_faultset *fs, sim_attrs *a)
{
    if (!sc->sections)
        return 0;
    size_t nt = a->ntriangles, nf = fs->nfaults;
    a->kin = malloc((nt + 1) * sizeof *a->kin);
    double *area = malloc((nt + 1) * sizeof *area);
    a->k_area = calloc(nf + 1, sizeof *a->k_area);
    a->k_matched = calloc(nf + 1, sizeof *a->k_matched);
    a->k_disagree = calloc(nf + 1, sizeof *a->k_disagree);
    a->k_rmin = malloc((nf + 1) * sizeof *a->k_rmin);
    a->k_rmax = malloc((nf + 1) * sizeof *a->k_rmax);
    if (!a->kin || !area || !a->k_area || !a->k_matched || !a->k_disagree || !a->k_rmin ||
        !a->k_rmax) {
        free(area);
        return -1;
    }
    fm_error err;
    fm_error_clear(&err);
    fm_kinematics_options o;
    fm_kinematics_options_default(&o);
    if (sc->kin_distance > 0)
        o.max_distance = sc->kin_distance;
    if (fm_kinematics_assign(sc->sections, fs, a->strike, a->dip, &o, a->kin, &err) != FM_OK) {
        run_log(sc->ctl, FM_LOG_ERROR, "--kinematics: %s", err.message);
        free(area);
        return -2;
    }
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh), *tag = fm_mesh_tags(fs->mesh);
    for (size_t f = 0; f < nf; f++) {
        a->k_rmin[f] = INFINITY;
        a->k_rmax[f] = -INFINITY;
    }
    for (size_t t = 0; t < nt; t++) {
        size_t f = (size_t)tag[t];
        const fm_fault_slip *s = &a->slip[f];
        const fm_element_kinematics *k = &a->kin[t];
        area[t] = fm_triangle_area(x + 3 * (size_t)tri[3 * t], x + 3 * (size_t)tri[3 * t + 1],
                                   x + 3 * (size_t)tri[3 * t + 2]);
        a->k_area[f] += area[t];
        const fm_section *sec = k->section >= 0 ? fm_sections_get(sc->sections, (size_t)k->section)
                                                : NULL;
        int rule_rake = s->rake_from == FM_SLIP_FROM_CSV || s->rake_from == FM_SLIP_FROM_SETTINGS;
        int rule_rate = s->rate_from == FM_SLIP_FROM_CSV || s->rate_from == FM_SLIP_FROM_SETTINGS;
        if (sec) {
            a->k_matched[f] += area[t];
            if (s->rake_from == FM_SLIP_FROM_METADATA &&
                angle_between(k->rake, s->rake) > SENSE_DISAGREES)
                a->k_disagree[f] += area[t];
        }
        if (!rule_rake && sec)
            a->rake_t[t] = k->rake;
        double mm = rule_rate               ? s->slip_rate_mm_yr
                    : sec && sec->has_rate ? sec->rate
                                           : sc->kin_fallback_rate;
        a->rate_t[t] = mm * FM_MM_PER_YEAR_TO_M_PER_S;
        if (sec) {
            a->k_rmin[f] = fmin(a->k_rmin[f], mm);
            a->k_rmax[f] = fmax(a->k_rmax[f], mm);
        }
    }
    int rc = fault_sections(fs, a, area);
    free(area);
    return rc;
}

void sim_kinematics_free(sim_attrs *a)
{
    free(a->kin);
    free(a->k_area);
    free(a->k_matched);
    free(a->k_disagree);
    free(a->k_rmin);
    free(a->k_rmax);
    free(a->ksec_start);
    free(a->ksec_id);
    free(a->ksec_area);
}

int sim_kinematics_rake_default(const sim_attrs *a, size_t t, size_t f)
{
    return a->slip[f].rake_from == FM_SLIP_FROM_DEFAULT && !(a->kin && a->kin[t].section >= 0);
}

void sim_kinematics_json_fault(fm_json *j, const sim_cli *sc, const sim_attrs *a, size_t f)
{
    if (!a->kin)
        return;
    fm_json_key(j, "kinematics");
    fm_json_begin_object(j);
    double A = a->k_area[f] > 0 ? a->k_area[f] : 1;
    fm_json_kv_number(j, "matched_area_share", a->k_matched[f] / A);
    fm_json_kv_number(j, "slip_sense_disagreement_area_share", a->k_disagree[f] / A);
    if (a->k_matched[f] > 0) {
        fm_json_kv_number(j, "rate_min_mm_yr", a->k_rmin[f]);
        fm_json_kv_number(j, "rate_max_mm_yr", a->k_rmax[f]);
    }
    fm_json_key(j, "sections");
    fm_json_begin_array(j);
    for (size_t i = a->ksec_start[f]; i < a->ksec_start[f + 1]; i++) {
        const fm_section *s = fm_sections_get(sc->sections, (size_t)a->ksec_id[i]);
        fm_json_begin_object(j);
        fm_json_kv_int(j, "id", s->id);
        fm_json_kv_string(j, "name", s->name);
        fm_json_kv_number(j, "area_share", a->ksec_area[i] / A);
        fm_json_kv_number(j, "rake_deg", s->rake);
        if (s->has_rate)
            fm_json_kv_number(j, "rate_mm_yr", s->rate);
        fm_json_end_object(j);
    }
    fm_json_end_array(j);
    fm_json_end_object(j);
}

void sim_kinematics_json_summary(fm_json *j, const sim_cli *sc, const sim_attrs *a,
                                 const char *const *names)
{
    if (!a->kin)
        return;
    fm_json_key(j, "kinematics");
    fm_json_begin_object(j);
    fm_json_key(j, "files");
    fm_json_begin_array(j);
    for (size_t i = 0; i < sc->nkin; i++)
        fm_json_string(j, sc->kin_paths[i]);
    fm_json_end_array(j);
    fm_json_kv_int(j, "sections", (int64_t)fm_sections_count(sc->sections));
    fm_json_kv_int(j, "sections_incomplete", (int64_t)fm_sections_incomplete(sc->sections));
    fm_json_kv_number(j, "fallback_rate_mm_yr", sc->kin_fallback_rate);
    double A = 0, M = 0;
    size_t unmatched = 0;
    for (size_t f = 0; f < a->nfaults; f++) {
        A += a->k_area[f];
        M += a->k_matched[f];
    }
    for (size_t t = 0; t < a->ntriangles; t++)
        unmatched += a->kin[t].section < 0;
    fm_json_kv_number(j, "matched_area_share", A > 0 ? M / A : 0);
    fm_json_kv_int(j, "elements_on_fallback", (int64_t)unmatched);
    /* every fault no element of which found a section */
    fm_json_key(j, "faults_on_fallback");
    fm_json_begin_array(j);
    for (size_t f = 0; f < a->nfaults; f++)
        if (a->k_matched[f] == 0)
            fm_json_string(j, names[f]);
    fm_json_end_array(j);
    fm_json_end_object(j);
}
