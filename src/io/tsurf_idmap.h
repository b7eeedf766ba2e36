/* faultmesh io: vertex id -> vertex index map of one TSurf object.
 *
 * Ids are any non-negative int64. Nearly every real file numbers its
 * vertices base, base+1, base+2, ... in file order; while that holds the map
 * is just arithmetic. The first id that breaks the run moves everything
 * into an open-addressing hash table. */
#ifndef FM_TSURF_IDMAP_H
#define FM_TSURF_IDMAP_H

#include <stddef.h>
#include <stdint.h>

typedef struct fm_idmap {
    int64_t base; /* dense mode: id of index 0 */
    size_t n;     /* ids inserted; index i was the i-th inserted */
    int dense;
    int64_t *keys; /* hash mode: -1 marks an empty slot */
    int32_t *vals;
    size_t mask; /* capacity - 1 (capacity a power of two) */
} fm_idmap;

void fm_idmap_init(fm_idmap *m);
void fm_idmap_free(fm_idmap *m);

/* Index of id, or -1. */
static inline int32_t fm_idmap_find_dense(const fm_idmap *m, int64_t id)
{
    uint64_t k = (uint64_t)id - (uint64_t)m->base;
    return id >= m->base && k < m->n ? (int32_t)k : -1;
}
int32_t fm_idmap_find_hashed(const fm_idmap *m, int64_t id);
static inline int32_t fm_idmap_find(const fm_idmap *m, int64_t id)
{
    return m->dense ? fm_idmap_find_dense(m, id) : fm_idmap_find_hashed(m, id);
}

/* Adds id with the next index (m->n). Returns 0, 1 when id is already
 * present (nothing added), -1 when memory runs out. */
int fm_idmap_add(fm_idmap *m, int64_t id);

#endif
