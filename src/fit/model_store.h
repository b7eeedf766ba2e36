/* Private to src/fit: fm_model_save / fm_model_load with the key of the
 * fit cache (model_cache.c) in the header: written (NULL: zeros), and
 * checked on reading (NULL: not checked). */
#ifndef FM_MODEL_STORE_H
#define FM_MODEL_STORE_H

#include "fm_model.h"

fm_status model_store_write(const fm_model *m, const unsigned char *key, const char *path,
                            fm_error *err);
fm_status model_store_read(const char *path, const unsigned char *key, fm_model **out,
                           fm_error *err);

#endif
