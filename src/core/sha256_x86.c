/* SHA-256 blocks with the x86 SHA extensions (SHA-NI), when the processor
 * has them: the fit cache checks every model file it reads by its SHA-256
 * and keys every input mesh by one, some hundreds of megabytes for the
 * whole CFM, where the portable rounds (sha256.c) took about a twentieth
 * of a warm run's CPU. The digest is the same by definition; the test
 * vectors of tests/unit/test_sha256.c run through whichever path the
 * machine takes, and it compares the two block functions on random
 * blocks. Written from the instructions' definitions (Intel SDM). */
#include "sha256_blocks.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <cpuid.h>
#include <immintrin.h>
#include <stdatomic.h>

int fm_sha256_x86_available(void)
{
    /* -1: not asked yet; a race only asks twice */
    static atomic_int have = -1;
    int h = atomic_load_explicit(&have, memory_order_relaxed);
    if (h < 0) {
        unsigned a, b, c, d;
        int sse = __get_cpuid(1, &a, &b, &c, &d) && (c & bit_SSSE3) && (c & bit_SSE4_1);
        int sha = __get_cpuid_count(7, 0, &a, &b, &c, &d) && (b & bit_SHA);
        h = sse && sha;
        atomic_store_explicit(&have, h, memory_order_relaxed);
    }
    return h;
}


/* The instructions keep the state as ABEF and CDGH (lanes high to low);
 * the message in groups of four words, each made from the four before
 * (msg1: w[t-16] + s0(w[t-15]); + w[t-7]; msg2: + s1(w[t-2])); two rounds
 * per rnds2, on the low two words of message + K. */
__attribute__((target("sha,sse4.1,ssse3"))) void fm_sha256_x86_blocks(uint32_t h[8],
                                                                      const unsigned char *p,
                                                                      size_t nblocks)
{
    const __m128i bswap = _mm_set_epi64x(0x0c0d0e0f08090a0bLL, 0x0405060700010203LL);
    __m128i t = _mm_loadu_si128((const __m128i *)&h[0]);  /* D C B A */
    __m128i s1 = _mm_loadu_si128((const __m128i *)&h[4]); /* H G F E */
    t = _mm_shuffle_epi32(t, 0xB1);                        /* C D A B */
    s1 = _mm_shuffle_epi32(s1, 0x1B);                      /* E F G H */
    __m128i s0 = _mm_alignr_epi8(t, s1, 8);                /* A B E F */
    s1 = _mm_blend_epi16(s1, t, 0xF0);                     /* C D G H */
    for (; nblocks; nblocks--, p += 64) {
        __m128i save0 = s0, save1 = s1, w[4];
        for (int g = 0; g < 16; g++) {
            if (g < 4) {
                w[g] = _mm_shuffle_epi8(_mm_loadu_si128((const __m128i *)(p + 16 * g)), bswap);
            } else {
                __m128i m = _mm_sha256msg1_epu32(w[g & 3], w[(g + 1) & 3]);
                m = _mm_add_epi32(m, _mm_alignr_epi8(w[(g + 3) & 3], w[(g + 2) & 3], 4));
                w[g & 3] = _mm_sha256msg2_epu32(m, w[(g + 3) & 3]);
            }
            __m128i k = _mm_loadu_si128((const __m128i *)&fm_sha256_k[4 * g]);
            __m128i m = _mm_add_epi32(w[g & 3], k);
            s1 = _mm_sha256rnds2_epu32(s1, s0, m);
            m = _mm_shuffle_epi32(m, 0x0E);
            s0 = _mm_sha256rnds2_epu32(s0, s1, m);
        }
        s0 = _mm_add_epi32(s0, save0);
        s1 = _mm_add_epi32(s1, save1);
    }
    t = _mm_shuffle_epi32(s0, 0x1B);  /* F E B A */
    s1 = _mm_shuffle_epi32(s1, 0xB1); /* D C H G */
    s0 = _mm_blend_epi16(t, s1, 0xF0); /* D C B A */
    s1 = _mm_alignr_epi8(s1, t, 8);    /* H G F E */
    _mm_storeu_si128((__m128i *)&h[0], s0);
    _mm_storeu_si128((__m128i *)&h[4], s1);
}
#else
int fm_sha256_x86_available(void) { return 0; }

void fm_sha256_x86_blocks(uint32_t h[8], const unsigned char *p, size_t nblocks)
{
    (void)h;
    (void)p;
    (void)nblocks;
}
#endif
