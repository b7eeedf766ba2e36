/* Fault set as Gmsh MSH 4.1 or 2.2 (ASCII). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_atomic.h"
#include "faultset_internal.h"
#include "fs_out.h"

/* Neither Gmsh (text between the first two quotes) nor meshio (shlex)
 * has an escape the other understands, so the two troublesome bytes are
 * replaced; see the header. */
void fs_msh_put_name(fs_out *o, const char *name)
{
    size_t n = strlen(name);
    if (n > FM_MSH_NAME_MAX)
        n = fs_utf8_cut(name, FM_MSH_NAME_MAX);
    fs_out_char(o, '"');
    for (size_t i = 0; i < n; i++)
        fs_out_char(o, name[i] == '"' ? '\'' : name[i] == '\\' ? '/' : name[i]);
    fs_out_str(o, "\"\n");
}

/* Whether no fault before i has i's physical tag. Quadratic only when
 * tags are given; the default tags are distinct. */
static int first_with_tag(const fm_faultset *fs, size_t i)
{
    if (!fs->physical_tags)
        return 1;
    for (size_t k = 0; k < i; k++)
        if (fs->physical_tags[k] == fs->physical_tags[i])
            return 0;
    return 1;
}

/* A line of $Comments as a quoted string (see the header). */
static void put_comment(fs_out *o, const char *key, const char *text)
{
    fs_out_char(o, '"');
    fs_out_str(o, key);
    for (const char *c = text; *c; c++)
        fs_out_char(o, *c == '"' ? '\'' : *c);
    fs_out_str(o, "\"\n");
}

static void put_head(fs_out *o, const fm_faultset *fs, const char *version,
                     const fs_edge_group *g, size_t ng)
{
    fs_out_printf(o, "$MeshFormat\n%s 0 8\n$EndMeshFormat\n$Comments\n", version);
    put_comment(o, "written by faultmesh ", FM_VERSION_STRING);
    if (fs->crs && fs->crs[0])
        put_comment(o, "crs ", fs->crs);
    put_comment(o, "units ", "metres, z up (negative below sea level)");
    fs_out_str(o, "$EndComments\n");
    /* one line per physical group: the first fault with each tag names it */
    size_t ngroups = 0;
    for (size_t i = 0; i < fs->nfaults; i++)
        ngroups += first_with_tag(fs, i);
    fs_out_printf(o, "$PhysicalNames\n%zu\n", ngroups + ng);
    for (size_t i = 0; i < ng; i++) {
        fs_out_printf(o, "1 %zu ", i + 1);
        fs_msh_put_name(o, g[i].name);
    }
    for (size_t i = 0; i < fs->nfaults; i++) {
        if (!first_with_tag(fs, i))
            continue;
        fs_out_printf(o, "2 %d ", (int)fs_physical_tag(fs, i));
        fs_msh_put_name(o, fs_physical_name(fs, i));
    }
    fs_out_str(o, "$EndPhysicalNames\n");
}

static void put_vertex(fs_out *o, const double *x)
{
    for (int d = 0; d < 3; d++) {
        if (d)
            fs_out_char(o, ' ');
        fs_out_double(o, x[d]);
    }
    fs_out_char(o, '\n');
}

static void put_triangle(fs_out *o, const int32_t *t)
{
    for (int k = 0; k < 3; k++) {
        fs_out_char(o, ' ');
        fs_out_i64(o, (int64_t)t[k] + 1);
    }
    fs_out_char(o, '\n');
}

static void put_entities(fs_out *o, const fm_faultset *fs, const size_t *tstart,
                         const size_t *torder, const fs_edge_group *g, size_t ng)
{
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh);
    fs_out_printf(o, "$Entities\n0 %zu %zu 0\n", ng, fs->nfaults);
    /* curve i + 1 in physical curve i + 1 */
    for (size_t i = 0; i < ng; i++) {
        double lo[3], hi[3];
        memcpy(lo, x + 3 * (size_t)g[i].edge[0][0], sizeof lo);
        memcpy(hi, lo, sizeof hi);
        for (size_t e = 0; e < g[i].n; e++)
            for (int k = 0; k < 2; k++)
                for (int d = 0; d < 3; d++) {
                    double v = x[3 * (size_t)g[i].edge[e][k] + (size_t)d];
                    lo[d] = v < lo[d] ? v : lo[d];
                    hi[d] = v > hi[d] ? v : hi[d];
                }
        fs_out_u64(o, i + 1);
        for (int d = 0; d < 6; d++) {
            fs_out_char(o, ' ');
            fs_out_double(o, d < 3 ? lo[d] : hi[d - 3]);
        }
        fs_out_printf(o, " 1 %zu 0\n", i + 1);
    }
    for (size_t f = 0; f < fs->nfaults; f++) {
        double lo[3], hi[3];
        const double *p0 = x + 3 * (size_t)tri[3 * torder[tstart[f]]];
        memcpy(lo, p0, sizeof lo);
        memcpy(hi, p0, sizeof hi);
        for (size_t i = tstart[f]; i < tstart[f + 1]; i++)
            for (int k = 0; k < 3; k++) {
                const double *p = x + 3 * (size_t)tri[3 * torder[i] + (size_t)k];
                for (int d = 0; d < 3; d++) {
                    lo[d] = p[d] < lo[d] ? p[d] : lo[d];
                    hi[d] = p[d] > hi[d] ? p[d] : hi[d];
                }
            }
        fs_out_u64(o, f + 1);
        for (int d = 0; d < 6; d++) {
            fs_out_char(o, ' ');
            fs_out_double(o, d < 3 ? lo[d] : hi[d - 3]);
        }
        fs_out_printf(o, " 1 %d 0\n", (int)fs_physical_tag(fs, f));
    }
    fs_out_str(o, "$EndEntities\n");
}

static void put_41(fs_out *o, const fm_faultset *fs, const size_t *vstart, const size_t *vorder,
                   const size_t *tstart, const size_t *torder, const fs_edge_group *g,
                   size_t ng)
{
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh);
    size_t nf = fs->nfaults, nused = vstart[nf], nblocks = 0, vmin = (size_t)-1, vmax = 0;
    for (size_t f = 0; f < nf; f++)
        if (vstart[f + 1] > vstart[f])
            nblocks++;
    for (size_t i = 0; i < nused; i++) {
        vmin = vorder[i] < vmin ? vorder[i] : vmin;
        vmax = vorder[i] > vmax ? vorder[i] : vmax;
    }
    put_entities(o, fs, tstart, torder, g, ng);
    fs_out_printf(o, "$Nodes\n%zu %zu %zu %zu\n", nblocks, nused, vmin + 1, vmax + 1);
    for (size_t f = 0; f < nf; f++) {
        if (vstart[f + 1] == vstart[f])
            continue; /* all its nodes belong to lower faults */
        fs_out_printf(o, "2 %zu 0 %zu\n", f + 1, vstart[f + 1] - vstart[f]);
        for (size_t i = vstart[f]; i < vstart[f + 1]; i++) {
            fs_out_u64(o, vorder[i] + 1);
            fs_out_char(o, '\n');
        }
        for (size_t i = vstart[f]; i < vstart[f + 1]; i++)
            put_vertex(o, x + 3 * vorder[i]);
    }
    size_t nt = fm_mesh_ntriangles(fs->mesh), ne = 0;
    for (size_t i = 0; i < ng; i++)
        ne += g[i].n;
    fs_out_printf(o, "$EndNodes\n$Elements\n%zu %zu 1 %zu\n", nf + ng, nt + ne, nt + ne);
    for (size_t f = 0; f < nf; f++) {
        fs_out_printf(o, "2 %zu 2 %zu\n", f + 1, tstart[f + 1] - tstart[f]);
        for (size_t i = tstart[f]; i < tstart[f + 1]; i++) {
            fs_out_u64(o, torder[i] + 1);
            put_triangle(o, tri + 3 * torder[i]);
        }
    }
    /* the curves' line elements after the triangles, tags nt + 1 on */
    size_t tagn = nt;
    for (size_t i = 0; i < ng; i++) {
        fs_out_printf(o, "1 %zu 1 %zu\n", i + 1, g[i].n);
        for (size_t e = 0; e < g[i].n; e++) {
            fs_out_u64(o, ++tagn);
            for (int k = 0; k < 2; k++) {
                fs_out_char(o, ' ');
                fs_out_i64(o, (int64_t)g[i].edge[e][k] + 1);
            }
            fs_out_char(o, '\n');
        }
    }
    fs_out_str(o, "$EndElements\n");
}

/* MSH 2.2 node tags: vertex index + 1, or with fs->msh_dense_nodes the
 * position among the written (used) vertices + 1; stored in owner[]'s
 * place as a tag per vertex, 0 for a vertex not written. */
static void put_22(fs_out *o, const fm_faultset *fs, int32_t *owner, const fs_edge_group *g,
                   size_t ng)
{
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh), *tag = fm_mesh_tags(fs->mesh);
    size_t nv = fm_mesh_nvertices(fs->mesh), nt = fm_mesh_ntriangles(fs->mesh), nused = 0;
    for (size_t v = 0; v < nv; v++) {
        nused += owner[v] >= 0;
        owner[v] = owner[v] < 0 ? 0 : fs->msh_dense_nodes ? (int32_t)nused : (int32_t)(v + 1);
    }
    fs_out_printf(o, "$Nodes\n%zu\n", nused);
    for (size_t v = 0; v < nv; v++)
        if (owner[v] > 0) {
            fs_out_i64(o, owner[v]);
            fs_out_char(o, ' ');
            put_vertex(o, x + 3 * v);
        }
    size_t ne = 0;
    for (size_t i = 0; i < ng; i++)
        ne += g[i].n;
    fs_out_printf(o, "$EndNodes\n$Elements\n%zu\n", nt + ne);
    for (size_t t = 0; t < nt; t++) {
        fs_out_u64(o, t + 1);
        fs_out_str(o, " 2 2 ");
        fs_out_i64(o, fs_physical_tag(fs, (size_t)tag[t]));
        fs_out_char(o, ' ');
        fs_out_i64(o, (int64_t)tag[t] + 1);
        for (int k = 0; k < 3; k++) {
            fs_out_char(o, ' ');
            fs_out_i64(o, owner[tri[3 * t + (size_t)k]]);
        }
        fs_out_char(o, '\n');
    }
    size_t tagn = nt;
    for (size_t i = 0; i < ng; i++)
        for (size_t e = 0; e < g[i].n; e++) {
            fs_out_u64(o, ++tagn);
            fs_out_printf(o, " 1 2 %zu %zu", i + 1, i + 1);
            for (int k = 0; k < 2; k++) {
                fs_out_char(o, ' ');
                fs_out_i64(o, owner[g[i].edge[e][k]]);
            }
            fs_out_char(o, '\n');
        }
    fs_out_str(o, "$EndElements\n");
}

fm_status fm_faultset_write_msh(const char *path, const fm_faultset *fs, fm_msh_version version,
                                fm_error *err)
{
    if (version != FM_MSH_41 && version != FM_MSH_22)
        return fm_error_set(err, FM_ERR_INVALID, path, 0, "unknown MSH version %d",
                            (int)version);
    fm_status st = fm_faultset_validate(fs, path, err);
    if (st != FM_OK)
        return st;
    size_t nv = fm_mesh_nvertices(fs->mesh), nt = fm_mesh_ntriangles(fs->mesh);
    size_t *vstart = NULL, *vorder = NULL, *tstart = NULL, *torder = NULL;
    int32_t *owner = fs_vertex_owner(fs);
    int bad = !owner;
    fs_edge_group *g = NULL;
    size_t ng = 0;
    if (!bad && !fs->msh_no_curves)
        bad = fs_edge_groups_make(fs, &g, &ng);
    if (!bad && version == FM_MSH_41)
        bad = fs_group_by(owner, nv, fs->nfaults, &vstart, &vorder) ||
              fs_group_by(fm_mesh_tags(fs->mesh), nt, fs->nfaults, &tstart, &torder);
    fm_atomic_file *f = NULL;
    if (bad)
        st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    else if (!(f = fm_atomic_open(path, err)))
        st = err ? err->code : FM_ERR_IO;
    fs_out *o = NULL;
    if (st == FM_OK && !(o = fs_out_open(fm_atomic_stream(f)))) {
        fm_atomic_abort(f);
        st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    if (st == FM_OK) {
        put_head(o, fs, version == FM_MSH_41 ? "4.1" : "2.2", g, ng);
        if (version == FM_MSH_41)
            put_41(o, fs, vstart, vorder, tstart, torder, g, ng);
        else
            put_22(o, fs, owner, g, ng);
        st = fs_out_commit(o, f, path, err);
    }
    fs_edge_groups_free(g, ng);
    free(owner);
    free(vstart);
    free(vorder);
    free(tstart);
    free(torder);
    return st;
}
