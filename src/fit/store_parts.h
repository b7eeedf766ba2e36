/* Private to src/fit: a fitted surface and a trimming loop in the byte
 * stream of a stored model (store_parts.c). The loads return NULL, with
 * in->failed set, on a damaged stream or no memory. */
#ifndef FM_STORE_PARTS_H
#define FM_STORE_PARTS_H

#include "fm_fit.h"
#include "fm_trim.h"
#include "fm_bytes.h"

void store_surface(fm_store_out *o, const fm_fit_surface *s);
fm_fit_surface *load_surface(fm_store_in *in);
void store_loop(fm_store_out *o, const fm_trim_loop *l);
fm_trim_loop *load_loop(fm_store_in *in);

#endif
