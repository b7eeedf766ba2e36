/* The CAD faces of one meshed fault for model.igs: each sheet's fitted
 * surface trimmed by the boundary of its mesh (one face per connected
 * part), the boundary cut into curves where it passes between the
 * outline, a shared intersection curve and the sea-level line. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "remesh_cad.h"
#include "run_internal.h"

/* What the boundary edge from point i to point j runs along: 1 a shared
 * curve (both ends are shared nodes), 2 the sea-level line (both ends on
 * it, the top cut), 0 the outline. */
static int edge_kind(const fm_remesh_boundary *b, size_t i, size_t j, int cut, double level)
{
    if (b->node[i] >= 0 && b->node[j] >= 0)
        return 1;
    if (cut && b->xyz[3 * i + 2] == level && b->xyz[3 * j + 2] == level)
        return 2;
    return 0;
}

fm_status run_cad_faces(const fm_model *m, const fm_remesh_boundary *bounds,
                           const unsigned char *sheet_meshed, const char *name, int cut,
                           double level, fm_cad_face ***faces, size_t *nfaces, size_t *skipped,
                           run_ctl *ctl, fm_error *err)
{
    *faces = NULL;
    *nfaces = 0;
    *skipped = 0;
    size_t total = 0;
    for (size_t s = 0; s < fm_model_nsheets(m); s++)
        total += bounds[s].nparts;
    fm_cad_face **out = calloc(total + 1, sizeof *out);
    if (!out)
        return fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
    fm_status st = FM_OK;
    size_t n = 0;
    for (size_t s = 0; s < fm_model_nsheets(m) && st == FM_OK; s++) {
        const fm_remesh_boundary *b = &bounds[s];
        if (b->nloops == 0 && sheet_meshed && sheet_meshed[s]) {
            run_log(ctl, FM_LOG_WARN, "%s: sheet %zu left out of model.igs: its mesh's "
                                      "boundary could not be traced", name, s);
            (*skipped)++;
        }
        size_t np = b->nloops ? b->start[b->nloops] : 0;
        unsigned char *corner = malloc(np + 1);
        size_t *start = malloc((b->nloops + 1) * sizeof *start);
        if (!corner || !start) {
            free(corner);
            free(start);
            st = fm_error_set(err, FM_ERR_NOMEM, name, 0, "out of memory");
            break;
        }
        for (size_t l = 0; l < b->nloops; l++) {
            size_t a = b->start[l], k = b->start[l + 1] - a;
            for (size_t i = 0; i < k; i++)
                corner[a + i] = edge_kind(b, a + (i + k - 1) % k, a + i, cut, level) !=
                                edge_kind(b, a + i, a + (i + 1) % k, cut, level);
        }
        /* a part's loops are consecutive, its outer one first */
        for (size_t l0 = 0; l0 < b->nloops && st == FM_OK;) {
            size_t l1 = l0 + 1;
            while (l1 < b->nloops && b->part[l1] == b->part[l0])
                l1++;
            for (size_t l = l0; l <= l1; l++)
                start[l - l0] = b->start[l] - b->start[l0];
            const size_t a = b->start[l0];
            fm_error ferr;
            st = fm_cad_face_create(name, fm_model_surface(m, s), b->uv + 2 * a, start, l1 - l0,
                                    corner + a, &out[n], &ferr);
            if (st == FM_OK) {
                n++;
            } else if (st != FM_ERR_NOMEM) {
                /* the mesh stays; the face is left out, and said so */
                run_log(ctl, FM_LOG_WARN, "%s: sheet %zu part %zu left out of model.igs: %s",
                        name, s, b->part[l0], ferr.message);
                (*skipped)++;
                st = FM_OK;
            } else {
                *err = ferr;
            }
            l0 = l1;
        }
        free(corner);
        free(start);
    }
    if (st != FM_OK) {
        for (size_t i = 0; i < n; i++)
            fm_cad_face_destroy(out[i]);
        free(out);
        return st;
    }
    *faces = out;
    *nfaces = n;
    return FM_OK;
}
