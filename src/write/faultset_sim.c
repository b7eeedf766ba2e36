/* Per-element strike and dip, section names, and the RSQSim fault file. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fm_atomic.h"
#include "faultset_internal.h"
#include "fm_sim_write.h"
#include "fs_out.h"
#include "fm_names.h"
#include "sim_internal.h"

#define RAD2DEG (180.0 / 3.14159265358979323846)

/* Azimuth in [0, 360) of the horizontal direction (east, north). */
static double azimuth(double e, double n)
{
    double az = atan2(e, n) * RAD2DEG;
    if (az < 0)
        az += 360;
    return az >= 360 ? 0 : az;
}

void sim_strike_dip(const double *n, double *strike, double *dip)
{
    double h = hypot(n[0], n[1]);
    if (h == 0 && n[2] == 0) {
        *strike = *dip = 0;
        return;
    }
    *dip = atan2(h, fabs(n[2])) * RAD2DEG;
    if (*dip > 90)
        *dip = 90;
    /* The upward normal's horizontal part points down dip; strike is a
     * quarter turn anticlockwise of that. */
    double s = h == 0 ? 0 : azimuth(n[0], n[1]) - 90;
    if (s < 0)
        s += 360;
    *strike = s >= 360 ? 0 : s;
}

int fm_element_orient(const double *a, const double *b, const double *c, double *strike,
                      double *dip)
{
    double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double g[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {e[1] * g[2] - e[2] * g[1], e[2] * g[0] - e[0] * g[2],
                   e[0] * g[1] - e[1] * g[0]};
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    int flip = 0;
    if (len == 0) {
        *strike = *dip = 0;
        return 0;
    }
    if (fabs(n[2]) <= 1e-9 * len) {
        /* Vertical: either side could be "up"; the one with strike in
         * [0, 180) is taken, so that a vertical fault's elements agree. */
        n[2] = 0;
        double s;
        sim_strike_dip(n, &s, dip);
        if (s >= 180) {
            flip = 1;
            s -= 180;
        }
        *strike = s;
        *dip = 90;
        return flip;
    }
    if (n[2] < 0) {
        flip = 1;
        for (int d = 0; d < 3; d++)
            n[d] = -n[d];
    }
    sim_strike_dip(n, strike, dip);
    return flip;
}

void fm_faultset_strike_dip(const fm_faultset *fs, double *strike, double *dip)
{
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh);
    size_t nt = fm_mesh_ntriangles(fs->mesh);
    for (size_t t = 0; t < nt; t++)
        fm_element_orient(x + 3 * (size_t)tri[3 * t], x + 3 * (size_t)tri[3 * t + 1],
                          x + 3 * (size_t)tri[3 * t + 2], &strike[t], &dip[t]);
}

char **sim_section_names(const fm_faultset *fs)
{
    return fm_short_names(fs->names, fs->nfaults, FM_SECTION_NAME_MAX);
}

void sim_section_names_free(char **sect, size_t n) { fm_short_names_free(sect, n); }

int sim_corners(const fm_faultset *fs, size_t t, int32_t v[3])
{
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh);
    for (int k = 0; k < 3; k++)
        v[k] = tri[3 * t + (size_t)k];
    double s, d;
    if (fm_element_orient(x + 3 * (size_t)v[0], x + 3 * (size_t)v[1], x + 3 * (size_t)v[2], &s,
                          &d)) {
        int32_t tmp = v[1];
        v[1] = v[2];
        v[2] = tmp;
        return 1;
    }
    return 0;
}

fm_status sim_check_slip(const fm_faultset *fs, const fm_sim_slip *slip, const char *path,
                         fm_error *err)
{
    if (!slip || !slip->rake || !slip->slip_rate)
        return fm_error_set(err, FM_ERR_INVALID, path, 0, "no rake or slip rate given");
    for (size_t f = 0; f < fs->nfaults; f++)
        if (!isfinite(slip->rake[f]) || !isfinite(slip->slip_rate[f]) || slip->slip_rate[f] < 0)
            return fm_error_set(err, FM_ERR_NUMERIC, path, 0,
                                "fault %zu: rake %g or slip rate %g m/s is not a finite "
                                "number (rate >= 0)",
                                f, slip->rake[f], slip->slip_rate[f]);
    size_t nt = fm_mesh_ntriangles(fs->mesh);
    for (size_t t = 0; t < nt && (slip->rake_t || slip->slip_rate_t); t++)
        if ((slip->rake_t && !isfinite(slip->rake_t[t])) ||
            (slip->slip_rate_t && !(isfinite(slip->slip_rate_t[t]) && slip->slip_rate_t[t] >= 0)))
            return fm_error_set(err, FM_ERR_NUMERIC, path, 0,
                                "triangle %zu: rake %g or slip rate %g m/s is not a finite "
                                "number (rate >= 0)",
                                t, slip->rake_t ? slip->rake_t[t] : 0,
                                slip->slip_rate_t ? slip->slip_rate_t[t] : 0);
    return FM_OK;
}

fm_status fm_faultset_write_rsqsim(const char *path, const fm_faultset *fs,
                                   const fm_sim_slip *slip, fm_error *err)
{
    fm_status st = fm_faultset_validate(fs, path, err);
    if (st == FM_OK)
        st = sim_check_slip(fs, slip, path, err);
    if (st != FM_OK)
        return st;
    size_t nt = fm_mesh_ntriangles(fs->mesh);
    size_t *start = NULL, *order = NULL;
    char **sect = sim_section_names(fs);
    int bad = !sect || fs_group_by(fm_mesh_tags(fs->mesh), nt, fs->nfaults, &start, &order);
    fm_atomic_file *af = NULL;
    fs_out *o = NULL;
    if (bad) {
        st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    } else if (!(af = fm_atomic_open(path, err))) {
        st = err ? err->code : FM_ERR_IO;
    } else if (!(o = fs_out_open(fm_atomic_stream(af)))) {
        fm_atomic_abort(af);
        st = fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    }
    if (st == FM_OK) {
        const double *x = fm_mesh_vertices(fs->mesh);
        for (size_t f = 0; f < fs->nfaults; f++) {
            for (size_t i = start[f]; i < start[f + 1]; i++) {
                int32_t v[3];
                sim_corners(fs, order[i], v);
                for (int k = 0; k < 3; k++)
                    for (int d = 0; d < 3; d++) {
                        fs_out_double(o, x[3 * (size_t)v[k] + (size_t)d]);
                        fs_out_char(o, ' ');
                    }
                size_t t = order[i];
                fs_out_double(o, slip->rake_t ? slip->rake_t[t] : slip->rake[f]);
                fs_out_char(o, ' ');
                fs_out_double(o, slip->slip_rate_t ? slip->slip_rate_t[t] : slip->slip_rate[f]);
                fs_out_char(o, ' ');
                fs_out_u64(o, f + 1);
                fs_out_char(o, ' ');
                fs_out_str(o, sect[f]);
                fs_out_char(o, '\n');
            }
        }
        st = fs_out_commit(o, af, path, err);
    }
    sim_section_names_free(sect, fs->nfaults);
    free(start);
    free(order);
    return st;
}
