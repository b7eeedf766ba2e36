/* fm_sha256 (src/core/sha256.c): the FIPS 180-4 / NIST example messages,
 * one million 'a', the lengths around the padding boundaries (digests
 * from Python's hashlib), and the same digest however the message is
 * split between updates; and the SHA-NI block function, where the
 * machine has it, state for state the portable one's on random blocks. */
#include <stdint.h>

#include "fm_sha256.h"
#include "fm_test.h"
#include "sha256_blocks.h"

static void check_hex(const void *msg, size_t n, const char *want)
{
    unsigned char d[FM_SHA256_BYTES];
    char hex[2 * FM_SHA256_BYTES + 1];
    fm_sha256_of(msg, n, d);
    fm_sha256_hex(d, hex);
    CHECK_STR(hex, want);
}

static void test_nist_examples(void)
{
    check_hex("", 0, "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    check_hex("abc", 3, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    const char *two = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
    check_hex(two, strlen(two), "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
    const char *four = "abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmnoijklmnop"
                       "jklmnopqklmnopqrlmnopqrsmnopqrstnopqrstu";
    check_hex(four, strlen(four), "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1");
    char *a = malloc(1000000);
    CHECK(a != NULL);
    if (!a)
        return;
    memset(a, 'a', 1000000);
    check_hex(a, 1000000, "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
    free(a);
}

/* bytes (7 i + 3) mod 256, digests from hashlib */
static void test_padding_boundaries(void)
{
    static const struct {
        size_t n;
        const char *hex;
    } v[] = {{55, "e7313d333c272e639f790978283f9eb392e843d0f29b7016828bb1daa4aac70b"},
             {56, "4324d65f3c103567f5589c710bc08f8523f929a9272e3af36fc968e52abc6c27"},
             {57, "35df609437dcfea3279283ab79fd554e2bf78f8f7ae2de532d8ee300b09e8f73"},
             {63, "81c80242132f230c3bd41b3e63bbcff16107339549214a99614ff26664625055"},
             {64, "39e3d7b6b5d075d37d053ad89b24b41bef4f3c29760c84447cab3f3be1882241"},
             {65, "aacca6ff74fdbb296d165a45cecfa04e5127bc008770fbbdd48006f2d2fae95e"},
             {119, "9ce7368e4daf32341631b492e80359dc9f594b48453cd0dd5bf0b19279cc177e"},
             {120, "7836b787757e95e58b3ca5aec90b1b004e8deba1e50e9675af9cabf1a13a04b5"},
             {128, "d2742f1f4ac6bb7ca2b239ee18402ba8b3f9f8e652d2a72973c2b9ba11c08cf6"}};
    unsigned char buf[128];
    for (size_t i = 0; i < sizeof buf; i++)
        buf[i] = (unsigned char)((i * 7 + 3) & 255);
    for (size_t k = 0; k < sizeof v / sizeof v[0]; k++)
        check_hex(buf, v[k].n, v[k].hex);
}

static void test_split_updates(void)
{
    enum { N = 1000 };
    unsigned char msg[N], whole[FM_SHA256_BYTES], part[FM_SHA256_BYTES];
    for (size_t i = 0; i < N; i++)
        msg[i] = (unsigned char)(i * 31 + i / 7);
    fm_sha256_of(msg, N, whole);
    static const size_t steps[] = {1, 3, 55, 63, 64, 65, 127, 500};
    for (size_t s = 0; s < sizeof steps / sizeof steps[0]; s++) {
        fm_sha256 c;
        fm_sha256_init(&c);
        for (size_t at = 0; at < N; at += steps[s])
            fm_sha256_update(&c, msg + at, at + steps[s] <= N ? steps[s] : N - at);
        fm_sha256_final(&c, part);
        CHECK(memcmp(whole, part, sizeof whole) == 0);
    }
}

static void test_x86_blocks(void)
{
    if (!fm_sha256_x86_available())
        return; /* the portable rounds ran every case above */
    enum { NB = 97 };
    static unsigned char msg[64 * NB];
    uint64_t x = 88172645463325252u; /* xorshift: fixed, varied bytes */
    for (size_t i = 0; i < sizeof msg; i++) {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        msg[i] = (unsigned char)x;
    }
    for (size_t nb = 1; nb <= NB; nb += 16) {
        uint32_t a[8], b[8];
        for (int k = 0; k < 8; k++)
            a[k] = b[k] = (uint32_t)(x >> (4 * k)) * 2654435761u;
        fm_sha256_portable_blocks(a, msg, nb);
        fm_sha256_x86_blocks(b, msg, nb);
        CHECK(memcmp(a, b, sizeof a) == 0);
    }
}

FM_TEST_MAIN(FM_CASE(test_nist_examples), FM_CASE(test_padding_boundaries),
             FM_CASE(test_split_updates), FM_CASE(test_x86_blocks))
