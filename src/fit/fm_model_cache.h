/* faultmesh fit: the fit cache, fitted models kept on disk by the hash of
 * everything that made them, so that a later run fits only what changed.
 *
 * Fitting is most of the cost of a run and does not depend on the mesh
 * size: a run at another size, after a change to a few faults, or on a
 * new release of the CFM finds the models of the faults whose input did
 * not change. A model is named by its key, the SHA-256 of
 *  - the cache format (FM_MODEL_FORMAT_VERSION, fm_model.h, and the key's
 *    own layout),
 *  - the code that fits: a digest of the sources of core, repair and fit
 *    and of the compiler and flags they were built with (made by the
 *    build, src/fit/code_hash.cmake), and the versions of the numerical
 *    libraries they call at run time (CHOLMOD, LAPACK, OpenBLAS and the
 *    CPU kernels it chose),
 *  - the fault's triangulation as read (every vertex coordinate, triangle
 *    and tag, bit for bit), which repair and then the fit are made from,
 *  - every repair option and every model option that reaches the fit
 *    (fm_repair_options; fm_model_options: fit, trim, sample_levels,
 *    measure_samples; not the names used in messages, nor the trim's
 *    corner_at, which the model sets per loop itself).
 * Anything that changes the model changes the key, so the cache never
 * gives a stale model; what it gives is the model the fit would make, bit
 * for bit, and so are the meshes made from it. A file that is damaged,
 * truncated, of another format version or of another key is rejected (the
 * caller fits again and stores the model anew). Files are written whole or
 * not at all (fm_atomic.h), so runs may share a cache; the cache may be
 * deleted at any time.
 *
 * Layout: DIR/CACHEDIR.TAG (so that backups skip it) and
 * DIR/models/XX/KEY.fmm, XX the first two hexadecimal digits of the key. */
#ifndef FM_MODEL_CACHE_H
#define FM_MODEL_CACHE_H

#include "fm_core.h"
#include "fm_mesh.h"
#include "fm_model.h"
#include "fm_repair.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FM_MODEL_KEY_BYTES 32

/* The key of the model fm_model_build makes of fm_repair(input, repair)
 * with opt (either may be NULL for the defaults, which give the same key
 * as the defaults given). */
void fm_model_key(const fm_mesh *input, const fm_repair_options *repair,
                  const fm_model_options *opt, unsigned char key[FM_MODEL_KEY_BYTES]);

/* The part of every key that stands for the code and libraries (hex), for
 * reports. */
const char *fm_model_code_id(void);

/* Makes dir a cache (creates it and its CACHEDIR.TAG if missing); fails
 * (err set) when it cannot be created or is not writable. */
fm_status fm_model_cache_open(const char *dir, fm_error *err);

/* The model stored under key: FM_OK and *out the model, or FM_OK and *out
 * NULL when there is none; an error (err set, *out NULL) when a file is
 * there but rejected (damaged, truncated, another format or key), or
 * cannot be read. */
fm_status fm_model_cache_get(const char *dir, const unsigned char key[FM_MODEL_KEY_BYTES],
                             fm_model **out, fm_error *err);

/* Stores m under key (replacing what is there). */
fm_status fm_model_cache_put(const char *dir, const unsigned char key[FM_MODEL_KEY_BYTES],
                             const fm_model *m, fm_error *err);

/* The file a key is stored in (malloc'ed; NULL when out of memory). */
char *fm_model_cache_path(const char *dir, const unsigned char key[FM_MODEL_KEY_BYTES]);

/* A cache's file for a key: DIR/FOLDER/XX/REST.EXT, XX the key's first two
 * hexadecimal digits and REST the others (malloc'ed; NULL when out of
 * memory); and its XX folder made, by whichever run comes first. */
char *fm_cache_key_path(const char *dir, const char *folder, const unsigned char key[32],
                        const char *ext);
fm_status fm_cache_key_folder(char *path, fm_error *err);

#ifdef __cplusplus
}
#endif
#endif
