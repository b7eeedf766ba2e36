/* What the check stage's files share. */
#ifndef CHECK_INTERNAL_H
#define CHECK_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "fm_check.h"
#include "fm_closest.h"
#include "fm_sort.h"

/* Union-find over up[] (each entry its own root to begin with): the root
 * of x, halving paths; two sets joined under the smaller root, so roots
 * do not depend on the order of the joins. */
int32_t ck_find(int32_t *up, int32_t x);
void ck_unite(int32_t *up, int32_t a, int32_t b);
/* qsort order of uint64_t values. */
int ck_cmp_u64(const void *a, const void *b);

/* The outline of o: its edges used by one triangle only, seams between
 * sheets left out, as (lo << 32 | hi) vertex pairs in *out (malloc'ed,
 * ascending), their number in *n. */
fm_status ck_outline_edges(const fm_mesh *o, uint64_t **out, size_t *n);
/* Distance from p to those edges (brute force), INFINITY when none. */
double ck_outline_distance(const fm_mesh *o, const uint64_t *E, size_t ne, const double p[3]);

/* The measures of fm_check_loss, shared by its files: the set's
 * topology, built once (loss.c), then every fault measured on its own,
 * on any thread (loss_fault.c). */
typedef struct ck_gap {
    int32_t other;
    double length;
} ck_gap;

typedef struct ck_set {
    const fm_loss_input *in;
    const fm_closest_tree *all; /* every triangle of the set */
    size_t *tri_first;          /* per fault: its triangles tri[tri_first[f] ..] */
    int32_t *tri;
    size_t *bnd_first;          /* per fault: its outline edges bnd[bnd_first[f] ..] */
    uint64_t *bnd;              /* fm_edge_key of the two vertices */
    fm_keyed *shared;           /* key: a << 32 | b (faults, a < b), index: a vertex both use */
    size_t nshared;
    size_t *piece_size;         /* per triangle root: its piece's triangles */
    int32_t *root;              /* per triangle: its piece's root triangle */
} ck_set;

typedef struct ck_fault_out {
    fm_loss_fault m;
    ck_gap *gaps;   /* per other fault it lies beside (sorted by other) */
    size_t ngaps;
    fm_status st;
} ck_fault_out;

/* Everything fm_loss_fault says of fault f but pieces and islands. */
void ck_measure_fault(const ck_set *s, size_t f, ck_fault_out *o);
/* Edge-connected pieces of o's part below zcut that reach minz below
 * zcut (vertices within FM_LOSS_TOUCH welded); SIZE_MAX when out of
 * memory. */
size_t ck_orig_pieces(const fm_mesh *o, double zcut, double minz);

#endif
