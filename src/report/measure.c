/* The distributions behind the histograms, measured on the set as
 * written: every triangle's smallest angle, every edge once per fault, and every
 * node of a fault against that fault's original. */
#include <math.h>
#include <stdlib.h>

#include "fm_closest.h"
#include "report_internal.h"

static fm_status node_distances(const fm_report *r, rp_hist *dist)
{
    const fm_mesh *m = r->set;
    size_t nt = fm_mesh_ntriangles(m), nv = fm_mesh_nvertices(m), ntags = 0;
    const int32_t *T = fm_mesh_triangles(m), *tag = fm_mesh_tags(m);
    const double *X = fm_mesh_vertices(m);
    for (size_t t = 0; t < nt; t++)
        if (tag[t] >= 0 && (size_t)tag[t] + 1 > ntags)
            ntags = (size_t)tag[t] + 1;
    /* triangles by tag (counting sort), and a stamp per vertex so a node
     * counts once per fault */
    size_t *start = calloc(ntags + 2, sizeof *start), *order = malloc((nt + 1) * sizeof *order);
    size_t *seen = calloc(nv + 1, sizeof *seen);
    fm_status st = start && order && seen ? FM_OK : FM_ERR_NOMEM;
    for (size_t t = 0; st == FM_OK && t < nt; t++)
        if (tag[t] >= 0)
            start[tag[t] + 1]++;
    for (size_t g = 0; st == FM_OK && g < ntags; g++)
        start[g + 1] += start[g];
    for (size_t t = 0; st == FM_OK && t < nt; t++)
        if (tag[t] >= 0)
            order[start[tag[t]]++] = t;
    for (size_t g = ntags; st == FM_OK && g > 0; g--)
        start[g] = start[g - 1];
    if (st == FM_OK)
        start[0] = 0;
    for (size_t i = 0; st == FM_OK && i < r->nf; i++) {
        const rp_fault *f = &r->f[i];
        if (f->tag < 0 || (size_t)f->tag >= ntags || !f->original)
            continue;
        fm_closest_tree *tree = fm_closest_tree_create_quick(f->original, NULL);
        if (!tree) {
            st = FM_ERR_NOMEM;
            break;
        }
        for (size_t k = start[f->tag]; k < start[f->tag + 1]; k++)
            for (int c = 0; c < 3; c++) {
                int32_t v = T[3 * order[k] + c];
                if (seen[v] == i + 1)
                    continue;
                seen[v] = i + 1;
                fm_closest_hit hit;
                if (fm_closest_query(tree, X + 3 * v, INFINITY, &hit))
                    rp_hist_add(dist, hit.dist);
            }
        fm_closest_tree_destroy(tree);
    }
    free(start);
    free(order);
    free(seen);
    return st;
}

fm_status rp_measure(const fm_report *r, rp_hist *angle, rp_hist *edge, rp_hist *dist)
{
    const fm_mesh *m = r->set;
    if (!m)
        return FM_OK;
    size_t nt = fm_mesh_ntriangles(m);
    const int32_t *T = fm_mesh_triangles(m);
    const double *X = fm_mesh_vertices(m);
    for (size_t t = 0; t < nt; t++)
        rp_hist_add(angle, fm_triangle_min_angle(X + 3 * T[3 * t], X + 3 * T[3 * t + 1],
                                                 X + 3 * T[3 * t + 2]));
    size_t ns = 0;
    fm_keyed *side = fm_mesh_sides(m, &ns);
    if (!side && nt)
        return FM_ERR_NOMEM;
    const int32_t *tag = fm_mesh_tags(m);
    for (size_t i = 0, start = 0; i < ns; i++) {
        if (i > 0 && side[i].key != side[i - 1].key)
            start = i;
        /* once per fault, as report.json counts edges: an edge two faults
         * share is an edge of each */
        int seen = 0;
        for (size_t k = start; k < i && !seen; k++)
            seen = tag[side[k].index] == tag[side[i].index];
        if (seen)
            continue;
        /* its vertices from its key (fm_edge_key: smaller << 32 | larger) */
        uint32_t a = (uint32_t)(side[i].key >> 32), b = (uint32_t)side[i].key;
        const double *p = X + 3 * (size_t)a, *q = X + 3 * (size_t)b;
        double d = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                        (p[2] - q[2]) * (p[2] - q[2]));
        rp_hist_add(edge, d / r->size);
    }
    free(side);
    return node_distances(r, dist);
}
