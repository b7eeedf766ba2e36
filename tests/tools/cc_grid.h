/* check_connect: broad phase. Every pair of items whose closed axis-aligned
 * boxes overlap, found through a uniform grid of cells (occupied cells
 * only, by sorting (cell, item) entries), each pair reported once: in the
 * cell holding the low corner of the two boxes' common box. */
#ifndef CC_GRID_H
#define CC_GRID_H

#include <stddef.h>
#include <stdint.h>

typedef void (*cc_pair_fn)(void *ctx, uint32_t i, uint32_t j);

/* box: 6 doubles per item (low x y z, high x y z). group: NULL, or one
 * value per item, and then only pairs of different groups are reported.
 * fn gets i < j; the order of calls is deterministic. 0, or -1 when out of
 * memory. */
int cc_grid_pairs(const double *box, size_t n, const uint32_t *group, cc_pair_fn fn, void *ctx);

#endif
