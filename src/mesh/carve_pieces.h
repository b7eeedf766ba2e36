/* Edge-connected pieces of each fault of a set, counted again as
 * triangles are taken away (carve.c: of two faults that still cross, the
 * one that gives way should not be cut in two, which leaves an island). */
#ifndef CARVE_PIECES_H
#define CARVE_PIECES_H

#include <stddef.h>
#include <stdint.h>

#include "fm_mesh.h"

typedef struct cv_pieces cv_pieces;

/* The adjacency of m's triangles through sides shared within a fault
 * (tag); NULL when out of memory. m must outlive it. */
cv_pieces *cv_pieces_create(const fm_mesh *m);
void cv_pieces_destroy(cv_pieces *p);

/* Pieces of fault f: its triangles neither gone (gone[t] != 0) nor among
 * t[0 .. n-1]. */
size_t cv_pieces_count(cv_pieces *p, int32_t f, const unsigned char *gone, const int32_t *t,
                       size_t n);

#endif
