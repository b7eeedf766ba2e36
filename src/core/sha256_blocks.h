/* faultmesh core: SHA-256's block function as the processor may offer it
 * (sha256_x86.c), for sha256.c. */
#ifndef FM_SHA256_BLOCKS_H
#define FM_SHA256_BLOCKS_H

#include <stddef.h>
#include <stdint.h>

/* The 64 round constants K (sha256_k.c). */
extern const uint32_t fm_sha256_k[64];

/* 1 when fm_sha256_x86_blocks may be called (x86-64 with SHA-NI, SSSE3
 * and SSE4.1). */
int fm_sha256_x86_available(void);
/* nblocks 64-byte blocks at p into the state h, as FIPS 180-4's
 * compression function, one block after the other. */
void fm_sha256_x86_blocks(uint32_t h[8], const unsigned char *p, size_t nblocks);
/* The same in portable C (sha256.c), what every other machine runs. */
void fm_sha256_portable_blocks(uint32_t h[8], const unsigned char *p, size_t nblocks);

#endif
