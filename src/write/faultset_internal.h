/* Helpers shared by the fault-set writers (private to src/write). */
#ifndef FAULTSET_INTERNAL_H
#define FAULTSET_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "fm_faultset_write.h"

/* Physical tag of fault i. */
int32_t fs_physical_tag(const fm_faultset *fs, size_t i);

/* Per vertex, the lowest fault whose triangles use it, -1 if none:
 * malloc'ed, NULL when memory runs out. */
int32_t *fs_vertex_owner(const fm_faultset *fs);

/* Per fault, how many triangles it has: malloc'ed (nfaults entries),
 * NULL when memory runs out. */
size_t *fs_fault_counts(const fm_faultset *fs);

/* Indices 0..n-1 grouped by key (0..nkeys-1; negative keys are left
 * out), ascending within a group: group k is order[start[k]..start[k+1]).
 * Both arrays malloc'ed (the caller frees them, also on failure); -1 when
 * memory runs out. */
int fs_group_by(const int32_t *key, size_t n, size_t nkeys, size_t **start, size_t **order);

/* Start of the last whole UTF-8 character at or before byte n of s (s is
 * valid UTF-8), so cutting there keeps the text valid. */
size_t fs_utf8_cut(const char *s, size_t n);

#endif
