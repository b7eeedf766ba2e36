/* faultmesh io: the decimal text of a double that every text writer
 * (TSurf, MSH, OBJ) prints, so that all formats agree digit for digit.
 *
 * fm_format_double writes the shortest of printf's %.15g, %.16g and %.17g
 * that reads back as exactly x (C locale) into buf (at least 32 bytes),
 * NUL-terminated, and returns its length. Deterministic, and for UTM
 * coordinates about 20 times faster than printf + strtod (see
 * src/io/tsurf_dtoa.c). The same declaration is in
 * the io stage's private tsurf_lex.h. */
#ifndef FM_DTOA_H
#define FM_DTOA_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

size_t fm_format_double(char *buf, double x);

#ifdef __cplusplus
}
#endif
#endif
