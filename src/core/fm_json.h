/* faultmesh core: a small streaming JSON writer.
 *
 * Output is stable (fixed indentation, keys in the order written, numbers in
 * a fixed format) so that reports diff cleanly and tests can compare them
 * byte for byte. Non-finite numbers are written as null. */
#ifndef FM_JSON_H
#define FM_JSON_H

#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

#define FM_JSON_MAX_DEPTH 32

typedef struct fm_json {
    FILE *fp;
    int depth;
    int count[FM_JSON_MAX_DEPTH]; /* items written at each depth */
    int after_key;
} fm_json;

void fm_json_init(fm_json *j, FILE *fp);
void fm_json_begin_object(fm_json *j);
void fm_json_end_object(fm_json *j);
void fm_json_begin_array(fm_json *j);
void fm_json_end_array(fm_json *j);
void fm_json_key(fm_json *j, const char *key);
void fm_json_string(fm_json *j, const char *s);
void fm_json_int(fm_json *j, int64_t v);
/* %.10g: ample for reported figures, identical across runs. */
void fm_json_number(fm_json *j, double v);
/* Full precision (%.17g), for coordinates that must round-trip. */
void fm_json_number_exact(fm_json *j, double v);
void fm_json_bool(fm_json *j, int v);
void fm_json_null(fm_json *j);

/* Convenience: key followed by value. */
void fm_json_kv_string(fm_json *j, const char *key, const char *s);
void fm_json_kv_int(fm_json *j, const char *key, int64_t v);
void fm_json_kv_number(fm_json *j, const char *key, double v);
void fm_json_kv_bool(fm_json *j, const char *key, int v);

#ifdef __cplusplus
}
#endif
#endif
