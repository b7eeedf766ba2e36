/* The repaired surface object and its accessors. Accessors are total: an
 * out-of-range index gives NULL / 0 / -1 rather than undefined behaviour,
 * since callers iterate over counts they got from the same object. */
#include "repair_internal.h"

#include <stdlib.h>
#include <string.h>

fm_surface *rep_surface_create(void)
{
    return calloc(1, sizeof(fm_surface));
}

void fm_surface_destroy(fm_surface *s)
{
    if (!s)
        return;
    for (size_t k = 0; k < s->nsheets; k++) {
        rep_sheet *sh = &s->sheets[k];
        fm_mesh_destroy(sh->mesh);
        free(sh->vorigin);
        free(sh->torigin);
        free(sh->loop_off);
        free(sh->loop_v);
    }
    for (size_t j = 0; j < s->njunctions; j++) {
        free(s->junctions[j].points);
        free(s->junctions[j].vorigin);
        free(s->junctions[j].sheets);
    }
    free(s->sheets);
    free(s->junctions);
    free(s);
}

const fm_repair_report *fm_surface_report(const fm_surface *s)
{
    return s ? &s->report : NULL;
}

size_t fm_surface_nsheets(const fm_surface *s)
{
    return s ? s->nsheets : 0;
}

static const rep_sheet *sheet_at(const fm_surface *s, size_t k)
{
    return s && k < s->nsheets ? &s->sheets[k] : NULL;
}

const fm_mesh *fm_surface_sheet_mesh(const fm_surface *s, size_t sheet)
{
    const rep_sheet *sh = sheet_at(s, sheet);
    return sh ? sh->mesh : NULL;
}

const int32_t *fm_surface_sheet_vertex_origin(const fm_surface *s, size_t sheet)
{
    const rep_sheet *sh = sheet_at(s, sheet);
    return sh ? sh->vorigin : NULL;
}

const int32_t *fm_surface_sheet_triangle_origin(const fm_surface *s, size_t sheet)
{
    const rep_sheet *sh = sheet_at(s, sheet);
    return sh ? sh->torigin : NULL;
}

void fm_surface_sheet_normal(const fm_surface *s, size_t sheet, double n[3])
{
    const rep_sheet *sh = sheet_at(s, sheet);
    if (sh)
        memcpy(n, sh->normal, sizeof sh->normal);
    else
        n[0] = n[1] = n[2] = 0;
}

size_t fm_surface_sheet_nloops(const fm_surface *s, size_t sheet)
{
    const rep_sheet *sh = sheet_at(s, sheet);
    return sh ? sh->nloops : 0;
}

const int32_t *fm_surface_sheet_loop(const fm_surface *s, size_t sheet, size_t loop,
                                     size_t *n)
{
    const rep_sheet *sh = sheet_at(s, sheet);
    if (!sh || loop >= sh->nloops) {
        if (n)
            *n = 0;
        return NULL;
    }
    if (n)
        *n = sh->loop_off[loop + 1] - sh->loop_off[loop];
    return sh->loop_v + sh->loop_off[loop];
}

long fm_surface_sheet_outer_loop(const fm_surface *s, size_t sheet)
{
    const rep_sheet *sh = sheet_at(s, sheet);
    return sh ? sh->outer : -1;
}

size_t fm_surface_njunctions(const fm_surface *s)
{
    return s ? s->njunctions : 0;
}

static const rep_junction *junction_at(const fm_surface *s, size_t j)
{
    return s && j < s->njunctions ? &s->junctions[j] : NULL;
}

const double *fm_surface_junction_points(const fm_surface *s, size_t j, size_t *npoints)
{
    const rep_junction *jc = junction_at(s, j);
    if (npoints)
        *npoints = jc ? jc->npoints : 0;
    return jc ? jc->points : NULL;
}

const int32_t *fm_surface_junction_vertex_origin(const fm_surface *s, size_t j,
                                                 size_t *npoints)
{
    const rep_junction *jc = junction_at(s, j);
    if (npoints)
        *npoints = jc ? jc->npoints : 0;
    return jc ? jc->vorigin : NULL;
}

int fm_surface_junction_closed(const fm_surface *s, size_t j)
{
    const rep_junction *jc = junction_at(s, j);
    return jc ? jc->closed : 0;
}

const int32_t *fm_surface_junction_sheets(const fm_surface *s, size_t j, size_t *nsheets)
{
    const rep_junction *jc = junction_at(s, j);
    if (nsheets)
        *nsheets = jc ? jc->nsheets : 0;
    return jc ? jc->sheets : NULL;
}
