/* faultmesh core: SHA-256 (FIPS 180-4).
 *
 * For content addresses (the fit cache names a fitted model by the hash of
 * everything that made it, fm_model.h) and for checking that a file read
 * back is the one written: a strong hash, so that two different inputs
 * never share a name in practice and a damaged file never passes. Written
 * from the standard rather than taken from a library, as none the project
 * links provides one. Streaming: init, any number of updates, final. */
#ifndef FM_SHA256_H
#define FM_SHA256_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define FM_SHA256_BYTES 32

typedef struct fm_sha256 {
    uint32_t h[8];
    uint64_t bytes;          /* message length so far */
    unsigned char block[64]; /* the partial block */
    size_t fill;             /* bytes in it */
} fm_sha256;

void fm_sha256_init(fm_sha256 *c);
void fm_sha256_update(fm_sha256 *c, const void *data, size_t n);
/* The digest; c must be initialised again before reuse. */
void fm_sha256_final(fm_sha256 *c, unsigned char digest[FM_SHA256_BYTES]);
/* One call for a whole buffer. */
void fm_sha256_of(const void *data, size_t n, unsigned char digest[FM_SHA256_BYTES]);
/* Lower-case hexadecimal, NUL-terminated (65 chars). */
void fm_sha256_hex(const unsigned char digest[FM_SHA256_BYTES], char hex[2 * FM_SHA256_BYTES + 1]);

#ifdef __cplusplus
}
#endif
#endif
