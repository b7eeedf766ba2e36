/* fm_sort_keyed (src/core/sort.c) against qsort by (key, index): edge keys
 * of small and large vertex numbers, many duplicates, every size class of
 * the radix (insertion sort, skipped digits, all six digits), keys all
 * the same and keys differing in scattered bits only. */
#include <stdint.h>

#include "fm_sort.h"
#include "fm_test.h"

static uint64_t state = 0x9e3779b97f4a7c15u;

static uint64_t next_random(void)
{
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return state;
}

static int by_key_index(const void *pa, const void *pb)
{
    const fm_keyed *a = pa, *b = pb;
    if (a->key != b->key)
        return a->key < b->key ? -1 : 1;
    return (a->index > b->index) - (a->index < b->index);
}

/* n entries in index order with keys from `make`; sorted both ways. */
static void check_sort(size_t n, uint64_t (*make)(void))
{
    fm_keyed *a = malloc((n ? n : 1) * sizeof *a), *b = malloc((n ? n : 1) * sizeof *b);
    CHECK(a && b);
    if (!a || !b)
        return;
    for (size_t i = 0; i < n; i++) {
        a[i].key = make();
        a[i].index = i;
        b[i] = a[i];
    }
    CHECK_EQ(fm_sort_keyed(a, n), 0);
    qsort(b, n, sizeof *b, by_key_index);
    size_t bad = 0;
    for (size_t i = 0; i < n; i++)
        bad += a[i].key != b[i].key || a[i].index != b[i].index;
    CHECK_EQ(bad, 0);
    free(a);
    free(b);
}

/* An edge of a mesh of some thousand vertices: many repeats. */
static uint64_t small_edge(void)
{
    uint64_t a = next_random() % 3000, b = next_random() % 3000;
    return a < b ? a << 32 | b : b << 32 | a;
}

static uint64_t large_edge(void)
{
    uint64_t a = next_random() % 5000000, b = next_random() % 5000000;
    return a < b ? a << 32 | b : b << 32 | a;
}

static uint64_t any_key(void) { return next_random(); }

static uint64_t few_keys(void) { return next_random() % 3; }

static uint64_t same_key(void) { return 0x123456789abcdefu; }

/* Keys differing only in bits a digit's width apart and in the top bit:
 * every digit sorts on one bit (six digits). */
static uint64_t sparse_bits(void)
{
    const uint64_t mask = 1u | 1u << 11 | (uint64_t)1 << 22 | (uint64_t)1 << 33 |
                          (uint64_t)1 << 44 | (uint64_t)1 << 55 | (uint64_t)1 << 63;
    return (next_random() & mask) | 0x40;
}

static void test_against_qsort(void)
{
    const size_t sizes[] = {0, 1, 2, 31, 32, 33, 100, 5000, 200000};
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        check_sort(sizes[s], small_edge);
        check_sort(sizes[s], large_edge);
        check_sort(sizes[s], any_key);
        check_sort(sizes[s], few_keys);
        check_sort(sizes[s], same_key);
        check_sort(sizes[s], sparse_bits);
    }
}

FM_TEST_MAIN(FM_CASE(test_against_qsort))
