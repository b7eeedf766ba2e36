/* `faultmesh remesh`: DIR/names.csv, every fault's name as each output
 * has it. Readers keep names short (RSQSim's tools 50 characters, many
 * Exodus II readers 32), so the files carry short names (fm_names.h);
 * this table leads from each back to the full name. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_atomic.h"
#include "fm_names.h"
#include "run_internal.h"

/* A CSV field: quoted when it holds a comma, a quote or a line break. */
static void field(FILE *fp, const char *s)
{
    if (!strpbrk(s, ",\"\r\n")) {
        fputs(s, fp);
        return;
    }
    fputc('"', fp);
    for (; *s; s++) {
        if (*s == '"')
            fputc('"', fp);
        fputc(*s, fp);
    }
    fputc('"', fp);
}

fm_status write_names_csv(const char *path, const fm_faultset *fs, fm_error *err)
{
    char **ts = NULL, **sect = fm_short_names(fs->names, fs->nfaults, FM_SECTION_NAME_MAX);
    char **exo = fm_short_names(fs->names, fs->nfaults, FM_EXODUS_NAME_MAX);
    fm_status st = sect && exo ? fm_faultset_tsurf_file_names(fs, &ts, err)
                               : fm_error_set(err, FM_ERR_NOMEM, path, 0, "out of memory");
    fm_atomic_file *af = st == FM_OK ? fm_atomic_open(path, err) : NULL;
    if (st == FM_OK && !af)
        st = err ? err->code : FM_ERR_IO;
    if (st == FM_OK) {
        FILE *fp = fm_atomic_stream(af);
        fputs("number,name,tsurf_file,section_name,exodus_name,msh_physical_tag,"
              "msh_physical_name\n",
              fp);
        for (size_t f = 0; f < fs->nfaults; f++) {
            fprintf(fp, "%zu,", f + 1);
            field(fp, fs->names[f]);
            fputc(',', fp);
            field(fp, ts[f]);
            fprintf(fp, ",%s,%s,%ld,", sect[f], exo[f],
                    (long)(fs->physical_tags ? fs->physical_tags[f] : (int32_t)f + 1));
            field(fp, fs->physical_names ? fs->physical_names[f] : fs->names[f]);
            fputc('\n', fp);
        }
        st = fm_atomic_commit(af, err);
    }
    fm_faultset_free_file_names(ts, ts ? fs->nfaults : 0);
    fm_short_names_free(sect, sect ? fs->nfaults : 0);
    fm_short_names_free(exo, exo ? fs->nfaults : 0);
    return st;
}
