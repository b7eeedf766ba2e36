/* Shared by the rectangle writers (private to src/write). */
#ifndef QUAD_INTERNAL_H
#define QUAD_INTERNAL_H

#include "fm_quad_write.h"

/* Checks what every rectangle writer checks (fm_quad_write.h). */
fm_status quad_validate(const fm_quadset *qs, const char *path, fm_error *err);
/* Element i's rake (180 when none given) and slip rate (0). */
double quad_rake(const fm_quadset *qs, size_t i);
double quad_rate(const fm_quadset *qs, size_t i);

#endif
