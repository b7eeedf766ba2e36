/* Fault set as VTU: the shared mesh with the fault number per triangle. */
#include <stdlib.h>

#include "faultset_internal.h"

fm_status fm_faultset_write_vtu(const char *path, const fm_faultset *fs, fm_error *err)
{
    fm_status st = fm_faultset_validate(fs, path, err);
    if (st != FM_OK)
        return st;
    size_t nt = fm_mesh_ntriangles(fs->mesh);
    fm_vtu_array *cd = malloc((fs->ncell_data + 1) * sizeof *cd);
    int32_t *number = malloc((nt + 1) * sizeof *number);
    if (!cd || !number) {
        free(cd);
        free(number);
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    /* the fault number, index + 1, as every other format numbers faults */
    const int32_t *tag = fm_mesh_tags(fs->mesh);
    for (size_t t = 0; t < nt; t++)
        number[t] = tag[t] + 1;
    cd[0] = (fm_vtu_array){"fault_id", FM_VTU_INT32, 1, number};
    for (size_t i = 0; i < fs->ncell_data; i++)
        cd[i + 1] = fs->cell_data[i];
    const char *crs[1] = {fs->crs};
    fm_vtu_strings fsd[2] = {{"fault_names", fs->names, fs->nfaults}, {"crs", crs, 1}};
    size_t nfs = fs->crs && fs->crs[0] ? 2 : 1;
    fm_vtu_content c = {.mesh = fs->mesh, .cell_data = cd, .ncell_data = fs->ncell_data + 1,
                        .field_strings = fsd, .nfield_strings = nfs};
    st = fm_vtu_write(path, &c, err);
    free(cd);
    free(number);
    return st;
}
