/* The outline of an original surface, seams left out. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "check_internal.h"

/* Outline edges whose ends lie this close (m) to those of another are a
 * seam between two sheets, not an edge of the surface. */
#define FM_SEAM_WELD 1.0

static double dist2(const double *a, const double *b)
{
    return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
}

/* The outline of o: its edges used by one triangle only, as (lo << 32 |
 * hi) vertex pairs in *out (malloc'ed, ascending), their number in *n. */
fm_status ck_outline_edges(const fm_mesh *o, uint64_t **out, size_t *n)
{
    size_t ns = 0;
    fm_keyed *side = fm_mesh_sides(o, &ns);
    uint64_t *key = side ? malloc((ns + 1) * sizeof *key) : NULL;
    *out = NULL;
    *n = 0;
    if (!key) {
        free(side);
        return FM_ERR_NOMEM;
    }
    size_t m = 0;
    for (size_t e = 0; e < ns;) {
        size_t r = e + 1;
        while (r < ns && side[r].key == side[e].key)
            r++;
        if (r - e == 1)
            key[m++] = side[e].key;
        e = r;
    }
    free(side);
    /* A seam is no outline: an original may hold two sheets side by side
     * whose vertices along the join are distinct ids a few millimetres
     * apart (Big Bear rupture), each edge there used once. An edge used
     * once whose ends lie within FM_SEAM_WELD of those of another such
     * edge is dropped. Quadratic in the outline (a few hundred edges). */
    const double *V = fm_mesh_vertices(o), w2 = FM_SEAM_WELD * FM_SEAM_WELD;
    unsigned char *seam = calloc(m + 1, 1);
    if (!seam) {
        free(key);
        return FM_ERR_NOMEM;
    }
    for (size_t e = 0; e < m; e++)
        for (size_t g = e + 1; g < m; g++) {
            const double *a = V + 3 * (key[e] >> 32), *b = V + 3 * (key[e] & 0xffffffffu);
            const double *c = V + 3 * (key[g] >> 32), *d = V + 3 * (key[g] & 0xffffffffu);
            if ((dist2(a, c) <= w2 && dist2(b, d) <= w2) || (dist2(a, d) <= w2 && dist2(b, c) <= w2))
                seam[e] = seam[g] = 1;
        }
    size_t k = 0;
    for (size_t e = 0; e < m; e++)
        if (!seam[e])
            key[k++] = key[e];
    free(seam);
    *out = key;
    *n = k;
    return FM_OK;
}


/* Brute force: asked only for nodes far from the original. */
double ck_outline_distance(const fm_mesh *o, const uint64_t *E, size_t ne, const double p[3])
{
    const double *V = fm_mesh_vertices(o);
    double best = INFINITY;
    for (size_t e = 0; e < ne; e++)
        best = fmin(best, fm_segment_distance3(p, V + 3 * (E[e] >> 32), V + 3 * (E[e] & 0xffffffffu)));
    return best;
}
