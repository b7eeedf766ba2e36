/* Union-find and a sort order the check stage's files share. */
#include "check_internal.h"

int32_t ck_find(int32_t *up, int32_t x)
{
    while (up[x] != x) {
        up[x] = up[up[x]];
        x = up[x];
    }
    return x;
}

void ck_unite(int32_t *up, int32_t a, int32_t b)
{
    a = ck_find(up, a);
    b = ck_find(up, b);
    if (a != b)
        up[a < b ? b : a] = a < b ? a : b;
}

int ck_cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}
