/* Distance of a mesh's nodes to an original surface. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "check_internal.h"

fm_status fm_check_fidelity(const fm_mesh *m, int32_t tag, const fm_mesh *orig,
                            const fm_closest_tree *tree, fm_fidelity *f)
{
    f->nodes = f->beyond_nodes = f->inside_over = 0;
    f->rms = f->max = f->beyond_max = f->inside_max = 0;
    size_t nv = fm_mesh_nvertices(m), nt = fm_mesh_ntriangles(m);
    const int32_t *T = fm_mesh_triangles(m), *tags = fm_mesh_tags(m);
    const double *X = fm_mesh_vertices(m);
    unsigned char *used = calloc(nv ? nv : 1, 1);
    uint64_t *E = NULL;
    size_t ne = 0;
    if (!used || (orig && ck_outline_edges(orig, &E, &ne) != FM_OK)) {
        free(used);
        return FM_ERR_NOMEM;
    }
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
        if (hit.dist <= FM_FIDELITY_TOL)
            f->inside_max = fmax(f->inside_max, hit.dist);
        else if (orig && ck_outline_distance(orig, E, ne, hit.foot) <= FM_FIDELITY_TOL) {
            /* The nearest original point is on its outline (within the
             * tolerance: past a curving edge it falls a little inside):
             * the node lies past the original's edge. */
            f->beyond_max = fmax(f->beyond_max, hit.dist);
            f->beyond_nodes++;
        } else {
            /* over the original's inside, farther than the tolerance */
            f->inside_max = fmax(f->inside_max, hit.dist);
            f->inside_over++;
        }
    }
    f->rms = f->nodes ? sqrt(sum2 / (double)f->nodes) : 0;
    free(used);
    free(E);
    return FM_OK;
}
