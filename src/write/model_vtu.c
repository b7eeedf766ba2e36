/* The sampled trimmed surfaces of a fault model as one VTU. */
#include <stdlib.h>
#include <string.h>

#include "fm_model_write.h"
#include "fm_vtu.h"

fm_status fm_model_write_vtu(const char *path, const char *name, const fm_model *m,
                             fm_error *err)
{
    fm_mesh *all = fm_mesh_create();
    size_t total = 0;
    for (size_t i = 0; i < fm_model_nsheets(m); i++)
        total += fm_mesh_nvertices(fm_model_samples(m, i));
    double *dist = malloc((total ? total : 1) * sizeof *dist);
    int32_t *sheet = NULL;
    fm_status rc = all && dist ? FM_OK : FM_ERR_NOMEM;
    for (size_t i = 0; i < fm_model_nsheets(m) && rc == FM_OK; i++) {
        const fm_mesh *s = fm_model_samples(m, i);
        memcpy(dist + fm_mesh_nvertices(all), fm_model_sample_distance(m, i),
               fm_mesh_nvertices(s) * sizeof *dist);
        rc = fm_mesh_append(all, s, (int32_t)i + 1); /* the sheet, from 1 */
    }
    if (rc != FM_OK) {
        fm_mesh_destroy(all);
        free(dist);
        return fm_error_set(err, rc, path, 0, "out of memory");
    }
    sheet = (int32_t *)fm_mesh_tags(all);
    fm_vtu_array pd = {"distance_to_original", FM_VTU_FLOAT64, 1, dist};
    fm_vtu_array cd = {"sheet", FM_VTU_INT32, 1, sheet};
    const char *names[1] = {name};
    fm_vtu_strings fs = {"fault_names", names, 1};
    fm_vtu_content c = {.mesh = all, .point_data = &pd, .npoint_data = 1, .cell_data = &cd,
                        .ncell_data = 1, .field_strings = &fs, .nfield_strings = 1};
    rc = fm_vtu_write(path, &c, err);
    fm_mesh_destroy(all);
    free(dist);
    return rc;
}
