/* The files and figures of a fitted fault as `faultmesh fit` gives them
 * (fm_model_write.h): the three files, each tried whatever became of the
 * others, and the fault-level figures of its sheets' fit reports. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_model_write.h"

const char *const fm_model_file_ext[FM_MODEL_NFILES] = {"model.json", "igs", "vtu"};

fm_status fm_model_write_files(const char *dir, const char *base, const char *name,
                               const fm_model *m, unsigned *missing,
                               fm_error errs[FM_MODEL_NFILES])
{
    *missing = 0;
    for (int k = 0; k < FM_MODEL_NFILES; k++)
        fm_error_clear(&errs[k]);
    size_t n = strlen(dir) + strlen(base) + 32;
    char *path = malloc(n);
    if (!path) {
        *missing = (1u << FM_MODEL_NFILES) - 1;
        for (int k = 0; k < FM_MODEL_NFILES; k++)
            fm_error_set(&errs[k], FM_ERR_NOMEM, name, 0, "out of memory");
        return FM_ERR_NOMEM;
    }
    fm_status first = FM_OK;
    for (int k = 0; k < FM_MODEL_NFILES; k++) {
        snprintf(path, n, "%s/%s.%s", dir, base, fm_model_file_ext[k]);
        fm_status st = k == 0   ? fm_model_write_json(path, name, m, &errs[k])
                       : k == 1 ? fm_model_write_iges(path, name, m, &errs[k])
                                : fm_model_write_vtu(path, name, m, &errs[k]);
        if (st == FM_OK)
            continue;
        *missing |= 1u << k;
        if (first == FM_OK)
            first = st;
    }
    free(path);
    return first;
}

void fm_model_fault_figures(const fm_model *m, fm_fault_figures *f)
{
    memset(f, 0, sizeof *f);
    double n1 = 0, s1 = 0, n2 = 0, s2 = 0;
    for (size_t i = 0; i < fm_model_nsheets(m); i++) {
        const fm_sheet_report *r = fm_model_report(m, i);
        n1 += (double)r->vertices;
        s1 += (double)r->vertices * r->to_surface_rms * r->to_surface_rms;
        n2 += (double)r->samples;
        s2 += (double)r->samples * r->from_trimmed_rms * r->from_trimmed_rms;
        f->to_max = fmax(f->to_max, r->to_surface_max);
        f->from_max = fmax(f->from_max, r->from_trimmed_max);
        f->outline_max = fmax(f->outline_max, r->outline_max);
    }
    f->to_rms = n1 > 0 ? sqrt(s1 / n1) : 0;
    f->from_rms = n2 > 0 ? sqrt(s2 / n2) : 0;
}
