/* Helpers shared by the fault-set writers (private to src/write). */
#ifndef FAULTSET_INTERNAL_H
#define FAULTSET_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "fm_faultset_write.h"

/* Physical tag and physical group name of fault i. */
int32_t fs_physical_tag(const fm_faultset *fs, size_t i);
const char *fs_physical_name(const fm_faultset *fs, size_t i);

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

/* Named groups of edges for the formats that tag them (MSH physical
 * curves, Exodus II side sets): each fault's outline edges by which way
 * they face within their triangle (up dip within 45 degrees: its top, at
 * or above sea level, or buried below it; down dip: its bottom; else its
 * ends), edges shared with another fault left out; then each node set
 * (fs->nodesets: the junction curves) as the edges two faults share with
 * both nodes in it. Groups without edges are left out. */
enum { FS_EDGE_TOP, FS_EDGE_BURIED, FS_EDGE_BOTTOM, FS_EDGE_ENDS, FS_EDGE_KINDS };
extern const char *const fs_edge_kind_names[FS_EDGE_KINDS];
typedef struct fs_edge_group {
    char *name;         /* "FAULT: top" ("buried top", "bottom", "ends"), or the set's name */
    int32_t fault;      /* its fault, -1 for a junction curve */
    int kind;           /* FS_EDGE_*, -1 for a junction curve */
    int32_t set;        /* the junction curve's node set, -1 for a fault's edges */
    int32_t (*edge)[4]; /* per edge: its two vertices, a triangle holding it, and which side
                           of that triangle it is (k: from corner k to corner k + 1) */
    size_t n, cap;
} fs_edge_group;
/* 0, or -1 when memory runs out. */
int fs_edge_groups_make(const fm_faultset *fs, fs_edge_group **out, size_t *n);
void fs_edge_groups_free(fs_edge_group *g, size_t n);

/* A physical name as MSH's $PhysicalNames line ends: double-quoted, '"'
 * written as '\'' and '\\' as '/', cut to FM_MSH_NAME_MAX bytes, then a
 * newline (faultset_msh.c; see fm_faultset_write_msh). */
struct fs_out;
void fs_msh_put_name(struct fs_out *o, const char *name);

/* Start of the last whole UTF-8 character at or before byte n of s (s is
 * valid UTF-8), so cutting there keeps the text valid. */
size_t fs_utf8_cut(const char *s, size_t n);

/* What writing the TSurf files of a validated set needs, shared by every
 * thread: file names, triangles grouped by fault. */
typedef struct fs_tsurf_plan {
    const fm_faultset *fs;
    const char *dir;
    char **files;
    size_t *tstart, *torder;
    size_t max_uses; /* 3 x the triangles of the largest fault */
} fs_tsurf_plan;

/* One thread's scratch: a vertex map of the whole set (-1 between uses),
 * the vertices of one fault, a path. */
typedef struct fs_tsurf_scratch {
    int32_t *map, *used;
    char *path;
} fs_tsurf_scratch;

/* Also creates dir. fs_tsurf_plan_free also after a failure. */
fm_status fs_tsurf_plan_make(fs_tsurf_plan *pl, const char *dir, const fm_faultset *fs,
                             fm_error *err);
void fs_tsurf_plan_free(fs_tsurf_plan *pl);
/* -1 when memory runs out; fs_tsurf_scratch_free also then. */
int fs_tsurf_scratch_init(fs_tsurf_scratch *sc, const fs_tsurf_plan *pl);
void fs_tsurf_scratch_free(fs_tsurf_scratch *sc);
/* Writes the file of fault f (atomic; the error names it). */
fm_status fs_tsurf_write_fault(const fs_tsurf_plan *pl, size_t f, fs_tsurf_scratch *sc,
                               fm_error *err);

/* The time a file records: SOURCE_DATE_EPOCH when set, else 0 (1970-01-01
 * 00:00:00 UTC), so that the same input gives the same bytes. */
fm_status fs_source_date(const char *path, long long *t, fm_error *err);

#endif
