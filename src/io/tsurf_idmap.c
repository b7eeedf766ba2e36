#include "tsurf_idmap.h"

#include <stdlib.h>

void fm_idmap_init(fm_idmap *m)
{
    m->base = 0;
    m->n = 0;
    m->dense = 1;
    m->keys = NULL;
    m->vals = NULL;
    m->mask = 0;
}

void fm_idmap_free(fm_idmap *m)
{
    free(m->keys);
    free(m->vals);
    fm_idmap_init(m);
}

static size_t slot_of(int64_t id, size_t mask)
{
    /* Fibonacci hashing: ids often differ only in low bits. */
    uint64_t h = (uint64_t)id * 0x9E3779B97F4A7C15ULL;
    return (size_t)(h >> 32 ^ h) & mask;
}

int32_t fm_idmap_find_hashed(const fm_idmap *m, int64_t id)
{
    for (size_t i = slot_of(id, m->mask);; i = (i + 1) & m->mask) {
        if (m->keys[i] == id)
            return m->vals[i];
        if (m->keys[i] < 0)
            return -1;
    }
}

static void put(int64_t *keys, int32_t *vals, size_t mask, int64_t id, int32_t v)
{
    size_t i = slot_of(id, mask);
    while (keys[i] >= 0)
        i = (i + 1) & mask;
    keys[i] = id;
    vals[i] = v;
}

/* Rebuilds the table with room for at least need ids at load <= 1/2. */
static int rehash(fm_idmap *m, size_t need)
{
    size_t cap = 64;
    while (cap < 2 * need)
        cap *= 2;
    int64_t *keys = malloc(cap * sizeof *keys);
    int32_t *vals = malloc(cap * sizeof *vals);
    if (!keys || !vals) {
        free(keys);
        free(vals);
        return -1;
    }
    for (size_t i = 0; i < cap; i++)
        keys[i] = -1;
    if (m->dense) {
        for (size_t i = 0; i < m->n; i++)
            put(keys, vals, cap - 1, m->base + (int64_t)i, (int32_t)i);
    } else {
        for (size_t i = 0; i <= m->mask; i++)
            if (m->keys[i] >= 0)
                put(keys, vals, cap - 1, m->keys[i], m->vals[i]);
    }
    free(m->keys);
    free(m->vals);
    m->keys = keys;
    m->vals = vals;
    m->mask = cap - 1;
    m->dense = 0;
    return 0;
}

int fm_idmap_add(fm_idmap *m, int64_t id)
{
    if (m->n >= (size_t)INT32_MAX)
        return -1;
    if (m->dense) {
        if (m->n == 0)
            m->base = id;
        if (id >= m->base && (uint64_t)id - (uint64_t)m->base == m->n) {
            m->n++;
            return 0;
        }
        if (fm_idmap_find_dense(m, id) >= 0)
            return 1;
        if (rehash(m, m->n + 1) != 0)
            return -1;
    } else {
        if (fm_idmap_find_hashed(m, id) >= 0)
            return 1;
        if (2 * (m->n + 1) > m->mask + 1 && rehash(m, m->n + 1) != 0)
            return -1;
    }
    put(m->keys, m->vals, m->mask, id, (int32_t)m->n);
    m->n++;
    return 0;
}
