/* The simulator side of remesh: slip from --slip and the CFM metadata,
 * element attributes, RSQSim and EQSim files, report.json entries. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "run_internal.h"
#include "sim_attrs.h"
#include "fm_tile.h"

#define DEG2RAD (3.14159265358979323846 / 180.0)
#define METADATA_FILE "CFM5.3_Metadata.csv"

static int is_dir(const char *p)
{
    struct stat s;
    return stat(p, &s) == 0 && S_ISDIR(s.st_mode);
}

static int is_file(const char *p)
{
    struct stat s;
    return stat(p, &s) == 0 && S_ISREG(s.st_mode);
}

/* Drops the last component of path p (trailing slashes first); one
 * that cannot be dropped textually ("", ".", "..", a bare name's folder)
 * gets "/.." appended instead. p has room for 4 more bytes. */
static void up_one(char *p)
{
    size_t n = strlen(p);
    while (n > 1 && p[n - 1] == '/')
        p[--n] = 0;
    char *slash = strrchr(p, '/');
    const char *last = slash ? slash + 1 : p;
    if (!*p || !strcmp(last, ".") || !strcmp(last, "..")) {
        strcat(p, *p ? "/.." : "..");
    } else if (!slash) {
        strcpy(p, ".");
    } else {
        slash[slash == p] = 0; /* keep the root's "/" */
    }
}

/* CFM5.3_Metadata.csv in the parent folder of an input folder, or of a
 * file's folder, malloc'ed, if that file exists. */
static char *metadata_beside(const char *input)
{
    size_t n = strlen(input);
    char *p = malloc(n + sizeof METADATA_FILE + 16);
    if (!p)
        return NULL;
    memcpy(p, input, n + 1);
    if (!is_dir(p))
        up_one(p);
    up_one(p);
    if (strcmp(p, "/"))
        strcat(p, "/");
    strcat(p, METADATA_FILE);
    if (is_file(p))
        return p;
    free(p);
    return NULL;
}

fm_status sim_cli_load(sim_cli *sc, const char *crs, const char *const *paths, size_t npaths,
                       fm_error *err)
{
    if (sc->slip_path && fm_slip_table_read(sc->slip_path, &sc->slip, err) != FM_OK)
        return err->code;
    if (sc->metadata_path) {
        if (!(sc->metadata_found = strdup(sc->metadata_path)))
            return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    } else {
        for (size_t i = 0; i < npaths && !sc->metadata_found; i++)
            sc->metadata_found = metadata_beside(paths[i]);
    }
    if (!sc->metadata_found)
        run_log(sc->ctl, FM_LOG_INFO,
                "no %s beside the inputs (in the parent folder of an input folder): rakes come "
                "from --slip or the settings file, else %g; give --metadata FILE",
                METADATA_FILE, FM_SLIP_DEFAULT_RAKE);
    if (sc->metadata_found && fm_metadata_read(sc->metadata_found, &sc->md, err) != FM_OK)
        return err->code;
    fm_error e;
    fm_error_clear(&e);
    if (sc->nkin && fm_sections_read(sc->kin_paths, sc->nkin, &sc->sections, &e) != FM_OK)
        return fm_error_set(err, e.code, NULL, 0, "--kinematics: %s", e.message);
    if (sc->nkin && !fm_sections_count(sc->sections))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0,
                            "--kinematics: no complete fault section (trace, dip, rake, depths) "
                            "in %s",
                            sc->kin_paths[0]);
    /* without --crs the CRS comes from the inputs, checked once read */
    if (crs && sc->eqsim == FM_EQSIM_SPHERICAL && fm_eqsim_check_crs(crs, &e) != FM_OK)
        return fm_error_set(err, e.code, NULL, 0, "%s; give --crs, or --eqsim-coords utm",
                            e.message);
    return FM_OK;
}

void sim_cli_free(sim_cli *sc)
{
    fm_metadata_destroy(sc->md);
    fm_sections_destroy(sc->sections);
    sc->sections = NULL;
    fm_slip_table_destroy(sc->slip);
    free(sc->metadata_found);
    sc->md = NULL;
    sc->slip = NULL;
    sc->metadata_found = NULL;
}

void sim_attrs_free(sim_attrs *a)
{
    sim_kinematics_free(a);
    fm_tiles_destroy(a->tiles);
    free(a->slip);
    free(a->rake_f);
    free(a->rate_f);
    free(a->strike);
    free(a->dip);
    free(a->rake_t);
    free(a->rate_t);
    free(a->mean_strike);
    free(a->mean_dip);
    memset(a, 0, sizeof *a);
}

int sim_attrs_make(const sim_cli *sc, const fm_faultset *fs, sim_attrs *a)
{
    memset(a, 0, sizeof *a);
    size_t nf = fs->nfaults, nt = fm_mesh_ntriangles(fs->mesh);
    a->nfaults = nf;
    a->ntriangles = nt;
    a->slip = calloc(nf + 1, sizeof *a->slip);
    a->rake_f = calloc(nf + 1, sizeof *a->rake_f);
    a->rate_f = calloc(nf + 1, sizeof *a->rate_f);
    a->mean_strike = calloc(nf + 1, sizeof *a->mean_strike);
    a->mean_dip = calloc(nf + 1, sizeof *a->mean_dip);
    a->strike = calloc(nt + 1, sizeof *a->strike);
    a->dip = calloc(nt + 1, sizeof *a->dip);
    a->rake_t = calloc(nt + 1, sizeof *a->rake_t);
    a->rate_t = calloc(nt + 1, sizeof *a->rate_t);
    double *sums = calloc(4 * nf + 1, sizeof *sums);
    if (!a->slip || !a->rake_f || !a->rate_f || !a->mean_strike || !a->mean_dip || !a->strike ||
        !a->dip || !a->rake_t || !a->rate_t || !sums) {
        free(sums);
        sim_attrs_free(a);
        return -1;
    }
    fm_slip_assign(fs->names, nf, sc->md, sc->slip, a->slip);
    for (size_t f = 0; sc->nrules && f < nf; f++) {
        fault_config fc;
        fm_fault_settings_lookup(sc->rules, sc->nrules, fs->names[f], &fc);
        fm_slip_override(&a->slip[f], fc.has_rake ? &fc.rake : NULL,
                         fc.has_rate ? &fc.slip_rate_mm_yr : NULL, FM_SLIP_FROM_SETTINGS);
    }
    for (size_t f = 0; f < nf; f++) {
        a->rake_f[f] = a->slip[f].rake;
        a->rate_f[f] = a->slip[f].slip_rate_mm_yr * FM_MM_PER_YEAR_TO_M_PER_S;
    }
    fm_faultset_strike_dip(fs, a->strike, a->dip);
    const double *x = fm_mesh_vertices(fs->mesh);
    const int32_t *tri = fm_mesh_triangles(fs->mesh), *tag = fm_mesh_tags(fs->mesh);
    /* Per fault: area-weighted mean dip; strike as an axial mean (a
     * vertical fault's elements may be ordered either way), weighted by
     * area x sin(dip) so that flat elements, whose strike means nothing,
     * count for little. */
    for (size_t t = 0; t < nt; t++) {
        size_t f = (size_t)tag[t];
        a->rake_t[t] = a->rake_f[f];
        a->rate_t[t] = a->rate_f[f];
        double area = fm_triangle_area(x + 3 * (size_t)tri[3 * t], x + 3 * (size_t)tri[3 * t + 1],
                                       x + 3 * (size_t)tri[3 * t + 2]);
        double w = area * sin(a->dip[t] * DEG2RAD);
        sums[4 * f] += area;
        sums[4 * f + 1] += area * a->dip[t];
        sums[4 * f + 2] += w * cos(2 * a->strike[t] * DEG2RAD);
        sums[4 * f + 3] += w * sin(2 * a->strike[t] * DEG2RAD);
    }
    for (size_t f = 0; f < nf; f++) {
        a->mean_dip[f] = sums[4 * f] > 0 ? sums[4 * f + 1] / sums[4 * f] : 0;
        double th = atan2(sums[4 * f + 3], sums[4 * f + 2]) / 2;
        sums[4 * f] = 0; /* reused: which way along the axis most point */
        a->mean_strike[f] = th;
    }
    for (size_t t = 0; t < nt; t++) {
        size_t f = (size_t)tag[t];
        double area = fm_triangle_area(x + 3 * (size_t)tri[3 * t], x + 3 * (size_t)tri[3 * t + 1],
                                       x + 3 * (size_t)tri[3 * t + 2]);
        sums[4 * f] += area * sin(a->dip[t] * DEG2RAD) *
                       cos(a->strike[t] * DEG2RAD - a->mean_strike[f]);
    }
    for (size_t f = 0; f < nf; f++) {
        double s = a->mean_strike[f] / DEG2RAD + (sums[4 * f] < 0 ? 180 : 0);
        s = fmod(s + 720, 360);
        a->mean_strike[f] = s >= 360 ? 0 : s;
    }
    free(sums);
    int kr = sim_kinematics_apply(sc, fs, a);
    if (kr) {
        sim_attrs_free(a);
        return kr;
    }
    a->cells[0] = (fm_vtu_array){"strike", FM_VTU_FLOAT64, 1, a->strike};
    a->cells[1] = (fm_vtu_array){"dip", FM_VTU_FLOAT64, 1, a->dip};
    a->cells[2] = (fm_vtu_array){"rake", FM_VTU_FLOAT64, 1, a->rake_t};
    a->cells[3] = (fm_vtu_array){"slip_rate", FM_VTU_FLOAT64, 1, a->rate_t};
    return 0;
}

/* No silent placeholders: a simulator takes a rate of 0 for a locked
 * patch (RSQSim then makes no earthquakes on it) and a defaulted rake for
 * a real one, so the simulator files say in the log how many elements carry
 * either, and why. */
static void say_placeholders(const sim_cli *sc, const fm_faultset *fs, const sim_attrs *a)
{
    size_t zero_t = 0, zero_f = 0, rake_t = 0, rake_f = 0, no_md = 0;
    /* per fault: 1 once counted for a zero rate, 2 for a defaulted rake */
    unsigned char *seen = calloc(fs->nfaults + 1, 1);
    const int32_t *tag = fm_mesh_tags(fs->mesh);
    for (size_t t = 0; seen && t < a->ntriangles; t++) {
        size_t f = (size_t)tag[t];
        if (a->rate_t[t] == 0) {
            zero_t++;
            zero_f += !(seen[f] & 1);
            seen[f] |= 1;
        }
        if (sim_kinematics_rake_default(a, t, f)) {
            rake_t++;
            if (!(seen[f] & 2)) {
                rake_f++;
                no_md += !a->slip[f].slip_sense;
            }
            seen[f] |= 2;
        }
    }
    free(seen);
    if (zero_f)
        run_log(sc->ctl, FM_LOG_INFO,
                "warning: mesh.rsqsim, mesh.eqsim: %zu of %zu elements (%zu of %zu "
                "faults) have slip rate 0: no --slip rule, settings value or --kinematics "
                "section gives them one; a simulator takes them for locked patches "
                "(report.json: attributes)",
                zero_t, a->ntriangles, zero_f, fs->nfaults);
    if (rake_f)
        run_log(sc->ctl, FM_LOG_INFO,
                "warning: mesh.rsqsim, mesh.eqsim: %zu elements (%zu faults) have "
                "the default rake %g: %s",
                rake_t, rake_f, FM_SLIP_DEFAULT_RAKE,
                !sc->metadata_found
                    ? "no CFM metadata CSV was found beside the inputs (give --metadata FILE, "
                      "or a --slip rule)"
                : no_md == rake_f ? "their faults are not in the metadata"
                                  : "their faults' slip sense is missing or not understood in "
                                    "the metadata (names in report.json: attributes)");
}

void sim_say(const sim_cli *sc, const fm_faultset *fs, const sim_attrs *a)
{
    if (a->kin) {
        double A = 0, M = 0;
        size_t none = 0;
        for (size_t f = 0; f < a->nfaults; f++) {
            A += a->k_area[f];
            M += a->k_matched[f];
            none += a->k_matched[f] == 0;
        }
        run_log(sc->ctl, FM_LOG_INFO, "--kinematics: %.1f%% of the area took a section; %zu of %zu "
                                      "faults took none (report.json: simulator.kinematics)",
                A > 0 ? 100 * M / A : 0, none, a->nfaults);
    }
    say_placeholders(sc, fs, a);
}

fm_status sim_write(const sim_cli *sc, const fm_faultset *fs, const sim_attrs *a,
                    const char *dir, int rsqsim, int eqsim, fm_output_done done, void *ctx)
{
    size_t n = strlen(dir) + 32;
    char *path = malloc(n);
    fm_sim_slip slip = {a->rake_f, a->rate_f, a->rake_t, a->rate_t};
    fm_status first = FM_OK;
    for (int k = 0; k < 2; k++) {
        if (!(k ? eqsim : rsqsim))
            continue;
        const char *name = k ? "mesh.eqsim" : "mesh.rsqsim";
        fm_error err;
        fm_error_clear(&err);
        fm_status st;
        if (!path) {
            st = fm_error_set(&err, FM_ERR_NOMEM, name, 0, "out of memory");
        } else {
            snprintf(path, n, "%s/%s", dir, name);
            st = k ? fm_faultset_write_eqsim(path, fs, &slip, sc->eqsim, &err)
                   : fm_faultset_write_rsqsim(path, fs, &slip, &err);
        }
        done(ctx, path ? path : name, SIZE_MAX, st == FM_OK ? NULL : &err);
        if (first == FM_OK)
            first = st;
    }
    free(path);
    return first;
}

void sim_json_fault(fm_json *j, const sim_cli *sc, const sim_attrs *a, size_t f)
{
    const fm_fault_slip *s = &a->slip[f];
    fm_json_key(j, "attributes");
    fm_json_begin_object(j);
    fm_json_kv_int(j, "section", (int64_t)f + 1);
    fm_json_kv_number(j, "mean_strike_deg", a->mean_strike[f]);
    fm_json_kv_number(j, "mean_dip_deg", a->mean_dip[f]);
    fm_json_kv_number(j, "rake_deg", s->rake);
    fm_json_kv_number(j, "slip_rate_mm_yr", s->slip_rate_mm_yr);
    fm_json_kv_number(j, "slip_rate_m_s", a->rate_f[f]);
    fm_json_kv_string(j, "rake_from", fm_slip_source_name(s->rake_from));
    fm_json_kv_string(j, "slip_rate_from", fm_slip_source_name(s->rate_from));
    if (s->slip_sense)
        fm_json_kv_string(j, "slip_sense", s->slip_sense);
    else
        fm_json_kv_string(j, "slip_sense", "");
    if (s->csv_line)
        fm_json_kv_int(j, "slip_csv_line", s->csv_line);
    fm_json_key(j, "warnings");
    fm_json_begin_array(j);
    char w[200];
    if (s->rake_from == FM_SLIP_FROM_DEFAULT) {
        snprintf(w, sizeof w, "rake unknown (%s): default %g degrees written",
                 !s->slip_sense         ? "fault not in the metadata"
                 : !s->slip_sense[0]    ? "no slip sense in the metadata"
                                        : "slip sense not understood",
                 FM_SLIP_DEFAULT_RAKE);
        fm_json_string(j, w);
    }
    if (s->rate_from == FM_SLIP_FROM_DEFAULT) {
        snprintf(w, sizeof w, "slip rate unknown (no --slip rule gives it): default %g mm/yr written",
                 FM_SLIP_DEFAULT_RATE_MM_YR);
        fm_json_string(j, w);
    }
    fm_json_end_array(j);
    sim_kinematics_json_fault(j, sc, a, f);
    fm_json_end_object(j);
}

void sim_json_summary(fm_json *j, const sim_cli *sc, const sim_attrs *a,
                      const char *const *names)
{
    size_t rake_default = 0, rate_default = 0, rake_md = 0, rake_csv = 0, rate_csv = 0;
    size_t rake_set = 0, rate_set = 0;
    for (size_t f = 0; f < a->nfaults; f++) {
        rake_default += a->slip[f].rake_from == FM_SLIP_FROM_DEFAULT;
        rake_md += a->slip[f].rake_from == FM_SLIP_FROM_METADATA;
        rake_csv += a->slip[f].rake_from == FM_SLIP_FROM_CSV;
        rate_default += a->slip[f].rate_from == FM_SLIP_FROM_DEFAULT;
        rate_csv += a->slip[f].rate_from == FM_SLIP_FROM_CSV;
        rake_set += a->slip[f].rake_from == FM_SLIP_FROM_SETTINGS;
        rate_set += a->slip[f].rate_from == FM_SLIP_FROM_SETTINGS;
    }
    fm_json_key(j, "simulator");
    fm_json_begin_object(j);
    fm_json_kv_string(j, "rsqsim", "mesh.rsqsim");
    fm_json_kv_string(j, "eqsim", "mesh.eqsim");
    fm_json_kv_string(j, "eqsim_coords",
                      sc->eqsim == FM_EQSIM_SPHERICAL ? "spherical (WGS 84, EPSG:4326)"
                                                      : "rectangular (mesh metres)");
    fm_json_kv_string(j, "metadata", sc->metadata_found ? sc->metadata_found : "");
    fm_json_kv_int(j, "metadata_faults", (int64_t)fm_metadata_count(sc->md));
    fm_json_kv_string(j, "slip_csv", sc->slip_path ? sc->slip_path : "");
    fm_json_kv_string(j, "strike_reference", "grid north (+y of the CRS)");
    fm_json_kv_int(j, "rake_from_csv", (int64_t)rake_csv);
    fm_json_kv_int(j, "rake_from_metadata", (int64_t)rake_md);
    fm_json_kv_int(j, "rake_default", (int64_t)rake_default);
    fm_json_kv_int(j, "slip_rate_from_csv", (int64_t)rate_csv);
    fm_json_kv_int(j, "slip_rate_default", (int64_t)rate_default);
    fm_json_kv_int(j, "rake_from_settings", (int64_t)rake_set);
    fm_json_kv_int(j, "slip_rate_from_settings", (int64_t)rate_set);
    sim_kinematics_json_summary(j, sc, a, names);
    fm_json_end_object(j);
}
