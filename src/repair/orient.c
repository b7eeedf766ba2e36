/* Step 5: consistent orientation, then the up / vertical convention.
 *
 * Breadth-first from the first triangle of each sheet, every neighbour is
 * flipped so that the shared edge is traversed in opposite directions. A
 * sheet where a neighbour already visited disagrees is not orientable
 * (Moebius-like); its first-come assignment is kept as best effort. */
#include "repair_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Below this |n_z| of the unit normal a sheet counts as vertical. */
#define VERTICAL_NZ 1e-3
/* An area vector shorter than this fraction of the summed triangle areas
 * has no meaningful direction (closed or folded sheet). */
#define NULL_AREA_FRACTION 1e-12

/* Per-sheet flags. */
enum { SHEET_NONORIENTABLE = 1, SHEET_REVERSE = 2 };

/* 1 when half-edges h and g run the same way in their stored triangles. */
static int same_direction(const rep_tris *t, int32_t h, int32_t g)
{
    return t->v[h] == t->v[g];
}

static fm_status make_consistent(const rep_tris *t, const int32_t *nbr, const int32_t *sheet,
                                 uint8_t *flip, uint8_t *bad)
{
    size_t n = t->n;
    int32_t *queue = malloc((n ? n : 1) * sizeof *queue);
    uint8_t *seen = calloc(n ? n : 1, 1);
    if (!queue || !seen) {
        free(queue);
        free(seen);
        return FM_ERR_NOMEM;
    }
    for (size_t s = 0; s < n; s++) {
        if (seen[s])
            continue;
        size_t head = 0, tail = 0;
        queue[tail++] = (int32_t)s;
        seen[s] = 1;
        flip[s] = 0;
        while (head < tail) {
            int32_t tr = queue[head++];
            for (int i = 0; i < 3; i++) {
                int32_t h = 3 * tr + i, g = nbr[h];
                if (g < 0)
                    continue;
                int32_t u = g / 3;
                /* Consistent when the edge runs opposite ways once flips are
                 * applied: flips must differ iff stored directions agree. */
                uint8_t want = (uint8_t)(flip[tr] ^ same_direction(t, h, g));
                if (!seen[u]) {
                    seen[u] = 1;
                    flip[u] = want;
                    queue[tail++] = u;
                } else if (flip[u] != want) {
                    bad[sheet[tr]] |= SHEET_NONORIENTABLE;
                }
            }
        }
    }
    free(queue);
    free(seen);
    return FM_OK;
}

/* Whether a sheet with unit normal n must be reversed. */
static int wants_flip(const double *n)
{
    if (fabs(n[2]) >= VERTICAL_NZ)
        return n[2] < 0;
    /* Normal azimuth (clockwise from north) must lie in [90, 270). */
    int in_range = n[1] < 0 || (n[1] == 0 && n[0] > 0);
    return !in_range;
}

static void sheet_area_vectors(const rep_tris *t, const int32_t *sheet, const double *xyz,
                               const uint8_t *flip, double *vec, double *sum)
{
    for (size_t i = 0; i < t->n; i++) {
        const double *a = xyz + 3 * (size_t)t->v[3 * i];
        const double *b = xyz + 3 * (size_t)t->v[3 * i + 1];
        const double *c = xyz + 3 * (size_t)t->v[3 * i + 2];
        double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double x[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                       u[0] * w[1] - u[1] * w[0]};
        double sign = flip[i] ? -1.0 : 1.0;
        double *v = vec + 3 * (size_t)sheet[i];
        for (int d = 0; d < 3; d++)
            v[d] += sign * x[d];
        sum[sheet[i]] += sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    }
}

fm_status rep_orient(const rep_tris *t, const int32_t *nbr, const int32_t *sheet,
                     size_t nsheets, const double *xyz, int orient, uint8_t *flip,
                     double *normals, fm_repair_report *r)
{
    memset(flip, 0, t->n);
    memset(normals, 0, 3 * nsheets * sizeof *normals);
    double *sum = calloc(nsheets ? nsheets : 1, sizeof *sum);
    uint8_t *bad = calloc(nsheets ? nsheets : 1, 1);
    if (!sum || !bad) {
        free(sum);
        free(bad);
        return FM_ERR_NOMEM;
    }
    if (orient) {
        fm_status st = make_consistent(t, nbr, sheet, flip, bad);
        if (st != FM_OK) {
            free(sum);
            free(bad);
            return st;
        }
    }
    sheet_area_vectors(t, sheet, xyz, flip, normals, sum);
    for (size_t s = 0; s < nsheets; s++) {
        double *n = normals + 3 * s;
        double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(len > NULL_AREA_FRACTION * sum[s])) {
            n[0] = n[1] = n[2] = 0; /* direction undefined: left as made consistent */
            continue;
        }
        for (int d = 0; d < 3; d++)
            n[d] /= len;
        if (orient && wants_flip(n)) {
            for (int d = 0; d < 3; d++)
                n[d] = -n[d];
            bad[s] |= SHEET_REVERSE;
        }
    }
    for (size_t i = 0; i < t->n; i++) {
        if (bad[sheet[i]] & SHEET_REVERSE)
            flip[i] ^= 1;
        r->triangles_flipped += flip[i];
    }
    for (size_t s = 0; s < nsheets; s++)
        r->nonorientable_sheets += (bad[s] & SHEET_NONORIENTABLE) != 0;
    free(sum);
    free(bad);
    return FM_OK;
}
