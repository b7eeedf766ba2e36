/* check_connect: the fault-set OBJ as faultmesh writes it (and any OBJ of
 * triangles): "v x y z" vertices, "o NAME" / "g NAME" starting a fault,
 * "f a b c" triangles (1-based or negative relative indices, "a/t/n"
 * allowed). A fault is identified by its name: the last o or g name seen,
 * so "o X" followed by "g X" is one fault and a name that comes back
 * continues its fault. Faces before any name belong to "(unnamed)". Other
 * statements are ignored; faces with other than three corners, indices
 * not yet defined and non-finite coordinates are errors. */
#ifndef CC_OBJ_H
#define CC_OBJ_H

#include <stddef.h>
#include <stdint.h>

/* Fault indices fit in 30 bits (cc_analyse packs them with edge numbers). */
#define CC_MAX_FAULTS (1u << 30)

typedef struct cc_mesh {
    size_t nv, nt, nfaults;
    double *x;       /* 3 per vertex */
    uint32_t *tri;   /* 3 per triangle, 0-based vertex indices */
    uint32_t *fault; /* per triangle, 0..nfaults-1 in order of first use */
    uint32_t *line;  /* per triangle, its line in the file */
    char **names;    /* per fault */
} cc_mesh;

/* 0 on success; else -1 with "FILE:LINE: message" (or "FILE: message")
 * in err. */
int cc_obj_read(const char *path, cc_mesh *m, char *err, size_t errlen);
void cc_mesh_free(cc_mesh *m);

#endif
