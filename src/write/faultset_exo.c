/* Fault set as Exodus II, the way Cubit hands a mesh to PyLith: one
 * element block and one node set per fault, node sets of the junction
 * curves, names stored. netCDF creates and writes the file itself, so the
 * atomic write is done here: created under a temporary name in the same
 * folder, renamed once closed. */
#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <exodusII.h>
#include <netcdf.h>

#include "faultset_internal.h"
#include "fm_atomic.h"
#include "fm_names.h"

/* Entity names are written short (FM_EXODUS_NAME_MAX, fm_names.h): many
 * readers keep 32 characters of a name and would see the CFM's long
 * names collide. */
#define EXO_NAME_MAX FM_EXODUS_NAME_MAX
/* An info record holds 80 characters, a QA field 32. */
#define EXO_LINE 80

static pthread_once_t opts_once = PTHREAD_ONCE_INIT;

/* The library's default options may print or abort on an error; errors
 * are reported through fm_error instead. */
static void quiet_exodus(void) { ex_opts(EX_DEFAULT); }

/* The last Exodus II error in words: its message and the netCDF or system
 * reason of its code. The library keeps one error for the process; only
 * one Exodus II file is written at a time here. */
static const char *exodus_reason(char *buf, size_t n)
{
    const char *msg = NULL, *func = NULL;
    int code = 0;
    ex_get_err(&msg, &func, &code);
    /* netCDF's codes are negative, the system's positive; Exodus's own
     * (beyond +-1000) say no more than its message */
    const char *why = code && code > -1000 && code < 1000 ? nc_strerror(code) : "";
    snprintf(buf, n, "%s%s%s (%s)", msg && *msg ? msg : "failed", *why ? ": " : "", why,
             func && *func ? func : "exodus");
    return buf;
}

typedef struct exo_job {
    const fm_faultset *fs;
    int32_t *node;       /* per vertex: node number (1-based), 0 if unused */
    size_t nnodes;
    size_t *tstart, *torder; /* triangles grouped by fault */
    char **names;        /* nfaults + nnodesets short names (fm_short_names) */
    char qa_date[16], qa_time[16]; /* SOURCE_DATE_EPOCH's, else the epoch's (UTC) */
    char **info;         /* ninfo lines */
    size_t ninfo;
    fs_edge_group *groups; /* the side sets: fault edges by kind, junction curves */
    size_t ngroups;
    char **gnames;       /* their short names */
} exo_job;

static char *cut_copy(const char *s, size_t max)
{
    size_t n = strlen(s);
    if (n > max)
        n = fs_utf8_cut(s, max);
    char *d = malloc(n + 1);
    if (d) {
        memcpy(d, s, n);
        d[n] = '\0';
    }
    return d;
}

static int add_info(exo_job *j, const char *text)
{
    char *d = cut_copy(text, EXO_LINE);
    if (!d)
        return -1;
    j->info[j->ninfo++] = d;
    return 0;
}

/* The CRS over as many 80-character lines as it needs ("crs: " first,
 * "crs+ " on the continuation lines), cut at UTF-8 boundaries. */
static int crs_info(exo_job *j, const char *crs)
{
    char line[EXO_LINE + 1];
    const char *p = crs;
    int first = 1;
    while (first || *p) {
        size_t room = EXO_LINE - 5, n = strlen(p);
        if (n > room)
            n = fs_utf8_cut(p, room);
        snprintf(line, sizeof line, "%s%.*s", first ? "crs: " : "crs+ ", (int)n, p);
        if (add_info(j, line))
            return -1;
        p += n;
        first = 0;
    }
    return 0;
}

static int prepare(exo_job *j)
{
    const fm_faultset *fs = j->fs;
    size_t nv = fm_mesh_nvertices(fs->mesh), nt = fm_mesh_ntriangles(fs->mesh);
    int32_t *owner = fs_vertex_owner(fs);
    if (!owner)
        return -1;
    j->node = owner; /* reused: owner -> node number */
    for (size_t v = 0; v < nv; v++)
        owner[v] = owner[v] >= 0 ? (int32_t)++j->nnodes : 0;
    if (fs_group_by(fm_mesh_tags(fs->mesh), nt, fs->nfaults, &j->tstart, &j->torder))
        return -1;
    size_t nn = fs->nfaults + fs->nnodesets;
    /* one list, so that a junction's set and a fault's never share a name */
    const char **full = malloc((nn + 1) * sizeof *full);
    if (!full)
        return -1;
    for (size_t i = 0; i < nn; i++)
        full[i] = i < fs->nfaults ? fs->names[i] : fs->nodesets[i - fs->nfaults].name;
    j->names = fm_short_names(full, nn, EXO_NAME_MAX);
    free(full);
    if (!j->names || fs_edge_groups_make(fs, &j->groups, &j->ngroups))
        return -1;
    /* side set names that fit Exodus' 32 bytes whole: a fault's edges
     * "fault<number>_<kind>" (names.csv gives the fault), a junction's
     * those of its node set */
    j->gnames = calloc(j->ngroups + 1, sizeof *j->gnames);
    if (!j->gnames)
        return -1;
    for (size_t i = 0; i < j->ngroups; i++) {
        const fs_edge_group *g = &j->groups[i];
        char buf[64];
        if (g->set >= 0)
            snprintf(buf, sizeof buf, "%s", j->names[fs->nfaults + (size_t)g->set]);
        else
            snprintf(buf, sizeof buf, "fault%d_%s", (int)g->fault + 1,
                     g->kind == FS_EDGE_TOP      ? "top"
                     : g->kind == FS_EDGE_BURIED ? "buried_top"
                     : g->kind == FS_EDGE_BOTTOM ? "bottom"
                                                 : "ends");
        if (!(j->gnames[i] = strdup(buf)))
            return -1;
    }
    size_t ncrs = fs->crs ? strlen(fs->crs) / (EXO_LINE - 5) + 2 : 0;
    j->info = calloc(ncrs + 4, sizeof *j->info);
    if (!j->info)
        return -1;
    if (add_info(j, "faultmesh " FM_VERSION_STRING ": fault set, one element block and node "
                    "set per fault") ||
        add_info(j, "units: metres; z up, negative below sea level") ||
        (fs->crs && fs->crs[0] && crs_info(j, fs->crs)))
        return -1;
    return 0;
}

static void release(exo_job *j)
{
    free(j->node);
    free(j->tstart);
    free(j->torder);
    for (size_t i = 0; j->names && i < j->fs->nfaults + j->fs->nnodesets; i++)
        free(j->names[i]);
    free(j->names);
    for (size_t i = 0; i < j->ninfo; i++)
        free(j->info[i]);
    free(j->info);
    for (size_t i = 0; j->gnames && i < j->ngroups; i++)
        free(j->gnames[i]);
    free(j->gnames);
    fs_edge_groups_free(j->groups, j->ngroups);
}

/* The side sets (fs_edge_groups_make's groups): per edge the element
 * holding it (its number: its place in the blocks + 1) and its side (TRI3:
 * side k from node k to node k + 1); -ENOMEM or 0. */
static int make_side_sets(const exo_job *j, ex_set *sets)
{
    size_t nt = fm_mesh_ntriangles(j->fs->mesh);
    int32_t *elem = malloc((nt + 1) * sizeof *elem);
    if (!elem)
        return -ENOMEM;
    for (size_t i = 0; i < nt; i++)
        elem[j->torder[i]] = (int32_t)(i + 1);
    int rc = 0;
    for (size_t s = 0; s < j->ngroups && rc == 0; s++) {
        const fs_edge_group *g = &j->groups[s];
        int32_t *e = malloc((g->n + 1) * sizeof *e), *side = malloc((g->n + 1) * sizeof *side);
        if (!e || !side)
            rc = -ENOMEM;
        for (size_t k = 0; e && side && k < g->n; k++) {
            e[k] = elem[g->edge[k][2]];
            side[k] = g->edge[k][3] + 1;
        }
        sets[s] = (ex_set){.id = (int64_t)(s + 1), .type = EX_SIDE_SET,
                           .num_entry = (int64_t)g->n, .entry_list = e, .extra_list = side};
    }
    free(elem);
    return rc;
}

static int cmp_i32(const void *a, const void *b)
{
    int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
    return (x > y) - (x < y);
}

/* Node numbers of a set's vertices, ascending, without repeats; n set. */
static int32_t *set_nodes(const exo_job *j, const int32_t *v, size_t *n)
{
    size_t k = 0, m = *n;
    int32_t *out = malloc((m ? m : 1) * sizeof *out);
    if (!out)
        return NULL;
    for (size_t i = 0; i < m; i++)
        out[i] = j->node[v[i]];
    qsort(out, m, sizeof *out, cmp_i32);
    for (size_t i = 0; i < m; i++)
        if (k == 0 || out[i] != out[k - 1])
            out[k++] = out[i];
    *n = k;
    return out;
}

/* The node sets, fault by fault and then the given ones, as vertex lists
 * turned node numbers (sets[k].entry_list malloc'ed); -ENOMEM or 0. */
static int make_sets(const exo_job *j, ex_set *sets)
{
    const fm_faultset *fs = j->fs;
    size_t nf = fs->nfaults, nt = fm_mesh_ntriangles(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh);
    int32_t *fv = malloc((nt ? nt : 1) * 3 * sizeof *fv);
    if (!fv)
        return -ENOMEM;
    int rc = 0;
    for (size_t s = 0; s < nf + fs->nnodesets && rc == 0; s++) {
        size_t n;
        const int32_t *v;
        if (s < nf) {
            n = 0;
            for (size_t i = j->tstart[s]; i < j->tstart[s + 1]; i++)
                for (int k = 0; k < 3; k++)
                    fv[n++] = tri[3 * j->torder[i] + (size_t)k];
            v = fv;
        } else {
            n = fs->nodesets[s - nf].n;
            v = fs->nodesets[s - nf].vertices;
        }
        int32_t *nodes = set_nodes(j, v, &n);
        if (!nodes)
            rc = -ENOMEM;
        sets[s] = (ex_set){.id = (int64_t)(s + 1), .type = EX_NODE_SET,
                           .num_entry = (int64_t)n, .entry_list = nodes};
    }
    free(fv);
    return rc;
}

/* Everything after ex_create; an Exodus error code or -ENOMEM. Every block
 * and set is defined in one call each, before any bulk data: netCDF moves
 * the data written so far each time it leaves define mode with a variable
 * added, which made one call per set quadratic (18 s for the whole CFM). */
static int put_all(int exo, const exo_job *j)
{
    const fm_faultset *fs = j->fs;
    size_t nv = fm_mesh_nvertices(fs->mesh), nf = fs->nfaults, ns = nf + fs->nnodesets;
    /* before ex_put_init, which sizes the name variables */
    int rc = ex_set_max_name_length(exo, EXO_NAME_MAX);
    if (rc < 0)
        return rc;
    rc = ex_put_init(exo, "faultmesh fault set", 3, (int64_t)j->nnodes,
                         (int64_t)fm_mesh_ntriangles(fs->mesh), (int64_t)nf, (int64_t)ns,
                         (int64_t)j->ngroups);
    if (rc < 0)
        return rc;
    char *qa[1][4] = {{"faultmesh", FM_VERSION_STRING, (char *)j->qa_date, (char *)j->qa_time}};
    if ((rc = ex_put_qa(exo, 1, qa)) < 0 || (rc = ex_put_info(exo, (int)j->ninfo, j->info)) < 0)
        return rc;

    /* the blocks: one per fault, TRI3 */
    int *id = malloc((nf + 1) * 4 * sizeof *id);
    char **type = malloc((nf + 1) * sizeof *type);
    /* the node sets, then the side sets, defined in one call */
    ex_set *sets = calloc(ns + j->ngroups + 1, sizeof *sets);
    if (!id || !type || !sets) {
        free(id);
        free(type);
        free(sets);
        return -ENOMEM;
    }
    int *count = id + nf, *per = id + 2 * nf, *attr = id + 3 * nf;
    for (size_t f = 0; f < nf; f++) {
        id[f] = (int)(f + 1);
        count[f] = (int)(j->tstart[f + 1] - j->tstart[f]);
        per[f] = 3;
        attr[f] = 0;
        type[f] = "TRI3";
    }
    if (nf)
        rc = ex_put_concat_elem_block(exo, id, type, count, per, attr, 0);
    free(id);
    free(type);
    if (rc >= 0)
        rc = make_sets(j, sets);
    if (rc >= 0)
        rc = make_side_sets(j, sets + ns);
    if (rc >= 0 && ns + j->ngroups)
        rc = ex_put_sets(exo, ns + j->ngroups, sets);
    for (size_t s = 0; s < ns + j->ngroups; s++) {
        free(sets[s].entry_list);
        free(sets[s].extra_list);
    }
    free(sets);
    if (rc >= 0)
        rc = ex_put_names(exo, EX_ELEM_BLOCK, j->names);
    if (rc >= 0)
        rc = ex_put_names(exo, EX_NODE_SET, j->names);
    if (rc >= 0 && j->ngroups)
        rc = ex_put_names(exo, EX_SIDE_SET, j->gnames);
    if (rc < 0)
        return rc;

    double *c = malloc((j->nnodes ? j->nnodes : 1) * 3 * sizeof *c);
    int32_t *map = malloc((j->nnodes ? j->nnodes : 1) * sizeof *map);
    if (!c || !map) {
        free(c);
        free(map);
        return -ENOMEM;
    }
    const double *x = fm_mesh_vertices(fs->mesh);
    for (size_t v = 0, k = 0; v < nv; v++)
        if (j->node[v]) {
            for (int d = 0; d < 3; d++)
                c[(size_t)d * j->nnodes + k] = x[3 * v + (size_t)d];
            map[k++] = (int32_t)(v + 1);
        }
    char *coord_names[3] = {"X", "Y", "Z"};
    rc = ex_put_coord(exo, c, c + j->nnodes, c + 2 * j->nnodes);
    if (rc >= 0)
        rc = ex_put_coord_names(exo, coord_names);
    /* node and element ids lead back to the mesh, as MSH tags do */
    if (rc >= 0)
        rc = ex_put_node_num_map(exo, map);
    free(c);
    free(map);
    if (rc < 0)
        return rc;

    size_t nt = fm_mesh_ntriangles(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh);
    int32_t *conn = malloc((nt ? nt : 1) * 3 * sizeof *conn);
    int32_t *emap = malloc((nt ? nt : 1) * sizeof *emap);
    if (!conn || !emap) {
        free(conn);
        free(emap);
        return -ENOMEM;
    }
    for (size_t f = 0; f < nf && rc >= 0; f++) {
        size_t n = j->tstart[f + 1] - j->tstart[f];
        for (size_t i = 0; i < n; i++) {
            size_t t = j->torder[j->tstart[f] + i];
            for (int k = 0; k < 3; k++)
                conn[3 * i + (size_t)k] = j->node[tri[3 * t + (size_t)k]];
            emap[j->tstart[f] + i] = (int32_t)(t + 1);
        }
        if (n)
            rc = ex_put_elem_conn(exo, (ex_entity_id)(f + 1), conn);
    }
    if (rc >= 0)
        rc = ex_put_elem_num_map(exo, emap);
    free(conn);
    free(emap);
    return rc;
}

fm_status fm_faultset_write_exodus(const char *path, const fm_faultset *fs, fm_error *err)
{
    fm_status st = fm_faultset_validate(fs, path, err);
    if (st != FM_OK)
        return st;
    exo_job j = {.fs = fs};
    long long when;
    if ((st = fs_source_date(path, &when, err)) != FM_OK)
        return st;
    time_t tt = (time_t)when;
    struct tm tm;
    gmtime_r(&tt, &tm);
    strftime(j.qa_date, sizeof j.qa_date, "%Y-%m-%d", &tm);
    strftime(j.qa_time, sizeof j.qa_time, "%H:%M:%S", &tm);
    if (prepare(&j)) {
        release(&j);
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    for (size_t i = 0; i < fs->nnodesets; i++)
        for (size_t k = 0; k < fs->nodesets[i].n; k++)
            if (!j.node[fs->nodesets[i].vertices[k]]) {
                st = fm_error_set(err, FM_ERR_INVALID, path, 0,
                                  "node set %zu (%s): vertex %d is in no triangle", i,
                                  fs->nodesets[i].name, (int)fs->nodesets[i].vertices[k]);
                release(&j);
                return st;
            }
    /* A registered temporary name (fm_atomic.h), which netCDF refuses to
     * create if anything took it in between (EX_NOCLOBBER). */
    fm_atomic_name *tmp = fm_atomic_name_create(path, err);
    if (!tmp) {
        release(&j);
        return FM_ERR_NOMEM;
    }
    pthread_once(&opts_once, quiet_exodus);
    if ((st = fm_atomic_name_creating(tmp, err)) != FM_OK) {
        fm_atomic_name_abort(tmp);
        release(&j);
        return st;
    }
    int cws = 8, iows = 8;
    int exo = ex_create(fm_atomic_name_tmp(tmp), EX_NOCLOBBER, &cws, &iows);
    fm_atomic_name_created(tmp);
    if (exo < 0) {
        char why[400];
        st = fm_error_set(err, FM_ERR_IO, path, 0, "cannot create Exodus II file: %s",
                          exodus_reason(why, sizeof why));
    } else {
        int rc = put_all(exo, &j);
        char why[400];
        if (rc < 0 && rc != -ENOMEM)
            exodus_reason(why, sizeof why); /* before ex_close can replace it */
        int rc_close = ex_close(exo);
        if (rc >= 0 && rc_close < 0)
            exodus_reason(why, sizeof why);
        if (rc == -ENOMEM)
            st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
        else if (rc < 0 || rc_close < 0)
            st = fm_error_set(err, FM_ERR_IO, path, 0, "Exodus II write failed: %s", why);
        else {
            st = fm_atomic_name_commit(tmp, 0, err);
            tmp = NULL; /* freed, and removed on failure */
        }
    }
    fm_atomic_name_abort(tmp);
    release(&j);
    return st;
}
