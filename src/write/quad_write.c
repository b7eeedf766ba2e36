/* Rectangular elements as VTU, MSH 4.1 and RSQSim's rectangular fault
 * file (fm_quad_write.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_atomic.h"
#include "fm_names.h"
#include "fm_quad_write.h"
#include "fm_vtu.h"
#include "faultset_internal.h"
#include "fs_out.h"
#include "quad_internal.h"
#include "sim_internal.h"

void fm_quad_strike_dip(const double c[12], double *strike, double *dip)
{
    double down[3], along[3], n[3];
    for (int d = 0; d < 3; d++) {
        down[d] = c[3 + d] - c[d];
        along[d] = c[9 + d] - c[d];
    }
    n[0] = down[1] * along[2] - down[2] * along[1];
    n[1] = down[2] * along[0] - down[0] * along[2];
    n[2] = down[0] * along[1] - down[1] * along[0];
    sim_strike_dip(n, strike, dip);
}

fm_status quad_validate(const fm_quadset *qs, const char *path, fm_error *err)
{
    if (!qs || !qs->names || !qs->nfaults || (qs->nquads && (!qs->corners || !qs->fault)))
        return fm_error_set(err, FM_ERR_INVALID, path, 0,
                            "a set of rectangles needs corners, faults and names");
    if (qs->nquads >= (size_t)INT32_MAX / 4)
        return fm_error_set(err, FM_ERR_INVALID, path, 0, "too many rectangles");
    for (size_t f = 0; f < qs->nfaults; f++)
        if (!qs->names[f] || !qs->names[f][0] || strpbrk(qs->names[f], "\n\r"))
            return fm_error_set(err, FM_ERR_INVALID, path, 0,
                                "fault %zu has no name, or one over several lines", f);
    for (size_t i = 0; i < qs->nquads; i++) {
        if (qs->fault[i] < 0 || (size_t)qs->fault[i] >= qs->nfaults ||
            (i && qs->fault[i] < qs->fault[i - 1]))
            return fm_error_set(err, FM_ERR_INVALID, path, 0,
                                "rectangle %zu: fault %d out of range or out of order", i,
                                (int)qs->fault[i]);
        for (int k = 0; k < 12; k++)
            if (!isfinite(qs->corners[12 * i + (size_t)k]))
                return fm_error_set(err, FM_ERR_NUMERIC, path, 0,
                                    "rectangle %zu has a non-finite corner", i);
        if ((qs->rake && !isfinite(qs->rake[i])) ||
            (qs->slip_rate && !(qs->slip_rate[i] >= 0 && isfinite(qs->slip_rate[i]))))
            return fm_error_set(err, FM_ERR_NUMERIC, path, 0,
                                "rectangle %zu: rake not finite or slip rate not >= 0", i);
    }
    return FM_OK;
}

double quad_rake(const fm_quadset *qs, size_t i) { return qs->rake ? qs->rake[i] : 180; }
double quad_rate(const fm_quadset *qs, size_t i) { return qs->slip_rate ? qs->slip_rate[i] : 0; }

fm_status fm_quadset_write_vtu(const char *path, const fm_quadset *qs, fm_error *err)
{
    fm_status st = quad_validate(qs, path, err);
    if (st != FM_OK)
        return st;
    size_t n = qs->nquads;
    int32_t *conn = malloc((4 * n + 1) * sizeof *conn), *number = malloc((n + 1) * sizeof *number);
    double *v = malloc((6 * n + 1) * sizeof *v);
    if (!conn || !v || !number) {
        free(conn);
        free(v);
        free(number);
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    double *strike = v, *dip = v + n, *rake = v + 2 * n, *rate = v + 3 * n, *len = v + 4 * n,
           *wid = v + 5 * n;
    for (size_t i = 0; i < n; i++) {
        const double *c = qs->corners + 12 * i;
        for (int k = 0; k < 4; k++)
            conn[4 * i + (size_t)k] = (int32_t)(4 * i + (size_t)k);
        fm_quad_strike_dip(c, &strike[i], &dip[i]);
        number[i] = qs->fault[i] + 1;
        rake[i] = quad_rake(qs, i);
        rate[i] = quad_rate(qs, i);
        len[i] = sqrt((c[9] - c[0]) * (c[9] - c[0]) + (c[10] - c[1]) * (c[10] - c[1]) +
                      (c[11] - c[2]) * (c[11] - c[2]));
        wid[i] = sqrt((c[3] - c[0]) * (c[3] - c[0]) + (c[4] - c[1]) * (c[4] - c[1]) +
                      (c[5] - c[2]) * (c[5] - c[2]));
    }
    fm_vtu_array cells[8] = {{"fault_id", FM_VTU_INT32, 1, number},
                             {"strike", FM_VTU_FLOAT64, 1, strike},
                             {"dip", FM_VTU_FLOAT64, 1, dip},
                             {"rake", FM_VTU_FLOAT64, 1, rake},
                             {"slip_rate", FM_VTU_FLOAT64, 1, rate},
                             {"length", FM_VTU_FLOAT64, 1, len},
                             {"width", FM_VTU_FLOAT64, 1, wid},
                             {"flatness", FM_VTU_FLOAT64, 1, qs->flatness}};
    const char *crs[1] = {qs->crs ? qs->crs : ""};
    fm_vtu_strings strings[2] = {{"fault_names", qs->names, qs->nfaults}, {"crs", crs, 1}};
    fm_vtu_content content = {.points = qs->corners, .npoints = 4 * n, .quads = conn,
                              .nquads = n, .cell_data = cells,
                              .ncell_data = qs->flatness ? 8 : 7,
                              .field_strings = strings,
                              .nfield_strings = qs->crs && qs->crs[0] ? 2 : 1};
    st = fm_vtu_write(path, &content, err);
    free(conn);
    free(v);
    free(number);
    return st;
}

fm_status fm_quadset_write_msh(const char *path, const fm_quadset *qs, fm_error *err)
{
    fm_status st = quad_validate(qs, path, err);
    if (st != FM_OK)
        return st;
    size_t *start = NULL, *order = NULL, nf = qs->nfaults, used = 0;
    if (fs_group_by(qs->fault, qs->nquads, nf, &start, &order))
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    for (size_t f = 0; f < nf; f++)
        used += start[f + 1] > start[f];
    fm_atomic_file *af = fm_atomic_open(path, err);
    fs_out *o = af ? fs_out_open(fm_atomic_stream(af)) : NULL;
    if (!af || !o) {
        free(start);
        free(order);
        if (!af)
            return err ? err->code : FM_ERR_IO;
        fm_atomic_abort(af);
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    fs_out_str(o, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
    fs_out_str(o, "$Comments\n\"faultmesh rectangular elements\"\n\"crs: ");
    if (qs->crs)
        for (const char *p = qs->crs; *p; p++)
            fs_out_char(o, *p == '"' ? '\'' : *p);
    fs_out_str(o, "\"\n$EndComments\n");
    fs_out_printf(o, "$PhysicalNames\n%zu\n", used);
    for (size_t f = 0; f < nf; f++)
        if (start[f + 1] > start[f]) {
            fs_out_printf(o, "2 %zu ", f + 1);
            fs_msh_put_name(o, qs->names[f]);
        }
    fs_out_printf(o, "$EndPhysicalNames\n$Entities\n0 0 %zu 0\n", used);
    for (size_t f = 0; f < nf; f++) {
        if (start[f + 1] == start[f])
            continue;
        double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (size_t i = start[f]; i < start[f + 1]; i++)
            for (int k = 0; k < 4; k++)
                for (int d = 0; d < 3; d++) {
                    double v = qs->corners[12 * i + 3 * (size_t)k + (size_t)d];
                    lo[d] = fmin(lo[d], v);
                    hi[d] = fmax(hi[d], v);
                }
        fs_out_u64(o, f + 1);
        for (int d = 0; d < 6; d++) {
            fs_out_char(o, ' ');
            fs_out_double(o, d < 3 ? lo[d] : hi[d - 3]);
        }
        fs_out_printf(o, " 1 %zu 0\n", f + 1);
    }
    size_t nn = 4 * qs->nquads;
    fs_out_printf(o, "$EndEntities\n$Nodes\n%zu %zu %zu %zu\n", used, nn, nn ? (size_t)1 : 0, nn);
    for (size_t f = 0; f < nf; f++) {
        size_t a = start[f], b = start[f + 1];
        if (a == b)
            continue;
        fs_out_printf(o, "2 %zu 0 %zu\n", f + 1, 4 * (b - a));
        for (size_t i = a; i < b; i++)
            for (int k = 0; k < 4; k++) {
                fs_out_u64(o, 4 * order[i] + (size_t)k + 1);
                fs_out_char(o, '\n');
            }
        for (size_t i = a; i < b; i++)
            for (int k = 0; k < 4; k++) {
                const double *p = qs->corners + 12 * order[i] + 3 * (size_t)k;
                for (int d = 0; d < 3; d++) {
                    if (d)
                        fs_out_char(o, ' ');
                    fs_out_double(o, p[d]);
                }
                fs_out_char(o, '\n');
            }
    }
    fs_out_printf(o, "$EndNodes\n$Elements\n%zu %zu %zu %zu\n", used, qs->nquads,
                  qs->nquads ? (size_t)1 : 0, qs->nquads);
    for (size_t f = 0; f < nf; f++) {
        size_t a = start[f], b = start[f + 1];
        if (a == b)
            continue;
        fs_out_printf(o, "2 %zu 3 %zu\n", f + 1, b - a);
        for (size_t i = a; i < b; i++) {
            fs_out_u64(o, order[i] + 1);
            for (int k = 0; k < 4; k++) {
                fs_out_char(o, ' ');
                fs_out_u64(o, 4 * order[i] + (size_t)k + 1);
            }
            fs_out_char(o, '\n');
        }
    }
    fs_out_str(o, "$EndElements\n");
    free(start);
    free(order);
    return fs_out_commit(o, af, path, err);
}

fm_status fm_quadset_write_rsqsim(const char *path, const fm_quadset *qs, fm_error *err)
{
    fm_status st = quad_validate(qs, path, err);
    if (st != FM_OK)
        return st;
    fm_atomic_file *af = fm_atomic_open(path, err);
    if (!af)
        return err ? err->code : FM_ERR_IO;
    fs_out *o = fs_out_open(fm_atomic_stream(af));
    if (!o) {
        fm_atomic_abort(af);
        return fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    for (size_t i = 0; i < qs->nquads; i++) {
        const double *c = qs->corners + 12 * i;
        double v[9];
        for (int d = 0; d < 3; d++)
            v[d] = (c[d] + c[3 + d] + c[6 + d] + c[9 + d]) / 4;
        v[3] = sqrt((c[9] - c[0]) * (c[9] - c[0]) + (c[10] - c[1]) * (c[10] - c[1]) +
                    (c[11] - c[2]) * (c[11] - c[2]));
        v[4] = sqrt((c[3] - c[0]) * (c[3] - c[0]) + (c[4] - c[1]) * (c[4] - c[1]) +
                    (c[5] - c[2]) * (c[5] - c[2]));
        fm_quad_strike_dip(c, &v[5], &v[6]);
        v[7] = quad_rake(qs, i);
        v[8] = quad_rate(qs, i);
        for (int k = 0; k < 9; k++) {
            fs_out_double(o, v[k]);
            fs_out_char(o, ' ');
        }
        fs_out_u64(o, (uint64_t)qs->fault[i] + 1);
        fs_out_char(o, '\n');
    }
    return fs_out_commit(o, af, path, err);
}
