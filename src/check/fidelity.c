/* Distance of a mesh's nodes to an original surface. */
#include <math.h>
#include <stdlib.h>

#include "fm_check.h"

fm_status fm_check_fidelity(const fm_mesh *m, int32_t tag, const fm_closest_tree *tree,
                            fm_fidelity *f)
{
    f->nodes = 0;
    f->rms = f->max = 0;
    size_t nv = fm_mesh_nvertices(m), nt = fm_mesh_ntriangles(m);
    const int32_t *T = fm_mesh_triangles(m), *tags = fm_mesh_tags(m);
    const double *X = fm_mesh_vertices(m);
    unsigned char *used = calloc(nv ? nv : 1, 1);
    if (!used)
        return FM_ERR_NOMEM;
    for (size_t t = 0; t < nt; t++)
        if (tag < 0 || tags[t] == tag)
            used[T[3 * t]] = used[T[3 * t + 1]] = used[T[3 * t + 2]] = 1;
    double sum2 = 0;
    for (size_t v = 0; v < nv; v++) {
        if (!used[v])
            continue;
        fm_closest_hit hit;
        if (!fm_closest_query(tree, X + 3 * v, INFINITY, &hit))
            continue;
        sum2 += hit.dist * hit.dist;
        f->max = fmax(f->max, hit.dist);
        f->nodes++;
    }
    f->rms = f->nodes ? sqrt(sum2 / (double)f->nodes) : 0;
    free(used);
    return FM_OK;
}
