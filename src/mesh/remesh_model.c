/* Every sheet of a fault model meshed into one mesh. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_remesh.h"
#include "fm_sort.h"

fm_status fm_remesh_model(const fm_model *m, const fm_remesh_options *opt, fm_mesh **out,
                          fm_remesh_stats *stats, fm_error *err)
{
    return fm_remesh_model_joined(m, NULL, opt, out, NULL, NULL, NULL, stats, NULL, err);
}

/* Appends ids (n of them, or n times -1) to *all, which holds *nall. */
static int append_ids(int64_t **all, size_t *nall, const int64_t *ids, size_t n)
{
    int64_t *g = realloc(*all, (*nall + n + 1) * sizeof *g);
    if (!g)
        return -1;
    *all = g;
    for (size_t k = 0; k < n; k++)
        g[*nall + k] = ids ? ids[k] : -1;
    *nall += n;
    return 0;
}

/* The vertices that carry a shared node id, by (id, vertex): NULL when
 * out of memory (*n = 0 and a non-NULL empty array when there are none). */
static fm_keyed *sorted_ids(const int64_t *ids, size_t nv, size_t *n)
{
    *n = 0;
    fm_keyed *k = malloc((nv + 1) * sizeof *k);
    if (!k)
        return NULL;
    for (size_t v = 0; ids && v < nv; v++)
        if (ids[v] >= 0)
            k[(*n)++] = (fm_keyed){(uint64_t)ids[v], v};
    if (fm_sort_keyed(k, *n)) {
        free(k);
        return NULL;
    }
    return k;
}

static int has_key(const fm_keyed *k, size_t n, uint64_t key)
{
    size_t at = fm_keyed_lower_bound(k, n, key);
    return at < n && k[at].key == key;
}

fm_keyed *fm_remesh_shared_edges(const fm_mesh *m, const int64_t *ids, int32_t tag, size_t *n)
{
    *n = 0;
    size_t nt = fm_mesh_ntriangles(m);
    const int32_t *T = fm_mesh_triangles(m), *tags = fm_mesh_tags(m);
    fm_keyed *edge = malloc((3 * nt + 1) * sizeof *edge);
    if (!edge)
        return NULL;
    for (size_t t = 0; t < nt; t++)
        for (int k = 0; k < 3 && (tag < 0 || tags[t] == tag); k++) {
            int64_t a = ids[T[3 * t + k]], b = ids[T[3 * t + (k + 1) % 3]];
            if (a >= 0 && b >= 0)
                edge[(*n)++] = (fm_keyed){fm_edge_key((uint64_t)a, (uint64_t)b), 0};
        }
    if (fm_sort_keyed(edge, *n)) {
        free(edge);
        return NULL;
    }
    return edge;
}

/* Sheets of one fault that end at the same triple point (or share a
 * curve) each carry a vertex of that shared node: one fault must hold it
 * once, as the fault set does, or the fault's own files and figures count
 * it twice. The first vertex of each id is kept; the order of the others
 * is unchanged. */
static int weld_shared(fm_mesh *all, int64_t *ids)
{
    size_t nv = fm_mesh_nvertices(all), n;
    fm_keyed *at = sorted_ids(ids, nv, &n);
    size_t *map = malloc((nv + 1) * sizeof *map);
    if (!at || !map) {
        free(at);
        free(map);
        return -1;
    }
    for (size_t v = 0; v < nv; v++)
        map[v] = v;
    size_t dup = 0;
    for (size_t k = 1; k < n; k++)
        if (at[k].key == at[k - 1].key) {
            map[at[k].index] = map[at[k - 1].index];
            dup++;
        }
    free(at);
    if (dup) {
        /* compact: kept vertices move down, merged ones take their keeper's new index */
        double *X = fm_mesh_vertices_mut(all);
        size_t w = 0;
        for (size_t v = 0; v < nv; v++) {
            if (map[v] != v) {
                map[v] = map[map[v]]; /* keepers come first, already renumbered */
                continue;
            }
            memmove(X + 3 * w, X + 3 * v, 3 * sizeof *X);
            ids[w] = ids[v];
            map[v] = w++;
        }
        int32_t *T = fm_mesh_triangles_mut(all);
        for (size_t t = 0; t < 3 * fm_mesh_ntriangles(all); t++)
            T[t] = (int32_t)map[T[t]];
        fm_mesh_truncate(all, w, fm_mesh_ntriangles(all));
    }
    free(map);
    return 0;
}

/* A curve the sheet took but whose faces were all left out (it lies in a
 * dropped flap or beyond the outline the sheet kept) has no edge in the
 * mesh: it is reported as left out like one that did not fit, so that the
 * junction is not called made while no node of it is shared. Its nodes
 * alone do not tell: both its ends may be points where three faults meet,
 * there through other curves. Returns -1 when out of memory. */
static int mark_absent(const fm_remesh_sheet_curves *sc, const int64_t *sid, const fm_mesh *sheet)
{
    if (!sc->dropped || !sc->n)
        return 0;
    if (!sid) { /* meshed without any */
        memset(sc->dropped, 1, sc->n);
        return 0;
    }
    size_t ne;
    fm_keyed *edge = fm_remesh_shared_edges(sheet, sid, -1, &ne);
    if (!edge)
        return -1;
    for (size_t k = 0; k < sc->n; k++) {
        const fm_remesh_curve *c = &sc->curves[k];
        int present = 0;
        for (size_t i = 0; c->node && i + 1 < c->n && !present; i++)
            present = has_key(edge, ne,
                              fm_edge_key((uint64_t)c->node[i], (uint64_t)c->node[i + 1]));
        if (!present)
            sc->dropped[k] = 1; /* taken through or not, it is not there */
    }
    free(edge);
    return 0;
}

/* The sheet meshed with the largest set of its curves that fits, built
 * up one curve at a time (more nodes first); sc->dropped marks the rest. */
static fm_status fit_some(const fm_model *m, size_t i, const fm_trim_loop **loops, size_t nl,
                          const fm_remesh_sheet_curves *sc, const fm_remesh_options *opt,
                          fm_mesh **sheet, double **suv, int64_t **sid, fm_remesh_stats *s,
                          fm_error *err)
{
    size_t nc = sc->n;
    fm_remesh_curve *use = malloc((nc + 1) * sizeof *use);
    size_t *order = malloc((nc + 1) * sizeof *order);
    if (!use || !order) {
        free(use);
        free(order);
        return fm_error_set(err, FM_ERR_NOMEM, opt->name, 0, "out of memory");
    }
    for (size_t k = 0; k < nc; k++)
        order[k] = k;
    for (size_t a = 1; a < nc; a++) /* insertion sort: more nodes first, then index */
        for (size_t b = a; b > 0 && sc->curves[order[b]].n > sc->curves[order[b - 1]].n; b--) {
            size_t t = order[b];
            order[b] = order[b - 1];
            order[b - 1] = t;
        }
    if (sc->dropped)
        memset(sc->dropped, 1, nc);
    size_t nu = 0;
    fm_mesh *best = NULL;
    int64_t *best_id = NULL;
    double *best_uv = NULL;
    fm_remesh_stats best_st;
    memset(&best_st, 0, sizeof best_st);
    fm_status st = FM_OK;
    for (size_t k = 0; k < nc && st != FM_ERR_NOMEM; k++) {
        use[nu] = sc->curves[order[k]];
        fm_mesh *mm = NULL;
        int64_t *id = NULL;
        double *uvm = NULL;
        fm_remesh_stats ss;
        fm_error e2;
        st = fm_remesh_sheet_joined(fm_model_surface(m, i), loops, nl, use, nu + 1, opt,
                                    (int32_t)i, &mm, suv ? &uvm : NULL, &id, &ss, &e2);
        int through = 0;
        if (st != FM_OK && st != FM_ERR_NOMEM && use[nu].end) {
            /* A flap it cannot cut off (its end does not reach the
             * outline, or what lies beyond it looks like most of the
             * sheet) is better kept than the junction lost: sharing the
             * curve's nodes, the two faults still do not cross there. */
            use[nu].end = 0;
            through = 1;
            st = fm_remesh_sheet_joined(fm_model_surface(m, i), loops, nl, use, nu + 1, opt,
                                        (int32_t)i, &mm, suv ? &uvm : NULL, &id, &ss, &e2);
        }
        if (st == FM_OK) {
            fm_mesh_destroy(best);
            free(best_id);
            free(best_uv);
            best = mm;
            best_id = id;
            best_uv = uvm;
            best_st = ss;
            nu++;
            if (sc->dropped)
                sc->dropped[order[k]] = (unsigned char)(through ? 2 : 0);
        } else if (st == FM_ERR_NOMEM) {
            *err = e2;
        }
    }
    free(use);
    free(order);
    if (st == FM_ERR_NOMEM) {
        fm_mesh_destroy(best);
        free(best_id);
        free(best_uv);
        return FM_ERR_NOMEM;
    }
    if (!best)
        return fm_remesh_sheet_joined(fm_model_surface(m, i), loops, nl, NULL, 0, opt, (int32_t)i,
                                      sheet, suv, sid, s, err);
    *sheet = best;
    *sid = best_id;
    if (suv)
        *suv = best_uv;
    *s = best_st;
    return FM_OK;
}

fm_status fm_remesh_model_joined(const fm_model *m, const fm_remesh_sheet_curves *curves,
                                 const fm_remesh_options *opt, fm_mesh **out, int64_t **node_out,
                                 unsigned char *join_failed, fm_error *join_errors,
                                 fm_remesh_stats *stats, fm_remesh_boundary *bounds,
                                 fm_error *err)
{
    *out = NULL;
    for (size_t i = 0; bounds && i < fm_model_nsheets(m); i++)
        memset(&bounds[i], 0, sizeof bounds[i]);
    if (node_out)
        *node_out = NULL;
    int64_t *ids = NULL;
    size_t nids = 0;
    fm_remesh_stats sum;
    memset(&sum, 0, sizeof sum);
    sum.empty = 1;
    fm_mesh *all = fm_mesh_create();
    if (!all)
        return fm_error_set(err, FM_ERR_NOMEM, opt->name, 0, "out of memory");
    fm_status st = FM_OK;
    for (size_t i = 0; i < fm_model_nsheets(m) && st == FM_OK; i++) {
        size_t nl = fm_model_nloops(m, i);
        const fm_trim_loop **loops = malloc((nl ? nl : 1) * sizeof *loops);
        if (!loops) {
            st = fm_error_set(err, FM_ERR_NOMEM, opt->name, 0, "out of memory");
            break;
        }
        for (size_t k = 0; k < nl; k++)
            loops[k] = fm_model_loop(m, i, k);
        fm_mesh *sheet = NULL;
        fm_remesh_stats s;
        int64_t *sid = NULL;
        double *suv = NULL;
        const fm_remesh_curve *cv = curves ? curves[i].curves : NULL;
        size_t nc = curves ? curves[i].n : 0;
        if (join_failed)
            join_failed[i] = 0;
        st = fm_remesh_sheet_joined(fm_model_surface(m, i), loops, nl, cv, nc, opt, (int32_t)i,
                                    &sheet, bounds ? &suv : NULL, &sid, &s, err);
        if (st != FM_OK && st != FM_ERR_NOMEM && nc > 0) {
            /* Curves that do not fit the domain together: the sheet takes
             * as many as fit, longest first (one bad curve should not
             * leave its other junctions open), and the caller reports the
             * ones left out. */
            if (join_failed)
                join_failed[i] = 1;
            if (join_errors)
                join_errors[i] = *err;
            st = fit_some(m, i, loops, nl, &curves[i], opt, &sheet, bounds ? &suv : NULL, &sid,
                          &s, err);
        } else if (curves && curves[i].dropped) {
            memset(curves[i].dropped, 0, nc);
        }
        free(loops);
        if (st != FM_OK)
            break;
        if (bounds) {
            /* before the sheets are welded: a node shared by two sheets
             * has a (u, v) in each. A boundary that cannot be traced costs
             * the sheet its CAD face (no loops), not its mesh. */
            fm_error berr;
            st = fm_remesh_boundary_of(sheet, suv, sid, &bounds[i], &berr);
            free(suv);
            if (st == FM_ERR_NOMEM) {
                free(sid);
                fm_mesh_destroy(sheet);
                fm_error_set(err, st, opt->name, 0, "out of memory");
                break;
            }
            st = FM_OK;
        }
        if (curves && mark_absent(&curves[i], sid, sheet)) {
            free(sid);
            fm_mesh_destroy(sheet);
            st = fm_error_set(err, FM_ERR_NOMEM, opt->name, 0, "out of memory");
            break;
        }
        if (append_ids(&ids, &nids, sid, fm_mesh_nvertices(sheet))) {
            free(sid);
            fm_mesh_destroy(sheet);
            st = fm_error_set(err, FM_ERR_NOMEM, opt->name, 0, "out of memory");
            break;
        }
        free(sid);
        st = fm_mesh_append(all, sheet, (int32_t)i);
        if (st != FM_OK) {
            fm_mesh_destroy(sheet);
            fm_error_set(err, st, opt->name, 0, "out of memory");
            break;
        }
        fm_mesh_destroy(sheet);
        sum.points += s.points;
        sum.triangles += s.triangles;
        sum.boundary_points += s.boundary_points;
        sum.level_points += s.level_points;
        sum.clamped += s.clamped;
        sum.clamp_max = fmax(sum.clamp_max, s.clamp_max);
        sum.flips += s.flips;
        sum.smoothed += s.smoothed;
        sum.collapsed += s.collapsed;
        sum.flaps_kept += s.flaps_kept;
        sum.slivers += s.slivers;
        sum.cut |= s.cut;
        sum.empty &= s.empty;
        sum.extended = fmax(sum.extended, s.extended);
        sum.time += s.time;
    }
    if (st == FM_OK && weld_shared(all, ids))
        st = fm_error_set(err, FM_ERR_NOMEM, opt->name, 0, "out of memory");
    if (st != FM_OK) {
        fm_mesh_destroy(all);
        free(ids);
        for (size_t i = 0; bounds && i < fm_model_nsheets(m); i++)
            fm_remesh_boundary_free(&bounds[i]);
        return st;
    }
    if (stats)
        *stats = sum;
    *out = all;
    if (node_out)
        *node_out = ids;
    else
        free(ids);
    return FM_OK;
}
