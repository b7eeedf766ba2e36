/* The physical tags and names that Tandem, SeisSol and PyLith expect of a
 * Gmsh mesh (see fm_faultset_write.h and docs/formats.md for the sources). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fm_faultset_write.h"

const char *fm_msh_tags_name(fm_msh_tags conv)
{
    switch (conv) {
    case FM_MSH_TAGS_DEFAULT: return "default";
    case FM_MSH_TAGS_TANDEM: return "tandem";
    case FM_MSH_TAGS_SEISSOL: return "seissol";
    case FM_MSH_TAGS_PYLITH: return "pylith";
    }
    return NULL;
}

static int is_label_char(unsigned char c)
{
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
           c == '_';
}

/* The label of a fault name (see the header), room for a suffix. */
static char *label_of(const char *name)
{
    size_t n = strlen(name);
    char *d = malloc(n + 32);
    if (!d)
        return NULL;
    size_t k = 0;
    unsigned char c0 = (unsigned char)name[0];
    if (!((c0 >= 'A' && c0 <= 'Z') || (c0 >= 'a' && c0 <= 'z'))) {
        memcpy(d, "fault_", 6);
        k = 6;
    }
    for (size_t i = 0; i < n; i++) {
        if (is_label_char((unsigned char)name[i]))
            d[k++] = name[i];
        else if (k == 0 || d[k - 1] != '_')
            d[k++] = '_';
    }
    d[k] = '\0';
    return d;
}

fm_status fm_msh_tags_make(fm_msh_tags conv, const char *const *fault_names, size_t n,
                           int32_t *tags, char ***names, fm_error *err)
{
    if (!fm_msh_tags_name(conv))
        return fm_error_set(err, FM_ERR_INVALID, NULL, 0, "unknown MSH tag convention %d",
                            (int)conv);
    char **out = calloc(n ? n : 1, sizeof *out);
    if (!out)
        return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
    for (size_t i = 0; i < n; i++) {
        const char *fixed = conv == FM_MSH_TAGS_TANDEM || conv == FM_MSH_TAGS_SEISSOL ? "fault"
                                                                                      : NULL;
        tags[i] = conv == FM_MSH_TAGS_TANDEM    ? 3
                  : conv == FM_MSH_TAGS_SEISSOL ? 103
                                                : (int32_t)(i + 1);
        out[i] = fixed ? strdup(fixed)
                 : conv == FM_MSH_TAGS_PYLITH ? label_of(fault_names[i])
                                              : strdup(fault_names[i]);
        if (!out[i]) {
            fm_faultset_free_file_names(out, n);
            return fm_error_set(err, FM_ERR_NOMEM, NULL, 0, "out of memory");
        }
        if (conv != FM_MSH_TAGS_PYLITH)
            continue;
        /* labels must tell the faults apart: a suffix on a repeat (the
         * quadratic scan is over a few hundred faults) */
        size_t base = strlen(out[i]);
        for (int suffix = 2;; suffix++) {
            int taken = 0;
            for (size_t k = 0; k < i && !taken; k++)
                taken = strcmp(out[k], out[i]) == 0;
            if (!taken)
                break;
            snprintf(out[i] + base, 32, "_%d", suffix);
        }
    }
    *names = out;
    return FM_OK;
}
