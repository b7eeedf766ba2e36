/* Fault set as Gmsh MSH 4.1 or 2.2 (ASCII). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_atomic.h"
#include "faultset_internal.h"

static void put_double(FILE *fp, double v)
{
    char buf[32];
    fwrite(buf, 1, fs_format_double(buf, v), fp);
}

/* Neither Gmsh (text between the first two quotes) nor meshio (shlex)
 * has an escape the other understands, so the two troublesome bytes are
 * replaced; see the header. */
static void put_name(FILE *fp, const char *name)
{
    size_t n = strlen(name);
    if (n > FM_MSH_NAME_MAX)
        n = fs_utf8_cut(name, FM_MSH_NAME_MAX);
    fputc('"', fp);
    for (size_t i = 0; i < n; i++)
        fputc(name[i] == '"' ? '\'' : name[i] == '\\' ? '/' : name[i], fp);
    fputs("\"\n", fp);
}

static void put_head(FILE *fp, const fm_faultset *fs, const char *version)
{
    fprintf(fp, "$MeshFormat\n%s 0 8\n$EndMeshFormat\n$PhysicalNames\n%zu\n", version,
            fs->nfaults);
    for (size_t i = 0; i < fs->nfaults; i++) {
        fprintf(fp, "2 %d ", (int)fs_physical_tag(fs, i));
        put_name(fp, fs->names[i]);
    }
    fputs("$EndPhysicalNames\n", fp);
}

static void put_vertex(FILE *fp, const double *x)
{
    for (int d = 0; d < 3; d++) {
        if (d)
            fputc(' ', fp);
        put_double(fp, x[d]);
    }
    fputc('\n', fp);
}

static void put_triangle(FILE *fp, const int32_t *t)
{
    fprintf(fp, " %ld %ld %ld\n", (long)t[0] + 1, (long)t[1] + 1, (long)t[2] + 1);
}

static void put_entities(FILE *fp, const fm_faultset *fs, const size_t *tstart,
                         const size_t *torder)
{
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh);
    fprintf(fp, "$Entities\n0 0 %zu 0\n", fs->nfaults);
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
        fprintf(fp, "%zu", f + 1);
        for (int d = 0; d < 6; d++) {
            fputc(' ', fp);
            put_double(fp, d < 3 ? lo[d] : hi[d - 3]);
        }
        fprintf(fp, " 1 %d 0\n", (int)fs_physical_tag(fs, f));
    }
    fputs("$EndEntities\n", fp);
}

static void put_41(FILE *fp, const fm_faultset *fs, const size_t *vstart, const size_t *vorder,
                   const size_t *tstart, const size_t *torder)
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
    put_entities(fp, fs, tstart, torder);
    fprintf(fp, "$Nodes\n%zu %zu %zu %zu\n", nblocks, nused, vmin + 1, vmax + 1);
    for (size_t f = 0; f < nf; f++) {
        if (vstart[f + 1] == vstart[f])
            continue; /* all its nodes belong to lower faults */
        fprintf(fp, "2 %zu 0 %zu\n", f + 1, vstart[f + 1] - vstart[f]);
        for (size_t i = vstart[f]; i < vstart[f + 1]; i++)
            fprintf(fp, "%zu\n", vorder[i] + 1);
        for (size_t i = vstart[f]; i < vstart[f + 1]; i++)
            put_vertex(fp, x + 3 * vorder[i]);
    }
    size_t nt = fm_mesh_ntriangles(fs->mesh);
    fprintf(fp, "$EndNodes\n$Elements\n%zu %zu 1 %zu\n", nf, nt, nt);
    for (size_t f = 0; f < nf; f++) {
        fprintf(fp, "2 %zu 2 %zu\n", f + 1, tstart[f + 1] - tstart[f]);
        for (size_t i = tstart[f]; i < tstart[f + 1]; i++) {
            fprintf(fp, "%zu", torder[i] + 1);
            put_triangle(fp, tri + 3 * torder[i]);
        }
    }
    fputs("$EndElements\n", fp);
}

static void put_22(FILE *fp, const fm_faultset *fs, const int32_t *owner)
{
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh), *tag = fm_mesh_tags(fs->mesh);
    size_t nv = fm_mesh_nvertices(fs->mesh), nt = fm_mesh_ntriangles(fs->mesh), nused = 0;
    for (size_t v = 0; v < nv; v++)
        nused += owner[v] >= 0;
    fprintf(fp, "$Nodes\n%zu\n", nused);
    for (size_t v = 0; v < nv; v++)
        if (owner[v] >= 0) {
            fprintf(fp, "%zu ", v + 1);
            put_vertex(fp, x + 3 * v);
        }
    fprintf(fp, "$EndNodes\n$Elements\n%zu\n", nt);
    for (size_t t = 0; t < nt; t++) {
        fprintf(fp, "%zu 2 2 %d %ld", t + 1, (int)fs_physical_tag(fs, (size_t)tag[t]),
                (long)tag[t] + 1);
        put_triangle(fp, tri + 3 * t);
    }
    fputs("$EndElements\n", fp);
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
    if (!bad && version == FM_MSH_41)
        bad = fs_group_by(owner, nv, fs->nfaults, &vstart, &vorder) ||
              fs_group_by(fm_mesh_tags(fs->mesh), nt, fs->nfaults, &tstart, &torder);
    fm_atomic_file *f = NULL;
    if (bad)
        st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    else if (!(f = fm_atomic_open(path, err)))
        st = err ? err->code : FM_ERR_IO;
    if (st == FM_OK) {
        FILE *fp = fm_atomic_stream(f);
        put_head(fp, fs, version == FM_MSH_41 ? "4.1" : "2.2");
        if (version == FM_MSH_41)
            put_41(fp, fs, vstart, vorder, tstart, torder);
        else
            put_22(fp, fs, owner);
        if (ferror(fp)) {
            fm_atomic_abort(f);
            st = fm_error_set(err, FM_ERR_IO, path, 0, "write failed");
        } else {
            st = fm_atomic_commit(f, err);
        }
    }
    free(owner);
    free(vstart);
    free(vorder);
    free(tstart);
    free(torder);
    return st;
}
