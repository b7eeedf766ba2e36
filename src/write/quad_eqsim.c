/* Rectangular elements as an EQSim input geometry file (record 204). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_atomic.h"
#include "fm_names.h"
#include "fm_reproject.h"
#include "fs_out.h"
#include "quad_internal.h"
#include "sim_internal.h"

#define DEG2RAD (3.14159265358979323846 / 180)

/* The section's mean strike direction (east, north): the axial mean of
 * its elements' strikes weighted by area, pointed the way most point. */
static void mean_strike(const fm_quadset *qs, size_t a, size_t b, double dir[2])
{
    double c2 = 0, s2 = 0, th, sense = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t i = a; i < b; i++) {
            const double *c = qs->corners + 12 * i;
            double st, dp, L = hypot(c[9] - c[0], c[10] - c[1]);
            fm_quad_strike_dip(c, &st, &dp);
            (void)dp;
            if (pass == 0) {
                c2 += L * cos(2 * st * DEG2RAD);
                s2 += L * sin(2 * st * DEG2RAD);
            } else {
                sense += L * cos(st * DEG2RAD - th);
            }
        }
        th = (c2 == 0 && s2 == 0) ? 0 : atan2(s2, c2) / 2;
    }
    if (sense < 0)
        th += 3.14159265358979323846;
    dir[0] = sin(th);
    dir[1] = cos(th);
}

fm_status fm_quadset_write_eqsim(const char *path, const fm_quadset *qs, fm_eqsim_coords coords,
                                 fm_error *err)
{
    fm_status st = quad_validate(qs, path, err);
    if (st != FM_OK)
        return st;
    if (coords != FM_EQSIM_SPHERICAL && coords != FM_EQSIM_RECTANGULAR)
        return fm_error_set(err, FM_ERR_INVALID, path, 0, "unknown EQSim coordinate system %d",
                            (int)coords);
    int sph = coords == FM_EQSIM_SPHERICAL;
    size_t n = 4 * qs->nquads;
    double *lat = malloc((n + 1) * sizeof *lat), *lon = malloc((n + 1) * sizeof *lon);
    double *das = malloc((n + 1) * sizeof *das);
    char **sect = fm_short_names(qs->names, qs->nfaults, FM_SECTION_NAME_MAX);
    fm_reproject *rp = NULL;
    if (!lat || !lon || !das || !sect)
        st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    if (st == FM_OK)
        st = sim_latlon(qs->corners, n, NULL, qs->crs, coords, lat, lon, &rp, path, err);
    fm_atomic_file *af = NULL;
    fs_out *o = NULL;
    if (st == FM_OK && !(af = fm_atomic_open(path, err)))
        st = err ? err->code : FM_ERR_IO;
    if (st == FM_OK && !(o = fs_out_open(fm_atomic_stream(af)))) {
        fm_atomic_abort(af);
        st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    if (st == FM_OK) {
        size_t nsec = 0;
        sim_bounds all;
        sim_bounds_init(&all);
        for (size_t i = 0; i < n; i++)
            sim_bounds_add(&all, lat[i], lon[i], qs->corners[3 * i + 2]);
        for (size_t i = 0; i < qs->nquads; i++)
            nsec += i == 0 || qs->fault[i] != qs->fault[i - 1];
        char title[160];
        snprintf(title, sizeof title, "faultmesh fault set: %zu sections, %zu rectangles", nsec,
                 qs->nquads);
        sim_eqsim_head(o, title, sph, rp, qs->crs, 1);
        sim_eqsim_summary(o, nsec, n, 0, qs->nquads, &all, sph);
        for (size_t a = 0; a < qs->nquads;) {
            size_t b = a + 1;
            while (b < qs->nquads && qs->fault[b] == qs->fault[a])
                b++;
            double dir[2], dlo = INFINITY, dhi = -INFINITY;
            mean_strike(qs, a, b, dir);
            sim_bounds sb;
            sim_bounds_init(&sb);
            for (size_t v = 4 * a; v < 4 * b; v++) {
                const double *p = qs->corners + 3 * v;
                das[v] = dir[0] * p[0] + dir[1] * p[1];
                dlo = fmin(dlo, das[v]);
                sim_bounds_add(&sb, lat[v], lon[v], p[2]);
            }
            /* the trace: upper corners of the top row; 2 and 3 at its ends */
            size_t first = SIZE_MAX, last = SIZE_MAX;
            for (size_t v = 4 * a; v < 4 * b; v++) {
                das[v] -= dlo;
                dhi = fmax(dhi, das[v]);
                size_t i = v / 4, k = v % 4;
                if (qs->top && qs->top[i] && (k == 0 || k == 3)) {
                    if (first == SIZE_MAX || das[v] < das[first])
                        first = v;
                    if (last == SIZE_MAX || das[v] > das[last])
                        last = v;
                }
            }
            int32_t f = qs->fault[a];
            sim_eqsim_section(o, (size_t)f + 1, sect[f], 4 * (b - a), 0, b - a, &sb, dhi);
            for (size_t v = 4 * a; v < 4 * b; v++) {
                size_t i = v / 4, k = v % 4;
                int on = qs->top && qs->top[i] && (k == 0 || k == 3);
                fs_out_str(o, "202");
                sim_put_int(o, v + 1);
                sim_put_num(o, lat[v]);
                sim_put_num(o, lon[v]);
                sim_put_num(o, qs->corners[3 * v + 2]);
                sim_put_num(o, das[v]);
                sim_put_int(o, !on ? 0 : v == first ? 2 : v == last ? 3 : 1);
                fs_out_char(o, '\n');
            }
            for (size_t i = a; i < b; i++) {
                const double *c = qs->corners + 12 * i;
                double sd, dd;
                if (sph) {
                    double la[3], lo[3], z[3], nrm[3];
                    const int k3[3] = {0, 1, 3};
                    /* corners 0, 1, 3: down dip then along strike, as the
                     * triangle writer's corner order has it */
                    for (int k = 0; k < 3; k++) {
                        size_t v = 4 * i + (size_t)k3[k];
                        la[k] = lat[v];
                        lo[k] = lon[v];
                        z[k] = qs->corners[3 * v + 2];
                    }
                    sim_enu_normal(la, lo, z, nrm);
                    sim_strike_dip(nrm, &sd, &dd);
                } else {
                    fm_quad_strike_dip(c, &sd, &dd);
                }
                fs_out_str(o, "204");
                sim_put_int(o, i + 1);
                for (int k = 0; k < 4; k++)
                    sim_put_int(o, 4 * i + (size_t)k + 1);
                sim_put_num(o, quad_rake(qs, i));
                sim_put_num(o, quad_rate(qs, i));
                sim_put_num(o, 0);
                sim_put_num(o, sd);
                sim_put_num(o, dd);
                sim_put_int(o, 1);
                fs_out_char(o, '\n');
            }
            a = b;
        }
        fs_out_str(o, "999 End\n");
        st = fs_out_commit(o, af, path, err);
    }
    fm_short_names_free(sect, qs->nfaults);
    free(lat);
    free(lon);
    free(das);
    fm_reproject_destroy(rp);
    return st;
}
