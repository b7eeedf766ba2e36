/* fm_synthetic.h's fm_synth_spec: the synthetic system's options, as the
 * installed API and `faultmesh synth` take them. */
#include <stdlib.h>

#include "fm_opt.h"
#include "fm_synth.h"

struct fm_synth_spec {
    fm_synth_options o;
};

fm_synth_spec *fm_synth_spec_create(void)
{
    fm_synth_spec *s = calloc(1, sizeof *s);
    if (s)
        fm_synth_options_default(&s->o);
    return s;
}

void fm_synth_spec_destroy(fm_synth_spec *spec)
{
    free(spec);
}

static int spacing(void *t, fm_opt_arg *a, fm_error *err)
{
    double *v = &((fm_synth_spec *)t)->o.spacing;
    if (fm_opt_double(a->name, a->val, v, err))
        return -1;
    /* fm_synth_create's bounds, said as the command line says them */
    if (*v < 20.0 || *v > 20000.0) {
        fm_error_set(err, FM_ERR_INVALID, NULL, 0, "%s needs 20 to 20000 (m), got '%s'",
                     a->name, a->val);
        return -1;
    }
    return 0;
}

static int seed(void *t, fm_opt_arg *a, fm_error *err)
{
    size_t v;
    if (fm_opt_size(a->name, a->val, &v, err))
        return -1;
    ((fm_synth_spec *)t)->o.seed = (unsigned)v;
    return 0;
}

static const fm_opt_spec table[] = {
    {"--spacing", NULL, 1, spacing},
    {"--seed", NULL, 1, seed},
};

int fm_synth_spec_take_option(fm_synth_spec *spec, int argc, const char *const *argv, int *i,
                              fm_error *err)
{
    return fm_opt_take(table, sizeof table / sizeof *table, spec, argc, argv, i, err);
}

fm_status fm_synth_generate(const fm_synth_spec *spec, fm_synth **out, fm_error *err)
{
    return fm_synth_create(spec ? &spec->o : NULL, out, err);
}
