/* fm_repair_take_option: the repair options as the commands spell them. */
#include "fm_opt.h"

static int weld(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_double(a->name, a->val, &((fm_repair_options *)t)->weld_tolerance, err);
}

static int min_triangles(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_size(a->name, a->val, &((fm_repair_options *)t)->min_fragment_triangles, err);
}

static int min_fraction(void *t, fm_opt_arg *a, fm_error *err)
{
    return fm_opt_double(a->name, a->val,
                         &((fm_repair_options *)t)->min_fragment_area_fraction, err);
}

static int keep_fragments(void *t, fm_opt_arg *a, fm_error *err)
{
    (void)a, (void)err;
    ((fm_repair_options *)t)->drop_fragments = 0;
    return 0;
}

static int no_split(void *t, fm_opt_arg *a, fm_error *err)
{
    (void)a, (void)err;
    ((fm_repair_options *)t)->split_nonmanifold = 0;
    return 0;
}

static const fm_opt_spec table[] = {
    {"--weld-tol", NULL, 1, weld},
    {"--min-fragment-triangles", NULL, 1, min_triangles},
    {"--min-fragment-fraction", NULL, 1, min_fraction},
    {"--keep-fragments", NULL, 0, keep_fragments},
    {"--no-split", NULL, 0, no_split},
};

int fm_repair_take_option(fm_repair_options *opt, int argc, const char *const *argv, int *i,
                          fm_error *err)
{
    return fm_opt_take(table, sizeof table / sizeof *table, opt, argc, argv, i, err);
}
